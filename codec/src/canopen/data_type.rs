//! The CiA 301 basic data types and the values they hold (CiA 301
//! Table 44, "Object dictionary data types"; docs/canopen.md#signals).
//!
//! [`DataType`] is a type as the object dictionary names it (by index,
//! 0001h BOOLEAN … 001Bh UNSIGNED64); [`Value`] is a value of one, as a
//! PDO's signals carry it, with its [`ValueKind`]; [`Octets`] holds the
//! bits of a string, a DOMAIN or an entry longer than 64 bits inline. The
//! PDO codecs ([`pdo`](super::pdo)), the EDS reader and the object table
//! ([`objects`](super::objects)) all speak these types.
//!
//! ```
//! use motionwire_codec::canopen::{DataType, Value, ValueKind};
//!
//! let data_type = DataType::from_index(0x0004).unwrap();
//! assert_eq!((data_type, data_type.bits()), (DataType::Integer32, Some(32)));
//! assert!(data_type.is_signed());
//! assert_eq!(Value::Signed(-4096).kind(), ValueKind::Signed);
//! assert_eq!(Value::Signed(-4096).to_string(), "-4096");
//! ```

use core::fmt;

use crate::error::What;
use crate::{Result, ValueError};

/// A CiA 301 basic data type, named by its index in the object dictionary
/// (CiA 301 Table 44, "Object dictionary data types"; docs/canopen.md#signals).
///
/// Indices 0001h–0007h double as the dummy entries of a PDO mapping
/// ([`MappingEntry::is_dummy`](super::MappingEntry::is_dummy)).
///
/// ```
/// use motionwire_codec::canopen::DataType;
///
/// assert_eq!(DataType::from_index(0x0010), Some(DataType::Integer24));
/// assert_eq!(DataType::Integer24.bits(), Some(24));
/// assert_eq!(DataType::Integer24.name(), "INTEGER24");
/// assert_eq!(DataType::VisibleString.bits(), None);
/// assert_eq!(DataType::from_index(0x000E), None); // reserved
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u16)]
pub enum DataType {
    /// 0001h BOOLEAN.
    Boolean = 0x0001,
    /// 0002h INTEGER8.
    Integer8 = 0x0002,
    /// 0003h INTEGER16.
    Integer16 = 0x0003,
    /// 0004h INTEGER32.
    Integer32 = 0x0004,
    /// 0005h UNSIGNED8.
    Unsigned8 = 0x0005,
    /// 0006h UNSIGNED16.
    Unsigned16 = 0x0006,
    /// 0007h UNSIGNED32.
    Unsigned32 = 0x0007,
    /// 0008h REAL32 (IEEE 754 single precision).
    Real32 = 0x0008,
    /// 0009h VISIBLE_STRING.
    VisibleString = 0x0009,
    /// 000Ah OCTET_STRING.
    OctetString = 0x000A,
    /// 000Bh UNICODE_STRING.
    UnicodeString = 0x000B,
    /// 000Ch TIME_OF_DAY (48 bits: milliseconds after midnight, days since
    /// 1984-01-01).
    TimeOfDay = 0x000C,
    /// 000Dh TIME_DIFFERENCE (48 bits, as TIME_OF_DAY).
    TimeDifference = 0x000D,
    /// 000Fh DOMAIN.
    Domain = 0x000F,
    /// 0010h INTEGER24.
    Integer24 = 0x0010,
    /// 0011h REAL64 (IEEE 754 double precision).
    Real64 = 0x0011,
    /// 0012h INTEGER40.
    Integer40 = 0x0012,
    /// 0013h INTEGER48.
    Integer48 = 0x0013,
    /// 0014h INTEGER56.
    Integer56 = 0x0014,
    /// 0015h INTEGER64.
    Integer64 = 0x0015,
    /// 0016h UNSIGNED24.
    Unsigned24 = 0x0016,
    /// 0018h UNSIGNED40.
    Unsigned40 = 0x0018,
    /// 0019h UNSIGNED48.
    Unsigned48 = 0x0019,
    /// 001Ah UNSIGNED56.
    Unsigned56 = 0x001A,
    /// 001Bh UNSIGNED64.
    Unsigned64 = 0x001B,
}

