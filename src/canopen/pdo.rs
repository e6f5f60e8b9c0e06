//! Process data objects: the communication and mapping parameters of a PDO
//! and its payload read as signals (CiA 301 PDO protocol, §7.5.2.35–§7.5.2.38;
//! SPEC §8.1, §8.2).
//!
//! A PDO's bytes mean nothing without its mapping. [`PdoMapping`] holds the
//! mapping parameter (objects 1600h–17FFh for RPDOs, 1A00h–1BFFh for TPDOs):
//! up to 64 [`MappingEntry`]s, each `index << 16 | sub-index << 8 | length
//! in bits`. [`PdoMapping::unpack`] reads a payload entry by entry,
//! little-endian and bit by bit in mapping order (an entry may straddle byte
//! boundaries), into [`Signal`]s whose [`Value`] follows the entry's CiA 301
//! [`DataType`]; [`PdoMapping::pack`] writes values back. Nothing allocates.
//!
//! The communication parameter (1400h–15FFh, 1800h–19FFh) is
//! [`PdoCommunication`]: the [`PdoCobId`] of sub-index 1, the
//! [`TransmissionType`] of sub-index 2, the [`InhibitTime`] of sub-index 3
//! and the [`EventTimer`] of sub-index 5.
//!
//! ```
//! use motionwire::canopen::{DataType, MappingEntry, PdoMapping, Value};
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
//! # Ok::<(), motionwire::Error>(())
//! ```

use core::fmt;
use core::time::Duration;

use crate::can::CanId;
use crate::error::What;
use crate::{Error, Result};

/// A PDO mapping entry that cannot be read from, or written into, a payload
/// (SPEC §8.2): the entry, its first bit and why. The crate's [`Error`]
/// carries it as [`Error::PdoEntry`]; its message reads e.g. `PDO entry
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

/// Why a PDO mapping entry cannot be read or written (SPEC §8.2): the
/// reason a [`PdoEntryError`] gives.
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

