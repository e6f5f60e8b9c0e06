//! The post-mortem's rules (docs/summary.md), each on a few frames.

use core::time::Duration;

use super::*;
use crate::can::{BusName, CanFrame, CanId, Iface, LogEvent, LogFrame, Timestamp};
use crate::canopen::{Cia402State, NodeId};
use crate::decoder::DecoderConfig;
use crate::logs::Position;
use crate::profiles::Profile;

/// Summarize `frames` (time in ms, identifier, data), line numbers from 1,
/// all on `can0`, with the heartbeat consumer time `heartbeat`; `untimed`
/// frames have no time.
fn summarize(frames: &[(Option<u64>, u32, &[u8])], heartbeat: Option<Duration>) -> Summary {
    let mut config = DecoderConfig::new()
        .node_profile(NodeId::new(3).unwrap(), Profile::Akd)
        .signals(false);
    if let Some(time) = heartbeat {
        config = config.heartbeat_timeout(time);
    }
    let mut summarizer = Summarizer::new(config);
    for (i, &(ms, id, data)) in frames.iter().enumerate() {
        let mut log = LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
            .with_iface(Iface::Name("can0"));
        if let Some(ms) = ms {
            log = log.with_timestamp(Timestamp::from_duration(Duration::from_millis(ms)));
        }
        summarizer.add(Position::Line(i as u64 + 1), &LogEvent::Frame(log));
    }
    summarizer.finish()
}

#[test]
fn the_first_error_is_the_root_cause_until_a_reset() {
    let summary = summarize(
        &[
            (Some(0), 0x083, &[0x10, 0x81, 0x11, 0, 0, 0, 0, 0]),
            (Some(1), 0x083, &[0x30, 0x73, 0x05, 0, 0, 0, 0, 0]),
            (Some(2), 0x084, &[0x00, 0x23, 0x03, 0, 0, 0, 0, 0]),
            (Some(3), 0x084, &[0x00, 0x00, 0x01, 0, 0, 0, 0, 0]),
        ],
        None,
    );
    let three = &summary.nodes[0];
    assert_eq!((three.node.get(), three.emcy, three.resets), (3, 2, 0));
    assert_eq!(three.first_error.unwrap().code.get(), 0x8110);
    assert_eq!(
        three.active_error.unwrap().line,
        1,
        "the follow-up is not the root cause"
    );
    let four = &summary.nodes[1];
    assert_eq!((four.emcy, four.resets), (2, 1));
    assert!(four.active_error.is_none());
    assert_eq!(four.last_register.unwrap().bits(), 0x01);
    let text = four.to_string();
    assert!(
        text.contains("error register 0x01 still set by the last EMCY"),
        "{text}"
    );
}

#[test]
fn heartbeat_gaps_are_timeouts_only_when_every_frame_has_a_time() {
    let frames: &[(Option<u64>, u32, &[u8])] = &[
        (Some(0), 0x705, &[0x00]),
        (Some(100), 0x705, &[0x05]),
        (Some(400), 0x705, &[0x05]),
        (Some(450), 0x705, &[0x05]),
        (Some(700), 0x080, &[]),
    ];
    let summary = summarize(frames, Some(Duration::from_millis(200)));
    let hb = &summary.nodes[0].heartbeat;
    assert_eq!(hb.boot_ups.head(), [1]);
    assert_eq!(
        hb.timeouts,
        Timeouts::Checked(Listed::from_iter([
            HeartbeatGap {
                after_line: 2,
                gap: Duration::from_millis(300),
                since: Timestamp::from_duration(Duration::from_millis(100)),
                due: Timestamp::from_duration(Duration::from_millis(300)),
                cause: None,
            },
            HeartbeatGap {
                after_line: 4,
                gap: Duration::from_millis(250),
                since: Timestamp::from_duration(Duration::from_millis(450)),
                due: Timestamp::from_duration(Duration::from_millis(650)),
                cause: None,
            },
        ]))
    );
    assert!(!summary.timeouts_not_checked());

    let mut untimed = frames.to_vec();
    untimed[2].0 = None;
    let summary = summarize(&untimed, Some(Duration::from_millis(200)));
    assert_eq!(summary.nodes[0].heartbeat.timeouts, Timeouts::NotChecked);
    assert!(summary.timeouts_not_checked());
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(json[0]["heartbeat"]["timeouts"], serde_json::Value::Null);

    let summary = summarize(frames, None);
    assert_eq!(summary.nodes[0].heartbeat.timeouts, Timeouts::NotAsked);
    let json = serde_json::to_value(&summary).unwrap();
    assert!(json[0]["heartbeat"].get("timeouts").is_none());
}

