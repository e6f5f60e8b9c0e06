use super::*;
use crate::test_gens::can::any_can_frame as any_frame;
use proptest::prelude::*;

proptest! {
    /// Any bytes, any state: no panic, and an error's column lies in the
    /// line (or one past its end).
    #[test]
    fn any_bytes(lines in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..120), 0..8)) {
        let mut parser = AscParser::new();
        for line in &lines {
            match parser.parse_line(line) {
                Err(Error::Syntax { format: LogFormat::Asc, column, .. }) => {
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
