//! Tests of the CiA 402 drive state machine, as CiA 402 writes it: the
//! state and command coding tables bit by bit, and each transition 0–16 a
//! named test, so that each test reads as the row of the standard it checks.

use super::*;

use Cia402Command as C;
use Cia402State as S;
use Cia402Transition as T;

/// CiA 402's state coding of 6041h, written out bit by bit as the
/// standard prints it ("x" = any), with a statusword a drive sends in
/// that state (remote, bit 9, set as drives on a bus report it).
const STATE_CODING: [(S, &str, u16); 8] = [
    (S::NotReadyToSwitchOn, "x0xx0000", 0x0200),
    (S::SwitchOnDisabled, "x1xx0000", 0x0250),
    (S::ReadyToSwitchOn, "x01x0001", 0x0231),
    (S::SwitchedOn, "x01x0011", 0x0233),
    (S::OperationEnabled, "x01x0111", 0x0237),
    (S::QuickStopActive, "x00x0111", 0x0217),
    (S::FaultReactionActive, "x0xx1111", 0x021F),
    (S::Fault, "x0xx1000", 0x0218),
];

/// Whether the low byte of `word` matches a pattern of bits 7..0.
fn matches_pattern(word: u16, pattern: &str) -> bool {
    pattern.bytes().rev().enumerate().all(|(bit, c)| match c {
        b'x' => true,
        b'0' => word & (1 << bit) == 0,
        b'1' => word & (1 << bit) != 0,
        _ => unreachable!("pattern characters are 0, 1, x"),
    })
}

#[test]
fn statusword_state_coding() {
    for (state, pattern, example) in STATE_CODING {
        assert_eq!(S::from_statusword(example), Some(state), "{example:#06x}");
        assert_eq!(Statusword::from_bits_retain(example).state(), Some(state));
        assert!(matches_pattern(example, pattern));
    }
    // The table and the written patterns agree on every low byte; the
    // high byte never matters.
    for word in 0..=0xFFu16 {
        let expected = STATE_CODING
            .iter()
            .find(|(_, pattern, _)| matches_pattern(word, pattern))
            .map(|&(state, _, _)| state);
        for high in [0x0000, 0x0200, 0xFF00] {
            assert_eq!(S::from_statusword(word | high), expected, "{word:#06x}");
        }
    }
}

#[test]
fn tables_follow_the_enum_order() {
    for (i, state) in S::ALL.into_iter().enumerate() {
        assert_eq!(S::STATUSWORD_CODING[i].0, state);
        let (mask, value) = state.statusword_pattern();
        assert_eq!(
            (S::STATUSWORD_CODING[i].1, S::STATUSWORD_CODING[i].2),
            (mask, value)
        );
        assert_eq!(state.statusword().bits(), value);
        assert_eq!(S::from_statusword(value), Some(state));
    }
    for (i, (command, _, _)) in C::CONTROLWORD_CODING.into_iter().enumerate() {
        assert_eq!(C::ALL[i], command);
    }
}

#[test]
fn patterns_that_name_no_state() {
    // Bits 0–3 of 0b0001, 0b0011 and 0b0111 with bit 6 set, and the
    // "ready" patterns with switch on disabled and quick stop both clear
    // apart from quick stop active: no state.
    for word in [
        0x0041, 0x0043, 0x0047, 0x0001, 0x0003, 0x0061, 0x0002, 0x0004, 0x0048, 0x004F,
    ] {
        assert_eq!(S::from_statusword(word), None, "{word:#06x}");
    }
}

// The transitions of CiA 402's state diagram, one test each.

#[test]
fn transition_0_power_on_enters_not_ready_to_switch_on() {
    for state in S::ALL {
        assert_eq!(state.on_drive_event(Cia402DriveEvent::PowerOn), Some(T::T0));
    }
    assert_eq!(T::T0.to(), S::NotReadyToSwitchOn);
}

#[test]
fn transition_1_initialisation_complete() {
    let t = S::NotReadyToSwitchOn.on_drive_event(Cia402DriveEvent::InitializationComplete);
    assert_eq!(t, Some(T::T1));
    assert_eq!(T::T1.to(), S::SwitchOnDisabled);
    for state in S::ALL.into_iter().filter(|&s| s != S::NotReadyToSwitchOn) {
        assert_eq!(
            state.on_drive_event(Cia402DriveEvent::InitializationComplete),
            None
        );
    }
}

