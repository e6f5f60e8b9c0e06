//! Reading a log through `motionwire::logs` (docs/formats.md) against parsing
//! the same text where it lies, in the same run. Run it with
//! `cargo bench --bench logs --features logs`; BENCHMARKS.md has the
//! numbers.
//!
//! The input is 100 000 lines of `samples/machine.log` (repeated: candump
//! `-l` lines of CANopen traffic, 3.7 MB), through `black_box`. Each
//! variant folds the same fields of every frame (time, identifier, length,
//! interface name's length) into the same checksum, compared before timing:
//!
//! - `logs/lines`: `logs::candump::lines` over the whole text in memory,
//!   the floor: no reading, no blocks, no positions;
//! - `logs/candump_reader`: `logs::candump::CandumpReader` reading the text
//!   through `std::io::Read`, 256 KiB at a time;
//! - `logs/read_next_event`: `logs::read` (detection, then the candump
//!   reader) and `ReadLog::next_event` on the `LogReader`, which picks the
//!   format's reader at each call;
//! - `logs/read_visit`: the same through `LogReader::visit`, whose loop is
//!   compiled for the candump reader.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use motionwire::can::{Iface, LogFrame};
use motionwire::logs::candump::{self, CandumpReader};
use motionwire::logs::{self, LogVisitor, ReadLog};

const LINES: usize = 100_000;

/// The sample log's lines, repeated up to [`LINES`].
fn text() -> Vec<u8> {
    let sample = include_str!("../samples/machine.log");
    let lines: Vec<&str> = sample.lines().filter(|l| l.starts_with('(')).collect();
    let mut out = Vec::new();
    for line in lines.iter().cycle().take(LINES) {
        out.extend_from_slice(line.as_bytes());
        out.push(b'\n');
    }
    out
}

#[inline(always)]
fn fold(sum: u64, frame: &LogFrame<'_>) -> u64 {
    let ts = frame
        .timestamp
        .map_or(0, |t| t.secs() ^ u64::from(t.micros()));
    let name = match frame.iface {
        Some(Iface::Name(name)) => name.len() as u64,
        _ => 0,
    };
    black_box(frame.frame.data());
    sum.wrapping_add(ts ^ u64::from(frame.frame.id().raw()) ^ u64::from(frame.frame.dlc()) ^ name)
}

fn by_lines(text: &[u8]) -> u64 {
    let mut sum = 0;
    for (_, parsed) in candump::lines(text) {
        if let Ok(Some(frame)) = parsed {
            sum = fold(sum, &frame);
        }
    }
    sum
}

fn drain<L: ReadLog + ?Sized>(log: &mut L) -> u64 {
    let mut sum = 0;
    while let Some(next) = log.next_event() {
        if let Ok(ref record) = next {
            if let Some(frame) = record.event.frame() {
                sum = fold(sum, frame);
            }
        }
    }
    sum
}

/// The fold as a visitor of the format's own reader.
struct Fold;

impl LogVisitor for Fold {
    type Output = u64;

    fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> u64 {
        drain(log)
    }
}

fn logs_group(c: &mut Criterion) {
    let text = text();
    let floor = by_lines(&text);
    assert_eq!(drain(&mut CandumpReader::new(&text[..])), floor);
    let owned = || std::io::Cursor::new(text.clone());
    assert_eq!(drain(&mut logs::read(owned()).unwrap()), floor);
    assert_eq!(logs::read(owned()).unwrap().visit(Fold), floor);

    let mut group = c.benchmark_group("logs");
    group.throughput(Throughput::Bytes(text.len() as u64));
    group.bench_function("lines", |b| b.iter(|| by_lines(black_box(&text))));
    group.bench_function("candump_reader", |b| {
        b.iter(|| drain(&mut CandumpReader::new(black_box(&text[..]))))
    });
    // The reader needs an input of its own (`'static`): a cursor over a
    // copy, made outside the timing.
    group.bench_function("read_next_event", |b| {
        b.iter_batched(
            owned,
            |input| drain(&mut logs::read(black_box(input)).unwrap()),
            criterion::BatchSize::LargeInput,
        )
    });
    group.bench_function("read_visit", |b| {
        b.iter_batched(
            owned,
            |input| logs::read(black_box(input)).unwrap().visit(Fold),
            criterion::BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, logs_group);
criterion_main!(benches);
