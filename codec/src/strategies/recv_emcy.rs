//! Strategies for the CiA 405 EMCY consumer (`canopen::recv_emcy`).

use proptest::prelude::*;

use super::canopen::error_register;
use crate::canopen::{DeviceSet, Emcy, ErrorCode, NodeId};

/// A device from a small pool — 1..=5 and the wrap-around edge 63, 64,
/// 126, 127 — so that random sequences hit the same devices often.
pub fn scan_device() -> impl Strategy<Value = NodeId> {
    prop_oneof![
        3 => 1u8..=5,
        1 => prop_oneof![Just(63u8), Just(64), Just(126), Just(127)],
    ]
    .prop_map(|raw| NodeId::new(raw).expect("pool holds node-IDs only"))
}

/// A set of devices from the pool of [`scan_device`], possibly empty.
pub fn device_set() -> impl Strategy<Value = DeviceSet> {
    proptest::collection::vec(scan_device(), 0..6).prop_map(DeviceSet::from_iter)
}

/// A reset EMCY: mostly code 0x0000, sometimes another 0x00xx
/// (docs/canopen.md#emcy-codes), any register and manufacturer bytes.
pub fn reset_emcy() -> impl Strategy<Value = Emcy> {
    (
        prop_oneof![3 => Just(0u16), 1 => 1u16..=0x00FF],
        error_register(),
        any::<[u8; 5]>(),
    )
        .prop_map(|(code, register, manufacturer)| {
            Emcy::new(ErrorCode::new(code), register, manufacturer)
        })
}

/// An error EMCY: any code outside 0x00xx.
pub fn error_emcy() -> impl Strategy<Value = Emcy> {
    (0x0100u16..=0xFFFF, error_register(), any::<[u8; 5]>()).prop_map(
        |(code, register, manufacturer)| Emcy::new(ErrorCode::new(code), register, manufacturer),
    )
}

/// A received EMCY: an error or a reset, about even.
pub fn received_emcy() -> impl Strategy<Value = Emcy> {
    prop_oneof![error_emcy(), reset_emcy()]
}

/// One thing that happens to a PLC's EMCY consumer.
#[derive(Debug, Clone, Copy)]
pub enum Op {
    /// An EMCY arrives from a device.
    Receive(NodeId, Emcy),
    /// The PLC calls `RECV_EMCY`.
    Call,
    /// The PLC calls `RECV_EMCY_DEV` for a device.
    CallDev(NodeId),
    /// A device is configured.
    AddDevice(NodeId),
    /// A device is removed from the configuration.
    RemoveDevice(NodeId),
}

/// One event, receives and `RECV_EMCY` calls most often.
pub fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        6 => (scan_device(), received_emcy()).prop_map(|(node, emcy)| Op::Receive(node, emcy)),
        6 => Just(Op::Call),
        2 => scan_device().prop_map(Op::CallDev),
        1 => scan_device().prop_map(Op::AddDevice),
        1 => scan_device().prop_map(Op::RemoveDevice),
    ]
}

/// A sequence of up to 200 events.
pub fn ops() -> impl Strategy<Value = Vec<Op>> {
    proptest::collection::vec(op(), 0..200)
}
