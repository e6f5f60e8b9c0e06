//! The multiplexed measurement of the feedback frame: message code and message
//! data (docs/servo.md#feedback; the interface manual, "Message Code", "Message
//! Data").
//!
//! The drive sends one measurement per cycle; the i32 message code says what
//! the f32 message data holds. [`Message`] keeps both exactly as received —
//! codes the interface manual leaves reserved or does not define at all
//! round-trip unchanged, and so do the bits of the float (NaN payloads
//! included) — and [`MessageCode`] says what they mean.
//!
//! ```
//! use motionwire_codec::servo::{Message, MessageCode};
//!
//! let message = Message::new(MessageCode::BusVoltage, 560.5);
//! assert_eq!(message.code, 3);
//! assert_eq!(message.kind().name(), "bus_voltage");
//! assert_eq!(message.kind().unit(), Some("V"));
//!
//! let unknown = Message::from_raw(42, f32::from_bits(0x7FC0_1234));
//! assert_eq!(unknown.kind(), MessageCode::Unknown(42));
//! assert_eq!(unknown.data.to_bits(), 0x7FC0_1234);
//! ```

use core::fmt;

/// The message data of one cycle with the code that says what it holds
/// (docs/servo.md#feedback).
///
/// Both fields are the raw wire values. `PartialEq` compares the float by
/// value, so a message holding NaN is not equal to itself; compare
/// `data.to_bits()` (or the frame's bytes) to test for identity.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Message {
    /// Message code (feedback bytes 16–19), i32.
    pub code: i32,
    /// Message data (feedback bytes 20–23), f32; its unit depends on the code.
    pub data: f32,
}

impl Message {
    /// Return a message of kind `kind` holding `value` (in the kind's
    /// [`unit`](MessageCode::unit)).
    #[inline]
    #[must_use]
    pub const fn new(kind: MessageCode, value: f32) -> Self {
        Message {
            code: kind.code(),
            data: value,
        }
    }

    /// Return a message with the raw code and data as they are on the wire.
    #[inline]
    #[must_use]
    pub const fn from_raw(code: i32, data: f32) -> Self {
        Message { code, data }
    }

    /// Return what the message data holds, from the message code.
    #[inline]
    #[must_use]
    pub const fn kind(self) -> MessageCode {
        MessageCode::from_code(self.code)
    }
}

/// The message code of the feedback frame, read: what the message data holds
/// (the table of docs/servo.md#feedback; the interface manual, "Message Code").
/// A code table: each code the interface manual defines is a variant, every
/// other code is kept ([`MessageCode::Reserved`], [`MessageCode::Unknown`]).
///
/// Not to be confused with `canopen::MessageKind`, the kind of a CANopen
/// frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum MessageCode {
    /// Code 0: motor speed, rpm.
    MotorSpeed,
    /// Code 1: motor current I, A.
    MotorCurrent,
    /// Code 2: motor relative current I/In, %.
    RelativeCurrent,
    /// Code 3: bus voltage, V.
    BusVoltage,
    /// Code 4: motor temperature, °C.
    MotorTemperature,
    /// Code 5: motor power, kW (not available on current firmware).
    MotorPower,
    /// Codes 6–9: reserved by the interface manual; holds the code (6..=9 when
    /// made by [`MessageCode::from_code`]).
    Reserved(u8),
    /// Any other code (negative or above 9): unknown; holds the code.
    Unknown(i32),
}

impl MessageCode {
    /// Return the kind of message code `code`.
    #[must_use]
    pub const fn from_code(code: i32) -> Self {
        match code {
            0 => MessageCode::MotorSpeed,
            1 => MessageCode::MotorCurrent,
            2 => MessageCode::RelativeCurrent,
            3 => MessageCode::BusVoltage,
            4 => MessageCode::MotorTemperature,
            5 => MessageCode::MotorPower,
            // 6..=9 fits in u8.
            6..=9 => MessageCode::Reserved(code as u8),
            other => MessageCode::Unknown(other),
        }
    }

    /// Return the message code of this kind; `from_code(kind.code())` gives
    /// back every kind that `from_code` makes.
    #[must_use]
    pub const fn code(self) -> i32 {
        match self {
            MessageCode::MotorSpeed => 0,
            MessageCode::MotorCurrent => 1,
            MessageCode::RelativeCurrent => 2,
            MessageCode::BusVoltage => 3,
            MessageCode::MotorTemperature => 4,
            MessageCode::MotorPower => 5,
            MessageCode::Reserved(code) => code as i32,
            MessageCode::Unknown(code) => code,
        }
    }

