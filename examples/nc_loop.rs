//! An NC running against the crate's drive model for a few thousand cycles
//! (docs/servo.md#handshakes, docs/servo.md#drive-model): enable, move, a
//! fault, error clear, enable again, the zero-pulse search, a lost encoder and
//! an over-temperature warning.
//!
//! The NC is written only against the crate's three handshakes
//! ([`EnableHandshake`], [`ErrorClearHandshake`], [`ZeroPulseHandshake`]):
//! it never writes an SE value or a request bit by hand. It exchanges real
//! 10-byte command and 40-byte feedback frames with the [`Drive`] and prints
//! one line per change of a goal, a handshake phase or the drive's state,
//! with the cycle and position.
//!
//! Run with `cargo run --example nc_loop`.

use motionwire::servo::{
    ActualPosition, Command, Drive, DriveConfig, EnableHandshake, EnablePhase, ErrorClearHandshake,
    Feedback, HandshakePhase, ServoControlWord, ServoFault, ServoStatusWord, ZeroPulseHandshake,
};

/// The cycles the example runs.
const CYCLES: u32 = 4_000;
/// Cycles the NC waits for an ack before it gives up on a handshake.
const TIMEOUT: u32 = 500;
/// Cycles the NC waits before it clears again when an error persists.
const RETRY: u32 = 50;

/// What the NC is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Goal {
    /// Enable the drive, then hold the axis still.
    Enable,
    /// Run the axis at this set point.
    Move(i32),
    /// Clear the drive's errors, then enable again.
    Clear,
    /// Search the zero pulse at this set point.
    Home(i32),
    /// Hold still, disabled.
    Park,
}

struct Nc {
    goal: Goal,
    scw: ServoControlWord,
    setpoint: i32,
    enable: EnableHandshake,
    clear: ErrorClearHandshake,
    zero: ZeroPulseHandshake,
}

impl Nc {
    /// One NC cycle: read the newest feedback, decide, return the command.
    fn cycle(&mut self, feedback: &Feedback) -> Command {
        let status = feedback.status;
        (self.enable, self.scw) = self.enable.step(self.scw, status);
        (self.clear, self.scw) = self.clear.step(self.scw, status);
        (self.zero, self.scw) = self.zero.step(self.scw, status);
        if self.enable.phase() == EnablePhase::Enabling && self.enable.cycles_in_phase() > TIMEOUT {
            println!("NC: no ServoEn after {TIMEOUT} cycles, arming again");
            self.enable = self.enable.cancel().start();
        }
        if self.clear.phase() == HandshakePhase::Requested && self.clear.cycles_in_phase() > TIMEOUT
        {
            println!("NC: no ErrClearAck after {TIMEOUT} cycles, giving up");
            self.clear = self.clear.cancel();
        }
        if self.zero.phase() == HandshakePhase::Requested && self.zero.cycles_in_phase() > TIMEOUT {
            println!("NC: no ZPulseAck after {TIMEOUT} cycles, giving up");
            self.zero = self.zero.cancel();
        }
        // A drive error stops the axis and starts a clear. The drive model
        // drops ServoEn itself (the handshake reports Dropped and writes SE
        // 0b00); in any other phase the NC withdraws the enable.
        if !feedback.errors.is_empty() && self.goal != Goal::Clear && self.goal != Goal::Park {
            self.goal = Goal::Clear;
            self.clear = self.clear.start();
            if self.enable.phase() != EnablePhase::Dropped {
                self.enable = self.enable.cancel();
            }
        }
        self.setpoint = match self.goal {
            Goal::Enable => {
                self.enable = self.enable.start();
                if self.enable.is_enabled() {
                    self.goal = Goal::Move(0);
                }
                0
            }
            Goal::Clear => {
                if self.clear.phase() == HandshakePhase::Done && feedback.errors.is_empty() {
                    self.goal = Goal::Enable;
                    self.enable = self.enable.start();
                } else if self.clear.phase() == HandshakePhase::Done
                    && self.clear.cycles_in_phase() >= RETRY
                {
                    // A cause persists: try again a little later.
                    self.clear = self.clear.start();
                }
                0
            }
            Goal::Move(speed) => speed,
            Goal::Home(speed) => {
                if self.zero.phase() == HandshakePhase::Idle
                    || self.zero.phase() == HandshakePhase::Done
                {
                    self.goal = Goal::Move(0);
                }
                speed
            }
            Goal::Park => {
                self.enable = self.enable.cancel();
                0
            }
        };
        // What the handshakes require after this cycle's starts and cancels.
        self.scw = self
            .zero
            .apply(self.clear.apply(self.enable.apply(self.scw)));
        Command::new(self.setpoint, self.scw, 0)
    }
}

