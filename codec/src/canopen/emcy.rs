//! The EMCY frame (CiA 301 §7.2.7.3; docs/canopen.md#emcy).
//!
//! [`EmcyFrame`] is a zero-copy view over the 8 data bytes of a CAN frame;
//! [`Emcy`] is the owned, `Copy` value. Both share the offsets in `field`.
//!
//! ```
//! use motionwire_codec::canopen::{Emcy, EmcyFrame, ErrorCode, ErrorRegister};
//!
//! // Emit an EMCY into a CAN frame's data field…
//! let emcy = Emcy::new(
//!     ErrorCode::new(0x8130),
//!     ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION,
//!     [0; 5],
//! );
//! let mut data = [0u8; 8];
//! emcy.emit(&mut EmcyFrame::new_unchecked(&mut data[..]));
//! assert_eq!(data, [0x30, 0x81, 0x11, 0, 0, 0, 0, 0]);
//!
//! // …and parse it back.
//! let frame = EmcyFrame::new_checked(&data[..])?;
//! assert_eq!(frame.error_code(), ErrorCode::new(0x8130));
//! assert_eq!(Emcy::parse(&data)?, emcy);
//!
//! // A short frame is an error that says how short.
//! assert!(Emcy::parse(&data[..5]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use byteorder::{ByteOrder, LittleEndian};

use super::{ErrorCode, ErrorRegister};
use crate::error::check_len;
use crate::{LenError, Result};

mod field {
    use core::ops::Range;

    /// Bytes 0–1: emergency error code, u16.
    pub(super) const CODE: Range<usize> = 0..2;
    /// Byte 2: error register, object 1001h.
    pub(super) const REGISTER: usize = 2;
    /// Bytes 3–7: manufacturer-specific error field.
    pub(super) const MANUFACTURER: Range<usize> = 3..8;
}

/// The length of an EMCY frame's data, 8 bytes (CiA 301 §7.2.7.3.1).
pub const EMCY_LEN: usize = field::MANUFACTURER.end;

const WHAT: What = What::EmcyFrame;

