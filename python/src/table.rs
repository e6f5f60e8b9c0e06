//! Arrow columns built frame by frame in Rust (docs/python.md#columns): no
//! Python object per frame. A log's frames go into plain vectors and bit
//! buffers that become Arrow arrays without a copy; strings that repeat (the
//! interface, the kind, an EMCY's description, a heartbeat's state) are
//! dictionary-encoded. An EtherCAT capture's datagrams are built beside
//! them (`ethercat`); the table holds one or the other (`batches`).

use std::collections::HashMap;
use std::sync::Arc;

use arrow_array::types::{Int32Type, Int8Type, UInt16Type, UInt32Type, UInt64Type, UInt8Type};
use arrow_array::{
    ArrayRef, BooleanArray, DictionaryArray, Float64Array, Int32Array, RecordBatch, StringArray,
    UInt16Array, UInt64Array, UInt8Array,
};
use arrow_buffer::BooleanBufferBuilder;
use arrow_schema::{ArrowError, DataType, Field, Schema, SchemaRef};
use motionwire::can::{FdFlags, LogEvent, LogFrame};
use motionwire::canopen::MessageKind;
use motionwire::decoder::ethercat::Counts;
use motionwire::decoder::Decoder;
use motionwire::logs::{LogError, LogErrorKind, LogFormat, LogVisitor, Position, ReadLog};
use serde_json::Value;

use crate::columns::{
    array, dictionary, take, Bytes, Chunk, Clock, Dictionary, Ifaces, Nullable, Skipped, Times,
    BATCH_BYTES, BATCH_ROWS,
};
use crate::error::Failure;
use crate::ethercat::{self, EthercatColumns, EthercatFinished};

/// The columns `decode` adds (docs/python.md#decode).
#[derive(Default)]
struct DecodedColumns {
    kind: Vec<i8>,
    node: Nullable<u8>,
    code: Nullable<u16>,
    register: Nullable<u8>,
    description: Nullable<i32>,
    state: Nullable<i32>,
    /// The drive's CiA 402 state the frame tells (`cia402.state`).
    cia402_state: Nullable<i32>,
    record: Bytes,
    /// The library's names: an EMCY code's description, a heartbeat's
    /// state, a CiA 402 state.
    descriptions: Dictionary,
    states: Dictionary,
    cia402_states: Dictionary,
}

/// The frames of one log, column by column.
pub struct Columns {
    line: Vec<u64>,
    times: Times,
    clock: Clock,
    iface: Nullable<i32>,
    id: Vec<u32>,
    /// extended, rtr, fd, brs, esi, error.
    flags: [BooleanBufferBuilder; 6],
    dlc: Vec<u8>,
    data: Bytes,
    decoded: Option<Box<DecodedColumns>>,
    chunks: Vec<Chunk>,
    ifaces: Ifaces,
    /// CAN frames added.
    frames: u64,
    /// The datagrams of the log's EtherCAT packets.
    ethercat: EthercatColumns,
    pub skipped: Skipped,
    pub format: Option<LogFormat>,
}

impl Columns {
    /// Columns for `read_log`, or for `decode` (with `decoded`).
    pub fn new(decoded: bool) -> Self {
        Columns {
            line: Vec::new(),
            times: Times::default(),
            clock: Clock::default(),
            iface: Nullable::default(),
            id: Vec::new(),
            flags: std::array::from_fn(|_| BooleanBufferBuilder::new(0)),
            dlc: Vec::new(),
            data: Bytes::default(),
            decoded: decoded.then(Box::default),
            chunks: Vec::new(),
            ifaces: Ifaces::default(),
            frames: 0,
            ethercat: EthercatColumns::new(decoded),
            skipped: Skipped::default(),
            format: None,
        }
    }

