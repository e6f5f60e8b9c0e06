//! The SDO transfer tracker: one pure state machine per SDO channel
//! (docs/canopen.md#transfers; CiA 301 §7.2.4.3).
//!
//! Fed every frame of one channel (one interface, one server node) in
//! order, in both directions, with its time, [`SdoTracker::feed`] says what
//! the frame is — block segments included, which only the transfer's state
//! tells apart — hands out the bytes of the transferred data the frame
//! carries, measures request → response latencies and reports each
//! transfer's end exactly once: completed, aborted, broken or timed out.
//! It keeps no data (no heap): the caller keeps the chunks it wants.
//!
//! ```
//! use motionwire_codec::can::Timestamp;
//! use motionwire_codec::canopen::sdo::{SdoEvent, SdoOutcome, SdoParty::*, SdoTracker, TransferDirection};
//!
//! let mut tracker = SdoTracker::new();
//! let at = |ms: u32| Timestamp::new(0, ms * 1000);
//! let mut name = Vec::new();
//!
//! // An upload of 1008h.00, "AKD-P00306" in two segments.
//! for (line, (sender, bytes, ms)) in [
//!     (Client, [0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0], 0),
//!     (Server, [0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0], 1),
//!     (Client, [0x60, 0, 0, 0, 0, 0, 0, 0], 2),
//!     (Server, [0x00, b'A', b'K', b'D', b'-', b'P', b'0', b'0'], 3),
//!     (Client, [0x70, 0, 0, 0, 0, 0, 0, 0], 4),
//!     (Server, [0x19, b'3', b'0', b'6', 0, 0, 0, 0], 5),
//! ].into_iter().enumerate() {
//!     let mut event = SdoEvent::new(sender, &bytes);
//!     tracker.feed(&mut event, at(ms), line as u64 + 1);
//!     name.extend_from_slice(event.chunk());
//!     if let Some(transfer) = event.ended {
//!         assert_eq!(transfer.direction, TransferDirection::Upload);
//!         assert_eq!(transfer.multiplexer.index, 0x1008);
//!         assert_eq!(transfer.outcome, SdoOutcome::Completed);
//!         assert_eq!((transfer.bytes, transfer.frames, transfer.start_position), (10, 6, 1));
//!         assert_eq!(transfer.duration.unwrap().as_micros(), 5000);
//!     }
//! }
//! assert_eq!(name, b"AKD-P00306");
//! assert!(tracker.finish().is_none());
//! ```

use core::fmt;
use core::time::Duration;

use super::frame::{
    field, segment_unused, BlockCrc, SdoBlockSegment, SdoFrame, SdoInitiateData, SdoParty,
    SdoRequest, SdoResponse, SdoService, BLKSIZE_MAX, CRC_SUPPORTED, LAST, SDO_LEN, SEGMENT_MAX,
    TOGGLE,
};
use crate::can::Timestamp;
use crate::canopen::{ObjectAddress, SdoAbortCode};
use crate::FrameError;

/// Which way a transfer moves the data (CiA 301 §7.2.4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum TransferDirection {
    /// Server → client: the client reads an object.
    Upload,
    /// Client → server: the client writes an object.
    Download,
}

impl TransferDirection {
    /// Return the name of the transfer's `direction` (docs/output.md#transfer):
    /// `upload` or `download`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            TransferDirection::Upload => "upload",
            TransferDirection::Download => "download",
        }
    }
}

impl fmt::Display for TransferDirection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How a transfer moves its data (CiA 301 §7.2.4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum TransferMode {
    /// Up to 4 bytes in the initiate frames.
    Expedited,
    /// Segments of up to 7 bytes, each confirmed.
    Segmented,
    /// Blocks of up to 127 segments, each block confirmed.
    Block,
}

impl TransferMode {
    /// Return the mode's name: `expedited`, `segmented`, `block`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            TransferMode::Expedited => "expedited",
            TransferMode::Segmented => "segmented",
            TransferMode::Block => "block",
        }
    }
}

impl fmt::Display for TransferMode {
    /// Write the mode's name, as the program's transfer text does
    /// (docs/output.md#sdo-text: `segmented, 10 B`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a transfer is broken (docs/canopen.md#transfers).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum BrokenReason {
    /// A segment or its confirmation did not alternate the toggle bit.
    WrongToggle,
    /// A response that answers no request of the transfer.
    UnexpectedResponse,
    /// A request that does not continue the transfer.
    UnexpectedRequest,
    /// The data transferred is not the size the transfer indicated.
    SizeMismatch,
    /// A new initiate request cut the transfer off while it waited for the
    /// client.
    CutOff,
    /// The input ended while the transfer waited for the client.
    InputEnded,
    /// Both sides said they support a CRC, and the CRC of the block end
    /// frame is not the CRC of the data.
    CrcMismatch,
    /// A sub-block confirmation acknowledges segments that were never
    /// sent.
    BadSequence,
    /// A block size outside 1..=127.
    InvalidBlockSize,
    /// A frame of the transfer that cannot be read: fewer than 8 bytes, or
    /// a command specifier CiA 301 does not define.
    MalformedFrame,
}

impl BrokenReason {
    /// Return the reason's name, as `reason` writes it
    /// (docs/output.md#transfer).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            BrokenReason::WrongToggle => "wrong_toggle",
            BrokenReason::UnexpectedResponse => "unexpected_response",
            BrokenReason::UnexpectedRequest => "unexpected_request",
            BrokenReason::SizeMismatch => "size_mismatch",
            BrokenReason::CutOff => "cut_off",
            BrokenReason::InputEnded => "input_ended",
            BrokenReason::CrcMismatch => "crc_mismatch",
            BrokenReason::BadSequence => "bad_sequence",
            BrokenReason::InvalidBlockSize => "invalid_block_size",
            BrokenReason::MalformedFrame => "malformed_frame",
        }
    }

    /// Return the reason in words.
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            BrokenReason::WrongToggle => "toggle bit not alternated",
            BrokenReason::UnexpectedResponse => "a response that answers no request",
            BrokenReason::UnexpectedRequest => "a request that does not continue the transfer",
            BrokenReason::SizeMismatch => "data size differs from the size indicated",
            BrokenReason::CutOff => "cut off by a new request",
            BrokenReason::InputEnded => "the input ended mid-transfer",
            BrokenReason::CrcMismatch => "block CRC differs from the data's CRC",
            BrokenReason::BadSequence => "sub-block confirmation of segments never sent",
            BrokenReason::InvalidBlockSize => "block size outside 1..=127",
            BrokenReason::MalformedFrame => "a frame that cannot be read",
        }
    }
}

