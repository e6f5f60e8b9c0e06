//! candump text logs: one CAN frame per line (can-utils `candump`; SPEC §5).
//!
//! [`parse_line`] reads one line in either of the two formats that
//! can-utils' `candump` writes and returns a [`CandumpFrame`] that borrows
//! the interface name from the line. [`lines`] walks a whole buffer.
//! [`CandumpFrame::write_log`] and [`CandumpFrame::write_screen`] write a
//! frame back; everything they write parses back to the same frame.
//! Nothing here allocates, and no input makes it panic.
//!
//! | form (SPEC §5) | example |
//! |---|---|
//! | log file, `candump -l` | `(1700000000.000500) can0 081#1081110000000000` |
//! | … with direction, `-x` | `(1700000000.000500) can0 081#1081110000000000 R` |
//! | remote request (RTR) | `(1700000000.000500) can0 701#R`, with length `701#R1` |
//! | extended identifier | `(1700000000.000500) can0 18FF1234#0102` |
//! | CAN FD: flags nibble, then up to 64 bytes | `(1700000000.000500) can0 123##1AABB` |
//! | screen output, `candump can0` | `  can0  081   [8]  10 81 11 00 00 00 00 00` |
//! | screen RTR | `  can0  705   [1]  remote request` |
//! | screen CAN FD (two-digit length) | `  can0  123  [12]  00 11 22 33 44 55 66 77 88 99 AA BB` |
//! | screen with `-ta` and `-x` | ` (1700000000.000500)  can0  RX B -  123  [02]  AA BB` |
//!
//! The formats are those written by can-utils' `lib.c`
//! (`snprintf_canframe`, `snprintf_long_canframe`) and `candump.c`.
//!
//! # Decisions (where SPEC §5 and can-utils leave room)
//!
//! - A blank line (nothing but white space) and a comment line (first
//!   non-blank byte `#`) are `Ok(None)`: there is no frame in them.
//!   Anything else that is not a frame is an error, e.g. the
//!   `DROPCOUNT: …` lines candump writes when the socket dropped frames, so
//!   that nothing is skipped silently.
//! - Trailing `\r` and `\n` (CRLF logs) and trailing spaces or tabs are
//!   ignored. Fields are separated by one or more spaces or tabs: candump
//!   right-aligns interface names to the longest one it listens on and
//!   indents standard identifiers once it has seen an extended one.
//! - The timestamp is optional in both formats (candump writes it with `-l`
//!   and, for the screen, with `-t a|d|z`). It is `(seconds.fraction)` with 1
//!   to 20 digits of seconds (anything that fits a `u64`) and 1 to 6 digits
//!   of fraction, read exactly as integers; `.5` is 500 000 µs. The
//!   `-t A` date form is not accepted.
//! - An identifier has exactly 3 hex digits (standard, at most `0x7FF`) or 8
//!   (extended, at most `0x1FFFFFFF`), in either case. Eight digits always
//!   mean an extended frame, even for a small value, as in can-utils. Error
//!   frames (`CAN_ERR_FLAG` `0x20000000` in an 8-digit identifier) are
//!   rejected as out of range.
//! - Data: classic frames 0 to 8 bytes, CAN FD frames 0 to 64 bytes (any
//!   length, as can-utils' own parser accepts). `R`/`r` marks a remote
//!   request, optionally followed by its length digit `0`–`8`.
//! - Not accepted (an error with its column): `.` separators between data
//!   bytes, the `_len8_dlc` suffix, CAN XL frames, and the screen's ASCII
//!   (`-a`), binary (`-b`) and raw-DLC (`{B}`) views.
//! - The screen format shows CAN FD flags only as the BRS/ESI letters of the
//!   `-x` column (`RX B E`), which needs a direction. A screen line without
//!   that column gives an FD frame with empty flags, and
//!   [`CandumpFrame::write_screen`] cannot show other flags or flags without
//!   a direction: such frames survive only the log format.
//!
//! # Speed
//!
//! Log-format lines are read in wide words (SWAR): 16 characters at a time
//! are loaded as a `u128`, checked for hex digits with bit arithmetic and
//! packed into 8 bytes; the timestamp's digits are converted the same way,
//! and [`lines`] finds line ends 16 bytes at a time. `benches/decode.rs`
//! measures it against a byte-at-a-time parser.
//!
//! ```
//! use motionwire::candump::{self, CanId, Direction};
//!
//! let frame = candump::parse_line_str("(1700000000.000500) can0 081#1081110000000000 R")?
//!     .expect("a frame");
//! let ts = frame.timestamp().expect("a timestamp");
//! assert_eq!((ts.secs(), ts.micros()), (1_700_000_000, 500));
//! assert_eq!(frame.iface_str(), "can0");
//! assert_eq!(frame.id(), CanId::standard(0x081).unwrap());
//! assert_eq!(frame.data(), &[0x10, 0x81, 0x11, 0, 0, 0, 0, 0]);
//! assert_eq!(frame.direction(), Some(Direction::Rx));
//!
//! // Written in either format, it parses back to itself.
//! let mut text = String::new();
//! frame.write_screen(&mut text).unwrap();
//! assert_eq!(text, " (1700000000.000500)  can0  RX - -  081   [8]  10 81 11 00 00 00 00 00");
//! assert_eq!(candump::parse_line_str(&text)?, Some(frame));
//! assert_eq!(frame.to_string(), "(1700000000.000500) can0 081#1081110000000000 R");
//!
//! // Blank lines hold no frame; a malformed line says where and why.
//! assert_eq!(candump::parse_line(b"\r\n")?, None);
//! let err = candump::parse_line(b"(1700000000.000500) can0 800#00").unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "candump line, column 26: expected an identifier at most 0x7FF, found 0x800"
//! );
//! # Ok::<(), motionwire::Error>(())
//! ```

use core::fmt;
use core::iter::FusedIterator;

use crate::error::{Error, Result};

// ------------------------------------------------------------------ values

/// A CAN identifier: standard (11-bit) or extended (29-bit) (ISO 11898-1;
/// SPEC §5: 3 hex digits in candump text for a standard identifier, 8 for an
/// extended one).
///
/// ```
/// use motionwire::candump::CanId;
///
/// assert_eq!(CanId::standard(0x7FF).map(CanId::raw), Some(0x7FF));
/// assert!(CanId::standard(0x800).is_none());
/// assert!(CanId::extended(0x1FFF_FFFF).unwrap().is_extended());
/// assert!(CanId::extended(0x2000_0000).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CanId {
    raw: u32,
    extended: bool,
}

impl CanId {
    /// The largest standard identifier, `0x7FF` (ISO 11898-1).
    pub const STANDARD_MAX: u32 = 0x7FF;
    /// The largest extended identifier, `0x1FFFFFFF` (ISO 11898-1).
    pub const EXTENDED_MAX: u32 = 0x1FFF_FFFF;

    /// Return the standard identifier `raw`, or `None` above `0x7FF`.
    #[inline]
    pub const fn standard(raw: u32) -> Option<Self> {
        if raw <= Self::STANDARD_MAX {
            Some(CanId {
                raw,
                extended: false,
            })
        } else {
            None
        }
    }

    /// Return the extended identifier `raw`, or `None` above `0x1FFFFFFF`.
    #[inline]
    pub const fn extended(raw: u32) -> Option<Self> {
        if raw <= Self::EXTENDED_MAX {
            Some(CanId {
                raw,
                extended: true,
            })
        } else {
            None
        }
    }

    /// Return the identifier as a number.
    #[inline]
    pub const fn raw(self) -> u32 {
        self.raw
    }

    /// Return whether this is an extended (29-bit) identifier.
    #[inline]
    pub const fn is_extended(self) -> bool {
        self.extended
    }
}

/// The flags nibble of a CAN FD frame, `123##<flags>…` in candump's log
/// format (SPEC §5; bit values from Linux `linux/can.h`, `CANFD_BRS`,
/// `CANFD_ESI`, `CANFD_FDF`). Bits the kernel may add later are kept.
///
/// ```
/// use motionwire::candump::FdFlags;
///
/// let flags = FdFlags::new(0x3).unwrap();
/// assert!(flags.contains(FdFlags::BRS) && flags.contains(FdFlags::ESI));
/// assert!(FdFlags::new(0x10).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct FdFlags(u8);

