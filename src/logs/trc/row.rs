//! The rows: one frame or bus event per line, in the columns of the file's
//! version (docs/formats.md#trc; PEAK's TRC format description).

use core::time::Duration;

use super::header::{Column, Layout, TrcVersion};
use crate::can::{
    BusStatus, CanFrame, CanId, Direction, ErrorClasses, FdFlags, FrameType, Iface, LogEvent,
    LogFrame, Timestamp, CLASSIC_MAX_LEN, FD_MAX_LEN,
};
use crate::logs::error::Result;
use crate::logs::lex::{bad_field, decimal, decimal_fraction, hex, hex_byte, syntax, Tokens};
use crate::logs::FormatError;
use crate::logs::{Found, LogFormat, SyntaxError};
use crate::CodecError;

/// What the file's header said, as a row needs it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Context {
    pub(super) version: TrcVersion,
    pub(super) start: Timestamp,
    pub(super) layout: Layout,
}

/// The CAN FD lengths by DLC (ISO 11898-1).
pub(super) use crate::can::FD_LENGTHS;

/// The identifier column of 1.x rows that marks an error warning (a bus
/// status row in version 1.0, which has no type column).
const WARNING_ID: &[u8] = b"FFFFFFFF";

/// The error classes of an error frame read from a PEAK error frame row:
/// a bus error with its protocol error type and location and the error
/// counters, as Linux's SJA1000 driver reports the same controller event
/// (`CAN_ERR_BUSERROR | CAN_ERR_PROT | CAN_ERR_CNT`).
pub const ERROR_FRAME_CLASSES: ErrorClasses = ErrorClasses::BUS_ERROR
    .union(ErrorClasses::PROTOCOL)
    .union(ErrorClasses::COUNTERS);

/// Linux `CAN_ERR_PROT_TX`: the protocol error happened while sending.
pub(super) const PROT_TX: u8 = 0x80;
/// The protocol error types PEAK and Linux number alike: bit 0x01, form
/// 0x02, stuff 0x04. PEAK's "other" (0x08) is Linux's unspecified (0).
pub(super) const PROT_TYPES: u8 = 0x07;
/// Linux's error locations are the SJA1000's ECC segment codes, 5 bits.
pub(super) const PROT_LOCATION: u8 = 0x1F;

/// The kind of a row, from its type column (2.x) or its type and
/// identifier columns (1.x).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// A frame of this type (the length fills in a remote request's DLC).
    Frame(FrameType),
    /// A PEAK error frame.
    Error,
    /// A bus status event: hardware status, error counter change, event,
    /// error warning.
    Status,
}

/// Read a data row of `ctx`'s version.
pub(super) fn parse_row(line: &[u8], ctx: &Context) -> Result<LogEvent<'static>> {
    if ctx.version.has_columns_header() {
        parse_v2(line, ctx)
    } else {
        parse_v1(line, ctx)
    }
}

/// The message number: digits, with `)` after them in 1.x.
fn number(tokens: &mut Tokens<'_>, v1: bool) -> Result<()> {
    let (start, field) = tokens.expect(|found| SyntaxError::TrcMessageNumber { found })?;
    let digits = match field.split_last() {
        Some((b')', digits)) if v1 => digits,
        _ => field,
    };
    let bad = digits
        .iter()
        .position(|b| !b.is_ascii_digit())
        .or(digits.is_empty().then_some(digits.len()));
    match bad {
        None => Ok(()),
        Some(i) => Err(bad_field(LogFormat::Trc, start, field, i, |found| {
            SyntaxError::TrcMessageNumber { found }
        })),
    }
}

/// The time offset in ms, up to 6 fraction digits, added to the start.
fn offset(tokens: &mut Tokens<'_>, ctx: &Context) -> Result<Timestamp> {
    let (start, field) = tokens.expect(|found| SyntaxError::TrcTimeOffset { found })?;
    let bad = |i: usize| {
        bad_field(LogFormat::Trc, start, field, i, |found| {
            SyntaxError::TrcTimeOffset { found }
        })
    };
    let (millis, nanos) = decimal_fraction(field, 15, 6, true).map_err(bad)?;
    let nanos = u64::try_from(nanos).map_err(|_| bad(0))?;
    let since_start = Duration::from_millis(millis) + Duration::from_nanos(nanos);
    ctx.start.checked_add(since_start).ok_or_else(|| bad(0))
}

