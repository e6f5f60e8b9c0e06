//! Vector BLF binary logs (CANoe, CANalyzer, python-can's `BLFWriter`;
//! docs/formats.md#blf), behind the `blf` feature.
//!
//! A BLF file is a 144-byte `LOGG` header (with the measurement's start
//! time) followed by objects, each behind a `LOBJ` header; the objects that
//! matter sit in `LOG_CONTAINER` objects whose data is zlib-compressed (or
//! stored), and an object may continue from one container into the next.
//! [`BlfReader`] streams them, memory bounded by [`MAX_RECORD_LEN`]
//! whatever the file claims: on a machine with more than one core, a
//! second thread inflates the next containers (up to three ahead) while
//! the objects of the one before are read (docs/formats.md#blf;
//! [`BlfReader::on_one_thread`] to inflate on the reading thread).
//!
//! | object | type | read as |
//! |---|---|---|
//! | `CAN_MESSAGE`, `CAN_MESSAGE2` | 1, 86 | classic data or remote frame |
//! | `CAN_FD_MESSAGE` | 100 | CAN FD frame (EDL set) or classic frame |
//! | `CAN_FD_MESSAGE_64` | 101 | CAN FD frame (EDL set) or classic frame |
//! | `CAN_ERROR_EXT` | 73 | error frame |
//! | `LOG_CONTAINER` | 10 | its objects |
//! | any other | | counted ([`ReadLog::other_records`]), skipped |
//!
//! # Decisions (where the format and the tools leave room; docs/formats.md#blf)
//!
//! - `line` is the 1-based number of the object among the objects that are
//!   not containers, every type counted (docs/formats.md#positions); containers
//!   only hold them.
//! - `ts` is the header's start time (a `SYSTEMTIME`, read as UTC as
//!   python-can does; 0 when the header has none) plus the object's time
//!   (units of 10 µs when its header's flags say 1, else nanoseconds).
//! - `iface` is the object's channel ([`Iface::Channel`], 1 for the first,
//!   as the file writes it; python-can counts from 0). `direction` is `Tx`
//!   when the object says it was sent.
//! - A frame whose valid-data-bytes count exceeds the bytes stored is padded
//!   with zeros; a remote request has no data whatever the object stores
//!   (docs/formats.md#blf). A classic frame's DLC above 8 carries 8 bytes.
//! - `CAN_ERROR_EXT` is an error frame of classes `bus_error | protocol`
//!   whose data is Linux's layout (docs/formats.md#error-frames) of the
//!   object's error byte, read as its flags say (Vector's definition):
//!   with bit 0 set it is SJA1000's error code capture register, with bit
//!   1 set (and 0 clear) Vector's CAN-Core error code (code and direction),
//!   with neither it says nothing. Byte 2 is the error type (bit 0x01,
//!   form 0x02, stuff 0x04, other 0) with 0x80 when it happened while
//!   sending, byte 3 the location (SJA1000's segment; CRC sequence 0x08
//!   or ACK delimiter 0x1B for CAN-Core's CRC and ACK errors); the
//!   direction is the frame's where the byte says it. python-can gives
//!   the object's identifier and data bytes instead.
//! - Objects inside a container follow each other after their size, with
//!   up to 7 bytes of padding skipped before the next `LOBJ` (writers pad
//!   differently); top-level objects are followed by `size % 4` padding
//!   bytes, as Vector's and python-can's writers write them.
//! - A damaged file ends the reading with one [`FormatError::Binary`] after the
//!   frames before it; a frame object whose content cannot be read (a
//!   standard identifier above 0x7FF, a body shorter than its type) is one
//!   error and the reading goes on with the next object. Its offset is the byte in the file for the header
//!   and containers, and the byte in the decompressed object stream (all
//!   containers' data in a row) for an object inside a container.
//!
//! ```
//! # fn main() -> Result<(), motionwire::logs::LogError> {
//! use motionwire::logs::blf::BlfReader;
//! use motionwire::logs::ReadLog;
//!
//! // A file with the header only: no records.
//! let mut file = vec![0u8; 144];
//! file[..4].copy_from_slice(b"LOGG");
//! file[4..8].copy_from_slice(&144u32.to_le_bytes());
//! let mut reader = BlfReader::new(&file[..])?;
//! assert!(reader.next_event().is_none());
//! # Ok(())
//! # }
//! ```

