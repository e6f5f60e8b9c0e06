//! The PLC-side EMCY consumer of CiA 405: `RECV_EMCY` and `RECV_EMCY_DEV`
//! (docs/canopen.md#recv-emcy; seed `001`, the CoDeSys help page of
//! `CIA405.RECV_EMCY`).
//!
//! CiA 405 (the IEC 61131-3 interface to CANopen) gives a PLC two function
//! blocks for the emergency messages of the devices 1..=127 on its network,
//! and recommends how the "lower level software" under them keeps the
//! received EMCYs. This module is that software, as two pure state machines:
//!
//! - [`EmcyStorage`] keeps one EMCY slot per device (fixed memory for all 127
//!   devices) and the set of devices that exist. [`EmcyStorage::receive`]
//!   stores an error only while the slot holds "no error" — the first error
//!   is the root cause and later ones do not overwrite it — and a reset
//!   always overwrites. [`EmcyStorage::recv_emcy_dev`] is `RECV_EMCY_DEV`: it
//!   returns the stored error on every call until the device sends a reset.
//! - [`RecvEmcy`] is one `RECV_EMCY` block: every [`RecvEmcy::call`]
//!   continues the scan over the existing devices where the last call
//!   stopped and delivers a pending error, a "reset error" (once), or — after
//!   a complete scan found nothing — "all devices are error-free".
//!
//! Each call has a typed result ([`RecvEmcyResult`], [`KernelError`]) and the
//! raw outputs `CONFIRM`, `ERROR`, `DEVICE`, `ERRORINFO` of the CiA 405
//! blocks ([`RecvEmcyOutputs`], [`RecvEmcyDevOutputs`]). Nothing here reads a
//! clock or allocates.
//!
//! ```
//! use motionwire_codec::canopen::{
//!     Emcy, EmcyStorage, NodeId, RecvEmcy, RecvEmcyResult, SlotUpdate,
//! };
//!
//! let drive = NodeId::new(5).unwrap();
//! let mut storage = EmcyStorage::new();
//! storage.add_device(drive);
//! let mut recv_emcy = RecvEmcy::new();
//!
//! // Device 5 reports a life-guard error, then a follow-up error.
//! let error = Emcy::parse(&[0x30, 0x81, 0x11, 0, 0, 0, 0, 0])?;
//! let follow_up = Emcy::parse(&[0x10, 0x81, 0x11, 0, 0, 0, 0, 0])?;
//! assert_eq!(storage.receive(drive, error), SlotUpdate::RootCause);
//! assert_eq!(storage.receive(drive, follow_up), SlotUpdate::FollowUp { root_cause: error });
//!
//! // RECV_EMCY delivers the root cause as long as it is pending…
//! let expected = RecvEmcyResult::Error { device: drive, emcy: error };
//! assert_eq!(recv_emcy.call(&storage), Ok(expected));
//! assert_eq!(recv_emcy.call(&storage), Ok(expected));
//! assert_eq!(storage.recv_emcy_dev(drive), Ok(Some(error)));
//!
//! // …the device's reset once, then "all devices are error-free".
//! let reset = Emcy::parse(&[0; 8])?;
//! storage.receive(drive, reset);
//! assert_eq!(recv_emcy.call(&storage), Ok(RecvEmcyResult::ResetError { device: drive, reset }));
//! assert_eq!(recv_emcy.call(&storage), Ok(RecvEmcyResult::AllClear));
//!
//! // The raw CiA 405 outputs of the same call.
//! let raw = recv_emcy.call_outputs(&storage);
//! assert!(raw.confirm());
//! assert_eq!((raw.device(), raw.errorinfo().code.get()), (0, 0x0000));
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use core::fmt;

use super::{Emcy, ErrorCode, ErrorRegister, NodeId};

/// The number of devices a CANopen network can hold, node-IDs 1..=127.
const DEVICES: usize = 127;

/// The `ERRORINFO` of "no error": code 0x0000, empty register, zero
/// manufacturer field.
const NO_ERROR: Emcy = Emcy::reset(ErrorRegister::empty());

// ---------------------------------------------------------------------------
// CANOPEN_KERNEL_ERROR

/// The `ERROR` output of the CiA 405 function blocks, type
/// `CANOPEN_KERNEL_ERROR` (CiA 405; CODESYS "CAA CiA 405" library,
/// `CANOPEN_KERNEL_ERROR`).
///
/// The values 0x0000–0x0003 and 0x0010–0x0011 are CiA 405's own; CiA 405
/// reserves 0x0004–0x000F for further SDO errors, 0x0012–0x001F for further
/// kernel errors and 0x0100–0xFFFF for itself, and leaves 0x0021–0x00FF to
/// the manufacturer. [`KernelError::NodeIdUnknown`] (0x0024) is the
/// manufacturer-specific value CODESYS gives an unknown node-ID; it is the
/// only error that [`RecvEmcy`] and [`EmcyStorage`] report.
///
/// ```
/// use motionwire_codec::canopen::KernelError;
///
/// assert_eq!(KernelError::from_code(0x0024), KernelError::NodeIdUnknown);
/// assert_eq!(KernelError::NodeIdUnknown.name(), "CANOPEN_NODEID_UNKNOWN");
/// assert_eq!(KernelError::from_code(0x0010).to_string(), "CAN bus off");
/// assert!(!KernelError::NoError.is_error());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum KernelError {
    /// 0x0000 `CANOPEN_KERNEL_NO_ERROR`: the call completed without error.
    NoError,
    /// 0x0001 `CANOPEN_KERNEL_OTHER_ERROR`: another error; a block with a
    /// further error output (e.g. `ERRORINFO`) says more there.
    OtherError,
    /// 0x0002 `CANOPEN_KERNEL_DATA_OVERFLOW`: a send or receive buffer of the
    /// kernel overflowed.
    DataOverflow,
    /// 0x0003 `CANOPEN_KERNEL_TIMEOUT`: a timeout, e.g. a device did not
    /// answer an SDO request.
    Timeout,
    /// 0x0010 `CANOPEN_KERNEL_CANBUS_OFF`: the PLC's CAN controller is bus
    /// off, disconnected from the bus.
    CanBusOff,
    /// 0x0011 `CANOPEN_KERNEL_CAN_ERROR_PASSIVE`: the PLC's CAN controller
    /// is error passive.
    CanErrorPassive,
    /// 0x0024 `CANOPEN_NODEID_UNKNOWN` (manufacturer-specific, CODESYS): the
    /// node-ID is not a device of the network. [`EmcyStorage::recv_emcy_dev`]
    /// reports it for a device that is not configured, and [`RecvEmcy::call`]
    /// when no device is configured at all.
    NodeIdUnknown,
    /// Any other value: reserved by CiA or manufacturer-specific. It holds a
    /// value no other variant names when made by [`KernelError::from_code`].
    Unlisted(u16),
}

impl KernelError {
    /// Return the kernel error with the numeric value `code`.
    #[must_use]
    pub const fn from_code(code: u16) -> Self {
        match code {
            0x0000 => KernelError::NoError,
            0x0001 => KernelError::OtherError,
            0x0002 => KernelError::DataOverflow,
            0x0003 => KernelError::Timeout,
            0x0010 => KernelError::CanBusOff,
            0x0011 => KernelError::CanErrorPassive,
            0x0024 => KernelError::NodeIdUnknown,
            other => KernelError::Unlisted(other),
        }
    }

    /// Return the numeric value of the `ERROR` output.
    #[must_use]
    pub const fn code(self) -> u16 {
        match self {
            KernelError::NoError => 0x0000,
            KernelError::OtherError => 0x0001,
            KernelError::DataOverflow => 0x0002,
            KernelError::Timeout => 0x0003,
            KernelError::CanBusOff => 0x0010,
            KernelError::CanErrorPassive => 0x0011,
            KernelError::NodeIdUnknown => 0x0024,
            KernelError::Unlisted(code) => code,
        }
    }

