//! The drive state machine's transitions: the state a command or a drive
//! event leads to, numbered 0–16 as CiA 402's state diagram draws them
//! (CiA 402-2 / IEC 61800-7-201, "drive state machine";
//! docs/canopen.md#cia402). Pure: `(state, event) -> transition`.

use core::fmt;

use super::{Cia402Command, Cia402State};

impl Cia402State {
    /// Return the transition a device-control command causes in this state,
    /// as CiA 402's state diagram and transition table draw it
    /// (docs/canopen.md#cia402), or `None` when the command causes no
    /// transition here (the drive stays where it is: e.g. shutdown in ready to
    /// switch on, any command in not ready to switch on or fault reaction
    /// active).
    ///
    /// | from | command | transition |
    /// |---|---|---|
    /// | switch on disabled | shutdown | 2 → ready to switch on |
    /// | ready to switch on | switch on | 3 → switched on |
    /// | ready to switch on | enable operation | 3+4 → operation enabled |
    /// | ready to switch on | disable voltage, quick stop | 7 → switch on disabled |
    /// | switched on | enable operation | 4 → operation enabled |
    /// | switched on | shutdown | 6 → ready to switch on |
    /// | switched on | disable voltage, quick stop | 10 → switch on disabled |
    /// | operation enabled | disable operation | 5 → switched on |
    /// | operation enabled | shutdown | 8 → ready to switch on |
    /// | operation enabled | disable voltage | 9 → switch on disabled |
    /// | operation enabled | quick stop | 11 → quick stop active |
    /// | quick stop active | disable voltage | 12 → switch on disabled |
    /// | quick stop active | enable operation | 16 → operation enabled |
    /// | fault | fault reset | 15 → switch on disabled |
    ///
    /// [`Cia402Command::SwitchOn`] has no transition from operation enabled:
    /// its bit pattern there is disable operation (transition 5), which
    /// [`Cia402Command::from_controlword`] reports as such. Transition 16 is
    /// taken only by drives whose quick stop option code (605Ah) is 5–8;
    /// the function gives it whenever asked, as the diagram draws it.
    #[must_use]
    pub const fn next(self, command: Cia402Command) -> Option<Cia402Transition> {
        use Cia402Command as C;
        use Cia402State as S;
        use Cia402Transition as T;
        Some(match (self, command) {
            (S::SwitchOnDisabled, C::Shutdown) => T::T2,
            (S::ReadyToSwitchOn, C::SwitchOn) => T::T3,
            (S::ReadyToSwitchOn, C::EnableOperation) => T::T3T4,
            (S::ReadyToSwitchOn, C::DisableVoltage | C::QuickStop) => T::T7,
            (S::SwitchedOn, C::EnableOperation) => T::T4,
            (S::SwitchedOn, C::Shutdown) => T::T6,
            (S::SwitchedOn, C::DisableVoltage | C::QuickStop) => T::T10,
            (S::OperationEnabled, C::DisableOperation) => T::T5,
            (S::OperationEnabled, C::Shutdown) => T::T8,
            (S::OperationEnabled, C::DisableVoltage) => T::T9,
            (S::OperationEnabled, C::QuickStop) => T::T11,
            (S::QuickStopActive, C::DisableVoltage) => T::T12,
            (S::QuickStopActive, C::EnableOperation) => T::T16,
            (S::Fault, C::FaultReset) => T::T15,
            _ => return None,
        })
    }

    /// Return the command a controlword gives in this state after `previous`
    /// ([`Cia402Command::from_controlword`]) and the transition it causes
    /// ([`Cia402State::next`]): the next state from state and controlword
    /// (docs/canopen.md#cia402) in one call. The state afterwards is the
    /// transition's [`Cia402Transition::to`], or `self` when there is none.
    ///
    /// ```
    /// use motionwire_codec::canopen::{Cia402Command, Cia402State, Cia402Transition};
    ///
    /// let state = Cia402State::ReadyToSwitchOn;
    /// let (command, transition) = state.on_controlword(0x000F, Some(0x0006));
    /// assert_eq!(command, Some(Cia402Command::EnableOperation));
    /// assert_eq!(transition, Some(Cia402Transition::T3T4));
    ///
    /// // Bit 7 held at 1: no command, no transition.
    /// assert_eq!(Cia402State::Fault.on_controlword(0x0080, Some(0x0080)), (None, None));
    /// ```
    #[must_use]
    pub const fn on_controlword(
        self,
        controlword: u16,
        previous: Option<u16>,
    ) -> (Option<Cia402Command>, Option<Cia402Transition>) {
        match Cia402Command::from_controlword(controlword, previous, Some(self)) {
            Some(command) => (Some(command), self.next(command)),
            None => (None, None),
        }
    }

