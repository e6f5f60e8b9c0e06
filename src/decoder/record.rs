//! A decoded frame as its JSON record (docs/output.md#json), with the keys
//! that SDO (docs/output.md#sdo, docs/output.md#transfer), PDOs
//! (docs/output.md#pdo) and CiA 402 (docs/output.md#cia402) add: built key by
//! key in a buffer (`append_json`, or one kept per thread for `write_json`),
//! without allocating per frame.

use std::io::{self, Write};

use crate::can::Iface;
use crate::canopen::sdo::SdoOutcome;
use crate::canopen::{CanOpenMessage, Emcy, MessageKind, NodeId, ObjectAddress};
use crate::profiles::akd::AkdManufacturerField;
use crate::profiles::baumer::BaumerEmcy;
use crate::profiles::Profile;

use super::json::{self, Object, Padded};
use super::{Cia402Reading, Decoded, EndedTransfer, ObjectNames, PdoReading, SdoStep};

/// A frame's flags and the start of its data (`,"extended":false,"rtr":false,
/// "fd":true,"data":"`), for each of the 8 sets of flags: extended 1, remote
/// request 2, CAN FD 4 (docs/output.md#common-keys).
const FLAGS: [Padded<64>; 8] = {
    const fn word(b: bool) -> &'static [u8] {
        if b {
            b"true"
        } else {
            b"false"
        }
    }
    let mut table = [Padded::EMPTY; 8];
    let mut i = 0;
    while i < table.len() {
        table[i] = Padded::concat(&[
            b",\"extended\":",
            word(i & 1 != 0),
            b",\"rtr\":",
            word(i & 2 != 0),
            b",\"fd\":",
            word(i & 4 != 0),
            b",\"data\":\"",
        ]);
        i += 1;
    }
    table
};

/// The end of a frame's data and its kind (`","kind":"pdo"`) for each
/// kind, by the kind's discriminant (docs/output.md#common-keys). The
/// names are the library's constant texts: no escaping.
const KINDS: [Padded<32>; MessageKind::ALL.len()] = {
    let mut table = [Padded::EMPTY; MessageKind::ALL.len()];
    let mut i = 0;
    while i < table.len() {
        let kind = MessageKind::ALL[i];
        table[kind as usize] = Padded::concat(&[b"\",\"kind\":\"", kind.name().as_bytes(), b"\""]);
        i += 1;
    }
    table
};

