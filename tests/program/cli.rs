//! Integration tests of the `motionwire` program: they run the built binary
//! on files and standard input and check its output against docs/output.md.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

use serde_json::{json, Value};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_motionwire"))
}

/// Run the program with `args`, feeding `stdin`.
fn run(args: &[&str], stdin: &str) -> Output {
    let mut child = bin()
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the motionwire binary runs");
    // A program that refuses its arguments exits without reading its input:
    // the pipe may then be closed before everything is written.
    match child.stdin.take().unwrap().write_all(stdin.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        other => other.unwrap(),
    }
    child.wait_with_output().unwrap()
}

fn stdout(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8(out.stderr.clone()).unwrap()
}

/// Parse every stdout line as JSON.
fn records(out: &Output) -> Vec<Value> {
    stdout(out)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

/// The summary's node records (docs/summary.md#node), without the bus records
/// that follow them.
fn node_records(out: &Output) -> Vec<Value> {
    let all = records(out);
    let nodes: Vec<Value> = all
        .iter()
        .filter(|r| r["type"] == "node")
        .cloned()
        .collect();
    // The verdict when something stopped, then the node records, then one
    // bus record per interface.
    let verdicts = usize::from(all.first().is_some_and(|r| r["type"] == "verdict"));
    assert!(all[..verdicts + nodes.len()]
        .iter()
        .skip(verdicts)
        .all(|r| r["type"] == "node"));
    assert!(all[verdicts + nodes.len()..]
        .iter()
        .all(|r| r["type"] == "bus"));
    nodes
}

/// Write `text` to a fresh file in the target directory and return its path.
fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

const FORMATS: &str = "\
(1700000000.000500) can0 081#1081110000000000 R
(1700000000.000600) can0 701#R
(1700000000.000700) can0 18FF1234#0102
(1700000000.000800) can0 123##1AABB
  can0  085   [8]  10 81 11 00 00 00 00 00
  can0  705   [1]  remote request
  can0  000   [2]  01 00
(1.5) vcan1 080#
(1.5) can0 581#4300100000000000
(1.5) can0 77F#FF
(1.5) can0 100#
(1.5) can0 283#00
";

#[test]
fn every_format_and_kind_as_json() {
    let out = run(&["decode", "--json"], FORMATS);
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    assert_eq!(recs.len(), 12);
    let common: Vec<_> = recs
        .iter()
        .map(|r| {
            (
                r["line"].as_u64().unwrap(),
                r["id"].as_u64().unwrap(),
                r["kind"].as_str().unwrap().to_owned(),
                r["extended"].as_bool().unwrap(),
                r["rtr"].as_bool().unwrap(),
                r["fd"].as_bool().unwrap(),
                r["data"].as_str().unwrap().to_owned(),
            )
        })
        .collect();
    let expected: Vec<(u64, u64, &str, bool, bool, bool, &str)> = vec![
        (1, 0x081, "emcy", false, false, false, "1081110000000000"),
        (2, 0x701, "guard_request", false, true, false, ""),
        (3, 0x18FF1234, "other", true, false, false, "0102"),
        (4, 0x123, "other", false, false, true, "aabb"),
        (5, 0x085, "emcy", false, false, false, "1081110000000000"),
        (6, 0x705, "guard_request", false, true, false, ""),
        (7, 0x000, "nmt_command", false, false, false, "0100"),
        (8, 0x080, "sync", false, false, false, ""),
        (9, 0x581, "sdo", false, false, false, "4300100000000000"),
        (10, 0x77F, "heartbeat", false, false, false, "ff"),
        // docs/canopen.md#identifiers: identifier 0x100 is `time`.
        (11, 0x100, "time", false, false, false, ""),
        (12, 0x283, "pdo", false, false, false, "00"),
    ];
    for (got, want) in common.iter().zip(&expected) {
        assert_eq!(
            (
                got.0,
                got.1,
                got.2.as_str(),
                got.3,
                got.4,
                got.5,
                got.6.as_str()
            ),
            *want
        );
    }
    // Timestamps, interfaces and nodes.
    assert_eq!(recs[0]["ts"].as_f64(), Some(1_700_000_000.000_5));
    assert_eq!(recs[0]["iface"], "can0");
    assert_eq!(recs[4]["ts"], Value::Null);
    assert_eq!(recs[7]["iface"], "vcan1");
    assert_eq!(recs[7]["ts"].as_f64(), Some(1.5));
    let nodes: Vec<_> = recs.iter().map(|r| r.get("node").cloned()).collect();
    assert_eq!(
        nodes,
        [
            Some(json!(1)),
            Some(json!(1)),
            None,
            None,
            Some(json!(5)),
            Some(json!(5)),
            None,
            None,
            Some(json!(1)),
            Some(json!(127)),
            None,
            Some(json!(3)),
        ]
    );
    // The EMCY keys (docs/output.md#emcy).
    let emcy = &recs[0];
    assert_eq!(emcy["code"], 0x8110);
    assert_eq!(emcy["class"], "monitoring");
    assert_eq!(emcy["description"], "CAN overrun (objects lost)");
    assert_eq!(emcy["register"], 0x11);
    assert_eq!(emcy["register_flags"], json!(["generic", "communication"]));
    assert_eq!(emcy["manufacturer"], "0000000000");
    assert!(emcy.get("axis").is_none() && emcy.get("alarms").is_none());
    // The heartbeat keys: bit 7 is the toggle, masked off in state_raw.
    assert_eq!(recs[9]["state"], "pre_operational");
    assert_eq!(recs[9]["state_raw"], 0x7F);
    assert_eq!(recs[9]["toggle"], true);
}

#[test]
fn frames_that_cannot_be_decoded_as_their_kind_carry_an_error() {
    let out = run(
        &["decode", "--json"],
        "(1.0) can0 081#1081\n(1.0) can0 701#\n(1.0) can0 702#12\n",
    );
    assert!(out.status.success());
    let recs = records(&out);
    assert_eq!(recs[0]["kind"], "emcy");
    assert_eq!(
        recs[0]["error"],
        "EMCY frame: buffer of 2 bytes where 8 are needed"
    );
    // docs/output.md#emcy: a short EMCY still gets `code` from its 2 bytes, no
    // `register` without a third.
    assert_eq!(recs[0]["code"], 0x8110);
    assert!(recs[0].get("register").is_none());
    assert_eq!(recs[1]["kind"], "heartbeat");
    assert!(recs[1]["error"]
        .as_str()
        .unwrap()
        .contains("0 bytes where 1"));
    // 0x12 is not an NMT state: decoded, reported as invalid.
    assert_eq!(recs[2]["state"], "invalid");
    assert_eq!(recs[2]["state_raw"], 0x12);
}

#[test]
fn profiles() {
    let log = "\
(1.0) can0 083#0573012100000000
(1.1) can0 083#0000002100000000
(1.2) can0 083#0573017100000000
(1.3) can0 085#01FF010180000000
(1.4) can0 085#0051000000080000
";
    let akd = records(&run(&["decode", "--json", "--profile", "akd"], log));
    assert_eq!(
        (&akd[0]["axis"], &akd[0]["feedback"]),
        (&json!(1), &json!(2))
    );
    // The reset EMCY still carries the axis and feedback ids
    // (docs/canopen.md#akd).
    assert_eq!(
        (&akd[1]["axis"], &akd[1]["feedback"]),
        (&json!(1), &json!(2))
    );
    // Feedback nibble 7 is invalid: reported, not guessed.
    assert_eq!(akd[2]["feedback"], Value::Null);
    assert!(akd[2]["error"].as_str().unwrap().contains("feedback"));
    assert!(akd[3].get("alarms").is_none());

    let baumer = records(&run(&["decode", "--json", "--profile", "baumer"], log));
    assert_eq!(baumer[3]["alarms"], 0x8001);
    assert_eq!(baumer[3]["warnings"], 0);
    assert_eq!(
        baumer[3]["sources"],
        json!(["battery_monitoring_error_startup"])
    );
    // 0x5100 at runtime: 6505h bit 3 tells it from the startup row.
    assert_eq!(baumer[4]["warnings"], 0x0008);
    assert_eq!(
        baumer[4]["sources"],
        json!(["non_volatile_data_manager_runtime"])
    );
    assert!(baumer[0].get("axis").is_none());
}

/// A crafted log whose summary is worked out by hand in the comments.
const SUMMARY_LOG: &str = "\
(100.000000) can0 705#00
(100.100000) can0 705#05
(100.200000) can0 085#1042090000000000
(100.300000) can0 085#1023020000000000
(100.400000) can0 705#05
(101.000000) can0 705#05
(101.100000) can0 085#0000000000000000
(101.200000) can0 085#1081110000000000
(101.300000) can0 70A#R
(101.301000) can0 70A#05
(101.400000) can0 70A#R
(101.401000) can0 70A#85
(101.500000) can0 70A#R
(101.501000) can0 70A#85
(101.600000) can0 70A#R
(101.601000) can0 70A#05
(101.700000) can0 70A#00
(101.800000) can0 70A#R
(101.801000) can0 70A#85
(103.000000) can0 705#05
(103.100000) can0 181#0102
";

#[test]
fn summary_keys_on_a_crafted_log() {
    let path = temp_file("summary.log", SUMMARY_LOG);
    let out = run(
        &[
            "decode",
            "--summary",
            "--json",
            "--heartbeat-ms",
            "500",
            path.to_str().unwrap(),
        ],
        "",
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = node_records(&out);
    let nodes: Vec<_> = recs.iter().map(|r| r["node"].as_u64().unwrap()).collect();
    assert_eq!(nodes, [1, 5, 10]);

    let n1 = &recs[0];
    assert_eq!(n1["frames"]["pdo"], 1);
    assert_eq!(n1["emcy"], 0);
    assert_eq!(n1["first_error"], Value::Null);
    assert_eq!(n1["active_error"], Value::Null);
    assert_eq!(n1["heartbeat"]["last_state"], Value::Null);

    let n5 = &recs[1];
    assert_eq!(
        n5["frames"],
        json!({"emcy": 4, "heartbeat": 5, "guard_request": 0, "guard_answer": 0,
               "nmt_command": 0, "sync": 0, "time": 0, "pdo": 0, "sdo": 0, "error_frame": 0,
               "other": 0})
    );
    assert_eq!(n5["emcy"], 4);
    assert_eq!(n5["resets"], 1);
    // The first error stays the first; the root cause (0x4210) was kept over
    // 0x2310 until the reset on line 7; 0x8110 on line 8 is the new slot.
    assert_eq!(
        n5["first_error"],
        json!({"line": 3, "ts": 100.2, "code": 0x4210,
               "description": "Excess device temperature"})
    );
    assert_eq!(
        n5["active_error"],
        json!({"line": 8, "ts": 101.2, "code": 0x8110,
               "description": "CAN overrun (objects lost)"})
    );
    assert_eq!(n5["type"], "node");
    assert_eq!(n5["iface"], "can0");
    assert_eq!(n5["heartbeat"]["count"], 5);
    assert_eq!(n5["heartbeat"]["last_state"], "operational");
    assert_eq!(n5["heartbeat"]["boot_ups"], json!([1]));
    // Gaps above 500 ms: 600 ms after line 5, 2000 ms after line 6.
    assert_eq!(
        n5["heartbeat"]["timeouts"],
        json!([{"after_line": 5, "gap_ms": 600.0}, {"after_line": 6, "gap_ms": 2000.0}])
    );
    assert_eq!(
        n5["guarding"],
        json!({"answers": 0, "toggle_errors": [], "toggle_error_count": 0})
    );

    let n10 = &recs[2];
    assert_eq!(n10["frames"]["guard_request"], 5);
    // Five answers and the boot-up: the answers are counted as such.
    assert_eq!(n10["frames"]["heartbeat"], 1);
    assert_eq!(n10["frames"]["guard_answer"], 5);
    // Guarding answers are not heartbeats; the boot-up on line 17 is.
    assert_eq!(n10["heartbeat"]["count"], 1);
    assert_eq!(n10["heartbeat"]["boot_ups"], json!([17]));
    assert_eq!(n10["heartbeat"]["timeouts"], json!([]));
    // Line 10 sets the baseline (no boot-up before it); line 14 repeats the
    // toggle of line 12; line 19 is the first answer after the boot-up on
    // line 17 and must carry toggle 0.
    assert_eq!(
        n10["guarding"],
        json!({"answers": 5, "toggle_errors": [14, 19], "toggle_error_count": 2})
    );
    // The last frame that tells node 10's state is the answer on line 19.
    assert_eq!(n10["heartbeat"]["last_state"], "operational");
}

/// docs/output.md#heartbeat: a node-guarding answer is its own kind in every
/// form, with its state and toggle, and `--only` keeps it.
#[test]
fn a_guarding_answer_is_its_own_kind() {
    let path = temp_file("guarding.log", SUMMARY_LOG);
    let path = path.to_str().unwrap();
    let out = run(&["decode", "--json", "--only", "guard_answer", path], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    let lines: Vec<_> = recs.iter().map(|r| r["line"].as_u64().unwrap()).collect();
    assert_eq!(lines, [10, 12, 14, 16, 19]);
    assert_eq!(
        (&recs[1]["kind"], &recs[1]["state"], &recs[1]["toggle"]),
        (&json!("guard_answer"), &json!("operational"), &json!(true))
    );
    // The boot-up between the answers stays a heartbeat.
    let out = run(
        &[
            "decode",
            "--json",
            "--only",
            "heartbeat",
            "--node",
            "10",
            path,
        ],
        "",
    );
    let lines: Vec<_> = records(&out)
        .iter()
        .map(|r| r["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, [17]);
    let text = stdout(&run(&["decode", "--only", "guard_answer", path], ""));
    let second = text.lines().nth(1).unwrap();
    assert!(
        second.contains("70A  guard_answer   node  10  operational, toggle 1"),
        "{second}"
    );
    let csv = stdout(&run(
        &["decode", "--csv", "--only", "guard_answer", path],
        "",
    ));
    assert!(
        csv.lines()
            .nth(2)
            .unwrap()
            .contains(",85,guard_answer,10,,"),
        "{csv}"
    );
}

#[test]
fn summary_timeout_runs_to_the_end_of_the_input_and_needs_the_option() {
    let log = "(10.0) can0 705#05\n(10.1) can0 705#05\n(12.6) can0 085#0000000000000000\n";
    let recs = records(&run(
        &["decode", "--summary", "--json", "--heartbeat-ms", "1000"],
        log,
    ));
    // The lost node stops: the verdict first.
    assert_eq!(recs[0]["stop"]["kind"], "heartbeat_timeout");
    assert_eq!(
        recs[1]["heartbeat"]["timeouts"],
        json!([{"after_line": 2, "gap_ms": 2500.0}])
    );
    let recs = records(&run(&["decode", "--summary", "--json"], log));
    assert!(recs[0]["heartbeat"].get("timeouts").is_none());
    let out = run(&["decode", "--heartbeat-ms", "100"], log);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn summary_as_text() {
    let out = run(&["decode", "--summary"], SUMMARY_LOG);
    assert!(out.status.success());
    let text = stdout(&out);
    assert!(text.contains("node   5"), "{text}");
    assert!(text.contains("first error: 0x4210"), "{text}");
    assert!(text.contains("wrong toggle at lines 14, 19"), "{text}");
}

#[test]
fn malformed_lines_are_reported_and_decoding_goes_on() {
    let log =
        "(1.0) can0 081#1081110000000000\nnot a frame\n\n(1.0) can0 800#00\n(1.0) can0 705#05\n";
    let path = temp_file("malformed.log", log);
    let out = run(&["decode", "--json", path.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1));
    let recs = records(&out);
    let lines: Vec<_> = recs.iter().map(|r| r["line"].as_u64().unwrap()).collect();
    assert_eq!(lines, [1, 5]);
    let err = stderr(&out);
    let name = path.display().to_string();
    assert!(
        err.contains(&format!("{name}:2: candump line, column 5")),
        "{err}"
    );
    assert!(
        err.contains(&format!("{name}:4: candump line, column 12")),
        "{err}"
    );
    assert!(err.contains("2 malformed lines skipped"), "{err}");
}

#[test]
fn exit_statuses_for_files_and_arguments() {
    let out = run(&["decode", "/nonexistent/motionwire.log"], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("/nonexistent/motionwire.log"));
    assert_eq!(
        run(&["decode", "--profile", "nope"], "").status.code(),
        Some(2)
    );
    assert_eq!(
        run(&["decode", "--only", "nope"], "").status.code(),
        Some(2)
    );
    assert_eq!(run(&["frobnicate"], "").status.code(), Some(2));
    let ok = run(&["decode"], "");
    assert_eq!(ok.status.code(), Some(0));
    assert!(ok.stdout.is_empty());
}

#[test]
fn standard_input_files_and_dash() {
    let a = temp_file("a.log", "(1.0) can0 705#05\n");
    let out = run(
        &["decode", "--json", a.to_str().unwrap(), "-"],
        "(2.0) can0 706#7F\n",
    );
    assert!(out.status.success());
    let recs = records(&out);
    assert_eq!(recs.len(), 2);
    assert_eq!((&recs[0]["node"], &recs[0]["line"]), (&json!(5), &json!(1)));
    // Line numbers restart in each input.
    assert_eq!((&recs[1]["node"], &recs[1]["line"]), (&json!(6), &json!(1)));
}

#[test]
fn only_keeps_the_named_kinds() {
    let recs = records(&run(&["decode", "--json", "--only", "emcy,sync"], FORMATS));
    let kinds: Vec<_> = recs.iter().map(|r| r["kind"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["emcy", "emcy", "sync"]);
}

#[test]
fn text_mode_is_one_aligned_line_per_frame() {
    let out = run(&["decode"], FORMATS);
    assert!(out.status.success());
    let text = stdout(&out);
    let lines: Vec<_> = text.lines().collect();
    assert_eq!(lines.len(), 12);
    assert!(lines[0].contains("0x8110 monitoring: CAN overrun (objects lost)"));
    assert!(lines[0].contains("[generic, communication]"));
    assert!(lines[1].contains("remote request"));
    // The kind column starts at the same place on every line.
    let col = lines[0].find("emcy").unwrap();
    assert_eq!(lines[6].find("nmt_command"), Some(col));
    assert_eq!(lines[2].find("other"), Some(col));
}

#[test]
fn servo_command_json() {
    let out = run(
        &["servo", "command", "--json", "e8030000 96140000 ffff"],
        "",
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let v: Value = serde_json::from_str(stdout(&out).trim()).unwrap();
    assert_eq!(
        v,
        json!({
            "speed_setpoint": 1000,
            "speed_setpoint_word": 1000,
            "control": 0x1496,
            "control_flags": ["EMGON", "Brake", "ExtPRMTBL"],
            "servo_enable": 2,
            "regulator_mode": "position",
            "parameter_table": 6,
            "extra_data_code": -1
        })
    );
}

#[test]
fn servo_feedback_json() {
    let hex = "40e20100 00100000 0f000000 01000800 00000000 0080bb44 \
               00000000 0000c07f 0000803f 000020c0";
    let out = run(&["servo", "feedback", "--json", hex], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let v: Value = serde_json::from_str(stdout(&out).trim()).unwrap();
    assert_eq!(
        v,
        json!({
            "position": (4096i64 << 32) + 123_456,
            "encoder": "incremental",
            "incremental_position": 123_456,
            "zero_pulse_position": 4096,
            "status": 0xF,
            "status_flags": ["ServoEn", "ServoRDY", "AbsIncr", "ZPulseAck"],
            "parameter_table": 1,
            "errors": 0x80001,
            "faults": [
                {"bit": 0, "name": "ServoErrors", "e_code": null},
                {"bit": 19, "name": "FollowerErr", "e_code": "E09"}
            ],
            "message_code": 0,
            "message": "motor_speed",
            "message_value": 1500.0,
            "extra": [0.0, null, 1.0, -2.5]
        })
    );
}

#[test]
fn servo_absolute_encoder_and_text() {
    let hex = format!("{}{}", "ffffffffffffffff", "0".repeat(64));
    let v: Value =
        serde_json::from_str(stdout(&run(&["servo", "feedback", "--json", &hex], "")).trim())
            .unwrap();
    assert_eq!(v["position"], -1);
    assert_eq!(v["encoder"], "absolute");
    assert_eq!(v["incremental_position"], Value::Null);
    assert_eq!(v["zero_pulse_position"], Value::Null);
    let text = stdout(&run(&["servo", "command", "00000000 00000000 0000"], ""));
    assert!(
        text.contains("emergency       active (EMGON = 0)"),
        "{text}"
    );
}

#[test]
fn servo_bad_hex_or_length_is_exit_2() {
    let out = run(&["servo", "command", "e80300000000000000zz"], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("not a hex digit"), "{}", stderr(&out));
    let out = run(&["servo", "feedback", "00112233"], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("needs 80 hex digits (40 bytes), found 8"),
        "{}",
        stderr(&out)
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn sample_log_summary_matches_its_ground_truth() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let log = root.join("samples/machine.log");
    let truth: Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("samples/machine.truth.json")).unwrap(),
    )
    .unwrap();
    let out = run(
        &[
            "decode",
            "--summary",
            "--json",
            "--heartbeat-ms",
            "300",
            log.to_str().unwrap(),
        ],
        "",
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = node_records(&out);
    for rec in &recs {
        let node = rec["node"].as_u64().unwrap().to_string();
        let Some(t) = truth["nodes"].get(&node) else {
            continue;
        };
        for (kind, count) in t["frames"].as_object().unwrap() {
            assert_eq!(&rec["frames"][kind], count, "node {node} {kind}");
        }
        assert_eq!(rec["emcy"], t["emcy"]["count"], "node {node}");
        assert_eq!(rec["resets"], t["emcy"]["resets"], "node {node}");
        assert_eq!(
            rec["first_error"]["line"], t["emcy"]["first_error"]["line"],
            "node {node}"
        );
        let slot = &t["emcy"]["slot_at_end"];
        if slot["state"] == "error" {
            assert_eq!(rec["active_error"]["line"], slot["line"], "node {node}");
            assert_eq!(rec["active_error"]["code"], slot["code"], "node {node}");
        } else {
            assert_eq!(rec["active_error"], Value::Null, "node {node}");
        }
        assert_eq!(
            rec["heartbeat"]["boot_ups"], t["boot_up_lines"],
            "node {node}"
        );
        // The last frame that tells the state: node 10's guarding answers.
        assert_eq!(
            rec["heartbeat"]["last_state"], t["last_state"],
            "node {node}"
        );
        let sdo = &t["sdo"];
        assert_eq!(rec["sdo"]["requests"], sdo["requests"], "node {node}");
        assert_eq!(rec["sdo"]["transfers"], sdo["transfers"], "node {node}");
        let aborts: Vec<Value> = rec["sdo"]["aborts"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| {
                json!({"line": a["line"], "index": a["index"], "subindex": a["subindex"],
                            "code": a["code"], "by": a["by"]})
            })
            .collect();
        assert_eq!(&Value::from(aborts), &sdo["aborts"], "node {node}");
        assert_eq!(rec["sdo"]["broken"], json!([]), "node {node}");
        assert_eq!(rec["sdo"]["timeouts"], json!([]), "node {node}");
        if !t["guarding"].is_null() {
            assert_eq!(
                rec["guarding"]["toggle_errors"], t["guarding"]["wrong_toggle_lines"],
                "node {node}"
            );
            assert_eq!(rec["guarding"]["answers"], t["guarding"]["answers"]);
        }
    }
    // Node 5 went silent: one heartbeat gap, at the line the truth names.
    let n5 = recs.iter().find(|r| r["node"] == 5).unwrap();
    let gap = &truth["nodes"]["5"]["heartbeat_gaps"][0];
    assert_eq!(
        n5["heartbeat"]["timeouts"][0]["after_line"],
        gap["line_before"]
    );
    assert_eq!(n5["heartbeat"]["timeouts"][0]["gap_ms"], gap["gap_ms"]);
}

#[test]
fn a_closed_pipe_ends_quietly() {
    // Enough frames that the program is still writing when the reader goes.
    let log: String = (0..200_000)
        .map(|i| {
            format!(
                "({}.{:06}) can0 705#05\n",
                1000 + i / 1000,
                (i % 1000) * 1000
            )
        })
        .collect();
    let path = temp_file("pipe.log", &log);
    let mut child = bin()
        .args(["decode", path.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 64];
    std::io::Read::read_exact(&mut stdout, &mut first).unwrap();
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(stderr(&out), "");
}

#[test]
fn profiles_per_node() {
    let log = "(1.0) can0 083#0573012100000000\n(1.3) can0 085#01FF010180000000\n(1.4) can0 08A#3081110000000000\n";
    let recs = records(&run(
        &["decode", "--json", "--profile", "3=akd,5=baumer"],
        log,
    ));
    assert_eq!(recs[0]["axis"], 1);
    assert!(recs[0].get("alarms").is_none());
    assert_eq!(recs[1]["alarms"], 0x8001);
    assert!(recs[1].get("axis").is_none());
    // Node 10 is not named: the default, generic.
    assert!(recs[2].get("axis").is_none() && recs[2].get("alarms").is_none());
    // A bare profile is the default for the nodes not named.
    let recs = records(&run(
        &["decode", "--json", "--profile", "akd,5=baumer"],
        log,
    ));
    assert_eq!(recs[2]["axis"], 0);
    assert_eq!(recs[1]["warnings"], 0);
    for bad in ["0=akd", "128=akd", "x=akd", "3=nope"] {
        let out = run(&["decode", "--profile", bad], log);
        assert_eq!(out.status.code(), Some(2), "{bad}");
    }
}

/// docs/formats.md#error-frames and docs/output.md#error-frame: error frames
/// (candump -e, python-can) are frames of kind `error_frame` with their
/// classes, controller status and counters; candump's explanation lines after a
/// screen error frame are not malformed.
#[test]
fn error_frames_are_frames_with_their_keys() {
    let log = "\
(1700000000.000100) can0 20000004#0020000000000000
(1700000000.000200) can0 20000248#0000081900008005
(1700000000.000300) vcan0 20000080#
  can0  20000040   [8]  00 00 00 00 00 00 00 00   ERRORFRAME
\tbus-off
";
    let out = run(&["decode", "--json"], log);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let recs = records(&out);
    assert_eq!(recs.len(), 4);
    for rec in &recs {
        assert_eq!(rec["kind"], "error_frame");
        assert_eq!(rec["extended"], true);
        assert!(rec.get("node").is_none());
    }
    assert_eq!(recs[0]["id"], 0x004);
    assert_eq!(recs[0]["error_classes"], json!(["controller"]));
    assert_eq!(recs[0]["controller"], json!(["tx_passive"]));
    assert_eq!(recs[0]["tx_errors"], Value::Null);
    assert_eq!(
        recs[1]["error_classes"],
        json!(["protocol", "bus_off", "counters"])
    );
    assert_eq!(recs[1]["controller"], json!([]));
    assert_eq!(
        (recs[1]["tx_errors"].clone(), recs[1]["rx_errors"].clone()),
        (json!(0x80), json!(5))
    );
    assert_eq!(recs[2]["error_classes"], json!(["bus_error"]));
    assert_eq!(recs[2]["data"], "");
    assert_eq!(recs[3]["error_classes"], json!(["bus_off"]));
    assert_eq!(recs[3]["line"], 4);

    let text = run(&["decode"], log);
    assert!(stdout(&text).contains("error frame: controller (tx_passive)"));
}

/// docs/formats.md#timestamps, docs/summary.md#heartbeat: a log without
/// timestamps cannot be checked for heartbeat timeouts: `timeouts` is null,
/// the text says so, and standard error says it once — never "no timeouts".
#[test]
fn without_timestamps_timeouts_are_not_checked() {
    let log = "can0 705#05\ncan0 705#05\ncan0 706#05\n";
    let out = run(
        &["decode", "--summary", "--json", "--heartbeat-ms", "100"],
        log,
    );
    assert!(out.status.success());
    let recs = node_records(&out);
    assert_eq!(recs.len(), 2);
    for rec in &recs {
        assert_eq!(rec["heartbeat"]["timeouts"], Value::Null);
    }
    assert_eq!(stderr(&out).matches("timeouts were not checked").count(), 1);
    let text = run(&["decode", "--summary", "--heartbeat-ms", "100"], log);
    assert!(stdout(&text).contains("timeouts not checked (no timestamps)"));
    assert!(!stdout(&text).contains("no timeouts"));
    // With timestamps they are checked.
    let timed = run(
        &["decode", "--summary", "--json", "--heartbeat-ms", "100"],
        "(1.0) can0 705#05\n(1.05) can0 705#05\n",
    );
    assert_eq!(records(&timed)[0]["heartbeat"]["timeouts"], json!([]));
    assert!(stderr(&timed).is_empty());
}

/// An output of many blocks (docs/output.md#writing): through a pipe and
/// into a file, where a thread of its own writes it, the same bytes, every
/// record once and in the order of the log; the text and CSV too.
#[test]
fn a_large_output_is_written_whole_and_in_order() {
    let lines = 60_000;
    let log: String = (0..lines)
        .map(|i| {
            format!(
                "({}.{:06}) can0 18{}#{:016X}\n",
                1000 + i / 1000,
                (i % 1000) * 1000,
                i % 10,
                i
            )
        })
        .collect();
    let path = temp_file("large-output.log", &log);
    let file = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests/large-output.out");
    for format in ["--json", "--csv", "--text"] {
        let args: Vec<&str> = ["decode", path.to_str().unwrap()]
            .into_iter()
            .chain((format != "--text").then_some(format))
            .collect();
        let piped = bin().args(&args).output().unwrap();
        assert!(piped.status.success(), "{}", stderr(&piped));
        let status = bin()
            .args(&args)
            .stdout(std::fs::File::create(&file).unwrap())
            .status()
            .unwrap();
        assert!(status.success());
        let written = std::fs::read(&file).unwrap();
        assert!(
            written.len() > 3 << 20,
            "{format}: {} bytes, fewer than 3 blocks",
            written.len()
        );
        assert!(
            written == piped.stdout,
            "{format}: the file and the pipe differ"
        );
        if format == "--json" {
            for (i, record) in written
                .split(|&b| b == b'\n')
                .filter(|r| !r.is_empty())
                .enumerate()
            {
                let value: Value = serde_json::from_slice(record).unwrap();
                assert_eq!(value["line"], i + 1);
            }
        }
    }
}

/// docs/output.md#live, live use: `candump -L can0 | motionwire decode --json
/// -` prints each record as soon as its line arrives, while the input is still
/// open.
#[test]
fn a_pipe_is_decoded_live() {
    use std::io::{BufRead, BufReader};
    use std::sync::mpsc;
    use std::time::Duration;

    let mut child = bin()
        .args(["decode", "--json", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the motionwire binary runs");
    let mut stdin = child.stdin.take().unwrap();
    let stdout = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines() {
            if tx.send(line.unwrap()).is_err() {
                break;
            }
        }
    });
    for (i, frame) in ["(1.0) can0 705#05", "(1.1) can0 085#1081110000000000"]
        .into_iter()
        .enumerate()
    {
        stdin.write_all(format!("{frame}\n").as_bytes()).unwrap();
        stdin.flush().unwrap();
        // The record comes while stdin is still open.
        let record = rx
            .recv_timeout(Duration::from_secs(20))
            .unwrap_or_else(|_| panic!("no record for line {} while the pipe is open", i + 1));
        let value: Value = serde_json::from_str(&record).unwrap();
        assert_eq!(value["line"], i + 1);
    }
    drop(stdin);
    assert!(child.wait().unwrap().success());
    reader.join().unwrap();
}

/// A log written by python-can's `CanutilsLogWriter`
/// (tests/codecs/python_can.rs checks it frame by frame against python-can's
/// reader) decodes without a malformed line, its error frame as
/// `error_frame`.
#[test]
fn a_python_can_log_decodes() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/python_can.log");
    let out = bin().args(["decode", "--json", path]).output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let kinds: Vec<String> = records(&out)
        .iter()
        .map(|r| r["kind"].as_str().unwrap().to_owned())
        .collect();
    assert_eq!(
        kinds,
        [
            "emcy",
            "heartbeat",
            "guard_request",
            "other",
            "pdo",
            "pdo",
            "error_frame",
            "other",
            "sdo"
        ]
    );
}

// ------------------------------------------------- issue 11: inputs, shapes

/// docs/formats.md#detection: a file that is none of the formats is one clear
/// error and exit status 2, not one error per line.
#[test]
fn an_unrecognised_file_is_one_error() {
    let text = "Hello, world!\nThis is not a CAN log.\nNor is this.\n";
    let out = run(&["decode", "--json"], text);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("unrecognised log format"), "{err}");
    // Blank and comment lines only: nothing to read, nothing wrong.
    let empty = run(&["decode", "--json"], "\n# nothing yet\n\n");
    assert_eq!(empty.status.code(), Some(0));
    assert!(empty.stdout.is_empty());
    // ... but said (issue 22): an empty input is not silently nothing,
    // with or without the summary.
    assert_eq!(stderr(&empty), "<stdin>: 0 frames\n");
    let summary = run(&["decode", "--summary"], "");
    assert_eq!(summary.status.code(), Some(0));
    assert!(summary.stdout.is_empty());
    assert_eq!(stderr(&summary), "<stdin>: 0 frames\n");
}

/// The decision in docs/formats.md#detection: random bytes never pass for a
/// log. One MiB of them (a fixed seed; issue 20: a line starting with `;` made
/// it a PEAK TRC file, read as 4 068 line errors and exit status 1) is one
/// "unrecognised log format" and exit status 2; so are they with every NUL
/// replaced, and a TRC header comment alone reads as nothing.
#[test]
fn random_bytes_are_one_unrecognised_error() {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut bytes = vec![0u8; 1 << 20];
    for b in &mut bytes {
        // splitmix64
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        *b = (z ^ (z >> 31)) as u8;
    }
    let no_nul: Vec<u8> = bytes.iter().map(|&b| b.max(1)).collect();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, data) in [("random.bin", &bytes), ("random_no_nul.bin", &no_nul)] {
        let path = dir.join(name);
        std::fs::write(&path, data).unwrap();
        let out = run(&["decode", path.to_str().unwrap()], "");
        assert_eq!(out.status.code(), Some(2), "{name}");
        assert!(out.stdout.is_empty(), "{name}");
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.contains("unrecognised log format"), "{name}: {err}");
    }
    let header = run(
        &["decode", "--json"],
        ";##########\n;   Start time: 12.08.2017 22:06:05.155.0\n",
    );
    assert_eq!(header.status.code(), Some(0), "{}", stderr(&header));
    assert!(header.stdout.is_empty());
    assert_eq!(stderr(&header), "<stdin>: 0 frames\n");
}

/// docs/formats.md#gzip: a gzip-compressed log is read as the log inside it,
/// detected by content whatever the file is called.
#[test]
fn gzip_input_is_detected_by_content() {
    use flate2::write::GzEncoder;
    let log = "(1700000000.000500) can0 081#1081110000000000\n\
               (1700000000.001000) can0 705#05\n";
    let mut gz = GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(log.as_bytes()).unwrap();
    let bytes = gz.finish().unwrap();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("compressed.log");
    std::fs::write(&path, &bytes).unwrap();
    let zipped = run(&["decode", "--json", path.to_str().unwrap()], "");
    assert!(zipped.status.success(), "{}", stderr(&zipped));
    let plain = run(&["decode", "--json"], log);
    assert_eq!(stdout(&zipped), stdout(&plain));
    assert_eq!(records(&zipped).len(), 2);
}

/// docs/output.md#csv: `--csv` writes the header row and one RFC 4180 row per
/// frame.
#[test]
fn csv_rows_under_the_header() {
    let log = "(1700000000.000500) can0 081#1081110000000000\n\
               (1700000000.001000) can0 705#05\n\
               \"can,1\" 18FF1234#0102\n";
    let out = run(&["decode", "--csv"], log);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let rows: Vec<&str> = text.split("\r\n").collect();
    assert_eq!(
        rows,
        [
            "line,ts,iface,id,extended,rtr,fd,data,kind,node,code,description",
            "1,1700000000.000500,can0,129,false,false,false,1081110000000000,emcy,1,33040,\
             CAN overrun (objects lost)",
            "2,1700000000.001000,can0,1797,false,false,false,05,heartbeat,5,,",
            // An interface name with a comma and quotes: quoted, quotes doubled.
            "3,,\"\"\"can,1\"\"\",419369524,true,false,false,0102,other,,,",
            "",
        ]
    );
    // --csv and --json exclude each other.
    assert_eq!(
        run(&["decode", "--csv", "--json"], log).status.code(),
        Some(2)
    );
}

/// docs/output.md#filters: `--node` keeps frames that carry one of the
/// node-IDs, `--id` identifiers and ranges; the summary still counts
/// everything.
#[test]
fn node_and_id_filters() {
    let log = "can0 000#0105\ncan0 085#1081110000000000\ncan0 705#05\ncan0 706#05\n\
               can0 185#0102\n";
    let lines = |args: &[&str]| -> Vec<u64> {
        let mut all = vec!["decode", "--json"];
        all.extend_from_slice(args);
        let out = run(&all, log);
        assert!(out.status.success(), "{}", stderr(&out));
        records(&out)
            .iter()
            .map(|r| r["line"].as_u64().unwrap())
            .collect()
    };
    // The NMT command's target (5) is not a node-ID it carries.
    assert_eq!(lines(&["--node", "5"]), [2, 3, 5]);
    assert_eq!(lines(&["--node", "5,6"]), [2, 3, 4, 5]);
    assert_eq!(lines(&["--id", "0x705"]), [3]);
    assert_eq!(lines(&["--id", "0x081-0x0FF,1798"]), [2, 4]);
    assert_eq!(lines(&["--id", "0x700-0x7FF", "--node", "6"]), [4]);
    assert_eq!(
        run(&["decode", "--id", "0x800-0x7FF"], log).status.code(),
        Some(2)
    );
    assert_eq!(
        run(&["decode", "--node", "128"], log).status.code(),
        Some(2)
    );
    let summary = run(&["decode", "--summary", "--json", "--node", "6"], log);
    let nodes: Vec<u64> = node_records(&summary)
        .iter()
        .map(|r| r["node"].as_u64().unwrap())
        .collect();
    assert_eq!(nodes, [5, 6]);
}

/// docs/formats.md#interfaces, docs/summary.md#bus: node 5 on can0 and node 5
/// on can1 are two devices;
/// one bus record per interface with its error frames, bus-off and
/// error-passive lines.
#[test]
fn summary_nodes_per_interface_and_bus_records() {
    let log = "(100.000000) can0 705#05\n\
               (100.100000) can1 705#7F\n\
               (100.200000) can0 085#1081110000000000\n\
               (100.300000) can1 20000040#0000000000000000\n\
               (100.400000) can1 20000004#0020000000000000\n\
               (100.500000) can1 705#05\n";
    let out = run(&["decode", "--summary", "--json"], log);
    assert!(out.status.success(), "{}", stderr(&out));
    let all = records(&out);
    // can1's bus-off stops (docs/summary.md#verdict): the verdict first.
    assert_eq!(all[0]["type"], "verdict");
    assert_eq!(all[0]["stop"]["iface"], "can1");
    assert_eq!(all[0]["stop"]["kind"], "bus_off");
    let recs = &all[1..];
    let keys: Vec<(String, String, u64)> = recs
        .iter()
        .map(|r| {
            (
                r["type"].as_str().unwrap().to_owned(),
                r["iface"].as_str().unwrap().to_owned(),
                r["node"].as_u64().unwrap_or(0),
            )
        })
        .collect();
    assert_eq!(
        keys,
        [
            ("node".to_owned(), "can0".to_owned(), 5),
            ("node".to_owned(), "can1".to_owned(), 5),
            ("bus".to_owned(), "can0".to_owned(), 0),
            ("bus".to_owned(), "can1".to_owned(), 0),
        ]
    );
    assert_eq!(recs[0]["emcy"], 1);
    assert_eq!(recs[0]["last_register"], 0x11);
    assert_eq!(recs[1]["emcy"], 0);
    assert_eq!(recs[1]["last_register"], Value::Null);
    assert_eq!(recs[1]["heartbeat"]["count"], 2);
    assert_eq!(
        recs[2],
        json!({"type": "bus", "iface": "can0", "frames": 2, "error_frames": 0,
               "bus_off": [], "bus_off_count": 0, "error_passive": [],
               "error_passive_count": 0, "status_events": 0,
               "first_ts": 100.0, "last_ts": 100.2, "nodes": [5]})
    );
    assert_eq!(
        recs[3],
        json!({"type": "bus", "iface": "can1", "frames": 4, "error_frames": 2,
               "bus_off": [4], "bus_off_count": 1, "error_passive": [5],
               "error_passive_count": 1, "status_events": 0,
               "first_ts": 100.1, "last_ts": 100.5, "nodes": [5]})
    );
    let text = stdout(&run(&["decode", "--summary"], log));
    assert!(text.contains("can1 node   5"), "{text}");
    assert!(
        text.contains("bus can1  frames 4, error frames 2, bus-off at lines 4"),
        "{text}"
    );
}

/// Memory stays bounded: a line longer than 1 MiB is one error, and the
/// lines after it are read.
#[test]
fn an_overlong_line_is_reported_and_skipped() {
    let mut log = String::from("(1700000000.000500) can0 081#00\n");
    log.push_str(&"x".repeat(3 << 20));
    log.push_str("\n(1700000000.000600) can0 705#05\n");
    let out = run(&["decode", "--json"], &log);
    assert_eq!(out.status.code(), Some(1));
    let lines: Vec<u64> = records(&out)
        .iter()
        .map(|r| r["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, [1, 3]);
    assert!(
        stderr(&out).contains("<stdin>:2: line longer than 1 MiB"),
        "{}",
        stderr(&out)
    );
}

/// docs/formats.md#candump-relative-times: `candump -t d` screen output: the
/// deltas add up, detected or forced with --timestamps.
#[test]
fn delta_timestamps_add_up() {
    let log = " (000.000000)  can0  705   [1]  05\n\
               (000.250000)  can0  705   [1]  05\n\
               (000.100000)  can0  705   [1]  05\n";
    let ts = |args: &[&str]| -> Vec<f64> {
        let mut all = vec!["decode", "--json"];
        all.extend_from_slice(args);
        records(&run(&all, log))
            .iter()
            .map(|r| r["ts"].as_f64().unwrap())
            .collect()
    };
    assert_eq!(ts(&[]), [0.0, 0.25, 0.35]);
    assert_eq!(ts(&["--timestamps", "zero"]), [0.0, 0.25, 0.1]);
    assert_eq!(ts(&["--timestamps", "delta"]), [0.0, 0.25, 0.35]);
}

/// docs/formats.md#detection: `--format` overrides detection.
#[test]
fn format_overrides_detection() {
    let out = run(
        &["decode", "--format", "candump", "--json"],
        "can0 705#05\n",
    );
    assert!(out.status.success());
    assert_eq!(records(&out).len(), 1);
    let bad = run(&["decode", "--format", "nope"], "");
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("candump, asc, trc, pcap, pcapng, blf"));
}

/// A gzip stream that inflates to far more than it is (64 MiB from a few
/// KiB, one line without an end) is read in bounded blocks: one overlong
/// line reported, the frame after it read.
#[test]
fn a_gzip_bomb_is_one_overlong_line() {
    use flate2::write::GzEncoder;
    let mut gz = GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(b"(1700000000.000500) can0 081#00\n").unwrap();
    let chunk = vec![b'A'; 1 << 20];
    for _ in 0..64 {
        gz.write_all(&chunk).unwrap();
    }
    gz.write_all(b"\n(1700000000.000600) can0 705#05\n")
        .unwrap();
    let bytes = gz.finish().unwrap();
    assert!(bytes.len() < 1 << 20);
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bomb.gz");
    std::fs::write(&path, &bytes).unwrap();
    let out = run(&["decode", "--json", path.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let lines: Vec<u64> = records(&out)
        .iter()
        .map(|r| r["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, [1, 3]);
    assert_eq!(stderr(&out).matches("line longer than 1 MiB").count(), 1);
}

/// docs/formats.md#pcap: a pcap or pcapng capture is detected and read like any
/// log: `line` is tshark's `frame.number`, `iface` the pcapng interface
/// name (null in pcap), and packets of other link types are said once,
/// with their link type.
#[test]
fn pcap_and_pcapng_captures() {
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/pcap/");
    for file in [
        "can.pcap",
        "can_be.pcap",
        "can_ns.pcap",
        "can.pcapng",
        "multi.pcapng",
    ] {
        let path = format!("{fixtures}{file}");
        let truth: Value =
            serde_json::from_slice(&std::fs::read(format!("{path}.json")).unwrap()).unwrap();
        let out = run(&["decode", "--json", &path], "");
        assert!(out.status.success(), "{file}: {}", stderr(&out));
        let recs = records(&out);
        let can: Vec<&Value> = truth["packets"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| {
                p["frame.protocols"]
                    .as_str()
                    .is_some_and(|p| p == "can" || p.starts_with("can:") || p.starts_with("canfd"))
            })
            .collect();
        assert_eq!(recs.len(), can.len(), "{file}");
        for (rec, packet) in recs.iter().zip(&can) {
            assert_eq!(
                rec["line"].to_string(),
                packet["frame.number"].as_str().unwrap(),
                "{file}"
            );
            // tshark shows an error frame's classes, not an identifier.
            if let Some(id) = packet["can.id"].as_str() {
                assert_eq!(rec["id"].to_string(), id, "{file}");
            } else {
                assert_eq!(rec["kind"], "error_frame", "{file}");
            }
            if file.ends_with(".pcap") {
                assert_eq!(rec["iface"], Value::Null, "{file}");
            }
        }
        let skipped = truth["packets"].as_array().unwrap().len() - can.len();
        let err = stderr(&out);
        if skipped > 0 {
            // docs/formats.md#pcap, docs/ethercat.md#reading: an Ethernet
            // packet without EtherCAT, once, naming its EtherType (ARP).
            assert_eq!(
                err.matches("packet of EtherType 0x0806 (ARP) skipped: neither CAN nor EtherCAT")
                    .count(),
                1,
                "{err}"
            );
        } else {
            assert!(err.is_empty(), "{file}: {err}");
        }
    }
    // A capture cut in the middle of a record: the frames before it, one
    // error with the byte offset, exit status 1.
    let whole = std::fs::read(format!("{fixtures}can.pcap")).unwrap();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let cut = dir.join("cut.pcap");
    std::fs::write(&cut, &whole[..whole.len() - 5]).unwrap();
    let out = run(&["decode", "--json", cut.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1));
    assert!(!records(&out).is_empty());
    let err = stderr(&out);
    assert!(err.contains("pcap file, byte "), "{err}");
    // A damaged header: nothing can be read, exit status 2.
    let header = dir.join("header.pcap");
    std::fs::write(&header, &whole[..10]).unwrap();
    let out = run(&["decode", header.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

/// docs/formats.md#trc, docs/summary.md#bus: a PEAK TRC file is detected and
/// read: `line` is the file's line, `iface` the bus number, status rows are the
/// bus record's `status_events`, not frames and not malformed.
#[test]
fn trc_files() {
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/trc/");
    let path = format!("{fixtures}python_can_v2_1.trc");
    let truth: Value =
        serde_json::from_slice(&std::fs::read(format!("{fixtures}python_can_v2_1.json")).unwrap())
            .unwrap();
    let out = run(&["decode", "--json", &path], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    let frames = truth["frames"].as_array().unwrap();
    assert_eq!(recs.len(), frames.len());
    let text = std::fs::read_to_string(&path).unwrap();
    for (rec, want) in recs.iter().zip(frames) {
        assert_eq!(rec["id"], want["arbitration_id"]);
        let ts: f64 = want["timestamp"].as_str().unwrap().parse().unwrap();
        assert_eq!(rec["ts"].as_f64().unwrap(), ts);
        assert_eq!(rec["iface"].as_str().unwrap(), want["channel"].to_string());
        // `line` points at the row of the frame in the file.
        let row = text
            .lines()
            .nth(rec["line"].as_u64().unwrap() as usize - 1)
            .unwrap();
        assert!(row.trim_start().starts_with(char::is_numeric), "{row}");
    }
    let summary = run(
        &[
            "decode",
            "--summary",
            "--json",
            &format!("{fixtures}handmade_v2_1.trc"),
        ],
        "",
    );
    assert!(summary.status.success(), "{}", stderr(&summary));
    let buses: Vec<Value> = records(&summary)
        .into_iter()
        .filter(|r| r["type"] == "bus")
        .collect();
    let status: u64 = buses
        .iter()
        .map(|b| b["status_events"].as_u64().unwrap())
        .sum();
    let errors: u64 = buses
        .iter()
        .map(|b| b["error_frames"].as_u64().unwrap())
        .sum();
    assert!(status > 0 && errors > 0, "{buses:?}");
}

/// docs/formats.md#asc: a Vector ASC file is detected and read: `line` is the
/// file's line, `iface` the channel as written, `ts` seconds since the
/// start (relative times added up).
#[test]
fn asc_files() {
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/asc/");
    let path = format!("{fixtures}handmade_dec_relative.asc");
    let out = run(&["decode", "--json", &path], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    let got: Vec<(u64, String, u64, f64)> = recs
        .iter()
        .map(|r| {
            (
                r["line"].as_u64().unwrap(),
                r["iface"].as_str().unwrap().to_owned(),
                r["id"].as_u64().unwrap(),
                r["ts"].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(got.len(), 7);
    assert_eq!(got[0], (9, "1".to_owned(), 129, 0.001));
    assert_eq!(got[1], (10, "2".to_owned(), 1797, 0.0015));
    assert_eq!(recs[5]["kind"], "error_frame");
    assert_eq!(recs[6]["ts"].as_f64().unwrap(), 0.016125);
    let summary = run(&["decode", "--summary", "--json", &path], "");
    let status: u64 = records(&summary)
        .iter()
        .filter(|r| r["type"] == "bus")
        .map(|r| r["status_events"].as_u64().unwrap())
        .sum();
    assert_eq!(status, 1);
}

/// docs/formats.md#blf: a Vector BLF file is detected and read: `line` is the
/// object's number, `iface` the channel, `ts` start time + offset; a file
/// cut inside a container gives the frames before it and one error.
#[test]
fn blf_files() {
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/blf/");
    let path = format!("{fixtures}python_can.blf");
    let truth: Value =
        serde_json::from_slice(&std::fs::read(format!("{fixtures}python_can.json")).unwrap())
            .unwrap();
    let out = run(&["decode", "--json", &path], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    let want = truth["frames"].as_array().unwrap();
    assert_eq!(recs.len(), want.len());
    for (i, (rec, want)) in recs.iter().zip(want).enumerate() {
        assert_eq!(rec["line"], i as u64 + 1);
        assert_eq!(rec["iface"].as_str().unwrap(), want["channel"].to_string());
        if want["error"] == false {
            assert_eq!(rec["id"], want["id"]);
        }
        let ts: f64 = want["timestamp"].as_str().unwrap().parse().unwrap();
        assert!((rec["ts"].as_f64().unwrap() - ts).abs() < 1e-6);
    }
    let whole = std::fs::read(&path).unwrap();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let cut = dir.join("cut.blf");
    std::fs::write(&cut, &whole[..whole.len() - 40]).unwrap();
    // Its one container cut: nothing could be read (docs/output.md#exit-status).
    let out = run(&["decode", "--json", cut.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("blf file, byte "), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("nothing could be read as a blf log: 1 damaged record and no frame"),
        "{}",
        stderr(&out)
    );
    // A file of many containers cut in its last: the frames before it.
    let many = std::fs::read(format!("{fixtures}python_can_many.blf")).unwrap();
    std::fs::write(&cut, &many[..many.len() - 40]).unwrap();
    let out = run(&["decode", "--json", cut.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1));
    assert!(!records(&out).is_empty());
    assert!(stderr(&out).contains("blf file, byte "), "{}", stderr(&out));
}

/// docs/formats.md#mf4: an MF4 file is detected and read, by name and from
/// standard input (gzip-compressed too): `iface` the bus channel, `ts` start
/// time + master channel, frames in time order across the data groups, `line`
/// the record's number over them; `--format mf4` names it.
#[test]
fn mf4_files() {
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/mf4/");
    let path = format!("{fixtures}python_can.mf4");
    let truth: Value =
        serde_json::from_slice(&std::fs::read(format!("{fixtures}python_can.json")).unwrap())
            .unwrap();
    let out = run(&["decode", "--json", "--format", "mf4", &path], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    let want = truth["frames"].as_array().unwrap();
    assert_eq!(recs.len(), want.len());
    for (rec, want) in recs.iter().zip(want) {
        assert_eq!(rec["iface"].as_str().unwrap(), want["channel"].to_string());
        if want["error"] == false {
            assert_eq!(rec["id"], want["id"]);
        }
        let ts: f64 = want["timestamp"].as_str().unwrap().parse().unwrap();
        assert!((rec["ts"].as_f64().unwrap() - ts).abs() < 1e-6);
    }
    let lines: Vec<u64> = recs
        .iter()
        .take(4)
        .map(|r| r["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, [1, 2, 39, 3]);
    // The same file through a pipe, and gzip-compressed.
    let whole = std::fs::read(&path).unwrap();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let gz = dir.join("python_can.mf4.gz");
    let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    std::io::Write::write_all(&mut encoder, &whole).unwrap();
    std::fs::write(&gz, encoder.finish().unwrap()).unwrap();
    let zipped = run(&["decode", "--json", gz.to_str().unwrap()], "");
    assert!(zipped.status.success(), "{}", stderr(&zipped));
    assert_eq!(zipped.stdout, out.stdout);
    // Cut inside its data: the frames before, one error.
    let cut = dir.join("cut.mf4");
    std::fs::write(&cut, &whole[..400]).unwrap();
    let out = run(&["decode", "--json", cut.to_str().unwrap()], "");
    assert_ne!(out.status.code(), Some(0));
    assert!(stderr(&out).contains("mf4 file, byte "), "{}", stderr(&out));
}

/// The keys of docs/output.md#nmt-command, docs/output.md#sync and
/// docs/output.md#time.
#[test]
fn nmt_sync_and_time_keys() {
    let log = "\
(1.0) can0 000#0105
(1.0) can0 000#8100
(1.0) can0 000#0305
(1.0) can0 080#
(1.0) can0 080#07
(1.0) can0 100#002E9302333D
(1.0) can0 100#002E93F2333D
(1.0) can0 100#0102
";
    let out = run(&["decode", "--json"], log);
    assert!(out.status.success(), "{}", stderr(&out));
    let recs = records(&out);
    let pick = |r: &Value, keys: &[&str]| -> Value {
        keys.iter()
            .map(|k| {
                (
                    k.to_string(),
                    r.get(*k).cloned().unwrap_or(Value::String("-".into())),
                )
            })
            .collect::<serde_json::Map<_, _>>()
            .into()
    };
    let nmt = ["kind", "command", "target", "error"];
    assert_eq!(
        pick(&recs[0], &nmt),
        json!({"kind": "nmt_command", "command": "start", "target": 5, "error": "-"})
    );
    assert_eq!(
        pick(&recs[1], &nmt),
        json!({"kind": "nmt_command", "command": "reset_node", "target": 0, "error": "-"})
    );
    // An undefined command is `unknown`, with the decoder's reason.
    assert_eq!(recs[2]["command"], "unknown");
    assert_eq!(recs[2]["target"], 5);
    assert!(recs[2]["error"]
        .as_str()
        .unwrap()
        .contains("NMT command specifier"));
    // `--node` matches frames that carry a node-ID: an NMT target is not one.
    assert!(recs[0].get("node").is_none());
    assert_eq!(recs[3]["counter"], Value::Null);
    assert_eq!(recs[4]["counter"], 7);
    // 12:00 on day 15667 (2026-11-23); the top 4 bits of byte 3 are reserved.
    assert_eq!(
        recs[5]["time_of_day"],
        json!({"ms": 43_200_000, "days": 15_667})
    );
    assert_eq!(
        recs[6]["time_of_day"],
        json!({"ms": 43_200_000, "days": 15_667})
    );
    assert!(recs[7].get("time_of_day").is_none());
    assert!(recs[7]["error"].as_str().unwrap().contains("TIME"));

    let text = stdout(&run(&["decode"], log));
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].ends_with("start node 5"), "{}", lines[0]);
    assert!(lines[1].ends_with("reset_node all nodes"), "{}", lines[1]);
    assert!(lines[4].ends_with("counter 7"), "{}", lines[4]);
    assert!(
        lines[5].ends_with("day 15667 (since 1984-01-01), 12:00:00.000"),
        "{}",
        lines[5]
    );
}

/// Several files are several recordings, each record naming its file; a
/// file given twice is read once; `--joined` reads them as one recording
/// with lines numbered on (docs/output.md#several-files, issue 22).
#[test]
fn several_files_are_kept_apart() {
    let a = temp_file(
        "several_a.log",
        "(1.000000) can0 705#00\n(1.100000) can0 085#1081110000000000\n",
    );
    let b = temp_file("several_b.log", "(2.000000) can0 705#05\n");
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());

    let out = run(&["decode", "--json", a, b, a], "");
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        stderr(&out),
        format!("motionwire: {a} is given more than once: read once\n")
    );
    let recs = records(&out);
    let files: Vec<(&str, u64)> = recs
        .iter()
        .map(|r| (r["file"].as_str().unwrap(), r["line"].as_u64().unwrap()))
        .collect();
    assert_eq!(files, [(a, 1), (a, 2), (b, 1)]);

    // One summary per file, each record naming its file: node 5 twice.
    let out = run(&["decode", "--summary", "--json", a, b], "");
    let recs = records(&out);
    let nodes: Vec<(&str, &Value)> = recs
        .iter()
        .filter(|r| r["type"] == "node")
        .map(|r| (r["file"].as_str().unwrap(), &r["heartbeat"]["boot_ups"]))
        .collect();
    assert_eq!(nodes, [(a, &json!([1])), (b, &json!([]))]);
    let text = run(&["decode", "--summary", a, b], "");
    assert!(stdout(&text).starts_with(&format!("{a}: can0 node   5  frames")));

    // --joined: one recording, lines numbered on, a record per file.
    let out = run(&["decode", "--summary", "--json", "--joined", a, b], "");
    let recs = records(&out);
    let node = recs.iter().find(|r| r["type"] == "node").unwrap();
    assert!(node.get("file").is_none());
    assert_eq!(node["heartbeat"]["count"], 2);
    assert_eq!(node["emcy"], 1);
    let spans: Vec<&Value> = recs.iter().filter(|r| r["type"] == "file").collect();
    assert_eq!(
        spans,
        [
            &json!({"type": "file", "file": a, "first_line": 1, "last_line": 2}),
            &json!({"type": "file", "file": b, "first_line": 3, "last_line": 3}),
        ]
    );
    let out = run(&["decode", "--csv", "--joined", a, b], "");
    let csv = stdout(&out);
    let rows: Vec<&str> = csv.lines().collect();
    assert!(rows[0].starts_with("file,line,ts,"));
    assert!(
        rows[3].starts_with(&format!("{b},3,2.000000,")),
        "{}",
        rows[3]
    );
}

/// The program explains itself (issue 22): the help lists the formats,
/// kinds and exit statuses and points at docs/; a bad profile names the
/// valid ones; an EDS that cannot be read says so without a line 0.
#[test]
fn help_and_messages_speak_plainly() {
    let top = run(&["--help"], "");
    assert!(
        stdout(&top).starts_with("motionwire: read CAN logs"),
        "{}",
        stdout(&top)
    );
    let help = run(&["decode", "--help"], "");
    let text = stdout(&help);
    for needle in [
        "candump, asc, trc, pcap, pcapng, blf, mf4",
        "emcy, heartbeat, guard_request, guard_answer, nmt_command, sync,\n          time, pdo, sdo, error_frame, other",
        "Exit status:",
        "docs/output.md",
        "line  ts                 iface  id        kind           node      detail",
    ] {
        assert!(text.contains(needle), "{needle:?} not in\n{text}");
    }
    assert!(!text.contains("SPEC"), "{text}");

    let profile = run(&["decode", "--profile", "3=kollmorgen"], "");
    assert_eq!(profile.status.code(), Some(2));
    assert!(
        stderr(&profile).contains("\"kollmorgen\" is not a profile; one of generic, akd, baumer"),
        "{}",
        stderr(&profile)
    );
    let eds = run(&["decode", "--eds", "3=/nonexistent/x.eds"], "");
    assert_eq!(eds.status.code(), Some(2));
    assert!(
        stderr(&eds).starts_with(
            "motionwire: --eds 3=/nonexistent/x.eds: /nonexistent/x.eds: cannot be read: "
        ),
        "{}",
        stderr(&eds)
    );
}

/// A candump log of `frames` heartbeats of node 5, a millisecond apart.
fn candump_heartbeats(frames: usize) -> String {
    (0..frames)
        .map(|i| format!("(1700000000.{i:06}) can0 705#05\n"))
        .collect()
}

/// docs/output.md#stderr: a log of which nothing could be read — every
/// line malformed, as a candump log read with `--format trc` — says its
/// first 100 malformed lines and then one line, and is exit status 2; the
/// page is not written.
#[test]
fn a_log_of_which_nothing_could_be_read_says_so_in_one_line() {
    let sample = concat!(env!("CARGO_MANIFEST_DIR"), "/samples/machine.log");
    let generated = temp_file("heartbeats.log", &candump_heartbeats(250));
    for (path, lines) in [(sample, 3765), (generated.to_str().unwrap(), 250)] {
        let out = run(&["decode", "--format", "trc", path], "");
        assert_eq!(out.status.code(), Some(2), "{path}");
        assert!(out.stdout.is_empty());
        let err = stderr(&out);
        let said: Vec<&str> = err.lines().collect();
        assert_eq!(said.len(), 101, "{err}");
        for (i, line) in said[..100].iter().enumerate() {
            assert!(
                line.starts_with(&format!("{path}:{}: trc line", i + 1)),
                "{line}"
            );
        }
        assert_eq!(
            said[100],
            format!(
                "motionwire: {path}: nothing could be read as a trc log: {lines} malformed lines \
                 and no frame; the first 100 are said above (--verbose says each)"
            )
        );
        let verbose = run(&["decode", "--verbose", "--format", "trc", path], "");
        assert_eq!(verbose.status.code(), Some(2));
        assert_eq!(stderr(&verbose).lines().count(), lines + 1);
    }
    // A few malformed lines: each said, and the one line without the rest.
    let out = run(&["decode", "--format", "trc", "-"], &candump_heartbeats(3));
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).ends_with(
            "motionwire: <stdin>: nothing could be read as a trc log: 3 malformed lines and no frame\n"
        ),
        "{}",
        stderr(&out)
    );
    // The page is not written.
    let page = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests/nothing.html");
    let _ = std::fs::remove_file(&page);
    let out = run(
        &[
            "report",
            "--format",
            "trc",
            sample,
            "-o",
            page.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(stderr(&out).lines().count(), 101);
    assert!(!page.exists());
    // An empty log is not a log of which nothing could be read.
    let out = run(&["decode", "--format", "trc", "-"], "");
    assert_eq!(out.status.code(), Some(0));
}

/// docs/output.md#stderr: per file, the first 100 malformed lines are said
/// one by one and the rest counted in one line; `--verbose` says all.
#[test]
fn malformed_lines_are_said_up_to_100_per_file() {
    let mut text = candump_heartbeats(2);
    for i in 0..150 {
        text.push_str(&format!("not a frame {i}\n"));
    }
    let a = temp_file("bounded_a.log", &text);
    let b = temp_file("bounded_b.log", &text);
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = run(&["decode", "--json", a, b], "");
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(records(&out).len(), 4, "the frames are written");
    let err = stderr(&out);
    let said: Vec<&str> = err.lines().collect();
    // 100 + 1 per file, then the run's count.
    assert_eq!(said.len(), 2 * 101 + 1, "{err}");
    assert!(
        said[99].starts_with(&format!("{a}:102: candump line")),
        "{}",
        said[99]
    );
    assert_eq!(
        said[100],
        format!(
            "{a}: 150 malformed lines in all; the first 100 are said above (--verbose says each)"
        )
    );
    assert!(
        said[101].starts_with(&format!("{b}:3: candump line")),
        "{}",
        said[101]
    );
    assert_eq!(said[202], "motionwire: 300 malformed lines skipped");

    let out = run(&["decode", "--verbose", "--json", a, b], "");
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stderr(&out).lines().count(), 2 * 150 + 1);

    // At most 100: nothing more than before.
    let few = temp_file("bounded_few.log", &(candump_heartbeats(1) + "junk\n"));
    let out = run(&["decode", few.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stderr(&out).lines().count(), 2);
}

/// docs/summary.md#verdict: the text summary and the JSON summary start with
/// the verdict; on the sample, drive 3's last fault after the EMCY on its
/// feedback 2, first caused by its first error.
#[test]
fn the_summary_starts_with_its_verdict() {
    let sample = concat!(env!("CARGO_MANIFEST_DIR"), "/samples/machine.log");
    let args = [
        "decode",
        "--summary",
        "--profile",
        "3=akd,5=baumer",
        "--heartbeat-ms",
        "300",
    ];
    let mut text = args.to_vec();
    text.push(sample);
    let out = run(&text, "");
    assert!(out.status.success(), "{}", stderr(&out));
    let lines: Vec<String> = stdout(&out).lines().take(2).map(str::to_owned).collect();
    assert_eq!(
        lines,
        [
            "verdict   stop: can0 node 3 went operation_enabled → fault at line 3239 (+8.820 s), \
             16.1 ms after EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2 (line 3231)",
            "          first cause: can0 node 3 first error: EMCY 0x7305 Incremental sensor 1 \
             fault on axis 1, feedback 1 at line 613 (+2.003 s)",
        ]
    );
    let mut json = args.to_vec();
    json.extend(["--json", sample]);
    let recs = records(&run(&json, ""));
    let verdict = &recs[0];
    assert_eq!(verdict["type"], "verdict");
    assert_eq!(
        verdict["stop"],
        json!({"iface": "can0", "node": 3, "slave": null, "line": 3239, "ts": 1700000008.820694,
               "kind": "cia402_fault", "severity": "fault",
               "text": "went operation_enabled → fault at line 3239, 16.1 ms after EMCY 0x7305 \
                        Incremental sensor 1 fault on axis 1, feedback 2 (line 3231)",
               "cause": {"line": 3231, "ts": 1700000008.804608, "code": 0x7305,
                         "description": "Incremental sensor 1 fault"}})
    );
    assert_eq!(verdict["first_cause"]["line"], 613);
    assert_eq!(verdict["first_cause"]["severity"], "error");
    assert_eq!(
        verdict["text"],
        format!(
            "stop: {}; first cause: {}",
            lines[0].strip_prefix("verdict   stop: ").unwrap(),
            lines[1].strip_prefix("          first cause: ").unwrap()
        )
    );
    // Nothing stopped in a log of heartbeats: no verdict.
    let calm = run(
        &["decode", "--summary", "--json", "-"],
        "(1.0) can0 705#05\n",
    );
    assert_eq!(records(&calm)[0]["type"], "node");
}

/// docs/ethercat.md#filters: `--only` takes EtherCAT kinds beside CAN
/// ones, `--slave` keeps one slave's records, and the CAN filters keep no
/// EtherCAT record.
#[test]
fn ethercat_records_are_filtered_by_kind_and_slave() {
    let capture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/ethercat/synthetic_akd_fault.pcapng"
    );
    let kinds = |out: &Output| {
        let mut kinds: Vec<String> = records(out)
            .iter()
            .map(|r| r["kind"].as_str().unwrap().to_owned())
            .collect();
        kinds.dedup();
        kinds
    };
    let out = run(&["decode", "--json", "--only", "coe_emcy", capture], "");
    assert_eq!(kinds(&out), ["coe_emcy"]);
    assert_eq!(records(&out)[0]["code"], 0x7305);
    let out = run(
        &[
            "decode", "--json", "--only", "al_state", "--slave", "0x1001", capture,
        ],
        "",
    );
    let all = records(&out);
    assert!(all
        .iter()
        .all(|r| r["kind"] == "al_state" && r["slave"] == 0x1001));
    assert_eq!(all.last().unwrap()["code"], 0x001B);
    // FPxx datagrams name their slave; the cyclic LRW names none.
    let out = run(
        &[
            "decode",
            "--json",
            "--only",
            "ecat_datagram",
            "--slave",
            "4096",
            capture,
        ],
        "",
    );
    let all = records(&out);
    assert!(!all.is_empty());
    assert!(all
        .iter()
        .all(|r| r["cmd"].as_str().unwrap().starts_with("FP") && r["adp"] == 0x1000));
    for filter in [["--only", "emcy"], ["--node", "3"], ["--id", "0x080"]] {
        let out = run(&["decode", "--json", filter[0], filter[1], capture], "");
        assert_eq!(stdout(&out), "", "{filter:?}");
    }
    let out = run(&["decode", "--only", "al_status", capture], "");
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("\"al_status\" is not a kind; one of emcy,"));
}

/// docs/ethercat.md#filters: `--slave` keeps the datagrams sent to a
/// slave's enabled alias with its own (scripts/ecat_pcapng.py --fixture
/// registers: packets 13 and 14 read AL status at alias 0x0077, which is
/// slave 0x1001's), and their records of what they tell.
#[test]
fn the_slave_filter_keeps_datagrams_sent_to_its_alias() {
    let capture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/ethercat/synthetic_registers.pcapng"
    );
    let out = run(
        &[
            "decode",
            "--json",
            "--only",
            "ecat_datagram,al_state",
            "--slave",
            "0x1001",
            capture,
        ],
        "",
    );
    let all = records(&out);
    let by_alias: Vec<_> = all
        .iter()
        .filter(|r| r["adp"] == 0x0077)
        .map(|r| {
            (
                r["packet"].as_u64().unwrap(),
                r["returned"].as_bool().unwrap(),
            )
        })
        .collect();
    assert_eq!(by_alias, [(13, false), (14, true)]);
    assert!(all
        .iter()
        .any(|r| r["packet"] == 14 && r["kind"] == "al_state" && r["slave"] == 0x1001));
    assert!(all
        .iter()
        .filter(|r| r["kind"] == "ecat_datagram")
        .all(|r| r["adp"] == 0x1001 || r["adp"] == 0x0077));
    // The alias is no station: nothing is sent to 0x0077 as such.
    let out = run(
        &[
            "decode",
            "--json",
            "--only",
            "ecat_datagram",
            "--slave",
            "0x0077",
            capture,
        ],
        "",
    );
    assert_eq!(stdout(&out), "");
}

/// docs/ethercat.md#reading: a capture whose times go back is read in its
/// order, and said once.
#[test]
fn ethercat_time_that_goes_back_is_said_once() {
    // pcap, microseconds, link type 1; three BRD frames as sent, at 2 s,
    // 1 s, then 0.5 s.
    let mut file = Vec::new();
    for word in [0xA1B2_C3D4u32, 0x0004_0002, 0, 0, 65_535, 1] {
        file.extend(word.to_le_bytes());
    }
    let mut frame = vec![0xff; 6];
    frame.extend([0x10; 6]);
    frame.extend([0x88, 0xa4, 0x0e, 0x10]);
    frame.extend([7, 1, 0, 0, 0x30, 0x01, 2, 0, 0, 0, 0, 0, 0, 0]);
    for secs in [2u32, 1, 0] {
        for word in [
            secs,
            500_000 * u32::from(secs == 0),
            frame.len() as u32,
            frame.len() as u32,
        ] {
            file.extend(word.to_le_bytes());
        }
        file.extend(&frame);
    }
    let path =
        std::env::temp_dir().join(format!("motionwire-reversal-{}.pcap", std::process::id()));
    std::fs::write(&path, &file).unwrap();
    let out = run(&["decode", path.to_str().unwrap()], "");
    std::fs::remove_file(&path).ok();
    assert_eq!(out.status.code(), Some(0));
    let err = stderr(&out);
    assert_eq!(
        err.matches("EtherCAT packets are earlier than the packet before (the first, packet 2, by 1.000000 s): read in the capture's order").count(),
        1,
        "{err}"
    );
    assert_eq!(stdout(&out).lines().count(), 3, "every packet read");
}

/// docs/summary.md#causes: a bus-off before heartbeat timeouts on its bus
/// causes them — the verdict's stop is the last loss, its first cause the
/// bus-off —, and a heartbeat timeout before another node's EMCY 0x8130
/// causes that EMCY.
#[test]
fn the_verdict_follows_bus_off_and_lost_heartbeats() {
    let log = "(10.000000) can0 705#05\n\
               (10.000100) can0 706#05\n\
               (10.100000) can0 705#05\n\
               (10.100100) can0 706#05\n\
               (10.150000) can0 20000040#0000000000000000\n\
               (10.600000) can0 08A#3081110000000000\n\
               (11.500000) can0 705#05\n\
               (11.500100) can0 706#05\n";
    let out = run(
        &["decode", "--summary", "--json", "--heartbeat-ms", "300"],
        log,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let all = records(&out);
    let verdict = &all[0];
    assert_eq!(verdict["type"], "verdict");
    assert_eq!(
        (&verdict["stop"]["kind"], &verdict["stop"]["node"]),
        (&json!("heartbeat_timeout"), &json!(6))
    );
    assert_eq!(
        verdict["stop"]["text"],
        "no heartbeat for 1400 ms after line 4, caused by bus-off at line 5"
    );
    assert_eq!(
        verdict["first_cause"],
        json!({"iface": "can0", "node": null, "slave": null, "line": 5, "ts": null, "kind": "bus_off",
               "severity": "fault", "text": "bus-off at line 5"})
    );
    let text = stdout(&run(&["decode", "--summary", "--heartbeat-ms", "300"], log));
    assert!(
        text.starts_with(
            "verdict   stop: can0 node 6 no heartbeat for 1400 ms after line 4, caused by \
             bus-off at line 5\n          first cause: bus can0 bus-off at line 5\n"
        ),
        "{text}"
    );
    // Node 10's EMCY 0x8130, 0.2 s after node 5's heartbeat was due.
    let ten = all
        .iter()
        .find(|r| r["type"] == "node" && r["node"] == 10)
        .unwrap();
    assert_eq!(ten["first_error"]["code"], 0x8130);
    let dir = std::env::temp_dir().join(format!("motionwire-causes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let page = dir.join("causes.html");
    let out = run(
        &[
            "report",
            "--heartbeat-ms",
            "300",
            "-o",
            page.to_str().unwrap(),
        ],
        log,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let page = std::fs::read_to_string(page).unwrap();
    assert!(page.contains(
        "first error: EMCY 0x8130 Life guard error or heartbeat error at line 6, caused by \
         node 5&#39;s heartbeat timeout after line 3"
    ));
}

/// docs/output.md#window: `--from` and `--to` count from the recording's
/// first time or name a UTC time, the window is `from <= ts < to`, and
/// `--iface` names interfaces or channels; the summary is the frames kept.
#[test]
fn time_window_and_interface_filters() {
    let log = "(1700000000.000000) can0 705#05\n\
               (1700000000.500000) can1 706#05\n\
               (1700000001.000000) can0 705#05\n\
               (1700000001.500000) can1 706#05\n\
               (1700000002.000000) can0 705#05\n";
    let lines = |args: &[&str]| -> Vec<u64> {
        let mut all = vec!["decode", "--json"];
        all.extend_from_slice(args);
        let out = run(&all, log);
        assert!(out.status.success(), "{}", stderr(&out));
        records(&out)
            .iter()
            .map(|r| r["line"].as_u64().unwrap())
            .collect()
    };
    assert_eq!(lines(&["--from", "1"]), [3, 4, 5]);
    assert_eq!(lines(&["--to", "1"]), [1, 2]);
    assert_eq!(lines(&["--from", "0.5", "--to", "1.5"]), [2, 3]);
    assert_eq!(
        lines(&[
            "--from",
            "2023-11-14T22:13:20.5Z",
            "--to",
            "2023-11-14T22:13:22Z"
        ]),
        [2, 3, 4]
    );
    assert_eq!(lines(&["--iface", "can1"]), [2, 4]);
    assert_eq!(lines(&["--iface", "can1,can0"]), [1, 2, 3, 4, 5]);
    assert_eq!(
        lines(&["--iface", "can0", "--iface", "can1"]),
        [1, 2, 3, 4, 5]
    );
    assert_eq!(lines(&["--iface", "can0", "--from", "0.5"]), [3, 5]);
    // With the other filters: a frame must pass all of them.
    assert_eq!(lines(&["--node", "5", "--to", "1.5"]), [1, 3]);

    // The summary counts the frames kept.
    let summary = run(&["decode", "--summary", "--json", "--iface", "can0"], log);
    let nodes: Vec<(String, u64)> = node_records(&summary)
        .iter()
        .map(|r| {
            (
                r["iface"].as_str().unwrap().to_owned(),
                r["frames"]["heartbeat"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(nodes, [("can0".to_owned(), 3)]);
    let summary = run(&["decode", "--summary", "--json", "--from", "1"], log);
    let heartbeats: u64 = node_records(&summary)
        .iter()
        .map(|r| r["frames"]["heartbeat"].as_u64().unwrap())
        .sum();
    assert_eq!(heartbeats, 3);

    // Nothing kept is said, not left to an empty output.
    let out = run(&["decode", "--iface", "2", "--to", "9"], log);
    assert!(out.status.success());
    assert_eq!(stdout(&out), "");
    assert_eq!(
        stderr(&out),
        "<stdin>: none of its 5 frames passes --to 9 --iface 2\n"
    );
    // A bad time is refused with what a time is.
    let out = run(&["decode", "--from", "2023-11-14 22:13:20"], log);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("UTC time (2023-11-14T22:13:20Z)"),
        "{}",
        stderr(&out)
    );
}

/// docs/output.md#window: each recording counts `--from` from its own
/// start; `--joined` files are one recording.
#[test]
fn the_window_starts_with_each_recording() {
    let a = temp_file("window_a.log", "(10.0) can0 705#05\n(11.0) can0 705#05\n");
    let b = temp_file("window_b.log", "(20.0) can0 705#05\n(21.0) can0 705#05\n");
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let count = |args: &[&str]| {
        let mut all = vec!["decode", "--json", "--from", "1"];
        all.extend_from_slice(args);
        records(&run(&all, "")).len()
    };
    assert_eq!(count(&[a, b]), 2);
    assert_eq!(count(&["--joined", a, b]), 3);
}

/// docs/output.md#stdin: reading standard input is said on a terminal
/// only; a pipe stays silent (the terminal case is the unit test of
/// `says_reading_stdin`).
#[test]
fn a_pipe_on_standard_input_is_not_announced() {
    for args in [&["decode"][..], &["decode", "-"], &["report", "-o", "-"]] {
        let out = run(args, "(1.0) can0 705#05\n");
        assert!(out.status.success(), "{}", stderr(&out));
        assert_eq!(stderr(&out), "", "{args:?}");
    }
}

/// README.md, "The program on your PATH": every `motionwire …` command
/// there runs on the checkout and writes something (the installed program
/// is this binary).
#[test]
fn the_readme_commands_after_install_run() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let section = readme
        .split("### The program on your PATH")
        .nth(1)
        .expect("the README says how to install the program");
    let install = section
        .find("cargo install --path . --features cli")
        .unwrap();
    let commands: Vec<&str> = section[install..]
        .split("\n```\n")
        .nth(1)
        .unwrap()
        .lines()
        .filter(|line| line.starts_with("motionwire "))
        .collect();
    assert!(commands.len() >= 3, "{commands:?}");
    let page = temp_file("readme_page.html", "");
    for command in commands {
        let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
        if let Some(at) = args.iter().position(|a| *a == "-o") {
            args[at + 1] = page.to_str().unwrap();
        }
        let out = bin().args(&args).current_dir(&root).output().unwrap();
        assert!(out.status.success(), "{command}: {}", stderr(&out));
        assert_eq!(stderr(&out), "", "{command}");
        let written = if args.contains(&"-o") {
            std::fs::read_to_string(&page).unwrap()
        } else {
            stdout(&out)
        };
        assert!(!written.is_empty(), "{command} wrote nothing");
    }
}
