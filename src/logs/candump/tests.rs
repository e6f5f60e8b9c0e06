use super::*;
use crate::can::LogFrame;
use crate::can::{CanId, Direction, FdFlags, Timestamp};
use crate::logs::lex::hex_value;
use crate::logs::FormatError;
use crate::logs::{Found, LogFormat, Position, SyntaxError};
use crate::test_gens::candump::{Build, FrameExt};
use crate::What;

/// The log example of docs/formats.md#candump-log: an EMCY of node 1 (code
/// 0x8110, register 0x11) as candump -l logs it.
const DOCS_LOG: &str = "(1700000000.000500) can0 081#1081110000000000";
/// The screen examples of docs/formats.md#candump-screen.
const DOCS_SCREEN: &str = "  can0  081   [8]  10 81 11 00 00 00 00 00";
const DOCS_SCREEN_RTR: &str = "  can0  705   [1]  remote request";

const EMCY: [u8; 8] = [0x10, 0x81, 0x11, 0, 0, 0, 0, 0];

fn ts(secs: u64, micros: u32) -> Timestamp {
    Timestamp::new(secs, micros).unwrap()
}

fn std_id(raw: u32) -> CanId {
    CanId::standard(raw).unwrap()
}

fn ext_id(raw: u32) -> CanId {
    CanId::extended(raw).unwrap()
}

/// Parse a line that must hold a frame, checking that the fast path
/// (when it takes the line) and the general parser agree.
fn frame(line: &str) -> LogFrame<'_> {
    let general = general(line.as_bytes());
    let parsed = parse_line_str(line);
    assert_eq!(parsed, general, "fast and general paths differ on {line:?}");
    parsed
        .unwrap_or_else(|e| panic!("{line:?}: {e}"))
        .unwrap_or_else(|| panic!("{line:?}: no frame"))
}

/// Parse a line that must be malformed; return (column, reason).
fn fail(line: &str) -> (usize, SyntaxError) {
    assert_eq!(general(line.as_bytes()), parse_line_str(line));
    match parse_line_str(line) {
        Err(FormatError::Syntax {
            format: LogFormat::Candump,
            column,
            reason,
        }) => (column, reason),
        other => panic!("{line:?}: expected an error, got {other:?}"),
    }
}

fn log(frame: &LogFrame<'_>) -> String {
    let mut s = String::new();
    frame.write_log(&mut s).unwrap();
    s
}

fn screen(frame: &LogFrame<'_>) -> String {
    let mut s = String::new();
    frame.write_screen(&mut s).unwrap();
    s
}

// ------------------------------------------ the examples of docs/formats.md

#[test]
fn docs_log_example() {
    let f = frame(DOCS_LOG);
    assert_eq!(f.timestamp(), Some(ts(1_700_000_000, 500)));
    assert_eq!(f.iface(), b"can0");
    assert_eq!(f.iface_str(), "can0");
    assert_eq!(f.id(), std_id(0x081));
    assert!(!f.is_extended() && !f.is_rtr() && !f.is_fd());
    assert_eq!(f.fd_flags(), FdFlags::EMPTY);
    assert_eq!(f.direction(), None);
    assert_eq!(f.data(), &EMCY);
    assert_eq!(f.dlc(), 8);
    let expected = Build::new_data("can0", std_id(0x081), &EMCY)
        .unwrap()
        .with_timestamp(ts(1_700_000_000, 500));
    assert_eq!(f, expected);
}

#[test]
fn docs_log_example_with_direction() {
    for (suffix, direction) in [(" R", Direction::Rx), (" T", Direction::Tx)] {
        let line = format!("{DOCS_LOG}{suffix}");
        let f = frame(&line);
        assert_eq!(f.direction(), Some(direction));
        assert_eq!(f.data(), &EMCY);
    }
}

#[test]
fn docs_log_remote_requests() {
    let f = frame("(1700000000.000500) can0 123#R");
    assert!(f.is_rtr());
    assert_eq!((f.dlc(), f.data()), (0, &[][..]));
    let f = frame("(1700000000.000500) can0 123#R5");
    assert!(f.is_rtr());
    assert_eq!((f.dlc(), f.data()), (5, &[][..]));
    assert_eq!(
        f,
        Build::new_remote("can0", std_id(0x123), 5)
            .unwrap()
            .with_timestamp(ts(1_700_000_000, 500))
    );
}

#[test]
fn docs_log_extended_identifier() {
    let f = frame("(1700000000.000500) can0 12345678#0102");
    assert_eq!(f.id(), ext_id(0x1234_5678));
    assert!(f.is_extended());
    assert_eq!(f.data(), &[1, 2]);
}

#[test]
fn docs_log_can_fd() {
    let f = frame("(1700000000.000500) can0 123##1AABB");
    assert!(f.is_fd() && !f.is_rtr());
    assert_eq!(f.fd_flags(), FdFlags::BRS);
    assert_eq!(f.data(), &[0xAA, 0xBB]);
}

#[test]
fn docs_screen_examples() {
    let f = frame(DOCS_SCREEN);
    assert_eq!(f.timestamp(), None);
    assert_eq!(f.iface_str(), "can0");
    assert_eq!(f.id(), std_id(0x081));
    assert_eq!(f.data(), &EMCY);
    assert_eq!(f, Build::new_data("can0", std_id(0x081), &EMCY).unwrap());

    let f = frame(DOCS_SCREEN_RTR);
    assert!(f.is_rtr());
    assert_eq!(f.id(), std_id(0x705));
    assert_eq!((f.dlc(), f.data()), (1, &[][..]));
}

// ------------------------------------------------------- every form

