//! A drive's EMCY producer: errors come and go, the EMCY state machine
//! (docs/canopen.md#emcy-producer) decides what to send, and the pre-defined
//! error field 1003h (docs/canopen.md#error-history) fills with the errors
//! sent.
//!
//! Run with `cargo run --example emcy_producer`.

use motionwire::canopen::{
    EmcyEvent, EmcyOutcome, EmcyProducer, ErrorCode, ErrorHistory, ErrorRegister, NodeId,
};

/// Axis 1 in byte 3 of the AKD manufacturer field (docs/canopen.md#akd).
const AXIS_1: [u8; 5] = [0x01, 0, 0, 0, 0];
/// Axis 1, feedback 2 (a feedback fault).
const AXIS_1_FB2: [u8; 5] = [0x21, 0, 0, 0, 0];

fn main() {
    let node = NodeId::new(5).expect("5 is a node-ID");
    let mut producer = EmcyProducer::new();
    let mut history = ErrorHistory::new();

    let over_temperature = ErrorCode::new(0x4210);
    let can_overrun = ErrorCode::new(0x8110);
    let dc_link_over_voltage = ErrorCode::new(0x3210);
    let feedback_fault = ErrorCode::new(0x7305);
    let short_circuit = ErrorCode::new(0x2320);
    let heartbeat = ErrorCode::LIFE_GUARD;

    let story: [(&str, EmcyEvent); 14] = [
        ("power on", EmcyEvent::Initialised),
        ("device too hot", EmcyEvent::error(over_temperature, AXIS_1)),
        ("CAN receive overrun", EmcyEvent::error(can_overrun, [0; 5])),
        ("CAN overrun again", EmcyEvent::error(can_overrun, [0; 5])),
        (
            "DC link over-voltage",
            EmcyEvent::error(dc_link_over_voltage, AXIS_1),
        ),
        ("CAN overrun cleared", EmcyEvent::reset(can_overrun)),
        ("device cooled down", EmcyEvent::reset(over_temperature)),
        ("reset of an inactive error", EmcyEvent::reset(heartbeat)),
        (
            "feedback 2 fault (own register bits)",
            EmcyEvent::error_with_register(
                feedback_fault,
                ErrorRegister::DEVICE_PROFILE | ErrorRegister::MANUFACTURER,
                AXIS_1_FB2,
            ),
        ),
        (
            "short circuit at the output",
            EmcyEvent::error(short_circuit, AXIS_1),
        ),
        ("fault reset by the master", EmcyEvent::AllErrorsReset),
        ("fault reset again", EmcyEvent::AllErrorsReset),
        (
            "heartbeat of the master lost",
            EmcyEvent::error(heartbeat, [0; 5]),
        ),
        ("heartbeat back", EmcyEvent::reset(heartbeat)),
    ];

    println!(
        "EMCY producer of node {} (COB-ID {:#05X})\n",
        node.get(),
        node.emcy_cob_id()
    );
    println!(
        "{:<38} {:<3} {:<25} {:<5} {:<16} register flags",
        "event", "tr", "EMCY data", "reg", "condition"
    );
    for (what, event) in story {
        let outcome = producer.apply(event);
        history.record_outcome(&outcome);
        print_step(what, &outcome, &producer);
    }

    println!("\nPre-defined error field 1003h:");
    print_history(&history);

    let count = history.read(0).unwrap_or(0);
    let past_count = u8::try_from(count + 1).unwrap_or(u8::MAX);
    match history.read(past_count) {
        Ok(value) => println!("  read  sub {past_count}: {value:#010X}"),
        Err(abort) => println!("  read  sub {past_count}: SDO abort {abort}"),
    }
    for (sub_index, value) in [(0u8, 3u32), (1, 0), (0, 0)] {
        match history.write(sub_index, value) {
            Ok(()) => println!("  write sub {sub_index} := {value}: ok, history cleared"),
            Err(abort) => println!("  write sub {sub_index} := {value}: SDO abort {abort}"),
        }
    }
    println!("\nAfter the clear:");
    print_history(&history);
}

fn print_step<const N: usize>(what: &str, outcome: &EmcyOutcome, producer: &EmcyProducer<N>) {
    let transition = outcome
        .transition()
        .map_or_else(|| "-".to_string(), |t| t.number().to_string());
    let (data, register) = match outcome.emcy() {
        Some(emcy) => {
            let bytes: Vec<String> = emcy.to_bytes().iter().map(|b| format!("{b:02X}")).collect();
            (bytes.join(" "), format!("{:#04X}", emcy.register.bits()))
        }
        None => ("(nothing sent)".to_string(), "-".to_string()),
    };
    let flags: Vec<&str> = producer.error_register().names().collect();
    let note = match (outcome.ignored(), outcome.overflow()) {
        (Some(reason), _) => format!("  [{reason}]"),
        (None, Some(code)) => format!("  [overflow: {code} not tracked]"),
        (None, None) => String::new(),
    };
    println!(
        "{what:<38} {transition:<3} {data:<25} {register:<5} {:<16} {}{note}",
        producer.condition().name(),
        if flags.is_empty() {
            "-".to_string()
        } else {
            flags.join(",")
        },
    );
}

fn print_history<const N: usize>(history: &ErrorHistory<N>) {
    println!("  sub 0: {} entries", history.len());
    for (sub_index, entry) in (1..).zip(history) {
        println!(
            "  sub {sub_index}: {:#010X}  code {} ({}), info {:#06X}",
            entry.to_u32(),
            entry.code,
            entry.code.class(),
            entry.additional_info
        );
    }
}
