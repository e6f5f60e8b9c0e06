//! Decoding speed of candump log text (SPEC §5).
//!
//! `candump/parse` runs `motionwire::candump::lines` over a generated log of
//! realistic CANopen traffic; `candump/byte_by_byte` runs a plain
//! byte-at-a-time parser of the same lines (written here as the baseline),
//! so that one run shows the ratio. Both read every field into a frame and
//! fold the frames into the same checksum, which is compared before timing.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use motionwire::candump;

/// Lines in the generated log.
const LINES: usize = 20_000;

/// A small deterministic generator (xorshift64*), so that every run times
/// the same log.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A candump `-l` log of CANopen traffic: PDOs, SDOs, heartbeats, EMCYs,
/// SYNC, node-guarding RTRs, some extended identifiers (J1939-like), a few
/// CAN FD frames and a few lines with a direction.
fn generate_log() -> Vec<u8> {
    use std::fmt::Write;

    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut out = String::with_capacity(LINES * 48);
    let mut micros: u64 = 1_700_000_000 * 1_000_000;
    for _ in 0..LINES {
        micros += 50 + rng.below(900);
        let iface = if rng.below(10) < 8 { "can0" } else { "can1" };
        let node = 1 + rng.below(127);
        let mut data = [0u8; 64];
        for b in data.iter_mut() {
            *b = rng.next() as u8;
        }
        let roll = rng.below(100);
        let (id, body): (String, String) = match roll {
            // TPDO/RPDO 1–4 with 2..8 bytes.
            0..=29 => {
                let base =
                    [0x180, 0x200, 0x280, 0x300, 0x380, 0x400, 0x480, 0x500][rng.below(8) as usize];
                let len = [2, 4, 6, 8, 8, 8][rng.below(6) as usize];
                (format!("{:03X}", base + node), hex(&data[..len]))
            }
            // SDO request / response, always 8 bytes.
            30..=49 => {
                let base = if rng.below(2) == 0 { 0x580 } else { 0x600 };
                (format!("{:03X}", base + node), hex(&data[..8]))
            }
            // Heartbeat: operational or pre-operational.
            50..=64 => {
                let state = if rng.below(4) == 0 { "7F" } else { "05" };
                (format!("{:03X}", 0x700 + node), state.to_string())
            }
            // EMCY, 8 bytes.
            65..=74 => (format!("{:03X}", 0x080 + node), hex(&data[..8])),
            // SYNC, no data.
            75..=79 => ("080".to_string(), String::new()),
            // Node guarding / remote PDO requests.
            80..=84 => {
                let body = if rng.below(2) == 0 { "R" } else { "R8" };
                (format!("{:03X}", 0x700 + node), body.to_string())
            }
            // Extended identifiers, 8 bytes.
            85..=96 => (
                format!("{:08X}", 0x18FF_0000 + rng.below(0xFFFF)),
                hex(&data[..8]),
            ),
            // CAN FD with BRS, 12..64 bytes.
            _ => {
                let len = [12, 16, 32, 64][rng.below(4) as usize];
                (
                    format!("{:03X}", 0x100 + node),
                    format!("#1{}", hex(&data[..len])),
                )
            }
        };
        let direction = match rng.below(20) {
            0 => " R",
            1 => " T",
            _ => "",
        };
        writeln!(
            out,
            "({}.{:06}) {iface} {id}#{body}{direction}",
            micros / 1_000_000,
            micros % 1_000_000
        )
        .expect("writing to a String");
    }
    out.into_bytes()
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect()
}

/// The frame the baseline parser produces: the same fields as
/// `CandumpFrame`.
struct PlainFrame<'a> {
    secs: u64,
    micros: u32,
    iface: &'a [u8],
    id: u32,
    extended: bool,
    rtr: bool,
    fd: bool,
    flags: u8,
    direction: u8,
    len: usize,
    data: [u8; 64],
}

fn nibble(b: u8) -> Option<u8> {
    match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'A'..=b'F' => Some(b - b'A' + 10),
        b'a'..=b'f' => Some(b - b'a' + 10),
        _ => None,
    }
}

