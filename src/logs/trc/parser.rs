//! The reader of TRC lines: [`TrcParser`].

use crate::can::{LogEvent, Timestamp};
use crate::logs::error::Result;
use crate::logs::lex::{is_space, trim_end};
use crate::logs::FormatError;

use super::header::{parse_header, HeaderKey, Layout, TrcVersion};
use super::row::{parse_row, Context};

/// A reader of TRC lines: the state the header sets (file version, start
/// time, column order) and the rows read in it (docs/formats.md#trc; see the
/// module's decisions).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct TrcParser {
    pub(super) version: TrcVersion,
    pub(super) start: Option<Timestamp>,
    pub(super) layout: Option<Layout>,
}

impl TrcParser {
    /// Return a parser for a file that has not said anything yet: version
    /// 1.0, no start time.
    #[must_use]
    pub const fn new() -> Self {
        TrcParser {
            version: TrcVersion::V1_0,
            start: None,
            layout: None,
        }
    }

    /// Return the version `;$FILEVERSION=` set (1.0 until it does).
    #[must_use]
    pub const fn version(&self) -> TrcVersion {
        self.version
    }

    /// Return the start time `;$STARTTIME=` set.
    #[must_use]
    pub const fn start_time(&self) -> Option<Timestamp> {
        self.start
    }

    /// Parse one line (a trailing `\n` or `\r\n` is allowed). Return
    /// `Ok(None)` for a blank, comment or header line (header keys set the
    /// parser's state), a [`LogEvent::Frame`] or [`LogEvent::Status`] for a
    /// row, and a [`FormatError::Syntax`] with the column
    /// and reason for anything else.
    #[inline]
    pub fn parse_line(&mut self, line: &[u8]) -> Result<Option<LogEvent<'static>>, FormatError> {
        let trimmed = trim_end(line);
        let Some(first) = trimmed.iter().position(|&b| !is_space(b)) else {
            return Ok(None);
        };
        if trimmed.get(first) == Some(&b';') {
            match parse_header(trimmed, first)? {
                Some(HeaderKey::Version(version)) => self.version = version,
                Some(HeaderKey::StartTime(start)) => self.start = Some(start),
                Some(HeaderKey::Columns(layout)) => self.layout = Some(layout),
                None => {}
            }
            return Ok(None);
        }
        let ctx = Context {
            version: self.version,
            start: self.start.unwrap_or(Timestamp::ZERO),
            layout: self.layout.unwrap_or_else(|| self.version.default_layout()),
        };
        parse_row(trimmed, &ctx).map(Some)
    }
}
