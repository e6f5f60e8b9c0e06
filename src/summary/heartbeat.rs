//! A node's heartbeats and node-guarding answers as the summary records
//! them: [`HeartbeatSummary`], [`GuardingSummary`], with their
//! [`HeartbeatGap`]s and [`Timeouts`].

use core::fmt;
use core::time::Duration;

use crate::can::Timestamp;
use crate::canopen::NmtStateByte;

use super::listed::Listed;

/// A bus-off or error-passive error frame the summary links to a heartbeat
/// timeout (docs/summary.md#causes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BusErrorSeen {
    /// Its line.
    pub line: u64,
    /// Its time.
    pub timestamp: Timestamp,
    /// Whether it says bus-off (else error-passive).
    pub bus_off: bool,
}

impl fmt::Display for BusErrorSeen {
    /// `bus-off at line 38`, `error-passive at line 38`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = if self.bus_off {
            "bus-off"
        } else {
            "error-passive"
        };
        write!(f, "{what} at line {}", self.line)
    }
}

/// A heartbeat gap longer than the consumer time (`heartbeat.timeouts`
/// in docs/summary.md#heartbeat).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HeartbeatGap {
    /// The line of the heartbeat before the gap.
    pub after_line: u64,
    /// The gap: up to the next heartbeat, or to the last time of the input.
    pub gap: Duration,
    /// The time of the heartbeat before the gap.
    pub since: Timestamp,
    /// When the next heartbeat was due: [`since`](Self::since) plus the
    /// consumer time (`--heartbeat-ms`).
    pub due: Timestamp,
    /// The bus-off or error-passive error frame on the node's bus that the
    /// log supports as the cause of the loss: the earliest at most a
    /// second before the heartbeat was due, and not after
    /// (docs/summary.md#causes).
    pub cause: Option<BusErrorSeen>,
}

impl HeartbeatGap {
    /// Return the gap in milliseconds, as `gap_ms` (docs/summary.md#heartbeat;
    /// exact for every gap below 2^53 µs).
    #[must_use]
    pub fn gap_ms(&self) -> f64 {
        self.gap.as_micros() as f64 / 1000.0
    }
}

/// Whether heartbeat timeouts were checked, and what was found
/// (docs/summary.md#heartbeat, docs/formats.md#timestamps).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Timeouts {
    /// No consumer time was given: timeouts are not part of the summary
    /// (no `timeouts` key).
    NotAsked,
    /// A consumer time was given, but frames without timestamps make a
    /// check impossible (`null`, never "none found").
    NotChecked,
    /// Checked: the gaps longer than the consumer time (the first and the
    /// last, and their count: docs/summary.md#lists).
    Checked(Listed<HeartbeatGap>),
}

/// A node's heartbeats (`heartbeat` in docs/summary.md#heartbeat).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HeartbeatSummary {
    /// Heartbeats seen (not node-guarding answers).
    pub count: u64,
    /// The state of the last one.
    pub last_state: Option<NmtStateByte>,
    /// The lines of its boot-up messages (the first and the last, and
    /// their count: docs/summary.md#lists).
    pub boot_ups: Listed<u64>,
    /// Its heartbeat timeouts.
    pub timeouts: Timeouts,
}

/// A node's node-guarding answers (`guarding` in docs/summary.md#guarding).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct GuardingSummary {
    /// Answers seen (the data frame after a guard request).
    pub answers: u64,
    /// The lines of the answers whose toggle bit is wrong
    /// (docs/canopen.md#error-control; the first and the last, and their
    /// count: docs/summary.md#lists).
    pub toggle_errors: Listed<u64>,
}