impl fmt::Display for BrokenReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.description())
    }
}

/// How a transfer ended (docs/canopen.md#transfers; `outcome` in
/// docs/output.md#transfer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SdoOutcome {
    /// Every byte moved and was confirmed.
    Completed,
    /// One side sent an abort.
    Aborted {
        /// The side that aborted.
        by: SdoParty,
        /// The abort code.
        code: SdoAbortCode,
    },
    /// The frames broke the protocol.
    Broken(BrokenReason),
    /// A frame that expects an answer got none before the client's next
    /// request or the end of the input.
    TimedOut,
}

impl SdoOutcome {
    /// Return the name `outcome` writes (docs/output.md#transfer): `ok`,
    /// `abort`, `broken`, `timeout`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            SdoOutcome::Completed => "ok",
            SdoOutcome::Aborted { .. } => "abort",
            SdoOutcome::Broken(_) => "broken",
            SdoOutcome::TimedOut => "timeout",
        }
    }
}

impl fmt::Display for SdoOutcome {
    /// Write the outcome in the words of docs/output.md#sdo-text, without
    /// the object and the figures the program adds around them:
    /// `completed`, `aborted by the server: General parameter
    /// incompatibility reason`, `broken: toggle bit not alternated`,
    /// `timed out: no answer`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SdoOutcome::Completed => f.write_str("completed"),
            SdoOutcome::Aborted { by, code } => {
                write!(f, "aborted by the {by}: {}", code.description())
            }
            SdoOutcome::Broken(reason) => write!(f, "broken: {reason}"),
            SdoOutcome::TimedOut => f.write_str("timed out: no answer"),
        }
    }
}

/// A transfer that ended, with what the tracker measured
/// (docs/canopen.md#transfers; `transfer` in docs/output.md#transfer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SdoTransfer {
    /// Upload or download.
    pub direction: TransferDirection,
    /// The object, from the initiate frame.
    pub multiplexer: ObjectAddress,
    /// Expedited, segmented or block, as far as the transfer got (a block
    /// upload that the server answers with a normal upload is expedited or
    /// segmented).
    pub mode: TransferMode,
    /// The size the transfer indicated, if it did.
    pub indicated_size: Option<u32>,
    /// The data bytes handed out as chunks.
    pub bytes: u32,
    /// Every frame of the transfer, both directions, from the initiate to
    /// the frame that ended it.
    pub frames: u32,
    /// The outcome.
    pub outcome: SdoOutcome,
    /// The position the caller gave with the first frame.
    pub start_position: u64,
    /// The time of the first frame.
    pub started_at: Option<Timestamp>,
    /// From the first frame to the transfer's last frame, when both have a
    /// time.
    pub duration: Option<Duration>,
}

impl SdoTransfer {
    /// Write the transfer as its `Display` does, with `data` — the
    /// transfer's data in words, which the tracker does not keep — after the
    /// object of a completed transfer: the text of docs/output.md#sdo-text,
    /// `read 1008h.00 "AKD-P00306" (segmented, 10 B, 4.6 ms)`, that a session
    /// keeping the data writes. `None` writes no data, as `Display`.
    ///
    /// # Errors
    ///
    /// The formatter's.
    pub fn fmt_with_data(
        &self,
        f: &mut fmt::Formatter<'_>,
        data: Option<&dyn fmt::Display>,
    ) -> fmt::Result {
        let verb = match self.direction {
            TransferDirection::Upload => "read",
            TransferDirection::Download => "write",
        };
        let object = self.multiplexer;
        match self.outcome {
            SdoOutcome::Completed => {
                write!(f, "{verb} {object} ")?;
                if let Some(data) = data {
                    write!(f, "{data} ")?;
                }
                write!(f, "({}, {} B", self.mode, self.bytes)?;
            }
            SdoOutcome::Aborted { code, by } => write!(
                f,
                "abort {object}: {} ({verb} aborted by the {by}",
                code.description()
            )?,
            SdoOutcome::Broken(reason) => {
                write!(f, "{verb} {object} broken: {reason} ({} B", self.bytes)?;
            }
            SdoOutcome::TimedOut => write!(
                f,
                "{verb} {object} timed out: no answer (line {}",
                self.start_position
            )?,
        }
        if let Some(d) = self.duration {
            write!(f, ", {:.1} ms", d.as_nanos() as f64 / 1e6)?;
        }
        f.write_str(")")
    }
}

impl fmt::Display for SdoTransfer {
    /// Write the transfer in the words of docs/output.md#sdo-text, without
    /// its data (which the tracker does not keep; see
    /// [`fmt_with_data`](Self::fmt_with_data)): `read 1008h.00 (segmented, 10
    /// B, 4.6 ms)`, `abort 1A00h.00: General parameter incompatibility reason
    /// (write aborted by the server, 2.0 ms)`, `write 2100h.00 broken: toggle
    /// bit not alternated (7 B, 4.0 ms)`, `read 1000h.00 timed out: no answer
    /// (line 6, 0.0 ms)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.fmt_with_data(f, None)
    }
}

/// A frame read by its service, as the tracker saw it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SdoMessage {
    /// A request (client → server).
    Request(SdoRequest),
    /// A response (server → client).
    Response(SdoResponse),
    /// A segment inside a block, from whichever side sends the data.
    BlockSegment(SdoBlockSegment),
}

impl SdoMessage {
    /// Return the service, as `service` names it (docs/output.md#sdo).
    #[must_use]
    pub fn service(&self) -> SdoService {
        match self {
            SdoMessage::Request(r) => r.service(),
            SdoMessage::Response(r) => r.service(),
            SdoMessage::BlockSegment(_) => SdoService::BlockSegment,
        }
    }

    /// Return the fields of the `sdo` key (docs/output.md#sdo) for the frame.
    #[must_use]
    pub fn fields(&self) -> super::SdoFields<'_> {
        match self {
            SdoMessage::Request(r) => r.fields(),
            SdoMessage::Response(r) => r.fields(),
            SdoMessage::BlockSegment(s) => s.fields(),
        }
    }
}

