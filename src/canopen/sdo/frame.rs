//! SDO frames: the 8 data bytes of a request (client → server, COB-ID
//! 0x600 + node) or a response (server → client, 0x580 + node)
//! (CiA 301 §7.2.4.3; SPEC §7.1).
//!
//! [`SdoFrame`] is the zero-copy view over the bytes, with the fields every
//! service shares; [`SdoRequest`], [`SdoResponse`] and [`SdoBlockSegment`]
//! are the owned values, each with `parse` and `to_bytes`. A segment inside
//! a block transfer cannot be told from a request or response by its bytes
//! alone: [`SdoTracker`](super::SdoTracker) knows when one is due.
//!
//! ```
//! use motionwire::canopen::sdo::{SdoInitiateData, SdoMultiplexer, SdoRequest, SdoResponse};
//!
//! // A client reads 1008h sub 0 (manufacturer device name)…
//! let request = SdoRequest::InitiateUpload { multiplexer: SdoMultiplexer::new(0x1008, 0) };
//! assert_eq!(request.to_bytes(), [0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]);
//! assert_eq!(SdoRequest::parse(&request.to_bytes())?, request);
//!
//! // …and the server answers "segmented, 10 bytes follow".
//! let response = SdoResponse::parse(&[0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0])?;
//! assert_eq!(response, SdoResponse::InitiateUpload {
//!     multiplexer: SdoMultiplexer::new(0x1008, 0),
//!     data: SdoInitiateData::Segmented { size: Some(10) },
//! });
//!
//! // A short frame is an error that says how short, never a panic.
//! assert!(SdoResponse::parse(&[0x41, 0x08, 0x10]).is_err());
//! # Ok::<(), motionwire::Error>(())
//! ```

use byteorder::{ByteOrder, LittleEndian};
use core::fmt;

use crate::canopen::SdoAbortCode;
use crate::error::{check_len, What};
use crate::{Error, Result};

mod field {
    use core::ops::Range;

    /// Byte 0: the command byte (specifier in bits 7–5).
    pub(super) const COMMAND: usize = 0;
    /// Bytes 1–2: the object index, little-endian.
    pub(super) const INDEX: Range<usize> = 1..3;
    /// Byte 3: the sub-index.
    pub(super) const SUBINDEX: usize = 3;
    /// Bytes 4–7: expedited data, the size, or the abort code.
    pub(super) const DATA: Range<usize> = 4..8;
    /// Bytes 1–7: the data of a segment.
    pub(super) const SEGMENT: Range<usize> = 1..8;
    /// Bytes 1–2: the CRC of a block transfer's end frame.
    pub(super) const CRC: Range<usize> = 1..3;
    /// Byte 1: `ackseq` of a sub-block confirmation.
    pub(super) const ACKSEQ: usize = 1;
    /// Byte 2: `blksize` of a sub-block confirmation.
    pub(super) const ACK_BLKSIZE: usize = 2;
    /// Byte 4: `blksize` of a block initiate (upload request, download
    /// response).
    pub(super) const INITIATE_BLKSIZE: usize = 4;
    /// Byte 5: `pst`, the protocol switch threshold of a block upload
    /// initiate request.
    pub(super) const PST: usize = 5;
}

/// The length of every SDO frame's data: 8 bytes (CiA 301 §7.2.4.3).
pub const SDO_LEN: usize = field::DATA.end;

/// The most bytes one segment carries (CiA 301 §7.2.4.3.4).
pub const SEGMENT_MAX: usize = 7;

/// The most segments in one block (`blksize`, CiA 301 §7.2.4.3.9).
pub const BLKSIZE_MAX: u8 = 127;

const WHAT: What = What::SdoFrame;

/// Which way an SDO frame travels (CiA 301 §7.2.4.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum SdoDirection {
    /// Client → server, on COB-ID 0x600 + node.
    Request,
    /// Server → client, on COB-ID 0x580 + node.
    Response,
}

impl SdoDirection {
    /// Return the name SPEC §7.3's `direction` writes: `request` or
    /// `response`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            SdoDirection::Request => "request",
            SdoDirection::Response => "response",
        }
    }
}

