//! The post-mortem of an EtherCAT capture (docs/ethercat.md#summary): a
//! record per interface (frames sent, returned, lost), per slave (identity,
//! the AL state timeline with its status codes, CoE emergencies, SDO and
//! mailbox counts) and per cyclic datagram stream (cycle time, jitter,
//! working-counter mismatches), read from what `ethercat::Session` tells.

use core::fmt;
use std::collections::VecDeque;

use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

use crate::can::{BusName, EthercatPacket, Timestamp};
use crate::canopen::Emcy;
use crate::decoder::ethercat::{
    AlRegister, CoeSdoStep, Counts, FrameCopy, Meaning, ProcessData, Session, SlaveRef,
    ERROR_COUNTERS_LEN, PAIRING_WINDOW,
};
use crate::ethercat::{
    AlStatus, AlStatusCode, CoeHeader, CoeSdo, CoeService, Command, Datagram, FrameType,
    MailboxType, COE_HEADER_LEN,
};
use crate::logs::Position;
use crate::profiles::Profile;

use super::cia402::{Cia402Fault, Cia402Timeline, Cia402Transition, TimelineBuilder};
use super::emcy::EmcySeen;
pub use super::ethercat_regs::{DcSummary, SlaveRegisters};
use super::servo::{ServoEvent, ServoTimeline};
use super::values::{Iface, Ts};

/// The AL state changes a slave record keeps; more are counted.
pub const MAX_AL_CHANGES: usize = 256;
/// The CoE emergencies a slave record keeps; more are counted.
pub const MAX_EMERGENCIES: usize = 256;
/// The datagram streams of an interface that are followed; a capture with
/// more distinct (command, address) pairs counts the rest.
pub const MAX_STREAMS: usize = 256;
/// A stream of FPRD or BRD status reads is cyclic, and reported, from this
/// many returned frames on (LRD, LWR, LRW, ARMW and FRMW always are).
pub const STATUS_STREAM_MIN: u64 = 100;

/// An AL state as a slave reported it, or as the master requested it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AlChange {
    /// The packet.
    pub packet: u64,
    /// When.
    pub timestamp: Option<Timestamp>,
    /// Requested by AL control (`true`) or reported by AL status.
    pub requested: bool,
    /// The status or control word.
    pub status: AlStatus,
    /// The AL status code, when read with it.
    pub code: Option<AlStatusCode>,
}

/// A CoE emergency a slave sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CoeEmergency {
    /// The packet it was read in.
    pub packet: u64,
    /// When.
    pub timestamp: Option<Timestamp>,
    /// The EMCY.
    pub emcy: Emcy,
    /// The profile that reads it.
    pub profile: Profile,
}

/// What a capture showed of one slave (`type: "slave"`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlaveSummary {
    /// The interface.
    pub iface: BusName,
    /// The configured station address.
    pub station: Option<u16>,
    /// The position on the ring.
    pub position: Option<u16>,
    /// SII vendor id.
    pub vendor: Option<u32>,
    /// SII product code.
    pub product: Option<u32>,
    /// SII revision.
    pub revision: Option<u32>,
    /// SII serial number.
    pub serial: Option<u32>,
    /// Every change of AL status or request, in order (at most
    /// [`MAX_AL_CHANGES`]).
    pub al_changes: Vec<AlChange>,
    /// AL changes past the limit.
    pub al_changes_dropped: u64,
    /// The last AL status read.
    pub al_last: Option<AlChange>,
    /// CoE emergencies (at most [`MAX_EMERGENCIES`]).
    pub emergencies: Vec<CoeEmergency>,
    /// Emergencies past the limit.
    pub emergencies_dropped: u64,
    /// CoE SDO requests written.
    pub sdo_requests: u64,
    /// CoE SDO responses read.
    pub sdo_responses: u64,
    /// SDO aborts, from either side.
    pub sdo_aborts: u64,
    /// SDO transfers that ended with their last confirmation.
    pub sdo_ok: u64,
    /// The aborts, each with its object (the first [`MAX_EMERGENCIES`]).
    pub sdo_abort_list: Vec<CoeSdoAbort>,
    /// The median time from a transfer's request to its last confirmation,
    /// ns (two significant digits).
    pub sdo_latency_median_ns: Option<u64>,
    /// The longest, ns.
    pub sdo_latency_max_ns: Option<u64>,
    /// Mailbox messages written and accepted.
    pub mailbox_written: u64,
    /// Mailbox messages read.
    pub mailbox_read: u64,
    /// Mailbox writes the slave did not accept.
    pub mailbox_refused: u64,
    /// Mailbox messages found in a guessed area.
    pub mailbox_guessed: u64,
    /// The DL status as last read (0x0110 low, 0x0111 high byte).
    pub dl_last: (Option<u8>, Option<u8>),
    /// Every change of DL status after the first read (at most
    /// [`MAX_AL_CHANGES`]).
    pub dl_changes: Vec<DlChange>,
    /// The error counters as last read (0x0300–0x0313).
    pub counters_last: [Option<u8>; ERROR_COUNTERS_LEN],
    /// Every rise of an error counter (a fall is a reset: not kept; at most
    /// [`MAX_AL_CHANGES`]).
    pub counter_rises: Vec<CounterRise>,
    /// Cycles of process data read for the slave (returned cyclic
    /// datagrams that hold its images).
    pub process_cycles: u64,
    /// Of them, cycles whose inputs the working counter left unconfirmed.
    pub process_unconfirmed: u64,
    /// The first of them: packet and working counter, expected count.
    pub first_unconfirmed: Option<(u64, u16, Option<u16>)>,
    /// The CiA 402 timeline of a slave whose PDOs map 6041h
    /// (docs/summary.md#cia402, the same as a CAN drive's).
    pub cia402: Option<Cia402Timeline>,
    /// The servo timeline of a slave read as a servo (docs/ethercat.md#servo).
    pub servo: Option<ServoTimeline>,
    /// Its station alias, mailbox polls and repeats, distributed clock.
    pub registers: SlaveRegisters,
}

/// A CoE SDO abort, from either side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CoeSdoAbort {
    /// The packet of the abort.
    pub packet: u64,
    /// When.
    pub timestamp: Option<Timestamp>,
    /// The object, as the abort names it.
    pub index: u16,
    /// Its sub-index.
    pub subindex: u8,
    /// The abort code.
    pub code: crate::canopen::SdoAbortCode,
    /// Whether the slave sent it (read from its mailbox, whatever the
    /// service) rather than the master.
    pub from_slave: bool,
}

/// A change of a slave's DL status.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DlChange {
    /// The packet.
    pub packet: u64,
    /// When.
    pub timestamp: Option<Timestamp>,
    /// The bytes before (low, high; as far as read).
    pub from: (Option<u8>, Option<u8>),
    /// The bytes after.
    pub to: (Option<u8>, Option<u8>),
}

/// A rise of one error counter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CounterRise {
    /// The packet.
    pub packet: u64,
    /// When.
    pub timestamp: Option<Timestamp>,
    /// The counter's register, 0x0300–0x0313.
    pub register: u16,
    /// Its value before.
    pub from: u8,
    /// Its value after.
    pub to: u8,
}

