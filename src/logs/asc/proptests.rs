use super::*;
use crate::can::{CanFrame, ErrorClasses};
use crate::logs::lex::trim_end;
use crate::logs::{FormatError, LogFormat};
use crate::test_gens::can::any_can_frame as any_frame;
use proptest::prelude::*;

/// A parser in any state a header can set, partway through a file.
fn any_parser() -> impl Strategy<Value = AscParser> {
    (
        any::<bool>(),
        any::<bool>(),
        0u64..1_000_000,
        0u32..1_000_000_000,
    )
        .prop_map(|(hex, relative, secs, nanos)| AscParser {
            hex,
            relative,
            elapsed: Timestamp::from_nanos(secs, nanos).unwrap_or(Timestamp::ZERO),
        })
}

/// Mostly `right`, sometimes `wrong` (regular expressions).
fn field(right: &'static str, wrong: &'static str) -> BoxedStrategy<String> {
    prop_oneof![19 => right, 1 => wrong].boxed()
}

/// White space between words: what the writers put, sometimes tabs or
/// none.
fn gap() -> BoxedStrategy<String> {
    field("[ ]{1,3}|[ ]{4,20}", "[ \\t]{1,3}|")
}

/// `n` data bytes (sometimes a few more or fewer), each after white
/// space, each sometimes not a byte.
fn data_bytes(n: usize) -> impl Strategy<Value = String> {
    let count = prop_oneof![9 => Just(n), 1 => 0..n + 3];
    count.prop_flat_map(|count| {
        proptest::collection::vec(
            (
                gap(),
                prop_oneof![
                    60 => "[0-9A-F]{2}|[0-9a-f]{1,2}",
                    1 => "[0-9A-F]{3}|G|\\r|"
                ],
            ),
            count,
        )
        .prop_map(|bytes| bytes.into_iter().map(|(g, b)| g + &b).collect::<String>())
    })
}

/// Lines shaped like the fast path's (a classic data frame, a `CANFD`
/// frame), each field mostly right and sometimes just wrong.
fn asc_like_line() -> impl Strategy<Value = String> {
    let head = (
        field(
            "[ ]{0,4}[0-9]{1,6}\\.[0-9]{6}",
            "[ \\t]{0,4}([0-9]{1,20}\\.[0-9]{0,11}|[0-9.]{1,5}|\\.5)",
        ),
        gap(),
        field("[1-9]|[0-9]{1,5}", "[0-9]{6}|0|CAN|x"),
        gap(),
        field(
            "[0-7][0-9A-F]{2}|[0-9A-Fa-f]{1,8}[xX]",
            "[0-9A-Fa-f]{9}x?|[0-9A-F]{0,3}[gxX ]|ErrorFrame",
        ),
        gap(),
        field("Rx|Tx", "TxRq|rx|R"),
    );
    let tail = field(
        "",
        "[ ]+Length = [0-9]+ BitCount = [0-9]+|\\r|[ \\t\\r]{1,3}|\\rx",
    );
    let classic = (
        head.clone(),
        gap(),
        field("d", "D|r|R|dd|x"),
        gap(),
        0usize..16,
        tail.clone(),
    )
        .prop_flat_map(|(head, g4, kind, g5, dlc, tail)| {
            let digit = field(
                [
                    "0", "1", "2", "3", "4", "5", "6", "7", "8", "9", "A", "B", "C", "D", "E", "F",
                ][dlc],
                "[0-9a-f]|[0-9]{2}|G|",
            );
            (
                Just((head, g4, kind, g5, tail)),
                digit,
                data_bytes(dlc.min(8)),
            )
        })
        .prop_map(|(((t, g1, c, g2, i, g3, d), g4, k, g5, tail), dlc, data)| {
            format!("{t}{g1}{c}{g2}{i}{g3}{d}{g4}{k}{g5}{dlc}{data}{tail}")
        });
    let fd = (
        head,
        field("[ ]{0,40}", "[ ]+[A-Za-z_]{1,8}"),
        field("[01] [01]", "[01]{2} [01]|2 0|1 x"),
        gap(),
        0usize..16,
        tail,
    )
        .prop_flat_map(|((t, g1, c, g2, i, g3, d), name, bits, g4, dlc, tail)| {
            let len = FD_LENGTHS[dlc];
            let len_text = field(
                [
                    "0", "1", "2", "3", "4", "5", "6", "7", "8", "12", "16", "20", "24", "32",
                    "48", "64",
                ][dlc],
                "[0-9]{1,3}|x",
            );
            let flags = field("1000|3000|5000|7000|0|10", "[0-9A-Fa-f]{1,9}|x");
            let rest = (
                Just(format!(
                    "{t}{g1}CANFD{g2}{c}{g3}{d}{g4}{i}{name} {bits} {dlc:x}"
                )),
                field("[ ]{1,2}", ""),
                len_text,
                data_bytes(usize::from(len)),
                flags,
                Just(tail),
            );
            rest
        })
        .prop_map(|(head, g, len, data, flags, tail)| {
            format!("{head}{g}{len}{data}        0    0 {flags:>8}        0        0{tail}")
        });
    prop_oneof![classic, fd]
}

