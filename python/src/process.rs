//! The process data of an EtherCAT capture as tables
//! (docs/python.md#process-data): `process_data`, one row per signal per
//! slave per returned cyclic datagram, and `servo`, one row per servo per
//! cycle. The library's `ethercat::Session` cuts each cyclic datagram per
//! slave (`Session::process_data`), reads the signals
//! (`ProcessData::for_each_signal`) and the servo frames with their
//! handshakes (`ServoReading`); this module only moves the values into
//! Arrow columns, in record batches of at most [`BATCH_ROWS`] rows.

use std::sync::Arc;

use arrow_array::types::{
    Float64Type, Int32Type, Int64Type, Int8Type, UInt16Type, UInt32Type, UInt64Type, UInt8Type,
};
use arrow_array::{BooleanArray, ListArray, RecordBatch, StringArray};
use arrow_buffer::OffsetBuffer;
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use motionwire::can::LogEvent;
use motionwire::canopen::Value;
use motionwire::decoder::ethercat::{
    Meaning, Packet, ProcessData, ServoItem, ServoItemError, ServoReading, ServoSlaves, Session,
};
use motionwire::decoder::DecoderConfig;
use motionwire::ethercat::Datagram;
use motionwire::logs::{LogErrorKind, LogFormat, LogVisitor, ReadLog};
use motionwire::servo::ActualPosition;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyString;
use pyo3::Borrowed;
use serde_json::Value as Json;

use crate::columns::{
    array, assemble, dictionary, offset, offsets, take, Clock, Dictionary, Ifaces, Nullable, Part,
    Skipped, Times, Validity, BATCH_ROWS,
};
use crate::error::Failure;
use crate::ethercat::counts_json;
use crate::source::Source;

/// The `servo=` argument: the slaves read as servos, as the program's
/// `--servo` names them (the library's [`ServoItem`]): `"auto"`, a station
/// address as an int, `"STATION[:MODE]"`, comma-separated items in one
/// string, or a list of these; None for none.
pub struct Servos(pub ServoSlaves);

impl Servos {
    /// `servo="auto"`: every slave of 10 output and 40 input bytes.
    pub fn auto() -> Self {
        Servos([ServoItem::Auto].into_iter().collect())
    }

    /// `servo=None`: no slave is read as a servo.
    pub fn none() -> Self {
        Servos(ServoSlaves::default())
    }

    /// Add one item: an int station address, or a string of items.
    fn add(slaves: &mut ServoSlaves, item: &Bound<'_, PyAny>) -> PyResult<()> {
        let invalid = |e: ServoItemError| PyValueError::new_err(e.to_string());
        if let Ok(text) = item.cast::<PyString>() {
            for part in text.to_cow()?.split(',') {
                slaves.add(part.trim().parse().map_err(invalid)?);
            }
            return Ok(());
        }
        if item.is_instance_of::<pyo3::types::PyInt>()
            && !item.is_instance_of::<pyo3::types::PyBool>()
        {
            let raw: i128 = item.extract()?;
            let station = u16::try_from(raw)
                .map_err(|_| invalid(ServoItemError::Station(raw.to_string())))?;
            slaves.add(ServoItem::Station(station, None));
            return Ok(());
        }
        Err(PyTypeError::new_err(format!(
            "servo must be \"auto\", a station address (int), \"STATION:MODE\", or a list of \
             them; not {}",
            item.get_type().name()?
        )))
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Servos {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let mut slaves = ServoSlaves::default();
        if obj.is_none() {
            return Ok(Servos(slaves));
        }
        if obj.is_instance_of::<pyo3::types::PyList>()
            || obj.is_instance_of::<pyo3::types::PyTuple>()
        {
            for item in obj.try_iter()? {
                Servos::add(&mut slaves, &item?)?;
            }
        } else {
            Servos::add(&mut slaves, &obj)?;
        }
        Ok(Servos(slaves))
    }
}

/// What the rows of every cyclic datagram share: the packet, the
/// datagram, the time, the interface and the slave.
struct Common {
    packet: u64,
    datagram: u16,
    ts: Option<f64>,
    /// `time`'s nanoseconds.
    nanos: Option<i64>,
    iface: Option<i32>,
    slave: Option<u16>,
    position: Option<u16>,
}

/// Rows made of a capture's datagrams, in the order `decode --json` writes
/// its records: each slave's process data ([`SignalColumns`],
/// [`ServoColumns`]), or the records themselves
/// ([`RecordColumns`](crate::records::RecordColumns)).
pub trait Rows {
    /// Add the rows of the `number`-th datagram (from 1) of `packet`
    /// itself (none by default).
    fn datagram(&mut self, _packet: &Packet<'_>, _number: usize, _datagram: Datagram<'_>) {}

