//! One data group's records, split and decoded (docs/formats.md#mf4): each
//! record is its channel group's record id (0 to 8 bytes) and its bytes, fixed
//! or, for a VLSD group, a u32 length and the bytes; a CAN group's record
//! is a frame, a VLSD group's the variable-length data of one, any other
//! group's counted.
//!
//! Frames come out in time order within the data group: a group with one
//! CAN channel group hands them on in record order; one with several
//! (CANedge ≥ 01.07 writes one per bus, kind and direction, up to ~1 s
//! apart) sorts them through a window of [`REORDER_WINDOW`] frames by time,
//! channel group and record.

use std::cmp::{Ordering, Reverse};
use std::collections::{BinaryHeap, VecDeque};
use std::io::{Read, Seek};

use crate::can::{
    CanFrame, CanId, Direction, ErrorClasses, FdFlags, Iface, LogFrame, Timestamp, CLASSIC_MAX_LEN,
    FD_MAX_LEN,
};
use crate::logs::bytes::padded;
use crate::logs::mf4::block::{binary, Source};
use crate::logs::mf4::data::{Budget, DataStream};
use crate::logs::mf4::layout::{CanGroup, DataBytes, DataGroup, FrameKind, Kind};
use crate::logs::{BinaryError, LogError, LogErrorKind, Position, MAX_RECORD_LEN};

/// The most frames a data group with several CAN channel groups holds to
/// put them in time order (about 7 MiB): a frame written up to this many
/// records late still comes out in its place.
pub const REORDER_WINDOW: usize = 1 << 16;

/// The most VLSD records and frames waiting for their VLSD record a data
/// group holds (CANedge writes a frame's VLSD record right after it).
const MAX_WAITING: usize = 1024;

/// The CAN FD lengths of DLC 9 to 15.
const FD_LENGTHS: [usize; 7] = [12, 16, 20, 24, 32, 48, 64];

/// Where a frame goes in the time order: time, data group, channel group,
/// record number (docs/formats.md#mf4: stable-sorted by `ts`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Key {
    pub(super) ts: Option<Timestamp>,
    pub(super) dg: u32,
    pub(super) cg: u32,
    pub(super) number: u64,
}

/// A frame with its place.
#[derive(Debug, Clone, Copy)]
pub(super) struct Item {
    pub(super) key: Key,
    pub(super) frame: LogFrame<'static>,
}

impl PartialEq for Item {
    fn eq(&self, other: &Self) -> bool {
        self.key == other.key
    }
}

impl Eq for Item {}