/// `n` data bytes as the writers write them, ` HH` (sometimes a few more
/// or fewer), each group mostly right and sometimes just wrong.
fn writers_data(n: usize) -> impl Strategy<Value = String> {
    let count = prop_oneof![9 => Just(n), 1 => 0..n + 3];
    count.prop_flat_map(|count| {
        proptest::collection::vec(
            (
                field(" ", "  |\\t|"),
                field(
                    "[0-9A-F]{2}",
                    "[0-9a-f]{1,2}|[0-9A-F]{3}|G[0-9]|\\r[0-9]|[0-9]\\n",
                ),
            ),
            count,
        )
        .prop_map(|bytes| bytes.into_iter().map(|(g, b)| g + &b).collect::<String>())
    })
}

/// Classic lines in the writers' columns (python-can, CANoe: `   0.012345
/// 1  123             Rx   d 8 11 22 …`, the identifier padded to 15
/// columns), each field and each run of padding mostly right and
/// sometimes just wrong: the shape the fast path reads from fixed
/// columns.
fn columns_line() -> impl Strategy<Value = String> {
    let id = field(
        "[0-7][0-9A-F]{2}|[0-9A-Fa-f]{1,8}[xX]",
        "[0-9A-Fa-f]{9,15}x?|[0-9A-F]{0,3}[gxX]|[0-9A-F]{16,17}",
    );
    let head = (
        field(
            "[ ]{1,4}[0-9]{1,6}\\.[0-9]{6}",
            "[ ]{0,4}[0-9]{1,3}\\.[0-9]{0,10}",
        ),
        field("[1-9]|1[0-6]", "0|[0-9]{6}"),
        id,
        // The padding to 15 columns, or one space more or less, or a tab.
        prop_oneof![16 => Just(0i8), 1 => Just(-1i8), 1 => Just(1i8), 1 => Just(2i8)],
        field("Rx|Tx", "TxRq|rx|R |RX|Rt"),
        field("   ", "  |    |\\t  | \\t "),
        field("d|D", "r|R|x|dd"),
        field(" ", "  |\\t|"),
        field("[0-8]", "[9A-Fa-f]|G|10|\\r"),
    );
    let tail = field(
        "",
        "[ ]+Length = [0-9]+ BitCount = [0-9]+|\\r|[ \\t\\r]{1,3}|\\rx|x",
    );
    (head, 0usize..=8, tail)
        .prop_flat_map(|(head, n, tail)| (Just(head), writers_data(n), Just(tail)))
        .prop_map(
            |((time, channel, id, pad, dir, gap, kind, g, dlc), data, tail)| {
                let width = (15 + i32::from(pad)).max(0) as usize;
                let padded = if pad == 2 {
                    format!("{id}\t")
                } else {
                    format!("{id:<width$}")
                };
                format!("{time} {channel}  {padded} {dir}{gap}{kind}{g}{dlc}{data}{tail}")
            },
        )
}

