//! The pure behaviours of the servo ↔ NC interface (docs/servo.md#handshakes;
//! the interface manual): the ServoRDY truth table, the enable handshake on
//! SCW.SE, and the NC side of the error-clear and zero-pulse handshakes.
//!
//! Nothing here reads a clock or does I/O; every state is `Copy`. A PLC
//! calls the handshakes once per NC cycle with the control word it wrote
//! last and the newest status word, and writes the control word they return.
//!
//! ```
//! use motionwire_codec::servo::{
//!     ErrorClearHandshake, HandshakePhase, ServoControlWord, ServoStatusWord,
//! };
//!
//! let mut clear = ErrorClearHandshake::new().start();
//! let mut scw = ServoControlWord::NORMAL;
//! // The drive's answers, one per cycle: no ack yet, ack, ack, ack dropped.
//! let acks = [false, true, true, false];
//! let mut phases = Vec::new();
//! for ack in acks {
//!     let ssw = ServoStatusWord::empty().with_flag(ServoStatusWord::ERR_CLEAR_ACK, ack);
//!     (clear, scw) = clear.step(scw, ssw);
//!     phases.push((clear.phase(), scw.contains(ServoControlWord::ERROR_CLEAR)));
//! }
//! assert_eq!(phases, [
//!     (HandshakePhase::Requested, true),     // write ErrorClear=1, wait
//!     (HandshakePhase::Acknowledged, false), // ack seen: drop ErrorClear
//!     (HandshakePhase::Releasing, false),    // wait for the drive to drop the ack
//!     (HandshakePhase::Done, false),
//! ]);
//! ```

use crate::error::What;
use core::fmt;
use core::marker::PhantomData;

use super::{ServoControlWord, ServoEnable, ServoErrorWord, ServoStatusWord};
use crate::{RangeError, Result};

/// The drive parameter Servo_Ready_Mode, which decides whether ServoRDY depends
/// on ServoEn (docs/servo.md#servo-ready; the interface manual, "Servo ReaDY").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum ServoReadyMode {
    /// Servo_Ready_Mode = 0: the drive is ready whenever it has no error.
    ErrorFree = 0,
    /// Servo_Ready_Mode = 1: the drive is ready only while enabled and
    /// without error.
    EnabledAndErrorFree = 1,
}

impl ServoReadyMode {
    /// Return the mode whose parameter value is `raw`, or `None` above 1.
    #[must_use]
    pub const fn new(raw: u8) -> Option<Self> {
        match raw {
            0 => Some(ServoReadyMode::ErrorFree),
            1 => Some(ServoReadyMode::EnabledAndErrorFree),
            _ => None,
        }
    }

    /// Return the mode whose parameter value is `raw`, or a
    /// [`RangeError`] above 1.
    pub const fn try_new(raw: u8) -> Result<Self, RangeError> {
        match Self::new(raw) {
            Some(mode) => Ok(mode),
            None => Err(RangeError {
                what: What::ServoReadyMode,
                found: raw as u32,
                min: 0,
                max: 1,
            }),
        }
    }

    /// Return the parameter value, 0 or 1.
    #[must_use]
    pub const fn get(self) -> u8 {
        self as u8
    }
}

/// Return SSW.ServoRDY for Servo_Ready_Mode `mode`, the drive's status word
/// (its SSW.ServoEn bit is e) and error word (its summary bit SEW.ServoErrors,
/// bit 0, is x — the only error bit the interface manual's table reads):
/// `!x && (m == 0 || e)` (docs/servo.md#servo-ready; the interface manual,
/// ServoRDY truth table). The other bits of both words do not matter.
///
/// ```
/// use motionwire_codec::servo::{servo_ready, ServoErrorWord, ServoReadyMode, ServoStatusWord};
///
/// let disabled = ServoStatusWord::empty();
/// let enabled = ServoStatusWord::SERVO_EN;
/// let no_errors = ServoErrorWord::empty();
/// assert!(servo_ready(ServoReadyMode::ErrorFree, disabled, no_errors));
/// assert!(!servo_ready(ServoReadyMode::EnabledAndErrorFree, disabled, no_errors));
/// assert!(servo_ready(ServoReadyMode::EnabledAndErrorFree, enabled, no_errors));
/// assert!(!servo_ready(ServoReadyMode::ErrorFree, enabled, ServoErrorWord::SERVO_ERRORS));
/// ```
#[must_use]
pub const fn servo_ready(
    mode: ServoReadyMode,
    status: ServoStatusWord,
    errors: ServoErrorWord,
) -> bool {
    let error = errors.contains(ServoErrorWord::SERVO_ERRORS);
    let enabled = status.contains(ServoStatusWord::SERVO_EN);
    !error && (matches!(mode, ServoReadyMode::ErrorFree) || enabled)
}

