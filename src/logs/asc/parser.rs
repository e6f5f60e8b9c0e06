//! The general parser of ASC lines: [`AscParser`].

use crate::can::{
    BusStatus, CanFrame, CanId, Direction, ErrorClasses, FdFlags, FrameType, Iface, LogEvent,
    LogFrame, Timestamp, CLASSIC_MAX_LEN, FD_LENGTHS, FD_MAX_LEN,
};
use crate::logs::error::Result;
use crate::logs::lex::{
    decimal, eq_ignore_case, found, hex, hex_digit, hex_value, starts_with_ignore_case, syntax,
    trim_end, Tokens,
};
use crate::logs::FormatError;
use crate::logs::{LogFormat, SyntaxError};

/// The `CANFD` flags field's bits that matter here (Vector's
/// documentation, as can-utils' `asc2log` names them).
const FLAG_RTR: u32 = 0x0000_0010;
pub(super) const FLAG_FDF: u32 = 0x0000_1000;
pub(super) const FLAG_BRS: u32 = 0x0000_2000;
pub(super) const FLAG_ESI: u32 = 0x0000_4000;

/// How an ASC file writes numbers and times, as its `base` header line
/// says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct AscParser {
    /// Identifiers and data bytes in hex (`base hex`, the default) or
    /// decimal (`base dec`).
    pub(super) hex: bool,
    /// `timestamps relative`: each time is the delta to the previous event.
    pub(super) relative: bool,
    /// The time of the last event, for relative timestamps.
    pub(super) elapsed: Timestamp,
}

impl Default for AscParser {
    fn default() -> Self {
        Self::new()
    }
}

impl AscParser {
    /// A parser for a file whose header has not been read yet: hex
    /// numbers and absolute times, as Vector's tools default to.
    #[must_use]
    pub const fn new() -> Self {
        AscParser {
            hex: true,
            relative: false,
            elapsed: Timestamp::ZERO,
        }
    }

    /// Whether identifiers and data are hex (`base hex`).
    #[must_use]
    pub const fn is_hex(&self) -> bool {
        self.hex
    }

    /// Whether times are relative to the previous event (`timestamps
    /// relative`).
    #[must_use]
    pub const fn is_relative(&self) -> bool {
        self.relative
    }

