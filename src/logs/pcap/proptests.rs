//! Property tests: arbitrary bytes never panic and end cleanly; frames
//! written by the test writer read back to themselves in both formats and
//! both byte orders, however the input is split into reads.

use std::io::Read;

use proptest::prelude::*;

use super::writer::{self, Interface, Pcapng};
use super::*;
use crate::can::CanFrame;
use crate::logs::FormatError;
use crate::test_gens::can::any_can_frame;

/// A reader that hands out at most `step` bytes per call.
struct Chunked<'a> {
    data: &'a [u8],
    step: usize,
}

impl Read for Chunked<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.step.min(buf.len()).min(self.data.len());
        let (head, rest) = self.data.split_at(n);
        buf[..n].copy_from_slice(head);
        self.data = rest;
        Ok(n)
    }
}

/// What a reader yields: (number, frame, timestamp, iface name), the error
/// and the other records.
type Outcome = (
    Vec<(u64, CanFrame, Option<Timestamp>, Option<String>)>,
    Option<String>,
    u64,
);

fn outcome<R: Read>(input: R) -> Outcome {
    outcome_of(input, false)
}

/// [`outcome`], every record read by the general path when `general`
/// (not by `PcapReader::next_classic` or `next_fd`).
/// What the reader with its fast paths and the general path alone read of
/// `data`, handed over `step` bytes at a time: (fast, general).
fn both_paths(data: &[u8], step: usize) -> (Outcome, Outcome) {
    (
        outcome_of(Chunked { data, step }, false),
        outcome_of(Chunked { data, step }, true),
    )
}

fn outcome_of<R: Read>(input: R, general: bool) -> Outcome {
    let mut reader = match PcapReader::new(input) {
        Ok(r) => r,
        Err(e) => return (Vec::new(), Some(e.to_string()), 0),
    };
    if general {
        reader.fast = false;
    }
    let mut frames = Vec::new();
    let mut error = None;
    let mut last = 0;
    // Packets of an Ethernet interface: EtherCAT events, and packets too
    // short for their headers (skipped, the capture read on).
    let mut ethernet = 0;
    while let Some(record) = reader.next_event() {
        match record {
            Ok(record) => {
                let number = record.position.number();
                assert!(number > last, "numbers increase");
                last = number;
                if let LogEvent::Ethercat(_) = record.event {
                    ethernet += 1;
                    continue;
                }
                let f = *record.event.frame().expect("pcap yields frames");
                assert_eq!(f.direction, None);
                frames.push((number, f.frame, f.timestamp, f.iface.map(|i| i.to_string())));
            }
            Err(e) if e.is_skipped() => {
                let number = e
                    .position()
                    .expect("a skipped packet has its number")
                    .number();
                assert!(number > last, "numbers increase");
                last = number;
                ethernet += 1;
            }
            Err(e) => {
                assert!(error.is_none(), "one error at most");
                match e.kind() {
                    LogErrorKind::Damaged(FormatError::Binary { format, .. }) => {
                        assert_eq!(*format, reader.format());
                    }
                    other => panic!("{other:?}"),
                }
                error = Some(e.to_string());
            }
        }
    }
    assert!(reader.next_event().is_none());
    let other = reader.other_records() + ethernet;
    if error.is_none() {
        assert_eq!(
            frames.len() as u64 + other,
            last.max(frames.len() as u64 + other)
        );
    }
    (frames, error, other)
}

fn micros_timestamp() -> impl Strategy<Value = Timestamp> {
    (0u64..=u64::from(u32::MAX), 0u32..1_000_000).prop_map(|(s, us)| Timestamp::new(s, us).unwrap())
}

