//! EtherCAT captures of real masters (tests/data/ethercat/README.md) read
//! datagram for datagram as tshark's `ecat` dissector reads them: the
//! expected files are tshark's own output (scripts/ecat_oracle.py).

use std::fmt::Write as _;
use std::path::Path;

use motionwire::can::LogEvent;
use motionwire::ethercat::{Addressing, Session};
use motionwire::logs::{self, ReadLog};

/// The fixtures, each with tshark's dissection beside it: six real
/// captures and one written by scripts/ecat_pcapng.py.
const CAPTURES: [&str; 7] = [
    "twincat-akd-startup",
    "soem-akd-sdo",
    "soem-single-lan9252",
    "replay-dc",
    "replay-ek1914-el3004-configure",
    "replay-ek1914-segmented-upload",
    "synthetic_akd_fault",
];

/// Read `name`'s capture and write one row per datagram in the columns of
/// its `.tshark.tsv`: frame, datagram, source MAC, command, index, ADP,
/// ADO, logical address, length, working counter, IRQ, data.
fn rows(name: &str) -> (String, Session) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(format!("{name}.pcapng"));
    let mut log = logs::open(&path).unwrap();
    let mut session = Session::new();
    let mut out =
        String::from("frame\tdg\teth_src\tcmd\tidx\tadp\tado\tlad\tlen\twkc\tirq\tdata\n");
    while let Some(record) = log.next_event() {
        let record = record.unwrap_or_else(|e| panic!("{name}: {e}"));
        let LogEvent::Ethercat(packet) = record.event else {
            panic!("{name}: only EtherCAT events, found {}", record.event)
        };
        let packet = session
            .read(record.position, &packet)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        for (at, datagram) in packet.datagrams().enumerate() {
            let d = datagram.unwrap_or_else(|e| panic!("{name}: {}: {e}", record.position));
            let (adp, ado, lad) = if d.command().addressing() == Addressing::Logical {
                (
                    String::new(),
                    String::new(),
                    format!("{:#010x}", d.address()),
                )
            } else {
                (
                    format!("{:#06x}", d.adp()),
                    format!("{:#06x}", d.ado()),
                    String::new(),
                )
            };
            let data: String = d.data().iter().map(|b| format!("{b:02x}")).collect();
            writeln!(
                out,
                "{}\t{}\t{}\t{:#04x}\t{:#04x}\t{adp}\t{ado}\t{lad}\t{}\t{}\t{:#06x}\t{data}",
                record.position,
                at + 1,
                packet.source,
                d.command().byte(),
                d.index(),
                d.length(),
                d.working_counter(),
                d.irq(),
            )
            .unwrap();
        }
    }
    (out, session)
}

#[test]
fn every_datagram_reads_as_tshark_reads_it() {
    for name in CAPTURES {
        let (ours, _) = rows(name);
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/ethercat")
            .join(format!("{name}.tshark.tsv"));
        let theirs = std::fs::read_to_string(path).unwrap();
        let (ours, theirs): (Vec<_>, Vec<_>) = (ours.lines().collect(), theirs.lines().collect());
        for (line, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            assert_eq!(a, b, "{name}, row {line}");
        }
        assert_eq!(ours.len(), theirs.len(), "{name}: rows");
    }
}

#[test]
fn sent_and_returned_copies_pair_up() {
    // The TwinCAT capture: 237 frames of datagrams sent, each returned
    // (some 27 frames later), 3 returned frames of a second master without
    // their sent copy, and one frame of a reserved type (7) that no slave
    // processes (tests/data/ethercat/README.md; tshark's `ecatf.type`).
    let (_, mut session) = rows("twincat-akd-startup");
    let counts = session.finish();
    assert_eq!(counts.packets, 478);
    assert_eq!(counts.sent, 237);
    assert_eq!(counts.returned, 237);
    assert_eq!(counts.returned_unpaired, 3);
    assert_eq!(counts.other_frame_types, 1);
    assert_eq!(counts.lost, 0);
    assert_eq!(counts.damaged, 0);
    // Every capture's frames are read with nothing damaged.
    for name in CAPTURES {
        let (_, mut session) = rows(name);
        let counts = session.finish();
        assert_eq!(counts.damaged, 0, "{name}");
        assert_eq!(
            counts.packets,
            counts.sent + counts.returned + counts.returned_unpaired + counts.other_frame_types,
            "{name}"
        );
        eprintln!("{name}: {counts:?}");
    }
}