    /// Return whether this value reports an error (anything but
    /// `CANOPEN_KERNEL_NO_ERROR`).
    #[must_use]
    pub const fn is_error(self) -> bool {
        self.code() != 0x0000
    }

    /// Return the identifier CiA 405 (or CODESYS, for the
    /// manufacturer-specific value) gives the value, e.g.
    /// `"CANOPEN_KERNEL_TIMEOUT"`; `"unlisted"` for [`KernelError::Unlisted`].
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            KernelError::NoError => "CANOPEN_KERNEL_NO_ERROR",
            KernelError::OtherError => "CANOPEN_KERNEL_OTHER_ERROR",
            KernelError::DataOverflow => "CANOPEN_KERNEL_DATA_OVERFLOW",
            KernelError::Timeout => "CANOPEN_KERNEL_TIMEOUT",
            KernelError::CanBusOff => "CANOPEN_KERNEL_CANBUS_OFF",
            KernelError::CanErrorPassive => "CANOPEN_KERNEL_CAN_ERROR_PASSIVE",
            KernelError::NodeIdUnknown => "CANOPEN_NODEID_UNKNOWN",
            KernelError::Unlisted(_) => "unlisted",
        }
    }

    /// Return the meaning of the value in words; for an unlisted value, the
    /// range CiA 405 puts it in.
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            KernelError::NoError => "no error",
            KernelError::OtherError => "other error",
            KernelError::DataOverflow => "data overflow",
            KernelError::Timeout => "timeout",
            KernelError::CanBusOff => "CAN bus off",
            KernelError::CanErrorPassive => "CAN error passive",
            KernelError::NodeIdUnknown => "unknown node-ID",
            KernelError::Unlisted(code) => match code {
                0x0004..=0x000F => "reserved for further SDO errors",
                0x0012..=0x001F => "reserved for further kernel errors",
                0x0021..=0x00FF => "manufacturer-specific error",
                0x0100..=0xFFFF => "reserved by CiA",
                _ => "unassigned",
            },
        }
    }
}

impl From<u16> for KernelError {
    fn from(code: u16) -> Self {
        KernelError::from_code(code)
    }
}

impl From<KernelError> for u16 {
    fn from(error: KernelError) -> u16 {
        error.code()
    }
}

impl fmt::Display for KernelError {
    /// Format the value as its meaning, e.g. `unknown node-ID`; an unlisted
    /// value also shows its number, e.g. `manufacturer-specific error 0x0042`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KernelError::Unlisted(code) => write!(f, "{} 0x{code:04X}", self.description()),
            _ => f.write_str(self.description()),
        }
    }
}

// ---------------------------------------------------------------------------
// The set of existing devices

/// A set of devices of one network, node-IDs 1..=127, one bit each: the
/// devices that exist (are configured) for CiA 405's "scan over all existing
/// devices" (docs/canopen.md#recv-emcy).
///
/// ```
/// use motionwire_codec::canopen::{DeviceSet, NodeId};
///
/// let n = |raw| NodeId::new(raw).unwrap();
/// let devices: DeviceSet = [n(3), n(64), n(127)].into_iter().collect();
/// assert_eq!(devices.len(), 3);
/// assert!(devices.contains(n(64)));
/// // The first device at or after 65, wrapping past 127 to 1.
/// assert_eq!(devices.first_from(n(65)), Some(n(127)));
/// assert_eq!(devices.without(n(127)).first_from(n(65)), Some(n(3)));
/// ```
///
/// With the `serde` feature a set serializes as the list of its node-IDs
/// in ascending order (`[3, 64, 127]` in JSON); deserializing checks each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DeviceSet(u128);

impl DeviceSet {
    /// No device.
    pub const EMPTY: DeviceSet = DeviceSet(0);
    /// Every device, 1 to 127.
    pub const ALL: DeviceSet = DeviceSet(u128::MAX >> 1);

    /// Return the empty set.
    #[inline]
    #[must_use]
    pub const fn new() -> Self {
        DeviceSet::EMPTY
    }

    /// The bit of `node`: bit 0 is node 1, bit 126 node 127 (bit 127 is
    /// never set).
    #[inline]
    const fn bit(node: NodeId) -> u128 {
        1 << node.index()
    }

    /// Return whether `node` is in the set.
    #[inline]
    #[must_use]
    pub const fn contains(self, node: NodeId) -> bool {
        self.0 & Self::bit(node) != 0
    }

    /// Add `node`; return whether it was not in the set before.
    #[inline]
    pub fn insert(&mut self, node: NodeId) -> bool {
        let added = !self.contains(node);
        self.0 |= Self::bit(node);
        added
    }

    /// Take `node` out; return whether it was in the set.
    #[inline]
    pub fn remove(&mut self, node: NodeId) -> bool {
        let removed = self.contains(node);
        self.0 &= !Self::bit(node);
        removed
    }

    /// Return the set with `node` added.
    #[inline]
    #[must_use]
    pub const fn with(self, node: NodeId) -> Self {
        DeviceSet(self.0 | Self::bit(node))
    }

    /// Return the set with `node` taken out.
    #[inline]
    #[must_use]
    pub const fn without(self, node: NodeId) -> Self {
        DeviceSet(self.0 & !Self::bit(node))
    }

    /// Return the number of devices in the set.
    #[inline]
    #[must_use]
    pub const fn len(self) -> usize {
        self.0.count_ones() as usize
    }

    /// Return whether the set holds no device.
    #[inline]
    #[must_use]
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Return the devices that are in `self` or in `other`.
    #[inline]
    #[must_use]
    pub const fn union(self, other: DeviceSet) -> Self {
        DeviceSet(self.0 | other.0)
    }

    /// Return the devices that are in both `self` and `other`.
    #[inline]
    #[must_use]
    pub const fn intersection(self, other: DeviceSet) -> Self {
        DeviceSet(self.0 & other.0)
    }

    /// Return the first device of the set at or after `start`, wrapping past
    /// 127 to 1: the order in which `RECV_EMCY` continues its scan
    /// (docs/canopen.md#recv-emcy). `None` when the set is empty.
    #[must_use]
    pub fn first_from(self, start: NodeId) -> Option<NodeId> {
        let at_or_after = self.0 & (u128::MAX << start.index());
        let bits = if at_or_after != 0 {
            at_or_after
        } else {
            self.0
        };
        if bits == 0 {
            return None;
        }
        // A set bit is at most bit 126 (node 127), so this is 1..=127.
        NodeId::new((bits.trailing_zeros() as u8).saturating_add(1))
    }

    /// Return the devices of the set in ascending order.
    #[must_use]
    pub fn iter(self) -> impl DoubleEndedIterator<Item = NodeId> + Clone {
        NodeId::all().filter(move |&node| self.contains(node))
    }
}

impl FromIterator<NodeId> for DeviceSet {
    fn from_iter<I: IntoIterator<Item = NodeId>>(nodes: I) -> Self {
        nodes.into_iter().fold(DeviceSet::EMPTY, DeviceSet::with)
    }
}

impl Extend<NodeId> for DeviceSet {
    fn extend<I: IntoIterator<Item = NodeId>>(&mut self, nodes: I) {
        for node in nodes {
            self.insert(node);
        }
    }
}

/// With the `serde` feature, a set serializes as the sequence of its
/// node-IDs in ascending order (`[3, 64, 127]` in JSON), not as its 128-bit
/// mask: readable, and carried by formats without 128-bit integers.
/// Deserializing checks every node-ID (1..=127) and accepts any order and
/// repeats, as [`FromIterator`] does.
#[cfg(feature = "serde")]
impl serde::Serialize for DeviceSet {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for DeviceSet {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NodeIds;

        impl<'de> serde::de::Visitor<'de> for NodeIds {
            type Value = DeviceSet;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a sequence of node-IDs 1..=127")
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<DeviceSet, A::Error> {
                let mut set = DeviceSet::EMPTY;
                while let Some(node) = seq.next_element::<NodeId>()? {
                    set.insert(node);
                }
                Ok(set)
            }
        }

