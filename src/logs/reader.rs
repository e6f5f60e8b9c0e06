//! One way to read any log (docs/formats.md#detection, docs/formats.md#gzip):
//! the format detected from the content, a gzip stream inflated, and the
//! format's reader behind one type.

use std::fmt;
use std::fs::File;
use std::io::{self, Cursor, Read};
use std::path::Path;

use crate::logs::asc::AscReader;
use crate::logs::blf::BlfReader;
use crate::logs::candump::{CandumpReader, RelativeTimestamps};
use crate::logs::mf4::{self, Mf4Reader};
use crate::logs::pcap::PcapReader;
use crate::logs::trc::TrcReader;
use crate::logs::{
    detect, Detected, LogError, LogErrorKind, LogFormat, LogRecord, ReadLog, DETECT_LEN,
};

/// What every reader of a [`LogReader`] reads from.
type Input = Box<dyn Read + Send>;

/// Open the log file at `path` and read it as [`read`] does: the format
/// detected from the content, gzip inflated.
///
/// # Errors
///
/// As [`read`]; the file cannot be opened: [`LogErrorKind::Io`].
///
/// ```
/// use motionwire::can::Iface;
/// use motionwire::logs::{self, LogFormat, Position, ReadLog};
///
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/blf/python_can.blf");
/// let mut log = logs::open(path)?;
/// assert_eq!(log.format(), LogFormat::Blf);
/// let first = log.next_event().unwrap()?;
/// assert_eq!(first.position, Position::Record(1));
/// assert_eq!(first.event.iface(), Some(Iface::Channel(1)));
/// let mut frames = 1;
/// while let Some(record) = log.next_event() {
///     record?;
///     frames += 1;
/// }
/// assert_eq!((frames, log.other_records()), (39, 0));
///
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/pcap/multi.pcapng");
/// let mut log = logs::open(path)?;
/// assert_eq!(log.format(), LogFormat::Pcapng);
/// let first = log.next_event().unwrap()?;
/// assert_eq!(first.event.iface(), Some(Iface::Name("can0")));
/// // pcapng: packets of other link types are counted, not handed on.
/// while let Some(record) = log.next_event() {
///     record?;
/// }
/// assert_eq!(log.other_records(), 1);
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
pub fn open(path: impl AsRef<Path>) -> Result<LogReader, LogError> {
    ReadOptions::new().open(path)
}

/// Read a log of any format of docs/formats.md from `input`: the format is
/// detected from the content ([`detect`]), a gzip stream is inflated
/// (once: a gzip inside a gzip is no log), and the format's reader hands
/// on the events ([`LogReader`], a [`ReadLog`]). An input of nothing but
/// blank and comment lines (`#`, `;`, `//`) reads as an empty candump log.
///
/// Reading starts with what detection needs (up to [`DETECT_LEN`] bytes,
/// less when the input pauses: a live stream is decided on its first
/// lines); nothing is read twice.
///
/// # Errors
///
/// [`LogErrorKind::Unrecognised`] when the input is none of the formats
/// (one error, not one per line); [`LogErrorKind::Damaged`] when a binary
/// log's header is damaged; [`LogErrorKind::Io`] when reading fails.
///
/// ```
/// use motionwire::can::Iface;
/// use motionwire::logs::{self, LogErrorKind, LogFormat, Position, ReadLog};
///
/// let text: &[u8] = b"(1700000000.000500) can0 081#1081110000000000\n\
///                     (1700000000.000600) can0 0X1#00\n\
///                     (1700000000.000700) can0 705#05\n";
/// let mut log = logs::read(text)?;
/// assert_eq!(log.format(), LogFormat::Candump);
/// let first = log.next_event().unwrap()?;
/// assert_eq!(first.position, Position::Line(1));
/// let frame = first.event.frame().unwrap();
/// assert_eq!(frame.frame.id().raw(), 0x081);
/// assert_eq!(frame.iface, Some(Iface::Name("can0")));
///
/// // A malformed line is reported with its position, and the reading goes on.
/// let error = log.next_event().unwrap().unwrap_err();
/// assert!(error.is_skipped());
/// assert_eq!(error.position(), Some(Position::Line(2)));
/// assert_eq!(
///     error.to_string(),
///     "line 2: candump line, column 27: expected a CAN identifier of 3 or 8 hex digits \
///      followed by '#' or white space, found 'X'"
/// );
/// assert_eq!(log.next_event().unwrap()?.position, Position::Line(3));
/// assert!(log.next_event().is_none());
/// assert_eq!(log.skipped(), 1);
///
/// // Anything else is one clear error.
/// let error = logs::read(&b"Hello, world!\n"[..]).unwrap_err();
/// assert!(matches!(error.kind(), LogErrorKind::Unrecognised));
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
pub fn read<R: Read + Send + 'static>(input: R) -> Result<LogReader, LogError> {
    ReadOptions::new().read(input)
}

