//! A drive's observed CiA 402 timeline, from statuswords only
//! (docs/summary.md#cia402).

use crate::can::Timestamp;
use crate::canopen::Cia402State;
use crate::decoder::Cia402Reading;

use super::{EmcySeen, Listed};

/// One change of a drive's observed state (`transitions` in
/// docs/summary.md#cia402).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cia402Transition {
    /// The line of the frame that first showed the new state.
    pub line: u64,
    /// Its time, where the log has one.
    pub timestamp: Option<Timestamp>,
    /// The state before (`None` for the first state observed).
    pub from: Option<Cia402State>,
    /// The new state.
    pub to: Cia402State,
}

/// A fault: the state entered `fault_reaction_active` or `fault` from a
/// state that is neither (`faults` in docs/summary.md#cia402), with the drive's
/// last error EMCY before it — what the text summary names as its likely cause.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cia402Fault {
    /// The transition into the fault.
    pub transition: Cia402Transition,
    /// The drive's last error EMCY at or before it, if any.
    pub emcy_before: Option<EmcySeen>,
}

/// A drive's observed timeline (docs/summary.md#cia402, the summary's
/// `cia402`).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Cia402Timeline {
    /// The changes of state, in order (the first and the last, and their
    /// count: docs/summary.md#lists).
    pub transitions: Listed<Cia402Transition>,
    /// The faults, in order (the same); `None` when no statusword was seen (the
    /// decision in docs/summary.md#cia402: nothing observed is not "no fault",
    /// `"faults": null`), `Some` and empty when the drive was seen and never
    /// faulted.
    pub faults: Option<Listed<Cia402Fault>>,
}

impl Cia402Timeline {
    /// Return the last state observed.
    #[must_use]
    pub fn last_state(&self) -> Option<Cia402State> {
        self.transitions.last().map(|t| t.to)
    }

    /// Return whether a statusword of the drive was seen: whether its
    /// faults are known ([`faults`](Self::faults) is `Some`).
    #[must_use]
    pub fn observed(&self) -> bool {
        self.faults.is_some()
    }
}

/// The timeline while the log is read.
#[derive(Debug, Default)]
pub(crate) struct TimelineBuilder {
    timeline: Cia402Timeline,
}

impl TimelineBuilder {
    pub(crate) fn is_empty(&self) -> bool {
        self.timeline.transitions.is_empty()
    }

    /// A frame's CiA 402 reading: a state that differs from the last one
    /// is a transition; entering fault reaction active or fault from a
    /// state that is neither is a fault.
    /// Return the transition recorded, and the fault it is, if any.
    pub(crate) fn observe(
        &mut self,
        line: u64,
        ts: Option<Timestamp>,
        reading: Cia402Reading,
        last_error: Option<EmcySeen>,
    ) -> Option<(Cia402Transition, Option<Cia402Fault>)> {
        let to = reading.state?;
        let timeline = &mut self.timeline;
        let from = timeline.last_state();
        if from == Some(to) {
            return None;
        }
        let transition = Cia402Transition {
            line,
            timestamp: ts,
            from,
            to,
        };
        // The first statusword makes the faults known: none so far.
        let faults = timeline.faults.get_or_insert_with(Listed::new);
        let mut fault = None;
        if to.is_fault() && !from.is_some_and(Cia402State::is_fault) {
            let f = Cia402Fault {
                transition,
                emcy_before: last_error,
            };
            faults.push(f);
            fault = Some(f);
        }
        timeline.transitions.push(transition);
        Some((transition, fault))
    }

    pub(crate) fn finish(self) -> Cia402Timeline {
        self.timeline
    }
}
