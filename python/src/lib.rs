//! The native module of the Python package `motionwire` (docs/python.md):
//! logs read by the library's readers into Arrow tables built column by
//! column, the decoder session's columns and JSON records, the summary's
//! records, python-can messages. Every value comes from the library; this
//! crate only moves it into Arrow and Python, with the GIL released while
//! a log is read.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Duration;

use arrow_pyarrow::{IntoPyArrow, Table};
use motionwire::canopen::NodeId;
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::profiles::{NodeProfiles, Profile};
use motionwire::report::Recorder;
use motionwire::summary::Summarizer;
use pyo3::exceptions::{PyNotImplementedError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

mod columns;
mod error;
mod ethercat;
mod fleet;
mod reader;
mod source;
mod table;

use error::{Failure, LogError};
use source::Source;
use table::{Columns, Fill, Finished};

/// Read one log into its columns, decoding each frame with `decoder` when
/// there is one (no GIL). `name` names the log in messages; `file` in the
/// skipped lines (`read_logs`).
fn fill(
    source: &Source,
    name: &str,
    options: motionwire::logs::ReadOptions,
    decoder: Option<&mut Decoder>,
    file: Option<&str>,
) -> Result<Finished, Failure> {
    let mut log = source.open(options, name)?;
    let mut columns = Columns::new(decoder.is_some());
    log.visit(Fill {
        columns: &mut columns,
        decoder,
        name,
        file,
    })?;
    Ok(columns.finish())
}

/// The pyarrow table of `logs`.
fn to_pyarrow(
    py: Python<'_>,
    logs: Vec<Finished>,
    files: Option<&[String]>,
) -> PyResult<Py<PyAny>> {
    let (schema, batches) = py
        .detach(|| table::batches(logs, files))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let table =
        Table::try_new(batches, schema).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(table.into_pyarrow(py)?.unbind())
}

/// Read a log into a pyarrow.Table, one row per frame (docs/python.md#read-log).
#[pyfunction]
#[pyo3(signature = (source, format = None))]
fn read_log(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let name = source.name();
    let finished = py.detach(|| fill(&source, &name, options, None, None))?;
    to_pyarrow(py, vec![finished], None)
}

/// Read many logs on Rust threads into one pyarrow.Table with a `file`
/// column (docs/python.md#read-logs).
#[pyfunction]
#[pyo3(signature = (sources, threads = None, *, format = None))]
fn read_logs(
    py: Python<'_>,
    sources: &Bound<'_, PyAny>,
    threads: Option<usize>,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let sources = source::extract_all(sources)?;
    let options = source::options(format)?;
    if threads == Some(0) {
        return Err(PyValueError::new_err("threads must be at least 1"));
    }
    let files: Vec<String> = sources
        .iter()
        .enumerate()
        .map(|(i, source)| match source {
            Source::Path(_) => source.name(),
            Source::Bytes(_) => format!("<bytes {i}>"),
        })
        .collect();
    let threads = threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .min(sources.len())
        .max(1);
    let results = py.detach(|| {
        let next = AtomicUsize::new(0);
        let results: Vec<Mutex<Option<Result<Finished, Failure>>>> =
            sources.iter().map(|_| Mutex::new(None)).collect();
        std::thread::scope(|scope| {
            for _ in 0..threads {
                scope.spawn(|| loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(source) = sources.get(i) else {
                        break;
                    };
                    let name = &files[i];
                    let result = fill(source, name, options, None, Some(name));
                    *results[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(result);
                });
            }
        });
        results
            .into_iter()
            .map(|slot| {
                slot.into_inner()
                    .unwrap_or_else(|e| e.into_inner())
                    .expect("every log is read")
            })
            .collect::<Result<Vec<_>, Failure>>()
    })?;
    to_pyarrow(py, results, Some(&files))
}

/// The decoder's configuration from `profiles=` and `eds=`.
fn config(
    profiles: Option<&Bound<'_, PyAny>>,
    eds: Option<&Bound<'_, PyDict>>,
) -> PyResult<DecoderConfig> {
    let profile = |value: &Bound<'_, PyAny>| -> PyResult<Profile> {
        let name: String = value.extract()?;
        Profile::from_name(&name).ok_or_else(|| {
            let names: Vec<_> = Profile::ALL.iter().map(|p| p.name()).collect();
            PyValueError::new_err(format!(
                "{name:?} is not a profile; one of {}",
                names.join(", ")
            ))
        })
    };
    let node = |value: &Bound<'_, PyAny>| -> PyResult<NodeId> {
        let raw: i64 = value.extract()?;
        u8::try_from(raw)
            .ok()
            .and_then(NodeId::new)
            .ok_or_else(|| PyValueError::new_err(format!("{raw} is not a node-ID (1..=127)")))
    };
    let mut table = NodeProfiles::default();
    match profiles {
        None => {}
        Some(value) if value.is_none() => {}
        Some(value) => {
            if let Ok(dict) = value.cast::<PyDict>() {
                for (key, value) in dict.iter() {
                    if key.is_none() {
                        table.set_default(profile(&value)?);
                    } else if key.is_instance_of::<PyTuple>() {
                        return Err(PyNotImplementedError::new_err(
                            "profiles per interface ({(iface, node): profile}) are not in the \
                             library yet: give {node: profile}, which holds on every interface",
                        ));
                    } else {
                        table.set(node(&key)?, profile(&value)?);
                    }
                }
            } else if value.extract::<String>().is_ok() {
                table.set_default(profile(value)?);
            } else {
                return Err(PyTypeError::new_err(
                    "profiles must be a profile name or a dict {node: profile name}",
                ));
            }
        }
    }
    let mut config = DecoderConfig::new().profiles_from(table);
    if let Some(eds) = eds {
        for (key, value) in eds.iter() {
            let node = node(&key)?;
            let path: PathBuf = value.extract()?;
            config = config
                .eds_file(node, &path)
                .map_err(|why| Failure::Value(format!("eds {}={}: {why}", node, path.display())))?;
        }
    }
    Ok(config)
}

