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

/// The EL2828 (8 outputs) and EL2889 (16 outputs) have no CoE: their
/// PDOs are only in their SII, whose RxPDO category ethercrab's start-up
/// reads (FPWR 0x0502, FPRD 0x0508, 8 bytes a read; the EL2828's at words
/// 0xDA–0x11B, the EL2889's at 0xE9–0x16A, as tshark shows the reads):
/// PDOs 0x1600 + k, each one entry 0x7000 + 0x10·k:01, BOOLEAN of 1 bit,
/// 0x1600–0x1607 on SM0 and the EL2889's 0x1608–0x160F on SM1. The
/// strings category was read only as far as the device's name, so the
/// entries keep their index as name. Each cycle's signals are the bits of
/// the bytes tshark shows at the terminal's FMMU, in order.
#[test]
fn output_terminals_are_read_by_their_sii_pdos() {
    for (name, rows) in [("replay-dc", 514), ("replay-ek1100-el2828-el2889", 263)] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/ethercat")
            .join(format!("{name}.pcapng"));
        let mut log = logs::open(&path).unwrap();
        let mut session = Session::new();
        let mut ours = Vec::new();
        while let Some(record) = log.next_event() {
            let record = record.unwrap();
            let LogEvent::Ethercat(packet) = record.event else {
                continue;
            };
            let packet = session.read(record.position, &packet).unwrap();
            for (at, datagram) in packet.datagrams().enumerate() {
                let datagram = datagram.unwrap();
                session.meanings(&packet, at, &datagram, |_| {});
                session.process_data(&packet, at, &datagram, |data| {
                    let mut signals = Vec::new();
                    data.for_each_signal(|output, name, signal| {
                        assert!(output, "{name}: an output terminal");
                        signals.push(format!("{name}={}", signal.unwrap().value));
                    });
                    let station = data.slave.and_then(|s| s.station);
                    ours.push(((record.position.number(), at, station), signals));
                });
            }
        }
        ours.sort_by_key(|(key, _)| *key);
        let theirs = theirs(name);
        assert_eq!(theirs.len(), rows, "{name}");
        assert_eq!(ours.len(), rows, "{name}");
        for ((_, signals), row) in ours.iter().zip(&theirs) {
            let cells: Vec<&str> = row.split('\t').collect();
            let outputs: Vec<u8> = (0..cells[6].len())
                .step_by(2)
                .map(|i| u8::from_str_radix(&cells[6][i..i + 2], 16).unwrap())
                .collect();
            let expected: Vec<String> = (0..outputs.len() * 8)
                .map(|k| {
                    let bit = outputs[k / 8] >> (k % 8) & 1 != 0;
                    format!("0x{:04X}:01={bit}", 0x7000 + 0x10 * k)
                })
                .collect();
            assert_eq!(*signals, expected, "{name}: {row}");
        }
    }
}

/// A session fed exchanges built by hand: each a frame of datagrams sent
/// and returned (the returned copy with the data and working counters
/// given), for the configuration problems of docs/ethercat.md#process-data.
mod problems {
    use motionwire::can::EthercatPacket;
    use motionwire::decoder::ethercat::{ImageError, Session};
    use motionwire::ethercat::{Command, DatagramRepr, Encapsulation, EthercatLink, Mac};
    use motionwire::logs::Position;

    /// One datagram: command, address word, data as returned, working
    /// counter as returned.
    type Spec = (Command, u32, Vec<u8>, u16);

    /// The frame's bytes, with each datagram's data and working counter.
    fn frame(specs: &[Spec], returned: bool) -> Vec<u8> {
        let mut body = Vec::new();
        for (i, (command, address, data, wkc)) in specs.iter().enumerate() {
            let repr = DatagramRepr {
                command: *command,
                index: i as u8,
                address: *address,
                circulating: false,
                more_follows: i + 1 < specs.len(),
                irq: 0,
                data,
                working_counter: if returned { *wkc } else { 0 },
            };
            let mut buffer = vec![0; 12 + data.len()];
            repr.emit(&mut buffer).unwrap();
            body.extend(buffer);
        }
        let mut bytes = (body.len() as u16 | 0x1000).to_le_bytes().to_vec();
        bytes.extend(body);
        bytes
    }

