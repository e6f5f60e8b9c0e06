//! A reference SDO transfer tracker, written the plain way: each frame
//! parsed into an [`SdoRequest`], [`SdoResponse`] or [`SdoBlockSegment`]
//! first, then followed by its parsed value. The tracker, which follows
//! the frame's bytes, is held to it frame by frame on arbitrary sequences
//! (`the_tracker_follows_the_reference` in `tests.rs`); the decisions are
//! the tracker's (docs/canopen.md#transfers).

#![allow(dead_code)]

use core::time::Duration;

use crate::can::Timestamp;
use crate::canopen::sdo::{
    BlockCrc, BrokenReason, SdoBlockSegment, SdoInitiateData, SdoMessage, SdoOutcome, SdoParty,
    SdoRequest, SdoResponse, SdoTransfer, TransferDirection, TransferMode, BLKSIZE_MAX,
    SEGMENT_MAX,
};
use crate::canopen::ObjectAddress;
use crate::FrameError;

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

/// What the reference made of one frame: the tracker's
/// [`SdoEvent`](crate::canopen::sdo::SdoEvent) with its message read at
/// once.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Event<'a> {
    pub(super) message: Result<SdoMessage, FrameError>,
    pub(super) chunk: &'a [u8],
    pub(super) latency: Option<Duration>,
    pub(super) ended: Option<SdoTransfer>,
    pub(super) started: bool,
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
pub(super) struct ReferenceTracker {
    open: Option<Open>,
    /// Bytes of the held segment to hand out with the current event.
    release: [u8; SEGMENT_MAX],
}

impl ReferenceTracker {
    /// Return a tracker with no open transfer.
    #[must_use]
    pub(super) const fn new() -> Self {
        ReferenceTracker {
            open: None,
            release: [0; SEGMENT_MAX],
        }
    }

    /// Return whether a transfer is open.
    #[must_use]
    pub(super) const fn is_open(&self) -> bool {
        self.open.is_some()
    }

    /// Return whether the next frame the server sends is read as a block
    /// segment.
    #[must_use]
    pub(super) fn expects_block_segment(&self, sender: SdoParty) -> bool {
        match self.open.as_ref().map(|o| o.phase) {
            Some(Phase::BlockDownloadSub(_)) => sender == SdoParty::Client,
            Some(Phase::BlockUploadSub(_)) => sender == SdoParty::Server,
            _ => false,
        }
    }

