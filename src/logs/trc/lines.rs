//! A whole buffer, line by line.

use core::iter::FusedIterator;

use super::parser::TrcParser;
use crate::can::LogEvent;
use crate::logs::error::Result;
use crate::logs::{FormatError, Position};

/// Return an iterator over the lines of `buf` that parses each one with
/// one [`TrcParser`] (docs/formats.md#trc): it yields the line's
/// [`Position`] (docs/formats.md#positions) and what [`TrcParser::parse_line`] makes of the
/// line, so that a malformed line is reported with its number and the next one
/// is read on. Lines end at `\n` (a `\r` before it is ignored); a last line
/// without `\n` is read too.
///
/// ```
/// use motionwire::can::LogEvent;
/// use motionwire::logs::{trc, Position};
///
/// let log = b";$FILEVERSION=1.1\r\n;$STARTTIME=44548.6028595139\r\n\
///             1)  17535.4  Tx  00000100  2  00 01\r\n\
///             2)  17540.3  Warng  FFFFFFFF  4  00 00 00 08  BUSHEAVY\r\n\
///             3)  17541.0  Rx  0800  0\r\n";
/// let items: Vec<_> = trc::lines(log).collect();
/// assert_eq!(items.len(), 5);
/// assert_eq!(items[0], (Position::Line(1), Ok(None)));
/// let Ok(Some(LogEvent::Frame(frame))) = items[2].1 else { panic!() };
/// assert_eq!(frame.frame.data(), [0x00, 0x01]);
/// assert!(matches!(items[3].1, Ok(Some(LogEvent::Status(_)))));
/// assert_eq!(items[4].0, Position::Line(5));
/// assert!(items[4].1.is_err()); // 0x800 is no standard identifier
/// ```
#[must_use]
pub fn lines(buf: &[u8]) -> TrcLines<'_> {
    TrcLines {
        rest: buf,
        line_number: 0,
        parser: TrcParser::new(),
    }
}

/// The iterator of [`lines`].
#[derive(Debug, Clone)]
pub struct TrcLines<'a> {
    rest: &'a [u8],
    line_number: u64,
    parser: TrcParser,
}

impl<'a> TrcLines<'a> {
    /// Return the parser with the state the lines read so far set.
    #[must_use]
    pub const fn parser(&self) -> &TrcParser {
        &self.parser
    }

    /// Return the part of the buffer not read yet.
    #[must_use]
    pub const fn remainder(&self) -> &'a [u8] {
        self.rest
    }
}

impl<'a> Iterator for TrcLines<'a> {
    type Item = (Position, Result<Option<LogEvent<'a>>, FormatError>);

    fn next(&mut self) -> Option<Self::Item> {
        let line = crate::logs::text::take_line(&mut self.rest)?;
        self.line_number += 1;
        Some((
            Position::Line(self.line_number),
            self.parser.parse_line(line),
        ))
    }
}

impl FusedIterator for TrcLines<'_> {}
