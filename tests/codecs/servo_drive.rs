//! The crate's NC-side handshakes against the crate's drive model
//! (docs/servo.md#handshakes, docs/servo.md#drive-model), through real frame
//! bytes: every `ServoReadyMode` and encoder kind, `EnableHandshake` with
//! faults and error clears for thousands of cycles, and a property test of
//! random command sequences with injected faults that checks the drive-side
//! rules on every cycle.

use std::num::NonZeroU32;

use motionwire::servo::{
    servo_ready, ActualPosition, Command, Drive, DriveConfig, EnableHandshake, EnablePhase,
    EncoderKind, ErrorClearHandshake, Feedback, HandshakePhase, MessageRotation, ServoControlWord,
    ServoEnable, ServoErrorWord, ServoFault, ServoReadyMode, ServoStatusWord, ZeroPulseHandshake,
    COMMAND_LEN, FEEDBACK_LEN,
};
use proptest::prelude::*;

const MODES: [ServoReadyMode; 2] = [
    ServoReadyMode::ErrorFree,
    ServoReadyMode::EnabledAndErrorFree,
];
const ENCODERS: [EncoderKind; 2] = [EncoderKind::Absolute, EncoderKind::Incremental];

/// One exchange through the bytes of the process image: the NC's command
/// is encoded, the drive decodes it, and its feedback is encoded and
/// decoded again.
fn exchange(drive: &mut Drive, command: &Command) -> Feedback {
    let out: [u8; COMMAND_LEN] = command.to_bytes();
    let command = Command::parse(&out).expect("10 bytes");
    let back: [u8; FEEDBACK_LEN] = drive.cycle(&command).to_bytes();
    Feedback::parse(&back).expect("40 bytes")
}

/// An NC written against the crate's handshakes: it enables the drive,
/// clears errors and searches the zero pulse, one cycle at a time.
struct Nc {
    scw: ServoControlWord,
    setpoint: i32,
    clear: ErrorClearHandshake,
    zero: ZeroPulseHandshake,
    last: Option<Feedback>,
}

impl Nc {
    fn new() -> Self {
        Nc {
            scw: ServoControlWord::NORMAL,
            setpoint: 0,
            clear: ErrorClearHandshake::new(),
            zero: ZeroPulseHandshake::new(),
            last: None,
        }
    }

    /// One cycle: step both handshakes on the newest feedback, write SE,
    /// exchange.
    fn cycle(&mut self, drive: &mut Drive, se: ServoEnable) -> Feedback {
        if let Some(fb) = self.last {
            (self.clear, self.scw) = self.clear.step(self.scw, fb.status);
            (self.zero, self.scw) = self.zero.step(self.scw, fb.status);
        } else {
            self.scw = self.zero.apply(self.clear.apply(self.scw));
        }
        self.scw = self.scw.with_servo_enable(se);
        let fb = exchange(drive, &Command::new(self.setpoint, self.scw, 0));
        self.last = Some(fb);
        fb
    }

    /// Enable: SE 0b00, 0b01, then 0b10 until ServoEn and ServoRDY; return
    /// the cycles taken.
    fn enable(&mut self, drive: &mut Drive) -> u32 {
        let _ = self.cycle(drive, ServoEnable::DISABLED);
        let _ = self.cycle(drive, ServoEnable::ARM);
        for n in 3..100 {
            let fb = self.cycle(drive, ServoEnable::ENABLE);
            if fb
                .status
                .contains(ServoStatusWord::SERVO_EN | ServoStatusWord::SERVO_RDY)
            {
                return n;
            }
        }
        panic!("the drive did not enable");
    }

    /// Run the error-clear handshake to Done, holding SE; return the cycles.
    fn clear_errors(&mut self, drive: &mut Drive, se: ServoEnable) -> u32 {
        self.clear = self.clear.start();
        for n in 1..100 {
            let _ = self.cycle(drive, se);
            if n > 1 && self.clear.phase() == HandshakePhase::Done {
                return n;
            }
        }
        panic!("error clear did not complete: {:?}", self.clear.phase());
    }
}