/// The drive's side of the enable handshake: return whether the drive is
/// enabled after a cycle in which SCW.SE went from `previous` to `current`,
/// given whether it `was_enabled` (docs/servo.md#handshakes; the interface
/// manual, "Servo Enable"). The NC's side is
/// [`EnableHandshake`](super::EnableHandshake).
///
/// The drive enables only on 0b01 → 0b10 (bit 0 falls and bit 1 rises in
/// the same cycle). **Decision (docs/servo.md#handshakes):** it stays enabled
/// while SE stays 0b10; every other value disables it; 0b10 not preceded by
/// 0b01 does not enable. An enabled drive whose previous SE was not 0b10 cannot
/// occur; such input yields "disabled", the safe answer.
///
/// ```
/// use motionwire_codec::servo::{drive_enabled, ServoEnable};
///
/// let on = drive_enabled(ServoEnable::ARM, ServoEnable::ENABLE, false);
/// assert!(on);
/// assert!(drive_enabled(ServoEnable::ENABLE, ServoEnable::ENABLE, on));
/// assert!(!drive_enabled(ServoEnable::DISABLED, ServoEnable::ENABLE, false));
/// assert!(!drive_enabled(ServoEnable::ENABLE, ServoEnable::BOTH, true));
/// ```
#[must_use]
pub const fn drive_enabled(previous: ServoEnable, current: ServoEnable, was_enabled: bool) -> bool {
    match (previous.get(), current.get()) {
        (0b01, 0b10) => true,
        (0b10, 0b10) => was_enabled,
        _ => false,
    }
}

/// The phase of an NC-side handshake (docs/servo.md#handshakes, error clear and
/// zero pulse).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum HandshakePhase {
    /// Nothing requested; the NC writes the request bit 0.
    Idle,
    /// The NC writes the request bit 1 and waits for the drive's ack. A
    /// drive that never acks keeps the handshake here; the caller bounds the
    /// wait with [`Handshake::cycles_in_phase`].
    Requested,
    /// The drive acknowledged (errors cleared / zero pulse found, its
    /// position in POSW2..3); the NC must write the request bit 0.
    Acknowledged,
    /// The NC dropped the request; waiting for the drive to drop the ack.
    Releasing,
    /// The drive dropped the ack: the handshake is complete. Stays until the
    /// next [`start`](Handshake::start) or an unsolicited ack.
    Done,
    /// The drive shows the ack although no request of this handshake is on
    /// the wire. The NC writes the request bit 0 and waits for the ack to
    /// drop; a [`start`](Handshake::start) made meanwhile is held back until
    /// then (an ack that was already up could not be told from the answer).
    UnsolicitedAck,
}

impl HandshakePhase {
    /// Return the phase's name in snake case, e.g. `"unsolicited_ack"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            HandshakePhase::Idle => "idle",
            HandshakePhase::Requested => "requested",
            HandshakePhase::Acknowledged => "acknowledged",
            HandshakePhase::Releasing => "releasing",
            HandshakePhase::Done => "done",
            HandshakePhase::UnsolicitedAck => "unsolicited_ack",
        }
    }

    /// Return whether the NC must write the request bit as 1 in this phase
    /// (only in [`HandshakePhase::Requested`]).
    #[must_use]
    pub const fn request_bit(self) -> bool {
        matches!(self, HandshakePhase::Requested)
    }
}

