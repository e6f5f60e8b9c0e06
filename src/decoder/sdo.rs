//! SDO channels as the decoder follows them: one [`SdoTracker`] per
//! (interface, node), the data of the transfer in progress (up to the
//! decoder's cap), and what each frame is in its transfer
//! (docs/canopen.md#transfers, docs/output.md#sdo).

use core::fmt;
use core::time::Duration;

use crate::can::{BusName, Timestamp};
use crate::canopen::sdo::{
    SdoEvent, SdoFrame, SdoMessage, SdoParty, SdoService, SdoTracker, SdoTransfer, TransferMode,
};
use crate::canopen::{NodeId, ObjectAddress, SdoAbortCode};

use super::ObjectNames;
use crate::FrameError;

/// One SDO frame as its channel's tracker read it (`sdo` in
/// docs/output.md#sdo), and the transfer it ends with that transfer's data
/// (`transfer`).
///
/// `Display` says it as a person reads it: the transfer it ends (`read
/// 1008h.00 "AKD-P00306" (segmented, 10 B, 2.1 ms)`), an abort (`abort
/// 6041h.00: Object does not exist in the object dictionary`), or the step
/// it is (`request initiate upload 1008h.00 Manufacturer device name`).
#[derive(Debug, Clone, Copy)]
pub struct SdoStep<'d> {
    /// The node whose SDO server the channel reaches (from the identifier).
    pub node: NodeId,
    /// Who sent the frame: the client (a request, docs/output.md#sdo
    /// `"direction": "request"`) or the server (a response).
    pub sender: SdoParty,
    /// The frame read in its transfer's context, or why it could not be
    /// read (a short frame, an undefined command specifier).
    pub message: Result<SdoMessage, FrameError>,
    /// The frame's data bytes.
    pub data: &'d [u8],
    /// The request → response latency this frame closes
    /// (docs/canopen.md#transfers).
    pub latency: Option<Duration>,
    /// The frame starts a transfer.
    pub started: bool,
    /// The transfer this frame ends, with its data.
    pub ended: Option<EndedTransfer<'d>>,
    /// Where this node's SDO objects get their names (`object` in
    /// docs/canopen.md#object-names): its EDS first, then the communication
    /// objects and the profile's.
    pub names: ObjectNames<'d>,
}

impl<'d> SdoStep<'d> {
    /// Return the service: the message's, or what the first byte says when
    /// the frame could not be read ([`SdoService::Unknown`] for no byte).
    #[must_use]
    pub fn service(&self) -> SdoService {
        match &self.message {
            Ok(message) => message.service(),
            Err(_) => self
                .data
                .first()
                .map_or(SdoService::Unknown, |&b| SdoService::of(self.sender, b)),
        }
    }

    /// Return the index and sub-index the frame carries: the message's, or,
    /// when it could not be read, bytes 1–3 if the frame is an initiate or an
    /// abort and they are there (the decision in docs/canopen.md#sdo: a short
    /// frame is decoded as far as it goes; 3 bytes give the index only, see
    /// [`index`](Self::index)).
    #[must_use]
    pub fn multiplexer(&self) -> Option<ObjectAddress> {
        match &self.message {
            Ok(message) => message.fields().multiplexer,
            Err(_) => (self.data.len() >= 4 && self.carries_multiplexer())
                .then(|| SdoFrame::new_unchecked(self.data).multiplexer()),
        }
    }

    /// Return the index of the object the frame addresses: the
    /// multiplexer's, or, for a frame cut after byte 2 that is an initiate
    /// or an abort, bytes 1–2 (little-endian; the decision in
    /// docs/canopen.md#sdo: 3 bytes give the service and the index, 4 the
    /// sub-index too).
    ///
    /// ```
    /// use motionwire::can::{CanFrame, CanId, LogFrame};
    /// use motionwire::decoder::{Decoder, DecoderConfig};
    /// use motionwire::logs::Position;
    ///
    /// let mut decoder = Decoder::new(DecoderConfig::new());
    /// let cut = LogFrame::new(CanFrame::new(CanId::standard(0x603).unwrap(), &[0x40, 0x00, 0x10]).unwrap());
    /// let step = decoder.decode(Position::Line(1), &cut).sdo.unwrap();
    /// assert!(step.message.is_err());
    /// assert_eq!((step.index(), step.multiplexer()), (Some(0x1000), None));
    /// assert_eq!(
    ///     step.to_string(),
    ///     "request initiate upload 1000h Device type, error: SDO frame: buffer of 3 bytes where 8 are needed"
    /// );
    /// ```
    #[must_use]
    pub fn index(&self) -> Option<u16> {
        if let Some(m) = self.multiplexer() {
            return Some(m.index);
        }
        match (&self.message, self.data) {
            (Err(_), [_, lo, hi, ..]) if self.carries_multiplexer() => {
                Some(u16::from_le_bytes([*lo, *hi]))
            }
            _ => None,
        }
    }

