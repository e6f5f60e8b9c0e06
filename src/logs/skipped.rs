//! The records a binary reader skips because they hold no CAN frame or bus
//! event, by kind (docs/formats.md#pcap, docs/formats.md#blf,
//! docs/formats.md#mf4): said once per kind with its count — "12 packets of
//! link type 1 (Ethernet) skipped: not CAN" — never per record.

use core::fmt;

/// A kind of record that holds no CAN frame or bus event: more may come
/// with more formats.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum OtherRecord {
    /// A pcap or pcapng packet of a link type that carries no CAN frames
    /// (docs/formats.md#pcap; the link type as the tcpdump.org link-type list
    /// numbers it).
    LinkType(u16),
    /// A packet of a Linux "cooked" capture (link type 113 or 276) whose
    /// protocol is neither CAN (0x000C) nor CAN FD (0x000D)
    /// (docs/formats.md#pcap).
    CookedProtocol {
        /// The link type: 113 (`LINUX_SLL`) or 276 (`LINUX_SLL2`).
        link_type: u16,
        /// The protocol type, an Ethernet type or Linux's `ETH_P_*`.
        protocol: u16,
    },
    /// An Ethernet packet that carries no EtherCAT, by its EtherType (the
    /// inner one behind an 802.1Q tag; docs/ethercat.md#reading).
    EtherType(u16),
    /// A CAN XL frame, which [`CanFrame`](crate::can::CanFrame) cannot
    /// hold: counted, never misread.
    CanXl,
    /// A pcapng systemd journal export block: numbered as a packet, as
    /// tshark numbers it.
    SystemdJournal,
    /// A BLF object of a type that holds no frame (docs/formats.md#blf).
    BlfObject(u32),
    /// A record of an MF4 channel group that holds no CAN frame (`LIN_Frame`,
    /// `CAN_OverloadFrame`, a signal group), by the group's name
    /// (docs/formats.md#mf4).
    #[cfg(feature = "mf4")]
    Mf4Group(String),
}

impl OtherRecord {
    /// Return the name of a pcap link type, where it is a common one
    /// (tcpdump.org's list of link-layer header types).
    #[must_use]
    pub const fn link_type_name(link_type: u16) -> Option<&'static str> {
        Some(match link_type {
            0 => "BSD loopback",
            1 => "Ethernet",
            101 => "raw IP",
            105 => "IEEE 802.11",
            113 => "Linux cooked v1",
            127 => "IEEE 802.11 radiotap",
            201 => "Bluetooth HCI H4",
            220 => "Linux USB",
            227 => "SocketCAN",
            228 => "IPv4",
            229 => "IPv6",
            253 => "Linux netlink",
            276 => "Linux cooked v2",
            _ => return None,
        })
    }

    /// Return the name of an EtherType, where it is a common one on a
    /// machine's network (IEEE's EtherType list).
    #[must_use]
    pub const fn ether_type_name(ether_type: u16) -> Option<&'static str> {
        Some(match ether_type {
            0x0800 => "IPv4",
            0x0806 => "ARP",
            0x86DD => "IPv6",
            0x88A4 => "EtherCAT",
            0x88AB => "Ethernet POWERLINK",
            0x88CC => "LLDP",
            0x88F7 => "PTP",
            0x8892 => "PROFINET",
            _ => return None,
        })
    }

    /// The noun for one record of this kind.
    const fn noun(&self) -> &'static str {
        match self {
            OtherRecord::LinkType(_)
            | OtherRecord::CookedProtocol { .. }
            | OtherRecord::EtherType(_) => "packet",
            OtherRecord::CanXl => "CAN XL frame",
            OtherRecord::SystemdJournal => "systemd journal export block",
            OtherRecord::BlfObject(_) => "BLF object",
            #[cfg(feature = "mf4")]
            OtherRecord::Mf4Group(_) => "MF4 record",
        }
    }
}

