//! Unit tests of the PDO codecs, as tables from CiA 301 and SPEC §8.

use super::*;

#[test]
fn data_types_follow_cia301_table_44() {
    // (index, name, bits) as CiA 301 Table 44 lists them.
    let table: &[(u16, &str, Option<u8>)] = &[
        (0x0001, "BOOLEAN", Some(1)),
        (0x0002, "INTEGER8", Some(8)),
        (0x0003, "INTEGER16", Some(16)),
        (0x0004, "INTEGER32", Some(32)),
        (0x0005, "UNSIGNED8", Some(8)),
        (0x0006, "UNSIGNED16", Some(16)),
        (0x0007, "UNSIGNED32", Some(32)),
        (0x0008, "REAL32", Some(32)),
        (0x0009, "VISIBLE_STRING", None),
        (0x000A, "OCTET_STRING", None),
        (0x000B, "UNICODE_STRING", None),
        (0x000C, "TIME_OF_DAY", Some(48)),
        (0x000D, "TIME_DIFFERENCE", Some(48)),
        (0x000F, "DOMAIN", None),
        (0x0010, "INTEGER24", Some(24)),
        (0x0011, "REAL64", Some(64)),
        (0x0012, "INTEGER40", Some(40)),
        (0x0013, "INTEGER48", Some(48)),
        (0x0014, "INTEGER56", Some(56)),
        (0x0015, "INTEGER64", Some(64)),
        (0x0016, "UNSIGNED24", Some(24)),
        (0x0018, "UNSIGNED40", Some(40)),
        (0x0019, "UNSIGNED48", Some(48)),
        (0x001A, "UNSIGNED56", Some(56)),
        (0x001B, "UNSIGNED64", Some(64)),
    ];
    assert_eq!(table.len(), DataType::ALL.len());
    for (&(index, name, bits), &data_type) in table.iter().zip(DataType::ALL.iter()) {
        assert_eq!(DataType::from_index(index), Some(data_type), "{index:#06x}");
        assert_eq!(data_type.index(), index);
        assert_eq!(data_type.name(), name);
        assert_eq!(data_type.to_string(), name);
        assert_eq!(data_type.bits(), bits, "{name}");
        assert_eq!(data_type.is_signed(), name.starts_with("INTEGER"), "{name}");
    }
    for index in [0x0000, 0x000E, 0x0017, 0x001C, 0x0020, 0xFFFF] {
        assert_eq!(DataType::from_index(index), None);
        assert_eq!(
            DataType::try_from(index),
            Err(Error::InvalidValue {
                what: What::DataType,
                found: u32::from(index),
                expected: "0x0001..=0x000D, 0x000F..=0x0016, 0x0018..=0x001B",
            })
        );
    }
}

#[test]
fn cob_id_bits() {
    // CiA 301 Table 71: bit 31 valid, bit 30 RTR, bit 29 frame.
    let table: &[(u32, bool, bool, bool, u32)] = &[
        (0x0000_0181, true, true, false, 0x181),
        (0x8000_0181, false, true, false, 0x181),
        (0x4000_0281, true, false, false, 0x281),
        (0xC000_0381, false, false, false, 0x381),
        (0x2012_3456, true, true, true, 0x0012_3456),
        (0x0000_F981, true, true, false, 0x181), // bits 11–28 ignored for 11-bit
    ];
    for &(raw, valid, rtr, extended, id) in table {
        let cob_id = PdoCobId::from_u32(raw);
        assert_eq!(cob_id.is_valid(), valid, "{raw:#x}");
        assert_eq!(cob_id.rtr_allowed(), rtr, "{raw:#x}");
        assert_eq!(cob_id.is_extended(), extended, "{raw:#x}");
        assert_eq!(cob_id.can_id().map(CanId::raw), Some(id), "{raw:#x}");
        assert_eq!(u32::from(cob_id), raw);
    }
    let id = CanId::standard(0x185).unwrap();
    assert_eq!(PdoCobId::new(id, true).to_u32(), 0x185);
    assert_eq!(PdoCobId::new(id, false).to_u32(), 0x4000_0185);
    let ext = CanId::extended(0x1ABC_DEF0).unwrap();
    assert_eq!(PdoCobId::new(ext, true).to_u32(), 0x3ABC_DEF0);
}

