//! A CAN frame read as CANopen: its identifier classified by the
//! pre-defined connection set and its data decoded by the crate's codecs,
//! once (CiA 301 §7.3.5 Table 72; docs/canopen.md#identifiers).
//!
//! [`CanOpenMessage::decode`] takes the crate's one frame type,
//! [`CanFrame`] (owned or borrowed), and returns the message: an [`Emcy`],
//! a heartbeat, an [`NmtNodeControl`], … or [`CanOpenMessage::Other`] for a
//! frame without a CANopen function. [`CanOpenMessage::kind`] names it as
//! `kind` does (docs/output.md#common-keys); [`CanOpenMessage::encode`] gives
//! the frame back. With the `embedded-can` feature,
//! `CanOpenMessage::from_frame` and `to_frame` do the same with any
//! `embedded_can::Frame`.
//!
//! ```
//! use motionwire_codec::can::{CanFrame, CanId};
//! use motionwire_codec::canopen::{CanOpenMessage, ErrorCode, MessageKind, NmtState, NodeId};
//!
//! let id = |raw| CanId::standard(raw).unwrap();
//! let node = NodeId::new(1).unwrap();
//!
//! // 081#3081110100000000: an EMCY of node 1.
//! let frame = CanFrame::new(id(0x081), &[0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0])?;
//! let message = CanOpenMessage::decode(&frame)?;
//! let CanOpenMessage::Emcy { node: from, emcy } = message else { unreachable!() };
//! assert_eq!((from, emcy.code), (node, ErrorCode::new(0x8130)));
//! assert_eq!(message.kind(), MessageKind::Emcy);
//! assert_eq!(message.kind().name(), "emcy");
//!
//! // 701#05 is a heartbeat, 701#R a node-guarding request.
//! let heartbeat = CanOpenMessage::decode(&CanFrame::new(id(0x701), &[0x05])?)?;
//! assert!(matches!(heartbeat, CanOpenMessage::Heartbeat { byte, .. }
//!     if byte.state() == Some(NmtState::Operational)));
//! let request = CanOpenMessage::decode(&CanFrame::new_remote(id(0x701), 1)?)?;
//! assert_eq!(request, CanOpenMessage::GuardRequest { node });
//!
//! // The frame back.
//! assert_eq!(message.encode(), Some(frame));
//!
//! // A frame too short for its kind is an error that still says the kind
//! // and the node, and what could be read.
//! let short = CanFrame::new(id(0x081), &[0x30, 0x81, 0x11])?;
//! let err = CanOpenMessage::decode(&short).unwrap_err();
//! assert_eq!((err.kind, err.node), (MessageKind::Emcy, Some(node)));
//! assert_eq!(err.to_string(), "EMCY frame: buffer of 3 bytes where 8 are needed");
//! assert_eq!(err.partial_emcy.and_then(|p| p.code), Some(ErrorCode::new(0x8130)));
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use super::{
    cob_id, CobFunction, Emcy, ErrorCode, ErrorRegister, GuardAnswer, Heartbeat, NmtNodeControl,
    NmtState, NodeId, PdoDirection, TimeOfDay, EMCY_LEN, HEARTBEAT_LEN, NMT_NODE_CONTROL_LEN,
};
use crate::can::{CanFrame, CanId, ErrorFrame, FrameData};
use crate::{Error, LenError, ValueError};

/// What a frame is on a CANopen bus: the `kind` of docs/output.md#common-keys.
///
/// ```
/// use motionwire_codec::canopen::MessageKind;
///
/// let names: Vec<_> = MessageKind::ALL.iter().map(|k| k.name()).collect();
/// assert_eq!(names, [
///     "emcy", "heartbeat", "guard_request", "guard_answer", "nmt_command",
///     "sync", "time", "pdo", "sdo", "error_frame", "other",
/// ]);
/// assert_eq!(MessageKind::GuardRequest.to_string(), "guard_request");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MessageKind {
    /// 0x081–0x0FF: an EMCY (CiA 301 §7.2.7).
    Emcy,
    /// 0x701–0x77F, data frame: heartbeat or boot-up (CiA 301 §7.2.8.3.2).
    Heartbeat,
    /// 0x701–0x77F, remote request: node-guarding request
    /// (CiA 301 §7.2.8.3.2.1).
    GuardRequest,
    /// 0x701–0x77F, data frame answering a guard request: node-guarding
    /// answer (CiA 301 §7.2.8.3.2.1). It shares its identifier with the
    /// heartbeat, so only the frames before it tell it: the first data frame
    /// on the node's identifier after a guard request
    /// (docs/output.md#heartbeat). [`MessageKind::classify`] reads one frame
    /// and never returns it; the decoder session does.
    GuardAnswer,
    /// 0x000: NMT node control (CiA 301 §7.2.8.3.1).
    NmtCommand,
    /// 0x080: SYNC (CiA 301 §7.2.5).
    Sync,
    /// 0x100: TIME (CiA 301 §7.2.6).
    Time,
    /// 0x181–0x57F: the default PDOs (CiA 301 §7.2.2).
    Pdo,
    /// 0x581–0x5FF and 0x601–0x67F: SDO (CiA 301 §7.2.4).
    Sdo,
    /// An error frame (docs/formats.md#error-frames).
    ErrorFrame,
    /// Everything else, and every extended frame.
    Other,
}

impl MessageKind {
    /// Every kind, in the order the summary lists them.
    pub const ALL: [MessageKind; 11] = [
        MessageKind::Emcy,
        MessageKind::Heartbeat,
        MessageKind::GuardRequest,
        MessageKind::GuardAnswer,
        MessageKind::NmtCommand,
        MessageKind::Sync,
        MessageKind::Time,
        MessageKind::Pdo,
        MessageKind::Sdo,
        MessageKind::ErrorFrame,
        MessageKind::Other,
    ];

