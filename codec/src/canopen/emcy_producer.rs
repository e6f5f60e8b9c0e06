//! The EMCY error state machine, producer side (docs/canopen.md#emcy-producer;
//! the Kollmorgen AKD CANopen manual, "Application of the Emergency Object";
//! CiA 301 §7.2.7.2).
//!
//! A device tells [`EmcyProducer`] what happens to it as [`EmcyEvent`]s: it was
//! initialised, an error occurred, one error was reset, all errors were reset.
//! [`EmcyProducer::step`] is a pure function of the state and the event: it
//! returns the next state and an [`EmcyOutcome`] that holds the EMCY to send
//! (if any), the number of the transition taken (0–4,
//! docs/canopen.md#emcy-producer), and an overflow report when the fixed
//! capacity for active errors was exceeded. There is no clock, no I/O and no
//! heap: the active errors live in an array of `N` slots (default
//! [`DEFAULT_ACTIVE_ERRORS`]).
//!
//! The rules, the **Decision**s taken where CiA 301 leaves a choice
//! (docs/canopen.md#emcy-producer), and an example are on [`EmcyProducer`].

use core::fmt;

use super::{Emcy, ErrorCode, ErrorRegister};

/// The default number of active errors an [`EmcyProducer`] tracks, 8.
///
/// The active errors are held in a fixed capacity
/// (docs/canopen.md#emcy-producer) of no set size (**Decision**: 8, enough for
/// one error of each register class bit at once; a device that needs more
/// chooses its own `N`).
pub const DEFAULT_ACTIVE_ERRORS: usize = 8;

/// The two error conditions of the EMCY state machine (the AKD CANopen manual:
/// "The error conditions error-free and error occurred are distinguished";
/// docs/canopen.md#emcy-producer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorCondition {
    /// No error is active; the error register reads 0x00.
    ErrorFree,
    /// At least one error is (or, after a capacity overflow, may be) active.
    ErrorOccurred,
}

impl ErrorCondition {
    /// Return the condition's name as docs/canopen.md#emcy-producer names it,
    /// e.g. `"error-free"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            ErrorCondition::ErrorFree => "error-free",
            ErrorCondition::ErrorOccurred => "error-occurred",
        }
    }
}

impl fmt::Display for ErrorCondition {
    /// Format the condition as its name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A transition of the EMCY state machine, numbered as in
/// docs/canopen.md#emcy-producer and the AKD CANopen manual ("Transition 0"
/// … "Transition 4").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum EmcyTransition {
    /// 0: (init) → error-free; initialisation, no EMCY.
    Initialised = 0,
    /// 1: error-free → error-occurred; an error is detected.
    FirstError = 1,
    /// 2: error-occurred → error-occurred; one error is reset, others remain.
    ErrorReset = 2,
    /// 3: error-occurred → error-occurred; a further error occurs.
    FurtherError = 3,
    /// 4: error-occurred → error-free; the last error (or all errors) reset.
    AllErrorsReset = 4,
}

impl EmcyTransition {
    /// Return the transition's number, 0–4, as in
    /// docs/canopen.md#emcy-producer.
    #[must_use]
    pub const fn number(self) -> u8 {
        self as u8
    }

    /// Return the transition numbered `number`, or `None` outside 0–4.
    #[must_use]
    pub const fn from_number(number: u8) -> Option<Self> {
        match number {
            0 => Some(EmcyTransition::Initialised),
            1 => Some(EmcyTransition::FirstError),
            2 => Some(EmcyTransition::ErrorReset),
            3 => Some(EmcyTransition::FurtherError),
            4 => Some(EmcyTransition::AllErrorsReset),
            _ => None,
        }
    }

    /// Return the condition the machine is in after this transition
    /// (the transitions of docs/canopen.md#emcy-producer).
    #[must_use]
    pub const fn target(self) -> ErrorCondition {
        match self {
            EmcyTransition::Initialised | EmcyTransition::AllErrorsReset => {
                ErrorCondition::ErrorFree
            }
            EmcyTransition::FirstError
            | EmcyTransition::ErrorReset
            | EmcyTransition::FurtherError => ErrorCondition::ErrorOccurred,
        }
    }
}

impl fmt::Display for EmcyTransition {
    /// Format the transition as `transition 3`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "transition {}", self.number())
    }
}

/// What happens to the device, as the EMCY state machine sees it
/// (the events of the transitions of docs/canopen.md#emcy-producer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EmcyEvent {
    /// The device was initialised (or re-initialised) and detects no error:
    /// transition 0 from any state.
    Initialised,
    /// An error occurred.
    ErrorOccurred {
        /// The error's emergency error code (docs/canopen.md#emcy-codes). A
        /// reset code (0x00xx) is refused, see [`EmcyProducer`].
        code: ErrorCode,
        /// The error-register bits this error contributes; `None` derives
        /// them from the code ([`ErrorCode::register_class_bits`]). Bit 0 is
        /// added by the machine whenever any error is active; the reserved
        /// bit 6 is ignored.
        register: Option<ErrorRegister>,
        /// The manufacturer-specific error field sent with this error's EMCY
        /// (bytes 3–7, docs/canopen.md#emcy; the AKD layout is
        /// docs/canopen.md#akd).
        manufacturer: [u8; 5],
    },
    /// The error with this code is no longer present.
    ErrorReset {
        /// The code of the error that went away.
        code: ErrorCode,
        /// The manufacturer-specific field of the reset EMCY: `None` sends a
        /// zero field, as a generic device does
        /// (docs/canopen.md#emcy-producer); a device profile that names the
        /// error's source in reset EMCYs too (the AKD keeps its axis id in byte
        /// 3, docs/canopen.md#akd) passes it here.
        manufacturer: Option<[u8; 5]>,
    },
    /// Every error is gone (e.g. after a fault reset).
    AllErrorsReset,
}

impl EmcyEvent {
    /// Return an [`EmcyEvent::ErrorOccurred`] whose register bits are derived
    /// from the code.
    #[must_use]
    pub const fn error(code: ErrorCode, manufacturer: [u8; 5]) -> Self {
        EmcyEvent::ErrorOccurred {
            code,
            register: None,
            manufacturer,
        }
    }

    /// Return an [`EmcyEvent::ErrorOccurred`] with register bits supplied by
    /// the caller.
    #[must_use]
    pub const fn error_with_register(
        code: ErrorCode,
        register: ErrorRegister,
        manufacturer: [u8; 5],
    ) -> Self {
        EmcyEvent::ErrorOccurred {
            code,
            register: Some(register),
            manufacturer,
        }
    }

    /// Return an [`EmcyEvent::ErrorReset`] for `code` whose reset EMCY has
    /// a zero manufacturer field (docs/canopen.md#emcy-producer).
    #[must_use]
    pub const fn reset(code: ErrorCode) -> Self {
        EmcyEvent::ErrorReset {
            code,
            manufacturer: None,
        }
    }