        deserializer.deserialize_seq(NodeIds)
    }
}

// ---------------------------------------------------------------------------
// Per-device storage: RECV_EMCY_DEV

/// What [`EmcyStorage::receive`] did with a received EMCY (CiA 405,
/// recommendation for `RECV_EMCY_DEV`; docs/canopen.md#recv-emcy).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SlotUpdate {
    /// The slot held "no error": the error is stored and is now the device's
    /// root cause.
    RootCause,
    /// The slot already holds an error: that earlier error stays the root
    /// cause and the received one is not stored.
    FollowUp {
        /// The earlier error that the slot keeps.
        root_cause: Emcy,
    },
    /// A reset ("error reset or no error", any 0x00xx code) overwrote the
    /// slot.
    Reset {
        /// The error the reset cleared; `None` when the slot already held
        /// "no error".
        cleared: Option<Emcy>,
    },
}

impl fmt::Display for SlotUpdate {
    /// Format what happened to the slot in words, with the [`Emcy`] it
    /// keeps or cleared as that writes itself: `stored as the root cause`,
    /// `not stored, the root cause stays EMCY 0x7305 …`, `reset, cleared
    /// EMCY 0x7305 …`, `reset, no error to clear`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SlotUpdate::RootCause => f.write_str("stored as the root cause"),
            SlotUpdate::FollowUp { root_cause } => {
                write!(f, "not stored, the root cause stays {root_cause}")
            }
            SlotUpdate::Reset {
                cleared: Some(cleared),
            } => write!(f, "reset, cleared {cleared}"),
            SlotUpdate::Reset { cleared: None } => f.write_str("reset, no error to clear"),
        }
    }
}

/// The EMCY slots of all 127 devices and the set of devices that exist: the
/// "lower level software" under CiA 405's `RECV_EMCY` and `RECV_EMCY_DEV`
/// (docs/canopen.md#recv-emcy; CiA 405, recommendations for `RECV_EMCY_DEV` and
/// `RECV_EMCY`).
///
/// Each device has one slot, which holds "no error" at the start.
/// [`EmcyStorage::receive`] stores an error EMCY only when the slot holds
/// "no error" — the first error of a device is its root cause; later errors
/// often just follow from it — and stores a reset EMCY (any 0x00xx code,
/// [`Emcy::is_reset`]) always. The memory is fixed: 127 slots of 8 bytes
/// and two 128-bit sets.
///
/// **Decision** (unconfigured devices): an EMCY from a device that is not
/// configured is stored all the same — every device has its slot — so that
/// a log analyser sees every device through [`EmcyStorage::slot`], and a
/// device configured later starts with what it has sent. The CiA 405 calls
/// see only configured devices: [`RecvEmcy`] scans the configured devices
/// only, and [`EmcyStorage::recv_emcy_dev`] answers
/// [`KernelError::NodeIdUnknown`] for any other device.
///
/// ```
/// use motionwire_codec::canopen::{Emcy, EmcyStorage, ErrorCode, ErrorRegister, KernelError, NodeId};
///
/// let node = NodeId::new(7).unwrap();
/// let mut storage = EmcyStorage::new();
/// let error = Emcy::new(ErrorCode::new(0x4310), ErrorRegister::GENERIC | ErrorRegister::TEMPERATURE, [0; 5]);
/// storage.receive(node, error);
///
/// // Stored, but RECV_EMCY_DEV answers only for configured devices.
/// assert_eq!(storage.root_cause(node), Some(error));
/// assert_eq!(storage.recv_emcy_dev(node), Err(KernelError::NodeIdUnknown));
/// storage.add_device(node);
/// assert_eq!(storage.recv_emcy_dev(node), Ok(Some(error)));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EmcyStorage {
    /// The slot of each device, indexed by [`NodeId::index`].
    slots: [Emcy; DEVICES],
    /// The devices that exist (are configured).
    configured: DeviceSet,
    /// The devices whose slot holds an error (not a reset code); kept equal
    /// to the slots so that a scan is a few bit operations.
    in_error: DeviceSet,
}

impl Default for EmcyStorage {
    fn default() -> Self {
        Self::new()
    }
}

impl EmcyStorage {
    /// Return a storage with no device configured and every slot at "no
    /// error".
    #[must_use]
    pub const fn new() -> Self {
        Self::with_devices(DeviceSet::EMPTY)
    }

    /// Return a storage with `devices` configured and every slot at "no
    /// error".
    #[must_use]
    pub const fn with_devices(devices: DeviceSet) -> Self {
        EmcyStorage {
            slots: [NO_ERROR; DEVICES],
            configured: devices,
            in_error: DeviceSet::EMPTY,
        }
    }

    /// Configure `node` as an existing device; return whether it was not
    /// configured before. Its slot is kept as it is.
    #[inline]
    pub fn add_device(&mut self, node: NodeId) -> bool {
        self.configured.insert(node)
    }

    /// Remove `node` from the existing devices; return whether it was
    /// configured. Its slot is kept as it is (see the type's **Decision**).
    #[inline]
    pub fn remove_device(&mut self, node: NodeId) -> bool {
        self.configured.remove(node)
    }

    /// Return whether `node` is a configured device.
    #[inline]
    #[must_use]
    pub const fn is_configured(&self, node: NodeId) -> bool {
        self.configured.contains(node)
    }

    /// Return the configured devices.
    #[inline]
    #[must_use]
    pub const fn devices(&self) -> DeviceSet {
        self.configured
    }

    /// Return every device, configured or not, whose slot holds an error.
    #[inline]
    #[must_use]
    pub const fn devices_in_error(&self) -> DeviceSet {
        self.in_error
    }

    /// Take in an EMCY received from `node` (COB-ID 0x080 + node-ID): store
    /// an error only when the slot holds "no error", store a reset always
    /// (docs/canopen.md#recv-emcy).
    pub fn receive(&mut self, node: NodeId, emcy: Emcy) -> SlotUpdate {
        let slot = &mut self.slots[node.index()];
        let held = *slot;
        if emcy.is_reset() {
            *slot = emcy;
            self.in_error.remove(node);
            SlotUpdate::Reset {
                cleared: (!held.is_reset()).then_some(held),
            }
        } else if held.is_reset() {
            *slot = emcy;
            self.in_error.insert(node);
            SlotUpdate::RootCause
        } else {
            SlotUpdate::FollowUp { root_cause: held }
        }
    }

    /// Take in a boot-up message of `node` (heartbeat state 0): the device
    /// has re-initialised, and a device starts error-free (transition 0
    /// of the EMCY state machine, CiA 301; docs/canopen.md#recv-emcy), so
    /// its slot returns to "no error" until a new EMCY says otherwise.
    /// Return the error the boot-up cleared; `None` when the slot held
    /// "no error".
    ///
    /// ```
    /// use motionwire_codec::canopen::{Emcy, EmcyStorage, ErrorCode, ErrorRegister, NodeId};
    ///
    /// let node = NodeId::new(5).unwrap();
    /// let mut storage = EmcyStorage::new();
    /// let hot = Emcy::new(ErrorCode::new(0x4200), ErrorRegister::GENERIC, [0; 5]);
    /// storage.receive(node, hot);
    /// assert_eq!(storage.boot_up(node), Some(hot));
    /// assert_eq!(storage.root_cause(node), None);
    /// assert_eq!(storage.boot_up(node), None);
    /// ```
    pub fn boot_up(&mut self, node: NodeId) -> Option<Emcy> {
        let held = core::mem::replace(&mut self.slots[node.index()], NO_ERROR);
        self.in_error.remove(node);
        (!held.is_reset()).then_some(held)
    }

    /// Return the slot of `node` as it is, configured or not: its root-cause
    /// error, or the last reset EMCY it received (with the register and
    /// manufacturer bytes the device sent), or the all-zero "no error" when
    /// it has sent nothing.
    #[inline]
    #[must_use]
    pub const fn slot(&self, node: NodeId) -> Emcy {
        self.slots[node.index()]
    }

