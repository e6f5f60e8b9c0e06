//! What the decoder's integration tests share: decode a log with the
//! library as `motionwire decode ARGS` would, and read its JSON records.
//!
//! [`decode`] takes the program's options that the tests use — `--json`
//! (implied), `--summary`, `--heartbeat-ms MS`, `--profile LIST`, `--eds
//! NODE=FILE` — and builds the library's configuration from them, so that
//! the tests check the library itself (no `cli` feature) while reading as
//! the command lines they stand for; `tests/library/library.rs` checks that
//! the program writes the same on every fixture. `tests/program/golden.rs`
//! and `tests/library/library.rs` find a case's snapshot by
//! [`golden_name`].
#![allow(dead_code)]

use std::path::Path;
use std::time::Duration;

use motionwire::canopen::NodeId;
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::logs::{self, ReadLog};
use motionwire::profiles::{NodeProfiles, Profile};
use motionwire::summary::Summarizer;
use serde_json::Value;

/// A decoding as `motionwire decode` would run it.
pub struct Run {
    /// `--summary`: the summary's records instead of one per frame.
    pub summary: bool,
    /// `--heartbeat-ms`.
    pub heartbeat: Option<Duration>,
    /// `--profile` and `--eds`.
    pub config: DecoderConfig,
    /// The logs, read one after the other.
    pub files: Vec<String>,
}

impl Run {
    /// Read the options of `motionwire decode ARGS`; `None` for an option
    /// outside the list above (the program's filters and renderings).
    pub fn from_args<'a>(args: impl IntoIterator<Item = &'a str>) -> Option<Run> {
        let mut words = args.into_iter();
        let (mut summary, mut heartbeat) = (false, None);
        let mut profiles = NodeProfiles::default();
        let mut eds = Vec::new();
        let mut files = Vec::new();
        while let Some(word) = words.next() {
            match word {
                "--json" => {}
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
                            Some((node, name)) => nodes.push((
                                NodeId::new(node.parse().ok()?)?,
                                Profile::from_name(name)?,
                            )),
                        }
                    }
                    profiles = NodeProfiles::new(default);
                    for (node, profile) in nodes {
                        profiles.set(node, profile);
                    }
                }
                "--eds" => {
                    let (node, file) = words.next()?.split_once('=')?;
                    eds.push((NodeId::new(node.parse().ok()?)?, file.to_owned()));
                }
                file if !file.starts_with('-') => files.push(file.to_owned()),
                _ => return None,
            }
        }
        let mut config = DecoderConfig::new()
            .profiles_from(profiles)
            .signals(!summary);
        for (node, file) in eds {
            config = config.eds_file(node, path(&file)).unwrap();
        }
        Some(Run {
            summary,
            heartbeat,
            config,
            files,
        })
    }

    /// Decode: every frame's JSON record, or the summary's records, one a
    /// line, as the program writes them to standard output. Several files
    /// are several recordings, each decoded and summarized apart, every
    /// record naming its file (docs/output.md#several-files).
    pub fn output(self) -> String {
        let several = self.files.len() > 1;
        let mut out = Vec::new();
        for file in &self.files {
            let mut decoder = Decoder::new(self.config.clone());
            let mut config = self.config.clone();
            if let Some(time) = self.heartbeat {
                config = config.heartbeat_timeout(time);
            }
            let mut summarizer = Summarizer::new(config);
            let mut ethercat = motionwire::decoder::ethercat::Session::new();
            let mut log = logs::open(path(file)).unwrap();
            while let Some(next) = log.next_event() {
                // Malformed lines and damaged records go to the program's
                // standard error; the records are what is compared.
                let Ok(record) = next else { continue };
                let position = record.position;
                if self.summary {
                    summarizer.add(position, &record.event);
                } else if let Some(frame) = record.event.frame() {
                    let decoded = decoder.decode(position, frame);
                    if several {
                        decoded.write_json_in(&mut out, file).unwrap();
                    } else {
                        decoded.write_json(&mut out).unwrap();
                    }
                } else if let motionwire::can::LogEvent::Ethercat(packet) = &record.event {
                    // docs/ethercat.md#records: a record per datagram.
                    let Ok(packet) = ethercat.read(position, packet) else {
                        continue;
                    };
                    for (at, datagram) in packet.datagrams().enumerate() {
                        let Ok(datagram) = datagram else { break };
                        let record = motionwire::decoder::ethercat::DatagramRecord {
                            packet: &packet,
                            number: at + 1,
                            datagram,
                        };
                        record.append_json(&mut out, several.then_some(file.as_str()));
                        let mut meanings = Vec::new();
                        ethercat.meanings(&packet, at, &datagram, |m| meanings.push(m));
                        for meaning in meanings {
                            let record = motionwire::decoder::ethercat::MeaningRecord {
                                packet: &packet,
                                number: at + 1,
                                meaning,
                            };
                            // docs/ethercat.md#filters: a record a cycle or
                            // a poll only when `--only` names it.
                            if motionwire::decoder::ethercat::QUIET_KINDS.contains(&record.kind()) {
                                continue;
                            }
                            record.append_json(&mut out, several.then_some(file.as_str()));
                        }
                        // docs/ethercat.md#process-data: a record per slave
                        // of a returned cyclic datagram.
                        ethercat.process_data(&packet, at, &datagram, |data| {
                            let record = motionwire::decoder::ethercat::ProcessRecord {
                                packet: &packet,
                                number: at + 1,
                                data,
                            };
                            record.append_json(&mut out, several.then_some(file.as_str()));
                            record.append_servo_json(&mut out, several.then_some(file.as_str()));
                        });
                    }
                }
            }
            if self.summary {
                let mut summary = summarizer.finish();
                summary.file = several.then(|| file.clone());
                summary.write_json(&mut out).unwrap();
            }
        }
        String::from_utf8(out).unwrap()
    }
}

/// Decode as `motionwire decode ARGS` (with the options of [`Run`]).
pub fn decode(args: &[&str]) -> String {
    Run::from_args(args.iter().copied())
        .unwrap_or_else(|| panic!("options the tests do not know: {args:?}"))
        .output()
}

/// Every output line as JSON.
pub fn records(out: &str) -> Vec<Value> {
    out.lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

/// A path inside the repository (an absolute path stays as it is).
pub fn path(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(rel)
        .to_str()
        .unwrap()
        .to_owned()
}

/// The file name of a case's snapshot in `tests/golden/` (the case one line
/// of `tests/golden/cases.txt`, the arguments after `motionwire`): the
/// arguments joined by `_`, with the fixtures' directory `tests/fixtures/`
/// left out and every other `/` and every `:` written `-` (a name every file
/// system holds, Windows' too), then `.gz`. `decode --json
/// tests/fixtures/pcap/sll.pcap` is `decode_--json_pcap-sll.pcap.gz`.
/// `scripts/gen_golden.sh` and the Python tests name them by the same rule.
pub fn golden_name(case: &str) -> String {
    let words: Vec<&str> = case.split_whitespace().collect();
    let name = words
        .join("_")
        .replace("tests/fixtures/", "")
        .replace(['/', ':'], "-");
    format!("{name}.gz")
}
