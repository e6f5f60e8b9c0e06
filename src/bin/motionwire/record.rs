//! One decoded frame, rendered as a JSON object or an aligned text line
//! (SPEC §6.1). The library decodes; this file only writes what it says.

use std::io::{self, Write};

use motionwire::can::{Iface, LogFrame};
use motionwire::canopen::{CanOpenMessage, DecodeError, Emcy, MessageKind, NodeId};
use motionwire::decoder::{Cia402Reading, Decoded, PdoReading};
use motionwire::profiles::akd::AkdManufacturerField;
use motionwire::profiles::baumer::BaumerEmcy;
use motionwire::profiles::{Profile, ProfiledEmcy};

use crate::json::{self, Object};
use crate::sdo;

/// One frame of the input with what the library's decoder made of it.
pub struct Record<'r, 'a, 'd> {
    /// 1-based line number in its input.
    pub line: u64,
    /// The frame as the log recorded it.
    pub log: &'r LogFrame<'a>,
    /// The decoder's reading.
    pub decoded: &'r Decoded<'d>,
    /// The frame read as CANopen.
    pub message: Result<CanOpenMessage, DecodeError>,
}

impl Record<'_, '_, '_> {
    /// Return the frame's kind (SPEC §6.1).
    pub fn kind(&self) -> MessageKind {
        self.decoded.kind
    }

    /// Return the node the identifier names, for the kinds that have one.
    pub fn node(&self) -> Option<NodeId> {
        self.decoded.node
    }

    /// Write the record as one JSON object and a newline (SPEC §6.1), with
    /// the `sdo` and `transfer` keys of an SDO frame's view (SPEC §7.3).
    pub fn write_json<W: Write>(&self, out: &mut W, keys: &mut PdoKeys) -> io::Result<()> {
        let log = self.log;
        let frame = &log.frame;
        let decoded = self.decoded;
        let profile = decoded.profile;
        let mut obj = Object::begin(out)?;
        obj.uint("line", self.line)?;
        match log.timestamp {
            Some(ts) => json::timestamp(obj.key("ts")?, ts)?,
            None => obj.null("ts")?,
        }
        match log.iface {
            Some(Iface::Name(name)) => obj.str("iface", name)?,
            Some(iface @ Iface::Channel(_)) => obj.display("iface", &iface)?,
            None => obj.null("iface")?,
        }
        obj.uint("id", u64::from(frame.id().raw()))?;
        obj.bool("extended", frame.is_extended())?;
        obj.bool("rtr", frame.is_rtr())?;
        obj.bool("fd", frame.is_fd())?;
        json::hex_string(obj.key("data")?, frame.data())?;
        obj.name("kind", self.kind().name())?;
        if let Some(node) = self.node() {
            obj.uint("node", u64::from(node.get()))?;
        }
        match &self.message {
            Ok(CanOpenMessage::Emcy { emcy, .. }) => emcy_json(&mut obj, emcy, profile)?,
            Ok(CanOpenMessage::Heartbeat { byte, .. }) => {
                obj.name("state", byte.state_name())?;
                obj.uint("state_raw", u64::from(byte.state_raw()))?;
                obj.bool("toggle", byte.toggle())?;
            }
            Ok(CanOpenMessage::NmtNodeControl(control)) => {
                obj.name("command", control.command.command_name())?;
                obj.uint("target", u64::from(control.node.map_or(0, NodeId::get)))?;
            }
            Ok(CanOpenMessage::Sync { counter }) => match counter {
                Some(counter) => obj.uint("counter", u64::from(*counter))?,
                None => obj.null("counter")?,
            },
            Ok(CanOpenMessage::Time(time)) => {
                let out = obj.key("time_of_day")?;
                let mut t = Object::begin(out)?;
                t.uint("ms", u64::from(time.ms()))?;
                t.uint("days", u64::from(time.days()))?;
                t.end()?;
            }
            Ok(CanOpenMessage::SdoRequest { .. } | CanOpenMessage::SdoResponse { .. }) => {
                if let Some(step) = &decoded.sdo {
                    sdo::write_sdo_json(&mut obj, step)?;
                    if let Some(ended) = &step.ended {
                        sdo::write_transfer_json(&mut obj, ended, step.objects)?;
                    }
                    if let Some(cia402) = &decoded.cia402 {
                        cia402_json(&mut obj, cia402)?;
                    }
                    if let Err(e) = &step.message {
                        obj.display("error", e)?;
                    }
                }
            }
            Ok(CanOpenMessage::Pdo { .. }) => {
                if let Some(reading) = &decoded.pdo {
                    pdo_json(&mut obj, reading, decoded.cia402.as_ref(), keys)?;
                }
            }
            Ok(CanOpenMessage::ErrorFrame(error)) => {
                obj.names("error_classes", error.classes.names())?;
                obj.names("controller", error.controller().names())?;
                match error.tx_errors() {
                    Some(n) => obj.uint("tx_errors", u64::from(n))?,
                    None => obj.null("tx_errors")?,
                }
                match error.rx_errors() {
                    Some(n) => obj.uint("rx_errors", u64::from(n))?,
                    None => obj.null("rx_errors")?,
                }
            }
            Ok(_) => {}
            Err(e) => {
                if e.kind == MessageKind::NmtCommand {
                    // An undefined command (or a target above 127): said as
                    // `unknown`, with the bytes that are there.
                    let data = frame.data();
                    if let Some(&command) = data.first() {
                        let name = motionwire::canopen::NmtCommand::from_byte(command)
                            .map_or("unknown", |c| c.command_name());
                        obj.name("command", name)?;
                    }
                    if let Some(&target) = data.get(1) {
                        obj.uint("target", u64::from(target))?;
                    }
                }
                if let Some(partial) = e.partial_emcy {
                    if let Some(code) = partial.code {
                        obj.uint("code", u64::from(code.get()))?;
                    }
                    if let Some(register) = partial.register {
                        obj.uint("register", u64::from(register.bits()))?;
                    }
                }
                obj.display("error", &e.error)?;
            }
        }
        obj.end()?;
        out_newline(out)
    }

    /// Write the record as one aligned line of text; an SDO frame in words
    /// from its view (SPEC §7.3).
    pub fn write_text<W: Write>(&self, out: &mut W) -> io::Result<()> {
        let log = self.log;
        let decoded = self.decoded;
        let frame = &log.frame;
        write!(out, "{:>7}  ", self.line)?;
        match log.timestamp {
            Some(ts) => write!(out, "{:>10}.{:06}  ", ts.secs(), ts.micros())?,
            None => write!(out, "{:>17}  ", "-")?,
        }
        match log.iface {
            Some(Iface::Name(name)) => write!(out, "{name:<6} ")?,
            Some(Iface::Channel(channel)) => write!(out, "{channel:<6} ")?,
            None => write!(out, "{:<6} ", "-")?,
        }
        if frame.is_extended() {
            write!(out, "{:08X}  ", frame.id().raw())?;
        } else {
            write!(out, "     {:03X}  ", frame.id().raw())?;
        }
        write!(out, "{:<13}  ", self.kind().name())?;
        match self.node() {
            Some(node) => write!(out, "node {:>3}  ", node.get())?,
            None => write!(out, "{:10}", "")?,
        }
        match &self.message {
            Err(e) => {
                write_data(out, log)?;
                write!(out, "  error: {}", e.error)?;
            }
            Ok(CanOpenMessage::GuardRequest { .. }) => out.write_all(b"remote request")?,
            Ok(CanOpenMessage::Heartbeat { byte, .. }) => {
                out.write_all(byte.state_name().as_bytes())?;
                if byte.state().is_none() {
                    write!(out, " (0x{:02X})", byte.state_raw())?;
                }
                if byte.toggle() {
                    out.write_all(b", toggle 1")?;
                }
            }
            Ok(CanOpenMessage::ErrorFrame(error)) => {
                write_data(out, log)?;
                write!(out, "  {error}")?;
            }
            Ok(CanOpenMessage::Emcy { emcy, .. }) => {
                write!(out, "{}", ProfiledEmcy::new(emcy, decoded.profile))?;
            }
            Ok(CanOpenMessage::NmtNodeControl(control)) => {
                out.write_all(control.command.command_name().as_bytes())?;
                match control.node {
                    Some(node) => write!(out, " node {node}")?,
                    None => out.write_all(b" all nodes")?,
                }
            }
            Ok(CanOpenMessage::Sync { counter }) => match counter {
                Some(counter) => write!(out, "counter {counter}")?,
                None => out.write_all(b"no counter")?,
            },
            Ok(CanOpenMessage::Time(time)) => write!(out, "{time}")?,
            Ok(CanOpenMessage::SdoRequest { .. } | CanOpenMessage::SdoResponse { .. }) => {
                match &decoded.sdo {
                    Some(step) => {
                        write!(out, "{step}")?;
                        if let Some(cia402) = &decoded.cia402 {
                            write!(out, "  [{cia402}]")?;
                        }
                    }
                    None => write_data(out, log)?,
                }
            }
            Ok(CanOpenMessage::Pdo { .. }) => match &decoded.pdo {
                Some(reading) => {
                    write!(out, "{reading}")?;
                    if let Some(cia402) = &decoded.cia402 {
                        write!(out, "  [{cia402}]")?;
                    }
                }
                None => write_data(out, log)?,
            },
            Ok(_) => write_data(out, log)?,
        }
        out_newline(out)
    }
}

