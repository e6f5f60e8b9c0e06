//! The parser's working frame, its conversion into the crate's
//! [`LogFrame`], and the writers of the two text formats
//! (docs/formats.md#candump-log, docs/formats.md#candump-screen).

use core::fmt;

use crate::can::{CanFrame, FrameHeader, FrameType, Iface, LogFrame, CAN_ERR_FLAG};
use crate::can::{CanId, Direction, FdFlags, Timestamp, CLASSIC_MAX_LEN, FD_MAX_LEN};

/// The frame a line is parsed into, field by field; every parser keeps the
/// invariants of [`CanFrame`] (lengths, an extended identifier for an error
/// frame), so the conversion checks nothing.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Parsed<'a> {
    pub(super) timestamp: Option<Timestamp>,
    /// The timestamp is relative (`candump -t d` or `-t z`: fewer than ten
    /// digits of seconds), not Unix time.
    pub(super) relative: bool,
    /// The interface name: printable ASCII without spaces (`scan_iface`, the
    /// fast path's `non_graphic` check).
    pub(super) iface: &'a [u8],
    /// The interface name as one word, its first byte least significant and
    /// zeros above, when it has at most 8 bytes and the fast path read it; 0
    /// otherwise. Names are printable ASCII, so two nonzero keys are equal
    /// exactly when the names are.
    pub(super) iface_key: u64,
    pub(super) id: CanId,
    /// The frame's kind, a remote request with its requested length.
    pub(super) kind: FrameType,
    pub(super) direction: Option<Direction>,
    /// Data length (0 for a remote request).
    pub(super) len: u8,
    /// `data[..len]` is the payload; the rest is zero.
    pub(super) data: [u8; FD_MAX_LEN],
}

impl<'a> Parsed<'a> {
    /// Return the crate's record of the frame (docs/formats.md).
    #[inline(always)]
    pub(super) fn into_log_frame(self) -> LogFrame<'a> {
        // ASCII by construction; the fallback is never taken.
        let iface = core::str::from_utf8(self.iface).unwrap_or_default();
        self.into_log_frame_named(iface)
    }

    /// [`Parsed::into_log_frame`] for a line of a buffer whose earlier lines
    /// named the interfaces `recent` (see [`name_after`]).
    #[inline(always)]
    pub(super) fn into_log_frame_after(self, recent: &mut [(u64, &'a str); 2]) -> LogFrame<'a> {
        let name = name_after(self.iface, self.iface_key, recent);
        self.into_log_frame_named(name)
    }

    #[inline(always)]
    fn into_log_frame_named(self, iface: &'a str) -> LogFrame<'a> {
        LogFrame {
            frame: CanFrame::from_array(self.id, self.kind, self.data, self.len),
            timestamp: self.timestamp,
            iface: Some(Iface::Name(iface)),
            direction: self.direction,
        }
    }
}

/// What the fast path reads from a `candump -l` line besides its data
/// bytes, which it writes where the caller keeps them
/// ([`parse_canonical_log`]): the caller builds the frame from the two (the
/// reader from the bytes in its `Names`), instead of moving the 64 bytes
/// from the parser's result to its own.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Canonical<'a> {
    pub(super) timestamp: Timestamp,
    /// As [`Parsed::iface`].
    pub(super) iface: &'a [u8],
    /// As [`Parsed::iface_key`].
    pub(super) iface_key: u64,
    /// The interface is the one the hint held when the line was read: the
    /// name of the last line this path read ([`IfaceHint`]). Read by the
    /// reader only.
    #[cfg(feature = "std")]
    pub(super) same_iface: bool,
    /// The identifier, kind and data length, made by the kind's own
    /// constructor where the line's shape told the kind.
    pub(super) header: FrameHeader,
    pub(super) direction: Option<Direction>,
}

impl<'a> Canonical<'a> {
    /// The frame as the general parser returns it, with its data `data`.
    #[inline(always)]
    pub(super) fn with_data(self, data: [u8; FD_MAX_LEN]) -> Parsed<'a> {
        Parsed {
            timestamp: Some(self.timestamp),
            relative: false,
            iface: self.iface,
            iface_key: self.iface_key,
            id: self.header.id(),
            kind: self.header.frame_type(),
            direction: self.direction,
            // At most 64: a header's length.
            len: self.header.len() as u8,
            data,
        }
    }
}

/// A frame line without its data bytes, which the parser leaves where its
/// caller keeps them (`lines::next_head`): the reader's line, whose record is
/// built from the bytes where they are.
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy)]
pub(crate) struct Head<'a> {
    pub(super) timestamp: Option<Timestamp>,
    /// As [`Parsed::iface`].
    pub(super) iface: &'a [u8],
    /// The interface is the last line's, and that line was read by the
    /// fast path too (`lines::next_head` forgets the hint on any other
    /// line): the reader's `Names` already holds it as its last name.
    pub(super) same_iface: bool,
    /// As [`Canonical::header`].
    pub(super) header: FrameHeader,
    pub(super) direction: Option<Direction>,
}

