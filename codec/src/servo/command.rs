//! The 10-byte command frame, NC → servo, sent once per NC control cycle
//! (docs/servo.md#command; the interface manual, "1. type message").
//!
//! [`CommandFrame`] is a zero-copy view over the bytes; [`Command`] is the
//! owned, `Copy` value. Both share the offsets in `field`.
//!
//! ```
//! use motionwire_codec::servo::{Command, CommandFrame, ServoControlWord, ServoEnable};
//!
//! // Emit a command into the process image…
//! let command = Command::new(
//!     -1000,
//!     ServoControlWord::NORMAL.with_servo_enable(ServoEnable::ARM),
//!     0,
//! );
//! let mut image = [0u8; 10];
//! command.emit(&mut CommandFrame::new_unchecked(&mut image[..]));
//! assert_eq!(image, [0x18, 0xFC, 0xFF, 0xFF, 0x05, 0x04, 0, 0, 0, 0]);
//!
//! // …and read it back, as a view or as an owned value.
//! let frame = CommandFrame::new_checked(&image[..])?;
//! assert_eq!(frame.speed_setpoint(), -1000);
//! assert_eq!(frame.control_word().servo_enable(), ServoEnable::ARM);
//! assert_eq!(Command::parse(&image)?, command);
//!
//! // A short buffer is an error that says how short.
//! assert!(Command::parse(&image[..9]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use byteorder::{ByteOrder, LittleEndian};
use core::fmt;

use super::ServoControlWord;
use crate::error::check_len;
use crate::{LenError, Result};

mod field {
    use core::ops::Range;

    /// Bytes 0–3: SSP, speed set point (SSPW0 low word, SSPW1 high word), i32.
    pub(super) const SPEED_SETPOINT: Range<usize> = 0..4;
    /// Bytes 0–1: SSPW0, the low word alone, for a 16-bit ("word type")
    /// reference.
    pub(super) const SPEED_SETPOINT_WORD: Range<usize> = 0..2;
    /// Bytes 4–7: SCW, servo control word (SCW0, SCW1), u32.
    pub(super) const CONTROL: Range<usize> = 4..8;
    /// Bytes 8–9: extra data code word, i16.
    pub(super) const EXTRA_DATA_CODE: Range<usize> = 8..10;
}

/// The length of a command frame, 10 bytes (docs/servo.md#command).
pub const COMMAND_LEN: usize = field::EXTRA_DATA_CODE.end;

const WHAT: What = What::ServoCommandFrame;

