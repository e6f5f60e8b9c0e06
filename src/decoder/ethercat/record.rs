//! One datagram of a packet as `decode` writes it: [`DatagramRecord`]
//! (docs/ethercat.md#records).

use core::fmt;
use std::cell::Cell;
use std::io::{self, Write};

use super::session::{IfaceKey, SharedKeys, SHARED_LEN};
use crate::can::Iface;
use crate::canopen::Emcy;
use crate::decoder::ethercat::{
    AlRegister, CoeSdoStep, CoeTransfer, Meaning, Missed, Packet, ProcessData, ServoReading,
    SiiField, SlaveRef,
};
use crate::decoder::json::{self, Block, Object, Padded};
use crate::decoder::record::emcy_json;
use crate::ethercat::register;
use crate::ethercat::{
    Addressing, CoeHeader, CoeSdo, CoeService, Command, Datagram, MailboxError, MailboxType,
    COE_HEADER_LEN,
};

/// The kind of a datagram's record (`"kind": "ecat_datagram"`).
pub const DATAGRAM_KIND: &str = "ecat_datagram";

/// The keys after `iface` up to `index`'s value, by command byte (the
/// last for every reserved one): `,"kind":"ecat_datagram","cmd":"LRW","index":`.
const COMMANDS: [Padded<64>; 16] = {
    let mut table = [Padded::EMPTY; 16];
    let mut byte = 0;
    while byte < table.len() {
        table[byte] = Padded::concat(&[
            b",\"kind\":\"",
            DATAGRAM_KIND.as_bytes(),
            b"\",\"cmd\":\"",
            Command::from_byte(byte as u8).name().as_bytes(),
            b"\",\"index\":",
        ]);
        byte += 1;
    }
    table
};

/// Every kind of record `decode` writes for an EtherCAT capture, in the
/// order docs/ethercat.md lists them: the datagram's, then what it tells
/// ([`MeaningRecord::kind`]).
pub const RECORD_KINDS: [&str; 16] = [
    DATAGRAM_KIND,
    "station",
    "al_state",
    "sii",
    "dl_status",
    "error_counters",
    "mailbox",
    "coe_sdo",
    "coe_emcy",
    PROCESS_DATA_KIND,
    SERVO_KIND,
    "alias",
    "dc",
    "dc_distribution",
    "mailbox_poll",
    "mailbox_repeat",
];

/// The kind of a slave's process-data record (`"kind": "process_data"`).
pub const PROCESS_DATA_KIND: &str = "process_data";
/// The kind of a servo's record (`"kind": "servo"`).
pub const SERVO_KIND: &str = "servo";

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
        // In one block: the prefix (62 bytes, then `ts` and `iface`: the
        // kept 64, or up to 203 with a piece's overrun when written here),
        // then the rest: the longest (a logical address, every field at
        // its largest, 16 data bytes) 178 bytes, a piece writing up to 64
        // bytes past its end.
        let mut b = Block::<448>::new();
        prefix_into(&mut b, out, self.packet, self.number, file);
        b.padded(&COMMANDS[usize::from(d.command().byte()).min(COMMANDS.len() - 1)]);
        b.uint(u64::from(d.index()));
        if d.command().addressing() == Addressing::Logical {
            b.text(b",\"logical\":");
            b.uint(u64::from(d.address()));
        } else {
            b.text(b",\"adp\":");
            b.uint(u64::from(d.adp()));
            b.text(b",\"ado\":");
            b.uint(u64::from(d.ado()));
        }
        b.text(b",\"length\":");
        b.uint(u64::from(d.length()));
        b.text(b",\"irq\":");
        b.uint(u64::from(d.irq()));
        b.text(b",\"wkc\":");
        b.uint(u64::from(d.working_counter()));
        if self.packet.copy.returned() {
            b.text(b",\"returned\":true,\"data\":");
        } else {
            b.text(b",\"returned\":false,\"data\":");
        }
        if b.short_hex_string(d.data()) {
            b.text(b"}\n");
            b.flush(out);
        } else {
            b.byte(b'"');
            b.flush(out);
            json::hex_digits(out, d.data());
            out.extend_from_slice(b"\"}\n");
        }
        debug_assert!(!b.is_full());
    }

    /// Write the record as one line of `decode`'s text output
    /// (docs/ethercat.md#records): packet, time, interface, command, kind,
    /// then the fields in words.
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_text<W: Write>(&self, out: &mut W, file: Option<&str>) -> io::Result<()> {
        text_prefix(out, self.packet, file)?;
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
            // Lowercase hex, 32 bytes a write: a mailbox datagram holds
            // a kilobyte.
            const HEX: &[u8; 16] = b"0123456789abcdef";
            let mut text = [0u8; 64];
            for chunk in d.data().chunks(32) {
                for (pair, &byte) in text.chunks_exact_mut(2).zip(chunk) {
                    pair[0] = HEX[usize::from(byte >> 4)];
                    pair[1] = HEX[usize::from(byte & 0x0f)];
                }
                let digits = text.get(..2 * chunk.len()).unwrap_or_default();
                f.write_str(core::str::from_utf8(digits).map_err(|_| fmt::Error)?)?;
            }
        }
        Ok(())
    }
}

