//! The EtherCAT session and its records (docs/ethercat.md#direction,
//! docs/ethercat.md#records): `motionwire::ethercat::{Session,
//! DatagramRecord}`.
//!
//! Arbitrary bytes → packets: each starts with a length byte and a flags
//! byte (bit 0: the returned bit of the source MAC, bits 1–2: one of four
//! interfaces, bit 3: another master, bit 4: a master whose own MAC has the
//! returned bit), then its EtherCAT payload. Invariants:
//! - nothing panics; a damaged packet is an error naming its position;
//! - a returned copy pairs only with an earlier sent packet;
//! - the counts add up: every packet is sent, returned, returned without
//!   its sent copy, of another frame type, or damaged; the frames lost are
//!   at most the frames sent, and after `finish` every sent frame is either
//!   returned or lost;
//! - every datagram's record is one line of valid JSON with the keys of
//!   docs/ethercat.md#records, and its text prints;
//! - the summary of the same packets (`Summarizer`) counts them as the
//!   session does, and every record is one JSON object with its `type`;
//! - a datagram names a slave's station (`Session::station`) exactly when
//!   it is station-addressed;
//! - what a datagram tells of the slaves comes from returned copies only,
//!   and every meaning's record is one line of JSON of its kind, its text
//!   one line;
//! - process data comes from returned cyclic datagrams only; an image is
//!   never longer than the datagram, a record is one line of JSON, a
//!   servo record too (every slave is read as a servo when its images
//!   are 10 and 40 bytes), and the text prints; a slave's inputs are
//!   confirmed as its working-counter verdict says, which is short only
//!   when the count is.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{EthercatPacket, Iface, LogEvent, Timestamp};
use motionwire::summary::Summarizer;
use motionwire::ethercat::{Addressing, Encapsulation, EthercatLink, Mac};
use motionwire::decoder::ethercat::{
    DatagramRecord, FrameCopy, MeaningRecord, ProcessRecord, ServoSlaves, Session,
};
use motionwire::logs::Position;

const NAMES: [&str; 4] = ["eth0", "eth1", "eth2", "eth3"];