use std::collections::VecDeque;
use std::io::{self, Read};

use crate::can::{
    CanFrame, CanId, Direction, ErrorClasses, FdFlags, Iface, LogEvent, LogFrame, Timestamp,
    CLASSIC_MAX_LEN, FD_MAX_LEN,
};
use crate::logs::bytes::{u16_le, u32_le, u64_le};
use crate::logs::calendar::{days_in_month, days_since_epoch};
use crate::logs::FormatError;
use crate::logs::{
    BinaryError, LogError, LogErrorKind, LogFormat, LogRecord, OtherCounts, OtherRecord,
    OtherRecords, Position, ReadLog, MAX_RECORD_LEN,
};

mod inflate;
#[cfg(test)]
mod tests;
#[cfg(test)]
pub(crate) mod writer;

/// Object types (Vector's binlog headers, as python-can names them).
mod object {
    pub(super) const CAN_MESSAGE: u32 = 1;
    pub(super) const LOG_CONTAINER: u32 = 10;
    pub(super) const CAN_ERROR_EXT: u32 = 73;
    pub(super) const CAN_MESSAGE2: u32 = 86;
    pub(super) const CAN_FD_MESSAGE: u32 = 100;
    pub(super) const CAN_FD_MESSAGE_64: u32 = 101;
}

/// The fixed part of the file header.
const FILE_HEADER_LEN: usize = 72;
/// `LOBJ`, header size, header version, object size, object type.
const BASE_HEADER_LEN: usize = 16;
const V1_HEADER_LEN: usize = 16;
const V2_HEADER_LEN: usize = 24;
const CONTAINER_HEADER_LEN: usize = 16;

/// What one object in the stream is.
#[derive(Debug)]
enum Object {
    Frame(LogFrame<'static>),
    /// A type that holds no frame: counted.
    Other,
    /// A frame object whose content cannot be read (e.g. a standard
    /// identifier above 0x7FF); the reading goes on after it.
    Bad(FormatError),
}

/// A reader of Vector BLF files (docs/formats.md#blf): see the
/// [module documentation](self).
#[derive(Debug)]
pub struct BlfReader<R: Read> {
    reader: R,
    /// Bytes of the file read so far.
    file_offset: u64,
    start: Timestamp,
    /// Decompressed object bytes not yet read, from `pos`.
    stream: Vec<u8>,
    pos: usize,
    /// Bytes of the decompressed stream dropped before `stream[0]`.
    stream_base: u64,
    /// Objects (not containers) seen.
    number: u64,
    other: OtherCounts,
    /// Objects reported as damaged and skipped.
    bad: u64,
    done: bool,
    /// The file has no more containers.
    file_done: bool,
    /// Inflate containers on a second thread (the default, on a machine
    /// with more than one core).
    ahead: bool,
    /// The second thread, once a compressed container was read.
    inflater: Option<inflate::Inflater>,
    /// The top-level objects read ahead of the stream, in file order.
    queue: VecDeque<Ahead>,
}

/// A top-level object read from the file.
enum TopLevel {
    /// Bytes that go to the stream as they are: an object outside any
    /// container, or a stored container's data.
    Bytes(Vec<u8>),
    /// A compressed container at `at` in the file: its body, whose zlib
    /// data starts after the container header, and its inflated size.
    Deflated {
        at: u64,
        body: Vec<u8>,
        uncompressed: usize,
    },
}

/// A top-level object read ahead, waiting for the stream.
#[derive(Debug)]
enum Ahead {
    Bytes(Vec<u8>),
    /// Given to the second thread: the container at `at` in the file.
    Inflating {
        at: u64,
    },
    /// What reading the file came to: the end of the reading.
    Failed(LogError),
}

impl<R: Read> BlfReader<R> {
    /// Read the file header.
    ///
    /// # Errors
    ///
    /// A [`LogError`] of kind [`LogErrorKind::Io`] when reading fails, and
    /// of kind [`LogErrorKind::Damaged`] with an
    /// [`FormatError::Binary`] of [`LogFormat::Blf`] when the file does not start
    /// with `LOGG` ([`BinaryError::BadMagic`]), is cut inside its header, or
    /// its header size is shorter than the header or above
    /// [`MAX_RECORD_LEN`].
    pub fn new(mut reader: R) -> Result<Self, LogError> {
        let mut head = [0u8; FILE_HEADER_LEN];
        let got = read_full(&mut reader, &mut head)?;
        if got >= 4 && head.get(..4) != Some(b"LOGG") {
            return Err(fail(
                0,
                BinaryError::BadMagic {
                    found: u32_le(&head, 0),
                },
            ));
        }
        if got < FILE_HEADER_LEN {
            return Err(fail(
                0,
                BinaryError::Truncated {
                    needed: FILE_HEADER_LEN as u64,
                    found: got as u64,
                },
            ));
        }
        let header_len = u32_le(&head, 4) as usize;
        if header_len < FILE_HEADER_LEN {
            return Err(fail(
                4,
                BinaryError::BadLength {
                    length: header_len as u64,
                },
            ));
        }
        if header_len > MAX_RECORD_LEN {
            return Err(fail(
                4,
                BinaryError::TooLarge {
                    length: header_len as u64,
                    limit: MAX_RECORD_LEN as u64,
                },
            ));
        }
        let rest = (header_len - FILE_HEADER_LEN) as u64;
        let skipped = io::copy(&mut (&mut reader).take(rest), &mut io::sink())?;
        if skipped < rest {
            return Err(fail(
                0,
                BinaryError::Truncated {
                    needed: header_len as u64,
                    found: FILE_HEADER_LEN as u64 + skipped,
                },
            ));
        }
        let start = system_time(&head, 40);
        Ok(BlfReader {
            reader,
            file_offset: header_len as u64,
            start,
            stream: Vec::new(),
            pos: 0,
            stream_base: 0,
            number: 0,
            other: OtherCounts::default(),
            bad: 0,
            done: false,
            file_done: false,
            ahead: std::thread::available_parallelism().is_ok_and(|n| n.get() > 1),
            inflater: None,
            queue: VecDeque::new(),
        })
    }

