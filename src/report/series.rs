//! Bounded series: what a row of the timeline keeps while a log of any size
//! is read (docs/report.md#bounded). Each series holds its items exactly up
//! to a limit, then as buckets of a width that doubles whenever the buckets
//! outgrow their cap: neighbours merge, counts add up, and memory stays
//! bounded whatever the log's length.

/// The most items a series keeps exactly: more than this many marks of one
/// kind on one row are drawn as clusters (docs/report.md#clusters).
pub(crate) const EXACT_MARKS: usize = 500;

/// The most buckets a series keeps: twice the timeline's default width in
/// pixels, so that a bucket never spans more than a pixel of it.
pub(crate) const BUCKETS: usize = 2048;

/// The most buckets of a signal: each gives its minimum and maximum, at
/// most 2 000 points a chart (docs/report.md#signals).
pub(crate) const SIGNAL_BUCKETS: usize = 1000;

/// Where an item lies: its time in microseconds (for a recording with
/// timestamps) and its line. The series of a recording with timestamps is
/// ordered and bucketed by time, else by line; both are kept, so that a page
/// whose axis counts lines can still draw it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct At {
    /// Microseconds (since the Unix epoch, or since the recording began,
    /// as the log counts them); 0 without timestamps.
    pub(crate) t: u64,
    /// The line.
    pub(crate) line: u64,
}

impl At {
    #[inline]
    pub(crate) fn key(self, timed: bool) -> u64 {
        if timed {
            self.t
        } else {
            self.line
        }
    }
}

use crate::servo::HandshakePhase;
use crate::summary::ServoChange;

/// An item a [`Series`] can hold and merge.
pub(crate) trait Item: Copy {
    /// Where it begins.
    fn at(&self) -> At;
    /// Take in `later`, which begins at or after it.
    fn absorb(&mut self, later: &Self);
}

/// A bounded series of items of one kind on one row.
#[derive(Debug, Clone)]
pub(crate) struct Series<T> {
    items: Vec<T>,
    /// Whether the items are kept exactly.
    exact_now: bool,
    /// The bucket width is `1 << shift` (microseconds or lines).
    shift: u32,
    /// The bucket of the last item.
    last_bucket: u64,
    exact: usize,
    cap: usize,
    timed: bool,
}

impl<T: Item> Series<T> {
    /// A series that keeps up to `exact` items one by one, then at most
    /// `cap` buckets.
    pub(crate) const fn new(exact: usize, cap: usize, timed: bool) -> Self {
        Series {
            items: Vec::new(),
            exact_now: true,
            shift: 0,
            last_bucket: 0,
            exact,
            cap,
            timed,
        }
    }

    /// Return whether the items are kept one by one (not bucketed).
    pub(crate) fn is_exact(&self) -> bool {
        self.exact_now
    }

    /// Return the bucket width (0 while items are kept one by one).
    pub(crate) fn width(&self) -> u64 {
        if self.exact_now {
            0
        } else {
            1 << self.shift
        }
    }