/// What the tracker made of one frame.
///
/// It borrows the frame's data only, not the tracker: a caller keeps it
/// while it feeds or changes other state (the decoder learns from the
/// transfer it ends), and reads [`chunk`](Self::chunk) from it.
#[derive(Clone, Copy)]
pub struct SdoEvent<'a> {
    /// The time from the client frame that expected this answer to this
    /// frame, when this is a server frame answering one and both have a
    /// time (docs/canopen.md#transfers).
    pub latency: Option<Duration>,
    /// A transfer that ends at this frame: one this frame completes,
    /// aborts or breaks, or the open one that this new request cut off or
    /// timed out.
    pub ended: Option<SdoTransfer>,
    /// Whether this frame starts a transfer (which, for a response that
    /// answers no request, also ends at once).
    pub started: bool,
    /// Who sent the frame.
    sender: SdoParty,
    /// The frame's data.
    data: &'a [u8],
    /// The tracker read the frame as a segment inside a block.
    block_segment: bool,
    /// Where [`chunk`](Self::chunk) lies.
    chunk: Chunk,
    /// The held segment's bytes, when the chunk is [`Chunk::Held`].
    held: [u8; SEGMENT_MAX],
}

impl<'a> SdoEvent<'a> {
    /// Return the event of the frame `data` that `sender` sent, before a
    /// tracker has followed it ([`SdoTracker::feed`]): no chunk, no
    /// latency, no transfer started or ended.
    #[inline]
    #[must_use]
    pub const fn new(sender: SdoParty, data: &'a [u8]) -> Self {
        SdoEvent {
            latency: None,
            ended: None,
            started: false,
            sender,
            data,
            block_segment: false,
            chunk: Chunk::None,
            held: [0; SEGMENT_MAX],
        }
    }

    /// Return the data bytes this frame delivers to the transfer (the
    /// expedited data, a segment's data, a block segment's data; the last
    /// block segment's bytes are held back until the end frame says how
    /// many of them are data, and come out with it).
    #[inline]
    #[must_use]
    pub fn chunk(&self) -> &[u8] {
        match self.chunk {
            Chunk::None => &[],
            Chunk::Input(start, end) => self
                .data
                .get(usize::from(start)..usize::from(end))
                .unwrap_or(&[]),
            Chunk::Held(len) => self.held.get(..usize::from(len)).unwrap_or(&[]),
        }
    }

    /// Return the frame read in the transfer's context, or why it could
    /// not be read (a short frame, an undefined command specifier): such a
    /// frame breaks the open transfer, and belongs to none on an idle
    /// channel. It is read from the frame's bytes when asked for
    /// ([`SdoMessage::read`]), not while the tracker follows the frame.
    #[inline]
    pub fn message(&self) -> Result<SdoMessage, FrameError> {
        SdoMessage::read(self.sender, self.block_segment, self.data)
    }

    /// Return the multiplexer and code of the frame when the tracker read
    /// it as an abort, without reading the whole message
    /// ([`SdoMessage::read_abort`]).
    #[inline]
    #[must_use]
    pub fn abort(&self) -> Option<(ObjectAddress, SdoAbortCode)> {
        SdoMessage::read_abort(self.block_segment, self.data)
    }

    /// Return who sent the frame.
    #[inline]
    #[must_use]
    pub const fn sender(&self) -> SdoParty {
        self.sender
    }

    /// Return whether the tracker read the frame as a segment inside a
    /// block (rather than as the request or response its bits also
    /// spell): what [`SdoMessage::read`] needs to read it again.
    #[inline]
    #[must_use]
    pub const fn is_block_segment(&self) -> bool {
        self.block_segment
    }
}

/// Two events are equal when they say the same of the same frame: the
/// chunk's bytes are compared, not where they lie.
impl PartialEq for SdoEvent<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.latency == other.latency
            && self.ended == other.ended
            && self.started == other.started
            && self.sender == other.sender
            && self.data == other.data
            && self.block_segment == other.block_segment
            && self.chunk() == other.chunk()
    }
}

impl fmt::Debug for SdoEvent<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SdoEvent")
            .field("chunk", &self.chunk())
            .field("latency", &self.latency)
            .field("ended", &self.ended)
            .field("started", &self.started)
            .field("sender", &self.sender)
            .field("data", &self.data)
            .field("block_segment", &self.block_segment)
            .finish()
    }
}

/// Where an open transfer stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Initiate download sent; the server's answer is due.
    DownloadInitiated,
    /// The client's next download segment (with this toggle) is due.
    DownloadSegment { toggle: bool },
    /// A download segment sent; the server's confirmation is due.
    DownloadSegmentSent { toggle: bool, last: bool },
    /// Initiate upload sent, or a block upload initiate (with the client's
    /// `blksize`), which the server may answer as a normal upload.
    UploadInitiated { block: Option<u8> },
    /// The client's next upload segment request is due.
    UploadRequestDue { toggle: bool },
    /// An upload segment asked for; the server's segment is due.
    UploadSegmentDue { toggle: bool },
    /// Block download initiate sent; the server's answer is due.
    BlockDownloadInitiated,
    /// The client's segments of a sub-block.
    BlockDownloadSub(SubBlock),
    /// A sub-block sent; the server's confirmation is due.
    BlockDownloadAckDue(SubBlock),
    /// Every segment confirmed; the client's end frame is due.
    BlockDownloadEndDue,
    /// The client's end frame sent; the server's confirmation is due.
    BlockDownloadEndSent,
    /// The client's start is due.
    BlockUploadStartDue { blksize: u8 },
    /// The server's segments of a sub-block.
    BlockUploadSub(SubBlock),
    /// A sub-block received; the client's confirmation is due.
    BlockUploadAckDue(SubBlock),
    /// Every segment confirmed; the server's end frame is due.
    BlockUploadEndDue,
    /// The server's end frame received; the client's confirmation is due.
    BlockUploadEndSent,
}

/// One sub-block of a block transfer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct SubBlock {
    /// Segments in this block.
    blksize: u8,
    /// The last sequence number received in order (0: none yet).
    received: u8,
    /// Segments at the start of this block that repeat data already handed
    /// out (after a confirmation with a lower `ackseq`).
    repeat: u8,
    /// The segment with `c` = 1 was received in order.
    last_received: bool,
}

impl SubBlock {
    const fn new(blksize: u8, repeat: u8) -> Self {
        SubBlock {
            blksize,
            received: 0,
            repeat,
            last_received: false,
        }
    }
}

