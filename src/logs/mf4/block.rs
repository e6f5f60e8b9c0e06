//! The block layer of an MDF 4 file (ASAM MDF 4.1 §4.4; docs/formats.md#mf4):
//! every block is `##XX`, 4 reserved bytes, its u64 length, its u64 link count,
//! the links (absolute file offsets, 0 for none) and its data, all
//! little-endian. [`Source`] reads blocks from anywhere in the file and
//! checks what the file claims before anything is allocated.

use std::collections::HashSet;
use std::io::{self, Read, Seek, SeekFrom};

use crate::logs::bytes::padded;
use crate::logs::FormatError;
use crate::logs::{BinaryError, LogError, LogErrorKind, LogFormat, MAX_RECORD_LEN};

/// The block header: id, reserved, length, link count.
pub(super) const HEADER_LEN: u64 = 24;

/// The most links a list block (DL) or a conversion's references hold
/// that the reader reads: a DL of 16 MiB of links.
const MAX_LINKS: u64 = (MAX_RECORD_LEN / 8) as u64;

/// A block as read: where it is, its links and the
/// first bytes of its data (as many as the caller asked for).
#[derive(Debug)]
pub(super) struct Block {
    /// The block's offset in the file.
    pub(super) at: u64,
    /// The links.
    pub(super) links: Vec<u64>,
    /// The data after the links, up to the bytes asked for.
    pub(super) data: Vec<u8>,
}

impl Block {
    /// Return link `i`, 0 (none) where the block has fewer.
    pub(super) fn link(&self, i: usize) -> u64 {
        self.links.get(i).copied().unwrap_or(0)
    }

    /// Return the offset of the block's data in the file.
    pub(super) fn data_at(&self) -> u64 {
        self.at + HEADER_LEN + 8 * self.links.len() as u64
    }

    /// Return the u8 at `at` of the data, 0 where it has fewer bytes.
    pub(super) fn u8(&self, at: usize) -> u8 {
        self.data.get(at).copied().unwrap_or(0)
    }

    /// Return the little-endian u16 at `at` of the data.
    pub(super) fn u16(&self, at: usize) -> u16 {
        u16::from_le_bytes(padded(&self.data, at))
    }

    /// Return the little-endian u32 at `at` of the data.
    pub(super) fn u32(&self, at: usize) -> u32 {
        u32::from_le_bytes(padded(&self.data, at))
    }

    /// Return the little-endian u64 at `at` of the data.
    pub(super) fn u64(&self, at: usize) -> u64 {
        u64::from_le_bytes(padded(&self.data, at))
    }

    /// Return the little-endian f64 at `at` of the data.
    pub(super) fn f64(&self, at: usize) -> f64 {
        f64::from_le_bytes(padded(&self.data, at))
    }
}

/// The file, read at any offset, with its length and the bytes read so far.
#[derive(Debug)]
pub(super) struct Source<R> {
    reader: R,
    /// The file's length.
    pub(super) len: u64,
    /// Bytes read so far (for progress).
    pub(super) read: u64,
}

impl<R: Read + Seek> Source<R> {
    /// Take the file; its length is where its end is.
    pub(super) fn new(mut reader: R) -> io::Result<Self> {
        let len = reader.seek(SeekFrom::End(0))?;
        reader.seek(SeekFrom::Start(0))?;
        Ok(Source {
            reader,
            len,
            read: 0,
        })
    }