    /// Whether the first byte makes the frame one whose bytes 1–3 are the
    /// multiplexer: an initiate of any service (a block transfer's
    /// sub-command 0), or an abort (docs/canopen.md#sdo).
    fn carries_multiplexer(&self) -> bool {
        let Some(&first) = self.data.first() else {
            return false;
        };
        match self.service() {
            SdoService::BlockDownload | SdoService::BlockUpload => {
                // ccs 5 / scs 5: the sub-command in bits 1–0; ccs 6 / scs
                // 6: in bit 0. Initiate is 0.
                let mask = if first >> 5 == 5 { 0x03 } else { 0x01 };
                first & mask == 0
            }
            service => service.has_multiplexer(),
        }
    }

    /// Return the name of the object the frame addresses, if it addresses
    /// one and the name is known (`object` in docs/canopen.md#object-names).
    #[must_use]
    pub fn object(&self) -> Option<&'d str> {
        self.index().and_then(|index| self.names.name(index))
    }
}

/// One SDO frame as its channel's tracker followed it: an [`SdoStep`]
/// without its message, which is read from the frame's bytes where it is
/// wanted ([`step`](Self::step) for [`Decoder::decode`](super::Decoder::decode);
/// the summary reads only whether the frame is an abort,
/// [`abort`](Self::abort)). The tracker's event is read where the decoder
/// keeps it, not copied.
#[derive(Clone, Copy)]
pub(crate) struct SdoSeen<'s, 'd> {
    /// [`SdoStep::node`].
    pub(crate) node: NodeId,
    /// What the channel's tracker made of the frame: [`SdoStep::sender`],
    /// [`SdoStep::data`], [`SdoStep::latency`], [`SdoStep::started`] and
    /// the transfer of [`SdoStep::ended`], whose data is looked up only for
    /// the step ([`finished`](Self::finished)).
    pub(crate) event: &'s SdoEvent<'d>,
    /// The frame's data, as the event holds it.
    pub(crate) data: &'d [u8],
    /// [`SdoStep::names`].
    pub(crate) names: ObjectNames<'d>,
    /// The decoder's buses and this frame's bus, where the node's channel
    /// keeps the ended transfer's data.
    pub(super) buses: &'d super::Buses<super::BusState>,
    /// This frame's bus.
    pub(super) at: usize,
}

impl<'d> SdoSeen<'_, 'd> {
    /// Return the step, with the message read from the frame's bytes as the
    /// tracker read them.
    #[inline]
    pub(crate) fn step(&self) -> SdoStep<'d> {
        let event = self.event;
        let mut step = SdoStep {
            node: self.node,
            sender: event.sender(),
            message: event.message(),
            data: self.data,
            latency: event.latency,
            started: event.started,
            ended: None,
            names: self.names,
        };
        // Most frames end no transfer: the step is not made with a copy of
        // an empty one.
        if let Some(transfer) = event.ended {
            step.ended = Some(EndedTransfer {
                transfer,
                data: self.finished(),
                names: self.names,
            });
        }
        step
    }

    /// The data of the transfer that ended last on the node's channel,
    /// looked up in the buses as they are after the frame (what the ended
    /// transfer taught may have changed them).
    #[inline]
    fn finished(&self) -> &'d [u8] {
        self.buses.get(self.at).nodes[usize::from(self.node.get())]
            .as_ref()
            .expect("made by the decoder")
            .sdo
            .finished()
    }

    /// Return the name of the frame's bus.
    #[inline]
    pub(crate) fn bus_name(&self) -> &'d BusName {
        self.buses.name(self.at)
    }

    /// Return the multiplexer and code of the frame when it is an abort
    /// (the step's message is [`SdoRequest::Abort`](crate::canopen::sdo::SdoRequest::Abort)
    /// or [`SdoResponse::Abort`](crate::canopen::sdo::SdoResponse::Abort)), without the message.
    #[inline]
    pub(crate) fn abort(&self) -> Option<(ObjectAddress, SdoAbortCode)> {
        self.event.abort()
    }
}

