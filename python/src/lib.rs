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
mod pdo;
mod process;
mod reader;
mod records;
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
    Ok(columns.finish(name))
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

/// Read a log into a table, one row per CAN frame, in the log's order
/// (MF4: time order across its channel groups).
///
/// Columns (docs/python.md#read-log; each as the JSON record's key of the
/// same name, docs/output.md#common-keys):
///
/// - ``line`` (uint64): the 1-based line of a text log, or the packet,
///   object or record number of a binary one (docs/formats.md#positions).
/// - ``ts`` (float64, null where the log has no time): seconds, absolute
///   Unix time where the log records the date, else since the start of the
///   recording (docs/formats.md#timestamps).
/// - ``time`` (null where ``ts`` is): the same instant to the nanosecond,
///   from the library's timestamps (never from the float):
///   ``timestamp[ns, tz=UTC]`` where every time of the table is a Unix
///   time (from 2001-09-09 on), else ``duration[ns]`` since the clock's
///   zero, the start of the recording (docs/python.md#time). pandas reads
///   them as ``datetime64[ns, UTC]`` and ``timedelta64[ns]``.
/// - ``iface`` (dictionary string, null where the log names none): the
///   interface name (``can0``) or channel number as the file writes it
///   (``1``).
/// - ``id`` (uint32): the identifier; of an error frame, its class bits.
/// - ``extended``, ``rtr``, ``fd``, ``brs``, ``esi``, ``error`` (bool).
/// - ``dlc`` (uint8): the data length code: the number of bytes of a
///   classic frame, the requested length of a remote request, the code
///   0–15 of a CAN FD frame (12 bytes: 9; 64 bytes: 15).
/// - ``data`` (binary): the data bytes; empty for a remote request.
///
/// Schema metadata: ``b"motionwire.format"`` (the format read),
/// ``b"motionwire.skipped"`` (a JSON list of ``{"line": …, "reason": …}``,
/// the first 1 000 lines or records skipped as malformed or damaged),
/// ``b"motionwire.skipped_count"`` (how many), where a binary log
/// had records without a CAN frame, ``b"motionwire.other"`` (what was
/// passed over, as the program says it), and where the log gave no row,
/// ``b"motionwire.empty"`` (a JSON list of the program's words,
/// ``["empty.log: 0 frames"]``).
///
/// An EtherCAT capture (docs/python.md#ethercat) gives one row per
/// datagram instead, with the keys of ``motionwire decode --json``'s
/// ``ecat_datagram`` record as columns, in that order:
///
/// - ``packet`` (uint64): the capture's packet number, from 1.
/// - ``datagram`` (uint16): the datagram's place in its frame, from 1.
/// - ``ts`` (float64 seconds, null where the capture has no time),
///   ``time``, ``iface`` (dictionary string, null where none): as for CAN
///   frames.
/// - ``kind`` (dictionary string): ``ecat_datagram``.
/// - ``cmd`` (dictionary string): ``NOP``, ``APRD``, … ``FRMW``, or
///   ``reserved``.
/// - ``index`` (uint8).
/// - ``adp``, ``ado`` (uint16): slave and register address; null for
///   LRD, LWR and LRW.
/// - ``logical`` (uint32): the logical address of LRD, LWR and LRW; null
///   for the others.
/// - ``length``, ``irq``, ``wkc`` (uint16): the data's length, the IRQ
///   field, the working counter.
/// - ``returned`` (bool): the copy that came back through the slaves
///   (paired with its sent copy or not), as the library's session tells.
/// - ``data`` (binary).
///
/// Its metadata adds ``b"motionwire.ethercat"``: the session's counts as
/// a JSON object (``packets``, ``sent``, ``returned``,
/// ``returned_unpaired``, ``lost``, ``other_frame_types``, ``damaged``).
/// A table holds CAN frames or EtherCAT datagrams, not both: the CAN
/// frames where the input has any, the EtherCAT packets then counted in
/// ``b"motionwire.other"``.
///
/// Raises LogError for an input that is no log; OSError for a path that
/// cannot be opened.
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

