//! A selection of a log's events by time and interface: [`EventFilter`],
//! with the bounds of its window, [`TimeBound`] (what `--from`, `--to` and
//! `--iface` of `motionwire decode` and `report` choose;
//! docs/output.md#window).

use core::fmt;
use core::str::FromStr;
use core::time::Duration;

use crate::can::{Iface, LogEvent, Timestamp};

use super::calendar::{days_in_month, days_since_epoch};

/// One end of a time window: seconds from the recording's start, or a
/// UTC time (compared with the log's own times, which are Unix time where
/// the log records a date; docs/formats.md#timestamps).
///
/// Parsed from `12.5` (seconds, up to nine decimals) or
/// `2023-11-14T22:13:20Z` (RFC 3339 in UTC: `Z` or `+00:00`, up to nine
/// decimals of the second); `Display` writes it back so.
///
/// ```
/// use core::time::Duration;
/// use motionwire::logs::TimeBound;
///
/// let start: TimeBound = "1.5".parse()?;
/// assert_eq!(start, TimeBound::SinceStart(Duration::from_millis(1_500)));
/// let at: TimeBound = "2023-11-14T22:13:20.25Z".parse()?;
/// assert_eq!(at.to_string(), "2023-11-14T22:13:20.25Z");
/// assert!("yesterday".parse::<TimeBound>().is_err());
/// # Ok::<(), motionwire::logs::TimeBoundError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeBound {
    /// This long after the recording's first time.
    SinceStart(Duration),
    /// This point in UTC, as Unix time.
    Utc(Timestamp),
}

/// Why a text is not a [`TimeBound`]: `Display` names the text and what
/// is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TimeBoundError {
    text: String,
    why: &'static str,
}

impl fmt::Display for TimeBoundError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:?} is not seconds from the start (12.5) or a UTC time \
             (2023-11-14T22:13:20Z): {}",
            self.text, self.why
        )
    }
}

impl std::error::Error for TimeBoundError {}

/// Parse `digits[.digits]` (at most nine decimals) as whole seconds and
/// nanoseconds.
fn seconds(text: &str) -> Result<(u64, u32), &'static str> {
    let (whole, fraction) = text.split_once('.').unwrap_or((text, ""));
    if whole.is_empty() || !whole.bytes().all(|b| b.is_ascii_digit()) {
        return Err("the seconds are not a decimal number");
    }
    if fraction.len() > 9 || !fraction.bytes().all(|b| b.is_ascii_digit()) {
        return Err("the fraction is not one to nine decimal digits");
    }
    if text.ends_with('.') {
        return Err("the fraction is not one to nine decimal digits");
    }
    let secs = whole.parse().map_err(|_| "too many seconds")?;
    let mut nanos = 0u32;
    for b in fraction.bytes().chain(core::iter::repeat(b'0')).take(9) {
        nanos = nanos * 10 + u32::from(b - b'0');
    }
    Ok((secs, nanos))
}

