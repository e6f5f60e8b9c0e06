//! Strategies for the Baumer EAM580 profile types (docs/canopen.md#baumer).

use proptest::prelude::*;

use super::canopen::{error_code, error_register};
use crate::canopen::{Emcy, ErrorCode};
use crate::profiles::baumer::{
    Alarms, BaumerEmcy, BaumerManufacturer, InjectionCode, InjectionKind, Warnings,
    DIAGNOSTIC_SOURCES,
};

/// Any alarms word, unnamed bits included.
pub fn alarms() -> impl Strategy<Value = Alarms> {
    any::<u16>().prop_map(Alarms::from_bits_retain)
}

/// Any warnings word, unnamed bits included.
pub fn warnings() -> impl Strategy<Value = Warnings> {
    any::<u16>().prop_map(Warnings::from_bits_retain)
}

/// Any manufacturer field: alarms, warnings and the unused byte.
pub fn manufacturer() -> impl Strategy<Value = BaumerManufacturer> {
    (alarms(), warnings(), any::<u8>()).prop_map(|(alarms, warnings, unused)| BaumerManufacturer {
        alarms,
        warnings,
        unused,
    })
}

/// Any EMCY with its manufacturer field decoded.
pub fn baumer_emcy() -> impl Strategy<Value = BaumerEmcy> {
    (error_code(), error_register(), manufacturer())
        .prop_map(|(code, register, manufacturer)| BaumerEmcy::new(code, register, manufacturer))
}

/// Any code the encoder sends, as listed in the diagnostic-source table.
pub fn table_code() -> impl Strategy<Value = ErrorCode> {
    let codes: Vec<ErrorCode> = DIAGNOSTIC_SOURCES.iter().filter_map(|s| s.code()).collect();
    proptest::sample::select(codes)
}

/// An EMCY carrying a code of the table and arbitrary other bytes.
pub fn table_emcy() -> impl Strategy<Value = Emcy> {
    (table_code(), error_register(), any::<[u8; 5]>())
        .prop_map(|(code, register, manufacturer)| Emcy::new(code, register, manufacturer))
}

/// Any injection kind.
pub fn injection_kind() -> impl Strategy<Value = InjectionKind> {
    prop_oneof![
        Just(InjectionKind::StartupAlarm),
        Just(InjectionKind::StartupWarning),
        Just(InjectionKind::Runtime),
    ]
}

/// Any valid injection code.
pub fn injection_code() -> impl Strategy<Value = InjectionCode> {
    prop_oneof![
        Just(InjectionCode::NO_ERROR),
        (injection_kind(), any::<u16>())
            .prop_map(|(kind, number)| InjectionCode::new(kind, number)),
    ]
}
