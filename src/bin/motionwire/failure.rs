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
    /// An input that is none of the log formats of SPEC §5 (§5.7: one
    /// clear error, not one per line).
    #[error("{name}: unrecognised log format: expected {expected}")]
    Unrecognised {
        /// The input's name.
        name: String,
        /// What was expected, in words.
        expected: &'static str,
    },
    /// A binary log whose header is damaged: nothing in it can be read.
    #[error("{name}: {error}")]
    Damaged {
        /// The input's name.
        name: String,
        /// What is wrong, and where.
        error: motionwire::Error,
    },
    /// An input of a format this build cannot read.
    #[error("{name}: {format} logs cannot be read by this build: {why}")]
    Unreadable {
        /// The input's name.
        name: String,
        /// The format.
        format: motionwire::logs::LogFormat,
        /// Why.
        why: &'static str,
    },
    /// Writing the output failed.
    #[error("writing the output: {0}")]
    Io(#[from] io::Error),
}
