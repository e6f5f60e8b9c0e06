//! A whole buffer, line by line.

use core::iter::FusedIterator;

use super::fast::{parse_canonical_log, IfaceHint};
#[cfg(feature = "std")]
use super::frame::Head;
use super::frame::Parsed;
use super::parse::parse_general;
use crate::can::{FrameType, LogFrame, Timestamp, FD_MAX_LEN};
use crate::logs::error::Result;
use crate::logs::lex::{is_space, skip_space};
use crate::logs::text::take_line;
use crate::logs::{FormatError, Position};

/// Return an iterator over the lines of `buf` that parses each one
/// (docs/formats.md#candump-log, docs/formats.md#candump-screen): it yields the
/// line's [`Position`] (docs/formats.md#positions) and what
/// [`parse_line`](super::parse_line) makes of the line, so that a malformed line is reported
/// with its number and the next line is read on. Lines end at `\n` (a `\r`
/// before it is ignored); a last line without `\n` is read too.
///
/// ```
/// use motionwire::logs::{candump, Position};
///
/// let log = b"(1.000000) can0 701#05\r\n\n(1.000100) can0 0X1#00\n  can0  705   [1]  remote request\n";
/// let mut lines = candump::lines(log);
/// let (n, first) = lines.next().unwrap();
/// assert_eq!((n, first?.unwrap().frame.data()), (Position::Line(1), &[0x05][..]));
/// assert_eq!(lines.next().unwrap().0, Position::Line(2)); // blank: Ok(None)
/// let (n, bad) = lines.next().unwrap();
/// assert_eq!(n, Position::Line(3));
/// assert!(bad.is_err());
/// assert!(lines.next().unwrap().1?.unwrap().frame.is_rtr());
/// assert!(lines.next().is_none());
/// # Ok::<(), motionwire::logs::FormatError>(())
/// ```
///
/// After an error frame, the lines that `candump -e` prints to explain it
/// belong to the frame: they are `Ok(None)`, not malformed
/// (docs/formats.md#candump-screen). Such a line is one that is no frame, is
/// indented with a tab (can-utils `candump.c` writes `"\n\t"` before each) and
/// starts with one of can-utils' error class names (`lib.c`, `error_classes`:
/// `bus-off`, `controller-problem{rx-error-warning}`, …). Anything else is read
/// as any other line, so no frame and no malformed line is ever hidden.
///
/// ```
/// use motionwire::logs::candump;
///
/// let log = b"  can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME\n\
///             \tcontroller-problem{rx-error-warning}\n\
///             \terror-counter-tx-rx{{0}{0}}\n";
/// let frames: Vec<_> = candump::lines(log).map(|(_, r)| r.unwrap()).collect();
/// assert!(frames[0].unwrap().frame.is_error());
/// assert_eq!((frames[1], frames[2]), (None, None));
/// ```
#[inline]
#[must_use]
pub fn lines(buf: &[u8]) -> CandumpLines<'_> {
    lines_from(buf, LineState::default())
}

/// Return an iterator over the lines of `buf` as [`lines`] does, going on
/// from where the lines of an earlier buffer of the same log left off
/// ([`CandumpLines::state`]): for a log read in blocks.
#[inline]
#[must_use]
pub fn lines_from(buf: &[u8], state: LineState) -> CandumpLines<'_> {
    CandumpLines {
        rest: buf,
        line_number: 0,
        state,
        recent_ifaces: [(0, ""); 2],
        hint: IfaceHint::NONE,
    }
}

/// What the lines read so far mean for the next one: whether it may be an
/// explanation line of an error frame (`candump -e`), how relative
/// timestamps are read and, for `candump -t d`, the time they add up to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LineState {
    after_error_frame: bool,
    relative: RelativeTimestamps,
    /// `-t d`: the sum of the deltas read so far.
    elapsed: Timestamp,
}

impl LineState {
    /// The state at the start of a log whose relative timestamps (`candump -t
    /// d` or `-t z`, docs/formats.md#candump-relative-times) are read as
    /// `relative` says; see [`detect_relative_timestamps`].
    #[inline]
    #[must_use]
    pub const fn new(relative: RelativeTimestamps) -> Self {
        LineState {
            after_error_frame: false,
            relative,
            elapsed: Timestamp::ZERO,
        }
    }

    /// How relative timestamps are read.
    #[inline]
    #[must_use]
    pub const fn relative_timestamps(&self) -> RelativeTimestamps {
        self.relative
    }

