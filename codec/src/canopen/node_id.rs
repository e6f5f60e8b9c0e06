//! Node-IDs and the CANopen pre-defined connection set (CiA 301 §7.3.5).
//!
//! A CANopen node-ID is 1..=127; [`NodeId`] cannot hold any other value.
//! [`CobFunction::classify`] maps an 11-bit identifier to the function the
//! pre-defined connection set gives it, with the node it belongs to.

use crate::error::What;
use core::fmt;

use crate::{RangeError, Result};

/// A CANopen node-ID, always within 1..=127 (CiA 301 §7.3.5;
/// docs/canopen.md#emcy).
///
/// ```
/// use motionwire_codec::canopen::NodeId;
///
/// let node = NodeId::new(5).unwrap();
/// assert_eq!(node.get(), 5);
/// assert_eq!(node.emcy_cob_id(), 0x085);
/// assert!(NodeId::new(0).is_none());
/// assert!(NodeId::new(128).is_none());
/// ```
///
/// With the `serde` feature a node-ID serializes as its number;
/// deserializing refuses any number outside 1..=127.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "u8", into = "u8")
)]
pub struct NodeId(u8);

impl NodeId {
    /// The smallest node-ID, 1.
    pub const MIN: NodeId = NodeId(1);
    /// The largest node-ID, 127.
    pub const MAX: NodeId = NodeId(127);

    /// Return the node-ID `raw`, or `None` when it is outside 1..=127.
    #[inline]
    #[must_use]
    pub const fn new(raw: u8) -> Option<Self> {
        if raw >= 1 && raw <= 127 {
            Some(NodeId(raw))
        } else {
            None
        }
    }

    /// Return the node-ID `raw`, or a [`RangeError`] that names the
    /// value when it is outside 1..=127.
    #[inline]
    pub const fn try_new(raw: u8) -> Result<Self, RangeError> {
        match Self::new(raw) {
            Some(id) => Ok(id),
            None => Err(RangeError {
                what: What::NodeId,
                found: raw as u32,
                min: 1,
                max: 127,
            }),
        }
    }

    /// Return the node-ID as a number in 1..=127.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u8 {
        self.0
    }

    /// Return the index of this node in a 127-entry table (node 1 → 0).
    #[inline]
    #[must_use]
    pub const fn index(self) -> usize {
        self.0 as usize - 1
    }

    /// Return every node-ID, 1 to 127, in ascending order.
    pub fn all() -> impl DoubleEndedIterator<Item = NodeId> + ExactSizeIterator + Clone {
        (1..=127u8).map(NodeId)
    }

    /// Return the COB-ID of this node's EMCY message, 0x080 + node-ID
    /// (CiA 301 §7.2.7.3.1; docs/canopen.md#emcy).
    #[inline]
    #[must_use]
    pub const fn emcy_cob_id(self) -> u16 {
        cob_id::EMCY_BASE + self.0 as u16
    }

    /// Return the COB-ID of this node's error-control messages (heartbeat,
    /// boot-up and node guarding), 0x700 + node-ID (CiA 301 §7.2.8.3;
    /// docs/canopen.md#error-control).
    #[inline]
    #[must_use]
    pub const fn error_control_cob_id(self) -> u16 {
        cob_id::ERROR_CONTROL_BASE + self.0 as u16
    }

    /// Return the COB-ID the pre-defined connection set gives this node's
    /// PDO `number` (1..=4): TPDO n at 0x080 + n·0x100 + node-ID, RPDO n at
    /// 0x100 + n·0x100 + node-ID (CiA 301 §7.3.5 Table 72); `None` for any
    /// other number, which the set leaves unassigned.
    ///
    /// ```
    /// use motionwire_codec::canopen::{NodeId, PdoDirection};
    ///
    /// let node = NodeId::new(3).unwrap();
    /// assert_eq!(node.pdo_cob_id(PdoDirection::Transmit, 1), Some(0x183));
    /// assert_eq!(node.pdo_cob_id(PdoDirection::Receive, 4), Some(0x503));
    /// assert_eq!(node.pdo_cob_id(PdoDirection::Transmit, 5), None);
    /// ```
    #[inline]
    #[must_use]
    pub const fn pdo_cob_id(self, direction: PdoDirection, number: u16) -> Option<u16> {
        if number < 1 || number > 4 {
            return None;
        }
        let base = match direction {
            PdoDirection::Transmit => 0x080,
            PdoDirection::Receive => 0x100,
        };
        Some(base + number * 0x100 + self.0 as u16)
    }
}

impl TryFrom<u8> for NodeId {
    type Error = RangeError;

    fn try_from(raw: u8) -> Result<Self, RangeError> {
        Self::try_new(raw)
    }
}

