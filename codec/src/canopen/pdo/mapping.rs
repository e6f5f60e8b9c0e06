//! The mapping parameter of a PDO, objects 1600h–17FFh (RPDO) and
//! 1A00h–1BFFh (TPDO): its entries, and a payload unpacked into signals or
//! packed from values (CiA 301 §7.5.2.36, §7.5.2.38;
//! docs/canopen.md#pdo-mappings, docs/canopen.md#signals).

use core::fmt;

use super::bits::{decode, encode};
use super::{PdoEntryError, PdoEntryReason, PdoPackError};
use crate::canopen::data_type::{DataType, Value, ValueKind};
use crate::canopen::ObjectAddress;
use crate::error::What;
use crate::{RangeError, Result};

/// One entry of a PDO mapping parameter, the `u32` object value
/// `index << 16 | sub-index << 8 | length in bits` (CiA 301 §7.5.2.36, §7.5.2.38;
/// docs/canopen.md#pdo-mappings). Every `u32` is an entry; [`PdoMapping::push`]
/// refuses the length 0.
///
/// ```
/// use motionwire_codec::canopen::MappingEntry;
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

    /// Return the object the entry maps; its
    /// [`sub_notation`](ObjectAddress::sub_notation) is how a
    /// signal is named when no file or profile knows its object
    /// (docs/canopen.md#signals): `6041sub0`.
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
    /// Format the entry as `6041sub0 (16 bits)`: the object named as
    /// docs/canopen.md#signals names an unknown one
    /// ([`ObjectAddress::sub_notation`]), and the length.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({} bit{})",
            self.object().sub_notation(),
            self.bits,
            if self.bits == 1 { "" } else { "s" }
        )
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
/// 1A00h–1BFFh; CiA 301 §7.5.2.36, §7.5.2.38; docs/canopen.md#pdo-mappings).
///
/// See the [module documentation](super) for unpacking and packing. With the
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
    pub fn from_u32s(raw: &[u32]) -> Result<Self, RangeError> {
        let mut mapping = PdoMapping::new();
        for &value in raw {
            mapping.push(MappingEntry::from_u32(value))?;
        }
        Ok(mapping)
    }

    /// Append `entry`. Refuses, with a [`RangeError`], an entry of
    /// length 0 ([`What::PdoMappingEntryLength`]), a 65th entry
    /// ([`What::PdoMappingEntries`]), and an entry that takes the mapping
    /// past [`MAX_PDO_BITS`] ([`What::PdoMappingBits`]); the mapping is then
    /// unchanged.
    pub fn push(&mut self, entry: MappingEntry) -> Result<(), RangeError> {
        if entry.bits == 0 {
            return Err(RangeError {
                what: What::PdoMappingEntryLength,
                found: 0,
                min: 1,
                max: 255,
            });
        }
        let len = usize::from(self.len);
        if len == MAX_MAPPING_ENTRIES {
            return Err(RangeError {
                what: What::PdoMappingEntries,
                found: MAX_MAPPING_ENTRIES as u32 + 1,
                min: 0,
                max: MAX_MAPPING_ENTRIES as u32,
            });
        }
        let bits = self.bits + u16::from(entry.bits);
        if bits > MAX_PDO_BITS {
            return Err(RangeError {
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
    /// [`Octets`](crate::canopen::Octets)) (docs/canopen.md#signals: else
    /// unsigned of the entry's length).
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
    pub fn pack<I: IntoIterator<Item = Value>>(
        &self,
        values: I,
        buf: &mut [u8],
    ) -> Result<usize, PdoPackError> {
        self.pack_with(ByLength, values, buf)
    }

    /// Write `values` into `buf` with the types `types` gives, and return
    /// the bytes written. Dummy entries and the bits past the last entry of
    /// the last byte are written as zeros; bytes past
    /// [`PdoMapping::byte_len`] are left as they were.
    ///
    /// Errors: `buf` shorter than [`PdoMapping::byte_len`]
    /// ([`PdoPackError::Length`] of [`What::PdoPayload`]); a value of the
    /// wrong kind, one that does not fit its entry's bits, a missing value
    /// ([`PdoPackError::PdoEntry`]); values left over
    /// ([`PdoPackError::OutOfRange`] of
    /// [`What::PdoValues`]). The bytes of `buf` are unspecified after an
    /// error.
    pub fn pack_with<T: TypeLookup, I: IntoIterator<Item = Value>>(
        &self,
        types: T,
        values: I,
        buf: &mut [u8],
    ) -> Result<usize, PdoPackError> {
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
            let error = |reason| PdoEntryError {
                entry,
                offset: at,
                reason,
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
            return Err(PdoPackError::OutOfRange(RangeError {
                what: What::PdoValues,
                found: given.saturating_add(u32::try_from(extra).unwrap_or(u32::MAX)),
                min: given,
                max: given,
            }));
        }
        Ok(len)
    }
}

/// The data type of each entry of a mapping, as a caller knows it (from an
/// EDS, a device profile, …): `None` reads the entry as unsigned of its
/// length (docs/canopen.md#signals). Implemented by closures
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
/// length, 1-bit entries booleans (docs/canopen.md#signals).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ByLength;

impl TypeLookup for ByLength {
    fn data_type(&self, _entry: MappingEntry) -> Option<DataType> {
        None
    }
}

impl ValueKind {
    /// Return the kind an entry of `bits` bits reads as with `data_type`
    /// (docs/canopen.md#signals):
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
}

/// One signal read from a PDO payload (docs/canopen.md#signals).
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
/// [`PdoEntryError`] when the entry's length does not suit its type (the
/// next entries are still read). Where the payload ends before an entry
/// (dummy or not) it yields one [`PdoEntryError`] with
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
    type Item = Result<Signal, PdoEntryError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let (&entry, rest) = self.entries.split_first()?;
            self.entries = rest;
            let offset = self.offset;
            let end = usize::from(offset) + usize::from(entry.bits);
            self.offset += u16::from(entry.bits);
            let error = |reason| PdoEntryError {
                entry,
                offset,
                reason,
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
                .map(|kind| decode(self.payload, usize::from(offset), entry.bits, kind));
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

#[cfg(test)]
mod tests {
    //! Unit tests of the mapping codecs, as tables from CiA 301 and
    //! docs/canopen.md#pdo-mappings.

    use super::*;
    use crate::canopen::data_type::Octets;
    use crate::LenError;

    #[test]
    fn mapping_limits() {
        let mut mapping = PdoMapping::new();
        assert!(mapping.is_empty());
        assert_eq!(
            mapping.push(MappingEntry::new(0x6041, 0, 0)),
            Err(RangeError {
                what: What::PdoMappingEntryLength,
                found: 0,
                min: 1,
                max: 255
            })
        );
        for _ in 0..64 {
            mapping.push(MappingEntry::new(0x2000, 1, 8)).unwrap();
        }
        assert_eq!(mapping.len(), 64);
        assert_eq!(mapping.bit_len(), 512);
        assert_eq!(mapping.byte_len(), 64);
        assert!(!mapping.fits_classic());
        assert_eq!(
            mapping.push(MappingEntry::new(0x2000, 1, 1)),
            Err(RangeError {
                what: What::PdoMappingEntries,
                found: 65,
                min: 0,
                max: 64
            })
        );
        let mut mapping = PdoMapping::from_u32s(&[0x2000_01FF, 0x2000_02FF]).unwrap();
        assert_eq!(mapping.bit_len(), 510);
        assert_eq!(
            mapping.push(MappingEntry::new(0x2000, 3, 3)),
            Err(RangeError {
                what: What::PdoMappingBits,
                found: 513,
                min: 0,
                max: 512
            })
        );
        assert_eq!(mapping.len(), 2);
        mapping.clear();
        assert_eq!(mapping, PdoMapping::default());
    }

    fn mapping(raw: &[u32]) -> PdoMapping {
        PdoMapping::from_u32s(raw).unwrap()
    }

    #[test]
    fn bits_straddle_bytes_little_endian() {
        // 3 bits, 12 bits, 1 bit, 8 bits: 0b_xxxxxxxx_y_zzzzzzzzzzzz_www.
        let m = mapping(&[0x2000_0103, 0x2000_020C, 0x2000_0301, 0x2000_0408]);
        // w = 0b101, z = 0xABC, y = 1, x = 0x5A.
        let raw: u32 = 0b101 | 0xABC << 3 | 1 << 15 | 0x5A << 16;
        let payload = raw.to_le_bytes();
        let values: Vec<_> = m.unpack(&payload[..3]).map(|s| s.unwrap().value).collect();
        assert_eq!(
            values,
            [
                Value::Unsigned(0b101),
                Value::Unsigned(0xABC),
                Value::Bool(true),
                Value::Unsigned(0x5A)
            ]
        );
        let offsets: Vec<_> = m.unpack(&payload).map(|s| s.unwrap().offset).collect();
        assert_eq!(offsets, [0, 3, 15, 16]);
        let mut buf = [0xFF; 4];
        assert_eq!(m.pack(values, &mut buf), Ok(3));
        assert_eq!(buf, [payload[0], payload[1], payload[2], 0xFF]);
    }

    #[test]
    fn integers_are_sign_extended_from_their_width() {
        let types = |entry: MappingEntry| DataType::from_index(entry.sub_index().into());
        // Sub-index = data type, so that the closure gives INTEGER24 etc.
        let m = mapping(&[
            0x2000_1018,
            0x2000_1228,
            0x2000_1330,
            0x2000_1438,
            0x2000_1640,
        ]);
        let mut payload = [0u8; 8 * 3 + 8];
        // INTEGER24 -2, INTEGER40 -3, INTEGER48 min, INTEGER56 max, UNSIGNED24 in 64 bits.
        let values = [
            Value::Signed(-2),
            Value::Signed(-3),
            Value::Signed(-(1 << 47)),
            Value::Signed((1 << 55) - 1),
            Value::Unsigned(0xFF_FFFF),
        ];
        let len = m.pack_with(types, values, &mut payload).unwrap();
        assert_eq!(len, 3 + 5 + 6 + 7 + 8);
        assert_eq!(payload[..3], [0xFE, 0xFF, 0xFF]);
        assert_eq!(payload[3..8], [0xFD, 0xFF, 0xFF, 0xFF, 0xFF]);
        assert_eq!(payload[8..14], [0, 0, 0, 0, 0, 0x80]);
        assert_eq!(payload[14..21], [0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F]);
        let back: Vec<_> = m
            .unpack_with(&payload, types)
            .map(|s| s.unwrap().value)
            .collect();
        assert_eq!(back, values);
    }

    #[test]
    fn reals_and_booleans() {
        let types = |entry: MappingEntry| match entry.index() {
            0x3000 => Some(DataType::Real32),
            0x3001 => Some(DataType::Real64),
            0x3002 => Some(DataType::Boolean),
            _ => None,
        };
        let m = mapping(&[0x3000_0020, 0x3001_0040, 0x3002_0008]);
        let mut payload = [0u8; 13];
        payload[..4].copy_from_slice(&1.5f32.to_le_bytes());
        payload[4..12].copy_from_slice(&(-0.25f64).to_le_bytes());
        payload[12] = 0x02;
        let values: Vec<_> = m
            .unpack_with(&payload, types)
            .map(|s| s.unwrap().value)
            .collect();
        assert_eq!(
            values,
            [Value::Real32(1.5), Value::Real64(-0.25), Value::Bool(true)]
        );
    }

    #[test]
    fn lengths_a_type_cannot_be_read_from() {
        let types = |entry: MappingEntry| match entry.index() {
            0x3000 => Some(DataType::Real32),
            _ => Some(DataType::Integer16),
        };
        // REAL32 mapped with 16 bits; an INTEGER16 with 72 bits; then a good one.
        let m = mapping(&[0x3000_0010, 0x3001_0048, 0x3002_0010]);
        let payload = [0u8; 14];
        let items: Vec<_> = m.unpack_with(&payload, types).collect();
        assert_eq!(
            items[0],
            Err(PdoEntryError {
                entry: MappingEntry::from_u32(0x3000_0010),
                offset: 0,
                reason: PdoEntryReason::BadLength {
                    data_type: DataType::Real32,
                    bits: 16
                }
            })
        );
        assert_eq!(
            items[0].unwrap_err().to_string(),
            "PDO entry 3000sub0 (16 bits) at bit 0: expected 32 bits for REAL32, found 16"
        );
        assert!(matches!(
            items[1],
            Err(PdoEntryError {
                offset: 16,
                reason: PdoEntryReason::BadLength { bits: 72, .. },
                ..
            })
        ));
        assert_eq!(items[2].map(|s| s.offset), Ok(88));
    }

    #[test]
    fn dummy_entries_take_their_bits() {
        // UNSIGNED8 dummy (0005h), then 6041h.
        let m = mapping(&[0x0005_0008, 0x6041_0010, 0x0001_0001]);
        let payload = [0xAA, 0x37, 0x02, 0x01];
        let signals: Vec<_> = m.unpack(&payload).map(|s| s.unwrap()).collect();
        assert_eq!(signals.len(), 1);
        assert_eq!(signals[0].offset, 8);
        assert_eq!(signals[0].value, Value::Unsigned(0x0237));
        let mut buf = [0xFF; 4];
        assert_eq!(m.pack([Value::Unsigned(0x0237)], &mut buf), Ok(4));
        assert_eq!(buf, [0x00, 0x37, 0x02, 0x00]);
        // A dummy that the payload cuts off is reported too.
        let items: Vec<_> = m.unpack(&payload[..3]).collect();
        assert_eq!(items.len(), 2);
        assert_eq!(
            items[1],
            Err(PdoEntryError {
                entry: MappingEntry::from_u32(0x0001_0001),
                offset: 24,
                reason: PdoEntryReason::Truncated {
                    needed: 4,
                    found: 3
                }
            })
        );
    }

    #[test]
    fn octets_for_strings_and_long_entries() {
        let types =
            |entry: MappingEntry| (entry.index() == 0x2008).then_some(DataType::VisibleString);
        let m = mapping(&[0x2008_0018, 0x2100_0048, 0x2200_0004]);
        let payload = *b"AKD\x01\x02\x03\x04\x05\x06\x07\x08\x09\x0F";
        let values: Vec<_> = m
            .unpack_with(&payload, types)
            .map(|s| s.unwrap().value)
            .collect();
        assert_eq!(values[0], Value::Octets(Octets::new(b"AKD", 24).unwrap()));
        assert_eq!(
            values[1],
            Value::Octets(Octets::new(&[1, 2, 3, 4, 5, 6, 7, 8, 9], 72).unwrap())
        );
        assert_eq!(values[2], Value::Unsigned(0xF));
        assert_eq!(values[1].to_string(), "010203040506070809");
        let mut buf = [0u8; 13];
        assert_eq!(m.pack_with(types, values, &mut buf), Ok(13));
        assert_eq!(buf, payload);
    }

    #[test]
    fn pack_errors() {
        let types = |_: MappingEntry| Some(DataType::Integer8);
        let m = mapping(&[0x2000_0008, 0x2001_0008]);
        let mut buf = [0u8; 2];
        assert_eq!(
            m.pack_with(types, [Value::Signed(1)], &mut buf[..1]),
            Err(PdoPackError::Length(LenError {
                what: What::PdoPayload,
                expected: 2,
                found: 1
            }))
        );
        let entry = MappingEntry::from_u32(0x2001_0008);
        assert_eq!(
            m.pack_with(types, [Value::Signed(1)], &mut buf),
            Err(PdoPackError::PdoEntry(PdoEntryError {
                entry,
                offset: 8,
                reason: PdoEntryReason::MissingValue
            }))
        );
        assert_eq!(
            m.pack_with(types, [Value::Signed(1), Value::Signed(128)], &mut buf),
            Err(PdoPackError::PdoEntry(PdoEntryError {
                entry,
                offset: 8,
                reason: PdoEntryReason::ValueTooWide { bits: 8 }
            }))
        );
        assert_eq!(
            m.pack_with(types, [Value::Signed(1), Value::Unsigned(1)], &mut buf),
            Err(PdoPackError::PdoEntry(PdoEntryError {
                entry,
                offset: 8,
                reason: PdoEntryReason::WrongKind {
                    expected: ValueKind::Signed,
                    found: ValueKind::Unsigned
                }
            }))
        );
        assert_eq!(
            m.pack_with(
                types,
                [Value::Signed(-128), Value::Signed(127), Value::Signed(0)],
                &mut buf
            ),
            Err(PdoPackError::OutOfRange(RangeError {
                what: What::PdoValues,
                found: 3,
                min: 2,
                max: 2
            }))
        );
        assert_eq!(
            m.pack_with(types, [Value::Signed(-128), Value::Signed(127)], &mut buf),
            Ok(2)
        );
        assert_eq!(buf, [0x80, 0x7F]);
    }

    #[test]
    fn unpack_of_an_empty_mapping_or_payload() {
        assert_eq!(PdoMapping::new().unpack(&[1, 2, 3]).count(), 0);
        let m = mapping(&[0x6041_0010]);
        let items: Vec<_> = m.unpack(&[]).collect();
        assert_eq!(
            items,
            [Err(PdoEntryError {
                entry: MappingEntry::from_u32(0x6041_0010),
                offset: 0,
                reason: PdoEntryReason::Truncated {
                    needed: 2,
                    found: 0
                }
            })]
        );
    }

    /// Any mapping and values pack and unpack back to themselves; any bytes
    /// unpack without panicking.
    mod proptests {
        use proptest::prelude::*;

        use super::*;
        use crate::strategies::pdo::{data_type_for, mapping_and_values, type_lookup_seed};

        proptest! {
            #[test]
            fn pack_unpack_round_trip((mapping, seed, values) in mapping_and_values()) {
                let types = |entry: MappingEntry| data_type_for(seed, entry);
                let mut buf = [0u8; 64];
                let len = mapping.pack_with(types, values.iter().copied(), &mut buf).unwrap();
                prop_assert_eq!(len, mapping.byte_len());
                let back: Vec<Value> = mapping
                    .unpack_with(&buf[..len], types)
                    .map(|s| s.map(|s| s.value))
                    .collect::<Result<_, _>>()
                    .unwrap();
                prop_assert_eq!(back.len(), values.len());
                for (a, b) in back.iter().zip(&values) {
                    // Compare floats by bits (NaN round-trips too).
                    match (a, b) {
                        (Value::Real32(x), Value::Real32(y)) => prop_assert_eq!(x.to_bits(), y.to_bits()),
                        (Value::Real64(x), Value::Real64(y)) => prop_assert_eq!(x.to_bits(), y.to_bits()),
                        _ => prop_assert_eq!(a, b),
                    }
                }
                // And packing what was unpacked gives the same bytes.
                let mut again = [0u8; 64];
                let len2 = mapping.pack_with(types, back, &mut again).unwrap();
                prop_assert_eq!(&buf[..len], &again[..len2]);
            }

            #[test]
            fn any_bytes_unpack_without_panic(
                raw in proptest::collection::vec(any::<u32>(), 0..70),
                seed in type_lookup_seed(),
                payload in proptest::collection::vec(any::<u8>(), 0..70),
            ) {
                let mut mapping = PdoMapping::new();
                for value in raw {
                    let _ = mapping.push(MappingEntry::from_u32(value));
                }
                let types = |entry: MappingEntry| data_type_for(seed, entry);
                let mut truncated = 0;
                let mut count = 0;
                for item in mapping.unpack_with(&payload, types) {
                    count += 1;
                    match item {
                        Ok(signal) => {
                            prop_assert!(usize::from(signal.offset) + usize::from(signal.entry.bits()) <= payload.len() * 8);
                            prop_assert!(!signal.entry.is_dummy());
                        }
                        Err(PdoEntryError { reason: PdoEntryReason::Truncated { needed, found }, .. }) => {
                            truncated += 1;
                            prop_assert!(needed > found);
                            prop_assert_eq!(found, payload.len());
                        }
                        Err(PdoEntryError { reason: PdoEntryReason::BadLength { .. }, .. }) => {}
                        Err(other) => prop_assert!(false, "unexpected {:?}", other),
                    }
                }
                prop_assert!(truncated <= 1);
                prop_assert!(count <= mapping.len());
                prop_assert_eq!(truncated == 1, payload.len() < mapping.byte_len());
                // Untyped: every entry reads.
                for item in mapping.unpack(&payload) {
                    if let Err(e) = item {
                        let truncated = matches!(e, PdoEntryError { reason: PdoEntryReason::Truncated { .. }, .. });
                        prop_assert!(truncated);
                    }
                }
            }
        }
    }
}
