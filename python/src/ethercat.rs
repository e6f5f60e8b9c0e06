//! The table of an EtherCAT capture (docs/python.md#ethercat): one row per
//! datagram, the keys of the program's `ecat_datagram` record as columns
//! (docs/ethercat.md#records). The library's `ethercat::Session` tells
//! which copy of its frame each packet is; `DatagramRecord` writes the
//! record `decode` adds.

use std::sync::Arc;

use arrow_array::types::Int8Type;
use arrow_array::{
    ArrayRef, BinaryArray, BooleanArray, DictionaryArray, Float64Array, Int32Array, Int64Array,
    Int8Array, StringArray, UInt16Array, UInt32Array, UInt64Array, UInt8Array,
};
use arrow_buffer::{BooleanBufferBuilder, Buffer, ScalarBuffer};
use arrow_schema::{DataType, Field};
use motionwire::can::EthercatPacket;
use motionwire::decoder::ethercat::{Counts, DatagramRecord, Packet, Session, DATAGRAM_KIND};
use motionwire::ethercat::{Addressing, Command, Datagram};
use motionwire::logs::Position;

use crate::columns::{
    offset, offsets, Chunk, Clock, Ifaces, Skipped, Validity, BATCH_BYTES, BATCH_ROWS,
};

/// The key of the `cmd` dictionary for commands 15–255, all named
/// `reserved` by the library; commands 0–14 are their own keys.
const RESERVED_KEY: u8 = 15;

/// Where the `iface` column sits among the columns of a datagram
/// (`packet`, `datagram`, `ts`, `time`, `iface`, …).
pub const IFACE_AT: usize = 4;

/// The datagrams of one capture, column by column.
pub struct EthercatColumns {
    session: Session,
    packet: Vec<u64>,
    datagram: Vec<u16>,
    ts: Vec<f64>,
    ts_valid: Validity,
    /// `time`'s nanoseconds, null where `ts` is.
    time: Vec<i64>,
    clock: Clock,
    iface: Vec<i32>,
    iface_valid: Validity,
    cmd: Vec<i8>,
    index: Vec<u8>,
    adp: Vec<u16>,
    adp_valid: Validity,
    ado: Vec<u16>,
    ado_valid: Validity,
    logical: Vec<u32>,
    logical_valid: Validity,
    length: Vec<u16>,
    irq: Vec<u16>,
    wkc: Vec<u16>,
    returned: BooleanBufferBuilder,
    data_offsets: Vec<i32>,
    data: Vec<u8>,
    /// `decode`'s `record` column: each datagram's JSON record.
    record: Option<(Vec<i32>, Vec<u8>)>,
    chunks: Vec<Chunk>,
    ifaces: Ifaces,
}

impl EthercatColumns {
    /// Columns for `read_log`, or for `decode` (with `record`).
    pub fn new(record: bool) -> Self {
        EthercatColumns {
            session: Session::new(),
            packet: Vec::new(),
            datagram: Vec::new(),
            ts: Vec::new(),
            ts_valid: Validity::default(),
            time: Vec::new(),
            clock: Clock::default(),
            iface: Vec::new(),
            iface_valid: Validity::default(),
            cmd: Vec::new(),
            index: Vec::new(),
            adp: Vec::new(),
            adp_valid: Validity::default(),
            ado: Vec::new(),
            ado_valid: Validity::default(),
            logical: Vec::new(),
            logical_valid: Validity::default(),
            length: Vec::new(),
            irq: Vec::new(),
            wkc: Vec::new(),
            returned: BooleanBufferBuilder::new(0),
            data_offsets: vec![0],
            data: Vec::new(),
            record: record.then(|| (vec![0], Vec::new())),
            chunks: Vec::new(),
            ifaces: Ifaces::default(),
        }
    }

