//! The 10-byte servo command frame, NC → servo (docs/servo.md#command,
//! docs/servo.md#scw).
//!
//! Arbitrary bytes → `Command::parse`. Invariants:
//! - fewer than 10 bytes is exactly `LenError { expected: 10, found }`;
//!   10 or more always parse;
//! - the zero-copy view and the owned value agree on every field, and
//!   `to_bytes` / `emit` give the first 10 bytes back;
//! - the typed fields of the control word (SE, parameter table, regulator
//!   mode, the active-low bits) read back what they were built from, and
//!   rebuilding the word from them changes no bit.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::servo::{
    Command, CommandFrame, ParameterTable, RegulatorMode, ServoControlWord, ServoEnable,
    COMMAND_LEN,
};
use motionwire::LenError;
use motionwire::What;

fuzz_target!(|data: &[u8]| {
    let command = match Command::parse(data) {
        Ok(command) => command,
        Err(error) => {
            assert_eq!(
                error,
                LenError {
                    what: What::ServoCommandFrame,
                    expected: COMMAND_LEN,
                    found: data.len(),
                }
            );
            assert!(CommandFrame::new_checked(data).is_err());
            let _ = error.to_string();
            return;
        }
    };
    let bytes: [u8; COMMAND_LEN] = data[..COMMAND_LEN].try_into().unwrap();

    // View and owned value agree on every field.
    let frame = CommandFrame::new_checked(data).expect("parse succeeded");
    assert_eq!(frame.speed_setpoint(), command.speed_setpoint);
    assert_eq!(frame.speed_setpoint_word(), command.speed_setpoint_word());
    assert_eq!(frame.control_word(), command.control);
    assert_eq!(frame.extra_data_code(), command.extra_data_code);
    assert_eq!(Command::parse_frame(&frame), command);
    assert_eq!(Command::from_bytes(&bytes), command);

    // The word reading is the low word of SSP.
    assert_eq!(
        command.speed_setpoint_word().to_le_bytes(),
        [bytes[0], bytes[1]]
    );

    // Encoding gives the bytes back, through the owned value and the view.
    assert_eq!(command.to_bytes(), bytes);
    let mut image = [0xA5u8; COMMAND_LEN];
    command.emit(&mut CommandFrame::new_unchecked(&mut image[..]));
    assert_eq!(image, bytes);

    // The view's setters write back what the getters read.
    let mut copy = bytes;
    let mut view = CommandFrame::new_unchecked(&mut copy[..]);
    view.set_speed_setpoint_word(command.speed_setpoint_word());
    view.set_control_word(command.control);
    view.set_extra_data_code(command.extra_data_code);
    assert_eq!(copy, bytes);

    check_control_word(command.control);
});

fn check_control_word(control: ServoControlWord) {
    let bits = control.bits();

    let se = control.servo_enable();
    assert_eq!(u32::from(se.get()), bits & 0b11);
    assert_eq!(ServoEnable::new(se.get()), Some(se));
    let table = control.parameter_table();
    assert!((1..=8).contains(&table.get()));
    assert_eq!(
        u32::from(table.get() - 1),
        ((bits >> 12) & 1) * 4 + ((bits >> 4) & 0b11)
    );
    assert_eq!(ParameterTable::new(table.get()), Some(table));
    let mode = control.regulator_mode();
    assert_eq!(u32::from(mode.get()), (bits >> 6) & 0b11);
    assert_eq!(RegulatorMode::new(mode.get()), Some(mode));

    // Active-low bits: EMGON (bit 2) and Brake (bit 10).
    assert_eq!(control.emergency_active(), bits & (1 << 2) == 0);
    assert_eq!(control.internal_brake_active(), bits & (1 << 10) == 0);

    // Clearing the typed fields and writing them back from their typed
    // values gives the same word: the builders write exactly their bits.
    const TYPED_BITS: u32 = 0b11 | 1 << 2 | 0b11 << 4 | 0b11 << 6 | 1 << 10 | 1 << 12;
    let rebuilt = ServoControlWord::from_bits_retain(bits & !TYPED_BITS)
        .with_servo_enable(se)
        .with_parameter_table(table)
        .with_regulator_mode(mode)
        .with_emergency(control.emergency_active())
        .with_internal_brake(control.internal_brake_active());
    assert_eq!(rebuilt, control);

    // The flag names are the set single-bit flags, in bit order.
    let names: Vec<&str> = control.flag_names().collect();
    let expected: Vec<&str> = ServoControlWord::NAMES
        .iter()
        .filter(|(flag, _)| control.contains(*flag))
        .map(|(_, name)| *name)
        .collect();
    assert_eq!(names, expected);
    let _ = (
        se.to_string(),
        table.to_string(),
        mode.to_string(),
        mode.name(),
    );
}
