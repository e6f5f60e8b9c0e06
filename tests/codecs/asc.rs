//! Vector ASC files written by the real tools, read as the real readers
//! read them (`scripts/gen_asc_fixtures.py`):
//!
//! - `python_can.asc`: python-can's `ASCWriter`; truth: python-can's
//!   `ASCReader` (channels there count from 0; the JSON adds 1, as the
//!   file writes them).
//! - `log2asc.asc`, `log2asc_fd.asc` (`-f`, every frame in the `CANFD`
//!   form): can-utils' `log2asc` from `log2asc_in.log`; truth: can-utils'
//!   `asc2log` reading them back.
//! - `canoe.asc`: hand-written in the shapes CANoe writes, as python-can's
//!   own test data has them (statistics after data and after a remote
//!   request's `r`, error frames with details, `CANFD` lines with and
//!   without EDL); truth: python-can's `ASCReader`.
//! - `handmade_dec_relative.asc`: hand-written (`base dec`, `timestamps
//!   relative`, a symbolic name, `TxRq`, statistics, chip status); truth:
//!   python-can's `ASCReader`, with the time since the start added up.
//!
//! Differences, each a decision of docs/formats.md#where-tools-disagree or of
//! `motionwire::logs::asc`: python-can marks every `CANFD` line as CAN FD and
//! gives an error frame identifier 0 and no data (the crate: class
//! `bus_error`, 8 zero bytes, as `asc2log`); python-can reads a `TxRq` line as
//! a frame (the crate skips the transmit request, as `asc2log` does);
//! python-can (4.6) returns relative times as written (the crate adds them up:
//! seconds since the start). can-utils' old `log2asc -f` writes an error frame
//! as a `CANFD` line with identifier 0x80 and zero data; `asc2log` and the
//! crate both read what the line says.

use motionwire::can::{Direction, FdFlags, Iface, LogEvent, LogFrame};
use motionwire::logs::asc::{self, AscParser};
use serde_json::Value;

fn fixture(name: &str) -> (Vec<u8>, Vec<Value>) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/asc/");
    let text = std::fs::read(format!("{dir}{name}.asc")).unwrap();
    let truth: Value =
        serde_json::from_slice(&std::fs::read(format!("{dir}{name}.json")).unwrap()).unwrap();
    (text, truth["frames"].as_array().unwrap().clone())
}

/// Every frame of a file, and the number of bus status events.
fn read(text: &[u8]) -> (Vec<LogFrame<'_>>, usize) {
    let mut frames = Vec::new();
    let mut status = 0;
    for (line, event) in asc::lines(text) {
        match event.unwrap_or_else(|e| panic!("line {line}: {e}")) {
            Some(LogEvent::Frame(frame)) => frames.push(frame),
            Some(LogEvent::Status(_)) => status += 1,
            Some(LogEvent::Ethercat(_)) => panic!("line {line}: an ASC line is no EtherCAT packet"),
            None => {}
        }
    }
    (frames, status)
}

fn hex(data: &[u8]) -> String {
    data.iter().map(|b| format!("{b:02x}")).collect()
}

fn time(frame: &LogFrame<'_>) -> String {
    let ts = frame.timestamp.expect("ASC lines have times");
    format!("{}.{:06}", ts.secs(), ts.micros())
}

fn check_common(at: &str, frame: &LogFrame<'_>, want: &Value) {
    let can = &frame.frame;
    assert_eq!(
        frame.iface,
        Some(Iface::Channel(want["channel"].as_u64().unwrap() as u16)),
        "{at}"
    );
    assert_eq!(can.is_error(), want["error"], "{at}");
    if can.is_error() {
        return;
    }
    assert_eq!(u64::from(can.id().raw()), want["id"], "{at}");
    assert_eq!(can.is_extended(), want["extended"], "{at}");
    assert_eq!(can.is_rtr(), want["rtr"], "{at}");
    assert_eq!(can.fd_flags().contains(FdFlags::BRS), want["brs"], "{at}");
    assert_eq!(can.fd_flags().contains(FdFlags::ESI), want["esi"], "{at}");
    assert_eq!(hex(can.data()), want["data"].as_str().unwrap(), "{at}");
    if can.is_rtr() {
        assert_eq!(u64::from(can.dlc()), want["dlc"], "{at}");
    } else {
        assert_eq!(can.data().len() as u64, want["dlc"], "{at}");
    }
}

