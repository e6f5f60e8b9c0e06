//! The station alias, the distributed-clock registers, SM1's polls and the
//! mailbox repeat (docs/ethercat.md#alias, #dc, #mailbox-repeat): on the
//! real captures that touch them, against the bytes tshark dissects
//! (`tests/data/ethercat/*.tshark.tsv`), and on the captures
//! scripts/ecat_pcapng.py writes for what no real one shows.

use std::collections::BTreeMap;
use std::path::Path;

use motionwire::can::LogEvent;
use motionwire::decoder::ethercat::{DcRegisters, FrameCopy, Meaning, Session, SlaveRef};
use motionwire::logs::{self, ReadLog};

fn path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(name)
}

/// What the session tells of the alias, the clock and the mailbox
/// protocol, by (packet, datagram from 1).
#[derive(Debug, Clone, PartialEq, Eq)]
enum Told {
    Alias(SlaveRef, Option<u16>, Option<bool>),
    Dc(SlaveRef, bool, DcRegisters),
    Distribution(SlaveRef, Option<u64>, u16),
    Poll(SlaveRef, bool),
    Repeat(SlaveRef, bool),
    /// A mailbox message: written, counter, repeated.
    Message(SlaveRef, bool, u8, bool),
    /// An AL status read.
    AlStatus(SlaveRef),
}

fn told(name: &str) -> (BTreeMap<(u64, usize), Vec<Told>>, Session) {
    let mut log = logs::open(path(&format!("{name}.pcapng"))).unwrap();
    let mut session = Session::new();
    let mut all: BTreeMap<(u64, usize), Vec<Told>> = BTreeMap::new();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        let packet = session.read(record.position, &packet).unwrap();
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = datagram.unwrap();
            let mut here = Vec::new();
            session.meanings(&packet, at, &datagram, |m| {
                here.push(match m {
                    Meaning::StationAlias {
                        slave,
                        alias,
                        enabled,
                    } => Told::Alias(slave, alias, enabled),
                    Meaning::Dc {
                        slave,
                        written,
                        registers,
                    } => Told::Dc(slave, written, registers),
                    Meaning::DcDistribution {
                        slave,
                        system_time,
                        wkc,
                    } => Told::Distribution(slave, system_time, wkc),
                    Meaning::MailboxPoll { slave, full } => Told::Poll(slave, full),
                    Meaning::MailboxRepeat {
                        slave,
                        acknowledged,
                    } => Told::Repeat(slave, acknowledged),
                    Meaning::Mailbox {
                        slave,
                        written,
                        header,
                        repeated,
                        ..
                    } => Told::Message(slave, written, header.counter, repeated),
                    Meaning::AlState { slave, .. } => Told::AlStatus(slave),
                    _ => return,
                });
            });
            if !here.is_empty() {
                all.insert((record.position.number(), at + 1), here);
            }
        }
    }
    (all, session)
}

/// One returned datagram of tshark's dissection.
struct Row {
    frame: u64,
    dg: usize,
    cmd: u8,
    adp: u16,
    ado: u16,
    wkc: u16,
    data: Vec<u8>,
}

/// tshark's returned datagrams (the source MAC's bit 0x02 set; none of
/// these captures has a master whose own MAC has it).
fn returned_rows(name: &str) -> Vec<Row> {
    let text = std::fs::read_to_string(path(&format!("{name}.tshark.tsv"))).unwrap();
    let hex = |s: &str| u16::from_str_radix(s.trim_start_matches("0x"), 16).unwrap();
    text.lines()
        .skip(1)
        .filter_map(|line| {
            let c: Vec<&str> = line.split('\t').collect();
            let first = u8::from_str_radix(&c[2][..2], 16).unwrap();
            if first & 0x02 == 0 || c[5].is_empty() {
                return None;
            }
            Some(Row {
                frame: c[0].parse().unwrap(),
                dg: c[1].parse().unwrap(),
                cmd: hex(c[3]) as u8,
                adp: hex(c[5]),
                ado: hex(c[6]),
                wkc: c[9].parse().unwrap(),
                data: (0..c[11].len())
                    .step_by(2)
                    .map(|i| u8::from_str_radix(&c[11][i..i + 2], 16).unwrap())
                    .collect(),
            })
        })
        .collect()
}

/// The bytes of `register` (`len` long) in a row's data, where it covers
/// them.
fn at(row: &Row, register: u16, len: usize) -> Option<&[u8]> {
    let start = usize::from(register.checked_sub(row.ado)?);
    row.data.get(start..start + len)
}

