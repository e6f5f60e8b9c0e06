//! Tests of the SDO frames, tracker and server (docs/canopen.md#sdo): vectors
//! written from CiA 301's figures, one named test per tracker rule, and
//! property tests over arbitrary bytes.

use super::*;
use crate::can::Timestamp;
use crate::canopen::{Emcy, ErrorCode, ErrorHistory, ErrorRegister, ObjectAddress, SdoAbortCode};
use crate::strategies::sdo as gens;
use crate::{FrameError, LenError};
use proptest::prelude::*;
use SdoParty::{Client as Rq, Server as Rs};

fn mux(index: u16, subindex: u8) -> ObjectAddress {
    ObjectAddress::new(index, subindex)
}

// ---------------------------------------------------------------- frames

/// Each request of CiA 301 §7.2.4.3 as bytes and as a value.
#[test]
fn request_vectors() {
    let vectors: [([u8; 8], SdoRequest); 12] = [
        // Expedited download of 2 bytes: e = s = 1, n = 2.
        (
            [0x2B, 0x17, 0x10, 0x00, 0xE8, 0x03, 0, 0],
            SdoRequest::InitiateDownload {
                multiplexer: mux(0x1017, 0),
                data: SdoInitiateData::expedited(&[0xE8, 0x03]).unwrap(),
            },
        ),
        // Segmented download of 20 bytes: s = 1, size in bytes 4–7.
        (
            [0x21, 0x08, 0x10, 0x00, 20, 0, 0, 0],
            SdoRequest::InitiateDownload {
                multiplexer: mux(0x1008, 0),
                data: SdoInitiateData::Segmented { size: Some(20) },
            },
        ),
        // Download segment, toggle 1, 3 bytes, last: n = 4, c = 1.
        (
            [0x19, b'a', b'b', b'c', 0, 0, 0, 0],
            SdoRequest::DownloadSegment {
                toggle: true,
                data: SdoSegmentData::new(b"abc").unwrap(),
                last: true,
            },
        ),
        (
            [0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0],
            SdoRequest::InitiateUpload {
                multiplexer: mux(0x1000, 0),
            },
        ),
        (
            [0x70, 0, 0, 0, 0, 0, 0, 0],
            SdoRequest::UploadSegment { toggle: true },
        ),
        (
            [0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x05],
            SdoRequest::Abort {
                multiplexer: mux(0, 0),
                code: SdoAbortCode::TIMED_OUT,
            },
        ),
        (
            [0xA4, 0x08, 0x10, 0x00, 127, 0, 0, 0],
            SdoRequest::BlockUploadInitiate {
                multiplexer: mux(0x1008, 0),
                crc_supported: true,
                blksize: 127,
                pst: 0,
            },
        ),
        ([0xA1, 0, 0, 0, 0, 0, 0, 0], SdoRequest::BlockUploadEnd),
        (
            [0xA2, 5, 127, 0, 0, 0, 0, 0],
            SdoRequest::BlockUploadAck {
                ackseq: 5,
                blksize: 127,
            },
        ),
        ([0xA3, 0, 0, 0, 0, 0, 0, 0], SdoRequest::BlockUploadStart),
        (
            [0xC6, 0x00, 0x20, 0x01, 0x00, 0x01, 0, 0],
            SdoRequest::BlockDownloadInitiate {
                multiplexer: mux(0x2000, 1),
                crc_supported: true,
                size: Some(256),
            },
        ),
        (
            [0xC9, 0x34, 0x12, 0, 0, 0, 0, 0],
            SdoRequest::BlockDownloadEnd {
                unused: 2,
                crc: 0x1234,
            },
        ),
    ];
    for (bytes, value) in vectors {
        assert_eq!(SdoRequest::parse(&bytes), Ok(value), "{bytes:02x?}");
        assert_eq!(value.to_bytes(), bytes, "{value:?}");
    }
}

/// Each response of CiA 301 §7.2.4.3 as bytes and as a value.
#[test]
fn response_vectors() {
    let vectors: [([u8; 8], SdoResponse); 10] = [
        (
            [0x09, b'A', b'K', b'D', 0, 0, 0, 0],
            SdoResponse::UploadSegment {
                toggle: false,
                data: SdoSegmentData::new(b"AKD").unwrap(),
                last: true,
            },
        ),
        (
            [0x30, 0, 0, 0, 0, 0, 0, 0],
            SdoResponse::DownloadSegment { toggle: true },
        ),
        (
            [0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00],
            SdoResponse::InitiateUpload {
                multiplexer: mux(0x1000, 0),
                data: SdoInitiateData::expedited(&[0x92, 0x01, 0x02, 0x00]).unwrap(),
            },
        ),
        (
            [0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0],
            SdoResponse::InitiateDownload {
                multiplexer: mux(0x1017, 0),
            },
        ),
        (
            [0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06],
            SdoResponse::Abort {
                multiplexer: mux(0x6041, 0),
                code: SdoAbortCode::OBJECT_DOES_NOT_EXIST,
            },
        ),
        (
            [0xA4, 0x00, 0x20, 0x01, 64, 0, 0, 0],
            SdoResponse::BlockDownloadInitiate {
                multiplexer: mux(0x2000, 1),
                crc_supported: true,
                blksize: 64,
            },
        ),
        ([0xA1, 0, 0, 0, 0, 0, 0, 0], SdoResponse::BlockDownloadEnd),
        (
            [0xA2, 64, 64, 0, 0, 0, 0, 0],
            SdoResponse::BlockDownloadAck {
                ackseq: 64,
                blksize: 64,
            },
        ),
        (
            [0xC2, 0x08, 0x10, 0x00, 30, 0, 0, 0],
            SdoResponse::BlockUploadInitiate {
                multiplexer: mux(0x1008, 0),
                crc_supported: false,
                size: Some(30),
            },
        ),
        (
            [0xD5, 0xCD, 0xAB, 0, 0, 0, 0, 0],
            SdoResponse::BlockUploadEnd {
                unused: 5,
                crc: 0xABCD,
            },
        ),
    ];
    for (bytes, value) in vectors {
        assert_eq!(SdoResponse::parse(&bytes), Ok(value), "{bytes:02x?}");
        assert_eq!(value.to_bytes(), bytes, "{value:?}");
    }
}