/// A SocketCAN packet's 8-byte header as a classic or CAN FD frame's often
/// is, or not: the identifier word's flags, a length around 8 or 64, the
/// flags byte and the reserved bytes zero or not.
fn socketcan_header() -> impl Strategy<Value = [u8; 8]> {
    (
        prop_oneof![
            any::<u32>(),
            0u32..0x800,
            (0u32..0x2000_0000).prop_map(|id| id | 0x8000_0000),
        ],
        prop_oneof![0u8..=9, 60u8..=65, any::<u8>()],
        prop_oneof![Just(0u8), 0u8..8, any::<u8>()],
        prop_oneof![Just([0u8; 2]), any::<[u8; 2]>()],
    )
        .prop_map(|(word, len, flags, [r0, r1])| {
            let [i0, i1, i2, i3] = word.to_be_bytes();
            [i0, i1, i2, i3, len, flags, r0, r1]
        })
}

/// One pcap record: seconds, fraction (a microsecond count or not),
/// captured length (16 or 72 mostly), the packet (a SocketCAN header, then
/// arbitrary bytes).
fn pcap_record() -> impl Strategy<Value = (u32, u32, u32, Vec<u8>)> {
    (
        any::<u32>(),
        prop_oneof![0u32..1_000_000, any::<u32>()],
        socketcan_header(),
        proptest::collection::vec(any::<u8>(), 64),
        prop_oneof![4 => Just(16usize), 2 => Just(72usize), 1 => 0usize..80],
        prop_oneof![4 => Just(None), 1 => (0u32..100).prop_map(Some)],
    )
        .prop_map(|(secs, frac, header, data, len, claimed)| {
            let mut packet = header.to_vec();
            packet.extend(data);
            packet.truncate(len);
            (secs, frac, claimed.unwrap_or(len as u32), packet)
        })
}

/// A pcapng interface as writers describe SocketCAN ones, or not: link
/// type 227 mostly, a name or none (`any` among them), the default
/// resolution or another (`if_tsresol`, decimal or binary), an offset or
/// none (`if_tsoffset`, zero, small or extreme).
fn pcapng_interface() -> impl Strategy<Value = Interface> {
    (
        prop_oneof![6 => Just(227u16), 1 => Just(1u16), 1 => Just(113u16), 1 => any::<u16>()],
        prop_oneof![
            Just(None),
            Just(Some("can0".to_string())),
            Just(Some("any".to_string())),
        ],
        prop_oneof![
            3 => Just(None),
            1 => Just(Some(6u8)),
            1 => Just(Some(9u8)),
            1 => Just(Some(0u8)),
            1 => Just(Some(0x80 | 20)),
            1 => any::<u8>().prop_map(Some),
        ],
        prop_oneof![
            3 => Just(None),
            1 => Just(Some(0i64)),
            1 => (-10_000i64..10_000).prop_map(Some),
            1 => any::<i64>().prop_map(Some),
        ],
    )
        .prop_map(|(link, name, tsresol, tsoffset)| Interface {
            link,
            name,
            tsresol,
            tsoffset,
        })
}

/// One pcapng block after the first section header: an enhanced packet
/// block mostly (interface 0..3, a time, a captured length that is the
/// packet's or not, the packet as [`pcap_record`] makes it, options or
/// none, a trailing length that is the block's or not), or a block of another kind: a simple packet, an interface
/// description, a new section (either byte order), a name resolution,
/// statistics or custom block.
#[derive(Debug, Clone)]
enum NgBlock {
    Enhanced {
        iface: u32,
        ticks: u64,
        claimed: Option<u32>,
        packet: Vec<u8>,
        options: Vec<u8>,
        trailer: Option<u32>,
    },
    Simple(Vec<u8>),
    Interface(Interface),
    Section(bool),
    Other(u32, Vec<u8>),
}