fn le32(b: &[u8]) -> u32 {
    u32::from_le_bytes([b[0], b[1], b[2], b[3]])
}

const APRD: u8 = 1;
const APWR: u8 = 2;
const FPRD: u8 = 4;
const FPWR: u8 = 5;
const ARMW: u8 = 13;
const FRMW: u8 = 14;

/// The real captures that read or write the clock and the alias
/// (`tshark -T fields -e ecat.cmd -e ecat.ado`: TwinCAT's APRD of 0x0900
/// with 32 bytes, FPWR of 0x0980 and ARMW of 0x0910; the replays' FPWR
/// of 0x0981 and 0x09A0, FPRD of 0x092C and 0x0012, FRMW of 0x0910;
/// SOEM's FPRD of 0x0012 and 0x0910; the offset 0x0920 and delay 0x0928
/// that TwinCAT, SOEM and ethercrab write): every register tshark shows covered
/// in a returned datagram that a slave took is decoded with its value.
#[test]
fn dc_and_alias_registers_read_as_tshark_shows_their_bytes() {
    let mut checked = BTreeMap::new();
    for name in [
        "twincat-akd-startup",
        "replay-dc",
        "replay-ek1100-el2828-el2889",
        "soem-akd-sdo",
        "soem-single-lan9252",
    ] {
        let (all, _) = told(name);
        for row in returned_rows(name) {
            if row.wkc == 0 {
                continue;
            }
            let here = all.get(&(row.frame, row.dg)).cloned().unwrap_or_default();
            let dc = here.iter().find_map(|t| match t {
                Told::Dc(_, written, r) => Some((*written, *r)),
                _ => None,
            });
            let what = format!("{name}: frame {} datagram {}", row.frame, row.dg);
            let read = matches!(row.cmd, APRD | FPRD);
            let written = matches!(row.cmd, APWR | FPWR);
            if matches!(row.cmd, ARMW | FRMW) {
                if let Some(b) = at(&row, 0x0910, 4) {
                    let time = at(&row, 0x0910, 8)
                        .map(|b| u64::from_le_bytes(b.try_into().unwrap()))
                        .unwrap_or(u64::from(le32(b)));
                    assert!(
                        here.iter()
                            .any(|t| matches!(t, Told::Distribution(s, Some(v), w)
                                if *v == time && *w == row.wkc
                                    && (row.cmd == ARMW || s.station == Some(row.adp)))),
                        "{what}: {here:?}"
                    );
                    *checked.entry("distribution").or_insert(0) += 1;
                }
                assert!(dc.is_none(), "{what}");
                continue;
            }
            if read || written {
                if let Some(b) = at(&row, 0x0012, 2).filter(|_| read) {
                    let alias = u16::from_le_bytes([b[0], b[1]]);
                    assert!(
                        here.iter()
                            .any(|t| matches!(t, Told::Alias(_, Some(a), _) if *a == alias)),
                        "{what}"
                    );
                    *checked.entry("alias").or_insert(0) += 1;
                }
                for p in 0..4u16 {
                    if let Some(b) = at(&row, 0x0900 + 4 * p, 4).filter(|_| read) {
                        let r = dc.expect(&what).1;
                        assert_eq!(r.receive_times[usize::from(p)], Some(le32(b)), "{what}");
                        *checked.entry("receive time").or_insert(0) += 1;
                    }
                }
                if let Some(b) = at(&row, 0x0920, 4) {
                    let offset = match at(&row, 0x0920, 8) {
                        Some(b) => i64::from_le_bytes(b.try_into().unwrap()),
                        None => i64::from(le32(b) as i32),
                    };
                    let (w, r) = dc.expect(&what);
                    assert_eq!(
                        (w, r.system_time_offset_ns),
                        (written, Some(offset)),
                        "{what}"
                    );
                    *checked.entry("system time offset").or_insert(0) += 1;
                }
                if let Some(b) = at(&row, 0x0928, 4) {
                    let (w, r) = dc.expect(&what);
                    assert_eq!(
                        (w, r.system_time_delay_ns),
                        (written, Some(le32(b))),
                        "{what}"
                    );
                    *checked.entry("system time delay").or_insert(0) += 1;
                }
                if let Some(b) = at(&row, 0x092C, 4).filter(|_| read) {
                    let raw = le32(b);
                    let magnitude = i64::from(raw & 0x7FFF_FFFF);
                    let ns = if raw >> 31 == 1 {
                        -magnitude
                    } else {
                        magnitude
                    };
                    assert_eq!(dc.expect(&what).1.time_difference_ns, Some(ns), "{what}");
                    *checked.entry("time difference").or_insert(0) += 1;
                }
                if let Some(b) = at(&row, 0x0981, 1) {
                    let (w, r) = dc.expect(&what);
                    assert_eq!((w, r.activation), (written, Some(b[0])), "{what}");
                    *checked.entry("activation").or_insert(0) += 1;
                }
                if let Some(b) = at(&row, 0x09A0, 4) {
                    assert_eq!(dc.expect(&what).1.sync0_cycle_ns, Some(le32(b)), "{what}");
                    *checked.entry("sync0 cycle").or_insert(0) += 1;
                }
            }
        }
    }
    // What the five captures hold in returned datagrams a slave took:
    // activation, the replay's 4 FPWR of 0x0981 and TwinCAT's FPWR of
    // 0x0980 with 2 bytes; the alias, 3 + 3 + 1 + 1 FPRD of 0x0012;
    // receive times, TwinCAT's 20 APRD of 32 bytes (4 each), the replays'
    // 2 × 3 FPRD of 16 bytes, SOEM's 2 × 4 FPRD of 4; the replay's 2 FPWR
    // of 0x09A0 and 2 FPRD of 0x092C; the replays' 357 + 100 FRMW and
    // TwinCAT's 36 ARMW of 0x0910; the system-time offset, the replays'
    // 2 × 2 FPWR of 0x0920 (ethercrab: negative offsets), SOEM's 2 FPWR
    // and TwinCAT's APWR; its delay, the replays' 2 × 2 FPWR of 0x0928
    // and TwinCAT's APWR (the writes to a slave without a clock, working
    // counter 0, and the BWRs name no value).
    assert_eq!(
        checked,
        BTreeMap::from([
            ("activation", 5),
            ("alias", 8),
            ("distribution", 493),
            ("receive time", 112),
            ("sync0 cycle", 2),
            ("system time delay", 5),
            ("system time offset", 7),
            ("time difference", 2),
        ])
    );
}