#[test]
fn log_forms() {
    // (line, id, extended, rtr, fd, flags, dlc, data, direction)
    type Row = (
        &'static str,
        u32,
        bool,
        bool,
        bool,
        u8,
        u8,
        &'static [u8],
        Option<Direction>,
    );
    let rows: &[Row] = &[
        (
            "(1.000000) can0 080#",
            0x080,
            false,
            false,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "(1.000000) can0 701#05",
            0x701,
            false,
            false,
            false,
            0,
            1,
            &[5],
            None,
        ),
        (
            "(1.000000) can0 1ab#abcdef",
            0x1AB,
            false,
            false,
            false,
            0,
            3,
            &[0xAB, 0xCD, 0xEF],
            None,
        ),
        (
            "(1.000000) can0 7FF#0102030405060708",
            0x7FF,
            false,
            false,
            false,
            0,
            8,
            &[1, 2, 3, 4, 5, 6, 7, 8],
            None,
        ),
        (
            "(1.000000) can0 000#00",
            0,
            false,
            false,
            false,
            0,
            1,
            &[0],
            None,
        ),
        (
            "(1.000000) can0 701#r",
            0x701,
            false,
            true,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "(1.000000) can0 701#R0",
            0x701,
            false,
            true,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "(1.000000) can0 181#R8",
            0x181,
            false,
            true,
            false,
            0,
            8,
            &[],
            None,
        ),
        (
            "(1.000000) can0 181#R8 T",
            0x181,
            false,
            true,
            false,
            0,
            8,
            &[],
            Some(Direction::Tx),
        ),
        (
            "(1.000000) can0 00000123#11",
            0x123,
            true,
            false,
            false,
            0,
            1,
            &[0x11],
            None,
        ),
        (
            "(1.000000) can0 1FFFFFFF#",
            0x1FFF_FFFF,
            true,
            false,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "(1.000000) can0 1fffffff#R",
            0x1FFF_FFFF,
            true,
            true,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "(1.000000) can0 123##0",
            0x123,
            false,
            false,
            true,
            0,
            0,
            &[],
            None,
        ),
        (
            "(1.000000) can0 123##F00 R",
            0x123,
            false,
            false,
            true,
            0xF,
            1,
            &[0],
            Some(Direction::Rx),
        ),
        (
            "(1.000000) can0 123##5000102030405060708090A0B",
            0x123,
            false,
            false,
            true,
            5,
            9,
            &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11],
            None,
        ),
        (
            "(1.000000) can0 080# R",
            0x080,
            false,
            false,
            false,
            0,
            0,
            &[],
            Some(Direction::Rx),
        ),
        (
            "can0 123#11",
            0x123,
            false,
            false,
            false,
            0,
            1,
            &[0x11],
            None,
        ),
        (
            "(1.000000)\tcan0\t123#11\tT",
            0x123,
            false,
            false,
            false,
            0,
            1,
            &[0x11],
            Some(Direction::Tx),
        ),
        (
            "(1.000000)   vcan10 123#11",
            0x123,
            false,
            false,
            false,
            0,
            1,
            &[0x11],
            None,
        ),
        (
            "   (1.000000) can0 123#11   ",
            0x123,
            false,
            false,
            false,
            0,
            1,
            &[0x11],
            None,
        ),
    ];
    for &(line, id, extended, rtr, fd, flags, dlc, data, direction) in rows {
        let f = frame(line);
        assert_eq!(f.id().raw(), id, "{line}");
        assert_eq!(f.is_extended(), extended, "{line}");
        assert_eq!(f.is_rtr(), rtr, "{line}");
        assert_eq!(f.is_fd(), fd, "{line}");
        assert_eq!(f.fd_flags().bits(), flags, "{line}");
        assert_eq!(f.dlc(), dlc, "{line}");
        assert_eq!(f.data(), data, "{line}");
        assert_eq!(f.direction(), direction, "{line}");
    }
}

#[test]
fn screen_forms() {
    // (line, timestamp, id, extended, rtr, fd, flags, dlc, data, direction)
    type Row = (
        &'static str,
        Option<(u64, u32)>,
        u32,
        bool,
        bool,
        bool,
        u8,
        u8,
        &'static [u8],
        Option<Direction>,
    );
    let rows: &[Row] = &[
        (
            "  can0  12345678   [3]  11 22 33",
            None,
            0x1234_5678,
            true,
            false,
            false,
            0,
            3,
            &[0x11, 0x22, 0x33],
            None,
        ),
        (
            "  can0  12345678   [0]  remote request",
            None,
            0x1234_5678,
            true,
            true,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "  can0       123   [3]  11 22 33",
            None,
            0x123,
            false,
            false,
            false,
            0,
            3,
            &[0x11, 0x22, 0x33],
            None,
        ),
        (
            "  can0  123   [0]",
            None,
            0x123,
            false,
            false,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "  can0  123   [0] ",
            None,
            0x123,
            false,
            false,
            false,
            0,
            0,
            &[],
            None,
        ),
        (
            "  can0  123  [00]",
            None,
            0x123,
            false,
            false,
            true,
            0,
            0,
            &[],
            None,
        ),
        (
            "  can0  123  [02]  aa bb",
            None,
            0x123,
            false,
            false,
            true,
            0,
            2,
            &[0xAA, 0xBB],
            None,
        ),
        (
            "  can0  12345678  [08]  01 02 03 04 05 06 07 08",
            None,
            0x1234_5678,
            true,
            false,
            true,
            0,
            8,
            &[1, 2, 3, 4, 5, 6, 7, 8],
            None,
        ),
        (
            " (1700000000.000500)  can0  081   [8]  10 81 11 00 00 00 00 00",
            Some((1_700_000_000, 500)),
            0x081,
            false,
            false,
            false,
            0,
            8,
            &EMCY,
            None,
        ),
        (
            " (000.000123)  can0  701   [1]  05",
            Some((0, 123)),
            0x701,
            false,
            false,
            false,
            0,
            1,
            &[5],
            None,
        ),
        (
            "  can0  RX - -  081   [8]  10 81 11 00 00 00 00 00",
            None,
            0x081,
            false,
            false,
            false,
            0,
            8,
            &EMCY,
            Some(Direction::Rx),
        ),
        (
            "  can0  TX - -  705   [1]  remote request",
            None,
            0x705,
            false,
            true,
            false,
            0,
            1,
            &[],
            Some(Direction::Tx),
        ),
        (
            "  can0  TX B E  123  [02]  AA BB",
            None,
            0x123,
            false,
            false,
            true,
            3,
            2,
            &[0xAA, 0xBB],
            Some(Direction::Tx),
        ),
        (
            "  can0  RX B -  123  [01]  AA",
            None,
            0x123,
            false,
            false,
            true,
            1,
            1,
            &[0xAA],
            Some(Direction::Rx),
        ),
        (
            "  can0  RX - E  123  [01]  AA\r\n",
            None,
            0x123,
            false,
            false,
            true,
            2,
            1,
            &[0xAA],
            Some(Direction::Rx),
        ),
    ];
    for &(line, timestamp, id, extended, rtr, fd, flags, dlc, data, direction) in rows {
        let f = frame(line);
        assert_eq!(f.timestamp(), timestamp.map(|(s, u)| ts(s, u)), "{line}");
        assert_eq!(f.iface_str(), "can0", "{line}");
        assert_eq!(f.id().raw(), id, "{line}");
        assert_eq!(f.is_extended(), extended, "{line}");
        assert_eq!(f.is_rtr(), rtr, "{line}");
        assert_eq!(f.is_fd(), fd, "{line}");
        assert_eq!(f.fd_flags().bits(), flags, "{line}");
        assert_eq!(f.dlc(), dlc, "{line}");
        assert_eq!(f.data(), data, "{line}");
        assert_eq!(f.direction(), direction, "{line}");
    }
}