impl Decoded<'_> {
    /// Write the frame as one JSON object and a newline: the record of
    /// docs/output.md#json — `line`, `ts`, `iface`, `id`, the flags, `data`,
    /// `kind`, `node` and the keys of its kind (EMCY with the node's profile,
    /// heartbeat, NMT, SYNC, TIME, error frames, `error` where the data
    /// cannot be read) — with `sdo` and `transfer` on SDO frames
    /// (docs/output.md#sdo, docs/output.md#transfer), `signals` on PDOs with a
    /// known mapping (docs/output.md#pdo) and `cia402` on a drive's
    /// (docs/output.md#cia402). This is `motionwire decode --json`'s line.
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_json<W: Write>(&self, out: &mut W) -> io::Result<()> {
        self.write_via_scratch(out, None)
    }

    /// Write the frame's record as [`write_json`](Self::write_json) does,
    /// with `"file": file` first: the record of one of several logs read
    /// at once (docs/output.md#several-files).
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_json_in<W: Write>(&self, out: &mut W, file: &str) -> io::Result<()> {
        self.write_via_scratch(out, Some(file))
    }

    /// Append the frame's record, as [`write_json`](Self::write_json)
    /// writes it (with `"file": file` first when given, as
    /// [`write_json_in`](Self::write_json_in)), to `buf`: the fastest way
    /// to write many records, which a caller then writes out in large
    /// pieces.
    pub fn append_json(&self, buf: &mut Vec<u8>, file: Option<&str>) {
        self.write_record(buf, file);
    }

    /// The record built in a buffer kept by the thread (no allocation per
    /// frame), then written in one piece.
    fn write_via_scratch<W: Write>(&self, out: &mut W, file: Option<&str>) -> io::Result<()> {
        thread_local! {
            static SCRATCH: core::cell::RefCell<Vec<u8>> = const { core::cell::RefCell::new(Vec::new()) };
        }
        SCRATCH.with(|scratch| match scratch.try_borrow_mut() {
            Ok(mut buf) => {
                buf.clear();
                self.write_record(&mut buf, file);
                out.write_all(&buf)
            }
            Err(_) => {
                let mut buf = Vec::new();
                self.write_record(&mut buf, file);
                out.write_all(&buf)
            }
        })
    }

    fn write_record(&self, out: &mut Vec<u8>, file: Option<&str>) {
        let log = self.log;
        let frame = &log.frame;
        let decoded = self;
        let profile = decoded.profile;
        out.reserve(512);
        match file {
            None => out.extend_from_slice(b"{\"line\":"),
            Some(file) => {
                out.extend_from_slice(b"{\"file\":");
                json::string(out, file);
                out.extend_from_slice(b",\"line\":");
            }
        }
        json::uint(out, self.position.number());
        match log.timestamp {
            Some(ts) => {
                out.extend_from_slice(b",\"ts\":");
                json::timestamp(out, ts);
            }
            None => out.extend_from_slice(b",\"ts\":null"),
        }
        match log.iface {
            Some(Iface::Name(name)) => {
                out.extend_from_slice(b",\"iface\":");
                json::string(out, name);
            }
            Some(Iface::Channel(channel)) => {
                out.extend_from_slice(b",\"iface\":\"");
                json::uint(out, u64::from(channel));
                out.push(b'"');
            }
            None => out.extend_from_slice(b",\"iface\":null"),
        }
        out.extend_from_slice(b",\"id\":");
        json::uint(out, u64::from(frame.id().raw()));
        let flags = usize::from(frame.is_extended())
            | usize::from(frame.is_rtr()) << 1
            | usize::from(frame.is_fd()) << 2;
        FLAGS[flags].write(out);
        let (data, len) = frame.data_array();
        json::hex_frame_data(out, data, len);
        KINDS[self.kind as usize].write(out);
        if let Some(node) = self.node {
            out.extend_from_slice(b",\"node\":");
            json::uint(out, u64::from(node.get()));
        }
        let mut obj = Object::after_first(out);
        // SDO and PDO frames (not remote requests) carry what the session
        // read of them; their message adds nothing, so it is not worked
        // out. Every other frame's keys come from its message.
        let message = match self.kind {
            MessageKind::Sdo if !frame.is_rtr() => {
                if let Some(step) = &decoded.sdo {
                    // The frame's multiplexer and its transfer's are most
                    // often the same object: its name is looked up once.
                    let mut names = NameOnce::new(step.names);
                    write_sdo_json(&mut obj, step, &mut names);
                    if let Some(ended) = &step.ended {
                        write_transfer_json(&mut obj, ended, &mut names);
                    }
                    if let Some(cia402) = &decoded.cia402 {
                        cia402_json(&mut obj, cia402);
                    }
                    if let Err(e) = &step.message {
                        obj.display("error", e);
                    }
                }
                None
            }
            MessageKind::Pdo if !frame.is_rtr() => {
                if let Some(reading) = &decoded.pdo {
                    pdo_json(&mut obj, reading, decoded.cia402.as_ref());
                }
                None
            }
            _ => Some(self.message()),
        };
        match &message {
            None => {}
            Some(Ok(CanOpenMessage::Emcy { emcy, .. })) => emcy_json(&mut obj, emcy, profile),
            Some(Ok(CanOpenMessage::Heartbeat { byte, .. })) => {
                obj.name("state", byte.state_name());
                obj.uint("state_raw", u64::from(byte.state_raw()));
                obj.bool("toggle", byte.toggle());
            }
            Some(Ok(CanOpenMessage::NmtNodeControl(control))) => {
                obj.name("command", control.command.command_name());
                obj.uint("target", u64::from(control.node.map_or(0, NodeId::get)));
            }
            Some(Ok(CanOpenMessage::Sync { counter })) => match counter {
                Some(counter) => obj.uint("counter", u64::from(*counter)),
                None => obj.null("counter"),
            },
            Some(Ok(CanOpenMessage::Time(time))) => {
                let out = obj.key("time_of_day");
                let mut t = Object::begin(out);
                t.uint("ms", u64::from(time.ms()));
                t.uint("days", u64::from(time.days()));
                t.end();
            }
            Some(Ok(CanOpenMessage::ErrorFrame(error))) => {
                obj.names("error_classes", error.classes.names());
                obj.names("controller", error.controller().names());
                match error.tx_errors() {
                    Some(n) => obj.uint("tx_errors", u64::from(n)),
                    None => obj.null("tx_errors"),
                }
                match error.rx_errors() {
                    Some(n) => obj.uint("rx_errors", u64::from(n)),
                    None => obj.null("rx_errors"),
                }
            }
            Some(Ok(_)) => {}
            Some(Err(e)) => {
                if e.kind == MessageKind::NmtCommand {
                    // An undefined command (or a target above 127): said as
                    // `unknown`, with the bytes that are there.
                    let data = frame.data();
                    if let Some(&command) = data.first() {
                        let name = crate::canopen::NmtCommand::from_byte(command)
                            .map_or("unknown", |c| c.command_name());
                        obj.name("command", name);
                    }
                    if let Some(&target) = data.get(1) {
                        obj.uint("target", u64::from(target));
                    }
                }
                if let Some(partial) = e.partial_emcy {
                    if let Some(code) = partial.code {
                        obj.uint("code", u64::from(code.get()));
                    }
                    if let Some(register) = partial.register {
                        obj.uint("register", u64::from(register.bits()));
                    }
                }
                obj.display("error", &e.error);
            }
        }
        obj.end();
        out.push(b'\n');
    }

    /// Return the frame's JSON record ([`write_json`](Self::write_json))
    /// without its newline.
    #[must_use]
    pub fn to_json(&self) -> String {
        let mut out = Vec::with_capacity(256);
        self.write_record(&mut out, None);
        out.pop();
        String::from_utf8(out).expect("the writer writes UTF-8")
    }
}

