//! Strategies for the CANopen types.

use proptest::prelude::*;

use crate::canopen::{Emcy, ErrorCode, ErrorRegister, NodeId};

/// Any valid node-ID, 1..=127.
pub fn node_id() -> impl Strategy<Value = NodeId> {
    (1u8..=127).prop_map(|raw| NodeId::new(raw).expect("1..=127 is a node-ID"))
}

/// Any error code.
pub fn error_code() -> impl Strategy<Value = ErrorCode> {
    any::<u16>().prop_map(ErrorCode::new)
}

/// Any error register byte, reserved bit included.
pub fn error_register() -> impl Strategy<Value = ErrorRegister> {
    any::<u8>().prop_map(ErrorRegister::from_bits_retain)
}

/// Any EMCY.
pub fn emcy() -> impl Strategy<Value = Emcy> {
    (error_code(), error_register(), any::<[u8; 5]>())
        .prop_map(|(code, register, manufacturer)| Emcy::new(code, register, manufacturer))
}
