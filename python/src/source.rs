//! A log as Python names it: a path (`str`, `os.PathLike`) or the bytes of
//! the file, opened with the library's readers (docs/formats.md#detection).

use std::fs::File;
use std::io::Cursor;
use std::path::PathBuf;
use std::sync::Arc;

use motionwire::logs::{LogFormat, LogReader, ReadOptions};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::pybacked::PyBackedBytes;

use crate::error::Failure;

/// Where a log is read from.
pub enum Source {
    /// A file, read in place (MF4 seeks through its blocks).
    Path(PathBuf),
    /// The bytes of a log, borrowed from the Python object (`bytes`), or a
    /// copy of them (`bytearray`, `memoryview`).
    Bytes(Shared),
}

impl Source {
    /// The source of a Python argument: bytes-like first, then a path.
    pub fn extract(source: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(bytes) = source.extract::<PyBackedBytes>() {
            return Ok(Source::Bytes(Shared(Arc::new(bytes))));
        }
        if let Ok(view) = source.cast::<pyo3::types::PyMemoryView>() {
            let bytes = view.call_method0("tobytes")?;
            return Ok(Source::Bytes(Shared(Arc::new(bytes.extract()?))));
        }
        match source.extract::<PathBuf>() {
            Ok(path) => Ok(Source::Path(path)),
            Err(_) => Err(PyTypeError::new_err(format!(
                "source must be a path (str or os.PathLike) or bytes, not {}",
                source.get_type().name()?
            ))),
        }
    }

    /// The name messages give the source when it is read alone: the path
    /// as given, `<bytes>` for bytes.
    pub fn name(&self) -> String {
        match self {
            Source::Path(path) => path.display().to_string(),
            Source::Bytes(_) => "<bytes>".to_owned(),
        }
    }

    /// Open the log: the format detected from the content (or `format`),
    /// gzip inflated; `name` names it in a [`LogError`](crate::error::LogError).
    /// Runs without the GIL.
    pub fn open(&self, options: ReadOptions, name: &str) -> Result<LogReader, Failure> {
        match self {
            Source::Path(path) => {
                // A path that cannot be opened is an OSError with its name
                // (FileNotFoundError, PermissionError, …); past that,
                // anything the content does wrong is a LogError.
                let open = |error| Failure::Open {
                    path: path.clone(),
                    error,
                };
                let file = File::open(path).map_err(open)?;
                // A directory opens on Unix and fails at the first read:
                // said as Python's open() says it, IsADirectoryError.
                if file.metadata().map_err(open)?.is_dir() {
                    return Err(open(is_a_directory()));
                }
                options.open(path).map_err(|e| Failure::log(name, e))
            }
            Source::Bytes(bytes) => options
                .read(Cursor::new(Shared(Arc::clone(&bytes.0))))
                .map_err(|e| Failure::log(name, e)),
        }
    }
}

/// The error of opening a directory to read it (EISDIR, 21 on Linux,
/// macOS and the BSDs; Windows refuses to open a directory already).
fn is_a_directory() -> std::io::Error {
    std::io::Error::from_raw_os_error(21)
}

/// The sources of a Python sequence.
pub fn extract_all(sources: &Bound<'_, PyAny>) -> PyResult<Vec<Source>> {
    if sources.extract::<PyBackedBytes>().is_ok() || sources.extract::<PathBuf>().is_ok() {
        return Err(PyTypeError::new_err(
            "sources must be a sequence of paths or bytes (for one log, use read_log)",
        ));
    }
    sources
        .try_iter()?
        .map(|source| Source::extract(&source?))
        .collect()
}

/// The reading options of `format=`.
pub fn options(format: Option<&str>) -> PyResult<ReadOptions> {
    let options = ReadOptions::new();
    let Some(name) = format else {
        return Ok(options);
    };
    match LogFormat::from_name(name) {
        Some(format) => Ok(options.format(format)),
        None => {
            let names: Vec<_> = LogFormat::ALL.iter().map(|f| f.name()).collect();
            Err(PyValueError::new_err(format!(
                "{name:?} is not a log format; one of {}",
                names.join(", ")
            )))
        }
    }
}

/// Bytes of a Python object that a reader can hold without the GIL.
pub struct Shared(Arc<PyBackedBytes>);

impl AsRef<[u8]> for Shared {
    fn as_ref(&self) -> &[u8] {
        &self.0
    }
}
