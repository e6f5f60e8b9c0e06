//! The one timestamp parser, `(seconds.fraction)` (docs/formats.md#candump-log,
//! docs/formats.md#candump-screen): the fixed `candump -l` template for the
//! fast path, the general form with SWAR, and the byte-by-byte form for the
//! rest; the tests check that the three agree.

use super::error::error;
use crate::can::Timestamp;
use crate::logs::calendar::{days_in_month, days_since_epoch};
use crate::logs::error::Result;
use crate::logs::lex::found;
use crate::logs::lex::swar::{
    decimal16, decimal8, lanes_before, load16, non_digits, HIGH, LOW7, ZERO_CHARS,
};
use crate::logs::lex::POW10_NANOS;
use crate::logs::FormatError;
use crate::logs::SyntaxError;

/// Read the template `candump -l` writes, `(SSSSSSSSSS.UUUUUU) ` (ten digits
/// of seconds, six of microseconds, a space), from the first 20 bytes of a
/// line, as three words (bytes 0–7, 8–15, 16–19). Each is XORed with the
/// template ([`TEMPLATE`], `'0'` where a digit stands): a digit becomes its
/// value, a byte of the template 0, so that one check per word tells the
/// shape ([`off_template`]) and the digits are read where they stand,
/// without a division. `None` for any other shape, which
/// [`parse_timestamp`] then reads or reports.
#[inline(always)]
pub(super) fn parse_canonical_timestamp(head: &[u8; 20]) -> Option<Timestamp> {
    let [w0, w1, w2] = TEMPLATE_WORDS;
    let [p0, p1, p2] = TEMPLATE_PLACES;
    let (first, rest) = head.split_first_chunk::<8>()?;
    let (second, third) = rest.split_first_chunk::<8>()?;
    let third: &[u8; 4] = third.first_chunk()?;
    let a = u64::from_le_bytes(*first) ^ w0;
    let b = u64::from_le_bytes(*second) ^ w1;
    let c = u64::from(u32::from_le_bytes(*third)) ^ w2;
    if off_template(a, p0) | off_template(b, p1) | off_template(c, p2) != 0 {
        return None;
    }
    // a: `(` s1 … s7, b: s8 s9 s10 `.` u1 … u4, c: u5 u6 `) `, one value a
    // lane (0 for the template's own bytes).
    let s1_s2 = (a >> 8) & 0xFFFF;
    let s3_s10 = (a >> 24) | (b << 40);
    let secs = ((s1_s2 & 0xFF) * 10 + (s1_s2 >> 8)) * 100_000_000 + decimal8(s3_s10);
    let micros = decimal8(((b >> 16) & !0xFFFF) | (c << 48));
    Timestamp::new(secs, micros as u32)
}

/// The fixed timestamp of the `candump -l` template, `'0'` for each digit.
const TEMPLATE: &[u8; 20] = b"(0000000000.000000) ";

/// [`TEMPLATE`] as the three words [`parse_canonical_timestamp`] loads.
const TEMPLATE_WORDS: [u64; 3] = {
    let t = TEMPLATE;
    [
        u64::from_le_bytes([t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7]]),
        u64::from_le_bytes([t[8], t[9], t[10], t[11], t[12], t[13], t[14], t[15]]),
        u32::from_le_bytes([t[16], t[17], t[18], t[19]]) as u64,
    ]
};

/// For each lane of [`TEMPLATE_WORDS`], what [`off_template`] adds: 0x76
/// where a digit stands (a value above 9 then reaches the high bit), 0x7F
/// where the template has its own byte (anything but 0 does), 0 past the
/// end.
const TEMPLATE_PLACES: [u64; 3] = {
    let mut places = [0u64; 3];
    let mut i = 0;
    while i < TEMPLATE.len() {
        let add: u64 = if TEMPLATE[i] == b'0' { 0x76 } else { 0x7F };
        places[i / 8] |= add << (8 * (i % 8));
        i += 1;
    }
    places
};

