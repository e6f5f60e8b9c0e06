//! Vector ASC text logs (CANalyzer, CANoe, python-can's `ASCWriter`,
//! can-utils' `log2asc`; docs/formats.md#asc).
//!
//! An ASC file is a short header (`date …`, `base hex|dec  timestamps
//! absolute|relative`, `internal events logged`, `Begin Triggerblock …`)
//! followed by one line per event. [`AscParser`] keeps what the header sets
//! and reads one line at a time; [`lines`] walks a whole buffer;
//! [`write_line`] writes a frame as python-can's writer does, which reads
//! back to the same frame. Nothing here allocates, and no input makes it
//! panic.
//!
//! | line | example |
//! |---|---|
//! | classic frame | `   0.012345 1  123             Rx   d 8 11 22 33 44 55 66 77 88` |
//! | extended identifier | `   0.012345 2  18FF1234x       Tx   d 2 01 02` |
//! | remote request | `   0.012345 1  705             Rx   r 1` (`r` alone before v8.5) |
//! | error frame | `   0.012345 1  ErrorFrame` |
//! | CAN FD (or classic in FD form) | `   0.012345 CANFD   1 Rx 123  1 0 9 12 00 … 0B   0  0  3000 0 0 0 0 0` |
//!
//! # Decisions (where the format and the tools leave room; docs/formats.md#asc)
//!
//! - `ts` is the event's time as written, in seconds since the start of
//!   the measurement (docs/formats.md#timestamps); with `timestamps relative`
//!   each time is the time since the previous event, and the parser adds them
//!   up, so `ts` is still seconds since the start. python-can's reader (by
//!   default) returns relative times as written. The `date` and `Begin
//!   Triggerblock` dates (local time, no zone) are not used.
//! - `iface` is the channel number as written ([`Iface::Channel`], 1 for
//!   the first channel); python-can counts channels from 0.
//! - `base dec` applies to identifiers and data bytes, of classic and
//!   `CANFD` lines alike (as python-can reads them; can-utils' `asc2log`
//!   reads `CANFD` lines in hex whatever the base). The DLC is one hex
//!   digit in both bases. On a classic line a code above 8 followed by
//!   exactly its CAN FD length of bytes (9: 12, … F: 64) is a CAN FD frame
//!   without BRS and ESI, followed by 8 a classic frame of 8 bytes; any
//!   other count of bytes, and anything after them but CANoe's statistics,
//!   is an error (python-can keeps 8 bytes).
//! - A `CANFD` line is a CAN FD frame only when its flags field has
//!   EDL/FDF (0x1000) set, with BRS (0x2000) and ESI (0x4000) from the same
//!   field; without it the line carries a classic frame, a remote request
//!   when the flags have 0x10 (the decision in docs/formats.md#asc, as
//!   `asc2log` reads it) — unless its data length exceeds 8 bytes, which only
//!   CAN FD can have (CANoe writes such lines, flags `11`): then it is CAN FD
//!   with BRS and ESI from their columns, as python-can reads it. python-can
//!   marks every `CANFD` line as CAN FD and reads BRS/ESI from their columns.
//! - CANoe's statistics after a frame's data (`Length = 1704000 BitCount
//!   = 145 ID = 88888888x`) are read past; after a remote request's `r`
//!   without a DLC they make a request of length 0, as python-can reads it.
//! - `ErrorFrame` says no more than that an error happened: it is an error
//!   frame of class `bus_error` with 8 zero data bytes, as `asc2log` writes
//!   it (python-can gives identifier 0 and no data).
//! - Not frames, and not reported: blank lines, `//` comments, the header
//!   lines above, `End TriggerBlock`, `Start of measurement`, `Log trigger
//!   event` and CANoe 15's `TriggerEvent: TriggerBlock[Logging] Start
//!   DirectLogging` (and `Stop`), bus `Statistic:`, `J1939TP` and system-variable (`SV:`) lines
//!   and `TxRq` (transmit request) lines, which announce a frame the log
//!   shows again when it is on the bus. Chip status lines (`CAN 1
//!   Status:…`) and `OverloadFrame` lines are [`LogEvent::Status`]. Every
//!   other line is a [`FormatError::Syntax`] with its
//!   column; `CANXL` lines are errors (CAN XL is not a frame of this crate).
//!
//! ```
//! use motionwire::logs::asc::AscParser;
//! use motionwire::can::{Direction, Iface, LogEvent};
//!
//! let mut parser = AscParser::new();
//! assert_eq!(parser.parse_line(b"base hex  timestamps absolute")?, None);
//! let Some(LogEvent::Frame(logged)) =
//!     parser.parse_line(b"   1.500000 1  701             Rx   d 1 05")?
//! else {
//!     panic!("a frame");
//! };
//! assert_eq!(logged.frame.id().raw(), 0x701);
//! assert_eq!(logged.frame.data(), &[0x05]);
//! assert_eq!(logged.iface, Some(Iface::Channel(1)));
//! assert_eq!(logged.direction, Some(Direction::Rx));
//! assert_eq!(logged.timestamp.map(|t| t.as_duration().as_millis()), Some(1500));
//! # Ok::<(), motionwire::Error>(())
//! ```

use core::fmt;
use core::iter::FusedIterator;

use crate::can::{Direction, FdFlags, FrameType, Iface, LogEvent, LogFrame, Timestamp, FD_LENGTHS};
use crate::logs::error::Result;
use crate::logs::text::take_line;
use crate::logs::FormatError;
use crate::logs::Position;

