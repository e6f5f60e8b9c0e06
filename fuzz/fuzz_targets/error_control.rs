//! Error control as docs/canopen.md#error-control describes it: the heartbeat
//! consumer and producer, the node-guarding master and life guarding, driven by
//! arbitrary sequences of messages, polls and configuration changes at
//! arbitrary times (forwards, backwards, up to the end of the clock).
//!
//! Input: a 10-byte header — master guard time u16 (100Ch, ms), flags u8
//! (bit 0: the master is a passive observer), life guarding's 1017h u16,
//! 100Ch u16 and 100Dh u8, the producer's 1017h u16 — then operations, an
//! opcode byte (taken modulo 19) and its payload:
//!
//! | op | what | payload |
//! |---|---|---|
//! | 0 | time passes | u16: bit 15 set → (bits 0–14) ms, else µs |
//! | 1 | the clock jumps | u8: 0xFF → near `u64::MAX`, else back by that many ms |
//! | 2 | consumer receives a heartbeat | node u8, state u8 |
//! | 3 | consumer poll, taking at most `n` events | n u8 |
//! | 4 | consumer 1016h entry | node u8, time ms u16 |
//! | 5 | consumer removes a node | node u8 |
//! | 6 | consumer monitors unconfigured nodes | time ms u16 |
//! | 7 | producer poll | state u8 |
//! | 8 | producer 1017h written | time ms u16 |
//! | 9 | producer restarted (boot-up sent) | — |
//! | 10 | guard request sent and received by the node | — |
//! | 11 | guard request sent, lost before the node | — |
//! | 12 | master poll | — |
//! | 13 | the node answers, toggling correctly | state u8 |
//! | 14 | an answer byte as received | byte |
//! | 15 | the node boots (master and life guarding told) | — |
//! | 16 | master's accepted states | bits 0–3: boot-up, stopped, operational, pre-op |
//! | 17 | life guarding poll | — |
//! | 18 | life guarding reconfigured | 1017h u16, 100Ch u16, 100Dh u8 |
//!
//! The consumer monitors nodes 1–5 with 3 entries (so that it runs out).
//!
//! Invariants, besides each machine's documented transition table (checked
//! event by event, exact fields):
//! - heartbeat consumer: no two `Timeout`s for a node without a heartbeat
//!   (or a new entry) in between; a `Timeout`'s deadline is the last
//!   heartbeat + the consumer time and has passed; a `Recovered` only after
//!   a `Timeout`; `CapacityExceeded` at most once per node; after a full
//!   poll no active node is past its deadline; at most N entries, and
//!   `set_entry` fails only when N configured entries are in use;
//! - heartbeat producer: sends exactly when due, never with bit 7, then is
//!   due again within one producer time (no burst);
//! - node-guarding master: every request is reported missing at most once
//!   and only when unanswered; a node that toggles correctly never gets a
//!   `WrongToggle`; the expected toggle follows the node's;
//! - life guarding: at most one EMCY per life-time expiry (a guard request
//!   in between), always 0x8130 with register 0x11 and pre-operational,
//!   only after the life time has passed since the last request; never when
//!   disabled.
#![no_main]

use motionwire::What;
use std::time::Duration;

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    AcceptedStates, ConsumerEntry, ErrorControlConfig, GuardAnswer, GuardingEvent,
    HeartbeatConsumer, HeartbeatEvent, HeartbeatProducer, LifeGuard, LifeGuardExpiry, MonitorState,
    NmtState, NodeGuardingMaster, NodeId,
};
use motionwire::RangeError;
use motionwire_fuzz::Reader;

/// The consumer's capacity.
const ENTRIES: usize = 3;
/// The nodes the consumer hears from: 1..=5.
const NODES: u8 = 5;
/// The node the master guards.
const GUARDED: NodeId = match NodeId::new(42) {
    Some(node) => node,
    None => panic!(),
};

fn node(raw: u8) -> NodeId {
    NodeId::new(raw % NODES + 1).expect("1..=5")
}

fn state(raw: u8) -> NmtState {
    NmtState::ALL[usize::from(raw % 4)]
}