#[test]
fn transition_2_shutdown_from_switch_on_disabled() {
    assert_eq!(S::SwitchOnDisabled.next(C::Shutdown), Some(T::T2));
    assert_eq!(T::T2.to(), S::ReadyToSwitchOn);
}

#[test]
fn transition_3_switch_on_from_ready_to_switch_on() {
    assert_eq!(S::ReadyToSwitchOn.next(C::SwitchOn), Some(T::T3));
    assert_eq!(T::T3.to(), S::SwitchedOn);
}

#[test]
fn transition_4_enable_operation_from_switched_on() {
    assert_eq!(S::SwitchedOn.next(C::EnableOperation), Some(T::T4));
    assert_eq!(T::T4.to(), S::OperationEnabled);
}

#[test]
fn transition_5_disable_operation_from_operation_enabled() {
    assert_eq!(S::OperationEnabled.next(C::DisableOperation), Some(T::T5));
    assert_eq!(T::T5.to(), S::SwitchedOn);
}

#[test]
fn transition_6_shutdown_from_switched_on() {
    assert_eq!(S::SwitchedOn.next(C::Shutdown), Some(T::T6));
    assert_eq!(T::T6.to(), S::ReadyToSwitchOn);
}

#[test]
fn transition_7_disable_voltage_or_quick_stop_from_ready_to_switch_on() {
    assert_eq!(S::ReadyToSwitchOn.next(C::DisableVoltage), Some(T::T7));
    assert_eq!(S::ReadyToSwitchOn.next(C::QuickStop), Some(T::T7));
    assert_eq!(T::T7.to(), S::SwitchOnDisabled);
}

#[test]
fn transition_8_shutdown_from_operation_enabled() {
    assert_eq!(S::OperationEnabled.next(C::Shutdown), Some(T::T8));
    assert_eq!(T::T8.to(), S::ReadyToSwitchOn);
}

#[test]
fn transition_9_disable_voltage_from_operation_enabled() {
    assert_eq!(S::OperationEnabled.next(C::DisableVoltage), Some(T::T9));
    assert_eq!(T::T9.to(), S::SwitchOnDisabled);
}

#[test]
fn transition_10_disable_voltage_or_quick_stop_from_switched_on() {
    assert_eq!(S::SwitchedOn.next(C::DisableVoltage), Some(T::T10));
    assert_eq!(S::SwitchedOn.next(C::QuickStop), Some(T::T10));
    assert_eq!(T::T10.to(), S::SwitchOnDisabled);
}

#[test]
fn transition_11_quick_stop_from_operation_enabled() {
    assert_eq!(S::OperationEnabled.next(C::QuickStop), Some(T::T11));
    assert_eq!(T::T11.to(), S::QuickStopActive);
}

#[test]
fn transition_12_disable_voltage_or_quick_stop_complete() {
    assert_eq!(S::QuickStopActive.next(C::DisableVoltage), Some(T::T12));
    assert_eq!(
        S::QuickStopActive.on_drive_event(Cia402DriveEvent::QuickStopComplete),
        Some(T::T12)
    );
    assert_eq!(T::T12.to(), S::SwitchOnDisabled);
    for state in S::ALL.into_iter().filter(|&s| s != S::QuickStopActive) {
        assert_eq!(
            state.on_drive_event(Cia402DriveEvent::QuickStopComplete),
            None
        );
    }
}

#[test]
fn transition_13_a_fault_from_every_state_but_the_fault_states() {
    for state in S::ALL {
        let t = state.on_drive_event(Cia402DriveEvent::Fault);
        if state.is_fault() {
            assert_eq!(t, None, "{state}");
        } else {
            assert_eq!(t, Some(T::T13), "{state}");
        }
    }
    assert_eq!(T::T13.to(), S::FaultReactionActive);
}

#[test]
fn transition_14_fault_reaction_complete() {
    let t = S::FaultReactionActive.on_drive_event(Cia402DriveEvent::FaultReactionComplete);
    assert_eq!(t, Some(T::T14));
    assert_eq!(T::T14.to(), S::Fault);
    for state in S::ALL.into_iter().filter(|&s| s != S::FaultReactionActive) {
        assert_eq!(
            state.on_drive_event(Cia402DriveEvent::FaultReactionComplete),
            None
        );
    }
}

