//! EtherCAT captures of real masters (tests/data/ethercat/README.md) read
//! datagram for datagram as tshark's `ecat` dissector reads them: the
//! expected files are tshark's own output (scripts/ecat_oracle.py).

use std::fmt::Write as _;
use std::path::Path;

use motionwire::can::LogEvent;
use motionwire::decoder::ethercat::{Meaning, Session};
use motionwire::ethercat::{Addressing, CoeHeader, CoeSdo, CoeService, MailboxType};
use motionwire::logs::{self, ReadLog};

/// The fixtures, each with tshark's dissection beside it: seven real
/// captures and one written by scripts/ecat_pcapng.py.
const CAPTURES: [&str; 8] = [
    "twincat-akd-startup",
    "soem-akd-sdo",
    "soem-single-lan9252",
    "replay-dc",
    "replay-ek1100-el2828-el2889",
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

/// Read `name`'s capture and write one row per mailbox message the
/// session finds, in the columns of its `.coe.tsv` that tshark's
/// `ecat_mailbox` dissector fills on the returned copies: frame,
/// datagram, mailbox length, type and counter, CoE service, SDO index and
/// sub-index.
fn mailbox_rows(name: &str) -> Vec<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(format!("{name}.pcapng"));
    let mut log = logs::open(&path).unwrap();
    let mut session = Session::new();
    let mut rows = Vec::new();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        let packet = session.read(record.position, &packet).unwrap();
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = datagram.unwrap();
            session.meanings(&packet, at, &datagram, |meaning| {
                let Meaning::Mailbox { header, body, .. } = meaning else {
                    return;
                };
                let mut row = format!(
                    "{}\t{}\t{}\t{}\t{}",
                    record.position,
                    at + 1,
                    header.length,
                    header.mailbox_type.bits(),
                    header.counter
                );
                if header.mailbox_type == MailboxType::Coe {
                    let coe = CoeHeader::parse(body).unwrap();
                    write!(row, "\t{}", coe.service.bits()).unwrap();
                    let sdo = matches!(
                        coe.service,
                        CoeService::SdoRequest | CoeService::SdoResponse
                    );
                    match CoeSdo::parse(&body[2..])
                        .ok()
                        .filter(|s| sdo && s.specifier() != 0)
                    {
                        Some(sdo) => {
                            let (index, sub) = sdo.multiplexer().unwrap();
                            write!(row, "\t{index:#06x}\t{sub:#04x}").unwrap();
                        }
                        None => row.push_str("\t\t"),
                    }
                } else {
                    row.push_str("\t\t\t");
                }
                rows.push(row);
            });
        }
    }
    rows
}

/// tshark's mailbox rows of the copies that prove a message was delivered
/// (docs/ethercat.md#mailbox): returned (the source MAC's bit 0x02), and a
/// read with a working counter of at least 1.
fn tshark_mailbox_rows(name: &str) -> Vec<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(format!("{name}.coe.tsv"));
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split('\t').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let [frame, dg, src, cmd, wkc, len, kind, cnt, coe, idx, sub] = [
        "frame", "dg", "eth_src", "dg_cmd", "dg_wkc", "mbx_len", "mbx_type", "mbx_cnt", "coe_type",
        "sdo_idx", "sdo_sub",
    ]
    .map(column);
    lines
        .map(|line| line.split('\t').collect::<Vec<_>>())
        .filter(|f| {
            let returned = u8::from_str_radix(&f[src][..2], 16).unwrap() & 2 != 0;
            let read = f[cmd] == "0x04";
            returned && (!read || f[wkc] != "0")
        })
        .map(|f| {
            let coe_type = if f[kind] == "3" { f[coe] } else { "" };
            let sdo = matches!(coe_type, "2" | "3");
            format!(
                "{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}",
                f[frame],
                f[dg],
                f[len],
                f[kind],
                f[cnt],
                coe_type,
                if sdo { f[idx] } else { "" },
                if sdo { f[sub] } else { "" }
            )
        })
        .collect()
}

