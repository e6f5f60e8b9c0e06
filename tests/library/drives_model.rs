//! What motionwire makes of the generated capture of a servo and two CiA
//! 402 drives (tests/common/ecat_drives.rs) against what the models did
//! (the model record): cycle for cycle from the session's process data,
//! and in the summary — on the committed 1 000-cycle fixture and on a
//! 100 000-cycle capture written for the test.

use crate::ecat_drives;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use motionwire::can::LogEvent;
use motionwire::decoder::ethercat::{ServoSlaves, Session};
use motionwire::decoder::DecoderConfig;
use motionwire::logs::{self, ReadLog};
use motionwire::servo::{ActualPosition, ServoErrorWord, ServoFault};
use motionwire::summary::{ServoChange, Summarizer, Summary};
use serde_json::Value;

use ecat_drives::{DRIVE_A, DRIVE_B, SERVO};

/// One thing a model did, as motionwire should tell it: the packet, the
/// slave and what.
type Event = (u64, u16, String);

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ethercat")
        .join(name)
}

/// The config that reads the servo.
fn config() -> DecoderConfig {
    DecoderConfig::new().servos(ServoSlaves {
        auto: false,
        stations: vec![(SERVO, None)],
    })
}

/// The model record's lines.
fn model(path: &Path) -> Vec<Value> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

/// The model's servo and drive events in the words of [`Event`]:
/// handshake phases, faults of the error word (its summary bit
/// ServoErrors aside: the model names the faults it injected), ServoRDY,
/// CiA 402 states.
fn model_events(model: &[Value]) -> BTreeSet<Event> {
    let mut events = BTreeSet::new();
    for r in model {
        let packet = r["packet"].as_u64().unwrap();
        let slave = r["slave"].as_u64().map(|s| s as u16).unwrap_or(0);
        let what = match r["kind"].as_str().unwrap() {
            "servo_enable" => format!("enable {}", r["to"].as_str().unwrap()),
            "error_clear" => format!("error_clear {}", r["to"].as_str().unwrap()),
            "zero_pulse" => format!("zero_pulse {}", r["to"].as_str().unwrap()),
            "sew_set" => format!("set {}", r["fault"].as_str().unwrap()),
            "sew_cleared" => format!("cleared {}", r["fault"].as_str().unwrap()),
            "servo_rdy" => format!("ready {}", r["value"]),
            "cia402_state" => format!("cia402 {}", r["to"].as_str().unwrap()),
            _ => continue,
        };
        events.insert((packet, slave, what));
    }
    events
}

/// Read a capture through the library's session, every packet, and tell
/// every change of each servo handshake, fault, ServoRDY and CiA 402
/// state; also each servo ActPos by packet.
fn session_events(path: &Path) -> (BTreeSet<Event>, Vec<(u64, i32)>) {
    let mut reader = logs::open(path).unwrap();
    let mut session = Session::with_config(&config());
    let mut events = BTreeSet::new();
    let mut positions = Vec::new();
    let mut last_servo: Option<motionwire::decoder::ethercat::ServoReading> = None;
    let mut errors = ServoErrorWord::empty();
    let mut ready = None;
    let mut states = [None; 2];
    while let Some(record) = reader.next_event() {
        let record = record.unwrap();
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        let Ok(packet) = session.read(record.position, &packet) else {
            continue;
        };
        let number = record.position.number();
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = datagram.unwrap();
            session.meanings(&packet, at, &datagram, |_| {});
            session.process_data(&packet, at, &datagram, |data| {
                let station = data.slave.and_then(|s| s.station).unwrap();
                if let Some(s) = data.servo {
                    let before = last_servo;
                    let mut say = |what: String| {
                        events.insert((number, station, what));
                    };
                    if before.map(|b| b.enable) != Some(s.enable) {
                        say(format!("enable {}", s.enable));
                    }
                    if before.map_or("idle".into(), |b| b.error_clear.to_string())
                        != s.error_clear.to_string()
                    {
                        say(format!("error_clear {}", s.error_clear));
                    }
                    if before.map_or("idle".into(), |b| b.zero_pulse.to_string())
                        != s.zero_pulse.to_string()
                    {
                        say(format!("zero_pulse {}", s.zero_pulse));
                    }
                    if let Some(feedback) = s.feedback {
                        for fault in feedback.errors.faults() {
                            if !errors.contains(fault.flag()) && fault != ServoFault::ServoErrors {
                                say(format!("set {}", fault.name()));
                            }
                        }
                        for fault in errors.faults() {
                            if !feedback.errors.contains(fault.flag())
                                && fault != ServoFault::ServoErrors
                            {
                                say(format!("cleared {}", fault.name()));
                            }
                        }
                        errors = feedback.errors;
                        if ready != s.ready {
                            say(format!("ready {}", s.ready.unwrap()));
                            ready = s.ready;
                        }
                        let position = match feedback.actual_position() {
                            ActualPosition::Incremental { position, .. } => position,
                            ActualPosition::Absolute(p) => p as i32,
                        };
                        positions.push((number, position));
                    }
                    last_servo = Some(s);
                }
                if let Some(state) = data.cia402.and_then(|c| c.state) {
                    let drive = usize::from(station - DRIVE_A);
                    if states[drive] != Some(state) {
                        states[drive] = Some(state);
                        events.insert((number, station, format!("cia402 {}", state.name())));
                    }
                }
            });
        }
    }
    (events, positions)
}