impl DataType {
    /// Every basic data type, in the order of their indices.
    pub const ALL: [DataType; 25] = [
        DataType::Boolean,
        DataType::Integer8,
        DataType::Integer16,
        DataType::Integer32,
        DataType::Unsigned8,
        DataType::Unsigned16,
        DataType::Unsigned32,
        DataType::Real32,
        DataType::VisibleString,
        DataType::OctetString,
        DataType::UnicodeString,
        DataType::TimeOfDay,
        DataType::TimeDifference,
        DataType::Domain,
        DataType::Integer24,
        DataType::Real64,
        DataType::Integer40,
        DataType::Integer48,
        DataType::Integer56,
        DataType::Integer64,
        DataType::Unsigned24,
        DataType::Unsigned40,
        DataType::Unsigned48,
        DataType::Unsigned56,
        DataType::Unsigned64,
    ];

    /// Return the data type at object-dictionary index `index`, or `None`
    /// for a reserved index or one that is no basic type (CiA 301 Table 44).
    #[must_use]
    pub const fn from_index(index: u16) -> Option<Self> {
        Some(match index {
            0x0001 => DataType::Boolean,
            0x0002 => DataType::Integer8,
            0x0003 => DataType::Integer16,
            0x0004 => DataType::Integer32,
            0x0005 => DataType::Unsigned8,
            0x0006 => DataType::Unsigned16,
            0x0007 => DataType::Unsigned32,
            0x0008 => DataType::Real32,
            0x0009 => DataType::VisibleString,
            0x000A => DataType::OctetString,
            0x000B => DataType::UnicodeString,
            0x000C => DataType::TimeOfDay,
            0x000D => DataType::TimeDifference,
            0x000F => DataType::Domain,
            0x0010 => DataType::Integer24,
            0x0011 => DataType::Real64,
            0x0012 => DataType::Integer40,
            0x0013 => DataType::Integer48,
            0x0014 => DataType::Integer56,
            0x0015 => DataType::Integer64,
            0x0016 => DataType::Unsigned24,
            0x0018 => DataType::Unsigned40,
            0x0019 => DataType::Unsigned48,
            0x001A => DataType::Unsigned56,
            0x001B => DataType::Unsigned64,
            _ => return None,
        })
    }

    /// Return the data type at `index`, or a [`ValueError`] for
    /// an index that is no basic type.
    pub const fn try_from_index(index: u16) -> Result<Self, ValueError> {
        match Self::from_index(index) {
            Some(data_type) => Ok(data_type),
            None => Err(ValueError {
                what: What::DataType,
                found: index as u32,
                expected: "0x0001..=0x000D, 0x000F..=0x0016, 0x0018..=0x001B",
            }),
        }
    }

    /// Return the type's object-dictionary index.
    #[must_use]
    pub const fn index(self) -> u16 {
        self as u16
    }

    /// Return the type's width in bits, or `None` for the types of variable
    /// length (strings, DOMAIN). BOOLEAN is 1 bit as a PDO maps it.
    #[must_use]
    pub const fn bits(self) -> Option<u8> {
        Some(match self {
            DataType::Boolean => 1,
            DataType::Integer8 | DataType::Unsigned8 => 8,
            DataType::Integer16 | DataType::Unsigned16 => 16,
            DataType::Integer24 | DataType::Unsigned24 => 24,
            DataType::Integer32 | DataType::Unsigned32 | DataType::Real32 => 32,
            DataType::Integer40 | DataType::Unsigned40 => 40,
            DataType::Integer48
            | DataType::Unsigned48
            | DataType::TimeOfDay
            | DataType::TimeDifference => 48,
            DataType::Integer56 | DataType::Unsigned56 => 56,
            DataType::Integer64 | DataType::Unsigned64 | DataType::Real64 => 64,
            DataType::VisibleString
            | DataType::OctetString
            | DataType::UnicodeString
            | DataType::Domain => return None,
        })
    }

