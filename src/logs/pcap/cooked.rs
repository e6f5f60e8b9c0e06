//! Linux "cooked" captures (docs/formats.md#pcap): what `tcpdump -i any`, and
//! Wireshark or dumpcap on a CAN interface in some setups, write — link
//! type 113 (`LINKTYPE_LINUX_SLL`) or 276 (`LINKTYPE_LINUX_SLL2`): a header
//! that says the packet's protocol, then the packet as the kernel handed
//! it to the capture (tcpdump.org's link-type pages; Wireshark's
//! `packet-sll.c`).
//!
//! ```text
//! SLL (16 bytes, big-endian)        SLL2 (20 bytes, big-endian)
//! 0..2    packet type               0..2    protocol type
//! 2..4    ARPHRD type (280: CAN)    2..4    reserved
//! 4..6    address length            4..8    interface index
//! 6..14   address                   8..10   ARPHRD type
//! 14..16  protocol type             10      packet type
//!                                   11      address length
//!                                   12..20  address
//! ```
//!
//! Protocol 0x000C (`ETH_P_CAN`) carries a `struct can_frame`, 0x000D
//! (`ETH_P_CANFD`) a `struct canfd_frame`, both in the capturing machine's
//! byte order (read little-endian, as tshark does: the decision in
//! docs/formats.md#pcap); 0x000E (`ETH_P_CANXL`) a CAN XL frame, which is
//! counted, never misread.

use crate::logs::BinaryError;

use super::not_can::NotCan;
use super::socketcan::FrameLayout;

/// `LINKTYPE_LINUX_SLL`: Linux cooked capture, version 1
/// (docs/formats.md#pcap).
pub const LINKTYPE_LINUX_SLL: u16 = 113;
/// `LINKTYPE_LINUX_SLL2`: Linux cooked capture, version 2
/// (docs/formats.md#pcap).
pub const LINKTYPE_LINUX_SLL2: u16 = 276;

/// The header fields this reader reads.
mod field {
    /// A byte range of a header.
    pub(super) type Field = core::ops::Range<usize>;
    /// SLL: the protocol type, last field of the header.
    pub(super) const SLL_PROTOCOL: Field = 14..16;
    /// SLL2: the protocol type, first field of the header.
    pub(super) const SLL2_PROTOCOL: Field = 0..2;
    /// SLL2: the interface index of the interface the packet went
    /// through (`sll.ifindex` in tshark).
    pub(super) const SLL2_IFINDEX: Field = 4..8;
    /// SLL2: the address, last field of the header.
    pub(super) const SLL2_ADDRESS: Field = 12..20;
}

/// The SLL header's length.
const SLL_HEADER_LEN: usize = field::SLL_PROTOCOL.end;
/// The SLL2 header's length.
const SLL2_HEADER_LEN: usize = field::SLL2_ADDRESS.end;

/// `ETH_P_CAN`: a classic CAN frame follows (`linux/if_ether.h`).
const ETH_P_CAN: u16 = 0x000C;
/// `ETH_P_CANFD`: a CAN FD frame follows.
const ETH_P_CANFD: u16 = 0x000D;
/// `ETH_P_CANXL`: a CAN XL frame follows.
const ETH_P_CANXL: u16 = 0x000E;

/// What a cooked packet holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Cooked {
    /// A SocketCAN frame at this offset in the packet, laid out so.
    Can {
        /// Where the frame starts: after the header.
        at: usize,
        /// How the frame is laid out.
        layout: FrameLayout,
        /// SLL2: the capturing machine's index of the interface the frame
        /// went through (`tcpdump -i any` captures every bus into one
        /// file); `None` for SLL, which does not record it.
        ifindex: Option<u32>,
    },
    /// A packet of an Ethernet interface (protocol 0x0600 or above, an
    /// EtherType) after the header at `at`: EtherCAT when the protocol is
    /// 0x88A4 (docs/ethercat.md#reading), else counted.
    Ethernet {
        /// Where the packet's payload starts: after the header.
        at: usize,
        /// The protocol, an EtherType.
        protocol: u16,
    },
    /// No CAN or CAN FD frame: counted as this kind.
    Other(NotCan),
}

