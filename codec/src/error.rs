//! The errors of the crate's layers, what each names, and the checks that
//! build them.
//!
//! A function returns exactly the errors it can produce: a frame whose
//! parse only checks its length fails with a [`LenError`], a checked
//! number with a [`RangeError`], a code with a
//! [`ValueError`], a text with a [`TextError`]; a parse that checks the
//! length and then a code fails with a [`FrameError`] of both, and a field
//! that can be out of range or undefined with a [`FieldError`]. The
//! crate's umbrella, [`Error`](crate::Error), declared at the crate root
//! above every layer, converts from each, so that `?` works across them.
//!
//! This module lies below every layer and imports none of them: [`What`],
//! the frame, field or value an error is about, typed so that a program
//! can match on it; the errors above; and the length
//! check every decoder starts with. The errors of log files are
//! motionwire's `logs` layer's own.

/// What was being decoded or built when an error occurred: the
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
    /// The CoE header.
    CoeHeader,
    /// The CoE SDO message.
    CoeSdo,
    /// An EtherCAT datagram.
    EthercatDatagram,
    /// The EtherCAT frame (its header's length).
    EthercatFrame,
    /// The EtherCAT header.
    EthercatHeader,
    /// The Ethernet frame.
    EthernetFrame,
    /// The IPv4 header.
    Ipv4Header,
    /// The mailbox error message.
    MailboxError,
    /// The mailbox header.
    MailboxHeader,
    /// The mailbox message (its header's length).
    MailboxMessage,
    /// The UDP header.
    UdpHeader,
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
            What::CoeHeader => "CoE header",
            What::CoeSdo => "CoE SDO message",
            What::EthercatDatagram => "EtherCAT datagram",
            What::EthercatFrame => "EtherCAT frame",
            What::EthercatHeader => "EtherCAT header",
            What::EthernetFrame => "Ethernet frame",
            What::Ipv4Header => "IPv4 header",
            What::MailboxError => "mailbox error message",
            What::MailboxHeader => "mailbox header",
            What::MailboxMessage => "mailbox message",
            What::UdpHeader => "UDP header",
        }
    }
}

impl core::fmt::Display for What {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.text())
    }
}

/// A buffer is shorter than the frame or field that must be read from it,
/// e.g. `EMCY frame: buffer of 5 bytes where 8 are needed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("{what}: buffer of {found} bytes where {expected} are needed")]
pub struct LenError {
    /// The frame or field that was being read, e.g. [`What::EmcyFrame`].
    pub what: What,
    /// The number of bytes the frame needs.
    pub expected: usize,
    /// The number of bytes that were given.
    pub found: usize,
}

/// A number lies outside the range its field allows, e.g.
/// `node-ID: 128 is outside 1..=127`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("{what}: {found} is outside {min}..={max}")]
pub struct RangeError {
    /// The field, e.g. [`What::NodeId`].
    pub what: What,
    /// The value that was given.
    pub found: u32,
    /// The smallest valid value.
    pub min: u32,
    /// The largest valid value.
    pub max: u32,
}

/// A value is in range for its type but is not one of the values the
/// protocol defines, e.g. an NMT state byte of `0x12`:
/// `NMT state: 0x12 is not one of 0x00, 0x04, 0x05, 0x7f`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("{what}: {found:#x} is not one of {expected}")]
pub struct ValueError {
    /// The field, e.g. [`What::NmtState`].
    pub what: What,
    /// The value that was given.
    pub found: u32,
    /// The values that are valid, in words, e.g. `"0x00, 0x04, 0x05, 0x7f"`.
    pub expected: &'static str,
}

/// A text is not written in the form its value needs (e.g. `"E5x"` for a
/// servo E-code, which is `E` followed by decimal digits). Text cannot be
/// kept without a heap, so the message says what form was expected:
/// `servo E-code: text is not of the form E followed by one or two decimal
/// digits, e.g. E05`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("{what}: text is not of the form {expected}")]
pub struct TextError {
    /// The value that was being read from text, e.g. [`What::ServoECode`].
    pub what: What,
    /// The form the text must have, in words.
    pub expected: &'static str,
}