    /// A frame's timestamp as the record's `ts`: relative ones are seconds
    /// since the first frame (`-t d`'s deltas accumulated).
    #[inline]
    fn resolve(&mut self, ts: Option<Timestamp>, relative: bool) -> Option<Timestamp> {
        match (ts, relative, self.relative) {
            (Some(delta), true, RelativeTimestamps::Delta) => {
                self.elapsed = self
                    .elapsed
                    .checked_add(delta.as_duration())
                    .unwrap_or(self.elapsed);
                Some(self.elapsed)
            }
            _ => ts,
        }
    }
}

/// What a relative timestamp `(000.000123)` counts
/// (docs/formats.md#candump-relative-times): `candump -t z` prints the time
/// since the first frame, `-t d` the time since the previous one, in the same
/// shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum RelativeTimestamps {
    /// Time since the first frame (`-t z`), taken as written.
    #[default]
    Zero,
    /// Time since the previous frame (`-t d`), accumulated.
    Delta,
}

/// Decide from the first (up to) 64 timestamped frames of `buf` whether its
/// relative timestamps are `-t z` or `-t d` (the decision in
/// docs/formats.md#candump-relative-times): times since the first frame never
/// decrease, deltas of real traffic do. A decrease means
/// [`RelativeTimestamps::Delta`]; 64 frames without one, or the whole log when
/// `complete`, mean [`RelativeTimestamps::Zero`] (also when the timestamps are
/// absolute, where the choice changes nothing, and when the first relative time
/// is not 0: both candump modes start at 0, so such a log is read as written).
/// `None` when `buf` is not `complete` and holds fewer than 64 timestamped
/// frames without a decrease: read more first.
///
/// ```
/// use motionwire::logs::candump::{detect_relative_timestamps, RelativeTimestamps};
///
/// let deltas = b"(000.000000) can0 081#00\n(000.001000) can0 081#00\n(000.000500) can0 081#00\n";
/// assert_eq!(detect_relative_timestamps(deltas, true), Some(RelativeTimestamps::Delta));
/// let zero = b"(000.000000) can0 081#00\n(000.001000) can0 081#00\n";
/// assert_eq!(detect_relative_timestamps(zero, true), Some(RelativeTimestamps::Zero));
/// assert_eq!(detect_relative_timestamps(zero, false), None);
/// ```
#[must_use]
pub fn detect_relative_timestamps(buf: &[u8], complete: bool) -> Option<RelativeTimestamps> {
    const FRAMES: usize = 64;
    let mut seen = 0;
    let mut last: Option<Timestamp> = None;
    for line in buf.split(|&b| b == b'\n') {
        let Ok(Some(frame)) = parse_general(line) else {
            continue;
        };
        let Some(ts) = frame.timestamp else { continue };
        if !frame.relative {
            return Some(RelativeTimestamps::Zero);
        }
        if last.is_none() && ts != Timestamp::ZERO {
            // Both -t d and -t z print 0 for the first frame: a log whose
            // first time is not 0 did not start there, and its times are
            // read as written.
            return Some(RelativeTimestamps::Zero);
        }
        if last.is_some_and(|last| ts < last) {
            return Some(RelativeTimestamps::Delta);
        }
        last = Some(ts);
        seen += 1;
        if seen == FRAMES {
            return Some(RelativeTimestamps::Zero);
        }
    }
    complete.then_some(RelativeTimestamps::Zero)
}

/// The iterator of [`lines`].
#[derive(Debug, Clone)]
pub struct CandumpLines<'a> {
    rest: &'a [u8],
    line_number: u64,
    state: LineState,
    /// The interface names of the last frames, from the buffer, with their
    /// keys: the last frame's, then the one before it that differs.
    recent_ifaces: [(u64, &'a str); 2],
    /// The interface of the last line the fast path read.
    hint: IfaceHint,
}

impl<'a> Iterator for CandumpLines<'a> {
    type Item = (Position, Result<Option<LogFrame<'a>>, FormatError>);

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        if self.rest.is_empty() {
            return None;
        }
        self.line_number += 1;
        let recent = &mut self.recent_ifaces;
        let parsed = next_parsed(&mut self.rest, &mut self.state, &mut self.hint, |f| {
            f.into_log_frame_after(recent)
        });
        Some((Position::Line(self.line_number), parsed))
    }
}

impl<'a> CandumpLines<'a> {
    /// Return what the lines read so far mean for the next one, to go on
    /// with [`lines_from`] in the next buffer.
    #[inline]
    #[must_use]
    pub fn state(&self) -> LineState {
        self.state
    }

    /// Return the part of the buffer not read yet.
    #[inline]
    #[must_use]
    pub fn remainder(&self) -> &'a [u8] {
        self.rest
    }
}

