//! The data an SDO initiate or segment frame carries: [`SdoInitiateData`]
//! (expedited bytes or a segmented size) and [`SdoSegmentData`] (CiA 301
//! §7.2.4.3.3–§7.2.4.3.7; docs/canopen.md#sdo).

use byteorder::{ByteOrder, LittleEndian};

use super::layout::SEGMENT_MAX;

/// What an initiate download request or initiate upload response says
/// about the data (bits `e`, `s`, `n` and bytes 4–7, CiA 301 §7.2.4.3.3,
/// §7.2.4.3.6; docs/canopen.md#sdo).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SdoInitiateData {
    /// `e` = 1: the data is in bytes 4–7.
    Expedited {
        /// Bytes 4–7: the data, then zeros where `n` says no data is (the
        /// bytes sent there are not kept).
        bytes: [u8; 4],
        /// The data length, 1..=4, when `s` = 1 (4 − `n`); `None` when the
        /// size is not indicated and all four bytes are the value
        /// (docs/canopen.md#sdo).
        len: Option<u8>,
    },
    /// `e` = 0: segments follow.
    Segmented {
        /// The data size from bytes 4–7 when `s` = 1.
        size: Option<u32>,
    },
}

impl SdoInitiateData {
    /// Return expedited data of 1..=4 bytes with its size indicated, or
    /// `None` for another length.
    #[must_use]
    pub fn expedited(data: &[u8]) -> Option<Self> {
        if data.is_empty() || data.len() > 4 {
            return None;
        }
        let mut bytes = [0; 4];
        bytes[..data.len()].copy_from_slice(data);
        Some(SdoInitiateData::Expedited {
            bytes,
            len: Some(data.len() as u8),
        })
    }

    /// Return the expedited data (all four bytes when the size is not
    /// indicated), or an empty slice for a segmented transfer.
    #[must_use]
    pub fn data(&self) -> &[u8] {
        match self {
            SdoInitiateData::Expedited { bytes, len } => {
                &bytes[..len.map_or(4, |n| usize::from(n.clamp(1, 4)))]
            }
            SdoInitiateData::Segmented { .. } => &[],
        }
    }

    /// Return the size the frame indicates: the expedited length or the
    /// segmented size; `None` when `s` = 0.
    #[must_use]
    pub fn size(&self) -> Option<u32> {
        match *self {
            SdoInitiateData::Expedited { len, .. } => len.map(u32::from),
            SdoInitiateData::Segmented { size } => size,
        }
    }

    /// Return whether the transfer is expedited (`e` = 1).
    #[must_use]
    pub const fn is_expedited(&self) -> bool {
        matches!(self, SdoInitiateData::Expedited { .. })
    }

    /// Read bits `e`, `s`, `n` of `command` and bytes 4–7.
    #[inline]
    pub(in crate::canopen::sdo) fn read(command: u8, data: [u8; 4]) -> Self {
        let expedited = command & 0b10 != 0;
        let size_indicated = command & 0b01 != 0;
        let n = (command >> 2) & 0b11;
        match (expedited, size_indicated) {
            (true, true) => {
                // The `len` low bytes kept, the rest zeros: one mask, not
                // a copy of a variable length (a `memcpy` call).
                let len = 4 - n;
                let keep = (1_u64 << (8 * u32::from(len))) - 1;
                let bytes = (u32::from_le_bytes(data) & keep as u32).to_le_bytes();
                SdoInitiateData::Expedited {
                    bytes,
                    len: Some(len),
                }
            }
            (true, false) => SdoInitiateData::Expedited {
                bytes: data,
                len: None,
            },
            (false, true) => SdoInitiateData::Segmented {
                size: Some(LittleEndian::read_u32(&data)),
            },
            (false, false) => SdoInitiateData::Segmented { size: None },
        }
    }