#[test]
fn transmission_types() {
    use TransmissionKind::*;
    let table: &[(u8, TransmissionKind, Option<u8>, bool)] = &[
        (0, SynchronousAcyclic, None, true),
        (1, SynchronousCyclic, Some(1), true),
        (240, SynchronousCyclic, Some(240), true),
        (241, Reserved, None, false),
        (251, Reserved, None, false),
        (252, RtrSynchronous, None, true),
        (253, RtrEventDriven, None, false),
        (254, EventDrivenManufacturer, None, false),
        (255, EventDrivenProfile, None, false),
    ];
    for &(byte, kind, interval, sync) in table {
        let t = TransmissionType::from_byte(byte);
        assert_eq!(t.kind(), kind, "{byte}");
        assert_eq!(t.sync_interval(), interval, "{byte}");
        assert_eq!(t.is_synchronous(), sync, "{byte}");
        assert_eq!(u8::from(t), byte);
    }
    assert_eq!(EventDrivenProfile.to_string(), "event_driven_profile");
}

#[test]
fn times_are_durations() {
    assert_eq!(InhibitTime::from_raw(0).duration(), Duration::ZERO);
    assert_eq!(
        InhibitTime::from_raw(u16::MAX).duration(),
        Duration::from_micros(6_553_500)
    );
    assert_eq!(EventTimer::from_raw(0).duration(), None);
    assert_eq!(
        EventTimer::from_raw(500).duration(),
        Some(Duration::from_millis(500))
    );
}

#[test]
fn mapping_limits() {
    let mut mapping = PdoMapping::new();
    assert!(mapping.is_empty());
    assert_eq!(
        mapping.push(MappingEntry::new(0x6041, 0, 0)),
        Err(Error::OutOfRange {
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
        Err(Error::OutOfRange {
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
        Err(Error::OutOfRange {
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
        Err(Error::PdoEntry(PdoEntryError {
            entry: MappingEntry::from_u32(0x3000_0010),
            offset: 0,
            reason: PdoEntryReason::BadLength {
                data_type: DataType::Real32,
                bits: 16
            }
        }))
    );
    assert_eq!(
        items[0].unwrap_err().to_string(),
        "PDO entry 3000sub0 (16 bits) at bit 0: expected 32 bits for REAL32, found 16"
    );
    assert!(matches!(
        items[1],
        Err(Error::PdoEntry(PdoEntryError {
            offset: 16,
            reason: PdoEntryReason::BadLength { bits: 72, .. },
            ..
        }))
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
        Err(Error::PdoEntry(PdoEntryError {
            entry: MappingEntry::from_u32(0x0001_0001),
            offset: 24,
            reason: PdoEntryReason::Truncated {
                needed: 4,
                found: 3
            }
        }))
    );
}

#[test]
fn octets_for_strings_and_long_entries() {
    let types = |entry: MappingEntry| (entry.index() == 0x2008).then_some(DataType::VisibleString);
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
        Err(Error::Length {
            what: What::PdoPayload,
            expected: 2,
            found: 1
        })
    );
    let entry = MappingEntry::from_u32(0x2001_0008);
    assert_eq!(
        m.pack_with(types, [Value::Signed(1)], &mut buf),
        Err(Error::PdoEntry(PdoEntryError {
            entry,
            offset: 8,
            reason: PdoEntryReason::MissingValue
        }))
    );
    assert_eq!(
        m.pack_with(types, [Value::Signed(1), Value::Signed(128)], &mut buf),
        Err(Error::PdoEntry(PdoEntryError {
            entry,
            offset: 8,
            reason: PdoEntryReason::ValueTooWide { bits: 8 }
        }))
    );
    assert_eq!(
        m.pack_with(types, [Value::Signed(1), Value::Unsigned(1)], &mut buf),
        Err(Error::PdoEntry(PdoEntryError {
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
        Err(Error::OutOfRange {
            what: What::PdoValues,
            found: 3,
            min: 2,
            max: 2
        })
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
        [Err(Error::PdoEntry(PdoEntryError {
            entry: MappingEntry::from_u32(0x6041_0010),
            offset: 0,
            reason: PdoEntryReason::Truncated {
                needed: 2,
                found: 0
            }
        }))]
    );
}
