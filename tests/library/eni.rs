//! ENI files read into the slaves' process-data configuration
//! (docs/ethercat.md#eni; tests/data/ethercat/eni/README.md): a real
//! TwinCAT export and the drives' layout written for this repository.

use std::path::Path;

use motionwire::canopen::{DataType, MappingEntry};
use motionwire::decoder::ethercat::{parse_eni, PdoConfig, PdoEntryConfig, SlaveConfig};
use motionwire::ethercat::{Fmmu, SyncManager};

fn read(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat/eni")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// An FMMU of whole bytes onto a sync manager's area, active.
fn fmmu(logical: u32, len: u16, physical: u16, kind: u8) -> Fmmu {
    Fmmu {
        logical,
        len,
        logical_start_bit: 0,
        logical_end_bit: 7,
        physical,
        physical_start_bit: 0,
        kind,
        active: true,
    }
}

fn sm(start: u16, len: u16, control: u8, activate: u8) -> SyncManager {
    SyncManager {
        start,
        len,
        control,
        status: 0,
        activate,
    }
}

fn entry(index: u16, sub_index: u8, bits: u8, named: Option<(&str, DataType)>) -> PdoEntryConfig {
    PdoEntryConfig {
        entry: MappingEntry::new(index, sub_index, bits),
        name: named.map(|(name, _)| name.to_owned()),
        data_type: named.map(|(_, data_type)| data_type),
    }
}

/// The CiA 402 PDOs of drives 2 and 3: 0x1600 and 0x1A00, each 7 bytes.
fn drive_pdos(named: bool) -> Vec<PdoConfig> {
    let name = |text, data_type| named.then_some((text, data_type));
    vec![
        PdoConfig {
            index: 0x1600,
            entries: vec![
                entry(0x6040, 0, 16, name("Controlword", DataType::Unsigned16)),
                entry(0x607A, 0, 32, name("Target position", DataType::Integer32)),
                entry(0x6060, 0, 8, name("Modes of operation", DataType::Integer8)),
            ],
        },
        PdoConfig {
            index: 0x1A00,
            entries: vec![
                entry(0x6041, 0, 16, name("Statusword", DataType::Unsigned16)),
                entry(
                    0x6064,
                    0,
                    32,
                    name("Position actual value", DataType::Integer32),
                ),
                entry(
                    0x6061,
                    0,
                    8,
                    name("Modes of operation display", DataType::Integer8),
                ),
            ],
        },
    ]
}

fn drives() -> Vec<SlaveConfig> {
    let drive = |n: u16, outputs: u32, inputs: u32, pdos: Vec<PdoConfig>| SlaveConfig {
        station: Some(0x1000 + n),
        position: Some(n - 1),
        name: Some(format!("Drive {n}")),
        vendor: Some(0x6A),
        product: Some(0x0041_4B44),
        fmmus: vec![
            (0, fmmu(outputs, 7, 0x1100, 2)),
            (1, fmmu(inputs, 7, 0x1180, 1)),
        ],
        sync_managers: vec![
            (0, sm(0x1000, 128, 0x26, 1)),
            (1, sm(0x1080, 128, 0x22, 1)),
            (2, sm(0x1100, 7, 0x64, 1)),
            (3, sm(0x1180, 7, 0x20, 1)),
        ],
        assignment: vec![(2, vec![0x1600]), (3, vec![0x1A00])],
        pdos,
    };
    let mut named = drive_pdos(true);
    named.insert(
        1,
        PdoConfig {
            index: 0x1601,
            entries: vec![
                entry(0x6040, 0, 16, Some(("Controlword", DataType::Unsigned16))),
                entry(0, 0, 8, None),
                entry(
                    0x60FF,
                    0,
                    32,
                    Some(("Target velocity", DataType::Integer32)),
                ),
            ],
        },
    );
    vec![
        SlaveConfig {
            station: Some(0x1001),
            position: Some(0),
            name: Some("Servo 1".to_owned()),
            vendor: Some(2),
            product: Some(0x1001),
            fmmus: vec![
                (0, fmmu(0x0001_0000, 10, 0x1000, 2)),
                (1, fmmu(0x0001_0018, 40, 0x1100, 1)),
            ],
            sync_managers: vec![(0, sm(0x1000, 10, 0x64, 1)), (1, sm(0x1100, 40, 0x20, 1))],
            assignment: vec![],
            pdos: vec![],
        },
        drive(2, 0x0001_000A, 0x0001_0040, named),
        drive(3, 0x0001_0011, 0x0001_0047, drive_pdos(false)),
    ]
}

#[test]
fn the_drives_layout_reads_as_written() {
    assert_eq!(parse_eni(&read("drives.eni.xml")).unwrap(), drives());
}

/// The text without the InitCmds whose comment holds `what`.
fn without_init_cmds(xml: &str, what: &str) -> String {
    let mut out = String::with_capacity(xml.len());
    let mut rest = xml;
    while let Some(start) = rest.find("<InitCmd>") {
        let end = start + rest[start..].find("</InitCmd>").unwrap() + "</InitCmd>".len();
        out.push_str(&rest[..start]);
        if !rest[start..end].contains(what) {
            out.push_str(&rest[start..end]);
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn send_and_recv_give_the_fmmus_the_init_cmds_write() {
    let xml = without_init_cmds(&read("drives.eni.xml"), "set fmmu");
    assert!(!xml.contains("set fmmu"));
    assert_eq!(parse_eni(&xml).unwrap(), drives());
}

#[test]
fn a_twincat_export_reads_as_twincat_configures_it() {
    let slaves = parse_eni(&read("twincat-imu-wheel.eni.xml")).unwrap();
    assert_eq!(slaves.len(), 2);

    let imu = &slaves[0];
    assert_eq!(imu.name.as_deref(), Some("Imu"));
    assert_eq!(
        (imu.station, imu.position, imu.vendor, imu.product),
        (Some(1001), Some(0), Some(33), Some(1))
    );
    // No outputs: TwinCAT writes FMMU 0 with the write type alone and SM2
    // with length 0, disabled; the mailbox-state FMMU maps bit 0 of
    // 0x080D at logical 0x09000000.
    assert_eq!(
        imu.fmmus,
        vec![
            (
                0,
                Fmmu {
                    kind: 2,
                    ..Fmmu::default()
                }
            ),
            (1, fmmu(0x0100_0000, 14, 0x2800, 1)),
            (
                2,
                Fmmu {
                    logical_end_bit: 0,
                    ..fmmu(0x0900_0000, 1, 0x080D, 1)
                }
            ),
        ]
    );
    assert_eq!(
        imu.sync_managers,
        vec![
            (0, sm(0x4000, 276, 0x26, 1)),
            (1, sm(0x4800, 276, 0x22, 1)),
            (2, sm(0x1000, 0, 0x64, 0)),
            (3, sm(0x2800, 14, 0x20, 1)),
        ]
    );
    assert_eq!(imu.assignment, vec![(2, vec![0x1600]), (3, vec![0x1A00])]);
    let names: Vec<_> = imu.pdos[0]
        .entries
        .iter()
        .map(|e| (e.entry.index(), e.name.as_deref().unwrap(), e.data_type))
        .collect();
    assert_eq!(
        names[0],
        (0x2065, "Acceleration X", Some(DataType::Integer16))
    );
    assert_eq!(names[6], (0x206B, "Error code", Some(DataType::Unsigned16)));
    assert_eq!(imu.pdos[0].entries.len(), 7);
    assert_eq!(
        imu.pdos[1],
        PdoConfig {
            index: 0x1600,
            entries: vec![]
        }
    );

    let wheel = &slaves[1];
    assert_eq!(
        (wheel.station, wheel.position, wheel.vendor, wheel.product),
        (Some(1002), Some(1), Some(0x9A), Some(198_948))
    );
    assert_eq!(
        wheel.fmmus,
        vec![
            (0, fmmu(0x0100_0800, 6, 0x1100, 2)),
            (1, fmmu(0x0100_0800, 14, 0x1180, 1)),
        ]
    );
    assert_eq!(
        wheel.sync_managers,
        vec![
            (0, sm(0x1800, 140, 0x26, 1)),
            (1, sm(0x1900, 140, 0x22, 1)),
            (2, sm(0x1100, 6, 0x64, 1)),
            (3, sm(0x1180, 14, 0x20, 1)),
        ]
    );
    assert_eq!(wheel.assignment, vec![(2, vec![0x1601]), (3, vec![0x1A03])]);
    // Every PDO of the drive is listed; the assigned ones fill their
    // sync managers exactly.
    assert_eq!(wheel.pdos.len(), 66);
    let bytes = |index: u16| {
        let pdo = wheel.pdos.iter().find(|p| p.index == index).unwrap();
        pdo.entries
            .iter()
            .map(|e| u32::from(e.entry.bits()))
            .sum::<u32>()
            / 8
    };
    assert_eq!((bytes(0x1601), bytes(0x1A03)), (6, 14));
    let gap = wheel.pdos.iter().find(|p| p.index == 0x1A0B).unwrap();
    assert_eq!(gap.entries[1], entry(0, 0, 8, None));
}

#[test]
fn the_twincat_export_s_send_and_recv_give_its_written_fmmus() {
    let xml = without_init_cmds(&read("twincat-imu-wheel.eni.xml"), "fmmu");
    let slaves = parse_eni(&xml).unwrap();
    let written = parse_eni(&read("twincat-imu-wheel.eni.xml")).unwrap();
    assert_eq!(slaves[1].fmmus, written[1].fmmus);
    // The IMU has inputs only: one FMMU, numbered 0.
    assert_eq!(slaves[0].fmmus, vec![(0, written[0].fmmus[1].1)]);
}