/// Write the keys every record of a packet starts with: `file` (when
/// given), `packet`, `datagram`, `ts`, `iface`.
#[inline]
fn prefix(out: &mut Vec<u8>, packet: &Packet<'_>, number: usize, file: Option<&str>) {
    let mut b = Block::<256>::new();
    prefix_into(&mut b, out, packet, number, file);
    b.flush(out);
}

/// Write the keys of [`prefix`] into the block `b`, `ts` and `iface` as
/// the packet's first record made them ([`SharedKeys`]: kept when they fit
/// in [`SHARED_LEN`] bytes); where they are longer, write `b` into `out`
/// and empty it, and where they do not fit in `b`, write `b` and them
/// into `out`, leaving `b` empty. `b` holds `N` ≥ 256 bytes.
#[inline(always)]
fn prefix_into<const N: usize>(
    b: &mut Block<N>,
    out: &mut Vec<u8>,
    packet: &Packet<'_>,
    number: usize,
    file: Option<&str>,
) {
    if let Some(file) = file {
        out.extend_from_slice(b"{\"file\":");
        json::string(out, file);
    }
    // 10 + 20 + 12 + 20 bytes at most, then the shared keys.
    b.text(if file.is_some() {
        b",\"packet\":"
    } else {
        b"{\"packet\":"
    });
    b.uint(packet.position.number());
    b.text(b",\"datagram\":");
    b.uint(number as u64);
    let iface = IfaceKey::of(packet.iface);
    if let Some(shared) = packet.shared_keys.get() {
        if shared.timestamp == packet.timestamp && shared.iface == iface {
            b.padded(&shared.text);
            return;
        }
    }
    // The packet's first record: the keys written here, then kept.
    let start = b.len();
    b.text(b",\"ts\":");
    match packet.timestamp {
        Some(ts) => b.timestamp(ts),
        None => b.text(b"null"),
    }
    b.text(b",\"iface\":");
    match packet.iface {
        Some(Iface::Name(name)) => iface_name(b, name),
        Some(Iface::Channel(channel)) => b.uint(u64::from(channel)),
        None => b.text(b"null"),
    }
    if b.is_full() {
        // A long interface name: written into `out`, not kept.
        b.truncate(start);
        b.flush(out);
        b.clear();
        shared_keys(out, packet);
    } else if let Some(text) = b.padded_from::<SHARED_LEN>(start) {
        let _ = packet.shared_keys.set(SharedKeys {
            timestamp: packet.timestamp,
            iface,
            text,
        });
    } else {
        // Longer than the kept keys: written, the block emptied for the
        // rest of the record.
        b.flush(out);
        b.clear();
    }
}

/// Write an interface's name as a JSON string: a name of up to 64 bytes
/// that is not a short string without escapes (a Windows capture's
/// `\Device\NPF_{…}`, 50 bytes and two backslashes, named by every
/// packet) escaped once for all the packets that name it in a row
/// ([`LAST_LONG_NAME`]).
#[inline(always)]
fn iface_name<const N: usize>(b: &mut Block<N>, name: &str) {
    if b.short_string(name) {
        return;
    }
    let Some(raw) = Padded::<64>::new(name.as_bytes()) else {
        b.string(name);
        return;
    };
    LAST_LONG_NAME.with(|last| {
        if let Some((was, text)) = last.get() {
            if was == raw {
                b.padded(&text);
                return;
            }
        }
        let start = b.len();
        b.string(name);
        match b.padded_from::<96>(start) {
            Some(text) if !b.is_full() => last.set(Some((raw, text))),
            _ => {}
        }
    });
}

thread_local! {
    /// The last interface name [`iface_name`] escaped, as it is and as a
    /// JSON string.
    static LAST_LONG_NAME: Cell<Option<(Padded<64>, Padded<96>)>> = const { Cell::new(None) };
}

