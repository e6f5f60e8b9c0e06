//! The fast path: the `candump -l` line shape in one pass, with SWAR.

use super::frame::Canonical;
use super::timestamp::parse_canonical_timestamp;
use crate::can::{CanId, Direction, FdFlags, FrameHeader, FD_MAX_LEN};
use crate::logs::lex::swar::{
    hex_bytes64, hex_lanes, lanes_before, load16, non_graphic, non_hex64, pack_hex, ZERO_CHARS,
};
use crate::logs::lex::HEX_TABLE;

/// The line shape `candump -l` writes, read in one pass from the start of
/// `buf`: `(` 10 digits `.` 6 digits `) ` interface (1 to 15 bytes) space,
/// identifier `#`, `R[len]`, `#<flags><data>` or `<data>`, an optional
/// direction (` R`, ` T`), then `\n`, `\r\n` or the end of `buf`. Return the frame and the
/// number of bytes read (line end included), or `None` for any other shape
/// (which [`parse_general`] then reads, or reports). On every line it
/// accepts it returns what [`parse_general`] returns.
///
/// The data bytes are written into `data`, which holds zeros on entry: the
/// first `len` bytes are the data, the rest stays zero. After `None`, `data`
/// may hold anything.
///
/// `hint` is the interface name of an earlier line that this path read, or
/// [`IfaceHint::NONE`]: a line that names the same interface is known to
/// name it validly, and its name is not checked again; a line that names
/// another leaves its own name there.
#[inline(always)]
pub(super) fn parse_canonical_log<'a>(
    buf: &'a [u8],
    data: &mut [u8; FD_MAX_LEN],
    hint: &mut IfaceHint,
) -> Option<(Canonical<'a>, usize)> {
    // Timestamp, bytes 0..20, `(SSSSSSSSSS.UUUUUU) `.
    let timestamp = parse_canonical_timestamp(buf.first_chunk::<20>()?)?;

    // Interface: printable ASCII up to a space, not starting with `(`/`#`.
    let iface_start = 20;
    let word = u64::from_le_bytes(*buf.get(iface_start..)?.first_chunk::<8>()?);
    let same_iface = word & hint.mask == hint.pattern;
    if !same_iface {
        *hint = read_iface(buf, word)?;
    }
    // Else the bytes of a name this path took, then a space: the checks of
    // `read_iface` would find the same.
    let iface_len = usize::from(hint.len);
    let iface_key = hint.key;
    let id_start = iface_start + iface_len + 1;
    let iface = buf.get(iface_start..id_start - 1)?;

    // Identifier: 3 hex digits and `#`, else 8 and `#`.
    let ids = buf.get(id_start..)?;
    let (id, body) = match ids.first_chunk::<4>()? {
        &[a, b, c, b'#'] => {
            let (a, b, c) = (
                HEX_TABLE[usize::from(a)],
                HEX_TABLE[usize::from(b)],
                HEX_TABLE[usize::from(c)],
            );
            if (a | b | c) & 0xF0 != 0 {
                return None;
            }
            let raw = u32::from(a) << 8 | u32::from(b) << 4 | u32::from(c);
            (CanId::standard(raw)?, id_start + 4)
        }
        _ => {
            let chunk = ids.first_chunk::<9>()?;
            if chunk[8] != b'#' {
                return None;
            }
            let w = u128::from(u64::from_le_bytes(*chunk.first_chunk::<8>()?)) | ZERO_CHARS << 64;
            let (values, bad) = hex_lanes(w);
            if bad != 0 {
                return None;
            }
            let raw = (pack_hex(values) as u32).swap_bytes();
            (CanId::extended(raw)?, id_start + 9)
        }
    };

    // Each arm makes the header with the constructor of the kind it read:
    // no match on the kind is left for the frame, only the kind's cut.
    let (header, end) = match buf.get(body) {
        Some(b'R' | b'r') => match buf.get(body + 1) {
            Some(&d @ b'0'..=b'8') => (FrameHeader::remote(id, d - b'0'), body + 2),
            _ => (FrameHeader::remote(id, 0), body + 1),
        },
        Some(b'#') => {
            let flags = HEX_TABLE[usize::from(*buf.get(body + 1)?)];
            if flags & 0xF0 != 0 {
                return None;
            }
            let (len, end) = decode_fd_data(buf, body + 2, data)?;
            (FrameHeader::fd(id, FdFlags::new(flags)?, len), end)
        }
        _ => {
            // Classic data: at most 16 hex digits, so one word holds them
            // and the byte after them.
            let (values, bad) = hex_lanes(load16(buf, body));
            let digits = lanes_before(bad);
            if digits % 2 != 0 {
                return None;
            }
            let packed = pack_hex(values) & KEEP_BYTES[(digits / 2) & 15];
            if let Some(first) = data.first_chunk_mut::<8>() {
                *first = packed.to_le_bytes();
            }
            (FrameHeader::data(id, (digits / 2) as u8), body + digits)
        }
    };

    // Optional direction, then the line end.
    let mut direction = None;
    let mut used = end;
    if let Some(&[b' ', d @ (b'R' | b'T')]) = buf.get(end..).and_then(|r| r.first_chunk::<2>()) {
        direction = Some(if d == b'R' {
            Direction::Rx
        } else {
            Direction::Tx
        });
        used += 2;
    }
    match buf.get(used) {
        None => {}
        Some(b'\n') => used += 1,
        Some(b'\r') => match buf.get(used + 1) {
            None => used += 1,
            Some(b'\n') => used += 2,
            Some(_) => return None,
        },
        Some(_) => return None,
    }
    let frame = Canonical {
        timestamp,
        iface,
        iface_key,
        #[cfg(feature = "std")]
        same_iface,
        header,
        direction,
    };
    Some((frame, used))
}

