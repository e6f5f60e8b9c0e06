//! `motionwire.Reader`: a log as python-can's `can.Message`s, a drop-in for
//! `can.LogReader` (docs/python.md#reader). Frames are read in blocks with
//! the GIL released; each message is made when it is asked for.

use std::collections::VecDeque;
use std::sync::Mutex;

use motionwire::can::{Direction, FdFlags, Iface, LogEvent};
use motionwire::logs::{LogErrorKind, LogReader, ReadLog};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString};

use crate::error::Failure;
use crate::source::{self, Source};

/// How many frames are read at a time without the GIL.
const BLOCK: usize = 4096;

/// A frame as it waits to become a message.
struct Frame {
    ts: Option<f64>,
    channel: Channel,
    id: u32,
    extended: bool,
    rtr: bool,
    error: bool,
    fd: bool,
    brs: bool,
    esi: bool,
    rx: Option<bool>,
    dlc: u8,
    len: u8,
    data: [u8; 64],
}

/// The interface of a frame, as python-can's `channel`.
#[derive(Clone, Copy)]
enum Channel {
    None,
    /// A name, by its index in the reader's names.
    Name(usize),
    /// A channel number, as the file writes it.
    Number(u16),
}

/// What the reader holds between calls (behind a lock: the log reader can
/// move between threads but is not shared).
struct State {
    log: Option<LogReader>,
    name: String,
    frames: VecDeque<Frame>,
    names: Vec<String>,
    skipped: Vec<(Option<u64>, String)>,
    skipped_count: u64,
    /// An input that failed while it was read: raised after the frames
    /// before it.
    failure: Option<String>,
}

impl State {
    /// Read up to [`BLOCK`] frames (without the GIL).
    fn fill(&mut self) {
        let Some(log) = self.log.as_mut() else {
            return;
        };
        while self.frames.len() < BLOCK {
            let Some(next) = log.next_event() else {
                self.log = None;
                return;
            };
            let record = match next {
                Ok(record) => record,
                Err(error) => {
                    if matches!(error.kind(), LogErrorKind::Io(_)) {
                        self.failure = Some(format!("{}: {error}", self.name));
                        self.log = None;
                        return;
                    }
                    self.skipped_count += 1;
                    if self.skipped.len() < crate::columns::SKIPPED_LISTED {
                        self.skipped.push((
                            error.position().map(|p| p.number()),
                            error.kind().to_string(),
                        ));
                    }
                    continue;
                }
            };
            let LogEvent::Frame(frame) = record.event else {
                continue;
            };
            let can = &frame.frame;
            let channel = match frame.iface {
                None => Channel::None,
                Some(Iface::Channel(n)) => Channel::Number(n),
                Some(Iface::Name(name)) => {
                    Channel::Name(match self.names.iter().rposition(|known| known == name) {
                        Some(at) => at,
                        None => {
                            self.names.push(name.to_owned());
                            self.names.len() - 1
                        }
                    })
                }
            };
            let bytes = can.data();
            let mut data = [0; 64];
            data[..bytes.len()].copy_from_slice(bytes);
            self.frames.push_back(Frame {
                ts: frame.timestamp.map(|ts| ts.as_secs_f64()),
                channel,
                id: can.id().raw(),
                extended: can.is_extended(),
                rtr: can.is_rtr(),
                error: can.is_error(),
                fd: can.is_fd(),
                brs: can.fd_flags().contains(FdFlags::BRS),
                esi: can.fd_flags().contains(FdFlags::ESI),
                rx: frame.direction.map(|d| d == Direction::Rx),
                // python-can's `dlc`: the data length of a CAN FD frame, the
                // requested length of a remote request, else the length.
                dlc: if can.is_fd() {
                    bytes.len() as u8
                } else {
                    can.dlc()
                },
                len: bytes.len() as u8,
                data,
            });
        }
    }
}

/// A log as python-can messages: a drop-in for python-can's
/// ``can.LogReader`` (docs/python.md#reader), for every format of
/// docs/formats.md.
///
///     with motionwire.Reader("trace.blf") as reader:
///         for msg in reader:          # can.Message
///             ...
///
/// Each message is python-can's ``can.Message`` when python-can is
/// installed (else ``motionwire.Message``, with the same attributes):
/// ``timestamp`` (0.0 where the log has no time), ``arbitration_id``,
/// ``is_extended_id``, ``is_remote_frame``, ``is_error_frame``, ``is_fd``,
/// ``bitrate_switch``, ``error_state_indicator``, ``dlc`` (python-can's:
/// the data length of a CAN FD frame), ``data``, ``channel`` (the interface
/// name, the channel number as the file writes it — from 1 where python-can
/// counts from 0 — or None) and ``is_rx`` (True where the log does not
/// say). Frames are read in blocks with the GIL released.
///
/// Lines skipped as malformed are in ``skipped`` and ``skipped_count``.
#[pyclass(module = "motionwire")]
pub struct Reader {
    state: Mutex<State>,
    /// The class of the messages, and whether it is python-can's.
    message: Py<PyAny>,
    python_can: bool,
    /// The interface names as Python strings, made once each.
    names: Vec<Py<PyString>>,
}

