//! The reader on files built here, block by block (ASAM MDF 4.1 §5): the
//! decisions of docs/formats.md#mf4, one test each, and damaged and hostile
//! files (loops, absurd lengths, a DZ block that claims gigabytes, cut files)
//! ending with one clear error after the frames before the damage.

use std::io::Cursor;

use proptest::prelude::*;

use super::Mf4Reader;
use crate::can::{Direction, Iface, LogEvent, LogFrame};
use crate::logs::FormatError;
use crate::logs::{
    BinaryError, LogError, LogErrorKind, OtherRecord, OtherRecords, Position, ReadLog,
};

/// An MDF 4 file built block by block, links patched in afterwards.
pub(crate) struct Builder {
    pub(crate) bytes: Vec<u8>,
}

impl Builder {
    /// The identification block of version `version` (e.g. 411), finalized
    /// or not.
    pub(crate) fn new(version: u16, finalized: bool) -> Self {
        let mut bytes = Vec::with_capacity(4096);
        bytes.extend_from_slice(if finalized { b"MDF     " } else { b"UnFinMF " });
        bytes.extend_from_slice(format!("{}.{:02}    ", version / 100, version % 100).as_bytes());
        bytes.extend_from_slice(b"test    ");
        bytes.resize(28, 0);
        bytes.extend_from_slice(&version.to_le_bytes());
        bytes.resize(64, 0);
        Builder { bytes }
    }

    /// Append a block; return its offset.
    pub(crate) fn block(&mut self, id: &[u8; 2], links: &[u64], data: &[u8]) -> u64 {
        let at = self.bytes.len() as u64;
        let len = 24 + 8 * links.len() + data.len();
        self.bytes.extend_from_slice(b"##");
        self.bytes.extend_from_slice(id);
        self.bytes.extend_from_slice(&[0; 4]);
        self.bytes.extend_from_slice(&(len as u64).to_le_bytes());
        self.bytes
            .extend_from_slice(&(links.len() as u64).to_le_bytes());
        for link in links {
            self.bytes.extend_from_slice(&link.to_le_bytes());
        }
        self.bytes.extend_from_slice(data);
        // Blocks start at multiples of 8.
        while self.bytes.len() % 8 != 0 {
            self.bytes.push(0);
        }
        at
    }

    /// Set the cycle count of the CG block at `cg` (its records).
    pub(crate) fn cycles(&mut self, cg: u64, records: u64) {
        let at = cg as usize + 24 + 8 * 6 + 8;
        self.bytes[at..at + 8].copy_from_slice(&records.to_le_bytes());
    }

    /// Set link `i` of the block at `at`.
    pub(crate) fn link(&mut self, at: u64, i: usize, to: u64) {
        let at = at as usize + 24 + 8 * i;
        self.bytes[at..at + 8].copy_from_slice(&to.to_le_bytes());
    }

    /// A TX block of `text`.
    pub(crate) fn text(&mut self, text: &str) -> u64 {
        let mut data = text.as_bytes().to_vec();
        data.push(0);
        self.block(b"TX", &[], &data)
    }

    /// A CN block: type, sync type, data type, bit offset, byte offset, bit
    /// count; name; composition and conversion links.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn channel(
        &mut self,
        name: &str,
        kind: u8,
        sync: u8,
        data_type: u8,
        bit: u8,
        byte: u32,
        bits: u32,
        composition: u64,
        conversion: u64,
    ) -> u64 {
        let name = self.text(name);
        let mut data = vec![kind, sync, data_type, bit];
        data.extend_from_slice(&byte.to_le_bytes());
        data.extend_from_slice(&bits.to_le_bytes());
        data.resize(72, 0);
        self.block(
            b"CN",
            &[0, composition, name, 0, conversion, 0, 0, 0],
            &data,
        )
    }

    /// Chain the CN blocks at `channels` by their next links; the first.
    pub(crate) fn chain(&mut self, channels: &[u64]) -> u64 {
        for pair in channels.windows(2) {
            self.link(pair[0], 0, pair[1]);
        }
        channels.first().copied().unwrap_or(0)
    }

    /// A CC block of `kind` with `values`.
    pub(crate) fn conversion(&mut self, kind: u8, values: &[f64]) -> u64 {
        let mut data = vec![kind, 0, 0, 0, 0, 0];
        data.extend_from_slice(&(values.len() as u16).to_le_bytes());
        data.resize(24, 0);
        for value in values {
            data.extend_from_slice(&value.to_le_bytes());
        }
        self.block(b"CC", &[0, 0, 0, 0], &data)
    }

    /// A CG block: record id, flags, data bytes; the first channel.
    pub(crate) fn group(&mut self, record_id: u64, flags: u16, data_bytes: u32, first: u64) -> u64 {
        let mut data = record_id.to_le_bytes().to_vec();
        data.extend_from_slice(&0u64.to_le_bytes());
        data.extend_from_slice(&flags.to_le_bytes());
        data.resize(24, 0);
        data.extend_from_slice(&data_bytes.to_le_bytes());
        data.extend_from_slice(&0u32.to_le_bytes());
        self.block(b"CG", &[0, first, 0, 0, 0, 0], &data)
    }
}

