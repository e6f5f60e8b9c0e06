//! The SWAR tricks of the text readers (the line splitter, candump's and
//! ASC's fast paths): wide-word arithmetic over the 16 bytes of a `u128`
//! ("SIMD within a register"): each byte is one lane, byte 0 (the first
//! character) the least significant.

/// `b` in every lane.
pub(crate) const fn splat(b: u8) -> u128 {
    u128::from_le_bytes([b; 16])
}

pub(crate) const LOW7: u128 = splat(0x7F);
pub(crate) const HIGH: u128 = splat(0x80);
pub(crate) const ONES: u128 = splat(0x01);
pub(crate) const NIBBLES: u128 = splat(0x0F);
pub(crate) const ZERO_CHARS: u128 = splat(b'0');

/// The high bit of every lane whose byte is at least `c` (for `c` in
/// 1..=0x80), for lanes below 0x80 only; no carry crosses lanes.
#[inline(always)]
const fn ge(low7: u128, c: u8) -> u128 {
    low7.wrapping_add(splat(0x80 - c)) & HIGH
}

/// A mask with the high bit set in the lanes of `w` holding `b` (and
/// possibly in later lanes: the first set lane is exact).
#[inline(always)]
pub(crate) const fn first_eq(w: u128, b: u8) -> u128 {
    let x = w ^ (ONES * b as u128);
    x.wrapping_sub(ONES) & !x & HIGH
}

/// Split 16 characters into their hex values (one per lane, valid where
/// the character is a hex digit) and a mask with the high bit of every
/// lane that is not a hex digit.
#[inline(always)]
pub(crate) const fn hex_lanes(w: u128) -> (u128, u128) {
    let x = w & LOW7;
    let digit = ge(x, b'0') & !ge(x, b'9' + 1);
    let l = x | splat(0x20);
    let letter = ge(l, b'a') & !ge(l, b'f' + 1);
    let bad = !(digit | letter) | w;
    // '0'..'9' → 0..9; 'A'..'F' and 'a'..'f' → 1..6 + 9.
    let values = (w & NIBBLES) + ((w >> 6) & ONES) * 9;
    (values, bad & HIGH)
}

/// A mask with the high bit of every lane that is not a decimal digit;
/// `d` is the characters XOR `'0'`.
#[inline(always)]
pub(crate) const fn non_digits(d: u128) -> u128 {
    ((d & LOW7).wrapping_add(splat(0x76)) | d) & HIGH
}

/// A mask with the high bit of every lane that is not printable ASCII
/// (0x21..=0x7E).
#[inline(always)]
pub(crate) const fn non_graphic(w: u128) -> u128 {
    let x = w & LOW7;
    (!(ge(x, 0x21) & !ge(x, 0x7F)) | w) & HIGH
}

/// Pack 16 hex values (one per lane, first the most significant nibble)
/// into 8 bytes, first byte least significant: each half of the word apart,
/// so that no shift crosses the two 64-bit registers it is made of.
#[inline(always)]
pub(crate) const fn pack_hex(values: u128) -> u64 {
    pack_hex64(values as u64) as u64 | (pack_hex64((values >> 64) as u64) as u64) << 32
}

/// Pack 8 hex values (one per lane, first the most significant nibble)
/// into 4 bytes, first byte least significant.
#[inline(always)]
const fn pack_hex64(values: u64) -> u32 {
    // Pairs of lanes → one byte in the high half of each 16-bit lane: with
    // `a` and `b` the pair's values (below 16), `a + 256 b` times
    // `1 + 2^12` puts `16 a + b` in bits 8..16 of the lane; the other terms
    // (a at bits 0..4, the lane below's b at bits 4..8) stay out of them, so
    // nothing carries.
    let x = (values.wrapping_mul(0x1001) >> 8) & 0x00FF_00FF_00FF_00FF;
    let x = (x | (x >> 8)) & 0x0000_FFFF_0000_FFFF;
    (x | (x >> 16)) as u32
}

/// Convert 8 decimal digit values (one per lane, first the most
/// significant) to their number.
#[inline(always)]
pub(crate) const fn decimal8(d: u64) -> u64 {
    let x = (d.wrapping_mul(10) + (d >> 8)) & 0x00FF_00FF_00FF_00FF;
    let x = (x.wrapping_mul(100) + (x >> 16)) & 0x0000_FFFF_0000_FFFF;
    (x.wrapping_mul(10_000) + (x >> 32)) & 0xFFFF_FFFF
}

