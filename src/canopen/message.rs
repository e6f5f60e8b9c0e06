//! A whole CAN frame read as CANopen: its identifier classified by the
//! pre-defined connection set and its data decoded by the crate's codecs
//! (CiA 301 §7.3.5 Table 72; SPEC §6.1, "Identifiers").
//!
//! [`CanOpenMessage::decode`] takes what any CAN driver or log gives — an
//! 11-bit identifier and a [`CanPayload`] (data bytes, or the DLC of a
//! remote frame) — and returns the message: an [`Emcy`], a [`Heartbeat`],
//! an [`NmtNodeControl`], … or [`CanOpenMessage::Other`] for an identifier
//! without a function. [`CanOpenMessage::cob_id`] and
//! [`CanOpenMessage::payload`] give the frame back. With the `embedded-can`
//! feature, `CanOpenMessage::from_frame` and `to_frame` do the same with any
//! `embedded_can::Frame`.
//!
//! ```
//! use motionwire::canopen::{CanOpenMessage, CanPayload, ErrorCode, NmtState, NodeId};
//!
//! let node = NodeId::new(1).unwrap();
//!
//! // 081#3081110100000000: an EMCY of node 1.
//! let data = [0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00];
//! let message = CanOpenMessage::decode(0x081, CanPayload::data(&data)?)?;
//! let CanOpenMessage::Emcy { node: from, emcy } = message else { unreachable!() };
//! assert_eq!((from, emcy.code), (node, ErrorCode::new(0x8130)));
//! assert_eq!(message.name(), "emcy");
//!
//! // 701#05 is a heartbeat, 701#R a node-guarding request.
//! let heartbeat = CanOpenMessage::decode(0x701, CanPayload::data(&[0x05])?)?;
//! assert!(matches!(heartbeat, CanOpenMessage::Heartbeat { heartbeat, .. }
//!     if heartbeat.state() == NmtState::Operational));
//! let request = CanOpenMessage::decode(0x701, CanPayload::remote(1)?)?;
//! assert_eq!(request, CanOpenMessage::GuardRequest { node });
//!
//! // The frame back.
//! assert_eq!(message.cob_id(), Some(0x081));
//! assert_eq!(message.payload(), CanPayload::data(&data)?);
//!
//! // A frame too short for its kind is an error that says so.
//! assert_eq!(
//!     CanOpenMessage::decode(0x081, CanPayload::data(&data[..5])?).unwrap_err().to_string(),
//!     "EMCY frame: buffer of 5 bytes where 8 are needed"
//! );
//! # Ok::<(), motionwire::Error>(())
//! ```

use core::fmt;

use super::{
    cob_id, CobFunction, Emcy, Heartbeat, NmtNodeControl, NodeId, PdoDirection, EMCY_LEN,
    HEARTBEAT_LEN, NMT_NODE_CONTROL_LEN,
};
use crate::error::{Error, Result};

/// The most data bytes a classic CAN frame carries, 8 (ISO 11898-1).
pub const CAN_MAX_DATA_LEN: usize = 8;

/// The largest 11-bit (standard) CAN identifier, 0x7FF (ISO 11898-1).
pub const MAX_STANDARD_ID: u16 = 0x7FF;

/// The largest 29-bit (extended) CAN identifier, 0x1FFF_FFFF (ISO 11898-1).
pub const MAX_EXTENDED_ID: u32 = 0x1FFF_FFFF;

/// The data field of a classic CAN frame, 0 to 8 bytes, owned
/// (ISO 11898-1).
///
/// ```
/// use motionwire::canopen::CanData;
///
/// let data = CanData::new(&[0x40, 0x00, 0x10])?;
/// assert_eq!(data.as_slice(), [0x40, 0x00, 0x10]);
/// assert_eq!(data.len(), 3);
/// assert!(CanData::new(&[0; 9]).is_err());
/// # Ok::<(), motionwire::Error>(())
/// ```
///
/// With the `serde` feature it serializes as the sequence of its bytes;
/// deserializing refuses more than 8.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CanData {
    /// The bytes; those from `len` on are always 0, so that the derived
    /// comparisons compare the data only.
    bytes: [u8; CAN_MAX_DATA_LEN],
    /// 0..=8.
    len: u8,
}

impl CanData {
    /// No data.
    pub const EMPTY: CanData = CanData {
        bytes: [0; CAN_MAX_DATA_LEN],
        len: 0,
    };

