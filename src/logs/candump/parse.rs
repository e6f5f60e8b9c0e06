//! The general parser: any line shape, byte by byte where the shape varies.

use super::error::error;
use super::fast::{parse_canonical_log, IfaceHint};
use super::frame::Parsed;
use super::log::parse_log_frame;
use super::screen::{need_space, parse_indicators, parse_screen_frame};
use super::timestamp::parse_timestamp;
use crate::can::CAN_ERR_FLAG;
use crate::can::{CanId, Direction, FdFlags, FrameType, LogFrame, FD_MAX_LEN};
use crate::logs::error::Result;
use crate::logs::lex::swar::{hex_lanes, lanes_before, load16, non_graphic, pack_hex};
use crate::logs::lex::{found, hex_value, is_space, skip_space, trim_end};
use crate::logs::FormatError;
use crate::logs::{Found, SyntaxError};

/// Parse one candump line in either format of docs/formats.md (see the module's
/// table and decisions). Return `Ok(None)` for a blank or comment line, the
/// frame for a frame line, and a [`FormatError::Syntax`] with the column and
/// reason for anything else. A trailing line end (`\n`, `\r\n`) is allowed.
#[inline]
pub fn parse_line(line: &[u8]) -> Result<Option<LogFrame<'_>>, FormatError> {
    let mut data = [0; FD_MAX_LEN];
    let mut hint = IfaceHint::NONE;
    match parse_canonical_log(line, &mut data, &mut hint) {
        Some((frame, used)) if used == line.len() => {
            Ok(Some(frame.with_data(data).into_log_frame()))
        }
        _ => parse_general(line).map(|frame| frame.map(Parsed::into_log_frame)),
    }
}

/// Parse one candump line given as text; see [`parse_line`].
#[inline]
pub fn parse_line_str(line: &str) -> Result<Option<LogFrame<'_>>, FormatError> {
    parse_line(line.as_bytes())
}

/// Parse one line of any shape, byte by byte where the shape varies.
#[inline(never)]
pub(super) fn parse_general(line: &[u8]) -> Result<Option<Parsed<'_>>> {
    if line.contains(&ESC) {
        return parse_coloured(line);
    }
    parse_plain(line)
}

const ESC: u8 = 0x1B;

/// The longest coloured line that is read (a CAN FD line of 64 bytes with a
/// date and `-x` is about 260 bytes).
const COLOURED_MAX: usize = 512;

/// `candump -c`: the line without its ANSI colour sequences (CSI: `ESC [`,
/// parameter bytes 0x30–0x3F, intermediate bytes 0x20–0x2F, a final byte
/// 0x40–0x7E), parsed as any line; the interface name (which candump never
/// colours inside) is taken from the line itself and error columns count in
/// the line as it was.
///
/// The line's leading spaces and tabs are not copied (the parser skips them
/// anyway), so that indentation never decides whether the rest fits in
/// [`COLOURED_MAX`]: a line reads the same, its error columns shifted,
/// however far it is indented (found by a 150 s fuzz run: a 512-byte
/// coloured line fitted, the same line with one more leading space did not
/// and was read with its escapes, its error 9 columns further right).
#[cold]
#[inline(never)]
fn parse_coloured(line: &[u8]) -> Result<Option<Parsed<'_>>> {
    let mut plain = [0u8; COLOURED_MAX];
    let mut origin = [0u16; COLOURED_MAX + 1];
    let mut len = 0;
    let mut at = skip_space(line, 0);
    while let Some(&b) = line.get(at) {
        if b == ESC && line.get(at + 1) == Some(&b'[') {
            let params = line
                .get(at + 2..)
                .unwrap_or_default()
                .iter()
                .take_while(|b| (0x20..0x40).contains(*b))
                .count();
            if matches!(line.get(at + 2 + params), Some(0x40..=0x7E)) {
                at += 3 + params;
                continue;
            }
        }
        match (plain.get_mut(len), origin.get_mut(len)) {
            (Some(p), Some(o)) => {
                *p = b;
                *o = at as u16;
            }
            // Too long to be candump's: read as it is.
            _ => return parse_plain(line),
        }
        len += 1;
        at += 1;
    }
    if let Some(o) = origin.get_mut(len) {
        *o = at as u16;
    }
    let stripped = plain.get(..len).unwrap_or_default();
    let to_line = |column: usize| {
        origin
            .get(column.saturating_sub(1))
            .map_or(column, |&o| usize::from(o) + 1)
    };
    match parse_plain(stripped) {
        Ok(Some(frame)) => {
            let start = (frame.iface.as_ptr() as usize).wrapping_sub(stripped.as_ptr() as usize);
            let from = origin.get(start).map_or(0, |&o| usize::from(o));
            let iface = line.get(from..from + frame.iface.len()).unwrap_or_default();
            if iface != frame.iface {
                // A colour sequence inside the name: not candump's.
                return Err(error(
                    from,
                    SyntaxError::BadInterface {
                        found: Found::Byte(ESC),
                    },
                ));
            }
            Ok(Some(Parsed { iface, ..frame }))
        }
        Ok(None) => Ok(None),
        Err(FormatError::Syntax {
            format,
            column,
            reason,
        }) => Err(FormatError::Syntax {
            format,
            column: to_line(column),
            reason,
        }),
        Err(other) => Err(other),
    }
}

