//! When a log recorded a frame (docs/formats.md#timestamps, `ts` in
//! docs/output.md#common-keys).

use crate::error::What;
use core::fmt;
use core::time::Duration;

use crate::{RangeError, Result};

/// When a log recorded a frame: a point on the logger's clock, to the
/// nanosecond (docs/formats.md#timestamps; `ts` in docs/output.md#common-keys).
///
/// The clock is the log's: Unix time (UTC) where the file records it
/// (`candump -l`, `-t a`, pcap, BLF, TRC with `$STARTTIME`), else time since
/// the start of the recording (`candump -t d`/`-t z`, ASC relative). Only
/// differences between the times of one log are promised exact: take them
/// with [`Timestamp::duration_since`], which gives a
/// [`Duration`] as every period of the crate is.
///
/// `Display` writes it as candump does, `1700000000.000500`: at least ten
/// digits of seconds and six of the fraction.
///
/// ```
/// use core::time::Duration;
/// use motionwire_codec::can::Timestamp;
///
/// let ts = Timestamp::new(1_700_000_000, 500).unwrap();
/// assert_eq!(ts.as_secs_f64(), 1_700_000_000.000_5);
/// assert_eq!(ts.to_string(), "1700000000.000500");
/// assert!(Timestamp::new(0, 1_000_000).is_none());
///
/// let later = Timestamp::from_nanos(1_700_000_000, 2_500_000).unwrap();
/// assert_eq!(later.duration_since(ts), Some(Duration::from_millis(2)));
/// assert_eq!(ts.duration_since(later), None);
/// ```
// Ordered, compared and hashed as the seconds then the nanoseconds, as a
// `Duration` is.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Timestamp {
    /// The time since the clock's zero. A `Duration` keeps its nanoseconds
    /// below a second, and the compiler knows it: an `Option<Timestamp>`
    /// is no larger than a timestamp, and
    /// [`as_duration`](Self::as_duration) and
    /// [`duration_since`](Self::duration_since) need no normalization.
    since_zero: Duration,
}

impl fmt::Debug for Timestamp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Timestamp")
            .field("secs", &self.secs())
            .field("nanos", &self.subsec_nanos())
            .finish()
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for Timestamp {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "Timestamp {{ secs: {=u64}, nanos: {=u32} }}",
            self.secs(),
            self.subsec_nanos()
        );
    }
}

impl Timestamp {
    /// The clock's zero: the start of the recording, or the Unix epoch.
    pub const ZERO: Timestamp = Timestamp {
        since_zero: Duration::ZERO,
    };

    /// Return the timestamp `secs` + `micros` µs, or `None` when `micros` is
    /// not below 1 000 000.
    #[inline]
    #[must_use]
    pub const fn new(secs: u64, micros: u32) -> Option<Self> {
        if micros < 1_000_000 {
            Some(Timestamp {
                since_zero: Duration::new(secs, micros * 1_000),
            })
        } else {
            None
        }
    }

    /// Return the timestamp `secs` + `nanos` ns, or `None` when `nanos` is
    /// not below 1 000 000 000.
    #[inline]
    #[must_use]
    pub const fn from_nanos(secs: u64, nanos: u32) -> Option<Self> {
        if nanos < 1_000_000_000 {
            Some(Timestamp {
                since_zero: Duration::new(secs, nanos),
            })
        } else {
            None
        }
    }

    /// Return the timestamp `secs` + `micros` µs, or a
    /// [`RangeError`] naming `micros` when it is not below 1 000 000.
    #[inline]
    pub const fn try_new(secs: u64, micros: u32) -> Result<Self, RangeError> {
        match Self::new(secs, micros) {
            Some(ts) => Ok(ts),
            None => Err(RangeError {
                what: What::TimestampMicroseconds,
                found: micros,
                min: 0,
                max: 999_999,
            }),
        }
    }

    /// The first time read as Unix time: 2001-09-09 01:46:40 UTC, 10⁹
    /// seconds after the epoch. A recording's own clock, counted from its
    /// start, stays far below it; a logger's clock that counts Unix time
    /// is past it for any recording of this century.
    pub const UNIX_FROM: Timestamp = Timestamp {
        since_zero: Duration::from_secs(1_000_000_000),
    };

    /// Return whether this time reads as Unix time (UTC), a date and a
    /// time of day: at or after [`Timestamp::UNIX_FROM`]. Below it, the
    /// time is a duration since the start of the recording (or since a
    /// logger's boot, where its clock was never set).
    ///
    /// ```
    /// use motionwire_codec::can::Timestamp;
    ///
    /// assert!(Timestamp::new(1_700_000_000, 500).unwrap().is_unix_time());
    /// assert!(!Timestamp::new(2, 3641).unwrap().is_unix_time());
    /// ```
    #[inline]
    #[must_use]
    pub const fn is_unix_time(self) -> bool {
        self.since_zero.as_secs() >= Self::UNIX_FROM.since_zero.as_secs()
    }

