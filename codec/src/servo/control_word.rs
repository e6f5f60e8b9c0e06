//! SCW, the servo control word the NC sends in every command frame
//! (docs/servo.md#scw; the interface manual, "ServoControlWord").
//!
//! [`ServoControlWord`] holds the eight single-bit flags as bitflags; the
//! multi-bit fields are typed: [`ServoEnable`] (bits 0–1),
//! [`ParameterTable`] (PRMTBL bits 4–5 with ExtPRMTBL bit 12) and
//! [`RegulatorMode`] (bits 6–7). Two bits are **active low** on the wire —
//! EMGON (bit 2) and Brake (bit 10) — so the word offers accessors named after
//! what they mean ([`ServoControlWord::emergency_active`],
//! [`ServoControlWord::internal_brake_active`]) and the all-zero word is *not*
//! a quiet word: it requests emergency braking. Start from
//! [`ServoControlWord::NORMAL`] instead.
//!
//! ```
//! use motionwire_codec::servo::{ParameterTable, RegulatorMode, ServoControlWord, ServoEnable};
//!
//! let scw = ServoControlWord::NORMAL
//!     .with_servo_enable(ServoEnable::ARM)
//!     .with_parameter_table(ParameterTable::try_new(6)?)
//!     .with_regulator_mode(RegulatorMode::Position);
//! // SE=01, EMGON=1, PRMTBL=01, ModeSel=10, Brake=1, ExtPRMTBL=1.
//! assert_eq!(scw.bits(), 0b1_0100_1001_0101);
//! assert!(!scw.emergency_active());
//! assert_eq!(scw.flag_names().collect::<Vec<_>>(), ["EMGON", "Brake", "ExtPRMTBL"]);
//!
//! // The all-zero word is emergency braking with internal braking requested.
//! let zero = ServoControlWord::empty();
//! assert!(zero.emergency_active() && zero.internal_brake_active());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use bitflags::bitflags;

use crate::{RangeError, Result};

bitflags! {
    /// SCW, the servo control word, NC → servo (docs/servo.md#scw; the
    /// interface manual).
    ///
    /// Only the single-bit fields are flags. The 2-bit and 3-bit fields are
    /// read and written through [`ServoControlWord::servo_enable`],
    /// [`ServoControlWord::parameter_table`] and
    /// [`ServoControlWord::regulator_mode`] and their `with_…` builders.
    /// Every other bit (the multi-bit fields and the reserved bits 13–30) is
    /// declared as known to bitflags, so decoding with
    /// [`ServoControlWord::from_bits_retain`] and every flag operation,
    /// complement included, keep them unchanged.
    ///
    /// **Active low:** [`EMGON`](Self::EMGON) and [`BRAKE`](Self::BRAKE) set
    /// mean *normal* operation; clear means emergency / internal braking.
    /// Prefer the accessors [`emergency_active`](Self::emergency_active) and
    /// [`internal_brake_active`](Self::internal_brake_active).
    ///
    /// With the `serde` feature the word serializes in bitflags' format (in
    /// text, e.g. JSON, flag names joined by `|` and any other bits as hex);
    /// every bit survives a round trip.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    #[cfg_attr(
        feature = "serde",
        derive(serde::Serialize, serde::Deserialize),
        serde(transparent)
    )]
    pub struct ServoControlWord: u32 {
        /// Bit 2, EMGON, **active low**: 1 = normal mode, 0 = emergency
        /// state (ramp to the drive's "Emergency Feed" speed).
        const EMGON = 1 << 2;
        /// Bit 3, POSLOCK: 1 = hold the axis at the position latched on the
        /// 0→1 edge of this bit.
        const POSLOCK = 1 << 3;
        /// Bit 8, SIntLock: 1 = freeze the speed regulator's integrator.
        const SINT_LOCK = 1 << 8;
        /// Bit 9, ErrorClear: 1 = request clearing of the drive's errors
        /// (handshake of docs/servo.md#handshakes).
        const ERROR_CLEAR = 1 << 9;
        /// Bit 10, Brake, **active low**: 1 = normal mode, 0 = "internal"
        /// braking or feed without drive enable (documented as not used yet).
        const BRAKE = 1 << 10;
        /// Bit 11, ZPulseRequest: 1 = search the incremental encoder's zero
        /// pulse (handshake of docs/servo.md#handshakes).
        const Z_PULSE_REQUEST = 1 << 11;
        /// Bit 12, ExtPRMTBL: high bit of the parameter-table select; see
        /// [`ServoControlWord::parameter_table`].
        const EXT_PRMTBL = 1 << 12;
        /// Bit 31, PRGDWN: named in the interface manual's layout, meaning not
        /// specified.
        const PRGDWN = 1 << 31;

        // SE, PRMTBL, ModeSel and the reserved bits are not flags but must
        // survive every operation (bitflags 2, "externally defined flags").
        const _ = !0;
    }
}

