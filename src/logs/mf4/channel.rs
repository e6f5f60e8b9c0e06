//! One channel of a record: where its bits are and how they convert
//! (ASAM MDF 4.1 §5.13 CN, §5.16 CC; docs/formats.md#mf4): a member is its
//! bits, read through its CC.

/// Data types of a CN (`cn_data_type`), those a CAN member may have.
mod data_type {
    pub(super) const UINT_LE: u8 = 0;
    pub(super) const UINT_BE: u8 = 1;
    pub(super) const INT_LE: u8 = 2;
    pub(super) const INT_BE: u8 = 3;
    pub(super) const FLOAT_LE: u8 = 4;
    pub(super) const FLOAT_BE: u8 = 5;
}

use crate::logs::bytes::padded;

/// Where a channel's value comes from.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Location {
    /// Bits of the record (after the record id): byte and bit offset, bit
    /// count, data type.
    Bits {
        byte: u32,
        bit: u8,
        bits: u32,
        data_type: u8,
    },
    /// A virtual channel (cn_type 3 or 6): the record's index in its
    /// channel group, through the conversion.
    Index,
}

/// A conversion (CC) as the reader applies it.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Conversion {
    /// cc_type 0, or none.
    Identity,
    /// cc_type 1: `b + a·x` (cc_val `[b, a]`).
    Linear { a: f64, b: f64 },
    /// cc_type 2: `(p1·x² + p2·x + p3) / (p4·x² + p5·x + p6)`.
    Rational([f64; 6]),
    /// cc_type 4 (interpolated) and 5: keys and values, keys ascending.
    Table {
        pairs: Vec<(f64, f64)>,
        interpolate: bool,
    },
    /// cc_type 6: `[min, max] → value` ranges and a default.
    Ranges {
        ranges: Vec<(f64, f64, f64)>,
        default: f64,
    },
    /// cc_type 7, value to text, as `Dir` uses it (docs/formats.md#mf4): each
    /// key with whether its text is `Tx` (1) or not (0), and the default's.
    Text { keys: Vec<(f64, f64)>, default: f64 },
}

impl Conversion {
    /// Apply the conversion to `x`.
    pub(super) fn apply(&self, x: f64) -> f64 {
        match self {
            Conversion::Identity => x,
            Conversion::Linear { a, b } => b + a * x,
            Conversion::Rational([p1, p2, p3, p4, p5, p6]) => {
                let below = p4 * x * x + p5 * x + p6;
                if below == 0.0 {
                    0.0
                } else {
                    (p1 * x * x + p2 * x + p3) / below
                }
            }
            Conversion::Table { pairs, interpolate } => table(pairs, *interpolate, x),
            Conversion::Ranges { ranges, default } => ranges
                .iter()
                .find(|(min, max, _)| (*min..=*max).contains(&x))
                .map_or(*default, |&(_, _, value)| value),
            Conversion::Text { keys, default } => keys
                .iter()
                .find(|(key, _)| *key == x)
                .map_or(*default, |&(_, value)| value),
        }
    }

    /// Return whether the conversion leaves every value as it is.
    #[inline]
    pub(super) fn is_identity(&self) -> bool {
        match self {
            Conversion::Identity => true,
            Conversion::Linear { a, b } => *a == 1.0 && *b == 0.0,
            _ => false,
        }
    }
}

/// A value-to-value table, as asammdf reads it: below the first key the
/// first value, above the last the last; between two keys the nearer
/// key's value (the lower on a tie), or the line between them when
/// interpolated.
fn table(pairs: &[(f64, f64)], interpolate: bool, x: f64) -> f64 {
    let Some(&(first_key, first)) = pairs.first() else {
        return x;
    };
    if x <= first_key {
        return first;
    }
    for window in pairs.windows(2) {
        let [(k0, v0), (k1, v1)] = [window[0], window[1]];
        if x == k1 {
            return v1;
        }
        if x < k1 {
            return if interpolate && k1 > k0 {
                v0 + (v1 - v0) * (x - k0) / (k1 - k0)
            } else if x - k0 <= k1 - x {
                v0
            } else {
                v1
            };
        }
    }
    pairs.last().map_or(x, |&(_, value)| value)
}

/// A channel: where it is and how it converts.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Channel {
    pub(super) location: Location,
    pub(super) conversion: Conversion,
}

/// A raw value as stored.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Raw {
    Unsigned(u64),
    Signed(i64),
    Float(f64),
}