/// `,"ts":…,"iface":…`, written into `out`.
fn shared_keys(out: &mut Vec<u8>, packet: &Packet<'_>) {
    out.extend_from_slice(b",\"ts\":");
    match packet.timestamp {
        Some(ts) => json::timestamp(out, ts),
        None => out.extend_from_slice(b"null"),
    }
    out.extend_from_slice(b",\"iface\":");
    match packet.iface {
        Some(Iface::Name(name)) => json::string(out, name),
        Some(Iface::Channel(channel)) => json::uint(out, u64::from(channel)),
        None => out.extend_from_slice(b"null"),
    }
}

/// What a datagram told of a slave, as `decode` writes it: one record per
/// [`Meaning`] (docs/ethercat.md#meanings), after the datagram's own.
#[derive(Debug, Clone)]
pub struct MeaningRecord<'p, 'a> {
    /// The packet the datagram is in.
    pub packet: &'p Packet<'a>,
    /// The datagram's place in its frame, from 1.
    pub number: usize,
    /// What it told.
    pub meaning: Meaning<'a>,
}

impl MeaningRecord<'_, '_> {
    /// Return the record's kind: `station`, `al_state`, `sii`, `coe_sdo`,
    /// `coe_emcy` or `mailbox` (docs/ethercat.md#meanings).
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self.meaning {
            Meaning::StationAddress { .. } => "station",
            Meaning::AlState { .. } | Meaning::BroadcastAlStatus { .. } => "al_state",
            Meaning::Sii { .. } => "sii",
            Meaning::DlStatus { .. } => "dl_status",
            Meaning::ErrorCounters { .. } => "error_counters",
            Meaning::Mailbox { header, body, .. } => match coe(header.mailbox_type, body) {
                Some((CoeService::Emergency, _)) => "coe_emcy",
                Some((CoeService::SdoRequest | CoeService::SdoResponse, _)) => "coe_sdo",
                _ => "mailbox",
            },
            ref other => super::record_regs::kind(other).unwrap_or("mailbox"),
        }
    }

    /// Return the slave the record is about (station and position as far
    /// as known; neither for a broadcast read).
    #[must_use]
    pub fn slave(&self) -> SlaveRef {
        match self.meaning {
            Meaning::StationAddress { slave }
            | Meaning::AlState { slave, .. }
            | Meaning::Sii { slave, .. }
            | Meaning::DlStatus { slave, .. }
            | Meaning::ErrorCounters { slave, .. }
            | Meaning::Mailbox { slave, .. } => slave,
            Meaning::BroadcastAlStatus { .. } => SlaveRef::default(),
            ref other => super::record_regs::slave(other).unwrap_or_default(),
        }
    }

    /// Append the record as one JSON object and a newline to `out`, with
    /// `"file": file` first when given (docs/ethercat.md#meanings).
    pub fn append_json(&self, out: &mut Vec<u8>, file: Option<&str>) {
        prefix(out, self.packet, self.number, file);
        let mut obj = Object::after_first(out);
        obj.name("kind", self.kind());
        match self.meaning {
            Meaning::StationAddress { slave } => slave_json(&mut obj, slave),
            Meaning::AlState {
                slave,
                register,
                status,
                code,
            } => {
                slave_json(&mut obj, slave);
                obj.bool("broadcast", false);
                obj.name("register", register.name());
                al_json(&mut obj, status, code);
                obj.null("answered");
            }
            Meaning::BroadcastAlStatus { status, answered } => {
                slave_json(&mut obj, SlaveRef::default());
                obj.bool("broadcast", true);
                obj.name("register", AlRegister::Status.name());
                al_json(&mut obj, Some(status), None);
                obj.uint("answered", u64::from(answered));
            }
            Meaning::DlStatus { slave, low, high } => {
                slave_json(&mut obj, slave);
                dl_status_json(&mut obj, low, high);
            }
            Meaning::ErrorCounters { slave, bytes } => {
                slave_json(&mut obj, slave);
                error_counters_json(&mut obj, &bytes);
            }
            Meaning::Sii { slave, word, value } => {
                slave_json(&mut obj, slave);
                obj.uint("word", u64::from(word));
                obj.uint("value", u64::from(value));
                match SiiField::at(word) {
                    Some(field) => obj.name("field", field.name()),
                    None => obj.null("field"),
                }
            }
            Meaning::Mailbox {
                slave,
                written,
                accepted,
                guessed,
                repeated,
                header,
                body,
                profile,
                ref sdo,
            } => {
                slave_json(&mut obj, slave);
                obj.name("direction", if written { "write" } else { "read" });
                obj.bool("accepted", accepted);
                obj.bool("guessed", guessed);
                obj.bool("repeated", repeated);
                obj.name("type", header.mailbox_type.name());
                obj.uint("length", u64::from(header.length));
                obj.uint("address", u64::from(header.address));
                obj.uint("channel", u64::from(header.channel));
                obj.uint("priority", u64::from(header.priority));
                obj.uint("counter", u64::from(header.counter));
                mailbox_json(&mut obj, header.mailbox_type, body, profile, sdo.as_ref());
            }
            ref other => {
                slave_json(&mut obj, self.slave());
                super::record_regs::append_json(&mut obj, other);
            }
        }
        obj.end();
        out.push(b'\n');
    }

    /// Write the record as one line of `decode`'s text output: packet,
    /// time, interface, the command of its datagram, kind, then what it
    /// says in words.
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_text<W: Write>(
        &self,
        out: &mut W,
        command: &str,
        file: Option<&str>,
    ) -> io::Result<()> {
        text_prefix(out, self.packet, file)?;
        writeln!(out, "{command:>8}  {:<13}  {}", self.kind(), Words(self))
    }
}

