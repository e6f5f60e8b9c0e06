//! The decoder session: what each frame reads as in the context of the
//! frames before it (docs/canopen.md#transfers, docs/output.md#sdo,
//! docs/canopen.md#pdo-mappings, docs/canopen.md#signals,
//! docs/canopen.md#cia402), and that no input makes it panic or lose a
//! transfer.

use proptest::prelude::*;

use super::*;
use crate::can::{BusName, CanFrame, CanId, LogEvent, Timestamp};
use crate::logs::Position;
use crate::summary::Summarizer;

fn at(ms: u64, id: u32, data: &[u8]) -> LogFrame<'static> {
    LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
        .with_timestamp(Timestamp::from_duration(Duration::from_millis(ms)))
        .with_iface(Iface::Name("can0"))
}

fn node(n: u8) -> NodeId {
    NodeId::new(n).unwrap()
}

/// SDO writes of node 3's TPDO1 mapping: 6041h (16 bits) then 6064h (32
/// bits), valid on the pre-defined COB-ID 0x183.
const TPDO1_MAPPING: [[u8; 8]; 4] = [
    [0x2F, 0x00, 0x1A, 0x00, 0x00, 0, 0, 0],
    [0x23, 0x00, 0x1A, 0x01, 0x10, 0x00, 0x41, 0x60],
    [0x23, 0x00, 0x1A, 0x02, 0x20, 0x00, 0x64, 0x60],
    [0x2F, 0x00, 0x1A, 0x00, 0x02, 0, 0, 0],
];

/// Feed node 3's TPDO1 mapping, each write answered.
fn map_tpdo1(decoder: &mut Decoder) {
    for (i, request) in TPDO1_MAPPING.iter().enumerate() {
        let line = 2 * i as u64 + 1;
        decoder.decode(Position::Line(line), &at(line, 0x603, request));
        let answer = [0x60, request[1], request[2], request[3], 0, 0, 0, 0];
        let frame = at(line + 1, 0x583, &answer);
        let decoded = decoder.decode(Position::Line(line + 1), &frame);
        let ended = decoded.sdo.unwrap().ended.unwrap();
        assert_eq!(ended.transfer.outcome, SdoOutcome::Completed);
        assert_eq!(ended.object(), Some("TPDO mapping parameter"));
    }
}

#[test]
fn a_mapping_written_by_sdo_names_the_pdo_signals() {
    let mut decoder = Decoder::new(DecoderConfig::new().node_profile(node(3), Profile::Akd));
    let frame = at(20, 0x183, &[0x37, 0x02, 0xA0, 0x86, 0x01, 0x00]);
    assert!(
        decoder.decode(Position::Line(9), &frame).pdo.is_none(),
        "no mapping yet"
    );
    map_tpdo1(&mut decoder);
    let decoded = decoder.decode(Position::Line(9), &frame);
    let pdo = decoded.pdo.unwrap();
    assert_eq!(pdo.map.node(), node(3));
    assert_eq!(pdo.map.number(), 1);
    assert_eq!(
        pdo.to_string(),
        "TPDO1 Statusword=567 Position actual value=100000"
    );
    let named: Vec<_> = pdo.named().map(|(name, s)| (name, s.value)).collect();
    assert_eq!(named.len(), 2);
    assert_eq!(named[0].0, "Statusword");
    assert!(pdo.error().is_none());
    let cia402 = decoded.cia402.unwrap();
    assert_eq!(
        cia402.state,
        Some(crate::canopen::Cia402State::OperationEnabled)
    );
    assert_eq!(cia402.to_string(), "operation_enabled");
    let json: serde_json::Value = serde_json::from_str(&decoded.to_json()).unwrap();
    assert_eq!(
        json["signals"],
        serde_json::json!({"Statusword": 567, "Position actual value": 100000})
    );
    assert_eq!(
        json["cia402"],
        serde_json::json!({"state": "operation_enabled"})
    );
}