    /// Return a copy of `data`, or an [`Error::OutOfRange`] when it is longer
    /// than 8 bytes.
    pub fn new(data: &[u8]) -> Result<Self> {
        let mut bytes = [0; CAN_MAX_DATA_LEN];
        match bytes.get_mut(..data.len()) {
            Some(head) => head.copy_from_slice(data),
            None => return Err(Self::too_long(data.len())),
        }
        Ok(CanData {
            bytes,
            // At most 8: `get_mut` succeeded.
            len: data.len() as u8,
        })
    }

    fn too_long(len: usize) -> Error {
        Error::OutOfRange {
            what: "CAN data length",
            found: u32::try_from(len).unwrap_or(u32::MAX),
            min: 0,
            max: CAN_MAX_DATA_LEN as u32,
        }
    }

    /// Return the data bytes.
    #[inline]
    pub fn as_slice(&self) -> &[u8] {
        let (data, _) = self
            .bytes
            .split_at(usize::from(self.len).min(CAN_MAX_DATA_LEN));
        data
    }

    /// Return the number of data bytes, 0..=8.
    #[inline]
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    /// Return whether there are no data bytes.
    #[inline]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl AsRef<[u8]> for CanData {
    fn as_ref(&self) -> &[u8] {
        self.as_slice()
    }
}

impl TryFrom<&[u8]> for CanData {
    type Error = Error;

    fn try_from(data: &[u8]) -> Result<Self> {
        Self::new(data)
    }
}

impl fmt::Display for CanData {
    /// Format the data as lowercase hex without separators, as SPEC §6.1's
    /// `data` writes it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.as_slice()
            .iter()
            .try_for_each(|byte| write!(f, "{byte:02x}"))
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for CanData {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.as_slice())
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for CanData {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Bytes;

        impl<'de> serde::de::Visitor<'de> for Bytes {
            type Value = CanData;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a sequence of at most 8 bytes")
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<CanData, A::Error> {
                let mut data = CanData::EMPTY;
                while let Some(byte) = seq.next_element::<u8>()? {
                    let len = data.len();
                    match data.bytes.get_mut(len) {
                        Some(slot) => *slot = byte,
                        None => {
                            return Err(serde::de::Error::invalid_length(
                                CAN_MAX_DATA_LEN + 1,
                                &self,
                            ))
                        }
                    }
                    data.len += 1;
                }
                Ok(data)
            }
        }

        deserializer.deserialize_seq(Bytes)
    }
}

/// The data length code of a remote frame, 0..=8: the length of the data
/// frame it requests (ISO 11898-1; a remote frame carries no data).
///
/// With the `serde` feature it serializes as its number; deserializing
/// refuses any number above 8.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "u8", into = "u8")
)]
pub struct Dlc(u8);

impl Dlc {
    /// Return the DLC `raw`, or `None` above 8.
    #[inline]
    pub const fn new(raw: u8) -> Option<Self> {
        if raw as usize <= CAN_MAX_DATA_LEN {
            Some(Dlc(raw))
        } else {
            None
        }
    }

    /// Return the DLC `raw`, or an [`Error::OutOfRange`] above 8.
    #[inline]
    pub const fn try_new(raw: u8) -> Result<Self> {
        match Self::new(raw) {
            Some(dlc) => Ok(dlc),
            None => Err(Error::OutOfRange {
                what: "CAN remote frame DLC",
                found: raw as u32,
                min: 0,
                max: CAN_MAX_DATA_LEN as u32,
            }),
        }
    }

    /// Return the DLC as a number in 0..=8.
    #[inline]
    pub const fn get(self) -> u8 {
        self.0
    }
}

impl TryFrom<u8> for Dlc {
    type Error = Error;

    fn try_from(raw: u8) -> Result<Self> {
        Self::try_new(raw)
    }
}

impl From<Dlc> for u8 {
    fn from(dlc: Dlc) -> u8 {
        dlc.0
    }
}

/// What a classic CAN frame carries besides its identifier: data bytes, or
/// for a remote (RTR) frame the length of the data it requests
/// (ISO 11898-1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CanPayload {
    /// A data frame's bytes.
    Data(CanData),
    /// A remote frame: no data, a data length code.
    Remote(Dlc),
}

impl CanPayload {
    /// Return a data frame's payload, or an [`Error::OutOfRange`] when
    /// `data` is longer than 8 bytes.
    #[inline]
    pub fn data(data: &[u8]) -> Result<Self> {
        CanData::new(data).map(CanPayload::Data)
    }