/// A bus number, or `-` for none.
fn bus(tokens: &mut Tokens<'_>) -> Result<Option<Iface<'static>>> {
    let (start, field) = tokens.expect(|found| SyntaxError::TrcBus { found })?;
    if field == b"-" {
        return Ok(None);
    }
    decimal(field, u64::from(u16::MAX))
        .and_then(|b| u16::try_from(b).ok())
        .map(|b| Some(Iface::Channel(b)))
        .ok_or_else(|| {
            bad_field(LogFormat::Trc, start, field, 0, |found| {
                SyntaxError::TrcBus { found }
            })
        })
}

/// `Rx`, `Tx`, or `-` for none.
fn direction_of(field: &[u8]) -> Option<Option<Direction>> {
    match field {
        b"Rx" => Some(Some(Direction::Rx)),
        b"Tx" => Some(Some(Direction::Tx)),
        b"-" => Some(None),
        _ => None,
    }
}

/// The direction column.
fn direction(tokens: &mut Tokens<'_>) -> Result<Option<Direction>> {
    let (start, field) = tokens.expect(|found| SyntaxError::TrcDirection { found })?;
    direction_of(field).ok_or_else(|| {
        bad_field(LogFormat::Trc, start, field, 0, |found| {
            SyntaxError::TrcDirection { found }
        })
    })
}

/// The identifier: up to 4 hex digits standard, more extended (PEAK writes
/// 4 and 8; python-can's writer 4 and 7; python-can's reader: more than 4).
fn identifier(tokens: &mut Tokens<'_>) -> Result<CanId> {
    let (start, field) = tokens.expect(|found| SyntaxError::TrcIdentifier { found })?;
    let Some(raw) = hex(field) else {
        let bad = field
            .iter()
            .position(|b| !b.is_ascii_hexdigit())
            .unwrap_or(8);
        return Err(bad_field(LogFormat::Trc, start, field, bad, |found| {
            SyntaxError::TrcIdentifier { found }
        }));
    };
    let (id, max) = if field.len() > 4 {
        (CanId::extended(raw), CanId::EXTENDED_MAX)
    } else {
        (CanId::standard(raw), CanId::STANDARD_MAX)
    };
    id.ok_or(syntax(
        LogFormat::Trc,
        start + 1,
        SyntaxError::IdentifierOutOfRange { id: raw, max },
    ))
}

/// The length column: a DLC (`dlc` true) or a byte count; the number of
/// data bytes (a remote request's requested length) for `kind`.
fn length(tokens: &mut Tokens<'_>, kind: Kind, dlc: bool) -> Result<u8> {
    let (start, field) = tokens.expect(|found| SyntaxError::TrcLength { found })?;
    let fd = matches!(kind, Kind::Frame(FrameType::Fd(_)));
    let value = match (dlc, fd) {
        (true, true) => {
            decimal(field, 15).and_then(|d| FD_LENGTHS.get(usize::try_from(d).ok()?).copied())
        }
        (false, true) => decimal(field, FD_MAX_LEN as u64).map(|l| l as u8),
        (_, false) => decimal(field, CLASSIC_MAX_LEN as u64).map(|l| l as u8),
    };
    value.ok_or_else(|| {
        bad_field(LogFormat::Trc, start, field, 0, |found| {
            SyntaxError::TrcLength { found }
        })
    })
}

/// The data bytes: up to `buf.len()` of two hex digits each, to the end of
/// the line. Return how many.
fn data(tokens: &mut Tokens<'_>, buf: &mut [u8]) -> Result<usize> {
    let mut n = 0;
    while let Some((start, field)) = tokens.next_token() {
        let Some(byte) = hex_byte(field) else {
            let bad = field
                .iter()
                .position(|b| !b.is_ascii_hexdigit())
                .unwrap_or(field.len().min(2));
            let found = tokens.found_at(start + bad);
            return Err(syntax(
                LogFormat::Trc,
                start + bad + 1,
                SyntaxError::TrcDataByte { found },
            ));
        };
        let Some(slot) = buf.get_mut(n) else {
            return Err(syntax(
                LogFormat::Trc,
                start + 1,
                SyntaxError::TrcTrailing {
                    found: Found::Byte(field.first().copied().unwrap_or(b' ')),
                },
            ));
        };
        *slot = byte;
        n += 1;
    }
    Ok(n)
}

/// Check that nothing is left on the line.
fn end(tokens: &mut Tokens<'_>) -> Result<()> {
    match tokens.next_token() {
        None => Ok(()),
        Some((start, field)) => Err(bad_field(LogFormat::Trc, start, field, 0, |found| {
            SyntaxError::TrcTrailing { found }
        })),
    }
}

/// The frame of `kind` with `len` bytes of `bytes` (a remote request's
/// requested length).
fn frame(
    id: CanId,
    kind: FrameType,
    bytes: &[u8; FD_MAX_LEN],
    len: u8,
) -> Result<CanFrame, CodecError> {
    match kind {
        FrameType::Remote { .. } => CanFrame::new_remote(id, len).map_err(CodecError::from),
        _ => CanFrame::with_type(id, kind, bytes.get(..usize::from(len)).unwrap_or_default())
            .map_err(CodecError::from),
    }
}

/// The error frame a PEAK error frame row reads as (see the module's
/// decisions): `kind` is PEAK's error type (1 bit, 2 form, 4 stuff, 8
/// other), `rx` whether it happened while receiving, `position` the bit
/// stream processor's position (SJA1000 ECC segment).
pub(super) fn error_frame(
    kind: u8,
    rx: bool,
    position: u8,
    rx_errors: u8,
    tx_errors: u8,
) -> CanFrame {
    let prot_type = (kind & PROT_TYPES) | if rx { 0 } else { PROT_TX };
    let mut data = [0u8; FD_MAX_LEN];
    data[2] = prot_type;
    data[3] = position & PROT_LOCATION;
    data[6] = tx_errors;
    data[7] = rx_errors;
    // The classes fit 29 bits; the frame has the 8 bytes Linux gives it.
    CanFrame::from_array(
        CanId::masked(ERROR_FRAME_CLASSES.bits(), true),
        FrameType::Error,
        data,
        8,
    )
}

/// The 2.x row type.
fn kind_v2(field: &[u8]) -> Option<Kind> {
    Some(match field {
        b"DT" => Kind::Frame(FrameType::Data),
        b"RR" => Kind::Frame(FrameType::Remote { dlc: 0 }),
        b"FD" => Kind::Frame(FrameType::Fd(FdFlags::EMPTY)),
        b"FB" => Kind::Frame(FrameType::Fd(FdFlags::BRS)),
        b"FE" => Kind::Frame(FrameType::Fd(FdFlags::ESI)),
        b"BI" => Kind::Frame(FrameType::Fd(FdFlags::BRS.union(FdFlags::ESI))),
        b"ER" => Kind::Error,
        b"ST" | b"EC" | b"EV" => Kind::Status,
        _ => return None,
    })
}

/// A 2.x row, its columns in the order of `;$COLUMNS=`.
fn parse_v2(line: &[u8], ctx: &Context) -> Result<LogEvent<'static>> {
    let mut tokens = Tokens::new(LogFormat::Trc, line);
    let mut ts = None;
    let mut kind = None;
    let mut iface = None;
    let mut dir = None;
    let mut id = None;
    let mut len = None;
    let mut bytes = [0u8; FD_MAX_LEN];
    let mut count = 0;
    for &column in ctx.layout.columns() {
        match (column, kind) {
            (Column::Number, _) => number(&mut tokens, false)?,
            (Column::Offset, _) => ts = Some(offset(&mut tokens, ctx)?),
            (Column::Type, _) => {
                let (start, field) = tokens.expect(|found| SyntaxError::TrcRowType { found })?;
                kind = Some(kind_v2(field).ok_or_else(|| {
                    bad_field(LogFormat::Trc, start, field, 0, |found| {
                        SyntaxError::TrcRowType { found }
                    })
                })?);
            }
            (Column::Bus, _) => iface = bus(&mut tokens)?,
            // A status row is a bus event whatever its other columns hold
            // (PEAK leaves them empty in 2.0, writes `-` in 2.1).
            (_, Some(Kind::Status)) => break,
            (_, Some(Kind::Error)) => {
                return error_row_v2(&mut tokens, ctx, column, ts, iface);
            }
            (Column::Id, _) => id = Some(identifier(&mut tokens)?),
            (Column::Direction, _) => dir = direction(&mut tokens)?,
            (Column::Reserved, _) => {
                tokens.expect(|found| SyntaxError::TrcLength { found })?;
            }
            (Column::Dlc | Column::Length, Some(k)) => {
                len = Some(length(&mut tokens, k, column == Column::Dlc)?);
            }
            (Column::Data, Some(Kind::Frame(FrameType::Remote { .. }))) => {}
            (Column::Data, _) => count = data(&mut tokens, &mut bytes)?,
            (Column::Dlc | Column::Length, None) => {
                let (start, field) = tokens.expect(|found| SyntaxError::TrcRowType { found })?;
                return Err(bad_field(LogFormat::Trc, start, field, 0, |found| {
                    SyntaxError::TrcRowType { found }
                }));
            }
        }
    }
    if kind == Some(Kind::Status) {
        return Ok(LogEvent::Status(BusStatus {
            timestamp: ts,
            iface,
        }));
    }
    end(&mut tokens)?;
    let (Some(Kind::Frame(frame_type)), Some(id), Some(len)) = (kind, id, len) else {
        // A layout without the type column: every complete layout has it.
        return Err(syntax(
            LogFormat::Trc,
            tokens.end_column(),
            SyntaxError::TrcRowType {
                found: Found::EndOfLine,
            },
        ));
    };
    if !matches!(frame_type, FrameType::Remote { .. }) && count != usize::from(len) {
        return Err(syntax(
            LogFormat::Trc,
            tokens.end_column(),
            SyntaxError::LengthMismatch {
                declared: usize::from(len),
                found: count,
            },
        ));
    }
    let frame = frame(id, frame_type, &bytes, len).map_err(|_| {
        syntax(
            LogFormat::Trc,
            tokens.end_column(),
            SyntaxError::TrcLength {
                found: Found::EndOfLine,
            },
        )
    })?;
    Ok(LogEvent::Frame(LogFrame {
        frame,
        timestamp: ts,
        iface,
        direction: dir,
    }))
}

