//! Node guarding and life guarding as pure state machines
//! (CiA 301 §7.2.8.3.2.1; docs/canopen.md#error-control).
//!
//! - [`NodeGuardingMaster`] is the master's side for one node: when to send
//!   the next guard request (a remote frame on 0x700 + node-ID) and what the
//!   answers mean: a wrong toggle, an unexpected state, a missing answer. It
//!   also observes a log passively ([`NodeGuardingMaster::observer`]).
//! - [`LifeGuard`] is the node's side: node life time = guard time × life
//!   time factor; no guard request within it → EMCY 0x8130 and
//!   pre-operational.
//!
//! Time is a [`Duration`] since the caller's epoch on its monotonic clock,
//! passed with every call; objects 100Ch and 100Dh are milliseconds and a
//! factor, and the constructors that take them say so (`from_millis`).
//!
//! ```
//! use core::time::Duration;
//! use motionwire_codec::canopen::{GuardAnswer, GuardingEvent, NmtState, NodeGuardingMaster, NodeId};
//!
//! let ms = Duration::from_millis;
//! let node = NodeId::new(5).unwrap();
//! let mut master = NodeGuardingMaster::from_millis(node, 100); // 100Ch = 100 ms
//!
//! assert!(master.request_due(Duration::ZERO));
//! assert_eq!(master.on_request(Duration::ZERO), None); // the RTR frame is sent at 0
//! // The first answer after start carries toggle 0.
//! let answer = GuardAnswer::parse(&[0x05])?;
//! assert!(master.on_answer(ms(2), answer).is_empty());
//! assert_eq!(master.expected_toggle(), Some(true));
//! assert_eq!(master.next_request_at(), Some(ms(100)));
//!
//! // The second answer repeats toggle 0: a guarding error.
//! assert_eq!(master.on_request(ms(100)), None);
//! let events: Vec<_> = master.on_answer(ms(101), answer).collect();
//! assert!(matches!(events[..], [GuardingEvent::WrongToggle { expected: true, found: false, .. }]));
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use core::fmt;
use core::time::Duration;

use super::error_control::{millis, ErrorControlConfig, Events};
use super::{Emcy, ErrorCode, ErrorRegister, GuardAnswer, NmtState, NodeId};

/// The set of NMT states a guarding master accepts in an answer
/// (CiA 301 §7.2.8.3.2.1: "the state … does not correspond to the one
/// expected").
///
/// ```
/// use motionwire_codec::canopen::{AcceptedStates, NmtState};
///
/// let accepted = AcceptedStates::only(NmtState::Operational).with(NmtState::PreOperational);
/// assert!(accepted.contains(NmtState::PreOperational));
/// assert!(!accepted.contains(NmtState::Stopped));
/// assert!(AcceptedStates::GUARDED.contains(NmtState::Stopped));
/// assert!(!AcceptedStates::GUARDED.contains(NmtState::BootUp));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AcceptedStates(u8);

impl AcceptedStates {
    /// No state: every answer is unexpected.
    pub const NONE: AcceptedStates = AcceptedStates(0);
    /// Every state a guarded node can answer with: stopped, operational,
    /// pre-operational (the boot-up state 0x00 is no guarding answer).
    pub const GUARDED: AcceptedStates = AcceptedStates::NONE
        .with(NmtState::Stopped)
        .with(NmtState::Operational)
        .with(NmtState::PreOperational);

    const fn bit(state: NmtState) -> u8 {
        match state {
            NmtState::BootUp => 1 << 0,
            NmtState::Stopped => 1 << 1,
            NmtState::Operational => 1 << 2,
            NmtState::PreOperational => 1 << 3,
        }
    }

    /// Return the set holding only `state`: the state the master commanded.
    #[inline]
    #[must_use]
    pub const fn only(state: NmtState) -> Self {
        AcceptedStates(Self::bit(state))
    }

    /// Return this set with `state` added.
    #[inline]
    #[must_use]
    pub const fn with(self, state: NmtState) -> Self {
        AcceptedStates(self.0 | Self::bit(state))
    }

    /// Return whether `state` is accepted.
    #[inline]
    #[must_use]
    pub const fn contains(self, state: NmtState) -> bool {
        self.0 & Self::bit(state) != 0
    }
}

impl Default for AcceptedStates {
    /// [`AcceptedStates::GUARDED`].
    fn default() -> Self {
        AcceptedStates::GUARDED
    }
}

/// A guarding error the master sees (CiA 301 §7.2.8.3.2.1;
/// docs/canopen.md#error-control).
///
/// Every time is on the caller's clock (a `Duration` since its epoch).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum GuardingEvent {
    /// The answer's toggle bit is not the one expected (the node missed a
    /// request, an answer was lost, or the node was reset unseen).
    WrongToggle {
        /// The guarded node.
        node: NodeId,
        /// When the answer came.
        at: Duration,
        /// The request it answers, if one was outstanding.
        request_at: Option<Duration>,
        /// The toggle expected.
        expected: bool,
        /// The toggle received.
        found: bool,
    },
    /// The answer reports a state the master does not accept.
    UnexpectedState {
        /// The guarded node.
        node: NodeId,
        /// When the answer came.
        at: Duration,
        /// The request it answers, if one was outstanding.
        request_at: Option<Duration>,
        /// The state reported.
        state: NmtState,
    },
    /// No answer to the request at `request_at` came by `due_by`.
    MissingAnswer {
        /// The guarded node.
        node: NodeId,
        /// When the unanswered request was sent.
        request_at: Duration,
        /// When the answer was due: the request + guard time, or the
        /// next request when that came first (or the guard time is unknown).
        due_by: Duration,
    },
}

