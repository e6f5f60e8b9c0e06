//! The one line layer of the text readers (candump, ASC, TRC;
//! docs/formats.md#memory): a buffer split into lines at `\n` (16 bytes at a
//! time) and — with `std` — whole lines read from a [`std::io::Read`] a
//! block at a time, with the over-long-line rule that keeps memory bounded
//! whatever the input. The fields and numbers of a line are the lexical
//! layer's (`lex`).
//!
//! A line is the bytes before a `\n`, without it; a last line without one
//! counts too, nothing after a final `\n` does. A `\r` before the `\n`
//! (CRLF files) stays on the line: every format's parser reads it as
//! trailing white space. A NUL byte is an ordinary byte of its line, never
//! a line end: the format's parser reports the line as malformed, with the
//! column of the NUL, and the reading goes on with the next line.

#[cfg(feature = "std")]
use crate::can::Iface;
use crate::logs::lex::swar;

/// The lines of a text buffer, split at `\n` (16 bytes at a time), each
/// without its `\n`; a last line without one counts too, nothing after a
/// final `\n` does. What the line readers of the text formats are fed.
///
/// ```
/// let lines: Vec<&[u8]> = motionwire::logs::split_lines(b"a\r\nbc\n\nd").collect();
/// assert_eq!(lines, [&b"a\r"[..], b"bc", b"", b"d"]);
/// ```
#[must_use]
pub fn split_lines(buf: &[u8]) -> SplitLines<'_> {
    SplitLines { rest: buf }
}

/// The iterator of [`split_lines`].
#[derive(Debug, Clone)]
pub struct SplitLines<'a> {
    rest: &'a [u8],
}

impl<'a> Iterator for SplitLines<'a> {
    type Item = &'a [u8];

    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        take_line(&mut self.rest)
    }
}

impl core::iter::FusedIterator for SplitLines<'_> {}

/// Take the first line off `rest` (without its `\n`; `None` when `rest`
/// is empty): the one line splitter of the text readers.
#[inline]
pub(crate) fn take_line<'a>(rest: &mut &'a [u8]) -> Option<&'a [u8]> {
    if rest.is_empty() {
        return None;
    }
    let (line, after) = match find_newline(rest) {
        Some(i) => (
            rest.get(..i).unwrap_or_default(),
            rest.get(i + 1..).unwrap_or_default(),
        ),
        None => (*rest, &[][..]),
    };
    *rest = after;
    Some(line)
}

/// The index of the first `\n` in `buf`, 16 bytes at a time: each 16 bytes
/// are loaded as a `u128` and the lanes equal to `\n` found with wide-word
/// arithmetic (SWAR).
#[inline(always)]
pub(crate) fn find_newline(buf: &[u8]) -> Option<usize> {
    let mut chunks = buf.chunks_exact(16);
    let mut at = 0;
    for chunk in &mut chunks {
        let w = chunk
            .first_chunk::<16>()
            .map_or(0, |c| u128::from_le_bytes(*c));
        let hits = swar::first_eq(w, b'\n');
        if hits != 0 {
            return Some(at + (hits.trailing_zeros() / 8) as usize);
        }
        at += 16;
    }
    chunks
        .remainder()
        .iter()
        .position(|&b| b == b'\n')
        .map(|i| at + i)
}

/// The longest line a text reader holds (1 MiB). A longer one is not a log
/// line of any format: it is reported
/// ([`OverlongLine`](crate::logs::LogErrorKind::OverlongLine))
/// and skipped unread, so memory stays bounded whatever the input
/// (docs/formats.md#memory).
#[cfg(feature = "std")]
pub const MAX_LINE_LEN: usize = 1 << 20;

/// How much a text reader asks its input for at a time (256 KiB): lines
/// are parsed where they lie in the block, without a copy.
#[cfg(feature = "std")]
const BLOCK_LEN: usize = 1 << 18;

/// The most text a reader holds back while it decides how to read the log
/// (candump's relative timestamps, docs/formats.md#candump-relative-times): as
/// much as format detection looks at.
#[cfg(feature = "std")]
const HOLD_LEN: usize = crate::logs::DETECT_LEN;