    /// Return a remote frame's payload, or an [`Error::OutOfRange`] when
    /// `dlc` is above 8. A DLC comes from a driver as a `usize`; any value
    /// above 8 is refused the same way.
    #[inline]
    pub fn remote(dlc: usize) -> Result<Self> {
        let raw = u8::try_from(dlc).unwrap_or(u8::MAX);
        Dlc::try_new(raw).map(CanPayload::Remote)
    }

    /// Return whether this is a remote frame's payload.
    #[inline]
    pub const fn is_remote(&self) -> bool {
        matches!(self, CanPayload::Remote(_))
    }

    /// Return the data bytes; empty for a remote frame.
    #[inline]
    pub fn bytes(&self) -> &[u8] {
        match self {
            CanPayload::Data(data) => data.as_slice(),
            CanPayload::Remote(_) => &[],
        }
    }

    /// Return the data length code: the number of data bytes, or a remote
    /// frame's DLC.
    #[inline]
    pub const fn dlc(&self) -> usize {
        match self {
            CanPayload::Data(data) => data.len(),
            CanPayload::Remote(dlc) => dlc.get() as usize,
        }
    }
}

/// The DLC of a node-guarding request: the length of the answer it asks
/// for, 1 byte (CiA 301 §7.2.8.3.2.1). Decoding accepts any DLC.
const GUARD_REQUEST_DLC: Dlc = Dlc(HEARTBEAT_LEN as u8);

/// A CAN frame read as CANopen, by the function its identifier has in the
/// pre-defined connection set (CiA 301 §7.3.5 Table 72; SPEC §6.1).
///
/// Data that a kind's codec refuses (an EMCY shorter than 8 bytes, an
/// undefined NMT state, …) makes [`CanOpenMessage::decode`] return that
/// codec's error instead. Remote frames mean something only on the
/// error-control identifiers (a node-guarding request); any other remote
/// frame is [`CanOpenMessage::Other`].
///
/// With the `serde` feature the message has serde's derived format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    /// 0x081..=0x0FF: an EMCY (CiA 301 §7.2.7; SPEC §2.1).
    Emcy {
        /// The node that sent it, from the identifier.
        node: NodeId,
        /// The decoded EMCY.
        emcy: Emcy,
    },
    /// 0x100: TIME stamp (CiA 301 §7.2.6), not decoded further.
    Time {
        /// The data bytes.
        data: CanData,
    },
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
        data: CanData,
    },
    /// 0x581..=0x5FF: an SDO response, server (the node) → client
    /// (CiA 301 §7.2.4).
    SdoResponse {
        /// The SDO server's node.
        node: NodeId,
        /// The data bytes.
        data: CanData,
    },
    /// 0x601..=0x67F: an SDO request, client → server (the node)
    /// (CiA 301 §7.2.4).
    SdoRequest {
        /// The SDO server's node.
        node: NodeId,
        /// The data bytes.
        data: CanData,
    },
    /// 0x701..=0x77F, data frame: a heartbeat, a boot-up message or a
    /// node-guarding answer — one byte on the same identifier, told apart
    /// only by context (CiA 301 §7.2.8.3.2; SPEC §2.7). Bit 7 is kept as
    /// [`Heartbeat::reserved_bit`]; [`CanOpenMessage::guard_answer`] reads
    /// it as a toggle.
    Heartbeat {
        /// The node that sent it.
        node: NodeId,
        /// The decoded byte.
        heartbeat: Heartbeat,
    },
    /// 0x701..=0x77F, remote frame: the NMT master's node-guarding request
    /// (CiA 301 §7.2.8.3.2.1; SPEC §2.7).
    GuardRequest {
        /// The guarded node.
        node: NodeId,
    },
    /// A standard frame that the pre-defined connection set gives no meaning:
    /// an identifier without a function (e.g. 0x7E5, or node-ID 0 in a
    /// node range), or a remote frame on an identifier other than error
    /// control (such as a request for an RTR-triggered TPDO; classify
    /// `cob_id` with [`CobFunction::classify`] to tell).
    Other {
        /// The 11-bit identifier.
        cob_id: u16,
        /// What the frame carries.
        payload: CanPayload,
    },
    /// A frame with a 29-bit identifier: not CANopen, whose pre-defined
    /// connection set uses 11-bit identifiers (CiA 301 §7.3.5; SPEC §6.1).
    Extended {
        /// The 29-bit identifier, at most [`MAX_EXTENDED_ID`].
        id: u32,
        /// What the frame carries.
        payload: CanPayload,
    },
}

