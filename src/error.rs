//! The crate's one error type.
//!
//! Every fallible decoder and checked constructor returns [`Error`]. Each
//! variant says *what* was being decoded, what was *expected* and what was
//! *found*, so that a message such as
//! `servo command frame: buffer of 7 bytes where 10 are needed` can be shown
//! to a person without further context (STYLE.md, "errors carry context").

/// What went wrong while decoding or constructing a value.
///
/// The enum is `#[non_exhaustive]`: later protocol layers add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A buffer is shorter than the frame or field that must be read from it.
    #[error("{what}: buffer of {found} bytes where {expected} are needed")]
    Length {
        /// The frame or field that was being read, e.g. `"EMCY frame"`.
        what: &'static str,
        /// The number of bytes the frame needs.
        expected: usize,
        /// The number of bytes that were given.
        found: usize,
    },
    /// A number lies outside the range its field allows.
    #[error("{what}: {found} is outside {min}..={max}")]
    OutOfRange {
        /// The field, e.g. `"node-ID"`.
        what: &'static str,
        /// The value that was given.
        found: u32,
        /// The smallest valid value.
        min: u32,
        /// The largest valid value.
        max: u32,
    },
    /// A value is in range for its type but is not one of the values the
    /// protocol defines (e.g. an NMT state byte of `0x12`).
    #[error("{what}: {found:#x} is not one of {expected}")]
    InvalidValue {
        /// The field, e.g. `"NMT state"`.
        what: &'static str,
        /// The value that was given.
        found: u32,
        /// The values that are valid, in words, e.g. `"0x00, 0x04, 0x05, 0x7f"`.
        expected: &'static str,
    },
    /// A text is not written in the form its value needs (e.g. `"E5x"` for a
    /// servo E-code, which is `E` followed by decimal digits). Text cannot be
    /// kept without a heap, so the message says what form was expected.
    #[error("{what}: text is not of the form {expected}")]
    Malformed {
        /// The value that was being read from text, e.g. `"servo E-code"`.
        what: &'static str,
        /// The form the text must have, in words.
        expected: &'static str,
    },
    /// A candump text line does not follow the formats of SPEC §5; the
    /// reason says what was expected at `column` and what was found there.
    #[error("candump line, column {column}: {reason}")]
    Candump {
        /// The 1-based byte column in the line where the problem starts.
        column: usize,
        /// What was expected there and what was found.
        reason: crate::candump::CandumpErrorKind,
    },
}

/// The crate's result type.
pub type Result<T, E = Error> = core::result::Result<T, E>;

/// Check that `buf` holds at least `expected` bytes for `what`.
#[inline]
pub(crate) const fn check_len(what: &'static str, buf: &[u8], expected: usize) -> Result<()> {
    if buf.len() < expected {
        Err(Error::Length {
            what,
            expected,
            found: buf.len(),
        })
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_say_expected_and_found() {
        let e = check_len("servo command frame", &[0; 7], 10).unwrap_err();
        assert_eq!(
            e.to_string(),
            "servo command frame: buffer of 7 bytes where 10 are needed"
        );
        let e = Error::OutOfRange {
            what: "node-ID",
            found: 128,
            min: 1,
            max: 127,
        };
        assert_eq!(e.to_string(), "node-ID: 128 is outside 1..=127");
        let e = Error::InvalidValue {
            what: "NMT state",
            found: 0x12,
            expected: "0x00, 0x04, 0x05, 0x7f",
        };
        assert_eq!(
            e.to_string(),
            "NMT state: 0x12 is not one of 0x00, 0x04, 0x05, 0x7f"
        );
        let e = Error::Malformed {
            what: "servo E-code",
            expected: "E followed by one or two decimal digits, e.g. E05",
        };
        assert_eq!(
            e.to_string(),
            "servo E-code: text is not of the form E followed by one or two decimal digits, e.g. E05"
        );
        assert!(check_len("x", &[0; 10], 10).is_ok());
    }
}