impl PartialOrd for Item {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Item {
    fn cmp(&self, other: &Self) -> Ordering {
        self.key.cmp(&other.key)
    }
}

/// What a data group hands on.
#[derive(Debug)]
pub(super) enum Output {
    Frame(Item),
    /// An error: a record skipped, the data group ended, or (kind
    /// [`LogErrorKind::Damaged`], I/O) the file.
    Error(LogError),
}

/// What a record id stands for.
#[derive(Debug, Clone, Copy)]
enum What {
    /// The CAN group `cans[i]`.
    Can(usize),
    /// The VLSD group `vlsd[i]`.
    Vlsd(usize),
    /// Another group, counted under `others[i]`.
    Other(usize),
}

#[derive(Debug, Clone, Copy)]
struct Slot {
    id: u64,
    /// Bytes after the record id; `None`: a VLSD record.
    len: Option<u64>,
    what: What,
}

/// A frame's fields as read from its record, before its data.
#[derive(Debug, Clone, Copy)]
struct Fields {
    kind: FrameKind,
    ts: Option<Timestamp>,
    channel: Option<u64>,
    id: u64,
    ide: Option<bool>,
    dlc: u64,
    data_length: Option<u64>,
    dir: Option<bool>,
    edl: bool,
    brs: bool,
    esi: bool,
    error_type: u64,
}

/// A frame whose data is a VLSD record not read yet.
#[derive(Debug, Clone, Copy)]
struct Waiting {
    key: Key,
    fields: Fields,
    vlsd: usize,
    offset: u64,
}

/// A VLSD record read before the frame that names it: up to 64 of its
/// bytes.
#[derive(Debug, Clone, Copy)]
struct Pooled {
    vlsd: usize,
    offset: u64,
    len: usize,
    bytes: [u8; FD_MAX_LEN],
}

/// A CAN channel group as its records are read.
#[derive(Debug)]
struct Can {
    group: CanGroup,
    /// Its place among the data group's channel groups.
    cg: u32,
    /// Records read (the index of virtual channels).
    records: u64,
    /// Where its VLSD data are, when in signal data.
    signal: Option<Signal>,
    /// The VLSD group of its data, when a channel group.
    vlsd: Option<usize>,
}

/// Signal data (SD) read forward as offsets grow.
#[derive(Debug)]
struct Signal {
    link: u64,
    stream: Option<DataStream>,
}

/// Where a frame's data are, as its record says.
#[derive(Debug, Clone, Copy)]
enum Data {
    /// In the record: this many bytes (copied out).
    Stored(usize),
    /// At this offset of its group's signal data.
    Signal(u64),
    /// At this offset of the records of a VLSD group of the data group.
    Group(Option<usize>, u64),
}

/// A VLSD channel group: its record id and the offset of its next record.
#[derive(Debug)]
struct Vlsd {
    id: u64,
    offset: u64,
}

/// One data group's records: see the [module documentation](self).
#[derive(Debug)]
pub(super) struct GroupReader {
    dg: u32,
    stream: DataStream,
    record_id_len: usize,
    /// Sorted by id.
    slots: Vec<Slot>,
    cans: Vec<Can>,
    vlsd: Vec<Vlsd>,
    /// Other groups' names and records read.
    others: Vec<(String, u64)>,
    start_ns: u64,
    /// The record number before this data group's first.
    base: u64,
    /// Records read.
    records: u64,
    /// The records the data holds in a finalized file (its channel
    /// groups' cycle counts); `None`: until the data end.
    bound: Option<u64>,
    /// Whether a data block of no length runs to the end of the file.
    open_ended: bool,
    pool: VecDeque<Pooled>,
    waiting: VecDeque<Waiting>,
    ready: VecDeque<Output>,
    /// Frames put in time order (several CAN groups).
    heap: Option<BinaryHeap<Reverse<Item>>>,
    ended: bool,
    budget: Budget,
}

impl GroupReader {
    /// The reader of data group `dg` (its index), whose records are
    /// numbered from `base + 1`.
    pub(super) fn new<R: Read + Seek>(
        source: &mut Source<R>,
        group: &DataGroup,
        dg: u32,
        base: u64,
        start_ns: u64,
        budget: &Budget,
    ) -> Result<Self, LogError> {
        let mut slots = Vec::new();
        let mut cans = Vec::new();
        let mut vlsd = Vec::new();
        let mut others = Vec::new();
        for (cg, channel_group) in group.groups.iter().enumerate() {
            let what = match &channel_group.kind {
                Kind::Can(can) => {
                    let signal = match &can.data_bytes {
                        Some(DataBytes::Signal { link, .. }) => Some(Signal {
                            link: *link,
                            stream: None,
                        }),
                        _ => None,
                    };
                    cans.push(Can {
                        group: (**can).clone(),
                        cg: cg as u32,
                        records: 0,
                        signal,
                        vlsd: None,
                    });
                    What::Can(cans.len() - 1)
                }
                Kind::Vlsd => {
                    vlsd.push(Vlsd {
                        id: channel_group.record_id,
                        offset: 0,
                    });
                    What::Vlsd(vlsd.len() - 1)
                }
                Kind::Other(name) => {
                    others.push((name.clone(), 0));
                    What::Other(others.len() - 1)
                }
            };
            slots.push(Slot {
                id: channel_group.record_id,
                len: channel_group.record_len,
                what,
            });
            if group.record_id_len == 0 {
                // Sorted: one channel group, no record ids.
                break;
            }
        }
        for can in &mut cans {
            if let Some(DataBytes::Group { record_id, .. }) = &can.group.data_bytes {
                can.vlsd = vlsd.iter().position(|v| v.id == *record_id);
            }
        }
        slots.sort_by_key(|slot| slot.id);
        let several = cans.len() > 1;
        Ok(GroupReader {
            dg,
            stream: DataStream::new(source, group.data, group.open_ended, budget.clone())?,
            record_id_len: usize::from(group.record_id_len),
            slots,
            cans,
            vlsd,
            others,
            start_ns,
            base,
            records: 0,
            bound: group.records,
            open_ended: group.open_ended,
            pool: VecDeque::new(),
            waiting: VecDeque::new(),
            ready: VecDeque::new(),
            heap: several.then(BinaryHeap::new),
            ended: false,
            budget: budget.clone(),
        })
    }

