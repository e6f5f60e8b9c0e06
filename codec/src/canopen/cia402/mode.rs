//! The modes of operation, objects 6060h and 6061h (CiA 402-2 /
//! IEC 61800-7-201; docs/canopen.md#cia402).

use core::fmt;

/// A mode of operation, the INTEGER8 of objects 6060h (modes of operation,
/// written by the master) and 6061h (modes of operation display, the mode the
/// drive runs) (CiA 402-2 / IEC 61800-7-201, objects 6060h and 6061h;
/// docs/canopen.md#cia402).
///
/// Every value is a mode and is kept as it is: 0 is no mode, 1–4 and 6–10
/// are the profile's modes (the associated constants), negative values are
/// manufacturer specific, 5 and 11–127 are reserved. The constants can be
/// used in patterns.
///
/// ```
/// use motionwire_codec::canopen::ModeOfOperation;
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
    /// (docs/canopen.md#cia402: modes of operation by name);
    /// `"manufacturer_specific"` or `"reserved"` for the values the profile
    /// does not name.
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
