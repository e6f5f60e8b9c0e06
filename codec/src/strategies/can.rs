//! Strategies for the crate's CAN frame vocabulary (`crate::can`) and for
//! whole frames read as CANopen.

use proptest::prelude::*;

use super::canopen::{emcy, node_id};
use crate::can::{CanFrame, CanId, FdFlags, FrameData, FrameType, Timestamp};
use crate::canopen::{
    CanOpenMessage, CobFunction, NmtCommand, NmtNodeControl, NmtStateByte, PdoDirection,
};

/// Any NMT command.
pub fn nmt_command() -> impl Strategy<Value = NmtCommand> {
    proptest::sample::select(NmtCommand::ALL.to_vec())
}

/// Any NMT node-control message, to one node or to all.
pub fn nmt_node_control() -> impl Strategy<Value = NmtNodeControl> {
    (nmt_command(), proptest::option::of(node_id()))
        .prop_map(|(command, node)| NmtNodeControl::new(command, node))
}

/// Any standard identifier, weighted towards CANopen's function codes.
pub fn standard_id() -> impl Strategy<Value = CanId> {
    (0u32..=CanId::STANDARD_MAX).prop_map(|raw| CanId::standard(raw).expect("11 bits"))
}

/// Any identifier, standard or extended.
pub fn can_id() -> impl Strategy<Value = CanId> {
    prop_oneof![
        4 => standard_id(),
        1 => (0u32..=CanId::EXTENDED_MAX).prop_map(|raw| CanId::extended(raw).expect("29 bits")),
    ]
}

/// Any CAN FD flags nibble.
pub fn fd_flags() -> impl Strategy<Value = FdFlags> {
    (0u8..=0xF).prop_map(|bits| FdFlags::new(bits).expect("a nibble"))
}

/// Any data of 0 to 8 bytes.
pub fn classic_data() -> impl Strategy<Value = FrameData> {
    proptest::collection::vec(any::<u8>(), 0..=8)
        .prop_map(|bytes| FrameData::new(&bytes).expect("at most 8 bytes"))
}

/// Any valid frame of every type: classic data, remote request, CAN FD
/// (0..=64 bytes), error frame.
pub fn any_can_frame() -> impl Strategy<Value = CanFrame> {
    prop_oneof![
        6 => (can_id(), proptest::collection::vec(any::<u8>(), 0..=8))
            .prop_map(|(id, data)| CanFrame::new(id, &data).expect("valid")),
        2 => (can_id(), 0u8..=8)
            .prop_map(|(id, dlc)| CanFrame::new_remote(id, dlc).expect("valid")),
        2 => (can_id(), fd_flags(), proptest::collection::vec(any::<u8>(), 0..=64))
            .prop_map(|(id, flags, data)| CanFrame::new_fd(id, flags, &data).expect("valid")),
        1 => (0u32..=CanId::EXTENDED_MAX, proptest::collection::vec(any::<u8>(), 0..=8))
            .prop_map(|(classes, data)| CanFrame::new_error(classes, &data).expect("valid")),
    ]
}

/// Any frame type with arbitrary (possibly invalid) parts: for the
/// constructors' checks.
pub fn any_frame_type() -> impl Strategy<Value = FrameType> {
    prop_oneof![
        Just(FrameType::Data),
        any::<u8>().prop_map(|dlc| FrameType::Remote { dlc }),
        fd_flags().prop_map(FrameType::Fd),
        Just(FrameType::Error),
    ]
}

/// Any timestamp.
pub fn timestamp() -> impl Strategy<Value = Timestamp> {
    (any::<u64>(), 0u32..1_000_000_000)
        .prop_map(|(secs, nanos)| Timestamp::from_nanos(secs, nanos).expect("nanos in range"))
}

/// Any direction of a PDO.
fn pdo_direction() -> impl Strategy<Value = PdoDirection> {
    prop_oneof![Just(PdoDirection::Transmit), Just(PdoDirection::Receive)]
}

/// Any message that a classic frame decodes to, of every kind: what
/// `decode` gives back from the message's own frame.
pub fn canopen_message() -> impl Strategy<Value = CanOpenMessage> {
    let other_id = (0u32..=0x7FF)
        .prop_filter("no function in the pre-defined connection set", |&id| {
            CobFunction::classify(id as u16) == CobFunction::Other
        });
    let not_guarding = (0u32..=0x7FF).prop_filter(
        "a remote request that decodes as it is: not on an error-control or EMCY identifier",
        |&id| {
            !matches!(
                CobFunction::classify(id as u16),
                CobFunction::ErrorControl(_) | CobFunction::Emcy(_)
            )
        },
    );
    prop_oneof![
        nmt_node_control().prop_map(CanOpenMessage::NmtNodeControl),
        any::<Option<u8>>().prop_map(|counter| CanOpenMessage::Sync { counter }),
        (node_id(), emcy()).prop_map(|(node, emcy)| CanOpenMessage::Emcy { node, emcy }),
        (0u32..=0x0FFF_FFFF, any::<u16>()).prop_map(|(ms, days)| CanOpenMessage::Time(
            crate::canopen::TimeOfDay::new(ms, days).expect("28 bits")
        )),
        (node_id(), 1u8..=4, pdo_direction(), classic_data()).prop_map(
            |(node, number, direction, data)| CanOpenMessage::Pdo {
                node,
                number,
                direction,
                data,
            }
        ),
        (node_id(), classic_data())
            .prop_map(|(node, data)| CanOpenMessage::SdoResponse { node, data }),
        (node_id(), classic_data())
            .prop_map(|(node, data)| CanOpenMessage::SdoRequest { node, data }),
        (node_id(), any::<u8>()).prop_map(|(node, byte)| CanOpenMessage::Heartbeat {
            node,
            byte: NmtStateByte::new(byte),
        }),
        node_id().prop_map(|node| CanOpenMessage::GuardRequest { node }),
        (other_id, classic_data()).prop_map(|(id, data)| CanOpenMessage::Other(
            CanFrame::new(CanId::standard(id).expect("11 bits"), data.as_slice()).expect("valid")
        )),
        (not_guarding, 0u8..=8).prop_map(|(id, dlc)| CanOpenMessage::Other(
            CanFrame::new_remote(CanId::standard(id).expect("11 bits"), dlc).expect("valid")
        )),
    ]
}
