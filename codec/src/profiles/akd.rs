//! Kollmorgen AKD: the manufacturer-specific field of its EMCY (the AKD
//! CANopen manual, "Composition of the Emergency Object";
//! docs/canopen.md#akd).
//!
//! The AKD fills bytes 3–7 of every EMCY (the 5-byte manufacturer field,
//! [`Emcy::manufacturer`]) like this:
//!
//! | EMCY byte | field byte | bits | content |
//! |---|---|---|---|
//! | 3 | 0 | 0–3 | axis id ([`AxisId`]: 1 = axis 1, 0 = not given) |
//! | 3 | 0 | 4–7 | feedback id ([`FeedbackId`]: 1..=5 = FB1..FB5, 0 = none) |
//! | 4–7 | 1–4 | — | reserved, kept as sent |
//!
//! A reset EMCY (code 0x0000) still carries the axis id and feedback id,
//! with the register of the errors that remain (docs/canopen.md#akd).
//!
//! [`AkdManufacturerField`] is a zero-copy view over the 5 bytes that never
//! fails to read them, not even a feedback nibble of 6..=15;
//! [`AkdManufacturer`] is the owned, typed value, and [`AkdEmcy`] an EMCY
//! whose manufacturer field is typed.
//!
//! ```
//! use motionwire_codec::canopen::{Emcy, ErrorCode, ErrorRegister};
//! use motionwire_codec::profiles::akd::{AkdEmcy, AxisId, FeedbackId};
//!
//! // A feedback fault on axis 1, feedback 2…
//! let axis = AxisId::try_new(1)?;
//! let fault = AkdEmcy::fault(ErrorCode::new(0x7306), ErrorRegister::GENERIC, axis, FeedbackId::Fb2);
//! assert_eq!(fault.to_bytes(), [0x06, 0x73, 0x01, 0x21, 0, 0, 0, 0]);
//!
//! // …and the reset EMCY that still names the axis.
//! let reset = AkdEmcy::reset(ErrorRegister::empty(), axis, FeedbackId::Fb2);
//! assert_eq!(reset.to_bytes(), [0x00, 0x00, 0x00, 0x21, 0, 0, 0, 0]);
//!
//! // Decoding an EMCY gives the fields back.
//! let emcy = Emcy::parse(&[0x06, 0x73, 0x01, 0x21, 0, 0, 0, 0])?;
//! let akd = AkdEmcy::from_emcy(&emcy);
//! assert_eq!(akd, fault);
//! assert_eq!(akd.manufacturer.feedback.number(), Some(2));
//!
//! // A feedback nibble of 6..=15 is kept as unknown; the code, register
//! // and axis are not lost.
//! let odd = AkdEmcy::from_bytes(&[0x06, 0x73, 0x01, 0x71, 0, 0, 0, 0]);
//! assert_eq!((odd.code, odd.manufacturer.axis), (fault.code, axis));
//! assert_eq!(odd.manufacturer.feedback.get(), 7);
//! assert!(!odd.manufacturer.feedback.is_defined());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use crate::canopen::{Emcy, EmcyFrame, ErrorCode, ErrorRegister, EMCY_LEN};
use crate::error::check_len;
use crate::{FieldError, LenError, RangeError, Result, ValueError};

mod field {
    use core::ops::Range;

    /// Field byte 0 (EMCY byte 3): axis id in bits 0–3, feedback id in bits 4–7.
    pub(super) const AXIS_FEEDBACK: usize = 0;
    /// Field bytes 1–4 (EMCY bytes 4–7): reserved.
    pub(super) const RESERVED: Range<usize> = 1..5;

    /// The bits of the axis id in [`AXIS_FEEDBACK`].
    pub(super) const AXIS_MASK: u8 = 0x0F;
    /// The position of the feedback id in [`AXIS_FEEDBACK`].
    pub(super) const FEEDBACK_SHIFT: u32 = 4;
}

/// The length of the AKD's manufacturer field, 5 bytes (EMCY bytes 3–7;
/// the AKD CANopen manual; docs/canopen.md#akd).
pub const AKD_MANUFACTURER_LEN: usize = field::RESERVED.end;

const WHAT: What = What::AkdManufacturerField;
const AXIS_WHAT: What = What::AkdAxisId;
const FEEDBACK_WHAT: What = What::AkdFeedbackId;

