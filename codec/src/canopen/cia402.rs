//! The CiA 402 drive state machine: statusword 6041h → state, controlword
//! 6040h → command, and the pure transition function (CiA 402-2 /
//! IEC 61800-7-201, "drive state machine"; docs/canopen.md#cia402).
//!
//! - [`Cia402State`]: the eight states of the state diagram, read from a
//!   statusword with [`Cia402State::from_statusword`] (bits 0–3, 5 and 6, as
//!   CiA 402's state-coding table of object 6041h gives them).
//! - [`Cia402Command`]: the seven device-control commands, read from a
//!   controlword with [`Cia402Command::from_controlword`] (bits 0–3 and 7,
//!   as CiA 402's command-coding table of object 6040h gives them), with
//!   the decision in docs/canopen.md#cia402 for the patterns that table leaves
//!   to context.
//! - [`Cia402State::next`]: the state a command leads to and the number of
//!   the transition (0–16) as the state diagram draws it; the drive's own
//!   transitions (0, 1, 12 automatic, 13, 14) come from
//!   [`Cia402State::on_drive_event`] with a [`Cia402DriveEvent`], so that
//!   drive firmware can run the same machine.
//! - [`Statusword`] and [`Controlword`]: the two words as flags, every bit
//!   named as CiA 402 names it; [`ModeOfOperation`]: objects 6060h/6061h.
//!
//! Everything here is a pure function of its arguments: no clock, no I/O, no
//! heap (STYLE "Ours, distilled" 5).
//!
//! The module's files: `statusword.rs` (6041h and the states it codes),
//! `controlword.rs` (6040h and the commands it codes), `state_machine.rs`
//! (transitions and drive events), `mode.rs` (6060h/6061h); the tests
//! read as CiA 402's tables and transitions in `tests.rs`.
//!
//! ```
//! use motionwire_codec::canopen::{Cia402Command, Cia402State, Cia402Transition, Statusword};
//!
//! // A master brings a drive up: shutdown, switch on, enable operation.
//! let mut state = Cia402State::from_statusword(0x0250).expect("a state");
//! assert_eq!(state, Cia402State::SwitchOnDisabled);
//! let mut previous = None;
//! for (controlword, number) in [(0x0006, 2), (0x0007, 3), (0x000F, 4)] {
//!     let command = Cia402Command::from_controlword(controlword, previous, Some(state))
//!         .expect("bit 7 is 0: every such controlword is a command");
//!     let transition = state.next(command).expect("allowed in this state");
//!     assert_eq!(transition.numbers(), &[number]);
//!     state = transition.to();
//!     previous = Some(controlword);
//! }
//! assert_eq!(state, Cia402State::OperationEnabled);
//! assert_eq!(Statusword::from_bits_retain(0x0637).state(), Some(state));
//!
//! // 0x07 again is "disable operation" in operation enabled (transition 5)…
//! let command = Cia402Command::from_controlword(0x0007, previous, Some(state));
//! assert_eq!(command, Some(Cia402Command::DisableOperation));
//! assert_eq!(state.next(Cia402Command::DisableOperation), Some(Cia402Transition::T5));
//!
//! // …and a fault reset is the 0 → 1 edge of bit 7 (transition 15).
//! let fault = Cia402State::Fault;
//! let reset = Cia402Command::from_controlword(0x0080, Some(0x0000), Some(fault));
//! assert_eq!(reset, Some(Cia402Command::FaultReset));
//! assert_eq!(fault.next(Cia402Command::FaultReset).map(|t| t.to()), Some(Cia402State::SwitchOnDisabled));
//! assert_eq!(Cia402Command::from_controlword(0x0080, Some(0x0080), Some(fault)), None);
//! ```

mod controlword;
mod mode;
mod state_machine;
mod statusword;

pub use controlword::{Cia402Command, Controlword};
pub use mode::ModeOfOperation;
pub use state_machine::{Cia402DriveEvent, Cia402Transition};
pub use statusword::{Cia402State, Statusword};

/// The device profile number of CiA 402 drives, 0x0192 (402), in the low
/// word of the device type 1000h (CiA 301 §7.5.2.1; docs/canopen.md#cia402).
pub const DRIVE_DEVICE_PROFILE: u16 = 402;

/// Return whether a device type (object 1000h) names a CiA 402 drive: its
/// low word is [`DRIVE_DEVICE_PROFILE`] (docs/canopen.md#cia402).
///
/// ```
/// use motionwire_codec::canopen::cia402::is_drive_device_type;
///
/// assert!(is_drive_device_type(0x0002_0192));
/// assert!(!is_drive_device_type(0x0000_0196)); // CiA 406, an encoder
/// ```
#[must_use]
pub const fn is_drive_device_type(device_type: u32) -> bool {
    device_type & 0xFFFF == DRIVE_DEVICE_PROFILE as u32
}

#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;
