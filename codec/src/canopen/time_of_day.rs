//! The TIME object's data: CiA 301's TIME_OF_DAY (CiA 301 §7.1.6.5,
//! §7.2.6; `time_of_day` in docs/output.md#time).
//!
//! Six bytes: milliseconds after midnight in the low 28 bits of bytes 0–3
//! (the top 4 bits are reserved) and days since 1984-01-01 in bytes 4–5,
//! both little-endian.
//!
//! ```
//! use motionwire_codec::canopen::TimeOfDay;
//!
//! // 12:00:00.000 on 2026-11-23, day 15667 after 1984-01-01.
//! let time = TimeOfDay::new(43_200_000, 15_667).unwrap();
//! let bytes = time.to_bytes();
//! assert_eq!(bytes, [0x00, 0x2E, 0x93, 0x02, 0x33, 0x3D]);
//! assert_eq!(TimeOfDay::parse(&bytes)?, time);
//! assert_eq!(time.to_string(), "day 15667 (since 1984-01-01), 12:00:00.000");
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use byteorder::{ByteOrder, LittleEndian};
use core::fmt;

use crate::error::{check_len, What};
use crate::{LenError, Result};

mod field {
    use core::ops::Range;

    /// Bytes 0–3: milliseconds after midnight (bits 0–27), reserved (28–31).
    pub(super) const MS: Range<usize> = 0..4;
    /// Bytes 4–5: days since 1984-01-01.
    pub(super) const DAYS: Range<usize> = 4..6;
}

/// The length of TIME_OF_DAY: 6 bytes (CiA 301 §7.1.6.5).
pub const TIME_OF_DAY_LEN: usize = field::DAYS.end;

const MS_MASK: u32 = 0x0FFF_FFFF;

/// CiA 301's TIME_OF_DAY (§7.1.6.5), the data of the TIME object (COB-ID
/// 0x100).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TimeOfDay {
    ms: u32,
    days: u16,
}

impl TimeOfDay {
    /// Return the time `ms` milliseconds after midnight of day `days` after
    /// 1984-01-01, or `None` when `ms` needs more than 28 bits.
    #[must_use]
    pub const fn new(ms: u32, days: u16) -> Option<Self> {
        if ms > MS_MASK {
            return None;
        }
        Some(TimeOfDay { ms, days })
    }

    /// Return the milliseconds after midnight (28 bits; values of a day or
    /// more are kept as sent).
    #[must_use]
    pub const fn ms(self) -> u32 {
        self.ms
    }

    /// Return the days since 1984-01-01.
    #[must_use]
    pub const fn days(self) -> u16 {
        self.days
    }

    /// Read the first 6 bytes of a TIME frame; the 4 reserved bits are
    /// ignored.
    ///
    /// # Errors
    ///
    /// [`LenError`] for fewer than 6 bytes.
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        check_len(What::TimeOfDay, data, TIME_OF_DAY_LEN)?;
        Ok(TimeOfDay {
            ms: LittleEndian::read_u32(&data[field::MS]) & MS_MASK,
            days: LittleEndian::read_u16(&data[field::DAYS]),
        })
    }

    /// Return the 6 bytes; the reserved bits are 0.
    #[must_use]
    pub fn to_bytes(self) -> [u8; TIME_OF_DAY_LEN] {
        let mut out = [0; TIME_OF_DAY_LEN];
        LittleEndian::write_u32(&mut out[field::MS], self.ms);
        LittleEndian::write_u16(&mut out[field::DAYS], self.days);
        out
    }
}

impl fmt::Display for TimeOfDay {
    /// `day 15667 (since 1984-01-01), 12:00:00.000`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ms = self.ms;
        write!(
            f,
            "day {} (since 1984-01-01), {:02}:{:02}:{:02}.{:03}",
            self.days,
            ms / 3_600_000,
            ms / 60_000 % 60,
            ms / 1000 % 60,
            ms % 1000
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn reserved_bits_are_ignored_and_short_data_refused() {
        let t = TimeOfDay::parse(&[0xFF, 0xFF, 0xFF, 0xFF, 1, 0]).unwrap();
        assert_eq!((t.ms(), t.days()), (MS_MASK, 1));
        for len in 0..TIME_OF_DAY_LEN {
            assert!(TimeOfDay::parse(&[0; 6][..len]).is_err());
        }
        assert_eq!(TimeOfDay::new(MS_MASK + 1, 0), None);
    }

    proptest! {
        #[test]
        fn round_trip(ms in 0..=MS_MASK, days: u16) {
            let t = TimeOfDay::new(ms, days).unwrap();
            prop_assert_eq!(TimeOfDay::parse(&t.to_bytes()).unwrap(), t);
        }

        #[test]
        fn any_bytes(data in proptest::collection::vec(any::<u8>(), 0..10)) {
            let _ = TimeOfDay::parse(&data);
        }
    }
}