fuzz_target!(|data: &[u8]| {
    let mut input = Reader::new(data);
    let (Some(guard_ms), Some(flags), Some(life_config), Some(producer_ms)) =
        (input.u16(), input.u8(), config(&mut input), input.u16())
    else {
        return;
    };
    let mut world = World {
        now: Duration::ZERO,
        consumer: Consumer::new(),
        producer: Producer::new(producer_ms),
        master: Master::new(guard_ms, flags & 1 != 0),
        life: Life::new(life_config),
    };
    while let Some(op) = input.u8() {
        if world.step(op % 19, &mut input).is_none() {
            break;
        }
    }
});

fn config(input: &mut Reader) -> Option<ErrorControlConfig> {
    Some(ErrorControlConfig {
        producer_heartbeat_time_ms: input.u16()?,
        guard_time_ms: input.u16()?,
        life_time_factor: input.u8()?,
    })
}

struct World {
    now: Duration,
    consumer: Consumer,
    producer: Producer,
    master: Master,
    life: Life,
}

impl World {
    fn step(&mut self, op: u8, input: &mut Reader) -> Option<()> {
        let now = self.now;
        match op {
            0 => {
                let d = input.u16()?;
                let delta = if d & 0x8000 != 0 {
                    Duration::from_millis(u64::from(d & 0x7FFF))
                } else {
                    Duration::from_micros(u64::from(d))
                };
                self.now = now.saturating_add(delta);
            }
            1 => {
                self.now = match input.u8()? {
                    0xFF => Duration::from_micros(u64::MAX - 1_000_000),
                    back => now.saturating_sub(Duration::from_millis(u64::from(back))),
                };
            }
            2 => {
                let (n, s) = (node(input.u8()?), state(input.u8()?));
                self.consumer.heartbeat(now, n, s);
            }
            3 => {
                let limit = input.u8()?;
                self.consumer.poll(now, usize::from(limit));
            }
            4 => {
                let n = node(input.u8()?);
                let time_ms = input.u16()?;
                self.consumer.set_entry(n, time_ms);
            }
            5 => {
                let n = node(input.u8()?);
                self.consumer.remove(n);
            }
            6 => {
                let time_ms = input.u16()?;
                self.consumer
                    .consumer
                    .monitor_unconfigured(Duration::from_millis(u64::from(time_ms)));
                self.consumer.unconfigured_ms = time_ms;
            }
            7 => {
                let s = state(input.u8()?);
                self.producer.poll(now, s);
            }
            8 => {
                let time_ms = input.u16()?;
                self.producer.set(time_ms);
            }
            9 => self.producer.restart(now),
            10 => {
                self.master.request(now);
                self.life.request(now);
            }
            11 => self.master.request(now),
            12 => self.master.poll(now),
            13 => {
                let s = state(input.u8()?);
                let toggle = self.master.node_toggle;
                self.master.answer(now, GuardAnswer::new(toggle, s), true);
            }
            14 => {
                let byte = input.u8()?;
                if let Ok(answer) = GuardAnswer::parse(&[byte]) {
                    let honest = answer.toggle == self.master.node_toggle;
                    self.master.answer(now, answer, honest);
                }
            }
            15 => {
                self.master.boot_up();
                self.life.reset();
            }
            16 => {
                let bits = input.u8()?;
                let accepted = NmtState::ALL
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| bits & (1 << i) != 0)
                    .fold(AcceptedStates::NONE, |set, (_, &s)| set.with(s));
                self.master.set_accepted(accepted);
            }
            17 => self.life.poll(now),
            _ => {
                let config = config(input)?;
                self.life.reconfigure(config);
            }
        }
        Some(())
    }
}

// ---------------------------------------------------------------------------
// Heartbeat consumer

struct Consumer {
    consumer: HeartbeatConsumer<ENTRIES>,
    /// Nodes with a configured 1016h entry (index = node-ID).
    configured: [bool; 128],
    unconfigured_ms: u16,
    /// A Timeout was reported and no heartbeat came since.
    timed_out: [bool; 128],
    capacity_reported: [bool; 128],
}

impl Consumer {
    fn new() -> Self {
        Consumer {
            consumer: HeartbeatConsumer::with_capacity(),
            configured: [false; 128],
            unconfigured_ms: 0,
            timed_out: [false; 128],
            capacity_reported: [false; 128],
        }
    }

    fn nodes() -> impl Iterator<Item = NodeId> {
        (0..NODES).map(node)
    }

    fn entries(&self) -> usize {
        Self::nodes()
            .filter(|&n| self.consumer.monitor_state(n).is_some())
            .count()
    }

