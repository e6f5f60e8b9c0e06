//! The fast path: the two event lines a log is made of — a classic data
//! frame (`   0.012345 1  123             Rx   d 8 11 22 …`) and a `CANFD`
//! frame — read in one pass over the line, in a `base hex` file.
//!
//! The reader reads a line where it lies in its block
//! ([`AscParser::parse_fast_in_place`]): the line's `\n` is looked for
//! only from where the frame's last word ends, and only when something
//! other than `\n` follows it. A classic line in the writers' columns
//! (python-can, CANoe) is read mostly from fixed-size loads: the time's
//! digits 8 bytes at a time, a one-digit channel from one 3-byte look,
//! the direction, `d` and DLC after the padded
//! identifier from one 16-byte and one 8-byte load
//! ([`Words::columns`]), the data bytes from one 24-byte load
//! ([`Words::classic_bytes`]); any other spacing or spelling is read
//! word by word.
//!
//! It accepts only lines the general parser reads to a frame, and returns
//! for them what the general parser returns; every other line (a remote
//! request, an error frame, a symbolic name, `base dec`, a header, a
//! malformed line) it declines without changing the parser, and the general
//! parser reads it or says where it goes wrong. The property tests in
//! `proptests.rs` hold the two to that.

use super::parser::{fd_frame, AscParser};
use crate::can::{CanFrame, CanId, Direction, FrameType, Iface, LogEvent, LogFrame, Timestamp};
use crate::can::{CLASSIC_MAX_LEN, FD_LENGTHS, FD_MAX_LEN};
use crate::logs::lex::swar::decimal8;
use crate::logs::lex::{hex, hex_value, is_space, trim_end, HEX_TABLE, POW10_NANOS};

/// The lanes (bytes) of ` HH HH HH HH HH` that hold a space (0, 3, …,
/// 12) …
const GROUP_SPACES: u128 = u128::from_le_bytes([
    0xFF, 0, 0, 0xFF, 0, 0, 0xFF, 0, 0, 0xFF, 0, 0, 0xFF, 0, 0, 0,
]);
/// … and the spaces in them.
const SPACES: u128 = u128::from_le_bytes([
    b' ', 0, 0, b' ', 0, 0, b' ', 0, 0, b' ', 0, 0, b' ', 0, 0, 0,
]);

impl AscParser {
    /// Read `line` (its trailing white space trimmed) when it is a classic
    /// data frame or a `CANFD` frame in a `base hex` file: the event, as
    /// the general parser reads it, or `None` for any other line, with the
    /// parser unchanged.
    #[inline]
    pub(super) fn parse_fast(&mut self, line: &[u8]) -> Option<LogEvent<'static>> {
        let (mut logged, end, classic) = self.read_fast(line)?;
        if !ends_line(line.get(end..).unwrap_or_default(), classic) {
            return None;
        }
        self.count_time(&mut logged);
        Some(LogEvent::Frame(logged))
    }

    /// [`parse_fast`](Self::parse_fast) for the line at the start of
    /// `text`, read where it lies (its `\n` not looked for first): the
    /// event and the length of the line with its `\n`, or `None` with
    /// the parser unchanged.
    #[cfg(any(feature = "std", test))]
    #[inline(always)]
    pub(super) fn parse_fast_in_place(
        &mut self,
        text: &[u8],
    ) -> Option<(LogEvent<'static>, usize)> {
        let (mut logged, end, classic) = self.read_fast(text)?;
        let next = line_after(text, end, classic)?;
        self.count_time(&mut logged);
        Some((LogEvent::Frame(logged), next))
    }

    /// The frame of the line at the start of `text`, its time as written,
    /// and where its last word read ends: a word ends at any byte up to
    /// `b' '`, so that the line's end (`\r`, `\n`) ends it, and the caller
    /// tells what that byte may be; and whether the line is a classic one.
    #[inline(always)]
    fn read_fast(&self, text: &[u8]) -> Option<(LogFrame<'static>, usize, bool)> {
        if !self.hex {
            return None;
        }
        let mut words = Words { line: text, pos: 0 };
        let written = words.time()?;
        // A classic line's channel, or `None` for a `CANFD` line.
        let classic_channel = match words
            .line
            .get(words.pos..)
            .and_then(|rest| rest.first_chunk::<3>())
        {
            // One digit between single spaces: the usual channel.
            Some(&[b' ', digit @ b'1'..=b'9', b' ']) => {
                words.pos += 2;
                Some(u16::from(digit - b'0'))
            }
            _ => match words.next()? {
                b"CANFD" => None,
                second => Some(channel(second)?),
            },
        };
        let is_classic = classic_channel.is_some();
        let (frame, channel, direction) = match classic_channel {
            Some(channel) => {
                let (frame, direction) = classic(&mut words)?;
                (frame, channel, direction)
            }
            None => fd(&mut words)?,
        };
        let logged = LogFrame {
            frame,
            timestamp: Some(written),
            iface: Some(Iface::Channel(channel)),
            direction: Some(direction),
        };
        Some((logged, words.pos, is_classic))
    }

    /// Count the time of a frame read (add it up, with relative times).
    #[inline(always)]
    fn count_time(&mut self, logged: &mut LogFrame<'static>) {
        if self.relative {
            logged.timestamp = logged.timestamp.map(|written| self.time(written));
        }
    }
}

