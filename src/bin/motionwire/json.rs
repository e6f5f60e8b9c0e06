//! A small streaming JSON writer for the decoder's records.
//!
//! Records are written straight into the buffered output, key by key, so that
//! decoding a line allocates nothing (SPEC §6.1). String escaping follows
//! RFC 8259; numbers are written with `itoa`-style integer formatting from
//! `core::fmt` and floats through `serde_json`, which prints the shortest
//! representation that reads back to the same value.

use std::io::{self, Write};

/// Writes one JSON object, tracking whether a comma is needed.
pub struct Object<'w, W: Write> {
    out: &'w mut W,
    first: bool,
}

impl<'w, W: Write> Object<'w, W> {
    /// Open an object (`{`).
    pub fn begin(out: &'w mut W) -> io::Result<Self> {
        out.write_all(b"{")?;
        Ok(Object { out, first: true })
    }

    /// Write the key and return the writer for its value.
    pub fn key(&mut self, key: &str) -> io::Result<&mut W> {
        if self.first {
            self.first = false;
        } else {
            self.out.write_all(b",")?;
        }
        string(self.out, key)?;
        self.out.write_all(b":")?;
        Ok(self.out)
    }

    /// Write a key with an unsigned integer value.
    pub fn uint(&mut self, key: &str, value: u64) -> io::Result<()> {
        let out = self.key(key)?;
        write!(out, "{value}")
    }

    /// Write a key with a signed integer value.
    pub fn int(&mut self, key: &str, value: i64) -> io::Result<()> {
        let out = self.key(key)?;
        write!(out, "{value}")
    }

    /// Write a key with a boolean value.
    pub fn bool(&mut self, key: &str, value: bool) -> io::Result<()> {
        let out = self.key(key)?;
        out.write_all(if value { b"true" } else { b"false" })
    }

    /// Write a key with a string value.
    pub fn str(&mut self, key: &str, value: &str) -> io::Result<()> {
        let out = self.key(key)?;
        string(out, value)
    }

    /// Write a key with a string value given by its `Display`, escaped,
    /// without allocating.
    pub fn display(&mut self, key: &str, value: &impl std::fmt::Display) -> io::Result<()> {
        let out = self.key(key)?;
        display_string(out, value)
    }

    /// Write a key with a `null` value.
    pub fn null(&mut self, key: &str) -> io::Result<()> {
        self.key(key)?.write_all(b"null")
    }

    /// Write a key with a float value; NaN and infinities become `null`
    /// (SPEC §6.2).
    pub fn float(&mut self, key: &str, value: f64) -> io::Result<()> {
        let out = self.key(key)?;
        float(out, value)
    }

    /// Write a key with an array of strings.
    pub fn strs<'s>(
        &mut self,
        key: &str,
        values: impl IntoIterator<Item = &'s str>,
    ) -> io::Result<()> {
        let out = self.key(key)?;
        out.write_all(b"[")?;
        for (i, value) in values.into_iter().enumerate() {
            if i > 0 {
                out.write_all(b",")?;
            }
            string(out, value)?;
        }
        out.write_all(b"]")
    }

    /// Write a key with an array of unsigned integers.
    pub fn uints(&mut self, key: &str, values: impl IntoIterator<Item = u64>) -> io::Result<()> {
        let out = self.key(key)?;
        out.write_all(b"[")?;
        for (i, value) in values.into_iter().enumerate() {
            if i > 0 {
                out.write_all(b",")?;
            }
            write!(out, "{value}")?;
        }
        out.write_all(b"]")
    }

    /// Close the object (`}`).
    pub fn end(self) -> io::Result<()> {
        self.out.write_all(b"}")
    }
}

/// Write a float, or `null` when it is not finite.
pub fn float<W: Write>(out: &mut W, value: f64) -> io::Result<()> {
    if value.is_finite() {
        serde_json::to_writer(&mut *out, &value).map_err(io::Error::from)
    } else {
        out.write_all(b"null")
    }
}

/// Write a JSON string with RFC 8259 escaping.
pub fn string<W: Write>(out: &mut W, value: &str) -> io::Result<()> {
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

/// Write a timestamp as seconds with six decimals, `1700000000.000500`
/// (SPEC §6.1 `ts`: exact to the microsecond, no float rounding).
pub fn timestamp<W: Write>(out: &mut W, ts: motionwire::can::Timestamp) -> io::Result<()> {
    write!(out, "{}.{:06}", ts.secs(), ts.micros())
}

/// Write a value's `Display` as a JSON string with RFC 8259 escaping,
/// piece by piece as `Display` hands them over.
pub fn display_string<W: Write>(out: &mut W, value: &impl std::fmt::Display) -> io::Result<()> {
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

/// Write bytes as lowercase hex digits, no separators, as a JSON string.
pub fn hex_string<W: Write>(out: &mut W, bytes: &[u8]) -> io::Result<()> {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    let mut buf = [0u8; 2 + 2 * 64];
    buf[0] = b'"';
    let mut n = 1;
    for &b in bytes.iter().take(64) {
        buf[n] = DIGITS[usize::from(b >> 4)];
        buf[n + 1] = DIGITS[usize::from(b & 0xF)];
        n += 2;
    }
    buf[n] = b'"';
    out.write_all(&buf[..=n])
}

#[cfg(test)]
mod tests {
    use super::*;

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
            obj.strs("l", ["p", "q"])?;
            obj.uints("n", [3, 4])?;
            hex_string(obj.key("h")?, &[0xAB, 0x01])?;
            obj.end()
        });
        assert_eq!(
            s,
            r#"{"a":1,"nan":null,"x":1.5,"l":["p","q"],"n":[3,4],"h":"ab01"}"#
        );
    }
}
