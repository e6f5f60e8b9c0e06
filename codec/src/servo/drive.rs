//! The drive model (docs/servo.md#drive-model): [`Drive`], its [`DriveConfig`]
//! and the types they use. The rules and decisions are documented on [`Drive`].

use core::fmt;
use core::num::NonZeroU32;

use super::{
    drive_enabled, servo_ready, ActualPosition, Command, EncoderKind, Feedback, Message,
    MessageCode, ServoControlWord, ServoEnable, ServoErrorWord, ServoFault, ServoReadyMode,
    ServoStatusWord,
};

/// The temperature above which the drive raises SSW.TempWarning, °C
/// (docs/servo.md#ssw, bit 11: motor temperature, measured in the encoder,
/// above 80 °C).
pub const TEMP_WARNING_CELSIUS: f32 = 80.0;

/// How the drive reads the speed set point SSP (docs/servo.md#command: a drive
/// may be configured for a 16-bit "word type" reference).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SetpointWidth {
    /// Double-word reference: SSPW1:SSPW0 as i32 ([`Command::speed_setpoint`]).
    DoubleWord,
    /// Word reference: only SSPW0, as i16 ([`Command::speed_setpoint_word`]).
    Word,
}

impl SetpointWidth {
    /// Return the set point of `command` read at this width
    /// (docs/servo.md#command).
    #[must_use]
    pub const fn read(self, command: &Command) -> i32 {
        match self {
            SetpointWidth::DoubleWord => command.speed_setpoint,
            SetpointWidth::Word => command.speed_setpoint_word() as i32,
        }
    }
}

/// How far the axis moves in one cycle per unit of speed set point: `counts`
/// position counts per cycle for a set point of `per_setpoint`
/// (docs/servo.md#drive-model, "integrates the speed set point into ActPos").
/// Fractions are carried from cycle to cycle, so the position never drifts from
/// the exact integral.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpeedScale {
    counts: u32,
    per_setpoint: NonZeroU32,
}

impl SpeedScale {
    /// One count per cycle per unit of set point: a set point of 100 moves
    /// the axis 100 counts per cycle (the default).
    pub const ONE_TO_ONE: SpeedScale = SpeedScale {
        counts: 1,
        per_setpoint: NonZeroU32::MIN,
    };

    /// Return the scale "`counts` counts per cycle for a set point of
    /// `per_setpoint`", or `None` when `per_setpoint` is 0.
    #[must_use]
    pub const fn new(counts: u32, per_setpoint: u32) -> Option<Self> {
        match NonZeroU32::new(per_setpoint) {
            Some(per_setpoint) => Some(SpeedScale {
                counts,
                per_setpoint,
            }),
            None => None,
        }
    }

    /// Return the counts per cycle for a set point of
    /// [`per_setpoint`](Self::per_setpoint) (docs/servo.md#drive-model).
    #[must_use]
    pub const fn counts(self) -> u32 {
        self.counts
    }

    /// Return the set point that moves the axis [`counts`](Self::counts)
    /// counts per cycle (never 0; docs/servo.md#drive-model).
    #[must_use]
    pub const fn per_setpoint(self) -> u32 {
        self.per_setpoint.get()
    }
}

impl Default for SpeedScale {
    fn default() -> Self {
        SpeedScale::ONE_TO_ONE
    }
}

/// The message codes the drive rotates through on the message channel, one
/// per cycle in increasing order (docs/servo.md#feedback: codes 0–9 of the
/// message-code table; codes outside 0..=9 are never sent by the model).
///
/// ```
/// use motionwire_codec::servo::{MessageCode, MessageRotation};
///
/// let rotation = MessageRotation::from_kinds(&[MessageCode::BusVoltage, MessageCode::MotorSpeed])
///     .unwrap();
/// assert_eq!(rotation.next_after(0), 3);
/// assert_eq!(rotation.next_after(3), 0);
/// assert_eq!(MessageRotation::default().codes().collect::<Vec<_>>(), [0, 1, 2, 3, 4]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MessageRotation {
    /// Bit n set: code n is sent.
    codes: u16,
}

/// The codes the message-code table of docs/servo.md#feedback lists, 0..=9.
const TABLE_CODES: u16 = 0x03FF;

impl MessageRotation {
    /// The measurements the drive has: codes 0–4 (speed, current, relative
    /// current, bus voltage, temperature). Code 5, motor power, is not on
    /// current firmware (docs/servo.md#feedback). The default.
    pub const MEASUREMENTS: MessageRotation = MessageRotation { codes: 0b1_1111 };

    /// Every code of the message-code table of docs/servo.md#feedback, 0–9 (the
    /// reserved ones carry 0.0).
    pub const ALL_CODES: MessageRotation = MessageRotation { codes: TABLE_CODES };

    /// Return the rotation through the codes whose bits are set in `codes`
    /// (bit n = code n), or `None` when it is empty or names a code above 9.
    #[must_use]
    pub const fn new(codes: u16) -> Option<Self> {
        if codes == 0 || codes & !TABLE_CODES != 0 {
            None
        } else {
            Some(MessageRotation { codes })
        }
    }

    /// Return the rotation through the codes of `kinds`, or `None` when it
    /// is empty or holds a kind outside the table (an unknown code).
    #[must_use]
    pub const fn from_kinds(kinds: &[MessageCode]) -> Option<Self> {
        let mut codes = 0u16;
        let mut i = 0;
        while i < kinds.len() {
            let code = kinds[i].code();
            if code < 0 || code > 9 {
                return None;
            }
            codes |= 1 << code;
            i += 1;
        }
        Self::new(codes)
    }

    /// Return the rotation sending only `kind`, or `None` for an unknown
    /// code.
    #[must_use]
    pub const fn only(kind: MessageCode) -> Option<Self> {
        Self::from_kinds(&[kind])
    }

    /// Return the set of message codes as bits (bit n = code n;
    /// docs/servo.md#feedback).
    #[must_use]
    pub const fn bits(self) -> u16 {
        self.codes
    }

    /// Return whether message code `code` is in the rotation
    /// (docs/servo.md#feedback).
    #[must_use]
    pub const fn contains(self, code: i32) -> bool {
        code >= 0 && code <= 9 && self.codes & (1 << code) != 0
    }

    /// Return the message codes in the order they are sent
    /// (docs/servo.md#feedback).
    pub fn codes(self) -> impl Iterator<Item = i32> + Clone {
        (0..=9).filter(move |&code| self.contains(code))
    }

    /// Return the first message code of the rotation (docs/servo.md#feedback).
    #[must_use]
    pub const fn first(self) -> i32 {
        // `codes` is never 0 and has no bit above 9.
        self.codes.trailing_zeros() as i32
    }

