//! A small JSON writer for the decoder's records (docs/output.md#json).
//!
//! A record is built in a `Vec<u8>` the caller keeps (the program's block of
//! records, or a buffer kept per thread for `write_json`), key by key, so
//! that decoding a line allocates nothing (docs/output.md#json) and nothing
//! here can fail: the buffer is written out whole. Keys and the library's
//! constant texts (kind, class and flag names, descriptions) are written as
//! they are — a test checks that none of them needs escaping — and only
//! texts that come from the input (interface names, error messages) are
//! escaped as RFC 8259 says. Integers below 10^16, timestamps and hex data
//! are turned into digits several at a time in machine words (`digits8`,
//! `hex32`; property tests check them against the plain formatting),
//! larger integers through `itoa`, floats through `serde_json`, which
//! prints the shortest representation that reads back to the same value.
//! Short texts of the writer's own (keys, flags, kind names) are kept
//! padded to a fixed size ([`Padded`]) and written as one fixed-size copy
//! cut to their length, not through `memcpy`.

/// Writes one JSON object into a buffer, tracking whether a comma is
/// needed. Writing into a `Vec` cannot fail, so nothing here returns a
/// `Result`: a record is built in the buffer and written out whole.
pub(crate) struct Object<'w> {
    out: &'w mut Vec<u8>,
    first: bool,
}

impl<'w> Object<'w> {
    /// Open an object (`{`).
    #[inline]
    pub(crate) fn begin(out: &'w mut Vec<u8>) -> Self {
        out.push(b'{');
        Object { out, first: true }
    }

    /// Go on with an object whose `{` and first key are written already.
    #[inline]
    pub(crate) fn after_first(out: &'w mut Vec<u8>) -> Self {
        Object { out, first: false }
    }

    /// Write the key and return the buffer for its value. Keys are the
    /// contract's names (docs/output.md): ASCII letters, digits and `_`, which
    /// need no escaping.
    #[inline(always)]
    pub(crate) fn key(&mut self, key: &'static str) -> &mut Vec<u8> {
        debug_assert!(key.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_'));
        let name = key.as_bytes();
        let len = name.len();
        if !self.first && len <= 12 {
            // `,"key":` in one write of 16 bytes cut to its length (the
            // key is a constant: the bytes are too).
            let mut text = [0u8; 16];
            text[0] = b',';
            text[1] = b'"';
            if let Some(at) = text.get_mut(2..2 + len) {
                at.copy_from_slice(name);
            }
            text[2 + len] = b'"';
            text[3 + len] = b':';
            let end = self.out.len() + 4 + len;
            self.out.extend_from_slice(&text);
            self.out.truncate(end);
            return self.out;
        }
        if !self.first {
            self.out.push(b',');
        }
        self.first = false;
        self.out.push(b'"');
        self.out.extend_from_slice(name);
        self.out.extend_from_slice(b"\":");
        self.out
    }

    /// Write bytes that hold a comma, a key of the contract and the start
    /// of its value, all escaped already (`,"signals":{`), after at least
    /// one key: one write where [`key`](Self::key) makes several.
    #[inline]
    pub(crate) fn raw_after_first(&mut self, bytes: &[u8]) -> &mut Vec<u8> {
        debug_assert!(!self.first && bytes.first() == Some(&b','));
        self.out.extend_from_slice(bytes);
        self.out
    }

    /// Write a key with an unsigned integer value.
    #[inline]
    pub(crate) fn uint(&mut self, key: &'static str, value: u64) {
        let out = self.key(key);
        uint(out, value);
    }

    /// Write a key with a boolean value.
    #[inline(always)]
    pub(crate) fn bool(&mut self, key: &'static str, value: bool) {
        let out = self.key(key);
        out.extend_from_slice(if value { b"true" } else { b"false" });
    }

    /// Write a key with a string value from the input, escaped.
    #[inline(always)]
    pub(crate) fn str(&mut self, key: &'static str, value: &str) {
        let out = self.key(key);
        string(out, value);
    }

    /// Write a key with one of the library's constant texts (a name or a
    /// description), which need no escaping (`constant_texts_need_no_escaping`).
    #[inline(always)]
    pub(crate) fn name(&mut self, key: &'static str, value: &'static str) {
        debug_assert!(!needs_escaping(value), "{value:?}");
        let out = self.key(key);
        out.push(b'"');
        out.extend_from_slice(value.as_bytes());
        out.push(b'"');
    }

    /// Write a key with a string value given by its `Display`, escaped,
    /// without allocating.
    pub(crate) fn display(&mut self, key: &'static str, value: &impl std::fmt::Display) {
        let out = self.key(key);
        display_string(out, value);
    }

    /// Write a key with a `null` value.
    #[inline(always)]
    pub(crate) fn null(&mut self, key: &'static str) {
        self.key(key).extend_from_slice(b"null");
    }

    /// Write a key with a float value; NaN and infinities become `null`
    /// (docs/servo.md#cli-feedback, docs/output.md#pdo).
    pub(crate) fn float(&mut self, key: &'static str, value: f64) {
        let out = self.key(key);
        float(out, value);
    }

    /// Write a key with an array of the library's constant names, which
    /// need no escaping.
    pub(crate) fn names(
        &mut self,
        key: &'static str,
        values: impl IntoIterator<Item = &'static str>,
    ) {
        let out = self.key(key);
        out.push(b'[');
        for (i, value) in values.into_iter().enumerate() {
            debug_assert!(!needs_escaping(value), "{value:?}");
            if i > 0 {
                out.push(b',');
            }
            out.push(b'"');
            out.extend_from_slice(value.as_bytes());
            out.push(b'"');
        }
        out.push(b']');
    }

    /// Close the object (`}`).
    #[inline]
    pub(crate) fn end(self) {
        self.out.push(b'}');
    }
}

/// A short text of the writer's own (keys with the comma before them, the
/// frame's flags, a kind's name) in an array of `N` bytes, written as one
/// copy of the whole array cut to the text's length: a copy of a length
/// known at compile time is a few moves, where a length known only at run
/// time is a call to `memcpy`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Padded<const N: usize> {
    bytes: [u8; N],
    len: u8,
}