    /// Return an [`EmcyEvent::ErrorReset`] for `code` whose reset EMCY
    /// carries `manufacturer`, e.g. the AKD's axis and feedback ids
    /// (docs/canopen.md#akd).
    ///
    /// ```
    /// use motionwire_codec::canopen::{EmcyEvent, EmcyProducer, ErrorCode};
    /// use motionwire_codec::profiles::akd::{AkdManufacturer, AxisId, FeedbackId};
    ///
    /// let axis_2 = AkdManufacturer::new(AxisId::try_new(2)?, FeedbackId::None).to_bytes();
    /// let mut producer = EmcyProducer::new();
    /// let _ = producer.apply(EmcyEvent::error(ErrorCode::new(0x4310), axis_2));
    /// let out = producer.apply(EmcyEvent::reset_with(ErrorCode::new(0x4310), axis_2));
    /// assert_eq!(out.emcy().unwrap().to_bytes(), [0x00, 0x00, 0x00, 0x02, 0, 0, 0, 0]);
    /// # Ok::<(), motionwire_codec::Error>(())
    /// ```
    #[must_use]
    pub const fn reset_with(code: ErrorCode, manufacturer: [u8; 5]) -> Self {
        EmcyEvent::ErrorReset {
            code,
            manufacturer: Some(manufacturer),
        }
    }
}

impl fmt::Display for EmcyEvent {
    /// Format the event in words: `initialised`, `error occurred: 0x4310
    /// Excess device temperature` (with `, register …` when the caller gives
    /// the bits and `, manufacturer …` when the field is not all zero, as
    /// [`Emcy`] writes them), `error reset: 0x4310 …`, `all errors reset`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            EmcyEvent::Initialised => f.write_str("initialised"),
            EmcyEvent::ErrorOccurred {
                code,
                register,
                manufacturer,
            } => {
                write!(f, "error occurred: {code} {}", code.description())?;
                if let Some(register) = register {
                    write!(f, ", register {register}")?;
                }
                write_manufacturer(f, Some(manufacturer))
            }
            EmcyEvent::ErrorReset { code, manufacturer } => {
                write!(f, "error reset: {code} {}", code.description())?;
                write_manufacturer(f, manufacturer)
            }
            EmcyEvent::AllErrorsReset => f.write_str("all errors reset"),
        }
    }
}

/// `, manufacturer 0100000000` for a field that is not all zero, as [`Emcy`]
/// writes its bytes.
fn write_manufacturer(f: &mut fmt::Formatter<'_>, field: Option<[u8; 5]>) -> fmt::Result {
    match field {
        Some(bytes) if bytes != [0; 5] => {
            f.write_str(", manufacturer ")?;
            for byte in bytes {
                write!(f, "{byte:02x}")?;
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

/// Why an event caused no transition and sent nothing (the Decisions of
/// docs/canopen.md#emcy-producer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum IgnoredEvent {
    /// The error that occurred is already active.
    AlreadyActive,
    /// The error that was reset is not active (or was never tracked, after a
    /// capacity overflow; a reset code 0x00xx is never active).
    NotActive,
    /// "All errors reset" while already error-free.
    AlreadyErrorFree,
    /// An "error occurred" event carried a reset code (0x00xx), which names
    /// no error (**Decision**, see [`EmcyProducer`]).
    ResetCodeIsNotAnError,
}

impl IgnoredEvent {
    /// Return the reason in words, e.g. `"the error is already active"`.
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            IgnoredEvent::AlreadyActive => "the error is already active",
            IgnoredEvent::NotActive => "the error is not active",
            IgnoredEvent::AlreadyErrorFree => "already error-free",
            IgnoredEvent::ResetCodeIsNotAnError => "a reset code (0x00xx) names no error",
        }
    }
}

impl fmt::Display for IgnoredEvent {
    /// Format the reason as its [`IgnoredEvent::description`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.description())
    }
}

/// What one step of the EMCY state machine produced
/// (docs/canopen.md#emcy-producer: `(state, event) → (state, Option<EMCY>,
/// transition number)`), as one of the things that can happen — never a
/// combination that cannot.
///
/// ```
/// use motionwire_codec::canopen::{EmcyEvent, EmcyOutcome, EmcyProducer, EmcyTransition, ErrorCode, IgnoredEvent};
///
/// let mut producer = EmcyProducer::new();
/// let code = ErrorCode::new(0x4310);
/// let out = producer.apply(EmcyEvent::error(code, [0; 5]));
/// assert!(matches!(out, EmcyOutcome::Sent { transition: EmcyTransition::FirstError, .. }));
/// assert_eq!(out.emcy().map(|e| e.code), Some(code));
/// let again = producer.apply(EmcyEvent::error(code, [0; 5]));
/// assert_eq!(again, EmcyOutcome::Ignored(IgnoredEvent::AlreadyActive));
/// assert_eq!((again.emcy(), again.transition()), (None, None));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[must_use]
pub enum EmcyOutcome {
    /// Transition 0: the machine starts over error-free; nothing is sent.
    Initialised,
    /// Transition 1–4 was taken; send `emcy`.
    Sent {
        /// The transition taken.
        transition: EmcyTransition,
        /// The EMCY to send.
        emcy: Emcy,
    },
    /// Transition 1 or 2 was taken and `emcy` must be sent, but the error
    /// cannot be tracked: all `N` slots hold other active errors
    /// (docs/canopen.md#emcy-producer: the EMCY is still produced and the
    /// overflow reported). Its code is `emcy.code`.
    SentUntracked {
        /// The transition taken.
        transition: EmcyTransition,
        /// The EMCY to send.
        emcy: Emcy,
    },
    /// The event caused no transition and sends nothing.
    Ignored(IgnoredEvent),
}

impl EmcyOutcome {
    /// Return the EMCY to send, if any.
    #[must_use]
    pub const fn emcy(&self) -> Option<Emcy> {
        match *self {
            EmcyOutcome::Sent { emcy, .. } | EmcyOutcome::SentUntracked { emcy, .. } => Some(emcy),
            EmcyOutcome::Initialised | EmcyOutcome::Ignored(_) => None,
        }
    }

    /// Return the transition taken, if any.
    #[must_use]
    pub const fn transition(&self) -> Option<EmcyTransition> {
        match *self {
            EmcyOutcome::Initialised => Some(EmcyTransition::Initialised),
            EmcyOutcome::Sent { transition, .. }
            | EmcyOutcome::SentUntracked { transition, .. } => Some(transition),
            EmcyOutcome::Ignored(_) => None,
        }
    }

    /// Return the code of an error that could not be tracked, if any.
    #[must_use]
    pub const fn overflow(&self) -> Option<ErrorCode> {
        match *self {
            EmcyOutcome::SentUntracked { emcy, .. } => Some(emcy.code),
            _ => None,
        }
    }

    /// Return why the event caused no transition, if it caused none.
    #[must_use]
    pub const fn ignored(&self) -> Option<IgnoredEvent> {
        match *self {
            EmcyOutcome::Ignored(reason) => Some(reason),
            _ => None,
        }
    }

