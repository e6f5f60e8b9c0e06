//! Unit tests of the EDS reader: CiA 306's forms, each a case, and
//! property tests over any text.

use super::*;
use crate::canopen::Value;

fn n(raw: u8) -> Option<NodeId> {
    NodeId::new(raw)
}

const DRIVE: &str = "\
[DeviceComissioning]
NodeID=0x10

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0x00020192

[1400]
ParameterName=RPDO 1 communication parameter
ObjectType=0x9
SubNumber=3

[1400sub1]
ParameterName=COB-ID used by RPDO
DataType=0x0007
AccessType=rw
DefaultValue=0x200+$NODEID

[1400sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=rw
DefaultValue=255

[1600]
ParameterName=RPDO 1 mapping parameter
ObjectType=0x9

[1600sub0]
ParameterName=Number of mapped objects
DataType=0x0005
AccessType=rw
DefaultValue=1
ParameterValue=2

[1600sub1]
ParameterName=Mapping entry 1
DataType=0x0007
AccessType=rw
DefaultValue=0x60400010

[1600sub2]
ParameterName=Mapping entry 2
DataType=0x0007
AccessType=rw
DefaultValue=0
ParameterValue=0x60600008

[1800]
ParameterName=TPDO 1 communication parameter
ObjectType=0x9

[1800sub1]
ParameterName=COB-ID used by TPDO
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x40000180

[1800sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=rw
DefaultValue=1

[1800sub3]
ParameterName=Inhibit time
DataType=0x0006
AccessType=rw
DefaultValue=010

[1800sub5]
ParameterName=Event timer
DataType=0x0006
AccessType=rw
DefaultValue=100

[1A00]
ParameterName=TPDO 1 mapping parameter
ObjectType=0x9

[1A00sub0]
ParameterName=Number of mapped objects
DataType=0x0005
AccessType=rw
DefaultValue=4

[1A00sub1]
ParameterName=Mapping entry 1
DataType=0x0007
AccessType=rw
DefaultValue=0x60410010

[1A00sub2]
ParameterName=Mapping entry 2
DataType=0x0007
AccessType=rw
DefaultValue=0x00050008

[1A00sub3]
ParameterName=Mapping entry 3
DataType=0x0007
AccessType=rw
DefaultValue=0x20010120

[1a00SUB4]
ParameterName=Mapping entry 4
DataType=0x0007
AccessType=rw
DefaultValue=0x30000110

[2001]
ParameterName=Velocity record
ObjectType=0x9

[2001sub1]
ParameterName=Velocity
DataType=0x0004
AccessType=ro
PDOMapping=1

[6040]
ParameterName=Controlword
DataType=0x0006
AccessType=rww
PDOMapping=1

[6041]
ParameterName=Statusword
DataType=0x0006
AccessType=ro
PDOMapping=1

[6060]
ParameterName=Modes of operation
DataType=0x0002
AccessType=rw
PDOMapping=1
";

#[test]
fn drive_objects_and_pdos() {
    let eds = Eds::parse(DRIVE, "drive.eds", None).unwrap();
    assert_eq!(eds.node(), n(0x10));
    assert_eq!(eds.file(), "drive.eds");
    assert_eq!(eds.device_type(), Some(0x0002_0192));
    assert!(eds.is_cia402());
    assert_eq!(eds.name(0x2001, 1), Some("Velocity record.Velocity"));
    assert_eq!(eds.name(0x6041, 0), Some("Statusword"));
    assert_eq!(eds.data_type(0x6060, 0), Some(DataType::Integer8));
    let e = eds.entry(0x6040, 0).unwrap();
    assert_eq!(e.access_type, Some(AccessType::ReadWriteWrite));
    assert!(e.pdo_mapping);
    assert_eq!(e.line, 124);
    // ParameterValue wins; DefaultValue kept.
    let sub0 = eds.entry(0x1600, 0).unwrap();
    assert_eq!(sub0.value(), Some(&EdsValue::Unsigned(2)));
    assert_eq!(sub0.default_value, Some(EdsValue::Unsigned(1)));
    // Octal 010 = 8.
    assert_eq!(eds.value(0x1800, 3), Some(&EdsValue::Unsigned(8)));

    let pdos = eds.pdos().unwrap();
    assert_eq!(pdos.len(), 2);
    let rpdo = &pdos[0];
    assert_eq!((rpdo.direction, rpdo.number), (PdoDirection::Receive, 1));
    assert_eq!(rpdo.communication.cob_id.to_u32(), 0x210);
    assert_eq!(
        rpdo.communication.transmission_type,
        Some(TransmissionType::EVENT_DRIVEN_PROFILE)
    );
    assert_eq!(
        rpdo.mapping.entries(),
        [
            MappingEntry::from_u32(0x6040_0010),
            MappingEntry::from_u32(0x6060_0008)
        ]
    );
    let tpdo = &pdos[1];
    assert_eq!((tpdo.direction, tpdo.number), (PdoDirection::Transmit, 1));
    assert_eq!(tpdo.communication.cob_id.to_u32(), 0x4000_0190);
    assert_eq!(
        tpdo.communication.inhibit_time,
        Some(InhibitTime::from_raw(8))
    );
    assert_eq!(
        tpdo.communication.event_timer,
        Some(EventTimer::from_raw(100))
    );
    assert_eq!(tpdo.mapping.len(), 4);
    assert_eq!(tpdo.mapping.bit_len(), 16 + 8 + 32 + 16);
    let names: Vec<_> = tpdo.signals.iter().map(|s| s.name.as_deref()).collect();
    assert_eq!(
        names,
        [Some("Statusword"), Some("Velocity record.Velocity"), None]
    );
    let payload = [0x37, 0x02, 0xEE, 0xFE, 0xFF, 0xFF, 0xFF, 0x34, 0x12];
    let values: Vec<_> = tpdo.unpack(&payload).map(|s| s.unwrap().value).collect();
    assert_eq!(
        values,
        [
            Value::Unsigned(0x237),
            Value::Signed(-2),
            Value::Unsigned(0x1234)
        ]
    );
}

#[test]
fn the_given_node_wins_over_commissioning() {
    let eds = Eds::parse(DRIVE, "drive.eds", n(3)).unwrap();
    assert_eq!(eds.value(0x1400, 1), Some(&EdsValue::Unsigned(0x203)));
}

#[test]
fn compact_sub_objects() {
    let text = "\
[3004]
ParameterName=Sensor Status
ObjectType=8
DataType=0x0006
AccessType=ro
DefaultValue=3
CompactSubObj=3

[3004Name]
NrOfEntries=2
1=Sensor Status 1
3=Sensor Status 3

[3004Value]
NrOfEntries=1
2=0x10
";
    let eds = Eds::parse(text, "c.eds", None).unwrap();
    assert_eq!(eds.name(0x3004, 0), Some("Sensor Status.Number of entries"));
    assert_eq!(eds.value(0x3004, 0), Some(&EdsValue::Unsigned(3)));
    assert_eq!(eds.name(0x3004, 1), Some("Sensor Status.Sensor Status 1"));
    assert_eq!(eds.name(0x3004, 2), Some("Sensor Status.Sensor Status2"));
    assert_eq!(eds.value(0x3004, 1), Some(&EdsValue::Unsigned(3)));
    assert_eq!(eds.value(0x3004, 2), Some(&EdsValue::Unsigned(0x10)));
    assert_eq!(eds.data_type(0x3004, 3), Some(DataType::Unsigned16));
    assert!(eds.entry(0x3004, 4).is_none());
}

#[test]
fn errors_name_file_line_section_key() {
    let cases: &[(&str, &str)] = &[
        ("[1000]\nDataType=7\n", "x.eds:1: [1000] ParameterName: the key is missing"),
        (
            "[1000]\nParameterName=a\nDataType=0x\n",
            "x.eds:3: [1000] DataType: expected a decimal, 0x hex or octal number or a $NODEID expression, found \"0x\"",
        ),
        (
            "[1000]\nParameterName=a\nDataType=7\nDefaultValue=$NODEID+1\n",
            "x.eds:4: [1000] DefaultValue: $NODEID with no node-ID given and none in [DeviceComissioning] NodeID",
        ),
        (
            "[1000]\nParameterName=a\nDataType=5\nDefaultValue=256\n",
            "x.eds:4: [1000] DefaultValue: \"256\" is out of range for its data type",
        ),
        (
            "[1000]\nParameterName=a\nObjectType=3\n",
            "x.eds:3: [1000] ObjectType: expected an object type 0x0, 0x2, 0x5, 0x6, 0x7, 0x8 or 0x9, found \"3\"",
        ),
        (
            "[1000]\nParameterName=a\nAccessType=rx\n",
            "x.eds:3: [1000] AccessType: expected an access type ro, wo, rw, rwr, rww or const, found \"rx\"",
        ),
        (
            "[1000sub1]\nParameterName=a\n",
            "x.eds:1: [1000sub1]: a sub-index section without its object's section",
        ),
        ("[1000]\nParameterName=a\nx\n", "x.eds:3: [1000]: expected a [section], a key=value line or a ; comment"),
        (
            "[1000]\nParameterName=a\n[1000]\n",
            "x.eds:3: [1000]: section already written at line 1",
        ),
    ];
    for (text, message) in cases {
        let e = Eds::parse(text, "x.eds", None).unwrap_err();
        assert_eq!(&e.to_string(), message, "{text:?}");
    }
}

#[test]
fn pdo_errors() {
    let text = "\
[1800]
ParameterName=TPDO 1
ObjectType=9

[1800sub2]
ParameterName=Transmission type
DataType=5
DefaultValue=1
";
    let eds = Eds::parse(text, "p.eds", None).unwrap();
    assert_eq!(
        eds.pdos().unwrap_err().to_string(),
        "p.eds:1: [1800]: expected sub-index 1 (COB-ID) with a value, found none"
    );
    let text = "\
[1800]
ParameterName=TPDO 1
ObjectType=9

[1800sub1]
ParameterName=COB-ID
DataType=7
DefaultValue=0x181

[1A00]
ParameterName=TPDO 1 mapping
ObjectType=9

[1A00sub0]
ParameterName=Count
DataType=5
DefaultValue=2

[1A00sub1]
ParameterName=Entry 1
DataType=7
DefaultValue=0x60410000
";
    let eds = Eds::parse(text, "p.eds", None).unwrap();
    assert_eq!(
        eds.pdos().unwrap_err().to_string(),
        "p.eds:19: [1A00sub1]: PDO mapping entry length: 0 is outside 1..=255"
    );
}

#[test]
fn section_names_that_are_not_ascii() {
    // Found by the eds fuzz target: a multi-byte character right after the
    // index, where "sub" would stand.
    for name in [
        "1000s\u{9e}",
        "1000\u{e9}",
        "10\u{e9}0",
        "1000sub\u{e9}",
        "1000Näme",
    ] {
        let text = format!("[1000]\nParameterName=a\n[{name}]\nParameterName=b\n");
        let eds = Eds::parse(&text, "u.eds", None).unwrap();
        assert_eq!(eds.objects().count(), 1, "{name}");
    }
}

#[test]
fn latin1_and_missing_files() {
    let bytes = b"[1000]\nParameterName=Ger\xe4tetyp\nDataType=7\n";
    let eds = Eds::from_bytes(bytes, "l.eds", None).unwrap();
    assert_eq!(eds.name(0x1000, 0), Some("Gerätetyp"));
    let e = Eds::read_file(Path::new("/nonexistent/x.eds"), None).unwrap_err();
    assert_eq!(e.line, 0);
    assert!(matches!(e.kind, EdsErrorKind::Io(_)));
}

mod proptests {
    use proptest::prelude::*;

    use super::*;

    /// Lines made of the pieces an EDS is made of, in any order.
    fn eds_like_text() -> impl Strategy<Value = String> {
        let line = prop_oneof![
            "\\[[0-9A-Fa-f]{4}\\]",
            "\\[[0-9A-Fa-f]{4}(sub|SUB|Sub)[0-9A-Fa-f]{1,3}\\]",
            "\\[[0-9A-F]{4}(Name|Value)\\]",
            Just("[DeviceComissioning]".to_owned()),
            "(ParameterName|ObjectType|DataType|AccessType|DefaultValue|ParameterValue|SubNumber|CompactSubObj|PDOMapping|NodeID|[0-9]{1,2})=[ -~]{0,12}",
            "(DefaultValue|ParameterValue)=(\\$NODEID\\+)?(0x)?[0-9A-F]{1,9}",
            "(DataType|ObjectType)=0x[0-9]{1,4}",
            "; .{0,10}",
            ".{0,20}",
        ];
        proptest::collection::vec(line, 0..40).prop_map(|lines| lines.join("\n"))
    }

    proptest! {
        #[test]
        fn any_text_reads_without_panic(text in eds_like_text(), node in 0u8..=128) {
            if let Ok(eds) = Eds::parse(&text, "p.eds", NodeId::new(node)) {
                let _ = eds.device_type();
                for object in eds.objects() {
                    for entry in object.entries() {
                        let _ = entry.value().map(ToString::to_string);
                    }
                }
                if let Ok(pdos) = eds.pdos() {
                    for pdo in &pdos {
                        prop_assert_eq!(pdo.signals.len(), pdo.mapping.entries().iter().filter(|e| !e.is_dummy()).count());
                        let _ = pdo.unpack(&[0xA5; 64]).count();
                    }
                }
            } else if let Err(e) = Eds::parse(&text, "p.eds", NodeId::new(node)) {
                prop_assert!(e.line >= 1 && e.line <= text.split('\n').count());
                let _ = e.to_string();
            }
        }

        #[test]
        fn any_bytes_read_without_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
            if let Err(e) = Eds::from_bytes(&bytes, "b.eds", None) {
                let _ = e.to_string();
            }
        }
    }
}

#[test]
fn errors_name_the_broken_line_and_a_file_that_cannot_be_read() {
    // A broken section header is reported on its own line, not as part of
    // the section before it.
    let text = "[1000]\nParameterName=Device type\nDataType=0x0007\n[1001\n";
    let e = Eds::parse(text, "bad.eds", None).unwrap_err();
    assert_eq!(e.line, 4);
    assert_eq!(e.section, None);
    assert_eq!(
        e.to_string(),
        "bad.eds:4: expected ']' to close the section name"
    );
    // A file that cannot be read has no line to name.
    let e = Eds::read_file(Path::new("/nonexistent/x.eds"), None).unwrap_err();
    assert_eq!(e.line, 0);
    let text = e.to_string();
    assert!(
        text.starts_with("/nonexistent/x.eds: cannot be read: "),
        "{text}"
    );
}