/// The error of an undefined feedback nibble, 6..=15.
const fn undefined_feedback(nibble: u8) -> ValueError {
    ValueError {
        what: FEEDBACK_WHAT,
        found: nibble as u32,
        expected: "0 (none), 1..=5 (FB1..FB5)",
    }
}

/// The axis an AKD EMCY reports, bits 0–3 of EMCY byte 3: 1 = axis 1,
/// 0 = not given (the AKD CANopen manual; docs/canopen.md#akd).
///
/// ```
/// use motionwire_codec::profiles::akd::AxisId;
///
/// let axis = AxisId::new(1).unwrap();
/// assert_eq!(axis.get(), 1);
/// assert!(axis.is_given());
/// assert!(!AxisId::NOT_GIVEN.is_given());
/// assert!(AxisId::new(16).is_none());
/// ```
///
/// With the `serde` feature an axis id serializes as its number;
/// deserializing refuses any number above 15.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "u8", into = "u8")
)]
pub struct AxisId(u8);

impl AxisId {
    /// 0: the EMCY names no axis.
    pub const NOT_GIVEN: AxisId = AxisId(0);
    /// 15, the largest value the 4-bit field holds.
    pub const MAX: AxisId = AxisId(field::AXIS_MASK);

    /// Return the axis id `raw`, or `None` when it does not fit in 4 bits.
    #[inline]
    #[must_use]
    pub const fn new(raw: u8) -> Option<Self> {
        if raw <= field::AXIS_MASK {
            Some(AxisId(raw))
        } else {
            None
        }
    }

    /// Return the axis id `raw`, or a [`RangeError`] when it does
    /// not fit in 4 bits (0..=15).
    #[inline]
    pub const fn try_new(raw: u8) -> Result<Self, RangeError> {
        match Self::new(raw) {
            Some(axis) => Ok(axis),
            None => Err(RangeError {
                what: AXIS_WHAT,
                found: raw as u32,
                min: 0,
                max: field::AXIS_MASK as u32,
            }),
        }
    }

    /// Return the axis id read from EMCY byte 3 (its bits 0–3).
    #[inline]
    const fn from_byte(byte: u8) -> Self {
        AxisId(byte & field::AXIS_MASK)
    }

    /// Return the axis id as a number in 0..=15.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self.0
    }

    /// Return whether the EMCY names an axis (the id is not 0).
    #[inline]
    #[must_use]
    pub const fn is_given(self) -> bool {
        self.0 != 0
    }
}

impl TryFrom<u8> for AxisId {
    type Error = RangeError;

    fn try_from(raw: u8) -> Result<Self, RangeError> {
        Self::try_new(raw)
    }
}

impl From<AxisId> for u8 {
    fn from(axis: AxisId) -> u8 {
        axis.0
    }
}

impl fmt::Display for AxisId {
    /// Format the axis as `axis 1`, or `no axis` when it is not given.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_given() {
            write!(f, "axis {}", self.0)
        } else {
            f.write_str("no axis")
        }
    }
}

/// The feedback device of a feedback fault, bits 4–7 of EMCY byte 3
/// (the AKD CANopen manual;
/// docs/canopen.md#akd): 0 = none (not a feedback fault), 1..=5 =
/// FB1..FB5. The values 6..=15 are not defined: building one with
/// [`FeedbackId::try_new`] is a [`FieldError::InvalidValue`] that names the
/// nibble, while decoding a received EMCY keeps it as
/// [`FeedbackId::Unknown`] ([`FeedbackId::from_nibble`]), so that nothing
/// else the EMCY says is lost.
///
/// ```
/// use motionwire_codec::profiles::akd::FeedbackId;
///
/// assert_eq!(FeedbackId::try_new(2)?, FeedbackId::Fb2);
/// assert_eq!(FeedbackId::Fb2.number(), Some(2));
/// assert_eq!(FeedbackId::None.number(), None);
/// assert!(FeedbackId::try_new(6).is_err());
/// let unknown = FeedbackId::from_nibble(6);
/// assert!(matches!(unknown, FeedbackId::Unknown(_)));
/// assert_eq!((unknown.get(), unknown.number()), (6, None));
/// assert_eq!(unknown.to_string(), "unknown feedback id 6");
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum FeedbackId {
    /// 0: no feedback fault.
    #[default]
    None,
    /// 1: feedback 1.
    Fb1,
    /// 2: feedback 2.
    Fb2,
    /// 3: feedback 3.
    Fb3,
    /// 4: feedback 4.
    Fb4,
    /// 5: feedback 5.
    Fb5,
    /// 6..=15: a value the AKD CANopen manual does not define, as received.
    Unknown(UndefinedFeedbackId),
}