/// The header row of `--csv` (SPEC §6.4).
pub const CSV_HEADER: &str = "line,ts,iface,id,extended,rtr,fd,data,kind,node,code,description";

impl Record<'_, '_, '_> {
    /// Write the frame as one CSV row under [`CSV_HEADER`] (SPEC §6.4):
    /// values as in the JSON, integers in decimal, `true`/`false`, data as
    /// hex, empty for null; a field with a comma, quote or line break is
    /// quoted as RFC 4180 says. Rows end with CRLF, as RFC 4180 says.
    pub fn write_csv<W: Write>(&self, out: &mut W) -> io::Result<()> {
        let log = self.log;
        let frame = &log.frame;
        let mut digits = itoa::Buffer::new();
        out.write_all(digits.format(self.line).as_bytes())?;
        out.write_all(b",")?;
        if let Some(ts) = log.timestamp {
            json::timestamp(out, ts)?;
        }
        out.write_all(b",")?;
        match log.iface {
            Some(Iface::Name(name)) => csv_field(out, name)?,
            Some(Iface::Channel(channel)) => write!(out, "{channel}")?,
            None => {}
        }
        out.write_all(b",")?;
        out.write_all(digits.format(frame.id().raw()).as_bytes())?;
        for flag in [frame.is_extended(), frame.is_rtr(), frame.is_fd()] {
            out.write_all(if flag { b",true" } else { b",false" })?;
        }
        out.write_all(b",")?;
        json::hex_digits(out, frame.data())?;
        out.write_all(b",")?;
        out.write_all(self.kind().name().as_bytes())?;
        out.write_all(b",")?;
        if let Some(node) = self.node() {
            out.write_all(digits.format(node.get()).as_bytes())?;
        }
        out.write_all(b",")?;
        let emcy = match &self.message {
            Ok(CanOpenMessage::Emcy { emcy, .. }) => Some((emcy.code, true)),
            Err(e) => e
                .partial_emcy
                .and_then(|p| p.code)
                .map(|code| (code, false)),
            Ok(_) => None,
        };
        if let Some((code, _)) = emcy {
            out.write_all(digits.format(code.get()).as_bytes())?;
        }
        out.write_all(b",")?;
        if let Some((code, _)) = emcy {
            csv_field(out, code.description())?;
        }
        out.write_all(b"\r\n")
    }
}

