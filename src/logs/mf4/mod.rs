//! ASAM MDF 4 bus logging (MF4: CSS Electronics' CANedge loggers, Vector
//! CANoe, asammdf, python-can's `MF4Writer`; docs/formats.md#mf4), behind the
//! `mf4` feature.
//!
//! An MDF 4 file is a tree of little-endian blocks linked by absolute file
//! offsets (ASAM MDF 4.1 §4–§5). [`Mf4Reader`] reads these:
//!
//! | block | what the reader takes from it |
//! |---|---|
//! | identification (bytes 0–63) | `MDF     ` or `UnFinMF ` (unfinalized), version 4.00 to 4.99 |
//! | HD, header (at 64) | the first data group; the start time (ns since 1970, UTC) |
//! | DG, data group | its channel groups; its data; the record-id size (0: sorted, one channel group; 1, 2, 4, 8: unsorted, each record after its group's id) |
//! | CG, channel group | record id, data and invalidation bytes, VLSD flag (records are a u32 length and bytes); its name when it is no CAN group |
//! | CN, channel | type (fixed, VLSD, master, virtual), data type, byte and bit offset, bit count; name, members (composition), conversion, data |
//! | CC, conversion | identity, linear, rational, value to value (with and without interpolation), value range to value, value to text (`Dir`: `Rx`/`Tx`) |
//! | TX | names and texts |
//! | DT, SD | records, signal data: read a chunk at a time |
//! | DZ | zlib-deflated DT or SD, also with the records transposed (zip types 0 and 1) |
//! | DL, HL | lists of data blocks |
//!
//! A CAN group is a channel group whose channels are `CAN_DataFrame`,
//! `CAN_RemoteFrame` or `CAN_ErrorFrame` and its members
//! (`CAN_DataFrame.ID`, …): `BusChannel`, `ID`, `IDE`, `DLC`,
//! `DataLength`, `DataBytes` (in the record, or VLSD: in signal data or
//! in a VLSD channel group's records), `Dir`, `EDL`, `BRS`, `ESI`,
//! `ErrorType`; any may be absent. Records of other groups (LIN, signals)
//! are counted by name ([`ReadLog::other_kinds`] as
//! [`OtherRecord::Mf4Group`],
//! [`Mf4Reader::other_groups`]), never reported as malformed.
//!
//! # Decisions (where the standard is silent, as asammdf reads;
//! docs/formats.md#mf4)
//!
//! - `ts` is the header's start time plus the master channel (seconds,
//!   through its conversion), to the nanosecond; the start time is UTC
//!   whatever the header's time flags and zone offsets say. A group
//!   without a master channel has no `ts`.
//! - `iface` is `BusChannel` ([`Iface::Channel`](crate::can::Iface)), as
//!   the file writes it (CANedge: 1, 2, 9; python-can: its channel 0 as 0).
//! - `line` is the record's 1-based number over all data groups, every
//!   record counted (VLSD records and other groups' too).
//! - The identifier is `ID & 0x1FFFFFFF`, extended when `IDE` is 1 or,
//!   without `IDE`, when bit 31 is set. `EDL` 1 is CAN FD. The data is the
//!   first `DataLength` bytes (without it, the length of the DLC), at most
//!   8 in a classic frame, zero-padded where fewer are stored; a remote
//!   frame has no data and keeps its DLC (at most 8).
//! - `CAN_ErrorFrame` is an error frame of classes `bus_error | protocol`
//!   whose data is Linux's layout (docs/formats.md#error-frames) of
//!   `ErrorType`: 1 bit, 2 form, 3 stuff error in byte 2 (0x01, 0x02, 0x04), 4
//!   CRC and 5 ACK in byte 3 (0x08, 0x19), byte 2 | 0x80 when `Dir` is Tx. Its
//!   `ID` and `DataBytes` are not used (python-can gives its own frame's).
//! - A finalized file (`MDF     `, and from version 4.10 no unfinalized
//!   flag in the identification block, as asammdf decides it) is read as
//!   its blocks say: a data block's length is the data it holds (a DT of
//!   length 24 holds none), and a data group's records are as many as its
//!   channel groups' cycle counts add up to; bytes after them are none.
//! - Unfinalized files (`UnFinMF `, every CANedge file as it records, or
//!   unfinalized flags set): cycle counts are ignored, records are read
//!   until the data end, a DT block whose length is its header runs to the
//!   end of the file.
//! - Frames come out stable-sorted by time (data group, channel group,
//!   record order break ties), as python-can's `MF4Reader` merges them:
//!   the data groups are merged by time, and the channel groups of one
//!   data group through a window of [`REORDER_WINDOW`] frames. Each channel
//!   group is taken to be in time order itself, as every writer writes it.
//!   Positions therefore do not always increase from one frame to the
//!   next.
//! - A record cut by the end of the data is dropped and reported; a record
//!   id that no channel group has ends its data group with one error
//!   (the frames before it are kept; asammdf drops the rest silently); a
//!   frame whose VLSD data is not there, or whose identifier or length
//!   cannot be, is one error and the reading goes on. These errors are
//!   [skipped](crate::logs::LogError::is_skipped) ones. A damaged block
//!   (a link out of the file or to the wrong block, a chain that loops —
//!   a data list that names one data block twice loops too —, a DZ block
//!   that does not inflate, zip types 2 to 5 — zstd and lz4, which
//!   asammdf also writes) ends the reading with one [`FormatError::Binary`] of
//!   [`LogFormat::Mf4`]. A DZ block of signal data that no frame's data
//!   lie in is passed over by its header, not inflated (so not checked,
//!   as the bytes of a DT block that no frame reads).
//!
//! # Memory
//!
//! Whatever the file claims, nothing is allocated beyond these limits: a
//! block or record of at most [`MAX_RECORD_LEN`] (16 MiB) — DT blocks are
//! read 256 KiB at a time, a DZ block inflated whole —, all data streams
//! together at most 256 MiB (sixteen such blocks), up to
//! [`REORDER_WINDOW`] frames per data group in the time window, 2^20
//! metadata blocks. A file read from a stream that cannot seek (a pipe,
//! gzip: `logs::read`) is held in memory, up to [`MAX_STREAMED_LEN`]
//! (256 MiB); give larger files by name (`logs::open` reads them in
//! place; both with the `logs` feature).
//!
//! ```
//! use motionwire::can::Iface;
//! use motionwire::logs::mf4::Mf4Reader;
//! use motionwire::logs::{Position, ReadLog};
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/mf4/python_can.mf4");
//! let mut reader = Mf4Reader::new(std::fs::File::open(path)?)?;
//! assert_eq!(reader.version(), 410);
//! let first = reader.next_event().unwrap()?;
//! let frame = first.event.frame().unwrap();
//! assert_eq!(frame.frame.id().raw(), 0x081);
//! assert_eq!(frame.iface, Some(Iface::Channel(0)));
//! assert_eq!(frame.timestamp.unwrap().to_string(), "1700000000.500000");
//! # Ok::<(), motionwire::logs::LogError>(())
//! ```

