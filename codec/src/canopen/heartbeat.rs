//! The heartbeat protocol as pure state machines: the producer's schedule
//! (object 1017h) and the consumer's monitor (object 1016h)
//! (CiA 301 §7.2.8.3.2.2; docs/canopen.md#error-control).
//!
//! Time is a [`Duration`] since the caller's epoch on its monotonic clock,
//! passed with every call; the object dictionary values are milliseconds
//! and the constructors that take them say so (`from_millis`). Nothing
//! reads a clock, sleeps or allocates, so the same code runs on a
//! microcontroller (poll from a timer tick), in a PLC runtime (poll every
//! cycle) and in a log analyser (feed the log's frames with their
//! timestamps, and poll at each timestamp before delivering its frame).
//!
//! ```
//! use core::time::Duration;
//! use motionwire_codec::canopen::{
//!     ConsumerEntry, HeartbeatConsumer, HeartbeatEvent, NmtState, NodeId,
//! };
//!
//! let ms = Duration::from_millis;
//! let node = NodeId::new(5).unwrap();
//! let mut consumer = HeartbeatConsumer::<4>::with_capacity();
//! consumer.set_entry(ConsumerEntry::from_millis(node, 150))?; // 1016h: 150 ms
//!
//! // Monitoring starts at the first heartbeat.
//! assert!(consumer.on_heartbeat(ms(1_000), node, NmtState::Operational).is_empty());
//! assert_eq!(consumer.poll(ms(1_150)).next(), None); // exactly at the deadline: in time
//! let timeout = consumer.poll(ms(1_150) + Duration::from_micros(1)).next();
//! assert_eq!(
//!     timeout,
//!     Some(HeartbeatEvent::Timeout {
//!         node,
//!         last_heartbeat: ms(1_000),
//!         deadline: ms(1_150),
//!     })
//! );
//! assert_eq!(consumer.poll(ms(9_000)).next(), None); // reported once
//!
//! let recovered: Vec<_> = consumer.on_heartbeat(ms(1_400), node, NmtState::Operational).collect();
//! assert_eq!(recovered[0].gap(), Some(ms(400))); // the gap after the heartbeat at 1.0 s
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;
use core::time::Duration;

use super::error_control::{millis, Events};
use super::{Heartbeat, NmtState, NodeId};
use crate::{RangeError, Result};

/// The heartbeat producer's schedule, object 1017h (CiA 301 §7.2.8.3.2.2
/// and object 1017h; docs/canopen.md#error-control).
///
/// [`HeartbeatProducer::poll`] says when to send: it returns the
/// [`Heartbeat`] to send (bit 7 never set) once per producer time. A
/// producer time of 0 disables the heartbeat.
///
/// ```
/// use core::time::Duration;
/// use motionwire_codec::canopen::{HeartbeatProducer, NmtState};
///
/// let us = Duration::from_micros;
/// let mut producer = HeartbeatProducer::from_millis(100); // 1017h = 100 ms
/// // The first poll sends at once, then every 100 ms.
/// assert!(producer.poll(us(5_000), NmtState::PreOperational).is_some());
/// assert!(producer.poll(us(104_999), NmtState::PreOperational).is_none());
/// let heartbeat = producer.poll(us(105_000), NmtState::Operational).unwrap();
/// assert_eq!(heartbeat.to_bytes(), [0x05]);
/// assert_eq!(producer.next_due(), Some(us(205_000)));
///
/// assert!(HeartbeatProducer::new(Duration::ZERO).poll(us(5_000), NmtState::Operational).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HeartbeatProducer {
    /// The producer time; 0 = off.
    period: Duration,
    /// When the next heartbeat is due; `None` before the first,
    /// which is due at once.
    next_due: Option<Duration>,
}

impl HeartbeatProducer {
    /// Return a producer sending a heartbeat every `period` (zero = off).
    /// Its first poll sends at once.
    #[inline]
    #[must_use]
    pub const fn new(period: Duration) -> Self {
        HeartbeatProducer {
            period,
            next_due: None,
        }
    }

    /// Return a producer with the producer heartbeat time of object 1017h,
    /// `producer_time_ms` milliseconds (0 = off).
    #[inline]
    #[must_use]
    pub const fn from_millis(producer_time_ms: u16) -> Self {
        Self::new(millis(producer_time_ms as u32))
    }

    /// Return the producer time in [`Duration`]; 0 when the heartbeat is off.
    #[inline]
    #[must_use]
    pub const fn producer_time(&self) -> Duration {
        self.period
    }

    /// Return whether the heartbeat is on (1017h ≠ 0).
    #[inline]
    #[must_use]
    pub const fn is_enabled(&self) -> bool {
        !self.period.is_zero()
    }

    /// Write object 1017h (milliseconds; 0 = off): the next poll sends at
    /// once, then the new period applies.
    #[inline]
    pub fn set_producer_time(&mut self, producer_time_ms: u16) {
        *self = Self::from_millis(producer_time_ms);
    }

    /// Schedule the next heartbeat one producer time after `now`: call
    /// it after sending the boot-up message, which stands in for the first
    /// heartbeat.
    #[inline]
    pub fn restart(&mut self, now: Duration) {
        self.next_due = Some(now.saturating_add(self.period));
    }

    /// Return when the next heartbeat is due, `None` when the heartbeat
    /// is off; before the first heartbeat this is 0 (due at once).
    #[inline]
    #[must_use]
    pub const fn next_due(&self) -> Option<Duration> {
        match (self.period.is_zero(), self.next_due) {
            (true, _) => None,
            (false, Some(due)) => Some(due),
            (false, None) => Some(Duration::ZERO),
        }
    }

    /// At `now` in NMT state `state`, return the heartbeat to send, if
    /// one is due. The first heartbeat is due at the first poll and sets the
    /// cadence.
    ///
    /// The schedule keeps its cadence when a poll comes a little late
    /// (the next is due one period after the previous due time); when a poll
    /// comes more than a period late it sends one heartbeat, not a burst, and
    /// the next is due one period after `now`.
    #[must_use = "a heartbeat that is due is returned only once"]
    pub fn poll(&mut self, now: Duration, state: NmtState) -> Option<Heartbeat> {
        if self.period.is_zero() {
            return None;
        }
        let next = match self.next_due {
            Some(due) if now < due => return None,
            Some(due) => due.saturating_add(self.period),
            None => now,
        };
        self.next_due = Some(if next > now {
            next
        } else {
            now.saturating_add(self.period)
        });
        Some(Heartbeat::new(state))
    }
}

