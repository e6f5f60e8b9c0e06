//! The CiA 402 drive state machine: statusword 6041h → state, controlword
//! 6040h → command, and the pure transition function (CiA 402-2 /
//! IEC 61800-7-201, "drive state machine"; SPEC §8.3).
//!
//! - [`Cia402State`]: the eight states of the state diagram, read from a
//!   statusword with [`Cia402State::from_statusword`] (bits 0–3, 5 and 6, as
//!   CiA 402's state-coding table of object 6041h gives them).
//! - [`Cia402Command`]: the seven device-control commands, read from a
//!   controlword with [`Cia402Command::from_controlword`] (bits 0–3 and 7,
//!   as CiA 402's command-coding table of object 6040h gives them), with
//!   SPEC §8.3's decision for the patterns that table leaves to context.
//! - [`Cia402State::next`]: the state a command leads to and the number of
//!   the transition (0–16) as the state diagram draws it; the drive's own
//!   transitions (0, 1, 12 automatic, 13, 14) come from
//!   [`Cia402State::on_drive_event`] with a [`Cia402DriveEvent`], so that
//!   drive firmware can run the same machine.
//! - [`Statusword`] and [`Controlword`]: the two words as flags, every bit
//!   named as CiA 402 names it; [`ModeOfOperation`]: objects 6060h/6061h.
//!
//! Everything here is a pure function of its arguments: no clock, no I/O, no
//! heap (STYLE "Ours, distilled" 5).
//!
//! ```
//! use motionwire::canopen::{Cia402Command, Cia402State, Cia402Transition, Statusword};
//!
//! // A master brings a drive up: shutdown, switch on, enable operation.
//! let mut state = Cia402State::from_statusword(0x0250).expect("a state");
//! assert_eq!(state, Cia402State::SwitchOnDisabled);
//! let mut previous = None;
//! for (controlword, number) in [(0x0006, 2), (0x0007, 3), (0x000F, 4)] {
//!     let command = Cia402Command::from_controlword(controlword, previous, Some(state))
//!         .expect("bit 7 is 0: every such controlword is a command");
//!     let transition = state.next(command).expect("allowed in this state");
//!     assert_eq!(transition.numbers(), &[number]);
//!     state = transition.to();
//!     previous = Some(controlword);
//! }
//! assert_eq!(state, Cia402State::OperationEnabled);
//! assert_eq!(Statusword::from_bits_retain(0x0637).state(), Some(state));
//!
//! // 0x07 again is "disable operation" in operation enabled (transition 5)…
//! let command = Cia402Command::from_controlword(0x0007, previous, Some(state));
//! assert_eq!(command, Some(Cia402Command::DisableOperation));
//! assert_eq!(state.next(Cia402Command::DisableOperation), Some(Cia402Transition::T5));
//!
//! // …and a fault reset is the 0 → 1 edge of bit 7 (transition 15).
//! let fault = Cia402State::Fault;
//! let reset = Cia402Command::from_controlword(0x0080, Some(0x0000), Some(fault));
//! assert_eq!(reset, Some(Cia402Command::FaultReset));
//! assert_eq!(fault.next(Cia402Command::FaultReset).map(|t| t.to()), Some(Cia402State::SwitchOnDisabled));
//! assert_eq!(Cia402Command::from_controlword(0x0080, Some(0x0080), Some(fault)), None);
//! ```

use core::fmt;

use bitflags::bitflags;

/// A state of the CiA 402 drive state machine (CiA 402-2 / IEC 61800-7-201,
/// the state diagram of the drive state machine; SPEC §8.3).
///
/// ```
/// use motionwire::canopen::Cia402State;
///
/// assert_eq!(Cia402State::from_statusword(0x0237), Some(Cia402State::OperationEnabled));
/// assert_eq!(Cia402State::OperationEnabled.name(), "operation_enabled");
/// // Bits 0–3 = 0b0001 with bit 6 set names no state.
/// assert_eq!(Cia402State::from_statusword(0x0041), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cia402State {
    /// Not ready to switch on: the drive is initialising and running its
    /// self-test; low-level power is on, the drive function is disabled.
    /// Statusword `xxxx xxxx x0xx 0000`.
    NotReadyToSwitchOn,
    /// Switch on disabled: initialisation is complete, parameters may be
    /// changed, high voltage may not be applied. Statusword
    /// `xxxx xxxx x1xx 0000`.
    SwitchOnDisabled,
    /// Ready to switch on: high voltage may be applied, the drive function is
    /// disabled. Statusword `xxxx xxxx x01x 0001`.
    ReadyToSwitchOn,
    /// Switched on: high voltage is applied, the power amplifier is ready,
    /// the drive function is disabled. Statusword `xxxx xxxx x01x 0011`.
    SwitchedOn,
    /// Operation enabled: the drive function is enabled and power is applied
    /// to the motor. Statusword `xxxx xxxx x01x 0111`.
    OperationEnabled,
    /// Quick stop active: the quick-stop function is being executed, the
    /// drive function is enabled. Statusword `xxxx xxxx x00x 0111`.
    QuickStopActive,
    /// Fault reaction active: a fault occurred and the drive executes its
    /// fault reaction. Statusword `xxxx xxxx x0xx 1111`.
    FaultReactionActive,
    /// Fault: the fault reaction is complete, the drive function is disabled.
    /// Statusword `xxxx xxxx x0xx 1000`.
    Fault,
}

/// The statusword bits that code the state: bits 0–3 and 6 (the states
/// where quick stop, bit 5, is "x").
const STATE_MASK_WITHOUT_QUICK_STOP: u16 = 0x004F;
/// The statusword bits that code the state: bits 0–3, 5 and 6.
const STATE_MASK_WITH_QUICK_STOP: u16 = 0x006F;

/// The device profile number of CiA 402 drives, 0x0192 (402), in the low
/// word of the device type 1000h (CiA 301 §7.5.2.1; SPEC §8.3).
pub const DRIVE_DEVICE_PROFILE: u16 = 402;

/// Return whether a device type (object 1000h) names a CiA 402 drive: its
/// low word is [`DRIVE_DEVICE_PROFILE`] (SPEC §8.3).
///
/// ```
/// use motionwire::canopen::cia402::is_drive_device_type;
///
/// assert!(is_drive_device_type(0x0002_0192));
/// assert!(!is_drive_device_type(0x0000_0196)); // CiA 406, an encoder
/// ```
#[must_use]
pub const fn is_drive_device_type(device_type: u32) -> bool {
    device_type & 0xFFFF == DRIVE_DEVICE_PROFILE as u32
}

