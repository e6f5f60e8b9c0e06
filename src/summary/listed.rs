//! The summary's lists (aborts, boot-ups, timeouts, …): the first and the
//! last entries of each, and how many there were (docs/summary.md#lists).

use core::fmt;
use core::iter::Chain;
use core::slice;
use std::vec::Vec;

/// The entries of a [`Listed`] in order ([`Listed::iter`]).
pub type ListedIter<'a, T> =
    Chain<slice::Iter<'a, T>, Chain<slice::Iter<'a, T>, slice::Iter<'a, T>>>;

/// A list the summary keeps of a node's or a bus's events, bounded: its
/// first [`FIRST`](Self::FIRST) and its last [`LAST`](Self::LAST) entries,
/// in order, and the [`count`](Self::count) of all of them
/// (docs/summary.md#lists).
///
/// A post-mortem needs where the trouble began and how it ended; the
/// entries between are counted, not kept, so that a summary's memory and
/// size do not grow with the events of a long log (71 356 SDO aborts in a
/// boot-heavy log of a million frames). Every event is still handed to the
/// caller of [`Summarizer::add_with`](super::Summarizer::add_with)
/// as a [`SummaryEvent`](super::SummaryEvent), and every frame is in
/// `decode --json`.
///
/// ```
/// use motionwire::summary::Listed;
///
/// let mut lines = Listed::new();
/// for line in 1..=25_u64 {
///     lines.push(line);
/// }
/// assert_eq!(lines.count(), 25);
/// assert_eq!(lines.omitted(), 5);
/// assert_eq!(lines.head(), (1..=10).collect::<Vec<_>>());
/// assert_eq!(lines.tail().copied().collect::<Vec<_>>(), (16..=25).collect::<Vec<_>>());
/// assert_eq!(lines.last(), Some(&25));
/// ```
#[derive(Debug, Clone)]
pub struct Listed<T> {
    /// The first entries, up to `FIRST`.
    head: Vec<T>,
    /// The last entries after the head, up to `LAST`, as a ring whose
    /// oldest entry is at `start` once it is full.
    tail: Vec<T>,
    start: usize,
    count: u64,
}

impl<T> Listed<T> {
    /// How many of the first entries are kept.
    pub const FIRST: usize = 10;
    /// How many of the last entries are kept (after the first ones).
    pub const LAST: usize = 10;

    /// Return an empty list.
    #[must_use]
    pub const fn new() -> Self {
        Listed {
            head: Vec::new(),
            tail: Vec::new(),
            start: 0,
            count: 0,
        }
    }

    /// Add an entry: kept when it is among the first or (for now) the last,
    /// counted in any case.
    pub fn push(&mut self, entry: T) {
        self.count += 1;
        // Each part is allocated once, at its size, on its first entry.
        if self.head.len() < Self::FIRST {
            if self.head.capacity() == 0 {
                self.head.reserve_exact(Self::FIRST);
            }
            self.head.push(entry);
        } else if self.tail.len() < Self::LAST {
            if self.tail.capacity() == 0 {
                self.tail.reserve_exact(Self::LAST);
            }
            self.tail.push(entry);
        } else {
            self.tail[self.start] = entry;
            self.start = (self.start + 1) % Self::LAST;
        }
    }

    /// Return how many entries were added, kept or not.
    #[must_use]
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Return whether no entry was added.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Return how many entries are kept: [`count`](Self::count) up to
    /// `FIRST + LAST`.
    #[must_use]
    pub fn kept(&self) -> usize {
        self.head.len() + self.tail.len()
    }

    /// Return how many entries were added between the first and the last
    /// ones kept, and not kept.
    #[must_use]
    pub fn omitted(&self) -> u64 {
        self.count - self.kept() as u64
    }

    /// Return the first entries, up to [`FIRST`](Self::FIRST).
    #[must_use]
    pub fn head(&self) -> &[T] {
        &self.head
    }

    /// Return the last entries after the [`head`](Self::head), up to
    /// [`LAST`](Self::LAST), in order: after the omitted ones, if any.
    pub fn tail(&self) -> Chain<slice::Iter<'_, T>, slice::Iter<'_, T>> {
        // The ring's oldest entry is at `start`.
        let (newest, oldest) = self.tail.split_at(self.start);
        oldest.iter().chain(newest)
    }

