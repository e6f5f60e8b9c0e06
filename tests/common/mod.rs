//! What the decoder's integration tests share: run `motionwire decode` and
//! read its JSON lines.

use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;

/// Run `motionwire decode ARGS`, which must succeed.
pub fn decode(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_motionwire"))
        .arg("decode")
        .args(args)
        .output()
        .expect("the motionwire binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Every stdout line as JSON.
pub fn records(out: &Output) -> Vec<Value> {
    String::from_utf8(out.stdout.clone())
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

/// A path inside the repository.
pub fn path(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(rel)
        .to_str()
        .unwrap()
        .to_owned()
}
