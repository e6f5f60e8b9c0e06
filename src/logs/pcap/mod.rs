//! pcap and pcapng captures of SocketCAN frames, as Wireshark, tshark,
//! tcpdump and dumpcap write them (docs/formats.md#pcap).
//!
//! [`PcapReader`] reads both file formats from any [`std::io::Read`],
//! detected from the magic number:
//!
//! - **pcap**: both byte orders, microsecond (`0xA1B2C3D4`) and nanosecond
//!   (`0xA1B23C4D`) timestamps, version 2.x;
//! - **pcapng**: any number of sections (each with its byte order) and of
//!   interface description blocks, each with its link type, its name
//!   (`if_name`, the frames' [`Iface::Name`]), its timestamp resolution
//!   (`if_tsresol`, microseconds when absent) and offset (`if_tsoffset`);
//!   enhanced, simple and (obsolete) packet blocks. Other blocks (name
//!   resolution, statistics, decryption secrets, custom) are skipped; a
//!   systemd journal export block takes a packet number, as in tshark, and
//!   is counted with the packets of other link types.
//!
//! Packets of link type 227, `LINKTYPE_CAN_SOCKETCAN`, are CAN frames (the
//! 8-byte header of `linux/can.h` with the identifier word big-endian, then
//! the data; see the `socketcan` notes below). So are the Linux "cooked"
//! captures of `tcpdump -i any` (and of Wireshark or dumpcap on a CAN
//! interface in some setups): link type 113 ([`LINKTYPE_LINUX_SLL`],
//! 16-byte header) and 276 ([`LINKTYPE_LINUX_SLL2`], 20-byte header) with
//! protocol 0x000C (CAN) or 0x000D (CAN FD), whose SocketCAN frame follows
//! in the capturing machine's byte order, read little-endian as tshark
//! reads it (the decision in docs/formats.md#pcap). Packets of link type 1
//! ([`LINKTYPE_ETHERNET`]) and cooked packets of protocol 0x88A4 are an
//! EtherCAT master's port: a packet that carries EtherCAT is a
//! [`LogEvent::Ethercat`], an Ethernet packet of another EtherType is
//! counted by it, and one shorter than its headers is a skipped
//! [`BinaryError::EthernetTooShort`] (docs/ethercat.md#reading). Packets of
//! any other link type or protocol, and CAN XL frames, take their number and are counted by
//! kind in [`ReadLog::other_records`] and [`ReadLog::other_kinds`]: the caller
//! reports them once, naming the link type (docs/formats.md#pcap).
//!
//! What each frame gets (docs/formats.md#pcap):
//! - `number`: the 1-based packet number, tshark's `frame.number`;
//! - `timestamp`: absolute Unix time to the file's resolution (a simple
//!   packet block records none);
//! - `iface`: the interface name of a pcapng interface that has one (other
//!   than `any`), else the interface index of a cooked SLL2 header as a
//!   channel number, else `None` (pcap names none);
//! - `direction`: `None`.
//!
//! **Classic, CAN FD, CAN XL.** A packet is CAN FD when its flags byte has
//! `CANFD_FDF` (0x04) and no unknown bit, with the two following bytes zero
//! (Wireshark's `packet-socketcan.c` rule), or when it is the whole
//! 72-byte `struct canfd_frame` (`CANFD_MTU`: a capture from a libpcap that
//! predates the FDF flag; tshark 4.0 shows such a packet as classic CAN).
//! `CAN_ERR_FLAG` in a classic frame makes an error frame whose identifier
//! holds the class bits and whose data is kept; a remote request keeps its
//! length as its DLC and has no data; identifier bits above the 11 of a
//! standard frame are ignored, as Wireshark and the kernel do. A CAN XL
//! frame (`CANXL_XLF`, 0x80, in the length byte) is skipped and counted,
//! never misread.
//!
//! **Damaged or hostile files.** Every error is a [`FormatError::Binary`] with
//! the byte offset of the damaged structure, returned after the frames
//! before it; [`ReadLog::next_event`] returns `None` afterwards. A length
//! above [`MAX_RECORD_LEN`] is [`BinaryError::TooLarge`] and is never
//! allocated; memory stays bounded whatever the file claims (the read-ahead
//! window grows only while the file supplies bytes; a section's interface
//! descriptions are held up to [`MAX_RECORD_LEN`] bytes).
//!
//! ```
//! use motionwire::can::{CanId, Iface, LogEvent};
//! use motionwire::logs::pcap::PcapReader;
//! use motionwire::logs::{LogFormat, Position, ReadLog};
//!
//! // pcap, little-endian, microseconds, link type 227; one packet:
//! // 705#05 at 1700000000.000500.
//! let mut file = Vec::new();
//! for word in [0xA1B2_C3D4u32, 0x0004_0002, 0, 0, 65_535, 227] {
//!     file.extend(word.to_le_bytes());
//! }
//! for word in [1_700_000_000u32, 500, 16, 16] {
//!     file.extend(word.to_le_bytes());
//! }
//! file.extend([0, 0, 0x07, 0x05, 1, 0, 0, 0, 0x05, 0, 0, 0, 0, 0, 0, 0]);
//!
//! let mut reader = PcapReader::new(&file[..])?;
//! assert_eq!(reader.format(), LogFormat::Pcap);
//! let record = reader.next_event().unwrap()?;
//! assert_eq!(record.position, Position::Record(1));
//! let LogEvent::Frame(logged) = record.event else { panic!() };
//! assert_eq!(logged.frame.id(), CanId::standard(0x705).unwrap());
//! assert_eq!(logged.frame.data(), [0x05]);
//! assert_eq!(logged.to_string(), "(1700000000.000500) 705#05");
//! assert!(reader.next_event().is_none());
//! # Ok::<(), motionwire::logs::LogError>(())
//! ```