/// A meaning in words, as the text output writes it.
struct Words<'r, 'p, 'a>(&'r MeaningRecord<'p, 'a>);

impl fmt::Display for Words<'_, '_, '_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let slave = |f: &mut fmt::Formatter<'_>, slave: SlaveRef| write!(f, "{slave}");
        match self.0.meaning {
            Meaning::StationAddress { slave: s } => {
                slave(f, s)?;
                f.write_str(" given its station address")
            }
            Meaning::AlState {
                slave: s,
                register,
                status,
                code,
            } => {
                slave(f, s)?;
                match (register, status) {
                    (AlRegister::Control, Some(st)) => {
                        write!(f, " requested {}", state_words(st))?;
                        if st.error() {
                            f.write_str(" (error acknowledged)")?;
                        }
                    }
                    (_, Some(st)) => {
                        write!(f, " in {}", state_words(st))?;
                        if st.error() {
                            f.write_str(" with error")?;
                        }
                    }
                    (_, None) => f.write_str(" AL status")?,
                }
                if let Some(code) = code {
                    write!(f, " code {code}")?;
                }
                Ok(())
            }
            Meaning::BroadcastAlStatus { status, answered } => write!(
                f,
                "broadcast: {} from {answered} slave{}{}",
                state_words(status),
                if answered == 1 { "" } else { "s" },
                if status.error() { ", error" } else { "" }
            ),
            Meaning::DlStatus {
                slave: s,
                low,
                high,
            } => {
                slave(f, s)?;
                f.write_str(" DL status")?;
                if let Some(low) = low {
                    write!(f, " link on ports {}", ports(low >> 4, 1))?;
                }
                if let Some(high) = high {
                    write!(
                        f,
                        " loop closed on ports {} communication on ports {}",
                        ports(high, 2),
                        ports(high >> 1, 2)
                    )?;
                }
                Ok(())
            }
            Meaning::ErrorCounters { slave: s, bytes } => {
                slave(f, s)?;
                f.write_str(" error counters")?;
                let mut any = false;
                for (at, value) in bytes.iter().enumerate() {
                    if let (Some(name), Some(value)) = (register::error_counter_name(at), value) {
                        write!(f, "{} {name} {value}", if any { "," } else { "" })?;
                        any = true;
                    }
                }
                Ok(())
            }
            Meaning::Sii {
                slave: s,
                word,
                value,
            } => {
                slave(f, s)?;
                write!(f, " SII word {word:#06x} = {value:#010x}")?;
                if let Some(field) = SiiField::at(word) {
                    write!(f, " ({})", field.name())?;
                }
                Ok(())
            }
            Meaning::Mailbox {
                slave: s,
                written,
                accepted,
                guessed,
                repeated,
                header,
                body,
                ..
            } => {
                slave(f, s)?;
                write!(
                    f,
                    " mailbox {} {} {} bytes counter {}",
                    if written { "write" } else { "read" },
                    header.mailbox_type,
                    header.length,
                    header.counter
                )?;
                if !accepted {
                    f.write_str(" not accepted")?;
                }
                if guessed {
                    f.write_str(" (area guessed)")?;
                }
                if repeated {
                    f.write_str(" (repeated, counted once)")?;
                }
                match coe(header.mailbox_type, body) {
                    Some((CoeService::Emergency, rest)) => match Emcy::parse(rest) {
                        Ok(emcy) => write!(
                            f,
                            ": emergency {:#06x} {}  register {:#04x}",
                            emcy.code.get(),
                            emcy.code.description(),
                            emcy.register.bits()
                        ),
                        Err(e) => write!(f, ": emergency, {e}"),
                    },
                    Some((service @ (CoeService::SdoRequest | CoeService::SdoResponse), rest)) => {
                        write!(f, ": {service}")?;
                        if let Ok(sdo) = CoeSdo::parse(rest) {
                            write!(f, " command {:#04x}", sdo.command())?;
                            let segment = sdo.specifier() == 0;
                            if let Some((index, sub)) = sdo.multiplexer().filter(|_| !segment) {
                                write!(f, " {index:04X}sub{sub}")?;
                            }
                            if sdo.complete_access() {
                                f.write_str(" complete access")?;
                            }
                            if let Some(abort) = sdo.abort_code() {
                                write!(f, " abort {abort}")?;
                            }
                        }
                        Ok(())
                    }
                    Some((service, _)) => write!(f, ": {service}"),
                    None if header.mailbox_type == MailboxType::Error => {
                        match MailboxError::parse(body) {
                            Ok(error) => write!(f, ": {error}"),
                            Err(e) => write!(f, ": {e}"),
                        }
                    }
                    None => Ok(()),
                }
            }
            ref other => {
                slave(f, self.0.slave())?;
                super::record_regs::words(f, other)
            }
        }
    }
}

