//! Decoding speed of the hot paths: the servo frames (docs/servo.md), the EMCY
//! (docs/canopen.md#emcy) and candump log text (docs/formats.md#candump-log).
//! Run it with `cargo bench --bench decode`; BENCHMARKS.md has the numbers.
//!
//! Every frame group decodes a buffer of [`FRAMES`] frames per iteration,
//! with varied, realistic contents generated deterministically, and times
//! five ways of reading the same fields:
//!
//! - `copy`: copy each frame into an output array and read its words as
//!   they lie in memory (native byte order, no decoding at all): the
//!   physical floor;
//! - `view`: every field through the zero-copy view (`FeedbackFrame`, …);
//! - `owned`: the owned value (`Feedback::parse`, …);
//! - `byteorder_cursor`: the common hand-written alternative, a
//!   `byteorder::ReadBytesExt` reader over a `std::io::Cursor`, one `?` per
//!   field, into a plain struct;
//! - `deku`: the common derive-based alternative, a `#[derive(DekuRead)]`
//!   little-endian struct of the same layout.
//!
//! Each variant folds the same fields into the same checksum (the sums of
//! `fold_*`), and the checksums of all variants are compared before
//! anything is timed. The input goes through `black_box`, and the checksum
//! is returned from the timed closure, which criterion passes to
//! `black_box`, so nothing can be optimised away. `emcy8/describe` also
//! looks up each code's description and class.
//!
//! The candump groups run over a generated log of realistic CANopen
//! traffic: `candump/parse` parses every line with
//! `motionwire::logs::candump::lines`, `candump/byte_by_byte` is a plain
//! byte-at-a-time parser of the same lines (written here as the baseline),
//! and `candump/decode` does the library-level work of `motionwire decode`
//! without the output: parse, decode each frame once with
//! `CanOpenMessage::decode` (identifier classified, EMCY and heartbeat
//! payloads decoded), look up each EMCY code's class and description.

use std::hint::black_box;
use std::io::Cursor;

use byteorder::{LittleEndian, ReadBytesExt};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use deku::prelude::*;
use motionwire::can::{Iface, LogFrame};
use motionwire::canopen::{CanOpenMessage, Emcy, EmcyFrame, ErrorCode, NmtState, EMCY_LEN};
use motionwire::logs::candump;
use motionwire::servo::{
    Command, CommandFrame, Feedback, FeedbackFrame, COMMAND_LEN, FEEDBACK_LEN,
};

/// Frames per buffer in the frame groups.
const FRAMES: usize = 1024;

/// A small deterministic generator (xorshift64*), so that every run times
/// the same inputs.
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

    /// A value in `centre ± spread`.
    fn around(&mut self, centre: f32, spread: f32) -> f32 {
        let unit = (self.next() >> 40) as f32 / (1u64 << 24) as f32;
        centre + spread * (2.0 * unit - 1.0)
    }
}

/// The bytes at `at..at + N` of a frame copied into an array.
#[inline(always)]
fn take<const N: usize, const L: usize>(frame: &[u8; L], at: usize) -> [u8; N] {
    let mut out = [0; N];
    out.copy_from_slice(&frame[at..at + N]);
    out
}

// ------------------------------------------------------- feedback, 40 bytes