#[cfg(feature = "std")]
impl Head<'_> {
    /// The frame with its data `data`, its interface named `iface` (the
    /// reader's copy of the name, which outlives the line).
    #[inline(always)]
    pub(super) fn into_log_frame_with<'n>(
        self,
        data: &[u8; FD_MAX_LEN],
        iface: &'n str,
    ) -> LogFrame<'n> {
        LogFrame {
            frame: CanFrame::from_header(self.header, *data),
            timestamp: self.timestamp,
            iface: Some(Iface::Name(iface)),
            direction: self.direction,
        }
    }
}

#[cfg(feature = "std")]
impl<'a> Canonical<'a> {
    /// The frame line without its data.
    #[inline(always)]
    pub(super) fn head(self) -> Head<'a> {
        Head {
            timestamp: Some(self.timestamp),
            iface: self.iface,
            same_iface: self.same_iface,
            header: self.header,
            direction: self.direction,
        }
    }
}

#[cfg(feature = "std")]
impl<'a> Parsed<'a> {
    /// The frame line without its data, which is written into `data`.
    #[inline(always)]
    pub(super) fn into_head(self, data: &mut [u8; FD_MAX_LEN]) -> Head<'a> {
        *data = self.data;
        Head {
            timestamp: self.timestamp,
            iface: self.iface,
            same_iface: false,
            header: FrameHeader::new(self.id, self.kind, self.len),
            direction: self.direction,
        }
    }
}

/// The interface `iface` (with its key, [`Parsed::iface_key`]) as text, for
/// a line whose earlier lines named the interfaces `recent` (the last
/// line's first, each with its key): a name seen there is not checked again
/// (a log's lines almost always name one or two interfaces, and UTF-8
/// validation costs more than the parse of the name), and this line's name
/// becomes the first.
#[inline(always)]
pub(super) fn name_after<'a>(
    iface: &'a [u8],
    key: u64,
    recent: &mut [(u64, &'a str); 2],
) -> &'a str {
    if key == 0 || key != recent[0].0 {
        if key != 0 && key == recent[1].0 {
            recent.swap(0, 1);
        } else {
            new_name(iface, key, recent);
        }
    }
    recent[0].1
}