    const fn sent(transition: EmcyTransition, emcy: Emcy) -> Self {
        EmcyOutcome::Sent { transition, emcy }
    }
}

impl fmt::Display for EmcyOutcome {
    /// Format the outcome as the transition and what it sends:
    /// `transition 0: nothing sent`, `transition 1: send EMCY 0x4310 …` (the
    /// [`Emcy`] as it writes itself), the same with `(overflow: 0x4310 not
    /// tracked)` for an error that could not be tracked, `ignored: the error
    /// is already active`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            EmcyOutcome::Initialised => {
                write!(f, "{}: nothing sent", EmcyTransition::Initialised)
            }
            EmcyOutcome::Sent { transition, emcy } => write!(f, "{transition}: send {emcy}"),
            EmcyOutcome::SentUntracked { transition, emcy } => write!(
                f,
                "{transition}: send {emcy} (overflow: {} not tracked)",
                emcy.code
            ),
            EmcyOutcome::Ignored(reason) => write!(f, "ignored: {reason}"),
        }
    }
}

/// One active error: its code and the error-register bits it contributes
/// (docs/canopen.md#emcy-producer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ActiveError {
    code: ErrorCode,
    register: ErrorRegister,
}

impl ActiveError {
    /// The filler of an unused slot; never reported as active.
    const VACANT: ActiveError = ActiveError {
        code: ErrorCode::NO_ERROR,
        register: ErrorRegister::empty(),
    };

    /// Return the error's emergency error code.
    #[must_use]
    pub const fn code(self) -> ErrorCode {
        self.code
    }

    /// Return the error-register bits this error contributes (without bit 0,
    /// which the machine sets whenever any error is active).
    #[must_use]
    pub const fn register(self) -> ErrorRegister {
        self.register
    }
}

/// The EMCY error state machine of a producer, holding up to `N` active errors
/// (docs/canopen.md#emcy-producer; the AKD CANopen manual; CiA 301 §7.2.7.2).
///
/// The value is the state: it is `Copy`, and two states compare equal when
/// they hold the same active errors with the same register contributions
/// (the order in which the errors occurred does not matter) and the same
/// untracked-overflow memory.
///
/// The rules, with the **Decision**s taken where CiA 301 leaves a choice
/// (docs/canopen.md#emcy-producer):
///
/// - The error register (object 1001h) has bit 0 set whenever any error is
///   active; its class bits are the union of every active error's
///   *contribution*: the bits the caller supplied for that error, or else
///   [`ErrorCode::register_class_bits`] (docs/canopen.md#emcy-producer). The
///   reserved bit 6 is always cleared from a contribution
///   (docs/canopen.md#error-register: always 0 when produced).
/// - Transitions 1 and 3 send the error's code, the accumulated register of
///   all active errors including the new one, and the error's manufacturer
///   bytes. Transition 2 sends code 0x0000, the register of the remaining
///   errors and a zero manufacturer area; transition 4 sends code 0x0000,
///   register 0x00 and a zero manufacturer area.
/// - An error that is already active occurring again sends nothing and leaves
///   the state as it is (the first report's register contribution stays).
///   Resetting an error that is not active sends nothing. "All errors reset"
///   from error-occurred is transition 4; from error-free it sends nothing.
/// - **Decision:** an "error occurred" event whose code is a reset code
///   (0x00xx, docs/canopen.md#emcy-codes) is refused: nothing is sent and the
///   state is unchanged ([`IgnoredEvent::ResetCodeIsNotAnError`]). Treating it
///   as "reset all" would let one wrong call clear real faults from the error
///   register; a device that means "all errors are gone" says
///   [`EmcyEvent::AllErrorsReset`].
/// - **Decision (capacity overflow):** when an error occurs while all `N`
///   slots hold other active errors, its EMCY is still sent, with the
///   register accumulated with that error's bits, and
///   [`EmcyOutcome::overflow`] names its code. The error is not tracked, but
///   the machine remembers that an untracked error may be active and the
///   bits it contributed: they stay in the register, and the state stays
///   error-occurred, until [`EmcyEvent::AllErrorsReset`] or
///   [`EmcyEvent::Initialised`]. Resetting an untracked code therefore sends
///   nothing (the machine cannot tell which untracked error it was) and
///   resetting the last *tracked* error is transition 2, not 4. The register
///   a device sends never claims "no error" while an error may be present.
/// - **Decision:** [`EmcyEvent::Initialised`] is transition 0 from any state (a
///   re-initialised device starts over, e.g. after an NMT reset): the machine
///   starts again error-free, without sending anything (the AKD CANopen manual:
///   "No error signal is generated in this condition").
/// - The manufacturer area of a reset EMCY is zero
///   (docs/canopen.md#emcy-producer), unless the device passes one with
///   [`EmcyEvent::reset_with`]: the AKD keeps its axis id in byte 3 of reset
///   EMCYs (the AKD CANopen manual, docs/canopen.md#akd).
///
/// ```
/// use motionwire_codec::canopen::{
///     EmcyEvent, EmcyProducer, EmcyTransition, ErrorCode, ErrorCondition,
/// };
///
/// let mut producer: EmcyProducer = EmcyProducer::new();
///
/// // Transition 1: device temperature (0x4210) on axis 1.
/// let out = producer.apply(EmcyEvent::error(ErrorCode::new(0x4210), [1, 0, 0, 0, 0]));
/// assert_eq!(out.transition(), Some(EmcyTransition::FirstError));
/// assert_eq!(out.emcy().unwrap().to_bytes(), [0x10, 0x42, 0x09, 1, 0, 0, 0, 0]);
///
/// // Transition 3: a CAN overrun (0x8110) adds the communication bit.
/// let out = producer.apply(EmcyEvent::error(ErrorCode::new(0x8110), [0; 5]));
/// assert_eq!(out.transition().map(EmcyTransition::number), Some(3));
/// assert_eq!(out.emcy().unwrap().to_bytes(), [0x10, 0x81, 0x19, 0, 0, 0, 0, 0]);
///
/// // Transition 2: the temperature error goes, the overrun remains.
/// let out = producer.apply(EmcyEvent::reset(ErrorCode::new(0x4210)));
/// assert_eq!(out.emcy().unwrap().to_bytes(), [0x00, 0x00, 0x11, 0, 0, 0, 0, 0]);
///
/// // Transition 4: the last error goes.
/// let out = producer.apply(EmcyEvent::reset(ErrorCode::new(0x8110)));
/// assert_eq!(out.emcy().unwrap().to_bytes(), [0; 8]);
/// assert_eq!(producer.condition(), ErrorCondition::ErrorFree);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EmcyProducer<const N: usize = DEFAULT_ACTIVE_ERRORS> {
    /// The active errors in ascending code order in `active[..len]`; every
    /// other slot is [`ActiveError::VACANT`], so the derived `PartialEq`
    /// compares sets.
    active: [ActiveError; N],
    /// The number of tracked active errors, `<= N`.
    len: usize,
    /// `Some(bits)` once an error could not be tracked for lack of a slot:
    /// the union of the register bits such errors contributed.
    untracked: Option<ErrorRegister>,
}