mod bits {
    /// Bits 0–1: SE, servo enable request.
    pub(super) const SE_SHIFT: u32 = 0;
    /// Bits 4–5: PRMTBL, parameter-table select, low two bits.
    pub(super) const PRMTBL_SHIFT: u32 = 4;
    /// Bits 6–7: ModeSel, regulator mode.
    pub(super) const MODE_SHIFT: u32 = 6;
    /// Mask of a 2-bit field once shifted down.
    pub(super) const TWO_BITS: u32 = 0b11;
}

impl ServoControlWord {
    /// The word for normal operation with nothing requested: EMGON=1 and
    /// Brake=1 (both active low, so neither braking mode is on), SE=00
    /// (disabled), parameter table 1, speed mode (docs/servo.md#scw).
    pub const NORMAL: ServoControlWord = ServoControlWord::EMGON.union(ServoControlWord::BRAKE);

    /// The names of the single-bit flags as docs/servo.md#cli-command writes
    /// them, in bit order.
    pub const NAMES: [(ServoControlWord, &'static str); 8] = [
        (ServoControlWord::EMGON, "EMGON"),
        (ServoControlWord::POSLOCK, "POSLOCK"),
        (ServoControlWord::SINT_LOCK, "SIntLock"),
        (ServoControlWord::ERROR_CLEAR, "ErrorClear"),
        (ServoControlWord::BRAKE, "Brake"),
        (ServoControlWord::Z_PULSE_REQUEST, "ZPulseRequest"),
        (ServoControlWord::EXT_PRMTBL, "ExtPRMTBL"),
        (ServoControlWord::PRGDWN, "PRGDWN"),
    ];

    /// Return the names of the set single-bit flags in bit order, as the
    /// command-line decoder's `control_flags` writes them
    /// (docs/servo.md#cli-command).
    ///
    /// The names are the wire bits, not their meaning: `"EMGON"` appears
    /// when bit 2 is 1, i.e. when the emergency state is *off*.
    pub fn flag_names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |&(flag, _)| self.contains(flag))
            .map(|(_, name)| name)
    }

    /// Return a copy with the 2-bit `field` at `shift` replaced by `value`.
    const fn with_field(self, shift: u32, value: u32) -> Self {
        let cleared = self.bits() & !(bits::TWO_BITS << shift);
        ServoControlWord::from_bits_retain(cleared | ((value & bits::TWO_BITS) << shift))
    }

    /// Return the 2-bit field at `shift`.
    const fn field(self, shift: u32) -> u8 {
        ((self.bits() >> shift) & bits::TWO_BITS) as u8
    }

    /// Return the SE field (bits 0–1), the servo enable request.
    #[must_use]
    pub const fn servo_enable(self) -> ServoEnable {
        ServoEnable(self.field(bits::SE_SHIFT))
    }

    /// Return a copy with the SE field (bits 0–1) set to `se`.
    #[must_use]
    pub const fn with_servo_enable(self, se: ServoEnable) -> Self {
        self.with_field(bits::SE_SHIFT, se.0 as u32)
    }

    /// Return whether the emergency state is requested: EMGON (bit 2) is
    /// **0** on the wire (docs/servo.md#scw, active low).
    #[must_use]
    pub const fn emergency_active(self) -> bool {
        !self.contains(ServoControlWord::EMGON)
    }

    /// Return a copy that requests (`true`: EMGON bit 2 written as 0) or
    /// releases (`false`: bit 2 written as 1) the emergency state.
    #[must_use]
    pub const fn with_emergency(self, active: bool) -> Self {
        self.with_flag(ServoControlWord::EMGON, !active)
    }

    /// Return whether "internal" braking is requested: Brake (bit 10) is
    /// **0** on the wire (docs/servo.md#scw, active low; documented as not used
    /// yet).
    #[must_use]
    pub const fn internal_brake_active(self) -> bool {
        !self.contains(ServoControlWord::BRAKE)
    }

    /// Return a copy that requests (`true`: Brake bit 10 written as 0) or
    /// releases (`false`: bit 10 written as 1) internal braking.
    #[must_use]
    pub const fn with_internal_brake(self, active: bool) -> Self {
        self.with_flag(ServoControlWord::BRAKE, !active)
    }

    /// Return a copy with the single-bit `flag` set or cleared.
    #[must_use]
    pub const fn with_flag(self, flag: ServoControlWord, set: bool) -> Self {
        if set {
            self.union(flag)
        } else {
            self.difference(flag)
        }
    }

    /// Return the selected parameter table, ExtPRMTBL·4 + PRMTBL + 1, from
    /// PRMTBL (bits 4–5) and ExtPRMTBL (bit 12) (the Decision in
    /// docs/servo.md#scw: PRMTBL is bits 4–5).
    #[must_use]
    pub const fn parameter_table(self) -> ParameterTable {
        ParameterTable::from_select(
            self.contains(ServoControlWord::EXT_PRMTBL),
            self.field(bits::PRMTBL_SHIFT),
        )
    }

    /// Return a copy that selects parameter table `table` (PRMTBL bits 4–5
    /// and ExtPRMTBL bit 12).
    #[must_use]
    pub const fn with_parameter_table(self, table: ParameterTable) -> Self {
        self.with_field(bits::PRMTBL_SHIFT, table.prmtbl() as u32)
            .with_flag(ServoControlWord::EXT_PRMTBL, table.ext_prmtbl())
    }

    /// Return the ModeSel field (bits 6–7), the regulator mode.
    #[must_use]
    pub const fn regulator_mode(self) -> RegulatorMode {
        RegulatorMode::from_bits(self.field(bits::MODE_SHIFT))
    }

    /// Return a copy with the ModeSel field (bits 6–7) set to `mode`.
    #[must_use]
    pub const fn with_regulator_mode(self, mode: RegulatorMode) -> Self {
        self.with_field(bits::MODE_SHIFT, mode as u32)
    }
}

