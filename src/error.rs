//! The crate's one error type.
//!
//! Every fallible decoder and checked constructor returns [`Error`]. Each
//! variant says *what* was being decoded, what was *expected* and what was
//! *found*, so that a message such as
//! `servo command frame: buffer of 7 bytes where 10 are needed` can be shown
//! to a person without further context (STYLE.md, "errors carry context").
//! The *what* is a typed [`What`], so a program can match on it; the error
//! depends on no parser's types (a text log's syntax errors are the
//! format-neutral [`SyntaxError`], defined with the log readers in
//! [`crate::logs`], as are [`BinaryError`] and [`LogFormat`]).

use crate::logs::{BinaryError, LogFormat, SyntaxError};

/// What went wrong while decoding or constructing a value.
///
/// The enum is `#[non_exhaustive]`: later protocol layers add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A buffer is shorter than the frame or field that must be read from it.
    #[error("{what}: buffer of {found} bytes where {expected} are needed")]
    Length {
        /// The frame or field that was being read, e.g. [`What::EmcyFrame`].
        what: What,
        /// The number of bytes the frame needs.
        expected: usize,
        /// The number of bytes that were given.
        found: usize,
    },
    /// A number lies outside the range its field allows.
    #[error("{what}: {found} is outside {min}..={max}")]
    OutOfRange {
        /// The field, e.g. [`What::NodeId`].
        what: What,
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
        /// The field, e.g. [`What::NmtState`].
        what: What,
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
        /// The value that was being read from text, e.g. [`What::ServoECode`].
        what: What,
        /// The form the text must have, in words.
        expected: &'static str,
    },
    /// A line of a text log does not follow its format (SPEC §5); the
    /// reason says what was expected at `column` and what was found there,
    /// e.g. `candump line, column 26: expected an identifier at most 0x7FF,
    /// found 0x800`.
    #[error("{format} line, column {column}: {reason}")]
    Syntax {
        /// The log format the line was read as.
        format: LogFormat,
        /// The 1-based byte column in the line where the problem starts.
        column: usize,
        /// What was expected there and what was found.
        reason: SyntaxError,
    },
    /// A binary log (pcap, pcapng, BLF; SPEC §5.5, §5.6) is damaged at
    /// `offset` (bytes from the start of the file, or of the decompressed
    /// container for BLF objects): the records before it were read, the rest
    /// of the file cannot be, e.g. `pcap file, byte 4120: record of 16 bytes
    /// cut off after 9`.
    #[error("{format} file, byte {offset}: {reason}")]
    Binary {
        /// The log format the file was read as.
        format: LogFormat,
        /// Where the damaged structure starts, in bytes.
        offset: u64,
        /// What is wrong there.
        reason: BinaryError,
    },
    /// A PDO mapping entry cannot be read from, or written into, a payload
    /// (SPEC §8.2), e.g. `PDO entry 6064sub0 (32 bits) at bit 24: expected
    /// a payload of at least 7 bytes, found 4`.
    #[error("PDO entry {entry} at bit {offset}: {reason}")]
    PdoEntry {
        /// The mapping entry.
        entry: crate::canopen::MappingEntry,
        /// Its first bit in the payload.
        offset: u16,
        /// What is wrong with it.
        reason: PdoEntryError,
    },
}

/// Why a PDO mapping entry cannot be read or written (SPEC §8.2): carried
/// by [`Error::PdoEntry`] with the entry and its bit offset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PdoEntryError {
    /// The payload ends before the entry does.
    Truncated {
        /// The bytes the mapping needs up to the end of the entry.
        needed: usize,
        /// The bytes the payload has.
        found: usize,
    },
    /// The entry's length is one its data type cannot be read from
    /// (REAL32 needs 32 bits, REAL64 64, the integers and BOOLEAN 1 to 64).
    BadLength {
        /// The entry's data type.
        data_type: crate::canopen::DataType,
        /// The entry's length in bits.
        bits: u8,
    },
    /// Packing: the value is of another kind than the entry reads as.
    WrongKind {
        /// The kind the entry reads as.
        expected: crate::canopen::ValueKind,
        /// The kind of the value given.
        found: crate::canopen::ValueKind,
    },
    /// Packing: the number does not fit in the entry's bits.
    ValueTooWide {
        /// The entry's length in bits.
        bits: u8,
    },
    /// Packing: the octets are not as long as the entry.
    OctetsLength {
        /// The entry's length in bits.
        expected: u8,
        /// The octets' length in bits.
        found: u8,
    },
    /// Packing: the values ended before this entry.
    MissingValue,
}

