//! Vector BLF files (docs/formats.md#blf): arbitrary bytes → `BlfReader`, both
//! as they are and behind a valid file header (so the fuzzer reaches the
//! objects and containers). Invariants:
//! - nothing panics, and memory stays bounded (every length is checked
//!   against `MAX_RECORD_LEN` before anything is allocated);
//! - every error is an `FormatError::Binary` of the BLF format (or I/O, never
//!   here) whose message prints; after an error of the file's structure the
//!   reader ends; at most one error per object;
//! - record numbers strictly increase; frames keep the crate's invariants
//!   (a channel, a time, at most 8 bytes unless CAN FD, a remote request
//!   without data);
//! - reading the same bytes in chunks of one byte gives the same records.
#![no_main]

use std::io::Read;

use libfuzzer_sys::fuzz_target;
use motionwire::can::{Iface, LogEvent};
use motionwire::logs::blf::BlfReader;
use motionwire::logs::FormatError;
use motionwire::logs::LogFormat;
use motionwire::logs::{LogError, LogErrorKind, ReadLog};

/// A reader that hands out one byte at a time.
struct Trickle<'a>(&'a [u8]);

impl Read for Trickle<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        match (self.0.split_first(), buf.first_mut()) {
            (Some((&b, rest)), Some(slot)) => {
                *slot = b;
                self.0 = rest;
                Ok(1)
            }
            _ => Ok(0),
        }
    }
}

fn records<R: Read>(reader: R) -> Vec<String> {
    let mut out = Vec::new();
    let mut reader = match BlfReader::new(reader) {
        Ok(reader) => reader,
        Err(e) => {
            check(&e);
            out.push(e.to_string());
            return out;
        }
    };
    let mut last = 0;
    let mut errors = 0u64;
    while let Some(record) = reader.next_event() {
        match record {
            Ok(record) => {
                let number = record.position.number();
                assert!(number > last, "numbers increase");
                last = number;
                let LogEvent::Frame(frame) = record.event else {
                    panic!("BLF has no status events");
                };
                assert!(matches!(frame.iface, Some(Iface::Channel(_))));
                assert!(frame.timestamp.is_some());
                let can = &frame.frame;
                if !can.is_fd() {
                    assert!(can.data().len() <= 8);
                }
                if can.is_rtr() {
                    assert!(can.data().is_empty());
                }
                out.push(format!("{number} {frame}"));
            }
            Err(e) => {
                check(&e);
                errors += 1;
                out.push(e.to_string());
            }
        }
        // At most one error per object, and an object is at least 16
        // bytes, read or inflated from a container (deflate makes at most
        // 1 032 bytes of one): not bounded by the file's length, which
        // compressible objects outnumber.
        assert!(
            errors <= 1032 * reader.bytes_read() / 16 + 1,
            "{errors} errors from {} bytes read",
            reader.bytes_read()
        );
    }
    assert!(reader.next_event().is_none());
    out
}

fn check(e: &LogError) {
    match e.kind() {
        LogErrorKind::Damaged(FormatError::Binary {
            format: LogFormat::Blf,
            reason,
            ..
        })
        | LogErrorKind::Malformed(FormatError::Binary {
            format: LogFormat::Blf,
            reason,
            ..
        }) => {
            let _ = reason.to_string();
        }
        other => panic!("{other:?}"),
    }
}

fuzz_target!(|data: &[u8]| {
    let whole = records(data);
    assert_eq!(records(Trickle(data)), whole);

    let mut file = vec![0u8; 144];
    file[..4].copy_from_slice(b"LOGG");
    file[4..8].copy_from_slice(&144u32.to_le_bytes());
    file.extend_from_slice(data);
    let behind = records(&file[..]);
    assert_eq!(records(Trickle(&file)), behind);
});