    /// Read into `buf` from `offset`, as much as the file has; the bytes read.
    pub(super) fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> Result<usize, LogError> {
        if offset >= self.len {
            return Ok(0);
        }
        self.reader.seek(SeekFrom::Start(offset))?;
        let mut got = 0;
        while got < buf.len() {
            match self.reader.read(&mut buf[got..]) {
                Ok(0) => break,
                Ok(n) => got += n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e.into()),
            }
        }
        self.read += got as u64;
        Ok(got)
    }

    /// Check that a link leads into the file, with room for a block header.
    pub(super) fn check_link(&self, link: u64) -> Result<(), LogError> {
        if link < 64 || link.saturating_add(HEADER_LEN) > self.len {
            return Err(damaged(
                link,
                BinaryError::LinkOutOfFile {
                    link,
                    len: self.len,
                },
            ));
        }
        Ok(())
    }

    /// Read the header of the block at `at` and check that it is one of
    /// `ids` (e.g. `"##DG"`, or `"##DT|##DZ|##DL|##HL"` written as a list):
    /// its id, length and link count.
    pub(super) fn header(
        &mut self,
        at: u64,
        ids: &'static str,
    ) -> Result<([u8; 4], u64, u64), LogError> {
        self.check_link(at)?;
        let mut head = [0u8; HEADER_LEN as usize];
        let got = self.read_at(at, &mut head)?;
        if got < head.len() {
            return Err(damaged(
                at,
                BinaryError::Truncated {
                    needed: HEADER_LEN,
                    found: got as u64,
                },
            ));
        }
        let id: [u8; 4] = padded(&head, 0);
        let wanted = ids
            .split('|')
            .any(|wanted| wanted.as_bytes() == id.as_slice());
        if !wanted {
            return Err(damaged(
                at,
                BinaryError::UnexpectedBlock {
                    expected: ids,
                    found: id,
                },
            ));
        }
        let len = u64::from_le_bytes(padded(&head, 8));
        let links = u64::from_le_bytes(padded(&head, 16));
        if len < HEADER_LEN || links > (len - HEADER_LEN) / 8 {
            return Err(damaged(at + 8, BinaryError::BadLength { length: len }));
        }
        if links > MAX_LINKS {
            return Err(damaged(
                at + 16,
                BinaryError::TooLarge {
                    length: links,
                    limit: MAX_LINKS,
                },
            ));
        }
        Ok((id, len, links))
    }

    /// Read the block at `at`, one of `ids`, with its links and up to
    /// `data` bytes of its data (fewer where the block or the file has
    /// fewer).
    pub(super) fn block(
        &mut self,
        at: u64,
        ids: &'static str,
        data: usize,
    ) -> Result<Block, LogError> {
        let (_, len, links) = self.header(at, ids)?;
        let links_len = 8 * links as usize;
        let data_len = ((len - HEADER_LEN) as usize - links_len).min(data);
        let mut bytes = vec![0u8; links_len + data_len];
        let got = self.read_at(at + HEADER_LEN, &mut bytes)?;
        if got < links_len {
            return Err(damaged(
                at,
                BinaryError::Truncated {
                    needed: HEADER_LEN + links_len as u64,
                    found: HEADER_LEN + got as u64,
                },
            ));
        }
        bytes.truncate(got);
        let data = bytes.split_off(links_len);
        let links = bytes
            .chunks_exact(8)
            .map(|link| u64::from_le_bytes(padded(link, 0)))
            .collect();
        Ok(Block { at, links, data })
    }

    /// Return the text of the TX block at `at` (up to `max` bytes, to the
    /// first NUL), or `None` without one; an MD block or a damaged link
    /// reads as no text.
    pub(super) fn text(&mut self, at: u64, max: usize) -> Result<Option<String>, LogError> {
        if at == 0 {
            return Ok(None);
        }
        let block = match self.block(at, "##TX|##MD", max) {
            Ok(block) => block,
            Err(_) => return Ok(None),
        };
        let end = block
            .data
            .iter()
            .position(|&b| b == 0)
            .unwrap_or(block.data.len());
        Ok(Some(
            String::from_utf8_lossy(block.data.get(..end).unwrap_or_default()).into_owned(),
        ))
    }
}

/// A damaged structure at `offset`, as the [`LogError`] that ends the
/// reading.
pub(super) fn damaged(offset: u64, reason: BinaryError) -> LogError {
    LogError::new(None, LogErrorKind::Damaged(binary(offset, reason)))
}

/// A [`FormatError::Binary`] of the MF4 format.
pub(super) fn binary(offset: u64, reason: BinaryError) -> FormatError {
    FormatError::Binary {
        format: LogFormat::Mf4,
        offset,
        reason,
    }
}

/// Follows a chain of blocks (`next` links; a data list's chain also
/// takes the data blocks it names) and says when it loops: a chain never
/// holds the same block twice (checked exactly for its first 65 536
/// blocks), nor more blocks than the file has room for.
#[derive(Debug, Default)]
pub(super) struct Chain {
    seen: HashSet<u64>,
    count: u64,
}

impl Chain {
    /// Take the next block of the chain, at `at`, in a file of `len` bytes.
    pub(super) fn visit(&mut self, at: u64, len: u64) -> Result<(), LogError> {
        self.count += 1;
        if self.count > len / HEADER_LEN + 1 {
            return Err(damaged(at, BinaryError::LinkLoop));
        }
        if self.seen.len() < 1 << 16 && !self.seen.insert(at) {
            return Err(damaged(at, BinaryError::LinkLoop));
        }
        Ok(())
    }
}
