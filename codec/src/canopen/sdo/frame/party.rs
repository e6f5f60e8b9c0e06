//! Who sent an SDO frame and the service it belongs to: [`SdoParty`],
//! [`SdoService`], and a block transfer's control frame's
//! [`BlockSubcommand`].

use core::fmt;

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

/// The sub-command of a block transfer's control frame, as `subcommand`
/// names it (docs/output.md#sdo; CiA 301 §7.2.4.3.9–§7.2.4.3.16).
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
    /// Return the name `subcommand` writes (docs/output.md#sdo).
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