impl Phase {
    /// Whether the server must answer before the client may speak.
    const fn server_due(self) -> bool {
        matches!(
            self,
            Phase::DownloadInitiated
                | Phase::DownloadSegmentSent { .. }
                | Phase::UploadInitiated { .. }
                | Phase::UploadSegmentDue { .. }
                | Phase::BlockDownloadInitiated
                | Phase::BlockDownloadAckDue(_)
                | Phase::BlockDownloadEndSent
                | Phase::BlockUploadSub(_)
                | Phase::BlockUploadEndDue
        )
    }
}

/// The transfer open on a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Open {
    direction: TransferDirection,
    multiplexer: ObjectAddress,
    mode: TransferMode,
    size: Option<u32>,
    bytes: u32,
    frames: u32,
    start_position: u64,
    started_at: Option<Timestamp>,
    last_at: Option<Timestamp>,
    phase: Phase,
    /// The time of the client frame whose answer is a latency
    /// (docs/canopen.md#transfers).
    asked_at: Option<Option<Timestamp>>,
    /// Both sides support a block CRC.
    crc_checked: bool,
    crc: BlockCrc,
    /// The segment with `c` = 1 of a block transfer, until the end frame
    /// says how many of its bytes are data.
    held: [u8; SEGMENT_MAX],
    /// A fault seen in a frame that the peer still had to answer: the
    /// transfer is broken for it when it would otherwise complete (an
    /// abort in answer is reported as the abort).
    fault: Option<BrokenReason>,
}

impl Open {
    fn end(&self, outcome: SdoOutcome) -> SdoTransfer {
        SdoTransfer {
            direction: self.direction,
            multiplexer: self.multiplexer,
            mode: self.mode,
            indicated_size: self.size,
            bytes: self.bytes,
            frames: self.frames,
            outcome,
            start_position: self.start_position,
            started_at: self.started_at,
            duration: match (self.started_at, self.last_at) {
                (Some(start), Some(last)) => last.duration_since(start),
                _ => None,
            },
        }
    }

    /// Whether the data moved so far contradicts the indicated size.
    fn too_much(&self) -> bool {
        self.size.is_some_and(|size| self.bytes > size)
    }

    fn size_ok(&self) -> bool {
        self.size.map_or(true, |size| self.bytes == size)
    }

    /// Check a block end frame: the size, and the CRC when both sides
    /// support it.
    fn check_end(&mut self, crc: u16) {
        if !self.size_ok() {
            self.fault = Some(BrokenReason::SizeMismatch);
        } else if self.crc_checked && crc != self.crc.value() {
            self.fault = Some(BrokenReason::CrcMismatch);
        }
    }
}

/// One SDO channel's transfer tracker (docs/canopen.md#transfers): pure, no
/// heap, no clock. Feed it every frame of one (interface, node) channel in
/// order with [`feed`](Self::feed), and [`finish`](Self::finish) at the end of
/// the input.
///
/// **Decisions** (docs/canopen.md#transfers, where CiA 301 describes endpoints
/// and a log shows both):
/// - An abort ends the open transfer whatever multiplexer it carries; an
///   abort with no open transfer ends nothing.
/// - A client frame while the server's answer is due means the answer
///   never came: the open transfer timed out. An initiate request while
///   the client's own next frame is due cuts the transfer off (broken).
///   Either way the new initiate starts the next transfer.
/// - A response on an idle channel answers no request: it is a transfer of
///   its own that starts and ends broken at that frame. A request on an
///   idle channel that is not an initiate belongs to no transfer.
/// - A frame that cannot be read (fewer than 8 bytes, command specifier 7)
///   breaks the open transfer ([`BrokenReason::MalformedFrame`]): the data
///   it should carry is not there. On an idle channel it starts nothing.
/// - In a block, segments out of sequence are discarded, as CiA 301 tells
///   the receiver to do; the confirmation's `ackseq` decides what was
///   received, and segments repeated after a lower `ackseq` are not handed
///   out twice.
/// - The block CRC is checked only when both sides said they support it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SdoTracker {
    open: Option<Open>,
}

impl SdoTracker {
    /// Return a tracker with no open transfer.
    #[must_use]
    pub const fn new() -> Self {
        SdoTracker { open: None }
    }

    /// Return whether a transfer is open.
    #[must_use]
    pub const fn is_open(&self) -> bool {
        self.open.is_some()
    }

    /// Return whether the next frame the server sends is read as a block
    /// segment.
    #[must_use]
    pub fn expects_block_segment(&self, sender: SdoParty) -> bool {
        match self.open.as_ref().map(|o| o.phase) {
            Some(Phase::BlockDownloadSub(_)) => sender == SdoParty::Client,
            Some(Phase::BlockUploadSub(_)) => sender == SdoParty::Server,
            _ => false,
        }
    }

    /// Feed one frame of the channel, `event` ([`SdoEvent::new`]: the side
    /// that sent it and its data), with its time (if the log has one) and a
    /// position the caller uses to find the frame again (a line number),
    /// which comes back as a transfer's `start_position`; what the frame is
    /// in its transfer is written into `event`.
    ///
    /// The event is written where the caller keeps it, not returned: a
    /// caller that reads it there (the decoder, the summary) makes no copy
    /// of it, the ended transfer included.
    #[inline]
    pub fn feed(&mut self, event: &mut SdoEvent<'_>, time: Option<Timestamp>, position: u64) {
        let (sender, data) = (event.sender, event.data);
        self.step(sender, data, time, position, event);
    }

    /// End the input: the open transfer, if any, timed out (when the server
    /// owed an answer) or broke off (when the client owed the next frame).
    pub fn finish(&mut self) -> Option<SdoTransfer> {
        let open = self.open.take()?;
        Some(open.end(if open.phase.server_due() {
            SdoOutcome::TimedOut
        } else {
            SdoOutcome::Broken(BrokenReason::InputEnded)
        }))
    }

    /// Follow one frame. The tracker follows the frame's bytes — its
    /// command specifier first, then only the fields the transfer's phase
    /// reads — and makes no message: the event's message is read from the
    /// bytes where it is wanted ([`SdoEvent::message`]), not built here and
    /// handed back through every caller.
    fn step(
        &mut self,
        sender: SdoParty,
        data: &[u8],
        time: Option<Timestamp>,
        position: u64,
        step: &mut SdoEvent<'_>,
    ) {
        if self.expects_block_segment(sender) && data.first() != Some(&ABORT_BYTE) {
            step.block_segment = true;
            return self.block_segment_frame(data, time, step);
        }
        let Some(frame) = Frame::read(sender, data) else {
            return self.malformed(time, step);
        };
        match sender {
            SdoParty::Client => self.request(frame, time, position, step),
            SdoParty::Server => self.response(frame, time, position, step),
        }
    }

