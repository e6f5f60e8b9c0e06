//! What every reader hands on (docs/formats.md#positions,
//! docs/formats.md#memory): an event with its position, the one trait of
//! the readers, and the limit that keeps a binary reader's memory bounded.

use core::fmt;

#[cfg(feature = "std")]
use std::sync::Arc;

use crate::can::LogEvent;
#[cfg(feature = "std")]
use crate::can::{BusStatus, EthercatPacket, Iface, LogFrame};
#[cfg(feature = "std")]
use crate::ethercat::EthercatLink;
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
/// Two ways through a log, the same events and errors in the same order:
///
/// - a `for` loop over the reader (every reader is [`IntoIterator`], by
///   value or by `&mut`; [`records`](ReadLog::records) in generic code)
///   yields [`Record`]s that own what they name, as python-can's
///   `for msg in can.LogReader(path)` does: records can be kept, collected
///   and sent to other threads;
/// - [`next_event`](ReadLog::next_event) lends each event without a copy:
///   the loop of a program that looks at each event once (the CLI, the
///   report, the Python package) and is done with it.
///
/// ```
/// use motionwire::logs;
///
/// let text: &[u8] = b"(1.000000) can0 705#05\n(1.100000) can0 0X1#00\n(1.200000) can1 705#05\n";
/// let mut frames = Vec::new();
/// let mut log = logs::read(text)?;
/// for record in &mut log {
///     match record {
///         Ok(record) => frames.push(record),
///         // A malformed line is reported, and the reading goes on.
///         Err(error) if error.is_skipped() => continue,
///         Err(error) => return Err(error),
///     }
/// }
/// assert_eq!(frames.len(), 2);
/// assert_eq!(frames[1].position, logs::Position::Line(3));
/// assert_eq!(frames[1].event().iface().unwrap().to_string(), "can1");
/// # use motionwire::logs::ReadLog;
/// assert_eq!(log.skipped(), 1);
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
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

    /// Return an iterator over the rest of the log's [`Record`]s, each
    /// owning what it names (see the trait): what `for record in &mut log`
    /// does.
    fn records(&mut self) -> Records<&mut Self>
    where
        Self: Sized,
    {
        Records::new(self)
    }
}

#[cfg(feature = "std")]
impl<L: ReadLog + ?Sized> ReadLog for &mut L {
    fn format(&self) -> LogFormat {
        (**self).format()
    }

    #[inline(always)]
    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        (**self).next_event()
    }

    fn other_records(&self) -> u64 {
        (**self).other_records()
    }

    fn other_kinds(&self) -> &[crate::logs::OtherRecords] {
        (**self).other_kinds()
    }

    fn skipped(&self) -> u64 {
        (**self).skipped()
    }

    fn bytes_read(&self) -> u64 {
        (**self).bytes_read()
    }

    #[inline(always)]
    fn drained(&self) -> bool {
        (**self).drained()
    }
}

/// One event of a log, with where it stands, owning what it names: what a
/// `for` loop over a reader yields ([`Records`]). [`event`](Record::event)
/// returns the event as the readers' [`LogRecord`] holds it, borrowing the
/// interface name from the record.
#[cfg(feature = "std")]
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Record {
    /// The line or record the event was read from.
    pub position: Position,
    /// The event, its interface name (if it has one) in `name`, an
    /// EtherCAT packet's bytes in `payload`.
    event: LogEvent<'static>,
    name: Option<Arc<str>>,
    payload: Option<Arc<[u8]>>,
}