    /// Return whether the group has CAN channel groups.
    pub(super) fn has_frames(&self) -> bool {
        !self.cans.is_empty()
    }

    /// Return the other groups' names and the records read of each.
    pub(super) fn others(&self) -> &[(String, u64)] {
        &self.others
    }

    /// The next frame or error in the group's time order; `None` at its end.
    pub(super) fn next<R: Read + Seek>(&mut self, source: &mut Source<R>) -> Option<Output> {
        loop {
            if let Some(out) = self.ready.pop_front() {
                return Some(out);
            }
            if let Some(heap) = &mut self.heap {
                if heap.len() > REORDER_WINDOW || (self.ended && !heap.is_empty()) {
                    return heap.pop().map(|Reverse(item)| Output::Frame(item));
                }
            }
            if self.ended {
                return None;
            }
            if let Err(error) = self.step(source) {
                self.end();
                self.ready.push_back(Output::Error(error));
            }
        }
    }

    /// Count the group's records (reading every one of an unsorted group;
    /// from the data blocks' lengths for a sorted one): all of them, and
    /// the other groups' names and records.
    pub(super) fn count<R: Read + Seek>(
        mut self,
        source: &mut Source<R>,
    ) -> Result<(u64, Vec<(String, u64)>), LogError> {
        if self.record_id_len == 0 {
            let len = self.slots.first().and_then(|s| s.len).unwrap_or(0);
            let stream = std::mem::replace(
                &mut self.stream,
                DataStream::new(source, 0, false, self.budget.clone())?,
            );
            let mut records = stream.len(source)?.checked_div(len).unwrap_or(0);
            if let Some(bound) = self.bound {
                records = records.min(bound);
            }
            for other in &mut self.others {
                other.1 = records;
            }
            return Ok((records, std::mem::take(&mut self.others)));
        }
        loop {
            match self.split(source) {
                Ok(Some((slot, len))) => {
                    self.stream.consume(len);
                    if let What::Other(i) = slot.what {
                        self.others[i].1 += 1;
                    }
                }
                // What cannot be read is said when the group is read.
                Ok(None) | Err(_) => return Ok((self.records, std::mem::take(&mut self.others))),
            }
        }
    }

    /// Move the waiting frames and the group's end on.
    fn end(&mut self) {
        self.ended = true;
        while let Some(waiting) = self.waiting.pop_front() {
            self.missing(waiting);
        }
    }

    /// Find the next record: its slot and its length with the record id
    /// (available in the stream); `None` at the end of the data.
    fn split<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
    ) -> Result<Option<(Slot, usize)>, LogError> {
        let id_len = self.record_id_len;
        if self.bound.is_some_and(|bound| self.records >= bound) {
            // Finalized: the cycle counts say how many records there are;
            // the bytes after them are no records (docs/formats.md#mf4).
            return Ok(None);
        }
        if !self.stream.fill(source, id_len.max(1))? {
            return self.cut(id_len.max(1));
        }
        let slot = if id_len == 0 {
            self.slots.first().copied()
        } else {
            let id = u64::from_le_bytes(padded(self.stream.available(), 0)) & mask(id_len);
            match self.slots.binary_search_by_key(&id, |slot| slot.id) {
                Ok(i) => self.slots.get(i).copied(),
                Err(_) => None,
            }
        };
        let Some(slot) = slot else {
            let id = u64::from_le_bytes(padded(self.stream.available(), 0)) & mask(id_len);
            self.records += 1;
            return Err(self.skipped(BinaryError::UnknownRecordId { id }));
        };
        let len = match slot.len {
            Some(len) => len,
            None => {
                if !self.stream.fill(source, id_len + 4)? {
                    return self.cut(id_len + 4);
                }
                let len = u32::from_le_bytes(padded(self.stream.available(), id_len));
                4 + u64::from(len)
            }
        };
        let total = id_len as u64 + len;
        if total > MAX_RECORD_LEN as u64 {
            self.records += 1;
            return Err(self.skipped(BinaryError::TooLarge {
                length: total,
                limit: MAX_RECORD_LEN as u64,
            }));
        }
        if total == 0 {
            // A channel group of no bytes: nothing to split.
            return Ok(None);
        }
        if !self.stream.fill(source, total as usize)? {
            return self.cut(total as usize);
        }
        self.records += 1;
        Ok(Some((slot, total as usize)))
    }

