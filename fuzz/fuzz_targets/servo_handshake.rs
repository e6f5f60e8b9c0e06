//! The NC-side handshakes of docs/servo.md#handshakes driven by an arbitrary
//! drive: the error-clear and zero-pulse request/ack machines, the NC's enable
//! handshake (`EnableHandshake`), the drive's enable rule and the ServoRDY
//! truth table.
//!
//! Input: a sequence of NC cycles, 6 bytes each:
//! `[action, status (u32 LE), se]` where `action` bits 0–1 / 2–3 / 5–6 are
//! the NC's wish for the error-clear / zero-pulse / enable handshake (1 =
//! start, 2 = cancel, else nothing), bit 4 the drive's Servo_Ready_Mode, bit
//! 7 whether the NC writes the SE value the enable handshake returned (1)
//! or `se` (0); `status` is the status word the drive answers with (anything
//! at all); `se` bits 0–1 the SE value the NC writes otherwise.
//!
//! Invariants, checked every cycle:
//! - `step` is pure and changes only its own request bit of the control word;
//!   the request bit is written 1 exactly in `Requested`;
//! - each phase is entered only the way the handshake of
//!   docs/servo.md#handshakes allows: `Acknowledged` only from `Requested` with
//!   the request on the wire and the ack up; `Releasing` only from
//!   `Acknowledged` with the request dropped and the ack still up; `Done` only
//!   from `Acknowledged` or `Releasing` once the ack is down; `UnsolicitedAck`
//!   only with the ack up and no request of ours on the wire; back to
//!   `Requested` only for a held-back start; an ack that is up never leaves the
//!   machine in `Idle` or `Done`;
//! - `cycles_in_phase` counts the steps spent in the phase;
//! - `start` / `cancel` do what their documentation says;
//! - `EnableHandshake::step` is pure and changes only SE, which it writes as
//!   its phase says and never as 0b11; every 0b10 it writes would enable a
//!   drive that accepts every edge (it is the edge 0b01 → 0b10 on the wire,
//!   or held since one); each enable phase is entered only as its table
//!   allows (Enabling from Arming with 0b01 on the wire and ServoEn down,
//!   Enabled from Enabling with 0b10 on the wire and ServoEn up, Dropped
//!   from Enabled with 0b10 on the wire and ServoEn down, Arming back from
//!   Enabling when 0b00 or 0b11 is on the wire, Disabling only with ServoEn
//!   up, Disabled only with it down); `cycles_in_phase` counts its steps;
//! - the drive's enable rule enables only on SE 0b01 → 0b10 and stays
//!   enabled only while SE stays 0b10; ServoRDY = !ServoErrors && (m == 0 ||
//!   ServoEn).
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::servo::{
    drive_enabled, servo_ready, EnableHandshake, EnablePhase, ErrorClear, Handshake,
    HandshakeBits, HandshakePhase, ServoControlWord, ServoEnable, ServoErrorWord, ServoReadyMode,
    ServoStatusWord, ZeroPulse,
};
use motionwire_fuzz::Reader;

use HandshakePhase::*;

