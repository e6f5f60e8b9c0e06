//! Strategies for PDO mappings and the values that fill them.

use proptest::prelude::*;

use crate::canopen::{DataType, MappingEntry, Octets, PdoMapping, Value, ValueKind};

/// A seed that picks a data type for each entry: the same seed and entry
/// always give the same type (so that a closure can be the lookup).
pub fn type_lookup_seed() -> impl Strategy<Value = u64> {
    any::<u64>()
}

/// The data type the seed gives an entry: `None` (untyped) or any basic
/// type, chosen by a hash of the seed and the entry.
#[must_use]
pub fn data_type_for(seed: u64, entry: MappingEntry) -> Option<DataType> {
    let h = (seed ^ u64::from(entry.to_u32())).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40;
    let pick = (h % (DataType::ALL.len() as u64 + 1)) as usize;
    DataType::ALL.get(pick).copied()
}

/// Any value of `kind` that fits `bits` bits.
fn value_for(kind: ValueKind, bits: u8) -> BoxedStrategy<Value> {
    match kind {
        ValueKind::Bool => any::<bool>().prop_map(Value::Bool).boxed(),
        ValueKind::Unsigned => any::<u64>()
            .prop_map(move |v| Value::Unsigned(if bits >= 64 { v } else { v & ((1 << bits) - 1) }))
            .boxed(),
        ValueKind::Signed => any::<i64>()
            .prop_map(move |v| {
                let unused = 64 - u32::from(bits);
                Value::Signed((v << unused) >> unused)
            })
            .boxed(),
        ValueKind::Real32 => any::<u32>()
            .prop_map(|b| Value::Real32(f32::from_bits(b)))
            .boxed(),
        ValueKind::Real64 => any::<u64>()
            .prop_map(|b| Value::Real64(f64::from_bits(b)))
            .boxed(),
        ValueKind::Octets => {
            let len = usize::from(bits).div_ceil(8);
            proptest::collection::vec(any::<u8>(), len)
                .prop_map(move |bytes| {
                    Value::Octets(Octets::new(&bytes, bits).expect("right length"))
                })
                .boxed()
        }
    }
}

/// Any mapping whose entries all read with the seed's types (lengths chosen
/// to suit each type, dummies included), with a value for each entry that
/// is not a dummy.
pub fn mapping_and_values() -> impl Strategy<Value = (PdoMapping, u64, Vec<Value>)> {
    (
        type_lookup_seed(),
        proptest::collection::vec((any::<u16>(), any::<u8>(), 1u8..=80), 0..20),
    )
        .prop_flat_map(|(seed, raw)| {
            let mut mapping = PdoMapping::new();
            let mut kinds = Vec::new();
            for (index, sub, bits) in raw {
                let entry = MappingEntry::new(index, sub, bits);
                let data_type = data_type_for(seed, entry);
                let bits = match data_type {
                    Some(DataType::Real32) => 32,
                    Some(DataType::Real64) => 64,
                    Some(t) if t.bits().is_some() => bits.min(64),
                    _ => bits,
                };
                let entry = MappingEntry::new(index, sub, bits);
                // The type depends on the entry: recompute with the final length.
                let data_type = data_type_for(seed, entry);
                let Ok(kind) = ValueKind::for_entry(data_type, bits) else {
                    continue;
                };
                if mapping.push(entry).is_err() {
                    break;
                }
                if !entry.is_dummy() {
                    kinds.push((kind, bits));
                }
            }
            let values: Vec<_> = kinds
                .into_iter()
                .map(|(kind, bits)| value_for(kind, bits))
                .collect();
            (Just(mapping), Just(seed), values)
        })
}
