//! What the reading loop hands on for a packet that holds no CAN frame:
//! [`NotCan`].

use crate::logs::OtherRecord;

/// A packet that holds no CAN frame, as the reading loop hands it on: the
/// kinds of [`OtherRecord`] a pcap has, `Copy` so that the loop's results
/// carry nothing to drop; made an [`OtherRecord`] where it is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum NotCan {
    /// [`OtherRecord::LinkType`].
    LinkType(u16),
    /// [`OtherRecord::CookedProtocol`].
    CookedProtocol { link_type: u16, protocol: u16 },
    /// [`OtherRecord::CanXl`].
    CanXl,
    /// [`OtherRecord::SystemdJournal`].
    SystemdJournal,
    /// [`OtherRecord::EtherType`].
    EtherType(u16),
}

impl From<NotCan> for OtherRecord {
    fn from(kind: NotCan) -> Self {
        match kind {
            NotCan::LinkType(link_type) => OtherRecord::LinkType(link_type),
            NotCan::CookedProtocol {
                link_type,
                protocol,
            } => OtherRecord::CookedProtocol {
                link_type,
                protocol,
            },
            NotCan::CanXl => OtherRecord::CanXl,
            NotCan::SystemdJournal => OtherRecord::SystemdJournal,
            NotCan::EtherType(ether_type) => OtherRecord::EtherType(ether_type),
        }
    }
}
