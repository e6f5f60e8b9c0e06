//! pcap and pcapng files made by the real tools, read as tshark reads them
//! (docs/formats.md#pcap). `scripts/gen_pcap_fixtures.py` wrote the files in
//! `tests/fixtures/pcap/`: `can.pcap` (libpcap's layout, little-endian,
//! microseconds), `can.pcapng` (`editcap -F pcapng`), `can_ns.pcap`
//! (`editcap -F nsecpcap`), `can_be.pcap` (big-endian),
//! `can_ns_comments.pcapng` (`editcap -F pcapng -a …` of `can_ns.pcap`:
//! nanosecond `if_tsresol`, two packets with a comment) and `multi.pcapng`
//! (two sections, named interfaces, nanosecond `if_tsresol`, an Ethernet
//! interface and packet, a name resolution block), and beside each
//! `FILE.json`, what `tshark -T fields` reads from it.
//!
//! `scripts/gen_sll_fixtures.py` wrote the Linux "cooked" captures with
//! scapy's `CookedLinux`/`CookedLinuxV2` and `CAN`/`CANFD` layers (the
//! identifier word in host byte order, as the kernel hands it to `tcpdump
//! -i any`): `sll.pcap` (link type 113), `sll2.pcap` (276), `sll2.pcapng`
//! (`editcap -F pcapng`), `sll_mixed.pcapng` (`mergecap` with an
//! Ethernet capture) and `sll2_two_buses.pcap` (interfaces 3 and 4), each
//! with an IPv4 packet among the CAN ones, and the
//! same `FILE.json` from tshark.
//!
//! Documented differences from tshark 4.0:
//! - a remote request has no data: tshark shows the bytes after the header
//!   as `data.data` (here the padding `00`), the crate keeps the length as
//!   the DLC only (docs/formats.md#candump-log: `123#R1`);
//! - tshark names an interface without `if_name` `unknown` (`editcap`
//!   writes none); the crate gives no interface, as for pcap
//!   (docs/formats.md#interfaces);
//! - in a pcapng file of several sections, an enhanced packet block's
//!   interface id counts the interfaces of its own section (pcapng
//!   specification, "Interface ID … in the current section"): the packets
//!   of `multi.pcapng`'s second section are on its interface 0, `can9`.
//!   tshark 4.0.17 lists `can9` as the file's interface #3 (`capinfos`) but
//!   shows those packets on the first section's interface 0, `can0`; the
//!   crate follows the specification.

use motionwire::can::{Iface, LogEvent, LogFrame};
use motionwire::logs::pcap::PcapReader;
use motionwire::logs::{BinaryError, FormatError, LogFormat};
use motionwire::logs::{LogError, LogErrorKind, ReadLog, MAX_RECORD_LEN};
use serde_json::Value;