#[cfg(feature = "logs")]
use std::fs::File;
#[cfg(feature = "logs")]
use std::io::{self, SeekFrom};
use std::io::{Cursor, Read, Seek};

use crate::can::{LogEvent, Timestamp};
#[cfg(doc)]
use crate::logs::FormatError;
use crate::logs::{
    BinaryError, LogError, LogFormat, LogRecord, OtherRecord, OtherRecords, Position, ReadLog,
    MAX_RECORD_LEN,
};

mod block;
mod channel;
mod data;
mod group;
mod layout;
#[cfg(test)]
mod tests;

pub use group::REORDER_WINDOW;

use block::{damaged, Source};
use data::Budget;
use group::{GroupReader, Item, Output};

/// The largest MF4 file read from a stream that cannot seek (256 MiB): such
/// a file is held in memory.
pub const MAX_STREAMED_LEN: usize = 16 * MAX_RECORD_LEN;

/// A reader of ASAM MDF 4 bus-logging files (docs/formats.md#mf4): see the
/// [module documentation](self).
pub struct Mf4Reader<R> {
    source: Source<R>,
    version: u16,
    start: Timestamp,
    groups: Vec<GroupReader>,
    /// The next frame of each group, once read.
    heads: Vec<Option<Item>>,
    /// The groups not at their end.
    active: Vec<usize>,
    /// Records of groups without CAN frames, by name (from the data groups
    /// read when the file was opened).
    counted: Vec<(String, u64)>,
    /// `counted` and the groups' counts as [`ReadLog::other_kinds`] hands
    /// them out, brought up to date before each event is handed out.
    kinds: Vec<OtherRecords>,
    /// The records `kinds` counts.
    kinds_total: u64,
    skipped: u64,
    done: bool,
}

impl<R> std::fmt::Debug for Mf4Reader<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Mf4Reader")
            .field("version", &self.version)
            .field("start", &self.start)
            .field("data_groups", &self.groups.len())
            .field("skipped", &self.skipped)
            .finish_non_exhaustive()
    }
}

