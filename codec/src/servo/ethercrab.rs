//! The servo frames as process data of the ethercrab EtherCAT master
//! (docs/servo.md#ethercrab; feature `ethercrab`).
//!
//! [`Command`] and [`Feedback`] implement ethercrab-wire's
//! [`EtherCrabWireRead`], [`EtherCrabWireWrite`], [`EtherCrabWireSized`] and
//! [`EtherCrabWireWriteSized`] with `PACKED_LEN` 10 and 40: the bytes are
//! exactly those of [`Command::to_bytes`] / [`Feedback::to_bytes`], and
//! reading is [`Command::parse`] / [`Feedback::parse`] (docs/servo.md#command,
//! docs/servo.md#feedback). A program on the master reads a drive's input
//! image straight into a [`Feedback`] and packs a [`Command`] into its output
//! image.
//!
//! A slice shorter than the frame is [`WireError::ReadBufferTooShort`] or
//! [`WireError::WriteBufferTooShort`], never a panic; longer slices are read
//! and written from their start. Only
//! [`pack_to_slice_unchecked`](EtherCrabWireWrite::pack_to_slice_unchecked)
//! panics on a short buffer, because ethercrab-wire's trait requires it to;
//! ethercrab calls it after checking the length itself.
//!
//! ethercrab-wire 0.3 needs Rust 1.79, below this crate's 1.81: the feature
//! keeps the crate's MSRV, and it is `no_std`.
//!
//! ```
//! use ethercrab_wire::{EtherCrabWireRead, EtherCrabWireSized, EtherCrabWireWrite, WireError};
//! use motionwire_codec::servo::{Command, Feedback, ServoControlWord, ServoEnable};
//!
//! // The drive's 10 output bytes and 40 input bytes in the process image.
//! let mut outputs = [0u8; 10];
//! let inputs = [0u8; 40];
//!
//! let command = Command::new(600, ServoControlWord::NORMAL.with_servo_enable(ServoEnable::ARM), 0);
//! command.pack_to_slice(&mut outputs)?;
//! assert_eq!(outputs, command.to_bytes());
//! let feedback = Feedback::unpack_from_slice(&inputs)?;
//! assert_eq!(feedback.to_bytes(), inputs);
//!
//! assert_eq!(<Command as EtherCrabWireSized>::PACKED_LEN, 10);
//! assert_eq!(<Feedback as EtherCrabWireSized>::PACKED_LEN, 40);
//! assert_eq!(Feedback::unpack_from_slice(&inputs[..39]), Err(WireError::ReadBufferTooShort));
//! assert_eq!(command.pack_to_slice(&mut [0u8; 9]), Err(WireError::WriteBufferTooShort));
//! # Ok::<(), WireError>(())
//! ```

use ethercrab_wire::{
    EtherCrabWireRead, EtherCrabWireSized, EtherCrabWireWrite, EtherCrabWireWriteSized, WireError,
};

use super::{Command, Feedback, COMMAND_LEN, FEEDBACK_LEN};

/// Implement the ethercrab-wire traits for a frame type with
/// `from_bytes(&[u8; N])` and `to_bytes() -> [u8; N]`.
macro_rules! process_data {
    ($frame:ty, $len:expr, $docs:literal) => {
        #[doc = concat!("The frame's ", stringify!($len), " bytes (", $docs, ", docs/servo.md#ethercrab).")]
        impl EtherCrabWireSized for $frame {
            const PACKED_LEN: usize = $len;

            type Buffer = [u8; $len];

            fn buffer() -> Self::Buffer {
                [0; $len]
            }
        }

        #[doc = concat!("Read the frame from the start of a slice (", $docs, ", docs/servo.md#ethercrab).")]
        impl EtherCrabWireRead for $frame {
            /// Decode the frame from the start of `buf`, as `parse` does; a
            /// shorter slice is [`WireError::ReadBufferTooShort`].
            fn unpack_from_slice(buf: &[u8]) -> Result<Self, WireError> {
                buf.first_chunk::<{ $len }>()
                    .map(<$frame>::from_bytes)
                    .ok_or(WireError::ReadBufferTooShort)
            }
        }

        #[doc = concat!("Write the frame into the start of a slice (", $docs, ", docs/servo.md#ethercrab).")]
        impl EtherCrabWireWrite for $frame {
            /// Encode the frame into the start of `buf` and return the bytes
            /// written; a shorter slice is [`WireError::WriteBufferTooShort`]
            /// and is left unchanged.
            fn pack_to_slice<'buf>(&self, buf: &'buf mut [u8]) -> Result<&'buf [u8], WireError> {
                let out = buf
                    .first_chunk_mut::<{ $len }>()
                    .ok_or(WireError::WriteBufferTooShort)?;
                *out = self.to_bytes();
                Ok(out)
            }

            /// Encode the frame into the start of `buf` and return the bytes
            /// written.
            ///
            /// # Panics
            ///
            /// When `buf` is shorter than the frame, as ethercrab-wire's
            /// trait requires; use [`pack_to_slice`](Self::pack_to_slice)
            /// for an error instead.
            fn pack_to_slice_unchecked<'buf>(&self, buf: &'buf mut [u8]) -> &'buf [u8] {
                let out = &mut buf[..$len];
                out.copy_from_slice(&self.to_bytes());
                out
            }

            /// Return the frame's length.
            fn packed_len(&self) -> usize {
                $len
            }
        }

        #[doc = concat!("The frame as a fixed array (", $docs, ", docs/servo.md#ethercrab).")]
        impl EtherCrabWireWriteSized for $frame {
            /// Return the frame's bytes, as `to_bytes` does.
            fn pack(&self) -> Self::Buffer {
                self.to_bytes()
            }
        }
    };
}