impl<const N: usize> Padded<N> {
    /// No text.
    pub(crate) const EMPTY: Self = Padded {
        bytes: [0; N],
        len: 0,
    };

    /// The texts of `parts` one after the other; more than `N` bytes (or
    /// than 255) fails to compile where it is a constant.
    pub(crate) const fn concat(parts: &[&[u8]]) -> Self {
        let mut bytes = [0u8; N];
        let mut len = 0;
        let mut p = 0;
        while p < parts.len() {
            let part = parts[p];
            let mut i = 0;
            while i < part.len() {
                bytes[len] = part[i];
                len += 1;
                i += 1;
            }
            p += 1;
        }
        assert!(len <= u8::MAX as usize);
        Padded {
            bytes,
            len: len as u8,
        }
    }

    /// The text `text`, if it fits in `N` bytes.
    pub(crate) fn new(text: &[u8]) -> Option<Self> {
        let mut bytes = [0u8; N];
        bytes.get_mut(..text.len())?.copy_from_slice(text);
        Some(Padded {
            bytes,
            len: u8::try_from(text.len()).ok()?,
        })
    }

    /// Write the text: the whole array, cut to the text's length.
    #[inline(always)]
    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        let end = out.len() + usize::from(self.len);
        out.extend_from_slice(&self.bytes);
        out.truncate(end);
    }
}

/// A record's bytes, or a run of them, built in an array of `N` bytes on
/// the stack and appended to the buffer in one write ([`flush`](Self::flush)):
/// each piece is a copy of a length known at compile time to the end of
/// what is written, which then moves on by the piece's length, so that a
/// record of twenty keys costs one check of the buffer's capacity, not
/// twenty. A piece that would pass the array's end is dropped and the
/// block marked full ([`is_full`](Self::is_full)): a writer sizes its
/// block for the longest record it builds from values of fixed size
/// (`datagram_records_as_the_plain_writer` in tests/library checks them at
/// their largest), and writes a text from the input that may not fit (an
/// interface name) another way when the block is full.
#[derive(Debug, Clone)]
pub(crate) struct Block<const N: usize> {
    bytes: [u8; N],
    len: usize,
    full: bool,
}

impl<const N: usize> Block<N> {
    /// An empty block.
    #[inline(always)]
    pub(crate) fn new() -> Self {
        Block {
            bytes: [0; N],
            len: 0,
            full: false,
        }
    }

    /// Write the `M` bytes of `piece` and move on by `len` of them (at
    /// most `M`): the rest are overwritten by the next piece or cut.
    #[inline(always)]
    fn put<const M: usize>(&mut self, piece: [u8; M], len: usize) {
        debug_assert!(len <= M);
        match self.bytes.get_mut(self.len..self.len + M) {
            Some(to) => {
                to.copy_from_slice(&piece);
                self.len += len.min(M);
            }
            None => self.full = true,
        }
    }

    /// Write a constant text (a key with its comma and colon).
    #[inline(always)]
    pub(crate) fn text<const M: usize>(&mut self, text: &[u8; M]) {
        self.put(*text, M);
    }

    /// Write a text of the writer's own kept padded ([`Padded`]).
    #[inline(always)]
    pub(crate) fn padded<const M: usize>(&mut self, text: &Padded<M>) {
        self.put(text.bytes, usize::from(text.len));
    }

    /// Write one byte.
    #[inline(always)]
    pub(crate) fn byte(&mut self, byte: u8) {
        self.put([byte], 1);
    }

    /// Write an unsigned integer in decimal, as [`uint`] does.
    #[inline(always)]
    pub(crate) fn uint(&mut self, v: u64) {
        if v < 10 {
            self.byte(b'0' + v as u8);
        } else if let Some((text, len)) = decimal(v) {
            self.put(text.to_le_bytes(), len);
        } else {
            let mut digits = itoa::Buffer::new();
            let digits = digits.format(v).as_bytes();
            let mut text = [0u8; 20];
            if let Some(to) = text.get_mut(..digits.len()) {
                to.copy_from_slice(digits);
            }
            self.put(text, digits.len());
        }
    }

    /// Write a timestamp, as [`timestamp`] does.
    #[inline]
    pub(crate) fn timestamp(&mut self, ts: crate::can::Timestamp) {
        match timestamp_text(ts) {
            Some((text, len)) => self.put(text, len),
            None => {
                let mut buf = [0; crate::can::SECONDS_LEN];
                let seconds = ts.format_seconds(&mut buf);
                let mut text = [0u8; crate::can::SECONDS_LEN];
                if let Some(to) = text.get_mut(..seconds.len()) {
                    to.copy_from_slice(seconds);
                }
                let len = seconds.len();
                self.put(text, len);
            }
        }
    }

