//! `motionwire decode --summary`: one record per node seen, built with the
//! crate's own state machines — the CiA 405 EMCY storage for the root cause
//! (SPEC §3), the heartbeat consumer for timeouts and the node-guarding
//! observer for toggle errors (SPEC §2.7).

use std::io::{self, Write};
use std::time::Duration;

use motionwire::can::{ErrorFrame, Iface, LogEvent, Timestamp};
use motionwire::canopen::{
    CanOpenMessage, EmcyStorage, GuardingEvent, HeartbeatConsumer, HeartbeatEvent, MessageKind,
    NmtStateByte, NodeGuardingMaster, NodeId, SlotUpdate,
};

use crate::json::{self, Object};
use motionwire::can::LogFrame;
use motionwire::canopen::ErrorCode;

use crate::args::Profile;
use crate::context::Cia402View;
use crate::profile::Profiles;
use crate::record::Record;
use crate::sdo::{SdoStats, SdoView};
use motionwire::canopen::sdo::SdoTransfer;
use motionwire::canopen::Cia402State;

/// Where an EMCY was seen: its line, timestamp and code.
#[derive(Debug, Clone, Copy)]
struct Seen {
    line: u64,
    ts: Option<Timestamp>,
    code: u16,
}

/// A heartbeat gap longer than `--heartbeat-ms`.
#[derive(Debug, Clone, Copy)]
struct Gap {
    /// The line of the heartbeat before the gap.
    after_line: u64,
    /// The gap.
    gap: Duration,
}

/// What the summary knows about one node.
#[derive(Debug)]
struct NodeSummary {
    node: NodeId,
    frames: [u64; MessageKind::ALL.len()],
    emcy: u64,
    resets: u64,
    first_error: Option<Seen>,
    active_error: Option<Seen>,
    last_register: Option<u8>,
    heartbeats: u64,
    last_state: Option<NmtStateByte>,
    boot_ups: Vec<u64>,
    /// The line of the last heartbeat (not guarding answer) seen.
    last_heartbeat_line: u64,
    /// A timeout reported by the consumer and not yet closed by a
    /// heartbeat: the line and time (µs) of the heartbeat before it.
    open_gap: Option<(u64, Duration)>,
    timeouts: Vec<Gap>,
    /// A guard request (RTR) was seen and not yet answered: the next data
    /// frame on 0x700 + node is its answer.
    guard_request_pending: bool,
    guarding: NodeGuardingMaster,
    answers: u64,
    toggle_errors: Vec<u64>,
    /// The node's SDO channel (SPEC §7.4).
    sdo: SdoStats,
    /// The node is a CiA 402 drive (SPEC §8.3).
    drive: bool,
    /// The observed CiA 402 timeline (SPEC §8.3).
    cia402: Cia402Timeline,
    /// The node's error EMCYs, for the text's "after EMCY …".
    errors: Vec<Seen>,
}

impl NodeSummary {
    fn new(node: NodeId) -> Self {
        NodeSummary {
            node,
            frames: [0; MessageKind::ALL.len()],
            emcy: 0,
            resets: 0,
            first_error: None,
            active_error: None,
            last_register: None,
            heartbeats: 0,
            last_state: None,
            boot_ups: Vec::new(),
            last_heartbeat_line: 0,
            open_gap: None,
            timeouts: Vec::new(),
            guard_request_pending: false,
            // A log rarely shows the guard time (100Ch): observe toggles only.
            guarding: NodeGuardingMaster::observer(node, Duration::ZERO),
            answers: 0,
            toggle_errors: Vec::new(),
            sdo: SdoStats::default(),
            drive: false,
            cia402: Cia402Timeline::default(),
            errors: Vec::new(),
        }
    }
}

/// The per-node summary of a whole input.
pub struct Summary {
    /// One per interface, in the order first seen.
    buses: Vec<Bus>,
    /// The bus of the last frame (a log's frames mostly share one).
    last_bus: usize,
    /// Where the last frame's interface name lay in the input buffer
    /// (address, length): the same name slice means the same bus without
    /// comparing (candump's lines of one block share one name slice). Valid
    /// until [`Summary::new_block`].
    last_name: (usize, usize),
    heartbeat_ms: Option<u16>,
    last_time: Option<Duration>,
    untimed: u64,
}