/// A CiA 301 basic data type, named by its index in the object dictionary
/// (CiA 301 Table 44, "Object dictionary data types"; SPEC §8.2).
///
/// Indices 0001h–0007h double as the dummy entries of a PDO mapping
/// ([`MappingEntry::is_dummy`]).
///
/// ```
/// use motionwire::canopen::DataType;
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

    /// Return the data type at `index`, or an [`Error::InvalidValue`] for
    /// an index that is no basic type.
    pub const fn try_from_index(index: u16) -> Result<Self> {
        match Self::from_index(index) {
            Some(data_type) => Ok(data_type),
            None => Err(Error::InvalidValue {
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
    type Error = Error;

    fn try_from(index: u16) -> Result<Self> {
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

/// The COB-ID of a PDO, sub-index 1 of its communication parameter
/// (CiA 301 §7.5.2.35, §7.5.2.37, "COB-ID used by PDO"; SPEC §8.1): bit 31 set = the PDO is not valid, bit 30
/// set = no RTR is allowed on it, bit 29 set = a 29-bit identifier. Every
/// bit of the 32 survives a round trip.
///
/// ```
/// use motionwire::canopen::PdoCobId;
///
/// let cob_id = PdoCobId::from_u32(0x4000_0185);
/// assert!(cob_id.is_valid());
/// assert!(!cob_id.rtr_allowed());
/// assert!(!cob_id.is_extended());
/// assert_eq!(cob_id.can_id().map(|id| id.raw()), Some(0x185));
/// assert!(!PdoCobId::from_u32(0x8000_0185).is_valid());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PdoCobId(u32);

impl PdoCobId {
    /// Bit 31: the PDO does not exist / is not valid.
    pub const NOT_VALID: u32 = 1 << 31;
    /// Bit 30: no RTR is allowed on this PDO.
    pub const NO_RTR: u32 = 1 << 30;
    /// Bit 29: the identifier has 29 bits (CAN extended frame).
    pub const EXTENDED: u32 = 1 << 29;

    /// Return the COB-ID held by the object value `raw`.
    #[must_use]
    pub const fn from_u32(raw: u32) -> Self {
        PdoCobId(raw)
    }

    /// Return the COB-ID of a valid PDO on `id` with RTR `rtr_allowed`.
    #[must_use]
    pub const fn new(id: CanId, rtr_allowed: bool) -> Self {
        let mut raw = id.raw();
        if id.is_extended() {
            raw |= Self::EXTENDED;
        }
        if !rtr_allowed {
            raw |= Self::NO_RTR;
        }
        PdoCobId(raw)
    }

    /// Return the object value, every bit as it was.
    #[must_use]
    pub const fn to_u32(self) -> u32 {
        self.0
    }

    /// Return whether bit 31 is clear: the PDO exists and is valid.
    #[must_use]
    pub const fn is_valid(self) -> bool {
        self.0 & Self::NOT_VALID == 0
    }

    /// Return whether bit 30 is clear: RTR is allowed on the PDO.
    #[must_use]
    pub const fn rtr_allowed(self) -> bool {
        self.0 & Self::NO_RTR == 0
    }

    /// Return whether bit 29 is set: the identifier has 29 bits.
    #[must_use]
    pub const fn is_extended(self) -> bool {
        self.0 & Self::EXTENDED != 0
    }

    /// Return the identifier: bits 0–10, or bits 0–28 when bit 29 is set.
    /// With bit 29 clear, bits 11–28 should be 0 (CiA 301); they are ignored
    /// here and kept by [`PdoCobId::to_u32`]. `None` never occurs for the
    /// masked bits but keeps the signature honest about [`CanId`]'s checks.
    #[must_use]
    pub const fn can_id(self) -> Option<CanId> {
        if self.is_extended() {
            CanId::extended(self.0 & 0x1FFF_FFFF)
        } else {
            CanId::standard(self.0 & 0x7FF)
        }
    }
}

impl From<u32> for PdoCobId {
    fn from(raw: u32) -> Self {
        PdoCobId::from_u32(raw)
    }
}

impl From<PdoCobId> for u32 {
    fn from(cob_id: PdoCobId) -> u32 {
        cob_id.to_u32()
    }
}

/// What a [`TransmissionType`] says about when the PDO is sent
/// (CiA 301 §7.5.2.35, §7.5.2.37, "transmission type"; SPEC §8.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TransmissionKind {
    /// 0: synchronous, acyclic (after a SYNC, when the data changed / an
    /// event occurred).
    SynchronousAcyclic,
    /// 1–240: synchronous, cyclic, every n-th SYNC.
    SynchronousCyclic,
    /// 241–251: reserved.
    Reserved,
    /// 252: RTR only, synchronous (sampled at SYNC, sent on request).
    RtrSynchronous,
    /// 253: RTR only, event-driven (sent on request).
    RtrEventDriven,
    /// 254: event-driven, manufacturer-specific events.
    EventDrivenManufacturer,
    /// 255: event-driven, device-profile / application-profile events.
    EventDrivenProfile,
}

impl TransmissionKind {
    /// Return the kind's name in lower-case words, e.g. `"synchronous_cyclic"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            TransmissionKind::SynchronousAcyclic => "synchronous_acyclic",
            TransmissionKind::SynchronousCyclic => "synchronous_cyclic",
            TransmissionKind::Reserved => "reserved",
            TransmissionKind::RtrSynchronous => "rtr_synchronous",
            TransmissionKind::RtrEventDriven => "rtr_event_driven",
            TransmissionKind::EventDrivenManufacturer => "event_driven_manufacturer",
            TransmissionKind::EventDrivenProfile => "event_driven_profile",
        }
    }
}

impl fmt::Display for TransmissionKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The transmission type of a PDO, sub-index 2 of its communication
/// parameter (CiA 301 §7.5.2.35, §7.5.2.37; SPEC §8.1). Every byte is a transmission
/// type; [`TransmissionType::kind`] says what it means.
///
/// ```
/// use motionwire::canopen::{TransmissionKind, TransmissionType};
///
/// let every_4th_sync = TransmissionType::from_byte(4);
/// assert_eq!(every_4th_sync.kind(), TransmissionKind::SynchronousCyclic);
/// assert_eq!(every_4th_sync.sync_interval(), Some(4));
/// assert_eq!(TransmissionType::from_byte(255).kind(), TransmissionKind::EventDrivenProfile);
/// assert_eq!(TransmissionType::from_byte(241).kind(), TransmissionKind::Reserved);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TransmissionType(u8);

impl TransmissionType {
    /// 0: synchronous, acyclic.
    pub const SYNCHRONOUS_ACYCLIC: TransmissionType = TransmissionType(0);
    /// 254: event-driven, manufacturer-specific.
    pub const EVENT_DRIVEN_MANUFACTURER: TransmissionType = TransmissionType(254);
    /// 255: event-driven, device profile.
    pub const EVENT_DRIVEN_PROFILE: TransmissionType = TransmissionType(255);

    /// Return the transmission type of the object value `byte`.
    #[must_use]
    pub const fn from_byte(byte: u8) -> Self {
        TransmissionType(byte)
    }

    /// Return the object value.
    #[must_use]
    pub const fn to_byte(self) -> u8 {
        self.0
    }

    /// Return what the type means.
    #[must_use]
    pub const fn kind(self) -> TransmissionKind {
        match self.0 {
            0 => TransmissionKind::SynchronousAcyclic,
            1..=240 => TransmissionKind::SynchronousCyclic,
            241..=251 => TransmissionKind::Reserved,
            252 => TransmissionKind::RtrSynchronous,
            253 => TransmissionKind::RtrEventDriven,
            254 => TransmissionKind::EventDrivenManufacturer,
            255 => TransmissionKind::EventDrivenProfile,
        }
    }

    /// Return n for a synchronous cyclic type (sent every n-th SYNC,
    /// 1..=240), else `None`.
    #[must_use]
    pub const fn sync_interval(self) -> Option<u8> {
        match self.0 {
            1..=240 => Some(self.0),
            _ => None,
        }
    }

    /// Return whether the PDO is tied to SYNC (0–240 and 252).
    #[must_use]
    pub const fn is_synchronous(self) -> bool {
        matches!(self.0, 0..=240 | 252)
    }
}

impl From<u8> for TransmissionType {
    fn from(byte: u8) -> Self {
        TransmissionType::from_byte(byte)
    }
}

impl From<TransmissionType> for u8 {
    fn from(transmission_type: TransmissionType) -> u8 {
        transmission_type.to_byte()
    }
}

/// The inhibit time of a PDO, sub-index 3 of its communication parameter:
/// the least time between two transmissions, in multiples of 100 µs
/// (CiA 301 §7.5.2.35; SPEC §8.1).
///
/// ```
/// use core::time::Duration;
/// use motionwire::canopen::InhibitTime;
///
/// assert_eq!(InhibitTime::from_raw(25).duration(), Duration::from_micros(2_500));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct InhibitTime(u16);

impl InhibitTime {
    /// Return the inhibit time of the object value `raw` (× 100 µs).
    #[must_use]
    pub const fn from_raw(raw: u16) -> Self {
        InhibitTime(raw)
    }

    /// Return the object value, in units of 100 µs.
    #[must_use]
    pub const fn raw(self) -> u16 {
        self.0
    }

    /// Return the time.
    #[must_use]
    pub const fn duration(self) -> Duration {
        Duration::from_micros(self.0 as u64 * 100)
    }
}

/// The event timer of a PDO, sub-index 5 of its communication parameter:
/// for a TPDO the period of event-driven transmission, for an RPDO the
/// deadline after which a missing PDO is an error; in milliseconds, 0 =
/// not used (CiA 301 §7.5.2.35; SPEC §8.1).
///
/// ```
/// use core::time::Duration;
/// use motionwire::canopen::EventTimer;
///
/// assert_eq!(EventTimer::from_raw(10).duration(), Some(Duration::from_millis(10)));
/// assert_eq!(EventTimer::from_raw(0).duration(), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventTimer(u16);

impl EventTimer {
    /// Return the event timer of the object value `raw` (ms).
    #[must_use]
    pub const fn from_raw(raw: u16) -> Self {
        EventTimer(raw)
    }

    /// Return the object value in milliseconds.
    #[must_use]
    pub const fn raw(self) -> u16 {
        self.0
    }

    /// Return the period, or `None` when the value is 0 (not used).
    #[must_use]
    pub const fn duration(self) -> Option<Duration> {
        if self.0 == 0 {
            None
        } else {
            Some(Duration::from_millis(self.0 as u64))
        }
    }
}

/// The communication parameter of a PDO, objects 1400h–15FFh (RPDO) and
/// 1800h–19FFh (TPDO) (CiA 301 §7.5.2.35, §7.5.2.37; SPEC §8.1). The
/// optional sub-indices are `None` where the device or the file gives none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PdoCommunication {
    /// Sub-index 1: COB-ID.
    pub cob_id: PdoCobId,
    /// Sub-index 2: transmission type.
    pub transmission_type: Option<TransmissionType>,
    /// Sub-index 3: inhibit time.
    pub inhibit_time: Option<InhibitTime>,
    /// Sub-index 5: event timer.
    pub event_timer: Option<EventTimer>,
    /// Sub-index 6: SYNC start value (TPDO only; 0 = not used).
    pub sync_start: Option<u8>,
}

impl PdoCommunication {
    /// Return the communication parameter with COB-ID `cob_id` and no other
    /// sub-index.
    #[must_use]
    pub const fn new(cob_id: PdoCobId) -> Self {
        PdoCommunication {
            cob_id,
            transmission_type: None,
            inhibit_time: None,
            event_timer: None,
            sync_start: None,
        }
    }
}

/// One entry of a PDO mapping parameter, the `u32` object value
/// `index << 16 | sub-index << 8 | length in bits` (CiA 301 §7.5.2.36, §7.5.2.38;
/// SPEC §8.1). Every `u32` is an entry; [`PdoMapping::push`] refuses the
/// length 0.
///
/// ```
/// use motionwire::canopen::MappingEntry;
///
/// let entry = MappingEntry::from_u32(0x6041_0010);
/// assert_eq!((entry.index(), entry.sub_index(), entry.bits()), (0x6041, 0, 16));
/// assert_eq!(entry, MappingEntry::new(0x6041, 0, 16));
/// assert_eq!(entry.to_u32(), 0x6041_0010);
/// assert_eq!(entry.to_string(), "6041sub0 (16 bits)");
/// assert!(MappingEntry::from_u32(0x0005_0008).is_dummy());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MappingEntry {
    index: u16,
    sub_index: u8,
    bits: u8,
}