    /// The data end inside a record of `needed` bytes: nothing when no
    /// byte of it is there, else it is dropped and counted
    /// (docs/formats.md#mf4).
    fn cut(&mut self, needed: usize) -> Result<Option<(Slot, usize)>, LogError> {
        let found = self.stream.available().len();
        if found == 0 {
            return Ok(None);
        }
        self.records += 1;
        self.stream.consume(found);
        Err(self.skipped(BinaryError::Truncated {
            needed: needed as u64,
            found: found as u64,
        }))
    }

    /// A record that cannot be read, reported at its number; the reading
    /// of the group ends (the caller ends it).
    fn skipped(&self, reason: BinaryError) -> LogError {
        LogError::new(
            Some(Position::Record(self.base + self.records)),
            LogErrorKind::Malformed(binary(self.stream.offset(), reason)),
        )
    }

    /// Read one record and hand on what it makes.
    fn step<R: Read + Seek>(&mut self, source: &mut Source<R>) -> Result<(), LogError> {
        let Some((slot, len)) = self.split(source)? else {
            self.end();
            return Ok(());
        };
        let number = self.base + self.records;
        let id_len = self.record_id_len;
        match slot.what {
            What::Other(i) => {
                self.others[i].1 += 1;
                self.stream.consume(len);
            }
            What::Vlsd(i) => {
                let record = self
                    .stream
                    .available()
                    .get(id_len + 4..len)
                    .unwrap_or_default();
                let offset = self.vlsd[i].offset;
                self.vlsd[i].offset += (len - id_len) as u64;
                let mut bytes = [0u8; FD_MAX_LEN];
                let n = record.len().min(FD_MAX_LEN);
                bytes[..n].copy_from_slice(&record[..n]);
                let pooled = Pooled {
                    vlsd: i,
                    offset,
                    len: record.len(),
                    bytes,
                };
                self.stream.consume(len);
                match self
                    .waiting
                    .iter()
                    .position(|w| w.vlsd == i && w.offset == offset)
                {
                    Some(at) => {
                        if let Some(waiting) = self.waiting.remove(at) {
                            let stored = &pooled.bytes[..pooled.len.min(FD_MAX_LEN)];
                            self.finish(waiting.key, waiting.fields, stored);
                        }
                    }
                    None => {
                        if self.pool.len() == MAX_WAITING {
                            self.pool.pop_front();
                        }
                        self.pool.push_back(pooled);
                    }
                }
            }
            What::Can(i) => {
                let record = self.stream.available().get(id_len..len).unwrap_or_default();
                let can = &mut self.cans[i];
                let index = can.records;
                can.records += 1;
                let fields = fields(&can.group, record, index, self.start_ns);
                let key = Key {
                    ts: fields.ts,
                    dg: self.dg,
                    cg: can.cg,
                    number,
                };
                let mut bytes = [0u8; FD_MAX_LEN];
                let data = match &can.group.data_bytes {
                    Some(DataBytes::Fixed { byte, len: n }) => {
                        let stored = record
                            .get(*byte as usize..)
                            .map(|r| &r[..r.len().min(*n as usize)])
                            .unwrap_or_default();
                        let copy = stored.len().min(FD_MAX_LEN);
                        bytes[..copy].copy_from_slice(&stored[..copy]);
                        Data::Stored(copy)
                    }
                    Some(DataBytes::Signal { offset, .. }) => {
                        Data::Signal(offset.unsigned(record, index).unwrap_or(0))
                    }
                    Some(DataBytes::Group { offset, .. }) => {
                        Data::Group(can.vlsd, offset.unsigned(record, index).unwrap_or(0))
                    }
                    None => Data::Stored(0),
                };
                self.stream.consume(len);
                match data {
                    Data::Stored(n) => self.finish(key, fields, &bytes[..n]),
                    Data::Signal(offset) => self.signal(source, i, key, fields, offset)?,
                    Data::Group(Some(vlsd), offset) => self.vlsd_record(key, fields, vlsd, offset),
                    Data::Group(None, offset) => self.missing(Waiting {
                        key,
                        fields,
                        vlsd: 0,
                        offset,
                    }),
                }
            }
        }
        Ok(())
    }