/// A cyclic datagram stream (`type: "stream"`): one command at one address
/// (docs/ethercat.md#cycle-health).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StreamSummary {
    /// The interface.
    pub iface: BusName,
    /// The command.
    pub command: Command,
    /// The address word (logical, or ADP and ADO).
    pub address: u32,
    /// Frames sent with it.
    pub sent: u64,
    /// Returned copies read.
    pub returned: u64,
    /// Frames sent with it that never came back
    /// (docs/ethercat.md#direction: pushed out of the pairing window,
    /// passed over by a later frame's returned copy, or still waiting at
    /// the end of the capture).
    pub lost: u64,
    /// Intervals between sent frames measured (both times known).
    pub intervals: u64,
    /// Intervals of zero: the capture's clock could not tell the frames
    /// apart.
    pub zero_intervals: u64,
    /// The median interval, ns (from a histogram: two significant digits).
    pub cycle_median_ns: Option<u64>,
    /// The 99th percentile, ns (two significant digits).
    pub cycle_p99_ns: Option<u64>,
    /// The longest interval, ns.
    pub cycle_max_ns: Option<u64>,
    /// The standard deviation of the intervals, ns: the jitter.
    pub jitter_ns: Option<u64>,
    /// The working counter the stream has most often.
    pub wkc_usual: Option<u16>,
    /// Returned copies with another working counter.
    pub wkc_mismatches: u64,
    /// The first of them.
    pub first_mismatch: Option<(u64, Option<Timestamp>, u16)>,
}

impl SlaveSummary {
    /// A slave of `iface` that nothing is known of yet.
    #[must_use]
    pub fn new(iface: BusName) -> Self {
        SlaveSummary {
            iface,
            station: None,
            position: None,
            vendor: None,
            product: None,
            revision: None,
            serial: None,
            al_changes: Vec::new(),
            al_changes_dropped: 0,
            al_last: None,
            emergencies: Vec::new(),
            emergencies_dropped: 0,
            sdo_requests: 0,
            sdo_responses: 0,
            sdo_aborts: 0,
            sdo_ok: 0,
            sdo_abort_list: Vec::new(),
            sdo_latency_median_ns: None,
            sdo_latency_max_ns: None,
            mailbox_written: 0,
            mailbox_read: 0,
            mailbox_refused: 0,
            mailbox_guessed: 0,
            dl_last: (None, None),
            dl_changes: Vec::new(),
            counters_last: [None; ERROR_COUNTERS_LEN],
            counter_rises: Vec::new(),
            process_cycles: 0,
            process_unconfirmed: 0,
            first_unconfirmed: None,
            cia402: None,
            servo: None,
            registers: SlaveRegisters::default(),
        }
    }
}

impl StreamSummary {
    /// Return the stream's command and address as the text writes them:
    /// `LRW logical 0x00000000`, `FRMW adp 0x1000 ado 0x0910`.
    #[must_use]
    pub fn key(&self) -> String {
        if matches!(self.command, Command::Lrd | Command::Lwr | Command::Lrw) {
            format!("{} logical {:#010x}", self.command.name(), self.address)
        } else {
            format!(
                "{} adp {:#06x} ado {:#06x}",
                self.command.name(),
                self.address & 0xFFFF,
                self.address >> 16
            )
        }
    }

    /// Return whether the capture's clock resolves the cycle: fewer than
    /// half the intervals are 0 (docs/ethercat.md#cycle-health; TwinCAT's
    /// captures are often coarser).
    #[must_use]
    pub const fn resolved(&self) -> bool {
        self.intervals > 0 && self.zero_intervals * 2 < self.intervals
    }
}

/// What a capture's interface showed (`type: "ethercat"`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PortSummary {
    /// The interface.
    pub iface: BusName,
    /// The session's counts for the whole capture.
    pub counts: Counts,
    /// Streams not followed past [`MAX_STREAMS`], by frames.
    pub streams_dropped: u64,
}

/// The EtherCAT part of a summary.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct EthercatSummary {
    /// One per interface with EtherCAT.
    pub ports: Vec<PortSummary>,
    /// One per slave seen, by interface and first sight.
    pub slaves: Vec<SlaveSummary>,
    /// One per cyclic stream.
    pub streams: Vec<StreamSummary>,
}

/// A log-scale histogram of intervals: two significant digits from 1 ns to
/// 10^10 ns, constant memory.
#[derive(Debug, Clone)]
struct Histogram {
    /// `[decade][mantissa 10..=99]`.
    counts: Box<[[u32; 90]; 11]>,
    total: u64,
    /// The largest value added.
    max: Option<u64>,
}

impl Histogram {
    fn new() -> Self {
        Histogram {
            counts: Box::new([[0; 90]; 11]),
            total: 0,
            max: None,
        }
    }

    fn add(&mut self, ns: u64) {
        self.max = Some(self.max.map_or(ns, |m| m.max(ns)));
        let (decade, mantissa) = split(ns);
        if let Some(cell) = self
            .counts
            .get_mut(decade)
            .and_then(|d| d.get_mut(mantissa))
        {
            *cell = cell.saturating_add(1);
            self.total += 1;
        }
    }

    /// The value below which `fraction` of the intervals lie.
    fn quantile(&self, fraction: f64) -> Option<u64> {
        if self.total == 0 {
            return None;
        }
        let rank = ((self.total as f64) * fraction).ceil().max(1.0) as u64;
        let mut seen = 0u64;
        for (decade, row) in self.counts.iter().enumerate() {
            for (mantissa, count) in row.iter().enumerate() {
                seen += u64::from(*count);
                if seen >= rank {
                    return Some(join(decade, mantissa));
                }
            }
        }
        None
    }
}

/// `ns` as a decade and a two-digit mantissa (0 counts as 1 ns's bucket's
/// floor, 10).
fn split(ns: u64) -> (usize, usize) {
    let mut value = ns.max(10);
    let mut decade = 0;
    while value >= 100 {
        value /= 10;
        decade += 1;
    }
    (decade, (value - 10) as usize)
}

/// The lower bound of a bucket.
fn join(decade: usize, mantissa: usize) -> u64 {
    (mantissa as u64 + 10) * 10u64.pow(decade as u32)
}

/// A stream as it is being read.
#[derive(Debug, Clone)]
struct Stream {
    command: Command,
    address: u32,
    sent: u64,
    returned: u64,
    lost: u64,
    last_sent: Option<Timestamp>,
    histogram: Histogram,
    zero: u64,
    max: u64,
    /// Welford's running mean and sum of squares, ns.
    mean: f64,
    m2: f64,
    intervals: u64,
    /// Working counters seen, with how often and where first.
    wkcs: Vec<(u16, u64, u64, Option<Timestamp>)>,
}

/// A sent frame waiting for its returned copy, as the session's pairing
/// window holds it (docs/ethercat.md#direction): its packet, time and how
/// many of the port's `waiting_streams` are its streams' datagrams.
#[derive(Debug, Clone, Copy)]
struct Waiting {
    packet: u64,
    timestamp: Option<Timestamp>,
    streams: usize,
}

