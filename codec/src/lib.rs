//! # motionwire-codec
//!
//! The `no_std` layer under [motionwire](https://docs.rs/motionwire): the
//! codecs and pure state machines of the diagnostic and cyclic-control
//! language of industrial motion devices — the EtherCAT servo ↔ NC cyclic
//! frames, CANopen emergency messages and error control, SDO, PDO and the
//! CiA 402 drive state, the CiA 405 `RECV_EMCY` consumer, and device
//! profiles (Kollmorgen AKD, Baumer EAM580).
//!
//! It allocates nothing, contains no `unsafe` code and knows nothing of log
//! files, decoder sessions or reports: those are motionwire's, built on this
//! crate, which re-exports its modules at its own top level
//! (`motionwire_codec::can`, `motionwire_codec::canopen`, `motionwire_codec::servo`,
//! `motionwire_codec::profiles`). A firmware or a master that only speaks the
//! protocols can depend on this crate alone. Every decoder takes outside
//! bytes and returns a typed [`Error`] instead of panicking. The formats
//! and behaviours are described in the repository's reference, the `docs/`
//! folder; each item's documentation names the page and section that
//! covers it, as `docs/canopen.md#emcy`.
//!
//! ## Layout
//!
//! - [`can`]: the one CAN frame vocabulary every other part speaks —
//!   identifiers, [`can::CanFrame`] (data, remote, CAN FD, error frames;
//!   owned or borrowed), error-frame classes, and [`can::LogFrame`], a frame
//!   with the time and interface a log records (ISO 11898-1, docs/formats.md).
//! - [`canopen`]: a [`can::CanFrame`] read as CANopen
//!   ([`canopen::CanOpenMessage::decode`], docs/canopen.md#identifiers);
//!   node-IDs and COB-IDs, the EMCY frame, error register and error codes with
//!   their descriptions, the EMCY producer state machine and the 1003h error
//!   history (CiA 301 §7.2.7, CiA 402, docs/canopen.md#emcy); NMT states,
//!   heartbeat, node guarding and life guarding (CiA 301 §7.2.8,
//!   docs/canopen.md#error-control); the CiA 405 `RECV_EMCY` consumer
//!   (docs/canopen.md#recv-emcy); the CiA 402 drive state machine, statusword,
//!   controlword and modes of operation (docs/canopen.md#cia402); SDO frames,
//!   the transfer tracker and the 1001h/1003h server (docs/canopen.md#sdo);
//!   PDO mappings and signals (docs/canopen.md#pdo-mappings,
//!   docs/canopen.md#signals); the names of object-dictionary entries,
//!   [`canopen::object_name`] (CiA 301, CiA 402, CiA 406,
//!   docs/canopen.md#object-names).
//! - [`profiles`]: device-specific layouts of the EMCY manufacturer field and
//!   diagnostic sources (Kollmorgen AKD, docs/canopen.md#akd; Baumer EAM580,
//!   docs/canopen.md#baumer).
//!   [`profiles::Profile`] says which one reads a node.
//! - [`servo`]: the EtherCAT servo ↔ NC cyclic frames, their control,
//!   status and error words, the enable, error-clear and zero-pulse
//!   handshakes (docs/servo.md), and a drive model to test an NC against
//!   (docs/servo.md#drive-model).
//!
//! ## Optional features
//!
//! - `serde`: `Serialize` and `Deserialize` for the owned value types (not
//!   the zero-copy views, not the state machines); checked numbers
//!   deserialize through their checks, flag words keep every bit
//!   (motionwire's crate documentation, "Optional features", has the
//!   formats).
//! - `embedded-can`: [`can::CanFrame`] implements `embedded_can::Frame`;
//!   any `embedded_can::Frame` reads as a [`canopen::CanOpenMessage`].
//! - `defmt`: `defmt::Format` on the frame vocabulary and the value types.
//! - `ethercrab`: [`servo::Command`] and [`servo::Feedback`] as process data
//!   of the ethercrab EtherCAT master (docs/servo.md#ethercrab).
//! - `proptest`: `strategies`, the proptest strategies of every type,
//!   for the property tests of crates built on this one (links `std`).
//!
//! ## Example
//!
//! A servo's answer to one NC cycle: build a [`servo::Feedback`], emit it
//! into the 40 bytes of the process image, and parse it back.
//!
//! ```
//! use motionwire_codec::servo::{
//!     ActualPosition, ECode, Feedback, Message, MessageCode, ServoErrorWord, ServoFault,
//!     ServoStatusWord, FEEDBACK_LEN,
//! };
//!
//! let mut feedback = Feedback {
//!     position: 0,
//!     status: ServoStatusWord::SERVO_EN | ServoStatusWord::PULSE_ENABLED,
//!     errors: ServoErrorWord::from_e_code(ECode::E09).summarized(),
//!     message: Message::new(MessageCode::MotorSpeed, 1500.0),
//!     extra_data: [0.0; 4],
//! };
//! feedback.set_actual_position(ActualPosition::Incremental {
//!     position: 123_456,
//!     zero_pulse_position: 4_096,
//! });
//!
//! let bytes: [u8; FEEDBACK_LEN] = feedback.to_bytes();
//! assert_eq!(bytes[..8], [0x40, 0xE2, 0x01, 0x00, 0x00, 0x10, 0x00, 0x00]);
//!
//! let back = Feedback::parse(&bytes)?;
//! assert_eq!(back.to_bytes(), bytes);
//! assert_eq!(
//!     back.actual_position(),
//!     ActualPosition::Incremental { position: 123_456, zero_pulse_position: 4_096 }
//! );
//! assert_eq!(back.message.kind().name(), "motor_speed");
//! assert_eq!(back.message.data, 1500.0);
//! let faults: Vec<_> = back.errors.faults().map(ServoFault::name).collect();
//! assert_eq!(faults, ["ServoErrors", "FollowerErr"]);
//!
//! // Fewer than 40 bytes is an error that says so; nothing panics.
//! assert_eq!(
//!     Feedback::parse(&bytes[..39]).unwrap_err().to_string(),
//!     "servo feedback frame: buffer of 39 bytes where 40 are needed"
//! );
//! # Ok::<(), motionwire_codec::Error>(())
//! ```
#![cfg_attr(not(any(test, feature = "proptest")), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![deny(trivial_numeric_casts)]
#![deny(unused_qualifications)]
#![deny(rustdoc::broken_intra_doc_links)]
#![deny(missing_copy_implementations)]
#![deny(missing_debug_implementations)]
#![deny(trivial_casts)]
#![deny(unreachable_pub)]
// Every pure function, transition and builder says its result must be used.
#![deny(clippy::must_use_candidate)]
#![deny(clippy::return_self_not_must_use)]

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod can;
pub mod canopen;
#[cfg(feature = "defmt")]
mod defmt_impls;
mod error;
pub mod ethercat;
mod names;
pub mod profiles;
pub mod servo;
#[cfg(any(test, feature = "proptest"))]
pub mod strategies;

