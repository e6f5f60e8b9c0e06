//! What the report's tests share: run `motionwire report`, and read a page
//! as a script would, by its contract (docs/report.md#contract): the rows,
//! the marks and bands of each row with their `data-*`, and the embedded
//! summary records.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_motionwire"))
}

pub fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// A folder of its own for one test's files.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("motionwire-report-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `motionwire ARGS`.
pub fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("the program runs")
}

/// An element's tag and attributes.
#[derive(Debug, Clone)]
pub struct Element {
    pub tag: String,
    pub attrs: BTreeMap<String, String>,
}

impl Element {
    pub fn get(&self, name: &str) -> Option<&str> {
        self.attrs.get(name).map(String::as_str)
    }

    pub fn num(&self, name: &str) -> u64 {
        self.get(name)
            .unwrap_or_else(|| panic!("{name} on {self:?}"))
            .parse()
            .unwrap()
    }
}

/// A row of the timeline (a `g` with `data-row`) and what is inside it.
#[derive(Debug, Clone)]
pub struct Row {
    pub row: Element,
    pub items: Vec<Element>,
}

impl Row {
    pub fn is_node(&self, iface: &str, node: u64) -> bool {
        self.row.get("data-row") == Some("node")
            && self.row.get("data-iface") == Some(iface)
            && self.row.get("data-node") == Some(&node.to_string())
    }

    /// The elements of a `data-kind`.
    pub fn kind(&self, kind: &str) -> Vec<&Element> {
        self.items
            .iter()
            .filter(|e| e.get("data-kind") == Some(kind))
            .collect()
    }

    /// What the `data-count`s of a kind add up to.
    pub fn count(&self, kind: &str) -> u64 {
        self.kind(kind).iter().map(|e| e.num("data-count")).sum()
    }

    /// The `data-line`s of a kind.
    pub fn lines(&self, kind: &str) -> Vec<u64> {
        self.kind(kind).iter().map(|e| e.num("data-line")).collect()
    }
}

/// A page read by its contract.
#[derive(Debug)]
pub struct Page {
    pub html: String,
    pub elements: Vec<Element>,
    pub rows: Vec<Row>,
}