impl Cia402State {
    /// Every state, in the order of the enum (the state diagram's order from
    /// start to fault).
    pub const ALL: [Cia402State; 8] = [
        Cia402State::NotReadyToSwitchOn,
        Cia402State::SwitchOnDisabled,
        Cia402State::ReadyToSwitchOn,
        Cia402State::SwitchedOn,
        Cia402State::OperationEnabled,
        Cia402State::QuickStopActive,
        Cia402State::FaultReactionActive,
        Cia402State::Fault,
    ];

    /// The state coding of the statusword, the one table that
    /// [`Cia402State::from_statusword`], [`Cia402State::statusword_pattern`]
    /// and the tests read: `(state, mask, value)`, where a statusword `sw`
    /// shows the state when `sw & mask == value` (CiA 402-2 /
    /// IEC 61800-7-201, state coding of object 6041h; SPEC §8.3).
    ///
    /// The patterns are disjoint, so at most one state matches any word.
    pub const STATUSWORD_CODING: [(Cia402State, u16, u16); 8] = [
        (
            Cia402State::NotReadyToSwitchOn,
            STATE_MASK_WITHOUT_QUICK_STOP,
            0x0000,
        ),
        (
            Cia402State::SwitchOnDisabled,
            STATE_MASK_WITHOUT_QUICK_STOP,
            0x0040,
        ),
        (
            Cia402State::ReadyToSwitchOn,
            STATE_MASK_WITH_QUICK_STOP,
            0x0021,
        ),
        (Cia402State::SwitchedOn, STATE_MASK_WITH_QUICK_STOP, 0x0023),
        (
            Cia402State::OperationEnabled,
            STATE_MASK_WITH_QUICK_STOP,
            0x0027,
        ),
        (
            Cia402State::QuickStopActive,
            STATE_MASK_WITH_QUICK_STOP,
            0x0007,
        ),
        (
            Cia402State::FaultReactionActive,
            STATE_MASK_WITHOUT_QUICK_STOP,
            0x000F,
        ),
        (Cia402State::Fault, STATE_MASK_WITHOUT_QUICK_STOP, 0x0008),
    ];

    /// Return the state a statusword (object 6041h) shows, from bits 0–3, 5
    /// and 6 as CiA 402's state coding gives them, or `None` when those bits
    /// form a pattern that names no state (e.g. `0x0041`, or
    /// `0x0001` with quick stop, bit 5, clear). Every other bit is ignored.
    #[must_use]
    pub const fn from_statusword(statusword: u16) -> Option<Cia402State> {
        let mut i = 0;
        while i < Self::STATUSWORD_CODING.len() {
            let (state, mask, value) = Self::STATUSWORD_CODING[i];
            if statusword & mask == value {
                return Some(state);
            }
            i += 1;
        }
        None
    }

    /// Return the state's statusword coding `(mask, value)`: a statusword
    /// `sw` shows this state exactly when `sw & mask == value`
    /// ([`Cia402State::STATUSWORD_CODING`]).
    #[must_use]
    pub const fn statusword_pattern(self) -> (u16, u16) {
        let (_, mask, value) = Self::STATUSWORD_CODING[self as usize];
        (mask, value)
    }

    /// Return the statusword that shows this state with every other bit 0,
    /// e.g. `0x0027` for operation enabled: what a drive that knows nothing
    /// else sends (use [`Statusword::with_state`] to keep the other bits).
    #[must_use]
    pub const fn statusword(self) -> Statusword {
        Statusword::from_bits_retain(self.statusword_pattern().1)
    }