/// A feedback nibble the AKD CANopen manual does not define, 6..=15, kept as
/// received ([`FeedbackId::Unknown`]; docs/canopen.md#akd). Only the crate
/// makes one, so it never holds a defined value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(try_from = "u8", into = "u8"))]
pub struct UndefinedFeedbackId(u8);

impl UndefinedFeedbackId {
    /// Return the nibble, 6..=15.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self.0
    }
}

impl TryFrom<u8> for UndefinedFeedbackId {
    type Error = RangeError;

    /// Accept 6..=15 only.
    fn try_from(raw: u8) -> Result<Self, RangeError> {
        match FeedbackId::from_nibble(raw) {
            FeedbackId::Unknown(undefined) if raw <= 0x0F => Ok(undefined),
            _ => Err(RangeError {
                what: FEEDBACK_WHAT,
                found: u32::from(raw),
                min: 6,
                max: 0x0F,
            }),
        }
    }
}

impl From<UndefinedFeedbackId> for u8 {
    fn from(undefined: UndefinedFeedbackId) -> u8 {
        undefined.0
    }
}

impl FeedbackId {
    /// Every feedback id in nibble order, none first.
    pub const ALL: [FeedbackId; 6] = [
        FeedbackId::None,
        FeedbackId::Fb1,
        FeedbackId::Fb2,
        FeedbackId::Fb3,
        FeedbackId::Fb4,
        FeedbackId::Fb5,
    ];

    /// Return the feedback id whose nibble is `raw`, or `None` when `raw`
    /// is not 0..=5.
    #[inline]
    #[must_use]
    pub const fn new(raw: u8) -> Option<Self> {
        match raw {
            0 => Some(FeedbackId::None),
            1 => Some(FeedbackId::Fb1),
            2 => Some(FeedbackId::Fb2),
            3 => Some(FeedbackId::Fb3),
            4 => Some(FeedbackId::Fb4),
            5 => Some(FeedbackId::Fb5),
            _ => None,
        }
    }

    /// Return the feedback id whose nibble is `raw`: a
    /// [`FieldError::InvalidValue`] for the undefined nibbles 6..=15, a
    /// [`FieldError::OutOfRange`] for a number that is no nibble at all.
    #[inline]
    pub const fn try_new(raw: u8) -> Result<Self, FieldError> {
        match Self::new(raw) {
            Some(feedback) => Ok(feedback),
            None if raw <= 0x0F => Err(FieldError::InvalidValue(undefined_feedback(raw))),
            None => Err(FieldError::OutOfRange(RangeError {
                what: FEEDBACK_WHAT,
                found: raw as u32,
                min: 0,
                max: 0x0F,
            })),
        }
    }

    /// Return the feedback id of a received nibble (the low 4 bits of
    /// `nibble`): 0..=5 as defined, 6..=15 as [`FeedbackId::Unknown`].
    #[inline]
    #[must_use]
    pub const fn from_nibble(nibble: u8) -> Self {
        let nibble = nibble & 0x0F;
        match Self::new(nibble) {
            Some(feedback) => feedback,
            None => FeedbackId::Unknown(UndefinedFeedbackId(nibble)),
        }
    }

    /// Return the nibble, 0..=15.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        match self {
            FeedbackId::None => 0,
            FeedbackId::Fb1 => 1,
            FeedbackId::Fb2 => 2,
            FeedbackId::Fb3 => 3,
            FeedbackId::Fb4 => 4,
            FeedbackId::Fb5 => 5,
            FeedbackId::Unknown(undefined) => undefined.0,
        }
    }

    /// Return whether the nibble is one the AKD CANopen manual defines (0..=5).
    #[inline]
    #[must_use]
    pub const fn is_defined(self) -> bool {
        !matches!(self, FeedbackId::Unknown(_))
    }

    /// Return the feedback's number, 1..=5, or `None` when the EMCY is not
    /// a feedback fault or names an undefined feedback (docs/output.md#emcy,
    /// `feedback`: integer or null).
    #[inline]
    #[must_use]
    pub const fn number(self) -> Option<u8> {
        match self {
            FeedbackId::None | FeedbackId::Unknown(_) => None,
            other => Some(other.get()),
        }
    }
}

