//! The bytes of a data group or of signal data, read as one stream
//! (ASAM MDF 4.1 §5.20–5.26, DT, DZ, DL and HL; docs/formats.md#mf4): a
//! DT or SD block is read a chunk at a time, a DZ block inflated whole (zlib,
//! or zlib of the transposed records), a DL a list of such blocks read in
//! turn with the next DL after it, an HL the DL it leads to.
//!
//! Memory: a stream holds one DZ block's bytes or one chunk of a DT, and
//! the unread end of the block before it. DZ blocks are bounded by
//! [`MAX_RECORD_LEN`] each, and all the streams of a reader together by
//! [`MAX_BUFFERED`]: beyond, [`BinaryError::TooLarge`].

use std::io::{Read, Seek};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use crate::logs::bytes::padded;
use crate::logs::mf4::block::{damaged, Chain, Source, HEADER_LEN};
use crate::logs::{BinaryError, LogError, MAX_RECORD_LEN};

/// The bytes of a DT block read at once.
const CHUNK: u64 = 256 * 1024;

/// The most bytes all the data streams of one reader hold together
/// (256 MiB): enough for sixteen data groups each in the middle of a DZ
/// block of the largest size read.
pub(super) const MAX_BUFFERED: usize = 16 * MAX_RECORD_LEN;

/// The bytes the streams of one reader hold, shared by them.
pub(super) type Budget = Arc<AtomicUsize>;

/// The blocks of a stream still to read.
#[derive(Debug)]
enum Blocks {
    /// The data link leads to one block (DT, SD, DZ) or to none.
    One(Option<u64>),
    /// A data list: the data links of the current DL from `index`, then
    /// the DL that `next` leads to; `chain` holds the DL blocks and the
    /// data blocks passed.
    List {
        links: Vec<u64>,
        index: usize,
        next: u64,
        chain: Chain,
    },
}

/// A stream of bytes over the data blocks a data link leads to.
#[derive(Debug)]
pub(super) struct DataStream {
    blocks: Blocks,
    /// Bytes read: consumed up to `pos`, the rest not yet.
    buf: Vec<u8>,
    pos: usize,
    /// The stream offset of `buf[pos]` (`buf[0]` is at `offset - pos`).
    offset: u64,
    /// The part of a DT or SD block not yet read: from, to.
    chunk: Option<(u64, u64)>,
    /// A DT whose length is its header and that is the data link itself
    /// runs to the end of the file: in an unfinalized file its length was
    /// never written (docs/formats.md#mf4). In a finalized file a block's
    /// length is the data it holds.
    open_ended: bool,
    /// What this stream counts in `budget`.
    held: usize,
    budget: Budget,
}

impl Drop for DataStream {
    fn drop(&mut self) {
        self.budget.fetch_sub(self.held, Ordering::Relaxed);
    }
}

/// What [`DataStream::read_more`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum More {
    /// Bytes were added to the buffer, or (when skipping) a DT block's
    /// part to read was set.
    Read,
    /// A DZ block of this many bytes was passed over.
    Skipped(u64),
    /// The stream has ended.
    End,
}

/// What a DZ block's header says (ASAM MDF 4.1 §5.26).
struct Dz {
    org_len: u64,
    zip_type: u8,
    parameter: u32,
    data_len: u64,
    data_at: u64,
}

impl DataStream {
    /// A stream over what `link` leads to (0: an empty stream); `open_ended`
    /// in an unfinalized file, where a DT block of no length runs to the
    /// end of the file.
    pub(super) fn new<R: Read + Seek>(
        source: &mut Source<R>,
        link: u64,
        open_ended: bool,
        budget: Budget,
    ) -> Result<Self, LogError> {
        let blocks = if link == 0 {
            Blocks::One(None)
        } else {
            let (id, _, _) = source.header(link, "##DT|##SD|##DV|##DZ|##DL|##HL")?;
            match &id {
                b"##DL" => Blocks::List {
                    links: Vec::new(),
                    index: 0,
                    next: link,
                    chain: Chain::default(),
                },
                b"##HL" => {
                    let hl = source.block(link, "##HL", 0)?;
                    Blocks::List {
                        links: Vec::new(),
                        index: 0,
                        next: hl.link(0),
                        chain: Chain::default(),
                    }
                }
                _ => Blocks::One(Some(link)),
            }
        };
        let open_ended = open_ended && matches!(blocks, Blocks::One(Some(_)));
        Ok(DataStream {
            blocks,
            buf: Vec::new(),
            pos: 0,
            offset: 0,
            chunk: None,
            open_ended,
            held: 0,
            budget,
        })
    }