/// Enable, fault, clear and enable again, for every Servo_Ready_Mode and
/// encoder kind; ServoRDY follows the truth table throughout.
#[test]
fn enable_and_error_clear_complete_for_every_mode_and_encoder() {
    for mode in MODES {
        for encoder in ENCODERS {
            for delay in [0, 1, 5] {
                let mut drive = Drive::new(DriveConfig {
                    ready_mode: mode,
                    encoder,
                    error_clear_delay: delay,
                    ..DriveConfig::default()
                });
                let mut nc = Nc::new();
                // Before enabling, mode 0 is ready and mode 1 is not.
                let fb = nc.cycle(&mut drive, ServoEnable::DISABLED);
                assert_eq!(
                    fb.status.contains(ServoStatusWord::SERVO_RDY),
                    mode == ServoReadyMode::ErrorFree
                );
                assert_eq!(fb.status.encoder(), encoder);
                assert_eq!(nc.enable(&mut drive), 3, "{mode:?} {encoder}");

                for fault in [ServoFault::FollowerErr, ServoFault::ECatWatchDog] {
                    drive.inject(fault);
                    let fb = nc.cycle(&mut drive, ServoEnable::ENABLE);
                    assert!(!fb.status.contains(ServoStatusWord::SERVO_RDY));
                    assert!(!fb.status.contains(ServoStatusWord::SERVO_EN));
                    assert_eq!(fb.errors, fault.flag() | ServoErrorWord::SERVO_ERRORS);
                    assert!(fault.e_code().is_some());

                    // Request, ack after the delay, drop, ack dropped.
                    let cycles = nc.clear_errors(&mut drive, ServoEnable::ENABLE);
                    assert_eq!(
                        cycles,
                        u32::from(delay) + 3,
                        "{mode:?} {encoder} delay {delay}"
                    );
                    let fb = nc.last.unwrap();
                    assert!(fb.errors.is_empty());
                    assert_eq!(
                        fb.status.contains(ServoStatusWord::SERVO_RDY),
                        mode == ServoReadyMode::ErrorFree
                    );
                    assert_eq!(nc.enable(&mut drive), 3);
                }
            }
        }
    }
}

/// Zero pulse: with an incremental encoder the handshake completes once the
/// axis passes the pulse, POSW2..3 holding its position; with an absolute
/// encoder the drive never answers and the NC gives up.
#[test]
fn zero_pulse_handshake_for_every_mode_and_encoder() {
    for mode in MODES {
        for encoder in ENCODERS {
            for (zero_pulse_position, setpoint) in [(1_000, 100), (-2_345, -70), (7, 3)] {
                let mut drive = Drive::new(DriveConfig {
                    ready_mode: mode,
                    encoder,
                    zero_pulse_position,
                    zero_pulse_pitch: None,
                    ..DriveConfig::default()
                });
                let mut nc = Nc::new();
                let _ = nc.enable(&mut drive);
                nc.setpoint = setpoint;
                nc.zero = nc.zero.start();
                let mut found = None;
                for _ in 0..200 {
                    let fb = nc.cycle(&mut drive, ServoEnable::ENABLE);
                    // The cycle whose feedback the NC will read as the ack.
                    if fb.status.contains(ServoStatusWord::Z_PULSE_ACK) && found.is_none() {
                        found = Some(fb.actual_position());
                    }
                    if nc.zero.phase() == HandshakePhase::Done {
                        break;
                    }
                }
                match encoder {
                    EncoderKind::Incremental => {
                        assert_eq!(nc.zero.phase(), HandshakePhase::Done, "{mode:?}");
                        let Some(ActualPosition::Incremental {
                            position,
                            zero_pulse_position: latched,
                        }) = found
                        else {
                            panic!("no incremental ack: {found:?}");
                        };
                        assert_eq!(latched, zero_pulse_position);
                        // The ack comes in the cycle the axis reaches the pulse.
                        assert!((position - latched).abs() < setpoint.abs(), "{position}");
                    }
                    EncoderKind::Absolute => {
                        assert_eq!(nc.zero.phase(), HandshakePhase::Requested);
                        assert!(nc.zero.cycles_in_phase() >= 199);
                        assert_eq!(found, None);
                        nc.zero = nc.zero.cancel();
                        let fb = nc.cycle(&mut drive, ServoEnable::ENABLE);
                        let fb = nc.cycle(&mut drive, ServoEnable::ENABLE).status.bits()
                            | fb.status.bits();
                        assert_eq!(fb & ServoStatusWord::Z_PULSE_ACK.bits(), 0);
                        assert_eq!(nc.zero.phase(), HandshakePhase::Idle);
                    }
                }
            }
        }
    }
}

