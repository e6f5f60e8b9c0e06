//! A candump log read from a [`Read`] (std): the line layer's blocks,
//! parsed where they lie.

use std::io::Read;

use super::fast::IfaceHint;
use super::frame::Head;
use super::lines::{is_explanation, next_head};
use super::{detect_relative_timestamps, parse_line, LineState, RelativeTimestamps};
use crate::can::LogEvent;
use crate::can::FD_MAX_LEN;
use crate::logs::error::Result;
use crate::logs::text::{Names, TextLog, TextParser};
use crate::logs::{LogError, LogFormat, LogRecord, Position, ReadLog};

/// A reader of candump logs and screen output (docs/formats.md#candump-log,
/// docs/formats.md#candump-screen) from any [`Read`]: whole lines a block at a
/// time (256 KiB), each parsed where it lies in the block — what [`lines`](super::lines)
/// does for a buffer, for an input of any length, with the rules of
/// docs/formats.md#reported (see [`ReadLog`]).
///
/// Relative timestamps (`candump -t d` or `-t z`) are read as
/// [`detect_relative_timestamps`] decides from the first 64 frames (or the
/// first 64 KiB, or the whole input when it is shorter), unless
/// [`CandumpReader::with_relative_timestamps`] says; a live stream waits
/// for those frames before its first event. Interface names are kept once
/// in the reader: every event of `can0` names it with the same `&str`.
///
/// ```
/// use motionwire::can::Iface;
/// use motionwire::logs::candump::CandumpReader;
/// use motionwire::logs::{Position, ReadLog};
///
/// let log = b"(000.000000) can0 701#05\n# a comment\n(000.250000) can0 701#05\n(000.100000) can0 0X1#00\n(000.100000) can0 701#05\n";
/// let mut reader = CandumpReader::new(&log[..]);
/// let first = reader.next_event().unwrap()?;
/// assert_eq!(first.position, Position::Line(1));
/// assert_eq!(first.event.iface(), Some(Iface::Name("can0")));
/// let second = reader.next_event().unwrap()?;
/// assert_eq!(second.position, Position::Line(3));
/// // Line 4 is malformed: reported with its position, and the reading goes on.
/// let bad = reader.next_event().unwrap().unwrap_err();
/// assert_eq!((bad.position(), bad.is_skipped()), (Some(Position::Line(4)), true));
/// // `-t d`: the times decrease, so they are deltas, and add up.
/// let last = reader.next_event().unwrap()?;
/// assert_eq!(last.event.timestamp().unwrap().as_duration().as_millis(), 350);
/// assert!(reader.next_event().is_none());
/// # Ok::<(), motionwire::logs::LogError>(())
/// ```
#[derive(Debug)]
pub struct CandumpReader<R> {
    log: TextLog<R, Candump>,
}

impl<R: Read> CandumpReader<R> {
    /// Return a reader of `input`; nothing is read yet.
    #[must_use]
    pub fn new(input: R) -> Self {
        CandumpReader {
            log: TextLog::new(
                input,
                Candump {
                    state: LineState::default(),
                    decided: false,
                    hint: IfaceHint::NONE,
                },
            ),
        }
    }

    /// Return a reader of `input` whose relative timestamps count as
    /// `relative` says (`--timestamps delta|zero`,
    /// docs/formats.md#candump-relative-times), without looking at the first
    /// frames.
    #[must_use]
    pub fn with_relative_timestamps(input: R, relative: RelativeTimestamps) -> Self {
        CandumpReader {
            log: TextLog::new(
                input,
                Candump {
                    state: LineState::new(relative),
                    decided: true,
                    hint: IfaceHint::NONE,
                },
            ),
        }
    }

    /// Return how relative timestamps are read: as given, or as decided
    /// from the first frames (`None` until then).
    #[must_use]
    pub fn relative_timestamps(&self) -> Option<RelativeTimestamps> {
        let parser = self.log.parser();
        parser.decided.then(|| parser.state.relative_timestamps())
    }
}

crate::logs::record::records_of!(CandumpReader<R: Read>);

impl<R: Read> ReadLog for CandumpReader<R> {
    fn format(&self) -> LogFormat {
        LogFormat::Candump
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

/// candump's line parser as the line layer drives it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candump {
    state: LineState,
    /// The relative timestamps are decided (or were given).
    decided: bool,
    /// The interface of the last line the fast path read.
    hint: IfaceHint,
}

impl TextParser for Candump {
    /// The frame line without its data bytes, which the parser leaves in
    /// the reader's [`Names`].
    type Line<'t> = Head<'t>;

    #[inline(always)]
    fn next_line<'t>(
        &mut self,
        rest: &mut &'t [u8],
        names: &mut Names,
    ) -> Result<Option<Head<'t>>> {
        names.data = [0; FD_MAX_LEN];
        let parsed = next_head(rest, &mut self.state, &mut self.hint, &mut names.data);
        if let Ok(Some(head)) = &parsed {
            // A name the last line interned is there already.
            if !head.same_iface {
                names.intern(head.iface);
            }
        }
        parsed
    }

    #[inline(always)]
    fn record<'a>(line: Head<'_>, position: Position, names: &'a Names) -> LogRecord<'a> {
        LogRecord {
            position,
            event: LogEvent::Frame(line.into_log_frame_with(&names.data, names.last())),
        }
    }

    fn holds_nothing(&self, line: &[u8]) -> bool {
        // An explanation line holds nothing after an error frame, and is
        // malformed elsewhere: counted as nothing, the only cost is a later
        // flush of a live stream's output.
        matches!(parse_line(line), Ok(None)) || is_explanation(line)
    }

    fn prepare(&mut self, text: &[u8], complete: bool) -> bool {
        if !self.decided {
            match detect_relative_timestamps(text, complete) {
                Some(relative) => {
                    self.state = LineState::new(relative);
                    self.decided = true;
                }
                None => return false,
            }
        }
        true
    }
}
