//! The NMT node-control message: the NMT master's command to one node or to
//! all nodes (CiA 301 §7.2.8.3.1).
//!
//! It travels on COB-ID 0x000 ([`cob_id::NMT`](super::cob_id::NMT)) with two
//! bytes: the command specifier and the addressed node-ID, where 0 addresses
//! every node. [`NmtNodeControlFrame`] is the zero-copy view,
//! [`NmtNodeControl`] the owned value, [`NmtCommand`] the command.
//!
//! ```
//! use motionwire_codec::canopen::{NmtCommand, NmtNodeControl, NmtNodeControlFrame, NodeId};
//!
//! // "Start remote node" for node 5…
//! let start = NmtNodeControl::new(NmtCommand::StartRemoteNode, NodeId::new(5));
//! let mut data = [0u8; 2];
//! start.emit(&mut NmtNodeControlFrame::new_unchecked(&mut data[..]));
//! assert_eq!(data, [0x01, 0x05]);
//! assert_eq!(NmtNodeControl::parse(&data)?, start);
//!
//! // …and "reset communication" for every node (node-ID 0).
//! let reset_all = NmtNodeControl::parse(&[0x82, 0x00])?;
//! assert_eq!(reset_all.command, NmtCommand::ResetCommunication);
//! assert_eq!(reset_all.node, None);
//!
//! // An undefined command or a node-ID above 127 is an error, never a panic.
//! assert!(NmtNodeControl::parse(&[0x03, 0x05]).is_err());
//! assert!(NmtNodeControl::parse(&[0x01, 0x80]).is_err());
//! assert!(NmtNodeControl::parse(&[0x01]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use super::NodeId;
use crate::error::check_len;
use crate::{FieldError, FrameError, LenError, RangeError, Result, ValueError};

mod field {
    /// Byte 0: command specifier.
    pub(super) const COMMAND: usize = 0;
    /// Byte 1: node-ID, 0 for all nodes.
    pub(super) const NODE: usize = 1;
}

/// The length of an NMT node-control message's data, 2 bytes
/// (CiA 301 §7.2.8.3.1).
pub const NMT_NODE_CONTROL_LEN: usize = field::NODE + 1;

const WHAT: What = What::NmtNodeControlMessage;

/// The node-ID byte that addresses every node (CiA 301 §7.2.8.3.1).
const ALL_NODES: u8 = 0;

/// An NMT command, the command specifier of the node-control message
/// (CiA 301 §7.2.8.3.1).
///
/// ```
/// use motionwire_codec::canopen::NmtCommand;
///
/// assert_eq!(NmtCommand::from_byte(0x80)?, NmtCommand::EnterPreOperational);
/// assert_eq!(NmtCommand::ResetNode.to_byte(), 0x81);
/// assert_eq!(NmtCommand::ResetNode.name(), "reset_node");
/// assert!(NmtCommand::from_byte(0x00).is_err());
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum NmtCommand {
    /// 0x01: start remote node; the node goes to operational.
    StartRemoteNode = 0x01,
    /// 0x02: stop remote node; the node goes to stopped.
    StopRemoteNode = 0x02,
    /// 0x80: enter pre-operational.
    EnterPreOperational = 0x80,
    /// 0x81: reset node (application and communication); the node boots up
    /// again.
    ResetNode = 0x81,
    /// 0x82: reset communication; the node boots up again.
    ResetCommunication = 0x82,
}

impl NmtCommand {
    /// Every command, in the order of their codes.
    pub const ALL: [NmtCommand; 5] = [
        NmtCommand::StartRemoteNode,
        NmtCommand::StopRemoteNode,
        NmtCommand::EnterPreOperational,
        NmtCommand::ResetNode,
        NmtCommand::ResetCommunication,
    ];