fuzz_target!(|data: &[u8]| {
    let mut session = Session::new();
    session.set_servos(ServoSlaves {
        auto: true,
        stations: vec![(0x1001, None)],
    });
    let mut summarizer = Summarizer::default();
    let mut rest = data;
    let mut number = 0u64;
    let mut headers_damaged = 0u64;
    let mut json = Vec::new();
    while let [len, flags, tail @ ..] = rest {
        let len = usize::from(*len).min(tail.len());
        let (payload, after) = tail.split_at(len);
        rest = after;
        number += 1;
        let mut source = [if flags & 8 != 0 { 0x20 } else { 0x10 }; 6];
        // Bit 4: a master whose own MAC has the bit, paired by order.
        if flags & 1 != 0 || flags & 0x10 != 0 {
            source[0] |= Mac::RETURNED_BIT;
        }
        let packet = EthercatPacket {
            timestamp: Timestamp::new(number, 0),
            iface: Some(Iface::Name(NAMES[usize::from((flags >> 1) & 3)])),
            link: EthercatLink {
                destination: None,
                source: Mac(source),
                encapsulation: Encapsulation::Ethernet,
                payload,
            },
        };
        let position = Position::Record(number);
        summarizer.add(position, &LogEvent::Ethercat(packet));
        let read = match session.read(position, &packet) {
            Ok(read) => read,
            Err(damaged) => {
                assert_eq!(damaged.position, position);
                let _ = damaged.to_string();
                headers_damaged += 1;
                continue;
            }
        };
        if let FrameCopy::Returned { sent } = read.copy {
            assert!(sent < position);
        }
        for (at, datagram) in read.datagrams().enumerate() {
            let Ok(datagram) = datagram else {
                session.count_damaged();
                break;
            };
            let record = DatagramRecord {
                packet: &read,
                number: at + 1,
                datagram,
            };
            json.clear();
            record.append_json(&mut json, Some("f\"ile"));
            assert_eq!(json.last(), Some(&b'\n'));
            let value: serde_json::Value = serde_json::from_slice(&json).unwrap();
            assert_eq!(value["packet"], number);
            assert_eq!(value["kind"], "ecat_datagram");
            assert_eq!(value["returned"], read.copy.returned());
            assert_eq!(value["data"].as_str().unwrap().len(), datagram.data().len() * 2);
            let mut text = Vec::new();
            record.write_text(&mut text, None).unwrap();
            assert_eq!(text.iter().filter(|&&b| b == b'\n').count(), 1);
            // A station-addressed datagram names the slave it reaches, by
            // station address or alias; no other one names a slave.
            let station = session.station(&read, &datagram);
            assert_eq!(
                station.is_some(),
                datagram.command().addressing() == Addressing::Station
            );
            let mut meanings = Vec::new();
            session.meanings(&read, at, &datagram, |m| meanings.push(m));
            if !read.copy.returned() {
                assert!(meanings.is_empty(), "a sent copy proves nothing");
            }
            for meaning in meanings {
                let record = MeaningRecord {
                    packet: &read,
                    number: at + 1,
                    meaning,
                };
                json.clear();
                record.append_json(&mut json, None);
                let value: serde_json::Value = serde_json::from_slice(&json).unwrap();
                assert_eq!(value["kind"], record.kind());
                assert_eq!(value["packet"], number);
                let mut text = Vec::new();
                record.write_text(&mut text, datagram.command().name(), None).unwrap();
                assert_eq!(text.iter().filter(|&&b| b == b'\n').count(), 1);
            }
            let mut cut = 0;
            session.process_data(&read, at, &datagram, |data| {
                cut += 1;
                for image in [data.outputs, data.inputs].into_iter().flatten() {
                    assert!(image.len() <= 0x7FF);
                }
                data.for_each_signal(|_, name, _| assert!(!name.is_empty()));
                if data.slave.is_some() {
                    // A short count's verdict is what confirms the inputs.
                    assert_eq!(data.confirmed, data.missed.confirmed());
                    let short = data.expected_wkc.is_some_and(|e| data.wkc < e);
                    assert!(!data.missed.short() || short);
                }
                let record = ProcessRecord {
                    packet: &read,
                    number: at + 1,
                    data,
                };
                let mut json = Vec::new();
                record.append_json(&mut json, None);
                record.append_servo_json(&mut json, None);
                for line in json.split(|&b| b == b'\n').filter(|l| !l.is_empty()) {
                    let value: serde_json::Value = serde_json::from_slice(line).unwrap();
                    assert_eq!(value["packet"], number);
                }
                let mut text = Vec::new();
                record.write_text(&mut text, None, true, true).unwrap();
            });
            if !read.copy.returned() {
                assert_eq!(cut, 0, "a sent copy's inputs are last cycle's");
            }
        }
    }
    let counts = session.counts();
    assert_eq!(counts.packets, number);
    assert_eq!(
        counts.sent + counts.returned + counts.returned_unpaired + counts.other_frame_types
            + headers_damaged,
        number
    );
    assert!(counts.lost <= counts.sent);
    let end = session.finish();
    assert_eq!(end.sent, end.returned + end.lost);
    // The summary of the same packets: the same counts, and every record
    // one JSON object of its type.
    let summary = summarizer.finish();
    // The capture's counts, on the first interface's record.
    let ports = &summary.ethercat.ports;
    assert_eq!(ports.iter().map(|p| p.counts.sent).sum::<u64>(), end.sent);
    assert_eq!(ports.iter().map(|p| p.counts.lost).sum::<u64>(), end.lost);
    assert!(ports.iter().skip(1).all(|p| p.counts.packets == 0));
    for record in summary.records() {
        let value: serde_json::Value = serde_json::from_str(&record.to_json()).unwrap();
        assert!(value["type"].is_string());
        let _ = record.to_string();
    }
});
