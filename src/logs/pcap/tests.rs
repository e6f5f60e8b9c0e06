//! The reader against hand-made files: every block kind, resolution and
//! damage the module documentation names (docs/formats.md#pcap).

use super::writer::{self, Interface, Pcapng};
use super::*;
use crate::can::{CanFrame, CanId, FdFlags};
use crate::logs::FormatError;

fn frame_705() -> CanFrame {
    CanFrame::new(CanId::standard(0x705).unwrap(), &[5]).unwrap()
}

fn can0(tsresol: Option<u8>, tsoffset: Option<i64>) -> Interface {
    Interface {
        link: LINKTYPE_CAN_SOCKETCAN,
        name: Some("can0".into()),
        tsresol,
        tsoffset,
    }
}

/// Every record as (number, frame, timestamp, iface), then the error.
fn read_all(bytes: &[u8]) -> (Vec<(u64, LogFrame<'static>)>, Option<FormatError>, u64) {
    let mut reader = match PcapReader::new(bytes) {
        Ok(r) => r,
        Err(e) => return (Vec::new(), Some(binary_error(e)), 0),
    };
    let mut out = Vec::new();
    let mut error = None;
    while let Some(record) = reader.next_event() {
        match record {
            Ok(LogRecord {
                position: Position::Record(number),
                event: LogEvent::Frame(f),
            }) => {
                let iface = f.iface.map(|i| match i {
                    Iface::Name(n) => Iface::Name(Box::leak(n.to_owned().into_boxed_str())),
                    Iface::Channel(c) => Iface::Channel(c),
                });
                out.push((
                    number,
                    LogFrame {
                        frame: f.frame,
                        timestamp: f.timestamp,
                        iface,
                        direction: f.direction,
                    },
                ));
            }
            Ok(other) => panic!("{other:?}"),
            Err(e) => error = Some(binary_error(e)),
        }
    }
    assert!(reader.next_event().is_none());
    (out, error, reader.other_records())
}

fn binary(format: LogFormat, offset: u64, reason: BinaryError) -> Option<FormatError> {
    Some(FormatError::Binary {
        format,
        offset,
        reason,
    })
}

#[test]
fn resolutions_and_offsets() {
    let p = writer::socketcan(&frame_705());
    let mut w = Pcapng::default();
    w.section(false)
        .interface(&can0(Some(0x80 | 20), None)) // 2^-20 s
        .interface(&can0(Some(3), Some(-100))) // ms, 100 s earlier
        .interface(&can0(Some(12), None)) // ps
        .packet(0, (5 << 20) | (1 << 19), &p)
        .packet(1, 200_500, &p)
        .packet(2, 1_000_000_000_123_456, &p);
    let (frames, error, _) = read_all(&w.bytes);
    assert_eq!(error, None);
    let ts: Vec<_> = frames.iter().map(|(_, f)| f.timestamp.unwrap()).collect();
    assert_eq!(ts[0], Timestamp::from_nanos(5, 500_000_000).unwrap());
    assert_eq!(ts[1], Timestamp::from_nanos(100, 500_000_000).unwrap());
    assert_eq!(ts[2], Timestamp::from_nanos(1000, 123).unwrap());
}

#[test]
fn big_endian_sections_simple_packets_and_can_xl() {
    let p = writer::socketcan(&frame_705());
    let xl = [0, 0, 0x01, 0x23, 0x81, 0x03, 1, 0, 0, 0, 0, 0, 0xAA];
    let mut w = Pcapng::default();
    w.section(true)
        .interface(&can0(None, None))
        .simple_packet(&p)
        .packet(0, 7_000_001, &xl)
        .block(4, &[0, 0, 0, 0]) // name resolution: no number
        .section(false)
        .interface(&Interface {
            link: 1,
            name: None,
            tsresol: None,
            tsoffset: None,
        })
        .interface(&Interface {
            name: Some("vcan9\0\0".into()),
            ..can0(None, None)
        })
        .packet(0, 1, &[0; 14])
        .packet(1, 7_000_001, &p);
    let (frames, error, other) = read_all(&w.bytes);
    assert_eq!(error, None);
    assert_eq!(other, 2);
    assert_eq!(frames.len(), 2);
    assert_eq!(frames[0].0, 1);
    assert_eq!(frames[0].1.timestamp, None);
    assert_eq!(frames[0].1.iface, Some(Iface::Name("can0")));
    assert_eq!(frames[1].0, 4);
    assert_eq!(frames[1].1.frame, frame_705());
    assert_eq!(frames[1].1.iface, Some(Iface::Name("vcan9")));
    assert_eq!(frames[1].1.timestamp, Timestamp::new(7, 1));
}

#[test]
fn unknown_interface_and_negative_time() {
    let p = writer::socketcan(&frame_705());
    let mut w = Pcapng::default();
    w.section(false)
        .interface(&can0(None, None))
        .packet(0, 1, &p);
    let good = w.bytes.len() as u64;
    w.packet(1, 1, &p);
    let (frames, error, _) = read_all(&w.bytes);
    assert_eq!(frames.len(), 1);
    assert_eq!(
        error,
        binary(
            LogFormat::Pcapng,
            good,
            BinaryError::UnknownInterface { id: 1, count: 1 }
        )
    );

    let mut w = Pcapng::default();
    w.section(false)
        .interface(&can0(None, Some(-10)))
        .packet(0, 1, &p);
    let (_, error, _) = read_all(&w.bytes);
    assert!(matches!(
        error,
        Some(FormatError::Binary {
            reason: BinaryError::TimestampOutOfRange,
            ..
        })
    ));
}

#[test]
fn damaged_headers() {
    assert_eq!(
        read_all(&[]).1,
        binary(
            LogFormat::Pcap,
            0,
            BinaryError::Truncated {
                needed: 4,
                found: 0
            }
        )
    );
    assert_eq!(
        read_all(b"(1700000000.000500) can0 705#05\n").1,
        binary(
            LogFormat::Pcap,
            0,
            BinaryError::BadMagic { found: 0x3037_3128 }
        )
    );
    let mut f = writer::pcap(&[], 227, false, false);
    f[4] = 3;
    assert_eq!(
        read_all(&f).1,
        binary(
            LogFormat::Pcap,
            0,
            BinaryError::UnsupportedVersion { major: 3, minor: 4 }
        )
    );
    let mut w = Pcapng::default();
    w.section(false);
    w.bytes[12] = 2;
    assert_eq!(
        read_all(&w.bytes).1,
        binary(
            LogFormat::Pcapng,
            0,
            BinaryError::UnsupportedVersion { major: 2, minor: 0 }
        )
    );
}

#[test]
fn damaged_packet_and_option() {
    let mut bad = writer::socketcan(&frame_705());
    bad[4] = 9;
    let f = writer::pcap(&[(Timestamp::ZERO, bad.clone())], 227, false, false);
    assert_eq!(
        read_all(&f).1,
        binary(
            LogFormat::Pcap,
            40,
            BinaryError::CanDataTooLong { len: 9, max: 8 }
        )
    );
    // An option whose value runs past the block.
    let mut w = Pcapng::default();
    w.section(false).interface(&can0(None, None));
    let name_len_at = 28 + 16 + 2;
    w.bytes[name_len_at] = 200;
    let idb_at = 28;
    assert_eq!(
        read_all(&w.bytes).1,
        binary(
            LogFormat::Pcapng,
            idb_at + 16,
            BinaryError::BadLength { length: 200 }
        )
    );
}

#[test]
fn fd_frames_of_every_flag() {
    for bits in 0..=0xF {
        let frame = CanFrame::new_fd(
            CanId::extended(0x1234).unwrap(),
            FdFlags::new(bits).unwrap(),
            &[1; 20],
        )
        .unwrap();
        let f = writer::pcap(
            &[(Timestamp::ZERO, writer::socketcan(&frame))],
            227,
            true,
            true,
        );
        let (frames, error, _) = read_all(&f);
        assert_eq!(error, None);
        assert_eq!(frames[0].1.frame, frame);
    }
}

#[test]
fn messages_of_the_new_reasons() {
    let e = FormatError::Binary {
        format: LogFormat::Pcapng,
        offset: 28,
        reason: BinaryError::UnknownInterface { id: 1, count: 1 },
    };
    assert_eq!(
        e.to_string(),
        "pcapng file, byte 28: expected an interface id below 1, found 1"
    );
    let reasons = [
        (
            BinaryError::SocketCanTooShort {
                needed: 16,
                found: 10,
            },
            "expected a SocketCAN packet of at least 16 bytes, found 10",
        ),
        (
            BinaryError::CanDataTooLong { len: 9, max: 8 },
            "expected a CAN data length of at most 8, found 9",
        ),
        (
            BinaryError::TimestampOutOfRange,
            "expected a time between the Unix epoch and 2^64 s after it, found one outside",
        ),
    ];
    for (reason, text) in reasons {
        assert_eq!(reason.to_string(), text);
    }
}

#[test]
fn a_packet_of_another_link_type_is_counted_not_decoded() {
    let f = writer::pcap(&[(Timestamp::ZERO, vec![0xFF; 3])], 105, false, false);
    let (frames, error, other) = read_all(&f);
    assert_eq!((frames.len(), error, other), (0, None, 1));
}

/// An Ethernet port's capture (docs/ethercat.md#reading): EtherCAT is an
/// event, another EtherType is counted, a packet shorter than its
/// Ethernet header is skipped with its number and the capture read on.
#[test]
fn ethernet_packets_are_ethercat_counted_or_skipped() {
    let mut ethercat = vec![0xff; 6];
    ethercat.extend([0x10; 6]);
    ethercat.extend([0x88, 0xa4, 0x0e, 0x10]);
    ethercat.extend([7, 1, 0, 0, 0x30, 0x01, 2, 0, 0, 0, 8, 0, 0, 0]);
    let mut arp = vec![0xff; 12];
    arp.extend([0x08, 0x06, 0, 1]);
    let packets = [
        (Timestamp::ZERO, vec![0xff; 9]),
        (Timestamp::ZERO, arp),
        (Timestamp::ZERO, ethercat.clone()),
    ];
    let f = writer::pcap(&packets, u32::from(LINKTYPE_ETHERNET), false, false);
    let mut reader = PcapReader::new(&f[..]).unwrap();
    let short = reader.next_event().unwrap().unwrap_err();
    assert!(short.is_skipped());
    assert_eq!(short.position(), Some(Position::Record(1)));
    assert_eq!(
        short.to_string(),
        "record 1: pcap file, byte 40: Ethernet frame: buffer of 9 bytes where 14 are needed"
    );
    let record = reader.next_event().unwrap().unwrap();
    assert_eq!(record.position, Position::Record(3));
    let LogEvent::Ethercat(packet) = record.event else {
        panic!("{}", record.event)
    };
    assert_eq!(packet.link.payload, &ethercat[14..]);
    assert_eq!(packet.link.source.to_string(), "10:10:10:10:10:10");
    assert!(reader.next_event().is_none());
    assert_eq!(reader.skipped(), 1);
    assert_eq!(
        reader.other_kinds()[0].to_string(),
        "1 packet of EtherType 0x0806 (ARP) skipped: neither CAN nor EtherCAT"
    );
}

/// The `FormatError::Binary` of a reader's error (an I/O error is a test failure).
fn binary_error(e: LogError) -> FormatError {
    match e.into_kind() {
        LogErrorKind::Damaged(e) | LogErrorKind::Malformed(e) => e,
        other => panic!("{other}"),
    }
}

/// `tcpdump -i any` on two CAN buses: one file, the buses told apart by the
/// SLL2 header's interface index (tshark's `sll.ifindex`); a pcapng
/// interface's own name wins, unless it is `any` (docs/formats.md#pcap).
#[test]
fn sll2_interface_indices_tell_the_buses_apart() {
    /// A cooked SLL2 packet of interface `ifindex` holding `705#05`, its
    /// identifier word little-endian (the capturing machine's order).
    fn cooked(ifindex: u32) -> Vec<u8> {
        let mut p = 0x000C_u16.to_be_bytes().to_vec();
        p.extend([0, 0]);
        p.extend(ifindex.to_be_bytes());
        p.extend([0x01, 0x18, 0, 0]);
        p.extend([0; 8]);
        p.extend(0x705_u32.to_le_bytes());
        p.extend([1, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0]);
        p
    }
    let packets: Vec<_> = [3, 4, 3, 70_000]
        .map(|i| (Timestamp::ZERO, cooked(i)))
        .into();
    let (frames, error, other) = read_all(&writer::pcap(&packets, 276, false, false));
    assert_eq!((error, other), (None, 0));
    let ifaces: Vec<_> = frames.iter().map(|(_, f)| f.iface).collect();
    // An index beyond a channel number's range names no bus.
    let (c3, c4) = (Some(Iface::Channel(3)), Some(Iface::Channel(4)));
    assert_eq!(ifaces, [c3, c4, c3, None]);
    assert!(frames.iter().all(|(_, f)| f.frame.data() == [5]));

    for (name, want) in [
        (None, c4),
        (Some("any"), c4),
        (Some("can1"), Some(Iface::Name("can1"))),
    ] {
        let mut w = Pcapng::default();
        w.section(false)
            .interface(&Interface {
                link: LINKTYPE_LINUX_SLL2,
                name: name.map(str::to_owned),
                tsresol: None,
                tsoffset: None,
            })
            .packet(0, 0, &cooked(4));
        let (frames, error, _) = read_all(&w.bytes);
        assert_eq!(error, None, "{name:?}");
        assert_eq!(frames[0].1.iface, want, "{name:?}");
    }
}
