//! candump text logs: one CAN frame per line (can-utils `candump`;
//! docs/formats.md).
//!
//! [`parse_line`] reads one line in either of the two formats that
//! can-utils' `candump` writes and returns the crate's
//! [`LogFrame`] — the [`CanFrame`](crate::can::CanFrame)
//! with its timestamp, interface (borrowed from the line) and direction.
//! [`lines`] walks a whole buffer. [`write_log`] and [`write_screen`] write
//! a frame back; everything they write parses back to the same frame.
//! Nothing here allocates, and no input makes it panic.
//!
//! The code is split by what it reads: log format and screen
//! format after the identifier, the one timestamp parser, the one hex
//! decoder, the SWAR fast path for the `candump -l` shape (with its own
//! tests against byte-at-a-time models), and the general parser for every
//! other shape; the fast path and the general parser are checked to agree
//! on every line by property tests and the `candump_line` fuzz target.
//!
//! | form (docs/formats.md) | example |
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
//! | error frame, `candump -e -l`, python-can | `(1700000000.000500) can0 20000004#0004000000000000` |
//! | screen error frame, `candump -e` | `  can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME` |
//! | screen with `-t A -a -8` | ` (2026-11-22 10:11:12.009100)  can0  385   {F}  48 69 20 43 61 6E 21 27   'Hi Can!''` |
//! | screen with `-t d` (or `-t z`), `-N` | ` (000.000499123)  can1  705   [1]  remote request` |
//!
//! The formats are those written by can-utils' `lib.c`
//! (`snprintf_canframe`, `snprintf_long_canframe`) and `candump.c`.
//!
//! # Decisions (where can-utils leaves room)
//!
//! See docs/formats.md#candump-log and docs/formats.md#candump-screen.
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
//!   and, for the screen, with `-t a|A|d|z`). It is `(seconds.fraction)`
//!   with 1 to 20 digits of seconds (anything that fits a `u64`) and 1 to 9
//!   digits of fraction (`-N` writes nanoseconds), read exactly as integers;
//!   `.5` is 500 ms. `-t A`'s `(2026-11-22 10:11:12.123456)` is read as UTC
//!   (docs/formats.md#candump-screen: the log does not say its time zone).
//!   Fewer than ten digits of seconds mark `-t d`/`-t z` times, relative to the
//!   first frame:
//!   [`lines_from`] adds `-t d`'s deltas up when its [`LineState`] says so,
//!   and [`detect_relative_timestamps`] tells the two apart from the first
//!   64 frames (zero-based times never decrease, deltas of real traffic do).
//! - An identifier has exactly 3 hex digits (standard, at most `0x7FF`) or 8
//!   (extended, at most `0x1FFFFFFF`), in either case. Eight digits always
//!   mean an extended frame, even for a small value, as in can-utils. An
//!   8-digit identifier with bit 29 set (`CAN_ERR_FLAG`, `0x20000000`) is an
//!   error frame (docs/formats.md#error-frames) whose classes are the other 29
//!   bits; bits 30 and 31 are out of range. An error frame carries classic data
//!   (0 to 8 bytes); in the screen format it may end with `ERRORFRAME`, and the
//!   tab-indented explanation lines `candump -e` prints after it are
//!   `Ok(None)` when read with [`lines`] (which knows the line before).
//! - Data: classic frames 0 to 8 bytes, CAN FD frames 0 to 64 bytes (any
//!   length, as can-utils' own parser accepts). `R`/`r` marks a remote
//!   request, optionally followed by its length digit `0`–`8`.
//! - The screen's views: `-a`'s ASCII column (`'Hi Can!.'`) is read and
//!   must show the data before it; `-8`'s raw DLC in braces (`{F}`: 9 to 15
//!   carry 8 bytes) is read; `-c`'s ANSI colour sequences are ignored.
//!   `-S` (bytes swapped, joined by a backquote) and `-i` (bytes in binary)
//!   cannot be read back faithfully: such lines are
//!   [`SyntaxError::UnsupportedOutput`](crate::logs::SyntaxError::UnsupportedOutput) errors, never misread.
//! - Not accepted (an error with its column): `.` separators between data
//!   bytes, the `_len8_dlc` suffix and CAN XL frames.
//! - The screen format shows CAN FD flags only as the BRS/ESI letters of the
//!   `-x` column (`RX B E`), which needs a direction. A screen line without
//!   that column gives an FD frame with empty flags, and [`write_screen`]
//!   cannot show other flags or flags without a direction: such frames
//!   survive only the log format.
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
//! use motionwire::can::{CanId, Direction, Iface};
//! use motionwire::logs::candump;
//!
//! let frame = candump::parse_line_str("(1700000000.000500) can0 081#1081110000000000 R")?
//!     .expect("a frame");
//! let ts = frame.timestamp.expect("a timestamp");
//! assert_eq!((ts.secs(), ts.micros()), (1_700_000_000, 500));
//! assert_eq!(frame.iface, Some(Iface::Name("can0")));
//! assert_eq!(frame.frame.id(), CanId::standard(0x081).unwrap());
//! assert_eq!(frame.frame.data(), &[0x10, 0x81, 0x11, 0, 0, 0, 0, 0]);
//! assert_eq!(frame.direction, Some(Direction::Rx));
//!
//! // Written in either format, it parses back to itself.
//! let mut text = String::new();
//! candump::write_screen(&frame, &mut text).unwrap();
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

mod error;
mod fast;
mod frame;
mod hex;
mod lines;
mod log;
mod parse;
#[cfg(feature = "std")]
mod reader;
mod screen;
mod timestamp;

#[cfg(any(test, doc))]
use crate::can::LogFrame;
#[cfg(test)]
use crate::logs::error::Result;
#[cfg(test)]
use crate::logs::FormatError;
#[cfg(test)]
use frame::Parsed;
#[cfg(test)]
use parse::parse_general;

pub use frame::{write_log, write_screen};
pub use lines::{
    detect_relative_timestamps, lines, lines_from, CandumpLines, LineState, RelativeTimestamps,
};
pub use parse::{parse_line, parse_line_str};
#[cfg(feature = "std")]
pub use reader::CandumpReader;

/// The general parser alone, as the public functions return it: for the
/// tests that compare it with the fast path.
#[cfg(test)]
fn general(line: &[u8]) -> Result<Option<LogFrame<'_>>, FormatError> {
    parse_general(line).map(|frame| frame.map(Parsed::into_log_frame))
}

#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;