/// Where the line after the one at the start of `text` begins (past its
/// `\n`, or the end of `text`), when the first line's last word read ends
/// at `end` and what follows it is white space or nothing, as
/// [`AscParser::parse_fast`] takes it after the line is trimmed; `None`
/// otherwise.
#[cfg(any(feature = "std", test))]
#[inline(always)]
fn line_after(text: &[u8], end: usize, classic: bool) -> Option<usize> {
    // The line ends right after its last word: the usual case.
    match text.get(end) {
        None => return Some(end),
        Some(b'\n') => return Some(end + 1),
        Some(_) => {}
    }
    let rest = text.get(end..)?;
    let (line, next) = match crate::logs::text::find_newline(rest) {
        Some(i) => (rest.get(..i)?, end + i + 1),
        None => (rest, text.len()),
    };
    ends_line(line, classic).then_some(next)
}

/// Whether `rest`, what follows the last word a frame's line read, may
/// end it: white space (a `\r` too), or words after a space that the
/// frame does not read — after a classic frame's data only CANoe's
/// statistics (anything else is the general parser's to judge and
/// report), after a `CANFD` line's flags CANoe's further columns.
fn ends_line(rest: &[u8], classic: bool) -> bool {
    let rest = trim_end(rest);
    rest.is_empty()
        || (rest.first().is_some_and(|&b| is_space(b))
            && (!classic || super::parser::is_classic_trailer(rest)))
}

/// Whether `b` ends a word for the fast path: a space or a tab, or a
/// byte that is no part of a word it reads (`\r`, `\n`, other control
/// bytes). A word that ends at one that is not a space or a tab is the
/// line's last (the next word, read from there, is empty), and the
/// caller decides what follows it.
#[inline(always)]
const fn ends_word(b: u8) -> bool {
    b <= b' '
}

/// `id Rx|Tx d dlc data…` after the channel, in hex; what follows the data
/// (CANoe's statistics) is not read, as the general parser does not read
/// it.
#[inline(always)]
fn classic(words: &mut Words<'_>) -> Option<(CanFrame, Direction)> {
    // The writers put two spaces after the channel.
    match words
        .line
        .get(words.pos..)
        .and_then(|rest| rest.first_chunk::<3>())
    {
        Some(&[b' ', b' ', b]) if !is_space(b) => words.pos += 2,
        _ => words.skip_space(),
    }
    let id_start = words.pos;
    let id = words.id_here()?;
    let (direction, dlc) = match words.columns(id_start) {
        Some(head) => head,
        None => words.head_spelt()?,
    };
    let len = usize::from(dlc).min(CLASSIC_MAX_LEN);
    // The bytes past `len` stay zero, as a frame's must be.
    let mut bytes = [0u8; FD_MAX_LEN];
    let data = bytes.first_chunk_mut::<CLASSIC_MAX_LEN>()?;
    if !words.classic_bytes(len, data) {
        words.classic_bytes_spelt(len, data)?;
    }
    let frame = CanFrame::from_array(id, FrameType::Data, bytes, len as u8);
    Some((frame, direction))
}

/// `ch Rx|Tx id brs esi dlc len data… duration bits flags` after `CANFD`
/// (no symbolic name), in hex.
// Out of line: inlined into the line's loop, it makes the loop of the
// classic lines, the common ones, longer (BENCHMARKS.md, "CAN FD data,
// candump and ASC").
#[inline(never)]
fn fd(words: &mut Words<'_>) -> Option<(CanFrame, u16, Direction)> {
    let FdHead {
        channel,
        direction,
        id,
        brs_column,
        esi_column,
        dlc,
        len,
    } = match words.fd_columns() {
        Some(head) => head,
        None => words.fd_head_spelt()?,
    };
    if len > 64 || FD_LENGTH_BITS >> len & 1 == 0 {
        return None;
    }
    let len = usize::from(len);
    let mut data = [0u8; FD_MAX_LEN];
    words.fd_bytes(data.get_mut(..len)?)?;
    let flags = match words.fd_tail_columns() {
        Some(flags) => flags,
        None => words.fd_tail_spelt()?,
    };
    let frame = fd_frame(id, dlc, &data, len, flags, brs_column, esi_column)?;
    Some((frame, channel, direction))
}

/// The lengths CAN FD data has ([`FD_LENGTHS`]), a bit each: one look-up,
/// where a search of the list takes up to 16 steps (and `contains` on bytes
/// is a `memchr` call; BENCHMARKS.md, "ASC reader").
const FD_LENGTH_BITS: u128 = {
    let mut bits = 0u128;
    let mut i = 0;
    while i < FD_LENGTHS.len() {
        bits |= 1 << FD_LENGTHS[i];
        i += 1;
    }
    bits
};

