//! The process data of an EtherCAT capture as tables
//! (docs/python.md#process-data): `process_data`, one row per signal per
//! slave per returned cyclic datagram, and `servo`, one row per servo per
//! cycle. The library's `ethercat::Session` cuts each cyclic datagram per
//! slave (`Session::process_data`), reads the signals
//! (`ProcessData::for_each_signal`) and the servo frames with their
//! handshakes (`ServoReading`); this module only moves the values into
//! Arrow columns, in record batches of at most [`BATCH_ROWS`] rows.

use std::collections::HashMap;
use std::sync::Arc;

use arrow_array::types::{Int32Type, Int8Type};
use arrow_array::{
    ArrayRef, BooleanArray, DictionaryArray, Float64Array, Int32Array, Int64Array, Int8Array,
    ListArray, RecordBatch, StringArray, UInt16Array, UInt32Array, UInt64Array, UInt8Array,
};
use arrow_buffer::{OffsetBuffer, ScalarBuffer};
use arrow_schema::{ArrowError, DataType, Field, Schema, SchemaRef};
use motionwire::can::LogEvent;
use motionwire::canopen::Value;
use motionwire::decoder::ethercat::{
    Packet, ProcessData, ServoItem, ServoItemError, ServoReading, ServoSlaves, Session,
};
use motionwire::decoder::DecoderConfig;
use motionwire::logs::{LogErrorKind, LogFormat, LogVisitor, ReadLog};
use motionwire::servo::ActualPosition;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyString;
use pyo3::Borrowed;
use serde_json::Value as Json;

use crate::columns::{offset, offsets, retype, Clock, Ifaces, Skipped, Validity, BATCH_ROWS};
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

/// A dictionary column's values, each once, and the key of each; keys
/// stay the same as values are added, so that every batch takes the
/// dictionary complete at the end.
#[derive(Default)]
pub struct Dictionary {
    values: Vec<String>,
    keys: HashMap<String, i32>,
}

impl Dictionary {
    fn with(values: &[&str]) -> Self {
        let mut dictionary = Dictionary::default();
        for value in values {
            dictionary.key(value);
        }
        dictionary
    }

    /// The dictionary of `values`, all different (an [`Ifaces`]').
    pub(crate) fn of(values: Vec<String>) -> Self {
        let keys = (0..).zip(&values).map(|(k, v)| (v.clone(), k)).collect();
        Dictionary { values, keys }
    }

    pub(crate) fn key(&mut self, value: &str) -> i32 {
        if let Some(&key) = self.keys.get(value) {
            return key;
        }
        let key = i32::try_from(self.values.len()).unwrap_or(i32::MAX);
        self.keys.insert(value.to_owned(), key);
        self.values.push(value.to_owned());
        key
    }

    fn array(&self) -> ArrayRef {
        Arc::new(StringArray::from_iter_values(self.values.iter()))
    }
}

/// One column of a batch: an array, or the keys of a dictionary column
/// whose values are known at the end (the interface, a signal's name).
pub enum Part {
    Array(ArrayRef),
    /// Keys into the table's dictionary number `.1`, int32.
    Keys32(Int32Array, usize),
    /// Keys into the table's dictionary number `.1`, int8.
    Keys8(Int8Array, usize),
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

/// Rows made of each slave's process data ([`SignalColumns`],
/// [`ServoColumns`]).
pub trait Rows {
    /// Add the rows of one slave's process data in the `number`-th
    /// datagram (from 1) of `packet`.
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
    ts: Vec<f64>,
    ts_valid: Validity,
    time: Vec<i64>,
    clock: Clock,
    iface: Vec<i32>,
    iface_valid: Validity,
    slave: Vec<u16>,
    slave_valid: Validity,
    position: Vec<u16>,
    position_valid: Validity,
    direction: Vec<i8>,
    name: Vec<i32>,
    value: Vec<f64>,
    value_valid: Validity,
    raw: Vec<i64>,
    raw_valid: Validity,
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
        self.ts_valid.push(&mut self.ts, common.ts);
        self.time.push(common.nanos.unwrap_or_default());
        self.iface_valid.push(&mut self.iface, common.iface);
        self.slave_valid.push(&mut self.slave, common.slave);
        self.position_valid
            .push(&mut self.position, common.position);
        // The direction dictionary: 0 `output`, 1 `input`.
        self.direction.push(i8::from(!output));
        let key = self.names.key(name);
        self.name.push(key);
        self.value_valid.push(&mut self.value, value);
        self.raw_valid.push(&mut self.raw, raw);
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
        let ts_nulls = self.ts_valid.0.finish();
        let parts = vec![
            Part::Array(Arc::new(UInt64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.packet)),
                None,
            ))),
            Part::Array(Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.datagram)),
                None,
            ))),
            Part::Array(Arc::new(Float64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.ts)),
                ts_nulls.clone(),
            ))),
            Part::Array(Arc::new(Int64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.time)),
                ts_nulls,
            ))),
            Part::Keys32(
                Int32Array::new(
                    ScalarBuffer::from(std::mem::take(&mut self.iface)),
                    self.iface_valid.0.finish(),
                ),
                IFACE,
            ),
            Part::Array(Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.slave)),
                self.slave_valid.0.finish(),
            ))),
            Part::Array(Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.position)),
                self.position_valid.0.finish(),
            ))),
            Part::Keys8(
                Int8Array::new(
                    ScalarBuffer::from(std::mem::take(&mut self.direction)),
                    None,
                ),
                DIRECTION,
            ),
            Part::Keys32(
                Int32Array::new(ScalarBuffer::from(std::mem::take(&mut self.name)), None),
                NAME,
            ),
            Part::Array(Arc::new(Float64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.value)),
                self.value_valid.0.finish(),
            ))),
            Part::Array(Arc::new(Int64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.raw)),
                self.raw_valid.0.finish(),
            ))),
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

