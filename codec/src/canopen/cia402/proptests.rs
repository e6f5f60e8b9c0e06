//! Property tests of the CiA 402 codecs and state machine: any word
//! decodes without panicking, and the machine agrees with its tables.

use proptest::prelude::*;

use super::*;
use crate::strategies::cia402::{cia402_command, cia402_state, controlword, statusword};

proptest! {
    #[test]
    fn any_statusword_decodes_without_panicking(word in any::<u16>()) {
        let state = Cia402State::from_statusword(word);
        prop_assert_eq!(Statusword::from_bits_retain(word).state(), state);
        prop_assert_eq!(Statusword::from_bits_retain(word).bits(), word);
        if let Some(state) = state {
            let (mask, value) = state.statusword_pattern();
            prop_assert_eq!(word & mask, value);
            // Exactly one pattern matches.
            prop_assert_eq!(
                Cia402State::STATUSWORD_CODING.iter().filter(|(_, m, v)| word & m == *v).count(),
                1
            );
        }
        let _ = Statusword::from_bits_retain(word).to_string();
    }

    #[test]
    fn any_controlword_decodes_without_panicking(
        word in any::<u16>(),
        previous in proptest::option::of(any::<u16>()),
        state in proptest::option::of(cia402_state()),
    ) {
        let command = Cia402Command::from_controlword(word, previous, state);
        let rising = word & 0x80 != 0 && previous.map_or(true, |p| p & 0x80 == 0);
        prop_assert_eq!(command == Some(Cia402Command::FaultReset), rising);
        prop_assert_eq!(command.is_none(), word & 0x80 != 0 && !rising);
        prop_assert_eq!(
            Controlword::from_bits_retain(word)
                .command(previous.map(Controlword::from_bits_retain), state),
            command
        );
        if let (Some(command), Some(state)) = (command, state) {
            if let Some(t) = state.next(command) {
                prop_assert_ne!(t.to(), state);
            }
        }
        let _ = Controlword::from_bits_retain(word).to_string();
    }

    #[test]
    fn a_state_written_into_a_statusword_reads_back(sw in statusword(), state in cia402_state()) {
        let written = sw.with_state(state);
        prop_assert_eq!(written.state(), Some(state));
        let (mask, _) = state.statusword_pattern();
        prop_assert_eq!(written.bits() & !mask, sw.bits() & !mask);
    }

    #[test]
    fn a_command_written_into_a_controlword_reads_back(
        cw in controlword(),
        command in cia402_command(),
        state in proptest::option::of(cia402_state()),
    ) {
        let written = cw.with_command(command);
        prop_assert_eq!(written.bits() & !0x008F, cw.bits() & !0x008F);
        let expected = match command {
            Cia402Command::SwitchOn | Cia402Command::DisableOperation
                if state == Some(Cia402State::OperationEnabled) => Cia402Command::DisableOperation,
            Cia402Command::SwitchOn | Cia402Command::DisableOperation => Cia402Command::SwitchOn,
            other => other,
        };
        // After a controlword with bit 7 clear.
        prop_assert_eq!(written.command(Some(Controlword::empty()), state), Some(expected));
    }

    #[test]
    fn names_round_trip(state in cia402_state(), command in cia402_command(), mode in any::<i8>()) {
        prop_assert_eq!(Cia402State::from_name(state.name()), Some(state));
        prop_assert_eq!(state.to_string(), state.name());
        prop_assert_eq!(Cia402Command::from_name(command.name()), Some(command));
        prop_assert_eq!(command.to_string(), command.name());
        let mode = ModeOfOperation::from_i8(mode);
        prop_assert!(mode.to_string().starts_with(mode.name()));
        prop_assert_eq!(ModeOfOperation::from_byte(mode.to_byte()), mode);
    }

    #[test]
    fn every_transition_leads_where_its_number_says(state in cia402_state(), command in cia402_command()) {
        if let Some(t) = state.next(command) {
            prop_assert_eq!(state.statusword().state(), Some(state));
            prop_assert_eq!(t.to().statusword().state(), Some(t.to()));
            prop_assert!(!t.numbers().is_empty());
            prop_assert!(t.numbers().iter().all(|&n| n <= 16));
        }
    }
}
