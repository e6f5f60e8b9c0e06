use crate::can::LogFrame;
use crate::test_gens::candump::FrameExt;
use proptest::prelude::*;

use super::fast::decode_fd_data;
use super::*;
use crate::can::FD_MAX_LEN;
use crate::logs::Position;
use crate::test_gens::candump::{frame_spec, mutated_line, screen_frame_spec};

fn write_log(frame: &LogFrame<'_>) -> String {
    let mut s = String::new();
    frame.write_log(&mut s).unwrap();
    s
}

fn write_screen(frame: &LogFrame<'_>) -> String {
    let mut s = String::new();
    frame.write_screen(&mut s).unwrap();
    s
}

proptest! {
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        let one = parse_line(&bytes);
        prop_assert_eq!(one, general(&bytes));
        let by_next: Vec<_> = lines(&bytes).by_ref().collect();
        let mut by_fold = Vec::new();
        lines(&bytes).for_each(|item| by_fold.push(item));
        prop_assert_eq!(by_next, by_fold);
    }

    #[test]
    fn near_valid_lines_never_panic_and_both_paths_agree(line in mutated_line()) {
        let result = parse_line(&line);
        prop_assert_eq!(result, general(&line));
        if let Ok(Some(frame)) = result {
            // Whatever parses writes back to something that parses to it.
            let text = write_log(&frame);
            prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
        }
        for item in lines(&line) {
            let _ = item;
        }
    }

    #[test]
    fn log_format_round_trips(spec in frame_spec()) {
        let frame = spec.frame();
        let text = write_log(&frame);
        prop_assert_eq!(frame.to_string(), text.clone());
        prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
        prop_assert_eq!(general(text.as_bytes()), Ok(Some(frame)));
        for end in ["\n", "\r\n"] {
            let line = format!("{text}{end}");
            prop_assert_eq!(parse_line_str(&line), Ok(Some(frame)));
            let buf = format!("{line}{line}");
            let items: Vec<_> = lines(buf.as_bytes()).collect();
            prop_assert_eq!(items, vec![(Position::Line(1), Ok(Some(frame))), (Position::Line(2), Ok(Some(frame)))]);
        }
    }

    #[test]
    fn log_format_without_direction_round_trips(spec in frame_spec()) {
        let mut spec = spec;
        spec.direction = None;
        let frame = spec.frame();
        let text = write_log(&frame);
        prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
    }

    #[test]
    fn screen_format_round_trips(spec in screen_frame_spec()) {
        let frame = spec.frame();
        let text = write_screen(&frame);
        prop_assert_eq!(parse_line_str(&text), Ok(Some(frame)));
        let line = format!("{text}\r\n");
        prop_assert_eq!(parse_line_str(&line), Ok(Some(frame)));
    }
}

/// A line for a whole log: a valid log line on one of a few interfaces (of
/// 1 to 8 bytes and more, some the start of another, so that every way the
/// lines remember a name is taken), the same with the byte after the name
/// replaced or another byte put before it, a screen line, or a mutated
/// line; without a line end inside.
fn log_line() -> impl Strategy<Value = Vec<u8>> {
    let names = vec![
        "can0",
        "can1",
        "can01",
        "can",
        "c",
        "vcan123",
        "vcan1234",
        "vcan12345",
        "a_long_name_0",
    ];
    let name = proptest::sample::select(names);
    let after_name = prop_oneof![
        proptest::sample::select(b" \t#(0aX\x00\x7f\xff".to_vec()),
        any::<u8>(),
    ];
    let on = |(mut spec, name): (crate::test_gens::candump::FrameSpec, &str)| {
        spec.iface = name.to_string();
        write_log(&spec.frame()).into_bytes()
    };
    prop_oneof![
        3 => (frame_spec(), name.clone()).prop_map(on),
        1 => (frame_spec(), name, after_name, any::<bool>()).prop_map(
            move |(spec, name, byte, insert)| {
                let mut line = on((spec, name));
                // The name starts after the timestamp's `) `, if any.
                let start = line
                    .windows(2)
                    .position(|w| w == b") ")
                    .map_or(0, |at| at + 2);
                let at = start + name.len();
                if insert {
                    line.insert(at, byte);
                } else {
                    line[at] = byte;
                }
                line.into_iter().map(|b| if b == b'\n' { b' ' } else { b }).collect()
            }
        ),
        1 => screen_frame_spec().prop_map(|spec| write_screen(&spec.frame()).into_bytes()),
        1 => mutated_line().prop_map(|line| {
            line.into_iter().map(|b| if b == b'\n' { b' ' } else { b }).collect()
        }),
    ]
}

proptest! {
    /// `lines` reads each line of a log as `parse_line` reads it alone, by
    /// `next` and by `for_each`, whatever the interfaces of the lines before it
    /// (the names it remembers), with `\n` or `\r\n` line ends; an
    /// explanation line after an error frame holds nothing.
    #[test]
    fn lines_read_each_line_as_parse_line_does(
        log in proptest::collection::vec((log_line(), any::<bool>()), 1..40),
    ) {
        let mut buf = Vec::new();
        for (line, crlf) in &log {
            buf.extend_from_slice(line);
            buf.extend_from_slice(if *crlf { b"\r\n" } else { b"\n" });
        }
        let items: Vec<_> = lines(&buf).collect();
        prop_assert_eq!(items.len(), log.len());
        // `for_each` (`fold`) reads the same items.
        let mut by_fold = Vec::new();
        lines(&buf).for_each(|item| by_fold.push(item));
        prop_assert_eq!(&by_fold, &items);
        let mut after_error_frame = false;
        for ((n, item), (number, (line, _))) in items.into_iter().zip((1..).zip(&log)) {
            prop_assert_eq!(n, Position::Line(number));
            let alone = parse_line(line);
            let expected = match alone {
                Err(_) if after_error_frame && lines::is_explanation(line) => Ok(None),
                other => other,
            };
            prop_assert_eq!(item, expected);
            after_error_frame = matches!(expected, Ok(Some(f)) if f.frame.is_error());
        }
    }
}