/// The words of a `CANFD` line before its data.
struct FdHead {
    channel: u16,
    direction: Direction,
    id: CanId,
    brs_column: bool,
    esi_column: bool,
    dlc: u8,
    /// The data length, as written (checked by the caller).
    len: u8,
}

/// A `CANFD` line's data length in decimal, one or two digits.
#[inline(always)]
fn fd_len(word: &[u8]) -> Option<u8> {
    match *word {
        [u] if u.is_ascii_digit() => Some(u - b'0'),
        [t, u] if t.is_ascii_digit() && u.is_ascii_digit() => Some((t - b'0') * 10 + (u - b'0')),
        _ => None,
    }
}

/// The word of a right-aligned column: `field` is a space, then spaces,
/// then a word that fills the rest of it (one byte at least, no byte that
/// [ends a word](ends_word)); `None` for any other field.
///
/// The field's bytes after its first (4 or 8) are read as one word: the
/// first that is no space found at once, and the bytes that end a word
/// flagged at once (wide-word arithmetic, SWAR, with no carry between
/// lanes), none allowed from the first that is no space on.
#[inline(always)]
fn right_aligned<const N: usize>(field: &[u8; N]) -> Option<&[u8]> {
    const SPACES: u64 = u64::from_le_bytes([b' '; 8]);
    const LOW7: u64 = u64::from_le_bytes([0x7F; 8]);
    const HIGH: u64 = u64::from_le_bytes([0x80; 8]);
    let (&first, rest) = field.split_first()?;
    if first != b' ' || rest.len() > 8 {
        return None;
    }
    // The lanes past the field's hold `0`, a byte of a word.
    let mut lanes = [b'0'; 8];
    lanes.get_mut(..rest.len())?.copy_from_slice(rest);
    let w = u64::from_le_bytes(lanes);
    let start = ((w ^ SPACES).trailing_zeros() / 8) as usize;
    if start >= rest.len() {
        return None;
    }
    // The high bit of every lane up to `b' '` (below 0x21, not 0x80 and
    // up); the spaces before `start` among them.
    let ends = !((w & LOW7).wrapping_add(u64::from_le_bytes([0x80 - 0x21; 8])) | w) & HIGH;
    if ends >> (8 * start) != 0 {
        return None;
    }
    rest.get(start..)
}

/// A channel number, 1 to 65535, in 1 to 5 digits (more, with leading
/// zeros, are left to the general parser).
#[inline(always)]
fn channel(word: &[u8]) -> Option<u16> {
    if word.is_empty() || word.len() > 5 {
        return None;
    }
    let mut value = 0u32;
    for &b in word {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        value = value * 10 + u32::from(d);
    }
    u16::try_from(value).ok().filter(|&n| n > 0)
}

/// The decimal digits that start the 8 bytes of `w` (the first in its
/// lowest lane), when fewer than 8: their value and number, read with
/// wide-word arithmetic (SWAR); `None` when all 8 are digits.
#[inline(always)]
const fn eight_digits(w: u64) -> Option<(u64, usize)> {
    const HIGH_NIBBLES: u64 = u64::from_le_bytes([0xF0; 8]);
    const THREES: u64 = u64::from_le_bytes([0x30; 8]);
    const SIXES: u64 = u64::from_le_bytes([0x06; 8]);
    // A lane is a digit when its high nibble is 3 and it stays 3 with 6
    // added (0x30..=0x39). The carry out of a lane 0xFA..=0xFF reaches
    // only lanes after it, and it is no digit itself: the first lane
    // marked is exact.
    let others = ((w & HIGH_NIBBLES) ^ THREES) | ((w.wrapping_add(SIXES) & HIGH_NIBBLES) ^ THREES);
    if others == 0 {
        return None;
    }
    let n = (others.trailing_zeros() / 8) as usize;
    if n == 0 {
        return Some((0, 0));
    }
    // The digits' values (a borrow out of the lanes after them reaches
    // only later lanes), moved to the highest lanes so that the lanes
    // before them are leading zeros for the candump reader's `decimal8`.
    let v = w.wrapping_sub(THREES) << (8 * (8 - n));
    Some((decimal8(v), n))
}

/// A hex digit's value times 16 by character, 0x100 for a character that
/// is no hex digit: or'd with [`HEX_LOW`]'s entry for the second digit,
/// the byte the two spell, 0x100 set when either is not a digit.
const HEX_HIGH: [u16; 256] = {
    let mut table = [0x100u16; 256];
    let mut i = 0;
    while i < 256 {
        if HEX_TABLE[i] & 0xF0 == 0 {
            table[i] = (HEX_TABLE[i] as u16) << 4;
        }
        i += 1;
    }
    table
};