/// An interface as the summary keeps it (owned: records outlive the input
/// buffer). Ordered for the output: no interface, channels, names.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub enum BusName {
    None,
    Channel(u16),
    Name(String),
}

impl BusName {
    pub fn of(iface: Option<Iface<'_>>) -> Self {
        match iface {
            None => BusName::None,
            Some(Iface::Channel(n)) => BusName::Channel(n),
            Some(Iface::Name(name)) => BusName::Name(name.to_owned()),
        }
    }

    #[inline]
    pub fn is(&self, iface: Option<Iface<'_>>) -> bool {
        match (self, iface) {
            (BusName::None, None) => true,
            (BusName::Channel(a), Some(Iface::Channel(b))) => *a == b,
            (BusName::Name(a), Some(Iface::Name(b))) => same_name(a.as_bytes(), b.as_bytes()),
            _ => false,
        }
    }

    fn json<W: Write>(&self, obj: &mut Object<'_, W>) -> io::Result<()> {
        match self {
            BusName::None => obj.null("iface"),
            BusName::Channel(n) => obj.str("iface", &n.to_string()),
            BusName::Name(name) => obj.str("iface", name),
        }
    }

    fn text(&self) -> String {
        match self {
            BusName::None => "-".to_owned(),
            BusName::Channel(n) => n.to_string(),
            BusName::Name(name) => name.clone(),
        }
    }
}

/// Whether two interface names are equal, compared in line: names are a
/// few bytes, and a call to `memcmp` per frame costs more than the compare.
#[inline(always)]
fn same_name(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x == y)
}

/// Everything seen on one interface: its nodes (SPEC §5.7: a node's
/// identity is (interface, node)) with their own EMCY storage and heartbeat
/// consumer, and the bus record of SPEC §6.3.
#[derive(Debug)]
struct Bus {
    name: BusName,
    nodes: Vec<Option<NodeSummary>>,
    storage: EmcyStorage,
    consumer: Option<HeartbeatConsumer>,
    frames: u64,
    error_frames: u64,
    bus_off: Vec<u64>,
    error_passive: Vec<u64>,
    status_events: u64,
    first_ts: Option<Timestamp>,
    last_ts: Option<Timestamp>,
}

impl Bus {
    fn new(name: BusName, heartbeat_ms: Option<u16>) -> Self {
        let consumer = heartbeat_ms.map(|ms| {
            let mut consumer = HeartbeatConsumer::new();
            consumer.monitor_unconfigured(Duration::from_millis(u64::from(ms)));
            consumer
        });
        Bus {
            name,
            nodes: (0..127).map(|_| None).collect(),
            storage: EmcyStorage::new(),
            consumer,
            frames: 0,
            error_frames: 0,
            bus_off: Vec::new(),
            error_passive: Vec::new(),
            status_events: 0,
            first_ts: None,
            last_ts: None,
        }
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

/// Whether heartbeat timeouts are reported (SPEC §6.3, §5.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Timeouts {
    /// `--heartbeat-ms` was not given: no `timeouts` key.
    NotAsked,
    /// Asked, but frames without timestamps make it impossible: `null`.
    NotChecked,
    /// Asked and checked: the list.
    Checked,
}

impl Summary {
    /// Start a summary; with `heartbeat_ms`, every node's heartbeats are
    /// monitored with that consumer time (object 1016h, ms).
    pub fn new(heartbeat_ms: Option<u16>) -> Self {
        Summary {
            buses: Vec::new(),
            last_bus: 0,
            last_name: (0, 0),
            heartbeat_ms,
            last_time: None,
            untimed: 0,
        }
    }

    /// The input buffer changes: interface names are no longer where they
    /// were.
    pub fn new_block(&mut self) {
        self.last_name = (0, 0);
    }

    /// The bus of an interface, made on first sight.
    #[inline]
    fn bus(&mut self, iface: Option<Iface<'_>>) -> &mut Bus {
        if let Some(Iface::Name(name)) = iface {
            let key = (name.as_ptr() as usize, name.len());
            if key == self.last_name {
                return &mut self.buses[self.last_bus];
            }
            self.last_name = key;
        }
        let at = match self.buses.get(self.last_bus) {
            Some(bus) if bus.name.is(iface) => self.last_bus,
            _ => match self.buses.iter().position(|bus| bus.name.is(iface)) {
                Some(at) => at,
                None => {
                    self.buses
                        .push(Bus::new(BusName::of(iface), self.heartbeat_ms));
                    self.buses.len() - 1
                }
            },
        };
        self.last_bus = at;
        &mut self.buses[at]
    }