    /// Return the bits `n`, `e`, `s` and bytes 4–7.
    pub(super) fn write(&self) -> (u8, [u8; 4]) {
        match *self {
            SdoInitiateData::Expedited { bytes, len: None } => (0b10, bytes),
            SdoInitiateData::Expedited {
                bytes,
                len: Some(len),
            } => {
                let len = len.clamp(1, 4);
                // Bytes past the data are sent as zeros.
                let mut out = [0; 4];
                out[..usize::from(len)].copy_from_slice(&bytes[..usize::from(len)]);
                (((4 - len) << 2) | 0b11, out)
            }
            SdoInitiateData::Segmented { size: None } => (0, [0; 4]),
            SdoInitiateData::Segmented { size: Some(size) } => (0b01, size.to_le_bytes()),
        }
    }
}

/// The data of one segment: 0..=7 bytes of bytes 1–7 (CiA 301 §7.2.4.3.4,
/// §7.2.4.3.7: `n` counts the bytes without data).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SdoSegmentData {
    pub(super) bytes: [u8; SEGMENT_MAX],
    len: u8,
}

impl SdoSegmentData {
    /// Return segment data holding `data`, or `None` above 7 bytes.
    #[must_use]
    pub fn new(data: &[u8]) -> Option<Self> {
        if data.len() > SEGMENT_MAX {
            return None;
        }
        let mut bytes = [0; SEGMENT_MAX];
        bytes[..data.len()].copy_from_slice(data);
        Some(SdoSegmentData {
            bytes,
            len: data.len() as u8,
        })
    }

    /// Return the data bytes.
    #[must_use]
    pub fn as_slice(&self) -> &[u8] {
        &self.bytes[..usize::from(self.len)]
    }

    /// Return `n`: the bytes of bytes 1–7 that hold no data.
    #[must_use]
    pub const fn unused(&self) -> u8 {
        SEGMENT_MAX as u8 - self.len
    }

    /// Read bytes 1–7 of a segment frame (`segment`, at least 7 bytes),
    /// `n` of them unused (0..=7): the data, then zeros.
    pub(super) fn read(n: u8, segment: &[u8]) -> Self {
        // The `len` low bytes kept, the rest zeros: one mask on a word,
        // not a `memset` call of a variable length.
        let mut word = [0; 8];
        word[..SEGMENT_MAX].copy_from_slice(&segment[..SEGMENT_MAX]);
        let len = SEGMENT_MAX as u8 - n;
        let keep = (1_u64 << (8 * u32::from(len))) - 1;
        let word = (u64::from_le_bytes(word) & keep).to_le_bytes();
        let mut bytes = [0; SEGMENT_MAX];
        bytes.copy_from_slice(&word[..SEGMENT_MAX]);
        SdoSegmentData { bytes, len }
    }
}

impl core::ops::Deref for SdoSegmentData {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        self.as_slice()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The masks keep exactly what copying the data bytes and zeroing
        /// the rest kept: a segment's `7 − n` bytes, an expedited
        /// frame's `4 − n`.
        #[test]
        fn masks_keep_what_copies_kept(
            n in 0_u8..=7,
            segment in proptest::array::uniform7(any::<u8>()),
            command in any::<u8>(),
            data in proptest::array::uniform4(any::<u8>()),
        ) {
            let len = SEGMENT_MAX - usize::from(n);
            let mut bytes = [0; SEGMENT_MAX];
            bytes[..len].copy_from_slice(&segment[..len]);
            let read = SdoSegmentData::read(n, &segment);
            prop_assert_eq!(read, SdoSegmentData { bytes, len: len as u8 });

            let read = SdoInitiateData::read(command, data);
            if command & 0b11 == 0b11 {
                let len = 4 - ((command >> 2) & 0b11);
                let mut bytes = [0; 4];
                bytes[..usize::from(len)].copy_from_slice(&data[..usize::from(len)]);
                prop_assert_eq!(read, SdoInitiateData::Expedited { bytes, len: Some(len) });
            }
        }
    }
}