    /// Add a frame, decoded by `decoder` for `decode`'s columns.
    #[inline]
    fn push(&mut self, position: Position, frame: &LogFrame<'_>, decoder: Option<&mut Decoder>) {
        let can = &frame.frame;
        self.frames += 1;
        self.line.push(position.number());
        let nanos = self.clock.nanos(frame.timestamp);
        self.times
            .push(frame.timestamp.map(|ts| ts.as_secs_f64()), nanos);
        let iface = frame.iface.map(|iface| self.ifaces.key(iface));
        self.iface.push(iface);
        self.id.push(can.id().raw());
        let fd = can.fd_flags();
        for (builder, flag) in self.flags.iter_mut().zip([
            can.is_extended(),
            can.is_rtr(),
            can.is_fd(),
            fd.contains(FdFlags::BRS),
            fd.contains(FdFlags::ESI),
            can.is_error(),
        ]) {
            builder.append(flag);
        }
        self.dlc.push(can.dlc());
        self.data.push(can.data());
        if let (Some(d), Some(decoder)) = (self.decoded.as_deref_mut(), decoder) {
            let decoded = decoder.decode(position, frame);
            d.kind.push(decoded.kind.index() as i8);
            d.node.push(decoded.node.map(|node| node.get()));
            let columns = decoded.columns();
            d.code.push(columns.code.map(|code| code.get()));
            d.register.push(columns.register.map(|r| r.bits()));
            let description = columns.description.map(|text| d.descriptions.key(text));
            d.description.push(description);
            let state = columns.state.map(|state| d.states.key(state));
            d.state.push(state);
            let cia402 = decoded.cia402.and_then(|reading| reading.state);
            let cia402 = cia402.map(|state| d.cia402_states.key(state.name()));
            d.cia402_state.push(cia402);
            let out = d.record.buffer();
            decoded.write_json(&mut *out).expect("writing to a Vec");
            // The record without its newline.
            out.pop();
            d.record.end_row();
        }
        if self.line.len() >= BATCH_ROWS
            || self.data.len() >= BATCH_BYTES
            || self
                .decoded
                .as_ref()
                .is_some_and(|d| d.record.len() >= BATCH_BYTES)
        {
            self.flush();
        }
    }

    /// A line or record the reader could not read: listed; an input that
    /// fails while it is read ends the call with a [`LogError`].
    fn skip(&mut self, error: LogError, name: &str, file: Option<&str>) -> Result<(), Failure> {
        if matches!(error.kind(), LogErrorKind::Io(_)) {
            return Err(Failure::log(name, error));
        }
        let line = error.position().map(|p| p.number());
        // The reason without the position, which is the `line` key.
        self.skipped.add(file, line, error.kind().to_string());
        Ok(())
    }

    /// Make a record batch of the rows added since the last.
    fn flush(&mut self) {
        if self.line.is_empty() {
            return;
        }
        let [ts, time] = self.times.arrays();
        let mut columns: Vec<ArrayRef> = vec![
            array::<UInt64Type>(&mut self.line),
            ts,
            time,
            array::<UInt32Type>(&mut self.id),
        ];
        for builder in &mut self.flags {
            columns.push(Arc::new(BooleanArray::new(builder.finish(), None)));
        }
        columns.push(array::<UInt8Type>(&mut self.dlc));
        columns.push(self.data.binary());
        if let Some(d) = self.decoded.as_deref_mut() {
            let kinds: ArrayRef = Arc::new(StringArray::from_iter_values(
                MessageKind::ALL.iter().map(|kind| kind.name()),
            ));
            columns.push(Arc::new(DictionaryArray::<Int8Type>::new(
                take::<Int8Type>(&mut d.kind),
                kinds,
            )));
            columns.push(d.node.array::<UInt8Type>());
            columns.push(d.code.array::<UInt16Type>());
            columns.push(d.register.array::<UInt8Type>());
            for (keys, values) in [
                (&mut d.description, &d.descriptions),
                (&mut d.state, &d.states),
                (&mut d.cia402_state, &d.cia402_states),
            ] {
                columns.push(Arc::new(DictionaryArray::<Int32Type>::new(
                    keys.take::<Int32Type>(),
                    values.array(),
                )));
            }
            columns.push(d.record.strings());
        }
        let iface = self.iface.take::<Int32Type>();
        self.chunks.push(Chunk { columns, iface });
    }

