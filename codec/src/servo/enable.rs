//! The NC side of the enable handshake on SCW.SE (docs/servo.md#handshakes; the
//! interface manual, "Servo Enable"): [`EnableHandshake`] and its
//! [`EnablePhase`]. The drive's side of the same rule is
//! [`drive_enabled`](super::drive_enabled).

use core::fmt;

use super::{ServoControlWord, ServoEnable, ServoStatusWord};

/// The phase of the NC side of the enable handshake (docs/servo.md#handshakes),
/// and so the SE value the NC writes ([`EnablePhase::servo_enable`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EnablePhase {
    /// No enable wanted: the NC writes SE 0b00 and the drive showed
    /// ServoEn = 0.
    Disabled,
    /// No enable wanted: the NC writes SE 0b00 and waits for the drive to
    /// drop ServoEn (after [`cancel`](EnableHandshake::cancel), or ServoEn
    /// seen although the NC did not enable the drive).
    Disabling,
    /// The NC writes SE 0b01 and waits until 0b01 is on the wire and the
    /// drive shows ServoEn = 0, so that the ServoEn that follows the edge
    /// is the drive's answer to it.
    Arming,
    /// The NC writes SE 0b10 right after 0b01 — the enable edge — and holds
    /// it while waiting for ServoEn. A drive that refuses the edge (the
    /// drive model refuses it while it has an error, docs/servo.md#drive-model)
    /// never answers: holding 0b10 cannot enable it any more, so the caller
    /// bounds the wait with [`EnableHandshake::cycles_in_phase`] and arms again
    /// with `cancel().start()`.
    Enabling,
    /// The drive answered the edge with ServoEn = 1; the NC holds SE 0b10.
    Enabled,
    /// The drive dropped ServoEn while the NC held 0b10 — the drive model
    /// disables itself on any error (docs/servo.md#drive-model). The NC writes
    /// 0b00; a new [`start`](EnableHandshake::start), once the errors are
    /// cleared, arms again.
    Dropped,
}

impl EnablePhase {
    /// Return the phase's name in snake case, e.g. `"enabling"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            EnablePhase::Disabled => "disabled",
            EnablePhase::Disabling => "disabling",
            EnablePhase::Arming => "arming",
            EnablePhase::Enabling => "enabling",
            EnablePhase::Enabled => "enabled",
            EnablePhase::Dropped => "dropped",
        }
    }

    /// Return the SE value the NC writes in this phase (docs/servo.md#scw,
    /// docs/servo.md#handshakes):
    /// 0b01 while arming, 0b10 while enabling and enabled, 0b00 otherwise.
    /// The handshake never writes 0b11.
    #[must_use]
    pub const fn servo_enable(self) -> ServoEnable {
        match self {
            EnablePhase::Disabled | EnablePhase::Disabling | EnablePhase::Dropped => {
                ServoEnable::DISABLED
            }
            EnablePhase::Arming => ServoEnable::ARM,
            EnablePhase::Enabling | EnablePhase::Enabled => ServoEnable::ENABLE,
        }
    }
}