impl GuardingEvent {
    /// Return the node the event is about.
    #[inline]
    #[must_use]
    pub const fn node(&self) -> NodeId {
        match *self {
            GuardingEvent::WrongToggle { node, .. }
            | GuardingEvent::UnexpectedState { node, .. }
            | GuardingEvent::MissingAnswer { node, .. } => node,
        }
    }

    /// Return when the event happened: the answer's arrival, or the
    /// instant a missing answer was due.
    #[inline]
    #[must_use]
    pub const fn at(&self) -> Duration {
        match *self {
            GuardingEvent::WrongToggle { at, .. } | GuardingEvent::UnexpectedState { at, .. } => at,
            GuardingEvent::MissingAnswer { due_by, .. } => due_by,
        }
    }

    /// Return the event's name: `wrong_toggle`, `unexpected_state` or
    /// `missing_answer`.
    #[inline]
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            GuardingEvent::WrongToggle { .. } => "wrong_toggle",
            GuardingEvent::UnexpectedState { .. } => "unexpected_state",
            GuardingEvent::MissingAnswer { .. } => "missing_answer",
        }
    }
}

impl fmt::Display for GuardingEvent {
    /// Format the event as e.g. `node 5: missing answer to the request at 0 µs`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let node = self.node();
        match *self {
            GuardingEvent::WrongToggle {
                at,
                expected,
                found,
                ..
            } => write!(
                f,
                "node {node}: toggle {} where {} was expected at {} µs",
                u8::from(found),
                u8::from(expected),
                at.as_micros()
            ),
            GuardingEvent::UnexpectedState { at, state, .. } => {
                write!(
                    f,
                    "node {node}: unexpected state {state} at {} µs",
                    at.as_micros()
                )
            }
            GuardingEvent::MissingAnswer {
                request_at, due_by, ..
            } => write!(
                f,
                "node {node}: missing answer to the request at {} µs (due by {} µs)",
                request_at.as_micros(),
                due_by.as_micros()
            ),
        }
    }
}

/// The events one answer produced: at most three (a missing answer whose
/// deadline passed without a poll, a wrong toggle, an unexpected state).
pub type GuardingEvents = Events<GuardingEvent, 3>;

/// The node-guarding master's view of one node (CiA 301 §7.2.8.3.2.1;
/// docs/canopen.md#error-control).
///
/// | input at `now` | effect | event |
/// |---|---|---|
/// | [`on_request`](Self::on_request) | the request is outstanding; the next is due one guard time later | [`MissingAnswer`](GuardingEvent::MissingAnswer) when the previous one is still unanswered |
/// | [`poll`](Self::poll), `now` > request + guard time | the request is given up | `MissingAnswer`, once |
/// | [`on_answer`](Self::on_answer), toggle ≠ expected | expect the inverse of the toggle received | [`WrongToggle`](GuardingEvent::WrongToggle) |
/// | `on_answer`, state not accepted | — | [`UnexpectedState`](GuardingEvent::UnexpectedState) |
/// | `on_answer`, toggle = expected or not yet known | expect the inverse of the toggle received | — |
/// | [`on_boot_up`](Self::on_boot_up) | expect toggle 0 | — |
///
/// **Decision:** after a wrong toggle the master expects the inverse of the
/// toggle it received, not of the one it expected: the node toggles with
/// every answer it sends, so one lost answer is one error, not an error in
/// every answer that follows. After a missing answer the expectation is kept
/// (the node did not answer, so it did not toggle, as far as the master
/// knows).
///
/// A guard time of 0 means no request schedule and no timeout: answers are
/// still checked, and a request that follows an unanswered one still reports
/// the missing answer (useful when observing a log whose 100Ch is unknown).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NodeGuardingMaster {
    node: NodeId,
    guard_time: Duration,
    accepted: AcceptedStates,
    /// `None`: not known yet (observer before its first answer).
    expected_toggle: Option<bool>,
    last_request: Option<Duration>,
    /// The request still waiting for its answer.
    outstanding: Option<Duration>,
}

impl NodeGuardingMaster {
    /// Return the master guarding `node` every `guard_time` (zero = no
    /// schedule), expecting toggle 0 in the first answer (the node has just
    /// started) and accepting [`AcceptedStates::GUARDED`].
    #[inline]
    #[must_use]
    pub const fn new(node: NodeId, guard_time: Duration) -> Self {
        NodeGuardingMaster {
            node,
            guard_time,
            accepted: AcceptedStates::GUARDED,
            expected_toggle: Some(false),
            last_request: None,
            outstanding: None,
        }
    }

    /// Return the master guarding `node` with the guard time of object
    /// 100Ch, `guard_time_ms` milliseconds (0 = no schedule); otherwise as
    /// [`NodeGuardingMaster::new`].
    #[inline]
    #[must_use]
    pub const fn from_millis(node: NodeId, guard_time_ms: u16) -> Self {
        Self::new(node, millis(guard_time_ms as u32))
    }

    /// Return a passive observer of `node`'s guarding in a log: like
    /// [`NodeGuardingMaster::new`], but the expected toggle is not known
    /// until the first answer, which sets the baseline (for a log that does
    /// not show the node's boot-up).
    #[inline]
    #[must_use]
    pub const fn observer(node: NodeId, guard_time: Duration) -> Self {
        let mut master = Self::new(node, guard_time);
        master.expected_toggle = None;
        master
    }