/// A port as it is being read.
#[derive(Debug)]
struct Port {
    name: BusName,
    slaves: Vec<SlaveSummary>,
    /// Per slave (same index): its SDO transfers' latencies.
    sdo: Vec<Histogram>,
    /// Per slave (same index): the CiA 402 timeline of a drive.
    drives: Vec<Option<TimelineBuilder>>,
    streams: Vec<Stream>,
    streams_dropped: u64,
    /// The sent frames of datagrams waiting for their returned copy, in
    /// the order the session's window keeps them, so that a lost frame's
    /// streams are known.
    waiting: VecDeque<Waiting>,
    /// The streams (places in `streams`) of the waiting frames' datagrams,
    /// in order.
    waiting_streams: VecDeque<u16>,
    /// DL control's alias bit as a BWR last set it for every slave.
    alias_broadcast: Option<bool>,
}

/// Reads a capture's EtherCAT packets for the summary.
#[derive(Debug, Default)]
pub(crate) struct EthercatSummarizer {
    session: Session,
    /// The interfaces' names, at their ports' places.
    names: Vec<BusName>,
    ports: Vec<Port>,
}

/// A fact an EtherCAT capture adds to its slave and stream records
/// (docs/ethercat.md#summary), handed over as a [`SummaryEvent`](super::SummaryEvent) whose
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

/// A fact of the slave and stream records, where it was recorded: the
/// interface, the packet and its time. The summarizer hands it on as a
/// `SummaryEvent`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FactAt<'s> {
    /// The interface.
    pub(crate) iface: &'s BusName,
    /// The packet.
    pub(crate) packet: u64,
    /// Its time.
    pub(crate) timestamp: Option<Timestamp>,
    /// The fact.
    pub(crate) fact: EthercatFact,
}