#[test]
fn transition_15_fault_reset_from_fault() {
    assert_eq!(S::Fault.next(C::FaultReset), Some(T::T15));
    assert_eq!(T::T15.to(), S::SwitchOnDisabled);
    for state in S::ALL.into_iter().filter(|&s| s != S::Fault) {
        assert_eq!(state.next(C::FaultReset), None, "{state}");
    }
}

#[test]
fn transition_16_enable_operation_from_quick_stop_active() {
    assert_eq!(S::QuickStopActive.next(C::EnableOperation), Some(T::T16));
    assert_eq!(T::T16.to(), S::OperationEnabled);
}

#[test]
fn transitions_3_and_4_enable_operation_from_ready_to_switch_on() {
    assert_eq!(S::ReadyToSwitchOn.next(C::EnableOperation), Some(T::T3T4));
    assert_eq!(T::T3T4.to(), S::OperationEnabled);
    assert_eq!(T::T3T4.numbers(), &[3, 4]);
    // Switch on then enable operation, one after the other, end in the
    // same place.
    let via = S::ReadyToSwitchOn.next(C::SwitchOn).unwrap().to();
    assert_eq!(via.next(C::EnableOperation).unwrap().to(), T::T3T4.to());
}

/// The whole command table: every (state, command) pair that moves the
/// machine; every other pair leaves it where it is.
#[test]
fn every_other_command_leaves_the_state() {
    let moves = [
        (S::SwitchOnDisabled, C::Shutdown, T::T2),
        (S::ReadyToSwitchOn, C::SwitchOn, T::T3),
        (S::ReadyToSwitchOn, C::EnableOperation, T::T3T4),
        (S::ReadyToSwitchOn, C::DisableVoltage, T::T7),
        (S::ReadyToSwitchOn, C::QuickStop, T::T7),
        (S::SwitchedOn, C::EnableOperation, T::T4),
        (S::SwitchedOn, C::Shutdown, T::T6),
        (S::SwitchedOn, C::DisableVoltage, T::T10),
        (S::SwitchedOn, C::QuickStop, T::T10),
        (S::OperationEnabled, C::DisableOperation, T::T5),
        (S::OperationEnabled, C::Shutdown, T::T8),
        (S::OperationEnabled, C::DisableVoltage, T::T9),
        (S::OperationEnabled, C::QuickStop, T::T11),
        (S::QuickStopActive, C::DisableVoltage, T::T12),
        (S::QuickStopActive, C::EnableOperation, T::T16),
        (S::Fault, C::FaultReset, T::T15),
    ];
    for state in S::ALL {
        for command in C::ALL {
            let expected = moves
                .iter()
                .find(|&&(s, c, _)| s == state && c == command)
                .map(|&(_, _, t)| t);
            assert_eq!(state.next(command), expected, "{state} {command}");
        }
    }
    // Not ready to switch on and fault reaction active take no command.
    for command in C::ALL {
        assert_eq!(S::NotReadyToSwitchOn.next(command), None);
        assert_eq!(S::FaultReactionActive.next(command), None);
    }
}

// The decision in docs/canopen.md#cia402: a command is a function of
// (controlword, previous controlword, current state).

/// CiA 402's command coding of 6040h bits 7, 3, 2, 1, 0 ("x" = any),
/// for the level-coded commands (bit 7 = 0).
const COMMAND_CODING: [(C, &str); 6] = [
    (C::Shutdown, "0x110"),
    (C::SwitchOn, "00111"),
    (C::DisableVoltage, "0xx0x"),
    (C::QuickStop, "0x01x"),
    (C::DisableOperation, "00111"),
    (C::EnableOperation, "01111"),
];

/// Whether bits 7, 3, 2, 1, 0 of `word` match a 5-character pattern.
fn matches_command(word: u16, pattern: &str) -> bool {
    let bits = [7, 3, 2, 1, 0];
    pattern.bytes().zip(bits).all(|(c, bit)| match c {
        b'x' => true,
        b'0' => word & (1 << bit) == 0,
        b'1' => word & (1 << bit) != 0,
        _ => unreachable!("pattern characters are 0, 1, x"),
    })
}

