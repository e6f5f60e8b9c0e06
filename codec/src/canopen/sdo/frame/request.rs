//! An SDO request, client → server: every service's frame as an owned
//! value, read with [`SdoRequest::parse`] and written with
//! [`SdoRequest::to_bytes`] (CiA 301 §7.2.4.3; docs/canopen.md#sdo).

use super::common::{abort_of, initiate_fields, segment_command};
use super::data::{SdoInitiateData, SdoSegmentData};
use super::layout::{
    crc_bit, field, invalid, segment_unused, CRC_SUPPORTED, LAST, SDO_LEN, TOGGLE,
};
use super::party::{BlockSubcommand, SdoParty, SdoService};
use super::view::{SdoFields, SdoFrame};
use crate::canopen::ObjectAddress;
use crate::canopen::SdoAbortCode;
use crate::error::What;
use crate::{FrameError, Result};

/// An SDO request, client → server (CiA 301 §7.2.4.3; docs/canopen.md#sdo).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SdoRequest {
    /// ccs 1: initiate a download (write) of an object.
    InitiateDownload {
        /// The object.
        multiplexer: ObjectAddress,
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
        multiplexer: ObjectAddress,
    },
    /// ccs 3: ask for the next upload segment.
    UploadSegment {
        /// `t` of the segment asked for.
        toggle: bool,
    },
    /// ccs 4: abort the transfer.
    Abort {
        /// The multiplexer the abort carries.
        multiplexer: ObjectAddress,
        /// Why.
        code: SdoAbortCode,
    },
    /// ccs 5, cs 0: initiate a block upload.
    BlockUploadInitiate {
        /// The object.
        multiplexer: ObjectAddress,
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
        multiplexer: ObjectAddress,
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

impl SdoRequest {
    /// Read a request from a frame's data. A block segment is not a
    /// request: [`SdoBlockSegment::parse`](super::SdoBlockSegment::parse) reads one.
    ///
    /// # Errors
    ///
    /// [`FrameError::Length`](crate::FrameError::Length) for fewer than 8 bytes;
    /// [`FrameError::Content`](crate::FrameError::Content) for
    /// command specifier 7.
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, FrameError> {
        Self::read(data)
    }

    /// [`parse`](Self::parse), always in line: the tracker's message
    /// ([`SdoMessage`](super::super::SdoMessage)) is made from the frame's
    /// bytes where it is read, each field written where it is kept.
    #[inline(always)]
    pub(in crate::canopen::sdo) fn read(data: &[u8]) -> Result<Self, FrameError> {
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

    /// Return the service (docs/output.md#sdo).
    #[must_use]
    pub fn service(&self) -> SdoService {
        SdoService::of(SdoParty::Client, self.to_bytes()[0])
    }

    /// Return the fields of the `sdo` key (docs/output.md#sdo) for this
    /// request.
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
