//! A node's SDO channel in the summary (docs/summary.md#sdo): requests,
//! transfers, aborts, broken and unanswered transfers, response latencies.

use core::time::Duration;

use crate::canopen::sdo::{SdoMessage, SdoOutcome, SdoParty, SdoRequest, SdoResponse, SdoTransfer};
use crate::canopen::{ObjectAddress, SdoAbortCode};
use crate::decoder::{ObjectNames, SdoSeen, SdoStep};

use super::Listed;

/// One abort seen on a node's channel (`aborts` in docs/summary.md#sdo).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SdoAbort {
    /// The line of the abort frame.
    pub line: u64,
    /// The object: the abort's multiplexer, or the aborted transfer's when
    /// the abort carries none (python-canopen's client aborts with
    /// 0000h.00).
    pub multiplexer: ObjectAddress,
    /// The object's name, where known (`object` in
    /// docs/canopen.md#object-names: the node's EDS first, then the
    /// communication objects and the profile's;
    /// [`SdoStep::object`]).
    pub object: Option<String>,
    /// The abort code.
    pub code: SdoAbortCode,
    /// Who aborted.
    pub by: SdoParty,
}

/// The request → response latencies of a channel (`latency_ms` in
/// docs/summary.md#sdo): nearest-rank percentiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LatencyStats {
    /// How many latencies.
    pub count: usize,
    /// The median.
    pub median: Duration,
    /// The 99th percentile.
    pub p99: Duration,
    /// The longest.
    pub max: Duration,
}

/// A node's SDO record (docs/summary.md#sdo).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SdoSummary {
    /// Client → server frames.
    pub requests: u64,
    /// Transfers that started, whatever their outcome.
    pub transfers: u64,
    /// The aborts, in order (the first and the last, and their count:
    /// docs/summary.md#lists).
    pub aborts: Listed<SdoAbort>,
    /// The start lines of broken transfers (the same).
    pub broken: Listed<u64>,
    /// The start lines of transfers no response answered (the same).
    pub timeouts: Listed<u64>,
    /// The latencies, when there were any.
    pub latency: Option<LatencyStats>,
}

impl SdoSummary {
    /// Return whether the node had no SDO frame.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.requests == 0
            && self.transfers == 0
            && self.aborts.is_empty()
            && self.broken.is_empty()
    }
}

/// What the summary reads of one SDO frame (docs/summary.md#sdo): of a
/// public [`SdoStep`] (a [`Decoded`](crate::decoder::Decoded) reading),
/// or of the decoder's own reading, which makes no message
/// ([`SdoSeen`]). Read where the frame's reading lies, not copied out.
pub(crate) trait SdoFrameFacts {
    /// Who sent the frame.
    fn sender(&self) -> SdoParty;
    /// The frame starts a transfer.
    fn started(&self) -> bool;
    /// The request → response latency the frame closes.
    fn latency(&self) -> Option<Duration>;
    /// The abort's multiplexer and code, when the frame is an abort.
    fn abort(&self) -> Option<(ObjectAddress, SdoAbortCode)>;
    /// The transfer the frame ends.
    fn ended(&self) -> Option<&SdoTransfer>;
    /// Where the node's objects get their names.
    fn names(&self) -> ObjectNames<'_>;
}

/// A step's abort is what its message says.
impl SdoFrameFacts for SdoStep<'_> {
    #[inline]
    fn sender(&self) -> SdoParty {
        self.sender
    }

    #[inline]
    fn started(&self) -> bool {
        self.started
    }

    #[inline]
    fn latency(&self) -> Option<Duration> {
        self.latency
    }

    #[inline]
    fn abort(&self) -> Option<(ObjectAddress, SdoAbortCode)> {
        match self.message {
            Ok(SdoMessage::Request(SdoRequest::Abort { multiplexer, code }))
            | Ok(SdoMessage::Response(SdoResponse::Abort { multiplexer, code })) => {
                Some((multiplexer, code))
            }
            _ => None,
        }
    }

    #[inline]
    fn ended(&self) -> Option<&SdoTransfer> {
        self.ended.as_ref().map(|ended| &ended.transfer)
    }

    #[inline]
    fn names(&self) -> ObjectNames<'_> {
        self.names
    }
}

/// The decoder's reading: an abort read from the frame's bytes as the
/// tracker read them.
impl SdoFrameFacts for SdoSeen<'_, '_> {
    #[inline]
    fn sender(&self) -> SdoParty {
        self.event.sender()
    }

    #[inline]
    fn started(&self) -> bool {
        self.event.started
    }

    #[inline]
    fn latency(&self) -> Option<Duration> {
        self.event.latency
    }