/// Read many logs at once on Rust threads (``threads``: by default one
/// per core) into one table: a ``file`` column (dictionary string: the
/// path as given, ``<bytes N>`` for the N-th source given as bytes) before
/// the columns of read_log, each log's rows in the order of ``sources``.
/// Each log is read on its own: nothing carries over from one to the next.
/// EtherCAT captures give read_log's datagram columns after ``file`` when
/// no log of the table has a CAN frame; else their packets are counted in
/// ``b"motionwire.other"``.
///
/// The way to take a fleet's logs to pandas, polars or DuckDB, and on to
/// Parquet (``pyarrow.parquet.write_table``). The skipped lines of every log
/// are in the metadata, each with its ``file``.
///
/// Raises LogError naming the first source (in the order given) that is no
/// log.
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

/// Decode a log as CANopen: the columns of read_log, then what the
/// decoder session reads in each frame, with SDO transfers followed, PDO
/// mappings learned from the log (or ``eds``) and each drive's CiA 402 state
/// (docs/python.md#decode):
///
/// - ``kind`` (dictionary string): ``emcy``, ``heartbeat``,
///   ``guard_request``, ``guard_answer``, ``nmt_command``, ``sync``,
///   ``time``, ``pdo``,
///   ``sdo``, ``error_frame``, ``other`` (docs/canopen.md#identifiers).
/// - ``node`` (uint8, null for kinds without one).
/// - ``code`` (uint16), ``register`` (uint8), ``description`` (dictionary
///   string): an EMCY's error code, error register and the code's
///   description (a truncated EMCY: the code and register its bytes hold).
/// - ``state`` (dictionary string): the NMT state of a heartbeat, boot-up
///   or guarding answer (``boot_up``, ``stopped``, ``operational``,
///   ``pre_operational``, ``invalid``).
/// - ``cia402_state`` (dictionary string, null where the frame tells
///   none): the drive's CiA 402 state a statusword in the frame tells
///   (``switch_on_disabled``, ``operation_enabled``, ``fault``, …), the
///   record's ``cia402.state``.
/// - ``record`` (string): the frame's whole JSON record, exactly the line
///   ``motionwire decode --json`` writes (docs/output.md#json): SDO,
///   transfer, signals, cia402 and every key of its kind.
///
/// ``profiles``: ``"akd"`` for every node, or ``{3: "akd", 5: "baumer"}``
/// (``--profile``; the key None sets the default). ``eds``: ``{node:
/// path}``, an EDS or DCF file describing that node (``--eds``).
///
/// An EtherCAT capture gives read_log's datagram columns and ``record``
/// (string): the datagram's ``ecat_datagram`` record, the line
/// ``motionwire decode --json`` writes (docs/ethercat.md#records).
///
/// For pandas, ``table.to_pandas(types_mapper=pandas.ArrowDtype)`` keeps
/// ``node``, ``code`` and ``register`` integers where they hold nulls
/// (plain ``to_pandas()`` makes them float64 with NaN).
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

