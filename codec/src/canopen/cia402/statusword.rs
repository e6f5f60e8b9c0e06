//! The statusword 6041h and the drive state it codes: [`Cia402State`],
//! read from bits 0–3, 5 and 6 as CiA 402's state-coding table gives them,
//! and [`Statusword`], every bit named (CiA 402-2 / IEC 61800-7-201,
//! object 6041h; docs/canopen.md#cia402).

use core::fmt;

use bitflags::bitflags;

/// A state of the CiA 402 drive state machine (CiA 402-2 / IEC 61800-7-201,
/// the state diagram of the drive state machine; docs/canopen.md#cia402).
///
/// ```
/// use motionwire_codec::canopen::Cia402State;
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
    /// IEC 61800-7-201, state coding of object 6041h; docs/canopen.md#cia402).
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

    /// Return the state's name in lower-case words as docs/canopen.md#cia402
    /// writes it, e.g. `"not_ready_to_switch_on"`.
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
    /// reaction active, fault): docs/summary.md#cia402 counts a fault where the
    /// state enters one of them from a state that is neither.
    #[must_use]
    pub const fn is_fault(self) -> bool {
        matches!(self, Cia402State::FaultReactionActive | Cia402State::Fault)
    }
}

impl fmt::Display for Cia402State {
    /// Format the state as its [`Cia402State::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

bitflags! {
    /// The statusword, object 6041h (CiA 402-2 / IEC 61800-7-201, object
    /// 6041h; docs/canopen.md#cia402): the drive's state in bits 0–3, 5, 6
    /// ([`Statusword::state`]) and its other status bits.
    ///
    /// Decode a word that a drive sent with [`Statusword::from_bits_retain`];
    /// every bit has a name, so all 16 survive every operation. With the
    /// `serde` feature the word serializes in bitflags' format.
    ///
    /// ```
    /// use motionwire_codec::canopen::{Cia402State, Statusword};
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