    /// Record a Timeout: never two without a heartbeat in between.
    fn timeout(&mut self, event: HeartbeatEvent, now: Duration) {
        let HeartbeatEvent::Timeout {
            node,
            last_heartbeat,
            deadline,
        } = event
        else {
            panic!("not a timeout: {event:?}");
        };
        let i = node.index();
        assert!(
            !self.timed_out[i],
            "second Timeout for {node} without a heartbeat"
        );
        self.timed_out[i] = true;
        let time = self
            .consumer
            .consumer_time(node)
            .expect("a timed-out node has an entry");
        assert_eq!(deadline, last_heartbeat.saturating_add(time));
        assert!(
            now > deadline,
            "Timeout at {now:?} before its deadline {deadline:?}"
        );
        assert_eq!(event.gap(), Some(deadline - last_heartbeat));
    }

    fn heartbeat(&mut self, now: Duration, node: NodeId, state: NmtState) {
        let i = node.index();
        let before = self.consumer.monitor_state(node);
        let time = self.consumer.consumer_time(node);
        let entries = self.entries();
        let events: Vec<HeartbeatEvent> = self.consumer.on_heartbeat(now, node, state).collect();
        assert!(events.len() <= 2);
        let after = self.consumer.monitor_state(node);
        let active = MonitorState::Active {
            last_heartbeat: now,
            state,
        };
        let heard = if state == NmtState::BootUp {
            MonitorState::Waiting
        } else {
            active
        };

        let expected: Vec<HeartbeatEvent> = match before {
            None if self.unconfigured_ms == 0 => {
                assert_eq!(after, None, "a node without an entry was taken up");
                vec![]
            }
            None if entries < ENTRIES => {
                assert_eq!(after, Some(heard), "an unconfigured node was not taken up");
                assert_eq!(
                    self.consumer.consumer_time(node),
                    Some(Duration::from_millis(u64::from(self.unconfigured_ms)))
                );
                vec![]
            }
            None => {
                assert_eq!(after, None);
                if std::mem::replace(&mut self.capacity_reported[i], true) {
                    vec![]
                } else {
                    vec![HeartbeatEvent::CapacityExceeded { node, at: now }]
                }
            }
            Some(MonitorState::Waiting) => {
                assert_eq!(after, Some(heard));
                vec![]
            }
            Some(MonitorState::Active { last_heartbeat, .. }) => {
                let deadline = last_heartbeat.saturating_add(time.expect("entry"));
                let mut expected = vec![];
                if now > deadline {
                    expected.push(HeartbeatEvent::Timeout {
                        node,
                        last_heartbeat,
                        deadline,
                    });
                }
                if state == NmtState::BootUp {
                    expected.push(HeartbeatEvent::RemoteReset {
                        node,
                        last_heartbeat,
                        at: now,
                    });
                } else if now > deadline {
                    expected.push(HeartbeatEvent::Recovered {
                        node,
                        last_heartbeat,
                        at: now,
                        state,
                    });
                }
                assert_eq!(after, Some(heard));
                expected
            }
            Some(MonitorState::TimedOut { last_heartbeat }) => {
                assert!(self.timed_out[i], "TimedOut without a reported Timeout");
                assert_eq!(after, Some(heard));
                if state == NmtState::BootUp {
                    vec![HeartbeatEvent::RemoteReset {
                        node,
                        last_heartbeat,
                        at: now,
                    }]
                } else {
                    vec![HeartbeatEvent::Recovered {
                        node,
                        last_heartbeat,
                        at: now,
                        state,
                    }]
                }
            }
        };
        assert_eq!(
            events, expected,
            "{node} {state} at {now:?} from {before:?}"
        );

        for event in &events {
            assert_eq!(event.node(), node);
            let _ = (event.to_string(), event.name(), event.at());
            match event {
                HeartbeatEvent::Timeout { .. } => self.timeout(*event, now),
                HeartbeatEvent::Recovered { .. } => {
                    assert!(self.timed_out[i], "Recovered without a Timeout")
                }
                _ => {}
            }
        }
        if after.is_some() {
            self.timed_out[i] = false;
        }
    }