impl FdFlags {
    /// No flag set.
    pub const EMPTY: FdFlags = FdFlags(0);
    /// Bit rate switch: the data phase ran at the higher bit rate (`CANFD_BRS`, 0x1).
    pub const BRS: FdFlags = FdFlags(0x1);
    /// Error state indicator: the sender was error passive (`CANFD_ESI`, 0x2).
    pub const ESI: FdFlags = FdFlags(0x2);
    /// FD frame marker that newer kernels set on every CAN FD frame (`CANFD_FDF`, 0x4).
    pub const FDF: FdFlags = FdFlags(0x4);

    /// Return the flags `bits`, or `None` when they do not fit a nibble.
    #[inline]
    pub const fn new(bits: u8) -> Option<Self> {
        if bits <= 0xF {
            Some(FdFlags(bits))
        } else {
            None
        }
    }

    /// Return the flags as a nibble, 0..=15.
    #[inline]
    pub const fn bits(self) -> u8 {
        self.0
    }

    /// Return whether every flag of `other` is set here.
    #[inline]
    pub const fn contains(self, other: FdFlags) -> bool {
        self.0 & other.0 == other.0
    }

    /// Return the flags of both.
    #[inline]
    pub const fn union(self, other: FdFlags) -> FdFlags {
        FdFlags(self.0 | other.0)
    }
}

/// Whether the logging host received the frame or sent it itself: the ` R`
/// / ` T` suffix of candump's log format and the `RX`/`TX` column of its
/// screen output, both written with `candump -x` (SPEC §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// Received from the bus (`R`, `RX`).
    Rx,
    /// Sent by the logging host (`T`, `TX`).
    Tx,
}

impl Direction {
    /// Return the letter candump's log format writes, `R` or `T`.
    #[inline]
    pub const fn letter(self) -> char {
        match self {
            Direction::Rx => 'R',
            Direction::Tx => 'T',
        }
    }

    const fn screen(self) -> &'static str {
        match self {
            Direction::Rx => "RX",
            Direction::Tx => "TX",
        }
    }
}

/// When a frame was logged: seconds and microseconds, exactly as the text
/// `(1700000000.000500)` gives them (SPEC §5; SPEC §6.1 `ts`). The clock is
/// the logger's: absolute for `candump -l`, relative for `-t d`/`-t z`.
///
/// ```
/// use motionwire::candump::Timestamp;
///
/// let ts = Timestamp::new(1_700_000_000, 500).unwrap();
/// assert_eq!(ts.as_secs_f64(), 1_700_000_000.0005);
/// assert!(Timestamp::new(0, 1_000_000).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Timestamp {
    secs: u64,
    micros: u32,
}

impl Timestamp {
    /// Return the timestamp `secs` + `micros` µs, or `None` when `micros` is
    /// not below 1 000 000.
    #[inline]
    pub const fn new(secs: u64, micros: u32) -> Option<Self> {
        if micros < 1_000_000 {
            Some(Timestamp { secs, micros })
        } else {
            None
        }
    }

    /// Return the timestamp `secs` + `micros` µs, or an
    /// [`Error::OutOfRange`] naming `micros` when it is not below 1 000 000.
    #[inline]
    pub const fn try_new(secs: u64, micros: u32) -> Result<Self> {
        match Self::new(secs, micros) {
            Some(ts) => Ok(ts),
            None => Err(Error::OutOfRange {
                what: "timestamp microseconds",
                found: micros,
                min: 0,
                max: 999_999,
            }),
        }
    }

    /// Return the whole seconds.
    #[inline]
    pub const fn secs(self) -> u64 {
        self.secs
    }

    /// Return the microseconds within the second, 0..=999 999.
    #[inline]
    pub const fn micros(self) -> u32 {
        self.micros
    }

    /// Return the timestamp in microseconds.
    #[inline]
    pub const fn as_micros(self) -> u128 {
        self.secs as u128 * 1_000_000 + self.micros as u128
    }

    /// Return the timestamp in seconds as a float (SPEC §6.1 `ts`); exact
    /// to the microsecond for any date of this era.
    #[inline]
    pub fn as_secs_f64(self) -> f64 {
        self.secs as f64 + f64::from(self.micros) / 1e6
    }
}

impl fmt::Display for Timestamp {
    /// Write the timestamp as candump does, `1700000000.000500` (ten digits
    /// of seconds at least, six of microseconds).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:010}.{:06}", self.secs, self.micros)
    }
}

/// The payload kind of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Kind {
    /// A classic data frame, 0..=8 bytes.
    Data,
    /// A classic remote request; `len` is the requested length, 0..=8.
    Remote,
    /// A CAN FD frame, 0..=64 bytes.
    Fd(FdFlags),
}

/// The most data bytes of a classic CAN frame (ISO 11898-1).
pub const CLASSIC_MAX_LEN: usize = 8;
/// The most data bytes of a CAN FD frame (ISO 11898-1).
pub const FD_MAX_LEN: usize = 64;

/// One CAN frame read from a candump text line (SPEC §5), borrowing the
/// interface name from the line.
///
/// Every value keeps the invariants of the text formats: the interface name
/// is printable ASCII without spaces that does not start with `(` or `#`; a
/// classic frame has at most 8 data bytes, a CAN FD frame at most 64; a
/// remote request has no data and a requested length 0..=8. So every frame
/// can be written with [`write_log`](Self::write_log) and parses back to
/// itself.
///
/// ```
/// use motionwire::candump::{CandumpFrame, CanId, Direction, FdFlags, Timestamp};
///
/// let frame = CandumpFrame::new_fd("can1", CanId::extended(0x18FF_1234).unwrap(), FdFlags::BRS, &[0xAB; 12])?
///     .with_timestamp(Timestamp::new(12, 345).unwrap())
///     .with_direction(Direction::Tx);
/// assert_eq!(frame.dlc(), 9);
/// assert_eq!(
///     frame.to_string(),
///     "(0000000012.000345) can1 18FF1234##1ABABABABABABABABABABABAB T"
/// );
/// # Ok::<(), motionwire::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CandumpFrame<'a> {
    timestamp: Option<Timestamp>,
    iface: &'a [u8],
    id: CanId,
    kind: Kind,
    direction: Option<Direction>,
    /// Data length, or the requested length of a remote request.
    len: u8,
    /// `data[..len]` is the payload; the rest is zero.
    data: [u8; FD_MAX_LEN],
}

impl<'a> CandumpFrame<'a> {
    /// Return a classic data frame of at most 8 bytes on interface `iface`;
    /// an interface name the text formats cannot carry is an
    /// [`Error::InvalidValue`], more data an [`Error::OutOfRange`].
    pub fn new_data(iface: &'a str, id: CanId, data: &[u8]) -> Result<Self> {
        Self::build(iface, id, Kind::Data, data, CLASSIC_MAX_LEN)
    }

    /// Return a classic remote request (RTR) asking for `dlc` bytes,
    /// 0..=8 (else an [`Error::OutOfRange`]).
    pub fn new_remote(iface: &'a str, id: CanId, dlc: u8) -> Result<Self> {
        if usize::from(dlc) > CLASSIC_MAX_LEN {
            return Err(Error::OutOfRange {
                what: "remote request length",
                found: u32::from(dlc),
                min: 0,
                max: 8,
            });
        }
        let mut frame = Self::build(iface, id, Kind::Remote, &[], 0)?;
        frame.len = dlc;
        Ok(frame)
    }

    /// Return a CAN FD frame of at most 64 bytes with `flags`.
    pub fn new_fd(iface: &'a str, id: CanId, flags: FdFlags, data: &[u8]) -> Result<Self> {
        Self::build(iface, id, Kind::Fd(flags), data, FD_MAX_LEN)
    }

    fn build(iface: &'a str, id: CanId, kind: Kind, payload: &[u8], max: usize) -> Result<Self> {
        check_iface(iface.as_bytes())?;
        if payload.len() > max {
            return Err(Error::OutOfRange {
                what: "candump frame data length",
                found: u32::try_from(payload.len()).unwrap_or(u32::MAX),
                min: 0,
                max: max as u32,
            });
        }
        let mut data = [0; FD_MAX_LEN];
        for (d, s) in data.iter_mut().zip(payload) {
            *d = *s;
        }
        Ok(CandumpFrame {
            timestamp: None,
            iface: iface.as_bytes(),
            id,
            kind,
            direction: None,
            len: payload.len() as u8,
            data,
        })
    }

    /// Return the frame with the timestamp `ts`.
    #[inline]
    pub const fn with_timestamp(mut self, ts: Timestamp) -> Self {
        self.timestamp = Some(ts);
        self
    }

    /// Return the frame with the direction `direction` (candump `-x`).
    #[inline]
    pub const fn with_direction(mut self, direction: Direction) -> Self {
        self.direction = Some(direction);
        self
    }