/// Parse `YYYY-MM-DDTHH:MM:SS[.fraction](Z|+00:00)` as Unix time.
fn utc(text: &str) -> Result<Timestamp, &'static str> {
    let body = text
        .strip_suffix('Z')
        .or_else(|| text.strip_suffix('z'))
        .or_else(|| text.strip_suffix("+00:00"))
        .ok_or("a UTC time ends with Z (or +00:00)")?;
    let (date, time) = body
        .split_once(['T', 't'])
        .ok_or("the date and the time are joined by T")?;
    let number = |part: &str, len: usize| -> Result<u64, &'static str> {
        if part.len() != len || !part.bytes().all(|b| b.is_ascii_digit()) {
            return Err("the date is YYYY-MM-DD and the time HH:MM:SS");
        }
        part.parse()
            .map_err(|_| "the date is YYYY-MM-DD and the time HH:MM:SS")
    };
    let mut date_parts = date.split('-');
    let mut next_date = || date_parts.next().unwrap_or("");
    let (year, month, day) = (
        number(next_date(), 4)?,
        number(next_date(), 2)?,
        number(next_date(), 2)?,
    );
    if date.split('-').count() != 3 {
        return Err("the date is YYYY-MM-DD and the time HH:MM:SS");
    }
    let (hms, fraction) = time.split_once('.').unwrap_or((time, ""));
    let mut time_parts = hms.split(':');
    let mut next_time = || time_parts.next().unwrap_or("");
    let (hour, minute, second) = (
        number(next_time(), 2)?,
        number(next_time(), 2)?,
        number(next_time(), 2)?,
    );
    if hms.split(':').count() != 3 {
        return Err("the date is YYYY-MM-DD and the time HH:MM:SS");
    }
    if year < 1970 {
        return Err("the year is before 1970, where Unix time starts");
    }
    if !(1..=12).contains(&month) || day == 0 || day > days_in_month(year, month) {
        return Err("there is no such day");
    }
    if hour > 23 || minute > 59 || second > 59 {
        return Err("there is no such time of day");
    }
    let nanos = if time.contains('.') {
        seconds(&["0.", fraction].concat())?.1
    } else {
        0
    };
    let secs = days_since_epoch(year, month, day) * 86_400 + hour * 3_600 + minute * 60 + second;
    Timestamp::from_nanos(secs, nanos).ok_or("there is no such time of day")
}

impl FromStr for TimeBound {
    type Err = TimeBoundError;

    fn from_str(text: &str) -> Result<Self, TimeBoundError> {
        let error = |why| TimeBoundError {
            text: text.to_owned(),
            why,
        };
        let trimmed = text.trim();
        if trimmed.contains(['T', 't', '-', ':']) {
            return utc(trimmed).map(TimeBound::Utc).map_err(error);
        }
        let (secs, nanos) = seconds(trimmed).map_err(error)?;
        Ok(TimeBound::SinceStart(Duration::new(secs, nanos)))
    }
}

/// Write up to nine decimals of `nanos`, without trailing zeros, after a
/// point; nothing for zero.
fn write_fraction(f: &mut fmt::Formatter<'_>, nanos: u32) -> fmt::Result {
    if nanos == 0 {
        return Ok(());
    }
    let digits = format!("{nanos:09}");
    write!(f, ".{}", digits.trim_end_matches('0'))
}

impl fmt::Display for TimeBound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TimeBound::SinceStart(after) => {
                write!(f, "{}", after.as_secs())?;
                write_fraction(f, after.subsec_nanos())
            }
            TimeBound::Utc(at) => {
                let secs = at.secs();
                let (mut days, rest) = (secs / 86_400, secs % 86_400);
                let mut year = 1970;
                loop {
                    let in_year = if super::calendar::is_leap(year) {
                        366
                    } else {
                        365
                    };
                    if days < in_year {
                        break;
                    }
                    days -= in_year;
                    year += 1;
                }
                let mut month = 1;
                while days >= days_in_month(year, month) {
                    days -= days_in_month(year, month);
                    month += 1;
                }
                write!(
                    f,
                    "{year:04}-{month:02}-{:02}T{:02}:{:02}:{:02}",
                    days + 1,
                    rest / 3_600,
                    rest / 60 % 60,
                    rest % 60
                )?;
                write_fraction(f, at.subsec_nanos())?;
                f.write_str("Z")
            }
        }
    }
}