impl fmt::Display for EnablePhase {
    /// Format the phase as its name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The NC side of the enable handshake: SE 0b01, then 0b10 in the next cycle —
/// the edge on which the drive enables — then 0b10 held while ServoEn stays up
/// (docs/servo.md#handshakes; the interface manual, "Servo Enable"). A pure
/// state machine stepped once per NC cycle, like
/// [`ErrorClearHandshake`](super::ErrorClearHandshake) and
/// [`ZeroPulseHandshake`](super::ZeroPulseHandshake): no clock, no I/O, no
/// heap.
///
/// Each cycle, [`step`](Self::step) takes the control word the NC wrote in
/// the previous cycle (so the machine knows which SE value is on the wire)
/// and the newest status word (its ServoEn bit), and returns the new state
/// and the control word to write next — the previous one with SE as the
/// new phase requires. [`apply`](Self::apply) does the same to any other
/// word.
///
/// | phase | SE on the wire | ServoEn | next phase |
/// |---|---|---|---|
/// | Disabled, Dropped | any | 0 | unchanged |
/// | Disabled, Dropped | any | 1 | Disabling |
/// | Disabling | any | 1 | Disabling |
/// | Disabling | any | 0 | Disabled |
/// | Arming | 0b01 | 0 | Enabling |
/// | Arming | 0b01 | 1 | Arming (waiting for the drive to drop ServoEn) |
/// | Arming | 0b00, 0b10, 0b11 | any | Arming (0b01 not written yet) |
/// | Enabling | 0b01 | any | Enabling (the edge is being written) |
/// | Enabling | 0b10 | 0 | Enabling (waiting for the drive) |
/// | Enabling | 0b10 | 1 | Enabled |
/// | Enabling | 0b00, 0b11 | any | Arming (the sequence was broken) |
/// | Enabled | 0b10 | 1 | Enabled |
/// | Enabled | 0b10 | 0 | Dropped |
/// | Enabled | 0b00, 0b01, 0b11 | 1 | Disabling (that value disables the drive) |
/// | Enabled | 0b00, 0b01, 0b11 | 0 | Disabled |
///
/// The machine writes 0b10 only in Enabling and Enabled, which it enters
/// only after 0b01 was on the wire, and leaves as soon as any value but
/// 0b01 or 0b10 is: every 0b10 it writes is the edge or held since the
/// edge, never a 0b10 "not preceded by 0b01" (the decision in
/// docs/servo.md#handshakes).
///
/// The machine assumes the status words arrive in the order the drive sent
/// them. A drive that answers a few cycles late only makes the phases last
/// longer, with one exception: when the NC cancels and starts again within
/// those few cycles, a ServoEn still on its way from the earlier enable can
/// be taken for the answer to the new edge (the Dropped that follows shows
/// it).
///
/// A run against the crate's drive model: enable, a following error that
/// disables the drive, the error clear, and the enable again.
///
/// ```
/// use motionwire_codec::servo::{
///     Command, Drive, DriveConfig, EnableHandshake, EnablePhase, ErrorClearHandshake,
///     ServoControlWord, ServoFault,
/// };
///
/// let mut drive = Drive::new(DriveConfig::default());
/// let mut enable = EnableHandshake::new().start();
/// let mut clear = ErrorClearHandshake::new();
/// let mut scw = ServoControlWord::NORMAL;
/// let mut feedback = drive.cycle(&Command::new(0, scw, 0));
/// let mut phases = vec![enable.phase()];
/// for cycle in 0..20 {
///     if cycle == 8 {
///         drive.inject(ServoFault::FollowerErr); // E09: the drive disables itself
///     }
///     if enable.phase() == EnablePhase::Dropped {
///         // Clear the errors first, then enable again.
///         if feedback.errors.is_empty() {
///             enable = enable.start();
///         } else {
///             clear = clear.start();
///         }
///     }
///     (enable, scw) = enable.step(scw, feedback.status);
///     (clear, scw) = clear.step(scw, feedback.status);
///     feedback = drive.cycle(&Command::new(100, scw, 0));
///     if phases.last() != Some(&enable.phase()) {
///         phases.push(enable.phase());
///     }
/// }
/// use EnablePhase::*;
/// assert_eq!(phases, [Arming, Enabling, Enabled, Dropped, Arming, Enabling, Enabled]);
/// assert!(drive.is_enabled() && feedback.errors.is_empty());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EnableHandshake {
    phase: EnablePhase,
    cycles_in_phase: u32,
}

impl Default for EnableHandshake {
    fn default() -> Self {
        Self::new()
    }
}

impl EnableHandshake {
    /// Return a handshake in [`EnablePhase::Disabled`].
    #[must_use]
    pub const fn new() -> Self {
        Self::enter(EnablePhase::Disabled)
    }

    const fn enter(phase: EnablePhase) -> Self {
        EnableHandshake {
            phase,
            cycles_in_phase: 0,
        }
    }

    /// Return the current phase.
    #[must_use]
    pub const fn phase(self) -> EnablePhase {
        self.phase
    }

    /// Return whether the drive answered the edge and the NC holds it
    /// enabled ([`EnablePhase::Enabled`]).
    #[must_use]
    pub const fn is_enabled(self) -> bool {
        matches!(self.phase, EnablePhase::Enabled)
    }

    /// Return how many [`step`](Self::step)s the handshake has spent in its
    /// current phase (saturating). A caller that wants a timeout compares it
    /// with a number of cycles of its own choosing.
    #[must_use]
    pub const fn cycles_in_phase(self) -> u32 {
        self.cycles_in_phase
    }