    /// Return the command coded by `byte`, or a [`ValueError`] for
    /// any byte other than 0x01, 0x02, 0x80, 0x81 and 0x82.
    #[inline]
    pub const fn from_byte(byte: u8) -> Result<Self, ValueError> {
        match byte {
            0x01 => Ok(NmtCommand::StartRemoteNode),
            0x02 => Ok(NmtCommand::StopRemoteNode),
            0x80 => Ok(NmtCommand::EnterPreOperational),
            0x81 => Ok(NmtCommand::ResetNode),
            0x82 => Ok(NmtCommand::ResetCommunication),
            found => Err(ValueError {
                what: What::NmtCommandSpecifier,
                found: found as u32,
                expected: "0x01, 0x02, 0x80, 0x81, 0x82",
            }),
        }
    }

    /// Return the command's code on the wire.
    #[inline]
    #[must_use]
    pub const fn to_byte(self) -> u8 {
        self as u8
    }

    /// Return the command's name in lower-case words, e.g.
    /// `"enter_pre_operational"`.
    #[inline]
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            NmtCommand::StartRemoteNode => "start_remote_node",
            NmtCommand::StopRemoteNode => "stop_remote_node",
            NmtCommand::EnterPreOperational => "enter_pre_operational",
            NmtCommand::ResetNode => "reset_node",
            NmtCommand::ResetCommunication => "reset_communication",
        }
    }
}

impl NmtCommand {
    /// Return the short name the `command` key writes
    /// (docs/output.md#nmt-command): `start`, `stop`, `enter_pre_operational`,
    /// `reset_node`, `reset_communication`.
    ///
    /// ```
    /// use motionwire_codec::canopen::NmtCommand;
    ///
    /// assert_eq!(NmtCommand::StartRemoteNode.command_name(), "start");
    /// assert_eq!(NmtCommand::ResetNode.command_name(), "reset_node");
    /// ```
    #[inline]
    #[must_use]
    pub const fn command_name(self) -> &'static str {
        match self {
            NmtCommand::StartRemoteNode => "start",
            NmtCommand::StopRemoteNode => "stop",
            other => other.name(),
        }
    }
}

impl TryFrom<u8> for NmtCommand {
    type Error = ValueError;

    fn try_from(byte: u8) -> Result<Self, ValueError> {
        Self::from_byte(byte)
    }
}

impl From<NmtCommand> for u8 {
    fn from(command: NmtCommand) -> u8 {
        command.to_byte()
    }
}

impl fmt::Display for NmtCommand {
    /// Format the command as its [`NmtCommand::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A zero-copy view over an NMT node-control message's data
/// (CiA 301 §7.2.8.3.1).
///
/// After [`NmtNodeControlFrame::new_checked`] (or
/// [`NmtNodeControlFrame::check_len`]) succeeds, no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NmtNodeControlFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> NmtNodeControlFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// shorter than [`NMT_NODE_CONTROL_LEN`].
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        NmtNodeControlFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least
    /// [`NMT_NODE_CONTROL_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`NMT_NODE_CONTROL_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(WHAT, self.buffer.as_ref(), NMT_NODE_CONTROL_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the command specifier field (byte 0) as a number.
    #[inline]
    pub fn command_raw(&self) -> u8 {
        self.buffer.as_ref()[field::COMMAND]
    }

    /// Return the command specifier field (byte 0), or a
    /// [`ValueError`] when it codes no command.
    #[inline]
    pub fn command(&self) -> Result<NmtCommand, ValueError> {
        NmtCommand::from_byte(self.command_raw())
    }

    /// Return the node-ID field (byte 1) as a number; 0 addresses all nodes.
    #[inline]
    pub fn node_raw(&self) -> u8 {
        self.buffer.as_ref()[field::NODE]
    }

