//! A PDO mapping with each entry's offset and value kind worked out once,
//! for a decoder that reads many frames of one PDO (docs/canopen.md#signals).

use super::bits::{decode, decode_aligned, is_aligned};
use super::mapping::{MappingEntry, PdoMapping, Signal, TypeLookup, MAX_MAPPING_ENTRIES};
use super::{PdoEntryError, PdoEntryReason};
use crate::canopen::data_type::{DataType, ValueKind};
use crate::Result;

/// One planned entry of a [`PdoLayout`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Planned {
    entry: MappingEntry,
    offset: u16,
    data_type: Option<DataType>,
    /// The kind to read, or why the entry cannot be read (never for a
    /// dummy, which is skipped).
    kind: core::result::Result<ValueKind, PdoEntryReason>,
    /// The entry's bytes when it is a number of 1, 2, 4 or 8 whole bytes
    /// from a byte boundary, read with one load (`bits::is_aligned`); 0
    /// else.
    aligned: u8,
}

/// A mapping with each entry's offset and value kind worked out once, for a
/// decoder that reads many frames of one PDO (docs/canopen.md#signals): its
/// [`unpack`](Self::unpack) gives exactly what [`PdoMapping::unpack_with`]
/// gives with the same types, without looking the types up per frame.
///
/// ```
/// use motionwire_codec::canopen::{DataType, MappingEntry, PdoLayout, PdoMapping, Value};
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
/// # Ok::<(), motionwire_codec::Error>(())
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
            aligned: 0,
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
            let kind = ValueKind::for_entry(data_type, entry.bits());
            let aligned = match kind {
                Ok(kind) if is_aligned(offset, entry.bits(), kind) => entry.bits() / 8,
                _ => 0,
            };
            *slot = Planned {
                entry,
                offset,
                data_type,
                kind,
                aligned,
            };
            offset += u16::from(entry.bits());
            layout.len += 1;
        }
        layout
    }

    /// Read `payload`: the signals in mapping order, as
    /// [`PdoMapping::unpack_with`] reads them.
    #[must_use]
    pub fn unpack<'a>(&'a self, payload: &'a [u8]) -> LayoutSignals<'a> {
        self.unpack_at(payload, 0)
    }

    /// Read the PDO placed at bit `bit` of `image` (an EtherCAT slave's
    /// process data image holds its PDOs one after the other, ETG.1000.6
    /// 5.6.7.4): what [`unpack`](Self::unpack) gives of the PDO's own bits
    /// moved to bit 0. Each signal's `offset` is its bit in the PDO; a
    /// truncated entry's `needed` counts the PDO's bytes, `found` the
    /// whole bytes of `image` from `bit` on.
    ///
    /// ```
    /// use motionwire_codec::canopen::{DataType, MappingEntry, PdoLayout, PdoMapping, Value};
    ///
    /// // Two 1-bit outputs from bit 3 of the image.
    /// let mapping = PdoMapping::from_u32s(&[0x7000_0101, 0x7010_0101])?;
    /// let layout = PdoLayout::new(&mapping, |_: MappingEntry| Some(DataType::Boolean));
    /// let image = [0b0001_0000];
    /// let values: Vec<Value> = layout.unpack_at(&image, 3).map(|s| s.unwrap().value).collect();
    /// assert_eq!(values, [Value::Bool(false), Value::Bool(true)]);
    /// # Ok::<(), motionwire_codec::Error>(())
    /// ```
    #[must_use]
    pub fn unpack_at<'a>(&'a self, image: &'a [u8], bit: usize) -> LayoutSignals<'a> {
        LayoutSignals {
            planned: &self.planned[..self.len],
            payload: image,
            base: bit,
        }
    }
}

impl PdoLayout {
    /// Read only the entry at `position` of the mapping (dummies counted):
    /// `None` for a position past the mapping or a dummy, else what
    /// [`unpack`](Self::unpack) gives for that entry — when the payload is
    /// too short for it, its truncation error.
    #[inline]
    #[must_use]
    pub fn read(&self, position: usize, payload: &[u8]) -> Option<Result<Signal, PdoEntryError>> {
        let p = self.planned[..self.len].get(position)?;
        if p.entry.is_dummy() {
            return None;
        }
        LayoutSignals {
            planned: core::slice::from_ref(p),
            payload,
            base: 0,
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
    /// The payload's bit where the PDO starts.
    base: usize,
}

impl Iterator for LayoutSignals<'_> {
    type Item = Result<Signal, PdoEntryError>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            let (p, rest) = self.planned.split_first()?;
            self.planned = rest;
            let end = usize::from(p.offset) + usize::from(p.entry.bits());
            let error = |reason| PdoEntryError {
                entry: p.entry,
                offset: p.offset,
                reason,
            };
            let bits = self.payload.len() * 8;
            if self.base + end > bits {
                self.planned = &[];
                return Some(Err(error(PdoEntryReason::Truncated {
                    needed: end.div_ceil(8),
                    found: bits.saturating_sub(self.base) / 8,
                })));
            }
            let offset = self.base + usize::from(p.offset);
            if p.entry.is_dummy() {
                continue;
            }
            return Some(match p.kind {
                Ok(kind) => Ok(Signal {
                    entry: p.entry,
                    offset: p.offset,
                    data_type: p.data_type,
                    // One load for whole bytes from a byte boundary, the
                    // bit window else.
                    value: if p.aligned != 0 && self.base % 8 == 0 {
                        decode_aligned(self.payload, offset, p.aligned, kind)
                    } else {
                        decode(self.payload, offset, p.entry.bits(), kind)
                    },
                }),
                Err(reason) => Err(error(reason)),
            });
        }
    }
}