impl fmt::Display for SdoDirection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The service an SDO frame belongs to, as SPEC §7.3's `service` names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum SdoService {
    /// Initiate an SDO download (ccs 1, scs 3).
    InitiateDownload,
    /// A segment of a download (ccs 0, scs 1).
    DownloadSegment,
    /// Initiate an SDO upload (ccs 2, scs 2).
    InitiateUpload,
    /// A segment of an upload (ccs 3, scs 0).
    UploadSegment,
    /// Abort an SDO transfer (cs 4).
    Abort,
    /// The control frames of a block download (ccs 6, scs 5).
    BlockDownload,
    /// The control frames of a block upload (ccs 5, scs 6).
    BlockUpload,
    /// A segment inside a block (bit 7 `c`, bits 6–0 the sequence number);
    /// told apart only by the transfer's state.
    BlockSegment,
    /// Command specifier 7, or a block sub-command CiA 301 does not define.
    Unknown,
}

impl SdoService {
    /// Every service, in the order of SPEC §7.3.
    pub const ALL: [SdoService; 9] = [
        SdoService::InitiateDownload,
        SdoService::DownloadSegment,
        SdoService::InitiateUpload,
        SdoService::UploadSegment,
        SdoService::Abort,
        SdoService::BlockDownload,
        SdoService::BlockUpload,
        SdoService::BlockSegment,
        SdoService::Unknown,
    ];

    /// Return the service of a request or response whose command byte is
    /// `command` (SPEC §7.1's table), without a transfer's context: a block
    /// segment is read as the request or response its bits also spell.
    #[must_use]
    pub const fn of(direction: SdoDirection, command: u8) -> SdoService {
        let specifier = command >> 5;
        match (direction, specifier) {
            (_, 4) => SdoService::Abort,
            (SdoDirection::Request, 0) | (SdoDirection::Response, 1) => SdoService::DownloadSegment,
            (SdoDirection::Request, 1) | (SdoDirection::Response, 3) => {
                SdoService::InitiateDownload
            }
            (SdoDirection::Request, 2) | (SdoDirection::Response, 2) => SdoService::InitiateUpload,
            (SdoDirection::Request, 3) | (SdoDirection::Response, 0) => SdoService::UploadSegment,
            (SdoDirection::Request, 5) => SdoService::BlockUpload,
            (SdoDirection::Response, 5) if command & 0b11 == 0b11 => SdoService::Unknown,
            (SdoDirection::Response, 5) | (SdoDirection::Request, 6) => SdoService::BlockDownload,
            (SdoDirection::Response, 6) => SdoService::BlockUpload,
            _ => SdoService::Unknown,
        }
    }

    /// Return the name SPEC §7.3's `service` writes, e.g.
    /// `initiate_upload`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            SdoService::InitiateDownload => "initiate_download",
            SdoService::DownloadSegment => "download_segment",
            SdoService::InitiateUpload => "initiate_upload",
            SdoService::UploadSegment => "upload_segment",
            SdoService::Abort => "abort",
            SdoService::BlockDownload => "block_download",
            SdoService::BlockUpload => "block_upload",
            SdoService::BlockSegment => "block_segment",
            SdoService::Unknown => "unknown",
        }
    }

    /// Return whether frames of this service carry a multiplexer (index and
    /// sub-index in bytes 1–3) when they are an initiate or an abort.
    #[must_use]
    pub const fn has_multiplexer(self) -> bool {
        matches!(
            self,
            SdoService::InitiateDownload
                | SdoService::InitiateUpload
                | SdoService::Abort
                | SdoService::BlockDownload
                | SdoService::BlockUpload
        )
    }
}

impl fmt::Display for SdoService {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The sub-command of a block transfer's control frame, as SPEC §7.3's
/// `subcommand` names it (CiA 301 §7.2.4.3.9–§7.2.4.3.16).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum BlockSubcommand {
    /// Initiate the block transfer.
    Initiate,
    /// Start the upload (block upload request, cs 3).
    Start,
    /// End the block transfer.
    End,
    /// Confirm a sub-block (`ackseq`, next `blksize`).
    Ack,
}

