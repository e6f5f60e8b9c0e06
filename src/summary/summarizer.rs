//! The [`Summarizer`]: what builds a [`Summary`] from a log, entry by entry.

use core::time::Duration;

use crate::can::{BusName, BusStatus, ErrorFrame, EthercatPacket, LogEvent, LogFrame, Timestamp};
use crate::canopen::sdo::{SdoOutcome, SdoTransfer};
use crate::canopen::{
    Emcy, EmcyStorage, ErrorRegister, GuardingEvent, HeartbeatConsumer, HeartbeatEvent,
    MessageKind, NmtStateByte, NodeGuardingMaster, NodeId, SlotUpdate,
};
use crate::decoder::ethercat::ProcessData;
use crate::decoder::{Cia402Reading, Decoded, Decoder, DecoderConfig, SdoSeen};
use crate::logs::Position;

use super::causes::{in_window, RecentBusErrors};
use super::emcy::EmcySeen;
use super::ethercat::EthercatSummarizer;
use super::event::{SummaryEvent, SummaryEventKind};
use super::heartbeat::{BusErrorSeen, GuardingSummary, HeartbeatGap, HeartbeatSummary, Timeouts};
use super::listed::Listed;
use super::record::{BusSummary, FrameCounts, NodeSummary, Summary};
use super::sdo::SdoFrameFacts;
use super::{cia402, sdo};

/// No SDO frame, for [`add_classified`].
const NO_SDO: Option<&SdoSeen<'static, 'static>> = None;

/// What the summarizer keeps of one node while the log is read.
#[derive(Debug)]
struct NodeState {
    node: NodeId,
    frames: FrameCounts,
    emcy: u64,
    resets: u64,
    first_error: Option<EmcySeen>,
    first_error_with_register: Option<EmcySeen>,
    active_error: Option<EmcySeen>,
    last_error: Option<EmcySeen>,
    last_register: Option<ErrorRegister>,
    heartbeats: u64,
    last_state: Option<NmtStateByte>,
    boot_ups: Listed<u64>,
    /// The line of the last heartbeat (not guarding answer) seen.
    last_heartbeat_line: u64,
    /// When its next heartbeat is due: the last one's time plus the
    /// consumer time (with `--heartbeat-ms` and times).
    heartbeat_due: Option<Duration>,
    /// The earliest bus-off or error-passive frame of the bus in the
    /// window of that heartbeat (docs/summary.md#causes).
    gap_cause: Option<BusErrorSeen>,
    /// A timeout reported by the consumer and not yet closed by a
    /// heartbeat: the line and time of the heartbeat before it.
    open_gap: Option<(u64, Duration)>,
    timeouts: Listed<HeartbeatGap>,
    guarding: NodeGuardingMaster,
    guarding_summary: GuardingSummary,
    sdo: sdo::SdoStats,
    cia402: cia402::TimelineBuilder,
}

impl NodeState {
    fn new(node: NodeId) -> Self {
        NodeState {
            node,
            frames: FrameCounts::default(),
            emcy: 0,
            resets: 0,
            first_error: None,
            first_error_with_register: None,
            active_error: None,
            last_error: None,
            last_register: None,
            heartbeats: 0,
            last_state: None,
            boot_ups: Listed::new(),
            last_heartbeat_line: 0,
            heartbeat_due: None,
            gap_cause: None,
            open_gap: None,
            timeouts: Listed::new(),
            // A log rarely shows the guard time (100Ch): observe toggles only.
            guarding: NodeGuardingMaster::observer(node, Duration::ZERO),
            guarding_summary: GuardingSummary::default(),
            sdo: sdo::SdoStats::default(),
            cia402: cia402::TimelineBuilder::default(),
        }
    }
}

/// What the summarizer keeps of one interface.
#[derive(Debug)]
struct BusState {
    nodes: Vec<Option<NodeState>>,
    storage: EmcyStorage,
    consumer: Option<HeartbeatConsumer>,
    /// The heartbeat consumer time.
    heartbeat: Option<Duration>,
    /// Its bus-off and error-passive frames of the last second.
    recent_errors: RecentBusErrors,
    frames: u64,
    error_frames: u64,
    bus_off: Listed<u64>,
    error_passive: Listed<u64>,
    status_events: u64,
    first_ts: Option<Timestamp>,
    last_ts: Option<Timestamp>,
}

