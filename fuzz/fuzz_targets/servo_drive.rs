//! The drive model of docs/servo.md#drive-model fed arbitrary command frames
//! and injections: every drive-side rule of docs/servo.md#handshakes must hold
//! on every cycle, whatever the NC writes (any set point, any control word,
//! reserved bits included).
//!
//! Input: one configuration byte, then cycles of 11 bytes each:
//! `[injection, command (10 bytes, the frame of docs/servo.md#command)]`.
//! - configuration: bit 0 Servo_Ready_Mode, bit 1 incremental encoder,
//!   bit 2 disable on fault, bits 3–4 error-clear delay, bit 5 a zero pulse
//!   every 256 counts (else a single one), bit 6 16-bit set point; the zero
//!   pulse lies at 100.
//! - injection: 0–24 inject the SEW bit of that number (the reserved bit 4
//!   and anything that is not a defined bit does nothing), 0x40 lose the
//!   encoder, 0x41 restore it, 0x42 heat the motor above both limits, 0x43
//!   cool it down; anything else nothing.
//!
//! Invariants, checked every cycle:
//! - ServoRDY = !ServoErrors && (m == 0 || ServoEn); the summary bit is set
//!   exactly when the error word is not empty; Abs/Incr is the configured
//!   encoder; PulseEnabled = ServoEn; the active parameter table echoes
//!   the command's;
//! - ServoEn only with SE = 0b10 after SE = 0b01 or while enabled (and
//!   without errors when faults disable); the edge 0b01 → 0b10 enables when
//!   nothing stops it;
//! - ErrClearAck only while ErrorClear is 1, first exactly after the
//!   configured delay, and then only errors with a persisting cause remain;
//!   injected faults show until cleared;
//! - ZPulseAck only while ZPulseRequest is 1 and with an incremental
//!   encoder; when it rises, POSW2..3 holds a zero pulse the axis just
//!   reached;
//! - the applied speed is the set point, the emergency feed or 0 under
//!   POSLOCK while enabled, 0 otherwise; ActPos moves by exactly that,
//!   wrapping like a counter, unless the encoder is lost; the frame carries it in the encoder's layout;
//! - the message code follows the rotation; the feedback round-trips
//!   through its 40 bytes.
#![no_main]

use core::num::NonZeroU32;

use libfuzzer_sys::fuzz_target;
use motionwire::servo::{
    servo_ready, ActualPosition, Command, Drive, DriveConfig, EncoderKind, Feedback,
    ServoControlWord, ServoEnable, ServoErrorWord, ServoFault, ServoReadyMode, ServoStatusWord,
    SetpointWidth, COMMAND_LEN,
};
use motionwire_fuzz::Reader;

