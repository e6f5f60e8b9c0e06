//! # motionwire
//!
//! Codecs and pure state machines for the diagnostic and cyclic-control
//! language of industrial motion devices: the EtherCAT servo ↔ NC cyclic
//! frames, CANopen emergency messages and error control, the CiA 405
//! `RECV_EMCY` consumer, and device profiles (Kollmorgen AKD, Baumer EAM580).
//!
//! The crate's core is `no_std`, allocates nothing and contains no `unsafe`
//! code; reading log files, the decoder session and the post-mortem need
//! `std` and sit behind features.
//! Every decoder takes outside bytes and returns a typed [`Error`] instead of
//! panicking. The formats and behaviours are described in the repository's
//! reference, the `docs/` folder (`docs/README.md`: the program's output,
//! the summary, every log format, CANopen as the crate reads it, the servo
//! frames); each item's documentation names the page and section that
//! covers it, as `docs/output.md#sdo`.
//!
//! ## Layout
//!
//! The protocols themselves — [`can`], [`canopen`], [`profiles`], [`servo`]
//! and their error type [`CodecError`] — are the `no_std` crate
//! `motionwire-codec`, re-exported here: the compiler holds the layers
//! apart, so nothing in them can reach the log readers, the decoder or the
//! report built on them. Everything else is this crate's.
//!
//! - [`can`]: the one CAN frame vocabulary every other part speaks —
//!   identifiers, [`can::CanFrame`] (data, remote, CAN FD, error frames;
//!   owned or borrowed), error-frame classes, and [`can::LogFrame`], a frame
//!   with the time and interface a log records (ISO 11898-1, docs/formats.md).
//! - [`logs`]: every log format in one folder — candump text (can-utils),
//!   Vector ASC, PEAK TRC, and with `std` Vector BLF, pcap/pcapng and ASAM
//!   MDF 4 — each read into [`can::LogFrame`]s, the format detected from
//!   the content (docs/formats.md).
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
//! - `decoder` (feature `decoder`): the decoder session — each frame of a
//!   log read in the context of the frames before it: SDO transfers, PDO
//!   signals from the mappings the log teaches, CiA 402 readings, the JSON
//!   record of `motionwire decode --json` (docs/output.md#json).
//! - `summary` (feature `decoder`): the post-mortem of a log, one record per
//!   device and per bus, as typed values, text and JSON (docs/summary.md),
//!   and what went wrong as a list of findings (docs/summary.md#findings).
//!
//! ## Optional features
//!
//! - `std`: links the standard library: each log format's reader of a
//!   `std::io::Read` (`logs::candump::CandumpReader`, `logs::asc::AscReader`,
//!   `logs::trc::TrcReader`), their one trait `logs::ReadLog` and its error
//!   `logs::LogError`. The rest of the library needs nothing from it
//!   ([`Error`] implements `core::error::Error` either way).
//! - `logs`: one way to read any log — `logs::open(path)`, `logs::read(input)`
//!   and `logs::ReadOptions` detect the format from the content, inflate
//!   gzip and hand on the events of every format through one
//!   `logs::LogReader` (docs/formats.md#detection, docs/formats.md#gzip). Needs
//!   `std`; enables `pcap`, `blf` and `mf4` and adds `flate2`.
//! - `decoder`: `decoder::Decoder` and `summary::Summarizer`, the decoder
//!   session and the post-mortem (docs/output.md, docs/summary.md). Needs
//!   `std`; enables `eds` and `serde`; adds `serde_json` (the summary's exact
//!   times) and `itoa` (the JSON records).
//! - `eni`: `decoder::ethercat::parse_eni`, a master's EtherCAT network
//!   information file (ETG.2100 XML) as the slaves' process-data
//!   configuration (docs/ethercat.md#eni). Enables `decoder`; adds
//!   `roxmltree`.
//! - `cli`: the `motionwire` program; enables `decoder`, `logs`, `eds` and
//!   `eni` and adds `clap`.
//! - `pcap`: `logs::pcap::PcapReader`, pcap and pcapng captures of
//!   SocketCAN interfaces (docs/formats.md#pcap). Needs `std`, no dependency.
//! - `blf`: `logs::blf::BlfReader`, Vector BLF logs (docs/formats.md#blf).
//!   Needs `std`; adds `flate2` for the zlib containers.
//! - `mf4`: `logs::mf4::Mf4Reader`, ASAM MDF 4 bus logging (CANedge,
//!   CANoe, asammdf, python-can's `MF4Writer`; docs/formats.md#mf4). Needs
//!   `std`; adds `flate2` for the deflated data blocks.
//! - `serde`: `Serialize` and `Deserialize` for the owned value types (not
//!   the zero-copy views, not the state machines).
//!   - Checked numbers — [`canopen::NodeId`], [`servo::ServoEnable`],
//!     [`servo::ParameterTable`], [`profiles::akd::AxisId`],
//!     [`profiles::baumer::InjectionCode`] — are their number, and
//!     deserializing checks it as their `try_new` does: no invalid value can
//!     be made. [`canopen::DeviceSet`] is the list of its node-IDs.
//!   - Flag words ([`canopen::ErrorRegister`], the servo words, the Baumer
//!     alarms and warnings) use bitflags 2's format: in text formats the
//!     names of the set flags joined by `|`, with every bit that no name
//!     covers (reserved bits, multi-bit fields) as one hex number, e.g.
//!     `"ENCODER_DATA_INVALID | 0x104"`; in binary formats the integer.
//!     Every bit survives a round trip.
//!   - Enums and structs have serde's derived format: variant and field
//!     names as written in Rust.
//!   - Floats are numbers. A text format without NaN and infinity (JSON)
//!     cannot carry those: `serde_json` writes `null` and refuses it back.
//!     For a bit-exact copy use a binary format or the frames' `to_bytes`.
//! - `embedded-can`: [`can::CanFrame`] implements `embedded_can::Frame`
//!   and converts from and to any driver's frame type
//!   (`CanFrame::from_embedded`, `to_embedded`); read any
//!   `embedded_can::Frame` as a [`canopen::CanOpenMessage`]
//!   (`CanOpenMessage::from_frame`) and write one back (`to_frame` on the
//!   message, and on [`canopen::Emcy`], [`canopen::Heartbeat`],
//!   [`canopen::GuardAnswer`] and [`canopen::NmtNodeControl`]). Without the
//!   feature, [`canopen::CanOpenMessage::decode`] does the same from the
//!   crate's [`can::CanFrame`].
//! - `eds`: `motionwire::eds`, the CiA 306 EDS/DCF reader: object names, data types
//!   and values, and each PDO's communication parameters and mapping with
//!   its signals' names and types (docs/canopen.md#eds). Needs `std`.
//! - `defmt`: `defmt::Format` on the frame vocabulary and the value types,
//!   for firmware that logs with defmt.
//!
//! ## Example
//!
//! A servo's answer to one NC cycle: build a [`servo::Feedback`], emit it
//! into the 40 bytes of the process image, and parse it back.
//!
//! ```
//! use motionwire::servo::{
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
//! # Ok::<(), motionwire::Error>(())
//! ```
#![cfg_attr(not(any(test, feature = "std")), no_std)]
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

