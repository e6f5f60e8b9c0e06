//! The records of an EtherCAT capture as a table
//! (docs/python.md#ethercat-records): one row per record `decode --json`
//! writes, of the kinds asked (by default what the datagrams tell of the
//! slaves, docs/ethercat.md#meanings), each with the keys every record
//! has, the library's typed columns of a meaning (`MeaningRecord::columns`)
//! and the exact JSON line (`record`). Read by the loop of
//! `process::read`, through the same session as the program's.

use std::sync::Arc;

use arrow_array::types::{Int8Type, UInt16Type, UInt32Type, UInt64Type, UInt8Type};
use arrow_array::BooleanArray;
use arrow_schema::{DataType, Field};
use motionwire::decoder::ethercat::{
    DatagramRecord, Meaning, MeaningColumns, MeaningRecord, Packet, ProcessData, ProcessRecord,
    DATAGRAM_KIND, PROCESS_DATA_KIND, RECORD_KINDS, SERVO_KIND,
};
use motionwire::ethercat::Datagram;

use crate::columns::{
    array, dictionary, take, Bytes, Clock, Dictionary, Ifaces, Nullable, Part, Times, BATCH_BYTES,
    BATCH_ROWS,
};
use crate::process::Rows;

/// The kinds `kinds=None` takes: what the datagrams tell of the slaves
/// (docs/ethercat.md#meanings), without the datagrams (decode's rows) and
/// the process data (process_data's and servo's).
pub const MEANING_KINDS: [&str; 11] = [
    "station",
    "al_state",
    "sii",
    "dl_status",
    "error_counters",
    "mailbox",
    "coe_sdo",
    "coe_emcy",
    "alias",
    "dc",
    "mailbox_repeat",
];

/// The dictionary numbers of the table (0: the interface's).
const KIND: usize = 1;
const AL_REGISTER: usize = 2;
const STATE: usize = 3;
const CODE_TEXT: usize = 4;
const FIELD: usize = 5;
const DIRECTION: usize = 6;
const TYPE: usize = 7;
const SERVICE: usize = 8;
const ABORT: usize = 9;
const DESCRIPTION: usize = 10;
/// How many dictionaries the table has.
const DICTIONARIES: usize = 11;

/// The table of `ethercat_records`, column by column.
pub struct RecordColumns {
    /// Which of [`RECORD_KINDS`] the table holds.
    kinds: [bool; RECORD_KINDS.len()],
    packet: Vec<u64>,
    datagram: Vec<u16>,
    times: Times,
    clock: Clock,
    iface: Nullable<i32>,
    kind: Vec<i8>,
    slave: Nullable<u16>,
    position: Nullable<u16>,
    al_register: Nullable<i8>,
    state: Nullable<i8>,
    al_error: Vec<Option<bool>>,
    code: Nullable<u16>,
    code_text: Nullable<i32>,
    word: Nullable<u32>,
    value: Nullable<u32>,
    field: Nullable<i8>,
    direction: Nullable<i8>,
    mailbox_type: Nullable<i8>,
    service: Nullable<i8>,
    index: Nullable<u16>,
    subindex: Nullable<u8>,
    abort_code: Nullable<u32>,
    abort: Nullable<i32>,
    register: Nullable<u8>,
    description: Nullable<i32>,
    record: Bytes,
    ifaces: Ifaces,
    /// The dictionaries after the interface's (KIND…DESCRIPTION).
    names: Vec<Dictionary>,
    batches: Vec<Vec<Part>>,
}

impl RecordColumns {
    /// The table of the records of `kinds` (each one of [`RECORD_KINDS`]).
    pub fn new(kinds: &[&str]) -> Self {
        let mut names: Vec<Dictionary> = (KIND..DICTIONARIES)
            .map(|_| Dictionary::default())
            .collect();
        names[0] = Dictionary::with(&RECORD_KINDS);
        RecordColumns {
            kinds: RECORD_KINDS.map(|kind| kinds.contains(&kind)),
            packet: Vec::new(),
            datagram: Vec::new(),
            times: Times::default(),
            clock: Clock::default(),
            iface: Nullable::default(),
            kind: Vec::new(),
            slave: Nullable::default(),
            position: Nullable::default(),
            al_register: Nullable::default(),
            state: Nullable::default(),
            al_error: Vec::new(),
            code: Nullable::default(),
            code_text: Nullable::default(),
            word: Nullable::default(),
            value: Nullable::default(),
            field: Nullable::default(),
            direction: Nullable::default(),
            mailbox_type: Nullable::default(),
            service: Nullable::default(),
            index: Nullable::default(),
            subindex: Nullable::default(),
            abort_code: Nullable::default(),
            abort: Nullable::default(),
            register: Nullable::default(),
            description: Nullable::default(),
            record: Bytes::default(),
            ifaces: Ifaces::default(),
            names,
            batches: Vec::new(),
        }
    }