/// The baseline: a plain parser of candump log lines that reads one byte
/// at a time with an index into the whole buffer, in one pass, as one
/// would write it without SWAR (no allocation, no UTF-8 validation, no
/// separate line split). Return the frame and the index after its line.
fn parse_byte_by_byte(buf: &[u8], start: usize) -> Option<(PlainFrame<'_>, usize)> {
    let mut i = start;
    if *buf.get(i)? != b'(' {
        return None;
    }
    i += 1;
    let mut secs: u64 = 0;
    let mut digits = 0;
    while let Some(&b @ b'0'..=b'9') = buf.get(i) {
        secs = secs * 10 + u64::from(b - b'0');
        digits += 1;
        i += 1;
    }
    if digits == 0 || digits > 19 || *buf.get(i)? != b'.' {
        return None;
    }
    i += 1;
    let mut micros: u32 = 0;
    let frac_start = i;
    while let Some(&b @ b'0'..=b'9') = buf.get(i) {
        micros = micros * 10 + u32::from(b - b'0');
        i += 1;
    }
    let frac_digits = i - frac_start;
    if frac_digits == 0 || frac_digits > 6 || *buf.get(i)? != b')' || *buf.get(i + 1)? != b' ' {
        return None;
    }
    for _ in frac_digits..6 {
        micros *= 10;
    }
    i += 2;
    let iface_start = i;
    while let Some(&b) = buf.get(i) {
        if b == b' ' {
            break;
        }
        if !b.is_ascii_graphic() {
            return None;
        }
        i += 1;
    }
    let iface = &buf[iface_start..i];
    if iface.is_empty() {
        return None;
    }
    i += 1;
    let id_start = i;
    let mut id: u32 = 0;
    while let Some(&b) = buf.get(i) {
        if b == b'#' {
            break;
        }
        id = id << 4 | u32::from(nibble(b)?);
        i += 1;
        if i - id_start > 8 {
            return None;
        }
    }
    let extended = match i - id_start {
        3 if id <= 0x7FF => false,
        8 if id <= 0x1FFF_FFFF => true,
        _ => return None,
    };
    i += 1;
    let mut frame = PlainFrame {
        secs,
        micros,
        iface,
        id,
        extended,
        rtr: false,
        fd: false,
        flags: 0,
        direction: 0,
        len: 0,
        data: [0; 64],
    };
    let mut max = 8;
    match buf.get(i) {
        Some(b'R' | b'r') => {
            frame.rtr = true;
            i += 1;
            if let Some(&b @ b'0'..=b'8') = buf.get(i) {
                frame.len = usize::from(b - b'0');
                i += 1;
            }
        }
        Some(b'#') => {
            frame.fd = true;
            frame.flags = nibble(*buf.get(i + 1)?)?;
            max = 64;
            i += 2;
        }
        _ => {}
    }
    if !frame.rtr {
        while let Some(hi) = buf.get(i).and_then(|&b| nibble(b)) {
            let lo = nibble(*buf.get(i + 1)?)?;
            if frame.len == max {
                return None;
            }
            frame.data[frame.len] = hi << 4 | lo;
            frame.len += 1;
            i += 2;
        }
    }
    if buf.get(i) == Some(&b' ') {
        match buf.get(i + 1) {
            Some(&d @ (b'R' | b'T')) => frame.direction = d,
            _ => return None,
        }
        i += 2;
    }
    match buf.get(i) {
        None => Some((frame, i)),
        Some(b'\n') => Some((frame, i + 1)),
        Some(b'\r') if buf.get(i + 1) == Some(&b'\n') => Some((frame, i + 2)),
        _ => None,
    }
}

/// Run the baseline over every line of `log`, skipping malformed lines.
fn for_each_byte_by_byte<'a>(log: &'a [u8], mut f: impl FnMut(&PlainFrame<'a>)) {
    let mut i = 0;
    while i < log.len() {
        match parse_byte_by_byte(log, i) {
            Some((frame, next)) => {
                f(&frame);
                i = next;
            }
            None => match log[i..].iter().position(|&b| b == b'\n') {
                Some(n) => i += n + 1,
                None => break,
            },
        }
    }
}

