//! ASAM MDF 4 files written by the real writers — python-can's `MF4Writer`,
//! asammdf, two CANedge loggers — and read back by python-can's
//! `MF4Reader` (asammdf underneath; `scripts/gen_mf4_fixtures.py`): the
//! crate reads every frame as python-can does — in the same order,
//! identifier, flags, DLC, data, channel, direction, time to the
//! microsecond (python-can computes it in floats).
//!
//! Documented differences (docs/formats.md#mf4, `motionwire::logs::mf4`'s
//! decisions): an error frame is Linux's layout of its `ErrorType`, not
//! python-can's identifier and data; a classic frame carries at most 8
//! bytes (python-can hands on `DataLength` bytes).

use std::fs::File;
use std::io::Read;

use motionwire::can::{Direction, FdFlags, Iface, LogEvent, LogFrame};
use motionwire::logs::mf4::Mf4Reader;
use motionwire::logs::{self, LogFormat, Position, ReadLog};
use serde_json::Value;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/mf4/");

/// The fixture's path and python-can's reading of it (short rows in a
/// `.json.gz`, objects in a `.json`), as objects.
fn truth(name: &str) -> (String, Vec<Value>) {
    let path = format!("{DIR}{name}.mf4");
    let json = format!("{DIR}{name}.json");
    let truth: Value = match std::fs::read(&json) {
        Ok(bytes) => serde_json::from_slice(&bytes).unwrap(),
        Err(_) => {
            let mut text = String::new();
            flate2::read::GzDecoder::new(File::open(format!("{json}.gz")).unwrap())
                .read_to_string(&mut text)
                .unwrap();
            serde_json::from_str(&text).unwrap()
        }
    };
    const KEYS: [&str; 12] = [
        "timestamp",
        "channel",
        "id",
        "extended",
        "rtr",
        "fd",
        "brs",
        "esi",
        "error",
        "dlc",
        "data",
        "rx",
    ];
    let frames = truth["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|frame| match frame {
            Value::Array(row) => Value::Object(
                KEYS.iter()
                    .zip(row)
                    .map(|(k, v)| ((*k).to_owned(), v.clone()))
                    .collect(),
            ),
            other => other.clone(),
        })
        .collect();
    (path, frames)
}

/// Every event of the file, read through `logs::open`.
fn read(path: &str) -> (Vec<(u64, LogFrame<'static>)>, u64, u64) {
    let mut log = logs::open(path).unwrap();
    assert_eq!(log.format(), LogFormat::Mf4);
    let mut out = Vec::new();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        let Position::Record(number) = record.position else {
            panic!("MF4 positions are records")
        };
        let LogEvent::Frame(frame) = record.event else {
            panic!("MF4 has no status events")
        };
        let iface = frame.iface.map(|i| match i {
            Iface::Channel(c) => Iface::Channel(c),
            Iface::Name(_) => panic!("MF4 names no interface"),
        });
        out.push((number, LogFrame { iface, ..frame }));
    }
    (out, log.other_records(), log.skipped())
}

fn seconds(frame: &LogFrame<'_>) -> f64 {
    let ts = frame.timestamp.unwrap();
    ts.secs() as f64 + f64::from(ts.subsec_nanos()) * 1e-9
}