    /// Return the state's name in lower-case words as SPEC §8.3 writes it,
    /// e.g. `"not_ready_to_switch_on"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Cia402State::NotReadyToSwitchOn => "not_ready_to_switch_on",
            Cia402State::SwitchOnDisabled => "switch_on_disabled",
            Cia402State::ReadyToSwitchOn => "ready_to_switch_on",
            Cia402State::SwitchedOn => "switched_on",
            Cia402State::OperationEnabled => "operation_enabled",
            Cia402State::QuickStopActive => "quick_stop_active",
            Cia402State::FaultReactionActive => "fault_reaction_active",
            Cia402State::Fault => "fault",
        }
    }

    /// Return the state whose [`Cia402State::name`] is `name`, or `None`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Cia402State> {
        Self::ALL.into_iter().find(|state| state.name() == name)
    }

    /// Return whether the state is one of the two fault states (fault
    /// reaction active, fault): SPEC §8.3 counts a fault where the state
    /// enters one of them from a state that is neither.
    #[must_use]
    pub const fn is_fault(self) -> bool {
        matches!(self, Cia402State::FaultReactionActive | Cia402State::Fault)
    }

    /// Return the transition a device-control command causes in this state,
    /// as CiA 402's state diagram and transition table draw it (SPEC §8.3),
    /// or `None` when the command causes no transition here (the drive stays
    /// where it is: e.g. shutdown in ready to switch on, any command in not
    /// ready to switch on or fault reaction active).
    ///
    /// | from | command | transition |
    /// |---|---|---|
    /// | switch on disabled | shutdown | 2 → ready to switch on |
    /// | ready to switch on | switch on | 3 → switched on |
    /// | ready to switch on | enable operation | 3+4 → operation enabled |
    /// | ready to switch on | disable voltage, quick stop | 7 → switch on disabled |
    /// | switched on | enable operation | 4 → operation enabled |
    /// | switched on | shutdown | 6 → ready to switch on |
    /// | switched on | disable voltage, quick stop | 10 → switch on disabled |
    /// | operation enabled | disable operation | 5 → switched on |
    /// | operation enabled | shutdown | 8 → ready to switch on |
    /// | operation enabled | disable voltage | 9 → switch on disabled |
    /// | operation enabled | quick stop | 11 → quick stop active |
    /// | quick stop active | disable voltage | 12 → switch on disabled |
    /// | quick stop active | enable operation | 16 → operation enabled |
    /// | fault | fault reset | 15 → switch on disabled |
    ///
    /// [`Cia402Command::SwitchOn`] has no transition from operation enabled:
    /// its bit pattern there is disable operation (transition 5), which
    /// [`Cia402Command::from_controlword`] reports as such. Transition 16 is
    /// taken only by drives whose quick stop option code (605Ah) is 5–8;
    /// the function gives it whenever asked, as the diagram draws it.
    #[must_use]
    pub const fn next(self, command: Cia402Command) -> Option<Cia402Transition> {
        use Cia402Command as C;
        use Cia402State as S;
        use Cia402Transition as T;
        Some(match (self, command) {
            (S::SwitchOnDisabled, C::Shutdown) => T::T2,
            (S::ReadyToSwitchOn, C::SwitchOn) => T::T3,
            (S::ReadyToSwitchOn, C::EnableOperation) => T::T3T4,
            (S::ReadyToSwitchOn, C::DisableVoltage | C::QuickStop) => T::T7,
            (S::SwitchedOn, C::EnableOperation) => T::T4,
            (S::SwitchedOn, C::Shutdown) => T::T6,
            (S::SwitchedOn, C::DisableVoltage | C::QuickStop) => T::T10,
            (S::OperationEnabled, C::DisableOperation) => T::T5,
            (S::OperationEnabled, C::Shutdown) => T::T8,
            (S::OperationEnabled, C::DisableVoltage) => T::T9,
            (S::OperationEnabled, C::QuickStop) => T::T11,
            (S::QuickStopActive, C::DisableVoltage) => T::T12,
            (S::QuickStopActive, C::EnableOperation) => T::T16,
            (S::Fault, C::FaultReset) => T::T15,
            _ => return None,
        })
    }

    /// Return the command a controlword gives in this state after
    /// `previous` ([`Cia402Command::from_controlword`]) and the transition it
    /// causes ([`Cia402State::next`]): SPEC §8.3's "next state from state +
    /// controlword" in one call. The state afterwards is the transition's
    /// [`Cia402Transition::to`], or `self` when there is none.
    ///
    /// ```
    /// use motionwire::canopen::{Cia402Command, Cia402State, Cia402Transition};
    ///
    /// let state = Cia402State::ReadyToSwitchOn;
    /// let (command, transition) = state.on_controlword(0x000F, Some(0x0006));
    /// assert_eq!(command, Some(Cia402Command::EnableOperation));
    /// assert_eq!(transition, Some(Cia402Transition::T3T4));
    ///
    /// // Bit 7 held at 1: no command, no transition.
    /// assert_eq!(Cia402State::Fault.on_controlword(0x0080, Some(0x0080)), (None, None));
    /// ```
    #[must_use]
    pub const fn on_controlword(
        self,
        controlword: u16,
        previous: Option<u16>,
    ) -> (Option<Cia402Command>, Option<Cia402Transition>) {
        match Cia402Command::from_controlword(controlword, previous, Some(self)) {
            Some(command) => (Some(command), self.next(command)),
            None => (None, None),
        }
    }

    /// Return the transition an event inside the drive causes in this state
    /// (CiA 402's automatic and fault transitions, which no controlword
    /// commands; SPEC §8.3: "usable by drive firmware too"), or `None` when
    /// the event causes none here.
    ///
    /// | from | event | transition |
    /// |---|---|---|
    /// | any state | power on | 0 → not ready to switch on |
    /// | not ready to switch on | initialisation complete | 1 → switch on disabled |
    /// | quick stop active | quick stop complete | 12 → switch on disabled |
    /// | any state but fault reaction active and fault | fault | 13 → fault reaction active |
    /// | fault reaction active | fault reaction complete | 14 → fault |
    ///
    /// Drive firmware runs the whole machine with this and
    /// [`Cia402State::on_controlword`], and reports the state in its
    /// statusword with [`Statusword::with_state`]:
    ///
    /// ```
    /// use motionwire::canopen::{Cia402DriveEvent, Cia402State, Cia402Transition, Statusword};
    ///
    /// let mut state = Cia402Transition::T0.to();
    /// let mut report = Statusword::REMOTE;
    /// for event in [Cia402DriveEvent::InitializationComplete, Cia402DriveEvent::Fault] {
    ///     if let Some(t) = state.on_drive_event(event) {
    ///         state = t.to();
    ///     }
    ///     report = report.with_state(state);
    /// }
    /// assert_eq!(state, Cia402State::FaultReactionActive);
    /// assert_eq!(report.bits(), 0x020F);
    /// ```
    #[must_use]
    pub const fn on_drive_event(self, event: Cia402DriveEvent) -> Option<Cia402Transition> {
        use Cia402DriveEvent as E;
        use Cia402State as S;
        use Cia402Transition as T;
        Some(match (self, event) {
            (_, E::PowerOn) => T::T0,
            (S::NotReadyToSwitchOn, E::InitializationComplete) => T::T1,
            (S::QuickStopActive, E::QuickStopComplete) => T::T12,
            (S::FaultReactionActive | S::Fault, E::Fault) => return None,
            (_, E::Fault) => T::T13,
            (S::FaultReactionActive, E::FaultReactionComplete) => T::T14,
            _ => return None,
        })
    }
}

impl fmt::Display for Cia402State {
    /// Format the state as its [`Cia402State::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A device-control command of the CiA 402 drive state machine, coded in
/// bits 0–3 and 7 of the controlword 6040h (CiA 402-2 / IEC 61800-7-201,
/// command coding of object 6040h; SPEC §8.3).
///
/// | command | bit 7 | bit 3 | bit 2 | bit 1 | bit 0 | transitions |
/// |---|---|---|---|---|---|---|
/// | shutdown | 0 | x | 1 | 1 | 0 | 2, 6, 8 |
/// | switch on | 0 | 0 | 1 | 1 | 1 | 3 |
/// | disable voltage | 0 | x | x | 0 | x | 7, 9, 10, 12 |
/// | quick stop | 0 | x | 0 | 1 | x | 7, 10, 11 |
/// | disable operation | 0 | 0 | 1 | 1 | 1 | 5 |
/// | enable operation | 0 | 1 | 1 | 1 | 1 | 4, 16 (3+4 from ready to switch on) |
/// | fault reset | 0 → 1 | x | x | x | x | 15 |
///
/// ```
/// use motionwire::canopen::{Cia402Command, Cia402State};
///
/// assert_eq!(Cia402Command::from_controlword(0x0006, None, None), Some(Cia402Command::Shutdown));
/// assert_eq!(Cia402Command::QuickStop.controlword().bits(), 0x0002);
/// assert_eq!(Cia402Command::FaultReset.to_string(), "fault_reset");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cia402Command {
    /// Shutdown, `0xxx x110`: transitions 2, 6, 8 to ready to switch on.
    Shutdown,
    /// Switch on, `0xxx 0111`: transition 3 to switched on.
    SwitchOn,
    /// Disable voltage, `0xxx xx0x`: transitions 7, 9, 10, 12 to switch on
    /// disabled.
    DisableVoltage,
    /// Quick stop, `0xxx x01x` (bit 2 is active low): transitions 7, 10 to
    /// switch on disabled, 11 to quick stop active.
    QuickStop,
    /// Disable operation, `0xxx 0111` in operation enabled: transition 5 to
    /// switched on.
    DisableOperation,
    /// Enable operation, `0xxx 1111`: transitions 4, 16 to operation
    /// enabled (3+4 from ready to switch on).
    EnableOperation,
    /// Fault reset, the 0 → 1 edge of bit 7: transition 15 to switch on
    /// disabled.
    FaultReset,
}