/// Decode a log: the columns of `read_log` and the decoder's (docs/python.md#decode).
#[pyfunction]
#[pyo3(signature = (source, *, profiles = None, eds = None, format = None))]
fn decode(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    profiles: Option<&Bound<'_, PyAny>>,
    eds: Option<&Bound<'_, PyDict>>,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let config = config(profiles, eds)?;
    let finished = py.detach(|| {
        let mut decoder = Decoder::new(config);
        fill(&source, &source.name(), options, Some(&mut decoder), None)
    })?;
    to_pyarrow(py, vec![finished], None)
}

/// The post-mortem: the records of `motionwire decode --summary --json`
/// (docs/python.md#summary).
#[pyfunction]
#[pyo3(signature = (source, *, heartbeat_ms = None, profiles = None, eds = None, format = None))]
fn summary<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    heartbeat_ms: Option<u64>,
    profiles: Option<&Bound<'py, PyAny>>,
    eds: Option<&Bound<'py, PyDict>>,
    format: Option<&str>,
) -> PyResult<Bound<'py, PyList>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let mut config = config(profiles, eds)?.signals(false);
    if let Some(ms) = heartbeat_ms {
        config = config.heartbeat_timeout(Duration::from_millis(ms));
    }
    let (records, fed) = py.detach(|| -> Result<_, Failure> {
        let name = source.name();
        let mut log = source.open(options, &name)?;
        let mut summarizer = Summarizer::new(config);
        let fed = log.visit(Feed {
            feed: |position, event: &motionwire::can::LogEvent<'_>| summarizer.add(position, event),
            name: &name,
        })?;
        let summary = summarizer.finish();
        let records: Vec<String> = summary.records().map(|record| record.to_json()).collect();
        Ok((records, fed))
    })?;
    warn_skipped(py, &source, fed.skipped)?;
    let loads = py.import("json")?.getattr("loads")?;
    let list = PyList::empty(py);
    for record in records {
        list.append(loads.call1((record,))?)?;
    }
    Ok(list)
}