/// The record of [`can_group`]: master f64 seconds, ID u32 (bit 31:
/// extended, no IDE member), DLC, DataLength, Dir, ErrorType, 8 data bytes.
pub(crate) const RECORD_LEN: u32 = 24;

/// A record of [`can_group`].
pub(crate) fn record(seconds: f64, id: u32, data: &[u8], tx: bool) -> Vec<u8> {
    let mut record = seconds.to_le_bytes().to_vec();
    record.extend_from_slice(&id.to_le_bytes());
    record.push(data.len() as u8);
    record.push(data.len() as u8);
    record.push(u8::from(tx));
    record.push(0);
    let mut bytes = [0u8; 8];
    bytes[..data.len().min(8)].copy_from_slice(&data[..data.len().min(8)]);
    record.extend_from_slice(&bytes);
    record
}

/// A CAN group of `top` (`CAN_DataFrame`, …) with record id `record_id`
/// and the record of [`record`]; BusChannel virtual (always 3).
pub(crate) fn can_group(file: &mut Builder, top: &str, record_id: u64) -> u64 {
    can_group_with(file, top, record_id, 0)
}

/// [`can_group`], its `DataBytes` VLSD when `signal_data` is a link (to
/// an SD, DZ or DL block): the record's 8 data bytes are then the offset
/// of the frame's data in the signal data.
fn can_group_with(file: &mut Builder, top: &str, record_id: u64, signal_data: u64) -> u64 {
    let member = |file: &mut Builder, name: &str, byte: u32, bits: u32| {
        file.channel(&format!("{top}.{name}"), 0, 0, 0, 0, byte, bits, 0, 0)
    };
    let id = member(file, "ID", 8, 32);
    let dlc = member(file, "DLC", 12, 8);
    let length = member(file, "DataLength", 13, 8);
    let dir = member(file, "Dir", 14, 8);
    let error = member(file, "ErrorType", 15, 8);
    let vlsd = u8::from(signal_data != 0);
    let data = file.channel(&format!("{top}.DataBytes"), vlsd, 0, 10, 0, 16, 64, 0, 0);
    file.link(data, 5, signal_data);
    let three = file.conversion(1, &[3.0, 0.0]);
    let bus = file.channel(&format!("{top}.BusChannel"), 6, 0, 0, 0, 0, 0, 0, three);
    let members = file.chain(&[bus, id, dlc, length, dir, error, data]);
    let master = file.channel("Timestamp", 2, 1, 4, 0, 0, 64, 0, 0);
    let frame = file.channel(top, 0, 0, 10, 0, 8, 128, members, 0);
    let first = file.chain(&[master, frame]);
    file.group(record_id, 0x6, RECORD_LEN, first)
}

/// How the data are stored.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Storage {
    Dt,
    /// A DT whose length is its header (CANedge): runs to the end.
    Unfinalized,
    Dz,
    DzTransposed,
    /// Two DT blocks in a DL.
    List,
}

