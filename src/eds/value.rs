//! Values of CiA 306 files: integers in decimal, hex (`0x`) and octal
//! (leading `0`), `$NODEID` expressions, reals and strings, read with the
//! object's data type.

use std::fmt;

use crate::canopen::{DataType, NodeId};

/// A `DefaultValue` or `ParameterValue` read with its object's data type
/// (CiA 306; docs/canopen.md#eds).
#[derive(Debug, Clone, PartialEq)]
pub enum EdsValue {
    /// BOOLEAN, UNSIGNEDn, TIME_OF_DAY, TIME_DIFFERENCE.
    Unsigned(u64),
    /// INTEGERn.
    Signed(i64),
    /// REAL32, REAL64.
    Real(f64),
    /// Strings, OCTET_STRING, DOMAIN and values of unknown data types, as
    /// written.
    Text(String),
}

impl EdsValue {
    /// Return the value as an unsigned number, if it is one, or a signed
    /// one that is not negative.
    #[must_use]
    pub fn as_u64(&self) -> Option<u64> {
        match *self {
            EdsValue::Unsigned(v) => Some(v),
            EdsValue::Signed(v) => u64::try_from(v).ok(),
            _ => None,
        }
    }

    /// Return the value as a signed number, if it is an integer in range.
    #[must_use]
    pub fn as_i64(&self) -> Option<i64> {
        match *self {
            EdsValue::Unsigned(v) => i64::try_from(v).ok(),
            EdsValue::Signed(v) => Some(v),
            _ => None,
        }
    }

    /// Return the value as a real, if it is one.
    #[must_use]
    pub fn as_f64(&self) -> Option<f64> {
        match *self {
            EdsValue::Real(v) => Some(v),
            _ => None,
        }
    }

    /// Return the text, if the value is text.
    #[must_use]
    pub fn as_str(&self) -> Option<&str> {
        match self {
            EdsValue::Text(text) => Some(text),
            _ => None,
        }
    }
}

impl fmt::Display for EdsValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EdsValue::Unsigned(v) => write!(f, "{v}"),
            EdsValue::Signed(v) => write!(f, "{v}"),
            EdsValue::Real(v) => write!(f, "{v}"),
            EdsValue::Text(v) => f.write_str(v),
        }
    }
}

/// Why a value cannot be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum ValueError {
    /// Not a number or `$NODEID` expression.
    Syntax,
    /// `$NODEID` with no node-ID given.
    NodeIdUnknown,
    /// A number outside the data type's range.
    OutOfRange,
}

/// Return the integer of `text`: terms joined by `+` or `-` (the first may
/// carry a sign), each a number — `0x` hex, a leading `0` octal, else
/// decimal — or `$NODEID` (any case), which is `node`. White space between
/// terms is allowed. CiA 306 writes `$NODEID+0x180`; files also
/// write `0x180+$NODEID`, `$NodeID + 0x180` and sums of several numbers.
pub(crate) fn parse_integer(text: &str, node: Option<NodeId>) -> Result<i128, ValueError> {
    let bytes = text.as_bytes();
    let mut pos = 0;
    let mut total: i128 = 0;
    let mut first = true;
    loop {
        skip_space(bytes, &mut pos);
        let negative = match bytes.get(pos) {
            Some(b'+') => {
                pos += 1;
                false
            }
            Some(b'-') => {
                pos += 1;
                true
            }
            _ if first => false,
            _ => return Err(ValueError::Syntax),
        };
        skip_space(bytes, &mut pos);
        let term = if bytes[pos..].starts_with(b"$") {
            let name = b"$NODEID";
            let end = pos + name.len();
            if bytes.len() < end || !bytes[pos..end].eq_ignore_ascii_case(name) {
                return Err(ValueError::Syntax);
            }
            pos = end;
            i128::from(node.ok_or(ValueError::NodeIdUnknown)?.get())
        } else {
            let start = pos;
            while pos < bytes.len() && bytes[pos].is_ascii_alphanumeric() {
                pos += 1;
            }
            parse_number(&text[start..pos])?
        };
        total = if negative { total - term } else { total + term };
        first = false;
        skip_space(bytes, &mut pos);
        if pos == bytes.len() {
            return Ok(total);
        }
    }
}

fn skip_space(bytes: &[u8], pos: &mut usize) {
    while *pos < bytes.len() && bytes[*pos].is_ascii_whitespace() {
        *pos += 1;
    }
}

/// Return the unsigned number `digits`: `0x`/`0X` hex, a leading `0`
/// octal, else decimal; at most 64 bits.
fn parse_number(digits: &str) -> Result<i128, ValueError> {
    let (radix, body) = if let Some(hex) = digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        (16, hex)
    } else if digits.len() > 1 && digits.starts_with('0') {
        (8, &digits[1..])
    } else {
        (10, digits)
    };
    if body.is_empty() || !body.bytes().all(|b| (b as char).is_digit(radix)) {
        return Err(ValueError::Syntax);
    }
    u64::from_str_radix(body, radix)
        .map(i128::from)
        .map_err(|_| ValueError::OutOfRange)
}