/// One entry of object 1016h, consumer heartbeat time: the node to monitor
/// and the time within which its heartbeat must come (CiA 301, object 1016h;
/// docs/canopen.md#error-control).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ConsumerEntry {
    /// The monitored node (bits 16–23 of the entry).
    pub node: NodeId,
    /// The consumer heartbeat time in ms (bits 0–15); 0 means the entry is
    /// not used.
    pub time_ms: u16,
}

impl ConsumerEntry {
    /// Return the entry monitoring `node` with consumer time `time_ms`
    /// milliseconds, as object 1016h holds it.
    #[inline]
    #[must_use]
    pub const fn from_millis(node: NodeId, time_ms: u16) -> Self {
        ConsumerEntry { node, time_ms }
    }

    /// Decode a 1016h sub-index value: bits 16–23 node-ID, bits 0–15 time in
    /// ms, bits 24–31 reserved (not read). `None` when the entry is not used:
    /// time 0, or node-ID 0 or above 127 (CiA 301, object 1016h).
    ///
    /// ```
    /// use motionwire_codec::canopen::{ConsumerEntry, NodeId};
    ///
    /// let entry = ConsumerEntry::from_od_value(0x0031_03E8).unwrap();
    /// assert_eq!(entry, ConsumerEntry::from_millis(NodeId::new(0x31).unwrap(), 1000));
    /// assert_eq!(entry.to_od_value(), 0x0031_03E8);
    /// assert_eq!(ConsumerEntry::from_od_value(0x0031_0000), None);
    /// ```
    #[inline]
    #[must_use]
    pub const fn from_od_value(raw: u32) -> Option<Self> {
        let time_ms = (raw & 0xFFFF) as u16;
        match NodeId::new(((raw >> 16) & 0xFF) as u8) {
            Some(node) if time_ms != 0 => Some(ConsumerEntry { node, time_ms }),
            _ => None,
        }
    }

    /// Encode the entry as a 1016h sub-index value (reserved bits 0).
    #[inline]
    #[must_use]
    pub const fn to_od_value(self) -> u32 {
        (self.node.get() as u32) << 16 | self.time_ms as u32
    }

    /// Return the consumer time in [`Duration`].
    #[inline]
    #[must_use]
    pub const fn consumer_time(self) -> Duration {
        millis(self.time_ms as u32)
    }
}

/// Where the consumer stands with one node (CiA 301 §7.2.8.3.2.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MonitorState {
    /// No heartbeat seen yet (or a boot-up since the last one): the node's
    /// state is unknown and it is not monitored ("monitoring starts after
    /// the reception of the first heartbeat").
    Waiting,
    /// Monitored: the last heartbeat came at `last_heartbeat` in
    /// `state`; the next is due within the consumer time.
    Active {
        /// When the last heartbeat came.
        last_heartbeat: Duration,
        /// The NMT state it reported.
        state: NmtState,
    },
    /// The consumer time passed after the heartbeat at `last_heartbeat`
    /// and a [`HeartbeatEvent::Timeout`] was reported.
    TimedOut {
        /// When the last heartbeat before the timeout came.
        last_heartbeat: Duration,
    },
}

impl fmt::Display for MonitorState {
    /// Format the state in the words of [`HeartbeatEvent`]'s text, times in
    /// µs on the caller's clock: `waiting for a heartbeat`, `active:
    /// operational at 1000000 µs`, `timed out after the heartbeat at 1000000
    /// µs`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            MonitorState::Waiting => f.write_str("waiting for a heartbeat"),
            MonitorState::Active {
                last_heartbeat,
                state,
            } => write!(f, "active: {state} at {} µs", last_heartbeat.as_micros()),
            MonitorState::TimedOut { last_heartbeat } => write!(
                f,
                "timed out after the heartbeat at {} µs",
                last_heartbeat.as_micros()
            ),
        }
    }
}

/// What the heartbeat consumer reports (CiA 301 §7.2.8.3.2.2;
/// docs/canopen.md#error-control).
///
/// Every time is on the caller's clock (a `Duration` since its epoch). For a log analyser: a
/// `Timeout` says "no heartbeat in the gap after the heartbeat at
/// `last_heartbeat`", and its `deadline` is `last_heartbeat` + consumer time
/// whenever the poll happened; a `Recovered` or `RemoteReset` closes that
/// gap at `at`, so the gap is `at − last_heartbeat` ([`HeartbeatEvent::gap`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum HeartbeatEvent {
    /// Heartbeat event: no heartbeat within the consumer time after the one
    /// at `last_heartbeat`. Reported once until the node is heard again.
    Timeout {
        /// The monitored node.
        node: NodeId,
        /// When its last heartbeat came.
        last_heartbeat: Duration,
        /// `last_heartbeat` + consumer time: the instant the timeout
        /// occurred.
        deadline: Duration,
    },
    /// A heartbeat came after a timeout: the node is monitored again.
    Recovered {
        /// The monitored node.
        node: NodeId,
        /// The last heartbeat before the timeout.
        last_heartbeat: Duration,
        /// When the heartbeat that ended the gap came.
        at: Duration,
        /// The NMT state that heartbeat reported.
        state: NmtState,
    },
    /// A boot-up message (state 0x00) came from a node that was monitored
    /// (active or timed out): the node was reset. Monitoring stops until its
    /// next heartbeat, as after start-up.
    RemoteReset {
        /// The monitored node.
        node: NodeId,
        /// The node's last heartbeat before the boot-up.
        last_heartbeat: Duration,
        /// When the boot-up message came.
        at: Duration,
    },
    /// A heartbeat came from a node that the consumer would monitor (see
    /// [`HeartbeatConsumer::monitor_unconfigured`]) but every entry is in
    /// use: the node is not monitored. Reported once per node, so that no
    /// node goes unmonitored silently.
    CapacityExceeded {
        /// The node that is not monitored.
        node: NodeId,
        /// When its heartbeat came.
        at: Duration,
    },
}

