//! A servo's timeline from its process data (docs/ethercat.md#servo): the
//! enable handshake's phases, the error word's faults set and cleared with
//! their E-codes, the error-clear and zero-pulse handshakes, ServoRDY, and
//! the actual position.

use core::fmt;

use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

use crate::can::Timestamp;
use crate::decoder::ethercat::ServoReading;
use crate::servo::{ActualPosition, EnablePhase, HandshakePhase, ServoErrorWord, ServoFault};

use super::values::Ts;
use super::Listed;

/// What changed in one cycle of a servo (`servo.events` in
/// docs/ethercat.md#servo).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ServoChange {
    /// The enable handshake went to a new phase; `cycles` spent in the
    /// phase before.
    Enable {
        /// The phase before.
        from: EnablePhase,
        /// The new phase.
        to: EnablePhase,
        /// The cycles spent in `from`.
        cycles: u32,
    },
    /// A fault of the error word appeared.
    FaultSet(ServoFault),
    /// A fault of the error word went away.
    FaultCleared(ServoFault),
    /// The error-clear handshake went to a new phase.
    ErrorClear(HandshakePhase),
    /// The zero-pulse handshake went to a new phase; at `acknowledged`,
    /// the zero-pulse position the feedback carries.
    ZeroPulse {
        /// The new phase.
        phase: HandshakePhase,
        /// The zero-pulse position (POSW2..3), where the feedback has it.
        position: Option<i32>,
    },
    /// ServoRDY changed.
    Ready(bool),
}

impl ServoChange {
    /// Return whether the change is an enable edge the drive did not
    /// answer: the enable handshake left `enabling` for another phase than
    /// `enabled` (counted in [`ServoTimeline::enable_unanswered`]).
    #[must_use]
    pub fn is_unanswered_enable(&self) -> bool {
        matches!(
            self,
            ServoChange::Enable {
                from: EnablePhase::Enabling,
                to,
                ..
            } if *to != EnablePhase::Enabled
        )
    }
}

/// One change, with where it was seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ServoEvent {
    /// The returned packet of the cycle.
    pub packet: u64,
    /// Its time.
    pub timestamp: Option<Timestamp>,
    /// What changed.
    pub change: ServoChange,
}

/// What the timeline keeps of the last cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LastCycle {
    enable: EnablePhase,
    enable_cycles: u32,
    error_clear: HandshakePhase,
    zero_pulse: HandshakePhase,
    /// The error word of the last confirmed feedback.
    errors: Option<ServoErrorWord>,
    ready: Option<bool>,
}

/// A servo's timeline (`servo` of a slave record, docs/ethercat.md#servo).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ServoTimeline {
    /// Cycles read.
    pub cycles: u64,
    /// Cycles whose feedback was unconfirmed (a short working counter).
    pub unconfirmed: u64,
    /// The changes in order (the first and the last, and their count).
    pub events: Listed<ServoEvent>,
    /// Every fault the error word showed.
    pub faults_seen: ServoErrorWord,
    /// Enable edges the drive did not answer: the enable handshake left
    /// `enabling` for another phase than `enabled`.
    pub enable_unanswered: u64,
    /// Changes of the enable handshake's phase (`enable` events).
    pub enable_change_count: u64,
    /// Faults of the error word that appeared (`fault_set` events).
    pub fault_set_count: u64,
    /// The faults set, each with where (the first and the last, and their
    /// count: docs/summary.md#lists): the findings of the servo
    /// (docs/ethercat.md#findings), whatever the changes around them.
    pub faults: Listed<ServoEvent>,
    /// Error-clear handshakes requested (`error_clear` events of phase
    /// `requested`).
    pub error_clear_count: u64,
    /// Zero-pulse handshakes requested (`zero_pulse` events of phase
    /// `requested`).
    pub zero_pulse_count: u64,
    /// ServoRDY seen low where it was high or not yet known (`ready`
    /// events of `false`).
    pub not_ready_count: u64,
    /// The first and the last actual position read.
    pub first_position: Option<ActualPosition>,
    /// The last.
    pub last_position: Option<ActualPosition>,
    /// The last cycle.
    pub(crate) last: Option<LastCycle>,
}

impl Default for ServoTimeline {
    fn default() -> Self {
        ServoTimeline {
            cycles: 0,
            unconfirmed: 0,
            events: Listed::new(),
            faults_seen: ServoErrorWord::empty(),
            enable_unanswered: 0,
            enable_change_count: 0,
            fault_set_count: 0,
            faults: Listed::new(),
            error_clear_count: 0,
            zero_pulse_count: 0,
            not_ready_count: 0,
            first_position: None,
            last_position: None,
            last: None,
        }
    }
}

