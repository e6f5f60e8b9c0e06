//! SDO abort codes (CiA 301 §7.2.4.3.17, Table 22).
//!
//! An SDO server refuses a read (upload) or write (download) of an object
//! dictionary entry with a 32-bit abort code. [`SdoAbortCode`] holds any
//! `u32`; the codes of CiA 301 Table 22 are named constants with their
//! descriptions.

use core::fmt;

/// An SDO abort code (CiA 301 §7.2.4.3.17, Table 22), sent little-endian in
/// bytes 4–7 of an abort transfer.
///
/// Every `u32` is a value of this type; [`SdoAbortCode::description`] names
/// the codes of CiA 301 Table 22 and reports any other as unknown.
///
/// ```
/// use motionwire_codec::canopen::SdoAbortCode;
///
/// let abort = SdoAbortCode::NO_DATA_AVAILABLE;
/// assert_eq!(abort.get(), 0x0800_0024);
/// assert_eq!(abort.to_string(), "0x08000024: No data available");
/// assert!(!SdoAbortCode::new(0x1234_5678).is_known());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(transparent)
)]
pub struct SdoAbortCode(u32);

impl SdoAbortCode {
    /// 0x0503_0000: toggle bit not alternated.
    pub const TOGGLE_BIT_NOT_ALTERNATED: SdoAbortCode = SdoAbortCode(0x0503_0000);
    /// 0x0504_0000: SDO protocol timed out.
    pub const TIMED_OUT: SdoAbortCode = SdoAbortCode(0x0504_0000);
    /// 0x0504_0001: client/server command specifier not valid or unknown.
    pub const INVALID_COMMAND_SPECIFIER: SdoAbortCode = SdoAbortCode(0x0504_0001);
    /// 0x0504_0002: invalid block size (block mode only).
    pub const INVALID_BLOCK_SIZE: SdoAbortCode = SdoAbortCode(0x0504_0002);
    /// 0x0504_0003: invalid sequence number (block mode only).
    pub const INVALID_SEQUENCE_NUMBER: SdoAbortCode = SdoAbortCode(0x0504_0003);
    /// 0x0504_0004: CRC error (block mode only).
    pub const CRC_ERROR: SdoAbortCode = SdoAbortCode(0x0504_0004);
    /// 0x0504_0005: out of memory.
    pub const OUT_OF_MEMORY: SdoAbortCode = SdoAbortCode(0x0504_0005);
    /// 0x0601_0000: unsupported access to an object.
    pub const UNSUPPORTED_ACCESS: SdoAbortCode = SdoAbortCode(0x0601_0000);
    /// 0x0601_0001: attempt to read a write-only object.
    pub const READ_OF_WRITE_ONLY: SdoAbortCode = SdoAbortCode(0x0601_0001);
    /// 0x0601_0002: attempt to write a read-only object.
    pub const WRITE_OF_READ_ONLY: SdoAbortCode = SdoAbortCode(0x0601_0002);
    /// 0x0602_0000: object does not exist in the object dictionary.
    pub const OBJECT_DOES_NOT_EXIST: SdoAbortCode = SdoAbortCode(0x0602_0000);
    /// 0x0604_0041: object cannot be mapped to the PDO.
    pub const NOT_MAPPABLE: SdoAbortCode = SdoAbortCode(0x0604_0041);
    /// 0x0604_0042: the number and length of the objects to be mapped would
    /// exceed the PDO length.
    pub const PDO_LENGTH_EXCEEDED: SdoAbortCode = SdoAbortCode(0x0604_0042);
    /// 0x0604_0043: general parameter incompatibility reason.
    pub const PARAMETER_INCOMPATIBILITY: SdoAbortCode = SdoAbortCode(0x0604_0043);
    /// 0x0604_0047: general internal incompatibility in the device.
    pub const INTERNAL_INCOMPATIBILITY: SdoAbortCode = SdoAbortCode(0x0604_0047);
    /// 0x0606_0000: access failed due to a hardware error.
    pub const HARDWARE_ERROR: SdoAbortCode = SdoAbortCode(0x0606_0000);
    /// 0x0607_0010: data type does not match, length of service parameter
    /// does not match.
    pub const LENGTH_MISMATCH: SdoAbortCode = SdoAbortCode(0x0607_0010);
    /// 0x0607_0012: data type does not match, length of service parameter
    /// too high.
    pub const LENGTH_TOO_HIGH: SdoAbortCode = SdoAbortCode(0x0607_0012);
    /// 0x0607_0013: data type does not match, length of service parameter
    /// too low.
    pub const LENGTH_TOO_LOW: SdoAbortCode = SdoAbortCode(0x0607_0013);
    /// 0x0609_0011: sub-index does not exist.
    pub const SUB_INDEX_DOES_NOT_EXIST: SdoAbortCode = SdoAbortCode(0x0609_0011);
    /// 0x0609_0030: invalid value for parameter (download only); older
    /// editions of CiA 301 and docs/canopen.md#error-history call it "value
    /// range of parameter exceeded".
    #[doc(alias = "VALUE_RANGE_EXCEEDED")]
    pub const INVALID_VALUE: SdoAbortCode = SdoAbortCode(0x0609_0030);
    /// 0x0609_0031: value of parameter written too high (download only).
    pub const VALUE_TOO_HIGH: SdoAbortCode = SdoAbortCode(0x0609_0031);
    /// 0x0609_0032: value of parameter written too low (download only).
    pub const VALUE_TOO_LOW: SdoAbortCode = SdoAbortCode(0x0609_0032);
    /// 0x0609_0036: maximum value is less than minimum value.
    pub const MAX_LESS_THAN_MIN: SdoAbortCode = SdoAbortCode(0x0609_0036);
    /// 0x060A_0023: resource not available: SDO connection.
    pub const RESOURCE_NOT_AVAILABLE: SdoAbortCode = SdoAbortCode(0x060A_0023);
    /// 0x0800_0000: general error.
    pub const GENERAL_ERROR: SdoAbortCode = SdoAbortCode(0x0800_0000);
    /// 0x0800_0020: data cannot be transferred or stored to the application.
    pub const CANNOT_TRANSFER: SdoAbortCode = SdoAbortCode(0x0800_0020);
    /// 0x0800_0021: data cannot be transferred or stored to the application
    /// because of local control.
    pub const CANNOT_TRANSFER_LOCAL_CONTROL: SdoAbortCode = SdoAbortCode(0x0800_0021);
    /// 0x0800_0022: data cannot be transferred or stored to the application
    /// because of the present device state.
    pub const CANNOT_TRANSFER_DEVICE_STATE: SdoAbortCode = SdoAbortCode(0x0800_0022);
    /// 0x0800_0023: object dictionary dynamic generation fails or no object
    /// dictionary is present.
    pub const NO_OBJECT_DICTIONARY: SdoAbortCode = SdoAbortCode(0x0800_0023);
    /// 0x0800_0024: no data available.
    pub const NO_DATA_AVAILABLE: SdoAbortCode = SdoAbortCode(0x0800_0024);