impl fmt::Display for HandshakePhase {
    /// Format the phase as its name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

mod sealed {
    pub trait Sealed {}
}

/// The pair of bits one handshake uses: a request bit in the control word and
/// an ack bit in the status word (docs/servo.md#scw, docs/servo.md#ssw,
/// docs/servo.md#handshakes). Implemented by [`ErrorClear`] and [`ZeroPulse`]
/// only.
pub trait HandshakeBits: sealed::Sealed + Copy {
    /// The control-word bit the NC raises to request.
    const REQUEST: ServoControlWord;
    /// The status-word bit the drive raises to acknowledge.
    const ACK: ServoStatusWord;
}

/// The error-clear handshake's bits: SCW.ErrorClear (bit 9) and
/// SSW.ErrClearAck (bit 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorClear {}

impl sealed::Sealed for ErrorClear {}
impl HandshakeBits for ErrorClear {
    const REQUEST: ServoControlWord = ServoControlWord::ERROR_CLEAR;
    const ACK: ServoStatusWord = ServoStatusWord::ERR_CLEAR_ACK;
}

/// The zero-pulse handshake's bits: SCW.ZPulseRequest (bit 11) and
/// SSW.ZPulseAck (bit 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ZeroPulse {}

impl sealed::Sealed for ZeroPulse {}
impl HandshakeBits for ZeroPulse {
    const REQUEST: ServoControlWord = ServoControlWord::Z_PULSE_REQUEST;
    const ACK: ServoStatusWord = ServoStatusWord::Z_PULSE_ACK;
}

/// The NC side of the error-clear handshake: ErrorClear=1 → drive clears
/// its errors and answers ErrClearAck=1 → ErrorClear=0 → drive drops
/// ErrClearAck (docs/servo.md#handshakes; the interface manual, "Error Clear",
/// "ErrClearAck").
pub type ErrorClearHandshake = Handshake<ErrorClear>;

/// The NC side of the zero-pulse handshake of an incremental encoder:
/// ZPulseRequest=1 → drive answers ZPulseAck=1 once the first zero pulse is
/// found, its position in POSW2..3 → ZPulseRequest=0 → drive drops ZPulseAck
/// (docs/servo.md#handshakes; the interface manual, "ZpulseRequest",
/// "ZpulseAck"). Read the zero-pulse position from the feedback of the cycle
/// that reports [`HandshakePhase::Acknowledged`].
pub type ZeroPulseHandshake = Handshake<ZeroPulse>;

/// The NC side of a request/ack handshake (docs/servo.md#handshakes): a pure
/// state machine stepped once per NC cycle. Use it as [`ErrorClearHandshake`]
/// or [`ZeroPulseHandshake`].
///
/// Each cycle, [`step`](Self::step) takes the control word the NC wrote in
/// the previous cycle (so the machine knows whether its request is on the
/// wire) and the newest status word, and returns the new state and the
/// control word to write next — the previous one with the request bit set
/// or cleared. [`apply`](Self::apply) does the same to any other word.
///
/// | phase | request bit on the wire | ack | next phase |
/// |---|---|---|---|
/// | Idle, Done | any | 0 | unchanged |
/// | Idle, Done | any | 1 | UnsolicitedAck |
/// | Requested | 0 (not written yet) | 0 | Requested |
/// | Requested | 0 (not written yet) | 1 | UnsolicitedAck, start held back |
/// | Requested | 1 | 0 | Requested (waiting) |
/// | Requested | 1 | 1 | Acknowledged |
/// | Acknowledged | 1 (not dropped yet) | any | Acknowledged |
/// | Acknowledged | 0 | 1 | Releasing |
/// | Acknowledged | 0 | 0 | Done |
/// | Releasing | any | 1 | Releasing |
/// | Releasing | any | 0 | Done |
/// | UnsolicitedAck | any | 1 | UnsolicitedAck |
/// | UnsolicitedAck | any | 0 | Requested if a start is held back, else Idle |
///
/// The request bit is written as 1 only in [`HandshakePhase::Requested`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Handshake<B: HandshakeBits> {
    phase: HandshakePhase,
    start_held_back: bool,
    cycles_in_phase: u32,
    bits: PhantomData<B>,
}

impl<B: HandshakeBits> Default for Handshake<B> {
    fn default() -> Self {
        Self::new()
    }
}

impl<B: HandshakeBits> Handshake<B> {
    /// Return a handshake in [`HandshakePhase::Idle`].
    #[must_use]
    pub const fn new() -> Self {
        Self::enter(HandshakePhase::Idle, false)
    }

    const fn enter(phase: HandshakePhase, start_held_back: bool) -> Self {
        Handshake {
            phase,
            start_held_back,
            cycles_in_phase: 0,
            bits: PhantomData,
        }
    }

    /// Return the current phase.
    #[must_use]
    pub const fn phase(self) -> HandshakePhase {
        self.phase
    }

    /// Return whether a [`start`](Self::start) is held back until an
    /// unsolicited ack drops.
    #[must_use]
    pub const fn start_held_back(self) -> bool {
        self.start_held_back
    }

    /// Return how many [`step`](Self::step)s the handshake has spent in its
    /// current phase (saturating). A caller that wants a timeout compares it
    /// with a number of cycles of its own choosing.
    #[must_use]
    pub const fn cycles_in_phase(self) -> u32 {
        self.cycles_in_phase
    }

