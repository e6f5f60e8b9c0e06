//! SDO channels for the decoder: one [`SdoTracker`] per (interface, node),
//! the data of the open transfer (the first 4096 bytes), and the per-node
//! statistics of the summary (SPEC §7.2–§7.4). The library tracks; this
//! file keeps what the output needs.

use std::io::{self, Write};
use std::time::Duration;

use motionwire::can::Timestamp;
use motionwire::canopen::sdo::{
    SdoMessage, SdoOutcome, SdoParty, SdoRequest, SdoResponse, SdoTracker, SdoTransfer,
};
use motionwire::canopen::{CanOpenMessage, NodeId, ObjectAddress, SdoAbortCode};

use crate::args::Profile;
use crate::context::Cia402View;
use crate::json::{self, Object};

/// The data bytes SPEC §7.3's `transfer.data` holds at most.
pub const DATA_MAX: usize = 4096;

/// One SDO frame as the channel's tracker read it, for its record.
pub struct SdoView<'c> {
    /// Which way the frame went.
    pub direction: SdoParty,
    /// The frame read in its transfer's context, or why not.
    pub message: Result<SdoMessage, motionwire::Error>,
    /// The request → response latency this frame closes.
    pub latency: Option<Duration>,
    /// The frame starts a transfer.
    pub started: bool,
    /// The transfer this frame ends, with its data (the first
    /// [`DATA_MAX`] bytes).
    pub ended: Option<(SdoTransfer, &'c [u8])>,
    /// The CiA 402 reading of a completed expedited transfer of the
    /// controlword, statusword or mode (SPEC §8.3).
    pub cia402: Option<Cia402View>,
}

/// What the tracker said of the channel's last frame.
#[derive(Debug)]
struct Last {
    direction: SdoParty,
    message: Result<SdoMessage, motionwire::Error>,
    latency: Option<Duration>,
    started: bool,
    ended: Option<SdoTransfer>,
}

/// One channel: its tracker and the data of its open transfer.
#[derive(Debug, Default)]
pub struct Channel {
    tracker: SdoTracker,
    data: Vec<u8>,
    finished: Vec<u8>,
    last: Option<Last>,
}

impl Channel {
    /// Feed one frame (`line`, time) and return what it is.
    pub fn feed(
        &mut self,
        direction: SdoParty,
        bytes: &[u8],
        ts: Option<Timestamp>,
        line: u64,
    ) -> SdoView<'_> {
        let event = self.tracker.feed(direction, bytes, ts, line);
        // The chunk belongs to the transfer that ends here unless this
        // frame also starts a new one (a new initiate after a timeout).
        let chunk_to_new = event.started && event.ended.map_or(true, |t| t.start_position != line);
        if event.started && event.ended.is_none() {
            self.data.clear();
        }
        if event.ended.is_some() {
            if !chunk_to_new {
                push(&mut self.data, event.chunk);
            }
            std::mem::swap(&mut self.data, &mut self.finished);
            self.data.clear();
            if chunk_to_new {
                push(&mut self.data, event.chunk);
            }
        } else {
            push(&mut self.data, event.chunk);
        }
        self.last = Some(Last {
            direction,
            message: event.message,
            latency: event.latency,
            started: event.started,
            ended: event.ended,
        });
        self.view()
    }

    /// The view of the last frame fed.
    pub fn view(&self) -> SdoView<'_> {
        let last = self.last.as_ref().expect("a frame was fed");
        SdoView {
            direction: last.direction,
            message: last.message,
            latency: last.latency,
            started: last.started,
            ended: last.ended.map(|t| (t, &self.finished[..])),
            cia402: None,
        }
    }

    /// End the input: the transfer left open, if any.
    pub fn finish(&mut self) -> Option<SdoTransfer> {
        self.tracker.finish()
    }
}

fn push(data: &mut Vec<u8>, chunk: &[u8]) {
    let room = DATA_MAX.saturating_sub(data.len());
    data.extend_from_slice(&chunk[..chunk.len().min(room)]);
}

