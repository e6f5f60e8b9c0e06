//! Process data objects: the communication and mapping parameters of a PDO
//! and its payload read as signals (CiA 301 PDO protocol, §7.5.2.35–§7.5.2.38;
//! docs/canopen.md#pdo-mappings, docs/canopen.md#signals).
//!
//! A PDO's bytes mean nothing without its mapping. [`PdoMapping`] holds the
//! mapping parameter (objects 1600h–17FFh for RPDOs, 1A00h–1BFFh for TPDOs):
//! up to 64 [`MappingEntry`]s, each `index << 16 | sub-index << 8 | length
//! in bits`. [`PdoMapping::unpack`] reads a payload entry by entry,
//! little-endian and bit by bit in mapping order (an entry may straddle byte
//! boundaries), into [`Signal`]s whose [`Value`](crate::canopen::Value)
//! follows the entry's CiA 301 [`DataType`]; [`PdoMapping::pack`] writes
//! values back. Nothing allocates.
//!
//! The communication parameter (1400h–15FFh, 1800h–19FFh) is
//! [`PdoCommunication`]: the [`PdoCobId`] of sub-index 1, the
//! [`TransmissionType`] of sub-index 2, the [`InhibitTime`] of sub-index 3
//! and the [`EventTimer`] of sub-index 5.
//!
//! The module's files: `communication.rs` (the communication parameter),
//! `mapping.rs` (entries, the mapping, unpacking and packing), `layout.rs`
//! ([`PdoLayout`], a mapping worked out once for many frames), `bits.rs`
//! (an entry's bits in a payload); here, the error of an entry,
//! [`PdoEntryError`]. The data types and values live in
//! [`data_type`](super::data_type), as the EDS reader and the object table
//! use them too.
//!
//! ```
//! use motionwire_codec::canopen::{DataType, MappingEntry, PdoMapping, Value};
//!
//! // TPDO: statusword 6041h (16 bits), modes of operation display 6061h
//! // (8 bits), position actual value 6064h (32 bits).
//! let mut mapping = PdoMapping::new();
//! for raw in [0x6041_0010, 0x6061_0008, 0x6064_0020] {
//!     mapping.push(MappingEntry::from_u32(raw))?;
//! }
//! assert_eq!(mapping.bit_len(), 56);
//!
//! // The caller knows the types (from an EDS, or the CiA 402 profile).
//! let types = |entry: MappingEntry| match entry.index() {
//!     0x6041 => Some(DataType::Unsigned16),
//!     0x6061 => Some(DataType::Integer8),
//!     0x6064 => Some(DataType::Integer32),
//!     _ => None,
//! };
//! let payload = [0x37, 0x02, 0xFF, 0x00, 0xF0, 0xFF, 0xFF];
//! let values: Vec<_> = mapping
//!     .unpack_with(&payload, types)
//!     .map(|signal| signal.map(|s| (s.entry.index(), s.value)))
//!     .collect::<Result<_, _>>()?;
//! assert_eq!(
//!     values,
//!     [
//!         (0x6041, Value::Unsigned(0x0237)),
//!         (0x6061, Value::Signed(-1)),
//!         (0x6064, Value::Signed(-4096)),
//!     ]
//! );
//!
//! // Packing the values back gives the payload.
//! let mut buf = [0u8; 8];
//! let len = mapping.pack_with(types, values.iter().map(|&(_, v)| v), &mut buf)?;
//! assert_eq!(&buf[..len], payload);
//!
//! // A payload shorter than the mapping gives the signals that fit and an
//! // error for the rest.
//! let mut signals = mapping.unpack_with(&payload[..4], types);
//! assert!(signals.next().unwrap().is_ok());
//! assert!(signals.next().unwrap().is_ok());
//! assert_eq!(
//!     signals.next().unwrap().unwrap_err().to_string(),
//!     "PDO entry 6064sub0 (32 bits) at bit 24: expected a payload of at least 7 bytes, found 4"
//! );
//! assert!(signals.next().is_none());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use core::fmt;

use crate::canopen::data_type::{DataType, ValueKind};
use crate::{LenError, RangeError};

mod bits;
mod communication;
mod layout;
mod mapping;

pub use communication::{
    EventTimer, InhibitTime, PdoCobId, PdoCommunication, TransmissionKind, TransmissionType,
};
pub use layout::{LayoutSignals, PdoLayout};
pub use mapping::{
    ByLength, MappingEntry, PdoMapping, Signal, Signals, TypeLookup, CLASSIC_PDO_BITS,
    MAX_MAPPING_ENTRIES, MAX_PDO_BITS,
};