    /// Return the SE value the NC must write next (docs/servo.md#scw,
    /// docs/servo.md#handshakes).
    #[must_use]
    pub const fn servo_enable(self) -> ServoEnable {
        self.phase.servo_enable()
    }

    /// Return `command` with SE as this state requires.
    #[must_use]
    pub const fn apply(self, command: ServoControlWord) -> ServoControlWord {
        command.with_servo_enable(self.servo_enable())
    }

    /// Request the enable: from Disabled, Disabling or Dropped, go to
    /// Arming; while arming, enabling or enabled, change nothing (to arm
    /// again after a refused edge, `cancel().start()`).
    #[must_use]
    pub const fn start(self) -> Self {
        match self.phase {
            EnablePhase::Disabled | EnablePhase::Disabling | EnablePhase::Dropped => {
                Self::enter(EnablePhase::Arming)
            }
            EnablePhase::Arming | EnablePhase::Enabling | EnablePhase::Enabled => self,
        }
    }

    /// Withdraw the enable: SE is written 0b00 from now on. From Arming,
    /// Enabling or Enabled go to Disabling, which becomes Disabled once the
    /// drive shows ServoEn = 0; from Dropped (ServoEn is already 0) go to
    /// Disabled; Disabled and Disabling stay.
    #[must_use]
    pub const fn cancel(self) -> Self {
        match self.phase {
            EnablePhase::Disabled | EnablePhase::Disabling => self,
            EnablePhase::Dropped => Self::enter(EnablePhase::Disabled),
            EnablePhase::Arming | EnablePhase::Enabling | EnablePhase::Enabled => {
                Self::enter(EnablePhase::Disabling)
            }
        }
    }

    /// Advance by one NC cycle. `last_command` is the control word written
    /// in the previous cycle, `status` the newest status word. Return the
    /// new state and the control word to write: `last_command` with SE as
    /// the new state requires.
    #[must_use]
    pub const fn step(
        self,
        last_command: ServoControlWord,
        status: ServoStatusWord,
    ) -> (Self, ServoControlWord) {
        let next = self.next(
            last_command.servo_enable(),
            status.contains(ServoStatusWord::SERVO_EN),
        );
        (next, next.apply(last_command))
    }

