//! What every reader hands on (docs/formats.md#positions,
//! docs/formats.md#memory): an event with its position, the one trait of
//! the readers, and the limit that keeps a binary reader's memory bounded.

use core::fmt;

use crate::can::LogEvent;
#[cfg(feature = "std")]
use crate::logs::{LogError, LogFormat};

/// The longest record, block or decompressed container a binary reader
/// holds in memory (16 MiB). A CAN record is at most a few hundred bytes and
/// a BLF container 128 KiB as the Vector tools write it; a length above this
/// is reported as [`BinaryError::TooLarge`](crate::logs::BinaryError::TooLarge),
/// never allocated.
pub const MAX_RECORD_LEN: usize = 16 << 20;

/// Where an event or an error is in its log (`line` in
/// docs/formats.md#positions): the line of a text file or the record of a
/// binary one, numbered from 1.
///
/// `Display` writes the number alone, as the program's records (`"line":
/// 12`) and messages (`log.txt:12: …`) do.
///
/// ```
/// use motionwire::logs::Position;
///
/// assert_eq!(Position::Line(12).to_string(), "12");
/// assert_eq!(Position::Record(3).number(), 3);
/// assert_eq!(Position::Record(3).unit(), "record");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Position {
    /// The 1-based line of a text log (candump, ASC, TRC).
    Line(u64),
    /// The 1-based number of the packet (pcap, pcapng: as tshark's
    /// `frame.number`) or object (BLF, every object type counted) in a
    /// binary log.
    Record(u64),
}

impl Position {
    /// Return the line or record number.
    #[inline]
    #[must_use]
    pub const fn number(self) -> u64 {
        match self {
            Position::Line(n) | Position::Record(n) => n,
        }
    }

    /// Return what the number counts, in words: `line` or `record`.
    #[must_use]
    pub const fn unit(self) -> &'static str {
        match self {
            Position::Line(_) => "line",
            Position::Record(_) => "record",
        }
    }
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.number(), f)
    }
}

/// One event of a log, with where it stands: what every reader hands on.
/// The event borrows what it names (an interface name) from the reader
/// until the next event is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LogRecord<'a> {
    /// The line or record the event was read from.
    pub position: Position,
    /// The frame or bus event.
    pub event: LogEvent<'a>,
}

/// A reader of a log of one format, reading from a [`std::io::Read`]:
/// hands on its events one at a time, each borrowing what it names from the
/// reader (a lending iterator: the next call needs the last event gone).
///
/// Every reader of [`crate::logs`] implements it, and so does
/// `logs::LogReader` (with the `logs` feature), which detects the format and
/// dispatches to them. The rule of docs/formats.md#reported holds for all: an
/// error that [`LogError::is_skipped`] (a malformed line, an over-long line, a
/// damaged record whose size is known) loses that line or record only and the
/// next call goes on; after any other error (the input cannot be read, a
/// binary file's structure is damaged) [`next_event`](ReadLog::next_event)
/// returns `None`. Positions increase from one event or error to the next,
/// except in MF4 files, whose frames come in time order across channel groups
/// (docs/formats.md#mf4).
///
/// Lines and records that hold no event (blank lines, comments, headers; a
/// pcap packet of another link type, a BLF object of another type) are not
/// handed on; they still take their number, so that numbers match what
/// editors and other tools show.
#[cfg(feature = "std")]
pub trait ReadLog {
    /// Return the format the reader reads.
    fn format(&self) -> LogFormat;

    /// Return the next event, an error with its position, or `None` at the
    /// end of the input or after an error that ends it (see the trait).
    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>>;

    /// Return how many records read so far hold no CAN frame or bus event
    /// and were skipped (docs/formats.md#pcap, docs/formats.md#blf,
    /// docs/formats.md#mf4: said once, not per record). Text readers have
    /// none.
    fn other_records(&self) -> u64 {
        0
    }

    /// Return the records counted by [`other_records`](ReadLog::other_records),
    /// kind by kind in the order first met (an MF4 file's groups in the
    /// file's order; docs/formats.md#pcap: the program names the link type
    /// of what it skipped, docs/formats.md#mf4 the group); `Display` of each
    /// says it ("12 packets of link type 1 (Ethernet) skipped: not CAN").
    /// Their counts add up to [`other_records`](ReadLog::other_records):
    /// every record skipped is said by its kind.
    fn other_kinds(&self) -> &[crate::logs::OtherRecords] {
        &[]
    }

    /// Return how many lines or records were reported and skipped so far
    /// (the errors for which [`LogError::is_skipped`] is true).
    fn skipped(&self) -> u64;

    /// Return how many bytes the reader has taken from its input so far
    /// (the decompressed bytes when it reads through gzip): for progress.
    fn bytes_read(&self) -> u64;

    /// Return whether the events handed on so far are all that the input
    /// has delivered, and the last read took everything it had buffered:
    /// the next call may wait for the input. A program that writes what it
    /// decodes flushes its output then, so that a live stream (`candump -L
    /// can0 | motionwire decode --json -`, docs/output.md#live) is shown as it
    /// comes, while a file, read in full blocks, streams at full speed.
    fn drained(&self) -> bool {
        false
    }

    /// Return the generation of the names the events borrow (interface
    /// names: candump's, pcapng's), for callers that cache by address.
    ///
    /// Readers keep each name at a stable address: an address names one
    /// interface for as long as this number stays the same. When it
    /// changes (a reader drops names it kept: a new pcapng section, a
    /// candump log with very many interface names), the names of the
    /// generation before stay where they are until the next change, so a
    /// caller that checks this number before each call to
    /// [`next_event`](ReadLog::next_event) and forgets its cache when it
    /// changed never mistakes one interface for another.
    fn generation(&self) -> u64 {
        0
    }
}
