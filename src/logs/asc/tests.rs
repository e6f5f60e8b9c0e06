use super::*;
use crate::can::{CanFrame, CanId, ErrorClasses};
use crate::logs::FormatError;
use crate::logs::Found;
use crate::logs::SyntaxError as K;
use crate::logs::{LogFormat, SyntaxError};

fn parse(parser: &mut AscParser, line: &str) -> Result<Option<LogEvent<'static>>> {
    // Leak-free: the lines are 'static literals.
    let line: &'static str = Box::leak(line.to_owned().into_boxed_str());
    parser.parse_line(line.as_bytes())
}

fn err(line: &str) -> (usize, SyntaxError) {
    let mut parser = AscParser::new();
    match parse(&mut parser, line) {
        Err(FormatError::Syntax {
            format: LogFormat::Asc,
            column,
            reason,
        }) => (column, reason),
        other => panic!("{line:?}: {other:?}"),
    }
}

#[test]
fn header_and_comment_lines_hold_nothing() {
    let mut parser = AscParser::new();
    for line in [
        "",
        "   ",
        "date Mon Nov 23 07:35:00.000 2026",
        "base hex  timestamps absolute",
        "internal events logged",
        "no internal events logged",
        "// version 13.0.0",
        "Begin Triggerblock Mon Nov 23 07:35:00.000 2026",
        "   0.000000 Start of measurement",
        "   1.000000 Log trigger event",
        "   1.000000 1  Statistic: D 0 R 0 XD 0 XR 0 E 0 O 0 B 0.00%",
        "   1.000000 1  705             TxRq d 1 05",
        "   1.000000 SV: 1 0 1 ::Namespace::Var = 1",
        "   1.000000 1  J1939TP FEF1p 6 0 0 - Rx d 23 01 02",
        "End TriggerBlock",
        "\r",
    ] {
        assert_eq!(parse(&mut parser, line), Ok(None), "{line:?}");
    }
}