/// The EMCY keys of docs/output.md#emcy, with the profile's keys.
pub(crate) fn emcy_json(obj: &mut Object<'_>, emcy: &Emcy, profile: Profile) {
    obj.uint("code", u64::from(emcy.code.get()));
    obj.name("class", emcy.code.class().name());
    obj.name("description", emcy.code.description());
    obj.uint("register", u64::from(emcy.register.bits()));
    obj.names("register_flags", emcy.register.names());
    let out = obj.key("manufacturer");
    out.push(b'"');
    json::hex_array(out, &emcy.manufacturer);
    out.push(b'"');
    match profile {
        Profile::Generic => {}
        Profile::Akd => {
            let field = AkdManufacturerField::new_unchecked(&emcy.manufacturer[..]);
            obj.uint("axis", u64::from(field.axis_id().get()));
            match field.feedback_id() {
                Ok(fb) => match fb.number() {
                    Some(n) => obj.uint("feedback", u64::from(n)),
                    None => obj.null("feedback"),
                },
                Err(e) => {
                    obj.null("feedback");
                    obj.display("error", &e);
                }
            }
        }
        Profile::Baumer => {
            let baumer = BaumerEmcy::from_emcy(emcy);
            obj.uint("alarms", u64::from(baumer.manufacturer.alarms.bits()));
            obj.uint("warnings", u64::from(baumer.manufacturer.warnings.bits()));
            obj.names("sources", baumer.sources().map(|s| s.name()));
        }
    }
}