    /// Return the name `kind` writes (docs/output.md#common-keys).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            MessageKind::Emcy => "emcy",
            MessageKind::Heartbeat => "heartbeat",
            MessageKind::GuardRequest => "guard_request",
            MessageKind::GuardAnswer => "guard_answer",
            MessageKind::NmtCommand => "nmt_command",
            MessageKind::Sync => "sync",
            MessageKind::Time => "time",
            MessageKind::Pdo => "pdo",
            MessageKind::Sdo => "sdo",
            MessageKind::ErrorFrame => "error_frame",
            MessageKind::Other => "other",
        }
    }

    /// Return the position of the kind in [`MessageKind::ALL`].
    #[must_use]
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Return the kind named `name` as `kind` writes it
    /// (docs/output.md#common-keys).
    #[must_use]
    pub fn from_name(name: &str) -> Option<MessageKind> {
        MessageKind::ALL
            .into_iter()
            .find(|kind| kind.name() == name)
    }

    /// Classify a frame by its identifier and type alone, and return the
    /// node its identifier belongs to where the kind has one (the identifier
    /// table of docs/canopen.md#identifiers). [`CanOpenMessage::decode`] gives
    /// the same kind and node, with the data decoded.
    ///
    /// One look-up in a table of the 2 048 standard identifiers (6 KiB),
    /// made at compile time from [`CobFunction::classify`]: the decoder and
    /// the summary classify every frame.
    #[inline]
    #[must_use]
    pub fn classify<D: AsRef<[u8]>>(frame: &CanFrame<D>) -> (MessageKind, Option<NodeId>) {
        if frame.is_error() {
            return (MessageKind::ErrorFrame, None);
        }
        let Some(cob_id) = frame.id().standard_raw() else {
            return (MessageKind::Other, None);
        };
        let (kind, node) = BY_COB_ID
            .get(usize::from(cob_id))
            .copied()
            .unwrap_or((MessageKind::Other, None));
        if kind == MessageKind::Heartbeat && frame.is_rtr() {
            return (MessageKind::GuardRequest, node);
        }
        (kind, node)
    }

    /// [`MessageKind::classify`], with the function of the identifier in
    /// the pre-defined connection set ([`CobFunction::Other`] for error and
    /// extended frames).
    #[inline]
    fn classify_with_function<D: AsRef<[u8]>>(
        frame: &CanFrame<D>,
    ) -> (MessageKind, Option<NodeId>, CobFunction) {
        if frame.is_error() {
            return (MessageKind::ErrorFrame, None, CobFunction::Other);
        }
        let Some(cob_id) = frame.id().standard_raw() else {
            return (MessageKind::Other, None, CobFunction::Other);
        };
        let function = CobFunction::classify(cob_id);
        let (kind, node) = Self::of_function(function, frame.is_rtr());
        (kind, node, function)
    }

    /// The kind and node of a frame whose identifier has `function`, a
    /// remote request when `rtr`.
    const fn of_function(function: CobFunction, rtr: bool) -> (MessageKind, Option<NodeId>) {
        match function {
            CobFunction::NmtCommand => (MessageKind::NmtCommand, None),
            CobFunction::Sync => (MessageKind::Sync, None),
            CobFunction::Time => (MessageKind::Time, None),
            CobFunction::Emcy(node) => (MessageKind::Emcy, Some(node)),
            CobFunction::Pdo { node, .. } => (MessageKind::Pdo, Some(node)),
            CobFunction::SdoTx(node) | CobFunction::SdoRx(node) => (MessageKind::Sdo, Some(node)),
            CobFunction::ErrorControl(node) if rtr => (MessageKind::GuardRequest, Some(node)),
            CobFunction::ErrorControl(node) => (MessageKind::Heartbeat, Some(node)),
            CobFunction::Other => (MessageKind::Other, None),
        }
    }
}

/// The kind of a data frame with each standard identifier, and its node:
/// [`MessageKind::classify`]'s table (a remote request to an error-control
/// identifier is a guard request instead of a heartbeat).
static BY_COB_ID: [(MessageKind, Option<NodeId>); 0x800] = {
    let mut table = [(MessageKind::Other, None); 0x800];
    let mut id = 0;
    while id < table.len() {
        table[id] = MessageKind::of_function(CobFunction::classify(id as u16), false);
        id += 1;
    }
    table
};

impl fmt::Display for MessageKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The one byte of an error-control frame as received: a heartbeat, a
/// boot-up message or a node-guarding answer, which share the identifier
/// (CiA 301 §7.2.8.3.2; docs/canopen.md#error-control and the `state`,
/// `state_raw` and `toggle` keys of docs/output.md#heartbeat).
///
/// Every byte is kept: bits 0–6 that code no NMT state are read as
/// `None` (`invalid` in docs/output.md#heartbeat), bit 7 is the node-guarding
/// toggle (a heartbeat producer leaves it 0).
///
/// ```
/// use motionwire_codec::canopen::{NmtState, NmtStateByte};
///
/// let byte = NmtStateByte::new(0x85);
/// assert_eq!((byte.state(), byte.state_raw(), byte.toggle()), (Some(NmtState::Operational), 5, true));
/// assert_eq!(NmtStateByte::new(0x12).state_name(), "invalid");
/// assert_eq!(byte.to_string(), "operational (toggle 1)");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NmtStateByte(u8);

impl NmtStateByte {
    /// Bit 7: the toggle of a node-guarding answer.
    const TOGGLE: u8 = 0x80;

    /// Return the byte as received.
    #[inline]
    #[must_use]
    pub const fn new(byte: u8) -> Self {
        NmtStateByte(byte)
    }