    /// Return the stream offset of the next byte.
    pub(super) fn offset(&self) -> u64 {
        self.offset
    }

    /// Return the bytes available from the next one (after [`fill`]).
    ///
    /// [`fill`]: DataStream::fill
    pub(super) fn available(&self) -> &[u8] {
        self.buf.get(self.pos..).unwrap_or_default()
    }

    /// Go back to the stream offset `to`, behind the next byte, when the
    /// bytes from there are still held (a VLSD offset that goes back into
    /// the block just read: read again without inflating it again);
    /// `false` when they are not.
    pub(super) fn rewind(&mut self, to: u64) -> bool {
        let back = self.offset.saturating_sub(to);
        if back > self.pos as u64 {
            return false;
        }
        self.pos -= back as usize;
        self.offset -= back;
        true
    }

    /// Consume `n` available bytes.
    pub(super) fn consume(&mut self, n: usize) {
        let n = n.min(self.buf.len() - self.pos);
        self.pos += n;
        self.offset += n as u64;
    }

    /// Make `need` bytes available; `false` when the stream ends first
    /// (what is left is then [`available`](DataStream::available)).
    pub(super) fn fill<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
        need: usize,
    ) -> Result<bool, LogError> {
        while self.buf.len() - self.pos < need {
            if self.read_more(source, 0)? == More::End {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Skip `n` bytes; `false` when the stream ends first.
    pub(super) fn skip<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
        mut n: u64,
    ) -> Result<bool, LogError> {
        loop {
            let here = (self.buf.len() - self.pos) as u64;
            let step = here.min(n);
            self.consume(step as usize);
            n -= step;
            if n == 0 {
                return Ok(true);
            }
            // Skip inside a DT without reading it (what was held is behind
            // the new offset: let go of it).
            if let Some((from, to)) = self.chunk {
                self.buf.clear();
                self.pos = 0;
                let step = (to - from).min(n);
                self.chunk = Some((from + step, to));
                self.offset += step;
                n -= step;
                if n == 0 {
                    return Ok(true);
                }
            }
            match self.read_more(source, n)? {
                More::End => return Ok(false),
                More::Read => {}
                More::Skipped(len) => {
                    // A whole DZ block passed over, not inflated.
                    self.buf.clear();
                    self.pos = 0;
                    self.offset += len;
                    n -= len;
                    if n == 0 {
                        return Ok(true);
                    }
                }
            }
        }
    }

    /// Read the next chunk or block into the buffer. When the caller
    /// skips `skippable` bytes (more than 0), a DZ block of at most as
    /// many is passed over without inflating it, and a DT block is only
    /// made the part to read (the caller skips inside it).
    fn read_more<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
        skippable: u64,
    ) -> Result<More, LogError> {
        loop {
            if let Some((from, to)) = self.chunk {
                if from < to {
                    let n = (to - from).min(CHUNK) as usize;
                    let start = self.make_room(n)?;
                    self.buf.resize(start + n, 0);
                    let got = source.read_at(from, &mut self.buf[start..])?;
                    self.buf.truncate(start + got);
                    if got == 0 {
                        // The file ends inside the block.
                        self.chunk = None;
                        continue;
                    }
                    self.chunk = Some((from + got as u64, to));
                    return Ok(More::Read);
                }
                self.chunk = None;
            }
            let Some(link) = self.next_block(source)? else {
                return Ok(More::End);
            };
            let (id, len, links) = source.header(link, "##DT|##SD|##DV|##DZ")?;
            if &id == b"##DZ" {
                let dz = dz_header(source, link, len, links)?;
                if dz.org_len == 0 {
                    continue;
                }
                if dz.org_len <= skippable {
                    return Ok(More::Skipped(dz.org_len));
                }
                self.inflate(source, link, &dz)?;
                return Ok(More::Read);
            }
            let from = link + HEADER_LEN + 8 * links;
            let mut to = link.saturating_add(len);
            if len == HEADER_LEN && self.open_ended {
                // Unfinalized: the length was never written
                // (docs/formats.md#mf4).
                to = source.len;
            }
            // Empty when the data would start past the end of the file
            // (links that the file cuts).
            self.chunk = Some((from, to.min(source.len).max(from)));
            if skippable > 0 {
                // The caller skips inside the DT without reading it.
                return Ok(More::Read);
            }
        }
    }

    /// The next data block's link, from the list; `None` at the end.
    fn next_block<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
    ) -> Result<Option<u64>, LogError> {
        match &mut self.blocks {
            Blocks::One(link) => Ok(link.take()),
            Blocks::List {
                links,
                index,
                next,
                chain,
            } => loop {
                if let Some(&link) = links.get(*index) {
                    *index += 1;
                    if link != 0 {
                        // The list's data blocks are links of its chain: a
                        // block named twice would be read twice, a list
                        // could repeat a block without end
                        // (docs/formats.md#mf4).
                        chain.visit(link, source.len)?;
                        return Ok(Some(link));
                    }
                    // Data links end at the first nil.
                    *index = links.len();
                    continue;
                }
                if *next == 0 {
                    return Ok(None);
                }
                chain.visit(*next, source.len)?;
                let dl = source.block(*next, "##DL", 0)?;
                *next = dl.link(0);
                *links = dl.links;
                *index = 1;
            },
        }
    }

    /// Drop the consumed bytes and count `n` more against the budget;
    /// return where they go.
    fn make_room(&mut self, n: usize) -> Result<usize, LogError> {
        if self.pos > 0 {
            self.buf.drain(..self.pos);
            self.pos = 0;
        }
        let want = self.buf.len() + n;
        let others = self
            .budget
            .load(Ordering::Relaxed)
            .saturating_sub(self.held);
        if others + want > MAX_BUFFERED {
            return Err(damaged(
                self.offset,
                BinaryError::TooLarge {
                    length: (others + want) as u64,
                    limit: MAX_BUFFERED as u64,
                },
            ));
        }
        self.buf.reserve_exact(n);
        let held = self.buf.capacity().max(want);
        self.budget.fetch_add(held, Ordering::Relaxed);
        self.budget.fetch_sub(self.held, Ordering::Relaxed);
        self.held = held;
        Ok(self.buf.len())
    }

    /// Inflate the DZ block at `at` onto the buffer.
    fn inflate<R: Read + Seek>(
        &mut self,
        source: &mut Source<R>,
        at: u64,
        dz: &Dz,
    ) -> Result<(), LogError> {
        let mut compressed = vec![0u8; dz.data_len as usize];
        let got = source.read_at(dz.data_at, &mut compressed)?;
        if got < compressed.len() {
            return Err(damaged(
                at,
                BinaryError::Truncated {
                    needed: dz.data_len,
                    found: got as u64,
                },
            ));
        }
        let org_len = dz.org_len as usize;
        let start = self.make_room(org_len)?;
        let mut inflater = flate2::Decompress::new(true);
        let inflated = if dz.zip_type == 1 && dz.parameter > 1 {
            let mut transposed = Vec::with_capacity(org_len);
            let status = inflater.decompress_vec(
                &compressed,
                &mut transposed,
                flate2::FlushDecompress::Finish,
            );
            let whole = matches!(status, Ok(flate2::Status::StreamEnd));
            if whole && transposed.len() == org_len {
                untranspose(&transposed, dz.parameter as usize, &mut self.buf);
            }
            whole && transposed.len() == org_len
        } else {
            let status = inflater.decompress_vec(
                &compressed,
                &mut self.buf,
                flate2::FlushDecompress::Finish,
            );
            matches!(status, Ok(flate2::Status::StreamEnd)) && self.buf.len() - start == org_len
        };
        if !inflated {
            self.buf.truncate(start);
            return Err(damaged(at, BinaryError::Decompression));
        }
        Ok(())
    }

    /// Return the number of bytes the stream holds, from the blocks'
    /// headers (a DZ block's original length), without reading their data.
    pub(super) fn len<R: Read + Seek>(mut self, source: &mut Source<R>) -> Result<u64, LogError> {
        let mut total = 0u64;
        while let Some(link) = self.next_block(source)? {
            let (id, len, links) = source.header(link, "##DT|##SD|##DV|##DZ")?;
            total = total.saturating_add(if &id == b"##DZ" {
                dz_header(source, link, len, links)?.org_len
            } else if len == HEADER_LEN && self.open_ended {
                source.len.saturating_sub(link + HEADER_LEN)
            } else {
                link.saturating_add(len).min(source.len)
                    - (link + HEADER_LEN + 8 * links).min(source.len)
            });
        }
        Ok(total)
    }
}

