//! The log format after the identifier's `#` (docs/formats.md#candump-log).

use super::error::error;
use super::frame::Parsed;
use super::hex::decode_hex;
use crate::can::{Direction, FdFlags, FrameType, CLASSIC_MAX_LEN, FD_MAX_LEN};
use crate::logs::error::Result;
use crate::logs::lex::{found, hex_value, is_space, skip_space, trim_end};
use crate::logs::FormatError;
use crate::logs::{Found, SyntaxError};

/// Parse the log format after the identifier's `#` at `start - 1`:
/// `R[len]`, `#<flags><data>` or `<data>`, then an optional direction.
#[inline(always)]
pub(super) fn parse_log_frame(line: &[u8], start: usize, frame: &mut Parsed<'_>) -> Result<()> {
    let mut end = line.len();
    if let [.., space, d @ (b'R' | b'T')] = line {
        // `start` ≤ the space's index: the byte before `start` is `#`.
        if is_space(*space) {
            frame.direction = Some(if *d == b'R' {
                Direction::Rx
            } else {
                Direction::Tx
            });
            end = trim_end(line.get(..end - 2).unwrap_or_default())
                .len()
                .max(start);
        }
    }
    match line.get(start) {
        // An error frame is classic data (Linux `CAN_ERR_DLC`,
        // docs/formats.md#error-frames).
        Some(&b @ (b'R' | b'r' | b'#')) if frame.kind == FrameType::Error => Err(error(
            start,
            SyntaxError::BadErrorFrame {
                found: Found::Byte(b),
            },
        )),
        Some(b'R' | b'r') => {
            let dlc = match line.get(start + 1..end).unwrap_or_default() {
                [] => 0,
                [d @ b'0'..=b'8'] => d - b'0',
                [b'0'..=b'8', ..] => return Err(trailing(line, skip_space(line, start + 2))),
                [b' ' | b'\t', ..] => return Err(trailing(line, skip_space(line, start + 1))),
                _ => {
                    return Err(error(
                        start + 1,
                        SyntaxError::BadRemoteLength {
                            found: found(line, start + 1),
                        },
                    ))
                }
            };
            frame.kind = FrameType::Remote { dlc };
            Ok(())
        }
        Some(b'#') => {
            let flags = match line.get(start + 1).and_then(|b| hex_value(*b)) {
                Some(v) => FdFlags::new(v).unwrap_or_default(),
                None => {
                    return Err(error(
                        start + 1,
                        SyntaxError::BadFdFlags {
                            found: found(line, start + 1),
                        },
                    ))
                }
            };
            frame.kind = FrameType::Fd(flags);
            frame.len = parse_log_data(line, start + 2, end, FD_MAX_LEN, &mut frame.data)?;
            Ok(())
        }
        _ => {
            frame.len = parse_log_data(line, start, end, CLASSIC_MAX_LEN, &mut frame.data)?;
            Ok(())
        }
    }
}

/// Decode the log format's hex data `line[start..end]`, at most `max`
/// bytes; return the number of bytes.
#[inline(always)]
pub(super) fn parse_log_data(
    line: &[u8],
    start: usize,
    end: usize,
    max: usize,
    data: &mut [u8; FD_MAX_LEN],
) -> Result<u8> {
    let digits = end.saturating_sub(start);
    if digits > 2 * max {
        return Err(data_too_long(line, start, end, max));
    }
    if let Err(at) = decode_hex(line, start, end, data) {
        return Err(bad_data(line, at));
    }
    if digits % 2 != 0 {
        return Err(error(start, SyntaxError::OddHexDigits { digits }));
    }
    Ok((digits / 2) as u8)
}

#[cold]
#[inline(never)]
pub(super) fn data_too_long(line: &[u8], start: usize, end: usize, max: usize) -> FormatError {
    let digits = line.get(start..end).unwrap_or_default();
    match digits.iter().position(|b| hex_value(*b).is_none()) {
        Some(i) => bad_data(line, start + i),
        None => error(
            start,
            SyntaxError::DataTooLong {
                digits: digits.len(),
                max_bytes: max,
            },
        ),
    }
}

/// The error for the non-hex byte at `at` in log-format data: white space
/// means the frame ended and something else follows.
#[cold]
#[inline(never)]
pub(super) fn bad_data(line: &[u8], at: usize) -> FormatError {
    match line.get(at) {
        Some(&b) if is_space(b) => {
            // After the data only a direction letter may stand; point past it
            // when it is there.
            let mut next = skip_space(line, at);
            if matches!(line.get(next), Some(b'R' | b'T')) {
                next = skip_space(line, next + 1);
            }
            trailing(line, next)
        }
        _ => error(
            at,
            SyntaxError::BadHexDigit {
                found: found(line, at),
            },
        ),
    }
}

#[cold]
pub(super) fn trailing(line: &[u8], at: usize) -> FormatError {
    error(
        at,
        SyntaxError::TrailingGarbage {
            found: found(line, at),
        },
    )
}
