//! The civil calendar the readers turn logged dates into Unix time with
//! (candump `-t A`, BLF's `SYSTEMTIME`; docs/formats.md#timestamps), proleptic
//! Gregorian, UTC.

/// Whether `year` is a leap year (proleptic Gregorian calendar).
pub(crate) const fn is_leap(year: u64) -> bool {
    year % 4 == 0 && (year % 100 != 0 || year % 400 == 0)
}

/// The days of `month` (1..=12) in `year`.
pub(crate) const fn days_in_month(year: u64, month: u64) -> u64 {
    match month {
        2 if is_leap(year) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Days from 1970-01-01 to the date (proleptic Gregorian calendar; the
/// year is at least 1970 and below 10 000, the month 1..=12).
pub(crate) const fn days_since_epoch(year: u64, month: u64, day: u64) -> u64 {
    // Count years from March on, so that the leap day ends a year.
    let (y, m) = if month <= 2 {
        (year - 1, month + 9)
    } else {
        (year, month - 3)
    };
    let year_days = y * 365 + y / 4 - y / 100 + y / 400;
    let day_of_year = (153 * m + 2) / 5 + day - 1;
    // 719_468: days from 0000-03-01 to 1970-01-01.
    year_days + day_of_year - 719_468
}