    /// Whether the table holds records of `kind`.
    fn wants(&self, kind: &str) -> bool {
        RECORD_KINDS
            .iter()
            .zip(self.kinds)
            .any(|(k, wanted)| wanted && *k == kind)
    }

    /// The key of `value` in dictionary `at` (int8 keys: few values).
    fn key8(&mut self, at: usize, value: &str) -> i8 {
        self.names[at - KIND].key8(value)
    }

    /// The key of `value` in dictionary `at` (int32 keys).
    fn key32(&mut self, at: usize, value: &str) -> i32 {
        self.names[at - KIND].key(value)
    }

    /// Start a row: the keys every record of `packet`'s `number`-th
    /// datagram has, and its kind and slave. `append` writes the record
    /// (with its newline, left out).
    fn row(
        &mut self,
        packet: &Packet<'_>,
        number: usize,
        kind: &str,
        slave: (Option<u16>, Option<u16>),
        append: impl FnOnce(&mut Vec<u8>),
    ) {
        self.packet.push(packet.position.number());
        // A frame's 11-bit length holds at most 170 datagrams.
        self.datagram
            .push(u16::try_from(number).unwrap_or(u16::MAX));
        let nanos = self.clock.nanos(packet.timestamp);
        self.times
            .push(packet.timestamp.map(|ts| ts.as_secs_f64()), nanos);
        let iface = packet.iface.map(|iface| self.ifaces.key(iface));
        self.iface.push(iface);
        let kind = self.key8(KIND, kind);
        self.kind.push(kind);
        self.slave.push(slave.0);
        self.position.push(slave.1);
        let out = self.record.buffer();
        append(out);
        // The record without its newline.
        out.pop();
        self.record.end_row();
    }

    /// The typed columns of a row: a meaning's, or none.
    fn typed(&mut self, columns: &MeaningColumns) {
        let al_register = columns
            .al_register
            .map(|r| self.key8(AL_REGISTER, r.name()));
        self.al_register.push(al_register);
        let state = columns.state.map(|s| self.key8(STATE, s.name()));
        self.state.push(state);
        self.al_error.push(columns.al_error);
        let code = columns
            .al_code
            .map(|code| code.0)
            .or(columns.emcy_code.map(|code| code.get()));
        self.code.push(code);
        let code_text = columns.al_code.and_then(|code| code.text());
        let code_text = code_text.map(|text| self.key32(CODE_TEXT, text));
        self.code_text.push(code_text);
        self.word.push(columns.sii_word);
        self.value.push(columns.sii_value);
        let field = columns.sii_field.map(|f| self.key8(FIELD, f.name()));
        self.field.push(field);
        let direction = columns
            .written
            .map(|w| self.key8(DIRECTION, if w { "write" } else { "read" }));
        self.direction.push(direction);
        let mailbox_type = columns.mailbox_type.map(|t| self.key8(TYPE, t.name()));
        self.mailbox_type.push(mailbox_type);
        let service = columns.service.map(|s| self.key8(SERVICE, s.name()));
        self.service.push(service);
        self.index.push(columns.index);
        self.subindex.push(columns.subindex);
        self.abort_code
            .push(columns.abort_code.map(|code| code.get()));
        let abort = columns
            .abort_code
            .map(|code| self.key32(ABORT, &code.to_string()));
        self.abort.push(abort);
        self.register.push(columns.emcy_register.map(|r| r.bits()));
        let description = columns
            .description
            .map(|text| self.key32(DESCRIPTION, text));
        self.description.push(description);
    }