/// A hex digit's value by character, 0x100 for a character that is no hex
/// digit (see [`HEX_HIGH`]).
const HEX_LOW: [u16; 256] = {
    let mut table = [0x100u16; 256];
    let mut i = 0;
    while i < 256 {
        if HEX_TABLE[i] & 0xF0 == 0 {
            table[i] = HEX_TABLE[i] as u16;
        }
        i += 1;
    }
    table
};

/// The white-space separated words of a line, read in order.
struct Words<'l> {
    line: &'l [u8],
    pos: usize,
}

impl<'l> Words<'l> {
    /// Skip spaces and tabs, 8 bytes at a time while they are spaces (the
    /// padding the writers put after identifiers).
    #[inline(always)]
    fn skip_space(&mut self) {
        // One space between words is the common case.
        if self.line.get(self.pos) == Some(&b' ')
            && !self.line.get(self.pos + 1).is_some_and(|&b| is_space(b))
        {
            self.pos += 1;
            return;
        }
        while let Some(chunk) = self
            .line
            .get(self.pos..)
            .and_then(|rest| rest.first_chunk::<8>())
        {
            let other = u64::from_le_bytes(*chunk) ^ u64::from_le_bytes([b' '; 8]);
            if other != 0 {
                self.pos += (other.trailing_zeros() / 8) as usize;
                break;
            }
            self.pos += 8;
        }
        while self.line.get(self.pos).is_some_and(|&b| is_space(b)) {
            self.pos += 1;
        }
    }

