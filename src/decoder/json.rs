//! A small streaming JSON writer for the decoder's records
//! (docs/output.md#json).
//!
//! Records are written straight into the buffered output, key by key, so that
//! decoding a line allocates nothing (docs/output.md#json). Keys and the
//! library's constant texts (kind, class and flag names, descriptions) are
//! written as they are — a test checks that none of them needs escaping — and
//! only texts that come from the input (interface names, error messages) are
//! escaped as RFC 8259 says. Integers are written with `itoa`, floats
//! through `serde_json`, which prints the shortest representation that
//! reads back to the same value.

use std::io::{self, Write};

/// Writes one JSON object, tracking whether a comma is needed.
pub(crate) struct Object<'w, W: Write> {
    out: &'w mut W,
    first: bool,
}

impl<'w, W: Write> Object<'w, W> {
    /// Open an object (`{`).
    pub(crate) fn begin(out: &'w mut W) -> io::Result<Self> {
        out.write_all(b"{")?;
        Ok(Object { out, first: true })
    }

    /// Write the key and return the writer for its value. Keys are the
    /// contract's names (docs/output.md): ASCII letters, digits and `_`, which
    /// need no escaping.
    pub(crate) fn key(&mut self, key: &'static str) -> io::Result<&mut W> {
        debug_assert!(key.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_'));
        // `,"key":` in one write.
        let mut buf = [0u8; 64];
        let start = usize::from(self.first);
        self.first = false;
        buf[0] = b',';
        buf[1] = b'"';
        let end = 2 + key.len();
        match buf.get_mut(2..end) {
            Some(slot) => slot.copy_from_slice(key.as_bytes()),
            None => {
                // Longer than any key of the contract: write it in pieces.
                self.out.write_all(&buf[start..2])?;
                self.out.write_all(key.as_bytes())?;
                self.out.write_all(b"\":")?;
                return Ok(self.out);
            }
        }
        buf[end] = b'"';
        buf[end + 1] = b':';
        self.out.write_all(&buf[start..end + 2])?;
        Ok(self.out)
    }

    /// Write bytes that hold a comma, a key of the contract and the start
    /// of its value, all escaped already (`,"signals":{`), after at least
    /// one key: one write where [`key`](Self::key) makes several.
    #[inline]
    pub(crate) fn raw_after_first(&mut self, bytes: &[u8]) -> io::Result<&mut W> {
        debug_assert!(!self.first && bytes.first() == Some(&b','));
        self.out.write_all(bytes)?;
        Ok(self.out)
    }

    /// Write a key with an unsigned integer value.
    pub(crate) fn uint(&mut self, key: &'static str, value: u64) -> io::Result<()> {
        let out = self.key(key)?;
        out.write_all(itoa::Buffer::new().format(value).as_bytes())
    }

    /// Write a key with a boolean value.
    pub(crate) fn bool(&mut self, key: &'static str, value: bool) -> io::Result<()> {
        let out = self.key(key)?;
        out.write_all(if value { b"true" } else { b"false" })
    }

    /// Write a key with a string value from the input, escaped.
    pub(crate) fn str(&mut self, key: &'static str, value: &str) -> io::Result<()> {
        let out = self.key(key)?;
        string(out, value)
    }

    /// Write a key with one of the library's constant texts (a name or a
    /// description), which need no escaping (`constant_texts_need_no_escaping`).
    pub(crate) fn name(&mut self, key: &'static str, value: &'static str) -> io::Result<()> {
        debug_assert!(!needs_escaping(value), "{value:?}");
        let out = self.key(key)?;
        out.write_all(b"\"")?;
        out.write_all(value.as_bytes())?;
        out.write_all(b"\"")
    }

    /// Write a key with a string value given by its `Display`, escaped,
    /// without allocating.
    pub(crate) fn display(
        &mut self,
        key: &'static str,
        value: &impl std::fmt::Display,
    ) -> io::Result<()> {
        let out = self.key(key)?;
        display_string(out, value)
    }

    /// Write a key with a `null` value.
    pub(crate) fn null(&mut self, key: &'static str) -> io::Result<()> {
        self.key(key)?.write_all(b"null")
    }

    /// Write a key with a float value; NaN and infinities become `null`
    /// (docs/servo.md#cli-feedback, docs/output.md#pdo).
    pub(crate) fn float(&mut self, key: &'static str, value: f64) -> io::Result<()> {
        let out = self.key(key)?;
        float(out, value)
    }

    /// Write a key with an array of the library's constant names, which
    /// need no escaping.
    pub(crate) fn names(
        &mut self,
        key: &'static str,
        values: impl IntoIterator<Item = &'static str>,
    ) -> io::Result<()> {
        let out = self.key(key)?;
        out.write_all(b"[")?;
        for (i, value) in values.into_iter().enumerate() {
            debug_assert!(!needs_escaping(value), "{value:?}");
            out.write_all(if i > 0 { b",\"" } else { b"\"" })?;
            out.write_all(value.as_bytes())?;
            out.write_all(b"\"")?;
        }
        out.write_all(b"]")
    }

    /// Close the object (`}`).
    pub(crate) fn end(self) -> io::Result<()> {
        self.out.write_all(b"}")
    }
}

/// Write a float, or `null` when it is not finite.
pub(crate) fn float<W: Write>(out: &mut W, value: f64) -> io::Result<()> {
    if value.is_finite() {
        serde_json::to_writer(&mut *out, &value).map_err(io::Error::from)
    } else {
        out.write_all(b"null")
    }
}

/// A name as a JSON object key, escaped once (`"Statusword":`), with the
/// comma before it when it is not the first.
pub(crate) fn key(name: &str, comma: bool) -> Box<[u8]> {
    let mut key = Vec::with_capacity(name.len() + 4);
    if comma {
        key.push(b',');
    }
    string(&mut key, name).expect("writing to a Vec");
    key.push(b':');
    key.into_boxed_slice()
}

/// Write a JSON string with RFC 8259 escaping.
pub(crate) fn string<W: Write>(out: &mut W, value: &str) -> io::Result<()> {
    out.write_all(b"\"")?;
    escaped(out, value)?;
    out.write_all(b"\"")
}

/// Write the inside of a JSON string with RFC 8259 escaping.
fn escaped<W: Write>(out: &mut W, value: &str) -> io::Result<()> {
    let bytes = value.as_bytes();
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        let escape: &[u8] = match b {
            b'"' => b"\\\"",
            b'\\' => b"\\\\",
            b'\n' => b"\\n",
            b'\r' => b"\\r",
            b'\t' => b"\\t",
            0x00..=0x1F => {
                out.write_all(&bytes[start..i])?;
                write!(out, "\\u{b:04x}")?;
                start = i + 1;
                continue;
            }
            _ => continue,
        };
        out.write_all(&bytes[start..i])?;
        out.write_all(escape)?;
        start = i + 1;
    }
    out.write_all(&bytes[start..])
}