    /// Return this master accepting `accepted` states in answers.
    #[inline]
    #[must_use]
    pub const fn with_accepted_states(mut self, accepted: AcceptedStates) -> Self {
        self.accepted = accepted;
        self
    }

    /// Tell the master which states it accepts from now on, e.g. after
    /// commanding the node into operational.
    #[inline]
    pub fn set_accepted_states(&mut self, accepted: AcceptedStates) {
        self.accepted = accepted;
    }

    /// Return the guarded node.
    #[inline]
    #[must_use]
    pub const fn node(&self) -> NodeId {
        self.node
    }

    /// Return the guard time; 0 when there is no schedule.
    #[inline]
    #[must_use]
    pub const fn guard_time(&self) -> Duration {
        self.guard_time
    }

    /// Return the toggle the next answer must carry, `None` while an
    /// observer has no baseline.
    #[inline]
    #[must_use]
    pub const fn expected_toggle(&self) -> Option<bool> {
        self.expected_toggle
    }

    /// Return when the outstanding request was sent, if it has not been
    /// answered or given up.
    #[inline]
    #[must_use]
    pub const fn outstanding_request(&self) -> Option<Duration> {
        self.outstanding
    }

    /// Return when the next guard request is due: one guard time after
    /// the last, 0 (at once) before the first; `None` with guard time 0.
    #[inline]
    #[must_use]
    pub const fn next_request_at(&self) -> Option<Duration> {
        if self.guard_time.is_zero() {
            return None;
        }
        match self.last_request {
            Some(last) => Some(last.saturating_add(self.guard_time)),
            None => Some(Duration::ZERO),
        }
    }

    /// Return whether a guard request is due at `now`.
    #[inline]
    #[must_use]
    pub fn request_due(&self, now: Duration) -> bool {
        self.next_request_at().is_some_and(|due| now >= due)
    }

    /// The node sent its boot-up message (or was reset): the next answer
    /// carries toggle 0 (CiA 301 §7.2.8.3.2.1).
    #[inline]
    pub fn on_boot_up(&mut self) {
        self.expected_toggle = Some(false);
    }

    /// A guard request was sent (or seen in a log) at `now`. Returns a
    /// [`GuardingEvent::MissingAnswer`] when the previous request is still
    /// unanswered.
    #[must_use = "the event is reported only once"]
    pub fn on_request(&mut self, now: Duration) -> Option<GuardingEvent> {
        let missing = self.outstanding.map(|request_at| {
            let due_by = if self.guard_time.is_zero() {
                now
            } else {
                now.min(request_at.saturating_add(self.guard_time))
            };
            GuardingEvent::MissingAnswer {
                node: self.node,
                request_at,
                due_by,
            }
        });
        self.outstanding = Some(now);
        self.last_request = Some(now);
        missing
    }

    /// At `now`, give up the outstanding request when its guard time
    /// has passed, returning the [`GuardingEvent::MissingAnswer`] once.
    #[must_use = "the event is reported only once"]
    pub fn poll(&mut self, now: Duration) -> Option<GuardingEvent> {
        let request_at = self.outstanding?;
        if self.guard_time.is_zero() {
            return None;
        }
        let due_by = request_at.saturating_add(self.guard_time);
        if now > due_by {
            self.outstanding = None;
            Some(GuardingEvent::MissingAnswer {
                node: self.node,
                request_at,
                due_by,
            })
        } else {
            None
        }
    }

    /// An answer came at `now`: check its toggle and state. An answer
    /// after the guard time of its request first reports the missing answer
    /// (when no poll did), then is checked like any other.
    pub fn on_answer(&mut self, now: Duration, answer: GuardAnswer) -> GuardingEvents {
        let mut events = GuardingEvents::new();
        events.push_some(self.poll(now));
        let request_at = self.outstanding.take();
        if let Some(expected) = self.expected_toggle {
            if answer.toggle != expected {
                events.push(GuardingEvent::WrongToggle {
                    node: self.node,
                    at: now,
                    request_at,
                    expected,
                    found: answer.toggle,
                });
            }
        }
        self.expected_toggle = Some(!answer.toggle);
        if !self.accepted.contains(answer.state) {
            events.push(GuardingEvent::UnexpectedState {
                node: self.node,
                at: now,
                request_at,
                state: answer.state,
            });
        }
        events
    }
}

/// What a node does when its life time expires without a guard request
/// (CiA 301 §7.2.8.3.2.1; docs/canopen.md#error-control): it sends an EMCY
/// and returns to pre-operational.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LifeGuardExpiry {
    /// The last guard request before the silence.
    pub last_request: Duration,
    /// `last_request` + node life time: the instant the life time expired,
    ///.
    pub deadline: Duration,
    /// The EMCY to send: [`LifeGuard::EMCY`].
    pub emcy: Emcy,
    /// The NMT state to switch to: pre-operational.
    pub new_state: NmtState,
}

impl fmt::Display for LifeGuardExpiry {
    /// Format the expiry as what the node does, times in µs on the caller's
    /// clock as [`GuardingEvent`] writes them: `life time expired at 1500000
    /// µs after the guard request at 1000000 µs: send EMCY 0x8130 …, go
    /// pre_operational` (the [`Emcy`] as it writes itself).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "life time expired at {} µs after the guard request at {} µs: send {}, go {}",
            self.deadline.as_micros(),
            self.last_request.as_micros(),
            self.emcy,
            self.new_state
        )
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum LifeTimer {
    /// No guard request yet: life guarding has not started.
    Idle,
    /// Running since the guard request at the given time.
    Running(Duration),
    /// Expired after the guard request at the given time; reported.
    Expired(Duration),
}