#[cfg(feature = "std")]
impl Record {
    /// Return the frame or bus event.
    #[inline]
    #[must_use]
    pub fn event(&self) -> LogEvent<'_> {
        let name = self.name.as_deref().map(Iface::Name);
        match self.event {
            LogEvent::Frame(frame) => {
                let mut frame: LogFrame<'_> = frame;
                if name.is_some() {
                    frame.iface = name;
                }
                LogEvent::Frame(frame)
            }
            LogEvent::Status(status) => {
                let mut status: BusStatus<'_> = status;
                if name.is_some() {
                    status.iface = name;
                }
                LogEvent::Status(status)
            }
            LogEvent::Ethercat(packet) => {
                let mut packet: EthercatPacket<'_> = packet;
                if name.is_some() {
                    packet.iface = name;
                }
                packet.link.payload = self.payload.as_deref().unwrap_or_default();
                LogEvent::Ethercat(packet)
            }
        }
    }

    /// Return the record as the readers lend it: [`LogRecord`], borrowing
    /// from this record.
    #[inline]
    #[must_use]
    pub fn as_log_record(&self) -> LogRecord<'_> {
        LogRecord {
            position: self.position,
            event: self.event(),
        }
    }
}

#[cfg(feature = "std")]
impl fmt::Display for Record {
    /// The event as its `Display` writes it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.event().fmt(f)
    }
}

/// The [`Record`]s of a log, read by a [`ReadLog`]: the iterator of a `for`
/// loop over a reader (`for record in logs::open(path)?`, or
/// `for record in &mut log` to ask the reader for its counts after the
/// loop). Each interface name is shared by the records that name it.
#[cfg(feature = "std")]
#[derive(Debug)]
pub struct Records<L> {
    log: L,
    /// The interface name of the last record that had one.
    name: Option<Arc<str>>,
}

#[cfg(feature = "std")]
impl<L: ReadLog> Records<L> {
    /// Return the records of `log`, from where it stands.
    pub const fn new(log: L) -> Self {
        Records { log, name: None }
    }

    /// Return the reader (for its counts: [`ReadLog::skipped`],
    /// [`ReadLog::other_records`]).
    pub const fn get_ref(&self) -> &L {
        &self.log
    }

    /// Return the reader, mutably.
    pub fn get_mut(&mut self) -> &mut L {
        &mut self.log
    }

    /// Return the reader.
    pub fn into_inner(self) -> L {
        self.log
    }
}

#[cfg(feature = "std")]
impl<L: ReadLog> Iterator for Records<L> {
    type Item = Result<Record, LogError>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let last = &mut self.name;
        let next = self.log.next_event()?;
        Some(next.map(|record| {
            let payload = match record.event {
                LogEvent::Ethercat(packet) => Some(Arc::from(packet.link.payload)),
                _ => None,
            };
            let (event, name) = detach(record.event);
            let name = name.map(|name| match last {
                Some(kept) if Iface::Name(kept).is_name(name.as_bytes()) => Arc::clone(kept),
                _ => Arc::clone(last.insert(Arc::from(name))),
            });
            Record {
                position: record.position,
                event,
                name,
                payload,
            }
        }))
    }
}

#[cfg(feature = "std")]
impl<L: ReadLog> core::iter::FusedIterator for Records<L> {}

/// `IntoIterator` for a reader type, by value and by `&mut`: the
/// [`Records`] of a `for` loop.
#[cfg(feature = "std")]
macro_rules! records_of {
    ($reader:ident $(<$r:ident: $b:path $(, $bs:path)*>)?) => {
        impl$(<$r: $b $(+ $bs)*>)? IntoIterator for $reader$(<$r>)?
        where
            $reader$(<$r>)?: $crate::logs::ReadLog,
        {
            type Item = Result<$crate::logs::Record, $crate::logs::LogError>;
            type IntoIter = $crate::logs::Records<Self>;

            /// Return the log's [`Record`](crate::logs::Record)s: `for record in log`.
            fn into_iter(self) -> Self::IntoIter {
                $crate::logs::Records::new(self)
            }
        }

        impl<'a $(, $r: $b $(+ $bs)*)?> IntoIterator for &'a mut $reader$(<$r>)?
        where
            $reader$(<$r>)?: $crate::logs::ReadLog,
        {
            type Item = Result<$crate::logs::Record, $crate::logs::LogError>;
            type IntoIter = $crate::logs::Records<Self>;

            /// Return the rest of the log's [`Record`](crate::logs::Record)s,
            /// the reader kept: `for record in &mut log`.
            fn into_iter(self) -> Self::IntoIter {
                $crate::logs::Records::new(self)
            }
        }
    };
}
#[cfg(feature = "std")]
pub(crate) use records_of;

