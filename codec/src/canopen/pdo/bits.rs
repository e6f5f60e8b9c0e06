//! An entry's bits in a PDO payload: read and written little-endian, bit
//! by bit in mapping order, and decoded as or encoded from a [`Value`]
//! (CiA 301, PDO mapping; docs/canopen.md#signals).

use super::PdoEntryReason;
use crate::canopen::data_type::{Octets, Value, ValueKind, MAX_OCTETS};

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
fn read_bits(payload: &[u8], offset: usize, bits: u8) -> u64 {
    let start = offset / 8;
    // One bit (a digital channel, a flag): one byte.
    if bits == 1 {
        return u64::from(payload[start] >> (offset % 8) & 1);
    }
    // Fast path: an 8-byte word that holds the field — from its first byte,
    // or the payload's last 8 bytes when it starts less than 8 from the end.
    if payload.len() >= 8 {
        let word_start = start.min(payload.len() - 8);
        let shift = (offset - 8 * word_start) as u32;
        if shift + u32::from(bits) <= 64 {
            let mut word = [0u8; 8];
            word.copy_from_slice(&payload[word_start..word_start + 8]);
            return (u64::from_le_bytes(word) >> shift) & mask(bits);
        }
    }
    let shift = (offset % 8) as u32;
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
pub(super) fn decode(payload: &[u8], offset: usize, bits: u8, kind: ValueKind) -> Value {
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
                let done = 8 * i;
                let take = (usize::from(bits) - done).min(8) as u8;
                *byte = read_bits(payload, offset + done, take) as u8;
            }
            Value::Octets(Octets { bytes, bits })
        }
    }
}

/// Return whether an entry of `bits` bits at bit `offset`, read as `kind`,
/// is one that [`decode_aligned`] reads: a number of 1, 2, 4 or 8 whole
/// bytes from a byte boundary — most of a drive's process data.
pub(super) const fn is_aligned(offset: u16, bits: u8, kind: ValueKind) -> bool {
    offset % 8 == 0
        && match kind {
            ValueKind::Bool | ValueKind::Signed | ValueKind::Unsigned => {
                matches!(bits, 8 | 16 | 32 | 64)
            }
            ValueKind::Real32 => bits == 32,
            ValueKind::Real64 => bits == 64,
            ValueKind::Octets => false,
        }
}

/// Decode the entry of `bytes` whole bytes (1, 2, 4 or 8) at bit `offset`
/// as [`decode`] decodes it with `8 * bytes` bits, for an entry that
/// [`is_aligned`] (the caller has worked that out once per mapping): one
/// little-endian load, no bit window. An entry past the payload (which the
/// caller has excluded) goes to [`decode`].
#[inline(always)]
pub(super) fn decode_aligned(payload: &[u8], offset: usize, bytes: u8, kind: ValueKind) -> Value {
    let rest = payload.get(offset / 8..).unwrap_or(&[]);
    let raw = match bytes {
        1 => rest.first().map(|&b| u64::from(b)),
        2 => rest
            .first_chunk::<2>()
            .map(|b| u64::from(u16::from_le_bytes(*b))),
        4 => rest
            .first_chunk::<4>()
            .map(|b| u64::from(u32::from_le_bytes(*b))),
        _ => rest.first_chunk::<8>().map(|b| u64::from_le_bytes(*b)),
    };
    let bits = 8 * bytes;
    let Some(raw) = raw else {
        return decode(payload, offset, bits, kind);
    };
    match kind {
        ValueKind::Bool => Value::Bool(raw != 0),
        ValueKind::Unsigned => Value::Unsigned(raw),
        ValueKind::Signed => {
            let unused = 64 - u32::from(bits);
            Value::Signed(((raw << unused) as i64) >> unused)
        }
        ValueKind::Real32 => Value::Real32(f32::from_bits(raw as u32)),
        ValueKind::Real64 => Value::Real64(f64::from_bits(raw)),
        ValueKind::Octets => decode(payload, offset, bits, kind),
    }
}

/// Encode `value` as an entry of `kind` and `bits` bits at `offset`.
pub(super) fn encode(
    buf: &mut [u8],
    offset: u16,
    bits: u8,
    kind: ValueKind,
    value: Value,
) -> Result<(), PdoEntryReason> {
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
mod proptests {
    use proptest::prelude::*;

    use super::*;

    fn kind() -> impl Strategy<Value = ValueKind> {
        prop::sample::select(vec![
            ValueKind::Bool,
            ValueKind::Signed,
            ValueKind::Unsigned,
            ValueKind::Real32,
            ValueKind::Real64,
            ValueKind::Octets,
        ])
    }

    /// The same value, NaNs compared by their bits.
    fn same(a: Value, b: Value) -> bool {
        match (a, b) {
            (Value::Real32(x), Value::Real32(y)) => x.to_bits() == y.to_bits(),
            (Value::Real64(x), Value::Real64(y)) => x.to_bits() == y.to_bits(),
            (a, b) => a == b,
        }
    }

    proptest! {
        /// The one-load path reads what the bit window reads, for every
        /// entry that `is_aligned` lets it read and that lies inside the
        /// payload (whole bytes from a byte boundary; the others, drawn
        /// here too, are refused by `is_aligned`).
        #[test]
        fn aligned_reads_what_the_bit_window_reads(
            payload in proptest::collection::vec(any::<u8>(), 1..70),
            byte in 0usize..70,
            width in prop::sample::select(vec![1u8, 2, 4, 8]),
            kind in kind(),
            any_offset in any::<u16>(),
            any_bits in 1u8..=64,
        ) {
            let mut cases = vec![(8 * (byte % payload.len()) as u16, 8 * width)];
            cases.push((any_offset % (8 * payload.len() as u16), any_bits));
            for (offset, bits) in cases {
                let bits = match kind {
                    ValueKind::Real32 => 32,
                    ValueKind::Real64 => 64,
                    _ => bits,
                };
                if usize::from(offset) + usize::from(bits) > payload.len() * 8 {
                    continue;
                }
                if !is_aligned(offset, bits, kind) {
                    prop_assert!(offset % 8 != 0 || !matches!(bits, 8 | 16 | 32 | 64) || kind == ValueKind::Octets);
                    continue;
                }
                let fast = decode_aligned(&payload, usize::from(offset), bits / 8, kind);
                let general = decode(&payload, usize::from(offset), bits, kind);
                prop_assert!(same(fast, general), "{offset} {bits} {kind:?}: {fast:?} != {general:?}");
            }
        }
    }
}