    fn poll(&mut self, now: Duration, limit: usize) {
        let due: Vec<NodeId> = Self::nodes()
            .filter(|&n| match self.consumer.monitor_state(n) {
                Some(MonitorState::Active { last_heartbeat, .. }) => {
                    now > last_heartbeat.saturating_add(self.consumer.consumer_time(n).unwrap())
                }
                _ => false,
            })
            .collect();
        let events: Vec<HeartbeatEvent> = self.consumer.poll(now).take(limit).collect();
        assert_eq!(events.len(), due.len().min(limit));
        for event in events {
            let node = event.node();
            assert!(due.contains(&node), "Timeout for {node}, which was not due");
            let Some(MonitorState::TimedOut { last_heartbeat }) = self.consumer.monitor_state(node)
            else {
                panic!("{node} not timed out after its Timeout");
            };
            assert_eq!(event.last_heartbeat(), Some(last_heartbeat));
            self.timeout(event, now);
        }
        if limit >= due.len() {
            // Nothing active is past its deadline after a full poll.
            if let Some(deadline) = self.consumer.next_deadline() {
                assert!(
                    deadline >= now,
                    "deadline {deadline:?} passed at {now:?} after a poll"
                );
            }
            assert_eq!(self.consumer.poll(now).count(), 0);
        }
    }

    fn set_entry(&mut self, node: NodeId, time_ms: u16) {
        let i = node.index();
        let configured = self.configured.iter().filter(|&&c| c).count();
        let result = self
            .consumer
            .set_entry(ConsumerEntry::from_millis(node, time_ms));
        if time_ms == 0 {
            assert_eq!(result, Ok(()));
            assert_eq!(self.consumer.monitor_state(node), None);
            self.configured[i] = false;
        } else if !self.configured[i] && configured == ENTRIES {
            assert_eq!(
                result,
                Err(RangeError {
                    what: What::HeartbeatConsumerEntries,
                    found: ENTRIES as u32 + 1,
                    min: 0,
                    max: ENTRIES as u32,
                })
            );
            return;
        } else {
            assert_eq!(result, Ok(()), "{configured} configured entries");
            assert_eq!(
                self.consumer.monitor_state(node),
                Some(MonitorState::Waiting)
            );
            assert_eq!(
                self.consumer.consumer_time(node),
                Some(Duration::from_millis(u64::from(time_ms)))
            );
            self.configured[i] = true;
        }
        self.timed_out[i] = false;
        assert!(self.entries() <= ENTRIES);
        // A configured node is never pushed out by another.
        for n in Self::nodes() {
            if self.configured[n.index()] {
                assert!(
                    self.consumer.monitor_state(n).is_some(),
                    "{n} lost its entry"
                );
            }
        }
    }

    fn remove(&mut self, node: NodeId) {
        let had = self.consumer.monitor_state(node).is_some();
        assert_eq!(self.consumer.remove(node), had);
        assert_eq!(self.consumer.monitor_state(node), None);
        self.configured[node.index()] = false;
        self.timed_out[node.index()] = false;
    }
}

// ---------------------------------------------------------------------------
// Heartbeat producer

struct Producer {
    producer: HeartbeatProducer,
}

impl Producer {
    fn new(time_ms: u16) -> Self {
        let producer = HeartbeatProducer::from_millis(time_ms);
        assert_eq!(producer.is_enabled(), time_ms != 0);
        assert_eq!(
            producer.next_due(),
            (time_ms != 0).then_some(Duration::ZERO)
        );
        Producer { producer }
    }

    fn set(&mut self, time_ms: u16) {
        self.producer.set_producer_time(time_ms);
        assert_eq!(
            self.producer.producer_time(),
            Duration::from_millis(u64::from(time_ms))
        );
        assert_eq!(
            self.producer.next_due(),
            (time_ms != 0).then_some(Duration::ZERO)
        );
    }

    fn restart(&mut self, now: Duration) {
        self.producer.restart(now);
        let period = self.producer.producer_time();
        assert_eq!(
            self.producer.next_due(),
            (!period.is_zero()).then(|| now.saturating_add(period))
        );
    }

    fn poll(&mut self, now: Duration, state: NmtState) {
        let due = self.producer.next_due();
        let period = self.producer.producer_time();
        let sent = self.producer.poll(now, state);
        assert_eq!(
            sent.is_some(),
            due.is_some_and(|due| now >= due),
            "due {due:?} at {now:?}"
        );
        match sent {
            Some(heartbeat) => {
                assert_eq!(heartbeat.state(), state);
                assert!(!heartbeat.reserved_bit());
                assert_eq!(heartbeat.to_bytes(), [state.to_byte()]);
                let next = self.producer.next_due().expect("enabled");
                // Due again after now, within one producer time: no burst.
                assert!(
                    next > now || next == Duration::MAX,
                    "next {next:?} at {now:?}"
                );
                assert!(next - now <= period);
            }
            None => assert_eq!(self.producer.next_due(), due),
        }
    }
}

