//! The Kollmorgen AKD EMCY (docs/canopen.md#akd).
//!
//! Arbitrary bytes → `AkdEmcy::parse`. Invariants:
//! - fewer than 8 bytes is exactly the EMCY `LenError`;
//! - with 8 or more, every input decodes and nothing is lost: the fields
//!   are byte 3's nibbles (a feedback nibble of 6..=15 kept as
//!   `FeedbackId::Unknown`, the strict `feedback_id()` of the view naming it
//!   as a `ValueError`) and the reserved bytes 4–7 as sent, and
//!   re-encoding gives the 8 bytes back;
//! - the 5-byte manufacturer field on its own (`AkdManufacturer::parse`)
//!   obeys the same rules with its own length error;
//! - `AxisId` / `FeedbackId` constructors accept exactly their ranges and
//!   name the value they refuse.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{Emcy, EmcyFrame, EMCY_LEN};
use motionwire::profiles::akd::{
    AkdEmcy, AkdManufacturer, AkdManufacturerField, AxisId, FeedbackId, AKD_MANUFACTURER_LEN,
};
use motionwire::What;
use motionwire::{FieldError, LenError, RangeError, ValueError};

const FEEDBACK_EXPECTED: &str = "0 (none), 1..=5 (FB1..FB5)";

fuzz_target!(|data: &[u8]| {
    check_ids(data);
    check_field(data);

    let result = AkdEmcy::parse(data);
    if data.len() < EMCY_LEN {
        assert_eq!(
            result,
            Err(LenError {
                what: What::EmcyFrame,
                expected: EMCY_LEN,
                found: data.len(),
            })
        );
        return;
    }
    let bytes: [u8; EMCY_LEN] = data[..EMCY_LEN].try_into().unwrap();
    let nibble = bytes[3] >> 4;
    let emcy = Emcy::from_bytes(&bytes);
    let akd = result.expect("8 bytes always decode");
    assert_eq!(AkdEmcy::from_bytes(&bytes), akd);
    assert_eq!(AkdEmcy::parse_frame(&EmcyFrame::new_unchecked(&bytes)), akd);
    assert_eq!(AkdEmcy::from_emcy(&emcy), akd);
    assert_eq!(AkdEmcy::from(emcy), akd);
    assert_eq!(akd.code, emcy.code);
    assert_eq!(akd.register, emcy.register);
    assert_eq!(akd.manufacturer.axis.get(), bytes[3] & 0x0F);
    assert_eq!(akd.manufacturer.feedback.get(), nibble);
    assert_eq!(akd.manufacturer.feedback.is_defined(), nibble <= 5);
    assert_eq!(akd.manufacturer.reserved, bytes[4..8]);
    assert_eq!(akd.is_reset(), emcy.is_reset());
    // Re-encoding gives the input back.
    assert_eq!(akd.to_bytes(), bytes);
    assert_eq!(akd.to_emcy(), emcy);
    assert_eq!(Emcy::from(akd), emcy);
    let mut image = [0x3Cu8; EMCY_LEN];
    akd.emit(&mut EmcyFrame::new_unchecked(&mut image[..]));
    assert_eq!(image, bytes);
    let _ = akd.manufacturer.feedback.to_string();
});

/// The 5-byte field from the front of the input.
fn check_field(data: &[u8]) {
    let result = AkdManufacturer::parse(data);
    let Ok(view) = AkdManufacturerField::new_checked(data) else {
        assert_eq!(
            result,
            Err(LenError {
                what: What::AkdManufacturerField,
                expected: AKD_MANUFACTURER_LEN,
                found: data.len(),
            })
        );
        return;
    };
    // The view reads every field, whatever the nibble.
    let nibble = view.feedback_nibble();
    assert_eq!(nibble, data[0] >> 4);
    assert_eq!(view.axis_id().get(), data[0] & 0x0F);
    assert_eq!(view.reserved(), data[1..5]);
    assert_eq!(
        view.feedback_id().map_err(FieldError::InvalidValue),
        FeedbackId::try_new(nibble)
    );
    let bytes: [u8; AKD_MANUFACTURER_LEN] = data[..AKD_MANUFACTURER_LEN].try_into().unwrap();
    let field = result.expect("5 bytes always decode");
    assert_eq!(AkdManufacturer::from_bytes(&bytes), field);
    assert_eq!(AkdManufacturer::parse_field(&view), field);
    assert_eq!(view.feedback(), field.feedback);
    assert_eq!(field.feedback.get(), nibble);
    match view.feedback_id() {
        Ok(strict) => assert_eq!(strict, field.feedback),
        Err(error) => {
            assert!(!field.feedback.is_defined());
            assert_eq!(
                error,
                ValueError {
                    what: What::AkdFeedbackId,
                    found: u32::from(nibble),
                    expected: FEEDBACK_EXPECTED,
                }
            );
        }
    }
    assert_eq!(field.to_bytes(), bytes);
    let mut image = [0xFFu8; AKD_MANUFACTURER_LEN];
    field.emit(&mut AkdManufacturerField::new_unchecked(&mut image[..]));
    assert_eq!(image, bytes);
}

/// The sub-byte newtypes on any byte.
fn check_ids(data: &[u8]) {
    let Some(&raw) = data.first() else {
        return;
    };
    match AxisId::try_new(raw) {
        Ok(axis) => {
            assert!(raw <= 15);
            assert_eq!(axis.get(), raw);
            assert_eq!(axis.is_given(), raw != 0);
        }
        Err(error) => assert_eq!(
            error,
            RangeError {
                what: What::AkdAxisId,
                found: u32::from(raw),
                min: 0,
                max: 15,
            }
        ),
    }
    match FeedbackId::try_new(raw) {
        Ok(feedback) => {
            assert!(raw <= 5);
            assert_eq!(feedback.get(), raw);
            assert_eq!(feedback.number(), (raw != 0).then_some(raw));
            assert_eq!(FeedbackId::ALL[usize::from(raw)], feedback);
        }
        Err(error) if raw <= 15 => assert_eq!(
            error,
            FieldError::InvalidValue(ValueError {
                what: What::AkdFeedbackId,
                found: u32::from(raw),
                expected: FEEDBACK_EXPECTED,
            })
        ),
        Err(error) => assert_eq!(
            error,
            FieldError::OutOfRange(RangeError {
                what: What::AkdFeedbackId,
                found: u32::from(raw),
                min: 0,
                max: 15,
            })
        ),
    }
    assert_eq!(FeedbackId::new(raw), FeedbackId::try_new(raw).ok());
    assert_eq!(AxisId::new(raw), AxisId::try_new(raw).ok());
}