    /// Return the error pending for `node`, configured or not: the first
    /// error it sent since its last reset; `None` when it holds "no error".
    #[inline]
    #[must_use]
    pub fn root_cause(&self, node: NodeId) -> Option<Emcy> {
        let slot = self.slot(node);
        (!slot.is_reset()).then_some(slot)
    }

    /// `RECV_EMCY_DEV` for `node`: the error pending for the device — the
    /// same on every call until the device sends a reset — or `None` when it
    /// has no error; [`KernelError::NodeIdUnknown`] when `node` is not a
    /// configured device (CiA 405 `RECV_EMCY_DEV`; docs/canopen.md#recv-emcy).
    pub fn recv_emcy_dev(&self, node: NodeId) -> Result<Option<Emcy>, KernelError> {
        if self.is_configured(node) {
            Ok(self.root_cause(node))
        } else {
            Err(KernelError::NodeIdUnknown)
        }
    }

    /// `RECV_EMCY_DEV` for `node` with the raw CiA 405 outputs `CONFIRM`,
    /// `ERROR` and `ERRORINFO`.
    #[must_use]
    pub fn recv_emcy_dev_outputs(&self, node: NodeId) -> RecvEmcyDevOutputs {
        match self.recv_emcy_dev(node) {
            Ok(_) => RecvEmcyDevOutputs {
                confirm: true,
                error: KernelError::NoError,
                errorinfo: as_errorinfo(self.slot(node)),
            },
            Err(error) => RecvEmcyDevOutputs {
                confirm: false,
                error,
                errorinfo: NO_ERROR,
            },
        }
    }
}

/// The `ERRORINFO` for a stored EMCY: the EMCY itself, with the code of a
/// reset set to exactly 0x0000 so that CiA 405's test "code ≠ 0" holds for
/// every 0x00xx a device may send (the **Decision** in
/// docs/canopen.md#emcy-codes); register and manufacturer bytes are kept.
#[inline]
fn as_errorinfo(emcy: Emcy) -> Emcy {
    if emcy.is_reset() {
        Emcy {
            code: ErrorCode::NO_ERROR,
            ..emcy
        }
    } else {
        emcy
    }
}

/// The raw outputs of one `RECV_EMCY_DEV` call (CiA 405; CODESYS
/// `RECV_EMCY_DEV`), from [`EmcyStorage::recv_emcy_dev_outputs`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RecvEmcyDevOutputs {
    confirm: bool,
    error: KernelError,
    errorinfo: Emcy,
}

impl RecvEmcyDevOutputs {
    /// Return `CONFIRM`: true when the call completed without error.
    #[inline]
    #[must_use]
    pub const fn confirm(&self) -> bool {
        self.confirm
    }

    /// Return `ERROR`: [`KernelError::NoError`] when the call completed.
    #[inline]
    #[must_use]
    pub const fn error(&self) -> KernelError {
        self.error
    }

    /// Return `ERRORINFO` (type `EMCY_ERROR`): the pending error, or an EMCY
    /// with code 0x0000 when the device has none (the last reset it sent,
    /// register and manufacturer bytes kept; all zero after an error of the
    /// call).
    #[inline]
    #[must_use]
    pub const fn errorinfo(&self) -> Emcy {
        self.errorinfo
    }

    /// Return whether an emergency is pending for the device: `ERRORINFO`'s
    /// code ≠ 0.
    #[inline]
    #[must_use]
    pub const fn emergency_received(&self) -> bool {
        self.errorinfo.code.get() != 0
    }
}

// ---------------------------------------------------------------------------
// The scan: RECV_EMCY

/// What one `RECV_EMCY` call delivers (CiA 405 `RECV_EMCY`;
/// docs/canopen.md#recv-emcy).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum RecvEmcyResult {
    /// `device` holds an error: `DEVICE` = device, `ERRORINFO` = the error.
    /// Delivered again on every scan as long as it is pending.
    Error {
        /// The device whose slot holds the error.
        device: NodeId,
        /// The stored error, the device's root cause.
        emcy: Emcy,
    },
    /// `device`, last delivered with an error, now holds "no error": it sent
    /// a reset. Delivered once (`DEVICE` > 0, `ERRORINFO` = 0).
    ResetError {
        /// The device that reset its error.
        device: NodeId,
        /// The reset EMCY as the device sent it (code 0x00xx, the register
        /// of its remaining errors, manufacturer bytes).
        reset: Emcy,
    },
    /// A complete scan over all existing devices found nothing to deliver:
    /// all devices are error-free (`DEVICE` = 0, `ERRORINFO` = 0).
    AllClear,
}

impl RecvEmcyResult {
    /// Return the `DEVICE` output as a node: `None` for
    /// [`RecvEmcyResult::AllClear`].
    #[inline]
    #[must_use]
    pub const fn device(&self) -> Option<NodeId> {
        match self {
            RecvEmcyResult::Error { device, .. } | RecvEmcyResult::ResetError { device, .. } => {
                Some(*device)
            }
            RecvEmcyResult::AllClear => None,
        }
    }

    /// Return whether an emergency was received: `DEVICE` ≠ 0 and
    /// `ERRORINFO`'s code ≠ 0, i.e. [`RecvEmcyResult::Error`].
    #[inline]
    #[must_use]
    pub const fn emergency_received(&self) -> bool {
        matches!(self, RecvEmcyResult::Error { .. })
    }
}

/// The raw outputs of one `RECV_EMCY` call: `CONFIRM`, `ERROR`, `DEVICE`,
/// `ERRORINFO` (CiA 405 `RECV_EMCY`; seed `001`), from
/// [`RecvEmcy::call_outputs`] or from a typed result with `From`.
///
/// ```
/// use motionwire_codec::canopen::{KernelError, RecvEmcyOutputs};
///
/// let raw = RecvEmcyOutputs::from(Err(KernelError::NodeIdUnknown));
/// assert!(!raw.confirm());
/// assert_eq!(raw.error().code(), 0x0024);
/// assert_eq!(raw.device(), 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RecvEmcyOutputs {
    confirm: bool,
    error: KernelError,
    device: u8,
    errorinfo: Emcy,
}

impl RecvEmcyOutputs {
    /// Return `CONFIRM`: true when the call completed without error.
    #[inline]
    #[must_use]
    pub const fn confirm(&self) -> bool {
        self.confirm
    }

    /// Return `ERROR`: [`KernelError::NoError`] when the call completed.
    #[inline]
    #[must_use]
    pub const fn error(&self) -> KernelError {
        self.error
    }

    /// Return `DEVICE`: the node-ID of the device delivered, 1..=127, or 0
    /// for "all devices are error-free" (and after an error of the call).
    #[inline]
    #[must_use]
    pub const fn device(&self) -> u8 {
        self.device
    }

    /// Return `ERRORINFO` (type `EMCY_ERROR`): the delivered error; for a
    /// reset, the reset EMCY with code 0x0000 (register and manufacturer
    /// bytes as the device sent them); all zero for "all clear" and after an
    /// error of the call.
    #[inline]
    #[must_use]
    pub const fn errorinfo(&self) -> Emcy {
        self.errorinfo
    }

    /// Return whether an emergency was received: `DEVICE` ≠ 0 and
    /// `ERRORINFO`'s code ≠ 0 (CiA 405 `RECV_EMCY`; docs/canopen.md#recv-emcy).
    #[inline]
    #[must_use]
    pub const fn emergency_received(&self) -> bool {
        self.device != 0 && self.errorinfo.code.get() != 0
    }
}

impl From<Result<RecvEmcyResult, KernelError>> for RecvEmcyOutputs {
    fn from(result: Result<RecvEmcyResult, KernelError>) -> Self {
        let (device, errorinfo) = match result {
            Ok(RecvEmcyResult::Error { device, emcy }) => (device.get(), emcy),
            Ok(RecvEmcyResult::ResetError { device, reset }) => (device.get(), as_errorinfo(reset)),
            Ok(RecvEmcyResult::AllClear) | Err(_) => (0, NO_ERROR),
        };
        RecvEmcyOutputs {
            confirm: result.is_ok(),
            error: result.err().unwrap_or(KernelError::NoError),
            device,
            errorinfo,
        }
    }
}