/// Read the line at the start of `rest` and take it off (with its `\n`),
/// with the state the lines before it set: the one step of [`CandumpLines`]
/// and of the reader. The canonical `candump -l` shape is read by the fast
/// path straight from the buffer; any other line is found first. A frame
/// is handed on as `convert` makes it, on each path apart, so that it is
/// built once where the caller reads it instead of copied from one path's
/// result to the other's.
#[inline(always)]
pub(super) fn next_parsed<'a, T>(
    rest: &mut &'a [u8],
    state: &mut LineState,
    hint: &mut IfaceHint,
    convert: impl FnOnce(Parsed<'a>) -> T,
) -> Result<Option<T>> {
    let mut data = [0; FD_MAX_LEN];
    if let Some((frame, used)) = parse_canonical_log(rest, &mut data, hint) {
        *rest = rest.get(used..).unwrap_or_default();
        state.after_error_frame = false;
        return Ok(Some(convert(frame.with_data(data))));
    }
    next_general(rest, state).map(|frame| frame.map(convert))
}

/// [`next_parsed`] with the frame's data bytes written into `data` (zeros
/// on entry) and the rest of the frame returned: for a caller that keeps
/// the bytes itself (the reader), so that they are copied once, where the
/// frame is read.
#[cfg(feature = "std")]
#[inline(always)]
pub(super) fn next_head<'a>(
    rest: &mut &'a [u8],
    state: &mut LineState,
    hint: &mut IfaceHint,
    data: &mut [u8; FD_MAX_LEN],
) -> Result<Option<Head<'a>>> {
    if let Some((frame, used)) = parse_canonical_log(rest, data, hint) {
        *rest = rest.get(used..).unwrap_or_default();
        state.after_error_frame = false;
        return Ok(Some(frame.head()));
    }
    // The general parser interns its line's name without the hint: the
    // next line of the fast path reads its name again.
    *hint = IfaceHint::NONE;
    next_general_head(rest, state, data)
}

/// [`next_head`] for a line that is not in the canonical log shape: the
/// general parser out of line, its frame taken apart here, so that the two
/// paths meet with the frame's fields in registers, not in memory.
#[cfg(feature = "std")]
#[inline(always)]
fn next_general_head<'a>(
    rest: &mut &'a [u8],
    state: &mut LineState,
    data: &mut [u8; FD_MAX_LEN],
) -> Result<Option<Head<'a>>> {
    next_general(rest, state).map(|frame| frame.map(|frame| frame.into_head(data)))
}

/// [`next_parsed`] for a line that is not in the canonical log shape.
#[inline(never)]
pub(super) fn next_general<'a>(
    rest: &mut &'a [u8],
    state: &mut LineState,
) -> Result<Option<Parsed<'a>>> {
    let line = take_line(rest).unwrap_or_default();
    let parsed = parse_general(line);
    if parsed.is_err() && state.after_error_frame && is_explanation(line) {
        return Ok(None);
    }
    state.after_error_frame = matches!(
        parsed,
        Ok(Some(Parsed {
            kind: FrameType::Error,
            ..
        }))
    );
    parsed.map(|frame| {
        frame.map(|mut f| {
            if f.relative {
                f.timestamp = state.resolve(f.timestamp, true);
            }
            f
        })
    })
}

impl FusedIterator for CandumpLines<'_> {}

/// can-utils' names of the error classes, with which every explanation line
/// of `candump -e` starts (`lib.c`, `error_classes`, in class-bit order).
const EXPLANATION_WORDS: [&[u8]; 10] = [
    b"tx-timeout",
    b"lost-arbitration",
    b"controller-problem",
    b"protocol-violation",
    b"transceiver-status",
    b"no-acknowledgement-on-tx",
    b"bus-off",
    b"bus-error",
    b"restarted-after-bus-off",
    b"error-counter-tx-rx",
];

/// Whether `line` looks like an explanation line of `candump -e`: a tab in
/// its indentation, then an error class name up to `{`, white space or the
/// end of the line.
#[cold]
pub(super) fn is_explanation(line: &[u8]) -> bool {
    let start = skip_space(line, 0);
    let (indent, text) = line.split_at(start.min(line.len()));
    let word_end = text
        .iter()
        .position(|&b| b == b'{' || is_space(b) || b == b'\r')
        .unwrap_or(text.len());
    let word = text.get(..word_end).unwrap_or_default();
    indent.contains(&b'\t') && EXPLANATION_WORDS.contains(&word)
}