impl CanOpenMessage {
    /// Decode a standard frame with identifier `cob_id`: an identifier above
    /// 0x7FF is an [`Error::OutOfRange`]; data that the kind's codec refuses
    /// is that codec's error ([`Error::Length`] for a short frame,
    /// [`Error::InvalidValue`] for an undefined code, …). Bytes past what a
    /// kind reads are not checked (as for every frame of the crate), except
    /// for SYNC, whose data is empty or one counter byte.
    pub fn decode(cob_id: u16, payload: CanPayload) -> Result<Self> {
        if cob_id > MAX_STANDARD_ID {
            return Err(Error::OutOfRange {
                what: "11-bit CAN identifier",
                found: u32::from(cob_id),
                min: 0,
                max: u32::from(MAX_STANDARD_ID),
            });
        }
        let function = CobFunction::classify(cob_id);
        let data = match payload {
            CanPayload::Data(data) => data,
            CanPayload::Remote(_) => {
                return Ok(match function {
                    CobFunction::ErrorControl(node) => CanOpenMessage::GuardRequest { node },
                    _ => CanOpenMessage::Other { cob_id, payload },
                })
            }
        };
        Ok(match function {
            CobFunction::NmtCommand => {
                CanOpenMessage::NmtNodeControl(NmtNodeControl::parse(data.as_slice())?)
            }
            CobFunction::Sync => CanOpenMessage::Sync {
                counter: match *data.as_slice() {
                    [] => None,
                    [counter] => Some(counter),
                    _ => {
                        return Err(Error::InvalidValue {
                            what: "SYNC data length",
                            found: data.len() as u32,
                            expected: "0, or 1 with the SYNC counter",
                        })
                    }
                },
            },
            CobFunction::Emcy(node) => CanOpenMessage::Emcy {
                node,
                emcy: Emcy::parse(data.as_slice())?,
            },
            CobFunction::Time => CanOpenMessage::Time { data },
            CobFunction::Pdo {
                node,
                number,
                direction,
            } => CanOpenMessage::Pdo {
                node,
                number,
                direction,
                data,
            },
            CobFunction::SdoTx(node) => CanOpenMessage::SdoResponse { node, data },
            CobFunction::SdoRx(node) => CanOpenMessage::SdoRequest { node, data },
            CobFunction::ErrorControl(node) => CanOpenMessage::Heartbeat {
                node,
                heartbeat: Heartbeat::parse(data.as_slice())?,
            },
            CobFunction::Other => CanOpenMessage::Other {
                cob_id,
                payload: CanPayload::Data(data),
            },
        })
    }

    /// Return the 11-bit identifier the message is sent on, or `None` for
    /// an [`Extended`](CanOpenMessage::Extended) frame and for fields that
    /// make no identifier (a PDO number outside 1..=4, an `Other` identifier
    /// above 0x7FF).
    pub const fn cob_id(&self) -> Option<u16> {
        match *self {
            CanOpenMessage::NmtNodeControl(_) => Some(cob_id::NMT),
            CanOpenMessage::Sync { .. } => Some(cob_id::SYNC),
            CanOpenMessage::Emcy { node, .. } => Some(node.emcy_cob_id()),
            CanOpenMessage::Time { .. } => Some(cob_id::TIME),
            CanOpenMessage::Pdo {
                node,
                number,
                direction,
                ..
            } => {
                if number < 1 || number > 4 {
                    return None;
                }
                // TPDO n: 0x080 + n·0x100; RPDO n: 0x100 + n·0x100.
                let base = match direction {
                    PdoDirection::Transmit => 0x080,
                    PdoDirection::Receive => 0x100,
                };
                Some(base + (number as u16) * 0x100 + node.get() as u16)
            }
            CanOpenMessage::SdoResponse { node, .. } => {
                Some(cob_id::SDO_TX_BASE + node.get() as u16)
            }
            CanOpenMessage::SdoRequest { node, .. } => {
                Some(cob_id::SDO_RX_BASE + node.get() as u16)
            }
            CanOpenMessage::Heartbeat { node, .. } | CanOpenMessage::GuardRequest { node } => {
                Some(node.error_control_cob_id())
            }
            CanOpenMessage::Other { cob_id, .. } => {
                if cob_id <= MAX_STANDARD_ID {
                    Some(cob_id)
                } else {
                    None
                }
            }
            CanOpenMessage::Extended { .. } => None,
        }
    }