/// The high bit of every lane of `x` (the bytes XOR the template) that is
/// off the template: a digit's lane above 9, a fixed byte's lane other than
/// 0, or a byte of 0x80 or more.
#[inline(always)]
const fn off_template(x: u64, places: u64) -> u64 {
    let low7 = LOW7 as u64;
    (((x & low7) + places) | x) & HIGH as u64
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
        return parse_timestamp_slow(line, open);
    }
    let frac_start = point + 1;
    let d = load16(line, frac_start) ^ ZERO_CHARS;
    let frac_digits = lanes_before(non_digits(d));
    if !(1..=6).contains(&frac_digits) {
        // Nanoseconds (`candump -N`), or an error: the byte-by-byte reader
        // says which.
        return parse_timestamp_slow(line, open);
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
pub(super) fn bad_timestamp(line: &[u8], at: usize) -> FormatError {
    error(
        at,
        SyntaxError::BadTimestamp {
            found: found(line, at),
        },
    )
}

/// The timestamp byte by byte: for no digits, and for 16 or more digits of
/// seconds (up to `u64::MAX`).
/// The byte-by-byte reader of every timestamp form: `(seconds.fraction)`
/// with 1 to 9 digits of fraction (`candump -N` writes nanoseconds), and
/// `candump -t A`'s local date and time `(2026-11-22 10:11:12.123456)`,
/// read as UTC (the decision in docs/formats.md#candump-screen).
#[cold]
#[inline(never)]
pub(super) fn parse_timestamp_slow(line: &[u8], open: usize) -> Result<(Timestamp, usize)> {
    let start = open + 1;
    let (secs, at) = decimal(line, start, u64::MAX)?;
    let (secs, at) = match line.get(at) {
        Some(b'-') if at - start == 4 => parse_date_time(line, start, secs)?,
        _ => (secs, at),
    };
    if at == start || line.get(at) != Some(&b'.') {
        return Err(bad_timestamp(line, at));
    }
    let frac_start = at + 1;
    let mut at = frac_start;
    let mut nanos: u32 = 0;
    while let Some(&b) = line.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        if at - frac_start == 9 {
            return Err(bad_timestamp(line, at));
        }
        nanos = nanos * 10 + u32::from(b - b'0');
        at += 1;
    }
    let frac_digits = at - frac_start;
    if frac_digits == 0 || line.get(at) != Some(&b')') {
        return Err(bad_timestamp(line, at));
    }
    let nanos = nanos * POW10_NANOS[9 - frac_digits];
    Ok((
        Timestamp::from_nanos(secs, nanos).unwrap_or_default(),
        at + 1,
    ))
}

/// Read decimal digits from `at` up to a value of `max`; return the value
/// and where the digits end.
fn decimal(line: &[u8], mut at: usize, max: u64) -> Result<(u64, usize)> {
    let mut value: u64 = 0;
    while let Some(&b) = line.get(at) {
        if !b.is_ascii_digit() {
            break;
        }
        value = match value
            .checked_mul(10)
            .and_then(|v| v.checked_add(u64::from(b - b'0')))
        {
            Some(v) if v <= max => v,
            _ => return Err(bad_timestamp(line, at)),
        };
        at += 1;
    }
    Ok((value, at))
}

/// Read exactly `width` digits at `at`, at most `max`, followed by `sep`.
fn field(line: &[u8], at: usize, width: usize, max: u64, sep: u8) -> Result<(u64, usize)> {
    let (value, end) = decimal(line, at, max)?;
    if end != at + width {
        return Err(bad_timestamp(line, end.min(at + width)));
    }
    if line.get(end) != Some(&sep) {
        return Err(bad_timestamp(line, end));
    }
    Ok((value, end + 1))
}

