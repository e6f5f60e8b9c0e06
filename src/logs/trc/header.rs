//! The header keys: `;$FILEVERSION=`, `;$STARTTIME=`, `;$COLUMNS=`
//! (docs/formats.md#trc).

use core::fmt;
use core::time::Duration;

use crate::can::Timestamp;
use crate::logs::error::Result;
use crate::logs::lex::{bad_field, decimal_fraction, syntax, trim_end};
use crate::logs::{Found, LogFormat, SyntaxError};

/// A column of a TRC 2.x row, as a letter of `;$COLUMNS=` names it
/// (PEAK's TRC format description, version 2.0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Column {
    /// `N`: the message number.
    Number,
    /// `O`: the time offset in milliseconds.
    Offset,
    /// `T`: the row type (`DT`, `FD`, …).
    Type,
    /// `B`: the bus (channel).
    Bus,
    /// `I`: the identifier in hex.
    Id,
    /// `d`: the direction, `Rx` or `Tx`.
    Direction,
    /// `R`: reserved (`-`).
    Reserved,
    /// `L`: the data length code, 0..=15.
    Dlc,
    /// `l`: the data length in bytes, 0..=64.
    Length,
    /// `D`: the data bytes, the rest of the row.
    Data,
}

impl Column {
    /// Return the column a `;$COLUMNS=` letter names.
    const fn from_letter(letter: u8) -> Option<Column> {
        Some(match letter {
            b'N' => Column::Number,
            b'O' => Column::Offset,
            b'T' => Column::Type,
            b'B' => Column::Bus,
            b'I' => Column::Id,
            b'd' => Column::Direction,
            b'R' => Column::Reserved,
            b'L' => Column::Dlc,
            b'l' => Column::Length,
            b'D' => Column::Data,
            _ => return None,
        })
    }
}

/// The most columns a layout has: each letter once.
const MAX_COLUMNS: usize = 10;

/// The order of the columns of a TRC 2.x row (`;$COLUMNS=`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) struct Layout {
    columns: [Column; MAX_COLUMNS],
    len: u8,
}

impl Layout {
    /// The layout PEAK's 2.0 example and python-can's 2.0 test file use:
    /// `N,O,T,I,d,l,D`.
    pub(super) const V2_0: Layout = Layout::of(&[
        Column::Number,
        Column::Offset,
        Column::Type,
        Column::Id,
        Column::Direction,
        Column::Length,
        Column::Data,
    ]);
    /// The layout PEAK's tools and python-can's `TRCWriter` write for 2.1:
    /// `N,O,T,B,I,d,R,L,D`.
    pub(super) const V2_1: Layout = Layout::of(&[
        Column::Number,
        Column::Offset,
        Column::Type,
        Column::Bus,
        Column::Id,
        Column::Direction,
        Column::Reserved,
        Column::Dlc,
        Column::Data,
    ]);

    /// Return the layout of `columns` (at most ten).
    const fn of(columns: &[Column]) -> Layout {
        let mut all = [Column::Number; MAX_COLUMNS];
        let mut i = 0;
        while i < columns.len() && i < MAX_COLUMNS {
            all[i] = columns[i];
            i += 1;
        }
        Layout {
            columns: all,
            len: i as u8,
        }
    }

    /// Return the columns in order.
    pub(super) fn columns(&self) -> &[Column] {
        self.columns
            .get(..usize::from(self.len))
            .unwrap_or_default()
    }

    /// Return whether the layout has `column`.
    pub(super) fn has(&self, column: Column) -> bool {
        self.columns().contains(&column)
    }
}

/// What a header line sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum HeaderKey {
    /// `;$FILEVERSION=`.
    Version(TrcVersion),
    /// `;$STARTTIME=`.
    StartTime(Timestamp),
    /// `;$COLUMNS=`.
    Columns(Layout),
}

/// Read the `;`-line `line` (`at` is the index of its `;`): a header key, or
/// `None` for a comment.
pub(super) fn parse_header(line: &[u8], at: usize) -> Result<Option<HeaderKey>> {
    let line = trim_end(line);
    let text = line.get(at + 1..).unwrap_or_default();
    let keys: [(&[u8], Parser); 3] = [
        (b"$FILEVERSION=", version),
        (b"$STARTTIME=", start_time),
        (b"$COLUMNS=", columns),
    ];
    for (key, parse) in keys {
        if let Some(value) = text.strip_prefix(key) {
            return parse(value, at + 1 + key.len()).map(Some);
        }
    }
    Ok(None)
}

/// A header value's parser: the value and its 0-based start in the line.
type Parser = fn(&[u8], usize) -> Result<HeaderKey>;

/// `1.0` … `2.1`, with white space around it.
fn version(value: &[u8], start: usize) -> Result<HeaderKey> {
    let skip = value
        .iter()
        .position(|&b| b != b' ' && b != b'\t')
        .unwrap_or(value.len());
    let text = value.get(skip..).unwrap_or_default();
    TrcVersion::ALL
        .into_iter()
        .find(|v| v.text().as_bytes() == text)
        .map(HeaderKey::Version)
        .ok_or_else(|| {
            let found = text.first().map_or(Found::EndOfLine, |&b| Found::Byte(b));
            syntax(
                LogFormat::Trc,
                start + skip + 1,
                SyntaxError::TrcFileVersion { found },
            )
        })
}

