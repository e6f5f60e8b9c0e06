//! The 40-byte feedback frame, servo → NC, sent once per NC control cycle
//! (docs/servo.md#feedback; the interface manual, "1. type message").
//!
//! [`FeedbackFrame`] is a zero-copy view over the bytes; [`Feedback`] is the
//! owned, `Copy` value. Both share the offsets in `field`. The actual
//! position is read according to the status word's Abs/Incr bit
//! ([`ActualPosition`]); the raw 64-bit value is always available too.
//!
//! ```
//! use motionwire_codec::servo::{
//!     ActualPosition, Feedback, FeedbackFrame, Message, MessageCode, ServoErrorWord,
//!     ServoStatusWord,
//! };
//!
//! let mut feedback = Feedback {
//!     position: 0,
//!     status: ServoStatusWord::SERVO_EN | ServoStatusWord::SERVO_RDY,
//!     errors: ServoErrorWord::empty(),
//!     message: Message::new(MessageCode::MotorSpeed, 1500.0),
//!     extra_data: [0.0; 4],
//! };
//! feedback.set_actual_position(ActualPosition::Incremental {
//!     position: 10_000,
//!     zero_pulse_position: 4_096,
//! });
//!
//! let mut image = [0u8; 40];
//! feedback.emit(&mut FeedbackFrame::new_unchecked(&mut image[..]));
//! let frame = FeedbackFrame::new_checked(&image[..])?;
//! assert_eq!(frame.zero_pulse_position(), 4_096);
//! assert_eq!(frame.status_word().encoder().name(), "incremental");
//! assert_eq!(Feedback::parse(&image)?.to_bytes(), image);
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use byteorder::{ByteOrder, LittleEndian};
use core::fmt;

use super::{EncoderKind, Message, ServoErrorWord, ServoStatusWord};
use crate::error::check_len;
use crate::{LenError, Result};

mod field {
    use core::ops::Range;

    /// Bytes 0–7: ActPos, actual position (POSW0..POSW3), i64.
    pub(super) const POSITION: Range<usize> = 0..8;
    /// Bytes 0–3: POSW0..1, the incremental encoder's position, i32.
    pub(super) const INCREMENTAL_POSITION: Range<usize> = 0..4;
    /// Bytes 4–7: POSW2..3, the position latched at the last zero pulse, i32.
    pub(super) const ZERO_PULSE_POSITION: Range<usize> = 4..8;
    /// Bytes 8–11: SSW, servo status word, u32.
    pub(super) const STATUS: Range<usize> = 8..12;
    /// Bytes 12–15: SEW, servo error word, u32.
    pub(super) const ERRORS: Range<usize> = 12..16;
    /// Bytes 16–19: message code, i32.
    pub(super) const MESSAGE_CODE: Range<usize> = 16..20;
    /// Bytes 20–23: message data, f32.
    pub(super) const MESSAGE_DATA: Range<usize> = 20..24;
    /// Bytes 24–39: extra data 1–4, four f32.
    pub(super) const EXTRA_DATA: Range<usize> = 24..40;
}

/// The length of a feedback frame, 40 bytes (docs/servo.md#feedback).
pub const FEEDBACK_LEN: usize = field::EXTRA_DATA.end;

const WHAT: What = What::ServoFeedbackFrame;

/// The actual position, read according to the status word's Abs/Incr bit
/// (docs/servo.md#feedback, "ActPos interpretation"; the interface manual,
/// "ActualPosition").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ActualPosition {
    /// Absolute (EnDat) encoder: the whole 64-bit ActPos is the position.
    Absolute(i64),
    /// Incremental encoder: ActPos holds two 32-bit values.
    Incremental {
        /// POSW0..1 (low i32): the position.
        position: i32,
        /// POSW2..3 (high i32): the position latched at the last zero pulse
        /// (written when the first zero pulse after a request is found, and
        /// again at every further zero pulse).
        zero_pulse_position: i32,
    },
}