#[inline(always)]
fn parse_plain(line: &[u8]) -> Result<Option<Parsed<'_>>> {
    let line = trim_end(line);
    let mut at = 0;
    match line.first() {
        None => return Ok(None),
        Some(&b) if is_space(b) => at = skip_space(line, 0),
        Some(_) => {}
    }
    let mut relative = false;
    let timestamp = match line.get(at) {
        Some(b'(') => {
            let (ts, end) = parse_timestamp(line, at)?;
            relative = is_relative(line, at);
            at = need_space(line, end)?;
            Some(ts)
        }
        Some(b'#') => return Ok(None),
        _ => None,
    };

    let iface_start = at;
    let iface_end = scan_iface(line, at)?;
    let iface = line.get(iface_start..iface_end).unwrap_or_default();
    at = skip_space(line, iface_end);

    let mut indicators = None;
    if let Some([d @ (b'R' | b'T'), b'X', s]) = line.get(at..).and_then(|r| r.first_chunk::<3>()) {
        if is_space(*s) {
            let direction = if *d == b'R' {
                Direction::Rx
            } else {
                Direction::Tx
            };
            let (flags, next) = parse_indicators(line, at + 3)?;
            indicators = Some((direction, flags, at));
            at = next;
        }
    }

    let (id, kind, delimiter) = parse_id(line, at)?;
    let mut frame = Parsed {
        timestamp,
        relative,
        iface,
        iface_key: 0,
        id,
        kind,
        direction: None,
        len: 0,
        data: [0; FD_MAX_LEN],
    };
    if line.get(delimiter) == Some(&b'#') {
        if let Some((_, _, column)) = indicators {
            return Err(error(
                column,
                SyntaxError::BadFdIndicators {
                    found: found(line, column),
                },
            ));
        }
        parse_log_frame(line, delimiter + 1, &mut frame)?;
    } else {
        parse_screen_frame(line, delimiter, &mut frame)?;
        if let Some((direction, flags, column)) = indicators {
            frame.direction = Some(direction);
            match frame.kind {
                FrameType::Fd(_) => frame.kind = FrameType::Fd(flags),
                _ if flags != FdFlags::EMPTY => {
                    // Point at the first flag letter a classic frame cannot have.
                    let mut at = skip_space(line, column + 3);
                    if line.get(at) == Some(&b'-') {
                        at = skip_space(line, at + 1);
                    }
                    return Err(error(
                        at,
                        SyntaxError::BadFdIndicators {
                            found: found(line, at),
                        },
                    ));
                }
                _ => {}
            }
        }
    }
    Ok(Some(frame))
}