    /// Read an EtherCAT packet with the session and add a row per
    /// datagram. A damaged header or datagram is skipped as the program
    /// reports it (docs/ethercat.md#damaged-packets): with the packet's
    /// number, the datagrams before it kept.
    pub fn push(
        &mut self,
        position: Position,
        packet: &EthercatPacket<'_>,
        skipped: &mut Skipped,
        file: Option<&str>,
    ) {
        let packet = match self.session.read(position, packet) {
            Ok(packet) => packet,
            Err(damaged) => {
                skipped.add(file, Some(position.number()), damaged.error.to_string());
                return;
            }
        };
        for (at, datagram) in packet.datagrams().enumerate() {
            match datagram {
                Ok(datagram) => self.push_datagram(&packet, at + 1, datagram),
                Err(error) => {
                    self.session.count_damaged();
                    skipped.add(
                        file,
                        Some(position.number()),
                        format!("datagram {}: {error}", at + 1),
                    );
                    break;
                }
            }
        }
    }

    /// Add the row of the `number`-th datagram of `packet`.
    fn push_datagram(&mut self, packet: &Packet<'_>, number: usize, datagram: Datagram<'_>) {
        self.packet.push(packet.position.number());
        // A frame's 11-bit length holds at most 170 datagrams.
        self.datagram
            .push(u16::try_from(number).unwrap_or(u16::MAX));
        self.ts_valid
            .push(&mut self.ts, packet.timestamp.map(|ts| ts.as_secs_f64()));
        let nanos = self.clock.nanos(packet.timestamp);
        self.time.push(nanos.unwrap_or_default());
        let iface = packet.iface.map(|iface| self.ifaces.key(iface));
        self.iface_valid.push(&mut self.iface, iface);
        let command = datagram.command();
        self.cmd.push(command.byte().min(RESERVED_KEY) as i8);
        self.index.push(datagram.index());
        let logical = command.addressing() == Addressing::Logical;
        self.adp_valid
            .push(&mut self.adp, (!logical).then(|| datagram.adp()));
        self.ado_valid
            .push(&mut self.ado, (!logical).then(|| datagram.ado()));
        self.logical_valid
            .push(&mut self.logical, logical.then(|| datagram.address()));
        self.length.push(datagram.length());
        self.irq.push(datagram.irq());
        self.wkc.push(datagram.working_counter());
        self.returned.append(packet.copy.returned());
        self.data.extend_from_slice(datagram.data());
        self.data_offsets.push(offset(self.data.len()));
        if let Some((offsets, record)) = self.record.as_mut() {
            DatagramRecord {
                packet,
                number,
                datagram,
            }
            .append_json(record, None);
            // The record without its newline.
            record.pop();
            offsets.push(offset(record.len()));
        }
        if self.packet.len() >= BATCH_ROWS
            || self.data.len() >= BATCH_BYTES
            || self
                .record
                .as_ref()
                .is_some_and(|(_, record)| record.len() >= BATCH_BYTES)
        {
            self.flush();
        }
    }

    /// Make a record batch's columns of the rows added since the last.
    fn flush(&mut self) {
        if self.packet.is_empty() {
            return;
        }
        let kinds: ArrayRef = Arc::new(StringArray::from_iter_values([DATAGRAM_KIND]));
        let rows = self.packet.len();
        let ts_nulls = self.ts_valid.0.finish();
        let mut columns: Vec<ArrayRef> = vec![
            Arc::new(UInt64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.packet)),
                None,
            )),
            Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.datagram)),
                None,
            )),
            Arc::new(Float64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.ts)),
                ts_nulls.clone(),
            )),
            Arc::new(Int64Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.time)),
                ts_nulls,
            )),
            Arc::new(DictionaryArray::<Int8Type>::new(
                Int8Array::new(ScalarBuffer::from(vec![0; rows]), None),
                kinds,
            )),
            Arc::new(DictionaryArray::<Int8Type>::new(
                Int8Array::new(ScalarBuffer::from(std::mem::take(&mut self.cmd)), None),
                command_names(),
            )),
            Arc::new(UInt8Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.index)),
                None,
            )),
            Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.adp)),
                self.adp_valid.0.finish(),
            )),
            Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.ado)),
                self.ado_valid.0.finish(),
            )),
            Arc::new(UInt32Array::new(
                ScalarBuffer::from(std::mem::take(&mut self.logical)),
                self.logical_valid.0.finish(),
            )),
        ];
        for values in [&mut self.length, &mut self.irq, &mut self.wkc] {
            columns.push(Arc::new(UInt16Array::new(
                ScalarBuffer::from(std::mem::take(values)),
                None,
            )));
        }
        columns.push(Arc::new(BooleanArray::new(self.returned.finish(), None)));
        columns.push(Arc::new(BinaryArray::new(
            offsets(&mut self.data_offsets),
            Buffer::from_vec(std::mem::take(&mut self.data)),
            None,
        )));
        if let Some((record_offsets, record)) = self.record.as_mut() {
            // DatagramRecord::append_json writes UTF-8; checked once more
            // here, at memory speed.
            columns.push(Arc::new(
                StringArray::try_new(
                    offsets(record_offsets),
                    Buffer::from_vec(std::mem::take(record)),
                    None,
                )
                .expect("the records are UTF-8"),
            ));
        }
        let iface = Int32Array::new(
            ScalarBuffer::from(std::mem::take(&mut self.iface)),
            self.iface_valid.0.finish(),
        );
        self.chunks.push(Chunk { columns, iface });
    }

    /// The rows read, the session's counts (the frames still waiting are
    /// lost).
    pub fn finish(mut self) -> EthercatFinished {
        self.flush();
        EthercatFinished {
            chunks: self.chunks,
            ifaces: self.ifaces.values,
            counts: self.session.finish(),
            clock: self.clock,
        }
    }
}