impl ActualPosition {
    /// Return the position that the raw ActPos `raw` means for `encoder`.
    #[must_use]
    pub const fn from_raw(raw: i64, encoder: EncoderKind) -> Self {
        match encoder {
            EncoderKind::Absolute => ActualPosition::Absolute(raw),
            EncoderKind::Incremental => ActualPosition::Incremental {
                // Low and high halves of the 64-bit word.
                position: raw as i32,
                zero_pulse_position: (raw >> 32) as i32,
            },
        }
    }

    /// Return the raw 64-bit ActPos that carries this position.
    #[must_use]
    pub const fn raw(self) -> i64 {
        match self {
            ActualPosition::Absolute(raw) => raw,
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => ((zero_pulse_position as i64) << 32) | (position as u32 as i64),
        }
    }

    /// Return the kind of encoder this position comes from.
    #[must_use]
    pub const fn encoder(self) -> EncoderKind {
        match self {
            ActualPosition::Absolute(_) => EncoderKind::Absolute,
            ActualPosition::Incremental { .. } => EncoderKind::Incremental,
        }
    }
}

/// A zero-copy view over a feedback frame, servo → NC (docs/servo.md#feedback).
///
/// After [`FeedbackFrame::new_checked`] (or [`FeedbackFrame::check_len`])
/// succeeds, no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FeedbackFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> FeedbackFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// shorter than [`FEEDBACK_LEN`].
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        FeedbackFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least [`FEEDBACK_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`FEEDBACK_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(WHAT, self.buffer.as_ref(), FEEDBACK_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the ActPos field (bytes 0–7) as the raw i64, whatever the
    /// encoder.
    #[inline]
    pub fn position(&self) -> i64 {
        LittleEndian::read_i64(&self.buffer.as_ref()[field::POSITION])
    }

    /// Return the POSW0..1 field (bytes 0–3), an incremental encoder's
    /// position.
    #[inline]
    pub fn incremental_position(&self) -> i32 {
        LittleEndian::read_i32(&self.buffer.as_ref()[field::INCREMENTAL_POSITION])
    }

    /// Return the POSW2..3 field (bytes 4–7), an incremental encoder's
    /// position at the last zero pulse.
    #[inline]
    pub fn zero_pulse_position(&self) -> i32 {
        LittleEndian::read_i32(&self.buffer.as_ref()[field::ZERO_PULSE_POSITION])
    }

    /// Return the ActPos field read as the status word's Abs/Incr bit says.
    #[inline]
    pub fn actual_position(&self) -> ActualPosition {
        ActualPosition::from_raw(self.position(), self.status_word().encoder())
    }

    /// Return the SSW field (bytes 8–11), reserved bits preserved.
    #[inline]
    pub fn status_word(&self) -> ServoStatusWord {
        ServoStatusWord::from_bits_retain(LittleEndian::read_u32(
            &self.buffer.as_ref()[field::STATUS],
        ))
    }

    /// Return the SEW field (bytes 12–15), reserved bits preserved.
    #[inline]
    pub fn error_word(&self) -> ServoErrorWord {
        ServoErrorWord::from_bits_retain(LittleEndian::read_u32(
            &self.buffer.as_ref()[field::ERRORS],
        ))
    }

    /// Return the message code field (bytes 16–19).
    #[inline]
    pub fn message_code(&self) -> i32 {
        LittleEndian::read_i32(&self.buffer.as_ref()[field::MESSAGE_CODE])
    }

    /// Return the message data field (bytes 20–23), bit for bit.
    #[inline]
    pub fn message_data(&self) -> f32 {
        LittleEndian::read_f32(&self.buffer.as_ref()[field::MESSAGE_DATA])
    }

    /// Return the message code and data fields (bytes 16–23).
    #[inline]
    pub fn message(&self) -> Message {
        Message::from_raw(self.message_code(), self.message_data())
    }

    /// Return the extra data 1–4 fields (bytes 24–39), bit for bit.
    #[inline]
    pub fn extra_data(&self) -> [f32; 4] {
        let mut out = [0.0; 4];
        LittleEndian::read_f32_into(&self.buffer.as_ref()[field::EXTRA_DATA], &mut out);
        out
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> FeedbackFrame<T> {
    /// Set the ActPos field (bytes 0–7) from the raw i64.
    #[inline]
    pub fn set_position(&mut self, value: i64) {
        LittleEndian::write_i64(&mut self.buffer.as_mut()[field::POSITION], value);
    }

    /// Set the POSW0..1 field (bytes 0–3) only.
    #[inline]
    pub fn set_incremental_position(&mut self, value: i32) {
        LittleEndian::write_i32(
            &mut self.buffer.as_mut()[field::INCREMENTAL_POSITION],
            value,
        );
    }

    /// Set the POSW2..3 field (bytes 4–7) only.
    #[inline]
    pub fn set_zero_pulse_position(&mut self, value: i32) {
        LittleEndian::write_i32(&mut self.buffer.as_mut()[field::ZERO_PULSE_POSITION], value);
    }

    /// Set the ActPos field (bytes 0–7) and the status word's Abs/Incr bit
    /// to match `position`.
    #[inline]
    pub fn set_actual_position(&mut self, position: ActualPosition) {
        self.set_position(position.raw());
        let status = self.status_word().with_encoder(position.encoder());
        self.set_status_word(status);
    }

    /// Set the SSW field (bytes 8–11).
    #[inline]
    pub fn set_status_word(&mut self, value: ServoStatusWord) {
        LittleEndian::write_u32(&mut self.buffer.as_mut()[field::STATUS], value.bits());
    }

    /// Set the SEW field (bytes 12–15).
    #[inline]
    pub fn set_error_word(&mut self, value: ServoErrorWord) {
        LittleEndian::write_u32(&mut self.buffer.as_mut()[field::ERRORS], value.bits());
    }

    /// Set the message code field (bytes 16–19).
    #[inline]
    pub fn set_message_code(&mut self, value: i32) {
        LittleEndian::write_i32(&mut self.buffer.as_mut()[field::MESSAGE_CODE], value);
    }

    /// Set the message data field (bytes 20–23), bit for bit.
    #[inline]
    pub fn set_message_data(&mut self, value: f32) {
        LittleEndian::write_f32(&mut self.buffer.as_mut()[field::MESSAGE_DATA], value);
    }

    /// Set the message code and data fields (bytes 16–23).
    #[inline]
    pub fn set_message(&mut self, message: Message) {
        self.set_message_code(message.code);
        self.set_message_data(message.data);
    }

    /// Set the extra data 1–4 fields (bytes 24–39), bit for bit.
    #[inline]
    pub fn set_extra_data(&mut self, values: [f32; 4]) {
        LittleEndian::write_f32_into(&values, &mut self.buffer.as_mut()[field::EXTRA_DATA]);
    }
}

/// A feedback frame, owned (docs/servo.md#feedback; the interface manual).
///
/// `PartialEq` compares the floats by value (NaN ≠ NaN, 0.0 == -0.0); to
/// test that two values carry the same bits compare
/// [`to_bytes`](Self::to_bytes).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Feedback {
    /// ActPos, the raw actual position (bytes 0–7); read it with
    /// [`Feedback::actual_position`].
    pub position: i64,
    /// SSW, the servo status word (bytes 8–11).
    pub status: ServoStatusWord,
    /// SEW, the servo error word (bytes 12–15).
    pub errors: ServoErrorWord,
    /// Message code and data (bytes 16–23).
    pub message: Message,
    /// Extra data 1–4 (bytes 24–39), meaning not specified.
    pub extra_data: [f32; 4],
}

impl Feedback {
    /// Return the actual position read as the status word's Abs/Incr bit says.
    #[inline]
    #[must_use]
    pub const fn actual_position(&self) -> ActualPosition {
        ActualPosition::from_raw(self.position, self.status.encoder())
    }

    /// Set the raw position and the status word's Abs/Incr bit from `position`.
    #[inline]
    pub fn set_actual_position(&mut self, position: ActualPosition) {
        self.position = position.raw();
        self.status = self.status.with_encoder(position.encoder());
    }

    /// Decode the 40 bytes of a feedback frame.
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; FEEDBACK_LEN]) -> Self {
        Self::parse_frame(&FeedbackFrame::new_unchecked(bytes))
    }

    /// Encode the feedback into its 40 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; FEEDBACK_LEN] {
        let mut bytes = [0; FEEDBACK_LEN];
        self.emit(&mut FeedbackFrame::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode a feedback frame from the start of `data`; fewer than 40 bytes
    /// is a [`LenError`].
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        Ok(Self::parse_frame(&FeedbackFrame::new_checked(data)?))
    }

    /// Read the owned value out of a view.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &FeedbackFrame<T>) -> Self {
        Feedback {
            position: frame.position(),
            status: frame.status_word(),
            errors: frame.error_word(),
            message: frame.message(),
            extra_data: frame.extra_data(),
        }
    }

    /// Write every field into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut FeedbackFrame<T>) {
        frame.set_position(self.position);
        frame.set_status_word(self.status);
        frame.set_error_word(self.errors);
        frame.set_message(self.message);
        frame.set_extra_data(self.extra_data);
    }

    /// Return the feedback laid out for people, one field per line
    /// ([`FeedbackDetails`]): the text `motionwire servo feedback` prints
    /// (docs/servo.md#cli-feedback).
    #[inline]
    #[must_use]
    pub const fn details(&self) -> FeedbackDetails {
        FeedbackDetails(*self)
    }
}

