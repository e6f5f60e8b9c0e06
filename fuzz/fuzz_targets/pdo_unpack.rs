//! PDO mappings and payloads (docs/canopen.md#pdo-mappings,
//! docs/canopen.md#signals): `PdoMapping::push`, `unpack`, `unpack_with` and
//! `pack_with`.
//!
//! Input: a count byte n (modulo 80), n little-endian `u32` mapping entries,
//! an 8-byte seed that picks each entry's data type (or none), then the
//! payload. Invariants:
//! - `push` refuses exactly length 0, a 65th entry and more than 512 bits,
//!   and leaves the mapping unchanged then;
//! - unpacking never panics; every signal lies inside the payload and is
//!   no dummy; at most one `Truncated` error, exactly when the payload is
//!   shorter than the mapping, and nothing after it; other errors are the
//!   `BadLength` of `ValueKind::for_entry`;
//! - when every entry reads, packing the signals gives the payload's bytes
//!   with the dummy bits and the bits past the mapping cleared (boolean
//!   entries of more than one bit aside: they pack as 0 or 1).
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    DataType, MappingEntry, PdoEntryError, PdoEntryReason, PdoMapping, Value, ValueKind,
    MAX_MAPPING_ENTRIES, MAX_PDO_BITS,
};
use motionwire_fuzz::Reader;

fn data_type_for(seed: u64, entry: MappingEntry) -> Option<DataType> {
    let h = (seed ^ u64::from(entry.to_u32())).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40;
    DataType::ALL
        .get((h % (DataType::ALL.len() as u64 + 1)) as usize)
        .copied()
}

fuzz_target!(|data: &[u8]| {
    let mut reader = Reader::new(data);
    let Some(count) = reader.u8() else { return };
    let mut mapping = PdoMapping::new();
    for _ in 0..count % 80 {
        let Some(raw) = reader.u32() else { return };
        let entry = MappingEntry::from_u32(raw);
        let before = mapping;
        let result = mapping.push(entry);
        let refuse = entry.bits() == 0
            || before.len() == MAX_MAPPING_ENTRIES
            || before.bit_len() + u16::from(entry.bits()) > MAX_PDO_BITS;
        assert_eq!(result.is_err(), refuse, "{entry}");
        if refuse {
            assert_eq!(mapping, before);
        } else {
            assert_eq!(mapping.entries().last(), Some(&entry));
        }
    }
    let seed = reader.u64().unwrap_or(0);
    let payload = reader.rest();
    let types = |entry: MappingEntry| data_type_for(seed, entry);

    let mut values = Vec::new();
    let mut all_read = true;
    let mut truncated = false;
    for item in mapping.unpack_with(payload, types) {
        assert!(!truncated, "an item after Truncated");
        match item {
            Ok(signal) => {
                assert!(!signal.entry.is_dummy());
                assert!(
                    usize::from(signal.offset) + usize::from(signal.entry.bits())
                        <= payload.len() * 8
                );
                assert_eq!(signal.data_type, types(signal.entry));
                values.push(signal.value);
            }
            Err(PdoEntryError {
                reason: PdoEntryReason::Truncated { needed, found },
                ..
            }) => {
                assert!(needed > found && found == payload.len());
                truncated = true;
                all_read = false;
            }
            Err(PdoEntryError {
                entry,
                reason: PdoEntryReason::BadLength { data_type, bits },
                ..
            }) => {
                assert_eq!(Some(data_type), types(entry));
                assert_eq!(bits, entry.bits());
                assert!(ValueKind::for_entry(Some(data_type), bits).is_err());
                all_read = false;
            }
            Err(other) => panic!("unexpected {other:?}"),
        }
    }
    assert_eq!(truncated, payload.len() < mapping.byte_len());
    for item in mapping.unpack(payload) {
        if let Err(e) = item {
            assert!(matches!(
                e,
                PdoEntryError {
                    reason: PdoEntryReason::Truncated { .. },
                    ..
                }
            ));
            let _ = e.to_string();
        }
    }
    if !all_read {
        return;
    }

    // Pack back; compare with the payload's mapped bits.
    let mut buf = [0u8; 64];
    let len = mapping
        .pack_with(types, values.iter().copied(), &mut buf)
        .expect("values read from the mapping pack");
    assert_eq!(len, mapping.byte_len());
    let mut offset = 0usize;
    for &entry in mapping.entries() {
        let bits = usize::from(entry.bits());
        let multi_bit_bool =
            bits > 1 && ValueKind::for_entry(types(entry), entry.bits()) == Ok(ValueKind::Bool);
        for bit in offset..offset + bits {
            let got = buf[bit / 8] >> (bit % 8) & 1;
            let want = if entry.is_dummy() {
                0
            } else {
                payload[bit / 8] >> (bit % 8) & 1
            };
            if !multi_bit_bool {
                assert_eq!(got, want, "bit {bit} of {entry}");
            }
        }
        offset += bits;
    }
    for bit in offset..len * 8 {
        assert_eq!(buf[bit / 8] >> (bit % 8) & 1, 0);
    }
    let _ = values.iter().map(Value::to_string).count();
});