/// The direction of an SDO frame on `id` (SPEC §6.1): 0x581–0x5FF server
/// → client, 0x601–0x67F client → server.
pub fn sdo_direction(id: u32) -> SdoParty {
    if id < u32::from(motionwire::canopen::cob_id::SDO_RX_BASE) {
        SdoParty::Server
    } else {
        SdoParty::Client
    }
}

/// The direction and data of an SDO message, if it is one.
pub fn sdo_frame(message: &CanOpenMessage) -> Option<(NodeId, SdoParty, &[u8])> {
    match message {
        CanOpenMessage::SdoRequest { node, data } => {
            Some((*node, SdoParty::Client, data.as_slice()))
        }
        CanOpenMessage::SdoResponse { node, data } => {
            Some((*node, SdoParty::Server, data.as_slice()))
        }
        _ => None,
    }
}

/// One abort seen on a node's channel (SPEC §7.4 `aborts`).
#[derive(Debug, Clone, Copy)]
pub struct Abort {
    line: u64,
    multiplexer: ObjectAddress,
    code: SdoAbortCode,
    by: SdoParty,
}

/// A node's SDO record for the summary (SPEC §7.4).
#[derive(Debug, Default)]
pub struct SdoStats {
    requests: u64,
    transfers: u64,
    aborts: Vec<Abort>,
    broken: Vec<u64>,
    timeouts: Vec<u64>,
    latencies: Vec<Duration>,
}

impl SdoStats {
    /// Add one frame of the node's channel, as its tracker read it.
    pub fn add(&mut self, event: &SdoView<'_>, line: u64) {
        if event.direction == SdoParty::Client {
            self.requests += 1;
        }
        if event.started {
            self.transfers += 1;
        }
        if let Some(latency) = event.latency {
            self.latencies.push(latency);
        }
        let abort = match event.message {
            Ok(SdoMessage::Request(SdoRequest::Abort { multiplexer, code })) => {
                Some((multiplexer, code, SdoParty::Client))
            }
            Ok(SdoMessage::Response(SdoResponse::Abort { multiplexer, code })) => {
                Some((multiplexer, code, SdoParty::Server))
            }
            _ => None,
        };
        if let Some((multiplexer, code, by)) = abort {
            // The multiplexer of the transfer an abort ends, when the abort
            // carries none (python-canopen's client aborts with 0000h.00).
            let multiplexer = match event.ended {
                Some((t, _)) if multiplexer == ObjectAddress::default() => t.multiplexer,
                _ => multiplexer,
            };
            self.aborts.push(Abort {
                line,
                multiplexer,
                code,
                by,
            });
        }
        if let Some((transfer, _)) = event.ended {
            self.ended(&transfer);
        }
    }

    /// A transfer that ended (at a frame, or left open at the end of the
    /// input).
    pub fn ended(&mut self, transfer: &SdoTransfer) {
        match transfer.outcome {
            SdoOutcome::Broken(_) => self.broken.push(transfer.start_position),
            SdoOutcome::TimedOut => self.timeouts.push(transfer.start_position),
            SdoOutcome::Completed | SdoOutcome::Aborted { .. } => {}
        }
    }

    /// Whether the node had any SDO frame.
    pub fn is_empty(&self) -> bool {
        self.requests == 0
            && self.transfers == 0
            && self.aborts.is_empty()
            && self.broken.is_empty()
    }

    /// The latencies' count, median, p99 and maximum (nearest rank), in ms.
    fn latency_ms(&self) -> Option<(usize, f64, f64, f64)> {
        if self.latencies.is_empty() {
            return None;
        }
        let mut sorted = self.latencies.clone();
        sorted.sort_unstable();
        let rank = |p: f64| {
            // Nearest rank: the smallest value with at least p of them at
            // or below it.
            let n = sorted.len();
            let k = ((p * n as f64).ceil() as usize).clamp(1, n);
            ms(sorted[k - 1])
        };
        Some((
            sorted.len(),
            rank(0.5),
            rank(0.99),
            ms(sorted[sorted.len() - 1]),
        ))
    }