    /// Feed one frame of the channel: the side that sent it, its data, its time
    /// (if the log has one) and a position the caller uses to find the
    /// frame again (a line number), which comes back as a transfer's
    /// `start_position`.
    #[inline]
    pub(super) fn feed<'a>(
        &'a mut self,
        sender: SdoParty,
        data: &'a [u8],
        time: Option<Timestamp>,
        position: u64,
    ) -> Event<'a> {
        let mut step = Step::new();
        let message = self.step(sender, data, time, position, &mut step);
        let chunk = self.chunk(&step, data);
        Event {
            message,
            chunk,
            latency: step.latency,
            ended: step.ended,
            started: step.started,
        }
    }

    /// The chunk of `step`, the step of the frame `data` fed last: the
    /// event's [`chunk`](Event::chunk).
    #[inline]
    fn chunk<'a>(&'a self, step: &Step, data: &'a [u8]) -> &'a [u8] {
        match &step.chunk {
            Chunk::None => &[],
            Chunk::Input(range) => data.get(range.clone()).unwrap_or(&[]),
            Chunk::Held(len) => &self.release[..usize::from(*len).min(SEGMENT_MAX)],
        }
    }

    /// End the input: the open transfer, if any, timed out (when the server
    /// owed an answer) or broke off (when the client owed the next frame).
    pub(super) fn finish(&mut self) -> Option<SdoTransfer> {
        let open = self.open.take()?;
        Some(open.end(if open.phase.server_due() {
            SdoOutcome::TimedOut
        } else {
            SdoOutcome::Broken(BrokenReason::InputEnded)
        }))
    }

    fn step(
        &mut self,
        sender: SdoParty,
        data: &[u8],
        time: Option<Timestamp>,
        position: u64,
        step: &mut Step,
    ) -> Result<SdoMessage, FrameError> {
        if self.expects_block_segment(sender) && data.first() != Some(&ABORT_BYTE) {
            let segment = match SdoBlockSegment::parse(data) {
                Ok(segment) => segment,
                Err(e) => {
                    self.malformed(time, step);
                    return Err(e.into());
                }
            };
            if let Some(open) = self.open.as_mut() {
                open.frames += 1;
                open.last_at = time.or(open.last_at);
            }
            self.block_segment(&segment, time, step);
            return Ok(SdoMessage::BlockSegment(segment));
        }
        // Each side's frame read and followed in its own arm: the message
        // is made once, not read back out of a `Result<SdoMessage>`.
        match sender {
            SdoParty::Client => match SdoRequest::parse(data) {
                Ok(request) => {
                    self.request(&request, time, position, step);
                    Ok(SdoMessage::Request(request))
                }
                Err(e) => {
                    self.malformed(time, step);
                    Err(e)
                }
            },
            SdoParty::Server => match SdoResponse::parse(data) {
                Ok(response) => {
                    self.response(&response, time, position, step);
                    Ok(SdoMessage::Response(response))
                }
                Err(e) => {
                    self.malformed(time, step);
                    Err(e)
                }
            },
        }
    }

    /// A frame that cannot be read breaks the open transfer.
    fn malformed(&mut self, time: Option<Timestamp>, step: &mut Step) {
        if let Some(open) = self.open.as_mut() {
            open.frames += 1;
            open.last_at = time.or(open.last_at);
            self.close_open(SdoOutcome::Broken(BrokenReason::MalformedFrame), step);
        }
    }

    /// Start a transfer at an initiate request, or return `None` for a
    /// request that starts none.
    fn start(request: &SdoRequest, time: Option<Timestamp>, position: u64) -> Option<Open> {
        let (direction, multiplexer, mode, size, phase, crc) = match *request {
            SdoRequest::InitiateDownload { multiplexer, data } => (
                TransferDirection::Download,
                multiplexer,
                if data.is_expedited() {
                    TransferMode::Expedited
                } else {
                    TransferMode::Segmented
                },
                data.size(),
                Phase::DownloadInitiated,
                false,
            ),
            SdoRequest::InitiateUpload { multiplexer } => (
                TransferDirection::Upload,
                multiplexer,
                TransferMode::Segmented,
                None,
                Phase::UploadInitiated { block: None },
                false,
            ),
            SdoRequest::BlockUploadInitiate {
                multiplexer,
                crc_supported,
                blksize,
                ..
            } => (
                TransferDirection::Upload,
                multiplexer,
                TransferMode::Block,
                None,
                Phase::UploadInitiated {
                    block: Some(blksize),
                },
                crc_supported,
            ),
            SdoRequest::BlockDownloadInitiate {
                multiplexer,
                crc_supported,
                size,
            } => (
                TransferDirection::Download,
                multiplexer,
                TransferMode::Block,
                size,
                Phase::BlockDownloadInitiated,
                crc_supported,
            ),
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

    /// Whether `request` starts a transfer ([`start`](Self::start) gives
    /// one for exactly these).
    const fn is_initiate(request: &SdoRequest) -> bool {
        matches!(
            request,
            SdoRequest::InitiateDownload { .. }
                | SdoRequest::InitiateUpload { .. }
                | SdoRequest::BlockUploadInitiate { .. }
                | SdoRequest::BlockDownloadInitiate { .. }
        )
    }

    fn request(
        &mut self,
        request: &SdoRequest,
        time: Option<Timestamp>,
        position: u64,
        step: &mut Step,
    ) {
        let Some(open) = self.open.as_mut() else {
            self.begin(request, time, position, step);
            return;
        };
        if let SdoRequest::Abort { code, .. } = *request {
            open.frames += 1;
            open.last_at = time.or(open.last_at);
            self.close_open(
                SdoOutcome::Aborted {
                    by: SdoParty::Client,
                    code,
                },
                step,
            );
            return;
        }
        if Self::is_initiate(request) {
            // A new initiate: the open transfer never got its answer, or was
            // left by the client.
            let outcome = if open.phase.server_due() {
                SdoOutcome::TimedOut
            } else {
                SdoOutcome::Broken(BrokenReason::CutOff)
            };
            step.ended = Some(open.end(outcome));
            self.open = None;
            self.begin(request, time, position, step);
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
        let next = match (open.phase, *request) {
            (
                Phase::DownloadSegment { toggle },
                SdoRequest::DownloadSegment {
                    toggle: t,
                    data,
                    last,
                },
            ) => {
                if t != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                open.bytes += data.as_slice().len() as u32;
                step.chunk = Chunk::Input(1..1 + data.as_slice().len());
                if open.too_much() || (last && !open.size_ok()) {
                    open.fault = Some(BrokenReason::SizeMismatch);
                }
                open.asked_at = Some(time);
                Phase::DownloadSegmentSent { toggle, last }
            }
            (Phase::UploadRequestDue { toggle }, SdoRequest::UploadSegment { toggle: t }) => {
                if t != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                open.asked_at = Some(time);
                Phase::UploadSegmentDue { toggle }
            }
            (Phase::BlockDownloadEndDue, SdoRequest::BlockDownloadEnd { unused, crc }) => {
                let len = SEGMENT_MAX - usize::from(unused).min(SEGMENT_MAX);
                self.release = open.held;
                open.bytes += len as u32;
                open.crc.update(&open.held[..len]);
                step.chunk = Chunk::Held(len as u8);
                open.check_end(crc);
                open.asked_at = Some(time);
                Phase::BlockDownloadEndSent
            }
            (Phase::BlockUploadStartDue { blksize }, SdoRequest::BlockUploadStart) => {
                Phase::BlockUploadSub(SubBlock::new(blksize, 0))
            }
            (Phase::BlockUploadAckDue(sub), SdoRequest::BlockUploadAck { ackseq, blksize }) => {
                match Self::acknowledge(sub, ackseq, blksize) {
                    Ok(Some(next)) => Phase::BlockUploadSub(next),
                    Ok(None) => Phase::BlockUploadEndDue,
                    Err(reason) => return self.close_open(SdoOutcome::Broken(reason), step),
                }
            }
            (Phase::BlockUploadEndSent, SdoRequest::BlockUploadEnd) => {
                return self.close_open(SdoOutcome::Completed, step);
            }
            _ => return self.close_open(SdoOutcome::Broken(BrokenReason::UnexpectedRequest), step),
        };
        open.phase = next;
    }

    /// Open a transfer at an initiate request on an idle channel.
    fn begin(
        &mut self,
        request: &SdoRequest,
        time: Option<Timestamp>,
        position: u64,
        step: &mut Step,
    ) {
        // Made where it is kept, not moved there.
        self.open = Self::start(request, time, position);
        let Some(new) = self.open.as_mut() else {
            return;
        };
        step.started = true;
        match *request {
            SdoRequest::BlockUploadInitiate { blksize, .. }
                if !(1..=BLKSIZE_MAX).contains(&blksize) =>
            {
                new.fault = Some(BrokenReason::InvalidBlockSize);
            }
            SdoRequest::InitiateDownload { data, .. } if data.is_expedited() => {
                let len = data.data().len();
                new.bytes = len as u32;
                step.chunk = Chunk::Input(4..4 + len);
            }
            _ => {}
        }
    }

    fn response(
        &mut self,
        response: &SdoResponse,
        time: Option<Timestamp>,
        position: u64,
        step: &mut Step,
    ) {
        let Some(open) = self.open.as_mut() else {
            if let SdoResponse::Abort { .. } = response {
                return;
            }
            // A response that answers no request: a transfer of its own.
            let (direction, multiplexer) = stray(response);
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
        if let SdoResponse::Abort { code, .. } = *response {
            return self.close_open(
                SdoOutcome::Aborted {
                    by: SdoParty::Server,
                    code,
                },
                step,
            );
        }
        let next = match (open.phase, *response) {
            (Phase::DownloadInitiated, SdoResponse::InitiateDownload { .. }) => {
                if open.mode == TransferMode::Expedited {
                    return self.close_open(SdoOutcome::Completed, step);
                }
                Phase::DownloadSegment { toggle: false }
            }
            (
                Phase::DownloadSegmentSent { toggle, last },
                SdoResponse::DownloadSegment { toggle: t },
            ) => {
                if t != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                if last {
                    return self.close_open(SdoOutcome::Completed, step);
                }
                Phase::DownloadSegment { toggle: !toggle }
            }
            (Phase::UploadInitiated { .. }, SdoResponse::InitiateUpload { data, .. }) => {
                open.size = data.size();
                match data {
                    SdoInitiateData::Expedited { .. } => {
                        open.mode = TransferMode::Expedited;
                        let len = data.data().len();
                        open.bytes = len as u32;
                        step.chunk = Chunk::Input(4..4 + len);
                        return self.close_open(SdoOutcome::Completed, step);
                    }
                    SdoInitiateData::Segmented { .. } => {
                        open.mode = TransferMode::Segmented;
                        Phase::UploadRequestDue { toggle: false }
                    }
                }
            }
            (
                Phase::UploadInitiated {
                    block: Some(blksize),
                },
                SdoResponse::BlockUploadInitiate {
                    crc_supported,
                    size,
                    ..
                },
            ) => {
                open.size = size;
                open.crc_checked &= crc_supported;
                Phase::BlockUploadStartDue { blksize }
            }
            (
                Phase::UploadSegmentDue { toggle },
                SdoResponse::UploadSegment {
                    toggle: t,
                    data,
                    last,
                },
            ) => {
                if t != toggle {
                    return self.close_open(SdoOutcome::Broken(BrokenReason::WrongToggle), step);
                }
                open.bytes += data.as_slice().len() as u32;
                step.chunk = Chunk::Input(1..1 + data.as_slice().len());
                if open.too_much() || (last && !open.size_ok()) {
                    open.fault = Some(BrokenReason::SizeMismatch);
                }
                if last {
                    return self.close_open(SdoOutcome::Completed, step);
                }
                Phase::UploadRequestDue { toggle: !toggle }
            }
            (
                Phase::BlockDownloadInitiated,
                SdoResponse::BlockDownloadInitiate {
                    crc_supported,
                    blksize,
                    ..
                },
            ) => {
                open.crc_checked &= crc_supported;
                if !(1..=BLKSIZE_MAX).contains(&blksize) {
                    return self
                        .close_open(SdoOutcome::Broken(BrokenReason::InvalidBlockSize), step);
                }
                Phase::BlockDownloadSub(SubBlock::new(blksize, 0))
            }
            (
                Phase::BlockDownloadAckDue(sub),
                SdoResponse::BlockDownloadAck { ackseq, blksize },
            ) => match Self::acknowledge(sub, ackseq, blksize) {
                Ok(Some(next)) => Phase::BlockDownloadSub(next),
                Ok(None) => Phase::BlockDownloadEndDue,
                Err(reason) => return self.close_open(SdoOutcome::Broken(reason), step),
            },
            (Phase::BlockDownloadEndSent, SdoResponse::BlockDownloadEnd) => {
                return self.close_open(SdoOutcome::Completed, step);
            }
            (Phase::BlockUploadEndDue, SdoResponse::BlockUploadEnd { unused, crc }) => {
                let len = SEGMENT_MAX - usize::from(unused).min(SEGMENT_MAX);
                self.release = open.held;
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

    /// A segment inside a sub-block, from whichever side sends the data.
    fn block_segment(
        &mut self,
        segment: &SdoBlockSegment,
        time: Option<Timestamp>,
        step: &mut Step,
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
                step.chunk = Chunk::Input(1..1 + SEGMENT_MAX);
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
    fn close_open(&mut self, outcome: SdoOutcome, step: &mut Step) {
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

/// Where an event's chunk lies.
enum Chunk {
    None,
    Input(core::ops::Range<usize>),
    Held(u8),
}

/// What one frame is in its transfer: an [`Event`] without its message,
/// and with its chunk as where it lies ([`ReferenceTracker::chunk`]).
struct Step {
    chunk: Chunk,
    /// [`Event::latency`].
    latency: Option<Duration>,
    /// [`Event::ended`].
    ended: Option<SdoTransfer>,
    /// [`Event::started`].
    started: bool,
}

impl Step {
    /// Nothing yet: no chunk, no latency, no transfer started or ended.
    #[inline]
    const fn new() -> Self {
        Step {
            chunk: Chunk::None,
            latency: None,
            ended: None,
            started: false,
        }
    }
}

impl ReferenceTracker {
    /// A frame that continues the open transfer where it stands (or starts
    /// one on an idle channel), its free fields from `pick` and `data`:
    /// what a client and a server that keep the protocol send next, so
    /// that sequences built from it reach every phase.
    pub(super) fn proposal(&self, pick: u8, data: [u8; 8]) -> (SdoParty, [u8; 8]) {
        use SdoParty::{Client, Server};
        let mut out = data;
        let n = (pick >> 1) & 0b111;
        let toggle = |t: bool| if t { 0x10 } else { 0 };
        let last = u8::from(pick % 3 == 0);
        let blksize = 1 + pick % 4;
        let Some(open) = self.open else {
            let (command, blk) = match pick % 5 {
                0 => (0x40, None),
                1 => (0x23 | ((n & 0b11) << 2), None),
                2 => (0x21, None),
                3 => (0xA0 | (pick & 0b100), Some(blksize)),
                _ => (0xC0 | (pick & 0b110), None),
            };
            out[0] = command;
            if let Some(blk) = blk {
                out[4] = blk;
            }
            if pick % 5 == 2 {
                out[4..8].copy_from_slice(&u32::from(data[4] % 24).to_le_bytes());
            }
            return (Client, out);
        };
        let (sender, command) = match open.phase {
            Phase::DownloadInitiated => (Server, 0x60),
            Phase::DownloadSegment { toggle: t } => (Client, toggle(t) | (n << 1) | last),
            Phase::DownloadSegmentSent { toggle: t, .. } => (Server, 0x20 | toggle(t)),
            Phase::UploadInitiated { block } => match (block, pick % 3) {
                (Some(_), 0) => {
                    out[4..8].copy_from_slice(&u32::from(data[4] % 24).to_le_bytes());
                    (Server, 0xC2 | (pick & 0b100))
                }
                (_, 1) => (Server, 0x43 | ((n & 0b11) << 2)),
                _ => {
                    out[4..8].copy_from_slice(&u32::from(data[4] % 24).to_le_bytes());
                    (Server, 0x41)
                }
            },
            Phase::UploadRequestDue { toggle: t } => (Client, 0x60 | toggle(t)),
            Phase::UploadSegmentDue { toggle: t } => (Server, toggle(t) | (n << 1) | last),
            Phase::BlockDownloadInitiated => {
                out[4] = blksize;
                (Server, 0xA0 | (pick & 0b100))
            }
            Phase::BlockDownloadSub(sub) => (Client, (sub.received + 1) | (last << 7)),
            Phase::BlockUploadSub(sub) => (Server, (sub.received + 1) | (last << 7)),
            Phase::BlockDownloadAckDue(sub) | Phase::BlockUploadAckDue(sub) => {
                out[1] = sub.received.saturating_sub(u8::from(pick % 4 == 0));
                out[2] = blksize;
                let sender = match open.phase {
                    Phase::BlockDownloadAckDue(_) => Server,
                    _ => Client,
                };
                (sender, 0xA2)
            }
            Phase::BlockDownloadEndDue => {
                if pick % 2 == 0 {
                    let crc = open.crc.value().to_le_bytes();
                    out[1..3].copy_from_slice(&crc);
                }
                (Client, 0xC1 | (n << 2))
            }
            Phase::BlockUploadEndDue => {
                if pick % 2 == 0 {
                    let crc = open.crc.value().to_le_bytes();
                    out[1..3].copy_from_slice(&crc);
                }
                (Server, 0xC1 | (n << 2))
            }
            Phase::BlockDownloadEndSent => (Server, 0xA1),
            Phase::BlockUploadStartDue { .. } => (Client, 0xA3),
            Phase::BlockUploadEndSent => (Client, 0xA1),
        };
        out[0] = command;
        (sender, out)
    }
}