    /// Return the code sent after `code`: the next higher code of the
    /// rotation, wrapping to the first. Any `code` is accepted
    /// (docs/servo.md#feedback).
    #[must_use]
    pub const fn next_after(self, code: i32) -> i32 {
        if code < 0 || code >= 9 {
            return self.first();
        }
        // Codes above `code`; `code + 1` is at most 9.
        let above = self.codes & !((2u16 << code) - 1);
        if above == 0 {
            self.first()
        } else {
            above.trailing_zeros() as i32
        }
    }
}

impl Default for MessageRotation {
    fn default() -> Self {
        MessageRotation::MEASUREMENTS
    }
}

/// The drive's parameters (docs/servo.md#drive-model). [`Default`] gives a
/// drive with an incremental encoder, Servo_Ready_Mode 0, the zero pulse at 1
/// 000 counts (one per revolution of 10 000 counts), one count per cycle per
/// unit of a 32-bit set point, the measurements 0–4 on the message channel, a
/// 2-cycle error clear and an EnDat maximum temperature of 95 °C.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DriveConfig {
    /// The encoder, reported in SSW.Abs/Incr; it decides the ActPos layout
    /// (docs/servo.md#feedback, docs/servo.md#ssw).
    pub encoder: EncoderKind,
    /// Servo_Ready_Mode, which decides ServoRDY (docs/servo.md#servo-ready).
    pub ready_mode: ServoReadyMode,
    /// Where the incremental encoder's zero pulse lies, in counts: the
    /// position the drive reports in POSW2..3 when it finds it
    /// (docs/servo.md#feedback, docs/servo.md#handshakes).
    pub zero_pulse_position: i32,
    /// The distance between two zero pulses (counts per revolution), or
    /// `None` for a single zero pulse at
    /// [`zero_pulse_position`](Self::zero_pulse_position). Later zero
    /// pulses update POSW2..3 (docs/servo.md#feedback,
    /// docs/servo.md#handshakes).
    pub zero_pulse_pitch: Option<NonZeroU32>,
    /// How the drive reads SSP (docs/servo.md#command).
    pub setpoint_width: SetpointWidth,
    /// Position counts per cycle per unit of speed set point
    /// (docs/servo.md#drive-model).
    pub speed_scale: SpeedScale,
    /// The speed applied while SCW.EMGON = 0, the "Emergency Feed"
    /// parameter, in set-point units (docs/servo.md#scw; 0 stops the axis).
    pub emergency_feed: i32,
    /// The message codes sent on the message channel (docs/servo.md#feedback).
    pub messages: MessageRotation,
    /// Cycles the drive takes to clear its errors after it sees ErrorClear,
    /// before it answers ErrClearAck (docs/servo.md#handshakes); 0 answers in
    /// the same cycle.
    pub error_clear_delay: u16,
    /// Whether a drive error disables the drive (see the module's
    /// decisions and docs/servo.md#drive-model).
    pub disable_on_fault: bool,
    /// The EnDat encoder's Max_Temperature, °C: above it an absolute
    /// encoder raises SEW.I2t_Endat, E19 (docs/servo.md#sew).
    pub max_temperature: f32,
}

impl Default for DriveConfig {
    fn default() -> Self {
        DriveConfig {
            encoder: EncoderKind::Incremental,
            ready_mode: ServoReadyMode::ErrorFree,
            zero_pulse_position: 1_000,
            zero_pulse_pitch: NonZeroU32::new(10_000),
            setpoint_width: SetpointWidth::DoubleWord,
            speed_scale: SpeedScale::ONE_TO_ONE,
            emergency_feed: 0,
            messages: MessageRotation::MEASUREMENTS,
            error_clear_delay: 2,
            disable_on_fault: true,
            max_temperature: 95.0,
        }
    }
}

/// Where the drive's side of the error-clear handshake is
/// (docs/servo.md#handshakes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorClearState {
    /// No request: ErrClearAck is 0.
    Idle,
    /// ErrorClear is 1; the errors are cleared after this many more cycles.
    Clearing(u16),
    /// The errors were cleared: ErrClearAck is 1 until ErrorClear falls.
    Acknowledged,
}

/// Where the drive's side of the zero-pulse handshake is
/// (docs/servo.md#handshakes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ZeroPulseState {
    /// No request: ZPulseAck is 0.
    Idle,
    /// ZPulseRequest is 1 and no zero pulse was passed since.
    Searching,
    /// A zero pulse was found: ZPulseAck is 1 until ZPulseRequest falls.
    Found,
}

/// A model of the servo drive's side of the interface, to test NC code
/// against without hardware (docs/servo.md#drive-model, following every
/// drive-side rule of docs/servo.md#handshakes; the interface manual).
///
/// [`Drive::cycle`] is one EtherCAT cycle: it takes the NC's [`Command`] and
/// returns the drive's [`Feedback`]. It is deterministic and pure: no
/// clock, no I/O, no heap; time is the number of cycles. Faults, a lost encoder and the motor temperature are
/// set between cycles with [`Drive::inject`], [`Drive::lose_encoder`] and
/// [`Drive::set_motor_temperature`].
///
/// ```
/// use motionwire_codec::servo::{
///     Command, Drive, DriveConfig, ServoControlWord, ServoEnable, ServoStatusWord,
/// };
///
/// let mut drive = Drive::new(DriveConfig::default());
/// let scw = |se| ServoControlWord::NORMAL.with_servo_enable(se);
/// // The enable edge SE 0b01 → 0b10 (docs/servo.md#handshakes).
/// let armed = drive.cycle(&Command::new(0, scw(ServoEnable::ARM), 0));
/// assert!(!armed.status.contains(ServoStatusWord::SERVO_EN));
/// let on = drive.cycle(&Command::new(100, scw(ServoEnable::ENABLE), 0));
/// assert!(on.status.contains(ServoStatusWord::SERVO_EN | ServoStatusWord::SERVO_RDY));
/// // ActPos integrates the speed set point: 100 counts per cycle by default.
/// assert_eq!(on.actual_position().raw(), 100);
/// let next = drive.cycle(&Command::new(100, scw(ServoEnable::ENABLE), 0));
/// assert_eq!(drive.position(), 200);
/// assert_eq!(next.actual_position().raw(), 200);
/// ```
///
/// # Decisions where the manual is silent (docs/servo.md#drive-model)
///
/// - A drive error disables the drive and keeps it disabled until the errors
///   are cleared and the NC makes the SE edge 0b01 → 0b10 again
///   ([`DriveConfig::disable_on_fault`], on by default; off, the drive keeps
///   running with errors, which shows the ServoRDY rows with ServoEn = 1 and
///   ServoErrors = 1).
/// - Error clear: a request seen while no clear is under way starts one;
///   after [`DriveConfig::error_clear_delay`] further cycles with the
///   request held, the drive clears every latched error and raises
///   ErrClearAck, which stays while ErrorClear stays 1. Faults injected
///   while the request is held stay until the next request. A cause that
///   persists (a lost encoder, an EnDat encoder above its maximum
///   temperature) sets its bit again in the same cycle.
/// - Zero pulse: only an incremental encoder has one; with an absolute
///   encoder the drive never answers ZPulseRequest. The axis passes a pulse
///   at p when it reaches p from the other side in a cycle
///   (`old < p <= new` moving forward, `new <= p < old` backward). Before
///   the first pulse found after a request POSW2..3 is 0; afterwards every
///   pulse passed updates it.
/// - Speed: while enabled the applied speed is the set point (read as 16 or
///   32 bits, [`SetpointWidth`]); EMGON = 0 applies
///   [`DriveConfig::emergency_feed`] instead; POSLOCK = 1 holds the axis
///   (speed 0). ModeSel, SIntLock, Brake and PRGDWN do not change the model.
/// - Status: PulseEnabled follows ServoEn (the model has no separate
///   PulseEnable input); N=0 is "applied speed 0"; N=Ns is "applied speed
///   equals the set point"; the active parameter table echoes the one the
///   command selects.
///
/// The value holds the drive's parameters and its state between two
/// cycles; it is `Copy` and allocates nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Drive {
    config: DriveConfig,
    cycles: u64,
    previous_se: ServoEnable,
    enabled: bool,
    /// Errors latched since the last clear, without the summary bit.
    latched: ServoErrorWord,
    clear: ErrorClearState,
    zero: ZeroPulseState,
    /// Whether a zero pulse was found after a request: from then on every
    /// pulse updates `zero_latch`.
    homed: bool,
    zero_latch: i64,
    position: i64,
    /// The fraction of a count carried to the next cycle, in units of
    /// 1 / `speed_scale.per_setpoint`; always in `0..per_setpoint`.
    remainder: i64,
    applied_speed: i32,
    message_code: i32,
    encoder_lost: bool,
    /// Message data of codes 0–9 (code 0 is the applied speed).
    measurements: [f32; 10],
}