#[test]
fn screen_can_fd_64_bytes() {
    let bytes: Vec<u8> = (0..64).collect();
    let hex: Vec<String> = bytes.iter().map(|b| format!("{b:02X}")).collect();
    let line = format!("  can0  123  [64]  {}", hex.join(" "));
    let f = frame(&line);
    assert!(f.is_fd());
    assert_eq!(f.data(), &bytes[..]);
    assert_eq!(f.dlc(), 15);
}

#[test]
fn timestamps() {
    // (text, secs, micros)
    let rows: &[(&str, u64, u32)] = &[
        ("(1700000000.000500)", 1_700_000_000, 500),
        ("(1700000000.999999)", 1_700_000_000, 999_999),
        ("(0000000000.000000)", 0, 0),
        ("(1.5)", 1, 500_000),
        ("(1.05)", 1, 50_000),
        ("(0.000001)", 0, 1),
        ("(000.000123)", 0, 123),
        ("(123456789012345.000001)", 123_456_789_012_345, 1),
        ("(1234567890123456.1)", 1_234_567_890_123_456, 100_000),
        ("(12345678901234567.25)", 12_345_678_901_234_567, 250_000),
        ("(18446744073709551615.999999)", u64::MAX, 999_999),
        ("(00000000000000000000000001.000002)", 1, 2),
    ];
    for &(text, secs, micros) in rows {
        let line = format!("{text} can0 123#");
        assert_eq!(frame(&line).timestamp(), Some(ts(secs, micros)), "{text}");
    }
}

#[test]
fn blank_and_comment_lines_hold_no_frame() {
    for line in [
        "",
        " ",
        "\t",
        "\n",
        "\r\n",
        "  \t \r\n",
        "# a comment",
        "   # indented comment",
        "#",
    ] {
        assert_eq!(parse_line_str(line), Ok(None), "{line:?}");
        assert_eq!(general(line.as_bytes()), Ok(None), "{line:?}");
    }
}

#[test]
fn crlf_and_lf_line_ends() {
    for end in ["", "\n", "\r\n", "\r"] {
        let line = format!("{DOCS_LOG}{end}");
        assert_eq!(frame(&line), frame(DOCS_LOG), "{end:?}");
        let line = format!("{DOCS_LOG} R{end}");
        assert_eq!(frame(&line).direction(), Some(Direction::Rx), "{end:?}");
        let line = format!("{DOCS_SCREEN}{end}");
        assert_eq!(frame(&line), frame(DOCS_SCREEN), "{end:?}");
    }
}

// ---------------------------------------------------------- extremes

#[test]
fn identifier_extremes() {
    assert_eq!(frame("(1.0) can0 7FF#").id(), std_id(0x7FF));
    assert_eq!(
        fail("(1.0) can0 800#"),
        (
            12,
            SyntaxError::IdentifierOutOfRange {
                id: 0x800,
                max: 0x7FF
            }
        )
    );
    assert_eq!(
        fail("  can0  FFF   [0]"),
        (
            9,
            SyntaxError::IdentifierOutOfRange {
                id: 0xFFF,
                max: 0x7FF
            }
        )
    );
    assert_eq!(frame("(1.0) can0 1FFFFFFF#").id(), ext_id(0x1FFF_FFFF));
    // Bit 29 is Linux's CAN_ERR_FLAG: an error frame
    // (docs/formats.md#error-frames).
    let error = frame("(1.0) can0 20000000#");
    assert!(error.can().is_error());
    assert_eq!(error.id(), ext_id(0));
    assert_eq!(
        fail("(1.0) can0 40000000#"),
        (
            12,
            SyntaxError::IdentifierOutOfRange {
                id: 0x4000_0000,
                max: 0x3FFF_FFFF
            }
        )
    );
    assert_eq!(
        fail("(1.0) can0 FFFFFFFF#"),
        (
            12,
            SyntaxError::IdentifierOutOfRange {
                id: 0xFFFF_FFFF,
                max: 0x3FFF_FFFF
            }
        )
    );
    // Eight digits are always extended, as in can-utils.
    let f = frame("(1.0) can0 000007FF#");
    assert_eq!((f.id().raw(), f.is_extended()), (0x7FF, true));
}

#[test]
fn data_length_extremes() {
    let eight = "(1.0) can0 123#0011223344556677";
    assert_eq!(
        frame(eight).data(),
        &[0, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77]
    );
    assert_eq!(
        fail("(1.0) can0 123#001122334455667788"),
        (
            16,
            SyntaxError::DataTooLong {
                digits: 18,
                max_bytes: 8
            }
        )
    );
    let bytes: Vec<u8> = (0..64).map(|i| i * 3).collect();
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    let line = format!("(1.0) can0 123##2{hex}");
    let f = frame(&line);
    assert_eq!(f.data(), &bytes[..]);
    assert_eq!((f.dlc(), f.fd_flags()), (15, FdFlags::ESI));
    assert_eq!(
        fail(&format!("(1.0) can0 123##2{hex}00")),
        (
            18,
            SyntaxError::DataTooLong {
                digits: 130,
                max_bytes: 64
            }
        )
    );
    // Every CAN FD length from 0 to 64 and its DLC.
    for len in 0..=64usize {
        let hex = "ab".repeat(len);
        let line = format!("(1.0) can0 123##1{hex}\r\n");
        let f = frame(&line);
        assert_eq!(f.data().len(), len);
        let dlc = match len {
            0..=8 => len,
            9..=12 => 9,
            13..=16 => 10,
            17..=20 => 11,
            21..=24 => 12,
            25..=32 => 13,
            33..=48 => 14,
            _ => 15,
        };
        assert_eq!(usize::from(f.dlc()), dlc, "{len}");
    }
}