    /// Return the reader inflating every container on the thread that
    /// reads it.
    ///
    /// By default, on a machine with more than one core, a second thread
    /// inflates the next containers (up to three ahead) while the reading
    /// thread reads the objects of the one before; the records, errors
    /// included, are the same and in the same order either way
    /// (docs/formats.md#blf). Where no thread can be started, the reader
    /// inflates on its own thread.
    #[must_use]
    pub fn on_one_thread(mut self) -> Self {
        self.ahead = false;
        self
    }

    /// Inflate ahead on a second thread even on a machine with one core
    /// (the tests hold both ways to each other).
    #[cfg(test)]
    fn ahead_always(mut self) -> Self {
        self.ahead = true;
        self
    }

    /// The measurement's start time from the file header (UTC).
    #[must_use]
    pub const fn start_time(&self) -> Timestamp {
        self.start
    }

    /// Make `need` bytes available in the stream from `pos`, reading
    /// containers (or top-level objects) from the file; `false` at the end
    /// of the file.
    fn fill(&mut self, need: usize) -> Result<bool, LogError> {
        while self.stream.len() - self.pos < need {
            if self.file_done && self.queue.is_empty() {
                return Ok(false);
            }
            // Drop what was read.
            if self.pos > 0 {
                self.stream.drain(..self.pos);
                self.stream_base += self.pos as u64;
                self.pos = 0;
            }
            if self.ahead {
                self.next_ahead()?;
                continue;
            }
            match self.read_top_level()? {
                None => self.file_done = true,
                Some(TopLevel::Bytes(bytes)) => self.stream.extend_from_slice(&bytes),
                Some(TopLevel::Deflated {
                    at,
                    body,
                    uncompressed,
                }) => {
                    let data = body.get(CONTAINER_HEADER_LEN..).unwrap_or_default();
                    if !inflate::append(data, uncompressed, &mut self.stream) {
                        return Err(fail(at, BinaryError::Decompression));
                    }
                }
            }
        }
        Ok(true)
    }