/// An interface name as the first bytes of a line's interface word (bytes
/// 20 to 27 of a `candump -l` line), with the space after it: a line whose
/// word starts with the same bytes names the same interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct IfaceHint {
    /// The name's bytes and the space, zeros above them.
    pattern: u64,
    /// The bytes of the word that `pattern` covers.
    mask: u64,
    /// The name's length.
    len: u8,
    /// The name's key ([`Parsed::iface_key`]).
    key: u64,
}

impl IfaceHint {
    /// No name: every word is checked.
    pub(super) const NONE: IfaceHint = IfaceHint {
        pattern: 1,
        mask: 0,
        len: 0,
        key: 0,
    };
}

/// Read the interface name of a `candump -l` line from byte 20 (`word`,
/// the first 8 of its bytes): printable ASCII up to a space, 1 to 15 bytes,
/// not starting with `(` or `#`. Return it as a hint for the lines after it
/// (one that matches nothing when the name and its space take more than 8
/// bytes), or `None` for any other shape.
#[inline(always)]
fn read_iface(buf: &[u8], word: u64) -> Option<IfaceHint> {
    let iface_start = 20;
    let stop = non_graphic(u128::from(word)) as u64;
    let iface_len = if stop != 0 {
        (stop.trailing_zeros() / 8) as usize
    } else {
        lanes_before(non_graphic(load16(buf, iface_start)))
    };
    if iface_len == 0
        || iface_len == 16
        || buf.get(iface_start + iface_len) != Some(&b' ')
        || matches!(buf.get(iface_start), Some(b'(' | b'#'))
    {
        return None;
    }
    let key = if iface_len <= 8 {
        word & KEEP_BYTES[iface_len]
    } else {
        0
    };
    let (pattern, mask) = if iface_len < 8 {
        let mask = KEEP_BYTES[iface_len + 1];
        (word & mask, mask)
    } else {
        (IfaceHint::NONE.pattern, IfaceHint::NONE.mask)
    };
    Some(IfaceHint {
        pattern,
        mask,
        len: iface_len as u8,
        key,
    })
}

/// A mask of the low `n` bytes of a `u64`, for `n` in 0..=8.
pub(super) const KEEP_BYTES: [u64; 16] = {
    let mut table = [u64::MAX; 16];
    let mut n = 0;
    while n < 8 {
        table[n] = (1u64 << (8 * n)) - 1;
        n += 1;
    }
    table
};