    pub(crate) fn items(&self) -> &[T] {
        &self.items
    }

    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }

    /// The last item (or bucket), to complete what it says.
    pub(crate) fn last_mut(&mut self) -> Option<&mut T> {
        self.items.last_mut()
    }

    /// Keep only the items (or buckets) for which `keep` holds.
    pub(crate) fn retain(&mut self, keep: impl FnMut(&T) -> bool) {
        self.items.retain(keep);
        self.last_bucket = self.items.last().map_or(u64::MAX, |last| self.key(last));
    }

    #[inline]
    fn key(&self, item: &T) -> u64 {
        item.at().key(self.timed) >> self.shift
    }

    /// Add an item; a log is mostly in order, so the common case is a
    /// push at the end.
    pub(crate) fn add(&mut self, item: T) {
        let key = item.at().key(self.timed);
        if self.exact_now {
            match self.items.last() {
                Some(last) if last.at().key(self.timed) > key => {
                    let at = self
                        .items
                        .partition_point(|i| i.at().key(self.timed) <= key);
                    self.items.insert(at, item);
                }
                _ => self.items.push(item),
            }
            if self.items.len() > self.exact {
                self.exact_now = false;
                self.coarsen(false);
                // Room for the cap and the one item that overflows it, so
                // that the vector never doubles past it.
                let room = (self.cap + 1).saturating_sub(self.items.len());
                self.items.reserve_exact(room);
            }
            return;
        }
        let bucket = key >> self.shift;
        if bucket == self.last_bucket {
            if let Some(last) = self.items.last_mut() {
                last.absorb(&item);
                return;
            }
        }
        let last = self.items.last().map(|last| self.key(last));
        match last {
            Some(last) if last > bucket => {
                let at = self.items.partition_point(|i| self.key(i) < bucket);
                match self.items.get(at) {
                    Some(there) if self.key(there) == bucket => {
                        let there = &mut self.items[at];
                        if there.at().key(self.timed) <= key {
                            there.absorb(&item);
                        } else {
                            let mut first = item;
                            first.absorb(there);
                            *there = first;
                        }
                    }
                    _ => self.items.insert(at, item),
                }
            }
            _ => self.items.push(item),
        }
        if self.items.len() > self.cap {
            self.coarsen(true);
        }
        self.last_bucket = self.items.last().map_or(u64::MAX, |last| self.key(last));
    }

    /// Merge the items of one bucket, doubling the width (when `double`)
    /// until they fit the cap. The items are merged in place: no vector
    /// is allocated, so an EMCY storm's rows do not touch fresh memory each
    /// time they coarsen (BENCHMARKS.md, "`motionwire report`").
    fn coarsen(&mut self, double: bool) {
        if double {
            self.shift += 1;
        }
        loop {
            let shift = self.shift;
            let timed = self.timed;
            let mut kept = 0;
            for read in 1..self.items.len() {
                let item = self.items[read];
                let last = &mut self.items[kept];
                if last.at().key(timed) >> shift == item.at().key(timed) >> shift {
                    last.absorb(&item);
                } else {
                    kept += 1;
                    self.items[kept] = item;
                }
            }
            self.items.truncate((kept + 1).min(self.items.len()));
            if self.items.len() <= self.cap || self.shift >= 63 {
                break;
            }
            self.shift += 1;
        }
        self.last_bucket = self.items.last().map_or(u64::MAX, |last| self.key(last));
    }
}

/// A mark, or a bucket of marks of one kind: the first event's place,
/// line and detail; the last's; how many.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MarkItem {
    pub(crate) at: At,
    /// Where its last event (or, for a heartbeat timeout, its gap) ends.
    pub(crate) end: At,
    pub(crate) count: u64,
    pub(crate) detail: Detail,
}

/// What a mark says beyond its kind (the first event's, for a cluster).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Detail {
    None,
    /// An EMCY's code, error register and manufacturer bytes (which the
    /// node's profile reads, docs/summary.md#profiles).
    Emcy {
        code: u16,
        register: u8,
        manufacturer: [u8; 5],
    },
    /// A heartbeat gap, in microseconds.
    Gap(u64),
    /// An AL status with its error indicator: the band's state byte, and
    /// the AL status code where it was read.
    Al {
        state: u8,
        code: Option<u16>,
    },
    /// An SDO abort's object and code.
    Abort {
        index: u16,
        subindex: u8,
        code: u32,
    },
    /// An error counter's register, and its value before and after.
    Counter {
        register: u16,
        from: u8,
        to: u8,
    },
    /// A returned copy's working counter, and the stream's usual one.
    Wkc {
        wkc: u16,
        usual: u16,
    },
    /// A servo's change: a fault set, ServoRDY low, an unanswered enable
    /// edge.
    Servo(ServoChange),
    /// A servo handshake's phases from its request on (the first `len`
    /// of `phases`), and the zero-pulse position its ack brought.
    Handshake {
        phases: [HandshakePhase; HANDSHAKE_PHASES],
        len: u8,
        position: Option<i32>,
    },
}

/// The most phases a handshake mark keeps: requested, acknowledged,
/// releasing, done.
pub(crate) const HANDSHAKE_PHASES: usize = 4;

