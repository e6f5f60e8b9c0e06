//! `motionwire report`: the page's contract (docs/report.md#contract) read
//! from the HTML the program writes — rows, marks and bands agree with the
//! summary, the embedded records are exactly `decode --summary --json`'s —
//! and the sample's faults where the summary puts them.

use std::io::Write;

#[path = "../common/ecat_drives.rs"]
mod ecat_drives;

use crate::report_common::{
    check_counts, check_ethercat, parse, repo, run, scratch, summary_records, Element, Page,
};
use serde_json::Value;

const SAMPLE_ARGS: [&str; 4] = ["--profile", "3=akd,5=baumer", "--heartbeat-ms", "300"];

fn sample_page(dir: &std::path::Path) -> Page {
    let out = dir.join("sample.html");
    let sample = repo("samples/machine.log");
    let mut args = vec!["report"];
    args.extend_from_slice(&SAMPLE_ARGS);
    args.extend([sample.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let run = run(&args);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    parse(&std::fs::read_to_string(out).unwrap())
}

fn sample_records() -> Value {
    let sample = repo("samples/machine.log");
    let mut args = SAMPLE_ARGS.to_vec();
    args.push(sample.to_str().unwrap());
    summary_records(&args)
}

#[test]
fn the_embedded_records_are_decode_summary_json() {
    let page = sample_page(&scratch("records"));
    assert_eq!(page.summary(), sample_records());
}

#[test]
fn rows_marks_and_bands_agree_with_the_summary() {
    let page = sample_page(&scratch("counts"));
    check_counts(&page, &sample_records());
    assert_eq!(
        page.rows
            .iter()
            .filter(|r| r.row.get("data-row") == Some("bus"))
            .count(),
        1
    );
}

#[test]
fn the_samples_faults_are_where_the_summary_says() {
    let page = sample_page(&scratch("faults"));
    let records = sample_records();
    let node = |id: u64| {
        records
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["type"] == "node" && r["node"] == id)
            .unwrap()
            .clone()
    };
    let body = page.body();
    let start: u64 = body.num("data-start");
    let span: u64 = body.num("data-span");
    assert_eq!(body.get("data-axis"), Some("time"));
    // The x of a time in seconds, as the page draws it by default.
    let x_of = |ts: &Value| {
        let us = (ts.as_f64().unwrap() * 1e6).round() as u64;
        170.0 + (us - start) as f64 / span as f64 * 1000.0
    };

    // Node 3: three faults, each with its EMCY before it.
    let three = page.node("can0", 3);
    assert_eq!(three.lines("cia402_fault"), [620, 1291, 3239]);
    let emcys = three.lines("emcy");
    for (fault, emcy) in [(620, 613), (1291, 1284), (3239, 3231)] {
        assert!(
            emcys.contains(&emcy),
            "EMCY at line {emcy} before the fault at {fault}"
        );
        let f = &node(3)["cia402"]["transitions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["line"] == fault)
            .unwrap()
            .clone();
        let mark = three
            .kind("cia402_fault")
            .into_iter()
            .find(|e| e.num("data-line") == fault)
            .unwrap();
        let x: f64 = mark.get("x").unwrap().parse().unwrap();
        assert!((x - x_of(&f["ts"])).abs() < 0.01, "fault at {fault}: x {x}");
        assert!(page
            .html
            .contains(&format!("went operation_enabled → fault at line {fault}")));
    }
    // Its bands: the CiA 402 states in turn, each where it begins.
    let transitions: Vec<u64> = node(3)["cia402"]["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["line"].as_u64().unwrap())
        .collect();
    assert_eq!(three.lines("cia402_state"), transitions);
    assert!(three
        .kind("cia402_state")
        .iter()
        .any(|b| b.get("data-state") == Some("fault") && b.num("data-line") == 620));

    // The SDO abort at line 95.
    assert_eq!(three.lines("sdo_abort"), [95, 3518]);
    assert!(page
        .html
        .contains("line 95: server aborted 1A00h.00 (TPDO mapping parameter)"));

    // Node 5: the heartbeat timeout after line 1559, drawn as a span of
    // its gap, and its two boot-ups.
    let five = page.node("can0", 5);
    let gaps = five.kind("heartbeat_timeout");
    assert_eq!(gaps.len(), 1);
    assert_eq!(gaps[0].num("data-line"), 1559);
    let width: f64 = gaps[0].get("width").unwrap().parse().unwrap();
    let gap_ms = node(5)["heartbeat"]["timeouts"][0]["gap_ms"]
        .as_f64()
        .unwrap();
    assert!((width - gap_ms * 1000.0 / span as f64 * 1000.0).abs() < 0.01);
    assert_eq!(five.lines("boot_up"), [15, 2681]);
    assert!(page
        .html
        .contains("restarted 1 time (boot-ups at lines 15, 2681)"));
    assert!(page
        .html
        .contains("no heartbeat for 3386.93 ms after line 1559"));
    // Silent past the consumer time (300 ms), its state is unknown up to
    // the boot-up that ends the gap: no band says `operational` there.
    let nmt: Vec<(&str, u64, f64)> = five
        .kind("nmt_state")
        .iter()
        .map(|b| {
            (
                b.get("data-state").unwrap(),
                b.num("data-line"),
                b.get("x").unwrap().parse().unwrap(),
            )
        })
        .collect();
    let silent = nmt.iter().position(|b| b.0 == "unknown").unwrap();
    assert_eq!(nmt[silent].1, 1559);
    assert_eq!((nmt[silent + 1].0, nmt[silent + 1].1), ("boot_up", 2681));
    assert_eq!(nmt[silent - 1].0, "operational");
    let x_gap = gaps[0].get("x").unwrap().parse::<f64>().unwrap();
    let consumer_px = 300_000.0 / span as f64 * 1000.0;
    assert!((nmt[silent].2 - (x_gap + consumer_px)).abs() < 0.01);
    assert_eq!(nmt.iter().filter(|b| b.0 == "unknown").count(), 1);

    // Node 10: the guarding toggle error.
    let ten = page.node("can0", 10);
    assert_eq!(ten.lines("toggle_error"), [1104]);
    assert!(page.html.contains("wrong toggle at line 1104"));

    // The verdict leads "What went wrong" (docs/report.md#page): the
    // stop with its wall-clock time, and the first cause.
    let wrong = page.html.find("id=\"wrong\"").unwrap();
    let verdict = page.html[wrong..].find("<div class=\"verdict\"").unwrap() + wrong;
    assert!(verdict < wrong + page.html[wrong..].find("<ul").unwrap());
    let block = &page.html[verdict..verdict + page.html[verdict..].find("</div>").unwrap()];
    assert!(
        block.starts_with(
            "<div class=\"verdict\" data-kind=\"verdict\" data-line=\"3239\" \
             data-iface=\"can0\" data-node=\"3\" data-severity=\"fault\">"
        ),
        "{block}"
    );
    assert!(
        block.contains(
            "<b>Stop at 2023-11-14 22:13:28.820694 UTC:</b> can0 node 3 went operation_enabled \
             → fault at line 3239 (+8.820 s), 16.1 ms after EMCY 0x7305 Incremental sensor 1 \
             fault on axis 1, feedback 2 (line 3231)"
        ),
        "{block}"
    );
    assert!(
        block.contains("<b>First cause:</b> can0 node 3 first error: EMCY 0x7305"),
        "{block}"
    );
    // Faults come first: before the timeline.
    let timeline = page.html.find("id=\"timeline\"").unwrap();
    assert!(wrong < timeline);
}

#[test]
fn the_page_is_self_contained() {
    let page = sample_page(&scratch("contained"));
    for e in &page.elements {
        for (name, value) in &e.attrs {
            if name == "href" || name == "src" {
                assert!(value.starts_with('#'), "{name}={value} on {}", e.tag);
            }
        }
    }
    assert!(!page.html.contains("http://") || !page.html.contains("src=\"http"));
    assert!(!page.html.contains("<link"));
    assert!(!page.html.contains("https://"));
    assert!(!page.html.contains("@import"));
}

/// A candump log of an EMCY storm from node 7: 3000 EMCYs, 300 of them
/// resets, and a heartbeat.
fn storm_log(path: &std::path::Path) {
    let mut f = std::fs::File::create(path).unwrap();
    writeln!(f, "(1700000000.000000) can0 707#05").unwrap();
    for i in 0..3000u64 {
        let us = 1_000 + i * 997;
        let data = if i % 10 == 9 {
            "0000000000000000"
        } else {
            "1081110000000000"
        };
        writeln!(f, "(1700000000.{us:06}) can0 087#{data}").unwrap();
    }
}

#[test]
fn a_storm_clusters_and_every_emcy_is_counted() {
    let dir = scratch("storm");
    let log = dir.join("storm.log");
    storm_log(&log);
    let out = dir.join("storm.html");
    let r = run(&["report", log.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(r.status.success());
    let page = parse(&std::fs::read_to_string(&out).unwrap());
    let records = summary_records(&[log.to_str().unwrap()]);
    check_counts(&page, &records);
    assert_eq!(page.summary(), records);
    let row = page.node("can0", 7);
    let clusters = row.kind("emcy");
    assert_eq!(row.count("emcy"), 2700);
    assert!(
        clusters.len() < 1000,
        "{} marks for 2700 EMCYs",
        clusters.len()
    );
    assert!(clusters.iter().any(|c| c.num("data-count") > 1));
    // A cluster's line is its first EMCY's.
    assert_eq!(clusters[0].num("data-line"), 2);
    // 300 resets: each its own mark.
    assert_eq!(row.kind("emcy_reset").len(), 300);
}

/// Node 5 boots 30 times and the server aborts 25 SDO uploads; the bus
/// goes bus-off 24 times: more of each than the summary lists
/// (docs/summary.md#lists).
#[test]
fn long_lists_are_counted_in_full_and_listed_first_and_last() {
    let dir = scratch("lists");
    let log = dir.join("lists.log");
    let mut f = std::fs::File::create(&log).unwrap();
    let mut us = 0u64;
    let mut at = || {
        us += 1_000;
        format!("(1700000000.{us:06})")
    };
    for _ in 0..30 {
        writeln!(f, "{} can0 705#00", at()).unwrap();
        writeln!(f, "{} can0 705#05", at()).unwrap();
    }
    for _ in 0..25 {
        writeln!(f, "{} can0 605#4000100000000000", at()).unwrap();
        writeln!(f, "{} can0 585#8000100000000206", at()).unwrap();
    }
    for _ in 0..24 {
        // An error frame of class bus-off (docs/output.md#error-frames).
        writeln!(f, "{} can0 20000040#0000000000000000", at()).unwrap();
    }
    drop(f);
    let out = dir.join("lists.html");
    let r = run(&["report", log.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let html = std::fs::read_to_string(&out).unwrap();
    let page = parse(&html);
    let records = summary_records(&[log.to_str().unwrap()]);
    assert_eq!(page.summary(), records);
    // Every mark is drawn and counted; every list is its first 10 and
    // last 10 (check_counts).
    check_counts(&page, &records);
    // The last bus-off stops (docs/summary.md#verdict): the verdict first.
    assert_eq!(records[0]["stop"]["kind"], "bus_off");
    let node = &records[1];
    assert_eq!(node["heartbeat"]["boot_up_count"], 30);
    assert_eq!(node["sdo"]["abort_count"], 25);
    assert_eq!(records[2]["bus_off_count"], 24);
    let row = page.node("can0", 5);
    assert_eq!(row.count("boot_up"), 30);
    assert_eq!(row.count("sdo_abort"), 25);
    // The findings say where the list omitted events and how many: the
    // aborts after the tenth (line 80), the bus-offs after the tenth
    // (line 120).
    assert!(
        html.contains("… and 5 more (SDO abort) after line 80"),
        "{html}"
    );
    assert!(
        html.contains("… and 4 more (bus-off) after line 120"),
        "{html}"
    );
    assert!(html.contains("boot-ups at lines 1, 3, 5, 7, 9, 11, 13, 15, 17, 19, … 10 more …, 41,"));

    let text =
        String::from_utf8(run(&["decode", "--summary", log.to_str().unwrap()]).stdout).unwrap();
    assert!(text.contains("          … 5 more aborts …\n"), "{text}");
    assert!(
        text.contains(
            "bus-off at lines 111, 112, 113, 114, 115, 116, 117, 118, 119, 120, … 4 more …, 125,"
        ),
        "{text}"
    );
}

#[test]
fn a_log_without_timestamps_is_drawn_by_line() {
    let dir = scratch("untimed");
    let log = dir.join("screen.log");
    std::fs::write(
        &log,
        "  can0  703   [1]  00\n  can0  083   [8]  10 81 11 00 00 00 00 00\n  can0  703   [1]  05\n  can0  703   [1]  05\n",
    )
    .unwrap();
    let out = dir.join("screen.html");
    let r = run(&[
        "report",
        "--heartbeat-ms",
        "100",
        log.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let stderr = String::from_utf8(r.stderr).unwrap();
    assert!(
        stderr.contains("heartbeat timeouts were not checked"),
        "{stderr}"
    );
    let page = parse(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(page.body().get("data-axis"), Some("line"));
    assert!(page.html.contains("The log has no timestamps:"));
    assert!(!page.html.contains("seconds</text>"));
    let row = page.node("can0", 3);
    assert_eq!(row.lines("boot_up"), [1]);
    assert_eq!(row.lines("emcy"), [2]);
    assert!(row.kind("heartbeat_timeout").is_empty());
    assert!(row.kind("frame_rate").is_empty());
    check_counts(
        &page,
        &summary_records(&["--heartbeat-ms", "100", log.to_str().unwrap()]),
    );
}

/// docs/report.md#bands: a device silent past the heartbeat consumer time
/// is drawn as `unknown` from then to its next heartbeat or to the end;
/// without `--heartbeat-ms` nothing is checked, and its last state lasts.
#[test]
fn a_silent_device_is_drawn_as_unknown() {
    let dir = scratch("silent");
    let log = dir.join("silent.log");
    std::fs::write(
        &log,
        "(10.000000) can0 705#05
(10.100000) can0 705#05
(10.900000) can0 705#7F
         (11.000000) can0 705#7F
(11.100000) can0 080#
(13.000000) can0 080#
",
    )
    .unwrap();
    let page_of = |args: &[&str], name: &str| {
        let out = dir.join(name);
        let mut all = vec!["report"];
        all.extend_from_slice(args);
        all.extend([log.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        let r = run(&all);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        parse(&std::fs::read_to_string(&out).unwrap())
    };
    let page = page_of(&["--heartbeat-ms", "200"], "checked.html");
    let row = page.node("can0", 5);
    let states: Vec<(&str, u64)> = row
        .kind("nmt_state")
        .iter()
        .map(|b| (b.get("data-state").unwrap(), b.num("data-line")))
        .collect();
    // 600 ms of silence after line 2 (unknown from 10.3 s), then
    // pre-operational from line 3; silent again after line 4 to the end.
    assert_eq!(
        states,
        [
            ("operational", 1),
            ("unknown", 2),
            ("pre_operational", 3),
            ("unknown", 4)
        ]
    );
    let unknown = row.kind("nmt_state")[1];
    let x: f64 = unknown.get("x").unwrap().parse().unwrap();
    let width: f64 = unknown.get("width").unwrap().parse().unwrap();
    // The axis spans 3 s: 10.3 s to 10.9 s is 200 px to 400 px of 1 000.
    assert!((x - (170.0 + 100.0)).abs() < 0.01, "{x}");
    assert!((width - 200.0).abs() < 0.01, "{width}");
    check_counts(
        &page,
        &summary_records(&["--heartbeat-ms", "200", log.to_str().unwrap()]),
    );

    let unchecked = page_of(&[], "unchecked.html");
    let states: Vec<&str> = unchecked
        .node("can0", 5)
        .kind("nmt_state")
        .iter()
        .map(|b| b.get("data-state").unwrap())
        .collect();
    assert_eq!(states, ["operational", "pre_operational"]);
}

#[test]
fn several_logs_and_joined_logs_embed_the_same_records_as_decode() {
    let dir = scratch("several");
    let sample = repo("samples/machine.log");
    let pcap = repo("tests/fixtures/pcap/multi.pcapng");
    for joined in [false, true] {
        let out = dir.join(format!("several-{joined}.html"));
        let mut args = vec!["report"];
        if joined {
            args.push("--joined");
        }
        args.extend([
            sample.to_str().unwrap(),
            pcap.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let r = run(&args);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let page = parse(&std::fs::read_to_string(&out).unwrap());
        let mut decode = Vec::new();
        if joined {
            decode.push("--joined");
        }
        decode.extend([sample.to_str().unwrap(), pcap.to_str().unwrap()]);
        let records = summary_records(&decode);
        assert_eq!(page.summary(), records);
        check_counts(&page, &records);
    }
}

#[test]
fn damaged_and_hostile_logs_give_the_errors_of_decode() {
    let dir = scratch("hostile");
    let garbage = dir.join("garbage.bin");
    std::fs::write(&garbage, [0xD4u8, 0xC3, 0xB2, 0xA1, 2, 0, 4, 0, 0xFF, 0xFF]).unwrap();
    let malformed = dir.join("malformed.log");
    std::fs::write(
        &malformed,
        "(1700000000.000000) can0 703#05\n(1700000000.1) can0 7Z3#05\nnot a frame at all\n(1700000000.200000) can0 703#05\n",
    )
    .unwrap();
    let missing = dir.join("missing.log");
    for log in [&garbage, &malformed, &missing] {
        let out = dir.join("page.html");
        let _ = std::fs::remove_file(&out);
        let report = run(&[
            "report",
            "--heartbeat-ms",
            "300",
            log.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let decode = run(&[
            "decode",
            "--summary",
            "--heartbeat-ms",
            "300",
            log.to_str().unwrap(),
        ]);
        assert_eq!(
            report.status.code(),
            decode.status.code(),
            "{}",
            log.display()
        );
        assert_eq!(
            String::from_utf8_lossy(&report.stderr),
            String::from_utf8_lossy(&decode.stderr),
            "{}",
            log.display()
        );
        // A page only when the log could be read.
        assert_eq!(
            out.exists(),
            report.status.code() != Some(2),
            "{}",
            log.display()
        );
    }
    let page = parse(&std::fs::read_to_string(dir.join("page.html")).unwrap_or_default());
    let _ = page;
    let out = dir.join("page.html");
    run(&[
        "report",
        malformed.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&out)
        .unwrap()
        .contains("2 malformed lines skipped"));
}

#[test]
fn an_output_folder_that_is_not_there_is_said_first() {
    let r = run(&[
        "report",
        repo("samples/machine.log").to_str().unwrap(),
        "-o",
        "/nonexistent-folder-of-motionwire/page.html",
    ]);
    assert_eq!(r.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&r.stderr).contains("does not exist"));
}

/// Found by the fuzz target `report`: an EMCY with a code 00xxh other than
/// 0000h is a reset for the summary (`resets`, docs/canopen.md#emcy-codes),
/// so the page marks it as one (`emcy_reset`), and the marks of a row add
/// up to the summary's counts.
#[test]
fn every_00xx_code_is_a_reset_mark() {
    use motionwire::can::LogEvent;
    use motionwire::decoder::DecoderConfig;
    use motionwire::report::{MarkKind, Recorder};

    let log = b"(1.000000) can0 083#0B00000000000000\n\
                (1.100000) can0 083#0573010000000000\n\
                (1.200000) can0 083#0000000000000000\n";
    let mut recorder = Recorder::new(DecoderConfig::new());
    for (i, text) in log.split(|&b| b == b'\n').enumerate() {
        if let Ok(Some(frame)) = motionwire::logs::candump::parse_line(text) {
            recorder.add(
                motionwire::logs::Position::Line(i as u64 + 1),
                &LogEvent::Frame(frame),
            );
        }
    }
    let recording = recorder.finish();
    let node = &recording.summary.nodes[0];
    assert_eq!((node.emcy, node.resets), (3, 2));
    let marks = |kind| {
        recording
            .timeline
            .mark_count(&node.bus, Some(node.node), kind)
    };
    assert_eq!(marks(MarkKind::EmcyReset), 2);
    assert_eq!(marks(MarkKind::Emcy), 1);
}

/// A page from any bytes read as a log (detected as the program detects
/// it): no panic, one whole document whose embedded records are JSON, and
/// marks that add up to the summary's counts (the fuzz target `report`
/// checks the same on longer runs).
fn page_of_any_log(bytes: Vec<u8>) -> Result<(), proptest::test_runner::TestCaseError> {
    use motionwire::decoder::DecoderConfig;
    use motionwire::logs::{self, ReadLog};
    use motionwire::report::{MarkKind, Recorder, Report};
    use proptest::prelude::*;

    let Ok(mut log) = logs::read(std::io::Cursor::new(bytes)) else {
        return Ok(());
    };
    let mut recorder =
        Recorder::new(DecoderConfig::new().heartbeat_timeout(std::time::Duration::from_millis(50)));
    while let Some(next) = log.next_event() {
        if let Ok(record) = next {
            recorder.add(record.position, &record.event);
        }
    }
    let recording = recorder.finish();
    for node in &recording.summary.nodes {
        let marks = |kind| {
            recording
                .timeline
                .mark_count(&node.bus, Some(node.node), kind)
        };
        prop_assert_eq!(
            marks(MarkKind::Emcy) + marks(MarkKind::EmcyReset),
            node.emcy
        );
        prop_assert_eq!(marks(MarkKind::EmcyReset), node.resets);
        prop_assert_eq!(marks(MarkKind::BootUp), node.heartbeat.boot_ups.count());
    }
    let records = recording.summary.records().count();
    let mut report = Report::new();
    report.add_recording(recording);
    let mut page = Vec::new();
    report.write_html(&mut page).unwrap();
    let page = String::from_utf8(page).expect("UTF-8");
    prop_assert!(page.starts_with("<!DOCTYPE html>") && page.ends_with("</html>\n"));
    let open = r#"<script type="application/json" id="motionwire-summary">"#;
    let start = page.find(open).unwrap() + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    let embedded: Value = serde_json::from_str(&page[start..end]).expect("JSON");
    prop_assert_eq!(embedded.as_array().map(Vec::len), Some(records));
    Ok(())
}

/// Text that looks like candump lines of CANopen traffic, with noise.
fn candump_like() -> impl proptest::strategy::Strategy<Value = Vec<u8>> {
    use proptest::prelude::*;
    let line = (
        0u32..3_000_000,
        prop_oneof![
            Just(0x000u32),
            0x080u32..0x100,
            0x180u32..0x280,
            0x580u32..0x680,
            0x700u32..0x780
        ],
        proptest::collection::vec(any::<u8>(), 0..=8),
        0u8..2,
    )
        .prop_map(|(us, id, data, iface)| {
            let hex: String = data.iter().map(|b| format!("{b:02X}")).collect();
            format!(
                "({}.{:06}) can{iface} {id:03X}#{hex}\n",
                us / 1_000_000,
                us % 1_000_000
            )
        });
    proptest::collection::vec(prop_oneof![9 => line, 1 => "[ -~]{0,20}\n"], 0..60)
        .prop_map(|lines| lines.concat().into_bytes())
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    #[test]
    fn any_bytes_make_a_whole_page(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..400)) {
        page_of_any_log(bytes)?;
    }

    #[test]
    fn any_candump_traffic_makes_a_whole_page(bytes in candump_like()) {
        page_of_any_log(bytes)?;
    }
}

/// docs/report.md#bands: when frames without a time make the summary's
/// heartbeat timeouts unchecked (`null`), no silence is drawn either.
#[test]
fn an_unchecked_silence_is_not_drawn() {
    use motionwire::can::{CanFrame, CanId, Iface, LogEvent, LogFrame, Timestamp};
    use motionwire::decoder::DecoderConfig;
    use motionwire::logs::Position;
    use motionwire::report::{Recorder, Report};
    use std::time::Duration;

    let page = |untimed: bool| {
        let mut recorder =
            Recorder::new(DecoderConfig::new().heartbeat_timeout(Duration::from_millis(200)));
        let frame = |ms: Option<u64>| {
            let log =
                LogFrame::new(CanFrame::new(CanId::standard(0x705).unwrap(), &[0x05]).unwrap())
                    .with_iface(Iface::Name("can0"));
            match ms {
                Some(ms) => log.with_timestamp(Timestamp::from_duration(Duration::from_millis(ms))),
                None => log,
            }
        };
        let mut times = vec![Some(0), Some(100), Some(1000)];
        if untimed {
            times.push(None);
        }
        for (line, ms) in (1..).zip(times) {
            recorder.add(Position::Line(line), &LogEvent::Frame(frame(ms)));
        }
        let recording = recorder.finish();
        assert_eq!(recording.summary.timeouts_not_checked(), untimed);
        let mut report = Report::new();
        report.add_recording(recording);
        let mut html = Vec::new();
        report.write_html(&mut html).unwrap();
        parse(&String::from_utf8(html).unwrap())
    };
    let states = |page: &Page| -> Vec<String> {
        page.node("can0", 5)
            .kind("nmt_state")
            .iter()
            .map(|b| b.get("data-state").unwrap().to_owned())
            .collect()
    };
    assert_eq!(
        states(&page(false)),
        ["operational", "unknown", "operational"]
    );
    let unchecked = page(true);
    assert!(!states(&unchecked).iter().any(|s| s == "unknown"));
    assert!(unchecked
        .node("can0", 5)
        .kind("heartbeat_timeout")
        .is_empty());
}

/// docs/summary.md#profiles: what `--profile` reads in an EMCY reaches the
/// page — the findings' text, the marks' details and the Events table —,
/// on the sample and on a generated log of an AKD drive and a Baumer
/// encoder.
#[test]
fn profiles_reach_the_findings_the_marks_and_the_events() {
    let page = sample_page(&scratch("profiles"));
    let html = &page.html;
    let wrong = &html[html.find("id=\"wrong\"").unwrap()..html.find("id=\"timeline\"").unwrap()];
    for text in [
        "first warning: EMCY 0xFF00 Device specific (source: Battery monitoring warning, a warning) at line 393",
        "first error: EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 1 at line 613",
        "went operation_enabled → fault at line 3239, 16.1 ms after EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2 (line 3231)",
        "first error: EMCY 0x8120 CAN in error passive mode (source: CAN controller bus passive, an error) at line 972",
    ] {
        assert!(wrong.contains(text), "{text}");
    }
    let events = &html[html.find("id=\"events\"").unwrap()..];
    assert!(events.contains(
        "<td>EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2 (register 0x01) (line 3231"
    ));
    assert!(events.contains(
        "<td>EMCY 0x4200 Device temperature (source: Temperature monitoring, an error) (register 0x09)"
    ));
    let timeline =
        &html[html.find("id=\"timeline\"").unwrap()..html.find("id=\"signals\"").unwrap()];
    assert!(timeline.contains(
        "<title>EMCY 0xFF00 Device specific (source: Battery monitoring warning, a warning) (register 0x00) (line 393"
    ));

    // A generated log: an AKD's EMCY on axis 2, feedback 3, and a Baumer
    // encoder's battery warning; without --profile the page says neither.
    let dir = scratch("profiles-generated");
    let log = dir.join("profiles.log");
    std::fs::write(
        &log,
        "(1700000000.000000) can0 083#0573013200000000\n\
         (1700000000.100000) can0 085#00FF000000100000\n\
         (1700000000.200000) can0 703#05\n",
    )
    .unwrap();
    let page_of = |args: &[&str], name: &str| {
        let out = dir.join(name);
        let mut all = vec!["report"];
        all.extend_from_slice(args);
        all.extend([log.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        let r = run(&all);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        std::fs::read_to_string(&out).unwrap()
    };
    let with = page_of(&["--profile", "3=akd,5=baumer"], "with.html");
    let without = page_of(&[], "without.html");
    let akd = "EMCY 0x7305 Incremental sensor 1 fault on axis 2, feedback 3";
    let baumer = "EMCY 0xFF00 Device specific (source: Battery monitoring warning, a warning)";
    // The finding, the mark's title and the event row; the Devices table
    // names the first error too.
    assert_eq!(with.matches(akd).count(), 3, "{akd}");
    assert_eq!(with.matches(baumer).count(), 3, "{baumer}");
    assert!(
        with.contains("<td>0x7305 Incremental sensor 1 fault on axis 2, feedback 3 (line 1)</td>")
    );
    assert!(!without.contains("on axis") && !without.contains("(source:"));
}

/// docs/report.md#page: "What went wrong" groups the findings by device
/// and kind, the worst first, each group's first and last shown and the
/// rest in a `details`; the verdict above them; every finding with its
/// wall-clock time beside the relative one.
#[test]
fn findings_are_grouped_by_device_and_kind_under_the_verdict() {
    let page = sample_page(&scratch("groups"));
    let html = &page.html;
    let wrong = &html[html.find("id=\"wrong\"").unwrap()..html.find("id=\"timeline\"").unwrap()];
    let verdict = wrong.find("<div class=\"verdict\"").unwrap();
    let groups: Vec<&Element> = page
        .elements
        .iter()
        .filter(|e| e.get("class") == Some("group"))
        .collect();
    assert!(verdict < wrong.find("<li class=\"group\"").unwrap());
    let kinds: Vec<(&str, &str, &str, u64)> = groups
        .iter()
        .map(|g| {
            (
                g.get("data-node").unwrap_or(""),
                g.get("data-kind").unwrap(),
                g.get("data-severity").unwrap(),
                g.num("data-count"),
            )
        })
        .collect();
    assert_eq!(
        kinds,
        [
            ("3", "cia402_fault", "fault", 3),
            ("5", "first_error", "error", 2),
            ("3", "first_error", "error", 1),
            ("5", "heartbeat_timeout", "error", 1),
            ("10", "first_error", "error", 1),
            ("10", "toggle_error", "warning", 1),
            ("5", "restarts", "warning", 1),
            ("3", "sdo_abort", "notice", 2),
        ]
    );
    // The first six open, the other two one click away.
    let more = wrong
        .find("<details class=\"more-groups\"><summary>2 more groups (3 findings)</summary>")
        .unwrap();
    assert!(wrong[more..].contains("data-kind=\"restarts\""));
    // Node 3's faults: the first and the last shown, the middle one in a
    // details.
    let faults = &wrong[wrong.find("data-kind=\"cia402_fault\"").unwrap()..];
    let faults = &faults[..faults.find("</ul></li>").unwrap()];
    let first = faults.find("data-line=\"620\"").unwrap();
    let rest = faults
        .find("<details><summary>1 more between them</summary>")
        .unwrap();
    let middle = faults.find("data-line=\"1291\"").unwrap();
    let last = faults.find("data-line=\"3239\"").unwrap();
    assert!(first < rest && rest < middle && middle < last);
    // Wall-clock time beside the relative one, as the log gives it
    // (line 3239: 1700000008.820694).
    assert!(faults.contains("(+8.820168 s, 2023-11-14 22:13:28.820694 UTC)"));
    let events = &html[html.find("id=\"events\"").unwrap()..];
    assert!(events.contains("<th>time</th><th>UTC</th>"));
    assert!(events.contains("<td>+8.820168 s</td><td>2023-11-14 22:13:28.820694 UTC</td>"));
}

/// docs/report.md#page: the Events table never hides a distinct code
/// behind a merged row — a row whose EMCYs are clustered lists them one
/// row per code.
#[test]
fn the_events_table_lists_a_clustered_rows_emcys_by_code() {
    let dir = scratch("codes");
    let log = dir.join("codes.log");
    let mut text = String::new();
    // 900 EMCYs of node 5, 1 ms apart: 0x8120 and 0x4200 in turn, and one
    // 0x3210 among them.
    for i in 0..900u64 {
        let code = match i {
            450 => "1032",
            i if i % 2 == 0 => "2081",
            _ => "0042",
        };
        text.push_str(&format!(
            "(1700000000.{:06}) can0 085#{code}110000000000\n",
            i * 1000
        ));
    }
    // A heartbeat 10 s on: a pixel is 10 ms, and the EMCYs cluster.
    text.push_str("(1700000010.000000) can0 705#05\n");
    std::fs::write(&log, text).unwrap();
    let out = dir.join("codes.html");
    let r = run(&["report", log.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let html = std::fs::read_to_string(&out).unwrap();
    let page = parse(&html);
    assert!(page
        .node("can0", 5)
        .kind("emcy")
        .iter()
        .any(|m| m.num("data-count") > 1));
    let rows: Vec<(u64, u64)> = page
        .elements
        .iter()
        .filter(|e| e.tag == "tr" && e.get("data-code").is_some())
        .map(|e| (e.num("data-code"), e.num("data-line")))
        .collect();
    assert_eq!(rows, [(0x8120, 1), (0x4200, 2), (0x3210, 451)]);
    assert!(html.contains("449 EMCYs of code 0x8120, lines 1 to 899"));
    assert!(html.contains("450 EMCYs of code 0x4200, lines 2 to 900"));
    assert!(html.contains("<td>EMCY 0x3210 DC link over-voltage (register 0x11) (line 451"));
}

/// docs/report.md#page: an empty log, and a log with no CANopen device,
/// say exactly that.
#[test]
fn an_empty_log_and_a_log_without_devices_say_so() {
    let dir = scratch("empty");
    let page_of = |text: &str, name: &str| {
        let log = dir.join(format!("{name}.log"));
        std::fs::write(&log, text).unwrap();
        let out = dir.join(format!("{name}.html"));
        let r = run(&["report", log.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        std::fs::read_to_string(&out).unwrap()
    };
    let empty = page_of("", "empty");
    assert!(
        empty.contains("<p class=\"empty\" data-kind=\"empty\"><strong>The log is empty:</strong>")
    );
    assert!(!empty.contains("No fault"));
    let none = page_of(
        "(1700000000.000000) can0 12345678#0102\n(1700000000.100000) can0 7E5#04\n",
        "none",
    );
    assert!(none.contains("<strong>No CANopen device in this log:</strong> 2 frames read"));
    assert!(!none.contains("No fault"));
}

/// docs/report.md#several: logs read apart give one timeline per
/// recording, each on its own axis; `--joined`, one.
#[test]
fn logs_read_apart_have_an_axis_each() {
    let dir = scratch("axes");
    let a = dir.join("a.log");
    let b = dir.join("b.log");
    std::fs::write(
        &a,
        "(1700000000.000000) can0 705#05\n(1700000001.000000) can0 085#1081110000000000\n(1700000002.000000) can0 705#05\n",
    )
    .unwrap();
    // Two years later, a recording of its own.
    std::fs::write(
        &b,
        "(1760000000.000000) can0 706#05\n(1760000000.500000) can0 086#1081110000000000\n",
    )
    .unwrap();
    let page_of = |joined: bool| {
        let out = dir.join(format!("axes-{joined}.html"));
        let mut args = vec!["report"];
        if joined {
            args.push("--joined");
        }
        args.extend([
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let r = run(&args);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        std::fs::read_to_string(&out).unwrap()
    };
    let apart = page_of(false);
    let page = parse(&apart);
    let svgs: Vec<(u64, u64)> = page
        .elements
        .iter()
        .filter(|e| e.tag == "svg" && e.get("aria-label") == Some("timeline"))
        .map(|e| (e.num("data-start"), e.num("data-span")))
        .collect();
    assert_eq!(
        svgs,
        [
            (1_700_000_000_000_000, 2_000_000),
            (1_760_000_000_000_000, 500_000)
        ]
    );
    assert_eq!(apart.matches("<h3 class=\"recording\"").count(), 2);
    // Each EMCY at its own recording's time, never at +60000000 s.
    assert!(apart.contains("(+1.000000 s, 2023-11-14 22:13:21.000000 UTC)"));
    assert!(apart.contains("(+0.500000 s, 2025-10-09 08:53:20.500000 UTC)"));
    assert!(!apart.contains("+60000000"));
    check_counts(
        &page,
        &summary_records(&[a.to_str().unwrap(), b.to_str().unwrap()]),
    );

    let joined = parse(&page_of(true));
    let svgs = joined
        .elements
        .iter()
        .filter(|e| e.tag == "svg" && e.get("aria-label") == Some("timeline"))
        .count();
    assert_eq!(svgs, 1);
}

/// The EtherCAT captures of tests/data/ethercat.
fn ethercat_captures() -> Vec<std::path::PathBuf> {
    let mut captures: Vec<_> = std::fs::read_dir(repo("tests/data/ethercat"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "pcapng"))
        .collect();
    captures.sort();
    captures
}

/// `report CAPTURE`: the page, read by its contract, and standard error.
fn capture_page(capture: &std::path::Path, dir: &std::path::Path) -> (Page, String) {
    let out = dir.join(format!(
        "{}.html",
        capture.file_stem().unwrap().to_string_lossy()
    ));
    let run = run(&[
        "report",
        capture.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{}: {stderr}", capture.display());
    (parse(&std::fs::read_to_string(out).unwrap()), stderr)
}

/// How many findings the slave records of `records` make: their first
/// error emergencies, AL errors, CiA 402 faults and servo faults
/// (docs/ethercat.md#findings).
fn summary_findings(records: &[serde_json::Value]) -> usize {
    records
        .iter()
        .filter(|r| r["type"] == "slave")
        .map(|s| {
            let emcy = s["emcy"]
                .as_array()
                .is_some_and(|e| e.iter().any(|e| e["code"] != 0));
            let al = s["al_timeline"].as_array().map_or(0, |t| {
                t.iter()
                    .filter(|c| c["requested"] == false && c["error"] == true)
                    .count()
            });
            let cia402 = s["cia402"]["fault_count"].as_u64().unwrap_or(0) as usize;
            let servo = s["servo"]["fault_set_count"].as_u64().unwrap_or(0) as usize;
            usize::from(emcy) + al + cia402 + servo
        })
        .sum()
}

/// Every capture's page draws a row per slave and per stream record, its
/// AL bands and marks adding up to the records (docs/report.md#ethercat),
/// on a time axis of the capture's span.
#[test]
fn every_ethercat_capture_draws_its_slaves_and_streams() {
    let dir = scratch("ethercat");
    let captures = ethercat_captures();
    assert_eq!(captures.len(), 11);
    let mut slaves = 0;
    for capture in captures {
        let (page, stderr) = capture_page(&capture, &dir);
        assert!(!stderr.contains("does not draw"), "{stderr}");
        let records = summary_records(&[capture.to_str().unwrap()]);
        assert_eq!(page.summary(), records, "{}", capture.display());
        check_counts(&page, &records);
        check_ethercat(&page, &records);
        slaves += page
            .rows
            .iter()
            .filter(|r| r.row.get("data-row") == Some("slave"))
            .count();
        assert_eq!(page.body().get("data-axis"), Some("time"));
        assert!(page.body().num("data-span") > 0);
        // Not an empty log: "What went wrong" lists the slaves' findings
        // (docs/ethercat.md#findings), or says no slave was in trouble.
        let findings = summary_findings(records.as_array().unwrap());
        let said = page
            .elements
            .iter()
            .any(|e| e.tag == "p" && e.get("data-kind") == Some("ethercat"));
        assert_eq!(said, findings == 0, "{}", capture.display());
        // Every AL band says a state, every mark its line.
        for row in &page.rows {
            for band in row.kind("al_state") {
                assert!(band.get("data-state").is_some() && band.get("data-line").is_some());
            }
        }
    }
    assert_eq!(slaves, 21, "the eleven captures' slaves");
}

/// The synthetic AKD fault (docs/ethercat.md#summary): the drive's EMCY at
/// packet 456, then its AL status safeop with error at 458, then the LRW
/// stream's working counter falling from packet 460 — each where the
/// records say, and said in the Events table.
#[test]
fn the_akd_fault_is_drawn_where_the_summary_says() {
    let (page, _) = capture_page(
        &repo("tests/data/ethercat/synthetic_akd_fault.pcapng"),
        &scratch("akd-fault"),
    );
    let akd = page
        .rows
        .iter()
        .find(|r| r.row.get("data-row") == Some("slave") && r.row.get("data-slave") == Some("4097"))
        .unwrap();
    assert_eq!(akd.row.get("data-iface"), Some("enp2s0"));
    assert_eq!(akd.row.get("data-position"), Some("1"));
    let states: Vec<(&str, u64, bool)> = akd
        .kind("al_state")
        .iter()
        .map(|b| {
            (
                b.get("data-state").unwrap(),
                b.num("data-line"),
                b.get("data-error") == Some("true"),
            )
        })
        .collect();
    assert_eq!(
        states,
        [
            ("preop", 84, false),
            ("safeop", 144, false),
            ("op", 152, false),
            ("safeop", 458, true)
        ]
    );
    assert_eq!(akd.lines("coe_emcy"), [456]);
    assert_eq!(akd.lines("al_error"), [458]);
    let lrw = page
        .rows
        .iter()
        .find(|r| r.row.get("data-row") == Some("stream"))
        .unwrap();
    assert_eq!(lrw.row.get("data-stream"), Some("LRW logical 0x00000000"));
    assert_eq!(lrw.count("wkc_mismatch"), 50);
    assert_eq!(lrw.lines("wkc_mismatch")[0], 460);
    assert_eq!(lrw.count("lost_frame"), 0);
    // Each mark an event row, with its row's attributes.
    let events: Vec<&Element> = page
        .elements
        .iter()
        .filter(|e| e.tag == "tr" && e.get("data-line").is_some())
        .collect();
    assert!(events
        .iter()
        .any(|e| e.num("data-line") == 456 && e.get("data-slave") == Some("4097")));
    assert_eq!(
        events
            .iter()
            .filter(|e| e.get("data-stream") == Some("LRW logical 0x00000000"))
            .count(),
        50
    );
    assert!(page
        .html
        .contains("AL status safeop with error 0x001b Sync manager watchdog"));
}

/// A pcap (link type Ethernet) of `cycles` LRW frames a millisecond apart,
/// sent by an ethercrab master and returned through three slaves: `wkc`
/// gives each cycle's returned working counter, `None` for a frame that
/// never comes back.
fn lrw_capture(path: &std::path::Path, cycles: usize, wkc: impl Fn(usize) -> Option<u16>) {
    let mut out = Vec::new();
    out.extend(0xa1b2_c3d4u32.to_le_bytes());
    out.extend(2u16.to_le_bytes());
    out.extend(4u16.to_le_bytes());
    out.extend([0; 8]);
    out.extend(65535u32.to_le_bytes());
    out.extend(1u32.to_le_bytes());
    let mut t = 1_700_000_000_000_000u64;
    let packet = |out: &mut Vec<u8>, t: u64, source: u8, index: u8, wkc: u16| {
        let data = [0u8; 4];
        let mut frame = vec![0xff; 6];
        frame.extend([source, 0x10, 0x10, 0x10, 0x10, 0x10]);
        frame.extend([0x88, 0xa4]);
        let len = 10 + data.len() + 2;
        frame.extend(((len as u16) | 0x1000).to_le_bytes());
        frame.extend([12, index]);
        frame.extend(0u32.to_le_bytes());
        frame.extend((data.len() as u16).to_le_bytes());
        frame.extend(0u16.to_le_bytes());
        frame.extend(data);
        frame.extend(wkc.to_le_bytes());
        out.extend(((t / 1_000_000) as u32).to_le_bytes());
        out.extend(((t % 1_000_000) as u32).to_le_bytes());
        out.extend((frame.len() as u32).to_le_bytes());
        out.extend((frame.len() as u32).to_le_bytes());
        out.extend(frame);
    };
    for cycle in 0..cycles {
        let index = cycle as u8;
        packet(&mut out, t, 0x10, index, 0);
        if let Some(wkc) = wkc(cycle) {
            packet(&mut out, t + 100, 0x12, index, wkc);
        }
        t += 1000;
    }
    std::fs::write(path, out).unwrap();
}

/// A busy stream: thousands of mismatches and lost frames are drawn as
/// clusters (docs/report.md#clusters) whose counts add up to the stream
/// record's, with the same code as the CAN rows.
#[test]
fn a_busy_stream_clusters_and_every_frame_is_counted() {
    let dir = scratch("ecat-storm");
    let capture = dir.join("storm.pcap");
    // Cycle by cycle: 800 in a row lost and every 97th, every 3rd with
    // working counter 2.
    lrw_capture(&capture, 6000, |c| {
        if (1000..1800).contains(&c) || c % 97 == 0 {
            None
        } else if c % 3 == 0 {
            Some(2)
        } else {
            Some(3)
        }
    });
    let (page, _) = capture_page(&capture, &dir);
    let records = summary_records(&[capture.to_str().unwrap()]);
    check_ethercat(&page, &records);
    let stream = records
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["type"] == "stream")
        .unwrap();
    assert!(stream["lost"].as_u64().unwrap() > 800);
    assert_eq!(stream["wkc_usual"], 3);
    let row = page
        .rows
        .iter()
        .find(|r| r.row.get("data-row") == Some("stream"))
        .unwrap();
    for kind in ["lost_frame", "wkc_mismatch"] {
        let marks = row.kind(kind);
        assert!(marks.len() < 1100, "{kind}: {} marks", marks.len());
        assert!(
            marks.iter().any(|m| m.num("data-count") > 1),
            "{kind} clusters"
        );
        for m in marks.iter().filter(|m| m.num("data-count") > 1) {
            assert!(m.num("data-last-line") > m.num("data-line"));
        }
    }
    assert!(page.html.len() < 1_500_000, "{} bytes", page.html.len());
}

/// The generated capture of a servo and two CiA 402 drives
/// (tests/data/ethercat/drives.pcapng) read with `--servo 0x1001`: the
/// page and its records.
fn drives_page(dir: &std::path::Path) -> (Page, Value) {
    let capture = repo("tests/data/ethercat/drives.pcapng");
    let out = dir.join("drives.html");
    let args = ["--servo", "0x1001", capture.to_str().unwrap()];
    let r = run(&[&["report"][..], &args, &["-o", out.to_str().unwrap()]].concat());
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let page = parse(&std::fs::read_to_string(out).unwrap());
    (page, summary_records(&args))
}

/// What the models did (tests/data/ethercat/drives.model.jsonl), record
/// by record.
fn drives_model() -> Vec<Value> {
    std::fs::read_to_string(repo("tests/data/ethercat/drives.model.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

/// A slave's row.
fn slave_row(page: &Page, station: u64) -> &crate::report_common::Row {
    page.rows
        .iter()
        .find(|r| {
            r.row.get("data-row") == Some("slave")
                && r.row.get("data-slave") == Some(station.to_string().as_str())
        })
        .unwrap_or_else(|| panic!("no row for slave {station}"))
}

/// The servo's row (docs/report.md#ethercat): one enable band per change
/// of the enable handshake, in order, each the phase the model's NC went
/// to at the packet it did, the summary's listed ones among them; each
/// kind of servo mark adding up to the servo timeline's count, the faults
/// with their E-codes and the handshakes with their phases in words; the
/// drive 0x1002's CiA 402 band going to fault after its over-current.
#[test]
fn the_servo_and_the_drives_are_drawn_as_the_summary_says() {
    let (page, records) = drives_page(&scratch("drives"));
    assert_eq!(page.summary(), records);
    check_counts(&page, &records);
    check_ethercat(&page, &records);
    let record = |station: u64| {
        records
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["type"] == "slave" && r["slave"] == station)
            .unwrap()
    };
    let servo = &record(0x1001)["servo"];
    let row = slave_row(&page, 0x1001);
    assert_eq!(row.row.get("data-position"), Some("0"));
    let bands: Vec<(String, u64)> = row
        .kind("servo_enable")
        .iter()
        .map(|b| {
            assert_eq!(b.num("data-count"), 1);
            (b.get("data-state").unwrap().to_owned(), b.num("data-line"))
        })
        .collect();
    assert_eq!(
        bands.len() as u64,
        servo["enable_change_count"].as_u64().unwrap()
    );
    // The model's every enable change, in order.
    let model: Vec<(String, u64)> = drives_model()
        .iter()
        .filter(|r| r["slave"] == 0x1001 && r["kind"] == "servo_enable")
        .map(|r| {
            (
                r["to"].as_str().unwrap().to_owned(),
                r["packet"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(bands, model);
    // The summary's listed enable events are among them, in order.
    let listed: Vec<(String, u64)> = servo["events"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["event"] == "enable")
        .map(|e| {
            (
                e["to"].as_str().unwrap().to_owned(),
                e["packet"].as_u64().unwrap(),
            )
        })
        .collect();
    assert!(listed.len() >= 8, "{listed:?}");
    let mut rest = bands.iter();
    for event in &listed {
        assert!(
            rest.any(|b| b == event),
            "{event:?} in order among {bands:?}"
        );
    }
    assert_eq!(bands[0], ("arming".to_owned(), 214));
    assert_eq!(bands.last().unwrap().0, "enabled");
    // The marks, each kind as many as the timeline counts.
    for (kind, key, at_least) in [
        ("servo_fault", "fault_set_count", 4),
        ("servo_error_clear", "error_clear_count", 3),
        ("servo_zero_pulse", "zero_pulse_count", 1),
        ("servo_not_ready", "not_ready_count", 2),
        ("servo_enable_unanswered", "enable_unanswered", 1),
    ] {
        assert_eq!(row.count(kind), servo[key].as_u64().unwrap(), "{kind}");
        assert!(row.count(kind) >= at_least, "{kind}");
    }
    assert_eq!(row.lines("servo_error_clear")[0], 514);
    assert_eq!(row.lines("servo_zero_pulse"), [712]);
    assert!(page.html.contains("servo fault FollowerErr (E09) set"));
    assert!(page.html.contains("servo fault EncoderErr (E01) set"));
    assert!(page
        .html
        .contains("servo error clear requested → acknowledged → done"));
    assert!(page
        .html
        .contains("servo zero pulse requested → acknowledged (zero pulse at"));
    assert!(page
        .html
        .contains("unanswered enable edge: enable disabling"));
    // The over-current's drive: its CiA 402 band goes to fault, marked.
    let drive = record(0x1002);
    let row = slave_row(&page, 0x1002);
    let fault_band = row
        .kind("cia402_state")
        .into_iter()
        .find(|b| b.get("data-state") == Some("fault"))
        .expect("a fault band");
    let fault_line = drive["cia402"]["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["to"] == "fault")
        .unwrap()["line"]
        .as_u64()
        .unwrap();
    assert_eq!(fault_band.num("data-line"), fault_line);
    assert_eq!(row.lines("cia402_fault"), [1611]);
    assert_eq!(row.lines("coe_emcy")[0], 1613);
    // Every event row names its slave.
    assert!(page.elements.iter().any(|e| e.tag == "tr"
        && e.get("data-slave") == Some("4097")
        && e.num("data-line") == 712));
}

/// The charts of each slave of the drives capture
/// (docs/report.md#signals): `data-signal` → (`data-points`, `data-min`,
/// `data-max`), by station.
fn charts(page: &Page) -> std::collections::BTreeMap<(u64, String), (u64, f64, f64)> {
    let mut charts = std::collections::BTreeMap::new();
    let mut slave = None;
    for e in &page.elements {
        if e.tag == "svg" {
            slave = e.get("data-slave").map(|s| s.parse::<u64>().unwrap());
        }
        if let (Some(slave), Some("signal")) = (slave, e.get("data-kind")) {
            let num = |key: &str| e.get(key).map_or(f64::NAN, |v| v.parse().unwrap());
            let key = (slave, e.get("data-signal").unwrap().to_owned());
            let old = charts.insert(
                key,
                (e.num("data-points"), num("data-min"), num("data-max")),
            );
            assert!(old.is_none(), "one chart of each signal");
        }
    }
    charts
}

/// The servo's ActPos and speed set point and the drives' position and
/// target position are charted (docs/report.md#signals): a point per cycle
/// (fewer cycles than buckets), ActPos only where the feedback is
/// confirmed, its range holding the model's last ActPos.
#[test]
fn the_servo_and_the_drives_signals_are_charted() {
    let (page, records) = drives_page(&scratch("drives-signals"));
    let charts = charts(&page);
    let slave = |station: u64| {
        records
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["type"] == "slave" && r["slave"] == station)
            .unwrap()
            .clone()
    };
    let servo = slave(0x1001)["servo"].clone();
    let cycles = servo["cycles"].as_u64().unwrap();
    let unconfirmed = servo["unconfirmed"].as_u64().unwrap();
    assert_eq!((cycles, unconfirmed), (999, 1));
    let act_pos = charts[&(0x1001, "act_pos".to_owned())];
    assert_eq!(act_pos.0, cycles - unconfirmed);
    let last = drives_model()
        .iter()
        .rev()
        .find(|r| r["kind"] == "act_pos")
        .unwrap()["value"]
        .as_f64()
        .unwrap();
    assert_eq!(last, 193_600.0);
    assert!(act_pos.1 <= last && last <= act_pos.2, "{act_pos:?}");
    assert_eq!(
        servo["last_position"]["position"].as_f64().unwrap(),
        last,
        "the summary's last ActPos"
    );
    let speed = charts[&(0x1001, "speed_setpoint".to_owned())];
    assert_eq!(speed.0, cycles);
    assert!(speed.1 < 0.0 && speed.2 > 0.0, "{speed:?}");
    // The servo has no CiA 402 chart; the drives theirs, and 6064h from
    // confirmed inputs, 607Ah from every cycle's outputs.
    assert!(!charts.contains_key(&(0x1001, "cia402_state".to_owned())));
    for station in [0x1002, 0x1003] {
        let record = slave(station);
        let cycles = record["process_cycles"].as_u64().unwrap();
        let unconfirmed = record["process_unconfirmed"].as_u64().unwrap();
        let state = charts[&(station, "cia402_state".to_owned())];
        assert_eq!(
            state.0,
            record["cia402"]["transition_count"].as_u64().unwrap()
        );
        let position = charts[&(station, "6064".to_owned())];
        assert_eq!(position.0, cycles - unconfirmed, "6064h of {station}");
        let target = charts[&(station, "607a".to_owned())];
        assert_eq!(target.0, cycles, "607Ah of {station}");
        assert!(target.1 < target.2, "607Ah of {station} moves");
    }
    assert!(page.html.len() < 400_000, "{} bytes", page.html.len());
}

/// A long capture of the same drives (30 000 cycles of
/// tests/common/ecat_drives.rs, as the ecat_drives example writes them): each chart is reduced to at most 1 000 buckets, 2 000 points
/// (docs/report.md#bounded), and the marks still add up.
#[test]
fn a_long_drives_capture_is_charted_in_buckets() {
    let dir = scratch("drives-long");
    let capture = dir.join("long.pcapng");
    let model = dir.join("long.jsonl");
    let eni = dir.join("long.xml");
    ecat_drives::write_files(30_000, &capture, &model, &eni).unwrap();
    let out = dir.join("long.html");
    let args = ["--servo", "0x1001", capture.to_str().unwrap()];
    let r = run(&[&["report"][..], &args, &["-o", out.to_str().unwrap()]].concat());
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let page = parse(&std::fs::read_to_string(&out).unwrap());
    let records = summary_records(&args);
    check_ethercat(&page, &records);
    let charts = charts(&page);
    for signal in ["act_pos", "speed_setpoint"] {
        let (points, lo, hi) = charts[&(0x1001, signal.to_owned())];
        // At most 1 000 buckets, each its minimum and maximum; at least
        // 500 (half the cap, once the width has doubled).
        assert!((500..=2000).contains(&points), "{signal}: {points} points");
        assert!(lo < hi, "{signal}");
    }
    for station in [0x1002, 0x1003] {
        let (points, ..) = charts[&(station, "6064".to_owned())];
        assert!(
            (1000..=2000).contains(&points),
            "6064h of {station}: {points}"
        );
    }
    let last = std::fs::read_to_string(&model)
        .unwrap()
        .lines()
        .rev()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .find(|r| r["kind"] == "act_pos")
        .unwrap()["value"]
        .as_f64()
        .unwrap();
    let (_, lo, hi) = charts[&(0x1001, "act_pos".to_owned())];
    assert!(lo <= last && last <= hi);
    assert!(page.html.len() < 1_000_000, "{} bytes", page.html.len());
}

/// docs/report.md#command: `--from`, `--to`, `--iface`, `--node` and `--id`
/// make the page of the frames kept: its records are `decode --summary`'s
/// of those frames; `--only` is refused.
#[test]
fn the_page_of_the_frames_kept() {
    let dir = scratch("kept");
    let sample = repo("samples/machine.log");
    let page = |args: &[&str]| {
        let out = dir.join("page.html");
        let mut all = vec!["report"];
        all.extend_from_slice(args);
        all.extend([sample.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        let r = run(&all);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        parse(&std::fs::read_to_string(out).unwrap())
    };
    let window = ["--from", "2", "--to", "6.5", "--iface", "can0"];
    let mut summary_args = window.to_vec();
    summary_args.push(sample.to_str().unwrap());
    let windowed = page(&window);
    assert_eq!(windowed.summary(), summary_records(&summary_args));
    check_counts(&windowed, &summary_records(&summary_args));
    assert_ne!(
        windowed.summary(),
        summary_records(&[sample.to_str().unwrap()])
    );

    let node3 = page(&["--node", "3"]);
    let nodes: Vec<u64> = node3
        .summary()
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["type"] == "node")
        .map(|r| r["node"].as_u64().unwrap())
        .collect();
    assert_eq!(nodes, [3]);
    let ids = page(&["--id", "0x083,0x703"]);
    let frames: Vec<Value> = ids
        .summary()
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["type"] == "node")
        .map(|r| r["frames"].clone())
        .collect();
    assert_eq!(frames.len(), 1);
    let counted: Vec<&String> = frames[0]
        .as_object()
        .unwrap()
        .iter()
        .filter(|(_, n)| n.as_u64() != Some(0))
        .map(|(kind, _)| kind)
        .collect();
    assert_eq!(counted, ["emcy", "heartbeat"]);

    let refused = run(&[
        "report",
        "--only",
        "emcy",
        sample.to_str().unwrap(),
        "-o",
        "-",
    ]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("report takes no --only"));
}