/// One `RECV_EMCY` function block: the scan over the existing devices of an
/// [`EmcyStorage`] (CiA 405 `RECV_EMCY`, with its recommendation;
/// docs/canopen.md#recv-emcy).
///
/// Every [`RecvEmcy::call`] continues the scan at the device after the one
/// it delivered last, in ascending node-ID order wrapping past 127 to 1,
/// over the configured devices, and delivers the first device that
///
/// - holds an error: [`RecvEmcyResult::Error`] — again on every scan while
///   it is pending;
/// - was last delivered with an error and now holds "no error":
///   [`RecvEmcyResult::ResetError`], once;
///
/// skipping every other device. When a complete scan over all existing
/// devices finds nothing to deliver, the call delivers
/// [`RecvEmcyResult::AllClear`]; so "all clear" comes only when no
/// configured device holds an error. With no device configured the call
/// fails with [`KernelError::NodeIdUnknown`] (**Decision**: a PLC whose
/// network knows no device is misconfigured, which "all clear" would hide).
///
/// An error that a device sends and resets between two calls is never
/// delivered (the scan looks at slots, not at messages); the return value of
/// [`EmcyStorage::receive`] shows it.
///
/// The block's state (where the scan continues, which errors it delivered)
/// is its own, apart from the storage it scans, as CiA 405 blocks are
/// instances over the one kernel: two `RecvEmcy` over the same storage each
/// deliver every reset once.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RecvEmcy {
    /// Where the next call starts its scan.
    next: NodeId,
    /// The devices this block last delivered with an error and whose reset
    /// it has not delivered yet.
    error_delivered: DeviceSet,
}

impl Default for RecvEmcy {
    fn default() -> Self {
        Self::new()
    }
}

impl RecvEmcy {
    /// Return a block whose first scan starts at device 1, with nothing
    /// delivered yet.
    #[must_use]
    pub const fn new() -> Self {
        RecvEmcy {
            next: NodeId::MIN,
            error_delivered: DeviceSet::EMPTY,
        }
    }

    /// Execute `RECV_EMCY` once over `storage` (docs/canopen.md#recv-emcy).
    pub fn call(&mut self, storage: &EmcyStorage) -> Result<RecvEmcyResult, KernelError> {
        let devices = storage.devices();
        if devices.is_empty() {
            return Err(KernelError::NodeIdUnknown);
        }
        let to_deliver =
            devices.intersection(storage.devices_in_error().union(self.error_delivered));
        let Some(device) = to_deliver.first_from(self.next) else {
            return Ok(RecvEmcyResult::AllClear);
        };
        self.next = NodeId::new(device.get().wrapping_add(1)).unwrap_or(NodeId::MIN);
        match storage.root_cause(device) {
            Some(emcy) => {
                self.error_delivered.insert(device);
                Ok(RecvEmcyResult::Error { device, emcy })
            }
            None => {
                self.error_delivered.remove(device);
                Ok(RecvEmcyResult::ResetError {
                    device,
                    reset: storage.slot(device),
                })
            }
        }
    }