    /// Return the timestamp, when the line had one.
    #[inline]
    pub const fn timestamp(&self) -> Option<Timestamp> {
        self.timestamp
    }

    /// Return the interface name as bytes of the line (printable ASCII).
    #[inline]
    pub const fn iface(&self) -> &'a [u8] {
        self.iface
    }

    /// Return the interface name, e.g. `can0`.
    #[inline]
    pub fn iface_str(&self) -> &'a str {
        // The name is ASCII by construction (`check_iface`, `scan_iface`).
        core::str::from_utf8(self.iface).unwrap_or_default()
    }

    /// Return the identifier.
    #[inline]
    pub const fn id(&self) -> CanId {
        self.id
    }

    /// Return whether the identifier is extended (29-bit).
    #[inline]
    pub const fn is_extended(&self) -> bool {
        self.id.extended
    }

    /// Return whether this is a remote request (RTR).
    #[inline]
    pub const fn is_rtr(&self) -> bool {
        matches!(self.kind, Kind::Remote)
    }

    /// Return whether this is a CAN FD frame.
    #[inline]
    pub const fn is_fd(&self) -> bool {
        matches!(self.kind, Kind::Fd(_))
    }

    /// Return the CAN FD flags; empty for a classic frame.
    #[inline]
    pub const fn fd_flags(&self) -> FdFlags {
        match self.kind {
            Kind::Fd(flags) => flags,
            _ => FdFlags::EMPTY,
        }
    }

    /// Return the direction, when the line had one (candump `-x`).
    #[inline]
    pub const fn direction(&self) -> Option<Direction> {
        self.direction
    }

    /// Return the data bytes; empty for a remote request.
    #[inline]
    pub fn data(&self) -> &[u8] {
        let len = if self.is_rtr() { 0 } else { self.len };
        self.data.get(..usize::from(len)).unwrap_or_default()
    }

    /// Return the data length code: the number of data bytes of a classic
    /// frame, the requested length of a remote request (`R5`, `[5]`), and
    /// for CAN FD the code 0..=15 of the smallest CAN FD length that holds
    /// the data (ISO 11898-1: 12 bytes → 9, 64 bytes → 15).
    #[inline]
    pub const fn dlc(&self) -> u8 {
        match self.kind {
            Kind::Fd(_) => match self.len {
                0..=8 => self.len,
                9..=12 => 9,
                13..=16 => 10,
                17..=20 => 11,
                21..=24 => 12,
                25..=32 => 13,
                33..=48 => 14,
                _ => 15,
            },
            _ => self.len,
        }
    }

    /// Write the frame in candump's log format (`candump -l`), without a
    /// line end: `(1700000000.000500) can0 081#1081110000000000 R`. Hex
    /// digits are upper case, the seconds have at least ten digits, as
    /// candump writes them.
    pub fn write_log<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        let mut buf = [0u8; 2 * FD_MAX_LEN];
        if let Some(ts) = self.timestamp {
            write!(w, "({ts}) ")?;
        }
        w.write_str(self.iface_str())?;
        w.write_char(' ')?;
        self.write_id(w)?;
        w.write_char('#')?;
        match self.kind {
            Kind::Remote => {
                w.write_char('R')?;
                if self.len > 0 {
                    write!(w, "{}", self.len)?;
                }
            }
            Kind::Fd(flags) => {
                w.write_char('#')?;
                w.write_char(char::from(HEX_UPPER[usize::from(flags.0 & 0xF)]))?;
            }
            Kind::Data => {}
        }
        let mut n = 0;
        for (pair, &byte) in buf.chunks_exact_mut(2).zip(self.data()) {
            pair.copy_from_slice(&hex_pair(byte));
            n += 2;
        }
        w.write_str(ascii_str(buf.get(..n).unwrap_or_default()))?;
        if let Some(direction) = self.direction {
            w.write_char(' ')?;
            w.write_char(direction.letter())?;
        }
        Ok(())
    }

    /// Write the frame as candump prints it on screen (`candump can0`,
    /// with `-t a` when it has a timestamp and `-x` when it has a
    /// direction), without a line end:
    /// `  can0  081   [8]  10 81 11 00 00 00 00 00`.
    ///
    /// The screen shows CAN FD flags only as BRS/ESI after a direction
    /// (`RX B E`); other flags, and flags of a frame without direction, are
    /// not written (see the module's decisions).
    pub fn write_screen<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        let mut buf = [0u8; 3 * FD_MAX_LEN];
        w.write_char(' ')?;
        if let Some(ts) = self.timestamp {
            write!(w, "({ts}) ")?;
        }
        w.write_char(' ')?;
        w.write_str(self.iface_str())?;
        if let Some(direction) = self.direction {
            let flags = self.fd_flags();
            w.write_str("  ")?;
            w.write_str(direction.screen())?;
            w.write_str(if flags.contains(FdFlags::BRS) {
                " B"
            } else {
                " -"
            })?;
            w.write_str(if flags.contains(FdFlags::ESI) {
                " E"
            } else {
                " -"
            })?;
        }
        w.write_str("  ")?;
        self.write_id(w)?;
        match self.kind {
            Kind::Remote => return write!(w, "   [{}]  remote request", self.len),
            Kind::Data => write!(w, "   [{}] ", self.len)?,
            Kind::Fd(_) => write!(w, "  [{:02}] ", self.len)?,
        }
        let mut n = 0;
        for (triple, &byte) in buf.chunks_exact_mut(3).zip(self.data()) {
            let [hi, lo] = hex_pair(byte);
            triple.copy_from_slice(&[b' ', hi, lo]);
            n += 3;
        }
        w.write_str(ascii_str(buf.get(..n).unwrap_or_default()))
    }

    fn write_id<W: fmt::Write + ?Sized>(&self, w: &mut W) -> fmt::Result {
        if self.id.extended {
            write!(w, "{:08X}", self.id.raw)
        } else {
            write!(w, "{:03X}", self.id.raw)
        }
    }
}

impl fmt::Display for CandumpFrame<'_> {
    /// Write the frame in candump's log format, as
    /// [`write_log`](CandumpFrame::write_log).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_log(f)
    }
}

const HEX_UPPER: [u8; 16] = *b"0123456789ABCDEF";

#[inline]
fn hex_pair(byte: u8) -> [u8; 2] {
    [
        HEX_UPPER[usize::from(byte >> 4)],
        HEX_UPPER[usize::from(byte & 0xF)],
    ]
}

/// View bytes that are ASCII by construction as text.
#[inline]
fn ascii_str(bytes: &[u8]) -> &str {
    core::str::from_utf8(bytes).unwrap_or_default()
}

/// Check that an interface name can be carried by both text formats.
fn check_iface(name: &[u8]) -> Result<()> {
    const WHAT: &str = "candump interface name";
    const EXPECTED: &str = "printable ASCII without spaces, not starting with '(' or '#'";
    match name.first() {
        None => Err(Error::Length {
            what: WHAT,
            expected: 1,
            found: 0,
        }),
        Some(&b @ (b'(' | b'#')) => Err(Error::InvalidValue {
            what: WHAT,
            found: u32::from(b),
            expected: EXPECTED,
        }),
        Some(_) => match name.iter().find(|b| !b.is_ascii_graphic()) {
            Some(&b) => Err(Error::InvalidValue {
                what: WHAT,
                found: u32::from(b),
                expected: EXPECTED,
            }),
            None => Ok(()),
        },
    }
}

// ------------------------------------------------------------------ errors

/// What a malformed line held where something else was expected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Found {
    /// This byte.
    Byte(u8),
    /// The line ended.
    EndOfLine,
}

impl fmt::Display for Found {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Found::Byte(b' ') => f.write_str("a space"),
            Found::Byte(b'\t') => f.write_str("a tab"),
            Found::Byte(b) if b.is_ascii_graphic() => write!(f, "'{}'", char::from(b)),
            Found::Byte(b) => write!(f, "byte {b:#04x}"),
            Found::EndOfLine => f.write_str("the end of the line"),
        }
    }
}