/// Hand on a fact of the interface `iface` at `packet`.
fn fact(
    on_event: &mut impl FnMut(FactAt<'_>),
    iface: &BusName,
    packet: u64,
    timestamp: Option<Timestamp>,
    fact: EthercatFact,
) {
    on_event(FactAt {
        iface,
        packet,
        timestamp,
        fact,
    });
}

impl EthercatSummarizer {
    /// A summarizer with the EtherCAT settings of `config`.
    pub(crate) fn new(config: &crate::decoder::DecoderConfig) -> Self {
        EthercatSummarizer {
            session: Session::with_config(config),
            ..EthercatSummarizer::default()
        }
    }

    /// Read one packet: its datagrams, what they tell, its streams; hand
    /// `on_event` each fact it adds to the slave and stream records, and
    /// `on_process` each slave's process data as the session cut it, with
    /// the slave's interface and place among its interface's records.
    pub(crate) fn add(
        &mut self,
        position: Position,
        event: &EthercatPacket<'_>,
        mut on_event: impl FnMut(FactAt<'_>),
        mut on_process: impl FnMut(&BusName, usize, &ProcessData<'_>),
    ) {
        let Ok(packet) = self.session.read(position, event) else {
            return;
        };
        let port = match self.names.iter().position(|n| n.is(packet.iface)) {
            Some(at) => at,
            None => {
                let name = BusName::of(packet.iface);
                self.names.push(name.clone());
                self.ports.push(Port {
                    name,
                    slaves: Vec::new(),
                    sdo: Vec::new(),
                    drives: Vec::new(),
                    streams: Vec::new(),
                    streams_dropped: 0,
                    waiting: VecDeque::new(),
                    waiting_streams: VecDeque::new(),
                    alias_broadcast: None,
                });
                self.ports.len() - 1
            }
        };
        let iface = &self.names[port];
        let number = position.number();
        let datagrams = packet.frame.frame_type() == FrameType::Datagrams;
        let sent_frame = datagrams && packet.copy == FrameCopy::Sent;
        {
            let port = &mut self.ports[port];
            match packet.copy {
                FrameCopy::Returned { sent } => port.paired(sent.number(), iface, &mut on_event),
                // The window is full: its oldest frame is lost.
                FrameCopy::Sent if sent_frame && port.waiting.len() == PAIRING_WINDOW => {
                    port.lose_first(iface, &mut on_event);
                }
                _ => {}
            }
        }
        let mut streams = 0;
        for (at, datagram) in packet.datagrams().enumerate() {
            let Ok(datagram) = datagram else {
                self.session.count_damaged();
                break;
            };
            let port = &mut self.ports[port];
            self.session.meanings(&packet, at, &datagram, |meaning| {
                port.meaning(number, packet.timestamp, meaning, &mut |f| {
                    fact(&mut on_event, iface, number, packet.timestamp, f);
                });
            });
            let sent_adp = packet.sent_adp(at, &datagram);
            let stream = port.stream(
                packet.copy,
                packet.timestamp,
                number,
                &datagram,
                sent_adp,
                &mut |f| fact(&mut on_event, iface, number, packet.timestamp, f),
            );
            if let (true, Some(stream)) = (sent_frame, stream) {
                port.waiting_streams.push_back(stream);
                streams += 1;
            }
            let timestamp = packet.timestamp;
            self.session.process_data(&packet, at, &datagram, |data| {
                let place = port.process_data(number, timestamp, data, &mut |f| {
                    fact(&mut on_event, iface, number, timestamp, f);
                });
                if let Some(place) = place {
                    on_process(iface, place, data);
                }
            });
        }
        if sent_frame {
            self.ports[port].waiting.push_back(Waiting {
                packet: number,
                timestamp: packet.timestamp,
                streams,
            });
        }
    }

    /// The summary of what was read; the frames still waiting are lost,
    /// and handed to `on_event`.
    pub(crate) fn finish(mut self, mut on_event: impl FnMut(FactAt<'_>)) -> EthercatSummary {
        let counts = self.session.finish();
        for (port, iface) in self.ports.iter_mut().zip(&self.names) {
            while !port.waiting.is_empty() {
                port.lose_first(iface, &mut on_event);
            }
        }
        let mut summary = EthercatSummary::default();
        for (at, (port, name)) in self.ports.into_iter().zip(self.names).enumerate() {
            summary.ports.push(PortSummary {
                iface: name.clone(),
                // The session counts the whole capture: the first
                // interface's record carries the counts
                // (docs/ethercat.md#summary).
                counts: if at == 0 { counts } else { Counts::default() },
                streams_dropped: port.streams_dropped,
            });
            for ((mut slave, latencies), drive) in
                port.slaves.into_iter().zip(port.sdo).zip(port.drives)
            {
                slave.sdo_latency_median_ns = latencies.quantile(0.5);
                slave.sdo_latency_max_ns = latencies.max;
                slave.cia402 = drive.map(TimelineBuilder::finish);
                summary.slaves.push(slave);
            }
            for stream in port.streams {
                let cyclic = matches!(
                    stream.command,
                    Command::Lrd | Command::Lwr | Command::Lrw | Command::Armw | Command::Frmw
                ) || stream.returned >= STATUS_STREAM_MIN;
                if cyclic {
                    summary.streams.push(stream.finish(name.clone()));
                }
            }
        }
        summary
    }
}

impl Stream {
    fn finish(self, iface: BusName) -> StreamSummary {
        let usual = self
            .wkcs
            .iter()
            .max_by_key(|(wkc, count, ..)| (*count, u16::MAX - wkc))
            .map(|w| w.0);
        let mismatches = self
            .wkcs
            .iter()
            .filter(|w| Some(w.0) != usual)
            .map(|w| w.1)
            .sum();
        let first_mismatch = self
            .wkcs
            .iter()
            .filter(|w| Some(w.0) != usual)
            .min_by_key(|w| w.2)
            .map(|w| (w.2, w.3, w.0));
        let jitter = (self.intervals > 1)
            .then(|| (self.m2 / (self.intervals - 1) as f64).sqrt().round() as u64);
        StreamSummary {
            iface,
            command: self.command,
            address: self.address,
            sent: self.sent,
            returned: self.returned,
            lost: self.lost,
            intervals: self.intervals,
            zero_intervals: self.zero,
            cycle_median_ns: self.histogram.quantile(0.5),
            cycle_p99_ns: self.histogram.quantile(0.99),
            cycle_max_ns: (self.intervals > 0).then_some(self.max),
            jitter_ns: jitter,
            wkc_usual: usual,
            wkc_mismatches: mismatches,
            first_mismatch,
        }
    }
}

impl Port {
    fn slave(&mut self, slave: SlaveRef) -> Option<(usize, &mut SlaveSummary)> {
        let at = self.slave_at(slave)?;
        Some((at, &mut self.slaves[at]))
    }

    /// A returned copy paired with the frame sent at `sent`: the frames
    /// sent before it are lost (docs/ethercat.md#direction).
    fn paired(&mut self, sent: u64, iface: &BusName, on_event: &mut impl FnMut(FactAt<'_>)) {
        if !self.waiting.iter().any(|w| w.packet == sent) {
            return;
        }
        while let Some(first) = self.waiting.front().copied() {
            if first.packet == sent {
                self.waiting.pop_front();
                for _ in 0..first.streams {
                    self.waiting_streams.pop_front();
                }
                return;
            }
            self.lose_first(iface, on_event);
        }
    }

    /// The oldest waiting frame is lost: each of its streams counts it.
    fn lose_first(&mut self, iface: &BusName, on_event: &mut impl FnMut(FactAt<'_>)) {
        let Some(lost) = self.waiting.pop_front() else {
            return;
        };
        for _ in 0..lost.streams {
            let Some(at) = self.waiting_streams.pop_front() else {
                break;
            };
            let Some(stream) = self.streams.get_mut(usize::from(at)) else {
                continue;
            };
            stream.lost += 1;
            let (command, address) = (stream.command, stream.address);
            fact(
                on_event,
                iface,
                lost.packet,
                lost.timestamp,
                EthercatFact::StreamLost { command, address },
            );
        }
    }

    /// The index of `slave`'s summary, added when new.
    fn slave_at(&mut self, slave: SlaveRef) -> Option<usize> {
        if slave.station.is_none() && slave.position.is_none() {
            return None;
        }
        let at = self.slaves.iter().position(|s| {
            (slave.station.is_some() && s.station == slave.station)
                || (slave.station.is_none()
                    && slave.position.is_some()
                    && s.position == slave.position)
                || (s.station.is_none() && s.position.is_some() && s.position == slave.position)
        });
        let at = match at {
            Some(at) => at,
            None => {
                let mut new = SlaveSummary::new(self.name.clone());
                new.registers.alias_enabled = self.alias_broadcast;
                self.slaves.push(new);
                self.sdo.push(Histogram::new());
                self.drives.push(None);
                self.slaves.len() - 1
            }
        };
        let found = &mut self.slaves[at];
        if slave.station.is_some() {
            found.station = slave.station;
        }
        if slave.position.is_some() {
            found.position = slave.position;
        }
        Some(at)
    }

    /// One slave's process data in one cycle: its counts, its CiA 402
    /// timeline (faults with the slave's last CoE emergency before them)
    /// and its servo timeline. Return the slave's place among the
    /// records, where the data is a slave's.
    fn process_data(
        &mut self,
        packet: u64,
        timestamp: Option<Timestamp>,
        data: &ProcessData<'_>,
        emit: &mut impl FnMut(EthercatFact),
    ) -> Option<usize> {
        let at = self.slave_at(data.slave?)?;
        let s = &mut self.slaves[at];
        s.process_cycles += 1;
        if !data.confirmed {
            s.process_unconfirmed += 1;
            s.first_unconfirmed
                .get_or_insert((packet, data.wkc, data.expected_wkc));
        }
        if let Some(reading) = data.cia402.filter(|r| r.state.is_some()) {
            let last_error = s.emergencies.last().map(|e| EmcySeen {
                line: e.packet,
                timestamp: e.timestamp,
                code: e.emcy.code,
                register: e.emcy.register,
                manufacturer: e.emcy.manufacturer,
            });
            if let Some((transition, fault)) = self.drives[at]
                .get_or_insert_with(TimelineBuilder::default)
                .observe(packet, timestamp, reading, last_error)
            {
                emit(EthercatFact::Cia402 {
                    slave: at,
                    transition,
                    fault,
                });
            }
        }
        if let Some(servo) = &data.servo {
            let timeline = s.servo.get_or_insert_with(ServoTimeline::default);
            let before = timeline.events.count();
            timeline.observe(packet, timestamp, servo);
            // The events this cycle added, newest last.
            let added = (timeline.events.count() - before) as usize;
            let kept = timeline.events.kept();
            for i in kept.saturating_sub(added)..kept {
                if let Some(&event) = timeline.events.get(i) {
                    emit(EthercatFact::Servo { slave: at, event });
                }
            }
        }
        Some(at)
    }

    /// Add what a datagram tells of a slave; hand `emit` each fact it
    /// adds to the slave's record.
    fn meaning(
        &mut self,
        packet: u64,
        timestamp: Option<Timestamp>,
        meaning: Meaning<'_>,
        emit: &mut impl FnMut(EthercatFact),
    ) {
        match meaning {
            Meaning::StationAddress { slave } => {
                self.slave(slave);
            }
            Meaning::BroadcastAlStatus { .. } => {}
            Meaning::DlStatus { slave, low, high } => {
                let Some((at, s)) = self.slave(slave) else {
                    return;
                };
                let before = s.dl_last;
                let after = (low.or(before.0), high.or(before.1));
                let changed = (low.is_some() && before.0.is_some() && low != before.0)
                    || (high.is_some() && before.1.is_some() && high != before.1);
                if changed && s.dl_changes.len() < MAX_AL_CHANGES {
                    let change = DlChange {
                        packet,
                        timestamp,
                        from: before,
                        to: after,
                    };
                    s.dl_changes.push(change);
                    emit(EthercatFact::DlChange { slave: at, change });
                }
                s.dl_last = after;
            }
            Meaning::ErrorCounters { slave, bytes } => {
                let Some((place, s)) = self.slave(slave) else {
                    return;
                };
                for (at, value) in bytes.iter().enumerate() {
                    let Some(value) = *value else { continue };
                    if let Some(before) = s.counters_last[at] {
                        if value > before
                            && crate::ethercat::register::error_counter_name(at).is_some()
                            && s.counter_rises.len() < MAX_AL_CHANGES
                        {
                            let rise = CounterRise {
                                packet,
                                timestamp,
                                register: 0x0300 + at as u16,
                                from: before,
                                to: value,
                            };
                            s.counter_rises.push(rise);
                            emit(EthercatFact::CounterRise { slave: place, rise });
                        }
                    }
                    s.counters_last[at] = Some(value);
                }
            }
            Meaning::AlState {
                slave,
                register,
                status,
                code,
            } => {
                let Some((at, s)) = self.slave(slave) else {
                    return;
                };
                let requested = register == AlRegister::Control;
                let status = match (status, s.al_last) {
                    (Some(status), _) => status,
                    // The code read alone completes the last status read.
                    (None, Some(last)) if code.is_some() => {
                        let change = AlChange { code, ..last };
                        if let Some(kept) = s.al_changes.last_mut() {
                            if !kept.requested && kept.status == last.status && kept.code.is_none()
                            {
                                kept.code = code;
                                if let Some(code) = code {
                                    emit(EthercatFact::AlCode {
                                        slave: at,
                                        of: kept.packet,
                                        code,
                                    });
                                }
                            }
                        }
                        s.al_last = Some(change);
                        return;
                    }
                    (None, _) => return,
                };
                let change = AlChange {
                    packet,
                    timestamp,
                    requested,
                    status,
                    code,
                };
                let last_same = s
                    .al_changes
                    .iter()
                    .rev()
                    .find(|c| c.requested == requested)
                    .is_some_and(|c| c.status == status && (code.is_none() || c.code == code));
                if !last_same {
                    if s.al_changes.len() < MAX_AL_CHANGES {
                        s.al_changes.push(change);
                    } else {
                        s.al_changes_dropped += 1;
                    }
                    emit(EthercatFact::AlState { slave: at, change });
                }
                if !requested {
                    s.al_last = Some(change);
                }
            }
            Meaning::Sii { slave, word, value } => {
                let Some((_, s)) = self.slave(slave) else {
                    return;
                };
                match word {
                    0x08 => s.vendor = Some(value),
                    0x0A => s.product = Some(value),
                    0x0C => s.revision = Some(value),
                    0x0E => s.serial = Some(value),
                    _ => {}
                }
            }
            Meaning::Mailbox {
                slave,
                written,
                accepted,
                guessed,
                repeated,
                header,
                body,
                profile,
                sdo: step,
            } => {
                let Some((at, s)) = self.slave(slave) else {
                    return;
                };
                if guessed {
                    s.mailbox_guessed += 1;
                }
                if repeated {
                    s.registers.mailbox_repeated += 1;
                    return;
                }
                if written && !accepted {
                    s.mailbox_refused += 1;
                    return;
                }
                if written {
                    s.mailbox_written += 1;
                } else {
                    s.mailbox_read += 1;
                }
                if header.mailbox_type != MailboxType::Coe {
                    return;
                }
                let Ok(coe) = CoeHeader::parse(body) else {
                    return;
                };
                let rest = &body[COE_HEADER_LEN..];
                match coe.service {
                    CoeService::Emergency => {
                        if let Ok(emcy) = Emcy::parse(rest) {
                            let emergency = CoeEmergency {
                                packet,
                                timestamp,
                                emcy,
                                profile,
                            };
                            if s.emergencies.len() < MAX_EMERGENCIES {
                                s.emergencies.push(emergency);
                            } else {
                                s.emergencies_dropped += 1;
                            }
                            emit(EthercatFact::Emergency {
                                slave: at,
                                emergency,
                            });
                        }
                    }
                    CoeService::SdoRequest | CoeService::SdoResponse => {
                        let request = coe.service == CoeService::SdoRequest;
                        if request {
                            s.sdo_requests += 1;
                        } else {
                            s.sdo_responses += 1;
                        }
                        if let Ok(sdo) = CoeSdo::parse(rest) {
                            self.sdo_step(slave, written, &sdo, step, packet, timestamp, emit);
                        }
                    }
                    _ => {}
                }
            }
            // A BWR of the alias bit: every slave's.
            Meaning::StationAlias {
                slave:
                    SlaveRef {
                        station: None,
                        position: None,
                    },
                enabled: Some(enabled),
                ..
            } => {
                self.alias_broadcast = Some(enabled);
                for s in &mut self.slaves {
                    s.registers.alias_enabled = Some(enabled);
                }
            }
            other => {
                if let Some((_, s)) = registers_slave(&other).and_then(|slave| self.slave(slave)) {
                    s.registers.observe(&other);
                }
            }
        }
    }

    /// A slave's CoE SDO message, with what the session made of it in its
    /// transfer (`step`, docs/ethercat.md#coe-sdo): an abort is listed, a
    /// completed transfer counted and timed (docs/ethercat.md#summary).
    #[allow(clippy::too_many_arguments)]
    fn sdo_step(
        &mut self,
        slave: SlaveRef,
        written: bool,
        sdo: &CoeSdo<'_>,
        step: Option<CoeSdoStep>,
        packet: u64,
        timestamp: Option<Timestamp>,
        emit: &mut impl FnMut(EthercatFact),
    ) {
        let Some(at) = self.slave_at(slave) else {
            return;
        };
        let summary = &mut self.slaves[at];
        if let Some(code) = sdo.abort_code() {
            summary.sdo_aborts += 1;
            let (index, subindex) = sdo.multiplexer().unwrap_or((0, 0));
            let abort = CoeSdoAbort {
                packet,
                timestamp,
                index,
                subindex,
                code,
                // A slave's abort is read from its mailbox, in a response
                // or, as real slaves send it, in a message of the request
                // service.
                from_slave: !written,
            };
            if summary.sdo_abort_list.len() < MAX_EMERGENCIES {
                summary.sdo_abort_list.push(abort);
            }
            emit(EthercatFact::SdoAbort { slave: at, abort });
            return;
        }
        if let Some(transfer) = step.and_then(|s| s.ended) {
            summary.sdo_ok += 1;
            if let Some(latency) = transfer.latency {
                self.sdo[at].add(u64::try_from(latency.as_nanos()).unwrap_or(u64::MAX));
            }
        }
    }

    /// Count a datagram in its stream, if it has one; return the stream's
    /// place, and hand `emit` a returned copy whose working counter the
    /// stream counts.
    fn stream(
        &mut self,
        copy: FrameCopy,
        timestamp: Option<Timestamp>,
        packet: u64,
        datagram: &Datagram<'_>,
        sent_adp: Option<u16>,
        emit: &mut impl FnMut(EthercatFact),
    ) -> Option<u16> {
        let command = datagram.command();
        if !matches!(
            command,
            Command::Lrd
                | Command::Lwr
                | Command::Lrw
                | Command::Armw
                | Command::Frmw
                | Command::Brd
                | Command::Fprd
        ) {
            return None;
        }
        let address = match command {
            // A returned BRD's ADP is counted on: the register names it.
            Command::Brd => u32::from(datagram.ado()) << 16,
            // So is an ARMW's: the sent copy's names the slave.
            Command::Armw => match sent_adp {
                Some(adp) => (u32::from(datagram.ado()) << 16) | u32::from(adp),
                None => return None,
            },
            _ => datagram.address(),
        };
        let at = match self
            .streams
            .iter()
            .position(|s| s.command == command && s.address == address)
        {
            Some(at) => at,
            None if self.streams.len() < MAX_STREAMS => {
                self.streams.push(Stream {
                    command,
                    address,
                    sent: 0,
                    returned: 0,
                    lost: 0,
                    last_sent: None,
                    histogram: Histogram::new(),
                    zero: 0,
                    max: 0,
                    mean: 0.0,
                    m2: 0.0,
                    intervals: 0,
                    wkcs: Vec::new(),
                });
                self.streams.len() - 1
            }
            None => {
                self.streams_dropped += 1;
                return None;
            }
        };
        let stream = &mut self.streams[at];
        match copy {
            FrameCopy::Sent => {
                stream.sent += 1;
                if let (Some(now), Some(before)) = (timestamp, stream.last_sent) {
                    let ns = now
                        .as_duration()
                        .saturating_sub(before.as_duration())
                        .as_nanos();
                    let ns = u64::try_from(ns).unwrap_or(u64::MAX);
                    stream.intervals += 1;
                    if ns == 0 {
                        stream.zero += 1;
                    }
                    stream.max = stream.max.max(ns);
                    stream.histogram.add(ns);
                    let x = ns as f64;
                    let delta = x - stream.mean;
                    stream.mean += delta / stream.intervals as f64;
                    stream.m2 += delta * (x - stream.mean);
                }
                if timestamp.is_some() {
                    stream.last_sent = timestamp;
                }
            }
            FrameCopy::Returned { .. } | FrameCopy::ReturnedUnpaired => {
                stream.returned += 1;
                let wkc = datagram.working_counter();
                let counted = if let Some(w) = stream.wkcs.iter_mut().find(|w| w.0 == wkc) {
                    w.1 += 1;
                    true
                } else if stream.wkcs.len() < 64 {
                    stream.wkcs.push((wkc, 1, packet, timestamp));
                    true
                } else {
                    false
                };
                if counted {
                    emit(EthercatFact::StreamReturned {
                        command,
                        address,
                        wkc,
                    });
                }
            }
        }
        u16::try_from(at).ok()
    }
}

/// The name of a device a capture's SII identifies, where it is one of the
/// devices of the fixtures and the seeds (docs/ethercat.md#summary): the
/// vendor's name and the product's.
#[must_use]
pub fn device_name(vendor: u32, product: u32) -> Option<&'static str> {
    Some(match (vendor, product) {
        (0x02, 0x044C_2C52) => "Beckhoff EK1100",
        (0x02, 0x077A_2C52) => "Beckhoff EK1914",
        (0x02, 0x0B0C_3052) => "Beckhoff EL2828",
        (0x02, 0x0B49_3052) => "Beckhoff EL2889",
        (0x02, 0x0BBC_3052) => "Beckhoff EL3004",
        (0x6A, 0x0041_4B44) => "Kollmorgen AKD",
        (0x09, 0x9252) => "Microchip LAN9252",
        _ => return None,
    })
}

fn opt_ts<M: SerializeMap>(map: &mut M, key: &str, ts: Option<Timestamp>) -> Result<(), M::Error> {
    map.serialize_entry(key, &ts.map(Ts))
}

fn state_name(status: AlStatus) -> Option<&'static str> {
    status.state().map(|s| s.name())
}

/// One AL change as JSON: `{"packet", "ts", "requested", "state",
/// "state_bits", "error", "code", "code_text"}`.
struct ChangeJson<'a>(&'a AlChange);

impl Serialize for ChangeJson<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let c = self.0;
        let mut map = serializer.serialize_map(Some(8))?;
        map.serialize_entry("packet", &c.packet)?;
        opt_ts(&mut map, "ts", c.timestamp)?;
        map.serialize_entry("requested", &c.requested)?;
        map.serialize_entry("state", &state_name(c.status))?;
        map.serialize_entry("state_bits", &c.status.state_bits())?;
        map.serialize_entry("error", &c.status.error())?;
        map.serialize_entry("code", &c.code.map(|c| c.0))?;
        map.serialize_entry("code_text", &c.code.and_then(AlStatusCode::text))?;
        map.end()
    }
}

/// One CoE emergency as JSON: `{"packet", "ts", "code", "description",
/// "register"}`, with `axis` and `feedback` for an AKD.
struct EmergencyJson<'a>(&'a CoeEmergency);

