//! Strategies for the candump types (docs/formats.md).

use proptest::prelude::*;

use core::fmt;

use crate::can::{CanFrame, CanId, Direction, FdFlags, Iface, LogFrame, Timestamp};
use crate::logs::candump;

/// Any timestamp.
pub(crate) fn timestamp() -> impl Strategy<Value = Timestamp> {
    prop_oneof![
        // Dates as candump -l writes them, and delta times.
        (1_600_000_000u64..1_900_000_000, 0u32..1_000_000),
        (0u64..1000, 0u32..1_000_000),
        // Anything a u64 holds.
        (any::<u64>(), 0u32..1_000_000),
    ]
    .prop_map(|(secs, micros)| Timestamp::new(secs, micros).expect("micros below 10^6"))
}

/// Any interface name both text formats carry: printable ASCII without
/// spaces, not starting with `(` or `#`, 1 to 20 bytes.
pub(crate) fn iface() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("can0".to_string()),
        "v?can[0-9]{1,2}",
        "[!-\"$-')-~][!-~]{0,19}",
    ]
}

/// Any standard or extended identifier.
pub(crate) fn can_id() -> impl Strategy<Value = CanId> {
    prop_oneof![
        (0..=CanId::STANDARD_MAX).prop_map(|raw| CanId::standard(raw).expect("11-bit")),
        (0..=CanId::EXTENDED_MAX).prop_map(|raw| CanId::extended(raw).expect("29-bit")),
    ]
}

/// Any direction.
pub(crate) fn direction() -> impl Strategy<Value = Direction> {
    prop_oneof![Just(Direction::Rx), Just(Direction::Tx)]
}

/// The payload of a frame.
#[derive(Debug, Clone)]
pub(crate) enum Payload {
    /// A classic data frame, 0..=8 bytes.
    Data(Vec<u8>),
    /// A remote request with its length, 0..=8.
    Remote(u8),
    /// A CAN FD frame, flags and 0..=64 bytes.
    Fd(FdFlags, Vec<u8>),
    /// An error frame: its classes (29 bits) and 0..=8 bytes.
    Error(u32, Vec<u8>),
}

/// An owned description of a frame; [`FrameSpec::frame`] borrows the
/// interface name from it.
#[derive(Debug, Clone)]
pub(crate) struct FrameSpec {
    pub(crate) timestamp: Option<Timestamp>,
    pub(crate) iface: String,
    pub(crate) id: CanId,
    pub(crate) payload: Payload,
    pub(crate) direction: Option<Direction>,
}

impl FrameSpec {
    /// The frame this describes.
    pub(crate) fn frame(&self) -> LogFrame<'_> {
        let mut frame = match &self.payload {
            Payload::Data(data) => Build::new_data(&self.iface, self.id, data),
            Payload::Remote(dlc) => Build::new_remote(&self.iface, self.id, *dlc),
            Payload::Fd(flags, data) => Build::new_fd(&self.iface, self.id, *flags, data),
            Payload::Error(classes, data) => Build::new_error(&self.iface, *classes, data),
        }
        .expect("the strategy makes valid frames");
        if let Some(ts) = self.timestamp {
            frame = frame.with_timestamp(ts);
        }
        if let Some(direction) = self.direction {
            frame = frame.with_direction(direction);
        }
        frame
    }
}

fn payload(fd_flags: BoxedStrategy<FdFlags>) -> impl Strategy<Value = Payload> {
    prop_oneof![
        4 => proptest::collection::vec(any::<u8>(), 0..=8).prop_map(Payload::Data),
        1 => (0u8..=8).prop_map(Payload::Remote),
        2 => (fd_flags, proptest::collection::vec(any::<u8>(), 0..=64))
            .prop_map(|(flags, data)| Payload::Fd(flags, data)),
        1 => (0..=CanId::EXTENDED_MAX, proptest::collection::vec(any::<u8>(), 0..=8))
            .prop_map(|(classes, data)| Payload::Error(classes, data)),
    ]
}

/// Any frame.
pub(crate) fn frame_spec() -> impl Strategy<Value = FrameSpec> {
    let flags = (0u8..=0xF)
        .prop_map(|bits| FdFlags::new(bits).expect("a nibble"))
        .boxed();
    (
        proptest::option::of(timestamp()),
        iface(),
        can_id(),
        payload(flags),
        proptest::option::of(direction()),
    )
        .prop_map(|(timestamp, iface, id, payload, direction)| FrameSpec {
            timestamp,
            iface,
            id,
            payload,
            direction,
        })
}

/// Any frame the screen format shows completely: CAN FD flags only BRS and
/// ESI, and only with a direction (the `-x` column that shows them).
pub(crate) fn screen_frame_spec() -> impl Strategy<Value = FrameSpec> {
    frame_spec().prop_map(|mut spec| {
        if let Payload::Fd(flags, _) = &mut spec.payload {
            let shown = flags.bits() & (FdFlags::BRS.bits() | FdFlags::ESI.bits());
            *flags =
                FdFlags::new(if spec.direction.is_some() { shown } else { 0 }).expect("a nibble");
        }
        spec
    })
}

