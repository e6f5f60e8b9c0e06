//! CAN identifiers: standard (11-bit) and extended (29-bit) (ISO 11898-1).

use core::fmt;

/// A CAN identifier: standard (11-bit) or extended (29-bit) (ISO 11898-1;
/// docs/formats.md#candump-log: 3 hex digits in candump text for a standard
/// identifier, 8 for an extended one).
///
/// `Display` writes it as candump does: 3 upper-case hex digits for a
/// standard identifier, 8 for an extended one.
///
/// ```
/// use motionwire_codec::can::CanId;
///
/// assert_eq!(CanId::standard(0x7FF).map(CanId::raw), Some(0x7FF));
/// assert!(CanId::standard(0x800).is_none());
/// assert!(CanId::extended(0x1FFF_FFFF).unwrap().is_extended());
/// assert!(CanId::extended(0x2000_0000).is_none());
/// assert_eq!(CanId::standard(0x81).unwrap().to_string(), "081");
/// assert_eq!(CanId::extended(0x81).unwrap().to_string(), "00000081");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CanId {
    raw: u32,
    extended: bool,
}

impl CanId {
    /// The largest standard identifier, `0x7FF` (ISO 11898-1).
    pub const STANDARD_MAX: u32 = 0x7FF;
    /// The largest extended identifier, `0x1FFFFFFF` (ISO 11898-1).
    pub const EXTENDED_MAX: u32 = 0x1FFF_FFFF;

    /// Return the standard identifier `raw`, or `None` above `0x7FF`.
    #[inline]
    #[must_use]
    pub const fn standard(raw: u32) -> Option<Self> {
        if raw <= Self::STANDARD_MAX {
            Some(CanId {
                raw,
                extended: false,
            })
        } else {
            None
        }
    }

    /// Return the extended identifier `raw`, or `None` above `0x1FFFFFFF`.
    #[inline]
    #[must_use]
    pub const fn extended(raw: u32) -> Option<Self> {
        if raw <= Self::EXTENDED_MAX {
            Some(CanId {
                raw,
                extended: true,
            })
        } else {
            None
        }
    }

    /// Return the identifier made of the low 29 bits of `raw` when
    /// `extended`, else of its low 11 bits: what a reader of a record that
    /// holds the identifier among other bits (Linux `can_id`, a BLF or MF4
    /// field) gets after masking them, with no check left to fail.
    #[inline]
    #[must_use]
    pub const fn masked(raw: u32, extended: bool) -> Self {
        if extended {
            CanId {
                raw: raw & Self::EXTENDED_MAX,
                extended,
            }
        } else {
            CanId {
                raw: raw & Self::STANDARD_MAX,
                extended,
            }
        }
    }

    /// Return the identifier as a number.
    #[inline]
    #[must_use]
    pub const fn raw(self) -> u32 {
        self.raw
    }

    /// Return whether this is an extended (29-bit) identifier.
    #[inline]
    #[must_use]
    pub const fn is_extended(self) -> bool {
        self.extended
    }

    /// Return the 11-bit value of a standard identifier, `None` for an
    /// extended one: the COB-ID space of CANopen's pre-defined connection
    /// set (CiA 301 §7.3.5).
    #[inline]
    #[must_use]
    pub const fn standard_raw(self) -> Option<u16> {
        if self.extended {
            None
        } else {
            // At most 0x7FF by construction.
            Some(self.raw as u16)
        }
    }
}

impl fmt::Display for CanId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.extended {
            write!(f, "{:08X}", self.raw)
        } else {
            write!(f, "{:03X}", self.raw)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits() {
        assert_eq!(CanId::standard(0).map(CanId::raw), Some(0));
        assert_eq!(CanId::standard(0x7FF).map(CanId::raw), Some(0x7FF));
        assert_eq!(CanId::standard(0x800), None);
        assert_eq!(
            CanId::extended(0x1FFF_FFFF).map(CanId::raw),
            Some(0x1FFF_FFFF)
        );
        assert_eq!(CanId::extended(0x2000_0000), None);
        assert!(!CanId::standard(5).unwrap().is_extended());
        assert!(CanId::extended(5).unwrap().is_extended());
        assert_ne!(CanId::standard(5), CanId::extended(5));
    }

    #[test]
    fn standard_raw_only_for_standard() {
        assert_eq!(CanId::standard(0x705).unwrap().standard_raw(), Some(0x705));
        assert_eq!(CanId::extended(0x705).unwrap().standard_raw(), None);
    }

    #[test]
    fn display_as_candump() {
        assert_eq!(CanId::standard(0).unwrap().to_string(), "000");
        assert_eq!(CanId::standard(0x7FF).unwrap().to_string(), "7FF");
        assert_eq!(
            CanId::extended(0x1FFF_FFFF).unwrap().to_string(),
            "1FFFFFFF"
        );
        assert_eq!(CanId::extended(0x123).unwrap().to_string(), "00000123");
    }
}
