//! The EtherCAT servo ↔ NC frames as JSON records: what `motionwire servo
//! command|feedback --json` writes (docs/servo.md#cli-command,
//! docs/servo.md#cli-feedback), key for key and in order, as values a
//! program serializes itself.

use serde::Serialize;

use crate::servo::{ActualPosition, Command, ECode, Feedback, ServoFault};

/// A command frame as its JSON record (docs/servo.md#cli-command): every
/// field of the [`Command`] with its control word read out.
///
/// ```
/// use motionwire::decoder::CommandRecord;
/// use motionwire::servo::Command;
///
/// let bytes = [0x64, 0, 0, 0, 0x06, 0x02, 0, 0, 0xFF, 0xFF];
/// let command = Command::parse(&bytes)?;
/// let json = serde_json::to_string(&CommandRecord::from(&command)).unwrap();
/// assert_eq!(
///     json,
///     r#"{"speed_setpoint":100,"speed_setpoint_word":100,"control":518,"control_flags":["EMGON","ErrorClear"],"servo_enable":2,"regulator_mode":"speed","parameter_table":1,"extra_data_code":-1}"#
/// );
/// # Ok::<(), motionwire::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct CommandRecord {
    /// SSP, the speed set point.
    pub speed_setpoint: i32,
    /// SSPW0 alone, the word-type reading.
    pub speed_setpoint_word: i16,
    /// SCW, every bit.
    pub control: u32,
    /// The names of the set single-bit flags of SCW, in bit order.
    pub control_flags: Vec<&'static str>,
    /// SE, the servo-enable field (0–3).
    pub servo_enable: u8,
    /// The regulator mode's name (`speed`, `current`, `position`,
    /// `precise_speed`).
    pub regulator_mode: &'static str,
    /// The parameter table (1–8).
    pub parameter_table: u8,
    /// The extra-data code.
    pub extra_data_code: i16,
}

impl From<&Command> for CommandRecord {
    fn from(c: &Command) -> Self {
        CommandRecord {
            speed_setpoint: c.speed_setpoint,
            speed_setpoint_word: c.speed_setpoint_word(),
            control: c.control.bits(),
            control_flags: c.control.flag_names().collect(),
            servo_enable: c.control.servo_enable().get(),
            regulator_mode: c.control.regulator_mode().name(),
            parameter_table: c.control.parameter_table().get(),
            extra_data_code: c.extra_data_code,
        }
    }
}

/// One fault of a feedback frame's error word, as `{"bit", "name",
/// "e_code"}` (docs/servo.md#cli-feedback).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct FaultRecord {
    /// The bit of SEW.
    pub bit: u8,
    /// The bit's name.
    pub name: &'static str,
    /// Its E-code, written `"E09"`; `null` for a bit without one.
    #[serde(serialize_with = "e_code")]
    pub e_code: Option<ECode>,
}

impl From<ServoFault> for FaultRecord {
    fn from(fault: ServoFault) -> Self {
        FaultRecord {
            bit: fault.bit(),
            name: fault.name(),
            e_code: fault.e_code(),
        }
    }
}

/// An E-code as its text, `"E09"`.
fn e_code<S: serde::Serializer>(code: &Option<ECode>, serializer: S) -> Result<S::Ok, S::Error> {
    match code {
        Some(code) => serializer.collect_str(code),
        None => serializer.serialize_none(),
    }
}

/// A feedback frame as its JSON record (docs/servo.md#cli-feedback): every
/// field of the [`Feedback`] with its status and error words read out.
/// Floats are the f32's value as `f64`; `serde_json` writes a NaN or an
/// infinity as `null`.
///
/// ```
/// use motionwire::decoder::FeedbackRecord;
/// use motionwire::servo::{Feedback, FEEDBACK_LEN};
///
/// let mut bytes = [0; FEEDBACK_LEN];
/// bytes[..8].copy_from_slice(&[0x40, 0xE2, 0x01, 0x00, 0x00, 0x10, 0x00, 0x00]);
/// bytes[8] = 0x04; // AbsIncr: an incremental encoder
/// let record = FeedbackRecord::from(&Feedback::parse(&bytes)?);
/// assert_eq!(record.encoder, "incremental");
/// assert_eq!(record.incremental_position, Some(123_456));
/// assert_eq!(record.zero_pulse_position, Some(4096));
/// let json = serde_json::to_value(&record).unwrap();
/// assert_eq!(json["status_flags"], serde_json::json!(["AbsIncr"]));
/// # Ok::<(), motionwire::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeedbackRecord {
    /// ActPos, raw.
    pub position: i64,
    /// The encoder's kind, `absolute` or `incremental` (SSW bit 2).
    pub encoder: &'static str,
    /// POSW0..1, for an incremental encoder.
    pub incremental_position: Option<i32>,
    /// POSW2..3, for an incremental encoder.
    pub zero_pulse_position: Option<i32>,
    /// SSW, every bit.
    pub status: u32,
    /// The names of the set single-bit flags of SSW, in bit order.
    pub status_flags: Vec<&'static str>,
    /// The active parameter table (1–8).
    pub parameter_table: u8,
    /// SEW, every bit.
    pub errors: u32,
    /// Each named SEW bit that is set, in bit order.
    pub faults: Vec<FaultRecord>,
    /// The message code.
    pub message_code: i32,
    /// The message's name (`motor_speed`, …, `unknown`).
    pub message: &'static str,
    /// The message data.
    pub message_value: f64,
    /// Extra data 1–4.
    pub extra: [f64; 4],
}

impl From<&Feedback> for FeedbackRecord {
    fn from(f: &Feedback) -> Self {
        let (incremental_position, zero_pulse_position) = match f.actual_position() {
            ActualPosition::Absolute(_) => (None, None),
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => (Some(position), Some(zero_pulse_position)),
        };
        FeedbackRecord {
            position: f.position,
            encoder: f.status.encoder().name(),
            incremental_position,
            zero_pulse_position,
            status: f.status.bits(),
            status_flags: f.status.flag_names().collect(),
            parameter_table: f.status.parameter_table().get(),
            errors: f.errors.bits(),
            faults: f.errors.faults().map(FaultRecord::from).collect(),
            message_code: f.message.code,
            message: f.message.kind().name(),
            message_value: f64::from(f.message.data),
            extra: f.extra_data.map(f64::from),
        }
    }
}