/// How [`ReadOptions::read`] and [`ReadOptions::open`] read a log where the
/// defaults of [`read`] do not fit: the format forced (`--format`,
/// docs/formats.md#detection), candump's relative timestamps given
/// (`--timestamps`, docs/formats.md#candump-relative-times).
///
/// ```
/// use motionwire::logs::candump::RelativeTimestamps;
/// use motionwire::logs::{LogFormat, ReadLog, ReadOptions};
///
/// // `candump -t z`: without the option, the decreasing times would be
/// // read as `-t d`'s deltas.
/// let text: &[u8] = b"(000.000000) can0 705#05\n(000.250000) can0 705#05\n(000.100000) can0 705#05\n";
/// let options = ReadOptions::new()
///     .format(LogFormat::Candump)
///     .relative_timestamps(RelativeTimestamps::Zero);
/// let mut log = options.read(text)?;
/// let mut times = Vec::new();
/// while let Some(record) = log.next_event() {
///     times.push(record?.event.timestamp().unwrap().to_string());
/// }
/// assert_eq!(times, ["0000000000.000000", "0000000000.250000", "0000000000.100000"]);
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ReadOptions {
    format: Option<LogFormat>,
    relative: Option<RelativeTimestamps>,
}

impl ReadOptions {
    /// Return the defaults: the format detected, relative timestamps
    /// decided from the first frames.
    #[must_use]
    pub const fn new() -> Self {
        ReadOptions {
            format: None,
            relative: None,
        }
    }

    /// Read the input as `format` whatever its content says (a gzip stream
    /// is still inflated first).
    #[must_use]
    pub const fn format(mut self, format: LogFormat) -> Self {
        self.format = Some(format);
        self
    }

    /// Read candump's relative timestamps (`(000.000123)`) as `relative`
    /// says instead of deciding from the first frames
    /// (docs/formats.md#candump-relative-times).
    #[must_use]
    pub const fn relative_timestamps(mut self, relative: RelativeTimestamps) -> Self {
        self.relative = Some(relative);
        self
    }

    /// Open the log file at `path` and read it as [`ReadOptions::read`]
    /// does.
    ///
    /// # Errors
    ///
    /// As [`ReadOptions::read`]; the file cannot be opened:
    /// [`LogErrorKind::Io`].
    pub fn open(&self, path: impl AsRef<Path>) -> Result<LogReader, LogError> {
        match mf4::Input::file(File::open(path)?, self.format)? {
            // MF4 is read in place, at any offset (docs/formats.md#mf4).
            Ok(file) => Ok(LogReader {
                inner: Inner::Mf4(Mf4Reader::new(file)?),
                gzip: false,
            }),
            Err(file) => self.read(file),
        }
    }