#[test]
fn a_drives_fault_names_the_emcy_before_it() {
    let summary = summarize(
        &[
            // Node 3 (akd) reads its statusword by SDO: operation enabled.
            (Some(0), 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
            (Some(1), 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]),
            (Some(10), 0x083, &[0x05, 0x73, 0x81, 0, 0, 0, 0, 0]),
            (Some(20), 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
            (Some(27), 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x08, 0x02, 0, 0]),
        ],
        None,
    );
    let drive = summary.nodes[0].cia402.as_ref().expect("an akd is a drive");
    let states: Vec<_> = drive.transitions.iter().map(|t| (t.line, t.to)).collect();
    assert_eq!(
        states,
        [(2, Cia402State::OperationEnabled), (5, Cia402State::Fault)]
    );
    let faults = drive.faults.as_ref().expect("statuswords seen");
    assert_eq!(faults.count(), 1);
    assert_eq!(faults.head()[0].emcy_before.unwrap().line, 3);
    let text = summary.nodes[0].to_string();
    assert!(
        text.contains("went operation_enabled → fault at line 5, 17.0 ms after EMCY 0x7305"),
        "{text}"
    );
    let json = serde_json::to_value(&summary).unwrap();
    // The verdict first, then node 3.
    assert_eq!(json[0]["type"], "verdict");
    assert_eq!(json[0]["stop"]["cause"]["line"], 3);
    assert_eq!(json[1]["cia402"]["faults"], serde_json::json!([5]));
    assert_eq!(json[1]["cia402"]["last_state"], "fault");
    assert_eq!(json[1]["sdo"]["latency_ms"]["count"], 2);
}

/// The decision in docs/summary.md#cia402: a drive whose statusword was never
/// seen has `"faults": null` — nothing observed is not "no fault" — and one
/// that was seen and never faulted `[]`.
#[test]
fn a_drive_never_seen_has_unknown_faults() {
    // Node 3 (akd) only answers a read of its device type: no statusword.
    let summary = summarize(
        &[
            (Some(0), 0x603, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]),
            (
                Some(1),
                0x583,
                &[0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0],
            ),
        ],
        None,
    );
    let drive = summary.nodes[0].cia402.as_ref().expect("an akd is a drive");
    assert!(drive.transitions.is_empty());
    assert_eq!(drive.faults, None);
    assert!(!drive.observed());
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(
        json[0]["cia402"],
        serde_json::json!({"transitions": [], "transition_count": 0, "last_state": null, "faults": null, "fault_count": null})
    );
    assert!(summary.nodes[0]
        .to_string()
        .contains("CiA 402: no statusword seen"));

    // Seen in operation enabled, never faulted: no fault, known.
    let summary = summarize(
        &[
            (Some(0), 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
            (Some(1), 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]),
        ],
        None,
    );
    let drive = summary.nodes[0].cia402.as_ref().unwrap();
    assert_eq!(drive.faults, Some(Listed::new()));
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(json[0]["cia402"]["faults"], serde_json::json!([]));
}

#[test]
fn a_log_without_times_says_timeouts_were_not_checked_even_with_no_node() {
    let summary = summarize(
        &[(None, 0x080, &[]), (Some(1), 0x080, &[])],
        Some(Duration::from_millis(100)),
    );
    assert!(summary.nodes.is_empty());
    assert!(summary.timeouts_not_checked());
    let summary = summarize(&[(None, 0x080, &[])], None);
    assert!(!summary.timeouts_not_checked(), "not asked");
}

#[test]
fn times_keep_their_digits_in_json() {
    let mut summarizer = Summarizer::default();
    let log = LogFrame::new(CanFrame::new(CanId::standard(0x705).unwrap(), &[5]).unwrap())
        .with_timestamp(Timestamp::new(1_700_000_000, 500).unwrap());
    summarizer.add(Position::Line(1), &LogEvent::Frame(log));
    let log = log.with_timestamp(Timestamp::from_nanos(1_700_000_001, 1).unwrap());
    summarizer.add(Position::Line(2), &LogEvent::Frame(log));
    let summary = summarizer.finish();
    let bus = serde_json::to_string(&summary.records().last().unwrap()).unwrap();
    assert_eq!(
        bus,
        r#"{"type":"bus","iface":null,"frames":2,"error_frames":0,"bus_off":[],"bus_off_count":0,"error_passive":[],"error_passive_count":0,"status_events":0,"first_ts":1700000000.000500,"last_ts":1700000001.000000001,"nodes":[5]}"#
    );
    assert_eq!(
        summary.buses[0].to_string(),
        "bus -  frames 2, error frames 0, from 1700000000.000500 to 1700000001.000000, nodes 5\n"
    );
}

#[test]
fn a_node_is_one_per_bus() {
    let mut summarizer = Summarizer::default();
    for (line, iface) in [(1, "can1"), (2, "can0"), (3, "can1")] {
        let log = LogFrame::new(CanFrame::new(CanId::standard(0x705).unwrap(), &[5]).unwrap())
            .with_iface(Iface::Name(iface));
        summarizer.add(Position::Line(line), &LogEvent::Frame(log));
    }
    let summary = summarizer.finish();
    let buses: Vec<_> = summary
        .nodes
        .iter()
        .map(|n| (n.bus.to_string(), n.heartbeat.count))
        .collect();
    assert_eq!(buses, [("can0".to_owned(), 1), ("can1".to_owned(), 2)]);
    assert!(summary
        .node(&BusName::Name("can1".to_owned()), NodeId::new(5).unwrap())
        .is_some());
}