    /// The next word, or `None` at the end of the line (or at a byte
    /// that [ends a word](ends_word) and is no space).
    #[inline(always)]
    fn next(&mut self) -> Option<&'l [u8]> {
        self.skip_space();
        self.word()
    }

    /// The word where the position is (after white space skipped), or
    /// `None` where none starts.
    #[inline(always)]
    fn word(&mut self) -> Option<&'l [u8]> {
        let start = self.pos;
        self.pos = self.word_end(start);
        if self.pos == start {
            return None;
        }
        self.line.get(start..self.pos)
    }

    /// Where the word at `at` ends: 8 bytes at a time, the lanes (bytes)
    /// up to `b' '` found with wide-word arithmetic (SWAR), the last bytes
    /// of the line one by one.
    #[inline(always)]
    fn word_end(&self, mut at: usize) -> usize {
        const ONES: u64 = u64::from_le_bytes([0x01; 8]);
        const HIGH: u64 = u64::from_le_bytes([0x80; 8]);
        while let Some(chunk) = self.line.get(at..).and_then(|rest| rest.first_chunk::<8>()) {
            let w = u64::from_le_bytes(*chunk);
            // The high bit of each lane below 0x21, and possibly of lanes
            // after the first such lane (a borrow): the first is exact.
            let ends = w.wrapping_sub(ONES * 0x21) & !w & HIGH;
            if ends != 0 {
                return at + (ends.trailing_zeros() / 8) as usize;
            }
            at += 8;
        }
        while self.line.get(at).is_some_and(|&b| !ends_word(b)) {
            at += 1;
        }
        at
    }

    /// The first word, read where it stands: `seconds.fraction`, 1 to 15
    /// digits of seconds and 1 to 9 of fraction.
    #[inline(always)]
    fn time(&mut self) -> Option<Timestamp> {
        self.skip_space();
        let (secs, digits, point) = self.digits(self.pos);
        if digits == 0 || digits > 15 || self.line.get(point) != Some(&b'.') {
            return None;
        }
        let (fraction, digits, end) = self.digits(point + 1);
        if digits == 0 || digits > 9 || self.line.get(end).is_some_and(|&b| !ends_word(b)) {
            return None;
        }
        self.pos = end;
        let nanos = u32::try_from(fraction).ok()? * POW10_NANOS.get(9 - digits)?;
        Timestamp::from_nanos(secs, nanos)
    }

    /// The decimal digits from `at`: their value (wrapped past 20
    /// digits), their number and where they end. Fewer than 8 followed by
    /// a byte that is none, with 8 bytes to load, are read at once
    /// ([`eight_digits`]); others one by one.
    #[inline(always)]
    fn digits(&self, at: usize) -> (u64, usize, usize) {
        if let Some(chunk) = self.line.get(at..).and_then(|rest| rest.first_chunk::<8>()) {
            if let Some((value, n)) = eight_digits(u64::from_le_bytes(*chunk)) {
                return (value, n, at + n);
            }
        }
        let mut value = 0u64;
        let mut end = at;
        while let Some(d) = self
            .line
            .get(end)
            .map(|b| b.wrapping_sub(b'0'))
            .filter(|&d| d <= 9)
        {
            value = value.wrapping_mul(10).wrapping_add(u64::from(d));
            end += 1;
        }
        (value, end - at, end)
    }

    /// An identifier in hex, `x` after an extended one.
    #[inline(always)]
    fn id(&mut self) -> Option<CanId> {
        self.skip_space();
        self.id_here()
    }

    /// [`id`](Self::id) where the position is, white space skipped.
    #[inline(always)]
    fn id_here(&mut self) -> Option<CanId> {
        let word = self.word()?;
        match word.split_last() {
            Some((b'x' | b'X', digits)) => CanId::extended(hex(digits)?),
            _ => CanId::standard(hex(word)?),
        }
    }

    /// A classic line's direction, `d` and DLC in the columns the writers
    /// put them in (python-can, CANoe: `702             Rx   d 8`): the
    /// identifier that began at `id_start`, and has just been read,
    /// padded with spaces to 15 columns, a space, `Rx` or `Tx`, three
    /// spaces, `d` (or `D`), a space and the DLC digit, then a byte that
    /// [ends a word](ends_word) or the end — read from one 16-byte and one
    /// 8-byte load. `None`, with the position unchanged, for any other
    /// spacing or word (read by [`head_spelt`](Self::head_spelt)).
    #[inline(always)]
    fn columns(&mut self, id_start: usize) -> Option<(Direction, u8)> {
        /// `x   d ` from the second lane on, the kind's case folded.
        const DIRECTION_TO_DLC: u64 =
            u64::from_le_bytes([0, b'x', b' ', b' ', b' ', b'd', b' ', 0]);
        const MIDDLE: u64 = u64::from_le_bytes([0, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0]);
        const KIND_CASE: u64 = u64::from_le_bytes([0, 0, 0, 0, 0, 0x20, 0, 0]);
        let head = self.line.get(id_start..)?.first_chunk::<24>()?;
        let (field, rest) = head.split_first_chunk::<16>()?;
        let rest = rest.first_chunk::<8>()?;
        // Every lane after the identifier's is a space.
        let id_len = self.pos - id_start;
        let padding = u128::MAX.checked_shl(8 * u32::try_from(id_len).ok()?)?;
        if (u128::from_le_bytes(*field) ^ u128::from_le_bytes([b' '; 16])) & padding != 0 {
            return None;
        }
        let rest = u64::from_le_bytes(*rest);
        if (rest | KIND_CASE) & MIDDLE != DIRECTION_TO_DLC {
            return None;
        }
        let direction = match rest.to_le_bytes() {
            [b'R', ..] => Direction::Rx,
            [b'T', ..] => Direction::Tx,
            _ => return None,
        };
        let dlc = HEX_TABLE[usize::from(rest.to_le_bytes()[7])];
        let end = id_start + 24;
        if dlc & 0xF0 != 0 || self.line.get(end).is_some_and(|&b| !ends_word(b)) {
            return None;
        }
        self.pos = end;
        Some((direction, dlc))
    }

    /// A `CANFD` line's words before its data in the columns python-can
    /// writes them in (`{channel:>3} {dir:<4} {id:>8} {name:>32}  {brs}
    /// {esi} {dlc:x} {len:>2}`, the name empty), from where `CANFD` ends:
    /// a one-digit channel, `Rx` or `Tx`, an identifier of up to 8
    /// characters, 35 spaces, BRS, ESI, the DLC and the length, each after
    /// a single space, then a byte that [ends a word](ends_word) — read from
    /// one 62-byte look, with no search for where words start and end (the
    /// 35 spaces alone took five of `skip_space`'s 8-byte steps). `None`, with
    /// the position unchanged, for any other spacing or word (read by
    /// [`fd_head_spelt`](Self::fd_head_spelt)). Where it reads a line, the
    /// words are the ones [`next`](Self::next) reads, so that it returns what
    /// `fd_head_spelt` would.
    #[inline(always)]
    fn fd_columns(&mut self) -> Option<FdHead> {
        const SPACES: u128 = u128::from_le_bytes([b' '; 16]);
        let at = self.pos;
        let head = self.line.get(at..)?.first_chunk::<62>()?;
        let (start, rest) = head.split_first_chunk::<10>()?;
        let (id_field, rest) = rest.split_first_chunk::<8>()?;
        let (gap, rest) = rest.split_first_chunk::<35>()?;
        let (gap_start, gap_end) = gap.split_first_chunk::<16>()?;
        let (gap_middle, gap_end) = gap_end.split_first_chunk::<16>()?;
        let tail = rest.first_chunk::<9>()?;
        let (channel, direction) = match *start {
            [b' ', b' ', b' ', d @ b'1'..=b'9', b' ', b'R', b'x', b' ', b' ', b' '] => {
                (u16::from(d - b'0'), Direction::Rx)
            }
            [b' ', b' ', b' ', d @ b'1'..=b'9', b' ', b'T', b'x', b' ', b' ', b' '] => {
                (u16::from(d - b'0'), Direction::Tx)
            }
            _ => return None,
        };
        if (u128::from_le_bytes(*gap_start) ^ SPACES) | (u128::from_le_bytes(*gap_middle) ^ SPACES)
            != 0
            || gap_end != b"   "
        {
            return None;
        }
        // The identifier: right-aligned, a word after spaces.
        let padding =
            (u64::from_le_bytes(*id_field) ^ u64::from_le_bytes([b' '; 8])).trailing_zeros() / 8;
        let word = id_field.get(padding as usize..)?;
        if word.is_empty() || word.iter().any(|&b| ends_word(b)) {
            return None;
        }
        let id = match word.split_last() {
            Some((b'x' | b'X', digits)) => CanId::extended(hex(digits)?),
            _ => CanId::standard(hex(word)?),
        }?;
        let [brs, b' ', esi, b' ', dlc, b' ', t, u, after] = *tail else {
            return None;
        };
        let bit = |b: u8| match b {
            b'0' => Some(false),
            b'1' => Some(true),
            _ => None,
        };
        let len = match t {
            b' ' => fd_len(&[u])?,
            _ => fd_len(&[t, u])?,
        };
        if !ends_word(after) {
            return None;
        }
        let head = FdHead {
            channel,
            direction,
            id,
            brs_column: bit(brs)?,
            esi_column: bit(esi)?,
            dlc: hex_value(dlc)?,
            len,
        };
        self.pos = at + 61;
        Some(head)
    }

    /// A `CANFD` line's message duration, bit count and flags after its
    /// data in the columns python-can writes them in (` {duration:>8}
    /// {bits:>4} {flags:>8X}`): the flags, read from one 24-byte look.
    /// `None`, with the position unchanged, for any other spacing (read by
    /// [`fd_tail_spelt`](Self::fd_tail_spelt)); where it reads them, the
    /// words are the ones [`next`](Self::next) reads.
    #[inline(always)]
    fn fd_tail_columns(&mut self) -> Option<u32> {
        let at = self.pos;
        let tail = self.line.get(at..)?.first_chunk::<24>()?;
        let (duration, rest) = tail.split_first_chunk::<9>()?;
        let (bits, rest) = rest.split_first_chunk::<5>()?;
        let (flags, after) = rest.split_first_chunk::<9>()?;
        right_aligned(duration)?;
        right_aligned(bits)?;
        let flags = hex(right_aligned(flags)?)?;
        if !ends_word(*after.first()?) {
            return None;
        }
        self.pos = at + 23;
        Some(flags)
    }

    /// A `CANFD` line's message duration, bit count and flags, each a word
    /// after white space: what [`fd_tail_columns`](Self::fd_tail_columns)
    /// declines, out of line.
    #[inline(never)]
    fn fd_tail_spelt(&mut self) -> Option<u32> {
        self.next()?;
        self.next()?;
        hex(self.next()?)
    }

    /// A `CANFD` line's words before its data, each a word after white
    /// space: what [`fd_columns`](Self::fd_columns) declines, out of line.
    #[inline(never)]
    fn fd_head_spelt(&mut self) -> Option<FdHead> {
        let channel = channel(self.next()?)?;
        let direction = self.direction_word()?;
        let id = self.id()?;
        let brs_column = self.bit()?;
        let esi_column = self.bit()?;
        let dlc = self.hex_digit()?;
        // The data length in decimal, one or two digits (a length CAN FD
        // has is the caller's to check: 0..=8, 12, …, 64).
        let len = fd_len(self.next()?)?;
        Some(FdHead {
            channel,
            direction,
            id,
            brs_column,
            esi_column,
            dlc,
            len,
        })
    }

    /// A classic line's direction, `d` and DLC, each a word after white
    /// space: what [`columns`](Self::columns) declines, out of line.
    #[inline(never)]
    fn head_spelt(&mut self) -> Option<(Direction, u8)> {
        let direction = self.direction_word()?;
        if !matches!(self.next()?, b"d" | b"D") {
            return None;
        }
        Some((direction, self.hex_digit()?))
    }

    /// `Rx` or `Tx`.
    #[inline(always)]
    fn direction_word(&mut self) -> Option<Direction> {
        match self.next()? {
            b"Rx" => Some(Direction::Rx),
            b"Tx" => Some(Direction::Tx),
            _ => None,
        }
    }

    /// A BRS or ESI column: `0` or `1`.
    #[inline(always)]
    fn bit(&mut self) -> Option<bool> {
        match self.next()? {
            b"0" => Some(false),
            b"1" => Some(true),
            _ => None,
        }
    }

    /// One hex digit (a DLC).
    #[inline(always)]
    fn hex_digit(&mut self) -> Option<u8> {
        match self.next()? {
            &[d] => hex_value(d),
            _ => None,
        }
    }

    /// A `CANFD` line's `out.len()` data bytes (up to 64): ` HH` five at
    /// a time by [`five_bytes`](Self::five_bytes) while they are, the rest
    /// by [`bytes`](Self::bytes). (A classic line's 8 at most are
    /// [`classic_bytes`](Self::classic_bytes)'s, all from one load;
    /// BENCHMARKS.md, "the ASC reader, classic lines".)
    #[inline(always)]
    fn fd_bytes(&mut self, out: &mut [u8]) -> Option<()> {
        let mut read = 0;
        while let Some(five) = out.get_mut(read..).and_then(|s| s.first_chunk_mut::<5>()) {
            if !self.five_bytes(five) {
                break;
            }
            read += 5;
        }
        self.bytes(out.get_mut(read..)?)
    }

    /// A classic line's `len` (up to 8) data bytes, each ` HH` (what the
    /// writers write), into the first `len` of `data` (the frame's array,
    /// the rest left as it is): from one 24-byte load, a look-up per
    /// digit in [`HEX_HIGH`] and [`HEX_LOW`], whose or is the byte (and
    /// 0x100 when a digit is no hex digit), the groups' spaces and digits
    /// checked once for all, then what follows the last group. `false`,
    /// with the position unchanged (and the first `len` of `data` written
    /// over), when they are not (the other spellings are
    /// [`classic_bytes_spelt`](Self::classic_bytes_spelt)'s) or fewer than
    /// 24 bytes are left.
    #[inline(always)]
    fn classic_bytes(&mut self, len: usize, data: &mut [u8; CLASSIC_MAX_LEN]) -> bool {
        let at = self.pos;
        let Some(groups) = self
            .line
            .get(at..)
            .and_then(|rest| rest.first_chunk::<24>())
        else {
            return false;
        };
        // The or of the bytes (0x100 set when a digit is no hex digit),
        // and of the groups' first bytes each xor a space (0 when all are
        // spaces).
        let (mut all, mut spaces) = (0u16, 0u8);
        for (i, slot) in data.iter_mut().enumerate().take(len) {
            let group = 3 * i;
            if let (Some(&space), Some(&hi), Some(&lo)) = (
                groups.get(group),
                groups.get(group + 1),
                groups.get(group + 2),
            ) {
                let byte = HEX_HIGH[usize::from(hi)] | HEX_LOW[usize::from(lo)];
                all |= byte;
                spaces |= space ^ b' ';
                *slot = byte as u8;
            }
        }
        let end = at + 3 * len;
        if all & 0x100 != 0 || spaces != 0 || self.line.get(end).is_some_and(|&b| !ends_word(b)) {
            return false;
        }
        self.pos = end;
        true
    }

    /// A classic line's `len` data bytes in any spelling
    /// [`bytes`](Self::bytes) reads, into the first `len` of `data`, out
    /// of line: what [`classic_bytes`](Self::classic_bytes) declines.
    #[cold]
    #[inline(never)]
    fn classic_bytes_spelt(&mut self, len: usize, data: &mut [u8; CLASSIC_MAX_LEN]) -> Option<()> {
        self.bytes(data.get_mut(..len)?)
    }

    /// `out.len()` data bytes: ` HH` (what the writers write) with a
    /// table look-up per digit, any other spelling by [`byte`](Self::byte).
    #[inline(always)]
    fn bytes(&mut self, out: &mut [u8]) -> Option<()> {
        for slot in out {
            let at = self.pos;
            if let Some(&[b' ', hi, lo]) = self.line.get(at..at + 3) {
                let (hi, lo) = (HEX_TABLE[usize::from(hi)], HEX_TABLE[usize::from(lo)]);
                if (hi | lo) & 0xF0 == 0 && !self.line.get(at + 3).is_some_and(|&b| !ends_word(b)) {
                    *slot = hi << 4 | lo;
                    self.pos = at + 3;
                    continue;
                }
            }
            *slot = self.byte()?;
        }
        Some(())
    }

    /// Five data bytes ` HH HH HH HH HH` followed by white space, read
    /// from one 16-byte load (the spaces checked at once, a table look-up
    /// per digit): `false` when they are not, with the position unchanged
    /// (and `out` written over).
    #[inline(always)]
    fn five_bytes(&mut self, out: &mut [u8; 5]) -> bool {
        let at = self.pos;
        let Some(chunk) = self
            .line
            .get(at..)
            .and_then(|rest| rest.first_chunk::<16>())
        else {
            return false;
        };
        if u128::from_le_bytes(*chunk) & GROUP_SPACES != SPACES || !ends_word(chunk[15]) {
            return false;
        }
        let mut all = 0u8;
        for (i, byte) in out.iter_mut().enumerate() {
            let hi = HEX_TABLE[usize::from(chunk[3 * i + 1])];
            let lo = HEX_TABLE[usize::from(chunk[3 * i + 2])];
            all |= hi | lo;
            *byte = hi << 4 | lo;
        }
        if all & 0xF0 != 0 {
            return false;
        }
        self.pos = at + 15;
        true
    }

    /// A data byte: one or two hex digits, read where they stand.
    #[inline(always)]
    fn byte(&mut self) -> Option<u8> {
        self.skip_space();
        let at = self.pos;
        let hi = hex_value(*self.line.get(at)?)?;
        match self.line.get(at + 1) {
            Some(&lo) if !ends_word(lo) => {
                let lo = hex_value(lo)?;
                if self.line.get(at + 2).is_some_and(|&b| !ends_word(b)) {
                    return None;
                }
                self.pos = at + 2;
                Some(hi << 4 | lo)
            }
            _ => {
                self.pos = at + 1;
                Some(hi)
            }
        }
    }
}