#[test]
fn python_can_writer_as_python_can_reads_it() {
    let (text, truth) = fixture("python_can");
    let (frames, status) = read(&text);
    assert_eq!(status, 0);
    assert_eq!(frames.len(), truth.len());
    for (i, (frame, want)) in frames.iter().zip(&truth).enumerate() {
        let at = format!("frame {i}");
        check_common(&at, frame, want);
        // python-can writes the time since its first frame.
        let t0: f64 = truth[0]["timestamp"].as_str().unwrap().parse().unwrap();
        let t: f64 = want["timestamp"].as_str().unwrap().parse().unwrap();
        assert_eq!(time(frame), format!("{:.6}", t - t0), "{at}");
        // python-can marks every CANFD line as CAN FD; its writer writes
        // only CAN FD frames in that form, so here both agree.
        assert_eq!(frame.frame.is_fd(), want["fd"], "{at}");
        let direction = if want["rx"] == true {
            Direction::Rx
        } else {
            Direction::Tx
        };
        if !frame.frame.is_error() {
            assert_eq!(frame.direction, Some(direction), "{at}");
        }
    }
    // The error frame: bus_error with 8 zero bytes (python-can: id 0, none).
    let error = frames.iter().find(|f| f.frame.is_error()).unwrap();
    assert_eq!(error.frame.data(), &[0; 8]);
}

#[test]
fn log2asc_as_asc2log_reads_it() {
    for name in ["log2asc", "log2asc_fd"] {
        let (text, truth) = fixture(name);
        let (frames, _) = read(&text);
        assert_eq!(frames.len(), truth.len(), "{name}");
        let t0 = frames[0].timestamp.unwrap();
        for (i, (frame, want)) in frames.iter().zip(&truth).enumerate() {
            let at = format!("{name} frame {i}");
            check_common(&at, frame, want);
            assert_eq!(frame.frame.is_fd(), want["fd"], "{at}");
            let since = frame.timestamp.unwrap().duration_since(t0).unwrap();
            assert_eq!(
                format!("{}.{:06}", since.as_secs(), since.subsec_micros()),
                want["since_first"].as_str().unwrap(),
                "{at}"
            );
            if !frame.frame.is_error() {
                let letter = match frame.direction {
                    Some(Direction::Rx) => "R",
                    Some(Direction::Tx) => "T",
                    None => "-",
                };
                assert_eq!(Some(letter), want["direction"].as_str(), "{at}");
            }
        }
    }
}

#[test]
fn decimal_base_and_relative_times() {
    let (text, truth) = fixture("handmade_dec_relative");
    let (frames, status) = read(&text);
    // The chip status line is a bus event.
    assert_eq!(status, 1);
    // python-can also reads the TxRq line (the third) as a frame.
    let truth: Vec<&Value> = truth
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != 2)
        .map(|(_, v)| v)
        .collect();
    assert_eq!(frames.len(), truth.len());
    for (i, (frame, want)) in frames.iter().zip(&truth).enumerate() {
        let at = format!("frame {i}");
        check_common(&at, frame, want);
        assert_eq!(frame.frame.is_fd(), want["fd"], "{at}");
        assert_eq!(time(frame), want["since_start"].as_str().unwrap(), "{at}");
    }
    let mut parser = AscParser::new();
    for line in text.split(|&b| b == b'\n') {
        let _ = parser.parse_line(line);
    }
    assert!(!parser.is_hex() && parser.is_relative());
}

#[test]
fn canfd_lines_without_fdf_are_classic_frames() {
    // The decision in docs/formats.md#asc: asc2log's reading of the flags
    // field.
    let mut parser = AscParser::new();
    let classic = b"   0.1 CANFD   1 Rx 123  0 0 2  2 01 02   130000  130        0 0 0 0 0 0";
    let remote = b"   0.2 CANFD   1 Rx 123  0 0 3  0   130000  130       10 0 0 0 0 0";
    let fd = b"   0.3 CANFD   1 Tx 123  1 1 2  2 01 02   130000  130     7000 0 0 0 0 0";
    let frame = |line: &[u8], parser: &mut AscParser| match parser.parse_line(line) {
        Ok(Some(LogEvent::Frame(f))) => f.frame,
        other => panic!("{other:?}"),
    };
    let c = frame(classic, &mut parser);
    assert!(!c.is_fd() && !c.is_rtr());
    assert_eq!(c.data(), &[1, 2]);
    let r = frame(remote, &mut parser);
    assert!(r.is_rtr());
    assert_eq!(r.dlc(), 3);
    let f = frame(fd, &mut parser);
    assert!(f.is_fd());
    assert_eq!(f.fd_flags(), FdFlags::BRS.union(FdFlags::ESI));
}