/// Why a candump line is malformed (SPEC §5): carried by
/// [`Error::Candump`] with the column where the problem starts. Each
/// reason's message says what was expected and what was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CandumpErrorKind {
    /// `(` opened a timestamp that is not `(seconds.fraction)` with 1 to 20
    /// digits of seconds (fitting a `u64`) and 1 to 6 of fraction.
    BadTimestamp {
        /// What stood where a digit, `.` or `)` was expected.
        found: Found,
    },
    /// Two fields are not separated by white space.
    MissingWhiteSpace {
        /// What stood where white space was expected.
        found: Found,
    },
    /// The line has a frame but no interface name before it.
    MissingInterface,
    /// The interface name holds a byte that is not printable ASCII.
    BadInterface {
        /// The byte.
        found: Found,
    },
    /// No CAN identifier followed by `#` (log format) or white space
    /// (screen format) where one was expected.
    BadIdentifier {
        /// What stood there.
        found: Found,
    },
    /// The identifier has neither 3 nor 8 hex digits.
    IdentifierDigits {
        /// The number of hex digits it has.
        digits: usize,
    },
    /// The identifier is above the largest of its kind (0x7FF for 3
    /// digits, 0x1FFFFFFF for 8).
    IdentifierOutOfRange {
        /// The identifier as read.
        id: u32,
        /// The largest allowed.
        max: u32,
    },
    /// `R` (remote request) is followed by something other than one length
    /// digit 0 to 8.
    BadRemoteLength {
        /// What stood there.
        found: Found,
    },
    /// `##` (CAN FD) is not followed by a flags hex digit.
    BadFdFlags {
        /// What stood there.
        found: Found,
    },
    /// A data byte holds something other than a hex digit.
    BadHexDigit {
        /// What stood there.
        found: Found,
    },
    /// The log-format data has an odd number of hex digits.
    OddHexDigits {
        /// The number of hex digits.
        digits: usize,
    },
    /// The log-format data is longer than its frame allows (8 bytes,
    /// 64 for CAN FD).
    DataTooLong {
        /// The number of hex digits.
        digits: usize,
        /// The most data bytes the frame allows.
        max_bytes: usize,
    },
    /// The screen format's length is not `[0]`…`[8]` or, for CAN FD,
    /// `[00]`…`[64]`.
    BadLength {
        /// What stood there.
        found: Found,
    },
    /// The screen format's data bytes are not as many as its length says.
    LengthMismatch {
        /// The length in brackets.
        declared: usize,
        /// The number of data bytes on the line.
        found: usize,
    },
    /// The screen format's `RX`/`TX` column is not followed by `- -`,
    /// `B -`, `- E` or `B E` (bit rate switch, error state; only `- -` for a
    /// classic frame), or the column precedes a log-format frame.
    BadFdIndicators {
        /// What stood there.
        found: Found,
    },
    /// Something follows the frame where the line should end (or, in the
    /// log format, where a direction `R`/`T` may stand).
    TrailingGarbage {
        /// What stood there.
        found: Found,
    },
}

impl fmt::Display for CandumpErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            CandumpErrorKind::BadTimestamp { found } => write!(
                f,
                "expected a timestamp (seconds.fraction) with 1 to 20 digits before the point \
                 and 1 to 6 after, found {found}"
            ),
            CandumpErrorKind::MissingWhiteSpace { found } => {
                write!(f, "expected white space between fields, found {found}")
            }
            CandumpErrorKind::MissingInterface => f.write_str(
                "expected an interface name before the frame, found the frame at the start",
            ),
            CandumpErrorKind::BadInterface { found } => write!(
                f,
                "expected an interface name of printable ASCII followed by white space, \
                 found {found}"
            ),
            CandumpErrorKind::BadIdentifier { found } => write!(
                f,
                "expected a CAN identifier of 3 or 8 hex digits followed by '#' or white space, \
                 found {found}"
            ),
            CandumpErrorKind::IdentifierDigits { digits } => write!(
                f,
                "expected a CAN identifier of 3 or 8 hex digits, found {digits} digits"
            ),
            CandumpErrorKind::IdentifierOutOfRange { id, max } => {
                write!(f, "expected an identifier at most {max:#X}, found {id:#X}")
            }
            CandumpErrorKind::BadRemoteLength { found } => write!(
                f,
                "expected at most one length digit 0 to 8 after 'R', found {found}"
            ),
            CandumpErrorKind::BadFdFlags { found } => {
                write!(f, "expected a CAN FD flags hex digit after '##', found {found}")
            }
            CandumpErrorKind::BadHexDigit { found } => {
                write!(f, "expected a hex digit, found {found}")
            }
            CandumpErrorKind::OddHexDigits { digits } => write!(
                f,
                "expected an even number of hex digits in the data, found {digits}"
            ),
            CandumpErrorKind::DataTooLong { digits, max_bytes } => write!(
                f,
                "expected at most {max_bytes} data bytes ({} hex digits), found {digits} hex digits",
                2 * max_bytes
            ),
            CandumpErrorKind::BadLength { found } => write!(
                f,
                "expected a data length [0] to [8], or [00] to [64] for CAN FD, found {found}"
            ),
            CandumpErrorKind::LengthMismatch { declared, found } => write!(
                f,
                "expected {declared} data bytes as the length says, found {found}"
            ),
            CandumpErrorKind::BadFdIndicators { found } => write!(
                f,
                "expected '- -', 'B -', '- E' or 'B E' after RX/TX ('- -' for a classic frame) \
                 before a screen-format frame, found {found}"
            ),
            CandumpErrorKind::TrailingGarbage { found } => write!(
                f,
                "expected the end of the line (or a direction R/T in the log format), \
                 found {found}"
            ),
        }
    }
}

/// The error at 0-based `index` of `line`.
#[cold]
#[inline(never)]
fn error(index: usize, reason: CandumpErrorKind) -> Error {
    Error::Candump {
        column: index.saturating_add(1),
        reason,
    }
}

/// What stands at `index` of `line`.
#[inline]
fn found(line: &[u8], index: usize) -> Found {
    match line.get(index) {
        Some(&b) => Found::Byte(b),
        None => Found::EndOfLine,
    }
}

// ------------------------------------------------------------------ SWAR

/// Wide-word arithmetic over the 16 bytes of a `u128` ("SIMD within a
/// register"): each byte is one lane, byte 0 (the first character) the
/// least significant.
mod swar {
    /// `b` in every lane.
    pub const fn splat(b: u8) -> u128 {
        u128::from_le_bytes([b; 16])
    }

    pub const LOW7: u128 = splat(0x7F);
    pub const HIGH: u128 = splat(0x80);
    pub const ONES: u128 = splat(0x01);
    pub const NIBBLES: u128 = splat(0x0F);
    pub const ZERO_CHARS: u128 = splat(b'0');

    /// The high bit of every lane whose byte is at least `c` (for `c` in
    /// 1..=0x80), for lanes below 0x80 only; no carry crosses lanes.
    #[inline(always)]
    const fn ge(low7: u128, c: u8) -> u128 {
        low7.wrapping_add(splat(0x80 - c)) & HIGH
    }

    /// Split 16 characters into their hex values (one per lane, valid where
    /// the character is a hex digit) and a mask with the high bit of every
    /// lane that is not a hex digit.
    #[inline(always)]
    pub const fn hex_lanes(w: u128) -> (u128, u128) {
        let x = w & LOW7;
        let digit = ge(x, b'0') & !ge(x, b'9' + 1);
        let l = x | splat(0x20);
        let letter = ge(l, b'a') & !ge(l, b'f' + 1);
        let bad = !(digit | letter) | w;
        // '0'..'9' → 0..9; 'A'..'F' and 'a'..'f' → 1..6 + 9.
        let values = (w & NIBBLES) + ((w >> 6) & ONES) * 9;
        (values, bad & HIGH)
    }

    pub const ZERO_CHARS64: u64 = ZERO_CHARS as u64;

    /// [`non_digits`] for the 8 lanes of a `u64`.
    #[inline(always)]
    pub const fn non_digits64(d: u64) -> u64 {
        let low7 = LOW7 as u64;
        ((d & low7).wrapping_add(splat(0x76) as u64) | d) & HIGH as u64
    }

    /// A mask with the high bit of every lane that is not a decimal digit;
    /// `d` is the characters XOR `'0'`.
    #[inline(always)]
    pub const fn non_digits(d: u128) -> u128 {
        ((d & LOW7).wrapping_add(splat(0x76)) | d) & HIGH
    }

    /// A mask with the high bit of every lane that is not printable ASCII
    /// (0x21..=0x7E).
    #[inline(always)]
    pub const fn non_graphic(w: u128) -> u128 {
        let x = w & LOW7;
        (!(ge(x, 0x21) & !ge(x, 0x7F)) | w) & HIGH
    }

    /// A mask with the high bit set in the lanes holding `b` (and possibly
    /// in later lanes: the first set lane is exact).
    #[inline(always)]
    pub const fn first_eq(w: u128, b: u8) -> u128 {
        let x = w ^ splat(b);
        x.wrapping_sub(ONES) & !x & HIGH
    }

