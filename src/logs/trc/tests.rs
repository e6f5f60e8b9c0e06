//! Unit tests: the header keys, each version's rows from PEAK's format
//! description, and every kind of malformed line.

use super::header::Layout;
use super::*;
use crate::can::{
    CanFrame, CanId, Direction, FdFlags, FrameType, Iface, LogEvent, LogFrame, Timestamp,
};
use crate::logs::FormatError;
use crate::logs::{Found, LogFormat, SyntaxError};

fn parser(header: &[&str]) -> TrcParser {
    let mut parser = TrcParser::new();
    for line in header {
        assert_eq!(parser.parse_line(line.as_bytes()), Ok(None), "{line}");
    }
    parser
}

fn frame<'l>(parser: &mut TrcParser, line: &'l str) -> LogFrame<'l> {
    match parser.parse_line(line.as_bytes()) {
        Ok(Some(LogEvent::Frame(frame))) => frame,
        other => panic!("{line}: {other:?}"),
    }
}

fn error(parser: &mut TrcParser, line: &str) -> (usize, SyntaxError) {
    match parser.parse_line(line.as_bytes()) {
        Err(FormatError::Syntax {
            format: LogFormat::Trc,
            column,
            reason,
        }) => (column, reason),
        other => panic!("{line}: {other:?}"),
    }
}

fn std_id(raw: u32) -> CanId {
    CanId::standard(raw).unwrap()
}

#[test]
fn blank_and_comment_lines_hold_nothing() {
    let mut p = TrcParser::new();
    for line in [
        "",
        "\r\n",
        "   \t ",
        ";",
        ";   Start time: 18.12.2021",
        "  ;$OTHER=1",
    ] {
        assert_eq!(p.parse_line(line.as_bytes()), Ok(None), "{line:?}");
    }
    assert_eq!(p, TrcParser::new());
}

#[test]
fn file_versions() {
    for version in TrcVersion::ALL {
        let line = format!(";$FILEVERSION={version}\r\n");
        let p = parser(&[&line]);
        assert_eq!(p.version(), version);
    }
    let mut p = TrcParser::new();
    assert_eq!(
        error(&mut p, ";$FILEVERSION=3.0"),
        (
            15,
            SyntaxError::TrcFileVersion {
                found: Found::Byte(b'3')
            }
        )
    );
    assert_eq!(
        error(&mut p, ";$FILEVERSION="),
        (
            15,
            SyntaxError::TrcFileVersion {
                found: Found::EndOfLine
            }
        )
    );
}

#[test]
fn start_time_is_read_exactly_to_the_microsecond() {
    let cases = [
        ("25569", 0, 0),
        ("25569.5", 43_200, 0),
        // 1 µs is 1/86 400 000 000 of a day.
        ("25569.0000000000115740740740", 0, 1),
        // Just under half a microsecond rounds down, just over rounds up.
        ("25569.000000000005787", 0, 0),
        ("25569.000000000005788", 0, 1),
        // python-can's TRCWriter for 1700000000.000500.
        ("45244.92592593171", 1_700_000_000, 500),
        // PEAK's 10 digits of days.
        ("44548.6028595139", 1_639_837_687, 62_001),
    ];
    for (text, secs, micros) in cases {
        let p = parser(&[&format!(";$STARTTIME={text}")]);
        assert_eq!(p.start_time(), Timestamp::new(secs, micros), "{text}");
    }
    let mut p = TrcParser::new();
    assert_eq!(
        error(&mut p, ";$STARTTIME=25568.9"),
        (
            13,
            SyntaxError::TrcStartTime {
                found: Found::Byte(b'2')
            }
        )
    );
    assert_eq!(
        error(&mut p, ";$STARTTIME=4.5e4"),
        (
            16,
            SyntaxError::TrcStartTime {
                found: Found::Byte(b'e')
            }
        )
    );
}

