//! The buses a session has seen, each found again by a frame's interface,
//! and a device named by its bus (docs/formats.md#interfaces: a node's
//! identity is its interface and its node-ID).

use core::fmt;

use crate::can::{BusName, Iface};
use crate::canopen::NodeId;

/// A device, named by its bus and node-ID as the summary's findings and
/// the report name it: `can0 node 3`, or `node 3` on a log that names no
/// interface.
///
/// ```
/// use motionwire::can::BusName;
/// use motionwire::canopen::NodeId;
/// use motionwire::decoder::Device;
///
/// let node = NodeId::new(3).unwrap();
/// assert_eq!(Device::new(&BusName::Name("can0".into()), node).to_string(), "can0 node 3");
/// assert_eq!(Device::new(&BusName::Unnamed, node).to_string(), "node 3");
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Device<'a> {
    bus: &'a BusName,
    node: NodeId,
}

impl<'a> Device<'a> {
    /// Return the device `node` on the bus `bus`.
    #[must_use]
    pub fn new(bus: &'a BusName, node: NodeId) -> Self {
        Device { bus, node }
    }
}

impl fmt::Display for Device<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.bus {
            BusName::Unnamed => write!(f, "node {}", self.node.get()),
            bus => write!(f, "{bus} node {}", self.node.get()),
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
    /// sight; the second value says whether it was made now. The interface
    /// is borrowed from the frame that holds it.
    #[inline(always)]
    pub(crate) fn find_or_insert(
        &mut self,
        iface: &Option<Iface<'_>>,
        make: impl FnOnce(&BusName) -> T,
    ) -> (usize, bool) {
        if let Some((name, _)) = self.buses.get(self.last) {
            if name.is(*iface) {
                return (self.last, false);
            }
        }
        self.find_or_insert_slow(iface, make)
    }

    #[inline(never)]
    fn find_or_insert_slow(
        &mut self,
        iface: &Option<Iface<'_>>,
        make: impl FnOnce(&BusName) -> T,
    ) -> (usize, bool) {
        let (at, made) = match self.buses.iter().position(|(name, _)| name.is(*iface)) {
            Some(at) => (at, false),
            None => {
                let name = BusName::of(*iface);
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