/// Write a timestamp as seconds with six decimals, `1700000000.000500`, or
/// nine when it is not a whole number of microseconds (`ts` in
/// docs/output.md#common-keys; docs/formats.md#timestamps: exact to the
/// format's resolution, no float rounding).
pub(crate) fn timestamp<W: Write>(out: &mut W, ts: crate::can::Timestamp) -> io::Result<()> {
    let mut buf = [0; crate::can::SECONDS_LEN];
    out.write_all(ts.format_seconds(&mut buf))
}

/// Whether a text needs escaping in a JSON string (RFC 8259).
pub(crate) fn needs_escaping(text: &str) -> bool {
    text.bytes().any(|b| b == b'"' || b == b'\\' || b < 0x20)
}

/// Write a value's `Display` as a JSON string with RFC 8259 escaping,
/// piece by piece as `Display` hands them over.
pub(crate) fn display_string<W: Write>(
    out: &mut W,
    value: &impl std::fmt::Display,
) -> io::Result<()> {
    struct Escaper<'w, W: Write> {
        out: &'w mut W,
        error: Option<io::Error>,
    }
    impl<W: Write> std::fmt::Write for Escaper<'_, W> {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            escaped(self.out, s).map_err(|e| {
                self.error = Some(e);
                std::fmt::Error
            })
        }
    }
    out.write_all(b"\"")?;
    let mut escaper = Escaper { out, error: None };
    if std::fmt::write(&mut escaper, format_args!("{value}")).is_err() {
        return Err(escaper
            .error
            .unwrap_or_else(|| io::Error::other("a Display implementation failed")));
    }
    escaper.out.write_all(b"\"")
}