mod fast;
mod parser;
#[cfg(test)]
mod proptests;
#[cfg(feature = "std")]
mod reader;
#[cfg(test)]
mod tests;

pub use parser::AscParser;
use parser::{FLAG_BRS, FLAG_ESI, FLAG_FDF};
#[cfg(feature = "std")]
pub use reader::AscReader;

/// Walk a whole buffer line by line: `(position, what the line holds)`,
/// the line's [`Position`], numbered from 1
/// (docs/formats.md#positions).
#[must_use]
pub fn lines(buf: &[u8]) -> AscLines<'_> {
    AscLines {
        rest: buf,
        line: 0,
        parser: AscParser::new(),
    }
}

/// The iterator of [`lines`].
#[derive(Debug, Clone)]
pub struct AscLines<'a> {
    rest: &'a [u8],
    line: u64,
    parser: AscParser,
}

impl<'a> AscLines<'a> {
    /// The parser's state after the lines read so far.
    #[must_use]
    pub const fn parser(&self) -> &AscParser {
        &self.parser
    }
}

impl<'a> Iterator for AscLines<'a> {
    type Item = (Position, Result<Option<LogEvent<'a>>, FormatError>);

    fn next(&mut self) -> Option<Self::Item> {
        let line = take_line(&mut self.rest)?;
        self.line += 1;
        Some((Position::Line(self.line), self.parser.parse_line(line)))
    }
}

impl FusedIterator for AscLines<'_> {}

/// Write a frame as one ASC event line the way python-can's `ASCWriter`
/// writes it in a `base hex  timestamps absolute` file (without a line
/// end): classic and remote frames in the classic form, CAN FD frames in
/// the `CANFD` form with their flags, error frames as `ErrorFrame`. The
/// time is the record's (0 without one); the channel is the record's
/// channel (1 without one).
///
/// # Errors
///
/// [`fmt::Error`] for what an ASC line cannot hold: an interface given by
/// name, a CAN FD frame whose length is no DLC's (e.g. 49 bytes).
pub fn write_line<W: fmt::Write + ?Sized>(logged: &LogFrame<'_>, w: &mut W) -> fmt::Result {
    let channel = match logged.iface {
        Some(Iface::Channel(channel)) => channel,
        None => 1,
        Some(Iface::Name(_)) => return Err(fmt::Error),
    };
    let ts = logged.timestamp.unwrap_or(Timestamp::ZERO);
    let nanos = ts.subsec_nanos();
    if nanos % 1000 == 0 {
        write!(w, "{:>9}.{:06} ", ts.secs(), nanos / 1000)?;
    } else {
        write!(w, "{:>9}.{:09} ", ts.secs(), nanos)?;
    }
    let frame = &logged.frame;
    let dir = match logged.direction {
        Some(Direction::Tx) => "Tx",
        _ => "Rx",
    };
    let id = frame.id();
    let x = if id.is_extended() { "x" } else { "" };
    match frame.frame_type() {
        FrameType::Error => write!(w, "{channel}  ErrorFrame"),
        FrameType::Fd(flags) => {
            if !FD_LENGTHS.contains(&(frame.data().len() as u8)) {
                return Err(fmt::Error);
            }
            let mut bits = FLAG_FDF;
            if flags.contains(FdFlags::BRS) {
                bits |= FLAG_BRS;
            }
            if flags.contains(FdFlags::ESI) {
                bits |= FLAG_ESI;
            }
            write!(
                w,
                "CANFD {channel:>3} {dir:<4} {:>8} {} {} {:x} {:>2}",
                HexId(id.raw(), x),
                u8::from(flags.contains(FdFlags::BRS)),
                u8::from(flags.contains(FdFlags::ESI)),
                frame.dlc(),
                frame.data().len()
            )?;
            for byte in frame.data() {
                write!(w, " {byte:02X}")?;
            }
            write!(w, " {:>8} {:>4} {bits:>8X} 0 0 0 0 0", 0, 0)
        }
        FrameType::Remote { dlc } => {
            write!(
                w,
                "{channel}  {:<15} {dir:<4} r {dlc:x}",
                HexId(id.raw(), x)
            )
        }
        FrameType::Data => {
            write!(
                w,
                "{channel}  {:<15} {dir:<4} d {:x}",
                HexId(id.raw(), x),
                frame.dlc()
            )?;
            for byte in frame.data() {
                write!(w, " {byte:02X}")?;
            }
            Ok(())
        }
    }
}

/// An identifier in upper-case hex with its extended marker, padded as a
/// whole.
struct HexId(u32, &'static str);

impl fmt::Display for HexId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buf = [0u8; 9];
        let mut n = 0;
        let mut started = false;
        for shift in (0..8).rev() {
            let digit = (self.0 >> (shift * 4)) & 0xF;
            if digit != 0 || started || shift == 0 {
                started = true;
                if let Some(slot) = buf.get_mut(n) {
                    *slot = b"0123456789ABCDEF"[digit as usize];
                }
                n += 1;
            }
        }
        if !self.1.is_empty() {
            if let Some(slot) = buf.get_mut(n) {
                *slot = b'x';
            }
            n += 1;
        }
        let text = core::str::from_utf8(buf.get(..n).unwrap_or_default()).unwrap_or_default();
        f.pad(text)
    }
}