/// Fold a frame into a checksum that depends on every field.
fn fold(sum: u64, secs: u64, micros: u32, iface: &[u8], id: u32, flags: u64, data: &[u8]) -> u64 {
    let mut s = sum
        .wrapping_mul(31)
        .wrapping_add(secs ^ u64::from(micros) ^ u64::from(id));
    s = s.wrapping_add(iface.len() as u64 + flags);
    for &b in data {
        s = s.wrapping_mul(3).wrapping_add(u64::from(b));
    }
    s
}

fn checksum_motionwire(log: &[u8]) -> u64 {
    let mut sum = 0;
    for (_, result) in candump::lines(log) {
        if let Ok(Some(f)) = result {
            let ts = f.timestamp().unwrap_or_else(|| unreachable!());
            let flags = u64::from(f.is_extended())
                | u64::from(f.is_rtr()) << 1
                | u64::from(f.is_fd()) << 2
                | u64::from(f.fd_flags().bits()) << 3
                | u64::from(f.direction().map_or(0, |d| d.letter() as u8)) << 8
                | u64::from(f.dlc()) << 16;
            sum = fold(
                sum,
                ts.secs(),
                ts.micros(),
                f.iface(),
                f.id().raw(),
                flags,
                f.data(),
            );
        }
    }
    sum
}

fn checksum_byte_by_byte(log: &[u8]) -> u64 {
    let mut sum = 0;
    for_each_byte_by_byte(log, |f| {
        let dlc = if f.fd { fd_dlc(f.len) } else { f.len as u64 };
        let flags = u64::from(f.extended)
            | u64::from(f.rtr) << 1
            | u64::from(f.fd) << 2
            | u64::from(f.flags) << 3
            | u64::from(f.direction) << 8
            | dlc << 16;
        let data = if f.rtr { &[][..] } else { &f.data[..f.len] };
        sum = fold(sum, f.secs, f.micros, f.iface, f.id, flags, data);
    });
    sum
}

fn fd_dlc(len: usize) -> u64 {
    match len {
        0..=8 => len as u64,
        9..=12 => 9,
        13..=16 => 10,
        17..=20 => 11,
        21..=24 => 12,
        25..=32 => 13,
        33..=48 => 14,
        _ => 15,
    }
}

fn candump_parse(c: &mut Criterion) {
    let log = generate_log();
    // Both parsers must read the same frames before their speed means
    // anything.
    let frames = candump::lines(&log)
        .filter(|(_, r)| matches!(r, Ok(Some(_))))
        .count();
    assert_eq!(frames, LINES, "every generated line is a frame");
    assert_eq!(
        checksum_motionwire(&log),
        checksum_byte_by_byte(&log),
        "both parsers read the same frames"
    );

    // The timed consumer reads the fields of each frame and hands its data
    // to `black_box`, the same for both parsers, so that nothing the parser
    // decodes can be optimised away.
    let mut group = c.benchmark_group("candump");
    group.throughput(Throughput::Bytes(log.len() as u64));
    group.bench_function("parse", |b| {
        b.iter(|| {
            let mut sum = 0u64;
            candump::lines(black_box(&log)).for_each(|(_, result)| {
                if let Ok(Some(f)) = result {
                    let ts = f
                        .timestamp()
                        .map_or(0, |t| t.secs() ^ u64::from(t.micros()));
                    sum = sum.wrapping_add(
                        ts ^ u64::from(f.id().raw()) ^ u64::from(f.dlc()) ^ f.iface().len() as u64,
                    );
                    black_box(f.data());
                }
            });
            sum
        })
    });
    group.bench_function("byte_by_byte", |b| {
        b.iter(|| {
            let mut sum = 0u64;
            for_each_byte_by_byte(black_box(&log), |f| {
                let dlc = if f.fd { fd_dlc(f.len) } else { f.len as u64 };
                sum = sum.wrapping_add(
                    (f.secs ^ u64::from(f.micros)) ^ u64::from(f.id) ^ dlc ^ f.iface.len() as u64,
                );
                black_box(if f.rtr { &[][..] } else { &f.data[..f.len] });
            });
            sum
        })
    });
    group.finish();
}

criterion_group!(benches, candump_parse);
criterion_main!(benches);