/// The datagrams of a capture read in full.
pub struct EthercatFinished {
    pub chunks: Vec<Chunk>,
    pub ifaces: Vec<String>,
    pub counts: Counts,
    pub clock: Clock,
}

/// The values of the `cmd` dictionary: the library's names of commands
/// 0–14, then `reserved`.
fn command_names() -> ArrayRef {
    Arc::new(StringArray::from_iter_values(
        (0..=RESERVED_KEY).map(|byte| Command::from_byte(byte).name()),
    ))
}

/// The fields of a datagram's row, after `file` (`read_logs`) and with
/// `record` last for `decode` (docs/python.md#ethercat).
pub fn fields(record: bool, clock: Clock) -> Vec<Field> {
    let dictionary = |key: DataType| DataType::Dictionary(Box::new(key), Box::new(DataType::Utf8));
    let mut fields = vec![
        Field::new("packet", DataType::UInt64, false),
        Field::new("datagram", DataType::UInt16, false),
        Field::new("ts", DataType::Float64, true),
        clock.field(),
        Field::new("iface", dictionary(DataType::Int32), true),
        Field::new("kind", dictionary(DataType::Int8), false),
        Field::new("cmd", dictionary(DataType::Int8), false),
        Field::new("index", DataType::UInt8, false),
        Field::new("adp", DataType::UInt16, true),
        Field::new("ado", DataType::UInt16, true),
        Field::new("logical", DataType::UInt32, true),
        Field::new("length", DataType::UInt16, false),
        Field::new("irq", DataType::UInt16, false),
        Field::new("wkc", DataType::UInt16, false),
        Field::new("returned", DataType::Boolean, false),
        Field::new("data", DataType::Binary, false),
    ];
    if record {
        fields.push(Field::new("record", DataType::Utf8, false));
    }
    fields
}

/// The session's counts as the schema metadata `motionwire.ethercat`
/// holds them (docs/python.md#ethercat): a JSON object, the keys in the
/// order of `Counts`' fields.
pub fn counts_json(counts: &Counts) -> String {
    let Counts {
        packets,
        sent,
        returned,
        returned_unpaired,
        lost,
        other_frame_types,
        damaged,
        time_reversals,
        ..
    } = counts;
    format!(
        "{{\"packets\":{packets},\"sent\":{sent},\"returned\":{returned},\
         \"returned_unpaired\":{returned_unpaired},\"lost\":{lost},\
         \"other_frame_types\":{other_frame_types},\"damaged\":{damaged},\
         \"time_reversals\":{time_reversals}}}"
    )
}

/// The sum of several captures' counts (`read_logs`).
pub fn add_counts(sum: &mut Counts, counts: &Counts) {
    sum.packets += counts.packets;
    sum.sent += counts.sent;
    sum.returned += counts.returned;
    sum.returned_unpaired += counts.returned_unpaired;
    sum.lost += counts.lost;
    sum.other_frame_types += counts.other_frame_types;
    sum.damaged += counts.damaged;
    sum.time_reversals += counts.time_reversals;
    if sum.first_reversal.is_none() {
        sum.first_reversal = counts.first_reversal;
    }
}