/// A [`Feedback`] laid out for people, one field per line, as `motionwire
/// servo feedback HEX` prints it (docs/servo.md#cli-feedback): the actual
/// position in the encoder's layout (docs/servo.md#feedback), the status word
/// in hex with the names of its set flags and the active parameter table
/// (docs/servo.md#ssw), the error word in hex and one line per fault with its
/// bit, E-code, name and meaning (docs/servo.md#sew), the message with its
/// unit and code (docs/servo.md#feedback), and the four extra floats. Made by
/// [`Feedback::details`]; its [`Display`](fmt::Display) writes the lines
/// without a final newline.
///
/// A separate type because the lines are a view for a terminal, not the
/// one way to print a feedback frame.
///
/// ```
/// use motionwire_codec::servo::{
///     ActualPosition, ECode, Feedback, Message, MessageCode, ServoErrorWord, ServoStatusWord,
/// };
///
/// let mut feedback = Feedback {
///     position: 0,
///     status: ServoStatusWord::SERVO_EN | ServoStatusWord::SERVO_RDY,
///     errors: ServoErrorWord::from_e_code(ECode::E09).summarized(),
///     message: Message::new(MessageCode::MotorSpeed, 1500.0),
///     extra_data: [0.0, 0.0, 1.0, -2.5],
/// };
/// feedback.set_actual_position(ActualPosition::Incremental {
///     position: 123_456,
///     zero_pulse_position: 4_096,
/// });
/// let text = feedback.details().to_string();
/// assert_eq!(
///     text.lines().collect::<Vec<_>>(),
///     [
///         "position          123456 (incremental encoder; zero pulse at 4096)",
///         "status word       0x00000007: ServoEn ServoRDY AbsIncr",
///         "  parameter table 1",
///         "error word        0x00080001",
///         "  bit  0     ServoErrors: summary: some drive error is present",
///         "  bit 19 E09 FollowerErr: speed following error",
///         "message           motor_speed = 1500 rpm (code 0)",
///         "extra data        0 0 1 -2.5",
///     ]
/// );
/// assert!(!text.ends_with('\n'));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedbackDetails(Feedback);

