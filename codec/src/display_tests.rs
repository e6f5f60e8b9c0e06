//! `Display` of every type a user prints, each against the text written
//! out.

use crate::can::{CanFrame, CanId};
use crate::canopen::sdo::{BrokenReason, SdoOutcome, SdoParty, TransferMode};
use crate::canopen::{
    CanOpenMessage, Emcy, ErrorCode, ErrorRegister, GuardAnswer, Heartbeat, NmtCommand,
    NmtNodeControl, NmtState, NodeId, RecvEmcyResult, SdoAbortCode,
};
use crate::servo::{Command, Feedback, ServoControlWord, ServoStatusWord};

fn n(raw: u8) -> NodeId {
    NodeId::new(raw).unwrap()
}

#[test]
fn canopen_values() {
    assert_eq!(ErrorCode::new(0x8130).to_string(), "0x8130");
    assert_eq!(
        ErrorRegister::from_bits_retain(0x81).to_string(),
        "0x81 [generic|manufacturer]"
    );
    assert_eq!(NmtState::Operational.to_string(), "operational");
    assert_eq!(
        Heartbeat::new(NmtState::Stopped).to_string(),
        "heartbeat stopped"
    );
    assert_eq!(Heartbeat::boot_up().to_string(), "boot-up");
    assert_eq!(
        GuardAnswer::new(true, NmtState::PreOperational).to_string(),
        "guard answer pre_operational, toggle 1"
    );
    let reset = NmtNodeControl::new(NmtCommand::ResetNode, Some(n(9)));
    assert_eq!(
        reset.to_string(),
        format!("NMT {} to node 9", NmtCommand::ResetNode)
    );
    let all = NmtNodeControl::new(NmtCommand::StartRemoteNode, None);
    assert!(all.to_string().ends_with(" to all nodes"));
    assert_eq!(
        SdoAbortCode::new(0x0602_0000).to_string(),
        format!(
            "0x06020000: {}",
            SdoAbortCode::new(0x0602_0000).description()
        )
    );
}

/// docs/output.md#sdo-text: the words of the transfer texts, without the
/// object and the figures.
#[test]
fn sdo_outcomes() {
    let code = SdoAbortCode::new(0x0604_0043);
    let cases = [
        (SdoOutcome::Completed, "completed".to_string()),
        (
            SdoOutcome::Aborted {
                by: SdoParty::Server,
                code,
            },
            format!("aborted by the server: {}", code.description()),
        ),
        (
            SdoOutcome::Broken(BrokenReason::WrongToggle),
            "broken: toggle bit not alternated".to_string(),
        ),
        (SdoOutcome::TimedOut, "timed out: no answer".to_string()),
    ];
    for (outcome, text) in cases {
        assert_eq!(outcome.to_string(), text);
    }
    assert_eq!(
        SdoOutcome::Aborted {
            by: SdoParty::Server,
            code
        }
        .to_string(),
        "aborted by the server: General parameter incompatibility reason"
    );
    assert_eq!(SdoParty::Client.to_string(), "client");
    assert_eq!(TransferMode::Segmented.to_string(), "segmented");
}

#[test]
fn recv_emcy_results() {
    let emcy = Emcy::from_bytes(&[0x30, 0x81, 0x11, 0, 0, 0, 0, 0]);
    assert_eq!(
        RecvEmcyResult::Error { device: n(5), emcy }.to_string(),
        format!("device 5: {emcy}")
    );
    let reset = Emcy::reset(ErrorRegister::empty());
    assert_eq!(
        RecvEmcyResult::ResetError {
            device: n(5),
            reset
        }
        .to_string(),
        format!("device 5: reset ({reset})")
    );
    assert_eq!(RecvEmcyResult::AllClear.to_string(), "all clear");
}