/// A file of one data group with record id size `id_len`, the channel
/// groups `groups` (top channel, record id) and `data` stored as `storage`;
/// start time 1 700 000 000 s.
pub(crate) fn file(id_len: u8, groups: &[(&str, u64)], data: &[u8], storage: Storage) -> Vec<u8> {
    let mut file = Builder::new(411, storage != Storage::Unfinalized);
    let mut hd = 1_700_000_000_000_000_000u64.to_le_bytes().to_vec();
    hd.resize(32, 0);
    let hd = file.block(b"HD", &[0, 0, 0, 0, 0, 0], &hd);
    assert_eq!(hd, 64);
    let cgs: Vec<u64> = groups
        .iter()
        .map(|(top, id)| can_group(&mut file, top, *id))
        .collect();
    for pair in cgs.windows(2) {
        file.link(pair[0], 0, pair[1]);
    }
    // Each group's cycle count is at least its records (every record, a
    // cut one too): the data decide where the records end.
    let records = data
        .len()
        .div_ceil(usize::from(id_len) + RECORD_LEN as usize) as u64;
    for &cg in &cgs {
        file.cycles(cg, records);
    }
    let mut dg = vec![id_len];
    dg.resize(8, 0);
    let dg = file.block(b"DG", &[0, cgs.first().copied().unwrap_or(0), 0, 0], &dg);
    file.link(hd, 0, dg);
    let data_link = match storage {
        Storage::Dt => file.block(b"DT", &[], data),
        Storage::Dz | Storage::DzTransposed => {
            let transposed = storage == Storage::DzTransposed;
            let columns = RECORD_LEN as usize;
            let plain: Vec<u8> = if transposed {
                let rows = data.len() / columns;
                let mut out = vec![0; rows * columns];
                for row in 0..rows {
                    for column in 0..columns {
                        out[column * rows + row] = data[row * columns + column];
                    }
                }
                out.extend_from_slice(&data[rows * columns..]);
                out
            } else {
                data.to_vec()
            };
            let mut encoder =
                flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
            std::io::Write::write_all(&mut encoder, &plain).unwrap();
            let compressed = encoder.finish().unwrap();
            let mut dz = b"DT".to_vec();
            dz.push(u8::from(transposed));
            dz.push(0);
            dz.extend_from_slice(&(columns as u32).to_le_bytes());
            dz.extend_from_slice(&(data.len() as u64).to_le_bytes());
            dz.extend_from_slice(&(compressed.len() as u64).to_le_bytes());
            dz.extend_from_slice(&compressed);
            file.block(b"DZ", &[], &dz)
        }
        Storage::List => {
            // Split inside a record: records run on from block to block.
            let half = data.len() / 2 + 3;
            let first = file.block(b"DT", &[], &data[..half.min(data.len())]);
            let second = file.block(b"DT", &[], data.get(half..).unwrap_or_default());
            let mut dl = vec![0u8; 8];
            dl[4..8].copy_from_slice(&2u32.to_le_bytes());
            file.block(b"DL", &[0, first, second], &dl)
        }
        Storage::Unfinalized => {
            let at = file.bytes.len() as u64;
            file.block(b"DT", &[], &[]);
            // No padding: the data run from the header to the end.
            file.bytes.truncate(at as usize + 24);
            file.link(dg, 2, at);
            file.bytes.extend_from_slice(data);
            return file.bytes;
        }
    };
    file.link(dg, 2, data_link);
    file.bytes
}