mod cooked;
mod ethernet;
mod input;
mod not_can;
#[cfg(test)]
mod proptests;
mod socketcan;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod writer;

use core::time::Duration;
use std::io::Read;

use crate::can::{CanFrame, EthercatPacket, Iface, LogEvent, LogFrame, Timestamp};
use crate::logs::bytes::{u16_at, u32_at};
use crate::logs::FormatError;
use crate::logs::{
    BinaryError, LogError, LogErrorKind, LogFormat, LogRecord, OtherCounts, OtherRecords, Position,
    ReadLog, MAX_RECORD_LEN,
};
use cooked::Cooked;
pub use cooked::{LINKTYPE_LINUX_SLL, LINKTYPE_LINUX_SLL2};
use ethernet::Ethernet;
pub use ethernet::LINKTYPE_ETHERNET;
use input::Input;
use not_can::NotCan;
use socketcan::{FrameLayout, Payload};

/// `LINKTYPE_CAN_SOCKETCAN`: SocketCAN frames (docs/formats.md#pcap).
pub const LINKTYPE_CAN_SOCKETCAN: u16 = 227;

/// The pcap magic numbers as the first four bytes read little-endian.
mod magic {
    /// pcap, microseconds, written little-endian.
    pub(super) const MICROS: u32 = 0xA1B2_C3D4;
    /// pcap, microseconds, written big-endian.
    pub(super) const MICROS_SWAPPED: u32 = 0xD4C3_B2A1;
    /// pcap, nanoseconds, written little-endian.
    pub(super) const NANOS: u32 = 0xA1B2_3C4D;
    /// pcap, nanoseconds, written big-endian.
    pub(super) const NANOS_SWAPPED: u32 = 0x4D3C_B2A1;
    /// pcapng section header block type (a palindrome: either order).
    pub(super) const SECTION_HEADER: u32 = 0x0A0D_0D0A;
    /// pcapng byte-order magic as written in the file's own order.
    pub(super) const BYTE_ORDER: u32 = 0x1A2B_3C4D;
}

/// pcapng block types (pcapng specification, §4).
mod block {
    /// Interface description block.
    pub(super) const INTERFACE: u32 = 1;
    /// Packet block (obsolete).
    pub(super) const PACKET: u32 = 2;
    /// Simple packet block.
    pub(super) const SIMPLE_PACKET: u32 = 3;
    /// Enhanced packet block.
    pub(super) const ENHANCED_PACKET: u32 = 6;
    /// systemd journal export block: a record in tshark, not a packet.
    pub(super) const SYSTEMD_JOURNAL: u32 = 9;
}

/// The pcap file header: magic, version, reserved, snaplen, link type.
/// The name of Linux's pseudo-interface that captures every interface
/// (`tcpdump -i any`): it names no bus.
const ANY: &str = "any";

const PCAP_HEADER_LEN: usize = 24;
/// A pcap record header: seconds, fraction, captured and original length.
const PCAP_RECORD_LEN: usize = 16;
/// A pcapng block's type, length and trailing length.
const BLOCK_OVERHEAD: usize = 12;
/// An enhanced packet block's head: type, length, interface, time (two
/// words), captured and original length (pcapng specification, §4.3).
const EPB_HEAD_LEN: usize = 28;
/// An enhanced packet block without options, besides its packet (a
/// multiple of 4 bytes long): its head and trailing length.
const EPB_LEN: usize = EPB_HEAD_LEN + 4;
/// What one interface description costs in memory besides its name.
const INTERFACE_COST: usize = size_of::<Interface>();

/// How a pcapng interface (or the pcap file) counts time: units of
/// 10^-n s or 2^-n s (`if_tsresol`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Resolution {
    /// 10^-n s.
    Decimal(u8),
    /// 2^-n s.
    Binary(u8),
}

impl Resolution {
    /// Read an `if_tsresol` byte: bit 7 chooses base 2, the rest is n.
    const fn from_byte(b: u8) -> Self {
        if b & 0x80 != 0 {
            Resolution::Binary(b & 0x7F)
        } else {
            Resolution::Decimal(b)
        }
    }

    /// Return `ticks` as seconds and nanoseconds (truncated).
    #[inline]
    fn split(self, ticks: u64) -> (u64, u32) {
        // The resolutions writers use, with constant divisors.
        match self {
            Resolution::Decimal(6) => (ticks / 1_000_000, (ticks % 1_000_000) as u32 * 1_000),
            Resolution::Decimal(9) => (ticks / 1_000_000_000, (ticks % 1_000_000_000) as u32),
            _ => self.split_any(ticks),
        }
    }

    /// [`Resolution::split`] for any resolution.
    fn split_any(self, ticks: u64) -> (u64, u32) {
        const NANOS: u128 = 1_000_000_000;
        let (secs, nanos) = match self {
            Resolution::Decimal(n) => match 10u64.checked_pow(u32::from(n)) {
                Some(unit) => {
                    let frac = u128::from(ticks % unit);
                    (ticks / unit, frac * NANOS / u128::from(unit))
                }
                // Finer than 10^-19 s: under a second whatever u64 holds.
                None => (
                    0,
                    10u128
                        .checked_pow(u32::from(n))
                        .map_or(0, |unit| u128::from(ticks) * NANOS / unit),
                ),
            },
            Resolution::Binary(n) if n < 64 => {
                let frac = u128::from(ticks & ((1u64 << n) - 1));
                (ticks >> n, (frac * NANOS) >> n)
            }
            Resolution::Binary(n) => (0, (u128::from(ticks) * NANOS) >> n.min(127)),
        };
        (secs, u32::try_from(nanos).unwrap_or(0))
    }
}