/// Put the name `iface` first in `recent` when its key is not there: unless
/// it has no key and is the last name, as text (ASCII by construction; the
/// fallback is never taken).
#[inline(never)]
fn new_name<'a>(iface: &'a [u8], key: u64, recent: &mut [(u64, &'a str); 2]) {
    if key == 0 && iface == recent[0].1.as_bytes() {
        return;
    }
    let name = core::str::from_utf8(iface).unwrap_or_default();
    *recent = [(key, name), recent[0]];
}

/// Write a frame in candump's log format (`candump -l`,
/// docs/formats.md#candump-log), without a line end: `(1700000000.000500) can0
/// 081#1081110000000000 R`, as can-utils writes it (upper-case hex, at least
/// ten digits of seconds; an error frame with `CAN_ERR_FLAG` in its 8-digit
/// identifier). This is the record's `Display`.
///
/// The record is written as it is: without a timestamp or a direction, none
/// is written; a channel number is written as the interface name (`1`); a
/// record without an interface gets none, and such a line does not read
/// back (a candump line needs an interface). An interface name with spaces
/// would not read back either.
///
/// ```
/// use motionwire::can::{CanFrame, CanId, Iface, LogFrame, Timestamp};
/// use motionwire::logs::candump;
///
/// let frame = CanFrame::new(CanId::standard(0x081).unwrap(), &[0x10, 0x81, 0x11, 0, 0, 0, 0, 0])?;
/// let logged = LogFrame::new(frame)
///     .with_timestamp(Timestamp::new(1_700_000_000, 500).unwrap())
///     .with_iface(Iface::Name("can0"));
/// let mut text = String::new();
/// candump::write_log(&logged, &mut text).unwrap();
/// assert_eq!(text, "(1700000000.000500) can0 081#1081110000000000");
/// assert_eq!(candump::parse_line_str(&text)?, Some(logged));
/// # Ok::<(), motionwire::Error>(())
/// ```
pub fn write_log<W: fmt::Write + ?Sized>(frame: &LogFrame<'_>, w: &mut W) -> fmt::Result {
    write!(w, "{frame}")
}

/// Write a frame as candump prints it on screen (`candump can0`, with
/// `-t a` when it has a timestamp and `-x` when it has a direction;
/// docs/formats.md#candump-screen), without a line end: `  can0  081   [8]  10
/// 81 11 00 00 00 00 00`, `  can0  705   [1]  remote request`, and for an error
/// frame the data followed by `ERRORFRAME` (the explanation lines of `candump
/// -e` are not written).
///
/// The screen shows CAN FD flags only as BRS/ESI after a direction
/// (`RX B E`); other flags, and the flags of a frame without direction, are
/// not written (see the module's decisions). Interfaces are written as
/// [`write_log`] writes them.
pub fn write_screen<W: fmt::Write + ?Sized>(frame: &LogFrame<'_>, w: &mut W) -> fmt::Result {
    let can = &frame.frame;
    let mut buf = [0u8; 3 * FD_MAX_LEN];
    w.write_char(' ')?;
    if let Some(ts) = frame.timestamp {
        write!(w, "({ts}) ")?;
    }
    w.write_char(' ')?;
    if let Some(iface) = frame.iface {
        write!(w, "{iface}")?;
    }
    if let Some(direction) = frame.direction {
        let flags = can.fd_flags();
        w.write_str("  ")?;
        w.write_str(direction.name())?;
        w.write_str(if flags.contains(FdFlags::BRS) {
            " B"
        } else {
            " -"
        })?;
        w.write_str(if flags.contains(FdFlags::ESI) {
            " E"
        } else {
            " -"
        })?;
    }
    w.write_str("  ")?;
    match can.frame_type() {
        FrameType::Error => write!(w, "{:08X}", can.id().raw() | CAN_ERR_FLAG)?,
        _ => write!(w, "{}", can.id())?,
    }
    let len = can.data().len();
    match can.frame_type() {
        FrameType::Remote { dlc } => return write!(w, "   [{dlc}]  remote request"),
        FrameType::Data | FrameType::Error => write!(w, "   [{len}] ")?,
        FrameType::Fd(_) => write!(w, "  [{len:02}] ")?,
    }
    let mut n = 0;
    for (triple, &byte) in buf.chunks_exact_mut(3).zip(can.data()) {
        let [hi, lo] = hex_pair(byte);
        triple.copy_from_slice(&[b' ', hi, lo]);
        n += 3;
    }
    w.write_str(ascii_str(buf.get(..n).unwrap_or_default()))?;
    if can.is_error() {
        // can-utils: `ERRORFRAME` right-aligned in 3 · (8 − len) + 13 columns.
        let width = 3 * (CLASSIC_MAX_LEN - len.min(CLASSIC_MAX_LEN)) + 13;
        write!(w, "{:>width$}", "ERRORFRAME")?;
    }
    Ok(())
}

pub(super) const HEX_UPPER: [u8; 16] = *b"0123456789ABCDEF";

#[inline]
pub(super) fn hex_pair(byte: u8) -> [u8; 2] {
    [
        HEX_UPPER[usize::from(byte >> 4)],
        HEX_UPPER[usize::from(byte & 0xF)],
    ]
}

/// View bytes that are ASCII by construction as text.
#[inline]
pub(super) fn ascii_str(bytes: &[u8]) -> &str {
    core::str::from_utf8(bytes).unwrap_or_default()
}