impl MappingEntry {
    /// Return the entry that maps `bits` bits of object `index`, sub-index
    /// `sub_index`.
    #[must_use]
    pub const fn new(index: u16, sub_index: u8, bits: u8) -> Self {
        MappingEntry {
            index,
            sub_index,
            bits,
        }
    }

    /// Return the entry of the object value `raw`.
    #[must_use]
    pub const fn from_u32(raw: u32) -> Self {
        MappingEntry {
            index: (raw >> 16) as u16,
            sub_index: (raw >> 8) as u8,
            bits: raw as u8,
        }
    }

    /// Return the object value.
    #[must_use]
    pub const fn to_u32(self) -> u32 {
        (self.index as u32) << 16 | (self.sub_index as u32) << 8 | self.bits as u32
    }

    /// Return the object's index.
    #[must_use]
    pub const fn index(self) -> u16 {
        self.index
    }

    /// Return the object's sub-index.
    #[must_use]
    pub const fn sub_index(self) -> u8 {
        self.sub_index
    }

    /// Return the length in bits.
    #[must_use]
    pub const fn bits(self) -> u8 {
        self.bits
    }

    /// Return the object the entry maps, which displays as SPEC §8.2 names
    /// an object no file or profile knows: `6041sub0`.
    #[must_use]
    pub const fn object(self) -> ObjectAddress {
        ObjectAddress {
            index: self.index,
            sub_index: self.sub_index,
        }
    }