    /// Feed one exchange; return the problems said.
    fn exchange(session: &mut Session, number: &mut u64, specs: &[Spec]) -> Vec<ImageError> {
        for returned in [false, true] {
            *number += 1;
            let bytes = frame(specs, returned);
            let mut source = [0x10; 6];
            if returned {
                source[0] |= Mac::RETURNED_BIT;
            }
            let packet = EthercatPacket {
                timestamp: None,
                iface: None,
                link: EthercatLink {
                    destination: None,
                    source: Mac(source),
                    encapsulation: Encapsulation::Ethernet,
                    payload: &bytes,
                },
            };
            let read = session.read(Position::Record(*number), &packet).unwrap();
            for (at, datagram) in read.datagrams().enumerate() {
                let datagram = datagram.unwrap();
                session.meanings(&read, at, &datagram, |_| {});
                session.process_data(&read, at, &datagram, |_| {});
            }
        }
        let (problems, more) = session.take_problems();
        assert_eq!(more, 0);
        problems.into_iter().map(|p| p.error).collect()
    }

    /// FPWR of `data` at register `ado` of station `station`.
    fn write(station: u16, ado: u16, data: Vec<u8>) -> Spec {
        (
            Command::Fpwr,
            u32::from(station) | u32::from(ado) << 16,
            data,
            1,
        )
    }

    /// An FMMU: `len` bytes at `logical` onto `physical`, of `kind`.
    fn fmmu(logical: u32, len: u16, physical: u16, kind: u8) -> Vec<u8> {
        motionwire::ethercat::Fmmu {
            logical,
            len,
            logical_start_bit: 0,
            logical_end_bit: 7,
            physical,
            physical_start_bit: 0,
            kind,
            active: true,
        }
        .to_bytes()
        .to_vec()
    }

    #[test]
    fn overlapping_outputs_are_said_once() {
        let mut session = Session::new();
        let mut n = 0;
        // Two slaves whose output FMMUs both map logical 2..4.
        let config = [
            write(0x1001, 0x0600, fmmu(0, 4, 0x1000, 2)),
            write(0x1002, 0x0600, fmmu(2, 4, 0x1000, 2)),
        ];
        assert!(exchange(&mut session, &mut n, &config).is_empty());
        let cycle = [(Command::Lrw, 0, vec![0; 6], 4)];
        let problems = exchange(&mut session, &mut n, &cycle);
        assert_eq!(problems.len(), 1, "{problems:?}");
        let ImageError::OverlappingFmmus { other, start, end } = problems[0] else {
            panic!("{problems:?}");
        };
        assert_eq!((other.station, start, end), (Some(0x1002), 2, 4));
        // Said where the plans are made, not every cycle.
        assert!(exchange(&mut session, &mut n, &cycle).is_empty());
    }

    #[test]
    fn a_mailbox_message_past_its_sync_manager_is_said() {
        let mut session = Session::new();
        let mut n = 0;
        // SM0: a 16-byte mailbox written by the master at 0x1000.
        let sm0 = vec![0x00, 0x10, 16, 0, 0x26, 0, 1, 0];
        assert!(exchange(&mut session, &mut n, &[write(0x1001, 0x0800, sm0)]).is_empty());
        // A CoE message whose header says 100 bytes, in 16.
        let mut message = vec![100, 0, 0, 0, 0, 0x03];
        message.extend([0; 10]);
        let problems = exchange(&mut session, &mut n, &[write(0x1001, 0x1000, message)]);
        assert_eq!(
            problems,
            [ImageError::MailboxPastSyncManager {
                length: 100,
                room: 10
            }]
        );
    }
}