#[test]
fn controlword_command_coding() {
    for (command, pattern) in COMMAND_CODING {
        let (mask, value) = command.controlword_pattern();
        for word in 0..=0xFFu16 {
            assert_eq!(
                word & mask == value,
                matches_command(word, pattern),
                "{command} {word:#06x}"
            );
        }
        assert_eq!(command.controlword().bits(), value);
    }
    assert_eq!(C::FaultReset.controlword().bits(), 0x0080);
}

#[test]
fn every_controlword_with_bit_7_clear_names_exactly_one_command() {
    for word in (0..=0xFFFFu16).filter(|w| w & 0x80 == 0) {
        let matching: Vec<_> = COMMAND_CODING
            .iter()
            .filter(|(c, p)| *c != C::DisableOperation && matches_command(word, p))
            .collect();
        assert_eq!(matching.len(), 1, "{word:#06x}");
        for state in S::ALL.map(Some).into_iter().chain([None]) {
            let command = C::from_controlword(word, Some(0), state);
            assert_eq!(C::from_controlword(word, None, state), command);
            assert_eq!(C::from_controlword(word, Some(0xFF7F), state), command);
            let expected = match matching[0].0 {
                C::SwitchOn if state == Some(S::OperationEnabled) => C::DisableOperation,
                c => c,
            };
            assert_eq!(command, Some(expected), "{word:#06x} in {state:?}");
        }
    }
}

#[test]
fn fault_reset_is_the_rising_edge_of_bit_7() {
    for low in 0..=0x7Fu16 {
        for state in S::ALL {
            let word = 0x0080 | low;
            assert_eq!(
                C::from_controlword(word, Some(low), Some(state)),
                Some(C::FaultReset),
                "{word:#06x}"
            );
            assert_eq!(
                C::from_controlword(word, Some(0x000F), Some(state)),
                Some(C::FaultReset)
            );
        }
    }
}

#[test]
fn bit_7_held_at_1_is_no_command() {
    for word in (0..=0xFFFFu16).filter(|w| w & 0x80 != 0) {
        assert_eq!(
            C::from_controlword(word, Some(0x0080), Some(S::Fault)),
            None
        );
        assert_eq!(C::from_controlword(word, Some(word), None), None);
    }
}

#[test]
fn bit_7_in_the_first_controlword_is_a_fault_reset() {
    // No previous controlword: bit 7 counts as having been 0.
    assert_eq!(
        C::from_controlword(0x0080, None, Some(S::Fault)),
        Some(C::FaultReset)
    );
    assert_eq!(C::from_controlword(0x0086, None, None), Some(C::FaultReset));
}

#[test]
fn x07_is_disable_operation_in_operation_enabled() {
    let command = C::from_controlword(0x0007, Some(0x000F), Some(S::OperationEnabled));
    assert_eq!(command, Some(C::DisableOperation));
    assert_eq!(S::OperationEnabled.next(C::DisableOperation), Some(T::T5));
    // Mode-specific bits and halt do not change it.
    assert_eq!(
        C::from_controlword(0x0177, None, Some(S::OperationEnabled)),
        Some(C::DisableOperation)
    );
}

#[test]
fn x07_is_switch_on_elsewhere() {
    for state in S::ALL.into_iter().filter(|&s| s != S::OperationEnabled) {
        assert_eq!(
            C::from_controlword(0x0007, Some(0x0006), Some(state)),
            Some(C::SwitchOn)
        );
    }
    assert_eq!(C::from_controlword(0x0007, None, None), Some(C::SwitchOn));
    // Switch on has no transition from operation enabled: there the
    // pattern is disable operation.
    assert_eq!(S::OperationEnabled.next(C::SwitchOn), None);
}

#[test]
fn x0f_in_ready_to_switch_on_is_enable_operation_by_3_and_4() {
    let command = C::from_controlword(0x000F, Some(0x0006), Some(S::ReadyToSwitchOn));
    assert_eq!(command, Some(C::EnableOperation));
    assert_eq!(S::ReadyToSwitchOn.next(C::EnableOperation), Some(T::T3T4));
}