impl HeartbeatEvent {
    /// Return the node the event is about.
    #[inline]
    #[must_use]
    pub const fn node(&self) -> NodeId {
        match *self {
            HeartbeatEvent::Timeout { node, .. }
            | HeartbeatEvent::Recovered { node, .. }
            | HeartbeatEvent::RemoteReset { node, .. }
            | HeartbeatEvent::CapacityExceeded { node, .. } => node,
        }
    }

    /// Return when the event happened: the deadline of a timeout, the
    /// arrival of the message otherwise.
    #[inline]
    #[must_use]
    pub const fn at(&self) -> Duration {
        match *self {
            HeartbeatEvent::Timeout { deadline, .. } => deadline,
            HeartbeatEvent::Recovered { at, .. }
            | HeartbeatEvent::RemoteReset { at, .. }
            | HeartbeatEvent::CapacityExceeded { at, .. } => at,
        }
    }

    /// Return the node's last heartbeat before the event, when there
    /// was one.
    #[inline]
    #[must_use]
    pub const fn last_heartbeat(&self) -> Option<Duration> {
        match *self {
            HeartbeatEvent::Timeout { last_heartbeat, .. }
            | HeartbeatEvent::Recovered { last_heartbeat, .. }
            | HeartbeatEvent::RemoteReset { last_heartbeat, .. } => Some(last_heartbeat),
            HeartbeatEvent::CapacityExceeded { .. } => None,
        }
    }

    /// Return the gap, between the last heartbeat and the event's
    /// [`at`](HeartbeatEvent::at): the consumer time for a timeout, the whole
    /// silence for a recovery or remote reset.
    #[inline]
    #[must_use]
    pub const fn gap(&self) -> Option<Duration> {
        match self.last_heartbeat() {
            Some(last) => Some(self.at().saturating_sub(last)),
            None => None,
        }
    }

    /// Return the event's name: `timeout`, `recovered`, `remote_reset` or
    /// `capacity_exceeded`.
    #[inline]
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            HeartbeatEvent::Timeout { .. } => "timeout",
            HeartbeatEvent::Recovered { .. } => "recovered",
            HeartbeatEvent::RemoteReset { .. } => "remote_reset",
            HeartbeatEvent::CapacityExceeded { .. } => "capacity_exceeded",
        }
    }
}

impl fmt::Display for HeartbeatEvent {
    /// Format the event as e.g. `node 5: timeout after the heartbeat at 1000000 µs`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let node = self.node();
        let us = |t: Duration| t.as_micros();
        match *self {
            HeartbeatEvent::Timeout { last_heartbeat, .. } => write!(
                f,
                "node {node}: timeout after the heartbeat at {} µs",
                us(last_heartbeat)
            ),
            HeartbeatEvent::Recovered {
                last_heartbeat, at, ..
            } => write!(
                f,
                "node {node}: recovered at {} µs after the heartbeat at {} µs",
                us(at),
                us(last_heartbeat)
            ),
            HeartbeatEvent::RemoteReset { at, .. } => {
                write!(f, "node {node}: remote reset (boot-up) at {} µs", us(at))
            }
            HeartbeatEvent::CapacityExceeded { at, .. } => write!(
                f,
                "node {node}: not monitored, every consumer entry in use ({} µs)",
                us(at)
            ),
        }
    }
}

/// The events one heartbeat produced: at most two (a timeout whose deadline
/// passed without a poll, then a recovery or remote reset).
pub type HeartbeatEvents = Events<HeartbeatEvent, 2>;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Monitored {
    node: NodeId,
    consumer_time: Duration,
    /// Set by [`HeartbeatConsumer::set_entry`]; `false` for a node taken up by
    /// [`HeartbeatConsumer::monitor_unconfigured`].
    configured: bool,
    state: MonitorState,
}

impl Monitored {
    /// Mark the node timed out when `now` is past its deadline, returning
    /// the timeout event once.
    fn expire(&mut self, now: Duration) -> Option<HeartbeatEvent> {
        match self.state {
            MonitorState::Active { last_heartbeat, .. } => {
                let deadline = last_heartbeat.saturating_add(self.consumer_time);
                if now > deadline {
                    self.state = MonitorState::TimedOut { last_heartbeat };
                    Some(HeartbeatEvent::Timeout {
                        node: self.node,
                        last_heartbeat,
                        deadline,
                    })
                } else {
                    None
                }
            }
            MonitorState::Waiting | MonitorState::TimedOut { .. } => None,
        }
    }

    /// Take a heartbeat (or boot-up) that came at `now`.
    fn receive(&mut self, now: Duration, state: NmtState) -> Option<HeartbeatEvent> {
        let node = self.node;
        let (next, event) = match (self.state, state) {
            (MonitorState::Waiting, NmtState::BootUp) => (MonitorState::Waiting, None),
            (
                MonitorState::Active { last_heartbeat, .. }
                | MonitorState::TimedOut { last_heartbeat },
                NmtState::BootUp,
            ) => (
                MonitorState::Waiting,
                Some(HeartbeatEvent::RemoteReset {
                    node,
                    last_heartbeat,
                    at: now,
                }),
            ),
            (MonitorState::TimedOut { last_heartbeat }, state) => (
                MonitorState::Active {
                    last_heartbeat: now,
                    state,
                },
                Some(HeartbeatEvent::Recovered {
                    node,
                    last_heartbeat,
                    at: now,
                    state,
                }),
            ),
            (MonitorState::Waiting | MonitorState::Active { .. }, state) => (
                MonitorState::Active {
                    last_heartbeat: now,
                    state,
                },
                None,
            ),
        };
        self.state = next;
        event
    }

    fn deadline(&self) -> Option<Duration> {
        match self.state {
            MonitorState::Active { last_heartbeat, .. } => {
                Some(last_heartbeat.saturating_add(self.consumer_time))
            }
            MonitorState::Waiting | MonitorState::TimedOut { .. } => None,
        }
    }
}