    /// Return the timestamp that lies `since_zero` after the clock's zero.
    #[inline]
    #[must_use]
    pub const fn from_duration(since_zero: Duration) -> Self {
        Timestamp { since_zero }
    }

    /// Return the time since the clock's zero.
    #[inline]
    #[must_use]
    pub const fn as_duration(self) -> Duration {
        self.since_zero
    }

    /// Return the whole seconds.
    #[inline]
    #[must_use]
    pub const fn secs(self) -> u64 {
        self.since_zero.as_secs()
    }

    /// Return the microseconds within the second, 0..=999 999 (truncated).
    #[inline]
    #[must_use]
    pub const fn micros(self) -> u32 {
        self.since_zero.subsec_micros()
    }

    /// Return the nanoseconds within the second, 0..=999 999 999.
    #[inline]
    #[must_use]
    pub const fn subsec_nanos(self) -> u32 {
        self.since_zero.subsec_nanos()
    }

    /// Return the timestamp in whole microseconds.
    #[inline]
    #[must_use]
    pub const fn as_micros(self) -> u128 {
        self.since_zero.as_micros()
    }

    /// Return the timestamp in seconds as a float (`ts` in
    /// docs/output.md#common-keys); exact to the microsecond for any date of
    /// this era.
    #[inline]
    #[must_use]
    pub fn as_secs_f64(self) -> f64 {
        self.secs() as f64 + f64::from(self.subsec_nanos()) / 1e9
    }

    /// Return how long after `earlier` this timestamp lies, or `None` when it
    /// lies before it.
    #[inline]
    #[must_use]
    pub fn duration_since(self, earlier: Timestamp) -> Option<Duration> {
        self.since_zero.checked_sub(earlier.since_zero)
    }

    /// Return the timestamp `period` later, or `None` when it would not fit.
    #[inline]
    #[must_use]
    pub fn checked_add(self, period: Duration) -> Option<Timestamp> {
        self.as_duration()
            .checked_add(period)
            .map(Timestamp::from_duration)
    }
}

impl From<Duration> for Timestamp {
    fn from(since_zero: Duration) -> Self {
        Timestamp::from_duration(since_zero)
    }
}

impl From<Timestamp> for Duration {
    fn from(ts: Timestamp) -> Self {
        ts.as_duration()
    }
}

impl Timestamp {
    /// Return the time as seconds without padding and with the
    /// resolution it has: six decimals, or nine when it is not a whole
    /// number of microseconds (`1700000000.000500`, `0.052000`,
    /// `1700000000.000500001`) — `ts` as a JSON number
    /// (docs/output.md#common-keys), exact (docs/formats.md#timestamps: no
    /// float rounding).
    ///
    /// ```
    /// use motionwire_codec::can::Timestamp;
    ///
    /// assert_eq!(Timestamp::new(1_700_000_000, 500).unwrap().seconds().to_string(), "1700000000.000500");
    /// assert_eq!(Timestamp::from_nanos(0, 52_000_001).unwrap().seconds().to_string(), "0.052000001");
    /// ```
    #[must_use]
    pub const fn seconds(self) -> Seconds {
        Seconds(self)
    }

    /// Write [`seconds`](Self::seconds) into `buf` without the formatting
    /// machinery, for writers of one record per frame, and return the
    /// ASCII text written.
    ///
    /// ```
    /// use motionwire_codec::can::{Timestamp, SECONDS_LEN};
    ///
    /// let mut buf = [0; SECONDS_LEN];
    /// let text = Timestamp::new(1_700_000_000, 500).unwrap().format_seconds(&mut buf);
    /// assert_eq!(text, b"1700000000.000500");
    /// ```
    pub fn format_seconds(self, buf: &mut [u8; SECONDS_LEN]) -> &[u8] {
        // Two digits a division, from a table, right to left.
        const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
                                    2021222324252627282930313233343536373839\
                                    4041424344454647484950515253545556575859\
                                    6061626364656667686970717273747576777879\
                                    8081828384858687888990919293949596979899";
        fn pair(buf: &mut [u8; SECONDS_LEN], at: usize, n: u64) {
            let i = 2 * (n % 100) as usize;
            buf[at] = PAIRS[i];
            buf[at + 1] = PAIRS[i + 1];
        }
        // The fraction: microseconds, or nanoseconds when the time has them.
        let nanos = self.subsec_nanos();
        let (mut fraction, width) = if nanos % 1000 == 0 {
            (u64::from(nanos / 1000), 6)
        } else {
            (u64::from(nanos), 9)
        };
        let end = 21 + width;
        let mut at = end;
        while at > 22 {
            at -= 2;
            pair(buf, at, fraction);
            fraction /= 100;
        }
        if at == 22 {
            buf[21] = b'0' + fraction as u8;
        }
        buf[20] = b'.';
        // The seconds' digits, right-aligned in the first 20 bytes.
        let mut secs = self.secs();
        let mut start = 20;
        while secs >= 100 {
            start -= 2;
            pair(buf, start, secs);
            secs /= 100;
        }
        if secs >= 10 {
            start -= 2;
            pair(buf, start, secs);
        } else {
            start -= 1;
            buf[start] = b'0' + secs as u8;
        }
        &buf[start..end]
    }
}