    /// Return whether the entry is a dummy: an index 0001h–0007h (a data
    /// type) that reserves its bits without mapping an object (CiA 301,
    /// PDO mapping, "dummy mapping"; CiA 306's `[DummyUsage]` lists the
    /// same seven, `Dummy0001`…`Dummy0007`). Unpacking skips it, packing writes zeros.
    #[must_use]
    pub const fn is_dummy(self) -> bool {
        matches!(self.index, 0x0001..=0x0007)
    }
}

impl From<u32> for MappingEntry {
    fn from(raw: u32) -> Self {
        MappingEntry::from_u32(raw)
    }
}

impl From<MappingEntry> for u32 {
    fn from(entry: MappingEntry) -> u32 {
        entry.to_u32()
    }
}

impl fmt::Display for MappingEntry {
    /// Format the entry as `6041sub0 (16 bits)`: the object as SPEC §8.2
    /// names an unknown one ([`ObjectAddress`]), and the length.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({} bit{})",
            self.object(),
            self.bits,
            if self.bits == 1 { "" } else { "s" }
        )
    }
}

/// An object-dictionary entry: index and sub-index. Displays as SPEC §8.2
/// names a signal that neither an EDS nor a profile names, and as CiA 306
/// names the entry's section: the index in four hex digits, `sub`, the
/// sub-index in hex (`6041sub0`, `1A00sub1A`).
///
/// ```
/// use motionwire::canopen::{MappingEntry, ObjectAddress};
///
/// assert_eq!(MappingEntry::from_u32(0x6041_0010).object().to_string(), "6041sub0");
/// assert_eq!(ObjectAddress { index: 0x1A00, sub_index: 0x1A }.to_string(), "1A00sub1A");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ObjectAddress {
    /// The index.
    pub index: u16,
    /// The sub-index.
    pub sub_index: u8,
}

impl fmt::Display for ObjectAddress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04X}sub{:X}", self.index, self.sub_index)
    }
}

/// The most entries a PDO mapping holds: sub-indices 1 to 64 (CiA 301
/// §7.5.2.36).
pub const MAX_MAPPING_ENTRIES: usize = 64;

/// The most bits a PDO carries: 64 bytes, a CAN FD frame (CiA 1301; a
/// classic CAN PDO carries at most 64 bits, [`CLASSIC_PDO_BITS`]).
pub const MAX_PDO_BITS: u16 = 512;

/// The most bits a classic CAN PDO carries, 8 bytes (CiA 301, PDO).
pub const CLASSIC_PDO_BITS: u16 = 64;

/// A PDO mapping parameter: up to [`MAX_MAPPING_ENTRIES`] entries of at
/// most [`MAX_PDO_BITS`] bits in all, without a heap (objects 1600h–17FFh,
/// 1A00h–1BFFh; CiA 301 §7.5.2.36, §7.5.2.38; SPEC §8.1).
///
/// See the [module documentation](self) for unpacking and packing. With the
/// `serde` feature a mapping is the sequence of its entries; reading one
/// back checks them as [`PdoMapping::push`] does.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct PdoMapping {
    entries: [MappingEntry; MAX_MAPPING_ENTRIES],
    len: u8,
    bits: u16,
}

impl Default for PdoMapping {
    fn default() -> Self {
        PdoMapping::new()
    }
}

impl fmt::Debug for PdoMapping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.entries()).finish()
    }
}

impl PdoMapping {
    /// Return an empty mapping.
    #[must_use]
    pub const fn new() -> Self {
        PdoMapping {
            entries: [MappingEntry::new(0, 0, 0); MAX_MAPPING_ENTRIES],
            len: 0,
            bits: 0,
        }
    }

    /// Return the mapping of the object values `raw`, in order (sub-index 1
    /// first), or the error of the first that [`PdoMapping::push`] refuses.
    pub fn from_u32s(raw: &[u32]) -> Result<Self> {
        let mut mapping = PdoMapping::new();
        for &value in raw {
            mapping.push(MappingEntry::from_u32(value))?;
        }
        Ok(mapping)
    }

    /// Append `entry`. Refuses, with an [`Error::OutOfRange`], an entry of
    /// length 0 ([`What::PdoMappingEntryLength`]), a 65th entry
    /// ([`What::PdoMappingEntries`]), and an entry that takes the mapping
    /// past [`MAX_PDO_BITS`] ([`What::PdoMappingBits`]); the mapping is then
    /// unchanged.
    pub fn push(&mut self, entry: MappingEntry) -> Result<()> {
        if entry.bits == 0 {
            return Err(Error::OutOfRange {
                what: What::PdoMappingEntryLength,
                found: 0,
                min: 1,
                max: 255,
            });
        }
        let len = usize::from(self.len);
        if len == MAX_MAPPING_ENTRIES {
            return Err(Error::OutOfRange {
                what: What::PdoMappingEntries,
                found: MAX_MAPPING_ENTRIES as u32 + 1,
                min: 0,
                max: MAX_MAPPING_ENTRIES as u32,
            });
        }
        let bits = self.bits + u16::from(entry.bits);
        if bits > MAX_PDO_BITS {
            return Err(Error::OutOfRange {
                what: What::PdoMappingBits,
                found: u32::from(bits),
                min: 0,
                max: u32::from(MAX_PDO_BITS),
            });
        }
        self.entries[len] = entry;
        self.len += 1;
        self.bits = bits;
        Ok(())
    }

