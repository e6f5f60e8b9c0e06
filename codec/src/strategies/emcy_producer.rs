//! Strategies for the EMCY producer side: state-machine events and the
//! pre-defined error field 1003h.

use proptest::prelude::*;

use super::canopen::{error_code, error_register};
use crate::canopen::{Emcy, EmcyEvent, ErrorCode, ErrorRegister};

/// Codes a drive reports, with two reset codes, drawn often enough that
/// errors repeat, get reset and fill the machine's slots.
const CODE_POOL: [u16; 12] = [
    0x0000, 0x0001, 0x1000, 0x2310, 0x3210, 0x4210, 0x5000, 0x6100, 0x8110, 0x8130, 0x8250, 0xFF01,
];

/// An error code from the pool (mostly) or any code.
pub fn pooled_error_code() -> impl Strategy<Value = ErrorCode> {
    prop_oneof![
        4 => proptest::sample::select(&CODE_POOL[..]).prop_map(ErrorCode::new),
        1 => error_code(),
    ]
}

/// Register bits a caller may supply: none (derived from the code) or any
/// byte, reserved bit included.
pub fn supplied_register() -> impl Strategy<Value = Option<ErrorRegister>> {
    prop_oneof![3 => Just(None), 1 => error_register().prop_map(Some)]
}

/// Any event of the EMCY state machine, weighted towards errors and resets.
pub fn emcy_event() -> impl Strategy<Value = EmcyEvent> {
    prop_oneof![
        1 => Just(EmcyEvent::Initialised),
        8 => (pooled_error_code(), supplied_register(), any::<[u8; 5]>()).prop_map(
            |(code, register, manufacturer)| EmcyEvent::ErrorOccurred { code, register, manufacturer }
        ),
        6 => pooled_error_code().prop_map(EmcyEvent::reset),
        1 => Just(EmcyEvent::AllErrorsReset),
    ]
}

/// A sequence of up to `max_len` events.
pub fn emcy_events(max_len: usize) -> impl Strategy<Value = Vec<EmcyEvent>> {
    proptest::collection::vec(emcy_event(), 0..=max_len)
}

/// An EMCY as a producer sends it: an error from the pool (sometimes a reset
/// code) with any register and manufacturer bytes.
pub fn produced_emcy() -> impl Strategy<Value = Emcy> {
    (pooled_error_code(), error_register(), any::<[u8; 5]>())
        .prop_map(|(code, register, manufacturer)| Emcy::new(code, register, manufacturer))
}
