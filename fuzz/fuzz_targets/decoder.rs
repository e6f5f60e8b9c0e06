//! The decoder session and the post-mortem (docs/output.md, docs/summary.md)
//! fed arbitrary frames: a stream of CANopen traffic on two buses, with SDO
//! transfers that teach PDO mappings, drives' statuswords and EMCY storms.
//!
//! Input: records of `[header, id, bytes…]`, read by
//! `motionwire_fuzz::traffic` (fuzz/src/lib.rs): the data length, the bus,
//! a remote frame and the time step in the header; the function and the
//! node in `id`.
//!
//! Invariants:
//! - nothing panics: not the decoder, not the summary, not their renderings;
//! - every JSON record the decoder writes is one valid JSON object whose
//!   `line`, `id` and `kind` are the frame's;
//! - every SDO transfer that starts ends exactly once: at a frame, or left
//!   open at the end of the input (`Decoder::finish`); a transfer's data
//!   never exceeds the cap;
//! - a PDO's signals never lie beyond its payload;
//! - the summary counts every frame once, and its JSON is what the
//!   records say.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{Iface, LogEvent, LogFrame, Timestamp};
use motionwire::canopen::NodeId;
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::logs::Position;
use motionwire::profiles::Profile;
use motionwire::summary::Summarizer;
use motionwire_fuzz::{traffic, TrafficFrame};

const CAP: usize = 64;

fuzz_target!(|input: &[u8]| {
    let drive = NodeId::new(3).unwrap();
    let config = DecoderConfig::new()
        .node_profile(drive, Profile::Akd)
        .node_profile(NodeId::new(5).unwrap(), Profile::Baumer)
        .sdo_data_cap(CAP);
    let mut decoder = Decoder::new(config.clone());
    let config = config
        .signals(false)
        .heartbeat_timeout(core::time::Duration::from_millis(50));
    // The summary's two ways in agree: frames read where the summary needs
    // them, and read whole.
    let mut summarizer = Summarizer::new(config.clone());
    let mut whole = Summarizer::new(config);
    let (mut started, mut ended) = (0u64, 0u64);
    let mut frames = 0u64;
    for TrafficFrame {
        line,
        ms,
        raw,
        frame,
        iface,
    } in traffic(input)
    {
        let log = LogFrame::new(frame)
            .with_timestamp(Timestamp::from_duration(core::time::Duration::from_millis(
                ms,
            )))
            .with_iface(Iface::Name(iface));
        frames += 1;

        let decoded = decoder.decode(Position::Line(line), &log);
        let json = decoded.to_json();
        let value: serde_json::Value = serde_json::from_str(&json).expect("a valid JSON record");
        assert_eq!(value["line"], line);
        assert_eq!(value["id"], raw);
        assert_eq!(value["kind"], decoded.kind.name());
        let _ = decoded.message();
        if let Some(step) = &decoded.sdo {
            let _ = step.to_string();
            if step.started {
                started += 1;
            }
            if let Some(end) = &step.ended {
                ended += 1;
                assert!(end.data.len() <= CAP);
                assert!(end.data.len() <= end.transfer.bytes as usize);
            }
        }
        if let Some(pdo) = &decoded.pdo {
            let _ = pdo.to_string();
            for signal in pdo.signals.iter().flatten() {
                let end = usize::from(signal.offset) + usize::from(signal.entry.bits());
                assert!(
                    end <= 8 * log.frame.data().len(),
                    "a signal beyond the payload"
                );
            }
        }
        if let Some(reading) = &decoded.cia402 {
            let _ = reading.to_string();
        }

        let event = LogEvent::Frame(log);
        summarizer.add(Position::Line(line), &event);
        let _ = whole.add_with(Position::Line(line), &event, |_| {});
    }
    let open = decoder.finish();
    assert_eq!(
        started,
        ended + open.len() as u64,
        "every transfer ends once"
    );

    let summary = summarizer.finish();
    assert_eq!(summary, whole.finish(), "both ways in give one summary");
    let counted: u64 = summary.buses.iter().map(|b| b.frames).sum();
    assert_eq!(counted, frames);
    let _ = summary.to_string();
    let records: serde_json::Value =
        serde_json::to_value(&summary).expect("the summary serializes");
    assert_eq!(
        records.as_array().map(Vec::len),
        Some(usize::from(summary.verdict().is_some()) + summary.nodes.len() + summary.buses.len())
    );
});