/// Both handshakes at once, with the encoder lost and found again: the
/// clear is acknowledged while the cause persists, and a second clear after
/// the encoder is back leaves no error.
#[test]
fn lost_encoder_needs_a_clear_after_it_is_back() {
    let mut drive = Drive::new(DriveConfig::default());
    let mut nc = Nc::new();
    let _ = nc.enable(&mut drive);
    drive.lose_encoder();
    let fb = nc.cycle(&mut drive, ServoEnable::ENABLE);
    assert_eq!(
        fb.errors.faults().map(ServoFault::name).collect::<Vec<_>>(),
        ["ServoErrors", "EncoderErr"]
    );
    let _ = nc.clear_errors(&mut drive, ServoEnable::DISABLED);
    assert!(nc
        .last
        .unwrap()
        .errors
        .contains(ServoErrorWord::ENCODER_ERR));
    drive.restore_encoder();
    let _ = nc.clear_errors(&mut drive, ServoEnable::DISABLED);
    assert!(nc.last.unwrap().errors.is_empty());
    assert_eq!(nc.enable(&mut drive), 3);
}

/// `EnableHandshake` against the drive model for 5 000 cycles, through the
/// frames' bytes, for every Servo_Ready_Mode, encoder kind and several
/// error-clear delays: enable, a fault every 400 cycles (every SEW bit in
/// turn) that makes the drive drop ServoEn, the error clear with
/// `ErrorClearHandshake`, and the enable again. A fault in the very cycle
/// of the first edge (cycle 1) is a refused edge: the NC times out,
/// withdraws the enable and clears. The handshake and the drive agree on
/// every cycle, and the axis moves only while enabled.
#[test]
fn enable_handshake_enable_fault_clear_enable_again_for_5000_cycles() {
    use EnablePhase::*;
    for mode in MODES {
        for encoder in ENCODERS {
            for error_clear_delay in [0, 1, 4] {
                for first_fault in [1, 200, 201] {
                    let case = format!(
                        "{mode:?} {encoder} delay {error_clear_delay} first fault {first_fault}"
                    );
                    let mut drive = Drive::new(DriveConfig {
                        ready_mode: mode,
                        encoder,
                        error_clear_delay,
                        ..DriveConfig::default()
                    });
                    let mut enable = EnableHandshake::new();
                    let mut clear = ErrorClearHandshake::new();
                    let mut scw = ServoControlWord::NORMAL;
                    let mut feedback = exchange(&mut drive, &Command::new(0, scw, 0));
                    let (mut enables, mut drops, mut refused) = (0u32, 0u32, 0u32);
                    let mut enabled_cycles = 0i64;
                    for cycle in 0..5_000u32 {
                        if cycle >= first_fault && (cycle - first_fault) % 400 == 0 {
                            let i = (cycle - first_fault) / 400;
                            drive.inject(ServoFault::ALL[i as usize % ServoFault::ALL.len()]);
                        }
                        // The NC: enable whenever the drive is error free,
                        // clear first otherwise; give up on an edge the
                        // drive does not answer.
                        match enable.phase() {
                            Disabled | Dropped if feedback.errors.is_empty() => {
                                enable = enable.start();
                            }
                            Disabled | Dropped => clear = clear.start(),
                            Enabling if enable.cycles_in_phase() >= 3 => {
                                refused += 1;
                                enable = enable.cancel();
                            }
                            _ => {}
                        }
                        let before = enable.phase();
                        (enable, scw) = enable.step(scw, feedback.status);
                        (clear, scw) = clear.step(scw, feedback.status);
                        let was_enabled = drive.is_enabled();
                        feedback = exchange(&mut drive, &Command::new(50, scw, 0));

                        let en = feedback.status.contains(ServoStatusWord::SERVO_EN);
                        assert_eq!(en, drive.is_enabled());
                        if en {
                            enabled_cycles += 1;
                            assert!(matches!(enable.phase(), Enabling | Enabled), "{case}");
                            assert!(feedback.errors.is_empty(), "{case}");
                        }
                        let now = enable.phase();
                        if now == Enabled && before != Enabled {
                            enables += 1;
                            assert!(was_enabled, "{case}, cycle {cycle}: Enabled on ServoEn");
                        }
                        if now == Dropped && before != Dropped {
                            drops += 1;
                            assert!(!was_enabled, "{case}, cycle {cycle}: Dropped on no ServoEn");
                        }
                        assert_ne!(clear.phase(), HandshakePhase::UnsolicitedAck, "{case}");
                    }
                    // Faults at `first_fault` + 400 k: 12 or 13 in 5 000
                    // cycles, each seen as a drop (or the refused first
                    // edge), cleared, and the drive enabled again.
                    let faults = (5_000 - 1 - first_fault) / 400 + 1;
                    assert_eq!(refused, u32::from(first_fault == 1), "{case}");
                    assert_eq!(drops + refused, faults, "{case}");
                    assert_eq!(enables, 1 + faults - refused, "{case}");
                    assert!(enable.is_enabled(), "{case}");
                    assert!(feedback.errors.is_empty(), "{case}");
                    assert_eq!(drive.position(), 50 * enabled_cycles, "{case}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------- property

/// What the test does to the drive between two cycles.
#[derive(Debug, Clone, Copy)]
enum Injection {
    Nothing,
    Fault(ServoFault),
    LoseEncoder,
    RestoreEncoder,
    Temperature(f32),
}

fn injection() -> impl Strategy<Value = Injection> {
    prop_oneof![
        80 => Just(Injection::Nothing),
        2 => (0..ServoFault::ALL.len()).prop_map(|i| Injection::Fault(ServoFault::ALL[i])),
        1 => Just(Injection::LoseEncoder),
        4 => Just(Injection::RestoreEncoder),
        1 => prop_oneof![Just(20.0f32), Just(85.0), Just(99.0), Just(f32::NAN)]
            .prop_map(Injection::Temperature),
    ]
}

/// One cycle of the NC: SE (or keep it), ErrorClear, ZPulseRequest, EMGON, POSLOCK, set
/// point, and what happens to the drive before the cycle.
fn step() -> impl Strategy<Value = (u8, bool, bool, bool, bool, i32, Injection)> {
    (
        // SE: 0..=3 writes that value, 4..=15 keeps the previous one, so
        // that SE holds for a while as an NC's does.
        0u8..16,
        any::<bool>(),
        any::<bool>(),
        prop::bool::weighted(0.9),
        prop::bool::weighted(0.1),
        -400i32..400,
        injection(),
    )
}

fn config() -> impl Strategy<Value = DriveConfig> {
    (
        0u8..2,
        any::<bool>(),
        -500i32..500,
        prop_oneof![Just(None), (1u32..2_000).prop_map(NonZeroU32::new)],
        0u16..4,
        any::<bool>(),
        1u16..0x400,
    )
        .prop_map(
            |(mode, incremental, zero, pitch, delay, disable, messages)| DriveConfig {
                ready_mode: ServoReadyMode::new(mode).unwrap(),
                encoder: if incremental {
                    EncoderKind::Incremental
                } else {
                    EncoderKind::Absolute
                },
                zero_pulse_position: zero,
                zero_pulse_pitch: pitch,
                error_clear_delay: delay,
                disable_on_fault: disable,
                messages: MessageRotation::new(messages).unwrap(),
                ..DriveConfig::default()
            },
        )
}

/// Return whether `p` is one of the configuration's zero pulses.
fn is_pulse(config: &DriveConfig, p: i64) -> bool {
    let offset = p - i64::from(config.zero_pulse_position);
    match config.zero_pulse_pitch {
        None => offset == 0,
        Some(pitch) => offset.rem_euclid(i64::from(pitch.get())) == 0,
    }
}

/// How often the interesting events happened over a sequence, to show that
/// the random sequences reach every rule.
#[derive(Debug, Default, Clone, Copy)]
struct Seen {
    enables: u32,
    faults: u32,
    clear_acks: u32,
    zero_acks: u32,
    moves: u32,
}

/// One of the random NC cycles of [`step`].
type Step = (u8, bool, bool, bool, bool, i32, Injection);

/// Run `steps` against a drive with `config`, checking every drive-side
/// rule of docs/servo.md#handshakes on every cycle.
fn check_sequence(config: DriveConfig, steps: &[Step]) -> Result<Seen, TestCaseError> {
    let mut seen = Seen::default();
    let mut drive = Drive::new(config);
    let mut previous_se = ServoEnable::DISABLED;
    let mut previous: Option<Feedback> = None;
    let mut clear_run = 0u32; // consecutive cycles with ErrorClear = 1
    let mut position = 0i64;
    let mut hot = false;
    let mut lost = false;
    let mut injected = ServoErrorWord::empty();

    for &(se, clear, zreq, emgon, poslock, setpoint, injection) in steps {
        match injection {
            Injection::Nothing => {}
            Injection::Fault(fault) => {
                drive.inject(fault);
                injected |= fault.flag();
            }
            Injection::LoseEncoder => {
                drive.lose_encoder();
                lost = true;
            }
            Injection::RestoreEncoder => {
                drive.restore_encoder();
                lost = false;
            }
            Injection::Temperature(t) => {
                drive.set_motor_temperature(t);
                hot = t > config.max_temperature;
            }
        }
        let se = ServoEnable::new(se).unwrap_or(previous_se);
        let scw = ServoControlWord::NORMAL
            .with_servo_enable(se)
            .with_flag(ServoControlWord::ERROR_CLEAR, clear)
            .with_flag(ServoControlWord::Z_PULSE_REQUEST, zreq)
            .with_flag(ServoControlWord::EMGON, emgon)
            .with_flag(ServoControlWord::POSLOCK, poslock);
        let fb = exchange(&mut drive, &Command::new(setpoint, scw, 0));
        let st = fb.status;
        let was = |flag| previous.is_some_and(|p: Feedback| p.status.contains(flag));
        clear_run = if clear { clear_run + 1 } else { 0 };

        // ServoRDY by the truth table; the summary bit; the layout bits.
        prop_assert_eq!(
            st.contains(ServoStatusWord::SERVO_RDY),
            servo_ready(config.ready_mode, st, fb.errors)
        );
        prop_assert_eq!(
            fb.errors.contains(ServoErrorWord::SERVO_ERRORS),
            !fb.errors.is_empty()
        );
        prop_assert_eq!(st.encoder(), config.encoder);
        prop_assert_eq!(
            st.contains(ServoStatusWord::PULSE_ENABLED),
            st.contains(ServoStatusWord::SERVO_EN)
        );
        prop_assert_eq!(st.parameter_table(), scw.parameter_table());

        // Enable: only on the edge 0b01 → 0b10 and while SE stays 0b10.
        let enabled = st.contains(ServoStatusWord::SERVO_EN);
        if enabled {
            prop_assert_eq!(se, ServoEnable::ENABLE);
            prop_assert!(previous_se == ServoEnable::ARM || was(ServoStatusWord::SERVO_EN));
            if config.disable_on_fault {
                prop_assert!(fb.errors.is_empty());
            }
        }
        if previous_se == ServoEnable::ARM
            && se == ServoEnable::ENABLE
            && (fb.errors.is_empty() || !config.disable_on_fault)
        {
            prop_assert!(enabled);
        }

        // Error clear: ack only while requested, first after the delay,
        // and then every error without a persisting cause is gone.
        let ack = st.contains(ServoStatusWord::ERR_CLEAR_ACK);
        if ack {
            prop_assert!(clear);
            prop_assert!(clear_run > u32::from(config.error_clear_delay));
        }
        if ack && !was(ServoStatusWord::ERR_CLEAR_ACK) {
            prop_assert_eq!(clear_run, u32::from(config.error_clear_delay) + 1);
            let mut allowed = ServoErrorWord::SERVO_ERRORS;
            if lost {
                allowed |= ServoErrorWord::ENCODER_ERR;
            }
            if hot && config.encoder == EncoderKind::Absolute {
                allowed |= ServoErrorWord::I2T_ENDAT;
            }
            prop_assert!(
                allowed.contains(fb.errors),
                "{:?} left after a clear",
                fb.errors
            );
            injected = ServoErrorWord::empty();
        } else if clear_run == u32::from(config.error_clear_delay) + 1 {
            prop_assert!(ack, "the clear is due this cycle");
        }
        // Injected faults show (until a clear).
        prop_assert!(fb.errors.contains(injected));

        // Zero pulse: ack only for an incremental encoder while
        // requested; when it rises, POSW2..3 holds a pulse just passed.
        let zack = st.contains(ServoStatusWord::Z_PULSE_ACK);
        if zack {
            prop_assert!(zreq);
            prop_assert_eq!(config.encoder, EncoderKind::Incremental);
        }
        let old = position;
        position = drive.position();
        if zack && !was(ServoStatusWord::Z_PULSE_ACK) {
            let latch = drive.zero_pulse_latch();
            prop_assert!(is_pulse(&config, latch));
            prop_assert!((old < latch && latch <= position) || (position <= latch && latch < old));
            let ActualPosition::Incremental {
                zero_pulse_position,
                ..
            } = fb.actual_position()
            else {
                panic!("incremental layout");
            };
            prop_assert_eq!(i64::from(zero_pulse_position), latch);
        }

        // ActPos integrates the set point while enabled, in the
        // encoder's layout (scale 1:1 by default).
        let expected = if enabled && !lost {
            if !emgon {
                i64::from(config.emergency_feed)
            } else if poslock {
                0
            } else {
                i64::from(setpoint)
            }
        } else {
            0
        };
        prop_assert_eq!(position - old, expected);
        match fb.actual_position() {
            ActualPosition::Absolute(p) => prop_assert_eq!(p, position),
            ActualPosition::Incremental { position: p, .. } => {
                prop_assert_eq!(i64::from(p), position)
            }
        }

        // The message channel rotates through the configured codes.
        prop_assert!(config.messages.contains(fb.message.code));
        let expected_code = previous.map_or(config.messages.first(), |p| {
            config.messages.next_after(p.message.code)
        });
        prop_assert_eq!(fb.message.code, expected_code);

        previous_se = se;
        seen.enables += u32::from(enabled && !was(ServoStatusWord::SERVO_EN));
        seen.faults +=
            u32::from(!fb.errors.is_empty() && previous.is_some_and(|p| p.errors.is_empty()));
        seen.clear_acks += u32::from(ack && !was(ServoStatusWord::ERR_CLEAR_ACK));
        seen.zero_acks += u32::from(zack && !was(ServoStatusWord::Z_PULSE_ACK));
        seen.moves += u32::from(position != old);
        previous = Some(fb);
    }
    Ok(seen)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2_000))]

    /// Thousands of random command sequences with faults injected: every
    /// drive-side rule of docs/servo.md#handshakes holds on every cycle.
    #[test]
    fn drive_rules_hold_on_every_cycle(
        config in config(),
        steps in proptest::collection::vec(step(), 1..150),
    ) {
        check_sequence(config, &steps)?;
    }
}

/// The random sequences are not vacuous: over 300 of them (fixed seed) the
/// drive is enabled, faults, clears, finds zero pulses and moves many times
/// (with this seed: about 300 enables, 460 faults, 2 750 clears, 50 zero
/// pulses found and 1 200 cycles of motion).
#[test]
fn random_sequences_reach_every_rule() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut runner = TestRunner::new_with_rng(
        Config::with_cases(300),
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let strategy = (config(), proptest::collection::vec(step(), 1..150));
    let mut total = Seen::default();
    for _ in 0..300 {
        let (config, steps) = strategy.new_tree(&mut runner).unwrap().current();
        let seen = check_sequence(config, &steps).unwrap();
        total.enables += seen.enables;
        total.faults += seen.faults;
        total.clear_acks += seen.clear_acks;
        total.zero_acks += seen.zero_acks;
        total.moves += seen.moves;
    }
    assert!(total.enables > 100, "{total:?}");
    assert!(total.faults > 100, "{total:?}");
    assert!(total.clear_acks > 100, "{total:?}");
    assert!(total.zero_acks > 20, "{total:?}");
    assert!(total.moves > 500, "{total:?}");
}