#[test]
fn a_short_pdo_has_the_signals_that_fit_and_an_error() {
    let mut decoder = Decoder::new(DecoderConfig::new());
    map_tpdo1(&mut decoder);
    let frame = at(20, 0x183, &[0x37, 0x02, 0xA0]);
    let decoded = decoder.decode(Position::Line(9), &frame);
    let pdo = decoded.pdo.unwrap();
    assert_eq!(pdo.named().count(), 1);
    assert_eq!(
        pdo.error().unwrap().to_string(),
        "PDO entry 6064sub0 (32 bits) at bit 16: expected a payload of at least 6 bytes, found 3"
    );
    // Not a drive: signals named by their entry, no CiA 402 reading.
    assert_eq!(pdo.map.names()[0], "6041sub0");
    assert!(decoded.cia402.is_none());
}

#[test]
fn without_signals_only_a_drives_statusword_is_read() {
    let config = DecoderConfig::new()
        .node_profile(node(3), Profile::Akd)
        .signals(false);
    let mut decoder = Decoder::new(config);
    map_tpdo1(&mut decoder);
    let frame = at(20, 0x183, &[0x08, 0x00, 0, 0, 0, 0]);
    let decoded = decoder.decode(Position::Line(9), &frame);
    assert!(decoded.pdo.unwrap().signals.is_empty());
    assert_eq!(
        decoded.cia402.unwrap().state,
        Some(crate::canopen::Cia402State::Fault)
    );
}

