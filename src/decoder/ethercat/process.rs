//! One slave's process data in one cyclic datagram, as the session cut
//! it ([`ProcessData`]), and the servo frames of docs/servo.md read from
//! it ([`ServoReading`]) (docs/ethercat.md#process-data).

use crate::canopen::Signal;
use crate::decoder::Cia402Reading;
use crate::servo::{
    servo_ready, Command, EnableHandshake, EnablePhase, ErrorClearHandshake, Feedback,
    HandshakePhase, ServoControlWord, ServoEnable, ServoReadyMode, ServoStatusWord,
    ZeroPulseHandshake, COMMAND_LEN, FEEDBACK_LEN,
};
use crate::CodecError;

use super::image::Plan;
use super::missing::Missed;
use super::slave::SlaveRef;

/// One item of `--servo` (docs/ethercat.md#servo): `auto`, or a station
/// address (decimal or `0x` hex) with `:MODE`, its Servo_Ready_Mode, where
/// given. The program and the Python package read the same text with
/// [`str::parse`].
///
/// ```
/// use motionwire::decoder::ethercat::{ServoItem, ServoSlaves};
/// use motionwire::servo::ServoReadyMode;
///
/// let slaves: ServoSlaves = ["auto", "0x1001:1", "4098"]
///     .iter()
///     .map(|item| item.parse::<ServoItem>())
///     .collect::<Result<_, _>>()?;
/// assert!(slaves.auto);
/// assert_eq!(
///     slaves.stations,
///     [(0x1001, Some(ServoReadyMode::EnabledAndErrorFree)), (0x1002, None)]
/// );
/// assert_eq!(
///     "0x1001:2".parse::<ServoItem>().unwrap_err().to_string(),
///     "\"2\" is not a Servo_Ready_Mode (0 or 1)"
/// );
/// # Ok::<(), motionwire::decoder::ethercat::ServoItemError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ServoItem {
    /// Every slave whose outputs are 10 bytes and inputs 40.
    Auto,
    /// One slave by station address, with its Servo_Ready_Mode where given.
    Station(u16, Option<ServoReadyMode>),
}

/// Why a `--servo` item does not read ([`ServoItem`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ServoItemError {
    /// The station address is not a number of 0 to 65535.
    #[error("{0:?} is not a station address (0 to 65535, decimal or 0x hex)")]
    Station(String),
    /// The mode after `:` is not 0 or 1.
    #[error("{0:?} is not a Servo_Ready_Mode (0 or 1)")]
    Mode(String),
}

impl core::str::FromStr for ServoItem {
    type Err = ServoItemError;

    /// Read `auto`, `STATION` or `STATION:MODE`.
    fn from_str(text: &str) -> Result<Self, ServoItemError> {
        if text == "auto" {
            return Ok(ServoItem::Auto);
        }
        let (station, mode) = match text.split_once(':') {
            Some((station, mode)) => {
                let parsed = mode.parse::<u8>().ok().and_then(ServoReadyMode::new);
                let mode = parsed.ok_or_else(|| ServoItemError::Mode(mode.to_owned()))?;
                (station, Some(mode))
            }
            None => (text, None),
        };
        let parsed = match station
            .strip_prefix("0x")
            .or_else(|| station.strip_prefix("0X"))
        {
            Some(hex) => u16::from_str_radix(hex, 16),
            None => station.parse(),
        };
        let station = parsed.map_err(|_| ServoItemError::Station(station.to_owned()))?;
        Ok(ServoItem::Station(station, mode))
    }
}

/// Which slaves carry the servo frames of docs/servo.md (`--servo`):
/// named by station address, or found by their images' lengths.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ServoSlaves {
    /// Every slave whose outputs are 10 bytes and inputs 40
    /// (`--servo auto`).
    pub auto: bool,
    /// Slaves by station address, each with its Servo_Ready_Mode where
    /// given (`--servo 0x1001:1`; the mode is not on the wire, the
    /// default is [`ServoReadyMode::ErrorFree`]).
    pub stations: Vec<(u16, Option<ServoReadyMode>)>,
}