    /// Return the node-ID field (byte 1): `None` when it addresses all nodes
    /// (0), or a [`RangeError`] above 127.
    #[inline]
    pub fn node(&self) -> Result<Option<NodeId>, RangeError> {
        match self.node_raw() {
            ALL_NODES => Ok(None),
            raw => match NodeId::new(raw) {
                Some(node) => Ok(Some(node)),
                None => Err(RangeError {
                    what: What::NmtNodeControlNodeId,
                    found: u32::from(raw),
                    min: 0,
                    max: 127,
                }),
            },
        }
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> NmtNodeControlFrame<T> {
    /// Set the command specifier field (byte 0).
    #[inline]
    pub fn set_command(&mut self, command: NmtCommand) {
        self.buffer.as_mut()[field::COMMAND] = command.to_byte();
    }

    /// Set the node-ID field (byte 1); `None` addresses all nodes (0).
    #[inline]
    pub fn set_node(&mut self, node: Option<NodeId>) {
        self.buffer.as_mut()[field::NODE] = node.map_or(ALL_NODES, NodeId::get);
    }
}

/// An NMT node-control message, owned (CiA 301 §7.2.8.3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NmtNodeControl {
    /// The command (byte 0).
    pub command: NmtCommand,
    /// The addressed node (byte 1); `None` addresses all nodes (node-ID 0).
    pub node: Option<NodeId>,
}

impl NmtNodeControl {
    /// Return the message that sends `command` to `node`, or to all nodes
    /// when `node` is `None`.
    #[inline]
    #[must_use]
    pub const fn new(command: NmtCommand, node: Option<NodeId>) -> Self {
        NmtNodeControl { command, node }
    }

    /// Decode the 2 bytes of the message: an undefined command is a
    /// [`FieldError::InvalidValue`], a node-ID above 127 a
    /// [`FieldError::OutOfRange`].
    #[inline]
    pub fn from_bytes(bytes: &[u8; NMT_NODE_CONTROL_LEN]) -> Result<Self, FieldError> {
        Self::parse_frame(&NmtNodeControlFrame::new_unchecked(bytes))
    }

    /// Encode the message into its 2 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; NMT_NODE_CONTROL_LEN] {
        let mut bytes = [0; NMT_NODE_CONTROL_LEN];
        self.emit(&mut NmtNodeControlFrame::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode the message from a CAN frame's data: fewer than 2 bytes is a
    /// [`FrameError::Length`], then as [`NmtNodeControl::from_bytes`]. Bytes after
    /// the second are not read.
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, FrameError<FieldError>> {
        Ok(Self::parse_frame(&NmtNodeControlFrame::new_checked(data)?)?)
    }

    /// Read the owned value out of a view whose length has been checked.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &NmtNodeControlFrame<T>) -> Result<Self, FieldError> {
        Ok(NmtNodeControl {
            command: frame.command()?,
            node: frame.node()?,
        })
    }

    /// Write every field into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut NmtNodeControlFrame<T>) {
        frame.set_command(self.command);
        frame.set_node(self.node);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    /// "Stop remote node" for node 0x0A.
    static FRAME_BYTES: [u8; 2] = [0x02, 0x0A];

    /// CiA 301 §7.2.8.3.1: (code, command, name).
    const COMMAND_TABLE: [(u8, NmtCommand, &str); 5] = [
        (0x01, NmtCommand::StartRemoteNode, "start_remote_node"),
        (0x02, NmtCommand::StopRemoteNode, "stop_remote_node"),
        (
            0x80,
            NmtCommand::EnterPreOperational,
            "enter_pre_operational",
        ),
        (0x81, NmtCommand::ResetNode, "reset_node"),
        (0x82, NmtCommand::ResetCommunication, "reset_communication"),
    ];

    #[test]
    fn command_table() {
        for (byte, command, name) in COMMAND_TABLE {
            assert_eq!(NmtCommand::from_byte(byte), Ok(command));
            assert_eq!(NmtCommand::try_from(byte), Ok(command));
            assert_eq!(command.to_byte(), byte);
            assert_eq!(u8::from(command), byte);
            assert_eq!(command.to_string(), name);
        }
        assert_eq!(
            NmtCommand::ALL.map(NmtCommand::to_byte),
            [0x01, 0x02, 0x80, 0x81, 0x82]
        );
    }

    #[test]
    fn every_other_byte_is_an_invalid_command() {
        for byte in 0..=255u8 {
            if COMMAND_TABLE.iter().any(|&(b, _, _)| b == byte) {
                continue;
            }
            assert_eq!(
                NmtCommand::from_byte(byte),
                Err(ValueError {
                    what: What::NmtCommandSpecifier,
                    found: u32::from(byte),
                    expected: "0x01, 0x02, 0x80, 0x81, 0x82",
                })
            );
        }
    }

