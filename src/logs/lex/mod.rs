//! The one lexical layer of the text formats (candump, ASC, TRC;
//! docs/formats.md): the white-space separated fields of a line, the
//! decimal and hex numbers in them, the error of a line at its column, and
//! the wide-word tricks of the fast paths ([`swar`]). Each format's parser
//! reads its line with these and nothing of another format's.

pub(crate) mod swar;

use crate::logs::FormatError;
use crate::logs::{Found, LogFormat, SyntaxError};

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

/// Hex values by character; 0xF0 marks a character that is no hex digit.
pub(crate) const HEX_TABLE: [u8; 256] = {
    let mut table = [0xF0u8; 256];
    let mut i = 0;
    while i < 256 {
        if let Some(v) = hex_value(i as u8) {
            table[i] = v;
        }
        i += 1;
    }
    table
};

/// `10^(9 - d)`, at index `9 - d`: what a fraction of `d` decimal digits
/// is multiplied by to give nanoseconds (`POW10_NANOS[9 - d]`), for the text
/// readers' timestamps.
pub(crate) const POW10_NANOS: [u32; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// Whether `b` separates fields: the writers write spaces; tabs are taken
/// too.
#[inline(always)]
pub(crate) const fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// `line` without its line end and trailing white space.
#[inline]
pub(crate) fn trim_end(line: &[u8]) -> &[u8] {
    let end = line
        .iter()
        .rposition(|&b| !matches!(b, b' ' | b'\t' | b'\r' | b'\n'))
        .map_or(0, |i| i + 1);
    line.get(..end).unwrap_or_default()
}

/// The index of the first byte at or after `at` that is not a space or tab.
#[inline(always)]
pub(crate) fn skip_space(line: &[u8], mut at: usize) -> usize {
    while let Some(&b) = line.get(at) {
        if !is_space(b) {
            break;
        }
        at += 1;
    }
    at
}

/// What stands at the 0-based index `at` of `line`.
#[inline]
pub(crate) fn found(line: &[u8], at: usize) -> Found {
    line.get(at).map_or(Found::EndOfLine, |&b| Found::Byte(b))
}

/// The error `reason` at the 1-based `column` of a line of `format`.
#[inline]
pub(crate) const fn syntax(format: LogFormat, column: usize, reason: SyntaxError) -> FormatError {
    FormatError::Syntax {
        format,
        column,
        reason,
    }
}

/// The error `reason` for the field starting at 0-based `start` of a line
/// of `format`: the column and byte of the field's byte `bad` (the end of
/// the line when the field has no such byte).
pub(crate) fn bad_field(
    format: LogFormat,
    start: usize,
    field: &[u8],
    bad: usize,
    reason: fn(Found) -> SyntaxError,
) -> FormatError {
    syntax(format, start + bad + 1, reason(found(field, bad)))
}

/// The white-space separated fields of one line of `format`, left to
/// right, each with its 0-based start.
#[derive(Debug, Clone)]
pub(crate) struct Tokens<'l> {
    format: LogFormat,
    line: &'l [u8],
    pos: usize,
}

impl<'l> Tokens<'l> {
    /// Return the fields of `line` (already trimmed at its end), a line of
    /// `format`.
    pub(crate) const fn new(format: LogFormat, line: &'l [u8]) -> Self {
        Tokens {
            format,
            line,
            pos: 0,
        }
    }

    /// Return the next field and its 0-based start, or `None` at the end.
    #[inline]
    pub(crate) fn next_token(&mut self) -> Option<(usize, &'l [u8])> {
        let line = self.line;
        let mut start = self.pos;
        while line.get(start).is_some_and(|&b| is_space(b)) {
            start += 1;
        }
        if start >= line.len() {
            self.pos = start;
            return None;
        }
        let mut end = start + 1;
        while line.get(end).is_some_and(|&b| !is_space(b)) {
            end += 1;
        }
        self.pos = end;
        Some((start, line.get(start..end).unwrap_or_default()))
    }

    /// Return the next field without taking it.
    pub(crate) fn peek(&self) -> Option<(usize, &'l [u8])> {
        self.clone().next_token()
    }

    /// Return what stands at the 0-based index `at` of the line.
    pub(crate) fn found_at(&self, at: usize) -> Found {
        found(self.line, at)
    }

    /// Return the 1-based column just past the line, where "the end of the
    /// line" is reported.
    pub(crate) const fn end_column(&self) -> usize {
        self.line.len() + 1
    }

    /// Return the next field, or the error `reason` of the end of the line.
    pub(crate) fn expect(
        &mut self,
        reason: fn(Found) -> SyntaxError,
    ) -> Result<(usize, &'l [u8]), FormatError> {
        match self.next_token() {
            Some(token) => Ok(token),
            None => Err(self.error_at(self.line.len(), reason)),
        }
    }

    /// The error `reason` for what stands at the 0-based index `at`.
    pub(crate) fn error_at(&self, at: usize, reason: fn(Found) -> SyntaxError) -> FormatError {
        syntax(self.format, at + 1, reason(self.found_at(at)))
    }
}

/// The index of the first byte of `field` that is not a decimal digit.
pub(crate) fn first_non_digit(field: &[u8]) -> Option<usize> {
    field.iter().position(|b| !b.is_ascii_digit())
}

