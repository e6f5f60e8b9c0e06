//! pcap and pcapng captures (docs/formats.md#pcap):
//! `motionwire::logs::pcap::PcapReader`.
//!
//! Arbitrary bytes → the reader, once over the whole input and once through
//! a reader that hands out a few bytes per call. Invariants:
//! - nothing panics; `new` fails or reads a format, pcap or pcapng;
//! - record numbers start at 1 or more and strictly increase; when the file
//!   ends cleanly, the frames and the other records add up to the last
//!   number or more (skipped packets after the last frame);
//! - at most one error that ends the capture, an `FormatError::Binary` of
//!   the reader's format whose offset lies within the input and whose
//!   message prints; `next_event` returns `None` after it and after the
//!   end; an Ethernet packet too short for its headers is a skipped error
//!   with its number, and the capture is read on;
//! - an EtherCAT packet's payload is no longer than the packet
//!   (docs/ethercat.md#reading);
//! - every frame keeps the frame invariants (identifier in range, at most
//!   8 data bytes, 64 for CAN FD, a remote request without data) and has
//!   no direction;
//! - the skipped packets' counts by kind (`other_kinds`) add up to
//!   `other_records`, one entry per kind;
//! - both readings give the same records, error and count: the read-ahead
//!   window does not depend on how the input arrives.
#![no_main]

use std::io::Read;

use libfuzzer_sys::fuzz_target;
use motionwire::can::{CanFrame, LogEvent, Timestamp};
use motionwire::logs::pcap::PcapReader;
use motionwire::logs::FormatError;
use motionwire::logs::LogFormat;
use motionwire::logs::{LogError, LogErrorKind, ReadLog};

struct Chunked<'a> {
    data: &'a [u8],
    step: usize,
}

impl Read for Chunked<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.step.min(buf.len()).min(self.data.len());
        let (head, rest) = self.data.split_at(n);
        buf[..n].copy_from_slice(head);
        self.data = rest;
        Ok(n)
    }
}

type Outcome = (
    Vec<(u64, CanFrame, Option<Timestamp>, Option<String>)>,
    Option<FormatError>,
    u64,
    Vec<(u64, Vec<u8>)>,
);

fn read_all<R: Read>(input: R, len: usize) -> Outcome {
    let mut reader = match PcapReader::new(input) {
        Ok(reader) => reader,
        Err(e) => {
            let e = binary(e);
            check_error(&e, None, len);
            return (Vec::new(), Some(e), 0, Vec::new());
        }
    };
    let format = reader.format();
    assert!(matches!(format, LogFormat::Pcap | LogFormat::Pcapng));
    let mut frames = Vec::new();
    let mut ethernet = Vec::new();
    let mut error = None;
    let mut last = 0;
    while let Some(record) = reader.next_event() {
        assert!(error.is_none(), "a record after an error");
        match record {
            Ok(record) => {
                let number = record.position.number();
                assert!(number > last);
                last = number;
                if let LogEvent::Ethercat(packet) = record.event {
                    assert!(packet.link.payload.len() <= len);
                    ethernet.push((number, packet.link.payload.to_vec()));
                    continue;
                }
                let logged = *record.event.frame().expect("pcap yields frames");
                assert_eq!(logged.direction, None);
                check_frame(&logged.frame);
                frames.push((
                    number,
                    logged.frame,
                    logged.timestamp,
                    logged.iface.map(|i| i.to_string()),
                ));
            }
            Err(e) if e.is_skipped() => {
                let number = e.position().expect("a skipped packet's number").number();
                assert!(number > last);
                last = number;
                let e = binary(e);
                check_error(&e, Some(format), len);
                ethernet.push((number, Vec::new()));
            }
            Err(e) => {
                let e = binary(e);
                check_error(&e, Some(format), len);
                error = Some(e);
            }
        }
    }
    assert!(reader.next_event().is_none());
    let other = reader.other_records();
    // The counts by kind add up to the count, one entry per kind, each
    // message printable.
    let kinds = reader.other_kinds();
    assert_eq!(kinds.iter().map(|k| k.count).sum::<u64>(), other);
    for (i, k) in kinds.iter().enumerate() {
        assert!(k.count > 0);
        assert!(kinds[..i].iter().all(|o| o.kind != k.kind));
        let _ = k.to_string();
    }
    if error.is_none() {
        assert!(frames.len() as u64 + ethernet.len() as u64 + other >= last);
    }
    (frames, error, other, ethernet)
}

/// The `FormatError::Binary` of a reader's error: a slice never fails to read.
fn binary(e: LogError) -> FormatError {
    match e.into_kind() {
        LogErrorKind::Damaged(e) | LogErrorKind::Malformed(e) => e,
        other => panic!("a slice never fails to read: {other}"),
    }
}

fn check_error(error: &FormatError, format: Option<LogFormat>, len: usize) {
    match *error {
        FormatError::Binary {
            format: f, offset, ..
        } => {
            if let Some(format) = format {
                assert_eq!(f, format);
            }
            assert!(offset <= len as u64, "offset {offset} past {len} bytes");
        }
        ref other => panic!("not a binary-log error: {other:?}"),
    }
    let _ = error.to_string();
}

fn check_frame(frame: &CanFrame) {
    let id = frame.id();
    assert!(id.raw() <= if id.is_extended() { 0x1FFF_FFFF } else { 0x7FF });
    if frame.is_fd() {
        assert!(frame.data().len() <= 64);
    } else {
        assert!(frame.data().len() <= 8);
    }
    if frame.is_rtr() {
        assert!(frame.data().is_empty());
        assert!(frame.dlc() <= 8);
    }
    if frame.is_error() {
        assert!(id.is_extended());
    }
}

fuzz_target!(|data: &[u8]| {
    let whole = read_all(data, data.len());
    let step = usize::from(data.first().copied().unwrap_or(1) % 16) + 1;
    let chunked = read_all(Chunked { data, step }, data.len());
    assert_eq!(whole, chunked);
});