/// One CSV field, quoted when RFC 4180 requires it (a comma, a double
/// quote, CR or LF), with its quotes doubled.
fn csv_field<W: Write>(out: &mut W, text: &str) -> io::Result<()> {
    if !text.contains([',', '"', '\r', '\n']) {
        return out.write_all(text.as_bytes());
    }
    out.write_all(b"\"")?;
    out.write_all(text.replace('"', "\"\"").as_bytes())?;
    out.write_all(b"\"")
}

/// The EMCY keys of SPEC §6.1, with the profile's keys.
fn emcy_json<W: Write>(obj: &mut Object<'_, W>, emcy: &Emcy, profile: Profile) -> io::Result<()> {
    obj.uint("code", u64::from(emcy.code.get()))?;
    obj.name("class", emcy.code.class().name())?;
    obj.name("description", emcy.code.description())?;
    obj.uint("register", u64::from(emcy.register.bits()))?;
    obj.names("register_flags", emcy.register.names())?;
    json::hex_string(obj.key("manufacturer")?, &emcy.manufacturer)?;
    match profile {
        Profile::Generic => {}
        Profile::Akd => {
            let field = AkdManufacturerField::new_unchecked(&emcy.manufacturer[..]);
            obj.uint("axis", u64::from(field.axis_id().get()))?;
            match field.feedback_id() {
                Ok(fb) => match fb.number() {
                    Some(n) => obj.uint("feedback", u64::from(n))?,
                    None => obj.null("feedback")?,
                },
                Err(e) => {
                    obj.null("feedback")?;
                    obj.display("error", &e)?;
                }
            }
        }
        Profile::Baumer => {
            let baumer = BaumerEmcy::from_emcy(emcy);
            obj.uint("alarms", u64::from(baumer.manufacturer.alarms.bits()))?;
            obj.uint("warnings", u64::from(baumer.manufacturer.warnings.bits()))?;
            obj.names("sources", baumer.sources().map(|s| s.name()))?;
        }
    }
    Ok(())
}