    /// The transition table of the type's documentation.
    const fn next(self, on_the_wire: ServoEnable, servo_en: bool) -> Self {
        use EnablePhase::*;
        let phase = match (self.phase, on_the_wire.get(), servo_en) {
            (Disabled | Dropped, _, false) => self.phase,
            (Disabled | Dropped, _, true) => Disabling,
            (Disabling, _, true) => Disabling,
            (Disabling, _, false) => Disabled,
            (Arming, 0b01, false) => Enabling,
            (Arming, _, _) => Arming,
            (Enabling, 0b01, _) => Enabling,
            (Enabling, 0b10, false) => Enabling,
            (Enabling, 0b10, true) => Enabled,
            (Enabling, _, _) => Arming,
            (Enabled, 0b10, true) => Enabled,
            (Enabled, 0b10, false) => Dropped,
            (Enabled, _, true) => Disabling,
            (Enabled, _, false) => Disabled,
        };
        if phase as u8 == self.phase as u8 {
            EnableHandshake {
                phase,
                cycles_in_phase: self.cycles_in_phase.saturating_add(1),
            }
        } else {
            Self::enter(phase)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::drive_enabled;

    use EnablePhase::*;

    const SE_OFF: ServoEnable = ServoEnable::DISABLED;
    const SE_ARM: ServoEnable = ServoEnable::ARM;
    const SE_ON: ServoEnable = ServoEnable::ENABLE;
    const SE_BOTH: ServoEnable = ServoEnable::BOTH;

    /// A control word with `se` on the wire.
    fn wire(se: ServoEnable) -> ServoControlWord {
        ServoControlWord::NORMAL.with_servo_enable(se)
    }

    /// A status word with ServoEn = `en` and some unrelated bits.
    fn servo_en(en: bool) -> ServoStatusWord {
        (ServoStatusWord::SERVO_RDY | ServoStatusWord::N_ZERO)
            .with_flag(ServoStatusWord::SERVO_EN, en)
    }

    /// A handshake in `phase`.
    fn at(phase: EnablePhase) -> EnableHandshake {
        EnableHandshake::enter(phase)
    }

    /// Step a handshake in `phase` once; give the new phase and the SE it
    /// writes.
    fn step(phase: EnablePhase, on_the_wire: ServoEnable, en: bool) -> (EnablePhase, ServoEnable) {
        let (next, out) = at(phase).step(wire(on_the_wire), servo_en(en));
        assert_eq!(
            out.bits() & !0b11,
            ServoControlWord::NORMAL.bits(),
            "only SE changes"
        );
        (next.phase(), out.servo_enable())
    }

    /// The type's transition table, row by row, for every SE value the
    /// rows cover: (phase, SE on the wire, ServoEn, next phase).
    const TABLE: [(EnablePhase, &[u8], bool, EnablePhase); 20] = [
        (Disabled, &[0, 1, 2, 3], false, Disabled),
        (Dropped, &[0, 1, 2, 3], false, Dropped),
        (Disabled, &[0, 1, 2, 3], true, Disabling),
        (Dropped, &[0, 1, 2, 3], true, Disabling),
        (Disabling, &[0, 1, 2, 3], true, Disabling),
        (Disabling, &[0, 1, 2, 3], false, Disabled),
        (Arming, &[1], false, Enabling),
        (Arming, &[1], true, Arming),
        (Arming, &[0, 2, 3], false, Arming),
        (Arming, &[0, 2, 3], true, Arming),
        (Enabling, &[1], false, Enabling),
        (Enabling, &[1], true, Enabling),
        (Enabling, &[2], false, Enabling),
        (Enabling, &[2], true, Enabled),
        (Enabling, &[0, 3], false, Arming),
        (Enabling, &[0, 3], true, Arming),
        (Enabled, &[2], true, Enabled),
        (Enabled, &[2], false, Dropped),
        (Enabled, &[0, 1, 3], true, Disabling),
        (Enabled, &[0, 1, 3], false, Disabled),
    ];

    #[test]
    fn transition_table() {
        let mut seen = Vec::new();
        for (phase, values, en, expected) in TABLE {
            for &raw in values {
                let se = ServoEnable::new(raw).unwrap();
                let (next, written) = step(phase, se, en);
                assert_eq!(
                    next, expected,
                    "{phase} with {se} on the wire, ServoEn {en}"
                );
                assert_eq!(written, expected.servo_enable());
                seen.push((phase, raw, en));
            }
        }
        // Every (phase, SE, ServoEn) is covered exactly once.
        seen.sort_by_key(|&(p, raw, en)| (p as u8, raw, en));
        seen.dedup();
        assert_eq!(seen.len(), 6 * 4 * 2);
    }

    #[test]
    fn start_arms_from_disabled_disabling_and_dropped() {
        for phase in [Disabled, Disabling, Dropped] {
            let mut hs = at(phase);
            hs.cycles_in_phase = 7;
            let started = hs.start();
            assert_eq!(started.phase(), Arming);
            assert_eq!(started.cycles_in_phase(), 0);
            assert_eq!(started.servo_enable(), SE_ARM);
        }
    }

    #[test]
    fn start_while_arming_enabling_or_enabled_changes_nothing() {
        for phase in [Arming, Enabling, Enabled] {
            let mut hs = at(phase);
            hs.cycles_in_phase = 7;
            assert_eq!(hs.start(), hs);
        }
    }

    #[test]
    fn cancel_writes_disabled_and_waits_for_servo_en_to_drop() {
        for phase in [Arming, Enabling, Enabled] {
            let hs = at(phase).cancel();
            assert_eq!((hs.phase(), hs.servo_enable()), (Disabling, SE_OFF));
            let (hs, out) = hs.step(wire(SE_ON), servo_en(true));
            assert_eq!((hs.phase(), out.servo_enable()), (Disabling, SE_OFF));
            let (hs, _) = hs.step(out, servo_en(false));
            assert_eq!(hs.phase(), Disabled);
        }
        assert_eq!(at(Dropped).cancel().phase(), Disabled);
        assert_eq!(at(Disabled).cancel(), at(Disabled));
        assert_eq!(at(Disabling).cancel(), at(Disabling));
    }

    /// docs/servo.md#handshakes from the NC's side: 0b01, then 0b10 in the next
    /// cycle, then 0b10 held; a drive without lag answers ServoEn in the cycle
    /// that carried the edge.
    #[test]
    fn disabled_to_enabled_sequence() {
        let mut hs = EnableHandshake::new().start();
        let mut scw = ServoControlWord::NORMAL;
        let mut drive_se = SE_OFF;
        let mut drive_on = false;
        let mut trace = Vec::new();
        for _ in 0..5 {
            (hs, scw) = hs.step(scw, servo_en(drive_on));
            drive_on = drive_enabled(drive_se, scw.servo_enable(), drive_on);
            drive_se = scw.servo_enable();
            trace.push((hs.phase(), scw.servo_enable(), drive_on));
        }
        assert_eq!(
            trace,
            [
                (Arming, SE_ARM, false),
                (Enabling, SE_ON, true), // the edge: the drive enables
                (Enabled, SE_ON, true),  // ServoEn seen
                (Enabled, SE_ON, true),
                (Enabled, SE_ON, true),
            ]
        );
        assert!(hs.is_enabled());
        assert_eq!(hs.cycles_in_phase(), 2);
    }

    /// A drive that answers two cycles late: the phases last longer, the
    /// sequence on the wire is the same.
    #[test]
    fn enabling_waits_for_a_late_servo_en() {
        let mut hs = EnableHandshake::new().start();
        let mut scw = ServoControlWord::NORMAL;
        let answers = [false, false, false, false, true, true];
        let mut trace = Vec::new();
        for en in answers {
            (hs, scw) = hs.step(scw, servo_en(en));
            trace.push((hs.phase(), scw.servo_enable()));
        }
        assert_eq!(
            trace,
            [
                (Arming, SE_ARM),
                (Enabling, SE_ON),
                (Enabling, SE_ON),
                (Enabling, SE_ON),
                (Enabled, SE_ON),
                (Enabled, SE_ON),
            ]
        );
    }

    /// The drive was enabled before the NC started (a restarted NC): the
    /// handshake arms, and makes the edge only once the drive shows that
    /// 0b01 disabled it.
    #[test]
    fn arming_waits_for_servo_en_to_drop() {
        let mut hs = EnableHandshake::new();
        let mut scw = wire(SE_ON);
        (hs, scw) = hs.step(scw, servo_en(true));
        assert_eq!((hs.phase(), scw.servo_enable()), (Disabling, SE_OFF));
        hs = hs.start();
        (hs, scw) = hs.step(scw, servo_en(true));
        assert_eq!((hs.phase(), scw.servo_enable()), (Arming, SE_ARM));
        (hs, scw) = hs.step(scw, servo_en(true));
        assert_eq!((hs.phase(), scw.servo_enable()), (Arming, SE_ARM));
        (hs, scw) = hs.step(scw, servo_en(false));
        assert_eq!((hs.phase(), scw.servo_enable()), (Enabling, SE_ON));
        (hs, _) = hs.step(scw, servo_en(true));
        assert_eq!(hs.phase(), Enabled);
    }

    /// The NC did not write what the handshake asked for: it keeps asking,
    /// and a broken sequence arms again instead of writing a 0b10 that
    /// does not follow 0b01.
    #[test]
    fn arming_and_enabling_when_the_nc_writes_something_else() {
        assert_eq!(step(Arming, SE_OFF, false), (Arming, SE_ARM));
        assert_eq!(step(Arming, SE_ON, false), (Arming, SE_ARM));
        assert_eq!(step(Enabling, SE_ARM, false), (Enabling, SE_ON));
        assert_eq!(step(Enabling, SE_OFF, false), (Arming, SE_ARM));
        assert_eq!(step(Enabling, SE_BOTH, true), (Arming, SE_ARM));
    }

    /// The drive dropped ServoEn while the NC held 0b10: a fault.
    #[test]
    fn enabled_to_dropped_when_servo_en_falls() {
        assert_eq!(step(Enabled, SE_ON, false), (Dropped, SE_OFF));
        // Dropped stays, writing 0b00, until a new start.
        let (hs, out) = at(Dropped).step(wire(SE_OFF), servo_en(false));
        assert_eq!((hs.phase(), out.servo_enable()), (Dropped, SE_OFF));
        assert_eq!(hs.cycles_in_phase(), 1);
        assert_eq!(hs.start().phase(), Arming);
    }

    /// Another SE value on the wire disables the drive
    /// (docs/servo.md#handshakes): the enable is withdrawn, not dropped by the
    /// drive.
    #[test]
    fn enabled_to_disabling_when_another_value_is_on_the_wire() {
        for se in [SE_OFF, SE_ARM, SE_BOTH] {
            assert_eq!(step(Enabled, se, true), (Disabling, SE_OFF));
            assert_eq!(step(Enabled, se, false), (Disabled, SE_OFF));
        }
    }

    /// ServoEn without an enable of the NC's: reported, and 0b00 written
    /// until it drops.
    #[test]
    fn disabled_to_disabling_when_servo_en_is_up() {
        assert_eq!(step(Disabled, SE_OFF, true), (Disabling, SE_OFF));
        assert_eq!(step(Dropped, SE_OFF, true), (Disabling, SE_OFF));
        assert_eq!(step(Disabling, SE_OFF, true), (Disabling, SE_OFF));
        assert_eq!(step(Disabling, SE_OFF, false), (Disabled, SE_OFF));
    }

    /// A drive that refuses the edge never answers; holding 0b10 is
    /// useless, the caller times out and arms again.
    #[test]
    fn enabling_refused_times_out_and_arms_again() {
        let mut hs = EnableHandshake::new().start();
        let mut scw = ServoControlWord::NORMAL;
        (hs, scw) = hs.step(scw, servo_en(false));
        (hs, scw) = hs.step(scw, servo_en(false));
        for cycle in 1..=300u32 {
            (hs, scw) = hs.step(scw, servo_en(false));
            assert_eq!((hs.phase(), scw.servo_enable()), (Enabling, SE_ON));
            assert_eq!(hs.cycles_in_phase(), cycle);
        }
        hs = hs.cancel().start();
        assert_eq!(hs.phase(), Arming);
        (hs, scw) = hs.step(scw, servo_en(false));
        assert_eq!((hs.phase(), scw.servo_enable()), (Arming, SE_ARM));
        (hs, scw) = hs.step(scw, servo_en(false));
        assert_eq!((hs.phase(), scw.servo_enable()), (Enabling, SE_ON));
    }

    #[test]
    fn cycles_in_phase_saturates() {
        let mut hs = at(Enabled);
        hs.cycles_in_phase = u32::MAX - 1;
        let (hs, _) = hs.step(wire(SE_ON), servo_en(true));
        let (hs, _) = hs.step(wire(SE_ON), servo_en(true));
        assert_eq!(hs.cycles_in_phase(), u32::MAX);
        assert_eq!(hs.phase(), Enabled);
    }

    #[test]
    fn phase_names_and_se_values() {
        let table = [
            (Disabled, "disabled", SE_OFF),
            (Disabling, "disabling", SE_OFF),
            (Arming, "arming", SE_ARM),
            (Enabling, "enabling", SE_ON),
            (Enabled, "enabled", SE_ON),
            (Dropped, "dropped", SE_OFF),
        ];
        for (phase, name, se) in table {
            assert_eq!(phase.name(), name);
            assert_eq!(phase.to_string(), name);
            assert_eq!(phase.servo_enable(), se);
            assert_eq!(at(phase).servo_enable(), se);
            assert_eq!(at(phase).apply(wire(SE_BOTH)), wire(se));
            assert_eq!(at(phase).is_enabled(), phase == Enabled);
        }
        assert_eq!(EnableHandshake::default(), EnableHandshake::new());
        assert_eq!(EnableHandshake::new().phase(), Disabled);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::servo::drive_enabled;
    use crate::strategies::servo::{servo_enable, status_word};

    /// One cycle: the NC's wish (0 start, 1 cancel, else nothing), whether
    /// it writes what the handshake returned or `other`, and the drive's
    /// status word.
    fn cycle() -> impl Strategy<Value = (u8, bool, ServoEnable, ServoStatusWord)> {
        (0u8..6, any::<bool>(), servo_enable(), status_word())
    }

    proptest! {
        /// Whatever the drive answers and whatever the NC writes instead,
        /// the handshake writes SE as its phase says, 0b10 only when it
        /// would enable a drive (the edge or held since the edge, on the
        /// wire), and enters each phase only as the table allows.
        #[test]
        fn every_written_enable_follows_an_arm(cycles in proptest::collection::vec(cycle(), 0..80)) {
            let mut hs = EnableHandshake::new();
            let mut written = ServoControlWord::NORMAL;
            // What a drive that accepts every edge would say about the wire.
            let mut would_enable = false;
            for (wish, obey, other, status) in cycles {
                hs = match wish {
                    0 => hs.start(),
                    1 => hs.cancel(),
                    _ => hs,
                };
                let before = hs;
                let (next, out) = hs.step(written, status);
                let on_the_wire = written.servo_enable();
                let en = status.contains(ServoStatusWord::SERVO_EN);
                prop_assert_eq!(out.bits() & !0b11, written.bits() & !0b11);
                prop_assert_eq!(out.servo_enable(), next.phase().servo_enable());
                prop_assert_ne!(out.servo_enable(), ServoEnable::BOTH);
                if out.servo_enable() == ServoEnable::ENABLE {
                    prop_assert!(drive_enabled(on_the_wire, ServoEnable::ENABLE, would_enable));
                }
                let (from, to) = (before.phase(), next.phase());
                if from == to {
                    prop_assert_eq!(next.cycles_in_phase(), before.cycles_in_phase().saturating_add(1));
                } else {
                    prop_assert_eq!(next.cycles_in_phase(), 0);
                    match to {
                        EnablePhase::Enabling => prop_assert!(from == EnablePhase::Arming && on_the_wire == ServoEnable::ARM && !en),
                        EnablePhase::Enabled => prop_assert!(from == EnablePhase::Enabling && on_the_wire == ServoEnable::ENABLE && en),
                        EnablePhase::Dropped => prop_assert!(from == EnablePhase::Enabled && on_the_wire == ServoEnable::ENABLE && !en),
                        EnablePhase::Arming => prop_assert!(from == EnablePhase::Enabling && on_the_wire != ServoEnable::ARM && on_the_wire != ServoEnable::ENABLE),
                        EnablePhase::Disabling => prop_assert!(en),
                        EnablePhase::Disabled => prop_assert!(!en),
                    }
                }
                hs = next;
                let now = if obey { out } else { written.with_servo_enable(other) };
                would_enable = drive_enabled(on_the_wire, now.servo_enable(), would_enable);
                written = now;
            }
        }

        /// Against a drive that follows docs/servo.md#handshakes and refuses
        /// the edge while faulted (docs/servo.md#drive-model), answering `lag`
        /// cycles late: an obedient NC's handshake is Enabled only on the
        /// drive's ServoEn, and a start not disturbed by a fault or a cancel
        /// leaves Arming and Enabling within a few cycles.
        #[test]
        fn against_a_lagging_drive(
            lag in 0usize..4,
            script in proptest::collection::vec((0u8..20, prop::bool::weighted(0.05)), 1..120),
        ) {
            let mut hs = EnableHandshake::new();
            let mut scw = ServoControlWord::NORMAL;
            let (mut previous_se, mut on) = (ServoEnable::DISABLED, false);
            // The drive's answers not yet delivered, oldest first.
            let mut in_flight = std::collections::VecDeque::from(vec![false; lag]);
            // Cycles since a start that armed, while nothing disturbed it.
            let mut since_start: Option<usize> = None;
            for (wish, fault) in script {
                let resting = matches!(hs.phase(), EnablePhase::Disabled | EnablePhase::Disabling | EnablePhase::Dropped);
                match wish {
                    0 => {
                        hs = hs.start();
                        if resting {
                            since_start = Some(0);
                        }
                    }
                    1 => {
                        hs = hs.cancel();
                        since_start = None;
                    }
                    _ => {}
                }
                in_flight.push_back(on);
                let delivered = in_flight.pop_front().unwrap_or(on);
                let status = ServoStatusWord::empty().with_flag(ServoStatusWord::SERVO_EN, delivered);
                (hs, scw) = hs.step(scw, status);
                // The drive's cycle.
                on = drive_enabled(previous_se, scw.servo_enable(), on) && !fault;
                previous_se = scw.servo_enable();
                if hs.is_enabled() {
                    prop_assert!(delivered, "Enabled only on the drive's ServoEn");
                }
                if fault {
                    since_start = None;
                }
                if let Some(n) = since_start.as_mut() {
                    *n += 1;
                    let waiting = matches!(hs.phase(), EnablePhase::Arming | EnablePhase::Enabling);
                    prop_assert!(!waiting || *n <= 3 + 2 * lag, "still {} after {} cycles, lag {}", hs.phase(), n, lag);
                }
            }
        }
    }
}