// ---------------------------------------------------------------------------
// Node-guarding master

struct Master {
    master: NodeGuardingMaster,
    guard_time: Duration,
    accepted: AcceptedStates,
    /// The model's expected toggle; `None` for an observer before its first
    /// answer.
    expected: Option<bool>,
    /// The toggle the node sends next.
    node_toggle: bool,
    outstanding: Option<Duration>,
    last_request: Option<Duration>,
}

impl Master {
    fn new(guard_ms: u16, observer: bool) -> Self {
        let master = if observer {
            NodeGuardingMaster::observer(GUARDED, Duration::from_millis(u64::from(guard_ms)))
        } else {
            NodeGuardingMaster::from_millis(GUARDED, guard_ms)
        };
        assert_eq!(master.node(), GUARDED);
        assert_eq!(
            master.guard_time(),
            Duration::from_millis(u64::from(guard_ms))
        );
        Master {
            master,
            guard_time: Duration::from_millis(u64::from(guard_ms)),
            accepted: AcceptedStates::GUARDED,
            expected: (!observer).then_some(false),
            node_toggle: false,
            outstanding: None,
            last_request: None,
        }
    }

    fn check(&self, now: Duration) {
        let master = &self.master;
        assert_eq!(master.expected_toggle(), self.expected);
        if let Some(expected) = self.expected {
            // The expectation follows the node's toggle.
            assert_eq!(expected, self.node_toggle);
        }
        assert_eq!(master.outstanding_request(), self.outstanding);
        let next = (!self.guard_time.is_zero()).then(|| {
            self.last_request
                .map_or(Duration::ZERO, |last| last.saturating_add(self.guard_time))
        });
        assert_eq!(master.next_request_at(), next);
        assert_eq!(master.request_due(now), next.is_some_and(|due| now >= due));
    }

    /// The event `poll(now)` must give, updating the model.
    fn expected_poll(&mut self, now: Duration) -> Option<GuardingEvent> {
        let request_at = self.outstanding?;
        if self.guard_time.is_zero() {
            return None;
        }
        let due_by = request_at.saturating_add(self.guard_time);
        (now > due_by).then(|| {
            self.outstanding = None;
            GuardingEvent::MissingAnswer {
                node: GUARDED,
                request_at,
                due_by,
            }
        })
    }

    fn request(&mut self, now: Duration) {
        let event = self.master.on_request(now);
        // An unanswered request is reported missing at most once: here, if
        // no poll or answer gave it up.
        let expected = self
            .outstanding
            .map(|request_at| GuardingEvent::MissingAnswer {
                node: GUARDED,
                request_at,
                due_by: if self.guard_time.is_zero() {
                    now
                } else {
                    now.min(request_at.saturating_add(self.guard_time))
                },
            });
        assert_eq!(event, expected);
        self.outstanding = Some(now);
        self.last_request = Some(now);
        self.check(now);
    }

    fn poll(&mut self, now: Duration) {
        let event = self.master.poll(now);
        assert_eq!(event, self.expected_poll(now));
        if let Some(event) = event {
            assert!(event.at() < now);
            let _ = (event.to_string(), event.name());
        }
        self.check(now);
    }

    fn answer(&mut self, now: Duration, answer: GuardAnswer, honest: bool) {
        let events: Vec<GuardingEvent> = self.master.on_answer(now, answer).collect();
        assert!(events.len() <= 3);
        let mut expected: Vec<GuardingEvent> = self.expected_poll(now).into_iter().collect();
        let request_at = self.outstanding.take();
        if let Some(toggle) = self.expected {
            if answer.toggle != toggle {
                expected.push(GuardingEvent::WrongToggle {
                    node: GUARDED,
                    at: now,
                    request_at,
                    expected: toggle,
                    found: answer.toggle,
                });
            }
        }
        if !self.accepted.contains(answer.state) {
            expected.push(GuardingEvent::UnexpectedState {
                node: GUARDED,
                at: now,
                request_at,
                state: answer.state,
            });
        }
        assert_eq!(events, expected, "answer {answer:?} at {now:?}");
        if honest && self.expected.is_some() {
            assert!(
                !events
                    .iter()
                    .any(|e| matches!(e, GuardingEvent::WrongToggle { .. })),
                "WrongToggle for a node that toggles correctly"
            );
        }
        for event in &events {
            let _ = (event.to_string(), event.name(), event.at());
        }
        // The node toggles with every answer it sends.
        self.node_toggle = !answer.toggle;
        self.expected = Some(!answer.toggle);
        self.check(now);
    }