/// The PDO signals of a CAN log as a long table (docs/python.md#signals):
/// one row per signal value of each PDO whose mapping the decoder knows
/// (learned from the log's SDO transfers, or from ``eds``), in the log's
/// order and the mapping's: the record's ``signals`` of decode, as
/// process_data's long table has EtherCAT's.
///
/// Columns: ``line`` (uint64), ``ts`` (float64 seconds, nullable),
/// ``time`` (as read_log's), ``iface`` (dictionary string, nullable),
/// ``node`` (uint8: the node whose PDO it is, the mapping's owner),
/// ``cob_id`` (uint32: the frame's identifier), ``name`` (dictionary
/// string: the signal's name, the EDS's or the object table's, else
/// ``0x6041:00``), ``value`` (float64: the value as a number, a boolean
/// 0 or 1, null for bytes; integers exact up to 2**53), ``raw`` (int64:
/// the value where it is an integer an int64 holds, else null).
///
/// ``profiles``, ``eds`` and ``format`` are decode's. Pivot it wide with
/// pandas: ``df.pivot_table(index=["line", "node"], columns="name",
/// values="value", observed=True)``. An EtherCAT capture's packets have no
/// rows and are said with a UserWarning (process_data has their signals);
/// the schema metadata is read_log's.
#[pyfunction]
#[pyo3(signature = (source, *, profiles = None, eds = None, format = None))]
fn signals(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    profiles: Option<&Bound<'_, PyAny>>,
    eds: Option<&Bound<'_, PyDict>>,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let config = config(profiles, eds)?;
    let read = py.detach(|| pdo::read(&source, options, Decoder::new(config)))?;
    if read.packets > 0 {
        let s = if read.packets == 1 { "" } else { "s" };
        warn(
            py,
            format!(
                "{}: {} EtherCAT packet{s} read: the signals of CAN PDOs have rows, \
                 EtherCAT packets none (process_data has their signals)",
                source.name(),
                read.packets
            ),
        )?;
    }
    let table = Table::try_new(read.batches, read.schema)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(table.into_pyarrow(py)?.unbind())
}

/// The post-mortem of a log: exactly the records of ``motionwire decode
/// --summary --json`` (docs/summary.md): the verdict when something
/// stopped (``type`` ``verdict``, docs/summary.md#verdict), then one dict
/// per node and per bus:
/// frame counts, first and active error with the CiA 405 root cause,
/// heartbeat boot-ups and gaps over ``heartbeat_ms``, node-guarding toggle
/// errors, SDO requests, transfers, aborts and latencies, each drive's CiA
/// 402 timeline. Each list holds the first 10 and the last 10 events of its
/// kind, and the count key after it counts them all (docs/summary.md#lists).
///
/// Lines skipped as malformed are said with a UserWarning (read_log lists
/// them). An EtherCAT capture gives one record per interface, slave and
/// cyclic stream (docs/ethercat.md#summary). A negative ``heartbeat_ms``
/// is a ValueError.
#[pyfunction]
#[pyo3(signature = (source, *, heartbeat_ms = None, profiles = None, eds = None, format = None, servo = None))]
#[allow(clippy::too_many_arguments)]
fn summary<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    heartbeat_ms: Option<i64>,
    profiles: Option<&Bound<'py, PyAny>>,
    eds: Option<&Bound<'py, PyDict>>,
    format: Option<&str>,
    servo: Option<process::Servos>,
) -> PyResult<Bound<'py, PyList>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let mut config = config(profiles, eds)?
        .signals(false)
        .servos(servo.map_or_else(Default::default, |s| s.0));
    if let Some(timeout) = heartbeat_timeout(heartbeat_ms)? {
        config = config.heartbeat_timeout(timeout);
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

/// The heartbeat timeout of `heartbeat_ms=`: milliseconds, 0 or more.
fn heartbeat_timeout(ms: Option<i64>) -> PyResult<Option<Duration>> {
    ms.map(|ms| {
        u64::try_from(ms).map(Duration::from_millis).map_err(|_| {
            PyValueError::new_err(format!(
                "heartbeat_ms must be a number of milliseconds, 0 or more; not {ms}"
            ))
        })
    })
    .transpose()
}

/// What went wrong (docs/summary.md#findings): one row per finding, the
/// list of the report's "What went wrong" (``motionwire report``), in time
/// order: first errors and warnings, CiA 402 faults, restarts, heartbeat
/// timeouts over ``heartbeat_ms``, SDO aborts, broken and unanswered SDO
/// transfers, node-guarding toggle errors, bus-off and error-passive frames;
/// an EtherCAT capture's slaves' AL errors and servo faults
/// (docs/ethercat.md#findings, ``servo=`` as process_data's); where the
/// summary omitted entries of a list, one row says how many.
///
/// Columns: ``line`` (uint64: the line, or an EtherCAT capture's packet),
/// ``ts`` (float64 seconds, null where the log has no time), ``iface``
/// (dictionary, null for an unnamed bus), ``node`` (uint8, null for a bus's
/// findings and an EtherCAT slave's), ``slave`` (uint16, the EtherCAT
/// slave's station address, null for CAN), ``kind`` (dictionary:
/// ``first_error``, ``first_warning``, ``cia402_fault``, ``restarts``,
/// ``heartbeat_timeout``, ``sdo_abort``, ``sdo_broken``, ``sdo_timeout``,
/// ``toggle_error``, ``bus_off``, ``error_passive``, ``al_error``,
/// ``servo_fault``), ``severity`` (dictionary: ``fault``, ``error``,
/// ``warning``, ``notice``; docs/summary.md#severity), ``text`` (what it
/// says, without the device).
///
/// Lines skipped as malformed are said with a UserWarning (read_log lists
/// them).
#[pyfunction]
#[pyo3(signature = (source, *, heartbeat_ms = None, profiles = None, eds = None, format = None, servo = None))]
#[allow(clippy::too_many_arguments)]
fn findings<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    heartbeat_ms: Option<i64>,
    profiles: Option<&Bound<'py, PyAny>>,
    eds: Option<&Bound<'py, PyDict>>,
    format: Option<&str>,
    servo: Option<process::Servos>,
) -> PyResult<Py<PyAny>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let mut config = config(profiles, eds)?
        .signals(false)
        .servos(servo.map_or_else(Default::default, |s| s.0));
    if let Some(timeout) = heartbeat_timeout(heartbeat_ms)? {
        config = config.heartbeat_timeout(timeout);
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
    let table =
        Table::try_new(batches, schema).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(table.into_pyarrow(py)?.unbind())
}