#[test]
fn expedited_without_size_keeps_all_four_bytes() {
    let response = SdoResponse::parse(&[0x42, 0x00, 0x10, 0x00, 1, 2, 3, 4]).unwrap();
    let SdoResponse::InitiateUpload { data, .. } = response else {
        panic!("{response:?}")
    };
    assert_eq!((data.data(), data.size()), (&[1, 2, 3, 4][..], None));
    let fields = response.fields();
    assert_eq!(fields.size, Some(None));
    assert_eq!(fields.value, Some(&[1, 2, 3, 4][..]));
}

#[test]
fn every_short_length_is_a_length_error() {
    for len in 0..SDO_LEN {
        let data = [0u8; SDO_LEN];
        let expected = LenError {
            what: crate::error::What::SdoFrame,
            expected: SDO_LEN,
            found: len,
        };
        assert_eq!(
            SdoRequest::parse(&data[..len]),
            Err(FrameError::Length(expected))
        );
        assert_eq!(
            SdoResponse::parse(&data[..len]),
            Err(FrameError::Length(expected))
        );
        assert_eq!(SdoBlockSegment::parse(&data[..len]), Err(expected));
    }
}

#[test]
fn undefined_specifiers_are_errors_and_service_unknown() {
    assert!(SdoRequest::parse(&[0xE0, 0, 0, 0, 0, 0, 0, 0]).is_err());
    assert!(SdoResponse::parse(&[0xE0, 0, 0, 0, 0, 0, 0, 0]).is_err());
    assert!(SdoResponse::parse(&[0xA3, 0, 0, 0, 0, 0, 0, 0]).is_err());
    assert_eq!(SdoService::of(Rq, 0xE0), SdoService::Unknown);
    assert_eq!(SdoService::of(Rs, 0xA3), SdoService::Unknown);
}

/// The table of docs/canopen.md#sdo, both columns.
#[test]
fn services_follow_the_specifier_table() {
    use SdoService::*;
    let requests = [
        DownloadSegment,
        InitiateDownload,
        InitiateUpload,
        UploadSegment,
        Abort,
        BlockUpload,
        BlockDownload,
        Unknown,
    ];
    let responses = [
        UploadSegment,
        DownloadSegment,
        InitiateUpload,
        InitiateDownload,
        Abort,
        BlockDownload,
        BlockUpload,
        Unknown,
    ];
    for cs in 0..8u8 {
        assert_eq!(SdoService::of(Rq, cs << 5), requests[usize::from(cs)]);
        assert_eq!(SdoService::of(Rs, cs << 5), responses[usize::from(cs)]);
    }
    let names: Vec<_> = SdoService::ALL.iter().map(|s| s.name()).collect();
    assert_eq!(
        names,
        [
            "initiate_download",
            "download_segment",
            "initiate_upload",
            "upload_segment",
            "abort",
            "block_download",
            "block_upload",
            "block_segment",
            "unknown"
        ]
    );
}

#[test]
fn block_crc_is_crc16_xmodem() {
    let mut crc = BlockCrc::new();
    crc.update(b"123456789");
    assert_eq!(crc.value(), 0x31C3);
    assert_eq!(BlockCrc::new().value(), 0);
}

proptest! {
    #[test]
    fn requests_round_trip(request in gens::request()) {
        prop_assert_eq!(SdoRequest::parse(&request.to_bytes()), Ok(request));
    }

    #[test]
    fn responses_round_trip(response in gens::response()) {
        prop_assert_eq!(SdoResponse::parse(&response.to_bytes()), Ok(response));
    }

    #[test]
    fn block_segments_round_trip(segment in gens::block_segment()) {
        prop_assert_eq!(SdoBlockSegment::parse(&segment.to_bytes()), Ok(segment));
    }

    /// Any bytes: never a panic, and what parses writes bytes that parse
    /// to the same value.
    #[test]
    fn any_bytes_parse_to_a_fixed_point(data in proptest::collection::vec(any::<u8>(), 0..12)) {
        if let Ok(request) = SdoRequest::parse(&data) {
            prop_assert_eq!(SdoRequest::parse(&request.to_bytes()), Ok(request));
            prop_assert_eq!(request.service(), SdoService::of(Rq, data[0]));
        }
        if let Ok(response) = SdoResponse::parse(&data) {
            prop_assert_eq!(SdoResponse::parse(&response.to_bytes()), Ok(response));
            prop_assert_eq!(response.service(), SdoService::of(Rs, data[0]));
        }
        let _ = SdoBlockSegment::parse(&data);
    }
}

// --------------------------------------------------------------- tracker

/// What a sequence of frames made the tracker say.
#[derive(Debug, Default)]
struct Run {
    data: Vec<u8>,
    ended: Vec<(u64, SdoTransfer)>,
    latencies: Vec<(u64, u128)>,
    services: Vec<SdoService>,
    started: Vec<u64>,
}

fn ts(ms: u32) -> Option<Timestamp> {
    Timestamp::new(u64::from(ms / 1000), (ms % 1000) * 1000)
}

/// Feed the frame `data` that `sender` sent to `tracker`, and return its
/// event.
fn feed<'a>(
    tracker: &mut SdoTracker,
    sender: SdoParty,
    data: &'a [u8],
    time: Option<Timestamp>,
    position: u64,
) -> SdoEvent<'a> {
    let mut event = SdoEvent::new(sender, data);
    tracker.feed(&mut event, time, position);
    event
}

