//! The `serde` feature, tested through JSON (`serde_json`): the format each
//! kind of type has, round trips of every owned value type, checked types
//! refusing values their constructors refuse, and reserved bits surviving.

use core::fmt::Debug;
use core::time::Duration;

use proptest::prelude::*;
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::can::{CanFrame, CanId, ErrorFrame, FdFlags, FrameData, Timestamp};
use crate::canopen::{
    CanOpenMessage, Cia402Command, Cia402DriveEvent, Cia402State, Cia402Transition, CobFunction,
    Controlword, DeviceSet, Emcy, EmcyTransition, ErrorClass, ErrorCode, ErrorHistoryEntry,
    ErrorRegister, GuardAnswer, GuardingEvent, Heartbeat, HeartbeatEvent, KernelError,
    ModeOfOperation, NmtCommand, NmtNodeControl, NmtState, NodeId, ObjectSet, RecvEmcyResult,
    SdoAbortCode, SlotUpdate, Statusword,
};
use crate::profiles::akd::{AkdEmcy, AkdManufacturer, AxisId, FeedbackId};
use crate::profiles::baumer::{
    Alarms, Appearance, BaumerEmcy, BaumerManufacturer, InjectionCode, InjectionKind,
    ResetBehaviour, Variant, Warnings,
};
use crate::servo::{
    ActualPosition, Command, ECode, EncoderKind, Feedback, Message, MessageCode, ParameterTable,
    RegulatorMode, ServoControlWord, ServoEnable, ServoErrorWord, ServoFault, ServoStatusWord,
};
use crate::strategies::{akd, baumer, can, canopen, error_control, owned, recv_emcy, servo};

fn to_json<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).expect("every value of the crate serializes to JSON")
}

fn from_json<T: DeserializeOwned>(text: &str) -> Result<T, serde_json::Error> {
    serde_json::from_str(text)
}

/// Serialize `value`, check the text is `expected`, and read it back.
fn check_json<T: Serialize + DeserializeOwned + PartialEq + Debug>(value: T, expected: &str) {
    assert_eq!(to_json(&value), expected, "{value:?}");
    assert_eq!(from_json::<T>(expected).unwrap(), value, "{expected}");
}

/// Serialize `value` to JSON and read it back.
fn round_trip<T: Serialize + DeserializeOwned>(value: &T) -> T {
    from_json(&to_json(value)).expect("what was serialized deserializes")
}

/// The message of the error that refusing `text` as a `T` gives.
fn refusal<T: DeserializeOwned + Debug>(text: &str) -> String {
    from_json::<T>(text)
        .expect_err("the text holds a value the type refuses")
        .to_string()
}

fn n(raw: u8) -> NodeId {
    NodeId::new(raw).unwrap()
}

// ---------------------------------------------------------------------------
// Checked numbers: the number itself, range checked on the way in

#[test]
fn checked_numbers_are_their_number() {
    check_json(n(5), "5");
    check_json(NodeId::MAX, "127");
    check_json(ServoEnable::ENABLE, "2");
    check_json(ParameterTable::try_new(7).unwrap(), "7");
    check_json(AxisId::new(15).unwrap(), "15");
    check_json(AxisId::NOT_GIVEN, "0");
    check_json(
        InjectionCode::new(InjectionKind::StartupWarning, 0x001C),
        "262172",
    );
    check_json(InjectionCode::NO_ERROR, "0");
    check_json(ErrorCode::new(0x8130), "33072");
    check_json(SdoAbortCode::NO_DATA_AVAILABLE, "134217764");
}

#[test]
fn every_node_id_outside_1_to_127_is_refused() {
    for raw in (0..=255u8).filter(|raw| !(1..=127).contains(raw)) {
        assert_eq!(
            refusal::<NodeId>(&raw.to_string()),
            format!("node-ID: {raw} is outside 1..=127"),
        );
    }
    // Not a u8 at all: serde's own message.
    assert!(refusal::<NodeId>("256").contains("invalid value"));
    assert!(refusal::<NodeId>("-1").contains("invalid value"));
    assert!(refusal::<NodeId>("\"5\"").contains("invalid type"));
}

