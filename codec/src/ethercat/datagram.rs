//! One EtherCAT datagram: [`Datagram`] (a view) and [`DatagramRepr`]
//! (what it says, and writes back).

use core::fmt;

use crate::error::check_len;
use crate::{LenError, What};

/// A datagram's bytes besides its data: the 10-byte header (command,
/// index, address, length and flags, IRQ) and the 2-byte working counter.
pub const DATAGRAM_OVERHEAD: usize = DATAGRAM_HEADER_LEN + WKC_LEN;

/// Command, index, address (4), length and flags (2), IRQ (2).
const DATAGRAM_HEADER_LEN: usize = 10;
/// The working counter.
const WKC_LEN: usize = 2;
/// The length field's 11 bits.
const LENGTH_MASK: u16 = 0x07FF;
/// Bit 14 of the length word: the frame has circulated.
const CIRCULATING: u16 = 0x4000;
/// Bit 15 of the length word: another datagram follows.
const MORE_FOLLOWS: u16 = 0x8000;

/// A datagram's command (ETG.1000.4 table 14; Wireshark's `ecat.cmd`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Command {
    /// 0: no operation.
    Nop,
    /// 1: auto-increment physical read.
    Aprd,
    /// 2: auto-increment physical write.
    Apwr,
    /// 3: auto-increment physical read-write.
    Aprw,
    /// 4: configured-address physical read.
    Fprd,
    /// 5: configured-address physical write.
    Fpwr,
    /// 6: configured-address physical read-write.
    Fprw,
    /// 7: broadcast read.
    Brd,
    /// 8: broadcast write.
    Bwr,
    /// 9: broadcast read-write.
    Brw,
    /// 10: logical read.
    Lrd,
    /// 11: logical write.
    Lwr,
    /// 12: logical read-write.
    Lrw,
    /// 13: auto-increment physical read, multiple write.
    Armw,
    /// 14: configured-address physical read, multiple write.
    Frmw,
    /// Another value, reserved.
    Reserved(u8),
}

/// How a command addresses its slaves, and so what its 4-byte address
/// holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Addressing {
    /// By position: ADP is the negative position, counted up by every
    /// slave the datagram passes; ADO the register (APxx, ARMW).
    Position,
    /// By configured station address (or alias): ADP the station, ADO
    /// the register (FPxx, FRMW).
    Station,
    /// Every slave: ADP counted up by each, ADO the register (Bxx).
    Broadcast,
    /// A 32-bit logical address in the process image (Lxx).
    Logical,
    /// No slave: a NOP, or a reserved command.
    None,
}

impl Command {
    /// Read a command byte.
    #[must_use]
    pub const fn from_byte(byte: u8) -> Self {
        match byte {
            0 => Command::Nop,
            1 => Command::Aprd,
            2 => Command::Apwr,
            3 => Command::Aprw,
            4 => Command::Fprd,
            5 => Command::Fpwr,
            6 => Command::Fprw,
            7 => Command::Brd,
            8 => Command::Bwr,
            9 => Command::Brw,
            10 => Command::Lrd,
            11 => Command::Lwr,
            12 => Command::Lrw,
            13 => Command::Armw,
            14 => Command::Frmw,
            other => Command::Reserved(other),
        }
    }

    /// Return the command byte.
    #[must_use]
    pub const fn byte(self) -> u8 {
        match self {
            Command::Nop => 0,
            Command::Aprd => 1,
            Command::Apwr => 2,
            Command::Aprw => 3,
            Command::Fprd => 4,
            Command::Fpwr => 5,
            Command::Fprw => 6,
            Command::Brd => 7,
            Command::Bwr => 8,
            Command::Brw => 9,
            Command::Lrd => 10,
            Command::Lwr => 11,
            Command::Lrw => 12,
            Command::Armw => 13,
            Command::Frmw => 14,
            Command::Reserved(byte) => byte,
        }
    }