/// Feed `frames` (direction, bytes, time in ms) as lines 1, 2, …, then end
/// the input.
fn run(frames: &[(SdoParty, [u8; 8], u32)]) -> Run {
    let mut tracker = SdoTracker::new();
    let mut out = Run::default();
    for (i, (direction, bytes, ms)) in frames.iter().enumerate() {
        let line = i as u64 + 1;
        let event = feed(&mut tracker, *direction, bytes, ts(*ms), line);
        out.data.extend_from_slice(event.chunk());
        out.services.push(
            event
                .message()
                .as_ref()
                .map_or(SdoService::Unknown, SdoMessage::service),
        );
        if let Some(latency) = event.latency {
            out.latencies.push((line, latency.as_micros()));
        }
        if event.started {
            out.started.push(line);
        }
        if let Some(transfer) = event.ended {
            out.ended.push((line, transfer));
        }
    }
    if let Some(transfer) = tracker.finish() {
        out.ended.push((0, transfer));
    }
    out
}

fn outcome(run: &Run) -> Vec<(u64, SdoOutcome)> {
    run.ended.iter().map(|(l, t)| (*l, t.outcome)).collect()
}

fn up(index: u16, sub: u8) -> [u8; 8] {
    SdoRequest::InitiateUpload {
        multiplexer: mux(index, sub),
    }
    .to_bytes()
}

#[test]
fn expedited_upload_completes_at_the_response() {
    let r = run(&[
        (Rq, up(0x1000, 0), 0),
        (Rs, [0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00], 2),
    ]);
    assert_eq!(outcome(&r), [(2, SdoOutcome::Completed)]);
    let t = r.ended[0].1;
    assert_eq!(t.direction, TransferDirection::Upload);
    assert_eq!((t.mode, t.bytes, t.frames), (TransferMode::Expedited, 4, 2));
    assert_eq!(r.data, [0x92, 0x01, 0x02, 0x00]);
    assert_eq!(r.latencies, [(2, 2000)]);
    assert_eq!(t.duration.map(|d| d.as_micros()), Some(2000));
}

#[test]
fn expedited_download_completes_at_the_confirmation() {
    let r = run(&[
        (Rq, [0x2B, 0x17, 0x10, 0x00, 0xE8, 0x03, 0, 0], 10),
        (Rs, [0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0], 11),
    ]);
    assert_eq!(outcome(&r), [(2, SdoOutcome::Completed)]);
    assert_eq!(r.data, [0xE8, 0x03]);
    assert_eq!(r.ended[0].1.indicated_size, Some(2));
}

/// A segmented download of 10 bytes: 7 + 3, toggles 0 and 1.
#[test]
fn segmented_download() {
    let r = run(&[
        (Rq, [0x21, 0x08, 0x20, 0x00, 10, 0, 0, 0], 0),
        (Rs, [0x60, 0x08, 0x20, 0x00, 0, 0, 0, 0], 1),
        (Rq, [0x00, 1, 2, 3, 4, 5, 6, 7], 2),
        (Rs, [0x20, 0, 0, 0, 0, 0, 0, 0], 3),
        (Rq, [0x19, 8, 9, 10, 0, 0, 0, 0], 4),
        (Rs, [0x30, 0, 0, 0, 0, 0, 0, 0], 6),
    ]);
    assert_eq!(outcome(&r), [(6, SdoOutcome::Completed)]);
    assert_eq!(r.data, [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]);
    assert_eq!(r.latencies, [(2, 1000), (4, 1000), (6, 2000)]);
    assert_eq!(r.ended[0].1.frames, 6);
}

#[test]
fn segmented_upload_with_a_full_last_segment() {
    let r = run(&[
        (Rq, up(0x1008, 0), 0),
        (Rs, [0x41, 0x08, 0x10, 0x00, 7, 0, 0, 0], 1),
        (Rq, [0x60, 0, 0, 0, 0, 0, 0, 0], 2),
        (Rs, [0x01, b'A', b'K', b'D', b'-', b'P', b'0', b'0'], 3),
    ]);
    assert_eq!(outcome(&r), [(4, SdoOutcome::Completed)]);
    assert_eq!(r.data, b"AKD-P00");
}

#[test]
fn wrong_toggle_breaks_the_transfer() {
    let r = run(&[
        (Rq, up(0x1008, 0), 0),
        (Rs, [0x41, 0x08, 0x10, 0x00, 20, 0, 0, 0], 1),
        (Rq, [0x60, 0, 0, 0, 0, 0, 0, 0], 2),
        (Rs, [0x00, 1, 2, 3, 4, 5, 6, 7], 3),
        // Toggle 0 again where 1 is due.
        (Rq, [0x60, 0, 0, 0, 0, 0, 0, 0], 4),
    ]);
    assert_eq!(
        outcome(&r),
        [(5, SdoOutcome::Broken(BrokenReason::WrongToggle))]
    );
}

#[test]
fn size_mismatch_breaks_the_transfer() {
    let r = run(&[
        (Rq, up(0x1008, 0), 0),
        (Rs, [0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0], 1),
        (Rq, [0x60, 0, 0, 0, 0, 0, 0, 0], 2),
        (Rs, [0x00, 1, 2, 3, 4, 5, 6, 7], 3),
        (Rq, [0x70, 0, 0, 0, 0, 0, 0, 0], 4),
        // 7 more bytes where 3 are due.
        (Rs, [0x11, 1, 2, 3, 4, 5, 6, 7], 5),
    ]);
    assert_eq!(
        outcome(&r),
        [(6, SdoOutcome::Broken(BrokenReason::SizeMismatch))]
    );
    assert_eq!(r.ended[0].1.bytes, 14);
}