impl<const N: usize> Default for EmcyProducer<N> {
    fn default() -> Self {
        Self::with_capacity()
    }
}

impl EmcyProducer {
    /// Return the machine after transition 0 (error-free, nothing active),
    /// tracking [`DEFAULT_ACTIVE_ERRORS`] (8) active errors at once: written
    /// without naming a capacity, as `HashMap::new` is.
    ///
    /// ```
    /// use motionwire_codec::canopen::EmcyProducer;
    ///
    /// let producer = EmcyProducer::new();
    /// assert_eq!(producer.active_errors().count(), 0);
    /// ```
    #[must_use]
    pub const fn new() -> Self {
        Self::with_capacity()
    }
}

impl<const N: usize> EmcyProducer<N> {
    /// The number of active errors this machine tracks.
    pub const CAPACITY: usize = N;

    /// Return the machine after transition 0 (error-free, nothing active),
    /// tracking `N` active errors at once, e.g.
    /// `EmcyProducer::<16>::with_capacity()`.
    #[must_use]
    pub const fn with_capacity() -> Self {
        EmcyProducer {
            active: [ActiveError::VACANT; N],
            len: 0,
            untracked: None,
        }
    }

    /// Return the error condition, error-free or error-occurred.
    #[must_use]
    pub const fn condition(&self) -> ErrorCondition {
        if self.is_error_free() {
            ErrorCondition::ErrorFree
        } else {
            ErrorCondition::ErrorOccurred
        }
    }

    /// Return whether no error is active (and none may be, after an
    /// overflow).
    #[must_use]
    pub const fn is_error_free(&self) -> bool {
        self.len == 0 && self.untracked.is_none()
    }

    /// Return the error register, object 1001h, that the device presents
    /// now: 0x00 when error-free, else bit 0 and every active error's
    /// contribution (docs/canopen.md#error-register,
    /// docs/canopen.md#emcy-producer).
    #[must_use]
    pub fn error_register(&self) -> ErrorRegister {
        if self.is_error_free() {
            return ErrorRegister::empty();
        }
        self.tracked()
            .iter()
            .fold(ErrorRegister::GENERIC, |acc, error| acc | error.register)
            | self.untracked.unwrap_or(ErrorRegister::empty())
    }