/// What went wrong: the summary's findings as a pyarrow.Table, one row per
/// finding, the list of the report's "What went wrong"
/// (docs/python.md#findings).
#[pyfunction]
#[pyo3(signature = (source, *, heartbeat_ms = None, profiles = None, eds = None, format = None))]
fn findings<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    heartbeat_ms: Option<u64>,
    profiles: Option<&Bound<'py, PyAny>>,
    eds: Option<&Bound<'py, PyDict>>,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let mut config = config(profiles, eds)?.signals(false);
    if let Some(ms) = heartbeat_ms {
        config = config.heartbeat_timeout(Duration::from_millis(ms));
    }
    let ((schema, batches), fed) = py.detach(|| -> Result<_, Failure> {
        let name = source.name();
        let mut log = source.open(options, &name)?;
        let mut recorder = Recorder::new(config);
        let fed = log.visit(Feed {
            feed: |position, event: &motionwire::can::LogEvent<'_>| recorder.add(position, event),
            name: &name,
        })?;
        let recording = recorder.finish();
        let table =
            table::findings(&recording.findings()).map_err(|e| Failure::Value(e.to_string()))?;
        Ok((table, fed))
    })?;
    warn_skipped(py, &source, fed.skipped)?;
    warn_ethercat(py, &source, fed.ethercat, "the findings do not")?;
    let table =
        Table::try_new(batches, schema).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(table.into_pyarrow(py)?.unbind())
}

/// Warn that lines or records of `source` were skipped.
fn warn_skipped(py: Python<'_>, source: &Source, skipped: u64) -> PyResult<()> {
    if skipped > 0 {
        let s = if skipped == 1 { "" } else { "s" };
        warn(
            py,
            format!(
                "{}: {skipped} malformed line{s} or damaged record{s} skipped (read_log lists them)",
                source.name()
            ),
        )?;
    }
    Ok(())
}

/// Warn that `packets` EtherCAT packets of `source` were read and left
/// out: the findings cover CAN logs (docs/ethercat.md#python). `what` is
/// `the findings do not`.
fn warn_ethercat(py: Python<'_>, source: &Source, packets: u64, what: &str) -> PyResult<()> {
    if packets > 0 {
        let s = if packets == 1 { "" } else { "s" };
        warn(
            py,
            format!(
                "{}: {packets} EtherCAT packet{s} read: {what} cover EtherCAT yet \
                 (decode shows every datagram)",
                source.name()
            ),
        )?;
    }
    Ok(())
}

/// Raise `message` as a `UserWarning` at the caller's line.
fn warn(py: Python<'_>, message: String) -> PyResult<()> {
    let warning = py.get_type::<pyo3::exceptions::PyUserWarning>();
    PyErr::warn(
        py,
        &warning,
        &std::ffi::CString::new(message).unwrap_or_default(),
        1,
    )
}

/// The loop of `summary` and `findings` over a log, compiled for its
/// format's reader: every entry fed to `feed` (a `Summarizer`'s or a
/// `Recorder`'s `add`), the malformed lines and damaged records and the
/// EtherCAT packets counted, a read error the end.
struct Feed<'a, F> {
    feed: F,
    name: &'a str,
}

impl<F: FnMut(motionwire::logs::Position, &motionwire::can::LogEvent<'_>)>
    motionwire::logs::LogVisitor for Feed<'_, F>
{
    type Output = Result<Fed, Failure>;

    fn visit<L: motionwire::logs::ReadLog + ?Sized>(mut self, log: &mut L) -> Result<Fed, Failure> {
        let mut fed = Fed::default();
        while let Some(next) = log.next_event() {
            match next {
                Ok(record) => {
                    if let motionwire::can::LogEvent::Ethercat(_) = record.event {
                        fed.ethercat += 1;
                    }
                    (self.feed)(record.position, &record.event);
                }
                Err(error) => {
                    if matches!(error.kind(), motionwire::logs::LogErrorKind::Io(_)) {
                        return Err(Failure::log(self.name, error));
                    }
                    fed.skipped += 1;
                }
            }
        }
        Ok(fed)
    }
}

/// What [`Feed`] counted.
#[derive(Default)]
struct Fed {
    /// Lines or records skipped.
    skipped: u64,
    /// EtherCAT packets: the summary and the findings do not cover them.
    ethercat: u64,
}

/// The module `motionwire._motionwire`, re-exported by `motionwire`.
#[pymodule]
fn _motionwire(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("LogError", m.py().get_type::<LogError>())?;
    m.add_function(wrap_pyfunction!(read_log, m)?)?;
    m.add_function(wrap_pyfunction!(read_logs, m)?)?;
    m.add_function(wrap_pyfunction!(decode, m)?)?;
    m.add_function(wrap_pyfunction!(summary, m)?)?;
    m.add_function(wrap_pyfunction!(findings, m)?)?;
    m.add_function(wrap_pyfunction!(fleet::post_mortem, m)?)?;
    m.add_class::<reader::Reader>()?;
    m.add_class::<reader::Message>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
