//! The causal links the log supports between findings
//! (docs/summary.md#causes), beyond a drive's EMCY and its fault
//! ([`CAUSE_WINDOW`](super::CAUSE_WINDOW)): a bus-off or error-passive
//! error frame before a heartbeat timeout on the same bus
//! ([`HeartbeatGap::cause`]), and a heartbeat timeout before another
//! node's EMCY 0x8130 "Life guard error or heartbeat error"
//! ([`Summary::lost_before`]).

use core::time::Duration;
use std::collections::VecDeque;

use crate::can::BusName;
use crate::canopen::{ErrorCode, NodeId};

use super::heartbeat::BusErrorSeen;
use super::{EmcySeen, HeartbeatGap, Summary, Timeouts, CAUSE_WINDOW};

/// The EMCY code a heartbeat consumer sends when it misses a heartbeat,
/// or a node when its life guarding fails: 0x8130 "Life guard error or
/// heartbeat error" (CiA 301, docs/canopen.md#error-control).
pub const LOST_HEARTBEAT: ErrorCode = ErrorCode::new(0x8130);

/// The most bus-off and error-passive frames a bus keeps from its last
/// second: a storm keeps its first ones, which are the earliest causes.
const RECENT: usize = 64;

/// A bus's bus-off and error-passive frames of the last second, for the
/// window of a heartbeat that was just seen.
#[derive(Debug, Default)]
pub(crate) struct RecentBusErrors(VecDeque<BusErrorSeen>);

impl RecentBusErrors {
    /// Keep `seen`, forgetting what came more than a second before it.
    pub(crate) fn push(&mut self, seen: BusErrorSeen) {
        let t = seen.timestamp.as_duration();
        while self
            .0
            .front()
            .is_some_and(|e| e.timestamp.as_duration() + CAUSE_WINDOW < t)
        {
            self.0.pop_front();
        }
        if self.0.len() < RECENT {
            self.0.push_back(seen);
        }
    }

    /// Return the earliest frame kept that lies in the window of a
    /// heartbeat due at `due`.
    pub(crate) fn earliest_for(&self, due: Duration) -> Option<BusErrorSeen> {
        self.0
            .iter()
            .find(|e| in_window(e.timestamp.as_duration(), due))
            .copied()
    }
}

/// Whether a bus error at `t` can cause the loss of a heartbeat due at
/// `due` (docs/summary.md#causes): at most [`CAUSE_WINDOW`] before it, and
/// not after it.
pub(crate) fn in_window(t: Duration, due: Duration) -> bool {
    t <= due && t + CAUSE_WINDOW >= due
}

impl Summary {
    /// Return the heartbeat timeout of another node of `bus` that the log
    /// supports as the cause of `emcy`, an EMCY of `node`
    /// (docs/summary.md#causes): for an EMCY 0x8130 ([`LOST_HEARTBEAT`]),
    /// the earliest gap of another node of its bus that it came in — after
    /// the heartbeat before the gap, before the one that ends it —, at
    /// most [`CAUSE_WINDOW`] after that node's heartbeat was due; the
    /// gaps the summary lists ([`Listed`](super::Listed)) are looked at.
    #[must_use]
    pub fn lost_before(
        &self,
        bus: &BusName,
        node: NodeId,
        emcy: &EmcySeen,
    ) -> Option<(NodeId, HeartbeatGap)> {
        if emcy.code != LOST_HEARTBEAT {
            return None;
        }
        let t = emcy.timestamp?;
        let mut best: Option<(NodeId, HeartbeatGap)> = None;
        for other in self
            .nodes
            .iter()
            .filter(|n| &n.bus == bus && n.node != node)
        {
            let Timeouts::Checked(gaps) = &other.heartbeat.timeouts else {
                continue;
            };
            for gap in gaps.iter() {
                let end = gap.since.checked_add(gap.gap).unwrap_or(gap.since);
                let late = gap.due.checked_add(CAUSE_WINDOW).unwrap_or(gap.due);
                let earliest = best.map_or(true, |(_, b)| gap.since < b.since);
                if gap.since < t && t <= end && t <= late && earliest {
                    best = Some((other.node, *gap));
                }
            }
        }
        best
    }
}