/// The SE field of the control word (bits 0–1), the 2-bit servo enable request,
/// always within 0..=3 (docs/servo.md#scw; the interface manual, "Servo
/// Enable").
///
/// The drive enables only on the change 0b01 → 0b10 between two consecutive
/// cycles; see [`drive_enabled`](crate::servo::drive_enabled).
///
/// ```
/// use motionwire_codec::servo::ServoEnable;
///
/// assert_eq!(ServoEnable::new(0b10), Some(ServoEnable::ENABLE));
/// assert!(ServoEnable::new(4).is_none());
/// assert!(ServoEnable::try_new(4).is_err());
/// ```
///
/// With the `serde` feature an SE value serializes as its number;
/// deserializing refuses any number above 3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "u8", into = "u8")
)]
pub struct ServoEnable(u8);

impl ServoEnable {
    /// 0b00: servo drive disabled.
    pub const DISABLED: ServoEnable = ServoEnable(0b00);
    /// 0b01: servo drive disabled; the value that must precede
    /// [`ServoEnable::ENABLE`] for the drive to enable.
    pub const ARM: ServoEnable = ServoEnable(0b01);
    /// 0b10: enable, when the previous cycle sent [`ServoEnable::ARM`]
    /// (bit 0 falls and bit 1 rises together); keeps the drive enabled
    /// while it stays 0b10.
    pub const ENABLE: ServoEnable = ServoEnable(0b10);
    /// 0b11: servo drive disabled.
    pub const BOTH: ServoEnable = ServoEnable(0b11);

    /// Return the SE value `raw`, or `None` when it is above 3.
    #[inline]
    #[must_use]
    pub const fn new(raw: u8) -> Option<Self> {
        if raw <= 0b11 {
            Some(ServoEnable(raw))
        } else {
            None
        }
    }

    /// Return the SE value `raw`, or a [`RangeError`] when it is above 3.
    #[inline]
    pub const fn try_new(raw: u8) -> Result<Self, RangeError> {
        match Self::new(raw) {
            Some(se) => Ok(se),
            None => Err(RangeError {
                what: What::ServoEnable,
                found: raw as u32,
                min: 0,
                max: 3,
            }),
        }
    }

