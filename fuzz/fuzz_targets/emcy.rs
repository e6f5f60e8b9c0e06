//! The generic EMCY frame (docs/canopen.md#emcy, docs/canopen.md#emcy-codes)
//! and the look-ups a decoder applies to the numbers a device sends.
//!
//! Arbitrary bytes → `Emcy::parse`. Invariants:
//! - fewer than 8 bytes is exactly `LenError { expected: 8, found }`;
//!   8 or more always parse, view and owned value agree, and `to_bytes` /
//!   `emit` give the first 8 bytes back;
//! - `ErrorCode::class` follows the range table of docs/canopen.md#emcy-codes,
//!   `is_reset` is the 0x00xx class, `register_class_bits` agrees with the
//!   class;
//! - `describe()` is consistent with `class()`: an unknown class (and only
//!   that) gives `Specificity::Unknown` without a source; a class-level
//!   match gives the class's own text; `description()` is `describe().text`;
//! - the register's `names()` are the set bits in bit order;
//! - other numbers from the same bytes: COB-ID classification, node-IDs,
//!   SDO abort codes, CiA 405 kernel errors and 1003h entries round-trip.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    CobFunction, Emcy, EmcyFrame, ErrorClass, ErrorCode, ErrorHistoryEntry, ErrorRegister,
    KernelError, NodeId, SdoAbortCode, Specificity, EMCY_LEN,
};
use motionwire::What;
use motionwire::{LenError, RangeError};

fuzz_target!(|data: &[u8]| {
    check_numbers(data);

    let emcy = match Emcy::parse(data) {
        Ok(emcy) => emcy,
        Err(error) => {
            assert_eq!(
                error,
                LenError {
                    what: What::EmcyFrame,
                    expected: EMCY_LEN,
                    found: data.len(),
                }
            );
            assert!(EmcyFrame::new_checked(data).is_err());
            return;
        }
    };
    let bytes: [u8; EMCY_LEN] = data[..EMCY_LEN].try_into().unwrap();

    let frame = EmcyFrame::new_checked(data).expect("parse succeeded");
    assert_eq!(frame.error_code(), emcy.code);
    assert_eq!(frame.error_register(), emcy.register);
    assert_eq!(frame.manufacturer(), emcy.manufacturer);
    assert_eq!(emcy.code.get(), u16::from_le_bytes([bytes[0], bytes[1]]));
    assert_eq!(emcy.register.bits(), bytes[2]);
    assert_eq!(emcy.manufacturer, bytes[3..8]);
    assert_eq!(Emcy::parse_frame(&frame), emcy);
    assert_eq!(Emcy::from_bytes(&bytes), emcy);

    assert_eq!(emcy.to_bytes(), bytes);
    let mut image = [0xC3u8; EMCY_LEN];
    emcy.emit(&mut EmcyFrame::new_unchecked(&mut image[..]));
    assert_eq!(image, bytes);

    assert_eq!(emcy.is_reset(), emcy.code.is_reset());
    check_code(emcy.code);
    check_register(emcy.register);
});

/// The range table of docs/canopen.md#emcy-codes, written out as the docs write
/// it.
fn table_class(raw: u16) -> ErrorClass {
    match raw >> 8 {
        0x00 => ErrorClass::Reset,
        0x10 => ErrorClass::Generic,
        0x20..=0x2F => ErrorClass::Current,
        0x30..=0x3F => ErrorClass::Voltage,
        0x40..=0x4F => ErrorClass::Temperature,
        0x50..=0x5F => ErrorClass::DeviceHardware,
        0x60..=0x6F => ErrorClass::DeviceSoftware,
        0x70..=0x7F => ErrorClass::AdditionalModules,
        0x80..=0x8F => ErrorClass::Monitoring,
        0x90..=0x9F => ErrorClass::External,
        0xF0 => ErrorClass::AdditionalFunctions,
        0xFF => ErrorClass::DeviceSpecific,
        _ => ErrorClass::Unknown,
    }
}