fn pcapng_block() -> impl Strategy<Value = NgBlock> {
    let enhanced = (
        prop_oneof![4 => Just(0u32), 2 => 0u32..3, 1 => any::<u32>()],
        prop_oneof![any::<u64>(), 0u64..1 << 52],
        pcap_record(),
        prop_oneof![4 => Just(None), 1 => (0u32..100).prop_map(Some)],
        prop_oneof![
            4 => Just(Vec::new()),
            1 => Just(vec![1, 0, 4, 0, b'h', b'i', b'!', 0, 0, 0, 0, 0]),
            1 => proptest::collection::vec(any::<u8>(), 0..12),
        ],
        prop_oneof![3 => Just(None), 1 => any::<u32>().prop_map(Some)],
    )
        .prop_map(
            |(iface, ticks, (_, _, _, packet), claimed, options, trailer)| NgBlock::Enhanced {
                iface,
                ticks,
                claimed,
                packet,
                options,
                trailer,
            },
        );
    prop_oneof![
        12 => enhanced,
        1 => proptest::collection::vec(any::<u8>(), 0..20).prop_map(NgBlock::Simple),
        1 => pcapng_interface().prop_map(NgBlock::Interface),
        1 => any::<bool>().prop_map(NgBlock::Section),
        1 => (
            prop_oneof![Just(4u32), Just(5u32), Just(0xBADu32), Just(9u32)],
            proptest::collection::vec(any::<u8>(), 0..24),
        )
            .prop_map(|(kind, body)| NgBlock::Other(kind, body)),
    ]
}

/// A pcapng file of a section header (either byte order), `interfaces`
/// and `blocks`.
fn pcapng_file(be: bool, interfaces: &[Interface], blocks: &[NgBlock]) -> Vec<u8> {
    let mut w = Pcapng::default();
    w.section(be);
    for i in interfaces {
        w.interface(i);
    }
    for block in blocks {
        match block {
            NgBlock::Enhanced {
                iface,
                ticks,
                claimed,
                packet,
                options,
                trailer,
            } => {
                let be = w.be;
                let u32b = |v: u32| {
                    if be {
                        v.to_be_bytes()
                    } else {
                        v.to_le_bytes()
                    }
                };
                let mut body = u32b(*iface).to_vec();
                body.extend(u32b((ticks >> 32) as u32));
                body.extend(u32b(*ticks as u32));
                body.extend(u32b(claimed.unwrap_or(packet.len() as u32)));
                body.extend(u32b(packet.len() as u32));
                body.extend(packet);
                body.resize(body.len().div_ceil(4) * 4, 0);
                body.extend(options);
                w.block(6, &body);
                if let Some(trailer) = trailer {
                    let end = w.bytes.len();
                    w.bytes[end - 4..].copy_from_slice(&u32b(*trailer));
                }
            }
            NgBlock::Simple(packet) => {
                w.simple_packet(packet);
            }
            NgBlock::Interface(i) => {
                w.interface(i);
            }
            NgBlock::Section(be) => {
                w.section(*be);
            }
            NgBlock::Other(kind, body) => {
                w.block(*kind, body);
            }
        }
    }
    w.bytes
}

fn nanos_timestamp() -> impl Strategy<Value = Timestamp> {
    (0u64..=u64::from(u32::MAX), 0u32..1_000_000_000)
        .prop_map(|(s, ns)| Timestamp::from_nanos(s, ns).unwrap())
}