impl core::iter::FusedIterator for LayoutSignals<'_> {}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::canopen::data_type::Value;
    use crate::strategies::pdo::{data_type_for, type_lookup_seed};

    proptest! {
        /// A layout reads exactly what the mapping reads with the same types,
        /// on any mapping and any bytes (NaNs compared by bits).
        #[test]
        fn layout_reads_what_the_mapping_reads(
            raw in proptest::collection::vec(any::<u32>(), 0..70),
            // Entries of whole bytes, most of them from a byte boundary
            // (the one-load path), now and then one of a few bits.
            bytes in proptest::collection::vec(
                (any::<u16>(), prop::sample::select(vec![8u32, 16, 32, 64, 8, 16, 32, 1, 12])),
                0..12,
            ),
            whole_bytes in any::<bool>(),
            seed in type_lookup_seed(),
            payload in proptest::collection::vec(any::<u8>(), 0..70),
        ) {
            let raw = if whole_bytes {
                bytes.iter().map(|&(index, bits)| u32::from(index) << 16 | bits).collect()
            } else {
                raw
            };
            let mut mapping = PdoMapping::new();
            for value in raw {
                if mapping.push(MappingEntry::from_u32(value)).is_err() {
                    break;
                }
            }
            let types = |entry: MappingEntry| data_type_for(seed, entry);
            let layout = PdoLayout::new(&mapping, types);
            let bits = |r: Result<Signal, PdoEntryError>| r.map(|s| match s.value {
                Value::Real32(x) => (s.entry, s.offset, s.data_type, Value::Unsigned(u64::from(x.to_bits()))),
                Value::Real64(x) => (s.entry, s.offset, s.data_type, Value::Unsigned(x.to_bits())),
                v => (s.entry, s.offset, s.data_type, v),
            });
            let a: Vec<_> = layout.unpack(&payload).map(bits).collect();
            let b: Vec<_> = mapping.unpack_with(&payload, types).map(bits).collect();
            prop_assert_eq!(&a, &b);
            // One entry alone reads as it does among the others (up to the
            // first truncation, which ends the others).
            let mut signals = a.iter();
            let mut offset = 0usize;
            for (position, entry) in mapping.entries().iter().enumerate() {
                offset += usize::from(entry.bits());
                let Some(alone) = layout.read(position, &payload).map(bits) else {
                    prop_assert!(entry.is_dummy());
                    // A dummy takes no signal, but a payload too short for it
                    // ends the signals there.
                    if offset > payload.len() * 8 {
                        prop_assert!(matches!(signals.next(), Some(Err(_))));
                        break;
                    }
                    continue;
                };
                match signals.next() {
                    Some(Err(e)) => {
                        prop_assert_eq!(alone, Err(*e));
                        break;
                    }
                    Some(together) => prop_assert_eq!(&alone, together),
                    None => break,
                }
            }
        }

        /// A PDO read at any bit of a larger image reads as its own bits
        /// moved to bit 0, up to the first entry the image does not hold
        /// whole: that one is truncated, counting the PDO's bytes it needs
        /// and the image's whole bytes from the PDO's first bit.
        #[test]
        fn a_pdo_reads_the_same_at_any_bit(
            raw in proptest::collection::vec(any::<u32>(), 0..12),
            seed in type_lookup_seed(),
            image in proptest::collection::vec(any::<u8>(), 0..40),
            bit in 0usize..340,
        ) {
            let mut mapping = PdoMapping::new();
            for value in raw {
                // Short entries, so that the PDOs fit the images often.
                let entry = MappingEntry::from_u32((value & 0xFFFF_FF00) | ((value & 0x0F) + 1));
                if mapping.push(entry).is_err() {
                    break;
                }
            }
            let types = |entry: MappingEntry| data_type_for(seed, entry);
            let layout = PdoLayout::new(&mapping, types);
            // The PDO's bits from bit 0, those past the image as zeros.
            let len = usize::from(mapping.bit_len());
            let left = (image.len() * 8).saturating_sub(bit);
            let mut moved = vec![0u8; len.div_ceil(8)];
            for i in 0..len.min(left) {
                let at = bit + i;
                if image[at / 8] >> (at % 8) & 1 != 0 {
                    moved[i / 8] |= 1 << (i % 8);
                }
            }
            let same = |r: Result<Signal, PdoEntryError>| r.map(|s| match s.value {
                Value::Real32(x) => (s.entry, s.offset, Value::Unsigned(u64::from(x.to_bits()))),
                Value::Real64(x) => (s.entry, s.offset, Value::Unsigned(x.to_bits())),
                v => (s.entry, s.offset, v),
            });
            let mut alone = layout.unpack(&moved).map(same);
            let mut expected = Vec::new();
            let mut offset = 0u16;
            for &entry in mapping.entries() {
                let end = usize::from(offset) + usize::from(entry.bits());
                if end > left {
                    expected.push(Err(PdoEntryError {
                        entry,
                        offset,
                        reason: PdoEntryReason::Truncated { needed: end.div_ceil(8), found: left / 8 },
                    }));
                    break;
                }
                if !entry.is_dummy() {
                    expected.push(alone.next().unwrap());
                }
                offset += u16::from(entry.bits());
            }
            let at: Vec<_> = layout.unpack_at(&image, bit).map(same).collect();
            prop_assert_eq!(at, expected);
        }
    }
}
