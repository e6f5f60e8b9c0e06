//! ASAM MDF 4 bus-logging files (docs/formats.md#mf4): arbitrary bytes →
//! `Mf4Reader`, both as they are (the seeds are real files: python-can's
//! `MF4Writer`, asammdf, a CANedge logger) and behind an identification
//! block (so the fuzzer reaches the header and the blocks it links).
//! Invariants:
//! - nothing panics, nothing loops for ever (every event is paid for by
//!   bytes read), and memory stays bounded (every length and count is
//!   checked before anything is allocated);
//! - every error is an `FormatError::Binary` of the MF4 format whose message
//!   prints; after an error that ends the reading the reader ends;
//! - frames keep the crate's invariants (at most 8 bytes unless CAN FD, a
//!   remote request without data, a numeric interface);
//! - a file read from a stream (held in memory) reads as the file itself.
#![no_main]

use std::io::Cursor;

use libfuzzer_sys::fuzz_target;
use motionwire::can::{Iface, LogEvent};
use motionwire::logs::mf4::Mf4Reader;
use motionwire::logs::FormatError;
use motionwire::logs::{LogError, LogErrorKind, LogFormat, ReadLog};

fn records(data: &[u8]) -> Vec<String> {
    let mut out = Vec::new();
    let mut reader = match Mf4Reader::new(Cursor::new(data)) {
        Ok(reader) => reader,
        Err(e) => {
            check(&e);
            out.push(e.to_string());
            return out;
        }
    };
    let mut events = 0u64;
    while let Some(record) = reader.next_event() {
        events += 1;
        match record {
            Ok(record) => {
                let LogEvent::Frame(frame) = record.event else {
                    panic!("MF4 has no status events");
                };
                assert!(matches!(frame.iface, None | Some(Iface::Channel(_))));
                let can = &frame.frame;
                if !can.is_fd() {
                    assert!(can.data().len() <= 8);
                }
                if can.is_rtr() {
                    assert!(can.data().is_empty());
                }
                out.push(format!("{} {frame}", record.position));
            }
            Err(e) => {
                check(&e);
                out.push(e.to_string());
                if !e.is_skipped() {
                    assert!(reader.next_event().is_none(), "events after the end");
                    break;
                }
            }
        }
        // Every event is paid for by bytes read: a record is at least a
        // byte of data, read from a DT or SD block or inflated from a DZ
        // block (deflate makes at most 1032 bytes of one), and there is at
        // most one error per record and one per data group more. Not
        // bounded by the file's length: a DZ block of compressible records
        // holds more records than the file has bytes.
        assert!(
            events <= 2 * 1032 * reader.bytes_read() + 16,
            "{events} events from {} bytes read",
            reader.bytes_read()
        );
    }
    let _ = (
        reader.other_records(),
        reader.other_groups(),
        reader.skipped(),
    );
    out
}

fn check(e: &LogError) {
    match e.kind() {
        LogErrorKind::Damaged(FormatError::Binary {
            format: LogFormat::Mf4,
            reason,
            ..
        })
        | LogErrorKind::Malformed(FormatError::Binary {
            format: LogFormat::Mf4,
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
    if data.len() < 4096 {
        let streamed = Mf4Reader::from_stream(data).map(|mut r| {
            let mut n = 0;
            while r.next_event().is_some() {
                n += 1;
            }
            n
        });
        if let Ok(n) = streamed {
            assert_eq!(n, whole.len());
        }
    }

    // Behind an identification block of version 4.11: the fuzzer's bytes
    // are the header and what it links.
    let mut file = b"MDF     4.11    fuzz".to_vec();
    file.resize(28, 0);
    file.extend_from_slice(&411u16.to_le_bytes());
    file.resize(64, 0);
    file.extend_from_slice(data);
    records(&file);
});