/// Read `field` as a decimal number of at most `max`, or `None`.
pub(crate) fn decimal(field: &[u8], max: u64) -> Option<u64> {
    if field.is_empty() || field.len() > 19 || !field.iter().all(u8::is_ascii_digit) {
        return None;
    }
    let value = field
        .iter()
        .fold(0u64, |acc, &b| acc * 10 + u64::from(b - b'0'));
    (value <= max).then_some(value)
}

/// Read `field` as 1 to 8 hex digits (an identifier, CAN FD flags), or
/// `None`.
#[inline(always)]
pub(crate) fn hex(field: &[u8]) -> Option<u32> {
    if field.is_empty() || field.len() > 8 {
        return None;
    }
    let mut value = 0u32;
    for &b in field {
        value = value << 4 | u32::from(hex_value(b)?);
    }
    Some(value)
}

/// Read `field` as exactly one hex digit, or `None`.
pub(crate) fn hex_digit(field: &[u8]) -> Option<u8> {
    match field {
        [b] => hex_value(*b),
        _ => None,
    }
}

/// Read a data byte of exactly two hex digits, or `None`.
pub(crate) fn hex_byte(field: &[u8]) -> Option<u8> {
    match field {
        [_, _] => hex(field).and_then(|v| u8::try_from(v).ok()),
        _ => None,
    }
}

/// Whether `a` and `b` are the same ASCII text but for case.
pub(crate) fn eq_ignore_case(a: &[u8], b: &[u8]) -> bool {
    a.eq_ignore_ascii_case(b)
}

/// Whether `text` starts with `prefix`, ASCII case ignored.
pub(crate) fn starts_with_ignore_case(text: &[u8], prefix: &[u8]) -> bool {
    text.get(..prefix.len())
        .is_some_and(|head| head.eq_ignore_ascii_case(prefix))
}

/// Read a decimal number `digits[.fraction]` into its integer part and up
/// to `max_fraction` fraction digits scaled to `10^max_fraction`; more
/// fraction digits are the error's index when `strict`, else dropped. The
/// error is the index of the offending byte.
pub(crate) fn decimal_fraction(
    field: &[u8],
    max_integer: usize,
    max_fraction: u32,
    strict: bool,
) -> Result<(u64, u128), usize> {
    let point = field.iter().position(|&b| b == b'.');
    let (integer, fraction) = match point {
        Some(p) => (
            field.get(..p).unwrap_or_default(),
            field.get(p + 1..).unwrap_or_default(),
        ),
        None => (field, &[][..]),
    };
    if integer.is_empty() {
        return Err(0);
    }
    if let Some(bad) = first_non_digit(integer) {
        return Err(bad);
    }
    if integer.len() > max_integer {
        return Err(max_integer);
    }
    let whole = integer
        .iter()
        .fold(0u64, |acc, &b| acc * 10 + u64::from(b - b'0'));
    let fraction_start = integer.len() + 1;
    if let Some(bad) = first_non_digit(fraction) {
        return Err(fraction_start + bad);
    }
    if point.is_some() && fraction.is_empty() && strict {
        return Err(fraction_start);
    }
    let max = max_fraction as usize;
    if strict && fraction.len() > max {
        return Err(fraction_start + max);
    }
    let mut scaled: u128 = 0;
    for i in 0..max {
        let digit = fraction.get(i).map_or(0, |&b| u128::from(b - b'0'));
        scaled = scaled * 10 + digit;
    }
    Ok((whole, scaled))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_digits_in_either_case() {
        for (b, v) in [(b'0', 0), (b'9', 9), (b'a', 10), (b'F', 15)] {
            assert_eq!(hex_value(b), Some(v));
            assert_eq!(hex_digit(&[b]), Some(v));
        }
        for b in [b'g', b'G', b' ', 0, b'/', b':', b'@', b'`'] {
            assert_eq!(hex_value(b), None);
            assert_eq!(hex_digit(&[b]), None);
        }
    }

    #[test]
    fn numbers_in_fields() {
        assert_eq!(hex(b"7fF"), Some(0x7FF));
        assert_eq!(hex(b"123456789"), None);
        assert_eq!(hex(b""), None);
        assert_eq!(hex_byte(b"0a"), Some(0x0A));
        assert_eq!(hex_byte(b"a"), None);
        assert_eq!(decimal(b"65535", 65535), Some(65535));
        assert_eq!(decimal(b"65536", 65535), None);
        assert_eq!(decimal(b"1x", 9), None);
    }

    #[test]
    fn fields_with_their_columns() {
        let mut tokens = Tokens::new(LogFormat::Trc, b" ab\tc  d");
        assert_eq!(tokens.next_token(), Some((1, &b"ab"[..])));
        assert_eq!(tokens.peek(), Some((4, &b"c"[..])));
        assert_eq!(tokens.next_token(), Some((4, &b"c"[..])));
        assert_eq!(tokens.next_token(), Some((7, &b"d"[..])));
        let error = tokens
            .expect(|found| SyntaxError::TrcTrailing { found })
            .unwrap_err();
        assert_eq!(
            error,
            syntax(
                LogFormat::Trc,
                9,
                SyntaxError::TrcTrailing {
                    found: Found::EndOfLine
                }
            )
        );
    }
}
