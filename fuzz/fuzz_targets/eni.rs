//! The ENI reader (docs/ethercat.md#eni): `parse_eni` on any text.
//!
//! Invariants:
//! - nothing panics; reading the same text twice gives the same result;
//! - an error is an XML error (no element) exactly when roxmltree refuses
//!   the text; every error's line is inside the text and it prints;
//! - a slave's FMMUs and sync managers are numbered 0–15, each number once
//!   and in order; the assignment names sync managers 0–15, each once and
//!   in order; every PDO entry has 1–255 bits.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::decoder::ethercat::{parse_eni, EniErrorKind};

fuzz_target!(|data: &[u8]| {
    let text: String = match std::str::from_utf8(data) {
        Ok(text) => text.to_owned(),
        Err(_) => data.iter().map(|&b| char::from(b)).collect(),
    };
    let result = parse_eni(&text);
    assert_eq!(result, parse_eni(&text));
    let xml_ok = roxmltree::Document::parse(&text).is_ok();
    match result {
        Err(error) => {
            let lines = text.split('\n').count();
            assert!(error.line >= 1 && error.line as usize <= lines, "{error}");
            let is_xml = matches!(error.kind, EniErrorKind::Xml { .. });
            assert_eq!(is_xml, !xml_ok, "{error}");
            assert_eq!(error.element.is_none(), is_xml, "{error}");
            assert!(!error.to_string().is_empty());
        }
        Ok(slaves) => {
            assert!(xml_ok);
            for slave in &slaves {
                let increasing = |numbers: &[u8]| {
                    numbers.windows(2).all(|w| w[0] < w[1]) && numbers.iter().all(|&n| n < 16)
                };
                let fmmus: Vec<u8> = slave.fmmus.iter().map(|&(n, _)| n).collect();
                let sms: Vec<u8> = slave.sync_managers.iter().map(|&(n, _)| n).collect();
                let assigned: Vec<u8> = slave.assignment.iter().map(|(n, _)| *n).collect();
                assert!(increasing(&fmmus) && increasing(&sms) && increasing(&assigned));
                for pdo in &slave.pdos {
                    assert!(pdo.entries.iter().all(|e| e.entry.bits() > 0));
                }
            }
        }
    }
});