#[test]
fn server_abort_ends_the_transfer_with_its_code() {
    let r = run(&[
        (Rq, up(0x6041, 0), 0),
        (Rs, [0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06], 1),
    ]);
    assert_eq!(
        outcome(&r),
        [(
            2,
            SdoOutcome::Aborted {
                by: SdoParty::Server,
                code: SdoAbortCode::OBJECT_DOES_NOT_EXIST
            }
        )]
    );
    assert_eq!(r.latencies, [(2, 1000)]);
}

/// docs/canopen.md#transfers: python-canopen's client aborts with 0000h.00; the
/// abort still ends the open transfer.
#[test]
fn client_abort_with_any_multiplexer_ends_the_open_transfer() {
    let r = run(&[
        (Rq, up(0x1008, 0), 0),
        (Rs, [0x41, 0x08, 0x10, 0x00, 20, 0, 0, 0], 1),
        (Rq, [0x80, 0, 0, 0, 0x00, 0x00, 0x04, 0x05], 2),
    ]);
    let (line, t) = r.ended[0];
    assert_eq!(line, 3);
    assert_eq!(
        t.outcome,
        SdoOutcome::Aborted {
            by: SdoParty::Client,
            code: SdoAbortCode::TIMED_OUT
        }
    );
    assert_eq!(t.multiplexer, mux(0x1008, 0));
}

#[test]
fn no_answer_before_the_next_request_is_a_timeout() {
    let r = run(&[
        (Rq, up(0x1000, 0), 0),
        (Rq, up(0x1001, 0), 500),
        (Rs, [0x4F, 0x01, 0x10, 0, 0, 0, 0, 0], 501),
    ]);
    assert_eq!(
        outcome(&r),
        [(2, SdoOutcome::TimedOut), (3, SdoOutcome::Completed)]
    );
    assert_eq!(r.started, [1, 2]);
    assert_eq!(r.ended[0].1.frames, 1);
}

#[test]
fn a_new_initiate_while_the_client_owes_a_segment_cuts_off() {
    let r = run(&[
        (Rq, up(0x1008, 0), 0),
        (Rs, [0x41, 0x08, 0x10, 0x00, 20, 0, 0, 0], 1),
        (Rq, up(0x1000, 0), 2),
    ]);
    assert_eq!(
        outcome(&r),
        [
            (3, SdoOutcome::Broken(BrokenReason::CutOff)),
            (0, SdoOutcome::TimedOut)
        ]
    );
}

#[test]
fn input_ending_mid_transfer() {
    // The client owes the next request: broken.
    let r = run(&[
        (Rq, up(0x1008, 0), 0),
        (Rs, [0x41, 0x08, 0x10, 0x00, 20, 0, 0, 0], 1),
    ]);
    assert_eq!(
        outcome(&r),
        [(0, SdoOutcome::Broken(BrokenReason::InputEnded))]
    );
    // The server owes the answer: timed out.
    let r = run(&[(Rq, up(0x1008, 0), 0)]);
    assert_eq!(outcome(&r), [(0, SdoOutcome::TimedOut)]);
}

#[test]
fn a_response_that_answers_no_request_is_a_broken_transfer_of_its_own() {
    let r = run(&[(Rs, [0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0], 0)]);
    assert_eq!(r.started, [1]);
    let (line, t) = r.ended[0];
    assert_eq!(line, 1);
    assert_eq!(
        t.outcome,
        SdoOutcome::Broken(BrokenReason::UnexpectedResponse)
    );
    assert_eq!(
        (t.direction, t.multiplexer, t.frames),
        (TransferDirection::Download, mux(0x1017, 0), 1)
    );
}

#[test]
fn an_abort_or_a_segment_on_an_idle_channel_starts_nothing() {
    let r = run(&[
        (Rs, [0x80, 0, 0, 0, 0, 0, 0x04, 0x05], 0),
        (Rq, [0x80, 0, 0, 0, 0, 0, 0x04, 0x05], 1),
        (Rq, [0x60, 0, 0, 0, 0, 0, 0, 0], 2),
    ]);
    assert!(r.ended.is_empty() && r.started.is_empty());
}

#[test]
fn an_unreadable_frame_breaks_the_open_transfer() {
    let mut tracker = SdoTracker::new();
    assert!(feed(&mut tracker, Rq, &up(0x1000, 0), None, 1).started);
    let short = feed(&mut tracker, Rs, &[0x43, 0x00, 0x10], None, 2);
    assert!(short.message().is_err());
    let t = short.ended.unwrap();
    assert_eq!(
        (t.outcome, t.frames),
        (SdoOutcome::Broken(BrokenReason::MalformedFrame), 2)
    );
    // On an idle channel it belongs to no transfer.
    let stray = feed(&mut tracker, Rs, &[0xE0, 0, 0, 0, 0, 0, 0, 0], None, 3);
    assert!(stray.message().is_err() && stray.ended.is_none() && !stray.started);
    // Without times, no latency.
    feed(&mut tracker, Rq, &up(0x1000, 0), None, 4);
    let event = feed(
        &mut tracker,
        Rs,
        &[0x4F, 0x00, 0x10, 0x00, 1, 0, 0, 0],
        None,
        5,
    );
    assert_eq!(event.ended.map(|t| t.outcome), Some(SdoOutcome::Completed));
    assert_eq!(event.latency, None);
}