/// The controlword bits that code a command: bits 0–3 and 7.
const COMMAND_MASK: u16 = 0x008F;
/// Bit 7, fault reset.
const FAULT_RESET_BIT: u16 = 0x0080;

impl Cia402Command {
    /// Every command, in the order of the enum (CiA 402's command table).
    pub const ALL: [Cia402Command; 7] = [
        Cia402Command::Shutdown,
        Cia402Command::SwitchOn,
        Cia402Command::DisableVoltage,
        Cia402Command::QuickStop,
        Cia402Command::DisableOperation,
        Cia402Command::EnableOperation,
        Cia402Command::FaultReset,
    ];

    /// The command coding of the controlword for the level-coded commands,
    /// the one table [`Cia402Command::from_controlword`],
    /// [`Cia402Command::controlword_pattern`] and the tests read:
    /// `(command, mask, value)`, where a controlword `cw` codes the command
    /// when `cw & mask == value` (CiA 402-2 / IEC 61800-7-201, command coding
    /// of object 6040h). Switch on and disable operation share `0xxx 0111`;
    /// fault reset is an edge and has no entry (its pattern is bit 7 set).
    pub const CONTROLWORD_CODING: [(Cia402Command, u16, u16); 6] = [
        (Cia402Command::Shutdown, 0x0087, 0x0006),
        (Cia402Command::SwitchOn, COMMAND_MASK, 0x0007),
        (Cia402Command::DisableVoltage, 0x0082, 0x0000),
        (Cia402Command::QuickStop, 0x0086, 0x0002),
        (Cia402Command::DisableOperation, COMMAND_MASK, 0x0007),
        (Cia402Command::EnableOperation, COMMAND_MASK, 0x000F),
    ];

    /// Return the command a controlword (object 6040h) gives, by SPEC §8.3's
    /// decision: a command is a function of the controlword, the previous
    /// controlword and the current state, as CiA 402's transition table
    /// draws it.
    ///
    /// - Bit 7 rising from 0 (in `previous`) to 1 (in `controlword`) is
    ///   [`Cia402Command::FaultReset`], whatever bits 0–3 say. With no
    ///   `previous` (the first controlword seen) bit 7 counts as having been
    ///   0, the controlword's value before a master writes it.
    /// - Bit 7 held at 1 is no command (`None`): every other command has bit 7
    ///   at 0.
    /// - With bit 7 at 0, bits 0–3 always name a command: `xx0x` disable
    ///   voltage, `x01x` quick stop, `x110` shutdown, `1111` enable operation
    ///   (also in ready to switch on, where it is switch on followed by
    ///   enable operation, transitions 3 + 4), and `0111` disable operation
    ///   in operation enabled (transition 5) and switch on in any other or an
    ///   unknown (`None`) state.
    ///
    /// Bits 4–6 and 8–15 (operation-mode specific, halt, manufacturer
    /// specific) are ignored.
    #[must_use]
    pub const fn from_controlword(
        controlword: u16,
        previous: Option<u16>,
        state: Option<Cia402State>,
    ) -> Option<Cia402Command> {
        let bit7_before = match previous {
            Some(previous) => previous & FAULT_RESET_BIT != 0,
            None => false,
        };
        if controlword & FAULT_RESET_BIT != 0 {
            return if bit7_before {
                None
            } else {
                Some(Cia402Command::FaultReset)
            };
        }
        let mut i = 0;
        while i < Self::CONTROLWORD_CODING.len() {
            let (command, mask, value) = Self::CONTROLWORD_CODING[i];
            if controlword & mask == value {
                return Some(match command {
                    Cia402Command::SwitchOn | Cia402Command::DisableOperation => {
                        if matches!(state, Some(Cia402State::OperationEnabled)) {
                            Cia402Command::DisableOperation
                        } else {
                            Cia402Command::SwitchOn
                        }
                    }
                    other => other,
                });
            }
            i += 1;
        }
        // Unreachable for bit 7 = 0: the table covers all 16 patterns of
        // bits 0–3 (checked by the tests); kept total rather than panicking.
        None
    }

    /// Return the command's controlword coding `(mask, value)`: a
    /// controlword `cw` with bit 7 at 0 codes the command (up to the switch
    /// on / disable operation choice by state) when `cw & mask == value`.
    /// For fault reset the pair is `(0x0080, 0x0080)`: bit 7 set, to be
    /// reached by a 0 → 1 edge.
    #[must_use]
    pub const fn controlword_pattern(self) -> (u16, u16) {
        match self {
            Cia402Command::FaultReset => (FAULT_RESET_BIT, FAULT_RESET_BIT),
            command => {
                let (_, mask, value) = Self::CONTROLWORD_CODING[command as usize];
                (mask, value)
            }
        }
    }

    /// Return the controlword a master writes for the command with every
    /// "x" bit and every bit above bit 3 at 0 (fault reset: `0x0080`, which
    /// resets a fault when the previous controlword had bit 7 at 0), e.g.
    /// `0x0006` for shutdown. Use [`Controlword::with_command`] to keep the
    /// operation-mode bits of a controlword.
    #[must_use]
    pub const fn controlword(self) -> Controlword {
        Controlword::from_bits_retain(self.controlword_pattern().1)
    }

    /// Return the command's name in lower-case words as SPEC §8.3 writes it,
    /// e.g. `"enable_operation"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Cia402Command::Shutdown => "shutdown",
            Cia402Command::SwitchOn => "switch_on",
            Cia402Command::DisableVoltage => "disable_voltage",
            Cia402Command::QuickStop => "quick_stop",
            Cia402Command::DisableOperation => "disable_operation",
            Cia402Command::EnableOperation => "enable_operation",
            Cia402Command::FaultReset => "fault_reset",
        }
    }

    /// Return the command whose [`Cia402Command::name`] is `name`, or `None`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Cia402Command> {
        Self::ALL.into_iter().find(|command| command.name() == name)
    }
}