    /// Count a log entry that is not a frame (a TRC status row; SPEC §6.3
    /// `status_events`).
    pub fn add_event(&mut self, event: &LogEvent<'_>) {
        if let LogEvent::Status(status) = event {
            let bus = self.bus(status.iface);
            bus.status_events += 1;
            bus.saw(status.timestamp);
        }
    }

    /// Add one frame, read on `line` of the input.
    /// Add one frame, read on `line` of the input; return its kind and
    /// node, which the caller's context may need.
    pub fn add(&mut self, line: u64, log: &LogFrame<'_>) -> (MessageKind, Option<NodeId>) {
        let (kind, node) = MessageKind::classify(&log.frame);
        self.add_classified(line, log, kind, node);
        (kind, node)
    }

    fn add_classified(
        &mut self,
        line: u64,
        log: &LogFrame<'_>,
        kind: MessageKind,
        node: Option<NodeId>,
    ) {
        let now = log.timestamp.map(Timestamp::as_duration);
        match now {
            Some(_) => self.last_time = now,
            None => self.untimed += 1,
        }
        let bus = self.bus(log.iface);
        bus.frames += 1;
        bus.saw(log.timestamp);
        if kind == MessageKind::ErrorFrame {
            bus.error_frames += 1;
            if let Ok(error) = ErrorFrame::from_frame(&log.frame) {
                if error.is_bus_off() {
                    bus.bus_off.push(line);
                }
                if error.is_error_passive() {
                    bus.error_passive.push(line);
                }
            }
            return;
        }
        let Some(node) = node else { return };
        let summary = bus.nodes[node.index()].get_or_insert_with(|| NodeSummary::new(node));
        summary.frames[kind.index()] += 1;
        if !matches!(
            kind,
            MessageKind::Emcy | MessageKind::Heartbeat | MessageKind::GuardRequest
        ) {
            return;
        }
        let record = Record::new(line, log);
        let Ok(message) = &record.decoded else { return };
        match *message {
            CanOpenMessage::Emcy { emcy, .. } => {
                summary.emcy += 1;
                summary.last_register = Some(emcy.register.bits());
                let seen = Seen {
                    line: record.line,
                    ts: record.log.timestamp,
                    code: emcy.code.get(),
                };
                if !emcy.is_reset() {
                    summary.errors.push(seen);
                }
                if emcy.is_reset() {
                    summary.resets += 1;
                } else if summary.first_error.is_none() {
                    summary.first_error = Some(seen);
                }
                match bus.storage.receive(node, emcy) {
                    SlotUpdate::RootCause => summary.active_error = Some(seen),
                    SlotUpdate::Reset { .. } => summary.active_error = None,
                    SlotUpdate::FollowUp { .. } => {}
                }
            }
            CanOpenMessage::GuardRequest { .. } => {
                summary.guard_request_pending = true;
                // A missing answer is not part of the summary's contract.
                let _ = summary.guarding.on_request(now.unwrap_or(Duration::ZERO));
            }
            CanOpenMessage::Heartbeat { byte, .. } if summary.guard_request_pending => {
                summary.guard_request_pending = false;
                summary.answers += 1;
                if let Some(answer) = byte.guard_answer() {
                    let events = summary
                        .guarding
                        .on_answer(now.unwrap_or(Duration::ZERO), answer);
                    if events
                        .into_iter()
                        .any(|e| matches!(e, GuardingEvent::WrongToggle { .. }))
                    {
                        summary.toggle_errors.push(record.line);
                    }
                }
            }
            CanOpenMessage::Heartbeat { byte, .. } => {
                summary.heartbeats += 1;
                summary.last_state = Some(byte);
                if byte.state_raw() == 0 {
                    summary.boot_ups.push(record.line);
                    summary.guarding.on_boot_up();
                }
                if let (Some(consumer), Some(now), Some(nmt)) =
                    (bus.consumer.as_mut(), now, byte.state())
                {
                    for event in consumer.on_heartbeat(now, node, nmt) {
                        match event {
                            HeartbeatEvent::Timeout { last_heartbeat, .. } => {
                                summary.open_gap =
                                    Some((summary.last_heartbeat_line, last_heartbeat));
                            }
                            HeartbeatEvent::Recovered { at, .. }
                            | HeartbeatEvent::RemoteReset { at, .. } => {
                                if let Some((after_line, last)) = summary.open_gap.take() {
                                    summary.timeouts.push(Gap {
                                        after_line,
                                        gap: at.saturating_sub(last),
                                    });
                                }
                            }
                            HeartbeatEvent::CapacityExceeded { .. } => {}
                        }
                    }
                }
                summary.last_heartbeat_line = record.line;
            }
            _ => {}
        }
    }