    /// Read ahead up to [`inflate::AHEAD`] top-level objects, compressed
    /// containers handed to the second thread, and add the first to the
    /// stream.
    fn next_ahead(&mut self) -> Result<(), LogError> {
        while !self.file_done && self.queue.len() < inflate::AHEAD {
            let next = match self.read_top_level() {
                Ok(None) => {
                    self.file_done = true;
                    break;
                }
                Ok(Some(next)) => next,
                // Said after the objects before it, as on one thread.
                Err(e) => {
                    self.file_done = true;
                    self.queue.push_back(Ahead::Failed(e));
                    break;
                }
            };
            let ahead = match next {
                TopLevel::Bytes(bytes) => Ahead::Bytes(bytes),
                TopLevel::Deflated {
                    at,
                    body,
                    uncompressed,
                } => {
                    if self.inflater.is_none() {
                        self.inflater = inflate::Inflater::start();
                    }
                    match &mut self.inflater {
                        Some(inflater) => {
                            if inflater.send(body, CONTAINER_HEADER_LEN, uncompressed) {
                                Ahead::Inflating { at }
                            } else {
                                Ahead::Failed(lost_thread(at))
                            }
                        }
                        None => {
                            // No second thread here: inflate on this one.
                            let data = body.get(CONTAINER_HEADER_LEN..).unwrap_or_default();
                            let mut out = Vec::new();
                            if inflate::inflate(data, uncompressed, &mut out) {
                                Ahead::Bytes(out)
                            } else {
                                Ahead::Failed(fail(at, BinaryError::Decompression))
                            }
                        }
                    }
                }
            };
            self.queue.push_back(ahead);
        }
        match self.queue.pop_front() {
            None => Ok(()),
            Some(Ahead::Bytes(bytes)) => {
                self.stream.extend_from_slice(&bytes);
                Ok(())
            }
            Some(Ahead::Failed(e)) => {
                self.queue.clear();
                Err(e)
            }
            Some(Ahead::Inflating { at }) => {
                let inflater = self.inflater.as_mut().ok_or_else(|| lost_thread(at))?;
                match inflater.next() {
                    Ok(Some(bytes)) => {
                        self.stream.extend_from_slice(&bytes);
                        inflater.recycle(bytes);
                        Ok(())
                    }
                    Ok(None) => {
                        self.queue.clear();
                        Err(fail(at, BinaryError::Decompression))
                    }
                    Err(_) => {
                        self.queue.clear();
                        Err(lost_thread(at))
                    }
                }
            }
        }
    }

    /// Read one top-level object: a container's data for the stream, or
    /// any other object (whole, as it stands in the file); `None` at the
    /// end of the file.
    fn read_top_level(&mut self) -> Result<Option<TopLevel>, LogError> {
        let at = self.file_offset;
        let mut header = [0u8; BASE_HEADER_LEN];
        let got = read_full(&mut self.reader, &mut header)?;
        if got == 0 {
            return Ok(None);
        }
        if got < BASE_HEADER_LEN {
            return Err(fail(
                at,
                BinaryError::Truncated {
                    needed: BASE_HEADER_LEN as u64,
                    found: got as u64,
                },
            ));
        }
        if header.get(..4) != Some(b"LOBJ") {
            return Err(fail(
                at,
                BinaryError::BadMagic {
                    found: u32_le(&header, 0),
                },
            ));
        }
        let size = u32_le(&header, 8) as usize;
        let kind = u32_le(&header, 12);
        if size < BASE_HEADER_LEN {
            return Err(fail(
                at + 8,
                BinaryError::BadLength {
                    length: size as u64,
                },
            ));
        }
        if size > MAX_RECORD_LEN {
            return Err(fail(
                at + 8,
                BinaryError::TooLarge {
                    length: size as u64,
                    limit: MAX_RECORD_LEN as u64,
                },
            ));
        }
        let mut body = vec![0u8; size - BASE_HEADER_LEN];
        let got = read_full(&mut self.reader, &mut body)?;
        if got < body.len() {
            return Err(fail(
                at,
                BinaryError::Truncated {
                    needed: size as u64,
                    found: (BASE_HEADER_LEN + got) as u64,
                },
            ));
        }
        // Padding after a top-level object: size % 4 bytes (Vector's and
        // python-can's writers); the end of the file may come first.
        let padding = size % 4;
        let mut pad = [0u8; 3];
        let got_pad = read_full(&mut self.reader, pad.get_mut(..padding).unwrap_or_default())?;
        self.file_offset = at + size as u64 + got_pad as u64;
        if kind != object::LOG_CONTAINER {
            // An object outside any container: into the stream as it is.
            let mut whole = Vec::with_capacity(size);
            whole.extend_from_slice(&header);
            whole.extend_from_slice(&body);
            return Ok(Some(TopLevel::Bytes(whole)));
        }
        if body.len() < CONTAINER_HEADER_LEN {
            return Err(fail(
                at + 8,
                BinaryError::BadLength {
                    length: size as u64,
                },
            ));
        }
        let method = u16::from_le_bytes([body[0], body[1]]);
        let uncompressed = u32_le(&body, 8) as usize;
        if uncompressed > MAX_RECORD_LEN {
            return Err(fail(
                at + BASE_HEADER_LEN as u64 + 8,
                BinaryError::TooLarge {
                    length: uncompressed as u64,
                    limit: MAX_RECORD_LEN as u64,
                },
            ));
        }
        match method {
            0 => {
                body.drain(..CONTAINER_HEADER_LEN);
                Ok(Some(TopLevel::Bytes(body)))
            }
            2 => Ok(Some(TopLevel::Deflated {
                at,
                body,
                uncompressed,
            })),
            other => Err(fail(
                at + BASE_HEADER_LEN as u64,
                BinaryError::UnsupportedCompression {
                    method: u32::from(other),
                },
            )),
        }
    }

