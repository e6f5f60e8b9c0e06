//! An SDO response, server → client: every service's frame as an owned
//! value, read with [`SdoResponse::parse`] and written with
//! [`SdoResponse::to_bytes`] (CiA 301 §7.2.4.3; docs/canopen.md#sdo).

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

/// An SDO response, server → client (CiA 301 §7.2.4.3; docs/canopen.md#sdo).
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
        multiplexer: ObjectAddress,
        /// Expedited data or the segmented size.
        data: SdoInitiateData,
    },
    /// scs 3: the answer to an initiate download.
    InitiateDownload {
        /// The object.
        multiplexer: ObjectAddress,
    },
    /// scs 4: abort the transfer.
    Abort {
        /// The multiplexer the abort carries.
        multiplexer: ObjectAddress,
        /// Why.
        code: SdoAbortCode,
    },
    /// scs 5, ss 0: the answer to a block download initiate.
    BlockDownloadInitiate {
        /// The object.
        multiplexer: ObjectAddress,
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
        multiplexer: ObjectAddress,
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

impl SdoResponse {
    /// Read a response from a frame's data. A block segment is not a
    /// response: [`SdoBlockSegment::parse`](super::SdoBlockSegment::parse) reads one.
    ///
    /// # Errors
    ///
    /// [`FrameError::Length`](crate::FrameError::Length) for fewer than 8 bytes;
    /// [`FrameError::Content`](crate::FrameError::Content) for
    /// command specifier 7 and for sub-command 3 of scs 5.
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

    /// Return the service (docs/output.md#sdo).
    #[must_use]
    pub fn service(&self) -> SdoService {
        SdoService::of(SdoParty::Server, self.to_bytes()[0])
    }

    /// Return the fields of the `sdo` key (docs/output.md#sdo) for this
    /// response.
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