/// What the timeline prints: it changes rarely.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Phases {
    goal: Goal,
    enable: EnablePhase,
    clear: HandshakePhase,
    zero: HandshakePhase,
    enabled: bool,
    ready: bool,
    warning: bool,
    errors: u32,
}

fn main() {
    let mut drive = Drive::new(DriveConfig::default());
    let mut nc = Nc {
        goal: Goal::Enable,
        scw: ServoControlWord::NORMAL,
        setpoint: 0,
        enable: EnableHandshake::new(),
        clear: ErrorClearHandshake::new(),
        zero: ZeroPulseHandshake::new(),
    };
    // The drive's answer before the first cycle: nothing yet.
    let mut feedback = Feedback::from_bytes(&[0; 40]);
    let mut last: Option<Phases> = None;
    let mut homed_at = None;

    println!(
        "{:>5}  {:<12} {:<10} {:<15} {:<15} {:<3} {:<3} {:<4} {:>9} {:>9}  errors",
        "cycle",
        "goal",
        "enable",
        "error clear",
        "zero pulse",
        "en",
        "rdy",
        "temp",
        "ActPos",
        "POSW2..3"
    );
    for cycle in 1..=CYCLES {
        // The script: what happens to the machine.
        match cycle {
            200 => nc.goal = Goal::Move(250),
            800 => drive.inject(ServoFault::FollowerErr),
            1_200 => {
                nc.goal = Goal::Home(-120);
                nc.zero = nc.zero.start();
            }
            2_000 => nc.goal = Goal::Move(400),
            2_300 => drive.set_motor_temperature(86.0),
            2_600 => drive.lose_encoder(),
            2_700 => drive.restore_encoder(),
            3_000 => drive.set_motor_temperature(45.0),
            3_100 => nc.goal = Goal::Move(-300),
            3_500 => nc.goal = Goal::Park,
            _ => {}
        }

        let command = nc.cycle(&feedback);
        // Through the bytes of the process image, as on the bus.
        let received = Command::from_bytes(&command.to_bytes());
        feedback = Feedback::from_bytes(&drive.cycle(&received).to_bytes());

        let (position, zero) = match feedback.actual_position() {
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => (i64::from(position), zero_pulse_position),
            ActualPosition::Absolute(position) => (position, 0),
        };
        if feedback.status.contains(ServoStatusWord::Z_PULSE_ACK) && homed_at.is_none() {
            homed_at = Some((cycle, zero));
        }
        let now = Phases {
            goal: nc.goal,
            enable: nc.enable.phase(),
            clear: nc.clear.phase(),
            zero: nc.zero.phase(),
            enabled: feedback.status.contains(ServoStatusWord::SERVO_EN),
            ready: feedback.status.contains(ServoStatusWord::SERVO_RDY),
            warning: feedback.status.contains(ServoStatusWord::TEMP_WARNING),
            errors: feedback.errors.bits(),
        };
        if last != Some(now) || cycle % 500 == 0 {
            let faults: Vec<_> = feedback
                .errors
                .faults()
                .map(|f| match f.e_code() {
                    Some(code) => format!("{} {code}", f.name()),
                    None => f.name().to_owned(),
                })
                .collect();
            let goal = match now.goal {
                Goal::Enable => "enable".to_owned(),
                Goal::Move(v) => format!("move {v}"),
                Goal::Home(v) => format!("home {v}"),
                Goal::Clear => "clear".to_owned(),
                Goal::Park => "park".to_owned(),
            };
            println!(
                "{cycle:>5}  {goal:<12} {:<10} {:<15} {:<15} {:<3} {:<3} {:<4} {position:>9} {zero:>9}  {}",
                now.enable.name(),
                now.clear.name(),
                now.zero.name(),
                u8::from(now.enabled),
                u8::from(now.ready),
                if now.warning { "warn" } else { "ok" },
                faults.join(", ")
            );
            last = Some(now);
        }
    }
    match homed_at {
        Some((cycle, zero)) => println!("zero pulse found in cycle {cycle} at {zero}"),
        None => println!("zero pulse not found"),
    }
    println!("{CYCLES} cycles, final position {}", drive.position());
}