/// A field that can fail two ways: a number outside the range its type
/// allows, or one inside it that the protocol does not define (an NMT
/// node-control frame's node-ID and command specifier, the AKD feedback
/// id, a CAN frame's length and an error frame's identifier). The message
/// is the inner error's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
pub enum FieldError {
    /// The number lies outside the range its field allows.
    #[error(transparent)]
    OutOfRange(#[from] RangeError),
    /// The number is not one of the values the protocol defines.
    #[error(transparent)]
    InvalidValue(#[from] ValueError),
}

/// A frame whose parse checks its length, then its content: a buffer
/// shorter than the frame ([`FrameError::Length`]), or a content that the
/// protocol does not define ([`FrameError::Content`], a [`ValueError`]
/// for a code, a [`FieldError`] where a number can also be out of range).
/// As etherparse's `HeaderSliceError`: the length error is the same type
/// for every frame, the content error is the frame's own. The message is
/// the inner error's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
pub enum FrameError<E = ValueError> {
    /// The buffer is shorter than the frame.
    #[error(transparent)]
    Length(#[from] LenError),
    /// The frame's content is not one the protocol defines.
    #[error(transparent)]
    Content(E),
}

impl From<ValueError> for FrameError<ValueError> {
    fn from(error: ValueError) -> Self {
        FrameError::Content(error)
    }
}

impl From<FieldError> for FrameError<FieldError> {
    fn from(error: FieldError) -> Self {
        FrameError::Content(error)
    }
}

/// Check that `buf` holds at least `expected` bytes for `what`.
#[inline]
pub(crate) const fn check_len(what: What, buf: &[u8], expected: usize) -> Result<(), LenError> {
    if buf.len() < expected {
        Err(LenError {
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
        let e = RangeError {
            what: What::NodeId,
            found: 128,
            min: 1,
            max: 127,
        };
        assert_eq!(e.to_string(), "node-ID: 128 is outside 1..=127");
        let e = ValueError {
            what: What::NmtState,
            found: 0x12,
            expected: "0x00, 0x04, 0x05, 0x7f",
        };
        assert_eq!(
            e.to_string(),
            "NMT state: 0x12 is not one of 0x00, 0x04, 0x05, 0x7f"
        );
        let e = TextError {
            what: What::ServoECode,
            expected: "E followed by one or two decimal digits, e.g. E05",
        };
        assert_eq!(
            e.to_string(),
            "servo E-code: text is not of the form E followed by one or two decimal digits, e.g. E05"
        );
        assert!(check_len(What::EmcyFrame, &[0; 10], 10).is_ok());
    }

    /// The enums that carry an error, and the crate's umbrella, show the
    /// message of the error they carry, unchanged, and convert into the
    /// umbrella's variant of the same name.
    #[test]
    fn carriers_show_the_inner_message() {
        use crate::Error;
        let len = LenError {
            what: What::HeartbeatMessage,
            expected: 1,
            found: 0,
        };
        let range = RangeError {
            what: What::NodeId,
            found: 0,
            min: 1,
            max: 127,
        };
        let value = ValueError {
            what: What::NmtState,
            found: 0x12,
            expected: "0x00, 0x04, 0x05, 0x7f",
        };
        let text = TextError {
            what: What::ServoECode,
            expected: "E followed by one or two decimal digits, e.g. E05",
        };
        let cases: [(Error, String); 8] = [
            (len.into(), len.to_string()),
            (range.into(), range.to_string()),
            (value.into(), value.to_string()),
            (text.into(), text.to_string()),
            (FrameError::<ValueError>::from(len).into(), len.to_string()),
            (FrameError::Content(value).into(), value.to_string()),
            (FieldError::from(range).into(), range.to_string()),
            (
                FrameError::Content(FieldError::from(value)).into(),
                value.to_string(),
            ),
        ];
        for (error, message) in cases {
            assert_eq!(error.to_string(), message);
        }
        assert_eq!(Error::from(len), Error::Length(len));
        assert_eq!(
            Error::from(FrameError::<ValueError>::Length(len)),
            Error::Length(len)
        );
        assert_eq!(
            Error::from(FieldError::OutOfRange(range)),
            Error::OutOfRange(range)
        );
        assert_eq!(
            Error::from(FrameError::Content(FieldError::InvalidValue(value))),
            Error::InvalidValue(value)
        );
        assert_eq!(FieldError::from(value).to_string(), value.to_string());
        assert_eq!(
            FrameError::<ValueError>::from(len).to_string(),
            len.to_string()
        );
    }
}