    #[test]
    fn deconstruct() {
        let frame = NmtNodeControlFrame::new_checked(&FRAME_BYTES[..]).unwrap();
        assert_eq!(frame.command_raw(), 0x02);
        assert_eq!(frame.command(), Ok(NmtCommand::StopRemoteNode));
        assert_eq!(frame.node_raw(), 0x0A);
        assert_eq!(frame.node(), Ok(Some(n(10))));
        assert_eq!(frame.into_inner(), &FRAME_BYTES[..]);
    }

    #[test]
    fn construct() {
        let mut bytes = [0xA5u8; 2];
        let mut frame = NmtNodeControlFrame::new_unchecked(&mut bytes[..]);
        frame.set_command(NmtCommand::StopRemoteNode);
        frame.set_node(Some(n(10)));
        assert_eq!(bytes, FRAME_BYTES);
    }

    #[test]
    fn parse_and_emit() {
        let message = NmtNodeControl::parse(&FRAME_BYTES).unwrap();
        assert_eq!(
            message,
            NmtNodeControl::new(NmtCommand::StopRemoteNode, Some(n(10)))
        );
        assert_eq!(message.to_bytes(), FRAME_BYTES);
        assert_eq!(NmtNodeControl::from_bytes(&FRAME_BYTES), Ok(message));
    }

    #[test]
    fn node_id_0_addresses_all_nodes() {
        let all = NmtNodeControl::new(NmtCommand::EnterPreOperational, None);
        assert_eq!(all.to_bytes(), [0x80, 0x00]);
        assert_eq!(NmtNodeControl::parse(&[0x80, 0x00]), Ok(all));
    }

    #[test]
    fn node_ids_above_127_are_out_of_range() {
        for raw in 128..=255u8 {
            assert_eq!(
                NmtNodeControl::parse(&[0x01, raw]),
                Err(FrameError::Content(FieldError::OutOfRange(RangeError {
                    what: What::NmtNodeControlNodeId,
                    found: u32::from(raw),
                    min: 0,
                    max: 127,
                })))
            );
        }
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        for len in 0..NMT_NODE_CONTROL_LEN {
            let expected = LenError {
                what: What::NmtNodeControlMessage,
                expected: 2,
                found: len,
            };
            assert_eq!(
                NmtNodeControl::parse(&FRAME_BYTES[..len]),
                Err(FrameError::Length(expected))
            );
            assert_eq!(
                NmtNodeControlFrame::new_checked(&FRAME_BYTES[..len]),
                Err(expected)
            );
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::can::nmt_node_control;

    proptest! {
        #[test]
        fn bytes_owned_bytes(bytes in any::<[u8; 2]>()) {
            match NmtNodeControl::from_bytes(&bytes) {
                Ok(value) => prop_assert_eq!(value.to_bytes(), bytes),
                Err(_) => prop_assert!(
                    NmtCommand::from_byte(bytes[0]).is_err() || bytes[1] > 127
                ),
            }
        }

        #[test]
        fn owned_bytes_owned(value in nmt_node_control()) {
            prop_assert_eq!(NmtNodeControl::from_bytes(&value.to_bytes()), Ok(value));
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..4)) {
            match NmtNodeControl::parse(&data) {
                Ok(value) => prop_assert_eq!(&value.to_bytes()[..], &data[..2]),
                Err(FrameError::Length(LenError { found, .. })) => prop_assert_eq!(found, data.len()),
                Err(FrameError::Content(_)) => prop_assert!(data.len() >= 2),
            }
        }
    }
}

impl fmt::Display for NmtNodeControl {
    /// `NMT reset_node to node 9`, `NMT start to all nodes`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "NMT {}", self.command)?;
        match self.node {
            Some(node) => write!(f, " to node {node}"),
            None => f.write_str(" to all nodes"),
        }
    }
}