/// `FRAMES` feedback frames of 8 axes, one after the other as a master
/// would collect them over successive cycles: incremental and absolute
/// encoders, positions and zero pulses moving, status words of enabled
/// axes in various parameter tables, a rare fault, the message channel
/// cycling through speed, current, relative current, bus voltage and
/// temperature, and the extra data carrying floats.
fn feedback_frames() -> Vec<u8> {
    let mut rng = Rng(0x51ED_2701_F00D_BEEF);
    let mut out = Vec::with_capacity(FRAMES * FEEDBACK_LEN);
    let mut positions = [0i64; 8];
    for (axis, p) in positions.iter_mut().enumerate() {
        *p = (axis as i64 + 1) * 1_000_003;
    }
    for i in 0..FRAMES {
        let axis = i % 8;
        let incremental = axis < 5;
        positions[axis] += rng.below(4_000) as i64 - 1_500;
        let position = if incremental {
            let zero_pulse = (positions[axis] as i32) & !0xFFF;
            (i64::from(zero_pulse) << 32) | i64::from(positions[axis] as u32)
        } else {
            positions[axis] << 12 | rng.below(4096) as i64
        };
        let mut status: u32 = 0b11 | 1 << 7 | ((axis as u32 % 4) << 8);
        if incremental {
            status |= 1 << 2 | 1 << 3;
        }
        if rng.below(8) == 0 {
            status |= 1 << 5;
        }
        if rng.below(100) == 0 {
            status |= 1 << 11;
        }
        let errors: u32 = match rng.below(64) {
            0 => 1 | 1 << 5,
            1 => 1 | 1 << 19,
            _ => 0,
        };
        let code = (i / 8 % 5) as i32;
        let data = match code {
            0 => rng.around(1500.0, 300.0),
            1 => rng.around(4.2, 1.5),
            2 => rng.around(35.0, 20.0),
            3 => rng.around(560.0, 8.0),
            _ => rng.around(45.0, 10.0),
        };
        let extra = [
            rng.around(0.0, 1.0),
            rng.around(100.0, 50.0),
            rng.around(-3.0, 3.0),
            if rng.below(4) == 0 {
                0.0
            } else {
                rng.around(1.0, 0.1)
            },
        ];
        out.extend_from_slice(&position.to_le_bytes());
        out.extend_from_slice(&status.to_le_bytes());
        out.extend_from_slice(&errors.to_le_bytes());
        out.extend_from_slice(&code.to_le_bytes());
        out.extend_from_slice(&data.to_le_bytes());
        for x in extra {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    out
}

/// Fold the fields of one feedback frame into the checksum: the sum of
/// every field (floats by their bits).
#[inline(always)]
fn fold_feedback(
    acc: u64,
    position: i64,
    status: u32,
    errors: u32,
    code: i32,
    data: f32,
    extra: [f32; 4],
) -> u64 {
    let [e0, e1, e2, e3] = extra.map(|x| u64::from(x.to_bits()));
    acc.wrapping_add(position as u64)
        .wrapping_add(u64::from(status))
        .wrapping_add(u64::from(errors))
        .wrapping_add(i64::from(code) as u64)
        .wrapping_add(u64::from(data.to_bits()))
        .wrapping_add(e0)
        .wrapping_add(e1)
        .wrapping_add(e2)
        .wrapping_add(e3)
}

#[inline(never)]
fn feedback_copy(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(FEEDBACK_LEN) {
        let Ok(bytes) = <[u8; FEEDBACK_LEN]>::try_from(chunk) else {
            continue;
        };
        let f = |at| f32::from_ne_bytes(take(&bytes, at));
        acc = fold_feedback(
            acc,
            i64::from_ne_bytes(take(&bytes, 0)),
            u32::from_ne_bytes(take(&bytes, 8)),
            u32::from_ne_bytes(take(&bytes, 12)),
            i32::from_ne_bytes(take(&bytes, 16)),
            f(20),
            [f(24), f(28), f(32), f(36)],
        );
    }
    acc
}

#[inline(never)]
fn feedback_view(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(FEEDBACK_LEN) {
        if let Ok(frame) = FeedbackFrame::new_checked(chunk) {
            acc = fold_feedback(
                acc,
                frame.position(),
                frame.status_word().bits(),
                frame.error_word().bits(),
                frame.message_code(),
                frame.message_data(),
                frame.extra_data(),
            );
        }
    }
    acc
}

#[inline(never)]
fn feedback_owned(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(FEEDBACK_LEN) {
        if let Ok(f) = Feedback::parse(chunk) {
            acc = fold_feedback(
                acc,
                f.position,
                f.status.bits(),
                f.errors.bits(),
                f.message.code,
                f.message.data,
                f.extra_data,
            );
        }
    }
    acc
}

/// The feedback frame as a hand-written decoder would hold it.
struct PlainFeedback {
    position: i64,
    status: u32,
    errors: u32,
    message_code: i32,
    message_data: f32,
    extra_data: [f32; 4],
}

/// The hand-written decoder: a `Cursor` and one `ReadBytesExt` call per
/// field.
fn read_feedback(bytes: &[u8]) -> std::io::Result<PlainFeedback> {
    let mut rdr = Cursor::new(bytes);
    let position = rdr.read_i64::<LittleEndian>()?;
    let status = rdr.read_u32::<LittleEndian>()?;
    let errors = rdr.read_u32::<LittleEndian>()?;
    let message_code = rdr.read_i32::<LittleEndian>()?;
    let message_data = rdr.read_f32::<LittleEndian>()?;
    let mut extra_data = [0.0; 4];
    for x in &mut extra_data {
        *x = rdr.read_f32::<LittleEndian>()?;
    }
    Ok(PlainFeedback {
        position,
        status,
        errors,
        message_code,
        message_data,
        extra_data,
    })
}

#[inline(never)]
fn feedback_byteorder_cursor(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(FEEDBACK_LEN) {
        if let Ok(f) = read_feedback(chunk) {
            acc = fold_feedback(
                acc,
                f.position,
                f.status,
                f.errors,
                f.message_code,
                f.message_data,
                f.extra_data,
            );
        }
    }
    acc
}

/// The feedback frame as a derive-based decoder reads it.
#[derive(DekuRead)]
#[deku(endian = "little")]
struct DekuFeedback {
    position: i64,
    status: u32,
    errors: u32,
    message_code: i32,
    message_data: f32,
    extra_data: [f32; 4],
}

#[inline(never)]
fn feedback_deku(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(FEEDBACK_LEN) {
        if let Ok((_, f)) = DekuFeedback::from_bytes((chunk, 0)) {
            acc = fold_feedback(
                acc,
                f.position,
                f.status,
                f.errors,
                f.message_code,
                f.message_data,
                f.extra_data,
            );
        }
    }
    acc
}

// -------------------------------------------------------- command, 10 bytes

/// `FRAMES` command frames of 8 axes: speed set points ramping both ways,
/// control words with EMGON and Brake, the servo-enable field, parameter
/// tables and regulator modes varying, sometimes POSLOCK or an error
/// clear, and the extra data code word mostly 0.
fn command_frames() -> Vec<u8> {
    let mut rng = Rng(0xC0FF_EE00_1234_5678);
    let mut out = Vec::with_capacity(FRAMES * COMMAND_LEN);
    let mut speeds = [0i32; 8];
    for i in 0..FRAMES {
        let axis = i % 8;
        speeds[axis] = speeds[axis]
            .wrapping_add(rng.below(20_001) as i32 - 10_000)
            .clamp(-3_000_000, 3_000_000);
        let mut control: u32 = 1 << 2 | 1 << 10; // EMGON, Brake
        control |= [0b01, 0b10, 0b10, 0b10, 0b11][rng.below(5) as usize];
        control |= (axis as u32 % 4) << 4 | (rng.below(4) as u32) << 6;
        if rng.below(10) == 0 {
            control |= 1 << 3;
        }
        if rng.below(50) == 0 {
            control |= 1 << 9;
        }
        let extra: i16 = if rng.below(8) == 0 {
            rng.below(200) as i16 - 100
        } else {
            0
        };
        out.extend_from_slice(&speeds[axis].to_le_bytes());
        out.extend_from_slice(&control.to_le_bytes());
        out.extend_from_slice(&extra.to_le_bytes());
    }
    out
}

/// Fold the fields of one command frame into the checksum.
#[inline(always)]
fn fold_command(acc: u64, speed: i32, control: u32, extra: i16) -> u64 {
    acc.wrapping_add(i64::from(speed) as u64)
        .wrapping_add(u64::from(control))
        .wrapping_add(i64::from(extra) as u64)
}

#[inline(never)]
fn command_copy(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(COMMAND_LEN) {
        let Ok(bytes) = <[u8; COMMAND_LEN]>::try_from(chunk) else {
            continue;
        };
        acc = fold_command(
            acc,
            i32::from_ne_bytes(take(&bytes, 0)),
            u32::from_ne_bytes(take(&bytes, 4)),
            i16::from_ne_bytes(take(&bytes, 8)),
        );
    }
    acc
}

#[inline(never)]
fn command_view(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(COMMAND_LEN) {
        if let Ok(frame) = CommandFrame::new_checked(chunk) {
            acc = fold_command(
                acc,
                frame.speed_setpoint(),
                frame.control_word().bits(),
                frame.extra_data_code(),
            );
        }
    }
    acc
}

#[inline(never)]
fn command_owned(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(COMMAND_LEN) {
        if let Ok(c) = Command::parse(chunk) {
            acc = fold_command(acc, c.speed_setpoint, c.control.bits(), c.extra_data_code);
        }
    }
    acc
}

/// The command frame as a hand-written decoder would hold it.
struct PlainCommand {
    speed_setpoint: i32,
    control: u32,
    extra_data_code: i16,
}

/// The hand-written decoder: a `Cursor` and one `ReadBytesExt` call per
/// field.
fn read_command(bytes: &[u8]) -> std::io::Result<PlainCommand> {
    let mut rdr = Cursor::new(bytes);
    Ok(PlainCommand {
        speed_setpoint: rdr.read_i32::<LittleEndian>()?,
        control: rdr.read_u32::<LittleEndian>()?,
        extra_data_code: rdr.read_i16::<LittleEndian>()?,
    })
}

#[inline(never)]
fn command_byteorder_cursor(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(COMMAND_LEN) {
        if let Ok(c) = read_command(chunk) {
            acc = fold_command(acc, c.speed_setpoint, c.control, c.extra_data_code);
        }
    }
    acc
}

/// The command frame as a derive-based decoder reads it.
#[derive(DekuRead)]
#[deku(endian = "little")]
struct DekuCommand {
    speed_setpoint: i32,
    control: u32,
    extra_data_code: i16,
}

#[inline(never)]
fn command_deku(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(COMMAND_LEN) {
        if let Ok((_, c)) = DekuCommand::from_bytes((chunk, 0)) {
            acc = fold_command(acc, c.speed_setpoint, c.control, c.extra_data_code);
        }
    }
    acc
}

// ------------------------------------------------------------ EMCY, 8 bytes

/// Error codes as drives and I/O nodes send them: CiA 301 communication
/// codes, CiA 402 drive codes, sub-class-only and class-only codes,
/// manufacturer-specific 0xFFxx, resets, and a rare code outside every
/// class.
const EMCY_CODES: [u16; 24] = [
    0x0000, 0x8130, 0x8110, 0x8120, 0x8140, 0x8210, 0x8250, 0x2310, 0x2320, 0x2350, 0x3210, 0x3220,
    0x4310, 0x5530, 0x6320, 0x7121, 0x7305, 0x8611, 0x1000, 0x2399, 0x5A00, 0xFF01, 0xFF42, 0xA000,
];

/// The 8 data bytes of one realistic EMCY: a code from [`EMCY_CODES`],
/// the error register it implies (generic plus the class bit; 0 after a
/// reset) and a manufacturer field with an axis number and a small
/// device-specific value.
fn emcy_bytes(rng: &mut Rng) -> [u8; 8] {
    let code = EMCY_CODES[rng.below(EMCY_CODES.len() as u64) as usize];
    let register = if code == 0 {
        0
    } else {
        1 | ErrorCode::new(code).register_class_bits().bits()
    };
    let [c0, c1] = code.to_le_bytes();
    let detail = rng.below(0x1_0000) as u16;
    let [d0, d1] = detail.to_le_bytes();
    let axis = 1 + rng.below(2) as u8;
    [c0, c1, register, axis, d0, d1, 0, rng.below(4) as u8]
}

/// `FRAMES` EMCY data fields from [`emcy_bytes`].
fn emcy_frames() -> Vec<u8> {
    let mut rng = Rng(0xE4C7_0081_8130_0001);
    let mut out = Vec::with_capacity(FRAMES * EMCY_LEN);
    for _ in 0..FRAMES {
        out.extend_from_slice(&emcy_bytes(&mut rng));
    }
    out
}

/// Fold the fields of one EMCY into the checksum.
#[inline(always)]
fn fold_emcy(acc: u64, code: u16, register: u8, manufacturer: [u8; 5]) -> u64 {
    let [m0, m1, m2, m3, m4] = manufacturer.map(u64::from);
    acc.wrapping_add(u64::from(code))
        .wrapping_add(u64::from(register))
        .wrapping_add(m0)
        .wrapping_add(m1)
        .wrapping_add(m2)
        .wrapping_add(m3)
        .wrapping_add(m4)
}

#[inline(never)]
fn emcy_copy(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(EMCY_LEN) {
        let Ok(bytes) = <[u8; EMCY_LEN]>::try_from(chunk) else {
            continue;
        };
        acc = fold_emcy(
            acc,
            u16::from_ne_bytes(take(&bytes, 0)),
            bytes[2],
            take(&bytes, 3),
        );
    }
    acc
}

#[inline(never)]
fn emcy_view(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(EMCY_LEN) {
        if let Ok(frame) = EmcyFrame::new_checked(chunk) {
            acc = fold_emcy(
                acc,
                frame.error_code().get(),
                frame.error_register().bits(),
                frame.manufacturer(),
            );
        }
    }
    acc
}

#[inline(never)]
fn emcy_owned(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(EMCY_LEN) {
        if let Ok(e) = Emcy::parse(chunk) {
            acc = fold_emcy(acc, e.code.get(), e.register.bits(), e.manufacturer);
        }
    }
    acc
}

/// Decode every EMCY and look up its code's description and class; fold
/// the fields and the lookups (text length, specificity, class).
#[inline(never)]
fn emcy_describe(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(EMCY_LEN) {
        if let Ok(e) = Emcy::parse(chunk) {
            let description = e.code.describe();
            acc = fold_emcy(acc, e.code.get(), e.register.bits(), e.manufacturer)
                .wrapping_add(description.text.len() as u64)
                .wrapping_add(description.specificity as u64)
                .wrapping_add(e.code.class() as u64);
        }
    }
    acc
}

/// The EMCY as a hand-written decoder would hold it.
struct PlainEmcy {
    code: u16,
    register: u8,
    manufacturer: [u8; 5],
}

/// The hand-written decoder: a `Cursor` and one `ReadBytesExt` call per
/// field.
fn read_emcy(bytes: &[u8]) -> std::io::Result<PlainEmcy> {
    let mut rdr = Cursor::new(bytes);
    let code = rdr.read_u16::<LittleEndian>()?;
    let register = rdr.read_u8()?;
    let mut manufacturer = [0; 5];
    std::io::Read::read_exact(&mut rdr, &mut manufacturer)?;
    Ok(PlainEmcy {
        code,
        register,
        manufacturer,
    })
}

#[inline(never)]
fn emcy_byteorder_cursor(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(EMCY_LEN) {
        if let Ok(e) = read_emcy(chunk) {
            acc = fold_emcy(acc, e.code, e.register, e.manufacturer);
        }
    }
    acc
}

/// The EMCY as a derive-based decoder reads it.
#[derive(DekuRead)]
#[deku(endian = "little")]
struct DekuEmcy {
    code: u16,
    register: u8,
    manufacturer: [u8; 5],
}

#[inline(never)]
fn emcy_deku(frames: &[u8]) -> u64 {
    let mut acc = 0;
    for chunk in frames.chunks_exact(EMCY_LEN) {
        if let Ok((_, e)) = DekuEmcy::from_bytes((chunk, 0)) {
            acc = fold_emcy(acc, e.code, e.register, e.manufacturer);
        }
    }
    acc
}

// ------------------------------------------------------------ frame groups

/// One variant of a frame group: its id and the function it times.
type Variant = (&'static str, fn(&[u8]) -> u64);

/// Check that every variant folds `frames` into the same checksum, then
/// time each of them, and each of `more` (which do more work, so are not
/// compared), over the whole buffer.
fn frame_group(
    c: &mut Criterion,
    name: &str,
    frames: &[u8],
    variants: &[Variant],
    more: &[Variant],
) {
    let expected = variants[0].1(frames);
    for (id, f) in variants {
        assert_eq!(f(frames), expected, "{name}/{id} reads the same fields");
    }
    let mut group = c.benchmark_group(name);
    group.throughput(Throughput::Bytes(frames.len() as u64));
    for &(id, f) in variants.iter().chain(more) {
        group.bench_function(id, |b| b.iter(|| f(black_box(frames))));
    }
    group.finish();
}

fn feedback40(c: &mut Criterion) {
    let frames = feedback_frames();
    frame_group(
        c,
        "feedback40",
        &frames,
        &[
            ("copy", feedback_copy),
            ("view", feedback_view),
            ("owned", feedback_owned),
            ("byteorder_cursor", feedback_byteorder_cursor),
            ("deku", feedback_deku),
        ],
        &[],
    );
}

fn command10(c: &mut Criterion) {
    let frames = command_frames();
    frame_group(
        c,
        "command10",
        &frames,
        &[
            ("copy", command_copy),
            ("view", command_view),
            ("owned", command_owned),
            ("byteorder_cursor", command_byteorder_cursor),
            ("deku", command_deku),
        ],
        &[],
    );
}

fn emcy8(c: &mut Criterion) {
    let frames = emcy_frames();
    frame_group(
        c,
        "emcy8",
        &frames,
        &[
            ("copy", emcy_copy),
            ("view", emcy_view),
            ("owned", emcy_owned),
            ("byteorder_cursor", emcy_byteorder_cursor),
            ("deku", emcy_deku),
        ],
        // Decoding plus the description lookup.
        &[("describe", emcy_describe)],
    );
}

// ------------------------------------------------------------ candump log

/// Lines in the generated log.
const LINES: usize = 20_000;

/// How many lines of each kind [`generate_log`] wrote.
#[derive(Debug, Default, PartialEq, Eq)]
struct LogKinds {
    emcy: usize,
    heartbeat: usize,
    guard_request: usize,
}

/// A candump `-l` log of CANopen traffic: PDOs, SDOs, heartbeats, EMCYs
/// (realistic codes, [`emcy_bytes`]), SYNC, node-guarding RTRs, some
/// extended identifiers (J1939-like), a few CAN FD frames and a few lines
/// with a direction.
fn generate_log() -> (Vec<u8>, LogKinds) {
    use std::fmt::Write;

    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut out = String::with_capacity(LINES * 48);
    let mut kinds = LogKinds::default();
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
                kinds.heartbeat += 1;
                let state = if rng.below(4) == 0 { "7F" } else { "05" };
                (format!("{:03X}", 0x700 + node), state.to_string())
            }
            // EMCY, 8 bytes.
            65..=74 => {
                kinds.emcy += 1;
                (format!("{:03X}", 0x080 + node), hex(&emcy_bytes(&mut rng)))
            }
            // SYNC, no data.
            75..=79 => ("080".to_string(), String::new()),
            // Node guarding / remote PDO requests.
            80..=84 => {
                kinds.guard_request += 1;
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
    (out.into_bytes(), kinds)
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect()
}

/// The frame the baseline parser produces: the same fields as
/// the `LogFrame` the crate yields.
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
        if let Ok(Some(logged)) = result {
            let f = &logged.frame;
            let ts = logged.timestamp.unwrap_or_else(|| unreachable!());
            let flags = u64::from(f.is_extended())
                | u64::from(f.is_rtr()) << 1
                | u64::from(f.is_fd()) << 2
                | u64::from(f.fd_flags().bits()) << 3
                | u64::from(logged.direction.map_or(0, |d| d.letter() as u8)) << 8
                | u64::from(f.dlc()) << 16;
            sum = fold(
                sum,
                ts.secs(),
                ts.micros(),
                iface(&logged),
                f.id().raw(),
                flags,
                f.data(),
            );
        }
    }
    sum
}

/// The interface name of a candump record, as bytes.
fn iface<'a>(logged: &LogFrame<'a>) -> &'a [u8] {
    match logged.iface {
        Some(Iface::Name(name)) => name.as_bytes(),
        _ => &[],
    }
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