/// `CANFD` lines in the columns python-can writes (`   0.012345 CANFD   2
/// Rx        181` and 35 spaces, `1 0 d 32`, the data ` HH` …, then
/// `        0    0     3000`), each
/// field and each run of padding mostly right and sometimes just wrong:
/// the shape the fast path reads from fixed columns.
fn fd_columns_line() -> impl Strategy<Value = String> {
    let head = (
        field(
            "[ ]{0,2}[0-9]{1,3}\\.[0-9]{6}",
            "[ ]{0,4}[0-9]{1,3}\\.[0-9]{0,10}",
        ),
        field("[1-9]", "[0-9]{2,4}|0|x| "),
        field("Rx|Tx", "TxRq|rx|R|RX|R\\t"),
        field(
            "[0-7][0-9A-F]{2}|[0-9A-Fa-f]{1,7}[xX]|[0-9A-F]{1,8}",
            "[0-9A-Fa-f]{9}x?|[0-9A-F]{0,3}[gxX ]|[0-9A-F] [0-9A-F]|[0-9A-F]\\t|",
        ),
        field("", "[A-Za-z_]{1,8}|\\t|[ ]{1,33}"),
        field("  ", " |   |\\t |"),
        field("[01]", "2|x||[01]{2}"),
        field(" ", "  |\\t|"),
        field("[01]", "2|x||\\r"),
    );
    let tail = field(
        "",
        "[ ]+Length = [0-9]+ BitCount = [0-9]+|\\r|[ \\t\\r]{1,3}|\\rx|x",
    );
    (head, 0usize..16, tail)
        .prop_flat_map(|(head, dlc, tail)| {
            let len = FD_LENGTHS[dlc];
            let dlc_text = field(
                [
                    "0", "1", "2", "3", "4", "5", "6", "7", "8", "9", "a", "b", "c", "d", "e", "f",
                ][dlc],
                "[0-9A-F]|G|10|\\r",
            );
            let len_text = field(
                [
                    "0", "1", "2", "3", "4", "5", "6", "7", "8", "12", "16", "20", "24", "32",
                    "48", "64",
                ][dlc],
                "[0-9]{1,3}|x|",
            );
            let flags = field("1000|3000|5000|7000|0|10", "[0-9A-Fa-f]{1,9}|x");
            let duration = field("[0-9]{1,8}", "|[0-9] [0-9]|[0-9]{9}|x\\t|\\r");
            let bits = field("[0-9]{1,4}", "|[0-9]{5}|\\t|[0-9] ");
            (
                Just((head, tail)),
                (
                    field(" ", "  |\\t|"),
                    dlc_text,
                    field(" ", "  |\\t|"),
                    len_text,
                ),
                writers_data(usize::from(len)),
                (duration, bits, flags),
            )
        })
        .prop_map(
            |(
                ((time, channel, dir, id, name, gap, brs, g, esi), tail),
                (g2, dlc, g3, len),
                data,
                (duration, bits, flags),
            )| {
                format!(
                    "{time} CANFD {channel:>3} {dir:<4} {id:>8} {name:>32}{gap}{brs}{g}{esi}{g2}{dlc}{g3}{len:>2}{data} {duration:>8} {bits:>4} {flags:>8}        0        0{tail}"
                )
            },
        )
}

/// The fast path, where it reads `line` at all, reads it as the general
/// parser does and leaves the parser as the general parser leaves it;
/// where it declines, it leaves the parser as it was.
fn fast_agrees(parser: &AscParser, line: &[u8]) -> Result<(), TestCaseError> {
    let line = trim_end(line);
    let mut fast = *parser;
    match fast.parse_fast(line) {
        Some(event) => {
            let mut general = *parser;
            prop_assert_eq!(general.parse_general(line), Ok(Some(event)));
            prop_assert_eq!(fast, general);
        }
        None => prop_assert_eq!(&fast, parser),
    }
    Ok(())
}

/// The fast path reading the first line of `text` where it lies (the
/// reader's way) reads it as it reads the line alone, trimmed, and says
/// where the next line begins; where it declines, the parser is as it
/// was. The line alone is held to the general parser by [`fast_agrees`].
fn in_place_agrees(parser: &AscParser, text: &[u8]) -> Result<(), TestCaseError> {
    let mut rest = text;
    let line = take_line(&mut rest).unwrap_or_default();
    let mut alone = *parser;
    let expected = alone.parse_fast(trim_end(line));
    let mut in_place = *parser;
    match in_place.parse_fast_in_place(text) {
        Some((event, len)) => {
            prop_assert_eq!(Some(event), expected);
            prop_assert_eq!(len, text.len() - rest.len());
            prop_assert_eq!(in_place, alone);
        }
        None => {
            prop_assert_eq!(expected, None);
            prop_assert_eq!(&in_place, parser);
        }
    }
    fast_agrees(parser, line)
}

/// What follows a line in a block: nothing (the last line, without its
/// `\n`), or its `\n` and another line, shaped like a frame line or any
/// bytes.
fn after_line() -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        1 => Just(Vec::new()),
        1 => Just(b"\n".to_vec()),
        4 => asc_like_line().prop_map(|next| [b"\n", next.as_bytes()].concat()),
        2 => proptest::collection::vec(any::<u8>(), 0..40).prop_map(|next| [&b"\n"[..], &next].concat()),
    ]
}

proptest! {
    // Each field is wrong in one line of 20: enough cases that most wrong
    // fields come up in a line that is otherwise right.
    #![proptest_config(ProptestConfig::with_cases(4096))]

    /// The fast path agrees with the general parser on lines shaped like
    /// the ones it reads, right and just wrong.
    #[test]
    fn fast_path_agrees_on_asc_like_lines(parser in any_parser(), line in asc_like_line()) {
        fast_agrees(&parser, line.as_bytes())?;
    }

    /// The fast path agrees with the general parser on classic lines in
    /// the writers' columns, right and just wrong, read alone and in
    /// place.
    #[test]
    fn fast_path_agrees_on_lines_in_columns(
        parser in any_parser(),
        line in columns_line(),
        after in after_line(),
    ) {
        fast_agrees(&parser, line.as_bytes())?;
        in_place_agrees(&parser, &[line.as_bytes(), &after].concat())?;
    }

    /// The fast path agrees with the general parser on `CANFD` lines in
    /// python-can's columns, right and just wrong, read alone and in place.
    #[test]
    fn fast_path_agrees_on_fd_lines_in_columns(
        parser in any_parser(),
        line in fd_columns_line(),
        after in after_line(),
    ) {
        fast_agrees(&parser, line.as_bytes())?;
        in_place_agrees(&parser, &[line.as_bytes(), &after].concat())?;
    }

    /// The fast path reads a line in place as it reads it alone, whatever
    /// follows it.
    #[test]
    fn fast_path_in_place_agrees_on_asc_like_lines(
        parser in any_parser(),
        line in asc_like_line(),
        after in after_line(),
    ) {
        in_place_agrees(&parser, &[line.as_bytes(), &after].concat())?;
    }
}

