//! What a summary is made of: a [`Summary`] of [`NodeSummary`] and
//! [`BusSummary`] records, read in order as [`SummaryRecord`]s.

use crate::can::{BusName, Timestamp};
use crate::canopen::{ErrorRegister, MessageKind, NodeId};
use crate::profiles::Profile;

use super::cia402::Cia402Timeline;
use super::emcy::EmcySeen;
use super::ethercat::{EthercatSummary, PortSummary, SlaveSummary, StreamSummary};
use super::heartbeat::{GuardingSummary, HeartbeatSummary};
use super::listed::Listed;
use super::sdo::SdoSummary;
use super::verdict::Verdict;

/// The frames of a node by kind (`frames` in docs/summary.md#frames): the
/// node-guarding answers ([`MessageKind::GuardAnswer`]) apart from the
/// heartbeats, as the decoder tells them (docs/output.md#heartbeat).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FrameCounts {
    pub(super) by_kind: [u64; MessageKind::ALL.len()],
}

impl FrameCounts {
    /// Return the count of frames of `kind`.
    #[must_use]
    pub fn get(&self, kind: MessageKind) -> u64 {
        self.by_kind[kind.index()]
    }

    /// Return the count of node-guarding answers: the data frames on
    /// 0x700 + node that answer a guard request
    /// ([`get`](Self::get)`(MessageKind::GuardAnswer)`).
    #[must_use]
    pub fn guard_answers(&self) -> u64 {
        self.get(MessageKind::GuardAnswer)
    }

    /// Return every count under its key in the summary, in the order of
    /// [`MessageKind::ALL`], by name.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        MessageKind::ALL
            .into_iter()
            .map(move |kind| (kind.name(), self.by_kind[kind.index()]))
    }
}

/// One device: an (interface, node) seen in the log (docs/summary.md#node, node
/// record).
#[derive(Debug, Clone, PartialEq)]
pub struct NodeSummary {
    /// The bus.
    pub bus: BusName,
    /// The node-ID.
    pub node: NodeId,
    /// Its profile: how its EMCYs' manufacturer bytes read (`--profile`,
    /// docs/canopen.md#profiles).
    pub profile: Profile,
    /// Its frames by kind.
    pub frames: FrameCounts,
    /// EMCYs seen, resets included.
    pub emcy: u64,
    /// Its first error EMCY.
    pub first_error: Option<EmcySeen>,
    /// Its first error EMCY that reports an error present: with its error
    /// register set ([`Emcy::reports_no_error`](crate::canopen::Emcy::reports_no_error)
    /// false; docs/summary.md#severity). The same as
    /// [`first_error`](Self::first_error) unless that one is a warning.
    pub first_error_with_register: Option<EmcySeen>,
    /// The error in its RECV_EMCY_DEV slot at the end of the input: the
    /// root cause under the rule of docs/canopen.md#recv-emcy, `None` after a
    /// reset.
    pub active_error: Option<EmcySeen>,
    /// Reset EMCYs (error code 0000h) seen.
    pub resets: u64,
    /// The error register of its last EMCY (a reset with a non-zero
    /// register: other errors are still active).
    pub last_register: Option<ErrorRegister>,
    /// Its heartbeats.
    pub heartbeat: HeartbeatSummary,
    /// Its node-guarding answers.
    pub guarding: GuardingSummary,
    /// Its SDO channel (docs/summary.md#sdo).
    pub sdo: SdoSummary,
    /// Its observed CiA 402 timeline, for a drive (docs/summary.md#cia402);
    /// `None` for a node that is not a drive.
    pub cia402: Option<Cia402Timeline>,
}