impl<R: Read + Seek> Mf4Reader<R> {
    /// Read the file's metadata: identification, header, data groups,
    /// channel groups and channels.
    ///
    /// # Errors
    ///
    /// A [`LogError`] of kind [`LogErrorKind::Io`](crate::logs::LogErrorKind::Io)
    /// when reading fails, and of kind
    /// [`LogErrorKind::Damaged`](crate::logs::LogErrorKind::Damaged) with an
    /// [`FormatError::Binary`] of [`LogFormat::Mf4`] when the file does not start
    /// with `MDF     ` or `UnFinMF ` ([`BinaryError::BadMagic`]), its version
    /// is not 4.x ([`BinaryError::UnsupportedVersion`]), or a metadata block
    /// is damaged (out of the file, of the wrong kind, in a loop, cut).
    pub fn new(reader: R) -> Result<Self, LogError> {
        let mut source = Source::new(reader)?;
        let layout = layout::read(&mut source)?;
        let start = Timestamp::from_nanos(
            layout.start_ns / 1_000_000_000,
            (layout.start_ns % 1_000_000_000) as u32,
        )
        .unwrap_or(Timestamp::ZERO);
        let budget = Budget::default();
        let mut groups = Vec::new();
        let mut counted: Vec<(String, u64)> = Vec::new();
        let mut base = 0u64;
        let last_can = layout.data_groups.iter().rposition(|dg| {
            dg.groups
                .iter()
                .any(|g| matches!(g.kind, layout::Kind::Can(_)))
        });
        for (i, dg) in layout.data_groups.iter().enumerate() {
            let index = u32::try_from(i).unwrap_or(u32::MAX);
            let reader = GroupReader::new(&mut source, dg, index, base, layout.start_ns, &budget)?;
            let has_frames = reader.has_frames();
            if has_frames && Some(i) == last_can {
                groups.push(reader);
                continue;
            }
            if has_frames {
                groups.push(GroupReader::new(
                    &mut source,
                    dg,
                    index,
                    base,
                    layout.start_ns,
                    &budget,
                )?);
            }
            // Counted for the numbers of the records after it (`line`
            // in docs/formats.md#mf4) and for its other groups.
            let (records, others) = reader.count(&mut source)?;
            base = base.saturating_add(records);
            if !has_frames {
                for (name, n) in others {
                    add(&mut counted, &name, n);
                }
            }
        }
        let active = (0..groups.len()).collect();
        let mut reader = Mf4Reader {
            source,
            version: layout.version,
            start,
            heads: vec![None; groups.len()],
            groups,
            active,
            counted,
            kinds: Vec::new(),
            kinds_total: 0,
            skipped: 0,
            done: false,
        };
        reader.sync_kinds();
        Ok(reader)
    }
}

impl<R> Mf4Reader<R> {
    /// Return the version number of the file, e.g. 411 for MDF 4.11.
    #[must_use]
    pub const fn version(&self) -> u16 {
        self.version
    }

    /// Return the start time of the recording (the header's, UTC;
    /// docs/formats.md#mf4).
    #[must_use]
    pub const fn start_time(&self) -> Timestamp {
        self.start
    }

    /// Return the groups without CAN frames whose records were read so far
    /// (all of them once the reading ends), by name (`LIN_Frame`,
    /// `CAN_OverloadFrame`, a signal group's name), with how many records
    /// each had: counted, and reported once per name (docs/formats.md#mf4).
    #[must_use]
    pub fn other_groups(&self) -> Vec<(String, u64)> {
        let mut all = self.counted.clone();
        for group in &self.groups {
            for (name, n) in group.others() {
                add(&mut all, name, *n);
            }
        }
        all.retain(|(_, n)| *n > 0);
        all
    }

    /// Bring `kinds` up to date with the records of other groups counted
    /// so far.
    fn sync_kinds(&mut self) {
        let total = self.other_total();
        if total != self.kinds_total {
            self.kinds = self
                .other_groups()
                .into_iter()
                .map(|(name, count)| OtherRecords {
                    kind: OtherRecord::Mf4Group(name),
                    count,
                })
                .collect();
            self.kinds_total = total;
        }
    }

    /// The records of other groups counted so far.
    fn other_total(&self) -> u64 {
        let counted: u64 = self.counted.iter().map(|(_, n)| n).sum();
        let read: u64 = self
            .groups
            .iter()
            .flat_map(|group| group.others())
            .map(|(_, n)| n)
            .sum();
        counted + read
    }
}

/// Add `n` records to `name`'s count.
fn add(counts: &mut Vec<(String, u64)>, name: &str, n: u64) {
    match counts.iter_mut().find(|(known, _)| known == name) {
        Some((_, count)) => *count += n,
        None => counts.push((name.to_owned(), n)),
    }
}

crate::logs::record::records_of!(Mf4Reader<R: Read, Seek>);