fuzz_target!(|data: &[u8]| {
    let mut input = Reader::new(data);
    let mut error_clear = Handshake::<ErrorClear>::new();
    let mut zero_pulse = Handshake::<ZeroPulse>::new();
    // What the NC wrote last cycle.
    let mut command = ServoControlWord::NORMAL;
    let mut enabled = false;
    let mut enable = EnableHandshake::new();

    while let (Some(action), Some(status), Some(se)) = (input.u8(), input.u32(), input.u8()) {
        let status = ServoStatusWord::from_bits_retain(status);

        error_clear = nc_action(error_clear, action & 0b11);
        zero_pulse = nc_action(zero_pulse, (action >> 2) & 0b11);

        let (next, written) = step_checked(error_clear, command, status);
        error_clear = next;
        let (next, written) = step_checked(zero_pulse, written, status);
        zero_pulse = next;
        enable = enable_action(enable, (action >> 5) & 0b11);
        let (next, written) = enable_step_checked(enable, written, status, enabled);
        enable = next;

        // The drive's enable rule on the SE the NC writes this cycle.
        let previous_se = command.servo_enable();
        let current_se = if action & 0x80 != 0 {
            written.servo_enable()
        } else {
            ServoEnable::new(se & 0b11).expect("two bits")
        };
        let now_enabled = drive_enabled(previous_se, current_se, enabled);
        if now_enabled {
            assert_eq!(current_se, ServoEnable::ENABLE);
            assert!(enabled || previous_se == ServoEnable::ARM);
        }
        if previous_se == ServoEnable::ARM && current_se == ServoEnable::ENABLE {
            assert!(now_enabled);
        }
        enabled = now_enabled;
        command = written.with_servo_enable(current_se);

        // ServoRDY truth table, docs/servo.md#servo-ready.
        let mode = ServoReadyMode::new((action >> 4) & 1).expect("one bit");
        let drive_enabled = status.contains(ServoStatusWord::SERVO_EN);
        let errors = ServoErrorWord::from_bits_retain(status.bits());
        assert_eq!(
            servo_ready(mode, status, errors),
            !errors.contains(ServoErrorWord::SERVO_ERRORS)
                && (mode == ServoReadyMode::ErrorFree || drive_enabled)
        );
    }
});

/// Apply the NC's enable wish (1 = start, 2 = cancel) and check what it
/// did.
fn enable_action(state: EnableHandshake, wish: u8) -> EnableHandshake {
    use EnablePhase::*;
    match wish {
        1 => {
            let next = state.start();
            match state.phase() {
                Disabled | Disabling | Dropped => {
                    assert_eq!(next.phase(), Arming);
                    assert_eq!(next.cycles_in_phase(), 0);
                }
                Arming | Enabling | Enabled => assert_eq!(next, state),
            }
            next
        }
        2 => {
            let next = state.cancel();
            match state.phase() {
                Disabled | Disabling => assert_eq!(next, state),
                Dropped => assert_eq!(next, EnableHandshake::new()),
                Arming | Enabling | Enabled => {
                    assert_eq!((next.phase(), next.cycles_in_phase()), (Disabling, 0))
                }
            }
            next
        }
        _ => state,
    }
}

/// Step the enable handshake and check every invariant of one cycle.
/// `would_enable` is what the drive's rule says about the SE values on the
/// wire so far (a drive that accepts every edge).
fn enable_step_checked(
    state: EnableHandshake,
    last_command: ServoControlWord,
    status: ServoStatusWord,
    would_enable: bool,
) -> (EnableHandshake, ServoControlWord) {
    use EnablePhase::*;
    let (next, written) = state.step(last_command, status);
    assert_eq!(
        state.step(last_command, status),
        (next, written),
        "step is pure"
    );
    // Only SE changes; it is the phase's, never 0b11, and 0b10 only as the
    // edge or held since the edge.
    assert_eq!(written.bits() & !0b11, last_command.bits() & !0b11);
    assert_eq!(written.servo_enable(), next.phase().servo_enable());
    assert_eq!(next.apply(last_command), written);
    assert_ne!(written.servo_enable(), ServoEnable::BOTH);
    let on_the_wire = last_command.servo_enable();
    if written.servo_enable() == ServoEnable::ENABLE {
        assert!(
            drive_enabled(on_the_wire, ServoEnable::ENABLE, would_enable),
            "0b10 after {on_the_wire} without an edge"
        );
    }
    assert_eq!(next.is_enabled(), next.phase() == Enabled);

    let en = status.contains(ServoStatusWord::SERVO_EN);
    let (from, to) = (state.phase(), next.phase());
    if from == to {
        assert_eq!(
            next.cycles_in_phase(),
            state.cycles_in_phase().saturating_add(1)
        );
    } else {
        assert_eq!(next.cycles_in_phase(), 0);
        match to {
            Enabling => assert!(from == Arming && on_the_wire == ServoEnable::ARM && !en),
            Enabled => assert!(from == Enabling && on_the_wire == ServoEnable::ENABLE && en),
            Dropped => assert!(from == Enabled && on_the_wire == ServoEnable::ENABLE && !en),
            Arming => assert!(
                from == Enabling
                    && (on_the_wire == ServoEnable::DISABLED || on_the_wire == ServoEnable::BOTH)
            ),
            Disabling => assert!(en && matches!(from, Disabled | Dropped | Enabled)),
            Disabled => assert!(!en && matches!(from, Disabling | Enabled)),
        }
    }
    let _ = to.name();
    (next, written)
}