impl BusState {
    fn new(heartbeat: Option<Duration>) -> Self {
        let consumer = heartbeat.map(|time| {
            let mut consumer = HeartbeatConsumer::new();
            consumer.monitor_unconfigured(time);
            consumer
        });
        BusState {
            nodes: (0..127).map(|_| None).collect(),
            storage: EmcyStorage::new(),
            consumer,
            heartbeat,
            recent_errors: RecentBusErrors::default(),
            frames: 0,
            error_frames: 0,
            bus_off: Listed::new(),
            error_passive: Listed::new(),
            status_events: 0,
            first_ts: None,
            last_ts: None,
        }
    }

    /// Note a bus-off or error-passive frame: it is the cause of the loss
    /// of each node whose next heartbeat is due at most a second after it
    /// and that has none yet (docs/summary.md#causes).
    fn bus_error(&mut self, seen: BusErrorSeen) {
        if self.heartbeat.is_none() {
            return;
        }
        let t = seen.timestamp.as_duration();
        for state in self.nodes.iter_mut().flatten() {
            if state.gap_cause.is_none() && state.heartbeat_due.is_some_and(|due| in_window(t, due))
            {
                state.gap_cause = Some(seen);
            }
        }
        self.recent_errors.push(seen);
    }

    /// Widen the bus's time span to `ts` (inputs are mostly in time order:
    /// one comparison per frame).
    #[inline]
    fn saw(&mut self, ts: Option<Timestamp>) {
        let Some(ts) = ts else { return };
        match self.last_ts {
            Some(last) if ts >= last => self.last_ts = Some(ts),
            Some(_) => {
                if self.first_ts.map_or(true, |first| ts < first) {
                    self.first_ts = Some(ts);
                }
            }
            None => {
                self.first_ts = Some(ts);
                self.last_ts = Some(ts);
            }
        }
    }
}

/// Builds the [`Summary`] of a log, entry by entry (see the
/// [module](super) documentation): the session's one way in.
///
/// It owns the [`Decoder`] that reads each frame, so that what the summary
/// learns from a frame is what the decoder read of it, once, and so that
/// both keep the buses in one table. [`add`](Self::add) feeds one log
/// entry; [`add_with`](Self::add_with) also hands back what the decoder
/// made of a frame and every fact the summary adds (what the report
/// draws); [`finish`](Self::finish) ends the input — the transfers left
/// open end there — and returns the [`Summary`].
#[derive(Debug)]
pub struct Summarizer {
    decoder: Decoder,
    /// What the summary keeps of each bus, at the bus's place in the
    /// decoder's table ([`Decoder::bus`]), with the bus's name (copied
    /// once, when the bus is first seen).
    buses: Vec<(BusName, BusState)>,
    heartbeat: Option<Duration>,
    last_time: Option<Duration>,
    untimed: u64,
    /// EtherCAT packets added (docs/ethercat.md#summary).
    ethercat_packets: u64,
    /// Their summary, from the first packet on.
    ethercat: Option<EthercatSummarizer>,
}

impl Default for Summarizer {
    fn default() -> Self {
        Summarizer::new(DecoderConfig::new())
    }
}

impl Summarizer {
    /// Start a summary read by a decoder of `config`, whose settings are
    /// the summary's too ([`DecoderConfig::heartbeat_timeout`]).
    #[must_use]
    pub fn new(config: DecoderConfig) -> Self {
        Summarizer {
            heartbeat: config.heartbeat(),
            decoder: Decoder::new(config),
            buses: Vec::new(),
            last_time: None,
            untimed: 0,
            ethercat_packets: 0,
            ethercat: None,
        }
    }