/// Convert 16 decimal digit values (one per lane, first the most
/// significant) to their number.
#[inline(always)]
pub(crate) const fn decimal16(d: u128) -> u64 {
    decimal8(d as u64) * 100_000_000 + decimal8((d >> 64) as u64)
}

/// The number of lanes before the first lane flagged in `mask` (16 when
/// none is).
#[inline(always)]
pub(crate) const fn lanes_before(mask: u128) -> usize {
    (mask.trailing_zeros() / 8) as usize
}

/// The 16 bytes of `line` from `at` as a word; bytes past the end read as
/// 0x00, which is no hex digit, decimal digit, printable or white space.
#[inline(always)]
pub(crate) fn load16(line: &[u8], at: usize) -> u128 {
    match line.get(at..).and_then(|s| s.first_chunk::<16>()) {
        Some(chunk) => u128::from_le_bytes(*chunk),
        None => load16_short(line, at),
    }
}

#[cold]
#[inline(never)]
pub(crate) fn load16_short(line: &[u8], at: usize) -> u128 {
    let mut buf = [0u8; 16];
    if let Some(rest) = line.get(at..) {
        for (d, s) in buf.iter_mut().zip(rest) {
            *d = *s;
        }
    }
    u128::from_le_bytes(buf)
}

/// `b` in every lane of a `u64`.
const fn splat64(b: u8) -> u64 {
    u64::from_le_bytes([b; 8])
}

/// [`ge`] over the 8 lanes of a `u64`.
#[inline(always)]
const fn ge64(low7: u64, c: u8) -> u64 {
    low7.wrapping_add(splat64(0x80 - c)) & splat64(0x80)
}

/// [`hex_lanes`]'s mask for 8 characters, in a `u64` (the CAN FD data's
/// loop, which has no use for 16-byte lanes): the high bit of every lane
/// that is not a hex digit.
#[inline(always)]
pub(crate) const fn non_hex64(w: u64) -> u64 {
    let x = w & splat64(0x7F);
    // `x ^ '0'` is a digit's value, 10 and more for any other lane (below
    // 0x80, so adding 0x76 carries out of no lane).
    let not_digit = (x ^ splat64(b'0')).wrapping_add(splat64(0x76));
    let l = x | splat64(0x20);
    let letter = ge64(l, b'a') & !ge64(l, b'f' + 1);
    ((not_digit & !letter) | w) & splat64(0x80)
}

/// The 4 bytes that 8 hex digits spell (the first digit the high nibble of
/// the first byte), the first byte least significant; meaningful where all
/// 8 lanes are hex digits ([`non_hex64`] is 0).
#[inline(always)]
pub(crate) const fn hex_bytes64(w: u64) -> u32 {
    // '0'..'9' → 0..9; 'A'..'F' and 'a'..'f' → 1..6 + 9.
    let v = (w & splat64(0x0F)) + ((w >> 6) & splat64(0x01)) * 9;
    // Lane 2k: its value times 16 or the value of lane 2k + 1 (both below
    // 16, so no lane overflows); the odd lanes are dropped.
    let x = ((v << 4) | (v >> 8)) & 0x00FF_00FF_00FF_00FF;
    let x = (x | (x >> 8)) & 0x0000_FFFF_0000_FFFF;
    (x | (x >> 16)) as u32
}

