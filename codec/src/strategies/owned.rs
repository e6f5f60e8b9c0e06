//! Strategies for the owned value types that the serde round trips need and
//! that no other area's file provides (events, outcomes, code tables).

use core::time::Duration;

use proptest::prelude::*;

use super::canopen::{emcy, error_code, node_id};
use super::error_control::nmt_state;
use super::servo::{actual_position, error_word, status_word};
use crate::canopen::{
    EmcyTransition, ErrorClass, ErrorHistoryEntry, GuardingEvent, HeartbeatEvent, KernelError,
    RecvEmcyResult, SdoAbortCode, SlotUpdate,
};
use crate::profiles::baumer::{Appearance, ResetBehaviour, Variant};
use crate::servo::{ECode, EncoderKind, Feedback, Message, MessageCode, RegulatorMode, ServoFault};

/// Any error class.
pub fn error_class() -> impl Strategy<Value = ErrorClass> {
    error_code().prop_map(|code| code.class())
}

/// Any SDO abort code, listed or not.
pub fn sdo_abort_code() -> impl Strategy<Value = SdoAbortCode> {
    any::<u32>().prop_map(SdoAbortCode::new)
}

/// Any kernel error, named values and unlisted ones.
pub fn kernel_error() -> impl Strategy<Value = KernelError> {
    prop_oneof![0u16..=0x30, any::<u16>()].prop_map(KernelError::from_code)
}

/// Any entry of the error history 1003h.
pub fn error_history_entry() -> impl Strategy<Value = ErrorHistoryEntry> {
    any::<u32>().prop_map(ErrorHistoryEntry::from_u32)
}

/// Any transition of the EMCY state machine.
pub fn emcy_transition() -> impl Strategy<Value = EmcyTransition> {
    (0u8..=4).prop_map(|n| EmcyTransition::from_number(n).expect("0..=4 is a transition"))
}

/// Any heartbeat-consumer event.
pub fn heartbeat_event() -> impl Strategy<Value = HeartbeatEvent> {
    (node_id(), any::<u64>(), any::<u64>(), nmt_state(), 0u8..4).prop_map(
        |(node, t0, t1, state, which)| {
            let (t0, t1) = (Duration::from_micros(t0), Duration::from_micros(t1));
            match which {
                0 => HeartbeatEvent::Timeout {
                    node,
                    last_heartbeat: t0,
                    deadline: t1,
                },
                1 => HeartbeatEvent::Recovered {
                    node,
                    last_heartbeat: t0,
                    at: t1,
                    state,
                },
                2 => HeartbeatEvent::RemoteReset {
                    node,
                    last_heartbeat: t0,
                    at: t1,
                },
                _ => HeartbeatEvent::CapacityExceeded { node, at: t1 },
            }
        },
    )
}

/// Any guarding error the master reports.
pub fn guarding_event() -> impl Strategy<Value = GuardingEvent> {
    (
        node_id(),
        any::<u64>(),
        any::<Option<u64>>(),
        any::<(bool, bool)>(),
        nmt_state(),
        0u8..3,
    )
        .prop_map(|(node, at, request_at, (expected, found), state, which)| {
            let at = Duration::from_micros(at);
            let request_at = request_at.map(Duration::from_micros);
            match which {
                0 => GuardingEvent::WrongToggle {
                    node,
                    at,
                    request_at,
                    expected,
                    found,
                },
                1 => GuardingEvent::UnexpectedState {
                    node,
                    at,
                    request_at,
                    state,
                },
                _ => GuardingEvent::MissingAnswer {
                    node,
                    request_at: at,
                    due_by: request_at.unwrap_or(at),
                },
            }
        })
}

/// Any result of a `RECV_EMCY` call.
pub fn recv_emcy_result() -> impl Strategy<Value = RecvEmcyResult> {
    prop_oneof![
        (node_id(), emcy()).prop_map(|(device, emcy)| RecvEmcyResult::Error { device, emcy }),
        (node_id(), emcy())
            .prop_map(|(device, reset)| RecvEmcyResult::ResetError { device, reset }),
        Just(RecvEmcyResult::AllClear),
    ]
}

/// Any update of an EMCY slot.
pub fn slot_update() -> impl Strategy<Value = SlotUpdate> {
    prop_oneof![
        Just(SlotUpdate::RootCause),
        emcy().prop_map(|root_cause| SlotUpdate::FollowUp { root_cause }),
        proptest::option::of(emcy()).prop_map(|cleared| SlotUpdate::Reset { cleared }),
    ]
}

/// Any regulator mode.
pub fn regulator_mode() -> impl Strategy<Value = RegulatorMode> {
    proptest::sample::select(RegulatorMode::ALL.to_vec())
}

/// Either encoder kind.
pub fn encoder_kind() -> impl Strategy<Value = EncoderKind> {
    prop_oneof![Just(EncoderKind::Absolute), Just(EncoderKind::Incremental)]
}

/// Any defined bit of the servo error word.
pub fn servo_fault() -> impl Strategy<Value = ServoFault> {
    proptest::sample::select(ServoFault::ALL.to_vec())
}

/// Any E-code.
pub fn e_code() -> impl Strategy<Value = ECode> {
    proptest::sample::select(ECode::ALL.to_vec())
}

/// Any message kind: known, reserved and unknown codes.
pub fn message_code() -> impl Strategy<Value = MessageCode> {
    prop_oneof![0i32..=9, any::<i32>()].prop_map(MessageCode::from_code)
}

/// Any finite float, signed zeros and subnormals included: the values a
/// text format such as JSON carries (it has no NaN or infinity).
pub fn finite_f32() -> impl Strategy<Value = f32> {
    any::<u32>()
        .prop_map(f32::from_bits)
        .prop_filter("finite", |value| value.is_finite())
}

/// Any message whose data is finite.
pub fn finite_message() -> impl Strategy<Value = Message> {
    (prop_oneof![0i32..=9, any::<i32>()], finite_f32())
        .prop_map(|(code, data)| Message::from_raw(code, data))
}

/// Any feedback frame whose floats are finite.
pub fn finite_feedback() -> impl Strategy<Value = Feedback> {
    (
        actual_position(),
        status_word(),
        error_word(),
        finite_message(),
        [finite_f32(), finite_f32(), finite_f32(), finite_f32()],
    )
        .prop_map(|(position, status, errors, message, extra_data)| {
            let mut feedback = Feedback {
                position: 0,
                status,
                errors,
                message,
                extra_data,
            };
            feedback.set_actual_position(position);
            feedback
        })
}

/// Any appearance of a Baumer diagnostic source.
pub fn appearance() -> impl Strategy<Value = Appearance> {
    prop_oneof![Just(Appearance::Startup), Just(Appearance::Runtime)]
}

/// Any Baumer encoder design.
pub fn variant() -> impl Strategy<Value = Variant> {
    prop_oneof![
        Just(Variant::Both),
        Just(Variant::Redundant),
        Just(Variant::NonRedundant),
    ]
}

/// Any reset behaviour of a Baumer diagnostic source.
pub fn reset_behaviour() -> impl Strategy<Value = ResetBehaviour> {
    prop_oneof![
        Just(ResetBehaviour::AtRuntime),
        Just(ResetBehaviour::AtReboot),
        Just(ResetBehaviour::AtRebootExceptRedundant),
        Just(ResetBehaviour::NoReset),
    ]
}