/// A block download of 17 bytes in one block (3 segments), both sides with
/// CRC: the last segment's data is held until the end frame says `n`.
#[test]
fn block_download_with_crc() {
    let data: Vec<u8> = (1..=17).collect();
    let mut crc = BlockCrc::new();
    crc.update(&data);
    let crc = crc.value().to_le_bytes();
    let seg = |c: u8, seq: u8, chunk: &[u8]| {
        let mut b = [0u8; 8];
        b[0] = (c << 7) | seq;
        b[1..1 + chunk.len()].copy_from_slice(chunk);
        b
    };
    let r = run(&[
        (Rq, [0xC6, 0x00, 0x20, 0x01, 17, 0, 0, 0], 0),
        (Rs, [0xA4, 0x00, 0x20, 0x01, 127, 0, 0, 0], 1),
        (Rq, seg(0, 1, &data[0..7]), 2),
        (Rq, seg(0, 2, &data[7..14]), 3),
        (Rq, seg(1, 3, &data[14..17]), 4),
        (Rs, [0xA2, 3, 127, 0, 0, 0, 0, 0], 5),
        (Rq, [0xC1 | (4 << 2), crc[0], crc[1], 0, 0, 0, 0, 0], 6),
        (Rs, [0xA1, 0, 0, 0, 0, 0, 0, 0], 7),
    ]);
    assert_eq!(outcome(&r), [(8, SdoOutcome::Completed)]);
    assert_eq!(r.data, data);
    assert_eq!(r.services[2..5], [SdoService::BlockSegment; 3]);
    assert_eq!(r.latencies, [(2, 1000), (6, 1000), (8, 1000)]);
    let t = r.ended[0].1;
    assert_eq!((t.mode, t.bytes, t.frames), (TransferMode::Block, 17, 8));
}

#[test]
fn block_download_with_a_wrong_crc_is_broken_when_both_support_crc() {
    let frames = |server_crc: bool| {
        run(&[
            (Rq, [0xC6, 0x00, 0x20, 0x01, 3, 0, 0, 0], 0),
            (
                Rs,
                [
                    if server_crc { 0xA4 } else { 0xA0 },
                    0x00,
                    0x20,
                    0x01,
                    127,
                    0,
                    0,
                    0,
                ],
                1,
            ),
            (Rq, [0x81, 1, 2, 3, 0, 0, 0, 0], 2),
            (Rs, [0xA2, 1, 127, 0, 0, 0, 0, 0], 3),
            (Rq, [0xC1 | (4 << 2), 0xFF, 0xFF, 0, 0, 0, 0, 0], 4),
            (Rs, [0xA1, 0, 0, 0, 0, 0, 0, 0], 5),
        ])
    };
    assert_eq!(
        outcome(&frames(true)),
        [(6, SdoOutcome::Broken(BrokenReason::CrcMismatch))]
    );
    // Without the server's support the CRC is not checked.
    assert_eq!(outcome(&frames(false)), [(6, SdoOutcome::Completed)]);
}

/// Segment 2 of 3 is lost: the server discards segment 3, confirms 1, and
/// the client sends 2 and 3 again as segments 1 and 2 of the next block.
/// Nothing is handed out twice.
#[test]
fn block_download_with_a_missing_sequence_number_is_repeated() {
    let data: Vec<u8> = (1..=21).collect();
    let seg = |c: u8, seq: u8, chunk: &[u8]| {
        let mut b = [0u8; 8];
        b[0] = (c << 7) | seq;
        b[1..1 + chunk.len()].copy_from_slice(chunk);
        b
    };
    let r = run(&[
        (Rq, [0xC2, 0x00, 0x20, 0x01, 21, 0, 0, 0], 0),
        (Rs, [0xA0, 0x00, 0x20, 0x01, 3, 0, 0, 0], 1),
        (Rq, seg(0, 1, &data[0..7]), 2),
        (Rq, seg(1, 3, &data[14..21]), 3),
        (Rs, [0xA2, 1, 3, 0, 0, 0, 0, 0], 4),
        (Rq, seg(0, 1, &data[7..14]), 5),
        (Rq, seg(1, 2, &data[14..21]), 6),
        (Rs, [0xA2, 2, 3, 0, 0, 0, 0, 0], 7),
        (Rq, [0xC1, 0, 0, 0, 0, 0, 0, 0], 8),
        (Rs, [0xA1, 0, 0, 0, 0, 0, 0, 0], 9),
    ]);
    assert_eq!(outcome(&r), [(10, SdoOutcome::Completed)]);
    assert_eq!(r.data, data);
}

/// The server confirms fewer segments than it got: the client repeats
/// them, and their bytes are not handed out a second time.
#[test]
fn block_segments_repeated_after_a_low_ackseq_are_not_handed_out_twice() {
    let seg = |c: u8, seq: u8, fill: u8| {
        let mut b = [fill; 8];
        b[0] = (c << 7) | seq;
        b
    };
    let r = run(&[
        (Rq, [0xC2, 0x00, 0x20, 0x01, 21, 0, 0, 0], 0),
        (Rs, [0xA0, 0x00, 0x20, 0x01, 3, 0, 0, 0], 1),
        (Rq, seg(0, 1, 1), 2),
        (Rq, seg(0, 2, 2), 3),
        (Rq, seg(1, 3, 3), 4),
        (Rs, [0xA2, 1, 3, 0, 0, 0, 0, 0], 5),
        (Rq, seg(0, 1, 2), 6),
        (Rq, seg(1, 2, 3), 7),
        (Rs, [0xA2, 2, 3, 0, 0, 0, 0, 0], 8),
        (Rq, [0xC1, 0, 0, 0, 0, 0, 0, 0], 9),
        (Rs, [0xA1, 0, 0, 0, 0, 0, 0, 0], 10),
    ]);
    assert_eq!(outcome(&r), [(11, SdoOutcome::Completed)]);
    let expected: Vec<u8> = [[1u8; 7], [2; 7], [3; 7]].concat();
    assert_eq!(r.data, expected);
}

#[test]
fn an_ack_of_segments_never_sent_is_a_bad_sequence() {
    let r = run(&[
        (Rq, [0xC0, 0x00, 0x20, 0x01, 0, 0, 0, 0], 0),
        (Rs, [0xA0, 0x00, 0x20, 0x01, 2, 0, 0, 0], 1),
        (Rq, [0x01, 0, 0, 0, 0, 0, 0, 0], 2),
        (Rq, [0x03, 0, 0, 0, 0, 0, 0, 0], 3),
        (Rs, [0xA2, 3, 2, 0, 0, 0, 0, 0], 4),
    ]);
    assert_eq!(
        outcome(&r),
        [(5, SdoOutcome::Broken(BrokenReason::BadSequence))]
    );
}

