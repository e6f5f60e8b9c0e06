//! PEAK TRC text logs, versions 1.0 to 2.1 (PCAN-View, PCAN-Explorer,
//! python-can's `TRCWriter`; docs/formats.md#trc).
//!
//! A TRC file is a `;` comment header followed by one row per frame or bus
//! event. Three header keys set how the rows are read: `;$FILEVERSION=`
//! (1.0 when absent) fixes the columns, `;$STARTTIME=` is the time the
//! offsets count from, and in 2.x `;$COLUMNS=` orders the columns.
//! [`TrcParser`] keeps that state and reads one line at a time; [`lines`]
//! walks a whole buffer; [`write_header`] and [`write_line`] write version
//! 2.1, which reads back to the same frames. Nothing here allocates, and
//! no input makes it panic.
//!
//! | version | columns | example row |
//! |---|---|---|
//! | 1.0 | number`)`, offset (ms), id, DLC, data | `1)  1841  0001  8  00 01 02 03 04 05 06 07` |
//! | 1.1 | + type `Rx`/`Tx`/`Warng`/`Error` after the offset | `1)  1841.5  Rx  0001  2  00 01` |
//! | 1.2 | + bus after the offset | `1)  1841.512 1  Rx  0001  2  00 01` |
//! | 1.3 | + reserved after the id | `1)  1841.512 1  Rx  0001 -  2  00 01` |
//! | 2.0, 2.1 | as `;$COLUMNS=` orders them, e.g. `N,O,T,B,I,d,R,L,D` | `1  1841.512 FB 1 0001 Rx -  9  00 01 … 0B` |
//!
//! The 2.x types: `DT` data, `RR` remote request, `FD` CAN FD, `FB` CAN FD
//! with bit rate switch, `FE` with error state indicator, `BI` with both,
//! `ER` error frame, `ST` hardware status, `EC` error counter change, `EV`
//! event. Column letters: `N` number, `O` offset, `T` type, `B` bus, `I`
//! identifier, `d` direction, `R` reserved, `L` DLC (0..=15), `l` length
//! in bytes, `D` data. The facts are those of PEAK's "PEAK CAN TRC File
//! Format" description and of the files PEAK's tools and python-can write.
//!
//! # Decisions (where the format and the tools leave room; docs/formats.md#trc)
//!
//! - Blank lines and `;` lines are `Ok(None)`; the three `$` keys among them
//!   set the parser's state, and a malformed value of one is an error (a
//!   file version other than the six, a start time that is not decimal
//!   days or lies before 1970, a `$COLUMNS` without `O`, `T`, `I` and `L`
//!   or `l`, with a letter twice or with `D` not last). Other `$` keys are
//!   comments.
//! - Time: `$STARTTIME` is read as UTC (docs/formats.md#trc), exactly from its
//!   decimal text (no floats), rounded to the nearest microsecond, half to
//!   even — what python-can's `timedelta` does, and finer than PEAK's own
//!   10 digits of days (8.64 µs) anyway. The offset is read exactly, with up
//!   to 6 digits after the point (nanoseconds). A file without
//!   `$STARTTIME` counts from [`Timestamp::ZERO`]; every row has a time.
//!   python-can ignores the start time of a 1.0 file; the crate adds it
//!   when one is there (docs/formats.md#timestamps).
//! - `iface` is [`Iface::Channel`] with the bus column's number where the
//!   version has one (1.2, 1.3, 2.x with `B`), else `None`
//!   (docs/formats.md#interfaces); python-can says channel 1 for those. A bus
//!   `-` is `None`.
//! - Identifiers: more than 4 hex digits is extended (PEAK writes 4 and 8,
//!   python-can's writer 4 and 7, and python-can's reader decides so).
//! - The direction is the `Rx`/`Tx` of the type column (1.1 to 1.3) or of
//!   the `d` column (2.x, `-` for none).
//! - CAN FD (2.x): the flags are [`FdFlags::BRS`] for `FB`,
//!   [`FdFlags::ESI`] for `FE`, both for `BI`, none for `FD` (not `FDF`). An
//!   `L` column is a DLC whose length is ISO 11898-1's (9 → 12 bytes, 15 →
//!   64); an `l` column is the length in bytes. python-can sets BRS for
//!   `FE` and not for `BI`; PEAK defines `FE` as ESI alone and `BI` as both.
//! - Remote requests: `RR` (2.x) or `RTR` in the data column (1.x); the
//!   length column is the requested length, 0..=8.
//! - Error frames (`ER` in 2.x; type `Error`, or `ERROR` before the data,
//!   in 1.x) are frames of [`FrameType::Error`]. PEAK records an error
//!   frame as its error type (1 bit, 2 form, 4 stuff, 8 other error;
//!   the identifier column in 1.x, the first data byte in 2.x), a direction
//!   byte (0 while sending, 1 while receiving), the bit stream processor's
//!   position, and the RX and TX error counters. The crate reads them as
//!   Linux's SJA1000 driver reports the same controller event
//!   (docs/formats.md#error-frames): classes `bus_error | protocol | counters`
//!   ([`ERROR_FRAME_CLASSES`]); data byte 2 the protocol error type (bit 0x01,
//!   form 0x02 and stuff 0x04 are numbered alike; "other" is Linux's
//!   unspecified 0) with `CAN_ERR_PROT_TX` (0x80) when it happened while
//!   sending; byte 3 the location (the SJA1000 segment code, low 5 bits of the
//!   position); byte 6 the TX and byte 7 the RX error counter. An error row of
//!   another number of bytes is an error. python-can skips error frames when
//!   reading and writing.
//! - Bus events — `ST`, `EC` and `EV` rows (2.x), `Warng` rows (1.1 to
//!   1.3), and rows whose identifier is `FFFFFFFF` (1.0's error warnings,
//!   `BUSLIGHT`, `BUSHEAVY`, `BUSOFF`) — are [`LogEvent::Status`] with
//!   their time and bus, whatever else they hold (docs/formats.md#trc: counted,
//!   not frames, not malformed). python-can skips them.
//! - Anything else is a [`FormatError::Syntax`] with its
//!   column: an unknown row type, a data byte that is not two hex digits,
//!   fewer or more data bytes than the length says, anything after the
//!   data.
//!
//! ```
//! use motionwire::can::{Direction, FdFlags, Iface, LogEvent};
//! use motionwire::logs::trc::TrcParser;
//!
//! let mut parser = TrcParser::new();
//! for header in [
//!     ";$FILEVERSION=2.1",
//!     ";$STARTTIME=45244.925925925926",
//!     ";$COLUMNS=N,O,T,B,I,d,R,L,D",
//! ] {
//!     assert_eq!(parser.parse_line(header.as_bytes())?, None);
//! }
//! let row = b"      1         1.250 FB  2     0705 Rx -  9    00 01 02 03 04 05 06 07 08 09 0A 0B";
//! let Some(LogEvent::Frame(logged)) = parser.parse_line(row)? else { panic!("a frame") };
//! assert_eq!(logged.timestamp.unwrap().to_string(), "1700000000.001250");
//! assert_eq!(logged.iface, Some(Iface::Channel(2)));
//! assert_eq!(logged.direction, Some(Direction::Rx));
//! assert_eq!(logged.frame.fd_flags(), FdFlags::BRS);
//! assert_eq!(logged.frame.data().len(), 12);
//!
//! // A status row is a bus event; a malformed row says where and why.
//! let status = parser.parse_line(b"      2         2.000 ST  1        - Rx -  4    00 00 00 08")?;
//! assert!(matches!(status, Some(LogEvent::Status(_))));
//! let err = parser.parse_line(b"      3         3.000 XX  1     0705 Rx -  0").unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "trc line, column 23: expected a TRC row type (DT, FD, FB, FE, BI, RR, ER, ST, EC, EV; \
//!      Rx, Tx, Warng, Error in 1.x), found 'X'"
//! );
//! # Ok::<(), motionwire::Error>(())
//! ```

mod header;
mod lines;
mod parser;
#[cfg(feature = "std")]
mod reader;
mod row;
mod write;

pub use header::TrcVersion;
pub use lines::{lines, TrcLines};
pub use parser::TrcParser;
#[cfg(feature = "std")]
pub use reader::TrcReader;
pub use row::ERROR_FRAME_CLASSES;
pub use write::{write_header, write_line};

#[cfg(doc)]
use crate::can::{FdFlags, FrameType, Iface, LogEvent, Timestamp};
#[cfg(doc)]
use crate::logs::FormatError;

#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;
