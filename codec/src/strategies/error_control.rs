//! Strategies for the error-control types: NMT states, heartbeat and
//! node-guarding messages, and timed input sequences for the heartbeat
//! consumer, the node-guarding master and life guarding
//! (docs/canopen.md#error-control).

use proptest::prelude::*;

use core::time::Duration;

use crate::canopen::{GuardAnswer, Heartbeat, NmtState, NodeId};

/// Any NMT state.
pub fn nmt_state() -> impl Strategy<Value = NmtState> {
    proptest::sample::select(NmtState::ALL.to_vec())
}

/// Any heartbeat a producer sends (bit 7 clear) or a device was seen to
/// send (bit 7 set), decoded from its byte.
pub fn heartbeat() -> impl Strategy<Value = Heartbeat> {
    (nmt_state(), any::<bool>()).prop_map(|(state, bit7)| {
        let byte = state.to_byte() | if bit7 { 0x80 } else { 0 };
        Heartbeat::from_bytes(&[byte]).expect("a defined state decodes")
    })
}

/// Any node-guarding answer.
pub fn guard_answer() -> impl Strategy<Value = GuardAnswer> {
    (any::<bool>(), nmt_state()).prop_map(|(toggle, state)| GuardAnswer::new(toggle, state))
}

/// Steps at arbitrary times (µs): jumping backwards, repeating, up to
/// `u64::MAX`; for "never panics" properties of the saturating arithmetic.
pub fn any_times<S: Strategy>(step: S) -> impl Strategy<Value = Vec<(Duration, S::Value)>> {
    let time = prop_oneof![
        any::<u64>().prop_map(Duration::from_micros),
        ((u64::MAX - 1_000_000)..=u64::MAX).prop_map(Duration::from_micros),
        (0u64..1_000_000).prop_map(Duration::from_micros),
        Just(Duration::MAX),
    ];
    proptest::collection::vec((time, step), 0..40)
}

/// Turn steps with time increments (µs) into steps with a monotonic time,
/// starting anywhere in the first hour.
fn timed<S: Strategy>(
    step: S,
    max_increment: u64,
) -> impl Strategy<Value = Vec<(Duration, S::Value)>> {
    (
        0..3_600_000_000u64,
        proptest::collection::vec((0..=max_increment, step), 0..80),
    )
        .prop_map(|(start, steps)| {
            let mut now = start;
            steps
                .into_iter()
                .map(|(increment, step)| {
                    now += increment;
                    (Duration::from_micros(now), step)
                })
                .collect()
        })
}

/// One input to the heartbeat consumer.
#[derive(Debug, Clone, Copy)]
pub enum ConsumerStep {
    /// A heartbeat or boot-up from a node.
    Rx(NodeId, NmtState),
    /// A poll.
    Poll,
}

/// Timed consumer inputs over nodes 1..=5 (more than a 3-entry consumer
/// holds), with gaps from 0 to 0.5 s.
pub fn consumer_steps() -> impl Strategy<Value = Vec<(Duration, ConsumerStep)>> {
    timed(consumer_step(), 500_000)
}

/// One consumer input, from nodes 1..=5.
pub fn consumer_step() -> impl Strategy<Value = ConsumerStep> {
    let node = (1u8..=5).prop_map(|raw| NodeId::new(raw).expect("1..=5 is a node-ID"));
    prop_oneof![
        3 => (node, nmt_state()).prop_map(|(node, state)| ConsumerStep::Rx(node, state)),
        1 => Just(ConsumerStep::Poll),
    ]
}

/// One input to the node-guarding master.
#[derive(Debug, Clone, Copy)]
pub enum GuardingStep {
    /// A guard request sent or seen.
    Request,
    /// An answer from the node.
    Answer(GuardAnswer),
    /// The node's boot-up message.
    BootUp,
    /// A poll.
    Poll,
}

/// Timed guarding inputs with gaps from 0 to 0.3 s.
pub fn guarding_steps() -> impl Strategy<Value = Vec<(Duration, GuardingStep)>> {
    timed(guarding_step(), 300_000)
}

/// One guarding input.
pub fn guarding_step() -> impl Strategy<Value = GuardingStep> {
    prop_oneof![
        3 => Just(GuardingStep::Request),
        3 => guard_answer().prop_map(GuardingStep::Answer),
        1 => Just(GuardingStep::BootUp),
        2 => Just(GuardingStep::Poll),
    ]
}

/// One input to life guarding.
#[derive(Debug, Clone, Copy)]
pub enum LifeStep {
    /// A guard request received.
    Request,
    /// A poll.
    Poll,
}

/// Timed life-guarding inputs with gaps from 0 to 0.6 s.
pub fn life_steps() -> impl Strategy<Value = Vec<(Duration, LifeStep)>> {
    timed(life_step(), 600_000)
}

/// One life-guarding input.
pub fn life_step() -> impl Strategy<Value = LifeStep> {
    prop_oneof![Just(LifeStep::Request), Just(LifeStep::Poll)]
}
