//! The 40-byte servo feedback frame, servo → NC (docs/servo.md#feedback,
//! docs/servo.md#ssw, docs/servo.md#sew).
//!
//! Arbitrary bytes → `Feedback::parse`. Invariants:
//! - fewer than 40 bytes is exactly `LenError { expected: 40, found }`;
//!   40 or more always parse;
//! - the zero-copy view and the owned value agree on every field (floats
//!   compared by their bits, so NaN payloads count too), and `to_bytes` /
//!   `emit` give the first 40 bytes back;
//! - both ActualPosition readings round-trip the raw 64-bit value, and the
//!   one chosen follows the Abs/Incr bit;
//! - the message code → kind mapping round-trips and its name, unit and
//!   Display never panic;
//! - the error word's faults are exactly its defined set bits, in bit
//!   order, each E-code maps back to its fault;
//! - the same bytes read as text: `ECode::from_str` never panics and a
//!   parsed code prints as a text that parses to the same code.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::servo::ParseECodeError;
use motionwire::servo::{
    ActualPosition, ECode, EncoderKind, Feedback, FeedbackFrame, MessageCode, ServoErrorWord,
    ServoFault, ServoStatusWord, FEEDBACK_LEN,
};
use motionwire::What;
use motionwire::{LenError, ValueError};

fuzz_target!(|data: &[u8]| {
    check_e_code_text(data);

    let feedback = match Feedback::parse(data) {
        Ok(feedback) => feedback,
        Err(error) => {
            assert_eq!(
                error,
                LenError {
                    what: What::ServoFeedbackFrame,
                    expected: FEEDBACK_LEN,
                    found: data.len(),
                }
            );
            assert!(FeedbackFrame::new_checked(data).is_err());
            return;
        }
    };
    let bytes: [u8; FEEDBACK_LEN] = data[..FEEDBACK_LEN].try_into().unwrap();

    // View and owned value agree on every field; floats by their bits.
    let frame = FeedbackFrame::new_checked(data).expect("parse succeeded");
    assert_eq!(frame.position(), feedback.position);
    assert_eq!(frame.status_word(), feedback.status);
    assert_eq!(frame.error_word(), feedback.errors);
    assert_eq!(frame.message_code(), feedback.message.code);
    assert_eq!(
        frame.message_data().to_bits(),
        feedback.message.data.to_bits()
    );
    assert_eq!(frame.message().code, feedback.message.code);
    assert_eq!(
        frame.message().data.to_bits(),
        feedback.message.data.to_bits()
    );
    let extra_bits = |extra: [f32; 4]| extra.map(f32::to_bits);
    assert_eq!(
        extra_bits(frame.extra_data()),
        extra_bits(feedback.extra_data)
    );
    assert_eq!(frame.actual_position(), feedback.actual_position());
    assert_eq!(Feedback::parse_frame(&frame).to_bytes(), bytes);
    assert_eq!(Feedback::from_bytes(&bytes).to_bytes(), bytes);

    // Encoding gives the bytes back, through the owned value and the view.
    assert_eq!(feedback.to_bytes(), bytes);
    let mut image = [0x5Au8; FEEDBACK_LEN];
    feedback.emit(&mut FeedbackFrame::new_unchecked(&mut image[..]));
    assert_eq!(image, bytes);

    check_position(&bytes, &feedback, &frame);
    check_message(&feedback);
    check_status_word(feedback.status);
    check_error_word(feedback.errors);
});

fn check_position(bytes: &[u8; FEEDBACK_LEN], feedback: &Feedback, frame: &FeedbackFrame<&[u8]>) {
    let raw = i64::from_le_bytes(bytes[..8].try_into().unwrap());
    assert_eq!(feedback.position, raw);
    for encoder in [EncoderKind::Absolute, EncoderKind::Incremental] {
        let position = ActualPosition::from_raw(raw, encoder);
        assert_eq!(position.raw(), raw);
        assert_eq!(position.encoder(), encoder);
    }
    let position = feedback.actual_position();
    assert_eq!(position.encoder(), feedback.status.encoder());
    assert_eq!(
        position.encoder() == EncoderKind::Incremental,
        bytes[8] & (1 << 2) != 0
    );
    match position {
        ActualPosition::Absolute(value) => assert_eq!(value, raw),
        ActualPosition::Incremental {
            position,
            zero_pulse_position,
        } => {
            assert_eq!(position, frame.incremental_position());
            assert_eq!(zero_pulse_position, frame.zero_pulse_position());
            assert_eq!(position.to_le_bytes(), bytes[0..4]);
            assert_eq!(zero_pulse_position.to_le_bytes(), bytes[4..8]);
        }
    }

    // Writing the position back through the typed setter changes nothing.
    let mut copy = *feedback;
    copy.set_actual_position(position);
    assert_eq!(copy.to_bytes(), *bytes);
    let mut image = *bytes;
    FeedbackFrame::new_unchecked(&mut image[..]).set_actual_position(position);
    assert_eq!(image, *bytes);
}