    #[inline]
    fn abort(&self) -> Option<(ObjectAddress, SdoAbortCode)> {
        SdoSeen::abort(self)
    }

    #[inline]
    fn ended(&self) -> Option<&SdoTransfer> {
        self.event.ended.as_ref()
    }

    #[inline]
    fn names(&self) -> ObjectNames<'_> {
        self.names
    }
}

/// What one frame added to a channel's record.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Added {
    /// An abort: [`SdoStats::last_abort`].
    pub(crate) abort: bool,
    /// The frame's step ended a transfer that is broken or unanswered.
    pub(crate) ended: bool,
}

/// What the summarizer keeps of a channel while the log is read.
#[derive(Debug, Default)]
pub(crate) struct SdoStats {
    summary: SdoSummary,
    latencies: Latencies,
}

/// A channel's latencies in nanoseconds (u64 nanoseconds hold 584 years),
/// for exact nearest-rank percentiles in memory that grows with the
/// distinct latencies, not with the responses: each distinct value once,
/// with its count, in an open-addressing table (linear probing, Fibonacci
/// hashing), sorted only when the statistics are asked for. A log's times
/// have a resolution (a microsecond for candump, python-can's float
/// seconds for its BLF files), so a channel's latencies take far fewer
/// values than it has responses; a response costs one probe or two, where
/// buffering and merging sorted runs cost a sort per latency.
#[derive(Debug, Default)]
struct Latencies {
    /// The slots, a power of two of them (none before the first latency):
    /// a latency and its count; a count of 0 marks a free slot.
    slots: Vec<(u64, u64)>,
    /// The slots in use: the distinct latencies.
    distinct: usize,
}

impl Latencies {
    /// The slots of a channel's first latency: 1 KiB.
    const FIRST: usize = 64;

    /// The slot where the search for `nanos` starts, among `len` (a power
    /// of two): the top bits of a Fibonacci hash, so that latencies that
    /// are multiples of a resolution spread over the table.
    #[inline]
    fn home(nanos: u64, len: usize) -> usize {
        let bits = len.trailing_zeros();
        (nanos.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (63 - bits) >> 1) as usize
    }

    #[inline]
    fn push(&mut self, nanos: u64) {
        // At most three slots in four in use: probes stay short.
        if (self.distinct + 1) * 4 > self.slots.len() * 3 {
            self.grow();
        }
        let mask = self.slots.len() - 1;
        let mut at = Self::home(nanos, self.slots.len());
        loop {
            let slot = &mut self.slots[at];
            if slot.1 == 0 {
                *slot = (nanos, 1);
                self.distinct += 1;
                return;
            }
            if slot.0 == nanos {
                slot.1 += 1;
                return;
            }
            at = (at + 1) & mask;
        }
    }

    /// Double the table (or make the first), every latency moved over.
    #[cold]
    fn grow(&mut self) {
        let len = (self.slots.len() * 2).max(Self::FIRST);
        let old = core::mem::replace(&mut self.slots, vec![(0, 0); len]);
        let mask = len - 1;
        for (value, count) in old.into_iter().filter(|&(_, count)| count > 0) {
            let mut at = Self::home(value, len);
            while self.slots[at].1 != 0 {
                at = (at + 1) & mask;
            }
            self.slots[at] = (value, count);
        }
    }

    /// Return the nearest-rank statistics (docs/summary.md#sdo): the
    /// smallest latency with at least p of them at or below it.
    fn stats(self) -> Option<LatencyStats> {
        let mut sorted: Vec<(u64, u64)> = self
            .slots
            .into_iter()
            .filter(|&(_, count)| count > 0)
            .collect();
        sorted.sort_unstable();
        let n: u64 = sorted.iter().map(|&(_, count)| count).sum();
        let max = sorted.last()?.0;
        let rank = |p: f64| {
            let r = ((p * n as f64).ceil() as u64).clamp(1, n);
            let mut seen = 0;
            for &(value, count) in &sorted {
                seen += count;
                if seen >= r {
                    return Duration::from_nanos(value);
                }
            }
            Duration::from_nanos(max)
        };
        Some(LatencyStats {
            count: usize::try_from(n).unwrap_or(usize::MAX),
            median: rank(0.5),
            p99: rank(0.99),
            max: Duration::from_nanos(max),
        })
    }
}

/// A latency in nanoseconds, `u64::MAX` for one longer than 584 years:
/// computed in `u64`, where `Duration::as_nanos` computes in `u128`.
#[inline]
fn nanos(latency: Duration) -> u64 {
    latency
        .as_secs()
        .checked_mul(1_000_000_000)
        .and_then(|n| n.checked_add(u64::from(latency.subsec_nanos())))
        .unwrap_or(u64::MAX)
}

