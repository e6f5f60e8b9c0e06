//! The library alone reproduces what `motionwire decode --json` and
//! `motionwire decode --summary --json` write (SPEC §6.1, §6.3): read any
//! log with `logs::open`, decode each frame with a `Decoder`, build the
//! summary with a `Summarizer`, serialize with serde_json. Compared line
//! for line with the program's output on every fixture and the sample
//! (the snapshot `tests/golden.rs` checks the program against), with no
//! `cli` feature.

use std::io::Read;
use std::path::Path;
use std::time::Duration;

use motionwire::canopen::NodeId;
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::logs::{self, ReadLog};
use motionwire::profiles::{NodeProfiles, Profile};
use motionwire::summary::Summarizer;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The program's standard output for case `n` of `tests/golden/cases.txt`.
fn golden_stdout(n: usize) -> String {
    let file = std::fs::File::open(root().join(format!("tests/golden/{n:03}.gz"))).unwrap();
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

/// A case's options, as the library takes them.
struct Case {
    summary: bool,
    heartbeat: Option<Duration>,
    config: DecoderConfig,
    files: Vec<String>,
}

/// Read the few options the JSON cases use (`--json`, `--summary`,
/// `--heartbeat-ms`, `--profile`, `--eds`); `None` for the cases that
/// filter or write text or CSV, which are the program's own rendering.
fn case(line: &str) -> Option<Case> {
    let mut words = line.split_whitespace();
    assert_eq!(words.next(), Some("decode"));
    let (mut json, mut summary, mut heartbeat) = (false, false, None);
    let mut profiles = NodeProfiles::default();
    let mut eds = Vec::new();
    let mut files = Vec::new();
    while let Some(word) = words.next() {
        match word {
            "--json" => json = true,
            "--summary" => summary = true,
            "--heartbeat-ms" => {
                let ms = words.next()?.parse().ok()?;
                heartbeat = Some(Duration::from_millis(ms));
            }
            "--profile" => {
                let mut default = profiles.default_profile();
                let mut nodes = Vec::new();
                for item in words.next()?.split(',') {
                    match item.split_once('=') {
                        None => default = Profile::from_name(item)?,
                        Some((node, name)) => nodes
                            .push((NodeId::new(node.parse().ok()?)?, Profile::from_name(name)?)),
                    }
                }
                profiles = NodeProfiles::new(default);
                for (node, profile) in nodes {
                    profiles.set(node, profile);
                }
            }
            "--eds" => {
                let (node, path) = words.next()?.split_once('=')?;
                eds.push((NodeId::new(node.parse().ok()?)?, path.to_owned()));
            }
            file if !file.starts_with('-') => files.push(file.to_owned()),
            _ => return None,
        }
    }
    if !json {
        return None;
    }
    let mut config = DecoderConfig::new()
        .profiles_from(profiles)
        .signals(!summary);
    for (node, path) in eds {
        config = config.eds_file(node, root().join(path)).unwrap();
    }
    Some(Case {
        summary,
        heartbeat,
        config,
        files,
    })
}

/// What the library writes for a case: every frame's record, or the
/// summary's records, one JSON value a line.
fn library_output(case: Case) -> String {
    let mut decoder = Decoder::new(case.config);
    let mut summarizer = Summarizer::new();
    if let Some(time) = case.heartbeat {
        summarizer = summarizer.heartbeat_timeout(time);
    }
    let mut out = Vec::new();
    for file in &case.files {
        let mut log = logs::open(root().join(file)).unwrap();
        while let Some(next) = log.next_event() {
            // Malformed lines and damaged records are the program's
            // standard error; the records are what is compared.
            let Ok(record) = next else { continue };
            let position = record.position.number();
            if case.summary {
                summarizer.add(position, &record.event, &mut decoder);
            } else if let Some(frame) = record.event.frame() {
                decoder
                    .decode(position, frame)
                    .write_json(&mut out)
                    .unwrap();
            }
        }
    }
    if case.summary {
        for record in summarizer.finish(&mut decoder).records() {
            serde_json::to_writer(&mut out, &record).unwrap();
            out.push(b'\n');
        }
    }
    String::from_utf8(out).unwrap()
}

#[test]
fn the_library_writes_what_the_program_writes() {
    let cases = std::fs::read_to_string(root().join("tests/golden/cases.txt")).unwrap();
    let mut compared = 0;
    let mut failures = Vec::new();
    for (i, line) in cases.lines().enumerate() {
        let Some(case) = case(line) else { continue };
        let expected = golden_stdout(i + 1);
        let found = library_output(case);
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