/// The longest text [`Timestamp::format_seconds`] writes: 20 digits of
/// seconds, the point and 9 digits.
pub const SECONDS_LEN: usize = 30;

/// A [`Timestamp`] written as seconds with the resolution it has
/// ([`Timestamp::seconds`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Seconds(Timestamp);

impl fmt::Display for Seconds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buf = [0; SECONDS_LEN];
        let text = self.0.format_seconds(&mut buf);
        f.write_str(core::str::from_utf8(text).map_err(|_| fmt::Error)?)
    }
}

impl fmt::Display for Timestamp {
    /// Write the timestamp as candump does, `1700000000.000500` (ten digits
    /// of seconds at least, six of microseconds), or with nine digits of
    /// nanoseconds as `candump -N` does when the time is not a whole number
    /// of microseconds (`1700000000.000500001`), so that nothing is lost.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let nanos = self.subsec_nanos();
        if nanos % 1000 == 0 {
            write!(f, "{:010}.{:06}", self.secs(), nanos / 1000)
        } else {
            write!(f, "{:010}.{:09}", self.secs(), nanos)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn micro_and_nano_limits() {
        assert_eq!(
            Timestamp::new(0, 999_999).map(Timestamp::micros),
            Some(999_999)
        );
        assert_eq!(Timestamp::new(0, 1_000_000), None);
        assert_eq!(
            Timestamp::from_nanos(0, 999_999_999).map(Timestamp::subsec_nanos),
            Some(999_999_999)
        );
        assert_eq!(Timestamp::from_nanos(0, 1_000_000_000), None);
        assert_eq!(
            Timestamp::try_new(5, 1_000_000).unwrap_err().to_string(),
            "timestamp microseconds: 1000000 is outside 0..=999999"
        );
    }

    #[test]
    fn duration_round_trip_and_differences() {
        let candump = Timestamp::new(1_700_000_000, 500).unwrap();
        assert_eq!(candump.as_micros(), 1_700_000_000_000_500);
        assert_eq!(candump.as_secs_f64(), 1_700_000_000.000_5);
        let ts = Timestamp::from_nanos(12, 345_678_901).unwrap();
        assert_eq!(Timestamp::from(Duration::from(ts)), ts);
        assert_eq!(ts.micros(), 345_678);
        assert_eq!(ts.as_micros(), 12_345_678);
        let later = ts.checked_add(Duration::from_micros(1_700_000)).unwrap();
        assert_eq!(
            later.duration_since(ts),
            Some(Duration::from_micros(1_700_000))
        );
        assert_eq!(ts.duration_since(later), None);
        let end = Timestamp::from_nanos(u64::MAX, 999_999_999).unwrap();
        assert_eq!(end.checked_add(Duration::from_nanos(1)), None);
    }

    #[test]
    fn display_as_candump() {
        assert_eq!(
            Timestamp::new(1_700_000_000, 500).unwrap().to_string(),
            "1700000000.000500"
        );
        assert_eq!(
            Timestamp::new(12, 5).unwrap().to_string(),
            "0000000012.000005"
        );
        assert_eq!(Timestamp::ZERO.to_string(), "0000000000.000000");
    }
}

#[cfg(test)]
mod proptests {
    use super::*;
    use crate::strategies::can::timestamp;
    use proptest::prelude::*;

    proptest! {
        /// A timestamp is its duration since zero; differences are exact.
        #[test]
        fn duration_round_trip_and_order(a in timestamp(), b in timestamp()) {
            prop_assert_eq!(Timestamp::from_duration(a.as_duration()), a);
            prop_assert_eq!(a.duration_since(b).is_some(), a >= b);
            if let Some(d) = a.duration_since(b) {
                prop_assert_eq!(b.checked_add(d), Some(a));
            }
            let text = a.to_string();
            let (secs, fraction) = text.split_once('.').expect("a point");
            prop_assert_eq!(secs.parse::<u64>().unwrap(), a.secs());
            // Six digits for whole microseconds, nine otherwise (candump -N).
            let digits = if a.subsec_nanos() % 1000 == 0 { 6 } else { 9 };
            prop_assert_eq!(fraction.len(), digits);
            let scale = if digits == 6 { 1000 } else { 1 };
            prop_assert_eq!(fraction.parse::<u32>().unwrap() * scale, a.subsec_nanos());
        }
    }
}