/// `op`, or the bits when they name no one state (`0x0a`).
fn state_words(status: crate::ethercat::AlStatus) -> String {
    match status.state() {
        Some(state) => state.name().to_owned(),
        None => format!("states {:#04x}", status.state_bits()),
    }
}

/// A CoE message's service and the bytes after its header.
pub(super) fn coe(mailbox_type: MailboxType, body: &[u8]) -> Option<(CoeService, &[u8])> {
    if mailbox_type != MailboxType::Coe {
        return None;
    }
    let header = CoeHeader::parse(body).ok()?;
    Some((header.service, &body[COE_HEADER_LEN..]))
}

/// `slave` and `position`, null where not known.
fn slave_json(obj: &mut Object<'_>, slave: SlaveRef) {
    match slave.station {
        Some(s) => obj.uint("slave", u64::from(s)),
        None => obj.null("slave"),
    }
    match slave.position {
        Some(p) => obj.uint("position", u64::from(p)),
        None => obj.null("position"),
    }
}

/// `state`, `state_bits`, `error`, `code`, `code_text`.
fn al_json(
    obj: &mut Object<'_>,
    status: Option<crate::ethercat::AlStatus>,
    code: Option<crate::ethercat::AlStatusCode>,
) {
    match status {
        Some(status) => {
            match status.state() {
                Some(state) => obj.name("state", state.name()),
                None => obj.null("state"),
            }
            obj.uint("state_bits", u64::from(status.state_bits()));
            obj.bool("error", status.error());
        }
        None => {
            obj.null("state");
            obj.null("state_bits");
            obj.null("error");
        }
    }
    match code {
        Some(code) => {
            obj.uint("code", u64::from(code.0));
            match code.text() {
                Some(text) => obj.name("code_text", text),
                None => obj.null("code_text"),
            }
        }
        None => {
            obj.null("code");
            obj.null("code_text");
        }
    }
}

/// The keys of what a mailbox message holds: CoE emergency (the EMCY keys
/// of docs/output.md#emcy), CoE SDO, another CoE service, a mailbox error.
fn mailbox_json(
    obj: &mut Object<'_>,
    mailbox_type: MailboxType,
    body: &[u8],
    profile: crate::profiles::Profile,
    step: Option<&CoeSdoStep>,
) {
    match coe(mailbox_type, body) {
        Some((CoeService::Emergency, rest)) => {
            obj.name("service", CoeService::Emergency.name());
            match Emcy::parse(rest) {
                Ok(emcy) => emcy_json(obj, &emcy, profile),
                Err(e) => obj.display("error", &e),
            }
        }
        Some((service @ (CoeService::SdoRequest | CoeService::SdoResponse), rest)) => {
            obj.name("service", service.name());
            match CoeSdo::parse(rest) {
                Ok(sdo) => {
                    obj.uint("command", u64::from(sdo.command()));
                    // A segment (command specifier 0, either way) has no
                    // index: its bytes after the command are data.
                    let segment = sdo.specifier() == 0;
                    match sdo.multiplexer().filter(|_| !segment) {
                        Some((index, sub)) => {
                            obj.uint("index", u64::from(index));
                            obj.uint("subindex", u64::from(sub));
                        }
                        None => {
                            obj.null("index");
                            obj.null("subindex");
                        }
                    }
                    obj.bool("complete_access", sdo.complete_access());
                    match sdo.abort_code() {
                        Some(abort) => {
                            obj.uint("abort_code", u64::from(abort.get()));
                            obj.display("abort", &abort);
                        }
                        None => {
                            obj.null("abort_code");
                            obj.null("abort");
                        }
                    }
                    let data = if segment {
                        sdo.segment_data()
                    } else {
                        sdo.initiate_data()
                    };
                    let out = obj.key("data");
                    json::hex_string(out, data);
                    transfer_json(obj, step.and_then(|s| s.ended.as_ref()), profile);
                }
                Err(e) => obj.display("error", &e),
            }
        }
        Some((service, _)) => obj.name("service", service.name()),
        None if mailbox_type == MailboxType::Error => match MailboxError::parse(body) {
            Ok(error) => {
                obj.uint("error_code", u64::from(error.detail));
                match error.text() {
                    Some(text) => obj.name("error_text", text),
                    None => obj.null("error_text"),
                }
            }
            Err(e) => obj.display("error", &e),
        },
        None => {}
    }
}

