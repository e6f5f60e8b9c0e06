//! The table of an EtherCAT capture (docs/python.md#ethercat): one row per
//! datagram, the keys of the program's `ecat_datagram` record as columns
//! (docs/ethercat.md#records). The library's `ethercat::Session` tells
//! which copy of its frame each packet is; `DatagramRecord` writes the
//! record `decode` adds.

use std::sync::Arc;

use arrow_array::types::{Int32Type, Int8Type, UInt16Type, UInt32Type, UInt64Type, UInt8Type};
use arrow_array::{ArrayRef, BooleanArray, DictionaryArray, Int8Array, StringArray};
use arrow_buffer::{BooleanBufferBuilder, ScalarBuffer};
use arrow_schema::{DataType, Field};
use motionwire::can::EthercatPacket;
use motionwire::decoder::ethercat::{Counts, DatagramRecord, Packet, Session, DATAGRAM_KIND};
use motionwire::ethercat::{Addressing, Command, Datagram};
use motionwire::logs::Position;

use crate::columns::{
    array, dictionary, take, Bytes, Chunk, Clock, Ifaces, Nullable, Skipped, Times, BATCH_BYTES,
    BATCH_ROWS,
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
    times: Times,
    clock: Clock,
    iface: Nullable<i32>,
    cmd: Vec<i8>,
    index: Vec<u8>,
    adp: Nullable<u16>,
    ado: Nullable<u16>,
    logical: Nullable<u32>,
    length: Vec<u16>,
    irq: Vec<u16>,
    wkc: Vec<u16>,
    returned: BooleanBufferBuilder,
    data: Bytes,
    /// `decode`'s `record` column: each datagram's JSON record.
    record: Option<Bytes>,
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
            times: Times::default(),
            clock: Clock::default(),
            iface: Nullable::default(),
            cmd: Vec::new(),
            index: Vec::new(),
            adp: Nullable::default(),
            ado: Nullable::default(),
            logical: Nullable::default(),
            length: Vec::new(),
            irq: Vec::new(),
            wkc: Vec::new(),
            returned: BooleanBufferBuilder::new(0),
            data: Bytes::default(),
            record: record.then(Bytes::default),
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
        let nanos = self.clock.nanos(packet.timestamp);
        self.times
            .push(packet.timestamp.map(|ts| ts.as_secs_f64()), nanos);
        let iface = packet.iface.map(|iface| self.ifaces.key(iface));
        self.iface.push(iface);
        let command = datagram.command();
        self.cmd.push(command.byte().min(RESERVED_KEY) as i8);
        self.index.push(datagram.index());
        let logical = command.addressing() == Addressing::Logical;
        self.adp.push((!logical).then(|| datagram.adp()));
        self.ado.push((!logical).then(|| datagram.ado()));
        self.logical.push(logical.then(|| datagram.address()));
        self.length.push(datagram.length());
        self.irq.push(datagram.irq());
        self.wkc.push(datagram.working_counter());
        self.returned.append(packet.copy.returned());
        self.data.push(datagram.data());
        if let Some(record) = self.record.as_mut() {
            let out = record.buffer();
            DatagramRecord {
                packet,
                number,
                datagram,
            }
            .append_json(out, None);
            // The record without its newline.
            out.pop();
            record.end_row();
        }
        if self.packet.len() >= BATCH_ROWS
            || self.data.len() >= BATCH_BYTES
            || self
                .record
                .as_ref()
                .is_some_and(|record| record.len() >= BATCH_BYTES)
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
        let [ts, time] = self.times.arrays();
        let mut columns: Vec<ArrayRef> = vec![
            array::<UInt64Type>(&mut self.packet),
            array::<UInt16Type>(&mut self.datagram),
            ts,
            time,
            Arc::new(DictionaryArray::<Int8Type>::new(
                Int8Array::new(ScalarBuffer::from(vec![0; rows]), None),
                kinds,
            )),
            Arc::new(DictionaryArray::<Int8Type>::new(
                take::<Int8Type>(&mut self.cmd),
                command_names(),
            )),
            array::<UInt8Type>(&mut self.index),
            self.adp.array::<UInt16Type>(),
            self.ado.array::<UInt16Type>(),
            self.logical.array::<UInt32Type>(),
            array::<UInt16Type>(&mut self.length),
            array::<UInt16Type>(&mut self.irq),
            array::<UInt16Type>(&mut self.wkc),
            Arc::new(BooleanArray::new(self.returned.finish(), None)),
            self.data.binary(),
        ];
        if let Some(record) = self.record.as_mut() {
            columns.push(record.strings());
        }
        let iface = self.iface.take::<Int32Type>();
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