impl<R: Read + Seek> ReadLog for Mf4Reader<R> {
    fn format(&self) -> LogFormat {
        LogFormat::Mf4
    }

    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        let next = self.next_item();
        // The other groups' records read on the way to it are said with it.
        self.sync_kinds();
        let item = match next? {
            Ok(item) => item,
            Err(error) => return Some(Err(error)),
        };
        Some(Ok(LogRecord {
            position: Position::Record(item.key.number),
            event: LogEvent::Frame(item.frame),
        }))
    }

    fn other_records(&self) -> u64 {
        self.other_total()
    }

    fn other_kinds(&self) -> &[OtherRecords] {
        &self.kinds
    }

    fn skipped(&self) -> u64 {
        self.skipped
    }

    fn bytes_read(&self) -> u64 {
        self.source.read
    }
}

impl<R: Read + Seek> Mf4Reader<R> {
    /// The next frame in time order, or an error, with the frame's key.
    fn next_item(&mut self) -> Option<Result<Item, LogError>> {
        if self.done {
            return None;
        }
        // Each group's next frame; an error is handed on as it comes.
        let mut g = 0;
        while g < self.active.len() {
            let i = self.active[g];
            if self.heads[i].is_none() {
                match self.groups[i].next(&mut self.source) {
                    Some(Output::Frame(item)) => self.heads[i] = Some(item),
                    Some(Output::Error(error)) => {
                        if error.is_skipped() {
                            self.skipped += 1;
                        } else {
                            self.done = true;
                        }
                        return Some(Err(error));
                    }
                    None => {
                        self.active.swap_remove(g);
                        continue;
                    }
                }
            }
            g += 1;
        }
        let first = self
            .active
            .iter()
            .copied()
            .filter_map(|i| self.heads[i].as_ref().map(|item| (item.key, i)))
            .min()
            .map(|(_, i)| i);
        let Some(item) = first.and_then(|i| self.heads[i].take()) else {
            self.done = true;
            return None;
        };
        Some(Ok(item))
    }
}

impl Mf4Reader<Cursor<Vec<u8>>> {
    /// Read an MF4 file from a stream that cannot seek (a pipe, a gzip
    /// stream): it is held in memory, up to [`MAX_STREAMED_LEN`].
    ///
    /// # Errors
    ///
    /// As [`Mf4Reader::new`]; a stream longer than [`MAX_STREAMED_LEN`]:
    /// [`BinaryError::TooLarge`].
    pub fn from_stream<Rd: Read>(input: Rd) -> Result<Self, LogError> {
        Mf4Reader::new(Cursor::new(in_memory(input)?))
    }
}

/// The whole of `input`, up to [`MAX_STREAMED_LEN`].
fn in_memory<Rd: Read>(input: Rd) -> Result<Vec<u8>, LogError> {
    let mut bytes = Vec::new();
    input
        .take(MAX_STREAMED_LEN as u64 + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() > MAX_STREAMED_LEN {
        return Err(damaged(
            0,
            BinaryError::TooLarge {
                length: bytes.len() as u64,
                limit: MAX_STREAMED_LEN as u64,
            },
        ));
    }
    Ok(bytes)
}

/// What [`LogReader`](crate::logs::LogReader) reads an MF4 file from: the
/// file itself, or a stream that cannot seek, held in memory.
#[cfg(feature = "logs")]
#[derive(Debug)]
pub(crate) enum Input {
    File(File),
    Memory(Cursor<Vec<u8>>),
}

#[cfg(feature = "logs")]
impl Input {
    /// The whole of a stream, in memory (up to [`MAX_STREAMED_LEN`]).
    pub(crate) fn memory<Rd: Read>(input: Rd) -> Result<Self, LogError> {
        Ok(Input::Memory(Cursor::new(in_memory(input)?)))
    }

    /// Return `file` when it is an MF4 file (its first bytes say so, or
    /// `forced`), rewound; else give it back, rewound.
    pub(crate) fn file(
        mut file: File,
        forced: Option<LogFormat>,
    ) -> io::Result<Result<Self, File>> {
        let mut head = [0u8; 16];
        let mut got = 0;
        while got < head.len() {
            match file.read(&mut head[got..]) {
                Ok(0) => break,
                Ok(n) => got += n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        file.seek(SeekFrom::Start(0))?;
        let gzip = head.starts_with(&[0x1f, 0x8b]);
        let mf4 = match forced {
            Some(LogFormat::Mf4) => !gzip,
            Some(_) => false,
            None => crate::logs::detect::is_mf4(&head),
        };
        Ok(if mf4 {
            Ok(Input::File(file))
        } else {
            Err(file)
        })
    }
}

#[cfg(feature = "logs")]
impl Read for Input {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        match self {
            Input::File(file) => file.read(buf),
            Input::Memory(memory) => memory.read(buf),
        }
    }
}

#[cfg(feature = "logs")]
impl Seek for Input {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        match self {
            Input::File(file) => file.seek(pos),
            Input::Memory(memory) => memory.seek(pos),
        }
    }
}