    /// Return the transition an event inside the drive causes in this state
    /// (CiA 402's automatic and fault transitions, which no controlword
    /// commands; usable by drive firmware too, docs/canopen.md#cia402), or
    /// `None` when the event causes none here.
    ///
    /// | from | event | transition |
    /// |---|---|---|
    /// | any state | power on | 0 → not ready to switch on |
    /// | not ready to switch on | initialisation complete | 1 → switch on disabled |
    /// | quick stop active | quick stop complete | 12 → switch on disabled |
    /// | any state but fault reaction active and fault | fault | 13 → fault reaction active |
    /// | fault reaction active | fault reaction complete | 14 → fault |
    ///
    /// Drive firmware runs the whole machine with this and
    /// [`Cia402State::on_controlword`], and reports the state in its
    /// statusword with [`Statusword::with_state`](super::Statusword::with_state):
    ///
    /// ```
    /// use motionwire_codec::canopen::{Cia402DriveEvent, Cia402State, Cia402Transition, Statusword};
    ///
    /// let mut state = Cia402Transition::T0.to();
    /// let mut report = Statusword::REMOTE;
    /// for event in [Cia402DriveEvent::InitializationComplete, Cia402DriveEvent::Fault] {
    ///     if let Some(t) = state.on_drive_event(event) {
    ///         state = t.to();
    ///     }
    ///     report = report.with_state(state);
    /// }
    /// assert_eq!(state, Cia402State::FaultReactionActive);
    /// assert_eq!(report.bits(), 0x020F);
    /// ```
    #[must_use]
    pub const fn on_drive_event(self, event: Cia402DriveEvent) -> Option<Cia402Transition> {
        use Cia402DriveEvent as E;
        use Cia402State as S;
        use Cia402Transition as T;
        Some(match (self, event) {
            (_, E::PowerOn) => T::T0,
            (S::NotReadyToSwitchOn, E::InitializationComplete) => T::T1,
            (S::QuickStopActive, E::QuickStopComplete) => T::T12,
            (S::FaultReactionActive | S::Fault, E::Fault) => return None,
            (_, E::Fault) => T::T13,
            (S::FaultReactionActive, E::FaultReactionComplete) => T::T14,
            _ => return None,
        })
    }
}

/// An event inside a drive that moves its state machine without a command:
/// CiA 402's automatic transitions and fault transitions (CiA 402-2 /
/// IEC 61800-7-201, transition table of the drive state machine). A log
/// decoder never sees them as frames; drive firmware feeds them to
/// [`Cia402State::on_drive_event`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cia402DriveEvent {
    /// Power on or application reset: transition 0 from the state diagram's
    /// "start" to not ready to switch on. Accepted in every state, since a
    /// reset ends whatever state the drive was in.
    PowerOn,
    /// The drive finished its initialisation and self-test: transition 1,
    /// not ready to switch on → switch on disabled.
    InitializationComplete,
    /// The quick stop finished in a drive whose quick stop option code
    /// (605Ah) is 1–4: transition 12, quick stop active → switch on disabled.
    QuickStopComplete,
    /// A fault occurred: transition 13 from any state but fault reaction
    /// active and fault to fault reaction active.
    Fault,
    /// The fault reaction finished: transition 14, fault reaction active →
    /// fault.
    FaultReactionComplete,
}

impl Cia402DriveEvent {
    /// Every event, in the order of the transitions they cause.
    pub const ALL: [Cia402DriveEvent; 5] = [
        Cia402DriveEvent::PowerOn,
        Cia402DriveEvent::InitializationComplete,
        Cia402DriveEvent::QuickStopComplete,
        Cia402DriveEvent::Fault,
        Cia402DriveEvent::FaultReactionComplete,
    ];

    /// Return the event's name in lower-case words, as
    /// [`Cia402Command::name`] writes a command's, e.g. `"quick_stop_complete"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Cia402DriveEvent::PowerOn => "power_on",
            Cia402DriveEvent::InitializationComplete => "initialization_complete",
            Cia402DriveEvent::QuickStopComplete => "quick_stop_complete",
            Cia402DriveEvent::Fault => "fault",
            Cia402DriveEvent::FaultReactionComplete => "fault_reaction_complete",
        }
    }
}

