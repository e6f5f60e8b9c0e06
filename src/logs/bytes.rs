//! The one byte layer of the binary formats (pcap, pcapng, BLF, MF4;
//! docs/formats.md): the integers of a header, block or record at a byte
//! offset, in the file's byte order. Each format's reader checks a
//! structure's length before it reads the fields in it; a field past the
//! end reads as 0 rather than panicking.

/// The `N` bytes at `at` in `bytes`; zeros when fewer than `N` are there.
#[cfg(feature = "pcap")]
#[inline]
pub(crate) fn array<const N: usize>(bytes: &[u8], at: usize) -> [u8; N] {
    bytes
        .get(at..)
        .and_then(<[u8]>::first_chunk::<N>)
        .copied()
        .unwrap_or([0; N])
}

/// The `N` bytes at `at` in `bytes`, zeros where `bytes` ends first (the
/// bytes before its end are kept: an MF4 block's data may be shorter than
/// the fields its type defines).
#[cfg(feature = "mf4")]
pub(crate) fn padded<const N: usize>(bytes: &[u8], at: usize) -> [u8; N] {
    let mut out = [0; N];
    if let Some(src) = bytes.get(at..) {
        let n = src.len().min(N);
        out[..n].copy_from_slice(&src[..n]);
    }
    out
}

/// The little-endian `u16` at `at` in `bytes` (0 past the end).
#[cfg(feature = "blf")]
pub(crate) fn u16_le(bytes: &[u8], at: usize) -> u16 {
    bytes
        .get(at..at + 2)
        .and_then(|b| b.first_chunk::<2>())
        .map_or(0, |b| u16::from_le_bytes(*b))
}

/// The little-endian `u32` at `at` in `bytes` (0 past the end).
#[cfg(feature = "blf")]
pub(crate) fn u32_le(bytes: &[u8], at: usize) -> u32 {
    bytes
        .get(at..at + 4)
        .and_then(|b| b.first_chunk::<4>())
        .map_or(0, |b| u32::from_le_bytes(*b))
}

/// The little-endian `u64` at `at` in `bytes` (0 past the end).
#[cfg(feature = "blf")]
pub(crate) fn u64_le(bytes: &[u8], at: usize) -> u64 {
    bytes
        .get(at..at + 8)
        .and_then(|b| b.first_chunk::<8>())
        .map_or(0, |b| u64::from_le_bytes(*b))
}

/// The `u16` at `at` in `bytes`, big-endian or little-endian as the file
/// says (pcap, pcapng; 0 past the end).
#[cfg(feature = "pcap")]
pub(crate) fn u16_at(bytes: &[u8], at: usize, big_endian: bool) -> u16 {
    let b = array(bytes, at);
    if big_endian {
        u16::from_be_bytes(b)
    } else {
        u16::from_le_bytes(b)
    }
}

/// The `u32` at `at` in `bytes`, big-endian or little-endian as the file
/// says (pcap, pcapng; 0 past the end).
#[cfg(feature = "pcap")]
pub(crate) fn u32_at(bytes: &[u8], at: usize, big_endian: bool) -> u32 {
    let b = array(bytes, at);
    if big_endian {
        u32::from_be_bytes(b)
    } else {
        u32::from_le_bytes(b)
    }
}

#[cfg(all(feature = "pcap", feature = "blf", feature = "mf4"))]
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_at_an_offset() {
        let bytes = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        assert_eq!(u16_le(&bytes, 1), 0x0302);
        assert_eq!(u32_le(&bytes, 0), 0x0403_0201);
        assert_eq!(u64_le(&bytes, 1), 0x0908_0706_0504_0302);
        assert_eq!(u16_at(&bytes, 0, true), 0x0102);
        assert_eq!(u32_at(&bytes, 0, true), 0x0102_0304);
        assert_eq!(u32_at(&bytes, 0, false), 0x0403_0201);
    }

    #[test]
    fn past_the_end() {
        let bytes = [1, 2, 3];
        assert_eq!(u32_le(&bytes, 0), 0);
        assert_eq!(u16_le(&bytes, 2), 0);
        assert_eq!(u16_at(&bytes, 9, true), 0);
        assert_eq!(padded::<4>(&bytes, 1), [2, 3, 0, 0]);
        assert_eq!(padded::<2>(&bytes, 5), [0, 0]);
    }
}
