//! The program's output on every case of `tests/golden/cases.txt` (one
//! command line a line, the arguments after `motionwire`) is byte for byte
//! the snapshot `scripts/gen_golden.sh` made: exit status, standard error
//! and standard output. The output changes only on purpose: then the
//! script is run again and CHANGELOG.md says what changed.
//!
//! Each case's snapshot is named after the case (`common::golden_name`,
//! the rule of `scripts/gen_golden.sh`), so that adding a case adds one
//! file and renames none.

use std::collections::BTreeSet;
use std::io::Read;
use std::path::Path;
use std::process::Command;

use crate::common::golden_name;

fn golden(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name);
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut text = Vec::new();
    flate2::read::GzDecoder::new(file)
        .read_to_end(&mut text)
        .unwrap();
    text
}

/// The first line that differs, for the failure message.
fn first_difference(expected: &[u8], found: &[u8]) -> String {
    let expected = String::from_utf8_lossy(expected);
    let found = String::from_utf8_lossy(found);
    for (i, (e, f)) in expected.lines().zip(found.lines()).enumerate() {
        if e != f {
            return format!("line {}:\n  expected {e:?}\n  found    {f:?}", i + 1);
        }
    }
    format!(
        "{} lines expected, {} found",
        expected.lines().count(),
        found.lines().count()
    )
}

/// Every case names a file of its own, every file is a case's (or the
/// list of cases): a snapshot nothing compares is an error, not a leftover.
fn check_files(root: &Path, cases: &[&str]) {
    let mut names = BTreeSet::new();
    for case in cases {
        assert!(
            names.insert(golden_name(case)),
            "two cases share the snapshot {}; make the case lines differ",
            golden_name(case)
        );
    }
    let present: BTreeSet<String> = std::fs::read_dir(root.join("tests/golden"))
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .filter(|name| name != "cases.txt")
        .collect();
    let missing: Vec<_> = names.difference(&present).collect();
    let stray: Vec<_> = present.difference(&names).collect();
    assert!(
        missing.is_empty() && stray.is_empty(),
        "tests/golden: snapshots missing {missing:?}, files no case names {stray:?} \
         (bash scripts/gen_golden.sh makes them)"
    );
}

#[test]
fn output_is_unchanged_on_every_fixture() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cases = std::fs::read_to_string(root.join("tests/golden/cases.txt")).unwrap();
    let cases: Vec<&str> = cases.lines().collect();
    check_files(root, &cases);
    let mut failures = Vec::new();
    for case in cases {
        let out = Command::new(env!("CARGO_BIN_EXE_motionwire"))
            .args(case.split_whitespace())
            .current_dir(root)
            .output()
            .unwrap();
        let mut found = Vec::new();
        found.extend_from_slice(format!("status {}\n", out.status.code().unwrap()).as_bytes());
        found.extend_from_slice(format!("stderr {}\n", out.stderr.len()).as_bytes());
        found.extend_from_slice(&out.stderr);
        found.extend_from_slice(&out.stdout);
        let expected = golden(&golden_name(case));
        if found != expected {
            failures.push(format!(
                "motionwire {case}: {}",
                first_difference(&expected, &found)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
