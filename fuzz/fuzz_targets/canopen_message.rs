//! A whole CAN frame read as CANopen (CiA 301 §7.3.5 Table 72; SPEC §6.1):
//! `CanOpenMessage::decode` and the NMT node-control codec.
//!
//! Input: identifier u16 LE, a flags byte (bit 0: remote frame), then the
//! data bytes (a data frame) or the DLC in the next byte (a remote frame).
//! Invariants:
//! - more than 8 data bytes, or a DLC above 8, is refused by `CanPayload`
//!   with an `Error::OutOfRange`; an identifier above 0x7FF is exactly the
//!   `OutOfRange` of an 11-bit identifier;
//! - only the kinds with a codec refuse data (NMT 0x000, SYNC 0x080, EMCY
//!   0x081–0x0FF, heartbeat 0x701–0x77F), never a remote frame;
//! - a decoded message gives back its identifier, its kind name and node as
//!   SPEC §6.1's identifier table says, a payload whose bytes begin the
//!   input's (equal for kinds that keep the data whole), and decoding that
//!   identifier and payload again gives the same message;
//! - the NMT node-control codec on the data: valid → re-encodes to the
//!   first two bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{CanOpenMessage, CanPayload, NmtNodeControl, NodeId};
use motionwire::Error;
use motionwire_fuzz::Reader;

fuzz_target!(|input: &[u8]| {
    let mut reader = Reader::new(input);
    let (Some(id), Some(flags)) = (reader.u16(), reader.u8()) else {
        return;
    };
    let remote = flags & 1 != 0;
    let data = &input[3..];
    check_nmt(data);

    let payload = if remote {
        let dlc = usize::from(data.first().copied().unwrap_or(0));
        match CanPayload::remote(dlc) {
            Ok(payload) => payload,
            Err(error) => {
                assert!(dlc > 8);
                assert!(
                    matches!(error, Error::OutOfRange { max: 8, .. }),
                    "{error:?}"
                );
                return;
            }
        }
    } else {
        match CanPayload::data(data) {
            Ok(payload) => payload,
            Err(error) => {
                assert!(data.len() > 8);
                assert!(
                    matches!(error, Error::OutOfRange { max: 8, .. }),
                    "{error:?}"
                );
                return;
            }
        }
    };
    assert_eq!(payload.is_remote(), remote);
    if !remote {
        assert_eq!(payload.bytes(), data);
        assert_eq!(payload.dlc(), data.len());
    }

    let result = CanOpenMessage::decode(id, payload);
    if id > 0x7FF {
        assert_eq!(
            result,
            Err(Error::OutOfRange {
                what: "11-bit CAN identifier",
                found: u32::from(id),
                min: 0,
                max: 0x7FF,
            })
        );
        return;
    }
    let node_bits = (id & 0x7F) as u8;
    let message = match result {
        Ok(message) => message,
        Err(error) => {
            assert!(!remote, "a remote frame refused: {error:?}");
            assert!(
                id == 0x000
                    || id == 0x080
                    || (0x081..=0x0FF).contains(&id)
                    || (0x701..=0x77F).contains(&id),
                "{id:#05x} refused: {error:?}"
            );
            let _ = error.to_string();
            return;
        }
    };

    // The identifier and kind, as SPEC §6.1's table gives them.
    assert_eq!(message.cob_id(), Some(id));
    let expected_kind = match id {
        0x000 => "nmt_command",
        0x080 => "sync",
        0x081..=0x0FF => "emcy",
        0x181..=0x57F if node_bits != 0 => "pdo",
        0x581..=0x67F if node_bits != 0 => "sdo",
        0x701..=0x77F if remote => "guard_request",
        0x701..=0x77F => "heartbeat",
        _ => "other",
    };
    let expected_kind = match (expected_kind, remote) {
        ("guard_request", true) => "guard_request",
        (_, true) => "other",
        (kind, false) => kind,
    };
    assert_eq!(message.name(), expected_kind, "{id:#05x} remote={remote}");
    match message.node() {
        Some(node) => assert_eq!(node.get(), node_bits),
        None => assert!(!matches!(
            expected_kind,
            "emcy" | "pdo" | "sdo" | "heartbeat" | "guard_request"
        )),
    }
    assert_eq!(
        message.guard_answer().is_some(),
        expected_kind == "heartbeat"
    );

    // The payload comes back: whole, or the prefix a codec reads.
    let back = message.payload();
    match message {
        CanOpenMessage::GuardRequest { .. } => assert_eq!(back, CanPayload::remote(1).unwrap()),
        CanOpenMessage::Heartbeat { .. } | CanOpenMessage::NmtNodeControl(_) => {
            assert!(data.starts_with(back.bytes()), "{back:?} from {data:?}");
        }
        _ => assert_eq!(back, payload),
    }
    // Decoding what it gives back gives the same message.
    assert_eq!(CanOpenMessage::decode(id, back), Ok(message));
    if let CanOpenMessage::Emcy { node, .. } = message {
        assert_eq!(NodeId::new(node_bits), Some(node));
    }
});

fn check_nmt(data: &[u8]) {
    if let Ok(control) = NmtNodeControl::parse(data) {
        assert_eq!(control.to_bytes()[..], data[..2]);
        assert_eq!(control.node.map_or(0, NodeId::get), data[1]);
        assert_eq!(control.command.to_byte(), data[0]);
    }
}