/// The rest of a 2.x `ER` row from `column` on. PEAK writes the identifier
/// and length columns empty (2.0) or as `-` and `5` (2.1); the data are
/// five bytes: error type, direction (0 sending, 1 receiving), position,
/// RX and TX error counters.
fn error_row_v2(
    tokens: &mut Tokens<'_>,
    ctx: &Context,
    first: Column,
    ts: Option<Timestamp>,
    mut iface: Option<Iface<'static>>,
) -> Result<LogEvent<'static>> {
    let columns = ctx.layout.columns();
    let from = columns.iter().position(|&c| c == first).unwrap_or(0);
    let mut dir = None;
    let mut declared = None;
    let mut bytes = [0u8; FD_MAX_LEN];
    let mut count = 0;
    for &column in columns.get(from..).unwrap_or_default() {
        let next = tokens.peek();
        let field = next.map_or(&[][..], |(_, f)| f);
        match column {
            Column::Bus => iface = bus(tokens)?,
            Column::Direction => dir = direction(tokens)?,
            // Empty in 2.0: the next field is then the direction.
            Column::Id if direction_of(field).flatten().is_none() && next.is_some() => {
                let _ = tokens.next_token();
            }
            Column::Reserved if field == b"-" => {
                let _ = tokens.next_token();
            }
            // A length is written without a leading zero; the first data
            // byte (the error type) always has one.
            Column::Dlc | Column::Length
                if next.is_some() && (field.len() == 1 || field.first() != Some(&b'0')) =>
            {
                declared = Some(length(tokens, Kind::Error, false)?);
            }
            Column::Data => count = data(tokens, &mut bytes)?,
            _ => {}
        }
    }
    end(tokens)?;
    if let Some(declared) = declared.filter(|&d| usize::from(d) != count) {
        return Err(syntax(
            LogFormat::Trc,
            tokens.end_column(),
            SyntaxError::LengthMismatch {
                declared: usize::from(declared),
                found: count,
            },
        ));
    }
    let [kind, direction_byte, position, rx_errors, tx_errors, ..] = bytes;
    if count != 5 {
        return Err(syntax(
            LogFormat::Trc,
            tokens.end_column(),
            SyntaxError::TrcErrorFrame {
                expected: 5,
                found: count,
            },
        ));
    }
    Ok(LogEvent::Frame(LogFrame {
        frame: error_frame(kind, direction_byte != 0, position, rx_errors, tx_errors),
        timestamp: ts,
        iface,
        direction: dir,
    }))
}

