//! PDOs decoded into signals and the CiA 402 state
//! (docs/canopen.md#pdo-mappings): a log in which python-canopen configures the
//! PDOs over SDO and then sends them (`tests/fixtures/pdo/`, made by
//! `scripts/gen_pdo_fixtures.py`), decoded with no EDS at all and with the
//! node's EDS, against python-canopen's (and, for entries that straddle bytes,
//! cantools') reading of the same bytes; and the sample log's drive timeline
//! against its own statuswords. Decoded by the library (`motionwire::decoder`,
//! `summary`) with the options of the command lines the tests name
//! (`tests/common`).

use crate::common::{decode, path, records};

use serde_json::{json, Value};

fn oracle() -> Value {
    serde_json::from_str(
        &std::fs::read_to_string(path("tests/fixtures/pdo/python_canopen.json")).unwrap(),
    )
    .unwrap()
}

/// The oracle's signals of one frame, dummies left out (they carry no
/// signal, docs/canopen.md#signals).
fn oracle_signals(frame: &Value) -> Vec<&Value> {
    frame["signals"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["dummy"] != true)
        .collect()
}

/// No EDS, no profile: the mapping comes from the SDO configuration the log
/// shows (docs/canopen.md#pdo-mappings item 1), the remap applies from where it
/// happens, and each entry is the unsigned of its bit length, 1-bit entries
/// booleans, named `6041sub0` style (docs/canopen.md#signals).
#[test]
fn learned_from_the_log_with_no_eds() {
    let oracle = oracle();
    let recs = records(&decode(&[
        "--json",
        &path("tests/fixtures/pdo/python_canopen.log"),
    ]));
    let frames = oracle["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 38);
    for frame in frames {
        let line = frame["line"].as_u64().unwrap();
        let rec = &recs[line as usize - 1];
        assert_eq!(rec["line"], line);
        let want: serde_json::Map<String, Value> = oracle_signals(frame)
            .iter()
            .map(|s| {
                // The `6041sub0` of docs/canopen.md#signals, the sub-index in
                // hex as CiA 306's section names write it.
                let name = format!(
                    "{:04X}sub{:X}",
                    s["index"].as_u64().unwrap(),
                    s["subindex"].as_u64().unwrap()
                );
                let raw = if s["bits"] == 1 {
                    json!(s["raw"] == 1)
                } else {
                    s["raw"].clone()
                };
                (name, raw)
            })
            .collect();
        assert_eq!(rec["signals"], Value::Object(want), "line {line}");
        assert!(rec.get("error").is_none(), "line {line}");
    }
    // Before the remap TPDO1 carried two entries, after it three.
    let remap = &oracle["remap"];
    let old = remap["last_frame_old_mapping"].as_u64().unwrap() as usize;
    let new = remap["first_frame_new_mapping"].as_u64().unwrap() as usize;
    assert_eq!(recs[old - 1]["signals"].as_object().unwrap().len(), 2);
    assert_eq!(recs[new - 1]["signals"].as_object().unwrap().len(), 3);
    // Frames before the configuration is complete have no signals: the
    // first PDO comes after NMT start.
    assert!(recs[..206].iter().all(|r| r.get("signals").is_none()));
}

/// With the node's EDS: names and types from the file
/// (docs/canopen.md#signals), values as python-canopen (or cantools, where
/// python-canopen misreads entries that straddle bytes; see the fixture's
/// README) reads them; the EDS's device type makes the node a drive, so its
/// words get `cia402`.
#[test]
fn with_the_eds_names_types_and_values_agree() {
    let oracle = oracle();
    let recs = records(&decode(&[
        "--json",
        "--eds",
        &format!("3={}", path("tests/fixtures/pdo/drive.eds")),
        &path("tests/fixtures/pdo/python_canopen.log"),
    ]));
    for frame in oracle["frames"].as_array().unwrap() {
        let line = frame["line"].as_u64().unwrap();
        let rec = &recs[line as usize - 1];
        let want: serde_json::Map<String, Value> = oracle_signals(frame)
            .iter()
            .map(|s| (s["name"].as_str().unwrap().to_owned(), s["value"].clone()))
            .collect();
        let got = rec["signals"].as_object().unwrap();
        assert_eq!(got.len(), want.len(), "line {line}");
        for (name, value) in &want {
            let ours = &got[name];
            match (ours.as_f64(), value.as_f64()) {
                (Some(a), Some(b)) if value.is_f64() => assert_eq!(a, b, "line {line} {name}"),
                _ => assert_eq!(ours, value, "line {line} {name}"),
            }
        }
    }
    // The CiA 402 walk of the statuswords python-canopen's drive sent.
    let states: Vec<(u64, &str)> = recs
        .iter()
        .filter(|r| r["id"] == 0x183)
        .filter_map(|r| Some((r["line"].as_u64()?, r["cia402"]["state"].as_str()?)))
        .collect();
    let mut walk: Vec<&str> = states.iter().map(|(_, s)| *s).collect();
    walk.dedup();
    assert_eq!(
        walk[..6],
        [
            "switch_on_disabled",
            "ready_to_switch_on",
            "switched_on",
            "operation_enabled",
            "fault",
            "switch_on_disabled"
        ]
    );
    // The fault reset is the 0 → 1 edge of controlword bit 7.
    let commands: Vec<&str> = recs
        .iter()
        .filter(|r| r["id"] == 0x203)
        .filter_map(|r| r["cia402"]["command"].as_str())
        .collect();
    assert!(commands.contains(&"fault_reset"), "{commands:?}");
    assert!(commands.contains(&"enable_operation"), "{commands:?}");
}

/// CiA 402's state coding (statusword bits 0–3, 5, 6), written out here
/// independently of the library.
fn state_of(sw: u16) -> Option<&'static str> {
    let table: [(u16, u16, &str); 8] = [
        (0x4F, 0x00, "not_ready_to_switch_on"),
        (0x4F, 0x40, "switch_on_disabled"),
        (0x6F, 0x21, "ready_to_switch_on"),
        (0x6F, 0x23, "switched_on"),
        (0x6F, 0x27, "operation_enabled"),
        (0x6F, 0x07, "quick_stop_active"),
        (0x4F, 0x0F, "fault_reaction_active"),
        (0x4F, 0x08, "fault"),
    ];
    table
        .iter()
        .find(|(mask, value, _)| sw & mask == *value)
        .map(|t| t.2)
}