    /// Pack 16 hex values (one per lane, first the most significant nibble)
    /// into 8 bytes, first byte least significant.
    #[inline(always)]
    pub const fn pack_hex(values: u128) -> u64 {
        // Pairs of lanes → one byte in the low half of each 16-bit lane.
        let x = ((values << 4) | (values >> 8)) & 0x00FF_00FF_00FF_00FF_00FF_00FF_00FF_00FF;
        let x = (x | (x >> 8)) & 0x0000_FFFF_0000_FFFF_0000_FFFF_0000_FFFF;
        let x = (x | (x >> 16)) & 0x0000_0000_FFFF_FFFF_0000_0000_FFFF_FFFF;
        (x | (x >> 32)) as u64
    }

    /// Convert 8 decimal digit values (one per lane, first the most
    /// significant) to their number.
    #[inline(always)]
    pub const fn decimal8(d: u64) -> u64 {
        let x = (d.wrapping_mul(10) + (d >> 8)) & 0x00FF_00FF_00FF_00FF;
        let x = (x.wrapping_mul(100) + (x >> 16)) & 0x0000_FFFF_0000_FFFF;
        (x.wrapping_mul(10_000) + (x >> 32)) & 0xFFFF_FFFF
    }

    /// Convert 16 decimal digit values (one per lane, first the most
    /// significant) to their number.
    #[inline(always)]
    pub const fn decimal16(d: u128) -> u64 {
        decimal8(d as u64) * 100_000_000 + decimal8((d >> 64) as u64)
    }

    /// The number of lanes before the first lane flagged in `mask` (16 when
    /// none is).
    #[inline(always)]
    pub const fn lanes_before(mask: u128) -> usize {
        (mask.trailing_zeros() / 8) as usize
    }
}

/// The 16 bytes of `line` from `at` as a word; bytes past the end read as
/// 0x00, which is no hex digit, decimal digit, printable or white space.
#[inline(always)]
fn load16(line: &[u8], at: usize) -> u128 {
    match line.get(at..).and_then(|s| s.first_chunk::<16>()) {
        Some(chunk) => u128::from_le_bytes(*chunk),
        None => load16_short(line, at),
    }
}

#[cold]
#[inline(never)]
fn load16_short(line: &[u8], at: usize) -> u128 {
    let mut buf = [0u8; 16];
    if let Some(rest) = line.get(at..) {
        for (d, s) in buf.iter_mut().zip(rest) {
            *d = *s;
        }
    }
    u128::from_le_bytes(buf)
}

/// The hex value of one character, or `None`.
#[inline]
const fn hex_value(b: u8) -> Option<u8> {
    match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'A'..=b'F' => Some(b - b'A' + 10),
        b'a'..=b'f' => Some(b - b'a' + 10),
        _ => None,
    }
}

/// Decode the hex digits `line[start..end]` into `out` (whose unused bytes
/// stay zero); `end - start` is at most `2 * out.len()`. An odd count is
/// decoded as if a `0` followed. On a non-hex byte, return its index.
#[inline(always)]
fn decode_hex(
    line: &[u8],
    start: usize,
    end: usize,
    out: &mut [u8; FD_MAX_LEN],
) -> core::result::Result<(), usize> {
    let digits = line.get(start..end).unwrap_or_default();
    let mut chunks = digits.chunks_exact(16);
    let mut outs = out.chunks_exact_mut(8);
    let mut at = start;
    for (chunk, dst) in (&mut chunks).zip(&mut outs) {
        let w = chunk
            .first_chunk::<16>()
            .map_or(0, |c| u128::from_le_bytes(*c));
        let (values, bad) = swar::hex_lanes(w);
        if bad != 0 {
            return Err(at + swar::lanes_before(bad));
        }
        dst.copy_from_slice(&swar::pack_hex(values).to_le_bytes());
        at += 16;
    }
    let rest = chunks.remainder().len();
    if rest == 0 {
        return Ok(());
    }
    // Load the 16 bytes that end where the digits end and shift the digits
    // down to the first lanes; fill the lanes above with '0'.
    let w = match line.get(..end).and_then(|s| s.last_chunk::<16>()) {
        Some(last) => u128::from_le_bytes(*last) >> (8 * (16 - rest)),
        None => load16(line, at) & (u128::MAX >> (8 * (16 - rest))),
    };
    let w = w | (swar::ZERO_CHARS << (8 * rest));
    let (values, bad) = swar::hex_lanes(w);
    if bad != 0 {
        return Err(at + swar::lanes_before(bad));
    }
    if let Some(dst) = outs.next() {
        dst.copy_from_slice(&swar::pack_hex(values).to_le_bytes());
    }
    Ok(())
}

// ------------------------------------------------------------------ parsing

#[inline(always)]
const fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// The index of the first byte at or after `at` that is not a space or tab.
#[inline(always)]
fn skip_space(line: &[u8], mut at: usize) -> usize {
    while let Some(&b) = line.get(at) {
        if !is_space(b) {
            break;
        }
        at += 1;
    }
    at
}

/// Skip one or more spaces or tabs at `at`.
#[inline(always)]
fn need_space(line: &[u8], at: usize) -> Result<usize> {
    match line.get(at) {
        Some(&b) if is_space(b) => Ok(skip_space(line, at + 1)),
        _ => Err(error(
            at,
            CandumpErrorKind::MissingWhiteSpace {
                found: found(line, at),
            },
        )),
    }
}

/// Strip trailing line ends, spaces and tabs.
#[inline(always)]
fn trim_end(mut line: &[u8]) -> &[u8] {
    while let [rest @ .., last] = line {
        if is_space(*last) || *last == b'\r' || *last == b'\n' {
            line = rest;
        } else {
            break;
        }
    }
    line
}

/// Hex values by character; 0xF0 marks a character that is no hex digit.
const HEX_TABLE: [u8; 256] = {
    let mut table = [0xF0u8; 256];
    let mut i = 0;
    while i < 256 {
        if let Some(v) = hex_value(i as u8) {
            table[i] = v;
        }
        i += 1;
    }
    table
};

