//! The decoder session and the post-mortem (docs/output.md, docs/summary.md) on
//! four traffic mixes, against the stateless floors in the same run. Run it
//! with `cargo bench --features decoder --bench session`; BENCHMARKS.md has
//! the numbers.
//!
//! Mixes (frames generated deterministically, or the repository's sample):
//! - `sample`: `samples/machine.log` (3 765 frames: a drive configured by
//!   SDO at boot, its PDOs, an encoder, heartbeats, guarding, EMCYs);
//! - `emcy_storm`: 30 % EMCY from 127 nodes with random codes, registers
//!   and manufacturer bytes, 20 % heartbeats in every state, 5 % SYNC, 45 %
//!   TPDO1 of random lengths 0–8 (the performance issue's mix);
//! - `pdo_drives`: four CiA 402 drives whose TPDO1/RPDO1 mappings are
//!   written by SDO at the start, then PDOs at 1 kHz (statusword and
//!   position; controlword and target);
//! - `sdo_boot`: SDO only — expedited and segmented uploads and downloads
//!   of 32 nodes, answered, some aborted.
//!
//! Variants, each over every frame of the mix:
//! - `classify`: the floor any decoder pays — the kind and node of each
//!   frame from its identifier;
//! - `message`: the stateless decode, `CanOpenMessage::decode`;
//! - `decoder`: `Decoder::decode` with signals (what `decode --json`
//!   needs);
//! - `decoder_json`: the same and each record written as JSON into a
//!   reused buffer (`decode --json` without the I/O);
//! - `summary`: a lean `Decoder` (no signals) feeding a `Summarizer`, and
//!   the `Summary` at the end (`decode --summary` without the I/O).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use motionwire::can::{CanFrame, CanId, Iface, LogEvent, LogFrame, Timestamp};
use motionwire::canopen::{CanOpenMessage, MessageKind, NodeId};
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::logs::Position;
use motionwire::profiles::Profile;
use motionwire::summary::Summarizer;

/// A small xorshift generator: the same frames on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

fn frame(us: u64, id: u32, data: &[u8]) -> LogFrame<'static> {
    LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
        .with_timestamp(Timestamp::from_duration(std::time::Duration::from_micros(
            us,
        )))
        .with_iface(Iface::Name("can0"))
}

fn sample() -> Vec<LogFrame<'static>> {
    let text = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/samples/machine.log")).unwrap();
    let text: &'static [u8] = Box::leak(text.into_boxed_slice());
    text.split(|&b| b == b'\n')
        .filter_map(|line| motionwire::logs::candump::parse_line(line).ok().flatten())
        .collect()
}

fn emcy_storm(n: usize) -> Vec<LogFrame<'static>> {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    (0..n as u64)
        .map(|i| {
            let node = 1 + rng.below(127) as u32;
            let r = rng.below(100);
            let mut data = [0u8; 8];
            for b in &mut data {
                *b = rng.next() as u8;
            }
            if r < 30 {
                frame(100 * i, 0x080 + node, &data)
            } else if r < 50 {
                let state = [0x00, 0x04, 0x05, 0x7F][rng.below(4) as usize];
                frame(100 * i, 0x700 + node, &[state])
            } else if r < 55 {
                frame(100 * i, 0x080, &[])
            } else {
                let len = rng.below(9) as usize;
                frame(100 * i, 0x180 + node, &data[..len])
            }
        })
        .collect()
}

/// SDO writes of a mapping object: sub 0 = 0, the entries, sub 0 = n, each
/// answered.
fn map_by_sdo(out: &mut Vec<LogFrame<'static>>, node: u32, index: u16, entries: &[u32]) {
    let mut write = |sub: u8, value: u32, cmd: u8| {
        let [lo, hi] = index.to_le_bytes();
        let v = value.to_le_bytes();
        let us = out.len() as u64 * 200;
        out.push(frame(
            us,
            0x600 + node,
            &[cmd, lo, hi, sub, v[0], v[1], v[2], v[3]],
        ));
        out.push(frame(
            us + 100,
            0x580 + node,
            &[0x60, lo, hi, sub, 0, 0, 0, 0],
        ));
    };
    write(0, 0, 0x2F);
    for (i, &entry) in entries.iter().enumerate() {
        write(i as u8 + 1, entry, 0x23);
    }
    write(0, entries.len() as u32, 0x2F);
}

fn pdo_drives(n: usize) -> Vec<LogFrame<'static>> {
    let mut out = Vec::with_capacity(n);
    for node in 1..=4 {
        map_by_sdo(&mut out, node, 0x1A00, &[0x6041_0010, 0x6064_0020]);
        map_by_sdo(&mut out, node, 0x1600, &[0x6040_0010, 0x607A_0020]);
    }
    let mut rng = Rng(42);
    let mut cycle = 0u64;
    while out.len() < n {
        for node in 1..=4u32 {
            let position = (rng.next() as i32).to_le_bytes();
            let sw: u16 = [0x0237, 0x0233, 0x0231, 0x0208][(cycle / 1000 % 4) as usize];
            let [s0, s1] = sw.to_le_bytes();
            let us = 1000 * cycle + u64::from(node) * 10;
            out.push(frame(
                us,
                0x180 + node,
                &[s0, s1, position[0], position[1], position[2], position[3]],
            ));
            out.push(frame(
                us + 5,
                0x200 + node,
                &[
                    0x0F,
                    0x00,
                    position[0],
                    position[1],
                    position[2],
                    position[3],
                ],
            ));
        }
        cycle += 1;
    }
    out.truncate(n);
    out
}