    fn boot_up(&mut self) {
        self.master.on_boot_up();
        self.node_toggle = false;
        self.expected = Some(false);
        assert_eq!(self.master.expected_toggle(), Some(false));
    }

    fn set_accepted(&mut self, accepted: AcceptedStates) {
        self.master.set_accepted_states(accepted);
        self.accepted = accepted;
    }
}

// ---------------------------------------------------------------------------
// Life guarding

#[derive(Clone, Copy, PartialEq, Debug)]
enum Timer {
    Idle,
    Running(Duration),
    Expired(Duration),
}

struct Life {
    life: LifeGuard,
    life_time: Option<Duration>,
    timer: Timer,
}

impl Life {
    fn new(config: ErrorControlConfig) -> Self {
        let life = LifeGuard::new(config);
        let life_time = (config.producer_heartbeat_time_ms == 0
            && config.guard_time_ms != 0
            && config.life_time_factor != 0)
            .then(|| {
                Duration::from_millis(
                    u64::from(config.guard_time_ms) * u64::from(config.life_time_factor),
                )
            });
        assert_eq!(life.node_life_time(), life_time);
        Life {
            life,
            life_time,
            timer: Timer::Idle,
        }
    }

    fn reconfigure(&mut self, config: ErrorControlConfig) {
        self.life.reconfigure(config);
        *self = Life {
            life: self.life,
            ..Life::new(config)
        };
        self.check();
    }

    fn reset(&mut self) {
        self.life.reset();
        self.timer = Timer::Idle;
        self.check();
    }

    fn check(&self) {
        let deadline = match (self.life_time, self.timer) {
            (Some(life_time), Timer::Running(last)) => Some(last.saturating_add(life_time)),
            _ => None,
        };
        assert_eq!(self.life.deadline(), deadline);
        assert_eq!(
            self.life.is_expired(),
            matches!(self.timer, Timer::Expired(_))
        );
        assert_eq!(self.life.node_life_time(), self.life_time);
    }

    /// The expiry `poll(now)` must give, updating the model.
    fn expected_poll(&mut self, now: Duration) -> Option<LifeGuardExpiry> {
        let (Some(life_time), Timer::Running(last_request)) = (self.life_time, self.timer) else {
            return None;
        };
        let deadline = last_request.saturating_add(life_time);
        (now > deadline).then(|| {
            self.timer = Timer::Expired(last_request);
            LifeGuardExpiry {
                last_request,
                deadline,
                emcy: LifeGuard::EMCY,
                new_state: NmtState::PreOperational,
            }
        })
    }

    fn check_expiry(&self, expiry: Option<LifeGuardExpiry>, now: Duration) {
        if let Some(expiry) = expiry {
            // At most one EMCY per expiry: the timer was running, so a guard
            // request came since the last one.
            assert_eq!(expiry.emcy.to_bytes(), [0x30, 0x81, 0x11, 0, 0, 0, 0, 0]);
            assert_eq!(expiry.new_state, NmtState::PreOperational);
            assert!(now > expiry.deadline);
            assert!(
                self.life_time.is_some(),
                "expiry while life guarding is disabled"
            );
        }
    }

    fn request(&mut self, now: Duration) {
        let expiry = self.life.on_request(now);
        let expected = self.expected_poll(now);
        assert_eq!(expiry, expected);
        self.check_expiry(expiry, now);
        if self.life_time.is_some() {
            self.timer = Timer::Running(now);
        }
        self.check();
    }

    fn poll(&mut self, now: Duration) {
        let was_expired = self.life.is_expired();
        let expiry = self.life.poll(now);
        assert_eq!(expiry, self.expected_poll(now));
        if was_expired {
            assert_eq!(expiry, None, "a second EMCY for the same expiry");
        }
        self.check_expiry(expiry, now);
        self.check();
    }
}