/// The model's measurements when it starts: 0 rpm, 0 A, 0 %, 560 V,
/// 40 °C, 0 kW, reserved 0.0.
const INITIAL_MEASUREMENTS: [f32; 10] = [0.0, 0.0, 0.0, 560.0, 40.0, 0.0, 0.0, 0.0, 0.0, 0.0];

impl Drive {
    /// Return a drive with `config`, disabled (as if SE had been 0b00),
    /// without errors, at position 0 (docs/servo.md#drive-model).
    #[must_use]
    pub const fn new(config: DriveConfig) -> Self {
        Drive {
            config,
            cycles: 0,
            previous_se: ServoEnable::DISABLED,
            enabled: false,
            latched: ServoErrorWord::empty(),
            clear: ErrorClearState::Idle,
            zero: ZeroPulseState::Idle,
            homed: false,
            zero_latch: 0,
            position: 0,
            remainder: 0,
            applied_speed: 0,
            // The first cycle sends the rotation's first code.
            message_code: -1,
            encoder_lost: false,
            measurements: INITIAL_MEASUREMENTS,
        }
    }

    /// Return the drive's parameters (docs/servo.md#drive-model).
    #[must_use]
    pub const fn config(&self) -> &DriveConfig {
        &self.config
    }

    /// Return the number of cycles run: the model's only clock
    /// (docs/servo.md#drive-model).
    #[must_use]
    pub const fn cycles(&self) -> u64 {
        self.cycles
    }

    /// Return whether the drive is enabled: SSW.ServoEn of the last cycle
    /// (docs/servo.md#ssw, docs/servo.md#handshakes).
    #[must_use]
    pub const fn is_enabled(&self) -> bool {
        self.enabled
    }

    /// Return the axis position in counts: ActPos (docs/servo.md#feedback; for
    /// an incremental encoder the frame carries its low 32 bits).
    #[must_use]
    pub const fn position(&self) -> i64 {
        self.position
    }

    /// Return the error word the next feedback reports if nothing changes:
    /// the latched errors with the summary bit (docs/servo.md#sew).
    #[must_use]
    pub fn errors(&self) -> ServoErrorWord {
        with_summary(self.latched.union(self.persistent_causes()))
    }

    /// Return the drive side of the error-clear handshake
    /// (docs/servo.md#handshakes).
    #[must_use]
    pub const fn error_clear_state(&self) -> ErrorClearState {
        self.clear
    }

    /// Return the drive side of the zero-pulse handshake
    /// (docs/servo.md#handshakes).
    #[must_use]
    pub const fn zero_pulse_state(&self) -> ZeroPulseState {
        self.zero
    }

    /// Return the position latched at the last zero pulse passed, which an
    /// incremental encoder's frame carries in POSW2..3 (docs/servo.md#feedback;
    /// 0 before the first one found after a request).
    #[must_use]
    pub const fn zero_pulse_latch(&self) -> i64 {
        self.zero_latch
    }

    /// Return whether the encoder is lost ([`Drive::lose_encoder`];
    /// docs/servo.md#sew, EncoderErr).
    #[must_use]
    pub const fn encoder_lost(&self) -> bool {
        self.encoder_lost
    }

    /// Return the speed applied in the last cycle, in set-point units
    /// (docs/servo.md#command, docs/servo.md#scw; the set point, the emergency
    /// feed or 0).
    #[must_use]
    pub const fn applied_speed(&self) -> i32 {
        self.applied_speed
    }

    /// Make the drive detect `fault`: its SEW bit (and so its E-code, if it
    /// has one) is set from the next cycle on, with the summary bit
    /// ServoErrors, until the NC clears it (docs/servo.md#sew,
    /// docs/servo.md#handshakes). Injecting
    /// [`ServoFault::ServoErrors`] sets the summary bit alone.
    pub fn inject(&mut self, fault: ServoFault) {
        self.latched = self.latched.union(fault.flag());
    }

    /// Lose the encoder (a broken cable): SEW.EncoderErr (E01) is set from
    /// the next cycle on and comes back after every clear, and the position
    /// stops changing, until [`Drive::restore_encoder`] (docs/servo.md#sew).
    pub fn lose_encoder(&mut self) {
        self.encoder_lost = true;
    }

    /// Reconnect the encoder; the latched EncoderErr stays until cleared.
    pub fn restore_encoder(&mut self) {
        self.encoder_lost = false;
    }

    /// Set the motor temperature the encoder measures, °C: above
    /// [`TEMP_WARNING_CELSIUS`] the drive raises SSW.TempWarning
    /// (docs/servo.md#ssw); with an absolute (EnDat) encoder, above
    /// [`DriveConfig::max_temperature`] it also raises SEW.I2t_Endat, E19
    /// (docs/servo.md#sew), which comes back after every clear until the motor
    /// cools down. Message code 4 reports the value.
    pub fn set_motor_temperature(&mut self, celsius: f32) {
        self.measurements[4] = celsius;
    }