#[test]
fn block_upload_of_ten_bytes() {
    let r = run(&[
        (Rq, [0xA4, 0x08, 0x10, 0x00, 127, 0, 0, 0], 0),
        (Rs, [0xC2, 0x08, 0x10, 0x00, 10, 0, 0, 0], 1),
        (Rq, [0xA3, 0, 0, 0, 0, 0, 0, 0], 2),
        (Rs, [0x01, 1, 2, 3, 4, 5, 6, 7], 3),
        (Rs, [0x82, 8, 9, 10, 0, 0, 0, 0], 4),
        (Rq, [0xA2, 2, 127, 0, 0, 0, 0, 0], 5),
        (Rs, [0xC1 | (4 << 2), 0, 0, 0, 0, 0, 0, 0], 6),
        (Rq, [0xA1, 0, 0, 0, 0, 0, 0, 0], 7),
    ]);
    // The server's CRC (0) is not the data's, but the server did not say
    // it supports CRC: not checked.
    assert_eq!(outcome(&r), [(8, SdoOutcome::Completed)]);
    assert_eq!(r.data, [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]);
    assert_eq!(r.services[3..5], [SdoService::BlockSegment; 2]);
    // The initiate's answer is a latency; the server's segments and end
    // answer the start and the confirmation, which docs/canopen.md#transfers
    // does not list.
    assert_eq!(r.latencies, [(2, 1000)]);
}

#[test]
fn block_upload_answered_as_an_expedited_upload() {
    let r = run(&[
        (Rq, [0xA4, 0x01, 0x10, 0x00, 127, 4, 0, 0], 0),
        (Rs, [0x4F, 0x01, 0x10, 0x00, 0x11, 0, 0, 0], 1),
    ]);
    assert_eq!(outcome(&r), [(2, SdoOutcome::Completed)]);
    assert_eq!(r.ended[0].1.mode, TransferMode::Expedited);
    assert_eq!(r.data, [0x11]);
}

#[test]
fn an_abort_inside_a_sub_block_is_an_abort() {
    let r = run(&[
        (Rq, [0xA4, 0x08, 0x10, 0x00, 127, 0, 0, 0], 0),
        (Rs, [0xC6, 0x08, 0x10, 0x00, 100, 0, 0, 0], 1),
        (Rq, [0xA3, 0, 0, 0, 0, 0, 0, 0], 2),
        (Rs, [0x01, 1, 2, 3, 4, 5, 6, 7], 3),
        (Rs, [0x80, 0x08, 0x10, 0x00, 0x05, 0x00, 0x06, 0x06], 4),
    ]);
    assert!(matches!(
        outcome(&r)[..],
        [(
            5,
            SdoOutcome::Aborted {
                by: SdoParty::Server,
                ..
            }
        )]
    ));
}

#[test]
fn an_invalid_block_size_is_broken() {
    // Reported when the server answers as if all were well.
    let r = run(&[
        (Rq, [0xA4, 0x08, 0x10, 0x00, 0, 0, 0, 0], 0),
        (Rs, [0x4B, 0x08, 0x10, 0x00, 1, 2, 0, 0], 1),
    ]);
    assert_eq!(
        outcome(&r),
        [(2, SdoOutcome::Broken(BrokenReason::InvalidBlockSize))]
    );
    let r = run(&[
        (Rq, [0xC0, 0x00, 0x20, 0x01, 0, 0, 0, 0], 0),
        (Rs, [0xA0, 0x00, 0x20, 0x01, 200, 0, 0, 0], 1),
    ]);
    assert_eq!(
        outcome(&r),
        [(2, SdoOutcome::Broken(BrokenReason::InvalidBlockSize))]
    );
}

/// Frames of both directions as arbitrary bytes.
fn any_frames() -> impl Strategy<Value = Vec<(bool, Vec<u8>)>> {
    proptest::collection::vec(
        (any::<bool>(), proptest::collection::vec(any::<u8>(), 0..=8)),
        0..64,
    )
}

/// Frames built from valid requests and responses, so that transfers do
/// start and run.
fn plausible_frames() -> impl Strategy<Value = Vec<(bool, Vec<u8>)>> {
    proptest::collection::vec(
        prop_oneof![
            gens::request().prop_map(|r| (true, r.to_bytes().to_vec())),
            gens::response().prop_map(|r| (false, r.to_bytes().to_vec())),
            gens::block_segment().prop_map(|s| (true, s.to_bytes().to_vec())),
            gens::block_segment().prop_map(|s| (false, s.to_bytes().to_vec())),
        ],
        0..64,
    )
}

/// docs/canopen.md#transfers: never more data than the frames
/// carried, every started transfer ends exactly once, frames counted at most
/// once.
fn check_invariants(frames: &[(bool, Vec<u8>)]) -> Result<(), TestCaseError> {
    let mut tracker = SdoTracker::new();
    let mut open = false;
    let mut data_frames = 0u64;
    let mut handed_out = 0u64;
    let mut ended = 0u64;
    let mut started = 0u64;
    for (i, (request, bytes)) in frames.iter().enumerate() {
        let direction = if *request { Rq } else { Rs };
        let event = feed(&mut tracker, direction, bytes, ts(i as u32), i as u64);
        handed_out += event.chunk().len() as u64;
        if !event.chunk().is_empty() {
            data_frames += 1;
        }
        if let Some(t) = event.ended {
            prop_assert!(open || (event.started && t.start_position == i as u64));
            ended += 1;
            prop_assert!(u64::from(t.frames) <= i as u64 + 1);
            open = false;
        }
        if event.started {
            started += 1;
            open = event.ended.map_or(true, |t| t.start_position != i as u64);
        }
        prop_assert_eq!(open, tracker.is_open());
    }
    if tracker.finish().is_some() {
        ended += 1;
    }
    prop_assert_eq!(started, ended);
    prop_assert!(handed_out <= 7 * frames.len() as u64);
    prop_assert!(data_frames <= frames.len() as u64);
    Ok(())
}