    /// The node summary of `node` on the interface of `log` (made by
    /// [`add`](Self::add) for that frame).
    fn node_of(&mut self, log: &LogFrame<'_>, node: NodeId) -> &mut NodeSummary {
        let bus = self.bus(log.iface);
        bus.nodes[node.index()].get_or_insert_with(|| NodeSummary::new(node))
    }

    /// An SDO frame as its channel's tracker read it (SPEC §7.4), with the
    /// CiA 402 state an expedited transfer of the statusword shows.
    pub fn add_sdo(&mut self, line: u64, log: &LogFrame<'_>, node: NodeId, view: &SdoView<'_>) {
        let summary = self.node_of(log, node);
        summary.sdo.add(view, line);
        if let Some(cia402) = view.cia402 {
            summary.cia402.observe(line, log.timestamp, cia402);
        }
    }

    /// A drive's PDO with its CiA 402 reading (SPEC §8.3).
    pub fn add_cia402(&mut self, line: u64, log: &LogFrame<'_>, node: NodeId, view: Cia402View) {
        let summary = self.node_of(log, node);
        summary.cia402.observe(line, log.timestamp, view);
    }

    /// A transfer the input ended in the middle of (SPEC §7.2: summary
    /// only).
    pub fn sdo_left_open(&mut self, bus: &BusName, node: NodeId, transfer: &SdoTransfer) {
        if let Some(summary) = self
            .buses
            .iter_mut()
            .find(|b| &b.name == bus)
            .and_then(|b| b.nodes[node.index()].as_mut())
        {
            summary.sdo.ended(transfer);
        }
    }

    /// Mark the nodes that are drives: their records get `cia402`
    /// (SPEC §8.3; null for the others).
    pub fn drives(&mut self, is_drive: impl Fn(&BusName, NodeId) -> bool) {
        for bus in &mut self.buses {
            for summary in bus.nodes.iter_mut().flatten() {
                summary.drive = is_drive(&bus.name, summary.node) || !summary.cia402.is_empty();
            }
        }
    }

    /// Close the input: heartbeats still missing at the last timestamp are
    /// timeouts up to that timestamp.
    fn finish(&mut self) {
        let Some(end) = self.last_time else { return };
        for bus in &mut self.buses {
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
                    if let Some(summary) = bus.nodes[node.index()].as_mut() {
                        summary.open_gap = Some((summary.last_heartbeat_line, last_heartbeat));
                    }
                }
            }
            for summary in bus.nodes.iter_mut().flatten() {
                if let Some((after_line, last)) = summary.open_gap.take() {
                    summary.timeouts.push(Gap {
                        after_line,
                        gap: end.saturating_sub(last),
                    });
                }
            }
        }
    }

    /// Return whether heartbeat timeouts were asked for but could not be
    /// checked because frames had no timestamps (SPEC §5.7: said once on
    /// standard error).
    pub fn timeouts_not_checked(&self) -> bool {
        self.timeouts() == Timeouts::NotChecked
    }

    fn timeouts(&self) -> Timeouts {
        match (self.heartbeat_ms.is_some(), self.untimed) {
            (false, _) => Timeouts::NotAsked,
            (true, 0) => Timeouts::Checked,
            (true, _) => Timeouts::NotChecked,
        }
    }

    /// Write one record per (interface, node) seen, by interface then node,
    /// then one record per interface (SPEC §6.3).
    pub fn write<W: Write>(
        mut self,
        out: &mut W,
        as_json: bool,
        profiles: &Profiles,
    ) -> io::Result<()> {
        self.finish();
        let with_timeouts = self.timeouts();
        self.buses.sort_by(|a, b| a.name.cmp(&b.name));
        for bus in &self.buses {
            for summary in bus.nodes.iter().flatten() {
                let profile = profiles.of(Some(summary.node));
                if as_json {
                    write_json(out, &bus.name, summary, with_timeouts, profile)?;
                } else {
                    write_text(out, &bus.name, summary, with_timeouts, profile)?;
                }
            }
        }
        for bus in &self.buses {
            if as_json {
                write_bus_json(out, bus)?;
            } else {
                write_bus_text(out, bus)?;
            }
        }
        Ok(())
    }
}

