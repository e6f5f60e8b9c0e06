//! The generated capture of a servo and two CiA 402 drives
//! (tests/common/ecat_drives.rs; tests/data/ethercat/README.md,
//! "drives.pcapng"): the committed fixture is what the generator writes,
//! every datagram and mailbox message reads through the crate's public
//! API as tshark reads it, and the model record names every fault at the
//! packets that show it.

use crate::ecat_drives;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use motionwire::can::LogEvent;
use motionwire::canopen::Emcy;
use motionwire::ethercat::{
    Addressing, CoeHeader, CoeSdo, CoeService, Command, EthercatFrame, MailboxHeader, MailboxType,
};
use motionwire::logs::{self, ReadLog};
use serde_json::Value;

use ecat_drives::{Schedule, DRIVE_A, DRIVE_B, SERVO};

/// The cycles of the committed fixture (scripts/gen_ecat_fixtures.sh).
const FIXTURE_CYCLES: u32 = 1000;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(name)
}

/// One datagram as the crate reads it.
#[derive(Debug, Clone)]
struct Datagram {
    command: Command,
    index: u8,
    address: u32,
    adp: u16,
    ado: u16,
    wkc: u16,
    irq: u16,
    data: Vec<u8>,
}

/// One packet of the capture as the crate reads it.
#[derive(Debug, Clone)]
struct Packet {
    number: u64,
    ns: u64,
    source: String,
    returned: bool,
    datagrams: Vec<Datagram>,
}

/// Read the fixture with `motionwire::logs` and take its datagrams with
/// `motionwire::ethercat`.
fn packets() -> Vec<Packet> {
    let mut log = logs::open(data("drives.pcapng")).unwrap();
    let mut packets = Vec::new();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        let LogEvent::Ethercat(packet) = record.event else {
            panic!("only EtherCAT packets, found {}", record.event)
        };
        let ts = packet.timestamp.expect("every packet has a time");
        let frame = EthercatFrame::parse(packet.link.payload).unwrap();
        let datagrams = frame
            .datagrams()
            .map(|d| {
                let d = d.unwrap();
                Datagram {
                    command: d.command(),
                    index: d.index(),
                    address: d.address(),
                    adp: d.adp(),
                    ado: d.ado(),
                    wkc: d.working_counter(),
                    irq: d.irq(),
                    data: d.data().to_vec(),
                }
            })
            .collect();
        packets.push(Packet {
            number: record.position.number(),
            ns: ts.secs() * 1_000_000_000 + u64::from(ts.subsec_nanos()),
            source: packet.link.source.to_string(),
            returned: packet.link.source.returned_bit(),
            datagrams,
        });
    }
    packets
}