/// Write a PDO signal's value (docs/output.md#pdo): integers and booleans as
/// JSON numbers and booleans, reals as numbers (null when not finite), octets
/// as a hex string.
pub(crate) fn pdo_value<W: Write>(out: &mut W, value: &crate::canopen::Value) -> io::Result<()> {
    use crate::canopen::Value;
    match value {
        Value::Bool(b) => out.write_all(if *b { b"true" } else { b"false" }),
        Value::Signed(v) => out.write_all(itoa::Buffer::new().format(*v).as_bytes()),
        Value::Unsigned(v) => out.write_all(itoa::Buffer::new().format(*v).as_bytes()),
        Value::Real32(v) => float(out, f64::from(*v)),
        Value::Real64(v) => float(out, *v),
        Value::Octets(o) => hex_string(out, o.as_bytes()),
    }
}

/// Write bytes as lowercase hex digits, no separators, as a JSON string.
pub(crate) fn hex_string<W: Write>(out: &mut W, bytes: &[u8]) -> io::Result<()> {
    if bytes.len() <= 64 {
        // A frame's data: the quotes and digits in one write.
        let mut buf = [0u8; 2 + 2 * 64];
        buf[0] = b'"';
        let n = 1 + hex_into(&mut buf[1..], bytes);
        buf[n] = b'"';
        return out.write_all(&buf[..=n]);
    }
    out.write_all(b"\"")?;
    hex_digits(out, bytes)?;
    out.write_all(b"\"")
}

/// Write bytes as lowercase hex digits without separators.
pub(crate) fn hex_digits<W: Write>(out: &mut W, bytes: &[u8]) -> io::Result<()> {
    let mut buf = [0u8; 2 * 64];
    for chunk in bytes.chunks(64) {
        let n = hex_into(&mut buf, chunk);
        out.write_all(&buf[..n])?;
    }
    Ok(())
}

/// Write the hex digits of `bytes` (at most `buf.len() / 2` of them) into
/// `buf`; return how many digits.
fn hex_into(buf: &mut [u8], bytes: &[u8]) -> usize {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    let mut n = 0;
    for (&b, pair) in bytes.iter().zip(buf.chunks_exact_mut(2)) {
        pair[0] = DIGITS[usize::from(b >> 4)];
        pair[1] = DIGITS[usize::from(b & 0xF)];
        n += 2;
    }
    n
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
            timestamp(&mut out, ts).unwrap();
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

    fn render(f: impl FnOnce(&mut Vec<u8>) -> io::Result<()>) -> String {
        let mut out = Vec::new();
        f(&mut out).unwrap();
        String::from_utf8(out).unwrap()
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
            let mut obj = Object::begin(o)?;
            obj.uint("a", 1)?;
            obj.float("nan", f64::NAN)?;
            obj.float("x", 1.5)?;
            obj.names("l", ["p", "q"])?;
            hex_string(obj.key("h")?, &[0xAB, 0x01])?;
            obj.end()
        });
        assert_eq!(s, r#"{"a":1,"nan":null,"x":1.5,"l":["p","q"],"h":"ab01"}"#);
    }
}
