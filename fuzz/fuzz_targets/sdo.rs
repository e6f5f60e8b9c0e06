//! SDO frames and the transfer tracker (docs/canopen.md#sdo,
//! docs/canopen.md#transfers) fed arbitrary frames of both directions.
//!
//! Input: records of `[header, bytes…]`: header bit 0 the direction
//! (1 request, 0 response), bits 1–4 the frame length (0..=15, cut to 8 and
//! to what is left), bits 5–7 the time step in ms.
//!
//! Invariants:
//! - a request, response or block segment that parses writes bytes that
//!   parse to the same value;
//! - the tracker never hands out more than 7 bytes a frame, nor more bytes
//!   than the frames carried;
//! - every transfer that starts ends exactly once (at a frame or at the end
//!   of the input), and `is_open` says whether one is open;
//! - a transfer never counts more frames than were fed, and its latency and
//!   duration never exceed the time since its start.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::Timestamp;
use motionwire::canopen::sdo::{
    SdoBlockSegment, SdoEvent, SdoParty, SdoRequest, SdoResponse, SdoTracker,
};

fuzz_target!(|input: &[u8]| {
    let mut tracker = SdoTracker::new();
    let mut rest = input;
    let mut ms: u32 = 0;
    let mut line = 0u64;
    let mut carried = 0u64;
    let mut handed_out = 0u64;
    let (mut started, mut ended) = (0u64, 0u64);
    let mut open_since: Option<u64> = None;
    while let Some((&header, tail)) = rest.split_first() {
        let len = usize::from((header >> 1) & 0x0F).min(8).min(tail.len());
        let (data, tail) = tail.split_at(len);
        rest = tail;
        line += 1;
        ms += u32::from(header >> 5);
        let direction = if header & 1 == 1 {
            SdoParty::Client
        } else {
            SdoParty::Server
        };

        if let Ok(r) = SdoRequest::parse(data) {
            assert_eq!(SdoRequest::parse(&r.to_bytes()), Ok(r));
        }
        if let Ok(r) = SdoResponse::parse(data) {
            assert_eq!(SdoResponse::parse(&r.to_bytes()), Ok(r));
        }
        if let Ok(s) = SdoBlockSegment::parse(data) {
            assert_eq!(SdoBlockSegment::parse(&s.to_bytes()), Ok(s));
        }

        carried += data.len().saturating_sub(1) as u64;
        let time = Timestamp::new(u64::from(ms / 1000), ms % 1000 * 1000);
        let mut event = SdoEvent::new(direction, data);
        tracker.feed(&mut event, time, line);
        assert!(event.chunk().len() <= 7);
        handed_out += event.chunk().len() as u64;
        assert!(handed_out <= carried, "{handed_out} bytes out of {carried}");
        if let Some(t) = event.ended {
            let own = event.started && t.start_position == line;
            assert!(open_since.is_some() || own, "an end without a start");
            if !own {
                assert_eq!(Some(t.start_position), open_since);
            }
            assert!(u64::from(t.frames) <= line - t.start_position + 1);
            ended += 1;
            open_since = None;
        }
        if event.started {
            started += 1;
            if event.ended.map_or(true, |t| t.start_position != line) {
                open_since = Some(line);
            }
        }
        assert_eq!(tracker.is_open(), open_since.is_some());
    }
    if let Some(t) = tracker.finish() {
        assert_eq!(Some(t.start_position), open_since);
        ended += 1;
    }
    assert_eq!(started, ended);
});