/// A pcapng interface description, or the pcap file's one interface.
#[derive(Debug, Clone)]
struct Interface {
    link_type: u16,
    snaplen: u32,
    name: Option<Box<str>>,
    resolution: Resolution,
    /// `if_tsoffset`: seconds added to every timestamp.
    offset_secs: i64,
}

impl Interface {
    /// Return the time of a packet stamped `ticks` on this interface: its
    /// resolution and offset applied (`None` when the time is out of
    /// range). The general path and the fast paths both read it here.
    #[inline]
    fn timestamp(&self, ticks: u64) -> Option<Timestamp> {
        let (mut secs, nanos) = self.resolution.split(ticks);
        if self.offset_secs != 0 {
            let shifted = i128::from(secs) + i128::from(self.offset_secs);
            secs = u64::try_from(shifted).ok()?;
        }
        Timestamp::from_nanos(secs, nanos)
    }
}

/// Which file format the reader reads, with its byte order.
#[derive(Debug, Clone, Copy)]
enum Layout {
    Pcap { big_endian: bool },
    Pcapng { big_endian: bool },
}

/// A packet found at the position, not yet consumed: its data lies at
/// `data` in the bytes after the position, the record ends at `len`.
#[derive(Debug)]
struct Packet {
    interface: usize,
    timestamp: Option<Timestamp>,
    /// The interface's link type; `None` for a record that is no packet.
    link_type: Option<u16>,
    data: core::ops::Range<usize>,
    len: usize,
}

/// What one pcapng block was.
#[derive(Debug)]
enum Block {
    /// The file ended before it.
    End,
    /// A packet.
    Packet(Packet),
    /// A block that holds no packet.
    Other,
}

/// A reader of pcap and pcapng captures of SocketCAN frames
/// (docs/formats.md#pcap): see the [module documentation](self) for what it
/// reads and how.
///
/// It reads through a window that grows only with the records it holds
/// (at most [`MAX_RECORD_LEN`] each), so wrapping the input in a
/// [`std::io::BufReader`] is not needed.
#[derive(Debug)]
pub struct PcapReader<R: Read> {
    input: Input<R>,
    layout: Layout,
    /// The current section's interfaces (pcap: the file's one).
    interfaces: Vec<Interface>,
    /// Bytes the interfaces hold, bounded by [`MAX_RECORD_LEN`].
    interface_bytes: usize,
    number: u64,
    /// The packets that hold no CAN frame, by kind.
    other: OtherCounts,
    done: bool,
    /// The fast paths are tried first: a pcap file of link type 227 (its
    /// records read by [`next_classic`](Self::next_classic) and
    /// [`next_fd`](Self::next_fd)), or a pcapng file (its enhanced packet
    /// blocks on interfaces of link type 227 read by
    /// [`next_block_classic`](Self::next_block_classic) and
    /// [`next_block_fd`](Self::next_block_fd)). Cleared, every record takes
    /// the general path (the property tests compare the two).
    fast: bool,
    /// The current section has an interface of link type 227, whose
    /// blocks the pcapng fast paths read: without one they are not tried.
    socketcan: bool,
    /// Ethernet packets shorter than a header they announce, skipped.
    skipped: u64,
    /// A pcap file's times are in nanoseconds (its interface's resolution,
    /// kept apart for [`record_time`](Self::record_time)).
    nanos: bool,
}

impl<R: Read> PcapReader<R> {
    /// Read the file header (pcap) or the first section header block
    /// (pcapng) from `reader`, telling the format from the magic number.
    ///
    /// # Errors
    ///
    /// A [`LogError`] of kind [`LogErrorKind::Io`] when reading fails, and
    /// of kind [`LogErrorKind::Damaged`] with an
    /// [`FormatError::Binary`] when the magic number is neither pcap's nor
    /// pcapng's ([`BinaryError::BadMagic`], format [`LogFormat::Pcap`]),
    /// the header is cut off, its version unknown or its snapshot length
    /// above [`MAX_RECORD_LEN`].
    pub fn new(reader: R) -> Result<Self, LogError> {
        let mut input = Input::new(reader);
        let available = input.fill(4)?;
        let first = input
            .bytes()
            .first_chunk::<4>()
            .map(|b| u32::from_le_bytes(*b));
        let Some(first) = first else {
            return Err(fail(
                LogFormat::Pcap,
                0,
                BinaryError::Truncated {
                    needed: 4,
                    found: available as u64,
                },
            ));
        };
        let mut reader = PcapReader {
            input,
            layout: Layout::Pcap { big_endian: false },
            interfaces: Vec::new(),
            interface_bytes: 0,
            number: 0,
            other: OtherCounts::default(),
            done: false,
            fast: false,
            socketcan: false,
            skipped: 0,
            nanos: false,
        };
        match first {
            magic::MICROS | magic::MICROS_SWAPPED | magic::NANOS | magic::NANOS_SWAPPED => {
                reader.read_pcap_header(first)?;
            }
            magic::SECTION_HEADER => {
                reader.layout = Layout::Pcapng { big_endian: false };
                reader.fast = true;
                // The first block is this section header: read it now so
                // that a bad one fails here.
                reader.next_pcapng_block()?;
            }
            found => return Err(fail(LogFormat::Pcap, 0, BinaryError::BadMagic { found })),
        }
        Ok(reader)
    }