    /// Return the command's name as ETG.1000.4 and Wireshark write it
    /// (`APRD`, `LRW`, …; `reserved` for another value).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Command::Nop => "NOP",
            Command::Aprd => "APRD",
            Command::Apwr => "APWR",
            Command::Aprw => "APRW",
            Command::Fprd => "FPRD",
            Command::Fpwr => "FPWR",
            Command::Fprw => "FPRW",
            Command::Brd => "BRD",
            Command::Bwr => "BWR",
            Command::Brw => "BRW",
            Command::Lrd => "LRD",
            Command::Lwr => "LWR",
            Command::Lrw => "LRW",
            Command::Armw => "ARMW",
            Command::Frmw => "FRMW",
            Command::Reserved(_) => "reserved",
        }
    }

    /// Return how the command addresses its slaves.
    #[must_use]
    pub const fn addressing(self) -> Addressing {
        match self {
            Command::Aprd | Command::Apwr | Command::Aprw | Command::Armw => Addressing::Position,
            Command::Fprd | Command::Fpwr | Command::Fprw | Command::Frmw => Addressing::Station,
            Command::Brd | Command::Bwr | Command::Brw => Addressing::Broadcast,
            Command::Lrd | Command::Lwr | Command::Lrw => Addressing::Logical,
            Command::Nop | Command::Reserved(_) => Addressing::None,
        }
    }

    /// Return whether the command reads from the slaves (its returned copy
    /// carries their data): every read, read-write and read-multiple-write.
    #[must_use]
    pub const fn reads(self) -> bool {
        matches!(
            self,
            Command::Aprd
                | Command::Aprw
                | Command::Fprd
                | Command::Fprw
                | Command::Brd
                | Command::Brw
                | Command::Lrd
                | Command::Lrw
                | Command::Armw
                | Command::Frmw
        )
    }

    /// Return whether the command writes to the slaves (its sent copy
    /// carries the master's data).
    #[must_use]
    pub const fn writes(self) -> bool {
        matches!(
            self,
            Command::Apwr
                | Command::Aprw
                | Command::Fpwr
                | Command::Fprw
                | Command::Bwr
                | Command::Brw
                | Command::Lwr
                | Command::Lrw
                | Command::Armw
                | Command::Frmw
        )
    }
}

impl fmt::Display for Command {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Command::Reserved(byte) => write!(f, "reserved ({byte})"),
            _ => f.write_str(self.name()),
        }
    }
}

/// One datagram of an EtherCAT frame, a zero-copy view (ETG.1000.4
/// §5.4.1.2; Beckhoff's ESC datasheet, section I, "EtherCAT datagram").
///
/// The view covers the header, the data and the working counter; every
/// accessor reads its field from the bytes, which [`Datagram::parse`]
/// checked are all there.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Datagram<'a> {
    bytes: &'a [u8],
}

impl<'a> Datagram<'a> {
    /// Read the datagram at the start of `bytes`; return it and the bytes
    /// after it.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::EthercatDatagram`]) when `bytes` is shorter
    /// than the header, or than the header, the data its length announces
    /// and the working counter.
    pub fn parse(bytes: &'a [u8]) -> Result<(Self, &'a [u8]), LenError> {
        check_len(What::EthercatDatagram, bytes, DATAGRAM_HEADER_LEN)?;
        let length = usize::from(u16::from_le_bytes([bytes[6], bytes[7]]) & LENGTH_MASK);
        let total = DATAGRAM_OVERHEAD + length;
        check_len(What::EthercatDatagram, bytes, total)?;
        let (datagram, rest) = bytes.split_at(total);
        Ok((Datagram { bytes: datagram }, rest))
    }

    /// Return the datagram's bytes, from its command to its working counter.
    #[inline]
    #[must_use]
    pub const fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// Return the command.
    #[inline]
    #[must_use]
    pub const fn command(&self) -> Command {
        Command::from_byte(self.bytes[0])
    }

    /// Return the index: the master's number for the datagram, which the
    /// slaves leave as it is.
    #[inline]
    #[must_use]
    pub const fn index(&self) -> u8 {
        self.bytes[1]
    }

    /// Return the 4-byte address as one little-endian word: the logical
    /// address of LRD/LWR/LRW, or ADP in the low and ADO in the high half.
    #[inline]
    #[must_use]
    pub const fn address(&self) -> u32 {
        u32::from_le_bytes([self.bytes[2], self.bytes[3], self.bytes[4], self.bytes[5]])
    }

    /// Return ADP, the slave address of position, station and broadcast
    /// commands (the low half of the address).
    #[inline]
    #[must_use]
    pub const fn adp(&self) -> u16 {
        u16::from_le_bytes([self.bytes[2], self.bytes[3]])
    }

    /// Return ADO, the register address (the high half of the address).
    #[inline]
    #[must_use]
    pub const fn ado(&self) -> u16 {
        u16::from_le_bytes([self.bytes[4], self.bytes[5]])
    }

    /// Return the data's length (the length field's 11 bits).
    #[inline]
    #[must_use]
    pub const fn length(&self) -> u16 {
        self.length_word() & LENGTH_MASK
    }