    /// Remove every entry.
    pub fn clear(&mut self) {
        *self = PdoMapping::new();
    }

    /// Return the entries in mapping order.
    #[must_use]
    pub fn entries(&self) -> &[MappingEntry] {
        &self.entries[..usize::from(self.len)]
    }

    /// Return the number of entries (sub-index 0 of the mapping parameter).
    #[must_use]
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    /// Return whether the mapping has no entry.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Return the total length of the entries in bits.
    #[must_use]
    pub const fn bit_len(&self) -> u16 {
        self.bits
    }

    /// Return the bytes a payload needs to hold every entry.
    #[must_use]
    pub const fn byte_len(&self) -> usize {
        (self.bits as usize).div_ceil(8)
    }

    /// Return whether the mapping fits a classic CAN frame (64 bits).
    #[must_use]
    pub const fn fits_classic(&self) -> bool {
        self.bits <= CLASSIC_PDO_BITS
    }

    /// Read `payload` as this mapping's signals, each entry as unsigned of
    /// its length (1-bit entries as booleans, entries longer than 64 bits as
    /// [`Octets`]) (SPEC §8.2, "else unsigned of the entry's bit length").
    #[must_use]
    pub fn unpack<'a>(&'a self, payload: &'a [u8]) -> Signals<'a, ByLength> {
        Signals::new(self, payload, ByLength)
    }

    /// Read `payload` as this mapping's signals, each entry with the type
    /// `types` gives it (`None`: unsigned of its length, as
    /// [`PdoMapping::unpack`]).
    #[must_use]
    pub fn unpack_with<'a, T: TypeLookup>(&'a self, payload: &'a [u8], types: T) -> Signals<'a, T> {
        Signals::new(self, payload, types)
    }

    /// Write `values` (one per entry that is not a dummy, in mapping order)
    /// into `buf`, each entry typed as [`PdoMapping::unpack`] types it, and
    /// return the bytes written ([`PdoMapping::byte_len`]). See
    /// [`PdoMapping::pack_with`] for the errors.
    pub fn pack<I: IntoIterator<Item = Value>>(&self, values: I, buf: &mut [u8]) -> Result<usize> {
        self.pack_with(ByLength, values, buf)
    }

    /// Write `values` into `buf` with the types `types` gives, and return
    /// the bytes written. Dummy entries and the bits past the last entry of
    /// the last byte are written as zeros; bytes past
    /// [`PdoMapping::byte_len`] are left as they were.
    ///
    /// Errors: `buf` shorter than [`PdoMapping::byte_len`]
    /// ([`Error::Length`] of [`What::PdoPayload`]); a value of the wrong
    /// kind, one that does not fit its entry's bits, a missing value
    /// ([`Error::PdoEntry`]); values left over ([`Error::OutOfRange`] of
    /// [`What::PdoValues`]). The bytes of `buf` are unspecified after an
    /// error.
    pub fn pack_with<T: TypeLookup, I: IntoIterator<Item = Value>>(
        &self,
        types: T,
        values: I,
        buf: &mut [u8],
    ) -> Result<usize> {
        let len = self.byte_len();
        crate::error::check_len(What::PdoPayload, buf, len)?;
        buf[..len].fill(0);
        let mut values = values.into_iter();
        let mut offset: u16 = 0;
        let mut given: u32 = 0;
        for &entry in self.entries() {
            let at = offset;
            offset += u16::from(entry.bits);
            if entry.is_dummy() {
                continue;
            }
            let error = |reason| {
                Error::PdoEntry(PdoEntryError {
                    entry,
                    offset: at,
                    reason,
                })
            };
            let value = values
                .next()
                .ok_or_else(|| error(PdoEntryReason::MissingValue))?;
            given += 1;
            let data_type = types.data_type(entry);
            let kind = ValueKind::for_entry(data_type, entry.bits).map_err(error)?;
            encode(buf, at, entry.bits, kind, value).map_err(error)?;
        }
        let extra = values.count();
        if extra > 0 {
            return Err(Error::OutOfRange {
                what: What::PdoValues,
                found: given.saturating_add(u32::try_from(extra).unwrap_or(u32::MAX)),
                min: given,
                max: given,
            });
        }
        Ok(len)
    }
}

/// The data type of each entry of a mapping, as a caller knows it (from an
/// EDS, a device profile, …): `None` reads the entry as unsigned of its
/// length (SPEC §8.2). Implemented by closures
/// `Fn(MappingEntry) -> Option<DataType>` and by [`ByLength`].
pub trait TypeLookup {
    /// Return the data type of the object `entry` maps, if known.
    fn data_type(&self, entry: MappingEntry) -> Option<DataType>;
}

impl<F: Fn(MappingEntry) -> Option<DataType>> TypeLookup for F {
    fn data_type(&self, entry: MappingEntry) -> Option<DataType> {
        self(entry)
    }
}

/// The [`TypeLookup`] that knows no type: every entry is unsigned of its
/// length, 1-bit entries booleans (SPEC §8.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ByLength;