#[test]
fn every_mailbox_message_reads_as_tshark_reads_it() {
    let mut messages = 0;
    for name in CAPTURES {
        let ours = mailbox_rows(name);
        let theirs = tshark_mailbox_rows(name);
        assert_eq!(ours, theirs, "{name}");
        messages += ours.len();
    }
    // The seven real captures and the synthetic one: 128 messages
    // delivered (replay-ek1100-el2828-el2889 has no mailbox traffic).
    assert_eq!(messages, 128);
}

/// The summary of a capture (docs/ethercat.md#summary).
fn summary(name: &str) -> motionwire::summary::Summary {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(format!("{name}.pcapng"));
    let mut log = logs::open(&path).unwrap();
    let mut summarizer = motionwire::summary::Summarizer::default();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        summarizer.add(record.position, &record.event);
    }
    summarizer.finish()
}

/// Issue 35's case: an AKD sends CoE EMCY 0x7305 on its feedback 2, leaves
/// OP for SAFEOP with AL status code 0x001B, and the cyclic LRW's working
/// counter falls from 3 to 1 (scripts/ecat_pcapng.py wrote the capture).
/// The summary says exactly that, in time order.
#[test]
fn the_akd_fault_is_summarized_in_time_order() {
    let summary = summary("synthetic_akd_fault");
    let port = &summary.ethercat.ports[0];
    assert_eq!(
        (port.counts.sent, port.counts.returned, port.counts.lost),
        (279, 279, 0)
    );
    let [coupler, akd] = &summary.ethercat.slaves[..] else {
        panic!("two slaves: {:?}", summary.ethercat.slaves)
    };
    assert_eq!((coupler.station, coupler.position), (Some(0x1000), Some(0)));
    assert_eq!(
        coupler.al_last.unwrap().status.state(),
        Some(motionwire::ethercat::AlState::Op)
    );
    assert_eq!((akd.station, akd.position), (Some(0x1001), Some(1)));
    assert_eq!((akd.vendor, akd.product), (Some(0x6A), Some(0x0041_4B44)));
    let emcy = &akd.emergencies[0];
    assert_eq!(emcy.emcy.code.get(), 0x7305);
    let last = akd.al_last.unwrap();
    assert_eq!(
        last.status.state(),
        Some(motionwire::ethercat::AlState::SafeOp)
    );
    assert!(last.status.error());
    assert_eq!(last.code.map(|c| c.0), Some(0x001B));
    assert!(emcy.packet < last.packet, "the EMCY comes first");
    let lrw = summary
        .ethercat
        .streams
        .iter()
        .find(|s| s.command == motionwire::ethercat::Command::Lrw)
        .unwrap();
    assert_eq!(
        (lrw.sent, lrw.wkc_usual, lrw.wkc_mismatches),
        (200, Some(3), 50)
    );
    let (first, _, wkc) = lrw.first_mismatch.unwrap();
    assert!(
        first > last.packet && wkc == 1,
        "then the working counter falls"
    );
    assert!(lrw.resolved());
    assert_eq!(lrw.cycle_median_ns, Some(1_000_000));
    // The text says it in that order.
    let text = summary.to_string();
    let akd_line = text.lines().find(|l| l.contains("Kollmorgen AKD")).unwrap();
    assert!(
        akd_line.contains(
            "op; EMCY 0x7305 Incremental sensor 1 fault (axis 1, feedback 2) (packet 456); \
         safeop with error 0x001b Sync manager watchdog (packet 458)"
        ),
        "{akd_line}"
    );
    assert!(
        text.contains("working counter 3, 50 mismatches from packet"),
        "{text}"
    );
}

/// The real captures: every slave named by its SII, streams as counted by
/// hand (tests/data/ethercat/README.md).
#[test]
fn real_captures_name_their_slaves_and_streams() {
    let dc = summary("replay-dc");
    let names: Vec<_> = dc
        .ethercat
        .slaves
        .iter()
        .map(|s| motionwire::summary::device_name(s.vendor.unwrap(), s.product.unwrap()))
        .collect();
    assert_eq!(
        names,
        [
            Some("Beckhoff EK1100"),
            Some("Beckhoff EL2828"),
            Some("Beckhoff EL2889")
        ]
    );
    let lrw = dc
        .ethercat
        .streams
        .iter()
        .find(|s| s.command == motionwire::ethercat::Command::Lrw)
        .unwrap();
    assert_eq!(
        (lrw.returned, lrw.wkc_usual, lrw.wkc_mismatches),
        (257, Some(4), 0)
    );
    // TwinCAT's clock: most intervals of its ARMW burst are 0, and the
    // summary says the cycle cannot be read from them.
    let twincat = summary("twincat-akd-startup");
    let armw = &twincat.ethercat.streams[0];
    assert_eq!(armw.command, motionwire::ethercat::Command::Armw);
    assert!(!armw.resolved());
    assert_eq!(twincat.ethercat.slaves[0].station, Some(1001));
}

