//! One decoded frame, rendered as an aligned text line or a CSV row
//! (docs/output.md#text, docs/output.md#csv); its JSON record is the library's
//! (`Decoded::write_json`). The library decodes; this file only writes
//! what it says.

use std::io::{self, Write};

use motionwire::can::{Iface, LogFrame, SECONDS_LEN};
use motionwire::canopen::{CanOpenMessage, DecodeError, MessageKind, NodeId};
use motionwire::decoder::Decoded;
use motionwire::profiles::ProfiledEmcy;

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
    /// The input's name, when several are read (docs/output.md#several-files).
    pub file: Option<&'r str>,
}

impl Record<'_, '_, '_> {
    /// Return the frame's kind (`kind` in docs/output.md#common-keys).
    pub fn kind(&self) -> MessageKind {
        self.decoded.kind
    }

    /// Return the node the identifier names, for the kinds that have one.
    pub fn node(&self) -> Option<NodeId> {
        self.decoded.node
    }

    /// Write the record as one aligned line of text; an SDO frame in words
    /// from its view (docs/output.md#sdo-text).
    pub fn write_text<W: Write>(&self, out: &mut W) -> io::Result<()> {
        let log = self.log;
        let decoded = self.decoded;
        let frame = &log.frame;
        if let Some(file) = self.file {
            write!(out, "{file}:")?;
        }
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

/// The header row of `--csv` (docs/output.md#csv).
pub const CSV_HEADER: &str = "line,ts,iface,id,extended,rtr,fd,data,kind,node,code,description";

impl Record<'_, '_, '_> {
    /// Write the frame as one CSV row under [`CSV_HEADER`]
    /// (docs/output.md#csv): values as in the JSON, integers in decimal,
    /// `true`/`false`, data as hex, empty for null; a field with a comma, quote
    /// or line break is quoted as RFC 4180 says. Rows end with CRLF, as RFC
    /// 4180 says.
    pub fn write_csv<W: Write>(&self, out: &mut W) -> io::Result<()> {
        let log = self.log;
        let frame = &log.frame;
        let mut digits = itoa::Buffer::new();
        if let Some(file) = self.file {
            csv_field(out, file)?;
            out.write_all(b",")?;
        }
        out.write_all(digits.format(self.line).as_bytes())?;
        out.write_all(b",")?;
        if let Some(ts) = log.timestamp {
            let mut buf = [0; SECONDS_LEN];
            out.write_all(ts.format_seconds(&mut buf))?;
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
        hex_digits(out, frame.data())?;
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

/// Bytes as lowercase hex digits, no separators (`data` in
/// docs/output.md#common-keys).
fn hex_digits<W: Write>(out: &mut W, bytes: &[u8]) -> io::Result<()> {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    let mut buf = [0u8; 128];
    let n = bytes.len().min(64);
    for (i, &b) in bytes[..n].iter().enumerate() {
        buf[2 * i] = DIGITS[usize::from(b >> 4)];
        buf[2 * i + 1] = DIGITS[usize::from(b & 0xF)];
    }
    out.write_all(&buf[..2 * n])
}

/// Write an EtherCAT datagram's record as one CSV row under
/// [`CSV_HEADER`] (docs/ethercat.md#records): `line` is the packet, `data`
/// the datagram's data, `kind` `ecat_datagram`, and `description` its
/// fields in words (`#1 idx 0x41 adp 0x0000 ado 0x0130 len 6 wkc 1
/// returned …`); the CAN columns are empty.
pub fn write_datagram_csv<W: Write>(
    out: &mut W,
    record: &motionwire::decoder::ethercat::DatagramRecord<'_, '_>,
    file: Option<&str>,
) -> io::Result<()> {
    let packet = record.packet;
    let mut digits = itoa::Buffer::new();
    if let Some(file) = file {
        csv_field(out, file)?;
        out.write_all(b",")?;
    }
    out.write_all(digits.format(packet.position.number()).as_bytes())?;
    out.write_all(b",")?;
    if let Some(ts) = packet.timestamp {
        let mut buf = [0; SECONDS_LEN];
        out.write_all(ts.format_seconds(&mut buf))?;
    }
    out.write_all(b",")?;
    match packet.iface {
        Some(Iface::Name(name)) => csv_field(out, name)?,
        Some(Iface::Channel(channel)) => write!(out, "{channel}")?,
        None => {}
    }
    out.write_all(b",,,,,")?;
    hex_digits(out, record.datagram.data())?;
    write!(out, ",{},,,", motionwire::decoder::ethercat::DATAGRAM_KIND)?;
    csv_field(out, &record.fields().to_string())?;
    out.write_all(b"\r\n")
}