    /// A frame whose data is VLSD record `offset` of VLSD group `vlsd`:
    /// from the pool, or waiting for it.
    fn vlsd_record(&mut self, key: Key, fields: Fields, vlsd: usize, offset: u64) {
        match self
            .pool
            .iter()
            .position(|p| p.vlsd == vlsd && p.offset == offset)
        {
            Some(at) => {
                if let Some(pooled) = self.pool.remove(at) {
                    let stored = &pooled.bytes[..pooled.len.min(FD_MAX_LEN)];
                    self.finish(key, fields, stored);
                }
            }
            None => {
                if self.waiting.len() == MAX_WAITING {
                    if let Some(oldest) = self.waiting.pop_front() {
                        self.missing(oldest);
                    }
                }
                self.waiting.push_back(Waiting {
                    key,
                    fields,
                    vlsd,
                    offset,
                });
            }
        }
    }

    /// A frame whose VLSD record never came: reported, skipped.
    fn missing(&mut self, waiting: Waiting) {
        self.ready.push_back(Output::Error(LogError::new(
            Some(Position::Record(waiting.key.number)),
            LogErrorKind::Malformed(binary(
                self.stream.offset(),
                BinaryError::MissingVlsd {
                    offset: waiting.offset,
                },
            )),
        )));
    }

    /// A frame whose data is at `offset` of its group's signal data.
    fn signal<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
        i: usize,
        key: Key,
        fields: Fields,
        offset: u64,
    ) -> Result<(), LogError> {
        let Some(signal) = self.cans[i].signal.as_mut() else {
            return Ok(());
        };
        let restart = signal
            .stream
            .as_mut()
            .map_or(true, |stream| !stream.rewind(offset));
        if restart {
            signal.stream = Some(DataStream::new(
                source,
                signal.link,
                self.open_ended,
                self.budget.clone(),
            )?);
        }
        let Some(stream) = signal.stream.as_mut() else {
            return Ok(());
        };
        let mut found = None;
        if stream.skip(source, offset - stream.offset())? && stream.fill(source, 4)? {
            let len = u32::from_le_bytes(padded(stream.available(), 0)) as usize;
            if len <= MAX_RECORD_LEN && stream.fill(source, 4 + len)? {
                let mut bytes = [0u8; FD_MAX_LEN];
                let copy = len.min(FD_MAX_LEN);
                bytes[..copy].copy_from_slice(&stream.available()[4..4 + copy]);
                stream.consume(4 + len);
                found = Some((bytes, len));
            }
        }
        match found {
            Some((bytes, len)) => self.finish(key, fields, &bytes[..len.min(FD_MAX_LEN)]),
            None => self.ready.push_back(Output::Error(LogError::new(
                Some(Position::Record(key.number)),
                LogErrorKind::Malformed(binary(
                    self.stream.offset(),
                    BinaryError::MissingVlsd { offset },
                )),
            ))),
        }
        Ok(())
    }

    /// The frame of `fields` and its stored data (up to 64 bytes), handed
    /// on.
    fn finish(&mut self, key: Key, fields: Fields, stored: &[u8]) {
        let out = match frame(&fields, stored) {
            Ok(frame) => {
                let item = Item { key, frame };
                match &mut self.heap {
                    Some(heap) => {
                        heap.push(Reverse(item));
                        return;
                    }
                    None => Output::Frame(item),
                }
            }
            Err(reason) => Output::Error(LogError::new(
                Some(Position::Record(key.number)),
                LogErrorKind::Malformed(binary(self.stream.offset(), reason)),
            )),
        };
        self.ready.push_back(out);
    }
}

/// The low `bytes` bytes of a u64.
const fn mask(bytes: usize) -> u64 {
    if bytes >= 8 {
        u64::MAX
    } else {
        (1u64 << (8 * bytes)) - 1
    }
}