/// `candump/parse`: parse every line and read the fields of each frame,
/// handing its data to `black_box`.
#[inline(never)]
fn candump_parse(log: &[u8]) -> u64 {
    let mut sum = 0u64;
    candump::lines(log).for_each(|(_, result)| {
        if let Ok(Some(logged)) = result {
            let f = &logged.frame;
            let ts = logged
                .timestamp
                .map_or(0, |t| t.secs() ^ u64::from(t.micros()));
            sum = sum.wrapping_add(
                ts ^ u64::from(f.id().raw()) ^ u64::from(f.dlc()) ^ iface(&logged).len() as u64,
            );
            black_box(f.data());
        }
    });
    sum
}

/// `candump/byte_by_byte`: the same with the baseline parser.
#[inline(never)]
fn candump_byte_by_byte(log: &[u8]) -> u64 {
    let mut sum = 0u64;
    for_each_byte_by_byte(log, |f| {
        let dlc = if f.fd { fd_dlc(f.len) } else { f.len as u64 };
        sum = sum.wrapping_add(
            (f.secs ^ u64::from(f.micros)) ^ u64::from(f.id) ^ dlc ^ f.iface.len() as u64,
        );
        black_box(if f.rtr { &[][..] } else { &f.data[..f.len] });
    });
    sum
}