impl TryFrom<u8> for FeedbackId {
    type Error = FieldError;

    fn try_from(raw: u8) -> Result<Self, FieldError> {
        Self::try_new(raw)
    }
}

impl From<FeedbackId> for u8 {
    fn from(feedback: FeedbackId) -> u8 {
        feedback.get()
    }
}

impl fmt::Display for FeedbackId {
    /// Format the feedback as `FB2`, `none`, or `unknown feedback id 6`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.number(), self) {
            (Some(n), _) => write!(f, "FB{n}"),
            (None, FeedbackId::Unknown(undefined)) => {
                write!(f, "unknown feedback id {}", undefined.0)
            }
            (None, _) => f.write_str("none"),
        }
    }
}

/// A zero-copy view over the AKD's 5-byte manufacturer field (EMCY bytes
/// 3–7; docs/canopen.md#akd).
///
/// Reading never fails once the length is checked: the raw feedback nibble
/// is readable with [`AkdManufacturerField::feedback_nibble`] even when it
/// is 6..=15. After [`AkdManufacturerField::new_checked`] (or
/// [`AkdManufacturerField::check_len`]) succeeds, no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AkdManufacturerField<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> AkdManufacturerField<T> {
    /// Wrap a buffer without checking its length; accessors panic when it
    /// is shorter than [`AKD_MANUFACTURER_LEN`].
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        AkdManufacturerField { buffer }
    }

    /// Wrap a buffer, checking that it holds at least
    /// [`AKD_MANUFACTURER_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let field = Self::new_unchecked(buffer);
        field.check_len()?;
        Ok(field)
    }

    /// Check that the buffer holds at least [`AKD_MANUFACTURER_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(WHAT, self.buffer.as_ref(), AKD_MANUFACTURER_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the axis id field (EMCY byte 3, bits 0–3).
    #[inline]
    pub fn axis_id(&self) -> AxisId {
        AxisId::from_byte(self.buffer.as_ref()[field::AXIS_FEEDBACK])
    }

    /// Return the feedback id field as sent (EMCY byte 3, bits 4–7),
    /// 0..=15, including the undefined values 6..=15.
    #[inline]
    pub fn feedback_nibble(&self) -> u8 {
        self.buffer.as_ref()[field::AXIS_FEEDBACK] >> field::FEEDBACK_SHIFT
    }

    /// Return the feedback id field, or a [`ValueError`] naming the nibble
    /// when it is 6..=15.
    #[inline]
    pub fn feedback_id(&self) -> Result<FeedbackId, ValueError> {
        let nibble = self.feedback_nibble();
        FeedbackId::new(nibble).ok_or(undefined_feedback(nibble))
    }

    /// Return the feedback id field as received: an undefined nibble
    /// 6..=15 as [`FeedbackId::Unknown`].
    #[inline]
    pub fn feedback(&self) -> FeedbackId {
        FeedbackId::from_nibble(self.feedback_nibble())
    }

    /// Return the reserved field (EMCY bytes 4–7), as sent.
    #[inline]
    pub fn reserved(&self) -> [u8; 4] {
        let mut out = [0; 4];
        out.copy_from_slice(&self.buffer.as_ref()[field::RESERVED]);
        out
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> AkdManufacturerField<T> {
    /// Set the axis id field (EMCY byte 3, bits 0–3), keeping the feedback id.
    #[inline]
    pub fn set_axis_id(&mut self, axis: AxisId) {
        let byte = &mut self.buffer.as_mut()[field::AXIS_FEEDBACK];
        *byte = (*byte & !field::AXIS_MASK) | axis.get();
    }

    /// Set the feedback id field (EMCY byte 3, bits 4–7), keeping the axis id.
    #[inline]
    pub fn set_feedback_id(&mut self, feedback: FeedbackId) {
        let byte = &mut self.buffer.as_mut()[field::AXIS_FEEDBACK];
        *byte = (*byte & field::AXIS_MASK) | (feedback.get() << field::FEEDBACK_SHIFT);
    }

    /// Set the reserved field (EMCY bytes 4–7).
    #[inline]
    pub fn set_reserved(&mut self, bytes: [u8; 4]) {
        self.buffer.as_mut()[field::RESERVED].copy_from_slice(&bytes);
    }
}

/// The AKD's manufacturer field, owned and typed (EMCY bytes 3–7;
/// docs/canopen.md#akd).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AkdManufacturer {
    /// The axis the EMCY reports (byte 3, bits 0–3).
    pub axis: AxisId,
    /// The feedback device of a feedback fault (byte 3, bits 4–7).
    pub feedback: FeedbackId,
    /// Reserved (bytes 4–7): 0 from an AKD, kept as sent when decoding.
    pub reserved: [u8; 4],
}

