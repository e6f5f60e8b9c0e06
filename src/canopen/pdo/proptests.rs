//! Property tests of the PDO codecs: any mapping and values pack and
//! unpack back to themselves; any bytes unpack without panicking.

use proptest::prelude::*;

use super::*;
use crate::test_gens::pdo::{data_type_for, mapping_and_values, type_lookup_seed};

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
            .collect::<Result<_>>()
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
                Err(Error::PdoEntry(PdoEntryError { reason: PdoEntryReason::Truncated { needed, found }, .. })) => {
                    truncated += 1;
                    prop_assert!(needed > found);
                    prop_assert_eq!(found, payload.len());
                }
                Err(Error::PdoEntry(PdoEntryError { reason: PdoEntryReason::BadLength { .. }, .. })) => {}
                Err(other) => prop_assert!(false, "unexpected {:?}", other),
            }
        }
        prop_assert!(truncated <= 1);
        prop_assert!(count <= mapping.len());
        prop_assert_eq!(truncated == 1, payload.len() < mapping.byte_len());
        // Untyped: every entry reads.
        for item in mapping.unpack(&payload) {
            if let Err(e) = item {
                let truncated = matches!(e, Error::PdoEntry(PdoEntryError { reason: PdoEntryReason::Truncated { .. }, .. }));
                prop_assert!(truncated);
            }
        }
    }
}

proptest! {
    /// A layout reads exactly what the mapping reads with the same types,
    /// on any mapping and any bytes (NaNs compared by bits).
    #[test]
    fn layout_reads_what_the_mapping_reads(
        raw in proptest::collection::vec(any::<u32>(), 0..70),
        seed in type_lookup_seed(),
        payload in proptest::collection::vec(any::<u8>(), 0..70),
    ) {
        let mut mapping = PdoMapping::new();
        for value in raw {
            if mapping.push(MappingEntry::from_u32(value)).is_err() {
                break;
            }
        }
        let types = |entry: MappingEntry| data_type_for(seed, entry);
        let layout = PdoLayout::new(&mapping, types);
        let bits = |r: Result<Signal>| r.map(|s| match s.value {
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
}
