//! A PEAK TRC log read from a [`Read`] (std).

use std::io::Read;

use super::parser::TrcParser;
use crate::can::LogEvent;
use crate::logs::text::{take_line, Names, TextLog, TextParser};
use crate::logs::{FormatError, LogError, LogFormat, LogRecord, Position, ReadLog};

/// A reader of PEAK TRC logs (docs/formats.md#trc) from any [`Read`]: whole
/// lines a block at a time, each read by one [`TrcParser`] where it lies, with
/// the rules of docs/formats.md#reported (see [`ReadLog`]). Status rows are
/// [`LogEvent::Status`] events.
///
/// ```
/// use motionwire::can::LogEvent;
/// use motionwire::logs::trc::TrcReader;
/// use motionwire::logs::{Position, ReadLog};
///
/// let log = b";$FILEVERSION=1.1\r\n1)  17535.4  Tx  00000100  2  00 01\r\n2)  17540.3  Warng  FFFFFFFF  4  00 00 00 08  BUSHEAVY\r\n";
/// let mut reader = TrcReader::new(&log[..]);
/// let frame = reader.next_event().unwrap()?;
/// assert_eq!(frame.position, Position::Line(2));
/// assert!(matches!(reader.next_event().unwrap()?.event, LogEvent::Status(_)));
/// assert!(reader.next_event().is_none());
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
#[derive(Debug)]
pub struct TrcReader<R> {
    log: TextLog<R, TrcParser>,
}

impl<R: Read> TrcReader<R> {
    /// Return a reader of `input`; nothing is read yet.
    #[must_use]
    pub fn new(input: R) -> Self {
        TrcReader {
            log: TextLog::new(input, TrcParser::new()),
        }
    }

    /// Return the parser, with the state the header read so far set.
    #[must_use]
    pub const fn parser(&self) -> &TrcParser {
        self.log.parser()
    }
}

crate::logs::record::records_of!(TrcReader<R: Read>);

impl<R: Read> ReadLog for TrcReader<R> {
    fn format(&self) -> LogFormat {
        LogFormat::Trc
    }

    #[inline(always)]
    fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        self.log.next_event()
    }

    fn skipped(&self) -> u64 {
        self.log.skipped()
    }

    fn bytes_read(&self) -> u64 {
        self.log.bytes_read()
    }

    #[inline]
    fn drained(&self) -> bool {
        self.log.drained()
    }
}

impl TextParser for TrcParser {
    type Line<'t> = LogEvent<'static>;

    #[inline]
    fn next_line(
        &mut self,
        rest: &mut &[u8],
        _names: &mut Names,
    ) -> Result<Option<LogEvent<'static>>, FormatError> {
        self.parse_line(take_line(rest).unwrap_or_default())
    }

    #[inline]
    fn record<'a>(
        event: LogEvent<'static>,
        position: Position,
        _names: &'a Names,
    ) -> LogRecord<'a> {
        LogRecord { position, event }
    }

    fn holds_nothing(&self, line: &[u8]) -> bool {
        matches!(self.clone().parse_line(line), Ok(None))
    }
}