/// Life guarding on the node: the node monitors its guarding master
/// (CiA 301 §7.2.8.3.2.1; docs/canopen.md#error-control).
///
/// Node life time = guard time (100Ch, ms) × life time factor (100Dh); 0 in
/// either, or a non-zero producer heartbeat time (heartbeat wins), disables
/// it ([`ErrorControlConfig::node_life_time`]). The timer starts at the first
/// guard request and restarts at each; when it runs out, the node sends
/// [`LifeGuard::EMCY`] and switches to pre-operational, reported once per
/// expiry as a [`LifeGuardExpiry`]. The next guard request starts the timer
/// again.
///
/// ```
/// use core::time::Duration;
/// use motionwire_codec::canopen::{ErrorControlConfig, LifeGuard, NmtState};
///
/// let us = Duration::from_micros;
/// let mut life = LifeGuard::new(ErrorControlConfig {
///     producer_heartbeat_time_ms: 0,
///     guard_time_ms: 100,
///     life_time_factor: 3,
/// });
/// assert_eq!(life.on_request(Duration::ZERO), None); // starts the 300 ms timer
/// assert_eq!(life.poll(us(300_000)), None);
/// let expiry = life.poll(us(300_001)).unwrap();
/// assert_eq!(expiry.emcy.to_bytes(), [0x30, 0x81, 0x11, 0, 0, 0, 0, 0]);
/// assert_eq!(expiry.new_state, NmtState::PreOperational);
/// assert_eq!(life.poll(us(900_000)), None); // once per expiry
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LifeGuard {
    /// The node life time; `None` = disabled.
    life_time: Option<Duration>,
    timer: LifeTimer,
}

impl LifeGuard {
    /// The EMCY a node sends when its life time expires: code 0x8130 (life
    /// guard error or heartbeat error), register generic + communication
    /// (0x11), manufacturer field zero (CiA 301 Table 26;
    /// docs/canopen.md#emcy-codes, docs/canopen.md#error-control).
    ///
    /// A device with other active errors ORs their class bits into the
    /// register (docs/canopen.md#emcy-producer).
    pub const EMCY: Emcy = Emcy::new(
        ErrorCode::LIFE_GUARD,
        ErrorRegister::GENERIC.union(ErrorRegister::COMMUNICATION),
        [0; 5],
    );

    /// Return life guarding for a node configured with `config`; inert when
    /// its node life time is `None`.
    #[inline]
    #[must_use]
    pub const fn new(config: ErrorControlConfig) -> Self {
        LifeGuard {
            life_time: config.node_life_time(),
            timer: LifeTimer::Idle,
        }
    }

    /// Apply a new configuration (100Ch, 100Dh or 1017h written): the timer
    /// starts again at the next guard request.
    #[inline]
    pub fn reconfigure(&mut self, config: ErrorControlConfig) {
        *self = Self::new(config);
    }

    /// The node was reset (NMT reset node or reset communication): life
    /// guarding waits for the first guard request again.
    #[inline]
    pub fn reset(&mut self) {
        self.timer = LifeTimer::Idle;
    }

    /// Return the node life time, `None` when life guarding is
    /// disabled.
    #[inline]
    #[must_use]
    pub const fn node_life_time(&self) -> Option<Duration> {
        self.life_time
    }

    /// Return when the life time runs out, if the timer is running.
    #[inline]
    #[must_use]
    pub const fn deadline(&self) -> Option<Duration> {
        match (self.life_time, self.timer) {
            (Some(life_time), LifeTimer::Running(last)) => Some(last.saturating_add(life_time)),
            _ => None,
        }
    }

    /// Return whether the life time has expired and no guard request has
    /// come since.
    #[inline]
    #[must_use]
    pub const fn is_expired(&self) -> bool {
        matches!(self.timer, LifeTimer::Expired(_))
    }

    /// A guard request came at `now`: restart the timer. Returns the
    /// expiry that happened before it when no poll reported it.
    #[must_use = "the event is reported only once"]
    pub fn on_request(&mut self, now: Duration) -> Option<LifeGuardExpiry> {
        let expiry = self.poll(now);
        if self.life_time.is_some() {
            self.timer = LifeTimer::Running(now);
        }
        expiry
    }

