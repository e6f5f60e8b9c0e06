//! The CiA 402 drive state machine (docs/canopen.md#cia402): arbitrary
//! controlwords, statuswords, drive events and mode bytes through the machine.
//!
//! Input: a sequence of operations, an opcode byte (taken modulo 4) and its
//! payload:
//! `0 controlword:u16` the master writes a controlword · `1 statusword:u16`
//! the drive reports a statusword · `2 event:u8` an event inside the drive
//! (taken modulo 5: power on, initialisation complete, quick stop complete,
//! fault, fault reaction complete) · `3 mode:u8` a 6060h/6061h byte.
//!
//! The machine's state starts unknown (`None`) and follows the transitions;
//! a statusword that shows a state sets it, as a log decoder that watches
//! both words does.
//!
//! Invariants:
//! - a controlword gives fault reset exactly on the 0 → 1 edge of bit 7
//!   (no previous controlword counting as bit 7 = 0), no command exactly
//!   when bit 7 stays 1, and otherwise the one command whose CiA 402 coding
//!   (written out here, independently of the crate's table) matches bits
//!   0–3: disable operation only in operation enabled, switch on never
//!   there; `Controlword::command` agrees, and `with_command` of the result
//!   reads back as it;
//! - a transition leaves the state, its numbers are among those CiA 402
//!   gives the command (or the event), it is the transition numbered so
//!   (`from_number`), and the state it leads to is what `from_statusword`
//!   reads from that state's documented statusword, with any other bits
//!   (the last statusword seen) kept by `with_state`;
//! - a statusword matches at most one state's pattern, exactly the one
//!   `from_statusword` gives, and `with_state` writes each state into it;
//! - a mode byte round-trips and is named, reserved or manufacturer
//!   specific exactly as CiA 402's value table says.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    Cia402Command, Cia402DriveEvent, Cia402State, Cia402Transition, Controlword, ModeOfOperation,
    Statusword,
};
use motionwire_fuzz::Reader;

/// CiA 402's command coding, bits 7, 3, 2, 1, 0 ("x" = any), and the
/// transitions it gives each command.
const CODING: [(Cia402Command, &str, &[u8]); 6] = [
    (Cia402Command::Shutdown, "0x110", &[2, 6, 8]),
    (Cia402Command::SwitchOn, "00111", &[3]),
    (Cia402Command::DisableVoltage, "0xx0x", &[7, 9, 10, 12]),
    (Cia402Command::QuickStop, "0x01x", &[7, 10, 11]),
    (Cia402Command::DisableOperation, "00111", &[5]),
    (Cia402Command::EnableOperation, "01111", &[4, 16, 3]),
];

fn matches(word: u16, pattern: &str) -> bool {
    pattern
        .bytes()
        .zip([7, 3, 2, 1, 0])
        .all(|(c, bit)| match c {
            b'0' => word & (1 << bit) == 0,
            b'1' => word & (1 << bit) != 0,
            _ => true,
        })
}

/// The transition numbers CiA 402 gives a command.
fn command_numbers(command: Cia402Command) -> &'static [u8] {
    match command {
        Cia402Command::FaultReset => &[15],
        command => CODING.iter().find(|(c, _, _)| *c == command).unwrap().2,
    }
}

fn event_numbers(event: Cia402DriveEvent) -> &'static [u8] {
    match event {
        Cia402DriveEvent::PowerOn => &[0],
        Cia402DriveEvent::InitializationComplete => &[1],
        Cia402DriveEvent::QuickStopComplete => &[12],
        Cia402DriveEvent::Fault => &[13],
        Cia402DriveEvent::FaultReactionComplete => &[14],
    }
}

fn check_transition(
    from: Cia402State,
    t: Cia402Transition,
    allowed: &[u8],
    statusword: Statusword,
) -> Cia402State {
    let to = t.to();
    assert_ne!(to, from, "{t} from {from}");
    assert!(
        t.numbers().iter().all(|n| allowed.contains(n)),
        "{t} not in {allowed:?}"
    );
    match t.numbers() {
        [n] => assert_eq!(Cia402Transition::from_number(*n), Some(t)),
        [3, 4] => assert_eq!(t, Cia402Transition::T3T4),
        other => panic!("numbers {other:?}"),
    }
    assert!(Cia402Transition::ALL.contains(&t));
    assert_eq!(
        Cia402State::from_statusword(to.statusword().bits()),
        Some(to)
    );
    assert_eq!(statusword.with_state(to).state(), Some(to));
    to
}