#[test]
fn long_lists_keep_their_first_and_last_entries_and_count_them_all() {
    // Node 5 boots 30 times; its drive (node 3) goes through 40 states:
    // enabled / fault by turns, read by SDO.
    let mut frames: Vec<(Option<u64>, u32, &[u8])> = Vec::new();
    for i in 0..30 {
        frames.push((Some(i * 10), 0x705, &[0x00]));
    }
    const ENABLED: &[u8] = &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0];
    const FAULT: &[u8] = &[0x4B, 0x41, 0x60, 0x00, 0x08, 0x02, 0, 0];
    const READ: &[u8] = &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0];
    for i in 0..40 {
        frames.push((Some(1000 + i * 10), 0x603, READ));
        frames.push((
            Some(1001 + i * 10),
            0x583,
            if i % 2 == 0 { ENABLED } else { FAULT },
        ));
    }
    let summary = summarize(&frames, None);
    let boots = &summary.node(&BusName::Name("can0".into()), NodeId::new(5).unwrap());
    let boots = &boots.unwrap().heartbeat.boot_ups;
    assert_eq!(boots.count(), 30);
    assert_eq!(boots.omitted(), 10);
    let kept: Vec<u64> = boots.iter().copied().collect();
    let expected: Vec<u64> = (1..=10).chain(21..=30).collect();
    assert_eq!(kept, expected);

    let drive = summary.nodes[0].cia402.as_ref().unwrap();
    assert_eq!(drive.transitions.count(), 40);
    assert_eq!(drive.faults.as_ref().unwrap().count(), 20);
    // The last state is the last one seen, not the last one kept first.
    assert_eq!(drive.last_state(), Some(Cia402State::Fault));

    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(json[0]["type"], "verdict", "the drive's last fault stops");
    let node5 = &json[2];
    assert_eq!(node5["heartbeat"]["boot_up_count"], 30);
    assert_eq!(node5["heartbeat"]["boot_ups"], serde_json::json!(expected));
    let cia402 = &json[1]["cia402"];
    assert_eq!(cia402["transition_count"], 40);
    assert_eq!(cia402["transitions"].as_array().unwrap().len(), 20);
    assert_eq!(cia402["fault_count"], 20);
    assert_eq!(cia402["faults"].as_array().unwrap().len(), 20);
    assert_eq!(cia402["last_state"], "fault");

    let text = summary.to_string();
    assert!(
        text.contains(
            "boot-ups at lines 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, … 10 more …, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30"
        ),
        "{text}"
    );
    assert!(text.contains("CiA 402, 40 states in turn:"), "{text}");
    assert!(text.contains("… 28 more …"), "{text}");
    // Faults: the first 10 and the last 10 are kept; none omitted.
    let drive = summary.nodes[0].to_string();
    assert_eq!(drive.matches("→ fault at line").count(), 20, "{drive}");
}

/// Every log of the repository (`samples/`, `tests/fixtures/`), for the
/// tests that read real files.
#[cfg(feature = "logs")]
fn repository_logs() -> Vec<std::path::PathBuf> {
    fn walk(dir: &std::path::Path, found: &mut Vec<std::path::PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, found);
            } else if path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| ["log", "asc", "blf", "pcap", "pcapng", "trc", "mf4"].contains(&e))
            {
                found.push(path);
            }
        }
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = Vec::new();
    walk(&root.join("samples"), &mut found);
    walk(&root.join("tests/fixtures"), &mut found);
    found.sort();
    found
}

/// `Summarizer::add` reads a frame with the decoder only where the
/// decoder keeps state, through the decoder's own short paths for SDO and
/// PDO frames; it gives exactly the summary that `Summarizer::add_with`,
/// which reads every frame whole, gives on every log of the repository (PDO
/// mappings learned from SDO, CiA 402 drives, SDO transfers and aborts,
/// EMCY, heartbeats with a consumer time, error frames), with a decoder
/// that unpacks signals and one that does not.
#[cfg(feature = "logs")]
#[test]
fn adding_is_decoding_then_adding_on_every_log() {
    use crate::logs::ReadLog;
    let logs = repository_logs();
    assert!(logs.len() > 20, "{logs:?}");
    let mut frames = 0u64;
    for path in &logs {
        for signals in [false, true] {
            let config = DecoderConfig::new()
                .node_profile(NodeId::new(3).unwrap(), Profile::Akd)
                .signals(signals);
            let config = config.heartbeat_timeout(Duration::from_millis(150));
            let mut by_add = Summarizer::new(config.clone());
            let mut by_decode = Summarizer::new(config);
            let Ok(mut log) = crate::logs::open(path) else {
                continue;
            };
            while let Some(record) = log.next_event() {
                let Ok(record) = record else { continue };
                let position = record.position;
                by_add.add(position, &record.event);
                let decoded = by_decode.add_with(position, &record.event, |_| {});
                frames += u64::from(decoded.is_some());
            }
            assert_eq!(
                by_add.finish(),
                by_decode.finish(),
                "{}, signals {signals}",
                path.display()
            );
        }
    }
    assert!(frames > 1_000, "{frames}");
}