/// The data bytes read five at a time against the same bytes read one by
/// one (the general spelling, [`Words::byte`]), over runs of ` HH` with
/// any byte anywhere and over arbitrary bytes.
#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Read `n` bytes from `line` at `pos` both ways: the same bytes and
    /// position wherever the byte-by-byte reading reads them, `None` where
    /// it does not.
    fn agrees(line: &[u8], pos: usize, n: usize) -> Result<(), TestCaseError> {
        let mut fast = Words { line, pos };
        let mut out = [0u8; FD_MAX_LEN];
        let read = fast.fd_bytes(&mut out[..n]);
        let mut slow = Words { line, pos };
        let expected: Option<Vec<u8>> = (0..n).map(|_| slow.byte()).collect();
        match expected {
            Some(bytes) => {
                prop_assert_eq!(read, Some(()));
                prop_assert_eq!(&out[..n], &bytes[..]);
                prop_assert_eq!(fast.pos, slow.pos);
            }
            None => prop_assert_eq!(read, None),
        }
        Ok(())
    }

    /// ` HH` groups, each character sometimes another (white space, a
    /// lower-case digit, a non-digit, any byte), then what follows data.
    fn data_run() -> impl Strategy<Value = Vec<u8>> {
        let byte = |right: &'static [u8]| {
            prop_oneof![
                40 => proptest::sample::select(right.to_vec()),
                1 => proptest::sample::select(b" \t\rabcdefGgx0".to_vec()),
                1 => any::<u8>(),
            ]
        };
        let group = (
            byte(b" "),
            byte(b"0123456789ABCDEF"),
            byte(b"0123456789ABCDEF"),
        );
        let tail = prop_oneof![
            Just(b"        0    0     3000".to_vec()),
            Just(Vec::new()),
            Just(b"\t0".to_vec()),
            Just(b" ".to_vec()),
            proptest::collection::vec(any::<u8>(), 0..4),
        ];
        (proptest::collection::vec(group, 0..70), tail).prop_map(|(groups, tail)| {
            let mut line: Vec<u8> = groups.into_iter().flat_map(|(s, h, l)| [s, h, l]).collect();
            line.extend(tail);
            line
        })
    }

    /// Eight bytes, mostly digits.
    fn mostly_digits() -> impl Strategy<Value = [u8; 8]> {
        proptest::array::uniform8(prop_oneof![
            8 => proptest::sample::select(b"0123456789".to_vec()),
            1 => proptest::sample::select(b" ./:\t\n\r\xFA\xFF".to_vec()),
            1 => any::<u8>(),
        ])
    }

    /// [`right_aligned`] byte by byte: a space, spaces, then a word to
    /// the end.
    fn right_aligned_one_by_one(field: &[u8]) -> Option<&[u8]> {
        let rest = field.strip_prefix(b" ")?;
        let start = rest.iter().position(|&b| b != b' ')?;
        let word = &rest[start..];
        (!word.iter().any(|&b| ends_word(b))).then_some(word)
    }

    /// Fields of spaces, digits and sometimes other bytes.
    fn column_field<const N: usize>() -> impl Strategy<Value = [u8; N]> {
        proptest::collection::vec(
            prop_oneof![
                6 => Just(b' '),
                3 => proptest::sample::select(b"0123456789ABCDEF".to_vec()),
                1 => proptest::sample::select(b"\t\r\n\x00\x1f!\x7f\x80\xa0\xff".to_vec()),
                1 => any::<u8>(),
            ],
            N,
        )
        .prop_map(|v| v.try_into().unwrap())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        #[test]
        fn right_aligned_reads_as_one_by_one(
            eight in column_field::<9>(),
            four in column_field::<5>(),
        ) {
            prop_assert_eq!(right_aligned(&eight), right_aligned_one_by_one(&eight));
            prop_assert_eq!(right_aligned(&four), right_aligned_one_by_one(&four));
        }

        /// The digits read at once are the digits read one by one.
        #[test]
        fn eight_digits_read_as_one_by_one(bytes in mostly_digits()) {
            let n = bytes.iter().take_while(|b| b.is_ascii_digit()).count();
            let value = bytes[..n].iter().fold(0u64, |v, &b| v * 10 + u64::from(b - b'0'));
            let expected = (n < 8).then_some((value, n));
            prop_assert_eq!(eight_digits(u64::from_le_bytes(bytes)), expected);
        }

        #[test]
        fn bytes_read_as_one_by_one_on_data_runs(line in data_run(), n in 0usize..=FD_MAX_LEN) {
            agrees(&line, 0, n)?;
        }

        #[test]
        fn bytes_read_as_one_by_one_on_any_bytes(
            line in proptest::collection::vec(any::<u8>(), 0..200),
            pos in 0usize..8,
            n in 0usize..=FD_MAX_LEN,
        ) {
            agrees(&line, pos, n)?;
        }
    }
}