impl From<NodeId> for u8 {
    fn from(node: NodeId) -> u8 {
        node.0
    }
}

impl fmt::Display for NodeId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

/// Base COB-IDs of the pre-defined connection set (CiA 301 Table 72).
pub mod cob_id {
    /// NMT node control, sent by the NMT master.
    pub const NMT: u16 = 0x000;
    /// SYNC.
    pub const SYNC: u16 = 0x080;
    /// EMCY base; the EMCY of node n is `EMCY_BASE + n`.
    pub const EMCY_BASE: u16 = 0x080;
    /// TIME stamp.
    pub const TIME: u16 = 0x100;
    /// SDO server → client (transmit) base.
    pub const SDO_TX_BASE: u16 = 0x580;
    /// SDO client → server (receive) base.
    pub const SDO_RX_BASE: u16 = 0x600;
    /// Error control (heartbeat, boot-up, node guarding) base.
    pub const ERROR_CONTROL_BASE: u16 = 0x700;
}

/// Which way a PDO goes, seen from the device that owns it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PdoDirection {
    /// TPDO: the device transmits (0x180, 0x280, 0x380, 0x480 + node-ID).
    Transmit,
    /// RPDO: the device receives (0x200, 0x300, 0x400, 0x500 + node-ID).
    Receive,
}

impl PdoDirection {
    /// Return the kind of PDO seen from its device, as the program writes it
    /// before the PDO's number (`TPDO1 Statusword=567`, docs/output.md#text):
    /// `"TPDO"` or `"RPDO"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            PdoDirection::Transmit => "TPDO",
            PdoDirection::Receive => "RPDO",
        }
    }
}

impl fmt::Display for PdoDirection {
    /// Format the direction as its [`PdoDirection::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The function an 11-bit CAN identifier has in the CANopen pre-defined
/// connection set (CiA 301 Table 72).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CobFunction {
    /// 0x000: NMT node control.
    NmtCommand,
    /// 0x080: SYNC.
    Sync,
    /// 0x081..=0x0FF: EMCY of a node.
    Emcy(NodeId),
    /// 0x100: TIME stamp.
    Time,
    /// 0x181..=0x57F: one of the four default PDOs of a node.
    Pdo {
        /// The node that owns the PDO.
        node: NodeId,
        /// The PDO number, 1..=4.
        number: u8,
        /// Transmit (TPDO) or receive (RPDO), seen from the node.
        direction: PdoDirection,
    },
    /// 0x581..=0x5FF: SDO response, server (node) → client.
    SdoTx(NodeId),
    /// 0x601..=0x67F: SDO request, client → server (node).
    SdoRx(NodeId),
    /// 0x701..=0x77F: error control (heartbeat, boot-up, node guarding).
    ErrorControl(NodeId),
    /// Any other identifier, including those with node-ID 0 inside a
    /// node-addressed range and everything above 0x7FF.
    Other,
}

impl CobFunction {
    /// Classify an 11-bit identifier (values above 0x7FF are [`CobFunction::Other`]).
    ///
    /// ```
    /// use motionwire_codec::canopen::{CobFunction, NodeId};
    ///
    /// assert_eq!(CobFunction::classify(0x081), CobFunction::Emcy(NodeId::new(1).unwrap()));
    /// assert_eq!(CobFunction::classify(0x080), CobFunction::Sync);
    /// assert_eq!(CobFunction::classify(0x705), CobFunction::ErrorControl(NodeId::new(5).unwrap()));
    /// assert_eq!(CobFunction::classify(0x700), CobFunction::Other);
    /// ```
    #[must_use]
    pub const fn classify(id: u16) -> CobFunction {
        if id > 0x7FF {
            return CobFunction::Other;
        }
        match id {
            cob_id::NMT => return CobFunction::NmtCommand,
            cob_id::SYNC => return CobFunction::Sync,
            cob_id::TIME => return CobFunction::Time,
            _ => {}
        }
        let node = match NodeId::new((id & 0x7F) as u8) {
            Some(node) => node,
            None => return CobFunction::Other,
        };
        match id & !0x7F {
            0x080 => CobFunction::Emcy(node),
            base @ 0x180..=0x500 => CobFunction::Pdo {
                node,
                // 0x180/0x200 → 1, 0x280/0x300 → 2, …
                number: (((base - 0x180) >> 8) + 1) as u8,
                direction: if base & 0x80 != 0 {
                    PdoDirection::Transmit
                } else {
                    PdoDirection::Receive
                },
            },
            cob_id::SDO_TX_BASE => CobFunction::SdoTx(node),
            cob_id::SDO_RX_BASE => CobFunction::SdoRx(node),
            cob_id::ERROR_CONTROL_BASE => CobFunction::ErrorControl(node),
            _ => CobFunction::Other,
        }
    }