/// `YYYY-MM-DD HH:MM:SS` after the year at `start`: seconds since the Unix
/// epoch, UTC, and where the seconds end (at the `.`).
fn parse_date_time(line: &[u8], start: usize, year: u64) -> Result<(u64, usize)> {
    if year < 1970 {
        return Err(bad_timestamp(line, start));
    }
    let (month, at) = field(line, start + 5, 2, 12, b'-')?;
    let (day, at) = field(line, at, 2, 31, b' ')?;
    if month == 0 || day == 0 || day > days_in_month(year, month) {
        return Err(bad_timestamp(line, start + 5));
    }
    let (hour, at) = field(line, at, 2, 23, b':')?;
    let (minute, at) = field(line, at, 2, 59, b':')?;
    // 60: a leap second as `strftime` may print it.
    let (second, end) = decimal(line, at, 60)?;
    if end != at + 2 {
        return Err(bad_timestamp(line, end.min(at + 2)));
    }
    let days = days_since_epoch(year, month, day);
    Ok((days * 86_400 + hour * 3_600 + minute * 60 + second, end))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::logs::calendar::is_leap;
    use proptest::prelude::*;

    #[test]
    fn nanoseconds_as_candump_n_writes_them() {
        assert_eq!(
            parse_timestamp(b"(1700000000.000500001) ", 0),
            Ok((Timestamp::from_nanos(1_700_000_000, 500_001).unwrap(), 22))
        );
        assert_eq!(
            parse_timestamp(b"(001.1234567)", 0),
            Ok((Timestamp::from_nanos(1, 123_456_700).unwrap(), 13))
        );
        assert!(parse_timestamp(b"(1.1234567890)", 0).is_err());
    }

    #[test]
    fn dates_as_candump_t_capital_a_writes_them() {
        // date -u -d '2026-11-22 10:11:12' +%s
        assert_eq!(
            parse_timestamp(b"(2026-11-22 10:11:12.123456) can0", 0),
            Ok((Timestamp::new(1_795_342_272, 123_456).unwrap(), 28))
        );
        assert_eq!(
            parse_timestamp(b"(1970-01-01 00:00:00.000000)", 0),
            Ok((Timestamp::new(0, 0).unwrap(), 28))
        );
        // A leap day, and nanoseconds (-t A -N).
        assert_eq!(
            parse_timestamp(b"(2024-02-29 23:59:59.000000001)", 0),
            Ok((Timestamp::from_nanos(1_709_251_199, 1).unwrap(), 31))
        );
        for bad in [
            &b"(2023-02-29 00:00:00.0)"[..],
            b"(2026-13-01 00:00:00.0)",
            b"(2026-00-01 00:00:00.0)",
            b"(2026-11-22 24:00:00.0)",
            b"(2026-11-22 10:60:00.0)",
            b"(1969-12-31 23:59:59.0)",
            b"(2026-11-2 10:11:12.0)",
            b"(2026-11-22T10:11:12.0)",
            b"(2026-11-22 10:11:12)",
        ] {
            assert!(
                parse_timestamp(bad, 0).is_err(),
                "{}",
                String::from_utf8_lossy(bad)
            );
        }
    }

    proptest! {
        #[test]
        fn dates_agree_with_the_calendar(secs in 0u64..253_402_300_800, micros in 0u32..1_000_000) {
            // The civil date of `secs`, by counting days forward (the model).
            let mut days = secs / 86_400;
            let mut year = 1970;
            loop {
                let len = if is_leap(year) { 366 } else { 365 };
                if days < len { break; }
                days -= len;
                year += 1;
            }
            let mut month = 1;
            while days >= days_in_month(year, month) {
                days -= days_in_month(year, month);
                month += 1;
            }
            let rest = secs % 86_400;
            let text = format!(
                "({year:04}-{month:02}-{:02} {:02}:{:02}:{:02}.{micros:06})",
                days + 1, rest / 3600, rest / 60 % 60, rest % 60
            );
            prop_assert_eq!(
                parse_timestamp(text.as_bytes(), 0),
                Ok((Timestamp::new(secs, micros).unwrap(), text.len()))
            );
        }
    }

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

        /// The template's words read exactly the lines a byte-by-byte check
        /// of the shape accepts, the same time as the byte-by-byte reader:
        /// valid templates with up to three bytes replaced by the bytes that
        /// matter (digits, the template's own, their neighbours, the high
        /// half) or by any byte.
        #[test]
        fn the_template_is_its_shape_byte_by_byte(
            secs in 0u64..10_000_000_000,
            micros in 0u32..1_000_000,
            edits in proptest::collection::vec((0usize..20, prop_oneof![
                proptest::sample::select(b"0123456789/:().- \x00\x7f\x80\xb0\xff".to_vec()),
                any::<u8>(),
            ]), 0..=3),
        ) {
            let mut head = [0u8; 20];
            head.copy_from_slice(format!("({secs:010}.{micros:06}) ").as_bytes());
            for (at, byte) in edits {
                head[at] = byte;
            }
            let shape = head.iter().zip(TEMPLATE).all(|(&b, &t)| {
                if t == b'0' { b.is_ascii_digit() } else { b == t }
            });
            let expected = if shape {
                let (ts, end) = parse_timestamp_slow(&head, 0).expect("the shape is a timestamp");
                prop_assert_eq!(end, 19);
                Some(ts)
            } else {
                None
            };
            prop_assert_eq!(parse_canonical_timestamp(&head), expected);
        }

        #[test]
        fn other_shapes_are_not_the_template(bytes in proptest::array::uniform20(any::<u8>())) {
            if let Some(ts) = parse_canonical_timestamp(&bytes) {
                prop_assert_eq!(parse_timestamp(&bytes, 0).map(|(t, _)| t), Ok(ts));
            }
        }
    }
}