/// Days between 1899-12-30 (PEAK's day 0, as in OLE automation dates) and
/// 1970-01-01.
pub(super) const UNIX_EPOCH_DAY: u64 = 25_569;
/// Microseconds in a day.
const DAY_MICROS: u128 = 86_400_000_000;
/// The fraction digits of the start time that are read; further digits
/// change the time by less than 10^-10 µs and are dropped.
const START_FRACTION_DIGITS: u32 = 24;

/// Days since 1899-12-30 as decimal text, read exactly and rounded to the
/// nearest microsecond (half to even), as python-can's `timedelta` does.
fn start_time(value: &[u8], start: usize) -> Result<HeaderKey> {
    let skip = value
        .iter()
        .position(|&b| b != b' ' && b != b'\t')
        .unwrap_or(value.len());
    let text = value.get(skip..).unwrap_or_default();
    let at = start + skip;
    let bad = |i: usize| {
        bad_field(LogFormat::Trc, at, text, i, |found| {
            SyntaxError::TrcStartTime { found }
        })
    };
    let (days, fraction) = decimal_fraction(text, 7, START_FRACTION_DIGITS, false).map_err(bad)?;
    let Some(unix_days) = days.checked_sub(UNIX_EPOCH_DAY) else {
        return Err(bad(0));
    };
    let scale = 10u128.pow(START_FRACTION_DIGITS);
    let numerator = fraction * DAY_MICROS;
    let (mut micros, rest) = (numerator / scale, numerator % scale);
    if 2 * rest > scale || (2 * rest == scale && micros % 2 == 1) {
        micros += 1;
    }
    // Both parts are far below u64::MAX for 7 digits of days.
    let total = u128::from(unix_days) * DAY_MICROS + micros;
    let total = u64::try_from(total).map_err(|_| bad(0))?;
    Ok(HeaderKey::StartTime(Timestamp::from_duration(
        Duration::from_micros(total),
    )))
}

/// `N,O,T,B,I,d,R,L,D`: distinct letters; O, T, I and L or l present; D,
/// when present, last (it takes the rest of the row).
fn columns(value: &[u8], start: usize) -> Result<HeaderKey> {
    let bad = |i: usize| {
        bad_field(LogFormat::Trc, start, value, i, |found| {
            SyntaxError::TrcColumns { found }
        })
    };
    let mut layout = Layout {
        columns: [Column::Number; MAX_COLUMNS],
        len: 0,
    };
    let mut i = 0;
    loop {
        let Some(column) = value.get(i).copied().and_then(Column::from_letter) else {
            return Err(bad(i));
        };
        if layout.has(column) || layout.has(Column::Data) {
            return Err(bad(i));
        }
        if let Some(slot) = layout.columns.get_mut(usize::from(layout.len)) {
            *slot = column;
            layout.len += 1;
        }
        match value.get(i + 1) {
            None => break,
            Some(b',') => i += 2,
            Some(_) => return Err(bad(i + 1)),
        }
    }
    let complete = [Column::Offset, Column::Type, Column::Id]
        .into_iter()
        .all(|c| layout.has(c))
        && (layout.has(Column::Dlc) || layout.has(Column::Length));
    if !complete {
        return Err(bad(value.len()));
    }
    Ok(HeaderKey::Columns(layout))
}

/// A version of the TRC format, as `;$FILEVERSION=` names it
/// (docs/formats.md#trc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum TrcVersion {
    /// 1.0 (PCAN-View 1, PCAN-Trace; the version of a file without
    /// `;$FILEVERSION=`): number, offset, identifier, DLC, data.
    #[default]
    V1_0,
    /// 1.1 (PCAN-View 3, PCAN-Explorer 4): adds the type column.
    V1_1,
    /// 1.2: adds the bus column.
    V1_2,
    /// 1.3: adds the reserved column.
    V1_3,
    /// 2.0 (PCAN-View 4, PCAN-Explorer 6): CAN FD; columns as `;$COLUMNS=`
    /// orders them.
    V2_0,
    /// 2.1: as 2.0, with bus and reserved columns.
    V2_1,
}

impl TrcVersion {
    /// Every version, oldest first.
    pub const ALL: [TrcVersion; 6] = [
        TrcVersion::V1_0,
        TrcVersion::V1_1,
        TrcVersion::V1_2,
        TrcVersion::V1_3,
        TrcVersion::V2_0,
        TrcVersion::V2_1,
    ];

    /// Return the version as `;$FILEVERSION=` writes it, e.g. `2.1`.
    #[must_use]
    pub const fn text(self) -> &'static str {
        match self {
            TrcVersion::V1_0 => "1.0",
            TrcVersion::V1_1 => "1.1",
            TrcVersion::V1_2 => "1.2",
            TrcVersion::V1_3 => "1.3",
            TrcVersion::V2_0 => "2.0",
            TrcVersion::V2_1 => "2.1",
        }
    }

    /// Return whether the rows' columns are those of `;$COLUMNS=` (2.x).
    #[must_use]
    pub const fn has_columns_header(self) -> bool {
        matches!(self, TrcVersion::V2_0 | TrcVersion::V2_1)
    }

    /// Return whether a 1.x row has the bus column (1.2, 1.3).
    pub(super) const fn has_bus_column(self) -> bool {
        matches!(self, TrcVersion::V1_2 | TrcVersion::V1_3)
    }

    /// The columns of a 2.x file without `;$COLUMNS=`.
    pub(super) const fn default_layout(self) -> Layout {
        match self {
            TrcVersion::V2_0 => Layout::V2_0,
            _ => Layout::V2_1,
        }
    }
}

impl fmt::Display for TrcVersion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.text())
    }
}