/// Bytes that matter to the parser, to mutate valid lines with.
fn interesting_byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        prop::sample::select(&b" \t\r\n#().[]RrTX-BE0123456789abcdefABCDEFgG\x00\x7f\xff"[..]),
        any::<u8>(),
    ]
}

/// A valid log or screen line with up to three bytes replaced, inserted or
/// removed: lines close to valid ones, to reach every error.
pub(crate) fn mutated_line() -> impl Strategy<Value = Vec<u8>> {
    (
        frame_spec(),
        any::<bool>(),
        proptest::collection::vec(
            (any::<prop::sample::Index>(), interesting_byte(), 0u8..3),
            0..=3,
        ),
    )
        .prop_map(|(spec, screen, edits)| {
            let mut text = String::new();
            let frame = spec.frame();
            if screen {
                frame.write_screen(&mut text).expect("writing to a String");
            } else {
                frame.write_log(&mut text).expect("writing to a String");
            }
            let mut line = text.into_bytes();
            for (index, byte, op) in edits {
                let at = index.index(line.len() + 1);
                match op {
                    0 if at < line.len() => line[at] = byte,
                    1 => line.insert(at, byte),
                    _ if at < line.len() => {
                        line.remove(at);
                    }
                    _ => line.push(byte),
                }
            }
            line
        })
}

/// Builds candump-shaped records (an interface name, no time or direction)
/// for the tests, with the crate's frame constructors.
pub(crate) struct Build;

impl Build {
    /// A classic data frame on `iface`.
    pub(crate) fn new_data<'a>(
        iface: &'a str,
        id: CanId,
        data: &[u8],
    ) -> Result<LogFrame<'a>, crate::CodecError> {
        Ok(LogFrame::new(CanFrame::new(id, data)?).with_iface(Iface::Name(iface)))
    }

    /// A remote request on `iface`.
    pub(crate) fn new_remote(
        iface: &str,
        id: CanId,
        dlc: u8,
    ) -> Result<LogFrame<'_>, crate::CodecError> {
        Ok(LogFrame::new(CanFrame::new_remote(id, dlc)?).with_iface(Iface::Name(iface)))
    }

    /// A CAN FD frame on `iface`.
    pub(crate) fn new_fd<'a>(
        iface: &'a str,
        id: CanId,
        flags: FdFlags,
        data: &[u8],
    ) -> Result<LogFrame<'a>, crate::CodecError> {
        Ok(LogFrame::new(CanFrame::new_fd(id, flags, data)?).with_iface(Iface::Name(iface)))
    }

    /// An error frame on `iface`.
    pub(crate) fn new_error<'a>(
        iface: &'a str,
        classes: u32,
        data: &[u8],
    ) -> Result<LogFrame<'a>, crate::CodecError> {
        Ok(LogFrame::new(CanFrame::new_error(classes, data)?).with_iface(Iface::Name(iface)))
    }
}

/// The fields of a candump record as the tests read them.
pub(crate) trait FrameExt<'a> {
    /// The interface name (candump records always have one).
    fn iface_str(&self) -> &'a str;
    /// The interface name as bytes.
    fn iface(&self) -> &'a [u8] {
        self.iface_str().as_bytes()
    }
    /// The timestamp.
    fn timestamp(&self) -> Option<Timestamp>;
    /// The direction.
    fn direction(&self) -> Option<Direction>;
    /// The frame.
    fn can(&self) -> &CanFrame;
    /// The identifier.
    fn id(&self) -> CanId {
        self.can().id()
    }
    /// The data.
    fn data(&self) -> &[u8] {
        self.can().data()
    }
    /// Whether it is a remote request.
    fn is_rtr(&self) -> bool {
        self.can().is_rtr()
    }
    /// Whether the identifier is extended.
    fn is_extended(&self) -> bool {
        self.can().is_extended()
    }
    /// Whether it is a CAN FD frame.
    fn is_fd(&self) -> bool {
        self.can().is_fd()
    }
    /// The CAN FD flags.
    fn fd_flags(&self) -> FdFlags {
        self.can().fd_flags()
    }
    /// The DLC.
    fn dlc(&self) -> u8 {
        self.can().dlc()
    }
    /// Write it in the log format.
    fn write_log<W: fmt::Write>(&self, w: &mut W) -> fmt::Result;
    /// Write it in the screen format.
    fn write_screen<W: fmt::Write>(&self, w: &mut W) -> fmt::Result;
}

impl<'a> FrameExt<'a> for LogFrame<'a> {
    fn iface_str(&self) -> &'a str {
        match self.iface {
            Some(Iface::Name(name)) => name,
            _ => panic!("a candump record without an interface name: {self:?}"),
        }
    }

    fn timestamp(&self) -> Option<Timestamp> {
        self.timestamp
    }

    fn direction(&self) -> Option<Direction> {
        self.direction
    }

    fn can(&self) -> &CanFrame {
        &self.frame
    }

    fn write_log<W: fmt::Write>(&self, w: &mut W) -> fmt::Result {
        candump::write_log(self, w)
    }

    fn write_screen<W: fmt::Write>(&self, w: &mut W) -> fmt::Result {
        candump::write_screen(self, w)
    }
}