#[cfg(feature = "std")]
proptest! {
    /// The reader reads a log as `lines` does: each frame at its line, each
    /// malformed line reported at its line, nothing for the rest, whatever
    /// the frames before it left in the reader (the data bytes it keeps, the
    /// interface names), in blocks of any size the input hands out.
    #[test]
    fn the_reader_reads_as_lines_does(
        log in proptest::collection::vec(log_line(), 1..40),
        chunk in 1usize..200,
    ) {
        use crate::logs::ReadLog;

        /// An input that hands out at most `chunk` bytes a read.
        struct Chunks<'a>(&'a [u8], usize);
        impl std::io::Read for Chunks<'_> {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let n = self.0.len().min(self.1).min(buf.len());
                buf[..n].copy_from_slice(&self.0[..n]);
                self.0 = &self.0[n..];
                Ok(n)
            }
        }

        let mut buf = Vec::new();
        for line in &log {
            buf.extend_from_slice(line);
            buf.push(b'\n');
        }
        let mut expected = Vec::new();
        for (n, item) in lines(&buf) {
            let position = Some(n);
            match item {
                Ok(Some(frame)) => expected.push((position, Some(frame.to_string()))),
                Ok(None) => {}
                Err(_) => expected.push((position, None)),
            }
        }
        let mut reader = CandumpReader::with_relative_timestamps(
            Chunks(&buf, chunk),
            RelativeTimestamps::Zero,
        );
        let mut read = Vec::new();
        while let Some(next) = reader.next_event() {
            read.push(match next {
                Ok(record) => (
                    Some(record.position),
                    record.event.frame().map(|frame| frame.to_string()),
                ),
                Err(error) => (error.position(), None),
            });
        }
        prop_assert_eq!(read, expected);
    }
}

proptest! {
    /// The CAN FD data decoder against a byte-by-byte model: the leading hex
    /// digits (at most 128 read), an odd count refused, then the bytes;
    /// whatever follows the digits (a line end, a space, another byte, the
    /// end of the buffer), at every length, in either case.
    #[test]
    fn fd_data_is_its_digits_byte_by_byte(
        bytes in proptest::collection::vec(any::<u8>(), 0..=66),
        lower in any::<bool>(),
        extra_digit in any::<bool>(),
        tail in proptest::collection::vec(
            prop_oneof![
                proptest::sample::select(b"\n\r RT#0aFgG\x00\xff".to_vec()),
                any::<u8>(),
            ],
            0..3,
        ),
        prefix in 0usize..4,
    ) {
        let mut buf = vec![b'x'; prefix];
        for b in &bytes {
            let text = if lower { format!("{b:02x}") } else { format!("{b:02X}") };
            buf.extend_from_slice(text.as_bytes());
        }
        if extra_digit {
            buf.push(b'7');
        }
        buf.extend_from_slice(&tail);
        let mut data = [0u8; FD_MAX_LEN];
        let got = decode_fd_data(&buf, prefix, &mut data).map(|(len, end)| (len, end, data));
        prop_assert_eq!(got, fd_data_digit_by_digit(&buf, prefix));
    }

    /// The same with any bytes after the digits, mostly more than the
    /// 32 that the decoder loads at once, so that the data ends inside
    /// a load as often as near the end of the buffer; the digits in any
    /// case, digit by digit.
    #[test]
    fn fd_data_is_its_digits_byte_by_byte_before_any_bytes(
        digits in proptest::collection::vec(
            proptest::sample::select(b"0123456789abcdefABCDEF".to_vec()),
            0..=140,
        ),
        tail in proptest::collection::vec(
            prop_oneof![
                4 => proptest::sample::select(b"0123456789aFgG\n\r #\x00\x80\xc6\xff".to_vec()),
                1 => any::<u8>(),
            ],
            0..48,
        ),
        prefix in 0usize..4,
    ) {
        let mut buf = vec![b'x'; prefix];
        buf.extend_from_slice(&digits);
        buf.extend_from_slice(&tail);
        let mut data = [0u8; FD_MAX_LEN];
        let got = decode_fd_data(&buf, prefix, &mut data).map(|(len, end)| (len, end, data));
        prop_assert_eq!(got, fd_data_digit_by_digit(&buf, prefix));
    }
}

/// What [`decode_fd_data`] returns for `buf` from `start`, digit by digit:
/// the bytes of the hex digits there (up to 128), `None` for an odd count.
fn fd_data_digit_by_digit(buf: &[u8], start: usize) -> Option<(u8, usize, [u8; FD_MAX_LEN])> {
    let digits = buf[start..]
        .iter()
        .take_while(|b| b.is_ascii_hexdigit())
        .count()
        .min(128);
    if digits % 2 == 1 {
        return None;
    }
    let mut data = [0u8; FD_MAX_LEN];
    for (i, pair) in buf[start..start + digits].chunks(2).enumerate() {
        let text = core::str::from_utf8(pair).unwrap();
        data[i] = u8::from_str_radix(text, 16).unwrap();
    }
    Some(((digits / 2) as u8, start + digits, data))
}