    /// Return the SE value as a number in 0..=3.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self.0
    }

    /// Return the four SE values in ascending order.
    pub fn all() -> impl DoubleEndedIterator<Item = ServoEnable> + ExactSizeIterator + Clone {
        (0..=0b11u8).map(ServoEnable)
    }
}

impl TryFrom<u8> for ServoEnable {
    type Error = RangeError;

    fn try_from(raw: u8) -> Result<Self, RangeError> {
        Self::try_new(raw)
    }
}

impl From<ServoEnable> for u8 {
    fn from(se: ServoEnable) -> u8 {
        se.0
    }
}

impl fmt::Display for ServoEnable {
    /// Format the SE value as two binary digits, e.g. `0b10`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#04b}", self.0)
    }
}

/// The regulator mode selected by ModeSel, control-word bits 6–7
/// (docs/servo.md#scw; the interface manual, "Mode Select", documented as not
/// used yet).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum RegulatorMode {
    /// 0b00: speed regulation.
    Speed = 0,
    /// 0b01: current (torque) regulation.
    Current = 1,
    /// 0b10: position regulation.
    Position = 2,
    /// 0b11: increased-accuracy speed regulation.
    PreciseSpeed = 3,
}

impl RegulatorMode {
    /// The four modes in wire order.
    pub const ALL: [RegulatorMode; 4] = [
        RegulatorMode::Speed,
        RegulatorMode::Current,
        RegulatorMode::Position,
        RegulatorMode::PreciseSpeed,
    ];

    /// Return the mode of the 2-bit value `raw` (its upper bits ignored).
    const fn from_bits(raw: u8) -> Self {
        match raw & 0b11 {
            0 => RegulatorMode::Speed,
            1 => RegulatorMode::Current,
            2 => RegulatorMode::Position,
            _ => RegulatorMode::PreciseSpeed,
        }
    }

    /// Return the mode whose ModeSel value is `raw`, or `None` above 3.
    #[inline]
    #[must_use]
    pub const fn new(raw: u8) -> Option<Self> {
        if raw <= 0b11 {
            Some(Self::from_bits(raw))
        } else {
            None
        }
    }

    /// Return the mode whose ModeSel value is `raw`, or a
    /// [`RangeError`] above 3.
    #[inline]
    pub const fn try_new(raw: u8) -> Result<Self, RangeError> {
        match Self::new(raw) {
            Some(mode) => Ok(mode),
            None => Err(RangeError {
                what: What::RegulatorMode,
                found: raw as u32,
                min: 0,
                max: 3,
            }),
        }
    }

    /// Return the ModeSel value, 0..=3.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self as u8
    }

    /// Return the mode's name as the command-line decoder's
    /// `regulator_mode` writes it (docs/servo.md#cli-command), e.g.
    /// `"precise_speed"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            RegulatorMode::Speed => "speed",
            RegulatorMode::Current => "current",
            RegulatorMode::Position => "position",
            RegulatorMode::PreciseSpeed => "precise_speed",
        }
    }
}

impl TryFrom<u8> for RegulatorMode {
    type Error = RangeError;

    fn try_from(raw: u8) -> Result<Self, RangeError> {
        Self::try_new(raw)
    }
}

impl fmt::Display for RegulatorMode {
    /// Format the mode as its name (docs/servo.md#cli-command).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A drive parameter table, always within 1..=8 (docs/servo.md#scw and
/// docs/servo.md#ssw; the interface manual, "PaRaMeterTaBLe Select" and
/// "ExtendedPaRaMeterTaBLe Select").
///
/// On the wire the table is ExtPRMTBL·4 + PRMTBL + 1: the 2-bit PRMTBL field
/// selects among tables 1–4, and ExtPRMTBL moves to tables 5–8. The control
/// word ([`ServoControlWord`]) selects a table; the status word
/// ([`ServoStatusWord`](crate::servo::ServoStatusWord)) reports the active one.
///
/// ```
/// use motionwire_codec::servo::ParameterTable;
///
/// let table = ParameterTable::try_new(7)?;
/// assert_eq!((table.ext_prmtbl(), table.prmtbl()), (true, 0b10));
/// assert_eq!(ParameterTable::from_select(true, 0b10), table);
/// assert!(ParameterTable::try_new(9).is_err());
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
///
/// With the `serde` feature a table serializes as its number;
/// deserializing refuses any number outside 1..=8.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "u8", into = "u8")
)]
pub struct ParameterTable(u8);