pub use error::{FieldError, FrameError, LenError, RangeError, TextError, ValueError, What};

/// What went wrong while decoding or constructing a value: the umbrella
/// over the layers' own errors, which converts from each, so that `?`
/// works in a function that calls decoders of several kinds.
///
/// Each function of the crate returns exactly the errors it can produce:
/// [`canopen::Emcy::parse`] a [`LenError`],
/// [`canopen::NodeId::try_new`] a [`RangeError`], [`canopen::Heartbeat::parse`]
/// a [`FrameError`] of a [`LenError`] or a [`ValueError`]. Each says *what*
/// was being decoded (a typed [`What`], so that a program can match on
/// it), what was *expected* and what was *found*, so that a message such
/// as `servo command frame: buffer of 7 bytes where 10 are needed` can be
/// shown to a person without further context; the umbrella shows the
/// message of the error it carries, unchanged. Its variants carry the same
/// types, so that matching on a narrow error and on the umbrella look
/// alike: `Error::Length(LenError { what, .. })`.
///
/// An error that belongs to one layer is that layer's own type, declared in
/// the layer and carried by a variant here ([`Error::PdoEntry`] carries a
/// [`canopen::PdoEntryError`]). Nothing here knows of log files: the
/// errors of reading them are motionwire's `logs` layer's own, which this
/// crate cannot import.
///
/// The enum is `#[non_exhaustive]`: later protocol layers add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A buffer is shorter than the frame or field that must be read from it.
    #[error(transparent)]
    Length(#[from] LenError),
    /// A number lies outside the range its field allows.
    #[error(transparent)]
    OutOfRange(#[from] RangeError),
    /// A value is in range for its type but is not one of the values the
    /// protocol defines (e.g. an NMT state byte of `0x12`).
    #[error(transparent)]
    InvalidValue(#[from] ValueError),
    /// A text is not written in the form its value needs (e.g. `"E5x"` for a
    /// servo E-code).
    #[error(transparent)]
    Malformed(#[from] TextError),
    /// A PDO mapping entry cannot be read from, or written into, a payload
    /// (docs/canopen.md#signals), e.g. `PDO entry 6064sub0 (32 bits) at bit 24:
    /// expected a payload of at least 7 bytes, found 4`.
    #[error(transparent)]
    PdoEntry(#[from] canopen::PdoEntryError),
}

impl From<FieldError> for Error {
    fn from(error: FieldError) -> Self {
        match error {
            FieldError::OutOfRange(e) => Error::OutOfRange(e),
            FieldError::InvalidValue(e) => Error::InvalidValue(e),
        }
    }
}

impl<E: Into<Error>> From<FrameError<E>> for Error {
    fn from(error: FrameError<E>) -> Self {
        match error {
            FrameError::Length(e) => Error::Length(e),
            FrameError::Content(e) => e.into(),
        }
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = core::result::Result<T, E>;

#[cfg(test)]
mod display_tests;
#[cfg(all(test, feature = "serde"))]
mod serde_tests;
