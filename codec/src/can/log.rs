//! A frame as a log records it: the frame with its time, interface and
//! direction (docs/formats.md#timestamps, docs/formats.md#interfaces).

use core::fmt;

use super::{CanFrame, Direction, Timestamp};
use crate::ethercat::EthercatLink;

/// Where a log says a frame was seen: an interface name (candump,
/// pcapng's interface description) or a channel number (Vector ASC and
/// BLF, PEAK TRC's bus column) (`iface` in docs/formats.md#interfaces).
///
/// `Display` writes the name, or the channel number as decimal text
/// (`"1"`), as `iface` does in the JSON (docs/output.md#common-keys).
///
/// ```
/// use motionwire_codec::can::Iface;
///
/// assert_eq!(Iface::Name("can0").to_string(), "can0");
/// assert_eq!(Iface::Channel(2).to_string(), "2");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Iface<'a> {
    /// An interface name, e.g. `can0`, borrowed from the log.
    Name(&'a str),
    /// A channel number, e.g. `1` in a Vector ASC line.
    Channel(u16),
}

impl Iface<'_> {
    /// Return whether this is the interface named `name` (the bytes of a
    /// name as a log holds them): never for a channel. Names are a few
    /// bytes (`can0`, `vcan1`), compared in line rather than by a call to
    /// `memcmp`, which costs more than the compare: names of 4 to 8 bytes
    /// as two overlapping 4-byte words.
    ///
    /// ```
    /// use motionwire_codec::can::Iface;
    ///
    /// assert!(Iface::Name("can0").is_name(b"can0"));
    /// assert!(!Iface::Name("can0").is_name(b"can1"));
    /// assert!(!Iface::Channel(0).is_name(b"0"));
    /// ```
    #[inline(always)]
    #[must_use]
    pub fn is_name(&self, name: &[u8]) -> bool {
        let Iface::Name(own) = self else {
            return false;
        };
        let (a, b) = (own.as_bytes(), name);
        if a.len() != b.len() {
            return false;
        }
        let word = |s: &[u8], at: usize| s.get(at..at + 4).map(|w| [w[0], w[1], w[2], w[3]]);
        match a.len() {
            n @ 4..=8 => word(a, 0) == word(b, 0) && word(a, n - 4) == word(b, n - 4),
            _ => a == b,
        }
    }
}

impl fmt::Display for Iface<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Iface::Name(name) => f.write_str(name),
            Iface::Channel(channel) => write!(f, "{channel}"),
        }
    }
}

/// One frame as a log records it: what every log reader yields
/// (docs/formats.md).
///
/// The fields are public, as in smoltcp's `Repr`s: a reader fills what its
/// format records and leaves the rest `None` — nothing is made up
/// (docs/formats.md#timestamps: `ts` and `iface` are null where the file has
/// none).
///
/// ```
/// use motionwire_codec::can::{CanFrame, CanId, Direction, Iface, LogFrame, Timestamp};
///
/// let frame = CanFrame::new(CanId::standard(0x705).unwrap(), &[0x05])?;
/// let logged = LogFrame::new(frame)
///     .with_timestamp(Timestamp::new(1_700_000_000, 500).unwrap())
///     .with_iface(Iface::Name("can0"))
///     .with_direction(Direction::Rx);
/// assert_eq!(logged.frame.data(), [0x05]);
/// assert_eq!(logged.to_string(), "(1700000000.000500) can0 705#05 R");
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LogFrame<'a> {
    /// The frame.
    pub frame: CanFrame,
    /// When it was recorded, where the log says.
    pub timestamp: Option<Timestamp>,
    /// Where it was seen, where the log says.
    pub iface: Option<Iface<'a>>,
    /// Whether the logging host received or sent it, where the log says.
    pub direction: Option<Direction>,
}

impl<'a> LogFrame<'a> {
    /// Return `frame` with no time, interface or direction.
    #[inline]
    #[must_use]
    pub const fn new(frame: CanFrame) -> Self {
        LogFrame {
            frame,
            timestamp: None,
            iface: None,
            direction: None,
        }
    }

    /// Return the record with the timestamp `ts`.
    #[inline]
    #[must_use]
    pub const fn with_timestamp(mut self, ts: Timestamp) -> Self {
        self.timestamp = Some(ts);
        self
    }

    /// Return the record with the interface `iface`.
    #[inline]
    #[must_use]
    pub const fn with_iface(mut self, iface: Iface<'a>) -> Self {
        self.iface = Some(iface);
        self
    }

    /// Return the record with the direction `direction`.
    #[inline]
    #[must_use]
    pub const fn with_direction(mut self, direction: Direction) -> Self {
        self.direction = Some(direction);
        self
    }
}