/// `transfer`: the transfer the message completed (docs/ethercat.md#coe-sdo),
/// or null; its object named as CAN's transfers name it, by the slave's
/// profile.
fn transfer_json(
    obj: &mut Object<'_>,
    transfer: Option<&CoeTransfer>,
    profile: crate::profiles::Profile,
) {
    let Some(t) = transfer else {
        obj.null("transfer");
        return;
    };
    let out = obj.key("transfer");
    let mut inner = Object::begin(out);
    inner.uint("index", u64::from(t.index));
    inner.uint("subindex", u64::from(t.sub_index));
    inner.name("direction", if t.upload { "upload" } else { "download" });
    inner.bool("complete_access", t.complete_access);
    inner.bool("segmented", t.segmented);
    inner.uint("size", t.size as u64);
    match t.latency {
        Some(latency) => inner.float("latency_ms", latency.as_nanos() as f64 / 1e6),
        None => inner.null("latency_ms"),
    }
    match crate::canopen::object_name(t.index, profile.object_set()) {
        Some(name) => inner.name("object", name),
        None => inner.null("object"),
    }
    json::hex_string(inner.key("data"), &t.data);
    inner.bool("truncated", t.truncated());
    inner.end();
}

/// The ports (0–3) whose bit is set in `bits`, every `step` bits:
/// `0 2`, or `none`.
fn ports(bits: u8, step: u32) -> String {
    let set: Vec<String> = (0..4u32)
        .filter(|p| bits >> (p * step) & 1 != 0)
        .map(|p| p.to_string())
        .collect();
    if set.is_empty() {
        "none".to_owned()
    } else {
        set.join(" ")
    }
}

/// Four flags of `byte`, every `step` bits from `shift`, as a JSON list.
fn flags(out: &mut Vec<u8>, byte: u8, shift: u32, step: u32) {
    out.push(b'[');
    for p in 0..4u32 {
        if p > 0 {
            out.push(b',');
        }
        let set = byte >> (shift + p * step) & 1 != 0;
        out.extend_from_slice(if set { b"true" } else { b"false" });
    }
    out.push(b']');
}

/// `pdi_operational`, `links`, `loops_closed`, `communication`: null where
/// the read does not cover the byte.
fn dl_status_json(obj: &mut Object<'_>, low: Option<u8>, high: Option<u8>) {
    match low {
        Some(low) => {
            obj.bool("pdi_operational", low & 1 != 0);
            flags(obj.key("links"), low, 4, 1);
        }
        None => {
            obj.null("pdi_operational");
            obj.null("links");
        }
    }
    match high {
        Some(high) => {
            flags(obj.key("loops_closed"), high, 0, 2);
            flags(obj.key("communication"), high, 1, 2);
        }
        None => {
            obj.null("loops_closed");
            obj.null("communication");
        }
    }
}

/// A list of four counters at `at`, null where not read.
fn counters(out: &mut Vec<u8>, bytes: &[Option<u8>], at: usize, step: usize) {
    out.push(b'[');
    for p in 0..4 {
        if p > 0 {
            out.push(b',');
        }
        match bytes.get(at + p * step).copied().flatten() {
            Some(value) => json::uint(out, u64::from(value)),
            None => out.extend_from_slice(b"null"),
        }
    }
    out.push(b']');
}

