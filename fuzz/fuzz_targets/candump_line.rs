//! candump text lines (docs/formats.md): the fast (SWAR) log-format path, the
//! general path, the line iterator and the two writers.
//!
//! Arbitrary bytes → `candump::parse_line` and `candump::lines`. Invariants:
//! - nothing panics; an error is an `FormatError::Syntax` of the candump format
//!   whose column lies in the line (1-based, at most one past its end) and
//!   whose message prints;
//! - a parsed frame keeps the formats' invariants: a non-empty printable
//!   interface name not starting with `(` or `#`, an identifier in range,
//!   at most 8 data bytes (64 for CAN FD, 8 for an error frame, whose
//!   identifier is extended), a remote request without data and with a
//!   length 0..=8;
//! - a parsed frame written back with `write_log` (and `Display`) parses to
//!   the same frame; written with `write_screen` it parses to the same frame
//!   but for the CAN FD flags the screen cannot show (the decision in
//!   docs/formats.md#candump-screen: only BRS/ESI, only with a direction);
//! - the same line with one leading space (which the fast path never takes)
//!   gives the same frame, or the same error one column further right: the
//!   fast path and the general parser agree;
//! - `parse_line_str` agrees with `parse_line`;
//! - `lines(input)` yields one item per line, numbered 1, 2, …, each equal
//!   to `parse_line` of that line — except a line after an error frame (or
//!   after such a line) that is no frame, has a tab in its indentation and
//!   starts with one of can-utils' error class names, which is `Ok(None)`
//!   (candump -e's explanation) — whether read with `next` or `fold`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::FdFlags;
use motionwire::can::{CanFrame, Iface, LogFrame, CLASSIC_MAX_LEN, FD_MAX_LEN};
use motionwire::logs::candump;
use motionwire::logs::FormatError;
use motionwire::logs::LogFormat;
use motionwire::logs::Position;

fuzz_target!(|data: &[u8]| {
    check_lines(data);

    // The first line on its own, as a caller that splits lines would pass it.
    let line = match data.iter().position(|&b| b == b'\n') {
        Some(end) => &data[..=end],
        None => data,
    };
    let result = candump::parse_line(line);
    if let Ok(text) = std::str::from_utf8(line) {
        assert_eq!(candump::parse_line_str(text), result);
    }
    check_leading_space(line, &result);

    match result {
        Ok(Some(frame)) => {
            check_frame(&frame);
            check_written(&frame);
        }
        Ok(None) => {}
        Err(error) => check_error(line, error),
    }
});

fn check_error(line: &[u8], error: FormatError) {
    match error {
        FormatError::Syntax {
            format: LogFormat::Candump,
            column,
            reason,
        } => {
            assert!(column >= 1, "column 0 for {line:?}");
            assert!(
                column <= line.len() + 1,
                "column {column} past the line {line:?}"
            );
            let _ = reason.to_string();
        }
        other => panic!("parse_line gave {other:?}, not a candump error"),
    }
    let _ = error.to_string();
}

fn check_frame(logged: &LogFrame) {
    let Some(Iface::Name(name)) = logged.iface else {
        panic!("a candump record without an interface name: {logged:?}");
    };
    let iface = name.as_bytes();
    assert!(!iface.is_empty());
    assert!(
        iface.iter().all(u8::is_ascii_graphic),
        "interface {iface:?}"
    );
    assert!(!matches!(iface[0], b'(' | b'#'));
    let frame = &logged.frame;
    let id = frame.id();
    assert_eq!(id.is_extended(), frame.is_extended());
    assert!(id.raw() <= if id.is_extended() { 0x1FFF_FFFF } else { 0x7FF });
    if frame.is_fd() {
        assert!(frame.data().len() <= FD_MAX_LEN);
        assert!(frame.fd_flags().bits() <= 0xF);
        assert!(frame.dlc() <= 15);
        assert!(!frame.is_rtr());
    } else {
        assert!(frame.data().len() <= CLASSIC_MAX_LEN);
        assert_eq!(frame.fd_flags(), FdFlags::EMPTY);
    }
    if frame.is_error() {
        assert!(frame.is_extended() && !frame.is_rtr() && !frame.is_fd());
    }
    if frame.is_rtr() {
        assert!(frame.data().is_empty());
        assert!(frame.dlc() <= 8);
    } else if !frame.is_fd() {
        assert_eq!(usize::from(frame.dlc()), frame.data().len());
    }
    if let Some(ts) = logged.timestamp {
        assert!(ts.micros() < 1_000_000);
        let _ = ts.as_secs_f64();
    }
}