#[test]
fn frames_of_every_shape() {
    let mut parser = AscParser::new();
    let frame = |parser: &mut AscParser, line: &str| match parse(parser, line) {
        Ok(Some(LogEvent::Frame(f))) => f,
        other => panic!("{line:?}: {other:?}"),
    };
    let f = frame(
        &mut parser,
        "   0.012345 1  123             Rx   d 8 11 22 33 44 55 66 77 88",
    );
    assert_eq!(
        f.frame.data(),
        &[0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88]
    );
    assert_eq!(f.timestamp, Timestamp::new(0, 12_345));
    // Trailing bus timing fields, and a raw DLC of 15 on 8 bytes.
    let f = frame(
        &mut parser,
        "   0.5 2  18FF1234x  Tx   d F 01 02 03 04 05 06 07 08  Length = 228000 BitCount = 118 ID = 419369524x",
    );
    assert!(f.frame.is_extended());
    assert_eq!(f.frame.data().len(), 8);
    assert_eq!(f.iface, Some(Iface::Channel(2)));
    assert_eq!(f.direction, Some(Direction::Tx));
    let f = frame(&mut parser, "   0.6 1  705             Rx   r");
    assert_eq!(f.frame.frame_type(), FrameType::Remote { dlc: 0 });
    let f = frame(&mut parser, "   0.6 1  705             Rx   r 1");
    assert_eq!(f.frame.frame_type(), FrameType::Remote { dlc: 1 });
    let f = frame(&mut parser, "   0.7 1  ErrorFrame");
    assert!(f.frame.is_error());
    assert_eq!(
        crate::can::ErrorFrame::from_frame(&f.frame)
            .unwrap()
            .classes,
        ErrorClasses::BUS_ERROR
    );
    // Nanoseconds.
    let f = frame(&mut parser, "   0.000000001 1  1 Rx d 0");
    assert_eq!(f.timestamp, Timestamp::from_nanos(0, 1));
    assert!(matches!(
        parse(&mut parser, "   0.9 1  OverloadFrame"),
        Ok(Some(LogEvent::Status(_)))
    ));
    match parse(&mut parser, "   0.8 CAN 2 Status:chip status error passive") {
        Ok(Some(LogEvent::Status(status))) => {
            assert_eq!(status.iface, Some(Iface::Channel(2)));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn relative_times_add_up_and_restart_with_a_trigger_block() {
    let mut parser = AscParser::new();
    assert_eq!(parse(&mut parser, "base hex timestamps relative"), Ok(None));
    let ts = |parser: &mut AscParser, line: &str| match parse(parser, line) {
        Ok(Some(LogEvent::Frame(f))) => f.timestamp.unwrap(),
        other => panic!("{other:?}"),
    };
    assert_eq!(
        ts(&mut parser, " 1.0 1 1 Rx d 0"),
        Timestamp::new(1, 0).unwrap()
    );
    assert_eq!(parse(&mut parser, " 0.5 Start of measurement"), Ok(None));
    assert_eq!(
        ts(&mut parser, " 0.25 1 1 Rx d 0"),
        Timestamp::new(1, 750_000).unwrap()
    );
    assert_eq!(
        parse(&mut parser, "Begin Triggerblock Mon Nov 23 2026"),
        Ok(None)
    );
    assert_eq!(
        ts(&mut parser, " 0.25 1 1 Rx d 0"),
        Timestamp::new(0, 250_000).unwrap()
    );
}

#[test]
fn every_error_with_its_column() {
    use Found::{Byte, EndOfLine};
    let rows: &[(&str, usize, SyntaxError)] = &[
        ("hello", 1, K::AscLine { found: Byte(b'h') }),
        ("base oct", 6, K::AscBase { found: Byte(b'o') }),
        (
            "base hex timestamps sometimes",
            21,
            K::AscBase { found: Byte(b's') },
        ),
        ("1.x 1 1 Rx d 0", 3, K::AscTime { found: Byte(b'x') }),
        (
            "1.0123456789 1 1 Rx d 0",
            13,
            K::AscTime { found: Byte(b' ') },
        ),
        ("1.0", 4, K::AscChannel { found: EndOfLine }),
        ("1.0 0 1 Rx d 0", 5, K::AscChannel { found: Byte(b'0') }),
        (
            "1.0 1 800 Rx d 0",
            7,
            K::AscIdentifier { found: Byte(b'8') },
        ),
        (
            "1.0 1 20000000x Rx d 0",
            7,
            K::AscIdentifier { found: Byte(b'2') },
        ),
        ("1.0 1 1 Qx d 0", 9, K::AscDirection { found: Byte(b'Q') }),
        ("1.0 1 1 Rx q 0", 12, K::AscFrameType { found: Byte(b'q') }),
        ("1.0 1 1 Rx d", 13, K::AscDlc { found: EndOfLine }),
        ("1.0 1 1 Rx d 10", 14, K::AscDlc { found: Byte(b'1') }),
        ("1.0 1 1 Rx d 2 01", 18, K::AscDataByte { found: EndOfLine }),
        (
            "1.0 1 1 Rx d 1 1FF",
            16,
            K::AscDataByte { found: Byte(b'1') },
        ),
        (
            "1.0 1 1 Rx d 1 G0",
            16,
            K::AscDataByte { found: Byte(b'G') },
        ),
        (
            "1.0 CANFD 1 Rx 1 x 2 0 0 0",
            20,
            K::AscFdColumn { found: Byte(b'2') },
        ),
        (
            "1.0 CANFD 1 Rx 1 0 0 9 11 00",
            24,
            K::AscDataLength { found: Byte(b'1') },
        ),
        (
            "1.0 CANFD 1 Rx 1 0 0 1 1 00",
            28,
            K::AscFlags { found: EndOfLine },
        ),
        (
            "1.0 CANFD 1 Rx 1 0 0 1 1 00 0 0 xyz",
            33,
            K::AscFlags { found: Byte(b'x') },
        ),
        // A CAN FD frame whose length is not its DLC's.
        (
            "1.0 CANFD 1 Rx 1 0 0 9 8 00 01 02 03 04 05 06 07 0 0 1000",
            24,
            K::AscDataLength { found: Byte(b'8') },
        ),
        ("1.0 CANXL 1 Rx", 5, K::AscLine { found: Byte(b'C') }),
        ("1.0 CAN 1 Hello", 11, K::AscLine { found: Byte(b'H') }),
    ];
    for (line, column, reason) in rows {
        assert_eq!(err(line), (*column, *reason), "{line:?}");
        let message = FormatError::Syntax {
            format: LogFormat::Asc,
            column: *column,
            reason: *reason,
        }
        .to_string();
        assert!(message.starts_with("asc line, column"), "{message}");
        assert!(message.contains("expected"), "{message}");
    }
}

#[test]
fn the_writer_writes_what_python_can_writes() {
    let frame = CanFrame::new(CanId::standard(0x81).unwrap(), &[0x30, 0x81]).unwrap();
    let logged = LogFrame::new(frame)
        .with_timestamp(Timestamp::new(0, 1000).unwrap())
        .with_iface(Iface::Channel(1));
    let mut text = String::new();
    write_line(&logged, &mut text).unwrap();
    assert_eq!(text, "        0.001000 1  81              Rx   d 2 30 81");
}

/// docs/formats.md#asc: a classic line's DLC code and the bytes present
/// decide; what cannot be read is reported, nothing dropped silently.
#[test]
fn classic_data_as_its_dlc_code_and_bytes_say() {
    use Found::{Byte, EndOfLine};
    let read = |line: &str| {
        let mut parser = AscParser::new();
        parse(&mut parser, line)
    };
    let frame = |line: &str| match read(line) {
        Ok(Some(LogEvent::Frame(frame))) => frame.frame,
        other => panic!("{line}: {other:?}"),
    };
    let twelve = "1.0 1 2A1 Rx d 9 01 02 03 04 05 06 07 08 09 0A 0B 0C";
    assert!(frame(twelve).is_fd());
    assert_eq!(frame(twelve).data().len(), 12);
    assert_eq!(frame("1.0 1 2A1 Rx d F 00 01 02 03 04 05 06 07 08 09 0A 0B 0C 0D 0E 0F 10 11 12 13 14 15 16 17 18 19 1A 1B 1C 1D 1E 1F 20 21 22 23 24 25 26 27 28 29 2A 2B 2C 2D 2E 2F 30 31 32 33 34 35 36 37 38 39 3A 3B 3C 3D 3E 3F").data().len(), 64);
    // A code above 8 with 8 bytes: a classic frame of 8.
    let eight = frame("1.0 1 2A1 Rx d 9 01 02 03 04 05 06 07 08");
    assert!(!eight.is_fd());
    assert_eq!(eight.data().len(), 8);
    // CANoe's statistics after the data are read past.
    assert_eq!(
        frame("1.0 1 181 Rx d 2 01 02  Length = 228000 BitCount = 117 ID = 385").data(),
        [1, 2]
    );
    let error = |line: &str| match read(line) {
        Err(FormatError::Syntax { column, reason, .. }) => (column, reason),
        other => panic!("{line}: {other:?}"),
    };
    // 10 bytes after code 9: neither 8 nor 12.
    assert_eq!(
        error("1.0 1 2A1 Rx d 9 01 02 03 04 05 06 07 08 09 0A"),
        (47, K::AscDataByte { found: EndOfLine })
    );
    // 13 bytes after code 9: one too many.
    assert_eq!(
        error("1.0 1 2A1 Rx d 9 01 02 03 04 05 06 07 08 09 0A 0B 0C 0D"),
        (54, K::AscTrailing { found: Byte(b'0') })
    );
    // Stray tokens after a classic frame's data.
    assert_eq!(
        error("1.0 1 181 Rx d 2 01 02 03"),
        (24, K::AscTrailing { found: Byte(b'0') })
    );
    assert_eq!(
        error("1.0 1 181 Rx d 2 01 02 foo"),
        (24, K::AscTrailing { found: Byte(b'f') })
    );
    assert_eq!(
        error("1.0 1 181 Rx d 2 01 02 Length ="),
        (24, K::AscTrailing { found: Byte(b'L') })
    );
    // CANoe 15's trigger events are no frames and no errors.
    for line in [
        "   0.000000 TriggerEvent: TriggerBlock[Logging] Start DirectLogging",
        "   9.500000 TriggerEvent: TriggerBlock[Logging] Stop DirectLogging",
    ] {
        assert!(matches!(read(line), Ok(None)), "{line}");
    }
}