    /// Read a log from `input` as [`read`] does, with these options.
    ///
    /// # Errors
    ///
    /// As [`read`] ([`LogErrorKind::Unrecognised`] only when no format is
    /// forced).
    pub fn read<R: Read + Send + 'static>(&self, input: R) -> Result<LogReader, LogError> {
        let mut input: Input = Box::new(input);
        let mut gzip = false;
        loop {
            let mut head = Vec::with_capacity(4096);
            let detected = loop {
                let ended = fill(&mut input, &mut head, DETECT_LEN)?;
                match detect(&head, ended) {
                    Detected::NeedMore if !ended => continue,
                    // Inflating once is enough: a gzip inside a gzip is no log.
                    Detected::Gzip if gzip => break Detected::Unrecognised,
                    other => break other,
                }
            };
            // The reader starts again at the first byte.
            let head_len = head.len();
            let again: Input = Box::new(Cursor::new(head).chain(input));
            let format = match (detected, self.format) {
                (Detected::Gzip, _) => {
                    gzip = true;
                    input = Box::new(flate2::read::MultiGzDecoder::new(again));
                    continue;
                }
                (_, Some(format)) | (Detected::Format(format), None) => format,
                // Nothing but blank or comment lines (`#`, `;`, `//`):
                // nothing to read. The whole input: an empty candump log
                // (the lines are no one's frames: not reported). The first
                // DETECT_LEN bytes only: read on as candump, which takes
                // `#` comments.
                (Detected::Empty, None) => {
                    if head_len < DETECT_LEN {
                        let nothing: Input = Box::new(io::empty());
                        return Ok(LogReader {
                            inner: Inner::Candump(CandumpReader::new(nothing)),
                            gzip,
                        });
                    }
                    LogFormat::Candump
                }
                (Detected::NeedMore | Detected::Unrecognised, None) => {
                    return Err(LogError::new(None, LogErrorKind::Unrecognised))
                }
            };
            let inner = match format {
                LogFormat::Candump => Inner::Candump(match self.relative {
                    Some(relative) => CandumpReader::with_relative_timestamps(again, relative),
                    None => CandumpReader::new(again),
                }),
                LogFormat::Asc => Inner::Asc(AscReader::new(again)),
                LogFormat::Trc => Inner::Trc(TrcReader::new(again)),
                LogFormat::Pcap | LogFormat::Pcapng => Inner::Pcap(PcapReader::new(again)?),
                LogFormat::Blf => Inner::Blf(BlfReader::new(again)?),
                LogFormat::Mf4 => Inner::Mf4(Mf4Reader::new(mf4::Input::memory(again)?)?),
            };
            return Ok(LogReader { inner, gzip });
        }
    }
}

/// Read into `head` until it holds `want` bytes or the input ends; return
/// whether it ended. One read at a time, so that a live pipe is decided on
/// its first lines.
fn fill(reader: &mut Input, head: &mut Vec<u8>, want: usize) -> io::Result<bool> {
    let start = head.len();
    head.resize(want.max(start), 0);
    loop {
        match reader.read(head.get_mut(start..).unwrap_or_default()) {
            Ok(n) => {
                head.truncate(start + n.min(want - start));
                return Ok(n == 0);
            }
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => {
                head.truncate(start);
                return Err(e);
            }
        }
    }
}

/// A log of any format of docs/formats.md, read by its format's reader: what
/// [`open`] and [`read`] return. It is a [`ReadLog`] like each of them,
/// and adds what the dispatch knows: whether the input was gzip.
pub struct LogReader {
    inner: Inner,
    gzip: bool,
}

/// The format's reader: an enum, so that each event costs one predictable
/// branch rather than a call through a vtable.
enum Inner {
    Candump(CandumpReader<Input>),
    Asc(AscReader<Input>),
    Trc(TrcReader<Input>),
    Pcap(PcapReader<Input>),
    Blf(BlfReader<Input>),
    Mf4(Mf4Reader<mf4::Input>),
}