/// The error counters: per port lists and the single ones, null where not
/// read.
fn error_counters_json(obj: &mut Object<'_>, bytes: &[Option<u8>]) {
    counters(obj.key("invalid_frames"), bytes, 0x00, 2);
    counters(obj.key("rx_errors"), bytes, 0x01, 2);
    counters(obj.key("forwarded_errors"), bytes, 0x08, 1);
    for (key, at) in [
        ("processing_unit_errors", 0x0C),
        ("pdi_errors", 0x0D),
        ("pdi_error_code", 0x0E),
    ] {
        match bytes.get(at).copied().flatten() {
            Some(value) => obj.uint(key, u64::from(value)),
            None => obj.null(key),
        }
    }
    counters(obj.key("lost_links"), bytes, 0x10, 1);
}

/// The columns every text line of a packet starts with: `FILE:` when
/// given, the packet, the time and the interface, as the CAN frames' lines
/// have them (docs/output.md#text).
fn text_prefix<W: Write>(out: &mut W, packet: &Packet<'_>, file: Option<&str>) -> io::Result<()> {
    if let Some(file) = file {
        write!(out, "{file}:")?;
    }
    write!(out, "{:>7}  ", packet.position.number())?;
    match packet.timestamp {
        Some(ts) => write!(out, "{:>10}.{:06}  ", ts.secs(), ts.micros())?,
        None => write!(out, "{:>17}  ", "-")?,
    }
    match packet.iface {
        Some(Iface::Name(name)) => write!(out, "{name:<6} "),
        Some(Iface::Channel(channel)) => write!(out, "{channel:<6} "),
        None => write!(out, "{:<6} ", "-"),
    }
}

/// One slave's process data in one cyclic datagram, as `decode` writes
/// it (docs/ethercat.md#process-data): the `process_data` record, and for
/// a servo the `servo` record after it.
#[derive(Debug, Clone, Copy)]
pub struct ProcessRecord<'r, 'p, 'a, 's> {
    /// The returned packet the datagram is in.
    pub packet: &'p Packet<'a>,
    /// The datagram's place in its frame, from 1.
    pub number: usize,
    /// The slave's process data.
    pub data: &'r ProcessData<'s>,
}

impl ProcessRecord<'_, '_, '_, '_> {
    /// Append the `process_data` record as one JSON object and a newline:
    /// the packet's keys, `kind`, `slave`, `position`, `logical`, `wkc`,
    /// `expected_wkc`, `confirmed`, `missing` (where the count is short:
    /// why this slave is taken as one that missed it, or null), `outputs`,
    /// `inputs` (hex, null where
    /// the datagram does not hold the whole image), `signals` (name →
    /// value, outputs then inputs) and `cia402` where the slave is a
    /// drive.
    pub fn append_json(&self, out: &mut Vec<u8>, file: Option<&str>) {
        let d = self.data;
        prefix(out, self.packet, self.number, file);
        let mut obj = Object::after_first(out);
        obj.name("kind", PROCESS_DATA_KIND);
        slave_json(&mut obj, d.slave.unwrap_or_default());
        obj.uint("logical", u64::from(d.logical));
        obj.uint("wkc", u64::from(d.wkc));
        match d.expected_wkc {
            Some(n) => obj.uint("expected_wkc", u64::from(n)),
            None => obj.null("expected_wkc"),
        }
        obj.bool("confirmed", d.confirmed);
        // A short count says why this slave is taken as one that missed
        // it, or null where others are.
        match d.missed {
            Missed::No => {}
            Missed::Others => obj.null("missing"),
            Missed::Named(evidence) => obj.name("missing", evidence.name()),
            Missed::Unknown => obj.name("missing", "unknown"),
        }
        for (key, image) in [("outputs", d.outputs), ("inputs", d.inputs)] {
            match image {
                Some(bytes) => json::hex_string(obj.key(key), bytes),
                None => obj.null(key),
            }
        }
        let buf = obj.key("signals");
        buf.push(b'{');
        let mut first = true;
        let mut error = None;
        d.for_each_signal(|_, name, signal| match signal {
            Ok(signal) => {
                if !first {
                    buf.push(b',');
                }
                first = false;
                json::string(buf, name);
                buf.push(b':');
                json::pdo_value(buf, &signal.value);
            }
            Err(e) => error = Some(e),
        });
        buf.push(b'}');
        match d.cia402 {
            Some(reading) => crate::decoder::record::cia402_json(&mut obj, &reading),
            None => obj.null("cia402"),
        }
        match error {
            Some(e) => obj.display("error", &e),
            None => obj.null("error"),
        }
        obj.end();
        out.push(b'\n');
    }