process_data!(Command, COMMAND_LEN, "docs/servo.md#command");
process_data!(Feedback, FEEDBACK_LEN, "docs/servo.md#feedback");

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::{command, feedback};

    #[test]
    fn packed_lengths() {
        assert_eq!(<Command as EtherCrabWireSized>::PACKED_LEN, 10);
        assert_eq!(<Feedback as EtherCrabWireSized>::PACKED_LEN, 40);
        assert_eq!(Command::buffer(), [0; 10]);
        assert_eq!(Feedback::buffer(), [0; 40]);
    }

    /// Every short slice is the exact error, for reading and writing, and a
    /// short write buffer is left unchanged.
    #[test]
    fn every_short_length_is_an_error() {
        let bytes = [0xA5u8; 64];
        for len in 0..COMMAND_LEN {
            assert_eq!(
                Command::unpack_from_slice(&bytes[..len]),
                Err(WireError::ReadBufferTooShort)
            );
            let mut out = [0x11u8; COMMAND_LEN];
            let command = Command::from_bytes(&[0x5A; COMMAND_LEN]);
            assert_eq!(
                command.pack_to_slice(&mut out[..len]),
                Err(WireError::WriteBufferTooShort)
            );
            assert_eq!(out, [0x11; COMMAND_LEN]);
        }
        for len in 0..FEEDBACK_LEN {
            assert_eq!(
                Feedback::unpack_from_slice(&bytes[..len]).map(|f| f.to_bytes()),
                Err(WireError::ReadBufferTooShort)
            );
            let mut out = [0x11u8; FEEDBACK_LEN];
            let feedback = Feedback::from_bytes(&[0x5A; FEEDBACK_LEN]);
            assert_eq!(
                feedback.pack_to_slice(&mut out[..len]),
                Err(WireError::WriteBufferTooShort)
            );
            assert_eq!(out, [0x11; FEEDBACK_LEN]);
        }
    }

    #[test]
    #[should_panic]
    fn pack_unchecked_panics_on_a_short_buffer_as_the_trait_requires() {
        let _ = Command::from_bytes(&[0; COMMAND_LEN]).pack_to_slice_unchecked(&mut [0; 9]);
    }

    proptest! {
        /// Through the traits and back, byte for byte, and the same bytes
        /// as the crate's own `to_bytes`.
        #[test]
        fn command_round_trip(command in command(), tail in proptest::collection::vec(any::<u8>(), 0..8)) {
            let mut buf = vec![0xEEu8; COMMAND_LEN];
            buf.extend_from_slice(&tail);
            let written = command.pack_to_slice(&mut buf).unwrap().to_vec();
            prop_assert_eq!(&written, &command.to_bytes());
            prop_assert_eq!(&buf[COMMAND_LEN..], &tail[..], "bytes after the frame untouched");
            prop_assert_eq!(command.pack(), command.to_bytes());
            prop_assert_eq!(command.packed_len(), COMMAND_LEN);
            let mut unchecked = [0u8; COMMAND_LEN];
            prop_assert_eq!(command.pack_to_slice_unchecked(&mut unchecked), &command.to_bytes()[..]);
            prop_assert_eq!(Command::unpack_from_slice(&buf).unwrap(), command);
        }

        #[test]
        fn feedback_round_trip(feedback in feedback(), tail in proptest::collection::vec(any::<u8>(), 0..8)) {
            let mut buf = vec![0xEEu8; FEEDBACK_LEN];
            buf.extend_from_slice(&tail);
            let written = feedback.pack_to_slice(&mut buf).unwrap().to_vec();
            prop_assert_eq!(&written, &feedback.to_bytes());
            prop_assert_eq!(&buf[FEEDBACK_LEN..], &tail[..]);
            prop_assert_eq!(feedback.pack(), feedback.to_bytes());
            prop_assert_eq!(feedback.packed_len(), FEEDBACK_LEN);
            let mut unchecked = [0u8; FEEDBACK_LEN];
            prop_assert_eq!(feedback.pack_to_slice_unchecked(&mut unchecked), &feedback.to_bytes()[..]);
            // Floats may be NaN: compare the bytes.
            prop_assert_eq!(Feedback::unpack_from_slice(&buf).unwrap().to_bytes(), feedback.to_bytes());
        }

        /// On any bytes at all, reading through the trait agrees with
        /// `parse`: the same value, or an error exactly when `parse` fails.
        #[test]
        fn reading_agrees_with_parse(bytes in proptest::collection::vec(any::<u8>(), 0..64)) {
            prop_assert_eq!(Command::unpack_from_slice(&bytes).ok(), Command::parse(&bytes).ok());
            prop_assert_eq!(
                Feedback::unpack_from_slice(&bytes).ok().map(|f| f.to_bytes()),
                Feedback::parse(&bytes).ok().map(|f| f.to_bytes())
            );
        }
    }
}