/// A datagram of `command` at `ado` of station 0x1001 as sent (with
/// `sent` data, working counter 0) and as returned (with `returned` data,
/// working counter 1): the two packets' EtherCAT payloads.
fn copies(
    command: motionwire::ethercat::Command,
    index: u8,
    ado: u16,
    sent: &[u8],
    returned: &[u8],
) -> [Vec<u8>; 2] {
    use motionwire::ethercat::DatagramRepr;
    let copy = |data: &[u8], wkc: u16| {
        let repr = DatagramRepr {
            command,
            index,
            address: (u32::from(ado) << 16) | 0x1001,
            circulating: false,
            more_follows: false,
            irq: 0,
            data,
            working_counter: wkc,
        };
        let mut payload = ((repr.buffer_len() as u16) | 0x1000).to_le_bytes().to_vec();
        let at = payload.len();
        payload.resize(at + repr.buffer_len(), 0);
        repr.emit(&mut payload[at..]).unwrap();
        payload
    };
    [copy(sent, 0), copy(returned, 1)]
}

/// The summary of `frames`, each sent by an ethercrab master (source MAC
/// 10:10:…) and returned (12:10:…), numbered from 1; with `timed`, packet
/// N at 1 700 000 000 s + N × 0.5 ms.
fn summarize(frames: &[[Vec<u8>; 2]], timed: bool) -> motionwire::summary::Summary {
    use motionwire::can::{EthercatPacket, LogEvent, Timestamp};
    use motionwire::ethercat::{Encapsulation, EthercatLink, Mac};
    let mut summarizer = motionwire::summary::Summarizer::default();
    let mut number = 0u64;
    for [sent, returned] in frames {
        for (payload, source) in [
            (sent, [0x10; 6]),
            (returned, [0x12, 0x10, 0x10, 0x10, 0x10, 0x10]),
        ] {
            number += 1;
            let packet = EthercatPacket {
                timestamp: timed
                    .then(|| Timestamp::new(1_700_000_000, number as u32 * 500))
                    .flatten(),
                iface: None,
                link: EthercatLink {
                    destination: None,
                    source: Mac(source),
                    encapsulation: Encapsulation::Ethernet,
                    payload,
                },
            };
            summarizer.add(logs::Position::Record(number), &LogEvent::Ethercat(packet));
        }
    }
    summarizer.finish()
}

/// An FPRD at `ado` of station 0x1001 that reads `data`.
fn fprd(index: u8, ado: u16, data: &[u8]) -> [Vec<u8>; 2] {
    let sent = vec![0; data.len()];
    copies(motionwire::ethercat::Command::Fprd, index, ado, &sent, data)
}