    /// Add the rows of what that datagram told of a slave, after the
    /// datagram's (none by default).
    fn meaning<'a>(&mut self, _packet: &Packet<'a>, _number: usize, _meaning: Meaning<'a>) {}

    /// Add the rows of one slave's process data in the `number`-th
    /// datagram (from 1) of `packet`, after what it told.
    fn push(&mut self, packet: &Packet<'_>, number: usize, data: &ProcessData<'_>);

    /// The clock of `time`, told of every packet (a table without rows
    /// still has the capture's type of time).
    fn clock(&mut self) -> &mut Clock;

    /// The table's fields, its batches' columns, and its dictionaries.
    fn finish(self) -> (Vec<Field>, Vec<Vec<Part>>, Vec<Dictionary>);
}

/// The dictionary numbers of the signals' table.
const IFACE: usize = 0;
const NAME: usize = 1;
const DIRECTION: usize = 2;

/// The long table of `process_data` (docs/python.md#process-data).
#[derive(Default)]
pub struct SignalColumns {
    packet: Vec<u64>,
    datagram: Vec<u16>,
    times: Times,
    clock: Clock,
    iface: Nullable<i32>,
    slave: Nullable<u16>,
    position: Nullable<u16>,
    direction: Vec<i8>,
    name: Vec<i32>,
    value: Nullable<f64>,
    raw: Nullable<i64>,
    confirmed: Vec<bool>,
    ifaces: Ifaces,
    names: Dictionary,
    batches: Vec<Vec<Part>>,
}

/// A signal's value as `value` (a float) and `raw` (where it is an
/// integer that an int64 holds): a boolean is 0 or 1, bytes are neither.
pub(crate) fn number(value: &Value) -> (Option<f64>, Option<i64>) {
    match *value {
        Value::Bool(b) => (Some(f64::from(u8::from(b))), Some(i64::from(b))),
        Value::Signed(v) => (Some(v as f64), Some(v)),
        Value::Unsigned(v) => (Some(v as f64), i64::try_from(v).ok()),
        Value::Real32(v) => (Some(f64::from(v)), None),
        Value::Real64(v) => (Some(v), None),
        Value::Octets(_) => (None, None),
    }
}

impl SignalColumns {
    fn row(&mut self, common: &Common, output: bool, name: &str, value: &Value, confirmed: bool) {
        let (value, raw) = number(value);
        self.packet.push(common.packet);
        self.datagram.push(common.datagram);
        self.times.push(common.ts, common.nanos);
        self.iface.push(common.iface);
        self.slave.push(common.slave);
        self.position.push(common.position);
        // The direction dictionary: 0 `output`, 1 `input`.
        self.direction.push(i8::from(!output));
        let key = self.names.key(name);
        self.name.push(key);
        self.value.push(value);
        self.raw.push(raw);
        self.confirmed.push(confirmed);
    }

