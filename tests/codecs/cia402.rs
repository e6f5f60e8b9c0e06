//! The CiA 402 drive state machine (docs/canopen.md#cia402) against an
//! independent implementation: python-canopen's `canopen/profiles/p402.py`.
//!
//! `scripts/gen_cia402_fixtures.py` wrote
//! `tests/fixtures/cia402/python_canopen.json` from python-canopen itself:
//! the state its `BaseNode402.state` gives for every statusword, its
//! `State402.SW_MASK` and `State402.TRANSITIONTABLE`, the controlwords its
//! `state` setter and `reset_from_fault` write to move a drive between
//! states, and its `OperationMode` names.
//!
//! Statuswords: the crate and python-canopen agree on all 65 536.
//!
//! Where python-canopen and docs/canopen.md#cia402 / CiA 402 differ, the crate
//! follows docs/canopen.md#cia402 (its differences are listed in
//! docs/canopen.md#where-tools-disagree) and the test checks the difference
//! exactly:
//!
//! 1. **Automatic transitions.** python-canopen's TRANSITIONTABLE lists
//!    transitions 0 (START → NOT READY TO SWITCH ON), 1 (NOT READY TO SWITCH
//!    ON → SWITCH ON DISABLED) and 14 (FAULT REACTION ACTIVE → FAULT) with
//!    controlword 0x00 (its comment: "automatic"), and its `state` setter
//!    writes 0x00 when a walk starts in those states. CiA 402 draws them as
//!    the drive's own transitions, with no command; 0x00 codes disable
//!    voltage, which has no transition from those states. The crate gives
//!    `None` for the command and the transition through
//!    `Cia402State::on_drive_event` (power on, initialisation complete,
//!    fault reaction complete).
//! 2. **0x07 in OPERATION ENABLED.** python-canopen names the controlword
//!    `CW_SWITCH_ON` for transition 5 (its table's comment);
//!    docs/canopen.md#cia402 names it `disable_operation` there. Same bits,
//!    same target state.
//! 3. **0x80.** python-canopen calls 0x80 `CW_SWITCH_ON_DISABLED` and writes
//!    it from FAULT; docs/canopen.md#cia402 (and CiA 402) read it as
//!    `fault_reset`, the 0 → 1 edge of bit 7, only after a controlword with bit
//!    7 clear. Every 0x80 python-canopen writes follows one (or is the first
//!    controlword), so each is a fault reset.
//! 4. **Mode names.** python-canopen writes `PROFILED POSITION`, `PROFILED
//!    VELOCITY`, `PROFILED TORQUE`; CiA 402 names the modes "profile
//!    position mode", … and docs/canopen.md#cia402 uses CiA 402's names
//!    (`profile_position`). Its `OPEN_LOOP_SCALAR_MODE` (−1) and
//!    `OPEN_LOOP_VECTOR_MODE` (−2) are negative, which CiA 402 leaves to
//!    manufacturers: the crate calls them `manufacturer_specific`.

use motionwire::canopen::{
    Cia402Command, Cia402DriveEvent, Cia402State, Cia402Transition, ModeOfOperation, Statusword,
};
use serde_json::Value;

fn fixture() -> Value {
    serde_json::from_str(include_str!("../fixtures/cia402/python_canopen.json"))
        .expect("the fixture is JSON")
}

/// The crate's state for a python-canopen state name ("QUICK STOP ACTIVE").
fn state(python_name: &str) -> Cia402State {
    let name = python_name.to_lowercase().replace(' ', "_");
    Cia402State::from_name(&name).unwrap_or_else(|| panic!("no state named {python_name}"))
}

fn u16_of(value: &Value) -> u16 {
    u16::try_from(value.as_u64().expect("a number")).expect("a 16-bit word")
}

#[test]
fn every_statusword_reads_as_python_canopen_reads_it() {
    let fixture = fixture();
    let groups = fixture["statusword"]["low_bytes_by_state"]
        .as_object()
        .unwrap();
    let mut by_low_byte: [Option<Option<Cia402State>>; 256] = [None; 256];
    for (name, low_bytes) in groups {
        let expected = (name != "UNKNOWN").then(|| state(name));
        for low in low_bytes.as_array().unwrap() {
            let low = usize::from(u16_of(low));
            assert!(by_low_byte[low].is_none(), "low byte {low:#04x} twice");
            by_low_byte[low] = Some(expected);
        }
    }
    let mut agreed = 0;
    for word in 0..=u16::MAX {
        let expected = by_low_byte[usize::from(word & 0xFF)].expect("every low byte listed");
        assert_eq!(
            Cia402State::from_statusword(word),
            expected,
            "statusword {word:#06x}"
        );
        assert_eq!(Statusword::from_bits_retain(word).state(), expected);
        agreed += 1;
    }
    assert_eq!(agreed, 65_536);
}