impl Serialize for EmergencyJson<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let e = self.0;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("packet", &e.packet)?;
        opt_ts(&mut map, "ts", e.timestamp)?;
        map.serialize_entry("code", &e.emcy.code.get())?;
        map.serialize_entry("description", e.emcy.code.description())?;
        map.serialize_entry("register", &e.emcy.register.bits())?;
        if let Some((axis, feedback)) = akd(e) {
            map.serialize_entry("axis", &axis)?;
            map.serialize_entry("feedback", &feedback)?;
        }
        map.end()
    }
}

/// An AKD emergency's axis and feedback (docs/canopen.md#akd).
fn akd(e: &CoeEmergency) -> Option<(u8, Option<u8>)> {
    if e.profile != Profile::Akd {
        return None;
    }
    let field = crate::profiles::akd::AkdManufacturerField::new_unchecked(&e.emcy.manufacturer[..]);
    Some((
        field.axis_id().get(),
        field.feedback_id().ok().and_then(|f| f.number()),
    ))
}

/// The entries of a `type: "ethercat"` record.
pub(super) fn port_entries<M: SerializeMap>(
    port: &PortSummary,
    map: &mut M,
) -> Result<(), M::Error> {
    let c = &port.counts;
    map.serialize_entry("type", "ethercat")?;
    map.serialize_entry("iface", &Iface(&port.iface))?;
    map.serialize_entry("packets", &c.packets)?;
    map.serialize_entry("sent", &c.sent)?;
    map.serialize_entry("returned", &c.returned)?;
    map.serialize_entry("returned_unpaired", &c.returned_unpaired)?;
    map.serialize_entry("lost", &c.lost)?;
    map.serialize_entry("other_frame_types", &c.other_frame_types)?;
    map.serialize_entry("damaged", &c.damaged)?;
    map.serialize_entry("time_reversals", &c.time_reversals)?;
    map.serialize_entry("streams_not_followed", &port.streams_dropped)
}

