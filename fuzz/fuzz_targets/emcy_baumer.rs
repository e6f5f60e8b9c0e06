//! The Baumer EAM580 EMCY and its diagnostic-source table
//! (docs/canopen.md#baumer).
//!
//! Arbitrary bytes → `BaumerEmcy::parse`. Invariants:
//! - fewer than 8 bytes is exactly the EMCY `LenError`; 8 or more
//!   always decode (alarms bytes 3–4, warnings bytes 5–6, unused byte 7,
//!   unnamed bits retained) and re-encode to the same 8 bytes;
//! - `matching_sources`: every returned row has the EMCY's code (any 0x00xx
//!   counting as 0x0000), no row is returned twice, the rows come in table
//!   order; when some row of that code is signalled in the alarm/warning
//!   bits only signalled rows are returned, otherwise every row of the code;
//!   a code no row has gives nothing; `BaumerEmcy::sources` is the same;
//! - error injection codes (object 2116h) from the same bytes: `try_new`
//!   accepts exactly 0 and the high words 1, 4, 8, and a code's row (if any)
//!   is the one row simulated by it;
//! - `source_by_name` on the bytes as text only finds the row of that name.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{Emcy, ErrorCode, EMCY_LEN};
use motionwire::profiles::baumer::{
    is_reserved_code, matching_sources, source_by_name, source_for_injection, sources_for_code,
    BaumerEmcy, DiagnosticSource, InjectionCode, InjectionKind, DIAGNOSTIC_SOURCES,
};
use motionwire::What;
use motionwire::{LenError, ValueError};

fuzz_target!(|data: &[u8]| {
    check_injection(data);
    if let Ok(name) = std::str::from_utf8(data) {
        if let Some(source) = source_by_name(name) {
            assert_eq!(source.name(), name);
        }
    }

    let baumer = match BaumerEmcy::parse(data) {
        Ok(baumer) => baumer,
        Err(error) => {
            assert_eq!(
                error,
                LenError {
                    what: What::EmcyFrame,
                    expected: EMCY_LEN,
                    found: data.len(),
                }
            );
            return;
        }
    };
    let bytes: [u8; EMCY_LEN] = data[..EMCY_LEN].try_into().unwrap();
    let emcy = Emcy::from_bytes(&bytes);

    // Decoding keeps every bit; encoding gives the bytes back.
    assert_eq!(baumer.code, emcy.code);
    assert_eq!(baumer.register, emcy.register);
    assert_eq!(
        baumer.manufacturer.alarms.bits(),
        u16::from_le_bytes([bytes[3], bytes[4]])
    );
    assert_eq!(
        baumer.manufacturer.warnings.bits(),
        u16::from_le_bytes([bytes[5], bytes[6]])
    );
    assert_eq!(baumer.manufacturer.unused, bytes[7]);
    assert_eq!(baumer.to_bytes(), bytes);
    assert_eq!(baumer.to_emcy(), emcy);
    assert_eq!(BaumerEmcy::from_bytes(&bytes), baumer);
    assert_eq!(BaumerEmcy::from(emcy), baumer);
    assert_eq!(Emcy::from(baumer), emcy);

    check_matching(&emcy, &baumer);
});

fn check_matching(emcy: &Emcy, baumer: &BaumerEmcy) {
    let code = if emcy.code.is_reset() {
        ErrorCode::NO_ERROR
    } else {
        emcy.code
    };
    let matched: Vec<&'static DiagnosticSource> = matching_sources(emcy).collect();
    let of_code: Vec<&'static DiagnosticSource> = sources_for_code(code).collect();

    for source in &matched {
        assert_eq!(
            source.code(),
            Some(code),
            "{} for {}",
            source.name(),
            emcy.code
        );
    }
    // Rows in table order, none twice: a subsequence of the code's rows.
    let mut rest = of_code.iter();
    for source in &matched {
        assert!(
            rest.any(|row| std::ptr::eq(*row, *source)),
            "{} out of order or twice",
            source.name()
        );
    }
    let signalled: Vec<&'static DiagnosticSource> = of_code
        .iter()
        .copied()
        .filter(|row| row.is_signalled_in(&baumer.manufacturer))
        .collect();
    let expected = if signalled.is_empty() {
        &of_code
    } else {
        &signalled
    };
    assert_eq!(names(&matched), names(expected));
    if DIAGNOSTIC_SOURCES
        .iter()
        .all(|row| row.code() != Some(code))
    {
        assert!(matched.is_empty());
    }
    assert_eq!(
        names(&baumer.sources().collect::<Vec<_>>()),
        names(&matched)
    );

    // The reserved codes are no row's code.
    if is_reserved_code(emcy.code) {
        assert!(of_code.is_empty(), "reserved {} has rows", emcy.code);
    }
    for source in &matched {
        let _ = (
            source.to_string(),
            source.appearance().name(),
            source.variant().name(),
        );
        if let Some(sent) = source.emcy() {
            assert_eq!(Some(sent.code), source.code());
        }
    }
}

fn names(rows: &[&'static DiagnosticSource]) -> Vec<&'static str> {
    rows.iter().map(|row| row.name()).collect()
}

fn check_injection(data: &[u8]) {
    let mut word = [0u8; 4];
    for (slot, byte) in word.iter_mut().zip(data) {
        *slot = *byte;
    }
    let raw = u32::from_le_bytes(word);
    let high = (raw >> 16) as u16;
    match InjectionCode::try_new(raw) {
        Ok(code) => {
            assert!(raw == 0 || matches!(high, 0x0001 | 0x0004 | 0x0008));
            assert_eq!(code.get(), raw);
            assert_eq!(code.number(), raw as u16);
            assert_eq!(code.kind(), InjectionKind::from_high_word(high));
            if let Some(kind) = code.kind() {
                assert_eq!(InjectionCode::new(kind, code.number()), code);
                assert_eq!(kind.high_word(), high);
            }
            if let Some(source) = source_for_injection(code) {
                assert_eq!(source.injection(), Some(code));
                let simulated = DIAGNOSTIC_SOURCES
                    .iter()
                    .filter(|row| row.injection() == Some(code))
                    .count();
                assert_eq!(simulated, 1, "{code} simulates {simulated} rows");
                if let Some(kind) = code.kind() {
                    assert_eq!(kind.appearance(), source.appearance());
                }
            }
            let _ = code.to_string();
        }
        Err(error) => {
            assert!(raw != 0 && !matches!(high, 0x0001 | 0x0004 | 0x0008));
            assert!(matches!(error, ValueError { found, .. } if found == raw));
        }
    }
}