    /// A frame the transfer's state makes a block segment.
    #[cold]
    #[inline(never)]
    fn block_segment_frame(
        &mut self,
        data: &[u8],
        time: Option<Timestamp>,
        step: &mut SdoEvent<'_>,
    ) {
        let Ok(segment) = SdoBlockSegment::parse(data) else {
            return self.malformed(time, step);
        };
        if let Some(open) = self.open.as_mut() {
            open.frames += 1;
            open.last_at = time.or(open.last_at);
        }
        self.block_segment(&segment, time, step);
    }

    /// A frame that cannot be read breaks the open transfer.
    #[cold]
    #[inline(never)]
    fn malformed(&mut self, time: Option<Timestamp>, step: &mut SdoEvent<'_>) {
        if let Some(open) = self.open.as_mut() {
            open.frames += 1;
            open.last_at = time.or(open.last_at);
            self.close_open(SdoOutcome::Broken(BrokenReason::MalformedFrame), step);
        }
    }

    /// Start a transfer at an initiate request (CiA 301 §7.2.4.3.3,
    /// §7.2.4.3.6, §7.2.4.3.9, §7.2.4.3.13), or return `None` for a
    /// request that starts none.
    #[inline]
    fn start(frame: Frame<'_>, time: Option<Timestamp>, position: u64) -> Option<Open> {
        let command = frame.command();
        let view = frame.view();
        let multiplexer = view.multiplexer();
        let (direction, mode, size, phase, crc) = match command >> 5 {
            // Initiate download: expedited (`e`) or segmented, the size
            // when `s` says so.
            1 => {
                let data = SdoInitiateData::read(command, view.data_field());
                (
                    TransferDirection::Download,
                    if data.is_expedited() {
                        TransferMode::Expedited
                    } else {
                        TransferMode::Segmented
                    },
                    data.size(),
                    Phase::DownloadInitiated,
                    false,
                )
            }
            2 => (
                TransferDirection::Upload,
                TransferMode::Segmented,
                None,
                Phase::UploadInitiated { block: None },
                false,
            ),
            // Block upload initiate: the client's `blksize` in byte 4.
            5 if command & 0b11 == 0 => (
                TransferDirection::Upload,
                TransferMode::Block,
                None,
                Phase::UploadInitiated {
                    block: Some(frame.byte(field::INITIATE_BLKSIZE)),
                },
                command & CRC_SUPPORTED != 0,
            ),
            6 if command & 0b1 == 0 => {
                let (crc, size) = view.sized_block_initiate();
                (
                    TransferDirection::Download,
                    TransferMode::Block,
                    size,
                    Phase::BlockDownloadInitiated,
                    crc,
                )
            }
            _ => return None,
        };
        Some(Open {
            direction,
            multiplexer,
            mode,
            size,
            bytes: 0,
            frames: 1,
            start_position: position,
            started_at: time,
            last_at: time,
            phase,
            asked_at: Some(time),
            crc_checked: crc,
            crc: BlockCrc::new(),
            held: [0; SEGMENT_MAX],
            fault: None,
        })
    }

    /// Whether a client's command byte is an initiate request
    /// ([`start`](Self::start) gives a transfer for exactly these).
    const fn is_initiate(command: u8) -> bool {
        match command >> 5 {
            1 | 2 => true,
            5 => command & 0b11 == 0,
            6 => command & 0b1 == 0,
            _ => false,
        }
    }

    fn request(
        &mut self,
        frame: Frame<'_>,
        time: Option<Timestamp>,
        position: u64,
        step: &mut SdoEvent<'_>,
    ) {
        let Some(open) = self.open.as_mut() else {
            self.begin(frame, time, position, step);
            return;
        };
        let command = frame.command();
        if command >> 5 == 4 {
            open.frames += 1;
            open.last_at = time.or(open.last_at);
            let code = frame.abort_code();
            self.close_open(
                SdoOutcome::Aborted {
                    by: SdoParty::Client,
                    code,
                },
                step,
            );
            return;
        }
        if Self::is_initiate(command) {
            // A new initiate: the open transfer never got its answer, or was
            // left by the client.
            let outcome = if open.phase.server_due() {
                SdoOutcome::TimedOut
            } else {
                SdoOutcome::Broken(BrokenReason::CutOff)
            };
            step.ended = Some(open.end(outcome));
            self.open = None;
            self.begin(frame, time, position, step);
            return;
        }
        if open.phase.server_due() {
            // The client speaks again: the answer never came.
            step.ended = Some(open.end(SdoOutcome::TimedOut));
            self.open = None;
            return;
        }
        open.frames += 1;
        open.last_at = time.or(open.last_at);
        // The initiates and the abort are taken above: specifier 6 here is
        // the block download end, 5 the block upload's end, ack or start.
        let next = match (open.phase, command >> 5) {
            // Download segment (ccs 0): `t`, `n`, `c`, data in bytes 1–7.
            (Phase::DownloadSegment { toggle }, 0) => {
                if (command & TOGGLE != 0) != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                let last = command & LAST != 0;
                let len = SEGMENT_MAX - usize::from(segment_unused(command));
                open.bytes += len as u32;
                step.chunk = Chunk::Input(1, (1 + len) as u8);
                if open.too_much() || (last && !open.size_ok()) {
                    open.fault = Some(BrokenReason::SizeMismatch);
                }
                open.asked_at = Some(time);
                Phase::DownloadSegmentSent { toggle, last }
            }
            // Upload segment request (ccs 3): `t`.
            (Phase::UploadRequestDue { toggle }, 3) => {
                if (command & TOGGLE != 0) != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                open.asked_at = Some(time);
                Phase::UploadSegmentDue { toggle }
            }
            (Phase::BlockDownloadEndDue, 6) => {
                let (unused, crc) = frame.view().block_end();
                let len = SEGMENT_MAX - usize::from(unused).min(SEGMENT_MAX);
                step.held = open.held;
                open.bytes += len as u32;
                open.crc.update(&open.held[..len]);
                step.chunk = Chunk::Held(len as u8);
                open.check_end(crc);
                open.asked_at = Some(time);
                Phase::BlockDownloadEndSent
            }
            (Phase::BlockUploadStartDue { blksize }, 5) if command & 0b11 == 3 => {
                Phase::BlockUploadSub(SubBlock::new(blksize, 0))
            }
            (Phase::BlockUploadAckDue(sub), 5) if command & 0b11 == 2 => {
                let (ackseq, blksize) = frame.view().block_ack();
                match Self::acknowledge(sub, ackseq, blksize) {
                    Ok(Some(next)) => Phase::BlockUploadSub(next),
                    Ok(None) => Phase::BlockUploadEndDue,
                    Err(reason) => return self.close_open(SdoOutcome::Broken(reason), step),
                }
            }
            (Phase::BlockUploadEndSent, 5) if command & 0b11 == 1 => {
                return self.close_open(SdoOutcome::Completed, step);
            }
            _ => return self.close_open(SdoOutcome::Broken(BrokenReason::UnexpectedRequest), step),
        };
        open.phase = next;
    }

