//! Which bus a frame was seen on, kept beyond the log's buffer
//! (docs/formats.md#interfaces: a node's identity is its interface and its
//! node-ID).

use core::fmt;

use crate::can::Iface;
use crate::canopen::NodeId;

/// An interface as the decoder and the summary keep it: owned, because
/// what they learn outlives the log's buffer. Ordered as the summary lists
/// buses: frames without an interface first, then channels, then names.
///
/// `Display` writes the name, the channel number, or `-` for a log that
/// names no interface (the text summary's column).
///
/// ```
/// use motionwire::can::Iface;
/// use motionwire::decoder::BusName;
///
/// let can0 = BusName::of(Some(Iface::Name("can0")));
/// assert!(can0.is(Some(Iface::Name("can0"))));
/// assert!(!can0.is(Some(Iface::Channel(1))));
/// assert_eq!(can0.to_string(), "can0");
/// assert_eq!(BusName::of(None).to_string(), "-");
/// assert!(BusName::of(None) < BusName::Channel(1));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
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
            (BusName::Name(a), Some(Iface::Name(b))) => {
                crate::iface::same_name(a.as_bytes(), b.as_bytes())
            }
            _ => false,
        }
    }

    /// Return the interface as `iface` holds it (docs/output.md#common-keys):
    /// the name, the channel as decimal text, or `None`.
    #[must_use]
    pub fn iface(&self) -> Option<Iface<'_>> {
        match self {
            BusName::Unnamed => None,
            BusName::Channel(n) => Some(Iface::Channel(*n)),
            BusName::Name(name) => Some(Iface::Name(name)),
        }
    }
}

impl BusName {
    /// Return the device `node` on this bus as the summary's findings and
    /// the report name it: `can0 node 3`, or `node 3` on a log that names
    /// no interface.
    ///
    /// ```
    /// use motionwire::canopen::NodeId;
    /// use motionwire::decoder::BusName;
    ///
    /// let node = NodeId::new(3).unwrap();
    /// assert_eq!(BusName::Name("can0".into()).device(node).to_string(), "can0 node 3");
    /// assert_eq!(BusName::Unnamed.device(node).to_string(), "node 3");
    /// ```
    #[must_use]
    pub fn device(&self, node: NodeId) -> Device<'_> {
        Device { bus: self, node }
    }
}

/// A device, named by its bus and node-ID ([`BusName::device`]).
#[derive(Debug, Clone, Copy)]
pub struct Device<'a> {
    bus: &'a BusName,
    node: NodeId,
}

impl fmt::Display for Device<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.bus {
            BusName::Unnamed => write!(f, "node {}", self.node.get()),
            bus => write!(f, "{bus} node {}", self.node.get()),
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

/// The buses seen so far, each with what a component keeps of it, found
/// again without a search for the common case of a log whose frames share
/// one interface.
#[derive(Debug)]
pub(crate) struct Buses<T> {
    buses: Vec<(BusName, T)>,
    last: usize,
}

impl<T> Default for Buses<T> {
    fn default() -> Self {
        Buses {
            buses: Vec::new(),
            last: 0,
        }
    }
}

impl<T> Buses<T> {
    /// Return the index of the bus of `iface`, made with `make` on first
    /// sight; the second value says whether it was made now.
    #[inline(always)]
    pub(crate) fn find_or_insert(
        &mut self,
        iface: Option<Iface<'_>>,
        make: impl FnOnce(&BusName) -> T,
    ) -> (usize, bool) {
        if let Some((name, _)) = self.buses.get(self.last) {
            if name.is(iface) {
                return (self.last, false);
            }
        }
        self.find_or_insert_slow(iface, make)
    }

    #[inline(never)]
    fn find_or_insert_slow(
        &mut self,
        iface: Option<Iface<'_>>,
        make: impl FnOnce(&BusName) -> T,
    ) -> (usize, bool) {
        let (at, made) = match self.buses.iter().position(|(name, _)| name.is(iface)) {
            Some(at) => (at, false),
            None => {
                let name = BusName::of(iface);
                let value = make(&name);
                self.buses.push((name, value));
                (self.buses.len() - 1, true)
            }
        };
        self.last = at;
        (at, made)
    }

    pub(crate) fn get_mut(&mut self, at: usize) -> &mut T {
        &mut self.buses[at].1
    }

    /// Return the name of the bus at `at`.
    pub(crate) fn name(&self, at: usize) -> &BusName {
        &self.buses[at].0
    }

    pub(crate) fn get(&self, at: usize) -> &T {
        &self.buses[at].1
    }

    pub(crate) fn find(&self, name: &BusName) -> Option<&T> {
        self.buses.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    pub(crate) fn iter_mut(&mut self) -> impl Iterator<Item = (&BusName, &mut T)> {
        self.buses.iter_mut().map(|(n, v)| (&*n, v))
    }
}