    /// Write at most 16 bytes as a JSON string of lowercase hex digits;
    /// `false`, and nothing written, for more.
    #[inline(always)]
    pub(crate) fn short_hex_string(&mut self, bytes: &[u8]) -> bool {
        let Some((first, second)) = load16(bytes) else {
            return false;
        };
        let mut block = [0u8; 16];
        block[..8].copy_from_slice(&first.to_le_bytes());
        block[8..].copy_from_slice(&second.to_le_bytes());
        let digits = hex32(&block);
        let mut text = [0u8; 34];
        text[0] = b'"';
        text[1..33].copy_from_slice(&digits);
        // The closing quote after the digits kept.
        let len = 2 * bytes.len();
        text[1 + len] = b'"';
        self.put(text, len + 2);
        true
    }

    /// Write a text from the input as a JSON string when it is at most 16
    /// bytes and needs no escaping; `false`, and nothing written, else.
    #[inline(always)]
    pub(crate) fn short_string(&mut self, value: &str) -> bool {
        let Some(text) = short_text(value.as_bytes()) else {
            return false;
        };
        let mut piece = [0u8; 18];
        piece[0] = b'"';
        piece[1..17].copy_from_slice(&text.to_le_bytes());
        piece[1 + value.len()] = b'"';
        self.put(piece, value.len() + 2);
        true
    }

    /// Write a text from the input as a JSON string with RFC 8259
    /// escaping, as [`string`] does: the bytes between characters to
    /// escape 8 at a time.
    #[inline]
    pub(crate) fn string(&mut self, value: &str) {
        if self.short_string(value) {
            return;
        }
        self.byte(b'"');
        let bytes = value.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            if let Some(word) = bytes.get(i..).and_then(|rest| rest.first_chunk::<8>()) {
                let mask = escape_mask(u64::from_le_bytes(*word));
                let clean = (mask.trailing_zeros() / 8) as usize;
                self.put(*word, clean.min(8));
                i += clean.min(8);
                if mask == 0 {
                    continue;
                }
            }
            let Some(&b) = bytes.get(i) else {
                break;
            };
            i += 1;
            match b {
                b'"' => self.text(b"\\\""),
                b'\\' => self.text(b"\\\\"),
                b'\n' => self.text(b"\\n"),
                b'\r' => self.text(b"\\r"),
                b'\t' => self.text(b"\\t"),
                0x00..=0x1F => self.text(&[
                    b'\\',
                    b'u',
                    b'0',
                    b'0',
                    HEX_DIGITS[usize::from(b >> 4)],
                    HEX_DIGITS[usize::from(b & 0xF)],
                ]),
                _ => self.byte(b),
            }
        }
        self.byte(b'"');
    }

    /// How many bytes are written.
    #[inline(always)]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Empty the block, full or not.
    #[inline(always)]
    pub(crate) fn clear(&mut self) {
        self.len = 0;
        self.full = false;
    }

    /// Keep the first `len` bytes written.
    #[inline(always)]
    pub(crate) fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }

    /// The bytes written from `start` as a [`Padded`] text of `M` bytes
    /// (a copy of `M` bytes); `None` when there are more, or the block
    /// does not hold `M` bytes from `start`.
    #[inline(always)]
    pub(crate) fn padded_from<const M: usize>(&self, start: usize) -> Option<Padded<M>> {
        let len = self.len.checked_sub(start)?;
        let bytes = *self.bytes.get(start..)?.first_chunk::<M>()?;
        Some(Padded {
            bytes,
            len: u8::try_from(len).ok().filter(|&l| usize::from(l) <= M)?,
        })
    }

    /// Whether a piece did not fit: the block's bytes are not the text.
    #[inline(always)]
    pub(crate) fn is_full(&self) -> bool {
        self.full
    }

    /// The bytes written.
    #[inline(always)]
    pub(crate) fn as_bytes(&self) -> &[u8] {
        self.bytes.get(..self.len).unwrap_or_default()
    }

    /// Append the bytes written to `out`.
    #[inline(always)]
    pub(crate) fn flush(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(self.as_bytes());
    }
}

/// Write a float, or `null` when it is not finite.
pub(crate) fn float(out: &mut Vec<u8>, value: f64) {
    if value.is_finite() {
        // Writing into a `Vec` does not fail.
        let _ = serde_json::to_writer(&mut *out, &value);
    } else {
        out.extend_from_slice(b"null");
    }
}

/// A name as a JSON object key with the comma before it, escaped once
/// (`,"Statusword":`): in an array of 32 bytes when it fits, as most
/// signal names do, so that it is written without a call to `memcpy`.
#[derive(Debug)]
pub(crate) enum Key {
    /// A key of at most 32 bytes.
    Short(Padded<32>),
    /// A longer key.
    Long(Box<[u8]>),
}

impl Key {
    /// The key of `name`, escaped.
    pub(crate) fn new(name: &str) -> Self {
        let mut key = Vec::with_capacity(name.len() + 4);
        key.push(b',');
        string(&mut key, name);
        key.push(b':');
        match Padded::new(&key) {
            Some(short) => Key::Short(short),
            None => Key::Long(key.into_boxed_slice()),
        }
    }

    /// Write the key.
    #[inline(always)]
    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        match self {
            Key::Short(key) => key.write(out),
            Key::Long(key) => out.extend_from_slice(key),
        }
    }
}

/// Write a JSON string with RFC 8259 escaping.
#[inline(always)]
pub(crate) fn string(out: &mut Vec<u8>, value: &str) {
    match short_text(value.as_bytes()) {
        Some(text) => {
            out.push(b'"');
            let end = out.len() + value.len();
            out.extend_from_slice(&text.to_le_bytes());
            out.truncate(end);
            out.push(b'"');
        }
        None => long_string(out, value),
    }
}

