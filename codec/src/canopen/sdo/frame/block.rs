//! What only block transfers have: the segments inside a block and the
//! transfer's CRC (CiA 301 §7.2.4.3.9–§7.2.4.3.16; docs/canopen.md#sdo);
//! the sub-command of a control frame is in `party.rs`, with the services.

use super::layout::{field, SDO_LEN, SEGMENT_MAX};
use super::view::{SdoFields, SdoFrame};
use crate::{LenError, Result};

/// A segment inside a block (CiA 301 §7.2.4.3.11, §7.2.4.3.14): bit 7 `c`,
/// bits 6–0 the sequence number, bytes 1–7 data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SdoBlockSegment {
    /// `c`: the last segment of the whole transfer.
    pub last: bool,
    /// The sequence number, 1..=127 in a valid block (0 is read as written).
    pub seqno: u8,
    /// Bytes 1–7; how many of the last segment's bytes are data is said
    /// only by the end frame that follows.
    pub data: [u8; SEGMENT_MAX],
}

impl SdoBlockSegment {
    /// Read a block segment from a frame's data.
    ///
    /// # Errors
    ///
    /// [`LenError`] for fewer than 8 bytes.
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        let frame = SdoFrame::new_checked(data)?;
        let mut bytes = [0; SEGMENT_MAX];
        bytes.copy_from_slice(frame.segment_field());
        Ok(SdoBlockSegment {
            last: frame.command() & 0x80 != 0,
            seqno: frame.command() & 0x7F,
            data: bytes,
        })
    }

    /// Return the frame's 8 data bytes.
    #[must_use]
    pub fn to_bytes(&self) -> [u8; SDO_LEN] {
        let mut out = [0u8; SDO_LEN];
        out[0] = (u8::from(self.last) << 7) | (self.seqno & 0x7F);
        out[field::SEGMENT].copy_from_slice(&self.data);
        out
    }

    /// Return the fields of the `sdo` key (docs/output.md#sdo) for a block
    /// segment.
    #[must_use]
    pub fn fields(&self) -> SdoFields<'_> {
        SdoFields {
            seqno: Some(self.seqno),
            last: Some(self.last),
            value: Some(&self.data),
            ..SdoFields::default()
        }
    }
}

/// The CRC of a block transfer: CRC-16 with polynomial x^16 + x^12 + x^5 +
/// 1 (0x1021), initial value 0, no reflection, over all the data
/// (CiA 301 §7.2.4.3.16, the "CRC-16-CCITT/XMODEM" variant).
///
/// ```
/// use motionwire_codec::canopen::sdo::BlockCrc;
///
/// let mut crc = BlockCrc::new();
/// crc.update(b"1234");
/// crc.update(b"56789");
/// assert_eq!(crc.value(), 0x31C3); // the check value of CRC-16/XMODEM
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BlockCrc(u16);

impl BlockCrc {
    /// Return the CRC of no data.
    #[must_use]
    pub const fn new() -> Self {
        BlockCrc(0)
    }

    /// Add `data` to the CRC.
    pub fn update(&mut self, data: &[u8]) {
        for &byte in data {
            self.0 = (self.0 << 8) ^ CRC_TABLE[usize::from((self.0 >> 8) as u8 ^ byte)];
        }
    }

    /// Return the CRC of the data so far.
    #[must_use]
    pub const fn value(self) -> u16 {
        self.0
    }
}

const CRC_TABLE: [u16; 256] = {
    let mut table = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let mut crc = (i as u16) << 8;
        let mut bit = 0;
        while bit < 8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ 0x1021
            } else {
                crc << 1
            };
            bit += 1;
        }
        table[i] = crc;
        i += 1;
    }
    table
};
