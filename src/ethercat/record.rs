//! One datagram of a packet as `decode` writes it: [`DatagramRecord`]
//! (docs/ethercat.md#records).

use core::fmt;
use std::io::{self, Write};

use crate::can::Iface;
use crate::decoder::json;
use crate::ethercat::{Addressing, Datagram, Packet};

/// The kind of a datagram's record (`"kind": "ecat_datagram"`).
pub const DATAGRAM_KIND: &str = "ecat_datagram";

/// One datagram of a packet, numbered in its frame from 1: the record
/// `motionwire decode` writes for it (docs/ethercat.md#records).
///
/// Its fields are the datagram's as they were on the wire in this copy (a
/// returned APRD's `adp` is the value counted on by the slaves), and
/// `returned` says which copy it is.
#[derive(Debug, Clone, Copy)]
pub struct DatagramRecord<'p, 'a> {
    /// The packet the datagram is in.
    pub packet: &'p Packet<'a>,
    /// The datagram's place in its frame, from 1.
    pub number: usize,
    /// The datagram.
    pub datagram: Datagram<'a>,
}

impl DatagramRecord<'_, '_> {
    /// Append the record as one JSON object and a newline to `out`, with
    /// `"file": file` first when given (docs/ethercat.md#records):
    /// `packet`, `datagram`, `ts`, `iface`, `kind`, `cmd`, `index`, `adp`
    /// and `ado` (or `logical` for LRD/LWR/LRW), `length`, `irq`, `wkc`,
    /// `returned`, `data`.
    pub fn append_json(&self, out: &mut Vec<u8>, file: Option<&str>) {
        let d = &self.datagram;
        match file {
            None => out.extend_from_slice(b"{\"packet\":"),
            Some(file) => {
                out.extend_from_slice(b"{\"file\":");
                json::string(out, file);
                out.extend_from_slice(b",\"packet\":");
            }
        }
        json::uint(out, self.packet.position.number());
        out.extend_from_slice(b",\"datagram\":");
        json::uint(out, self.number as u64);
        out.extend_from_slice(b",\"ts\":");
        match self.packet.timestamp {
            Some(ts) => json::timestamp(out, ts),
            None => out.extend_from_slice(b"null"),
        }
        out.extend_from_slice(b",\"iface\":");
        match self.packet.iface {
            Some(Iface::Name(name)) => json::string(out, name),
            Some(Iface::Channel(channel)) => json::uint(out, u64::from(channel)),
            None => out.extend_from_slice(b"null"),
        }
        out.extend_from_slice(b",\"kind\":\"ecat_datagram\",\"cmd\":");
        json::string(out, d.command().name());
        out.extend_from_slice(b",\"index\":");
        json::uint(out, u64::from(d.index()));
        if d.command().addressing() == Addressing::Logical {
            out.extend_from_slice(b",\"logical\":");
            json::uint(out, u64::from(d.address()));
        } else {
            out.extend_from_slice(b",\"adp\":");
            json::uint(out, u64::from(d.adp()));
            out.extend_from_slice(b",\"ado\":");
            json::uint(out, u64::from(d.ado()));
        }
        out.extend_from_slice(b",\"length\":");
        json::uint(out, u64::from(d.length()));
        out.extend_from_slice(b",\"irq\":");
        json::uint(out, u64::from(d.irq()));
        out.extend_from_slice(b",\"wkc\":");
        json::uint(out, u64::from(d.working_counter()));
        out.extend_from_slice(if self.packet.copy.returned() {
            b",\"returned\":true,\"data\":"
        } else {
            b",\"returned\":false,\"data\":"
        });
        json::hex_string(out, d.data());
        out.extend_from_slice(b"}\n");
    }

    /// Write the record as one line of `decode`'s text output
    /// (docs/ethercat.md#records): packet, time, interface, command, kind,
    /// then the fields in words.
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_text<W: Write>(&self, out: &mut W, file: Option<&str>) -> io::Result<()> {
        if let Some(file) = file {
            write!(out, "{file}:")?;
        }
        write!(out, "{:>7}  ", self.packet.position.number())?;
        match self.packet.timestamp {
            Some(ts) => write!(out, "{:>10}.{:06}  ", ts.secs(), ts.micros())?,
            None => write!(out, "{:>17}  ", "-")?,
        }
        match self.packet.iface {
            Some(Iface::Name(name)) => write!(out, "{name:<6} ")?,
            Some(Iface::Channel(channel)) => write!(out, "{channel:<6} ")?,
            None => write!(out, "{:<6} ", "-")?,
        }
        writeln!(
            out,
            "{:>8}  {DATAGRAM_KIND:<13}  {}",
            self.datagram.command().name(),
            self.fields()
        )
    }

    /// Return the record's fields in words, as the text output and the
    /// CSV's `description` write them: `#1 idx 0x41 adp 0x0000 ado 0x0130
    /// len 6 wkc 1 returned data 140000001b00`.
    #[must_use]
    pub fn fields(&self) -> Fields<'_, '_, '_> {
        Fields(self)
    }
}

/// A datagram record's fields in words ([`DatagramRecord::fields`]).
#[derive(Debug, Clone, Copy)]
pub struct Fields<'r, 'p, 'a>(&'r DatagramRecord<'p, 'a>);

impl fmt::Display for Fields<'_, '_, '_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let record = self.0;
        let d = &record.datagram;
        write!(f, "#{} idx {:#04x} ", record.number, d.index())?;
        if d.command().addressing() == Addressing::Logical {
            write!(f, "logical {:#010x}", d.address())?;
        } else {
            write!(f, "adp {:#06x} ado {:#06x}", d.adp(), d.ado())?;
        }
        write!(f, " len {} wkc {}", d.length(), d.working_counter())?;
        if d.irq() != 0 {
            write!(f, " irq {:#06x}", d.irq())?;
        }
        f.write_str(if record.packet.copy.returned() {
            " returned"
        } else {
            " sent"
        })?;
        if !d.data().is_empty() {
            f.write_str(" data ")?;
            for byte in d.data() {
                write!(f, "{byte:02x}")?;
            }
        }
        Ok(())
    }
}
