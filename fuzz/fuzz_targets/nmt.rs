//! The one-byte error-control messages and object values
//! (docs/canopen.md#error-control; CiA 301 §7.2.8.3).
//!
//! Arbitrary bytes → `Heartbeat::parse`, `GuardAnswer::parse`,
//! `NmtState::from_byte`, and the object values 1016h / 1017h / 100Ch /
//! 100Dh read from the same bytes. Invariants:
//! - an empty slice is exactly the `FrameError::Length` of each message; any
//!   other first byte decodes iff its bits 0–6 are 0x00, 0x04, 0x05 or 0x7F,
//!   else exactly `FrameError::Content(ValueError { what: What::NmtState, found: bits 0–6 })`;
//! - the zero-copy views read every field whatever the state bits, and agree
//!   with the owned values; a decoded message re-encodes to the first byte
//!   (bit 7 kept: reserved bit of a heartbeat, toggle of an answer);
//!   `Heartbeat::new` never sets bit 7;
//! - `NmtState::from_byte` accepts exactly the four codes and round-trips;
//! - a 1016h entry decodes iff its time is non-zero and its node-ID byte is
//!   1..=127, and re-encodes to the low 24 bits; `ErrorControlConfig`
//!   chooses heartbeat iff 1017h ≠ 0, and its node life time is guard time ×
//!   life time factor exactly when guarding is in force with a non-zero
//!   factor.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::canopen::{
    ConsumerEntry, ErrorControlConfig, ErrorControlMethod, GuardAnswer, GuardAnswerFrame,
    Heartbeat, HeartbeatFrame, NmtState, GUARD_ANSWER_LEN, HEARTBEAT_LEN,
};
use motionwire::What;
use motionwire::{FrameError, LenError, ValueError};

fuzz_target!(|data: &[u8]| {
    check_object_values(data);

    let heartbeat = Heartbeat::parse(data);
    let answer = GuardAnswer::parse(data);
    let Some(&byte) = data.first() else {
        assert_eq!(
            heartbeat,
            Err(FrameError::Length(LenError {
                what: What::HeartbeatMessage,
                expected: HEARTBEAT_LEN,
                found: 0,
            }))
        );
        assert_eq!(
            answer,
            Err(FrameError::Length(LenError {
                what: What::NodeGuardingAnswer,
                expected: GUARD_ANSWER_LEN,
                found: 0,
            }))
        );
        return;
    };
    let state_bits = byte & 0x7F;
    let bit7 = byte & 0x80 != 0;
    let state = NmtState::from_byte(state_bits);
    let defined = matches!(state_bits, 0x00 | 0x04 | 0x05 | 0x7F);
    assert_eq!(state.is_ok(), defined);
    if let Err(error) = state {
        assert_eq!(
            error,
            ValueError {
                what: What::NmtState,
                found: u32::from(state_bits),
                expected: "0x00, 0x04, 0x05, 0x7f",
            }
        );
    }
    check_state_byte(byte);

    // The views read every field, whatever the state bits.
    let hb_view = HeartbeatFrame::new_checked(data).expect("one byte");
    assert_eq!(hb_view.state_raw(), state_bits);
    assert_eq!(hb_view.reserved_bit(), bit7);
    assert_eq!(hb_view.state(), state);
    let ga_view = GuardAnswerFrame::new_checked(data).expect("one byte");
    assert_eq!(ga_view.state_raw(), state_bits);
    assert_eq!(ga_view.toggle(), bit7);
    assert_eq!(ga_view.state(), state);

    // With its one byte there, a message's only error is its content's.
    let content = FrameError::Content;
    assert_eq!(heartbeat, Heartbeat::from_bytes(&[byte]).map_err(content));
    assert_eq!(heartbeat, Heartbeat::parse_frame(&hb_view).map_err(content));
    assert_eq!(answer, GuardAnswer::from_bytes(&[byte]).map_err(content));
    assert_eq!(answer, GuardAnswer::parse_frame(&ga_view).map_err(content));

    match (heartbeat, answer) {
        (Ok(heartbeat), Ok(answer)) => {
            let state = state.expect("defined");
            assert_eq!(heartbeat.state(), state);
            assert_eq!(heartbeat.reserved_bit(), bit7);
            assert_eq!(heartbeat.is_boot_up(), state == NmtState::BootUp);
            assert_eq!(heartbeat.to_bytes(), [byte]);
            let mut image = [!byte];
            heartbeat.emit(&mut HeartbeatFrame::new_unchecked(&mut image[..]));
            assert_eq!(image, [byte]);
            // A producer never sets bit 7.
            assert_eq!(Heartbeat::new(state).to_bytes(), [state_bits]);
            let mut image = [0xFF];
            HeartbeatFrame::new_unchecked(&mut image[..]).set_state(state);
            assert_eq!(image, [state_bits]);

            assert_eq!(answer, GuardAnswer::new(bit7, state));
            assert_eq!(answer.to_bytes(), [byte]);
            let mut image = [!byte];
            answer.emit(&mut GuardAnswerFrame::new_unchecked(&mut image[..]));
            assert_eq!(image, [byte]);
        }
        (Err(hb_error), Err(ga_error)) => {
            assert!(!defined);
            assert_eq!(Err::<(), _>(hb_error), state.map(drop).map_err(content));
            assert_eq!(Err::<(), _>(ga_error), state.map(drop).map_err(content));
        }
        (heartbeat, answer) => panic!("the messages disagree: {heartbeat:?} / {answer:?}"),
    }
});