/// The entries of a `type: "slave"` record.
pub(super) fn slave_entries<M: SerializeMap>(
    s: &SlaveSummary,
    map: &mut M,
) -> Result<(), M::Error> {
    map.serialize_entry("type", "slave")?;
    map.serialize_entry("iface", &Iface(&s.iface))?;
    map.serialize_entry("slave", &s.station)?;
    map.serialize_entry("position", &s.position)?;
    map.serialize_entry("vendor", &s.vendor)?;
    map.serialize_entry("product", &s.product)?;
    map.serialize_entry("revision", &s.revision)?;
    map.serialize_entry("serial", &s.serial)?;
    let name = s.vendor.zip(s.product).and_then(|(v, p)| device_name(v, p));
    map.serialize_entry("name", &name)?;
    match &s.al_last {
        Some(last) => {
            map.serialize_entry("al_state", &state_name(last.status))?;
            map.serialize_entry("al_error", &last.status.error())?;
            map.serialize_entry("al_code", &last.code.map(|c| c.0))?;
            map.serialize_entry("al_code_text", &last.code.and_then(AlStatusCode::text))?;
        }
        None => {
            map.serialize_entry("al_state", &None::<&str>)?;
            map.serialize_entry("al_error", &None::<bool>)?;
            map.serialize_entry("al_code", &None::<u16>)?;
            map.serialize_entry("al_code_text", &None::<&str>)?;
        }
    }
    let changes: Vec<_> = s.al_changes.iter().map(ChangeJson).collect();
    map.serialize_entry("al_timeline", &changes)?;
    map.serialize_entry("al_timeline_dropped", &s.al_changes_dropped)?;
    map.serialize_entry(
        "emcy_count",
        &(s.emergencies.len() as u64 + s.emergencies_dropped),
    )?;
    let emergencies: Vec<_> = s.emergencies.iter().map(EmergencyJson).collect();
    map.serialize_entry("emcy", &emergencies)?;
    map.serialize_entry("sdo_requests", &s.sdo_requests)?;
    map.serialize_entry("sdo_responses", &s.sdo_responses)?;
    map.serialize_entry("sdo_aborts", &s.sdo_aborts)?;
    map.serialize_entry("sdo_ok", &s.sdo_ok)?;
    let aborts: Vec<_> = s.sdo_abort_list.iter().map(AbortJson).collect();
    map.serialize_entry("sdo_abort_list", &aborts)?;
    let ms = |ns: Option<u64>| ns.map(|ns| ns as f64 / 1e6);
    map.serialize_entry("sdo_latency_median_ms", &ms(s.sdo_latency_median_ns))?;
    map.serialize_entry("sdo_latency_max_ms", &ms(s.sdo_latency_max_ns))?;
    map.serialize_entry("mailbox_written", &s.mailbox_written)?;
    map.serialize_entry("mailbox_read", &s.mailbox_read)?;
    map.serialize_entry("mailbox_refused", &s.mailbox_refused)?;
    map.serialize_entry("mailbox_guessed", &s.mailbox_guessed)?;
    let dl: Vec<_> = s.dl_changes.iter().map(DlJson).collect();
    map.serialize_entry("dl_status_changes", &dl)?;
    let rises: Vec<_> = s.counter_rises.iter().map(RiseJson).collect();
    map.serialize_entry("error_counter_rises", &rises)?;
    map.serialize_entry("process_cycles", &s.process_cycles)?;
    map.serialize_entry("process_unconfirmed", &s.process_unconfirmed)?;
    map.serialize_entry(
        "first_unconfirmed",
        &s.first_unconfirmed.map(|(packet, wkc, expected)| {
            serde_json::json!({"packet": packet, "wkc": wkc, "expected_wkc": expected})
        }),
    )?;
    map.serialize_entry("cia402", &s.cia402)?;
    map.serialize_entry("servo", &s.servo)?;
    s.registers.entries(map)
}

