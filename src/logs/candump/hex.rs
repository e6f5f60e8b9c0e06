//! The one hex decoder of both formats and of the fast path.

use crate::can::FD_MAX_LEN;
use crate::logs::lex::swar::{hex_lanes, lanes_before, load16, pack_hex, ZERO_CHARS};

/// Decode the hex digits `line[start..end]` into `out` (whose unused bytes
/// stay zero); `end - start` is at most `2 * out.len()`. An odd count is
/// decoded as if a `0` followed. On a non-hex byte, return its index.
#[inline(always)]
pub(super) fn decode_hex(
    line: &[u8],
    start: usize,
    end: usize,
    out: &mut [u8; FD_MAX_LEN],
) -> Result<(), usize> {
    let digits = line.get(start..end).unwrap_or_default();
    let mut chunks = digits.chunks_exact(16);
    let mut outs = out.chunks_exact_mut(8);
    let mut at = start;
    for (chunk, dst) in (&mut chunks).zip(&mut outs) {
        let w = chunk
            .first_chunk::<16>()
            .map_or(0, |c| u128::from_le_bytes(*c));
        let (values, bad) = hex_lanes(w);
        if bad != 0 {
            return Err(at + lanes_before(bad));
        }
        dst.copy_from_slice(&pack_hex(values).to_le_bytes());
        at += 16;
    }
    let rest = chunks.remainder().len();
    if rest == 0 {
        return Ok(());
    }
    // Load the 16 bytes that end where the digits end and shift the digits
    // down to the first lanes; fill the lanes above with '0'.
    let w = match line.get(..end).and_then(|s| s.last_chunk::<16>()) {
        Some(last) => u128::from_le_bytes(*last) >> (8 * (16 - rest)),
        None => load16(line, at) & (u128::MAX >> (8 * (16 - rest))),
    };
    let w = w | (ZERO_CHARS << (8 * rest));
    let (values, bad) = hex_lanes(w);
    if bad != 0 {
        return Err(at + lanes_before(bad));
    }
    if let Some(dst) = outs.next() {
        dst.copy_from_slice(&pack_hex(values).to_le_bytes());
    }
    Ok(())
}