    /// Write the records as lines of `decode`'s text output: for
    /// `process`, the slave, its images and signals; for `servo` (a servo
    /// slave), its command, feedback and handshakes in words.
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_text<W: Write>(
        &self,
        out: &mut W,
        file: Option<&str>,
        process: bool,
        servo: bool,
    ) -> io::Result<()> {
        let d = self.data;
        let slave = d
            .slave
            .map_or_else(|| format!("logical {:#010x}", d.logical), |s| s.to_string());
        if process {
            text_prefix(out, self.packet, file)?;
            write!(out, "{:>8}  {:<13}  {slave}", "", PROCESS_DATA_KIND)?;
            if !d.confirmed {
                write!(out, " (inputs unconfirmed: wkc {}", d.wkc)?;
                if let Some(expected) = d.expected_wkc {
                    write!(out, " of {expected}")?;
                }
                if let Missed::Named(evidence) = d.missed {
                    write!(out, ", named by {}", evidence.text())?;
                }
                write!(out, ")")?;
            }
            let mut sep = ":";
            let mut named = false;
            d.for_each_signal(|_, name, signal| {
                if let Ok(signal) = signal {
                    let _ = write!(out, "{sep} {name} {}", signal.value);
                    sep = ",";
                    named = true;
                }
            });
            if !named {
                for (label, image) in [("outputs", d.outputs), ("inputs", d.inputs)] {
                    if let Some(bytes) = image {
                        write!(out, "{sep} {label} ")?;
                        for b in bytes {
                            write!(out, "{b:02x}")?;
                        }
                        sep = ",";
                    }
                }
            }
            if let Some(cia402) = d.cia402 {
                write!(out, "; {cia402}")?;
            }
            writeln!(out)?;
        }
        if let (true, Some(s)) = (servo, d.servo) {
            text_prefix(out, self.packet, file)?;
            write!(
                out,
                "{:>8}  {:<13}  {slave}: SSP {}, SE 0b{:02b}; enable {}",
                "",
                SERVO_KIND,
                s.command.speed_setpoint,
                s.command.control.servo_enable().get(),
                s.enable
            )?;
            if s.error_clear != crate::servo::HandshakePhase::Idle {
                write!(out, ", error clear {}", s.error_clear)?;
            }
            if s.zero_pulse != crate::servo::HandshakePhase::Idle {
                write!(out, ", zero pulse {}", s.zero_pulse)?;
            }
            match &s.feedback {
                Some(feedback) => write!(
                    out,
                    "; ActPos {}, SSW {}, SEW {}",
                    feedback.actual_position(),
                    feedback.status,
                    feedback.errors
                )?,
                None => write!(out, "; feedback unconfirmed")?,
            }
            writeln!(out)?;
        }
        Ok(())
    }

    /// Append the `servo` record of a servo slave (nothing for another):
    /// the packet's keys, `kind`, `slave`, `position`, `command` (as
    /// `motionwire servo command --json` writes it), `feedback` (as
    /// `servo feedback --json`; null where the inputs are unconfirmed),
    /// `enable`, `enable_cycles`, `error_clear`, `zero_pulse` (the
    /// handshakes' phases) and `ready`.
    pub fn append_servo_json(&self, out: &mut Vec<u8>, file: Option<&str>) {
        let Some(servo) = self.data.servo else { return };
        prefix(out, self.packet, self.number, file);
        let mut obj = Object::after_first(out);
        obj.name("kind", SERVO_KIND);
        slave_json(&mut obj, self.data.slave.unwrap_or_default());
        servo_json(&mut obj, &servo);
        obj.end();
        out.push(b'\n');
    }
}

/// The servo's values (docs/ethercat.md#servo).
fn servo_json(obj: &mut Object<'_>, servo: &ServoReading) {
    let command = crate::decoder::CommandRecord::from(&servo.command);
    // The records serialize; writing to a Vec cannot fail.
    let _ = serde_json::to_writer(&mut *obj.key("command"), &command);
    match &servo.feedback {
        Some(feedback) => {
            let feedback = crate::decoder::FeedbackRecord::from(feedback);
            let _ = serde_json::to_writer(&mut *obj.key("feedback"), &feedback);
        }
        None => obj.null("feedback"),
    }
    obj.name("enable", servo.enable.name());
    obj.uint("enable_cycles", u64::from(servo.enable_cycles));
    obj.name("error_clear", servo.error_clear.name());
    obj.name("zero_pulse", servo.zero_pulse.name());
    match servo.ready {
        Some(ready) => obj.bool("ready", ready),
        None => obj.null("ready"),
    }
}
