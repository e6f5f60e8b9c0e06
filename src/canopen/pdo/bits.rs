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
pub(super) fn decode(payload: &[u8], offset: u16, bits: u8, kind: ValueKind) -> Value {
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