#[test]
fn every_servo_enable_above_3_is_refused() {
    for raw in 4..=255u8 {
        assert_eq!(
            refusal::<ServoEnable>(&raw.to_string()),
            format!("servo enable (SCW.SE): {raw} is outside 0..=3"),
        );
    }
}

#[test]
fn every_parameter_table_outside_1_to_8_is_refused() {
    for raw in (0..=255u8).filter(|raw| !(1..=8).contains(raw)) {
        assert_eq!(
            refusal::<ParameterTable>(&raw.to_string()),
            format!("parameter table: {raw} is outside 1..=8"),
        );
    }
}

#[test]
fn axis_ids_and_injection_codes_are_checked() {
    assert_eq!(refusal::<AxisId>("16"), "AKD axis id: 16 is outside 0..=15");
    assert_eq!(
        refusal::<InjectionCode>("131072"),
        "error injection code: 0x20000 is not one of \
         0x00000000 or a high word of 0x0001, 0x0004 or 0x0008",
    );
}

#[test]
fn a_node_id_inside_a_value_is_checked_too() {
    assert!(
        refusal::<HeartbeatEvent>(r#"{"CapacityExceeded":{"node":0,"at":1}}"#)
            .starts_with("node-ID: 0 is outside 1..=127")
    );
    assert!(
        refusal::<RecvEmcyResult>(r#"{"ResetError":{"device":200,"reset":{}}}"#)
            .starts_with("node-ID: 200 is outside 1..=127")
    );
}

// ---------------------------------------------------------------------------
// The device set: its node-IDs, checked

#[test]
fn device_set_is_its_node_ids_in_ascending_order() {
    let devices: DeviceSet = [n(127), n(3), n(64)].into_iter().collect();
    check_json(devices, "[3,64,127]");
    check_json(DeviceSet::EMPTY, "[]");
    assert_eq!(round_trip(&DeviceSet::ALL), DeviceSet::ALL);
    // Any order and repeats read as a set.
    assert_eq!(from_json::<DeviceSet>("[64,3,127,3]").unwrap(), devices);
}

#[test]
fn device_set_refuses_what_is_no_node_id() {
    assert!(refusal::<DeviceSet>("[3,0]").starts_with("node-ID: 0 is outside 1..=127"));
    assert!(refusal::<DeviceSet>("[128]").starts_with("node-ID: 128 is outside 1..=127"));
    assert!(refusal::<DeviceSet>("{}").contains("a sequence of node-IDs 1..=127"));
}

// ---------------------------------------------------------------------------
// Flags: bitflags' text, every bit kept

#[test]
fn flag_words_are_bitflags_text() {
    // Names of the set flags joined by `|`; bits without a name as hex.
    check_json(
        ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION,
        r#""GENERIC | COMMUNICATION""#,
    );
    check_json(ErrorRegister::empty(), r#""""#);
    check_json(
        ServoControlWord::NORMAL.with_servo_enable(ServoEnable::ARM),
        r#""EMGON | BRAKE | 0x1""#,
    );
    check_json(
        ServoStatusWord::SERVO_EN | ServoStatusWord::PULSE_ENABLED,
        r#""SERVO_EN | PULSE_ENABLED""#,
    );
    check_json(
        ServoErrorWord::SERVO_ERRORS | ServoErrorWord::FOLLOWER_ERR,
        r#""SERVO_ERRORS | FOLLOWER_ERR""#,
    );
    check_json(Alarms::BATTERY_EMPTY, r#""BATTERY_EMPTY""#);
    check_json(Warnings::BATTERY_LOW, r#""BATTERY_LOW""#);
    // Written by hand: any spacing, names and hex mixed.
    assert_eq!(
        from_json::<ErrorRegister>(r#""GENERIC|0x40""#)
            .unwrap()
            .bits(),
        0x41
    );
    assert!(refusal::<ErrorRegister>(r#""GENERIC | OVERHEAT""#).contains("OVERHEAT"));
}

#[test]
fn reserved_and_unnamed_bits_survive() {
    // Error register bit 6 is reserved but named.
    check_json(
        ErrorRegister::from_bits_retain(0xC1),
        r#""GENERIC | RESERVED | MANUFACTURER""#,
    );
    // Alarms bits 2 and 8 and warnings bit 1 have no name.
    check_json(
        Alarms::from_bits_retain(0x1104),
        r#""ENCODER_DATA_INVALID | 0x104""#,
    );
    check_json(Warnings::from_bits_retain(0x0002), r#""0x2""#);
    // SEW reserved bits 4 and 25–31.
    check_json(
        ServoErrorWord::from_bits_retain(0xFE00_0010),
        r#""0xfe000010""#,
    );
    // SCW: SE, PRMTBL, ModeSel and reserved bits 13–30 all survive.
    check_json(
        ServoControlWord::from_bits_retain(u32::MAX),
        r#""EMGON | POSLOCK | SINT_LOCK | ERROR_CLEAR | BRAKE | Z_PULSE_REQUEST | EXT_PRMTBL | PRGDWN | 0x7fffe0f3""#,
    );
}

#[test]
fn every_error_register_alarms_and_warnings_value_round_trips() {
    for bits in 0..=u8::MAX {
        let register = ErrorRegister::from_bits_retain(bits);
        assert_eq!(round_trip(&register).bits(), bits);
    }
    for bits in 0..=u16::MAX {
        assert_eq!(round_trip(&Alarms::from_bits_retain(bits)).bits(), bits);
        assert_eq!(round_trip(&Warnings::from_bits_retain(bits)).bits(), bits);
    }
}

#[test]
fn cia402_words_states_commands_and_modes() {
    check_json(
        Statusword::from_bits_retain(0x0237),
        r#""READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | VOLTAGE_ENABLED | QUICK_STOP | REMOTE""#,
    );
    check_json(Controlword::from_bits_retain(0x0080), r#""FAULT_RESET""#);
    for bits in 0..=u16::MAX {
        assert_eq!(round_trip(&Statusword::from_bits_retain(bits)).bits(), bits);
        assert_eq!(
            round_trip(&Controlword::from_bits_retain(bits)).bits(),
            bits
        );
    }
    check_json(Cia402State::QuickStopActive, r#""QuickStopActive""#);
    check_json(Cia402Command::FaultReset, r#""FaultReset""#);
    check_json(Cia402Transition::T3T4, r#""T3T4""#);
    check_json(Cia402DriveEvent::Fault, r#""Fault""#);
    // A mode is its INTEGER8, whatever the value.
    check_json(ModeOfOperation::CYCLIC_SYNCHRONOUS_POSITION, "8");
    for value in i8::MIN..=i8::MAX {
        assert_eq!(round_trip(&ModeOfOperation::from_i8(value)).to_i8(), value);
    }
}

// ---------------------------------------------------------------------------
// Enums and structs: serde's derived format

#[test]
fn enums_are_their_variant_names() {
    check_json(NmtState::PreOperational, r#""PreOperational""#);
    check_json(ObjectSet::Encoder, r#""Encoder""#);
    check_json(ErrorClass::DeviceHardware, r#""DeviceHardware""#);
    check_json(EmcyTransition::FurtherError, r#""FurtherError""#);
    check_json(ECode::E05, r#""E05""#);
    check_json(ServoFault::I2tEndat, r#""I2tEndat""#);
    check_json(RegulatorMode::PreciseSpeed, r#""PreciseSpeed""#);
    check_json(EncoderKind::Incremental, r#""Incremental""#);
    check_json(FeedbackId::Fb2, r#""Fb2""#);
    check_json(FeedbackId::from_nibble(7), r#"{"Unknown":7}"#);
    assert!(refusal::<FeedbackId>(r#"{"Unknown":3}"#).contains("is outside 6..=15"));
    check_json(Appearance::Startup, r#""Startup""#);
    check_json(Variant::NonRedundant, r#""NonRedundant""#);
    check_json(
        ResetBehaviour::AtRebootExceptRedundant,
        r#""AtRebootExceptRedundant""#,
    );
    check_json(InjectionKind::Runtime, r#""Runtime""#);
    check_json(KernelError::NodeIdUnknown, r#""NodeIdUnknown""#);
    check_json(KernelError::Unlisted(0x0042), r#"{"Unlisted":66}"#);
    check_json(MessageCode::Reserved(7), r#"{"Reserved":7}"#);
    check_json(MessageCode::Unknown(-1), r#"{"Unknown":-1}"#);
    check_json(
        ActualPosition::Incremental {
            position: -5,
            zero_pulse_position: 4096,
        },
        r#"{"Incremental":{"position":-5,"zero_pulse_position":4096}}"#,
    );
    check_json(RecvEmcyResult::AllClear, r#""AllClear""#);
    check_json(
        SlotUpdate::Reset { cleared: None },
        r#"{"Reset":{"cleared":null}}"#,
    );
    assert!(refusal::<NmtState>(r#""Initialising""#).contains("unknown variant"));
}

#[test]
fn structs_are_their_fields() {
    // An AKD EMCY (docs/canopen.md#akd): code 0x8130, register 0x11, axis 1.
    let emcy = Emcy::from_bytes(&[0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0]);
    check_json(
        emcy,
        r#"{"code":33072,"register":"GENERIC | COMMUNICATION","manufacturer":[1,0,0,0,0]}"#,
    );
    check_json(
        AkdEmcy::from_emcy(&emcy),
        r#"{"code":33072,"register":"GENERIC | COMMUNICATION","manufacturer":{"axis":1,"feedback":"None","reserved":[0,0,0,0]}}"#,
    );
    check_json(
        Heartbeat::from_bytes(&[0x85]).unwrap(),
        r#"{"state":"Operational","reserved_bit":true}"#,
    );
    check_json(
        GuardAnswer::new(true, NmtState::Stopped),
        r#"{"toggle":true,"state":"Stopped"}"#,
    );
    check_json(
        ErrorHistoryEntry::from_u32(0x0001_4210),
        r#"{"code":16912,"additional_info":1}"#,
    );
    check_json(
        HeartbeatEvent::Timeout {
            node: n(5),
            last_heartbeat: Duration::from_millis(1_000),
            deadline: Duration::from_micros(1_500_000),
        },
        r#"{"Timeout":{"node":5,"last_heartbeat":{"secs":1,"nanos":0},"deadline":{"secs":1,"nanos":500000000}}}"#,
    );
    check_json(
        GuardingEvent::MissingAnswer {
            node: n(9),
            request_at: Duration::from_micros(10),
            due_by: Duration::from_micros(20),
        },
        r#"{"MissingAnswer":{"node":9,"request_at":{"secs":0,"nanos":10000},"due_by":{"secs":0,"nanos":20000}}}"#,
    );
    check_json(
        Command::new(-1500, ServoControlWord::NORMAL, 0),
        r#"{"speed_setpoint":-1500,"control":"EMGON | BRAKE","extra_data_code":0}"#,
    );
    check_json(
        BaumerManufacturer::new(Alarms::empty(), Warnings::MULTITURN_SYSTEM),
        r#"{"alarms":"","warnings":"MULTITURN_SYSTEM","unused":0}"#,
    );
    // A heartbeat's state is checked like the byte's.
    assert!(
        refusal::<Heartbeat>(r#"{"state":"Sleeping","reserved_bit":false}"#)
            .contains("unknown variant")
    );
}

#[test]
fn floats_are_numbers_and_json_cannot_carry_nan() {
    let message = Message::new(MessageCode::BusVoltage, 560.5);
    assert_eq!(to_json(&message), r#"{"code":3,"data":560.5}"#);
    assert_eq!(round_trip(&message), message);
    // -0.0 keeps its sign.
    let zero = Message::from_raw(0, -0.0);
    assert_eq!(round_trip(&zero).data.to_bits(), (-0.0f32).to_bits());
    // JSON has no NaN: serde_json writes null, and null is no f32. The
    // value is refused, never replaced by another.
    let nan = Message::from_raw(0, f32::NAN);
    assert_eq!(to_json(&nan), r#"{"code":0,"data":null}"#);
    assert!(from_json::<Message>(&to_json(&nan)).is_err());
}

// ---------------------------------------------------------------------------
// Round trips of every owned value type

/// Check the round trip of `value` through JSON.
fn same<T: Serialize + DeserializeOwned + PartialEq + Debug>(
    value: T,
) -> Result<(), TestCaseError> {
    prop_assert_eq!(round_trip(&value), value);
    Ok(())
}

proptest! {
    #[test]
    fn canopen_values_round_trip(
        node in canopen::node_id(),
        code in canopen::error_code(),
        class in owned::error_class(),
        register in canopen::error_register(),
        emcy in canopen::emcy(),
        state in error_control::nmt_state(),
        heartbeat in error_control::heartbeat(),
        answer in error_control::guard_answer(),
        abort in owned::sdo_abort_code(),
        kernel in owned::kernel_error(),
        entry in owned::error_history_entry(),
        transition in owned::emcy_transition(),
        devices in recv_emcy::device_set(),
    ) {
        same(node)?;
        same(code)?;
        same(class)?;
        same(register)?;
        same(emcy)?;
        same(state)?;
        same(heartbeat)?;
        same(answer)?;
        same(abort)?;
        same(kernel)?;
        same(entry)?;
        same(transition)?;
        same(devices)?;
    }

    #[test]
    fn canopen_events_round_trip(
        heartbeat_event in owned::heartbeat_event(),
        guarding_event in owned::guarding_event(),
        result in owned::recv_emcy_result(),
        update in owned::slot_update(),
    ) {
        same(heartbeat_event)?;
        same(guarding_event)?;
        same(result)?;
        same(update)?;
    }

    #[test]
    fn any_device_set_round_trips(mask in any::<u128>()) {
        let devices: DeviceSet = NodeId::all().filter(|node| mask & (1 << node.index()) != 0).collect();
        same(devices)?;
    }

    #[test]
    fn servo_values_round_trip(
        control in servo::control_word(),
        status in servo::status_word(),
        errors in servo::error_word(),
        enable in servo::servo_enable(),
        mode in owned::regulator_mode(),
        table in servo::parameter_table(),
        encoder in owned::encoder_kind(),
        fault in owned::servo_fault(),
        e_code in owned::e_code(),
        kind in owned::message_code(),
        position in servo::actual_position(),
        command in servo::command(),
    ) {
        same(control)?;
        same(status)?;
        same(errors)?;
        same(enable)?;
        same(mode)?;
        same(table)?;
        same(encoder)?;
        same(fault)?;
        same(e_code)?;
        same(kind)?;
        same(position)?;
        same(command)?;
    }

    /// Floats compared by their bits: a finite value comes back exactly.
    #[test]
    fn servo_frames_with_finite_floats_round_trip(
        message in owned::finite_message(),
        feedback in owned::finite_feedback(),
    ) {
        let back = round_trip(&message);
        prop_assert_eq!((back.code, back.data.to_bits()), (message.code, message.data.to_bits()));
        prop_assert_eq!(round_trip(&feedback).to_bytes(), feedback.to_bytes());
    }

    #[test]
    fn profile_values_round_trip(
        axis in akd::axis_id(),
        feedback in akd::feedback_id(),
        akd_manufacturer in akd::akd_manufacturer(),
        akd_emcy in akd::akd_emcy(),
        alarms in baumer::alarms(),
        warnings in baumer::warnings(),
        baumer_manufacturer in baumer::manufacturer(),
        baumer_emcy in baumer::baumer_emcy(),
        appearance in owned::appearance(),
        variant in owned::variant(),
        reset in owned::reset_behaviour(),
        injection_kind in baumer::injection_kind(),
        injection_code in baumer::injection_code(),
    ) {
        same(axis)?;
        same(feedback)?;
        same(akd_manufacturer)?;
        same(akd_emcy)?;
        same(alarms)?;
        same(warnings)?;
        same(baumer_manufacturer)?;
        same(baumer_emcy)?;
        same(appearance)?;
        same(variant)?;
        same(reset)?;
        same(injection_kind)?;
        same(injection_code)?;
    }

    /// Whatever number a text holds, a checked type is made only through its
    /// constructor: accepted exactly when `try_new` accepts.
    #[test]
    fn checked_types_accept_what_their_constructors_accept(raw in any::<u8>(), wide in any::<u32>()) {
        let text = raw.to_string();
        prop_assert_eq!(from_json::<NodeId>(&text).ok(), NodeId::new(raw));
        prop_assert_eq!(from_json::<ServoEnable>(&text).ok(), ServoEnable::new(raw));
        prop_assert_eq!(from_json::<ParameterTable>(&text).ok(), ParameterTable::new(raw));
        prop_assert_eq!(from_json::<AxisId>(&text).ok(), AxisId::new(raw));
        prop_assert_eq!(
            from_json::<InjectionCode>(&wide.to_string()).ok(),
            InjectionCode::try_new(wide).ok()
        );
    }
}

#[test]
fn akd_manufacturer_refuses_an_undefined_feedback() {
    assert!(
        refusal::<AkdManufacturer>(r#"{"axis":1,"feedback":"Fb6","reserved":[0,0,0,0]}"#)
            .contains("unknown variant `Fb6`")
    );
    assert!(refusal::<BaumerEmcy>(
        r#"{"code":1,"register":"","manufacturer":{"alarms":"","warnings":"","unused":256}}"#
    )
    .contains("invalid value"));
    // Feedback compared by bytes: PartialEq would compare floats by value.
    let feedback = Feedback {
        position: 1,
        status: ServoStatusWord::SERVO_EN,
        errors: ServoErrorWord::empty(),
        message: Message::new(MessageCode::MotorSpeed, 1500.0),
        extra_data: [0.5, -0.0, 1e-40, f32::MAX],
    };
    assert_eq!(round_trip(&feedback).to_bytes(), feedback.to_bytes());
}

// ---------------------------------------------------------------------------
// Whole CAN frames read as CANopen

#[test]
fn can_frames_are_their_fields() {
    check_json(FrameData::new(&[0x40, 0x00, 0x10]).unwrap(), "[64,0,16]");
    let id = |raw| CanId::standard(raw).unwrap();
    check_json(
        CanFrame::new_remote(id(0x705), 1).unwrap(),
        r#"{"id":{"raw":1797,"extended":false},"frame_type":{"Remote":{"dlc":1}},"data":[]}"#,
    );
    check_json(
        CanFrame::new_fd(id(0x123), FdFlags::BRS, &[1]).unwrap(),
        r#"{"id":{"raw":291,"extended":false},"frame_type":{"Fd":1},"data":[1]}"#,
    );
    check_json(
        ErrorFrame::from_frame(&CanFrame::new_error(0x40, &[0; 2]).unwrap()).unwrap(),
        r#"{"classes":"BUS_OFF","data":[0,0]}"#,
    );
    check_json(Timestamp::new(3, 4).unwrap(), r#"{"secs":3,"nanos":4000}"#);
    check_json(
        NmtNodeControl::new(NmtCommand::ResetCommunication, None),
        r#"{"command":"ResetCommunication","node":null}"#,
    );
    check_json(
        CanOpenMessage::GuardRequest { node: n(5) },
        r#"{"GuardRequest":{"node":5}}"#,
    );
    check_json(
        CanOpenMessage::decode(&CanFrame::new(id(0x285), &[1, 2]).unwrap()).unwrap(),
        r#"{"Pdo":{"node":5,"number":2,"direction":"Transmit","data":[1,2]}}"#,
    );
    check_json(CobFunction::classify(0x705), r#"{"ErrorControl":5}"#);
}

#[test]
fn can_frames_refuse_what_their_constructors_refuse() {
    assert!(refusal::<FrameData>(&format!("{:?}", [0u8; 65])).contains("invalid length 65"));
    assert!(refusal::<FrameData>("[256]").contains("invalid value"));
    assert!(refusal::<CanId>(r#"{"raw":2048,"extended":false}"#).contains("invalid value"));
    assert_eq!(
        refusal::<CanFrame>(
            r#"{"id":{"raw":1,"extended":false},"frame_type":"Data","data":[1,2,3,4,5,6,7,8,9]}"#
        ),
        "CAN frame data length: 9 is outside 0..=8"
    );
    assert_eq!(
        refusal::<CanFrame>(
            r#"{"id":{"raw":1,"extended":false},"frame_type":{"Remote":{"dlc":9}},"data":[]}"#
        ),
        "CAN remote request length: 9 is outside 0..=8"
    );
    assert!(
        refusal::<NmtNodeControl>(r#"{"command":"StartRemoteNode","node":0}"#)
            .starts_with("node-ID: 0 is outside 1..=127")
    );
}

proptest! {
    #[test]
    fn frames_round_trip(frame in can::any_can_frame(), ts in can::timestamp()) {
        same(frame)?;
        same(ts)?;
    }
}

proptest! {
    #[test]
    fn can_values_round_trip(
        message in can::canopen_message(),
        control in can::nmt_node_control(),
        id in 0u16..=0x7FF,
    ) {
        same(message)?;
        same(control)?;
        same(CobFunction::classify(id))?;
    }
}

#[test]
fn pdo_types() {
    use crate::canopen::{
        DataType, MappingEntry, Octets, PdoCobId, PdoMapping, Signal, TransmissionType, Value,
    };

    check_json(
        MappingEntry::from_u32(0x6041_0010),
        r#"{"index":24641,"sub_index":0,"bits":16}"#,
    );
    let mapping = PdoMapping::from_u32s(&[0x6041_0010, 0x0005_0008]).unwrap();
    check_json(
        mapping,
        r#"[{"index":24641,"sub_index":0,"bits":16},{"index":5,"sub_index":0,"bits":8}]"#,
    );
    check_json(PdoCobId::from_u32(0x8000_0181), "2147484033");
    check_json(TransmissionType::from_byte(254), "254");
    check_json(DataType::Integer24, r#""Integer24""#);
    check_json(Value::Signed(-2), r#"{"Signed":-2}"#);
    check_json(
        Value::Octets(Octets::new(b"AK", 12).unwrap()),
        r#"{"Octets":{"bits":12,"bytes":[65,11]}}"#,
    );
    check_json(
        Signal {
            entry: MappingEntry::from_u32(0x6061_0008),
            offset: 16,
            data_type: Some(DataType::Integer8),
            value: Value::Signed(-1),
        },
        r#"{"entry":{"index":24673,"sub_index":0,"bits":8},"offset":16,"data_type":"Integer8","value":{"Signed":-1}}"#,
    );
    assert!(
        refusal::<PdoMapping>(r#"[{"index":24641,"sub_index":0,"bits":0}]"#)
            .starts_with("PDO mapping entry length: 0 is outside 1..=255")
    );
    let too_many = format!(
        "[{}]",
        [r#"{"index":1,"sub_index":0,"bits":9}"#; 57].join(",")
    );
    assert!(refusal::<PdoMapping>(&too_many)
        .starts_with("PDO mapping length in bits: 513 is outside 0..=512"));
    assert!(refusal::<Octets>(r#"{"bits":12,"bytes":[65]}"#)
        .starts_with("1 bytes do not hold 12 bits exactly"));
    assert!(refusal::<Octets>(&format!(
        r#"{{"bits":8,"bytes":[{}]}}"#,
        ["0"; 33].join(",")
    ))
    .starts_with("invalid length 33"));
}

proptest! {
    #[test]
    fn pdo_values_round_trip(
        (mapping, _seed, values) in crate::strategies::pdo::mapping_and_values(),
    ) {
        same(mapping)?;
        for value in values {
            // Reals are left out: NaN is not JSON
            // (floats_are_numbers_and_json_cannot_carry_nan), and serde_json
            // without `float_roundtrip` may round the last digit of an f64.
            if !matches!(
                value,
                crate::canopen::Value::Real32(_) | crate::canopen::Value::Real64(_)
            ) {
                same(value)?;
            }
        }
    }
}
