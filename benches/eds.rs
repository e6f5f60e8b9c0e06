//! Reading EDS and DCF files (docs/canopen.md#eds): the crate's hand-written
//! INI layer against the rust-ini crate in the same run. Run it with
//! `cargo bench --bench eds --features eds`; BENCHMARKS.md has the numbers.
//!
//! The input is the real DCF of a CiA 402 drive, `prbt_0_1.dcf` (2 052
//! lines; tests/fixtures/eds/README.md), through `black_box`:
//!
//! - `eds/ini_motionwire`: `motionwire::eds::IniFile::parse`, then every
//!   section's entries (key, value, line) folded into a checksum;
//! - `eds/ini_rust_ini`: `ini::Ini::load_from_str_opt` (quotes and escapes
//!   off, as CiA 306 has none; features `case-insensitive` and
//!   `inline-comment`), then the same fold without line numbers, which
//!   rust-ini does not keep;
//! - `eds/parse`: the whole reader, `Eds::parse` (objects, names, typed
//!   values, `$NODEID`) and `Eds::pdos` (communication and mapping of every
//!   PDO with its signals' names and types).
//!
//! Both INI readers must find the same sections, keys and values (checked
//! before timing).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use ini::{Ini, ParseOption};
use motionwire::canopen::NodeId;
use motionwire::eds::{Eds, IniFile};

const DCF: &str = include_str!("../tests/fixtures/eds/prbt_0_1.dcf");

/// Sections, entries and value bytes, as (sections, entries, bytes).
fn fold_motionwire(text: &str) -> (usize, usize, usize, usize) {
    let ini = IniFile::parse(text).expect("the fixture is valid");
    let mut sum = (0, 0, 0, 0);
    for section in ini.sections() {
        sum.0 += 1;
        for entry in &section.entries {
            sum.1 += 1;
            sum.2 += entry.key.len() + entry.value.len();
            sum.3 += entry.line;
        }
    }
    sum
}

fn fold_rust_ini(text: &str) -> (usize, usize, usize) {
    let option = ParseOption {
        enabled_quote: false,
        enabled_escape: false,
        ..ParseOption::default()
    };
    let ini = Ini::load_from_str_opt(text, option).expect("the fixture is valid");
    let mut sum = (0, 0, 0);
    for (name, properties) in ini.iter() {
        if name.is_none() {
            continue;
        }
        sum.0 += 1;
        for (key, value) in properties.iter() {
            sum.1 += 1;
            sum.2 += key.len() + value.len();
        }
    }
    sum
}

fn eds(c: &mut Criterion) {
    let (sections, entries, bytes, _) = fold_motionwire(DCF);
    assert_eq!(
        fold_rust_ini(DCF),
        (sections, entries, bytes),
        "the readers agree"
    );
    let eds = Eds::parse(DCF, "prbt_0_1.dcf", NodeId::new(3)).unwrap();
    assert_eq!(eds.pdos().unwrap().len(), 6);

    let mut group = c.benchmark_group("eds");
    group.throughput(Throughput::Bytes(DCF.len() as u64));
    group.bench_function("ini_motionwire", |b| {
        b.iter(|| fold_motionwire(black_box(DCF)))
    });
    group.bench_function("ini_rust_ini", |b| b.iter(|| fold_rust_ini(black_box(DCF))));
    group.bench_function("parse", |b| {
        b.iter(|| {
            let eds = Eds::parse(black_box(DCF), "prbt_0_1.dcf", NodeId::new(3)).unwrap();
            eds.pdos().unwrap().len()
        })
    });
    group.finish();
}

criterion_group!(benches, eds);
criterion_main!(benches);