/// Summarise a capture with the servo read.
fn summary(path: &Path) -> Summary {
    let mut reader = logs::open(path).unwrap();
    let mut summarizer = Summarizer::new(config().signals(false));
    while let Some(record) = reader.next_event() {
        let record = record.unwrap();
        summarizer.add(record.position, &record.event);
    }
    summarizer.finish()
}

/// The session tells every change the models made, at the packet of the
/// cycle, and the servo's ActPos where the model wrote it.
fn check_cycle_for_cycle(capture: &Path, model: &[Value]) {
    let (found, positions) = session_events(capture);
    let expected = model_events(model);
    let missing: Vec<_> = expected.difference(&found).collect();
    let extra: Vec<_> = found.difference(&expected).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "{}: missing {missing:?}\nextra {extra:?}",
        capture.display()
    );
    // A cycle whose returned copy is lost, or whose working counter is
    // short, has no confirmed feedback to read ActPos from.
    let unread: BTreeSet<u64> = model
        .iter()
        .filter(|r| r["kind"] == "lost_frame" || r["kind"] == "short_wkc")
        .map(|r| r["cycle"].as_u64().unwrap())
        .collect();
    let mut checked = 0;
    for r in model.iter().filter(|r| r["kind"] == "act_pos") {
        if unread.contains(&r["cycle"].as_u64().unwrap()) {
            continue;
        }
        let packet = r["packet"].as_u64().unwrap();
        let (_, position) = positions
            .iter()
            .find(|(p, _)| *p == packet)
            .unwrap_or_else(|| panic!("no feedback at packet {packet}"));
        assert_eq!(i64::from(*position), r["value"].as_i64().unwrap());
        checked += 1;
    }
    assert!(checked >= 1);
}