    /// The next object in the stream: `None` at the end.
    fn next_object(&mut self) -> Result<Option<Object>, LogError> {
        // Padding before an object: up to 7 bytes before `LOBJ`.
        if !self.fill(4)? {
            return self.end_of_stream();
        }
        let mut skipped = 0;
        while self.stream.get(self.pos..self.pos + 4) != Some(b"LOBJ") {
            if skipped == 7 || !self.fill(5)? {
                return if skipped == 7 {
                    Err(self.stream_fail(BinaryError::BadMagic {
                        found: u32_le(&self.stream, self.pos),
                    }))
                } else {
                    self.end_of_stream()
                };
            }
            self.pos += 1;
            skipped += 1;
        }
        if !self.fill(BASE_HEADER_LEN)? {
            return Err(self.truncated(BASE_HEADER_LEN));
        }
        let at = self.pos;
        let header_len = usize::from(u16_le(&self.stream, at + 4));
        let version = u16_le(&self.stream, at + 6);
        let size = u32_le(&self.stream, at + 8) as usize;
        let kind = u32_le(&self.stream, at + 12);
        if size > MAX_RECORD_LEN {
            return Err(self.stream_fail(BinaryError::TooLarge {
                length: size as u64,
                limit: MAX_RECORD_LEN as u64,
            }));
        }
        if size < BASE_HEADER_LEN || header_len > size {
            return Err(self.stream_fail(BinaryError::BadLength {
                length: size as u64,
            }));
        }
        if !self.fill(size)? {
            return Err(self.truncated(size));
        }
        // Filling may have moved the unread bytes to the front.
        let at = self.pos;
        self.number = self.number.saturating_add(1);
        let object = self.stream.get(at..at + size).unwrap_or_default();
        let outcome = match decode_object(object, kind, version, self.start) {
            Ok(Some(frame)) => Object::Frame(frame),
            Ok(None) => {
                self.other.add(OtherRecord::BlfObject(kind));
                Object::Other
            }
            // The object's size is known: report it, go on after it.
            Err(reason) => Object::Bad(FormatError::Binary {
                format: LogFormat::Blf,
                offset: self.stream_base + self.pos as u64,
                reason,
            }),
        };
        self.pos = at + size;
        Ok(Some(outcome))
    }

    fn end_of_stream(&self) -> Result<Option<Object>, LogError> {
        // Nothing but padding may be left.
        let rest = self.stream.get(self.pos..).unwrap_or_default();
        if rest.iter().all(|&b| b == 0) {
            Ok(None)
        } else {
            Err(self.truncated(BASE_HEADER_LEN))
        }
    }

    fn truncated(&self, needed: usize) -> LogError {
        self.stream_fail(BinaryError::Truncated {
            needed: needed as u64,
            found: (self.stream.len() - self.pos) as u64,
        })
    }

