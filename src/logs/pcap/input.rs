//! A window on the input: the bytes from the reader's position on, as many
//! as the structure being read needs, in one slice, with its offset in the
//! file. The window grows by doubling only while the input supplies bytes,
//! and never beyond what the caller asks, so a length field that claims
//! more than the file holds costs at most twice what the file holds
//! (bounded by [`crate::logs::MAX_RECORD_LEN`] in the callers).

use std::io::{ErrorKind, Read};

/// The first allocation and the smallest read: 64 KiB, large enough that a
/// capture of small CAN packets is read in few system calls.
const CHUNK: usize = 64 << 10;

/// The reader and the bytes read ahead of the position.
#[derive(Debug)]
pub(super) struct Input<R> {
    reader: R,
    buf: Vec<u8>,
    /// The position: the first byte not yet consumed.
    start: usize,
    /// One past the last byte read.
    end: usize,
    /// The offset in the file of `buf[start]`.
    offset: u64,
    /// The reader returned 0: no more bytes.
    eof: bool,
    /// Bytes taken from the reader.
    taken: u64,
    /// The last read returned fewer bytes than asked (and some): it took
    /// everything the input had buffered.
    short: bool,
}

impl<R: Read> Input<R> {
    /// Return a window on `reader` at offset 0; nothing is read yet.
    pub(super) fn new(reader: R) -> Self {
        Input {
            reader,
            buf: Vec::new(),
            start: 0,
            end: 0,
            offset: 0,
            eof: false,
            taken: 0,
            short: false,
        }
    }

    /// Read until at least `need` bytes lie after the position or the input
    /// ends; return how many lie there (fewer than `need` only at the end).
    #[inline]
    pub(super) fn fill(&mut self, need: usize) -> std::io::Result<usize> {
        let available = self.end - self.start;
        if available >= need {
            return Ok(available);
        }
        self.read_more(need)
    }

    /// [`Input::fill`] when the bytes read are not enough.
    fn read_more(&mut self, need: usize) -> std::io::Result<usize> {
        while self.end - self.start < need && !self.eof {
            if self.buf.len() - self.start < need {
                // Move the unread bytes to the front, then grow if needed.
                self.buf.copy_within(self.start..self.end, 0);
                self.end -= self.start;
                self.start = 0;
                // Grow only once the bytes read fill the buffer.
                if self.buf.len() < need && self.end == self.buf.len() {
                    let doubled = self.buf.len().saturating_mul(2).max(CHUNK);
                    self.buf.resize(doubled.min(need.max(CHUNK)), 0);
                }
            }
            let space = self.buf.get_mut(self.end..).unwrap_or_default();
            let room = space.len();
            match self.reader.read(space) {
                Ok(0) => self.eof = true,
                Ok(n) => {
                    let n = n.min(space_len(self.buf.len(), self.end));
                    self.end += n;
                    self.taken += n as u64;
                    self.short = n < room;
                }
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        Ok(self.end - self.start)
    }

    /// Return the bytes after the position that have been read.
    pub(super) fn bytes(&self) -> &[u8] {
        self.buf.get(self.start..self.end).unwrap_or_default()
    }

    /// Move the position `n` bytes on (at most to the bytes read).
    pub(super) fn consume(&mut self, n: usize) {
        let n = n.min(self.end - self.start);
        self.start += n;
        self.offset = self.offset.saturating_add(n as u64);
    }

    /// Return `len` bytes from `back` bytes before the position: a part of
    /// a record just consumed, which stays in the buffer until the next
    /// read.
    pub(super) fn behind(&self, back: usize, len: usize) -> &[u8] {
        let Some(from) = self.start.checked_sub(back) else {
            return &[];
        };
        self.buf
            .get(from..from.saturating_add(len))
            .unwrap_or_default()
    }

    /// Return the offset of the position in the file.
    pub(super) fn offset(&self) -> u64 {
        self.offset
    }

    /// Return how many bytes were taken from the reader.
    pub(super) fn taken(&self) -> u64 {
        self.taken
    }

    /// Return whether the last read took everything the reader had
    /// buffered (it returned fewer bytes than asked).
    pub(super) fn drained(&self) -> bool {
        self.short && !self.eof
    }
}

/// The room after `end` in a buffer of `len` bytes: a reader that claims to
/// have read more than it was given is not believed.
fn space_len(len: usize, end: usize) -> usize {
    len.saturating_sub(end)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader that hands out one byte per call.
    struct Trickle<'a>(&'a [u8]);

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            match (self.0.split_first(), buf.first_mut()) {
                (Some((&b, rest)), Some(slot)) => {
                    *slot = b;
                    self.0 = rest;
                    Ok(1)
                }
                _ => Ok(0),
            }
        }
    }

    #[test]
    fn fills_consumes_and_stops_at_the_end() {
        let data: Vec<u8> = (0..=255).collect();
        let mut input = Input::new(Trickle(&data));
        assert_eq!(input.fill(10).unwrap(), 10);
        assert_eq!(input.bytes(), &data[..10]);
        input.consume(4);
        assert_eq!(input.offset(), 4);
        assert_eq!(input.fill(100).unwrap(), 100);
        assert_eq!(&input.bytes()[..100], &data[4..104]);
        input.consume(100);
        assert_eq!(input.fill(1000).unwrap(), 152);
        input.consume(1000);
        assert_eq!(input.offset(), 256);
        assert_eq!(input.fill(1).unwrap(), 0);
    }

    #[test]
    fn grows_only_with_the_input() {
        let data = [7u8; 100];
        let mut input = Input::new(&data[..]);
        assert_eq!(input.fill(16 << 20).unwrap(), 100);
        assert!(input.buf.len() <= CHUNK);
    }
}