impl SdoStats {
    /// Add one frame of the node's channel, as its tracker read it.
    #[inline]
    pub(crate) fn add(&mut self, frame: &impl SdoFrameFacts, line: u64) -> Added {
        let s = &mut self.summary;
        s.requests += u64::from(frame.sender() == SdoParty::Client);
        s.transfers += u64::from(frame.started());
        if let Some(latency) = frame.latency() {
            self.latencies.push(nanos(latency));
        }
        let abort = frame.abort();
        if let Some((multiplexer, code)) = abort {
            self.abort(
                frame.sender(),
                frame.ended(),
                frame.names(),
                line,
                multiplexer,
                code,
            );
        }
        let ended = match frame.ended() {
            Some(transfer) => self.ended(transfer),
            None => false,
        };
        Added {
            abort: abort.is_some(),
            ended,
        }
    }

    /// An abort: recorded with the object's name.
    #[inline(never)]
    fn abort(
        &mut self,
        by: SdoParty,
        ended: Option<&SdoTransfer>,
        names: ObjectNames<'_>,
        line: u64,
        multiplexer: ObjectAddress,
        code: SdoAbortCode,
    ) {
        let multiplexer = match ended {
            Some(ended) if multiplexer == ObjectAddress::default() => ended.multiplexer,
            _ => multiplexer,
        };
        self.summary.aborts.push(SdoAbort {
            line,
            multiplexer,
            object: names.name(multiplexer.index).map(str::to_owned),
            code,
            by,
        });
    }

    /// A transfer that ended (at a frame, or left open at the end of the
    /// input); whether it is recorded as broken or unanswered.
    #[inline]
    pub(crate) fn ended(&mut self, transfer: &SdoTransfer) -> bool {
        match transfer.outcome {
            SdoOutcome::Broken(_) => self.summary.broken.push(transfer.start_position),
            SdoOutcome::TimedOut => self.summary.timeouts.push(transfer.start_position),
            SdoOutcome::Completed | SdoOutcome::Aborted { .. } => return false,
        }
        true
    }

    /// The abort recorded last.
    pub(crate) fn last_abort(&self) -> Option<&SdoAbort> {
        self.summary.aborts.last()
    }

    pub(crate) fn finish(mut self) -> SdoSummary {
        self.summary.latency = self.latencies.stats();
        self.summary
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The statistics as the summary computed them before: every latency
    /// kept, sorted, nearest rank.
    fn sorted_stats(mut all: Vec<u64>) -> Option<LatencyStats> {
        if all.is_empty() {
            return None;
        }
        all.sort_unstable();
        let n = all.len();
        let rank =
            |p: f64| Duration::from_nanos(all[((p * n as f64).ceil() as usize).clamp(1, n) - 1]);
        Some(LatencyStats {
            count: n,
            median: rank(0.5),
            p99: rank(0.99),
            max: Duration::from_nanos(all[n - 1]),
        })
    }

    proptest! {
        /// Whatever the latencies and their order, the table of counts
        /// gives exactly the statistics of sorting them all.
        #[test]
        fn the_histogram_is_exact(
            latencies in proptest::collection::vec(
                prop_oneof![0u64..50, any::<u64>(), Just(u64::MAX)],
                0..3000,
            )
        ) {
            let mut kept = Latencies::default();
            for &l in &latencies {
                kept.push(l);
            }
            let mut distinct = latencies.clone();
            distinct.sort_unstable();
            distinct.dedup();
            prop_assert_eq!(kept.distinct, distinct.len());
            prop_assert!(kept.distinct * 4 <= kept.slots.len() * 3);
            prop_assert_eq!(kept.stats(), sorted_stats(latencies));
        }
    }

    proptest! {
        /// A latency's nanoseconds are `as_nanos`, saturated at
        /// `u64::MAX`.
        #[test]
        fn nanos_are_as_nanos_saturated(secs in any::<u64>(), sub in 0u32..1_000_000_000) {
            let latency = Duration::new(secs, sub);
            prop_assert_eq!(
                nanos(latency),
                u64::try_from(latency.as_nanos()).unwrap_or(u64::MAX)
            );
            let short = Duration::new(secs % 1_000_000, sub);
            prop_assert_eq!(u128::from(nanos(short)), short.as_nanos());
        }
    }

    #[test]
    fn memory_follows_the_distinct_latencies() {
        let mut kept = Latencies::default();
        for i in 0..100_000u64 {
            kept.push(100_000 + (i * 7919) % 400 * 1000);
        }
        assert_eq!(kept.distinct, 400);
        assert_eq!(kept.slots.len(), 1024);
        assert_eq!(
            kept.slots.iter().map(|&(_, count)| count).sum::<u64>(),
            100_000
        );
    }
}
