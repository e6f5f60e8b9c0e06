//! What the error-control state machines share: the time unit, the choice
//! between heartbeat and node/life guarding, and the small fixed-capacity
//! list in which one input returns its events (CiA 301 §7.2.8;
//! docs/canopen.md#error-control).
//!
//! # Time
//!
//! Every state machine of the error-control modules is pure: the caller
//! passes the current time with every event and every poll as a
//! [`Duration`] since an epoch of the caller's choice
//! on any monotonic clock (a microcontroller's tick counter, a PLC's cycle
//! clock, or a log's timestamps: [`Timestamp::as_duration`](crate::can::Timestamp::as_duration)).
//! Periods are durations too, so no unit is ever guessed. Nothing reads a
//! clock or sleeps; all arithmetic on times saturates, so a clock that
//! wraps or runs backwards gives wrong answers but never a panic. The object
//! dictionary values (1016h, 1017h, 100Ch) are milliseconds, as CiA 301
//! defines them: the fields and constructors that take them say so in their
//! names (`guard_time_ms`, `from_millis`).
//!
//! ```
//! use core::time::Duration;
//! use motionwire_codec::canopen::{ErrorControlConfig, ErrorControlMethod};
//!
//! // Only one method is used: a non-zero 1017h wins
//! // (docs/canopen.md#error-control).
//! let config = ErrorControlConfig {
//!     producer_heartbeat_time_ms: 100,
//!     guard_time_ms: 50,
//!     life_time_factor: 3,
//! };
//! assert_eq!(config.method(), ErrorControlMethod::Heartbeat);
//! assert_eq!(config.node_life_time(), None);
//!
//! let config = ErrorControlConfig { producer_heartbeat_time_ms: 0, ..config };
//! assert_eq!(config.method(), ErrorControlMethod::Guarding);
//! assert_eq!(config.node_life_time(), Some(Duration::from_millis(150)));
//! ```

use core::fmt;
use core::time::Duration;

/// A time in milliseconds, the unit of objects 1016h, 1017h and 100Ch
/// (CiA 301 object dictionary), as a [`Duration`].
#[inline]
pub(crate) const fn millis(ms: u32) -> Duration {
    Duration::from_millis(ms as u64)
}

/// Which error-control method a node's configuration puts in force
/// (CiA 301 §7.2.8.1; docs/canopen.md#error-control): a node uses one of the
/// two monitoring methods, heartbeat when its producer time is not 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorControlMethod {
    /// The producer heartbeat time 1017h is non-zero: the node sends
    /// heartbeats; node guarding and life guarding are not used.
    Heartbeat,
    /// 1017h is 0 and the guard time 100Ch is non-zero: the master guards
    /// the node; the node also guards the master (life guarding) when the
    /// life time factor 100Dh is non-zero as well.
    Guarding,
    /// Neither is configured: no error control.
    None,
}

impl ErrorControlMethod {
    /// Return the method in force for a producer heartbeat time (1017h, ms),
    /// guard time (100Ch, ms) and life time factor (100Dh).
    ///
    /// The life time factor does not decide between guarding and nothing: a
    /// node with a guard time but factor 0 is still guarded by its master,
    /// it only does not monitor the master (docs/canopen.md#error-control).
    #[inline]
    #[must_use]
    pub const fn select(producer_heartbeat_time_ms: u16, guard_time_ms: u16) -> Self {
        if producer_heartbeat_time_ms != 0 {
            ErrorControlMethod::Heartbeat
        } else if guard_time_ms != 0 {
            ErrorControlMethod::Guarding
        } else {
            ErrorControlMethod::None
        }
    }

    /// Return the method's name: `heartbeat`, `guarding` or `none`.
    #[inline]
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            ErrorControlMethod::Heartbeat => "heartbeat",
            ErrorControlMethod::Guarding => "guarding",
            ErrorControlMethod::None => "none",
        }
    }
}

impl fmt::Display for ErrorControlMethod {
    /// Format the method as its [`ErrorControlMethod::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A node's error-control objects (CiA 301, objects 1017h, 100Ch and 100Dh;
/// docs/canopen.md#error-control).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ErrorControlConfig {
    /// Producer heartbeat time, object 1017h, in ms; 0 disables heartbeat.
    pub producer_heartbeat_time_ms: u16,
    /// Guard time, object 100Ch, in ms; 0 disables node and life guarding.
    pub guard_time_ms: u16,
    /// Life time factor, object 100Dh; 0 disables life guarding.
    pub life_time_factor: u8,
}

impl ErrorControlConfig {
    /// Return the method in force ([`ErrorControlMethod::select`]).
    #[inline]
    #[must_use]
    pub const fn method(&self) -> ErrorControlMethod {
        ErrorControlMethod::select(self.producer_heartbeat_time_ms, self.guard_time_ms)
    }

