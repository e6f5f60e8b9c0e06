//! One way to read any log (docs/formats.md): arbitrary bytes →
//! `logs::read` (the format detected, or forced; gzip-compressed or not;
//! candump's relative timestamps decided or given), once over the whole
//! input and once through a reader that hands out a few bytes per call.
//! Invariants:
//! - nothing panics, and the reading ends;
//! - an input that cannot be opened is one error that is not "skipped", with
//!   no position;
//! - every event and every error after opening has a position, and the
//!   positions strictly increase (lines of a text log, records of a binary
//!   one: never both);
//! - after an error that is not "skipped" (I/O, damaged binary structure)
//!   the reader ends; `next_event` returns `None` after the end;
//! - the reader's counter of skipped lines and records is the number of
//!   skipped errors it handed on; it never reads more bytes than the input
//!   has (gzip aside);
//! - both readings hand on the same events and errors: nothing depends on
//!   how the input arrives.
#![no_main]

use std::io::{Cursor, Read, Write};

use libfuzzer_sys::fuzz_target;
use motionwire::logs::candump::RelativeTimestamps;
use motionwire::logs::{LogFormat, Position, ReadLog, ReadOptions};

/// A reader that hands out `step` bytes per call.
struct Chunked {
    data: Vec<u8>,
    at: usize,
    step: usize,
}

impl Read for Chunked {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let rest = self.data.get(self.at..).unwrap_or_default();
        let n = self.step.min(buf.len()).min(rest.len());
        buf[..n].copy_from_slice(&rest[..n]);
        self.at += n;
        Ok(n)
    }
}

/// What the reading handed on: each event or error as text, with its
/// position.
type Outcome = Result<Vec<(Position, String)>, String>;

fn read_all<R: Read + Send + 'static>(
    options: ReadOptions,
    input: R,
    len: usize,
    gzip: bool,
) -> Outcome {
    let mut log = match options.read(input) {
        Ok(log) => log,
        Err(e) => {
            assert!(!e.is_skipped());
            assert_eq!(e.position(), None);
            return Err(e.to_string());
        }
    };
    assert_eq!(log.is_gzip(), gzip);
    let mut items: Vec<(Position, String)> = Vec::new();
    let mut skipped = 0;
    let mut ended = false;
    while let Some(next) = log.next_event() {
        assert!(!ended, "an item after an error that ends the input");
        let (position, text) = match next {
            Ok(record) => (record.position, format!("{:?}", record.event)),
            Err(e) => {
                if e.is_skipped() {
                    skipped += 1;
                } else {
                    ended = true;
                }
                let position = e.position().expect("errors after opening have a position");
                (position, e.to_string())
            }
        };
        if let Some((last, _)) = items.last() {
            assert_eq!(
                matches!(last, Position::Line(_)),
                matches!(position, Position::Line(_)),
                "lines and records mixed"
            );
            assert!(
                last.number() < position.number(),
                "{last:?} then {position:?}"
            );
        }
        assert!(position.number() >= 1);
        items.push((position, text));
    }
    assert!(log.next_event().is_none());
    assert_eq!(log.skipped(), skipped);
    if !gzip {
        assert!(log.bytes_read() <= len as u64);
    }
    Ok(items)
}

fuzz_target!(|data: &[u8]| {
    // The first byte chooses how to read the rest.
    let Some((&how, bytes)) = data.split_first() else {
        return;
    };
    let mut options = ReadOptions::new();
    if how & 0x08 != 0 {
        let format = LogFormat::ALL[usize::from(how & 0x07) % LogFormat::ALL.len()];
        options = options.format(format);
    }
    match (how >> 4) & 0x03 {
        1 => options = options.relative_timestamps(RelativeTimestamps::Delta),
        2 => options = options.relative_timestamps(RelativeTimestamps::Zero),
        _ => {}
    }
    let gzip = how & 0x40 != 0;
    let input = if gzip {
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        gz.write_all(bytes).unwrap();
        gz.finish().unwrap()
    } else {
        bytes.to_vec()
    };
    // What the reader inflates: the stream made here, or one the input is.
    let inflated = gzip || bytes.starts_with(&[0x1f, 0x8b]);
    let whole = read_all(options, Cursor::new(input.clone()), input.len(), inflated);
    let step = usize::from(how >> 6) * 5 + 1;
    let len = input.len();
    let chunked = read_all(
        options,
        Chunked {
            data: input,
            at: 0,
            step,
        },
        len,
        inflated,
    );
    assert_eq!(whole, chunked);
});