/// A text of at most 16 bytes without a character to escape (an interface
/// name, most object names) in one 128-bit word, zeros past the text:
/// loaded in two words and checked a word at a time.
#[inline(always)]
fn short_text(bytes: &[u8]) -> Option<u128> {
    let (first, second) = load16(bytes)?;
    let len = bytes.len();
    // The bytes past the text read as 'a', which needs no escaping.
    let fill = |used: usize| {
        (u64::from(b'a') * ONES)
            .checked_shl(8 * used as u32)
            .unwrap_or(0)
    };
    if word_needs_escaping(first | fill(len))
        || (len > 8 && word_needs_escaping(second | fill(len - 8)))
    {
        return None;
    }
    Some(u128::from(first) | u128::from(second) << 64)
}

/// Write a JSON string with RFC 8259 escaping, 8 bytes at a time.
fn long_string(out: &mut Vec<u8>, value: &str) {
    out.push(b'"');
    // A text without a character to escape, in one write.
    if !needs_escaping(value) {
        out.extend_from_slice(value.as_bytes());
    } else {
        escaped(out, value);
    }
    out.push(b'"');
}

/// The bytes of a text of at most 16 bytes in two little-endian words,
/// zeros past the text; `None` for a longer text. Read with two loads of
/// 8, 4 or 1 bytes that overlap in the middle, as a text of any length
/// from 1 to 16 bytes can be, instead of a copy whose length is known only
/// at run time (a call to `memcpy`).
#[inline(always)]
fn load16(bytes: &[u8]) -> Option<(u64, u64)> {
    let len = bytes.len();
    match len {
        8..=16 => {
            let first = u64::from_le_bytes(*bytes.first_chunk::<8>()?);
            let last = u64::from_le_bytes(*bytes.last_chunk::<8>()?);
            // The last 8 bytes end with the text: shift out those that
            // the first word holds already (all of them for 8 bytes).
            let second = last.checked_shr(8 * (16 - len) as u32).unwrap_or(0);
            Some((first, second))
        }
        4..=7 => {
            let first = u32::from_le_bytes(*bytes.first_chunk::<4>()?);
            let last = u32::from_le_bytes(*bytes.last_chunk::<4>()?);
            Some((u64::from(first) | u64::from(last) << (8 * (len - 4)), 0))
        }
        1..=3 => {
            let byte = |i: usize| u64::from(bytes.get(i).copied().unwrap_or(0)) << (8 * i);
            Some((byte(0) | byte(len / 2) | byte(len - 1), 0))
        }
        0 => Some((0, 0)),
        _ => None,
    }
}

/// Write the inside of a JSON string with RFC 8259 escaping: the bytes
/// between characters to escape skipped 8 at a time, to the first that
/// needs it (a Windows interface name, `\Device\NPF_{…}`, has two
/// backslashes in 50 bytes, and every record of its capture names it).
fn escaped(out: &mut Vec<u8>, value: &str) {
    let bytes = value.as_bytes();
    let mut start = 0;
    let mut i = 0;
    loop {
        if let Some(word) = bytes.get(i..).and_then(|rest| rest.first_chunk::<8>()) {
            let mask = escape_mask(u64::from_le_bytes(*word));
            if mask == 0 {
                i += 8;
                continue;
            }
            i += (mask.trailing_zeros() / 8) as usize;
        }
        let Some(&b) = bytes.get(i) else {
            break;
        };
        i += 1;
        let escape: &[u8] = match b {
            b'"' => b"\\\"",
            b'\\' => b"\\\\",
            b'\n' => b"\\n",
            b'\r' => b"\\r",
            b'\t' => b"\\t",
            0x00..=0x1F => {
                out.extend_from_slice(&bytes[start..i - 1]);
                out.extend_from_slice(b"\\u00");
                out.push(HEX_DIGITS[usize::from(b >> 4)]);
                out.push(HEX_DIGITS[usize::from(b & 0xF)]);
                start = i;
                continue;
            }
            _ => continue,
        };
        out.extend_from_slice(&bytes[start..i - 1]);
        out.extend_from_slice(escape);
        start = i;
    }
    out.extend_from_slice(&bytes[start..]);
}

/// The two decimal digits of every number below 100, in order.
const PAIRS: [u8; 200] = {
    let mut pairs = [0u8; 200];
    let mut n = 0;
    while n < 100 {
        pairs[2 * n] = b'0' + (n / 10) as u8;
        pairs[2 * n + 1] = b'0' + (n % 10) as u8;
        n += 1;
    }
    pairs
};

const HEX_DIGITS: &[u8; 16] = b"0123456789abcdef";

/// The 8 decimal digits of `v` (below 10^8, with leading zeros) as ASCII,
/// the first digit in the low byte: two divisions and wide-word arithmetic
/// on the four pairs of digits at once, instead of a division a digit.
#[inline(always)]
pub(crate) const fn digits8(v: u32) -> u64 {
    let v = v as u64;
    // Lanes of 32 bits: the first four digits, the last four.
    let x = (v / 10_000) | (v % 10_000) << 32;
    // Lanes of 16 bits: each four-digit number split into hundreds and the
    // rest (10486 / 2^20 is 1/100 within the range).
    let q = ((x * 10_486) >> 20) & 0x0000_007F_0000_007F;
    let x = q | (x - q * 100) << 16;
    // Lanes of 8 bits: tens and units (103 / 2^10 is 1/10 within the range).
    let q = ((x * 103) >> 10) & 0x000F_000F_000F_000F;
    let x = q | (x - q * 10) << 8;
    x | 0x3030_3030_3030_3030
}

