//! One log's post-mortem in one pass, for the tables of a fleet
//! (`motionwire.spark`, docs/spark.md): the summary's records as the
//! program writes them, the file's own record (format, frames read, lines
//! skipped and why), and with `findings=True` what went wrong with the
//! code each finding is about. Rows of a Spark DataFrame are made from
//! these in Python; the reading is the library's, with the GIL released.

use std::time::Duration;

use motionwire::can::{BusName, LogEvent};
use motionwire::decoder::DecoderConfig;
use motionwire::logs::{LogErrorKind, LogVisitor, Position, ReadLog};
use motionwire::report::Recorder;
use motionwire::summary::{Finding, FindingCause, FindingDetail, Summarizer, Summary};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use serde_json::{json, Value};

use crate::error::Failure;
use crate::source::{self, Source};

/// How many skipped lines the file's record lists (the first ones; its
/// `skipped_count` counts them all).
const SKIPPED_LISTED: usize = 10;

/// One finding as a row: `line`, `ts`, `iface`, `node`, `slave`, `kind`,
/// `severity`, `code`, `text`.
type FindingRow = (
    u64,
    Option<f64>,
    Option<String>,
    Option<u8>,
    Option<u16>,
    &'static str,
    &'static str,
    Option<u32>,
    String,
);

/// A log's post-mortem for a fleet's tables (docs/spark.md#summary): a
/// tuple `(file, records, findings)`. `file` is the file's JSON record
/// (`{"type": "file", "format", "frames", "ethercat_packets", "skipped",
/// "skipped_count"}`), `records` the JSON records of `decode --summary
/// --json` as strings, `findings` a list of `(line, ts, iface, node, slave,
/// kind, severity, code, text)` with `findings=True`, else None. An unreadable
/// log raises what `summary` raises.
#[pyfunction]
#[pyo3(signature = (source, *, heartbeat_ms = None, profiles = None, eds = None, format = None, findings = false))]
pub fn post_mortem<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    heartbeat_ms: Option<u64>,
    profiles: Option<&Bound<'py, PyAny>>,
    eds: Option<&Bound<'py, PyDict>>,
    format: Option<&str>,
    findings: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let mut config = crate::config(profiles, eds)?.signals(false);
    if let Some(ms) = heartbeat_ms {
        config = config.heartbeat_timeout(Duration::from_millis(ms));
    }
    let PostMortem {
        file,
        records,
        findings,
    } = py.detach(|| read(&source, options, config, findings))?;
    let records = PyList::new(py, records)?;
    let rows = match findings {
        Some(rows) => PyList::new(py, rows)?.into_any(),
        None => py.None().into_bound(py),
    };
    PyTuple::new(
        py,
        [file.into_pyobject(py)?.into_any(), records.into_any(), rows],
    )
}

/// The pass over the log without the GIL: a [`Summarizer`], or a
/// [`Recorder`] when the findings are asked for (their times are the
/// report timeline's, as `motionwire.findings` gives them).
fn read(
    source: &Source,
    options: motionwire::logs::ReadOptions,
    config: DecoderConfig,
    findings: bool,
) -> Result<PostMortem, Failure> {
    let name = source.name();
    let mut log = source.open(options, &name)?;
    let (summary, counted, rows) = if findings {
        let mut recorder = Recorder::new(config);
        let counted = log.visit(Count {
            feed: |position, event: &LogEvent<'_>| recorder.add(position, event),
            name: &name,
        })?;
        let recording = recorder.finish();
        let rows = recording.findings().iter().map(row).collect();
        (recording.summary, counted, Some(rows))
    } else {
        let mut summarizer = Summarizer::new(config);
        let counted = log.visit(Count {
            feed: |position, event: &LogEvent<'_>| summarizer.add(position, event),
            name: &name,
        })?;
        (summarizer.finish(), counted, None)
    };
    Ok(PostMortem {
        file: counted.record(),
        records: records(&summary),
        findings: rows,
    })
}

/// What [`read`] gives: the file's record, the summary's, the findings.
struct PostMortem {
    file: String,
    records: Vec<String>,
    findings: Option<Vec<FindingRow>>,
}

/// The summary's records, as `decode --summary --json` writes them.
fn records(summary: &Summary) -> Vec<String> {
    summary.records().map(|record| record.to_json()).collect()
}

/// A finding's row. `code` is the EMCY code of a first error or warning,
/// or of the EMCY that caused a drive's fault (docs/summary.md#causes),
/// or the abort code of an SDO abort; null for the other kinds.
fn row(finding: &Finding) -> FindingRow {
    let code = match (&finding.detail, &finding.cause) {
        (FindingDetail::Emcy(emcy), _) => Some(u32::from(emcy.code.get())),
        (FindingDetail::SdoAbort(abort), _) => Some(abort.code.get()),
        (_, Some(FindingCause::Emcy(emcy))) => Some(u32::from(emcy.code.get())),
        _ => None,
    };
    let iface = match &finding.bus {
        BusName::Unnamed => None,
        bus => Some(bus.to_string()),
    };
    (
        finding.line,
        finding.timestamp.map(|ts| ts.as_secs_f64()),
        iface,
        finding.node.map(|node| node.get()),
        finding.slave.and_then(|slave| slave.station),
        finding.kind.name(),
        finding.severity.name(),
        code,
        finding.text(),
    )
}

/// What a pass counted besides what it fed: the file's record.
#[derive(Default)]
struct Counted {
    format: Option<&'static str>,
    frames: u64,
    ethercat_packets: u64,
    skipped_count: u64,
    skipped: Vec<Value>,
}

impl Counted {
    /// The file's record (docs/spark.md#file-rows).
    fn record(&self) -> String {
        // Written key by key so that `type` comes first, as in the
        // summary's records.
        format!(
            r#"{{"type":"file","format":{},"frames":{},"ethercat_packets":{},"skipped":{},"skipped_count":{}}}"#,
            json!(self.format),
            self.frames,
            self.ethercat_packets,
            Value::Array(self.skipped.clone()),
            self.skipped_count,
        )
    }
}

/// Every entry of a log fed to `feed` (a `Summarizer`'s or a `Recorder`'s
/// `add`), its CAN frames and EtherCAT packets counted and its malformed
/// lines and damaged records counted with the first reasons, as
/// `read_log` lists them (docs/python.md#metadata); a read error the end.
struct Count<'a, F> {
    feed: F,
    name: &'a str,
}

impl<F: FnMut(Position, &LogEvent<'_>)> LogVisitor for Count<'_, F> {
    type Output = Result<Counted, Failure>;

    fn visit<L: ReadLog + ?Sized>(mut self, log: &mut L) -> Result<Counted, Failure> {
        let mut counted = Counted {
            format: Some(log.format().name()),
            ..Counted::default()
        };
        while let Some(next) = log.next_event() {
            match next {
                Ok(record) => {
                    match record.event {
                        LogEvent::Frame(_) => counted.frames += 1,
                        LogEvent::Ethercat(_) => counted.ethercat_packets += 1,
                        LogEvent::Status(_) => {}
                    }
                    (self.feed)(record.position, &record.event);
                }
                Err(error) => {
                    if matches!(error.kind(), LogErrorKind::Io(_)) {
                        return Err(Failure::log(self.name, error));
                    }
                    counted.skipped_count += 1;
                    if counted.skipped.len() < SKIPPED_LISTED {
                        let line = error.position().map(|p| p.number());
                        counted
                            .skipped
                            .push(json!({"line": line, "reason": error.kind().to_string()}));
                    }
                }
            }
        }
        Ok(counted)
    }
}