/// An FPxx to an alias reaches the slave whose alias it is once DL
/// control enables it; SM1's polls are polls; a message read again after
/// the master's repeat request (0x080E bit 1 toggled, 0x080F's
/// acknowledge) is the same message, counted once; the clock's
/// configuration and reads are the slave's, its distribution the
/// reference clock's (scripts/ecat_pcapng.py --fixture registers).
#[test]
fn the_generated_registers_capture_reads_as_written() {
    let (all, _) = told("synthetic_registers");
    let slave = SlaveRef {
        station: Some(0x1001),
        position: Some(1),
    };
    let coupler = SlaveRef {
        station: Some(0x1000),
        position: Some(0),
    };
    let get = |packet: u64| all.get(&(packet, 1)).cloned().unwrap_or_default();
    // The BWR of 0x0103 names no slave; the alias read, enabled, used.
    assert_eq!(
        get(4),
        [Told::Alias(SlaveRef::default(), None, Some(false))]
    );
    assert_eq!(get(10), [Told::Alias(slave, Some(0x0077), None)]);
    assert_eq!(get(12), [Told::Alias(slave, None, Some(true))]);
    assert_eq!(get(14), [Told::AlStatus(slave)]);
    // The mailbox: polls, the response, the repeat, the same response.
    assert_eq!(get(20), [Told::Poll(slave, false)]);
    assert_eq!(get(22), [Told::Poll(slave, true)]);
    assert_eq!(get(24), [Told::Message(slave, false, 1, false)]);
    assert_eq!(get(26), [Told::Poll(slave, false)]);
    assert_eq!(get(28), [Told::Repeat(slave, false)]);
    assert_eq!(get(30), [Told::Repeat(slave, true)]);
    assert_eq!(get(32), [Told::Poll(slave, true)]);
    assert_eq!(get(34), [Told::Message(slave, false, 1, true)]);
    assert_eq!(get(38), [Told::Message(slave, false, 2, false)]);
    // The clock.
    let Told::Dc(_, true, cycles) = get(46)[0] else {
        panic!("{:?}", get(46))
    };
    assert_eq!(
        (cycles.sync0_cycle_ns, cycles.sync1_cycle_ns),
        (Some(1_000_000), Some(0))
    );
    let distributions: Vec<_> = all
        .values()
        .flatten()
        .filter(|t| matches!(t, Told::Distribution(s, Some(_), 2) if *s == coupler))
        .collect();
    assert_eq!(distributions.len(), 10);

    // The summary counts the repeated message once.
    let mut log = logs::open(path("synthetic_registers.pcapng")).unwrap();
    let mut summarizer = motionwire::summary::Summarizer::default();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        summarizer.add(record.position, &record.event);
    }
    let summary = summarizer.finish();
    let s = &summary.ethercat.slaves[1];
    assert_eq!(s.station, Some(0x1001));
    assert_eq!((s.mailbox_written, s.mailbox_read), (2, 2));
    assert_eq!((s.sdo_requests, s.sdo_responses, s.sdo_ok), (2, 2, 2));
    let r = &s.registers;
    assert_eq!((r.alias, r.alias_enabled), (Some(0x0077), Some(true)));
    assert_eq!((r.mailbox_polls, r.mailbox_polls_full), (4, 2));
    assert_eq!((r.mailbox_repeat_requests, r.mailbox_repeated), (1, 1));
    let dc = r.dc.unwrap();
    assert_eq!(dc.activation, Some(0x03));
    assert_eq!(dc.sync0_cycle_ns, Some(1_000_000));
    assert_eq!(dc.receive_times, [Some(1000), Some(1400), Some(0), Some(0)]);
    assert_eq!(
        (
            dc.time_difference_reads,
            dc.time_difference_last_ns,
            dc.time_difference_min_ns,
            dc.time_difference_max_ns
        ),
        (3, Some(3), Some(-9), Some(20))
    );
    assert_eq!(dc.distributions, 0);
    // The BWR of 0x0103 before the slaves were known is every slave's.
    assert_eq!(
        summary.ethercat.slaves[0].registers.alias_enabled,
        Some(false)
    );
    let reference = summary.ethercat.slaves[0].registers.dc.unwrap();
    assert_eq!(reference.distributions, 10);
}