/// The most interface names a reader keeps at a stable address (a log
/// names a handful); beyond it the table starts again.
#[cfg(feature = "std")]
const MAX_NAMES: usize = 256;

/// Whole lines of an input, a block at a time: [`BLOCK_LEN`], more for a
/// long line, at most [`MAX_LINE_LEN`] for one line; a longer line is
/// dropped up to its end and said in the next block.
#[cfg(feature = "std")]
#[derive(Debug)]
struct TextInput<R> {
    reader: R,
    buf: Vec<u8>,
    /// Bytes of `buf` read from the input.
    filled: usize,
    /// The block handed out: `buf[..text]`, whole lines.
    text: usize,
    /// Keep the block at the next call and hand it out again, with more.
    held: bool,
    /// The input has ended.
    at_end: bool,
    /// Dropping the rest of an over-long line.
    skipping: bool,
    /// Bytes taken from the input.
    bytes: u64,
}

/// What [`TextInput::next_block`] found, besides the block's text.
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy)]
struct BlockInfo {
    /// The read that ended the block took everything the input had
    /// buffered (it returned fewer bytes than asked): live use.
    drained: bool,
    /// The block holds the end of the input (its last line may lack its
    /// `\n`).
    at_end: bool,
    /// The buffer is full: no more text can join a held block.
    full: bool,
    /// An over-long line was skipped right before the block's text.
    overlong: bool,
}

#[cfg(feature = "std")]
impl<R: std::io::Read> TextInput<R> {
    fn new(reader: R) -> Self {
        TextInput {
            reader,
            buf: Vec::new(),
            filled: 0,
            text: 0,
            held: false,
            at_end: false,
            skipping: false,
            bytes: 0,
        }
    }

    /// The block handed out last.
    #[inline(always)]
    fn text(&self) -> &[u8] {
        self.buf.get(..self.text).unwrap_or_default()
    }

    /// Hand the last block out again, with more after it, at the next call.
    fn hold(&mut self) {
        self.held = true;
    }

    /// Read the next block of whole lines (all that is left at the end of
    /// the input); `None` when nothing is left.
    fn next_block(&mut self) -> std::io::Result<Option<BlockInfo>> {
        if !self.held {
            self.buf.copy_within(self.text..self.filled, 0);
            self.filled -= self.text;
            self.text = 0;
        }
        self.held = false;
        if self.at_end && self.filled == 0 {
            return Ok(None);
        }
        if self.buf.is_empty() {
            self.buf.resize(BLOCK_LEN, 0);
        }
        let mut info = BlockInfo {
            drained: false,
            at_end: false,
            full: false,
            overlong: false,
        };
        while !self.at_end {
            if self.filled == self.buf.len() {
                if self
                    .buf
                    .get(..self.filled)
                    .is_some_and(|b| b.contains(&b'\n'))
                {
                    // Held lines fill the buffer: hand them out as they are.
                    info.full = true;
                    break;
                }
                if self.buf.len() < MAX_LINE_LEN {
                    let len = (self.buf.len() * 2).min(MAX_LINE_LEN);
                    self.buf.resize(len, 0);
                } else {
                    // One line fills the largest buffer: drop it up to its
                    // end.
                    self.skipping = true;
                    self.filled = 0;
                }
            }
            let start = self.filled;
            let space = self.buf.get_mut(start..).unwrap_or_default();
            let room = space.len();
            let n = match self.reader.read(space) {
                // A reader that claims more than it was given is not believed.
                Ok(n) => n.min(room),
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            self.bytes += n as u64;
            self.filled += n;
            self.at_end = n == 0;
            info.drained = n < room && !self.at_end;
            let new = self.buf.get(start..self.filled).unwrap_or_default();
            if self.skipping {
                match new.iter().position(|&b| b == b'\n') {
                    Some(i) => {
                        self.buf.copy_within(start + i + 1..self.filled, 0);
                        self.filled -= start + i + 1;
                        self.skipping = false;
                        info.overlong = true;
                    }
                    None => {
                        self.filled = 0;
                        if self.at_end {
                            self.skipping = false;
                            info.overlong = true;
                        }
                        continue;
                    }
                }
                let rest = self.buf.get(..self.filled).unwrap_or_default();
                if rest.contains(&b'\n') || self.filled == 0 {
                    // Say the skipped line before waiting for more.
                    break;
                }
                continue;
            }
            if new.contains(&b'\n') {
                break;
            }
        }
        if self.at_end && self.filled == 0 && !info.overlong {
            return Ok(None);
        }
        let filled = self.buf.get(..self.filled).unwrap_or_default();
        self.text = if self.at_end {
            self.filled
        } else {
            filled
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |i| i + 1)
        };
        info.at_end = self.at_end;
        Ok(Some(info))
    }
}