/// Write the `sdo` key's object for one frame (docs/output.md#sdo).
fn write_sdo_json(obj: &mut Object<'_>, step: &SdoStep<'_>, names: &mut NameOnce<'_>) {
    let out = obj.key("sdo");
    let mut o = Object::begin(out);
    o.name("direction", step.sender.direction_name());
    o.name("service", step.service().name());
    let message = match &step.message {
        Ok(message) => message,
        Err(_) => {
            // A short frame, as far as it goes (the decision in
            // docs/canopen.md#sdo): the multiplexer, or from a 3-byte frame the
            // index alone.
            if let Some(m) = step.multiplexer() {
                write_multiplexer(&mut o, m, names);
            } else if let Some(index) = step.index() {
                o.uint("index", u64::from(index));
                match step.object() {
                    // From the EDS or a table: escaped (a file's name may
                    // hold anything).
                    Some(name) => o.str("object", name),
                    None => o.null("object"),
                }
            }
            return o.end();
        }
    };
    let f = message.fields();
    if let Some(sub) = f.subcommand {
        o.name("subcommand", sub.name());
    }
    if let Some(m) = f.multiplexer {
        write_multiplexer(&mut o, m, names);
    }
    if let Some(e) = f.expedited {
        o.bool("expedited", e);
    }
    if let Some(size) = f.size {
        match size {
            Some(size) => o.uint("size", u64::from(size)),
            None => o.null("size"),
        }
    }
    if let Some(value) = f.value {
        json::hex_string(o.key("value"), value);
    }
    if let Some(t) = f.toggle {
        o.uint("toggle", u64::from(t));
    }
    if let Some(last) = f.last {
        o.bool("last", last);
    }
    if let Some(code) = f.abort_code {
        o.uint("abort_code", u64::from(code.get()));
        o.name("abort_description", code.description());
    }
    if let Some(crc) = f.crc_supported {
        o.bool("crc_supported", crc);
    }
    if let Some(b) = f.blksize {
        o.uint("blksize", u64::from(b));
    }
    if let Some(a) = f.ackseq {
        o.uint("ackseq", u64::from(a));
    }
    if let Some(s) = f.seqno {
        o.uint("seqno", u64::from(s));
    }
    if let Some(crc) = f.crc {
        o.uint("crc", u64::from(crc));
    }
    o.end()
}

/// A node's object names, with the last name looked up kept: a record's
/// `sdo` and `transfer` keys most often name the same object.
struct NameOnce<'d> {
    names: ObjectNames<'d>,
    last: Option<(u16, Option<&'d str>)>,
}

impl<'d> NameOnce<'d> {
    fn new(names: ObjectNames<'d>) -> Self {
        NameOnce { names, last: None }
    }

    /// Return what [`ObjectNames::name`] returns for `index`.
    #[inline]
    fn name(&mut self, index: u16) -> Option<&'d str> {
        match self.last {
            Some((last, name)) if last == index => name,
            _ => {
                let name = self.names.name(index);
                self.last = Some((index, name));
                name
            }
        }
    }
}

fn write_multiplexer(o: &mut Object<'_>, m: ObjectAddress, names: &mut NameOnce<'_>) {
    o.uint("index", u64::from(m.index));
    o.uint("subindex", u64::from(m.sub_index));
    match names.name(m.index) {
        Some(name) => o.str("object", name),
        None => o.null("object"),
    }
}

/// Write the `transfer` key (docs/output.md#transfer).
fn write_transfer_json(obj: &mut Object<'_>, ended: &EndedTransfer<'_>, names: &mut NameOnce<'_>) {
    let transfer = &ended.transfer;
    let out = obj.key("transfer");
    let mut o = Object::begin(out);
    o.name("direction", transfer.direction.name());
    write_multiplexer(&mut o, transfer.multiplexer, names);
    o.uint("size", u64::from(transfer.bytes));
    json::hex_string(o.key("data"), ended.data);
    o.bool("truncated", ended.truncated());
    o.uint("frames", u64::from(transfer.frames));
    o.name("outcome", transfer.outcome.name());
    match transfer.outcome {
        SdoOutcome::Aborted { code, .. } => {
            o.uint("abort_code", u64::from(code.get()));
            o.name("abort_description", code.description());
        }
        _ => {
            o.null("abort_code");
            o.null("abort_description");
        }
    }
    match transfer.outcome {
        SdoOutcome::Broken(reason) => o.name("reason", reason.name()),
        _ => o.null("reason"),
    }
    o.uint("start_line", transfer.start_position);
    match transfer.duration {
        Some(d) => o.float("duration_ms", d.as_nanos() as f64 / 1e6),
        None => o.null("duration_ms"),
    }
    o.end()
}

/// The `signals` of docs/output.md#pdo: name → value in mapping order, and
/// `error` when the PDO is shorter than its mapping (its signals are those that
/// fit); the `cia402` of docs/output.md#cia402 for a drive.
fn pdo_json(obj: &mut Object<'_>, reading: &PdoReading<'_>, cia402: Option<&Cia402Reading>) {
    let keys = &reading.map.keys;
    // `line` and the frame's keys come first, so this is never the first.
    let out = obj.raw_after_first(b",\"signals\":");
    // Each signal's key starts with a comma: the first one written becomes
    // the brace that opens the object.
    let open = out.len();
    let mut error = None;
    for (i, signal) in reading.signals.iter().enumerate() {
        match signal {
            Ok(signal) => {
                if let Some(key) = keys.get(i) {
                    key.write(out);
                    json::pdo_value(out, &signal.value);
                }
            }
            Err(e) => error = Some(*e),
        }
    }
    match out.get_mut(open) {
        Some(comma) => {
            *comma = b'{';
            out.push(b'}');
        }
        None => out.extend_from_slice(b"{}"),
    }
    if let Some(cia402) = cia402 {
        cia402_json(obj, cia402);
    }
    if let Some(e) = error {
        obj.display("error", &e);
    }
}