fn nodes_of(bus: &Bus) -> impl Iterator<Item = u64> + '_ {
    bus.nodes
        .iter()
        .flatten()
        .map(|summary| u64::from(summary.node.get()))
}

fn write_bus_json<W: Write>(out: &mut W, bus: &Bus) -> io::Result<()> {
    let mut obj = Object::begin(out)?;
    obj.name("type", "bus")?;
    bus.name.json(&mut obj)?;
    obj.uint("frames", bus.frames)?;
    obj.uint("error_frames", bus.error_frames)?;
    obj.uints("bus_off", bus.bus_off.iter().copied())?;
    obj.uints("error_passive", bus.error_passive.iter().copied())?;
    obj.uint("status_events", bus.status_events)?;
    for (key, ts) in [("first_ts", bus.first_ts), ("last_ts", bus.last_ts)] {
        match ts {
            Some(ts) => json::timestamp(obj.key(key)?, ts)?,
            None => obj.null(key)?,
        }
    }
    obj.uints("nodes", nodes_of(bus))?;
    obj.end()?;
    out.write_all(b"\n")
}

fn write_bus_text<W: Write>(out: &mut W, bus: &Bus) -> io::Result<()> {
    write!(
        out,
        "bus {}  frames {}, error frames {}",
        bus.name.text(),
        bus.frames,
        bus.error_frames
    )?;
    if !bus.bus_off.is_empty() {
        write!(out, ", bus-off at lines {}", Lines(&bus.bus_off))?;
    }
    if !bus.error_passive.is_empty() {
        write!(
            out,
            ", error-passive at lines {}",
            Lines(&bus.error_passive)
        )?;
    }
    if bus.status_events > 0 {
        write!(out, ", status events {}", bus.status_events)?;
    }
    if let (Some(first), Some(last)) = (bus.first_ts, bus.last_ts) {
        write!(out, ", from {} to {}", Seconds(first), Seconds(last))?;
    }
    let nodes: Vec<u64> = nodes_of(bus).collect();
    if !nodes.is_empty() {
        write!(out, ", nodes {}", Lines(&nodes))?;
    }
    writeln!(out)
}

fn seen_json<W: Write>(
    obj: &mut Object<'_, W>,
    key: &'static str,
    seen: Option<Seen>,
) -> io::Result<()> {
    let Some(seen) = seen else {
        return obj.null(key);
    };
    let out = obj.key(key)?;
    let mut inner = Object::begin(out)?;
    inner.uint("line", seen.line)?;
    match seen.ts {
        Some(ts) => json::timestamp(inner.key("ts")?, ts)?,
        None => inner.null("ts")?,
    }
    inner.uint("code", u64::from(seen.code))?;
    inner.str("description", ErrorCode::new(seen.code).description())?;
    inner.end()
}

fn gap_ms(gap: &Gap) -> f64 {
    // Exact for every gap below 2^53 µs (285 years).
    gap.gap.as_micros() as f64 / 1000.0
}

