//! The program's output is byte for byte what it was before the decoder and
//! the summary moved into the library (issue 19): every case of
//! `tests/golden/cases.txt` is run and its exit status, standard error and
//! standard output compared with the snapshot `scripts/gen_golden.sh` made.

use std::io::Read;
use std::path::Path;
use std::process::Command;

fn golden(n: usize) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{n:03}.gz"));
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

#[test]
fn output_is_unchanged_on_every_fixture() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cases = std::fs::read_to_string(root.join("tests/golden/cases.txt")).unwrap();
    let mut failures = Vec::new();
    for (i, case) in cases.lines().enumerate() {
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
        let expected = golden(i + 1);
        if found != expected {
            failures.push(format!(
                "motionwire {case}: {}",
                first_difference(&expected, &found)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