#[test]
fn sdo_steps_and_transfers_read_as_a_person_says_them() {
    let mut decoder = Decoder::new(DecoderConfig::new());
    let frame = at(0, 0x605, &[0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]);
    let request = decoder.decode(Position::Line(1), &frame);
    let step = request.sdo.unwrap();
    assert!(step.started);
    assert_eq!(step.object(), Some("Manufacturer device name"));
    assert_eq!(
        step.to_string(),
        "request initiate upload 1008h.00 Manufacturer device name"
    );
    // A segmented upload of "AKD" (3 bytes).
    decoder.decode(
        Position::Line(2),
        &at(1, 0x585, &[0x41, 0x08, 0x10, 0x00, 3, 0, 0, 0]),
    );
    decoder.decode(
        Position::Line(3),
        &at(2, 0x605, &[0x60, 0, 0, 0, 0, 0, 0, 0]),
    );
    let frame = at(4, 0x585, &[0x09, b'A', b'K', b'D', 0, 0, 0, 0]);
    let last = decoder.decode(Position::Line(4), &frame);
    let ended = last.sdo.unwrap().ended.unwrap();
    assert_eq!(ended.data, b"AKD");
    assert!(!ended.truncated());
    assert_eq!(ended.transfer.frames, 4);
    assert_eq!(
        ended.to_string(),
        "read 1008h.00 \"AKD\" (segmented, 3 B, 4.0 ms)"
    );
    // An abort by the server.
    decoder.decode(
        Position::Line(5),
        &at(10, 0x605, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
    );
    let frame = at(11, 0x585, &[0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06]);
    let abort = decoder.decode(Position::Line(6), &frame);
    let text = abort.sdo.unwrap().to_string();
    assert!(
        text.starts_with("abort 6041h.00: Object does not exist"),
        "{text}"
    );
    assert!(
        text.ends_with("(read aborted by the server, 1.0 ms)"),
        "{text}"
    );
}

/// The decision in docs/canopen.md#sdo: a short SDO frame is decoded as far as
/// it goes — 3 bytes give the service and the index, 4 the sub-index too — in
/// the text and in the JSON `sdo` object.
#[test]
fn a_short_sdo_frame_says_as_much_as_it_holds() {
    let mut decoder = Decoder::new(DecoderConfig::new().node_profile(node(3), Profile::Akd));
    let rows: [(u32, &[u8], &str, &str); 6] = [
        (
            0x603,
            &[0x40, 0x41, 0x60],
            "request initiate upload 6041h Statusword, error: SDO frame: buffer of 3 bytes where 8 are needed",
            r#""sdo":{"direction":"request","service":"initiate_upload","index":24641,"object":"Statusword"}"#,
        ),
        (
            0x603,
            &[0x2B, 0x40, 0x60, 0x00],
            "request initiate download 6040h.00 Controlword, error: SDO frame: buffer of 4 bytes where 8 are needed",
            r#""sdo":{"direction":"request","service":"initiate_download","index":24640,"subindex":0,"object":"Controlword"}"#,
        ),
        (
            0x583,
            &[0x80, 0x00, 0x10],
            "response abort 1000h Device type, error: SDO frame: buffer of 3 bytes where 8 are needed",
            r#""sdo":{"direction":"response","service":"abort","index":4096,"object":"Device type"}"#,
        ),
        (
            0x603,
            &[0x40, 0x41],
            "request initiate upload, error: SDO frame: buffer of 2 bytes where 8 are needed",
            r#""sdo":{"direction":"request","service":"initiate_upload"}"#,
        ),
        // A segment has no multiplexer: bytes 1–2 are data.
        (
            0x603,
            &[0x60, 0x41, 0x60],
            "request upload segment, error: SDO frame: buffer of 3 bytes where 8 are needed",
            r#""sdo":{"direction":"request","service":"upload_segment"}"#,
        ),
        // A block download's end (sub-command 1): bytes 1–2 are the CRC.
        (
            0x603,
            &[0xC1, 0x34, 0x12],
            "request block download, error: SDO frame: buffer of 3 bytes where 8 are needed",
            r#""sdo":{"direction":"request","service":"block_download"}"#,
        ),
    ];
    for (i, (id, data, text, json)) in rows.into_iter().enumerate() {
        let frame = at(i as u64, id, data);
        let decoded = decoder.decode(Position::Line(i as u64 + 1), &frame);
        let step = decoded.sdo.unwrap();
        assert_eq!(step.to_string(), text);
        let mut out = Vec::new();
        decoded.write_json(&mut out).unwrap();
        let out = String::from_utf8(out).unwrap();
        assert!(out.contains(json), "{out}");
    }
}

#[test]
fn the_sdo_data_cap_keeps_the_first_bytes() {
    let mut decoder = Decoder::new(DecoderConfig::new().sdo_data_cap(2));
    decoder.decode(
        Position::Line(1),
        &at(0, 0x605, &[0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]),
    );
    decoder.decode(
        Position::Line(2),
        &at(1, 0x585, &[0x41, 0x08, 0x10, 0x00, 3, 0, 0, 0]),
    );
    decoder.decode(
        Position::Line(3),
        &at(2, 0x605, &[0x60, 0, 0, 0, 0, 0, 0, 0]),
    );
    let frame = at(4, 0x585, &[0x09, b'A', b'K', b'D', 0, 0, 0, 0]);
    let last = decoder.decode(Position::Line(4), &frame);
    let ended = last.sdo.unwrap().ended.unwrap();
    assert_eq!(ended.data, b"AK");
    assert!(ended.truncated());
}

#[test]
fn an_upload_of_the_device_type_makes_a_drive() {
    let mut decoder = Decoder::new(DecoderConfig::new());
    let bus = BusName::Name("can0".to_owned());
    decoder.decode(
        Position::Line(1),
        &at(0, 0x607, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]),
    );
    assert!(!decoder.is_drive(&bus, node(7)));
    decoder.decode(
        Position::Line(2),
        &at(1, 0x587, &[0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00]),
    );
    assert!(decoder.is_drive(&bus, node(7)));
    assert!(
        !decoder.is_drive(&BusName::Channel(1), node(7)),
        "another bus"
    );
    // Now an SDO read of its statusword is a CiA 402 reading.
    decoder.decode(
        Position::Line(3),
        &at(2, 0x607, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
    );
    let frame = at(3, 0x587, &[0x4B, 0x41, 0x60, 0x00, 0x40, 0x02, 0, 0]);
    let decoded = decoder.decode(Position::Line(4), &frame);
    assert_eq!(decoded.cia402.unwrap().to_string(), "switch_on_disabled");
}

#[test]
fn a_transfer_the_input_ends_in_is_handed_over_by_finish() {
    let mut decoder = Decoder::new(DecoderConfig::new());
    decoder.decode(
        Position::Line(7),
        &at(0, 0x605, &[0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]),
    );
    let open = decoder.finish();
    assert_eq!(open.len(), 1);
    assert_eq!(open[0].node, node(5));
    assert_eq!(open[0].bus, BusName::Name("can0".to_owned()));
    assert_eq!(open[0].transfer.start_position, 7);
    assert_eq!(open[0].transfer.outcome, SdoOutcome::TimedOut);
    assert_eq!(open[0].object.as_deref(), Some("Manufacturer device name"));
    assert!(decoder.finish().is_empty(), "handed over once");
}

#[test]
fn an_eds_names_the_pdos_it_configures_from_the_first_frame() {
    // TPDO1 of the bit-packed EDS maps 6041h, then 2100h "Digital input 1"
    // (1 bit, BOOLEAN), a name no profile knows.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/eds/bitfields.eds"
    );
    let config = DecoderConfig::new().eds_file(node(3), path).unwrap();
    let mut decoder = Decoder::new(config);
    // TPDO1 as the EDS maps it, before any SDO configuration in the log.
    let frame = at(0, 0x183, &[0x37, 0x02, 0x01, 0, 0, 0, 0, 0]);
    let decoded = decoder.decode(Position::Line(1), &frame);
    let pdo = decoded.pdo.expect("the EDS's mapping");
    assert_eq!(pdo.map.names()[..2], ["Statusword", "Digital input 1"]);
    let (name, signal) = pdo.named().nth(1).unwrap();
    assert_eq!((name, signal.value), ("Digital input 1", Value::Bool(true)));
    // Its device type says CiA 402: a drive.
    assert!(decoder.is_drive(&BusName::Name("can0".to_owned()), node(3)));
}