    /// Return what the frame of this message carries: the encoded data, or
    /// for a node-guarding request a remote frame of DLC 1 (the length of
    /// the answer).
    pub fn payload(&self) -> CanPayload {
        // Every encoded length below is at most 8, so `CanData::new` accepts
        // it; the fallback is never taken.
        let data = |bytes: &[u8]| CanPayload::Data(CanData::new(bytes).unwrap_or_default());
        match self {
            CanOpenMessage::NmtNodeControl(control) => {
                let bytes: [u8; NMT_NODE_CONTROL_LEN] = control.to_bytes();
                data(&bytes)
            }
            CanOpenMessage::Sync { counter: None } => CanPayload::Data(CanData::EMPTY),
            CanOpenMessage::Sync {
                counter: Some(counter),
            } => data(&[*counter]),
            CanOpenMessage::Emcy { emcy, .. } => {
                let bytes: [u8; EMCY_LEN] = emcy.to_bytes();
                data(&bytes)
            }
            CanOpenMessage::Heartbeat { heartbeat, .. } => data(&heartbeat.to_bytes()),
            CanOpenMessage::GuardRequest { .. } => CanPayload::Remote(GUARD_REQUEST_DLC),
            CanOpenMessage::Time { data }
            | CanOpenMessage::Pdo { data, .. }
            | CanOpenMessage::SdoResponse { data, .. }
            | CanOpenMessage::SdoRequest { data, .. } => CanPayload::Data(*data),
            CanOpenMessage::Other { payload, .. } | CanOpenMessage::Extended { payload, .. } => {
                *payload
            }
        }
    }

    /// Return the node the identifier belongs to, for the kinds that SPEC
    /// §6.1 gives a `node`: EMCY, heartbeat, guard request, PDO and SDO.
    /// (An NMT command's addressed node is in its data, not here.)
    pub const fn node(&self) -> Option<NodeId> {
        match *self {
            CanOpenMessage::Emcy { node, .. }
            | CanOpenMessage::Pdo { node, .. }
            | CanOpenMessage::SdoResponse { node, .. }
            | CanOpenMessage::SdoRequest { node, .. }
            | CanOpenMessage::Heartbeat { node, .. }
            | CanOpenMessage::GuardRequest { node } => Some(node),
            CanOpenMessage::NmtNodeControl(_)
            | CanOpenMessage::Sync { .. }
            | CanOpenMessage::Time { .. }
            | CanOpenMessage::Other { .. }
            | CanOpenMessage::Extended { .. } => None,
        }
    }