/// A zero-copy view over a command frame, NC → servo (docs/servo.md#command).
///
/// After [`CommandFrame::new_checked`] (or [`CommandFrame::check_len`])
/// succeeds, no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CommandFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> CommandFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// shorter than [`COMMAND_LEN`].
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        CommandFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least [`COMMAND_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`COMMAND_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(WHAT, self.buffer.as_ref(), COMMAND_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the SSP field (bytes 0–3), the speed set point as a 32-bit
    /// ("double word type") reference.
    #[inline]
    pub fn speed_setpoint(&self) -> i32 {
        LittleEndian::read_i32(&self.buffer.as_ref()[field::SPEED_SETPOINT])
    }

    /// Return the SSPW0 field (bytes 0–1), the speed set point as a 16-bit
    /// ("word type") reference; the high word is then not significant.
    #[inline]
    pub fn speed_setpoint_word(&self) -> i16 {
        LittleEndian::read_i16(&self.buffer.as_ref()[field::SPEED_SETPOINT_WORD])
    }

    /// Return the SCW field (bytes 4–7), reserved bits preserved.
    #[inline]
    pub fn control_word(&self) -> ServoControlWord {
        ServoControlWord::from_bits_retain(LittleEndian::read_u32(
            &self.buffer.as_ref()[field::CONTROL],
        ))
    }

    /// Return the extra data code word field (bytes 8–9), carried raw (its
    /// meaning is not specified).
    #[inline]
    pub fn extra_data_code(&self) -> i16 {
        LittleEndian::read_i16(&self.buffer.as_ref()[field::EXTRA_DATA_CODE])
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> CommandFrame<T> {
    /// Set the SSP field (bytes 0–3).
    #[inline]
    pub fn set_speed_setpoint(&mut self, value: i32) {
        LittleEndian::write_i32(&mut self.buffer.as_mut()[field::SPEED_SETPOINT], value);
    }

    /// Set the SSPW0 field (bytes 0–1) only; the high word SSPW1 is left as
    /// it is.
    #[inline]
    pub fn set_speed_setpoint_word(&mut self, value: i16) {
        LittleEndian::write_i16(&mut self.buffer.as_mut()[field::SPEED_SETPOINT_WORD], value);
    }

    /// Set the SCW field (bytes 4–7).
    #[inline]
    pub fn set_control_word(&mut self, value: ServoControlWord) {
        LittleEndian::write_u32(&mut self.buffer.as_mut()[field::CONTROL], value.bits());
    }

    /// Set the extra data code word field (bytes 8–9).
    #[inline]
    pub fn set_extra_data_code(&mut self, value: i16) {
        LittleEndian::write_i16(&mut self.buffer.as_mut()[field::EXTRA_DATA_CODE], value);
    }
}

/// A command frame, owned (docs/servo.md#command; the interface manual).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Command {
    /// SSP, the speed set point (bytes 0–3). For a 16-bit reference only
    /// the low word counts; see [`Command::speed_setpoint_word`].
    pub speed_setpoint: i32,
    /// SCW, the servo control word (bytes 4–7).
    pub control: ServoControlWord,
    /// Extra data code word (bytes 8–9), carried raw.
    pub extra_data_code: i16,
}

impl Command {
    /// Return a command with the given fields.
    #[inline]
    #[must_use]
    pub const fn new(speed_setpoint: i32, control: ServoControlWord, extra_data_code: i16) -> Self {
        Command {
            speed_setpoint,
            control,
            extra_data_code,
        }
    }

    /// Return a command carrying a 16-bit ("word type") speed reference. The
    /// value is sign-extended into SSP, so both readings of the frame
    /// ([`speed_setpoint`](Self::speed_setpoint) and
    /// [`speed_setpoint_word`](Self::speed_setpoint_word)) give the same number.
    #[inline]
    #[must_use]
    pub const fn with_word_setpoint(
        speed_setpoint: i16,
        control: ServoControlWord,
        extra_data_code: i16,
    ) -> Self {
        Command::new(speed_setpoint as i32, control, extra_data_code)
    }

    /// Return the speed set point read as a 16-bit reference: the low word
    /// SSPW0 (docs/servo.md#command).
    #[inline]
    #[must_use]
    pub const fn speed_setpoint_word(&self) -> i16 {
        // Keeping only the low 16 bits is the meaning of the word reading.
        self.speed_setpoint as i16
    }

    /// Decode the 10 bytes of a command frame.
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; COMMAND_LEN]) -> Self {
        Self::parse_frame(&CommandFrame::new_unchecked(bytes))
    }

    /// Encode the command into its 10 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; COMMAND_LEN] {
        let mut bytes = [0; COMMAND_LEN];
        self.emit(&mut CommandFrame::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode a command frame from the start of `data`; fewer than 10 bytes
    /// is a [`LenError`].
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        Ok(Self::parse_frame(&CommandFrame::new_checked(data)?))
    }

    /// Read the owned value out of a view.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &CommandFrame<T>) -> Self {
        Command {
            speed_setpoint: frame.speed_setpoint(),
            control: frame.control_word(),
            extra_data_code: frame.extra_data_code(),
        }
    }

    /// Write every field into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut CommandFrame<T>) {
        frame.set_speed_setpoint(self.speed_setpoint);
        frame.set_control_word(self.control);
        frame.set_extra_data_code(self.extra_data_code);
    }

    /// Return the command laid out for people, one field per line
    /// ([`CommandDetails`]): the text `motionwire servo command` prints
    /// (docs/servo.md#cli-command).
    #[inline]
    #[must_use]
    pub const fn details(&self) -> CommandDetails {
        CommandDetails(*self)
    }
}

