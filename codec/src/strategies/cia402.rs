//! Strategies for the CiA 402 drive state machine (docs/canopen.md#cia402).

use proptest::prelude::*;

use crate::canopen::{Cia402Command, Cia402State, Controlword, Statusword};

/// Any drive state.
pub fn cia402_state() -> impl Strategy<Value = Cia402State> {
    proptest::sample::select(Cia402State::ALL.to_vec())
}

/// Any device-control command.
pub fn cia402_command() -> impl Strategy<Value = Cia402Command> {
    proptest::sample::select(Cia402Command::ALL.to_vec())
}

/// Any statusword, every bit included.
pub fn statusword() -> impl Strategy<Value = Statusword> {
    any::<u16>().prop_map(Statusword::from_bits_retain)
}

/// Any controlword, every bit included.
pub fn controlword() -> impl Strategy<Value = Controlword> {
    any::<u16>().prop_map(Controlword::from_bits_retain)
}
