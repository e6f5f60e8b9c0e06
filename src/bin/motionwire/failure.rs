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
    /// An input that cannot be read as a log: none of the formats of
    /// docs/formats.md (docs/formats.md#detection: one clear error, not one per
    /// line).
    #[error("{name}: {kind}")]
    Log {
        /// The input's name.
        name: String,
        /// Why.
        kind: motionwire::logs::LogErrorKind,
    },
    /// A binary log whose header is damaged: nothing in it can be read.
    #[error("{name}: {error}")]
    Damaged {
        /// The input's name.
        name: String,
        /// What is wrong, and where.
        error: motionwire::Error,
    },
    /// A log of which nothing could be read: every line or record of it
    /// was malformed or damaged, and said (the first
    /// [`COMPLAINTS_PER_FILE`](crate::decode::COMPLAINTS_PER_FILE) of them,
    /// docs/output.md#stderr).
    #[error(
        "{name}: nothing could be read as a {format} log: {complaints} and no frame{}",
        if *partly {
            format!(
                "; the first {} are said above (--verbose says each)",
                crate::decode::COMPLAINTS_PER_FILE
            )
        } else {
            String::new()
        }
    )]
    NothingRead {
        /// The input's name.
        name: String,
        /// The format it was read as (`--format`, or as detected).
        format: &'static str,
        /// How many lines were malformed and records damaged, in words.
        complaints: String,
        /// Only the first [`COMPLAINTS_PER_FILE`](crate::decode::COMPLAINTS_PER_FILE)
        /// of them were said one by one.
        partly: bool,
    },
    /// Writing the output failed.
    #[error("writing the output: {0}")]
    Io(#[from] io::Error),
}