/// A [`Command`] laid out for people, one field per line, as `motionwire
/// servo command HEX` prints it (docs/servo.md#cli-command): the two readings
/// of the set point (docs/servo.md#command), the control word in hex, then its
/// fields — SE, the active-low EMGON and Brake read as states, the regulator
/// mode, the parameter table and the names of the set flags (docs/servo.md#scw)
/// — and the extra data code. Made by [`Command::details`]; its
/// [`Display`](fmt::Display) writes the lines without a final newline.
///
/// A separate type because the lines are a view for a terminal, not the
/// one way to print a command.
///
/// ```
/// use motionwire_codec::servo::{Command, ServoControlWord, ServoEnable};
///
/// let scw = ServoControlWord::NORMAL.with_servo_enable(ServoEnable::ENABLE);
/// let text = Command::new(1000, scw, -1).details().to_string();
/// assert_eq!(
///     text.lines().collect::<Vec<_>>(),
///     [
///         "speed set point   1000 (word reading 1000)",
///         "control word      0x00000406",
///         "  servo enable    0b10",
///         "  emergency       off (EMGON = 1)",
///         "  internal brake  off (Brake = 1)",
///         "  regulator mode  speed",
///         "  parameter table 1",
///         "  flags           EMGON Brake",
///         "extra data code   -1",
///     ]
/// );
/// assert!(!text.ends_with('\n'));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CommandDetails(Command);

impl CommandDetails {
    /// Return the command these lines describe.
    #[inline]
    #[must_use]
    pub const fn command(&self) -> Command {
        self.0
    }
}

impl fmt::Display for CommandDetails {
    /// Write the command's lines (docs/servo.md#cli-command), without a final
    /// newline.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = &self.0;
        let control = c.control;
        writeln!(
            f,
            "speed set point   {} (word reading {})",
            c.speed_setpoint,
            c.speed_setpoint_word()
        )?;
        writeln!(f, "control word      0x{:08X}", control.bits())?;
        writeln!(
            f,
            "  servo enable    0b{:02b}",
            control.servo_enable().get()
        )?;
        let emergency = if control.emergency_active() {
            "active (EMGON = 0)"
        } else {
            "off (EMGON = 1)"
        };
        writeln!(f, "  emergency       {emergency}")?;
        let brake = if control.internal_brake_active() {
            "active (Brake = 0)"
        } else {
            "off (Brake = 1)"
        };
        writeln!(f, "  internal brake  {brake}")?;
        writeln!(f, "  regulator mode  {}", control.regulator_mode().name())?;
        writeln!(f, "  parameter table {}", control.parameter_table().get())?;
        f.write_str("  flags          ")?;
        for name in control.flag_names() {
            write!(f, " {name}")?;
        }
        f.write_str("\n")?;
        write!(f, "extra data code   {}", c.extra_data_code)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::{ParameterTable, RegulatorMode, ServoEnable};

    /// SSP = -2 (0xFFFF_FFFE); SCW = SE 0b10, EMGON, POSLOCK, table 6,
    /// position mode, Brake, ZPulseRequest, ExtPRMTBL, reserved bit 20 and
    /// PRGDWN; extra data code 0x1234.
    static FRAME_BYTES: [u8; 10] = [0xFE, 0xFF, 0xFF, 0xFF, 0x9E, 0x1C, 0x10, 0x80, 0x34, 0x12];

    fn fixture_control() -> ServoControlWord {
        ServoControlWord::NORMAL
            .with_servo_enable(ServoEnable::ENABLE)
            .with_parameter_table(ParameterTable::try_new(6).unwrap())
            .with_regulator_mode(RegulatorMode::Position)
            .union(ServoControlWord::POSLOCK)
            .union(ServoControlWord::Z_PULSE_REQUEST)
            .union(ServoControlWord::PRGDWN)
            .union(ServoControlWord::from_bits_retain(1 << 20))
    }

    #[test]
    fn deconstruct() {
        let frame = CommandFrame::new_checked(&FRAME_BYTES[..]).unwrap();
        assert_eq!(frame.speed_setpoint(), -2);
        assert_eq!(frame.speed_setpoint_word(), -2);
        let scw = frame.control_word();
        assert_eq!(scw, fixture_control());
        assert_eq!(scw.bits(), 0x8010_1C9E);
        assert_eq!(scw.servo_enable(), ServoEnable::ENABLE);
        assert_eq!(scw.parameter_table().get(), 6);
        assert_eq!(scw.regulator_mode(), RegulatorMode::Position);
        assert_eq!(
            scw.flag_names().collect::<Vec<_>>(),
            [
                "EMGON",
                "POSLOCK",
                "Brake",
                "ZPulseRequest",
                "ExtPRMTBL",
                "PRGDWN"
            ]
        );
        assert_eq!(frame.extra_data_code(), 0x1234);
    }

    #[test]
    fn construct() {
        let mut bytes = [0xA5u8; 10];
        let mut frame = CommandFrame::new_unchecked(&mut bytes[..]);
        frame.set_speed_setpoint(-2);
        frame.set_control_word(fixture_control());
        frame.set_extra_data_code(0x1234);
        assert_eq!(bytes, FRAME_BYTES);
    }