    /// The rows read, as record batches; the interface dictionary and the
    /// log's other columns apart.
    pub fn finish(mut self, name: &str) -> Finished {
        self.flush();
        Finished {
            name: name.to_owned(),
            chunks: self.chunks,
            ifaces: self.ifaces.values,
            frames: self.frames,
            clock: self.clock,
            ethercat: self.ethercat.finish(),
            skipped: self.skipped,
            format: self.format,
            decoded: self.decoded.is_some(),
        }
    }
}

/// The columns of a log read in full.
pub struct Finished {
    /// The log's name, as messages give it.
    name: String,
    chunks: Vec<Chunk>,
    ifaces: Vec<String>,
    frames: u64,
    clock: Clock,
    ethercat: EthercatFinished,
    pub skipped: Skipped,
    pub format: Option<LogFormat>,
    decoded: bool,
}

/// Read every event of a log into `columns` (a [`LogVisitor`], so that
/// the loop is compiled for the format's reader), decoding each frame with
/// `decoder` when there is one.
pub struct Fill<'a> {
    pub columns: &'a mut Columns,
    pub decoder: Option<&'a mut Decoder>,
    /// The source's name, for messages.
    pub name: &'a str,
    /// The name the skipped lines give (`read_logs`: each names its file).
    pub file: Option<&'a str>,
}

impl LogVisitor for Fill<'_> {
    type Output = Result<(), Failure>;

    fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> Result<(), Failure> {
        let Fill {
            columns,
            mut decoder,
            name,
            file,
        } = self;
        columns.format = Some(log.format());
        while let Some(next) = log.next_event() {
            match next {
                Ok(record) => match &record.event {
                    LogEvent::Frame(frame) => {
                        columns.push(record.position, frame, decoder.as_deref_mut());
                    }
                    LogEvent::Ethercat(packet) => {
                        columns
                            .ethercat
                            .push(record.position, packet, &mut columns.skipped, file)
                    }
                    LogEvent::Status(_) => {}
                },
                Err(error) => columns.skip(error, name, file)?,
            }
        }
        // Records that hold no frame, said once per kind as the program
        // says them (docs/formats.md#pcap, docs/formats.md#blf,
        // docs/formats.md#mf4).
        for kind in log.other_kinds() {
            columns.skipped.other.push(Value::from(kind.to_string()));
        }
        Ok(())
    }
}

/// What a table's rows are: CAN frames (docs/python.md#columns) or the
/// datagrams of an EtherCAT capture (docs/python.md#ethercat).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rows {
    Can,
    Ethercat,
}

impl Rows {
    /// Where the `iface` column sits among a row's columns (after `file`).
    fn iface_at(self) -> usize {
        match self {
            Rows::Can => 3,
            Rows::Ethercat => ethercat::IFACE_AT,
        }
    }
}

/// The schema of `read_log` (with `file` first for `read_logs`) or of
/// `decode`, for CAN frames or EtherCAT datagrams, `time` typed by the
/// table's `clock`.
pub fn schema(
    rows: Rows,
    decoded: bool,
    file: bool,
    clock: Clock,
    metadata: HashMap<String, String>,
) -> Schema {
    let mut fields = Vec::new();
    if file {
        fields.push(Field::new("file", dictionary(DataType::Int32), false));
    }
    if rows == Rows::Ethercat {
        fields.extend(ethercat::fields(decoded, clock));
        return Schema::new(fields).with_metadata(metadata);
    }
    fields.extend([
        Field::new("line", DataType::UInt64, false),
        Field::new("ts", DataType::Float64, true),
        clock.field(),
        Field::new("iface", dictionary(DataType::Int32), true),
        Field::new("id", DataType::UInt32, false),
        Field::new("extended", DataType::Boolean, false),
        Field::new("rtr", DataType::Boolean, false),
        Field::new("fd", DataType::Boolean, false),
        Field::new("brs", DataType::Boolean, false),
        Field::new("esi", DataType::Boolean, false),
        Field::new("error", DataType::Boolean, false),
        Field::new("dlc", DataType::UInt8, false),
        Field::new("data", DataType::Binary, false),
    ]);
    if decoded {
        fields.extend([
            Field::new("kind", dictionary(DataType::Int8), false),
            Field::new("node", DataType::UInt8, true),
            Field::new("code", DataType::UInt16, true),
            Field::new("register", DataType::UInt8, true),
            Field::new("description", dictionary(DataType::Int32), true),
            Field::new("state", dictionary(DataType::Int32), true),
            Field::new("cia402_state", dictionary(DataType::Int32), true),
            Field::new("record", DataType::Utf8, false),
        ]);
    }
    Schema::new(fields).with_metadata(metadata)
}