#[test]
fn columns_must_be_distinct_known_and_complete() {
    let p = parser(&[";$FILEVERSION=2.0", ";$COLUMNS=N,O,T,I,d,l,D"]);
    assert_eq!(p.layout, Some(Layout::V2_0));
    let mut p = TrcParser::new();
    for (text, column, found) in [
        ("N,O,T,I,d,X,D", 21, Found::Byte(b'X')),
        ("N,O,T,I,I,L,D", 19, Found::Byte(b'I')),
        ("N,O,T,I,D,L", 21, Found::Byte(b'L')),
        ("N,O,T,I,d,D", 22, Found::EndOfLine),
        ("N,O,T,,I,L", 17, Found::Byte(b',')),
        ("N,O,TI,L", 16, Found::Byte(b'I')),
        ("", 11, Found::EndOfLine),
    ] {
        assert_eq!(
            error(&mut p, &format!(";$COLUMNS={text}")),
            (column, SyntaxError::TrcColumns { found }),
            "{text}"
        );
    }
}

/// PEAK's example rows of version 1.0: a data frame, an error frame, an
/// error warning and a remote request.
#[test]
fn version_1_0_rows() {
    let mut p = TrcParser::new();
    let data = frame(
        &mut p,
        "     1)      1841  0001  8  00 01 02 03 04 05 06 07",
    );
    assert_eq!(
        data.frame,
        CanFrame::new(std_id(1), &[0, 1, 2, 3, 4, 5, 6, 7]).unwrap()
    );
    assert_eq!(data.timestamp, Timestamp::new(1, 841_000));
    assert_eq!((data.iface, data.direction), (None, None));

    let err = frame(&mut p, "     2)      1842  0008  4  ERROR 00 19 08 08");
    assert!(err.frame.is_error());
    assert_eq!(err.frame.id().raw(), ERROR_FRAME_CLASSES.bits());
    // "Other" (8) is Linux's unspecified type; direction 0: while sending.
    assert_eq!(err.frame.data(), [0, 0, 0x80, 0x19, 0, 0, 0x08, 0x08]);

    let status = p.parse_line(b"     3)      1843  FFFFFFFF  4  00 00 00 04 ------BUSLIGHT");
    assert_eq!(
        status,
        Ok(Some(LogEvent::Status(BusStatus {
            timestamp: Timestamp::new(1, 843_000),
            iface: None
        })))
    );
    let rtr = frame(&mut p, "     4)      1844  0100  3  RTR");
    assert_eq!(rtr.frame, CanFrame::new_remote(std_id(0x100), 3).unwrap());
}

use crate::can::BusStatus;

#[test]
fn version_1_x_columns() {
    let start = ";$STARTTIME=25569";
    let mut p = parser(&[";$FILEVERSION=1.1", start]);
    let f = frame(&mut p, "  7)  7468.9  Tx  18FF1234  2  0A 0B");
    assert_eq!(f.frame.id(), CanId::extended(0x18FF_1234).unwrap());
    assert_eq!(f.direction, Some(Direction::Tx));
    assert_eq!(f.timestamp, Timestamp::new(7, 468_900));
    assert!(matches!(
        p.parse_line(b"  8)  7469.0  Warng  FFFFFFFF  4  00 00 00 08  BUSHEAVY"),
        Ok(Some(LogEvent::Status(_)))
    ));

    let mut p = parser(&[";$FILEVERSION=1.2", start]);
    let f = frame(&mut p, "  1)  1.5 3  Rx  0705  1  05");
    assert_eq!(f.iface, Some(Iface::Channel(3)));
    assert_eq!(f.frame.data(), [5]);

    let mut p = parser(&[";$FILEVERSION=1.3", start]);
    let f = frame(&mut p, "  1)  1.500 2  Rx  0705 -  1  RTR");
    assert_eq!(f.iface, Some(Iface::Channel(2)));
    assert_eq!(f.frame.frame_type(), FrameType::Remote { dlc: 1 });
    let s = p.parse_line(b"  2)  2.000 2  Warng  FFFFFFFF -  4  00 00 00 08 BUSOFF");
    assert_eq!(
        s,
        Ok(Some(LogEvent::Status(BusStatus {
            timestamp: Timestamp::new(0, 2_000),
            iface: Some(Iface::Channel(2))
        })))
    );
    assert_eq!(
        error(&mut p, "  3)  3.000 2  Rx  0705 -  2  01"),
        (
            33,
            SyntaxError::LengthMismatch {
                declared: 2,
                found: 1
            }
        )
    );
    assert_eq!(
        error(&mut p, "  3x)  3.000 2  Rx  0705 -  1  01"),
        (
            4,
            SyntaxError::TrcMessageNumber {
                found: Found::Byte(b'x')
            }
        )
    );
}