fn check_code(code: ErrorCode) {
    let raw = code.get();
    let class = code.class();
    assert_eq!(class, table_class(raw), "class of {code}");
    assert_eq!(code.is_reset(), class == ErrorClass::Reset);
    assert_eq!(ErrorCode::new(raw), code);
    assert_eq!(code.to_string(), format!("0x{raw:04X}"));
    assert!(!class.name().is_empty() && !class.description().is_empty());

    // The register bits a code implies agree with its class
    // (docs/canopen.md#emcy-producer).
    let bits = code.register_class_bits();
    let expected = match class {
        ErrorClass::Current => ErrorRegister::CURRENT,
        ErrorClass::Voltage => ErrorRegister::VOLTAGE,
        ErrorClass::Temperature => ErrorRegister::TEMPERATURE,
        ErrorClass::Monitoring if matches!(raw >> 8, 0x81 | 0x82) => ErrorRegister::COMMUNICATION,
        _ => ErrorRegister::empty(),
    };
    assert_eq!(bits, expected, "register bits of {code}");

    // describe() is consistent with class().
    let description = code.describe();
    assert_eq!(code.description(), description.text);
    assert!(!description.text.is_empty());
    assert_eq!(
        class == ErrorClass::Unknown,
        description.specificity == Specificity::Unknown,
        "{code}: class {class}, specificity {}",
        description.specificity
    );
    assert_eq!(
        description.source.is_none(),
        description.specificity == Specificity::Unknown
    );
    match description.specificity {
        Specificity::Unknown | Specificity::Class => {
            assert_eq!(description.text, class.description())
        }
        Specificity::Exact | Specificity::SubClass => {}
    }
    // A sub-class text belongs to the whole block hhxx: the block's 0xhh00
    // code has a description at least as specific.
    if description.specificity == Specificity::SubClass {
        let head = ErrorCode::new(raw & 0xFF00).describe();
        assert!(
            head.specificity <= Specificity::SubClass,
            "{code}: head {head:?}"
        );
    }
    let _ = (description.to_string(), description.specificity.name());
    if let Some(source) = description.source {
        let _ = (source.to_string(), source.document());
    }
}

fn check_register(register: ErrorRegister) {
    let names: Vec<&str> = register.names().collect();
    let expected: Vec<&str> = (0..8)
        .filter(|bit| register.bits() & (1 << bit) != 0)
        .map(|bit| ErrorRegister::NAMES[bit].1)
        .collect();
    assert_eq!(names, expected);
    assert_eq!(ErrorRegister::from_bits_retain(register.bits()), register);
}

/// Numbers that other frames carry, read from the front of the input.
fn check_numbers(data: &[u8]) {
    let mut word = [0u8; 4];
    for (slot, byte) in word.iter_mut().zip(data) {
        *slot = *byte;
    }
    let u32_value = u32::from_le_bytes(word);
    let u16_value = u16::from_le_bytes([word[0], word[1]]);

    // COB-ID classification (CiA 301 Table 72) of any 16-bit identifier.
    let function = CobFunction::classify(u16_value);
    if u16_value > 0x7FF {
        assert_eq!(function, CobFunction::Other);
    }
    if let Some(node) = function.node() {
        assert_eq!(u16::from(node.get()), u16_value & 0x7F);
    }
    match function {
        CobFunction::Emcy(node) => assert_eq!(node.emcy_cob_id(), u16_value),
        CobFunction::ErrorControl(node) => assert_eq!(node.error_control_cob_id(), u16_value),
        CobFunction::Pdo { number, .. } => assert!((1..=4).contains(&number)),
        _ => {}
    }

    // Node-IDs: 1..=127 and nothing else.
    let byte = word[0];
    match NodeId::new(byte) {
        Some(node) => {
            assert!((1..=127).contains(&byte));
            assert_eq!(node.get(), byte);
            assert_eq!(node.index(), usize::from(byte) - 1);
        }
        None => assert_eq!(
            NodeId::try_new(byte),
            Err(RangeError {
                what: What::NodeId,
                found: u32::from(byte),
                min: 1,
                max: 127,
            })
        ),
    }

    // SDO abort codes (CiA 301 Table 22).
    let abort = SdoAbortCode::new(u32_value);
    assert_eq!(abort.get(), u32_value);
    assert_eq!(
        abort.is_known(),
        abort.description() != "Unknown SDO abort code"
    );
    let _ = abort.to_string();

    // CiA 405 kernel errors round-trip every value.
    let kernel = KernelError::from_code(u16_value);
    assert_eq!(kernel.code(), u16_value);
    assert_eq!(kernel.is_error(), u16_value != 0);
    let _ = (kernel.name(), kernel.description(), kernel.to_string());

    // 1003h entries round-trip every value.
    let entry = ErrorHistoryEntry::from_u32(u32_value);
    assert_eq!(entry.to_u32(), u32_value);
    assert_eq!(entry.code.get(), u16_value);
}