impl core::fmt::Display for PdoEntryError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            PdoEntryError::Truncated { needed, found } => write!(
                f,
                "expected a payload of at least {needed} bytes, found {found}"
            ),
            PdoEntryError::BadLength { data_type, bits } => {
                let expected = match data_type {
                    crate::canopen::DataType::Real32 => "32 bits",
                    crate::canopen::DataType::Real64 => "64 bits",
                    _ => "1 to 64 bits",
                };
                write!(f, "expected {expected} for {data_type}, found {bits}")
            }
            PdoEntryError::WrongKind { expected, found } => {
                write!(f, "expected a {expected} value, found a {found} value")
            }
            PdoEntryError::ValueTooWide { bits } => {
                write!(
                    f,
                    "expected a value that fits in {bits} bits, found a wider one"
                )
            }
            PdoEntryError::OctetsLength { expected, found } => {
                write!(f, "expected {expected} bits of octets, found {found}")
            }
            PdoEntryError::MissingValue => f.write_str("expected a value, found none left"),
        }
    }
}

/// What was being decoded or built when an [`Error`] occurred: the
/// frame, field or value, in words when displayed (`EMCY frame`,
/// `node-ID`, …). A typed value, so that a program can match on it;
/// `#[non_exhaustive]`: new decoders add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum What {
    /// The AKD axis id.
    AkdAxisId,
    /// The AKD feedback id.
    AkdFeedbackId,
    /// The AKD manufacturer field.
    AkdManufacturerField,
    /// The CAN error frame classes.
    CanErrorFrameClasses,
    /// The CAN error frame identifier.
    CanErrorFrameIdentifier,
    /// The CAN frame data length.
    CanFrameDataLength,
    /// The CAN frame type.
    CanFrameType,
    /// The CAN remote request data length.
    CanRemoteRequestDataLength,
    /// The CAN remote request length.
    CanRemoteRequestLength,
    /// A CiA 301 data type index.
    DataType,
    /// The EMCY frame.
    EmcyFrame,
    /// The error injection code.
    ErrorInjectionCode,
    /// The heartbeat consumer entries.
    HeartbeatConsumerEntries,
    /// The heartbeat message.
    HeartbeatMessage,
    /// The NMT command specifier.
    NmtCommandSpecifier,
    /// The NMT node-control message.
    NmtNodeControlMessage,
    /// The NMT node-control node-ID.
    NmtNodeControlNodeId,
    /// The NMT state.
    NmtState,
    /// The node-guarding answer.
    NodeGuardingAnswer,
    /// The node-ID.
    NodeId,
    /// The parameter table.
    ParameterTable,
    /// The number of entries of a PDO mapping.
    PdoMappingEntries,
    /// The length of a PDO mapping entry.
    PdoMappingEntryLength,
    /// The total length of a PDO mapping.
    PdoMappingBits,
    /// A PDO payload.
    PdoPayload,
    /// The values packed into a PDO.
    PdoValues,
    /// The regulator mode (SCW.ModeSel).
    RegulatorMode,
    /// The SDO block sub-command.
    SdoBlockSubcommand,
    /// The SDO command specifier.
    SdoCommandSpecifier,
    /// The SDO frame.
    SdoFrame,
    /// The servo command frame.
    ServoCommandFrame,
    /// The servo E-code.
    ServoECode,
    /// The servo enable (SCW.SE).
    ServoEnable,
    /// The servo feedback frame.
    ServoFeedbackFrame,
    /// Servo_Ready_Mode.
    ServoReadyMode,
    /// The SYNC data length.
    SyncDataLength,
    /// The TIME frame (TIME_OF_DAY).
    TimeOfDay,
    /// The timestamp microseconds.
    TimestampMicroseconds,
}