    /// Set the value the message channel reports for `kind`
    /// (docs/servo.md#feedback): current, relative current, bus voltage,
    /// temperature (as [`Drive::set_motor_temperature`]), power or a reserved
    /// code. The motor speed (code 0) is the applied speed and unknown codes
    /// are not sent: for those nothing changes.
    pub fn set_measurement(&mut self, kind: MessageCode, value: f32) {
        let code = kind.code();
        if (1..=9).contains(&code) {
            // 1..=9 indexes the 10 measurements.
            self.measurements[code as usize] = value;
        }
    }

    /// The error bits whose cause is still present: they are set again in
    /// every cycle, clear or not.
    fn persistent_causes(&self) -> ServoErrorWord {
        let mut causes = ServoErrorWord::empty();
        if self.encoder_lost {
            causes = causes.union(ServoErrorWord::ENCODER_ERR);
        }
        if matches!(self.config.encoder, EncoderKind::Absolute)
            && self.measurements[4] > self.config.max_temperature
        {
            causes = causes.union(ServoErrorWord::I2T_ENDAT);
        }
        causes
    }

    /// Run one EtherCAT cycle: take the NC's `command`, return the feedback
    /// (docs/servo.md#handshakes, docs/servo.md#drive-model). The steps, in
    /// order:
    ///
    /// 1. Error clear: ErrorClear = 1 starts a clear (or continues it);
    ///    after [`DriveConfig::error_clear_delay`] cycles the latched errors
    ///    are cleared and ErrClearAck rises; ErrorClear = 0 drops it.
    /// 2. Errors whose cause persists are set again.
    /// 3. Enable: [`drive_enabled`] on the previous and this cycle's SE;
    ///    with [`DriveConfig::disable_on_fault`], any error disables.
    /// 4. Motion: while enabled, the applied speed (set point, emergency
    ///    feed, or 0 under POSLOCK) times the speed scale moves the axis,
    ///    unless the encoder is lost.
    /// 5. Zero pulse: ZPulseRequest = 1 searches; the first pulse passed
    ///    latches its position and raises ZPulseAck; ZPulseRequest = 0
    ///    drops it. Every later pulse updates the latch.
    /// 6. Feedback: status word (ServoRDY by [`servo_ready`]), error word
    ///    with its summary bit, ActPos in the encoder's layout, the next
    ///    message code of the rotation with its data.
    #[must_use]
    pub fn cycle(&mut self, command: &Command) -> Feedback {
        self.cycles = self.cycles.wrapping_add(1);
        let scw = command.control;

        // 1. Error clear (docs/servo.md#handshakes).
        self.clear = if scw.contains(ServoControlWord::ERROR_CLEAR) {
            match self.clear {
                ErrorClearState::Idle => self.clearing(self.config.error_clear_delay),
                ErrorClearState::Clearing(left) => self.clearing(left.saturating_sub(1)),
                ErrorClearState::Acknowledged => ErrorClearState::Acknowledged,
            }
        } else {
            ErrorClearState::Idle
        };

        // 2. Causes that persist.
        self.latched = self.latched.union(self.persistent_causes());
        let errors = with_summary(self.latched);

        // 3. Enable (docs/servo.md#handshakes).
        let se = scw.servo_enable();
        let faulted = self.config.disable_on_fault && !errors.is_empty();
        self.enabled = drive_enabled(self.previous_se, se, self.enabled) && !faulted;
        self.previous_se = se;

        // 4. Motion.
        let setpoint = self.config.setpoint_width.read(command);
        self.applied_speed = if !self.enabled {
            0
        } else if scw.emergency_active() {
            self.config.emergency_feed
        } else if scw.contains(ServoControlWord::POSLOCK) {
            0
        } else {
            setpoint
        };
        let old = self.position;
        if !self.encoder_lost {
            let delta = self.counts(self.applied_speed);
            self.position = old.wrapping_add(delta);
        }

        // 5. Zero pulse (docs/servo.md#feedback, docs/servo.md#handshakes).
        let requested = scw.contains(ServoControlWord::Z_PULSE_REQUEST);
        let passed = match self.config.encoder {
            EncoderKind::Incremental => self.pulse_passed(old, self.position),
            EncoderKind::Absolute => None,
        };
        self.zero = match (requested, self.zero, passed) {
            (false, _, _) => ZeroPulseState::Idle,
            (true, ZeroPulseState::Found, _) => ZeroPulseState::Found,
            (true, _, Some(_)) => ZeroPulseState::Found,
            (true, _, None) => match self.config.encoder {
                EncoderKind::Incremental => ZeroPulseState::Searching,
                // An absolute encoder has no zero pulse to search.
                EncoderKind::Absolute => ZeroPulseState::Idle,
            },
        };
        if let Some(pulse) = passed {
            if self.homed || self.zero == ZeroPulseState::Found {
                self.homed = true;
                self.zero_latch = pulse;
            }
        }

        // 6. Feedback.
        self.measurements[0] = self.applied_speed as f32;
        self.message_code = self.config.messages.next_after(self.message_code);
        let message = Message::from_raw(self.message_code, self.measurement(self.message_code));

        let status = ServoStatusWord::empty()
            .with_flag(ServoStatusWord::SERVO_EN, self.enabled)
            .with_encoder(self.config.encoder)
            .with_flag(
                ServoStatusWord::Z_PULSE_ACK,
                self.zero == ZeroPulseState::Found,
            )
            .with_flag(
                ServoStatusWord::ERR_CLEAR_ACK,
                self.clear == ErrorClearState::Acknowledged,
            )
            .with_flag(ServoStatusWord::N_ZERO, self.applied_speed == 0)
            .with_flag(ServoStatusWord::N_EQ_NS, self.applied_speed == setpoint)
            .with_flag(ServoStatusWord::PULSE_ENABLED, self.enabled)
            .with_flag(
                ServoStatusWord::TEMP_WARNING,
                self.measurements[4] > TEMP_WARNING_CELSIUS,
            )
            .with_parameter_table(scw.parameter_table());
        let status = status.with_flag(
            ServoStatusWord::SERVO_RDY,
            servo_ready(self.config.ready_mode, status, errors),
        );

        let mut feedback = Feedback {
            position: 0,
            status,
            errors,
            message,
            extra_data: [0.0; 4],
        };
        feedback.set_actual_position(match self.config.encoder {
            EncoderKind::Absolute => ActualPosition::Absolute(self.position),
            // The frame carries the low 32 bits of both
            // (docs/servo.md#feedback).
            EncoderKind::Incremental => ActualPosition::Incremental {
                position: self.position as i32,
                zero_pulse_position: self.zero_latch as i32,
            },
        });
        feedback
    }

    /// Continue a clear with `left` cycles to go; at 0, clear the latched
    /// errors and acknowledge.
    fn clearing(&mut self, left: u16) -> ErrorClearState {
        if left == 0 {
            self.latched = ServoErrorWord::empty();
            ErrorClearState::Acknowledged
        } else {
            ErrorClearState::Clearing(left)
        }
    }

