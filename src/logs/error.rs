//! The errors of the log readers' layer (docs/formats.md,
//! docs/formats.md#reported): which format a log is in ([`LogFormat`]), a
//! line or record that its format's rules reject ([`FormatError`]: why a
//! line of a text log is malformed, [`SyntaxError`], what it [`Found`]; why
//! a binary log cannot be read further, [`BinaryError`]). The crate's
//! umbrella [`Error`](crate::Error) converts from [`FormatError`]; the
//! reading itself fails with a `LogError` that adds where.

/// What the logs layer's functions return: a [`FormatError`] unless said.
pub(crate) type Result<T, E = FormatError> = core::result::Result<T, E>;

/// A line or record that its format's rules reject (docs/formats.md,
/// docs/formats.md#reported): the error of every parser of the logs layer
/// (`candump::parse_line`, `AscParser::parse_line`, `TrcParser::parse_line`,
/// the binary readers), carried by a `LogError`'s
/// `LogErrorKind::Malformed` and `LogErrorKind::Damaged`. Each shows to a
/// person without further context.
///
/// ```
/// use motionwire::logs::{candump, FormatError, Found, LogFormat, SyntaxError};
///
/// let error = candump::parse_line(b"(1.0) can0 0X1#00").unwrap_err();
/// assert_eq!(
///     error,
///     FormatError::Syntax {
///         format: LogFormat::Candump,
///         column: 13,
///         reason: SyntaxError::BadIdentifier { found: Found::Byte(b'X') },
///     }
/// );
/// assert_eq!(
///     error.to_string(),
///     "candump line, column 13: expected a CAN identifier of 3 or 8 hex digits \
///      followed by '#' or white space, found 'X'"
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum FormatError {
    /// A line of a text log does not follow its format (docs/formats.md); the
    /// reason says what was expected at `column` and what was found there,
    /// e.g. `candump line, column 26: expected an identifier at most 0x7FF,
    /// found 0x800`.
    #[error("{format} line, column {column}: {reason}")]
    Syntax {
        /// The log format the line was read as.
        format: LogFormat,
        /// The 1-based byte column in the line where the problem starts.
        column: usize,
        /// What was expected there and what was found.
        reason: SyntaxError,
    },
    /// A binary log (pcap, pcapng, BLF, MF4; docs/formats.md#pcap,
    /// docs/formats.md#blf, docs/formats.md#mf4) is damaged at `offset`
    /// (bytes from the start of the file, or of the decompressed container
    /// for BLF objects), e.g. `pcap file, byte 4120: record of 16 bytes cut
    /// off after 9`.
    #[error("{format} file, byte {offset}: {reason}")]
    Binary {
        /// The log format the file was read as.
        format: LogFormat,
        /// Where the damaged structure starts, in bytes.
        offset: u64,
        /// What is wrong there.
        reason: BinaryError,
    },
}

impl FormatError {
    /// Return the format whose rules the line or record breaks.
    #[must_use]
    pub const fn format(&self) -> LogFormat {
        match *self {
            FormatError::Syntax { format, .. } | FormatError::Binary { format, .. } => format,
        }
    }
}

/// A log format of docs/formats.md, as an error names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum LogFormat {
    /// candump text, log and screen formats (docs/formats.md#candump-log,
    /// docs/formats.md#candump-screen).
    Candump,
    /// Vector ASC text (docs/formats.md#asc).
    Asc,
    /// PEAK TRC text, versions 1.0 to 2.1 (docs/formats.md#trc).
    Trc,
    /// pcap with link type 227, SocketCAN (docs/formats.md#pcap).
    Pcap,
    /// pcapng with SocketCAN interfaces (docs/formats.md#pcap).
    Pcapng,
    /// Vector BLF (docs/formats.md#blf).
    Blf,
    /// ASAM MDF 4 bus logging (docs/formats.md#mf4).
    Mf4,
}