impl ParameterTable {
    /// Table 1, selected by the all-zero select bits.
    pub const MIN: ParameterTable = ParameterTable(1);
    /// Table 8, ExtPRMTBL=1 and PRMTBL=0b11.
    pub const MAX: ParameterTable = ParameterTable(8);

    /// Return table `number`, or `None` when it is outside 1..=8.
    #[inline]
    #[must_use]
    pub const fn new(number: u8) -> Option<Self> {
        if number >= 1 && number <= 8 {
            Some(ParameterTable(number))
        } else {
            None
        }
    }

    /// Return table `number`, or a [`RangeError`] when it is
    /// outside 1..=8.
    #[inline]
    pub const fn try_new(number: u8) -> Result<Self, RangeError> {
        match Self::new(number) {
            Some(table) => Ok(table),
            None => Err(RangeError {
                what: What::ParameterTable,
                found: number as u32,
                min: 1,
                max: 8,
            }),
        }
    }

    /// Return the table selected by the wire bits: ExtPRMTBL `ext_prmtbl`
    /// and the 2-bit PRMTBL field `prmtbl` (its upper bits are ignored).
    #[inline]
    #[must_use]
    pub const fn from_select(ext_prmtbl: bool, prmtbl: u8) -> Self {
        ParameterTable((ext_prmtbl as u8) * 4 + (prmtbl & 0b11) + 1)
    }

    /// Return the table number, 1..=8.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self.0
    }

    /// Return the ExtPRMTBL bit that selects this table (tables 5–8).
    #[inline]
    #[must_use]
    pub const fn ext_prmtbl(self) -> bool {
        self.0 > 4
    }

    /// Return the 2-bit PRMTBL field that selects this table, 0..=3.
    #[inline]
    #[must_use]
    pub const fn prmtbl(self) -> u8 {
        (self.0 - 1) & 0b11
    }

    /// Return every table, 1 to 8, in ascending order.
    pub fn all() -> impl DoubleEndedIterator<Item = ParameterTable> + ExactSizeIterator + Clone {
        (1..=8u8).map(ParameterTable)
    }
}

impl TryFrom<u8> for ParameterTable {
    type Error = RangeError;

    fn try_from(number: u8) -> Result<Self, RangeError> {
        Self::try_new(number)
    }
}

impl From<ParameterTable> for u8 {
    fn from(table: ParameterTable) -> u8 {
        table.0
    }
}

impl fmt::Display for ParameterTable {
    /// Format the table number, 1..=8.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/servo.md#scw / the interface manual's bit diagram: every single-bit
    /// flag at its bit.
    #[test]
    fn flag_bit_positions() {
        let table = [
            (ServoControlWord::EMGON, 2),
            (ServoControlWord::POSLOCK, 3),
            (ServoControlWord::SINT_LOCK, 8),
            (ServoControlWord::ERROR_CLEAR, 9),
            (ServoControlWord::BRAKE, 10),
            (ServoControlWord::Z_PULSE_REQUEST, 11),
            (ServoControlWord::EXT_PRMTBL, 12),
            (ServoControlWord::PRGDWN, 31),
        ];
        for (flag, bit) in table {
            assert_eq!(flag.bits(), 1u32 << bit, "{flag:?}");
            assert!(ServoControlWord::from_bits_retain(1 << bit).contains(flag));
        }
    }

    #[test]
    fn flag_names_are_the_json_names_in_bit_order() {
        assert_eq!(
            ServoControlWord::from_bits_retain(u32::MAX)
                .flag_names()
                .collect::<Vec<_>>(),
            [
                "EMGON",
                "POSLOCK",
                "SIntLock",
                "ErrorClear",
                "Brake",
                "ZPulseRequest",
                "ExtPRMTBL",
                "PRGDWN"
            ]
        );
        // The multi-bit fields and reserved bits have no names.
        let fields_only = ServoControlWord::from_bits_retain(0x7FFF_E0F3);
        assert_eq!(fields_only.flag_names().count(), 0);
        assert_eq!(
            ServoControlWord::from_bits_retain(0x8000_0208)
                .flag_names()
                .collect::<Vec<_>>(),
            ["POSLOCK", "ErrorClear", "PRGDWN"]
        );
    }