    /// Return the whole byte.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self.0
    }

    /// Return bits 0–6, the NMT state as a number (`state_raw` in
    /// docs/output.md#heartbeat).
    #[inline]
    #[must_use]
    pub const fn state_raw(self) -> u8 {
        self.0 & !Self::TOGGLE
    }

    /// Return bit 7: the toggle of a node-guarding answer, reserved (0) in a
    /// heartbeat (`toggle` in docs/output.md#heartbeat).
    #[inline]
    #[must_use]
    pub const fn toggle(self) -> bool {
        self.0 & Self::TOGGLE != 0
    }

    /// Return the NMT state bits 0–6 code, `None` for an undefined value.
    #[inline]
    #[must_use]
    pub fn state(self) -> Option<NmtState> {
        NmtState::from_byte(self.state_raw()).ok()
    }

    /// Return the state's name as `state` writes it (docs/output.md#heartbeat):
    /// `boot_up`, `stopped`, `operational`, `pre_operational`, or `invalid`.
    #[must_use]
    pub fn state_name(self) -> &'static str {
        self.state().map_or("invalid", NmtState::name)
    }

    /// Return the byte read as a heartbeat, `None` for an undefined state.
    #[must_use]
    pub fn heartbeat(self) -> Option<Heartbeat> {
        Heartbeat::parse(&[self.0]).ok()
    }

    /// Return the byte read as a node-guarding answer (bit 7 the toggle),
    /// `None` for an undefined state (CiA 301 §7.2.8.3.2.1).
    #[must_use]
    pub fn guard_answer(self) -> Option<GuardAnswer> {
        Some(GuardAnswer::new(self.toggle(), self.state()?))
    }
}

impl fmt::Display for NmtStateByte {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.state() {
            Some(state) => f.write_str(state.name())?,
            None => write!(f, "invalid state {:#04x}", self.state_raw())?,
        }
        if self.toggle() {
            f.write_str(" (toggle 1)")?;
        }
        Ok(())
    }
}

/// What a truncated EMCY still says (docs/output.md#emcy: an EMCY shorter than
/// 8 bytes still gets `code` when 2 bytes are there and `register` when 3
/// are, as Wireshark does).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PartialEmcy {
    /// The error code, when the frame has bytes 0–1.
    pub code: Option<ErrorCode>,
    /// The error register, when the frame has byte 2.
    pub register: Option<ErrorRegister>,
}

impl PartialEmcy {
    /// Read what `data` (shorter than an EMCY) holds.
    #[must_use]
    pub fn read(data: &[u8]) -> Self {
        PartialEmcy {
            code: match data {
                [lo, hi, ..] => Some(ErrorCode::new(u16::from_le_bytes([*lo, *hi]))),
                _ => None,
            },
            register: data.get(2).map(|r| ErrorRegister::from_bits_retain(*r)),
        }
    }
}

/// A frame whose identifier names a CANopen kind but whose data that
/// kind's codec refuses: the kind and node are still known, and the error
/// says what was expected and found (`error` in docs/output.md#error).
///
/// It converts into the crate's [`Error`] (the codec's error), so `?` works
/// in functions returning [`motionwire_codec::Result`](crate::Result).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DecodeError {
    /// The kind the identifier gives.
    pub kind: MessageKind,
    /// The node the identifier gives, for the kinds that have one.
    pub node: Option<NodeId>,
    /// The codec's error.
    pub error: Error,
    /// For a truncated EMCY, what its bytes still say.
    pub partial_emcy: Option<PartialEmcy>,
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.error, f)
    }
}

impl core::error::Error for DecodeError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        Some(&self.error)
    }
}

impl From<DecodeError> for Error {
    fn from(e: DecodeError) -> Self {
        e.error
    }
}

/// The DLC of a node-guarding request: the length of the answer it asks
/// for, 1 byte (CiA 301 §7.2.8.3.2.1). Decoding accepts any DLC.
const GUARD_REQUEST_DLC: u8 = HEARTBEAT_LEN as u8;