/// Decode the hex digits of CAN FD data from `start` up to the first other
/// byte into `data` (zeros on entry; the bytes after the data stay zero);
/// return the number of bytes and the index after the digits, or `None`
/// for an odd count (which [`parse_general`] reports). Stops after 64
/// bytes.
///
/// 32 digits (16 bytes) at a time, from four 8-byte loads checked at once
/// ([`non_hex64`]) and packed ([`hex_bytes64`]): the data's lengths are
/// mostly 16 or 32 bytes (the `fd` mix), a load or two. After a full
/// 32 digits, the byte that follows tells whether more follow, so that
/// such data needs no load of the bytes past it. Near the end of `buf`
/// (fewer than 32 bytes left), [`decode_fd_words`] reads the rest.
#[inline(never)]
pub(super) fn decode_fd_data(
    buf: &[u8],
    start: usize,
    data: &mut [u8; FD_MAX_LEN],
) -> Option<(u8, usize)> {
    let mut end = start;
    let mut len = 0;
    while let Some(dst) = data
        .get_mut(len..)
        .and_then(|rest| rest.first_chunk_mut::<16>())
    {
        let Some(chunk) = buf.get(end..).and_then(|rest| rest.first_chunk::<32>()) else {
            return decode_fd_words(buf, end, len, data);
        };
        let (a, rest) = chunk.split_first_chunk::<8>()?;
        let (b, rest) = rest.split_first_chunk::<8>()?;
        let (c, d) = rest.split_first_chunk::<8>()?;
        let d = d.first_chunk::<8>()?;
        let words = [a, b, c, d].map(|w| u64::from_le_bytes(*w));
        let bad = words.map(non_hex64);
        // Written as four 4-byte pieces, not one 16-byte word built with
        // shifts: so the compiler packs the four words in SSE registers too
        // (BENCHMARKS.md, "CAN FD data, candump and ASC").
        let bytes = words.map(hex_bytes64);
        for (to, b) in dst.chunks_exact_mut(4).zip(bytes) {
            to.copy_from_slice(&b.to_le_bytes());
        }
        if bad[0] | bad[1] | bad[2] | bad[3] != 0 {
            let packed = bytes.map(u128::from);
            let packed = packed[0] | packed[1] << 32 | packed[2] << 64 | packed[3] << 96;
            // The data ends in these 32 bytes: at the first lane flagged.
            let low = u128::from(bad[0]) | u128::from(bad[1]) << 64;
            let high = u128::from(bad[2]) | u128::from(bad[3]) << 64;
            let digits = if low != 0 {
                lanes_before(low)
            } else {
                16 + lanes_before(high)
            };
            if digits % 2 != 0 {
                return None;
            }
            // Fewer than 32 digits: the bytes they spell, zeros after.
            let keep = (1u128 << (4 * digits)) - 1;
            *dst = (packed & keep).to_le_bytes();
            return Some(((len + digits / 2) as u8, end + digits));
        }
        end += 32;
        len += 16;
        if buf
            .get(end)
            .map_or(true, |&b| HEX_TABLE[usize::from(b)] > 0xF)
        {
            break;
        }
    }
    Some((len as u8, end))
}

/// [`decode_fd_data`] from `start` on, with `len` bytes (a multiple of 16)
/// already in `data`, 16 digits at a time from [`load16`], which reads
/// zeros past the end of `buf`: the last digits of a buffer.
#[cold]
#[inline(never)]
fn decode_fd_words(
    buf: &[u8],
    start: usize,
    len: usize,
    data: &mut [u8; FD_MAX_LEN],
) -> Option<(u8, usize)> {
    let mut end = start;
    let mut len = len;
    for dst in data.get_mut(len..)?.chunks_exact_mut(8) {
        let (values, bad) = hex_lanes(load16(buf, end));
        let digits = lanes_before(bad);
        if digits % 2 != 0 {
            return None;
        }
        let packed = pack_hex(values) & KEEP_BYTES[(digits / 2) & 15];
        dst.copy_from_slice(&packed.to_le_bytes());
        end += digits;
        len += digits / 2;
        // After a full word, the byte that follows tells whether another
        // word of digits follows.
        if digits < 16
            || buf
                .get(end)
                .map_or(true, |&b| HEX_TABLE[usize::from(b)] > 0xF)
        {
            break;
        }
    }
    Some((len as u8, end))
}
