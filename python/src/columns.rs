//! What the tables of CAN frames and of EtherCAT datagrams share
//! (docs/python.md#memory): columns built in plain vectors and bit buffers
//! that become Arrow arrays without a copy, cut into record batches, the
//! interface dictionary, and what was skipped.

use std::collections::HashMap;

use arrow_array::{Array, ArrayRef, Int32Array};
use arrow_buffer::{NullBufferBuilder, OffsetBuffer, ScalarBuffer};
use arrow_schema::{ArrowError, DataType, Field, TimeUnit};
use motionwire::can::{Iface, Timestamp};
use serde_json::{json, Value};

/// The most rows one record batch holds.
pub const BATCH_ROWS: usize = 1 << 20;
/// The most bytes of `data` or `record` one batch holds (Arrow's 32-bit
/// offsets reach 2 GiB).
pub const BATCH_BYTES: usize = 1 << 30;
/// How many skipped lines the schema metadata lists (docs/python.md#metadata: the first 1 000).
pub const SKIPPED_LISTED: usize = 1000;

/// The dictionary of an interface column: each interface's name (`can0`)
/// or channel number (`1`) once, and the key of each.
#[derive(Default)]
pub struct Ifaces {
    pub values: Vec<String>,
    by_name: HashMap<String, i32>,
    by_channel: HashMap<u16, i32>,
    /// The key of the last name looked up: most logs have one interface or
    /// alternate between few.
    last: Option<i32>,
}

impl Ifaces {
    pub fn key(&mut self, iface: Iface<'_>) -> i32 {
        match iface {
            Iface::Name(name) => {
                if let Some(key) = self.last {
                    if self.values[key as usize] == name {
                        return key;
                    }
                }
                let key = match self.by_name.get(name) {
                    Some(&key) => key,
                    None => self.add(name.to_owned()),
                };
                self.last = Some(key);
                key
            }
            Iface::Channel(channel) => match self.by_channel.get(&channel) {
                Some(&key) => key,
                None => {
                    let key = self.add(channel.to_string());
                    self.by_channel.insert(channel, key);
                    key
                }
            },
        }
    }

    /// The key of `name`, added when new (a name and a channel that print
    /// alike are one value).
    pub fn add(&mut self, name: String) -> i32 {
        if let Some(&key) = self.by_name.get(&name) {
            return key;
        }
        let key = i32::try_from(self.values.len()).unwrap_or(i32::MAX);
        self.by_name.insert(name.clone(), key);
        self.values.push(name);
        key
    }
}

/// What was skipped while a log was read (docs/formats.md#reported): the
/// schema metadata `motionwire.skipped` (the first [`SKIPPED_LISTED`]),
/// `motionwire.skipped_count` and `motionwire.other`.
#[derive(Default)]
pub struct Skipped {
    pub count: u64,
    pub listed: Vec<Value>,
    pub other: Vec<Value>,
}

impl Skipped {
    pub fn add(&mut self, file: Option<&str>, line: Option<u64>, reason: String) {
        self.count += 1;
        if self.listed.len() < SKIPPED_LISTED {
            self.listed.push(match file {
                Some(file) => json!({"file": file, "line": line, "reason": reason}),
                None => json!({"line": line, "reason": reason}),
            });
        }
    }

    /// Add what `other` skipped to this one, for a table of several logs.
    pub fn extend(&mut self, other: Skipped) {
        self.count += other.count;
        let room = SKIPPED_LISTED.saturating_sub(self.listed.len());
        self.listed.extend(other.listed.into_iter().take(room));
        self.other.extend(other.other);
    }

    /// The schema metadata.
    pub fn metadata(&self) -> HashMap<String, String> {
        let mut metadata = HashMap::new();
        metadata.insert(
            "motionwire.skipped".to_owned(),
            Value::Array(self.listed.clone()).to_string(),
        );
        metadata.insert(
            "motionwire.skipped_count".to_owned(),
            self.count.to_string(),
        );
        if !self.other.is_empty() {
            metadata.insert(
                "motionwire.other".to_owned(),
                Value::Array(self.other.clone()).to_string(),
            );
        }
        metadata
    }
}

