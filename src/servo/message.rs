//! The multiplexed measurement of the feedback frame: message code and
//! message data (SPEC §1.2; seed 002, "Message Code", "Message Data").
//!
//! The drive sends one measurement per cycle; the i32 message code says what
//! the f32 message data holds. [`Message`] keeps both exactly as received —
//! codes the seed leaves reserved or does not define at all round-trip
//! unchanged, and so do the bits of the float (NaN payloads included) — and
//! [`MessageKind`] says what they mean.
//!
//! ```
//! use motionwire::servo::{Message, MessageKind};
//!
//! let message = Message::new(MessageKind::BusVoltage, 560.5);
//! assert_eq!(message.code, 3);
//! assert_eq!(message.kind().name(), "bus_voltage");
//! assert_eq!(message.kind().unit(), Some("V"));
//!
//! let unknown = Message::from_raw(42, f32::from_bits(0x7FC0_1234));
//! assert_eq!(unknown.kind(), MessageKind::Unknown(42));
//! assert_eq!(unknown.data.to_bits(), 0x7FC0_1234);
//! ```

use core::fmt;

/// The message data of one cycle with the code that says what it holds
/// (SPEC §1.2).
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
    /// [`unit`](MessageKind::unit)).
    #[inline]
    #[must_use]
    pub const fn new(kind: MessageKind, value: f32) -> Self {
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
    pub const fn kind(self) -> MessageKind {
        MessageKind::from_code(self.code)
    }
}

/// What the message data holds, from the message code (SPEC §1.2's table;
/// seed 002, "Message Code").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum MessageKind {
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
    /// Codes 6–9: reserved by the seed; holds the code (6..=9 when made by
    /// [`MessageKind::from_code`]).
    Reserved(u8),
    /// Any other code (negative or above 9): unknown; holds the code.
    Unknown(i32),
}

impl MessageKind {
    /// Return the kind of message code `code`.
    #[must_use]
    pub const fn from_code(code: i32) -> Self {
        match code {
            0 => MessageKind::MotorSpeed,
            1 => MessageKind::MotorCurrent,
            2 => MessageKind::RelativeCurrent,
            3 => MessageKind::BusVoltage,
            4 => MessageKind::MotorTemperature,
            5 => MessageKind::MotorPower,
            // 6..=9 fits in u8.
            6..=9 => MessageKind::Reserved(code as u8),
            other => MessageKind::Unknown(other),
        }
    }

    /// Return the message code of this kind; `from_code(kind.code())` gives
    /// back every kind that `from_code` makes.
    #[must_use]
    pub const fn code(self) -> i32 {
        match self {
            MessageKind::MotorSpeed => 0,
            MessageKind::MotorCurrent => 1,
            MessageKind::RelativeCurrent => 2,
            MessageKind::BusVoltage => 3,
            MessageKind::MotorTemperature => 4,
            MessageKind::MotorPower => 5,
            MessageKind::Reserved(code) => code as i32,
            MessageKind::Unknown(code) => code,
        }
    }

    /// Return the kind's name as the command-line decoder's `message` writes
    /// it (SPEC §6.2), e.g. `"relative_current"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            MessageKind::MotorSpeed => "motor_speed",
            MessageKind::MotorCurrent => "motor_current",
            MessageKind::RelativeCurrent => "relative_current",
            MessageKind::BusVoltage => "bus_voltage",
            MessageKind::MotorTemperature => "motor_temperature",
            MessageKind::MotorPower => "motor_power",
            MessageKind::Reserved(_) => "reserved",
            MessageKind::Unknown(_) => "unknown",
        }
    }

    /// Return the unit of the message data (SPEC §1.2), or `None` for a
    /// reserved or unknown code.
    #[must_use]
    pub const fn unit(self) -> Option<&'static str> {
        match self {
            MessageKind::MotorSpeed => Some("rpm"),
            MessageKind::MotorCurrent => Some("A"),
            MessageKind::RelativeCurrent => Some("%"),
            MessageKind::BusVoltage => Some("V"),
            MessageKind::MotorTemperature => Some("°C"),
            MessageKind::MotorPower => Some("kW"),
            MessageKind::Reserved(_) | MessageKind::Unknown(_) => None,
        }
    }
}

impl fmt::Display for MessageKind {
    /// Format the kind as its SPEC §6.2 name.
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

    /// SPEC §1.2's message-code table: (code, kind, name, unit).
    #[rustfmt::skip]
    const TABLE: [(i32, MessageKind, &str, Option<&str>); 10] = [
        (0, MessageKind::MotorSpeed,       "motor_speed",       Some("rpm")),
        (1, MessageKind::MotorCurrent,     "motor_current",     Some("A")),
        (2, MessageKind::RelativeCurrent,  "relative_current",  Some("%")),
        (3, MessageKind::BusVoltage,       "bus_voltage",       Some("V")),
        (4, MessageKind::MotorTemperature, "motor_temperature", Some("°C")),
        (5, MessageKind::MotorPower,       "motor_power",       Some("kW")),
        (6, MessageKind::Reserved(6),      "reserved",          None),
        (7, MessageKind::Reserved(7),      "reserved",          None),
        (8, MessageKind::Reserved(8),      "reserved",          None),
        (9, MessageKind::Reserved(9),      "reserved",          None),
    ];

    #[test]
    fn message_code_table() {
        for (code, kind, name, unit) in TABLE {
            assert_eq!(MessageKind::from_code(code), kind);
            assert_eq!(kind.code(), code);
            assert_eq!(kind.name(), name);
            assert_eq!(kind.to_string(), name);
            assert_eq!(kind.unit(), unit);
        }
    }

    #[test]
    fn other_codes_are_unknown_and_kept() {
        for code in [-1, 10, 42, i32::MIN, i32::MAX] {
            let kind = MessageKind::from_code(code);
            assert_eq!(kind, MessageKind::Unknown(code));
            assert_eq!(kind.code(), code);
            assert_eq!(kind.name(), "unknown");
            assert_eq!(kind.unit(), None);
        }
    }

    #[test]
    fn display() {
        assert_eq!(
            Message::new(MessageKind::MotorSpeed, 1500.0).to_string(),
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
        assert_eq!(message.kind(), MessageKind::Unknown(-7));
    }
}
