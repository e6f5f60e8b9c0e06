//! Decode the EMCY frames a Kollmorgen AKD sends through its error state
//! machine (seed 000, "Application of the Emergency Object";
//! docs/canopen.md#akd, docs/canopen.md#emcy-producer) and print them in words.
//!
//! Run with `cargo run --example akd_emcy`.

use motionwire::canopen::{Emcy, NodeId};
use motionwire::profiles::akd::AkdEmcy;

/// The frames, in the order the drive sends them, with what the seed says
/// about each.
const FRAMES: [(&str, [u8; 8]); 5] = [
    (
        "transition 1: an error on axis 1, a feedback fault on FB2",
        [0x06, 0x73, 0x01, 0x21, 0x00, 0x00, 0x00, 0x00],
    ),
    (
        "transition 3: a second error on axis 1, the register accumulates",
        [0x10, 0x43, 0x09, 0x01, 0x00, 0x00, 0x00, 0x00],
    ),
    (
        "transition 2: the feedback fault is reset, the temperature error remains",
        [0x00, 0x00, 0x09, 0x21, 0x00, 0x00, 0x00, 0x00],
    ),
    (
        "transition 4: the last error is reset",
        [0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00],
    ),
    (
        "not from a healthy drive: feedback id 7 is undefined",
        [0x06, 0x73, 0x01, 0x71, 0x00, 0x00, 0x00, 0x00],
    ),
];

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect()
}

fn main() -> Result<(), motionwire::Error> {
    let node = NodeId::try_new(1)?;
    println!(
        "AKD EMCY frames from node {node} (COB-ID {:#05X})\n",
        node.emcy_cob_id()
    );

    for (what, data) in FRAMES {
        println!("{:03X}#{}  {what}", node.emcy_cob_id(), hex(&data));
        let emcy = Emcy::parse(&data)?;
        let description = emcy.code.describe();
        println!(
            "  code      {}  {} ({} match{})",
            emcy.code,
            emcy.code.description(),
            description.specificity,
            description
                .source
                .map(|source| format!(", {source}"))
                .unwrap_or_default(),
        );
        let flags: Vec<&str> = emcy.register.names().collect();
        println!(
            "  register  {:#04X}    [{}]",
            emcy.register.bits(),
            flags.join(", ")
        );

        // Decoding keeps everything: an undefined feedback nibble shows as
        // "unknown feedback id N" next to the axis.
        let akd = AkdEmcy::from_emcy(&emcy);
        let m = akd.manufacturer;
        println!("  AKD       {}, feedback {}", m.axis, m.feedback);
        let state = if !akd.is_reset() {
            "error occurred"
        } else if akd.register.is_empty() {
            "error reset: error-free"
        } else {
            "error reset: errors remain"
        };
        println!("  state     {state}\n");
    }
    Ok(())
}