/// The interface names a text reader's events borrow (candump: `can0`),
/// each kept once at a stable address, so that every event of one
/// interface names it with the same slice.
#[cfg(feature = "std")]
#[derive(Debug)]
pub(crate) struct Names {
    names: Vec<Box<str>>,
    /// The name of the last event.
    last: usize,
    /// The data bytes of the last event, for a parser that writes them here
    /// rather than into its line (candump): the record is built from them
    /// where the caller reads it, so that they are copied once.
    pub(crate) data: [u8; crate::can::FD_MAX_LEN],
}

#[cfg(feature = "std")]
impl Default for Names {
    fn default() -> Self {
        Names {
            names: Vec::new(),
            last: 0,
            data: [0; crate::can::FD_MAX_LEN],
        }
    }
}

#[cfg(feature = "std")]
impl Names {
    /// Make `name` the last event's name.
    #[inline(always)]
    pub(crate) fn intern(&mut self, name: &[u8]) {
        if self
            .names
            .get(self.last)
            .is_some_and(|n| Iface::Name(n).is_name(name))
        {
            return;
        }
        self.intern_other(name);
    }

    #[cold]
    #[inline(never)]
    fn intern_other(&mut self, name: &[u8]) {
        if let Some(at) = self.names.iter().position(|n| n.as_bytes() == name) {
            self.last = at;
            return;
        }
        if self.names.len() == MAX_NAMES {
            self.names.clear();
        }
        // The parsers take printable ASCII only; the fallback is never taken.
        let text = core::str::from_utf8(name).unwrap_or_default();
        self.last = self.names.len();
        self.names.push(text.into());
    }

    /// The last event's name.
    #[inline(always)]
    pub(crate) fn last(&self) -> &str {
        self.names.get(self.last).map_or("", |n| n)
    }
}

/// A text format's parser as the line layer drives it: one line at a time,
/// with the state the lines before it set (a header's base, candump's
/// relative timestamps).
#[cfg(feature = "std")]
pub(crate) trait TextParser: Clone {
    /// What a line that holds something is parsed into, borrowing the
    /// line.
    type Line<'t>;

    /// Read the line at the start of `rest` and take it off, with its
    /// `\n`: `Ok(None)` when it holds nothing. A frame's interface name is
    /// left in `names`.
    fn next_line<'t>(
        &mut self,
        rest: &mut &'t [u8],
        names: &mut Names,
    ) -> Result<Option<Self::Line<'t>>, FormatError>;

    /// The record of a line that holds something, at `position`, its
    /// interface name from `names`. (Built where the reader returns it, so
    /// that the frame is written once, where the caller reads it.)
    fn record<'a>(line: Self::Line<'_>, position: Position, names: &'a Names) -> LogRecord<'a>;

    /// Whether `line` holds nothing (blank, comment, header) whatever comes
    /// before it: where a live stream's reader can tell that the events
    /// of a block are all handed out.
    fn holds_nothing(&self, line: &[u8]) -> bool;

    /// Decide how to read the log from its first block(s) (`complete`: no
    /// more text comes with this block); `false` to see more text first.
    fn prepare(&mut self, _text: &[u8], _complete: bool) -> bool {
        true
    }
}

#[cfg(feature = "std")]
use crate::logs::{FormatError, LogError, LogErrorKind, LogRecord, Position};