    /// Return the type's name as CiA 301 writes it, e.g. `"UNSIGNED16"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            DataType::Boolean => "BOOLEAN",
            DataType::Integer8 => "INTEGER8",
            DataType::Integer16 => "INTEGER16",
            DataType::Integer32 => "INTEGER32",
            DataType::Unsigned8 => "UNSIGNED8",
            DataType::Unsigned16 => "UNSIGNED16",
            DataType::Unsigned32 => "UNSIGNED32",
            DataType::Real32 => "REAL32",
            DataType::VisibleString => "VISIBLE_STRING",
            DataType::OctetString => "OCTET_STRING",
            DataType::UnicodeString => "UNICODE_STRING",
            DataType::TimeOfDay => "TIME_OF_DAY",
            DataType::TimeDifference => "TIME_DIFFERENCE",
            DataType::Domain => "DOMAIN",
            DataType::Integer24 => "INTEGER24",
            DataType::Real64 => "REAL64",
            DataType::Integer40 => "INTEGER40",
            DataType::Integer48 => "INTEGER48",
            DataType::Integer56 => "INTEGER56",
            DataType::Integer64 => "INTEGER64",
            DataType::Unsigned24 => "UNSIGNED24",
            DataType::Unsigned40 => "UNSIGNED40",
            DataType::Unsigned48 => "UNSIGNED48",
            DataType::Unsigned56 => "UNSIGNED56",
            DataType::Unsigned64 => "UNSIGNED64",
        }
    }

    /// Return whether the type is one of the signed integers INTEGER8…64.
    #[must_use]
    pub const fn is_signed(self) -> bool {
        matches!(
            self,
            DataType::Integer8
                | DataType::Integer16
                | DataType::Integer24
                | DataType::Integer32
                | DataType::Integer40
                | DataType::Integer48
                | DataType::Integer56
                | DataType::Integer64
        )
    }
}

impl TryFrom<u16> for DataType {
    type Error = ValueError;

    fn try_from(index: u16) -> Result<Self, ValueError> {
        Self::try_from_index(index)
    }
}

impl From<DataType> for u16 {
    fn from(data_type: DataType) -> u16 {
        data_type.index()
    }
}

impl fmt::Display for DataType {
    /// Format the type as its [`DataType::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The most bytes an [`Octets`] value holds: 255 bits, the longest entry.
pub const MAX_OCTETS: usize = 32;

/// The bits of a mapping entry that is no number: a string, a DOMAIN, or an
/// untyped entry longer than 64 bits (at most 255 bits, held inline). With
/// the `serde` feature: `{"bits": n, "bytes": [...]}`, checked as
/// [`Octets::new`] checks when read back.
///
/// ```
/// use motionwire_codec::canopen::Octets;
///
/// let text = Octets::new(b"AKD", 24).unwrap();
/// assert_eq!(text.as_bytes(), b"AKD");
/// assert_eq!(text.to_string(), "414b44");
/// assert!(Octets::new(b"AKD", 16).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Octets {
    pub(super) bytes: [u8; MAX_OCTETS],
    pub(super) bits: u8,
}

impl Octets {
    /// Return the value of `bits` bits held by `bytes` (little-endian, the
    /// first bit in bit 0 of byte 0), or `None` when `bytes` is not exactly
    /// the `bits.div_ceil(8)` bytes they need. Bits of the last byte above
    /// `bits` are cleared.
    #[must_use]
    pub fn new(bytes: &[u8], bits: u8) -> Option<Self> {
        let len = usize::from(bits).div_ceil(8);
        if bytes.len() != len {
            return None;
        }
        let mut octets = Octets {
            bytes: [0; MAX_OCTETS],
            bits,
        };
        octets.bytes[..len].copy_from_slice(bytes);
        let rest = bits % 8;
        if rest != 0 {
            octets.bytes[len - 1] &= (1u8 << rest) - 1;
        }
        Some(octets)
    }

    /// Return the bytes, `bits().div_ceil(8)` of them.
    #[must_use]
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..usize::from(self.bits).div_ceil(8)]
    }

    /// Return the length in bits.
    #[must_use]
    pub const fn bits(&self) -> u8 {
        self.bits
    }
}

impl fmt::Display for Octets {
    /// Format the bytes as lowercase hex without separators.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for byte in self.as_bytes() {
            write!(f, "{byte:02x}")?;
        }
        Ok(())
    }
}

/// The value of one signal of a PDO (docs/canopen.md#signals).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Value {
    /// BOOLEAN, or an untyped 1-bit entry.
    Bool(bool),
    /// INTEGER8…INTEGER64, sign-extended from the entry's length.
    Signed(i64),
    /// UNSIGNED8…UNSIGNED64, TIME_OF_DAY / TIME_DIFFERENCE (raw 48 bits),
    /// or an untyped entry of 2 to 64 bits.
    Unsigned(u64),
    /// REAL32.
    Real32(f32),
    /// REAL64.
    Real64(f64),
    /// A string, DOMAIN or untyped entry longer than 64 bits, as bytes.
    Octets(Octets),
}