fn check_message(feedback: &Feedback) {
    let message = feedback.message;
    let kind = message.kind();
    assert_eq!(kind.code(), message.code);
    assert_eq!(MessageCode::from_code(kind.code()), kind);
    match message.code {
        0..=5 => assert!(kind.unit().is_some()),
        6..=9 => assert_eq!(kind, MessageCode::Reserved(message.code as u8)),
        _ => assert_eq!(kind, MessageCode::Unknown(message.code)),
    }
    assert!(!kind.name().is_empty());
    let _ = (message.to_string(), kind.to_string());
}

fn check_status_word(status: ServoStatusWord) {
    let table = status.parameter_table();
    let bits = status.bits();
    assert_eq!(
        u32::from(table.get() - 1),
        ((bits >> 12) & 1) * 4 + ((bits >> 8) & 0b11)
    );
    // Clearing the typed fields and writing them back changes no bit.
    const TYPED_BITS: u32 = 1 << 2 | 0b11 << 8 | 1 << 12;
    let rebuilt = ServoStatusWord::from_bits_retain(bits & !TYPED_BITS)
        .with_parameter_table(table)
        .with_encoder(status.encoder());
    assert_eq!(rebuilt, status);
    let names: Vec<&str> = status.flag_names().collect();
    let expected: Vec<&str> = ServoStatusWord::NAMES
        .iter()
        .filter(|(flag, _)| status.contains(*flag))
        .map(|(_, name)| *name)
        .collect();
    assert_eq!(names, expected);
}

fn check_error_word(errors: ServoErrorWord) {
    // The faults are the defined set bits (0–3, 5–24) in ascending order.
    let bits: Vec<u8> = errors.faults().map(ServoFault::bit).collect();
    let expected: Vec<u8> = (0..32u8)
        .filter(|&bit| bit != 4 && bit <= 24 && errors.bits() & (1 << bit) != 0)
        .collect();
    assert_eq!(bits, expected);
    for fault in errors.faults() {
        assert_eq!(ServoFault::from_bit(fault.bit()), Some(fault));
        assert!(errors.contains(fault.flag()));
        if let Some(code) = fault.e_code() {
            assert_eq!(code.fault(), fault);
            assert_eq!(code.bit(), fault.bit());
            assert_eq!(ServoErrorWord::from_e_code(code), fault.flag());
        }
        let _ = (fault.name(), fault.description(), fault.to_string());
    }
    // The summary bit is set exactly when a cause bit is, reserved bits kept.
    let summarized = errors.summarized();
    assert_eq!(
        summarized.contains(ServoErrorWord::SERVO_ERRORS),
        errors.has_cause()
    );
    assert_eq!(summarized.bits() & !1, errors.bits() & !1);
}

fn check_e_code_text(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match text.parse::<ECode>() {
        Ok(code) => {
            assert_eq!(ECode::from_number(code.number()), Some(code));
            assert_eq!(code.to_string().parse::<ECode>(), Ok(code));
            assert_eq!(code.fault().e_code(), Some(code));
        }
        Err(ParseECodeError::Malformed(_)) => {}
        Err(ParseECodeError::InvalidValue(ValueError { found, .. })) => {
            let number = u8::try_from(found).expect("at most two digits");
            assert!(number <= 99);
            assert_eq!(ECode::from_number(number), None);
        }
    }
    for &byte in data.iter().take(4) {
        match ECode::from_number(byte) {
            Some(code) => assert_eq!(code.number(), byte),
            None => assert!(ECode::try_from_number(byte).is_err()),
        }
    }
}
