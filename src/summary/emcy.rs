//! The EMCY a summary points at: [`EmcySeen`].

use crate::can::Timestamp;
use crate::canopen::ErrorCode;

/// An EMCY the summary points at: where it was seen and its code
/// (`first_error` in docs/summary.md#emcy, `active_error`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmcySeen {
    /// The line (or record number) it was read on.
    pub line: u64,
    /// Its time, where the log has one.
    pub timestamp: Option<Timestamp>,
    /// Its error code.
    pub code: ErrorCode,
}