/// A 1.x row: number `)`, offset, [bus (1.2, 1.3)], [type (1.1+)],
/// identifier, [reserved (1.3)], DLC, data or `RTR`.
fn parse_v1(line: &[u8], ctx: &Context) -> Result<LogEvent<'static>> {
    let version = ctx.version;
    let mut tokens = Tokens::new(LogFormat::Trc, line);
    number(&mut tokens, true)?;
    let ts = Some(offset(&mut tokens, ctx)?);
    let iface = if version.has_bus_column() {
        bus(&mut tokens)?
    } else {
        None
    };
    let mut dir = None;
    let mut kind = Kind::Frame(FrameType::Data);
    if version != TrcVersion::V1_0 {
        let (start, field) = tokens.expect(|found| SyntaxError::TrcRowType { found })?;
        match field {
            b"Rx" => dir = Some(Direction::Rx),
            b"Tx" => dir = Some(Direction::Tx),
            b"Warng" => kind = Kind::Status,
            b"Error" => kind = Kind::Error,
            _ => {
                return Err(bad_field(LogFormat::Trc, start, field, 0, |found| {
                    SyntaxError::TrcRowType { found }
                }))
            }
        }
    }
    if kind == Kind::Status || tokens.peek().map(|(_, f)| f) == Some(WARNING_ID) {
        return Ok(LogEvent::Status(BusStatus {
            timestamp: ts,
            iface,
        }));
    }
    let id_at = tokens.peek().map_or(0, |(start, _)| start);
    let (error_type, id) = if kind == Kind::Error {
        let (start, field) = tokens.expect(|found| SyntaxError::TrcIdentifier { found })?;
        let raw = hex(field)
            .and_then(|v| u8::try_from(v).ok())
            .ok_or_else(|| {
                bad_field(LogFormat::Trc, start, field, 0, |found| {
                    SyntaxError::TrcIdentifier { found }
                })
            })?;
        (raw, CanId::masked(0, false))
    } else {
        (0, identifier(&mut tokens)?)
    };
    if version == TrcVersion::V1_3 {
        tokens.expect(|found| SyntaxError::TrcLength { found })?;
    }
    let len = length(&mut tokens, Kind::Frame(FrameType::Data), true)?;
    let next = tokens.peek().map(|(_, f)| f);
    if next == Some(b"RTR") && kind != Kind::Error {
        let _ = tokens.next_token();
        end(&mut tokens)?;
        let frame = CanFrame::new_remote(id, len).map_err(|_| bad_len(id_at))?;
        return Ok(LogEvent::Frame(LogFrame {
            frame,
            timestamp: ts,
            iface,
            direction: dir,
        }));
    }
    // Version 1.0 marks an error frame with `ERROR` before its data (its
    // identifier column holds the error type); later versions may too.
    let mut error_type = error_type;
    if next == Some(b"ERROR") {
        let _ = tokens.next_token();
        if kind != Kind::Error {
            error_type = u8::try_from(id.raw()).unwrap_or(0);
        }
        kind = Kind::Error;
    }
    let mut bytes = [0u8; FD_MAX_LEN];
    let count = data(&mut tokens, &mut bytes[..CLASSIC_MAX_LEN])?;
    if count != usize::from(len) {
        return Err(syntax(
            LogFormat::Trc,
            tokens.end_column(),
            SyntaxError::LengthMismatch {
                declared: usize::from(len),
                found: count,
            },
        ));
    }
    let frame = if kind == Kind::Error {
        let [direction_byte, position, rx_errors, tx_errors, ..] = bytes;
        if count != 4 {
            return Err(syntax(
                LogFormat::Trc,
                tokens.end_column(),
                SyntaxError::TrcErrorFrame {
                    expected: 4,
                    found: count,
                },
            ));
        }
        error_frame(
            error_type,
            direction_byte != 0,
            position,
            rx_errors,
            tx_errors,
        )
    } else {
        frame(id, FrameType::Data, &bytes, len).map_err(|_| bad_len(id_at))?
    };
    Ok(LogEvent::Frame(LogFrame {
        frame,
        timestamp: ts,
        iface,
        direction: dir,
    }))
}

/// A length the frame cannot have (not reached: lengths are checked when
/// read).
fn bad_len(at: usize) -> FormatError {
    syntax(
        LogFormat::Trc,
        at + 1,
        SyntaxError::TrcLength {
            found: Found::EndOfLine,
        },
    )
}