impl What {
    /// Return the words the error message uses, e.g. `EMCY frame`.
    #[must_use]
    pub const fn text(self) -> &'static str {
        match self {
            What::AkdAxisId => "AKD axis id",
            What::AkdFeedbackId => "AKD feedback id",
            What::AkdManufacturerField => "AKD manufacturer field",
            What::CanErrorFrameClasses => "CAN error frame classes",
            What::CanErrorFrameIdentifier => "CAN error frame identifier",
            What::CanFrameDataLength => "CAN frame data length",
            What::CanFrameType => "CAN frame type",
            What::CanRemoteRequestDataLength => "CAN remote request data length",
            What::CanRemoteRequestLength => "CAN remote request length",
            What::DataType => "data type",
            What::EmcyFrame => "EMCY frame",
            What::ErrorInjectionCode => "error injection code",
            What::HeartbeatConsumerEntries => "heartbeat consumer entries",
            What::HeartbeatMessage => "heartbeat message",
            What::NmtCommandSpecifier => "NMT command specifier",
            What::NmtNodeControlMessage => "NMT node-control message",
            What::NmtNodeControlNodeId => "NMT node-control node-ID",
            What::NmtState => "NMT state",
            What::NodeGuardingAnswer => "node-guarding answer",
            What::NodeId => "node-ID",
            What::ParameterTable => "parameter table",
            What::PdoMappingEntries => "PDO mapping entries",
            What::PdoMappingEntryLength => "PDO mapping entry length",
            What::PdoMappingBits => "PDO mapping length in bits",
            What::PdoPayload => "PDO payload",
            What::PdoValues => "PDO values",
            What::RegulatorMode => "regulator mode (SCW.ModeSel)",
            What::SdoBlockSubcommand => "SDO block sub-command",
            What::SdoCommandSpecifier => "SDO command specifier",
            What::SdoFrame => "SDO frame",
            What::ServoCommandFrame => "servo command frame",
            What::ServoECode => "servo E-code",
            What::ServoEnable => "servo enable (SCW.SE)",
            What::ServoFeedbackFrame => "servo feedback frame",
            What::ServoReadyMode => "Servo_Ready_Mode",
            What::SyncDataLength => "SYNC data length",
            What::TimeOfDay => "TIME frame (TIME_OF_DAY)",
            What::TimestampMicroseconds => "timestamp microseconds",
        }
    }
}

impl core::fmt::Display for What {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.text())
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = core::result::Result<T, E>;

/// Check that `buf` holds at least `expected` bytes for `what`.
#[inline]
pub(crate) const fn check_len(what: What, buf: &[u8], expected: usize) -> Result<()> {
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
        let e = check_len(What::ServoCommandFrame, &[0; 7], 10).unwrap_err();
        assert_eq!(
            e.to_string(),
            "servo command frame: buffer of 7 bytes where 10 are needed"
        );
        let e = Error::OutOfRange {
            what: What::NodeId,
            found: 128,
            min: 1,
            max: 127,
        };
        assert_eq!(e.to_string(), "node-ID: 128 is outside 1..=127");
        let e = Error::InvalidValue {
            what: What::NmtState,
            found: 0x12,
            expected: "0x00, 0x04, 0x05, 0x7f",
        };
        assert_eq!(
            e.to_string(),
            "NMT state: 0x12 is not one of 0x00, 0x04, 0x05, 0x7f"
        );
        let e = Error::Malformed {
            what: What::ServoECode,
            expected: "E followed by one or two decimal digits, e.g. E05",
        };
        assert_eq!(
            e.to_string(),
            "servo E-code: text is not of the form E followed by one or two decimal digits, e.g. E05"
        );
        assert!(check_len(What::EmcyFrame, &[0; 10], 10).is_ok());
    }
}
