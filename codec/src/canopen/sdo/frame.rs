//! SDO frames: the 8 data bytes of a request (client → server, COB-ID
//! 0x600 + node) or a response (server → client, 0x580 + node)
//! (CiA 301 §7.2.4.3; docs/canopen.md#sdo).
//!
//! [`SdoFrame`] is the zero-copy view over the bytes, with the fields every
//! service shares; [`SdoRequest`], [`SdoResponse`] and [`SdoBlockSegment`]
//! are the owned values, each with `parse` and `to_bytes`. A segment inside
//! a block transfer cannot be told from a request or response by its bytes
//! alone: [`SdoTracker`](super::SdoTracker) knows when one is due.
//!
//! The module's files: `view.rs` ([`SdoFrame`] and [`SdoFields`]),
//! `data.rs` (what initiate and segment frames carry), `request.rs`,
//! `response.rs`, and `block.rs` (block sub-commands, segments and the
//! CRC); here, the byte offsets they all share (`mod field`), a frame's
//! sender and service, and the command-byte helpers. The multiplexer of
//! a frame is an [`ObjectAddress`].
//!
//! ```
//! use motionwire_codec::canopen::sdo::{SdoInitiateData, SdoRequest, SdoResponse};
//! use motionwire_codec::canopen::ObjectAddress;
//!
//! // A client reads 1008h sub 0 (manufacturer device name)…
//! let request = SdoRequest::InitiateUpload { multiplexer: ObjectAddress::new(0x1008, 0) };
//! assert_eq!(request.to_bytes(), [0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]);
//! assert_eq!(SdoRequest::parse(&request.to_bytes())?, request);
//!
//! // …and the server answers "segmented, 10 bytes follow".
//! let response = SdoResponse::parse(&[0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0])?;
//! assert_eq!(response, SdoResponse::InitiateUpload {
//!     multiplexer: ObjectAddress::new(0x1008, 0),
//!     data: SdoInitiateData::Segmented { size: Some(10) },
//! });
//!
//! // A short frame is an error that says how short, never a panic.
//! assert!(SdoResponse::parse(&[0x41, 0x08, 0x10]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use core::fmt;

use crate::canopen::{ObjectAddress, SdoAbortCode};
use crate::error::What;
use crate::{FrameError, ValueError};

mod block;
mod data;
mod request;
mod response;
mod view;

pub use block::{BlockCrc, BlockSubcommand, SdoBlockSegment};
pub use data::{SdoInitiateData, SdoSegmentData};
pub use request::SdoRequest;
pub use response::SdoResponse;
pub use view::{SdoFields, SdoFrame};

pub(super) mod field {
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

const WHAT: What = What::SdoFrame;

/// The side of an SDO channel that sent a frame (CiA 301 §7.2.4.1, the
/// SDO client/server model): the client sends requests, on COB-ID
/// 0x600 + node; the server sends responses, on 0x580 + node. One value
/// says both who sent a frame and which of the two it is.
///
/// ```
/// use motionwire_codec::canopen::sdo::SdoParty;
///
/// // The `direction` of a frame the client sends (docs/output.md#sdo)…
/// assert_eq!(SdoParty::Client.direction_name(), "request");
/// // …and the `by` of an abort the server sends (docs/summary.md#sdo).
/// assert_eq!(SdoParty::Server.name(), "server");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum SdoParty {
    /// The client (the master, a tool): sends requests, client → server,
    /// on COB-ID 0x600 + node.
    Client,
    /// The server (the device): sends responses, server → client, on
    /// COB-ID 0x580 + node.
    Server,
}

impl SdoParty {
    /// Return the name `by` writes (docs/summary.md#sdo): `client` or `server`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            SdoParty::Client => "client",
            SdoParty::Server => "server",
        }
    }

    /// Return the name `direction` writes (docs/output.md#sdo) for a frame this
    /// side sends: `request` (client) or `response` (server).
    #[must_use]
    pub const fn direction_name(self) -> &'static str {
        match self {
            SdoParty::Client => "request",
            SdoParty::Server => "response",
        }
    }
}

impl fmt::Display for SdoParty {
    /// Write the side's name, `client` or `server`, as the program's abort
    /// text does (docs/output.md#sdo-text: `aborted by the server`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The service an SDO frame belongs to, as `service` names it
/// (docs/output.md#sdo).
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
    /// Every service, in the order of docs/output.md#sdo.
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
    /// `command` (the table of docs/canopen.md#sdo), without a transfer's
    /// context: a block segment is read as the request or response its bits
    /// also spell.
    #[must_use]
    pub const fn of(sender: SdoParty, command: u8) -> SdoService {
        let specifier = command >> 5;
        match (sender, specifier) {
            (_, 4) => SdoService::Abort,
            (SdoParty::Client, 0) | (SdoParty::Server, 1) => SdoService::DownloadSegment,
            (SdoParty::Client, 1) | (SdoParty::Server, 3) => SdoService::InitiateDownload,
            (SdoParty::Client, 2) | (SdoParty::Server, 2) => SdoService::InitiateUpload,
            (SdoParty::Client, 3) | (SdoParty::Server, 0) => SdoService::UploadSegment,
            (SdoParty::Client, 5) => SdoService::BlockUpload,
            (SdoParty::Server, 5) if command & 0b11 == 0b11 => SdoService::Unknown,
            (SdoParty::Server, 5) | (SdoParty::Client, 6) => SdoService::BlockDownload,
            (SdoParty::Server, 6) => SdoService::BlockUpload,
            _ => SdoService::Unknown,
        }
    }

    /// Return the name `service` writes (docs/output.md#sdo), e.g.
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

fn invalid(what: What, found: u8, expected: &'static str) -> FrameError {
    FrameError::Content(ValueError {
        what,
        found: u32::from(found),
        expected,
    })
}

/// `n` of a segment: bits 3–1.
pub(super) const fn segment_unused(command: u8) -> u8 {
    (command >> 1) & 0b111
}

/// `t`, the toggle bit of a segment and its confirmation.
pub(super) const TOGGLE: u8 = 0b1_0000;
/// `c`, the last segment.
pub(super) const LAST: u8 = 0b1;
/// `cc`/`sc`, the CRC support of a block initiate.
pub(super) const CRC_SUPPORTED: u8 = 0b100;

fn abort_of(frame: &SdoFrame<&[u8]>) -> (ObjectAddress, SdoAbortCode) {
    (
        frame.multiplexer(),
        SdoAbortCode::new(u32::from_le_bytes(frame.data_field())),
    )
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