fn unescape(text: &str) -> String {
    text.replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// Read the start tags of `html` (a page as the program writes it, or a DOM
/// as a browser serializes it: attributes in double quotes), and which row
/// each is in.
pub fn parse(html: &str) -> Page {
    let mut elements = Vec::new();
    let mut rows: Vec<Row> = Vec::new();
    // The open rows: the index in `rows` and the depth of `g` they opened at.
    let mut open: Option<(usize, usize)> = None;
    let mut depth = 0usize;
    let bytes = html.as_bytes();
    let mut i = 0;
    let mut raw_until: Option<&str> = None;
    while let Some(at) = html[i..].find('<') {
        let start = i + at;
        if let Some(end_tag) = raw_until {
            // Inside a script or style: only its end tag counts.
            let Some(close) = html[start..].find(end_tag) else {
                break;
            };
            i = start + close + end_tag.len();
            raw_until = None;
            continue;
        }
        if html[start..].starts_with("<!--") {
            i = start
                + html[start..]
                    .find("-->")
                    .map_or(html.len() - start, |e| e + 3);
            continue;
        }
        let Some(len) = html[start..].find('>') else {
            break;
        };
        let tag_text = &html[start + 1..start + len];
        i = start + len + 1;
        if let Some(name) = tag_text.strip_prefix('/') {
            if name.trim() == "g" {
                depth = depth.saturating_sub(1);
                if let Some((_, at_depth)) = open {
                    if depth < at_depth {
                        open = None;
                    }
                }
            }
            continue;
        }
        if tag_text.starts_with('!') {
            continue;
        }
        let self_closing = tag_text.ends_with('/');
        let tag_text = tag_text.trim_end_matches('/');
        let name_end = tag_text
            .find(|c: char| c.is_whitespace())
            .unwrap_or(tag_text.len());
        let tag = tag_text[..name_end].to_ascii_lowercase();
        let mut attrs = BTreeMap::new();
        let mut rest = &tag_text[name_end..];
        loop {
            rest = rest.trim_start();
            if rest.is_empty() {
                break;
            }
            let name_len = rest
                .find(|c: char| c == '=' || c.is_whitespace())
                .unwrap_or(rest.len());
            let name = rest[..name_len].to_owned();
            rest = &rest[name_len..];
            if let Some(after) = rest.strip_prefix('=') {
                let after = after.trim_start();
                let (value, next) = if let Some(q) = after.strip_prefix('"') {
                    let end = q.find('"').expect("closing quote");
                    (&q[..end], &q[end + 1..])
                } else {
                    let end = after
                        .find(|c: char| c.is_whitespace())
                        .unwrap_or(after.len());
                    (&after[..end], &after[end..])
                };
                attrs.insert(name, unescape(value));
                rest = next;
            } else {
                attrs.insert(name, String::new());
            }
        }
        let _ = bytes;
        let element = Element {
            tag: tag.clone(),
            attrs,
        };
        if tag == "script" || tag == "style" {
            raw_until = Some(if tag == "script" {
                "</script>"
            } else {
                "</style>"
            });
        }
        if tag == "g" && !self_closing {
            depth += 1;
            if element.get("data-row").is_some() {
                rows.push(Row {
                    row: element.clone(),
                    items: Vec::new(),
                });
                open = Some((rows.len() - 1, depth));
            }
        } else if let Some((row, _)) = open {
            rows[row].items.push(element.clone());
        }
        elements.push(element);
    }
    Page {
        html: html.to_owned(),
        elements,
        rows,
    }
}

impl Page {
    /// The embedded summary records.
    pub fn summary(&self) -> Value {
        let open = "<script type=\"application/json\" id=\"motionwire-summary\">";
        let start = self.html.find(open).expect("the summary's script") + open.len();
        let end = self.html[start..].find("</script>").expect("its end") + start;
        serde_json::from_str(&self.html[start..end]).expect("JSON")
    }

    pub fn node_rows(&self) -> Vec<&Row> {
        self.rows
            .iter()
            .filter(|r| r.row.get("data-row") == Some("node"))
            .collect()
    }

    pub fn node(&self, iface: &str, node: u64) -> &Row {
        self.rows
            .iter()
            .find(|r| r.is_node(iface, node))
            .unwrap_or_else(|| panic!("no row for {iface} node {node}"))
    }

    pub fn body(&self) -> &Element {
        self.elements
            .iter()
            .find(|e| e.tag == "body")
            .expect("body")
    }
}

/// The records of `decode --summary --json ARGS`.
pub fn summary_records(args: &[&str]) -> Value {
    let mut all = vec!["decode", "--summary", "--json"];
    all.extend_from_slice(args);
    let out = run(&all);
    let text = String::from_utf8(out.stdout).unwrap();
    Value::Array(
        text.lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect(),
    )
}

/// Check every row against the summary's records: one row per node
/// record, and the `data-count`s of each kind adding up to its count
/// (docs/report.md#contract).
pub fn check_counts(page: &Page, records: &Value) {
    let records = records.as_array().unwrap();
    let nodes: Vec<&Value> = records.iter().filter(|r| r["type"] == "node").collect();
    assert_eq!(page.node_rows().len(), nodes.len(), "one row per device");
    for n in nodes {
        let iface = n["iface"].as_str().unwrap_or("");
        let id = n["node"].as_u64().unwrap();
        let row = page
            .rows
            .iter()
            .find(|r| {
                r.is_node(iface, id)
                    && r.row.get("data-file") == n.get("file").and_then(Value::as_str)
            })
            .unwrap_or_else(|| panic!("row of {n}"));
        // A list's count (docs/summary.md#lists), after checking that the
        // list keeps as many of its events as it should: all of them up
        // to 20, else the first 10 and the last 10.
        let len = |list: &Value, count: &Value| {
            let count = count.as_u64().unwrap_or(0);
            assert_eq!(
                list.as_array().map_or(0, Vec::len) as u64,
                count.min(20),
                "a list of {count} in {n}"
            );
            count
        };
        let what = format!("{iface} node {id}");
        let emcy = n["emcy"].as_u64().unwrap();
        let resets = n["resets"].as_u64().unwrap();
        assert_eq!(row.count("emcy"), emcy - resets, "emcy of {what}");
        assert_eq!(row.count("emcy_reset"), resets, "emcy_reset of {what}");
        assert_eq!(
            row.count("boot_up"),
            len(
                &n["heartbeat"]["boot_ups"],
                &n["heartbeat"]["boot_up_count"]
            ),
            "boot_up of {what}"
        );
        assert_eq!(
            row.count("heartbeat_timeout"),
            len(
                &n["heartbeat"]["timeouts"],
                &n["heartbeat"]["timeout_count"]
            ),
            "heartbeat_timeout of {what}"
        );
        assert_eq!(
            row.count("sdo_abort"),
            len(&n["sdo"]["aborts"], &n["sdo"]["abort_count"]),
            "sdo_abort of {what}"
        );
        assert_eq!(
            row.count("sdo_broken"),
            len(&n["sdo"]["broken"], &n["sdo"]["broken_count"]),
            "sdo_broken of {what}"
        );
        assert_eq!(
            row.count("sdo_timeout"),
            len(&n["sdo"]["timeouts"], &n["sdo"]["timeout_count"]),
            "sdo_timeout of {what}"
        );
        assert_eq!(
            row.count("toggle_error"),
            len(
                &n["guarding"]["toggle_errors"],
                &n["guarding"]["toggle_error_count"]
            ),
            "toggle_error of {what}"
        );
        assert_eq!(
            row.count("cia402_fault"),
            len(&n["cia402"]["faults"], &n["cia402"]["fault_count"]),
            "cia402_fault of {what}"
        );
        assert_eq!(
            row.count("cia402_state"),
            len(
                &n["cia402"]["transitions"],
                &n["cia402"]["transition_count"]
            ),
            "cia402_state bands of {what}"
        );
        for band in row
            .kind("nmt_state")
            .into_iter()
            .chain(row.kind("cia402_state"))
        {
            assert!(band.get("data-state").is_some() && band.get("data-line").is_some());
        }
    }
    for b in records.iter().filter(|r| r["type"] == "bus") {
        let iface = b["iface"].as_str().unwrap_or("");
        let row = page
            .rows
            .iter()
            .find(|r| {
                r.row.get("data-row") == Some("bus")
                    && r.row.get("data-iface") == Some(iface)
                    && r.row.get("data-file") == b.get("file").and_then(Value::as_str)
            })
            .unwrap_or_else(|| panic!("row of {b}"));
        assert_eq!(
            row.count("error_frame"),
            b["error_frames"].as_u64().unwrap()
        );
        assert_eq!(row.count("bus_off"), b["bus_off_count"].as_u64().unwrap());
        assert_eq!(
            row.count("error_passive"),
            b["error_passive_count"].as_u64().unwrap()
        );
    }
}

/// Check the EtherCAT rows against the summary's records
/// (docs/report.md#ethercat): one row per slave and per stream record, the
/// AL bands one per reported AL change, in order, and the `data-count`s of
/// each kind adding up to the records' counts.
pub fn check_ethercat(page: &Page, records: &Value) {
    let records = records.as_array().unwrap();
    let of = |row: &str| {
        page.rows
            .iter()
            .filter(|r| r.row.get("data-row") == Some(row))
            .count()
    };
    let slaves: Vec<&Value> = records.iter().filter(|r| r["type"] == "slave").collect();
    let streams: Vec<&Value> = records.iter().filter(|r| r["type"] == "stream").collect();
    assert_eq!(of("slave"), slaves.len(), "one row per slave");
    assert_eq!(of("stream"), streams.len(), "one row per stream");
    let text = |v: &Value| match v {
        Value::Null => String::new(),
        v => v.as_str().map_or_else(|| v.to_string(), str::to_owned),
    };
    for s in slaves {
        let iface = text(&s["iface"]);
        let row = page
            .rows
            .iter()
            .find(|r| {
                r.row.get("data-row") == Some("slave")
                    && r.row.get("data-iface") == Some(iface.as_str())
                    && r.row.get("data-slave") == Some(text(&s["slave"]).as_str())
                    && r.row.get("data-position").map(str::to_owned)
                        == s["position"].as_u64().map(|p| p.to_string())
            })
            .unwrap_or_else(|| panic!("row of {s}"));
        let what = format!("{iface} slave {}", s["slave"]);
        assert_eq!(s["al_timeline_dropped"], 0, "every change listed in {what}");
        let reported: Vec<&Value> = s["al_timeline"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["requested"] == false)
            .collect();
        let bands = row.kind("al_state");
        assert_eq!(
            row.count("al_state"),
            reported.len() as u64,
            "AL bands of {what}"
        );
        if bands.iter().all(|b| b.num("data-count") == 1) {
            for (band, change) in bands.iter().zip(&reported) {
                let state = change["state"].as_str().unwrap_or("unknown");
                assert_eq!(band.get("data-state"), Some(state), "{what}: {change}");
                assert_eq!(band.num("data-line"), change["packet"].as_u64().unwrap());
                assert_eq!(
                    band.get("data-error") == Some("true"),
                    change["error"] == true,
                    "{what}: {change}"
                );
            }
        }
        let errors = reported.iter().filter(|c| c["error"] == true).count() as u64;
        assert_eq!(row.count("al_error"), errors, "al_error of {what}");
        assert_eq!(
            row.count("coe_emcy"),
            s["emcy_count"].as_u64().unwrap(),
            "coe_emcy of {what}"
        );
        assert_eq!(
            row.count("sdo_abort"),
            s["sdo_aborts"].as_u64().unwrap(),
            "sdo_abort of {what}"
        );
        let len = |key: &str| s[key].as_array().unwrap().len() as u64;
        assert_eq!(row.count("dl_change"), len("dl_status_changes"), "{what}");
        assert_eq!(
            row.count("error_counter"),
            len("error_counter_rises"),
            "{what}"
        );
        // A servo's bands and marks add up to its timeline's counts
        // (docs/report.md#marks); a slave not read as a servo has none.
        let servo = &s["servo"];
        let servo_count = |key: &str| {
            if servo.is_null() {
                0
            } else {
                servo[key]
                    .as_u64()
                    .unwrap_or_else(|| panic!("{key} of {what}"))
            }
        };
        for (kind, key) in [
            ("servo_enable", "enable_change_count"),
            ("servo_fault", "fault_set_count"),
            ("servo_error_clear", "error_clear_count"),
            ("servo_zero_pulse", "zero_pulse_count"),
            ("servo_not_ready", "not_ready_count"),
            ("servo_enable_unanswered", "enable_unanswered"),
        ] {
            assert_eq!(row.count(kind), servo_count(key), "{kind} of {what}");
        }
        let cia402 = &s["cia402"];
        if !cia402.is_null() {
            assert_eq!(
                row.count("cia402_state"),
                cia402["transition_count"].as_u64().unwrap(),
                "CiA 402 bands of {what}"
            );
            assert_eq!(
                row.count("cia402_fault"),
                cia402["fault_count"].as_u64().unwrap(),
                "cia402_fault of {what}"
            );
        }
        for mark in &row.items {
            if let Some(kind) = mark.get("data-kind") {
                if kind != "al_state" {
                    assert!(
                        mark.get("data-line").is_some() && mark.get("data-count").is_some(),
                        "{what}: {mark:?}"
                    );
                }
            }
        }
    }
    for s in streams {
        let iface = text(&s["iface"]);
        let cmd = s["cmd"].as_str().unwrap();
        let row = page
            .rows
            .iter()
            .find(|r| {
                let same = |key: &str| {
                    r.row.get(&format!("data-{key}")).map(str::to_owned)
                        == s.get(key).map(|v| v.to_string())
                };
                r.row.get("data-row") == Some("stream")
                    && r.row.get("data-iface") == Some(iface.as_str())
                    && r.row.get("data-cmd") == Some(cmd)
                    && same("logical")
                    && same("adp")
                    && same("ado")
            })
            .unwrap_or_else(|| panic!("row of {s}"));
        let key = row.row.get("data-stream").unwrap();
        assert!(key.starts_with(&format!("{cmd} ")), "{key}");
        assert_eq!(
            row.count("lost_frame"),
            s["lost"].as_u64().unwrap(),
            "{key}"
        );
        assert_eq!(
            row.count("wkc_mismatch"),
            s["wkc_mismatches"].as_u64().unwrap(),
            "{key}"
        );
        if let Some(first) = s["first_mismatch_packet"].as_u64() {
            assert_eq!(row.lines("wkc_mismatch")[0], first, "{key}");
        }
    }
}