#[test]
fn remote_request_lengths() {
    for dlc in 0..=8u8 {
        let line = format!("(1.0) can0 123#R{dlc}");
        let f = frame(&line);
        assert_eq!((f.is_rtr(), f.dlc()), (true, dlc));
        let line = format!("  can0  123   [{dlc}]  remote request");
        let f = frame(&line);
        assert_eq!((f.is_rtr(), f.dlc()), (true, dlc));
    }
    assert_eq!(
        fail("(1.0) can0 123#R9"),
        (
            17,
            SyntaxError::BadRemoteLength {
                found: Found::Byte(b'9')
            }
        )
    );
}

// ------------------------------------------------------------ errors

#[test]
fn every_error_with_its_column() {
    use Found::{Byte, EndOfLine};
    use SyntaxError as K;
    let rows: &[(&str, usize, K)] = &[
        (
            "(17x0.000500) can0 123#00",
            4,
            K::BadTimestamp { found: Byte(b'x') },
        ),
        (
            "(1700000000) can0 123#00",
            12,
            K::BadTimestamp { found: Byte(b')') },
        ),
        (
            "(1700000000.0005001234) can0 123#00",
            22,
            K::BadTimestamp { found: Byte(b'4') },
        ),
        ("(.5) can0 123#00", 2, K::BadTimestamp { found: Byte(b'.') }),
        ("(1.) can0 123#00", 4, K::BadTimestamp { found: Byte(b')') }),
        ("(1.5 can0 123#00", 5, K::BadTimestamp { found: Byte(b' ') }),
        ("(1.5", 5, K::BadTimestamp { found: EndOfLine }),
        (
            "(18446744073709551616.0) can0 123#",
            21,
            K::BadTimestamp { found: Byte(b'6') },
        ),
        (
            "(1234567890123456789.1234567891) can0 123#",
            31,
            K::BadTimestamp { found: Byte(b'1') },
        ),
        (
            "(1.5)can0 123#00",
            6,
            K::MissingWhiteSpace { found: Byte(b'c') },
        ),
        ("(1.5)", 6, K::MissingWhiteSpace { found: EndOfLine }),
        ("(1.5) 123#00", 7, K::MissingInterface),
        (
            "(1.5) ca\x01n0 123#00",
            9,
            K::BadInterface { found: Byte(0x01) },
        ),
        (
            "(1.5) can0\x7f 123#00",
            11,
            K::BadInterface { found: Byte(0x7F) },
        ),
        (
            "(1.5) cän0 123#00",
            8,
            K::BadInterface { found: Byte(0xC3) },
        ),
        ("(1.5) #x 123#00", 7, K::BadInterface { found: Byte(b'#') }),
        ("(1.5) (x 123#00", 7, K::BadInterface { found: Byte(b'(') }),
        ("can0", 5, K::BadIdentifier { found: EndOfLine }),
        ("can0 12x#00", 8, K::BadIdentifier { found: Byte(b'x') }),
        ("can0 123", 9, K::BadIdentifier { found: EndOfLine }),
        ("can0 123X#00", 9, K::BadIdentifier { found: Byte(b'X') }),
        ("can0 #00", 6, K::BadIdentifier { found: Byte(b'#') }),
        (
            "DROPCOUNT: dropped 3 CAN frames on 'can0' socket (total drops 3)",
            13,
            K::BadIdentifier { found: Byte(b'r') },
        ),
        ("can0 1234#00", 6, K::IdentifierDigits { digits: 4 }),
        ("can0 12 [1] 00", 6, K::IdentifierDigits { digits: 2 }),
        ("can0 123456789#00", 6, K::IdentifierDigits { digits: 9 }),
        (
            "can0 12345678901234567890#00",
            6,
            K::IdentifierDigits { digits: 20 },
        ),
        (
            "can0 12345678901234567890",
            6,
            K::IdentifierDigits { digits: 20 },
        ),
        (
            "can0 800#00",
            6,
            K::IdentifierOutOfRange {
                id: 0x800,
                max: 0x7FF,
            },
        ),
        (
            "can0 60000080#00",
            6,
            K::IdentifierOutOfRange {
                id: 0x6000_0080,
                max: 0x3FFF_FFFF,
            },
        ),
        (
            "can0 20000080#R",
            15,
            K::BadErrorFrame { found: Byte(b'R') },
        ),
        (
            "can0 20000080##100",
            15,
            K::BadErrorFrame { found: Byte(b'#') },
        ),
        (
            "can0 20000080#001122334455667788",
            15,
            K::DataTooLong {
                digits: 18,
                max_bytes: 8,
            },
        ),
        (
            "  can0  20000080  [08]  00 00 00 00 00 00 00 00",
            19,
            K::BadErrorFrame { found: Byte(b'[') },
        ),
        (
            "  can0  20000080   [1]  remote request",
            25,
            K::BadHexDigit { found: Byte(b'r') },
        ),
        ("can0 123#R9", 11, K::BadRemoteLength { found: Byte(b'9') }),
        ("can0 123#RX", 11, K::BadRemoteLength { found: Byte(b'X') }),
        ("can0 123##G00", 11, K::BadFdFlags { found: Byte(b'G') }),
        ("can0 123##", 11, K::BadFdFlags { found: EndOfLine }),
        ("can0 123#1G", 11, K::BadHexDigit { found: Byte(b'G') }),
        ("can0 123#1.22", 11, K::BadHexDigit { found: Byte(b'.') }),
        ("can0 123##11G0", 13, K::BadHexDigit { found: Byte(b'G') }),
        (
            "can0 123#11223344_E",
            18,
            K::BadHexDigit { found: Byte(b'_') },
        ),
        (
            "can0 123 [2] 0G 11",
            15,
            K::BadHexDigit { found: Byte(b'G') },
        ),
        (
            "can0 123 [1] remote reques",
            14,
            K::BadHexDigit { found: Byte(b'r') },
        ),
        (
            "can0 123  [01]  remote request",
            17,
            K::BadHexDigit { found: Byte(b'r') },
        ),
        ("can0 123#123", 10, K::OddHexDigits { digits: 3 }),
        ("can0 123##0123", 12, K::OddHexDigits { digits: 3 }),
        (
            "can0 123#001122334455667788",
            10,
            K::DataTooLong {
                digits: 18,
                max_bytes: 8,
            },
        ),
        ("can0 123 [9] 00", 11, K::BadLength { found: Byte(b'9') }),
        ("can0 123 [65] 00", 11, K::BadLength { found: Byte(b'6') }),
        ("can0 123 8] 00", 10, K::BadLength { found: Byte(b'8') }),
        ("can0 123 [x] 00", 11, K::BadLength { found: Byte(b'x') }),
        ("can0 123 [8 00", 12, K::BadLength { found: Byte(b' ') }),
        ("can0 123 [123] 00", 13, K::BadLength { found: Byte(b'3') }),
        ("can0 123 (8) 00", 10, K::BadLength { found: Byte(b'(') }),
        // candump -8: a raw DLC of 11 carries 8 bytes.
        (
            "can0 123 {B} 00",
            10,
            K::LengthMismatch {
                declared: 8,
                found: 1,
            },
        ),
        ("can0 123 {b} 00", 11, K::BadLength { found: Byte(b'b') }),
        ("can0 123 {8] 00", 12, K::BadLength { found: Byte(b']') }),
        (
            "can0 123 [2] 41 42 'AC'",
            22,
            K::BadAscii {
                expected: b'B',
                found: Byte(b'C'),
            },
        ),
        (
            "can0 123 [2] 41 42 'AB",
            23,
            K::BadAscii {
                expected: b'\'',
                found: EndOfLine,
            },
        ),
        (
            "can0 123 [2] 41 42 'AB' x",
            24,
            K::TrailingGarbage { found: Byte(b' ') },
        ),
        (
            "can0 123 [2] 41 'A'",
            10,
            K::LengthMismatch {
                declared: 2,
                found: 1,
            },
        ),
        (
            "can0 123 [2] 42`41",
            14,
            K::UnsupportedOutput { option: b'S' },
        ),
        (
            "can0 123 [1] 01000001",
            14,
            K::UnsupportedOutput { option: b'i' },
        ),
        (
            "\x1b[1;31mcan0 123 [1] 4X\x1b[0m",
            22,
            K::BadHexDigit { found: Byte(b'X') },
        ),
        ("can0 123 ", 9, K::BadIdentifier { found: EndOfLine }),
        (
            "can0 123 [2] 00",
            10,
            K::LengthMismatch {
                declared: 2,
                found: 1,
            },
        ),
        (
            "can0 123 [1] 00 11",
            10,
            K::LengthMismatch {
                declared: 1,
                found: 2,
            },
        ),
        (
            "can0 123 [1]",
            10,
            K::LengthMismatch {
                declared: 1,
                found: 0,
            },
        ),
        (
            "can0 123 [02] 00",
            10,
            K::LengthMismatch {
                declared: 2,
                found: 1,
            },
        ),
        (
            "can0 123 [2] 0011",
            16,
            K::MissingWhiteSpace { found: Byte(b'1') },
        ),
        (
            "can0 123 [1]00",
            13,
            K::MissingWhiteSpace { found: Byte(b'0') },
        ),
        (
            "can0  RX X -  123  [1]  00",
            10,
            K::BadFdIndicators { found: Byte(b'X') },
        ),
        (
            "can0  RX B X  123  [1]  00",
            12,
            K::BadFdIndicators { found: Byte(b'X') },
        ),
        (
            "can0  RX B -  123   [1]  00",
            10,
            K::BadFdIndicators { found: Byte(b'B') },
        ),
        (
            "can0  TX - E  705   [1]  remote request",
            12,
            K::BadFdIndicators { found: Byte(b'E') },
        ),
        (
            "can0  RX - -  123#00",
            7,
            K::BadFdIndicators { found: Byte(b'R') },
        ),
        (
            "can0  RX - -",
            13,
            K::MissingWhiteSpace { found: EndOfLine },
        ),
        (
            "can0 123#11 X",
            13,
            K::TrailingGarbage { found: Byte(b'X') },
        ),
        (
            "can0 123#11 R X",
            15,
            K::TrailingGarbage { found: Byte(b'X') },
        ),
        (
            "can0 123#11 RR",
            14,
            K::TrailingGarbage { found: Byte(b'R') },
        ),
        ("can0 123#R12", 12, K::TrailingGarbage { found: Byte(b'2') }),
        ("can0 123#R X", 12, K::TrailingGarbage { found: Byte(b'X') }),
        (
            "can0 123#R5 X",
            13,
            K::TrailingGarbage { found: Byte(b'X') },
        ),
        (
            "can0 705 [1] remote request please",
            28,
            K::TrailingGarbage { found: Byte(b' ') },
        ),
        (
            "(1.000000) can0 123#11 R\r\nmore",
            25,
            K::TrailingGarbage { found: Byte(b'\r') },
        ),
    ];
    for &(line, column, reason) in rows {
        assert_eq!(fail(line), (column, reason), "{line:?}");
    }
}

