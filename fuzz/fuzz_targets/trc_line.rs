//! PEAK TRC text (docs/formats.md#trc): `trc::lines` over the whole input and
//! `TrcParser::parse_line` on its first line in every version's state.
//!
//! Invariants:
//! - nothing panics; an error is an `FormatError::Syntax` of the TRC format whose
//!   column lies in the line (1-based, at most one past its end) and whose
//!   message prints;
//! - a frame has a timestamp, keeps its type's length limits (8 bytes, 64
//!   for CAN FD, none for a remote request whose length is 0..=8), an
//!   identifier in range, a channel number or no interface (never a name);
//!   an error frame has the classes `trc::ERROR_FRAME_CLASSES` and 8 bytes;
//! - a frame that `write_line` accepts reads back to itself after
//!   `write_header` with the parser's start time;
//! - `lines(input)` yields one item per line, numbered 1, 2, …, and the
//!   parser it ends with saw the same header keys as one fed line by line.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{Iface, LogEvent, Timestamp, CLASSIC_MAX_LEN, FD_MAX_LEN};
use motionwire::logs::trc::{self, TrcParser, TrcVersion};
use motionwire::logs::FormatError;
use motionwire::logs::LogFormat;
use motionwire::logs::Position;

fuzz_target!(|data: &[u8]| {
    check_lines(data);
    let line = match data.iter().position(|&b| b == b'\n') {
        Some(end) => &data[..=end],
        None => data,
    };
    for version in TrcVersion::ALL {
        let mut parser = TrcParser::new();
        let header = format!(";$FILEVERSION={version}");
        assert_eq!(parser.parse_line(header.as_bytes()), Ok(None));
        assert_eq!(
            parser.parse_line(b";$STARTTIME=45244.925925925926"),
            Ok(None)
        );
        let result = parser.parse_line(line);
        match result {
            Ok(Some(LogEvent::Frame(frame))) => {
                check_frame(&frame);
                check_written(&parser, &frame);
            }
            Ok(Some(LogEvent::Status(status))) => {
                assert!(!matches!(status.iface, Some(Iface::Name(_))));
            }
            Ok(Some(LogEvent::Ethercat(_))) => panic!("a TRC line is no EtherCAT packet"),
            Ok(None) => {}
            Err(error) => check_error(line, error),
        }
    }
});

fn check_error(line: &[u8], error: FormatError) {
    match error {
        FormatError::Syntax {
            format: LogFormat::Trc,
            column,
            reason,
        } => {
            assert!(column >= 1, "column 0 for {line:?}");
            assert!(column <= line.len() + 1, "column {column} past {line:?}");
            let _ = reason.to_string();
        }
        other => panic!("parse_line gave {other:?}, not a TRC error"),
    }
    let _ = error.to_string();
}

fn check_frame(logged: &motionwire::can::LogFrame) {
    assert!(logged.timestamp.is_some());
    assert!(!matches!(logged.iface, Some(Iface::Name(_))));
    let frame = &logged.frame;
    let id = frame.id();
    assert!(id.raw() <= if id.is_extended() { 0x1FFF_FFFF } else { 0x7FF });
    if frame.is_fd() {
        assert!(frame.data().len() <= FD_MAX_LEN);
    } else {
        assert!(frame.data().len() <= CLASSIC_MAX_LEN);
    }
    if frame.is_rtr() {
        assert!(frame.data().is_empty() && frame.dlc() <= 8);
    }
    if frame.is_error() {
        assert_eq!(id.raw(), trc::ERROR_FRAME_CLASSES.bits());
        assert_eq!(frame.data().len(), 8);
    }
}

/// Written in version 2.1 (when the row can hold it), the frame reads back.
fn check_written(parser: &TrcParser, frame: &motionwire::can::LogFrame) {
    let start = parser.start_time().unwrap_or(Timestamp::ZERO);
    let mut text = String::new();
    trc::write_header(&mut text, start).expect("a start of this era");
    if trc::write_line(&mut text, 7, start, frame).is_err() {
        return;
    }
    let back: Vec<_> = trc::lines(text.as_bytes())
        .map(|(n, r)| r.unwrap_or_else(|e| panic!("line {n} of {text:?}: {e}")))
        .flatten()
        .collect();
    assert_eq!(back, vec![LogEvent::Frame(*frame)], "{text:?}");
}

/// `lines` agrees with one parser fed line by line.
fn check_lines(data: &[u8]) {
    let mut parser = TrcParser::new();
    let mut expected = Vec::new();
    let mut rest = data;
    while !rest.is_empty() {
        let (line, next) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&rest[..i], &rest[i + 1..]),
            None => (rest, &[][..]),
        };
        rest = next;
        let position = Position::Line(expected.len() as u64 + 1);
        expected.push((position, parser.parse_line(line)));
    }
    let mut lines = trc::lines(data);
    let items: Vec<_> = lines.by_ref().collect();
    assert_eq!(items, expected);
    assert!(lines.remainder().is_empty());
    assert_eq!(lines.parser(), &parser);
}