#[test]
fn the_statusword_masks_are_python_canopens() {
    let fixture = fixture();
    let masks = fixture["sw_mask"].as_object().unwrap();
    assert_eq!(masks.len(), Cia402State::ALL.len());
    for (name, pair) in masks {
        let pair = pair.as_array().unwrap();
        assert_eq!(
            state(name).statusword_pattern(),
            (u16_of(&pair[0]), u16_of(&pair[1])),
            "{name}"
        );
    }
}

/// The transition numbers python-canopen's TRANSITIONTABLE gives in its
/// comments (`# transition 7` …), by (from, to).
const PYTHON_CANOPEN_NUMBERS: [(&str, &str, u8); 17] = [
    ("READY TO SWITCH ON", "SWITCH ON DISABLED", 7),
    ("OPERATION ENABLED", "SWITCH ON DISABLED", 9),
    ("SWITCHED ON", "SWITCH ON DISABLED", 10),
    ("QUICK STOP ACTIVE", "SWITCH ON DISABLED", 12),
    ("NOT READY TO SWITCH ON", "SWITCH ON DISABLED", 1),
    ("START", "NOT READY TO SWITCH ON", 0),
    ("FAULT REACTION ACTIVE", "FAULT", 14),
    ("SWITCH ON DISABLED", "READY TO SWITCH ON", 2),
    ("SWITCHED ON", "READY TO SWITCH ON", 6),
    ("OPERATION ENABLED", "READY TO SWITCH ON", 8),
    ("READY TO SWITCH ON", "SWITCHED ON", 3),
    ("OPERATION ENABLED", "SWITCHED ON", 5),
    ("SWITCHED ON", "OPERATION ENABLED", 4),
    ("QUICK STOP ACTIVE", "OPERATION ENABLED", 16),
    ("OPERATION ENABLED", "QUICK STOP ACTIVE", 11),
    ("FAULT", "SWITCH ON DISABLED", 15),
    // Not in python-canopen's table: its state setter never asks for a
    // fault. Listed so that the lookup below is total.
    ("OPERATION ENABLED", "FAULT REACTION ACTIVE", 13),
];

fn python_number(from: &str, to: &str) -> u8 {
    PYTHON_CANOPEN_NUMBERS
        .iter()
        .find(|&&(f, t, _)| f == from && t == to)
        .map(|&(_, _, n)| n)
        .unwrap_or_else(|| panic!("no number for {from} -> {to}"))
}

/// What the crate makes of python-canopen writing `controlword` (after
/// `previous`) to a drive in `from` that python-canopen expects to end in
/// `to`; panics where they disagree beyond the documented differences.
fn check_step(from: &str, controlword: u16, previous: Option<u16>, to: &str) {
    let context = format!("{from} --{controlword:#06x} (after {previous:x?})--> {to}");
    if from == "START" {
        // Difference 1: transition 0 is the drive's power-on, no command.
        let t = Cia402State::Fault.on_drive_event(Cia402DriveEvent::PowerOn);
        assert_eq!(t, Some(Cia402Transition::T0), "{context}");
        assert_eq!(Cia402Transition::T0.to(), state(to), "{context}");
        return;
    }
    let before = state(from);
    let command = Cia402Command::from_controlword(controlword, previous, Some(before))
        .unwrap_or_else(|| panic!("{context}: no command"));
    if from == to {
        // The drive stays (reset_from_fault's first 0x00 in FAULT).
        assert_eq!(before.next(command), None, "{context}");
        return;
    }
    let number = python_number(from, to);
    match before.next(command) {
        Some(t) => {
            assert_eq!(t.to(), state(to), "{context}");
            assert_eq!(t.numbers(), &[number], "{context}");
            match number {
                // Difference 2: python-canopen's CW_SWITCH_ON in OPERATION
                // ENABLED is disable_operation (docs/canopen.md#cia402).
                5 => assert_eq!(command, Cia402Command::DisableOperation, "{context}"),
                // Difference 3: python-canopen's CW_SWITCH_ON_DISABLED is
                // fault_reset (docs/canopen.md#cia402), on the edge of bit 7.
                15 => {
                    assert_eq!(command, Cia402Command::FaultReset, "{context}");
                    assert!(previous.map_or(true, |p| p & 0x80 == 0), "{context}");
                }
                _ => {}
            }
        }
        None => {
            // Difference 1: the automatic transitions 1 and 14, for which
            // python-canopen writes 0x00 (disable voltage).
            assert_eq!(controlword, 0x0000, "{context}");
            assert_eq!(command, Cia402Command::DisableVoltage, "{context}");
            let event = match number {
                1 => Cia402DriveEvent::InitializationComplete,
                14 => Cia402DriveEvent::FaultReactionComplete,
                _ => panic!("{context}: python-canopen moves, the crate does not"),
            };
            let t = before
                .on_drive_event(event)
                .expect("the drive's own transition");
            assert_eq!(t.to(), state(to), "{context}");
            assert_eq!(t.numbers(), &[number], "{context}");
        }
    }
}

