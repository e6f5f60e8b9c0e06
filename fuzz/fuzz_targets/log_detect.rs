//! Log format detection (docs/formats.md#detection): arbitrary bytes →
//! `logs::detect`. Invariants:
//! - nothing panics;
//! - a decision on a complete input is never `NeedMore`;
//! - the binary magics decide on the first four bytes alone, and gzip on
//!   the first two, whatever follows;
//! - a text decided as candump has a first deciding line that candump's
//!   own parser reads as a frame;
//! - deciding on more bytes never changes a decision made on fewer, except
//!   `NeedMore` (and `Empty` → anything, once more lines arrive).
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::logs::LogFormat;
use motionwire::logs::{detect, Detected};

fuzz_target!(|data: &[u8]| {
    let whole = detect(data, true);
    assert_ne!(whole, Detected::NeedMore, "{data:?}");
    if data.starts_with(&[0x1f, 0x8b]) {
        assert_eq!(whole, Detected::Gzip);
    }
    if data.starts_with(b"LOGG") {
        assert_eq!(whole, Detected::Format(LogFormat::Blf));
    }
    if whole == Detected::Format(LogFormat::Candump) {
        let deciding = data
            .split(|&b| b == b'\n')
            .find(|line| matches!(motionwire::logs::candump::parse_line(line), Ok(Some(_))));
        assert!(deciding.is_some(), "candump without a frame line: {data:?}");
    }
    // A prefix that decides decides the same as the whole.
    for cut in [1, 4, 16, data.len() / 2] {
        let Some(prefix) = data.get(..cut) else {
            continue;
        };
        match detect(prefix, false) {
            Detected::NeedMore => {}
            early => assert_eq!(early, whole, "prefix {cut} of {data:?}"),
        }
    }
});