/// The model record, one JSON object per line.
fn model() -> Vec<Value> {
    std::fs::read_to_string(data("drives.model.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn the_fixture_is_what_the_generator_writes() {
    let (mut capture, mut record, mut eni) = (Vec::new(), Vec::new(), Vec::new());
    let written = ecat_drives::write(FIXTURE_CYCLES, &mut capture, &mut record, &mut eni).unwrap();
    assert_eq!(written.packets, 2215);
    for (name, ours) in [
        ("drives.pcapng", &capture),
        ("drives.model.jsonl", &record),
        ("drives.eni.xml", &eni),
    ] {
        let committed = std::fs::read(data(name)).unwrap();
        assert!(
            *ours == committed,
            "{name} differs from what the generator writes: run scripts/gen_ecat_fixtures.sh"
        );
    }
    // Too few cycles for the faults to complete is refused.
    let err = ecat_drives::write(
        ecat_drives::MIN_CYCLES - 1,
        Vec::new(),
        Vec::new(),
        Vec::new(),
    )
    .unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
}

#[test]
fn every_datagram_reads_as_tshark_reads_it() {
    let mut ours =
        String::from("frame\tdg\teth_src\tcmd\tidx\tadp\tado\tlad\tlen\twkc\tirq\tdata\n");
    for p in packets() {
        for (at, d) in p.datagrams.iter().enumerate() {
            let (adp, ado, lad) = if d.command.addressing() == Addressing::Logical {
                (String::new(), String::new(), format!("{:#010x}", d.address))
            } else {
                (
                    format!("{:#06x}", d.adp),
                    format!("{:#06x}", d.ado),
                    String::new(),
                )
            };
            let hex: String = d.data.iter().map(|b| format!("{b:02x}")).collect();
            writeln!(
                ours,
                "{}\t{}\t{}\t{:#04x}\t{:#04x}\t{adp}\t{ado}\t{lad}\t{}\t{}\t{:#06x}\t{hex}",
                p.number,
                at + 1,
                p.source,
                d.command.byte(),
                d.index,
                d.data.len(),
                d.wkc,
                d.irq,
            )
            .unwrap();
        }
    }
    let theirs = std::fs::read_to_string(data("drives.tshark.tsv")).unwrap();
    let (ours, theirs): (Vec<_>, Vec<_>) = (ours.lines().collect(), theirs.lines().collect());
    for (line, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert_eq!(a, b, "row {line}");
    }
    assert_eq!(ours.len(), theirs.len(), "rows");
    // Every cycle's frame: one LRW and one BRD, sent and returned.
    assert_eq!(ours.len() - 1, 4214);
}

#[test]
fn every_mailbox_message_reads_as_tshark_reads_it() {
    // The copies that prove a message was delivered: returned, and a read
    // with a working counter of at least 1 (docs/ethercat.md#mailbox).
    let mut ours = Vec::new();
    for p in packets().iter().filter(|p| p.returned) {
        for (at, d) in p.datagrams.iter().enumerate() {
            let mailbox = matches!(
                (d.command, d.ado),
                (Command::Fpwr, 0x1000) | (Command::Fprd, 0x1080)
            ) && d.adp != SERVO;
            if !mailbox || d.wkc == 0 {
                continue;
            }
            let header = MailboxHeader::parse(&d.data).unwrap();
            assert_eq!(header.mailbox_type, MailboxType::Coe);
            let body = &d.data[6..6 + usize::from(header.length)];
            let coe = CoeHeader::parse(body).unwrap();
            let mut row = format!(
                "{}\t{}\t{}\t{}\t{}",
                p.number,
                at + 1,
                header.length,
                header.counter,
                coe.service.bits()
            );
            match coe.service {
                CoeService::SdoRequest | CoeService::SdoResponse => {
                    let (index, sub) = CoeSdo::parse(&body[2..]).unwrap().multiplexer().unwrap();
                    write!(row, "\t{index:#06x}\t{sub:#04x}").unwrap();
                }
                CoeService::Emergency => row.push_str("\t\t"),
                other => panic!("packet {}: CoE service {other:?}", p.number),
            }
            ours.push(row);
        }
    }
    let text = std::fs::read_to_string(data("drives.coe.tsv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split('\t').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let [frame, dg, src, cmd, wkc, len, cnt, coe, idx, sub] = [
        "frame", "dg", "eth_src", "dg_cmd", "dg_wkc", "mbx_len", "mbx_cnt", "coe_type", "sdo_idx",
        "sdo_sub",
    ]
    .map(column);
    let theirs: Vec<String> = lines
        .map(|line| line.split('\t').collect::<Vec<_>>())
        .filter(|f| f[src].starts_with("02:") && (f[cmd] != "0x04" || f[wkc] != "0"))
        .map(|f| [f[frame], f[dg], f[len], f[cnt], f[coe], f[idx], f[sub]].join("\t"))
        .collect();
    assert_eq!(ours, theirs);
    // 23 SDO transfers (16 to drive A, 7 to drive B), each a request and
    // a response, and two emergencies.
    assert_eq!(ours.len(), 2 * 23 + 2);
}

/// The packet numbered `number`.
fn packet(packets: &[Packet], number: u64) -> &Packet {
    &packets[usize::try_from(number - 1).unwrap()]
}

fn field<'a>(record: &'a Value, key: &str) -> &'a Value {
    record
        .get(key)
        .unwrap_or_else(|| panic!("{key} in {record}"))
}

fn number(record: &Value, key: &str) -> u64 {
    field(record, key)
        .as_u64()
        .unwrap_or_else(|| panic!("{key} in {record}"))
}

fn text<'a>(record: &'a Value, key: &str) -> &'a str {
    field(record, key)
        .as_str()
        .unwrap_or_else(|| panic!("{key} in {record}"))
}