    /// Return the kind as the command-line decoder's `kind` writes it
    /// (SPEC §6.1): `emcy`, `heartbeat`, `guard_request`, `nmt_command`,
    /// `sync`, `pdo`, `sdo` or `other` (TIME, unassigned identifiers and
    /// extended frames).
    pub const fn name(&self) -> &'static str {
        match self {
            CanOpenMessage::NmtNodeControl(_) => "nmt_command",
            CanOpenMessage::Sync { .. } => "sync",
            CanOpenMessage::Emcy { .. } => "emcy",
            CanOpenMessage::Pdo { .. } => "pdo",
            CanOpenMessage::SdoResponse { .. } | CanOpenMessage::SdoRequest { .. } => "sdo",
            CanOpenMessage::Heartbeat { .. } => "heartbeat",
            CanOpenMessage::GuardRequest { .. } => "guard_request",
            CanOpenMessage::Time { .. }
            | CanOpenMessage::Other { .. }
            | CanOpenMessage::Extended { .. } => "other",
        }
    }

    /// Return a [`Heartbeat`](CanOpenMessage::Heartbeat) read as a
    /// node-guarding answer: bit 7 as the toggle (CiA 301 §7.2.8.3.2.1).
    /// `None` for every other kind.
    pub const fn guard_answer(&self) -> Option<super::GuardAnswer> {
        match self {
            CanOpenMessage::Heartbeat { heartbeat, .. } => Some(super::GuardAnswer::new(
                heartbeat.reserved_bit(),
                heartbeat.state(),
            )),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::{ErrorCode, ErrorRegister, GuardAnswer, NmtCommand, NmtState};

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    fn data(bytes: &[u8]) -> CanPayload {
        CanPayload::data(bytes).unwrap()
    }

    fn remote(dlc: usize) -> CanPayload {
        CanPayload::remote(dlc).unwrap()
    }

    fn bytes(raw: &[u8]) -> CanData {
        CanData::new(raw).unwrap()
    }

    /// The AKD EMCY of seed 000 (SPEC §2.1): code 0x8130, register 0x11, axis 1.
    static EMCY_BYTES: [u8; 8] = [0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00];

    /// SPEC §6.1's identifier table, one frame per row: (id, payload,
    /// message, kind).
    #[test]
    fn identifiers_of_spec_6_1() {
        use CanOpenMessage::*;
        use PdoDirection::{Receive, Transmit};
        let emcy = super::Emcy::from_bytes(&EMCY_BYTES);
        let table: &[(u16, CanPayload, CanOpenMessage, &str)] = &[
            (
                0x000,
                data(&[0x01, 0x00]),
                NmtNodeControl(super::NmtNodeControl::new(
                    NmtCommand::StartRemoteNode,
                    None,
                )),
                "nmt_command",
            ),
            (0x080, data(&[]), Sync { counter: None }, "sync"),
            (0x080, data(&[7]), Sync { counter: Some(7) }, "sync"),
            (0x081, data(&EMCY_BYTES), Emcy { node: n(1), emcy }, "emcy"),
            (
                0x0FF,
                data(&EMCY_BYTES),
                Emcy { node: n(127), emcy },
                "emcy",
            ),
            (
                0x100,
                data(&[1, 2, 3, 4, 5, 6]),
                Time {
                    data: bytes(&[1, 2, 3, 4, 5, 6]),
                },
                "other",
            ),
            (
                0x181,
                data(&[0xAA]),
                Pdo {
                    node: n(1),
                    number: 1,
                    direction: Transmit,
                    data: bytes(&[0xAA]),
                },
                "pdo",
            ),
            (
                0x57F,
                data(&[]),
                Pdo {
                    node: n(127),
                    number: 4,
                    direction: Receive,
                    data: CanData::EMPTY,
                },
                "pdo",
            ),
            (
                0x585,
                data(&[0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00]),
                SdoResponse {
                    node: n(5),
                    data: bytes(&[0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00]),
                },
                "sdo",
            ),
            (
                0x605,
                data(&[0x40, 0x00, 0x10, 0x00]),
                SdoRequest {
                    node: n(5),
                    data: bytes(&[0x40, 0x00, 0x10, 0x00]),
                },
                "sdo",
            ),
            (
                0x705,
                data(&[0x7F]),
                Heartbeat {
                    node: n(5),
                    heartbeat: super::Heartbeat::new(NmtState::PreOperational),
                },
                "heartbeat",
            ),
            (
                0x705,
                remote(1),
                GuardRequest { node: n(5) },
                "guard_request",
            ),
            (
                0x705,
                remote(0),
                GuardRequest { node: n(5) },
                "guard_request",
            ),
            (
                0x700,
                data(&[0x05]),
                Other {
                    cob_id: 0x700,
                    payload: data(&[0x05]),
                },
                "other",
            ),
            (
                0x7E5,
                data(&[0x04]),
                Other {
                    cob_id: 0x7E5,
                    payload: data(&[0x04]),
                },
                "other",
            ),
            (
                0x181,
                remote(3),
                Other {
                    cob_id: 0x181,
                    payload: remote(3),
                },
                "other",
            ),
            (
                0x081,
                remote(8),
                Other {
                    cob_id: 0x081,
                    payload: remote(8),
                },
                "other",
            ),
        ];
        for &(id, payload, expected, kind) in table {
            let message = CanOpenMessage::decode(id, payload).unwrap();
            assert_eq!(message, expected, "{id:#05x}");
            assert_eq!(message.name(), kind, "{id:#05x}");
        }
    }

    #[test]
    fn nodes_come_from_the_identifier() {
        let cases: &[(u16, CanPayload, Option<NodeId>)] = &[
            (0x000, data(&[0x81, 0x05]), None),
            (0x080, data(&[]), None),
            (0x085, data(&EMCY_BYTES), Some(n(5))),
            (0x100, data(&[]), None),
            (0x285, data(&[]), Some(n(5))),
            (0x585, data(&[]), Some(n(5))),
            (0x605, data(&[]), Some(n(5))),
            (0x705, data(&[0x05]), Some(n(5))),
            (0x705, remote(1), Some(n(5))),
            (0x7E5, data(&[]), None),
        ];
        for &(id, payload, node) in cases {
            assert_eq!(
                CanOpenMessage::decode(id, payload).unwrap().node(),
                node,
                "{id:#05x}"
            );
        }
    }

    #[test]
    fn encoding_gives_the_frame_back() {
        let emcy = Emcy::new(
            ErrorCode::new(0x8130),
            ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION,
            [1, 0, 0, 0, 0],
        );
        let cases: &[(CanOpenMessage, Option<u16>, CanPayload)] = &[
            (
                CanOpenMessage::Emcy { node: n(1), emcy },
                Some(0x081),
                data(&EMCY_BYTES),
            ),
            (
                CanOpenMessage::Heartbeat {
                    node: n(127),
                    heartbeat: Heartbeat::boot_up(),
                },
                Some(0x77F),
                data(&[0x00]),
            ),
            (
                CanOpenMessage::GuardRequest { node: n(3) },
                Some(0x703),
                remote(1),
            ),
            (
                CanOpenMessage::NmtNodeControl(NmtNodeControl::new(
                    NmtCommand::ResetNode,
                    Some(n(9)),
                )),
                Some(0x000),
                data(&[0x81, 0x09]),
            ),
            (
                CanOpenMessage::Sync { counter: None },
                Some(0x080),
                data(&[]),
            ),
            (
                CanOpenMessage::Sync { counter: Some(240) },
                Some(0x080),
                data(&[240]),
            ),
            (
                CanOpenMessage::Pdo {
                    node: n(2),
                    number: 3,
                    direction: PdoDirection::Transmit,
                    data: bytes(&[9]),
                },
                Some(0x382),
                data(&[9]),
            ),
            (
                CanOpenMessage::Pdo {
                    node: n(2),
                    number: 3,
                    direction: PdoDirection::Receive,
                    data: bytes(&[9]),
                },
                Some(0x402),
                data(&[9]),
            ),
            (
                CanOpenMessage::SdoResponse {
                    node: n(1),
                    data: bytes(&[0x60]),
                },
                Some(0x581),
                data(&[0x60]),
            ),
            (
                CanOpenMessage::SdoRequest {
                    node: n(1),
                    data: bytes(&[0x40]),
                },
                Some(0x601),
                data(&[0x40]),
            ),
            (
                CanOpenMessage::Time {
                    data: CanData::EMPTY,
                },
                Some(0x100),
                data(&[]),
            ),
            (
                CanOpenMessage::Other {
                    cob_id: 0x7E5,
                    payload: remote(2),
                },
                Some(0x7E5),
                remote(2),
            ),
            (
                CanOpenMessage::Extended {
                    id: 0x18FF_0001,
                    payload: data(&[1]),
                },
                None,
                data(&[1]),
            ),
            // Fields that make no identifier.
            (
                CanOpenMessage::Pdo {
                    node: n(2),
                    number: 5,
                    direction: PdoDirection::Transmit,
                    data: CanData::EMPTY,
                },
                None,
                data(&[]),
            ),
            (
                CanOpenMessage::Other {
                    cob_id: 0x800,
                    payload: data(&[]),
                },
                None,
                data(&[]),
            ),
        ];
        for &(message, cob_id, payload) in cases {
            assert_eq!(message.cob_id(), cob_id, "{message:?}");
            assert_eq!(message.payload(), payload, "{message:?}");
        }
    }

    #[test]
    fn a_heartbeat_read_as_a_guard_answer() {
        let message = CanOpenMessage::decode(0x705, data(&[0x85])).unwrap();
        assert_eq!(
            message.guard_answer(),
            Some(GuardAnswer::new(true, NmtState::Operational))
        );
        assert_eq!(
            CanOpenMessage::GuardRequest { node: n(5) }.guard_answer(),
            None
        );
    }

    #[test]
    fn data_a_kind_refuses_is_that_kinds_error() {
        let cases: &[(u16, CanPayload, Error)] = &[
            (
                0x081,
                data(&EMCY_BYTES[..7]),
                Error::Length {
                    what: "EMCY frame",
                    expected: 8,
                    found: 7,
                },
            ),
            (
                0x705,
                data(&[]),
                Error::Length {
                    what: "heartbeat message",
                    expected: 1,
                    found: 0,
                },
            ),
            (
                0x705,
                data(&[0x12]),
                Error::InvalidValue {
                    what: "NMT state",
                    found: 0x12,
                    expected: "0x00, 0x04, 0x05, 0x7f",
                },
            ),
            (
                0x000,
                data(&[0x01]),
                Error::Length {
                    what: "NMT node-control message",
                    expected: 2,
                    found: 1,
                },
            ),
            (
                0x000,
                data(&[0x03, 0x00]),
                Error::InvalidValue {
                    what: "NMT command specifier",
                    found: 3,
                    expected: "0x01, 0x02, 0x80, 0x81, 0x82",
                },
            ),
            (
                0x080,
                data(&[1, 2]),
                Error::InvalidValue {
                    what: "SYNC data length",
                    found: 2,
                    expected: "0, or 1 with the SYNC counter",
                },
            ),
            (
                0x800,
                data(&[]),
                Error::OutOfRange {
                    what: "11-bit CAN identifier",
                    found: 0x800,
                    min: 0,
                    max: 0x7FF,
                },
            ),
        ];
        for &(id, payload, expected) in cases {
            assert_eq!(
                CanOpenMessage::decode(id, payload),
                Err(expected),
                "{id:#05x}"
            );
        }
    }

    #[test]
    fn every_short_emcy_is_an_exact_error() {
        for len in 0..EMCY_LEN {
            assert_eq!(
                CanOpenMessage::decode(0x081, data(&EMCY_BYTES[..len])),
                Err(Error::Length {
                    what: "EMCY frame",
                    expected: 8,
                    found: len
                })
            );
        }
    }

    #[test]
    fn can_data_holds_0_to_8_bytes() {
        let all = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        for len in 0..=8 {
            let data = CanData::new(&all[..len]).unwrap();
            assert_eq!(data.as_slice(), &all[..len]);
            assert_eq!(data.len(), len);
            assert_eq!(data.is_empty(), len == 0);
            assert_eq!(CanData::try_from(&all[..len]), Ok(data));
        }
        assert_eq!(
            CanData::new(&all),
            Err(Error::OutOfRange {
                what: "CAN data length",
                found: 9,
                min: 0,
                max: 8
            })
        );
        assert_eq!(bytes(&[0x0A, 0xFF]).to_string(), "0aff");
        assert_eq!(CanData::EMPTY.to_string(), "");
    }

    #[test]
    fn dlc_holds_0_to_8() {
        for raw in 0..=255u8 {
            assert_eq!(Dlc::new(raw).is_some(), raw <= 8, "{raw}");
        }
        assert_eq!(
            CanPayload::remote(9),
            Err(Error::OutOfRange {
                what: "CAN remote frame DLC",
                found: 9,
                min: 0,
                max: 8
            })
        );
        assert_eq!(
            CanPayload::remote(usize::MAX),
            Err(Error::OutOfRange {
                what: "CAN remote frame DLC",
                found: 255,
                min: 0,
                max: 8
            })
        );
        assert_eq!(remote(5).dlc(), 5);
        assert!(remote(5).is_remote());
        assert_eq!(remote(5).bytes(), [0u8; 0]);
        assert_eq!(data(&[1, 2]).dlc(), 2);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::test_gens::can::{can_payload, canopen_message};

    proptest! {
        /// Every standard frame decodes or is refused; none panics, and what
        /// decodes encodes to the same identifier and, up to the bytes a
        /// kind reads, the same payload.
        #[test]
        fn any_standard_frame_never_panics(cob_id in 0u16..=0x7FF, payload in can_payload()) {
            if let Ok(message) = CanOpenMessage::decode(cob_id, payload) {
                prop_assert_eq!(message.cob_id(), Some(cob_id));
                let again = message.payload();
                prop_assert_eq!(again.is_remote(), payload.is_remote());
                prop_assert!(payload.bytes().starts_with(again.bytes()) || again.is_remote());
            }
        }

        #[test]
        fn message_frame_message(message in canopen_message()) {
            let cob_id = message.cob_id().expect("generated messages have an identifier");
            prop_assert_eq!(CanOpenMessage::decode(cob_id, message.payload()), Ok(message));
        }

        #[test]
        fn identifiers_above_0x7ff_are_refused(cob_id in 0x800u16.., payload in can_payload()) {
            let refused = matches!(
                CanOpenMessage::decode(cob_id, payload),
                Err(Error::OutOfRange { what: "11-bit CAN identifier", .. })
            );
            prop_assert!(refused);
        }
    }
}