    fn stream_fail(&self, reason: BinaryError) -> LogError {
        fail(self.stream_base + self.pos as u64, reason)
    }
}

crate::logs::record::records_of!(BlfReader<R: Read>);

impl<R: Read> ReadLog for BlfReader<R> {
    fn format(&self) -> LogFormat {
        LogFormat::Blf
    }

    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        loop {
            if self.done {
                return None;
            }
            match self.next_object() {
                Ok(Some(Object::Frame(frame))) => {
                    return Some(Ok(LogRecord {
                        position: Position::Record(self.number),
                        event: LogEvent::Frame(frame),
                    }))
                }
                Ok(Some(Object::Other)) => continue,
                Ok(Some(Object::Bad(error))) => {
                    self.bad += 1;
                    return Some(Err(LogError::new(
                        Some(Position::Record(self.number)),
                        LogErrorKind::Malformed(error),
                    )));
                }
                Ok(None) => {
                    self.done = true;
                    return None;
                }
                Err(e) => {
                    self.done = true;
                    return Some(Err(e.or_at(Position::Record(self.number + 1))));
                }
            }
        }
    }

    fn other_records(&self) -> u64 {
        self.other.total()
    }

    fn other_kinds(&self) -> &[OtherRecords] {
        self.other.by_kind()
    }

    fn skipped(&self) -> u64 {
        self.bad
    }

    fn bytes_read(&self) -> u64 {
        self.file_offset
    }
}

/// Decode one object (`LOBJ` header included): a frame, or `None` for a
/// type that holds none.
fn decode_object(
    object: &[u8],
    kind: u32,
    version: u16,
    start: Timestamp,
) -> Result<Option<LogFrame<'static>>, BinaryError> {
    let header_len = match version {
        1 => BASE_HEADER_LEN + V1_HEADER_LEN,
        2 => BASE_HEADER_LEN + V2_HEADER_LEN,
        // An unknown header version: nothing can be read from it.
        _ => return Ok(None),
    };
    if !matches!(
        kind,
        object::CAN_MESSAGE
            | object::CAN_MESSAGE2
            | object::CAN_FD_MESSAGE
            | object::CAN_FD_MESSAGE_64
            | object::CAN_ERROR_EXT
    ) {
        return Ok(None);
    }
    if object.len() < header_len {
        return Err(BinaryError::BadLength {
            length: object.len() as u64,
        });
    }
    let flags = u32_le(object, BASE_HEADER_LEN);
    let time = u64_le(object, BASE_HEADER_LEN + 8);
    let offset = if flags == 1 {
        // Units of 10 µs.
        core::time::Duration::from_micros(time.saturating_mul(10))
    } else {
        core::time::Duration::from_nanos(time)
    };
    let timestamp = start.checked_add(offset).unwrap_or(start);
    let body = object.get(header_len..).unwrap_or_default();
    let need = |len: usize| {
        if body.len() < len {
            Err(BinaryError::BadLength {
                length: object.len() as u64,
            })
        } else {
            Ok(())
        }
    };
    let (channel, frame, direction) = match kind {
        object::CAN_MESSAGE | object::CAN_MESSAGE2 => {
            need(16)?;
            let channel = u16_le(body, 0);
            let msg_flags = body[2];
            let dlc = body[3];
            let (id, extended) = id_of(u32_le(body, 4));
            let id = can_id(id, extended)?;
            let frame = if msg_flags & 0x80 != 0 {
                CanFrame::new_remote(id, dlc.min(CLASSIC_MAX_LEN as u8))
            } else {
                let len = usize::from(dlc).min(CLASSIC_MAX_LEN);
                CanFrame::new(id, body.get(8..8 + len).unwrap_or_default())
            };
            (channel, frame, tx(msg_flags & 0x01 != 0))
        }
        object::CAN_FD_MESSAGE => {
            need(84)?;
            let channel = u16_le(body, 0);
            let msg_flags = body[2];
            let dlc = body[3] & 0x0F;
            let (id, extended) = id_of(u32_le(body, 4));
            let id = can_id(id, extended)?;
            let fd_flags = body[13];
            let valid = usize::from(body[14]).min(FD_MAX_LEN);
            let stored = body.get(20..84).unwrap_or_default();
            let frame = frame_of(
                id,
                msg_flags & 0x80 != 0,
                fd_flags & 0x1 != 0,
                fd_flags & 0x2 != 0,
                fd_flags & 0x4 != 0,
                dlc,
                valid,
                stored,
            );
            (channel, frame, tx(msg_flags & 0x01 != 0))
        }
        object::CAN_FD_MESSAGE_64 => {
            need(40)?;
            let channel = u16::from(body[0]);
            let dlc = body[1] & 0x0F;
            let valid = usize::from(body[2]).min(FD_MAX_LEN);
            let (id, extended) = id_of(u32_le(body, 4));
            let id = can_id(id, extended)?;
            let fd_flags = u32_le(body, 12);
            let direction = body[34];
            let ext_offset = usize::from(body[35]);
            // The data run up to the extended data (or the object's end).
            let data_end = if ext_offset != 0 {
                ext_offset
            } else {
                object.len()
            };
            let room = data_end.saturating_sub(header_len + 40);
            let stored = body.get(40..40 + room.min(valid)).unwrap_or_default();
            let frame = frame_of(
                id,
                fd_flags & 0x0010 != 0,
                fd_flags & 0x1000 != 0,
                fd_flags & 0x2000 != 0,
                fd_flags & 0x4000 != 0,
                dlc,
                valid,
                stored,
            );
            (channel, frame, tx(direction != 0))
        }
        _ => {
            // CAN_ERROR_EXT: channel, length, flags, ECC, position, DLC, …
            need(16)?;
            let channel = u16_le(body, 0);
            let (data, sent) = error_ext(u32_le(body, 4), body[8]);
            let classes = ErrorClasses::BUS_ERROR.union(ErrorClasses::PROTOCOL);
            (
                channel,
                CanFrame::new_error(classes.bits(), &data),
                sent.and_then(tx),
            )
        }
    };
    let frame = frame.map_err(|_| BinaryError::BadLength {
        length: object.len() as u64,
    })?;
    let mut logged = LogFrame::new(frame)
        .with_timestamp(timestamp)
        .with_iface(Iface::Channel(channel));
    logged.direction = direction;
    Ok(Some(logged))
}