impl TypeLookup for ByLength {
    fn data_type(&self, _entry: MappingEntry) -> Option<DataType> {
        None
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
/// use motionwire::canopen::Octets;
///
/// let text = Octets::new(b"AKD", 24).unwrap();
/// assert_eq!(text.as_bytes(), b"AKD");
/// assert_eq!(text.to_string(), "414b44");
/// assert!(Octets::new(b"AKD", 16).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Octets {
    bytes: [u8; MAX_OCTETS],
    bits: u8,
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

/// The value of one signal of a PDO (SPEC §8.2).
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
    /// Return the kind an entry of `bits` bits reads as with `data_type`
    /// (SPEC §8.2):
    ///
    /// | type | bits | kind |
    /// |---|---|---|
    /// | none | 1 / 2–64 / 65–255 | `Bool` / `Unsigned` / `Octets` |
    /// | BOOLEAN | 1–64 | `Bool` (any bit set) |
    /// | INTEGERn | 1–64 | `Signed`, sign-extended from the entry's top bit |
    /// | UNSIGNEDn, TIME_OF_DAY, TIME_DIFFERENCE | 1–64 | `Unsigned` |
    /// | REAL32 / REAL64 | 32 / 64 | `Real32` / `Real64` |
    /// | strings, DOMAIN | any | `Octets` |
    ///
    /// **Decision:** the entry's length, not the type's width, says how many
    /// bits are read (the bits on the wire are the mapping's); a length the
    /// type cannot be read from is a [`PdoEntryReason::BadLength`].
    pub const fn for_entry(
        data_type: Option<DataType>,
        bits: u8,
    ) -> Result<ValueKind, PdoEntryReason> {
        let Some(data_type) = data_type else {
            return Ok(match bits {
                1 => ValueKind::Bool,
                2..=64 => ValueKind::Unsigned,
                _ => ValueKind::Octets,
            });
        };
        let kind = match data_type {
            DataType::Real32 => ValueKind::Real32,
            DataType::Real64 => ValueKind::Real64,
            DataType::VisibleString
            | DataType::OctetString
            | DataType::UnicodeString
            | DataType::Domain => return Ok(ValueKind::Octets),
            DataType::Boolean => ValueKind::Bool,
            t if t.is_signed() => ValueKind::Signed,
            _ => ValueKind::Unsigned,
        };
        let fits = match kind {
            ValueKind::Real32 => bits == 32,
            ValueKind::Real64 => bits == 64,
            _ => bits >= 1 && bits <= 64,
        };
        if fits {
            Ok(kind)
        } else {
            Err(PdoEntryReason::BadLength { data_type, bits })
        }
    }

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

/// One signal read from a PDO payload (SPEC §8.2).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Signal {
    /// The mapping entry it was read for.
    pub entry: MappingEntry,
    /// Its first bit in the payload (bit 0 = bit 0 of byte 0).
    pub offset: u16,
    /// The type it was read as (`None`: unsigned of its length).
    pub data_type: Option<DataType>,
    /// Its value.
    pub value: Value,
}

/// The signals of a PDO payload, in mapping order: the iterator
/// [`PdoMapping::unpack`] and [`PdoMapping::unpack_with`] return.
///
/// Yields one item per entry that is not a dummy: the [`Signal`], or an
/// [`Error::PdoEntry`] when the entry's length does not suit its type (the
/// next entries are still read). Where the payload ends before an entry
/// (dummy or not) it yields one [`Error::PdoEntry`] with
/// [`PdoEntryReason::Truncated`] and ends. Bytes past the mapping are
/// ignored.
#[derive(Debug, Clone)]
pub struct Signals<'a, T> {
    entries: &'a [MappingEntry],
    payload: &'a [u8],
    types: T,
    offset: u16,
}

impl<'a, T: TypeLookup> Signals<'a, T> {
    fn new(mapping: &'a PdoMapping, payload: &'a [u8], types: T) -> Self {
        Signals {
            entries: mapping.entries(),
            payload,
            types,
            offset: 0,
        }
    }
}

impl<T: TypeLookup> Iterator for Signals<'_, T> {
    type Item = Result<Signal>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let (&entry, rest) = self.entries.split_first()?;
            self.entries = rest;
            let offset = self.offset;
            let end = usize::from(offset) + usize::from(entry.bits);
            self.offset += u16::from(entry.bits);
            let error = |reason| {
                Error::PdoEntry(PdoEntryError {
                    entry,
                    offset,
                    reason,
                })
            };
            if end > self.payload.len() * 8 {
                self.entries = &[];
                return Some(Err(error(PdoEntryReason::Truncated {
                    needed: end.div_ceil(8),
                    found: self.payload.len(),
                })));
            }
            if entry.is_dummy() {
                continue;
            }
            let data_type = self.types.data_type(entry);
            let value = ValueKind::for_entry(data_type, entry.bits)
                .map(|kind| decode(self.payload, offset, entry.bits, kind));
            return Some(match value {
                Ok(value) => Ok(Signal {
                    entry,
                    offset,
                    data_type,
                    value,
                }),
                Err(reason) => Err(error(reason)),
            });
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (0, Some(self.entries.len()))
    }
}

impl<T: TypeLookup> core::iter::FusedIterator for Signals<'_, T> {}

/// One planned entry of a [`PdoLayout`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Planned {
    entry: MappingEntry,
    offset: u16,
    data_type: Option<DataType>,
    /// The kind to read, or why the entry cannot be read (never for a
    /// dummy, which is skipped).
    kind: core::result::Result<ValueKind, PdoEntryReason>,
}