impl fmt::Display for Cia402Command {
    /// Format the command as its [`Cia402Command::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An event inside a drive that moves its state machine without a command:
/// CiA 402's automatic transitions and fault transitions (CiA 402-2 /
/// IEC 61800-7-201, transition table of the drive state machine). A log
/// decoder never sees them as frames; drive firmware feeds them to
/// [`Cia402State::on_drive_event`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cia402DriveEvent {
    /// Power on or application reset: transition 0 from the state diagram's
    /// "start" to not ready to switch on. Accepted in every state, since a
    /// reset ends whatever state the drive was in.
    PowerOn,
    /// The drive finished its initialisation and self-test: transition 1,
    /// not ready to switch on → switch on disabled.
    InitializationComplete,
    /// The quick stop finished in a drive whose quick stop option code
    /// (605Ah) is 1–4: transition 12, quick stop active → switch on disabled.
    QuickStopComplete,
    /// A fault occurred: transition 13 from any state but fault reaction
    /// active and fault to fault reaction active.
    Fault,
    /// The fault reaction finished: transition 14, fault reaction active →
    /// fault.
    FaultReactionComplete,
}

impl Cia402DriveEvent {
    /// Every event, in the order of the transitions they cause.
    pub const ALL: [Cia402DriveEvent; 5] = [
        Cia402DriveEvent::PowerOn,
        Cia402DriveEvent::InitializationComplete,
        Cia402DriveEvent::QuickStopComplete,
        Cia402DriveEvent::Fault,
        Cia402DriveEvent::FaultReactionComplete,
    ];
}

/// A transition of the CiA 402 drive state machine, named by its number in
/// the state diagram (CiA 402-2 / IEC 61800-7-201, the drive state machine's
/// diagram and transition table; SPEC §8.3), plus
/// [`Cia402Transition::T3T4`] for switch on followed at once by enable
/// operation.
///
/// The number fixes the state the transition leads to
/// ([`Cia402Transition::to`]).
///
/// ```
/// use motionwire::canopen::{Cia402Command, Cia402State, Cia402Transition};
///
/// let t = Cia402State::ReadyToSwitchOn.next(Cia402Command::EnableOperation).unwrap();
/// assert_eq!(t, Cia402Transition::T3T4);
/// assert_eq!(t.numbers(), &[3, 4]);
/// assert_eq!(t.to_string(), "3+4");
/// assert_eq!(t.to(), Cia402State::OperationEnabled);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cia402Transition {
    /// 0: start → not ready to switch on (power on, application reset).
    T0,
    /// 1: not ready to switch on → switch on disabled (automatic, after
    /// initialisation).
    T1,
    /// 2: switch on disabled → ready to switch on (shutdown).
    T2,
    /// 3: ready to switch on → switched on (switch on).
    T3,
    /// 4: switched on → operation enabled (enable operation).
    T4,
    /// 5: operation enabled → switched on (disable operation).
    T5,
    /// 6: switched on → ready to switch on (shutdown).
    T6,
    /// 7: ready to switch on → switch on disabled (disable voltage, quick
    /// stop).
    T7,
    /// 8: operation enabled → ready to switch on (shutdown).
    T8,
    /// 9: operation enabled → switch on disabled (disable voltage).
    T9,
    /// 10: switched on → switch on disabled (disable voltage, quick stop).
    T10,
    /// 11: operation enabled → quick stop active (quick stop).
    T11,
    /// 12: quick stop active → switch on disabled (disable voltage, or
    /// automatic when the quick stop completes with option code 1–4).
    T12,
    /// 13: any state but the fault states → fault reaction active (a fault
    /// occurred).
    T13,
    /// 14: fault reaction active → fault (automatic, the fault reaction is
    /// complete).
    T14,
    /// 15: fault → switch on disabled (fault reset).
    T15,
    /// 16: quick stop active → operation enabled (enable operation, quick
    /// stop option code 5–8).
    T16,
    /// 3 + 4: ready to switch on → operation enabled (enable operation,
    /// `0x0F`, in ready to switch on: switch on followed by enable
    /// operation; SPEC §8.3).
    T3T4,
}

impl Cia402Transition {
    /// Every transition: 0–16 in order, then 3+4.
    pub const ALL: [Cia402Transition; 18] = [
        Cia402Transition::T0,
        Cia402Transition::T1,
        Cia402Transition::T2,
        Cia402Transition::T3,
        Cia402Transition::T4,
        Cia402Transition::T5,
        Cia402Transition::T6,
        Cia402Transition::T7,
        Cia402Transition::T8,
        Cia402Transition::T9,
        Cia402Transition::T10,
        Cia402Transition::T11,
        Cia402Transition::T12,
        Cia402Transition::T13,
        Cia402Transition::T14,
        Cia402Transition::T15,
        Cia402Transition::T16,
        Cia402Transition::T3T4,
    ];

    /// Return the transition numbered `number` in the state diagram (0–16),
    /// or `None` for any other number.
    #[must_use]
    pub const fn from_number(number: u8) -> Option<Cia402Transition> {
        if number <= 16 {
            Some(Self::ALL[number as usize])
        } else {
            None
        }
    }

    /// Return the diagram's numbers of the transition: one number, or
    /// `[3, 4]` for [`Cia402Transition::T3T4`].
    #[must_use]
    pub const fn numbers(self) -> &'static [u8] {
        use Cia402Transition as T;
        match self {
            T::T0 => &[0],
            T::T1 => &[1],
            T::T2 => &[2],
            T::T3 => &[3],
            T::T4 => &[4],
            T::T5 => &[5],
            T::T6 => &[6],
            T::T7 => &[7],
            T::T8 => &[8],
            T::T9 => &[9],
            T::T10 => &[10],
            T::T11 => &[11],
            T::T12 => &[12],
            T::T13 => &[13],
            T::T14 => &[14],
            T::T15 => &[15],
            T::T16 => &[16],
            T::T3T4 => &[3, 4],
        }
    }

    /// Return the state the transition leads to.
    #[must_use]
    pub const fn to(self) -> Cia402State {
        use Cia402State as S;
        use Cia402Transition as T;
        match self {
            T::T0 => S::NotReadyToSwitchOn,
            T::T1 | T::T7 | T::T9 | T::T10 | T::T12 | T::T15 => S::SwitchOnDisabled,
            T::T2 | T::T6 | T::T8 => S::ReadyToSwitchOn,
            T::T3 | T::T5 => S::SwitchedOn,
            T::T4 | T::T16 | T::T3T4 => S::OperationEnabled,
            T::T11 => S::QuickStopActive,
            T::T13 => S::FaultReactionActive,
            T::T14 => S::Fault,
        }
    }
}