/// The slave of a meaning of the alias, the mailbox protocol or the clock
/// (a broadcast of the alias bit names none: no slave's).
fn registers_slave(meaning: &Meaning<'_>) -> Option<SlaveRef> {
    match *meaning {
        Meaning::StationAlias { slave, .. }
        | Meaning::Dc { slave, .. }
        | Meaning::DcDistribution { slave, .. }
        | Meaning::MailboxPoll { slave, .. }
        | Meaning::MailboxRepeat { slave, .. } => Some(slave),
        _ => None,
    }
}

/// An SDO abort as JSON: `{"packet", "ts", "index", "subindex",
/// "abort_code", "abort", "from_slave"}`.
struct AbortJson<'a>(&'a CoeSdoAbort);

impl Serialize for AbortJson<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let a = self.0;
        let mut map = serializer.serialize_map(Some(7))?;
        map.serialize_entry("packet", &a.packet)?;
        opt_ts(&mut map, "ts", a.timestamp)?;
        map.serialize_entry("index", &a.index)?;
        map.serialize_entry("subindex", &a.subindex)?;
        map.serialize_entry("abort_code", &a.code.get())?;
        map.serialize_entry("abort", &a.code.to_string())?;
        map.serialize_entry("from_slave", &a.from_slave)?;
        map.end()
    }
}

/// A DL status change as JSON: `{"packet", "ts", "links",
/// "loops_closed"}`, each list of four ports (null where not read).
struct DlJson<'a>(&'a DlChange);

impl Serialize for DlJson<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let c = self.0;
        let bits = |byte: Option<u8>, shift: u32, step: u32| {
            byte.map(|b| {
                (0..4u32)
                    .map(|p| b >> (shift + p * step) & 1 != 0)
                    .collect::<Vec<_>>()
            })
        };
        let mut map = serializer.serialize_map(Some(6))?;
        map.serialize_entry("packet", &c.packet)?;
        opt_ts(&mut map, "ts", c.timestamp)?;
        map.serialize_entry("links_before", &bits(c.from.0, 4, 1))?;
        map.serialize_entry("links", &bits(c.to.0, 4, 1))?;
        map.serialize_entry("loops_closed_before", &bits(c.from.1, 0, 2))?;
        map.serialize_entry("loops_closed", &bits(c.to.1, 0, 2))?;
        map.end()
    }
}

/// An error counter's rise as JSON: `{"packet", "ts", "register", "name",
/// "from", "to"}`.
struct RiseJson<'a>(&'a CounterRise);

impl Serialize for RiseJson<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let r = self.0;
        let mut map = serializer.serialize_map(Some(6))?;
        map.serialize_entry("packet", &r.packet)?;
        opt_ts(&mut map, "ts", r.timestamp)?;
        map.serialize_entry("register", &r.register)?;
        map.serialize_entry(
            "name",
            &crate::ethercat::register::error_counter_name(usize::from(r.register - 0x0300)),
        )?;
        map.serialize_entry("from", &r.from)?;
        map.serialize_entry("to", &r.to)?;
        map.end()
    }
}

/// The entries of a `type: "stream"` record.
pub(super) fn stream_entries<M: SerializeMap>(
    s: &StreamSummary,
    map: &mut M,
) -> Result<(), M::Error> {
    map.serialize_entry("type", "stream")?;
    map.serialize_entry("iface", &Iface(&s.iface))?;
    map.serialize_entry("cmd", s.command.name())?;
    if matches!(s.command, Command::Lrd | Command::Lwr | Command::Lrw) {
        map.serialize_entry("logical", &s.address)?;
    } else {
        map.serialize_entry("adp", &(s.address & 0xFFFF))?;
        map.serialize_entry("ado", &(s.address >> 16))?;
    }
    map.serialize_entry("sent", &s.sent)?;
    map.serialize_entry("returned", &s.returned)?;
    map.serialize_entry("lost", &s.lost)?;
    map.serialize_entry("intervals", &s.intervals)?;
    map.serialize_entry("resolved", &s.resolved())?;
    let us = |ns: Option<u64>| ns.map(|ns| ns as f64 / 1000.0);
    map.serialize_entry("cycle_median_us", &us(s.cycle_median_ns))?;
    map.serialize_entry("cycle_p99_us", &us(s.cycle_p99_ns))?;
    map.serialize_entry("cycle_max_us", &us(s.cycle_max_ns))?;
    map.serialize_entry("jitter_us", &us(s.jitter_ns))?;
    map.serialize_entry("wkc_usual", &s.wkc_usual)?;
    map.serialize_entry("wkc_mismatches", &s.wkc_mismatches)?;
    match s.first_mismatch {
        Some((packet, ts, wkc)) => {
            map.serialize_entry("first_mismatch_packet", &packet)?;
            opt_ts(map, "first_mismatch_ts", ts)?;
            map.serialize_entry("first_mismatch_wkc", &wkc)?;
        }
        None => {
            map.serialize_entry("first_mismatch_packet", &None::<u64>)?;
            map.serialize_entry("first_mismatch_ts", &None::<f64>)?;
            map.serialize_entry("first_mismatch_wkc", &None::<u16>)?;
        }
    }
    Ok(())
}