impl ServoTimeline {
    /// One cycle's reading.
    pub(crate) fn observe(
        &mut self,
        packet: u64,
        timestamp: Option<Timestamp>,
        now: &ServoReading,
    ) {
        self.cycles += 1;
        let mut push = |change| {
            let event = ServoEvent {
                packet,
                timestamp,
                change,
            };
            match change {
                ServoChange::Enable { .. } => self.enable_change_count += 1,
                ServoChange::FaultSet(fault) => {
                    self.fault_set_count += 1;
                    if fault != ServoFault::ServoErrors {
                        self.faults.push(event);
                    }
                }
                ServoChange::ErrorClear(HandshakePhase::Requested) => self.error_clear_count += 1,
                ServoChange::ZeroPulse {
                    phase: HandshakePhase::Requested,
                    ..
                } => self.zero_pulse_count += 1,
                ServoChange::Ready(false) => self.not_ready_count += 1,
                _ => {}
            }
            self.events.push(event);
        };
        let before = self.last;
        let enable_before = before.map_or(EnablePhase::Disabled, |b| b.enable);
        if now.enable != enable_before {
            let cycles = before.map_or(0, |b| b.enable_cycles.saturating_add(1));
            let change = ServoChange::Enable {
                from: enable_before,
                to: now.enable,
                cycles,
            };
            push(change);
            if change.is_unanswered_enable() {
                self.enable_unanswered += 1;
            }
        }
        let clear_before = before.map_or(HandshakePhase::Idle, |b| b.error_clear);
        if now.error_clear != clear_before {
            push(ServoChange::ErrorClear(now.error_clear));
        }
        let zero_before = before.map_or(HandshakePhase::Idle, |b| b.zero_pulse);
        if now.zero_pulse != zero_before {
            // The ack came with the last cycle's feedback, and with it the
            // zero-pulse position.
            let position = self
                .last_position
                .filter(|_| now.zero_pulse == HandshakePhase::Acknowledged)
                .and_then(|p| match p {
                    ActualPosition::Incremental {
                        zero_pulse_position,
                        ..
                    } => Some(zero_pulse_position),
                    ActualPosition::Absolute(_) => None,
                });
            push(ServoChange::ZeroPulse {
                phase: now.zero_pulse,
                position,
            });
        }
        match &now.feedback {
            Some(feedback) => {
                let errors_before = before
                    .and_then(|b| b.errors)
                    .unwrap_or(ServoErrorWord::empty());
                for fault in feedback.errors.faults() {
                    if !errors_before.contains(fault.flag()) {
                        push(ServoChange::FaultSet(fault));
                    }
                }
                for fault in errors_before.faults() {
                    if !feedback.errors.contains(fault.flag()) {
                        push(ServoChange::FaultCleared(fault));
                    }
                }
                self.faults_seen |= feedback.errors;
                let position = feedback.actual_position();
                self.first_position.get_or_insert(position);
                self.last_position = Some(position);
            }
            None => self.unconfirmed += 1,
        }
        if let Some(ready) = now.ready {
            if before.and_then(|b| b.ready) != Some(ready) {
                push(ServoChange::Ready(ready));
            }
        }
        // A cycle without feedback keeps the last feedback's as "before".
        self.last = Some(LastCycle {
            enable: now.enable,
            enable_cycles: now.enable_cycles,
            error_clear: now.error_clear,
            zero_pulse: now.zero_pulse,
            errors: now
                .feedback
                .map(|f| f.errors)
                .or_else(|| before.and_then(|b| b.errors)),
            ready: now.ready.or_else(|| before.and_then(|b| b.ready)),
        });
    }
}

impl fmt::Display for ServoChange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ServoChange::Enable { from, to, cycles } => {
                write!(f, "enable {to} (after {cycles} cycles {from})")
            }
            ServoChange::FaultSet(fault) => match fault.e_code() {
                Some(code) => write!(f, "fault {} ({code}) set", fault.name()),
                None => write!(f, "fault {} set", fault.name()),
            },
            ServoChange::FaultCleared(fault) => write!(f, "fault {} cleared", fault.name()),
            ServoChange::ErrorClear(phase) => write!(f, "error clear {phase}"),
            ServoChange::ZeroPulse { phase, position } => match position {
                Some(p) => write!(f, "zero pulse {phase} at {p}"),
                None => write!(f, "zero pulse {phase}"),
            },
            ServoChange::Ready(true) => f.write_str("ServoRDY"),
            ServoChange::Ready(false) => f.write_str("not ServoRDY"),
        }
    }
}

