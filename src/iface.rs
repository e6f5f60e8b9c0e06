//! Interface names as the log readers and the decoder compare them.

/// Whether two interface names are equal, compared in line: names are a
/// few bytes (`can0`, `vcan1`), and a call to `memcmp` per frame costs more
/// than the compare. Names of 4 to 8 bytes are compared as two
/// overlapping 4-byte words.
#[inline(always)]
pub(crate) fn same_name(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let word = |s: &[u8], at: usize| s.get(at..at + 4).map(|w| [w[0], w[1], w[2], w[3]]);
    match a.len() {
        n @ 4..=8 => word(a, 0) == word(b, 0) && word(a, n - 4) == word(b, n - 4),
        _ => a == b,
    }
}