    /// Write the `sdo` value of the node record (SPEC §7.4).
    pub fn write_json<W: Write>(&self, out: &mut W, profile: Profile) -> io::Result<()> {
        let mut obj = Object::begin(out)?;
        obj.uint("requests", self.requests)?;
        obj.uint("transfers", self.transfers)?;
        let out = obj.key("aborts")?;
        out.write_all(b"[")?;
        for (i, abort) in self.aborts.iter().enumerate() {
            if i > 0 {
                out.write_all(b",")?;
            }
            let mut a = Object::begin(out)?;
            a.uint("line", abort.line)?;
            a.uint("index", u64::from(abort.multiplexer.index))?;
            a.uint("subindex", u64::from(abort.multiplexer.sub_index))?;
            match object_name(abort.multiplexer.index, profile) {
                Some(name) => a.name("object", name)?,
                None => a.null("object")?,
            }
            a.uint("code", u64::from(abort.code.get()))?;
            a.name("description", abort.code.description())?;
            a.name("by", abort.by.name())?;
            a.end()?;
        }
        out.write_all(b"]")?;
        obj.uints("broken", self.broken.iter().copied())?;
        obj.uints("timeouts", self.timeouts.iter().copied())?;
        match self.latency_ms() {
            None => obj.null("latency_ms")?,
            Some((count, median, p99, max)) => {
                let out = obj.key("latency_ms")?;
                let mut l = Object::begin(out)?;
                l.uint("count", count as u64)?;
                l.float("median", median)?;
                l.float("p99", p99)?;
                l.float("max", max)?;
                l.end()?;
            }
        }
        obj.end()
    }

    /// Write the text summary's SDO sentences.
    pub fn write_text<W: Write>(&self, out: &mut W, profile: Profile) -> io::Result<()> {
        if self.is_empty() {
            return Ok(());
        }
        write!(
            out,
            "          SDO: {} requests, {} transfers",
            self.requests, self.transfers
        )?;
        if let Some((count, median, p99, max)) = self.latency_ms() {
            write!(
                out,
                "; latency median {median:.3} ms, p99 {p99:.3} ms, max {max:.3} ms over {count}"
            )?;
        }
        writeln!(out)?;
        for abort in &self.aborts {
            write!(
                out,
                "          line {}: {} aborted {}",
                abort.line,
                abort.by.name(),
                abort.multiplexer
            )?;
            if let Some(name) = object_name(abort.multiplexer.index, profile) {
                write!(out, " ({name})")?;
            }
            writeln!(out, ": {}", abort.code)?;
        }
        if !self.broken.is_empty() {
            writeln!(
                out,
                "          broken transfers starting at lines {}",
                crate::summary::Lines(&self.broken)
            )?;
        }
        if !self.timeouts.is_empty() {
            writeln!(
                out,
                "          unanswered requests at lines {}",
                crate::summary::Lines(&self.timeouts)
            )?;
        }
        Ok(())
    }
}

fn ms(d: Duration) -> f64 {
    d.as_nanos() as f64 / 1e6
}

/// The name of object `index` for a node read with `profile` (SPEC §7.3
/// `object`).
pub fn object_name(index: u16, profile: Profile) -> Option<&'static str> {
    motionwire::canopen::object_name(index, profile.object_set())
}