impl fmt::Display for Cia402Transition {
    /// The diagram's number, `"5"`, or `"3+4"`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, number) in self.numbers().iter().enumerate() {
            if i > 0 {
                f.write_str("+")?;
            }
            write!(f, "{number}")?;
        }
        Ok(())
    }
}

bitflags! {
    /// The statusword, object 6041h (CiA 402-2 / IEC 61800-7-201, object
    /// 6041h; SPEC §8.3): the drive's state in bits 0–3, 5, 6
    /// ([`Statusword::state`]) and its other status bits.
    ///
    /// Decode a word that a drive sent with [`Statusword::from_bits_retain`];
    /// every bit has a name, so all 16 survive every operation. With the
    /// `serde` feature the word serializes in bitflags' format.
    ///
    /// ```
    /// use motionwire::canopen::{Cia402State, Statusword};
    ///
    /// let sw = Statusword::from_bits_retain(0x0637);
    /// assert_eq!(sw.state(), Some(Cia402State::OperationEnabled));
    /// assert!(sw.contains(Statusword::REMOTE | Statusword::TARGET_REACHED));
    /// assert_eq!(
    ///     sw.to_string(),
    ///     "0x0637 [ready_to_switch_on|switched_on|operation_enabled|voltage_enabled|quick_stop|remote|target_reached]"
    /// );
    /// ```
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
    #[cfg_attr(
        feature = "serde",
        derive(serde::Serialize, serde::Deserialize),
        serde(transparent)
    )]
    pub struct Statusword: u16 {
        /// Bit 0: ready to switch on.
        const READY_TO_SWITCH_ON = 1 << 0;
        /// Bit 1: switched on.
        const SWITCHED_ON = 1 << 1;
        /// Bit 2: operation enabled.
        const OPERATION_ENABLED = 1 << 2;
        /// Bit 3: fault.
        const FAULT = 1 << 3;
        /// Bit 4: voltage enabled (high voltage is applied to the drive).
        const VOLTAGE_ENABLED = 1 << 4;
        /// Bit 5: quick stop, active low: 0 while the drive executes a quick
        /// stop.
        const QUICK_STOP = 1 << 5;
        /// Bit 6: switch on disabled.
        const SWITCH_ON_DISABLED = 1 << 6;
        /// Bit 7: warning (a warning condition; the state does not change).
        const WARNING = 1 << 7;
        /// Bit 8: manufacturer specific.
        const MANUFACTURER_SPECIFIC_8 = 1 << 8;
        /// Bit 9: remote (the controlword is processed).
        const REMOTE = 1 << 9;
        /// Bit 10: target reached (meaning per mode of operation).
        const TARGET_REACHED = 1 << 10;
        /// Bit 11: internal limit active.
        const INTERNAL_LIMIT_ACTIVE = 1 << 11;
        /// Bit 12: operation-mode specific (e.g. set-point acknowledge in
        /// profile position mode).
        const OPERATION_MODE_SPECIFIC_12 = 1 << 12;
        /// Bit 13: operation-mode specific (e.g. following error in profile
        /// position mode).
        const OPERATION_MODE_SPECIFIC_13 = 1 << 13;
        /// Bit 14: manufacturer specific.
        const MANUFACTURER_SPECIFIC_14 = 1 << 14;
        /// Bit 15: manufacturer specific.
        const MANUFACTURER_SPECIFIC_15 = 1 << 15;
    }
}

impl Statusword {
    /// The sixteen bits in bit order with their CiA 402 names in lower-case
    /// words: the one table the names, `Display` and the tests read.
    pub const NAMES: [(Statusword, &'static str); 16] = [
        (Statusword::READY_TO_SWITCH_ON, "ready_to_switch_on"),
        (Statusword::SWITCHED_ON, "switched_on"),
        (Statusword::OPERATION_ENABLED, "operation_enabled"),
        (Statusword::FAULT, "fault"),
        (Statusword::VOLTAGE_ENABLED, "voltage_enabled"),
        (Statusword::QUICK_STOP, "quick_stop"),
        (Statusword::SWITCH_ON_DISABLED, "switch_on_disabled"),
        (Statusword::WARNING, "warning"),
        (
            Statusword::MANUFACTURER_SPECIFIC_8,
            "manufacturer_specific_8",
        ),
        (Statusword::REMOTE, "remote"),
        (Statusword::TARGET_REACHED, "target_reached"),
        (Statusword::INTERNAL_LIMIT_ACTIVE, "internal_limit_active"),
        (
            Statusword::OPERATION_MODE_SPECIFIC_12,
            "operation_mode_specific_12",
        ),
        (
            Statusword::OPERATION_MODE_SPECIFIC_13,
            "operation_mode_specific_13",
        ),
        (
            Statusword::MANUFACTURER_SPECIFIC_14,
            "manufacturer_specific_14",
        ),
        (
            Statusword::MANUFACTURER_SPECIFIC_15,
            "manufacturer_specific_15",
        ),
    ];

    /// Return the state the word shows ([`Cia402State::from_statusword`]).
    #[must_use]
    pub const fn state(self) -> Option<Cia402State> {
        Cia402State::from_statusword(self.bits())
    }

    /// Return a copy that shows `state`: the state-coding bits of `state`'s
    /// pattern (bits 0–3 and 6, and 5 where the pattern has it) are set to
    /// its value, every other bit is kept.
    #[must_use]
    pub const fn with_state(self, state: Cia402State) -> Self {
        let (mask, value) = state.statusword_pattern();
        Statusword::from_bits_retain((self.bits() & !mask) | value)
    }

    /// Return the names of the set bits in bit order.
    pub fn names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |&(flag, _)| self.contains(flag))
            .map(|(_, name)| name)
    }
}

impl fmt::Display for Statusword {
    /// `0x0237 [ready_to_switch_on|switched_on|…]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        crate::names::write_word(f, format_args!("{:#06x}", self.bits()), self.names())
    }
}