/// The line shape `candump -l` writes, read in one pass from the start of
/// `buf`: `(` 10 digits `.` 6 digits `) ` interface (1 to 15 bytes) space,
/// identifier `#`, `R[len]`, `#<flags><data>` or `<data>`, optional ` R`/`
/// T`, then `\n`, `\r\n` or the end of `buf`. Return the frame and the
/// number of bytes read (line end included), or `None` for any other shape
/// (which [`parse_general`] then reads, or reports). On every line it
/// accepts it returns what [`parse_general`] returns.
#[inline(always)]
fn parse_canonical_log(buf: &[u8]) -> Option<(CandumpFrame<'_>, usize)> {
    // Timestamp, bytes 0..20, `(SSSSSSSSSS.UUUUUU) `: the 16 digits in two
    // words, seconds 1–8, then seconds 9–10 and microseconds 1–6.
    let head = buf.first_chunk::<20>()?;
    if head[0] != b'(' || head[11] != b'.' || head[18] != b')' || head[19] != b' ' {
        return None;
    }
    let word = |at: usize| head.get(at..).and_then(|s| s.first_chunk::<8>()).copied();
    let high = u64::from_le_bytes(word(1)?) ^ swar::ZERO_CHARS64;
    let low = (u64::from(u16::from_le_bytes([head[9], head[10]]))
        | u64::from_le_bytes(word(12)?) << 16)
        ^ swar::ZERO_CHARS64;
    if swar::non_digits64(high) | swar::non_digits64(low) != 0 {
        return None;
    }
    let all = swar::decimal8(high) * 100_000_000 + swar::decimal8(low);
    let (secs, micros) = (all / 1_000_000, (all % 1_000_000) as u32);

    // Interface: printable ASCII up to a space, not starting with `(`/`#`.
    let iface_start = 20;
    let word = u64::from_le_bytes(*buf.get(iface_start..)?.first_chunk::<8>()?);
    let stop = swar::non_graphic(u128::from(word)) as u64;
    let iface_len = if stop != 0 {
        (stop.trailing_zeros() / 8) as usize
    } else {
        swar::lanes_before(swar::non_graphic(load16(buf, iface_start)))
    };
    let id_start = iface_start + iface_len + 1;
    if iface_len == 0
        || iface_len == 16
        || buf.get(id_start - 1) != Some(&b' ')
        || matches!(buf.get(iface_start), Some(b'(' | b'#'))
    {
        return None;
    }
    let iface = buf.get(iface_start..id_start - 1)?;

    // Identifier: 3 hex digits and `#`, else 8 and `#`.
    let ids = buf.get(id_start..)?;
    let (id, body) = match ids.first_chunk::<4>()? {
        &[a, b, c, b'#'] => {
            let (a, b, c) = (
                HEX_TABLE[usize::from(a)],
                HEX_TABLE[usize::from(b)],
                HEX_TABLE[usize::from(c)],
            );
            if (a | b | c) & 0xF0 != 0 {
                return None;
            }
            let raw = u32::from(a) << 8 | u32::from(b) << 4 | u32::from(c);
            (CanId::standard(raw)?, id_start + 4)
        }
        _ => {
            let chunk = ids.first_chunk::<9>()?;
            if chunk[8] != b'#' {
                return None;
            }
            let w =
                u128::from(u64::from_le_bytes(*chunk.first_chunk::<8>()?)) | swar::ZERO_CHARS << 64;
            let (values, bad) = swar::hex_lanes(w);
            if bad != 0 {
                return None;
            }
            let raw = (swar::pack_hex(values) as u32).swap_bytes();
            (CanId::extended(raw)?, id_start + 9)
        }
    };

    let mut data = [0; FD_MAX_LEN];
    let (kind, len, end) = match buf.get(body) {
        Some(b'R' | b'r') => match buf.get(body + 1) {
            Some(&d @ b'0'..=b'8') => (Kind::Remote, d - b'0', body + 2),
            _ => (Kind::Remote, 0, body + 1),
        },
        Some(b'#') => {
            let flags = HEX_TABLE[usize::from(*buf.get(body + 1)?)];
            if flags & 0xF0 != 0 {
                return None;
            }
            let (len, end) = decode_fd_data(buf, body + 2, &mut data)?;
            (Kind::Fd(FdFlags(flags)), len, end)
        }
        _ => {
            // Classic data: at most 16 hex digits, so one word holds them
            // and the byte after them.
            let (values, bad) = swar::hex_lanes(load16(buf, body));
            let digits = swar::lanes_before(bad);
            if digits % 2 != 0 {
                return None;
            }
            let packed = swar::pack_hex(values) & KEEP_BYTES[(digits / 2) & 15];
            if let Some(first) = data.first_chunk_mut::<8>() {
                *first = packed.to_le_bytes();
            }
            (Kind::Data, (digits / 2) as u8, body + digits)
        }
    };

    // Optional direction, then the line end.
    let mut direction = None;
    let mut used = end;
    if let Some(&[b' ', d @ (b'R' | b'T')]) = buf.get(end..).and_then(|r| r.first_chunk::<2>()) {
        direction = Some(if d == b'R' {
            Direction::Rx
        } else {
            Direction::Tx
        });
        used += 2;
    }
    match buf.get(used) {
        None => {}
        Some(b'\n') => used += 1,
        Some(b'\r') => match buf.get(used + 1) {
            None => used += 1,
            Some(b'\n') => used += 2,
            Some(_) => return None,
        },
        Some(_) => return None,
    }
    let frame = CandumpFrame {
        timestamp: Some(Timestamp { secs, micros }),
        iface,
        id,
        kind,
        direction,
        len,
        data,
    };
    Some((frame, used))
}

/// A mask of the low `n` bytes of a `u64`, for `n` in 0..=8.
const KEEP_BYTES: [u64; 16] = {
    let mut table = [u64::MAX; 16];
    let mut n = 0;
    while n < 8 {
        table[n] = (1u64 << (8 * n)) - 1;
        n += 1;
    }
    table
};

/// Decode the hex digits of CAN FD data from `start` up to the first other
/// byte, 16 at a time, into `data`; return the number of bytes and the index
/// after the digits, or `None` for an odd count (which [`parse_general`]
/// reports). Stops after 64 bytes.
#[inline(never)]
fn decode_fd_data(buf: &[u8], start: usize, data: &mut [u8; FD_MAX_LEN]) -> Option<(u8, usize)> {
    let mut end = start;
    let mut len = 0;
    for dst in data.chunks_exact_mut(8) {
        let (values, bad) = swar::hex_lanes(load16(buf, end));
        let digits = swar::lanes_before(bad);
        if digits % 2 != 0 {
            return None;
        }
        let packed = swar::pack_hex(values) & KEEP_BYTES[(digits / 2) & 15];
        dst.copy_from_slice(&packed.to_le_bytes());
        end += digits;
        len += digits / 2;
        if digits < 16 {
            break;
        }
    }
    Some((len as u8, end))
}

/// Parse one candump line in either format of SPEC §5 (see the module's
/// table and decisions). Return `Ok(None)` for a blank or comment line, the
/// frame for a frame line, and an [`Error::Candump`] with the column and
/// reason for anything else. A trailing line end (`\n`, `\r\n`) is allowed.
#[inline]
pub fn parse_line(line: &[u8]) -> Result<Option<CandumpFrame<'_>>> {
    match parse_canonical_log(line) {
        Some((frame, used)) if used == line.len() => Ok(Some(frame)),
        _ => parse_general(line),
    }
}

/// Parse one line of any shape, byte by byte where the shape varies.
#[inline(never)]
fn parse_general(line: &[u8]) -> Result<Option<CandumpFrame<'_>>> {
    let line = trim_end(line);
    let mut at = 0;
    match line.first() {
        None => return Ok(None),
        Some(&b) if is_space(b) => at = skip_space(line, 0),
        Some(_) => {}
    }
    let timestamp = match line.get(at) {
        Some(b'(') => {
            let (ts, end) = parse_timestamp(line, at)?;
            at = need_space(line, end)?;
            Some(ts)
        }
        Some(b'#') => return Ok(None),
        _ => None,
    };

    let iface_start = at;
    let iface_end = scan_iface(line, at)?;
    let iface = line.get(iface_start..iface_end).unwrap_or_default();
    at = skip_space(line, iface_end);

    let mut indicators = None;
    if let Some([d @ (b'R' | b'T'), b'X', s]) = line.get(at..).and_then(|r| r.first_chunk::<3>()) {
        if is_space(*s) {
            let direction = if *d == b'R' {
                Direction::Rx
            } else {
                Direction::Tx
            };
            let (flags, next) = parse_indicators(line, at + 3)?;
            indicators = Some((direction, flags, at));
            at = next;
        }
    }

    let (id, delimiter) = parse_id(line, at)?;
    let mut frame = CandumpFrame {
        timestamp,
        iface,
        id,
        kind: Kind::Data,
        direction: None,
        len: 0,
        data: [0; FD_MAX_LEN],
    };
    if line.get(delimiter) == Some(&b'#') {
        if let Some((_, _, column)) = indicators {
            return Err(error(
                column,
                CandumpErrorKind::BadFdIndicators {
                    found: found(line, column),
                },
            ));
        }
        parse_log_frame(line, delimiter + 1, &mut frame)?;
    } else {
        parse_screen_frame(line, delimiter, &mut frame)?;
        if let Some((direction, flags, column)) = indicators {
            frame.direction = Some(direction);
            match frame.kind {
                Kind::Fd(_) => frame.kind = Kind::Fd(flags),
                _ if flags != FdFlags::EMPTY => {
                    let at = skip_space(line, column + 3);
                    return Err(error(
                        at,
                        CandumpErrorKind::BadFdIndicators {
                            found: found(line, at),
                        },
                    ));
                }
                _ => {}
            }
        }
    }
    Ok(Some(frame))
}

/// Parse one candump line given as text; see [`parse_line`].
#[inline]
pub fn parse_line_str(line: &str) -> Result<Option<CandumpFrame<'_>>> {
    parse_line(line.as_bytes())
}

/// Read `(seconds.fraction)` starting at the `(` at `open`; return the
/// timestamp and the index after `)`.
#[inline(always)]
fn parse_timestamp(line: &[u8], open: usize) -> Result<(Timestamp, usize)> {
    let start = open + 1;
    let d = load16(line, start) ^ swar::ZERO_CHARS;
    let digits = swar::lanes_before(swar::non_digits(d));
    let secs = if (1..16).contains(&digits) {
        // Right-align the digits: the lanes shifted in are leading zeros.
        swar::decimal16(d << (8 * (16 - digits)))
    } else {
        return parse_timestamp_slow(line, open);
    };
    let point = start + digits;
    if line.get(point) != Some(&b'.') {
        return Err(bad_timestamp(line, point));
    }
    let frac_start = point + 1;
    let d = load16(line, frac_start) ^ swar::ZERO_CHARS;
    let frac_digits = swar::lanes_before(swar::non_digits(d));
    if !(1..=6).contains(&frac_digits) {
        return Err(bad_timestamp(line, frac_start + frac_digits.min(6)));
    }
    let close = frac_start + frac_digits;
    if line.get(close) != Some(&b')') {
        return Err(bad_timestamp(line, close));
    }
    let fraction = swar::decimal8((d << (8 * (8 - frac_digits))) as u64) as u32;
    let micros = fraction * POW10[6 - frac_digits];
    Ok((Timestamp { secs, micros }, close + 1))
}

