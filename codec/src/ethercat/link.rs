//! An Ethernet frame unwrapped to its EtherCAT payload: [`Link`].

use core::fmt;

use crate::error::check_len;
use crate::{LenError, What};

/// The EtherType of EtherCAT (ETG.1000.4 §5.3.2).
pub const ETHERTYPE_ETHERCAT: u16 = 0x88A4;
/// The UDP port of EtherCAT in UDP/IP (ETG.1000.4 §5.3.3): 0x88A4, 34980.
pub const UDP_PORT_ETHERCAT: u16 = 0x88A4;

/// The EtherType of an 802.1Q tag.
const ETHERTYPE_VLAN: u16 = 0x8100;
/// The EtherType of IPv4.
const ETHERTYPE_IPV4: u16 = 0x0800;
/// IP protocol number of UDP.
const IP_PROTOCOL_UDP: u8 = 17;
/// Destination and source MAC, EtherType.
const ETHERNET_HEADER_LEN: usize = 14;
/// Tag control information and the inner EtherType.
const VLAN_TAG_LEN: usize = 4;
/// The shortest IPv4 header.
const IPV4_MIN_LEN: usize = 20;
/// Source and destination port, length and checksum.
const UDP_HEADER_LEN: usize = 8;

/// A MAC address, written `10:10:10:10:10:10`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Mac(pub [u8; 6]);

impl Mac {
    /// The bit every EtherCAT slave controller sets in the first byte of the
    /// source MAC of every frame it forwards (bit 1, 0x02; Beckhoff's ESC
    /// datasheet, section I, "Frame processing"): the frame came back
    /// through the slaves.
    pub const RETURNED_BIT: u8 = 0x02;

    /// Return whether the returned bit is set.
    #[inline]
    #[must_use]
    pub const fn returned_bit(self) -> bool {
        self.0[0] & Self::RETURNED_BIT != 0
    }

    /// Return the address with the returned bit cleared: the same for a
    /// frame as sent and as it came back.
    #[inline]
    #[must_use]
    pub const fn without_returned_bit(self) -> Mac {
        let mut bytes = self.0;
        bytes[0] &= !Self::RETURNED_BIT;
        Mac(bytes)
    }
}

impl fmt::Display for Mac {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [a, b, c, d, e, g] = self.0;
        write!(f, "{a:02x}:{b:02x}:{c:02x}:{d:02x}:{e:02x}:{g:02x}")
    }
}

/// How an EtherCAT payload was carried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Encapsulation {
    /// Directly in Ethernet, EtherType 0x88A4.
    Ethernet,
    /// In Ethernet behind one 802.1Q tag, with its VLAN identifier.
    Vlan(u16),
    /// In UDP to port 0x88A4 over IPv4.
    Udp,
}

/// An EtherCAT payload found in an Ethernet frame: who sent the frame,
/// how the payload was carried, and the payload from the EtherCAT header
/// on (with any Ethernet padding after it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EthercatLink<'a> {
    /// The destination MAC (EtherCAT masters send to broadcast or to
    /// themselves; slaves do not look at it); `None` in a Linux cooked
    /// capture, whose header records only the source.
    pub destination: Option<Mac>,
    /// The source MAC: the master's, with [`Mac::RETURNED_BIT`] set once
    /// the frame has passed a slave.
    pub source: Mac,
    /// How the payload was carried.
    pub encapsulation: Encapsulation,
    /// The bytes from the EtherCAT header to the end of the packet.
    pub payload: &'a [u8],
}

impl EthercatLink<'_> {
    /// Return whether the frame came back through the slaves (the source
    /// MAC's bit 0x02; docs/ethercat.md#direction).
    #[inline]
    #[must_use]
    pub const fn returned_bit(&self) -> bool {
        self.source.returned_bit()
    }
}