/// `event` without its interface name, which is returned apart, so that
/// what is left borrows nothing; a channel number stays.
#[cfg(feature = "std")]
#[inline(always)]
fn detach(event: LogEvent<'_>) -> (LogEvent<'static>, Option<&str>) {
    fn split(iface: Option<Iface<'_>>) -> (Option<Iface<'static>>, Option<&str>) {
        match iface {
            Some(Iface::Name(name)) => (None, Some(name)),
            Some(Iface::Channel(n)) => (Some(Iface::Channel(n)), None),
            None => (None, None),
        }
    }
    match event {
        LogEvent::Frame(frame) => {
            let (iface, name) = split(frame.iface);
            let frame = LogFrame {
                frame: frame.frame,
                timestamp: frame.timestamp,
                iface,
                direction: frame.direction,
            };
            (LogEvent::Frame(frame), name)
        }
        LogEvent::Status(status) => {
            let (iface, name) = split(status.iface);
            let status = BusStatus {
                timestamp: status.timestamp,
                iface,
            };
            (LogEvent::Status(status), name)
        }
        LogEvent::Ethercat(packet) => {
            let (iface, name) = split(packet.iface);
            // The bytes are the record's own.
            let link = EthercatLink {
                destination: packet.link.destination,
                source: packet.link.source,
                encapsulation: packet.link.encapsulation,
                payload: &[],
            };
            let packet = EthercatPacket {
                timestamp: packet.timestamp,
                iface,
                link,
            };
            (LogEvent::Ethercat(packet), name)
        }
    }
}

#[cfg(feature = "logs")]
#[cfg(test)]
mod tests {
    use super::*;
    use crate::can::Iface;

    /// The `for` loop yields what `next_event` lends, owned, and leaves the
    /// reader's counts as `next_event` does.
    #[test]
    fn records_are_the_lent_events_owned() {
        let text: &[u8] = b"(1.000000) can0 705#05\n(1.100000) can0 0X1#00\n\
                            (1.200000) vcan12 081#01\n(1.300000) can0 705#05\n";
        let mut lent = Vec::new();
        let mut log = crate::logs::read(text).unwrap();
        while let Some(next) = log.next_event() {
            lent.push(next.map(|r| r.event.to_string()).map_err(|e| e.to_string()));
        }
        let mut log = crate::logs::read(text).unwrap();
        let records: Vec<_> = (&mut log).into_iter().collect();
        assert_eq!(log.skipped(), 1);
        let owned: Vec<_> = records
            .iter()
            .map(|r| r.as_ref().map(Record::to_string).map_err(|e| e.to_string()))
            .collect();
        assert_eq!(owned, lent);
        let kept: Vec<_> = records.into_iter().flatten().collect();
        assert_eq!(kept[1].position, Position::Line(3));
        assert_eq!(kept[1].event().iface(), Some(Iface::Name("vcan12")));
        assert_eq!(
            kept[2].as_log_record().event.iface(),
            Some(Iface::Name("can0"))
        );
        // Records of one interface share its name.
        assert!(Arc::ptr_eq(
            kept[0].name.as_ref().unwrap(),
            kept[0].clone().name.as_ref().unwrap()
        ));
    }

    /// A channel number stays in the event; nothing is shared.
    #[test]
    fn channels_stay_in_the_event() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/fixtures/blf/python_can.blf"
        );
        let records: Vec<_> = crate::logs::open(path).unwrap().into_iter().collect();
        assert_eq!(records.len(), 39);
        let first = records[0].as_ref().unwrap();
        assert_eq!(first.position, Position::Record(1));
        assert_eq!(first.event().iface(), Some(Iface::Channel(1)));
        assert!(first.name.is_none());
    }
}
