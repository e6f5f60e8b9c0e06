//! What every table shares (docs/python.md#memory): columns built in plain
//! vectors and bit buffers that become Arrow arrays without a copy
//! ([`take`], [`Nullable`], [`Times`], [`Bytes`]), cut into record
//! batches, dictionary columns whose values are known at the end
//! ([`Dictionary`], [`Part`], [`assemble`]), the interface dictionary, and
//! what was skipped.

use std::collections::HashMap;
use std::sync::Arc;

use arrow_array::types::{Float64Type, Int32Type, Int64Type, Int8Type};
use arrow_array::{
    Array, ArrayRef, ArrowPrimitiveType, BinaryArray, DictionaryArray, Int32Array, Int8Array,
    PrimitiveArray, RecordBatch, StringArray,
};
use arrow_buffer::{Buffer, NullBuffer, NullBufferBuilder, OffsetBuffer, ScalarBuffer};
use arrow_schema::{ArrowError, DataType, Field, SchemaRef, TimeUnit};
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

/// The values of a column without nulls as an Arrow array, without a copy;
/// the vector is left empty for the next batch.
#[inline]
pub fn take<A: ArrowPrimitiveType>(values: &mut Vec<A::Native>) -> PrimitiveArray<A> {
    PrimitiveArray::new(ScalarBuffer::from(std::mem::take(values)), None)
}

/// [`take`] as an [`ArrayRef`].
#[inline]
pub fn array<A: ArrowPrimitiveType>(values: &mut Vec<A::Native>) -> ArrayRef {
    Arc::new(take::<A>(values))
}

/// A column with nulls: its values (a default where null) and which are
/// there, pushed together.
pub struct Nullable<T> {
    values: Vec<T>,
    valid: Validity,
}

impl<T> Default for Nullable<T> {
    fn default() -> Self {
        Nullable {
            values: Vec::new(),
            valid: Validity::default(),
        }
    }
}

impl<T: Default> Nullable<T> {
    #[inline]
    pub fn push(&mut self, value: Option<T>) {
        self.valid.push(&mut self.values, value);
    }
}

impl<T: arrow_buffer::ArrowNativeType> Nullable<T> {
    /// The rows pushed since the last batch as an Arrow array of `A`.
    pub fn take<A: ArrowPrimitiveType<Native = T>>(&mut self) -> PrimitiveArray<A> {
        PrimitiveArray::new(
            ScalarBuffer::from(std::mem::take(&mut self.values)),
            self.valid.0.finish(),
        )
    }

    /// [`take`](Self::take) as an [`ArrayRef`].
    pub fn array<A: ArrowPrimitiveType<Native = T>>(&mut self) -> ArrayRef {
        Arc::new(self.take::<A>())
    }
}

/// `ts` and `time` (docs/python.md#time): float64 seconds and int64
/// nanoseconds of the same instants, null together.
#[derive(Default)]
pub struct Times {
    ts: Nullable<f64>,
    nanos: Vec<i64>,
}

impl Times {
    /// Add a row's time: its seconds and the nanoseconds [`Clock::nanos`]
    /// gave for it.
    #[inline]
    pub fn push(&mut self, ts: Option<f64>, nanos: Option<i64>) {
        self.ts.push(ts);
        self.nanos.push(nanos.unwrap_or_default());
    }

    /// The `ts` column and `time` as int64 nanoseconds (typed by the
    /// table's [`Clock`] once every log is read).
    pub fn arrays(&mut self) -> [ArrayRef; 2] {
        let ts = self.ts.take::<Float64Type>();
        let nulls: Option<NullBuffer> = ts.nulls().cloned();
        let time = PrimitiveArray::<Int64Type>::new(
            ScalarBuffer::from(std::mem::take(&mut self.nanos)),
            nulls,
        );
        [Arc::new(ts), Arc::new(time)]
    }
}

/// A binary or string column: every row's bytes one after another, and
/// where each ends.
pub struct Bytes {
    offsets: Vec<i32>,
    bytes: Vec<u8>,
}

impl Default for Bytes {
    fn default() -> Self {
        Bytes {
            offsets: vec![0],
            bytes: Vec::new(),
        }
    }
}

impl Bytes {
    /// Add a row of `value`.
    #[inline]
    pub fn push(&mut self, value: &[u8]) {
        self.bytes.extend_from_slice(value);
        self.end_row();
    }

    /// The bytes written so far, to append a row's to before
    /// [`end_row`](Self::end_row).
    #[inline]
    pub fn buffer(&mut self) -> &mut Vec<u8> {
        &mut self.bytes
    }

    /// End the row at the bytes written so far.
    #[inline]
    pub fn end_row(&mut self) {
        self.offsets.push(offset(self.bytes.len()));
    }

    /// The bytes of the rows since the last batch.
    pub fn len(&self) -> usize {
        self.bytes.len()
    }

    /// The rows since the last batch as a binary array.
    pub fn binary(&mut self) -> ArrayRef {
        Arc::new(BinaryArray::new(
            offsets(&mut self.offsets),
            Buffer::from_vec(std::mem::take(&mut self.bytes)),
            None,
        ))
    }

    /// The rows since the last batch as a string array: the library's JSON
    /// records, UTF-8 as written, checked once more here at memory speed.
    pub fn strings(&mut self) -> ArrayRef {
        Arc::new(
            StringArray::try_new(
                offsets(&mut self.offsets),
                Buffer::from_vec(std::mem::take(&mut self.bytes)),
                None,
            )
            .expect("the records are UTF-8"),
        )
    }
}

/// The type of a dictionary column of strings keyed by `key`.
pub fn dictionary(key: DataType) -> DataType {
    DataType::Dictionary(Box::new(key), Box::new(DataType::Utf8))
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
    /// The dictionary of `values` in this order.
    pub fn with(values: &[&str]) -> Self {
        let mut dictionary = Dictionary::default();
        for value in values {
            dictionary.key(value);
        }
        dictionary
    }

    /// The dictionary of `values`, all different (an [`Ifaces`]').
    pub fn of(values: Vec<String>) -> Self {
        let keys = (0..).zip(&values).map(|(k, v)| (v.clone(), k)).collect();
        Dictionary { values, keys }
    }

    pub fn key(&mut self, value: &str) -> i32 {
        if let Some(&key) = self.keys.get(value) {
            return key;
        }
        let key = i32::try_from(self.values.len()).unwrap_or(i32::MAX);
        self.keys.insert(value.to_owned(), key);
        self.values.push(value.to_owned());
        key
    }

    /// The key of `value` in a dictionary of few values (int8 keys).
    pub fn key8(&mut self, value: &str) -> i8 {
        i8::try_from(self.key(value)).unwrap_or(i8::MAX)
    }

    pub fn array(&self) -> ArrayRef {
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

impl Part {
    /// The keys of `keys` into dictionary number `at`, int32.
    pub fn keys32(keys: &mut Nullable<i32>, at: usize) -> Part {
        Part::Keys32(keys.take::<Int32Type>(), at)
    }

    /// The keys of `keys` into dictionary number `at`, int8.
    pub fn keys8(keys: &mut Nullable<i8>, at: usize) -> Part {
        Part::Keys8(keys.take::<Int8Type>(), at)
    }
}

/// The record batches, each dictionary column with its complete values.
pub fn assemble(
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