/// Which values of a nullable column are there: a [`NullBufferBuilder`]
/// with a [`Default`], that pushes the value and its validity together.
pub struct Validity(pub NullBufferBuilder);

impl Default for Validity {
    fn default() -> Self {
        Validity(NullBufferBuilder::new(0))
    }
}

impl Validity {
    #[inline]
    pub fn push<T: Default>(&mut self, values: &mut Vec<T>, value: Option<T>) {
        match value {
            Some(value) => {
                values.push(value);
                self.0.append_non_null();
            }
            None => {
                values.push(T::default());
                self.0.append_null();
            }
        }
    }
}

/// One record batch's columns, the interface still as keys (its dictionary
/// is the log's, complete only at the end).
pub struct Chunk {
    /// The columns in schema order without `file` and `iface`.
    pub columns: Vec<ArrayRef>,
    pub iface: Int32Array,
}

/// An offset of a binary or string column (the batch ends before 2 GiB).
#[inline]
pub fn offset(len: usize) -> i32 {
    i32::try_from(len).expect("a batch holds less than 2 GiB")
}

/// The offsets of a finished batch, and a fresh start for the next.
pub fn offsets(offsets: &mut Vec<i32>) -> OffsetBuffer<i32> {
    let taken = std::mem::replace(offsets, vec![0]);
    OffsetBuffer::new(ScalarBuffer::from(taken))
}

/// The `time` column beside `ts` (docs/python.md#time): the library's
/// timestamps to the nanosecond, as Arrow `timestamp[ns, tz=UTC]` where
/// every time of the table reads as Unix time
/// ([`Timestamp::is_unix_time`]), else as `duration[ns]` since the clock's
/// zero (the start of the recording). Built as int64 nanoseconds; the type
/// is the table's, known when every log is read.
#[derive(Debug, Clone, Copy)]
pub struct Clock {
    /// Some time was seen.
    timed: bool,
    /// Every time seen reads as Unix time.
    unix: bool,
}

impl Default for Clock {
    fn default() -> Self {
        Clock {
            timed: false,
            unix: true,
        }
    }
}

impl Clock {
    /// The nanoseconds of `ts` since the clock's zero, the clock told of
    /// it (an int64 of nanoseconds reaches the year 2262).
    #[inline]
    pub fn nanos(&mut self, ts: Option<Timestamp>) -> Option<i64> {
        let ts = ts?;
        self.timed = true;
        self.unix &= ts.is_unix_time();
        Some(i64::try_from(ts.as_duration().as_nanos()).unwrap_or(i64::MAX))
    }

    /// The clock of a table of several logs.
    pub fn merge(&mut self, other: Clock) {
        self.timed |= other.timed;
        self.unix &= other.unix;
    }

    /// Whether `time` is a timestamp (else a duration).
    pub fn is_unix(self) -> bool {
        self.timed && self.unix
    }

    /// The `time` field.
    pub fn field(self) -> Field {
        let data_type = if self.is_unix() {
            DataType::Timestamp(TimeUnit::Nanosecond, Some("UTC".into()))
        } else {
            DataType::Duration(TimeUnit::Nanosecond)
        };
        Field::new("time", data_type, true)
    }

    /// The `time` column of `nanos` with the field's type, without a copy.
    pub fn array(self, nanos: &ArrayRef) -> Result<ArrayRef, ArrowError> {
        retype(nanos, self.field().data_type())
    }
}

/// The int64 `nanos` as the `time` type `to` (a timestamp or a duration
/// of nanoseconds: the same 64 bits), without a copy.
pub fn retype(nanos: &ArrayRef, to: &DataType) -> Result<ArrayRef, ArrowError> {
    let data = nanos
        .to_data()
        .into_builder()
        .data_type(to.clone())
        .build()?;
    Ok(arrow_array::make_array(data))
}