proptest! {
    #[test]
    fn tracker_invariants_over_any_bytes(frames in any_frames()) {
        check_invariants(&frames)?;
    }

    #[test]
    fn tracker_invariants_over_plausible_frames(frames in plausible_frames()) {
        check_invariants(&frames)?;
    }
}

// ---------------------------------------------------------------- server

fn history() -> ErrorHistory {
    let mut h = ErrorHistory::new();
    h.record(&Emcy::new(
        ErrorCode::new(0x8130),
        ErrorRegister::GENERIC,
        [0x01, 0x00, 0, 0, 0],
    ));
    h.record(&Emcy::new(
        ErrorCode::new(0x4210),
        ErrorRegister::GENERIC,
        [0; 5],
    ));
    h
}

fn serve(request: SdoRequest, h: &mut ErrorHistory) -> Option<SdoResponse> {
    serve_error_objects(
        &request.to_bytes(),
        h,
        ErrorRegister::GENERIC | ErrorRegister::TEMPERATURE,
    )
    .map(|bytes| SdoResponse::parse(&bytes).unwrap())
}

fn read(index: u16, sub: u8) -> SdoRequest {
    SdoRequest::InitiateUpload {
        multiplexer: mux(index, sub),
    }
}

fn write(index: u16, sub: u8, data: &[u8]) -> SdoRequest {
    SdoRequest::InitiateDownload {
        multiplexer: mux(index, sub),
        data: SdoInitiateData::expedited(data).unwrap(),
    }
}

fn aborted(index: u16, sub: u8, code: SdoAbortCode) -> Option<SdoResponse> {
    Some(SdoResponse::Abort {
        multiplexer: mux(index, sub),
        code,
    })
}

fn uploaded(index: u16, sub: u8, data: &[u8]) -> Option<SdoResponse> {
    Some(SdoResponse::InitiateUpload {
        multiplexer: mux(index, sub),
        data: SdoInitiateData::expedited(data).unwrap(),
    })
}

/// docs/canopen.md#serving-1001h-and-1003h and docs/canopen.md#error-history,
/// one row per rule.
#[test]
fn serving_1003h_and_1001h() {
    let mut h = history();
    assert_eq!(serve(read(0x1001, 0), &mut h), uploaded(0x1001, 0, &[0x09]));
    assert_eq!(serve(read(0x1003, 0), &mut h), uploaded(0x1003, 0, &[2]));
    assert_eq!(
        serve(read(0x1003, 1), &mut h),
        uploaded(0x1003, 1, &[0x10, 0x42, 0, 0])
    );
    assert_eq!(
        serve(read(0x1003, 2), &mut h),
        uploaded(0x1003, 2, &[0x30, 0x81, 0x01, 0])
    );
    let cases = [
        (
            read(0x1003, 3),
            aborted(0x1003, 3, SdoAbortCode::NO_DATA_AVAILABLE),
        ),
        (
            read(0x1003, 11),
            aborted(0x1003, 11, SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST),
        ),
        (
            read(0x1001, 1),
            aborted(0x1001, 1, SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST),
        ),
        (
            write(0x1001, 0, &[0]),
            aborted(0x1001, 0, SdoAbortCode::WRITE_OF_READ_ONLY),
        ),
        (
            write(0x1003, 0, &[1]),
            aborted(0x1003, 0, SdoAbortCode::INVALID_VALUE),
        ),
        (
            write(0x1003, 0, &[0, 0]),
            aborted(0x1003, 0, SdoAbortCode::LENGTH_TOO_HIGH),
        ),
        (
            write(0x1003, 1, &[0, 0, 0, 0]),
            aborted(0x1003, 1, SdoAbortCode::WRITE_OF_READ_ONLY),
        ),
        (
            read(0x1000, 0),
            aborted(0x1000, 0, SdoAbortCode::OBJECT_DOES_NOT_EXIST),
        ),
        (
            write(0x6040, 0, &[6, 0]),
            aborted(0x6040, 0, SdoAbortCode::OBJECT_DOES_NOT_EXIST),
        ),
        (
            SdoRequest::UploadSegment { toggle: false },
            aborted(0, 0, SdoAbortCode::INVALID_COMMAND_SPECIFIER),
        ),
        (
            SdoRequest::BlockUploadInitiate {
                multiplexer: mux(0x1003, 0),
                crc_supported: true,
                blksize: 127,
                pst: 0,
            },
            aborted(0x1003, 0, SdoAbortCode::UNSUPPORTED_ACCESS),
        ),
        (
            SdoRequest::InitiateDownload {
                multiplexer: mux(0x1003, 0),
                data: SdoInitiateData::Segmented { size: Some(1) },
            },
            aborted(0x1003, 0, SdoAbortCode::UNSUPPORTED_ACCESS),
        ),
        (
            SdoRequest::Abort {
                multiplexer: mux(0x1003, 0),
                code: SdoAbortCode::TIMED_OUT,
            },
            None,
        ),
    ];
    for (request, expected) in cases {
        assert_eq!(serve(request, &mut h), expected, "{request:?}");
    }
    assert_eq!(h.read(0), Ok(2), "refused writes change nothing");
    assert_eq!(
        serve(write(0x1003, 0, &[0]), &mut h),
        Some(SdoResponse::InitiateDownload {
            multiplexer: mux(0x1003, 0)
        })
    );
    assert_eq!(h.read(0), Ok(0));
    assert_eq!(
        serve_error_objects(&[0x40, 0x03], &mut h, ErrorRegister::empty()),
        None
    );
}