/// A frame with its record number, or an error.
type Event = Result<(u64, LogFrame<'static>), LogError>;

/// Every event of `bytes`: frames, and errors as their reasons.
fn read_all(bytes: &[u8]) -> Result<Vec<Event>, LogError> {
    let mut reader = Mf4Reader::new(Cursor::new(bytes.to_vec()))?;
    let mut out = Vec::new();
    while let Some(next) = reader.next_event() {
        out.push(next.map(|record| {
            let LogEvent::Frame(frame) = record.event else {
                panic!("MF4 has no status events")
            };
            let iface = frame.iface.map(|iface| match iface {
                Iface::Channel(c) => Iface::Channel(c),
                Iface::Name(_) => panic!("MF4 names no interface"),
            });
            (record.position.number(), LogFrame { iface, ..frame })
        }));
    }
    Ok(out)
}

fn reason(error: &LogError) -> BinaryError {
    match error.kind() {
        LogErrorKind::Damaged(FormatError::Binary { reason, .. })
        | LogErrorKind::Malformed(FormatError::Binary { reason, .. }) => *reason,
        other => panic!("not a binary error: {other:?}"),
    }
}

fn two_frames() -> Vec<u8> {
    let mut data = record(0.25, 0x081, &[1, 2, 3], false);
    data.extend(record(0.5, 0x8000_1234, &[9; 8], true));
    data
}

#[test]
fn reads_frames_in_every_storage() {
    for storage in [
        Storage::Dt,
        Storage::Unfinalized,
        Storage::Dz,
        Storage::DzTransposed,
        Storage::List,
    ] {
        let bytes = file(0, &[("CAN_DataFrame", 0)], &two_frames(), storage);
        let frames = read_all(&bytes).unwrap();
        let [Ok((1, first)), Ok((2, second))] = &frames[..] else {
            panic!("{storage:?}: {frames:?}")
        };
        assert_eq!(
            first.to_string(),
            "(1700000000.250000) 3 081#010203 R",
            "{storage:?}"
        );
        // Bit 31 of ID without IDE: extended.
        assert_eq!(
            second.to_string(),
            "(1700000000.500000) 3 00001234#0909090909090909 T",
            "{storage:?}"
        );
        assert_eq!(second.iface, Some(Iface::Channel(3)));
        assert_eq!(second.direction, Some(Direction::Tx));
    }
}

#[test]
fn a_cut_record_is_dropped_and_counted() {
    let mut data = two_frames();
    data.truncate(data.len() - 5);
    let bytes = file(0, &[("CAN_DataFrame", 0)], &data, Storage::Unfinalized);
    let mut reader = Mf4Reader::new(Cursor::new(bytes)).unwrap();
    assert!(reader.next_event().unwrap().is_ok());
    let error = reader.next_event().unwrap().unwrap_err();
    assert!(error.is_skipped());
    assert_eq!(error.position(), Some(Position::Record(2)));
    assert_eq!(
        reason(&error),
        BinaryError::Truncated {
            needed: 24,
            found: 19
        }
    );
    assert!(reader.next_event().is_none());
    assert_eq!(reader.skipped(), 1);
}

#[test]
fn an_unknown_record_id_ends_its_data_group() {
    let mut data = vec![1];
    data.extend(record(0.25, 0x081, &[1], false));
    data.push(7);
    data.extend(record(0.5, 0x082, &[2], false));
    let bytes = file(1, &[("CAN_DataFrame", 1)], &data, Storage::Dt);
    let events = read_all(&bytes).unwrap();
    assert_eq!(events.len(), 2, "{events:?}");
    assert!(events[0].is_ok());
    let error = events[1].as_ref().unwrap_err();
    assert!(error.is_skipped());
    assert_eq!(reason(error), BinaryError::UnknownRecordId { id: 7 });
    assert_eq!(error.position(), Some(Position::Record(2)));
}

#[test]
fn channel_groups_of_one_data_group_merged_by_time() {
    // CANedge ≥ 01.07: one group per kind, the second's records late.
    let mut data = Vec::new();
    for (id, seconds, can_id) in [
        (1, 0.1, 0x101),
        (1, 0.3, 0x103),
        (2, 0.2, 0x202),
        (1, 0.4, 0x104),
        (2, 0.3, 0x203),
    ] {
        data.push(id);
        data.extend(record(seconds, can_id, &[], false));
    }
    let bytes = file(
        1,
        &[("CAN_DataFrame", 1), ("CAN_RemoteFrame", 2)],
        &data,
        Storage::Dt,
    );
    let events = read_all(&bytes).unwrap();
    let order: Vec<(u64, u32)> = events
        .iter()
        .map(|e| {
            let (n, f) = e.as_ref().unwrap();
            (*n, f.frame.id().raw())
        })
        .collect();
    // Equal times: the first channel group first.
    assert_eq!(
        order,
        [(1, 0x101), (3, 0x202), (2, 0x103), (5, 0x203), (4, 0x104)]
    );
    assert!(events[1].as_ref().unwrap().1.frame.is_rtr());
}

/// docs/formats.md#mf4: records of groups without CAN frames are counted
/// by group name, as `other_kinds` says them, and up to date with each
/// event handed out.
#[test]
fn other_groups_are_said_by_name() {
    let mut data = Vec::new();
    for (id, seconds, can_id) in [
        (2, 0.1, 0x11),
        (1, 0.2, 0x101),
        (2, 0.3, 0x12),
        (2, 0.4, 0x13),
        (3, 0.5, 0x14),
        (1, 0.6, 0x102),
    ] {
        data.push(id);
        data.extend(record(seconds, can_id, &[], false));
    }
    let bytes = file(
        1,
        &[("CAN_DataFrame", 1), ("LIN_Frame", 2), ("Line\nBreak", 3)],
        &data,
        Storage::Dt,
    );
    let mut reader = Mf4Reader::new(Cursor::new(bytes)).unwrap();
    assert!(reader.other_kinds().is_empty());
    let lin = |count| OtherRecords {
        kind: OtherRecord::Mf4Group("LIN_Frame".into()),
        count,
    };
    let first = reader.next_event().unwrap().unwrap();
    assert_eq!(first.position, Position::Record(2));
    // The LIN record before it.
    assert_eq!(reader.other_kinds(), [lin(1)]);
    assert_eq!(reader.other_records(), 1);
    let second = reader.next_event().unwrap().unwrap();
    assert_eq!(second.position, Position::Record(6));
    assert!(reader.next_event().is_none());
    let odd = OtherRecords {
        kind: OtherRecord::Mf4Group("Line\nBreak".into()),
        count: 1,
    };
    assert_eq!(reader.other_kinds(), [lin(3), odd.clone()]);
    assert_eq!(reader.other_records(), 4);
    assert_eq!(
        reader.other_groups(),
        [("LIN_Frame".to_string(), 3), ("Line\nBreak".to_string(), 1)]
    );
    // Said on one line whatever the name holds.
    assert_eq!(
        odd.to_string(),
        "1 MF4 record of group Line\\nBreak skipped: not CAN"
    );
}

/// A data group of other groups only is counted when the file is opened.
#[test]
fn a_data_group_without_frames_is_counted_when_opened() {
    let mut data = Vec::new();
    for seconds in [0.1, 0.2] {
        data.extend(record(seconds, 0x11, &[], false));
    }
    let bytes = file(0, &[("LIN_Frame", 0)], &data, Storage::Dt);
    let mut reader = Mf4Reader::new(Cursor::new(bytes)).unwrap();
    let lin = OtherRecords {
        kind: OtherRecord::Mf4Group("LIN_Frame".into()),
        count: 2,
    };
    assert_eq!(reader.other_kinds(), core::slice::from_ref(&lin));
    assert!(reader.next_event().is_none());
    assert_eq!(reader.other_kinds(), [lin]);
    assert_eq!(reader.other_records(), 2);
}

#[test]
fn error_frames_as_spec_5_8_maps_error_type() {
    // ErrorType → (byte 2, byte 3), received and sent.
    let table = [
        (0u8, false, [0x00, 0x00]),
        (1, false, [0x01, 0x00]),
        (2, false, [0x02, 0x00]),
        (3, false, [0x04, 0x00]),
        (4, false, [0x00, 0x08]),
        (5, false, [0x00, 0x19]),
        (6, false, [0x00, 0x00]),
        (1, true, [0x81, 0x00]),
        (5, true, [0x80, 0x19]),
    ];
    let mut data = Vec::new();
    for (i, &(error_type, tx, _)) in table.iter().enumerate() {
        let mut r = record(i as f64, 0x123, &[0xAA; 8], tx);
        r[15] = error_type;
        data.extend(r);
    }
    let bytes = file(0, &[("CAN_ErrorFrame", 0)], &data, Storage::Dt);
    let events = read_all(&bytes).unwrap();
    for (event, (error_type, tx, bytes)) in events.iter().zip(table) {
        let frame = event.as_ref().unwrap().1.frame;
        assert!(frame.is_error());
        // Classes bus_error (0x80) | protocol (0x08).
        assert_eq!(frame.id().raw(), 0x88);
        assert_eq!(
            &frame.data()[2..4],
            bytes,
            "ErrorType {error_type}, tx {tx}"
        );
    }
}

#[test]
fn a_standard_identifier_above_0x7ff_is_one_error() {
    let mut data = record(0.1, 0x800, &[], false);
    data.extend(record(0.2, 0x7FF, &[], false));
    let bytes = file(0, &[("CAN_DataFrame", 0)], &data, Storage::Dt);
    let events = read_all(&bytes).unwrap();
    assert_eq!(
        reason(events[0].as_ref().unwrap_err()),
        BinaryError::BadIdentifier { raw: 0x800 }
    );
    assert_eq!(events[1].as_ref().unwrap().1.frame.id().raw(), 0x7FF);
}

#[test]
fn damaged_headers() {
    let good = file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::Dt);
    let damage = |at: usize, bytes: &[u8]| {
        let mut file = good.clone();
        file[at..at + bytes.len()].copy_from_slice(bytes);
        reason(&Mf4Reader::new(Cursor::new(file)).unwrap_err())
    };
    assert_eq!(
        damage(0, b"MDF3    "),
        BinaryError::BadMagic {
            found: u32::from_le_bytes(*b"MDF3")
        }
    );
    assert_eq!(
        damage(28, &330u16.to_le_bytes()),
        BinaryError::UnsupportedVersion {
            major: 3,
            minor: 30
        }
    );
    // HD's first data group link out of the file.
    assert_eq!(
        damage(64 + 24, &(1u64 << 40).to_le_bytes()),
        BinaryError::LinkOutOfFile {
            link: 1 << 40,
            len: good.len() as u64
        }
    );
    // ... to the HD itself: no data group.
    assert!(matches!(
        damage(64 + 24, &64u64.to_le_bytes()),
        BinaryError::UnexpectedBlock {
            expected: "##DG",
            ..
        }
    ));
    // The file cut inside its identification block.
    let error = Mf4Reader::new(Cursor::new(good[..40].to_vec())).unwrap_err();
    assert_eq!(
        reason(&error),
        BinaryError::Truncated {
            needed: 64,
            found: 40
        }
    );
}