/// A PDO mapping entry that cannot be read from, or written into, a payload
/// (docs/canopen.md#signals): the entry, its first bit and why. The crate's
/// [`Error`](crate::Error) carries it as [`Error::PdoEntry`](crate::Error::PdoEntry); its message reads e.g. `PDO entry
/// 6064sub0 (32 bits) at bit 24: expected a payload of at least 7 bytes,
/// found 4`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("PDO entry {entry} at bit {offset}: {reason}")]
pub struct PdoEntryError {
    /// The mapping entry.
    pub entry: MappingEntry,
    /// Its first bit in the payload.
    pub offset: u16,
    /// What is wrong with it.
    pub reason: PdoEntryReason,
}

/// Why [`PdoMapping::pack`] and [`PdoMapping::pack_with`] cannot write
/// values into a payload (docs/canopen.md#signals): the buffer is shorter
/// than the mapping, an entry cannot take its value, or values are left
/// over. The message is the inner error's, e.g. `PDO payload: buffer of 2
/// bytes where 4 are needed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
pub enum PdoPackError {
    /// The buffer is shorter than [`PdoMapping::byte_len`]
    /// ([`What::PdoPayload`](crate::What::PdoPayload)).
    #[error(transparent)]
    Length(#[from] LenError),
    /// An entry cannot take its value: of the wrong kind, wider than the
    /// entry, or missing.
    #[error(transparent)]
    PdoEntry(#[from] PdoEntryError),
    /// More values than entries that are not dummies
    /// ([`What::PdoValues`](crate::What::PdoValues)).
    #[error(transparent)]
    OutOfRange(#[from] RangeError),
}

impl From<PdoPackError> for crate::Error {
    fn from(error: PdoPackError) -> Self {
        match error {
            PdoPackError::Length(e) => e.into(),
            PdoPackError::PdoEntry(e) => e.into(),
            PdoPackError::OutOfRange(e) => e.into(),
        }
    }
}

/// Why a PDO mapping entry cannot be read or written (docs/canopen.md#signals):
/// the reason a [`PdoEntryError`] gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PdoEntryReason {
    /// The payload ends before the entry does.
    Truncated {
        /// The bytes the mapping needs up to the end of the entry.
        needed: usize,
        /// The bytes the payload has.
        found: usize,
    },
    /// The entry's length is one its data type cannot be read from
    /// (REAL32 needs 32 bits, REAL64 64, the integers and BOOLEAN 1 to 64).
    BadLength {
        /// The entry's data type.
        data_type: DataType,
        /// The entry's length in bits.
        bits: u8,
    },
    /// Packing: the value is of another kind than the entry reads as.
    WrongKind {
        /// The kind the entry reads as.
        expected: ValueKind,
        /// The kind of the value given.
        found: ValueKind,
    },
    /// Packing: the number does not fit in the entry's bits.
    ValueTooWide {
        /// The entry's length in bits.
        bits: u8,
    },
    /// Packing: the octets are not as long as the entry.
    OctetsLength {
        /// The entry's length in bits.
        expected: u8,
        /// The octets' length in bits.
        found: u8,
    },
    /// Packing: the values ended before this entry.
    MissingValue,
}

impl fmt::Display for PdoEntryReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PdoEntryReason::Truncated { needed, found } => write!(
                f,
                "expected a payload of at least {needed} bytes, found {found}"
            ),
            PdoEntryReason::BadLength { data_type, bits } => {
                let expected = match data_type {
                    DataType::Real32 => "32 bits",
                    DataType::Real64 => "64 bits",
                    _ => "1 to 64 bits",
                };
                write!(f, "expected {expected} for {data_type}, found {bits}")
            }
            PdoEntryReason::WrongKind { expected, found } => {
                write!(f, "expected a {expected} value, found a {found} value")
            }
            PdoEntryReason::ValueTooWide { bits } => {
                write!(
                    f,
                    "expected a value that fits in {bits} bits, found a wider one"
                )
            }
            PdoEntryReason::OctetsLength { expected, found } => {
                write!(f, "expected {expected} bits of octets, found {found}")
            }
            PdoEntryReason::MissingValue => f.write_str("expected a value, found none left"),
        }
    }
}

#[cfg(feature = "serde")]
mod serde_impls;