fn write_json<W: Write>(
    out: &mut W,
    bus: &BusName,
    s: &NodeSummary,
    with_timeouts: Timeouts,
    profile: Profile,
) -> io::Result<()> {
    let mut obj = Object::begin(out)?;
    obj.name("type", "node")?;
    bus.json(&mut obj)?;
    obj.uint("node", u64::from(s.node.get()))?;
    {
        let mut frames = Object::begin(obj.key("frames")?)?;
        for kind in MessageKind::ALL {
            frames.uint(kind.name(), s.frames[kind.index()])?;
        }
        frames.end()?;
    }
    obj.uint("emcy", s.emcy)?;
    seen_json(&mut obj, "first_error", s.first_error)?;
    seen_json(&mut obj, "active_error", s.active_error)?;
    obj.uint("resets", s.resets)?;
    match s.last_register {
        Some(register) => obj.uint("last_register", u64::from(register))?,
        None => obj.null("last_register")?,
    }
    {
        let mut hb = Object::begin(obj.key("heartbeat")?)?;
        hb.uint("count", s.heartbeats)?;
        match s.last_state {
            Some(state) => hb.name("last_state", state.state_name())?,
            None => hb.null("last_state")?,
        }
        hb.uints("boot_ups", s.boot_ups.iter().copied())?;
        if with_timeouts == Timeouts::NotChecked {
            hb.null("timeouts")?;
        }
        if with_timeouts == Timeouts::Checked {
            let out = hb.key("timeouts")?;
            out.write_all(b"[")?;
            for (i, gap) in s.timeouts.iter().enumerate() {
                if i > 0 {
                    out.write_all(b",")?;
                }
                let mut t = Object::begin(out)?;
                t.uint("after_line", gap.after_line)?;
                t.float("gap_ms", gap_ms(gap))?;
                t.end()?;
            }
            out.write_all(b"]")?;
        }
        hb.end()?;
    }
    {
        let mut g = Object::begin(obj.key("guarding")?)?;
        g.uint("answers", s.answers)?;
        g.uints("toggle_errors", s.toggle_errors.iter().copied())?;
        g.end()?;
    }
    s.sdo.write_json(obj.key("sdo")?, profile)?;
    if s.drive {
        s.cia402.write_json(obj.key("cia402")?)?;
    } else {
        obj.null("cia402")?;
    }
    obj.end()?;
    out.write_all(b"\n")
}

fn write_text<W: Write>(
    out: &mut W,
    bus: &BusName,
    s: &NodeSummary,
    with_timeouts: Timeouts,
    profile: Profile,
) -> io::Result<()> {
    write!(out, "{} node {:>3}  frames", bus.text(), s.node.get())?;
    for kind in MessageKind::ALL {
        let n = s.frames[kind.index()];
        if n > 0 {
            write!(out, " {}={n}", kind.name())?;
        }
    }
    writeln!(out)?;
    write!(out, "          emcy {} (resets {})", s.emcy, s.resets)?;
    write_seen(out, "first error", s.first_error)?;
    write_seen(out, "active error", s.active_error)?;
    if let Some(register) = s.last_register.filter(|&r| r != 0) {
        if s.active_error.is_none() {
            // A reset EMCY with a non-zero register: other errors are still
            // active (SPEC §6.3).
            write!(
                out,
                ", error register {register:#04x} still set by the last EMCY"
            )?;
        }
    }
    writeln!(out)?;
    write!(
        out,
        "          heartbeats {}, last state {}",
        s.heartbeats,
        s.last_state.map_or("-", |st| st.state_name())
    )?;
    if !s.boot_ups.is_empty() {
        write!(out, ", boot-ups at lines {}", Lines(&s.boot_ups))?;
    }
    if with_timeouts == Timeouts::NotChecked {
        out.write_all(b", timeouts not checked (no timestamps)")?;
    }
    if with_timeouts == Timeouts::Checked {
        if s.timeouts.is_empty() {
            out.write_all(b", no timeouts")?;
        }
        for gap in &s.timeouts {
            write!(
                out,
                ", timeout: {} ms after line {}",
                gap_ms(gap),
                gap.after_line
            )?;
        }
    }
    writeln!(out)?;
    if s.answers > 0 || !s.toggle_errors.is_empty() {
        write!(out, "          guarding answers {}", s.answers)?;
        if !s.toggle_errors.is_empty() {
            write!(out, ", wrong toggle at lines {}", Lines(&s.toggle_errors))?;
        }
        writeln!(out)?;
    }
    s.sdo.write_text(out, profile)?;
    if s.drive {
        s.cia402.write_text(out, &s.errors)?;
    }
    Ok(())
}

fn write_seen<W: Write>(out: &mut W, what: &str, seen: Option<Seen>) -> io::Result<()> {
    match seen {
        None => write!(out, ", {what}: none"),
        Some(seen) => {
            let code = motionwire::canopen::ErrorCode::new(seen.code);
            write!(
                out,
                ", {what}: {code} {} (line {})",
                code.description(),
                seen.line
            )
        }
    }
}

/// A time as seconds with six decimals and no padding (`0.052000`,
/// `1700000000.000520`): relative times read as they are.
struct Seconds(Timestamp);

impl std::fmt::Display for Seconds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}.{:06}", self.0.secs(), self.0.micros())
    }
}

pub struct Lines<'a>(pub &'a [u64]);

