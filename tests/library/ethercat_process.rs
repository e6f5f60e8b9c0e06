//! Each slave's process data cut out of real LRW cycles by the library
//! (`Session::process_data`), checked against what tshark's dissection
//! alone says it is: `NAME.process.tsv`, written by
//! scripts/ecat_process_oracle.py from the FMMU and sync-manager writes
//! tshark shows in the start-up and each datagram's bytes
//! (tests/data/ethercat/README.md, "Expected files").

use std::fmt::Write as _;
use std::path::Path;

use motionwire::can::LogEvent;
use motionwire::decoder::ethercat::Session;
use motionwire::logs::{self, ReadLog};

/// The captures with cyclic process data and how many records each
/// gives: two real ethercrab captures (EK1100 + EL2828 + EL2889: 257
/// cycles of both output terminals; 8 cycles of the EL2889 and 255 of the
/// EL2828 in two groups) and the synthetic AKD capture, whose sent copies
/// carry the previous cycle's inputs, so that inputs taken from the wrong
/// copy differ.
const CAPTURES: [(&str, usize); 3] = [
    ("replay-dc", 514),
    ("replay-ek1100-el2828-el2889", 263),
    ("synthetic_akd_fault", 200),
];

/// One `process_data` record in the oracle's columns, and whether the
/// library took its inputs as confirmed.
struct Row {
    /// packet, dg, logical, station, wkc, expected_wkc, outputs, inputs.
    line: String,
    confirmed: bool,
}

fn hex(bytes: Option<&[u8]>) -> String {
    bytes.map_or_else(String::new, |b| {
        b.iter().fold(String::new(), |mut s, byte| {
            write!(s, "{byte:02x}").unwrap();
            s
        })
    })
}

/// Read `name`'s capture as `motionwire decode` does (every datagram's
/// meanings, then its process data) and write each record in the
/// oracle's columns, ordered as the oracle orders them: by packet,
/// datagram, then station.
fn ours(name: &str) -> Vec<Row> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(format!("{name}.pcapng"));
    let mut log = logs::open(&path).unwrap();
    let mut session = Session::new();
    let mut rows = Vec::new();
    while let Some(record) = log.next_event() {
        let record = record.unwrap_or_else(|e| panic!("{name}: {e}"));
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        let packet = session
            .read(record.position, &packet)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = datagram.unwrap_or_else(|e| panic!("{name}: {e}"));
            session.meanings(&packet, at, &datagram, |_| {});
            session.process_data(&packet, at, &datagram, |data| {
                let station = data.slave.and_then(|s| s.station);
                let line = format!(
                    "{}\t{}\t{:#010x}\t{}\t{}\t{}\t{}\t{}",
                    record.position,
                    at + 1,
                    data.logical,
                    station.map_or_else(String::new, |s| format!("{s:#06x}")),
                    data.wkc,
                    data.expected_wkc
                        .map_or_else(String::new, |e| e.to_string()),
                    hex(data.outputs),
                    hex(data.inputs),
                );
                rows.push((
                    (record.position.number(), at, station),
                    Row {
                        line,
                        confirmed: data.confirmed,
                    },
                ));
            });
        }
    }
    // The oracle lists a datagram's slaves by station address; the
    // library in the order it met them.
    rows.sort_by_key(|(key, _)| *key);
    rows.into_iter().map(|(_, row)| row).collect()
}

/// The oracle's rows of `name`, without the header.
fn theirs(name: &str) -> Vec<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(format!("{name}.process.tsv"));
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("packet\tdg\tlogical\tstation\twkc\texpected_wkc\toutputs\tinputs"),
        "{name}: header"
    );
    lines.map(str::to_owned).collect()
}

#[test]
fn every_slave_is_cut_at_the_bytes_tshark_shows() {
    for (name, count) in CAPTURES {
        let ours = ours(name);
        let theirs = theirs(name);
        assert_eq!(theirs.len(), count, "{name}: the oracle's rows");
        for (n, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            assert_eq!(a.line, *b, "{name}, row {}", n + 1);
        }
        assert_eq!(ours.len(), theirs.len(), "{name}: records");
        // Every record is one slave's, with the whole of its images: the
        // start-up configured every FMMU before the first cycle.
        for row in &theirs {
            let cells: Vec<&str> = row.split('\t').collect();
            assert!(!cells[3].is_empty(), "{name}: {row}");
            assert!(
                !cells[6].is_empty() || !cells[7].is_empty(),
                "{name}: {row}"
            );
        }
    }
}

/// Where the working counter tshark shows is the full count the FMMUs ask
/// for (the oracle's `wkc` equals its `expected_wkc`), the library expects
/// exactly that count and takes the inputs as confirmed; where it is short
/// (the synthetic AKD's last 50 cycles, the datagram's only slave), the
/// library expects the full count all the same and leaves the inputs
/// unconfirmed.
#[test]
fn the_expected_working_counter_is_the_full_count() {
    for ((name, _), full_cycles) in CAPTURES.into_iter().zip([514, 263, 150]) {
        let ours = ours(name);
        let theirs = theirs(name);
        assert_eq!(ours.len(), theirs.len(), "{name}: records");
        let mut full = 0;
        for (row, oracle) in ours.iter().zip(&theirs) {
            let cells: Vec<&str> = oracle.split('\t').collect();
            let (wkc, expected) = (cells[4], cells[5]);
            let our_expected = row.line.split('\t').nth(5).unwrap();
            assert_eq!(our_expected, expected, "{name}: {}", row.line);
            if wkc == expected {
                full += 1;
                assert_eq!(our_expected, wkc, "{name}: {}", row.line);
                assert!(row.confirmed, "{name}: {}", row.line);
            } else {
                assert!(
                    wkc.parse::<u16>().unwrap() < expected.parse().unwrap(),
                    "{name}: {oracle}"
                );
                assert!(!row.confirmed, "{name}: {}", row.line);
            }
        }
        assert_eq!(full, full_cycles, "{name}: records at the full count");
    }
}