#[test]
fn messages() {
    let id = |raw| CanId::standard(raw).unwrap();
    let cases = [
        (CanFrame::new(id(0x080), &[7]).unwrap(), "SYNC 7"),
        (CanFrame::new(id(0x080), &[]).unwrap(), "SYNC"),
        (
            CanFrame::new_remote(id(0x703), 1).unwrap(),
            "node 3 guard request",
        ),
        (
            CanFrame::new(id(0x603), &[0x40, 0x00, 0x10, 0]).unwrap(),
            "node 3 SDO request [4] 40 00 10 00",
        ),
        (CanFrame::new(id(0x7E5), &[1]).unwrap(), "7E5#01"),
        (
            CanFrame::new(id(0x705), &[0x92]).unwrap(),
            "node 5 heartbeat invalid state 0x12 (toggle 1)",
        ),
    ];
    for (frame, text) in cases {
        assert_eq!(CanOpenMessage::decode(&frame).unwrap().to_string(), text);
    }
}

#[test]
fn servo_words() {
    let control = ServoControlWord::from_bits_retain(0);
    assert_eq!(control.to_string(), "0x00000000 []");
    let status = ServoStatusWord::SERVO_EN | ServoStatusWord::SERVO_RDY;
    assert_eq!(status.to_string(), "0x00000003 [ServoEn|ServoRDY]");
}

/// `motionwire servo command` and `servo feedback` print these lines
/// (docs/servo.md#cli-command, docs/servo.md#cli-feedback); the program's
/// output is a contract, so the spacing is too: the flags line of a word
/// without flags keeps its trailing space, a message without a unit keeps the
/// empty unit between two spaces.
#[test]
fn servo_frame_details() {
    let command =
        Command::from_bytes(&[0x18, 0xFC, 0xFF, 0xFF, 0x01, 0x00, 0x00, 0x80, 0x34, 0x12]);
    assert_eq!(
        command.details().to_string(),
        "speed set point   -1000 (word reading -1000)\n\
         control word      0x80000001\n  \
         servo enable    0b01\n  \
         emergency       active (EMGON = 0)\n  \
         internal brake  active (Brake = 0)\n  \
         regulator mode  speed\n  \
         parameter table 1\n  \
         flags           PRGDWN\n\
         extra data code   4660"
    );
    let bare = Command::from_bytes(&[0; 10]).details().to_string();
    assert!(
        bare.contains("\n  flags          \nextra data code   0"),
        "{bare}"
    );
    assert_eq!(command.details().command(), command);

    let bytes: [u8; 40] = [
        0x40, 0xE2, 0x01, 0x00, 0x00, 0x10, 0x00, 0x00, // ActPos
        0x0B, 0x00, 0x00, 0x00, // SSW: ServoEn ServoRDY ZPulseAck, absolute
        0x06, 0x00, 0x00, 0x00, // SEW: EncoderErr, I2t_Endat (no summary bit)
        0x2A, 0x00, 0x00, 0x00, // message code 42
        0xCD, 0xCC, 0x4C, 0x3F, // 0.8
        0x00, 0x00, 0xC0, 0x7F, // NaN
        0x00, 0x00, 0x80, 0x7F, // inf
        0x00, 0x00, 0x80, 0xFF, // -inf
        0x00, 0x00, 0x00, 0x80, // -0
    ];
    let feedback = Feedback::from_bytes(&bytes);
    assert_eq!(
        feedback.details().to_string(),
        "position          17592186167872 (absolute encoder)\n\
         status word       0x0000000B: ServoEn ServoRDY ZPulseAck\n  \
         parameter table 1\n\
         error word        0x00000006\n  \
         bit  1 E01 EncoderErr: encoder error (EnDat, SinCos or TTL)\n  \
         bit  2 E19 I2t_Endat: EnDat encoder temperature above Max_Temperature (usually 95 °C)\n\
         message           unknown = 0.8  (code 42)\n\
         extra data        NaN inf -inf -0"
    );
    let empty = Feedback::from_bytes(&[0; 40]).details().to_string();
    assert!(empty.contains("status word       0x00000000:\n"), "{empty}");
    assert_eq!(feedback.details().feedback().to_bytes(), bytes);
}
