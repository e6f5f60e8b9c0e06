//! A few hundred simulated NC cycles against a simulated servo drive,
//! exchanging real 10-byte command and 40-byte feedback frames (docs/servo.md).
//!
//! The NC enables the drive (SE 0b01 → 0b10), runs the axis, searches the
//! incremental encoder's zero pulse, and — after a following error is
//! injected into the drive — clears it and enables again, using the crate's
//! handshakes ([`EnableHandshake`], [`ErrorClearHandshake`],
//! [`ZeroPulseHandshake`]) and never writing SE or a request bit by hand.
//! Only events are printed, not every cycle.
//!
//! Run with `cargo run --example servo_cycle`.

use motionwire::servo::{
    drive_enabled, servo_ready, ActualPosition, Command, CommandFrame, EnableHandshake,
    EnablePhase, ErrorClearHandshake, Feedback, HandshakePhase, Message, MessageCode,
    ParameterTable, ServoControlWord, ServoEnable, ServoErrorWord, ServoFault, ServoReadyMode,
    ServoStatusWord, ZeroPulseHandshake, COMMAND_LEN, FEEDBACK_LEN,
};

/// Cycle time of the simulation, ms.
const CYCLE_MS: f32 = 1.0;
/// Incremental encoder resolution, counts per revolution.
const COUNTS_PER_REV: i32 = 10_000;
/// Speed reference the NC runs the axis at, rpm.
const SPEED_RPM: i32 = 600;
/// Cycles the drive needs to clear its errors after ErrorClear=1.
const CLEAR_CYCLES: u32 = 3;

/// A servo drive as seed 002 describes it, reduced to what the NC sees:
/// the enable edge, ServoRDY by the truth table, error clear with
/// ErrClearAck, zero-pulse search with ZPulseAck and POSW2..3.
struct SimulatedDrive {
    ready_mode: ServoReadyMode,
    previous_se: ServoEnable,
    enabled: bool,
    errors: ServoErrorWord,
    clearing_for: u32,
    err_clear_ack: bool,
    /// The control word of the previous exchange: the drive drops an ack
    /// one cycle after the request drops.
    previous_scw: ServoControlWord,
    searching: bool,
    z_pulse_ack: bool,
    speed_rpm: f32,
    /// Position in encoder counts, with the fraction the ramp leaves.
    position: f64,
    zero_pulse_position: i32,
    cycle: u32,
}

impl SimulatedDrive {
    fn new() -> Self {
        SimulatedDrive {
            ready_mode: ServoReadyMode::EnabledAndErrorFree,
            previous_se: ServoEnable::DISABLED,
            enabled: false,
            errors: ServoErrorWord::empty(),
            clearing_for: 0,
            err_clear_ack: false,
            previous_scw: ServoControlWord::NORMAL,
            searching: false,
            z_pulse_ack: false,
            speed_rpm: 0.0,
            position: 3_217.0,
            zero_pulse_position: 0,
            cycle: 0,
        }
    }

    /// Make the drive detect `fault` (with the summary bit); it disables.
    fn inject(&mut self, fault: ServoFault) {
        self.errors = self.errors.union(fault.flag()).summarized();
    }