impl AkdManufacturer {
    /// Return the field for `axis` and `feedback`, reserved bytes zero.
    #[inline]
    #[must_use]
    pub const fn new(axis: AxisId, feedback: FeedbackId) -> Self {
        AkdManufacturer {
            axis,
            feedback,
            reserved: [0; 4],
        }
    }

    /// Decode the 5 bytes of the field; a feedback nibble of 6..=15 is
    /// kept as [`FeedbackId::Unknown`].
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; AKD_MANUFACTURER_LEN]) -> Self {
        Self::parse_field(&AkdManufacturerField::new_unchecked(bytes))
    }

    /// Encode the field into its 5 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; AKD_MANUFACTURER_LEN] {
        let mut bytes = [0; AKD_MANUFACTURER_LEN];
        self.emit(&mut AkdManufacturerField::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode the field from a slice: fewer than 5 bytes is a
    /// [`LenError`]; a feedback nibble of 6..=15 is kept as
    /// [`FeedbackId::Unknown`].
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        Ok(Self::parse_field(&AkdManufacturerField::new_checked(data)?))
    }

    /// Read the owned value out of a view.
    #[inline]
    pub fn parse_field<T: AsRef<[u8]>>(field: &AkdManufacturerField<T>) -> Self {
        AkdManufacturer {
            axis: field.axis_id(),
            feedback: field.feedback(),
            reserved: field.reserved(),
        }
    }

    /// Write every field into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, field: &mut AkdManufacturerField<T>) {
        field.set_axis_id(self.axis);
        field.set_feedback_id(self.feedback);
        field.set_reserved(self.reserved);
    }
}

/// An EMCY from a Kollmorgen AKD: the generic code and register with a typed
/// manufacturer field (the AKD CANopen manual; docs/canopen.md#emcy,
/// docs/canopen.md#akd).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AkdEmcy {
    /// Emergency error code (bytes 0–1).
    pub code: ErrorCode,
    /// Error register, object 1001h (byte 2).
    pub register: ErrorRegister,
    /// The AKD's manufacturer field (bytes 3–7).
    pub manufacturer: AkdManufacturer,
}

impl AkdEmcy {
    /// Return the EMCY an AKD sends for an error: its `code`, the `register`
    /// of all active errors, and the `axis` and `feedback` it occurred in
    /// (the AKD CANopen manual, transitions 1 and 3). Reserved bytes are zero.
    #[inline]
    #[must_use]
    pub const fn fault(
        code: ErrorCode,
        register: ErrorRegister,
        axis: AxisId,
        feedback: FeedbackId,
    ) -> Self {
        AkdEmcy {
            code,
            register,
            manufacturer: AkdManufacturer::new(axis, feedback),
        }
    }

    /// Return the reset EMCY an AKD sends when errors are reset: code
    /// 0x0000, the `remaining` register (empty once the last error is
    /// reset), and still the `axis` and `feedback` id in byte 3
    /// (docs/canopen.md#akd).
    #[inline]
    #[must_use]
    pub const fn reset(remaining: ErrorRegister, axis: AxisId, feedback: FeedbackId) -> Self {
        Self::fault(ErrorCode::NO_ERROR, remaining, axis, feedback)
    }

    /// Return whether this EMCY reports "error reset or no error" (any
    /// 0x00xx code, docs/canopen.md#emcy-codes).
    #[inline]
    #[must_use]
    pub const fn is_reset(&self) -> bool {
        self.code.is_reset()
    }

    /// Decode an EMCY's manufacturer field the AKD way. Nothing is lost: a
    /// feedback nibble of 6..=15 is kept as [`FeedbackId::Unknown`] with the
    /// code, register and axis.
    #[inline]
    #[must_use]
    pub fn from_emcy(emcy: &Emcy) -> Self {
        AkdEmcy {
            code: emcy.code,
            register: emcy.register,
            manufacturer: AkdManufacturer::from_bytes(&emcy.manufacturer),
        }
    }

    /// Encode into a generic EMCY.
    #[inline]
    #[must_use]
    pub fn to_emcy(&self) -> Emcy {
        Emcy::new(self.code, self.register, self.manufacturer.to_bytes())
    }