/// One frame as `motionwire decode` reads it before writing it: decoded
/// once with `CanOpenMessage::decode` (the identifier classified by CiA
/// 301's pre-defined connection set, EMCY and heartbeat payloads decoded),
/// an EMCY code's class and description looked up; folded into a checksum
/// with the timestamp and identifier. The kinds are counted into `kinds`.
#[inline(always)]
fn decode_frame(logged: &LogFrame<'_>, kinds: &mut LogKinds) -> u64 {
    let frame = &logged.frame;
    let ts = logged
        .timestamp
        .map_or(0, |t| t.secs() ^ u64::from(t.micros()));
    let common = ts ^ u64::from(frame.id().raw());
    let payload = match CanOpenMessage::decode(frame) {
        Ok(CanOpenMessage::Emcy { node, emcy }) => {
            kinds.emcy += 1;
            let description = emcy.code.describe();
            fold_emcy(0, emcy.code.get(), emcy.register.bits(), emcy.manufacturer)
                .wrapping_add(description.text.len() as u64)
                .wrapping_add(emcy.code.class() as u64)
                .wrapping_add(u64::from(node.get()) << 32)
        }
        Ok(CanOpenMessage::GuardRequest { node }) => {
            kinds.guard_request += 1;
            2 + (u64::from(node.get()) << 32)
        }
        Ok(CanOpenMessage::Heartbeat { node, byte }) => {
            kinds.heartbeat += 1;
            let state = byte.state().map_or(0xFF, NmtState::to_byte);
            u64::from(byte.state_raw()) << 8
                | u64::from(byte.toggle()) << 16
                | u64::from(state)
                | u64::from(node.get()) << 32
        }
        Ok(message) if frame.is_extended() => {
            let _ = message;
            return common;
        }
        Ok(message) => 4 + message.node().map_or(0, |n| u64::from(n.get()) << 32),
        Err(e) => 1 + e.node.map_or(0, |n| u64::from(n.get()) << 32),
    };
    common.wrapping_add(payload)
}