    /// Return the counts the axis moves in one cycle at `speed`, carrying
    /// the fraction in `remainder`.
    fn counts(&mut self, speed: i32) -> i64 {
        let per = i64::from(self.config.speed_scale.per_setpoint());
        // |i32| · u32 < 2^63: no overflow.
        let product = i64::from(speed) * i64::from(self.config.speed_scale.counts());
        let mut delta = product.div_euclid(per);
        // Both in 0..per, so the sum is below 2·2^32.
        let mut remainder = product.rem_euclid(per) + self.remainder;
        if remainder >= per {
            remainder -= per;
            delta += 1;
        }
        self.remainder = remainder;
        delta
    }

    /// Return the position of the zero pulse the axis passed last when it
    /// moved from `old` to `new`, if it passed one.
    fn pulse_passed(&self, old: i64, new: i64) -> Option<i64> {
        if old == new {
            return None;
        }
        let zero = i64::from(self.config.zero_pulse_position);
        let pulse = match self.config.zero_pulse_pitch {
            None => zero,
            // i64 arithmetic; i128 only near the ends of the i64 range.
            Some(pitch) => nearest_pulse(zero, i64::from(pitch.get()), old, new).or_else(|| {
                nearest_pulse(
                    i128::from(zero),
                    i128::from(pitch.get()),
                    i128::from(old),
                    i128::from(new),
                )
                .and_then(|pulse| i64::try_from(pulse).ok())
            })?,
        };
        let passed = (old < pulse && pulse <= new) || (new <= pulse && pulse < old);
        passed.then_some(pulse)
    }

    /// Return the message data of `code` (0.0 for a code outside 0..=9).
    fn measurement(&self, code: i32) -> f32 {
        usize::try_from(code)
            .ok()
            .and_then(|i| self.measurements.get(i))
            .copied()
            .unwrap_or(0.0)
    }
}

/// Return the zero pulse (`zero` + k·`pitch`) the axis reaches last moving
/// from `old` to `new`, if any is on the way: forward the highest at or
/// below `new`, backward the lowest at or above it; `None` on overflow.
fn nearest_pulse<T>(zero: T, pitch: T, old: T, new: T) -> Option<T>
where
    T: Copy + PartialOrd + Euclid,
{
    let k = if new >= old {
        new.checked_sub(zero)?.div_euclid(pitch)
    } else {
        zero.checked_sub(new)?.div_euclid(pitch).checked_neg()?
    };
    zero.checked_add(k.checked_mul(pitch)?)
}

/// The checked integer operations [`nearest_pulse`] needs, for i64 and i128.
trait Euclid: Sized {
    fn checked_sub(self, rhs: Self) -> Option<Self>;
    fn checked_add(self, rhs: Self) -> Option<Self>;
    fn checked_mul(self, rhs: Self) -> Option<Self>;
    fn checked_neg(self) -> Option<Self>;
    /// `pitch` is positive: never divides by zero; the quotient of a
    /// non-negative dividend cannot overflow.
    fn div_euclid(self, rhs: Self) -> Self;
}

macro_rules! euclid {
    ($($t:ty),*) => {$(
        impl Euclid for $t {
            fn checked_sub(self, rhs: Self) -> Option<Self> { <$t>::checked_sub(self, rhs) }
            fn checked_add(self, rhs: Self) -> Option<Self> { <$t>::checked_add(self, rhs) }
            fn checked_mul(self, rhs: Self) -> Option<Self> { <$t>::checked_mul(self, rhs) }
            fn checked_neg(self) -> Option<Self> { <$t>::checked_neg(self) }
            fn div_euclid(self, rhs: Self) -> Self { <$t>::div_euclid(self, rhs) }
        }
    )*};
}
euclid!(i64, i128);

/// Return `errors` with the summary bit set when any other bit is
/// (docs/servo.md#sew); a lone summary bit (an injected ServoErrors) stays.
const fn with_summary(errors: ServoErrorWord) -> ServoErrorWord {
    if errors.is_empty() {
        errors
    } else {
        errors.union(ServoErrorWord::SERVO_ERRORS)
    }
}

impl fmt::Display for ErrorClearState {
    /// Format the state as `idle`, `clearing (n)` or `acknowledged`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorClearState::Idle => f.write_str("idle"),
            ErrorClearState::Clearing(left) => write!(f, "clearing ({left})"),
            ErrorClearState::Acknowledged => f.write_str("acknowledged"),
        }
    }
}

impl fmt::Display for ZeroPulseState {
    /// Format the state as `idle`, `searching` or `found`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ZeroPulseState::Idle => "idle",
            ZeroPulseState::Searching => "searching",
            ZeroPulseState::Found => "found",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::ParameterTable;

    const SE_OFF: ServoEnable = ServoEnable::DISABLED;
    const SE_ARM: ServoEnable = ServoEnable::ARM;
    const SE_ON: ServoEnable = ServoEnable::ENABLE;

    fn scw(se: ServoEnable) -> ServoControlWord {
        ServoControlWord::NORMAL.with_servo_enable(se)
    }

    fn command(ssp: i32, control: ServoControlWord) -> Command {
        Command::new(ssp, control, 0)
    }

    /// Arm and enable: two cycles, SE 0b01 then 0b10.
    fn enable(drive: &mut Drive) -> Feedback {
        let _ = drive.cycle(&command(0, scw(SE_ARM)));
        drive.cycle(&command(0, scw(SE_ON)))
    }

    #[test]
    fn a_new_drive_is_disabled_at_zero_without_errors() {
        let mut drive = Drive::new(DriveConfig::default());
        assert!(!drive.is_enabled());
        assert_eq!(drive.position(), 0);
        assert_eq!(drive.errors(), ServoErrorWord::empty());
        // 0b10 without 0b01 before does not enable: the drive starts as if
        // SE had been 0b00.
        let fb = drive.cycle(&command(100, scw(SE_ON)));
        assert!(!fb.status.contains(ServoStatusWord::SERVO_EN));
        assert_eq!(fb.position, 0);
        assert_eq!(drive.cycles(), 1);
    }