    /// Read one line (without or with its line end): `Ok(None)` for a line
    /// that holds no frame or bus event (header, comment, blank), the
    /// event, or an error with its column.
    ///
    /// # Errors
    ///
    /// [`FormatError::Syntax`] with [`LogFormat::Asc`], the 1-based column and
    /// what was expected there.
    #[inline]
    pub fn parse_line(&mut self, line: &[u8]) -> Result<Option<LogEvent<'static>>, FormatError> {
        let line = trim_end(line);
        // The common frame lines in one pass; every other line (and every
        // line the fast path declines) is read by the general parser.
        if let Some(event) = self.parse_fast(line) {
            return Ok(Some(event));
        }
        self.parse_general(line)
    }

    /// [`parse_line`](Self::parse_line) for a line the fast path, reading
    /// it in place, has declined: the general parser, out of line.
    #[cfg(feature = "std")]
    #[inline(never)]
    pub(super) fn parse_other(
        &mut self,
        line: &[u8],
    ) -> Result<Option<LogEvent<'static>>, FormatError> {
        self.parse_general(trim_end(line))
    }

    /// [`parse_line`](Self::parse_line) without the fast path, for a line
    /// whose trailing white space is trimmed.
    pub(super) fn parse_general(
        &mut self,
        line: &[u8],
    ) -> Result<Option<LogEvent<'static>>, FormatError> {
        let mut tokens = Tokens::new(LogFormat::Asc, line);
        let Some((start, first)) = tokens.next_token() else {
            return Ok(None);
        };
        if first.first().is_some_and(u8::is_ascii_digit) {
            return self.parse_event(line, start, first, tokens);
        }
        let rest = line.get(start..).unwrap_or_default();
        if rest.starts_with(b"//") {
            return Ok(None);
        }
        if eq_ignore_case(first, b"base") {
            return self.parse_base(tokens).map(|()| None);
        }
        if eq_ignore_case(first, b"date")
            || eq_ignore_case(first, b"internal")
            || starts_with_ignore_case(rest, b"no internal events logged")
            || starts_with_ignore_case(rest, b"begin triggerblock")
            || starts_with_ignore_case(rest, b"end triggerblock")
        {
            if starts_with_ignore_case(rest, b"begin triggerblock") {
                // A new measurement: relative times start again.
                self.elapsed = Timestamp::ZERO;
            }
            return Ok(None);
        }
        Err(syntax(
            LogFormat::Asc,
            start + 1,
            SyntaxError::AscLine {
                found: found(line, start),
            },
        ))
    }

    /// `base hex|dec [timestamps absolute|relative]`.
    fn parse_base(&mut self, mut tokens: Tokens<'_>) -> Result<()> {
        let (at, base) = tokens.expect(|found| SyntaxError::AscBase { found })?;
        self.hex = if eq_ignore_case(base, b"hex") {
            true
        } else if eq_ignore_case(base, b"dec") {
            false
        } else {
            return Err(tokens.error_at(at, |found| SyntaxError::AscBase { found }));
        };
        if let Some((at, word)) = tokens.next_token() {
            if !eq_ignore_case(word, b"timestamps") {
                return Err(tokens.error_at(at, |found| SyntaxError::AscBase { found }));
            }
            let (at, kind) = tokens.expect(|found| SyntaxError::AscBase { found })?;
            self.relative = if eq_ignore_case(kind, b"relative") {
                true
            } else if eq_ignore_case(kind, b"absolute") {
                false
            } else {
                return Err(tokens.error_at(at, |found| SyntaxError::AscBase { found }));
            };
        }
        Ok(())
    }

    /// A line that starts with a time.
    fn parse_event<'l>(
        &mut self,
        line: &'l [u8],
        start: usize,
        time: &'l [u8],
        mut tokens: Tokens<'l>,
    ) -> Result<Option<LogEvent<'static>>, FormatError> {
        let written = parse_time(time).ok_or_else(|| {
            tokens.error_at(start + bad_time_at(time), |found| SyntaxError::AscTime {
                found,
            })
        })?;
        let (at, second) = tokens.expect(|found| SyntaxError::AscChannel { found })?;
        // Every event's time counts, relative times add up over all of them.
        let timestamp = self.time(written);
        let rest = line.get(at..).unwrap_or_default();
        // Events that hold no frame.
        // `TriggerEvent: TriggerBlock[Logging] Start DirectLogging` is
        // CANoe 15's form of `Log trigger event`.
        if starts_with_ignore_case(rest, b"start of measurement")
            || starts_with_ignore_case(rest, b"log trigger event")
            || starts_with_ignore_case(rest, b"triggerevent:")
        {
            return Ok(None);
        }
        if second == b"CANFD" {
            return self.parse_fd(line, timestamp, tokens);
        }
        if second == b"SV:" {
            // A system variable's value: no frame.
            return Ok(None);
        }
        if second == b"CANXL" {
            return Err(tokens.error_at(at, |found| SyntaxError::AscLine { found }));
        }
        if second == b"CAN" {
            // `CAN 1 Status:chip status error active`: a bus event.
            let (at, channel) = tokens.expect(|found| SyntaxError::AscChannel { found })?;
            let channel = channel_number(channel)
                .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscChannel { found }))?;
            return match tokens.next_token() {
                Some((_, word)) if starts_with_ignore_case(word, b"status") => {
                    Ok(Some(LogEvent::Status(BusStatus {
                        timestamp: Some(timestamp),
                        iface: Some(Iface::Channel(channel)),
                    })))
                }
                Some((at, _)) => Err(tokens.error_at(at, |found| SyntaxError::AscLine { found })),
                None => Err(tokens.error_at(line.len(), |found| SyntaxError::AscLine { found })),
            };
        }
        let channel = channel_number(second)
            .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscChannel { found }))?;
        let iface = Iface::Channel(channel);
        let (at, id) = tokens.expect(|found| SyntaxError::AscIdentifier { found })?;
        if starts_with_ignore_case(id, b"errorframe") {
            return Ok(Some(LogEvent::Frame(error_frame(timestamp, iface))));
        }
        if starts_with_ignore_case(id, b"statistic:") || id == b"J1939TP" {
            // Bus statistics, a J1939 transport-protocol summary: no frame.
            return Ok(None);
        }
        if id == b"OverloadFrame" {
            return Ok(Some(LogEvent::Status(BusStatus {
                timestamp: Some(timestamp),
                iface: Some(iface),
            })));
        }
        let id = self
            .parse_id(id)
            .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscIdentifier { found }))?;
        let (at, dir) = tokens.expect(|found| SyntaxError::AscDirection { found })?;
        let direction = match dir {
            b"Rx" => Direction::Rx,
            b"Tx" => Direction::Tx,
            // A transmit request: the frame shows again when it is sent.
            b"TxRq" => return Ok(None),
            _ => return Err(tokens.error_at(at, |found| SyntaxError::AscDirection { found })),
        };
        let (at, kind) = tokens.expect(|found| SyntaxError::AscFrameType { found })?;
        let remote = match kind {
            b"d" | b"D" => false,
            b"r" | b"R" => true,
            _ => return Err(tokens.error_at(at, |found| SyntaxError::AscFrameType { found })),
        };
        let dlc = match tokens.clone().next_token() {
            // CANoe writes its statistics right after `r` when the request
            // has no DLC (`Tx r Length = 1704000 BitCount = 145 ID = …`):
            // a remote request of length 0, as python-can reads it.
            Some((_, next)) if remote && hex_digit(next).is_none() => None,
            Some((at, dlc)) => {
                tokens.next_token();
                Some(
                    hex_digit(dlc).ok_or_else(|| {
                        tokens.error_at(at, |found| SyntaxError::AscDlc { found })
                    })?,
                )
            }
            None if remote => None,
            None => return Err(tokens.error_at(line.len(), |found| SyntaxError::AscDlc { found })),
        };
        let frame = if remote {
            // `r` alone (before v8.5) requests nothing: length 0.
            let dlc = dlc.unwrap_or(0).min(CLASSIC_MAX_LEN as u8);
            CanFrame::new_remote(id, dlc)
        } else {
            self.classic_data(line, id, dlc.unwrap_or(0), &mut tokens)?
        };
        let frame =
            frame.map_err(|_| tokens.error_at(at, |found| SyntaxError::AscDlc { found }))?;
        Ok(Some(LogEvent::Frame(
            LogFrame::new(frame)
                .with_timestamp(timestamp)
                .with_iface(iface)
                .with_direction(direction),
        )))
    }

    /// The data frame of a classic line from its DLC code `dlc` on
    /// (docs/formats.md#asc): as many bytes as the code says (a code above
    /// 8 followed by exactly its CAN FD length of bytes is a CAN FD frame,
    /// followed by 8 a classic frame of 8), then nothing or CANoe's
    /// statistics. A byte missing, or anything else after the data, is an
    /// error: nothing is dropped silently.
    fn classic_data(
        &self,
        line: &[u8],
        id: CanId,
        dlc: u8,
        tokens: &mut Tokens<'_>,
    ) -> core::result::Result<core::result::Result<CanFrame, crate::RangeError>, FormatError> {
        let fd_len = usize::from(FD_LENGTHS[usize::from(dlc & 0xF)]);
        let mut data = [0u8; FD_MAX_LEN];
        let mut len = 0;
        // The bytes present, up to the code's length.
        while len < fd_len {
            let mut ahead = tokens.clone();
            let byte = match ahead.next_token() {
                Some((_, word)) => self.parse_byte(word),
                None => None,
            };
            let Some(byte) = byte else { break };
            data[len] = byte;
            len += 1;
            *tokens = ahead;
        }
        let fd = len == fd_len && fd_len > CLASSIC_MAX_LEN;
        if len < fd_len && !(fd_len > CLASSIC_MAX_LEN && len == CLASSIC_MAX_LEN) {
            // A byte missing where one was due.
            let (at, _) = tokens.clone().next_token().unwrap_or((line.len(), b""));
            return Err(tokens.error_at(at, |found| SyntaxError::AscDataByte { found }));
        }
        if let Some((at, _)) = tokens.clone().next_token() {
            if !is_classic_trailer(line.get(at..).unwrap_or_default()) {
                return Err(tokens.error_at(at, |found| SyntaxError::AscTrailing { found }));
            }
        }
        let bytes = data.get(..len).unwrap_or_default();
        Ok(if fd {
            CanFrame::new_fd(id, FdFlags::EMPTY, bytes)
        } else {
            CanFrame::new(id, bytes)
        })
    }

    /// `CANFD ch dir id [name] brs esi dlc len data… duration bits flags …`.
    fn parse_fd<'l>(
        &self,
        line: &'l [u8],
        timestamp: Timestamp,
        mut tokens: Tokens<'l>,
    ) -> Result<Option<LogEvent<'static>>, FormatError> {
        let (at, channel) = tokens.expect(|found| SyntaxError::AscChannel { found })?;
        let channel = channel_number(channel)
            .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscChannel { found }))?;
        let (at, dir) = tokens.expect(|found| SyntaxError::AscDirection { found })?;
        let direction = match dir {
            b"Rx" => Direction::Rx,
            b"Tx" => Direction::Tx,
            _ => return Err(tokens.error_at(at, |found| SyntaxError::AscDirection { found })),
        };
        let (at, id) = tokens.expect(|found| SyntaxError::AscIdentifier { found })?;
        if starts_with_ignore_case(id, b"errorframe") {
            let frame = error_frame(timestamp, Iface::Channel(channel)).with_direction(direction);
            return Ok(Some(LogEvent::Frame(frame)));
        }
        let id = self
            .parse_id(id)
            .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscIdentifier { found }))?;
        // An optional symbolic name stands before the BRS and ESI columns
        // (each `0` or `1`).
        let bit = |t: Option<(usize, &[u8])>| matches!(t, Some((_, b"0" | b"1")));
        let mut ahead = tokens.clone();
        let (first, second) = (ahead.next_token(), ahead.next_token());
        if !(bit(first) && bit(second)) {
            tokens.next_token();
        }
        // The BRS and ESI columns.
        let mut columns = [false; 2];
        for column in &mut columns {
            let (at, flag) = tokens.expect(|found| SyntaxError::AscFdColumn { found })?;
            *column = match flag {
                b"0" => false,
                b"1" => true,
                _ => return Err(tokens.error_at(at, |found| SyntaxError::AscFdColumn { found })),
            };
        }
        let [brs_column, esi_column] = columns;
        let (at, dlc) = tokens.expect(|found| SyntaxError::AscDlc { found })?;
        let dlc = hex_digit(dlc)
            .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscDlc { found }))?;
        let (len_at, len) = tokens.expect(|found| SyntaxError::AscDataLength { found })?;
        let len = decimal(len, FD_MAX_LEN as u64)
            .filter(|&len| FD_LENGTHS.contains(&(len as u8)))
            .ok_or_else(|| tokens.error_at(len_at, |found| SyntaxError::AscDataLength { found }))?
            as usize;
        let mut data = [0u8; FD_MAX_LEN];
        for slot in data.iter_mut().take(len) {
            let (at, byte) = tokens.expect(|found| SyntaxError::AscDataByte { found })?;
            *slot = self
                .parse_byte(byte)
                .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscDataByte { found }))?;
        }
        // Message duration and bit count, then the flags.
        for _ in 0..2 {
            tokens.expect(|found| SyntaxError::AscFlags { found })?;
        }
        let (at, flags) = tokens.expect(|found| SyntaxError::AscFlags { found })?;
        let flags = hex(flags)
            .ok_or_else(|| tokens.error_at(at, |found| SyntaxError::AscFlags { found }))?;
        let frame = fd_frame(id, dlc, &data, len, flags, brs_column, esi_column)
            .ok_or_else(|| tokens.error_at(len_at, |found| SyntaxError::AscDataLength { found }))?;
        let _ = line;
        Ok(Some(LogEvent::Frame(
            LogFrame::new(frame)
                .with_timestamp(timestamp)
                .with_iface(Iface::Channel(channel))
                .with_direction(direction),
        )))
    }

    /// The event's time since the start: as written, or added up.
    pub(super) fn time(&mut self, written: Timestamp) -> Timestamp {
        if self.relative {
            self.elapsed = self
                .elapsed
                .checked_add(written.as_duration())
                .unwrap_or(self.elapsed);
            self.elapsed
        } else {
            written
        }
    }

    /// An identifier in the file's base, `x` after an extended one.
    fn parse_id(&self, text: &[u8]) -> Option<CanId> {
        let (digits, extended) = match text.split_last() {
            Some((b'x' | b'X', digits)) => (digits, true),
            _ => (text, false),
        };
        let raw = if self.hex {
            hex(digits)?
        } else {
            u32::try_from(decimal(digits, u64::from(u32::MAX))?).ok()?
        };
        if extended {
            CanId::extended(raw)
        } else {
            CanId::standard(raw)
        }
    }

    /// A data byte in the file's base.
    fn parse_byte(&self, text: &[u8]) -> Option<u8> {
        if self.hex {
            match *text {
                [lo] => hex_value(lo),
                [hi, lo] => Some(hex_value(hi)? << 4 | hex_value(lo)?),
                _ => None,
            }
        } else {
            decimal(text, 255).and_then(|v| u8::try_from(v).ok())
        }
    }
}