/// The offset of the first block `##{id}` of `bytes`.
fn find(bytes: &[u8], id: &[u8; 2]) -> usize {
    let want = [b'#', b'#', id[0], id[1]];
    (0..bytes.len() - 4)
        .step_by(8)
        .find(|&at| bytes[at..at + 4] == want)
        .unwrap()
}

#[test]
fn loops_end_with_one_error() {
    let good = file(
        1,
        &[("CAN_DataFrame", 1), ("CAN_RemoteFrame", 2)],
        &[],
        Storage::Dt,
    );
    // The data group's next link to itself; the channel group's next link
    // to itself; a channel's next link to itself.
    for id in [b"DG", b"CG", b"CN"] {
        let mut bytes = good.clone();
        let at = find(&bytes, id);
        bytes[at + 24..at + 32].copy_from_slice(&(at as u64).to_le_bytes());
        let error = Mf4Reader::new(Cursor::new(bytes)).unwrap_err();
        assert_eq!(reason(&error), BinaryError::LinkLoop, "{id:?}");
    }
    // A data list whose next link is itself: the reading ends (the cycle
    // count claims a third record, so the reader looks for it).
    let mut bytes = file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::List);
    let at = find(&bytes, b"DL");
    bytes[at + 24..at + 32].copy_from_slice(&(at as u64).to_le_bytes());
    let cg = find(&bytes, b"CG") + 80;
    bytes[cg..cg + 8].copy_from_slice(&3u64.to_le_bytes());
    let events = read_all(&bytes).unwrap();
    let last = events.last().unwrap().as_ref().unwrap_err();
    assert_eq!(reason(last), BinaryError::LinkLoop);
    assert!(!last.is_skipped());
    // A data list that names its first data block again, in place of the
    // second: the records of the first block, then the loop (read again,
    // such a list could repeat a block without end).
    let mut bytes = file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::List);
    let at = find(&bytes, b"DL");
    let first = bytes[at + 32..at + 40].to_vec();
    bytes[at + 40..at + 48].copy_from_slice(&first);
    let events = read_all(&bytes).unwrap();
    let [Ok((1, frame)), Err(last)] = &events[..] else {
        panic!("{events:?}");
    };
    assert_eq!(frame.frame.id().raw(), 0x081);
    assert_eq!(reason(last), BinaryError::LinkLoop);
    assert!(!last.is_skipped());
}