/// Which events of a log to keep: those inside a time window and on some
/// interfaces. An empty filter keeps every event.
///
/// The window is `from <= time < to`, each end optional; a
/// [`TimeBound::SinceStart`] counts from the recording's start, the time
/// of the first event with a time that the filter is shown (all events
/// are shown, kept or not; [`restart`](Self::restart) begins a new
/// recording). With a window, an event without a time is not kept. With
/// interfaces, an event is kept when its interface's name is one of them,
/// or its channel number written in decimal is (`1` names channel 1); an
/// event without an interface is not kept. Both given, an event must pass
/// both.
///
/// ```
/// use motionwire::can::{BusStatus, Iface, LogEvent, Timestamp};
/// use motionwire::logs::{EventFilter, TimeBound};
///
/// let at = |secs, iface| {
///     LogEvent::Status(BusStatus {
///         timestamp: Timestamp::new(secs, 0),
///         iface: Some(iface),
///     })
/// };
/// let mut filter = EventFilter::new()
///     .from("1".parse::<TimeBound>()?)
///     .to("3".parse::<TimeBound>()?)
///     .iface("can0");
/// let kept: Vec<bool> = [
///     at(100, Iface::Name("can0")), // the start, before the window
///     at(101, Iface::Name("can0")),
///     at(102, Iface::Name("can1")), // another interface
///     at(103, Iface::Name("can0")), // the window's end is not in it
/// ]
/// .iter()
/// .map(|event| filter.keeps(event))
/// .collect();
/// assert_eq!(kept, [false, true, false, false]);
/// # Ok::<(), motionwire::logs::TimeBoundError>(())
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct EventFilter {
    from: Option<TimeBound>,
    to: Option<TimeBound>,
    names: Vec<String>,
    /// The names that are channel numbers.
    channels: Vec<u16>,
    /// The recording's first time, once an event with one is shown.
    start: Option<Timestamp>,
    /// Whether a window or a name is set: what [`keeps`](Self::keeps)
    /// asks first of every event.
    narrows: bool,
}

impl EventFilter {
    /// A filter that keeps every event.
    #[must_use]
    pub fn new() -> Self {
        EventFilter::default()
    }

    /// Keep only events at `bound` or later.
    #[must_use]
    pub fn from(mut self, bound: TimeBound) -> Self {
        self.from = Some(bound);
        self.narrows = true;
        self
    }

    /// Keep only events before `bound`.
    #[must_use]
    pub fn to(mut self, bound: TimeBound) -> Self {
        self.to = Some(bound);
        self.narrows = true;
        self
    }

    /// Keep events on the interface named `name` (or the channel it
    /// names, when it is a decimal number), beside those already named.
    #[must_use]
    pub fn iface(mut self, name: impl Into<String>) -> Self {
        let name = name.into();
        if let Ok(channel) = name.parse() {
            self.channels.push(channel);
        }
        self.names.push(name);
        self.narrows = true;
        self
    }