/// Write an unsigned integer in decimal: below 10^16, the digits of
/// [`decimal`] in one write of 16 bytes cut to their length; one digit as
/// one byte.
#[inline(always)]
pub(crate) fn uint(out: &mut Vec<u8>, v: u64) {
    if v < 10 {
        // One digit (a toggle, a sub-index, a count): one byte.
        out.push(b'0' + v as u8);
    } else if let Some((text, len)) = decimal(v) {
        let end = out.len() + len;
        out.extend_from_slice(&text.to_le_bytes());
        out.truncate(end);
    } else {
        out.extend_from_slice(itoa::Buffer::new().format(v).as_bytes());
    }
}

/// The decimal digits of `v` below 10^16 in one 128-bit word, the first
/// digit in the low byte, and how many there are; `None` from 10^16.
/// Below 10^8 the digits of [`digits8`] with their leading zeros shifted
/// out; below 10^10 one or two digits and eight; else the high eight,
/// their leading zeros cut, then the low eight.
#[inline(always)]
pub(crate) fn decimal(v: u64) -> Option<(u128, usize)> {
    if v < 100 {
        // A count, an index, a working counter: the pair from a table.
        let pair = PAIRS
            .get(2 * v as usize..2 * v as usize + 2)
            .unwrap_or_default();
        let (Some(&tens), Some(&units)) = (pair.first(), pair.get(1)) else {
            return None;
        };
        let skip = usize::from(v < 10);
        let text = (u128::from(tens) | u128::from(units) << 8) >> (8 * skip);
        Some((text, 2 - skip))
    } else if v < 10_000 {
        // A register or station address: two pairs from the table.
        let (high, low) = (v / 100, v % 100);
        let pair = |n: u64| {
            PAIRS
                .get(2 * n as usize..2 * n as usize + 2)
                .map_or(0, |p| u128::from(p[0]) | u128::from(p[1]) << 8)
        };
        let skip = usize::from(high < 10);
        let text = (pair(high) | pair(low) << 16) >> (8 * skip);
        Some((text, 4 - skip))
    } else if v < 100_000_000 {
        let digits = digits8(v as u32);
        // Leading zeros: the low bytes equal to '0' (all but one for 0).
        let zeros = (((digits ^ 0x3030_3030_3030_3030).trailing_zeros() / 8) as usize).min(7);
        Some((u128::from(digits >> (8 * zeros)), 8 - zeros))
    } else if v < 10_000_000_000 {
        // 9 or 10 digits (a 32-bit value).
        let high = (v / 100_000_000) as u32;
        let low = digits8((v % 100_000_000) as u32);
        let tens = high / 10;
        let pair = u128::from(b'0' + tens as u8) | u128::from(b'0' + (high % 10) as u8) << 8;
        let skip = usize::from(tens == 0);
        Some((
            pair >> (8 * skip) | u128::from(low) << (8 * (2 - skip)),
            10 - skip,
        ))
    } else if v < 10_000_000_000_000_000 {
        let high = digits8((v / 100_000_000) as u32);
        let low = digits8((v % 100_000_000) as u32);
        let zeros = ((high ^ 0x3030_3030_3030_3030).trailing_zeros() / 8) as usize;
        let text = u128::from(high >> (8 * zeros)) | u128::from(low) << (8 * (8 - zeros));
        Some((text, 16 - zeros))
    } else {
        None
    }
}

/// Write a signed integer in decimal.
#[inline]
pub(crate) fn int(out: &mut Vec<u8>, v: i64) {
    if v < 0 {
        out.push(b'-');
    }
    uint(out, v.unsigned_abs());
}

/// Write a timestamp as seconds with six decimals, `1700000000.000500`, or
/// nine when it is not a whole number of microseconds (`ts` in
/// docs/output.md#common-keys; docs/formats.md#timestamps: exact to the
/// format's resolution, no float rounding). A time of today's ten digits
/// of seconds is written in one piece ([`timestamp_text`]).
#[inline]
pub(crate) fn timestamp(out: &mut Vec<u8>, ts: crate::can::Timestamp) {
    match timestamp_text(ts) {
        Some((text, len)) => {
            let end = out.len() + len;
            out.extend_from_slice(&text);
            out.truncate(end);
        }
        None => {
            let mut buf = [0; crate::can::SECONDS_LEN];
            out.extend_from_slice(ts.format_seconds(&mut buf));
        }
    }
}

/// The text of a time of ten digits of seconds (from 2001 to 2286) in 24
/// bytes and its length: six decimals, or nine when it is not a whole
/// number of microseconds; `None` for another time.
#[inline]
pub(crate) fn timestamp_text(ts: crate::can::Timestamp) -> Option<([u8; 24], usize)> {
    let secs = ts.secs();
    let nanos = ts.subsec_nanos();
    if !(1_000_000_000..10_000_000_000).contains(&secs) {
        return None;
    }
    let top = (secs / 100_000_000) as u32;
    let mut text = [0u8; 24];
    text[0] = b'0' + (top / 10) as u8;
    text[1] = b'0' + (top % 10) as u8;
    let rest = digits8((secs % 100_000_000) as u32).to_le_bytes();
    if let Some(a) = text.get_mut(2..10) {
        a.copy_from_slice(&rest);
    }
    text[10] = b'.';
    if nanos % 1000 == 0 {
        let fraction = (digits8(nanos / 1000) >> 16).to_le_bytes();
        if let Some(b) = text.get_mut(11..19) {
            b.copy_from_slice(&fraction);
        }
        return Some((text, 17));
    }
    // Nine decimals (a capture in nanoseconds): the first, then eight.
    text[11] = b'0' + (nanos / 100_000_000) as u8;
    let fraction = digits8(nanos % 100_000_000).to_le_bytes();
    if let Some(b) = text.get_mut(12..20) {
        b.copy_from_slice(&fraction);
    }
    Some((text, 20))
}