/// A zero-copy view over an EMCY frame's data (docs/canopen.md#emcy).
///
/// After [`EmcyFrame::new_checked`] (or [`EmcyFrame::check_len`]) succeeds,
/// no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmcyFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> EmcyFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// shorter than [`EMCY_LEN`].
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        EmcyFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least [`EMCY_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`EMCY_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(WHAT, self.buffer.as_ref(), EMCY_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the emergency error code field (bytes 0–1).
    #[inline]
    pub fn error_code(&self) -> ErrorCode {
        ErrorCode::new(LittleEndian::read_u16(&self.buffer.as_ref()[field::CODE]))
    }

    /// Return the error register field (byte 2), reserved bit preserved.
    #[inline]
    pub fn error_register(&self) -> ErrorRegister {
        ErrorRegister::from_bits_retain(self.buffer.as_ref()[field::REGISTER])
    }

    /// Return the manufacturer-specific error field (bytes 3–7).
    #[inline]
    pub fn manufacturer(&self) -> [u8; 5] {
        let mut out = [0; 5];
        out.copy_from_slice(&self.buffer.as_ref()[field::MANUFACTURER]);
        out
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> EmcyFrame<T> {
    /// Set the emergency error code field (bytes 0–1).
    #[inline]
    pub fn set_error_code(&mut self, code: ErrorCode) {
        LittleEndian::write_u16(&mut self.buffer.as_mut()[field::CODE], code.get());
    }

    /// Set the error register field (byte 2).
    #[inline]
    pub fn set_error_register(&mut self, register: ErrorRegister) {
        self.buffer.as_mut()[field::REGISTER] = register.bits();
    }

    /// Set the manufacturer-specific error field (bytes 3–7).
    #[inline]
    pub fn set_manufacturer(&mut self, bytes: [u8; 5]) {
        self.buffer.as_mut()[field::MANUFACTURER].copy_from_slice(&bytes);
    }
}

/// An emergency message, owned (CiA 301 §7.2.7.3; docs/canopen.md#emcy).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Emcy {
    /// Emergency error code (bytes 0–1).
    pub code: ErrorCode,
    /// Error register, object 1001h (byte 2).
    pub register: ErrorRegister,
    /// Manufacturer-specific error field (bytes 3–7).
    pub manufacturer: [u8; 5],
}

impl Emcy {
    /// Return an EMCY with the given fields.
    #[inline]
    #[must_use]
    pub const fn new(code: ErrorCode, register: ErrorRegister, manufacturer: [u8; 5]) -> Self {
        Emcy {
            code,
            register,
            manufacturer,
        }
    }

    /// Return the reset EMCY a producer sends when errors are reset: code
    /// 0x0000, the remaining `register`, and a zero manufacturer area
    /// (docs/canopen.md#emcy-producer, transitions 2 and 4).
    #[inline]
    #[must_use]
    pub const fn reset(register: ErrorRegister) -> Self {
        Emcy::new(ErrorCode::NO_ERROR, register, [0; 5])
    }

    /// Return whether this EMCY reports "error reset or no error" (any
    /// 0x00xx code, docs/canopen.md#emcy-codes).
    #[inline]
    #[must_use]
    pub const fn is_reset(&self) -> bool {
        self.code.is_reset()
    }

    /// Return whether this EMCY names an error code but reports no error
    /// present: a code that is not a reset with an empty error register.
    /// Bit 0 of the error register (1001h) is set in every error
    /// situation (CiA 301 §7.5.2.2), and the EMCY state machine sends a
    /// code other than 0x0000 only with it set (docs/canopen.md#emcy-producer);
    /// a device that sends a code with the register at 0 says it is still
    /// error-free — a warning, as the Baumer EAM580 sends its sources
    /// signalled in 6505h (docs/canopen.md#profiles).
    ///
    /// ```
    /// use motionwire_codec::canopen::{Emcy, ErrorCode, ErrorRegister};
    ///
    /// let battery = Emcy::new(ErrorCode::new(0xFF00), ErrorRegister::empty(), [0, 0, 0x10, 0, 0]);
    /// assert!(battery.reports_no_error());
    /// let hot = Emcy::new(ErrorCode::new(0x4200), ErrorRegister::from_bits_retain(0x09), [0; 5]);
    /// assert!(!hot.reports_no_error());
    /// assert!(!Emcy::reset(ErrorRegister::empty()).reports_no_error());
    /// ```
    #[inline]
    #[must_use]
    pub const fn reports_no_error(&self) -> bool {
        !self.is_reset() && self.register.is_empty()
    }

    /// Decode the 8 bytes of an EMCY.
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; EMCY_LEN]) -> Self {
        Self::parse_frame(&EmcyFrame::new_unchecked(bytes))
    }

    /// Encode the EMCY into its 8 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; EMCY_LEN] {
        let mut bytes = [0; EMCY_LEN];
        self.emit(&mut EmcyFrame::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode an EMCY from a CAN frame's data; fewer than 8 bytes is a
    /// [`LenError`] (docs/canopen.md#emcy: a decoder does not guess).
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        // Through the fixed-size array rather than the view over the slice:
        // the compiler then keeps the eight bytes in registers instead of
        // storing the value and reading its manufacturer field back from
        // the stack (benches/decode.rs, `emcy8/owned` against `emcy8/copy`).
        match data.first_chunk::<EMCY_LEN>() {
            Some(bytes) => Ok(Self::from_bytes(bytes)),
            None => Err(LenError {
                what: WHAT,
                expected: EMCY_LEN,
                found: data.len(),
            }),
        }
    }

    /// Read the owned value out of a view.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &EmcyFrame<T>) -> Self {
        Emcy {
            code: frame.error_code(),
            register: frame.error_register(),
            manufacturer: frame.manufacturer(),
        }
    }

    /// Write every field into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut EmcyFrame<T>) {
        frame.set_error_code(self.code);
        frame.set_error_register(self.register);
        frame.set_manufacturer(self.manufacturer);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An AKD EMCY (docs/canopen.md#akd): code 0x8130, register 0x11, axis 1.
    static FRAME_BYTES: [u8; 8] = [0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00];

    #[test]
    fn deconstruct() {
        let frame = EmcyFrame::new_checked(&FRAME_BYTES[..]).unwrap();
        assert_eq!(frame.error_code(), ErrorCode::new(0x8130));
        assert_eq!(
            frame.error_register(),
            ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION
        );
        assert_eq!(frame.manufacturer(), [1, 0, 0, 0, 0]);
    }

    #[test]
    fn construct() {
        let mut bytes = [0xA5u8; 8];
        let mut frame = EmcyFrame::new_unchecked(&mut bytes[..]);
        frame.set_error_code(ErrorCode::new(0x8130));
        frame.set_error_register(ErrorRegister::from_bits_retain(0x11));
        frame.set_manufacturer([1, 0, 0, 0, 0]);
        assert_eq!(bytes, FRAME_BYTES);
    }

    #[test]
    fn parse_and_emit() {
        let emcy = Emcy::parse(&FRAME_BYTES).unwrap();
        assert_eq!(emcy.code.get(), 0x8130);
        assert_eq!(emcy.to_bytes(), FRAME_BYTES);
        assert_eq!(Emcy::from_bytes(&FRAME_BYTES), emcy);
    }

    #[test]
    fn reserved_register_bit_survives() {
        let mut bytes = FRAME_BYTES;
        bytes[2] = 0xFF;
        assert_eq!(Emcy::from_bytes(&bytes).to_bytes(), bytes);
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        for len in 0..EMCY_LEN {
            let expected = LenError {
                what: What::EmcyFrame,
                expected: 8,
                found: len,
            };
            assert_eq!(Emcy::parse(&FRAME_BYTES[..len]), Err(expected));
            assert_eq!(EmcyFrame::new_checked(&FRAME_BYTES[..len]), Err(expected));
        }
    }

    #[test]
    fn reset() {
        let emcy = Emcy::reset(ErrorRegister::empty());
        assert!(emcy.is_reset());
        assert_eq!(emcy.to_bytes(), [0; 8]);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::canopen::emcy;

    proptest! {
        #[test]
        fn bytes_owned_bytes(bytes in any::<[u8; 8]>()) {
            prop_assert_eq!(Emcy::from_bytes(&bytes).to_bytes(), bytes);
        }

        #[test]
        fn owned_bytes_owned(value in emcy()) {
            prop_assert_eq!(Emcy::from_bytes(&value.to_bytes()), value);
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..16)) {
            match Emcy::parse(&data) {
                Ok(value) => prop_assert_eq!(&value.to_bytes()[..], &data[..8]),
                Err(e) => prop_assert_eq!(e, LenError { what: What::EmcyFrame, expected: 8, found: data.len() }),
            }
        }
    }
}

impl core::fmt::Display for Emcy {
    /// The EMCY in words (docs/canopen.md#emcy, docs/canopen.md#emcy-codes):
    /// code, description, register and manufacturer bytes.
    ///
    /// ```
    /// use motionwire_codec::canopen::Emcy;
    ///
    /// let emcy = Emcy::from_bytes(&[0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0]);
    /// assert_eq!(
    ///     emcy.to_string(),
    ///     "EMCY 0x8130 Life guard error or heartbeat error, register 0x11 [generic|communication], manufacturer 0100000000"
    /// );
    /// ```
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "EMCY {} {}, register {}, manufacturer ",
            self.code,
            self.code.description(),
            self.register
        )?;
        for byte in self.manufacturer {
            write!(f, "{byte:02x}")?;
        }
        Ok(())
    }
}
