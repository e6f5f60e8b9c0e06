//! Speed of the drive model (docs/servo.md#drive-model): one EtherCAT cycle of
//! `Drive::cycle` alone, and with the frames of that cycle encoded and decoded
//! as they are on the bus, and a 64-axis machine. Run it with
//! `cargo bench --bench drive`. Criterion's elements per second are axis
//! cycles in the group `drive` and machine cycles (one exchange with each of
//! the 64 axes) in the group `machine`: the machine's figure is its
//! `thrpt`, and the bench prints it in words after the group.
//!
//! Every group runs the same script of [`CYCLES`] NC commands per iteration
//! for each axis: enable (SE 0b01 → 0b10), move at changing speeds, a zero
//! pulse search, POSLOCK, an error clear after a fault injected every 1 000
//! cycles. The drives start from the same state each iteration, so every
//! iteration does the same work. The variants:
//!
//! - `frames_only`: the baseline, the frame work of a cycle without the
//!   model: encode the command, decode it, encode a fixed feedback, decode
//!   it (the encoded bytes pass through `black_box`, so they are really
//!   written and read, as in a process image);
//! - `cycle`: `Drive::cycle` on the decoded command, no frames;
//! - `cycle_with_frames`: the whole exchange, command bytes → drive →
//!   feedback bytes → `Feedback`;
//! - `machine/64_axes`: 64 drives (half incremental, half absolute), each
//!   machine cycle one exchange per axis, as a master simulating a 64-axis
//!   machine would.
//!
//! The result of every cycle is folded into a checksum that the timed
//! closure returns, so nothing can be optimised away.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use motionwire::servo::{
    Command, Drive, DriveConfig, EncoderKind, Feedback, ServoControlWord, ServoEnable, ServoFault,
};

/// NC cycles per iteration.
const CYCLES: usize = 4_096;
/// Axes of the machine group.
const AXES: usize = 64;

/// The NC's commands of the script, one per cycle.
fn script() -> Vec<Command> {
    (0..CYCLES)
        .map(|i| {
            let phase = i % 1_000;
            let se = match phase {
                0..=1 => ServoEnable::DISABLED,
                2 => ServoEnable::ARM,
                _ => ServoEnable::ENABLE,
            };
            let speed = ((i * 37) % 900) as i32 - 300;
            let scw = ServoControlWord::NORMAL
                .with_servo_enable(se)
                .with_flag(
                    ServoControlWord::Z_PULSE_REQUEST,
                    (100..400).contains(&phase),
                )
                .with_flag(ServoControlWord::POSLOCK, (600..650).contains(&phase))
                .with_flag(ServoControlWord::ERROR_CLEAR, (0..3).contains(&phase));
            Command::new(speed, scw, 0)
        })
        .collect()
}

/// Whether the script injects a fault before cycle `i`.
fn fault_at(i: usize) -> bool {
    i % 1_000 == 990
}

fn fold(acc: u64, feedback: &Feedback) -> u64 {
    acc.rotate_left(5)
        ^ feedback.position as u64
        ^ u64::from(feedback.status.bits())
        ^ u64::from(feedback.errors.bits())
}

fn run_cycle(initial: &Drive, script: &[Command]) -> u64 {
    let mut drive = *initial;
    let mut acc = 0;
    for (i, command) in script.iter().enumerate() {
        if fault_at(i) {
            drive.inject(ServoFault::FollowerErr);
        }
        acc = fold(acc, &drive.cycle(command));
    }
    acc
}

fn run_cycle_with_frames(initial: &Drive, script: &[Command]) -> u64 {
    let mut drive = *initial;
    let mut acc = 0;
    for (i, command) in script.iter().enumerate() {
        if fault_at(i) {
            drive.inject(ServoFault::FollowerErr);
        }
        // The bytes really exist, as in the process image.
        let out = black_box(command.to_bytes());
        let received = Command::from_bytes(&out);
        let back = black_box(drive.cycle(&received).to_bytes());
        acc = fold(acc, &Feedback::from_bytes(&back));
    }
    acc
}

fn run_frames_only(feedback: &Feedback, script: &[Command]) -> u64 {
    let mut acc = 0;
    for command in script {
        let received = Command::from_bytes(&black_box(command.to_bytes()));
        let mut answer = *feedback;
        answer.position = i64::from(received.speed_setpoint);
        acc = fold(acc, &Feedback::from_bytes(&black_box(answer.to_bytes())));
    }
    acc
}

fn run_machine(initial: &[Drive; AXES], script: &[Command]) -> u64 {
    let mut drives = *initial;
    let mut acc = 0;
    for (i, command) in script.iter().enumerate() {
        for drive in drives.iter_mut() {
            if fault_at(i) {
                drive.inject(ServoFault::FollowerErr);
            }
            let received = Command::from_bytes(&black_box(command.to_bytes()));
            let back = black_box(drive.cycle(&received).to_bytes());
            acc = fold(acc, &Feedback::from_bytes(&back));
        }
    }
    acc
}

fn drive_group(c: &mut Criterion) {
    let script = script();
    let initial = Drive::new(DriveConfig::default());
    let feedback = {
        let mut d = initial;
        d.cycle(&script[0])
    };
    // The model and the whole exchange see the same feedback.
    assert_eq!(
        run_cycle(&initial, &script),
        run_cycle_with_frames(&initial, &script)
    );

    let mut group = c.benchmark_group("drive");
    group.throughput(Throughput::Elements(CYCLES as u64));
    group.bench_function("frames_only", |b| {
        b.iter(|| run_frames_only(black_box(&feedback), black_box(&script)))
    });
    group.bench_function("cycle", |b| {
        b.iter(|| run_cycle(black_box(&initial), black_box(&script)))
    });
    group.bench_function("cycle_with_frames", |b| {
        b.iter(|| run_cycle_with_frames(black_box(&initial), black_box(&script)))
    });
    let machine: [Drive; AXES] = core::array::from_fn(|axis| {
        Drive::new(DriveConfig {
            encoder: if axis % 2 == 0 {
                EncoderKind::Incremental
            } else {
                EncoderKind::Absolute
            },
            ..DriveConfig::default()
        })
    });
    group.finish();

    // One element is one machine cycle: an exchange with each of the 64
    // axes.
    let mut group = c.benchmark_group("machine");
    group.throughput(Throughput::Elements(CYCLES as u64));
    group.bench_function("64_axes", |b| {
        b.iter(|| run_machine(black_box(&machine), black_box(&script)))
    });
    group.finish();
    // `cargo bench` passes `--bench`; `cargo test --benches` runs each
    // bench once, to check it, and needs no figure.
    if std::env::args().any(|a| a == "--bench") {
        say_machine_cycles(&machine, &script);
    }
}

/// Print the machine's figure in words: machine cycles per second and the
/// times real time at an 8 kHz cycle, from a timed second of runs (the
/// same work as `machine/64_axes`, so the two agree within the noise).
fn say_machine_cycles(machine: &[Drive; AXES], script: &[Command]) {
    let start = std::time::Instant::now();
    let mut runs = 0u64;
    while start.elapsed() < std::time::Duration::from_secs(1) {
        black_box(run_machine(black_box(machine), black_box(script)));
        runs += 1;
    }
    let per_second = (runs * CYCLES as u64) as f64 / start.elapsed().as_secs_f64();
    println!(
        "machine/64_axes: {per_second:.0} machine cycles per second ({AXES} axes each), \
         {:.0} times real time at 8 kHz",
        per_second / 8_000.0
    );
}

criterion_group!(benches, drive_group);
criterion_main!(benches);