    /// Open a transfer at an initiate request on an idle channel.
    #[inline(always)]
    fn begin(
        &mut self,
        frame: Frame<'_>,
        time: Option<Timestamp>,
        position: u64,
        step: &mut SdoEvent<'_>,
    ) {
        // Made where it is kept, not moved there.
        self.open = Self::start(frame, time, position);
        let Some(new) = self.open.as_mut() else {
            return;
        };
        step.started = true;
        match new.phase {
            Phase::UploadInitiated {
                block: Some(blksize),
            } if !(1..=BLKSIZE_MAX).contains(&blksize) => {
                new.fault = Some(BrokenReason::InvalidBlockSize);
            }
            Phase::DownloadInitiated if new.mode == TransferMode::Expedited => {
                let data = SdoInitiateData::read(frame.command(), frame.view().data_field());
                let len = data.data().len();
                new.bytes = len as u32;
                step.chunk = Chunk::Input(4, (4 + len) as u8);
            }
            _ => {}
        }
    }

    fn response(
        &mut self,
        frame: Frame<'_>,
        time: Option<Timestamp>,
        position: u64,
        step: &mut SdoEvent<'_>,
    ) {
        let command = frame.command();
        let Some(open) = self.open.as_mut() else {
            if command >> 5 != 4 {
                // A response that answers no request: a transfer of its own.
                self.stray(frame, time, position, step);
            }
            return;
        };
        open.frames += 1;
        open.last_at = time.or(open.last_at);
        if let Some(asked) = open.asked_at.take() {
            if open.phase.server_due() {
                step.latency = match (asked, time) {
                    (Some(asked), Some(now)) => now.duration_since(asked),
                    _ => None,
                };
            }
        }
        if command >> 5 == 4 {
            let code = frame.abort_code();
            return self.close_open(
                SdoOutcome::Aborted {
                    by: SdoParty::Server,
                    code,
                },
                step,
            );
        }
        let next = match (open.phase, command >> 5) {
            // Initiate download response (scs 3).
            (Phase::DownloadInitiated, 3) => {
                if open.mode == TransferMode::Expedited {
                    return self.close_open(SdoOutcome::Completed, step);
                }
                Phase::DownloadSegment { toggle: false }
            }
            // Download segment response (scs 1): `t`.
            (Phase::DownloadSegmentSent { toggle, last }, 1) => {
                if (command & TOGGLE != 0) != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                if last {
                    return self.close_open(SdoOutcome::Completed, step);
                }
                Phase::DownloadSegment { toggle: !toggle }
            }
            // Initiate upload response (scs 2): expedited data or the size.
            (Phase::UploadInitiated { .. }, 2) => {
                let data = SdoInitiateData::read(command, frame.view().data_field());
                open.size = data.size();
                if data.is_expedited() {
                    open.mode = TransferMode::Expedited;
                    let len = data.data().len();
                    open.bytes = len as u32;
                    step.chunk = Chunk::Input(4, (4 + len) as u8);
                    return self.close_open(SdoOutcome::Completed, step);
                }
                open.mode = TransferMode::Segmented;
                Phase::UploadRequestDue { toggle: false }
            }
            // Block upload initiate response (scs 6, ss 0).
            (
                Phase::UploadInitiated {
                    block: Some(blksize),
                },
                6,
            ) if command & 0b1 == 0 => {
                let (crc_supported, size) = frame.view().sized_block_initiate();
                open.size = size;
                open.crc_checked &= crc_supported;
                Phase::BlockUploadStartDue { blksize }
            }
            // Upload segment response (scs 0): `t`, `n`, `c`, data in
            // bytes 1–7.
            (Phase::UploadSegmentDue { toggle }, 0) => {
                if (command & TOGGLE != 0) != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                let last = command & LAST != 0;
                let len = SEGMENT_MAX - usize::from(segment_unused(command));
                open.bytes += len as u32;
                step.chunk = Chunk::Input(1, (1 + len) as u8);
                if open.too_much() || (last && !open.size_ok()) {
                    open.fault = Some(BrokenReason::SizeMismatch);
                }
                if last {
                    return self.close_open(SdoOutcome::Completed, step);
                }
                Phase::UploadRequestDue { toggle: !toggle }
            }
            // Block download initiate response (scs 5, ss 0): `blksize`
            // in byte 4.
            (Phase::BlockDownloadInitiated, 5) if command & 0b11 == 0 => {
                open.crc_checked &= command & CRC_SUPPORTED != 0;
                let blksize = frame.byte(field::INITIATE_BLKSIZE);
                if !(1..=BLKSIZE_MAX).contains(&blksize) {
                    return self
                        .close_open(SdoOutcome::Broken(BrokenReason::InvalidBlockSize), step);
                }
                Phase::BlockDownloadSub(SubBlock::new(blksize, 0))
            }
            (Phase::BlockDownloadAckDue(sub), 5) if command & 0b11 == 2 => {
                let (ackseq, blksize) = frame.view().block_ack();
                match Self::acknowledge(sub, ackseq, blksize) {
                    Ok(Some(next)) => Phase::BlockDownloadSub(next),
                    Ok(None) => Phase::BlockDownloadEndDue,
                    Err(reason) => return self.close_open(SdoOutcome::Broken(reason), step),
                }
            }
            (Phase::BlockDownloadEndSent, 5) if command & 0b11 == 1 => {
                return self.close_open(SdoOutcome::Completed, step);
            }
            (Phase::BlockUploadEndDue, 6) if command & 0b1 == 1 => {
                let (unused, crc) = frame.view().block_end();
                let len = SEGMENT_MAX - usize::from(unused).min(SEGMENT_MAX);
                step.held = open.held;
                open.bytes += len as u32;
                open.crc.update(&open.held[..len]);
                step.chunk = Chunk::Held(len as u8);
                open.check_end(crc);
                Phase::BlockUploadEndSent
            }
            _ => {
                return self.close_open(SdoOutcome::Broken(BrokenReason::UnexpectedResponse), step)
            }
        };
        open.phase = next;
    }