#[test]
fn an_eds_mapping_is_listed_with_its_origin() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/eds/bitfields.eds"
    );
    let config = DecoderConfig::new().eds_file(node(3), path).unwrap();
    let mut decoder = Decoder::new(config);
    let can0 = BusName::Name("can0".to_owned());
    assert_eq!(decoder.mappings(&can0, node(3)).count(), 0, "no bus yet");
    decoder.decode(
        Position::Line(1),
        &at(0, 0x183, &[0x37, 0x02, 0x01, 0, 0, 0, 0, 0]),
    );
    let maps: Vec<_> = decoder.mappings(&can0, node(3)).collect();
    let tpdo1 = maps.first().expect("the EDS's TPDO1");
    assert_eq!(
        (tpdo1.direction(), tpdo1.number()),
        (PdoDirection::Transmit, 1)
    );
    assert_eq!(tpdo1.origin(), PdoOrigin::Eds);
    assert_eq!(tpdo1.cob_id_origin(), PdoOrigin::Eds);
    assert_eq!(tpdo1.can_id().raw(), 0x183);
    assert!(tpdo1.cob_id().is_valid());
    assert_eq!(decoder.mappings(&can0, node(4)).count(), 0);
}

#[test]
fn mappings_are_listed_tpdos_then_rpdos_where_they_are_in_force() {
    let mut decoder = Decoder::new(DecoderConfig::new().node_profile(node(3), Profile::Akd));
    // RPDO2 first: the controlword.
    let rpdo2 = [
        [0x23, 0x01, 0x16, 0x01, 0x10, 0x00, 0x40, 0x60],
        [0x2F, 0x01, 0x16, 0x00, 0x01, 0, 0, 0],
    ];
    for (i, request) in rpdo2.iter().enumerate() {
        let line = 100 + 2 * i as u64;
        decoder.decode(Position::Line(line), &at(line, 0x603, request));
        let answer = [0x60, request[1], request[2], request[3], 0, 0, 0, 0];
        decoder.decode(Position::Line(line + 1), &at(line + 1, 0x583, &answer));
    }
    map_tpdo1(&mut decoder);
    let can0 = BusName::Name("can0".to_owned());
    let listed: Vec<_> = decoder
        .mappings(&can0, node(3))
        .map(|m| (m.direction(), m.number(), m.can_id().raw(), m.origin()))
        .collect();
    assert_eq!(
        listed,
        [
            (
                PdoDirection::Transmit,
                1,
                0x183,
                PdoOrigin::Sdo {
                    position: Position::Line(8)
                }
            ),
            (
                PdoDirection::Receive,
                2,
                0x303,
                PdoOrigin::Sdo {
                    position: Position::Line(103)
                }
            ),
        ]
    );
    // TPDO1 moved to 0x190 (valid, 11-bit): listed there, no longer on 0x183.
    decoder.decode(
        Position::Line(20),
        &at(20, 0x603, &[0x23, 0x00, 0x18, 0x01, 0x90, 0x01, 0, 0]),
    );
    decoder.decode(
        Position::Line(21),
        &at(21, 0x583, &[0x60, 0x00, 0x18, 0x01, 0, 0, 0, 0]),
    );
    let tpdo1 = decoder.mappings(&can0, node(3)).next().unwrap();
    assert_eq!(tpdo1.can_id().raw(), 0x190);
    assert_eq!(tpdo1.cob_id().to_u32(), 0x190);
    assert_eq!(
        tpdo1.origin(),
        PdoOrigin::Sdo {
            position: Position::Line(21)
        }
    );
    assert_eq!(
        tpdo1.cob_id_origin(),
        PdoOrigin::Sdo {
            position: Position::Line(21)
        }
    );
    assert!(decoder
        .decode(Position::Line(22), &at(22, 0x183, &[0x37, 0x02]))
        .pdo
        .is_none());
    // Made not valid (bit 31): out of force, not listed.
    decoder.decode(
        Position::Line(30),
        &at(30, 0x603, &[0x23, 0x00, 0x18, 0x01, 0x90, 0x01, 0, 0x80]),
    );
    decoder.decode(
        Position::Line(31),
        &at(31, 0x583, &[0x60, 0x00, 0x18, 0x01, 0, 0, 0, 0]),
    );
    let left: Vec<_> = decoder
        .mappings(&can0, node(3))
        .map(|m| (m.direction(), m.number()))
        .collect();
    assert_eq!(left, [(PdoDirection::Receive, 2)]);
}