    /// The rows of a servo's values (docs/python.md#process-data): the
    /// command's, then the feedback's where it is known.
    fn servo_rows(&mut self, common: &Common, servo: &ServoReading, confirmed: bool) {
        let command = &servo.command;
        let outputs = [
            (
                "speed_setpoint",
                Value::Signed(i64::from(command.speed_setpoint)),
            ),
            (
                "control",
                Value::Unsigned(u64::from(command.control.bits())),
            ),
            (
                "servo_enable",
                Value::Unsigned(u64::from(command.control.servo_enable().get())),
            ),
        ];
        for (name, value) in &outputs {
            self.row(common, true, name, value, true);
        }
        let Some(feedback) = &servo.feedback else {
            return;
        };
        match feedback.actual_position() {
            ActualPosition::Absolute(position) => {
                self.row(
                    common,
                    false,
                    "position",
                    &Value::Signed(position),
                    confirmed,
                );
            }
            ActualPosition::Incremental {
                position,
                zero_pulse_position,
            } => {
                self.row(
                    common,
                    false,
                    "position",
                    &Value::Signed(i64::from(position)),
                    confirmed,
                );
                self.row(
                    common,
                    false,
                    "zero_pulse_position",
                    &Value::Signed(i64::from(zero_pulse_position)),
                    confirmed,
                );
            }
        }
        let inputs = [
            ("status", Value::Unsigned(u64::from(feedback.status.bits()))),
            ("errors", Value::Unsigned(u64::from(feedback.errors.bits()))),
            (
                "message_code",
                Value::Signed(i64::from(feedback.message.code)),
            ),
            ("message_value", Value::Real32(feedback.message.data)),
        ];
        for (name, value) in &inputs {
            self.row(common, false, name, value, confirmed);
        }
    }

    fn flush(&mut self) {
        if self.packet.is_empty() {
            return;
        }
        let [ts, time] = self.times.arrays();
        let parts = vec![
            Part::Array(array::<UInt64Type>(&mut self.packet)),
            Part::Array(array::<UInt16Type>(&mut self.datagram)),
            Part::Array(ts),
            Part::Array(time),
            Part::keys32(&mut self.iface, IFACE),
            Part::Array(self.slave.array::<UInt16Type>()),
            Part::Array(self.position.array::<UInt16Type>()),
            Part::Keys8(take::<Int8Type>(&mut self.direction), DIRECTION),
            Part::Keys32(take::<Int32Type>(&mut self.name), NAME),
            Part::Array(self.value.array::<Float64Type>()),
            Part::Array(self.raw.array::<Int64Type>()),
            Part::Array(Arc::new(BooleanArray::from(std::mem::take(
                &mut self.confirmed,
            )))),
        ];
        self.batches.push(parts);
    }
}

/// The fields every table of process data starts with.
fn common_fields(datagram: bool, clock: Clock) -> Vec<Field> {
    let mut fields = vec![Field::new("packet", DataType::UInt64, false)];
    if datagram {
        fields.push(Field::new("datagram", DataType::UInt16, false));
    }
    fields.extend([
        Field::new("ts", DataType::Float64, true),
        clock.field(),
        Field::new("iface", dictionary(DataType::Int32), true),
        Field::new("slave", DataType::UInt16, true),
    ]);
    fields
}

/// The rows' [`Common`] part.
fn common(
    packet: &Packet<'_>,
    number: usize,
    data: &ProcessData<'_>,
    ifaces: &mut Ifaces,
    clock: &mut Clock,
) -> Common {
    Common {
        packet: packet.position.number(),
        // A frame's 11-bit length holds at most 170 datagrams.
        datagram: u16::try_from(number).unwrap_or(u16::MAX),
        ts: packet.timestamp.map(|ts| ts.as_secs_f64()),
        nanos: clock.nanos(packet.timestamp),
        iface: packet.iface.map(|iface| ifaces.key(iface)),
        slave: data.slave.and_then(|s| s.station),
        position: data.slave.and_then(|s| s.position),
    }
}

impl Rows for SignalColumns {
    fn clock(&mut self) -> &mut Clock {
        &mut self.clock
    }

    fn push(&mut self, packet: &Packet<'_>, number: usize, data: &ProcessData<'_>) {
        let common = common(packet, number, data, &mut self.ifaces, &mut self.clock);
        // The outputs are what the master wrote: nothing to confirm.
        data.for_each_signal(|output, name, signal| {
            if let Ok(signal) = signal {
                self.row(
                    &common,
                    output,
                    name,
                    &signal.value,
                    output || data.confirmed,
                );
            }
        });
        if let Some(servo) = &data.servo {
            self.servo_rows(&common, servo, data.confirmed);
        }
        if self.packet.len() >= BATCH_ROWS {
            self.flush();
        }
    }