fn check_state_byte(byte: u8) {
    match NmtState::from_byte(byte) {
        Ok(state) => {
            assert!(matches!(byte, 0x00 | 0x04 | 0x05 | 0x7F));
            assert_eq!(state.to_byte(), byte);
            assert_eq!(u8::from(state), byte);
            assert!(NmtState::ALL.contains(&state));
            let _ = (state.name(), state.to_string());
        }
        Err(_) => assert!(!matches!(byte, 0x00 | 0x04 | 0x05 | 0x7F)),
    }
    assert_eq!(NmtState::try_from(byte), NmtState::from_byte(byte));
}

fn check_object_values(data: &[u8]) {
    let mut bytes = [0u8; 5];
    for (slot, byte) in bytes.iter_mut().zip(data) {
        *slot = *byte;
    }
    // 1016h sub-index value: node-ID in bits 16–23, time in ms in bits 0–15.
    let raw = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
    let time_ms = raw as u16;
    let node_byte = (raw >> 16) as u8;
    match ConsumerEntry::from_od_value(raw) {
        Some(entry) => {
            assert!(time_ms != 0 && (1..=127).contains(&node_byte));
            assert_eq!(entry.node.get(), node_byte);
            assert_eq!(entry.time_ms, time_ms);
            assert_eq!(entry.to_od_value(), raw & 0x00FF_FFFF);
            assert_eq!(
                entry.consumer_time(),
                std::time::Duration::from_millis(u64::from(time_ms))
            );
        }
        None => assert!(time_ms == 0 || !(1..=127).contains(&node_byte)),
    }

    // 1017h, 100Ch, 100Dh.
    let config = ErrorControlConfig {
        producer_heartbeat_time_ms: u16::from_le_bytes([bytes[0], bytes[1]]),
        guard_time_ms: u16::from_le_bytes([bytes[2], bytes[3]]),
        life_time_factor: bytes[4],
    };
    let method = config.method();
    let expected = if config.producer_heartbeat_time_ms != 0 {
        ErrorControlMethod::Heartbeat
    } else if config.guard_time_ms != 0 {
        ErrorControlMethod::Guarding
    } else {
        ErrorControlMethod::None
    };
    assert_eq!(method, expected);
    let life_time =
        (method == ErrorControlMethod::Guarding && config.life_time_factor != 0).then(|| {
            std::time::Duration::from_millis(
                u64::from(config.guard_time_ms) * u64::from(config.life_time_factor),
            )
        });
    assert_eq!(config.node_life_time(), life_time);
    let _ = method.to_string();
}