/// The summary says the same: the servo timeline's and the drives' kept
/// events are the model's, their counts match, the fault injected with
/// its E-code, the unanswered enable, the lost frame, the short working
/// counter and the emergencies at their packets.
fn check_summary(capture: &Path, model: &[Value]) {
    let summary = summary(capture);
    let expected = model_events(model);
    let ethercat = &summary.ethercat;
    assert_eq!(ethercat.ports[0].counts.lost, 1);
    let slave = |station| {
        ethercat
            .slaves
            .iter()
            .find(|s| s.station == Some(station))
            .unwrap()
    };
    let servo = slave(SERVO).servo.as_ref().expect("the servo's timeline");
    let mut servo_events = 0;
    for event in servo.events.iter() {
        let what = match event.change {
            ServoChange::Enable { to, .. } => format!("enable {to}"),
            ServoChange::ErrorClear(phase) => format!("error_clear {phase}"),
            ServoChange::ZeroPulse { phase, .. } => format!("zero_pulse {phase}"),
            ServoChange::FaultSet(ServoFault::ServoErrors)
            | ServoChange::FaultCleared(ServoFault::ServoErrors) => continue,
            ServoChange::FaultSet(fault) => format!("set {}", fault.name()),
            ServoChange::FaultCleared(fault) => format!("cleared {}", fault.name()),
            ServoChange::Ready(ready) => format!("ready {ready}"),
        };
        assert!(
            expected.contains(&(event.packet, SERVO, what.clone())),
            "{what} at {}",
            event.packet
        );
        servo_events += 1;
    }
    assert!(servo_events >= 10);
    let model_servo = expected.iter().filter(|e| e.1 == SERVO).count() as u64;
    let summary_bit = servo
        .events
        .iter()
        .filter(|e| {
            matches!(
                e.change,
                ServoChange::FaultSet(ServoFault::ServoErrors)
                    | ServoChange::FaultCleared(ServoFault::ServoErrors)
            )
        })
        .count() as u64;
    // Every ServoErrors change is kept when the list keeps everything; the
    // count compares when it does.
    if servo.events.omitted() == 0 {
        assert_eq!(servo.events.count() - summary_bit, model_servo);
    }
    let timeouts = model
        .iter()
        .filter(|r| r["kind"] == "enable_timeout")
        .count() as u64;
    assert_eq!(servo.enable_unanswered, timeouts);
    // The counts by kind are the model's, listed or not.
    let of = |kind: &str, to: Option<&str>| {
        model
            .iter()
            .filter(|r| {
                r["slave"] == u64::from(SERVO)
                    && r["kind"] == kind
                    && to.map_or(true, |to| r["to"] == to)
            })
            .count() as u64
    };
    assert_eq!(servo.enable_change_count, of("servo_enable", None));
    assert_eq!(
        servo.error_clear_count,
        of("error_clear", Some("requested"))
    );
    assert_eq!(servo.zero_pulse_count, of("zero_pulse", Some("requested")));
    let rdy_low = model
        .iter()
        .filter(|r| {
            r["slave"] == u64::from(SERVO) && r["kind"] == "servo_rdy" && r["value"] == false
        })
        .count() as u64;
    assert_eq!(servo.not_ready_count, rdy_low);
    // Each fault the model set, and the ServoErrors summary bit with it.
    assert_eq!(servo.fault_set_count, 2 * of("sew_set", None));
    assert!(servo.faults_seen.contains(ServoErrorWord::FOLLOWER_ERR));
    assert!(servo.faults_seen.contains(ServoErrorWord::ENCODER_ERR));
    assert_eq!(servo.unconfirmed, 1);
    let last_act_pos = model.iter().rev().find(|r| r["kind"] == "act_pos").unwrap();
    if let Some(ActualPosition::Incremental { position, .. }) = servo.last_position {
        assert_eq!(i64::from(position), last_act_pos["value"].as_i64().unwrap());
    } else {
        panic!("an incremental position");
    }
    for station in [DRIVE_A, DRIVE_B] {
        let drive = slave(station);
        let timeline = drive.cia402.as_ref().expect("a CiA 402 timeline");
        let model_states: Vec<_> = expected
            .iter()
            .filter(|e| e.1 == station && e.2.starts_with("cia402"))
            .collect();
        assert_eq!(timeline.transitions.count(), model_states.len() as u64);
        for t in timeline.transitions.iter() {
            let what = format!("cia402 {}", t.to.name());
            assert!(expected.contains(&(t.line, station, what)));
        }
        let faults = timeline.faults.as_ref().unwrap();
        assert_eq!(faults.count(), u64::from(station == DRIVE_A));
    }
    let emcys: Vec<u64> = slave(DRIVE_A)
        .emergencies
        .iter()
        .map(|e| e.packet)
        .collect();
    let model_emcys: Vec<u64> = model
        .iter()
        .filter(|r| r["kind"] == "emcy")
        .map(|r| r["mailbox_packet"].as_u64().unwrap())
        .collect();
    assert_eq!(emcys, model_emcys);
    let short = model.iter().find(|r| r["kind"] == "short_wkc").unwrap();
    for station in [SERVO, DRIVE_A, DRIVE_B] {
        let (packet, wkc, expected_wkc) = slave(station).first_unconfirmed.unwrap();
        assert_eq!(packet, short["packet"].as_u64().unwrap());
        assert_eq!(u64::from(wkc), short["wkc"].as_u64().unwrap());
        assert_eq!(expected_wkc.map(u64::from), short["expected"].as_u64());
    }
}

