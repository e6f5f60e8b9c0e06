//! The screen format after the identifier (docs/formats.md#candump-screen).

use super::error::error;
use super::frame::Parsed;
use super::log::trailing;
use crate::can::{FdFlags, FrameType, CLASSIC_MAX_LEN, FD_MAX_LEN};
use crate::logs::error::Result;
use crate::logs::lex::{found, hex_value, is_space, skip_space};
use crate::logs::FormatError;
use crate::logs::{Found, SyntaxError};

/// Skip one or more spaces or tabs at `at`.
#[inline(always)]
pub(super) fn need_space(line: &[u8], at: usize) -> Result<usize> {
    match line.get(at) {
        Some(&b) if is_space(b) => Ok(skip_space(line, at + 1)),
        _ => Err(error(
            at,
            SyntaxError::MissingWhiteSpace {
                found: found(line, at),
            },
        )),
    }
}

/// The word candump -e writes after an error frame's data (can-utils
/// `lib.c`, `snprintf_long_canframe`).
const ERRORFRAME: &[u8] = b"ERRORFRAME";

/// Parse the `- -`/`B -`/`- E`/`B E` of the screen's `RX`/`TX` column
/// starting at the white space at `at`; return the flags and the index of
/// the identifier.
pub(super) fn parse_indicators(line: &[u8], at: usize) -> Result<(FdFlags, usize)> {
    let brs_at = skip_space(line, at);
    let brs = match line.get(brs_at) {
        Some(b'-') => FdFlags::EMPTY,
        Some(b'B') => FdFlags::BRS,
        _ => return Err(bad_indicators(line, brs_at)),
    };
    let esi_at = need_space(line, brs_at + 1)?;
    let esi = match line.get(esi_at) {
        Some(b'-') => FdFlags::EMPTY,
        Some(b'E') => FdFlags::ESI,
        _ => return Err(bad_indicators(line, esi_at)),
    };
    Ok((brs.union(esi), need_space(line, esi_at + 1)?))
}

#[cold]
pub(super) fn bad_indicators(line: &[u8], at: usize) -> FormatError {
    error(
        at,
        SyntaxError::BadFdIndicators {
            found: found(line, at),
        },
    )
}

/// Parse the screen format after the identifier, from the white space at
/// `at`: `[len]` then `remote request` or the data bytes.
pub(super) fn parse_screen_frame(line: &[u8], at: usize, frame: &mut Parsed<'_>) -> Result<()> {
    let open = skip_space(line, at);
    let bad_length = |i: usize| {
        error(
            i,
            SyntaxError::BadLength {
                found: found(line, i),
            },
        )
    };
    let digit = |i: usize| match line.get(i) {
        Some(b @ b'0'..=b'9') => Some(usize::from(b - b'0')),
        _ => None,
    };
    let (declared, close) = match line.get(open) {
        // `candump -8`: a classic frame's raw DLC as one upper-case hex
        // digit; 9 to F carry 8 bytes (ISO 11898-1).
        Some(b'{') => match line.get(open + 1) {
            Some(&b @ (b'0'..=b'9' | b'A'..=b'F')) => (
                hex_value(b).map_or(0, usize::from).min(CLASSIC_MAX_LEN),
                open + 2,
            ),
            _ => return Err(bad_length(open + 1)),
        },
        Some(b'[') => match (digit(open + 1), digit(open + 2)) {
            (Some(len), None) => (len, open + 2),
            (Some(tens), Some(ones)) => (tens * 10 + ones, open + 3),
            (None, _) => return Err(bad_length(open + 1)),
        },
        _ => return Err(bad_length(open)),
    };
    let closing = if line.get(open) == Some(&b'{') {
        b'}'
    } else {
        b']'
    };
    if line.get(close) != Some(&closing) {
        return Err(bad_length(close));
    }
    let fd = close == open + 3;
    if fd && frame.kind == FrameType::Error {
        return Err(error(
            open,
            SyntaxError::BadErrorFrame {
                found: Found::Byte(b'['),
            },
        ));
    }
    let max = if fd { FD_MAX_LEN } else { CLASSIC_MAX_LEN };
    if declared > max {
        return Err(bad_length(open + 1));
    }
    if fd {
        frame.kind = FrameType::Fd(FdFlags::EMPTY);
    }

    let mut at = close + 1;
    if at == line.len() {
        return if declared == 0 {
            Ok(())
        } else {
            Err(mismatch(open, declared, 0))
        };
    }
    at = need_space(line, at)?;
    const REMOTE: &[u8] = b"remote request";
    if !fd && frame.kind != FrameType::Error && line.get(at..at + REMOTE.len()) == Some(REMOTE) {
        // At most 8 (checked above for a classic length).
        frame.kind = FrameType::Remote {
            dlc: declared as u8,
        };
        let end = at + REMOTE.len();
        return if end == line.len() {
            Ok(())
        } else {
            Err(trailing(line, end))
        };
    }

    let mut count = 0;
    loop {
        // candump -e ends an error frame's line with `ERRORFRAME`.
        if frame.kind == FrameType::Error && line.get(at..) == Some(ERRORFRAME) {
            break;
        }
        if line.get(at) == Some(&b'\'') && frame.kind != FrameType::Error {
            // `candump -a`: the data as ASCII between single quotes.
            if count != declared {
                return Err(mismatch(open, declared, count));
            }
            frame.len = declared as u8;
            return parse_ascii(line, at, frame);
        }
        let byte = match (
            line.get(at).and_then(|b| hex_value(*b)),
            line.get(at + 1).and_then(|b| hex_value(*b)),
            line.get(at + 2),
        ) {
            (Some(hi), Some(lo), None) => hi << 4 | lo,
            (Some(hi), Some(lo), Some(&b)) if is_space(b) => hi << 4 | lo,
            _ => return Err(unsupported_or_bad_hex(line, at)),
        };
        if let Some(d) = frame.data.get_mut(count) {
            *d = byte;
        }
        count += 1;
        at += 2;
        if at == line.len() {
            break;
        }
        at = need_space(line, at)?;
    }

    if count != declared {
        return Err(mismatch(open, declared, count));
    }
    frame.len = declared as u8;
    Ok(())
}