/// docs/summary.md#verdict: a summary has a verdict exactly when one of
/// its findings stops the recording (a fault, a heartbeat timeout, a
/// bus-off, an AL error, a servo fault), on every log of the repository,
/// with a heartbeat consumer time and without; a log with findings but no
/// such one among them has none.
#[cfg(feature = "logs")]
#[test]
fn a_verdict_exactly_when_a_finding_stops_on_every_log() {
    use crate::logs::ReadLog;
    let (mut with, mut without) = (0, 0);
    for path in &repository_logs() {
        for heartbeat in [None, Some(Duration::from_millis(150))] {
            let mut config = DecoderConfig::new();
            if let Some(time) = heartbeat {
                config = config.heartbeat_timeout(time);
            }
            let mut summarizer = Summarizer::new(config);
            let Ok(mut log) = crate::logs::open(path) else {
                continue;
            };
            while let Some(record) = log.next_event() {
                if let Ok(record) = record {
                    summarizer.add(record.position, &record.event);
                }
            }
            let summary = summarizer.finish();
            let findings = summary.findings();
            assert_eq!(
                summary.verdict().is_some(),
                findings.iter().any(Finding::stops),
                "{}, heartbeat {heartbeat:?}",
                path.display()
            );
            if summary.verdict().is_some() {
                with += 1;
            } else if !findings.is_empty() {
                without += 1;
            }
        }
    }
    assert!(
        with > 0 && without > 0,
        "{with} with a verdict, {without} without"
    );
}

/// The summary keeps each bus at its place in the decoder's table: frames
/// of two interfaces in turns, SDO and not, count each on its own bus.
#[test]
fn frames_of_buses_in_turns_count_each_on_its_bus() {
    let frame = |iface: &'static str, id: u32, first: u8| {
        LogEvent::Frame(
            LogFrame::new(
                CanFrame::new(
                    CanId::standard(id).unwrap(),
                    &[first, 0x00, 0x10, 0, 0, 0, 0, 0],
                )
                .unwrap(),
            )
            .with_iface(Iface::Name(iface)),
        )
    };
    let mut summarizer = Summarizer::default();
    // can1's first frame is an EMCY: the bus is found before any SDO frame.
    summarizer.add(Position::Line(1), &frame("can1", 0x085, 0x10));
    summarizer.add(Position::Line(2), &frame("can0", 0x602, 0x40));
    summarizer.add(Position::Line(3), &frame("can1", 0x605, 0x40));
    summarizer.add(Position::Line(4), &frame("can0", 0x602, 0x40));
    summarizer.add(Position::Line(5), &frame("can1", 0x605, 0x40));
    let summary = summarizer.finish();
    let frames: Vec<(String, u64)> = summary
        .buses
        .iter()
        .map(|bus| (bus.bus.to_string(), bus.frames))
        .collect();
    assert_eq!(frames, [("can0".to_string(), 2), ("can1".to_string(), 3)]);
    let requests = |bus: &str, node: u8| {
        summary
            .node(&BusName::Name(bus.into()), NodeId::new(node).unwrap())
            .map(|n| n.sdo.requests)
    };
    assert_eq!(requests("can0", 2), Some(2));
    assert_eq!(requests("can1", 5), Some(2));
    assert_eq!(requests("can0", 5), None);
    assert_eq!(requests("can1", 2), None);
}

/// docs/summary.md#emcy: a boot-up is the device's re-initialisation, after
/// which the EMCY state machine starts error-free (transition 0, CiA 301):
/// the active error before it is gone, and the first error after it is the
/// new root cause, not a follow-up of the old one.
#[test]
fn a_boot_up_clears_the_active_error_until_a_new_emcy() {
    let hot: &[u8] = &[0x00, 0x42, 0x09, 0, 0, 0, 0, 0];
    let current: &[u8] = &[0x10, 0x23, 0x03, 0, 0, 0, 0, 0];
    let before = summarize(&[(Some(0), 0x705, &[0x05]), (Some(1), 0x085, hot)], None);
    assert_eq!(before.nodes[0].active_error.unwrap().line, 2);

    let rebooted = summarize(
        &[
            (Some(0), 0x705, &[0x05]),
            (Some(1), 0x085, hot),
            (Some(2), 0x705, &[0x00]),
        ],
        None,
    );
    let five = &rebooted.nodes[0];
    assert_eq!(five.active_error, None);
    assert_eq!(five.last_register, None, "no EMCY since the boot-up");
    assert_eq!(five.first_error.unwrap().line, 2, "the first error stays");

    let again = summarize(
        &[
            (Some(0), 0x705, &[0x05]),
            (Some(1), 0x085, hot),
            (Some(2), 0x705, &[0x00]),
            (Some(3), 0x085, current),
            (Some(4), 0x085, hot),
        ],
        None,
    );
    let five = &again.nodes[0];
    assert_eq!(five.active_error.unwrap().code.get(), 0x2310);
    assert_eq!(five.active_error.unwrap().line, 4);
}