impl fmt::Display for LogFrame<'_> {
    /// Write the record in candump's log notation
    /// (docs/formats.md#candump-log): the timestamp in parentheses, the
    /// interface, the frame and the direction letter, each where the record has
    /// it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(ts) = self.timestamp {
            write!(f, "({ts}) ")?;
        }
        if let Some(iface) = self.iface {
            write!(f, "{iface} ")?;
        }
        write!(f, "{}", self.frame)?;
        if let Some(direction) = self.direction {
            write!(f, " {}", direction.letter())?;
        }
        Ok(())
    }
}

/// One entry of a log that a reader hands on: a frame, or a bus event that
/// is not a frame (docs/formats.md#trc: PEAK TRC status rows;
/// docs/summary.md#bus counts them as `status_events`). Lines and records that
/// are neither (headers, comments) are not entries; nothing else is dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LogEvent<'a> {
    /// A CAN frame (data, remote, CAN FD or error frame).
    Frame(LogFrame<'a>),
    /// A bus status event.
    Status(BusStatus<'a>),
    /// An Ethernet packet that carries EtherCAT (docs/ethercat.md#reading):
    /// a capture of an EtherCAT master's port.
    Ethercat(EthercatPacket<'a>),
}

impl<'a> LogEvent<'a> {
    /// Return the frame, if the entry is one.
    #[inline]
    #[must_use]
    pub const fn frame(&self) -> Option<&LogFrame<'a>> {
        match self {
            LogEvent::Frame(frame) => Some(frame),
            LogEvent::Status(_) | LogEvent::Ethercat(_) => None,
        }
    }

    /// Return the entry's time, when the log records one.
    #[inline]
    #[must_use]
    pub const fn timestamp(&self) -> Option<Timestamp> {
        match self {
            LogEvent::Frame(frame) => frame.timestamp,
            LogEvent::Status(status) => status.timestamp,
            LogEvent::Ethercat(packet) => packet.timestamp,
        }
    }

    /// Return the entry's interface or channel, when the log records one.
    #[inline]
    #[must_use]
    pub const fn iface(&self) -> Option<Iface<'a>> {
        match self {
            LogEvent::Frame(frame) => frame.iface,
            LogEvent::Status(status) => status.iface,
            LogEvent::Ethercat(packet) => packet.iface,
        }
    }
}

impl<'a> From<LogFrame<'a>> for LogEvent<'a> {
    #[inline]
    fn from(frame: LogFrame<'a>) -> Self {
        LogEvent::Frame(frame)
    }
}

/// A bus event that is not a frame: a status row of a PEAK TRC file
/// (`ST`, or a status word such as `Warng` or `BUSHEAVY`; docs/formats.md#trc).
/// The summary's bus record counts them (`status_events` in
/// docs/summary.md#bus).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BusStatus<'a> {
    /// When the event was recorded.
    pub timestamp: Option<Timestamp>,
    /// The interface or channel it was recorded on.
    pub iface: Option<Iface<'a>>,
}

/// An Ethernet packet of a capture that carries EtherCAT: when and where
/// it was captured, and what [`EthercatLink`] found in it (the source MAC,
/// the encapsulation, the bytes from the EtherCAT header on). The session
/// of motionwire's `ethercat` module reads its datagrams
/// (docs/ethercat.md#reading).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EthercatPacket<'a> {
    /// When the packet was captured.
    pub timestamp: Option<Timestamp>,
    /// The interface it was captured on.
    pub iface: Option<Iface<'a>>,
    /// The packet, unwrapped to its EtherCAT payload.
    pub link: EthercatLink<'a>,
}

impl fmt::Display for LogEvent<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LogEvent::Frame(frame) => frame.fmt(f),
            LogEvent::Status(status) => {
                if let Some(ts) = status.timestamp {
                    write!(f, "({ts}) ")?;
                }
                if let Some(iface) = status.iface {
                    write!(f, "{iface} ")?;
                }
                f.write_str("bus status event")
            }
            LogEvent::Ethercat(packet) => {
                if let Some(ts) = packet.timestamp {
                    write!(f, "({ts}) ")?;
                }
                if let Some(iface) = packet.iface {
                    write!(f, "{iface} ")?;
                }
                write!(
                    f,
                    "EtherCAT from {} ({} bytes)",
                    packet.link.source,
                    packet.link.payload.len()
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::can::CanId;

    #[test]
    fn display_writes_only_what_is_there() {
        let frame = CanFrame::new(CanId::standard(0x081).unwrap(), &[1, 2]).unwrap();
        assert_eq!(LogFrame::new(frame).to_string(), "081#0102");
        assert_eq!(
            LogFrame::new(frame)
                .with_iface(Iface::Channel(1))
                .to_string(),
            "1 081#0102"
        );
        assert_eq!(
            LogFrame::new(frame)
                .with_direction(Direction::Tx)
                .with_timestamp(Timestamp::new(3, 4).unwrap())
                .to_string(),
            "(0000000003.000004) 081#0102 T"
        );
    }
}