/// `Session::station`: an FPxx names the slave it reaches — by its
/// station address, or by the alias DL control enabled (packets 13 and
/// 14 read AL status at alias 0x0077, the slave 0x1001's) — and a
/// datagram addressed otherwise names none
/// (scripts/ecat_pcapng.py --fixture registers).
#[test]
fn a_datagram_to_an_enabled_alias_names_the_station_it_reaches() {
    let mut log = logs::open(path("synthetic_registers.pcapng")).unwrap();
    let mut session = Session::new();
    let (mut by_alias, mut by_station, mut none) = (Vec::new(), 0, 0);
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        let packet = session.read(record.position, &packet).unwrap();
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = datagram.unwrap();
            match session.station(&packet, &datagram) {
                Some(station) if station != datagram.adp() => {
                    by_alias.push((record.position.number(), datagram.adp(), station));
                }
                Some(_) => by_station += 1,
                None => none += 1,
            }
            session.meanings(&packet, at, &datagram, |_| {});
        }
    }
    assert_eq!(by_alias, [(13, 0x0077, 0x1001), (14, 0x0077, 0x1001)]);
    // The other FPRD, FPWR and FRMW; the APRD, APWR and BWR.
    assert_eq!((by_station, none), (60, 12));
}

/// A master whose own MAC has bit 0x02 set sends frames that look
/// returned: order decides, the first of a pair is the sent copy
/// (scripts/ecat_pcapng.py --fixture local_mac: six exchanges, the
/// fourth lost).
#[test]
fn a_master_whose_mac_has_the_bit_is_paired_by_order() {
    let mut log = logs::open(path("synthetic_local_mac.pcapng")).unwrap();
    let mut session = Session::new();
    let mut copies = Vec::new();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        assert!(packet.link.source.returned_bit());
        let packet = session.read(record.position, &packet).unwrap();
        copies.push(match packet.copy {
            FrameCopy::Sent => "sent".to_owned(),
            FrameCopy::Returned { sent } => format!("returned {}", sent.number()),
            FrameCopy::ReturnedUnpaired => "unpaired".to_owned(),
        });
    }
    assert_eq!(
        copies,
        [
            "sent",
            "returned 1",
            "sent",
            "returned 3",
            "sent",
            "returned 5",
            "sent",
            "sent",
            "returned 8",
            "sent",
            "returned 10",
        ]
    );
    let counts = session.finish();
    assert_eq!(
        (
            counts.sent,
            counts.returned,
            counts.lost,
            counts.returned_unpaired
        ),
        (6, 5, 1, 0)
    );
}