/// Each trick against a byte-at-a-time model of what it promises, over
/// arbitrary words and over words of the characters that matter.
#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn lanes(w: u128) -> [u8; 16] {
        w.to_le_bytes()
    }

    fn high_bits(flags: impl Fn(u8) -> bool, w: u128) -> u128 {
        u128::from_le_bytes(lanes(w).map(|b| if flags(b) { 0x80 } else { 0 }))
    }

    fn hex_value(b: u8) -> Option<u8> {
        char::from(b).to_digit(16).map(|v| v as u8)
    }

    /// The bytes that pairs of hex digits spell, the first the high nibble.
    fn spelt(digits: &[u8]) -> Vec<u8> {
        digits
            .chunks(2)
            .map(|p| hex_value(p[0]).unwrap() << 4 | hex_value(p[1]).unwrap())
            .collect()
    }

    /// Words made of the bytes a candump line holds, and any byte.
    fn word() -> impl Strategy<Value = u128> {
        let byte = prop_oneof![
            3 => proptest::sample::select(b"0123456789abcdefABCDEFgGxX#()[] .\t\r\nR".to_vec()),
            1 => any::<u8>(),
        ];
        proptest::array::uniform16(byte).prop_map(u128::from_le_bytes)
    }

    proptest! {
        #[test]
        fn first_eq_finds_the_first_lane(bytes in proptest::array::uniform16(any::<u8>()), b in any::<u8>()) {
            let first = bytes.iter().position(|&x| x == b).unwrap_or(16);
            let mask = first_eq(u128::from_le_bytes(bytes), b);
            prop_assert_eq!((mask.trailing_zeros() / 8) as usize, first);
        }

        #[test]
        fn hex_lanes_is_hex_digit_by_digit(w in word()) {
            let (values, bad) = hex_lanes(w);
            prop_assert_eq!(bad, high_bits(|b| hex_value(b).is_none(), w));
            for (i, b) in lanes(w).into_iter().enumerate() {
                if let Some(v) = hex_value(b) {
                    prop_assert_eq!(lanes(values)[i], v, "lane {}", i);
                }
            }
        }

        #[test]
        fn hex64_is_hex_digit_by_digit(w in word()) {
            for half in [w as u64, (w >> 64) as u64] {
                let bytes = half.to_le_bytes();
                let flags = u64::from_le_bytes(bytes.map(|b| if hex_value(b).is_none() { 0x80 } else { 0 }));
                prop_assert_eq!(non_hex64(half), flags);
                if flags == 0 {
                    prop_assert_eq!(hex_bytes64(half).to_le_bytes().to_vec(), spelt(&bytes));
                }
            }
        }

        #[test]
        fn hex64_on_hex_digits(digits in proptest::array::uniform8(proptest::sample::select(b"0123456789abcdefABCDEF".to_vec()))) {
            let w = u64::from_le_bytes(digits);
            prop_assert_eq!(non_hex64(w), 0);
            prop_assert_eq!(hex_bytes64(w).to_le_bytes().to_vec(), spelt(&digits));
        }

        #[test]
        fn non_digits_is_decimal_digit_by_digit(w in word()) {
            let d = w ^ ZERO_CHARS;
            prop_assert_eq!(non_digits(d), high_bits(|b| !b.is_ascii_digit(), w));
        }

        #[test]
        fn non_graphic_is_printable_by_byte(w in word()) {
            prop_assert_eq!(non_graphic(w), high_bits(|b| !b.is_ascii_graphic(), w));
        }

        #[test]
        fn pack_hex_packs_pairs_of_nibbles(nibbles in proptest::array::uniform16(0u8..16)) {
            let values = u128::from_le_bytes(nibbles);
            let expected: Vec<u8> = nibbles.chunks(2).map(|p| p[0] << 4 | p[1]).collect();
            prop_assert_eq!(pack_hex(values).to_le_bytes().to_vec(), expected);
        }

        #[test]
        fn decimal_is_the_number_of_the_digits(digits in proptest::array::uniform16(0u8..10)) {
            let number = digits.iter().fold(0u64, |n, &d| n * 10 + u64::from(d));
            prop_assert_eq!(decimal16(u128::from_le_bytes(digits)), number);
            let eight: [u8; 8] = digits[..8].try_into().unwrap();
            let number8 = eight.iter().fold(0u64, |n, &d| n * 10 + u64::from(d));
            prop_assert_eq!(decimal8(u64::from_le_bytes(eight)), number8);
        }

        #[test]
        fn load16_reads_zeros_past_the_end(bytes in proptest::collection::vec(any::<u8>(), 0..40), at in 0usize..48) {
            let mut expected = [0u8; 16];
            for (i, e) in expected.iter_mut().enumerate() {
                *e = bytes.get(at + i).copied().unwrap_or(0);
            }
            prop_assert_eq!(load16(&bytes, at), u128::from_le_bytes(expected));
        }
    }
}