/// An Ethernet frame as captured (link type 1, without its frame check
/// sequence), read as far as needed to tell whether it carries EtherCAT.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Link<'a> {
    /// The frame carries EtherCAT.
    Ethercat(EthercatLink<'a>),
    /// The frame carries something else, named by its EtherType (the
    /// inner one behind a tag; 0x0800 for IPv4 that is not EtherCAT in
    /// UDP). A value below 0x0600 is an 802.3 length, not a type.
    Other {
        /// The source MAC, so that a session can count a frame that passed
        /// the slaves once.
        source: Mac,
        /// The EtherType.
        ether_type: u16,
    },
}

impl<'a> Link<'a> {
    /// Read an Ethernet frame (destination, source, EtherType; one 802.1Q
    /// tag; IPv4 and UDP for EtherCAT in UDP).
    ///
    /// # Errors
    ///
    /// [`LenError`] when the frame is shorter than the headers it announces
    /// (Ethernet, tag, IPv4 header length, UDP).
    pub fn parse(packet: &'a [u8]) -> Result<Self, LenError> {
        check_len(What::EthernetFrame, packet, ETHERNET_HEADER_LEN)?;
        let destination = Mac(mac_at(packet, 0));
        let source = Mac(mac_at(packet, 6));
        let mut ether_type = be16(packet, 12);
        let mut rest = &packet[ETHERNET_HEADER_LEN..];
        let mut encapsulation = Encapsulation::Ethernet;
        if ether_type == ETHERTYPE_VLAN {
            check_len(
                What::EthernetFrame,
                packet,
                ETHERNET_HEADER_LEN + VLAN_TAG_LEN,
            )?;
            encapsulation = Encapsulation::Vlan(be16(rest, 0) & 0x0FFF);
            ether_type = be16(rest, 2);
            rest = &rest[VLAN_TAG_LEN..];
        }
        let payload = match ether_type {
            ETHERTYPE_ETHERCAT => rest,
            ETHERTYPE_IPV4 => match udp_payload(rest)? {
                Some(payload) => {
                    encapsulation = Encapsulation::Udp;
                    payload
                }
                None => return Ok(Link::Other { source, ether_type }),
            },
            _ => return Ok(Link::Other { source, ether_type }),
        };
        Ok(Link::Ethercat(EthercatLink {
            destination: Some(destination),
            source,
            encapsulation,
            payload,
        }))
    }
}

/// Return the UDP payload of an IPv4 packet sent to port 0x88A4, or `None`
/// when the packet is not UDP to that port (or is a later fragment).
fn udp_payload(ip: &[u8]) -> Result<Option<&[u8]>, LenError> {
    check_len(What::Ipv4Header, ip, IPV4_MIN_LEN)?;
    let header_len = usize::from(ip[0] & 0x0F) * 4;
    let fragment_offset = be16(ip, 6) & 0x1FFF;
    if ip[0] >> 4 != 4 || ip[9] != IP_PROTOCOL_UDP || fragment_offset != 0 {
        return Ok(None);
    }
    check_len(What::Ipv4Header, ip, header_len.max(IPV4_MIN_LEN))?;
    let udp = &ip[header_len.max(IPV4_MIN_LEN)..];
    check_len(What::UdpHeader, udp, UDP_HEADER_LEN)?;
    if be16(udp, 2) != UDP_PORT_ETHERCAT {
        return Ok(None);
    }
    Ok(Some(&udp[UDP_HEADER_LEN..]))
}

/// Read a big-endian `u16` at `at` (the caller checked the length).
#[inline]
fn be16(bytes: &[u8], at: usize) -> u16 {
    u16::from_be_bytes([bytes[at], bytes[at + 1]])
}

/// Read six bytes at `at` (the caller checked the length).
#[inline]
fn mac_at(bytes: &[u8], at: usize) -> [u8; 6] {
    let mut mac = [0; 6];
    mac.copy_from_slice(&bytes[at..at + 6]);
    mac
}
