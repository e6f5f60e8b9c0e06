//! Vector ASC lines (docs/formats.md#asc): arbitrary bytes → `asc::lines` and
//! `AscParser::parse_line`. Invariants:
//! - nothing panics; an error is an `FormatError::Syntax` of the ASC format whose
//!   column lies in the line (1-based, at most one past its end), and whose
//!   message prints;
//! - a frame keeps the crate's invariants (identifier in range, at most 8
//!   data bytes for classic and error frames, a CAN FD length of a DLC, a
//!   remote request without data), has a time, a channel ≥ 1 and, unless
//!   it is an error frame, a direction;
//! - `lines` yields one item per line, numbered 1, 2, …, each equal to what
//!   a parser fed the same lines in order gives;
//! - a frame written back with `write_line` reads back to itself in a
//!   fresh parser (times as written when the file's are absolute).
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{Iface, LogEvent};
use motionwire::logs::asc::{self, AscParser};
use motionwire::logs::FormatError;
use motionwire::logs::LogFormat;
use motionwire::logs::Position;

const FD_LENGTHS: [usize; 16] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64];

fuzz_target!(|data: &[u8]| {
    let mut parser = AscParser::new();
    let mut expected = Vec::new();
    let mut rest = data;
    while !rest.is_empty() {
        let (line, next) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&rest[..i], &rest[i + 1..]),
            None => (rest, &[][..]),
        };
        rest = next;
        let parsed = parser.parse_line(line);
        match &parsed {
            Err(error) => check_error(line, error),
            Ok(Some(LogEvent::Frame(frame))) => {
                let can = &frame.frame;
                assert!(frame.timestamp.is_some());
                assert!(matches!(frame.iface, Some(Iface::Channel(n)) if n >= 1));
                assert!(can.is_error() || frame.direction.is_some());
                if can.is_fd() {
                    assert!(FD_LENGTHS.contains(&can.data().len()));
                } else {
                    assert!(can.data().len() <= 8);
                }
                if can.is_rtr() {
                    assert!(can.data().is_empty() && can.dlc() <= 8);
                }
                let mut text = String::new();
                if asc::write_line(frame, &mut text).is_ok() && !parser.is_relative() {
                    let mut fresh = AscParser::new();
                    if let Ok(Some(LogEvent::Frame(back))) = fresh.parse_line(text.as_bytes()) {
                        if !can.is_error() {
                            assert_eq!(back.frame, *can, "{text}");
                        }
                        assert_eq!(back.timestamp, frame.timestamp, "{text}");
                    } else {
                        panic!("{text:?} does not read back");
                    }
                }
            }
            Ok(_) => {}
        }
        expected.push(parsed);
    }
    let items: Vec<_> = asc::lines(data).collect();
    assert_eq!(items.len(), expected.len());
    for (i, ((number, item), want)) in items.into_iter().zip(expected).enumerate() {
        assert_eq!(number, Position::Line(i as u64 + 1));
        assert_eq!(item, want);
    }
});

fn check_error(line: &[u8], error: &FormatError) {
    match error {
        FormatError::Syntax {
            format: LogFormat::Asc,
            column,
            reason,
        } => {
            assert!(
                *column >= 1 && *column <= line.len() + 1,
                "{column} {line:?}"
            );
            let _ = reason.to_string();
        }
        other => panic!("{other:?}"),
    }
    let _ = error.to_string();
}
