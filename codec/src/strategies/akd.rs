//! Strategies for the Kollmorgen AKD profile (docs/canopen.md#akd).

use proptest::prelude::*;

use super::canopen::{error_code, error_register};
use crate::profiles::akd::{AkdEmcy, AkdManufacturer, AxisId, FeedbackId};

/// Any axis id, 0..=15.
pub fn axis_id() -> impl Strategy<Value = AxisId> {
    (0u8..=15).prop_map(|raw| AxisId::new(raw).expect("0..=15 is an axis id"))
}

/// Any valid feedback id: none or FB1..FB5.
pub fn feedback_id() -> impl Strategy<Value = FeedbackId> {
    prop_oneof![
        3 => prop::sample::select(FeedbackId::ALL.to_vec()),
        1 => (6u8..=15).prop_map(FeedbackId::from_nibble),
    ]
}

/// Any valid AKD manufacturer field, reserved bytes arbitrary.
pub fn akd_manufacturer() -> impl Strategy<Value = AkdManufacturer> {
    (axis_id(), feedback_id(), any::<[u8; 4]>()).prop_map(|(axis, feedback, reserved)| {
        AkdManufacturer {
            axis,
            feedback,
            reserved,
        }
    })
}

/// Any valid AKD EMCY.
pub fn akd_emcy() -> impl Strategy<Value = AkdEmcy> {
    (error_code(), error_register(), akd_manufacturer()).prop_map(
        |(code, register, manufacturer)| AkdEmcy {
            code,
            register,
            manufacturer,
        },
    )
}