/// The heartbeat consumer: monitors up to `N` nodes, each with its consumer
/// time (object 1016h; CiA 301 §7.2.8.3.2.2; docs/canopen.md#error-control).
///
/// Behaviour, per node:
///
/// | monitor state | input at `now` | next state | event |
/// |---|---|---|---|
/// | waiting | heartbeat, state ≠ boot-up | active | — |
/// | waiting | boot-up | waiting | — |
/// | active | heartbeat, state ≠ boot-up, `now` ≤ deadline | active | — |
/// | active | poll, `now` > last + consumer time | timed out | [`Timeout`](HeartbeatEvent::Timeout) |
/// | timed out | poll | timed out | — (once only) |
/// | timed out | heartbeat, state ≠ boot-up | active | [`Recovered`](HeartbeatEvent::Recovered) |
/// | active or timed out | boot-up | waiting | [`RemoteReset`](HeartbeatEvent::RemoteReset) |
///
/// A heartbeat or boot-up that arrives after the deadline without a poll in
/// between first times the node out, so it returns `Timeout` followed by
/// `Recovered` or `RemoteReset`. A heartbeat from a node without an entry is
/// ignored, unless [`HeartbeatConsumer::monitor_unconfigured`] gave a time
/// for such nodes.
///
/// **Decision:** after a boot-up the node is monitored again from its next
/// heartbeat, not from the boot-up message: a node that has just been reset
/// may need its producer time configured first (as CANopenNode does).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HeartbeatConsumer<const N: usize = DEFAULT_CONSUMER_ENTRIES> {
    entries: [Option<Monitored>; N],
    /// The consumer time for nodes without an entry; 0 = ignore them.
    unconfigured_time: Duration,
    /// Bit n-1 set: `CapacityExceeded` already reported for node n.
    capacity_reported: u128,
}

impl<const N: usize> Default for HeartbeatConsumer<N> {
    fn default() -> Self {
        Self::with_capacity()
    }
}

/// The number of nodes a [`HeartbeatConsumer::new`] can monitor: every
/// node-ID, 127 (object 1016h has up to 127 entries, CiA 301).
pub const DEFAULT_CONSUMER_ENTRIES: usize = 127;

impl HeartbeatConsumer<DEFAULT_CONSUMER_ENTRIES> {
    /// Return a consumer with no entries that can monitor every node
    /// ([`DEFAULT_CONSUMER_ENTRIES`]), written without naming a capacity, as
    /// `HashMap::new` is.
    ///
    /// ```
    /// use motionwire_codec::canopen::HeartbeatConsumer;
    ///
    /// let consumer = HeartbeatConsumer::new();
    /// assert_eq!(consumer.capacity(), 127);
    /// ```
    #[inline]
    #[must_use]
    pub const fn new() -> Self {
        Self::with_capacity()
    }
}

impl<const N: usize> HeartbeatConsumer<N> {
    /// Return a consumer with no entries (every 1016h sub-index 0) that can
    /// monitor `N` nodes, e.g. `HeartbeatConsumer::<4>::with_capacity()`.
    #[inline]
    #[must_use]
    pub const fn with_capacity() -> Self {
        HeartbeatConsumer {
            entries: [None; N],
            unconfigured_time: Duration::ZERO,
            capacity_reported: 0,
        }
    }

    /// Return the number of nodes the consumer can monitor, `N`.
    #[inline]
    #[must_use]
    pub const fn capacity(&self) -> usize {
        N
    }

    /// Configure a 1016h entry: monitor `entry.node` with `entry.time_ms`.
    /// An existing entry for the node is replaced (its monitoring starts over
    /// at the next heartbeat); a time of 0 removes the entry (CiA 301: "if
    /// the consumer heartbeat time is 0 the entry is not used").
    ///
    /// When all `N` entries are configured, this is a
    /// [`RangeError`]; a node taken up by
    /// [`HeartbeatConsumer::monitor_unconfigured`] gives its place to a
    /// configured one.
    pub fn set_entry(&mut self, entry: ConsumerEntry) -> Result<(), RangeError> {
        if entry.time_ms == 0 {
            self.remove(entry.node);
            return Ok(());
        }
        let monitored = Monitored {
            node: entry.node,
            consumer_time: entry.consumer_time(),
            configured: true,
            state: MonitorState::Waiting,
        };
        let slot = match self.position(entry.node) {
            Some(i) => self.entries.get_mut(i),
            None => {
                let free = self.entries.iter().position(Option::is_none).or_else(|| {
                    self.entries
                        .iter()
                        .position(|e| matches!(e, Some(m) if !m.configured))
                });
                free.and_then(|i| self.entries.get_mut(i))
            }
        };
        match slot {
            Some(slot) => {
                *slot = Some(monitored);
                Ok(())
            }
            None => Err(RangeError {
                what: What::HeartbeatConsumerEntries,
                found: u32::try_from(N).unwrap_or(u32::MAX).saturating_add(1),
                min: 0,
                max: u32::try_from(N).unwrap_or(u32::MAX),
            }),
        }
    }

    /// Stop monitoring `node`; return whether it was monitored.
    pub fn remove(&mut self, node: NodeId) -> bool {
        match self.position(node).and_then(|i| self.entries.get_mut(i)) {
            Some(slot) => {
                *slot = None;
                true
            }
            None => false,
        }
    }

    /// Also monitor every node without an entry, from its first heartbeat,
    /// with consumer time `time_ms` (milliseconds; 0 = ignore such nodes,
    /// the default). Such nodes take free entries; when none is left the
    /// node is reported once as [`HeartbeatEvent::CapacityExceeded`].
    ///
    /// This is for a log analyser or a diagnostic tool that does not know
    /// the network's 1016h configuration.
    #[inline]
    pub fn monitor_unconfigured(&mut self, time: Duration) {
        self.unconfigured_time = time;
    }

    /// Return where the consumer stands with `node`, `None` when it has no
    /// entry.
    #[must_use]
    pub fn monitor_state(&self, node: NodeId) -> Option<MonitorState> {
        self.find(node).map(|m| m.state)
    }

    /// Return the consumer time of `node` `None` when it has no entry.
    #[must_use]
    pub fn consumer_time(&self, node: NodeId) -> Option<Duration> {
        self.find(node).map(|m| m.consumer_time)
    }

    /// Return the earliest deadline among the active nodes: the next
    /// time a [`HeartbeatConsumer::poll`] can report something. `None` when
    /// no node is active.
    pub fn next_deadline(&self) -> Option<Duration> {
        self.entries
            .iter()
            .flatten()
            .filter_map(Monitored::deadline)
            .min()
    }