pub(crate) fn dictionary(key: DataType) -> DataType {
    DataType::Dictionary(Box::new(key), Box::new(DataType::Utf8))
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
    ts: Vec<f64>,
    ts_valid: Validity,
    time: Vec<i64>,
    clock: Clock,
    iface: Vec<i32>,
    iface_valid: Validity,
    slave: Vec<u16>,
    slave_valid: Validity,
    speed_setpoint: Vec<i32>,
    control: Vec<u32>,
    servo_enable: Vec<u8>,
    position: Vec<i64>,
    position_valid: Validity,
    encoder: Vec<i8>,
    encoder_valid: Validity,
    status: Vec<u32>,
    status_valid: Validity,
    errors: Vec<u32>,
    errors_valid: Validity,
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
        i8::try_from(self.names[dictionary - ENCODER].key(name)).unwrap_or(i8::MAX)
    }

    fn flush(&mut self) {
        if self.packet.is_empty() {
            return;
        }
        let ts_nulls = self.ts_valid.0.finish();
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
        let key8 = |keys: &mut Vec<i8>, valid: Option<&mut Validity>, at| {
            Part::Keys8(
                Int8Array::new(
                    ScalarBuffer::from(std::mem::take(keys)),
                    valid.and_then(|v| v.0.finish()),
                ),
                at,
            )
        };
        let parts = vec![
            Part::Array(Arc::new(UInt64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.packet)),
                None,
            ))),
            Part::Array(Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.datagram)),
                None,
            ))),
            Part::Array(Arc::new(Float64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.ts)),
                ts_nulls.clone(),
            ))),
            Part::Array(Arc::new(Int64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.time)),
                ts_nulls,
            ))),
            Part::Keys32(
                Int32Array::new(
                    ScalarBuffer::from(std::mem::take(&mut self.iface)),
                    self.iface_valid.0.finish(),
                ),
                0,
            ),
            Part::Array(Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.slave)),
                self.slave_valid.0.finish(),
            ))),
            Part::Array(Arc::new(Int32Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.speed_setpoint)),
                None,
            ))),
            Part::Array(Arc::new(UInt32Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.control)),
                None,
            ))),
            Part::Array(Arc::new(UInt8Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.servo_enable)),
                None,
            ))),
            Part::Array(Arc::new(Int64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.position)),
                self.position_valid.0.finish(),
            ))),
            key8(&mut self.encoder, Some(&mut self.encoder_valid), ENCODER),
            Part::Array(Arc::new(UInt32Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.status)),
                self.status_valid.0.finish(),
            ))),
            Part::Array(Arc::new(UInt32Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.errors)),
                self.errors_valid.0.finish(),
            ))),
            Part::Array(Arc::new(faults)),
            Part::Array(Arc::new(e_codes)),
            key8(&mut self.enable, None, ENABLE),
            Part::Array(Arc::new(UInt32Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.enable_cycles)),
                None,
            ))),
            key8(&mut self.error_clear, None, ERROR_CLEAR),
            key8(&mut self.zero_pulse, None, ZERO_PULSE),
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
        self.ts_valid.push(&mut self.ts, common.ts);
        self.time.push(common.nanos.unwrap_or_default());
        self.iface_valid.push(&mut self.iface, common.iface);
        self.slave_valid.push(&mut self.slave, common.slave);
        let command = &servo.command;
        self.speed_setpoint.push(command.speed_setpoint);
        self.control.push(command.control.bits());
        self.servo_enable.push(command.control.servo_enable().get());
        let feedback = servo.feedback.as_ref();
        self.position_valid
            .push(&mut self.position, feedback.map(|f| f.position));
        let encoder = feedback.map(|f| self.key8(ENCODER, f.status.encoder().name()));
        self.encoder_valid.push(&mut self.encoder, encoder);
        self.status_valid
            .push(&mut self.status, feedback.map(|f| f.status.bits()));
        self.errors_valid
            .push(&mut self.errors, feedback.map(|f| f.errors.bits()));
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

/// The record batches, each dictionary column with its complete values.
pub(crate) fn assemble(
    schema: &SchemaRef,
    parts: Vec<Vec<Part>>,
    dictionaries: &[Dictionary],
) -> Result<Vec<RecordBatch>, ArrowError> {
    let values: Vec<ArrayRef> = dictionaries.iter().map(Dictionary::array).collect();
    parts
        .into_iter()
        .map(|batch| {
            let columns =
                batch
                    .into_iter()
                    .zip(schema.fields())
                    .map(|(part, field)| {
                        Ok(match part {
                            // `time`: int64 nanoseconds made the table's type.
                            Part::Array(array) if field.name() == "time" => {
                                retype(&array, field.data_type())?
                            }
                            Part::Array(array) => array,
                            Part::Keys32(keys, at) => Arc::new(
                                DictionaryArray::<Int32Type>::try_new(keys, values[at].clone())?,
                            ) as ArrayRef,
                            Part::Keys8(keys, at) => Arc::new(
                                DictionaryArray::<Int8Type>::try_new(keys, values[at].clone())?,
                            ),
                        })
                    })
                    .collect::<Result<Vec<_>, ArrowError>>()?;
            RecordBatch::try_new(schema.clone(), columns)
        })
        .collect()
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
/// each packet read by the session, each datagram's meanings followed
/// (the session learns the slaves and their process images from them),
/// each returned cyclic datagram's process data made rows. A damaged
/// packet or datagram is skipped as `read_log` skips it.
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
                c.session.meanings(&packet, at, &datagram, |_| {});
                let rows = &mut c.rows;
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