const ONES: u64 = 0x0101_0101_0101_0101;

/// Whether one of the 8 bytes of `w` needs escaping in a JSON string
/// (RFC 8259): a quote, a backslash or a byte below 0x20.
#[inline(always)]
const fn word_needs_escaping(w: u64) -> bool {
    const HIGH: u64 = 0x8080_8080_8080_8080;
    /// Whether a byte of `w` is zero (exact: a borrow only runs past a
    /// zero byte, and a byte above 0x80 is masked off by `!w`).
    const fn has_zero(w: u64) -> bool {
        w.wrapping_sub(ONES) & !w & HIGH != 0
    }
    // A byte below 0x20: its bits 5-7 are 0 (bytes of 0x80 and more are
    // not below 0x20, and `& 0xE0` keeps their high bit).
    has_zero(w & (0xE0 * ONES))
        || has_zero(w ^ (b'"' as u64 * ONES))
        || has_zero(w ^ (b'\\' as u64 * ONES))
}

/// The high bit of the first byte of `w` (in memory order) that needs
/// escaping in a JSON string, and maybe of later ones (a borrow can mark
/// the byte after one); 0 when none does.
#[inline(always)]
const fn escape_mask(w: u64) -> u64 {
    const HIGH: u64 = 0x8080_8080_8080_8080;
    /// The high bit of the first zero byte of `w` (exact: a borrow only
    /// runs past a zero byte, and a byte above 0x80 is masked off by
    /// `!w`), and maybe of later bytes.
    const fn zeros(w: u64) -> u64 {
        w.wrapping_sub(ONES) & !w & HIGH
    }
    // A byte below 0x20: its bits 5-7 are 0 (bytes of 0x80 and more are
    // not below 0x20, and `& 0xE0` keeps their high bit).
    zeros(w & (0xE0 * ONES)) | zeros(w ^ (b'"' as u64 * ONES)) | zeros(w ^ (b'\\' as u64 * ONES))
}

/// Whether a text needs escaping in a JSON string (RFC 8259): 8 bytes at a
/// time (object and interface names are 4 to 40 bytes), the rest one by
/// one.
#[inline]
pub(crate) fn needs_escaping(text: &str) -> bool {
    let bytes = text.as_bytes();
    let mut chunks = bytes.chunks_exact(8);
    for chunk in &mut chunks {
        let Some(eight) = chunk.first_chunk::<8>() else {
            break;
        };
        if word_needs_escaping(u64::from_le_bytes(*eight)) {
            return true;
        }
    }
    chunks
        .remainder()
        .iter()
        .any(|&b| b == b'"' || b == b'\\' || b < 0x20)
}

/// Write a value's `Display` as a JSON string with RFC 8259 escaping,
/// piece by piece as `Display` hands them over.
pub(crate) fn display_string(out: &mut Vec<u8>, value: &impl std::fmt::Display) {
    struct Escaper<'w> {
        out: &'w mut Vec<u8>,
    }
    impl std::fmt::Write for Escaper<'_> {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            escaped(self.out, s);
            Ok(())
        }
    }
    out.push(b'"');
    let mut escaper = Escaper { out };
    // Writing into a `Vec` does not fail; a failing `Display` leaves what
    // it wrote.
    let _ = std::fmt::write(&mut escaper, format_args!("{value}"));
    escaper.out.push(b'"');
}

/// Write a PDO signal's value (docs/output.md#pdo): integers and booleans as
/// JSON numbers and booleans, reals as numbers (null when not finite), octets
/// as a hex string.
pub(crate) fn pdo_value(out: &mut Vec<u8>, value: &crate::canopen::Value) {
    use crate::canopen::Value;
    match value {
        Value::Bool(b) => out.extend_from_slice(if *b { b"true" } else { b"false" }),
        Value::Signed(v) => int(out, *v),
        Value::Unsigned(v) => uint(out, *v),
        Value::Real32(v) => float(out, f64::from(*v)),
        Value::Real64(v) => float(out, *v),
        Value::Octets(o) => hex_string(out, o.as_bytes()),
    }
}

/// The 32 lowercase hex digits of 16 bytes, in order: each byte spread
/// over a lane of 16 bits (its high nibble in the low byte, which comes
/// first), then each lane turned into its two digits by the same few
/// operations, which the compiler does on eight lanes at once (SSE2 on
/// x86-64): fewer instructions than a table lookup a byte (BENCHMARKS.md,
/// "`--json` on the FD mix, instructions cut").
#[inline(always)]
fn hex32(bytes: &[u8; 16]) -> [u8; 32] {
    let mut digits = [0u8; 32];
    for (pair, &b) in digits.chunks_exact_mut(2).zip(bytes) {
        let lane = u16::from(b) * 0x0101;
        // High nibble in the low byte, low nibble in the high byte.
        let n = (lane >> 4) & 0x000F | (lane & 0x0F00);
        // 1 in each byte of 10 and more: 'a' is 39 past '0' + 10.
        let letters = ((n + 0x7676) >> 7) & 0x0101;
        pair.copy_from_slice(&(n + 0x3030 + letters * 39).to_le_bytes());
    }
    digits
}