    /// Return the kind's name as the command-line decoder's `message` writes
    /// it (docs/servo.md#cli-feedback), e.g. `"relative_current"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            MessageCode::MotorSpeed => "motor_speed",
            MessageCode::MotorCurrent => "motor_current",
            MessageCode::RelativeCurrent => "relative_current",
            MessageCode::BusVoltage => "bus_voltage",
            MessageCode::MotorTemperature => "motor_temperature",
            MessageCode::MotorPower => "motor_power",
            MessageCode::Reserved(_) => "reserved",
            MessageCode::Unknown(_) => "unknown",
        }
    }

    /// Return the unit of the message data (docs/servo.md#feedback), or `None`
    /// for a reserved or unknown code.
    #[must_use]
    pub const fn unit(self) -> Option<&'static str> {
        match self {
            MessageCode::MotorSpeed => Some("rpm"),
            MessageCode::MotorCurrent => Some("A"),
            MessageCode::RelativeCurrent => Some("%"),
            MessageCode::BusVoltage => Some("V"),
            MessageCode::MotorTemperature => Some("°C"),
            MessageCode::MotorPower => Some("kW"),
            MessageCode::Reserved(_) | MessageCode::Unknown(_) => None,
        }
    }
}

impl fmt::Display for MessageCode {
    /// Format the kind as its name (docs/servo.md#cli-feedback).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for Message {
    /// Format the message as value and unit, e.g. `motor_speed 1500 rpm`,
    /// or `unknown (code 42) 1.5` for a code without a unit.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = self.kind();
        match kind.unit() {
            Some(unit) => write!(f, "{kind} {} {unit}", self.data),
            None => write!(f, "{kind} (code {}) {}", self.code, self.data),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message-code table of docs/servo.md#feedback: (code, kind, name,
    /// unit).
    #[rustfmt::skip]
    const TABLE: [(i32, MessageCode, &str, Option<&str>); 10] = [
        (0, MessageCode::MotorSpeed,       "motor_speed",       Some("rpm")),
        (1, MessageCode::MotorCurrent,     "motor_current",     Some("A")),
        (2, MessageCode::RelativeCurrent,  "relative_current",  Some("%")),
        (3, MessageCode::BusVoltage,       "bus_voltage",       Some("V")),
        (4, MessageCode::MotorTemperature, "motor_temperature", Some("°C")),
        (5, MessageCode::MotorPower,       "motor_power",       Some("kW")),
        (6, MessageCode::Reserved(6),      "reserved",          None),
        (7, MessageCode::Reserved(7),      "reserved",          None),
        (8, MessageCode::Reserved(8),      "reserved",          None),
        (9, MessageCode::Reserved(9),      "reserved",          None),
    ];

    #[test]
    fn message_code_table() {
        for (code, kind, name, unit) in TABLE {
            assert_eq!(MessageCode::from_code(code), kind);
            assert_eq!(kind.code(), code);
            assert_eq!(kind.name(), name);
            assert_eq!(kind.to_string(), name);
            assert_eq!(kind.unit(), unit);
        }
    }

    #[test]
    fn other_codes_are_unknown_and_kept() {
        for code in [-1, 10, 42, i32::MIN, i32::MAX] {
            let kind = MessageCode::from_code(code);
            assert_eq!(kind, MessageCode::Unknown(code));
            assert_eq!(kind.code(), code);
            assert_eq!(kind.name(), "unknown");
            assert_eq!(kind.unit(), None);
        }
    }

    #[test]
    fn display() {
        assert_eq!(
            Message::new(MessageCode::MotorSpeed, 1500.0).to_string(),
            "motor_speed 1500 rpm"
        );
        assert_eq!(
            Message::from_raw(7, 1.5).to_string(),
            "reserved (code 7) 1.5"
        );
    }

    #[test]
    fn raw_bits_are_kept() {
        let message = Message::from_raw(-7, f32::from_bits(0xFFC0_0001));
        assert_eq!(message.data.to_bits(), 0xFFC0_0001);
        assert_eq!(message.kind(), MessageCode::Unknown(-7));
    }
}
