//! The controlword 6040h and the device-control command it codes:
//! [`Cia402Command`], read from bits 0–3 and 7 as CiA 402's command-coding
//! table gives them, and [`Controlword`], every bit named (CiA 402-2 /
//! IEC 61800-7-201, object 6040h; docs/canopen.md#cia402).

use core::fmt;

use bitflags::bitflags;

use super::Cia402State;

/// A device-control command of the CiA 402 drive state machine, coded in
/// bits 0–3 and 7 of the controlword 6040h (CiA 402-2 / IEC 61800-7-201,
/// command coding of object 6040h; docs/canopen.md#cia402).
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
/// use motionwire_codec::canopen::{Cia402Command, Cia402State};
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

    /// Return the command a controlword (object 6040h) gives, by the
    /// decision in docs/canopen.md#cia402: a command is a function of the
    /// controlword, the previous controlword and the current state, as CiA
    /// 402's transition table draws it.
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

    /// Return the command's name in lower-case words as docs/canopen.md#cia402
    /// writes it, e.g. `"enable_operation"`.
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

bitflags! {
    /// The controlword, object 6040h (CiA 402-2 / IEC 61800-7-201, object
    /// 6040h; docs/canopen.md#cia402): the device-control command in bits 0–3
    /// and 7 ([`Controlword::command`]), halt and the mode-specific bits.
    ///
    /// Decode a word that a master sent with
    /// [`Controlword::from_bits_retain`]; every bit has a name, so all 16
    /// survive every operation. With the `serde` feature the word serializes
    /// in bitflags' format.
    ///
    /// ```
    /// use motionwire_codec::canopen::{Cia402Command, Controlword};
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
    /// ([`Cia402Command::from_controlword`], the decision in
    /// docs/canopen.md#cia402).
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