impl LogFormat {
    /// Every format, in the order of docs/formats.md.
    pub const ALL: [LogFormat; 7] = [
        LogFormat::Candump,
        LogFormat::Asc,
        LogFormat::Trc,
        LogFormat::Pcap,
        LogFormat::Pcapng,
        LogFormat::Blf,
        LogFormat::Mf4,
    ];

    /// Return the format's name as messages and `--format` write it, e.g.
    /// `candump`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            LogFormat::Candump => "candump",
            LogFormat::Asc => "asc",
            LogFormat::Trc => "trc",
            LogFormat::Pcap => "pcap",
            LogFormat::Pcapng => "pcapng",
            LogFormat::Blf => "blf",
            LogFormat::Mf4 => "mf4",
        }
    }

    /// Return the format [`name`](Self::name) names (`--format`'s value,
    /// the Python package's `format=`), `None` for any other text.
    ///
    /// ```
    /// use motionwire::logs::LogFormat;
    ///
    /// assert_eq!(LogFormat::from_name("pcapng"), Some(LogFormat::Pcapng));
    /// assert_eq!(LogFormat::from_name("PCAP"), None);
    /// assert!(LogFormat::ALL.iter().all(|f| LogFormat::from_name(f.name()) == Some(*f)));
    /// ```
    #[must_use]
    pub fn from_name(name: &str) -> Option<LogFormat> {
        LogFormat::ALL.into_iter().find(|f| f.name() == name)
    }
}

impl core::fmt::Display for LogFormat {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// What a malformed line held where something else was expected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Found {
    /// This byte.
    Byte(u8),
    /// The line ended.
    EndOfLine,
}

impl core::fmt::Display for Found {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Found::Byte(b' ') => f.write_str("a space"),
            Found::Byte(b'\t') => f.write_str("a tab"),
            Found::Byte(b) if b.is_ascii_graphic() => write!(f, "'{}'", char::from(b)),
            Found::Byte(b) => write!(f, "byte {b:#04x}"),
            Found::EndOfLine => f.write_str("the end of the line"),
        }
    }
}

/// Why a binary log cannot be read further (docs/formats.md#reported,
/// docs/output.md#stderr): carried by [`FormatError::Binary`] with the
/// format and the byte offset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum BinaryError {
    /// The file does not start with the format's magic number.
    BadMagic {
        /// The first four bytes, read little-endian.
        found: u32,
    },
    /// A version of the file format this reader does not know.
    UnsupportedVersion {
        /// The major version.
        major: u16,
        /// The minor version.
        minor: u16,
    },
    /// The file ends inside a header, block or record.
    Truncated {
        /// The bytes the structure needs.
        needed: u64,
        /// The bytes that were there.
        found: u64,
    },
    /// A length field is inconsistent with the structure that holds it
    /// (shorter than its own header, not a multiple of 4 where the format
    /// requires it, or different from its trailing copy).
    BadLength {
        /// The length as read.
        length: u64,
    },
    /// A length field claims more than a reader will hold in memory; the
    /// file is damaged or hostile.
    TooLarge {
        /// The length as read.
        length: u64,
        /// The most the reader accepts.
        limit: u64,
    },
    /// A compressed container does not inflate (damaged deflate stream, or
    /// more or fewer bytes than its header says).
    Decompression,
    /// A compression method other than those the format defines.
    UnsupportedCompression {
        /// The method as read.
        method: u32,
    },
    /// A pcapng packet names an interface that its section has not
    /// described (docs/formats.md#pcap).
    UnknownInterface {
        /// The interface id the packet names.
        id: u32,
        /// The number of interfaces the section has described.
        count: u32,
    },
    /// A SocketCAN packet (link type 227) is shorter than its 8-byte header
    /// and the data length it declares, or a Linux cooked packet (link type
    /// 113 or 276) than its own header (docs/formats.md#pcap).
    SocketCanTooShort {
        /// The bytes the header and the declared data need.
        needed: u64,
        /// The bytes the packet holds.
        found: u64,
    },
    /// An Ethernet packet (link type 1) is shorter than a header it
    /// announces: Ethernet, an 802.1Q tag, IPv4 or UDP
    /// (docs/ethercat.md#reading). The packet is skipped, the capture read
    /// on.
    EthernetTooShort(crate::LenError),
    /// A SocketCAN packet declares more data than its frame kind carries:
    /// 8 bytes for a classic or error frame, 64 for CAN FD
    /// (docs/formats.md#pcap).
    CanDataTooLong {
        /// The data length as read.
        len: u8,
        /// The most the frame kind carries.
        max: u8,
    },
    /// A packet's time, with its interface's offset, lies before the Unix
    /// epoch or beyond what a timestamp holds (docs/formats.md#timestamps).
    TimestampOutOfRange,
    /// A frame's identifier is out of range for its kind (above 0x7FF for
    /// a standard frame); the record is skipped, the file read on.
    BadIdentifier {
        /// The identifier as stored.
        raw: u32,
    },
    /// An MF4 link leads to a block of another kind than the one its place
    /// calls for, or to no block at all (docs/formats.md#mf4).
    UnexpectedBlock {
        /// The block kinds the link may lead to, e.g. `##DG`.
        expected: &'static str,
        /// The first four bytes found there.
        found: [u8; 4],
    },
    /// An MF4 link points outside the file (docs/formats.md#mf4).
    LinkOutOfFile {
        /// The link as read.
        link: u64,
        /// The file's length.
        len: u64,
    },
    /// A chain of MF4 blocks (data groups, channel groups, channels, data
    /// lists and the data blocks they name) leads back to a block it has
    /// passed, or is longer than the file could hold (docs/formats.md#mf4).
    LinkLoop,
    /// An MF4 record starts with a record id that no channel group of its
    /// data group has (docs/formats.md#mf4): the rest of the data group cannot
    /// be split into records.
    UnknownRecordId {
        /// The record id as read.
        id: u64,
    },
    /// An MF4 frame's variable-length data (VLSD) is not where its record
    /// says (docs/formats.md#mf4).
    MissingVlsd {
        /// The offset the record holds.
        offset: u64,
    },
}