#[test]
fn a_dz_block_that_claims_gigabytes() {
    let good = file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::Dz);
    let at = find(&good, b"DZ") + 24;
    // Original length: 4 GiB.
    let mut bytes = good.clone();
    bytes[at + 8..at + 16].copy_from_slice(&(4u64 << 30).to_le_bytes());
    let events = read_all(&bytes).unwrap();
    assert_eq!(
        reason(events[0].as_ref().unwrap_err()),
        BinaryError::TooLarge {
            length: 4 << 30,
            limit: crate::logs::MAX_RECORD_LEN as u64
        }
    );
    // An original length that the data do not inflate to.
    let mut bytes = good.clone();
    bytes[at + 8..at + 16].copy_from_slice(&1000u64.to_le_bytes());
    let events = read_all(&bytes).unwrap();
    assert_eq!(
        reason(events[0].as_ref().unwrap_err()),
        BinaryError::Decompression
    );
    // zstd (asammdf's zip type 2): unsupported.
    let mut bytes = good;
    bytes[at + 2] = 2;
    let events = read_all(&bytes).unwrap();
    assert_eq!(
        reason(events[0].as_ref().unwrap_err()),
        BinaryError::UnsupportedCompression { method: 2 }
    );
}

#[test]
fn a_dz_block_holds_more_records_than_the_file_has_bytes() {
    // 20 000 records of one frame, deflated: every one is read, although
    // the file is far shorter than their number (the fuzz target bounds
    // events by the bytes read and inflated, not by the file's length).
    let data: Vec<u8> = (0..20_000)
        .flat_map(|_| record(0.25, 0x081, &[1, 2, 3], false))
        .collect();
    let bytes = file(0, &[("CAN_DataFrame", 0)], &data, Storage::Dz);
    assert!(bytes.len() < 20_000 / 4, "{} bytes", bytes.len());
    let events = read_all(&bytes).unwrap();
    assert_eq!(events.len(), 20_000);
    assert!(events
        .iter()
        .all(|e| matches!(e, Ok((_, frame)) if frame.frame.data() == [1, 2, 3])));
}

/// Signal data entries (a u32 length, the bytes) in one block.
fn entries(data: &[&[u8]]) -> Vec<u8> {
    let mut out = Vec::new();
    for bytes in data {
        out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
        out.extend_from_slice(bytes);
    }
    out
}

/// A DZ block of `plain` (an SD block deflated); `compressed` replaces the
/// deflated bytes when given.
fn dz_block(file: &mut Builder, plain: &[u8], compressed: Option<&[u8]>) -> u64 {
    let mut encoder = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    std::io::Write::write_all(&mut encoder, plain).unwrap();
    let deflated = encoder.finish().unwrap();
    let compressed = compressed.unwrap_or(&deflated);
    let mut dz = b"SD".to_vec();
    dz.extend_from_slice(&[0; 6]);
    dz.extend_from_slice(&(plain.len() as u64).to_le_bytes());
    dz.extend_from_slice(&(compressed.len() as u64).to_le_bytes());
    dz.extend_from_slice(compressed);
    file.block(b"DZ", &[], &dz)
}

/// A file of one CAN group whose `DataBytes` are VLSD in the signal data
/// `signal` leads to (built by `signal` on the file), one frame (id 0x100)
/// for each of `frames`: the offset of its data and their length.
fn vlsd_file(signal: impl FnOnce(&mut Builder) -> u64, frames: &[(u64, u8)]) -> Vec<u8> {
    let mut file = Builder::new(411, true);
    let mut hd = 1_700_000_000_000_000_000u64.to_le_bytes().to_vec();
    hd.resize(32, 0);
    let hd = file.block(b"HD", &[0, 0, 0, 0, 0, 0], &hd);
    let sd = signal(&mut file);
    let cg = can_group_with(&mut file, "CAN_DataFrame", 0, sd);
    file.cycles(cg, frames.len() as u64);
    let mut data = Vec::new();
    for (i, (offset, length)) in frames.iter().enumerate() {
        let mut record = record(i as f64, 0x100, &[0; 8], false);
        record[13] = *length;
        record[16..24].copy_from_slice(&offset.to_le_bytes());
        data.extend(record);
    }
    let dt = file.block(b"DT", &[], &data);
    let mut dg = vec![0u8];
    dg.resize(8, 0);
    let dg = file.block(b"DG", &[0, cg, dt, 0], &dg);
    file.link(hd, 0, dg);
    file.bytes
}

