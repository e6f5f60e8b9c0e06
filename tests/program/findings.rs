//! What went wrong, from the library (docs/summary.md#findings): the
//! findings of a recording read with the library alone are, one for one,
//! the items of the page's "What went wrong" that `motionwire report`
//! writes (docs/report.md#page).

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use motionwire::canopen::NodeId;
use motionwire::decoder::DecoderConfig;
use motionwire::logs::ReadLog;
use motionwire::profiles::{NodeProfiles, Profile};
use motionwire::report::{Recorder, Recording};
use motionwire::summary::{Finding, FindingKind, Severity};

fn repo(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The sample read as `motionwire report --profile 3=akd,5=baumer
/// --heartbeat-ms 300 samples/machine.log` reads it.
fn sample_recording() -> Recording {
    let mut profiles = NodeProfiles::default();
    profiles.set(NodeId::new(3).unwrap(), Profile::Akd);
    profiles.set(NodeId::new(5).unwrap(), Profile::Baumer);
    let mut recorder = Recorder::new(
        DecoderConfig::new()
            .profiles_from(profiles)
            .heartbeat_timeout(Duration::from_millis(300)),
    );
    let mut log = motionwire::logs::open(repo("samples/machine.log")).unwrap();
    while let Some(record) = log.next_event() {
        let record = record.unwrap();
        recorder.add(record.position, &record.event);
    }
    recorder.finish()
}

/// The page's findings: each `<li>` of "What went wrong" with a
/// `data-line` (not the groups' own), as its
/// `data-line`, `data-iface`, `data-node` and text without markup.
fn page_findings(html: &str) -> Vec<(u64, String, Option<u8>, String)> {
    let start = html.find("<section id=\"wrong\">").unwrap();
    let end = start + html[start..].find("</section>").unwrap();
    let attr = |li: &str, name: &str| -> Option<String> {
        let at = li.find(&format!("{name}=\""))? + name.len() + 2;
        Some(li[at..at + li[at..].find('"')?].to_owned())
    };
    html[start..end]
        .split("<li ")
        .skip(1)
        .filter(|li| li.starts_with("data-line="))
        .map(|li| {
            let li = &li[..li.find("</li>").unwrap()];
            let text = li[li.find('>').unwrap() + 1..]
                .replace("<b>", "")
                .replace("</b>", "")
                .replace("&amp;", "&")
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&quot;", "\"")
                .replace("&#39;", "'");
            (
                attr(li, "data-line").unwrap().parse().unwrap(),
                attr(li, "data-iface").unwrap(),
                attr(li, "data-node").map(|n| n.parse().unwrap()),
                text,
            )
        })
        .collect()
}

#[test]
fn the_samples_findings_are_the_pages() {
    let recording = sample_recording();
    let findings: Vec<Finding> = recording.findings();
    assert!(findings.len() >= 5, "{findings:#?}");
    // In time order, the library's.
    assert!(findings
        .windows(2)
        .all(|w| (w[0].timestamp, w[0].line) <= (w[1].timestamp, w[1].line)));
    // The page groups them by device and kind (docs/report.md#groups):
    // the same findings, each once, in its own order.

    let dir = std::env::temp_dir().join(format!("motionwire-findings-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("sample.html");
    let run = Command::new(env!("CARGO_BIN_EXE_motionwire"))
        .args([
            "report",
            "--profile",
            "3=akd,5=baumer",
            "--heartbeat-ms",
            "300",
        ])
        .arg(repo("samples/machine.log"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut page = page_findings(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(page.len(), findings.len(), "{page:#?}");
    for f in &findings {
        // The page adds when it was, or that the timeline has every one.
        let at = page
            .iter()
            .position(|(line, iface, node, text)| {
                *line == f.line
                    && *iface == f.bus.to_string()
                    && *node == f.node.map(NodeId::get)
                    && text.starts_with(&f.to_string())
            })
            .unwrap_or_else(|| panic!("{f} not on the page: {page:#?}"));
        page.remove(at);
        assert!(f.timestamp.is_some(), "{f}: the sample has timestamps");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_finding_serializes_with_its_text() {
    let recording = sample_recording();
    let findings = recording.findings();
    let first = findings
        .iter()
        .find(|f| f.kind == FindingKind::FirstError)
        .unwrap();
    let json: serde_json::Value = serde_json::to_value(first).unwrap();
    assert_eq!(json["kind"], "first_error");
    assert_eq!(json["iface"], first.bus.to_string());
    assert_eq!(json["node"], first.node.unwrap().get());
    assert_eq!(json["line"], first.line);
    assert_eq!(json["text"], first.text());
    assert!(json["ts"].is_number());
}

/// docs/summary.md#verdict on the sample read with `--profile
/// 3=akd,5=baumer --heartbeat-ms 300`: the stop is drive 3's last fault,
/// after the EMCY on its feedback 2; the first cause its first error; the
/// Baumer encoder's battery EMCY is a warning, not an error.
#[test]
fn the_samples_verdict() {
    let recording = sample_recording();
    let verdict = recording.summary.verdict().expect("the sample stops");
    let stop = &verdict.stop;
    assert_eq!(
        (
            stop.kind,
            stop.node.map(NodeId::get),
            stop.line,
            stop.severity
        ),
        (FindingKind::Cia402Fault, Some(3), 3239, Severity::Fault)
    );
    let cause = verdict.cause.expect("the EMCY 16.1 ms before");
    assert_eq!((cause.line, cause.code.get()), (3231, 0x7305));
    assert_eq!(
        verdict.stop_text(),
        "can0 node 3 went operation_enabled → fault at line 3239 (+8.820 s), 16.1 ms after \
         EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2 (line 3231)"
    );
    let first = &verdict.first_cause;
    assert_eq!(
        (
            first.kind,
            first.node.map(NodeId::get),
            first.line,
            first.severity
        ),
        (FindingKind::FirstError, Some(3), 613, Severity::Error)
    );

    let five: Vec<(FindingKind, u64, Severity)> = recording
        .findings()
        .iter()
        .filter(|f| f.node.map(NodeId::get) == Some(5))
        .filter(|f| matches!(f.kind, FindingKind::FirstError | FindingKind::FirstWarning))
        .map(|f| (f.kind, f.line, f.severity))
        .collect();
    assert_eq!(
        five,
        [
            (FindingKind::FirstWarning, 393, Severity::Warning),
            (FindingKind::FirstError, 972, Severity::Error),
        ]
    );
}