#[test]
fn a_pdo_origin_reads_as_a_person_says_it() {
    assert_eq!(
        PdoOrigin::Sdo {
            position: Position::Line(102)
        }
        .to_string(),
        "SDO transfer at line 102"
    );
    assert_eq!(PdoOrigin::Eds.to_string(), "EDS");
    assert_eq!(
        PdoOrigin::PredefinedConnectionSet.to_string(),
        "pre-defined connection set"
    );
}

/// A frame on a CANopen identifier that the session does something with,
/// or any frame at all.
fn canopen_frame() -> impl Strategy<Value = CanFrame> {
    let node = 1u32..=8;
    let data = proptest::collection::vec(any::<u8>(), 0..=8);
    prop_oneof![
        3 => (prop_oneof![Just(0x580u32), Just(0x600)], node.clone(), data.clone())
            .prop_map(|(base, n, d)| CanFrame::new(CanId::standard(base + n).unwrap(), &d).unwrap()),
        2 => (prop_oneof![Just(0x180u32), Just(0x200), Just(0x280), Just(0x700), Just(0x080)], node, data)
            .prop_map(|(base, n, d)| CanFrame::new(CanId::standard(base + n).unwrap(), &d).unwrap()),
        1 => crate::test_gens::can::any_can_frame(),
    ]
}

