//! The library alone reproduces what `motionwire decode --json` and
//! `motionwire decode --summary --json` write (docs/output.md#json,
//! docs/summary.md): read any log with `logs::open`, decode each frame with a
//! `Decoder`, build the summary with a `Summarizer`, serialize with serde_json.
//! Compared line for line with the program's output on every fixture and the
//! sample (the snapshot `tests/program/golden.rs` checks the program
//! against), with no `cli` feature.

use std::io::Read;
use std::path::Path;

use crate::common::{golden_name, Run};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The program's standard output for `case`, a line of
/// `tests/golden/cases.txt`.
fn golden_stdout(case: &str) -> String {
    let file = std::fs::File::open(root().join("tests/golden").join(golden_name(case))).unwrap();
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap();
    // "status N\nstderr LEN\n" + stderr + stdout.
    let mut rest = text.as_str();
    let mut next_line = || {
        let (line, after) = rest.split_once('\n').unwrap();
        rest = after;
        line.to_owned()
    };
    let _status = next_line();
    let stderr_len: usize = next_line()
        .strip_prefix("stderr ")
        .unwrap()
        .parse()
        .unwrap();
    rest[stderr_len..].to_owned()
}

#[test]
fn the_library_writes_what_the_program_writes() {
    let cases = std::fs::read_to_string(root().join("tests/golden/cases.txt")).unwrap();
    let mut compared = 0;
    let mut failures = Vec::new();
    for line in cases.lines() {
        let args = line.split_whitespace().skip(1);
        let Some(run) = Run::from_args(args).filter(|_| line.contains("--json")) else {
            continue;
        };
        let expected = golden_stdout(line);
        let found = run.output();
        compared += 1;
        if found != expected {
            let at = expected
                .lines()
                .zip(found.lines())
                .position(|(e, f)| e != f)
                .map_or_else(
                    || "the line count".to_owned(),
                    |k| format!("line {}", k + 1),
                );
            failures.push(format!("motionwire {line}: differs at {at}"));
        }
    }
    assert!(compared >= 80, "only {compared} JSON cases");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `Decoded::columns` (the Python package's `decode` columns) holds what the
/// record's `code`, `register`, `description` and `state` keys hold, on every
/// frame of the sample and the SDO fixtures (EMCYs whole and truncated,
/// heartbeats, boot-ups, guarding answers).
#[test]
fn columns_hold_what_the_record_holds() {
    use motionwire::decoder::{Decoder, DecoderConfig};
    use motionwire::logs::{self, ReadLog};
    use serde_json::Value;

    let mut seen = [0; 4];
    for file in [
        "samples/machine.log",
        "tests/fixtures/sdo/broken.log",
        "tests/fixtures/python_can.log",
    ] {
        let mut decoder = Decoder::new(DecoderConfig::new());
        let mut log = logs::open(root().join(file)).unwrap();
        while let Some(next) = log.next_event() {
            let Ok(record) = next else { continue };
            let Some(frame) = record.event.frame() else {
                continue;
            };
            let decoded = decoder.decode(record.position, frame);
            let json: Value = serde_json::from_str(&decoded.to_json()).unwrap();
            let columns = decoded.columns();
            let keys = [
                columns.code.map(|c| Value::from(c.get())),
                columns.register.map(|r| Value::from(r.bits())),
                columns.description.map(Value::from),
                columns.state.map(Value::from),
            ];
            for (i, (key, value)) in ["code", "register", "description", "state"]
                .iter()
                .zip(keys)
                .enumerate()
            {
                assert_eq!(
                    json.get(key),
                    value.as_ref(),
                    "{file}:{}: {key}",
                    decoded.position
                );
                seen[i] += usize::from(value.is_some());
            }
        }
    }
    assert!(seen.iter().all(|&n| n > 10), "{seen:?}");
}