/// `CAN_ERROR_EXT` flags bit 0: the error byte is an SJA1000 error code
/// capture register.
const ERROR_EXT_SJA1000: u32 = 0x1;
/// `CAN_ERROR_EXT` flags bit 1: the error byte is a Vector CAN-Core error
/// code.
const ERROR_EXT_CAN_CORE: u32 = 0x2;

/// Linux's error frame data (docs/formats.md#error-frames) of a
/// `CAN_ERROR_EXT` object's `flags` and error byte `ecc`, read as the
/// flags say (docs/formats.md#blf), and whether the error happened while
/// sending, where the byte says.
///
/// - SJA1000 (flags bit 0): bits 6–7 the type (bit, form, stuff, other),
///   bit 5 the direction (1: received), bits 0–4 the segment, Linux's
///   location code.
/// - Vector CAN-Core (flags bit 1, bit 0 clear): bits 0–5 the code (0 bit,
///   1 form, 2 stuff, 3 other, 4 CRC, 5 ACK delimiter error), bits 6–7
///   the direction (0 received, not acknowledged; 1 sent, not
///   acknowledged; 2 received; 3 sent). CRC and ACK delimiter errors are
///   Linux's locations 0x08 and 0x1B with an unspecified type.
/// - Neither: the byte means nothing; type and location unspecified.
fn error_ext(flags: u32, ecc: u8) -> ([u8; CLASSIC_MAX_LEN], Option<bool>) {
    let (error_type, location, sent) = if flags & ERROR_EXT_SJA1000 != 0 {
        let error_type = match ecc >> 6 {
            0 => 0x01, // bit error
            1 => 0x02, // form error
            2 => 0x04, // stuff error
            _ => 0x00, // other
        };
        (error_type, ecc & 0x1F, Some(ecc & 0x20 == 0))
    } else if flags & ERROR_EXT_CAN_CORE != 0 {
        let (error_type, location) = match ecc & 0x3F {
            0 => (0x01, 0x00), // bit error
            1 => (0x02, 0x00), // form error
            2 => (0x04, 0x00), // stuff error
            4 => (0x00, 0x08), // CRC error: the CRC sequence
            5 => (0x00, 0x1B), // ACK delimiter error
            _ => (0x00, 0x00), // other
        };
        (error_type, location, Some(ecc & 0x40 != 0))
    } else {
        (0x00, 0x00, None)
    };
    let mut data = [0u8; CLASSIC_MAX_LEN];
    data[2] = error_type | if sent == Some(true) { 0x80 } else { 0 };
    data[3] = location;
    (data, sent)
}