    fn finish(mut self) -> (Vec<Field>, Vec<Vec<Part>>, Vec<Dictionary>) {
        self.flush();
        let mut fields = common_fields(true, self.clock);
        fields.extend([
            Field::new("position", DataType::UInt16, true),
            Field::new("direction", dictionary(DataType::Int8), false),
            Field::new("name", dictionary(DataType::Int32), false),
            Field::new("value", DataType::Float64, true),
            Field::new("raw", DataType::Int64, true),
            Field::new("confirmed", DataType::Boolean, false),
        ]);
        let ifaces = Dictionary::of(self.ifaces.values);
        let dictionaries = vec![ifaces, self.names, Dictionary::with(&["output", "input"])];
        (fields, self.batches, dictionaries)
    }
}

/// The dictionary numbers of the servo table.
const ENCODER: usize = 1;
const ENABLE: usize = 2;
const ERROR_CLEAR: usize = 3;
const ZERO_PULSE: usize = 4;

/// The table of `servo` (docs/python.md#servo): one row per servo per
/// cycle.
#[derive(Default)]
pub struct ServoColumns {
    packet: Vec<u64>,
    datagram: Vec<u16>,
    times: Times,
    clock: Clock,
    iface: Nullable<i32>,
    slave: Nullable<u16>,
    speed_setpoint: Vec<i32>,
    control: Vec<u32>,
    servo_enable: Vec<u8>,
    position: Nullable<i64>,
    encoder: Nullable<i8>,
    status: Nullable<u32>,
    errors: Nullable<u32>,
    /// `faults` and `e_codes`: one offset list, the lists null together.
    fault_offsets: Vec<i32>,
    faults_valid: Validity,
    fault_names: Vec<String>,
    e_codes: Vec<Option<String>>,
    enable: Vec<i8>,
    enable_cycles: Vec<u32>,
    error_clear: Vec<i8>,
    zero_pulse: Vec<i8>,
    ready: Vec<Option<bool>>,
    confirmed: Vec<bool>,
    ifaces: Ifaces,
    /// The library's names of the encoders and the phases (dictionaries
    /// ENCODER…ZERO_PULSE; 0 is the interface's).
    names: [Dictionary; 4],
    batches: Vec<Vec<Part>>,
}

impl ServoColumns {
    pub fn new() -> Self {
        ServoColumns {
            fault_offsets: vec![0],
            ..ServoColumns::default()
        }
    }

    fn key8(&mut self, dictionary: usize, name: &str) -> i8 {
        // Six names at most: the phases of a handshake.
        self.names[dictionary - ENCODER].key8(name)
    }

    fn flush(&mut self) {
        if self.packet.is_empty() {
            return;
        }
        let faults_valid = self.faults_valid.0.finish();
        let fault_offsets: OffsetBuffer<i32> = offsets(&mut self.fault_offsets);
        let item = Arc::new(Field::new_list_field(DataType::Utf8, true));
        let faults = ListArray::new(
            item.clone(),
            fault_offsets.clone(),
            Arc::new(StringArray::from_iter_values(std::mem::take(
                &mut self.fault_names,
            ))),
            faults_valid.clone(),
        );
        let e_codes = ListArray::new(
            item,
            fault_offsets,
            Arc::new(StringArray::from(std::mem::take(&mut self.e_codes))),
            faults_valid,
        );
        let [ts, time] = self.times.arrays();
        let parts = vec![
            Part::Array(array::<UInt64Type>(&mut self.packet)),
            Part::Array(array::<UInt16Type>(&mut self.datagram)),
            Part::Array(ts),
            Part::Array(time),
            Part::keys32(&mut self.iface, 0),
            Part::Array(self.slave.array::<UInt16Type>()),
            Part::Array(array::<Int32Type>(&mut self.speed_setpoint)),
            Part::Array(array::<UInt32Type>(&mut self.control)),
            Part::Array(array::<UInt8Type>(&mut self.servo_enable)),
            Part::Array(self.position.array::<Int64Type>()),
            Part::keys8(&mut self.encoder, ENCODER),
            Part::Array(self.status.array::<UInt32Type>()),
            Part::Array(self.errors.array::<UInt32Type>()),
            Part::Array(Arc::new(faults)),
            Part::Array(Arc::new(e_codes)),
            Part::Keys8(take::<Int8Type>(&mut self.enable), ENABLE),
            Part::Array(array::<UInt32Type>(&mut self.enable_cycles)),
            Part::Keys8(take::<Int8Type>(&mut self.error_clear), ERROR_CLEAR),
            Part::Keys8(take::<Int8Type>(&mut self.zero_pulse), ZERO_PULSE),
            Part::Array(Arc::new(BooleanArray::from(std::mem::take(
                &mut self.ready,
            )))),
            Part::Array(Arc::new(BooleanArray::from(std::mem::take(
                &mut self.confirmed,
            )))),
        ];
        self.batches.push(parts);
    }
}

impl Rows for ServoColumns {
    fn clock(&mut self) -> &mut Clock {
        &mut self.clock
    }