impl core::fmt::Display for BinaryError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            BinaryError::BadMagic { found } => {
                write!(f, "expected the format's magic number, found {found:#010x}")
            }
            BinaryError::UnsupportedVersion { major, minor } => {
                write!(f, "version {major}.{minor} of the format is not supported")
            }
            BinaryError::Truncated { needed, found } => write!(
                f,
                "the file ends inside a structure of {needed} bytes, after {found}"
            ),
            BinaryError::BadLength { length } => {
                write!(f, "length field {length} does not fit its structure")
            }
            BinaryError::TooLarge { length, limit } => write!(
                f,
                "length field {length} is above the {limit} bytes a reader accepts"
            ),
            BinaryError::Decompression => f.write_str("compressed data does not inflate"),
            BinaryError::UnsupportedCompression { method } => {
                write!(f, "compression method {method} is not supported")
            }
            BinaryError::UnknownInterface { id, count } => {
                write!(f, "expected an interface id below {count}, found {id}")
            }
            BinaryError::SocketCanTooShort { needed, found } => write!(
                f,
                "expected a SocketCAN packet of at least {needed} bytes, found {found}"
            ),
            BinaryError::EthernetTooShort(error) => error.fmt(f),
            BinaryError::CanDataTooLong { len, max } => write!(
                f,
                "expected a CAN data length of at most {max}, found {len}"
            ),
            BinaryError::TimestampOutOfRange => f.write_str(
                "expected a time between the Unix epoch and 2^64 s after it, found one outside",
            ),
            BinaryError::BadIdentifier { raw } => write!(
                f,
                "expected a standard identifier at most 0x7FF, found {raw:#x}"
            ),
            BinaryError::UnexpectedBlock { expected, found } => {
                write!(f, "expected an MDF block {expected}, found ")?;
                if found.iter().all(u8::is_ascii_graphic) {
                    f.write_str("'")?;
                    for b in found {
                        core::fmt::Write::write_char(f, char::from(b))?;
                    }
                    f.write_str("'")
                } else {
                    write!(f, "{:#010x}", u32::from_le_bytes(found))
                }
            }
            BinaryError::LinkOutOfFile { link, len } => write!(
                f,
                "expected a link inside the file of {len} bytes, found {link}"
            ),
            BinaryError::LinkLoop => {
                f.write_str("expected a chain of blocks that ends, found one that loops")
            }
            BinaryError::UnknownRecordId { id } => write!(
                f,
                "expected the record id of a channel group of the data group, found {id}"
            ),
            BinaryError::MissingVlsd { offset } => write!(
                f,
                "expected the frame's variable-length data at offset {offset}, found none"
            ),
        }
    }
}

