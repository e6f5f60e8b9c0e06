//! The servo ↔ NC interface end to end through real frame bytes
//! (docs/servo.md): the NC side uses the crate's handshakes, the drive side is
//! scripted feedback, and every command the NC sends is checked byte for byte.

use motionwire::servo::{
    drive_enabled, servo_ready, ActualPosition, Command, CommandFrame, ECode, ErrorClearHandshake,
    Feedback, FeedbackFrame, HandshakePhase, Message, MessageCode, ServoControlWord, ServoEnable,
    ServoErrorWord, ServoFault, ServoReadyMode, ServoStatusWord, ZeroPulseHandshake, COMMAND_LEN,
    FEEDBACK_LEN,
};
use motionwire::LenError;
use motionwire::What;

/// A feedback frame with the given status and error words, an incremental
/// position and a zero-pulse position.
fn feedback_bytes(ssw: u32, sew: u32, position: i32, zero: i32) -> [u8; FEEDBACK_LEN] {
    let mut bytes = [0u8; FEEDBACK_LEN];
    bytes[0..4].copy_from_slice(&position.to_le_bytes());
    bytes[4..8].copy_from_slice(&zero.to_le_bytes());
    bytes[8..12].copy_from_slice(&ssw.to_le_bytes());
    bytes[12..16].copy_from_slice(&sew.to_le_bytes());
    bytes
}

/// The command frame the NC writes: SSP, SCW, extra data code 0.
fn command_bytes(ssp: i32, scw: u32) -> [u8; COMMAND_LEN] {
    let mut bytes = [0u8; COMMAND_LEN];
    bytes[0..4].copy_from_slice(&ssp.to_le_bytes());
    bytes[4..8].copy_from_slice(&scw.to_le_bytes());
    bytes
}

/// docs/servo.md#handshakes: the NC clears a following error (E09). The drive
/// reports it, the NC raises ErrorClear, the drive clears and acks, the NC
/// drops the request, the drive drops the ack.
#[test]
fn error_clear_through_frames() {
    // SSW: ServoRDY=0 while the error is up (mode 0), AbsIncr=1.
    // SEW: 0x0008_0001 = ServoErrors + FollowerErr.
    let drive = [
        feedback_bytes(0x0004, 0x0008_0001, 0, 0), // error present
        feedback_bytes(0x0004, 0x0008_0001, 0, 0), // request not seen yet
        feedback_bytes(0x0016, 0x0000_0000, 0, 0), // cleared: ErrClearAck + ServoRDY
        feedback_bytes(0x0016, 0x0000_0000, 0, 0), // ack still up
        feedback_bytes(0x0006, 0x0000_0000, 0, 0), // ack dropped
    ];
    // NC output per cycle: SCW 0x0604 = NORMAL + ErrorClear, 0x0404 = NORMAL.
    let expected = [
        (HandshakePhase::Requested, command_bytes(0, 0x0604)),
        (HandshakePhase::Requested, command_bytes(0, 0x0604)),
        (HandshakePhase::Acknowledged, command_bytes(0, 0x0404)),
        (HandshakePhase::Releasing, command_bytes(0, 0x0404)),
        (HandshakePhase::Done, command_bytes(0, 0x0404)),
    ];

    let mut clear = ErrorClearHandshake::new();
    let mut last = Command::new(0, ServoControlWord::NORMAL, 0);
    for (cycle, (bytes, (phase, out))) in drive.iter().zip(expected).enumerate() {
        let feedback = Feedback::parse(bytes).unwrap();
        if cycle == 0 {
            let faults: Vec<_> = feedback.errors.faults().collect();
            assert_eq!(faults, [ServoFault::ServoErrors, ServoFault::FollowerErr]);
            assert_eq!(faults[1].e_code(), Some(ECode::E09));
            clear = clear.start();
        }
        let (next, scw) = clear.step(last.control, feedback.status);
        clear = next;
        last.control = scw;
        assert_eq!(clear.phase(), phase, "cycle {cycle}");
        assert_eq!(last.to_bytes(), out, "cycle {cycle}");
    }
}

/// docs/servo.md#handshakes: zero-pulse search on an incremental encoder; the
/// zero-pulse position is read in POSW2..3 in the cycle of the ack.
#[test]
fn zero_pulse_through_frames() {
    // SSW 0x0007: ServoEn, ServoRDY, AbsIncr; +0x08 ZPulseAck.
    let drive = [
        feedback_bytes(0x0007, 0, 1_000, 0),
        feedback_bytes(0x0007, 0, 1_500, 0),
        feedback_bytes(0x000F, 0, 2_000, 1_800), // found at 1800
        feedback_bytes(0x000F, 0, 2_500, 1_800),
        feedback_bytes(0x0007, 0, 3_000, 1_800),
        feedback_bytes(0x0007, 0, 3_500, 3_400), // a later zero pulse updates POSW2..3
    ];
    // SCW: NORMAL + SE 0b10 = 0x0406; + ZPulseRequest = 0x0C06.
    let expected = [
        (HandshakePhase::Requested, 0x0C06),
        (HandshakePhase::Requested, 0x0C06),
        (HandshakePhase::Acknowledged, 0x0406),
        (HandshakePhase::Releasing, 0x0406),
        (HandshakePhase::Done, 0x0406),
        (HandshakePhase::Done, 0x0406),
    ];
    let mut zero = ZeroPulseHandshake::new().start();
    let mut scw = ServoControlWord::NORMAL.with_servo_enable(ServoEnable::ENABLE);
    let mut latched = None;
    let mut zero_pulses = Vec::new();
    for (cycle, (bytes, (phase, out))) in drive.iter().zip(expected).enumerate() {
        let frame = FeedbackFrame::new_checked(&bytes[..]).unwrap();
        (zero, scw) = zero.step(scw, frame.status_word());
        assert_eq!(zero.phase(), phase, "cycle {cycle}");
        assert_eq!(
            Command::new(250, scw, 0).to_bytes(),
            command_bytes(250, out),
            "cycle {cycle}"
        );
        if zero.phase() == HandshakePhase::Acknowledged {
            latched = Some(frame.zero_pulse_position());
        }
        if let ActualPosition::Incremental {
            zero_pulse_position,
            ..
        } = frame.actual_position()
        {
            zero_pulses.push(zero_pulse_position);
        }
    }
    assert_eq!(latched, Some(1_800));
    assert_eq!(zero_pulses, [0, 0, 1_800, 1_800, 1_800, 3_400]);
}