proptest! {
    /// No stream of frames makes the session panic; every transfer that
    /// starts ends once (at a frame or at `finish`); every record is one
    /// JSON object; the summary counts every frame.
    #[test]
    fn any_stream_decodes_and_every_transfer_ends_once(
        frames in proptest::collection::vec((canopen_frame(), any::<bool>(), 0u64..50), 0..120),
    ) {
        let config = DecoderConfig::new().node_profile(node(3), Profile::Akd).sdo_data_cap(16);
        let mut decoder = Decoder::new(config.clone());
        let config = config.signals(false).heartbeat_timeout(Duration::from_millis(20));
        // The summary's two ways in: the frames read where the summary
        // needs them, and read whole (what the report reads).
        let mut summarizer = Summarizer::new(config.clone());
        let mut whole = Summarizer::new(config);
        let (mut started, mut ended, mut ms) = (0u64, 0u64, 0u64);
        for (i, (frame, bus, step)) in frames.iter().enumerate() {
            ms += step;
            let line = i as u64 + 1;
            let log = LogFrame::new(*frame)
                .with_timestamp(Timestamp::from_duration(Duration::from_millis(ms)))
                .with_iface(Iface::Channel(u16::from(*bus)));
            let decoded = decoder.decode(Position::Line(line), &log);
            let json: serde_json::Value = serde_json::from_str(&decoded.to_json()).unwrap();
            prop_assert_eq!(&json["line"], line);
            // The record appended to a buffer is the record written, with
            // and without a file name to escape.
            let mut appended = Vec::new();
            decoded.append_json(&mut appended, Some("a \"b\"\u{1}.log"));
            decoded.append_json(&mut appended, None);
            let mut written = Vec::new();
            decoded.write_json_in(&mut written, "a \"b\"\u{1}.log").unwrap();
            decoded.write_json(&mut written).unwrap();
            prop_assert_eq!(&appended, &written);
            let with_file = format!("{{\"file\":\"a \\\"b\\\"\\u0001.log\",{}\n", &decoded.to_json()[1..]);
            prop_assert_eq!(written.get(..with_file.len()), Some(with_file.as_bytes()));
            if let Some(step) = &decoded.sdo {
                started += u64::from(step.started);
                if let Some(end) = step.ended {
                    ended += 1;
                    prop_assert!(end.data.len() <= 16);
                }
            }
            let event = LogEvent::Frame(log);
            summarizer.add(Position::Line(line), &event);
            let _ = whole.add_with(Position::Line(line), &event, |_| {});
        }
        prop_assert_eq!(started, ended + decoder.finish().len() as u64);
        let summary = summarizer.finish();
        prop_assert_eq!(&summary, &whole.finish());
        prop_assert_eq!(summary.buses.iter().map(|b| b.frames).sum::<u64>(), frames.len() as u64);
        let _ = summary.to_string();
        serde_json::to_string(&summary).unwrap();
    }
}

/// A completed transfer reaches `Decoder::learn` only for the objects
/// `teaches` names: every other object, read or written, at sub-index 0
/// or 1, gives no CiA 402 reading and changes nothing — no PDO
/// parameter, no drive made, on a drive (AKD) and on a generic node.
#[test]
fn the_objects_left_out_of_learn_teach_nothing() {
    let mut decoder = Decoder::new(DecoderConfig::new().node_profile(node(3), Profile::Akd));
    // The bus and both nodes made by a frame each.
    decoder.decode(
        Position::Line(1),
        &at(1, 0x603, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]),
    );
    decoder.decode(
        Position::Line(2),
        &at(2, 0x605, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]),
    );
    let mut left_out = 0;
    for index in (0..=u16::MAX).filter(|&index| !teaches(index)) {
        left_out += 1;
        for (n, direction, sub) in [
            (3, TransferDirection::Upload, 0),
            (3, TransferDirection::Download, 0),
            (3, TransferDirection::Upload, 1),
            (5, TransferDirection::Upload, 0),
            (5, TransferDirection::Download, 1),
        ] {
            let transfer = SdoTransfer {
                direction,
                multiplexer: crate::canopen::ObjectAddress::new(index, sub),
                mode: crate::canopen::sdo::TransferMode::Expedited,
                indicated_size: Some(4),
                bytes: 4,
                frames: 2,
                outcome: SdoOutcome::Completed,
                start_position: 1,
                started_at: None,
                duration: None,
            };
            // 0x0002_0192: a device type that says CiA 402.
            let reading = decoder.learn(0, node(n), Position::Line(2), &transfer, 0x0002_0192);
            assert!(reading.is_none(), "{index:04X}h.{sub} on node {n}");
        }
    }
    assert_eq!(left_out, 0x1_0000 - 1 - 0x800 - 4);
    let bus = decoder.buses.get(0);
    for (n, drive) in [(3, true), (5, false)] {
        let state = bus.nodes[n].as_ref().expect("made by a frame");
        assert!(state.pdos.is_empty(), "node {n}");
        assert_eq!(state.drive, drive, "node {n}");
    }
}

