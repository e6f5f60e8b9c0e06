//! Unpacking PDO payloads with a mapping (docs/canopen.md#signals). Run it with
//! `cargo bench --bench pdo`; BENCHMARKS.md has the numbers.
//!
//! 1024 payloads of a CiA 402 drive's TPDO — statusword 6041h (16 bits),
//! modes of operation display 6061h (INTEGER8), position actual value
//! 6064h (INTEGER32), and an 8-bit field split into a 1-bit flag and 7
//! bits — generated deterministically, through `black_box`. Each variant
//! folds the same five values into the same checksum (compared before
//! timing):
//!
//! - `copy`: the floor — read the fields with `from_le_bytes` at their
//!   fixed offsets (what code generated for this one mapping would do);
//! - `byteorder_cursor`: the usual hand-written decoder for one fixed
//!   layout, `byteorder::ReadBytesExt` on a `std::io::Cursor`;
//! - `unpack`: `PdoMapping::unpack_with` with the types from a closure —
//!   the mapping known only at run time, as from an EDS or a log's SDOs.

use std::hint::black_box;
use std::io::Cursor;

use byteorder::{LittleEndian, ReadBytesExt};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use motionwire::canopen::{DataType, MappingEntry, PdoMapping, Value};

const PAYLOADS: usize = 1024;
const LEN: usize = 8;

fn payloads() -> Vec<u8> {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut out = Vec::with_capacity(PAYLOADS * LEN);
    for i in 0..PAYLOADS {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let status: u16 = [0x0237, 0x0233, 0x0250, 0x0218][i % 4];
        let mode: i8 = [1, 3, 8, -1][(state % 4) as usize];
        let position = (state >> 20) as i32;
        out.extend_from_slice(&status.to_le_bytes());
        out.push(mode as u8);
        out.extend_from_slice(&position.to_le_bytes());
        out.push(state as u8);
    }
    out
}

fn mapping() -> PdoMapping {
    PdoMapping::from_u32s(&[
        0x6041_0010,
        0x6061_0008,
        0x6064_0020,
        0x2000_0101,
        0x2000_0207,
    ])
    .unwrap()
}

fn types(entry: MappingEntry) -> Option<DataType> {
    match entry.index() {
        0x6041 => Some(DataType::Unsigned16),
        0x6061 => Some(DataType::Integer8),
        0x6064 => Some(DataType::Integer32),
        _ => None,
    }
}

fn copy(data: &[u8]) -> i64 {
    let mut sum = 0i64;
    for p in data.chunks_exact(LEN) {
        sum += i64::from(u16::from_le_bytes([p[0], p[1]]));
        sum += i64::from(p[2] as i8);
        sum += i64::from(i32::from_le_bytes([p[3], p[4], p[5], p[6]]));
        sum += i64::from(p[7] & 1);
        sum += i64::from(p[7] >> 1);
    }
    sum
}

fn byteorder_cursor(data: &[u8]) -> i64 {
    let mut sum = 0i64;
    for p in data.chunks_exact(LEN) {
        let mut c = Cursor::new(p);
        sum += i64::from(c.read_u16::<LittleEndian>().unwrap());
        sum += i64::from(c.read_i8().unwrap());
        sum += i64::from(c.read_i32::<LittleEndian>().unwrap());
        let last = c.read_u8().unwrap();
        sum += i64::from(last & 1) + i64::from(last >> 1);
    }
    sum
}

fn unpack(mapping: &PdoMapping, data: &[u8]) -> i64 {
    let mut sum = 0i64;
    for p in data.chunks_exact(LEN) {
        for signal in mapping.unpack_with(p, types) {
            sum += match signal.unwrap().value {
                Value::Bool(b) => i64::from(b),
                Value::Signed(v) => v,
                Value::Unsigned(v) => v as i64,
                _ => 0,
            };
        }
    }
    sum
}

fn pdo(c: &mut Criterion) {
    let data = payloads();
    let mapping = mapping();
    let want = copy(&data);
    assert_eq!(byteorder_cursor(&data), want);
    assert_eq!(unpack(&mapping, &data), want);

    let mut group = c.benchmark_group("pdo");
    group.throughput(Throughput::Elements(PAYLOADS as u64));
    group.bench_function("copy", |b| b.iter(|| copy(black_box(&data))));
    group.bench_function("byteorder_cursor", |b| {
        b.iter(|| byteorder_cursor(black_box(&data)))
    });
    group.bench_function("unpack", |b| {
        b.iter(|| unpack(black_box(&mapping), black_box(&data)))
    });
    group.finish();
}

criterion_group!(benches, pdo);
criterion_main!(benches);
