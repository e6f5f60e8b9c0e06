//! A Vector ASC log read from a [`Read`] (std).

use std::io::Read;

use super::AscParser;
use crate::can::LogEvent;
use crate::logs::text::{take_line, Names, TextLog, TextParser};
use crate::logs::{FormatError, LogError, LogFormat, LogRecord, Position, ReadLog};

/// A reader of Vector ASC logs (docs/formats.md#asc) from any [`Read`]: whole
/// lines a block at a time, each read by one [`AscParser`] where it lies, with
/// the rules of docs/formats.md#reported (see [`ReadLog`]).
///
/// ```
/// use motionwire::can::Iface;
/// use motionwire::logs::asc::AscReader;
/// use motionwire::logs::{Position, ReadLog};
///
/// let log = b"base hex  timestamps absolute\r\n   1.500000 1  701             Rx   d 1 05\r\n";
/// let mut reader = AscReader::new(&log[..]);
/// let record = reader.next_event().unwrap()?;
/// assert_eq!(record.position, Position::Line(2));
/// assert_eq!(record.event.iface(), Some(Iface::Channel(1)));
/// assert!(reader.next_event().is_none());
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
#[derive(Debug)]
pub struct AscReader<R> {
    log: TextLog<R, AscParser>,
}

impl<R: Read> AscReader<R> {
    /// Return a reader of `input`; nothing is read yet.
    #[must_use]
    pub fn new(input: R) -> Self {
        AscReader {
            log: TextLog::new(input, AscParser::new()),
        }
    }

    /// Return the parser, with the state the header read so far set.
    #[must_use]
    pub const fn parser(&self) -> &AscParser {
        self.log.parser()
    }
}

crate::logs::record::records_of!(AscReader<R: Read>);

impl<R: Read> ReadLog for AscReader<R> {
    fn format(&self) -> LogFormat {
        LogFormat::Asc
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

impl TextParser for AscParser {
    type Line<'t> = LogEvent<'static>;

    #[inline]
    fn next_line(
        &mut self,
        rest: &mut &[u8],
        _names: &mut Names,
    ) -> Result<Option<LogEvent<'static>>, FormatError> {
        // The common frame lines where they lie, the line's end found
        // from where the frame ends; every other line on its own.
        if let Some((event, len)) = self.parse_fast_in_place(rest) {
            *rest = rest.get(len..).unwrap_or_default();
            return Ok(Some(event));
        }
        self.parse_other(take_line(rest).unwrap_or_default())
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