/// The frame of a `CANFD` line from its fields: `dlc`, the `len` data
/// bytes at the start of `data` (zeros after them), the flags field and
/// the BRS and ESI columns; `None` when the data length does not fit (the
/// line's error is at its data length). The frame is made from the array
/// as it is, without copying the bytes again.
#[inline]
pub(super) fn fd_frame(
    id: CanId,
    dlc: u8,
    data: &[u8; FD_MAX_LEN],
    len: usize,
    flags: u32,
    brs_column: bool,
    esi_column: bool,
) -> Option<CanFrame> {
    // Without EDL/FDF, more than 8 bytes can only be CAN FD (CANoe
    // writes such lines; the decision in docs/formats.md#asc): BRS and ESI
    // then come from their columns, as python-can reads them, and the
    // flags' other bits (0x10 included) are not read.
    let fd_without_edl = flags & FLAG_FDF == 0 && len > CLASSIC_MAX_LEN;
    let frame_type = if flags & FLAG_FDF != 0 || fd_without_edl {
        // FDF itself is what makes the frame CAN FD here; the flags
        // kept are BRS and ESI, as the other readers keep them.
        let (brs, esi) = if fd_without_edl {
            (brs_column, esi_column)
        } else {
            (flags & FLAG_BRS != 0, flags & FLAG_ESI != 0)
        };
        let mut fd = FdFlags::EMPTY;
        if brs {
            fd = fd.union(FdFlags::BRS);
        }
        if esi {
            fd = fd.union(FdFlags::ESI);
        }
        if FD_LENGTHS.get(usize::from(dlc)) != Some(&(len as u8)) {
            return None;
        }
        FrameType::Fd(fd)
    } else if flags & FLAG_RTR != 0 {
        return CanFrame::new_remote(id, dlc.min(CLASSIC_MAX_LEN as u8)).ok();
    } else {
        // Classic content in the CAN FD form: at most 8 bytes (more is
        // CAN FD, above).
        FrameType::Data
    };
    // The length is one CAN FD has (64 at most), or at most 8 for a data
    // frame (more without FDF is `fd_without_edl`): what `CanFrame::new_fd`
    // and `CanFrame::new` accept; `data` holds zeros after it.
    Some(CanFrame::from_array(id, frame_type, *data, len as u8))
}

