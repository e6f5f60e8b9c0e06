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
use crate::ethercat::{AlStatusCode, Command};

use super::{
    AlChange, Cia402Fault, Cia402Transition, CoeEmergency, CoeSdoAbort, CounterRise, DlChange,
    HeartbeatGap, SdoAbort, ServoEvent,
};

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

/// A fact an EtherCAT capture adds to its slave and stream records
/// (docs/ethercat.md#summary), handed over as a [`SummaryEvent`] whose
/// `bus` is the interface and whose `line` is the packet the record names.
///
/// A slave is named by its place among the slave records of its interface,
/// in the order [`EthercatSummary::slaves`](super::EthercatSummary::slaves)
/// keeps them; a stream by its command and address, as its
/// [`StreamSummary`](super::StreamSummary) has them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum EthercatFact {
    /// A change of AL state requested or reported: an entry of
    /// `al_timeline`, or one of those `al_timeline_dropped` counts.
    AlState {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The change.
        change: AlChange,
    },
    /// An AL status code read alone, which completes the status read at
    /// `of` (its `al_timeline` entry then has the code).
    AlCode {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The packet of the status read the code completes.
        of: u64,
        /// The code.
        code: AlStatusCode,
    },
    /// A CoE emergency, counted in `emcy_count`.
    Emergency {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The emergency.
        emergency: CoeEmergency,
    },
    /// A CoE SDO abort, counted in `sdo_aborts`.
    SdoAbort {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The abort.
        abort: CoeSdoAbort,
    },
    /// A change of DL status, an entry of `dl_status_changes`.
    DlChange {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The change.
        change: DlChange,
    },
    /// A rise of an error counter, an entry of `error_counter_rises`.
    CounterRise {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The rise.
        rise: CounterRise,
    },
    /// A returned copy of a stream's datagram whose working counter the
    /// stream record counts: `wkc_mismatches` counts those whose `wkc` is
    /// not the record's `wkc_usual`, which only the end of the capture
    /// tells.
    StreamReturned {
        /// The stream's command.
        command: Command,
        /// The stream's address word.
        address: u32,
        /// The working counter.
        wkc: u16,
    },
    /// A change of a CiA 402 drive's state from its process data, an entry
    /// of the slave's `cia402.transitions`, with the fault it is, if any.
    Cia402 {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The transition.
        transition: Cia402Transition,
        /// The fault it is.
        fault: Option<Cia402Fault>,
    },
    /// A change of a servo's handshakes, faults or ServoRDY, an entry of
    /// the slave's `servo.events`.
    Servo {
        /// The slave's place among its interface's slave records.
        slave: usize,
        /// The event.
        event: ServoEvent,
    },
    /// A frame sent with the stream's datagram that never came back,
    /// counted in the stream's `lost`; the event's line is the sent
    /// copy's packet.
    StreamLost {
        /// The stream's command.
        command: Command,
        /// The stream's address word.
        address: u32,
    },
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
