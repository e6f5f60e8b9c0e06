use super::writer::{can_fd_message, can_message, container, file_header, object, Object};
use super::*;
use crate::can::FrameType;
use crate::logs::FormatError;

type ReadAll = (Vec<(u64, LogFrame<'static>)>, Option<FormatError>, u64);

/// Read `file` whole, with the containers inflated on a second thread and
/// on the reading thread: the records, errors included, must be the same.
fn read_all(file: &[u8]) -> ReadAll {
    let ahead = read_all_with(file, |r| r.ahead_always());
    let one = read_all_with(file, BlfReader::on_one_thread);
    assert_eq!(ahead, one, "a second thread or one");
    one
}

fn read_all_with<'f>(
    file: &'f [u8],
    how: impl FnOnce(BlfReader<&'f [u8]>) -> BlfReader<&'f [u8]>,
) -> ReadAll {
    let mut reader = match BlfReader::new(file) {
        Ok(reader) => how(reader),
        Err(e) => return (Vec::new(), Some(binary_error(e)), 0),
    };
    let mut frames = Vec::new();
    let mut error = None;
    while let Some(record) = reader.next_event() {
        match record {
            Ok(LogRecord {
                position: Position::Record(number),
                event: LogEvent::Frame(frame),
            }) => frames.push((number, owned(&frame))),
            Ok(other) => panic!("{other:?}"),
            Err(e) => error = Some(binary_error(e)),
        }
    }
    assert!(reader.next_event().is_none());
    (frames, error, reader.other_records())
}

/// The record without its borrow of the reader (BLF names no interface).
fn owned(frame: &LogFrame<'_>) -> LogFrame<'static> {
    LogFrame {
        frame: frame.frame,
        timestamp: frame.timestamp,
        iface: match frame.iface {
            Some(Iface::Channel(channel)) => Some(Iface::Channel(channel)),
            _ => None,
        },
        direction: frame.direction,
    }
}

fn sample(compress: bool) -> Vec<u8> {
    let mut stream = Vec::new();
    stream.extend(object(&Object {
        kind: object::CAN_MESSAGE,
        nanos: 1_500,
        body: can_message(1, 0, 2, 0x181, &[1, 2]),
    }));
    // A global marker (type 96): counted, skipped.
    stream.extend(object(&Object {
        kind: 96,
        nanos: 2_000,
        body: vec![0; 20],
    }));
    stream.extend(object(&Object {
        kind: object::CAN_MESSAGE2,
        nanos: 3_000,
        body: can_message(2, 0x81, 3, 0x8000_0705, &[9, 9, 9]),
    }));
    stream.extend(object(&Object {
        kind: object::CAN_FD_MESSAGE,
        nanos: 4_000,
        body: can_fd_message(1, 0x01, 9, 0x185, 0x3, &(0..12).collect::<Vec<u8>>()),
    }));
    let mut file = file_header(2023, 11, 14, 22, 13, 20, 500);
    // Two containers, the stream cut in the middle of the third object.
    let (a, b) = stream.split_at(stream.len() / 2 + 3);
    file.extend(container(a, compress));
    file.extend(container(b, compress));
    file
}

#[test]
fn objects_across_containers_stored_and_compressed() {
    for compress in [false, true] {
        let (frames, error, other) = read_all(&sample(compress));
        assert_eq!(error, None);
        assert_eq!(other, 1);
        let numbers: Vec<u64> = frames.iter().map(|(n, _)| *n).collect();
        assert_eq!(numbers, [1, 3, 4]);
        let start = Timestamp::new(1_700_000_000, 500_000).unwrap();
        let (_, first) = &frames[0];
        assert_eq!(first.frame.data(), &[1, 2]);
        assert_eq!(first.iface, Some(Iface::Channel(1)));
        assert_eq!(first.direction, Some(Direction::Rx));
        assert_eq!(
            first.timestamp,
            start.checked_add(core::time::Duration::from_nanos(1_500))
        );
        let (_, remote) = &frames[1];
        assert_eq!(remote.frame.frame_type(), FrameType::Remote { dlc: 3 });
        assert!(remote.frame.is_extended());
        assert_eq!(remote.direction, Some(Direction::Tx));
        let (_, fd) = &frames[2];
        assert_eq!(fd.frame.frame_type(), FrameType::Fd(FdFlags::BRS));
        assert_eq!(fd.frame.data().len(), 12);
    }
}

#[test]
fn valid_bytes_beyond_the_stored_ones_are_zeros() {
    // CAN_FD_MESSAGE_64 whose valid-bytes count (12) exceeds the 4 stored.
    let mut body = vec![0u8; 40];
    body[0] = 1; // channel
    body[1] = 9; // DLC
    body[2] = 12; // valid bytes
    body[4..8].copy_from_slice(&0x123u32.to_le_bytes());
    body[12..16].copy_from_slice(&0x1000u32.to_le_bytes()); // EDL
    body.extend_from_slice(&[1, 2, 3, 4]);
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    file.extend(container(
        &object(&Object {
            kind: object::CAN_FD_MESSAGE_64,
            nanos: 0,
            body,
        }),
        true,
    ));
    let (frames, error, _) = read_all(&file);
    assert_eq!(error, None);
    assert_eq!(
        frames[0].1.frame.data(),
        &[1, 2, 3, 4, 0, 0, 0, 0, 0, 0, 0, 0]
    );
}

#[test]
fn damaged_files() {
    let whole = sample(true);
    let (all, _, _) = read_all(&whole);
    // Where a file may end: after the header or after a container.
    let mut ends = vec![144, whole.len()];
    {
        // The first container's length, from its header.
        let size = u32::from_le_bytes(whole[152..156].try_into().unwrap()) as usize;
        ends.push(144 + size + size % 4);
    }
    // Every cut: a prefix of the frames, then one typed error unless the
    // cut falls where a file may end; never a panic.
    for cut in 0..whole.len() {
        let (frames, error, _) = read_all(&whole[..cut]);
        assert!(
            frames.len() <= all.len() && frames[..] == all[..frames.len()],
            "cut {cut}"
        );
        // A cut inside the padding after a container reads as its end.
        let in_padding = ends
            .iter()
            .any(|&end| end >= cut && end - cut < 4 && whole[cut..end].iter().all(|&b| b == 0));
        if !in_padding {
            assert!(
                matches!(
                    error,
                    Some(FormatError::Binary {
                        format: LogFormat::Blf,
                        ..
                    })
                ),
                "cut {cut}: {error:?}"
            );
        }
    }
    // Not a BLF file.
    let (_, error, _) = read_all(
        b"LOGX and more bytes to fill a header ...............................................",
    );
    assert!(matches!(
        error,
        Some(FormatError::Binary {
            reason: BinaryError::BadMagic { .. },
            ..
        })
    ));
    // A container that claims gigabytes.
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    let mut c = container(b"", false);
    c[8..12].copy_from_slice(&0xF000_0000u32.to_le_bytes());
    file.extend(c);
    let (_, error, _) = read_all(&file);
    assert!(
        matches!(
            error,
            Some(FormatError::Binary {
                offset: 152,
                reason: BinaryError::TooLarge { .. },
                ..
            })
        ),
        "{error:?}"
    );
    // Uncompressed size that claims gigabytes.
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    let mut c = container(&[0; 64], true);
    c[24..28].copy_from_slice(&0xF000_0000u32.to_le_bytes());
    file.extend(c);
    let (_, error, _) = read_all(&file);
    assert!(
        matches!(
            error,
            Some(FormatError::Binary {
                reason: BinaryError::TooLarge { .. },
                ..
            })
        ),
        "{error:?}"
    );
    // A zlib stream that does not inflate, and one of another size.
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    let mut c = container(&[7; 64], true);
    let last = c.len() - 8;
    c[last] ^= 0xFF;
    c[40] ^= 0xFF;
    file.extend(c);
    let (_, error, _) = read_all(&file);
    assert!(
        matches!(
            error,
            Some(FormatError::Binary {
                reason: BinaryError::Decompression,
                ..
            })
        ),
        "{error:?}"
    );
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    let mut c = container(&[7; 64], true);
    c[24..28].copy_from_slice(&65u32.to_le_bytes());
    file.extend(c);
    let (_, error, _) = read_all(&file);
    assert!(
        matches!(
            error,
            Some(FormatError::Binary {
                reason: BinaryError::Decompression,
                ..
            })
        ),
        "{error:?}"
    );
    // An unknown compression method.
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    let mut c = container(&[7; 64], false);
    c[16] = 5;
    file.extend(c);
    let (_, error, _) = read_all(&file);
    assert!(
        matches!(
            error,
            Some(FormatError::Binary {
                reason: BinaryError::UnsupportedCompression { method: 5 },
                ..
            })
        ),
        "{error:?}"
    );
}

#[test]
fn error_ext_in_linux_layout() {
    let mut body = vec![0u8; 32];
    body[0] = 2; // channel
    body[4] = 0x1; // flags: the error byte is SJA1000's ECC
    body[8] = 0b1010_0011; // ECC: stuff error, received, segment 3
    let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
    file.extend(container(
        &object(&Object {
            kind: object::CAN_ERROR_EXT,
            nanos: 0,
            body,
        }),
        false,
    ));
    let (frames, error, _) = read_all(&file);
    assert_eq!(error, None);
    let frame = &frames[0].1.frame;
    let decoded = crate::can::ErrorFrame::from_frame(frame).unwrap();
    assert_eq!(
        decoded.classes,
        ErrorClasses::BUS_ERROR.union(ErrorClasses::PROTOCOL)
    );
    assert_eq!(decoded.protocol(), Some((0x04, 0x03)));
}

mod proptests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn any_bytes_after_a_header(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
            let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
            file.extend_from_slice(&bytes);
            let _ = read_all(&file);
            let _ = read_all(&bytes);
        }

        #[test]
        fn any_container_content(bytes in proptest::collection::vec(any::<u8>(), 0..600), compress in any::<bool>()) {
            let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
            file.extend(container(&bytes, compress));
            let _ = read_all(&file);
        }

        /// Many containers, one byte of the file changed: the same records
        /// and the same error, inflated ahead or not (read_all).
        #[test]
        fn a_damaged_byte_among_many_containers(
            frames in 1usize..200,
            per_container in 1usize..40,
            at in any::<proptest::sample::Index>(),
            byte in any::<u8>(),
        ) {
            let mut file = file_header(2023, 1, 1, 0, 0, 0, 0);
            let objects: Vec<Vec<u8>> = (0..frames)
                .map(|i| {
                    let data = [i as u8; 8];
                    object(&Object {
                        kind: object::CAN_MESSAGE,
                        nanos: i as u64 * 1000,
                        body: can_message(1, 0, 8, 0x181, &data),
                    })
                })
                .collect();
            for (i, chunk) in objects.chunks(per_container).enumerate() {
                file.extend(container(&chunk.concat(), i % 3 != 0));
            }
            let (read, error, _) = read_all(&file);
            prop_assert_eq!(read.len(), frames);
            prop_assert_eq!(error, None);
            let at = 144 + at.index(file.len() - 144);
            file[at] = byte;
            let _ = read_all(&file);
        }

        #[test]
        fn classic_frames_read_back(
            frames in proptest::collection::vec((1u16..4, 0u32..0x800, proptest::collection::vec(any::<u8>(), 0..=8), any::<bool>(), 0u64..1_000_000_000_000), 1..40),
            split in 1usize..64,
            compress in any::<bool>(),
        ) {
            let mut stream = Vec::new();
            for (channel, id, data, tx, nanos) in &frames {
                stream.extend(object(&Object {
                    kind: object::CAN_MESSAGE,
                    nanos: *nanos,
                    body: can_message(*channel, u8::from(*tx), data.len() as u8, *id, data),
                }));
            }
            let mut file = file_header(2024, 2, 29, 23, 59, 59, 999);
            for chunk in stream.chunks(split * 7) {
                file.extend(container(chunk, compress));
            }
            let (read, error, _) = read_all(&file);
            prop_assert_eq!(error, None);
            prop_assert_eq!(read.len(), frames.len());
            let start = Timestamp::new(1_709_251_199, 999_000).unwrap();
            for ((number, got), (i, (channel, id, data, tx, nanos))) in read.iter().zip(frames.iter().enumerate()) {
                prop_assert_eq!(*number, i as u64 + 1);
                prop_assert_eq!(got.frame.id().raw(), *id);
                prop_assert_eq!(got.frame.data(), &data[..]);
                prop_assert_eq!(got.iface, Some(Iface::Channel(*channel)));
                prop_assert_eq!(got.direction, Some(if *tx { Direction::Tx } else { Direction::Rx }));
                prop_assert_eq!(got.timestamp, start.checked_add(core::time::Duration::from_nanos(*nanos)));
            }
        }
    }
}

/// The `FormatError::Binary` of a reader's error (an I/O error is a test failure).
fn binary_error(e: LogError) -> FormatError {
    match e.into_kind() {
        LogErrorKind::Damaged(e) | LogErrorKind::Malformed(e) => e,
        other => panic!("{other}"),
    }
}