#[pymethods]
impl Reader {
    #[new]
    #[pyo3(signature = (source, format = None))]
    fn new(py: Python<'_>, source: &Bound<'_, PyAny>, format: Option<&str>) -> PyResult<Self> {
        let source = Source::extract(source)?;
        let options = source::options(format)?;
        let name = source.name();
        let log = py.detach(|| source.open(options, &name))?;
        let (message, python_can) = match py.import("can") {
            Ok(can) => (can.getattr("Message")?.unbind(), true),
            Err(_) => (py.get_type::<Message>().into_any().unbind(), false),
        };
        Ok(Reader {
            state: Mutex::new(State {
                log: Some(log),
                name,
                frames: VecDeque::new(),
                names: Vec::new(),
                skipped: Vec::new(),
                skipped_count: 0,
                failure: None,
            }),
            message,
            python_can,
            names: Vec::new(),
        })
    }

    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&mut self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        let mut state = self
            .state
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the reader failed in another thread"))?;
        if state.frames.is_empty() {
            let state: &mut State = &mut state;
            py.detach(|| state.fill());
        }
        let Some(frame) = state.frames.pop_front() else {
            if let Some(failure) = state.failure.take() {
                return Err(Failure::Log(failure).into());
            }
            return Ok(None);
        };
        while self.names.len() < state.names.len() {
            let name = &state.names[self.names.len()];
            self.names.push(PyString::new(py, name).unbind());
        }
        drop(state);
        let channel = match frame.channel {
            Channel::None => py.None(),
            Channel::Name(at) => self.names[at].clone_ref(py).into_any(),
            Channel::Number(n) => n.into_pyobject(py)?.into_any().unbind(),
        };
        let data = PyBytes::new(py, &frame.data[..usize::from(frame.len)]);
        let ts = frame.ts.unwrap_or(0.0);
        let rx = frame.rx.unwrap_or(true);
        if !self.python_can {
            let message = Message {
                timestamp: ts,
                arbitration_id: frame.id,
                is_extended_id: frame.extended,
                is_remote_frame: frame.rtr,
                is_error_frame: frame.error,
                is_fd: frame.fd,
                bitrate_switch: frame.brs,
                error_state_indicator: frame.esi,
                dlc: frame.dlc,
                data: data.unbind(),
                channel,
                is_rx: rx,
            };
            return Ok(Some(Py::new(py, message)?.into_any()));
        }
        let kwargs = PyDict::new(py);
        kwargs.set_item(pyo3::intern!(py, "timestamp"), ts)?;
        kwargs.set_item(pyo3::intern!(py, "arbitration_id"), frame.id)?;
        kwargs.set_item(pyo3::intern!(py, "is_extended_id"), frame.extended)?;
        kwargs.set_item(pyo3::intern!(py, "is_remote_frame"), frame.rtr)?;
        kwargs.set_item(pyo3::intern!(py, "is_error_frame"), frame.error)?;
        kwargs.set_item(pyo3::intern!(py, "channel"), channel)?;
        kwargs.set_item(pyo3::intern!(py, "dlc"), frame.dlc)?;
        kwargs.set_item(pyo3::intern!(py, "data"), data)?;
        kwargs.set_item(pyo3::intern!(py, "is_fd"), frame.fd)?;
        kwargs.set_item(pyo3::intern!(py, "is_rx"), rx)?;
        kwargs.set_item(pyo3::intern!(py, "bitrate_switch"), frame.brs)?;
        kwargs.set_item(pyo3::intern!(py, "error_state_indicator"), frame.esi)?;
        Ok(Some(
            self.message.bind(py).call((), Some(&kwargs))?.unbind(),
        ))
    }

    fn __enter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    #[pyo3(signature = (*_args))]
    fn __exit__(&self, _args: &Bound<'_, pyo3::types::PyTuple>) {
        self.stop();
    }

    /// Stop reading and close the log (python-can's `MessageReader.stop`).
    fn stop(&self) {
        if let Ok(mut state) = self.state.lock() {
            state.log = None;
            state.frames.clear();
        }
    }

    /// The lines or records skipped so far (the first 1 000), as
    /// `{"line": …, "reason": …}`.
    #[getter]
    fn skipped<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let state = self
            .state
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the reader failed in another thread"))?;
        let list = PyList::empty(py);
        for (line, reason) in &state.skipped {
            let item = PyDict::new(py);
            item.set_item("line", line)?;
            item.set_item("reason", reason)?;
            list.append(item)?;
        }
        Ok(list)
    }

    /// How many lines or records were skipped so far.
    #[getter]
    fn skipped_count(&self) -> u64 {
        self.state.lock().map_or(0, |state| state.skipped_count)
    }
}

/// A CAN frame with python-can's attribute names: what Reader yields
/// when python-can is not installed.
#[pyclass(module = "motionwire", get_all, frozen)]
pub struct Message {
    timestamp: f64,
    arbitration_id: u32,
    is_extended_id: bool,
    is_remote_frame: bool,
    is_error_frame: bool,
    is_fd: bool,
    bitrate_switch: bool,
    error_state_indicator: bool,
    dlc: u8,
    data: Py<PyBytes>,
    channel: Py<PyAny>,
    is_rx: bool,
}

#[pymethods]
impl Message {
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "motionwire.Message(timestamp={}, arbitration_id={:#x}, is_extended_id={}, \
             is_remote_frame={}, is_error_frame={}, is_fd={}, dlc={}, data={}, channel={})",
            self.timestamp,
            self.arbitration_id,
            py_bool(self.is_extended_id),
            py_bool(self.is_remote_frame),
            py_bool(self.is_error_frame),
            py_bool(self.is_fd),
            self.dlc,
            self.data.bind(py).repr()?,
            self.channel.bind(py).repr()?,
        ))
    }
}

fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}