    /// Return the tracked active errors in ascending code order.
    #[must_use]
    pub fn active_errors(
        &self,
    ) -> impl DoubleEndedIterator<Item = ActiveError> + ExactSizeIterator + '_ {
        self.tracked().iter().copied()
    }

    /// Return the number of tracked active errors.
    #[must_use]
    pub const fn active_count(&self) -> usize {
        self.len
    }

    /// Return whether the error `code` is tracked as active.
    #[must_use]
    pub fn is_active(&self, code: ErrorCode) -> bool {
        self.position(code).is_some()
    }

    /// Return whether an error may be active that could not be tracked for
    /// lack of a slot (see [`EmcyProducer`]'s overflow rule).
    #[must_use]
    pub const fn has_untracked_errors(&self) -> bool {
        self.untracked.is_some()
    }

    /// Return the next state and what the step produced, leaving `self` as
    /// it is (docs/canopen.md#emcy-producer: the function is pure).
    pub fn step(&self, event: EmcyEvent) -> (Self, EmcyOutcome) {
        let mut next = *self;
        let outcome = next.apply(event);
        (next, outcome)
    }

    /// Take the step for `event` in place and return what it produced.
    pub fn apply(&mut self, event: EmcyEvent) -> EmcyOutcome {
        match event {
            EmcyEvent::Initialised => {
                *self = Self::with_capacity();
                EmcyOutcome::Initialised
            }
            EmcyEvent::ErrorOccurred {
                code,
                register,
                manufacturer,
            } => self.error_occurred(code, register, manufacturer),
            EmcyEvent::ErrorReset { code, manufacturer } => {
                self.error_reset(code, manufacturer.unwrap_or([0; 5]))
            }
            EmcyEvent::AllErrorsReset => {
                if self.is_error_free() {
                    EmcyOutcome::Ignored(IgnoredEvent::AlreadyErrorFree)
                } else {
                    *self = Self::with_capacity();
                    EmcyOutcome::sent(
                        EmcyTransition::AllErrorsReset,
                        Emcy::reset(ErrorRegister::empty()),
                    )
                }
            }
        }
    }

    fn error_occurred(
        &mut self,
        code: ErrorCode,
        register: Option<ErrorRegister>,
        manufacturer: [u8; 5],
    ) -> EmcyOutcome {
        if code.is_reset() {
            return EmcyOutcome::Ignored(IgnoredEvent::ResetCodeIsNotAnError);
        }
        if self.is_active(code) {
            return EmcyOutcome::Ignored(IgnoredEvent::AlreadyActive);
        }
        let transition = if self.is_error_free() {
            EmcyTransition::FirstError
        } else {
            EmcyTransition::FurtherError
        };
        let contribution = register
            .unwrap_or(code.register_class_bits())
            .difference(ErrorRegister::RESERVED);
        let error = ActiveError {
            code,
            register: contribution,
        };
        if self.insert(error) {
            EmcyOutcome::sent(
                transition,
                Emcy::new(code, self.error_register(), manufacturer),
            )
        } else {
            let bits = self.untracked.unwrap_or(ErrorRegister::empty());
            self.untracked = Some(bits | contribution);
            EmcyOutcome::SentUntracked {
                transition,
                emcy: Emcy::new(code, self.error_register(), manufacturer),
            }
        }
    }

    fn error_reset(&mut self, code: ErrorCode, manufacturer: [u8; 5]) -> EmcyOutcome {
        if !self.remove(code) {
            return EmcyOutcome::Ignored(IgnoredEvent::NotActive);
        }
        let (transition, register) = if self.is_error_free() {
            (EmcyTransition::AllErrorsReset, ErrorRegister::empty())
        } else {
            (EmcyTransition::ErrorReset, self.error_register())
        };
        EmcyOutcome::sent(
            transition,
            Emcy::new(ErrorCode::NO_ERROR, register, manufacturer),
        )
    }

    /// The tracked errors, `active[..len]`.
    fn tracked(&self) -> &[ActiveError] {
        self.active.get(..self.len).unwrap_or(&[])
    }

    fn position(&self, code: ErrorCode) -> Option<usize> {
        self.tracked().binary_search_by_key(&code, |e| e.code).ok()
    }

    /// Insert `error` (not active yet) in code order; `false` when all
    /// slots are in use.
    fn insert(&mut self, error: ActiveError) -> bool {
        let at = self.tracked().partition_point(|e| e.code < error.code);
        let Some(shifted) = self.active.get_mut(at..=self.len) else {
            return false;
        };
        shifted.rotate_right(1);
        if let Some(slot) = shifted.first_mut() {
            *slot = error;
        }
        self.len += 1;
        true
    }

    /// Remove the error `code`; `false` when it is not tracked.
    fn remove(&mut self, code: ErrorCode) -> bool {
        let Some(at) = self.position(code) else {
            return false;
        };
        if let Some(shifted) = self.active.get_mut(at..self.len) {
            shifted.rotate_left(1);
            if let Some(slot) = shifted.last_mut() {
                *slot = ActiveError::VACANT;
            }
        }
        self.len -= 1;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OVER_TEMPERATURE: ErrorCode = ErrorCode::new(0x4210);
    const CAN_OVERRUN: ErrorCode = ErrorCode::new(0x8110);
    const INTERNAL_VOLTAGE: ErrorCode = ErrorCode::new(0x3210);
    const HARDWARE: ErrorCode = ErrorCode::new(0x5000);
    /// Axis 1 in the AKD layout of the manufacturer field
    /// (docs/canopen.md#akd).
    const AXIS_1: [u8; 5] = [0x01, 0, 0, 0, 0];

    /// Apply `events` to a fresh machine, asserting that each took a
    /// transition, and return the machine.
    fn after<const N: usize>(events: &[EmcyEvent]) -> EmcyProducer<N> {
        let mut producer = EmcyProducer::<N>::with_capacity();
        for &event in events {
            let out = producer.apply(event);
            assert!(out.transition().is_some(), "{event:?} took no transition");
        }
        producer
    }

    fn sent(out: &EmcyOutcome) -> [u8; 8] {
        out.emcy().expect("an EMCY is sent").to_bytes()
    }

    #[test]
    fn transition_0_initialisation_is_error_free_and_sends_nothing() {
        let fresh: EmcyProducer = EmcyProducer::new();
        let (next, out) = fresh.step(EmcyEvent::Initialised);
        assert_eq!(out.transition(), Some(EmcyTransition::Initialised));
        assert_eq!(out.transition().map(EmcyTransition::number), Some(0));
        assert_eq!(out.emcy(), None);
        assert_eq!(next.condition(), ErrorCondition::ErrorFree);
        assert_eq!(next.error_register().bits(), 0x00);
        assert_eq!(next, EmcyProducer::default());

        // Re-initialising a device with active errors starts again error-free
        // without an EMCY.
        let busy: EmcyProducer = after(&[EmcyEvent::error(OVER_TEMPERATURE, AXIS_1)]);
        let (next, out) = busy.step(EmcyEvent::Initialised);
        assert_eq!(out.transition(), Some(EmcyTransition::Initialised));
        assert_eq!(out.emcy(), None);
        assert_eq!(next, EmcyProducer::new());
    }

    #[test]
    fn transition_1_first_error_sends_code_register_and_manufacturer_bytes() {
        let (next, out) =
            EmcyProducer::<8>::with_capacity().step(EmcyEvent::error(OVER_TEMPERATURE, AXIS_1));
        assert_eq!(out.transition(), Some(EmcyTransition::FirstError));
        assert_eq!(out.transition().map(EmcyTransition::number), Some(1));
        // 0x4210 LE, register generic | temperature, axis 1.
        assert_eq!(sent(&out), [0x10, 0x42, 0x09, 0x01, 0x00, 0x00, 0x00, 0x00]);
        assert_eq!(out.overflow(), None);
        assert_eq!(next.condition(), ErrorCondition::ErrorOccurred);
        assert_eq!(next.error_register().bits(), 0x09);
    }

    #[test]
    fn transition_1_seed_000_life_guard_error_on_axis_1() {
        // The AKD frame emcy.rs uses: 0x8130, register 0x11.
        let (_, out) = EmcyProducer::<8>::with_capacity()
            .step(EmcyEvent::error(ErrorCode::LIFE_GUARD, AXIS_1));
        assert_eq!(sent(&out), [0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00]);
    }

    #[test]
    fn transition_2_one_error_reset_sends_0000_and_the_remaining_register() {
        let producer: EmcyProducer = after(&[
            EmcyEvent::error(OVER_TEMPERATURE, AXIS_1),
            EmcyEvent::error(CAN_OVERRUN, [0x01, 0, 0, 0, 0x7F]),
        ]);
        let (next, out) = producer.step(EmcyEvent::reset(OVER_TEMPERATURE));
        assert_eq!(out.transition(), Some(EmcyTransition::ErrorReset));
        assert_eq!(out.transition().map(EmcyTransition::number), Some(2));
        // Code 0x0000, register generic | communication, manufacturer zero.
        assert_eq!(sent(&out), [0x00, 0x00, 0x11, 0x00, 0x00, 0x00, 0x00, 0x00]);
        assert_eq!(next.condition(), ErrorCondition::ErrorOccurred);
        assert!(next.is_active(CAN_OVERRUN));
        assert!(!next.is_active(OVER_TEMPERATURE));
    }

    #[test]
    fn transition_3_further_error_sends_its_code_and_the_accumulated_register() {
        let producer: EmcyProducer = after(&[EmcyEvent::error(OVER_TEMPERATURE, AXIS_1)]);
        let (next, out) = producer.step(EmcyEvent::error(INTERNAL_VOLTAGE, [0x01, 0, 0, 0, 0x42]));
        assert_eq!(out.transition(), Some(EmcyTransition::FurtherError));
        assert_eq!(out.transition().map(EmcyTransition::number), Some(3));
        // 0x3210 LE, register generic | voltage | temperature, its own bytes.
        assert_eq!(sent(&out), [0x10, 0x32, 0x0D, 0x01, 0x00, 0x00, 0x00, 0x42]);
        assert_eq!(next.active_count(), 2);
    }

    #[test]
    fn transition_4_last_error_reset_sends_all_zero() {
        let producer: EmcyProducer = after(&[EmcyEvent::error(INTERNAL_VOLTAGE, AXIS_1)]);
        let (next, out) = producer.step(EmcyEvent::reset(INTERNAL_VOLTAGE));
        assert_eq!(out.transition(), Some(EmcyTransition::AllErrorsReset));
        assert_eq!(out.transition().map(EmcyTransition::number), Some(4));
        assert_eq!(sent(&out), [0x00; 8]);
        assert_eq!(next, EmcyProducer::new());
    }

    #[test]
    fn transition_4_reset_all_from_error_occurred_sends_all_zero() {
        let producer: EmcyProducer = after(&[
            EmcyEvent::error(OVER_TEMPERATURE, AXIS_1),
            EmcyEvent::error(CAN_OVERRUN, AXIS_1),
            EmcyEvent::error(INTERNAL_VOLTAGE, AXIS_1),
        ]);
        let (next, out) = producer.step(EmcyEvent::AllErrorsReset);
        assert_eq!(out.transition(), Some(EmcyTransition::AllErrorsReset));
        assert_eq!(sent(&out), [0x00; 8]);
        assert_eq!(next.condition(), ErrorCondition::ErrorFree);
        assert_eq!(next, EmcyProducer::new());
    }

    /// The transitions of docs/canopen.md#emcy-producer as a table:
    /// (transition, number, target condition).
    #[test]
    fn transition_table() {
        use EmcyTransition::*;
        use ErrorCondition::*;
        let table = [
            (Initialised, 0, ErrorFree),
            (FirstError, 1, ErrorOccurred),
            (ErrorReset, 2, ErrorOccurred),
            (FurtherError, 3, ErrorOccurred),
            (AllErrorsReset, 4, ErrorFree),
        ];
        for (transition, number, target) in table {
            assert_eq!(transition.number(), number);
            assert_eq!(EmcyTransition::from_number(number), Some(transition));
            assert_eq!(transition.target(), target);
            assert_eq!(transition.to_string(), format!("transition {number}"));
        }
        assert_eq!(EmcyTransition::from_number(5), None);
        assert_eq!(ErrorFree.to_string(), "error-free");
        assert_eq!(ErrorOccurred.to_string(), "error-occurred");
    }

    #[test]
    fn events_read_as_a_person_says_them() {
        let table = [
            (EmcyEvent::Initialised, "initialised"),
            (
                EmcyEvent::error(OVER_TEMPERATURE, [0; 5]),
                "error occurred: 0x4210 Excess device temperature",
            ),
            (
                EmcyEvent::error_with_register(
                    OVER_TEMPERATURE,
                    ErrorRegister::TEMPERATURE,
                    AXIS_1,
                ),
                "error occurred: 0x4210 Excess device temperature, register 0x08 [temperature], \
                 manufacturer 0100000000",
            ),
            (
                EmcyEvent::reset(OVER_TEMPERATURE),
                "error reset: 0x4210 Excess device temperature",
            ),
            (
                EmcyEvent::reset_with(OVER_TEMPERATURE, AXIS_1),
                "error reset: 0x4210 Excess device temperature, manufacturer 0100000000",
            ),
            (EmcyEvent::AllErrorsReset, "all errors reset"),
        ];
        for (event, text) in table {
            assert_eq!(event.to_string(), text, "{event:?}");
        }
    }

    #[test]
    fn ignored_events_read_as_a_person_says_them() {
        let table = [
            (IgnoredEvent::AlreadyActive, "the error is already active"),
            (IgnoredEvent::NotActive, "the error is not active"),
            (IgnoredEvent::AlreadyErrorFree, "already error-free"),
            (
                IgnoredEvent::ResetCodeIsNotAnError,
                "a reset code (0x00xx) names no error",
            ),
        ];
        for (reason, text) in table {
            assert_eq!(reason.to_string(), text);
        }
    }

    #[test]
    fn outcomes_read_as_a_person_says_them() {
        let mut producer = EmcyProducer::<1>::with_capacity();
        assert_eq!(
            producer.apply(EmcyEvent::Initialised).to_string(),
            "transition 0: nothing sent"
        );
        assert_eq!(
            producer
                .apply(EmcyEvent::error(OVER_TEMPERATURE, AXIS_1))
                .to_string(),
            "transition 1: send EMCY 0x4210 Excess device temperature, \
             register 0x09 [generic|temperature], manufacturer 0100000000"
        );
        assert_eq!(
            producer
                .apply(EmcyEvent::error(CAN_OVERRUN, [0; 5]))
                .to_string(),
            "transition 3: send EMCY 0x8110 CAN overrun (objects lost), \
             register 0x19 [generic|temperature|communication], manufacturer 0000000000 \
             (overflow: 0x8110 not tracked)"
        );
        assert_eq!(
            producer
                .apply(EmcyEvent::error(OVER_TEMPERATURE, AXIS_1))
                .to_string(),
            "ignored: the error is already active"
        );
    }

    #[test]
    fn a_repeated_active_error_sends_nothing_and_keeps_its_first_bits() {
        let producer: EmcyProducer = after(&[EmcyEvent::error(OVER_TEMPERATURE, AXIS_1)]);
        let again =
            EmcyEvent::error_with_register(OVER_TEMPERATURE, ErrorRegister::MANUFACTURER, [9; 5]);
        let (next, out) = producer.step(again);
        assert_eq!(out.emcy(), None);
        assert_eq!(out.transition(), None);
        assert_eq!(out.ignored(), Some(IgnoredEvent::AlreadyActive));
        assert_eq!(next, producer);
        assert_eq!(next.error_register().bits(), 0x09);
    }

    #[test]
    fn resetting_an_inactive_error_sends_nothing() {
        let (next, out) =
            EmcyProducer::<8>::with_capacity().step(EmcyEvent::reset(OVER_TEMPERATURE));
        assert_eq!((out.emcy(), out.transition()), (None, None));
        assert_eq!(out.ignored(), Some(IgnoredEvent::NotActive));
        assert_eq!(next, EmcyProducer::new());

        let producer: EmcyProducer = after(&[EmcyEvent::error(OVER_TEMPERATURE, AXIS_1)]);
        let (next, out) = producer.step(EmcyEvent::reset(CAN_OVERRUN));
        assert_eq!(
            (out.emcy(), out.ignored()),
            (None, Some(IgnoredEvent::NotActive))
        );
        assert_eq!(next, producer);
    }

    #[test]
    fn reset_all_from_error_free_sends_nothing() {
        let (next, out) = EmcyProducer::<8>::with_capacity().step(EmcyEvent::AllErrorsReset);
        assert_eq!((out.emcy(), out.transition()), (None, None));
        assert_eq!(out.ignored(), Some(IgnoredEvent::AlreadyErrorFree));
        assert!(next.is_error_free());
    }

    #[test]
    fn a_reset_code_as_an_error_is_refused_in_both_conditions() {
        for raw in [0x0000, 0x0001, 0x00FF] {
            let event = EmcyEvent::error(ErrorCode::new(raw), AXIS_1);
            let (next, out) = EmcyProducer::<8>::with_capacity().step(event);
            assert_eq!(out.emcy(), None, "{raw:#06x}");
            assert_eq!(out.ignored(), Some(IgnoredEvent::ResetCodeIsNotAnError));
            assert!(next.is_error_free());

            let busy: EmcyProducer = after(&[EmcyEvent::error(CAN_OVERRUN, AXIS_1)]);
            let (next, out) = busy.step(event);
            assert_eq!(out.emcy(), None);
            assert_eq!(out.ignored(), Some(IgnoredEvent::ResetCodeIsNotAnError));
            assert_eq!(next, busy, "a reset code must not clear active errors");
        }
    }

    /// Register contributions: (code, caller bits, register sent alone).
    #[test]
    fn register_bits_from_the_code_or_from_the_caller() {
        let table: [(u16, Option<u8>, u8); 9] = [
            (0x2310, None, 0x03),       // current
            (0x3210, None, 0x05),       // voltage
            (0x4210, None, 0x09),       // temperature
            (0x8110, None, 0x11),       // communication
            (0x8250, None, 0x11),       // protocol error → communication
            (0x5000, None, 0x01),       // hardware: generic only
            (0xFF01, Some(0x80), 0x81), // device specific, manufacturer bit
            (0x4210, Some(0x20), 0x21), // caller bits replace the class bits
            (0x1000, Some(0x40), 0x01), // reserved bit 6 is never produced
        ];
        for (raw, bits, register) in table {
            let code = ErrorCode::new(raw);
            let event = match bits {
                None => EmcyEvent::error(code, [0; 5]),
                Some(bits) => EmcyEvent::error_with_register(
                    code,
                    ErrorRegister::from_bits_retain(bits),
                    [0; 5],
                ),
            };
            let (next, out) = EmcyProducer::<8>::with_capacity().step(event);
            let [lo, hi] = raw.to_le_bytes();
            assert_eq!(sent(&out), [lo, hi, register, 0, 0, 0, 0, 0], "{raw:#06x}");
            assert_eq!(next.error_register().bits(), register);
        }
    }

    #[test]
    fn caller_bits_are_that_errors_contribution_and_leave_with_it() {
        let producer: EmcyProducer = after(&[
            EmcyEvent::error_with_register(HARDWARE, ErrorRegister::MANUFACTURER, [0; 5]),
            EmcyEvent::error(OVER_TEMPERATURE, AXIS_1),
        ]);
        assert_eq!(producer.error_register().bits(), 0x89);
        let (_, out) = producer.step(EmcyEvent::reset(HARDWARE));
        assert_eq!(sent(&out), [0x00, 0x00, 0x09, 0, 0, 0, 0, 0]);
        let (_, out) = producer.step(EmcyEvent::reset(OVER_TEMPERATURE));
        assert_eq!(sent(&out), [0x00, 0x00, 0x81, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn two_errors_of_one_class_keep_the_bit_until_both_are_reset() {
        let producer: EmcyProducer = after(&[
            EmcyEvent::error(ErrorCode::new(0x4110), [0; 5]),
            EmcyEvent::error(ErrorCode::new(0x4210), [0; 5]),
        ]);
        let (next, out) = producer.step(EmcyEvent::reset(ErrorCode::new(0x4110)));
        assert_eq!(sent(&out), [0x00, 0x00, 0x09, 0, 0, 0, 0, 0]);
        let (_, out) = next.step(EmcyEvent::reset(ErrorCode::new(0x4210)));
        assert_eq!(sent(&out), [0x00; 8]);
    }

    #[test]
    fn the_state_does_not_depend_on_the_order_errors_occurred() {
        let a: EmcyProducer = after(&[
            EmcyEvent::error(CAN_OVERRUN, [0; 5]),
            EmcyEvent::error(OVER_TEMPERATURE, [0; 5]),
            EmcyEvent::error(INTERNAL_VOLTAGE, [0; 5]),
        ]);
        let b: EmcyProducer = after(&[
            EmcyEvent::error(INTERNAL_VOLTAGE, [1; 5]),
            EmcyEvent::error(CAN_OVERRUN, [2; 5]),
            EmcyEvent::error(OVER_TEMPERATURE, [3; 5]),
        ]);
        assert_eq!(a, b);
        let codes: Vec<u16> = a.active_errors().map(|e| e.code().get()).collect();
        assert_eq!(codes, [0x3210, 0x4210, 0x8110]);
        assert_eq!(
            a.active_errors()
                .map(ActiveError::register)
                .collect::<Vec<_>>(),
            [
                ErrorRegister::VOLTAGE,
                ErrorRegister::TEMPERATURE,
                ErrorRegister::COMMUNICATION
            ]
        );
    }

    #[test]
    fn overflow_still_sends_the_emcy_and_reports_the_code() {
        let producer: EmcyProducer<2> = after(&[
            EmcyEvent::error(HARDWARE, [0; 5]),
            EmcyEvent::error(CAN_OVERRUN, [0; 5]),
        ]);
        let (next, out) = producer.step(EmcyEvent::error(OVER_TEMPERATURE, AXIS_1));
        assert_eq!(out.transition(), Some(EmcyTransition::FurtherError));
        assert_eq!(out.overflow(), Some(OVER_TEMPERATURE));
        // Register: generic | communication | temperature (the untracked one).
        assert_eq!(sent(&out), [0x10, 0x42, 0x19, 0x01, 0, 0, 0, 0]);
        assert_eq!(next.active_count(), 2);
        assert!(!next.is_active(OVER_TEMPERATURE));
        assert!(next.has_untracked_errors());
        assert_eq!(next.error_register().bits(), 0x19);
    }

    #[test]
    fn after_overflow_the_machine_never_claims_error_free_until_reset_all() {
        let mut producer: EmcyProducer<2> = after(&[
            EmcyEvent::error(HARDWARE, [0; 5]),
            EmcyEvent::error(CAN_OVERRUN, [0; 5]),
            EmcyEvent::error(OVER_TEMPERATURE, [0; 5]),
        ]);
        // The untracked error's reset is unknown to the machine: nothing.
        let out = producer.apply(EmcyEvent::reset(OVER_TEMPERATURE));
        assert_eq!(
            (out.emcy(), out.ignored()),
            (None, Some(IgnoredEvent::NotActive))
        );
        // Resetting the tracked errors keeps the untracked temperature bit.
        let out = producer.apply(EmcyEvent::reset(CAN_OVERRUN));
        assert_eq!(out.transition(), Some(EmcyTransition::ErrorReset));
        assert_eq!(sent(&out), [0x00, 0x00, 0x09, 0, 0, 0, 0, 0]);
        let out = producer.apply(EmcyEvent::reset(HARDWARE));
        assert_eq!(out.transition(), Some(EmcyTransition::ErrorReset));
        assert_eq!(sent(&out), [0x00, 0x00, 0x09, 0, 0, 0, 0, 0]);
        assert_eq!(producer.condition(), ErrorCondition::ErrorOccurred);
        assert_eq!(producer.active_count(), 0);
        // A freed slot tracks the next error normally; transition 3.
        let out = producer.apply(EmcyEvent::error(INTERNAL_VOLTAGE, [0; 5]));
        assert_eq!(out.transition(), Some(EmcyTransition::FurtherError));
        assert_eq!(out.overflow(), None);
        assert_eq!(sent(&out), [0x10, 0x32, 0x0D, 0, 0, 0, 0, 0]);
        // Only "reset all" returns to error-free.
        let out = producer.apply(EmcyEvent::AllErrorsReset);
        assert_eq!(out.transition(), Some(EmcyTransition::AllErrorsReset));
        assert_eq!(sent(&out), [0x00; 8]);
        assert_eq!(producer, EmcyProducer::with_capacity());
    }

    #[test]
    fn initialisation_forgets_untracked_errors() {
        let producer: EmcyProducer<1> = after(&[
            EmcyEvent::error(HARDWARE, [0; 5]),
            EmcyEvent::error(CAN_OVERRUN, [0; 5]),
        ]);
        assert!(producer.has_untracked_errors());
        let (next, _) = producer.step(EmcyEvent::Initialised);
        assert!(!next.has_untracked_errors());
        assert!(next.is_error_free());
    }

    #[test]
    fn a_machine_without_slots_still_sends_every_emcy() {
        let mut producer = EmcyProducer::<0>::with_capacity();
        let out = producer.apply(EmcyEvent::error(OVER_TEMPERATURE, AXIS_1));
        assert_eq!(out.transition(), Some(EmcyTransition::FirstError));
        assert_eq!(out.overflow(), Some(OVER_TEMPERATURE));
        assert_eq!(sent(&out), [0x10, 0x42, 0x09, 0x01, 0, 0, 0, 0]);
        let out = producer.apply(EmcyEvent::error(CAN_OVERRUN, [0; 5]));
        assert_eq!(out.transition(), Some(EmcyTransition::FurtherError));
        assert_eq!(sent(&out), [0x10, 0x81, 0x19, 0, 0, 0, 0, 0]);
        let out = producer.apply(EmcyEvent::AllErrorsReset);
        assert_eq!(sent(&out), [0x00; 8]);
    }

    #[test]
    fn step_is_pure_and_apply_matches_it() {
        let producer: EmcyProducer = after(&[EmcyEvent::error(OVER_TEMPERATURE, AXIS_1)]);
        let before = producer;
        let first = producer.step(EmcyEvent::error(CAN_OVERRUN, [0; 5]));
        let second = producer.step(EmcyEvent::error(CAN_OVERRUN, [0; 5]));
        assert_eq!(first, second);
        assert_eq!(producer, before);
        let mut applied = producer;
        let out = applied.apply(EmcyEvent::error(CAN_OVERRUN, [0; 5]));
        assert_eq!((applied, out), first);
    }

    #[test]
    fn capacity() {
        assert_eq!(EmcyProducer::<DEFAULT_ACTIVE_ERRORS>::CAPACITY, 8);
        assert_eq!(EmcyProducer::<3>::CAPACITY, 3);
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::emcy_producer::emcy_events;

    /// A plain reference model of docs/canopen.md#emcy-producer, written
    /// independently of the array-based machine.
    #[derive(Default)]
    struct Model {
        /// (code, contribution) in occurrence order.
        active: Vec<(u16, u8)>,
        untracked: Option<u8>,
    }

    impl Model {
        fn error_free(&self) -> bool {
            self.active.is_empty() && self.untracked.is_none()
        }

        fn register(&self) -> u8 {
            if self.error_free() {
                return 0;
            }
            self.active.iter().fold(1, |acc, &(_, bits)| acc | bits) | self.untracked.unwrap_or(0)
        }

        /// Apply the event; return the EMCY bytes it sends.
        fn apply(&mut self, event: EmcyEvent, capacity: usize) -> Option<[u8; 8]> {
            match event {
                EmcyEvent::Initialised => {
                    *self = Model::default();
                    None
                }
                EmcyEvent::AllErrorsReset => {
                    if self.error_free() {
                        None
                    } else {
                        *self = Model::default();
                        Some([0; 8])
                    }
                }
                EmcyEvent::ErrorOccurred {
                    code,
                    register,
                    manufacturer,
                } => {
                    let raw = code.get();
                    if raw <= 0x00FF || self.active.iter().any(|&(c, _)| c == raw) {
                        return None;
                    }
                    let bits = register.unwrap_or(code.register_class_bits()).bits() & !0x40;
                    if self.active.len() < capacity {
                        self.active.push((raw, bits));
                    } else {
                        self.untracked = Some(self.untracked.unwrap_or(0) | bits);
                    }
                    let [lo, hi] = raw.to_le_bytes();
                    let [m0, m1, m2, m3, m4] = manufacturer;
                    Some([lo, hi, self.register(), m0, m1, m2, m3, m4])
                }
                EmcyEvent::ErrorReset { code, .. } => {
                    let at = self.active.iter().position(|&(c, _)| c == code.get())?;
                    self.active.remove(at);
                    Some([0, 0, self.register(), 0, 0, 0, 0, 0])
                }
            }
        }
    }

    fn check_sequence<const N: usize>(events: &[EmcyEvent]) -> Result<(), TestCaseError> {
        let mut producer = EmcyProducer::<N>::with_capacity();
        let mut model = Model::default();
        for &event in events {
            let was_free = producer.is_error_free();
            let (next, out) = producer.step(event);
            let expected = model.apply(event, N);
            prop_assert_eq!(out.emcy().map(|e| e.to_bytes()), expected, "{:?}", event);

            // The state is error-free exactly when no error is active.
            prop_assert_eq!(next.is_error_free(), model.error_free());
            prop_assert_eq!(next.error_register().bits(), model.register());
            prop_assert!(next.active_count() <= N);
            prop_assert_eq!(next.active_errors().count(), next.active_count());
            if let Some(emcy) = out.emcy() {
                // Bit 0 of every sent register is set exactly when errors
                // are active after the step.
                prop_assert_eq!(
                    emcy.register.contains(ErrorRegister::GENERIC),
                    !next.is_error_free()
                );
                prop_assert!(!emcy.register.contains(ErrorRegister::RESERVED));
                // Every reset EMCY is 0x0000 with a zero manufacturer area.
                if emcy.is_reset() {
                    prop_assert_eq!(emcy.code, ErrorCode::NO_ERROR);
                    prop_assert_eq!(emcy.manufacturer, [0; 5]);
                }
            }
            // Exactly one of transition / ignored; an EMCY exactly for 1–4.
            prop_assert!(out.transition().is_some() != out.ignored().is_some());
            let number = out.transition().map(EmcyTransition::number);
            prop_assert_eq!(out.emcy().is_some(), matches!(number, Some(1..=4)));
            if let Some(transition) = out.transition() {
                prop_assert_eq!(transition.target(), next.condition());
                match transition {
                    EmcyTransition::FirstError => prop_assert!(was_free),
                    EmcyTransition::ErrorReset
                    | EmcyTransition::FurtherError
                    | EmcyTransition::AllErrorsReset => {
                        prop_assert!(!was_free)
                    }
                    EmcyTransition::Initialised => {}
                }
            } else {
                prop_assert_eq!(next, producer, "an ignored event changes nothing");
            }
            if out.overflow().is_some() {
                prop_assert!(next.has_untracked_errors());
                prop_assert!(out.emcy().is_some());
            }
            producer = next;
        }
        Ok(())
    }

    proptest! {
        #[test]
        fn random_sequences_match_the_model_with_default_capacity(events in emcy_events(64)) {
            check_sequence::<DEFAULT_ACTIVE_ERRORS>(&events)?;
        }

        #[test]
        fn random_sequences_match_the_model_with_overflow(events in emcy_events(64)) {
            check_sequence::<3>(&events)?;
        }

        #[test]
        fn random_sequences_with_no_slots(events in emcy_events(16)) {
            check_sequence::<0>(&events)?;
        }
    }
}