    fn push(&mut self, packet: &Packet<'_>, number: usize, data: &ProcessData<'_>) {
        let Some(servo) = &data.servo else { return };
        let common = common(packet, number, data, &mut self.ifaces, &mut self.clock);
        self.packet.push(common.packet);
        self.datagram.push(common.datagram);
        self.times.push(common.ts, common.nanos);
        self.iface.push(common.iface);
        self.slave.push(common.slave);
        let command = &servo.command;
        self.speed_setpoint.push(command.speed_setpoint);
        self.control.push(command.control.bits());
        self.servo_enable.push(command.control.servo_enable().get());
        let feedback = servo.feedback.as_ref();
        self.position.push(feedback.map(|f| f.position));
        let encoder = feedback.map(|f| self.key8(ENCODER, f.status.encoder().name()));
        self.encoder.push(encoder);
        self.status.push(feedback.map(|f| f.status.bits()));
        self.errors.push(feedback.map(|f| f.errors.bits()));
        let nulls = &mut self.faults_valid.0;
        match feedback {
            Some(feedback) => {
                for fault in feedback.errors.faults() {
                    self.fault_names.push(fault.name().to_owned());
                    self.e_codes
                        .push(fault.e_code().map(|code| code.to_string()));
                }
                nulls.append_non_null();
            }
            None => nulls.append_null(),
        }
        self.fault_offsets.push(offset(self.fault_names.len()));
        let enable = self.key8(ENABLE, servo.enable.name());
        self.enable.push(enable);
        self.enable_cycles.push(servo.enable_cycles);
        let error_clear = self.key8(ERROR_CLEAR, servo.error_clear.name());
        self.error_clear.push(error_clear);
        let zero_pulse = self.key8(ZERO_PULSE, servo.zero_pulse.name());
        self.zero_pulse.push(zero_pulse);
        self.ready.push(servo.ready);
        self.confirmed.push(data.confirmed);
        if self.packet.len() >= BATCH_ROWS {
            self.flush();
        }
    }