#[test]
fn on_controlword_is_from_controlword_then_next() {
    for state in S::ALL {
        for word in 0..=0x01FFu16 {
            for previous in [None, Some(0x0000), Some(0x0080)] {
                let command = C::from_controlword(word, previous, Some(state));
                let transition = command.and_then(|c| state.next(c));
                assert_eq!(state.on_controlword(word, previous), (command, transition));
            }
        }
    }
}

#[test]
fn a_drive_brought_up_and_faulted_and_reset() {
    // Power on, initialise, shutdown, switch on, enable operation, a
    // fault, its reaction, a fault reset, as a drive's statuswords show.
    let mut state = T::T0.to();
    let steps: [(Option<u16>, Option<Cia402DriveEvent>, T, u16); 8] = [
        (
            None,
            Some(Cia402DriveEvent::InitializationComplete),
            T::T1,
            0x0250,
        ),
        (Some(0x0006), None, T::T2, 0x0231),
        (Some(0x0007), None, T::T3, 0x0233),
        (Some(0x000F), None, T::T4, 0x0237),
        (None, Some(Cia402DriveEvent::Fault), T::T13, 0x021F),
        (
            None,
            Some(Cia402DriveEvent::FaultReactionComplete),
            T::T14,
            0x0218,
        ),
        (Some(0x0080), None, T::T15, 0x0250),
        (Some(0x0006), None, T::T2, 0x0231),
    ];
    let mut previous = Some(0x000F);
    for (controlword, event, transition, statusword) in steps {
        let t = match (controlword, event) {
            (Some(cw), None) => {
                let command = C::from_controlword(cw, previous, Some(state)).unwrap();
                previous = Some(cw);
                state.next(command)
            }
            (None, Some(event)) => state.on_drive_event(event),
            _ => unreachable!(),
        };
        assert_eq!(t, Some(transition));
        state = transition.to();
        assert_eq!(S::from_statusword(statusword), Some(state));
    }
}

#[test]
fn names_and_display() {
    let names = [
        "not_ready_to_switch_on",
        "switch_on_disabled",
        "ready_to_switch_on",
        "switched_on",
        "operation_enabled",
        "quick_stop_active",
        "fault_reaction_active",
        "fault",
    ];
    assert_eq!(S::ALL.map(S::name), names);
    for state in S::ALL {
        assert_eq!(state.to_string(), state.name());
        assert_eq!(S::from_name(state.name()), Some(state));
    }
    let names = [
        "shutdown",
        "switch_on",
        "disable_voltage",
        "quick_stop",
        "disable_operation",
        "enable_operation",
        "fault_reset",
    ];
    assert_eq!(C::ALL.map(C::name), names);
    for command in C::ALL {
        assert_eq!(command.to_string(), command.name());
        assert_eq!(C::from_name(command.name()), Some(command));
    }
    assert_eq!(S::from_name("Fault"), None);
    assert_eq!(C::from_name("halt"), None);
    let names = [
        "power_on",
        "initialization_complete",
        "quick_stop_complete",
        "fault",
        "fault_reaction_complete",
    ];
    assert_eq!(Cia402DriveEvent::ALL.map(Cia402DriveEvent::name), names);
    for event in Cia402DriveEvent::ALL {
        assert_eq!(event.to_string(), event.name());
    }
}

#[test]
fn transition_numbers() {
    for (n, t) in T::ALL.into_iter().take(17).enumerate() {
        assert_eq!(t.numbers(), &[n as u8]);
        assert_eq!(T::from_number(n as u8), Some(t));
        assert_eq!(t.to_string(), n.to_string());
    }
    assert_eq!(T::from_number(17), None);
    assert_eq!(T::T3T4.to_string(), "3+4");
}

#[test]
fn statusword_bits() {
    for (bit, (flag, _)) in Statusword::NAMES.into_iter().enumerate() {
        assert_eq!(flag.bits(), 1 << bit);
    }
    let names = [
        "ready_to_switch_on",
        "switched_on",
        "operation_enabled",
        "fault",
        "voltage_enabled",
        "quick_stop",
        "switch_on_disabled",
        "warning",
        "manufacturer_specific_8",
        "remote",
        "target_reached",
        "internal_limit_active",
        "operation_mode_specific_12",
        "operation_mode_specific_13",
        "manufacturer_specific_14",
        "manufacturer_specific_15",
    ];
    assert_eq!(Statusword::all().names().collect::<Vec<_>>(), names);
    assert_eq!(Statusword::all().bits(), 0xFFFF);
    assert_eq!(Statusword::empty().to_string(), "0x0000 []");
    assert_eq!(
        Statusword::from_bits_retain(0x0218).to_string(),
        "0x0218 [fault|voltage_enabled|remote]"
    );
}