/// The process data of an EtherCAT capture as a long table
/// (docs/python.md#process-data): one row per signal per slave per
/// returned cyclic datagram, the values of the program's ``process_data``
/// records' ``signals`` (outputs then inputs, in mapping order), then a
/// servo's values (``servo=``) as signals too.
///
/// Columns: ``packet`` (uint64), ``datagram`` (uint16), ``ts`` (float64
/// seconds, null without time), ``time`` (as read_log's), ``iface``
/// (dictionary string), ``slave``
/// (uint16 station address, null where no FMMU is known), ``position``
/// (uint16 ring position, nullable), ``direction`` (dictionary:
/// ``output``, ``input``), ``name`` (dictionary string: the key of
/// ``signals``, or a servo value's name: ``speed_setpoint``, ``control``,
/// ``servo_enable``; ``position``, ``zero_pulse_position`` (incremental
/// encoders), ``status``, ``errors``, ``message_code``,
/// ``message_value``), ``value`` (float64: the value as a number, a
/// boolean 0 or 1, null for bytes; integers exact up to 2**53), ``raw``
/// (int64: the value where it is an integer an int64 holds, else null),
/// ``confirmed`` (bool: the working counter confirms the inputs; true for
/// outputs).
///
/// Pivot it wide with pandas: ``df.pivot_table(index=["packet", "slave"],
/// columns="name", values="value")``. A log's CAN frames have no rows and
/// are said with a UserWarning; the schema metadata is read_log's.
#[pyfunction]
#[pyo3(
    signature = (source, *, servo = process::Servos::none(), format = None),
    text_signature = "(source, *, servo=None, format=None)"
)]
fn process_data(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    servo: process::Servos,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    process_table(
        py,
        source,
        servo,
        format,
        process::SignalColumns::default(),
        PROCESS_CAN,
    )
}

/// What the tables of process data say of a log's CAN frames.
const PROCESS_CAN: &str =
    "the process data of EtherCAT captures has rows, CAN frames none (decode's records hold \
     their PDO signals)";