/// The sample log: the drive (node 3) is configured by SDO at boot, so its
/// TPDO1 is decoded with no EDS and no profile, and the summary's `cia402`
/// timeline is exactly the state changes of its statuswords (read here
/// from the raw frames), with a fault line wherever it enters fault.
#[test]
fn sample_drive_timeline() {
    let log = path("samples/machine.log");
    let text = std::fs::read_to_string(&log).unwrap();
    let mut expected = Vec::new();
    let mut faults = Vec::new();
    let mut last: Option<&str> = None;
    let mut started = false;
    for (i, l) in text.lines().enumerate() {
        let line = i as u64 + 1;
        // TPDO1 becomes valid at the SDO write of 1800h.01 = 0x183.
        if l.contains(" 603#2300180183010000") {
            started = true;
        }
        let Some(data) = l.split(" 183#").nth(1) else {
            continue;
        };
        if !started {
            continue;
        }
        let sw = u16::from_str_radix(&format!("{}{}", &data[2..4], &data[0..2]), 16).unwrap();
        let state = state_of(sw).unwrap();
        if last != Some(state) {
            if state == "fault" && !matches!(last, Some("fault" | "fault_reaction_active")) {
                faults.push(line);
            }
            expected.push(json!({"line": line, "from": last, "to": state}));
            last = Some(state);
        }
    }
    assert!(faults.len() >= 2, "the sample's drive faults");
    let recs = records(&decode(&["--summary", "--json", &log]));
    let drive = recs.iter().find(|r| r["node"] == 3).unwrap();
    let got: Vec<Value> = drive["cia402"]["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| json!({"line": t["line"], "from": t["from"], "to": t["to"]}))
        .collect();
    assert_eq!(got, expected);
    assert_eq!(drive["cia402"]["faults"], json!(faults));
    assert_eq!(drive["cia402"]["last_state"], json!(last));
    // Nodes that are not drives: null.
    let encoder = recs.iter().find(|r| r["node"] == 5).unwrap();
    assert_eq!(encoder["cia402"], Value::Null);
}

/// A crafted drive (node 4, `--profile 4=akd`) whose TPDO1 mapping is
/// written by SDO with no COB-ID: the pre-defined connection set puts it on
/// 0x184 (docs/canopen.md#pdo-mappings item 3); a refused write changes
/// nothing; a PDO shorter than its mapping carries the signals that fit and
/// `error` (docs/canopen.md#signals); expedited SDO transfers of 6041h and
/// 6040h get `cia402` and the statusword read by SDO joins the summary's
/// timeline (docs/summary.md#cia402).
#[test]
fn sdo_configured_mapping_short_pdos_and_sdo_statuswords() {
    let log = "\
(1.000) can0 604#2F001A0000000000
(1.001) can0 584#60001A0000000000
(1.002) can0 604#23001A0110004160
(1.003) can0 584#60001A0100000000
(1.004) can0 604#23001A0220006460
(1.005) can0 584#60001A0200000000
(1.006) can0 604#2F001A0002000000
(1.007) can0 584#60001A0000000000
(1.008) can0 604#2F001A0005000000
(1.009) can0 584#80001A0030000906
(1.010) can0 184#3702E8030000
(1.020) can0 184#3702E8
(1.030) can0 604#4041600000000000
(1.031) can0 584#4B41600018020000
(1.040) can0 604#2B40600080000000
(1.041) can0 584#6040600000000000
";
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("pdo-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("crafted.log");
    std::fs::write(&file, log).unwrap();
    let file = file.to_str().unwrap();

    let recs = records(&decode(&["--json", "--profile", "4=akd", file]));
    // Line 11: the whole mapping (the refused sub 0 = 5 of line 9 taught
    // nothing), on the pre-defined COB-ID.
    assert_eq!(
        recs[10]["signals"],
        json!({"Statusword": 0x0237, "Position actual value": 1000})
    );
    assert_eq!(recs[10]["cia402"], json!({"state": "operation_enabled"}));
    // Line 12: 3 bytes of a 6-byte mapping.
    assert_eq!(recs[11]["signals"], json!({"Statusword": 0x0237}));
    let error = recs[11]["error"].as_str().unwrap();
    assert!(error.contains('6') && error.contains('3'), "{error}");
    // Lines 14 and 16: the statusword read and the controlword written by
    // SDO.
    assert_eq!(recs[13]["cia402"], json!({"state": "fault"}));
    assert_eq!(recs[15]["cia402"], json!({"command": "fault_reset"}));

    let summary = records(&decode(&[
        "--summary",
        "--json",
        "--profile",
        "4=akd",
        file,
    ]));
    let drive = summary.iter().find(|r| r["node"] == 4).unwrap();
    let to: Vec<(&Value, &Value)> = drive["cia402"]["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| (&t["line"], &t["to"]))
        .collect();
    assert_eq!(
        to,
        [
            (&json!(11), &json!("operation_enabled")),
            (&json!(14), &json!("fault"))
        ]
    );
    assert_eq!(drive["cia402"]["faults"], json!([14]));
}
