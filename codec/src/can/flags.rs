//! The flags a CAN frame carries besides its identifier and data: the CAN FD
//! flags nibble (Linux `linux/can.h`) and the direction a log records.

use core::fmt;

/// The flags nibble of a CAN FD frame, `123##<flags>…` in candump's log
/// format (docs/formats.md#candump-log; bit values from Linux `linux/can.h`,
/// `CANFD_BRS`, `CANFD_ESI`, `CANFD_FDF`). Bits the kernel may add later are
/// kept.
///
/// `Display` writes the set flags' names joined by `|` (`BRS|ESI`), `-`
/// when none is set, and a bit without a name as hex.
///
/// ```
/// use motionwire_codec::can::FdFlags;
///
/// let flags = FdFlags::new(0x3).unwrap();
/// assert!(flags.contains(FdFlags::BRS) && flags.contains(FdFlags::ESI));
/// assert!(FdFlags::new(0x10).is_none());
/// assert_eq!(flags.to_string(), "BRS|ESI");
/// assert_eq!(FdFlags::new(0xC).unwrap().to_string(), "FDF|0x8");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FdFlags(u8);

impl FdFlags {
    /// No flag set.
    pub const EMPTY: FdFlags = FdFlags(0);
    /// Bit rate switch: the data phase ran at the higher bit rate (`CANFD_BRS`, 0x1).
    pub const BRS: FdFlags = FdFlags(0x1);
    /// Error state indicator: the sender was error passive (`CANFD_ESI`, 0x2).
    pub const ESI: FdFlags = FdFlags(0x2);
    /// FD frame marker that newer kernels set on every CAN FD frame (`CANFD_FDF`, 0x4).
    pub const FDF: FdFlags = FdFlags(0x4);

    /// The named flags in bit order with their names: the one table that
    /// `Display` and every user of the names read.
    pub const NAMES: [(FdFlags, &'static str); 3] = [
        (FdFlags::BRS, "BRS"),
        (FdFlags::ESI, "ESI"),
        (FdFlags::FDF, "FDF"),
    ];

    /// Return the flags `bits`, or `None` when they do not fit a nibble.
    #[inline]
    #[must_use]
    pub const fn new(bits: u8) -> Option<Self> {
        if bits <= 0xF {
            Some(FdFlags(bits))
        } else {
            None
        }
    }

    /// Return the flags as a nibble, 0..=15.
    #[inline]
    #[must_use]
    pub const fn bits(self) -> u8 {
        self.0
    }

    /// Return whether every flag of `other` is set here.
    #[inline]
    #[must_use]
    pub const fn contains(self, other: FdFlags) -> bool {
        self.0 & other.0 == other.0
    }

    /// Return the flags of both.
    #[inline]
    #[must_use]
    pub const fn union(self, other: FdFlags) -> FdFlags {
        FdFlags(self.0 | other.0)
    }

    /// Return whether no flag is set.
    #[inline]
    #[must_use]
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }
}

impl fmt::Display for FdFlags {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("-");
        }
        let names = FdFlags::NAMES
            .into_iter()
            .filter(|(flag, _)| self.contains(*flag))
            .map(|(_, name)| name);
        let any = crate::names::write_joined(f, names, "|")?;
        let rest = FdFlags::NAMES
            .into_iter()
            .fold(self.0, |rest, (flag, _)| rest & !flag.0);
        if rest != 0 {
            if any {
                f.write_str("|")?;
            }
            write!(f, "{rest:#x}")?;
        }
        Ok(())
    }
}

/// Whether the logging host received the frame or sent it itself: the ` R`
/// / ` T` suffix of candump's log format, the `RX`/`TX` column of its
/// screen output (`candump -x`), `Rx`/`Tx` in Vector ASC and PEAK TRC
/// (docs/formats.md).
///
/// ```
/// use motionwire_codec::can::Direction;
///
/// assert_eq!(Direction::Rx.letter(), 'R');
/// assert_eq!(Direction::Tx.to_string(), "TX");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Direction {
    /// Received from the bus (`R`, `RX`).
    Rx,
    /// Sent by the logging host (`T`, `TX`).
    Tx,
}

impl Direction {
    /// Return the letter candump's log format writes, `R` or `T`.
    #[inline]
    #[must_use]
    pub const fn letter(self) -> char {
        match self {
            Direction::Rx => 'R',
            Direction::Tx => 'T',
        }
    }

    /// Return the column candump's screen output writes, `RX` or `TX`.
    #[inline]
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Direction::Rx => "RX",
            Direction::Tx => "TX",
        }
    }
}

impl fmt::Display for Direction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fd_flags_bits_and_names() {
        assert_eq!(FdFlags::BRS.bits(), 0x1);
        assert_eq!(FdFlags::ESI.bits(), 0x2);
        assert_eq!(FdFlags::FDF.bits(), 0x4);
        assert_eq!(FdFlags::new(0xF).map(FdFlags::bits), Some(0xF));
        assert_eq!(FdFlags::new(0x10), None);
        assert!(FdFlags::EMPTY.is_empty());
        assert_eq!(FdFlags::EMPTY.to_string(), "-");
        assert_eq!(FdFlags::BRS.union(FdFlags::FDF).to_string(), "BRS|FDF");
        assert_eq!(FdFlags::new(0x8).unwrap().to_string(), "0x8");
        assert_eq!(FdFlags::new(0xF).unwrap().to_string(), "BRS|ESI|FDF|0x8");
    }

    #[test]
    fn direction_letters() {
        assert_eq!([Direction::Rx.letter(), Direction::Tx.letter()], ['R', 'T']);
        assert_eq!([Direction::Rx.name(), Direction::Tx.name()], ["RX", "TX"]);
    }
}