bitflags! {
    /// The controlword, object 6040h (CiA 402-2 / IEC 61800-7-201, object
    /// 6040h; SPEC §8.3): the device-control command in bits 0–3 and 7
    /// ([`Controlword::command`]), halt and the mode-specific bits.
    ///
    /// Decode a word that a master sent with
    /// [`Controlword::from_bits_retain`]; every bit has a name, so all 16
    /// survive every operation. With the `serde` feature the word serializes
    /// in bitflags' format.
    ///
    /// ```
    /// use motionwire::canopen::{Cia402Command, Controlword};
    ///
    /// let cw = Controlword::from_bits_retain(0x011F);
    /// assert!(cw.contains(Controlword::HALT));
    /// assert_eq!(cw.command(None, None), Some(Cia402Command::EnableOperation));
    /// assert_eq!(
    ///     cw.to_string(),
    ///     "0x011f [switch_on|enable_voltage|quick_stop|enable_operation|operation_mode_specific_4|halt]"
    /// );
    /// ```
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
    #[cfg_attr(
        feature = "serde",
        derive(serde::Serialize, serde::Deserialize),
        serde(transparent)
    )]
    pub struct Controlword: u16 {
        /// Bit 0: switch on.
        const SWITCH_ON = 1 << 0;
        /// Bit 1: enable voltage.
        const ENABLE_VOLTAGE = 1 << 1;
        /// Bit 2: quick stop, active low: 0 commands a quick stop.
        const QUICK_STOP = 1 << 2;
        /// Bit 3: enable operation.
        const ENABLE_OPERATION = 1 << 3;
        /// Bit 4: operation-mode specific (e.g. new set-point in profile
        /// position mode, homing operation start in homing mode).
        const OPERATION_MODE_SPECIFIC_4 = 1 << 4;
        /// Bit 5: operation-mode specific (e.g. change set immediately in
        /// profile position mode).
        const OPERATION_MODE_SPECIFIC_5 = 1 << 5;
        /// Bit 6: operation-mode specific (e.g. absolute/relative in profile
        /// position mode).
        const OPERATION_MODE_SPECIFIC_6 = 1 << 6;
        /// Bit 7: fault reset, acting on its 0 → 1 edge.
        const FAULT_RESET = 1 << 7;
        /// Bit 8: halt.
        const HALT = 1 << 8;
        /// Bit 9: operation-mode specific (e.g. change on set-point in profile
        /// position mode).
        const OPERATION_MODE_SPECIFIC_9 = 1 << 9;
        /// Bit 10: reserved.
        const RESERVED_10 = 1 << 10;
        /// Bit 11: manufacturer specific.
        const MANUFACTURER_SPECIFIC_11 = 1 << 11;
        /// Bit 12: manufacturer specific.
        const MANUFACTURER_SPECIFIC_12 = 1 << 12;
        /// Bit 13: manufacturer specific.
        const MANUFACTURER_SPECIFIC_13 = 1 << 13;
        /// Bit 14: manufacturer specific.
        const MANUFACTURER_SPECIFIC_14 = 1 << 14;
        /// Bit 15: manufacturer specific.
        const MANUFACTURER_SPECIFIC_15 = 1 << 15;
    }
}

impl Controlword {
    /// The sixteen bits in bit order with their CiA 402 names in lower-case
    /// words: the one table the names, `Display` and the tests read.
    pub const NAMES: [(Controlword, &'static str); 16] = [
        (Controlword::SWITCH_ON, "switch_on"),
        (Controlword::ENABLE_VOLTAGE, "enable_voltage"),
        (Controlword::QUICK_STOP, "quick_stop"),
        (Controlword::ENABLE_OPERATION, "enable_operation"),
        (
            Controlword::OPERATION_MODE_SPECIFIC_4,
            "operation_mode_specific_4",
        ),
        (
            Controlword::OPERATION_MODE_SPECIFIC_5,
            "operation_mode_specific_5",
        ),
        (
            Controlword::OPERATION_MODE_SPECIFIC_6,
            "operation_mode_specific_6",
        ),
        (Controlword::FAULT_RESET, "fault_reset"),
        (Controlword::HALT, "halt"),
        (
            Controlword::OPERATION_MODE_SPECIFIC_9,
            "operation_mode_specific_9",
        ),
        (Controlword::RESERVED_10, "reserved_10"),
        (
            Controlword::MANUFACTURER_SPECIFIC_11,
            "manufacturer_specific_11",
        ),
        (
            Controlword::MANUFACTURER_SPECIFIC_12,
            "manufacturer_specific_12",
        ),
        (
            Controlword::MANUFACTURER_SPECIFIC_13,
            "manufacturer_specific_13",
        ),
        (
            Controlword::MANUFACTURER_SPECIFIC_14,
            "manufacturer_specific_14",
        ),
        (
            Controlword::MANUFACTURER_SPECIFIC_15,
            "manufacturer_specific_15",
        ),
    ];

    /// Return the command the word gives after `previous` in `state`
    /// ([`Cia402Command::from_controlword`], SPEC §8.3's decision).
    #[must_use]
    pub const fn command(
        self,
        previous: Option<Controlword>,
        state: Option<Cia402State>,
    ) -> Option<Cia402Command> {
        let previous = match previous {
            Some(previous) => Some(previous.bits()),
            None => None,
        };
        Cia402Command::from_controlword(self.bits(), previous, state)
    }

    /// Return a copy that codes `command`: bits 0–3 and 7 set to the
    /// command's [`Cia402Command::controlword`], every other bit (the
    /// operation-mode bits, halt, manufacturer bits) kept.
    #[must_use]
    pub const fn with_command(self, command: Cia402Command) -> Self {
        Controlword::from_bits_retain((self.bits() & !COMMAND_MASK) | command.controlword().bits())
    }

    /// Return the names of the set bits in bit order.
    pub fn names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |&(flag, _)| self.contains(flag))
            .map(|(_, name)| name)
    }
}

impl fmt::Display for Controlword {
    /// `0x000f [switch_on|enable_voltage|quick_stop|enable_operation]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        crate::names::write_word(f, format_args!("{:#06x}", self.bits()), self.names())
    }
}