#[test]
fn the_model_record_names_every_fault_where_the_capture_shows_it() {
    let packets = packets();
    let records = model();
    let s = Schedule::new(FIXTURE_CYCLES);
    let of = |kind: &str| -> Vec<&Value> {
        records.iter().filter(|r| text(r, "kind") == kind).collect()
    };

    // Every record is on a packet of its cycle's frame, at that packet's
    // time; cycles never go back.
    let mut last_cycle = 0;
    for r in &records {
        let p = packet(&packets, number(r, "packet"));
        let lrw = &p.datagrams[0];
        assert_eq!(lrw.command, Command::Lrw, "{r}");
        let ts = field(r, "ts").as_f64().unwrap();
        assert!((ts - p.ns as f64 / 1e9).abs() < 1e-6, "{r}");
        let cycle = number(r, "cycle");
        assert!(cycle >= last_cycle, "{r}");
        last_cycle = cycle;
    }

    // (a) SEW FollowerErr (E09): set in its cycle, cleared by the NC's
    // error-clear handshake, and the NC enables again.
    let sew_set = of("sew_set");
    let sew_cleared = of("sew_cleared");
    let e09 = |rs: &[&Value]| {
        rs.iter()
            .find(|r| text(r, "e_code") == "E09")
            .map(|r| number(r, "cycle"))
            .unwrap()
    };
    assert_eq!(e09(&sew_set), u64::from(s.sew_error));
    let e09_cleared = e09(&sew_cleared);
    let clears = of("error_clear");
    assert!(clears.iter().any(|r| text(r, "to") == "acknowledged"
        && number(r, "cycle") > u64::from(s.sew_error)
        && number(r, "cycle") <= e09_cleared + 1));
    let enabled: Vec<u64> = of("servo_enable")
        .iter()
        .filter(|r| text(r, "to") == "enabled")
        .map(|r| number(r, "cycle"))
        .collect();
    assert!(enabled
        .iter()
        .any(|&c| c > e09_cleared && c < u64::from(s.home)));

    // (c) the lost encoder (E01): the enable times out once, then the NC
    // clears again and the drive enables.
    let e01 = |rs: &[&Value]| {
        rs.iter()
            .find(|r| text(r, "e_code") == "E01")
            .map(|r| number(r, "cycle"))
            .unwrap()
    };
    assert_eq!(e01(&sew_set), u64::from(s.encoder_lost));
    let timeouts = of("enable_timeout");
    assert_eq!(timeouts.len(), 1);
    let timeout = number(timeouts[0], "cycle");
    assert_eq!(number(timeouts[0], "cycles"), u64::from(s.timeout));
    assert!(timeout > u64::from(s.encoder_back) && timeout < e01(&sew_cleared));
    assert!(enabled.iter().any(|&c| c > e01(&sew_cleared)));

    // (e) the zero pulse: requested, acknowledged with its position, done.
    let zero: Vec<&str> = of("zero_pulse").iter().map(|r| text(r, "to")).collect();
    assert_eq!(zero, ["requested", "acknowledged", "done"]);
    assert_eq!(number(of("zero_pulse")[0], "cycle"), u64::from(s.home));
    assert_eq!(number(of("zero_pulse")[1], "position") % 10_000, 1_000);

    // (b) the lost frame: the record is on the sent copy, and the next
    // packet is the next cycle's sent copy.
    let lost = of("lost_frame");
    assert_eq!(lost.len(), 1);
    assert_eq!(number(lost[0], "cycle"), u64::from(s.lost_frame));
    assert!(lost[0]["slave"].is_null());
    let sent = packet(&packets, number(lost[0], "packet"));
    let next = packet(&packets, sent.number + 1);
    assert!(!sent.returned && !next.returned);
    assert_eq!(next.ns - sent.ns, ecat_drives::CYCLE_NS);
    let lost_frames = packets
        .iter()
        .filter(|p| !p.returned)
        .filter(|p| {
            !matches!(
                packets.get(usize::try_from(p.number).unwrap()),
                Some(next) if next.returned
            )
        })
        .count();
    assert_eq!(
        lost_frames, 1,
        "no other sent frame goes without its return"
    );

    // (b) the servo takes no part: LRW working counter 6, its inputs
    // returned as they were sent.
    let short = of("short_wkc");
    assert_eq!(short.len(), 1);
    assert_eq!(
        (number(short[0], "slave"), number(short[0], "cycle")),
        (u64::from(SERVO), u64::from(s.servo_absent))
    );
    let returned = packet(&packets, number(short[0], "packet"));
    let sent = packet(&packets, returned.number - 1);
    assert!(returned.returned && !sent.returned);
    assert_eq!(returned.datagrams[0].wkc, 6);
    assert_eq!(
        returned.datagrams[0].data[24..64],
        sent.datagrams[0].data[24..64]
    );
    let short_lrws = packets
        .iter()
        .filter(|p| p.returned && p.datagrams[0].command == Command::Lrw)
        .filter(|p| p.datagrams[0].wkc != ecat_drives::LRW_WKC)
        .count();
    assert_eq!(short_lrws, 1);

    // (d) drive A: fault reaction active, fault, the fault reset, and back
    // to operation enabled; each statusword as the returned LRW carries it.
    let a: Vec<&Value> = of("cia402_state")
        .into_iter()
        .filter(|r| number(r, "slave") == u64::from(DRIVE_A))
        .collect();
    let path: Vec<&str> = a
        .iter()
        .filter(|r| number(r, "cycle") >= u64::from(s.drive_fault))
        .map(|r| text(r, "to"))
        .collect();
    assert_eq!(
        path,
        [
            "fault_reaction_active",
            "fault",
            "switch_on_disabled",
            "ready_to_switch_on",
            "switched_on",
            "operation_enabled"
        ]
    );
    for r in of("cia402_state") {
        let at = if number(r, "slave") == u64::from(DRIVE_A) {
            64
        } else {
            assert_eq!(number(r, "slave"), u64::from(DRIVE_B));
            71
        };
        let lrw = &packet(&packets, number(r, "packet")).datagrams[0].data;
        let statusword = u16::from_le_bytes([lrw[at], lrw[at + 1]]);
        assert_eq!(u64::from(statusword), number(r, "statusword"), "{r}");
    }
    // Drive B never faults.
    assert!(of("cia402_state")
        .iter()
        .filter(|r| number(r, "slave") == u64::from(DRIVE_B))
        .all(|r| !text(r, "to").contains("fault")));

    // The emergencies: 0x2310 with the fault, 0x0000 after the reset, each
    // read from drive A's SM1 mailbox in a frame of its own.
    let emcys = of("emcy");
    assert_eq!(emcys.len(), 2);
    for (r, (code, register)) in emcys.iter().zip([(0x2310, 0x03), (0x0000, 0x00)]) {
        assert_eq!((number(r, "code"), number(r, "register")), (code, register));
        let read = packet(&packets, number(r, "mailbox_packet"));
        assert!(read.returned);
        let [d] = &read.datagrams[..] else {
            panic!("one datagram in {read:?}")
        };
        assert_eq!(
            (d.command, d.adp, d.ado, d.wkc),
            (Command::Fprd, DRIVE_A, 0x1080, 1)
        );
        let header = MailboxHeader::parse(&d.data).unwrap();
        let coe = CoeHeader::parse(&d.data[6..]).unwrap();
        assert_eq!((header.length, coe.service), (10, CoeService::Emergency));
        let emcy = Emcy::parse(&d.data[8..16]).unwrap();
        assert_eq!(
            (u64::from(emcy.code.get()), u64::from(emcy.register.bits())),
            (code, register)
        );
        // The mailbox-state bit told the master, in the cycle before.
        let cycle = packet(&packets, number(r, "packet"));
        assert_eq!(cycle.datagrams[0].data[78] & 1, 1);
    }
    assert_eq!(
        number(emcys[0], "cycle"),
        u64::from(s.drive_fault),
        "the emergency comes with the fault"
    );

    // ActPos once per 1000 cycles.
    assert_eq!(of("act_pos").len(), (FIXTURE_CYCLES / 1000) as usize);
}