/// Why a line of a text log is malformed (docs/formats.md#reported): carried
/// by [`FormatError::Syntax`] with the format and the column where the
/// problem starts. Each reason's message says what was expected and what was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SyntaxError {
    /// `(` opened a timestamp that is not `(seconds.fraction)` with 1 to 20
    /// digits of seconds (fitting a `u64`) and 1 to 9 of fraction, or
    /// `candump -t A`'s date and time.
    BadTimestamp {
        /// What stood where a digit, `.` or `)` was expected.
        found: Found,
    },
    /// Two fields are not separated by white space.
    MissingWhiteSpace {
        /// What stood where white space was expected.
        found: Found,
    },
    /// The line has a frame but no interface name before it.
    MissingInterface,
    /// The interface name holds a byte that is not printable ASCII.
    BadInterface {
        /// The byte.
        found: Found,
    },
    /// No CAN identifier followed by `#` (log format) or white space
    /// (screen format) where one was expected.
    BadIdentifier {
        /// What stood there.
        found: Found,
    },
    /// The identifier has neither 3 nor 8 hex digits.
    IdentifierDigits {
        /// The number of hex digits it has.
        digits: usize,
    },
    /// The identifier is above the largest of its kind (0x7FF for 3
    /// digits, 0x1FFFFFFF for 8).
    IdentifierOutOfRange {
        /// The identifier as read.
        id: u32,
        /// The largest allowed.
        max: u32,
    },
    /// `R` (remote request) is followed by something other than one length
    /// digit 0 to 8.
    BadRemoteLength {
        /// What stood there.
        found: Found,
    },
    /// `##` (CAN FD) is not followed by a flags hex digit.
    BadFdFlags {
        /// What stood there.
        found: Found,
    },
    /// A data byte holds something other than a hex digit.
    BadHexDigit {
        /// What stood there.
        found: Found,
    },
    /// The log-format data has an odd number of hex digits.
    OddHexDigits {
        /// The number of hex digits.
        digits: usize,
    },
    /// The log-format data is longer than its frame allows (8 bytes,
    /// 64 for CAN FD).
    DataTooLong {
        /// The number of hex digits.
        digits: usize,
        /// The most data bytes the frame allows.
        max_bytes: usize,
    },
    /// The screen format's length is not `[0]`…`[8]` or, for CAN FD,
    /// `[00]`…`[64]`.
    BadLength {
        /// What stood there.
        found: Found,
    },
    /// The screen format's data bytes are not as many as its length says.
    LengthMismatch {
        /// The length in brackets.
        declared: usize,
        /// The number of data bytes on the line.
        found: usize,
    },
    /// The screen format's `RX`/`TX` column is not followed by `- -`,
    /// `B -`, `- E` or `B E` (bit rate switch, error state; only `- -` for a
    /// classic frame), or the column precedes a log-format frame.
    BadFdIndicators {
        /// What stood there.
        found: Found,
    },
    /// An error frame (`CAN_ERR_FLAG` in its identifier,
    /// docs/formats.md#error-frames) written as a remote request or a CAN FD
    /// frame: Linux error frames are classic data frames.
    BadErrorFrame {
        /// What stood where the data was expected.
        found: Found,
    },
    /// Something follows the frame where the line should end (or, in the
    /// log format, where a direction `R`/`T` may stand).
    TrailingGarbage {
        /// What stood there.
        found: Found,
    },
    /// `candump -a`'s ASCII column does not show the data before it (each
    /// byte as itself when printable ASCII, else `.`, between `'` quotes).
    BadAscii {
        /// The character the data calls for.
        expected: u8,
        /// What stood there.
        found: Found,
    },
    /// A screen form that cannot be read back faithfully
    /// (docs/formats.md#candump-screen): `candump -S` (data bytes swapped,
    /// marked with a backquote) or `candump -i` (data bytes in binary).
    UnsupportedOutput {
        /// The candump option that made the line: `b'S'` or `b'i'`.
        option: u8,
    },
    /// A PEAK TRC `;$FILEVERSION=` names no version of docs/formats.md#trc.
    TrcFileVersion {
        /// What stood where the version was expected.
        found: Found,
    },
    /// A PEAK TRC `;$STARTTIME=` is not days since 1899-12-30 as a decimal
    /// number (docs/formats.md#trc), or lies before 1970.
    TrcStartTime {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC `;$COLUMNS=` is not a comma-separated list of distinct
    /// column letters with the time offset, type, identifier and length.
    TrcColumns {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row has no message number (decimal digits, `)` after
    /// them in versions 1.x) where one was expected.
    TrcMessageNumber {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's time offset is not milliseconds as a decimal number
    /// with at most 6 digits after the point.
    TrcTimeOffset {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's type is none the file version defines.
    TrcRowType {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's bus is not a decimal number 0..=65535 or `-`.
    TrcBus {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's direction is not `Rx`, `Tx` or `-`.
    TrcDirection {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's identifier is not 1 to 8 hex digits.
    TrcIdentifier {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's data length code or length is not one its frame
    /// type allows (0 to 8; a DLC 0 to 15 or a length 0 to 64 for CAN FD).
    TrcLength {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC row's data holds something other than bytes of two hex
    /// digits.
    TrcDataByte {
        /// What stood there.
        found: Found,
    },
    /// A PEAK TRC error frame row does not hold the bytes PEAK's error
    /// frames have (1.x: 4, 2.x: 5).
    TrcErrorFrame {
        /// The number of bytes the format's error frame has.
        expected: usize,
        /// The number of bytes the row has.
        found: usize,
    },
    /// Something follows the last column of a PEAK TRC row.
    TrcTrailing {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC line that is no header, comment or event line the format
    /// defines (docs/formats.md#asc).
    AscLine {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC `base` line that is not `base hex|dec [timestamps absolute|relative]`.
    AscBase {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC event time that is not `seconds.fraction` with 1 to 9 fraction digits.
    AscTime {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC channel that is not a number 1 to 65535 (or `CANFD`).
    AscChannel {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC identifier that is not a number in the file's base (with `x` after an extended one) in range, nor `ErrorFrame`.
    AscIdentifier {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC direction that is not `Rx`, `Tx` (or `TxRq`).
    AscDirection {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC frame type that is not `d` (data) or `r` (remote request).
    AscFrameType {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC DLC that is not one hex digit.
    AscDlc {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC data byte that is not a byte in the file's base, or a missing one.
    AscDataByte {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC `CANFD` data length that is no CAN FD length (or does not match the DLC of a CAN FD frame, or exceeds 8 for classic content).
    AscDataLength {
        /// What stood there.
        found: Found,
    },
    /// Something after a Vector ASC classic frame's data that is neither
    /// another byte the DLC allows nor CANoe's statistics (`Length = …
    /// BitCount = … ID = …`; docs/formats.md#asc).
    AscTrailing {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC `CANFD` BRS or ESI column that is not `0` or `1`.
    AscFdColumn {
        /// What stood there.
        found: Found,
    },
    /// A Vector ASC `CANFD` line without its message duration, bit count and hex flags after the data.
    AscFlags {
        /// What stood there.
        found: Found,
    },
}

impl core::fmt::Display for SyntaxError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            SyntaxError::BadTimestamp { found } => write!(
                f,
                "expected a timestamp (seconds.fraction) with 1 to 20 digits before the point \
                 and 1 to 9 after, or a date (YYYY-MM-DD hh:mm:ss.fraction), found {found}"
            ),
            SyntaxError::MissingWhiteSpace { found } => {
                write!(f, "expected white space between fields, found {found}")
            }
            SyntaxError::MissingInterface => f.write_str(
                "expected an interface name before the frame, found the frame at the start",
            ),
            SyntaxError::BadInterface { found } => write!(
                f,
                "expected an interface name of printable ASCII followed by white space, \
                 found {found}"
            ),
            SyntaxError::BadIdentifier { found } => write!(
                f,
                "expected a CAN identifier of 3 or 8 hex digits followed by '#' or white space, \
                 found {found}"
            ),
            SyntaxError::IdentifierDigits { digits } => write!(
                f,
                "expected a CAN identifier of 3 or 8 hex digits, found {digits} digit{}",
                if digits == 1 { "" } else { "s" }
            ),
            SyntaxError::IdentifierOutOfRange { id, max } => {
                write!(f, "expected an identifier at most {max:#X}, found {id:#X}")
            }
            SyntaxError::BadRemoteLength { found } => write!(
                f,
                "expected at most one length digit 0 to 8 after 'R', found {found}"
            ),
            SyntaxError::BadFdFlags { found } => {
                write!(f, "expected a CAN FD flags hex digit after '##', found {found}")
            }
            SyntaxError::BadHexDigit { found } => {
                write!(f, "expected a hex digit, found {found}")
            }
            SyntaxError::OddHexDigits { digits } => write!(
                f,
                "expected an even number of hex digits in the data, found {digits}"
            ),
            SyntaxError::DataTooLong { digits, max_bytes } => write!(
                f,
                "expected at most {max_bytes} data bytes ({} hex digits), found {digits} hex digits",
                2 * max_bytes
            ),
            SyntaxError::BadLength { found } => write!(
                f,
                "expected a data length [0] to [8], or [00] to [64] for CAN FD, found {found}"
            ),
            SyntaxError::LengthMismatch { declared, found } => write!(
                f,
                "expected {declared} data bytes as the length says, found {found}"
            ),
            SyntaxError::BadFdIndicators { found } => write!(
                f,
                "expected '- -', 'B -', '- E' or 'B E' after RX/TX ('- -' for a classic frame) \
                 before a screen-format frame, found {found}"
            ),
            SyntaxError::BadErrorFrame { found } => write!(
                f,
                "expected the data of an error frame (classic hex data), found {found}"
            ),
            SyntaxError::TrailingGarbage { found } => write!(
                f,
                "expected the end of the line (or a direction R/T in the log format), \
                 found {found}"
            ),
            SyntaxError::BadAscii { expected, found } => write!(
                f,
                "expected the ASCII column to show the data, {}, found {found}",
                Found::Byte(expected)
            ),
            SyntaxError::UnsupportedOutput { option } => write!(
                f,
                "expected candump output that can be read back, found candump -{} output ({})",
                char::from(option),
                if option == b'S' {
                    "data bytes swapped"
                } else {
                    "data bytes in binary"
                }
            ),
            SyntaxError::TrcFileVersion { found } => write!(
                f,
                "expected a TRC file version 1.0, 1.1, 1.2, 1.3, 2.0 or 2.1, found {found}"
            ),
            SyntaxError::TrcStartTime { found } => write!(
                f,
                "expected a start time in days since 1899-12-30 (digits, optionally a point \
                 and more digits), not before 1970, found {found}"
            ),
            SyntaxError::TrcColumns { found } => write!(
                f,
                "expected distinct TRC column letters N, O, T, B, I, d, R, L, l, D separated by \
                 commas, with O, T, I and L or l, D last, found {found}"
            ),
            SyntaxError::TrcMessageNumber { found } => write!(
                f,
                "expected a message number (decimal digits, ')' after them in TRC 1.x), \
                 found {found}"
            ),
            SyntaxError::TrcTimeOffset { found } => write!(
                f,
                "expected a time offset in milliseconds with at most 6 digits after the point, \
                 found {found}"
            ),
            SyntaxError::TrcRowType { found } => write!(
                f,
                "expected a TRC row type (DT, FD, FB, FE, BI, RR, ER, ST, EC, EV; Rx, Tx, \
                 Warng, Error in 1.x), found {found}"
            ),
            SyntaxError::TrcBus { found } => {
                write!(f, "expected a bus number 0 to 65535 or '-', found {found}")
            }
            SyntaxError::TrcDirection { found } => {
                write!(f, "expected a direction Rx, Tx or '-', found {found}")
            }
            SyntaxError::TrcIdentifier { found } => write!(
                f,
                "expected a CAN identifier of 1 to 8 hex digits (more than 4: extended), \
                 found {found}"
            ),
            SyntaxError::TrcLength { found } => write!(
                f,
                "expected a data length code 0 to 8 (0 to 15 for CAN FD) or a length 0 to 8 \
                 (0 to 64 for CAN FD), found {found}"
            ),
            SyntaxError::TrcDataByte { found } => {
                write!(f, "expected a data byte of two hex digits, found {found}")
            }
            SyntaxError::TrcErrorFrame { expected, found } => write!(
                f,
                "expected the {expected} data bytes of a PEAK error frame, found {found}"
            ),
            SyntaxError::TrcTrailing { found } => {
                write!(f, "expected the end of the row after its data, found {found}")
            }
            SyntaxError::AscLine { found } => {
                write!(f, "expected an ASC header, comment or event line, found {found}")
            }
            SyntaxError::AscBase { found } => {
                write!(f, "expected 'base hex' or 'base dec', optionally followed by 'timestamps absolute' or 'timestamps relative', found {found}")
            }
            SyntaxError::AscTime { found } => {
                write!(f, "expected an event time seconds.fraction with 1 to 9 digits of fraction, found {found}")
            }
            SyntaxError::AscChannel { found } => {
                write!(f, "expected a channel number 1 to 65535, or CANFD, found {found}")
            }
            SyntaxError::AscIdentifier { found } => {
                write!(f, "expected a CAN identifier in the file's base (x after an extended one) or ErrorFrame, found {found}")
            }
            SyntaxError::AscDirection { found } => {
                write!(f, "expected the direction Rx or Tx, found {found}")
            }
            SyntaxError::AscFrameType { found } => {
                write!(f, "expected d (data) or r (remote request), found {found}")
            }
            SyntaxError::AscDlc { found } => {
                write!(f, "expected a DLC of one hex digit, found {found}")
            }
            SyntaxError::AscDataByte { found } => {
                write!(f, "expected a data byte in the file's base, found {found}")
            }
            SyntaxError::AscDataLength { found } => {
                write!(f, "expected a CAN FD data length (0 to 8, 12, 16, 20, 24, 32, 48, 64) that fits the DLC, found {found}")
            }
            SyntaxError::AscTrailing { found } => {
                write!(f, "expected the end of the line or CANoe's statistics ('Length = …') after the frame's data, found {found}")
            }
            SyntaxError::AscFdColumn { found } => {
                write!(f, "expected a BRS or ESI column 0 or 1, found {found}")
            }
            SyntaxError::AscFlags { found } => {
                write!(f, "expected the message duration, bit count and hex flags after the data, found {found}")
            }
        }
    }
}

/// The formats [`crate::logs::read`] knows, in words: what an unrecognised
/// input was expected to be (docs/formats.md#detection).
#[cfg(feature = "std")]
pub(crate) const EXPECTED: &str = "a candump log or screen output, Vector ASC or BLF, PEAK TRC, \
                                   pcap or pcapng, ASAM MDF 4 (gzip-compressed or not)";

/// Why a log reader could not hand on an event, and where
/// (docs/formats.md#reported): what every [`ReadLog`](crate::logs::ReadLog)
/// returns.
///
/// [`is_skipped`](LogError::is_skipped) tells the two kinds apart: a line
/// or record that was reported and skipped, after which the reading goes
/// on, and an error after which the input ends here. `Display` writes the
/// position, then the [`LogErrorKind`]: `line 3: candump line, column 26:
/// expected an identifier at most 0x7FF, found 0x800`.
#[cfg(feature = "std")]
#[derive(Debug)]
pub struct LogError {
    position: Option<crate::logs::Position>,
    kind: LogErrorKind,
}

/// What went wrong while reading a log: the reason of a [`LogError`],
/// written without its position by `Display`.
#[cfg(feature = "std")]
#[derive(Debug)]
#[non_exhaustive]
pub enum LogErrorKind {
    /// A line of a text log that is no line of its format
    /// ([`FormatError::Syntax`]), or a record of a binary log whose content
    /// cannot be read but whose size is known ([`FormatError::Binary`], e.g.
    /// a BLF frame object with a standard identifier above 0x7FF). Only it
    /// is skipped.
    Malformed(FormatError),
    /// A line longer than [`MAX_LINE_LEN`](crate::logs::MAX_LINE_LEN): not a
    /// log line of any format. It is skipped unread, so memory stays
    /// bounded whatever the input.
    OverlongLine,
    /// The structure of a binary log is damaged ([`FormatError::Binary`]):
    /// the records before it were read, the rest of the file cannot be.
    Damaged(FormatError),
    /// Reading the input failed.
    Io(std::io::Error),
    /// The input is none of the formats of docs/formats.md (said once, when it
    /// is opened: not one error per line).
    Unrecognised,
}

#[cfg(feature = "std")]
impl LogError {
    /// Return an error of `kind` at `position`: for readers outside the
    /// crate that implement [`ReadLog`](crate::logs::ReadLog).
    #[must_use]
    pub const fn new(position: Option<crate::logs::Position>, kind: LogErrorKind) -> Self {
        LogError { position, kind }
    }

    /// Return the line or record the error is about, where it has one (an
    /// unrecognised input or a damaged file header has none).
    #[must_use]
    pub const fn position(&self) -> Option<crate::logs::Position> {
        self.position
    }

    /// Return what went wrong.
    #[must_use]
    pub const fn kind(&self) -> &LogErrorKind {
        &self.kind
    }

    /// Return what went wrong, by value (e.g. to keep the I/O error).
    #[must_use]
    pub fn into_kind(self) -> LogErrorKind {
        self.kind
    }

    /// Return whether only this line or record was lost and the reading
    /// goes on (a malformed or over-long line, a damaged record of known
    /// size, each reported with its position and reason:
    /// docs/formats.md#reported), rather than the input ending here.
    #[must_use]
    pub const fn is_skipped(&self) -> bool {
        matches!(
            self.kind,
            LogErrorKind::Malformed(_) | LogErrorKind::OverlongLine
        )
    }

    /// The same error at `position`, unless it has one already.
    pub(crate) fn or_at(mut self, position: crate::logs::Position) -> Self {
        self.position.get_or_insert(position);
        self
    }
}

#[cfg(feature = "std")]
impl From<std::io::Error> for LogError {
    fn from(error: std::io::Error) -> Self {
        LogError::new(None, LogErrorKind::Io(error))
    }
}

#[cfg(feature = "std")]
impl core::fmt::Display for LogErrorKind {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LogErrorKind::Malformed(error) | LogErrorKind::Damaged(error) => error.fmt(f),
            LogErrorKind::OverlongLine => write!(
                f,
                "line longer than {} MiB: not a log line, skipped",
                crate::logs::MAX_LINE_LEN >> 20
            ),
            LogErrorKind::Io(error) => write!(f, "read error: {error}"),
            LogErrorKind::Unrecognised => {
                write!(f, "unrecognised log format: expected {EXPECTED}")
            }
        }
    }
}

#[cfg(feature = "std")]
impl core::fmt::Display for LogError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if let Some(position) = self.position {
            write!(f, "{} {position}: ", position.unit())?;
        }
        self.kind.fmt(f)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for LogError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            LogErrorKind::Malformed(error) | LogErrorKind::Damaged(error) => Some(error),
            LogErrorKind::Io(error) => Some(error),
            LogErrorKind::OverlongLine | LogErrorKind::Unrecognised => None,
        }
    }
}