const POW10: [u32; 7] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000];

#[cold]
fn bad_timestamp(line: &[u8], at: usize) -> Error {
    error(
        at,
        CandumpErrorKind::BadTimestamp {
            found: found(line, at),
        },
    )
}

/// The timestamp byte by byte: for no digits, and for 16 or more digits of
/// seconds (up to `u64::MAX`).
#[cold]
#[inline(never)]
fn parse_timestamp_slow(line: &[u8], open: usize) -> Result<(Timestamp, usize)> {
    let mut at = open + 1;
    let mut secs: u64 = 0;
    while let Some(&b) = line.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        secs = match secs
            .checked_mul(10)
            .and_then(|s| s.checked_add(u64::from(b - b'0')))
        {
            Some(s) => s,
            None => return Err(bad_timestamp(line, at)),
        };
        at += 1;
    }
    if at == open + 1 || line.get(at) != Some(&b'.') {
        return Err(bad_timestamp(line, at));
    }
    at += 1;
    let frac_start = at;
    let mut micros: u32 = 0;
    while let Some(&b) = line.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        if at - frac_start == 6 {
            return Err(bad_timestamp(line, at));
        }
        micros = micros * 10 + u32::from(b - b'0');
        at += 1;
    }
    let frac_digits = at - frac_start;
    if frac_digits == 0 || line.get(at) != Some(&b')') {
        return Err(bad_timestamp(line, at));
    }
    let micros = micros * POW10[6 - frac_digits];
    Ok((Timestamp { secs, micros }, at + 1))
}

/// Scan the interface name from `start`; return the index of the white
/// space after it.
#[inline(always)]
fn scan_iface(line: &[u8], start: usize) -> Result<usize> {
    let mut at = start;
    loop {
        let stop = swar::non_graphic(load16(line, at));
        if stop != 0 {
            at += swar::lanes_before(stop);
            break;
        }
        at += 16;
    }
    match line.get(at) {
        _ if matches!(line.get(start), Some(b'(' | b'#')) => Err(error(
            start,
            CandumpErrorKind::BadInterface {
                found: found(line, start),
            },
        )),
        Some(&b) if is_space(b) && at > start => Ok(at),
        None if at > start => Err(missing_frame(line, start, at)),
        _ => Err(error(
            at,
            CandumpErrorKind::BadInterface {
                found: found(line, at),
            },
        )),
    }
}

/// The error for a line that ends after its interface name: a frame where
/// the interface should be, or nothing after the interface.
#[cold]
#[inline(never)]
fn missing_frame(line: &[u8], start: usize, end: usize) -> Error {
    if line.get(start..end).unwrap_or_default().contains(&b'#') {
        error(start, CandumpErrorKind::MissingInterface)
    } else {
        error(
            end,
            CandumpErrorKind::BadIdentifier {
                found: Found::EndOfLine,
            },
        )
    }
}

/// Parse the `- -`/`B -`/`- E`/`B E` of the screen's `RX`/`TX` column
/// starting at the white space at `at`; return the flags and the index of
/// the identifier.
fn parse_indicators(line: &[u8], at: usize) -> Result<(FdFlags, usize)> {
    let brs_at = skip_space(line, at);
    let brs = match line.get(brs_at) {
        Some(b'-') => FdFlags::EMPTY,
        Some(b'B') => FdFlags::BRS,
        _ => return Err(bad_indicators(line, brs_at)),
    };
    let esi_at = need_space(line, brs_at + 1)?;
    let esi = match line.get(esi_at) {
        Some(b'-') => FdFlags::EMPTY,
        Some(b'E') => FdFlags::ESI,
        _ => return Err(bad_indicators(line, esi_at)),
    };
    Ok((brs.union(esi), need_space(line, esi_at + 1)?))
}

#[cold]
fn bad_indicators(line: &[u8], at: usize) -> Error {
    error(
        at,
        CandumpErrorKind::BadFdIndicators {
            found: found(line, at),
        },
    )
}

/// Parse a 3- or 8-digit identifier at `start`; return it and the index of
/// the `#` or white space after it.
#[inline(always)]
fn parse_id(line: &[u8], start: usize) -> Result<(CanId, usize)> {
    let (values, bad) = swar::hex_lanes(load16(line, start));
    let digits = swar::lanes_before(bad);
    let end = start + digits;
    let delimited = matches!(line.get(end), Some(&(b'#' | b' ' | b'\t')));
    if digits == 3 && delimited {
        let v = values as u32;
        let raw = (v & 0xF) << 8 | (v >> 8 & 0xF) << 4 | (v >> 16 & 0xF);
        match CanId::standard(raw) {
            Some(id) => Ok((id, end)),
            None => Err(out_of_range(start, raw, CanId::STANDARD_MAX)),
        }
    } else if digits == 8 && delimited {
        let raw = (swar::pack_hex(values) as u32).swap_bytes();
        match CanId::extended(raw) {
            Some(id) => Ok((id, end)),
            None => Err(out_of_range(start, raw, CanId::EXTENDED_MAX)),
        }
    } else {
        Err(bad_id(line, start))
    }
}

#[cold]
fn out_of_range(start: usize, id: u32, max: u32) -> Error {
    error(start, CandumpErrorKind::IdentifierOutOfRange { id, max })
}

#[cold]
#[inline(never)]
fn bad_id(line: &[u8], start: usize) -> Error {
    let rest = line.get(start..).unwrap_or_default();
    let digits = rest.iter().take_while(|b| hex_value(**b).is_some()).count();
    let end = start + digits;
    match line.get(end) {
        Some(b'#' | b' ' | b'\t') if digits > 0 => {
            error(start, CandumpErrorKind::IdentifierDigits { digits })
        }
        None if digits > 8 => error(start, CandumpErrorKind::IdentifierDigits { digits }),
        _ => error(
            end,
            CandumpErrorKind::BadIdentifier {
                found: found(line, end),
            },
        ),
    }
}

/// Parse the log format after the identifier's `#` at `start - 1`:
/// `R[len]`, `#<flags><data>` or `<data>`, then an optional direction.
#[inline(always)]
fn parse_log_frame(line: &[u8], start: usize, frame: &mut CandumpFrame<'_>) -> Result<()> {
    let mut end = line.len();
    if let [.., space, d @ (b'R' | b'T')] = line {
        // `start` ≤ the space's index: the byte before `start` is `#`.
        if is_space(*space) {
            frame.direction = Some(if *d == b'R' {
                Direction::Rx
            } else {
                Direction::Tx
            });
            end = trim_end(line.get(..end - 2).unwrap_or_default())
                .len()
                .max(start);
        }
    }
    match line.get(start) {
        Some(b'R' | b'r') => {
            frame.kind = Kind::Remote;
            frame.len = match line.get(start + 1..end).unwrap_or_default() {
                [] => 0,
                [d @ b'0'..=b'8'] => d - b'0',
                [b'0'..=b'8', ..] => return Err(trailing(line, skip_space(line, start + 2))),
                [b' ' | b'\t', ..] => return Err(trailing(line, skip_space(line, start + 1))),
                _ => {
                    return Err(error(
                        start + 1,
                        CandumpErrorKind::BadRemoteLength {
                            found: found(line, start + 1),
                        },
                    ))
                }
            };
            Ok(())
        }
        Some(b'#') => {
            let flags = match line.get(start + 1).and_then(|b| hex_value(*b)) {
                Some(v) => FdFlags(v),
                None => {
                    return Err(error(
                        start + 1,
                        CandumpErrorKind::BadFdFlags {
                            found: found(line, start + 1),
                        },
                    ))
                }
            };
            frame.kind = Kind::Fd(flags);
            frame.len = parse_log_data(line, start + 2, end, FD_MAX_LEN, &mut frame.data)?;
            Ok(())
        }
        _ => {
            frame.len = parse_log_data(line, start, end, CLASSIC_MAX_LEN, &mut frame.data)?;
            Ok(())
        }
    }
}