    /// Return the node life time, guard time × life time factor; `None` when
    /// either is 0 (0 in either disables life guarding,
    /// docs/canopen.md#error-control) or when heartbeat is configured
    /// (heartbeat wins, docs/canopen.md#error-control).
    #[inline]
    #[must_use]
    pub const fn node_life_time(&self) -> Option<Duration> {
        match self.method() {
            ErrorControlMethod::Guarding if self.life_time_factor != 0 => Some(millis(
                // 65 535 × 255 < u32::MAX: cannot overflow.
                self.guard_time_ms as u32 * self.life_time_factor as u32,
            )),
            _ => None,
        }
    }
}

/// The events one input to an error-control state machine produced, in the
/// order they occurred: at most `N`, stored in place (no heap;
/// docs/canopen.md#error-control: pure state machines). Iterate it, or check
/// [`Events::is_empty`].
///
/// One input can stand for more than one event: a heartbeat that arrives
/// after its deadline without a poll in between is both a timeout and a
/// recovery, and both are returned, the timeout first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[must_use = "events are lost unless they are read"]
pub struct Events<E: Copy, const N: usize> {
    items: [Option<E>; N],
    next: usize,
}

impl<E: Copy, const N: usize> Events<E, N> {
    /// Return an empty list.
    #[inline]
    pub(crate) const fn new() -> Self {
        Events {
            items: [None; N],
            next: 0,
        }
    }

    /// Append an event. The callers size `N` for the most events one input
    /// can produce; a push beyond that is a bug in the crate, not the input,
    /// and is dropped rather than panicking.
    #[inline]
    pub(crate) fn push(&mut self, event: E) {
        if let Some(slot) = self.items.iter_mut().find(|slot| slot.is_none()) {
            *slot = Some(event);
        }
    }

    /// Append an event when there is one.
    #[inline]
    pub(crate) fn push_some(&mut self, event: Option<E>) {
        if let Some(event) = event {
            self.push(event);
        }
    }

    /// Return whether no event is left.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<E: Copy, const N: usize> Iterator for Events<E, N> {
    type Item = E;

    fn next(&mut self) -> Option<E> {
        while let Some(slot) = self.items.get_mut(self.next) {
            self.next += 1;
            if let Some(event) = slot.take() {
                return Some(event);
            }
        }
        None
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.items.get(self.next..).map_or(0, |items| {
            items.iter().filter(|slot| slot.is_some()).count()
        });
        (left, Some(left))
    }
}

impl<E: Copy, const N: usize> ExactSizeIterator for Events<E, N> {}

#[cfg(test)]
mod tests {
    use super::*;

    /// Which method is in force, as a truth table
    /// (docs/canopen.md#error-control).
    #[test]
    fn method_truth_table() {
        use ErrorControlMethod as M;
        // (1017h ms, 100Ch ms, 100Dh) → method, node life time in µs
        let table: [(u16, u16, u8, M, Option<u64>); 8] = [
            (0, 0, 0, M::None, None),
            (0, 0, 3, M::None, None),
            (0, 100, 0, M::Guarding, None),
            (0, 100, 3, M::Guarding, Some(300_000)),
            (0, u16::MAX, u8::MAX, M::Guarding, Some(65_535 * 255 * 1000)),
            (200, 0, 0, M::Heartbeat, None),
            (200, 100, 0, M::Heartbeat, None),
            (200, 100, 3, M::Heartbeat, None),
        ];
        for (heartbeat, guard, factor, method, life) in table {
            let config = ErrorControlConfig {
                producer_heartbeat_time_ms: heartbeat,
                guard_time_ms: guard,
                life_time_factor: factor,
            };
            assert_eq!(config.method(), method, "{config:?}");
            assert_eq!(ErrorControlMethod::select(heartbeat, guard), method);
            assert_eq!(
                config.node_life_time(),
                life.map(Duration::from_micros),
                "{config:?}"
            );
        }
        assert_eq!(ErrorControlConfig::default().method(), M::None);
    }

    #[test]
    fn method_names() {
        assert_eq!(ErrorControlMethod::Heartbeat.to_string(), "heartbeat");
        assert_eq!(ErrorControlMethod::Guarding.name(), "guarding");
        assert_eq!(ErrorControlMethod::None.name(), "none");
    }

    #[test]
    fn millis_are_durations() {
        assert_eq!(millis(0), Duration::ZERO);
        assert_eq!(millis(1), Duration::from_micros(1000));
        assert_eq!(millis(u32::MAX), Duration::from_millis(u64::from(u32::MAX)));
    }

    #[test]
    fn events_keep_order_and_count() {
        let mut events = Events::<u8, 3>::new();
        assert!(events.is_empty());
        assert_eq!(events.len(), 0);
        events.push(7);
        events.push_some(None);
        events.push_some(Some(9));
        assert!(!events.is_empty());
        assert_eq!(events.len(), 2);
        assert_eq!(events.next(), Some(7));
        assert_eq!(events.len(), 1);
        assert_eq!(events.collect::<Vec<_>>(), [9]);
        let mut full = Events::<u8, 1>::new();
        full.push(1);
        full.push(2);
        assert_eq!(full.collect::<Vec<_>>(), [1]);
    }
}