    /// Read the 24-byte pcap file header whose magic number is `first`.
    fn read_pcap_header(&mut self, first: u32) -> Result<(), LogError> {
        let big_endian = matches!(first, magic::MICROS_SWAPPED | magic::NANOS_SWAPPED);
        let nanos = matches!(first, magic::NANOS | magic::NANOS_SWAPPED);
        self.layout = Layout::Pcap { big_endian };
        let available = self.input.fill(PCAP_HEADER_LEN)?;
        let header = self
            .input
            .bytes()
            .first_chunk::<PCAP_HEADER_LEN>()
            .copied()
            .ok_or_else(|| self.truncated(PCAP_HEADER_LEN, available))?;
        let major = u16_at(&header, 4, big_endian);
        let minor = u16_at(&header, 6, big_endian);
        if major != 2 {
            return Err(self.fail(0, BinaryError::UnsupportedVersion { major, minor }));
        }
        let snaplen = u32_at(&header, 16, big_endian);
        if snaplen as usize > MAX_RECORD_LEN {
            return Err(self.fail(0, too_large(snaplen.into())));
        }
        // The low 16 bits are the link type; the high ones say FCS length.
        let link_type = (u32_at(&header, 20, big_endian) & 0xFFFF) as u16;
        self.interfaces.push(Interface {
            link_type,
            snaplen,
            name: None,
            resolution: Resolution::Decimal(if nanos { 9 } else { 6 }),
            offset_secs: 0,
        });
        self.fast = link_type == LINKTYPE_CAN_SOCKETCAN;
        self.nanos = nanos;
        self.input.consume(PCAP_HEADER_LEN);
        Ok(())
    }

    /// Return the next packet, `None` at the end of the file.
    fn next_packet(&mut self) -> Result<Option<Packet>, LogError> {
        match self.layout {
            Layout::Pcap { big_endian } => self.next_pcap_record(big_endian),
            Layout::Pcapng { .. } => loop {
                match self.next_pcapng_block()? {
                    Block::End => return Ok(None),
                    Block::Packet(packet) => return Ok(Some(packet)),
                    Block::Other => {}
                }
            },
        }
    }

    /// Read one pcap record.
    fn next_pcap_record(&mut self, big_endian: bool) -> Result<Option<Packet>, LogError> {
        let available = self.input.fill(PCAP_RECORD_LEN)?;
        if available == 0 {
            return Ok(None);
        }
        let header = self
            .input
            .bytes()
            .first_chunk::<PCAP_RECORD_LEN>()
            .copied()
            .ok_or_else(|| self.truncated(PCAP_RECORD_LEN, available))?;
        let captured = u32_at(&header, 8, big_endian);
        if captured as usize > MAX_RECORD_LEN {
            return Err(self.fail(0, too_large(captured.into())));
        }
        let total = PCAP_RECORD_LEN + captured as usize;
        let available = self.input.fill(total)?;
        if available < total {
            return Err(self.truncated(total, available));
        }
        let interface = self.interfaces.first();
        let timestamp = self.record_time(&header, big_endian);
        Ok(Some(Packet {
            interface: 0,
            timestamp: Some(timestamp),
            link_type: interface.map(|i| i.link_type),
            data: PCAP_RECORD_LEN..total,
            len: total,
        }))
    }

    /// The time of a pcap record, from its header.
    #[inline]
    fn record_time(&self, header: &[u8; PCAP_RECORD_LEN], big_endian: bool) -> Timestamp {
        let secs = u32_at(header, 0, big_endian);
        let frac = u64::from(u32_at(header, 4, big_endian));
        let nanos = if self.nanos {
            frac
        } else {
            frac.saturating_mul(1_000)
        };
        match u32::try_from(nanos) {
            Ok(nanos) if nanos < 1_000_000_000 => {
                Timestamp::from_duration(Duration::new(secs.into(), nanos))
            }
            // A fraction of a second or more is carried into the seconds.
            _ => Timestamp::from_duration(
                Duration::from_secs(secs.into()).saturating_add(Duration::from_nanos(nanos)),
            ),
        }
    }

    /// The next record of a pcap file of link type 227 when it is whole in
    /// the bytes read ahead (`LEN` bytes, the header's and `MTU`) and its
    /// packet is `MTU` bytes long: its header,
    /// packet and byte order, nothing consumed; `None` for any other record,
    /// which [`next_packet`](Self::next_packet) reads.
    #[inline(always)]
    fn fast_record<const MTU: usize, const LEN: usize>(
        &self,
    ) -> Option<(&[u8; PCAP_RECORD_LEN], &[u8; MTU], bool)> {
        let Layout::Pcap { big_endian } = self.layout else {
            return None;
        };
        if !self.fast {
            return None;
        }
        let record = self.input.bytes().first_chunk::<LEN>()?;
        let (header, packet) = record.split_first_chunk::<PCAP_RECORD_LEN>()?;
        if u32_at(header, 8, big_endian) as usize != MTU {
            return None;
        }
        Some((header, packet.first_chunk::<MTU>()?, big_endian))
    }

    /// A classic data frame in a packet of [`socketcan::CAN_MTU`] bytes, a
    /// capture's usual record ([`fast_record`](Self::fast_record)): its
    /// frame and time, the record consumed; `None` (nothing consumed) for
    /// any other. The frame and time are those the general path makes of
    /// the record.
    #[inline(always)]
    fn next_classic(&mut self) -> Option<(CanFrame, Timestamp)> {
        let (header, packet, big_endian) =
            self.fast_record::<{ socketcan::CAN_MTU }, { PCAP_RECORD_LEN + socketcan::CAN_MTU }>()?;
        let frame = socketcan::classic_data(packet)?;
        let timestamp = self.record_time(header, big_endian);
        self.input.consume(PCAP_RECORD_LEN + socketcan::CAN_MTU);
        Some((frame, timestamp))
    }

