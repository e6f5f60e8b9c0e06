//! The EtherCAT servo ↔ NC cyclic process data (docs/servo.md; the drive
//! vendor's manual "EtherCat Communication interface V0.18", the interface
//! manual in this module's docs).
//!
//! Once per NC control cycle the NC sends a 10-byte [`Command`] (speed set
//! point, [`ServoControlWord`], extra data code) and the servo answers with a
//! 40-byte [`Feedback`] (actual position, [`ServoStatusWord`],
//! [`ServoErrorWord`], a multiplexed [`Message`], four extra floats). Each
//! frame has a zero-copy view ([`CommandFrame`], [`FeedbackFrame`]) and an
//! owned `Copy` value sharing one set of offsets.
//!
//! The behaviours of docs/servo.md#handshakes are pure functions and state
//! machines:
//! [`servo_ready`] (the ServoRDY truth table), [`drive_enabled`] (SE
//! 0b01 → 0b10, the drive's rule), and the NC side of the three
//! handshakes: [`EnableHandshake`] and the two request/ack handshakes,
//! [`ErrorClearHandshake`] and [`ZeroPulseHandshake`].
//!
//! [`Drive`] is the other side: a deterministic model of a servo drive
//! following docs/servo.md#handshakes from the drive's side, to test NC code
//! against without hardware (docs/servo.md#drive-model).
//!
//! With the `ethercrab` feature, [`Command`] and [`Feedback`] implement the
//! process-data traits of the ethercrab EtherCAT master's `ethercrab-wire`
//! crate (`EtherCrabWireRead`, `EtherCrabWireWrite`, `EtherCrabWireSized`
//! with `PACKED_LEN` 10 and 40, `EtherCrabWireWriteSized`), byte for byte
//! the frames' own [`Command::to_bytes`] / [`Command::parse`]; a short slice
//! is a `WireError`, never a panic (docs/servo.md#ethercrab). ethercrab-wire
//! 0.3 is `no_std` and needs Rust 1.79, below this crate's MSRV 1.81.
//!
//! Layout, one file per word or frame:
//! - `control_word`: [`ServoControlWord`], [`ServoEnable`],
//!   [`RegulatorMode`], [`ParameterTable`] (docs/servo.md#scw);
//! - `status_word`: [`ServoStatusWord`], [`EncoderKind`] (docs/servo.md#ssw);
//! - `error_word`: [`ServoErrorWord`], [`ServoFault`], [`ECode`]
//!   (docs/servo.md#sew);
//! - `command`: [`CommandFrame`], [`Command`] (docs/servo.md#command);
//! - `feedback`: [`FeedbackFrame`], [`Feedback`], [`ActualPosition`]
//!   (docs/servo.md#feedback);
//! - `message`: [`Message`], [`MessageCode`] (docs/servo.md#feedback);
//! - `behaviour`: the pure behaviours (docs/servo.md#handshakes);
//! - `enable`: [`EnableHandshake`], the NC side of the enable handshake
//!   (docs/servo.md#handshakes);
//! - `drive`: [`Drive`], the drive model, and its [`DriveConfig`]
//!   (docs/servo.md#drive-model);
//! - `ethercrab` (feature `ethercrab`): the frames as ethercrab-wire process
//!   data (docs/servo.md#ethercrab).

mod behaviour;
mod command;
mod control_word;
mod drive;
mod enable;
mod error_word;
#[cfg(feature = "ethercrab")]
mod ethercrab;
mod feedback;
mod message;
mod status_word;

pub use behaviour::{
    drive_enabled, servo_ready, ErrorClear, ErrorClearHandshake, Handshake, HandshakeBits,
    HandshakePhase, ServoReadyMode, ZeroPulse, ZeroPulseHandshake,
};
pub use command::{Command, CommandDetails, CommandFrame, COMMAND_LEN};
pub use control_word::{ParameterTable, RegulatorMode, ServoControlWord, ServoEnable};
pub use drive::{
    Drive, DriveConfig, ErrorClearState, MessageRotation, SetpointWidth, SpeedScale,
    ZeroPulseState, TEMP_WARNING_CELSIUS,
};
pub use enable::{EnableHandshake, EnablePhase};
pub use error_word::{ECode, FaultInfo, ParseECodeError, ServoErrorWord, ServoFault};
pub use feedback::{ActualPosition, Feedback, FeedbackDetails, FeedbackFrame, FEEDBACK_LEN};
pub use message::{Message, MessageCode};
pub use status_word::{EncoderKind, ServoStatusWord};