/// The `cia402` of docs/output.md#cia402: `state`, `command`, `mode` where the
/// frame tells them.
pub(crate) fn cia402_json(obj: &mut Object<'_>, reading: &Cia402Reading) {
    let out = obj.raw_after_first(b",\"cia402\":{");
    let mut sep: &[u8] = b"";
    if let Some(state) = reading.state {
        out.extend_from_slice(b"\"state\":\"");
        out.extend_from_slice(state.name().as_bytes());
        out.extend_from_slice(b"\"");
        sep = b",";
    }
    if let Some(command) = reading.command {
        out.extend_from_slice(sep);
        out.extend_from_slice(b"\"command\":\"");
        out.extend_from_slice(command.name().as_bytes());
        out.extend_from_slice(b"\"");
        sep = b",";
    }
    if let Some(mode) = reading.mode {
        out.extend_from_slice(sep);
        out.extend_from_slice(b"\"mode\":");
        json::display_string(out, &mode);
    }
    out.push(b'}');
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::{PdoDirection, PdoMapping, Signal};

    /// The `signals` object (docs/output.md#pdo) opens at the first signal
    /// written, whichever that is: a signal that cannot be read leaves no
    /// key and no comma; no signal at all is `{}`.
    #[test]
    fn the_signals_object_opens_at_the_first_signal_written() {
        let mapping = PdoMapping::from_u32s(&[0x6041_0010, 0x6064_0020, 0x2000_0008]).unwrap();
        let node = NodeId::new(3).unwrap();
        let force = super::super::pdo::InForce {
            cob_id: crate::canopen::PdoCobId::from_u32(0x183),
            can_id: crate::can::CanId::standard(0x183).unwrap(),
            cob_id_origin: super::super::PdoOrigin::PredefinedConnectionSet,
            mapping,
        };
        let map = super::super::pdo::build_map(
            1,
            node,
            PdoDirection::Transmit,
            1,
            &force,
            super::super::PdoOrigin::Sdo {
                position: crate::logs::Position::Line(1),
            },
            None,
            None,
            false,
        );
        let whole: Vec<_> = map
            .layout()
            .unpack(&[0x37, 0x02, 1, 0, 0, 0, 9])
            .map(|s| s.map_err(crate::CodecError::from))
            .collect();
        let error = map
            .layout()
            .unpack(&[])
            .next()
            .unwrap()
            .map_err(crate::CodecError::from);
        assert!(error.is_err());
        let render = |signals: &[Result<Signal, crate::CodecError>]| {
            let mut out = b"{\"line\":1".to_vec();
            let mut obj = Object::after_first(&mut out);
            pdo_json(&mut obj, &PdoReading { map: &map, signals }, None);
            obj.end();
            String::from_utf8(out).unwrap()
        };
        let error_text = "\"PDO entry 6041sub0 (16 bits) at bit 0: expected a payload of at least 2 bytes, found 0\"";
        assert_eq!(
            render(&whole),
            r#"{"line":1,"signals":{"6041sub0":567,"6064sub0":1,"2000sub0":9}}"#
        );
        assert_eq!(
            render(&[error, whole[1], whole[2]]),
            format!(r#"{{"line":1,"signals":{{"6064sub0":1,"2000sub0":9}},"error":{error_text}}}"#)
        );
        assert_eq!(
            render(&[whole[0], error]),
            format!(r#"{{"line":1,"signals":{{"6041sub0":567}},"error":{error_text}}}"#)
        );
        assert_eq!(
            render(&[error]),
            format!(r#"{{"line":1,"signals":{{}},"error":{error_text}}}"#)
        );
        assert_eq!(render(&[]), r#"{"line":1,"signals":{}}"#);
    }
}