    /// Take a heartbeat or boot-up message from `node` in `state` that came
    /// at `now`, and return what it means (see the table on
    /// [`HeartbeatConsumer`]).
    pub fn on_heartbeat(
        &mut self,
        now: Duration,
        node: NodeId,
        state: NmtState,
    ) -> HeartbeatEvents {
        let mut events = HeartbeatEvents::new();
        let index = match self.position(node) {
            Some(i) => i,
            None => match self.take_up(now, node) {
                Ok(i) => i,
                Err(event) => {
                    events.push_some(event);
                    return events;
                }
            },
        };
        if let Some(Some(monitored)) = self.entries.get_mut(index) {
            events.push_some(monitored.expire(now));
            events.push_some(monitored.receive(now, state));
        }
        events
    }

    /// At `now`, time out every active node whose deadline has passed
    /// and return one [`HeartbeatEvent::Timeout`] for each, in entry order.
    ///
    /// The iterator marks a node as it yields its timeout; timeouts it has
    /// not yielded when dropped are returned by the next poll.
    pub fn poll(&mut self, now: Duration) -> impl Iterator<Item = HeartbeatEvent> + '_ {
        self.entries
            .iter_mut()
            .filter_map(move |slot| slot.as_mut().and_then(|m| m.expire(now)))
    }

    fn position(&self, node: NodeId) -> Option<usize> {
        self.entries
            .iter()
            .position(|e| matches!(e, Some(m) if m.node == node))
    }

    fn find(&self, node: NodeId) -> Option<&Monitored> {
        self.entries.iter().flatten().find(|m| m.node == node)
    }

    /// Give an unconfigured node an entry, if such nodes are monitored;
    /// `Err` with the event to report (if any) when it gets none.
    fn take_up(
        &mut self,
        now: Duration,
        node: NodeId,
    ) -> core::result::Result<usize, Option<HeartbeatEvent>> {
        if self.unconfigured_time.is_zero() {
            return Err(None);
        }
        match self.entries.iter().position(Option::is_none) {
            Some(i) => {
                if let Some(slot) = self.entries.get_mut(i) {
                    *slot = Some(Monitored {
                        node,
                        consumer_time: self.unconfigured_time,
                        configured: false,
                        state: MonitorState::Waiting,
                    });
                }
                Ok(i)
            }
            None => {
                let bit = 1u128 << node.index();
                if self.capacity_reported & bit != 0 {
                    Err(None)
                } else {
                    self.capacity_reported |= bit;
                    Err(Some(HeartbeatEvent::CapacityExceeded { node, at: now }))
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn monitor_states_read_as_a_person_says_them() {
        let at = Duration::from_millis(1000);
        let table = [
            (MonitorState::Waiting, "waiting for a heartbeat"),
            (
                MonitorState::Active {
                    last_heartbeat: at,
                    state: Operational,
                },
                "active: operational at 1000000 µs",
            ),
            (
                MonitorState::TimedOut { last_heartbeat: at },
                "timed out after the heartbeat at 1000000 µs",
            ),
        ];
        for (state, text) in table {
            assert_eq!(state.to_string(), text);
        }
    }

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    /// A time in microseconds.
    fn us(n: u64) -> Duration {
        Duration::from_micros(n)
    }

    const MS: Duration = Duration::from_millis(1);
    /// One microsecond.
    const US: Duration = Duration::from_micros(1);

    use NmtState::{BootUp, Operational, PreOperational, Stopped};

    /// One step of a heartbeat-consumer scenario, as the manuals draw them.
    #[derive(Debug, Clone, Copy)]
    enum Step {
        /// A heartbeat (or boot-up) from the node.
        Rx(NodeId, NmtState),
        /// A poll.
        Poll,
    }

    /// Run `(time, step, expected events)` rows against `consumer`.
    fn run<const N: usize>(
        consumer: &mut HeartbeatConsumer<N>,
        rows: &[(Duration, Step, &[HeartbeatEvent])],
    ) {
        for (row, &(now, step, expected)) in rows.iter().enumerate() {
            let got: Vec<HeartbeatEvent> = match step {
                Step::Rx(node, state) => consumer.on_heartbeat(now, node, state).collect(),
                Step::Poll => consumer.poll(now).collect(),
            };
            assert_eq!(got, expected, "row {row}: {step:?} at {now:?}");
        }
    }

    fn consumer_of(entries: &[(u8, u16)]) -> HeartbeatConsumer<4> {
        let mut consumer = HeartbeatConsumer::with_capacity();
        for &(node, ms) in entries {
            consumer
                .set_entry(ConsumerEntry::from_millis(n(node), ms))
                .unwrap();
        }
        consumer
    }

    #[test]
    fn first_heartbeat_starts_monitoring() {
        let mut consumer = consumer_of(&[(5, 100)]);
        assert_eq!(consumer.monitor_state(n(5)), Some(MonitorState::Waiting));
        run(
            &mut consumer,
            &[
                // Nothing heard yet: no timeout however long we wait.
                (us(0), Step::Poll, &[]),
                (10_000 * MS, Step::Poll, &[]),
                (10_000 * MS, Step::Rx(n(5), PreOperational), &[]),
                (10_050 * MS, Step::Poll, &[]),
                (10_100 * MS, Step::Poll, &[]),
            ],
        );
        assert_eq!(
            consumer.monitor_state(n(5)),
            Some(MonitorState::Active {
                last_heartbeat: 10_000 * MS,
                state: PreOperational
            })
        );
        assert_eq!(consumer.next_deadline(), Some(10_100 * MS));
    }

    #[test]
    fn timeout_is_reported_exactly_once() {
        let mut consumer = consumer_of(&[(5, 100)]);
        let timeout = HeartbeatEvent::Timeout {
            node: n(5),
            last_heartbeat: 1_000 * MS,
            deadline: 1_100 * MS,
        };
        run(
            &mut consumer,
            &[
                (1_000 * MS, Step::Rx(n(5), Operational), &[]),
                (1_100 * MS, Step::Poll, &[]),
                (1_100 * MS + 1 * US, Step::Poll, &[timeout]),
                (1_100 * MS + 2 * US, Step::Poll, &[]),
                (5_000 * MS, Step::Poll, &[]),
            ],
        );
        assert_eq!(
            consumer.monitor_state(n(5)),
            Some(MonitorState::TimedOut {
                last_heartbeat: 1_000 * MS
            })
        );
        assert_eq!(consumer.next_deadline(), None);
        assert_eq!(timeout.gap(), Some(100 * MS));
        assert_eq!(timeout.at(), 1_100 * MS);
    }

    #[test]
    fn heartbeats_in_time_keep_the_node_monitored() {
        let mut consumer = consumer_of(&[(5, 100)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(5), Operational), &[]),
                (90 * MS, Step::Poll, &[]),
                (100 * MS, Step::Rx(n(5), Operational), &[]),
                (190 * MS, Step::Poll, &[]),
                (200 * MS, Step::Rx(n(5), Stopped), &[]),
                (300 * MS, Step::Poll, &[]),
            ],
        );
    }

    #[test]
    fn heartbeat_after_timeout_is_recovered() {
        let mut consumer = consumer_of(&[(5, 100)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(5), Operational), &[]),
                (
                    150 * MS,
                    Step::Poll,
                    &[HeartbeatEvent::Timeout {
                        node: n(5),
                        last_heartbeat: Duration::ZERO,
                        deadline: 100 * MS,
                    }],
                ),
                (
                    400 * MS,
                    Step::Rx(n(5), Operational),
                    &[HeartbeatEvent::Recovered {
                        node: n(5),
                        last_heartbeat: Duration::ZERO,
                        at: 400 * MS,
                        state: Operational,
                    }],
                ),
                // Monitored again from the recovering heartbeat.
                (500 * MS, Step::Poll, &[]),
                (
                    501 * MS,
                    Step::Poll,
                    &[HeartbeatEvent::Timeout {
                        node: n(5),
                        last_heartbeat: 400 * MS,
                        deadline: 500 * MS,
                    }],
                ),
            ],
        );
    }

    #[test]
    fn late_heartbeat_without_poll_is_timeout_then_recovered() {
        let mut consumer = consumer_of(&[(5, 100)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(5), Operational), &[]),
                (
                    250 * MS,
                    Step::Rx(n(5), Operational),
                    &[
                        HeartbeatEvent::Timeout {
                            node: n(5),
                            last_heartbeat: Duration::ZERO,
                            deadline: 100 * MS,
                        },
                        HeartbeatEvent::Recovered {
                            node: n(5),
                            last_heartbeat: Duration::ZERO,
                            at: 250 * MS,
                            state: Operational,
                        },
                    ],
                ),
                (300 * MS, Step::Poll, &[]),
            ],
        );
    }

    #[test]
    fn boot_up_while_monitored_is_remote_reset() {
        let mut consumer = consumer_of(&[(5, 100)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(5), Operational), &[]),
                (
                    50 * MS,
                    Step::Rx(n(5), BootUp),
                    &[HeartbeatEvent::RemoteReset {
                        node: n(5),
                        last_heartbeat: Duration::ZERO,
                        at: 50 * MS,
                    }],
                ),
                // Not monitored until its next heartbeat.
                (1_000 * MS, Step::Poll, &[]),
                (1_000 * MS, Step::Rx(n(5), BootUp), &[]),
                (1_200 * MS, Step::Rx(n(5), PreOperational), &[]),
                (
                    1_301 * MS,
                    Step::Poll,
                    &[HeartbeatEvent::Timeout {
                        node: n(5),
                        last_heartbeat: 1_200 * MS,
                        deadline: 1_300 * MS,
                    }],
                ),
                // A boot-up after a timeout is a remote reset too.
                (
                    1_400 * MS,
                    Step::Rx(n(5), BootUp),
                    &[HeartbeatEvent::RemoteReset {
                        node: n(5),
                        last_heartbeat: 1_200 * MS,
                        at: 1_400 * MS,
                    }],
                ),
            ],
        );
        assert_eq!(consumer.monitor_state(n(5)), Some(MonitorState::Waiting));
    }

    #[test]
    fn boot_up_before_first_heartbeat_is_not_an_event() {
        let mut consumer = consumer_of(&[(5, 100)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(5), BootUp), &[]),
                (500 * MS, Step::Poll, &[]),
            ],
        );
    }

    #[test]
    fn unconfigured_node_is_ignored() {
        let mut consumer = consumer_of(&[(5, 100)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(6), Operational), &[]),
                (1_000 * MS, Step::Poll, &[]),
                (1_000 * MS, Step::Rx(n(6), BootUp), &[]),
            ],
        );
        assert_eq!(consumer.monitor_state(n(6)), None);
    }

    #[test]
    fn nodes_are_monitored_independently() {
        let mut consumer = consumer_of(&[(5, 100), (6, 300)]);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(5), Operational), &[]),
                (us(0), Step::Rx(n(6), Operational), &[]),
                (
                    200 * MS,
                    Step::Poll,
                    &[HeartbeatEvent::Timeout {
                        node: n(5),
                        last_heartbeat: Duration::ZERO,
                        deadline: 100 * MS,
                    }],
                ),
                (250 * MS, Step::Rx(n(6), Operational), &[]),
                (
                    1_000 * MS,
                    Step::Poll,
                    &[HeartbeatEvent::Timeout {
                        node: n(6),
                        last_heartbeat: 250 * MS,
                        deadline: 550 * MS,
                    }],
                ),
            ],
        );
    }

    #[test]
    fn monitor_unconfigured_takes_up_nodes_and_reports_overflow_once() {
        let mut consumer = HeartbeatConsumer::<2>::with_capacity();
        consumer.monitor_unconfigured(100 * MS);
        run(
            &mut consumer,
            &[
                (us(0), Step::Rx(n(1), Operational), &[]),
                (us(0), Step::Rx(n(2), Operational), &[]),
                (
                    10 * MS,
                    Step::Rx(n(3), Operational),
                    &[HeartbeatEvent::CapacityExceeded {
                        node: n(3),
                        at: 10 * MS,
                    }],
                ),
                (20 * MS, Step::Rx(n(3), Operational), &[]),
                (
                    101 * MS,
                    Step::Poll,
                    &[
                        HeartbeatEvent::Timeout {
                            node: n(1),
                            last_heartbeat: Duration::ZERO,
                            deadline: 100 * MS,
                        },
                        HeartbeatEvent::Timeout {
                            node: n(2),
                            last_heartbeat: Duration::ZERO,
                            deadline: 100 * MS,
                        },
                    ],
                ),
            ],
        );
        assert_eq!(consumer.consumer_time(n(1)), Some(100 * MS));
        // A configured entry displaces a node that was only taken up.
        consumer
            .set_entry(ConsumerEntry::from_millis(n(9), 50))
            .unwrap();
        assert_eq!(consumer.consumer_time(n(9)), Some(50 * MS));
        assert_eq!(consumer.monitor_state(n(1)), None);
        consumer
            .set_entry(ConsumerEntry::from_millis(n(10), 50))
            .unwrap();
        assert_eq!(
            consumer.set_entry(ConsumerEntry::from_millis(n(11), 50)),
            Err(RangeError {
                what: What::HeartbeatConsumerEntries,
                found: 3,
                min: 0,
                max: 2,
            })
        );
    }

    #[test]
    fn entries_replace_and_remove() {
        let mut consumer = consumer_of(&[(5, 100)]);
        assert!(consumer.on_heartbeat(us(0), n(5), Operational).is_empty());
        // Rewriting the entry restarts monitoring at the next heartbeat.
        consumer
            .set_entry(ConsumerEntry::from_millis(n(5), 200))
            .unwrap();
        assert_eq!(consumer.monitor_state(n(5)), Some(MonitorState::Waiting));
        assert_eq!(consumer.consumer_time(n(5)), Some(200 * MS));
        // Time 0: the entry is not used.
        consumer
            .set_entry(ConsumerEntry::from_millis(n(5), 0))
            .unwrap();
        assert_eq!(consumer.monitor_state(n(5)), None);
        assert!(!consumer.remove(n(5)));
        assert_eq!(consumer.capacity(), 4);
    }

    /// 1016h sub-index values (CiA 301, object 1016h).
    #[test]
    fn consumer_entry_od_values() {
        let table: [(u32, Option<(u8, u16)>); 6] = [
            (0x0031_03E8, Some((0x31, 1000))),
            (0x007F_0001, Some((127, 1))),
            (0xFF05_0064, Some((5, 100))), // reserved bits not read
            (0x0005_0000, None),           // time 0
            (0x0000_0064, None),           // node-ID 0
            (0x0080_0064, None),           // node-ID 128
        ];
        for (raw, expected) in table {
            let expected = expected.map(|(node, ms)| ConsumerEntry::from_millis(n(node), ms));
            assert_eq!(ConsumerEntry::from_od_value(raw), expected, "{raw:#010x}");
            if let Some(entry) = expected {
                assert_eq!(entry.to_od_value(), raw & 0x00FF_FFFF);
                assert_eq!(entry.consumer_time(), u32::from(entry.time_ms) * MS);
            }
        }
    }

    #[test]
    fn event_accessors() {
        let recovered = HeartbeatEvent::Recovered {
            node: n(5),
            last_heartbeat: us(1_000),
            at: us(401_000),
            state: Operational,
        };
        assert_eq!(recovered.node(), n(5));
        assert_eq!(recovered.at(), us(401_000));
        assert_eq!(recovered.last_heartbeat(), Some(us(1_000)));
        assert_eq!(recovered.gap(), Some(us(400_000)));
        assert_eq!(recovered.name(), "recovered");
        assert_eq!(
            recovered.to_string(),
            "node 5: recovered at 401000 µs after the heartbeat at 1000 µs"
        );
        let overflow = HeartbeatEvent::CapacityExceeded {
            node: n(7),
            at: us(3),
        };
        assert_eq!(overflow.gap(), None);
        assert_eq!(overflow.name(), "capacity_exceeded");
    }

    /// Producer rows: (time, state, expected bytes sent).
    fn run_producer(
        producer: &mut HeartbeatProducer,
        rows: &[(Duration, NmtState, Option<[u8; 1]>)],
    ) {
        for (row, &(now, state, expected)) in rows.iter().enumerate() {
            let sent = producer.poll(now, state).map(|h| h.to_bytes());
            assert_eq!(sent, expected, "row {row} at {now:?}");
        }
    }

    #[test]
    fn producer_period() {
        let mut producer = HeartbeatProducer::from_millis(100);
        run_producer(
            &mut producer,
            &[
                (us(0), PreOperational, Some([0x7F])),
                (50 * MS, PreOperational, None),
                (100 * MS - 1 * US, PreOperational, None),
                (100 * MS, Operational, Some([0x05])),
                (100 * MS, Operational, None),
                // A little late: the cadence is kept.
                (210 * MS, Operational, Some([0x05])),
                (300 * MS, Stopped, Some([0x04])),
                // More than a period late: one heartbeat, no burst.
                (750 * MS, Stopped, Some([0x04])),
                (760 * MS, Stopped, None),
                (850 * MS, Stopped, Some([0x04])),
            ],
        );
        assert_eq!(producer.next_due(), Some(950 * MS));
        assert_eq!(producer.producer_time(), 100 * MS);
    }

    #[test]
    fn producer_zero_is_off() {
        let mut producer = HeartbeatProducer::from_millis(0);
        assert!(!producer.is_enabled());
        assert_eq!(producer.next_due(), None);
        run_producer(
            &mut producer,
            &[
                (us(0), Operational, None),
                (1_000 * MS, Operational, None),
                (Duration::MAX, Operational, None),
            ],
        );
        // Writing 1017h switches it on: the next poll sends at once.
        producer.set_producer_time(20);
        run_producer(
            &mut producer,
            &[
                (2_000 * MS, Operational, Some([0x05])),
                (2_020 * MS, Operational, Some([0x05])),
            ],
        );
        producer.set_producer_time(0);
        run_producer(&mut producer, &[(3_000 * MS, Operational, None)]);
    }

    #[test]
    fn producer_restart_after_boot_up() {
        let mut producer = HeartbeatProducer::from_millis(100);
        // The node sends its boot-up at 5 ms; the first heartbeat follows a
        // period later.
        producer.restart(5 * MS);
        run_producer(
            &mut producer,
            &[
                (5 * MS, PreOperational, None),
                (105 * MS, PreOperational, Some([0x7F])),
            ],
        );
    }

    #[test]
    fn producer_never_sets_bit7() {
        let mut producer = HeartbeatProducer::from_millis(1);
        for (i, state) in NmtState::ALL.into_iter().enumerate() {
            let heartbeat = producer.poll(i as u32 * MS, state).unwrap();
            assert!(!heartbeat.reserved_bit());
            assert_eq!(heartbeat.to_bytes(), [state.to_byte()]);
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;

    /// A time in microseconds.
    fn us(n: u64) -> Duration {
        Duration::from_micros(n)
    }
    use crate::strategies::error_control::{
        any_times, consumer_step, consumer_steps, nmt_state, ConsumerStep,
    };

    proptest! {
        /// Random heartbeats, boot-ups and polls never panic, and the
        /// consumer keeps CiA 301's promises: one timeout per silence, a
        /// recovery only after a timeout, and times that tell the gap.
        #[test]
        fn consumer_invariants(
            time_ms in 1u16..400,
            unconfigured_ms in prop_oneof![Just(0u16), 1u16..400],
            steps in consumer_steps(),
        ) {
            let mut consumer = HeartbeatConsumer::<3>::with_capacity();
            consumer.set_entry(ConsumerEntry::from_millis(NodeId::MIN, time_ms)).unwrap();
            consumer.monitor_unconfigured(millis(u32::from(unconfigured_ms)));
            // Per node: timed out since its last message, and its last
            // heartbeat (non-boot-up) time while monitored.
            let mut timed_out = [false; 128];
            let mut last: [Option<Duration>; 128] = [None; 128];
            for (now, step) in steps {
                let (events, rx): (Vec<HeartbeatEvent>, _) = match step {
                    ConsumerStep::Rx(node, state) => {
                        (consumer.on_heartbeat(now, node, state).collect(), Some((node, state)))
                    }
                    ConsumerStep::Poll => (consumer.poll(now).collect(), None),
                };
                prop_assert!(events.len() <= 2 || rx.is_none());
                for event in &events {
                    let i = usize::from(event.node().get());
                    match *event {
                        HeartbeatEvent::Timeout { last_heartbeat, deadline, node } => {
                            prop_assert!(!timed_out[i], "two timeouts for node {}", node);
                            prop_assert_eq!(Some(last_heartbeat), last[i]);
                            prop_assert!(deadline < now);
                            prop_assert_eq!(Some(deadline - last_heartbeat), consumer.consumer_time(node));
                            timed_out[i] = true;
                        }
                        HeartbeatEvent::Recovered { last_heartbeat, at, .. } => {
                            prop_assert!(timed_out[i], "recovered without a timeout");
                            prop_assert_eq!(Some(last_heartbeat), last[i]);
                            prop_assert_eq!(at, now);
                        }
                        HeartbeatEvent::RemoteReset { last_heartbeat, at, .. } => {
                            prop_assert_eq!(Some(last_heartbeat), last[i]);
                            prop_assert_eq!(at, now);
                        }
                        HeartbeatEvent::CapacityExceeded { at, .. } => {
                            prop_assert_eq!(at, now);
                            prop_assert!(consumer.monitor_state(event.node()).is_none());
                        }
                    }
                }
                if let Some((node, state)) = rx {
                    let i = usize::from(node.get());
                    timed_out[i] = false;
                    last[i] = match (consumer.monitor_state(node), state) {
                        (Some(_), NmtState::BootUp) | (None, _) => None,
                        (Some(_), _) => Some(now),
                    };
                }
                // No active node is left past its deadline after a poll.
                if rx.is_none() {
                    prop_assert!(consumer.next_deadline().map_or(true, |d| d >= now));
                }
            }
        }

        #[test]
        fn producer_invariants(
            producer_ms in 0u16..50,
            polls in proptest::collection::vec((0u64..120_000, nmt_state()), 0..64),
        ) {
            let mut producer = HeartbeatProducer::from_millis(producer_ms);
            let period = millis(u32::from(producer_ms));
            let mut now = Duration::ZERO;
            let mut first_sent: Option<Duration> = None;
            let mut sent = 0u32;
            for (dt, state) in polls {
                now += us(dt);
                match producer.poll(now, state) {
                    Some(heartbeat) => {
                        prop_assert!(producer_ms != 0);
                        prop_assert_eq!(heartbeat.to_bytes(), [state.to_byte()]);
                        // Never more than one heartbeat per period on average…
                        let first = *first_sent.get_or_insert(now);
                        prop_assert!(sent * period <= now - first);
                        sent += 1;
                        // …and the next is due within one period.
                        let due = producer.next_due().unwrap();
                        prop_assert!(now < due && due <= now + period);
                    }
                    None => prop_assert!(producer_ms == 0 || producer.next_due().unwrap() > now),
                }
            }
        }

        /// Times that jump backwards or sit at `Duration::MAX` never panic; the
        /// outputs stay well-formed.
        #[test]
        fn any_times_never_panic(
            time_ms in any::<u16>(),
            steps in any_times(consumer_step()),
            producer_polls in any_times(nmt_state()),
        ) {
            let mut consumer = HeartbeatConsumer::<2>::with_capacity();
            consumer.set_entry(ConsumerEntry::from_millis(NodeId::MIN, time_ms)).unwrap();
            consumer.monitor_unconfigured(millis(u32::from(time_ms)));
            for (now, step) in steps {
                let events: Vec<HeartbeatEvent> = match step {
                    ConsumerStep::Rx(node, state) => consumer.on_heartbeat(now, node, state).collect(),
                    ConsumerStep::Poll => consumer.poll(now).collect(),
                };
                for event in events {
                    if let HeartbeatEvent::Timeout { deadline, .. } = event {
                        prop_assert!(deadline < now);
                    }
                    prop_assert!(event.gap().map_or(true, |gap| gap <= event.at()));
                }
            }
            let mut producer = HeartbeatProducer::from_millis(time_ms);
            for (now, state) in producer_polls {
                if let Some(heartbeat) = producer.poll(now, state) {
                    prop_assert!(!heartbeat.reserved_bit());
                }
            }
        }
    }
}