/// The record batches of one log (`file` = `None`) or of several, each
/// with its name.
///
/// A table holds one kind of row (docs/ethercat.md#python): CAN frames
/// when any log has one, else the datagrams of the EtherCAT packets when
/// any log has one. The EtherCAT packets of a table of CAN frames are
/// counted in `motionwire.other`, not dropped.
pub fn batches(
    logs: Vec<Finished>,
    files: Option<&[String]>,
) -> Result<(SchemaRef, Vec<RecordBatch>), ArrowError> {
    let decoded = logs.first().is_some_and(|log| log.decoded);
    let any_frames = logs.iter().any(|log| log.frames > 0);
    let any_packets = logs.iter().any(|log| log.ethercat.counts.packets > 0);
    let rows = if !any_frames && any_packets {
        Rows::Ethercat
    } else {
        Rows::Can
    };
    let mut skipped = Skipped::default();
    let mut format = None;
    let mut counts = Counts::default();
    let mut clock = Clock::default();
    let mut empty = Vec::new();
    let mut parts = Vec::with_capacity(logs.len());
    for mut log in logs {
        format = format.or(log.format);
        let packets = log.ethercat.counts.packets;
        ethercat::add_counts(&mut counts, &log.ethercat.counts);
        if rows == Rows::Can && packets > 0 {
            let why = if log.frames > 0 {
                "the capture holds CAN frames too, and a table holds CAN frames or EtherCAT \
                 datagrams, not both"
            } else {
                "other logs of the table hold CAN frames, and a table holds CAN frames or \
                 EtherCAT datagrams, not both"
            };
            log.skipped.other.insert(
                0,
                Value::from(format!(
                    "{packets} EtherCAT packet{} skipped: {why}",
                    if packets == 1 { "" } else { "s" }
                )),
            );
        }
        skipped.extend(log.skipped);
        let rows_of_log = match rows {
            Rows::Can => log.frames,
            Rows::Ethercat => log
                .ethercat
                .chunks
                .iter()
                .map(|c| c.iface.len() as u64)
                .sum(),
        };
        if rows_of_log == 0 {
            // As the program says it on standard error (docs/output.md#stderr).
            let unit = match rows {
                Rows::Can => "frames",
                Rows::Ethercat => "datagrams",
            };
            empty.push(Value::from(format!("{}: 0 {unit}", log.name)));
        }
        parts.push(match rows {
            Rows::Can => {
                clock.merge(log.clock);
                (log.chunks, log.ifaces)
            }
            Rows::Ethercat => {
                clock.merge(log.ethercat.clock);
                (log.ethercat.chunks, log.ethercat.ifaces)
            }
        });
    }
    let mut metadata = skipped.metadata();
    if files.is_none() {
        if let Some(format) = format {
            metadata.insert("motionwire.format".to_owned(), format.name().to_owned());
        }
    }
    if any_packets {
        metadata.insert(
            "motionwire.ethercat".to_owned(),
            ethercat::counts_json(&counts),
        );
    }
    if !empty.is_empty() {
        metadata.insert(
            "motionwire.empty".to_owned(),
            Value::Array(empty).to_string(),
        );
    }
    let schema = Arc::new(schema(rows, decoded, files.is_some(), clock, metadata));
    // One interface dictionary for the whole table: each log's keys mapped
    // onto it.
    let mut ifaces = Ifaces::default();
    let maps: Vec<Vec<i32>> = parts
        .iter()
        .map(|(_, names)| names.iter().map(|name| ifaces.add(name.clone())).collect())
        .collect();
    let iface_values: ArrayRef = Arc::new(StringArray::from_iter_values(ifaces.values.iter()));
    let file_values: Option<ArrayRef> =
        files.map(|files| Arc::new(StringArray::from_iter_values(files.iter())) as ArrayRef);
    let mut batches = Vec::new();
    for (i, (chunks, _)) in parts.into_iter().enumerate() {
        let map = &maps[i];
        for chunk in chunks {
            let rows_in = chunk.iface.len();
            let keys = if map.iter().enumerate().all(|(k, &g)| k as i32 == g) {
                chunk.iface
            } else {
                chunk
                    .iface
                    .unary(|key| map.get(key as usize).copied().unwrap_or(0))
            };
            let mut columns = Vec::with_capacity(chunk.columns.len() + 2);
            if let Some(values) = &file_values {
                let key = i32::try_from(i).unwrap_or(i32::MAX);
                columns.push(Arc::new(DictionaryArray::<Int32Type>::try_new(
                    Int32Array::from(vec![key; rows_in]),
                    values.clone(),
                )?) as ArrayRef);
            }
            let mut own = chunk.columns;
            // `time`, just before `iface`: int64 nanoseconds made the
            // table's type.
            let time = rows.iface_at() - 1;
            own[time] = clock.array(&own[time])?;
            let mut rest = own.into_iter();
            columns.extend(rest.by_ref().take(rows.iface_at()));
            columns.push(Arc::new(DictionaryArray::<Int32Type>::try_new(
                keys,
                iface_values.clone(),
            )?));
            columns.extend(rest);
            batches.push(RecordBatch::try_new(schema.clone(), columns)?);
        }
    }
    Ok((schema, batches))
}

