//! Strategies for the error-control types: NMT states, heartbeat and
//! node-guarding messages (SPEC §2.7).

use proptest::prelude::*;

use crate::canopen::{GuardAnswer, Heartbeat, NmtState};

/// Any NMT state.
pub(crate) fn nmt_state() -> impl Strategy<Value = NmtState> {
    proptest::sample::select(NmtState::ALL.to_vec())
}

/// Any heartbeat a producer sends (bit 7 clear) or a device was seen to
/// send (bit 7 set), decoded from its byte.
pub(crate) fn heartbeat() -> impl Strategy<Value = Heartbeat> {
    (nmt_state(), any::<bool>()).prop_map(|(state, bit7)| {
        let byte = state.to_byte() | if bit7 { 0x80 } else { 0 };
        Heartbeat::from_bytes(&[byte]).expect("a defined state decodes")
    })
}

/// Any node-guarding answer.
pub(crate) fn guard_answer() -> impl Strategy<Value = GuardAnswer> {
    (any::<bool>(), nmt_state()).prop_map(|(toggle, state)| GuardAnswer::new(toggle, state))
}