    /// Return every entry kept, in order: the head, then the tail.
    pub fn iter(&self) -> ListedIter<'_, T> {
        self.head.iter().chain(self.tail())
    }

    /// Return the entry added last.
    #[must_use]
    pub fn last(&self) -> Option<&T> {
        match self.start {
            0 => self.tail.last().or_else(|| self.head.last()),
            start => self.tail.get(start - 1),
        }
    }

    /// Return the entry `i` among those kept ([`iter`](Self::iter) order).
    #[must_use]
    pub fn get(&self, i: usize) -> Option<&T> {
        self.iter().nth(i)
    }
}

impl<T> Default for Listed<T> {
    fn default() -> Self {
        Listed::new()
    }
}

impl<T: PartialEq> PartialEq for Listed<T> {
    /// Equal when the same entries are kept, in the same order, of the
    /// same count.
    fn eq(&self, other: &Self) -> bool {
        self.count == other.count && self.iter().eq(other.iter())
    }
}

impl<T: Eq> Eq for Listed<T> {}

impl<T> FromIterator<T> for Listed<T> {
    fn from_iter<I: IntoIterator<Item = T>>(entries: I) -> Self {
        let mut listed = Listed::new();
        listed.extend(entries);
        listed
    }
}

impl<T> Extend<T> for Listed<T> {
    fn extend<I: IntoIterator<Item = T>>(&mut self, entries: I) {
        for entry in entries {
            self.push(entry);
        }
    }
}

impl<'a, T> IntoIterator for &'a Listed<T> {
    type Item = &'a T;
    type IntoIter = ListedIter<'a, T>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<T: serde::Serialize> serde::Serialize for Listed<T> {
    /// The entries kept, as a sequence (the count is its own key,
    /// docs/summary.md#lists).
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

/// The lines of a [`Listed`], with the count of those omitted between
/// its first and its last (docs/summary.md#lists): `1, 2, …, 10, … 30
/// more …, 41, …, 50`.
pub(super) struct ListedLines<'a, T>(pub(super) &'a Listed<T>);

impl<T: fmt::Display> fmt::Display for ListedLines<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        each(
            self.0,
            f,
            |entry, f, i| {
                if i > 0 {
                    f.write_str(", ")?;
                }
                write!(f, "{entry}")
            },
            |omitted, f| write!(f, ", … {omitted} more …"),
        )
    }
}

/// Write the entries of `listed` in order with `entry` (given its index
/// among those kept), and `more` where entries were omitted.
pub(super) fn each<T>(
    listed: &Listed<T>,
    f: &mut fmt::Formatter<'_>,
    mut entry: impl FnMut(&T, &mut fmt::Formatter<'_>, usize) -> fmt::Result,
    more: impl FnOnce(u64, &mut fmt::Formatter<'_>) -> fmt::Result,
) -> fmt::Result {
    let head = listed.head();
    for (i, e) in head.iter().enumerate() {
        entry(e, f, i)?;
    }
    if listed.omitted() > 0 {
        more(listed.omitted(), f)?;
    }
    for (i, e) in listed.tail().enumerate() {
        entry(e, f, head.len() + i)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::Listed;
    use proptest::prelude::*;

    proptest! {
        /// Whatever is pushed, the list keeps the first FIRST and the last
        /// LAST entries in order, counts them all, and its last is the
        /// last pushed.
        #[test]
        fn keeps_the_first_and_the_last(entries in proptest::collection::vec(any::<u32>(), 0..60)) {
            let listed: Listed<u32> = entries.iter().copied().collect();
            let n = entries.len();
            prop_assert_eq!(listed.count(), n as u64);
            let first = n.min(Listed::<u32>::FIRST);
            let last = (n - first).min(Listed::<u32>::LAST);
            prop_assert_eq!(listed.head(), &entries[..first]);
            let tail: Vec<u32> = listed.tail().copied().collect();
            prop_assert_eq!(&tail[..], &entries[n - last..]);
            prop_assert_eq!(listed.omitted(), (n - first - last) as u64);
            prop_assert_eq!(listed.last(), entries.last());
            let kept: Vec<u32> = listed.iter().copied().collect();
            prop_assert_eq!(kept.len(), first + last);
            prop_assert_eq!(listed.get(kept.len()), None);
            prop_assert_eq!(listed.is_empty(), n == 0);
            let json = serde_json::to_string(&listed).unwrap();
            prop_assert_eq!(json, serde_json::to_string(&kept).unwrap());
        }
    }
}