#[test]
fn error_messages_say_expected_and_found() {
    let rows: &[(&str, &str)] = &[
        (
            "(17x0.000500) can0 123#00",
            "candump line, column 4: expected a timestamp (seconds.fraction) with 1 to 20 \
             digits before the point and 1 to 9 after, or a date (YYYY-MM-DD hh:mm:ss.fraction), found 'x'",
        ),
        (
            "(1.5)can0 123#00",
            "candump line, column 6: expected white space between fields, found 'c'",
        ),
        (
            "(1.5) 123#00",
            "candump line, column 7: expected an interface name before the frame, found the \
             frame at the start",
        ),
        (
            "(1.5) ca\x01n0 123#00",
            "candump line, column 9: expected an interface name of printable ASCII followed \
             by white space, found byte 0x01",
        ),
        (
            "can0 123",
            "candump line, column 9: expected a CAN identifier of 3 or 8 hex digits followed \
             by '#' or white space, found the end of the line",
        ),
        (
            "can0 1234#00",
            "candump line, column 6: expected a CAN identifier of 3 or 8 hex digits, found 4 \
             digits",
        ),
        (
            "can0 800#00",
            "candump line, column 6: expected an identifier at most 0x7FF, found 0x800",
        ),
        (
            "can0 123#R9",
            "candump line, column 11: expected at most one length digit 0 to 8 after 'R', \
             found '9'",
        ),
        (
            "can0 123##G",
            "candump line, column 11: expected a CAN FD flags hex digit after '##', found 'G'",
        ),
        (
            "can0 123#1G",
            "candump line, column 11: expected a hex digit, found 'G'",
        ),
        (
            "can0 123#123",
            "candump line, column 10: expected an even number of hex digits in the data, \
             found 3",
        ),
        (
            "can0 123#001122334455667788",
            "candump line, column 10: expected at most 8 data bytes (16 hex digits), found 18 \
             hex digits",
        ),
        (
            "can0 123 [9] 00",
            "candump line, column 11: expected a data length [0] to [8], or [00] to [64] for \
             CAN FD, found '9'",
        ),
        (
            "can0 123 [2] 00",
            "candump line, column 10: expected 2 data bytes as the length says, found 1",
        ),
        (
            "can0 RX B - 123 [1] 00",
            "candump line, column 9: expected '- -', 'B -', '- E' or 'B E' after RX/TX ('- -' \
             for a classic frame) before a screen-format frame, found 'B'",
        ),
        (
            "can0 123#11 X",
            "candump line, column 13: expected the end of the line (or a direction R/T in the \
             log format), found 'X'",
        ),
        (
            "can0 123#11\tX",
            "candump line, column 13: expected the end of the line (or a direction R/T in the \
             log format), found 'X'",
        ),
        (
            "can0 123#1 1",
            "candump line, column 12: expected the end of the line (or a direction R/T in the \
             log format), found '1'",
        ),
    ];
    for &(line, message) in rows {
        assert_eq!(
            parse_line_str(line).unwrap_err().to_string(),
            message,
            "{line:?}"
        );
    }
    assert_eq!(Found::Byte(b' ').to_string(), "a space");
    assert_eq!(Found::Byte(b'\t').to_string(), "a tab");
    assert_eq!(Found::Byte(0xFF).to_string(), "byte 0xff");
}