impl ServoSlaves {
    /// Add what `item` names: every slave of 10 and 40 bytes, or a
    /// station.
    pub fn add(&mut self, item: ServoItem) {
        match item {
            ServoItem::Auto => self.auto = true,
            ServoItem::Station(station, mode) => self.stations.push((station, mode)),
        }
    }

    /// Return whether no slave is read as a servo.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !self.auto && self.stations.is_empty()
    }

    /// The mode of the slave at `station` with images of `lens` bytes,
    /// when it is read as a servo.
    pub(super) fn mode(
        &self,
        station: Option<u16>,
        lens: (usize, usize),
    ) -> Option<ServoReadyMode> {
        let named = station.and_then(|s| self.stations.iter().find(|(n, _)| *n == s));
        match named {
            Some((_, mode)) => Some(mode.unwrap_or(ServoReadyMode::ErrorFree)),
            None if self.auto && lens == (COMMAND_LEN, FEEDBACK_LEN) => {
                Some(ServoReadyMode::ErrorFree)
            }
            None => None,
        }
    }
}

impl FromIterator<ServoItem> for ServoSlaves {
    fn from_iter<I: IntoIterator<Item = ServoItem>>(items: I) -> Self {
        let mut slaves = ServoSlaves::default();
        for item in items {
            slaves.add(item);
        }
        slaves
    }
}

/// What one cycle's process data of a servo says (docs/servo.md): the
/// command the NC wrote, the drive's feedback, and the phases of the
/// three handshakes as the crate's own NC-side state machines follow them
/// across cycles from what is on the wire.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoReading {
    /// The command of this cycle's outputs.
    pub command: Command,
    /// The feedback of this cycle's inputs; `None` where the inputs are
    /// unconfirmed (a short working counter).
    pub feedback: Option<Feedback>,
    /// The enable handshake's phase (SCW.SE and SSW.ServoEn).
    pub enable: EnablePhase,
    /// How many cycles the enable handshake has been in its phase.
    pub enable_cycles: u32,
    /// The error-clear handshake's phase.
    pub error_clear: HandshakePhase,
    /// The zero-pulse handshake's phase.
    pub zero_pulse: HandshakePhase,
    /// ServoRDY by the drive's Servo_Ready_Mode (docs/servo.md#servo-ready),
    /// where the feedback is known.
    pub ready: Option<bool>,
}

/// The NC side of a servo's handshakes, stepped from the wire.
#[derive(Debug, Clone, Copy)]
pub(super) struct ServoWatch {
    mode: ServoReadyMode,
    enable: EnableHandshake,
    clear: ErrorClearHandshake,
    zero: ZeroPulseHandshake,
    /// The last cycle's control word and the status word that came back
    /// with it (`None`: unconfirmed).
    last: Option<(ServoControlWord, Option<ServoStatusWord>)>,
}

impl ServoWatch {
    pub(super) fn new(mode: ServoReadyMode) -> Self {
        ServoWatch {
            mode,
            enable: EnableHandshake::new(),
            clear: ErrorClearHandshake::new(),
            zero: ZeroPulseHandshake::new(),
            last: None,
        }
    }