#[test]
fn version_2_fd_types_and_lengths() {
    let mut p = parser(&[";$FILEVERSION=2.1", ";$STARTTIME=25569"]);
    for (kind, flags) in [
        ("FD", FdFlags::EMPTY),
        ("FB", FdFlags::BRS),
        ("FE", FdFlags::ESI),
        ("BI", FdFlags::BRS.union(FdFlags::ESI)),
    ] {
        let bytes: Vec<String> = (0..12).map(|b| format!("{b:02X}")).collect();
        let line = format!("  1  0.001 {kind} 1  0123 Rx -  9  {}", bytes.join(" "));
        let f = frame(&mut p, &line);
        assert_eq!(f.frame.frame_type(), FrameType::Fd(flags), "{kind}");
        assert_eq!((f.frame.data().len(), f.frame.dlc()), (12, 9));
        assert_eq!(f.timestamp, Timestamp::from_nanos(0, 1_000));
    }
    // Without $COLUMNS a 2.1 file has PEAK's 2.1 columns; the offset may
    // have up to 6 digits after the point.
    let f = frame(&mut p, "  2  1.000001 RR 2  00000705 Tx -  8");
    assert_eq!(
        f.frame,
        CanFrame::new_remote(CanId::extended(0x705).unwrap(), 8).unwrap()
    );
    assert_eq!(f.timestamp, Timestamp::from_nanos(0, 1_000_001));
    assert_eq!(f.iface, Some(Iface::Channel(2)));
    let f = frame(&mut p, "  3  2.000 DT -  0705 - -  0");
    assert_eq!((f.iface, f.direction), (None, None));
}

#[test]
fn version_2_0_uses_byte_lengths() {
    let mut p = parser(&[";$FILEVERSION=2.0", ";$COLUMNS=N,O,T,I,d,l,D"]);
    let f = frame(
        &mut p,
        "  1  5.000 FD 0500 Rx 16 00 01 02 03 04 05 06 07 08 09 0A 0B 0C 0D 0E 0F",
    );
    assert_eq!((f.frame.data().len(), f.frame.dlc()), (16, 10));
    assert_eq!(f.iface, None);
    let e = frame(&mut p, "  2  6.000 ER      Tx    01 01 1C 7F 80");
    assert_eq!(e.frame.data(), [0, 0, 0x01, 0x1C, 0, 0, 0x80, 0x7F]);
    assert_eq!(e.direction, Some(Direction::Tx));
    for line in [
        "  3  7.000 ST      Rx    00 00 00 08",
        "  4  8.000 EC      Rx    02 02",
    ] {
        assert!(matches!(
            p.parse_line(line.as_bytes()),
            Ok(Some(LogEvent::Status(_)))
        ));
    }
    assert_eq!(
        error(&mut p, "  5  9.000 ER      Rx    04 00 02 00"),
        (
            37,
            SyntaxError::TrcErrorFrame {
                expected: 5,
                found: 4
            }
        )
    );
}