    /// docs/servo.md#servo-ready, the interface manual's eight rows, produced
    /// by the model: (Servo_Ready_Mode, ServoEn, ServoErrors) → ServoRDY.
    #[test]
    fn servo_ready_truth_table_from_the_model() {
        const ROWS: [(u8, bool, bool, bool); 8] = [
            (0, false, false, true),
            (0, false, true, false),
            (0, true, false, true),
            (0, true, true, false),
            (1, false, false, false),
            (1, false, true, false),
            (1, true, false, true),
            (1, true, true, false),
        ];
        for (mode, enabled, error, ready) in ROWS {
            let mut drive = Drive::new(DriveConfig {
                ready_mode: ServoReadyMode::new(mode).unwrap(),
                // Keep running with an error, to reach the rows e=1, x=1.
                disable_on_fault: false,
                ..DriveConfig::default()
            });
            if error {
                drive.inject(ServoFault::HallErr);
            }
            let fb = if enabled {
                enable(&mut drive)
            } else {
                drive.cycle(&command(0, scw(SE_OFF)))
            };
            assert_eq!(fb.status.contains(ServoStatusWord::SERVO_EN), enabled);
            assert_eq!(fb.errors.contains(ServoErrorWord::SERVO_ERRORS), error);
            assert_eq!(
                fb.status.contains(ServoStatusWord::SERVO_RDY),
                ready,
                "mode {mode}, ServoEn {enabled}, ServoErrors {error}"
            );
        }
    }

    #[test]
    fn enable_only_on_the_edge_and_while_se_stays() {
        let mut drive = Drive::new(DriveConfig::default());
        let steps = [
            (SE_OFF, false),
            (SE_ON, false),
            (SE_ARM, false),
            (SE_ON, true),
            (SE_ON, true),
            (ServoEnable::BOTH, false),
            (SE_ON, false),
            (SE_ARM, false),
            (SE_ON, true),
            (SE_OFF, false),
        ];
        for (i, (se, enabled)) in steps.into_iter().enumerate() {
            let fb = drive.cycle(&command(0, scw(se)));
            assert_eq!(
                fb.status.contains(ServoStatusWord::SERVO_EN),
                enabled,
                "cycle {i}"
            );
            assert_eq!(fb.status.contains(ServoStatusWord::PULSE_ENABLED), enabled);
        }
    }

    #[test]
    fn a_fault_disables_until_cleared_and_enabled_again() {
        let mut drive = Drive::new(DriveConfig {
            error_clear_delay: 0,
            ..DriveConfig::default()
        });
        assert!(enable(&mut drive)
            .status
            .contains(ServoStatusWord::SERVO_EN));
        drive.inject(ServoFault::FollowerErr);
        let fb = drive.cycle(&command(0, scw(SE_ON)));
        assert!(!fb.status.contains(ServoStatusWord::SERVO_EN));
        assert_eq!(fb.errors.bits(), (1 << 19) | 1);
        assert_eq!(fb.errors.faults().filter_map(ServoFault::e_code).count(), 1);
        // An edge while the error is present is lost.
        let _ = drive.cycle(&command(0, scw(SE_ARM)));
        assert!(!drive
            .cycle(&command(0, scw(SE_ON)))
            .status
            .contains(ServoStatusWord::SERVO_EN));
        // Clear: acked in the same cycle (delay 0); SE 0b10 held does not
        // enable again.
        let fb = drive.cycle(&command(0, scw(SE_ON) | ServoControlWord::ERROR_CLEAR));
        assert!(fb.status.contains(ServoStatusWord::ERR_CLEAR_ACK));
        assert_eq!(fb.errors, ServoErrorWord::empty());
        assert!(!fb.status.contains(ServoStatusWord::SERVO_EN));
        let fb = drive.cycle(&command(0, scw(SE_ON)));
        assert!(!fb.status.contains(ServoStatusWord::ERR_CLEAR_ACK));
        assert!(enable(&mut drive)
            .status
            .contains(ServoStatusWord::SERVO_EN));
    }

    #[test]
    fn error_clear_waits_the_delay_and_acks_until_the_request_falls() {
        let mut drive = Drive::new(DriveConfig {
            error_clear_delay: 2,
            ..DriveConfig::default()
        });
        drive.inject(ServoFault::BvErr);
        let clear = scw(SE_OFF) | ServoControlWord::ERROR_CLEAR;
        let acks: Vec<(bool, u32)> = [clear, clear, clear, clear, scw(SE_OFF), scw(SE_OFF)]
            .iter()
            .map(|&c| {
                let fb = drive.cycle(&command(0, c));
                (
                    fb.status.contains(ServoStatusWord::ERR_CLEAR_ACK),
                    fb.errors.bits(),
                )
            })
            .collect();
        assert_eq!(
            acks,
            [
                (false, 0x21), // clearing (2)
                (false, 0x21), // clearing (1)
                (true, 0),     // cleared, acked
                (true, 0),     // ack held while ErrorClear is 1
                (false, 0),    // ErrorClear fell: ack dropped
                (false, 0),
            ]
        );
    }

    #[test]
    fn a_fault_during_a_held_request_stays_until_the_next_request() {
        let mut drive = Drive::new(DriveConfig {
            error_clear_delay: 0,
            ..DriveConfig::default()
        });
        let clear = scw(SE_OFF) | ServoControlWord::ERROR_CLEAR;
        assert!(drive
            .cycle(&command(0, clear))
            .status
            .contains(ServoStatusWord::ERR_CLEAR_ACK));
        drive.inject(ServoFault::CurrErr);
        let fb = drive.cycle(&command(0, clear));
        assert!(fb.status.contains(ServoStatusWord::ERR_CLEAR_ACK));
        assert_eq!(fb.errors.bits(), 0x41);
        let _ = drive.cycle(&command(0, scw(SE_OFF)));
        assert_eq!(
            drive.cycle(&command(0, clear)).errors,
            ServoErrorWord::empty()
        );
    }

    #[test]
    fn a_request_dropped_before_the_delay_clears_nothing() {
        let mut drive = Drive::new(DriveConfig::default());
        drive.inject(ServoFault::OverSpeed);
        let clear = scw(SE_OFF) | ServoControlWord::ERROR_CLEAR;
        let _ = drive.cycle(&command(0, clear));
        assert_eq!(drive.error_clear_state(), ErrorClearState::Clearing(2));
        let fb = drive.cycle(&command(0, scw(SE_OFF)));
        assert_eq!(drive.error_clear_state(), ErrorClearState::Idle);
        assert!(fb.errors.contains(ServoErrorWord::OVER_SPEED));
    }

    #[test]
    fn a_lone_summary_bit_is_an_error() {
        let mut drive = Drive::new(DriveConfig::default());
        drive.inject(ServoFault::ServoErrors);
        let fb = drive.cycle(&command(0, scw(SE_OFF)));
        assert_eq!(fb.errors, ServoErrorWord::SERVO_ERRORS);
        assert!(!fb.status.contains(ServoStatusWord::SERVO_RDY));
    }

