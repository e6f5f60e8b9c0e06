//! The CiA 306 EDS/DCF reader (docs/canopen.md#eds): `Eds::from_bytes` on any
//! bytes, for node 5 and for none, then `pdos`.
//!
//! Invariants:
//! - nothing panics; an error names the file given, a line inside the text
//!   (1-based) and prints;
//! - `IniFile::parse` fails exactly when the reader fails with an INI
//!   error, on the same line;
//! - an entry's name is its `ParameterName`, prefixed with its object's
//!   name and a dot for a sub-entry of an ARRAY or RECORD; `value()` is the
//!   `ParameterValue` when there is one;
//! - each PDO has one signal per mapping entry that is not a dummy, its
//!   mapping holds at most 64 entries and 512 bits, and unpacking any
//!   payload does not panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{NodeId, MAX_MAPPING_ENTRIES, MAX_PDO_BITS};
use motionwire::eds::{Eds, EdsErrorKind, IniFile};

fuzz_target!(|data: &[u8]| {
    let text: String = match std::str::from_utf8(data) {
        Ok(text) => text.to_owned(),
        Err(_) => data.iter().map(|&b| char::from(b)).collect(),
    };
    let lines = text.split('\n').count();
    let ini = IniFile::parse(&text);
    for node in [NodeId::new(5), None] {
        match Eds::from_bytes(data, "fuzz.eds", node) {
            Err(error) => {
                assert_eq!(error.file, "fuzz.eds");
                assert!(error.line >= 1 && error.line <= lines, "{error}");
                let _ = error.to_string();
                match (&ini, &error.kind) {
                    (Err(ini_error), EdsErrorKind::Ini(kind)) => {
                        assert_eq!(ini_error.kind, *kind);
                        assert_eq!(ini_error.line, error.line);
                    }
                    (Err(e), other) => panic!("INI error {e:?} but reader error {other:?}"),
                    (Ok(_), EdsErrorKind::Ini(kind)) => panic!("reader INI error {kind:?}"),
                    (Ok(_), _) => {}
                }
            }
            Ok(eds) => {
                assert!(ini.is_ok());
                check(&eds);
            }
        }
    }
});

fn check(eds: &Eds) {
    let _ = (eds.device_type(), eds.is_cia402(), eds.node());
    for object in eds.objects() {
        for entry in object.entries() {
            assert_eq!(entry.index, object.index);
            if object.object_type.is_compound() {
                assert_eq!(
                    entry.name,
                    format!("{}.{}", object.name, entry.parameter_name)
                );
            } else {
                assert_eq!(entry.name, entry.parameter_name);
            }
            if entry.parameter_value.is_some() {
                assert_eq!(entry.value(), entry.parameter_value.as_ref());
            } else {
                assert_eq!(entry.value(), entry.default_value.as_ref());
            }
            let _ = entry.value().map(ToString::to_string);
        }
    }
    match eds.pdos() {
        Ok(pdos) => {
            for pdo in &pdos {
                assert!(pdo.mapping.len() <= MAX_MAPPING_ENTRIES);
                assert!(pdo.mapping.bit_len() <= MAX_PDO_BITS);
                let real = pdo
                    .mapping
                    .entries()
                    .iter()
                    .filter(|e| !e.is_dummy())
                    .count();
                assert_eq!(pdo.signals.len(), real);
                for payload in [&[0u8; 0][..], &[0xA5; 8], &[0xFF; 64]] {
                    let _ = pdo.unpack(payload).count();
                }
            }
        }
        Err(error) => {
            assert!(error.line >= 1);
            let _ = error.to_string();
        }
    }
}