    /// One cycle: the command on the wire and the feedback that came back
    /// with it. As an NC does each cycle, the handshakes first step on the
    /// last cycle's control word and the status word it brought back; then
    /// the NC's decisions (arm, withdraw, request) are read from this
    /// cycle's command. The phases returned are the NC's as it wrote the
    /// command.
    pub(super) fn cycle(&mut self, command: &Command, feedback: Option<&Feedback>) -> ServoReading {
        if let Some((control, Some(status))) = self.last {
            (self.enable, _) = self.enable.step(control, status);
            (self.clear, _) = self.clear.step(control, status);
            (self.zero, _) = self.zero.step(control, status);
        }
        let control = command.control;
        let se = control.servo_enable();
        let enable = self.enable.phase();
        if se == ServoEnable::ARM
            && matches!(
                enable,
                EnablePhase::Disabled | EnablePhase::Disabling | EnablePhase::Dropped
            )
        {
            self.enable = self.enable.start();
        } else if se == ServoEnable::ARM && enable == EnablePhase::Enabling {
            self.enable = self.enable.cancel().start();
        } else if se == ServoEnable::DISABLED
            && matches!(
                enable,
                EnablePhase::Arming | EnablePhase::Enabling | EnablePhase::Enabled
            )
        {
            self.enable = self.enable.cancel();
        }
        let requested = |bit: ServoControlWord| control.contains(bit);
        if requested(ServoControlWord::ERROR_CLEAR)
            && matches!(
                self.clear.phase(),
                HandshakePhase::Idle | HandshakePhase::Done
            )
        {
            self.clear = self.clear.start();
        }
        if requested(ServoControlWord::Z_PULSE_REQUEST)
            && matches!(
                self.zero.phase(),
                HandshakePhase::Idle | HandshakePhase::Done
            )
        {
            self.zero = self.zero.start();
        }
        self.last = Some((control, feedback.map(|f| f.status)));
        ServoReading {
            command: *command,
            feedback: feedback.copied(),
            enable: self.enable.phase(),
            enable_cycles: self.enable.cycles_in_phase(),
            error_clear: self.clear.phase(),
            zero_pulse: self.zero.phase(),
            ready: feedback.map(|f| servo_ready(self.mode, f.status, f.errors)),
        }
    }
}

/// One slave's process data in one cyclic datagram (LRW, LRD, LWR), as
/// the session cut it (docs/ethercat.md#process-data): its outputs from
/// the sent copy, its inputs from the returned one, whether the working
/// counter confirms the inputs, and what they say of a CiA 402 drive or a
/// servo.
#[derive(Debug, Clone, Copy)]
pub struct ProcessData<'s> {
    /// The slave; `None` where no FMMU of the range is known: the record
    /// is then the datagram's bytes as outputs (sent) and inputs
    /// (returned).
    pub slave: Option<SlaveRef>,
    /// The datagram's logical address.
    pub logical: u32,
    /// The working counter that came back.
    pub wkc: u16,
    /// The working counter the FMMUs expect of the datagram, where they
    /// are known.
    pub expected_wkc: Option<u16>,
    /// Whether the inputs are confirmed: the working counter is the
    /// expected one, or the shortfall can only be other slaves'.
    pub confirmed: bool,
    /// What a short working counter says of this slave: whether the
    /// evidence names it, and which (docs/ethercat.md#wkc); [`Missed::No`]
    /// for a whole count and for a record of no slave.
    pub missed: Missed,
    /// The outputs image, when the datagram holds all of it (from the
    /// sent copy; the returned one where the capture has no sent copy).
    pub outputs: Option<&'s [u8]>,
    /// The inputs image, when the datagram holds all of it.
    pub inputs: Option<&'s [u8]>,
    /// The CiA 402 reading of a slave whose PDOs map 6041h, 6040h or
    /// 6060h/6061h (no state is read from unconfirmed inputs).
    pub cia402: Option<Cia402Reading>,
    /// The servo frames, for a slave read as a servo ([`ServoSlaves`]).
    pub servo: Option<ServoReading>,
    pub(super) plan: Option<&'s Plan>,
}

impl ProcessData<'_> {
    /// Call `f` with each signal of the outputs, then of the inputs, in
    /// mapping order: whether it is an output, its name (the
    /// configuration's, the object table's, or `0x6041:00`) and its value
    /// or why it could not be read.
    pub fn for_each_signal(&self, mut f: impl FnMut(bool, &str, Result<Signal, CodecError>)) {
        let Some(plan) = self.plan else { return };
        for (output, image) in [(true, self.outputs), (false, self.inputs)] {
            if let Some(image) = image {
                plan.for_each_signal(output, image, |name, signal| f(output, name, signal));
            }
        }
    }

    /// Return whether the slave's PDOs are known (its signals can be read).
    #[must_use]
    pub fn has_signals(&self) -> bool {
        self.plan.is_some_and(Plan::has_signals)
    }
}