    /// An EtherCAT packet: read by the EtherCAT part of the summary.
    #[cold]
    #[inline(never)]
    fn add_ethercat(
        &mut self,
        position: Position,
        packet: &EthercatPacket<'_>,
        mut on_event: impl FnMut(SummaryEvent<'_>),
        on_process: impl FnMut(&BusName, usize, &ProcessData<'_>),
    ) {
        self.ethercat_packets += 1;
        let config = self.decoder.config();
        self.ethercat
            .get_or_insert_with(|| EthercatSummarizer::new(config))
            .add(position, packet, |f| on_event(f.into()), on_process);
    }

    /// Add one EtherCAT packet, as [`add_with`](Self::add_with) does:
    /// hand `on_event` each fact it adds to the summary, in order, and
    /// `on_process` each slave's process data in it as the session cut it
    /// ([`Session::process_data`]; docs/ethercat.md#process-data) — its
    /// signals, CiA 402 reading and servo frames — with the slave's
    /// interface and its place among that interface's slave records
    /// (as [`EthercatFact`](super::EthercatFact) names a slave). The
    /// report charts the drives' signals from it (docs/report.md#signals).
    ///
    /// [`Session::process_data`]: crate::decoder::ethercat::Session::process_data
    pub fn add_ethercat_with(
        &mut self,
        position: Position,
        packet: &EthercatPacket<'_>,
        on_event: impl FnMut(SummaryEvent<'_>),
        on_process: impl FnMut(&BusName, usize, &ProcessData<'_>),
    ) {
        self.add_ethercat(position, packet, on_event, on_process);
    }

    /// Return how many EtherCAT packets were added: the summary's
    /// [`Summary::ethercat`] part is made of them (docs/ethercat.md#summary).
    #[must_use]
    pub const fn ethercat_packets(&self) -> u64 {
        self.ethercat_packets
    }

    /// Return the decoder that reads the frames: its configuration, the
    /// names of each node's objects, the mappings it has learned.
    #[must_use]
    pub fn decoder(&self) -> &Decoder {
        &self.decoder
    }

    /// Return the place of the bus of `iface` in the decoder's table of
    /// buses ([`Decoder::bus`]), made on first sight: where the report
    /// keeps its rows of the bus, as the summary keeps its buses. A bus
    /// made here is the one the next [`add_with`](Self::add_with) of a
    /// frame on `iface` finds, so the summary's table follows the
    /// decoder's in order.
    #[cfg(feature = "report")]
    #[inline]
    pub(crate) fn bus_at(&mut self, iface: Option<crate::can::Iface<'_>>) -> usize {
        self.decoder.bus(&iface)
    }

    /// What the summary keeps of the bus at `at` in the decoder's table,
    /// with its name, made on first sight (the decoder adds buses in
    /// order, so the bus at `at` is new exactly when `at` is the length):
    /// `name` is asked for then only.
    #[inline(always)]
    fn bus_state(
        buses: &mut Vec<(BusName, BusState)>,
        heartbeat: Option<Duration>,
        at: usize,
        name: impl FnOnce() -> BusName,
    ) -> (&BusName, &mut BusState) {
        if at < buses.len() {
            let (name, bus) = &mut buses[at];
            return (name, bus);
        }
        Self::new_bus(buses, heartbeat, name());
        let (name, bus) = &mut buses[at];
        (name, bus)
    }

    #[cold]
    #[inline(never)]
    fn new_bus(buses: &mut Vec<(BusName, BusState)>, heartbeat: Option<Duration>, name: BusName) {
        buses.push((name, BusState::new(heartbeat)));
    }

    /// Add one log entry read at `position` (`line` in
    /// docs/formats.md#positions): a frame is read by the decoder where the
    /// decoder keeps state (SDO and PDO data frames), and summarized; a bus
    /// event is counted (`status_events` in docs/summary.md#bus).
    #[inline]
    pub fn add(&mut self, position: Position, event: &LogEvent<'_>) {
        match event {
            LogEvent::Frame(frame) => self.add_frame(position, frame),
            LogEvent::Status(status) => self.add_status(status),
            LogEvent::Ethercat(packet) => self.add_ethercat(position, packet, |_| {}, |_, _, _| {}),
        }
    }

    /// Add one log entry, as [`add`](Self::add) does, reading every frame
    /// whole; hand `on_event` each fact the entry adds to the summary, in
    /// order ([`SummaryEvent`]: what the report draws,
    /// docs/report.md#timeline), and return what the decoder made of a
    /// frame (`None` for a bus event).
    pub fn add_with<'s>(
        &'s mut self,
        position: Position,
        event: &'s LogEvent<'s>,
        on_event: impl FnMut(SummaryEvent<'_>),
    ) -> Option<Decoded<'s>> {
        let log = match event {
            LogEvent::Frame(frame) => frame,
            LogEvent::Status(status) => {
                self.add_status(status);
                return None;
            }
            LogEvent::Ethercat(packet) => {
                self.add_ethercat(position, packet, on_event, |_, _, _| {});
                return None;
            }
        };
        let Summarizer {
            decoder,
            buses,
            heartbeat,
            last_time,
            untimed,
            ..
        } = self;
        let at = decoder.bus(&log.iface);
        let (name, bus) = Self::bus_state(buses, *heartbeat, at, || decoder.bus_name(at).clone());
        let decoded = decoder.decode(position, log);
        add_classified(
            bus,
            name,
            (last_time, untimed),
            position.number(),
            log,
            decoded.kind,
            decoded.node,
            decoded.sdo.as_ref(),
            decoded.drive().zip(decoded.cia402),
            on_event,
        );
        Some(decoded)
    }

    /// A frame, for [`add`](Self::add): the decoder reads the SDO and PDO
    /// data frames and the error-control frames it keeps state for (the
    /// other kinds teach it nothing), and the summary reads what the
    /// decoder read, where it was read.
    #[inline]
    fn add_frame(&mut self, at_position: Position, log: &LogFrame<'_>) {
        let position = at_position.number();
        let (kind, node) = MessageKind::classify(&log.frame);
        let Summarizer {
            decoder,
            buses,
            heartbeat,
            last_time,
            untimed,
            ..
        } = self;
        let times = (last_time, untimed);
        let (at, kind) = match (kind, node) {
            (MessageKind::Sdo, Some(n)) if !log.frame.is_rtr() => {
                decoder.sdo_frame(at_position, log, n, |at, seen, cia402| {
                    let (name, bus) =
                        Self::bus_state(buses, *heartbeat, at, || seen.bus_name().clone());
                    add_classified(
                        bus,
                        name,
                        times,
                        position,
                        log,
                        kind,
                        node,
                        Some(seen),
                        cia402.map(|reading| (n, reading)),
                        |_| {},
                    );
                });
                return;
            }
            // The PDO arm keeps its own call rather than passing its
            // CiA 402 reading to the shared one below, which then compiles
            // worse for every frame (BENCHMARKS.md, the summary's second
            // cut).
            (MessageKind::Pdo, Some(_)) if !log.frame.is_rtr() => {
                let (at, cia402) = decoder.pdo_cia402(log);
                let (name, bus) =
                    Self::bus_state(buses, *heartbeat, at, || decoder.bus_name(at).clone());
                add_classified(
                    bus,
                    name,
                    times,
                    position,
                    log,
                    kind,
                    node,
                    NO_SDO,
                    cia402,
                    |_| {},
                );
                return;
            }
            // A data frame on 0x700 + node is a guarding answer or a
            // heartbeat by the frames before it: the decoder tells.
            (MessageKind::Heartbeat | MessageKind::GuardRequest, Some(n)) => {
                decoder.error_control_frame(log, kind, n)
            }
            _ => (decoder.bus(&log.iface), kind),
        };
        let (name, bus) = Self::bus_state(buses, *heartbeat, at, || decoder.bus_name(at).clone());
        add_classified(
            bus,
            name,
            times,
            position,
            log,
            kind,
            node,
            NO_SDO,
            None,
            |_| {},
        );
    }

    /// Count a log entry that is not a frame (a TRC status row).
    fn add_status(&mut self, status: &BusStatus<'_>) {
        let at = self.decoder.bus(&status.iface);
        let decoder = &self.decoder;
        let (_, bus) = Self::bus_state(&mut self.buses, self.heartbeat, at, || {
            decoder.bus_name(at).clone()
        });
        bus.status_events += 1;
        bus.saw(status.timestamp);
    }
}

/// Add one frame of `kind` and `node` seen on `bus` (named `name`), with
/// its SDO step and CiA 402 reading where the decoder gave one, handing
/// `on_event` each fact; `times` are the summarizer's last time and count
/// of frames without one.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn add_classified(
    bus: &mut BusState,
    name: &BusName,
    times: (&mut Option<Duration>, &mut u64),
    position: u64,
    log: &LogFrame<'_>,
    kind: MessageKind,
    node: Option<NodeId>,
    sdo: Option<&impl SdoFrameFacts>,
    cia402: Option<(NodeId, Cia402Reading)>,
    mut on_event: impl FnMut(SummaryEvent<'_>),
) {
    let now = log.timestamp.map(Timestamp::as_duration);
    match now {
        Some(_) => *times.0 = now,
        None => *times.1 += 1,
    }
    let event = |node, kind| SummaryEvent {
        bus: name,
        node,
        line: position,
        timestamp: log.timestamp,
        kind,
    };
    bus.frames += 1;
    bus.saw(log.timestamp);
    if kind == MessageKind::ErrorFrame {
        bus.error_frames += 1;
        let (mut bus_off, mut error_passive) = (false, false);
        if let Ok(error) = ErrorFrame::from_frame(&log.frame) {
            bus_off = error.is_bus_off();
            error_passive = error.is_error_passive();
            if bus_off {
                bus.bus_off.push(position);
            }
            if error_passive {
                bus.error_passive.push(position);
            }
            if let (true, Some(ts)) = (bus_off || error_passive, log.timestamp) {
                bus.bus_error(BusErrorSeen {
                    line: position,
                    timestamp: ts,
                    bus_off,
                });
            }
        }
        on_event(event(
            None,
            SummaryEventKind::ErrorFrame {
                bus_off,
                error_passive,
            },
        ));
        return;
    }
    let Some(node) = node else { return };
    let BusState {
        nodes,
        storage,
        consumer,
        heartbeat,
        recent_errors,
        ..
    } = bus;
    let state = nodes[node.index()].get_or_insert_with(|| NodeState::new(node));
    state.frames.by_kind[kind.index()] += 1;
    if let Some(step) = sdo {
        let added = state.sdo.add(step, position);
        if added.abort {
            if let Some(abort) = state.sdo.last_abort() {
                on_event(SummaryEvent {
                    bus: name,
                    node: Some(node),
                    line: position,
                    timestamp: log.timestamp,
                    kind: SummaryEventKind::SdoAbort(abort),
                });
            }
        }
        if let (true, Some(ended)) = (added.ended, step.ended()) {
            on_event(sdo_ended(name, node, ended));
        }
    }
    if let Some((owner, reading)) = cia402 {
        // A PDO's drive is the node that owns it, which the log may
        // have moved to another node's COB-ID.
        let drive = nodes[owner.index()].get_or_insert_with(|| NodeState::new(owner));
        let last_error = drive.last_error;
        if let Some((transition, fault)) =
            drive
                .cia402
                .observe(position, log.timestamp, reading, last_error)
        {
            on_event(event(
                Some(owner),
                SummaryEventKind::Cia402 { transition, fault },
            ));
        }
        return;
    }
    // What `CanOpenMessage::decode` reads of the three kinds the
    // summary follows, read here without the rest of the message: an
    // EMCY of at least 8 bytes (not a remote request), a heartbeat's
    // first byte, a guard request.
    let frame = &log.frame;
    match kind {
        MessageKind::Emcy => {
            if frame.is_rtr() {
                return;
            }
            let Ok(emcy) = Emcy::parse(frame.data()) else {
                return;
            };
            state.emcy += 1;
            state.last_register = Some(emcy.register);
            let seen = EmcySeen {
                line: position,
                timestamp: log.timestamp,
                code: emcy.code,
                register: emcy.register,
                manufacturer: emcy.manufacturer,
            };
            on_event(event(
                Some(node),
                SummaryEventKind::Emcy {
                    code: emcy.code,
                    register: emcy.register,
                    manufacturer: emcy.manufacturer,
                },
            ));
            if emcy.is_reset() {
                state.resets += 1;
            } else {
                state.last_error = Some(seen);
                if state.first_error.is_none() {
                    state.first_error = Some(seen);
                }
            }
            // An EMCY that reports no error present (a warning) leaves the
            // node error-free: it is not the node's active error.
            if !emcy.reports_no_error() {
                if !emcy.is_reset() && state.first_error_with_register.is_none() {
                    state.first_error_with_register = Some(seen);
                }
                match storage.receive(node, emcy) {
                    SlotUpdate::RootCause => state.active_error = Some(seen),
                    SlotUpdate::Reset { .. } => state.active_error = None,
                    SlotUpdate::FollowUp { .. } => {}
                }
            }
        }
        MessageKind::GuardRequest => {
            // A missing answer is not part of the summary's contract.
            let _ = state.guarding.on_request(now.unwrap_or(Duration::ZERO));
        }
        MessageKind::GuardAnswer => {
            let Some(&byte) = frame.data().first() else {
                return;
            };
            let byte = NmtStateByte::new(byte);
            state.guarding_summary.answers += 1;
            // The node's last NMT state is the last frame's that tells it.
            state.last_state = Some(byte);
            on_event(event(
                Some(node),
                SummaryEventKind::Nmt {
                    state: byte,
                    guard_answer: true,
                },
            ));
            if let Some(answer) = byte.guard_answer() {
                let events = state
                    .guarding
                    .on_answer(now.unwrap_or(Duration::ZERO), answer);
                if events
                    .into_iter()
                    .any(|e| matches!(e, GuardingEvent::WrongToggle { .. }))
                {
                    state.guarding_summary.toggle_errors.push(position);
                    on_event(event(Some(node), SummaryEventKind::ToggleError));
                }
            }
        }
        MessageKind::Heartbeat => {
            let Some(&byte) = frame.data().first() else {
                return;
            };
            let byte = NmtStateByte::new(byte);
            state.heartbeats += 1;
            state.last_state = Some(byte);
            // The gap this heartbeat closes comes first: it lies before it.
            // The state is read only when a consumer watches the node.
            if let (Some(consumer), Some(now)) = (consumer.as_mut(), now) {
                if let Some(nmt) = byte.state() {
                    for event in consumer.on_heartbeat(now, node, nmt) {
                        match event {
                            HeartbeatEvent::Timeout { last_heartbeat, .. } => {
                                state.open_gap = Some((state.last_heartbeat_line, last_heartbeat));
                            }
                            HeartbeatEvent::Recovered { at, .. }
                            | HeartbeatEvent::RemoteReset { at, .. } => {
                                if let Some((after_line, last)) = state.open_gap.take() {
                                    let gap = HeartbeatGap {
                                        after_line,
                                        gap: at.saturating_sub(last),
                                        since: Timestamp::from_duration(last),
                                        due: Timestamp::from_duration(
                                            last + heartbeat.unwrap_or_default(),
                                        ),
                                        cause: state.gap_cause,
                                    };
                                    state.timeouts.push(gap);
                                    on_event(SummaryEvent {
                                        bus: name,
                                        node: Some(node),
                                        line: after_line,
                                        timestamp: Some(Timestamp::from_duration(last)),
                                        kind: SummaryEventKind::HeartbeatTimeout(gap),
                                    });
                                }
                            }
                            HeartbeatEvent::CapacityExceeded { .. } => {}
                        }
                    }
                }
            }
            on_event(event(
                Some(node),
                SummaryEventKind::Nmt {
                    state: byte,
                    guard_answer: false,
                },
            ));
            if byte.state_raw() == 0 {
                state.boot_ups.push(position);
                state.guarding.on_boot_up();
                // A device that re-initialises starts error-free (the
                // EMCY state machine's transition 0, CiA 301).
                storage.boot_up(node);
                state.active_error = None;
                state.last_register = None;
                on_event(event(Some(node), SummaryEventKind::BootUp));
            }
            state.last_heartbeat_line = position;
            if let (Some(time), Some(now)) = (*heartbeat, now) {
                let due = now + time;
                state.heartbeat_due = Some(due);
                state.gap_cause = recent_errors.earliest_for(due);
            }
        }
        _ => {}
    }
}

impl Summarizer {
    /// Close the input: transfers left open end (docs/canopen.md#transfers),
    /// heartbeats still missing at the last timestamp are timeouts up to it,
    /// and the nodes that are drives get their CiA 402 timeline
    /// (docs/summary.md#cia402).
    #[must_use]
    pub fn finish(self) -> Summary {
        self.finish_with(|_| {})
    }

    /// Close the input, as [`finish`](Self::finish) does, and hand
    /// `on_event` the facts that only the end of the input shows: the
    /// transfers left open, the heartbeat gaps still open at the last
    /// timestamp, the EtherCAT frames still waiting for their returned
    /// copy, which are lost ([`SummaryEvent`]).
    #[must_use]
    pub fn finish_with(mut self, mut on_event: impl FnMut(SummaryEvent<'_>)) -> Summary {
        for open in self.decoder.finish() {
            let state = self
                .buses
                .iter_mut()
                .find(|(name, _)| *name == open.bus)
                .and_then(|(_, bus)| bus.nodes[open.node.index()].as_mut());
            if let Some(state) = state {
                if state.sdo.ended(&open.transfer) {
                    on_event(sdo_ended(&open.bus, open.node, &open.transfer));
                }
            }
        }
        if let Some(end) = self.last_time {
            for (name, bus) in self.buses.iter_mut() {
                let name = &*name;
                let Some(consumer) = bus.consumer.as_mut() else {
                    continue;
                };
                for event in consumer.poll(end) {
                    if let HeartbeatEvent::Timeout {
                        node,
                        last_heartbeat,
                        ..
                    } = event
                    {
                        if let Some(state) = bus.nodes[node.index()].as_mut() {
                            state.open_gap = Some((state.last_heartbeat_line, last_heartbeat));
                        }
                    }
                }
                for state in bus.nodes.iter_mut().flatten() {
                    if let Some((after_line, last)) = state.open_gap.take() {
                        let gap = HeartbeatGap {
                            after_line,
                            gap: end.saturating_sub(last),
                            since: Timestamp::from_duration(last),
                            due: Timestamp::from_duration(last + bus.heartbeat.unwrap_or_default()),
                            cause: state.gap_cause,
                        };
                        state.timeouts.push(gap);
                        on_event(SummaryEvent {
                            bus: name,
                            node: Some(state.node),
                            line: after_line,
                            timestamp: Some(Timestamp::from_duration(last)),
                            kind: SummaryEventKind::HeartbeatTimeout(gap),
                        });
                    }
                }
            }
        }
        let checked = match (self.heartbeat.is_some(), self.untimed) {
            (false, _) => None,
            (true, 0) => Some(true),
            (true, _) => Some(false),
        };
        let decoder = &self.decoder;
        let mut buses = self.buses;
        buses.sort_by(|a, b| a.0.cmp(&b.0));
        let mut summary = Summary {
            nodes: Vec::new(),
            buses: Vec::new(),
            file: None,
            checked,
            verdict: None,
            ethercat: self
                .ethercat
                .map(|ethercat| ethercat.finish(|f| on_event(f.into())))
                .unwrap_or_default(),
        };
        for (name, bus) in buses {
            let mut nodes = Vec::new();
            for state in bus.nodes.into_iter().flatten() {
                nodes.push(state.node);
                let drive = decoder.is_drive(&name, state.node) || !state.cia402.is_empty();
                summary.nodes.push(NodeSummary {
                    bus: name.clone(),
                    node: state.node,
                    profile: decoder.config().profiles().of(Some(state.node)),
                    frames: state.frames,
                    emcy: state.emcy,
                    first_error: state.first_error,
                    first_error_with_register: state.first_error_with_register,
                    active_error: state.active_error,
                    resets: state.resets,
                    last_register: state.last_register,
                    heartbeat: HeartbeatSummary {
                        count: state.heartbeats,
                        last_state: state.last_state,
                        boot_ups: state.boot_ups,
                        timeouts: match checked {
                            None => Timeouts::NotAsked,
                            Some(false) => Timeouts::NotChecked,
                            Some(true) => Timeouts::Checked(state.timeouts),
                        },
                    },
                    guarding: state.guarding_summary,
                    sdo: state.sdo.finish(),
                    cia402: drive.then(|| state.cia402.finish()),
                });
            }
            summary.buses.push(BusSummary {
                bus: name,
                frames: bus.frames,
                error_frames: bus.error_frames,
                bus_off: bus.bus_off,
                error_passive: bus.error_passive,
                status_events: bus.status_events,
                first_timestamp: bus.first_ts,
                last_timestamp: bus.last_ts,
                nodes,
            });
        }
        summary.verdict = super::Verdict::of(&summary);
        summary
    }
}

/// The event of an SDO transfer that ended broken or unanswered, at its
/// start line (`sdo.broken`, `sdo.timeouts` in docs/summary.md#sdo).
fn sdo_ended<'s>(bus: &'s BusName, node: NodeId, transfer: &'s SdoTransfer) -> SummaryEvent<'s> {
    let kind = match transfer.outcome {
        SdoOutcome::TimedOut => SummaryEventKind::SdoTimeout(transfer),
        _ => SummaryEventKind::SdoBroken(transfer),
    };
    SummaryEvent {
        bus,
        node: Some(node),
        line: transfer.start_position,
        timestamp: transfer.started_at,
        kind,
    }
}