fn sdo_boot(n: usize) -> Vec<LogFrame<'static>> {
    let mut out = Vec::with_capacity(n);
    let mut rng = Rng(7);
    while out.len() < n {
        let node = 1 + rng.below(32) as u32;
        let us = out.len() as u64 * 300;
        match rng.below(4) {
            // An expedited read.
            0 => {
                out.push(frame(
                    us,
                    0x600 + node,
                    &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0],
                ));
                out.push(frame(
                    us + 100,
                    0x580 + node,
                    &[0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00],
                ));
            }
            // An expedited write.
            1 => {
                out.push(frame(
                    us,
                    0x600 + node,
                    &[0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0, 0],
                ));
                out.push(frame(
                    us + 100,
                    0x580 + node,
                    &[0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0],
                ));
            }
            // A segmented read of 20 bytes.
            2 => {
                out.push(frame(
                    us,
                    0x600 + node,
                    &[0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0],
                ));
                out.push(frame(
                    us + 100,
                    0x580 + node,
                    &[0x41, 0x08, 0x10, 0x00, 20, 0, 0, 0],
                ));
                for (i, last) in [(0u8, false), (1, false), (0, true)] {
                    let t = i << 4;
                    out.push(frame(
                        us + 200,
                        0x600 + node,
                        &[0x60 | t, 0, 0, 0, 0, 0, 0, 0],
                    ));
                    let cmd = if last { t | (1 << 1) | 1 } else { t };
                    out.push(frame(
                        us + 300,
                        0x580 + node,
                        &[cmd, b'm', b'o', b't', b'i', b'o', b'n', b'w'],
                    ));
                }
            }
            // A read the server aborts.
            _ => {
                out.push(frame(
                    us,
                    0x600 + node,
                    &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0],
                ));
                out.push(frame(
                    us + 100,
                    0x580 + node,
                    &[0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06],
                ));
            }
        }
    }
    out.truncate(n);
    out
}

fn config() -> DecoderConfig {
    let mut config = DecoderConfig::new();
    for node in 1..=4 {
        config = config.node_profile(NodeId::new(node).unwrap(), Profile::Akd);
    }
    config
}

fn session(c: &mut Criterion) {
    const N: usize = 20_000;
    let mixes = [
        ("sample", sample()),
        ("emcy_storm", emcy_storm(N)),
        ("pdo_drives", pdo_drives(N)),
        ("sdo_boot", sdo_boot(N)),
    ];
    for (mix, frames) in &mixes {
        let mut group = c.benchmark_group(format!("session/{mix}"));
        group.throughput(Throughput::Elements(frames.len() as u64));
        group.bench_function("classify", |b| {
            b.iter(|| {
                let mut sum = 0usize;
                for f in black_box(frames) {
                    let (kind, node) = MessageKind::classify(&f.frame);
                    sum += kind.index() + node.map_or(0, |n| usize::from(n.get()));
                }
                sum
            })
        });
        group.bench_function("message", |b| {
            b.iter(|| {
                let mut ok = 0usize;
                for f in black_box(frames) {
                    ok += usize::from(CanOpenMessage::decode(&f.frame).is_ok());
                }
                ok
            })
        });
        group.bench_function("decoder", |b| {
            b.iter(|| {
                let mut decoder = Decoder::new(config());
                let mut seen = 0usize;
                for (i, f) in black_box(frames).iter().enumerate() {
                    let d = decoder.decode(Position::Line(i as u64 + 1), f);
                    seen += usize::from(d.sdo.is_some()) + usize::from(d.pdo.is_some());
                }
                seen
            })
        });
        group.bench_function("decoder_json", |b| {
            let mut out = Vec::with_capacity(1 << 20);
            b.iter(|| {
                let mut decoder = Decoder::new(config());
                out.clear();
                for (i, f) in black_box(frames).iter().enumerate() {
                    decoder
                        .decode(Position::Line(i as u64 + 1), f)
                        .write_json(&mut out)
                        .unwrap();
                }
                out.len()
            })
        });
        group.bench_function("summary", |b| {
            b.iter(|| {
                let mut summarizer = Summarizer::new(
                    config()
                        .signals(false)
                        .heartbeat_timeout(std::time::Duration::from_millis(100)),
                );
                for (i, f) in black_box(frames).iter().enumerate() {
                    summarizer.add(
                        motionwire::logs::Position::Line(i as u64 + 1),
                        &LogEvent::Frame(*f),
                    );
                }
                summarizer.finish().nodes.len()
            })
        });
        group.finish();
    }
}

criterion_group!(benches, session);
criterion_main!(benches);