    #[test]
    fn a_lost_encoder_freezes_the_position_and_comes_back_after_a_clear() {
        let mut drive = Drive::new(DriveConfig {
            error_clear_delay: 0,
            disable_on_fault: false,
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        let _ = drive.cycle(&command(10, scw(SE_ON)));
        assert_eq!(drive.position(), 10);
        drive.lose_encoder();
        let fb = drive.cycle(&command(10, scw(SE_ON)));
        assert_eq!(drive.position(), 10);
        assert_eq!(fb.errors.bits(), 0b11);
        assert!(drive.encoder_lost());
        let fb = drive.cycle(&command(10, scw(SE_ON) | ServoControlWord::ERROR_CLEAR));
        assert!(fb.status.contains(ServoStatusWord::ERR_CLEAR_ACK));
        assert_eq!(fb.errors.bits(), 0b11, "the cause persists");
        drive.restore_encoder();
        let fb = drive.cycle(&command(10, scw(SE_ON)));
        assert_eq!(fb.errors.bits(), 0b11, "latched until cleared");
        assert_eq!(drive.position(), 20);
        let fb = drive.cycle(&command(10, scw(SE_ON) | ServoControlWord::ERROR_CLEAR));
        assert_eq!(fb.errors, ServoErrorWord::empty());
    }

    #[test]
    fn temperature_warning_and_endat_over_temperature() {
        for (encoder, e19) in [
            (EncoderKind::Absolute, true),
            (EncoderKind::Incremental, false),
        ] {
            let mut drive = Drive::new(DriveConfig {
                encoder,
                messages: MessageRotation::only(MessageCode::MotorTemperature).unwrap(),
                ..DriveConfig::default()
            });
            drive.set_motor_temperature(80.0);
            let fb = drive.cycle(&command(0, scw(SE_OFF)));
            assert!(!fb.status.contains(ServoStatusWord::TEMP_WARNING));
            assert_eq!(
                fb.message,
                Message::new(MessageCode::MotorTemperature, 80.0)
            );
            drive.set_motor_temperature(85.5);
            let fb = drive.cycle(&command(0, scw(SE_OFF)));
            assert!(fb.status.contains(ServoStatusWord::TEMP_WARNING));
            assert!(fb.errors.is_empty());
            drive.set_motor_temperature(96.0);
            let fb = drive.cycle(&command(0, scw(SE_OFF)));
            assert_eq!(
                fb.errors.contains(ServoErrorWord::I2T_ENDAT),
                e19,
                "{encoder}"
            );
            assert_eq!(fb.errors.contains(ServoErrorWord::SERVO_ERRORS), e19);
        }
    }

    #[test]
    fn act_pos_integrates_the_set_point_while_enabled() {
        let mut drive = Drive::new(DriveConfig {
            encoder: EncoderKind::Absolute,
            ..DriveConfig::default()
        });
        let _ = drive.cycle(&command(500, scw(SE_OFF)));
        assert_eq!(drive.position(), 0, "disabled: no motion");
        let _ = enable(&mut drive);
        for _ in 0..10 {
            let _ = drive.cycle(&command(-250, scw(SE_ON)));
        }
        assert_eq!(drive.position(), -2_500);
        let fb = drive.cycle(&command(0, scw(SE_ON)));
        assert_eq!(fb.actual_position(), ActualPosition::Absolute(-2_500));
        assert!(fb
            .status
            .contains(ServoStatusWord::N_ZERO | ServoStatusWord::N_EQ_NS));
    }

    #[test]
    fn the_speed_scale_carries_fractions() {
        let mut drive = Drive::new(DriveConfig {
            speed_scale: SpeedScale::new(1, 3).unwrap(),
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        let positions: Vec<i64> = (0..6)
            .map(|_| {
                let _ = drive.cycle(&command(1, scw(SE_ON)));
                drive.position()
            })
            .collect();
        assert_eq!(positions, [0, 0, 1, 1, 1, 2]);
        for _ in 0..6 {
            let _ = drive.cycle(&command(-1, scw(SE_ON)));
        }
        assert_eq!(drive.position(), 0);
        assert_eq!(SpeedScale::new(7, 0), None);
        let extreme = SpeedScale::new(u32::MAX, 1).unwrap();
        let mut drive = Drive::new(DriveConfig {
            speed_scale: extreme,
            encoder: EncoderKind::Absolute,
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        for _ in 0..4 {
            let _ = drive.cycle(&command(i32::MIN, scw(SE_ON)));
        }
        // Wraps like a counter, never panics.
        let step = i64::from(i32::MIN) * i64::from(u32::MAX);
        assert_eq!(drive.position(), step.wrapping_mul(4));
    }

    #[test]
    fn word_setpoint_emergency_feed_and_poslock() {
        let mut drive = Drive::new(DriveConfig {
            setpoint_width: SetpointWidth::Word,
            emergency_feed: -3,
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        // 0x0001_0005: the word reading is 5.
        let fb = drive.cycle(&command(0x0001_0005, scw(SE_ON)));
        assert_eq!(drive.position(), 5);
        assert!(fb.status.contains(ServoStatusWord::N_EQ_NS));
        let fb = drive.cycle(&command(5, scw(SE_ON).with_emergency(true)));
        assert_eq!(drive.position(), 2);
        assert_eq!(drive.applied_speed(), -3);
        assert!(!fb.status.contains(ServoStatusWord::N_EQ_NS));
        let fb = drive.cycle(&command(5, scw(SE_ON) | ServoControlWord::POSLOCK));
        assert_eq!(drive.position(), 2);
        assert!(fb.status.contains(ServoStatusWord::N_ZERO));
    }

    #[test]
    fn zero_pulse_found_once_passed_and_dropped_with_the_request() {
        let mut drive = Drive::new(DriveConfig {
            zero_pulse_position: 25,
            zero_pulse_pitch: None,
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        let search = scw(SE_ON) | ServoControlWord::Z_PULSE_REQUEST;
        let mut trace = Vec::new();
        for c in [search, search, search, search, scw(SE_ON), scw(SE_ON)] {
            let fb = drive.cycle(&command(10, c));
            let ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } = fb.actual_position()
            else {
                panic!("incremental layout expected");
            };
            trace.push((
                position,
                fb.status.contains(ServoStatusWord::Z_PULSE_ACK),
                zero_pulse_position,
            ));
        }
        assert_eq!(
            trace,
            [
                (10, false, 0),
                (20, false, 0),
                (30, true, 25), // passed 25
                (40, true, 25),
                (50, false, 25), // request fell: ack dropped, position kept
                (60, false, 25),
            ]
        );
    }

    #[test]
    fn later_zero_pulses_update_the_latch_in_both_directions() {
        let mut drive = Drive::new(DriveConfig {
            zero_pulse_position: 5,
            zero_pulse_pitch: NonZeroU32::new(100),
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        // Passing a pulse before any request latches nothing.
        let _ = drive.cycle(&command(10, scw(SE_ON)));
        assert_eq!(drive.zero_pulse_latch(), 0);
        let search = scw(SE_ON) | ServoControlWord::Z_PULSE_REQUEST;
        for _ in 0..10 {
            let _ = drive.cycle(&command(10, search));
        }
        assert_eq!(drive.position(), 110);
        assert_eq!(drive.zero_pulse_state(), ZeroPulseState::Found);
        assert_eq!(drive.zero_pulse_latch(), 105);
        let _ = drive.cycle(&command(0, scw(SE_ON)));
        // Backward across 105 and 5, then to -95 (reached: passed).
        let mut latches = Vec::new();
        for _ in 0..4 {
            let fb = drive.cycle(&command(-50, scw(SE_ON)));
            latches.push((drive.position(), fb.actual_position()));
        }
        let incr = |position, zero_pulse_position| ActualPosition::Incremental {
            position,
            zero_pulse_position,
        };
        assert_eq!(
            latches,
            [
                (60, incr(60, 105)),
                (10, incr(10, 105)),
                (-40, incr(-40, 5)),
                (-90, incr(-90, 5))
            ]
        );
        let _ = drive.cycle(&command(-5, scw(SE_ON)));
        assert_eq!(drive.zero_pulse_latch(), -95);
    }

    /// Near the ends of the i64 range the pulse is found with i128
    /// arithmetic, and nothing overflows.
    #[test]
    fn zero_pulses_at_the_ends_of_the_range() {
        let mut drive = Drive::new(DriveConfig {
            zero_pulse_position: -1_000,
            zero_pulse_pitch: NonZeroU32::new(1_000),
            speed_scale: SpeedScale::new(u32::MAX, 1).unwrap(),
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        let search = scw(SE_ON) | ServoControlWord::Z_PULSE_REQUEST;
        let fb = drive.cycle(&command(i32::MAX, search));
        let new = i128::from(i32::MAX) * i128::from(u32::MAX);
        assert_eq!(i128::from(drive.position()), new);
        let expected = -1_000 + (new + 1_000).div_euclid(1_000) * 1_000;
        assert_eq!(i128::from(drive.zero_pulse_latch()), expected);
        assert!(fb.status.contains(ServoStatusWord::Z_PULSE_ACK));
        // And back down past i64::MIN's side, wrapping: no panic.
        for _ in 0..3 {
            let _ = drive.cycle(&command(i32::MIN, search));
        }
        assert_eq!(
            nearest_pulse(0i64, 10, i64::MIN, i64::MAX),
            Some(i64::MAX - 7)
        );
        assert_eq!(nearest_pulse(-5i64, 10, 0, i64::MAX), None);
        assert_eq!(
            nearest_pulse(-5i128, 10, 0, i128::from(i64::MAX)),
            Some(i128::from(i64::MAX) - 2)
        );
    }

    #[test]
    fn an_absolute_encoder_never_answers_a_zero_pulse_request() {
        let mut drive = Drive::new(DriveConfig {
            encoder: EncoderKind::Absolute,
            ..DriveConfig::default()
        });
        let _ = enable(&mut drive);
        for _ in 0..100 {
            let fb = drive.cycle(&command(
                1_000,
                scw(SE_ON) | ServoControlWord::Z_PULSE_REQUEST,
            ));
            assert!(!fb.status.contains(ServoStatusWord::Z_PULSE_ACK));
            assert!(!fb.status.contains(ServoStatusWord::ABS_INCR));
            assert_eq!(
                fb.actual_position(),
                ActualPosition::Absolute(drive.position())
            );
        }
        assert_eq!(drive.position(), 100_000);
    }

    #[test]
    fn the_message_channel_rotates() {
        let mut drive = Drive::new(DriveConfig::default());
        drive.set_measurement(MessageCode::BusVoltage, 600.0);
        drive.set_measurement(MessageCode::MotorCurrent, 1.5);
        // Speed is the applied speed, not settable; unknown codes ignored.
        drive.set_measurement(MessageCode::MotorSpeed, 9.0);
        drive.set_measurement(MessageCode::Unknown(42), 9.0);
        let _ = drive.cycle(&command(0, scw(SE_ARM)));
        let mut seen = Vec::new();
        for _ in 0..6 {
            let fb = drive.cycle(&command(7, scw(SE_ON)));
            seen.push((fb.message.code, fb.message.data));
        }
        assert_eq!(
            seen,
            [
                (1, 1.5),
                (2, 0.0),
                (3, 600.0),
                (4, 40.0),
                (0, 7.0),
                (1, 1.5)
            ]
        );
        assert_eq!(MessageRotation::new(0), None);
        assert_eq!(MessageRotation::new(1 << 10), None);
        assert_eq!(
            MessageRotation::from_kinds(&[MessageCode::Unknown(10)]),
            None
        );
        assert_eq!(MessageRotation::from_kinds(&[]), None);
        let all = MessageRotation::ALL_CODES;
        assert_eq!(all.codes().collect::<Vec<_>>(), (0..=9).collect::<Vec<_>>());
        assert_eq!(all.next_after(9), 0);
        assert_eq!(all.next_after(-7), 0);
        assert_eq!(all.next_after(i32::MAX), 0);
        let odd =
            MessageRotation::from_kinds(&[MessageCode::Reserved(9), MessageCode::MotorCurrent])
                .unwrap();
        assert_eq!(
            (
                odd.first(),
                odd.next_after(1),
                odd.next_after(5),
                odd.bits()
            ),
            (1, 9, 9, 0x202)
        );
    }

    #[test]
    fn the_parameter_table_is_echoed() {
        let mut drive = Drive::new(DriveConfig::default());
        for table in ParameterTable::all() {
            let fb = drive.cycle(&command(0, scw(SE_OFF).with_parameter_table(table)));
            assert_eq!(fb.status.parameter_table(), table);
        }
    }

    #[test]
    fn the_model_is_deterministic() {
        let run = || {
            let mut drive = Drive::new(DriveConfig::default());
            let mut out = Vec::new();
            for i in 0..200i32 {
                if i == 77 {
                    drive.inject(ServoFault::ECatRtErr);
                }
                let se = ServoEnable::new((i % 7 % 4) as u8).unwrap();
                let control = scw(se).with_flag(ServoControlWord::ERROR_CLEAR, i % 11 > 6);
                out.push(drive.cycle(&command(i * 3 - 100, control)).to_bytes());
            }
            (out, drive)
        };
        assert_eq!(run(), run());
    }

    #[test]
    fn states_display() {
        assert_eq!(ErrorClearState::Clearing(3).to_string(), "clearing (3)");
        assert_eq!(ErrorClearState::Idle.to_string(), "idle");
        assert_eq!(ErrorClearState::Acknowledged.to_string(), "acknowledged");
        assert_eq!(ZeroPulseState::Searching.to_string(), "searching");
        assert_eq!(ZeroPulseState::Found.to_string(), "found");
        assert_eq!(ZeroPulseState::Idle.to_string(), "idle");
        let scale = SpeedScale::default();
        assert_eq!((scale.counts(), scale.per_setpoint()), (1, 1));
        assert_eq!(SetpointWidth::Word.read(&command(-1, scw(SE_OFF))), -1);
    }
}