fuzz_target!(|data: &[u8]| {
    let mut input = Reader::new(data);
    let mut state: Option<Cia402State> = None;
    let mut previous: Option<u16> = None;
    let mut statusword = Statusword::empty();

    while let Some(op) = input.u8() {
        match op % 4 {
            0 => {
                let Some(word) = input.u16() else { return };
                let command = Cia402Command::from_controlword(word, previous, state);
                let bit7 = word & 0x80 != 0;
                let bit7_before = previous.is_some_and(|p| p & 0x80 != 0);
                let expected = if bit7 && !bit7_before {
                    Some(Cia402Command::FaultReset)
                } else if bit7 {
                    None
                } else {
                    let found: Vec<_> = CODING
                        .iter()
                        .filter(|(c, p, _)| {
                            let here = state == Some(Cia402State::OperationEnabled);
                            matches(word, p)
                                && match c {
                                    Cia402Command::SwitchOn => !here,
                                    Cia402Command::DisableOperation => here,
                                    _ => true,
                                }
                        })
                        .map(|&(c, _, _)| c)
                        .collect();
                    assert_eq!(found.len(), 1, "{word:#06x}: {found:?}");
                    Some(found[0])
                };
                assert_eq!(
                    command, expected,
                    "{word:#06x} after {previous:x?} in {state:?}"
                );
                let cw = Controlword::from_bits_retain(word);
                assert_eq!(
                    cw.command(previous.map(Controlword::from_bits_retain), state),
                    command
                );
                if let Some(command) = command {
                    let written = cw.with_command(command);
                    assert_eq!(written.bits() & !0x8F, word & !0x8F);
                    assert_eq!(
                        written.command(Some(Controlword::empty()), state),
                        Some(command)
                    );
                    let _ = (command.name(), command.to_string());
                    if let Some(from) = state {
                        if let Some(t) = from.next(command) {
                            state = Some(check_transition(
                                from,
                                t,
                                command_numbers(command),
                                statusword,
                            ));
                        }
                    }
                }
                let _ = cw.to_string();
                previous = Some(word);
            }
            1 => {
                let Some(word) = input.u16() else { return };
                statusword = Statusword::from_bits_retain(word);
                let shown = Cia402State::from_statusword(word);
                let matching: Vec<_> = Cia402State::ALL
                    .into_iter()
                    .filter(|s| {
                        let (mask, value) = s.statusword_pattern();
                        word & mask == value
                    })
                    .collect();
                assert!(matching.len() <= 1);
                assert_eq!(shown, matching.first().copied());
                assert_eq!(statusword.state(), shown);
                for s in Cia402State::ALL {
                    assert_eq!(statusword.with_state(s).state(), Some(s));
                }
                let _ = statusword.to_string();
                if shown.is_some() {
                    state = shown;
                }
            }
            2 => {
                let Some(byte) = input.u8() else { return };
                let event = Cia402DriveEvent::ALL[usize::from(byte % 5)];
                // Before the first state is known only a power on says one.
                let from = match state {
                    Some(from) => from,
                    None if event == Cia402DriveEvent::PowerOn => Cia402State::NotReadyToSwitchOn,
                    None => continue,
                };
                match from.on_drive_event(event) {
                    Some(t) if event == Cia402DriveEvent::PowerOn && from == t.to() => {
                        assert_eq!(t, Cia402Transition::T0);
                    }
                    Some(t) => {
                        state = Some(check_transition(from, t, event_numbers(event), statusword));
                    }
                    None => assert_ne!(event, Cia402DriveEvent::PowerOn),
                }
            }
            _ => {
                let Some(byte) = input.u8() else { return };
                let mode = ModeOfOperation::from_byte(byte);
                let value = byte as i8;
                assert_eq!(mode.to_i8(), value);
                assert_eq!(mode.to_byte(), byte);
                assert_eq!(mode.is_manufacturer_specific(), value < 0);
                assert_eq!(mode.is_reserved(), value == 5 || value > 10);
                let named = (0..=10).contains(&value) && value != 5;
                assert_eq!(
                    ModeOfOperation::NAMED
                        .iter()
                        .any(|&(m, n)| m == mode && n == mode.name()),
                    named
                );
                let _ = mode.to_string();
            }
        }
    }
    assert!(input.is_empty());
});