#[test]
fn every_controlword_of_python_canopens_transition_table() {
    let fixture = fixture();
    let table = fixture["transition_table"].as_array().unwrap();
    assert_eq!(table.len(), 16);
    for entry in table {
        let from = entry["from"].as_str().unwrap();
        let to = entry["to"].as_str().unwrap();
        let controlword = u16_of(&entry["controlword"]);
        // The table gives no previous controlword: bit 7 before a fault
        // reset was 0, as python-canopen's reset_from_fault makes it.
        check_step(from, controlword, Some(0x0000), to);
    }
}

#[test]
fn every_walk_python_canopen_makes_between_states() {
    let fixture = fixture();
    let walks = fixture["walks"].as_array().unwrap();
    // Every start state, every target its setter accepts (5), but itself.
    assert_eq!(walks.len(), 8 * 5 - 5);
    let mut steps_checked = 0;
    for walk in walks {
        assert_eq!(walk["outcome"], "reached", "{walk}");
        let start = walk["start"].as_str().unwrap();
        let mut here = state(start);
        let mut previous = None;
        for step in walk["steps"].as_array().unwrap() {
            let from = step["from"].as_str().unwrap();
            let to = step["to"].as_str().unwrap();
            let controlword = u16_of(&step["controlword"]);
            assert_eq!(state(from), here);
            check_step(from, controlword, previous, to);
            // The statusword python-canopen's drive then shows reads as the
            // state the crate went to.
            let (_, value) = fixture["sw_mask"][to]
                .as_array()
                .map(|p| (u16_of(&p[0]), u16_of(&p[1])))
                .unwrap();
            assert_eq!(Cia402State::from_statusword(value), Some(state(to)));
            here = state(to);
            previous = Some(controlword);
            steps_checked += 1;
        }
        assert_eq!(here, state(walk["target"].as_str().unwrap()));
    }
    assert!(steps_checked > 80, "{steps_checked}");
}

#[test]
fn reset_from_fault_as_python_canopen_sends_it() {
    let fixture = fixture();
    let reset = &fixture["reset_from_fault"];
    let steps = reset["steps"].as_array().unwrap();
    let words: Vec<u16> = steps.iter().map(|s| u16_of(&s["controlword"])).collect();
    assert_eq!(words, [0x0000, 0x0080, 0x0006, 0x0007, 0x000F]);
    let mut here = Cia402State::Fault;
    let mut previous = None;
    let mut commands = Vec::new();
    for &controlword in &words {
        let command = Cia402Command::from_controlword(controlword, previous, Some(here)).unwrap();
        commands.push(command);
        if let Some(t) = here.next(command) {
            here = t.to();
        }
        previous = Some(controlword);
    }
    assert_eq!(
        commands,
        [
            Cia402Command::DisableVoltage,
            Cia402Command::FaultReset,
            Cia402Command::Shutdown,
            Cia402Command::SwitchOn,
            Cia402Command::EnableOperation,
        ]
    );
    assert_eq!(here, state(reset["final"].as_str().unwrap()));
}

#[test]
fn modes_of_operation_as_python_canopen_names_them() {
    let fixture = fixture();
    let names = fixture["operation_modes"].as_object().unwrap();
    assert_eq!(names.len(), 10);
    for (code, python_name) in names {
        let mode = ModeOfOperation::from_i8(code.parse().unwrap());
        // Difference 4: PROFILED → CiA 402's "profile".
        let expected = python_name
            .as_str()
            .unwrap()
            .to_lowercase()
            .replace("profiled ", "profile ")
            .replace(' ', "_");
        assert_eq!(mode.name(), expected, "{code}");
    }
    let constants = fixture["operation_mode_constants"].as_object().unwrap();
    for (python_name, value) in constants {
        let value = i8::try_from(value.as_i64().unwrap()).unwrap();
        let mode = ModeOfOperation::from_i8(value);
        if value < 0 {
            // Difference 4: OPEN_LOOP_SCALAR_MODE, OPEN_LOOP_VECTOR_MODE.
            assert!(mode.is_manufacturer_specific(), "{python_name}");
            assert_eq!(mode.name(), "manufacturer_specific");
        } else {
            let expected = python_name.to_lowercase().replace("profiled_", "profile_");
            assert_eq!(mode.name(), expected, "{python_name}");
        }
    }
}