/// docs/summary.md#emcy: an EMCY with an error code and the error register
/// at 0 says no error is present (CiA 301: bit 0 is set in any error
/// situation): it is counted, and is a first error, but not the active
/// error (the Baumer encoder's battery warning, 0xFF00, is sent so).
#[test]
fn an_emcy_that_reports_no_error_is_not_the_active_error() {
    let battery: &[u8] = &[0x00, 0xFF, 0x00, 0, 0, 0x10, 0, 0];
    let passive: &[u8] = &[0x20, 0x81, 0x10, 0, 0, 0x10, 0, 0];
    let summary = summarize(
        &[(Some(0), 0x085, battery), (Some(1), 0x085, passive)],
        None,
    );
    let five = &summary.nodes[0];
    assert_eq!(five.emcy, 2);
    assert_eq!(five.first_error.unwrap().code.get(), 0xFF00);
    assert_eq!(
        five.active_error.unwrap().code.get(),
        0x8120,
        "the warning did not take the slot"
    );
    // The text says which is which.
    assert!(
        five.to_string().contains(
            "first warning: 0xFF00 Device specific (line 1), \
             first error: 0x8120 CAN in error passive mode (line 2)"
        ),
        "{five}"
    );
    assert_eq!(five.first_warning().map(|e| e.line), Some(1));
    assert_eq!(five.first_error_reported().map(|e| e.line), Some(2));
    let alone = summarize(&[(Some(0), 0x085, battery)], None);
    assert_eq!(alone.nodes[0].active_error, None);
    assert_eq!(alone.nodes[0].first_error_reported(), None);
    assert!(
        alone.nodes[0].to_string().contains("first error: none"),
        "{}",
        alone.nodes[0]
    );
}

/// docs/summary.md#heartbeat: the node's last state is the last frame's
/// that tells it, a heartbeat or a node-guarding answer; the answers are
/// counted as `guard_answer`, not as heartbeats.
#[test]
fn the_last_state_comes_from_the_last_frame_that_tells_it() {
    let mut summarizer = Summarizer::new(DecoderConfig::new().signals(false));
    let data = |id: u32, data: &'static [u8]| {
        LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
    };
    let request = LogFrame::new(CanFrame::new_remote(CanId::standard(0x70A).unwrap(), 1).unwrap());
    let frames = [
        data(0x70A, &[0x00]),
        request,
        data(0x70A, &[0x7F]),
        request,
        data(0x70A, &[0x85]),
    ];
    for (i, frame) in frames.into_iter().enumerate() {
        summarizer.add(Position::Line(i as u64 + 1), &LogEvent::Frame(frame));
    }
    let summary = summarizer.finish();
    let ten = &summary.nodes[0];
    assert_eq!(
        ten.heartbeat.last_state.and_then(|b| b.state()),
        Some(crate::canopen::NmtState::Operational)
    );
    assert_eq!(ten.heartbeat.count, 1, "the boot-up only");
    assert_eq!(ten.frames.get(crate::canopen::MessageKind::Heartbeat), 1);
    assert_eq!(ten.frames.guard_answers(), 2);
    assert_eq!(ten.guarding.answers, 2);
    assert!(ten.to_string().contains("last state operational"), "{ten}");
}

