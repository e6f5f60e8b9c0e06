//! Every log format in one folder (docs/formats.md), as python-can's `can/io`
//! shows them: one module per format, the detection of the format from the
//! content, the one line layer the text formats share, and — with the
//! `logs` feature — one way to read any log, `open` or `read`.
#![cfg_attr(
    feature = "logs",
    doc = "([`open`], [`read`]: with the `logs` feature, as here.)"
)]
//!
//! | file or folder | what it holds | needs |
//! |---|---|---|
//! | [`candump/`](candump) | candump log and screen output (can-utils;
//! docs/formats.md#candump-log, docs/formats.md#candump-screen) | |
//! | [`asc/`](asc) | Vector ASC (CANalyzer, CANoe; docs/formats.md#asc) | |
//! | [`trc/`](trc) | PEAK TRC 1.0 to 2.1 (PCAN-View, PCAN-Explorer;
//! docs/formats.md#trc) | |
//! | `pcap/` | pcap and pcapng captures of SocketCAN interfaces
//! (docs/formats.md#pcap) | feature `pcap` |
//! | `blf/` | Vector BLF (docs/formats.md#blf) | feature `blf` |
//! | `mf4/` | ASAM MDF 4 bus logging (CANedge, CANoe, asammdf;
//! docs/formats.md#mf4) | feature `mf4` |
//! | `detect.rs` | the format from the first bytes: [`detect`]
//! (docs/formats.md#detection) | |
//! | `text.rs` | the line layer: [`split_lines`]; with `std`, blocks of whole lines read from a `std::io::Read`, the over-long-line rule (`MAX_LINE_LEN`), CRLF and NUL | reading: `std` |
//! | `lex/` | the fields, decimal and hex numbers of a text line, a line's syntax error at its column, and the wide-word (SWAR) tricks of the fast paths | |
//! | `record.rs` | what every reader hands on: [`LogRecord`], [`Position`]; the readers' one trait `ReadLog` | trait: `std` |
//! | `error.rs` | [`LogFormat`]; [`FormatError`], the layer's own error: [`SyntaxError`], [`Found`], [`BinaryError`]; `LogError` | `LogError`: `std` |
//! | `reader.rs` | `LogReader`: `open`, `read`, `ReadOptions` — detection, gzip, dispatch | feature `logs` |
//! | `bytes.rs` | the integers of a binary record at a byte offset, in the file's byte order | `pcap`, `blf` or `mf4` |
//! | `calendar.rs` | logged dates as Unix time | |
//! | `filter.rs` | `EventFilter`, `TimeBound`: a log's events by time window and interface (docs/output.md#window) | `std` |
//!
//! Without the standard library, each text format parses lines from a
//! buffer without allocating ([`candump::parse_line`], [`candump::lines`],
//! [`asc::AscParser`], [`trc::TrcParser`]). With `std`, every format has a
//! reader that reads a `std::io::Read` and implements the one
//! trait `ReadLog` (`CandumpReader`, `AscReader`, `TrcReader`,
//! `PcapReader`, `BlfReader`, `Mf4Reader`), and `LogReader` reads any of
//! them.
//!
//! What holds for every reader (docs/formats.md#positions,
//! docs/formats.md#reported, docs/formats.md#memory):
//!
//! - an event's [`Position`] is the 1-based line of a text file, or the
//!   1-based number of the packet or object in a binary one;
//! - a malformed line, an over-long line and a damaged record whose size is
//!   known are reported with their position and skipped, and the reading
//!   goes on; an I/O error or a damaged binary structure ends it;
//! - memory is bounded whatever the input claims: a text line is held up to
//!   `MAX_LINE_LEN` (1 MiB), a binary record, block or container up to
//!   [`MAX_RECORD_LEN`] (16 MiB).
//!
//! MF4 (docs/formats.md#mf4) is read at any offset rather than in one pass, and
//! its frames come out in time order across its channel groups: its positions
//! (record numbers) do not always increase.

pub mod asc;
#[cfg(feature = "blf")]
pub mod blf;
#[cfg(any(feature = "pcap", feature = "blf", feature = "mf4"))]
mod bytes;
mod calendar;
pub mod candump;
mod detect;
mod error;
#[cfg(feature = "std")]
mod filter;
mod lex;
#[cfg(feature = "mf4")]
pub mod mf4;
#[cfg(feature = "pcap")]
pub mod pcap;
#[cfg(feature = "logs")]
mod reader;
mod record;
mod skipped;
mod text;
pub mod trc;

pub use detect::{detect, Detected, DETECT_LEN, DETECT_MAX_UNDECIDED};
pub use error::{BinaryError, FormatError, Found, LogFormat, SyntaxError};
#[cfg(feature = "std")]
pub use error::{LogError, LogErrorKind};
#[cfg(feature = "std")]
pub use filter::{EventFilter, TimeBound, TimeBoundError};
#[cfg(feature = "logs")]
pub use reader::{open, read, LogReader, LogVisitor, ReadOptions};
pub use record::{LogRecord, Position, MAX_RECORD_LEN};
#[cfg(feature = "std")]
pub use record::{ReadLog, Record, Records};
#[cfg(any(feature = "pcap", feature = "blf"))]
pub(crate) use skipped::OtherCounts;
pub use skipped::{OtherRecord, OtherRecords};
#[cfg(feature = "std")]
pub use text::MAX_LINE_LEN;
pub use text::{split_lines, SplitLines};