/// Error counters that rise and a DL status that changes are said per
/// slave, with their packets; a counter that falls was reset, not an event
/// (docs/ethercat.md#summary).
#[test]
fn error_counters_rising_and_a_link_lost_are_summarized() {
    let mut counters = [0u8; 20];
    let mut reads = Vec::new();
    // Counters 0, then RX errors on port 1 at 5, then reset to 0.
    reads.push(fprd(1, 0x0300, &counters));
    counters[3] = 5;
    reads.push(fprd(2, 0x0300, &counters));
    counters[3] = 0;
    reads.push(fprd(3, 0x0300, &counters));
    // DL status: links on ports 0 and 1, then port 1's link lost.
    reads.push(fprd(4, 0x0110, &[0x31, 0x5a]));
    reads.push(fprd(5, 0x0110, &[0x11, 0x5e]));
    let summary = summarize(&reads, false);
    let slave = &summary.ethercat.slaves[0];
    assert_eq!(slave.station, Some(0x1001));
    assert_eq!(slave.counter_rises.len(), 1, "the reset is no event");
    let rise = slave.counter_rises[0];
    assert_eq!(
        (rise.register, rise.from, rise.to, rise.packet),
        (0x0303, 0, 5, 4)
    );
    assert_eq!(slave.dl_changes.len(), 1);
    assert_eq!(slave.dl_changes[0].packet, 10);
    let text = summary.to_string();
    assert!(text.contains("RX errors port 1 0 → 5 (packet 4)"), "{text}");
    assert!(text.contains("DL status changed at packet 10"), "{text}");
    let json: Vec<String> = summary.records().map(|r| r.to_json()).collect();
    assert!(json.iter().any(|r| r.contains(r#""error_counter_rises":[{"packet":4,"ts":null,"register":771,"name":"RX errors port 1","from":0,"to":5}]"#)), "{json:?}");
}

/// A mailbox message of `body` (CoE header and SDO) at `ado`: written by
/// an FPWR, or read by an FPRD, of station 0x1001, sent and returned.
fn mailbox(index: u8, written: bool, ado: u16, counter: u8, body: &[u8]) -> [Vec<u8>; 2] {
    use motionwire::ethercat::{Command, MailboxHeader, MailboxType};
    let mut message = vec![0; 6];
    MailboxHeader {
        length: body.len() as u16,
        address: 0,
        channel: 0,
        priority: 0,
        mailbox_type: MailboxType::Coe,
        counter,
    }
    .emit(&mut message)
    .unwrap();
    message.extend(body);
    if written {
        copies(Command::Fpwr, index, ado, &message, &message)
    } else {
        copies(Command::Fprd, index, ado, &vec![0; message.len()], &message)
    }
}

/// CoE SDO transfers followed per slave (docs/ethercat.md#summary): an
/// expedited upload that ends, then one the slave aborts in a message of
/// the request service, as real slaves do; the abort names its object and
/// code, and that the slave sent it.
#[test]
fn coe_sdo_transfers_and_a_slave_abort_are_summarized() {
    let messages = [
        // Upload 0x1018:01: request, then the expedited response.
        mailbox(
            1,
            true,
            0x1000,
            1,
            &[0x00, 0x20, 0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0],
        ),
        mailbox(
            2,
            false,
            0x1080,
            1,
            &[0x00, 0x30, 0x4f, 0x18, 0x10, 0x01, 0x6a, 0, 0, 0],
        ),
        // Upload 0x6041:07: the slave aborts, "object does not exist".
        mailbox(
            3,
            true,
            0x1000,
            2,
            &[0x00, 0x20, 0x40, 0x41, 0x60, 0x07, 0, 0, 0, 0],
        ),
        mailbox(
            4,
            false,
            0x1080,
            2,
            &[0x00, 0x20, 0x80, 0x41, 0x60, 0x07, 0x00, 0x00, 0x02, 0x06],
        ),
    ];
    let summary = summarize(&messages, true);
    let slave = &summary.ethercat.slaves[0];
    assert_eq!(
        slave.mailbox_guessed, 4,
        "no sync manager seen: the areas are guessed"
    );
    assert_eq!(
        (slave.sdo_requests, slave.sdo_ok, slave.sdo_aborts),
        (3, 1, 1)
    );
    // Request at packet 2, response at packet 4: 1 ms.
    assert_eq!(slave.sdo_latency_max_ns, Some(1_000_000));
    let abort = slave.sdo_abort_list[0];
    assert_eq!(
        (abort.index, abort.subindex, abort.code.get()),
        (0x6041, 7, 0x0602_0000)
    );
    assert!(abort.from_slave);
    assert_eq!(abort.packet, 8);
    let text = summary.to_string();
    assert!(text.contains("SDO abort 6041sub7 0x06020000"), "{text}");
}

/// A stream's frames that never come back are its `lost`, each handed on
/// at its sent packet; its returned copies are handed on with their
/// working counters, and the facts of `add_with` are the record's
/// (docs/ethercat.md#cycle-health).
#[test]
fn a_streams_lost_frames_and_working_counters_are_its_records() {
    use motionwire::can::{EthercatPacket, LogEvent, Timestamp};
    use motionwire::ethercat::{Command, Encapsulation, EthercatLink, Mac};
    use motionwire::summary::{EthercatFact, SummaryEventKind};
    // Ten LRW cycles: cycle 4 never comes back (the return of cycle 5
    // passes it over), cycle 6 comes back with working counter 2, cycle 9
    // is still waiting at the end.
    let cycles: Vec<[Vec<u8>; 2]> = (0..10u8)
        .map(|i| copies(Command::Lrw, i, 0, &[0; 4], &[1; 4]))
        .collect();
    let mut packets: Vec<(Vec<u8>, [u8; 6])> = Vec::new();
    for (i, [sent, returned]) in cycles.iter().enumerate() {
        packets.push((sent.clone(), [0x10; 6]));
        if i == 4 || i == 9 {
            continue;
        }
        let mut returned = returned.clone();
        let wkc = if i == 6 { 2u16 } else { 3 };
        let end = returned.len();
        returned[end - 2..].copy_from_slice(&wkc.to_le_bytes());
        packets.push((returned, [0x12, 0x10, 0x10, 0x10, 0x10, 0x10]));
    }
    let mut summarizer = motionwire::summary::Summarizer::default();
    let (mut lost_at, mut wkcs) = (Vec::new(), Vec::new());
    let mut on_event = |event: motionwire::summary::SummaryEvent<'_>| match event.kind {
        SummaryEventKind::Ethercat(EthercatFact::StreamLost { command, .. }) => {
            assert_eq!(command, Command::Lrw);
            lost_at.push(event.line);
        }
        SummaryEventKind::Ethercat(EthercatFact::StreamReturned { wkc, .. }) => wkcs.push(wkc),
        _ => {}
    };
    for (n, (payload, source)) in packets.iter().enumerate() {
        let number = n as u64 + 1;
        let packet = EthercatPacket {
            timestamp: Timestamp::new(1_700_000_000, number as u32 * 500),
            iface: None,
            link: EthercatLink {
                destination: None,
                source: Mac(*source),
                encapsulation: Encapsulation::Ethernet,
                payload,
            },
        };
        let event = LogEvent::Ethercat(packet);
        let _ = summarizer.add_with(logs::Position::Record(number), &event, &mut on_event);
    }
    let summary = summarizer.finish_with(&mut on_event);
    let lrw = &summary.ethercat.streams[0];
    assert_eq!((lrw.sent, lrw.returned, lrw.lost), (10, 8, 2));
    assert_eq!((lrw.wkc_usual, lrw.wkc_mismatches), (Some(3), 1));
    // Cycle 4 was sent as packet 9, cycle 9 as packet 18.
    assert_eq!(lost_at, [9, 18]);
    assert_eq!(wkcs.len(), 8);
    assert_eq!(wkcs.iter().filter(|&&w| w != 3).count(), 1);
    assert_eq!(summary.ethercat.ports[0].counts.lost, 2, "as the session");
    assert!(summary.to_string().contains(": 10 frames, 2 lost,"));
}

/// The `coe_sdo` record that completes a transfer carries its data, the
/// object's name and whether the data was cut (docs/ethercat.md#coe-sdo):
/// the EK1914 answers the upload of 0x1008 with its name, and every
/// transfer of the fixtures keeps all it carried (none passes 258 bytes).
#[test]
fn a_completed_coe_transfer_carries_its_data_and_object() {
    use crate::common::{decode, path, records};
    use motionwire::decoder::ethercat::COE_DATA_KEPT;
    let mut transfers = 0;
    for name in CAPTURES {
        let file = path(&format!("tests/data/ethercat/{name}.pcapng"));
        for record in records(&decode(&["--json", &file])) {
            let Some(transfer) = record.get("transfer").filter(|t| !t.is_null()) else {
                continue;
            };
            transfers += 1;
            let size = transfer["size"].as_u64().unwrap() as usize;
            let data = transfer["data"].as_str().unwrap();
            assert_eq!(data.len() / 2, size.min(COE_DATA_KEPT), "{record}");
            assert_eq!(transfer["truncated"], size > COE_DATA_KEPT, "{record}");
            if transfer["index"] == 0x1008 {
                assert_eq!(transfer["object"], "Manufacturer device name");
                // "EK1914" in ASCII.
                assert_eq!(data, "454b31393134", "{record}");
            }
        }
    }
    assert!(transfers > 20, "{transfers} transfers");
}