/// The table of `findings` (docs/python.md#findings): one row per finding,
/// in the library's order.
pub fn findings(
    findings: &[motionwire::summary::Finding],
) -> Result<(SchemaRef, Vec<RecordBatch>), ArrowError> {
    let schema = Arc::new(Schema::new(vec![
        Field::new("line", DataType::UInt64, false),
        Field::new("ts", DataType::Float64, true),
        Field::new("iface", dictionary(DataType::Int32), true),
        Field::new("node", DataType::UInt8, true),
        Field::new("slave", DataType::UInt16, true),
        Field::new("kind", dictionary(DataType::Int8), false),
        Field::new("severity", dictionary(DataType::Int8), false),
        Field::new("text", DataType::Utf8, false),
    ]));
    let ifaces: Vec<Option<String>> = findings
        .iter()
        .map(|f| match &f.bus {
            motionwire::can::BusName::Unnamed => None,
            bus => Some(bus.to_string()),
        })
        .collect();
    let columns: Vec<ArrayRef> = vec![
        Arc::new(UInt64Array::from_iter_values(
            findings.iter().map(|f| f.line),
        )),
        Arc::new(Float64Array::from_iter(
            findings
                .iter()
                .map(|f| f.timestamp.map(|ts| ts.as_secs_f64())),
        )),
        Arc::new(DictionaryArray::<Int32Type>::from_iter(
            ifaces.iter().map(Option::as_deref),
        )),
        Arc::new(UInt8Array::from_iter(
            findings.iter().map(|f| f.node.map(|n| n.get())),
        )),
        Arc::new(UInt16Array::from_iter(
            findings.iter().map(|f| f.slave.and_then(|s| s.station)),
        )),
        Arc::new(DictionaryArray::<Int8Type>::from_iter(
            findings.iter().map(|f| f.kind.name()),
        )),
        Arc::new(DictionaryArray::<Int8Type>::from_iter(
            findings.iter().map(|f| f.severity.name()),
        )),
        Arc::new(StringArray::from_iter_values(
            findings.iter().map(|f| f.text()),
        )),
    ];
    let batch = RecordBatch::try_new(schema.clone(), columns)?;
    Ok((schema, vec![batch]))
}