/// Read a frame's fields from its record (the bytes after the record id),
/// the `index`-th of its group.
fn fields(group: &CanGroup, record: &[u8], index: u64, start_ns: u64) -> Fields {
    let m = &group.members;
    let get = |channel: &Option<crate::logs::mf4::channel::Channel>| {
        channel.as_ref().and_then(|c| c.unsigned(record, index))
    };
    let ts = group.master.as_ref().and_then(|master| {
        let seconds = master.value(record, index)?;
        let ns = (seconds * 1e9).round();
        if !(-9.2e18..9.2e18).contains(&ns) {
            return None;
        }
        let total = start_ns.checked_add_signed(ns as i64)?;
        Timestamp::from_nanos(total / 1_000_000_000, (total % 1_000_000_000) as u32)
    });
    Fields {
        kind: group.kind,
        ts,
        channel: get(&m.bus_channel),
        id: get(&m.id).unwrap_or(0),
        ide: get(&m.ide).map(|v| v != 0),
        dlc: get(&m.dlc).unwrap_or(0),
        data_length: get(&m.data_length),
        dir: get(&m.dir).map(|v| v != 0),
        edl: get(&m.edl).is_some_and(|v| v != 0),
        brs: get(&m.brs).is_some_and(|v| v != 0),
        esi: get(&m.esi).is_some_and(|v| v != 0),
        error_type: get(&m.error_type).unwrap_or(0),
    }
}

/// The frame of docs/formats.md#mf4 from a record's fields and its stored data.
fn frame(fields: &Fields, stored: &[u8]) -> Result<LogFrame<'static>, BinaryError> {
    let frame = match fields.kind {
        FrameKind::Error => {
            // docs/formats.md#mf4: ErrorType 1 bit, 2 form, 3 stuff (byte 2), 4
            // CRC, 5 ACK (byte 3); 0x80 in byte 2 when sent.
            let mut data = [0u8; CLASSIC_MAX_LEN];
            match fields.error_type {
                1 => data[2] = 0x01,
                2 => data[2] = 0x02,
                3 => data[2] = 0x04,
                4 => data[3] = 0x08,
                5 => data[3] = 0x19,
                _ => {}
            }
            if fields.dir == Some(true) {
                data[2] |= 0x80;
            }
            let classes = ErrorClasses::BUS_ERROR.union(ErrorClasses::PROTOCOL);
            CanFrame::new_error(classes.bits(), &data)
        }
        kind => {
            let raw = (fields.id & 0x1FFF_FFFF) as u32;
            let extended = fields.ide.unwrap_or(fields.id & 0x8000_0000 != 0);
            let id = if extended {
                CanId::extended(raw)
            } else {
                CanId::standard(raw)
            }
            .ok_or(BinaryError::BadIdentifier { raw })?;
            let dlc = fields.dlc.min(15) as usize;
            if kind == FrameKind::Remote {
                CanFrame::new_remote(id, dlc.min(CLASSIC_MAX_LEN) as u8)
            } else {
                let length = fields.data_length.map_or_else(
                    || match dlc {
                        0..=8 => dlc,
                        _ => FD_LENGTHS[dlc - 9],
                    },
                    |n| n.min(FD_MAX_LEN as u64) as usize,
                );
                let mut data = [0u8; FD_MAX_LEN];
                if fields.edl {
                    let copy = stored.len().min(length);
                    data[..copy].copy_from_slice(&stored[..copy]);
                    let mut flags = FdFlags::EMPTY;
                    if fields.brs {
                        flags = flags.union(FdFlags::BRS);
                    }
                    if fields.esi {
                        flags = flags.union(FdFlags::ESI);
                    }
                    CanFrame::new_fd(id, flags, &data[..length])
                } else {
                    let length = length.min(CLASSIC_MAX_LEN);
                    let copy = stored.len().min(length);
                    data[..copy].copy_from_slice(&stored[..copy]);
                    CanFrame::new(id, &data[..length])
                }
            }
        }
    }
    .map_err(|_| BinaryError::CanDataTooLong {
        len: fields.data_length.unwrap_or(0).min(255) as u8,
        max: FD_MAX_LEN as u8,
    })?;
    let mut logged = LogFrame::new(frame);
    logged.timestamp = fields.ts;
    logged.iface = match fields.channel {
        Some(channel) => Some(Iface::Channel(
            u16::try_from(channel).map_err(|_| BinaryError::BadLength { length: channel })?,
        )),
        None => None,
    };
    logged.direction = fields
        .dir
        .map(|tx| if tx { Direction::Tx } else { Direction::Rx });
    Ok(logged)
}