    /// A response on an idle channel, other than an abort: it answers no
    /// request, and is a transfer of its own that starts and ends broken.
    #[cold]
    #[inline(never)]
    fn stray(
        &mut self,
        frame: Frame<'_>,
        time: Option<Timestamp>,
        position: u64,
        step: &mut SdoEvent<'_>,
    ) {
        let Ok(response) = SdoResponse::parse(frame.bytes) else {
            return;
        };
        let (direction, multiplexer) = stray(&response);
        step.started = true;
        let stray = Open {
            direction,
            multiplexer,
            mode: match response {
                SdoResponse::UploadSegment { .. } | SdoResponse::DownloadSegment { .. } => {
                    TransferMode::Segmented
                }
                SdoResponse::InitiateUpload { data, .. } if data.is_expedited() => {
                    TransferMode::Expedited
                }
                SdoResponse::InitiateUpload { .. } | SdoResponse::InitiateDownload { .. } => {
                    TransferMode::Segmented
                }
                _ => TransferMode::Block,
            },
            size: None,
            bytes: 0,
            frames: 1,
            start_position: position,
            started_at: time,
            last_at: time,
            phase: Phase::DownloadInitiated,
            asked_at: None,
            crc_checked: false,
            crc: BlockCrc::new(),
            held: [0; SEGMENT_MAX],
            fault: None,
        };
        step.ended = Some(stray.end(SdoOutcome::Broken(BrokenReason::UnexpectedResponse)));
    }

    /// A segment inside a sub-block, from whichever side sends the data.
    fn block_segment(
        &mut self,
        segment: &SdoBlockSegment,
        time: Option<Timestamp>,
        step: &mut SdoEvent<'_>,
    ) {
        let Some(mut open) = self.open else { return };
        let (Phase::BlockDownloadSub(mut sub) | Phase::BlockUploadSub(mut sub)) = open.phase else {
            return;
        };
        if segment.seqno == sub.received + 1 && !sub.last_received {
            sub.received = segment.seqno;
            if segment.last {
                // Held until the end frame says how many bytes are data.
                open.held = segment.data;
                sub.last_received = true;
            } else if sub.repeat > 0 {
                // Handed out before a confirmation with a lower `ackseq`:
                // the same bytes again.
                sub.repeat -= 1;
            } else {
                open.bytes += SEGMENT_MAX as u32;
                open.crc.update(&segment.data);
                step.chunk = Chunk::Input(1, (1 + SEGMENT_MAX) as u8);
                if open.too_much() {
                    open.fault = Some(BrokenReason::SizeMismatch);
                }
            }
        }
        let block_done = segment.last || segment.seqno >= sub.blksize;
        open.phase = match (open.phase, block_done) {
            (Phase::BlockDownloadSub(_), true) => {
                open.asked_at = Some(time);
                Phase::BlockDownloadAckDue(sub)
            }
            (Phase::BlockDownloadSub(_), false) => Phase::BlockDownloadSub(sub),
            (_, true) => Phase::BlockUploadAckDue(sub),
            (_, false) => Phase::BlockUploadSub(sub),
        };
        self.open = Some(open);
    }

    /// A sub-block confirmation: the next sub-block, `None` when every
    /// segment is confirmed, or why the confirmation is broken.
    fn acknowledge(
        sub: SubBlock,
        ackseq: u8,
        blksize: u8,
    ) -> Result<Option<SubBlock>, BrokenReason> {
        if ackseq > sub.received {
            return Err(BrokenReason::BadSequence);
        }
        // Segments received after `ackseq` come again in the next block.
        let repeat = sub.received - ackseq;
        if sub.last_received && repeat == 0 {
            return Ok(None);
        }
        if !(1..=BLKSIZE_MAX).contains(&blksize) {
            return Err(BrokenReason::InvalidBlockSize);
        }
        // The held last segment was not confirmed: it comes again; the
        // repeated segments before it were handed out already.
        let repeat = if sub.last_received {
            repeat - 1
        } else {
            repeat
        };
        Ok(Some(SubBlock::new(blksize, repeat)))
    }

    /// Close the open transfer where it stands (nothing when none is open),
    /// read where it lies: the open transfer is not copied out first.
    #[inline(always)]
    fn close_open(&mut self, outcome: SdoOutcome, step: &mut SdoEvent<'_>) {
        if let Some(open) = &self.open {
            let outcome = match (outcome, open.fault) {
                (SdoOutcome::Completed, Some(fault)) => SdoOutcome::Broken(fault),
                _ => outcome,
            };
            step.ended = Some(open.end(outcome));
            self.open = None;
        }
    }
}

const ABORT_BYTE: u8 = 4 << 5;

/// A request or response that can be read: 8 bytes or more, a command
/// specifier CiA 301 defines for its sender (CiA 301 §7.2.4.3; what
/// [`SdoRequest::parse`] and [`SdoResponse::parse`] accept). The tracker
/// reads its fields from the bytes as the transfer's phase needs them.
#[derive(Clone, Copy)]
struct Frame<'a> {
    bytes: &'a [u8; SDO_LEN],
}

impl<'a> Frame<'a> {
    /// The frame `data` that `sender` sent, or `None` when neither parser
    /// would read it.
    #[inline]
    fn read(sender: SdoParty, data: &'a [u8]) -> Option<Self> {
        let bytes = data.first_chunk::<SDO_LEN>()?;
        let command = bytes[field::COMMAND];
        let readable = match (sender, command >> 5) {
            (_, 7) => false,
            // scs 5, sub-command 3: no block download response.
            (SdoParty::Server, 5) => command & 0b11 != 0b11,
            _ => true,
        };
        readable.then_some(Frame { bytes })
    }