/// The reader of a text log over the line layer: blocks of whole lines
/// from a [`std::io::Read`], each line parsed where it lies, positions
/// counted, over-long lines reported, a live stream's end of block known.
#[cfg(feature = "std")]
#[derive(Debug)]
pub(crate) struct TextLog<R, P> {
    input: TextInput<R>,
    parser: P,
    names: Names,
    /// Offset of the next line in the block.
    pos: usize,
    /// Where the lines to read now end: the block's end, or 0 while the
    /// parser is not ready or an over-long line is still to be said (one
    /// comparison per line tells the usual case).
    end: usize,
    /// The number of the last line read.
    line: u64,
    /// The parser is ready for the block ([`TextParser::prepare`]).
    ready: bool,
    /// An over-long line is to be said before the block.
    overlong: bool,
    /// Lines reported and skipped.
    skipped: u64,
    /// From this offset on, the block's lines hold nothing and it came
    /// from a read that drained the input: the reader is drained once it
    /// gets there (`usize::MAX` otherwise).
    tail: usize,
    done: bool,
}

/// What the slow path of [`TextLog::next_event`] found.
#[cfg(feature = "std")]
enum Step {
    /// Lines to read.
    Lines,
    /// The end of the input.
    End,
    /// An error to hand on.
    Error(LogError),
}

#[cfg(feature = "std")]
impl<R: std::io::Read, P: TextParser> TextLog<R, P> {
    pub(crate) fn new(reader: R, parser: P) -> Self {
        TextLog {
            input: TextInput::new(reader),
            parser,
            names: Names::default(),
            pos: 0,
            end: 0,
            line: 0,
            ready: false,
            overlong: false,
            skipped: 0,
            tail: usize::MAX,
            done: false,
        }
    }

    /// The parser, with the state the lines read so far set.
    pub(crate) const fn parser(&self) -> &P {
        &self.parser
    }

    #[inline(always)]
    pub(crate) fn next_event(&mut self) -> Option<Result<LogRecord<'_>, LogError>> {
        loop {
            if self.pos < self.end {
                let mut rest = self.input.buf.get(self.pos..self.end).unwrap_or_default();
                let len = rest.len();
                let parsed = self.parser.next_line(&mut rest, &mut self.names);
                self.pos += len - rest.len();
                self.line += 1;
                match parsed {
                    Ok(None) => continue,
                    Ok(Some(line)) => {
                        // Borrowed only on the way out: the loop goes on
                        // without it.
                        let position = Position::Line(self.line);
                        return Some(Ok(P::record(line, position, &self.names)));
                    }
                    Err(error) => {
                        self.skipped += 1;
                        return Some(Err(malformed(self.line, error)));
                    }
                }
            }
            match self.step() {
                Step::Lines => {}
                Step::End => return None,
                Step::Error(error) => return Some(Err(error)),
            }
        }
    }

    /// The block is read: say a skipped over-long line, or read the next
    /// block and get the parser ready for it.
    #[cold]
    #[inline(never)]
    fn step(&mut self) -> Step {
        if self.overlong {
            self.overlong = false;
            self.line += 1;
            self.skipped += 1;
            if self.ready {
                self.end = self.input.text;
            }
            return Step::Error(LogError::new(
                Some(Position::Line(self.line)),
                LogErrorKind::OverlongLine,
            ));
        }
        if self.done {
            return Step::End;
        }
        let info = match self.input.next_block() {
            Ok(Some(info)) => info,
            Ok(None) => {
                self.done = true;
                return Step::End;
            }
            Err(error) => {
                self.done = true;
                return Step::Error(LogError::from(error).or_at(Position::Line(self.line + 1)));
            }
        };
        self.pos = 0;
        self.end = 0;
        self.tail = usize::MAX;
        self.overlong = info.overlong;
        let text = self.input.text();
        let complete = info.at_end || info.full || text.len() >= HOLD_LEN;
        self.ready = self.parser.prepare(text, complete);
        if !self.ready {
            self.input.hold();
            return Step::Lines;
        }
        if info.drained {
            self.tail = quiet_tail(text, &self.parser);
        }
        if !self.overlong {
            self.end = text.len();
        }
        Step::Lines
    }

    pub(crate) fn bytes_read(&self) -> u64 {
        self.input.bytes
    }

    pub(crate) const fn skipped(&self) -> u64 {
        self.skipped
    }

    #[inline]
    pub(crate) fn drained(&self) -> bool {
        self.pos >= self.tail
    }
}

/// The error for line `line`, malformed as `error` says: reported, and
/// the reading goes on.
#[cfg(feature = "std")]
#[cold]
pub(crate) fn malformed(line: u64, error: FormatError) -> LogError {
    LogError::new(Some(Position::Line(line)), LogErrorKind::Malformed(error))
}

