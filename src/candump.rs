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

pub use crate::can::{CanId, Direction, FdFlags, Timestamp, CLASSIC_MAX_LEN, FD_MAX_LEN};
use crate::error::{Error, Result};

// ------------------------------------------------------------------ values

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
        self.id.is_extended()
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
                w.write_char(char::from(HEX_UPPER[usize::from(flags.bits() & 0xF)]))?;
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
            w.write_str(direction.name())?;
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
        write!(w, "{}", self.id)
    }
}

impl<'a> From<CandumpFrame<'a>> for crate::can::LogFrame<'a> {
    /// The crate's log record of the frame (SPEC §5): the frame, its time,
    /// interface and direction.
    fn from(frame: CandumpFrame<'a>) -> Self {
        let frame_type = match frame.kind {
            Kind::Data => crate::can::FrameType::Data,
            Kind::Remote => crate::can::FrameType::Remote { dlc: frame.len },
            Kind::Fd(flags) => crate::can::FrameType::Fd(flags),
        };
        let len = if frame.is_rtr() { 0 } else { frame.len };
        let can = crate::can::CanFrame::from_checked_parts(frame.id, frame_type, frame.data, len);
        crate::can::LogFrame {
            frame: can,
            timestamp: frame.timestamp,
            iface: Some(crate::can::Iface::Name(frame.iface_str())),
            direction: frame.direction,
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
                "expected a CAN identifier of 3 or 8 hex digits, found {digits} digit{}",
                if digits == 1 { "" } else { "s" }
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
/// identifier `#`, `R[len]`, `#<flags><data>` or `<data>`, an optional
/// direction (` R`, ` T`), then `\n`, `\r\n` or the end of `buf`. Return the frame and the
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
            (Kind::Fd(FdFlags::new(flags)?), len, end)
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
        timestamp: Some(Timestamp::new(secs, micros).unwrap_or_default()),
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
                    // Point at the first flag letter a classic frame cannot have.
                    let mut at = skip_space(line, column + 3);
                    if line.get(at) == Some(&b'-') {
                        at = skip_space(line, at + 1);
                    }
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
    Ok((Timestamp::new(secs, micros).unwrap_or_default(), close + 1))
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
    Ok((Timestamp::new(secs, micros).unwrap_or_default(), at + 1))
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
                Some(v) => FdFlags::new(v).unwrap_or_default(),
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
        Some(&b) if is_space(b) => {
            // After the data only a direction letter may stand; point past it
            // when it is there.
            let mut next = skip_space(line, at);
            if matches!(line.get(next), Some(b'R' | b'T')) {
                next = skip_space(line, next + 1);
            }
            trailing(line, next)
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The SPEC §5 log example: the AKD EMCY of seed 000 as candump -l logs it.
    const SPEC_LOG: &str = "(1700000000.000500) can0 081#1081110000000000";
    /// The SPEC §5 screen examples.
    const SPEC_SCREEN: &str = "  can0  081   [8]  10 81 11 00 00 00 00 00";
    const SPEC_SCREEN_RTR: &str = "  can0  705   [1]  remote request";

    const EMCY: [u8; 8] = [0x10, 0x81, 0x11, 0, 0, 0, 0, 0];

    fn ts(secs: u64, micros: u32) -> Timestamp {
        Timestamp::new(secs, micros).unwrap()
    }

    fn std_id(raw: u32) -> CanId {
        CanId::standard(raw).unwrap()
    }

    fn ext_id(raw: u32) -> CanId {
        CanId::extended(raw).unwrap()
    }

    /// Parse a line that must hold a frame, checking that the fast path
    /// (when it takes the line) and the general parser agree.
    fn frame(line: &str) -> CandumpFrame<'_> {
        let general = parse_general(line.as_bytes());
        let parsed = parse_line_str(line);
        assert_eq!(parsed, general, "fast and general paths differ on {line:?}");
        parsed
            .unwrap_or_else(|e| panic!("{line:?}: {e}"))
            .unwrap_or_else(|| panic!("{line:?}: no frame"))
    }

    /// Parse a line that must be malformed; return (column, reason).
    fn fail(line: &str) -> (usize, CandumpErrorKind) {
        assert_eq!(parse_general(line.as_bytes()), parse_line_str(line));
        match parse_line_str(line) {
            Err(Error::Candump { column, reason }) => (column, reason),
            other => panic!("{line:?}: expected an error, got {other:?}"),
        }
    }

    fn log(frame: &CandumpFrame<'_>) -> String {
        let mut s = String::new();
        frame.write_log(&mut s).unwrap();
        s
    }

    fn screen(frame: &CandumpFrame<'_>) -> String {
        let mut s = String::new();
        frame.write_screen(&mut s).unwrap();
        s
    }

    // ------------------------------------------------------------ SPEC §5

    #[test]
    fn spec_log_example() {
        let f = frame(SPEC_LOG);
        assert_eq!(f.timestamp(), Some(ts(1_700_000_000, 500)));
        assert_eq!(f.iface(), b"can0");
        assert_eq!(f.iface_str(), "can0");
        assert_eq!(f.id(), std_id(0x081));
        assert!(!f.is_extended() && !f.is_rtr() && !f.is_fd());
        assert_eq!(f.fd_flags(), FdFlags::EMPTY);
        assert_eq!(f.direction(), None);
        assert_eq!(f.data(), &EMCY);
        assert_eq!(f.dlc(), 8);
        let expected = CandumpFrame::new_data("can0", std_id(0x081), &EMCY)
            .unwrap()
            .with_timestamp(ts(1_700_000_000, 500));
        assert_eq!(f, expected);
    }

    #[test]
    fn spec_log_example_with_direction() {
        for (suffix, direction) in [(" R", Direction::Rx), (" T", Direction::Tx)] {
            let line = format!("{SPEC_LOG}{suffix}");
            let f = frame(&line);
            assert_eq!(f.direction(), Some(direction));
            assert_eq!(f.data(), &EMCY);
        }
    }

    #[test]
    fn spec_log_remote_requests() {
        let f = frame("(1700000000.000500) can0 123#R");
        assert!(f.is_rtr());
        assert_eq!((f.dlc(), f.data()), (0, &[][..]));
        let f = frame("(1700000000.000500) can0 123#R5");
        assert!(f.is_rtr());
        assert_eq!((f.dlc(), f.data()), (5, &[][..]));
        assert_eq!(
            f,
            CandumpFrame::new_remote("can0", std_id(0x123), 5)
                .unwrap()
                .with_timestamp(ts(1_700_000_000, 500))
        );
    }

    #[test]
    fn spec_log_extended_identifier() {
        let f = frame("(1700000000.000500) can0 12345678#0102");
        assert_eq!(f.id(), ext_id(0x1234_5678));
        assert!(f.is_extended());
        assert_eq!(f.data(), &[1, 2]);
    }

    #[test]
    fn spec_log_can_fd() {
        let f = frame("(1700000000.000500) can0 123##1AABB");
        assert!(f.is_fd() && !f.is_rtr());
        assert_eq!(f.fd_flags(), FdFlags::BRS);
        assert_eq!(f.data(), &[0xAA, 0xBB]);
    }

    #[test]
    fn spec_screen_examples() {
        let f = frame(SPEC_SCREEN);
        assert_eq!(f.timestamp(), None);
        assert_eq!(f.iface_str(), "can0");
        assert_eq!(f.id(), std_id(0x081));
        assert_eq!(f.data(), &EMCY);
        assert_eq!(
            f,
            CandumpFrame::new_data("can0", std_id(0x081), &EMCY).unwrap()
        );

        let f = frame(SPEC_SCREEN_RTR);
        assert!(f.is_rtr());
        assert_eq!(f.id(), std_id(0x705));
        assert_eq!((f.dlc(), f.data()), (1, &[][..]));
    }

    // ------------------------------------------------------- every form

    #[test]
    fn log_forms() {
        // (line, id, extended, rtr, fd, flags, dlc, data, direction)
        type Row = (
            &'static str,
            u32,
            bool,
            bool,
            bool,
            u8,
            u8,
            &'static [u8],
            Option<Direction>,
        );
        let rows: &[Row] = &[
            (
                "(1.000000) can0 080#",
                0x080,
                false,
                false,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "(1.000000) can0 701#05",
                0x701,
                false,
                false,
                false,
                0,
                1,
                &[5],
                None,
            ),
            (
                "(1.000000) can0 1ab#abcdef",
                0x1AB,
                false,
                false,
                false,
                0,
                3,
                &[0xAB, 0xCD, 0xEF],
                None,
            ),
            (
                "(1.000000) can0 7FF#0102030405060708",
                0x7FF,
                false,
                false,
                false,
                0,
                8,
                &[1, 2, 3, 4, 5, 6, 7, 8],
                None,
            ),
            (
                "(1.000000) can0 000#00",
                0,
                false,
                false,
                false,
                0,
                1,
                &[0],
                None,
            ),
            (
                "(1.000000) can0 701#r",
                0x701,
                false,
                true,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "(1.000000) can0 701#R0",
                0x701,
                false,
                true,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "(1.000000) can0 181#R8",
                0x181,
                false,
                true,
                false,
                0,
                8,
                &[],
                None,
            ),
            (
                "(1.000000) can0 181#R8 T",
                0x181,
                false,
                true,
                false,
                0,
                8,
                &[],
                Some(Direction::Tx),
            ),
            (
                "(1.000000) can0 00000123#11",
                0x123,
                true,
                false,
                false,
                0,
                1,
                &[0x11],
                None,
            ),
            (
                "(1.000000) can0 1FFFFFFF#",
                0x1FFF_FFFF,
                true,
                false,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "(1.000000) can0 1fffffff#R",
                0x1FFF_FFFF,
                true,
                true,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "(1.000000) can0 123##0",
                0x123,
                false,
                false,
                true,
                0,
                0,
                &[],
                None,
            ),
            (
                "(1.000000) can0 123##F00 R",
                0x123,
                false,
                false,
                true,
                0xF,
                1,
                &[0],
                Some(Direction::Rx),
            ),
            (
                "(1.000000) can0 123##5000102030405060708090A0B",
                0x123,
                false,
                false,
                true,
                5,
                9,
                &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11],
                None,
            ),
            (
                "(1.000000) can0 080# R",
                0x080,
                false,
                false,
                false,
                0,
                0,
                &[],
                Some(Direction::Rx),
            ),
            (
                "can0 123#11",
                0x123,
                false,
                false,
                false,
                0,
                1,
                &[0x11],
                None,
            ),
            (
                "(1.000000)\tcan0\t123#11\tT",
                0x123,
                false,
                false,
                false,
                0,
                1,
                &[0x11],
                Some(Direction::Tx),
            ),
            (
                "(1.000000)   vcan10 123#11",
                0x123,
                false,
                false,
                false,
                0,
                1,
                &[0x11],
                None,
            ),
            (
                "   (1.000000) can0 123#11   ",
                0x123,
                false,
                false,
                false,
                0,
                1,
                &[0x11],
                None,
            ),
        ];
        for &(line, id, extended, rtr, fd, flags, dlc, data, direction) in rows {
            let f = frame(line);
            assert_eq!(f.id().raw(), id, "{line}");
            assert_eq!(f.is_extended(), extended, "{line}");
            assert_eq!(f.is_rtr(), rtr, "{line}");
            assert_eq!(f.is_fd(), fd, "{line}");
            assert_eq!(f.fd_flags().bits(), flags, "{line}");
            assert_eq!(f.dlc(), dlc, "{line}");
            assert_eq!(f.data(), data, "{line}");
            assert_eq!(f.direction(), direction, "{line}");
        }
    }

    #[test]
    fn screen_forms() {
        // (line, timestamp, id, extended, rtr, fd, flags, dlc, data, direction)
        type Row = (
            &'static str,
            Option<(u64, u32)>,
            u32,
            bool,
            bool,
            bool,
            u8,
            u8,
            &'static [u8],
            Option<Direction>,
        );
        let rows: &[Row] = &[
            (
                "  can0  12345678   [3]  11 22 33",
                None,
                0x1234_5678,
                true,
                false,
                false,
                0,
                3,
                &[0x11, 0x22, 0x33],
                None,
            ),
            (
                "  can0  12345678   [0]  remote request",
                None,
                0x1234_5678,
                true,
                true,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "  can0       123   [3]  11 22 33",
                None,
                0x123,
                false,
                false,
                false,
                0,
                3,
                &[0x11, 0x22, 0x33],
                None,
            ),
            (
                "  can0  123   [0]",
                None,
                0x123,
                false,
                false,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "  can0  123   [0] ",
                None,
                0x123,
                false,
                false,
                false,
                0,
                0,
                &[],
                None,
            ),
            (
                "  can0  123  [00]",
                None,
                0x123,
                false,
                false,
                true,
                0,
                0,
                &[],
                None,
            ),
            (
                "  can0  123  [02]  aa bb",
                None,
                0x123,
                false,
                false,
                true,
                0,
                2,
                &[0xAA, 0xBB],
                None,
            ),
            (
                "  can0  12345678  [08]  01 02 03 04 05 06 07 08",
                None,
                0x1234_5678,
                true,
                false,
                true,
                0,
                8,
                &[1, 2, 3, 4, 5, 6, 7, 8],
                None,
            ),
            (
                " (1700000000.000500)  can0  081   [8]  10 81 11 00 00 00 00 00",
                Some((1_700_000_000, 500)),
                0x081,
                false,
                false,
                false,
                0,
                8,
                &EMCY,
                None,
            ),
            (
                " (000.000123)  can0  701   [1]  05",
                Some((0, 123)),
                0x701,
                false,
                false,
                false,
                0,
                1,
                &[5],
                None,
            ),
            (
                "  can0  RX - -  081   [8]  10 81 11 00 00 00 00 00",
                None,
                0x081,
                false,
                false,
                false,
                0,
                8,
                &EMCY,
                Some(Direction::Rx),
            ),
            (
                "  can0  TX - -  705   [1]  remote request",
                None,
                0x705,
                false,
                true,
                false,
                0,
                1,
                &[],
                Some(Direction::Tx),
            ),
            (
                "  can0  TX B E  123  [02]  AA BB",
                None,
                0x123,
                false,
                false,
                true,
                3,
                2,
                &[0xAA, 0xBB],
                Some(Direction::Tx),
            ),
            (
                "  can0  RX B -  123  [01]  AA",
                None,
                0x123,
                false,
                false,
                true,
                1,
                1,
                &[0xAA],
                Some(Direction::Rx),
            ),
            (
                "  can0  RX - E  123  [01]  AA\r\n",
                None,
                0x123,
                false,
                false,
                true,
                2,
                1,
                &[0xAA],
                Some(Direction::Rx),
            ),
        ];
        for &(line, timestamp, id, extended, rtr, fd, flags, dlc, data, direction) in rows {
            let f = frame(line);
            assert_eq!(f.timestamp(), timestamp.map(|(s, u)| ts(s, u)), "{line}");
            assert_eq!(f.iface_str(), "can0", "{line}");
            assert_eq!(f.id().raw(), id, "{line}");
            assert_eq!(f.is_extended(), extended, "{line}");
            assert_eq!(f.is_rtr(), rtr, "{line}");
            assert_eq!(f.is_fd(), fd, "{line}");
            assert_eq!(f.fd_flags().bits(), flags, "{line}");
            assert_eq!(f.dlc(), dlc, "{line}");
            assert_eq!(f.data(), data, "{line}");
            assert_eq!(f.direction(), direction, "{line}");
        }
    }

    #[test]
    fn screen_can_fd_64_bytes() {
        let bytes: Vec<u8> = (0..64).collect();
        let hex: Vec<String> = bytes.iter().map(|b| format!("{b:02X}")).collect();
        let line = format!("  can0  123  [64]  {}", hex.join(" "));
        let f = frame(&line);
        assert!(f.is_fd());
        assert_eq!(f.data(), &bytes[..]);
        assert_eq!(f.dlc(), 15);
    }

    #[test]
    fn timestamps() {
        // (text, secs, micros)
        let rows: &[(&str, u64, u32)] = &[
            ("(1700000000.000500)", 1_700_000_000, 500),
            ("(1700000000.999999)", 1_700_000_000, 999_999),
            ("(0000000000.000000)", 0, 0),
            ("(1.5)", 1, 500_000),
            ("(1.05)", 1, 50_000),
            ("(0.000001)", 0, 1),
            ("(000.000123)", 0, 123),
            ("(123456789012345.000001)", 123_456_789_012_345, 1),
            ("(1234567890123456.1)", 1_234_567_890_123_456, 100_000),
            ("(12345678901234567.25)", 12_345_678_901_234_567, 250_000),
            ("(18446744073709551615.999999)", u64::MAX, 999_999),
            ("(00000000000000000000000001.000002)", 1, 2),
        ];
        for &(text, secs, micros) in rows {
            let line = format!("{text} can0 123#");
            assert_eq!(frame(&line).timestamp(), Some(ts(secs, micros)), "{text}");
        }
    }

    #[test]
    fn blank_and_comment_lines_hold_no_frame() {
        for line in [
            "",
            " ",
            "\t",
            "\n",
            "\r\n",
            "  \t \r\n",
            "# a comment",
            "   # indented comment",
            "#",
        ] {
            assert_eq!(parse_line_str(line), Ok(None), "{line:?}");
            assert_eq!(parse_general(line.as_bytes()), Ok(None), "{line:?}");
        }
    }

    #[test]
    fn crlf_and_lf_line_ends() {
        for end in ["", "\n", "\r\n", "\r"] {
            let line = format!("{SPEC_LOG}{end}");
            assert_eq!(frame(&line), frame(SPEC_LOG), "{end:?}");
            let line = format!("{SPEC_LOG} R{end}");
            assert_eq!(frame(&line).direction(), Some(Direction::Rx), "{end:?}");
            let line = format!("{SPEC_SCREEN}{end}");
            assert_eq!(frame(&line), frame(SPEC_SCREEN), "{end:?}");
        }
    }

    // ---------------------------------------------------------- extremes

    #[test]
    fn identifier_extremes() {
        assert_eq!(frame("(1.0) can0 7FF#").id(), std_id(0x7FF));
        assert_eq!(
            fail("(1.0) can0 800#"),
            (
                12,
                CandumpErrorKind::IdentifierOutOfRange {
                    id: 0x800,
                    max: 0x7FF
                }
            )
        );
        assert_eq!(
            fail("  can0  FFF   [0]"),
            (
                9,
                CandumpErrorKind::IdentifierOutOfRange {
                    id: 0xFFF,
                    max: 0x7FF
                }
            )
        );
        assert_eq!(frame("(1.0) can0 1FFFFFFF#").id(), ext_id(0x1FFF_FFFF));
        assert_eq!(
            fail("(1.0) can0 20000000#"),
            (
                12,
                CandumpErrorKind::IdentifierOutOfRange {
                    id: 0x2000_0000,
                    max: 0x1FFF_FFFF
                }
            )
        );
        assert_eq!(
            fail("(1.0) can0 FFFFFFFF#"),
            (
                12,
                CandumpErrorKind::IdentifierOutOfRange {
                    id: 0xFFFF_FFFF,
                    max: 0x1FFF_FFFF
                }
            )
        );
        // Eight digits are always extended, as in can-utils.
        let f = frame("(1.0) can0 000007FF#");
        assert_eq!((f.id().raw(), f.is_extended()), (0x7FF, true));
    }

    #[test]
    fn data_length_extremes() {
        let eight = "(1.0) can0 123#0011223344556677";
        assert_eq!(
            frame(eight).data(),
            &[0, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77]
        );
        assert_eq!(
            fail("(1.0) can0 123#001122334455667788"),
            (
                16,
                CandumpErrorKind::DataTooLong {
                    digits: 18,
                    max_bytes: 8
                }
            )
        );
        let bytes: Vec<u8> = (0..64).map(|i| i * 3).collect();
        let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
        let line = format!("(1.0) can0 123##2{hex}");
        let f = frame(&line);
        assert_eq!(f.data(), &bytes[..]);
        assert_eq!((f.dlc(), f.fd_flags()), (15, FdFlags::ESI));
        assert_eq!(
            fail(&format!("(1.0) can0 123##2{hex}00")),
            (
                18,
                CandumpErrorKind::DataTooLong {
                    digits: 130,
                    max_bytes: 64
                }
            )
        );
        // Every CAN FD length from 0 to 64 and its DLC.
        for len in 0..=64usize {
            let hex = "ab".repeat(len);
            let line = format!("(1.0) can0 123##1{hex}\r\n");
            let f = frame(&line);
            assert_eq!(f.data().len(), len);
            let dlc = match len {
                0..=8 => len,
                9..=12 => 9,
                13..=16 => 10,
                17..=20 => 11,
                21..=24 => 12,
                25..=32 => 13,
                33..=48 => 14,
                _ => 15,
            };
            assert_eq!(usize::from(f.dlc()), dlc, "{len}");
        }
    }

    #[test]
    fn remote_request_lengths() {
        for dlc in 0..=8u8 {
            let line = format!("(1.0) can0 123#R{dlc}");
            let f = frame(&line);
            assert_eq!((f.is_rtr(), f.dlc()), (true, dlc));
            let line = format!("  can0  123   [{dlc}]  remote request");
            let f = frame(&line);
            assert_eq!((f.is_rtr(), f.dlc()), (true, dlc));
        }
        assert_eq!(
            fail("(1.0) can0 123#R9"),
            (
                17,
                CandumpErrorKind::BadRemoteLength {
                    found: Found::Byte(b'9')
                }
            )
        );
    }

    // ------------------------------------------------------------ errors

    #[test]
    fn every_error_with_its_column() {
        use CandumpErrorKind as K;
        use Found::{Byte, EndOfLine};
        let rows: &[(&str, usize, K)] = &[
            (
                "(17x0.000500) can0 123#00",
                4,
                K::BadTimestamp { found: Byte(b'x') },
            ),
            (
                "(1700000000) can0 123#00",
                12,
                K::BadTimestamp { found: Byte(b')') },
            ),
            (
                "(1700000000.0005001) can0 123#00",
                19,
                K::BadTimestamp { found: Byte(b'1') },
            ),
            ("(.5) can0 123#00", 2, K::BadTimestamp { found: Byte(b'.') }),
            ("(1.) can0 123#00", 4, K::BadTimestamp { found: Byte(b')') }),
            ("(1.5 can0 123#00", 5, K::BadTimestamp { found: Byte(b' ') }),
            ("(1.5", 5, K::BadTimestamp { found: EndOfLine }),
            (
                "(18446744073709551616.0) can0 123#",
                21,
                K::BadTimestamp { found: Byte(b'6') },
            ),
            (
                "(1234567890123456789.1234567) can0 123#",
                28,
                K::BadTimestamp { found: Byte(b'7') },
            ),
            (
                "(1.5)can0 123#00",
                6,
                K::MissingWhiteSpace { found: Byte(b'c') },
            ),
            ("(1.5)", 6, K::MissingWhiteSpace { found: EndOfLine }),
            ("(1.5) 123#00", 7, K::MissingInterface),
            (
                "(1.5) ca\x01n0 123#00",
                9,
                K::BadInterface { found: Byte(0x01) },
            ),
            (
                "(1.5) can0\x7f 123#00",
                11,
                K::BadInterface { found: Byte(0x7F) },
            ),
            (
                "(1.5) cän0 123#00",
                8,
                K::BadInterface { found: Byte(0xC3) },
            ),
            ("(1.5) #x 123#00", 7, K::BadInterface { found: Byte(b'#') }),
            ("(1.5) (x 123#00", 7, K::BadInterface { found: Byte(b'(') }),
            ("can0", 5, K::BadIdentifier { found: EndOfLine }),
            ("can0 12x#00", 8, K::BadIdentifier { found: Byte(b'x') }),
            ("can0 123", 9, K::BadIdentifier { found: EndOfLine }),
            ("can0 123X#00", 9, K::BadIdentifier { found: Byte(b'X') }),
            ("can0 #00", 6, K::BadIdentifier { found: Byte(b'#') }),
            (
                "DROPCOUNT: dropped 3 CAN frames on 'can0' socket (total drops 3)",
                13,
                K::BadIdentifier { found: Byte(b'r') },
            ),
            ("can0 1234#00", 6, K::IdentifierDigits { digits: 4 }),
            ("can0 12 [1] 00", 6, K::IdentifierDigits { digits: 2 }),
            ("can0 123456789#00", 6, K::IdentifierDigits { digits: 9 }),
            (
                "can0 12345678901234567890#00",
                6,
                K::IdentifierDigits { digits: 20 },
            ),
            (
                "can0 12345678901234567890",
                6,
                K::IdentifierDigits { digits: 20 },
            ),
            (
                "can0 800#00",
                6,
                K::IdentifierOutOfRange {
                    id: 0x800,
                    max: 0x7FF,
                },
            ),
            (
                "can0 20000080#00",
                6,
                K::IdentifierOutOfRange {
                    id: 0x2000_0080,
                    max: 0x1FFF_FFFF,
                },
            ),
            ("can0 123#R9", 11, K::BadRemoteLength { found: Byte(b'9') }),
            ("can0 123#RX", 11, K::BadRemoteLength { found: Byte(b'X') }),
            ("can0 123##G00", 11, K::BadFdFlags { found: Byte(b'G') }),
            ("can0 123##", 11, K::BadFdFlags { found: EndOfLine }),
            ("can0 123#1G", 11, K::BadHexDigit { found: Byte(b'G') }),
            ("can0 123#1.22", 11, K::BadHexDigit { found: Byte(b'.') }),
            ("can0 123##11G0", 13, K::BadHexDigit { found: Byte(b'G') }),
            (
                "can0 123#11223344_E",
                18,
                K::BadHexDigit { found: Byte(b'_') },
            ),
            (
                "can0 123 [2] 0G 11",
                15,
                K::BadHexDigit { found: Byte(b'G') },
            ),
            (
                "can0 123 [1] remote reques",
                14,
                K::BadHexDigit { found: Byte(b'r') },
            ),
            (
                "can0 123  [01]  remote request",
                17,
                K::BadHexDigit { found: Byte(b'r') },
            ),
            ("can0 123#123", 10, K::OddHexDigits { digits: 3 }),
            ("can0 123##0123", 12, K::OddHexDigits { digits: 3 }),
            (
                "can0 123#001122334455667788",
                10,
                K::DataTooLong {
                    digits: 18,
                    max_bytes: 8,
                },
            ),
            ("can0 123 [9] 00", 11, K::BadLength { found: Byte(b'9') }),
            ("can0 123 [65] 00", 11, K::BadLength { found: Byte(b'6') }),
            ("can0 123 8] 00", 10, K::BadLength { found: Byte(b'8') }),
            ("can0 123 [x] 00", 11, K::BadLength { found: Byte(b'x') }),
            ("can0 123 [8 00", 12, K::BadLength { found: Byte(b' ') }),
            ("can0 123 [123] 00", 13, K::BadLength { found: Byte(b'3') }),
            ("can0 123 {B} 00", 10, K::BadLength { found: Byte(b'{') }),
            ("can0 123 ", 9, K::BadIdentifier { found: EndOfLine }),
            (
                "can0 123 [2] 00",
                10,
                K::LengthMismatch {
                    declared: 2,
                    found: 1,
                },
            ),
            (
                "can0 123 [1] 00 11",
                10,
                K::LengthMismatch {
                    declared: 1,
                    found: 2,
                },
            ),
            (
                "can0 123 [1]",
                10,
                K::LengthMismatch {
                    declared: 1,
                    found: 0,
                },
            ),
            (
                "can0 123 [02] 00",
                10,
                K::LengthMismatch {
                    declared: 2,
                    found: 1,
                },
            ),
            (
                "can0 123 [2] 0011",
                16,
                K::MissingWhiteSpace { found: Byte(b'1') },
            ),
            (
                "can0 123 [1]00",
                13,
                K::MissingWhiteSpace { found: Byte(b'0') },
            ),
            (
                "can0  RX X -  123  [1]  00",
                10,
                K::BadFdIndicators { found: Byte(b'X') },
            ),
            (
                "can0  RX B X  123  [1]  00",
                12,
                K::BadFdIndicators { found: Byte(b'X') },
            ),
            (
                "can0  RX B -  123   [1]  00",
                10,
                K::BadFdIndicators { found: Byte(b'B') },
            ),
            (
                "can0  TX - E  705   [1]  remote request",
                12,
                K::BadFdIndicators { found: Byte(b'E') },
            ),
            (
                "can0  RX - -  123#00",
                7,
                K::BadFdIndicators { found: Byte(b'R') },
            ),
            (
                "can0  RX - -",
                13,
                K::MissingWhiteSpace { found: EndOfLine },
            ),
            (
                "can0 123#11 X",
                13,
                K::TrailingGarbage { found: Byte(b'X') },
            ),
            (
                "can0 123#11 R X",
                15,
                K::TrailingGarbage { found: Byte(b'X') },
            ),
            (
                "can0 123#11 RR",
                14,
                K::TrailingGarbage { found: Byte(b'R') },
            ),
            ("can0 123#R12", 12, K::TrailingGarbage { found: Byte(b'2') }),
            ("can0 123#R X", 12, K::TrailingGarbage { found: Byte(b'X') }),
            (
                "can0 123#R5 X",
                13,
                K::TrailingGarbage { found: Byte(b'X') },
            ),
            (
                "can0 705 [1] remote request please",
                28,
                K::TrailingGarbage { found: Byte(b' ') },
            ),
            (
                "(1.000000) can0 123#11 R\r\nmore",
                25,
                K::TrailingGarbage { found: Byte(b'\r') },
            ),
        ];
        for &(line, column, reason) in rows {
            assert_eq!(fail(line), (column, reason), "{line:?}");
        }
    }

    #[test]
    fn error_messages_say_expected_and_found() {
        let rows: &[(&str, &str)] = &[
            (
                "(17x0.000500) can0 123#00",
                "candump line, column 4: expected a timestamp (seconds.fraction) with 1 to 20 \
                 digits before the point and 1 to 6 after, found 'x'",
            ),
            (
                "(1.5)can0 123#00",
                "candump line, column 6: expected white space between fields, found 'c'",
            ),
            (
                "(1.5) 123#00",
                "candump line, column 7: expected an interface name before the frame, found the \
                 frame at the start",
            ),
            (
                "(1.5) ca\x01n0 123#00",
                "candump line, column 9: expected an interface name of printable ASCII followed \
                 by white space, found byte 0x01",
            ),
            (
                "can0 123",
                "candump line, column 9: expected a CAN identifier of 3 or 8 hex digits followed \
                 by '#' or white space, found the end of the line",
            ),
            (
                "can0 1234#00",
                "candump line, column 6: expected a CAN identifier of 3 or 8 hex digits, found 4 \
                 digits",
            ),
            (
                "can0 800#00",
                "candump line, column 6: expected an identifier at most 0x7FF, found 0x800",
            ),
            (
                "can0 123#R9",
                "candump line, column 11: expected at most one length digit 0 to 8 after 'R', \
                 found '9'",
            ),
            (
                "can0 123##G",
                "candump line, column 11: expected a CAN FD flags hex digit after '##', found 'G'",
            ),
            (
                "can0 123#1G",
                "candump line, column 11: expected a hex digit, found 'G'",
            ),
            (
                "can0 123#123",
                "candump line, column 10: expected an even number of hex digits in the data, \
                 found 3",
            ),
            (
                "can0 123#001122334455667788",
                "candump line, column 10: expected at most 8 data bytes (16 hex digits), found 18 \
                 hex digits",
            ),
            (
                "can0 123 [9] 00",
                "candump line, column 11: expected a data length [0] to [8], or [00] to [64] for \
                 CAN FD, found '9'",
            ),
            (
                "can0 123 [2] 00",
                "candump line, column 10: expected 2 data bytes as the length says, found 1",
            ),
            (
                "can0 RX B - 123 [1] 00",
                "candump line, column 9: expected '- -', 'B -', '- E' or 'B E' after RX/TX ('- -' \
                 for a classic frame) before a screen-format frame, found 'B'",
            ),
            (
                "can0 123#11 X",
                "candump line, column 13: expected the end of the line (or a direction R/T in the \
                 log format), found 'X'",
            ),
            (
                "can0 123#11\tX",
                "candump line, column 13: expected the end of the line (or a direction R/T in the \
                 log format), found 'X'",
            ),
            (
                "can0 123#1 1",
                "candump line, column 12: expected the end of the line (or a direction R/T in the \
                 log format), found '1'",
            ),
        ];
        for &(line, message) in rows {
            assert_eq!(
                parse_line_str(line).unwrap_err().to_string(),
                message,
                "{line:?}"
            );
        }
        assert_eq!(Found::Byte(b' ').to_string(), "a space");
        assert_eq!(Found::Byte(b'\t').to_string(), "a tab");
        assert_eq!(Found::Byte(0xFF).to_string(), "byte 0xff");
    }

    // ----------------------------------------------------------- writers

    #[test]
    fn write_log_exact() {
        let t = ts(1_700_000_000, 500);
        let rows: Vec<(CandumpFrame<'_>, &str)> = vec![
            (frame(SPEC_LOG), SPEC_LOG),
            (
                CandumpFrame::new_data("can0", std_id(0x081), &EMCY)
                    .unwrap()
                    .with_timestamp(t)
                    .with_direction(Direction::Rx),
                "(1700000000.000500) can0 081#1081110000000000 R",
            ),
            (
                CandumpFrame::new_remote("can0", std_id(0x701), 0)
                    .unwrap()
                    .with_timestamp(t),
                "(1700000000.000500) can0 701#R",
            ),
            (
                CandumpFrame::new_remote("can1", std_id(0x181), 8).unwrap(),
                "can1 181#R8",
            ),
            (
                CandumpFrame::new_data("can0", ext_id(0x12AB), &[0xAB, 0xCD]).unwrap(),
                "can0 000012AB#ABCD",
            ),
            (
                CandumpFrame::new_data("can0", std_id(0x80), &[])
                    .unwrap()
                    .with_direction(Direction::Tx),
                "can0 080# T",
            ),
            (
                CandumpFrame::new_fd("can0", std_id(0x123), FdFlags::new(0xA).unwrap(), &[])
                    .unwrap(),
                "can0 123##A",
            ),
            (
                CandumpFrame::new_fd("can0", std_id(0x123), FdFlags::BRS, &[0xAA, 0xBB])
                    .unwrap()
                    .with_timestamp(ts(1, 2)),
                "(0000000001.000002) can0 123##1AABB",
            ),
        ];
        for (f, text) in &rows {
            assert_eq!(log(f), *text);
            assert_eq!(f.to_string(), *text);
            assert_eq!(frame(text), *f);
        }
    }

    #[test]
    fn write_screen_exact() {
        let t = ts(1_700_000_000, 500);
        let twelve: Vec<u8> = (0..12).map(|i| i * 0x11).collect();
        let rows: Vec<(CandumpFrame<'_>, &str)> = vec![
            (frame(SPEC_SCREEN), SPEC_SCREEN),
            (frame(SPEC_SCREEN_RTR), SPEC_SCREEN_RTR),
            (
                CandumpFrame::new_data("can0", std_id(0x081), &EMCY)
                    .unwrap()
                    .with_timestamp(t),
                " (1700000000.000500)  can0  081   [8]  10 81 11 00 00 00 00 00",
            ),
            (
                CandumpFrame::new_data("can0", ext_id(0x1234_5678), &[0x11, 0x22, 0x33]).unwrap(),
                "  can0  12345678   [3]  11 22 33",
            ),
            (
                CandumpFrame::new_remote("can0", ext_id(0x1234_5678), 0).unwrap(),
                "  can0  12345678   [0]  remote request",
            ),
            (
                CandumpFrame::new_data("can0", std_id(0x123), &[]).unwrap(),
                "  can0  123   [0] ",
            ),
            (
                CandumpFrame::new_fd("can0", std_id(0x123), FdFlags::EMPTY, &twelve).unwrap(),
                "  can0  123  [12]  00 11 22 33 44 55 66 77 88 99 AA BB",
            ),
            (
                CandumpFrame::new_fd("can0", std_id(0x123), FdFlags::EMPTY, &[]).unwrap(),
                "  can0  123  [00] ",
            ),
            (
                CandumpFrame::new_fd(
                    "can0",
                    std_id(0x123),
                    FdFlags::BRS.union(FdFlags::ESI),
                    &[0xAA, 0xBB],
                )
                .unwrap()
                .with_direction(Direction::Tx),
                "  can0  TX B E  123  [02]  AA BB",
            ),
            (
                CandumpFrame::new_remote("can0", std_id(0x705), 1)
                    .unwrap()
                    .with_direction(Direction::Rx)
                    .with_timestamp(t),
                " (1700000000.000500)  can0  RX - -  705   [1]  remote request",
            ),
        ];
        for (f, text) in &rows {
            assert_eq!(screen(f), *text);
            assert_eq!(frame(text), *f);
        }
    }

    #[test]
    fn screen_drops_fd_flags_it_cannot_show() {
        // FDF has no place on the screen; BRS shows only in the -x column.
        let f = CandumpFrame::new_fd(
            "can0",
            std_id(0x123),
            FdFlags::FDF.union(FdFlags::BRS),
            &[1],
        )
        .unwrap();
        assert_eq!(screen(&f), "  can0  123  [01]  01");
        assert_eq!(frame(&screen(&f)).fd_flags(), FdFlags::EMPTY);
        let f = f.with_direction(Direction::Rx);
        assert_eq!(frame(&screen(&f)).fd_flags(), FdFlags::BRS);
        // The log format keeps every flag.
        assert_eq!(frame(&log(&f)), f);
    }

    // ------------------------------------------------------ constructors

    #[test]
    fn constructors_check_their_values() {
        assert_eq!(
            CandumpFrame::new_data("can0", std_id(1), &[0; 9]),
            Err(Error::OutOfRange {
                what: "candump frame data length",
                found: 9,
                min: 0,
                max: 8
            })
        );
        assert_eq!(
            CandumpFrame::new_fd("can0", std_id(1), FdFlags::EMPTY, &[0; 65]),
            Err(Error::OutOfRange {
                what: "candump frame data length",
                found: 65,
                min: 0,
                max: 64
            })
        );
        assert_eq!(
            CandumpFrame::new_remote("can0", std_id(1), 9),
            Err(Error::OutOfRange {
                what: "remote request length",
                found: 9,
                min: 0,
                max: 8
            })
        );
        assert_eq!(
            CandumpFrame::new_data("", std_id(1), &[]),
            Err(Error::Length {
                what: "candump interface name",
                expected: 1,
                found: 0
            })
        );
        for (name, byte) in [
            ("can 0", b' '),
            ("#can", b'#'),
            ("(can", b'('),
            ("cän", 0xC3),
            ("can\t", b'\t'),
        ] {
            assert_eq!(
                CandumpFrame::new_data(name, std_id(1), &[]),
                Err(Error::InvalidValue {
                    what: "candump interface name",
                    found: u32::from(byte),
                    expected: "printable ASCII without spaces, not starting with '(' or '#'",
                }),
                "{name:?}"
            );
        }
        assert!(CandumpFrame::new_data("c#(", std_id(1), &[]).is_ok());
    }

    #[test]
    fn values() {
        assert_eq!(CanId::standard(0x7FF).map(CanId::raw), Some(0x7FF));
        assert_eq!(CanId::standard(0x800), None);
        assert_eq!(
            CanId::extended(0x1FFF_FFFF).map(CanId::raw),
            Some(0x1FFF_FFFF)
        );
        assert_eq!(CanId::extended(0x2000_0000), None);
        assert_ne!(CanId::standard(0x123), CanId::extended(0x123));
        assert_eq!(FdFlags::new(0xF).map(FdFlags::bits), Some(0xF));
        assert_eq!(FdFlags::new(0x10), None);
        assert!(FdFlags::new(0x7).unwrap().contains(FdFlags::FDF));
        assert!(!FdFlags::BRS.contains(FdFlags::ESI));
        assert_eq!(Direction::Rx.letter(), 'R');
        assert_eq!(Direction::Tx.letter(), 'T');

        let t = ts(1_700_000_000, 500);
        assert_eq!(
            (t.secs(), t.micros(), t.as_micros()),
            (1_700_000_000, 500, 1_700_000_000_000_500)
        );
        assert_eq!(t.as_secs_f64(), 1_700_000_000.000_5);
        assert_eq!(t.to_string(), "1700000000.000500");
        assert_eq!(ts(1, 2).to_string(), "0000000001.000002");
        assert_eq!(
            Timestamp::new(0, 999_999).map(Timestamp::micros),
            Some(999_999)
        );
        assert_eq!(Timestamp::new(0, 1_000_000), None);
        assert_eq!(
            Timestamp::try_new(5, 1_000_000),
            Err(Error::OutOfRange {
                what: "timestamp microseconds",
                found: 1_000_000,
                min: 0,
                max: 999_999
            })
        );
    }

    // ------------------------------------------------------------- lines

    const LOG: &str = "(1700000000.000500) can0 081#1081110000000000\r\n\
                       \n\
                       # a comment\n\
                       (1700000000.000600) can0 0X1#00\n\
                       DROPCOUNT: dropped 1 CAN frame on 'can0' socket (total drops 1)\n\
                         can0  705   [1]  remote request\n\
                       (1700000000.000700)  vcan10 12345678##3AABB T\n\
                       (1700000000.000800) can0 701#7F";

    #[test]
    fn lines_numbers_every_line() {
        let items: Vec<_> = lines(LOG.as_bytes()).collect();
        assert_eq!(items.len(), 8);
        let numbers: Vec<usize> = items.iter().map(|(n, _)| *n).collect();
        assert_eq!(numbers, [1, 2, 3, 4, 5, 6, 7, 8]);
        assert_eq!(items[0].1, Ok(Some(frame(SPEC_LOG))));
        assert_eq!(items[1].1, Ok(None));
        assert_eq!(items[2].1, Ok(None));
        assert_eq!(
            items[3].1,
            Err(Error::Candump {
                column: 27,
                reason: CandumpErrorKind::BadIdentifier {
                    found: Found::Byte(b'X')
                }
            })
        );
        assert!(items[4].1.is_err());
        assert!(items[5].1.as_ref().unwrap().unwrap().is_rtr());
        let fd = items[6].1.unwrap().unwrap();
        assert_eq!(
            (fd.iface_str(), fd.id(), fd.fd_flags().bits(), fd.data()),
            ("vcan10", ext_id(0x1234_5678), 3, &[0xAA, 0xBB][..])
        );
        assert_eq!(fd.direction(), Some(Direction::Tx));
        assert_eq!(items[7].1.unwrap().unwrap().data(), &[0x7F]);
        // Every line as `parse_line` reads it alone.
        for ((_, result), line) in items.iter().zip(LOG.split('\n')) {
            assert_eq!(*result, parse_line_str(line), "{line:?}");
        }
    }

    #[test]
    fn lines_fold_matches_next() {
        let by_next: Vec<_> = lines(LOG.as_bytes()).by_ref().collect();
        let mut by_fold = Vec::new();
        lines(LOG.as_bytes()).for_each(|item| by_fold.push(item));
        assert_eq!(by_next, by_fold);
        assert_eq!(lines(LOG.as_bytes()).count(), 8);
    }

    #[test]
    fn lines_ends_and_remainder() {
        assert_eq!(lines(b"").next(), None);
        assert_eq!(lines(b"\n").collect::<Vec<_>>(), [(1, Ok(None))]);
        assert_eq!(lines(b"\n\n").count(), 2);
        let mut it = lines(b"can0 123#11\ncan0 123#22");
        assert_eq!(it.remainder(), b"can0 123#11\ncan0 123#22");
        assert!(it.next().is_some());
        assert_eq!(it.remainder(), b"can0 123#22");
        assert!(it.next().is_some());
        assert_eq!((it.next(), it.next()), (None, None));
    }

    #[test]
    fn hex_decoding_matches_a_table() {
        // Every byte value, as the one digit that differs in a classic and a
        // CAN FD data field, on the fast and the general path.
        for b in 0..=255u8 {
            let mut line = b"(1700000000.000500) can0 123#0011223344556677".to_vec();
            line[31] = b;
            let expected = hex_value(b).map(|v| v << 4 | 1);
            match parse_line(&line) {
                Ok(Some(f)) => assert_eq!(Some(f.data()[1]), expected, "{b:#x}"),
                Ok(None) => panic!("{b:#x}"),
                Err(_) => assert_eq!(expected, None, "{b:#x}"),
            }
            assert_eq!(parse_line(&line), parse_general(&line), "{b:#x}");
        }
        for (a, b) in [(b'0', b'9'), (b'a', b'f'), (b'A', b'F')] {
            for c in a..=b {
                let line = format!("(1.0) can0 123#{}{}", char::from(c), char::from(c));
                let v = hex_value(c).unwrap();
                assert_eq!(frame(&line).data(), &[v << 4 | v]);
            }
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::test_gens::candump::{frame_spec, mutated_line, screen_frame_spec};

    fn write_log(frame: &CandumpFrame<'_>) -> String {
        let mut s = String::new();
        frame.write_log(&mut s).unwrap();
        s
    }

    fn write_screen(frame: &CandumpFrame<'_>) -> String {
        let mut s = String::new();
        frame.write_screen(&mut s).unwrap();
        s
    }

    proptest! {
        #[test]
        fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
            let one = parse_line(&bytes);
            prop_assert_eq!(one, parse_general(&bytes));
            let by_next: Vec<_> = lines(&bytes).by_ref().collect();
            let mut by_fold = Vec::new();
            lines(&bytes).for_each(|item| by_fold.push(item));
            prop_assert_eq!(by_next, by_fold);
        }

        #[test]
        fn near_valid_lines_never_panic_and_both_paths_agree(line in mutated_line()) {
            let result = parse_line(&line);
            prop_assert_eq!(result, parse_general(&line));
            if let Ok(Some(frame)) = result {
                // Whatever parses writes back to something that parses to it.
                let text = write_log(&frame);
                prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
            }
            for item in lines(&line) {
                let _ = item;
            }
        }

        #[test]
        fn log_format_round_trips(spec in frame_spec()) {
            let frame = spec.frame();
            let text = write_log(&frame);
            prop_assert_eq!(frame.to_string(), text.clone());
            prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
            prop_assert_eq!(parse_general(text.as_bytes()), Ok(Some(frame)));
            for end in ["\n", "\r\n"] {
                let line = format!("{text}{end}");
                prop_assert_eq!(parse_line_str(&line), Ok(Some(frame)));
                let buf = format!("{line}{line}");
                let items: Vec<_> = lines(buf.as_bytes()).collect();
                prop_assert_eq!(items, vec![(1, Ok(Some(frame))), (2, Ok(Some(frame)))]);
            }
        }

        #[test]
        fn log_format_without_direction_round_trips(spec in frame_spec()) {
            let mut spec = spec;
            spec.direction = None;
            let frame = spec.frame();
            let text = write_log(&frame);
            prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
        }

        #[test]
        fn screen_format_round_trips(spec in screen_frame_spec()) {
            let frame = spec.frame();
            let text = write_screen(&frame);
            prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
            let line = format!("{text}\r\n");
            prop_assert_eq!(parse_line_str(&line), Ok(Some(frame)));
        }
    }
}