/// Write bytes as lowercase hex digits, no separators, as a JSON string.
#[inline]
pub(crate) fn hex_string(out: &mut Vec<u8>, bytes: &[u8]) {
    out.push(b'"');
    hex_digits(out, bytes);
    out.push(b'"');
}

/// Write bytes as lowercase hex digits without separators: 16 bytes at a
/// time, in one write of 32 digits each, the last cut to the length.
#[inline]
pub(crate) fn hex_digits(out: &mut Vec<u8>, bytes: &[u8]) {
    let mut chunks = bytes.chunks_exact(16);
    for chunk in &mut chunks {
        if let Some(block) = chunk.first_chunk::<16>() {
            out.extend_from_slice(&hex32(block));
        }
    }
    let rest = chunks.remainder();
    if !rest.is_empty() {
        let mut block = [0u8; 16];
        if let Some(head) = block.get_mut(..rest.len()) {
            head.copy_from_slice(rest);
        }
        let end = out.len() + 2 * rest.len();
        out.extend_from_slice(&hex32(&block));
        out.truncate(end);
    }
}

/// Write an array of at most 16 bytes (an EMCY's manufacturer field) as
/// lowercase hex digits: its length is known at compile time, so it is
/// copied into the block without a call to `memcpy`.
#[inline(always)]
pub(crate) fn hex_array<const N: usize>(out: &mut Vec<u8>, bytes: &[u8; N]) {
    const { assert!(N <= 16) };
    let mut block = [0u8; 16];
    for (d, s) in block.iter_mut().zip(bytes) {
        *d = *s;
    }
    let end = out.len() + 2 * N;
    out.extend_from_slice(&hex32(&block));
    out.truncate(end);
}

