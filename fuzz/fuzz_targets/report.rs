//! The post-mortem page (docs/report.md) fed arbitrary CANopen traffic: the
//! [`Recorder`] beside the summary it holds, then [`Report::write_html`].
//!
//! Input: one flags byte (bit 0: the frames carry no timestamps, the page is
//! drawn by line; bit 1: heartbeats are checked against a 50 ms consumer
//! time), then the `decoder` target's records of `[header, id, bytes…]`
//! (`motionwire_fuzz::traffic`, fuzz/src/lib.rs).
//!
//! Invariants:
//! - nothing panics, not the recorder and not the page;
//! - the page is one whole document: UTF-8, from `<!DOCTYPE html>` to
//!   `</html>`, with the embedded summary records, which parse as JSON and
//!   are as many as the summary's nodes and buses;
//! - the timeline counts what the summary counts (docs/report.md#marks):
//!   each node row's error and reset EMCY marks add up to its `emcy`, its
//!   boot-up marks to its boot-ups, its toggle-error marks to its toggle
//!   errors, its SDO abort marks to its aborts, however the marks cluster;
//! - a recording without timestamps is drawn by line.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{Iface, LogEvent, LogFrame, Timestamp};
use motionwire::canopen::NodeId;
use motionwire::decoder::DecoderConfig;
use motionwire::logs::Position;
use motionwire::profiles::Profile;
use motionwire::report::{MarkKind, Recorder, Report};
use motionwire_fuzz::{traffic, TrafficFrame};

const SUMMARY_OPEN: &str = r#"<script type="application/json" id="motionwire-summary">"#;

fuzz_target!(|input: &[u8]| {
    let Some((&flags, rest)) = input.split_first() else {
        return;
    };
    let untimed = flags & 1 != 0;
    let mut config = DecoderConfig::new()
        .node_profile(NodeId::new(3).unwrap(), Profile::Akd)
        .sdo_data_cap(64);
    if flags & 2 != 0 {
        config = config.heartbeat_timeout(core::time::Duration::from_millis(50));
    }
    let mut recorder = Recorder::new(config);
    for TrafficFrame {
        line,
        ms,
        frame,
        iface,
        ..
    } in traffic(rest)
    {
        let mut log = LogFrame::new(frame).with_iface(Iface::Name(iface));
        if !untimed {
            log = log.with_timestamp(Timestamp::from_duration(core::time::Duration::from_millis(
                ms,
            )));
        }
        recorder.add(Position::Line(line), &LogEvent::Frame(log));
    }
    let recording = recorder.finish();
    if untimed {
        assert!(!recording.timeline.is_timed(), "drawn by line");
    }
    for node in &recording.summary.nodes {
        let marks = |kind| {
            recording
                .timeline
                .mark_count(&node.bus, Some(node.node), kind)
        };
        assert_eq!(
            marks(MarkKind::Emcy) + marks(MarkKind::EmcyReset),
            node.emcy,
            "EMCY marks of node {}",
            node.node
        );
        assert_eq!(marks(MarkKind::EmcyReset), node.resets);
        assert_eq!(marks(MarkKind::BootUp), node.heartbeat.boot_ups.count());
        assert_eq!(
            marks(MarkKind::ToggleError),
            node.guarding.toggle_errors.count()
        );
        assert_eq!(marks(MarkKind::SdoAbort), node.sdo.aborts.count());
    }
    // Every record of the summary: the verdict when something stopped,
    // the nodes, the buses (docs/summary.md#verdict).
    let records = recording.summary.records().count();
    assert_eq!(
        records,
        usize::from(recording.summary.verdict().is_some())
            + recording.summary.nodes.len()
            + recording.summary.buses.len()
    );

    let mut report = Report::new();
    report.add_recording(recording);
    let mut page = Vec::new();
    report.write_html(&mut page).expect("writing to a Vec");
    let page = String::from_utf8(page).expect("the page is UTF-8");
    assert!(page.starts_with("<!DOCTYPE html>"), "a whole document");
    assert!(page.ends_with("</html>\n"), "a whole document");
    let start = page.find(SUMMARY_OPEN).expect("the embedded summary") + SUMMARY_OPEN.len();
    let end = start + page[start..].find("</script>").expect("its end");
    let embedded: serde_json::Value =
        serde_json::from_str(&page[start..end]).expect("the embedded records are JSON");
    assert_eq!(embedded.as_array().map(Vec::len), Some(records));
});
