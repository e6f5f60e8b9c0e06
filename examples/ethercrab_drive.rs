//! How a program on the ethercrab EtherCAT master reads a servo drive's
//! inputs into [`Feedback`] and writes [`Command`] into its outputs, through
//! ethercrab-wire's traits (docs/servo.md#ethercrab; feature `ethercrab`).
//!
//! Run with `cargo run --example ethercrab_drive --features ethercrab`.
//!
//! On a real master the process data image (PDI) comes from ethercrab:
//!
//! ```text
//! let group = group.into_op(&maindevice).await?;
//! loop {
//!     group.tx_rx(&maindevice).await?;
//!     for drive in group.iter(&maindevice) {
//!         let io = drive.io_raw_mut();
//!         let feedback = Feedback::unpack_from_slice(&io.inputs())?;   // 40 bytes
//!         let command = nc.cycle(&feedback);
//!         command.pack_to_slice(&mut io.outputs())?;                   // 10 bytes
//!     }
//!     tick.next().await;
//! }
//! ```
//!
//! This example does not depend on the `ethercrab` crate itself: the
//! master's current release (0.7.1, the one on ethercrab-wire 0.3) needs
//! Rust 1.85, above this crate's MSRV 1.81, and a dev-dependency is built
//! for every test, example and bench; 0.6 (Rust 1.81) is on ethercrab-wire
//! 0.2, whose traits are other types. It would also bring some twenty
//! direct dependencies (async I/O, raw sockets, io_uring) into every
//! `cargo test`, and it cannot run here without a network interface anyway.
//! So the PDI below is a byte buffer laid out as ethercrab lays out a
//! group's image — each drive's outputs and inputs at their offsets — and a
//! crate [`Drive`] model per axis stands in for the bus: it reads the output
//! bytes and writes the input bytes, as the drives do during `tx_rx`. The
//! NC side uses only what it would use on the master: the two traits on
//! slices of the image.

use ethercrab_wire::{
    EtherCrabWireRead, EtherCrabWireReadSized, EtherCrabWireSized, EtherCrabWireWrite, WireError,
};
use motionwire::servo::{
    Command, Drive, DriveConfig, EncoderKind, Feedback, ServoControlWord, ServoEnable,
    ServoStatusWord,
};

/// Axes on the simulated bus.
const AXES: usize = 4;
/// One drive's share of the image: 10 output bytes, then 40 input bytes.
const OUT_LEN: usize = <Command as EtherCrabWireSized>::PACKED_LEN;
const IN_LEN: usize = <Feedback as EtherCrabWireSized>::PACKED_LEN;
const STRIDE: usize = OUT_LEN + IN_LEN;

/// A group's process data image: the drives' output and input areas.
struct ProcessImage {
    bytes: [u8; AXES * STRIDE],
}

impl ProcessImage {
    /// Return axis `axis`'s (inputs, outputs), as ethercrab's `io_raw_mut`
    /// does for a subdevice.
    fn io_mut(&mut self, axis: usize) -> (&[u8], &mut [u8]) {
        let area = &mut self.bytes[axis * STRIDE..(axis + 1) * STRIDE];
        let (outputs, inputs) = area.split_at_mut(OUT_LEN);
        (inputs, outputs)
    }

    /// The bus: every drive reads its outputs and writes its inputs.
    fn tx_rx(&mut self, drives: &mut [Drive; AXES]) -> Result<(), WireError> {
        for (axis, drive) in drives.iter_mut().enumerate() {
            let area = &mut self.bytes[axis * STRIDE..(axis + 1) * STRIDE];
            let (outputs, inputs) = area.split_at_mut(OUT_LEN);
            let command = Command::unpack_from_slice(outputs)?;
            drive.cycle(&command).pack_to_slice(inputs)?;
        }
        Ok(())
    }
}

/// Read any sized process-data type from an input area: the bound ethercrab
/// itself puts on PDI and SDO reads.
fn read_inputs<T: EtherCrabWireReadSized>(inputs: &[u8]) -> Result<T, WireError> {
    T::unpack_from_slice(inputs)
}

fn main() -> Result<(), WireError> {
    let mut drives = core::array::from_fn(|axis| {
        Drive::new(DriveConfig {
            encoder: if axis % 2 == 0 {
                EncoderKind::Incremental
            } else {
                EncoderKind::Absolute
            },
            ..DriveConfig::default()
        })
    });
    let mut image = ProcessImage {
        bytes: [0; AXES * STRIDE],
    };

    for cycle in 0..6u32 {
        image.tx_rx(&mut drives)?;
        for axis in 0..AXES {
            let (inputs, outputs) = image.io_mut(axis);
            let feedback: Feedback = read_inputs(inputs)?;
            // Enable on SE 0b01 → 0b10 (docs/servo.md#handshakes), then run
            // each axis at its own speed.
            let se = if cycle < 2 {
                ServoEnable::ARM
            } else {
                ServoEnable::ENABLE
            };
            let setpoint = if feedback.status.contains(ServoStatusWord::SERVO_EN) {
                100 * (axis as i32 + 1)
            } else {
                0
            };
            let command = Command::new(setpoint, ServoControlWord::NORMAL.with_servo_enable(se), 0);
            let written = command.pack_to_slice(outputs)?;
            println!(
                "cycle {cycle} axis {axis}: in {:02X?}.. ServoEn {} {} -> out {:02X?}",
                &inputs[..8],
                u8::from(feedback.status.contains(ServoStatusWord::SERVO_EN)),
                feedback.actual_position(),
                written
            );
        }
    }

    // A short area is an error, never a panic.
    let (inputs, _) = image.io_mut(0);
    assert_eq!(
        Feedback::unpack_from_slice(&inputs[..IN_LEN - 1]).map(|f| f.to_bytes()),
        Err(WireError::ReadBufferTooShort)
    );
    let mut short = [0u8; OUT_LEN - 1];
    assert_eq!(
        Command::new(0, ServoControlWord::NORMAL, 0).pack_to_slice(&mut short),
        Err(WireError::WriteBufferTooShort)
    );
    println!(
        "short areas: {} / {}",
        WireError::ReadBufferTooShort,
        WireError::WriteBufferTooShort
    );
    Ok(())
}
