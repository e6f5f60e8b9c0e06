//! What every log reader shares (SPEC §5, §5.7): the record a binary
//! reader hands on, its error, and the limits that keep memory bounded
//! whatever a damaged or hostile file claims.
//!
//! The text formats (candump, ASC, TRC) are read line by line, without
//! allocation, by their own modules ([`candump`], …); the binary
//! formats (pcap, pcapng, BLF) read from a [`std::io::Read`] through
//! [`ReadLog`] and need the standard library.

pub mod asc;
#[cfg(feature = "blf")]
pub mod blf;
mod calendar;
pub mod candump;
mod detect;
mod error;
#[cfg(feature = "pcap")]
pub mod pcap;
mod text;
pub mod trc;

pub use detect::{detect, Detected, DETECT_LEN};
pub use error::{BinaryError, Found, LogFormat, SyntaxError};
pub use text::{split_lines, SplitLines};

#[cfg(feature = "std")]
use crate::can::LogEvent;
#[cfg(feature = "std")]
use crate::Error;

/// The longest record, block or decompressed container a binary reader
/// holds in memory (16 MiB). A CAN record is at most a few hundred bytes and
/// a BLF container 128 KiB as the Vector tools write it; a length above this
/// is reported as [`BinaryError::TooLarge`], never allocated.
pub const MAX_RECORD_LEN: usize = 16 << 20;

/// One record of a binary log: its number and what it holds.
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Record<'a> {
    /// The 1-based number of the packet (pcap, pcapng: as tshark's
    /// `frame.number`) or object (BLF, every object type counted) in the
    /// file (SPEC §5.7 `line`).
    pub number: u64,
    /// The frame or bus event the record holds.
    pub event: LogEvent<'a>,
}

/// Why a binary log reader could not hand on a record: the input could not
/// be read, or the file is damaged at a known place ([`Error::Binary`]).
/// The records before the error were handed on. After damage to the file's
/// structure (a cut-off or inconsistent block) the reader returns `None`;
/// after an error in one record's content whose size is known (e.g. an
/// identifier out of range) it may go on with the next record, as a text
/// reader goes on after a malformed line (SPEC §5.7).
#[cfg(feature = "std")]
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// Reading the input failed.
    #[error("read error: {0}")]
    Io(#[from] std::io::Error),
    /// The file is damaged (or not of the format it was read as).
    #[error(transparent)]
    Log(#[from] Error),
}

/// A reader of a binary log: hands on its records one at a time, each
/// borrowing what it names (a pcapng interface name) from the reader.
///
/// Records that hold no CAN frame (a pcap packet of another link type, a
/// BLF object of another type) are counted in [`ReadLog::other_records`]
/// and still take their number, so numbers match what other tools show.
#[cfg(feature = "std")]
pub trait ReadLog {
    /// The format the reader reads.
    fn format(&self) -> LogFormat;

    /// Return the next record, `None` at the end of the file or after
    /// damage to its structure (see [`ReadError`]).
    fn next_record(&mut self) -> Option<Result<Record<'_>, ReadError>>;

    /// The number of records read so far that hold no CAN frame or bus
    /// event and were skipped.
    fn other_records(&self) -> u64;
}