#[test]
fn the_fixture_says_what_the_models_did() {
    let model = model(&fixture("drives.model.jsonl"));
    check_cycle_for_cycle(&fixture("drives.pcapng"), &model);
    check_summary(&fixture("drives.pcapng"), &model);
}

#[test]
fn a_hundred_thousand_cycles_say_what_the_models_did() {
    let dir = std::env::temp_dir().join(format!("motionwire-drives-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (capture, model_path, eni) = (
        dir.join("drives.pcapng"),
        dir.join("drives.model.jsonl"),
        dir.join("drives.eni.xml"),
    );
    ecat_drives::write_files(100_000, &capture, &model_path, &eni).unwrap();
    let model = model(&model_path);
    check_cycle_for_cycle(&capture, &model);
    check_summary(&capture, &model);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// What the session cuts of every cycle: packet, slave, images, signal
/// values, CiA 402 reading.
type Cut = (
    u64,
    Option<u16>,
    Option<Vec<u8>>,
    Option<Vec<u8>>,
    Vec<String>,
    String,
);

/// Read `path` from packet `from` on with `session`, and say every cut.
fn cuts(path: &Path, mut session: Session, from: u64) -> Vec<Cut> {
    let mut reader = logs::open(path).unwrap();
    let mut out = Vec::new();
    while let Some(record) = reader.next_event() {
        let record = record.unwrap();
        if record.position.number() < from {
            continue;
        }
        let LogEvent::Ethercat(packet) = record.event else {
            continue;
        };
        let Ok(packet) = session.read(record.position, &packet) else {
            continue;
        };
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = datagram.unwrap();
            session.meanings(&packet, at, &datagram, |_| {});
            session.process_data(&packet, at, &datagram, |data| {
                let mut values = Vec::new();
                data.for_each_signal(|_, _, signal| {
                    values.push(format!("{:?}", signal.map(|s| s.value)))
                });
                out.push((
                    record.position.number(),
                    data.slave.and_then(|s| s.station),
                    data.outputs.map(<[u8]>::to_vec),
                    data.inputs.map(<[u8]>::to_vec),
                    values,
                    format!("{:?}", data.cia402),
                ));
            });
        }
    }
    out
}

/// A capture cut after its start-up, read with the master's ENI, gives
/// every slave's images, signals and CiA 402 readings as the whole
/// capture does — and the servo's signals, which only the ENI describes:
/// the ENI's layout is the start-up's (both ENI files that
/// describe the generated capture: the generator's, with PDO elements,
/// and the reader's fixture, whose third slave has its PDOs in CoE
/// InitCmds only).
#[test]
fn the_eni_gives_the_layout_the_start_up_gives() {
    let capture = fixture("drives.pcapng");
    // The first cycle's sent copy (tests/data/ethercat/README.md).
    let first_cycle = 213;
    let whole: Vec<Cut> = cuts(&capture, Session::with_config(&config()), 1)
        .into_iter()
        .filter(|c| c.0 >= first_cycle)
        .collect();
    assert!(whole.len() > 2_900);
    assert!(whole.iter().any(|c| c.4.len() == 6), "the drives' signals");
    for eni in ["drives.eni.xml", "eni/drives.eni.xml"] {
        let text = std::fs::read_to_string(fixture(eni)).unwrap();
        let slaves = motionwire::decoder::ethercat::parse_eni(&text).unwrap();
        assert_eq!(slaves.len(), 3, "{eni}");
        let session = Session::with_config(&config().ethercat_slaves(slaves));
        let late = cuts(&capture, session, first_cycle);
        assert_eq!(late.len(), whole.len(), "{eni}");
        for (a, b) in late.iter().zip(&whole) {
            if a.1 == Some(SERVO) {
                // The servo has no CoE: its PDOs are in the ENI alone,
                // which names its 10 and 40 bytes; the start-up gives
                // bytes only.
                assert_eq!((&a.0, &a.2, &a.3, &a.5), (&b.0, &b.2, &b.3, &b.5), "{eni}");
                assert!(b.4.is_empty(), "{eni}");
                // The generator's ENI describes the servo's PDOs; the
                // reader's fixture leaves them out.
                assert_eq!(a.4.is_empty(), eni != "drives.eni.xml", "{eni}");
            } else {
                assert_eq!(a, b, "{eni}");
            }
        }
    }
}
