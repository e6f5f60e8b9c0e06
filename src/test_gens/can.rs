//! Strategies for whole CAN frames read as CANopen: NMT node control, CAN
//! data and payloads, and every kind of [`CanOpenMessage`].

use proptest::prelude::*;

use super::canopen::{emcy, node_id};
use super::error_control::heartbeat;
use crate::canopen::{
    CanData, CanOpenMessage, CanPayload, CobFunction, NmtCommand, NmtNodeControl, PdoDirection,
};

/// Any NMT command.
pub(crate) fn nmt_command() -> impl Strategy<Value = NmtCommand> {
    proptest::sample::select(NmtCommand::ALL.to_vec())
}

/// Any NMT node-control message, to one node or to all.
pub(crate) fn nmt_node_control() -> impl Strategy<Value = NmtNodeControl> {
    (nmt_command(), proptest::option::of(node_id()))
        .prop_map(|(command, node)| NmtNodeControl::new(command, node))
}

/// Any data field, 0 to 8 bytes.
pub(crate) fn can_data() -> impl Strategy<Value = CanData> {
    proptest::collection::vec(any::<u8>(), 0..=8)
        .prop_map(|bytes| CanData::new(&bytes).expect("at most 8 bytes"))
}

/// Any payload: data of 0 to 8 bytes, or a remote frame of DLC 0 to 8.
pub(crate) fn can_payload() -> impl Strategy<Value = CanPayload> {
    prop_oneof![
        3 => can_data().prop_map(CanPayload::Data),
        1 => (0usize..=8).prop_map(|dlc| CanPayload::remote(dlc).expect("DLC 0..=8")),
    ]
}

/// Any direction of a PDO.
fn pdo_direction() -> impl Strategy<Value = PdoDirection> {
    prop_oneof![Just(PdoDirection::Transmit), Just(PdoDirection::Receive)]
}

/// Any message that a frame decodes to, of every kind: what `decode` gives
/// back from the message's own identifier and payload.
pub(crate) fn canopen_message() -> impl Strategy<Value = CanOpenMessage> {
    let other_id = (0u16..=0x7FF)
        .prop_filter("no function in the pre-defined connection set", |&id| {
            CobFunction::classify(id) == CobFunction::Other
        });
    let not_guarding = (0u16..=0x7FF).prop_filter("not an error-control identifier", |&id| {
        !matches!(CobFunction::classify(id), CobFunction::ErrorControl(_))
    });
    prop_oneof![
        nmt_node_control().prop_map(CanOpenMessage::NmtNodeControl),
        any::<Option<u8>>().prop_map(|counter| CanOpenMessage::Sync { counter }),
        (node_id(), emcy()).prop_map(|(node, emcy)| CanOpenMessage::Emcy { node, emcy }),
        can_data().prop_map(|data| CanOpenMessage::Time { data }),
        (node_id(), 1u8..=4, pdo_direction(), can_data()).prop_map(
            |(node, number, direction, data)| CanOpenMessage::Pdo {
                node,
                number,
                direction,
                data,
            }
        ),
        (node_id(), can_data()).prop_map(|(node, data)| CanOpenMessage::SdoResponse { node, data }),
        (node_id(), can_data()).prop_map(|(node, data)| CanOpenMessage::SdoRequest { node, data }),
        (node_id(), heartbeat())
            .prop_map(|(node, heartbeat)| CanOpenMessage::Heartbeat { node, heartbeat }),
        node_id().prop_map(|node| CanOpenMessage::GuardRequest { node }),
        (other_id, can_data()).prop_map(|(cob_id, data)| CanOpenMessage::Other {
            cob_id,
            payload: CanPayload::Data(data),
        }),
        (not_guarding, 0usize..=8).prop_map(|(cob_id, dlc)| CanOpenMessage::Other {
            cob_id,
            payload: CanPayload::remote(dlc).expect("DLC 0..=8"),
        }),
    ]
}