/// The servo frames of an EtherCAT capture (docs/python.md#servo): one
/// row per servo per cycle, the values of the program's ``servo``
/// records.
///
/// Columns: ``packet`` (uint64), ``datagram`` (uint16), ``ts``, ``time``,
/// ``iface``, ``slave`` (uint16); the command: ``speed_setpoint`` (int32),
/// ``control`` (uint32, SCW), ``servo_enable`` (uint8, SE); the feedback,
/// null where the inputs are unconfirmed: ``position`` (int64, ActPos
/// raw), ``encoder`` (dictionary: ``absolute``, ``incremental``),
/// ``status`` (uint32, SSW), ``errors`` (uint32, SEW), ``faults``
/// (list of the set error bits' names), ``e_codes`` (list: each fault's
/// E-code, ``"E09"``, or null); the handshakes: ``enable``,
/// ``enable_cycles`` (uint32), ``error_clear``, ``zero_pulse``
/// (dictionary: the phases' names); ``ready`` (bool, ServoRDY by the
/// mode, null without feedback); ``confirmed`` (bool).
#[pyfunction]
#[pyo3(
    signature = (source, *, servo = process::Servos::auto(), format = None),
    text_signature = "(source, *, servo='auto', format=None)"
)]
fn servo(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    servo: process::Servos,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    process_table(
        py,
        source,
        servo,
        format,
        process::ServoColumns::new(),
        PROCESS_CAN,
    )
}

/// The records an EtherCAT capture's datagrams tell of its slaves, as a
/// table (docs/python.md#ethercat-records): one row per record that
/// ``motionwire decode --json`` writes, in its order, of the kinds
/// ``kinds`` names.
///
/// ``kinds`` (a kind, or a list of them; the program's ``--only``): by
/// default ``station``, ``al_state``, ``sii``, ``dl_status``,
/// ``error_counters``, ``mailbox``, ``coe_sdo``, ``coe_emcy``, ``alias``,
/// ``dc``, ``mailbox_repeat`` (docs/ethercat.md#meanings);
/// ``ecat_datagram`` (decode's rows), ``process_data`` and ``servo`` (the
/// process data, one record per slave per cycle), ``dc_distribution`` and
/// ``mailbox_poll`` (a record a cycle or a poll, which ``decode`` too
/// writes only when named) when named. ``servo`` (process_data's ``servo=``): the
/// slaves read as servos, whose cycles get ``servo`` records.
///
/// Columns: the keys every record has, then those of the meanings'
/// records, each the key of the same name (null where the row's kind has
/// no such key or the record says null; on the rows of ``ecat_datagram``,
/// ``process_data`` and ``servo`` all are null but ``slave`` and
/// ``position``):
///
/// - ``packet`` (uint64), ``datagram`` (uint16), ``ts`` (float64 seconds),
///   ``time`` (as read_log's), ``iface`` (dictionary string).
/// - ``kind`` (dictionary string).
/// - ``slave`` (uint16 station address), ``position`` (uint16 ring
///   position).
/// - ``al_state``: ``al_register`` (the record's ``register``:
///   ``al_control``, ``al_status``, ``al_status_code``), ``state``
///   (``init``, ``preop``, ``boot``, ``safeop``, ``op``), ``al_error``
///   (bool, the record's ``error``), ``code`` (uint16, AL status code)
///   and ``code_text``.
/// - ``sii``: ``word`` (uint32), ``value`` (uint32), ``field``.
/// - ``mailbox``, ``coe_sdo``, ``coe_emcy``: ``direction`` (``write``,
///   ``read``), ``type`` (the mailbox type), ``service`` (a CoE message's).
/// - ``coe_sdo``: ``index`` (uint16), ``subindex`` (uint8), null in a
///   segment; ``abort_code`` (uint32) and ``abort`` (its text).
/// - ``coe_emcy``: ``code`` (uint16, the EMCY error code), ``register``
///   (uint8, the error register), ``description``.
/// - ``record`` (string): the whole JSON record, exactly the line
///   ``motionwire decode --json`` writes (every key of its kind: a
///   ``coe_sdo``'s ``transfer``, a ``coe_emcy``'s AKD fields …).
///
/// Query it in DuckDB: ``duckdb.sql("select packet, slave, state from t
/// where kind = 'al_state'")``. A log's CAN frames have no rows and are
/// said with a UserWarning; the schema metadata is read_log's. An unknown
/// kind is a ValueError.
#[pyfunction]
#[pyo3(
    signature = (source, *, kinds = None, servo = process::Servos::none(), format = None),
    text_signature = "(source, *, kinds=None, servo=None, format=None)"
)]
fn ethercat_records(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    kinds: Option<&Bound<'_, PyAny>>,
    servo: process::Servos,
    format: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let kinds = record_kinds(kinds)?;
    process_table(
        py,
        source,
        servo,
        format,
        records::RecordColumns::new(&kinds),
        "the records of EtherCAT captures have rows, CAN frames none (decode has theirs)",
    )
}