/// Write the `sdo` key's object for one frame (SPEC §7.3).
pub fn write_sdo_json<W: Write>(
    obj: &mut Object<'_, W>,
    view: &SdoView<'_>,
    bytes: &[u8],
    profile: Profile,
) -> io::Result<()> {
    let out = obj.key("sdo")?;
    let mut o = Object::begin(out)?;
    o.name("direction", view.direction.direction_name())?;
    let message = match &view.message {
        Ok(message) => message,
        Err(_) => {
            let service = bytes
                .first()
                .map_or(motionwire::canopen::sdo::SdoService::Unknown, |&b| {
                    motionwire::canopen::sdo::SdoService::of(view.direction, b)
                });
            o.name("service", service.name())?;
            // A short frame: the multiplexer as far as it goes.
            if service.has_multiplexer() && bytes.len() >= 4 {
                let frame = motionwire::canopen::sdo::SdoFrame::new_unchecked(bytes);
                write_multiplexer(&mut o, frame.multiplexer(), profile)?;
            }
            return o.end();
        }
    };
    o.name("service", message.service().name())?;
    let f = message.fields();
    if let Some(sub) = f.subcommand {
        o.name("subcommand", sub.name())?;
    }
    if let Some(m) = f.multiplexer {
        write_multiplexer(&mut o, m, profile)?;
    }
    if let Some(e) = f.expedited {
        o.bool("expedited", e)?;
    }
    if let Some(size) = f.size {
        match size {
            Some(size) => o.uint("size", u64::from(size))?,
            None => o.null("size")?,
        }
    }
    if let Some(value) = f.value {
        json::hex_string(o.key("value")?, value)?;
    }
    if let Some(t) = f.toggle {
        o.uint("toggle", u64::from(t))?;
    }
    if let Some(last) = f.last {
        o.bool("last", last)?;
    }
    if let Some(code) = f.abort_code {
        o.uint("abort_code", u64::from(code.get()))?;
        o.name("abort_description", code.description())?;
    }
    if let Some(crc) = f.crc_supported {
        o.bool("crc_supported", crc)?;
    }
    if let Some(b) = f.blksize {
        o.uint("blksize", u64::from(b))?;
    }
    if let Some(a) = f.ackseq {
        o.uint("ackseq", u64::from(a))?;
    }
    if let Some(s) = f.seqno {
        o.uint("seqno", u64::from(s))?;
    }
    if let Some(crc) = f.crc {
        o.uint("crc", u64::from(crc))?;
    }
    o.end()
}

fn write_multiplexer<W: Write>(
    o: &mut Object<'_, W>,
    m: ObjectAddress,
    profile: Profile,
) -> io::Result<()> {
    o.uint("index", u64::from(m.index))?;
    o.uint("subindex", u64::from(m.sub_index))?;
    match object_name(m.index, profile) {
        Some(name) => o.name("object", name),
        None => o.null("object"),
    }
}

/// Write the `transfer` key (SPEC §7.3).
pub fn write_transfer_json<W: Write>(
    obj: &mut Object<'_, W>,
    transfer: &SdoTransfer,
    data: &[u8],
    profile: Profile,
) -> io::Result<()> {
    let out = obj.key("transfer")?;
    let mut o = Object::begin(out)?;
    o.name("direction", transfer.direction.name())?;
    write_multiplexer(&mut o, transfer.multiplexer, profile)?;
    o.uint("size", u64::from(transfer.bytes))?;
    json::hex_string(o.key("data")?, data)?;
    o.bool("truncated", transfer.bytes as usize > data.len())?;
    o.uint("frames", u64::from(transfer.frames))?;
    o.name("outcome", transfer.outcome.name())?;
    match transfer.outcome {
        SdoOutcome::Aborted { code, .. } => o.uint("abort_code", u64::from(code.get()))?,
        _ => o.null("abort_code")?,
    }
    match transfer.outcome {
        SdoOutcome::Broken(reason) => o.name("reason", reason.name())?,
        _ => o.null("reason")?,
    }
    o.uint("start_line", transfer.start_position)?;
    match transfer.duration {
        Some(d) => o.float("duration_ms", ms(d))?,
        None => o.null("duration_ms")?,
    }
    o.end()
}