/// Apply the NC's wish (1 = start, 2 = cancel) and check what it did.
fn nc_action<B: HandshakeBits + PartialEq + core::fmt::Debug>(
    state: Handshake<B>,
    wish: u8,
) -> Handshake<B> {
    match wish {
        1 => {
            let next = state.start();
            match state.phase() {
                Idle | Done => {
                    assert_eq!(next.phase(), Requested);
                    assert_eq!(next.cycles_in_phase(), 0);
                    assert!(!next.start_held_back());
                }
                UnsolicitedAck => {
                    assert_eq!(next.phase(), UnsolicitedAck);
                    assert!(next.start_held_back());
                }
                Requested | Acknowledged | Releasing => assert_eq!(next, state),
            }
            next
        }
        2 => {
            let next = state.cancel();
            assert_eq!(next, Handshake::new());
            next
        }
        _ => state,
    }
}

/// Step one handshake and check every invariant of one cycle.
fn step_checked<B: HandshakeBits + PartialEq + core::fmt::Debug>(
    state: Handshake<B>,
    last_command: ServoControlWord,
    status: ServoStatusWord,
) -> (Handshake<B>, ServoControlWord) {
    let (next, written) = state.step(last_command, status);
    assert_eq!(
        state.step(last_command, status),
        (next, written),
        "step is pure"
    );

    // Only the request bit changes, and it is 1 exactly in Requested.
    assert_eq!(
        written.bits() & !B::REQUEST.bits(),
        last_command.bits() & !B::REQUEST.bits()
    );
    assert_eq!(written.contains(B::REQUEST), next.phase() == Requested);
    assert_eq!(next.request_bit(), next.phase() == Requested);
    assert_eq!(next.apply(last_command), written);

    let requested = last_command.contains(B::REQUEST);
    let ack = status.contains(B::ACK);
    let (from, to) = (state.phase(), next.phase());

    if ack {
        assert!(!matches!(to, Idle | Done), "{from} → {to} with the ack up");
    } else {
        assert!(
            !matches!(to, Releasing | UnsolicitedAck),
            "{from} → {to} with the ack down"
        );
    }
    // Only an unsolicited ack holds a start back, and it keeps holding it
    // while the ack stays up.
    assert!(!next.start_held_back() || to == UnsolicitedAck);
    if from == UnsolicitedAck && to == UnsolicitedAck {
        assert_eq!(next.start_held_back(), state.start_held_back());
    }

    if from == to {
        assert_eq!(
            next.cycles_in_phase(),
            state.cycles_in_phase().saturating_add(1)
        );
    } else {
        assert_eq!(next.cycles_in_phase(), 0);
        match to {
            Requested => assert!(from == UnsolicitedAck && state.start_held_back() && !ack),
            Acknowledged => assert!(from == Requested && requested && ack),
            Releasing => assert!(from == Acknowledged && !requested && ack),
            Done => {
                assert!((from == Acknowledged && !requested && !ack) || (from == Releasing && !ack))
            }
            UnsolicitedAck => {
                assert!(ack && (matches!(from, Idle | Done) || (from == Requested && !requested)))
            }
            Idle => assert!(from == UnsolicitedAck && !state.start_held_back() && !ack),
        }
    }
    let _ = to.name();
    (next, written)
}