/// The kinds of `kinds=`: a kind, a list of kinds, or None for
/// [`records::MEANING_KINDS`].
fn record_kinds(kinds: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<&'static str>> {
    use motionwire::decoder::ethercat::RECORD_KINDS;
    let Some(kinds) = kinds.filter(|k| !k.is_none()) else {
        return Ok(records::MEANING_KINDS.to_vec());
    };
    let names: Vec<String> = if let Ok(name) = kinds.extract::<String>() {
        vec![name]
    } else {
        kinds
            .try_iter()
            .map_err(|_| {
                PyTypeError::new_err("kinds must be a kind's name or a list of kinds' names")
            })?
            .map(|kind| kind?.extract::<String>())
            .collect::<PyResult<_>>()?
    };
    names
        .iter()
        .map(|name| {
            RECORD_KINDS
                .iter()
                .copied()
                .find(|kind| kind == name)
                .ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "{name:?} is not a kind of EtherCAT record; one of {}",
                        RECORD_KINDS.join(", ")
                    ))
                })
        })
        .collect()
}

/// Read a capture into the table of `rows`; a log's CAN frames are said
/// with a `UserWarning`, `why` they have no rows.
fn process_table<R: process::Rows + Send>(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    servo: process::Servos,
    format: Option<&str>,
    rows: R,
    why: &str,
) -> PyResult<Py<PyAny>> {
    let source = Source::extract(source)?;
    let options = source::options(format)?;
    let read = py.detach(|| process::read(&source, options, servo.0, rows))?;
    if read.frames > 0 {
        let s = if read.frames == 1 { "" } else { "s" };
        warn(
            py,
            format!(
                "{}: {} CAN frame{s} read: {why}",
                source.name(),
                read.frames
            ),
        )?;
    }
    let table = Table::try_new(read.batches, read.schema)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
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
/// `Recorder`'s `add`), the malformed lines and damaged records counted, a
/// read error the end.
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
                Ok(record) => (self.feed)(record.position, &record.event),
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
}

/// The module `motionwire._motionwire`, re-exported by `motionwire`.
#[pymodule]
fn _motionwire(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("LogError", m.py().get_type::<LogError>())?;
    m.add_function(wrap_pyfunction!(read_log, m)?)?;
    m.add_function(wrap_pyfunction!(read_logs, m)?)?;
    m.add_function(wrap_pyfunction!(decode, m)?)?;
    m.add_function(wrap_pyfunction!(signals, m)?)?;
    m.add_function(wrap_pyfunction!(summary, m)?)?;
    m.add_function(wrap_pyfunction!(findings, m)?)?;
    m.add_function(wrap_pyfunction!(process_data, m)?)?;
    m.add_function(wrap_pyfunction!(servo, m)?)?;
    m.add_function(wrap_pyfunction!(ethercat_records, m)?)?;
    m.add_function(wrap_pyfunction!(fleet::post_mortem, m)?)?;
    m.add_class::<reader::Reader>()?;
    m.add_class::<reader::Message>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