/// An `ErrorFrame` line's frame: all the line says is that an error
/// happened, so class `bus_error` with 8 zero bytes, as can-utils'
/// `asc2log` writes it.
fn error_frame(timestamp: Timestamp, iface: Iface<'static>) -> LogFrame<'static> {
    // The class bits are an extended identifier and 8 bytes an error
    // frame's data: the parts are valid as they are.
    let id = CanId::masked(ErrorClasses::BUS_ERROR.bits(), true);
    let frame = CanFrame::from_array(id, FrameType::Error, [0; FD_MAX_LEN], CLASSIC_MAX_LEN as u8);
    LogFrame::new(frame)
        .with_timestamp(timestamp)
        .with_iface(iface)
}

// ------------------------------------------------------------ fields

/// A channel number, 1 to 65535.
fn channel_number(field: &[u8]) -> Option<u16> {
    decimal(field, u64::from(u16::MAX))
        .and_then(|n| u16::try_from(n).ok())
        .filter(|&n| n > 0)
}

/// `seconds.fraction` with 1 to 9 digits of fraction, exactly.
fn parse_time(field: &[u8]) -> Option<Timestamp> {
    let point = field.iter().position(|&b| b == b'.')?;
    let (secs, fraction) = (field.get(..point)?, field.get(point + 1..)?);
    if fraction.is_empty() || fraction.len() > 9 {
        return None;
    }
    let secs = decimal(secs, u64::MAX / 2)?;
    let digits = decimal(fraction, 999_999_999)?;
    let nanos = digits * 10u64.pow(9 - fraction.len() as u32);
    Timestamp::from_nanos(secs, u32::try_from(nanos).ok()?)
}

/// Where a bad time goes wrong: the first byte that is not a digit or the
/// one point (or its end).
fn bad_time_at(field: &[u8]) -> usize {
    let mut seen_point = false;
    for (i, &b) in field.iter().enumerate() {
        match b {
            b'0'..=b'9' => {}
            b'.' if !seen_point && i > 0 => seen_point = true,
            _ => return i,
        }
    }
    field.len()
}

/// Whether `rest`, what follows a classic frame's data, is CANoe's
/// statistics: `Length = N BitCount = N ID = N[x]`, any of the three, in
/// any order (docs/formats.md#asc).
pub(super) fn is_classic_trailer(rest: &[u8]) -> bool {
    let mut words = rest
        .split(|&b| b == b' ' || b == b'\t')
        .filter(|word| !word.is_empty());
    let mut any = false;
    while let Some(name) = words.next() {
        if !matches!(name, b"Length" | b"BitCount" | b"ID")
            || words.next() != Some(b"=".as_slice())
            || words.next().is_none()
        {
            return false;
        }
        any = true;
    }
    any
}