/// The offset in `text` from which every line holds nothing.
#[cfg(feature = "std")]
fn quiet_tail<P: TextParser>(text: &[u8], parser: &P) -> usize {
    let mut end = text.len();
    while end > 0 {
        let body = match text.get(..end) {
            Some([body @ .., b'\n']) | Some(body) => body,
            None => break,
        };
        let start = body.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        if !parser.holds_nothing(body.get(start..).unwrap_or_default()) {
            break;
        }
        end = start;
    }
    end
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn find_newline_is_the_first_newline(
            bytes in proptest::collection::vec(prop_oneof![Just(b'\n'), any::<u8>()], 0..80),
        ) {
            prop_assert_eq!(find_newline(&bytes), bytes.iter().position(|&b| b == b'\n'));
        }

        #[test]
        fn split_lines_is_split_at_newlines(
            bytes in proptest::collection::vec(prop_oneof![Just(b'\n'), Just(0), any::<u8>()], 0..80),
        ) {
            let mut expected: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
            // Nothing after a final `\n` is a line.
            if expected.last().is_some_and(|l| l.is_empty()) {
                expected.pop();
            }
            prop_assert_eq!(split_lines(&bytes).collect::<Vec<_>>(), expected);
        }
    }

    /// A held block that a long partial line would push past the largest
    /// buffer is handed out as it is (`full`), never dropped with the
    /// over-long line.
    #[cfg(feature = "std")]
    #[test]
    fn held_lines_are_handed_out_when_the_buffer_is_full() {
        let mut text = b"a\nb\n".to_vec();
        text.extend(std::iter::repeat(b'x').take(3 * MAX_LINE_LEN));
        text.extend_from_slice(b"\nc\n");
        let mut input = TextInput::new(&text[..]);
        let first = input.next_block().unwrap().unwrap();
        assert!(!first.full);
        assert_eq!(input.text(), b"a\nb\n");
        let mut holds = 0;
        loop {
            input.hold();
            let info = input.next_block().unwrap().unwrap();
            assert_eq!(input.text(), b"a\nb\n");
            holds += 1;
            if info.full {
                break;
            }
            assert!(holds < 10, "the buffer never fills");
        }
        assert!(input.buf.len() <= MAX_LINE_LEN);
        let info = input.next_block().unwrap().unwrap();
        assert!(info.overlong);
        assert_eq!(input.text(), b"c\n");
        assert!(input.buf.len() <= MAX_LINE_LEN);
        assert!(input.next_block().unwrap().is_none());
    }

    /// Where the lines that hold nothing begin at the end of a block.
    #[cfg(feature = "std")]
    #[test]
    fn the_quiet_tail_of_a_block() {
        use crate::logs::trc::TrcParser;
        let parser = TrcParser::new();
        for (text, tail) in [
            (&b""[..], 0),
            (b"\n\n", 0),
            (b"1)  1841  0001  8  00 01 02 03 04 05 06 07\n", 43),
            (
                b"1)  1841  0001  8  00 01 02 03 04 05 06 07\n; comment\n\r\n",
                43,
            ),
            (b"; comment\n1)  1841  0001  8  00 01 02 03 04 05 06 07", 52),
            (b"X\n;\n", 2),
        ] {
            assert_eq!(
                quiet_tail(text, &parser),
                tail,
                "{:?}",
                String::from_utf8_lossy(text)
            );
        }
    }

    /// The names of a log: each kept once, the table started again past
    /// `MAX_NAMES`.
    #[cfg(feature = "std")]
    #[test]
    fn names_are_kept_once() {
        let mut names = Names::default();
        names.intern(b"can0");
        let can0 = names.last().as_ptr();
        names.intern(b"can1");
        assert_eq!(names.last(), "can1");
        names.intern(b"can0");
        assert_eq!(names.last().as_ptr(), can0);
        for i in 0..MAX_NAMES {
            names.intern(format!("x{i}").as_bytes());
        }
        assert!(names.names.len() < MAX_NAMES);
        assert_eq!(names.last(), format!("x{}", MAX_NAMES - 1));
    }
}