    /// Execute `RECV_EMCY` once over `storage` and return the raw CiA 405
    /// outputs.
    pub fn call_outputs(&mut self, storage: &EmcyStorage) -> RecvEmcyOutputs {
        self.call(storage).into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slot_updates_read_as_a_person_says_them() {
        let error = Emcy::from_bytes(&[0x05, 0x73, 0x01, 0x01, 0, 0, 0, 0]);
        let table = [
            (SlotUpdate::RootCause, "stored as the root cause"),
            (
                SlotUpdate::FollowUp { root_cause: error },
                "not stored, the root cause stays EMCY 0x7305 Incremental sensor 1 fault, \
                 register 0x01 [generic], manufacturer 0100000000",
            ),
            (
                SlotUpdate::Reset {
                    cleared: Some(error),
                },
                "reset, cleared EMCY 0x7305 Incremental sensor 1 fault, \
                 register 0x01 [generic], manufacturer 0100000000",
            ),
            (
                SlotUpdate::Reset { cleared: None },
                "reset, no error to clear",
            ),
        ];
        for (update, text) in table {
            assert_eq!(update.to_string(), text);
        }
    }

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    // EMCY frames as devices send them (8 data bytes, docs/canopen.md#emcy).
    /// 0x4310 excess temperature (CiA 402), register generic + temperature.
    const OVER_TEMPERATURE: [u8; 8] = [0x10, 0x43, 0x09, 0, 0, 0, 0, 0];
    /// 0x3210 DC link over-voltage (CiA 402), register generic + voltage.
    const OVER_VOLTAGE: [u8; 8] = [0x10, 0x32, 0x05, 0, 0, 0, 0, 0];
    /// 0x8130 life guard or heartbeat error, register generic + communication,
    /// AKD axis 1 in byte 3 (docs/canopen.md#akd).
    const LIFE_GUARD: [u8; 8] = [0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0];
    /// 0x8210 PDO not processed due to length error.
    const PDO_LENGTH: [u8; 8] = [0x10, 0x82, 0x11, 0, 0, 0, 0, 0];
    /// 0x5100 non-volatile memory problem (Baumer EAM580,
    /// docs/canopen.md#baumer).
    const MEMORY: [u8; 8] = [0x00, 0x51, 0x01, 0x03, 0x00, 0, 0, 0];
    /// 0x0000 error reset, no error remaining (docs/canopen.md#emcy-producer
    /// transition 4).
    const RESET: [u8; 8] = [0; 8];

    /// One line of a scenario: what arrives on the bus, what the
    /// configuration changes, or a call of a CiA 405 block with the outputs
    /// the PLC must see.
    #[derive(Debug, Clone, Copy)]
    enum Step {
        /// An EMCY frame from a device (COB-ID 0x080 + node-ID).
        Rx(u8, [u8; 8]),
        /// `RECV_EMCY` → CONFIRM, ERROR, DEVICE, ERRORINFO's error code.
        RecvEmcy(bool, u16, u8, u16),
        /// `RECV_EMCY_DEV(DEVICE)` → CONFIRM, ERROR, ERRORINFO's error code.
        RecvEmcyDev(u8, bool, u16, u16),
        /// A device is configured.
        Add(u8),
        /// A device is removed from the configuration.
        Remove(u8),
    }
    use Step::{Add, RecvEmcy as Call, RecvEmcyDev as Dev, Remove, Rx};

    /// Run `steps` over a storage with `devices` configured and a fresh
    /// `RECV_EMCY` block, checking every call's outputs; the typed result of
    /// every call must give the same raw outputs.
    fn run(devices: &[u8], steps: &[Step]) {
        let mut storage = EmcyStorage::with_devices(devices.iter().map(|&d| n(d)).collect());
        let mut block = RecvEmcy::new();
        for (line, &step) in steps.iter().enumerate() {
            match step {
                Rx(node, frame) => {
                    storage.receive(n(node), Emcy::parse(&frame).unwrap());
                }
                Add(node) => {
                    storage.add_device(n(node));
                }
                Remove(node) => {
                    storage.remove_device(n(node));
                }
                Call(confirm, error, device, code) => {
                    let typed = block.clone().call(&storage);
                    let raw = block.call_outputs(&storage);
                    assert_eq!(RecvEmcyOutputs::from(typed), raw, "line {line}");
                    let seen = (
                        raw.confirm(),
                        raw.error().code(),
                        raw.device(),
                        raw.errorinfo().code.get(),
                    );
                    assert_eq!(
                        seen,
                        (confirm, error, device, code),
                        "line {line}: {step:?}"
                    );
                    assert_eq!(raw.emergency_received(), device != 0 && code != 0);
                    assert_eq!(
                        typed.is_ok_and(|t| t.emergency_received()),
                        raw.emergency_received()
                    );
                }
                Dev(node, confirm, error, code) => {
                    let raw = storage.recv_emcy_dev_outputs(n(node));
                    let seen = (
                        raw.confirm(),
                        raw.error().code(),
                        raw.errorinfo().code.get(),
                    );
                    assert_eq!(seen, (confirm, error, code), "line {line}: {step:?}");
                    assert_eq!(raw.emergency_received(), code != 0);
                    let typed = storage.recv_emcy_dev(n(node));
                    match typed {
                        Ok(Some(emcy)) => assert_eq!(emcy, raw.errorinfo()),
                        Ok(None) => assert!(confirm && code == 0),
                        Err(e) => assert_eq!(e.code(), error),
                    }
                }
            }
        }
    }

    #[test]
    fn several_devices_with_errors_and_resets() {
        run(
            &[2, 5, 9],
            &[
                //                      CONFIRM ERROR   DEVICE ERRORINFO
                Call(true, 0x0000, 0, 0x0000),
                Rx(5, OVER_VOLTAGE),
                Rx(9, LIFE_GUARD),
                Call(true, 0x0000, 5, 0x3210),
                Call(true, 0x0000, 9, 0x8130),
                Call(true, 0x0000, 5, 0x3210), // pending: delivered again
                Rx(5, RESET),
                Call(true, 0x0000, 9, 0x8130), // the scan goes on after 5
                Call(true, 0x0000, 5, 0x0000), // "reset error" of 5
                Call(true, 0x0000, 9, 0x8130),
                Rx(9, RESET),
                Call(true, 0x0000, 9, 0x0000), // "reset error" of 9
                Call(true, 0x0000, 0, 0x0000), // all devices error-free
                Dev(2, true, 0x0000, 0x0000),
                Dev(5, true, 0x0000, 0x0000),
                Dev(9, true, 0x0000, 0x0000),
            ],
        );
    }

    #[test]
    fn no_error_is_delivered_once() {
        run(
            &[4],
            &[
                Rx(4, OVER_TEMPERATURE),
                Call(true, 0x0000, 4, 0x4310),
                Rx(4, RESET),
                Call(true, 0x0000, 4, 0x0000),
                Call(true, 0x0000, 0, 0x0000),
                Call(true, 0x0000, 0, 0x0000),
                Rx(4, RESET), // a second reset changes nothing
                Call(true, 0x0000, 0, 0x0000),
            ],
        );
    }

    #[test]
    fn all_clear_only_after_a_complete_scan_found_nothing() {
        run(
            &[1, 2, 3],
            &[
                Rx(1, OVER_VOLTAGE),
                Rx(3, MEMORY),
                Call(true, 0x0000, 1, 0x3210),
                Call(true, 0x0000, 3, 0x5100),
                Rx(1, RESET),
                Call(true, 0x0000, 1, 0x0000),
                Call(true, 0x0000, 3, 0x5100), // 3 is still pending: no all-clear
                Call(true, 0x0000, 3, 0x5100),
                Rx(3, RESET),
                Call(true, 0x0000, 3, 0x0000),
                Call(true, 0x0000, 0, 0x0000), // complete scan, nothing found
            ],
        );
    }

    #[test]
    fn the_root_cause_is_kept_over_later_errors() {
        run(
            &[6],
            &[
                Rx(6, OVER_TEMPERATURE),
                Rx(6, LIFE_GUARD),
                Rx(6, PDO_LENGTH),
                Call(true, 0x0000, 6, 0x4310),
                Dev(6, true, 0x0000, 0x4310),
                Dev(6, true, 0x0000, 0x4310), // on every call until the reset
                Call(true, 0x0000, 6, 0x4310),
                Rx(6, RESET),
                Dev(6, true, 0x0000, 0x0000),
                Rx(6, LIFE_GUARD), // first error after the reset: new root cause
                Dev(6, true, 0x0000, 0x8130),
                Call(true, 0x0000, 6, 0x8130),
            ],
        );
    }

    #[test]
    fn a_reset_overwrites_the_slot() {
        let node = n(8);
        let mut storage = EmcyStorage::with_devices(DeviceSet::new().with(node));
        let error = Emcy::parse(&LIFE_GUARD).unwrap();
        // AKD: code 0x0000, the remaining register, axis 1 still in byte 3.
        let partial_reset = Emcy::parse(&[0x00, 0x00, 0x05, 0x01, 0, 0, 0, 0]).unwrap();
        assert_eq!(storage.receive(node, error), SlotUpdate::RootCause);
        assert_eq!(
            storage.receive(node, partial_reset),
            SlotUpdate::Reset {
                cleared: Some(error)
            }
        );
        assert_eq!(storage.slot(node), partial_reset);
        assert_eq!(storage.root_cause(node), None);
        assert_eq!(storage.recv_emcy_dev(node), Ok(None));
        assert_eq!(
            storage.receive(node, Emcy::parse(&RESET).unwrap()),
            SlotUpdate::Reset { cleared: None }
        );
        assert_eq!(storage.slot(node).to_bytes(), RESET);
    }

    #[test]
    fn a_reset_notification_carries_the_reset_emcy() {
        let node = n(8);
        let mut storage = EmcyStorage::with_devices(DeviceSet::new().with(node));
        let mut block = RecvEmcy::new();
        storage.receive(node, Emcy::parse(&LIFE_GUARD).unwrap());
        block.call(&storage).unwrap();
        // A device sending 0x0001 (a 0x00xx reset, docs/canopen.md#emcy-codes)
        // with register 0x05.
        let reset = Emcy::parse(&[0x01, 0x00, 0x05, 0x01, 0, 0, 0, 0]).unwrap();
        storage.receive(node, reset);
        let typed = block.clone().call(&storage);
        assert_eq!(
            typed,
            Ok(RecvEmcyResult::ResetError {
                device: node,
                reset
            })
        );
        assert!(!typed.unwrap().emergency_received());
        let raw = block.call_outputs(&storage);
        assert_eq!(raw.device(), 8);
        // ERRORINFO: code exactly 0, register and manufacturer bytes kept.
        assert_eq!(raw.errorinfo().to_bytes(), [0, 0, 0x05, 0x01, 0, 0, 0, 0]);
        assert!(!raw.emergency_received());
        let dev = storage.recv_emcy_dev_outputs(node);
        assert_eq!(dev.errorinfo().to_bytes(), [0, 0, 0x05, 0x01, 0, 0, 0, 0]);
        assert!(!dev.emergency_received());
    }

    #[test]
    fn the_scan_resumes_where_it_stopped_and_wraps_past_127() {
        run(
            &[1, 64, 126, 127],
            &[
                Rx(127, OVER_VOLTAGE),
                Rx(64, LIFE_GUARD),
                Rx(1, OVER_TEMPERATURE),
                Call(true, 0x0000, 1, 0x4310), // a new block starts at 1
                Call(true, 0x0000, 64, 0x8130),
                Call(true, 0x0000, 127, 0x3210),
                Call(true, 0x0000, 1, 0x4310), // past 127 back to 1
                Rx(126, MEMORY),
                Call(true, 0x0000, 64, 0x8130),
                Call(true, 0x0000, 126, 0x5100),
                Call(true, 0x0000, 127, 0x3210),
                Rx(1, RESET),
                Rx(64, RESET),
                Call(true, 0x0000, 1, 0x0000),
                Call(true, 0x0000, 64, 0x0000),
                Call(true, 0x0000, 126, 0x5100),
                Call(true, 0x0000, 127, 0x3210),
                Call(true, 0x0000, 126, 0x5100), // 1 and 64 are skipped now
            ],
        );
    }

    #[test]
    fn unconfigured_devices() {
        run(
            &[],
            &[
                Call(false, 0x0024, 0, 0x0000), // no device: CANOPEN_NODEID_UNKNOWN
                Dev(10, false, 0x0024, 0x0000),
                Add(10),
                Rx(11, OVER_VOLTAGE), // stored, but 11 is not configured
                Call(true, 0x0000, 0, 0x0000),
                Dev(11, false, 0x0024, 0x0000),
                Dev(10, true, 0x0000, 0x0000),
                Add(11), // configured later: its pending error shows
                Dev(11, true, 0x0000, 0x3210),
                Call(true, 0x0000, 11, 0x3210),
                Remove(11),
                Call(true, 0x0000, 0, 0x0000),
                Rx(11, RESET),
                Add(11), // its error was delivered: the reset is notified once
                Call(true, 0x0000, 11, 0x0000),
                Call(true, 0x0000, 0, 0x0000),
                Remove(10),
                Remove(11),
                Call(false, 0x0024, 0, 0x0000),
            ],
        );
    }

    #[test]
    fn a_device_errs_again_after_its_reset_was_delivered() {
        run(
            &[20],
            &[
                Rx(20, OVER_TEMPERATURE),
                Call(true, 0x0000, 20, 0x4310),
                Rx(20, RESET),
                Call(true, 0x0000, 20, 0x0000),
                Rx(20, LIFE_GUARD),
                Call(true, 0x0000, 20, 0x8130),
                Call(true, 0x0000, 20, 0x8130),
                Rx(20, RESET),
                Call(true, 0x0000, 20, 0x0000),
                Call(true, 0x0000, 0, 0x0000),
            ],
        );
    }

    #[test]
    fn what_comes_and_goes_between_two_calls() {
        run(
            &[7],
            &[
                // An error reset before any call: never delivered.
                Rx(7, OVER_VOLTAGE),
                Rx(7, RESET),
                Call(true, 0x0000, 0, 0x0000),
                // A delivered error replaced by a new one before the next
                // call: the new error, no reset notification in between.
                Rx(7, OVER_VOLTAGE),
                Call(true, 0x0000, 7, 0x3210),
                Rx(7, RESET),
                Rx(7, PDO_LENGTH),
                Call(true, 0x0000, 7, 0x8210),
                Rx(7, RESET),
                Call(true, 0x0000, 7, 0x0000),
                Call(true, 0x0000, 0, 0x0000),
            ],
        );
    }

    #[test]
    fn two_blocks_over_one_storage_each_deliver_the_reset() {
        let node = n(3);
        let mut storage = EmcyStorage::with_devices(DeviceSet::new().with(node));
        let (mut plc, mut hmi) = (RecvEmcy::new(), RecvEmcy::default());
        let error = Emcy::parse(&MEMORY).unwrap();
        storage.receive(node, error);
        assert_eq!(plc.call(&storage).unwrap().device(), Some(node));
        assert_eq!(hmi.call(&storage).unwrap().device(), Some(node));
        storage.receive(node, Emcy::parse(&RESET).unwrap());
        for block in [&mut plc, &mut hmi] {
            assert!(matches!(
                block.call(&storage),
                Ok(RecvEmcyResult::ResetError { .. })
            ));
            assert_eq!(block.call(&storage), Ok(RecvEmcyResult::AllClear));
        }
    }

    #[test]
    fn slot_updates() {
        let node = n(1);
        let mut storage = EmcyStorage::default();
        let first = Emcy::parse(&OVER_TEMPERATURE).unwrap();
        let later = Emcy::parse(&LIFE_GUARD).unwrap();
        let reset = Emcy::parse(&RESET).unwrap();
        let table = [
            (first, SlotUpdate::RootCause),
            (later, SlotUpdate::FollowUp { root_cause: first }),
            (later, SlotUpdate::FollowUp { root_cause: first }),
            (
                reset,
                SlotUpdate::Reset {
                    cleared: Some(first),
                },
            ),
            (reset, SlotUpdate::Reset { cleared: None }),
            (later, SlotUpdate::RootCause),
        ];
        for (i, (emcy, update)) in table.into_iter().enumerate() {
            assert_eq!(storage.receive(node, emcy), update, "row {i}");
        }
        assert_eq!(storage.devices_in_error(), DeviceSet::new().with(node));
        assert_eq!(storage.devices(), DeviceSet::EMPTY);
    }

    #[test]
    fn fresh_storage_holds_no_error_everywhere() {
        let storage = EmcyStorage::new();
        for node in NodeId::all() {
            assert_eq!(storage.slot(node).to_bytes(), [0; 8]);
            assert_eq!(storage.root_cause(node), None);
            assert!(!storage.is_configured(node));
        }
        let all = EmcyStorage::with_devices(DeviceSet::ALL);
        assert!(NodeId::all().all(|node| all.recv_emcy_dev(node) == Ok(None)));
        assert_eq!(RecvEmcy::new().call(&all), Ok(RecvEmcyResult::AllClear));
    }

    #[test]
    fn device_set_first_from() {
        let set: DeviceSet = [n(3), n(64), n(127)].into_iter().collect();
        // (start, first device at or after start, wrapping)
        let table = [(1, 3), (3, 3), (4, 64), (64, 64), (65, 127), (127, 127)];
        for (start, first) in table {
            assert_eq!(set.first_from(n(start)), Some(n(first)), "from {start}");
        }
        let without_127 = set.without(n(127));
        assert_eq!(without_127.first_from(n(65)), Some(n(3)));
        assert_eq!(without_127.first_from(n(127)), Some(n(3)));
        assert_eq!(DeviceSet::EMPTY.first_from(n(1)), None);
        assert_eq!(DeviceSet::ALL.first_from(n(127)), Some(n(127)));
    }

    #[test]
    fn device_set_operations() {
        let mut set = DeviceSet::new();
        assert!(set.is_empty());
        assert!(set.insert(n(127)));
        assert!(!set.insert(n(127)));
        assert!(set.insert(n(1)));
        assert_eq!(set.len(), 2);
        assert_eq!(set.iter().collect::<Vec<_>>(), [n(1), n(127)]);
        assert!(set.remove(n(1)));
        assert!(!set.remove(n(1)));
        assert_eq!(set, DeviceSet::EMPTY.with(n(127)));
        set.extend([n(2), n(3)]);
        assert_eq!(set.intersection(DeviceSet::EMPTY.with(n(3))).len(), 1);
        assert_eq!(set.union(DeviceSet::ALL), DeviceSet::ALL);
        assert_eq!(DeviceSet::ALL.len(), 127);
        assert_eq!(
            DeviceSet::ALL.iter().collect::<Vec<_>>(),
            NodeId::all().collect::<Vec<_>>()
        );
    }

    /// CiA 405 `CANOPEN_KERNEL_ERROR` (CODESYS for 0x0024): (value, name).
    const KERNEL_ERRORS: [(u16, &str); 7] = [
        (0x0000, "CANOPEN_KERNEL_NO_ERROR"),
        (0x0001, "CANOPEN_KERNEL_OTHER_ERROR"),
        (0x0002, "CANOPEN_KERNEL_DATA_OVERFLOW"),
        (0x0003, "CANOPEN_KERNEL_TIMEOUT"),
        (0x0010, "CANOPEN_KERNEL_CANBUS_OFF"),
        (0x0011, "CANOPEN_KERNEL_CAN_ERROR_PASSIVE"),
        (0x0024, "CANOPEN_NODEID_UNKNOWN"),
    ];

    #[test]
    fn kernel_error_table() {
        for (code, name) in KERNEL_ERRORS {
            let error = KernelError::from_code(code);
            assert_eq!(error.name(), name);
            assert!(!matches!(error, KernelError::Unlisted(_)), "{name}");
            assert_eq!(error.is_error(), code != 0);
        }
        for code in 0..=u16::MAX {
            let error = KernelError::from(code);
            assert_eq!(u16::from(error), code);
            let listed = KERNEL_ERRORS.iter().any(|&(c, _)| c == code);
            assert_eq!(matches!(error, KernelError::Unlisted(_)), !listed);
        }
    }

    #[test]
    fn kernel_error_texts() {
        let table = [
            (0x0000, "no error"),
            (0x0024, "unknown node-ID"),
            (0x0005, "reserved for further SDO errors 0x0005"),
            (0x0012, "reserved for further kernel errors 0x0012"),
            (0x0020, "unassigned 0x0020"),
            (0x0042, "manufacturer-specific error 0x0042"),
            (0x0100, "reserved by CiA 0x0100"),
        ];
        for (code, text) in table {
            assert_eq!(KernelError::from_code(code).to_string(), text);
        }
        assert_eq!(KernelError::Unlisted(0x0042).name(), "unlisted");
    }

    #[test]
    fn outputs_of_an_error_of_the_call() {
        let raw = RecvEmcyOutputs::from(Err(KernelError::NodeIdUnknown));
        assert_eq!(
            (raw.confirm(), raw.error(), raw.device(), raw.errorinfo()),
            (false, KernelError::NodeIdUnknown, 0, NO_ERROR)
        );
        assert!(!raw.emergency_received());
        let dev = EmcyStorage::new().recv_emcy_dev_outputs(n(1));
        assert_eq!(
            (dev.confirm(), dev.error(), dev.errorinfo()),
            (false, KernelError::NodeIdUnknown, NO_ERROR)
        );
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::recv_emcy::{device_set, ops, Op};

    /// CiA 405's recommendation read literally, one device at a time: the
    /// first error since the last reset per device, the last reset, and a
    /// linear scan of 127 positions from where the last call stopped.
    struct Model {
        first_error: [Option<Emcy>; DEVICES],
        last_reset: [Emcy; DEVICES],
        configured: [bool; DEVICES],
        last_delivered_error: [bool; DEVICES],
        next: usize,
    }

    impl Model {
        fn new(devices: DeviceSet) -> Self {
            let mut configured = [false; DEVICES];
            for node in devices.iter() {
                configured[node.index()] = true;
            }
            Model {
                first_error: [None; DEVICES],
                last_reset: [NO_ERROR; DEVICES],
                configured,
                last_delivered_error: [false; DEVICES],
                next: 0,
            }
        }

        fn receive(&mut self, node: NodeId, emcy: Emcy) {
            let i = node.index();
            if emcy.is_reset() {
                self.first_error[i] = None;
                self.last_reset[i] = emcy;
            } else if self.first_error[i].is_none() {
                self.first_error[i] = Some(emcy);
            }
        }

        fn call(&mut self) -> Result<RecvEmcyResult, KernelError> {
            if !self.configured.contains(&true) {
                return Err(KernelError::NodeIdUnknown);
            }
            for step in 0..DEVICES {
                let i = (self.next + step) % DEVICES;
                let device = NodeId::new(i as u8 + 1).unwrap();
                if !self.configured[i] {
                    continue;
                }
                if let Some(emcy) = self.first_error[i] {
                    self.last_delivered_error[i] = true;
                    self.next = (i + 1) % DEVICES;
                    return Ok(RecvEmcyResult::Error { device, emcy });
                }
                if self.last_delivered_error[i] {
                    self.last_delivered_error[i] = false;
                    self.next = (i + 1) % DEVICES;
                    return Ok(RecvEmcyResult::ResetError {
                        device,
                        reset: self.last_reset[i],
                    });
                }
            }
            Ok(RecvEmcyResult::AllClear)
        }
    }

    /// What `RECV_EMCY` delivered last for a device.
    #[derive(Clone, Copy, PartialEq, Eq)]
    enum Last {
        Nothing,
        Error,
        Reset,
    }

    proptest! {
        /// Over random receives, calls and configuration changes: RECV_EMCY
        /// never delivers a reset of a device twice without an error of it
        /// in between (nor one with no error before it), delivers DEVICE = 0
        /// only when no configured device holds an error, and delivers what
        /// the literal reading of CiA 405 delivers; RECV_EMCY_DEV always
        /// returns the first error since the last reset. Nothing panics.
        #[test]
        fn recv_emcy_over_random_sequences(devices in device_set(), ops in ops()) {
            let mut storage = EmcyStorage::with_devices(devices);
            let mut block = RecvEmcy::new();
            let mut model = Model::new(devices);
            let mut last = [Last::Nothing; DEVICES];
            for op in ops {
                match op {
                    Op::Receive(node, emcy) => {
                        storage.receive(node, emcy);
                        model.receive(node, emcy);
                    }
                    Op::AddDevice(node) => {
                        storage.add_device(node);
                        model.configured[node.index()] = true;
                    }
                    Op::RemoveDevice(node) => {
                        storage.remove_device(node);
                        model.configured[node.index()] = false;
                    }
                    Op::CallDev(node) => {
                        let expected = if storage.is_configured(node) {
                            Ok(model.first_error[node.index()])
                        } else {
                            Err(KernelError::NodeIdUnknown)
                        };
                        prop_assert_eq!(storage.recv_emcy_dev(node), expected);
                        let raw = storage.recv_emcy_dev_outputs(node);
                        prop_assert_eq!(raw.confirm(), expected.is_ok());
                        prop_assert_eq!(
                            raw.emergency_received(),
                            matches!(expected, Ok(Some(_)))
                        );
                    }
                    Op::Call => {
                        let in_error = storage.devices().intersection(storage.devices_in_error());
                        let result = block.clone().call(&storage);
                        let raw = block.call_outputs(&storage);
                        prop_assert_eq!(RecvEmcyOutputs::from(result), raw);
                        prop_assert_eq!(result, model.call());
                        match result {
                            Ok(RecvEmcyResult::Error { device, emcy }) => {
                                prop_assert!(!emcy.is_reset());
                                prop_assert_eq!(storage.recv_emcy_dev(device), Ok(Some(emcy)));
                                last[device.index()] = Last::Error;
                            }
                            Ok(RecvEmcyResult::ResetError { device, reset }) => {
                                prop_assert!(reset.is_reset());
                                prop_assert!(
                                    last[device.index()] == Last::Error,
                                    "reset of {} without an error delivered before it",
                                    device
                                );
                                last[device.index()] = Last::Reset;
                            }
                            Ok(RecvEmcyResult::AllClear) => {
                                prop_assert!(in_error.is_empty(), "all clear while {:?} hold errors", in_error);
                                prop_assert_eq!((raw.device(), raw.errorinfo()), (0, NO_ERROR));
                            }
                            Err(error) => {
                                prop_assert_eq!(error, KernelError::NodeIdUnknown);
                                prop_assert!(storage.devices().is_empty());
                            }
                        }
                    }
                }
            }
        }

        /// Every configured device holding an error is delivered within as
        /// many calls as there are configured devices.
        #[test]
        fn every_pending_error_is_delivered_within_one_scan(devices in device_set(), ops in ops()) {
            let mut storage = EmcyStorage::with_devices(devices);
            let mut block = RecvEmcy::new();
            for op in ops {
                match op {
                    Op::Receive(node, emcy) => { storage.receive(node, emcy); }
                    Op::AddDevice(node) => { storage.add_device(node); }
                    Op::RemoveDevice(node) => { storage.remove_device(node); }
                    Op::Call => { let _ = block.call(&storage); }
                    Op::CallDev(_) => {}
                }
            }
            let pending = storage.devices().intersection(storage.devices_in_error());
            let mut seen = DeviceSet::new();
            for _ in 0..storage.devices().len() {
                if let Ok(RecvEmcyResult::Error { device, .. }) = block.call(&storage) {
                    seen.insert(device);
                }
            }
            prop_assert_eq!(seen, pending);
        }
    }
}

impl fmt::Display for RecvEmcyResult {
    /// `device 5: EMCY 0x8130 …`, `device 5: reset (EMCY 0x0000 …)`,
    /// `all clear`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RecvEmcyResult::Error { device, emcy } => write!(f, "device {device}: {emcy}"),
            RecvEmcyResult::ResetError { device, reset } => {
                write!(f, "device {device}: reset ({reset})")
            }
            RecvEmcyResult::AllClear => f.write_str("all clear"),
        }
    }
}