impl FeedbackDetails {
    /// Return the feedback these lines describe.
    #[inline]
    #[must_use]
    pub const fn feedback(&self) -> Feedback {
        self.0
    }
}

impl fmt::Display for FeedbackDetails {
    /// Write the feedback's lines (docs/servo.md#cli-feedback), without a final
    /// newline.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let fb = &self.0;
        match fb.actual_position() {
            ActualPosition::Absolute(p) => writeln!(f, "position          {p} (absolute encoder)")?,
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => writeln!(
                f,
                "position          {position} (incremental encoder; zero pulse at {zero_pulse_position})"
            )?,
        }
        write!(f, "status word       0x{:08X}:", fb.status.bits())?;
        for name in fb.status.flag_names() {
            write!(f, " {name}")?;
        }
        f.write_str("\n")?;
        writeln!(f, "  parameter table {}", fb.status.parameter_table().get())?;
        writeln!(f, "error word        0x{:08X}", fb.errors.bits())?;
        for fault in fb.errors.faults() {
            match fault.e_code() {
                Some(code) => writeln!(
                    f,
                    "  bit {:>2} {code} {}: {}",
                    fault.bit(),
                    fault.name(),
                    fault.description()
                )?,
                None => writeln!(
                    f,
                    "  bit {:>2}     {}: {}",
                    fault.bit(),
                    fault.name(),
                    fault.description()
                )?,
            }
        }
        let kind = fb.message.kind();
        writeln!(
            f,
            "message           {} = {} {} (code {})",
            kind.name(),
            fb.message.data,
            kind.unit().unwrap_or(""),
            fb.message.code
        )?;
        let [e1, e2, e3, e4] = fb.extra_data;
        write!(f, "extra data        {e1} {e2} {e3} {e4}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::{ECode, MessageCode, ServoFault};

    /// An incremental axis, enabled and ready, table 3, that found its zero
    /// pulse: position 100_000 (POSW0..1), zero pulse at -4_096 (POSW2..3);
    /// SEW: summary + BVErr + reserved bit 30; message: bus voltage 560.0 V;
    /// extra data 1.0, -2.5, NaN (payload 0x7FC0_0ABC), 0.0.
    #[rustfmt::skip]
    static FRAME_BYTES: [u8; 40] = [
        0xA0, 0x86, 0x01, 0x00,  0x00, 0xF0, 0xFF, 0xFF, // ActPos
        0x8F, 0x02, 0x00, 0x00,                          // SSW 0x0000_028F
        0x21, 0x00, 0x00, 0x40,                          // SEW 0x4000_0021
        0x03, 0x00, 0x00, 0x00,                          // message code 3
        0x00, 0x00, 0x0C, 0x44,                          // message data 560.0
        0x00, 0x00, 0x80, 0x3F,                          // extra data 1: 1.0
        0x00, 0x00, 0x20, 0xC0,                          // extra data 2: -2.5
        0xBC, 0x0A, 0xC0, 0x7F,                          // extra data 3: NaN
        0x00, 0x00, 0x00, 0x00,                          // extra data 4: 0.0
    ];

    #[test]
    fn deconstruct() {
        let frame = FeedbackFrame::new_checked(&FRAME_BYTES[..]).unwrap();
        assert_eq!(frame.incremental_position(), 100_000);
        assert_eq!(frame.zero_pulse_position(), -4_096);
        assert_eq!(frame.position(), (-4_096i64 << 32) | 100_000);
        assert_eq!(
            frame.actual_position(),
            ActualPosition::Incremental {
                position: 100_000,
                zero_pulse_position: -4_096
            }
        );
        let ssw = frame.status_word();
        assert_eq!(
            ssw.flag_names().collect::<Vec<_>>(),
            [
                "ServoEn",
                "ServoRDY",
                "AbsIncr",
                "ZPulseAck",
                "PulseEnabled"
            ]
        );
        assert_eq!(ssw.parameter_table().get(), 3);
        let sew = frame.error_word();
        assert_eq!(
            sew.faults().collect::<Vec<_>>(),
            [ServoFault::ServoErrors, ServoFault::BvErr]
        );
        assert_eq!(sew.bits(), 0x4000_0021);
        assert_eq!(ServoFault::BvErr.e_code(), Some(ECode::E05));
        assert_eq!(frame.message_code(), 3);
        assert_eq!(frame.message_data(), 560.0);
        assert_eq!(frame.message().kind(), MessageCode::BusVoltage);
        let extra = frame.extra_data();
        assert_eq!(extra[0], 1.0);
        assert_eq!(extra[1], -2.5);
        assert_eq!(extra[2].to_bits(), 0x7FC0_0ABC);
        assert_eq!(extra[3].to_bits(), 0);
    }

    fn fixture() -> Feedback {
        Feedback {
            position: (-4_096i64 << 32) | 100_000,
            status: ServoStatusWord::from_bits_retain(0x028F),
            errors: ServoErrorWord::SERVO_ERRORS
                | ServoErrorWord::BV_ERR
                | ServoErrorWord::from_bits_retain(1 << 30),
            message: Message::new(MessageCode::BusVoltage, 560.0),
            extra_data: [1.0, -2.5, f32::from_bits(0x7FC0_0ABC), 0.0],
        }
    }

    #[test]
    fn construct() {
        let mut bytes = [0xA5u8; 40];
        let mut frame = FeedbackFrame::new_unchecked(&mut bytes[..]);
        frame.set_status_word(ServoStatusWord::from_bits_retain(0x028F));
        frame.set_incremental_position(100_000);
        frame.set_zero_pulse_position(-4_096);
        frame.set_error_word(ServoErrorWord::from_bits_retain(0x4000_0021));
        frame.set_message_code(3);
        frame.set_message_data(560.0);
        frame.set_extra_data([1.0, -2.5, f32::from_bits(0x7FC0_0ABC), 0.0]);
        assert_eq!(bytes, FRAME_BYTES);
    }

    #[test]
    fn parse_and_emit() {
        let feedback = Feedback::parse(&FRAME_BYTES).unwrap();
        assert_eq!(feedback.to_bytes(), FRAME_BYTES);
        assert_eq!(fixture().to_bytes(), FRAME_BYTES);
        assert_eq!(Feedback::from_bytes(&FRAME_BYTES).to_bytes(), FRAME_BYTES);
        let mut bytes = [0u8; 40];
        feedback.emit(&mut FeedbackFrame::new_unchecked(&mut bytes[..]));
        assert_eq!(bytes, FRAME_BYTES);
    }

    /// docs/servo.md#feedback: Abs/Incr = 0 means the whole 64 bits are the
    /// position.
    #[test]
    fn absolute_position_is_64_bit() {
        let mut bytes = FRAME_BYTES;
        bytes[8] &= !0x04; // Abs/Incr = 0
        let frame = FeedbackFrame::new_checked(&bytes[..]).unwrap();
        assert_eq!(
            frame.actual_position(),
            ActualPosition::Absolute((-4_096i64 << 32) | 100_000)
        );
        assert_eq!(
            Feedback::from_bytes(&bytes).actual_position(),
            frame.actual_position()
        );
    }

    #[test]
    fn set_actual_position_sets_the_encoder_bit() {
        let mut feedback = fixture();
        feedback.set_actual_position(ActualPosition::Absolute(-1));
        assert_eq!(feedback.position, -1);
        assert!(!feedback.status.contains(ServoStatusWord::ABS_INCR));
        let incremental = ActualPosition::Incremental {
            position: -1,
            zero_pulse_position: 7,
        };
        feedback.set_actual_position(incremental);
        assert_eq!(feedback.position, 0x0000_0007_FFFF_FFFF);
        assert_eq!(feedback.actual_position(), incremental);

        let mut bytes = [0u8; 40];
        let mut frame = FeedbackFrame::new_unchecked(&mut bytes[..]);
        frame.set_actual_position(incremental);
        assert_eq!(frame.actual_position(), incremental);
        assert_eq!(bytes[..8], [0xFF, 0xFF, 0xFF, 0xFF, 7, 0, 0, 0]);
        assert_eq!(bytes[8], 0x04);
    }

    #[test]
    fn actual_position_raw_round_trip() {
        for raw in [0i64, -1, i64::MIN, i64::MAX, 0x1234_5678_9ABC_DEF0] {
            for encoder in [EncoderKind::Absolute, EncoderKind::Incremental] {
                let position = ActualPosition::from_raw(raw, encoder);
                assert_eq!(position.raw(), raw);
                assert_eq!(position.encoder(), encoder);
            }
        }
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        for len in 0..FEEDBACK_LEN {
            let expected = LenError {
                what: What::ServoFeedbackFrame,
                expected: 40,
                found: len,
            };
            assert_eq!(
                Feedback::parse(&FRAME_BYTES[..len]).map(|f| f.to_bytes()),
                Err(expected)
            );
            assert_eq!(
                FeedbackFrame::new_checked(&FRAME_BYTES[..len]),
                Err(expected)
            );
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::{actual_position, feedback};

    proptest! {
        #[test]
        fn bytes_owned_bytes(bytes in any::<[u8; FEEDBACK_LEN]>()) {
            prop_assert_eq!(Feedback::from_bytes(&bytes).to_bytes(), bytes);
        }

        /// Floats are compared through their bytes, so NaN payloads count.
        #[test]
        fn owned_bytes_owned(value in feedback()) {
            let back = Feedback::from_bytes(&value.to_bytes());
            prop_assert_eq!(back.position, value.position);
            prop_assert_eq!(back.status, value.status);
            prop_assert_eq!(back.errors, value.errors);
            prop_assert_eq!(back.message.code, value.message.code);
            prop_assert_eq!(back.message.data.to_bits(), value.message.data.to_bits());
            prop_assert_eq!(back.extra_data.map(f32::to_bits), value.extra_data.map(f32::to_bits));
            prop_assert_eq!(back.to_bytes(), value.to_bytes());
        }

        #[test]
        fn view_and_owned_agree(bytes in any::<[u8; FEEDBACK_LEN]>()) {
            let frame = FeedbackFrame::new_checked(&bytes[..]).unwrap();
            let owned = Feedback::parse_frame(&frame);
            prop_assert_eq!(frame.position(), owned.position);
            prop_assert_eq!(frame.actual_position(), owned.actual_position());
            prop_assert_eq!(frame.status_word(), owned.status);
            prop_assert_eq!(frame.error_word(), owned.errors);
            prop_assert_eq!(frame.message_code(), owned.message.code);
            prop_assert_eq!(frame.message_data().to_bits(), owned.message.data.to_bits());
            prop_assert_eq!(frame.message().kind(), owned.message.kind());
            prop_assert_eq!(
                frame.extra_data().map(f32::to_bits),
                owned.extra_data.map(f32::to_bits)
            );
            // The two halves of ActPos are the incremental reading.
            let raw = owned.position;
            prop_assert_eq!(i64::from(frame.incremental_position()) & 0xFFFF_FFFF, raw & 0xFFFF_FFFF);
            prop_assert_eq!(i64::from(frame.zero_pulse_position()), raw >> 32);
        }

        #[test]
        fn setters_match_emit(value in feedback(), fill in any::<u8>()) {
            let mut bytes = [fill; FEEDBACK_LEN];
            let mut frame = FeedbackFrame::new_unchecked(&mut bytes[..]);
            frame.set_status_word(value.status);
            frame.set_position(value.position);
            frame.set_error_word(value.errors);
            frame.set_message(value.message);
            frame.set_extra_data(value.extra_data);
            prop_assert_eq!(bytes, value.to_bytes());
        }

        #[test]
        fn actual_position_round_trips(position in actual_position()) {
            prop_assert_eq!(ActualPosition::from_raw(position.raw(), position.encoder()), position);
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..64)) {
            match Feedback::parse(&data) {
                Ok(value) => prop_assert_eq!(&value.to_bytes()[..], &data[..FEEDBACK_LEN]),
                Err(e) => prop_assert_eq!(e, LenError {
                    what: What::ServoFeedbackFrame,
                    expected: FEEDBACK_LEN,
                    found: data.len(),
                }),
            }
        }
    }
}

impl fmt::Display for ActualPosition {
    /// `absolute 123456`, `incremental 123456 (zero pulse at 4096)`.
    ///
    /// ```
    /// use motionwire_codec::servo::ActualPosition;
    ///
    /// let p = ActualPosition::Incremental { position: 10, zero_pulse_position: -4 };
    /// assert_eq!(p.to_string(), "incremental 10 (zero pulse at -4)");
    /// assert_eq!(ActualPosition::Absolute(7).to_string(), "absolute 7");
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ActualPosition::Absolute(position) => write!(f, "absolute {position}"),
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => write!(
                f,
                "incremental {position} (zero pulse at {zero_pulse_position})"
            ),
        }
    }
}