// ----------------------------------------------------------- writers

#[test]
fn write_log_exact() {
    let t = ts(1_700_000_000, 500);
    let rows: Vec<(LogFrame<'_>, &str)> = vec![
        (frame(DOCS_LOG), DOCS_LOG),
        (
            Build::new_data("can0", std_id(0x081), &EMCY)
                .unwrap()
                .with_timestamp(t)
                .with_direction(Direction::Rx),
            "(1700000000.000500) can0 081#1081110000000000 R",
        ),
        (
            Build::new_remote("can0", std_id(0x701), 0)
                .unwrap()
                .with_timestamp(t),
            "(1700000000.000500) can0 701#R",
        ),
        (
            Build::new_remote("can1", std_id(0x181), 8).unwrap(),
            "can1 181#R8",
        ),
        (
            Build::new_data("can0", ext_id(0x12AB), &[0xAB, 0xCD]).unwrap(),
            "can0 000012AB#ABCD",
        ),
        (
            Build::new_data("can0", std_id(0x80), &[])
                .unwrap()
                .with_direction(Direction::Tx),
            "can0 080# T",
        ),
        (
            Build::new_fd("can0", std_id(0x123), FdFlags::new(0xA).unwrap(), &[]).unwrap(),
            "can0 123##A",
        ),
        (
            Build::new_fd("can0", std_id(0x123), FdFlags::BRS, &[0xAA, 0xBB])
                .unwrap()
                .with_timestamp(ts(1, 2)),
            "(0000000001.000002) can0 123##1AABB",
        ),
    ];
    for (f, text) in &rows {
        assert_eq!(log(f), *text);
        assert_eq!(f.to_string(), *text);
        assert_eq!(frame(text), *f);
    }
}

#[test]
fn write_screen_exact() {
    let t = ts(1_700_000_000, 500);
    let twelve: Vec<u8> = (0..12).map(|i| i * 0x11).collect();
    let rows: Vec<(LogFrame<'_>, &str)> = vec![
        (frame(DOCS_SCREEN), DOCS_SCREEN),
        (frame(DOCS_SCREEN_RTR), DOCS_SCREEN_RTR),
        (
            Build::new_data("can0", std_id(0x081), &EMCY)
                .unwrap()
                .with_timestamp(t),
            " (1700000000.000500)  can0  081   [8]  10 81 11 00 00 00 00 00",
        ),
        (
            Build::new_data("can0", ext_id(0x1234_5678), &[0x11, 0x22, 0x33]).unwrap(),
            "  can0  12345678   [3]  11 22 33",
        ),
        (
            Build::new_remote("can0", ext_id(0x1234_5678), 0).unwrap(),
            "  can0  12345678   [0]  remote request",
        ),
        (
            Build::new_data("can0", std_id(0x123), &[]).unwrap(),
            "  can0  123   [0] ",
        ),
        (
            Build::new_fd("can0", std_id(0x123), FdFlags::EMPTY, &twelve).unwrap(),
            "  can0  123  [12]  00 11 22 33 44 55 66 77 88 99 AA BB",
        ),
        (
            Build::new_fd("can0", std_id(0x123), FdFlags::EMPTY, &[]).unwrap(),
            "  can0  123  [00] ",
        ),
        (
            Build::new_fd(
                "can0",
                std_id(0x123),
                FdFlags::BRS.union(FdFlags::ESI),
                &[0xAA, 0xBB],
            )
            .unwrap()
            .with_direction(Direction::Tx),
            "  can0  TX B E  123  [02]  AA BB",
        ),
        (
            Build::new_remote("can0", std_id(0x705), 1)
                .unwrap()
                .with_direction(Direction::Rx)
                .with_timestamp(t),
            " (1700000000.000500)  can0  RX - -  705   [1]  remote request",
        ),
    ];
    for (f, text) in &rows {
        assert_eq!(screen(f), *text);
        assert_eq!(frame(text), *f);
    }
}