    /// Cut a batch when it is full.
    fn full(&mut self) {
        if self.packet.len() >= BATCH_ROWS || self.record.len() >= BATCH_BYTES {
            self.flush();
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
            Part::keys32(&mut self.iface, 0),
            Part::Keys8(take::<Int8Type>(&mut self.kind), KIND),
            Part::Array(self.slave.array::<UInt16Type>()),
            Part::Array(self.position.array::<UInt16Type>()),
            Part::keys8(&mut self.al_register, AL_REGISTER),
            Part::keys8(&mut self.state, STATE),
            Part::Array(Arc::new(BooleanArray::from(std::mem::take(
                &mut self.al_error,
            )))),
            Part::Array(self.code.array::<UInt16Type>()),
            Part::keys32(&mut self.code_text, CODE_TEXT),
            Part::Array(self.word.array::<UInt32Type>()),
            Part::Array(self.value.array::<UInt32Type>()),
            Part::keys8(&mut self.field, FIELD),
            Part::keys8(&mut self.direction, DIRECTION),
            Part::keys8(&mut self.mailbox_type, TYPE),
            Part::keys8(&mut self.service, SERVICE),
            Part::Array(self.index.array::<UInt16Type>()),
            Part::Array(self.subindex.array::<UInt8Type>()),
            Part::Array(self.abort_code.array::<UInt32Type>()),
            Part::keys32(&mut self.abort, ABORT),
            Part::Array(self.register.array::<UInt8Type>()),
            Part::keys32(&mut self.description, DESCRIPTION),
            Part::Array(self.record.strings()),
        ];
        self.batches.push(parts);
    }
}

impl Rows for RecordColumns {
    fn clock(&mut self) -> &mut Clock {
        &mut self.clock
    }

    fn datagram(&mut self, packet: &Packet<'_>, number: usize, datagram: Datagram<'_>) {
        if !self.wants(DATAGRAM_KIND) {
            return;
        }
        let record = DatagramRecord {
            packet,
            number,
            datagram,
        };
        self.row(packet, number, DATAGRAM_KIND, (None, None), |out| {
            record.append_json(out, None)
        });
        self.typed(&MeaningColumns::default());
        self.full();
    }

    fn meaning<'a>(&mut self, packet: &Packet<'a>, number: usize, meaning: Meaning<'a>) {
        let record = MeaningRecord {
            packet,
            number,
            meaning,
        };
        let kind = record.kind();
        if !self.wants(kind) {
            return;
        }
        let slave = record.slave();
        self.row(
            packet,
            number,
            kind,
            (slave.station, slave.position),
            |out| record.append_json(out, None),
        );
        self.typed(&record.columns());
        self.full();
    }

    fn push(&mut self, packet: &Packet<'_>, number: usize, data: &ProcessData<'_>) {
        let record = ProcessRecord {
            packet,
            number,
            data,
        };
        let slave = data.slave.unwrap_or_default();
        let slave = (slave.station, slave.position);
        if self.wants(PROCESS_DATA_KIND) {
            self.row(packet, number, PROCESS_DATA_KIND, slave, |out| {
                record.append_json(out, None)
            });
            self.typed(&MeaningColumns::default());
        }
        if data.servo.is_some() && self.wants(SERVO_KIND) {
            self.row(packet, number, SERVO_KIND, slave, |out| {
                record.append_servo_json(out, None)
            });
            self.typed(&MeaningColumns::default());
        }
        self.full();
    }

    fn finish(mut self) -> (Vec<Field>, Vec<Vec<Part>>, Vec<Dictionary>) {
        self.flush();
        let key8 = || dictionary(DataType::Int8);
        let key32 = || dictionary(DataType::Int32);
        let fields = vec![
            Field::new("packet", DataType::UInt64, false),
            Field::new("datagram", DataType::UInt16, false),
            Field::new("ts", DataType::Float64, true),
            self.clock.field(),
            Field::new("iface", key32(), true),
            Field::new("kind", key8(), false),
            Field::new("slave", DataType::UInt16, true),
            Field::new("position", DataType::UInt16, true),
            Field::new("al_register", key8(), true),
            Field::new("state", key8(), true),
            Field::new("al_error", DataType::Boolean, true),
            Field::new("code", DataType::UInt16, true),
            Field::new("code_text", key32(), true),
            Field::new("word", DataType::UInt32, true),
            Field::new("value", DataType::UInt32, true),
            Field::new("field", key8(), true),
            Field::new("direction", key8(), true),
            Field::new("type", key8(), true),
            Field::new("service", key8(), true),
            Field::new("index", DataType::UInt16, true),
            Field::new("subindex", DataType::UInt8, true),
            Field::new("abort_code", DataType::UInt32, true),
            Field::new("abort", key32(), true),
            Field::new("register", DataType::UInt8, true),
            Field::new("description", key32(), true),
            Field::new("record", DataType::Utf8, false),
        ];
        let mut dictionaries = vec![Dictionary::of(self.ifaces.values)];
        dictionaries.extend(self.names);
        (fields, self.batches, dictionaries)
    }
}
