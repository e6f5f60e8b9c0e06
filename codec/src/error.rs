//! What every error of the crate names, and the checks that build them.
//!
//! The crate's one error type, [`Error`], is declared at the crate root, above
//! every layer, because it carries the layers' own errors (a PDO entry's error
//! is `canopen::pdo`'s). This module lies below every layer and imports none of
//! them, so that layers point one way: [`What`], the frame, field or value an
//! error is about, typed so that a program can match on it; and the length
//! check every decoder starts with. The errors of log files are
//! [`crate::logs`]' own.

use crate::{Error, Result};

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
