//! Packets of an Ethernet port (docs/ethercat.md#reading): link type 1, and
//! Linux cooked captures of an Ethernet interface whose protocol is
//! EtherCAT's EtherType. What carries EtherCAT becomes an event; every
//! other packet is counted by its EtherType.

use crate::ethercat::{Encapsulation, EthercatLink, Link, Mac, ETHERTYPE_ETHERCAT};
use crate::logs::BinaryError;

use super::cooked::{LINKTYPE_LINUX_SLL, LINKTYPE_LINUX_SLL2};
use super::not_can::NotCan;

/// `LINKTYPE_ETHERNET`: IEEE 802.3 Ethernet (docs/ethercat.md#reading).
pub const LINKTYPE_ETHERNET: u16 = 1;

/// What an Ethernet packet holds, with offsets into the packet (so that
/// the reader can lend the bytes after it has moved past the record).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Ethernet {
    /// EtherCAT, from this offset to the end of the packet.
    Ethercat {
        /// Where the EtherCAT header starts.
        at: usize,
        /// The destination MAC, where the header records it.
        destination: Option<Mac>,
        /// The source MAC.
        source: Mac,
        /// How the payload was carried.
        encapsulation: Encapsulation,
        /// SLL2: the capturing machine's interface index.
        ifindex: Option<u32>,
    },
    /// Something else, counted as this kind.
    Other(NotCan),
}

impl Ethernet {
    /// Return the link the packet `data` holds at `at`.
    pub(super) fn link<'a>(self, payload: &'a [u8]) -> Option<EthercatLink<'a>> {
        match self {
            Ethernet::Ethercat {
                destination,
                source,
                encapsulation,
                ..
            } => Some(EthercatLink {
                destination,
                source,
                encapsulation,
                payload,
            }),
            Ethernet::Other(_) => None,
        }
    }
}

/// Read an Ethernet frame (link type 1).
///
/// # Errors
///
/// [`BinaryError::EthernetTooShort`] when the frame is shorter than a
/// header it announces: the packet is skipped, the capture read on.
pub(super) fn split(packet: &[u8]) -> Result<Ethernet, BinaryError> {
    match Link::parse(packet) {
        Ok(Link::Ethercat(link)) => Ok(Ethernet::Ethercat {
            at: packet.len() - link.payload.len(),
            destination: link.destination,
            source: link.source,
            encapsulation: link.encapsulation,
            ifindex: None,
        }),
        Ok(Link::Other { ether_type, .. }) => Ok(Ethernet::Other(NotCan::EtherType(ether_type))),
        Err(error) => Err(BinaryError::EthernetTooShort(error)),
    }
}

/// Read a Linux cooked packet whose protocol is EtherCAT's EtherType
/// (`tcpdump -i any` on a master's machine): the source MAC is the
/// header's address when it is 6 bytes long; `None` for another protocol.
pub(super) fn cooked(link_type: u16, packet: &[u8], protocol: u16, at: usize) -> Option<Ethernet> {
    if protocol != ETHERTYPE_ETHERCAT {
        return None;
    }
    // SLL: address length at 4..6, address at 6..14; SLL2: the length at
    // 11, the address at 12..20, the interface index at 4..8.
    let (length, address, ifindex) = if link_type == LINKTYPE_LINUX_SLL2 {
        (
            usize::from(*packet.get(11)?),
            packet.get(12..18)?,
            packet
                .get(4..8)
                .and_then(|b| b.first_chunk::<4>())
                .map(|b| u32::from_be_bytes(*b)),
        )
    } else {
        debug_assert_eq!(link_type, LINKTYPE_LINUX_SLL);
        let length = packet.get(4..6)?;
        (
            usize::from(u16::from_be_bytes([length[0], length[1]])),
            packet.get(6..12)?,
            None,
        )
    };
    let mut source = [0; 6];
    if length == 6 {
        source.copy_from_slice(address);
    }
    Some(Ethernet::Ethercat {
        at,
        destination: None,
        source: Mac(source),
        encapsulation: Encapsulation::Ethernet,
        ifindex,
    })
}