    /// Return whether the circulating flag is set: the frame passed a
    /// slave's port 0 twice, and was not returned to the master.
    #[inline]
    #[must_use]
    pub const fn circulating(&self) -> bool {
        self.length_word() & CIRCULATING != 0
    }

    /// Return whether another datagram follows in the frame.
    #[inline]
    #[must_use]
    pub const fn more_follows(&self) -> bool {
        self.length_word() & MORE_FOLLOWS != 0
    }

    /// Return the IRQ field: the slaves' event requests, ORed.
    #[inline]
    #[must_use]
    pub const fn irq(&self) -> u16 {
        u16::from_le_bytes([self.bytes[8], self.bytes[9]])
    }

    /// Return the data.
    #[inline]
    #[must_use]
    pub fn data(&self) -> &'a [u8] {
        &self.bytes[DATAGRAM_HEADER_LEN..self.bytes.len() - WKC_LEN]
    }

    /// Return the working counter: how many slaves took part, counted up
    /// by 1 per read and 2 per write (3 for both) on the way.
    #[inline]
    #[must_use]
    pub const fn working_counter(&self) -> u16 {
        let n = self.bytes.len();
        u16::from_le_bytes([self.bytes[n - 2], self.bytes[n - 1]])
    }

    /// Return the length word: length, reserved bits and flags.
    #[inline]
    const fn length_word(&self) -> u16 {
        u16::from_le_bytes([self.bytes[6], self.bytes[7]])
    }
}

/// What a datagram says, field by field, with a borrowed data: parsed
/// from a [`Datagram`] and written back by [`DatagramRepr::emit`] (the
/// smoltcp `Repr` pattern; the synthetic captures of the tests are built
/// with it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DatagramRepr<'a> {
    /// The command.
    pub command: Command,
    /// The index.
    pub index: u8,
    /// The address word (ADP low, ADO high, or the logical address).
    pub address: u32,
    /// The circulating flag.
    pub circulating: bool,
    /// The more-follows flag.
    pub more_follows: bool,
    /// The IRQ field.
    pub irq: u16,
    /// The data (at most 2047 bytes: the length field's 11 bits).
    pub data: &'a [u8],
    /// The working counter.
    pub working_counter: u16,
}

impl<'a> DatagramRepr<'a> {
    /// Return what `datagram` says. The reserved bits of its length word
    /// are not kept.
    #[must_use]
    pub fn parse(datagram: &Datagram<'a>) -> Self {
        DatagramRepr {
            command: datagram.command(),
            index: datagram.index(),
            address: datagram.address(),
            circulating: datagram.circulating(),
            more_follows: datagram.more_follows(),
            irq: datagram.irq(),
            data: datagram.data(),
            working_counter: datagram.working_counter(),
        }
    }

    /// Return the bytes the datagram takes: 12 plus its data.
    #[must_use]
    pub const fn buffer_len(&self) -> usize {
        DATAGRAM_OVERHEAD + self.data.len()
    }

    /// Write the datagram at the start of `buffer`; return the bytes
    /// written.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::EthercatDatagram`]) when `buffer` is shorter
    /// than [`DatagramRepr::buffer_len`], or when the data is longer than
    /// the length field can say (2047 bytes: `found` is then the data's
    /// length and `expected` the limit).
    pub fn emit(&self, buffer: &mut [u8]) -> Result<usize, LenError> {
        if self.data.len() > usize::from(LENGTH_MASK) {
            return Err(LenError {
                what: What::EthercatDatagram,
                expected: usize::from(LENGTH_MASK),
                found: self.data.len(),
            });
        }
        let total = self.buffer_len();
        check_len(What::EthercatDatagram, buffer, total)?;
        // The length fits in 11 bits: checked above.
        let mut length_word = self.data.len() as u16;
        if self.circulating {
            length_word |= CIRCULATING;
        }
        if self.more_follows {
            length_word |= MORE_FOLLOWS;
        }
        buffer[0] = self.command.byte();
        buffer[1] = self.index;
        buffer[2..6].copy_from_slice(&self.address.to_le_bytes());
        buffer[6..8].copy_from_slice(&length_word.to_le_bytes());
        buffer[8..10].copy_from_slice(&self.irq.to_le_bytes());
        buffer[DATAGRAM_HEADER_LEN..total - WKC_LEN].copy_from_slice(self.data);
        buffer[total - WKC_LEN..total].copy_from_slice(&self.working_counter.to_le_bytes());
        Ok(total)
    }
}