    #[test]
    fn parse_and_emit() {
        let command = Command::parse(&FRAME_BYTES).unwrap();
        assert_eq!(command, Command::new(-2, fixture_control(), 0x1234));
        assert_eq!(command.to_bytes(), FRAME_BYTES);
        assert_eq!(Command::from_bytes(&FRAME_BYTES), command);
        let mut bytes = [0u8; 10];
        command.emit(&mut CommandFrame::new_unchecked(&mut bytes[..]));
        assert_eq!(bytes, FRAME_BYTES);
    }

    /// docs/servo.md#command: with a 16-bit reference only SSPW0 counts.
    #[test]
    fn word_type_speed_setpoint() {
        // High word 0x0001 is not significant for the word reading.
        let bytes = [0x30, 0xF8, 0x01, 0x00, 0, 0, 0, 0, 0, 0];
        let frame = CommandFrame::new_checked(&bytes[..]).unwrap();
        assert_eq!(frame.speed_setpoint(), 0x0001_F830);
        assert_eq!(frame.speed_setpoint_word(), -2000);
        assert_eq!(Command::from_bytes(&bytes).speed_setpoint_word(), -2000);

        // The view's word setter leaves the high word alone.
        let mut bytes = [0xFFu8; 10];
        CommandFrame::new_unchecked(&mut bytes[..]).set_speed_setpoint_word(0x1234);
        assert_eq!(bytes[..4], [0x34, 0x12, 0xFF, 0xFF]);

        // The owned word constructor sign-extends so both readings agree.
        let command = Command::with_word_setpoint(-2000, ServoControlWord::NORMAL, 0);
        assert_eq!(command.to_bytes()[..4], [0x30, 0xF8, 0xFF, 0xFF]);
        assert_eq!(command.speed_setpoint, -2000);
        assert_eq!(command.speed_setpoint_word(), -2000);
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        for len in 0..COMMAND_LEN {
            let expected = LenError {
                what: What::ServoCommandFrame,
                expected: 10,
                found: len,
            };
            assert_eq!(Command::parse(&FRAME_BYTES[..len]), Err(expected));
            assert_eq!(
                CommandFrame::new_checked(&FRAME_BYTES[..len]),
                Err(expected)
            );
        }
    }

    #[test]
    fn longer_buffers_read_the_first_ten_bytes() {
        let mut long = [0xEEu8; 16];
        long[..10].copy_from_slice(&FRAME_BYTES);
        assert_eq!(Command::parse(&long).unwrap().to_bytes(), FRAME_BYTES);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::command;

    proptest! {
        #[test]
        fn bytes_owned_bytes(bytes in any::<[u8; COMMAND_LEN]>()) {
            prop_assert_eq!(Command::from_bytes(&bytes).to_bytes(), bytes);
        }

        #[test]
        fn owned_bytes_owned(value in command()) {
            prop_assert_eq!(Command::from_bytes(&value.to_bytes()), value);
        }

        #[test]
        fn view_and_owned_agree(bytes in any::<[u8; COMMAND_LEN]>()) {
            let frame = CommandFrame::new_checked(&bytes[..]).unwrap();
            let owned = Command::parse_frame(&frame);
            prop_assert_eq!(frame.speed_setpoint(), owned.speed_setpoint);
            prop_assert_eq!(frame.speed_setpoint_word(), owned.speed_setpoint_word());
            prop_assert_eq!(frame.control_word(), owned.control);
            prop_assert_eq!(frame.extra_data_code(), owned.extra_data_code);
        }

        #[test]
        fn setters_match_emit(value in command(), fill in any::<u8>()) {
            let mut bytes = [fill; COMMAND_LEN];
            let mut frame = CommandFrame::new_unchecked(&mut bytes[..]);
            frame.set_speed_setpoint(value.speed_setpoint);
            frame.set_control_word(value.control);
            frame.set_extra_data_code(value.extra_data_code);
            prop_assert_eq!(bytes, value.to_bytes());
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..24)) {
            match Command::parse(&data) {
                Ok(value) => prop_assert_eq!(&value.to_bytes()[..], &data[..COMMAND_LEN]),
                Err(e) => prop_assert_eq!(e, LenError {
                    what: What::ServoCommandFrame,
                    expected: COMMAND_LEN,
                    found: data.len(),
                }),
            }
        }
    }
}
