//! Read a log of any format of docs/formats.md through `logs::open` and count
//! its frames: the library's reading alone, without decoding (the MF4 read
//! measurement of BENCHMARKS.md runs it, and issue 21's account of where the
//! summary's time goes). The loop is compiled for the format's reader
//! (`LogReader::visit`), as the program's is, and every record is handed to
//! `std::hint::black_box`: a loop that reads two of a record's fields lets
//! the compiler drop the parsing of the others (the timestamp, the
//! interface, most data bytes), which then is not the library's reading
//! (callgrind, the sample's 100 000 candump lines: 273 instructions a line
//! without it, 394 with it).
//!
//!     cargo run --release --example read_log --features logs -- FILE…

use motionwire::logs::{self, LogVisitor, ReadLog};

/// Frames, their data bytes and the errors of a log.
struct Count;

impl LogVisitor for Count {
    type Output = (u64, usize, u64);

    fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> (u64, usize, u64) {
        let (mut frames, mut bytes, mut errors) = (0u64, 0usize, 0u64);
        while let Some(record) = log.next_event() {
            std::hint::black_box(&record);
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
        (frames, bytes, errors)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for path in std::env::args().skip(1) {
        let mut log = logs::open(&path)?;
        let (frames, bytes, errors) = log.visit(Count);
        println!(
            "{path}: {} log, {frames} frames ({bytes} data bytes), {errors} errors, {} other records",
            log.format(),
            log.other_records()
        );
    }
    Ok(())
}