    /// Return the abort code `raw`.
    #[inline]
    #[must_use]
    pub const fn new(raw: u32) -> Self {
        SdoAbortCode(raw)
    }

    /// Return the abort code as a number.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u32 {
        self.0
    }

    /// Return whether CiA 301 Table 22 names this code.
    #[must_use]
    pub const fn is_known(self) -> bool {
        self.known_description().is_some()
    }

    /// Return the code's description from CiA 301 Table 22, or
    /// `"Unknown SDO abort code"`.
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self.known_description() {
            Some(text) => text,
            None => "Unknown SDO abort code",
        }
    }

    const fn known_description(self) -> Option<&'static str> {
        Some(match self.0 {
            0x0503_0000 => "Toggle bit not alternated",
            0x0504_0000 => "SDO protocol timed out",
            0x0504_0001 => "Client/server command specifier not valid or unknown",
            0x0504_0002 => "Invalid block size (block mode only)",
            0x0504_0003 => "Invalid sequence number (block mode only)",
            0x0504_0004 => "CRC error (block mode only)",
            0x0504_0005 => "Out of memory",
            0x0601_0000 => "Unsupported access to an object",
            0x0601_0001 => "Attempt to read a write only object",
            0x0601_0002 => "Attempt to write a read only object",
            0x0602_0000 => "Object does not exist in the object dictionary",
            0x0604_0041 => "Object cannot be mapped to the PDO",
            0x0604_0042 => {
                "The number and length of the objects to be mapped would exceed PDO length"
            }
            0x0604_0043 => "General parameter incompatibility reason",
            0x0604_0047 => "General internal incompatibility in the device",
            0x0606_0000 => "Access failed due to a hardware error",
            0x0607_0010 => "Data type does not match, length of service parameter does not match",
            0x0607_0012 => "Data type does not match, length of service parameter too high",
            0x0607_0013 => "Data type does not match, length of service parameter too low",
            0x0609_0011 => "Sub-index does not exist",
            0x0609_0030 => "Invalid value for parameter (download only)",
            0x0609_0031 => "Value of parameter written too high (download only)",
            0x0609_0032 => "Value of parameter written too low (download only)",
            0x0609_0036 => "Maximum value is less than minimum value",
            0x060A_0023 => "Resource not available: SDO connection",
            0x0800_0000 => "General error",
            0x0800_0020 => "Data cannot be transferred or stored to the application",
            0x0800_0021 => {
                "Data cannot be transferred or stored to the application because of local control"
            }
            0x0800_0022 => {
                "Data cannot be transferred or stored to the application because of the present device state"
            }
            0x0800_0023 => {
                "Object dictionary dynamic generation fails or no object dictionary is present"
            }
            0x0800_0024 => "No data available",
            _ => return None,
        })
    }
}