/// Write the first `len` bytes of a frame's 64-byte data array as
/// lowercase hex digits: whole blocks of 16 bytes read from the array
/// (past `len` it holds zeros, which the cut drops), so no block is
/// copied first.
#[inline]
pub(crate) fn hex_frame_data(out: &mut Vec<u8>, bytes: &[u8; 64], len: usize) {
    let len = len.min(64);
    let end = out.len() + 2 * len;
    for chunk in bytes.chunks_exact(16).take(len.div_ceil(16)) {
        if let Some(block) = chunk.first_chunk::<16>() {
            out.extend_from_slice(&hex32(block));
        }
    }
    out.truncate(end);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every constant text the program writes with `name`/`names` needs no
    /// escaping: kind, class, state and flag names, every EMCY description,
    /// the Baumer source names and the servo names.
    #[test]
    fn constant_texts_need_no_escaping() {
        use crate::can::{ControllerStatus, ErrorClasses};
        use crate::canopen::{ErrorCode, ErrorRegister, MessageKind, NmtStateByte};
        use crate::profiles::baumer::DIAGNOSTIC_SOURCES;
        use crate::servo::{
            EncoderKind, RegulatorMode, ServoControlWord, ServoFault, ServoStatusWord,
        };

        let mut texts: Vec<&'static str> = Vec::new();
        texts.extend(MessageKind::ALL.iter().map(|k| k.name()));
        for code in 0..=u16::MAX {
            let code = ErrorCode::new(code);
            texts.push(code.description());
            texts.push(code.class().name());
        }
        texts.extend(ErrorRegister::NAMES.iter().map(|(_, n)| *n));
        texts.extend(ErrorClasses::NAMES.iter().map(|(_, n)| *n));
        texts.extend(ControllerStatus::NAMES.iter().map(|(_, n)| *n));
        texts.extend((0..=u8::MAX).map(|b| NmtStateByte::new(b).state_name()));
        texts.extend(DIAGNOSTIC_SOURCES.iter().map(|s| s.name()));
        texts.extend(ServoControlWord::NAMES.iter().map(|(_, n)| *n));
        texts.extend(ServoStatusWord::NAMES.iter().map(|(_, n)| *n));
        texts.extend(ServoFault::TABLE.iter().map(|row| row.name));
        texts.extend(RegulatorMode::ALL.iter().map(|m| m.name()));
        texts.extend([
            EncoderKind::Absolute.name(),
            EncoderKind::Incremental.name(),
        ]);
        for code in -1..=8 {
            texts.push(crate::servo::MessageCode::from_code(code).name());
        }
        for text in texts {
            assert!(!needs_escaping(text), "{text:?}");
        }
    }

    #[test]
    fn timestamps_keep_six_decimals() {
        use crate::can::Timestamp;
        let render = |ts| {
            let mut out = Vec::new();
            timestamp(&mut out, ts);
            String::from_utf8(out).unwrap()
        };
        assert_eq!(
            render(Timestamp::new(1_700_000_000, 500).unwrap()),
            "1700000000.000500"
        );
        assert_eq!(render(Timestamp::new(0, 0).unwrap()), "0.000000");
        assert_eq!(
            render(Timestamp::new(u64::MAX, 999_999).unwrap()),
            "18446744073709551615.999999"
        );
    }

    fn render(f: impl FnOnce(&mut Vec<u8>)) -> String {
        let mut out = Vec::new();
        f(&mut out);
        String::from_utf8(out).unwrap()
    }

    proptest::proptest! {
        /// The wide-word writers against the plain ones.
        #[test]
        fn integers_hex_and_times_as_the_plain_writers(
            v in proptest::prelude::any::<u64>(),
            small in 0u64..200_000_000,
            bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..70),
            secs in proptest::prelude::any::<u64>(),
            epoch in 1_000_000_000u64..10_000_000_000,
            nanos in 0u32..1_000_000_000,
        ) {
            for n in [v, small, small % 1000, v % 10, v % 10_000_000_000, v % 100_000_000_000_000_000, v >> 11, 999_999_999 + small, 9_999_999_999 - small] {
                proptest::prop_assert_eq!(render(|o| uint(o, n)), n.to_string());
                let i = n as i64;
                proptest::prop_assert_eq!(render(|o| int(o, i)), i.to_string());
            }
            let plain: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
            proptest::prop_assert_eq!(&render(|o| hex_digits(o, &bytes)), &plain);
            let mut padded = [0u8; 64];
            let len = bytes.len().min(64);
            padded[..len].copy_from_slice(&bytes[..len]);
            let rendered = render(|o| hex_frame_data(o, &padded, len));
            proptest::prop_assert_eq!(rendered.as_str(), &plain[..2 * len]);
            let mut five = [0u8; 5];
            for (d, s) in five.iter_mut().zip(&bytes) {
                *d = *s;
            }
            let plain5: String = five.iter().map(|b| format!("{b:02x}")).collect();
            proptest::prop_assert_eq!(render(|o| hex_array(o, &five)), plain5);
            for (secs, nanos) in [(secs, nanos), (epoch, nanos), (epoch, nanos / 1000 * 1000)] {
                let ts = crate::can::Timestamp::from_nanos(secs, nanos).unwrap();
                proptest::prop_assert_eq!(render(|o| timestamp(o, ts)), ts.seconds().to_string());
            }
        }
    }

    proptest::proptest! {
        /// The 8-bytes-at-a-time check against the plain one, on any text
        /// and on texts made of the bytes around the ones that need it.
        #[test]
        fn needs_escaping_as_the_plain_check(
            text in proptest::prelude::any::<String>(),
            near in proptest::collection::vec(
                proptest::sample::select(vec![
                    0x00u8, 0x01, 0x1F, 0x20, 0x21, b'"', 0x23, 0x5B, b'\\', 0x5D, 0x7F, b'a',
                ]),
                0..40,
            ),
        ) {
            let plain = |t: &str| t.bytes().any(|b| b == b'"' || b == b'\\' || b < 0x20);
            proptest::prop_assert_eq!(needs_escaping(&text), plain(&text));
            let near = String::from_utf8(near).unwrap();
            proptest::prop_assert_eq!(needs_escaping(&near), plain(&near));
            // The writer, on short texts (two words) and long, against the
            // plain one, character by character; serde_json reads it back.
            let plain_string = |t: &str| {
                let mut s = String::from("\"");
                for c in t.chars() {
                    match c {
                        '"' => s.push_str("\\\""),
                        '\\' => s.push_str("\\\\"),
                        '\n' => s.push_str("\\n"),
                        '\r' => s.push_str("\\r"),
                        '\t' => s.push_str("\\t"),
                        c if u32::from(c) < 0x20 => s.push_str(&format!("\\u{:04x}", u32::from(c))),
                        c => s.push(c),
                    }
                }
                s.push('"');
                s
            };
            for t in [&text, &near] {
                let written = render(|o| string(o, t));
                proptest::prop_assert_eq!(&written, &plain_string(t));
                proptest::prop_assert_eq!(&serde_json::from_str::<String>(&written).unwrap(), t);
            }
        }
    }

    proptest::proptest! {
        /// A key, padded (up to 32 bytes) or not, is the name written as
        /// a string between its comma and its colon.
        #[test]
        fn keys_are_the_escaped_name(
            name in proptest::prelude::any::<String>(),
            short in "[a-zA-Z0-9 _.\"\\\\]{0,40}",
        ) {
            for name in [&name, &short] {
                let plain = format!(",{}:", render(|o| string(o, name)));
                let key = Key::new(name);
                proptest::prop_assert_eq!(matches!(key, Key::Short(_)), plain.len() <= 32);
                proptest::prop_assert_eq!(render(|o| key.write(o)), plain);
            }
        }
    }

    #[test]
    fn long_strings_are_escaped_between_words() {
        let name = "\\Device\\NPF_{DCEDC919-0A20-47A2-9788-FC57D0169EDB}\"\n\u{1f}é12345678\\";
        let s = render(|o| string(o, name));
        assert_eq!(s, serde_json::to_string(name).unwrap());
    }

    #[test]
    fn strings_are_escaped() {
        let s = render(|o| string(o, "a\"b\\c\nd\u{1}é"));
        assert_eq!(s, "\"a\\\"b\\\\c\\nd\\u0001é\"");
        let v: serde_json::Value = serde_json::from_str(&s).unwrap();
        assert_eq!(v, "a\"b\\c\nd\u{1}é");
    }

    #[test]
    fn objects_and_floats() {
        let s = render(|o| {
            let mut obj = Object::begin(o);
            obj.uint("a", 1);
            obj.float("nan", f64::NAN);
            obj.float("x", 1.5);
            obj.names("l", ["p", "q"]);
            hex_string(obj.key("h"), &[0xAB, 0x01]);
            obj.end();
        });
        assert_eq!(s, r#"{"a":1,"nan":null,"x":1.5,"l":["p","q"],"h":"ab01"}"#);
    }
}