/// Read and check a DZ block's header: zip type 0 (deflate) or 1
/// (transposition + deflate), lengths within [`MAX_RECORD_LEN`].
fn dz_header<R: Read + Seek>(
    source: &mut Source<R>,
    at: u64,
    len: u64,
    links: u64,
) -> Result<Dz, LogError> {
    let data_at = at + HEADER_LEN + 8 * links;
    let mut head = [0u8; 24];
    let got = source.read_at(data_at, &mut head)?;
    if got < head.len() {
        return Err(damaged(
            at,
            BinaryError::Truncated {
                needed: data_at - at + 24,
                found: data_at - at + got as u64,
            },
        ));
    }
    let zip_type = head[2];
    let parameter = u32::from_le_bytes(padded(&head, 4));
    let org_len = u64::from_le_bytes(padded(&head, 8));
    let data_len = u64::from_le_bytes(padded(&head, 16));
    if zip_type > 1 {
        // zstd, lz4 (asammdf's types 2 to 5): not read (docs/formats.md#mf4).
        return Err(damaged(
            data_at + 2,
            BinaryError::UnsupportedCompression {
                method: u32::from(zip_type),
            },
        ));
    }
    for (length, field) in [(org_len, 8), (data_len, 16)] {
        if length > MAX_RECORD_LEN as u64 {
            return Err(damaged(
                data_at + field,
                BinaryError::TooLarge {
                    length,
                    limit: MAX_RECORD_LEN as u64,
                },
            ));
        }
    }
    if data_len > len.saturating_sub(data_at - at + 24) {
        return Err(damaged(at + 8, BinaryError::BadLength { length: len }));
    }
    Ok(Dz {
        org_len,
        zip_type,
        parameter,
        data_len,
        data_at: data_at + 24,
    })
}