impl fmt::Display for Cia402DriveEvent {
    /// Format the event as its [`Cia402DriveEvent::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A transition of the CiA 402 drive state machine, named by its number in
/// the state diagram (CiA 402-2 / IEC 61800-7-201, the drive state machine's
/// diagram and transition table; docs/canopen.md#cia402), plus
/// [`Cia402Transition::T3T4`] for switch on followed at once by enable
/// operation.
///
/// The number fixes the state the transition leads to
/// ([`Cia402Transition::to`]).
///
/// ```
/// use motionwire_codec::canopen::{Cia402Command, Cia402State, Cia402Transition};
///
/// let t = Cia402State::ReadyToSwitchOn.next(Cia402Command::EnableOperation).unwrap();
/// assert_eq!(t, Cia402Transition::T3T4);
/// assert_eq!(t.numbers(), &[3, 4]);
/// assert_eq!(t.to_string(), "3+4");
/// assert_eq!(t.to(), Cia402State::OperationEnabled);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cia402Transition {
    /// 0: start → not ready to switch on (power on, application reset).
    T0,
    /// 1: not ready to switch on → switch on disabled (automatic, after
    /// initialisation).
    T1,
    /// 2: switch on disabled → ready to switch on (shutdown).
    T2,
    /// 3: ready to switch on → switched on (switch on).
    T3,
    /// 4: switched on → operation enabled (enable operation).
    T4,
    /// 5: operation enabled → switched on (disable operation).
    T5,
    /// 6: switched on → ready to switch on (shutdown).
    T6,
    /// 7: ready to switch on → switch on disabled (disable voltage, quick
    /// stop).
    T7,
    /// 8: operation enabled → ready to switch on (shutdown).
    T8,
    /// 9: operation enabled → switch on disabled (disable voltage).
    T9,
    /// 10: switched on → switch on disabled (disable voltage, quick stop).
    T10,
    /// 11: operation enabled → quick stop active (quick stop).
    T11,
    /// 12: quick stop active → switch on disabled (disable voltage, or
    /// automatic when the quick stop completes with option code 1–4).
    T12,
    /// 13: any state but the fault states → fault reaction active (a fault
    /// occurred).
    T13,
    /// 14: fault reaction active → fault (automatic, the fault reaction is
    /// complete).
    T14,
    /// 15: fault → switch on disabled (fault reset).
    T15,
    /// 16: quick stop active → operation enabled (enable operation, quick
    /// stop option code 5–8).
    T16,
    /// 3 + 4: ready to switch on → operation enabled (enable operation,
    /// `0x0F`, in ready to switch on: switch on followed by enable
    /// operation; docs/canopen.md#cia402).
    T3T4,
}

impl Cia402Transition {
    /// Every transition: 0–16 in order, then 3+4.
    pub const ALL: [Cia402Transition; 18] = [
        Cia402Transition::T0,
        Cia402Transition::T1,
        Cia402Transition::T2,
        Cia402Transition::T3,
        Cia402Transition::T4,
        Cia402Transition::T5,
        Cia402Transition::T6,
        Cia402Transition::T7,
        Cia402Transition::T8,
        Cia402Transition::T9,
        Cia402Transition::T10,
        Cia402Transition::T11,
        Cia402Transition::T12,
        Cia402Transition::T13,
        Cia402Transition::T14,
        Cia402Transition::T15,
        Cia402Transition::T16,
        Cia402Transition::T3T4,
    ];

    /// Return the transition numbered `number` in the state diagram (0–16),
    /// or `None` for any other number.
    #[must_use]
    pub const fn from_number(number: u8) -> Option<Cia402Transition> {
        if number <= 16 {
            Some(Self::ALL[number as usize])
        } else {
            None
        }
    }

    /// Return the diagram's numbers of the transition: one number, or
    /// `[3, 4]` for [`Cia402Transition::T3T4`].
    #[must_use]
    pub const fn numbers(self) -> &'static [u8] {
        use Cia402Transition as T;
        match self {
            T::T0 => &[0],
            T::T1 => &[1],
            T::T2 => &[2],
            T::T3 => &[3],
            T::T4 => &[4],
            T::T5 => &[5],
            T::T6 => &[6],
            T::T7 => &[7],
            T::T8 => &[8],
            T::T9 => &[9],
            T::T10 => &[10],
            T::T11 => &[11],
            T::T12 => &[12],
            T::T13 => &[13],
            T::T14 => &[14],
            T::T15 => &[15],
            T::T16 => &[16],
            T::T3T4 => &[3, 4],
        }
    }

    /// Return the state the transition leads to.
    #[must_use]
    pub const fn to(self) -> Cia402State {
        use Cia402State as S;
        use Cia402Transition as T;
        match self {
            T::T0 => S::NotReadyToSwitchOn,
            T::T1 | T::T7 | T::T9 | T::T10 | T::T12 | T::T15 => S::SwitchOnDisabled,
            T::T2 | T::T6 | T::T8 => S::ReadyToSwitchOn,
            T::T3 | T::T5 => S::SwitchedOn,
            T::T4 | T::T16 | T::T3T4 => S::OperationEnabled,
            T::T11 => S::QuickStopActive,
            T::T13 => S::FaultReactionActive,
            T::T14 => S::Fault,
        }
    }
}

impl fmt::Display for Cia402Transition {
    /// The diagram's number, `"5"`, or `"3+4"`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, number) in self.numbers().iter().enumerate() {
            if i > 0 {
                f.write_str("+")?;
            }
            write!(f, "{number}")?;
        }
        Ok(())
    }
}