    /// [`next_classic`](Self::next_classic) for a CAN FD frame in a packet
    /// of [`socketcan::CANFD_MTU`] bytes, a CAN FD capture's usual record;
    /// tried after it. Its own return in `next_event`: one result for both
    /// kinds would have the classic frame made in a temporary and copied.
    #[inline(always)]
    fn next_fd(&mut self) -> Option<(CanFrame, Timestamp)> {
        let (header, packet, big_endian) = self
            .fast_record::<{ socketcan::CANFD_MTU }, { PCAP_RECORD_LEN + socketcan::CANFD_MTU }>(
            )?;
        let frame = socketcan::fd_data(packet)?;
        let timestamp = self.record_time(header, big_endian);
        self.input.consume(PCAP_RECORD_LEN + socketcan::CANFD_MTU);
        Some((frame, timestamp))
    }

    /// The record of a frame read by a fast path, numbered next: on the
    /// pcapng section's interface `interface`, named by
    /// [`iface_of`](Self::iface_of) as the general path names it, or of a
    /// pcap file (`None`), which names no interface.
    #[inline(always)]
    fn fast_event(
        &mut self,
        frame: CanFrame,
        timestamp: Timestamp,
        interface: Option<usize>,
    ) -> LogRecord<'_> {
        self.number = self.number.saturating_add(1);
        LogRecord {
            position: Position::Record(self.number),
            event: LogEvent::Frame(LogFrame {
                frame,
                timestamp: Some(timestamp),
                iface: interface.and_then(|id| self.iface_of(id, None)),
                direction: None,
            }),
        }
    }

    /// The bus a packet on `interface` names: the pcapng interface's name,
    /// unless it is `any` (`tcpdump -i any`: every bus in one file, told
    /// apart by the cooked header's interface index, `ifindex`); `None`
    /// when neither says.
    #[inline(always)]
    fn iface_of(&self, interface: usize, ifindex: Option<u16>) -> Option<Iface<'_>> {
        let name = self
            .interfaces
            .get(interface)
            .and_then(|i| i.name.as_deref());
        match (name, ifindex) {
            (Some(name), _) if name != ANY => Some(Iface::Name(name)),
            (_, Some(index)) => Some(Iface::Channel(index)),
            (name, None) => name.map(Iface::Name),
        }
    }

    /// The next block of a little-endian pcapng section when it is an
    /// enhanced packet block whole in the bytes read ahead (`LEN` bytes:
    /// its 28-byte head, a packet of `MTU` bytes, no options, its trailing
    /// length) on an interface of the section of link type 227: the packet,
    /// the interface's index and the packet's time, nothing consumed;
    /// `None` for any other block (and for every block of a big-endian
    /// section, or an EPB whose time is out of range), which
    /// [`next_pcapng_block`](Self::next_pcapng_block) reads.
    ///
    /// The checks are those the general path makes of such a block, so
    /// that this reads a block only when the general path would make a
    /// packet of it: block type and length (one word), the trailing length,
    /// the captured length, the interface; the time is
    /// [`Interface::timestamp`], the general path's.
    #[inline(always)]
    fn fast_block<const MTU: usize, const LEN: usize>(
        &self,
    ) -> Option<(&[u8; MTU], usize, Timestamp)> {
        let Layout::Pcapng { big_endian: false } = self.layout else {
            return None;
        };
        if !self.fast {
            return None;
        }
        let block = self.input.bytes().first_chunk::<LEN>()?;
        let (head, rest) = block.split_first_chunk::<EPB_HEAD_LEN>()?;
        let (packet, trailer) = rest.split_first_chunk::<MTU>()?;
        let word = |at: usize| u32_at(head, at, false);
        // Type and length, as the little-endian u64 they make.
        let kind = (LEN as u64) << 32 | u64::from(block::ENHANCED_PACKET);
        if u64::from(word(0)) | u64::from(word(4)) << 32 != kind
            || u32_at(trailer, 0, false) as usize != LEN
            || word(20) as usize != MTU
        {
            return None;
        }
        let id = word(8) as usize;
        let interface = self.interfaces.get(id)?;
        if interface.link_type != LINKTYPE_CAN_SOCKETCAN {
            return None;
        }
        let ticks = u64::from(word(12)) << 32 | u64::from(word(16));
        Some((packet, id, interface.timestamp(ticks)?))
    }

    /// [`next_classic`](Self::next_classic) for a pcapng file: a classic
    /// data frame in an enhanced packet block of [`socketcan::CAN_MTU`]
    /// bytes ([`fast_block`](Self::fast_block)), its frame, time and
    /// interface, the block consumed; `None` (nothing consumed) for any
    /// other block.
    #[inline(always)]
    fn next_block_classic(&mut self) -> Option<(CanFrame, Timestamp, usize)> {
        let (packet, id, timestamp) =
            self.fast_block::<{ socketcan::CAN_MTU }, { EPB_LEN + socketcan::CAN_MTU }>()?;
        let frame = socketcan::classic_data(packet)?;
        self.input.consume(EPB_LEN + socketcan::CAN_MTU);
        Some((frame, timestamp, id))
    }

    /// [`next_block_classic`](Self::next_block_classic) for a CAN FD frame
    /// in an enhanced packet block of [`socketcan::CANFD_MTU`] bytes.
    #[inline(always)]
    fn next_block_fd(&mut self) -> Option<(CanFrame, Timestamp, usize)> {
        let (packet, id, timestamp) =
            self.fast_block::<{ socketcan::CANFD_MTU }, { EPB_LEN + socketcan::CANFD_MTU }>()?;
        let frame = socketcan::fd_data(packet)?;
        self.input.consume(EPB_LEN + socketcan::CANFD_MTU);
        Some((frame, timestamp, id))
    }

    /// Read one pcapng block.
    fn next_pcapng_block(&mut self) -> Result<Block, LogError> {
        let available = self.input.fill(8)?;
        if available == 0 {
            return Ok(Block::End);
        }
        let head = self
            .input
            .bytes()
            .first_chunk::<8>()
            .copied()
            .ok_or_else(|| self.truncated(8, available))?;
        let block_type_le = u32_at(&head, 0, false);
        if block_type_le == magic::SECTION_HEADER {
            let available = self.input.fill(12)?;
            let order = self
                .input
                .bytes()
                .get(8..12)
                .map(|b| u32_at(b, 0, false))
                .ok_or_else(|| self.truncated(12, available))?;
            let big_endian = match order {
                magic::BYTE_ORDER => false,
                o if o == magic::BYTE_ORDER.swap_bytes() => true,
                found => return Err(self.fail(0, BinaryError::BadMagic { found })),
            };
            self.layout = Layout::Pcapng { big_endian };
        }
        let Layout::Pcapng { big_endian } = self.layout else {
            return Ok(Block::End);
        };
        let block_type = u32_at(&head, 0, big_endian);
        let len = u32_at(&head, 4, big_endian);
        if len as usize > MAX_RECORD_LEN {
            return Err(self.fail(0, too_large(len.into())));
        }
        let total = len as usize;
        if total < BLOCK_OVERHEAD || total % 4 != 0 {
            return Err(self.fail(0, BinaryError::BadLength { length: len.into() }));
        }
        let available = self.input.fill(total)?;
        if available < total {
            return Err(self.truncated(total, available));
        }
        let bytes = self.input.bytes().get(..total).unwrap_or_default();
        let trailer = u32_at(bytes, total - 4, big_endian);
        if trailer != len {
            return Err(self.fail(0, BinaryError::BadLength { length: len.into() }));
        }
        let body = bytes.get(8..total - 4).unwrap_or_default();
        let block = match block_type {
            magic::SECTION_HEADER => {
                let body = body.to_vec();
                self.read_section_header(&body)?;
                Block::Other
            }
            block::INTERFACE => {
                let body = body.to_vec();
                self.read_interface(&body)?;
                Block::Other
            }
            // Packets are consumed once decoded.
            block::ENHANCED_PACKET | block::PACKET => {
                return Ok(Block::Packet(
                    self.read_packet_block(block_type, body, big_endian, total)?,
                ));
            }
            block::SIMPLE_PACKET => {
                return Ok(Block::Packet(
                    self.read_simple_packet(body, big_endian, total)?,
                ));
            }
            block::SYSTEMD_JOURNAL => {
                return Ok(Block::Packet(Packet {
                    interface: 0,
                    timestamp: None,
                    link_type: None,
                    data: 0..0,
                    len: total,
                }));
            }
            _ => Block::Other,
        };
        self.input.consume(total);
        Ok(block)
    }

    /// A section header block's body: byte order, version, section length,
    /// options. Starts a new list of interfaces.
    fn read_section_header(&mut self, body: &[u8]) -> Result<(), LogError> {
        let Layout::Pcapng { big_endian } = self.layout else {
            return Ok(());
        };
        if body.len() < 16 {
            return Err(self.fail(0, bad_length(body.len() + BLOCK_OVERHEAD)));
        }
        let major = u16_at(body, 4, big_endian);
        let minor = u16_at(body, 6, big_endian);
        if major != 1 {
            return Err(self.fail(0, BinaryError::UnsupportedVersion { major, minor }));
        }
        self.interfaces.clear();
        self.interface_bytes = 0;
        self.socketcan = false;
        Ok(())
    }

    /// An interface description block's body: link type, reserved,
    /// snaplen, options (`if_name`, `if_tsresol`, `if_tsoffset`).
    fn read_interface(&mut self, body: &[u8]) -> Result<(), LogError> {
        let Layout::Pcapng { big_endian } = self.layout else {
            return Ok(());
        };
        if body.len() < 8 {
            return Err(self.fail(0, bad_length(body.len() + BLOCK_OVERHEAD)));
        }
        let mut interface = Interface {
            link_type: u16_at(body, 0, big_endian),
            snaplen: u32_at(body, 4, big_endian),
            name: None,
            resolution: Resolution::Decimal(6),
            offset_secs: 0,
        };
        let mut options = body.get(8..).unwrap_or_default();
        let mut at = 16;
        while let Some(head) = options.first_chunk::<4>() {
            let code = u16_at(head, 0, big_endian);
            let len = usize::from(u16_at(head, 2, big_endian));
            let padded = (len + 3) & !3;
            let Some(value) = options.get(4..4 + len) else {
                return Err(self.fail(at, bad_length(len)));
            };
            match code {
                0 => break,
                2 => {
                    // Some writers end the name with NULs.
                    let end = value.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
                    let name = value.get(..end).unwrap_or_default();
                    interface.name = Some(String::from_utf8_lossy(name).into());
                }
                9 => {
                    if let Some(&b) = value.first() {
                        interface.resolution = Resolution::from_byte(b);
                    }
                }
                14 => {
                    if let Some(v) = value.first_chunk::<8>() {
                        let raw = u64::from_le_bytes(*v);
                        let raw = if big_endian { raw.swap_bytes() } else { raw };
                        interface.offset_secs = raw as i64;
                    }
                }
                _ => {}
            }
            options = options.get(4 + padded..).unwrap_or_default();
            at += 4 + padded;
        }
        let cost = INTERFACE_COST + interface.name.as_ref().map_or(0, |n| n.len());
        let total = self.interface_bytes.saturating_add(cost);
        if total > MAX_RECORD_LEN {
            return Err(self.fail(0, too_large(total as u64)));
        }
        self.interface_bytes = total;
        self.socketcan |= interface.link_type == LINKTYPE_CAN_SOCKETCAN;
        self.interfaces.push(interface);
        Ok(())
    }

    /// An enhanced (or obsolete) packet block's body: interface, time,
    /// captured and original length, data, options.
    fn read_packet_block(
        &self,
        block_type: u32,
        body: &[u8],
        big_endian: bool,
        len: usize,
    ) -> Result<Packet, LogError> {
        const FIXED: usize = 20;
        if body.len() < FIXED {
            return Err(self.fail(0, bad_length(body.len() + BLOCK_OVERHEAD)));
        }
        let id = if block_type == block::PACKET {
            u32::from(u16_at(body, 0, big_endian))
        } else {
            u32_at(body, 0, big_endian)
        };
        let ticks =
            (u64::from(u32_at(body, 4, big_endian)) << 32) | u64::from(u32_at(body, 8, big_endian));
        let captured = u32_at(body, 12, big_endian);
        let end = FIXED.saturating_add(captured as usize);
        if end > body.len() {
            return Err(self.fail(0, bad_length(captured as usize)));
        }
        let interface = self.interface(id)?;
        let timestamp = interface
            .timestamp(ticks)
            .ok_or_else(|| self.fail(0, BinaryError::TimestampOutOfRange))?;
        Ok(Packet {
            interface: id as usize,
            timestamp: Some(timestamp),
            link_type: Some(interface.link_type),
            data: 8 + FIXED..8 + end,
            len,
        })
    }

    /// A simple packet block's body: original length, data; interface 0,
    /// no time. The data captured is the original length cut to the
    /// interface's snaplen.
    fn read_simple_packet(
        &self,
        body: &[u8],
        big_endian: bool,
        len: usize,
    ) -> Result<Packet, LogError> {
        let Some(head) = body.first_chunk::<4>() else {
            return Err(self.fail(0, bad_length(body.len() + BLOCK_OVERHEAD)));
        };
        let original = u32_at(head, 0, big_endian) as usize;
        let interface = self.interface(0)?;
        let mut captured = original;
        if interface.snaplen != 0 {
            captured = captured.min(interface.snaplen as usize);
        }
        let end = 4usize.saturating_add(captured);
        if end > body.len() {
            return Err(self.fail(0, bad_length(original)));
        }
        Ok(Packet {
            interface: 0,
            timestamp: None,
            link_type: Some(interface.link_type),
            data: 8 + 4..8 + end,
            len,
        })
    }

    /// Return the interface `id` of the current section.
    fn interface(&self, id: u32) -> Result<&Interface, LogError> {
        self.interfaces.get(id as usize).ok_or_else(|| {
            self.fail(
                0,
                BinaryError::UnknownInterface {
                    id,
                    count: u32::try_from(self.interfaces.len()).unwrap_or(u32::MAX),
                },
            )
        })
    }

    /// Whether the bytes read ahead hold the whole next record (pcap) or
    /// block (pcapng), so that handing it on needs no read.
    fn whole_record_buffered(&self) -> bool {
        let bytes = self.input.bytes();
        let (len_at, overhead, big_endian) = match self.layout {
            Layout::Pcap { big_endian } => (8, PCAP_RECORD_LEN, big_endian),
            Layout::Pcapng { big_endian } => (4, 0, big_endian),
        };
        bytes.len() >= len_at + 4
            && bytes.len() >= overhead + u32_at(bytes, len_at, big_endian) as usize
    }

    /// The reader's format.
    fn log_format(&self) -> LogFormat {
        match self.layout {
            Layout::Pcap { .. } => LogFormat::Pcap,
            Layout::Pcapng { .. } => LogFormat::Pcapng,
        }
    }

    /// An error at `at` bytes from the position.
    fn fail(&self, at: usize, reason: BinaryError) -> LogError {
        fail(
            self.log_format(),
            self.input.offset().saturating_add(at as u64),
            reason,
        )
    }

    /// The file ends inside a structure of `needed` bytes at the position.
    fn truncated(&self, needed: usize, found: usize) -> LogError {
        self.fail(
            0,
            BinaryError::Truncated {
                needed: needed as u64,
                found: found as u64,
            },
        )
    }
}