/// CANoe's lines (docs/formats.md#asc): statistics after a remote request's `r`
/// (`Tx r Length = 1704000 BitCount = 145 ID = …`) and after `r 8`, and
/// `CANFD` lines of 12 and 64 bytes whose flags lack EDL, read frame for
/// frame as python-can's `ASCReader` reads them. The one difference is the
/// decision in docs/formats.md#asc: a `CANFD` line without EDL of at most 8
/// bytes (here the remote request with flags 0x200050) is classic; python-can
/// marks every `CANFD` line as CAN FD.
#[test]
fn canoe_lines_as_python_can_reads_them() {
    let (text, truth) = fixture("canoe");
    let (frames, status) = read(&text);
    assert_eq!(status, 2, "the two chip status lines");
    assert_eq!(frames.len(), truth.len());
    for (i, (frame, want)) in frames.iter().zip(&truth).enumerate() {
        let at = format!("frame {i} at {}", want["as_written"]);
        check_common(&at, frame, want);
        assert_eq!(time(frame), want["as_written"].as_str().unwrap(), "{at}");
        // An error frame is no CAN FD frame (python-can: a `CANFD`
        // ErrorFrame line is).
        let classic_canfd_line = frame.frame.is_rtr() && want["fd"] == true;
        if !classic_canfd_line && !frame.frame.is_error() {
            assert_eq!(frame.frame.is_fd(), want["fd"], "{at}");
        }
        if !frame.frame.is_error() {
            let direction = if want["rx"] == true {
                Direction::Rx
            } else {
                Direction::Tx
            };
            assert_eq!(frame.direction, Some(direction), "{at}");
        }
    }
    // What was rejected before: the remote requests followed by statistics
    // (length 0 without a DLC, 8 with one) and the 64-byte lines without
    // EDL (BRS / ESI from their columns).
    let remote: Vec<_> = frames
        .iter()
        .filter(|f| f.frame.is_rtr())
        .map(|f| (f.frame.id().raw(), f.frame.dlc()))
        .collect();
    assert_eq!(
        remote,
        [(0x705, 0), (0x603, 0), (0x18FF_50E5, 8), (0x5_0005, 5)]
    );
    let long: Vec<_> = frames
        .iter()
        .filter(|f| f.frame.data().len() > 8 && !f.frame.is_error())
        .map(|f| (f.frame.data().len(), f.frame.fd_flags()))
        .collect();
    assert_eq!(
        long,
        [
            (12, FdFlags::ESI),
            (64, FdFlags::BRS),
            (64, FdFlags::ESI),
            (12, FdFlags::BRS.union(FdFlags::ESI)),
        ]
    );
}

/// CANoe 15's `TriggerEvent:` lines are trigger events, not frames and not
/// malformed; a classic-syntax line with DLC 9 and 12 data bytes is a
/// 12-byte CAN FD frame, with 8 a classic frame (docs/formats.md#asc).
/// python-can agrees on every frame's time, channel, identifier and
/// direction, and keeps only the first 8 bytes of the 12 (where it
/// disagrees with the file, the file wins).
#[test]
fn canoe15_trigger_events_and_fd_frames_in_classic_syntax() {
    let (text, truth) = fixture("canoe15");
    let (frames, status) = read(&text);
    assert_eq!(status, 0);
    assert_eq!(frames.len(), truth.len());
    for (i, (frame, want)) in frames.iter().zip(&truth).enumerate() {
        let at = format!("frame {i}");
        assert_eq!(
            time(frame),
            format!("0.{}", &want["timestamp"].as_str().unwrap()[2..])
        );
        let can = &frame.frame;
        assert_eq!(
            frame.iface,
            Some(Iface::Channel(want["channel"].as_u64().unwrap() as u16)),
            "{at}"
        );
        assert_eq!(u64::from(can.id().raw()), want["id"], "{at}");
        assert_eq!(can.is_extended(), want["extended"], "{at}");
        let direction = if want["rx"] == true {
            Direction::Rx
        } else {
            Direction::Tx
        };
        assert_eq!(frame.direction, Some(direction), "{at}");
        // python-can's bytes are ours, or the first 8 of our 12.
        let theirs = want["data"].as_str().unwrap();
        assert!(hex(can.data()).starts_with(theirs), "{at}");
    }
    let shapes: Vec<_> = frames
        .iter()
        .map(|f| (f.frame.id().raw(), f.frame.is_fd(), f.frame.data().len()))
        .collect();
    assert_eq!(
        shapes,
        [
            (0x181, false, 8),
            (0x2A1, true, 12),
            (0x2A2, false, 8),
            (0x181, false, 2),
            (0x18FF_1234, true, 12),
        ]
    );
    assert_eq!(hex(frames[1].frame.data()), "0102030405060708090a0b0c");
    assert_eq!(frames[1].frame.fd_flags(), FdFlags::EMPTY);
}
