//! The zero-copy view over an SDO frame's 8 data bytes, [`SdoFrame`], with
//! the fields every service shares, and [`SdoFields`], the fields of
//! the `sdo` key (docs/output.md#sdo) for one frame (CiA 301 §7.2.4.3;
//! docs/canopen.md#sdo).

use byteorder::{ByteOrder, LittleEndian};

use super::layout::{crc_bit, field, CRC_SUPPORTED, SDO_LEN, WHAT};
use super::party::BlockSubcommand;
use crate::canopen::ObjectAddress;
use crate::canopen::SdoAbortCode;
use crate::error::check_len;
use crate::{LenError, Result};

/// A zero-copy view over an SDO frame's data (CiA 301 §7.2.4.3;
/// docs/canopen.md#sdo): the fields every service shares.
///
/// After [`SdoFrame::new_checked`] (or [`SdoFrame::check_len`]) succeeds,
/// no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> SdoFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// shorter than [`SDO_LEN`].
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        SdoFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least [`SDO_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`SDO_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(WHAT, self.buffer.as_ref(), SDO_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the command byte (byte 0).
    #[inline]
    pub fn command(&self) -> u8 {
        self.buffer.as_ref()[field::COMMAND]
    }

    /// Return the command specifier, bits 7–5 of byte 0.
    #[inline]
    pub fn specifier(&self) -> u8 {
        self.command() >> 5
    }

    /// Return the index field (bytes 1–2, little-endian).
    #[inline]
    pub fn index(&self) -> u16 {
        LittleEndian::read_u16(&self.buffer.as_ref()[field::INDEX])
    }

    /// Return the sub-index field (byte 3).
    #[inline]
    pub fn subindex(&self) -> u8 {
        self.buffer.as_ref()[field::SUBINDEX]
    }

    /// Return the multiplexer (bytes 1–3).
    #[inline]
    pub fn multiplexer(&self) -> ObjectAddress {
        ObjectAddress::new(self.index(), self.subindex())
    }

    /// Return bytes 4–7: expedited data, a size or an abort code.
    #[inline]
    pub fn data_field(&self) -> [u8; 4] {
        let mut out = [0; 4];
        out.copy_from_slice(&self.buffer.as_ref()[field::DATA]);
        out
    }

    /// Return bytes 1–7, the data of a segment.
    #[inline]
    pub fn segment_field(&self) -> &[u8] {
        &self.buffer.as_ref()[field::SEGMENT]
    }
}

impl<T: AsRef<[u8]>> SdoFrame<T> {
    /// Return `ackseq` and `blksize` of a sub-block confirmation (bytes 1
    /// and 2; CiA 301 §7.2.4.3.12, §7.2.4.3.15).
    #[inline]
    pub fn block_ack(&self) -> (u8, u8) {
        let buf = self.buffer.as_ref();
        (buf[field::ACKSEQ], buf[field::ACK_BLKSIZE])
    }

    /// Return the CRC-support bit and the size (when `s`, bit 1, is set) of
    /// a block initiate that carries a size: the client's block download
    /// initiate or the server's block upload answer (CiA 301 §7.2.4.3.9,
    /// §7.2.4.3.13).
    #[inline]
    pub fn sized_block_initiate(&self) -> (bool, Option<u32>) {
        let command = self.command();
        (
            command & CRC_SUPPORTED != 0,
            (command & 0b10 != 0).then(|| u32::from_le_bytes(self.data_field())),
        )
    }

    /// Return `n` (bits 4–2: bytes of the last segment without data) and
    /// the CRC (bytes 1–2) of a block end frame (CiA 301 §7.2.4.3.14,
    /// §7.2.4.3.16).
    #[inline]
    pub fn block_end(&self) -> (u8, u16) {
        (
            (self.command() >> 2) & 0b111,
            LittleEndian::read_u16(&self.buffer.as_ref()[field::CRC]),
        )
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> SdoFrame<T> {
    /// Write a sub-block confirmation: command (cs/ss 2 of block upload
    /// request / block download response, specifier 5), `ackseq`,
    /// `blksize`.
    #[inline]
    pub fn set_block_ack(&mut self, ackseq: u8, blksize: u8) {
        self.set_command((5 << 5) | 2);
        let buf = self.buffer.as_mut();
        buf[field::ACKSEQ] = ackseq;
        buf[field::ACK_BLKSIZE] = blksize;
    }

    /// Write a block initiate that carries a size (specifier 6: the
    /// client's block download initiate, the server's block upload
    /// answer).
    #[inline]
    pub fn set_sized_block_initiate(
        &mut self,
        multiplexer: ObjectAddress,
        crc_supported: bool,
        size: Option<u32>,
    ) {
        let s = if size.is_some() { 0b10 } else { 0 };
        self.set_command((6 << 5) | crc_bit(crc_supported) | s);
        self.set_multiplexer(multiplexer);
        self.set_data_field(size.unwrap_or(0).to_le_bytes());
    }

    /// Write a block end frame with specifier 6 (the client's block
    /// download end, the server's block upload end): `n` and the CRC.
    #[inline]
    pub fn set_block_end(&mut self, unused: u8, crc: u16) {
        self.set_command((6 << 5) | ((unused & 0b111) << 2) | 1);
        self.buffer.as_mut()[field::CRC].copy_from_slice(&crc.to_le_bytes());
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> SdoFrame<T> {
    /// Set the command byte (byte 0).
    #[inline]
    pub fn set_command(&mut self, command: u8) {
        self.buffer.as_mut()[field::COMMAND] = command;
    }

    /// Set the multiplexer (bytes 1–3).
    #[inline]
    pub fn set_multiplexer(&mut self, multiplexer: ObjectAddress) {
        let buf = self.buffer.as_mut();
        LittleEndian::write_u16(&mut buf[field::INDEX], multiplexer.index);
        buf[field::SUBINDEX] = multiplexer.sub_index;
    }

    /// Set bytes 4–7.
    #[inline]
    pub fn set_data_field(&mut self, data: [u8; 4]) {
        self.buffer.as_mut()[field::DATA].copy_from_slice(&data);
    }
}

/// The fields of the `sdo` key (docs/output.md#sdo) for one frame, whichever
/// its service.
///
/// Every `Option` is `Some` exactly for the services whose frames carry
/// that field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SdoFields<'a> {
    /// Index and sub-index: initiates and aborts.
    pub multiplexer: Option<ObjectAddress>,
    /// `e`: initiate download requests and initiate upload responses.
    pub expedited: Option<bool>,
    /// The indicated size (`null` in the JSON when the frame could carry
    /// one but `s` = 0).
    pub size: Option<Option<u32>>,
    /// The expedited data, or a segment's data.
    pub value: Option<&'a [u8]>,
    /// The toggle bit of a segment frame.
    pub toggle: Option<bool>,
    /// `c`: the last segment.
    pub last: Option<bool>,
    /// The abort code.
    pub abort_code: Option<SdoAbortCode>,
    /// The block sub-command.
    pub subcommand: Option<BlockSubcommand>,
    /// The CRC-support bit of a block initiate.
    pub crc_supported: Option<bool>,
    /// `blksize`.
    pub blksize: Option<u8>,
    /// `ackseq`.
    pub ackseq: Option<u8>,
    /// The sequence number of a block segment.
    pub seqno: Option<u8>,
    /// The CRC of a block end.
    pub crc: Option<u16>,
}