#[test]
fn screen_drops_fd_flags_it_cannot_show() {
    // FDF has no place on the screen; BRS shows only in the -x column.
    let f = Build::new_fd(
        "can0",
        std_id(0x123),
        FdFlags::FDF.union(FdFlags::BRS),
        &[1],
    )
    .unwrap();
    assert_eq!(screen(&f), "  can0  123  [01]  01");
    assert_eq!(frame(&screen(&f)).fd_flags(), FdFlags::EMPTY);
    let f = f.with_direction(Direction::Rx);
    assert_eq!(frame(&screen(&f)).fd_flags(), FdFlags::BRS);
    // The log format keeps every flag.
    assert_eq!(frame(&log(&f)), f);
}

// ------------------------------------------------------ constructors

#[test]
fn constructors_check_their_values() {
    // The frame's limits are the crate's frame constructors' (can::CanFrame).
    assert_eq!(
        Build::new_data("can0", std_id(1), &[0; 9]),
        Err(crate::CodecError::OutOfRange(crate::RangeError {
            what: What::CanFrameDataLength,
            found: 9,
            min: 0,
            max: 8
        }))
    );
    assert_eq!(
        Build::new_fd("can0", std_id(1), FdFlags::EMPTY, &[0; 65]),
        Err(crate::CodecError::OutOfRange(crate::RangeError {
            what: What::CanFrameDataLength,
            found: 65,
            min: 0,
            max: 64
        }))
    );
    assert_eq!(
        Build::new_remote("can0", std_id(1), 9),
        Err(crate::CodecError::OutOfRange(crate::RangeError {
            what: What::CanRemoteRequestLength,
            found: 9,
            min: 0,
            max: 8
        }))
    );
}

// ------------------------------------------------------------- lines

const LOG: &str = "(1700000000.000500) can0 081#1081110000000000\r\n\
                   \n\
                   # a comment\n\
                   (1700000000.000600) can0 0X1#00\n\
                   DROPCOUNT: dropped 1 CAN frame on 'can0' socket (total drops 1)\n\
                     can0  705   [1]  remote request\n\
                   (1700000000.000700)  vcan10 12345678##3AABB T\n\
                   (1700000000.000800) can0 701#7F";

#[test]
fn lines_numbers_every_line() {
    let items: Vec<_> = lines(LOG.as_bytes()).collect();
    assert_eq!(items.len(), 8);
    let numbers: Vec<u64> = items.iter().map(|(n, _)| n.number()).collect();
    assert_eq!(numbers, [1, 2, 3, 4, 5, 6, 7, 8]);
    assert_eq!(items[0].1, Ok(Some(frame(DOCS_LOG))));
    assert_eq!(items[1].1, Ok(None));
    assert_eq!(items[2].1, Ok(None));
    assert_eq!(
        items[3].1,
        Err(FormatError::Syntax {
            format: LogFormat::Candump,
            column: 27,
            reason: SyntaxError::BadIdentifier {
                found: Found::Byte(b'X')
            }
        })
    );
    assert!(items[4].1.is_err());
    assert!(items[5].1.as_ref().unwrap().unwrap().is_rtr());
    let fd = items[6].1.unwrap().unwrap();
    assert_eq!(
        (fd.iface_str(), fd.id(), fd.fd_flags().bits(), fd.data()),
        ("vcan10", ext_id(0x1234_5678), 3, &[0xAA, 0xBB][..])
    );
    assert_eq!(fd.direction(), Some(Direction::Tx));
    assert_eq!(items[7].1.unwrap().unwrap().data(), &[0x7F]);
    // Every line as `parse_line` reads it alone.
    for ((_, result), line) in items.iter().zip(LOG.split('\n')) {
        assert_eq!(*result, parse_line_str(line), "{line:?}");
    }
}

#[test]
fn lines_fold_matches_next() {
    let by_next: Vec<_> = lines(LOG.as_bytes()).by_ref().collect();
    let mut by_fold = Vec::new();
    lines(LOG.as_bytes()).for_each(|item| by_fold.push(item));
    assert_eq!(by_next, by_fold);
    assert_eq!(lines(LOG.as_bytes()).count(), 8);
}

#[test]
fn lines_ends_and_remainder() {
    assert_eq!(lines(b"").next(), None);
    assert_eq!(
        lines(b"\n").collect::<Vec<_>>(),
        [(Position::Line(1), Ok(None))]
    );
    assert_eq!(lines(b"\n\n").count(), 2);
    let mut it = lines(b"can0 123#11\ncan0 123#22");
    assert_eq!(it.remainder(), b"can0 123#11\ncan0 123#22");
    assert!(it.next().is_some());
    assert_eq!(it.remainder(), b"can0 123#22");
    assert!(it.next().is_some());
    assert_eq!((it.next(), it.next()), (None, None));
}

#[test]
fn hex_decoding_matches_a_table() {
    // Every byte value, as the one digit that differs in a classic and a
    // CAN FD data field, on the fast and the general path.
    for b in 0..=255u8 {
        let mut line = b"(1700000000.000500) can0 123#0011223344556677".to_vec();
        line[31] = b;
        let expected = hex_value(b).map(|v| v << 4 | 1);
        match parse_line(&line) {
            Ok(Some(f)) => assert_eq!(Some(f.data()[1]), expected, "{b:#x}"),
            Ok(None) => panic!("{b:#x}"),
            Err(_) => assert_eq!(expected, None, "{b:#x}"),
        }
        assert_eq!(parse_line(&line), general(&line), "{b:#x}");
    }
    for (a, b) in [(b'0', b'9'), (b'a', b'f'), (b'A', b'F')] {
        for c in a..=b {
            let line = format!("(1.0) can0 123#{}{}", char::from(c), char::from(c));
            let v = hex_value(c).unwrap();
            assert_eq!(frame(&line).data(), &[v << 4 | v]);
        }
    }
}