/// Every frame's data; the bytes read after the file was opened.
fn vlsd_read(bytes: &[u8]) -> (Vec<Vec<u8>>, u64) {
    let mut reader = Mf4Reader::new(Cursor::new(bytes.to_vec())).unwrap();
    let opened = reader.bytes_read();
    let mut read = Vec::new();
    while let Some(event) = reader.next_event() {
        read.push(event.unwrap().event.frame().unwrap().frame.data().to_vec());
    }
    (read, reader.bytes_read() - opened)
}

#[test]
fn vlsd_offsets_that_go_back_read_the_same_data() {
    // Signal data of two entries, deflated; records that point at them
    // out of order, back to the first again and again.
    let (one, two) = (&[1u8, 2, 3][..], &[7u8, 8][..]);
    let signal = entries(&[one, two]);
    let frames = [(0, 3), (7, 2), (0, 3), (0, 3), (7, 2), (0, 3)];
    let bytes = vlsd_file(|file| dz_block(file, &signal, None), &frames);
    let (read, data_read) = vlsd_read(&bytes);
    assert_eq!(read, [one, two, one, one, two, one]);
    // Each going back found the entry among the bytes held: the records
    // and the DZ block were read once, not the DZ block again for every
    // record that goes back (reading a block reads its 24-byte header;
    // the DZ block's is read when its stream starts too, and its zip
    // header is 24 bytes more).
    let records = frames.len() * RECORD_LEN as usize;
    let dz = find(&bytes, b"DZ");
    let compressed = u64::from_le_bytes(bytes[dz + 40..dz + 48].try_into().unwrap());
    let once = (24 + records) as u64 + (3 * 24 + compressed);
    assert_eq!(data_read, once);
}

#[test]
fn vlsd_data_skipped_over_is_not_inflated() {
    // Signal data in a data list of two DZ blocks; the frames' data all
    // lie in the second. The first is passed over by its header's
    // length: its deflated bytes (here not deflate at all) are never
    // inflated, also when a frame goes back to an entry of the second.
    let first = entries(&[&[1, 2, 3], &[4, 5]]);
    let second = entries(&[&[7, 8], &[9]]);
    let at = first.len() as u64;
    let two_blocks = |frames: &[(u64, u8)]| {
        vlsd_file(
            |file| {
                let a = dz_block(file, &first, Some(&[0xFF; 16]));
                let b = dz_block(file, &second, None);
                let mut dl = vec![0u8; 8];
                dl[4..8].copy_from_slice(&2u32.to_le_bytes());
                file.block(b"DL", &[0, a, b], &dl)
            },
            frames,
        )
    };
    let (read, _) = vlsd_read(&two_blocks(&[(at, 2), (at + 6, 1), (at, 2)]));
    assert_eq!(read, [&[7u8, 8][..], &[9], &[7, 8]]);
    // A frame whose data lie in the first block inflates it: damaged.
    let events = read_all(&two_blocks(&[(at, 2), (0, 3)])).unwrap();
    let [Ok((1, frame)), Err(damaged)] = &events[..] else {
        panic!("{events:?}");
    };
    assert_eq!(frame.frame.data(), [7, 8]);
    assert_eq!(reason(damaged), BinaryError::Decompression);
}

#[test]
fn vlsd_data_past_a_block_cut_by_the_end_of_the_file_is_missing() {
    // Signal data in a data list: a DZ block, then a DT block at the end
    // of the file whose links (two, says its header) lie past it. A frame
    // whose data would lie in the DT has none; skipping to it passes the
    // DZ block and an empty DT.
    let first = entries(&[&[1, 2, 3]]);
    let at = first.len() as u64;
    let mut list = 0;
    let mut bytes = vlsd_file(
        |file| {
            let dz = dz_block(file, &first, None);
            let mut dl = vec![0u8; 8];
            dl[4..8].copy_from_slice(&2u32.to_le_bytes());
            list = file.block(b"DL", &[0, dz, 0], &dl);
            list
        },
        &[(0, 3), (at + 5, 2)],
    );
    // The DL's second data link: the DT appended here.
    let dt = bytes.len() as u64;
    let link = list as usize + 24 + 2 * 8;
    bytes[link..link + 8].copy_from_slice(&dt.to_le_bytes());
    bytes.extend_from_slice(b"##DT\0\0\0\0");
    bytes.extend_from_slice(&40u64.to_le_bytes());
    bytes.extend_from_slice(&2u64.to_le_bytes());
    let events = read_all(&bytes).unwrap();
    let [Ok((1, frame)), Err(missing)] = &events[..] else {
        panic!("{events:?}");
    };
    assert_eq!(frame.frame.data(), [1, 2, 3]);
    assert_eq!(reason(missing), BinaryError::MissingVlsd { offset: at + 5 });
    assert!(missing.is_skipped());
}