    /// One EtherCAT exchange: take the NC's command frame, answer with the
    /// feedback frame.
    fn exchange(&mut self, image: &[u8; COMMAND_LEN]) -> [u8; FEEDBACK_LEN] {
        self.cycle += 1;
        let command = CommandFrame::new_unchecked(&image[..]);
        let scw = command.control_word();

        // A request counts as dropped once it was 0 in two exchanges in a
        // row: the drive drops its ack one cycle late.
        let dropped = |flag| !scw.contains(flag) && !self.previous_scw.contains(flag);

        // Error clear: clear after a few cycles of ErrorClear=1, ack until
        // the NC drops the request.
        if scw.contains(ServoControlWord::ERROR_CLEAR) {
            if !self.err_clear_ack {
                self.clearing_for += 1;
                if self.clearing_for >= CLEAR_CYCLES {
                    self.errors = ServoErrorWord::empty();
                    self.err_clear_ack = true;
                }
            }
        } else {
            self.clearing_for = 0;
            if dropped(ServoControlWord::ERROR_CLEAR) {
                self.err_clear_ack = false;
            }
        }

        // Enable only on the SE edge 0b01 → 0b10, never with an error.
        let has_error = self.errors.contains(ServoErrorWord::SERVO_ERRORS);
        self.enabled =
            drive_enabled(self.previous_se, scw.servo_enable(), self.enabled) && !has_error;
        self.previous_se = scw.servo_enable();

        // Speed follows the reference on a ramp while enabled and not in the
        // emergency state; otherwise it ramps down.
        let target = if self.enabled && !scw.emergency_active() {
            command.speed_setpoint() as f32
        } else {
            0.0
        };
        let ramp = 20.0; // rpm per cycle
        self.speed_rpm += (target - self.speed_rpm).clamp(-ramp, ramp);

        // Move, and look for zero pulses: one per revolution.
        let step = f64::from(self.speed_rpm / 60.0 / 1000.0 * CYCLE_MS) * f64::from(COUNTS_PER_REV);
        let before = self.position;
        self.position += step;
        let crossed = (before / f64::from(COUNTS_PER_REV)).floor()
            != (self.position / f64::from(COUNTS_PER_REV)).floor();
        if scw.contains(ServoControlWord::Z_PULSE_REQUEST) {
            if !self.z_pulse_ack {
                self.searching = true;
            }
        } else {
            self.searching = false;
            if dropped(ServoControlWord::Z_PULSE_REQUEST) {
                self.z_pulse_ack = false;
            }
        }
        self.previous_scw = scw;
        if crossed {
            let revolution = (self.position / f64::from(COUNTS_PER_REV)).floor() as i32;
            // Every zero pulse updates POSW2..3; the first after a request is acked.
            self.zero_pulse_position = revolution * COUNTS_PER_REV;
            if self.searching {
                self.searching = false;
                self.z_pulse_ack = true;
            }
        }

        let status = ServoStatusWord::empty().with_flag(ServoStatusWord::SERVO_EN, self.enabled);
        let status = status
            .with_flag(
                ServoStatusWord::SERVO_RDY,
                servo_ready(self.ready_mode, status, self.errors),
            )
            .with_flag(ServoStatusWord::Z_PULSE_ACK, self.z_pulse_ack)
            .with_flag(ServoStatusWord::ERR_CLEAR_ACK, self.err_clear_ack)
            .with_flag(ServoStatusWord::N_ZERO, self.speed_rpm.abs() < 5.0)
            .with_flag(
                ServoStatusWord::N_EQ_NS,
                (self.speed_rpm - target).abs() < 10.0,
            )
            .with_flag(ServoStatusWord::PULSE_ENABLED, true)
            .with_parameter_table(scw.parameter_table());

        // One measurement per cycle, codes 0..=4 in turn (5, motor power,
        // is not available on this firmware).
        let message = match self.cycle % 5 {
            0 => Message::new(MessageCode::MotorSpeed, self.speed_rpm),
            1 => Message::new(MessageCode::MotorCurrent, self.speed_rpm.abs() / 200.0),
            2 => Message::new(MessageCode::RelativeCurrent, self.speed_rpm.abs() / 30.0),
            3 => Message::new(MessageCode::BusVoltage, 560.0),
            _ => Message::new(MessageCode::MotorTemperature, 41.5),
        };

        let mut feedback = Feedback {
            position: 0,
            status,
            errors: self.errors,
            message,
            extra_data: [0.0; 4],
        };
        feedback.set_actual_position(ActualPosition::Incremental {
            // The counter wraps like a 32-bit encoder counter.
            position: self.position.floor() as i64 as i32,
            zero_pulse_position: self.zero_pulse_position,
        });
        feedback.to_bytes()
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The names of the status flags that differ between two words, `+` set and
/// `-` cleared.
fn status_changes(before: ServoStatusWord, now: ServoStatusWord) -> String {
    let set = now.difference(before).flag_names().map(|n| format!("+{n}"));
    let cleared = before.difference(now).flag_names().map(|n| format!("-{n}"));
    set.chain(cleared).collect::<Vec<_>>().join(" ")
}

fn main() -> Result<(), motionwire::Error> {
    let mut drive = SimulatedDrive::new();
    let mut enable = EnableHandshake::new();
    let mut clear = ErrorClearHandshake::new();
    let mut zero = ZeroPulseHandshake::new();

    let mut command = Command::new(
        0,
        ServoControlWord::NORMAL.with_parameter_table(ParameterTable::try_new(2)?),
        0,
    );
    let mut feedback_image = drive.exchange(&command.to_bytes());
    let mut previous_status = ServoStatusWord::empty();
    let mut homed_at: Option<i32> = None;
    let mut last_zero_pulse = 0;
    let mut reported_errors = ServoErrorWord::empty();
    let mut measurements: [Option<Message>; 6] = [None; 6];

    println!(
        "first exchange: command {} → feedback {}",
        hex(&command.to_bytes()),
        hex(&feedback_image)
    );

    for cycle in 1..=400u32 {
        // Read the drive's answer.
        let feedback = Feedback::parse(&feedback_image)?;
        let status = feedback.status;
        let last = command.control;

        let changes = status_changes(previous_status, status);
        if !changes.is_empty() {
            println!("[{cycle:3}] drive status {:#06x}: {changes}", status.bits());
        }
        previous_status = status;

        if cycle == 200 {
            println!("[{cycle:3}] (simulation) the drive detects a speed following error");
            drive.inject(ServoFault::FollowerErr);
        }

        // Errors: report once, then clear them.
        let has_error = feedback.errors.contains(ServoErrorWord::SERVO_ERRORS);
        if has_error && feedback.errors != reported_errors {
            for fault in feedback.errors.faults() {
                let code = fault.e_code().map_or("---".to_string(), |c| c.to_string());
                println!(
                    "[{cycle:3}] fault bit {:2} {:<12} {code}: {}",
                    fault.bit(),
                    fault.name(),
                    fault.description()
                );
            }
            reported_errors = feedback.errors;
            println!("[{cycle:3}] NC starts the error clear");
            clear = clear.start();
        }
        if !has_error {
            reported_errors = ServoErrorWord::empty();
        }

        // Enable while error free: step the handshake with the word written
        // last cycle, then (re)start it; it writes 0b01, then 0b10 (the
        // edge), and holds 0b10 while ServoEn stays. A drive error drops
        // ServoEn (the handshake reports `dropped` and writes 0b00); in any
        // other phase the NC withdraws the enable itself.
        let enabled = status.contains(ServoStatusWord::SERVO_EN);
        let (mut next_enable, _) = enable.step(last, status);
        if !has_error {
            next_enable = next_enable.start();
        } else if next_enable.phase() != EnablePhase::Dropped {
            next_enable = next_enable.cancel();
        }
        if next_enable.phase() != enable.phase() {
            println!(
                "[{cycle:3}] enable: {} → {} (SE {})",
                enable.phase(),
                next_enable.phase(),
                next_enable.servo_enable()
            );
        }
        enable = next_enable;

        // Home on the zero pulse once the axis runs at speed.
        if homed_at.is_none()
            && zero.phase() == HandshakePhase::Idle
            && status.contains(ServoStatusWord::SERVO_EN | ServoStatusWord::N_EQ_NS)
            && !status.contains(ServoStatusWord::N_ZERO)
        {
            println!("[{cycle:3}] axis at speed: NC starts the zero-pulse search");
            zero = zero.start();
        }

        // Step both handshakes with the word written last cycle.
        let (next_clear, _) = clear.step(last, status);
        let (next_zero, _) = zero.step(last, status);
        if next_clear.phase() != clear.phase() {
            println!(
                "[{cycle:3}] error clear: {} → {} (ErrorClear={})",
                clear.phase(),
                next_clear.phase(),
                u8::from(next_clear.request_bit())
            );
        }
        if next_zero.phase() != zero.phase() {
            println!(
                "[{cycle:3}] zero pulse: {} → {} (ZPulseRequest={})",
                zero.phase(),
                next_zero.phase(),
                u8::from(next_zero.request_bit())
            );
            if next_zero.phase() == HandshakePhase::Acknowledged {
                if let ActualPosition::Incremental {
                    position,
                    zero_pulse_position,
                } = feedback.actual_position()
                {
                    println!(
                        "[{cycle:3}] zero pulse found at {zero_pulse_position} counts (axis at {position})"
                    );
                    homed_at = Some(zero_pulse_position);
                    last_zero_pulse = zero_pulse_position;
                }
            }
        }
        clear = next_clear;
        zero = next_zero;

        // Later zero pulses still update POSW2..3.
        if let ActualPosition::Incremental {
            zero_pulse_position,
            ..
        } = feedback.actual_position()
        {
            if homed_at.is_some() && zero_pulse_position != last_zero_pulse {
                println!("[{cycle:3}] later zero pulse: POSW2..3 = {zero_pulse_position}");
                last_zero_pulse = zero_pulse_position;
            }
        }

        // The drive multiplexes one measurement per cycle; keep the newest
        // of each kind and show them now and then.
        if let Ok(slot) = usize::try_from(feedback.message.code) {
            if let Some(newest) = measurements.get_mut(slot) {
                *newest = Some(feedback.message);
            }
        }
        if cycle % 100 == 0 {
            let line: Vec<String> = measurements
                .iter()
                .flatten()
                .map(|m| m.to_string())
                .collect();
            println!("[{cycle:3}] measurements: {}", line.join(", "));
        }

        // Write this cycle's command and exchange it.
        let ssp = if enabled { SPEED_RPM } else { 0 };
        let scw = zero.apply(clear.apply(enable.apply(last)));
        let next = Command::new(ssp, scw, 0);
        if next.control != command.control {
            println!(
                "[{cycle:3}] command {} (SCW {:#010x}: {})",
                hex(&next.to_bytes()),
                scw.bits(),
                scw.flag_names().collect::<Vec<_>>().join(" ")
            );
        }
        command = next;
        feedback_image = drive.exchange(&command.to_bytes());
    }

    let feedback = Feedback::parse(&feedback_image)?;
    println!(
        "end: status {:#06x} [{}], errors {:#010x}, homed at {:?}, parameter table {}",
        feedback.status.bits(),
        feedback.status.flag_names().collect::<Vec<_>>().join(" "),
        feedback.errors.bits(),
        homed_at,
        feedback.status.parameter_table()
    );
    Ok(())
}