/// The codec layer's error: a frame, field or value of a protocol that
/// could not be decoded or built (`motionwire-codec`'s `Error`).
pub use motionwire_codec::Error as CodecError;
pub use motionwire_codec::{
    can, canopen, profiles, servo, FieldError, FrameError, LenError, RangeError, TextError,
    ValueError, What,
};

#[cfg(feature = "decoder")]
pub mod decoder;
#[cfg(feature = "eds")]
pub mod eds;
pub mod ethercat;
pub mod logs;
#[cfg(feature = "report")]
pub mod report;
#[cfg(feature = "decoder")]
pub mod summary;

use logs::FormatError;

/// What went wrong while decoding, reading or constructing a value: the
/// umbrella over the layers' own errors, which converts from each.
///
/// A protocol's frame, field or value ([`Error::Codec`]: what was decoded,
/// what was expected, what was found, e.g. `servo command frame: buffer of
/// 7 bytes where 10 are needed`) and a log line or file that does not
/// follow its format ([`Error::Format`]). Each shows to a
/// person without further context.
///
/// The enum is `#[non_exhaustive]`: later layers add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A frame, field or value of a protocol that could not be decoded or
    /// built: the codec layer's own error.
    #[error(transparent)]
    Codec(#[from] CodecError),
    /// A line or record of a log that its format's rules reject: the logs
    /// layer's own error ([`FormatError`]), e.g. `candump line, column 26:
    /// expected an identifier at most 0x7FF, found 0x800`.
    #[error(transparent)]
    Format(#[from] FormatError),
}

/// Each of the codec layer's own errors converts through [`CodecError`],
/// so that `?` works across the layers.
macro_rules! from_codec {
    ($($error:ty),* $(,)?) => {
        $(
            impl From<$error> for Error {
                fn from(error: $error) -> Self {
                    Error::Codec(CodecError::from(error))
                }
            }
        )*
    };
}

from_codec!(
    LenError,
    RangeError,
    ValueError,
    TextError,
    FieldError,
    canopen::PdoEntryError,
    canopen::PdoPackError,
    servo::ParseECodeError,
);

impl<E: Into<CodecError>> From<FrameError<E>> for Error {
    fn from(error: FrameError<E>) -> Self {
        Error::Codec(error.into())
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = core::result::Result<T, E>;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

#[cfg(test)]
mod test_gens;