impl fmt::Display for PortSummary {
    /// `ethercat  eth0: 558 packets, 279 frames sent, 279 returned, 0 lost`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = &self.counts;
        write!(
            f,
            "ethercat  {}: {} packets, {} frames sent, {} returned, {} lost",
            self.iface, c.packets, c.sent, c.returned, c.lost
        )?;
        if c.returned_unpaired > 0 {
            write!(
                f,
                ", {} returned without their sent copy",
                c.returned_unpaired
            )?;
        }
        if c.other_frame_types > 0 {
            write!(f, ", {} of another EtherCAT type", c.other_frame_types)?;
        }
        if c.damaged > 0 {
            write!(f, ", {} damaged", c.damaged)?;
        }
        writeln!(f)
    }
}

impl fmt::Display for SlaveSummary {
    /// The slave, what it is, its AL states and emergencies in time order.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ", self.iface)?;
        write!(
            f,
            "{}",
            SlaveRef {
                station: self.station,
                position: self.position,
            }
        )?;
        if let Some((v, p)) = self.vendor.zip(self.product) {
            match device_name(v, p) {
                Some(name) => write!(f, " {name}")?,
                None => write!(f, " vendor {v:#x} product {p:#x}")?,
            }
        }
        if let Some(rev) = self.revision {
            write!(f, " rev {rev:#x}")?;
        }
        f.write_str(":")?;
        // AL states and emergencies, merged in time (packet) order.
        let mut states = self.al_changes.iter().filter(|c| !c.requested).peekable();
        let mut emcys = self.emergencies.iter().peekable();
        let mut first = true;
        loop {
            let take_state = match (states.peek(), emcys.peek()) {
                (Some(s), Some(e)) => s.packet <= e.packet,
                (Some(_), None) => true,
                (None, Some(_)) => false,
                (None, None) => break,
            };
            f.write_str(if first { " " } else { "; " })?;
            first = false;
            if take_state {
                let Some(c) = states.next() else { break };
                match c.status.state() {
                    Some(state) => write!(f, "{state}")?,
                    None => write!(f, "states {:#04x}", c.status.state_bits())?,
                }
                if c.status.error() {
                    f.write_str(" with error")?;
                    match c.code {
                        Some(code) => write!(f, " {code}")?,
                        None => f.write_str(", code not read")?,
                    }
                    write!(f, " (packet {})", c.packet)?;
                }
            } else {
                let Some(e) = emcys.next() else { break };
                write!(
                    f,
                    "EMCY {:#06x} {}",
                    e.emcy.code.get(),
                    e.emcy.code.description()
                )?;
                if let Some((axis, feedback)) = akd(e) {
                    write!(f, " (axis {axis}")?;
                    if let Some(fb) = feedback {
                        write!(f, ", feedback {fb}")?;
                    }
                    f.write_str(")")?;
                }
                write!(f, " (packet {})", e.packet)?;
            }
        }
        if first {
            f.write_str(" no AL status read")?;
        }
        if self.sdo_requests + self.sdo_responses > 0 {
            write!(
                f,
                "; SDO {} requests, {} responses, {} transfers ended, {} aborts",
                self.sdo_requests, self.sdo_responses, self.sdo_ok, self.sdo_aborts
            )?;
            if let (Some(median), Some(max)) = (self.sdo_latency_median_ns, self.sdo_latency_max_ns)
            {
                write!(
                    f,
                    ", latency median {:.2} ms, max {:.2} ms",
                    median as f64 / 1e6,
                    max as f64 / 1e6
                )?;
            }
            for abort in self.sdo_abort_list.iter().take(3) {
                write!(
                    f,
                    "; SDO abort {:04X}sub{} {} (packet {})",
                    abort.index, abort.subindex, abort.code, abort.packet
                )?;
            }
        }
        if self.mailbox_refused > 0 {
            write!(f, "; {} mailbox writes not accepted", self.mailbox_refused)?;
        }
        if !self.dl_changes.is_empty() {
            let first = &self.dl_changes[0];
            match self.dl_changes.len() {
                1 => write!(f, "; DL status changed at packet {}", first.packet)?,
                n => write!(
                    f,
                    "; DL status changed {n} times, first at packet {}",
                    first.packet
                )?,
            }
        }
        for rise in self.counter_rises.iter().take(4) {
            write!(
                f,
                "; {} {} → {} (packet {})",
                crate::ethercat::register::error_counter_name(usize::from(rise.register - 0x0300))
                    .unwrap_or("counter"),
                rise.from,
                rise.to,
                rise.packet
            )?;
        }
        if self.counter_rises.len() > 4 {
            write!(
                f,
                "; {} more error counter rises",
                self.counter_rises.len() - 4
            )?;
        }
        if self.process_cycles > 0 {
            write!(f, "; {} cycles of process data", self.process_cycles)?;
            if let Some((packet, wkc, expected)) = self.first_unconfirmed {
                write!(
                    f,
                    ", {} with inputs unconfirmed, first at packet {packet} (working counter {wkc}",
                    self.process_unconfirmed
                )?;
                if let Some(expected) = expected {
                    write!(f, " of {expected}")?;
                }
                f.write_str(")")?;
            }
        }
        fmt::Display::fmt(&self.registers, f)?;
        writeln!(f)?;
        if let Some(cia402) = &self.cia402 {
            fmt::Display::fmt(cia402, f)?;
        }
        if let Some(servo) = &self.servo {
            fmt::Display::fmt(servo, f)?;
        }
        Ok(())
    }
}

impl fmt::Display for StreamSummary {
    /// `stream eth0 LRW logical 0x00000000: 200 frames, cycle median
    /// 1000.0 µs, p99 1000.0 µs, max 1000.0 µs, jitter 0.0 µs; working
    /// counter 3, 50 mismatches from packet 460 (1)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "stream {} {}: {} frames",
            self.iface,
            self.key(),
            self.sent
        )?;
        if self.lost > 0 {
            write!(f, ", {} lost", self.lost)?;
        }
        let us = |ns: u64| ns as f64 / 1000.0;
        if self.resolved() {
            if let (Some(median), Some(p99), Some(max)) =
                (self.cycle_median_ns, self.cycle_p99_ns, self.cycle_max_ns)
            {
                write!(
                    f,
                    ", cycle median {:.1} µs, p99 {:.1} µs, max {:.1} µs",
                    us(median),
                    us(p99),
                    us(max)
                )?;
            }
            if let Some(jitter) = self.jitter_ns {
                write!(f, ", jitter {:.1} µs", us(jitter))?;
            }
        } else if self.intervals > 0 {
            write!(
                f,
                ", cycle not resolved ({} of {} intervals are 0 in the capture's clock)",
                self.zero_intervals, self.intervals
            )?;
        }
        if let Some(usual) = self.wkc_usual {
            write!(f, "; working counter {usual}")?;
            if let Some((packet, _, wkc)) = self.first_mismatch {
                write!(
                    f,
                    ", {} mismatches from packet {packet} ({wkc})",
                    self.wkc_mismatches
                )?;
            }
        }
        writeln!(f)
    }
}
