//! The screen format after the identifier (SPEC §5.2).

use super::*;

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
pub(super) fn bad_indicators(line: &[u8], at: usize) -> Error {
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
    if line.get(open) != Some(&b'[') {
        return Err(bad_length(open));
    }
    let digit = |i: usize| match line.get(i) {
        Some(b @ b'0'..=b'9') => Some(usize::from(b - b'0')),
        _ => None,
    };
    let (declared, close) = match (digit(open + 1), digit(open + 2)) {
        (Some(len), None) => (len, open + 2),
        (Some(tens), Some(ones)) => (tens * 10 + ones, open + 3),
        (None, _) => return Err(bad_length(open + 1)),
    };
    if line.get(close) != Some(&b']') {
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
        let byte = match (
            line.get(at).and_then(|b| hex_value(*b)),
            line.get(at + 1).and_then(|b| hex_value(*b)),
        ) {
            (Some(hi), Some(lo)) => hi << 4 | lo,
            (None, _) => return Err(bad_hex(line, at)),
            (Some(_), None) => return Err(bad_hex(line, at + 1)),
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

#[cold]
pub(super) fn bad_hex(line: &[u8], at: usize) -> Error {
    error(
        at,
        SyntaxError::BadHexDigit {
            found: found(line, at),
        },
    )
}

#[cold]
pub(super) fn mismatch(open: usize, declared: usize, found: usize) -> Error {
    error(open, SyntaxError::LengthMismatch { declared, found })
}