    /// The command byte.
    #[inline]
    fn command(self) -> u8 {
        self.bytes[field::COMMAND]
    }

    /// The byte at `at`.
    #[inline]
    fn byte(self, at: usize) -> u8 {
        self.bytes[at]
    }

    /// The view over the bytes, for the fields every service shares.
    #[inline]
    fn view(self) -> SdoFrame<&'a [u8]> {
        SdoFrame::new_unchecked(&self.bytes[..])
    }

    /// The abort code, bytes 4–7 (CiA 301 §7.2.4.3.17).
    #[inline]
    fn abort_code(self) -> SdoAbortCode {
        SdoAbortCode::new(u32::from_le_bytes(self.view().data_field()))
    }
}

/// The direction and multiplexer a response that answers no request
/// implies.
fn stray(response: &SdoResponse) -> (TransferDirection, ObjectAddress) {
    match *response {
        SdoResponse::InitiateUpload { multiplexer, .. }
        | SdoResponse::BlockUploadInitiate { multiplexer, .. } => {
            (TransferDirection::Upload, multiplexer)
        }
        SdoResponse::InitiateDownload { multiplexer }
        | SdoResponse::BlockDownloadInitiate { multiplexer, .. }
        | SdoResponse::Abort { multiplexer, .. } => (TransferDirection::Download, multiplexer),
        SdoResponse::UploadSegment { .. } | SdoResponse::BlockUploadEnd { .. } => {
            (TransferDirection::Upload, ObjectAddress::default())
        }
        SdoResponse::DownloadSegment { .. }
        | SdoResponse::BlockDownloadAck { .. }
        | SdoResponse::BlockDownloadEnd => (TransferDirection::Download, ObjectAddress::default()),
    }
}

/// Where an event's chunk lies: nowhere, bytes `start..end` of the
/// frame's data (at most 8), or the first bytes of the held segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Chunk {
    None,
    Input(u8, u8),
    Held(u8),
}

impl SdoMessage {
    /// Return the frame `data` that `sender` sent, read as a tracker read
    /// it: a segment inside a block when `block_segment`
    /// ([`SdoEvent::is_block_segment`]), else the request or response it
    /// spells ([`SdoEvent::message`]).
    #[inline]
    pub fn read(
        sender: SdoParty,
        block_segment: bool,
        data: &[u8],
    ) -> Result<SdoMessage, FrameError> {
        if block_segment {
            return Ok(SdoBlockSegment::parse(data).map(SdoMessage::BlockSegment)?);
        }
        match sender {
            SdoParty::Client => SdoRequest::read(data).map(SdoMessage::Request),
            SdoParty::Server => SdoResponse::read(data).map(SdoMessage::Response),
        }
    }

    /// Return the multiplexer and code of the frame `data` when it is an
    /// abort ([`read`](Self::read) would give [`SdoRequest::Abort`] or
    /// [`SdoResponse::Abort`]), read from its bytes without the message.
    #[inline]
    #[must_use]
    pub fn read_abort(block_segment: bool, data: &[u8]) -> Option<(ObjectAddress, SdoAbortCode)> {
        let bytes = data.first_chunk::<SDO_LEN>()?;
        if block_segment || bytes[field::COMMAND] >> 5 != 4 {
            return None;
        }
        let frame = Frame { bytes };
        Some((frame.view().multiplexer(), frame.abort_code()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The transfers of docs/output.md#sdo-text, without their data.
    #[test]
    fn transfers_read_as_the_program_writes_them() {
        let transfer = |direction, index, outcome, bytes, start_position, ms: u64| SdoTransfer {
            direction,
            multiplexer: ObjectAddress::new(index, 0),
            mode: TransferMode::Segmented,
            indicated_size: None,
            bytes,
            frames: 2,
            outcome,
            start_position,
            started_at: None,
            duration: Some(Duration::from_micros(ms)),
        };
        let table = [
            (
                transfer(
                    TransferDirection::Upload,
                    0x1008,
                    SdoOutcome::Completed,
                    10,
                    1,
                    4600,
                ),
                "read 1008h.00 (segmented, 10 B, 4.6 ms)",
            ),
            (
                transfer(
                    TransferDirection::Download,
                    0x1A00,
                    SdoOutcome::Aborted {
                        by: SdoParty::Server,
                        code: SdoAbortCode::new(0x0604_0043),
                    },
                    1,
                    94,
                    2019,
                ),
                "abort 1A00h.00: General parameter incompatibility reason \
                 (write aborted by the server, 2.0 ms)",
            ),
            (
                transfer(
                    TransferDirection::Download,
                    0x2100,
                    SdoOutcome::Broken(BrokenReason::WrongToggle),
                    7,
                    1,
                    4000,
                ),
                "write 2100h.00 broken: toggle bit not alternated (7 B, 4.0 ms)",
            ),
            (
                transfer(
                    TransferDirection::Upload,
                    0x1000,
                    SdoOutcome::TimedOut,
                    0,
                    6,
                    0,
                ),
                "read 1000h.00 timed out: no answer (line 6, 0.0 ms)",
            ),
        ];
        for (transfer, text) in table {
            assert_eq!(transfer.to_string(), text);
        }
        let mut untimed = table[0].0;
        untimed.duration = None;
        assert_eq!(untimed.to_string(), "read 1008h.00 (segmented, 10 B)");
    }

    /// [`Frame::read`] says which command bytes can be read on its own
    /// (the tracker follows the bytes, not a parsed message): for every
    /// command byte from either side, of 8 bytes and of 7, it reads a
    /// frame exactly when the side's parser does.
    #[test]
    fn a_frame_is_read_where_the_parsers_read_one() {
        for command in 0..=u8::MAX {
            for len in [SDO_LEN - 1, SDO_LEN] {
                let mut data = [0x5Au8; SDO_LEN];
                data[field::COMMAND] = command;
                let data = &data[..len];
                assert_eq!(
                    Frame::read(SdoParty::Client, data).is_some(),
                    SdoRequest::parse(data).is_ok(),
                    "client command {command:#04x}, {len} bytes"
                );
                assert_eq!(
                    Frame::read(SdoParty::Server, data).is_some(),
                    SdoResponse::parse(data).is_ok(),
                    "server command {command:#04x}, {len} bytes"
                );
            }
        }
    }
}