/// Read the cooked header of a packet of `link_type` (113 or 276).
///
/// # Errors
///
/// The packet is shorter than its header
/// ([`BinaryError::SocketCanTooShort`]).
pub(super) fn split(link_type: u16, packet: &[u8]) -> Result<Cooked, BinaryError> {
    let (header_len, protocol) = if link_type == LINKTYPE_LINUX_SLL2 {
        (SLL2_HEADER_LEN, field::SLL2_PROTOCOL)
    } else {
        (SLL_HEADER_LEN, field::SLL_PROTOCOL)
    };
    let Some(protocol) = packet
        .get(protocol)
        .and_then(|b| b.first_chunk::<2>())
        .map(|b| u16::from_be_bytes(*b))
        .filter(|_| packet.len() >= header_len)
    else {
        return Err(BinaryError::SocketCanTooShort {
            needed: header_len as u64,
            found: packet.len() as u64,
        });
    };
    let ifindex = (link_type == LINKTYPE_LINUX_SLL2)
        .then(|| packet.get(field::SLL2_IFINDEX)?.first_chunk::<4>().copied())
        .flatten()
        .map(u32::from_be_bytes);
    Ok(match protocol {
        ETH_P_CAN | ETH_P_CANFD => Cooked::Can {
            at: header_len,
            layout: FrameLayout::Cooked {
                fd: protocol == ETH_P_CANFD,
            },
            ifindex,
        },
        ETH_P_CANXL => Cooked::Other(NotCan::CanXl),
        crate::ethercat::ETHERTYPE_ETHERCAT => Cooked::Ethernet {
            at: header_len,
            protocol,
        },
        protocol => Cooked::Other(NotCan::CookedProtocol {
            link_type,
            protocol,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An SLL header for `protocol`, then `rest`.
    fn sll(protocol: u16, rest: &[u8]) -> Vec<u8> {
        let mut p = vec![0, 0, 0x01, 0x18, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0];
        p.extend(protocol.to_be_bytes());
        p.extend(rest);
        p
    }

    /// An SLL2 header for `protocol`, interface 3, then `rest`.
    fn sll2(protocol: u16, rest: &[u8]) -> Vec<u8> {
        let mut p = protocol.to_be_bytes().to_vec();
        p.extend([0, 0, 0, 0, 0, 3, 0x01, 0x18, 4, 0]);
        p.extend([0; 8]);
        p.extend(rest);
        p
    }

    #[test]
    fn can_and_can_fd_follow_their_header() {
        let classic = Cooked::Can {
            at: 16,
            layout: FrameLayout::Cooked { fd: false },
            ifindex: None,
        };
        assert_eq!(split(LINKTYPE_LINUX_SLL, &sll(0x000C, &[])), Ok(classic));
        let fd = Cooked::Can {
            at: 20,
            layout: FrameLayout::Cooked { fd: true },
            ifindex: Some(3),
        };
        assert_eq!(split(LINKTYPE_LINUX_SLL2, &sll2(0x000D, &[1])), Ok(fd));
    }

    #[test]
    fn other_protocols_are_counted_by_kind() {
        assert_eq!(
            split(LINKTYPE_LINUX_SLL, &sll(0x0800, &[0x45])),
            Ok(Cooked::Other(NotCan::CookedProtocol {
                link_type: 113,
                protocol: 0x0800
            }))
        );
        assert_eq!(
            split(LINKTYPE_LINUX_SLL2, &sll2(0x000E, &[])),
            Ok(Cooked::Other(NotCan::CanXl))
        );
    }

    #[test]
    fn a_packet_shorter_than_its_header() {
        for (link_type, len) in [(LINKTYPE_LINUX_SLL, 16), (LINKTYPE_LINUX_SLL2, 20)] {
            for cut in 0..len {
                assert_eq!(
                    split(link_type, &vec![0; cut]),
                    Err(BinaryError::SocketCanTooShort {
                        needed: len as u64,
                        found: cut as u64
                    }),
                    "{link_type} cut at {cut}"
                );
            }
        }
    }
}