#[test]
fn controlword_bits() {
    for (bit, (flag, _)) in Controlword::NAMES.into_iter().enumerate() {
        assert_eq!(flag.bits(), 1 << bit);
    }
    let names = [
        "switch_on",
        "enable_voltage",
        "quick_stop",
        "enable_operation",
        "operation_mode_specific_4",
        "operation_mode_specific_5",
        "operation_mode_specific_6",
        "fault_reset",
        "halt",
        "operation_mode_specific_9",
        "reserved_10",
        "manufacturer_specific_11",
        "manufacturer_specific_12",
        "manufacturer_specific_13",
        "manufacturer_specific_14",
        "manufacturer_specific_15",
    ];
    assert_eq!(Controlword::all().names().collect::<Vec<_>>(), names);
    assert_eq!(Controlword::all().bits(), 0xFFFF);
    assert_eq!(
        Controlword::from_bits_retain(0x0080).to_string(),
        "0x0080 [fault_reset]"
    );
}

#[test]
fn with_state_and_with_command_keep_the_other_bits() {
    let sw = Statusword::from_bits_retain(0xFF80);
    assert_eq!(sw.with_state(S::OperationEnabled).bits(), 0xFFA7);
    assert_eq!(sw.with_state(S::QuickStopActive).bits(), 0xFF87);
    assert_eq!(sw.with_state(S::Fault).bits(), 0xFF88);
    // Not ready to switch on keeps bit 5 as it was.
    assert_eq!(
        Statusword::from_bits_retain(0x0037)
            .with_state(S::NotReadyToSwitchOn)
            .bits(),
        0x0030
    );
    let cw = Controlword::from_bits_retain(0x0170);
    assert_eq!(cw.with_command(C::EnableOperation).bits(), 0x017F);
    assert_eq!(cw.with_command(C::Shutdown).bits(), 0x0176);
    assert_eq!(
        Controlword::from_bits_retain(0x008F)
            .with_command(C::QuickStop)
            .bits(),
        0x0002
    );
    assert_eq!(cw.with_command(C::FaultReset).bits(), 0x01F0);
}

#[test]
fn modes_of_operation() {
    let table: [(i8, &str); 10] = [
        (0, "no_mode"),
        (1, "profile_position"),
        (2, "velocity"),
        (3, "profile_velocity"),
        (4, "profile_torque"),
        (6, "homing"),
        (7, "interpolated_position"),
        (8, "cyclic_synchronous_position"),
        (9, "cyclic_synchronous_velocity"),
        (10, "cyclic_synchronous_torque"),
    ];
    for ((value, name), (mode, table_name)) in table.into_iter().zip(ModeOfOperation::NAMED) {
        assert_eq!(ModeOfOperation::from_i8(value), mode);
        assert_eq!(mode.to_i8(), value);
        assert_eq!(mode.name(), name);
        assert_eq!(table_name, name);
        assert_eq!(mode.to_string(), name);
        assert!(!mode.is_reserved() && !mode.is_manufacturer_specific());
    }
    for value in i8::MIN..=i8::MAX {
        let mode = ModeOfOperation::from_i8(value);
        assert_eq!(ModeOfOperation::from(value), mode);
        assert_eq!(i8::from(mode), value);
        assert_eq!(ModeOfOperation::from_byte(value as u8), mode);
        assert_eq!(mode.to_byte(), value as u8);
        if value < 0 {
            assert!(mode.is_manufacturer_specific());
            assert_eq!(mode.to_string(), format!("manufacturer_specific({value})"));
        } else if value == 5 || value > 10 {
            assert!(mode.is_reserved());
            assert_eq!(mode.to_string(), format!("reserved({value})"));
        }
    }
    assert_eq!(
        ModeOfOperation::from_byte(0xFF).to_string(),
        "manufacturer_specific(-1)"
    );
}
