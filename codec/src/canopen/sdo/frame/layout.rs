//! The layout of an SDO frame: its fields, lengths and command bits.

use crate::error::What;
use crate::{FrameError, ValueError};

pub(in crate::canopen::sdo) mod field {
    use core::ops::Range;

    /// Byte 0: the command byte (specifier in bits 7–5).
    pub(in crate::canopen::sdo) const COMMAND: usize = 0;
    /// Bytes 1–2: the object index, little-endian.
    pub(in crate::canopen::sdo) const INDEX: Range<usize> = 1..3;
    /// Byte 3: the sub-index.
    pub(in crate::canopen::sdo) const SUBINDEX: usize = 3;
    /// Bytes 4–7: expedited data, the size, or the abort code.
    pub(in crate::canopen::sdo) const DATA: Range<usize> = 4..8;
    /// Bytes 1–7: the data of a segment.
    pub(in crate::canopen::sdo) const SEGMENT: Range<usize> = 1..8;
    /// Bytes 1–2: the CRC of a block transfer's end frame.
    pub(in crate::canopen::sdo) const CRC: Range<usize> = 1..3;
    /// Byte 1: `ackseq` of a sub-block confirmation.
    pub(in crate::canopen::sdo) const ACKSEQ: usize = 1;
    /// Byte 2: `blksize` of a sub-block confirmation.
    pub(in crate::canopen::sdo) const ACK_BLKSIZE: usize = 2;
    /// Byte 4: `blksize` of a block initiate (upload request, download
    /// response).
    pub(in crate::canopen::sdo) const INITIATE_BLKSIZE: usize = 4;
    /// Byte 5: `pst`, the protocol switch threshold of a block upload
    /// initiate request.
    pub(in crate::canopen::sdo) const PST: usize = 5;
}

/// The length of every SDO frame's data: 8 bytes (CiA 301 §7.2.4.3).
pub const SDO_LEN: usize = field::DATA.end;

/// The most bytes one segment carries (CiA 301 §7.2.4.3.4).
pub const SEGMENT_MAX: usize = 7;

/// The most segments in one block (`blksize`, CiA 301 §7.2.4.3.9).
pub const BLKSIZE_MAX: u8 = 127;

pub(super) const WHAT: What = What::SdoFrame;

pub(super) fn invalid(what: What, found: u8, expected: &'static str) -> FrameError {
    FrameError::Content(ValueError {
        what,
        found: u32::from(found),
        expected,
    })
}

/// `n` of a segment: bits 3–1.
pub(in crate::canopen::sdo) const fn segment_unused(command: u8) -> u8 {
    (command >> 1) & 0b111
}

/// `t`, the toggle bit of a segment and its confirmation.
pub(in crate::canopen::sdo) const TOGGLE: u8 = 0b1_0000;
/// `c`, the last segment.
pub(in crate::canopen::sdo) const LAST: u8 = 0b1;
/// `cc`/`sc`, the CRC support of a block initiate.
pub(in crate::canopen::sdo) const CRC_SUPPORTED: u8 = 0b100;

pub(super) const fn crc_bit(supported: bool) -> u8 {
    if supported {
        CRC_SUPPORTED
    } else {
        0
    }
}