/// Written back in either format, the frame parses to itself.
fn check_written(frame: &LogFrame) {
    let mut log = String::new();
    candump::write_log(frame, &mut log).expect("a String takes any text");
    assert_eq!(frame.to_string(), log);
    assert!(!log.contains('\n'));
    assert_eq!(
        candump::parse_line(log.as_bytes()),
        Ok(Some(*frame)),
        "log form {log:?}"
    );
    let with_end = format!("{log}\r\n");
    assert_eq!(candump::parse_line(with_end.as_bytes()), Ok(Some(*frame)));

    let mut screen = String::new();
    candump::write_screen(frame, &mut screen).expect("a String takes any text");
    assert!(!screen.contains('\n'));
    let expected = if frame.frame.is_fd() {
        // The screen shows only BRS and ESI, and only after a direction.
        let shown = match frame.direction {
            Some(_) => FdFlags::new(frame.frame.fd_flags().bits() & 0x3).expect("a nibble"),
            None => FdFlags::EMPTY,
        };
        LogFrame {
            frame: CanFrame::new_fd(frame.frame.id(), shown, frame.frame.data())
                .expect("the frame's own fields"),
            ..*frame
        }
    } else {
        *frame
    };
    assert_eq!(
        candump::parse_line(screen.as_bytes()),
        Ok(Some(expected)),
        "screen form {screen:?}"
    );
}

/// One more leading space changes nothing but error columns.
fn check_leading_space(line: &[u8], result: &Result<Option<LogFrame>, FormatError>) {
    let mut spaced = Vec::with_capacity(line.len() + 1);
    spaced.push(b' ');
    spaced.extend_from_slice(line);
    let shifted = candump::parse_line(&spaced);
    match (result, shifted) {
        (Ok(frame), Ok(shifted)) => assert_eq!(*frame, shifted, "{line:?}"),
        (
            Err(FormatError::Syntax { column, reason, .. }),
            Err(FormatError::Syntax {
                column: shifted_column,
                reason: shifted_reason,
                ..
            }),
        ) => {
            assert_eq!(shifted_column, column + 1, "{line:?}: {reason}");
            assert_eq!(shifted_reason, *reason, "{line:?}");
        }
        (result, shifted) => panic!("{line:?}: {result:?}, with a leading space {shifted:?}"),
    }
}

/// The line iterator agrees with `parse_line` on each line.
fn check_lines(data: &[u8]) {
    let mut after_error_frame = false;
    let expected: Vec<_> = split_lines(data)
        .enumerate()
        .map(|(i, line)| {
            let parsed = candump::parse_line(line);
            if parsed.is_err() && after_error_frame && is_explanation(line) {
                return (Position::Line(i as u64 + 1), Ok(None));
            }
            after_error_frame = matches!(&parsed, Ok(Some(f)) if f.frame.is_error());
            (Position::Line(i as u64 + 1), parsed)
        })
        .collect();
    let mut by_next = Vec::new();
    let mut iter = candump::lines(data);
    // A `for` loop calls `next`, the path `fold` does not take.
    for item in iter.by_ref() {
        by_next.push(item);
        assert!(by_next.len() <= expected.len(), "more items than lines");
    }
    assert!(iter.remainder().is_empty());
    assert_eq!(by_next, expected);
    let by_fold = candump::lines(data).fold(Vec::new(), |mut items, item| {
        items.push(item);
        items
    });
    assert_eq!(by_fold, expected);
}

/// Lines as `lines` documents them: ending at `\n`, a last line without one
/// counting too, nothing after a final `\n`.
fn split_lines(data: &[u8]) -> impl Iterator<Item = &[u8]> {
    let mut rest = data;
    std::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        let (line, next) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&rest[..i], &rest[i + 1..]),
            None => (rest, &[][..]),
        };
        rest = next;
        Some(line)
    })
}

/// The model of candump -e's explanation lines: a tab in the indentation,
/// then one of can-utils' error class names up to `{`, white space, `\r` or
/// the end of the line.
fn is_explanation(line: &[u8]) -> bool {
    const WORDS: [&str; 10] = [
        "tx-timeout",
        "lost-arbitration",
        "controller-problem",
        "protocol-violation",
        "transceiver-status",
        "no-acknowledgement-on-tx",
        "bus-off",
        "bus-error",
        "restarted-after-bus-off",
        "error-counter-tx-rx",
    ];
    let start = line
        .iter()
        .position(|&b| b != b' ' && b != b'\t')
        .unwrap_or(line.len());
    let (indent, text) = line.split_at(start);
    let end = text
        .iter()
        .position(|&b| matches!(b, b'{' | b' ' | b'\t' | b'\r'))
        .unwrap_or(text.len());
    indent.contains(&b'\t') && WORDS.iter().any(|w| w.as_bytes() == &text[..end])
}