    fn finish(mut self) -> (Vec<Field>, Vec<Vec<Part>>, Vec<Dictionary>) {
        self.flush();
        let list = DataType::List(Arc::new(Field::new_list_field(DataType::Utf8, true)));
        let mut fields = common_fields(true, self.clock);
        fields.extend([
            Field::new("speed_setpoint", DataType::Int32, false),
            Field::new("control", DataType::UInt32, false),
            Field::new("servo_enable", DataType::UInt8, false),
            Field::new("position", DataType::Int64, true),
            Field::new("encoder", dictionary(DataType::Int8), true),
            Field::new("status", DataType::UInt32, true),
            Field::new("errors", DataType::UInt32, true),
            Field::new("faults", list.clone(), true),
            Field::new("e_codes", list, true),
            Field::new("enable", dictionary(DataType::Int8), false),
            Field::new("enable_cycles", DataType::UInt32, false),
            Field::new("error_clear", dictionary(DataType::Int8), false),
            Field::new("zero_pulse", dictionary(DataType::Int8), false),
            Field::new("ready", DataType::Boolean, true),
            Field::new("confirmed", DataType::Boolean, false),
        ]);
        let ifaces = Dictionary::of(self.ifaces.values);
        let [encoder, enable, error_clear, zero_pulse] = self.names;
        let dictionaries = vec![ifaces, encoder, enable, error_clear, zero_pulse];
        (fields, self.batches, dictionaries)
    }
}

/// What reading a capture gave besides the rows.
pub struct Read {
    pub schema: SchemaRef,
    pub batches: Vec<RecordBatch>,
    /// CAN frames read: the tables hold none of them.
    pub frames: u64,
}

/// Read the capture `source` through a session configured with `servos`
/// and make the table of `rows` (no GIL).
pub fn read<R: Rows>(
    source: &Source,
    options: motionwire::logs::ReadOptions,
    servos: ServoSlaves,
    rows: R,
) -> Result<Read, Failure> {
    let name = source.name();
    let mut log = source.open(options, &name)?;
    let session = Session::with_config(&DecoderConfig::new().servos(servos));
    let mut capture = Capture {
        session,
        rows,
        skipped: Skipped::default(),
        frames: 0,
        format: None,
        name: &name,
    };
    capture = log.visit(Visit(capture))?;
    let counts = capture.session.finish();
    let mut metadata = capture.skipped.metadata();
    if let Some(format) = capture.format {
        metadata.insert("motionwire.format".to_owned(), format.name().to_owned());
    }
    if counts.packets > 0 {
        metadata.insert("motionwire.ethercat".to_owned(), counts_json(&counts));
    }
    let frames = capture.frames;
    let (fields, parts, dictionaries) = capture.rows.finish();
    let schema = Arc::new(Schema::new(fields).with_metadata(metadata));
    let batches =
        assemble(&schema, parts, &dictionaries).map_err(|e| Failure::Value(e.to_string()))?;
    Ok(Read {
        schema,
        batches,
        frames,
    })
}

/// A capture being read: the session, the rows, what was skipped.
struct Capture<'a, R> {
    session: Session,
    rows: R,
    skipped: Skipped,
    frames: u64,
    format: Option<LogFormat>,
    name: &'a str,
}

/// The loop over a capture's packets, compiled for its format's reader:
/// each packet read by the session, and for each datagram, in the order
/// of `decode --json`'s records, the datagram, what it tells (the session
/// learns the slaves and their process images from it) and each slave's
/// process data of a returned cyclic datagram handed to the rows. A
/// damaged packet or datagram is skipped as `read_log` skips it.
struct Visit<'a, R>(Capture<'a, R>);

impl<'a, R: Rows> LogVisitor for Visit<'a, R> {
    type Output = Result<Capture<'a, R>, Failure>;

    fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> Self::Output {
        let Visit(mut c) = self;
        c.format = Some(log.format());
        while let Some(next) = log.next_event() {
            let record = match next {
                Ok(record) => record,
                Err(error) => {
                    if matches!(error.kind(), LogErrorKind::Io(_)) {
                        return Err(Failure::log(c.name, error));
                    }
                    let line = error.position().map(|p| p.number());
                    c.skipped.add(None, line, error.kind().to_string());
                    continue;
                }
            };
            let packet = match &record.event {
                LogEvent::Ethercat(packet) => packet,
                LogEvent::Frame(_) => {
                    c.frames += 1;
                    continue;
                }
                LogEvent::Status(_) => continue,
            };
            c.rows.clock().nanos(packet.timestamp);
            let number = record.position.number();
            let packet = match c.session.read(record.position, packet) {
                Ok(packet) => packet,
                Err(damaged) => {
                    c.skipped.add(None, Some(number), damaged.error.to_string());
                    continue;
                }
            };
            for (at, datagram) in packet.datagrams().enumerate() {
                let datagram = match datagram {
                    Ok(datagram) => datagram,
                    Err(error) => {
                        c.session.count_damaged();
                        c.skipped
                            .add(None, Some(number), format!("datagram {}: {error}", at + 1));
                        break;
                    }
                };
                let rows = &mut c.rows;
                rows.datagram(&packet, at + 1, datagram);
                c.session.meanings(&packet, at, &datagram, |meaning| {
                    rows.meaning(&packet, at + 1, meaning);
                });
                c.session.process_data(&packet, at, &datagram, |data| {
                    rows.push(&packet, at + 1, data);
                });
            }
        }
        for kind in log.other_kinds() {
            c.skipped.other.push(Json::from(kind.to_string()));
        }
        Ok(c)
    }
}