impl Serialize for ServoEvent {
    /// `{"packet", "ts", "event", …}`: `event` is `enable` (`from`, `to`,
    /// `cycles`), `fault_set` / `fault_cleared` (`fault`, `e_code`),
    /// `error_clear` / `zero_pulse` (`phase`; `position`), `ready`
    /// (`ready`).
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("packet", &self.packet)?;
        map.serialize_entry("ts", &self.timestamp.map(Ts))?;
        match self.change {
            ServoChange::Enable { from, to, cycles } => {
                map.serialize_entry("event", "enable")?;
                map.serialize_entry("from", from.name())?;
                map.serialize_entry("to", to.name())?;
                map.serialize_entry("cycles", &cycles)?;
            }
            ServoChange::FaultSet(fault) | ServoChange::FaultCleared(fault) => {
                let set = matches!(self.change, ServoChange::FaultSet(_));
                map.serialize_entry("event", if set { "fault_set" } else { "fault_cleared" })?;
                map.serialize_entry("fault", fault.name())?;
                map.serialize_entry("e_code", &fault.e_code().map(|c| c.to_string()))?;
            }
            ServoChange::ErrorClear(phase) => {
                map.serialize_entry("event", "error_clear")?;
                map.serialize_entry("phase", phase.name())?;
            }
            ServoChange::ZeroPulse { phase, position } => {
                map.serialize_entry("event", "zero_pulse")?;
                map.serialize_entry("phase", phase.name())?;
                map.serialize_entry("position", &position)?;
            }
            ServoChange::Ready(ready) => {
                map.serialize_entry("event", "ready")?;
                map.serialize_entry("ready", &ready)?;
            }
        }
        map.end()
    }
}

impl Serialize for ServoTimeline {
    /// `{"cycles", "unconfirmed", "events", "event_count", "faults_seen",
    /// "enable_unanswered", "enable_change_count", "fault_set_count", "faults",
    /// "error_clear_count", "zero_pulse_count", "not_ready_count",
    /// "enable", "ready", "first_position", "last_position"}` (docs/ethercat.md#servo); a position is
    /// `{"encoder", "position"}`, with `zero_pulse_position` for an
    /// incremental encoder.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("cycles", &self.cycles)?;
        map.serialize_entry("unconfirmed", &self.unconfirmed)?;
        map.serialize_entry("events", &self.events)?;
        map.serialize_entry("event_count", &self.events.count())?;
        let faults: Vec<&str> = self.faults_seen.faults().map(ServoFault::name).collect();
        map.serialize_entry("faults_seen", &faults)?;
        map.serialize_entry("enable_unanswered", &self.enable_unanswered)?;
        map.serialize_entry("enable_change_count", &self.enable_change_count)?;
        map.serialize_entry("fault_set_count", &self.fault_set_count)?;
        map.serialize_entry("faults", &self.faults)?;
        map.serialize_entry("error_clear_count", &self.error_clear_count)?;
        map.serialize_entry("zero_pulse_count", &self.zero_pulse_count)?;
        map.serialize_entry("not_ready_count", &self.not_ready_count)?;
        map.serialize_entry("enable", &self.last.map(|l| l.enable.name()))?;
        map.serialize_entry("ready", &self.last.and_then(|l| l.ready))?;
        map.serialize_entry("first_position", &self.first_position.map(Position))?;
        map.serialize_entry("last_position", &self.last_position.map(Position))?;
        map.end()
    }
}

/// An actual position as JSON: `{"encoder": "absolute", "position"}` or
/// `{"encoder": "incremental", "position", "zero_pulse_position"}`.
struct Position(ActualPosition);

impl Serialize for Position {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        match self.0 {
            ActualPosition::Absolute(position) => {
                map.serialize_entry("encoder", "absolute")?;
                map.serialize_entry("position", &position)?;
            }
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => {
                map.serialize_entry("encoder", "incremental")?;
                map.serialize_entry("position", &position)?;
                map.serialize_entry("zero_pulse_position", &zero_pulse_position)?;
            }
        }
        map.end()
    }
}

impl fmt::Display for ServoTimeline {
    /// `servo, N cycles: enable enabled (…), fault … set, …` — the first
    /// and last changes.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "          servo, {} cycles", self.cycles)?;
        if self.unconfirmed > 0 {
            write!(f, " ({} without confirmed feedback)", self.unconfirmed)?;
        }
        f.write_str(":")?;
        let mut sep = " ";
        for event in self.events.iter() {
            write!(f, "{sep}{} (packet {})", event.change, event.packet)?;
            sep = "; ";
        }
        if self.events.omitted() > 0 {
            write!(f, "; … {} more changes", self.events.omitted())?;
        }
        if self.enable_unanswered > 0 {
            write!(f, "; {} enable edges unanswered", self.enable_unanswered)?;
        }
        if let Some(position) = self.last_position {
            write!(f, "; last ActPos {position}")?;
        }
        writeln!(f)
    }
}