#[test]
fn malformed_rows_say_where_and_why() {
    let mut p = parser(&[";$FILEVERSION=2.1"]);
    let cases: [(&str, usize, SyntaxError); 9] = [
        (
            "  1  1.000 XX 1  0705 Rx -  0",
            12,
            SyntaxError::TrcRowType {
                found: Found::Byte(b'X'),
            },
        ),
        (
            "  1  1.0.0 DT 1  0705 Rx -  0",
            9,
            SyntaxError::TrcTimeOffset {
                found: Found::Byte(b'.'),
            },
        ),
        (
            "  1  1.0000001 DT 1  0705 Rx -  0",
            14,
            SyntaxError::TrcTimeOffset {
                found: Found::Byte(b'1'),
            },
        ),
        (
            "  1  1.000 DT 1  0800 Rx -  0",
            18,
            SyntaxError::IdentifierOutOfRange {
                id: 0x800,
                max: 0x7FF,
            },
        ),
        (
            "  1  1.000 DT 1  07G5 Rx -  0",
            20,
            SyntaxError::TrcIdentifier {
                found: Found::Byte(b'G'),
            },
        ),
        (
            "  1  1.000 DT x  0705 Rx -  0",
            15,
            SyntaxError::TrcBus {
                found: Found::Byte(b'x'),
            },
        ),
        (
            "  1  1.000 DT 1  0705 RX -  0",
            23,
            SyntaxError::TrcDirection {
                found: Found::Byte(b'R'),
            },
        ),
        (
            "  1  1.000 DT 1  0705 Rx -  9  00",
            29,
            SyntaxError::TrcLength {
                found: Found::Byte(b'9'),
            },
        ),
        (
            "  1  1.000 DT 1  0705 Rx -  1  0",
            33,
            SyntaxError::TrcDataByte {
                found: Found::EndOfLine,
            },
        ),
    ];
    for (line, column, reason) in cases {
        assert_eq!(error(&mut p, line), (column, reason), "{line}");
    }
    assert_eq!(
        error(&mut p, "  1  1.000 RR 1  0705 Rx -  1  00"),
        (
            32,
            SyntaxError::TrcTrailing {
                found: Found::Byte(b'0')
            }
        )
    );
    assert_eq!(
        error(&mut p, "  1  1.000 DT 1  0705 Rx -  1"),
        (
            30,
            SyntaxError::LengthMismatch {
                declared: 1,
                found: 0
            }
        )
    );
    assert_eq!(
        error(&mut p, "  1  1.000 DT 1  0705"),
        (
            22,
            SyntaxError::TrcDirection {
                found: Found::EndOfLine
            }
        )
    );
    let message = error(&mut p, "  1  1.000 DT 1  0705 Rx -  1  ZZ")
        .1
        .to_string();
    assert_eq!(message, "expected a data byte of two hex digits, found 'Z'");
}

#[test]
fn written_rows_read_back() {
    let start = Timestamp::new(1_700_000_000, 500).unwrap();
    let mut text = String::new();
    write_header(&mut text, start).unwrap();
    assert!(text.starts_with(";$FILEVERSION=2.1\r\n;$STARTTIME=45244.92592593171296296296\r\n"));
    let frames = [
        LogFrame::new(CanFrame::new_fd(std_id(0x123), FdFlags::BRS, &[0xAB; 64]).unwrap())
            .with_timestamp(start)
            .with_iface(Iface::Channel(2))
            .with_direction(Direction::Tx),
        LogFrame::new(
            CanFrame::new_error(ERROR_FRAME_CLASSES.bits(), &[0, 0, 0x84, 2, 0, 0, 9, 7]).unwrap(),
        )
        .with_timestamp(Timestamp::from_nanos(1_700_000_001, 123_456_789).unwrap()),
    ];
    for (n, f) in frames.iter().enumerate() {
        write_line(&mut text, n as u64, start, f).unwrap();
    }
    let read: Vec<_> = lines(text.as_bytes())
        .filter_map(|(_, r)| r.unwrap())
        .collect();
    assert_eq!(read, frames.map(LogEvent::Frame));

    let mut out = String::new();
    let named = frames[0].with_iface(Iface::Name("can0"));
    assert!(write_line(&mut out, 0, start, &named).is_err());
    let odd = LogFrame::new(CanFrame::new_fd(std_id(1), FdFlags::EMPTY, &[0; 10]).unwrap())
        .with_timestamp(start);
    assert!(write_line(&mut out, 0, start, &odd).is_err());
    let early = frames[0].with_timestamp(Timestamp::new(1, 0).unwrap());
    assert!(write_line(&mut out, 0, start, &early).is_err());
}