    /// Return whether the NC must write the request bit as 1 next.
    #[must_use]
    pub const fn request_bit(self) -> bool {
        self.phase.request_bit()
    }

    /// Return `command` with the request bit set as this state requires.
    #[must_use]
    pub const fn apply(self, command: ServoControlWord) -> ServoControlWord {
        command.with_flag(B::REQUEST, self.request_bit())
    }

    /// Start a handshake: from Idle or Done, go to Requested; during an
    /// unsolicited ack, hold the start back until the ack drops; while a
    /// handshake is already running (Requested, Acknowledged, Releasing),
    /// change nothing.
    #[must_use]
    pub const fn start(self) -> Self {
        match self.phase {
            HandshakePhase::Idle | HandshakePhase::Done => {
                Self::enter(HandshakePhase::Requested, false)
            }
            HandshakePhase::UnsolicitedAck => Handshake {
                start_held_back: true,
                ..self
            },
            HandshakePhase::Requested
            | HandshakePhase::Acknowledged
            | HandshakePhase::Releasing => self,
        }
    }

    /// Abandon the handshake and go to Idle; the request bit is written 0.
    /// An ack that arrives later is reported as [`HandshakePhase::UnsolicitedAck`].
    #[must_use]
    pub const fn cancel(self) -> Self {
        Self::enter(HandshakePhase::Idle, false)
    }

    /// Advance by one NC cycle. `last_command` is the control word written
    /// in the previous cycle, `status` the newest status word. Return the
    /// new state and the control word to write: `last_command` with the
    /// request bit as the new state requires.
    #[must_use]
    pub const fn step(
        self,
        last_command: ServoControlWord,
        status: ServoStatusWord,
    ) -> (Self, ServoControlWord) {
        let next = self.next(last_command.contains(B::REQUEST), status.contains(B::ACK));
        (next, next.apply(last_command))
    }