const fn tx(sent: bool) -> Option<Direction> {
    Some(if sent { Direction::Tx } else { Direction::Rx })
}

/// A frame from an FD object's fields: CAN FD when EDL is set (length: the
/// valid bytes), else classic (at most 8 bytes;
/// a remote request with the DLC). Stored bytes short of the valid count
/// are padded with zeros (docs/formats.md#blf).
#[allow(clippy::too_many_arguments)]
fn frame_of(
    id: CanId,
    remote: bool,
    edl: bool,
    brs: bool,
    esi: bool,
    dlc: u8,
    valid: usize,
    stored: &[u8],
) -> Result<CanFrame, crate::RangeError> {
    let mut data = [0u8; FD_MAX_LEN];
    let len = if edl {
        valid
    } else {
        valid.min(CLASSIC_MAX_LEN)
    };
    let copy = stored.len().min(len);
    data[..copy].copy_from_slice(&stored[..copy]);
    if edl {
        let mut flags = FdFlags::EMPTY;
        if brs {
            flags = flags.union(FdFlags::BRS);
        }
        if esi {
            flags = flags.union(FdFlags::ESI);
        }
        CanFrame::new_fd(id, flags, &data[..len])
    } else if remote {
        CanFrame::new_remote(id, dlc.min(CLASSIC_MAX_LEN as u8))
    } else {
        CanFrame::new(id, &data[..len])
    }
}

/// The identifier and whether bit 31 (`CAN_MSG_EXT`) marks it extended.
const fn id_of(raw: u32) -> (u32, bool) {
    (raw & 0x1FFF_FFFF, raw & 0x8000_0000 != 0)
}

fn can_id(raw: u32, extended: bool) -> Result<CanId, BinaryError> {
    let id = if extended {
        CanId::extended(raw)
    } else {
        CanId::standard(raw)
    };
    id.ok_or(BinaryError::BadIdentifier { raw })
}

/// A `SYSTEMTIME` (year, month, day of week, day, hour, minute, second,
/// milliseconds; little-endian `u16`s) at `at`, as UTC; zero when it is no
/// valid date (python-can does the same).
fn system_time(head: &[u8], at: usize) -> Timestamp {
    let field = |i: usize| u64::from(u16_le(head, at + 2 * i));
    let (year, month, day) = (field(0), field(1), field(3));
    let (hour, minute, second, millis) = (field(4), field(5), field(6), field(7));
    if !(1970..10_000).contains(&year)
        || !(1..=12).contains(&month)
        || day == 0
        || day > days_in_month(year, month)
        || hour > 23
        || minute > 59
        || second > 59
        || millis > 999
    {
        return Timestamp::ZERO;
    }
    let days = days_since_epoch(year, month, day);
    let secs = days * 86_400 + hour * 3_600 + minute * 60 + second;
    Timestamp::new(secs, (millis * 1000) as u32).unwrap_or(Timestamp::ZERO)
}

/// Read until `buf` is full or the input ends; the bytes read.
fn read_full<R: Read>(reader: &mut R, buf: &mut [u8]) -> io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match reader.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(n) => got += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

/// A [`FormatError::Binary`] as the [`LogError`] that ends the reading.
/// The error when the second thread stopped before giving back the
/// container at `at` (it does not, unless the system takes it away).
fn lost_thread(at: u64) -> LogError {
    LogError::from(io::Error::other(format!(
        "the thread inflating BLF containers stopped before the container at byte {at}"
    )))
}

fn fail(offset: u64, reason: BinaryError) -> LogError {
    LogError::new(
        None,
        LogErrorKind::Damaged(FormatError::Binary {
            format: LogFormat::Blf,
            offset,
            reason,
        }),
    )
}
