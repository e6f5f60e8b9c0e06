//! The crate's CAN frame and a frame read as CANopen (ISO 11898-1; CiA 301
//! §7.3.5 Table 72; docs/formats.md#error-frames, docs/canopen.md#identifiers):
//! the `CanFrame` constructors, `ErrorFrame`, `MessageKind::classify` and
//! `CanOpenMessage::decode`.
//!
//! Input: identifier u32 LE, a type byte (low 2 bits: 0 data, 1 remote,
//! 2 CAN FD, 3 error frame; bit 2: extended identifier; bits 4–7: the FD
//! flags), for a remote frame its DLC byte, then the data bytes.
//! Invariants:
//! - a constructor refuses exactly what ISO 11898-1 / Linux refuse (an
//!   identifier too wide, more than 8 data bytes — 64 for CAN FD —, a remote
//!   DLC above 8, an error frame on a standard identifier), with an error,
//!   never a panic; an accepted frame keeps its identifier, type and data;
//!   the borrowed form agrees with the owned one;
//! - `CanOpenMessage::decode` never panics; its kind and node are the ones
//!   identifier table of docs/canopen.md#identifiers gives (also on a
//!   `DecodeError`); only the kinds with a codec refuse data; what decodes
//!   encodes to a frame that decodes to the same message;
//! - an error frame's details appear only when their class is set.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{CanFrame, CanFrameRef, CanId, ErrorClasses, ErrorFrame, FdFlags, FrameType};
use motionwire::canopen::{CanOpenMessage, MessageKind, NmtNodeControl, NodeId};
use motionwire_fuzz::Reader;

fuzz_target!(|input: &[u8]| {
    let mut reader = Reader::new(input);
    let (Some(raw), Some(ty)) = (reader.u32(), reader.u8()) else {
        return;
    };
    let extended = ty & 0b100 != 0;
    let flags = FdFlags::new(ty >> 4).expect("a nibble");
    let (frame_type, data) = match ty & 0b11 {
        0 => (FrameType::Data, &input[5..]),
        1 => {
            let Some(dlc) = reader.u8() else { return };
            (FrameType::Remote { dlc }, &input[6..])
        }
        2 => (FrameType::Fd(flags), &input[5..]),
        _ => (FrameType::Error, &input[5..]),
    };
    check_nmt(data);
    let id = if extended {
        CanId::extended(raw)
    } else {
        CanId::standard(raw)
    };
    let Some(id) = id else {
        assert!(raw > if extended { 0x1FFF_FFFF } else { 0x7FF });
        return;
    };

    let valid = match frame_type {
        FrameType::Data => data.len() <= 8,
        FrameType::Remote { dlc } => dlc <= 8 && data.is_empty(),
        FrameType::Fd(_) => data.len() <= 64,
        FrameType::Error => extended && data.len() <= 8,
    };
    let owned = CanFrame::with_type(id, frame_type, data);
    let borrowed = CanFrameRef::new_ref(id, frame_type, data);
    assert_eq!(owned.is_ok(), valid, "{frame_type:?} {} bytes", data.len());
    assert_eq!(borrowed.is_ok(), valid);
    let (Ok(frame), Ok(view)) = (owned, borrowed) else {
        let _ = owned.map(|_| ()).unwrap_err().to_string();
        return;
    };
    assert_eq!(frame, view);
    assert_eq!(
        (frame.id(), frame.frame_type(), frame.data()),
        (id, frame_type, data)
    );
    assert_eq!(view.to_owned_frame(), frame);
    let _ = frame.to_string();

    check_error_frame(&frame);
    check_message(&frame, raw);
    // The borrowed form decodes the same.
    assert_eq!(
        CanOpenMessage::decode(&view).map_err(|e| (e.kind, e.node, e.error)),
        CanOpenMessage::decode(&frame).map_err(|e| (e.kind, e.node, e.error))
    );
});

fn check_error_frame(frame: &CanFrame) {
    let Ok(error) = ErrorFrame::from_frame(frame) else {
        assert!(!frame.is_error());
        return;
    };
    assert!(frame.is_error());
    assert_eq!(error.classes.bits(), frame.id().raw());
    assert_eq!(error.data(), frame.data());
    if !error.classes.contains(ErrorClasses::CONTROLLER) {
        assert!(error.controller().is_empty());
    }
    if !error.classes.contains(ErrorClasses::COUNTERS) {
        assert_eq!((error.tx_errors(), error.rx_errors()), (None, None));
    }
    let _ = error.to_string();
}

fn check_message(frame: &CanFrame, raw: u32) {
    let (kind, node) = MessageKind::classify(frame);
    let standard = !frame.is_extended();
    let node_bits = (raw & 0x7F) as u8;
    let expected = if frame.is_error() {
        MessageKind::ErrorFrame
    } else if !standard {
        MessageKind::Other
    } else {
        match raw {
            0x000 => MessageKind::NmtCommand,
            0x080 => MessageKind::Sync,
            0x081..=0x0FF => MessageKind::Emcy,
            0x100 => MessageKind::Time,
            0x181..=0x57F if node_bits != 0 => MessageKind::Pdo,
            0x581..=0x5FF | 0x601..=0x67F if node_bits != 0 => MessageKind::Sdo,
            0x701..=0x77F if frame.is_rtr() => MessageKind::GuardRequest,
            0x701..=0x77F => MessageKind::Heartbeat,
            _ => MessageKind::Other,
        }
    };
    assert_eq!(kind, expected, "{frame}");
    let has_node = matches!(
        kind,
        MessageKind::Emcy
            | MessageKind::Pdo
            | MessageKind::Sdo
            | MessageKind::Heartbeat
            | MessageKind::GuardRequest
    );
    assert_eq!(node.map(NodeId::get), has_node.then_some(node_bits));

    match CanOpenMessage::decode(frame) {
        Ok(message) => {
            assert_eq!((message.kind(), message.node()), (kind, node));
            match message.encode() {
                Some(again) => {
                    let decoded = CanOpenMessage::decode(&again);
                    assert_eq!(decoded, Ok(message), "{frame} → {again}");
                }
                None => assert!(frame.is_error()),
            }
        }
        Err(e) => {
            assert_eq!((e.kind, e.node), (kind, node));
            assert!(
                matches!(
                    kind,
                    MessageKind::NmtCommand
                        | MessageKind::Sync
                        | MessageKind::Emcy
                        | MessageKind::Heartbeat
                        | MessageKind::Time
                ),
                "{frame} refused: {e}"
            );
            // TIME is refused only when TIME_OF_DAY's 6 bytes are not there.
            if kind == MessageKind::Time {
                assert!(
                    frame.data().len() < motionwire::canopen::TIME_OF_DAY_LEN,
                    "{frame}"
                );
            }
            assert_eq!(e.partial_emcy.is_some(), kind == MessageKind::Emcy);
            let _ = e.to_string();
        }
    }
}

fn check_nmt(data: &[u8]) {
    if let Ok(control) = NmtNodeControl::parse(data) {
        assert_eq!(control.to_bytes()[..], data[..2]);
        assert_eq!(control.node.map_or(0, NodeId::get), data[1]);
        assert_eq!(control.command.to_byte(), data[0]);
    }
}
