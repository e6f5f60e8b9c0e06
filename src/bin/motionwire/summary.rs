//! `motionwire decode --summary`: one record per node seen, built with the
//! crate's own state machines — the CiA 405 EMCY storage for the root cause
//! (SPEC §3), the heartbeat consumer for timeouts and the node-guarding
//! observer for toggle errors (SPEC §2.7).

use std::io::{self, Write};
use std::time::Duration;

use motionwire::can::Timestamp;
use motionwire::canopen::{
    CanOpenMessage, EmcyStorage, GuardingEvent, HeartbeatConsumer, HeartbeatEvent, MessageKind,
    NmtStateByte, NodeGuardingMaster, NodeId, SlotUpdate,
};

use crate::json::{self, Object};
use motionwire::can::LogFrame;

use crate::record::Record;

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
        }
    }
}

/// The per-node summary of a whole input.
pub struct Summary {
    nodes: Vec<Option<NodeSummary>>,
    storage: EmcyStorage,
    consumer: Option<HeartbeatConsumer>,
    last_time: Option<Duration>,
    /// Frames of nodes that had no timestamp: with any, heartbeat timeouts
    /// cannot be checked (SPEC §5.7, §6.3).
    untimed: u64,
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
        let consumer = heartbeat_ms.map(|ms| {
            let mut consumer = HeartbeatConsumer::new();
            consumer.monitor_unconfigured(Duration::from_millis(u64::from(ms)));
            consumer
        });
        Summary {
            nodes: (0..127).map(|_| None).collect(),
            storage: EmcyStorage::new(),
            consumer,
            last_time: None,
            untimed: 0,
        }
    }

    /// Take one decoded frame into account.
    ///
    /// Only the frames whose contents the summary reads (EMCY, heartbeat,
    /// guard request) are decoded; the others are counted by the kind the
    /// library gives their identifier.
    pub fn add(&mut self, line: u64, log: &LogFrame<'_>) {
        let (kind, node) = MessageKind::classify(&log.frame);
        let Some(node) = node else { return };
        let now = log.timestamp.map(Timestamp::as_duration);
        match now {
            Some(_) => self.last_time = now,
            None => self.untimed += 1,
        }
        let summary = self.nodes[node.index()].get_or_insert_with(|| NodeSummary::new(node));
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
                let seen = Seen {
                    line: record.line,
                    ts: record.log.timestamp,
                    code: emcy.code.get(),
                };
                if emcy.is_reset() {
                    summary.resets += 1;
                } else if summary.first_error.is_none() {
                    summary.first_error = Some(seen);
                }
                match self.storage.receive(node, emcy) {
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
                    (self.consumer.as_mut(), now, byte.state())
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

    /// Close the input: heartbeats still missing at the last timestamp are
    /// timeouts up to that timestamp.
    fn finish(&mut self) {
        let (Some(consumer), Some(end)) = (self.consumer.as_mut(), self.last_time) else {
            return;
        };
        for event in consumer.poll(end) {
            if let HeartbeatEvent::Timeout {
                node,
                last_heartbeat,
                ..
            } = event
            {
                if let Some(summary) = self.nodes[node.index()].as_mut() {
                    summary.open_gap = Some((summary.last_heartbeat_line, last_heartbeat));
                }
            }
        }
        for summary in self.nodes.iter_mut().flatten() {
            if let Some((after_line, last)) = summary.open_gap.take() {
                summary.timeouts.push(Gap {
                    after_line,
                    gap: end.saturating_sub(last),
                });
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
        match (self.consumer.is_some(), self.untimed) {
            (false, _) => Timeouts::NotAsked,
            (true, 0) => Timeouts::Checked,
            (true, _) => Timeouts::NotChecked,
        }
    }

    /// Write one record per node seen, in node order.
    pub fn write<W: Write>(mut self, out: &mut W, as_json: bool) -> io::Result<()> {
        self.finish();
        let with_timeouts = self.timeouts();
        for summary in self.nodes.iter().flatten() {
            if as_json {
                write_json(out, summary, with_timeouts)?;
            } else {
                write_text(out, summary, with_timeouts)?;
            }
        }
        Ok(())
    }
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
    inner.end()
}

fn gap_ms(gap: &Gap) -> f64 {
    // Exact for every gap below 2^53 µs (285 years).
    gap.gap.as_micros() as f64 / 1000.0
}

fn write_json<W: Write>(out: &mut W, s: &NodeSummary, with_timeouts: Timeouts) -> io::Result<()> {
    let mut obj = Object::begin(out)?;
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
    obj.end()?;
    out.write_all(b"\n")
}

fn write_text<W: Write>(out: &mut W, s: &NodeSummary, with_timeouts: Timeouts) -> io::Result<()> {
    write!(out, "node {:>3}  frames", s.node.get())?;
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

struct Lines<'a>(&'a [u64]);

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
