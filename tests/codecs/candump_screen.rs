//! candump's screen output with every option of docs/formats.md#candump-screen,
//! as can-utils' own formatting code prints it:
//! `scripts/gen_candump_screen_fixtures.sh` builds can-utils' `lib.c` with
//! `scripts/candump_screen/driver.c`, which assembles each line as `candump.c`
//! does (timestamp modes `-t a|A|d|z`, `-N`, `-x`, `-e`, `-a`, `-8`, `-c`,
//! `-S`, `-i`), and writes beside each `tests/fixtures/candump_screen/MODE.txt`
//! a `MODE.json` with what every line holds. The crate must read every frame as
//! written.
//!
//! The truth's `ts` follows the decision in docs/formats.md#candump-screen: `-t
//! a` and `-t A` (read as UTC) are Unix time, `-t z` the time since the first
//! frame as printed, `-t d` the printed deltas added up. `-S` and `-i` lines
//! with data cannot be read back faithfully and are errors saying so.

use motionwire::can::{Direction, FdFlags, Iface, LogFrame};
use motionwire::logs::candump::{self, RelativeTimestamps};
use motionwire::logs::{FormatError, SyntaxError};
use serde_json::Value;

fn fixture(mode: &str) -> (Vec<u8>, Vec<Value>) {
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/candump_screen/"
    );
    let text = std::fs::read(format!("{dir}{mode}.txt")).unwrap();
    let truth: Value =
        serde_json::from_slice(&std::fs::read(format!("{dir}{mode}.json")).unwrap()).unwrap();
    (text, truth["frames"].as_array().unwrap().clone())
}

/// Every frame of the file, in order, detecting the relative time base as
/// a reader of a whole file does.
fn read(text: &[u8]) -> Vec<LogFrame<'_>> {
    let relative = candump::detect_relative_timestamps(text, true).unwrap();
    let state = candump::LineState::new(relative);
    candump::lines_from(text, state)
        .filter_map(|(line, parsed)| parsed.unwrap_or_else(|e| panic!("line {line}: {e}")))
        .collect()
}

fn check(mode: &str) {
    let (text, truth) = fixture(mode);
    let frames = read(&text);
    assert_eq!(frames.len(), truth.len(), "{mode}: frames");
    for (i, (logged, want)) in frames.iter().zip(&truth).enumerate() {
        let at = format!("{mode} frame {i}");
        let frame = &logged.frame;
        assert_eq!(
            logged.iface,
            Some(Iface::Name(want["iface"].as_str().unwrap())),
            "{at}"
        );
        assert_eq!(u64::from(frame.id().raw()), want["id"], "{at}");
        assert_eq!(frame.is_extended(), want["extended"], "{at}");
        assert_eq!(frame.is_rtr(), want["rtr"], "{at}");
        assert_eq!(frame.is_fd(), want["fd"], "{at}");
        assert_eq!(frame.is_error(), want["error"], "{at}");
        let flags = frame.fd_flags();
        assert_eq!(flags.contains(FdFlags::BRS), want["brs"], "{at}");
        assert_eq!(flags.contains(FdFlags::ESI), want["esi"], "{at}");
        if frame.is_rtr() {
            assert_eq!(u64::from(frame.dlc()), want["dlc"], "{at}");
        } else {
            assert_eq!(frame.data().len() as u64, want["dlc"], "{at}");
        }
        let data: String = frame.data().iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(data, want["data"].as_str().unwrap(), "{at}");
        let direction = logged.direction.map(|d| match d {
            Direction::Rx => "rx",
            Direction::Tx => "tx",
        });
        assert_eq!(direction, want["direction"].as_str(), "{at}");
        let ts = logged
            .timestamp
            .map(|ts| format!("{}.{:09}", ts.secs(), ts.subsec_nanos()));
        assert_eq!(ts.as_deref(), want["ts"].as_str(), "{at}");
    }
}

#[test]
fn plain() {
    check("plain");
}

#[test]
fn absolute_times_with_direction_fd_flags_and_error_explanations() {
    // -t a -x -e: the explanation lines after each error frame belong to it.
    check("ta_x_e");
}

#[test]
fn dates_ascii_column_and_raw_dlc() {
    // -t A -a -8: `{F}` is a raw DLC of 15 on an 8-byte classic frame.
    check("tA_a_8");
}

#[test]
fn deltas_add_up_to_the_time_since_the_first_frame() {
    let (text, _) = fixture("td");
    assert_eq!(
        candump::detect_relative_timestamps(&text, true),
        Some(RelativeTimestamps::Delta)
    );
    check("td");
}

#[test]
fn zero_based_nanosecond_times() {
    let (text, _) = fixture("tz_N");
    assert_eq!(
        candump::detect_relative_timestamps(&text, true),
        Some(RelativeTimestamps::Zero)
    );
    check("tz_N");
}

#[test]
fn colours_are_ignored() {
    // -c -c -c colours the whole line; -c with -x, -t A -N and -a colours
    // the interface and its columns.
    check("c3_ta");
    check("c1_tA_N_a");
}

#[test]
fn swapped_and_binary_data_are_reported_as_unsupported() {
    for (mode, option) in [("S", b'S'), ("i", b'i')] {
        let (text, truth) = fixture(mode);
        let mut read = 0;
        for ((line, parsed), want) in candump::lines(&text).zip(&truth) {
            let bytes = want["dlc"].as_u64().unwrap();
            let faithful = want["rtr"] == true
                || bytes == 0
                // One byte swapped is itself.
                || (option == b'S' && bytes == 1);
            match parsed {
                Ok(Some(_)) if faithful => read += 1,
                Err(FormatError::Syntax {
                    reason: SyntaxError::UnsupportedOutput { option: o },
                    ..
                }) if !faithful && o == option => {}
                other => panic!("{mode} line {line}: {other:?}"),
            }
        }
        assert!(read > 0, "{mode}");
    }
}

/// can-utils' `log2long` writes a candump log (`log2long_in.log`) in the
/// screen form with the ASCII column and the timestamp
/// (`log2long.txt`); both read as the same frames, except the CAN FD flags
/// the screen form does not show without `-x` (docs/formats.md#candump-screen).
#[test]
fn log2long_output_reads_as_its_input() {
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/candump_screen/"
    );
    let input = std::fs::read(format!("{dir}log2long_in.log")).unwrap();
    let screen = std::fs::read(format!("{dir}log2long.txt")).unwrap();
    let frames = |text: &[u8]| -> Vec<LogFrame<'static>> {
        let text: &'static [u8] = Box::leak(text.to_vec().into_boxed_slice());
        candump::lines(text)
            .filter_map(|(line, parsed)| parsed.unwrap_or_else(|e| panic!("line {line}: {e}")))
            .collect()
    };
    let logged = frames(&input);
    let shown = frames(&screen);
    assert_eq!(logged.len(), shown.len());
    for (log, screen) in logged.iter().zip(&shown) {
        let mut expected = *log;
        if log.frame.is_fd() {
            expected.frame =
                motionwire::can::CanFrame::new_fd(log.frame.id(), FdFlags::EMPTY, log.frame.data())
                    .unwrap();
        }
        assert_eq!(*screen, expected);
    }
}