/// One interface (docs/summary.md#bus, bus record).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BusSummary {
    /// The bus.
    pub bus: BusName,
    /// Frames seen on it, error frames included.
    pub frames: u64,
    /// Error frames seen on it.
    pub error_frames: u64,
    /// The lines of error frames that say bus-off (the first and the
    /// last, and their count: docs/summary.md#lists).
    pub bus_off: Listed<u64>,
    /// The lines of error frames that say error-passive (the same).
    pub error_passive: Listed<u64>,
    /// Log entries that are not frames (a TRC status row).
    pub status_events: u64,
    /// The earliest time seen on it.
    pub first_timestamp: Option<Timestamp>,
    /// The latest time seen on it.
    pub last_timestamp: Option<Timestamp>,
    /// The node-IDs seen on it, in order.
    pub nodes: Vec<NodeId>,
}

/// The post-mortem of a whole input (docs/summary.md): the devices by bus then
/// node-ID, then the buses in the same order.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// One record per (interface, node) seen.
    pub nodes: Vec<NodeSummary>,
    /// One record per interface.
    pub buses: Vec<BusSummary>,
    /// The file the summary is of, when it should name it: set by a caller
    /// that summarizes several logs apart, so that every record says which
    /// log its lines are in (`"file"` in JSON, `FILE: ` in text).
    pub file: Option<String>,
    /// Whether heartbeat timeouts were checked: `None` when not asked,
    /// `Some(false)` when frames without a time made it impossible.
    pub(super) checked: Option<bool>,
    /// The verdict on its findings ([`Verdict::of`]).
    pub(super) verdict: Option<Verdict>,
    /// The EtherCAT captures' part: interfaces, slaves, cyclic streams
    /// (docs/ethercat.md#summary).
    pub ethercat: EthercatSummary,
}

/// One record of the summary, as `decode --summary` writes them: the
/// nodes, then the buses; with the file the summary is of, when it names
/// one (several logs read apart; docs/output.md#several-files).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummaryRecord<'s> {
    /// The summary's file ([`Summary::file`]).
    pub file: Option<&'s str>,
    /// The record.
    pub item: SummaryItem<'s>,
}

/// What a [`SummaryRecord`] is about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SummaryItem<'s> {
    /// What stopped the machine and its first cause (docs/summary.md#verdict).
    Verdict(&'s Verdict),
    /// A device.
    Node(&'s NodeSummary),
    /// A bus.
    Bus(&'s BusSummary),
    /// An interface of an EtherCAT capture (docs/ethercat.md#summary).
    EthercatPort(&'s PortSummary),
    /// An EtherCAT slave.
    Slave(&'s SlaveSummary),
    /// A cyclic EtherCAT datagram stream.
    Stream(&'s StreamSummary),
}

impl Summary {
    /// Return the records in output order: the verdict when something
    /// stopped (docs/summary.md#verdict), every node, then every bus.
    pub fn records(&self) -> impl Iterator<Item = SummaryRecord<'_>> + '_ {
        let file = self.file.as_deref();
        self.verdict
            .iter()
            .map(SummaryItem::Verdict)
            .chain(self.nodes.iter().map(SummaryItem::Node))
            .chain(self.buses.iter().map(SummaryItem::Bus))
            .chain(self.ethercat.ports.iter().map(SummaryItem::EthercatPort))
            .chain(self.ethercat.slaves.iter().map(SummaryItem::Slave))
            .chain(self.ethercat.streams.iter().map(SummaryItem::Stream))
            .map(move |item| SummaryRecord { file, item })
    }

    /// Return what stopped the machine and its first cause, when something
    /// stopped (docs/summary.md#verdict).
    #[must_use]
    pub fn verdict(&self) -> Option<&Verdict> {
        self.verdict.as_ref()
    }

    /// Return whether heartbeat timeouts were asked for but could not be
    /// checked because frames had no timestamps (docs/formats.md#timestamps: a
    /// program says so once).
    #[must_use]
    pub fn timeouts_not_checked(&self) -> bool {
        self.checked == Some(false)
    }

    /// Return the node `node` on `bus`, if it was seen.
    #[must_use]
    pub fn node(&self, bus: &BusName, node: NodeId) -> Option<&NodeSummary> {
        self.nodes.iter().find(|n| &n.bus == bus && n.node == node)
    }
}