#[test]
fn streams_read_as_files() {
    let bytes = file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::Dz);
    let mut from_stream = Mf4Reader::from_stream(&bytes[..]).unwrap();
    let mut from_file = Mf4Reader::new(Cursor::new(bytes.clone())).unwrap();
    loop {
        let a = from_stream.next_event().map(|e| format!("{e:?}"));
        let b = from_file.next_event().map(|e| format!("{e:?}"));
        assert_eq!(a, b);
        if a.is_none() {
            break;
        }
    }
    assert_eq!(from_stream.bytes_read(), from_file.bytes_read());
}

/// The fixtures the property tests damage.
fn fixtures() -> Vec<Vec<u8>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/mf4/");
    ["python_can.mf4", "canedge_vlsd.mf4", "asammdf_many.mf4"]
        .iter()
        .map(|name| std::fs::read(format!("{dir}{name}")).unwrap())
        .chain([
            file(
                1,
                &[("CAN_DataFrame", 1), ("CAN_ErrorFrame", 2)],
                &[],
                Storage::Dt,
            ),
            file(
                0,
                &[("CAN_DataFrame", 0)],
                &two_frames(),
                Storage::DzTransposed,
            ),
            file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::List),
        ])
        .collect()
}

/// Read to the end: no panic, and nothing after an error that ends it.
fn drain(bytes: Vec<u8>) -> Result<(), TestCaseError> {
    if let Ok(mut reader) = Mf4Reader::new(Cursor::new(bytes)) {
        let mut events = 0u64;
        while let Some(next) = reader.next_event() {
            events += 1;
            if let Err(error) = next {
                if !error.is_skipped() {
                    prop_assert!(reader.next_event().is_none());
                    break;
                }
            }
            // Each record read at most once, plus the errors.
            prop_assert!(events <= 1 + 2 * reader.bytes_read().max(1));
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any bytes after the magic: a typed error or an end, no panic.
    #[test]
    fn any_bytes_after_the_magic(rest in proptest::collection::vec(any::<u8>(), 0..2048)) {
        let mut bytes = b"MDF     4.10    ".to_vec();
        bytes.extend(rest);
        drain(bytes)?;
    }

    /// The fixtures with bytes changed, cut, or both.
    #[test]
    fn damaged_fixtures(
        which in 0usize..6,
        changes in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
        cut in proptest::option::of(any::<prop::sample::Index>()),
    ) {
        let mut bytes = fixtures().swap_remove(which);
        for (at, value) in changes {
            let at = at.index(bytes.len());
            bytes[at] = value;
        }
        if let Some(cut) = cut {
            bytes.truncate(cut.index(bytes.len()));
        }
        drain(bytes)?;
    }
}

/// docs/formats.md#mf4: in a finalized file a group's cycle count bounds
/// its records (the bytes after them are none, as asammdf reads them) and
/// a DT block's length is its data; in an unfinalized file the data decide.
#[test]
fn cycle_counts_and_block_lengths_of_a_finalized_file() {
    let mut bytes = file(0, &[("CAN_DataFrame", 0)], &two_frames(), Storage::Dt);
    let cg = find(&bytes, b"CG") + 80;
    bytes[cg..cg + 8].copy_from_slice(&1u64.to_le_bytes());
    let frames = read_all(&bytes).unwrap();
    let [Ok((1, frame))] = &frames[..] else {
        panic!("{frames:?}")
    };
    assert_eq!(frame.frame.id().raw(), 0x081);
    // The same file unfinalized (flag: cycle counters not updated): both.
    bytes[60] = 1;
    assert_eq!(read_all(&bytes).unwrap().len(), 2);

    // An empty group: cycle count 0, a DT of its header only, before the
    // records of the file's last bytes.
    let mut bytes = file(0, &[("CAN_DataFrame", 0)], &[], Storage::Dt);
    let dt = find(&bytes, b"DT");
    assert_eq!(bytes[dt + 8], 24);
    bytes.extend(two_frames());
    let events = read_all(&bytes).unwrap();
    assert!(events.is_empty(), "{events:?}");
    // Unfinalized, the DT of no length runs to the end of the file.
    bytes[..8].copy_from_slice(b"UnFinMF ");
    assert_eq!(read_all(&bytes).unwrap().len(), 2);
}
