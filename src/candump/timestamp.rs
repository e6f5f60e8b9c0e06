//! The one timestamp parser, `(seconds.fraction)` (SPEC §5.1, §5.2): the
//! fixed `candump -l` template for the fast path, the general form with
//! SWAR, and the byte-by-byte form for the rest; the tests check that the
//! three agree.

use super::*;

/// Read the template `candump -l` writes, `(SSSSSSSSSS.UUUUUU) ` (ten digits
/// of seconds, six of microseconds, a space), from the first 20 bytes of a
/// line: the 16 digits in two words (seconds 1–8, then seconds 9–10 and
/// microseconds 1–6). `None` for any other shape, which
/// [`parse_timestamp`] then reads or reports.
#[inline(always)]
pub(super) fn parse_canonical_timestamp(head: &[u8; 20]) -> Option<Timestamp> {
    if head[0] != b'(' || head[11] != b'.' || head[18] != b')' || head[19] != b' ' {
        return None;
    }
    let word = |at: usize| head.get(at..).and_then(|s| s.first_chunk::<8>()).copied();
    let high = u64::from_le_bytes(word(1)?) ^ ZERO_CHARS64;
    let low = (u64::from(u16::from_le_bytes([head[9], head[10]]))
        | u64::from_le_bytes(word(12)?) << 16)
        ^ ZERO_CHARS64;
    if non_digits64(high) | non_digits64(low) != 0 {
        return None;
    }
    let all = decimal8(high) * 100_000_000 + decimal8(low);
    Timestamp::new(all / 1_000_000, (all % 1_000_000) as u32)
}

/// Read `(seconds.fraction)` starting at the `(` at `open`; return the
/// timestamp and the index after `)`.
#[inline(always)]
pub(super) fn parse_timestamp(line: &[u8], open: usize) -> Result<(Timestamp, usize)> {
    let start = open + 1;
    let d = load16(line, start) ^ ZERO_CHARS;
    let digits = lanes_before(non_digits(d));
    let secs = if (1..16).contains(&digits) {
        // Right-align the digits: the lanes shifted in are leading zeros.
        decimal16(d << (8 * (16 - digits)))
    } else {
        return parse_timestamp_slow(line, open);
    };
    let point = start + digits;
    if line.get(point) != Some(&b'.') {
        return Err(bad_timestamp(line, point));
    }
    let frac_start = point + 1;
    let d = load16(line, frac_start) ^ ZERO_CHARS;
    let frac_digits = lanes_before(non_digits(d));
    if !(1..=6).contains(&frac_digits) {
        return Err(bad_timestamp(line, frac_start + frac_digits.min(6)));
    }
    let close = frac_start + frac_digits;
    if line.get(close) != Some(&b')') {
        return Err(bad_timestamp(line, close));
    }
    let fraction = decimal8((d << (8 * (8 - frac_digits))) as u64) as u32;
    let micros = fraction * POW10[6 - frac_digits];
    Ok((Timestamp::new(secs, micros).unwrap_or_default(), close + 1))
}

pub(super) const POW10: [u32; 7] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000];

#[cold]
pub(super) fn bad_timestamp(line: &[u8], at: usize) -> Error {
    error(
        at,
        SyntaxError::BadTimestamp {
            found: found(line, at),
        },
    )
}

/// The timestamp byte by byte: for no digits, and for 16 or more digits of
/// seconds (up to `u64::MAX`).
#[cold]
#[inline(never)]
pub(super) fn parse_timestamp_slow(line: &[u8], open: usize) -> Result<(Timestamp, usize)> {
    let mut at = open + 1;
    let mut secs: u64 = 0;
    while let Some(&b) = line.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        secs = match secs
            .checked_mul(10)
            .and_then(|s| s.checked_add(u64::from(b - b'0')))
        {
            Some(s) => s,
            None => return Err(bad_timestamp(line, at)),
        };
        at += 1;
    }
    if at == open + 1 || line.get(at) != Some(&b'.') {
        return Err(bad_timestamp(line, at));
    }
    at += 1;
    let frac_start = at;
    let mut micros: u32 = 0;
    while let Some(&b) = line.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        if at - frac_start == 6 {
            return Err(bad_timestamp(line, at));
        }
        micros = micros * 10 + u32::from(b - b'0');
        at += 1;
    }
    let frac_digits = at - frac_start;
    if frac_digits == 0 || line.get(at) != Some(&b')') {
        return Err(bad_timestamp(line, at));
    }
    let micros = micros * POW10[6 - frac_digits];
    Ok((Timestamp::new(secs, micros).unwrap_or_default(), at + 1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The fixed template, the general SWAR form and the byte-by-byte
        /// form read the same timestamp.
        #[test]
        fn the_three_forms_agree(secs in 0u64..10_000_000_000, micros in 0u32..1_000_000) {
            let text = format!("({secs:010}.{micros:06}) ");
            let head: &[u8; 20] = text.as_bytes().first_chunk().unwrap();
            let expected = Timestamp::new(secs, micros).unwrap();
            prop_assert_eq!(parse_canonical_timestamp(head), Some(expected));
            prop_assert_eq!(parse_timestamp(text.as_bytes(), 0), Ok((expected, 19)));
            prop_assert_eq!(parse_timestamp_slow(text.as_bytes(), 0), Ok((expected, 19)));
        }

        #[test]
        fn other_shapes_are_not_the_template(bytes in proptest::array::uniform20(any::<u8>())) {
            if let Some(ts) = parse_canonical_timestamp(&bytes) {
                prop_assert_eq!(parse_timestamp(&bytes, 0).map(|(t, _)| t), Ok(ts));
            }
        }
    }
}
