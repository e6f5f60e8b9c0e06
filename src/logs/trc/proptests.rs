//! Property tests: nothing panics, errors point into the line, and every
//! frame written in version 2.1 reads back to itself.

use proptest::prelude::*;

use super::row::{FD_LENGTHS, PROT_LOCATION, PROT_TX, PROT_TYPES};
use super::*;
use crate::can::{CanFrame, Direction, FdFlags, Iface, LogEvent, LogFrame, Timestamp};
use crate::logs::error::Result;
use crate::logs::FormatError;
use crate::logs::LogFormat;
use crate::test_gens::can::can_id;

/// Every state a header can put the parser in, with and without columns.
fn parsers() -> Vec<TrcParser> {
    let mut all = Vec::new();
    for version in TrcVersion::ALL {
        let mut p = TrcParser::new();
        p.parse_line(format!(";$FILEVERSION={version}").as_bytes())
            .unwrap();
        p.parse_line(b";$STARTTIME=45244.5").unwrap();
        all.push(p);
    }
    let mut p = TrcParser::new();
    p.parse_line(b";$FILEVERSION=2.0").unwrap();
    p.parse_line(b";$COLUMNS=O,T,l,I,B,D").unwrap();
    all.push(p);
    all
}

/// The checks every result must pass.
fn check(line: &[u8], result: &Result<Option<LogEvent<'_>>>) -> Result<(), TestCaseError> {
    match result {
        Ok(Some(LogEvent::Frame(f))) => {
            prop_assert!(f.timestamp.is_some());
            prop_assert!(f.frame.data().len() <= f.frame.frame_type().max_len());
            prop_assert!(!matches!(f.iface, Some(Iface::Name(_))));
        }
        Ok(Some(LogEvent::Status(_)) | None) => {}
        Ok(Some(LogEvent::Ethercat(_))) => prop_assert!(false, "a TRC line is no EtherCAT packet"),
        Err(FormatError::Syntax {
            format: LogFormat::Trc,
            column,
            reason,
        }) => {
            prop_assert!(*column >= 1 && *column <= line.len() + 1);
            prop_assert!(!reason.to_string().is_empty());
        }
        Err(other) => prop_assert!(false, "not a TRC syntax error: {other:?}"),
    }
    Ok(())
}

/// Lines that look like rows of any version, with bytes changed.
fn row_like() -> impl Strategy<Value = Vec<u8>> {
    let rows = prop_oneof![
        Just("     1)      1841  0001  8  00 01 02 03 04 05 06 07"),
        Just("     2)      1842  0008  4  ERROR 00 19 08 08"),
        Just("     1)      1841.0  Rx         0081  2  30 81"),
        Just("     5)      1845.9  Warng  FFFFFFFF  4  00 00 00 04  BUSLIGHT"),
        Just("     1)      1841.512 1  Rx        0081 -  1    RTR"),
        Just("      1      1334.416 FD 1      0500 Rx -  9    00 01 02 03 04 05 06 07 08 09 0A 0B"),
        Just("      5      1334.522 ER 1         - Rx -  5    04 00 02 00 00"),
        Just("      6      1334.522 ER          Rx    04 00 02 00 00"),
        Just("      7      1334.531 ST 1         - Rx -  4    00 00 00 08"),
        Just(";$STARTTIME=44548.6028595139"),
        Just(";$COLUMNS=N,O,T,B,I,d,R,L,D"),
    ];
    (
        rows,
        proptest::collection::vec((any::<usize>(), any::<u8>()), 0..4),
    )
        .prop_map(|(row, changes)| {
            let mut bytes = row.as_bytes().to_vec();
            for (at, byte) in changes {
                let at = at % (bytes.len() + 1);
                if byte % 3 == 0 && at < bytes.len() {
                    bytes.remove(at);
                } else if byte % 3 == 1 {
                    bytes.insert(at, byte);
                } else if at < bytes.len() {
                    bytes[at] = b"0123456789ABCDEF -.)"[usize::from(byte) % 20];
                }
            }
            bytes
        })
}

