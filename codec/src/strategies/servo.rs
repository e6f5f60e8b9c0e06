//! Strategies for the servo ↔ NC types (docs/servo.md).

use proptest::prelude::*;

use crate::servo::{
    ActualPosition, Command, Feedback, Message, ParameterTable, ServoControlWord, ServoEnable,
    ServoErrorWord, ServoStatusWord,
};

/// Any control word, reserved bits included.
pub fn control_word() -> impl Strategy<Value = ServoControlWord> {
    any::<u32>().prop_map(ServoControlWord::from_bits_retain)
}

/// Any status word, reserved bits included.
pub fn status_word() -> impl Strategy<Value = ServoStatusWord> {
    any::<u32>().prop_map(ServoStatusWord::from_bits_retain)
}

/// Any error word, reserved bits included.
pub fn error_word() -> impl Strategy<Value = ServoErrorWord> {
    any::<u32>().prop_map(ServoErrorWord::from_bits_retain)
}

/// Any SE value, 0..=3.
pub fn servo_enable() -> impl Strategy<Value = ServoEnable> {
    (0u8..=3).prop_map(|raw| ServoEnable::new(raw).expect("0..=3 is an SE value"))
}

/// Any parameter table, 1..=8.
pub fn parameter_table() -> impl Strategy<Value = ParameterTable> {
    (1u8..=8).prop_map(|raw| ParameterTable::new(raw).expect("1..=8 is a table"))
}

/// Any float bit pattern, NaNs with payloads and infinities included.
pub fn any_f32_bits() -> impl Strategy<Value = f32> {
    any::<u32>().prop_map(f32::from_bits)
}

/// Any message: known, reserved and unknown codes, any float bits.
pub fn message() -> impl Strategy<Value = Message> {
    let code = prop_oneof![0i32..=9, any::<i32>()];
    (code, any_f32_bits()).prop_map(|(code, data)| Message::from_raw(code, data))
}

/// Any actual position of either encoder kind.
pub fn actual_position() -> impl Strategy<Value = ActualPosition> {
    prop_oneof![
        any::<i64>().prop_map(ActualPosition::Absolute),
        (any::<i32>(), any::<i32>()).prop_map(|(position, zero_pulse_position)| {
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            }
        }),
    ]
}

/// Any command frame.
pub fn command() -> impl Strategy<Value = Command> {
    (any::<i32>(), control_word(), any::<i16>())
        .prop_map(|(ssp, scw, extra)| Command::new(ssp, scw, extra))
}

/// Any feedback frame.
pub fn feedback() -> impl Strategy<Value = Feedback> {
    (
        any::<i64>(),
        status_word(),
        error_word(),
        message(),
        [
            any_f32_bits(),
            any_f32_bits(),
            any_f32_bits(),
            any_f32_bits(),
        ],
    )
        .prop_map(|(position, status, errors, message, extra_data)| Feedback {
            position,
            status,
            errors,
            message,
            extra_data,
        })
}