/// `$body` with `$reader` bound to the format's reader.
macro_rules! each {
    ($inner:expr, $reader:ident => $body:expr) => {
        match $inner {
            Inner::Candump($reader) => $body,
            Inner::Asc($reader) => $body,
            Inner::Trc($reader) => $body,
            Inner::Pcap($reader) => $body,
            Inner::Blf($reader) => $body,
            Inner::Mf4($reader) => $body,
        }
    };
}

impl LogReader {
    /// Return whether the input was a gzip stream, inflated while it is read
    /// (docs/formats.md#gzip).
    #[must_use]
    pub const fn is_gzip(&self) -> bool {
        self.gzip
    }

    /// Hand the format's own reader to `visitor`, so that its loop over
    /// the events is compiled for that reader's type.
    ///
    /// [`LogReader::next_event`](ReadLog::next_event) picks the format's
    /// reader at every call, and the event is written out to memory instead
    /// of staying where the parser put it: in a loop that does little with
    /// each event, that is a large part of the time (`benches/logs.rs`
    /// measures both loops; BENCHMARKS.md, "one way to read any log"). A
    /// visitor's loop is compiled for the format's reader and has no such
    /// cost.
    ///
    /// ```
    /// use motionwire::logs::{self, LogVisitor, ReadLog};
    ///
    /// /// The frames of a log, counted.
    /// struct CountFrames;
    ///
    /// impl LogVisitor for CountFrames {
    ///     type Output = u64;
    ///
    ///     fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> u64 {
    ///         let mut frames = 0;
    ///         while let Some(next) = log.next_event() {
    ///             if next.is_ok_and(|record| record.event.frame().is_some()) {
    ///                 frames += 1;
    ///             }
    ///         }
    ///         frames
    ///     }
    /// }
    ///
    /// let text: &[u8] = b"(1.000000) can0 705#05\n(1.100000) can0 705#05\n";
    /// assert_eq!(logs::read(text)?.visit(CountFrames), 2);
    /// # Ok::<(), motionwire::logs::LogError>(())
    /// ```
    pub fn visit<V: LogVisitor>(&mut self, visitor: V) -> V::Output {
        each!(&mut self.inner, reader => visit_one(visitor, reader))
    }
}

/// `visitor` over one format's reader, in a function of its own: each
/// format's loop is compiled apart, so that the code of one reader does
/// not change how another's loop is compiled.
#[inline(never)]
fn visit_one<V: LogVisitor, L: ReadLog>(visitor: V, log: &mut L) -> V::Output {
    visitor.visit(log)
}

/// Code that reads a log through whichever reader its format has, compiled
/// for each: see [`LogReader::visit`].
pub trait LogVisitor {
    /// What the visit returns.
    type Output;

    /// Read `log`, a [`LogReader`]'s reader of the log's format.
    fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> Self::Output;
}

crate::logs::record::records_of!(LogReader);

impl ReadLog for LogReader {
    fn format(&self) -> LogFormat {
        each!(&self.inner, reader => reader.format())
    }

    #[inline(always)]
    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        each!(&mut self.inner, reader => reader.next_event())
    }

    fn skipped(&self) -> u64 {
        each!(&self.inner, reader => reader.skipped())
    }

    fn other_records(&self) -> u64 {
        each!(&self.inner, reader => reader.other_records())
    }

    fn other_kinds(&self) -> &[crate::logs::OtherRecords] {
        each!(&self.inner, reader => reader.other_kinds())
    }

    fn bytes_read(&self) -> u64 {
        each!(&self.inner, reader => reader.bytes_read())
    }

    #[inline(always)]
    fn drained(&self) -> bool {
        each!(&self.inner, reader => reader.drained())
    }
}

impl fmt::Debug for LogReader {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("LogReader")
            .field("format", &self.format())
            .field("gzip", &self.gzip)
            .field("skipped", &self.skipped())
            .field("bytes_read", &self.bytes_read())
            .finish_non_exhaustive()
    }
}