/// Any frame a TRC 2.1 row holds.
fn trc_frame() -> impl Strategy<Value = CanFrame> {
    let fd_len = proptest::sample::select(FD_LENGTHS.to_vec());
    prop_oneof![
        4 => (can_id(), proptest::collection::vec(any::<u8>(), 0..=8))
            .prop_map(|(id, data)| CanFrame::new(id, &data).unwrap()),
        1 => (can_id(), 0u8..=8).prop_map(|(id, dlc)| CanFrame::new_remote(id, dlc).unwrap()),
        3 => (can_id(), 0u8..4, fd_len, any::<u8>()).prop_map(|(id, flags, len, seed)| {
            let data: Vec<u8> = (0..len).map(|i| i.wrapping_mul(31) ^ seed).collect();
            CanFrame::new_fd(id, FdFlags::new(flags).unwrap(), &data).unwrap()
        }),
        1 => (any::<u8>(), any::<u8>(), any::<u8>(), any::<u8>()).prop_map(|(prot, loc, tx, rx)| {
            let data = [0, 0, prot & (PROT_TYPES | PROT_TX), loc & PROT_LOCATION, 0, 0, tx, rx];
            CanFrame::new_error(ERROR_FRAME_CLASSES.bits(), &data).unwrap()
        }),
    ]
}

fn trc_log_frame() -> impl Strategy<Value = (Timestamp, Vec<LogFrame<'static>>)> {
    let start = (0u64..200_000_000_000, 0u32..1_000_000_000)
        .prop_map(|(s, n)| Timestamp::from_nanos(s, n).unwrap());
    let frame = (
        trc_frame(),
        0u64..10_000_000_000_000,
        proptest::option::of(any::<u16>()),
        proptest::option::of(prop_oneof![Just(Direction::Rx), Just(Direction::Tx)]),
    );
    (start, proptest::collection::vec(frame, 1..8)).prop_map(|(start, frames)| {
        let base = Timestamp::from_nanos(start.secs(), start.micros() * 1_000).unwrap();
        let frames = frames
            .into_iter()
            .map(|(frame, after, bus, direction)| LogFrame {
                frame,
                timestamp: base.checked_add(core::time::Duration::from_nanos(after)),
                iface: bus.map(Iface::Channel),
                direction,
            })
            .collect();
        (start, frames)
    })
}

proptest! {
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        for mut parser in parsers() {
            let result = parser.parse_line(&bytes);
            check(&bytes, &result)?;
        }
        for (n, item) in lines(&bytes) {
            prop_assert!(n.number() >= 1);
            let _ = item;
        }
    }

    #[test]
    fn near_valid_rows_never_panic(line in row_like()) {
        for mut parser in parsers() {
            let result = parser.parse_line(&line);
            check(&line, &result)?;
            if let Ok(Some(LogEvent::Frame(frame))) = result {
                // Whatever parses as a frame of a 2.1 shape writes back.
                let start = parser.start_time().unwrap_or(Timestamp::ZERO);
                let mut text = String::new();
                write_header(&mut text, start).unwrap();
                if write_line(&mut text, 1, start, &frame).is_ok() {
                    let back: Vec<_> = lines(text.as_bytes()).filter_map(|(_, r)| r.unwrap()).collect();
                    prop_assert_eq!(back, vec![LogEvent::Frame(frame)]);
                }
            }
        }
    }

    #[test]
    fn written_frames_read_back((start, frames) in trc_log_frame()) {
        let mut text = String::new();
        write_header(&mut text, start).unwrap();
        for (n, frame) in frames.iter().enumerate() {
            write_line(&mut text, n as u64, start, frame).unwrap();
        }
        let mut lines = lines(text.as_bytes());
        let back: Vec<_> = lines.by_ref().filter_map(|(_, r)| r.unwrap()).collect();
        let expected: Vec<_> = frames.into_iter().map(LogEvent::Frame).collect();
        prop_assert_eq!(back, expected);
        prop_assert_eq!(lines.parser().version(), TrcVersion::V2_1);
        // The header keeps the start to the microsecond.
        let micros = Timestamp::from_nanos(start.secs(), start.micros() * 1_000).unwrap();
        prop_assert_eq!(lines.parser().start_time(), Some(micros));
    }
}
