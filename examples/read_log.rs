//! Read a log of any format of docs/formats.md through `logs::open` and count
//! its frames: the library's reading alone, without decoding (the MF4 read
//! measurement of BENCHMARKS.md runs it).
//!
//!     cargo run --release --example read_log --features logs -- FILE…

use motionwire::logs::{self, ReadLog};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for path in std::env::args().skip(1) {
        let mut log = logs::open(&path)?;
        let (mut frames, mut errors, mut bytes) = (0u64, 0u64, 0usize);
        while let Some(record) = log.next_event() {
            match record {
                Ok(record) => {
                    if let Some(frame) = record.event.frame() {
                        frames += 1;
                        bytes += frame.frame.data().len();
                    }
                }
                Err(_) => errors += 1,
            }
        }
        println!(
            "{path}: {} log, {frames} frames ({bytes} data bytes), {errors} errors, {} other records",
            log.format(),
            log.other_records()
        );
    }
    Ok(())
}