impl Value {
    /// Return the value's kind.
    #[must_use]
    pub const fn kind(&self) -> ValueKind {
        match self {
            Value::Bool(_) => ValueKind::Bool,
            Value::Signed(_) => ValueKind::Signed,
            Value::Unsigned(_) => ValueKind::Unsigned,
            Value::Real32(_) => ValueKind::Real32,
            Value::Real64(_) => ValueKind::Real64,
            Value::Octets(_) => ValueKind::Octets,
        }
    }
}

impl fmt::Display for Value {
    /// Format the value as a number (`true`/`false` for a boolean), an
    /// [`Octets`] value as lowercase hex.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Bool(b) => write!(f, "{b}"),
            Value::Signed(v) => write!(f, "{v}"),
            Value::Unsigned(v) => write!(f, "{v}"),
            Value::Real32(v) => write!(f, "{v}"),
            Value::Real64(v) => write!(f, "{v}"),
            Value::Octets(v) => write!(f, "{v}"),
        }
    }
}

/// The kind of a [`Value`], and the kind an entry reads as.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ValueKind {
    /// [`Value::Bool`].
    Bool,
    /// [`Value::Signed`].
    Signed,
    /// [`Value::Unsigned`].
    Unsigned,
    /// [`Value::Real32`].
    Real32,
    /// [`Value::Real64`].
    Real64,
    /// [`Value::Octets`].
    Octets,
}

impl ValueKind {
    /// Return the kind's name, e.g. `"signed"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            ValueKind::Bool => "boolean",
            ValueKind::Signed => "signed",
            ValueKind::Unsigned => "unsigned",
            ValueKind::Real32 => "REAL32",
            ValueKind::Real64 => "REAL64",
            ValueKind::Octets => "octets",
        }
    }
}

impl fmt::Display for ValueKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(feature = "serde")]
mod serde_impls;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_types_follow_cia301_table_44() {
        // (index, name, bits) as CiA 301 Table 44 lists them.
        let table: &[(u16, &str, Option<u8>)] = &[
            (0x0001, "BOOLEAN", Some(1)),
            (0x0002, "INTEGER8", Some(8)),
            (0x0003, "INTEGER16", Some(16)),
            (0x0004, "INTEGER32", Some(32)),
            (0x0005, "UNSIGNED8", Some(8)),
            (0x0006, "UNSIGNED16", Some(16)),
            (0x0007, "UNSIGNED32", Some(32)),
            (0x0008, "REAL32", Some(32)),
            (0x0009, "VISIBLE_STRING", None),
            (0x000A, "OCTET_STRING", None),
            (0x000B, "UNICODE_STRING", None),
            (0x000C, "TIME_OF_DAY", Some(48)),
            (0x000D, "TIME_DIFFERENCE", Some(48)),
            (0x000F, "DOMAIN", None),
            (0x0010, "INTEGER24", Some(24)),
            (0x0011, "REAL64", Some(64)),
            (0x0012, "INTEGER40", Some(40)),
            (0x0013, "INTEGER48", Some(48)),
            (0x0014, "INTEGER56", Some(56)),
            (0x0015, "INTEGER64", Some(64)),
            (0x0016, "UNSIGNED24", Some(24)),
            (0x0018, "UNSIGNED40", Some(40)),
            (0x0019, "UNSIGNED48", Some(48)),
            (0x001A, "UNSIGNED56", Some(56)),
            (0x001B, "UNSIGNED64", Some(64)),
        ];
        assert_eq!(table.len(), DataType::ALL.len());
        for (&(index, name, bits), &data_type) in table.iter().zip(DataType::ALL.iter()) {
            assert_eq!(DataType::from_index(index), Some(data_type), "{index:#06x}");
            assert_eq!(data_type.index(), index);
            assert_eq!(data_type.name(), name);
            assert_eq!(data_type.to_string(), name);
            assert_eq!(data_type.bits(), bits, "{name}");
            assert_eq!(data_type.is_signed(), name.starts_with("INTEGER"), "{name}");
        }
        for index in [0x0000, 0x000E, 0x0017, 0x001C, 0x0020, 0xFFFF] {
            assert_eq!(DataType::from_index(index), None);
            assert_eq!(
                DataType::try_from(index),
                Err(ValueError {
                    what: What::DataType,
                    found: u32::from(index),
                    expected: "0x0001..=0x000D, 0x000F..=0x0016, 0x0018..=0x001B",
                })
            );
        }
    }
}