/// A mapping with each entry's offset and value kind worked out once, for a
/// decoder that reads many frames of one PDO (SPEC §8.2): its
/// [`unpack`](Self::unpack) gives exactly what [`PdoMapping::unpack_with`]
/// gives with the same types, without looking the types up per frame.
///
/// ```
/// use motionwire::canopen::{DataType, MappingEntry, PdoLayout, PdoMapping, Value};
///
/// let mapping = PdoMapping::from_u32s(&[0x6041_0010, 0x6064_0020])?;
/// let types = |e: MappingEntry| match e.index() {
///     0x6041 => Some(DataType::Unsigned16),
///     0x6064 => Some(DataType::Integer32),
///     _ => None,
/// };
/// let layout = PdoLayout::new(&mapping, types);
/// let payload = [0x37, 0x02, 0xFF, 0xFF, 0xFF, 0xFF];
/// let values: Vec<Value> = layout.unpack(&payload).map(|s| s.unwrap().value).collect();
/// assert_eq!(values, [Value::Unsigned(0x0237), Value::Signed(-1)]);
/// assert!(layout.unpack(&payload).eq(mapping.unpack_with(&payload, types)));
/// # Ok::<(), motionwire::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct PdoLayout {
    planned: [Planned; MAX_MAPPING_ENTRIES],
    len: usize,
}

impl PdoLayout {
    /// Work out the layout of `mapping` with the data types `types` gives.
    pub fn new<T: TypeLookup>(mapping: &PdoMapping, types: T) -> Self {
        let empty = Planned {
            entry: MappingEntry::from_u32(0),
            offset: 0,
            data_type: None,
            kind: Ok(ValueKind::Unsigned),
        };
        let mut layout = PdoLayout {
            planned: [empty; MAX_MAPPING_ENTRIES],
            len: 0,
        };
        let mut offset: u16 = 0;
        for (slot, &entry) in layout.planned.iter_mut().zip(mapping.entries()) {
            let data_type = if entry.is_dummy() {
                None
            } else {
                types.data_type(entry)
            };
            *slot = Planned {
                entry,
                offset,
                data_type,
                kind: ValueKind::for_entry(data_type, entry.bits),
            };
            offset += u16::from(entry.bits);
            layout.len += 1;
        }
        layout
    }

    /// Read `payload`: the signals in mapping order, as
    /// [`PdoMapping::unpack_with`] reads them.
    #[must_use]
    pub fn unpack<'a>(&'a self, payload: &'a [u8]) -> LayoutSignals<'a> {
        LayoutSignals {
            planned: &self.planned[..self.len],
            payload,
        }
    }
}

impl PdoLayout {
    /// Read only the entry at `position` of the mapping (dummies counted):
    /// `None` for a position past the mapping or a dummy, else what
    /// [`unpack`](Self::unpack) gives for that entry — when the payload is
    /// too short for it, its truncation error.
    #[must_use]
    pub fn read(&self, position: usize, payload: &[u8]) -> Option<Result<Signal>> {
        let p = self.planned[..self.len].get(position)?;
        if p.entry.is_dummy() {
            return None;
        }
        LayoutSignals {
            planned: core::slice::from_ref(p),
            payload,
        }
        .next()
    }

    /// Return the position of the first entry that maps `index`.`sub_index`.
    #[must_use]
    pub fn position(&self, index: u16, sub_index: u8) -> Option<usize> {
        self.planned[..self.len]
            .iter()
            .position(|p| p.entry.index() == index && p.entry.sub_index() == sub_index)
    }
}

/// The signals of one payload read with a [`PdoLayout`].
#[derive(Debug, Clone)]
pub struct LayoutSignals<'a> {
    planned: &'a [Planned],
    payload: &'a [u8],
}

impl Iterator for LayoutSignals<'_> {
    type Item = Result<Signal>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let (p, rest) = self.planned.split_first()?;
            self.planned = rest;
            let end = usize::from(p.offset) + usize::from(p.entry.bits);
            let error = |reason| {
                Error::PdoEntry(PdoEntryError {
                    entry: p.entry,
                    offset: p.offset,
                    reason,
                })
            };
            if end > self.payload.len() * 8 {
                self.planned = &[];
                return Some(Err(error(PdoEntryReason::Truncated {
                    needed: end.div_ceil(8),
                    found: self.payload.len(),
                })));
            }
            if p.entry.is_dummy() {
                continue;
            }
            return Some(match p.kind {
                Ok(kind) => Ok(Signal {
                    entry: p.entry,
                    offset: p.offset,
                    data_type: p.data_type,
                    value: decode(self.payload, p.offset, p.entry.bits, kind),
                }),
                Err(reason) => Err(error(reason)),
            });
        }
    }
}

impl core::iter::FusedIterator for LayoutSignals<'_> {}