/// A CAN frame read as CANopen, by the function its identifier has in the
/// pre-defined connection set (CiA 301 §7.3.5 Table 72;
/// docs/canopen.md#identifiers).
///
/// Data that a kind's codec refuses (an EMCY shorter than 8 bytes, an NMT
/// command specifier CiA 301 does not define, …) makes
/// [`CanOpenMessage::decode`] return a [`DecodeError`] instead. Remote
/// frames mean something only on the error-control identifiers (a
/// node-guarding request); any other remote frame is
/// [`CanOpenMessage::Other`].
///
/// With the `serde` feature the message has serde's derived format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CanOpenMessage {
    /// 0x000: NMT node control (CiA 301 §7.2.8.3.1).
    NmtNodeControl(NmtNodeControl),
    /// 0x080: SYNC, with its counter when the producer sends one
    /// (CiA 301 §7.2.5: no data, or 1 byte of counter).
    Sync {
        /// The SYNC counter, if the frame carries one.
        counter: Option<u8>,
    },
    /// 0x081..=0x0FF: an EMCY (CiA 301 §7.2.7; docs/canopen.md#emcy).
    Emcy {
        /// The node that sent it, from the identifier.
        node: NodeId,
        /// The decoded EMCY.
        emcy: Emcy,
    },
    /// 0x100: TIME (CiA 301 §7.2.6): the producer's TIME_OF_DAY
    /// (`time_of_day` in docs/output.md#time).
    Time(TimeOfDay),
    /// 0x181..=0x57F: one of the four default TPDOs or RPDOs of a node
    /// (CiA 301 §7.2.2); the data's meaning comes from the PDO mapping.
    Pdo {
        /// The node that owns the PDO.
        node: NodeId,
        /// The PDO number, 1..=4.
        number: u8,
        /// Transmit (TPDO) or receive (RPDO), seen from the node.
        direction: PdoDirection,
        /// The data bytes.
        data: FrameData,
    },
    /// 0x581..=0x5FF: an SDO response, server (the node) → client
    /// (CiA 301 §7.2.4).
    SdoResponse {
        /// The SDO server's node.
        node: NodeId,
        /// The data bytes.
        data: FrameData,
    },
    /// 0x601..=0x67F: an SDO request, client → server (the node)
    /// (CiA 301 §7.2.4).
    SdoRequest {
        /// The SDO server's node.
        node: NodeId,
        /// The data bytes.
        data: FrameData,
    },
    /// 0x701..=0x77F, data frame: a heartbeat, a boot-up message or a
    /// node-guarding answer — one byte on the same identifier, told apart
    /// only by context (CiA 301 §7.2.8.3.2; docs/canopen.md#error-control).
    Heartbeat {
        /// The node that sent it.
        node: NodeId,
        /// The byte as received, undefined states kept.
        byte: NmtStateByte,
    },
    /// 0x701..=0x77F, remote frame: the NMT master's node-guarding request
    /// (CiA 301 §7.2.8.3.2.1; docs/canopen.md#error-control).
    GuardRequest {
        /// The guarded node.
        node: NodeId,
    },
    /// An error frame (docs/formats.md#error-frames): not a CANopen message,
    /// but a fact about the bus that a CANopen log carries.
    ErrorFrame(ErrorFrame),
    /// A frame that is not decoded further: an identifier without a
    /// function (e.g. 0x7E5, or node-ID 0 in a node range), a frame with a
    /// 29-bit identifier, which CANopen's pre-defined connection set does
    /// not use (CiA 301 §7.3.5; docs/canopen.md#identifiers), or a remote
    /// request on an identifier other than error control and EMCY (such as a
    /// request for an RTR-triggered TPDO, CiA 301 §7.2.2.2). Its
    /// [`kind`](CanOpenMessage::kind) and [`node`](CanOpenMessage::node) are
    /// still what the identifier says: a TPDO request is kind `pdo`.
    Other(CanFrame),
}

impl CanOpenMessage {
    /// Decode a frame (owned or borrowed). Data that the kind's codec
    /// refuses is a [`DecodeError`] with that codec's error
    /// ([`Error::Length`] for a short frame, [`Error::InvalidValue`] for an
    /// undefined code, …), the kind and the node. Bytes past what a kind
    /// reads are not checked (as for every frame of the crate), except for
    /// SYNC, whose data is empty or one counter byte.
    pub fn decode<D: AsRef<[u8]>>(frame: &CanFrame<D>) -> Result<Self, DecodeError> {
        let (kind, node, function) = MessageKind::classify_with_function(frame);
        let fail = |error: Error| DecodeError {
            kind,
            node,
            error,
            partial_emcy: None,
        };
        let data = frame.data();
        let owned = || FrameData::new(data).map_err(|e| fail(e.into()));
        if frame.is_error() {
            return ErrorFrame::from_frame(frame)
                .map(CanOpenMessage::ErrorFrame)
                .map_err(|e| fail(e.into()));
        }
        if frame.is_rtr() {
            return match function {
                CobFunction::ErrorControl(node) => Ok(CanOpenMessage::GuardRequest { node }),
                // An EMCY has 8 bytes; a request carries none.
                CobFunction::Emcy(_) => Err(DecodeError {
                    partial_emcy: Some(PartialEmcy::read(&[])),
                    ..fail(
                        LenError {
                            what: What::EmcyFrame,
                            expected: EMCY_LEN,
                            found: 0,
                        }
                        .into(),
                    )
                }),
                // A request for an RTR-triggered TPDO (CiA 301 §7.2.2.2) and
                // requests without a CANopen meaning: kept as they are.
                _ => Ok(CanOpenMessage::Other(frame.to_owned_frame())),
            };
        }
        Ok(match function {
            CobFunction::NmtCommand => CanOpenMessage::NmtNodeControl(
                NmtNodeControl::parse(data).map_err(|e| fail(e.into()))?,
            ),
            CobFunction::Sync => CanOpenMessage::Sync {
                counter: match *data {
                    [] => None,
                    [counter] => Some(counter),
                    _ => {
                        return Err(fail(
                            ValueError {
                                what: What::SyncDataLength,
                                found: data.len() as u32,
                                expected: "0, or 1 with the SYNC counter",
                            }
                            .into(),
                        ))
                    }
                },
            },
            CobFunction::Emcy(node) => match Emcy::parse(data) {
                Ok(emcy) => CanOpenMessage::Emcy { node, emcy },
                Err(error) => {
                    return Err(DecodeError {
                        partial_emcy: Some(PartialEmcy::read(data)),
                        ..fail(error.into())
                    })
                }
            },
            CobFunction::Time => {
                CanOpenMessage::Time(TimeOfDay::parse(data).map_err(|e| fail(e.into()))?)
            }
            CobFunction::Pdo {
                node,
                number,
                direction,
            } => CanOpenMessage::Pdo {
                node,
                number,
                direction,
                data: owned()?,
            },
            CobFunction::SdoTx(node) => CanOpenMessage::SdoResponse {
                node,
                data: owned()?,
            },
            CobFunction::SdoRx(node) => CanOpenMessage::SdoRequest {
                node,
                data: owned()?,
            },
            CobFunction::ErrorControl(node) => match data.first() {
                Some(&byte) => CanOpenMessage::Heartbeat {
                    node,
                    byte: NmtStateByte::new(byte),
                },
                None => {
                    return Err(fail(
                        LenError {
                            what: What::HeartbeatMessage,
                            expected: HEARTBEAT_LEN,
                            found: 0,
                        }
                        .into(),
                    ))
                }
            },
            CobFunction::Other => CanOpenMessage::Other(frame.to_owned_frame()),
        })
    }