impl std::fmt::Display for Lines<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, line) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{line}")?;
        }
        Ok(())
    }
}

/// One change of a drive's observed state (SPEC §8.3).
#[derive(Debug, Clone, Copy)]
struct Transition {
    line: u64,
    ts: Option<Timestamp>,
    from: Option<Cia402State>,
    to: Cia402State,
}

/// A drive's observed CiA 402 timeline, from statuswords only (SPEC §8.3).
#[derive(Debug, Default)]
struct Cia402Timeline {
    transitions: Vec<Transition>,
    faults: Vec<u64>,
}

impl Cia402Timeline {
    fn is_empty(&self) -> bool {
        self.transitions.is_empty()
    }

    fn last_state(&self) -> Option<Cia402State> {
        self.transitions.last().map(|t| t.to)
    }

    /// A frame's CiA 402 reading: a state that differs from the last one
    /// is a transition; entering fault reaction active or fault from a
    /// state that is neither is a fault.
    fn observe(&mut self, line: u64, ts: Option<Timestamp>, view: Cia402View) {
        let Some(to) = view.state else { return };
        let from = self.last_state();
        if from == Some(to) {
            return;
        }
        if to.is_fault() && !from.is_some_and(Cia402State::is_fault) {
            self.faults.push(line);
        }
        self.transitions.push(Transition { line, ts, from, to });
    }

    fn write_json<W: Write>(&self, out: &mut W) -> io::Result<()> {
        let mut obj = Object::begin(out)?;
        let list = obj.key("transitions")?;
        list.write_all(b"[")?;
        for (i, t) in self.transitions.iter().enumerate() {
            if i > 0 {
                list.write_all(b",")?;
            }
            let mut o = Object::begin(list)?;
            o.uint("line", t.line)?;
            match t.ts {
                Some(ts) => json::timestamp(o.key("ts")?, ts)?,
                None => o.null("ts")?,
            }
            match t.from {
                Some(from) => o.name("from", from.name())?,
                None => o.null("from")?,
            }
            o.name("to", t.to.name())?;
            o.end()?;
        }
        list.write_all(b"]")?;
        match self.last_state() {
            Some(state) => obj.name("last_state", state.name())?,
            None => obj.null("last_state")?,
        }
        obj.uints("faults", self.faults.iter().copied())?;
        obj.end()
    }

    /// The timeline in sentences: the states in order, and each fault with
    /// the EMCY before it.
    fn write_text<W: Write>(&self, out: &mut W, errors: &[Seen]) -> io::Result<()> {
        if self.transitions.is_empty() {
            return writeln!(out, "          CiA 402: no statusword seen");
        }
        // Up to 12 states in full; a longer timeline shows its first 4 and
        // last 8 (the JSON record has them all).
        let n = self.transitions.len();
        write!(out, "          CiA 402, {n} states in turn:")?;
        for (i, t) in self.transitions.iter().enumerate() {
            if n > 12 && (4..n - 8).contains(&i) {
                if i == 4 {
                    write!(out, " → … {} more …", n - 12)?;
                }
                continue;
            }
            if i > 0 {
                out.write_all(" →".as_bytes())?;
            }
            write!(out, " {} (line {})", t.to.name(), t.line)?;
        }
        writeln!(out)?;
        for &line in &self.faults {
            let t = self
                .transitions
                .iter()
                .find(|t| t.line == line)
                .expect("a fault is a transition");
            write!(
                out,
                "          went {} → {} at line {}",
                t.from.map_or("-", Cia402State::name),
                t.to.name(),
                line
            )?;
            // The node's last error EMCY at or before the fault.
            let before = errors.partition_point(|e| e.line <= line);
            if let Some(&emcy) = before.checked_sub(1).and_then(|i| errors.get(i)) {
                let code = motionwire::canopen::ErrorCode::new(emcy.code);
                match (t.ts, emcy.ts) {
                    (Some(at), Some(then)) => {
                        let gap = at.duration_since(then).unwrap_or_default();
                        write!(
                            out,
                            ", {:.1} ms after EMCY {code} {} (line {})",
                            gap.as_secs_f64() * 1000.0,
                            code.description(),
                            emcy.line
                        )?;
                    }
                    _ => write!(
                        out,
                        ", after EMCY {code} {} (line {})",
                        code.description(),
                        emcy.line
                    )?,
                }
            }
            writeln!(out)?;
        }
        Ok(())
    }
}