/// Write an SDO frame as a person reads it: the transfer it ends
/// (`read 1008h.00 "AKD-P00306" (segmented, 10 B, 2.1 ms)`), an abort
/// (`abort 6041h.00: Object does not exist in the object dictionary`), or
/// the step it is.
pub fn write_sdo_text<W: Write>(
    out: &mut W,
    view: &SdoView<'_>,
    profile: Profile,
) -> io::Result<()> {
    if let Some((transfer, data)) = &view.ended {
        let verb = match transfer.direction {
            motionwire::canopen::sdo::TransferDirection::Upload => "read",
            motionwire::canopen::sdo::TransferDirection::Download => "write",
        };
        match transfer.outcome {
            SdoOutcome::Completed => {
                write!(out, "{verb} {} ", transfer.multiplexer)?;
                let expedited = transfer.mode == motionwire::canopen::sdo::TransferMode::Expedited;
                write_value(out, data, expedited, transfer.bytes as usize > data.len())?;
                write!(out, " ({}, {} B", transfer.mode.name(), transfer.bytes)?;
            }
            SdoOutcome::Aborted { code, by } => {
                write!(
                    out,
                    "abort {}: {} ({verb} aborted by the {}",
                    transfer.multiplexer,
                    code.description(),
                    by.name()
                )?;
            }
            SdoOutcome::Broken(reason) => write!(
                out,
                "{verb} {} broken: {reason} ({} B",
                transfer.multiplexer, transfer.bytes
            )?,
            SdoOutcome::TimedOut => write!(
                out,
                "{verb} {} timed out: no answer (line {}",
                transfer.multiplexer, transfer.start_position
            )?,
        }
        if let Some(d) = transfer.duration {
            write!(out, ", {:.1} ms", ms(d))?;
        }
        out.write_all(b")")?;
        return Ok(());
    }
    let message = match &view.message {
        Ok(m) => m,
        Err(e) => return write!(out, "{} error: {e}", view.direction.direction_name()),
    };
    let f = message.fields();
    if let Some(code) = f.abort_code {
        write!(out, "abort")?;
        if let Some(m) = f.multiplexer {
            write!(out, " {m}")?;
        }
        return write!(out, ": {}", code.description());
    }
    write!(
        out,
        "{} {}",
        view.direction.direction_name(),
        message.service().name().replace('_', " ")
    )?;
    if let Some(sub) = f.subcommand {
        write!(out, " {}", sub.name())?;
    }
    if let Some(m) = f.multiplexer {
        write!(out, " {m}")?;
        if let Some(name) = object_name(m.index, profile) {
            write!(out, " {name}")?;
        }
    }
    match (f.expedited, f.value) {
        (Some(true), Some(value)) => {
            out.write_all(b" ")?;
            write_value(out, value, true, false)?;
        }
        _ => {
            if let Some(Some(size)) = f.size {
                write!(out, ", size {size}")?;
            }
            if let Some(value) = f.value {
                write!(out, ", {} B", value.len())?;
            }
        }
    }
    if let Some(t) = f.toggle {
        write!(out, ", toggle {}", u8::from(t))?;
    }
    if let Some(s) = f.seqno {
        write!(out, ", seqno {s}")?;
    }
    if let Some(b) = f.blksize {
        write!(out, ", blksize {b}")?;
    }
    if let Some(a) = f.ackseq {
        write!(out, ", ackseq {a}")?;
    }
    if f.last == Some(true) {
        out.write_all(b", last")?;
    }
    if let Some(latency) = view.latency {
        write!(out, " ({:.1} ms)", ms(latency))?;
    }
    Ok(())
}

/// Data as a person reads it: expedited data as a little-endian number
/// (`= 0x0064`); else printable text in quotes, up to 8 bytes as a number,
/// longer data as hex bytes.
fn write_value<W: Write>(
    out: &mut W,
    data: &[u8],
    expedited: bool,
    truncated: bool,
) -> io::Result<()> {
    let text = data.strip_suffix(&[0]).unwrap_or(data);
    if !expedited && !text.is_empty() && text.iter().all(|b| (0x20..0x7F).contains(b)) {
        out.write_all(b"\"")?;
        for &b in text {
            if b == b'"' || b == b'\\' {
                out.write_all(b"\\")?;
            }
            out.write_all(&[b])?;
        }
        out.write_all(b"\"")?;
    } else if !data.is_empty() && data.len() <= 8 {
        out.write_all(b"= 0x")?;
        for b in data.iter().rev() {
            write!(out, "{b:02X}")?;
        }
    } else {
        out.write_all(b"[")?;
        for (i, b) in data.iter().take(32).enumerate() {
            if i > 0 {
                out.write_all(b" ")?;
            }
            write!(out, "{b:02X}")?;
        }
        if data.len() > 32 || truncated {
            out.write_all(" …".as_bytes())?;
        }
        out.write_all(b"]")?;
    }
    Ok(())
}