/// Scan the interface name from `start`; return the index of the white
/// space after it.
/// A timestamp with fewer than ten digits of seconds is `candump -t d` or
/// `-t z`'s `(%03llu.%06llu)`, relative to an earlier frame; `-t a` and the
/// log format write at least ten (`%010llu`), `-t A` a date.
#[inline]
fn is_relative(line: &[u8], open: usize) -> bool {
    let digits = line
        .get(open + 1..)
        .unwrap_or_default()
        .iter()
        .take_while(|b| b.is_ascii_digit())
        .count();
    digits < 10 && line.get(open + 1 + digits) == Some(&b'.')
}

#[inline(always)]
pub(super) fn scan_iface(line: &[u8], start: usize) -> Result<usize> {
    let mut at = start;
    loop {
        let stop = non_graphic(load16(line, at));
        if stop != 0 {
            at += lanes_before(stop);
            break;
        }
        at += 16;
    }
    match line.get(at) {
        _ if matches!(line.get(start), Some(b'(' | b'#')) => Err(error(
            start,
            SyntaxError::BadInterface {
                found: found(line, start),
            },
        )),
        Some(&b) if is_space(b) && at > start => Ok(at),
        None if at > start => Err(missing_frame(line, start, at)),
        _ => Err(error(
            at,
            SyntaxError::BadInterface {
                found: found(line, at),
            },
        )),
    }
}

/// The error for a line that ends after its interface name: a frame where
/// the interface should be, or nothing after the interface.
#[cold]
#[inline(never)]
pub(super) fn missing_frame(line: &[u8], start: usize, end: usize) -> FormatError {
    if line.get(start..end).unwrap_or_default().contains(&b'#') {
        error(start, SyntaxError::MissingInterface)
    } else {
        error(
            end,
            SyntaxError::BadIdentifier {
                found: Found::EndOfLine,
            },
        )
    }
}

/// Parse a 3- or 8-digit identifier at `start`; return it and the index of
/// the `#` or white space after it.
#[inline(always)]
pub(super) fn parse_id(line: &[u8], start: usize) -> Result<(CanId, FrameType, usize)> {
    let (values, bad) = hex_lanes(load16(line, start));
    let digits = lanes_before(bad);
    let end = start + digits;
    let delimited = matches!(line.get(end), Some(&(b'#' | b' ' | b'\t')));
    if digits == 3 && delimited {
        let v = values as u32;
        let raw = (v & 0xF) << 8 | (v >> 8 & 0xF) << 4 | (v >> 16 & 0xF);
        match CanId::standard(raw) {
            Some(id) => Ok((id, FrameType::Data, end)),
            None => Err(out_of_range(start, raw, CanId::STANDARD_MAX)),
        }
    } else if digits == 8 && delimited {
        let raw = (pack_hex(values) as u32).swap_bytes();
        // `CAN_ERR_FLAG` (bit 29) marks an error frame whose other bits are
        // its classes (candump -e, python-can; docs/formats.md#error-frames).
        // Bits 30 and 31 (Linux's RTR and EFF flags) never appear in candump
        // text.
        match CanId::extended(raw & !CAN_ERR_FLAG) {
            Some(id) if raw & CAN_ERR_FLAG == 0 => Ok((id, FrameType::Data, end)),
            Some(id) => Ok((id, FrameType::Error, end)),
            None => Err(out_of_range(start, raw, CAN_ERR_FLAG | CanId::EXTENDED_MAX)),
        }
    } else {
        Err(bad_id(line, start))
    }
}

#[cold]
pub(super) fn out_of_range(start: usize, id: u32, max: u32) -> FormatError {
    error(start, SyntaxError::IdentifierOutOfRange { id, max })
}

#[cold]
#[inline(never)]
pub(super) fn bad_id(line: &[u8], start: usize) -> FormatError {
    let rest = line.get(start..).unwrap_or_default();
    let digits = rest.iter().take_while(|b| hex_value(**b).is_some()).count();
    let end = start + digits;
    match line.get(end) {
        Some(b'#' | b' ' | b'\t') if digits > 0 => {
            error(start, SyntaxError::IdentifierDigits { digits })
        }
        None if digits > 8 => error(start, SyntaxError::IdentifierDigits { digits }),
        _ => error(
            end,
            SyntaxError::BadIdentifier {
                found: found(line, end),
            },
        ),
    }
}