impl Item for MarkItem {
    fn at(&self) -> At {
        self.at
    }

    fn absorb(&mut self, later: &Self) {
        self.count += later.count;
        if later.end.t > self.end.t {
            self.end.t = later.end.t;
        }
        if later.end.line > self.end.line {
            self.end.line = later.end.line;
        }
    }
}

/// A state band, or a bucket of bands: where the first begins, its state,
/// and how many bands (state changes) it stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct BandItem {
    pub(crate) at: At,
    /// The state it begins with (an NMT state byte's bits 0–6, or a
    /// `Cia402State` as its index).
    pub(crate) state: u8,
    /// The state it ends with.
    pub(crate) last_state: u8,
    pub(crate) count: u64,
}

impl Item for BandItem {
    fn at(&self) -> At {
        self.at
    }

    fn absorb(&mut self, later: &Self) {
        self.count += later.count;
        self.last_state = later.last_state;
    }
}

/// A signal's values in one bucket: the first, the smallest and the
/// largest, each where it was seen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SignalBucket {
    pub(crate) at: At,
    pub(crate) min: (At, f64),
    pub(crate) max: (At, f64),
}

impl Item for SignalBucket {
    fn at(&self) -> At {
        self.at
    }

    fn absorb(&mut self, later: &Self) {
        if later.min.1 < self.min.1 {
            self.min = later.min;
        }
        if later.max.1 > self.max.1 {
            self.max = later.max;
        }
    }
}

/// Frames counted per bucket of a bus (the bus row's frame rate).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RateBucket {
    pub(crate) at: At,
    pub(crate) frames: u64,
}

impl Item for RateBucket {
    fn at(&self) -> At {
        self.at
    }

    fn absorb(&mut self, later: &Self) {
        self.frames += later.frames;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mark(t: u64, line: u64) -> MarkItem {
        let at = At { t, line };
        MarkItem {
            at,
            end: at,
            count: 1,
            detail: Detail::None,
        }
    }

    #[test]
    fn up_to_500_marks_are_kept_one_by_one() {
        let mut series = Series::new(EXACT_MARKS, BUCKETS, true);
        for i in 0..500 {
            series.add(mark(i * 1000, i + 1));
        }
        assert!(series.is_exact());
        assert_eq!(series.len(), 500);
    }

    #[test]
    fn a_storm_of_300_000_is_bounded_and_every_event_counted() {
        let mut series = Series::new(EXACT_MARKS, BUCKETS, true);
        for i in 0..300_000u64 {
            series.add(mark(i * 37, i + 1));
        }
        assert!(!series.is_exact());
        assert!(series.len() <= BUCKETS);
        assert_eq!(series.items().iter().map(|m| m.count).sum::<u64>(), 300_000);
        assert_eq!(series.items()[0].at.line, 1);
        let keys: Vec<u64> = series.items().iter().map(|m| m.at.t).collect();
        assert!(keys.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn out_of_order_items_keep_the_order_and_the_count() {
        let mut series = Series::new(4, BUCKETS, true);
        for (i, t) in [50, 10, 40, 20, 30, 5, 45].into_iter().enumerate() {
            series.add(mark(t, i as u64 + 1));
        }
        assert_eq!(series.items().iter().map(|m| m.count).sum::<u64>(), 7);
        let keys: Vec<u64> = series.items().iter().map(|m| m.at.t).collect();
        assert!(keys.windows(2).all(|w| w[0] < w[1]), "{keys:?}");
    }

    #[test]
    fn signal_buckets_keep_the_extremes() {
        let mut series = Series::new(0, SIGNAL_BUCKETS, true);
        for i in 0..100_000u64 {
            let at = At { t: i, line: i + 1 };
            let v = if i == 77_777 { 1e9 } else { (i % 100) as f64 };
            series.add(SignalBucket {
                at,
                min: (at, v),
                max: (at, v),
            });
        }
        assert!(series.len() <= SIGNAL_BUCKETS);
        assert!(series.items().iter().any(|b| b.max.1 == 1e9));
    }
}