proptest! {
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        let whole = outcome(&bytes[..]);
        prop_assert_eq!(outcome(Chunked { data: &bytes, step: 1 }), whole);
    }

    #[test]
    fn damaged_files_never_panic(
        frames in proptest::collection::vec((any_can_frame(), micros_timestamp()), 1..6),
        ng in any::<bool>(),
        flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..4),
        cut in any::<usize>(),
    ) {
        let mut bytes = if ng {
            let mut w = Pcapng::default();
            w.section(false).interface(&Interface { link: 227, name: Some("can0".into()), tsresol: None, tsoffset: None });
            for (f, ts) in &frames {
                w.packet(0, ts.as_micros() as u64, &writer::socketcan(f));
            }
            w.bytes
        } else {
            let packets: Vec<_> = frames.iter().map(|(f, ts)| (*ts, writer::socketcan(f))).collect();
            writer::pcap(&packets, 227, false, false)
        };
        for (at, b) in flips {
            let at = at % bytes.len();
            bytes[at] = b;
        }
        bytes.truncate(cut % (bytes.len() + 1));
        let whole = outcome(&bytes[..]);
        prop_assert_eq!(outcome(Chunked { data: &bytes, step: 7 }), whole);
    }

    /// A packet of 16 bytes: the fast reading of a classic data frame is
    /// `decode`'s, and it reads every packet `decode` makes a classic data
    /// frame of.
    #[test]
    fn classic_data_is_decode(header in socketcan_header(), data in any::<[u8; 8]>()) {
        let mut packet = [0u8; socketcan::CAN_MTU];
        packet[..8].copy_from_slice(&header);
        packet[8..].copy_from_slice(&data);
        let general = socketcan::decode(&packet, FrameLayout::LinkType227);
        match socketcan::classic_data(&packet) {
            Some(frame) => prop_assert_eq!(general, Ok(Payload::Frame(frame))),
            None => prop_assert!(!matches!(
                general,
                Ok(Payload::Frame(f)) if f.frame_type() == crate::can::FrameType::Data
            )),
        }
    }

    /// A packet of 72 bytes: the fast reading of a CAN FD frame is
    /// `decode`'s, and it reads every packet `decode` makes a frame of.
    #[test]
    fn fd_data_is_decode(
        header in socketcan_header(),
        data in proptest::collection::vec(any::<u8>(), 64),
    ) {
        let mut packet = [0u8; socketcan::CANFD_MTU];
        packet[..8].copy_from_slice(&header);
        packet[8..].copy_from_slice(&data);
        let general = socketcan::decode(&packet, FrameLayout::LinkType227);
        match socketcan::fd_data(&packet) {
            Some(frame) => prop_assert_eq!(general, Ok(Payload::Frame(frame))),
            None => prop_assert!(!matches!(general, Ok(Payload::Frame(_)))),
        }
    }

    /// A pcap file of arbitrary records, in either byte order and
    /// resolution, whole or cut, read in whole or in pieces: what the fast
    /// paths for classic and CAN FD records read is what the general path
    /// reads.
    #[test]
    fn the_fast_paths_read_as_the_general_path(
        records in proptest::collection::vec(pcap_record(), 0..12),
        be in any::<bool>(),
        nanos in any::<bool>(),
        link in prop_oneof![4 => Just(227u32), 1 => any::<u32>()],
        cut in any::<usize>(),
        step in prop_oneof![Just(1usize << 16), 1usize..40],
    ) {
        let mut bytes = writer::pcap(&[], link, be, nanos);
        let u32b = |v: u32| if be { v.to_be_bytes() } else { v.to_le_bytes() };
        for (secs, frac, claimed, packet) in &records {
            bytes.extend(u32b(*secs));
            bytes.extend(u32b(*frac));
            bytes.extend(u32b(*claimed));
            bytes.extend(u32b(*claimed));
            bytes.extend(packet);
        }
        if cut % 4 == 0 {
            bytes.truncate(cut % (bytes.len() + 1));
        }
        let (fast, general) = both_paths(&bytes, step);
        prop_assert_eq!(fast, general);
    }

    #[test]
    fn pcap_round_trip(
        frames in proptest::collection::vec((any_can_frame(), nanos_timestamp()), 0..20),
        be in any::<bool>(),
        nanos in any::<bool>(),
    ) {
        let packets: Vec<_> = frames.iter().map(|(f, ts)| (*ts, writer::socketcan(f))).collect();
        let bytes = writer::pcap(&packets, 227, be, nanos);
        let (read, error, other) = outcome(Chunked { data: &bytes, step: 13 });
        prop_assert_eq!(error, None);
        prop_assert_eq!(other, 0);
        prop_assert_eq!(read.len(), frames.len());
        for (i, ((number, frame, ts, iface), (want, want_ts))) in read.into_iter().zip(&frames).enumerate() {
            prop_assert_eq!(number, i as u64 + 1);
            prop_assert_eq!(frame, *want);
            let ns = if nanos { want_ts.subsec_nanos() } else { want_ts.micros() * 1000 };
            prop_assert_eq!(ts, Timestamp::from_nanos(want_ts.secs(), ns));
            prop_assert_eq!(iface, None);
        }
    }

    #[test]
    fn pcapng_round_trip(
        frames in proptest::collection::vec((any_can_frame(), any::<u64>(), 0u32..3), 0..20),
        be in any::<bool>(),
    ) {
        let ifaces = [
            Interface { link: 227, name: Some("can0".into()), tsresol: None, tsoffset: None },
            Interface { link: 1, name: Some("eth0".into()), tsresol: None, tsoffset: None },
            Interface { link: 227, name: None, tsresol: Some(9), tsoffset: None },
        ];
        let mut w = Pcapng::default();
        w.section(be);
        for i in &ifaces {
            w.interface(i);
        }
        for (f, ticks, iface) in &frames {
            w.packet(*iface, *ticks, &writer::socketcan(f));
        }
        let (read, error, other) = outcome(Chunked { data: &w.bytes, step: 61 });
        prop_assert_eq!(error, None);
        let want: Vec<_> = frames
            .iter()
            .enumerate()
            .filter(|(_, (_, _, iface))| *iface != 1)
            .map(|(i, (f, ticks, iface))| {
                let ts = if *iface == 0 {
                    Timestamp::from_nanos(ticks / 1_000_000, (ticks % 1_000_000) as u32 * 1000)
                } else {
                    Timestamp::from_nanos(ticks / 1_000_000_000, (ticks % 1_000_000_000) as u32)
                };
                let name = if *iface == 0 { Some("can0".to_string()) } else { None };
                (i as u64 + 1, *f, ts, name)
            })
            .collect();
        prop_assert_eq!(other, (frames.len() - want.len()) as u64);
        prop_assert_eq!(read, want);
    }
}

