//! Issue 21: would reading the log on the second core pay? A measurement,
//! not part of the crate (BENCHMARKS.md, "Issue 21: the account").
//!
//! The text readers read their input in blocks with `read()` on the thread
//! that parses it: the copy from the page cache is system time on that
//! thread (`cat LOG` shows it: 5–10 ms for the 1 000 000-frame mixes). This
//! program compares, on one file:
//!
//! - `one`: blocks read and then scanned on one thread;
//! - `two`: blocks read on a second thread and handed over, full, through a
//!   bounded channel (4 blocks in flight, recycled), scanned on the first.
//!
//! The scan stands in for the parse: it touches every byte a word at a
//! time (a sum and a count of line ends), so what `two` can save is the
//! read's system time, and what it costs is the hand-over and the bytes
//! arriving from the other core's cache. Both print the same two numbers,
//! which the caller compares.
//!
//! Build and run (no dependencies):
//!
//!     rustc -O --edition 2021 bench/read_offload.rs -o /tmp/read_offload
//!     hyperfine -N --warmup 5 --runs 60 \
//!         '/tmp/read_offload one /tmp/motionwire-bench/mixes/sample.log 1048576' \
//!         '/tmp/read_offload two /tmp/motionwire-bench/mixes/sample.log 1048576'

use std::fs::File;
use std::io::Read;
use std::sync::mpsc::sync_channel;
use std::thread;

/// What the scan finds: line ends, and a sum of the bytes as words.
#[derive(Debug, Default, PartialEq, Eq)]
struct Scan {
    lines: u64,
    sum: u64,
}

impl Scan {
    fn add(&mut self, block: &[u8]) {
        const ONES: u64 = 0x0101_0101_0101_0101;
        for chunk in block.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            let x = u64::from_le_bytes(word);
            self.sum = self.sum.wrapping_add(x);
            // The lanes that hold b'\n' (a zero after the XOR); a zero
            // byte of a short last chunk is not one.
            let n = x ^ (ONES * u64::from(b'\n'));
            let zero = n.wrapping_sub(ONES) & !n & (ONES << 7);
            let valid = if chunk.len() == 8 {
                u64::MAX
            } else {
                (1u64 << (8 * chunk.len())) - 1
            };
            self.lines += u64::from((zero & valid).count_ones());
        }
    }
}

/// Fill `buf` from `file` as far as it goes; the bytes read.
fn fill(file: &mut File, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match file.read(&mut buf[n..])? {
            0 => break,
            r => n += r,
        }
    }
    Ok(n)
}

fn one(path: &str, block: usize) -> std::io::Result<Scan> {
    let mut file = File::open(path)?;
    let mut buf = vec![0u8; block];
    let mut scan = Scan::default();
    loop {
        let n = fill(&mut file, &mut buf)?;
        if n == 0 {
            return Ok(scan);
        }
        scan.add(&buf[..n]);
    }
}

fn two(path: &str, block: usize) -> std::io::Result<Scan> {
    const IN_FLIGHT: usize = 4;
    let mut file = File::open(path)?;
    let (full_tx, full_rx) = sync_channel::<std::io::Result<(Vec<u8>, usize)>>(IN_FLIGHT);
    let (empty_tx, empty_rx) = sync_channel::<Vec<u8>>(IN_FLIGHT);
    for _ in 0..IN_FLIGHT {
        empty_tx.send(vec![0u8; block]).expect("the channel holds them");
    }
    let reader = thread::spawn(move || {
        while let Ok(mut buf) = empty_rx.recv() {
            let read = fill(&mut file, &mut buf);
            let end = !matches!(read, Ok(n) if n > 0);
            if full_tx.send(read.map(|n| (buf, n))).is_err() || end {
                return;
            }
        }
    });
    let mut scan = Scan::default();
    while let Ok(read) = full_rx.recv() {
        let (buf, n) = read?;
        if n == 0 {
            break;
        }
        scan.add(&buf[..n]);
        // The reader may have ended: a block it does not take back is dropped.
        let _ = empty_tx.send(buf);
    }
    drop(empty_tx);
    reader.join().expect("the reading thread does not panic");
    Ok(scan)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(mode), Some(path)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: read_offload one|two FILE [BLOCK_BYTES]");
        std::process::exit(2);
    };
    let block = args.get(3).map_or(1 << 20, |b| b.parse().expect("a block size in bytes"));
    let scan = match mode.as_str() {
        "one" => one(path, block),
        "two" => two(path, block),
        _ => {
            eprintln!("usage: read_offload one|two FILE [BLOCK_BYTES]");
            std::process::exit(2);
        }
    };
    match scan {
        Ok(scan) => println!("{} lines, sum {:#x}", scan.lines, scan.sum),
        Err(e) => {
            eprintln!("read_offload: {path}: {e}");
            std::process::exit(1);
        }
    }
}