crate::logs::record::records_of!(PcapReader<R: Read>);

impl<R: Read> ReadLog for PcapReader<R> {
    fn format(&self) -> LogFormat {
        self.log_format()
    }

    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        let (found, packet) = loop {
            if self.done {
                return None;
            }
            match self.layout {
                Layout::Pcap { .. } => {
                    if let Some((frame, timestamp)) = self.next_classic() {
                        return Some(Ok(self.fast_event(frame, timestamp, None)));
                    }
                    if let Some((frame, timestamp)) = self.next_fd() {
                        return Some(Ok(self.fast_event(frame, timestamp, None)));
                    }
                }
                Layout::Pcapng { .. } if self.socketcan => {
                    if let Some((frame, timestamp, id)) = self.next_block_classic() {
                        return Some(Ok(self.fast_event(frame, timestamp, Some(id))));
                    }
                    if let Some((frame, timestamp, id)) = self.next_block_fd() {
                        return Some(Ok(self.fast_event(frame, timestamp, Some(id))));
                    }
                }
                Layout::Pcapng { .. } => {}
            }
            let packet = match self.next_packet() {
                Ok(Some(packet)) => packet,
                Ok(None) => {
                    self.done = true;
                    return None;
                }
                Err(e) => {
                    self.done = true;
                    return Some(Err(e.or_at(Position::Record(self.number + 1))));
                }
            };
            self.number = self.number.saturating_add(1);
            let data = self
                .input
                .bytes()
                .get(packet.data.clone())
                .unwrap_or_default();
            // An Ethernet port's packet: EtherCAT, or counted by kind.
            let ethernet = match packet.link_type {
                Some(LINKTYPE_ETHERNET) => Some(ethernet::split(data)),
                Some(link_type @ (LINKTYPE_LINUX_SLL | LINKTYPE_LINUX_SLL2)) => {
                    match cooked::split(link_type, data) {
                        Ok(Cooked::Ethernet { at, protocol }) => {
                            ethernet::cooked(link_type, data, protocol, at).map(Ok)
                        }
                        _ => None,
                    }
                }
                _ => None,
            };
            match ethernet {
                None => {}
                Some(Ok(Ethernet::Other(kind))) => {
                    self.input.consume(packet.len);
                    self.other.add(kind.into());
                    continue;
                }
                Some(Ok(found @ Ethernet::Ethercat { .. })) => {
                    // Made an event after the loop, which can lend the
                    // bytes.
                    self.input.consume(packet.len);
                    break (found, packet);
                }
                Some(Err(reason)) => {
                    // A damaged packet whose size is known: skipped, the
                    // capture read on.
                    self.input.consume(packet.len);
                    let error = LogError::new(
                        Some(Position::Record(self.number)),
                        LogErrorKind::Malformed(FormatError::Binary {
                            format: self.log_format(),
                            offset: self.input.offset() - (packet.len - packet.data.start) as u64,
                            reason,
                        }),
                    );
                    self.skipped = self.skipped.saturating_add(1);
                    return Some(Err(error));
                }
            }
            // The SocketCAN frame's offset in the packet, and how it is
            // laid out; or the kind of packet that holds none.
            let framed = match packet.link_type {
                Some(LINKTYPE_CAN_SOCKETCAN) => Ok((0, FrameLayout::LinkType227, None)),
                Some(link_type @ (LINKTYPE_LINUX_SLL | LINKTYPE_LINUX_SLL2)) => {
                    match cooked::split(link_type, data) {
                        Ok(Cooked::Can {
                            at,
                            layout,
                            ifindex,
                        }) => Ok((at, layout, ifindex)),
                        Ok(Cooked::Other(kind)) => Err(Ok(kind)),
                        Ok(Cooked::Ethernet { protocol, .. }) => Err(Ok(NotCan::CookedProtocol {
                            link_type,
                            protocol,
                        })),
                        Err(reason) => Err(Err((0, reason))),
                    }
                }
                Some(link_type) => Err(Ok(NotCan::LinkType(link_type))),
                None => Err(Ok(NotCan::SystemdJournal)),
            };
            let decoded = framed.and_then(|(at, layout, ifindex)| {
                match socketcan::decode(data.get(at..).unwrap_or_default(), layout) {
                    Ok(Payload::Frame(frame)) => Ok((frame, ifindex)),
                    Ok(Payload::NotCan) => Err(Ok(NotCan::CanXl)),
                    Err(reason) => Err(Err((at, reason))),
                }
            });
            let (frame, ifindex) = match decoded {
                Ok(decoded) => decoded,
                Err(Ok(kind)) => {
                    self.input.consume(packet.len);
                    self.other.add(kind.into());
                    continue;
                }
                Err(Err((at, reason))) => {
                    self.done = true;
                    let error = self.fail(packet.data.start + at, reason);
                    return Some(Err(error.or_at(Position::Record(self.number))));
                }
            };
            self.input.consume(packet.len);
            let iface = self.iface_of(
                packet.interface,
                ifindex.and_then(|i| u16::try_from(i).ok()),
            );
            return Some(Ok(LogRecord {
                position: Position::Record(self.number),
                event: LogEvent::Frame(LogFrame {
                    frame,
                    timestamp: packet.timestamp,
                    iface,
                    direction: None,
                }),
            }));
        };
        let Ethernet::Ethercat { at, ifindex, .. } = found else {
            return None;
        };
        let payload = self
            .input
            .behind(packet.len - packet.data.start - at, packet.data.len() - at);
        let link = found.link(payload)?;
        let iface = self.iface_of(
            packet.interface,
            ifindex.and_then(|i| u16::try_from(i).ok()),
        );
        Some(Ok(LogRecord {
            position: Position::Record(self.number),
            event: LogEvent::Ethercat(EthercatPacket {
                timestamp: packet.timestamp,
                iface,
                link,
            }),
        }))
    }

    fn other_records(&self) -> u64 {
        self.other.total()
    }

    fn other_kinds(&self) -> &[OtherRecords] {
        self.other.by_kind()
    }

    fn skipped(&self) -> u64 {
        // Every other error of a capture ends it.
        self.skipped
    }

    fn bytes_read(&self) -> u64 {
        self.input.taken()
    }

    #[inline]
    fn drained(&self) -> bool {
        self.input.drained() && !self.whole_record_buffered()
    }
}

/// A [`FormatError::Binary`] as the [`LogError`] that ends the reading.
fn fail(format: LogFormat, offset: u64, reason: BinaryError) -> LogError {
    LogError::new(
        None,
        LogErrorKind::Damaged(FormatError::Binary {
            format,
            offset,
            reason,
        }),
    )
}

/// A length above [`MAX_RECORD_LEN`].
fn too_large(length: u64) -> BinaryError {
    BinaryError::TooLarge {
        length,
        limit: MAX_RECORD_LEN as u64,
    }
}

/// A length that does not fit its structure.
fn bad_length(length: usize) -> BinaryError {
    BinaryError::BadLength {
        length: length as u64,
    }
}
