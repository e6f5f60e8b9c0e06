//! The emergency error code and its class: [`ErrorCode`], [`ErrorClass`].

use core::fmt;

use crate::canopen::ErrorRegister;

/// An emergency error code, bytes 0–1 of an EMCY (CiA 301 §7.2.7.3.2;
/// docs/canopen.md#emcy-codes).
///
/// Every `u16` is a valid code: [`ErrorCode::class`] sorts it into one of the
/// classes of CiA 301's table, or [`ErrorClass::Unknown`] when it lies outside
/// every range.
///
/// ```
/// use motionwire_codec::canopen::{ErrorClass, ErrorCode};
///
/// let code = ErrorCode::new(0x8130);
/// assert_eq!(code.class(), ErrorClass::Monitoring);
/// assert_eq!(code.to_string(), "0x8130");
/// assert!(ErrorCode::new(0x0001).is_reset());
/// assert_eq!(ErrorCode::new(0xA000).class(), ErrorClass::Unknown);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(transparent)
)]
pub struct ErrorCode(u16);

impl ErrorCode {
    /// 0x0000, "error reset or no error": the only code a producer sends for
    /// a reset (the **Decision** in docs/canopen.md#emcy-codes).
    pub const NO_ERROR: ErrorCode = ErrorCode(0x0000);
    /// 0x8130, life guard error or heartbeat error (CiA 301 Table 26).
    pub const LIFE_GUARD: ErrorCode = ErrorCode(0x8130);

    /// Return the error code `raw`.
    #[inline]
    #[must_use]
    pub const fn new(raw: u16) -> Self {
        ErrorCode(raw)
    }

    /// Return the code as a number.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u16 {
        self.0
    }

    /// Return whether this is an "error reset or no error" code: any 0x00xx
    /// when decoding (the **Decision** in docs/canopen.md#emcy-codes).
    #[inline]
    #[must_use]
    pub const fn is_reset(self) -> bool {
        self.0 >> 8 == 0
    }

    /// Return the class of the code, from the ranges of CiA 301 Table 26
    /// (docs/canopen.md#emcy-codes).
    #[must_use]
    pub const fn class(self) -> ErrorClass {
        match self.0 {
            0x0000..=0x00FF => ErrorClass::Reset,
            0x1000..=0x10FF => ErrorClass::Generic,
            0x2000..=0x2FFF => ErrorClass::Current,
            0x3000..=0x3FFF => ErrorClass::Voltage,
            0x4000..=0x4FFF => ErrorClass::Temperature,
            0x5000..=0x5FFF => ErrorClass::DeviceHardware,
            0x6000..=0x6FFF => ErrorClass::DeviceSoftware,
            0x7000..=0x7FFF => ErrorClass::AdditionalModules,
            0x8000..=0x8FFF => ErrorClass::Monitoring,
            0x9000..=0x9FFF => ErrorClass::External,
            0xF000..=0xF0FF => ErrorClass::AdditionalFunctions,
            0xFF00..=0xFFFF => ErrorClass::DeviceSpecific,
            _ => ErrorClass::Unknown,
        }
    }

    /// Return the error-register class bits that this code implies: 2xxx
    /// current, 3xxx voltage, 4xxx temperature, 81xx/82xx communication
    /// (docs/canopen.md#emcy-producer). Bit 0 (generic) is not included: the
    /// EMCY state machine sets it whenever any error is active.
    #[must_use]
    pub const fn register_class_bits(self) -> ErrorRegister {
        match self.0 >> 8 {
            0x20..=0x2F => ErrorRegister::CURRENT,
            0x30..=0x3F => ErrorRegister::VOLTAGE,
            0x40..=0x4F => ErrorRegister::TEMPERATURE,
            0x81 | 0x82 => ErrorRegister::COMMUNICATION,
            _ => ErrorRegister::empty(),
        }
    }
}

impl From<u16> for ErrorCode {
    fn from(raw: u16) -> Self {
        ErrorCode(raw)
    }
}

impl From<ErrorCode> for u16 {
    fn from(code: ErrorCode) -> u16 {
        code.0
    }
}

impl fmt::Display for ErrorCode {
    /// Format the code as `0x8130`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:04X}", self.0)
    }
}

/// The class of an emergency error code (CiA 301 Table 26;
/// docs/canopen.md#emcy-codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ErrorClass {
    /// 0x00xx: error reset or no error.
    Reset,
    /// 0x10xx: generic error.
    Generic,
    /// 0x2xxx: current.
    Current,
    /// 0x3xxx: voltage.
    Voltage,
    /// 0x4xxx: temperature.
    Temperature,
    /// 0x5xxx: device hardware.
    DeviceHardware,
    /// 0x6xxx: device software.
    DeviceSoftware,
    /// 0x7xxx: additional modules.
    AdditionalModules,
    /// 0x8xxx: monitoring (0x81xx communication, 0x82xx protocol error).
    Monitoring,
    /// 0x9xxx: external error.
    External,
    /// 0xF0xx: additional functions.
    AdditionalFunctions,
    /// 0xFFxx: device specific.
    DeviceSpecific,
    /// Outside every range of CiA 301's table (0x01xx–0x0Fxx, 0x11xx–0x1Fxx,
    /// 0xA000–0xEFFF, 0xF100–0xFEFF).
    Unknown,
}

impl ErrorClass {
    /// Return the class's name as the JSON output writes it
    /// (docs/canopen.md#emcy-codes), e.g. `"device_hardware"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            ErrorClass::Reset => "reset",
            ErrorClass::Generic => "generic",
            ErrorClass::Current => "current",
            ErrorClass::Voltage => "voltage",
            ErrorClass::Temperature => "temperature",
            ErrorClass::DeviceHardware => "device_hardware",
            ErrorClass::DeviceSoftware => "device_software",
            ErrorClass::AdditionalModules => "additional_modules",
            ErrorClass::Monitoring => "monitoring",
            ErrorClass::External => "external",
            ErrorClass::AdditionalFunctions => "additional_functions",
            ErrorClass::DeviceSpecific => "device_specific",
            ErrorClass::Unknown => "unknown",
        }
    }

    /// Return the class's description in words (CiA 301 Table 26).
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            ErrorClass::Reset => "Error reset or no error",
            ErrorClass::Generic => "Generic error",
            ErrorClass::Current => "Current",
            ErrorClass::Voltage => "Voltage",
            ErrorClass::Temperature => "Temperature",
            ErrorClass::DeviceHardware => "Device hardware",
            ErrorClass::DeviceSoftware => "Device software",
            ErrorClass::AdditionalModules => "Additional modules",
            ErrorClass::Monitoring => "Monitoring",
            ErrorClass::External => "External error",
            ErrorClass::AdditionalFunctions => "Additional functions",
            ErrorClass::DeviceSpecific => "Device specific",
            ErrorClass::Unknown => "Unknown error code",
        }
    }
}

impl fmt::Display for ErrorClass {
    /// Format the class as its JSON name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
