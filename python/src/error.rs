//! What goes wrong, made while the GIL is released and raised as a Python
//! exception once it is held again (docs/python.md#errors).

use std::io;
use std::path::PathBuf;

use motionwire::logs::LogError as ReadError;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    motionwire,
    LogError,
    PyValueError,
    "A log that cannot be read: none of the formats of docs/formats.md\n(unrecognised), a binary log whose header is damaged, or an input that\nfails while it is read (a damaged gzip stream). The message names the\nsource and the reason:\n\n    <bytes>: unrecognised log format: expected a candump log or screen\n    output, Vector ASC or BLF, PEAK TRC, pcap or pcapng, ASAM MDF 4\n    (gzip-compressed or not)\n\nA malformed line inside a recognised log is no LogError: it is skipped\nand listed in the table's schema metadata. A path that cannot be opened\nraises the OSError that Python's open() would (FileNotFoundError, …)."
);

/// Why a call failed, without the GIL.
#[derive(Debug)]
pub enum Failure {
    /// The file cannot be opened: an `OSError` (`FileNotFoundError`, …)
    /// with its name.
    Open { path: PathBuf, error: io::Error },
    /// The log cannot be read: a [`LogError`] with this message.
    Log(String),
    /// An argument is wrong (an EDS file that cannot be read): a
    /// `ValueError`.
    Value(String),
}

impl Failure {
    /// The log `name` cannot be read: `error` says why and where.
    pub fn log(name: impl std::fmt::Display, error: ReadError) -> Self {
        Failure::Log(format!("{name}: {error}"))
    }
}

impl From<Failure> for PyErr {
    fn from(failure: Failure) -> PyErr {
        match failure {
            Failure::Open { path, error } => {
                let name = path.display().to_string();
                match error.raw_os_error() {
                    // As Python's own open() says it: the subclass the errno
                    // selects (FileNotFoundError, PermissionError, …), with
                    // the file's name.
                    Some(errno) => {
                        let text = error.to_string();
                        let text = text
                            .split(" (os error")
                            .next()
                            .unwrap_or_default()
                            .to_owned();
                        PyOSError::new_err((errno, text, name))
                    }
                    None => PyOSError::new_err(format!("{name}: {error}")),
                }
            }
            Failure::Log(message) => LogError::new_err(message),
            Failure::Value(message) => PyValueError::new_err(message),
        }
    }
}
