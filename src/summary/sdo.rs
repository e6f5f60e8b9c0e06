//! A node's SDO channel in the summary (docs/summary.md#sdo): requests,
//! transfers, aborts, broken and unanswered transfers, response latencies.

use core::time::Duration;

use crate::canopen::sdo::{SdoMessage, SdoOutcome, SdoParty, SdoRequest, SdoResponse, SdoTransfer};
use crate::canopen::{ObjectAddress, SdoAbortCode};
use crate::decoder::SdoStep;

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
    /// Every latency in nanoseconds, for exact percentiles: 8 bytes a
    /// request (a `Duration` takes 16; u64 nanoseconds hold 584 years).
    latencies: Vec<u64>,
}

impl SdoStats {
    /// Add one frame of the node's channel, as its tracker read it.
    pub(crate) fn add(&mut self, step: &SdoStep<'_>, line: u64) -> Added {
        let mut added = Added::default();
        let s = &mut self.summary;
        if step.sender == SdoParty::Client {
            s.requests += 1;
        }
        if step.started {
            s.transfers += 1;
        }
        if let Some(latency) = step.latency {
            self.latencies
                .push(u64::try_from(latency.as_nanos()).unwrap_or(u64::MAX));
        }
        let abort = match step.message {
            Ok(SdoMessage::Request(SdoRequest::Abort { multiplexer, code })) => {
                Some((multiplexer, code, SdoParty::Client))
            }
            Ok(SdoMessage::Response(SdoResponse::Abort { multiplexer, code })) => {
                Some((multiplexer, code, SdoParty::Server))
            }
            _ => None,
        };
        if let Some((multiplexer, code, by)) = abort {
            let multiplexer = match step.ended {
                Some(ended) if multiplexer == ObjectAddress::default() => {
                    ended.transfer.multiplexer
                }
                _ => multiplexer,
            };
            s.aborts.push(SdoAbort {
                line,
                multiplexer,
                object: step.names.name(multiplexer.index).map(str::to_owned),
                code,
                by,
            });
            added.abort = true;
        }
        if let Some(ended) = step.ended {
            added.ended = self.ended(&ended.transfer);
        }
        added
    }

    /// A transfer that ended (at a frame, or left open at the end of the
    /// input); whether it is recorded as broken or unanswered.
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
        if !self.latencies.is_empty() {
            let sorted = &mut self.latencies;
            sorted.sort_unstable();
            let n = sorted.len();
            // Nearest rank: the smallest value with at least p of them at
            // or below it.
            let rank = |p: f64| {
                Duration::from_nanos(sorted[((p * n as f64).ceil() as usize).clamp(1, n) - 1])
            };
            self.summary.latency = Some(LatencyStats {
                count: n,
                median: rank(0.5),
                p99: rank(0.99),
                max: Duration::from_nanos(sorted[n - 1]),
            });
        }
        self.summary
    }
}