/// Writes ` of link type 1 (Ethernet)`.
fn link_type(f: &mut fmt::Formatter<'_>, link_type: u16) -> fmt::Result {
    write!(f, " of link type {link_type}")?;
    match OtherRecord::link_type_name(link_type) {
        Some(name) => write!(f, " ({name})"),
        None => Ok(()),
    }
}

/// How many records of one kind a reader skipped.
///
/// `Display` says it as the program does (docs/formats.md#pcap):
///
/// ```
/// use motionwire::logs::{OtherRecord, OtherRecords};
///
/// let ethernet = OtherRecords { kind: OtherRecord::LinkType(1), count: 12 };
/// assert_eq!(ethernet.to_string(), "12 packets of link type 1 (Ethernet) skipped: not CAN");
/// let ip = OtherRecords {
///     kind: OtherRecord::CookedProtocol { link_type: 113, protocol: 0x0800 },
///     count: 1,
/// };
/// assert_eq!(
///     ip.to_string(),
///     "1 packet of link type 113 (Linux cooked v1) with protocol 0x0800 skipped: not CAN"
/// );
/// # #[cfg(feature = "mf4")] {
/// let lin = OtherRecords { kind: OtherRecord::Mf4Group("LIN_Frame".into()), count: 3 };
/// assert_eq!(lin.to_string(), "3 MF4 records of group LIN_Frame skipped: not CAN");
/// # }
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct OtherRecords {
    /// The kind.
    pub kind: OtherRecord,
    /// How many.
    pub count: u64,
}

impl fmt::Display for OtherRecords {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = if self.count == 1 { "" } else { "s" };
        write!(f, "{} {}{s}", self.count, self.kind.noun())?;
        match &self.kind {
            OtherRecord::LinkType(t) => link_type(f, *t)?,
            OtherRecord::CookedProtocol {
                link_type: t,
                protocol,
            } => {
                link_type(f, *t)?;
                write!(f, " with protocol {protocol:#06x}")?;
            }
            OtherRecord::BlfObject(t) => write!(f, " of type {t}")?,
            OtherRecord::EtherType(t) => {
                write!(f, " of EtherType {t:#06x}")?;
                if let Some(name) = OtherRecord::ether_type_name(*t) {
                    write!(f, " ({name})")?;
                }
            }
            // The name is the file's: control characters are escaped, so
            // that it cannot break the line it is said on.
            #[cfg(feature = "mf4")]
            OtherRecord::Mf4Group(name) => write!(f, " of group {}", name.escape_debug())?,
            OtherRecord::CanXl | OtherRecord::SystemdJournal => {}
        }
        f.write_str(match self.kind {
            OtherRecord::CanXl => " skipped: not read",
            OtherRecord::EtherType(_) => " skipped: neither CAN nor EtherCAT",
            _ => " skipped: not CAN",
        })
    }
}

/// The counts of a reader's skipped records, kind by kind in the order
/// first met (a handful of kinds at most: a linear search): what the
/// binary readers keep.
#[cfg(any(feature = "pcap", feature = "blf"))]
#[derive(Debug, Clone, Default)]
pub(crate) struct OtherCounts {
    counts: Vec<OtherRecords>,
    total: u64,
}

#[cfg(any(feature = "pcap", feature = "blf"))]
impl OtherCounts {
    /// Count one record of `kind`: out of the readers' loops, which read
    /// frames.
    #[cold]
    #[inline(never)]
    pub(crate) fn add(&mut self, kind: OtherRecord) {
        self.total = self.total.saturating_add(1);
        match self.counts.iter_mut().find(|c| c.kind == kind) {
            Some(c) => c.count = c.count.saturating_add(1),
            None => self.counts.push(OtherRecords { kind, count: 1 }),
        }
    }

    /// Every record counted.
    pub(crate) const fn total(&self) -> u64 {
        self.total
    }

    /// The counts by kind.
    pub(crate) fn by_kind(&self) -> &[OtherRecords] {
        &self.counts
    }
}