proptest! {
    // The cases where the two paths could part are a few of the blocks
    // generated: more cases than the default 256.
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// A pcapng file of arbitrary interfaces (link types, names, time
    /// resolutions and offsets) and blocks (enhanced packet blocks of
    /// arbitrary packets, captured lengths and options on any interface,
    /// other blocks, sections of either byte order), whole or cut, read in
    /// whole or in pieces: what the fast paths for enhanced packet blocks
    /// read is what the general path reads.
    #[test]
    fn the_pcapng_fast_paths_read_as_the_general_path(
        be in prop_oneof![4 => Just(false), 1 => Just(true)],
        interfaces in proptest::collection::vec(pcapng_interface(), 1..4),
        blocks in proptest::collection::vec(pcapng_block(), 0..16),
        cut in any::<usize>(),
        step in prop_oneof![Just(1usize << 16), 1usize..40],
    ) {
        let mut bytes = pcapng_file(be, &interfaces, &blocks);
        if cut % 4 == 0 {
            bytes.truncate(cut % (bytes.len() + 1));
        }
        let (fast, general) = both_paths(&bytes, step);
        prop_assert_eq!(fast, general);
    }

    /// The fast paths' usual file, as dumpcap and editcap write it: one
    /// little-endian section, SocketCAN interfaces with or without a name,
    /// resolution and offset, enhanced packet blocks of whole 16- and
    /// 72-byte packets of arbitrary frames on them: the general path's
    /// records, in whole or in pieces.
    #[test]
    fn the_pcapng_fast_paths_read_usual_files_as_the_general_path(
        interfaces in proptest::collection::vec(
            pcapng_interface().prop_map(|i| Interface { link: 227, ..i }),
            1..3,
        ),
        frames in proptest::collection::vec((any_can_frame(), any::<u64>(), 0u32..3), 0..20),
        step in prop_oneof![Just(1usize << 16), 1usize..120],
    ) {
        let mut w = Pcapng::default();
        w.section(false);
        for i in &interfaces {
            w.interface(i);
        }
        for (f, ticks, iface) in &frames {
            w.packet(iface % interfaces.len() as u32, *ticks, &writer::socketcan(f));
        }
        let (fast, general) = both_paths(&w.bytes, step);
        prop_assert_eq!(fast, general);
    }
}