/// Check `ours` against python-can's reading, frame for frame.
fn same_as_python_can(name: &str, ours: &[(u64, LogFrame<'static>)], theirs: &[Value]) {
    assert_eq!(ours.len(), theirs.len(), "{name}: frames");
    for (i, ((_, ours), theirs)) in ours.iter().zip(theirs).enumerate() {
        let at = format!("{name} frame {i}: {ours} vs {theirs}");
        let time: f64 = theirs["timestamp"].as_str().unwrap().parse().unwrap();
        assert!((seconds(ours) - time).abs() < 1e-6, "{at}: time");
        let channel = theirs["channel"].as_u64().map(|c| Iface::Channel(c as u16));
        assert_eq!(ours.iface, channel, "{at}: channel");
        let tx = !theirs["rx"].as_bool().unwrap();
        assert_eq!(
            ours.direction,
            Some(if tx { Direction::Tx } else { Direction::Rx }),
            "{at}: direction"
        );
        let frame = &ours.frame;
        assert_eq!(frame.is_error(), theirs["error"].as_bool().unwrap(), "{at}");
        if frame.is_error() {
            // docs/formats.md#mf4: classes bus_error | protocol, data from
            // ErrorType.
            assert_eq!(frame.id().raw(), 0x88, "{at}");
            continue;
        }
        assert_eq!(
            u64::from(frame.id().raw()),
            theirs["id"].as_u64().unwrap(),
            "{at}"
        );
        assert_eq!(
            frame.is_extended(),
            theirs["extended"].as_bool().unwrap(),
            "{at}"
        );
        assert_eq!(frame.is_rtr(), theirs["rtr"].as_bool().unwrap(), "{at}");
        assert_eq!(frame.is_fd(), theirs["fd"].as_bool().unwrap(), "{at}");
        let flags = frame.fd_flags();
        assert_eq!(
            flags.contains(FdFlags::BRS),
            theirs["brs"].as_bool().unwrap(),
            "{at}"
        );
        assert_eq!(
            flags.contains(FdFlags::ESI),
            theirs["esi"].as_bool().unwrap(),
            "{at}"
        );
        let data = theirs["data"].as_str().unwrap();
        let data: Vec<u8> = (0..data.len() / 2)
            .map(|i| u8::from_str_radix(&data[2 * i..2 * i + 2], 16).unwrap())
            .collect();
        if frame.is_rtr() {
            assert_eq!(
                u64::from(frame.dlc()),
                theirs["dlc"].as_u64().unwrap(),
                "{at}"
            );
            assert!(frame.data().is_empty(), "{at}");
        } else if frame.is_fd() {
            assert_eq!(frame.data(), data, "{at}");
        } else {
            // docs/formats.md#mf4: at most 8 bytes in a classic frame.
            assert_eq!(frame.data(), &data[..data.len().min(8)], "{at}");
        }
    }
}

fn fixture(name: &str) -> (Vec<(u64, LogFrame<'static>)>, u64, u64) {
    let (path, theirs) = truth(name);
    let (ours, others, skipped) = read(&path);
    same_as_python_can(name, &ours, &theirs);
    (ours, others, skipped)
}

#[test]
fn python_can_mf4_writer_transposed_deflate() {
    let (frames, others, skipped) = fixture("python_can");
    assert_eq!((frames.len(), others, skipped), (40, 0, 0));
    // Three data groups (data, error, remote frames) merged by time; the
    // records numbered over all of them.
    let numbers: Vec<u64> = frames.iter().take(10).map(|(n, _)| *n).collect();
    assert_eq!(numbers, [1, 2, 39, 3, 4, 5, 38, 6, 7, 40]);
    // The error frame: ErrorType absent, received: classes only.
    let error = &frames[6].1.frame;
    assert!(error.is_error());
    assert_eq!(error.data(), [0; 8]);
}

#[test]
fn python_can_mf4_writer_deflate_and_plain() {
    assert_eq!(fixture("python_can_deflate").0.len(), 40);
    // MF4Writer's own start time: the master channel's offsets are
    // negative.
    assert_eq!(fixture("python_can_plain").0.len(), 40);
}

#[test]
fn asammdf_data_list_of_transposed_dz_blocks() {
    let (frames, others, skipped) = fixture("asammdf_many");
    assert_eq!((frames.len(), others, skipped), (2000, 0, 0));
    let numbers: Vec<u64> = frames.iter().map(|(n, _)| *n).collect();
    assert_eq!(numbers, (1..=2000).collect::<Vec<_>>());
}

/// docs/formats.md#mf4: a data group of signals (asammdf's `append`) holds
/// no CAN frame; its records are counted by the group's name, and the
/// frames read as python-can reads them.
#[test]
fn asammdf_signal_group_counted_by_name() {
    let (frames, others, skipped) = fixture("asammdf_signals");
    assert_eq!((frames.len(), others, skipped), (40, 3, 0));
    let mut log = logs::open(format!("{DIR}asammdf_signals.mf4")).unwrap();
    while log.next_event().is_some() {}
    let by_kind: u64 = log.other_kinds().iter().map(|kind| kind.count).sum();
    assert_eq!(by_kind, log.other_records());
    let kinds: Vec<String> = log.other_kinds().iter().map(ToString::to_string).collect();
    assert_eq!(
        kinds,
        ["3 MF4 records of group EngineSpeed skipped: not CAN"]
    );
}

#[test]
fn asammdf_vlsd_data_bytes_in_signal_data() {
    let (frames, others, skipped) = fixture("asammdf_sd");
    assert_eq!((frames.len(), others, skipped), (2010, 0, 0));
}

#[test]
fn canedge_unfinalized_vlsd_channel_group() {
    let (frames, others, skipped) = fixture("canedge_vlsd");
    assert_eq!((frames.len(), others, skipped), (2010, 0, 0));
    // Each frame's VLSD record follows it: frames are records 1, 3, 5, …
    assert_eq!(frames[1].0, 3);
    let mut reader = Mf4Reader::new(File::open(format!("{DIR}canedge_vlsd.mf4")).unwrap()).unwrap();
    assert_eq!(reader.version(), 411);
    assert_eq!(reader.start_time().to_string(), "1607975914.000000");
    while reader.next_event().is_some() {}
    assert!(reader.other_groups().is_empty());
}

#[test]
fn canedge_01_07_virtual_channels_many_groups() {
    let (frames, others, skipped) = fixture("canedge_01_07");
    assert_eq!(skipped, 0);
    assert_eq!(others, 0);
    let tx = frames
        .iter()
        .filter(|(_, f)| f.direction == Some(Direction::Tx))
        .count();
    assert_eq!(tx, 70);
    let buses: std::collections::BTreeSet<_> = frames.iter().map(|(_, f)| f.iface).collect();
    assert_eq!(
        buses.into_iter().collect::<Vec<_>>(),
        [Some(Iface::Channel(1)), Some(Iface::Channel(2))]
    );
    // Time order across the channel groups.
    assert!(frames
        .windows(2)
        .all(|w| w[0].1.timestamp <= w[1].1.timestamp));
}

/// A finalized file whose empty groups have DT blocks of no data (cycle
/// count 0, block length 24) before the frames' DT: each empty block holds
/// nothing and its group no record; the frames are read as asammdf reads
/// them, nothing skipped.
#[test]
fn finalized_file_with_empty_data_blocks() {
    let (frames, others, skipped) = fixture("finalized_empty_groups");
    assert_eq!((frames.len(), others, skipped), (37, 0, 0));
    let mut log = logs::open(format!("{DIR}finalized_empty_groups.mf4")).unwrap();
    while log.next_event().is_some() {}
    assert!(log.other_kinds().is_empty(), "{:?}", log.other_kinds());
}