/// A transfer that ended, with its data (`transfer` in
/// docs/output.md#transfer).
///
/// `Display` writes the transfer as a person reads it: `read 1008h.00
/// "AKD-P00306" (segmented, 10 B, 2.1 ms)`, `write 1A00h.00 = 0x00 …`,
/// `abort 1A00h.00: … (write aborted by the server, 0.4 ms)`, `read 6041h.00
/// timed out: no answer (line 12)`. The object's name is not in it
/// (docs/output.md#sdo-text); [`object`](Self::object) gives it.
///
/// ```
/// use motionwire::can::{CanFrame, CanId, LogFrame};
/// use motionwire::decoder::{Decoder, DecoderConfig};
/// use motionwire::logs::Position;
///
/// let mut decoder = Decoder::new(DecoderConfig::new());
/// let frame = |id: u32, data: &[u8]| {
///     LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
/// };
/// decoder.decode(Position::Line(1), &frame(0x605, &[0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0, 0]));
/// let answer = frame(0x585, &[0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0]);
/// let ended = decoder.decode(Position::Line(2), &answer).sdo.unwrap().ended.unwrap();
/// assert_eq!(ended.to_string(), "write 1017h.00 = 0x0064 (expedited, 2 B)");
/// assert_eq!(ended.object(), Some("Producer heartbeat time"));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct EndedTransfer<'d> {
    /// The transfer: object, direction, mode, size, frames, outcome, start
    /// and duration.
    pub transfer: SdoTransfer,
    /// Its data bytes, the first ones up to the decoder's cap
    /// ([`DecoderConfig::sdo_data_cap`](super::DecoderConfig::sdo_data_cap)).
    pub data: &'d [u8],
    /// Where the node's objects get their names (`object` in
    /// docs/canopen.md#object-names), as [`SdoStep::names`].
    pub names: ObjectNames<'d>,
}

impl<'d> EndedTransfer<'d> {
    /// Return the name of the transfer's object, where known (`object` in
    /// docs/canopen.md#object-names: the node's EDS first, then the
    /// communication objects and the profile's), as [`SdoStep::object`]
    /// names it for a frame.
    #[must_use]
    pub fn object(&self) -> Option<&'d str> {
        self.names.name(self.transfer.multiplexer.index)
    }

    /// Return whether the transfer moved more bytes than [`data`](Self::data)
    /// holds.
    #[must_use]
    pub fn truncated(&self) -> bool {
        self.transfer.bytes as usize > self.data.len()
    }
}

/// A channel: its tracker and the data of its open transfer.
#[derive(Debug, Default)]
pub(crate) struct SdoChannel {
    tracker: SdoTracker,
    data: Vec<u8>,
    finished: Vec<u8>,
}

impl SdoChannel {
    /// Feed one frame, `event` (`position`, time): what it is in its
    /// transfer is written into `event`; keep at most `cap` data bytes of
    /// a transfer.
    #[inline]
    pub(crate) fn feed(
        &mut self,
        event: &mut SdoEvent<'_>,
        ts: Option<Timestamp>,
        position: u64,
        cap: usize,
    ) {
        self.tracker.feed(event, ts, position);
        let chunk = event.chunk();
        let Some(ended) = &event.ended else {
            // Most frames: no transfer ends here (a segment request, a
            // segment, an initiate answered later).
            if event.started {
                self.data.clear();
            }
            push(&mut self.data, chunk, cap);
            return;
        };
        // The chunk belongs to the transfer that ends here unless this
        // frame also starts a new one (a new initiate after a timeout).
        let chunk_to_new = event.started && ended.start_position != position;
        if !chunk_to_new {
            push(&mut self.data, chunk, cap);
        }
        core::mem::swap(&mut self.data, &mut self.finished);
        self.data.clear();
        if chunk_to_new {
            push(&mut self.data, chunk, cap);
        }
    }

    /// The data of the transfer that ended last.
    pub(crate) fn finished(&self) -> &[u8] {
        &self.finished
    }

    /// End the input: the transfer left open, if any.
    pub(crate) fn finish(&mut self) -> Option<SdoTransfer> {
        self.tracker.finish()
    }
}

/// Keep `chunk` in `data`, up to `cap` bytes in all; most frames carry
/// none (a request for a segment, a confirmation), and cost a test.
#[inline]
fn push(data: &mut Vec<u8>, chunk: &[u8], cap: usize) {
    if chunk.is_empty() {
        return;
    }
    extend(data, chunk, cap);
}

/// [`push`] of a chunk that is not empty, out of line.
#[inline(never)]
fn extend(data: &mut Vec<u8>, chunk: &[u8], cap: usize) {
    let room = cap.saturating_sub(data.len());
    let chunk = &chunk[..chunk.len().min(room)];
    // A full segment's 7 bytes and expedited data's 4 as arrays: copied
    // in line, not by a call to `memcpy` for a few bytes.
    if let Ok(segment) = <&[u8; 7]>::try_from(chunk) {
        data.extend_from_slice(segment);
    } else if let Ok(expedited) = <&[u8; 4]>::try_from(chunk) {
        data.extend_from_slice(expedited);
    } else {
        data.extend_from_slice(chunk);
    }
}