/// Node 3 (akd) reads its statusword by SDO: operation enabled at line 2,
/// then the frames of `between` (at their times), then fault at `fault_ms`.
fn drive_faulting(between: &[(Option<u64>, u32, &'static [u8])], fault_ms: u64) -> Summary {
    let mut frames: Vec<(Option<u64>, u32, &[u8])> = vec![
        (Some(0), 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
        (Some(1), 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]),
    ];
    frames.extend_from_slice(between);
    frames.push((
        Some(fault_ms - 1),
        0x603,
        &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0],
    ));
    frames.push((
        Some(fault_ms),
        0x583,
        &[0x4B, 0x41, 0x60, 0x00, 0x08, 0x02, 0, 0],
    ));
    summarize(&frames, Some(Duration::from_millis(300)))
}

/// docs/summary.md#severity: each kind of finding has its severity; an
/// EMCY's comes from its error register and the node's profile.
#[test]
fn severities_follow_the_table() {
    use crate::canopen::{Emcy, ErrorCode, ErrorRegister};
    let emcy = |code, register, manufacturer| {
        Emcy::new(
            ErrorCode::new(code),
            ErrorRegister::from_bits_retain(register),
            manufacturer,
        )
    };
    let cases = [
        // An error register set: an error, whatever the profile.
        (
            emcy(0x7305, 0x01, [0x21, 0, 0, 0, 0]),
            Profile::Akd,
            Severity::Error,
        ),
        (emcy(0x4200, 0x09, [0; 5]), Profile::Baumer, Severity::Error),
        (
            emcy(0x8120, 0x10, [0; 5]),
            Profile::Generic,
            Severity::Error,
        ),
        // The register at 0: no error present, a warning.
        (
            emcy(0xFF00, 0x00, [0, 0, 0x10, 0, 0]),
            Profile::Generic,
            Severity::Warning,
        ),
        // Baumer's table: 0xFF00 with 6505h bit 4 is the battery warning.
        (
            emcy(0xFF00, 0x00, [0, 0, 0x10, 0, 0]),
            Profile::Baumer,
            Severity::Warning,
        ),
        (
            emcy(0x6100, 0x00, [0, 0, 0x04, 0, 0]),
            Profile::Baumer,
            Severity::Warning,
        ),
        // A reset is a notice.
        (
            emcy(0x0000, 0x00, [0; 5]),
            Profile::Generic,
            Severity::Notice,
        ),
    ];
    for (emcy, profile, severity) in cases {
        assert_eq!(
            Severity::of_emcy(&emcy, profile),
            severity,
            "{emcy:?} {profile}"
        );
    }
    for (kind, severity) in [
        (FindingKind::Cia402Fault, Severity::Fault),
        (FindingKind::BusOff, Severity::Fault),
        (FindingKind::HeartbeatTimeout, Severity::Error),
        (FindingKind::Restarts, Severity::Warning),
        (FindingKind::SdoBroken, Severity::Warning),
        (FindingKind::SdoTimeout, Severity::Warning),
        (FindingKind::ToggleError, Severity::Warning),
        (FindingKind::ErrorPassive, Severity::Warning),
        (FindingKind::SdoAbort, Severity::Notice),
    ] {
        assert_eq!(
            Severity::of_finding(kind, &FindingDetail::Line, Profile::Generic),
            severity,
            "{kind}"
        );
    }
}

/// docs/summary.md#causes: the drive's last error EMCY is the cause of its
/// fault when it came at most a second before; an older one, or a log
/// without times, links nothing.
#[test]
fn an_emcy_causes_a_fault_within_the_window() {
    let sensor: &[u8] = &[0x05, 0x73, 0x01, 0x21, 0, 0, 0, 0];
    let near = drive_faulting(&[(Some(10), 0x083, sensor)], 27);
    let verdict = near.verdict().expect("a fault stops");
    assert_eq!(verdict.stop.kind, FindingKind::Cia402Fault);
    assert_eq!(verdict.stop.line, 5);
    assert_eq!(verdict.cause.unwrap().line, 3);
    assert_eq!(
        verdict.stop_text(),
        "can0 node 3 went operation_enabled → fault at line 5 (+0.027 s), 17.0 ms after \
         EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2 (line 3)"
    );
    // Exactly the window is in it; a microsecond more is not.
    let edge = drive_faulting(&[(Some(10), 0x083, sensor)], 1010);
    assert!(edge.verdict().unwrap().cause.is_some());
    let far = drive_faulting(&[(Some(10), 0x083, sensor)], 1011);
    let verdict = far.verdict().unwrap();
    assert_eq!(verdict.cause, None);
    assert!(
        verdict.stop_text().ends_with("fault at line 5 (+1.011 s)"),
        "{}",
        verdict.stop_text()
    );
    // The summary's own sentence still names the EMCY before the fault.
    assert!(far.nodes[0].to_string().contains("after EMCY 0x7305"));
}

/// docs/summary.md#verdict: the stop is the last fault, heartbeat timeout
/// or bus-off; the first cause the earliest fault or error of its device
/// at or before it — a warning is never one.
#[test]
fn the_stop_is_the_last_and_the_first_cause_the_earliest_error_of_its_device() {
    let sensor: &[u8] = &[0x05, 0x73, 0x01, 0x21, 0, 0, 0, 0];
    let warning: &[u8] = &[0x00, 0xFF, 0x00, 0, 0, 0x10, 0, 0];
    let summary = drive_faulting(
        &[
            // Node 3's warning, then its error; node 4's earlier error.
            (Some(2), 0x084, &[0x10, 0x81, 0x11, 0, 0, 0, 0, 0]),
            (Some(5), 0x083, warning),
            (Some(10), 0x083, sensor),
        ],
        27,
    );
    let verdict = summary.verdict().unwrap();
    assert_eq!(
        (verdict.stop.node.unwrap().get(), verdict.stop.line),
        (3, 7)
    );
    // Node 3's first EMCY is a warning, a finding of its own; its first
    // error, the sensor fault, is the first cause.
    let first = &verdict.first_cause;
    assert_eq!((first.node.unwrap().get(), first.line), (3, 5));
    assert_eq!(
        (first.kind, first.severity),
        (FindingKind::FirstError, Severity::Error)
    );
    let warnings: Vec<_> = summary
        .findings()
        .into_iter()
        .filter(|f| f.kind == FindingKind::FirstWarning)
        .map(|f| (f.line, f.severity, f.text()))
        .collect();
    assert_eq!(
        warnings,
        [(
            4,
            Severity::Warning,
            "first warning: EMCY 0xFF00 Device specific at line 4".to_owned()
        )]
    );
    // A warning alone is no cause: the first cause is the fault itself.
    let warned_first = drive_faulting(&[(Some(5), 0x083, warning)], 27);
    let verdict = warned_first.verdict().unwrap();
    assert_eq!(verdict.first_cause, verdict.stop);
    assert_eq!(
        verdict.first_cause_text(),
        "the stop itself: no fault or error before it on its device"
    );
    // A later heartbeat timeout of another node is the stop.
    let frames: &[(Option<u64>, u32, &[u8])] = &[
        (Some(0), 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
        (Some(1), 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]),
        (Some(10), 0x083, sensor),
        (Some(26), 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
        (Some(27), 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x08, 0x02, 0, 0]),
        (Some(100), 0x705, &[0x05]),
        (Some(2000), 0x080, &[]),
    ];
    let lost = summarize(frames, Some(Duration::from_millis(300)));
    let verdict = lost.verdict().unwrap();
    assert_eq!(verdict.stop.kind, FindingKind::HeartbeatTimeout);
    assert_eq!(
        (verdict.stop.node.unwrap().get(), verdict.stop.line),
        (5, 6)
    );
    assert_eq!(
        verdict.first_cause, verdict.stop,
        "node 5 had nothing before"
    );
    let text = lost.to_string();
    assert!(
        text.starts_with(
            "verdict   stop: can0 node 5 no heartbeat for 1900 ms after line 6\n          \
             first cause: the stop itself"
        ),
        "{text}"
    );
    // Nothing stopped: no verdict, no record.
    let calm = summarize(
        &[(Some(0), 0x705, &[0x05]), (Some(100), 0x705, &[0x05])],
        None,
    );
    assert!(calm.verdict().is_none());
    assert_eq!(calm.records().count(), 2);
}

/// docs/summary.md#profiles: a finding says what its device's profile
/// reads in its EMCY — an AKD's axis and feedback, a Baumer encoder's
/// diagnostic source and its class —, and nothing for a generic node.
#[test]
fn findings_say_what_the_profile_reads() {
    let mut config = DecoderConfig::new()
        .node_profile(NodeId::new(3).unwrap(), Profile::Akd)
        .node_profile(NodeId::new(5).unwrap(), Profile::Baumer)
        .signals(false);
    config = config.heartbeat_timeout(Duration::from_millis(300));
    let frames: &[(u64, u32, &[u8])] = &[
        (0, 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
        (1, 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]),
        // AKD: 0x7305 on axis 2, feedback 3.
        (10, 0x083, &[0x05, 0x73, 0x01, 0x32, 0, 0, 0, 0]),
        (26, 0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
        (27, 0x583, &[0x4B, 0x41, 0x60, 0x00, 0x08, 0x02, 0, 0]),
        // Baumer: the battery warning, then temperature out of range.
        (30, 0x085, &[0x00, 0xFF, 0x00, 0, 0, 0x10, 0, 0]),
        (40, 0x085, &[0x00, 0x42, 0x09, 0, 0, 0, 0, 0]),
        // A generic node: the same bytes say nothing more.
        (50, 0x086, &[0x00, 0x42, 0x09, 0, 0, 0, 0, 0]),
    ];
    let mut summarizer = Summarizer::new(config);
    for (i, &(ms, id, data)) in frames.iter().enumerate() {
        let log = LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
            .with_iface(Iface::Name("can0"))
            .with_timestamp(Timestamp::from_duration(Duration::from_millis(ms)));
        summarizer.add(Position::Line(i as u64 + 1), &LogEvent::Frame(log));
    }
    let summary = summarizer.finish();
    let texts: Vec<String> = summary.findings().iter().map(ToString::to_string).collect();
    assert_eq!(
        texts,
        [
            "can0 node 3 first error: EMCY 0x7305 Incremental sensor 1 fault on axis 2, feedback 3 at line 3",
            "can0 node 3 went operation_enabled → fault at line 5, 17.0 ms after EMCY 0x7305 Incremental sensor 1 fault on axis 2, feedback 3 (line 3)",
            "can0 node 5 first warning: EMCY 0xFF00 Device specific (source: Battery monitoring warning, a warning) at line 6",
            "can0 node 5 first error: EMCY 0x4200 Device temperature (source: Temperature monitoring, an error) at line 7",
            "can0 node 6 first error: EMCY 0x4200 Device temperature at line 8",
        ]
    );
    let verdict = summary.verdict().unwrap();
    assert!(verdict
        .first_cause_text()
        .contains("fault on axis 2, feedback 3 at line 3"));
    let json = serde_json::to_string(&summary.findings()[2]).unwrap();
    assert!(json.contains(r#""text":"first warning: EMCY 0xFF00 Device specific (source: Battery monitoring warning, a warning) at line 6""#), "{json}");
}

/// Summarize a candump log with heartbeat timeouts checked; node 3 is an
/// AKD drive.
fn summarize_log(log: &str) -> Summary {
    let config = DecoderConfig::new()
        .node_profile(NodeId::new(3).unwrap(), Profile::Akd)
        .signals(false)
        .heartbeat_timeout(Duration::from_millis(300));
    let mut summarizer = Summarizer::new(config);
    for (i, line) in log.lines().enumerate() {
        let frame = crate::logs::candump::parse_line(line.trim().as_bytes())
            .unwrap()
            .unwrap();
        summarizer.add(Position::Line(i as u64 + 1), &LogEvent::Frame(frame));
    }
    summarizer.finish()
}

/// docs/summary.md#causes: a bus-off or error-passive frame at most a
/// second before a heartbeat was due, and not after, causes its loss; the
/// loss is the stop and the bus-off its first cause.
#[test]
fn a_bus_error_causes_the_heartbeat_timeouts_after_it() {
    let log = "(10.000000) can0 705#05
               (10.000100) can0 706#05
               (10.100000) can0 705#05
               (10.100100) can0 706#05
               (10.150000) can0 20000040#0000000000000000
               (11.500000) can0 705#05
               (11.500100) can0 706#05";
    let summary = summarize_log(log);
    let texts: Vec<String> = summary.findings().iter().map(ToString::to_string).collect();
    assert_eq!(
        texts,
        [
            "can0 node 5 no heartbeat for 1400 ms after line 3, caused by bus-off at line 5",
            "can0 node 6 no heartbeat for 1400 ms after line 4, caused by bus-off at line 5",
            "bus can0 bus-off at line 5",
        ]
    );
    let gap = match &summary.nodes[0].heartbeat.timeouts {
        Timeouts::Checked(gaps) => *gaps.head().first().unwrap(),
        other => panic!("{other:?}"),
    };
    assert_eq!(gap.cause.map(|c| (c.line, c.bus_off)), Some((5, true)));
    assert_eq!(
        gap.due,
        Timestamp::from_duration(Duration::from_millis(10_400))
    );
    let verdict = summary.verdict().unwrap();
    assert_eq!(
        (verdict.stop.kind, verdict.stop.node.map(NodeId::get)),
        (FindingKind::HeartbeatTimeout, Some(6))
    );
    assert_eq!(
        (verdict.first_cause.kind, verdict.first_cause.line),
        (FindingKind::BusOff, 5)
    );
    assert_eq!(verdict.first_cause_text(), "bus can0 bus-off at line 5");

    // Error-passive links too (a warning, so it is no first cause).
    let passive = log.replace("20000040#0000000000000000", "20000004#0010000000000000");
    let summary = summarize_log(&passive);
    let first = &summary.findings()[0];
    assert!(
        first.text().ends_with("caused by error-passive at line 5"),
        "{}",
        first.text()
    );
    let verdict = summary.verdict().unwrap();
    assert_eq!(verdict.first_cause, verdict.stop);

    // The window: a bus-off more than a second before the heartbeat was
    // due, or after it, causes nothing.
    for (at, linked) in [
        ("10.399999", true),
        ("10.400000", true),
        ("10.400001", false),
        ("9.399999", false),
        ("9.400000", true),
    ] {
        let mut lines: Vec<String> = log.lines().map(|l| l.trim().to_owned()).collect();
        lines.retain(|l| !l.contains("2000004"));
        let error = format!("({at}) can0 20000040#0000000000000000");
        let place = lines
            .iter()
            .position(|l| {
                l[1..l.find(')').unwrap()].parse::<f64>().unwrap() > at.parse::<f64>().unwrap()
            })
            .unwrap_or(lines.len());
        lines.insert(place, error);
        let summary = summarize_log(&lines.join("\n"));
        let Timeouts::Checked(gaps) = &summary.nodes[0].heartbeat.timeouts else {
            panic!()
        };
        assert_eq!(
            gaps.iter().any(|g| g.cause.is_some()),
            linked,
            "bus-off at {at}: {gaps:?}"
        );
    }
}

/// docs/summary.md#causes: a heartbeat timeout before another node's EMCY
/// 0x8130 (within the gap, at most a second after the heartbeat was due)
/// causes it; a drive's fault after that EMCY traces back to the lost
/// node.
#[test]
fn a_lost_heartbeat_causes_another_nodes_emcy_8130() {
    let log = "(0.000000) can0 603#4041600000000000
               (0.001000) can0 583#4B41600037020000
               (0.010000) can0 705#05
               (0.110000) can0 705#05
               (0.600000) can0 083#3081110100000000
               (0.615000) can0 603#4041600000000000
               (0.616000) can0 583#4B41600008020000
               (2.000000) can0 705#05";
    let summary = summarize_log(log);
    let texts: Vec<String> = summary.findings().iter().map(ToString::to_string).collect();
    assert_eq!(
        texts,
        [
            "can0 node 5 no heartbeat for 1890 ms after line 4",
            "can0 node 3 first error: EMCY 0x8130 Life guard error or heartbeat error on axis 1 at line 5, caused by node 5's heartbeat timeout after line 4",
            "can0 node 3 went operation_enabled → fault at line 7, 16.0 ms after EMCY 0x8130 Life guard error or heartbeat error on axis 1 (line 5)",
        ]
    );
    let (node, gap) = summary
        .lost_before(
            &summary.nodes[0].bus,
            NodeId::new(3).unwrap(),
            &summary.nodes[0].first_error.unwrap(),
        )
        .unwrap();
    assert_eq!((node.get(), gap.after_line), (5, 4));
    let verdict = summary.verdict().unwrap();
    assert_eq!(verdict.stop.kind, FindingKind::Cia402Fault);
    assert_eq!(
        (
            verdict.first_cause.kind,
            verdict.first_cause.node.map(NodeId::get)
        ),
        (FindingKind::HeartbeatTimeout, Some(5))
    );
    assert!(verdict
        .to_string()
        .contains("first cause: can0 node 5 no heartbeat for 1890 ms after line 4"));

    // The window: the EMCY 1.3 s after the heartbeat was due (0.41 s) is
    // not linked; before the heartbeat before the gap neither.
    for (at, linked) in [("1.410000", true), ("1.410001", false), ("0.100000", false)] {
        let moved = log.replace("(0.600000) can0 083", &format!("({at}) can0 083"));
        let mut lines: Vec<&str> = moved.lines().map(str::trim).collect();
        lines.sort_by(|a, b| {
            let t = |l: &str| l[1..l.find(')').unwrap()].parse::<f64>().unwrap();
            t(a).total_cmp(&t(b))
        });
        let summary = summarize_log(&lines.join("\n"));
        let three = summary
            .node(&summary.nodes[0].bus, NodeId::new(3).unwrap())
            .unwrap();
        let found = summary.lost_before(&three.bus, three.node, &three.first_error.unwrap());
        assert_eq!(found.is_some(), linked, "EMCY at {at}");
    }
}
