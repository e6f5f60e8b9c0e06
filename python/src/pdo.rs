//! The PDO signals of a CAN log as a long table (docs/python.md#signals):
//! one row per signal value, the signals the library's decoder reads in
//! each PDO with the mapping in force (`Decoded::pdo`,
//! `PdoReading::named`): `process_data`'s long table for CAN, its values
//! made numbers the same way.

use std::sync::Arc;

use arrow_array::types::{Float64Type, Int32Type, Int64Type, UInt32Type, UInt64Type, UInt8Type};
use arrow_array::RecordBatch;
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use motionwire::can::LogEvent;
use motionwire::decoder::Decoder;
use motionwire::logs::{LogErrorKind, LogFormat, LogVisitor, ReadLog};
use serde_json::Value as Json;

use crate::columns::{
    array, assemble, dictionary, take, Clock, Dictionary, Ifaces, Nullable, Part, Skipped, Times,
    BATCH_ROWS,
};
use crate::error::Failure;
use crate::process::number;
use crate::source::Source;

/// The dictionary numbers of the table.
const IFACE: usize = 0;
const NAME: usize = 1;

/// The rows, column by column.
#[derive(Default)]
struct SignalRows {
    line: Vec<u64>,
    times: Times,
    clock: Clock,
    iface: Nullable<i32>,
    node: Vec<u8>,
    cob_id: Vec<u32>,
    name: Vec<i32>,
    value: Nullable<f64>,
    raw: Nullable<i64>,
    ifaces: Ifaces,
    names: Dictionary,
    batches: Vec<Vec<Part>>,
}

impl SignalRows {
    fn flush(&mut self) {
        if self.line.is_empty() {
            return;
        }
        let [ts, time] = self.times.arrays();
        let parts = vec![
            Part::Array(array::<UInt64Type>(&mut self.line)),
            Part::Array(ts),
            Part::Array(time),
            Part::keys32(&mut self.iface, IFACE),
            Part::Array(array::<UInt8Type>(&mut self.node)),
            Part::Array(array::<UInt32Type>(&mut self.cob_id)),
            Part::Keys32(take::<Int32Type>(&mut self.name), NAME),
            Part::Array(self.value.array::<Float64Type>()),
            Part::Array(self.raw.array::<Int64Type>()),
        ];
        self.batches.push(parts);
    }

    fn fields(&self) -> Vec<Field> {
        vec![
            Field::new("line", DataType::UInt64, false),
            Field::new("ts", DataType::Float64, true),
            self.clock.field(),
            Field::new("iface", dictionary(DataType::Int32), true),
            Field::new("node", DataType::UInt8, false),
            Field::new("cob_id", DataType::UInt32, false),
            Field::new("name", dictionary(DataType::Int32), false),
            Field::new("value", DataType::Float64, true),
            Field::new("raw", DataType::Int64, true),
        ]
    }
}

/// What reading a log gave besides the rows.
pub struct Read {
    pub schema: SchemaRef,
    pub batches: Vec<RecordBatch>,
    /// EtherCAT packets read: their signals are `process_data`'s.
    pub packets: u64,
}

/// Read `source`, decoding each frame with `decoder`, and make the table
/// of its PDO signals (no GIL).
pub fn read(
    source: &Source,
    options: motionwire::logs::ReadOptions,
    decoder: Decoder,
) -> Result<Read, Failure> {
    let name = source.name();
    let mut log = source.open(options, &name)?;
    let visit = Visit {
        decoder,
        rows: SignalRows::default(),
        skipped: Skipped::default(),
        packets: 0,
        format: None,
        name: &name,
    };
    let mut visit = log.visit(visit)?;
    visit.rows.flush();
    let mut metadata = visit.skipped.metadata();
    if let Some(format) = visit.format {
        metadata.insert("motionwire.format".to_owned(), format.name().to_owned());
    }
    let schema = Arc::new(Schema::new(visit.rows.fields()).with_metadata(metadata));
    let dictionaries = [
        Dictionary::of(std::mem::take(&mut visit.rows.ifaces.values)),
        std::mem::take(&mut visit.rows.names),
    ];
    let batches = assemble(&schema, visit.rows.batches, &dictionaries)
        .map_err(|e| Failure::Value(e.to_string()))?;
    Ok(Read {
        schema,
        batches,
        packets: visit.packets,
    })
}

/// The loop over a log's frames, compiled for its format's reader.
struct Visit<'a> {
    decoder: Decoder,
    rows: SignalRows,
    skipped: Skipped,
    packets: u64,
    format: Option<LogFormat>,
    name: &'a str,
}

impl<'a> LogVisitor for Visit<'a> {
    type Output = Result<Visit<'a>, Failure>;

    fn visit<L: ReadLog + ?Sized>(mut self, log: &mut L) -> Self::Output {
        self.format = Some(log.format());
        while let Some(next) = log.next_event() {
            let record = match next {
                Ok(record) => record,
                Err(error) => {
                    if matches!(error.kind(), LogErrorKind::Io(_)) {
                        return Err(Failure::log(self.name, error));
                    }
                    let line = error.position().map(|p| p.number());
                    self.skipped.add(None, line, error.kind().to_string());
                    continue;
                }
            };
            let frame = match &record.event {
                LogEvent::Frame(frame) => frame,
                LogEvent::Ethercat(_) => {
                    self.packets += 1;
                    continue;
                }
                LogEvent::Status(_) => continue,
            };
            let decoded = self.decoder.decode(record.position, frame);
            let Some(pdo) = decoded.pdo else { continue };
            let rows = &mut self.rows;
            let nanos = rows.clock.nanos(frame.timestamp);
            let ts = frame.timestamp.map(|ts| ts.as_secs_f64());
            let iface = frame.iface.map(|iface| rows.ifaces.key(iface));
            let node = pdo.map.node().get();
            let cob_id = frame.frame.id().raw();
            for (name, signal) in pdo.named() {
                let (value, raw) = number(&signal.value);
                rows.line.push(record.position.number());
                rows.times.push(ts, nanos);
                rows.iface.push(iface);
                rows.node.push(node);
                rows.cob_id.push(cob_id);
                let key = rows.names.key(name);
                rows.name.push(key);
                rows.value.push(value);
                rows.raw.push(raw);
            }
            if rows.line.len() >= BATCH_ROWS {
                rows.flush();
            }
        }
        for kind in log.other_kinds() {
            self.skipped.other.push(Json::from(kind.to_string()));
        }
        Ok(self)
    }
}
