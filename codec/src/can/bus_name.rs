//! A bus as a log names it, owned: the [`Iface`] of a frame, or none
//! (docs/formats.md#interfaces: a node's identity is its interface and its
//! node-ID), kept beyond the log's buffer.

use alloc::borrow::ToOwned;
use alloc::string::String;
use core::fmt;

use super::Iface;

/// A bus as a log names it, owned: an interface name, a channel number, or
/// nothing for a log that names no interface — the owned form of a frame's
/// `Option<Iface>`, for what outlives the log's buffer (the decoder's and
/// the summary's buses). Ordered as the summary lists buses: frames
/// without an interface first, then channels, then names.
///
/// `Display` writes the name, the channel number, or `-` for a log that
/// names no interface (the text summary's column).
///
/// ```
/// use motionwire_codec::can::{BusName, Iface};
///
/// let can0 = BusName::of(Some(Iface::Name("can0")));
/// assert!(can0.is(Some(Iface::Name("can0"))));
/// assert!(!can0.is(Some(Iface::Channel(1))));
/// assert_eq!(can0.iface(), Some(Iface::Name("can0")));
/// assert_eq!(can0.to_string(), "can0");
/// assert_eq!(BusName::of(None).to_string(), "-");
/// assert!(BusName::of(None) < BusName::Channel(1));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
// A tag of its own: `is` runs for every frame of a log, and reads the kind
// of bus with one compare instead of from the name's capacity.
#[repr(u8)]
pub enum BusName {
    /// The log names no interface (pcap, TRC without a bus column).
    Unnamed,
    /// A channel number (Vector ASC and BLF, PEAK TRC).
    Channel(u16),
    /// An interface name (candump, pcapng).
    Name(String),
}

impl BusName {
    /// Return the bus of a frame's interface.
    #[must_use]
    pub fn of(iface: Option<Iface<'_>>) -> Self {
        match iface {
            None => BusName::Unnamed,
            Some(Iface::Channel(n)) => BusName::Channel(n),
            Some(Iface::Name(name)) => BusName::Name(name.to_owned()),
        }
    }

    /// Return whether a frame seen on `iface` is on this bus.
    #[inline]
    #[must_use]
    pub fn is(&self, iface: Option<Iface<'_>>) -> bool {
        match (self, iface) {
            (BusName::Unnamed, None) => true,
            (BusName::Channel(a), Some(Iface::Channel(b))) => *a == b,
            (BusName::Name(a), Some(name @ Iface::Name(_))) => name.is_name(a.as_bytes()),
            _ => false,
        }
    }

    /// Return the interface as a frame holds it (`iface` in
    /// docs/output.md#common-keys): the name, the channel, or `None`.
    #[must_use]
    pub fn iface(&self) -> Option<Iface<'_>> {
        match self {
            BusName::Unnamed => None,
            BusName::Channel(n) => Some(Iface::Channel(*n)),
            BusName::Name(name) => Some(Iface::Name(name)),
        }
    }
}

impl fmt::Display for BusName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BusName::Unnamed => f.write_str("-"),
            BusName::Channel(n) => write!(f, "{n}"),
            BusName::Name(name) => f.write_str(name),
        }
    }
}
