//! Why a command could not do its job (exit status 2).

use std::io;
use std::path::PathBuf;

/// Why a command could not do its job (exit status 2).
#[derive(Debug, thiserror::Error)]
pub enum Failure {
    /// Bad input given on the command line (e.g. bad hex).
    #[error("{0}")]
    Usage(String),
    /// A file that cannot be read.
    #[error("{}: {source}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// Why it cannot be read.
        source: io::Error,
    },
    /// Writing the output failed.
    #[error("writing the output: {0}")]
    Io(#[from] io::Error),
}
