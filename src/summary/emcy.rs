//! The EMCY a summary points at: [`EmcySeen`].

use crate::can::Timestamp;
use crate::canopen::{Emcy, ErrorCode, ErrorRegister};

/// An EMCY the summary points at: where it was seen, its code, its error
/// register and manufacturer bytes (`first_error` in docs/summary.md#emcy,
/// `active_error`; the JSON keeps the line, time and code).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmcySeen {
    /// The line (or record number) it was read on.
    pub line: u64,
    /// Its time, where the log has one.
    pub timestamp: Option<Timestamp>,
    /// Its error code.
    pub code: ErrorCode,
    /// Its error register (1001h).
    pub register: ErrorRegister,
    /// Its manufacturer-specific bytes 3–7, which a node's profile reads
    /// (docs/canopen.md#profiles).
    pub manufacturer: [u8; 5],
}

impl EmcySeen {
    /// Return the EMCY itself.
    #[must_use]
    pub fn emcy(&self) -> Emcy {
        Emcy::new(self.code, self.register, self.manufacturer)
    }
}