/// `candump -a`'s column after the data: `'` then one character per data
/// byte (the byte when it is printable ASCII, 0x20 to 0x7E, else `.`) then
/// `'` and the end of the line. The column must show the data read before
/// it: a line whose two forms disagree is not silently believed.
fn parse_ascii(line: &[u8], open: usize, frame: &Parsed<'_>) -> Result<()> {
    let len = usize::from(frame.len);
    let data = frame.data.get(..len).unwrap_or_default();
    for (i, &byte) in data.iter().enumerate() {
        let expected = if (0x20..0x7F).contains(&byte) {
            byte
        } else {
            b'.'
        };
        let at = open + 1 + i;
        if line.get(at) != Some(&expected) {
            return Err(error(
                at,
                SyntaxError::BadAscii {
                    expected,
                    found: found(line, at),
                },
            ));
        }
    }
    let close = open + 1 + len;
    if line.get(close) != Some(&b'\'') {
        return Err(error(
            close,
            SyntaxError::BadAscii {
                expected: b'\'',
                found: found(line, close),
            },
        ));
    }
    if close + 1 != line.len() {
        return Err(trailing(line, close + 1));
    }
    Ok(())
}

/// A data field that is not two hex digits: candump's `-S` (bytes swapped,
/// joined by a backquote) and `-i` (bytes in binary) forms cannot be read
/// back faithfully and say so (docs/formats.md#candump-screen); anything else
/// is a bad digit.
#[cold]
fn unsupported_or_bad_hex(line: &[u8], at: usize) -> FormatError {
    let rest = line.get(at..).unwrap_or_default();
    let token_len = rest.iter().position(|&b| is_space(b)).unwrap_or(rest.len());
    let token = rest.get(..token_len).unwrap_or_default();
    if token.contains(&b'`') {
        return error(at, SyntaxError::UnsupportedOutput { option: b'S' });
    }
    if token.len() == 8 && token.iter().all(|b| matches!(b, b'0' | b'1')) {
        return error(at, SyntaxError::UnsupportedOutput { option: b'i' });
    }
    match (
        line.get(at).and_then(|b| hex_value(*b)),
        line.get(at + 1).and_then(|b| hex_value(*b)),
    ) {
        (None, _) => bad_hex(line, at),
        (Some(_), None) => bad_hex(line, at + 1),
        (Some(_), Some(_)) => error(
            at + 2,
            SyntaxError::MissingWhiteSpace {
                found: found(line, at + 2),
            },
        ),
    }
}

#[cold]
pub(super) fn bad_hex(line: &[u8], at: usize) -> FormatError {
    error(
        at,
        SyntaxError::BadHexDigit {
            found: found(line, at),
        },
    )
}

#[cold]
pub(super) fn mismatch(open: usize, declared: usize, found: usize) -> FormatError {
    error(open, SyntaxError::LengthMismatch { declared, found })
}