/// The server's answers read back through the tracker as the transfers
/// they are.
#[test]
fn served_answers_are_transfers() {
    let mut h = history();
    let mut tracker = SdoTracker::new();
    let request = read(0x1003, 1).to_bytes();
    feed(&mut tracker, Rq, &request, None, 1);
    let answer = serve_error_objects(&request, &mut h, ErrorRegister::GENERIC).unwrap();
    let event = feed(&mut tracker, Rs, &answer, None, 2);
    assert_eq!(event.chunk(), [0x10, 0x42, 0, 0]);
    assert_eq!(event.ended.map(|t| t.outcome), Some(SdoOutcome::Completed));
}

proptest! {
    #[test]
    fn the_server_never_panics(data in proptest::collection::vec(any::<u8>(), 0..10)) {
        let mut h = history();
        if let Some(answer) = serve_error_objects(&data, &mut h, ErrorRegister::GENERIC) {
            prop_assert!(SdoResponse::parse(&answer).is_ok());
        }
    }
}

mod reference;

/// Frames of both directions built to run through every phase: valid
/// requests and responses, block segments, and arbitrary bytes (short
/// frames, undefined specifiers), with their times.
fn mixed_frames() -> impl Strategy<Value = Vec<(bool, Vec<u8>, u32)>> {
    proptest::collection::vec(
        (
            prop_oneof![
                3 => gens::request().prop_map(|r| (true, r.to_bytes().to_vec())),
                3 => gens::response().prop_map(|r| (false, r.to_bytes().to_vec())),
                2 => (any::<bool>(), gens::block_segment()).prop_map(|(c, s)| (c, s.to_bytes().to_vec())),
                1 => (any::<bool>(), proptest::collection::vec(any::<u8>(), 0..=9)),
            ],
            prop_oneof![Just(None), (0u32..5000).prop_map(Some)],
        )
            .prop_map(|((c, bytes), ms)| (c, bytes, ms.unwrap_or(u32::MAX))),
        0..96,
    )
}

/// Feed `frames` to the tracker and to the reference (the tracker as it
/// was, parsing each frame before following it): every event and the end
/// of the input the same.
fn follows_the_reference(frames: &[(bool, Vec<u8>, u32)]) -> Result<(), TestCaseError> {
    let mut tracker = SdoTracker::new();
    let mut reference = reference::ReferenceTracker::new();
    for (i, (request, bytes, ms)) in frames.iter().enumerate() {
        let direction = if *request { Rq } else { Rs };
        let time = if *ms == u32::MAX { None } else { ts(*ms) };
        prop_assert_eq!(
            tracker.expects_block_segment(direction),
            reference.expects_block_segment(direction)
        );
        let event = feed(&mut tracker, direction, bytes, time, i as u64 + 1);
        let event = reference::Event {
            message: event.message(),
            chunk: event.chunk(),
            latency: event.latency,
            ended: event.ended,
            started: event.started,
        };
        let expected = reference.feed(direction, bytes, time, i as u64 + 1);
        prop_assert_eq!(event, expected, "frame {}", i + 1);
        prop_assert_eq!(tracker.is_open(), reference.is_open());
    }
    prop_assert_eq!(tracker.finish(), reference.finish());
    Ok(())
}

/// A sequence that keeps the protocol most of the time: each step either
/// the frame the reference's open transfer expects next
/// ([`reference::ReferenceTracker::proposal`]), that frame with its toggle
/// bit flipped, its sub-command bits changed, cut short or sent by the
/// other side, an abort, or arbitrary bytes; with or without a time.
fn scripted(steps: &[(u8, u8, [u8; 8], Option<u32>)]) -> Vec<(bool, Vec<u8>, u32)> {
    let mut reference = reference::ReferenceTracker::new();
    let mut frames = Vec::new();
    for (i, &(kind, pick, data, ms)) in steps.iter().enumerate() {
        let (sender, mut bytes) = reference.proposal(pick, data);
        let mut sender = sender;
        let mut len = 8;
        match kind % 16 {
            0 => bytes[0] ^= 0x10,
            1 => len = usize::from(pick % 8),
            2 => sender = if sender == Rq { Rs } else { Rq },
            3 => bytes[0] = 0x80,
            4 => bytes = data,
            5 => bytes[0] = (bytes[0] & 0xE0) | (pick & 0x1F),
            _ => {}
        }
        let time = ms.map(|ms| ms.saturating_add(i as u32 * 10));
        reference.feed(sender, &bytes[..len], time.and_then(ts), i as u64 + 1);
        frames.push((
            sender == Rq,
            bytes[..len].to_vec(),
            time.unwrap_or(u32::MAX),
        ));
    }
    frames
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// The tracker, which follows a frame's bytes and makes the message
    /// only for the event, says of every frame what the tracker that parsed
    /// each frame first said: message, chunk, latency, started and ended
    /// transfers, and the transfer left open at the end.
    #[test]
    fn the_tracker_follows_the_reference(
        steps in proptest::collection::vec(
            (any::<u8>(), any::<u8>(), any::<[u8; 8]>(), prop_oneof![Just(None), (0u32..5).prop_map(Some)]),
            0..160,
        )
    ) {
        follows_the_reference(&scripted(&steps))?;
    }

    #[test]
    fn the_tracker_follows_the_reference_over_mixed_frames(frames in mixed_frames()) {
        follows_the_reference(&frames)?;
    }

    #[test]
    fn the_tracker_follows_the_reference_over_any_bytes(frames in any_frames()) {
        let frames: Vec<_> = frames.into_iter().enumerate().map(|(i, (c, b))| (c, b, i as u32)).collect();
        follows_the_reference(&frames)?;
    }
}