    /// The interface manual, "Servo Enable": SE is bits 0–1.
    #[test]
    fn servo_enable_field() {
        let table = [
            (0b00u32, ServoEnable::DISABLED),
            (0b01, ServoEnable::ARM),
            (0b10, ServoEnable::ENABLE),
            (0b11, ServoEnable::BOTH),
        ];
        for (bits, se) in table {
            let word = ServoControlWord::from_bits_retain(bits);
            assert_eq!(word.servo_enable(), se);
            assert_eq!(ServoControlWord::empty().with_servo_enable(se).bits(), bits);
            // Replacing SE leaves every other bit alone.
            let full = ServoControlWord::from_bits_retain(u32::MAX).with_servo_enable(se);
            assert_eq!(full.bits(), 0xFFFF_FFFC | bits);
        }
    }

    #[test]
    fn servo_enable_range() {
        for raw in 0..=255u8 {
            match ServoEnable::try_new(raw) {
                Ok(se) => {
                    assert!(raw <= 3);
                    assert_eq!(se.get(), raw);
                }
                Err(e) => assert_eq!(
                    e,
                    RangeError {
                        what: What::ServoEnable,
                        found: u32::from(raw),
                        min: 0,
                        max: 3
                    }
                ),
            }
            assert_eq!(ServoEnable::new(raw).is_some(), raw <= 3);
        }
        assert_eq!(
            ServoEnable::all().map(u8::from).collect::<Vec<_>>(),
            [0, 1, 2, 3]
        );
        assert_eq!(ServoEnable::ARM.to_string(), "0b01");
    }

    /// docs/servo.md#scw: EMGON and Brake are active low.
    #[test]
    fn active_low_bits() {
        // (wire bits, emergency_active, internal_brake_active)
        let table = [
            (0x0000_0000u32, true, true),
            (0x0000_0004, false, true),
            (0x0000_0400, true, false),
            (0x0000_0404, false, false),
        ];
        for (bits, emergency, brake) in table {
            let word = ServoControlWord::from_bits_retain(bits);
            assert_eq!(word.emergency_active(), emergency, "{bits:#x}");
            assert_eq!(word.internal_brake_active(), brake, "{bits:#x}");
            let built = ServoControlWord::empty()
                .with_emergency(emergency)
                .with_internal_brake(brake);
            assert_eq!(built.bits(), bits);
        }
        assert!(!ServoControlWord::NORMAL.emergency_active());
        assert!(!ServoControlWord::NORMAL.internal_brake_active());
        assert_eq!(ServoControlWord::NORMAL.bits(), 0x0404);
        assert_eq!(
            ServoControlWord::NORMAL.with_emergency(true).bits(),
            0x0400,
            "requesting the emergency state writes bit 2 as 0"
        );
    }

    /// The Decision in docs/servo.md#scw and the interface manual,
    /// "ExtendedPaRaMeterTaBLe Select": the eight combinations of ExtPRMTBL
    /// (bit 12) and PRMTBL (bits 5–4).
    #[test]
    fn every_parameter_table_combination() {
        // (ExtPRMTBL, PRMTBL, wire bits, table)
        let table = [
            (false, 0b00, 0x0000u32, 1u8),
            (false, 0b01, 0x0010, 2),
            (false, 0b10, 0x0020, 3),
            (false, 0b11, 0x0030, 4),
            (true, 0b00, 0x1000, 5),
            (true, 0b01, 0x1010, 6),
            (true, 0b10, 0x1020, 7),
            (true, 0b11, 0x1030, 8),
        ];
        for (ext, prmtbl, bits, number) in table {
            let expected = ParameterTable::try_new(number).unwrap();
            assert_eq!(ParameterTable::from_select(ext, prmtbl), expected);
            assert_eq!((expected.ext_prmtbl(), expected.prmtbl()), (ext, prmtbl));
            assert_eq!(
                ServoControlWord::from_bits_retain(bits).parameter_table(),
                expected
            );
            assert_eq!(
                ServoControlWord::empty()
                    .with_parameter_table(expected)
                    .bits(),
                bits
            );
            let full = ServoControlWord::from_bits_retain(u32::MAX).with_parameter_table(expected);
            assert_eq!(full.bits(), !0x1030 | bits);
        }
        assert_eq!(
            ParameterTable::all().map(u8::from).collect::<Vec<_>>(),
            [1, 2, 3, 4, 5, 6, 7, 8]
        );
    }

