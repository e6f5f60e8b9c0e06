//! The white-space separated fields of a TRC line, and the numbers in them.

use crate::logs::{Found, LogFormat, SyntaxError};
use crate::Error;

/// Whether `b` separates fields: PEAK writes spaces; tabs are taken too.
#[inline]
pub(super) const fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// `line` without its line end and trailing white space.
pub(super) fn trim_end(line: &[u8]) -> &[u8] {
    let end = line
        .iter()
        .rposition(|&b| !matches!(b, b' ' | b'\t' | b'\r' | b'\n'))
        .map_or(0, |i| i + 1);
    line.get(..end).unwrap_or_default()
}

/// The fields of one line, left to right, each with its 0-based start.
#[derive(Debug, Clone)]
pub(super) struct Tokens<'l> {
    line: &'l [u8],
    pos: usize,
}

impl<'l> Tokens<'l> {
    /// Return the fields of `line` (already trimmed at its end).
    pub(super) const fn new(line: &'l [u8]) -> Self {
        Tokens { line, pos: 0 }
    }

    /// Return the next field and its 0-based start, or `None` at the end.
    pub(super) fn next_token(&mut self) -> Option<(usize, &'l [u8])> {
        let rest = self.line.get(self.pos..).unwrap_or_default();
        let skip = rest.iter().position(|&b| !is_space(b))?;
        let start = self.pos + skip;
        let field = self.line.get(start..).unwrap_or_default();
        let len = field
            .iter()
            .position(|&b| is_space(b))
            .unwrap_or(field.len());
        self.pos = start + len;
        Some((start, field.get(..len).unwrap_or_default()))
    }

    /// Return what stands at the 0-based index `at` of the line.
    pub(super) fn found_at(&self, at: usize) -> Found {
        self.line
            .get(at)
            .map_or(Found::EndOfLine, |&b| Found::Byte(b))
    }

    /// Return the next field without taking it.
    pub(super) fn peek(&self) -> Option<(usize, &'l [u8])> {
        self.clone().next_token()
    }

    /// Return the 1-based column just past the line, where "the end of the
    /// line" is reported.
    pub(super) const fn end_column(&self) -> usize {
        self.line.len() + 1
    }

    /// Return the next field, or `error` of the end of the line.
    pub(super) fn expect(
        &mut self,
        error: fn(Found) -> SyntaxError,
    ) -> Result<(usize, &'l [u8]), Error> {
        match self.next_token() {
            Some(token) => Ok(token),
            None => Err(syntax(self.end_column(), error(Found::EndOfLine))),
        }
    }
}

/// The error `reason` at the 1-based `column` of a TRC line.
#[inline]
pub(super) const fn syntax(column: usize, reason: SyntaxError) -> Error {
    Error::Syntax {
        format: LogFormat::Trc,
        column,
        reason,
    }
}

/// The error `reason` for the field starting at 0-based `start`: the column
/// and byte of its first byte, or of `bad` bytes into it.
pub(super) fn bad_field(
    start: usize,
    field: &[u8],
    bad: usize,
    reason: fn(Found) -> SyntaxError,
) -> Error {
    let found = field.get(bad).map_or(Found::EndOfLine, |&b| Found::Byte(b));
    syntax(start + bad + 1, reason(found))
}

/// The index of the first byte of `field` that is not a decimal digit.
fn first_non_digit(field: &[u8]) -> Option<usize> {
    field.iter().position(|b| !b.is_ascii_digit())
}

/// Read `field` as a decimal number of at most `max`, or `None`.
pub(super) fn decimal(field: &[u8], max: u64) -> Option<u64> {
    if field.is_empty() || field.len() > 19 || first_non_digit(field).is_some() {
        return None;
    }
    let value = field
        .iter()
        .fold(0u64, |acc, &b| acc * 10 + u64::from(b - b'0'));
    (value <= max).then_some(value)
}

/// Read `field` as hex digits (at most 8), or `None`.
pub(super) fn hex(field: &[u8]) -> Option<u32> {
    if field.is_empty() || field.len() > 8 {
        return None;
    }
    field.iter().try_fold(0u32, |acc, &b| {
        let digit = char::from(b).to_digit(16)?;
        Some(acc << 4 | digit)
    })
}

/// Read a data byte of exactly two hex digits.
pub(super) fn hex_byte(field: &[u8]) -> Option<u8> {
    match field {
        [_, _] => hex(field).and_then(|v| u8::try_from(v).ok()),
        _ => None,
    }
}

/// Read a decimal number `digits[.fraction]` into its integer part and up
/// to `max_fraction` fraction digits scaled to `10^max_fraction`; more
/// fraction digits are the error's index when `strict`, else dropped. The
/// error is the index of the offending byte.
pub(super) fn decimal_fraction(
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