/// Decode the log format's hex data `line[start..end]`, at most `max`
/// bytes; return the number of bytes.
#[inline(always)]
fn parse_log_data(
    line: &[u8],
    start: usize,
    end: usize,
    max: usize,
    data: &mut [u8; FD_MAX_LEN],
) -> Result<u8> {
    let digits = end.saturating_sub(start);
    if digits > 2 * max {
        return Err(data_too_long(line, start, end, max));
    }
    if let Err(at) = decode_hex(line, start, end, data) {
        return Err(bad_data(line, at));
    }
    if digits % 2 != 0 {
        return Err(error(start, CandumpErrorKind::OddHexDigits { digits }));
    }
    Ok((digits / 2) as u8)
}

#[cold]
#[inline(never)]
fn data_too_long(line: &[u8], start: usize, end: usize, max: usize) -> Error {
    let digits = line.get(start..end).unwrap_or_default();
    match digits.iter().position(|b| hex_value(*b).is_none()) {
        Some(i) => bad_data(line, start + i),
        None => error(
            start,
            CandumpErrorKind::DataTooLong {
                digits: digits.len(),
                max_bytes: max,
            },
        ),
    }
}

/// The error for the non-hex byte at `at` in log-format data: white space
/// means the frame ended and something else follows.
#[cold]
#[inline(never)]
fn bad_data(line: &[u8], at: usize) -> Error {
    match line.get(at) {
        Some(&b) if is_space(b) => trailing(line, skip_space(line, at)),
        _ => error(
            at,
            CandumpErrorKind::BadHexDigit {
                found: found(line, at),
            },
        ),
    }
}

#[cold]
fn trailing(line: &[u8], at: usize) -> Error {
    error(
        at,
        CandumpErrorKind::TrailingGarbage {
            found: found(line, at),
        },
    )
}

/// Parse the screen format after the identifier, from the white space at
/// `at`: `[len]` then `remote request` or the data bytes.
fn parse_screen_frame(line: &[u8], at: usize, frame: &mut CandumpFrame<'_>) -> Result<()> {
    let open = skip_space(line, at);
    let bad_length = |i: usize| {
        error(
            i,
            CandumpErrorKind::BadLength {
                found: found(line, i),
            },
        )
    };
    if line.get(open) != Some(&b'[') {
        return Err(bad_length(open));
    }
    let digit = |i: usize| match line.get(i) {
        Some(b @ b'0'..=b'9') => Some(usize::from(b - b'0')),
        _ => None,
    };
    let (declared, close) = match (digit(open + 1), digit(open + 2)) {
        (Some(len), None) => (len, open + 2),
        (Some(tens), Some(ones)) => (tens * 10 + ones, open + 3),
        (None, _) => return Err(bad_length(open + 1)),
    };
    if line.get(close) != Some(&b']') {
        return Err(bad_length(close));
    }
    let fd = close == open + 3;
    let max = if fd { FD_MAX_LEN } else { CLASSIC_MAX_LEN };
    if declared > max {
        return Err(bad_length(open + 1));
    }
    if fd {
        frame.kind = Kind::Fd(FdFlags::EMPTY);
    }

    let mut at = close + 1;
    if at == line.len() {
        return if declared == 0 {
            Ok(())
        } else {
            Err(mismatch(open, declared, 0))
        };
    }
    at = need_space(line, at)?;
    const REMOTE: &[u8] = b"remote request";
    if !fd && line.get(at..at + REMOTE.len()) == Some(REMOTE) {
        frame.kind = Kind::Remote;
        frame.len = declared as u8;
        let end = at + REMOTE.len();
        return if end == line.len() {
            Ok(())
        } else {
            Err(trailing(line, end))
        };
    }

    let mut count = 0;
    loop {
        let byte = match (
            line.get(at).and_then(|b| hex_value(*b)),
            line.get(at + 1).and_then(|b| hex_value(*b)),
        ) {
            (Some(hi), Some(lo)) => hi << 4 | lo,
            (None, _) => return Err(bad_hex(line, at)),
            (Some(_), None) => return Err(bad_hex(line, at + 1)),
        };
        if let Some(d) = frame.data.get_mut(count) {
            *d = byte;
        }
        count += 1;
        at += 2;
        if at == line.len() {
            break;
        }
        at = need_space(line, at)?;
    }
    if count != declared {
        return Err(mismatch(open, declared, count));
    }
    frame.len = declared as u8;
    Ok(())
}

#[cold]
fn bad_hex(line: &[u8], at: usize) -> Error {
    error(
        at,
        CandumpErrorKind::BadHexDigit {
            found: found(line, at),
        },
    )
}

#[cold]
fn mismatch(open: usize, declared: usize, found: usize) -> Error {
    error(open, CandumpErrorKind::LengthMismatch { declared, found })
}

// ------------------------------------------------------------------ lines

/// Return an iterator over the lines of `buf` that parses each one
/// (SPEC §5, §6.1): it yields the 1-based line number and what
/// [`parse_line`] makes of the line, so that a malformed line is reported
/// with its number and the next line is read on. Lines end at `\n` (a `\r`
/// before it is ignored); a last line without `\n` is read too.
///
/// ```
/// use motionwire::candump;
///
/// let log = b"(1.000000) can0 701#05\r\n\n(1.000100) can0 0X1#00\n  can0  705   [1]  remote request\n";
/// let mut lines = candump::lines(log);
/// let (n, first) = lines.next().unwrap();
/// assert_eq!((n, first?.unwrap().data()), (1, &[0x05][..]));
/// assert_eq!(lines.next().unwrap().0, 2); // blank: Ok(None)
/// let (n, bad) = lines.next().unwrap();
/// assert_eq!(n, 3);
/// assert!(bad.is_err());
/// assert!(lines.next().unwrap().1?.unwrap().is_rtr());
/// assert!(lines.next().is_none());
/// # Ok::<(), motionwire::Error>(())
/// ```
#[inline]
pub fn lines(buf: &[u8]) -> CandumpLines<'_> {
    CandumpLines {
        rest: buf,
        line_number: 0,
    }
}

/// The iterator of [`lines`].
#[derive(Debug, Clone)]
pub struct CandumpLines<'a> {
    rest: &'a [u8],
    line_number: usize,
}

impl<'a> Iterator for CandumpLines<'a> {
    type Item = (usize, Result<Option<CandumpFrame<'a>>>);

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        if self.rest.is_empty() {
            return None;
        }
        self.line_number += 1;
        if let Some((frame, used)) = parse_canonical_log(self.rest) {
            self.rest = self.rest.get(used..).unwrap_or_default();
            return Some((self.line_number, Ok(Some(frame))));
        }
        Some(self.next_general())
    }

    /// Read every line, handing each to `f` straight from the parser (what
    /// `for_each`, `count`, `sum` and most adapters use).
    #[inline]
    fn fold<B, F>(mut self, init: B, mut f: F) -> B
    where
        F: FnMut(B, Self::Item) -> B,
    {
        let mut acc = init;
        while !self.rest.is_empty() {
            self.line_number += 1;
            acc = match parse_canonical_log(self.rest) {
                Some((frame, used)) => {
                    self.rest = self.rest.get(used..).unwrap_or_default();
                    f(acc, (self.line_number, Ok(Some(frame))))
                }
                None => {
                    let item = self.next_general();
                    f(acc, item)
                }
            };
        }
        acc
    }
}

impl<'a> CandumpLines<'a> {
    /// Return the part of the buffer not read yet.
    #[inline]
    pub fn remainder(&self) -> &'a [u8] {
        self.rest
    }

    /// Read the next line when it is not in the canonical log shape.
    #[inline(never)]
    fn next_general(&mut self) -> (usize, Result<Option<CandumpFrame<'a>>>) {
        let (line, rest) = match find_newline(self.rest) {
            Some(i) => (
                self.rest.get(..i).unwrap_or_default(),
                self.rest.get(i + 1..).unwrap_or_default(),
            ),
            None => (self.rest, &[][..]),
        };
        self.rest = rest;
        (self.line_number, parse_general(line))
    }
}

impl FusedIterator for CandumpLines<'_> {}

/// The index of the first `\n` in `buf`, 16 bytes at a time.
#[inline(always)]
fn find_newline(buf: &[u8]) -> Option<usize> {
    let mut chunks = buf.chunks_exact(16);
    let mut at = 0;
    for chunk in &mut chunks {
        let w = chunk
            .first_chunk::<16>()
            .map_or(0, |c| u128::from_le_bytes(*c));
        let hits = swar::first_eq(w, b'\n');
        if hits != 0 {
            return Some(at + swar::lanes_before(hits));
        }
        at += 16;
    }
    chunks
        .remainder()
        .iter()
        .position(|&b| b == b'\n')
        .map(|i| at + i)
}
