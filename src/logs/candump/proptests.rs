use crate::can::LogFrame;
use crate::test_gens::candump::FrameExt;
use proptest::prelude::*;

use super::*;
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
            prop_assert_eq!(items, vec![(1, Ok(Some(frame))), (2, Ok(Some(frame)))]);
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