    /// Whether the filter keeps every event.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !self.narrows
    }

    /// Whether the filter has a time window.
    #[must_use]
    pub fn has_window(&self) -> bool {
        self.from.is_some() || self.to.is_some()
    }

    /// Begin a new recording: the next time shown is its start.
    pub fn restart(&mut self) {
        self.start = None;
    }

    /// The recording's start: the first time shown since the filter was
    /// made or restarted.
    #[must_use]
    pub fn start(&self) -> Option<Timestamp> {
        self.start
    }

    /// Show the filter the next event of the recording; return whether it
    /// is kept.
    #[inline]
    pub fn keeps(&mut self, event: &LogEvent<'_>) -> bool {
        if self.start.is_none() {
            self.start = event.timestamp();
        }
        if !self.narrows {
            return true;
        }
        if !self.names.is_empty() {
            let on = match event.iface() {
                Some(Iface::Name(name)) => self.names.iter().any(|n| n == name),
                Some(Iface::Channel(channel)) => self.channels.contains(&channel),
                None => false,
            };
            if !on {
                return false;
            }
        }
        if !self.has_window() {
            return true;
        }
        let (Some(time), Some(start)) = (event.timestamp(), self.start) else {
            return false;
        };
        let at = |bound: TimeBound| match bound {
            TimeBound::SinceStart(after) => start.checked_add(after),
            TimeBound::Utc(at) => Some(at),
        };
        if let Some(from) = self.from {
            match at(from) {
                Some(from) if time >= from => {}
                _ => return false,
            }
        }
        if let Some(to) = self.to {
            if let Some(to) = at(to) {
                if time >= to {
                    return false;
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::can::BusStatus;

    fn status(ts: Option<Timestamp>, iface: Option<Iface<'_>>) -> LogEvent<'_> {
        LogEvent::Status(BusStatus {
            timestamp: ts,
            iface,
        })
    }

    #[test]
    fn utc_times_are_unix_time() {
        let bound: TimeBound = "2023-11-14T22:13:20Z".parse().unwrap();
        assert_eq!(
            bound,
            TimeBound::Utc(Timestamp::new(1_700_000_000, 0).unwrap())
        );
        let bound: TimeBound = "2024-02-29T00:00:00.000001+00:00".parse().unwrap();
        assert_eq!(
            bound,
            TimeBound::Utc(Timestamp::new(1_709_164_800, 1).unwrap())
        );
        assert_eq!(bound.to_string(), "2024-02-29T00:00:00.000001Z");
        assert_eq!(
            "1970-01-01T00:00:00Z"
                .parse::<TimeBound>()
                .unwrap()
                .to_string(),
            "1970-01-01T00:00:00Z"
        );
    }

    #[test]
    fn wrong_times_say_why() {
        for (text, why) in [
            ("2023-02-29T00:00:00Z", "no such day"),
            ("2023-11-14T24:00:00Z", "no such time"),
            ("2023-11-14T22:13:20", "ends with Z"),
            ("2023-11-14 22:13:20Z", "joined by T"),
            ("1969-12-31T23:59:59Z", "before 1970"),
            ("2023-11-14T22:13Z", "HH:MM:SS"),
            ("-1", "ends with Z"),
            ("1.", "fraction"),
            ("0.1234567891", "fraction"),
            ("1e3", "decimal"),
            ("", "decimal"),
        ] {
            let error = text.parse::<TimeBound>().unwrap_err().to_string();
            assert!(error.contains(why), "{text}: {error}");
            assert!(error.starts_with(&format!("{text:?}")), "{error}");
        }
    }

    #[test]
    fn seconds_keep_nine_decimals() {
        let bound: TimeBound = "12.000000005".parse().unwrap();
        assert_eq!(bound, TimeBound::SinceStart(Duration::new(12, 5)));
        assert_eq!(bound.to_string(), "12.000000005");
        assert_eq!("7".parse::<TimeBound>().unwrap().to_string(), "7");
    }

    #[test]
    fn the_window_counts_from_the_first_time_and_ends_before_to() {
        let ts = |micros| Timestamp::new(1_000, micros);
        let mut filter = EventFilter::new()
            .from(TimeBound::SinceStart(Duration::from_micros(10)))
            .to(TimeBound::SinceStart(Duration::from_micros(20)));
        assert!(!filter.keeps(&status(None, None)), "no time: not kept");
        let kept: Vec<bool> = [0, 9, 10, 19, 20]
            .into_iter()
            .map(|us| filter.keeps(&status(ts(us), None)))
            .collect();
        assert_eq!(kept, [false, false, true, true, false]);
        assert_eq!(filter.start(), ts(0));
        // A new recording learns its own start.
        filter.restart();
        assert!(!filter.keeps(&status(ts(500), None)));
        assert!(filter.keeps(&status(ts(510), None)));
    }

    #[test]
    fn utc_bounds_compare_the_log_times() {
        let mut filter =
            EventFilter::new().to(TimeBound::Utc(Timestamp::new(1_700_000_001, 0).unwrap()));
        assert!(filter.keeps(&status(Timestamp::new(1_700_000_000, 999_999), None)));
        assert!(!filter.keeps(&status(Timestamp::new(1_700_000_001, 0), None)));
    }

    #[test]
    fn interfaces_match_names_and_channel_numbers() {
        let mut filter = EventFilter::new().iface("can1").iface("2");
        assert!(filter.keeps(&status(None, Some(Iface::Name("can1")))));
        assert!(!filter.keeps(&status(None, Some(Iface::Name("can10")))));
        assert!(filter.keeps(&status(None, Some(Iface::Channel(2)))));
        assert!(filter.keeps(&status(None, Some(Iface::Name("2")))));
        assert!(!filter.keeps(&status(None, Some(Iface::Channel(1)))));
        assert!(!filter.keeps(&status(None, None)));
        let mut every = EventFilter::new();
        assert!(every.is_empty());
        assert!(every.keeps(&status(None, None)));
    }
}