/// Parse, classify and decode every line of `log` (the library-level work
/// of `motionwire decode`); return the checksum.
#[inline(never)]
fn candump_decode(log: &[u8], kinds: &mut LogKinds) -> u64 {
    let mut sum = 0u64;
    candump::lines(log).for_each(|(line, result)| {
        sum = sum.wrapping_add(match result {
            Ok(Some(frame)) => decode_frame(&frame, kinds),
            Ok(None) => 0,
            Err(_) => line.number(),
        });
    });
    sum
}

fn candump_group(c: &mut Criterion) {
    let (log, expected_kinds) = generate_log();
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
    let mut kinds = LogKinds::default();
    candump_decode(&log, &mut kinds);
    assert_eq!(
        kinds, expected_kinds,
        "decode finds every EMCY, heartbeat and request"
    );

    // The timed consumer reads the fields of each frame and hands its data
    // to `black_box`, the same for both parsers, so that nothing the parser
    // decodes can be optimised away.
    let mut group = c.benchmark_group("candump");
    group.throughput(Throughput::Bytes(log.len() as u64));
    group.bench_function("parse", |b| b.iter(|| candump_parse(black_box(&log))));
    group.bench_function("byte_by_byte", |b| {
        b.iter(|| candump_byte_by_byte(black_box(&log)))
    });
    group.bench_function("decode", |b| {
        b.iter(|| {
            let mut kinds = LogKinds::default();
            let sum = candump_decode(black_box(&log), &mut kinds);
            (sum, kinds.emcy)
        })
    });
    group.finish();
}

criterion_group!(benches, feedback40, command10, emcy8, candump_group);
criterion_main!(benches);