fuzz_target!(|data: &[u8]| {
    let mut input = Reader::new(data);
    let Some(setup) = input.u8() else { return };
    let config = DriveConfig {
        ready_mode: if setup & 1 == 0 {
            ServoReadyMode::ErrorFree
        } else {
            ServoReadyMode::EnabledAndErrorFree
        },
        encoder: if setup & 2 == 0 {
            EncoderKind::Absolute
        } else {
            EncoderKind::Incremental
        },
        disable_on_fault: setup & 4 != 0,
        error_clear_delay: u16::from((setup >> 3) & 0b11),
        zero_pulse_pitch: if setup & 0x20 != 0 {
            NonZeroU32::new(256)
        } else {
            None
        },
        setpoint_width: if setup & 0x40 != 0 {
            SetpointWidth::Word
        } else {
            SetpointWidth::DoubleWord
        },
        zero_pulse_position: 100,
        ..DriveConfig::default()
    };
    let mut drive = Drive::new(config);
    let mut previous: Option<Feedback> = None;
    let mut previous_se = ServoEnable::DISABLED;
    let mut clear_run = 0u32;
    let mut lost = false;
    let mut hot = false;
    let mut injected = ServoErrorWord::empty();

    while let (Some(injection), Some(bytes)) = (input.u8(), input.array::<COMMAND_LEN>()) {
        match injection {
            0..=24 => {
                if let Some(fault) = ServoFault::from_bit(injection) {
                    drive.inject(fault);
                    injected |= fault.flag();
                }
            }
            0x40 => {
                drive.lose_encoder();
                lost = true;
            }
            0x41 => {
                drive.restore_encoder();
                lost = false;
            }
            0x42 => {
                drive.set_motor_temperature(120.0);
                hot = true;
            }
            0x43 => {
                drive.set_motor_temperature(30.0);
                hot = false;
            }
            _ => {}
        }
        let command = Command::from_bytes(&bytes);
        let scw = command.control;
        let se = scw.servo_enable();
        let old = drive.position();
        let fb = drive.cycle(&command);
        let st = fb.status;
        let was = |flag| previous.is_some_and(|p: Feedback| p.status.contains(flag));
        let clear = scw.contains(ServoControlWord::ERROR_CLEAR);
        clear_run = if clear {
            clear_run.saturating_add(1)
        } else {
            0
        };

        assert_eq!(
            st.contains(ServoStatusWord::SERVO_RDY),
            servo_ready(config.ready_mode, st, fb.errors)
        );
        assert_eq!(
            fb.errors.contains(ServoErrorWord::SERVO_ERRORS),
            !fb.errors.is_empty()
        );
        assert_eq!(st.encoder(), config.encoder);
        let enabled = st.contains(ServoStatusWord::SERVO_EN);
        assert_eq!(st.contains(ServoStatusWord::PULSE_ENABLED), enabled);
        assert_eq!(st.parameter_table(), scw.parameter_table());

        // Enable.
        if enabled {
            assert_eq!(se, ServoEnable::ENABLE);
            assert!(previous_se == ServoEnable::ARM || was(ServoStatusWord::SERVO_EN));
            assert!(!config.disable_on_fault || fb.errors.is_empty());
        }
        if previous_se == ServoEnable::ARM
            && se == ServoEnable::ENABLE
            && (fb.errors.is_empty() || !config.disable_on_fault)
        {
            assert!(enabled);
        }

        // Error clear.
        let ack = st.contains(ServoStatusWord::ERR_CLEAR_ACK);
        let due = u32::from(config.error_clear_delay) + 1;
        if ack {
            assert!(clear && clear_run >= due);
        }
        if ack && !was(ServoStatusWord::ERR_CLEAR_ACK) {
            assert_eq!(clear_run, due);
            let mut allowed = ServoErrorWord::SERVO_ERRORS;
            if lost {
                allowed |= ServoErrorWord::ENCODER_ERR;
            }
            if hot && config.encoder == EncoderKind::Absolute {
                allowed |= ServoErrorWord::I2T_ENDAT;
            }
            assert!(allowed.contains(fb.errors), "{:?} after a clear", fb.errors);
            injected = ServoErrorWord::empty();
        } else if clear_run == due {
            assert!(ack, "the clear is due");
        }
        assert!(fb.errors.contains(injected));
        assert_eq!(st.contains(ServoStatusWord::TEMP_WARNING), hot);

        // Zero pulse.
        let position = drive.position();
        let zack = st.contains(ServoStatusWord::Z_PULSE_ACK);
        if zack {
            assert!(scw.contains(ServoControlWord::Z_PULSE_REQUEST));
            assert_eq!(config.encoder, EncoderKind::Incremental);
        }
        if zack && !was(ServoStatusWord::Z_PULSE_ACK) {
            let latch = drive.zero_pulse_latch();
            let offset = i128::from(latch) - 100;
            match config.zero_pulse_pitch {
                None => assert_eq!(offset, 0),
                Some(pitch) => assert_eq!(offset.rem_euclid(i128::from(pitch.get())), 0),
            }
            assert!((old < latch && latch <= position) || (position <= latch && latch < old));
        }

        // ActPos.
        let speed = if enabled {
            if scw.emergency_active() {
                config.emergency_feed
            } else if scw.contains(ServoControlWord::POSLOCK) {
                0
            } else {
                config.setpoint_width.read(&command)
            }
        } else {
            0
        };
        assert_eq!(drive.applied_speed(), speed);
        // A lost encoder measures nothing: the position stands.
        let moved = if lost { 0 } else { i64::from(speed) };
        assert_eq!(position, old.wrapping_add(moved));
        match fb.actual_position() {
            ActualPosition::Absolute(p) => assert_eq!(p, position),
            ActualPosition::Incremental {
                position: p,
                zero_pulse_position,
            } => {
                assert_eq!(p, position as i32);
                assert_eq!(zero_pulse_position, drive.zero_pulse_latch() as i32);
            }
        }

        // Message channel and bytes.
        let expected = previous.map_or(config.messages.first(), |p| {
            config.messages.next_after(p.message.code)
        });
        assert_eq!(fb.message.code, expected);
        assert_eq!(
            Feedback::from_bytes(&fb.to_bytes()).to_bytes(),
            fb.to_bytes()
        );

        previous_se = se;
        previous = Some(fb);
    }
});