/// A mode of operation, the INTEGER8 of objects 6060h (modes of operation,
/// written by the master) and 6061h (modes of operation display, the mode the
/// drive runs) (CiA 402-2 / IEC 61800-7-201, objects 6060h and 6061h;
/// SPEC §8.3).
///
/// Every value is a mode and is kept as it is: 0 is no mode, 1–4 and 6–10
/// are the profile's modes (the associated constants), negative values are
/// manufacturer specific, 5 and 11–127 are reserved. The constants can be
/// used in patterns.
///
/// ```
/// use motionwire::canopen::ModeOfOperation;
///
/// let mode = ModeOfOperation::from_i8(8);
/// assert_eq!(mode, ModeOfOperation::CYCLIC_SYNCHRONOUS_POSITION);
/// assert_eq!(mode.name(), "cyclic_synchronous_position");
/// assert!(matches!(mode, ModeOfOperation::CYCLIC_SYNCHRONOUS_POSITION));
///
/// let vendor = ModeOfOperation::from_byte(0xFD);
/// assert_eq!(vendor.to_i8(), -3);
/// assert!(vendor.is_manufacturer_specific());
/// assert_eq!(vendor.to_string(), "manufacturer_specific(-3)");
/// assert_eq!(ModeOfOperation::from_i8(5).to_string(), "reserved(5)");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(transparent)
)]
pub struct ModeOfOperation(i8);

impl ModeOfOperation {
    /// 0: no mode assigned.
    pub const NO_MODE: ModeOfOperation = ModeOfOperation(0);
    /// 1: profile position mode (pp).
    pub const PROFILE_POSITION: ModeOfOperation = ModeOfOperation(1);
    /// 2: velocity mode (vl, frequency converters).
    pub const VELOCITY: ModeOfOperation = ModeOfOperation(2);
    /// 3: profile velocity mode (pv).
    pub const PROFILE_VELOCITY: ModeOfOperation = ModeOfOperation(3);
    /// 4: profile torque mode (tq).
    pub const PROFILE_TORQUE: ModeOfOperation = ModeOfOperation(4);
    /// 6: homing mode (hm).
    pub const HOMING: ModeOfOperation = ModeOfOperation(6);
    /// 7: interpolated position mode (ip).
    pub const INTERPOLATED_POSITION: ModeOfOperation = ModeOfOperation(7);
    /// 8: cyclic synchronous position mode (csp).
    pub const CYCLIC_SYNCHRONOUS_POSITION: ModeOfOperation = ModeOfOperation(8);
    /// 9: cyclic synchronous velocity mode (csv).
    pub const CYCLIC_SYNCHRONOUS_VELOCITY: ModeOfOperation = ModeOfOperation(9);
    /// 10: cyclic synchronous torque mode (cst).
    pub const CYCLIC_SYNCHRONOUS_TORQUE: ModeOfOperation = ModeOfOperation(10);

    /// The named modes with their names: the one table
    /// [`ModeOfOperation::name`] and the tests read (CiA 402-2 /
    /// IEC 61800-7-201, value definition of object 6060h).
    pub const NAMED: [(ModeOfOperation, &'static str); 10] = [
        (ModeOfOperation::NO_MODE, "no_mode"),
        (ModeOfOperation::PROFILE_POSITION, "profile_position"),
        (ModeOfOperation::VELOCITY, "velocity"),
        (ModeOfOperation::PROFILE_VELOCITY, "profile_velocity"),
        (ModeOfOperation::PROFILE_TORQUE, "profile_torque"),
        (ModeOfOperation::HOMING, "homing"),
        (
            ModeOfOperation::INTERPOLATED_POSITION,
            "interpolated_position",
        ),
        (
            ModeOfOperation::CYCLIC_SYNCHRONOUS_POSITION,
            "cyclic_synchronous_position",
        ),
        (
            ModeOfOperation::CYCLIC_SYNCHRONOUS_VELOCITY,
            "cyclic_synchronous_velocity",
        ),
        (
            ModeOfOperation::CYCLIC_SYNCHRONOUS_TORQUE,
            "cyclic_synchronous_torque",
        ),
    ];

    /// Return the mode coded by `value`; every value is one.
    #[must_use]
    pub const fn from_i8(value: i8) -> ModeOfOperation {
        ModeOfOperation(value)
    }

    /// Return the mode read from the object's byte on the wire (INTEGER8,
    /// two's complement), e.g. `0xFF` is −1, manufacturer specific.
    #[must_use]
    pub const fn from_byte(byte: u8) -> ModeOfOperation {
        ModeOfOperation(i8::from_le_bytes([byte]))
    }

    /// Return the mode's value as objects 6060h/6061h hold it.
    #[must_use]
    pub const fn to_i8(self) -> i8 {
        self.0
    }

    /// Return the mode's byte on the wire (INTEGER8, two's complement).
    #[must_use]
    pub const fn to_byte(self) -> u8 {
        self.0.to_le_bytes()[0]
    }

    /// Return whether the mode is manufacturer specific (a negative value).
    #[must_use]
    pub const fn is_manufacturer_specific(self) -> bool {
        self.0 < 0
    }

    /// Return whether the value is reserved by CiA 402 (5 and 11–127).
    #[must_use]
    pub const fn is_reserved(self) -> bool {
        self.0 == 5 || self.0 > 10
    }

    /// Return the mode's name in lower-case words, e.g. `"profile_position"`
    /// (SPEC §8.3: modes of operation by name); `"manufacturer_specific"` or
    /// `"reserved"` for the values the profile does not name.
    #[must_use]
    pub const fn name(self) -> &'static str {
        let mut i = 0;
        while i < Self::NAMED.len() {
            let (mode, name) = Self::NAMED[i];
            if mode.0 == self.0 {
                return name;
            }
            i += 1;
        }
        if self.is_manufacturer_specific() {
            "manufacturer_specific"
        } else {
            "reserved"
        }
    }
}

impl From<i8> for ModeOfOperation {
    fn from(value: i8) -> Self {
        Self::from_i8(value)
    }
}

impl From<ModeOfOperation> for i8 {
    fn from(mode: ModeOfOperation) -> i8 {
        mode.to_i8()
    }
}

impl fmt::Display for ModeOfOperation {
    /// The name, `"homing"`; with the value for the modes the profile does
    /// not name, `"manufacturer_specific(-1)"`, `"reserved(5)"`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_manufacturer_specific() || self.is_reserved() {
            write!(f, "{}({})", self.name(), self.0)
        } else {
            f.write_str(self.name())
        }
    }
}

#[cfg(test)]
mod tests {
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

    // SPEC §8.3's decision: a command is a function of (controlword,
    // previous controlword, current state).

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
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::test_gens::cia402::{cia402_command, cia402_state, controlword, statusword};

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
}