proptest! {
    /// The fast path agrees with the general parser on arbitrary bytes.
    #[test]
    fn fast_path_agrees_on_any_bytes(parser in any_parser(), line in proptest::collection::vec(any::<u8>(), 0..200)) {
        fast_agrees(&parser, &line)?;
    }

    /// The fast path reads arbitrary bytes in place as it reads their
    /// first line alone.
    #[test]
    fn fast_path_in_place_agrees_on_any_bytes(parser in any_parser(), text in proptest::collection::vec(any::<u8>(), 0..200)) {
        in_place_agrees(&parser, &text)?;
    }


    /// Any bytes, any state: no panic, and an error's column lies in the
    /// line (or one past its end).
    #[test]
    fn any_bytes(lines in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..120), 0..8)) {
        let mut parser = AscParser::new();
        for line in &lines {
            match parser.parse_line(line) {
                Err(FormatError::Syntax { format: LogFormat::Asc, column, .. }) => {
                    prop_assert!(column >= 1 && column <= line.len() + 1);
                }
                Err(other) => prop_assert!(false, "{other:?}"),
                Ok(_) => {}
            }
        }
    }

    /// Lines that look like events, with random fields.
    #[test]
    fn near_valid_lines(
        time in "[0-9]{1,4}\\.[0-9]{1,9}",
        channel in "[0-9]{1,3}|CANFD|CAN",
        fields in proptest::collection::vec("[0-9A-Fa-fxXRrTd]{1,4}|Rx|Tx|ErrorFrame|TxRq", 0..12),
        hex_base in any::<bool>(),
        relative in any::<bool>(),
    ) {
        let mut parser = AscParser::new();
        let header = format!(
            "base {} timestamps {}",
            if hex_base { "hex" } else { "dec" },
            if relative { "relative" } else { "absolute" }
        );
        prop_assert_eq!(parser.parse_line(header.as_bytes()), Ok(None));
        let line = format!("   {time} {channel}  {}", fields.join(" "));
        let _ = parser.parse_line(line.as_bytes());
    }

    /// Every frame written the way python-can writes it reads back to
    /// itself (the time to the written resolution; FD frames without FDF,
    /// which a CANFD line's flags give implicitly).
    #[test]
    fn written_frames_read_back(frame in any_frame(), secs in 0u64..100_000, nanos in 0u32..1_000_000_000, channel in 1u16..20, tx in any::<bool>()) {
        // ASC writes a CAN FD frame's DLC: only its lengths are written.
        prop_assume!(!frame.is_fd() || FD_LENGTHS.contains(&(frame.data().len() as u8)));
        let frame = match frame.frame_type() {
            FrameType::Fd(flags) => CanFrame::new_fd(
                frame.id(),
                FdFlags::new(flags.bits() & 0x3).unwrap(),
                frame.data(),
            ).unwrap(),
            _ => frame,
        };
        let mut logged = LogFrame::new(frame)
            .with_timestamp(Timestamp::from_nanos(secs, nanos).unwrap())
            .with_iface(Iface::Channel(channel));
        logged.direction = Some(if tx { Direction::Tx } else { Direction::Rx });
        let mut text = String::new();
        write_line(&logged, &mut text).unwrap();
        let mut parser = AscParser::new();
        // The data and CAN FD frames python-can writes are the fast path's.
        let fast = parser.clone().parse_fast(text.as_bytes());
        prop_assert_eq!(fast.is_some(), matches!(frame.frame_type(), FrameType::Data | FrameType::Fd(_)), "{}", text);
        fast_agrees(&parser, text.as_bytes())?;
        let read = parser.parse_line(text.as_bytes());
        let expected = if frame.is_error() {
            // ASC says only that an error happened.
            LogFrame::new(CanFrame::new_error(ErrorClasses::BUS_ERROR.bits(), &[0; 8]).unwrap())
                .with_timestamp(Timestamp::from_nanos(secs, nanos).unwrap())
                .with_iface(Iface::Channel(channel))
        } else {
            logged
        };
        prop_assert_eq!(read, Ok(Some(LogEvent::Frame(expected))), "{}", text);
    }
}