/// docs/servo.md#handshakes: a drive that reacts to the NC's SE field with
/// `drive_enabled` and reports ServoRDY by the truth table, driven by the
/// NC's command bytes; the feedback's first status byte is checked.
#[test]
fn enable_through_frames() {
    // (SE written by the NC, SSW low byte with mode 0, with mode 1)
    let script = [
        (ServoEnable::DISABLED, 0x02u8, 0x00u8),
        (ServoEnable::ENABLE, 0x02, 0x00), // 00 → 10: no edge
        (ServoEnable::ARM, 0x02, 0x00),
        (ServoEnable::ENABLE, 0x03, 0x03), // 01 → 10: enabled and ready
        (ServoEnable::ENABLE, 0x03, 0x03),
        (ServoEnable::BOTH, 0x02, 0x00), // disabled
    ];
    for (mode, column) in [
        (ServoReadyMode::ErrorFree, 1),
        (ServoReadyMode::EnabledAndErrorFree, 2),
    ] {
        let mut previous = ServoEnable::DISABLED;
        let mut enabled = false;
        for (cycle, &(se, mode0, mode1)) in script.iter().enumerate() {
            let image =
                Command::new(0, ServoControlWord::NORMAL.with_servo_enable(se), 0).to_bytes();
            // The drive's side.
            let received = CommandFrame::new_checked(&image[..])
                .unwrap()
                .control_word();
            enabled = drive_enabled(previous, received.servo_enable(), enabled);
            previous = received.servo_enable();
            let status = ServoStatusWord::empty().with_flag(ServoStatusWord::SERVO_EN, enabled);
            let ready = servo_ready(mode, status, ServoErrorWord::empty());
            let status = status.with_flag(ServoStatusWord::SERVO_RDY, ready);
            let feedback = Feedback {
                position: 0,
                status,
                errors: ServoErrorWord::empty(),
                message: Message::new(MessageCode::MotorSpeed, 0.0),
                extra_data: [0.0; 4],
            };
            let expected = if column == 1 { mode0 } else { mode1 };
            assert_eq!(feedback.to_bytes()[8], expected, "{mode:?}, cycle {cycle}");
        }
    }
}

/// docs/servo.md#command, docs/servo.md#feedback: every buffer shorter than a
/// frame is the exact length error, for both frames, views and owned values.
#[test]
fn every_short_buffer_is_an_exact_error() {
    let long = [0x5Au8; 64];
    for len in 0..=64 {
        let data = &long[..len];
        match Command::parse(data) {
            Ok(command) => {
                assert!(len >= COMMAND_LEN);
                assert_eq!(command.to_bytes()[..], data[..COMMAND_LEN]);
            }
            Err(e) => assert_eq!(
                e,
                LenError {
                    what: What::ServoCommandFrame,
                    expected: COMMAND_LEN,
                    found: len
                }
            ),
        }
        match FeedbackFrame::new_checked(data) {
            Ok(frame) => {
                assert!(len >= FEEDBACK_LEN);
                assert_eq!(
                    Feedback::parse_frame(&frame).to_bytes()[..],
                    data[..FEEDBACK_LEN]
                );
            }
            Err(e) => assert_eq!(
                e,
                LenError {
                    what: What::ServoFeedbackFrame,
                    expected: FEEDBACK_LEN,
                    found: len
                }
            ),
        }
    }
}

/// docs/servo.md#cli-feedback: the names a decoder prints for a feedback frame.
#[test]
fn names_for_the_command_line_decoder() {
    let mut bytes = feedback_bytes(0x1F7F, 0xFFFF_FFFF, -1, -2);
    bytes[16..20].copy_from_slice(&7i32.to_le_bytes());
    let feedback = Feedback::parse(&bytes).unwrap();
    assert_eq!(
        feedback.status.flag_names().collect::<Vec<_>>(),
        [
            "ServoEn",
            "ServoRDY",
            "AbsIncr",
            "ZPulseAck",
            "ErrClearAck",
            "N0",
            "NNs",
            "NoEncoder",
            "TempWarning",
            "ExtPRMTBL"
        ]
    );
    assert_eq!(feedback.status.parameter_table().get(), 8);
    assert_eq!(feedback.status.encoder().name(), "incremental");
    assert_eq!(feedback.errors.faults().count(), 24);
    let e_codes: Vec<String> = feedback
        .errors
        .faults()
        .filter_map(|f| f.e_code())
        .map(|c| c.to_string())
        .collect();
    assert_eq!(
        e_codes,
        [
            "E01", "E19", "E14", "E05", "E06", "E07", "E08", "E15", "E16", "E30", "E09", "E20",
            "E32", "E31", "E11", "E12"
        ]
    );
    assert_eq!(feedback.message.kind().name(), "reserved");
    assert_eq!(feedback.message.kind().unit(), None);
}