/// Each check of the pcapng fast paths, failed by one block of a usual
/// file (after a classic frame on interface 0, which the general path
/// reads as the first packet after the interface's description, and
/// before a CAN FD frame): the reader with the fast paths reads what the
/// general path reads.
#[test]
fn each_check_of_the_pcapng_fast_paths() {
    let classic = [0, 0, 0x07, 0x05, 1, 0, 0, 0, 0x05, 0, 0, 0, 0, 0, 0, 0];
    let mut fd = vec![0, 0, 0x01, 0x23, 12, 0x05, 0, 0];
    fd.extend(1..=64u8);
    let can0 = Interface {
        link: 227,
        name: Some("can0".into()),
        tsresol: None,
        tsoffset: None,
    };
    let usual = |be: bool, interface: &Interface| {
        let mut w = Pcapng::default();
        w.section(be).interface(interface);
        w.packet(0, 1_700_000_000_000_400, &classic);
        w.packet(0, 1_700_000_000_000_500, &classic);
        w.packet(0, 1_700_000_000_000_600, &fd);
        w
    };
    let mut files = Vec::new();
    // Other interfaces: times in nanoseconds, 2^-20 s, with an offset, one
    // before the Unix epoch; Ethernet; named `any`; byte-swapped.
    for (tsresol, tsoffset) in [
        (Some(9), None),
        (Some(0x80 | 20), None),
        (None, Some(-3600)),
        (None, Some(-1_800_000_000)),
    ] {
        files.push(
            usual(
                false,
                &Interface {
                    tsresol,
                    tsoffset,
                    ..can0.clone()
                },
            )
            .bytes,
        );
    }
    files.push(
        usual(
            false,
            &Interface {
                link: 1,
                ..can0.clone()
            },
        )
        .bytes,
    );
    files.push(
        usual(
            false,
            &Interface {
                name: Some("any".into()),
                ..can0.clone()
            },
        )
        .bytes,
    );
    files.push(usual(true, &can0).bytes);
    // One damaged block each: the trailing length, the block length, the
    // captured length, the interface.
    let at = usual(false, &can0).bytes.len() - 48 - 104;
    for (offset, value) in [(44u32, 52u32), (4, 52), (20, 12), (20, 17), (8, 1)] {
        let mut w = usual(false, &can0);
        let at = at + offset as usize;
        w.bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
        files.push(w.bytes);
    }
    // An option after the packet; a padded shorter packet.
    let mut w = Pcapng::default();
    w.section(false).interface(&can0).packet(0, 1, &classic);
    let mut body = [0u32, 0, 1, 16, 16].map(u32::to_le_bytes).concat();
    body.extend(classic);
    body.extend([1, 0, 4, 0, b'h', b'i', b'!', 0, 0, 0, 0, 0]);
    w.block(6, &body);
    let mut body = [0u32, 0, 1, 13, 13].map(u32::to_le_bytes).concat();
    body.extend(&classic[..13]);
    w.block(6, &body);
    w.packet(0, 2, &classic);
    files.push(w.bytes);
    for (i, bytes) in files.iter().enumerate() {
        for step in [1 << 16, 1, 50] {
            let (fast, general) = both_paths(bytes, step);
            assert_eq!(fast, general, "file {i}, step {step}");
        }
    }
}