/// A guard request (RTR on 0x700 + node) at `ms`.
fn guard_request(ms: u64, id: u32) -> LogFrame<'static> {
    LogFrame::new(CanFrame::new_remote(CanId::standard(id).unwrap(), 1).unwrap())
        .with_timestamp(Timestamp::from_duration(Duration::from_millis(ms)))
        .with_iface(Iface::Name("can0"))
}

/// docs/output.md#heartbeat: the first data frame on 0x700 + node after a
/// guard request is a `guard_answer`, every other one a `heartbeat`; a
/// request to another node, or on another bus, answers nothing.
#[test]
fn the_first_data_frame_after_a_guard_request_is_its_answer() {
    let mut decoder = Decoder::new(DecoderConfig::new());
    let on_can1 = at(7, 0x70A, &[0x05]).with_iface(Iface::Name("can1"));
    let frames = [
        (at(0, 0x70A, &[0x00]), MessageKind::Heartbeat),
        (guard_request(1, 0x70A), MessageKind::GuardRequest),
        (at(2, 0x70A, &[0x7F]), MessageKind::GuardAnswer),
        (at(3, 0x70A, &[0x05]), MessageKind::Heartbeat),
        (guard_request(4, 0x70B), MessageKind::GuardRequest),
        (at(5, 0x70A, &[0x85]), MessageKind::Heartbeat),
        (guard_request(6, 0x70A), MessageKind::GuardRequest),
        (on_can1, MessageKind::Heartbeat),
        (at(8, 0x70A, &[0x85]), MessageKind::GuardAnswer),
    ];
    for (i, (frame, kind)) in frames.iter().enumerate() {
        let decoded = decoder.decode(Position::Line(i as u64 + 1), frame);
        assert_eq!(decoded.kind, *kind, "line {}", i + 1);
    }
    // The answer keeps the heartbeat's keys: its state and toggle.
    let answer = at(9, 0x70A, &[0x85]);
    decoder.decode(Position::Line(10), &guard_request(9, 0x70A));
    let decoded = decoder.decode(Position::Line(11), &answer);
    let mut json = Vec::new();
    decoded.append_json(&mut json, None);
    let json = String::from_utf8(json).unwrap();
    assert!(
        json.contains(
            r#""kind":"guard_answer","node":10,"state":"operational","state_raw":5,"toggle":true}"#
        ),
        "{json}"
    );
}

/// A request repeated before its answer is answered once; the requests of
/// several nodes each get their own answer, and once all are answered,
/// every data frame is a heartbeat again.
#[test]
fn each_waiting_guard_request_gets_one_answer() {
    let mut decoder = Decoder::new(DecoderConfig::new());
    let frames = [
        (guard_request(0, 0x70A), MessageKind::GuardRequest),
        (guard_request(1, 0x70A), MessageKind::GuardRequest),
        (guard_request(2, 0x70B), MessageKind::GuardRequest),
        (at(3, 0x70A, &[0x05]), MessageKind::GuardAnswer),
        (at(4, 0x70A, &[0x05]), MessageKind::Heartbeat),
        (at(5, 0x70B, &[0x85]), MessageKind::GuardAnswer),
        (at(6, 0x70B, &[0x05]), MessageKind::Heartbeat),
        (at(7, 0x70A, &[0x05]), MessageKind::Heartbeat),
        (guard_request(8, 0x70B), MessageKind::GuardRequest),
        (at(9, 0x70A, &[0x05]), MessageKind::Heartbeat),
        (at(10, 0x70B, &[0x05]), MessageKind::GuardAnswer),
    ];
    for (i, (frame, kind)) in frames.iter().enumerate() {
        let decoded = decoder.decode(Position::Line(i as u64 + 1), frame);
        assert_eq!(decoded.kind, *kind, "line {}", i + 1);
    }
}