impl From<u32> for SdoAbortCode {
    fn from(raw: u32) -> Self {
        SdoAbortCode(raw)
    }
}

impl From<SdoAbortCode> for u32 {
    fn from(code: SdoAbortCode) -> u32 {
        code.0
    }
}

impl fmt::Display for SdoAbortCode {
    /// Format the code as `0x06090030: Invalid value for parameter
    /// (download only)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#010x}: {}", self.0, self.description())
    }
}

impl core::error::Error for SdoAbortCode {}

#[cfg(test)]
mod tests {
    use super::*;

    /// CiA 301 Table 22, written out: (constant, code).
    const TABLE: [(SdoAbortCode, u32); 31] = [
        (SdoAbortCode::TOGGLE_BIT_NOT_ALTERNATED, 0x0503_0000),
        (SdoAbortCode::TIMED_OUT, 0x0504_0000),
        (SdoAbortCode::INVALID_COMMAND_SPECIFIER, 0x0504_0001),
        (SdoAbortCode::INVALID_BLOCK_SIZE, 0x0504_0002),
        (SdoAbortCode::INVALID_SEQUENCE_NUMBER, 0x0504_0003),
        (SdoAbortCode::CRC_ERROR, 0x0504_0004),
        (SdoAbortCode::OUT_OF_MEMORY, 0x0504_0005),
        (SdoAbortCode::UNSUPPORTED_ACCESS, 0x0601_0000),
        (SdoAbortCode::READ_OF_WRITE_ONLY, 0x0601_0001),
        (SdoAbortCode::WRITE_OF_READ_ONLY, 0x0601_0002),
        (SdoAbortCode::OBJECT_DOES_NOT_EXIST, 0x0602_0000),
        (SdoAbortCode::NOT_MAPPABLE, 0x0604_0041),
        (SdoAbortCode::PDO_LENGTH_EXCEEDED, 0x0604_0042),
        (SdoAbortCode::PARAMETER_INCOMPATIBILITY, 0x0604_0043),
        (SdoAbortCode::INTERNAL_INCOMPATIBILITY, 0x0604_0047),
        (SdoAbortCode::HARDWARE_ERROR, 0x0606_0000),
        (SdoAbortCode::LENGTH_MISMATCH, 0x0607_0010),
        (SdoAbortCode::LENGTH_TOO_HIGH, 0x0607_0012),
        (SdoAbortCode::LENGTH_TOO_LOW, 0x0607_0013),
        (SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST, 0x0609_0011),
        (SdoAbortCode::INVALID_VALUE, 0x0609_0030),
        (SdoAbortCode::VALUE_TOO_HIGH, 0x0609_0031),
        (SdoAbortCode::VALUE_TOO_LOW, 0x0609_0032),
        (SdoAbortCode::MAX_LESS_THAN_MIN, 0x0609_0036),
        (SdoAbortCode::RESOURCE_NOT_AVAILABLE, 0x060A_0023),
        (SdoAbortCode::GENERAL_ERROR, 0x0800_0000),
        (SdoAbortCode::CANNOT_TRANSFER, 0x0800_0020),
        (SdoAbortCode::CANNOT_TRANSFER_LOCAL_CONTROL, 0x0800_0021),
        (SdoAbortCode::CANNOT_TRANSFER_DEVICE_STATE, 0x0800_0022),
        (SdoAbortCode::NO_OBJECT_DICTIONARY, 0x0800_0023),
        (SdoAbortCode::NO_DATA_AVAILABLE, 0x0800_0024),
    ];

    #[test]
    fn every_named_code_has_its_value_and_a_description() {
        for (code, raw) in TABLE {
            assert_eq!(code.get(), raw);
            assert_eq!(SdoAbortCode::new(raw), code);
            assert!(code.is_known(), "{raw:#010x}");
            assert_ne!(code.description(), "Unknown SDO abort code");
        }
    }

    #[test]
    fn the_codes_error_history_uses() {
        let table = [
            (
                0x0609_0030,
                "0x06090030: Invalid value for parameter (download only)",
            ),
            (0x0800_0024, "0x08000024: No data available"),
            (
                0x0601_0002,
                "0x06010002: Attempt to write a read only object",
            ),
            (0x0609_0011, "0x06090011: Sub-index does not exist"),
        ];
        for (raw, text) in table {
            assert_eq!(SdoAbortCode::new(raw).to_string(), text);
        }
    }

    #[test]
    fn unknown_codes_are_reported_as_unknown() {
        for raw in [0, 0x0503_0001, 0x0609_0033, 0xFFFF_FFFF] {
            let code = SdoAbortCode::from(raw);
            assert!(!code.is_known());
            assert_eq!(u32::from(code), raw);
            assert_eq!(
                code.to_string(),
                format!("{raw:#010x}: Unknown SDO abort code")
            );
        }
    }
}