/// (number, frame) of every record, the error, the other records.
type Read = (Vec<(u64, LogFrame<'static>)>, Option<FormatError>, u64);

/// The `FormatError::Binary` of a reader's error (an I/O error is a test failure).
fn binary_error(e: LogError) -> FormatError {
    match e.into_kind() {
        LogErrorKind::Damaged(e) | LogErrorKind::Malformed(e) => e,
        other => panic!("{other}"),
    }
}

fn read(bytes: &[u8]) -> Read {
    let mut reader = match PcapReader::new(bytes) {
        Ok(r) => r,
        Err(e) => return (Vec::new(), Some(binary_error(e)), 0),
    };
    let mut frames = Vec::new();
    let mut error = None;
    while let Some(record) = reader.next_event() {
        match record {
            Ok(record) => {
                let LogEvent::Frame(f) = record.event else {
                    panic!("{record:?}")
                };
                let iface = f.iface.map(|i| match i {
                    Iface::Name(n) => Iface::Name(&*Box::leak(n.to_owned().into_boxed_str())),
                    Iface::Channel(c) => Iface::Channel(c),
                });
                let f = LogFrame {
                    frame: f.frame,
                    timestamp: f.timestamp,
                    iface,
                    direction: f.direction,
                };
                frames.push((record.position.number(), f));
            }
            Err(e) => error = Some(binary_error(e)),
        }
    }
    assert!(
        reader.next_event().is_none(),
        "None after the end or an error"
    );
    (frames, error, reader.other_records())
}

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(format!(
        "{}/tests/fixtures/pcap/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

fn field<'a>(packet: &'a Value, name: &str) -> Option<&'a str> {
    packet[name].as_str()
}

fn flag(packet: &Value, name: &str) -> bool {
    field(packet, name) == Some("1")
}

/// Every packet of `name` decodes as tshark read it; returns the format.
fn check_against_tshark(name: &str, format: LogFormat) {
    let bytes = fixture(name);
    let truth: Value = serde_json::from_slice(&fixture(&format!("{name}.json"))).unwrap();
    let packets = truth["packets"].as_array().unwrap();
    assert_eq!(PcapReader::new(&bytes[..]).unwrap().format(), format);
    let (frames, error, other) = read(&bytes);
    assert_eq!(error, None, "{name}");
    // `can:data`, `canfd`; after a cooked header `sll:can:data`.
    let can: Vec<_> = packets
        .iter()
        .filter(|p| {
            field(p, "frame.protocols")
                .unwrap()
                .split(':')
                .any(|layer| layer == "can" || layer == "canfd")
        })
        .collect();
    assert_eq!(other as usize, packets.len() - can.len(), "{name}");
    assert_eq!(frames.len(), can.len(), "{name}");
    for ((number, logged), want) in frames.iter().zip(can) {
        let at = format!("{name} packet {number}");
        let frame = &logged.frame;
        assert_eq!(
            number.to_string(),
            field(want, "frame.number").unwrap(),
            "{at}"
        );
        let ts = logged.timestamp.expect("pcap records times");
        assert_eq!(
            format!("{}.{:09}", ts.secs(), ts.subsec_nanos()),
            field(want, "frame.time_epoch").unwrap(),
            "{at}"
        );
        // An unnamed interface (or `any`): a cooked SLL2 header's
        // interface index, tshark's `sll.ifindex` (docs/formats.md#pcap).
        let iface = match field(want, "frame.interface_name") {
            None | Some("unknown" | "any") => field(want, "sll.ifindex"),
            // tshark 4.0 names the second section's interface 0 after the
            // first section's (see the module documentation).
            Some("can0") if name == "multi.pcapng" && *number >= 8 => Some("can9"),
            Some(n) => Some(n),
        };
        assert_eq!(
            logged.iface.map(|i| i.to_string()).as_deref(),
            iface,
            "{at}"
        );
        assert_eq!(logged.direction, None, "{at}");
        assert_eq!(frame.is_error(), flag(want, "can.flags.err"), "{at}");
        let len: usize = field(want, "can.len").unwrap().parse().unwrap();
        if frame.is_error() {
            // tshark shows the classes and data as error fields.
            assert_eq!(
                frame.id().raw() & 0x4 != 0,
                flag(want, "can.err.ctrl"),
                "{at}"
            );
            assert_eq!(
                frame.data().get(1).is_some_and(|b| b & 0x04 != 0),
                flag(want, "can.err.ctrl.rx_warning"),
                "{at}"
            );
            assert_eq!(frame.data().len(), len, "{at}");
            continue;
        }
        assert_eq!(
            frame.id().raw().to_string(),
            field(want, "can.id").unwrap(),
            "{at}"
        );
        assert_eq!(frame.is_extended(), flag(want, "can.flags.xtd"), "{at}");
        assert_eq!(frame.is_rtr(), flag(want, "can.flags.rtr"), "{at}");
        assert_eq!(
            frame.is_fd(),
            field(want, "canfd.flags.brs").is_some(),
            "{at}"
        );
        if frame.is_fd() {
            let flags = frame.fd_flags();
            assert_eq!(
                flags.contains(motionwire::can::FdFlags::BRS),
                flag(want, "canfd.flags.brs")
            );
            assert_eq!(
                flags.contains(motionwire::can::FdFlags::ESI),
                flag(want, "canfd.flags.esi")
            );
        }
        if frame.is_rtr() {
            assert_eq!(usize::from(frame.dlc()), len, "{at}");
            assert!(frame.data().is_empty(), "{at}");
            continue;
        }
        assert_eq!(frame.data().len(), len, "{at}");
        let hex: String = frame.data().iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(
            Some(hex.as_str()).filter(|h| !h.is_empty()),
            field(want, "data.data"),
            "{at}"
        );
    }
}

#[test]
fn pcap_reads_as_tshark_reads_it() {
    check_against_tshark("can.pcap", LogFormat::Pcap);
}

#[test]
fn editcap_pcapng_reads_as_tshark_reads_it() {
    check_against_tshark("can.pcapng", LogFormat::Pcapng);
}

#[test]
fn nanosecond_pcap_reads_as_tshark_reads_it() {
    check_against_tshark("can_ns.pcap", LogFormat::Pcap);
}

/// `editcap -F pcapng` of the nanosecond pcap, with comments on a classic
/// and a CAN FD frame: an interface whose `if_tsresol` is 9, enhanced
/// packet blocks with and without options (the reader's fast paths read
/// those without, its general path the others).
#[test]
fn editcap_nanosecond_pcapng_with_comments_reads_as_tshark_reads_it() {
    check_against_tshark("can_ns_comments.pcapng", LogFormat::Pcapng);
}

#[test]
fn big_endian_pcap_reads_as_tshark_reads_it() {
    check_against_tshark("can_be.pcap", LogFormat::Pcap);
}

#[test]
fn multi_interface_pcapng_reads_as_tshark_reads_it() {
    check_against_tshark("multi.pcapng", LogFormat::Pcapng);
    let (frames, _, other) = read(&fixture("multi.pcapng"));
    assert_eq!(other, 1, "the Ethernet packet");
    assert_eq!(frames[3].0, 5, "the Ethernet packet took number 4");
}

/// Linux cooked captures (docs/formats.md#pcap): link types 113 and 276,
/// protocol 0x000C / 0x000D, the SocketCAN frame in host byte order — every
/// frame as tshark reads it; the IPv4 packet (and the Ethernet ones of the
/// mixed file) counted by kind, named by link type.
#[test]
fn linux_cooked_captures_read_as_tshark_reads_them() {
    use motionwire::logs::{OtherRecord, OtherRecords};
    check_against_tshark("sll.pcap", LogFormat::Pcap);
    check_against_tshark("sll2.pcap", LogFormat::Pcap);
    check_against_tshark("sll2.pcapng", LogFormat::Pcapng);
    check_against_tshark("sll_mixed.pcapng", LogFormat::Pcapng);
    // `tcpdump -i any` on two buses: each frame's iface is its packet's
    // `sll.ifindex` ("3" or "4"), as check_against_tshark compares.
    check_against_tshark("sll2_two_buses.pcap", LogFormat::Pcap);
    let ip = |link_type| OtherRecord::CookedProtocol {
        link_type,
        protocol: 0x0800,
    };
    for (name, kinds) in [
        ("sll.pcap", vec![(ip(113), 1)]),
        ("sll2.pcap", vec![(ip(276), 1)]),
        ("sll2.pcapng", vec![(ip(276), 1)]),
        ("sll2_two_buses.pcap", vec![(ip(276), 1)]),
        (
            "sll_mixed.pcapng",
            vec![(OtherRecord::EtherType(0x9000), 2), (ip(276), 1)],
        ),
    ] {
        let bytes = fixture(name);
        let mut reader = PcapReader::new(&bytes[..]).unwrap();
        let mut frames = 0;
        while let Some(record) = reader.next_event() {
            record.unwrap();
            frames += 1;
        }
        assert_eq!(frames, 10, "{name}");
        let counted: Vec<_> = reader
            .other_kinds()
            .iter()
            .map(|k| (k.kind.clone(), k.count))
            .collect();
        assert_eq!(counted, kinds, "{name}");
        assert_eq!(
            reader.other_records(),
            kinds.iter().map(|k| k.1).sum::<u64>(),
            "{name}"
        );
    }
    assert_eq!(
        OtherRecords {
            kind: OtherRecord::LinkType(1),
            count: 2
        }
        .to_string(),
        "2 packets of link type 1 (Ethernet) skipped: not CAN"
    );
}

/// A cooked packet cut inside its header, or inside the SocketCAN frame
/// after it: the error says where, after the frames before it.
#[test]
fn a_cut_cooked_packet_is_damage() {
    let bytes = fixture("sll.pcap");
    let records = pcap_record_offsets(&bytes);
    // The first packet: 16-byte cooked header + 16-byte can_frame.
    let first = records[0];
    let len = u32::from_le_bytes(bytes[first + 8..first + 12].try_into().unwrap());
    assert_eq!(len, 32);
    for (captured, needed, at) in [(10u32, 16u64, 0u64), (20, 8, 16)] {
        let mut b = bytes.clone();
        b[first + 8..first + 12].copy_from_slice(&captured.to_le_bytes());
        b.truncate(first + 16 + captured as usize);
        let (frames, error, _) = read(&b);
        assert!(frames.is_empty());
        let found = u64::from(captured) - at;
        assert_eq!(
            error,
            binary(
                LogFormat::Pcap,
                (first + 16) as u64 + at,
                BinaryError::SocketCanTooShort { needed, found }
            ),
            "captured {captured}"
        );
    }
}

fn binary(format: LogFormat, offset: u64, reason: BinaryError) -> Option<FormatError> {
    Some(FormatError::Binary {
        format,
        offset,
        reason,
    })
}

/// The offsets of can.pcap's records: a 24-byte header, classic records of
/// 16 + 16 bytes, CAN FD records of 16 + 72.
fn pcap_record_offsets(bytes: &[u8]) -> Vec<usize> {
    let mut at = 24;
    let mut out = Vec::new();
    while at < bytes.len() {
        out.push(at);
        let len = u32::from_le_bytes(bytes[at + 8..at + 12].try_into().unwrap()) as usize;
        at += 16 + len;
    }
    out
}

/// The offsets of a little-endian pcapng file's blocks and their types.
fn pcapng_blocks(bytes: &[u8]) -> Vec<(usize, u32)> {
    let mut at = 0;
    let mut out = Vec::new();
    while at < bytes.len() {
        let ty = u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
        out.push((at, ty));
        at += u32::from_le_bytes(bytes[at + 4..at + 8].try_into().unwrap()) as usize;
    }
    out
}

#[test]
fn pcap_cut_inside_a_record() {
    let bytes = fixture("can.pcap");
    let records = pcap_record_offsets(&bytes);
    assert_eq!(records[..4], [24, 56, 88, 120]);
    // Inside the 4th record's data; inside the 6th record's header.
    let (frames, error, _) = read(&bytes[..120 + 20]);
    assert_eq!(frames.len(), 3);
    let truncated = BinaryError::Truncated {
        needed: 32,
        found: 20,
    };
    assert_eq!(error, binary(LogFormat::Pcap, 120, truncated));
    let sixth = records[5];
    let (frames, error, _) = read(&bytes[..sixth + 5]);
    assert_eq!(frames.len(), 5);
    let truncated = BinaryError::Truncated {
        needed: 16,
        found: 5,
    };
    assert_eq!(error, binary(LogFormat::Pcap, sixth as u64, truncated));
    // The whole file, every cut: frames before the cut, then Truncated at
    // the record that was cut.
    for cut in 24..bytes.len() {
        let (frames, error, _) = read(&bytes[..cut]);
        let whole = records.iter().filter(|&&r| r < cut).count();
        let cut_record = records.iter().rev().find(|&&r| r < cut).copied();
        let boundary = records.contains(&cut);
        let expected = if boundary { whole } else { whole - 1 };
        assert_eq!(frames.len(), expected, "cut at {cut}");
        match error {
            None => assert!(boundary, "cut at {cut}"),
            Some(FormatError::Binary {
                offset,
                reason: BinaryError::Truncated { .. },
                ..
            }) => assert_eq!(Some(offset), cut_record.map(|r| r as u64)),
            other => panic!("cut at {cut}: {other:?}"),
        }
    }
}

#[test]
fn pcap_absurd_lengths() {
    let mut bytes = fixture("can.pcap");
    bytes[16..20].copy_from_slice(&u32::MAX.to_le_bytes());
    let too_large = BinaryError::TooLarge {
        length: u32::MAX.into(),
        limit: MAX_RECORD_LEN as u64,
    };
    assert_eq!(read(&bytes).1, binary(LogFormat::Pcap, 0, too_large));

    let mut bytes = fixture("can.pcap");
    bytes[88 + 8..88 + 12].copy_from_slice(&0x4000_0000u32.to_le_bytes());
    let (frames, error, _) = read(&bytes);
    assert_eq!(frames.len(), 2);
    let too_large = BinaryError::TooLarge {
        length: 0x4000_0000,
        limit: MAX_RECORD_LEN as u64,
    };
    assert_eq!(error, binary(LogFormat::Pcap, 88, too_large));
}

#[test]
fn pcapng_damaged_blocks() {
    let bytes = fixture("multi.pcapng");
    let blocks = pcapng_blocks(&bytes);
    // SHB, 3 IDBs, then packets: the third block after the IDBs is the
    // third packet (the Ethernet one follows it).
    let (third, ty) = blocks[6];
    assert_eq!(ty, 6);
    let set_len = |bytes: &mut Vec<u8>, at: usize, len: u32| {
        bytes[at + 4..at + 8].copy_from_slice(&len.to_le_bytes());
    };

    // A length past the end of the file.
    let mut b = bytes.clone();
    set_len(&mut b, third, 0x1_0000);
    let (frames, error, _) = read(&b);
    assert_eq!(frames.len(), 2);
    let truncated = BinaryError::Truncated {
        needed: 0x1_0000,
        found: (bytes.len() - third) as u64,
    };
    assert_eq!(error, binary(LogFormat::Pcapng, third as u64, truncated));

    // Above the limit: never allocated.
    let mut b = bytes.clone();
    set_len(&mut b, third, 0xFFFF_FFFC);
    let too_large = BinaryError::TooLarge {
        length: 0xFFFF_FFFC,
        limit: MAX_RECORD_LEN as u64,
    };
    assert_eq!(
        read(&b).1,
        binary(LogFormat::Pcapng, third as u64, too_large)
    );

    // Not a multiple of 4.
    let mut b = bytes.clone();
    set_len(&mut b, third, 47);
    assert_eq!(
        read(&b).1,
        binary(
            LogFormat::Pcapng,
            third as u64,
            BinaryError::BadLength { length: 47 }
        )
    );

    // A trailing length that differs from the leading one.
    let mut b = bytes.clone();
    let next = blocks[7].0;
    b[next - 4] ^= 0x10;
    let (frames, error, _) = read(&b);
    assert_eq!(frames.len(), 2);
    let length = u32::from_le_bytes(bytes[third + 4..third + 8].try_into().unwrap());
    assert_eq!(
        error,
        binary(
            LogFormat::Pcapng,
            third as u64,
            BinaryError::BadLength {
                length: length.into()
            }
        )
    );

    // Cut in the middle of the block.
    let (frames, error, _) = read(&bytes[..third + 30]);
    assert_eq!(frames.len(), 2);
    let truncated = BinaryError::Truncated {
        needed: length.into(),
        found: 30,
    };
    assert_eq!(error, binary(LogFormat::Pcapng, third as u64, truncated));
}

#[test]
fn error_messages_say_where() {
    let bytes = fixture("can.pcap");
    let error = read(&bytes[..140]).1.unwrap();
    assert_eq!(
        error.to_string(),
        "pcap file, byte 120: the file ends inside a structure of 32 bytes, after 20"
    );
}
