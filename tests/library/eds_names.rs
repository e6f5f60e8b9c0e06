//! Names from a node's EDS (docs/canopen.md#object-names,
//! docs/canopen.md#signals): `tests/fixtures/eds/
//! array_drive.eds` names its objects in its own words ("Control word",
//! "Status word") and has an ARRAY 20C2h "Driver temperature" and a RECORD
//! 2010h whose sub-entries its TPDO1 maps; `array_drive.log` reads and
//! writes those objects by SDO (one abort) and sends TPDO1. The truth,
//! `array_drive.json`, is python-canopen's reading of the same EDS
//! (`scripts/gen_eds_names_fixtures.py`): every object's name, every
//! sub-entry's qualified name, TPDO1's signals and their values.
//!
//! Decoded by the library as `motionwire decode --json --eds
//! 3=tests/fixtures/eds/array_drive.eds tests/fixtures/eds/array_drive.log`
//! (and `--summary`) would (`tests/common`).

use crate::common::{decode, path, records};
use serde_json::Value;

const EDS: &str = "3=tests/fixtures/eds/array_drive.eds";
const LOG: &str = "tests/fixtures/eds/array_drive.log";

fn truth() -> Value {
    serde_json::from_str(
        &std::fs::read_to_string(path("tests/fixtures/eds/array_drive.json")).unwrap(),
    )
    .unwrap()
}

/// python-canopen's name of object `index` (`od[index].name`).
fn object_name(truth: &Value, index: u64) -> &str {
    truth["objects"][format!("{index:04X}")]
        .as_str()
        .unwrap_or_else(|| panic!("{index:04X}h is in the EDS"))
}

/// With `--eds`, every SDO record's `object` (and its transfer's) is the
/// EDS's ParameterName of the object, as python-canopen names it — also
/// 6040h/6041h, which the file names otherwise than CiA 402 does, and the
/// manufacturer objects, which no table names.
#[test]
fn sdo_records_name_the_object_from_the_eds() {
    let truth = truth();
    let records = records(&decode(&["--json", "--eds", EDS, LOG]));
    let mut sdo = 0;
    for record in &records {
        let Some(step) = record.get("sdo") else {
            continue;
        };
        sdo += 1;
        let line = &record["line"];
        let index = step["index"].as_u64().unwrap();
        assert_eq!(step["object"], object_name(&truth, index), "line {line}");
        if let Some(transfer) = record.get("transfer") {
            let index = transfer["index"].as_u64().unwrap();
            assert_eq!(
                transfer["object"],
                object_name(&truth, index),
                "line {line}"
            );
        }
    }
    assert_eq!(sdo, 20);
}

/// TPDO1's signals as python-canopen maps and decodes them: a sub-entry of
/// the ARRAY 20C2h is `Driver temperature.Actual temperature`, of the
/// RECORD 2010h `Digital inputs.Enable input` (docs/canopen.md#signals), with
/// the values python-canopen reads.
#[test]
fn array_and_record_sub_entries_are_named_object_dot_sub_entry() {
    let truth = truth();
    let records = records(&decode(&["--json", "--eds", EDS, LOG]));
    let frames = truth["tpdo1"]["frames"].as_array().unwrap();
    let names: Vec<&str> = truth["tpdo1"]["signals"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect();
    assert_eq!(names[1], "Driver temperature.Actual temperature");
    for frame in frames {
        let line = frame["line"].as_u64().unwrap() as usize;
        let signals = records[line - 1]["signals"].as_object().unwrap();
        // (serde_json's map sorts its keys: compare the sets.)
        let mut ours: Vec<&str> = signals.keys().map(String::as_str).collect();
        let mut want = names.clone();
        ours.sort_unstable();
        want.sort_unstable();
        assert_eq!(ours, want, "line {line}");
        for (name, value) in frame["signals"].as_object().unwrap() {
            assert_eq!(&signals[name], value, "line {line}: {name}");
        }
    }
}

/// The summary's abort names its object from the EDS too (docs/summary.md#sdo).
#[test]
fn the_summary_names_an_abort_from_the_eds() {
    let records = records(&decode(&["--summary", "--json", "--eds", EDS, LOG]));
    let node = records
        .iter()
        .find(|r| r["type"] == "node" && r["node"] == 3)
        .unwrap();
    let aborts = node["sdo"]["aborts"].as_array().unwrap();
    assert_eq!(aborts.len(), 1);
    assert_eq!(aborts[0]["object"], "Status word");
    assert_eq!(aborts[0]["line"], 17);
}