impl BlockSubcommand {
    /// Return the name SPEC §7.3's `subcommand` writes.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            BlockSubcommand::Initiate => "initiate",
            BlockSubcommand::Start => "start",
            BlockSubcommand::End => "end",
            BlockSubcommand::Ack => "ack",
        }
    }
}

impl fmt::Display for BlockSubcommand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The object an SDO transfer reads or writes: index and sub-index, the
/// "multiplexer" of CiA 301 §7.2.4.3 (bytes 1–3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SdoMultiplexer {
    /// The object index, e.g. `0x1003`.
    pub index: u16,
    /// The sub-index.
    pub subindex: u8,
}

impl SdoMultiplexer {
    /// Return the multiplexer of `index`, sub-index `subindex`.
    #[must_use]
    pub const fn new(index: u16, subindex: u8) -> Self {
        SdoMultiplexer { index, subindex }
    }
}

impl fmt::Display for SdoMultiplexer {
    /// `1008h.00`: CiA's notation, index and sub-index in hex.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04X}h.{:02X}", self.index, self.subindex)
    }
}

/// What an initiate download request or initiate upload response says
/// about the data (bits `e`, `s`, `n` and bytes 4–7, CiA 301 §7.2.4.3.3,
/// §7.2.4.3.6; SPEC §7.1).
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
        /// (SPEC §7.1).
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
    fn read(command: u8, data: [u8; 4]) -> Self {
        let expedited = command & 0b10 != 0;
        let size_indicated = command & 0b01 != 0;
        let n = (command >> 2) & 0b11;
        match (expedited, size_indicated) {
            (true, true) => {
                let len = 4 - n;
                let mut bytes = [0; 4];
                bytes[..usize::from(len)].copy_from_slice(&data[..usize::from(len)]);
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
    fn write(&self) -> (u8, [u8; 4]) {
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
    bytes: [u8; SEGMENT_MAX],
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

    fn read(n: u8, segment: &[u8]) -> Self {
        let mut bytes = [0; SEGMENT_MAX];
        bytes.copy_from_slice(&segment[..SEGMENT_MAX]);
        let len = SEGMENT_MAX as u8 - n;
        bytes[usize::from(len)..].fill(0);
        SdoSegmentData { bytes, len }
    }
}

impl core::ops::Deref for SdoSegmentData {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        self.as_slice()
    }
}

/// A zero-copy view over an SDO frame's data (CiA 301 §7.2.4.3; SPEC §7.1):
/// the fields every service shares.
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
    pub fn new_checked(buffer: T) -> Result<Self> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`SDO_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<()> {
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
    pub fn multiplexer(&self) -> SdoMultiplexer {
        SdoMultiplexer::new(self.index(), self.subindex())
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
        multiplexer: SdoMultiplexer,
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
    pub fn set_multiplexer(&mut self, multiplexer: SdoMultiplexer) {
        let buf = self.buffer.as_mut();
        LittleEndian::write_u16(&mut buf[field::INDEX], multiplexer.index);
        buf[field::SUBINDEX] = multiplexer.subindex;
    }

    /// Set bytes 4–7.
    #[inline]
    pub fn set_data_field(&mut self, data: [u8; 4]) {
        self.buffer.as_mut()[field::DATA].copy_from_slice(&data);
    }
}

/// The fields SPEC §7.3 writes for one frame, whichever its service.
///
/// Every `Option` is `Some` exactly for the services whose frames carry
/// that field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SdoFields<'a> {
    /// Index and sub-index: initiates and aborts.
    pub multiplexer: Option<SdoMultiplexer>,
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

/// An SDO request, client → server (CiA 301 §7.2.4.3; SPEC §7.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SdoRequest {
    /// ccs 1: initiate a download (write) of an object.
    InitiateDownload {
        /// The object.
        multiplexer: SdoMultiplexer,
        /// Expedited data or the segmented size.
        data: SdoInitiateData,
    },
    /// ccs 0: one segment of a download.
    DownloadSegment {
        /// `t`: 0 for the first segment, alternating.
        toggle: bool,
        /// The segment's data.
        data: SdoSegmentData,
        /// `c`: no more segments follow.
        last: bool,
    },
    /// ccs 2: initiate an upload (read) of an object.
    InitiateUpload {
        /// The object.
        multiplexer: SdoMultiplexer,
    },
    /// ccs 3: ask for the next upload segment.
    UploadSegment {
        /// `t` of the segment asked for.
        toggle: bool,
    },
    /// ccs 4: abort the transfer.
    Abort {
        /// The multiplexer the abort carries.
        multiplexer: SdoMultiplexer,
        /// Why.
        code: SdoAbortCode,
    },
    /// ccs 5, cs 0: initiate a block upload.
    BlockUploadInitiate {
        /// The object.
        multiplexer: SdoMultiplexer,
        /// `cc`: the client can check a CRC.
        crc_supported: bool,
        /// The segments per block the client accepts.
        blksize: u8,
        /// The protocol switch threshold: at most this many bytes may be
        /// answered with a normal upload instead (0: no switch).
        pst: u8,
    },
    /// ccs 5, cs 1: the client confirms the end of a block upload.
    BlockUploadEnd,
    /// ccs 5, cs 2: the client confirms a sub-block.
    BlockUploadAck {
        /// The sequence number of the last segment received in order.
        ackseq: u8,
        /// The segments of the next block.
        blksize: u8,
    },
    /// ccs 5, cs 3: the client starts the upload of the segments.
    BlockUploadStart,
    /// ccs 6, cs 0: initiate a block download.
    BlockDownloadInitiate {
        /// The object.
        multiplexer: SdoMultiplexer,
        /// `cc`: the client can send a CRC.
        crc_supported: bool,
        /// The data size, when `s` = 1.
        size: Option<u32>,
    },
    /// ccs 6, cs 1: the client ends a block download.
    BlockDownloadEnd {
        /// `n`: bytes of the last segment without data.
        unused: u8,
        /// The CRC of all the data (0 when CRC is not used).
        crc: u16,
    },
}

/// An SDO response, server → client (CiA 301 §7.2.4.3; SPEC §7.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SdoResponse {
    /// scs 0: one segment of an upload.
    UploadSegment {
        /// `t`: the toggle of the request it answers.
        toggle: bool,
        /// The segment's data.
        data: SdoSegmentData,
        /// `c`: no more segments follow.
        last: bool,
    },
    /// scs 1: a download segment received.
    DownloadSegment {
        /// `t`: the toggle of the segment it confirms.
        toggle: bool,
    },
    /// scs 2: the answer to an initiate upload.
    InitiateUpload {
        /// The object.
        multiplexer: SdoMultiplexer,
        /// Expedited data or the segmented size.
        data: SdoInitiateData,
    },
    /// scs 3: the answer to an initiate download.
    InitiateDownload {
        /// The object.
        multiplexer: SdoMultiplexer,
    },
    /// scs 4: abort the transfer.
    Abort {
        /// The multiplexer the abort carries.
        multiplexer: SdoMultiplexer,
        /// Why.
        code: SdoAbortCode,
    },
    /// scs 5, ss 0: the answer to a block download initiate.
    BlockDownloadInitiate {
        /// The object.
        multiplexer: SdoMultiplexer,
        /// `sc`: the server can check a CRC.
        crc_supported: bool,
        /// The segments per block the server accepts.
        blksize: u8,
    },
    /// scs 5, ss 1: the server confirms the end of a block download.
    BlockDownloadEnd,
    /// scs 5, ss 2: the server confirms a sub-block.
    BlockDownloadAck {
        /// The sequence number of the last segment received in order.
        ackseq: u8,
        /// The segments of the next block.
        blksize: u8,
    },
    /// scs 6, ss 0: the answer to a block upload initiate.
    BlockUploadInitiate {
        /// The object.
        multiplexer: SdoMultiplexer,
        /// `sc`: the server sends a CRC.
        crc_supported: bool,
        /// The data size, when `s` = 1.
        size: Option<u32>,
    },
    /// scs 6, ss 1: the server ends a block upload.
    BlockUploadEnd {
        /// `n`: bytes of the last segment without data.
        unused: u8,
        /// The CRC of all the data (0 when CRC is not used).
        crc: u16,
    },
}

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

fn invalid(what: What, found: u8, expected: &'static str) -> Error {
    Error::InvalidValue {
        what,
        found: u32::from(found),
        expected,
    }
}

/// `n` of a segment: bits 3–1.
const fn segment_unused(command: u8) -> u8 {
    (command >> 1) & 0b111
}

const TOGGLE: u8 = 0b1_0000;
const LAST: u8 = 0b1;
const CRC_SUPPORTED: u8 = 0b100;

fn abort_of(frame: &SdoFrame<&[u8]>) -> (SdoMultiplexer, SdoAbortCode) {
    (
        frame.multiplexer(),
        SdoAbortCode::new(u32::from_le_bytes(frame.data_field())),
    )
}

impl SdoRequest {
    /// Read a request from a frame's data. A block segment is not a
    /// request: [`SdoBlockSegment::parse`] reads one.
    ///
    /// # Errors
    ///
    /// [`Error::Length`] for fewer than 8 bytes; [`Error::InvalidValue`] for
    /// command specifier 7.
    pub fn parse(data: &[u8]) -> Result<Self> {
        let frame = SdoFrame::new_checked(data)?;
        let command = frame.command();
        let multiplexer = frame.multiplexer();
        Ok(match frame.specifier() {
            0 => SdoRequest::DownloadSegment {
                toggle: command & TOGGLE != 0,
                data: SdoSegmentData::read(segment_unused(command), frame.segment_field()),
                last: command & LAST != 0,
            },
            1 => SdoRequest::InitiateDownload {
                multiplexer,
                data: SdoInitiateData::read(command, frame.data_field()),
            },
            2 => SdoRequest::InitiateUpload { multiplexer },
            3 => SdoRequest::UploadSegment {
                toggle: command & TOGGLE != 0,
            },
            4 => {
                let (multiplexer, code) = abort_of(&frame);
                SdoRequest::Abort { multiplexer, code }
            }
            5 => match command & 0b11 {
                0 => SdoRequest::BlockUploadInitiate {
                    multiplexer,
                    crc_supported: command & CRC_SUPPORTED != 0,
                    blksize: data[field::INITIATE_BLKSIZE],
                    pst: data[field::PST],
                },
                1 => SdoRequest::BlockUploadEnd,
                2 => {
                    let (ackseq, blksize) = frame.block_ack();
                    SdoRequest::BlockUploadAck { ackseq, blksize }
                }
                _ => SdoRequest::BlockUploadStart,
            },
            6 => match command & 0b1 {
                0 => {
                    let (crc_supported, size) = frame.sized_block_initiate();
                    SdoRequest::BlockDownloadInitiate {
                        multiplexer,
                        crc_supported,
                        size,
                    }
                }
                _ => {
                    let (unused, crc) = frame.block_end();
                    SdoRequest::BlockDownloadEnd { unused, crc }
                }
            },
            _ => {
                return Err(invalid(
                    What::SdoCommandSpecifier,
                    command >> 5,
                    "client command specifiers 0..=6",
                ))
            }
        })
    }

    /// Return the frame's 8 data bytes; reserved bits and bytes are 0.
    #[must_use]
    pub fn to_bytes(&self) -> [u8; SDO_LEN] {
        let mut out = [0u8; SDO_LEN];
        let mut frame = SdoFrame::new_unchecked(&mut out[..]);
        match *self {
            SdoRequest::DownloadSegment { toggle, data, last } => {
                frame.set_command(segment_command(0, toggle, &data, last));
                out[field::SEGMENT].copy_from_slice(&data.bytes);
            }
            SdoRequest::InitiateDownload { multiplexer, data } => {
                let (bits, bytes) = data.write();
                frame.set_command((1 << 5) | bits);
                frame.set_multiplexer(multiplexer);
                frame.set_data_field(bytes);
            }
            SdoRequest::InitiateUpload { multiplexer } => {
                frame.set_command(2 << 5);
                frame.set_multiplexer(multiplexer);
            }
            SdoRequest::UploadSegment { toggle } => {
                frame.set_command((3 << 5) | if toggle { TOGGLE } else { 0 });
            }
            SdoRequest::Abort { multiplexer, code } => {
                frame.set_command(4 << 5);
                frame.set_multiplexer(multiplexer);
                frame.set_data_field(code.get().to_le_bytes());
            }
            SdoRequest::BlockUploadInitiate {
                multiplexer,
                crc_supported,
                blksize,
                pst,
            } => {
                frame.set_command((5 << 5) | crc_bit(crc_supported));
                frame.set_multiplexer(multiplexer);
                out[field::INITIATE_BLKSIZE] = blksize;
                out[field::PST] = pst;
            }
            SdoRequest::BlockUploadEnd => frame.set_command((5 << 5) | 1),
            SdoRequest::BlockUploadAck { ackseq, blksize } => {
                frame.set_block_ack(ackseq, blksize);
            }
            SdoRequest::BlockUploadStart => frame.set_command((5 << 5) | 3),
            SdoRequest::BlockDownloadInitiate {
                multiplexer,
                crc_supported,
                size,
            } => frame.set_sized_block_initiate(multiplexer, crc_supported, size),
            SdoRequest::BlockDownloadEnd { unused, crc } => frame.set_block_end(unused, crc),
        }
        out
    }

    /// Return the service (SPEC §7.3).
    #[must_use]
    pub fn service(&self) -> SdoService {
        SdoService::of(SdoDirection::Request, self.to_bytes()[0])
    }

    /// Return the fields SPEC §7.3 writes for this request.
    #[must_use]
    pub fn fields(&self) -> SdoFields<'_> {
        let mut f = SdoFields::default();
        match self {
            SdoRequest::InitiateDownload { multiplexer, data } => {
                f.multiplexer = Some(*multiplexer);
                initiate_fields(&mut f, data);
            }
            SdoRequest::DownloadSegment { toggle, data, last } => {
                f.toggle = Some(*toggle);
                f.value = Some(data.as_slice());
                f.last = Some(*last);
            }
            SdoRequest::InitiateUpload { multiplexer } => f.multiplexer = Some(*multiplexer),
            SdoRequest::UploadSegment { toggle } => f.toggle = Some(*toggle),
            SdoRequest::Abort { multiplexer, code } => {
                f.multiplexer = Some(*multiplexer);
                f.abort_code = Some(*code);
            }
            SdoRequest::BlockUploadInitiate {
                multiplexer,
                crc_supported,
                blksize,
                ..
            } => {
                f.subcommand = Some(BlockSubcommand::Initiate);
                f.multiplexer = Some(*multiplexer);
                f.crc_supported = Some(*crc_supported);
                f.blksize = Some(*blksize);
            }
            SdoRequest::BlockUploadEnd => f.subcommand = Some(BlockSubcommand::End),
            SdoRequest::BlockUploadAck { ackseq, blksize } => {
                f.subcommand = Some(BlockSubcommand::Ack);
                f.ackseq = Some(*ackseq);
                f.blksize = Some(*blksize);
            }
            SdoRequest::BlockUploadStart => f.subcommand = Some(BlockSubcommand::Start),
            SdoRequest::BlockDownloadInitiate {
                multiplexer,
                crc_supported,
                size,
            } => {
                f.subcommand = Some(BlockSubcommand::Initiate);
                f.multiplexer = Some(*multiplexer);
                f.crc_supported = Some(*crc_supported);
                f.size = Some(*size);
            }
            SdoRequest::BlockDownloadEnd { crc, .. } => {
                f.subcommand = Some(BlockSubcommand::End);
                f.crc = Some(*crc);
            }
        }
        f
    }
}

impl SdoResponse {
    /// Read a response from a frame's data. A block segment is not a
    /// response: [`SdoBlockSegment::parse`] reads one.
    ///
    /// # Errors
    ///
    /// [`Error::Length`] for fewer than 8 bytes; [`Error::InvalidValue`] for
    /// command specifier 7 and for sub-command 3 of scs 5.
    pub fn parse(data: &[u8]) -> Result<Self> {
        let frame = SdoFrame::new_checked(data)?;
        let command = frame.command();
        let multiplexer = frame.multiplexer();
        Ok(match frame.specifier() {
            0 => SdoResponse::UploadSegment {
                toggle: command & TOGGLE != 0,
                data: SdoSegmentData::read(segment_unused(command), frame.segment_field()),
                last: command & LAST != 0,
            },
            1 => SdoResponse::DownloadSegment {
                toggle: command & TOGGLE != 0,
            },
            2 => SdoResponse::InitiateUpload {
                multiplexer,
                data: SdoInitiateData::read(command, frame.data_field()),
            },
            3 => SdoResponse::InitiateDownload { multiplexer },
            4 => {
                let (multiplexer, code) = abort_of(&frame);
                SdoResponse::Abort { multiplexer, code }
            }
            5 => match command & 0b11 {
                0 => SdoResponse::BlockDownloadInitiate {
                    multiplexer,
                    crc_supported: command & CRC_SUPPORTED != 0,
                    blksize: data[field::INITIATE_BLKSIZE],
                },
                1 => SdoResponse::BlockDownloadEnd,
                2 => {
                    let (ackseq, blksize) = frame.block_ack();
                    SdoResponse::BlockDownloadAck { ackseq, blksize }
                }
                sub => {
                    return Err(invalid(
                        What::SdoBlockSubcommand,
                        sub,
                        "block download sub-commands 0, 1, 2",
                    ))
                }
            },
            6 => match command & 0b1 {
                0 => {
                    let (crc_supported, size) = frame.sized_block_initiate();
                    SdoResponse::BlockUploadInitiate {
                        multiplexer,
                        crc_supported,
                        size,
                    }
                }
                _ => {
                    let (unused, crc) = frame.block_end();
                    SdoResponse::BlockUploadEnd { unused, crc }
                }
            },
            _ => {
                return Err(invalid(
                    What::SdoCommandSpecifier,
                    command >> 5,
                    "server command specifiers 0..=6",
                ))
            }
        })
    }

    /// Return the frame's 8 data bytes; reserved bits and bytes are 0.
    #[must_use]
    pub fn to_bytes(&self) -> [u8; SDO_LEN] {
        let mut out = [0u8; SDO_LEN];
        let mut frame = SdoFrame::new_unchecked(&mut out[..]);
        match *self {
            SdoResponse::UploadSegment { toggle, data, last } => {
                frame.set_command(segment_command(0, toggle, &data, last));
                out[field::SEGMENT].copy_from_slice(&data.bytes);
            }
            SdoResponse::DownloadSegment { toggle } => {
                frame.set_command((1 << 5) | if toggle { TOGGLE } else { 0 });
            }
            SdoResponse::InitiateUpload { multiplexer, data } => {
                let (bits, bytes) = data.write();
                frame.set_command((2 << 5) | bits);
                frame.set_multiplexer(multiplexer);
                frame.set_data_field(bytes);
            }
            SdoResponse::InitiateDownload { multiplexer } => {
                frame.set_command(3 << 5);
                frame.set_multiplexer(multiplexer);
            }
            SdoResponse::Abort { multiplexer, code } => {
                frame.set_command(4 << 5);
                frame.set_multiplexer(multiplexer);
                frame.set_data_field(code.get().to_le_bytes());
            }
            SdoResponse::BlockDownloadInitiate {
                multiplexer,
                crc_supported,
                blksize,
            } => {
                frame.set_command((5 << 5) | crc_bit(crc_supported));
                frame.set_multiplexer(multiplexer);
                out[field::INITIATE_BLKSIZE] = blksize;
            }
            SdoResponse::BlockDownloadEnd => frame.set_command((5 << 5) | 1),
            SdoResponse::BlockDownloadAck { ackseq, blksize } => {
                frame.set_block_ack(ackseq, blksize);
            }
            SdoResponse::BlockUploadInitiate {
                multiplexer,
                crc_supported,
                size,
            } => frame.set_sized_block_initiate(multiplexer, crc_supported, size),
            SdoResponse::BlockUploadEnd { unused, crc } => frame.set_block_end(unused, crc),
        }
        out
    }

    /// Return the service (SPEC §7.3).
    #[must_use]
    pub fn service(&self) -> SdoService {
        SdoService::of(SdoDirection::Response, self.to_bytes()[0])
    }

    /// Return the fields SPEC §7.3 writes for this response.
    #[must_use]
    pub fn fields(&self) -> SdoFields<'_> {
        let mut f = SdoFields::default();
        match self {
            SdoResponse::UploadSegment { toggle, data, last } => {
                f.toggle = Some(*toggle);
                f.value = Some(data.as_slice());
                f.last = Some(*last);
            }
            SdoResponse::DownloadSegment { toggle } => f.toggle = Some(*toggle),
            SdoResponse::InitiateUpload { multiplexer, data } => {
                f.multiplexer = Some(*multiplexer);
                initiate_fields(&mut f, data);
            }
            SdoResponse::InitiateDownload { multiplexer } => f.multiplexer = Some(*multiplexer),
            SdoResponse::Abort { multiplexer, code } => {
                f.multiplexer = Some(*multiplexer);
                f.abort_code = Some(*code);
            }
            SdoResponse::BlockDownloadInitiate {
                multiplexer,
                crc_supported,
                blksize,
            } => {
                f.subcommand = Some(BlockSubcommand::Initiate);
                f.multiplexer = Some(*multiplexer);
                f.crc_supported = Some(*crc_supported);
                f.blksize = Some(*blksize);
            }
            SdoResponse::BlockDownloadEnd => f.subcommand = Some(BlockSubcommand::End),
            SdoResponse::BlockDownloadAck { ackseq, blksize } => {
                f.subcommand = Some(BlockSubcommand::Ack);
                f.ackseq = Some(*ackseq);
                f.blksize = Some(*blksize);
            }
            SdoResponse::BlockUploadInitiate {
                multiplexer,
                crc_supported,
                size,
            } => {
                f.subcommand = Some(BlockSubcommand::Initiate);
                f.multiplexer = Some(*multiplexer);
                f.crc_supported = Some(*crc_supported);
                f.size = Some(*size);
            }
            SdoResponse::BlockUploadEnd { crc, .. } => {
                f.subcommand = Some(BlockSubcommand::End);
                f.crc = Some(*crc);
            }
        }
        f
    }
}

impl SdoBlockSegment {
    /// Read a block segment from a frame's data.
    ///
    /// # Errors
    ///
    /// [`Error::Length`] for fewer than 8 bytes.
    pub fn parse(data: &[u8]) -> Result<Self> {
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

    /// Return the fields SPEC §7.3 writes for a block segment.
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

fn initiate_fields<'a>(f: &mut SdoFields<'a>, data: &'a SdoInitiateData) {
    f.expedited = Some(data.is_expedited());
    f.size = Some(data.size());
    if data.is_expedited() {
        f.value = Some(data.data());
    }
}

const fn crc_bit(supported: bool) -> u8 {
    if supported {
        CRC_SUPPORTED
    } else {
        0
    }
}

fn segment_command(specifier: u8, toggle: bool, data: &SdoSegmentData, last: bool) -> u8 {
    (specifier << 5)
        | if toggle { TOGGLE } else { 0 }
        | (data.unused() << 1)
        | if last { LAST } else { 0 }
}

/// The CRC of a block transfer: CRC-16 with polynomial x^16 + x^12 + x^5 +
/// 1 (0x1021), initial value 0, no reflection, over all the data
/// (CiA 301 §7.2.4.3.16, the "CRC-16-CCITT/XMODEM" variant).
///
/// ```
/// use motionwire::canopen::sdo::BlockCrc;
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