    /// The transition table of the type's documentation.
    const fn next(self, requested: bool, ack: bool) -> Self {
        use HandshakePhase::*;
        let (phase, held_back) = match (self.phase, requested, ack) {
            (Idle | Done, _, false) => (self.phase, false),
            (Idle | Done, _, true) => (UnsolicitedAck, false),
            (Requested, false, true) => (UnsolicitedAck, true),
            (Requested, _, false) => (Requested, false),
            (Requested, true, true) => (Acknowledged, false),
            (Acknowledged, true, _) => (Acknowledged, false),
            (Acknowledged, false, true) => (Releasing, false),
            (Acknowledged, false, false) => (Done, false),
            (Releasing, _, true) => (Releasing, false),
            (Releasing, _, false) => (Done, false),
            (UnsolicitedAck, _, true) => (UnsolicitedAck, self.start_held_back),
            (UnsolicitedAck, _, false) => {
                if self.start_held_back {
                    (Requested, false)
                } else {
                    (Idle, false)
                }
            }
        };
        if phase as u8 == self.phase as u8 {
            Handshake {
                phase,
                start_held_back: held_back,
                cycles_in_phase: self.cycles_in_phase.saturating_add(1),
                bits: PhantomData,
            }
        } else {
            Self::enter(phase, held_back)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interface manual, ServoRDY chart, all eight rows:
    /// (Servo_Ready_Mode, ServoEn, ServoErrors, ServoRDY).
    #[rustfmt::skip]
    const SERVO_READY_TABLE: [(u8, bool, bool, bool); 8] = [
        (0, false, false, true),
        (0, false, true,  false),
        (0, true,  false, true),
        (0, true,  true,  false),
        (1, false, false, false),
        (1, false, true,  false),
        (1, true,  false, true),
        (1, true,  true,  false),
    ];

    #[test]
    fn servo_ready_truth_table() {
        for (m, e, x, rdy) in SERVO_READY_TABLE {
            let mode = ServoReadyMode::try_new(m).unwrap();
            let errors = if x {
                ServoErrorWord::SERVO_ERRORS
            } else {
                ServoErrorWord::empty()
            };
            let status = ServoStatusWord::empty().with_flag(ServoStatusWord::SERVO_EN, e);
            assert_eq!(servo_ready(mode, status, errors), rdy, "m={m} e={e} x={x}");
            // Every other status bit is ignored.
            let noisy = ServoStatusWord::from_bits_retain(!ServoStatusWord::SERVO_EN.bits())
                .with_flag(ServoStatusWord::SERVO_EN, e);
            assert_eq!(servo_ready(mode, noisy, errors), rdy, "m={m} e={e} x={x}");
        }
    }

    /// Only the summary bit counts: cause bits without it, or reserved
    /// bits, do not make the drive "not ready".
    #[test]
    fn servo_ready_reads_the_summary_bit() {
        let causes_only = ServoErrorWord::from_bits_retain(0xFFFF_FFFE);
        assert!(servo_ready(
            ServoReadyMode::ErrorFree,
            ServoStatusWord::empty(),
            causes_only
        ));
        assert!(!servo_ready(
            ServoReadyMode::ErrorFree,
            ServoStatusWord::SERVO_EN,
            ServoErrorWord::SERVO_ERRORS
        ));
    }

    #[test]
    fn servo_ready_mode_range() {
        assert_eq!(ServoReadyMode::new(0), Some(ServoReadyMode::ErrorFree));
        assert_eq!(
            ServoReadyMode::new(1),
            Some(ServoReadyMode::EnabledAndErrorFree)
        );
        for raw in 2..=255u8 {
            assert_eq!(
                ServoReadyMode::try_new(raw),
                Err(RangeError {
                    what: What::ServoReadyMode,
                    found: u32::from(raw),
                    min: 0,
                    max: 1
                })
            );
        }
        assert_eq!(ServoReadyMode::EnabledAndErrorFree.get(), 1);
    }

    /// docs/servo.md#handshakes and its Decision: all 4 × 4 × 2 cases of
    /// (previous SE, current SE, was enabled) → enabled.
    #[rustfmt::skip]
    const ENABLE_TABLE: [(u8, u8, bool, bool); 32] = [
        (0b00, 0b00, false, false), (0b00, 0b00, true, false),
        (0b00, 0b01, false, false), (0b00, 0b01, true, false),
        (0b00, 0b10, false, false), (0b00, 0b10, true, false),
        (0b00, 0b11, false, false), (0b00, 0b11, true, false),
        (0b01, 0b00, false, false), (0b01, 0b00, true, false),
        (0b01, 0b01, false, false), (0b01, 0b01, true, false),
        (0b01, 0b10, false, true ), (0b01, 0b10, true, true ), // the enable edge
        (0b01, 0b11, false, false), (0b01, 0b11, true, false),
        (0b10, 0b00, false, false), (0b10, 0b00, true, false),
        (0b10, 0b01, false, false), (0b10, 0b01, true, false),
        (0b10, 0b10, false, false), (0b10, 0b10, true, true ), // stays enabled
        (0b10, 0b11, false, false), (0b10, 0b11, true, false),
        (0b11, 0b00, false, false), (0b11, 0b00, true, false),
        (0b11, 0b01, false, false), (0b11, 0b01, true, false),
        (0b11, 0b10, false, false), (0b11, 0b10, true, false),
        (0b11, 0b11, false, false), (0b11, 0b11, true, false),
    ];

    #[test]
    fn enable_handshake_table() {
        for (previous, current, was_enabled, enabled) in ENABLE_TABLE {
            let p = ServoEnable::try_new(previous).unwrap();
            let c = ServoEnable::try_new(current).unwrap();
            assert_eq!(
                drive_enabled(p, c, was_enabled),
                enabled,
                "{p} -> {c}, was enabled: {was_enabled}"
            );
        }
        // The table covers every combination exactly once.
        let mut seen: Vec<_> = ENABLE_TABLE.iter().map(|&(p, c, w, _)| (p, c, w)).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 32);
    }

    #[test]
    fn enable_sequence_over_cycles() {
        use ServoEnable as Se;
        // SE per cycle, and whether the drive is enabled after that cycle.
        let cycles = [
            (Se::DISABLED, false),
            (Se::ENABLE, false), // 00 → 10: no edge from 01
            (Se::ARM, false),
            (Se::ENABLE, true), // 01 → 10: enabled
            (Se::ENABLE, true), // stays
            (Se::BOTH, false),  // any other value disables
            (Se::ENABLE, false),
            (Se::ARM, false),
            (Se::ENABLE, true),
            (Se::DISABLED, false),
        ];
        let mut previous = Se::DISABLED;
        let mut enabled = false;
        for (i, (se, expected)) in cycles.into_iter().enumerate() {
            enabled = drive_enabled(previous, se, enabled);
            assert_eq!(enabled, expected, "cycle {i}: {previous} -> {se}");
            previous = se;
        }
    }

    type Clear = ErrorClearHandshake;
    type Zero = ZeroPulseHandshake;

    fn clear_ack(ack: bool) -> ServoStatusWord {
        ServoStatusWord::SERVO_RDY.with_flag(ServoStatusWord::ERR_CLEAR_ACK, ack)
    }

    fn zero_ack(ack: bool) -> ServoStatusWord {
        (ServoStatusWord::SERVO_EN | ServoStatusWord::ABS_INCR)
            .with_flag(ServoStatusWord::Z_PULSE_ACK, ack)
    }

    /// Run `acks` through a handshake that was started before the first
    /// cycle, writing back what it returns; give (phase, SCW bits) per cycle.
    fn run<B: HandshakeBits>(
        mut hs: Handshake<B>,
        status: fn(bool) -> ServoStatusWord,
        acks: &[bool],
    ) -> Vec<(HandshakePhase, u32)> {
        let mut scw = ServoControlWord::NORMAL;
        acks.iter()
            .map(|&ack| {
                (hs, scw) = hs.step(scw, status(ack));
                (hs.phase(), scw.bits())
            })
            .collect()
    }

    use HandshakePhase::*;

    /// docs/servo.md#handshakes: ErrorClear=1 → ErrClearAck=1 → ErrorClear=0 →
    /// ack drops. SCW 0x0604 = NORMAL + ErrorClear, 0x0404 = NORMAL.
    #[test]
    fn error_clear_sequence() {
        let steps = run(
            Clear::new().start(),
            clear_ack,
            &[false, false, true, true, true, false, false],
        );
        assert_eq!(
            steps,
            [
                (Requested, 0x0604),    // request on the wire from now on
                (Requested, 0x0604),    // drive has not answered yet
                (Acknowledged, 0x0404), // errors cleared: drop the request
                (Releasing, 0x0404),    // request dropped, ack still up
                (Releasing, 0x0404),
                (Done, 0x0404), // ack dropped
                (Done, 0x0404), // and stays done
            ]
        );
    }

    /// The drive drops the ack in the very cycle the request drop arrives.
    #[test]
    fn error_clear_without_releasing_phase() {
        let steps = run(Clear::new().start(), clear_ack, &[true, true, false]);
        // The first ack comes before the request was on the wire: it is
        // not ours, so the start is held back until it drops.
        assert_eq!(
            steps,
            [
                (UnsolicitedAck, 0x0404),
                (UnsolicitedAck, 0x0404),
                (Requested, 0x0604),
            ]
        );
        let steps = run(Clear::new().start(), clear_ack, &[false, true, false]);
        assert_eq!(
            steps,
            [(Requested, 0x0604), (Acknowledged, 0x0404), (Done, 0x0404)]
        );
    }

    #[test]
    fn error_clear_drive_never_acks() {
        let mut hs = Clear::new().start();
        let mut scw = ServoControlWord::NORMAL;
        for cycle in 1..=1000u32 {
            (hs, scw) = hs.step(scw, clear_ack(false));
            assert_eq!(hs.phase(), Requested);
            assert_eq!(hs.cycles_in_phase(), cycle);
            assert_eq!(scw.bits(), 0x0604, "the request stays on the wire");
        }
        // The caller gives up: the request is dropped.
        hs = hs.cancel();
        (hs, scw) = hs.step(scw, clear_ack(false));
        assert_eq!((hs.phase(), scw.bits()), (Idle, 0x0404));
    }

    /// An ack that arrives when no request was made is reported, never
    /// taken for a completed handshake.
    #[test]
    fn error_clear_unsolicited_ack() {
        let steps = run(Clear::new(), clear_ack, &[false, true, true, false, false]);
        assert_eq!(
            steps,
            [
                (Idle, 0x0404),
                (UnsolicitedAck, 0x0404),
                (UnsolicitedAck, 0x0404),
                (Idle, 0x0404),
                (Idle, 0x0404),
            ]
        );
    }

    /// A start during an unsolicited ack waits for the ack to drop.
    #[test]
    fn start_is_held_back_during_an_unsolicited_ack() {
        let mut hs = Clear::new();
        let mut scw = ServoControlWord::NORMAL;
        (hs, scw) = hs.step(scw, clear_ack(true));
        assert_eq!(hs.phase(), UnsolicitedAck);
        hs = hs.start();
        assert!(hs.start_held_back());
        assert!(!hs.request_bit());
        (hs, scw) = hs.step(scw, clear_ack(true));
        assert_eq!((hs.phase(), scw.bits()), (UnsolicitedAck, 0x0404));
        assert!(hs.start_held_back());
        (hs, scw) = hs.step(scw, clear_ack(false));
        assert_eq!((hs.phase(), scw.bits()), (Requested, 0x0604));
        assert!(!hs.start_held_back());
        (hs, scw) = hs.step(scw, clear_ack(true));
        assert_eq!((hs.phase(), scw.bits()), (Acknowledged, 0x0404));
    }

    /// The NC did not write the request the handshake asked for (the word
    /// it passes back lacks the bit): the handshake keeps asking, and an
    /// ack seen meanwhile cannot be its answer.
    #[test]
    fn request_not_yet_on_the_wire() {
        let hs = Clear::new().start();
        let (hs, out) = hs.step(ServoControlWord::NORMAL, clear_ack(false));
        assert_eq!((hs.phase(), out.bits()), (Requested, 0x0604));
        let (hs, out) = hs.step(ServoControlWord::NORMAL, clear_ack(false));
        assert_eq!((hs.phase(), out.bits()), (Requested, 0x0604));
        let (hs, out) = hs.step(ServoControlWord::NORMAL, clear_ack(true));
        assert_eq!((hs.phase(), out.bits()), (UnsolicitedAck, 0x0404));
        assert!(hs.start_held_back());
    }

    /// Acknowledged holds until the request drop is on the wire, even if
    /// the drive drops the ack first.
    #[test]
    fn acknowledged_waits_for_the_request_to_drop() {
        let hs = Clear::new().start();
        let with_request = ServoControlWord::NORMAL | ServoControlWord::ERROR_CLEAR;
        let (hs, _) = hs.step(with_request, clear_ack(true));
        assert_eq!(hs.phase(), Acknowledged);
        let (hs, out) = hs.step(with_request, clear_ack(false));
        assert_eq!((hs.phase(), out.bits()), (Acknowledged, 0x0404));
        let (hs, _) = hs.step(out, clear_ack(false));
        assert_eq!(hs.phase(), Done);
    }

    #[test]
    fn start_while_running_changes_nothing_and_restart_after_done() {
        let mut hs = Clear::new().start();
        let mut scw = ServoControlWord::NORMAL;
        (hs, scw) = hs.step(scw, clear_ack(false));
        assert_eq!(hs.start(), hs);
        (hs, scw) = hs.step(scw, clear_ack(true));
        assert_eq!(hs.start(), hs);
        (hs, scw) = hs.step(scw, clear_ack(true));
        assert_eq!(hs.phase(), Releasing);
        assert_eq!(hs.start(), hs);
        (hs, scw) = hs.step(scw, clear_ack(false));
        assert_eq!(hs.phase(), Done);
        hs = hs.start();
        assert_eq!(hs.phase(), Requested);
        (hs, scw) = hs.step(scw, clear_ack(false));
        assert_eq!(scw.bits(), 0x0604);
        assert_eq!(hs.phase(), Requested);
    }

    /// docs/servo.md#handshakes: ZPulseRequest=1 → ZPulseAck=1 (zero pulse
    /// found) → ZPulseRequest=0 → ack drops. SCW 0x0C04 = NORMAL +
    /// ZPulseRequest.
    #[test]
    fn zero_pulse_sequence() {
        let steps = run(
            Zero::new().start(),
            zero_ack,
            &[false, false, false, true, true, false],
        );
        assert_eq!(
            steps,
            [
                (Requested, 0x0C04),
                (Requested, 0x0C04),
                (Requested, 0x0C04),    // searching
                (Acknowledged, 0x0404), // found: position in POSW2..3
                (Releasing, 0x0404),
                (Done, 0x0404),
            ]
        );
    }

    #[test]
    fn zero_pulse_drive_never_acks() {
        let mut hs = Zero::new().start();
        let mut scw = ServoControlWord::NORMAL;
        for _ in 0..500 {
            (hs, scw) = hs.step(scw, zero_ack(false));
        }
        assert_eq!((hs.phase(), scw.bits()), (Requested, 0x0C04));
        assert_eq!(hs.cycles_in_phase(), 500);
    }

    #[test]
    fn zero_pulse_unsolicited_ack() {
        let steps = run(Zero::new(), zero_ack, &[true, false]);
        assert_eq!(steps, [(UnsolicitedAck, 0x0404), (Idle, 0x0404)]);
        // After Done, a new ack without a request is unsolicited too.
        let steps = run(Zero::new().start(), zero_ack, &[false, true, false, true]);
        assert_eq!(
            steps,
            [
                (Requested, 0x0C04),
                (Acknowledged, 0x0404),
                (Done, 0x0404),
                (UnsolicitedAck, 0x0404)
            ]
        );
    }

    /// The two handshakes only touch their own bit and each other's ack is
    /// invisible to them.
    #[test]
    fn handshakes_are_independent() {
        let clear = Clear::new().start();
        let zero = Zero::new().start();
        let status = clear_ack(true) | zero_ack(false);
        let with_both = ServoControlWord::NORMAL
            | ServoControlWord::ERROR_CLEAR
            | ServoControlWord::Z_PULSE_REQUEST;
        let (clear, _) = clear.step(with_both, status);
        let (zero, _) = zero.step(with_both, status);
        assert_eq!(clear.phase(), Acknowledged);
        assert_eq!(zero.phase(), Requested);
        let next = zero.apply(clear.apply(with_both));
        assert_eq!(next.bits(), 0x0C04);
    }

    #[test]
    fn cycles_in_phase_saturates() {
        let mut hs = Clear::new().start();
        hs.cycles_in_phase = u32::MAX - 1;
        let scw = hs.apply(ServoControlWord::NORMAL);
        let (hs, _) = hs.step(scw, clear_ack(false));
        let (hs, _) = hs.step(scw, clear_ack(false));
        assert_eq!(hs.cycles_in_phase(), u32::MAX);
        assert_eq!(hs.phase(), Requested);
    }

    #[test]
    fn phase_names() {
        let table = [
            (Idle, "idle", false),
            (Requested, "requested", true),
            (Acknowledged, "acknowledged", false),
            (Releasing, "releasing", false),
            (Done, "done", false),
            (UnsolicitedAck, "unsolicited_ack", false),
        ];
        for (phase, name, request) in table {
            assert_eq!(phase.name(), name);
            assert_eq!(phase.to_string(), name);
            assert_eq!(phase.request_bit(), request);
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::{servo_enable, status_word};

    /// A handshake input per cycle: optionally start or cancel, then step
    /// with this status word; `obey` says whether the NC writes what the
    /// handshake returned.
    fn cycle() -> impl Strategy<Value = (u8, bool, ServoStatusWord)> {
        (0u8..8, any::<bool>(), status_word())
    }

    proptest! {
        /// docs/servo.md#handshakes as a model over a whole sequence: after
        /// each cycle the drive is enabled exactly when some earlier cycle made
        /// the edge 0b01 → 0b10 and SE has stayed 0b10 since.
        #[test]
        fn enable_matches_the_sequence_model(ses in proptest::collection::vec(servo_enable(), 1..40)) {
            let mut previous = ServoEnable::DISABLED;
            let mut enabled = false;
            for (now, &se) in ses.iter().enumerate() {
                enabled = drive_enabled(previous, se, enabled);
                previous = se;
                // Model: walk back over the run of 0b10 ending now.
                let run_start = ses[..=now].iter().rposition(|&s| s != ServoEnable::ENABLE);
                let model = match run_start {
                    Some(i) if i < now => ses[i] == ServoEnable::ARM,
                    _ => false,
                };
                prop_assert_eq!(enabled, model, "cycle {}: {:?}", now, &ses[..=now]);
            }
        }

        /// Whatever the drive answers and whether or not the NC obeys,
        /// the handshake writes the request only in Requested, and reports
        /// Acknowledged only when its request was on the wire and the ack up.
        #[test]
        fn handshake_invariants(cycles in proptest::collection::vec(cycle(), 0..60)) {
            let mut hs = ErrorClearHandshake::new();
            let mut written = ServoControlWord::NORMAL;
            for (action, obey, status) in cycles {
                hs = match action {
                    0 => hs.start(),
                    1 => hs.cancel(),
                    _ => hs,
                };
                let before = hs;
                let (next, out) = hs.step(written, status);
                prop_assert_eq!(out.contains(ServoControlWord::ERROR_CLEAR), next.phase() == HandshakePhase::Requested);
                prop_assert_eq!(out.bits() & !0x200, written.bits() & !0x200);
                if next.phase() == HandshakePhase::Acknowledged && before.phase() != HandshakePhase::Acknowledged {
                    prop_assert!(written.contains(ServoControlWord::ERROR_CLEAR));
                    prop_assert!(status.contains(ServoStatusWord::ERR_CLEAR_ACK));
                    prop_assert_eq!(before.phase(), HandshakePhase::Requested);
                }
                if next.phase() == HandshakePhase::Done && before.phase() != HandshakePhase::Done {
                    prop_assert!(!status.contains(ServoStatusWord::ERR_CLEAR_ACK));
                }
                hs = next;
                if obey {
                    written = out;
                }
            }
        }
    }
}