    /// Return the node an identifier belongs to, if its function is node-addressed.
    #[must_use]
    pub const fn node(self) -> Option<NodeId> {
        match self {
            CobFunction::Emcy(n)
            | CobFunction::SdoTx(n)
            | CobFunction::SdoRx(n)
            | CobFunction::ErrorControl(n)
            | CobFunction::Pdo { node: n, .. } => Some(n),
            CobFunction::NmtCommand
            | CobFunction::Sync
            | CobFunction::Time
            | CobFunction::Other => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pdo_directions_are_named_as_the_program_writes_them() {
        assert_eq!(PdoDirection::Transmit.to_string(), "TPDO");
        assert_eq!(PdoDirection::Receive.to_string(), "RPDO");
    }

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    #[test]
    fn node_id_range() {
        for raw in 0..=255u8 {
            let valid = (1..=127).contains(&raw);
            assert_eq!(NodeId::new(raw).is_some(), valid, "{raw}");
            match NodeId::try_new(raw) {
                Ok(id) => assert_eq!(id.get(), raw),
                Err(e) => assert_eq!(
                    e,
                    RangeError {
                        what: What::NodeId,
                        found: raw as u32,
                        min: 1,
                        max: 127
                    }
                ),
            }
        }
        assert_eq!(NodeId::all().count(), 127);
        assert_eq!(NodeId::all().next(), Some(NodeId::MIN));
        assert_eq!(NodeId::all().last(), Some(NodeId::MAX));
        assert_eq!(NodeId::MAX.index(), 126);
    }

    #[test]
    fn cob_ids() {
        assert_eq!(n(1).emcy_cob_id(), 0x081);
        assert_eq!(n(127).emcy_cob_id(), 0x0FF);
        assert_eq!(n(1).error_control_cob_id(), 0x701);
        assert_eq!(n(127).error_control_cob_id(), 0x77F);
    }

    #[test]
    fn classify_predefined_connection_set() {
        use CobFunction::*;
        use PdoDirection::*;
        let table: &[(u16, CobFunction)] = &[
            (0x000, NmtCommand),
            (0x001, Other),
            (0x07F, Other),
            (0x080, Sync),
            (0x081, Emcy(n(1))),
            (0x0FF, Emcy(n(127))),
            (0x100, Time),
            (0x101, Other),
            (0x180, Other),
            (
                0x181,
                Pdo {
                    node: n(1),
                    number: 1,
                    direction: Transmit,
                },
            ),
            (
                0x201,
                Pdo {
                    node: n(1),
                    number: 1,
                    direction: Receive,
                },
            ),
            (
                0x285,
                Pdo {
                    node: n(5),
                    number: 2,
                    direction: Transmit,
                },
            ),
            (
                0x305,
                Pdo {
                    node: n(5),
                    number: 2,
                    direction: Receive,
                },
            ),
            (
                0x3FF,
                Pdo {
                    node: n(127),
                    number: 3,
                    direction: Transmit,
                },
            ),
            (
                0x401,
                Pdo {
                    node: n(1),
                    number: 3,
                    direction: Receive,
                },
            ),
            (
                0x4A0,
                Pdo {
                    node: n(0x20),
                    number: 4,
                    direction: Transmit,
                },
            ),
            (
                0x57F,
                Pdo {
                    node: n(127),
                    number: 4,
                    direction: Receive,
                },
            ),
            (0x580, Other),
            (0x581, SdoTx(n(1))),
            (0x5FF, SdoTx(n(127))),
            (0x601, SdoRx(n(1))),
            (0x67F, SdoRx(n(127))),
            (0x680, Other),
            (0x6FF, Other),
            (0x700, Other),
            (0x701, ErrorControl(n(1))),
            (0x77F, ErrorControl(n(127))),
            (0x780, Other),
            (0x7E5, Other),
            (0x7FF, Other),
            (0x800, Other),
            (0xFFFF, Other),
        ];
        for &(id, expected) in table {
            assert_eq!(CobFunction::classify(id), expected, "{id:#x}");
        }
    }

    #[test]
    fn classify_every_identifier_agrees_with_node() {
        for id in 0..=0x7FFu16 {
            let f = CobFunction::classify(id);
            if let Some(node) = f.node() {
                assert_eq!(u16::from(node.get()), id & 0x7F);
            }
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::canopen::node_id;

    proptest! {
        #[test]
        fn cob_ids_classify_back_to_their_node(node in node_id()) {
            prop_assert_eq!(CobFunction::classify(node.emcy_cob_id()), CobFunction::Emcy(node));
            prop_assert_eq!(
                CobFunction::classify(node.error_control_cob_id()),
                CobFunction::ErrorControl(node)
            );
            prop_assert_eq!(NodeId::try_from(node.get()), Ok(node));
        }
    }
}