/// Return the mask of the low `bits` bits (1..=64).
const fn mask(bits: u8) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// Read `bits` (1..=64) bits from bit `offset` of `payload`, little-endian.
/// The caller has checked that they lie inside the payload.
fn read_bits(payload: &[u8], offset: u16, bits: u8) -> u64 {
    let start = usize::from(offset / 8);
    // Fast path: an 8-byte word that holds the field — from its first byte,
    // or the payload's last 8 bytes when it starts less than 8 from the end.
    if payload.len() >= 8 {
        let word_start = start.min(payload.len() - 8);
        let shift = u32::from(offset) - 8 * word_start as u32;
        if shift + u32::from(bits) <= 64 {
            let mut word = [0u8; 8];
            word.copy_from_slice(&payload[word_start..word_start + 8]);
            return (u64::from_le_bytes(word) >> shift) & mask(bits);
        }
    }
    let shift = u32::from(offset % 8);
    let len = (shift as usize + usize::from(bits)).div_ceil(8);
    // Byte-aligned entries of whole bytes, most of a drive's process data:
    // one little-endian load.
    if shift == 0 {
        match bits {
            8 => return u64::from(payload[start]),
            16 => return u64::from(u16::from_le_bytes([payload[start], payload[start + 1]])),
            32 => {
                let b = &payload[start..start + 4];
                return u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
            }
            _ => {}
        }
    }
    if len <= 8 {
        // An entry inside 8 bytes: a 64-bit window.
        let mut window = 0u64;
        for (i, &byte) in payload[start..start + len].iter().enumerate() {
            window |= u64::from(byte) << (8 * i);
        }
        return (window >> shift) & mask(bits);
    }
    let mut window = 0u128;
    for (i, &byte) in payload[start..start + len].iter().enumerate() {
        window |= u128::from(byte) << (8 * i);
    }
    (window >> shift) as u64 & mask(bits)
}

/// Write the low `bits` (1..=64) bits of `value` at bit `offset` of `buf`,
/// keeping the other bits. The caller has checked that they lie inside.
fn write_bits(buf: &mut [u8], offset: u16, bits: u8, value: u64) {
    let start = usize::from(offset / 8);
    let shift = u32::from(offset % 8);
    let len = (shift as usize + usize::from(bits)).div_ceil(8);
    let field = u128::from(mask(bits)) << shift;
    let value = u128::from(value & mask(bits)) << shift;
    for (i, byte) in buf[start..start + len].iter_mut().enumerate() {
        let field_byte = (field >> (8 * i)) as u8;
        let value_byte = (value >> (8 * i)) as u8;
        *byte = (*byte & !field_byte) | value_byte;
    }
}

/// Decode the entry at `offset` as `kind` (from [`ValueKind::for_entry`],
/// which has checked the length for the numeric kinds).
fn decode(payload: &[u8], offset: u16, bits: u8, kind: ValueKind) -> Value {
    match kind {
        ValueKind::Bool => Value::Bool(read_bits(payload, offset, bits) != 0),
        ValueKind::Unsigned => Value::Unsigned(read_bits(payload, offset, bits)),
        ValueKind::Signed => {
            let raw = read_bits(payload, offset, bits);
            let unused = 64 - u32::from(bits);
            Value::Signed(((raw << unused) as i64) >> unused)
        }
        ValueKind::Real32 => Value::Real32(f32::from_bits(read_bits(payload, offset, 32) as u32)),
        ValueKind::Real64 => Value::Real64(f64::from_bits(read_bits(payload, offset, 64))),
        ValueKind::Octets => {
            let mut bytes = [0u8; MAX_OCTETS];
            let len = usize::from(bits).div_ceil(8);
            for (i, byte) in bytes[..len].iter_mut().enumerate() {
                let done = 8 * i as u16;
                let take = (u16::from(bits) - done).min(8) as u8;
                *byte = read_bits(payload, offset + done, take) as u8;
            }
            Value::Octets(Octets { bytes, bits })
        }
    }
}

/// Encode `value` as an entry of `kind` and `bits` bits at `offset`.
fn encode(
    buf: &mut [u8],
    offset: u16,
    bits: u8,
    kind: ValueKind,
    value: Value,
) -> core::result::Result<(), PdoEntryReason> {
    let raw = match (kind, value) {
        (ValueKind::Bool, Value::Bool(b)) => u64::from(b),
        (ValueKind::Unsigned, Value::Unsigned(v)) => {
            if v & !mask(bits) != 0 {
                return Err(PdoEntryReason::ValueTooWide { bits });
            }
            v
        }
        (ValueKind::Signed, Value::Signed(v)) => {
            let unused = 64 - u32::from(bits);
            if ((v << unused) >> unused) != v {
                return Err(PdoEntryReason::ValueTooWide { bits });
            }
            v as u64 & mask(bits)
        }
        (ValueKind::Real32, Value::Real32(v)) => u64::from(v.to_bits()),
        (ValueKind::Real64, Value::Real64(v)) => v.to_bits(),
        (ValueKind::Octets, Value::Octets(v)) => {
            if v.bits != bits {
                return Err(PdoEntryReason::OctetsLength {
                    expected: bits,
                    found: v.bits,
                });
            }
            for (i, &byte) in v.as_bytes().iter().enumerate() {
                let done = 8 * i as u16;
                let take = (u16::from(bits) - done).min(8) as u8;
                write_bits(buf, offset + done, take, u64::from(byte));
            }
            return Ok(());
        }
        (expected, value) => {
            return Err(PdoEntryReason::WrongKind {
                expected,
                found: value.kind(),
            })
        }
    };
    write_bits(buf, offset, bits, raw);
    Ok(())
}

#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;

#[cfg(feature = "serde")]
mod serde_impls;