    /// At `now`, report the expiry of the life time, once.
    #[must_use = "the event is reported only once"]
    pub fn poll(&mut self, now: Duration) -> Option<LifeGuardExpiry> {
        let deadline = self.deadline()?;
        let LifeTimer::Running(last_request) = self.timer else {
            return None;
        };
        if now > deadline {
            self.timer = LifeTimer::Expired(last_request);
            Some(LifeGuardExpiry {
                last_request,
                deadline,
                emcy: Self::EMCY,
                new_state: NmtState::PreOperational,
            })
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_life_guard_expiry_reads_as_a_person_says_it() {
        let expiry = LifeGuardExpiry {
            last_request: Duration::from_millis(1000),
            deadline: Duration::from_millis(1500),
            emcy: LifeGuard::EMCY,
            new_state: PreOperational,
        };
        assert_eq!(
            expiry.to_string(),
            "life time expired at 1500000 µs after the guard request at 1000000 µs: \
             send EMCY 0x8130 Life guard error or heartbeat error, register 0x11 \
             [generic|communication], manufacturer 0000000000, go pre_operational"
        );
    }
    use NmtState::{BootUp, Operational, PreOperational, Stopped};

    /// A time in microseconds.
    fn us(n: u64) -> Duration {
        Duration::from_micros(n)
    }

    const MS: Duration = Duration::from_millis(1);
    /// One microsecond.
    const US: Duration = Duration::from_micros(1);

    fn node() -> NodeId {
        NodeId::new(5).unwrap()
    }

    /// One step of a node-guarding scenario.
    #[derive(Debug, Clone, Copy)]
    enum Step {
        /// The master sends (or the log shows) a guard request.
        Request,
        /// The node answers with (toggle, state).
        Answer(bool, NmtState),
        /// The node sent its boot-up message.
        BootUp,
        /// A poll.
        Poll,
    }

    fn run(master: &mut NodeGuardingMaster, rows: &[(Duration, Step, &[GuardingEvent])]) {
        for (row, &(now, step, expected)) in rows.iter().enumerate() {
            let got: Vec<GuardingEvent> = match step {
                Step::Request => master.on_request(now).into_iter().collect(),
                Step::Answer(toggle, state) => master
                    .on_answer(now, GuardAnswer::new(toggle, state))
                    .collect(),
                Step::BootUp => {
                    master.on_boot_up();
                    Vec::new()
                }
                Step::Poll => master.poll(now).into_iter().collect(),
            };
            assert_eq!(got, expected, "row {row}: {step:?} at {now:?}");
        }
    }

    #[test]
    fn toggle_alternates_from_zero() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        assert_eq!(master.expected_toggle(), Some(false));
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (MS, Step::Answer(false, PreOperational), &[]),
                (100 * MS, Step::Request, &[]),
                (101 * MS, Step::Answer(true, PreOperational), &[]),
                (200 * MS, Step::Request, &[]),
                (201 * MS, Step::Answer(false, Operational), &[]),
                (300 * MS, Step::Request, &[]),
                (301 * MS, Step::Answer(true, Operational), &[]),
                (400 * MS, Step::Poll, &[]),
            ],
        );
        assert_eq!(master.expected_toggle(), Some(false));
    }

    #[test]
    fn request_schedule() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        assert_eq!(master.next_request_at(), Some(us(0)));
        assert!(master.request_due(us(0)));
        assert_eq!(master.on_request(10 * MS), None);
        assert_eq!(master.next_request_at(), Some(110 * MS));
        assert!(!master.request_due(110 * MS - 1 * US));
        assert!(master.request_due(110 * MS));
        assert_eq!(master.outstanding_request(), Some(10 * MS));
        assert_eq!(master.guard_time(), 100 * MS);
        assert_eq!(
            NodeGuardingMaster::from_millis(node(), 0).next_request_at(),
            None
        );
        assert!(!NodeGuardingMaster::from_millis(node(), 0).request_due(Duration::MAX));
    }

    #[test]
    fn wrong_toggle() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (MS, Step::Answer(false, Operational), &[]),
                (100 * MS, Step::Request, &[]),
                (
                    101 * MS,
                    Step::Answer(false, Operational),
                    &[GuardingEvent::WrongToggle {
                        node: node(),
                        at: 101 * MS,
                        request_at: Some(100 * MS),
                        expected: true,
                        found: false,
                    }],
                ),
                // Resynchronised on the toggle received: one error, not many.
                (200 * MS, Step::Request, &[]),
                (201 * MS, Step::Answer(true, Operational), &[]),
            ],
        );
    }

    #[test]
    fn first_answer_after_start_must_be_toggle_zero() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (
                    MS,
                    Step::Answer(true, PreOperational),
                    &[GuardingEvent::WrongToggle {
                        node: node(),
                        at: MS,
                        request_at: Some(us(0)),
                        expected: false,
                        found: true,
                    }],
                ),
            ],
        );
    }

    #[test]
    fn unexpected_state() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100)
            .with_accepted_states(AcceptedStates::only(Operational));
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (MS, Step::Answer(false, Operational), &[]),
                (100 * MS, Step::Request, &[]),
                (
                    101 * MS,
                    Step::Answer(true, Stopped),
                    &[GuardingEvent::UnexpectedState {
                        node: node(),
                        at: 101 * MS,
                        request_at: Some(100 * MS),
                        state: Stopped,
                    }],
                ),
            ],
        );
        // Told to expect pre-operational (after an NMT command).
        master.set_accepted_states(AcceptedStates::only(PreOperational));
        run(
            &mut master,
            &[
                (200 * MS, Step::Request, &[]),
                (201 * MS, Step::Answer(false, PreOperational), &[]),
            ],
        );
    }

    #[test]
    fn wrong_toggle_and_unexpected_state_together() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (
                    MS,
                    Step::Answer(true, BootUp),
                    &[
                        GuardingEvent::WrongToggle {
                            node: node(),
                            at: MS,
                            request_at: Some(us(0)),
                            expected: false,
                            found: true,
                        },
                        GuardingEvent::UnexpectedState {
                            node: node(),
                            at: MS,
                            request_at: Some(us(0)),
                            state: BootUp,
                        },
                    ],
                ),
            ],
        );
    }

    #[test]
    fn missing_answer() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        let missing = GuardingEvent::MissingAnswer {
            node: node(),
            request_at: Duration::ZERO,
            due_by: 100 * MS,
        };
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (100 * MS, Step::Poll, &[]),
                (100 * MS + 1 * US, Step::Poll, &[missing]),
                (150 * MS, Step::Poll, &[]),
                // The expectation is kept: the next answer carries toggle 0.
                (200 * MS, Step::Request, &[]),
                (201 * MS, Step::Answer(false, PreOperational), &[]),
            ],
        );
    }

    #[test]
    fn missing_answer_found_by_the_next_request() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (
                    100 * MS,
                    Step::Request,
                    &[GuardingEvent::MissingAnswer {
                        node: node(),
                        request_at: Duration::ZERO,
                        due_by: 100 * MS,
                    }],
                ),
                (
                    180 * MS,
                    Step::Request,
                    &[GuardingEvent::MissingAnswer {
                        node: node(),
                        request_at: 100 * MS,
                        due_by: 180 * MS,
                    }],
                ),
            ],
        );
    }

    #[test]
    fn late_answer_without_poll_reports_the_missing_answer_first() {
        let mut master = NodeGuardingMaster::from_millis(node(), 100);
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (
                    150 * MS,
                    Step::Answer(false, Operational),
                    &[GuardingEvent::MissingAnswer {
                        node: node(),
                        request_at: Duration::ZERO,
                        due_by: 100 * MS,
                    }],
                ),
                (200 * MS, Step::Request, &[]),
                (201 * MS, Step::Answer(true, Operational), &[]),
            ],
        );
    }

    #[test]
    fn observer_baseline_from_first_answer() {
        let mut master = NodeGuardingMaster::observer(node(), Duration::ZERO);
        assert_eq!(master.expected_toggle(), None);
        run(
            &mut master,
            &[
                // The log starts mid-way: toggle 1 is the baseline.
                (7 * MS, Step::Request, &[]),
                (8 * MS, Step::Answer(true, Operational), &[]),
                (107 * MS, Step::Request, &[]),
                (108 * MS, Step::Answer(false, Operational), &[]),
                (207 * MS, Step::Request, &[]),
                (
                    208 * MS,
                    Step::Answer(false, Operational),
                    &[GuardingEvent::WrongToggle {
                        node: node(),
                        at: 208 * MS,
                        request_at: Some(207 * MS),
                        expected: true,
                        found: false,
                    }],
                ),
                // Guard time unknown: no timeout by polling…
                (307 * MS, Step::Request, &[]),
                (10_000 * MS, Step::Poll, &[]),
                // …but an unanswered request is found by the next one.
                (
                    10_001 * MS,
                    Step::Request,
                    &[GuardingEvent::MissingAnswer {
                        node: node(),
                        request_at: 307 * MS,
                        due_by: 10_001 * MS,
                    }],
                ),
            ],
        );
    }

    #[test]
    fn boot_up_resets_the_toggle_to_zero() {
        let mut master = NodeGuardingMaster::observer(node(), 100 * MS);
        run(
            &mut master,
            &[
                (us(0), Step::Request, &[]),
                (MS, Step::Answer(false, Operational), &[]),
                (100 * MS, Step::Request, &[]),
                (101 * MS, Step::Answer(true, Operational), &[]),
                (150 * MS, Step::BootUp, &[]),
                (200 * MS, Step::Request, &[]),
                (201 * MS, Step::Answer(false, PreOperational), &[]),
                (300 * MS, Step::Request, &[]),
                (301 * MS, Step::Answer(true, PreOperational), &[]),
            ],
        );
    }

    #[test]
    fn event_accessors() {
        let missing = GuardingEvent::MissingAnswer {
            node: node(),
            request_at: Duration::ZERO,
            due_by: us(100_000),
        };
        assert_eq!(missing.node(), node());
        assert_eq!(missing.at(), us(100_000));
        assert_eq!(missing.name(), "missing_answer");
        assert_eq!(
            missing.to_string(),
            "node 5: missing answer to the request at 0 µs (due by 100000 µs)"
        );
        let toggle = GuardingEvent::WrongToggle {
            node: node(),
            at: us(7),
            request_at: None,
            expected: true,
            found: false,
        };
        assert_eq!(toggle.name(), "wrong_toggle");
        assert_eq!(
            toggle.to_string(),
            "node 5: toggle 0 where 1 was expected at 7 µs"
        );
        let state = GuardingEvent::UnexpectedState {
            node: node(),
            at: us(9),
            request_at: None,
            state: Stopped,
        };
        assert_eq!(state.at(), us(9));
        assert_eq!(state.name(), "unexpected_state");
        assert_eq!(
            state.to_string(),
            "node 5: unexpected state stopped at 9 µs"
        );
    }

    fn guarding(guard_time_ms: u16, life_time_factor: u8) -> ErrorControlConfig {
        ErrorControlConfig {
            producer_heartbeat_time_ms: 0,
            guard_time_ms,
            life_time_factor,
        }
    }

    /// One step of a life-guarding scenario.
    #[derive(Debug, Clone, Copy)]
    enum Life {
        Request,
        Poll,
    }

    /// A row: (time, step, expected expiry as (last request, deadline)).
    type LifeRow = (Duration, Life, Option<(Duration, Duration)>);

    fn run_life(life: &mut LifeGuard, rows: &[LifeRow]) {
        for (row, &(now, step, expected)) in rows.iter().enumerate() {
            let got = match step {
                Life::Request => life.on_request(now),
                Life::Poll => life.poll(now),
            };
            let expected = expected.map(|(last_request, deadline)| LifeGuardExpiry {
                last_request,
                deadline,
                emcy: LifeGuard::EMCY,
                new_state: PreOperational,
            });
            assert_eq!(got, expected, "row {row}: {step:?} at {now:?}");
        }
    }

    #[test]
    fn life_guard_expiry_sends_emcy_and_goes_pre_operational() {
        let mut life = LifeGuard::new(guarding(100, 3));
        assert_eq!(life.node_life_time(), Some(300 * MS));
        run_life(
            &mut life,
            &[
                (us(0), Life::Request, None),
                (300 * MS, Life::Poll, None),
                (300 * MS + 1 * US, Life::Poll, Some((us(0), 300 * MS))),
                (400 * MS, Life::Poll, None),
                (10_000 * MS, Life::Poll, None),
            ],
        );
        assert!(life.is_expired());
        let emcy = LifeGuard::EMCY;
        assert_eq!(
            emcy.to_bytes(),
            [0x30, 0x81, 0x11, 0x00, 0x00, 0x00, 0x00, 0x00]
        );
        assert_eq!(emcy.code, ErrorCode::LIFE_GUARD);
        assert_eq!(
            emcy.register,
            ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION
        );
    }

    #[test]
    fn life_guard_starts_at_the_first_request() {
        let mut life = LifeGuard::new(guarding(100, 3));
        run_life(
            &mut life,
            &[
                (us(0), Life::Poll, None),
                (10_000 * MS, Life::Poll, None),
                (10_000 * MS, Life::Request, None),
                (10_300 * MS, Life::Poll, None),
                (10_301 * MS, Life::Poll, Some((10_000 * MS, 10_300 * MS))),
            ],
        );
    }

    #[test]
    fn life_guard_requests_keep_it_alive() {
        let mut life = LifeGuard::new(guarding(100, 3));
        run_life(
            &mut life,
            &[
                (us(0), Life::Request, None),
                (250 * MS, Life::Request, None),
                (500 * MS, Life::Poll, None),
                (550 * MS, Life::Request, None),
                (850 * MS, Life::Poll, None),
            ],
        );
        assert_eq!(life.deadline(), Some(850 * MS));
        assert!(!life.is_expired());
    }

    #[test]
    fn life_guard_once_per_expiry_and_restarts_at_the_next_request() {
        let mut life = LifeGuard::new(guarding(10, 2));
        run_life(
            &mut life,
            &[
                (us(0), Life::Request, None),
                (30 * MS, Life::Poll, Some((us(0), 20 * MS))),
                (40 * MS, Life::Poll, None),
                (50 * MS, Life::Request, None),
                (60 * MS, Life::Poll, None),
                // Late request without a poll: the expiry is still reported.
                (100 * MS, Life::Request, Some((50 * MS, 70 * MS))),
                (120 * MS, Life::Poll, None),
            ],
        );
    }

    #[test]
    fn life_guard_zero_disables_it() {
        for config in [guarding(0, 3), guarding(100, 0), guarding(0, 0)] {
            let mut life = LifeGuard::new(config);
            assert_eq!(life.node_life_time(), None);
            run_life(
                &mut life,
                &[
                    (us(0), Life::Request, None),
                    (10_000 * MS, Life::Poll, None),
                    (20_000 * MS, Life::Request, None),
                ],
            );
            assert_eq!(life.deadline(), None);
        }
    }

    #[test]
    fn life_guard_is_inert_when_heartbeat_is_configured() {
        let config = ErrorControlConfig {
            producer_heartbeat_time_ms: 100,
            guard_time_ms: 100,
            life_time_factor: 3,
        };
        let mut life = LifeGuard::new(config);
        assert_eq!(life.node_life_time(), None);
        run_life(
            &mut life,
            &[
                (us(0), Life::Request, None),
                (10_000 * MS, Life::Poll, None),
            ],
        );
        // Switching the heartbeat off brings life guarding back.
        life.reconfigure(ErrorControlConfig {
            producer_heartbeat_time_ms: 0,
            ..config
        });
        run_life(
            &mut life,
            &[
                (20_000 * MS, Life::Request, None),
                (20_301 * MS, Life::Poll, Some((20_000 * MS, 20_300 * MS))),
            ],
        );
        life.reset();
        assert!(!life.is_expired());
        run_life(&mut life, &[(90_000 * MS, Life::Poll, None)]);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;

    /// A time in microseconds.
    fn us(n: u64) -> Duration {
        Duration::from_micros(n)
    }
    use crate::strategies::error_control::{
        any_times, guarding_step, guarding_steps, life_step, life_steps, GuardingStep, LifeStep,
    };

    proptest! {
        /// Random requests, answers, boot-ups and polls never panic, and
        /// every event is consistent with the inputs.
        #[test]
        fn master_invariants(
            guard_ms in 0u16..200,
            observer in any::<bool>(),
            steps in guarding_steps(),
        ) {
            let node = NodeId::MIN;
            let mut master = if observer {
                NodeGuardingMaster::observer(node, millis(u32::from(guard_ms)))
            } else {
                NodeGuardingMaster::from_millis(node, guard_ms)
            };
            let guard_time = millis(u32::from(guard_ms));
            // Requests are numbered; each is reported missing at most once.
            let mut request_number = 0usize;
            let mut reported_missing: Option<usize> = None;
            for (now, step) in steps {
                let before = master;
                let events: Vec<GuardingEvent> = match step {
                    GuardingStep::Request => master.on_request(now).into_iter().collect(),
                    GuardingStep::Answer(answer) => master.on_answer(now, answer).collect(),
                    GuardingStep::BootUp => {
                        master.on_boot_up();
                        prop_assert_eq!(master.expected_toggle(), Some(false));
                        Vec::new()
                    }
                    GuardingStep::Poll => master.poll(now).into_iter().collect(),
                };
                for event in &events {
                    prop_assert_eq!(event.node(), node);
                    match *event {
                        GuardingEvent::MissingAnswer { request_at, due_by, .. } => {
                            prop_assert_eq!(Some(request_at), before.outstanding_request());
                            prop_assert!(reported_missing != Some(request_number));
                            prop_assert!(due_by <= now);
                            if guard_time != us(0) {
                                prop_assert!(due_by <= request_at + guard_time);
                            }
                            reported_missing = Some(request_number);
                        }
                        GuardingEvent::WrongToggle { expected, found, at, .. } => {
                            prop_assert_eq!(before.expected_toggle(), Some(expected));
                            prop_assert!(expected != found);
                            prop_assert_eq!(at, now);
                        }
                        GuardingEvent::UnexpectedState { state, .. } => {
                            prop_assert!(!AcceptedStates::GUARDED.contains(state));
                        }
                    }
                }
                if let GuardingStep::Request = step {
                    request_number += 1;
                }
                if let GuardingStep::Answer(answer) = step {
                    // After any answer the next toggle is known: its inverse.
                    prop_assert_eq!(master.expected_toggle(), Some(!answer.toggle));
                    prop_assert_eq!(master.outstanding_request(), None);
                    let wrong = events.iter().any(|e| matches!(e, GuardingEvent::WrongToggle { .. }));
                    prop_assert_eq!(
                        wrong,
                        before.expected_toggle().is_some_and(|t| t != answer.toggle)
                    );
                }
            }
        }

        /// A node answering every request in time with alternating toggles
        /// is never reported.
        #[test]
        fn a_healthy_node_is_never_reported(
            guard_ms in 1u16..200,
            delays in proptest::collection::vec(0u64..1000, 1..40),
        ) {
            let mut master = NodeGuardingMaster::from_millis(NodeId::MIN, guard_ms);
            let mut toggle = false;
            let mut now = Duration::ZERO;
            for delay in delays {
                prop_assert!(master.request_due(now));
                prop_assert_eq!(master.on_request(now), None);
                let answered = now + us(delay).min(millis(u32::from(guard_ms)));
                prop_assert_eq!(master.poll(answered), None);
                let events: Vec<_> = master
                    .on_answer(answered, GuardAnswer::new(toggle, NmtState::Operational))
                    .collect();
                prop_assert_eq!(events, vec![]);
                toggle = !toggle;
                now = master.next_request_at().unwrap();
            }
        }

        /// Life guarding emits at most one EMCY per expiry, only after a
        /// request, never while disabled, and always exactly 0x8130/0x11.
        #[test]
        fn life_guard_invariants(
            heartbeat_ms in prop_oneof![Just(0u16), 1u16..100],
            guard_ms in 0u16..100,
            factor in 0u8..5,
            steps in life_steps(),
        ) {
            let config = ErrorControlConfig {
                producer_heartbeat_time_ms: heartbeat_ms,
                guard_time_ms: guard_ms,
                life_time_factor: factor,
            };
            let mut life = LifeGuard::new(config);
            let enabled = heartbeat_ms == 0 && guard_ms != 0 && factor != 0;
            prop_assert_eq!(life.node_life_time().is_some(), enabled);
            let mut last_request: Option<Duration> = None;
            let mut expiries_since_request = 0;
            for (now, step) in steps {
                let expiry = match step {
                    LifeStep::Request => life.on_request(now),
                    LifeStep::Poll => life.poll(now),
                };
                if let Some(expiry) = expiry {
                    prop_assert!(enabled);
                    prop_assert_eq!(Some(expiry.last_request), last_request);
                    prop_assert_eq!(
                        expiry.deadline,
                        expiry.last_request + life.node_life_time().unwrap()
                    );
                    prop_assert!(expiry.deadline < now);
                    prop_assert_eq!(expiry.emcy.to_bytes(), [0x30, 0x81, 0x11, 0, 0, 0, 0, 0]);
                    prop_assert_eq!(expiry.new_state, NmtState::PreOperational);
                    expiries_since_request += 1;
                    prop_assert!(expiries_since_request <= 1, "two EMCYs for one expiry");
                }
                if let LifeStep::Request = step {
                    last_request = Some(now);
                    expiries_since_request = 0;
                }
            }
        }

        /// Times that jump backwards or sit at `Duration::MAX` never panic; the
        /// outputs stay well-formed.
        #[test]
        fn any_times_never_panic(
            guard_ms in any::<u16>(),
            factor in any::<u8>(),
            steps in any_times(guarding_step()),
            life_steps in any_times(life_step()),
        ) {
            let mut master = NodeGuardingMaster::from_millis(NodeId::MAX, guard_ms);
            for (now, step) in steps {
                let events: Vec<GuardingEvent> = match step {
                    GuardingStep::Request => master.on_request(now).into_iter().collect(),
                    GuardingStep::Answer(answer) => master.on_answer(now, answer).collect(),
                    GuardingStep::BootUp => {
                        master.on_boot_up();
                        Vec::new()
                    }
                    GuardingStep::Poll => master.poll(now).into_iter().collect(),
                };
                for event in events {
                    prop_assert!(event.at() <= now);
                }
            }
            let mut life = LifeGuard::new(ErrorControlConfig {
                producer_heartbeat_time_ms: 0,
                guard_time_ms: guard_ms,
                life_time_factor: factor,
            });
            for (now, step) in life_steps {
                let expiry = match step {
                    LifeStep::Request => life.on_request(now),
                    LifeStep::Poll => life.poll(now),
                };
                if let Some(expiry) = expiry {
                    prop_assert!(expiry.deadline < now);
                    prop_assert_eq!(expiry.emcy, LifeGuard::EMCY);
                }
            }
        }
    }
}