// ---------------------------- error frames (docs/formats.md#error-frames)

/// `candump -e -l` and python-can's `CanutilsLogWriter` write error frames
/// with CAN_ERR_FLAG in an 8-digit identifier.
#[test]
fn error_frames_in_the_log_format() {
    let f = frame("(1700000000.000500) can0 20000004#0004000000000000");
    assert!(f.can().is_error() && f.is_extended());
    assert_eq!(f.id().raw(), 0x004);
    assert_eq!(f.data(), [0, 4, 0, 0, 0, 0, 0, 0]);
    assert_eq!(
        log(&f),
        "(1700000000.000500) can0 20000004#0004000000000000"
    );
    // python-can writes every error frame as 0x20000080, data as it has it.
    let p = frame("(1700000000.000500) vcan0 20000080#");
    assert!(p.can().is_error());
    assert_eq!((p.id().raw(), p.data()), (0x080, &[][..]));
    assert_eq!(
        Build::new_error("can0", 0x004, &[0, 4, 0, 0, 0, 0, 0, 0]).unwrap(),
        frame("can0 20000004#0004000000000000")
    );
}

/// `candump -e can0` prints `ERRORFRAME` after the data, right-aligned as
/// can-utils' `snprintf_long_canframe` does, and its explanation on
/// tab-indented lines after it.
#[test]
fn error_frames_in_the_screen_format() {
    let line = "  can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME";
    let f = frame(line);
    assert!(f.can().is_error());
    assert_eq!(
        (f.id().raw(), f.data()),
        (0x004, &[0, 4, 0, 0, 0, 0, 0, 0][..])
    );
    assert_eq!(screen(&f), line);
    // Fewer bytes: ERRORFRAME stays in its column.
    let short = Build::new_error("can0", 0x040, &[0, 0]).unwrap();
    let text = screen(&short);
    assert_eq!(
        text,
        "  can0  20000040   [2]  00 00                     ERRORFRAME"
    );
    assert_eq!(frame(&text), short);
    // Without the word (as a tool that drops it may write): still read.
    assert!(frame("  can0  20000004   [8]  00 04 00 00 00 00 00 00")
        .can()
        .is_error());
    // The word after a frame that is not an error frame is not hex.
    assert_eq!(
        fail("  can0  123   [0]  ERRORFRAME"),
        (
            21,
            SyntaxError::BadHexDigit {
                found: Found::Byte(b'R')
            }
        )
    );
}

#[test]
fn error_frame_explanation_lines_belong_to_the_frame() {
    let log = "\
 (1700000000.000500)  can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME
\tcontroller-problem{rx-error-warning}
\terror-counter-tx-rx{{0}{0}}
 (1700000000.000600)  can0  081   [8]  10 81 11 00 00 00 00 00
\tbus-off
";
    let items: Vec<_> = lines(log.as_bytes()).collect();
    assert!(items[0].1.as_ref().unwrap().unwrap().can().is_error());
    assert_eq!((&items[1].1, &items[2].1), (&Ok(None), &Ok(None)));
    assert!(items[3].1.as_ref().unwrap().is_some());
    // No error frame before it: an explanation word alone is malformed.
    assert!(items[4].1.is_err());
    // After an error frame, a tab-indented line that is a frame stays a
    // frame, and one that is neither a frame nor an explanation stays an
    // error: nothing is hidden.
    let mixed = "can0 20000040#0000000000000000\n\tcan1 123#01\n\tbus-offline\n\tbus-off\n";
    let items: Vec<_> = lines(mixed.as_bytes()).map(|(_, r)| r).collect();
    assert!(items[0].as_ref().unwrap().unwrap().can().is_error());
    assert_eq!(items[1].as_ref().unwrap().unwrap().id().raw(), 0x123);
    assert!(items[2].is_err());
    assert!(items[3].is_err(), "an explanation after a data frame");
    // Read in two blocks, the state carries over.
    let (first, second) = log.split_at(log.find("\tcontroller").unwrap());
    let mut block = lines(first.as_bytes());
    for _ in block.by_ref() {}
    let next: Vec<_> = lines_from(second.as_bytes(), block.state()).collect();
    assert_eq!(next[0].1, Ok(None));
    // Without the state, a lone explanation line is malformed.
    assert!(parse_line(b"\tcontroller-problem{rx-error-warning}").is_err());
}

/// A `candump -c` line whose text without its colour escapes is 512 bytes
/// long fits the buffer the escapes are stripped into, with or without
/// leading white space (which is not copied): the line with one leading
/// space reads as the line without, its error at the same column. The input
/// is the one a fuzz run of `candump_line` found.
#[test]
fn indentation_never_decides_how_a_coloured_line_reads() {
    let input = include_bytes!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/regressions/candump_line-crash-60073776.bin"
    ));
    let line = match input.iter().position(|&b| b == b'\n') {
        Some(end) => &input[..=end],
        None => &input[..],
    };
    let Err(FormatError::Syntax { column, reason, .. }) = parse_line(line) else {
        panic!("the line is malformed");
    };
    for indent in 1..=3 {
        let mut spaced = vec![b' '; indent];
        spaced.extend_from_slice(line);
        match parse_line(&spaced) {
            Err(FormatError::Syntax {
                column: shifted,
                reason: shifted_reason,
                ..
            }) => {
                assert_eq!(shifted, column + indent, "{indent} spaces: {reason}");
                assert_eq!(shifted_reason, reason);
            }
            other => panic!("{indent} spaces: {other:?}"),
        }
    }
    // Tabs too, and a coloured frame line still reads.
    let mut tabbed = b"\t\t".to_vec();
    tabbed.extend_from_slice(line);
    assert!(
        matches!(parse_line(&tabbed), Err(FormatError::Syntax { column: c, .. }) if c == column + 2)
    );
    let coloured = b"   \x1b[1;31mcan0  123   [1]  42\x1b[0m";
    let frame = parse_line(coloured).unwrap().unwrap();
    assert_eq!(frame.frame.data(), [0x42]);
}
