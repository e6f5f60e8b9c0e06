//! Vector BLF files written by python-can's `BLFWriter` and read back by
//! python-can's `BLFReader` (`scripts/gen_blf_fixtures.py`): the crate reads
//! every frame as python-can does — identifier, flags, data, channel (the
//! JSON adds 1 to python-can's 0-based channel), direction, time to the
//! microsecond (python-can computes it in floats).
//!
//! One documented difference (`motionwire::logs::blf`'s decision): python-can
//! reads a `CAN_ERROR_EXT` object as an error frame with the object's
//! identifier and data bytes; the crate gives Linux's layout of the
//! object's error byte, read as its flags say (classes bus_error and
//! protocol).

use motionwire::can::{Direction, ErrorClasses, ErrorFrame, FdFlags, Iface, LogEvent};
use motionwire::logs::blf::BlfReader;
use motionwire::logs::{LogRecord, ReadLog};
use serde_json::Value;

fn fixture(name: &str) -> (Vec<u8>, Value) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/blf/");
    let file = std::fs::read(format!("{dir}{name}.blf")).unwrap();
    let truth: Value =
        serde_json::from_slice(&std::fs::read(format!("{dir}{name}.json")).unwrap()).unwrap();
    (file, truth)
}

/// (number, time in µs since the epoch as text, channel, id, data, frame).
fn read(file: &[u8]) -> Vec<(u64, motionwire::can::LogFrame<'static>)> {
    let mut reader = BlfReader::new(file).unwrap();
    let mut out = Vec::new();
    while let Some(record) = reader.next_event() {
        let LogRecord { position, event } = record.unwrap();
        let number = position.number();
        let LogEvent::Frame(frame) = event else {
            panic!("BLF has no status events")
        };
        out.push((
            number,
            motionwire::can::LogFrame {
                frame: frame.frame,
                timestamp: frame.timestamp,
                iface: frame.iface.map(|i| match i {
                    Iface::Channel(c) => Iface::Channel(c),
                    Iface::Name(_) => panic!("BLF names no interface"),
                }),
                direction: frame.direction,
            },
        ));
    }
    assert_eq!(reader.other_records(), 0);
    out
}

fn close(ours: &motionwire::can::LogFrame<'_>, theirs: &str) {
    let ts = ours.timestamp.unwrap();
    let ours = ts.secs() as f64 + f64::from(ts.subsec_nanos()) * 1e-9;
    let theirs: f64 = theirs.parse().unwrap();
    assert!((ours - theirs).abs() < 1e-6, "{ours} vs {theirs}");
}

#[test]
fn python_can_files_as_python_can_reads_them() {
    for name in ["python_can", "python_can_stored"] {
        let (file, truth) = fixture(name);
        let frames = read(&file);
        let want = truth["frames"].as_array().unwrap();
        assert_eq!(frames.len(), want.len(), "{name}");
        for (i, ((number, got), want)) in frames.iter().zip(want).enumerate() {
            let at = format!("{name} frame {i}");
            assert_eq!(*number, i as u64 + 1, "{at}");
            close(got, want["timestamp"].as_str().unwrap());
            let can = &got.frame;
            assert_eq!(
                got.iface,
                Some(Iface::Channel(want["channel"].as_u64().unwrap() as u16)),
                "{at}"
            );
            assert_eq!(can.is_error(), want["error"], "{at}");
            let direction = if want["rx"] == true {
                Direction::Rx
            } else {
                Direction::Tx
            };
            if can.is_error() {
                continue;
            }
            assert_eq!(got.direction, Some(direction), "{at}");
            assert_eq!(u64::from(can.id().raw()), want["id"], "{at}");
            assert_eq!(can.is_extended(), want["extended"], "{at}");
            assert_eq!(can.is_rtr(), want["rtr"], "{at}");
            assert_eq!(can.is_fd(), want["fd"], "{at}");
            assert_eq!(can.fd_flags().contains(FdFlags::BRS), want["brs"], "{at}");
            assert_eq!(can.fd_flags().contains(FdFlags::ESI), want["esi"], "{at}");
            let data: String = can.data().iter().map(|b| format!("{b:02x}")).collect();
            assert_eq!(data, want["data"].as_str().unwrap(), "{at}");
            if can.is_rtr() {
                assert_eq!(u64::from(can.dlc()), want["dlc"], "{at}");
            }
        }
    }
}

#[test]
fn objects_across_many_containers() {
    let (file, truth) = fixture("python_can_many");
    let frames = read(&file);
    let want = truth["frames"].as_array().unwrap();
    assert_eq!(frames.len(), want.len());
    for ((_, got), row) in frames.iter().zip(want) {
        close(got, row[0].as_str().unwrap());
        assert_eq!(
            got.iface,
            Some(Iface::Channel(row[1].as_u64().unwrap() as u16))
        );
        assert_eq!(u64::from(got.frame.id().raw()), row[2]);
        let data: String = got
            .frame
            .data()
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect();
        assert_eq!(data, row[3].as_str().unwrap());
    }
}

/// `CAN_ERROR_EXT` objects read by their flags (Vector's definition;
/// docs/formats.md#blf): CANoe 10's flags 0xFFFE (bit 1, CAN-Core) with
/// error byte 0x81 are a form error, received; an SJA1000 register with
/// flags bit 0; nothing known with neither. python-can reads each as an
/// error frame on the same channel at the same time (with the object's
/// identifier and data, which say nothing here).
#[test]
fn error_ext_by_its_flags() {
    let (file, truth) = fixture("error_ext");
    let frames = read(&file);
    let want = truth["frames"].as_array().unwrap();
    assert_eq!(frames.len(), want.len());
    for ((_, got), want) in frames.iter().zip(want) {
        close(got, want["timestamp"].as_str().unwrap());
        assert_eq!(
            got.iface,
            Some(Iface::Channel(want["channel"].as_u64().unwrap() as u16))
        );
        assert_eq!(got.frame.is_error(), want["error"]);
    }
    let errors: Vec<_> = frames[1..5]
        .iter()
        .map(|(_, got)| {
            let error = ErrorFrame::from_frame(&got.frame).unwrap();
            assert_eq!(
                error.classes,
                ErrorClasses::BUS_ERROR.union(ErrorClasses::PROTOCOL)
            );
            (error.protocol(), got.direction)
        })
        .collect();
    assert_eq!(
        errors,
        [
            // 0x81: form error, received (not "stuff error while sending").
            (Some((0x02, 0x00)), Some(Direction::Rx)),
            // SJA1000 0xA3: stuff error, received, segment 3.
            (Some((0x04, 0x03)), Some(Direction::Rx)),
            // CAN-Core 0xC4: CRC error while sending: the CRC sequence.
            (Some((0x80, 0x08)), Some(Direction::Tx)),
            // Flags 0 (python-can's): nothing known.
            (Some((0x00, 0x00)), None),
        ]
    );
}
