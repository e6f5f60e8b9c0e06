//! The one line layer of the text readers (candump, ASC, TRC; SPEC §5,
//! §5.7): a buffer split into lines at `\n` (16 bytes at a time), the hex
//! digits every format writes, and — with `std` — whole lines read from a
//! [`std::io::Read`] a block at a time, with the over-long-line rule that
//! keeps memory bounded whatever the input.
//!
//! A line is the bytes before a `\n`, without it; a last line without one
//! counts too, nothing after a final `\n` does. A `\r` before the `\n`
//! (CRLF files) stays on the line: every format's parser reads it as
//! trailing white space. A NUL byte is an ordinary byte of its line, never
//! a line end: the format's parser reports the line as malformed, with the
//! column of the NUL, and the reading goes on with the next line.

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
        let hits = first_eq(w, b'\n');
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

/// A mask with the high bit set in the lanes (bytes) of `w` holding `b`
/// (and possibly in later lanes: the first set lane is exact).
#[inline(always)]
const fn first_eq(w: u128, b: u8) -> u128 {
    const ONES: u128 = u128::from_le_bytes([0x01; 16]);
    const HIGH: u128 = u128::from_le_bytes([0x80; 16]);
    let x = w ^ (ONES * b as u128);
    x.wrapping_sub(ONES) & !x & HIGH
}

/// The hex value of one character, or `None`: the hex digits of every
/// text format (either case).
#[inline]
pub(crate) const fn hex_value(b: u8) -> Option<u8> {
    match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'A'..=b'F' => Some(b - b'A' + 10),
        b'a'..=b'f' => Some(b - b'a' + 10),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn first_eq_finds_the_first_lane(bytes in proptest::array::uniform16(any::<u8>()), b in any::<u8>()) {
            let first = bytes.iter().position(|&x| x == b).unwrap_or(16);
            let mask = first_eq(u128::from_le_bytes(bytes), b);
            prop_assert_eq!((mask.trailing_zeros() / 8) as usize, first);
        }

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

    #[test]
    fn hex_digits_in_either_case() {
        for (b, v) in [(b'0', 0), (b'9', 9), (b'a', 10), (b'F', 15)] {
            assert_eq!(hex_value(b), Some(v));
        }
        for b in [b'g', b'G', b' ', 0, b'/', b':', b'@', b'`'] {
            assert_eq!(hex_value(b), None);
        }
    }
}