/// Append to `out` the records that `transposed` holds column by column
/// (ASAM MDF 4.1 §5.26.2): `columns` bytes a record, the rows that fill
/// whole records transposed, the bytes after them as they are.
fn untranspose(transposed: &[u8], columns: usize, out: &mut Vec<u8>) {
    /// Rows put in place at a time: a tile of `TILE × columns` bytes stays
    /// in the cache while each column's run of `TILE` bytes is read.
    const TILE: usize = 64;
    let rows = transposed.len() / columns;
    let whole = rows * columns;
    let start = out.len();
    out.resize(start + whole, 0);
    let records = &mut out[start..];
    let mut first = 0;
    while first < rows {
        let n = TILE.min(rows - first);
        let tile = &mut records[first * columns..(first + n) * columns];
        for column in 0..columns {
            let run = &transposed[column * rows + first..column * rows + first + n];
            for (row, &byte) in run.iter().enumerate() {
                tile[row * columns + column] = byte;
            }
        }
        first += n;
    }
    out.extend_from_slice(&transposed[whole..]);
}

#[cfg(test)]
mod tests {
    use super::untranspose;

    #[test]
    fn untranspose_rows_and_rest() {
        // Three records of two bytes (a1 a2, b1 b2, c1 c2) and one byte
        // more, as a transposing writer stores them.
        let transposed = [0xa1, 0xb1, 0xc1, 0xa2, 0xb2, 0xc2, 0xff];
        let mut out = vec![0x00];
        untranspose(&transposed, 2, &mut out);
        assert_eq!(out, [0x00, 0xa1, 0xa2, 0xb1, 0xb2, 0xc1, 0xc2, 0xff]);
        // Fewer bytes than one record: as they are.
        let mut out = Vec::new();
        untranspose(&[1, 2], 3, &mut out);
        assert_eq!(out, [1, 2]);
    }
}