    /// Return the kind, as `kind` names it (docs/output.md#common-keys).
    #[must_use]
    pub fn kind(&self) -> MessageKind {
        match self {
            CanOpenMessage::NmtNodeControl(_) => MessageKind::NmtCommand,
            CanOpenMessage::Sync { .. } => MessageKind::Sync,
            CanOpenMessage::Emcy { .. } => MessageKind::Emcy,
            CanOpenMessage::Time(_) => MessageKind::Time,
            CanOpenMessage::Pdo { .. } => MessageKind::Pdo,
            CanOpenMessage::SdoResponse { .. } | CanOpenMessage::SdoRequest { .. } => {
                MessageKind::Sdo
            }
            CanOpenMessage::Heartbeat { .. } => MessageKind::Heartbeat,
            CanOpenMessage::GuardRequest { .. } => MessageKind::GuardRequest,
            CanOpenMessage::ErrorFrame(_) => MessageKind::ErrorFrame,
            CanOpenMessage::Other(frame) => MessageKind::classify(frame).0,
        }
    }

    /// Return the node the identifier belongs to, for the kinds that
    /// have a `node` (docs/output.md#common-keys): EMCY, heartbeat, guard
    /// request, PDO and SDO. (An NMT command's addressed node is in its data,
    /// not here.)
    #[must_use]
    pub fn node(&self) -> Option<NodeId> {
        match *self {
            CanOpenMessage::Emcy { node, .. }
            | CanOpenMessage::Pdo { node, .. }
            | CanOpenMessage::SdoResponse { node, .. }
            | CanOpenMessage::SdoRequest { node, .. }
            | CanOpenMessage::Heartbeat { node, .. }
            | CanOpenMessage::GuardRequest { node } => Some(node),
            CanOpenMessage::NmtNodeControl(_)
            | CanOpenMessage::Sync { .. }
            | CanOpenMessage::Time(_)
            | CanOpenMessage::ErrorFrame(_) => None,
            CanOpenMessage::Other(frame) => MessageKind::classify(&frame).1,
        }
    }

    /// Return the 11-bit identifier the message is sent on, or `None` for
    /// an error frame, a frame with a 29-bit identifier, and fields that
    /// make no identifier (a PDO number outside 1..=4).
    #[must_use]
    pub fn cob_id(&self) -> Option<u16> {
        match *self {
            CanOpenMessage::NmtNodeControl(_) => Some(cob_id::NMT),
            CanOpenMessage::Sync { .. } => Some(cob_id::SYNC),
            CanOpenMessage::Emcy { node, .. } => Some(node.emcy_cob_id()),
            CanOpenMessage::Time(_) => Some(cob_id::TIME),
            CanOpenMessage::Pdo {
                node,
                number,
                direction,
                ..
            } => node.pdo_cob_id(direction, u16::from(number)),
            CanOpenMessage::SdoResponse { node, .. } => {
                Some(cob_id::SDO_TX_BASE + u16::from(node.get()))
            }
            CanOpenMessage::SdoRequest { node, .. } => {
                Some(cob_id::SDO_RX_BASE + u16::from(node.get()))
            }
            CanOpenMessage::Heartbeat { node, .. } | CanOpenMessage::GuardRequest { node } => {
                Some(node.error_control_cob_id())
            }
            CanOpenMessage::ErrorFrame(_) => None,
            CanOpenMessage::Other(frame) if frame.is_error() => None,
            CanOpenMessage::Other(frame) => frame.id().standard_raw(),
        }
    }

    /// Return the frame of this message: its identifier and encoded data,
    /// a remote frame of DLC 1 for a node-guarding request, the frame
    /// itself for [`Other`](CanOpenMessage::Other). `None` where the fields
    /// make no identifier (see [`cob_id`](Self::cob_id)) and for an error
    /// frame, whose details are read, not written.
    #[must_use]
    pub fn encode(&self) -> Option<CanFrame> {
        if let CanOpenMessage::Other(frame) = self {
            return Some(*frame);
        }
        let id = CanId::standard(u32::from(self.cob_id()?))?;
        let frame = match self {
            CanOpenMessage::NmtNodeControl(control) => {
                let bytes: [u8; NMT_NODE_CONTROL_LEN] = control.to_bytes();
                CanFrame::new(id, &bytes)
            }
            CanOpenMessage::Sync { counter: None } => CanFrame::new(id, &[]),
            CanOpenMessage::Sync {
                counter: Some(counter),
            } => CanFrame::new(id, &[*counter]),
            CanOpenMessage::Emcy { emcy, .. } => {
                let bytes: [u8; EMCY_LEN] = emcy.to_bytes();
                CanFrame::new(id, &bytes)
            }
            CanOpenMessage::Heartbeat { byte, .. } => CanFrame::new(id, &[byte.get()]),
            CanOpenMessage::GuardRequest { .. } => CanFrame::new_remote(id, GUARD_REQUEST_DLC),
            CanOpenMessage::Time(time) => CanFrame::new(id, &time.to_bytes()),
            CanOpenMessage::Pdo { data, .. }
            | CanOpenMessage::SdoResponse { data, .. }
            | CanOpenMessage::SdoRequest { data, .. } => {
                // Data longer than 8 bytes came from a CAN FD frame.
                if data.len() > crate::can::CLASSIC_MAX_LEN {
                    CanFrame::new_fd(id, crate::can::FdFlags::EMPTY, data.as_slice())
                } else {
                    CanFrame::new(id, data.as_slice())
                }
            }
            CanOpenMessage::ErrorFrame(_) | CanOpenMessage::Other(_) => return None,
        };
        frame.ok()
    }

