//! What the summary records, as it records it: one [`SummaryEvent`] per
//! fact a frame adds to the post-mortem (docs/summary.md), handed to the
//! caller of [`Summarizer::add_with`](super::Summarizer::add_with)
//! and [`Summarizer::finish_with`](super::Summarizer::finish_with). The
//! report's timeline (docs/report.md#timeline) is drawn from them, so that
//! its marks are exactly the summary's facts.

use core::time::Duration;

use crate::can::{BusName, Timestamp};
use crate::canopen::sdo::SdoTransfer;
use crate::canopen::{ErrorCode, ErrorRegister, NmtStateByte, NodeId};

use super::ethercat::FactAt;
use super::{Cia402Fault, Cia402Transition, EthercatFact, HeartbeatGap, SdoAbort};

impl<'s> From<FactAt<'s>> for SummaryEvent<'s> {
    /// The fact as the summary's event: its interface the bus, its
    /// packet the line.
    fn from(f: FactAt<'s>) -> Self {
        SummaryEvent {
            bus: f.iface,
            node: None,
            line: f.packet,
            timestamp: f.timestamp,
            kind: SummaryEventKind::Ethercat(f.fact),
        }
    }
}

/// One fact the summary records, where it records it: the bus (or the
/// EtherCAT interface), the node (none for a bus's facts and for
/// EtherCAT's), the line (an EtherCAT capture's packet) the summary names
/// and its time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummaryEvent<'s> {
    /// The bus.
    pub bus: &'s BusName,
    /// The node, for a device's facts; `None` for a bus's (error frames)
    /// and for an EtherCAT fact, whose kind names its slave or stream.
    pub node: Option<NodeId>,
    /// The line the summary names for it (for a heartbeat timeout, the
    /// heartbeat before the gap; for a broken or unanswered SDO transfer,
    /// its start).
    pub line: u64,
    /// The time of that line, where the log has one.
    pub timestamp: Option<Timestamp>,
    /// What happened.
    pub kind: SummaryEventKind<'s>,
}

/// What a [`SummaryEvent`] is (docs/summary.md, key by key).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum SummaryEventKind<'s> {
    /// An EMCY, counted in `emcy`; a reset EMCY (code 0000h) also in
    /// `resets` (docs/summary.md#emcy).
    Emcy {
        /// Its error code.
        code: ErrorCode,
        /// Its error register.
        register: ErrorRegister,
        /// Its manufacturer-specific bytes 3–7, which the node's profile
        /// reads (docs/summary.md#profiles).
        manufacturer: [u8; 5],
    },
    /// A heartbeat or a node-guarding answer, with the NMT state it
    /// reports (docs/summary.md#heartbeat, docs/summary.md#guarding).
    Nmt {
        /// The state byte (bit 7 the toggle of a guarding answer).
        state: NmtStateByte,
        /// Whether it answered a guard request (else a heartbeat).
        guard_answer: bool,
    },
    /// A boot-up message (`heartbeat.boot_ups`).
    BootUp,
    /// A heartbeat gap longer than the consumer time
    /// (`heartbeat.timeouts`): reported when the gap closes, at the next
    /// heartbeat (before that heartbeat's own events) or at the end of the
    /// input.
    HeartbeatTimeout(HeartbeatGap),
    /// A node-guarding answer with a wrong toggle (`guarding.toggle_errors`).
    ToggleError,
    /// An SDO abort (`sdo.aborts`).
    SdoAbort(&'s SdoAbort),
    /// A broken SDO transfer (`sdo.broken`).
    SdoBroken(&'s SdoTransfer),
    /// An SDO transfer no response answered (`sdo.timeouts`).
    SdoTimeout(&'s SdoTransfer),
    /// A change of a drive's observed CiA 402 state (`cia402.transitions`),
    /// with the fault it is when it enters a fault state (`cia402.faults`).
    Cia402 {
        /// The transition.
        transition: Cia402Transition,
        /// The fault, when the transition is one.
        fault: Option<Cia402Fault>,
    },
    /// An error frame (`error_frames` of the bus record), and whether it
    /// says bus-off (`bus_off`) or error-passive (`error_passive`).
    ErrorFrame {
        /// It says bus-off.
        bus_off: bool,
        /// It says error-passive.
        error_passive: bool,
    },
    /// A fact of an EtherCAT capture's slave or stream record
    /// (docs/ethercat.md#summary).
    Ethercat(EthercatFact),
}

impl SummaryEventKind<'_> {
    /// Return the span a heartbeat timeout covers, from the heartbeat
    /// before it; zero for every other event.
    #[must_use]
    pub fn span(&self) -> Duration {
        match self {
            SummaryEventKind::HeartbeatTimeout(gap) => gap.gap,
            _ => Duration::ZERO,
        }
    }
}