fn out_newline<W: Write>(out: &mut W) -> io::Result<()> {
    out.write_all(b"\n")
}

fn write_data<W: Write>(out: &mut W, log: &LogFrame<'_>) -> io::Result<()> {
    let frame = &log.frame;
    if frame.is_rtr() {
        return write!(out, "[{}] remote request", frame.dlc());
    }
    write!(out, "[{}]", frame.data().len())?;
    for b in frame.data() {
        write!(out, " {b:02X}")?;
    }
    Ok(())
}

/// The signal names of each PDO mapping as JSON object keys, escaped once
/// per mapping (`"Statusword":`, `,"Position actual value":` with the comma
/// before every key but the first), by the mapping's id.
#[derive(Default)]
pub struct PdoKeys {
    by_map: Vec<Option<Vec<Box<[u8]>>>>,
}

impl PdoKeys {
    fn of(&mut self, reading: &PdoReading<'_>) -> &[Box<[u8]>] {
        let id = reading.map.id() as usize;
        if self.by_map.len() <= id {
            self.by_map.resize_with(id + 1, || None);
        }
        self.by_map[id].get_or_insert_with(|| {
            reading
                .map
                .names()
                .iter()
                .enumerate()
                .map(|(i, name)| json_key(name, i > 0))
                .collect()
        })
    }
}

/// A signal's name as a JSON object key, escaped once (`"Statusword":`),
/// with the comma before it for every signal but the first.
fn json_key(name: &str, comma: bool) -> Box<[u8]> {
    let mut key = Vec::with_capacity(name.len() + 4);
    if comma {
        key.push(b',');
    }
    json::string(&mut key, name).expect("writing to a Vec");
    key.push(b':');
    key.into_boxed_slice()
}

/// SPEC §8.2's `signals`: name → value in mapping order, and `error` when
/// the PDO is shorter than its mapping (its signals are those that fit);
/// §8.3's `cia402` for a drive.
fn pdo_json<W: Write>(
    obj: &mut Object<'_, W>,
    reading: &PdoReading<'_>,
    cia402: Option<&Cia402Reading>,
    keys: &mut PdoKeys,
) -> io::Result<()> {
    let keys = keys.of(reading);
    // `line` and the frame's keys come first, so this is never the first.
    let out = obj.raw_after_first(b",\"signals\":{")?;
    let mut error = None;
    let mut first = true;
    for (i, signal) in reading.signals.iter().enumerate() {
        match (signal, keys.get(i)) {
            // The keys carry their leading comma from the second on (not
            // wanted when the signals before could not be read).
            (Ok(signal), Some(key)) => {
                let key = if first && i > 0 { &key[1..] } else { &key[..] };
                first = false;
                out.write_all(key)?;
                json::pdo_value(out, &signal.value)?;
            }
            (Ok(_), None) => {}
            (Err(e), _) => error = Some(*e),
        }
    }
    out.write_all(b"}")?;
    if let Some(cia402) = cia402 {
        cia402_json(obj, cia402)?;
    }
    if let Some(e) = error {
        obj.display("error", &e)?;
    }
    Ok(())
}

/// SPEC §8.3's `cia402`: `state`, `command`, `mode` where the frame tells
/// them.
fn cia402_json<W: Write>(obj: &mut Object<'_, W>, reading: &Cia402Reading) -> io::Result<()> {
    let out = obj.raw_after_first(b",\"cia402\":{")?;
    let mut sep: &[u8] = b"";
    if let Some(state) = reading.state {
        out.write_all(b"\"state\":\"")?;
        out.write_all(state.name().as_bytes())?;
        out.write_all(b"\"")?;
        sep = b",";
    }
    if let Some(command) = reading.command {
        out.write_all(sep)?;
        out.write_all(b"\"command\":\"")?;
        out.write_all(command.name().as_bytes())?;
        out.write_all(b"\"")?;
        sep = b",";
    }
    if let Some(mode) = reading.mode {
        out.write_all(sep)?;
        out.write_all(b"\"mode\":")?;
        json::display_string(out, &mode)?;
    }
    out.write_all(b"}")
}