impl Channel {
    /// Return the raw bits of the channel in `record` (the bytes after the
    /// record id); `index` is the record's index in its channel group, for
    /// a virtual channel. `None` when the record is too short.
    #[inline]
    fn raw(&self, record: &[u8], index: u64) -> Option<Raw> {
        let Location::Bits {
            byte,
            bit,
            bits,
            data_type,
        } = self.location
        else {
            return Some(Raw::Unsigned(index));
        };
        let bits = bits.min(64);
        if bit > 7 {
            // ASAM MDF 4.1: the bit offset is 0 to 7.
            return None;
        }
        let bit = u32::from(bit);
        let start = byte as usize;
        if data_type == data_type::UINT_LE && bit + bits <= 64 {
            // The common case: an unsigned little-endian field read as one
            // word (of the record's bytes from `start`, zeros past them).
            let needed = (bit + bits).div_ceil(8) as usize;
            let rest = record.get(start..)?;
            if rest.len() < needed {
                return None;
            }
            let word = match rest.first_chunk::<8>() {
                Some(word) => u64::from_le_bytes(*word),
                None => u64::from_le_bytes(padded(rest, 0)),
            };
            let value = if bits == 0 {
                0
            } else {
                (word >> bit) & (u64::MAX >> (64 - bits))
            };
            return Some(Raw::Unsigned(value));
        }
        let len = (bit + bits).div_ceil(8) as usize;
        let bytes = record.get(start..start.checked_add(len)?)?;
        let big_endian = matches!(
            data_type,
            data_type::UINT_BE | data_type::INT_BE | data_type::FLOAT_BE
        );
        let mut wide = [0u8; 16];
        wide[..len].copy_from_slice(bytes);
        let word = if big_endian {
            wide[..len].reverse();
            u128::from_le_bytes(wide)
        } else {
            u128::from_le_bytes(wide)
        };
        let mask = if bits == 64 {
            u64::MAX
        } else {
            (1u64 << bits) - 1
        };
        let value = (word >> bit) as u64 & mask;
        Some(match data_type {
            data_type::INT_LE | data_type::INT_BE if bits > 0 && bits < 64 => {
                let shift = 64 - bits;
                Raw::Signed(((value << shift) as i64) >> shift)
            }
            data_type::INT_LE | data_type::INT_BE => Raw::Signed(value as i64),
            data_type::FLOAT_LE | data_type::FLOAT_BE if bits == 32 => {
                Raw::Float(f64::from(f32::from_bits(value as u32)))
            }
            data_type::FLOAT_LE | data_type::FLOAT_BE if bits == 64 => {
                Raw::Float(f64::from_bits(value))
            }
            _ => Raw::Unsigned(value),
        })
    }

    /// Return the channel's value, converted.
    #[inline]
    pub(super) fn value(&self, record: &[u8], index: u64) -> Option<f64> {
        let x = match self.raw(record, index)? {
            Raw::Unsigned(v) => v as f64,
            Raw::Signed(v) => v as f64,
            Raw::Float(v) => v,
        };
        Some(self.conversion.apply(x))
    }

    /// Return the channel's value as an unsigned integer: the raw bits when
    /// the conversion changes nothing, else the converted value rounded
    /// (0 below 0, saturated above).
    #[inline]
    pub(super) fn unsigned(&self, record: &[u8], index: u64) -> Option<u64> {
        if self.conversion.is_identity() {
            if let Some(Raw::Unsigned(v)) = self.raw(record, index) {
                return Some(v);
            }
        }
        let value = self.value(record, index)?;
        Some(if value.is_nan() || value <= 0.0 {
            0
        } else {
            value.round() as u64
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bits(byte: u32, bit: u8, bits: u32, data_type: u8) -> Channel {
        Channel {
            location: Location::Bits {
                byte,
                bit,
                bits,
                data_type,
            },
            conversion: Conversion::Identity,
        }
    }

    #[test]
    fn bit_fields_as_canedge_packs_them() {
        // CANedge: IDE bit 0, ID bits 3..32 of byte 8 (here 0).
        let record = (0x1234_5678u32 << 3 | 1).to_le_bytes();
        assert_eq!(bits(0, 0, 1, 0).unsigned(&record, 0), Some(1));
        assert_eq!(bits(0, 3, 29, 0).unsigned(&record, 0), Some(0x1234_5678));
        // Past the record: nothing.
        assert_eq!(bits(2, 0, 32, 0).unsigned(&record, 0), None);
        // A signed byte; a float.
        assert_eq!(bits(0, 0, 8, 2).value(&[0xFE], 0), Some(-2.0));
        assert_eq!(bits(0, 0, 64, 4).value(&1.5f64.to_le_bytes(), 0), Some(1.5));
        assert_eq!(bits(0, 0, 32, 5).value(&2.5f32.to_be_bytes(), 0), Some(2.5));
        assert_eq!(bits(0, 0, 16, 1).unsigned(&[0x12, 0x34], 0), Some(0x1234));
    }

    #[test]
    fn conversions() {
        let linear = Conversion::Linear { a: 0.0, b: 9.0 };
        assert_eq!(linear.apply(1234.0), 9.0);
        // CANedge's DataLength: DLC 9..15 to 12..64.
        let dlc = Conversion::Table {
            pairs: (0..=8)
                .map(|n| (f64::from(n), f64::from(n)))
                .chain([(9.0, 12.0), (10.0, 16.0), (15.0, 64.0)])
                .collect(),
            interpolate: false,
        };
        assert_eq!(dlc.apply(9.0), 12.0);
        assert_eq!(dlc.apply(15.0), 64.0);
        assert_eq!(dlc.apply(99.0), 64.0);
        let text = Conversion::Text {
            keys: vec![(0.0, 0.0), (1.0, 1.0)],
            default: 0.0,
        };
        assert_eq!(text.apply(1.0), 1.0);
        assert_eq!(text.apply(7.0), 0.0);
    }
}