    /// Return a [`Heartbeat`](CanOpenMessage::Heartbeat) read as a
    /// node-guarding answer: bit 7 as the toggle (CiA 301 §7.2.8.3.2.1).
    /// `None` for every other kind and for an undefined state.
    #[must_use]
    pub fn guard_answer(&self) -> Option<GuardAnswer> {
        match self {
            CanOpenMessage::Heartbeat { byte, .. } => byte.guard_answer(),
            _ => None,
        }
    }
}

impl fmt::Display for CanOpenMessage {
    /// The message in words: `node 1 EMCY 0x8130 …`, `node 5 heartbeat
    /// operational`, `SYNC 7`, `node 3 TPDO1 [2] 01 02`, the candump
    /// notation for anything else.
    ///
    /// ```
    /// use motionwire_codec::can::{CanFrame, CanId};
    /// use motionwire_codec::canopen::CanOpenMessage;
    ///
    /// let frame = CanFrame::new(CanId::standard(0x705).unwrap(), &[0x05])?;
    /// assert_eq!(CanOpenMessage::decode(&frame)?.to_string(), "node 5 heartbeat operational");
    /// let frame = CanFrame::new(CanId::standard(0x183).unwrap(), &[1, 2])?;
    /// assert_eq!(CanOpenMessage::decode(&frame)?.to_string(), "node 3 TPDO1 [2] 01 02");
    /// # Ok::<(), motionwire_codec::Error>(())
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fn bytes(f: &mut fmt::Formatter<'_>, data: &[u8]) -> fmt::Result {
            write!(f, "[{}]", data.len())?;
            for b in data {
                write!(f, " {b:02X}")?;
            }
            Ok(())
        }
        match self {
            CanOpenMessage::NmtNodeControl(control) => write!(f, "{control}"),
            CanOpenMessage::Sync { counter: None } => f.write_str("SYNC"),
            CanOpenMessage::Sync {
                counter: Some(counter),
            } => write!(f, "SYNC {counter}"),
            CanOpenMessage::Emcy { node, emcy } => write!(f, "node {node} {emcy}"),
            CanOpenMessage::Time(time) => write!(f, "TIME {time}"),
            CanOpenMessage::Pdo {
                node,
                number,
                direction,
                data,
            } => {
                let t = match direction {
                    PdoDirection::Transmit => 'T',
                    PdoDirection::Receive => 'R',
                };
                write!(f, "node {node} {t}PDO{number} ")?;
                bytes(f, data.as_slice())
            }
            CanOpenMessage::SdoResponse { node, data } => {
                write!(f, "node {node} SDO response ")?;
                bytes(f, data.as_slice())
            }
            CanOpenMessage::SdoRequest { node, data } => {
                write!(f, "node {node} SDO request ")?;
                bytes(f, data.as_slice())
            }
            CanOpenMessage::Heartbeat { node, byte } => write!(f, "node {node} heartbeat {byte}"),
            CanOpenMessage::GuardRequest { node } => write!(f, "node {node} guard request"),
            CanOpenMessage::ErrorFrame(error) => write!(f, "{error}"),
            CanOpenMessage::Other(frame) => write!(f, "{frame}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::can::{FdFlags, FrameType};
    use crate::canopen::{NmtCommand, NmtState};

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    /// The table gives, for every standard identifier as a data, remote and
    /// CAN FD frame, the kind and node of the identifier's function
    /// (`classify_with_function`, which `CanOpenMessage::decode` reads);
    /// extended and error frames are `Other` and `ErrorFrame`.
    #[test]
    fn classify_by_table_is_classify_by_function() {
        for id in 0..=0x7FF_u16 {
            let std_id = CanId::standard(u32::from(id)).unwrap();
            let frames = [
                CanFrame::new(std_id, &[0x05]).unwrap(),
                CanFrame::new_remote(std_id, 1).unwrap(),
                CanFrame::with_type(std_id, FrameType::Fd(FdFlags::BRS), &[0; 12]).unwrap(),
                CanFrame::new(CanId::extended(u32::from(id)).unwrap(), &[]).unwrap(),
            ];
            for frame in frames {
                let (kind, node, _) = MessageKind::classify_with_function(&frame);
                assert_eq!(MessageKind::classify(&frame), (kind, node), "{frame}");
            }
        }
        let error =
            CanFrame::with_type(CanId::extended(0x40).unwrap(), FrameType::Error, &[0; 8]).unwrap();
        assert_eq!(
            MessageKind::classify(&error),
            (MessageKind::ErrorFrame, None)
        );
    }

    fn std_id(raw: u16) -> CanId {
        CanId::standard(u32::from(raw)).unwrap()
    }

    fn data(id: u16, bytes: &[u8]) -> CanFrame {
        CanFrame::new(std_id(id), bytes).unwrap()
    }

    fn remote(id: u16, dlc: u8) -> CanFrame {
        CanFrame::new_remote(std_id(id), dlc).unwrap()
    }

    fn bytes(raw: &[u8]) -> FrameData {
        FrameData::new(raw).unwrap()
    }

    /// An AKD EMCY (docs/canopen.md#emcy, docs/canopen.md#akd): code 0x8130,
    /// register 0x11, axis 1.
    static EMCY_BYTES: [u8; 8] = [0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00];

    /// The identifier table of docs/canopen.md#identifiers, one frame per row:
    /// (frame, message, kind, node).
    #[test]
    fn identifiers_of_spec_6_1() {
        use CanOpenMessage::*;
        use PdoDirection::{Receive, Transmit};
        let emcy = super::Emcy::from_bytes(&EMCY_BYTES);
        let ext = CanFrame::new(CanId::extended(0x0000_0081).unwrap(), &EMCY_BYTES).unwrap();
        let table: Vec<(CanFrame, CanOpenMessage, &str, Option<u8>)> = vec![
            (
                data(0x000, &[0x01, 0x00]),
                NmtNodeControl(super::NmtNodeControl::new(
                    NmtCommand::StartRemoteNode,
                    None,
                )),
                "nmt_command",
                None,
            ),
            (data(0x080, &[]), Sync { counter: None }, "sync", None),
            (data(0x080, &[7]), Sync { counter: Some(7) }, "sync", None),
            (
                data(0x081, &EMCY_BYTES),
                Emcy { node: n(1), emcy },
                "emcy",
                Some(1),
            ),
            (
                data(0x0FF, &EMCY_BYTES),
                Emcy { node: n(127), emcy },
                "emcy",
                Some(127),
            ),
            (
                data(0x100, &[1, 2, 3, 4, 5, 6]),
                Time(TimeOfDay::parse(&[1, 2, 3, 4, 5, 6]).unwrap()),
                "time",
                None,
            ),
            (
                data(0x181, &[0xAA]),
                Pdo {
                    node: n(1),
                    number: 1,
                    direction: Transmit,
                    data: bytes(&[0xAA]),
                },
                "pdo",
                Some(1),
            ),
            (
                data(0x57F, &[]),
                Pdo {
                    node: n(127),
                    number: 4,
                    direction: Receive,
                    data: bytes(&[]),
                },
                "pdo",
                Some(127),
            ),
            (
                data(0x581, &[0x60]),
                SdoResponse {
                    node: n(1),
                    data: bytes(&[0x60]),
                },
                "sdo",
                Some(1),
            ),
            (
                data(0x67F, &[0x40]),
                SdoRequest {
                    node: n(127),
                    data: bytes(&[0x40]),
                },
                "sdo",
                Some(127),
            ),
            (data(0x580, &[]), Other(data(0x580, &[])), "other", None),
            (data(0x600, &[]), Other(data(0x600, &[])), "other", None),
            (
                data(0x705, &[0x05]),
                Heartbeat {
                    node: n(5),
                    byte: NmtStateByte::new(0x05),
                },
                "heartbeat",
                Some(5),
            ),
            (
                data(0x705, &[0x12]),
                Heartbeat {
                    node: n(5),
                    byte: NmtStateByte::new(0x12),
                },
                "heartbeat",
                Some(5),
            ),
            (
                remote(0x705, 1),
                GuardRequest { node: n(5) },
                "guard_request",
                Some(5),
            ),
            (
                remote(0x705, 0),
                GuardRequest { node: n(5) },
                "guard_request",
                Some(5),
            ),
            (data(0x700, &[0]), Other(data(0x700, &[0])), "other", None),
            (data(0x7E5, &[]), Other(data(0x7E5, &[])), "other", None),
            (remote(0x181, 8), Other(remote(0x181, 8)), "pdo", Some(1)),
            (remote(0x605, 0), Other(remote(0x605, 0)), "sdo", Some(5)),
            (ext, Other(ext), "other", None),
        ];
        for (frame, expected, kind, node) in table {
            let message = CanOpenMessage::decode(&frame).unwrap();
            assert_eq!(message, expected, "{frame}");
            assert_eq!(message.kind().name(), kind, "{frame}");
            assert_eq!(message.node().map(NodeId::get), node, "{frame}");
            assert_eq!(
                MessageKind::classify(&frame),
                (message.kind(), message.node()),
                "{frame}"
            );
            // The borrowed form decodes the same.
            assert_eq!(CanOpenMessage::decode(&frame.as_frame_ref()), Ok(expected));
        }
    }

    #[test]
    fn error_frames() {
        let frame = CanFrame::new_error(0x040, &[0; 8]).unwrap();
        let message = CanOpenMessage::decode(&frame).unwrap();
        assert_eq!(message.kind(), MessageKind::ErrorFrame);
        let CanOpenMessage::ErrorFrame(error) = message else {
            panic!("{message:?}")
        };
        assert!(error.is_bus_off());
        assert_eq!(
            (message.node(), message.cob_id(), message.encode()),
            (None, None, None)
        );
    }

    #[test]
    fn fd_frames_keep_all_their_data() {
        let frame = CanFrame::new_fd(std_id(0x181), FdFlags::BRS, &[7; 12]).unwrap();
        let message = CanOpenMessage::decode(&frame).unwrap();
        assert!(matches!(message, CanOpenMessage::Pdo { data, .. } if data.as_slice() == [7; 12]));
        let back = message.encode().unwrap();
        assert_eq!((back.is_fd(), back.data()), (true, &[7; 12][..]));
    }

    #[test]
    fn encoding_gives_the_frame_back() {
        let frames = [
            data(0x081, &EMCY_BYTES),
            data(0x77F, &[0x00]),
            data(0x705, &[0x85]),
            data(0x705, &[0x12]),
            remote(0x703, 1),
            data(0x000, &[0x81, 0x09]),
            data(0x080, &[]),
            data(0x080, &[240]),
            data(0x382, &[9]),
            data(0x402, &[9]),
            data(0x581, &[0x60]),
            data(0x601, &[0x40]),
            data(0x100, &[0x00, 0x2E, 0x93, 0x02, 0x33, 0x3D]),
            remote(0x7E5, 2),
            CanFrame::new(CanId::extended(0x18FF_0001).unwrap(), &[1]).unwrap(),
        ];
        for frame in frames {
            let message = CanOpenMessage::decode(&frame).unwrap();
            assert_eq!(message.encode(), Some(frame), "{frame}");
            assert_eq!(message.cob_id(), frame.id().standard_raw(), "{frame}");
        }
        // A guard request is written with DLC 1, whatever DLC was read.
        let request = CanOpenMessage::GuardRequest { node: n(3) };
        assert_eq!(request.encode(), Some(remote(0x703, 1)));
        // Fields that make no identifier.
        let pdo = CanOpenMessage::Pdo {
            node: n(2),
            number: 5,
            direction: PdoDirection::Transmit,
            data: FrameData::EMPTY,
        };
        assert_eq!((pdo.cob_id(), pdo.encode()), (None, None));
    }

    #[test]
    fn a_heartbeat_read_as_a_guard_answer() {
        let message = CanOpenMessage::decode(&data(0x705, &[0x85])).unwrap();
        assert_eq!(
            message.guard_answer(),
            Some(GuardAnswer::new(true, NmtState::Operational))
        );
        let invalid = CanOpenMessage::decode(&data(0x705, &[0x92])).unwrap();
        assert_eq!(invalid.guard_answer(), None);
        assert_eq!(
            CanOpenMessage::GuardRequest { node: n(5) }.guard_answer(),
            None
        );
    }

    #[test]
    fn state_bytes() {
        for byte in 0..=u8::MAX {
            let b = NmtStateByte::new(byte);
            assert_eq!(b.state_raw(), byte & 0x7F);
            assert_eq!(b.toggle(), byte >= 0x80);
            let expected = match byte & 0x7F {
                0x00 => "boot_up",
                0x04 => "stopped",
                0x05 => "operational",
                0x7F => "pre_operational",
                _ => "invalid",
            };
            assert_eq!(b.state_name(), expected, "{byte:#x}");
            assert_eq!(b.heartbeat().is_some(), expected != "invalid");
        }
    }

    #[test]
    fn data_a_kind_refuses_is_that_kinds_error() {
        let cases: Vec<(CanFrame, MessageKind, Option<u8>, Error)> = vec![
            (
                data(0x081, &EMCY_BYTES[..7]),
                MessageKind::Emcy,
                Some(1),
                Error::Length(LenError {
                    what: What::EmcyFrame,
                    expected: 8,
                    found: 7,
                }),
            ),
            (
                data(0x705, &[]),
                MessageKind::Heartbeat,
                Some(5),
                Error::Length(LenError {
                    what: What::HeartbeatMessage,
                    expected: 1,
                    found: 0,
                }),
            ),
            (
                data(0x000, &[0x01]),
                MessageKind::NmtCommand,
                None,
                Error::Length(LenError {
                    what: What::NmtNodeControlMessage,
                    expected: 2,
                    found: 1,
                }),
            ),
            (
                data(0x000, &[0x03, 0x00]),
                MessageKind::NmtCommand,
                None,
                Error::InvalidValue(ValueError {
                    what: What::NmtCommandSpecifier,
                    found: 3,
                    expected: "0x01, 0x02, 0x80, 0x81, 0x82",
                }),
            ),
            (
                data(0x080, &[1, 2]),
                MessageKind::Sync,
                None,
                Error::InvalidValue(ValueError {
                    what: What::SyncDataLength,
                    found: 2,
                    expected: "0, or 1 with the SYNC counter",
                }),
            ),
        ];
        for (frame, kind, node, error) in cases {
            let e = CanOpenMessage::decode(&frame).unwrap_err();
            assert_eq!(
                (e.kind, e.node.map(NodeId::get), e.error),
                (kind, node, error),
                "{frame}"
            );
            assert_eq!(Error::from(e), error);
        }
    }

    /// docs/output.md#emcy: a short EMCY keeps `code` from 2 bytes and
    /// `register` from 3.
    #[test]
    fn every_short_emcy_is_an_exact_error_with_what_it_still_says() {
        for len in 0..EMCY_LEN {
            let e = CanOpenMessage::decode(&data(0x083, &EMCY_BYTES[..len])).unwrap_err();
            assert_eq!(
                e.error,
                Error::Length(LenError {
                    what: What::EmcyFrame,
                    expected: 8,
                    found: len
                })
            );
            let partial = e.partial_emcy.unwrap();
            assert_eq!(partial.code, (len >= 2).then(|| ErrorCode::new(0x8130)));
            assert_eq!(
                partial.register,
                (len >= 3).then(|| ErrorRegister::from_bits_retain(0x11))
            );
        }
    }
}

#[cfg(test)]
mod proptests {
    use super::*;
    use crate::strategies::can::{any_can_frame, canopen_message};
    use proptest::prelude::*;

    proptest! {
        /// Every frame decodes without panicking, to the kind and node its
        /// identifier gives; what decodes, encodes to a frame that decodes
        /// to the same message.
        #[test]
        fn decode_never_panics_and_encodes_back(frame in any_can_frame()) {
            match CanOpenMessage::decode(&frame) {
                Ok(message) => {
                    prop_assert_eq!(MessageKind::classify(&frame), (message.kind(), message.node()));
                    match message.encode() {
                        Some(again) => prop_assert_eq!(CanOpenMessage::decode(&again), Ok(message)),
                        None => prop_assert!(frame.is_error()),
                    }
                }
                Err(e) => prop_assert_eq!(MessageKind::classify(&frame), (e.kind, e.node)),
            }
        }

        /// Every message encodes to a frame that decodes to it.
        #[test]
        fn message_frame_message(message in canopen_message()) {
            let frame = message.encode().expect("generated messages have a frame");
            prop_assert_eq!(CanOpenMessage::decode(&frame), Ok(message));
        }
    }
}