fn ms(d: Duration) -> f64 {
    d.as_nanos() as f64 / 1e6
}

impl fmt::Display for EndedTransfer<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let transfer = &self.transfer;
        let value = DataText {
            data: self.data,
            expedited: transfer.mode == TransferMode::Expedited,
            truncated: self.truncated(),
        };
        transfer.fmt_with_data(f, Some(&value))
    }
}

impl fmt::Display for SdoStep<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(ended) = &self.ended {
            return fmt::Display::fmt(ended, f);
        }
        let message = match &self.message {
            Ok(m) => m,
            Err(e) => {
                // The decision in docs/canopen.md#sdo: as far as the frame goes
                // — the service, the index (3 bytes), the sub-index (4).
                f.write_str(self.sender.direction_name())?;
                let service = self.service();
                if service != SdoService::Unknown {
                    write_words(f, service.name())?;
                }
                match (self.multiplexer(), self.index()) {
                    (Some(m), _) => write!(f, " {m}")?,
                    (None, Some(index)) => write!(f, " {index:04X}h")?,
                    (None, None) => {}
                }
                if let Some(name) = self.object() {
                    write!(f, " {name}")?;
                }
                return write!(f, ", error: {e}");
            }
        };
        let fields = message.fields();
        if let Some(code) = fields.abort_code {
            f.write_str("abort")?;
            if let Some(m) = fields.multiplexer {
                write!(f, " {m}")?;
            }
            return write!(f, ": {}", code.description());
        }
        f.write_str(self.sender.direction_name())?;
        write_words(f, message.service().name())?;
        if let Some(sub) = fields.subcommand {
            write!(f, " {}", sub.name())?;
        }
        if let Some(m) = fields.multiplexer {
            write!(f, " {m}")?;
            if let Some(name) = self.names.name(m.index) {
                write!(f, " {name}")?;
            }
        }
        match (fields.expedited, fields.value) {
            (Some(true), Some(value)) => {
                let value = DataText {
                    data: value,
                    expedited: true,
                    truncated: false,
                };
                write!(f, " {value}")?;
            }
            _ => {
                if let Some(Some(size)) = fields.size {
                    write!(f, ", size {size}")?;
                }
                if let Some(value) = fields.value {
                    write!(f, ", {} B", value.len())?;
                }
            }
        }
        if let Some(t) = fields.toggle {
            write!(f, ", toggle {}", u8::from(t))?;
        }
        if let Some(s) = fields.seqno {
            write!(f, ", seqno {s}")?;
        }
        if let Some(b) = fields.blksize {
            write!(f, ", blksize {b}")?;
        }
        if let Some(a) = fields.ackseq {
            write!(f, ", ackseq {a}")?;
        }
        if fields.last == Some(true) {
            f.write_str(", last")?;
        }
        if let Some(latency) = self.latency {
            write!(f, " ({:.1} ms)", ms(latency))?;
        }
        Ok(())
    }
}

/// A service's name as words (`initiate_upload` → ` initiate upload`),
/// each after a space.
fn write_words(f: &mut fmt::Formatter<'_>, name: &str) -> fmt::Result {
    for word in name.split('_') {
        write!(f, " {word}")?;
    }
    Ok(())
}

/// Transfer data as a person reads it: expedited data as a little-endian
/// number (`= 0x0064`); else printable text in quotes, up to 8 bytes as a
/// number, longer data as hex bytes (the first 32, then `…`).
struct DataText<'a> {
    data: &'a [u8],
    expedited: bool,
    truncated: bool,
}

impl fmt::Display for DataText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let data = self.data;
        let text = data.strip_suffix(&[0]).unwrap_or(data);
        if !self.expedited && !text.is_empty() && text.iter().all(|b| (0x20..0x7F).contains(b)) {
            f.write_str("\"")?;
            for &b in text {
                if b == b'"' || b == b'\\' {
                    f.write_str("\\")?;
                }
                write!(f, "{}", char::from(b))?;
            }
            f.write_str("\"")
        } else if !data.is_empty() && data.len() <= 8 {
            f.write_str("= 0x")?;
            for b in data.iter().rev() {
                write!(f, "{b:02X}")?;
            }
            Ok(())
        } else {
            f.write_str("[")?;
            for (i, b) in data.iter().take(32).enumerate() {
                if i > 0 {
                    f.write_str(" ")?;
                }
                write!(f, "{b:02X}")?;
            }
            if data.len() > 32 || self.truncated {
                f.write_str(" …")?;
            }
            f.write_str("]")
        }
    }
}