/// Return `text` read as a value of `data_type` (`None`: a type the crate
/// does not know, kept as text). An empty text is no value.
pub(crate) fn parse_value(
    text: &str,
    data_type: Option<DataType>,
    node: Option<NodeId>,
) -> Result<Option<EdsValue>, ValueError> {
    if text.is_empty() {
        return Ok(None);
    }
    let Some(data_type) = data_type else {
        return Ok(Some(EdsValue::Text(text.to_owned())));
    };
    let value = match data_type {
        DataType::VisibleString
        | DataType::OctetString
        | DataType::UnicodeString
        | DataType::Domain => EdsValue::Text(text.to_owned()),
        DataType::Real32 | DataType::Real64 => {
            let real: f64 = text.trim().parse().map_err(|_| ValueError::Syntax)?;
            EdsValue::Real(real)
        }
        _ => {
            let bits = u32::from(data_type.bits().unwrap_or(64)).max(8);
            let value = parse_integer(text, node)?;
            let span: i128 = 1 << bits;
            if data_type.is_signed() {
                let max = span / 2 - 1;
                let min = -span / 2;
                // A hex or large value up to 2^bits - 1 is the two's
                // complement pattern (e.g. 0xFFFF for an INTEGER16 is -1).
                let value = if value > max && value < span {
                    value - span
                } else {
                    value
                };
                if value < min || value > max {
                    return Err(ValueError::OutOfRange);
                }
                EdsValue::Signed(value as i64)
            } else {
                if value < 0 || value >= span {
                    return Err(ValueError::OutOfRange);
                }
                EdsValue::Unsigned(value as u64)
            }
        }
    };
    Ok(Some(value))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(raw: u8) -> Option<NodeId> {
        NodeId::new(raw)
    }

    #[test]
    fn numbers_and_expressions() {
        let table: &[(&str, Option<NodeId>, Result<i128, ValueError>)] = &[
            ("0", None, Ok(0)),
            ("42", None, Ok(42)),
            ("0x2A", None, Ok(42)),
            ("0X2a", None, Ok(42)),
            ("052", None, Ok(42)),
            ("-5", None, Ok(-5)),
            ("+5", None, Ok(5)),
            ("$NODEID+0x180", n(5), Ok(0x185)),
            ("$NODEID+384", n(0x10), Ok(0x190)),
            ("1280+$NODEID", n(0x10), Ok(0x510)),
            ("0x180 + $NodeID", n(1), Ok(0x181)),
            ("$NodeID + 0x80", n(127), Ok(0xFF)),
            ("0x80000000+$NODEID+0x280", n(2), Ok(0x8000_0282)),
            ("$NODEID", n(7), Ok(7)),
            ("$NODEID+0x180", None, Err(ValueError::NodeIdUnknown)),
            ("0x", None, Err(ValueError::Syntax)),
            ("08", None, Err(ValueError::Syntax)),
            ("12a", None, Err(ValueError::Syntax)),
            ("$NODE+1", n(1), Err(ValueError::Syntax)),
            ("1 2", None, Err(ValueError::Syntax)),
            ("1+", None, Err(ValueError::Syntax)),
            ("0x10000000000000000", None, Err(ValueError::OutOfRange)),
        ];
        for (text, node, expected) in table {
            assert_eq!(&parse_integer(text, *node), expected, "{text:?}");
        }
    }

    #[test]
    fn values_by_type() {
        use DataType::*;
        type Case = (&'static str, DataType, Result<Option<EdsValue>, ValueError>);
        let table: &[Case] = &[
            ("", Unsigned8, Ok(None)),
            ("255", Unsigned8, Ok(Some(EdsValue::Unsigned(255)))),
            ("256", Unsigned8, Err(ValueError::OutOfRange)),
            ("-1", Unsigned8, Err(ValueError::OutOfRange)),
            ("0xFFFF", Integer16, Ok(Some(EdsValue::Signed(-1)))),
            ("-32768", Integer16, Ok(Some(EdsValue::Signed(-32768)))),
            ("-32769", Integer16, Err(ValueError::OutOfRange)),
            ("0x10000", Integer16, Err(ValueError::OutOfRange)),
            ("0xFFFFFF", Integer24, Ok(Some(EdsValue::Signed(-1)))),
            ("1", Boolean, Ok(Some(EdsValue::Unsigned(1)))),
            ("5.2", Real32, Ok(Some(EdsValue::Real(5.2)))),
            ("x", Real32, Err(ValueError::Syntax)),
            (
                "hello ; x",
                VisibleString,
                Ok(Some(EdsValue::Text("hello ; x".into()))),
            ),
            (
                "0xFFFFFFFFFFFFFFFF",
                Unsigned64,
                Ok(Some(EdsValue::Unsigned(u64::MAX))),
            ),
            (
                "0x8000000000000000",
                Integer64,
                Ok(Some(EdsValue::Signed(i64::MIN))),
            ),
        ];
        for (text, data_type, expected) in table {
            assert_eq!(
                &parse_value(text, Some(*data_type), None),
                expected,
                "{text:?} {data_type}"
            );
        }
        assert_eq!(
            parse_value("0x40", None, None),
            Ok(Some(EdsValue::Text("0x40".into())))
        );
    }
}