    /// Decode the 8 bytes of an AKD EMCY.
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; EMCY_LEN]) -> Self {
        Self::from_emcy(&Emcy::from_bytes(bytes))
    }

    /// Encode the EMCY into its 8 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; EMCY_LEN] {
        self.to_emcy().to_bytes()
    }

    /// Decode an AKD EMCY from a CAN frame's data: fewer than 8 bytes is a
    /// [`LenError`]; a feedback nibble of 6..=15 is kept as
    /// [`FeedbackId::Unknown`].
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        Ok(Self::from_emcy(&Emcy::parse(data)?))
    }

    /// Read the owned value out of an EMCY view.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &EmcyFrame<T>) -> Self {
        Self::from_emcy(&Emcy::parse_frame(frame))
    }

    /// Write every field into an EMCY view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut EmcyFrame<T>) {
        self.to_emcy().emit(frame);
    }
}

impl From<Emcy> for AkdEmcy {
    fn from(emcy: Emcy) -> Self {
        Self::from_emcy(&emcy)
    }
}

impl From<AkdEmcy> for Emcy {
    fn from(akd: AkdEmcy) -> Emcy {
        akd.to_emcy()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AKD CANopen manual, transition 1: a feedback fault (0x7306,
    /// incremental sensor 2) on axis 1 with FB2; register: generic.
    static FAULT_BYTES: [u8; 8] = [0x06, 0x73, 0x01, 0x21, 0x00, 0x00, 0x00, 0x00];
    /// The AKD CANopen manual, transition 2: one error reset, a temperature
    /// error remains; the reset EMCY still names axis 1 and FB2.
    static RESET_BYTES: [u8; 8] = [0x00, 0x00, 0x09, 0x21, 0x00, 0x00, 0x00, 0x00];

    fn axis(raw: u8) -> AxisId {
        AxisId::new(raw).expect("a nibble")
    }

    #[test]
    fn deconstruct() {
        let field = AkdManufacturerField::new_checked(&FAULT_BYTES[3..]).unwrap();
        assert_eq!(field.axis_id(), axis(1));
        assert_eq!(field.feedback_nibble(), 2);
        assert_eq!(field.feedback_id(), Ok(FeedbackId::Fb2));
        assert_eq!(field.reserved(), [0; 4]);
    }

    #[test]
    fn construct() {
        let mut bytes = [0xA5u8; 5];
        let mut field = AkdManufacturerField::new_unchecked(&mut bytes[..]);
        field.set_axis_id(axis(1));
        field.set_feedback_id(FeedbackId::Fb2);
        field.set_reserved([0; 4]);
        assert_eq!(bytes, FAULT_BYTES[3..]);
    }

    #[test]
    fn setters_keep_the_other_nibble() {
        // (byte 3 before, setter, byte 3 after)
        type Set = fn(&mut AkdManufacturerField<&mut [u8]>);
        let table: [(u8, Set, u8); 4] = [
            (0x00, |f| f.set_feedback_id(FeedbackId::Fb5), 0x50),
            (0x50, |f| f.set_axis_id(AxisId::MAX), 0x5F),
            (0x5F, |f| f.set_axis_id(AxisId::new(3).unwrap()), 0x53),
            (0x53, |f| f.set_feedback_id(FeedbackId::None), 0x03),
        ];
        for (before, set, after) in table {
            let mut bytes = [before, 0, 0, 0, 0];
            set(&mut AkdManufacturerField::new_unchecked(&mut bytes[..]));
            assert_eq!(bytes[0], after, "{before:#04x}");
        }
    }

    #[test]
    fn fault_vector() {
        let fault = AkdEmcy::fault(
            ErrorCode::new(0x7306),
            ErrorRegister::GENERIC,
            axis(1),
            FeedbackId::Fb2,
        );
        assert_eq!(fault.to_bytes(), FAULT_BYTES);
        assert_eq!(AkdEmcy::from_bytes(&FAULT_BYTES), fault);
        assert_eq!(AkdEmcy::parse(&FAULT_BYTES), Ok(fault));
        assert!(!fault.is_reset());
        let emcy = Emcy::from_bytes(&FAULT_BYTES);
        assert_eq!(AkdEmcy::from(emcy), fault);
        assert_eq!(Emcy::from(fault), emcy);
        assert_eq!(fault.code.description(), "Incremental sensor 2 fault");
    }

    #[test]
    fn reset_vector_carries_the_axis_id() {
        let reset = AkdEmcy::reset(
            ErrorRegister::GENERIC | ErrorRegister::TEMPERATURE,
            axis(1),
            FeedbackId::Fb2,
        );
        assert_eq!(reset.code, ErrorCode::NO_ERROR);
        assert!(reset.is_reset());
        assert_eq!(reset.to_bytes(), RESET_BYTES);
        assert_eq!(AkdEmcy::from_bytes(&RESET_BYTES), reset);
    }

    #[test]
    fn last_reset_is_error_free_with_the_axis_id() {
        // The AKD CANopen manual, transition 4: register 0x00, axis 1, no
        // feedback fault.
        let reset = AkdEmcy::reset(ErrorRegister::empty(), axis(1), FeedbackId::None);
        assert_eq!(reset.to_bytes(), [0, 0, 0, 0x01, 0, 0, 0, 0]);
        assert_eq!(AkdEmcy::from_bytes(&reset.to_bytes()), reset);
    }

    #[test]
    fn emit_and_parse_frame() {
        let fault = AkdEmcy::from_bytes(&FAULT_BYTES);
        let mut data = [0xFFu8; 8];
        fault.emit(&mut EmcyFrame::new_unchecked(&mut data[..]));
        assert_eq!(data, FAULT_BYTES);
        let frame = EmcyFrame::new_checked(&data[..]).unwrap();
        assert_eq!(AkdEmcy::parse_frame(&frame), fault);
    }

    #[test]
    fn reserved_bytes_survive_a_round_trip() {
        let bytes = [0x06, 0x73, 0x01, 0x21, 0xDE, 0xAD, 0xBE, 0xEF];
        let akd = AkdEmcy::from_bytes(&bytes);
        assert_eq!(akd.manufacturer.reserved, [0xDE, 0xAD, 0xBE, 0xEF]);
        assert_eq!(akd.to_bytes(), bytes);
    }

    /// Every feedback nibble: 0 none, 1..=5 FB1..FB5, 6..=15 an error that
    /// names the nibble while the raw value and the axis stay readable.
    #[test]
    fn every_feedback_nibble() {
        let table: [(u8, Option<FeedbackId>); 16] = [
            (0, Some(FeedbackId::None)),
            (1, Some(FeedbackId::Fb1)),
            (2, Some(FeedbackId::Fb2)),
            (3, Some(FeedbackId::Fb3)),
            (4, Some(FeedbackId::Fb4)),
            (5, Some(FeedbackId::Fb5)),
            (6, None),
            (7, None),
            (8, None),
            (9, None),
            (10, None),
            (11, None),
            (12, None),
            (13, None),
            (14, None),
            (15, None),
        ];
        for (nibble, expected) in table {
            let bytes = [(nibble << 4) | 0x07, 0, 0, 0, 0];
            let field = AkdManufacturerField::new_checked(&bytes[..]).unwrap();
            assert_eq!(field.feedback_nibble(), nibble);
            assert_eq!(field.axis_id(), axis(7));
            let invalid = ValueError {
                what: What::AkdFeedbackId,
                found: u32::from(nibble),
                expected: "0 (none), 1..=5 (FB1..FB5)",
            };
            assert_eq!(FeedbackId::new(nibble), expected, "{nibble}");
            assert_eq!(field.feedback_id(), expected.ok_or(invalid), "{nibble}");
            assert_eq!(
                FeedbackId::try_new(nibble),
                expected.ok_or(FieldError::InvalidValue(invalid))
            );
            // Decoding keeps every nibble: the defined ones as themselves,
            // 6..=15 as unknown, with the axis.
            let decoded = AkdManufacturer::from_bytes(&bytes);
            assert_eq!(decoded.axis, axis(7));
            assert_eq!(decoded.feedback.get(), nibble);
            assert_eq!(field.feedback(), decoded.feedback);
            match expected {
                Some(feedback) => {
                    assert_eq!(feedback.get(), nibble);
                    assert_eq!(decoded.feedback, feedback);
                }
                None => {
                    assert!(
                        matches!(decoded.feedback, FeedbackId::Unknown(u) if u.get() == nibble)
                    );
                    assert_eq!(decoded.feedback.number(), None);
                    assert_eq!(
                        UndefinedFeedbackId::try_from(nibble).map(u8::from),
                        Ok(nibble)
                    );
                }
            }
        }
    }

    #[test]
    fn feedback_numbers_and_names() {
        let table = [
            (FeedbackId::None, None, "none"),
            (FeedbackId::Fb1, Some(1), "FB1"),
            (FeedbackId::Fb2, Some(2), "FB2"),
            (FeedbackId::Fb3, Some(3), "FB3"),
            (FeedbackId::Fb4, Some(4), "FB4"),
            (FeedbackId::Fb5, Some(5), "FB5"),
        ];
        for (feedback, number, name) in table {
            assert_eq!(feedback.number(), number);
            assert_eq!(feedback.to_string(), name);
            assert_eq!(FeedbackId::try_from(u8::from(feedback)), Ok(feedback));
        }
        assert_eq!(FeedbackId::ALL.map(FeedbackId::get), [0, 1, 2, 3, 4, 5]);
        assert_eq!(
            FeedbackId::try_new(16),
            Err(FieldError::OutOfRange(RangeError {
                what: What::AkdFeedbackId,
                found: 16,
                min: 0,
                max: 15
            }))
        );
    }

    #[test]
    fn axis_ids() {
        for raw in 0..=15u8 {
            let axis = AxisId::try_new(raw).unwrap();
            assert_eq!(axis.get(), raw);
            assert_eq!(axis.is_given(), raw != 0);
            assert_eq!(AxisId::try_from(raw), Ok(axis));
            assert_eq!(u8::from(axis), raw);
        }
        for raw in 16..=255u8 {
            assert_eq!(AxisId::new(raw), None);
            assert_eq!(
                AxisId::try_new(raw),
                Err(RangeError {
                    what: What::AkdAxisId,
                    found: u32::from(raw),
                    min: 0,
                    max: 15
                })
            );
        }
        assert_eq!(axis(1).to_string(), "axis 1");
        assert_eq!(AxisId::NOT_GIVEN.to_string(), "no axis");
        assert_eq!(AxisId::default(), AxisId::NOT_GIVEN);
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        for len in 0..AKD_MANUFACTURER_LEN {
            let expected = LenError {
                what: What::AkdManufacturerField,
                expected: 5,
                found: len,
            };
            assert_eq!(
                AkdManufacturer::parse(&FAULT_BYTES[3..3 + len]),
                Err(expected)
            );
            assert_eq!(
                AkdManufacturerField::new_checked(&FAULT_BYTES[3..3 + len]),
                Err(expected)
            );
        }
        for len in 0..EMCY_LEN {
            let expected = LenError {
                what: What::EmcyFrame,
                expected: 8,
                found: len,
            };
            assert_eq!(AkdEmcy::parse(&FAULT_BYTES[..len]), Err(expected));
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::akd::{akd_emcy, akd_manufacturer};

    proptest! {
        #[test]
        fn decode_never_panics_and_valid_frames_round_trip(bytes in any::<[u8; 8]>()) {
            let nibble = bytes[3] >> 4;
            let field = AkdManufacturerField::new_checked(&bytes[3..]).unwrap();
            prop_assert_eq!(field.feedback_nibble(), nibble);
            prop_assert_eq!(field.axis_id().get(), bytes[3] & 0x0F);
            // Every EMCY decodes and encodes back to its bytes: an
            // undefined feedback nibble is kept, never dropped.
            let akd = AkdEmcy::from_bytes(&bytes);
            prop_assert_eq!(akd.to_bytes(), bytes);
            prop_assert_eq!(akd.manufacturer.feedback.is_defined(), nibble <= 5);
            prop_assert_eq!(akd.manufacturer.feedback.get(), nibble);
        }

        #[test]
        fn owned_bytes_owned(value in akd_emcy()) {
            prop_assert_eq!(AkdEmcy::from_bytes(&value.to_bytes()), value);
            prop_assert_eq!(AkdEmcy::from(value.to_emcy()), value);
        }

        #[test]
        fn manufacturer_owned_bytes_owned(value in akd_manufacturer()) {
            prop_assert_eq!(AkdManufacturer::from_bytes(&value.to_bytes()), value);
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..16)) {
            match AkdEmcy::parse(&data) {
                Ok(value) => prop_assert_eq!(&value.to_bytes()[..], &data[..8]),
                Err(e) => prop_assert_eq!(e, LenError { what: What::EmcyFrame, expected: 8, found: data.len() }),
            }
            let _ = AkdManufacturer::parse(&data);
        }
    }
}