    #[test]
    fn parameter_table_range() {
        for raw in 0..=255u8 {
            match ParameterTable::try_new(raw) {
                Ok(t) => assert_eq!(t.get(), raw),
                Err(e) => assert_eq!(
                    e,
                    RangeError {
                        what: What::ParameterTable,
                        found: u32::from(raw),
                        min: 1,
                        max: 8
                    }
                ),
            }
            assert_eq!(ParameterTable::new(raw).is_some(), (1..=8).contains(&raw));
        }
    }

    /// The interface manual, "Mode Select": ModeSel is bits 6–7.
    #[test]
    fn regulator_mode_field() {
        let table = [
            (0x00u32, RegulatorMode::Speed, "speed"),
            (0x40, RegulatorMode::Current, "current"),
            (0x80, RegulatorMode::Position, "position"),
            (0xC0, RegulatorMode::PreciseSpeed, "precise_speed"),
        ];
        for (bits, mode, name) in table {
            assert_eq!(
                ServoControlWord::from_bits_retain(bits).regulator_mode(),
                mode
            );
            assert_eq!(
                ServoControlWord::empty().with_regulator_mode(mode).bits(),
                bits
            );
            assert_eq!(mode.name(), name);
            assert_eq!(mode.to_string(), name);
            assert_eq!(RegulatorMode::try_new(mode.get()), Ok(mode));
        }
        assert_eq!(
            RegulatorMode::try_new(4),
            Err(RangeError {
                what: What::RegulatorMode,
                found: 4,
                min: 0,
                max: 3
            })
        );
    }

    /// docs/servo.md#scw: the reserved bits 13–30 round-trip, and so do the
    /// fields through every flag operation, complement included.
    #[test]
    fn reserved_bits_survive() {
        let reserved = 0x7FFF_E000u32;
        let word = ServoControlWord::from_bits_retain(reserved | 0xF3);
        assert_eq!(word.bits(), reserved | 0xF3);
        assert_eq!((!word).bits(), !(reserved | 0xF3));
        let mut w = word;
        w.insert(ServoControlWord::ERROR_CLEAR);
        w.remove(ServoControlWord::ERROR_CLEAR);
        assert_eq!(w, word);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::{control_word, parameter_table, servo_enable};

    proptest! {
        #[test]
        fn bits_round_trip(bits in any::<u32>()) {
            prop_assert_eq!(ServoControlWord::from_bits_retain(bits).bits(), bits);
        }

        /// Each builder writes its field and leaves every other bit alone.
        #[test]
        fn builders_touch_only_their_field(
            word in control_word(),
            se in servo_enable(),
            table in parameter_table(),
            mode in 0u8..=3,
            emergency in any::<bool>(),
            brake in any::<bool>(),
        ) {
            let mode = RegulatorMode::try_new(mode).unwrap();
            let w = word.with_servo_enable(se);
            prop_assert_eq!(w.servo_enable(), se);
            prop_assert_eq!(w.bits() & !0b11, word.bits() & !0b11);

            let w = word.with_parameter_table(table);
            prop_assert_eq!(w.parameter_table(), table);
            prop_assert_eq!(w.bits() & !0x1030, word.bits() & !0x1030);

            let w = word.with_regulator_mode(mode);
            prop_assert_eq!(w.regulator_mode(), mode);
            prop_assert_eq!(w.bits() & !0xC0, word.bits() & !0xC0);

            let w = word.with_emergency(emergency).with_internal_brake(brake);
            prop_assert_eq!(w.emergency_active(), emergency);
            prop_assert_eq!(w.internal_brake_active(), brake);
            prop_assert_eq!(w.bits() & !0x404, word.bits() & !0x404);
        }

        #[test]
        fn flag_names_match_the_bits(word in control_word()) {
            let names: Vec<_> = word.flag_names().collect();
            let expected: Vec<_> = ServoControlWord::NAMES
                .iter()
                .filter(|(flag, _)| word.bits() & flag.bits() != 0)
                .map(|&(_, name)| name)
                .collect();
            prop_assert_eq!(names, expected);
        }
    }
}

impl fmt::Display for ServoControlWord {
    /// The word in hex with the names of its set single-bit flags, as
    /// docs/servo.md#cli-command names them: `0x00000021 [EMGON|Brake]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        crate::names::write_word(f, format_args!("{:#010x}", self.bits()), self.flag_names())
    }
}
