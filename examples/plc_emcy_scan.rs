//! A PLC calling CiA 405 `RECV_EMCY` once per cycle over a simulated CAN bus
//! (docs/canopen.md#recv-emcy).
//!
//! Three devices are configured: a Kollmorgen AKD drive (node 3), a Baumer
//! encoder (node 5) and an I/O module (node 12). Their errors come and go as
//! real 8-byte EMCY frames on COB-ID 0x080 + node-ID; a device that is not
//! configured (node 40) and a truncated frame show up too. Each cycle the bus
//! frames go through `CobFunction::classify` and `Emcy::parse` into the
//! storage, then the PLC calls `RECV_EMCY` and logs its outputs.
//!
//! Run with `cargo run --example plc_emcy_scan`.

use motionwire::canopen::{
    CobFunction, DeviceSet, Emcy, EmcyStorage, NodeId, RecvEmcy, RecvEmcyOutputs, SlotUpdate,
};

/// The simulated bus: (PLC cycle, CAN identifier, data bytes).
const BUS: &[(u32, u16, &[u8])] = &[
    // AKD node 3: life guard error on axis 1, then a follow-up PDO error.
    (2, 0x083, &[0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00]),
    (3, 0x083, &[0x10, 0x82, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00]),
    // Baumer node 5: temperature out of range (alarms 6503h = 0, warnings 0).
    (4, 0x085, &[0x00, 0x42, 0x09, 0x00, 0x00, 0x00, 0x00, 0x00]),
    // Node 40 is not configured: stored, never scanned.
    (5, 0x0A8, &[0x00, 0x50, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00]),
    // I/O node 12 sends a truncated frame: reported, not guessed.
    (6, 0x08C, &[0x00, 0xFF, 0x81, 0x00, 0x00, 0x00, 0x00]),
    // AKD resets its error (axis id still in byte 3).
    (8, 0x083, &[0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00]),
    // I/O node 12: device-specific error.
    (9, 0x08C, &[0x00, 0xFF, 0x81, 0x00, 0x00, 0x00, 0x00, 0x00]),
    // Baumer resets.
    (11, 0x085, &[0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00]),
    // I/O node 12 resets and errs again before the PLC looks.
    (14, 0x08C, &[0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00]),
    (14, 0x08C, &[0x10, 0x23, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00]),
    (17, 0x08C, &[0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00]),
];

const CYCLES: u32 = 21;

fn node(raw: u8) -> NodeId {
    NodeId::new(raw).expect("a node-ID in 1..=127")
}

fn hex(data: &[u8]) -> String {
    data.iter()
        .map(|b| format!("{b:02X}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// One frame from the bus into the storage; returns the log line.
fn receive(storage: &mut EmcyStorage, id: u16, data: &[u8]) -> String {
    let CobFunction::Emcy(device) = CobFunction::classify(id) else {
        return format!("{id:03X} not an EMCY, ignored");
    };
    let emcy = match Emcy::parse(data) {
        Ok(emcy) => emcy,
        Err(error) => return format!("node {device:>3}: {error}"),
    };
    let what = match storage.receive(device, emcy) {
        SlotUpdate::RootCause => "root cause",
        SlotUpdate::FollowUp { .. } => "follow-up, root cause kept",
        SlotUpdate::Reset { cleared: Some(_) } => "reset, error cleared",
        SlotUpdate::Reset { cleared: None } => "reset, no error held",
    };
    let configured = if storage.is_configured(device) {
        ""
    } else {
        " (not configured)"
    };
    format!("node {device:>3}: {} {what}{configured}", emcy.code)
}

/// The PLC's view of one RECV_EMCY call.
fn outputs(out: &RecvEmcyOutputs) -> String {
    let meaning = if !out.confirm() {
        format!("call failed: {}", out.error())
    } else if out.emergency_received() {
        format!("EMERGENCY ({})", out.errorinfo().code.class())
    } else if out.device() != 0 {
        "reset error".to_string()
    } else {
        "all devices error-free".to_string()
    };
    format!(
        "CONFIRM={} ERROR={:#06X} DEVICE={:>3} ERRORINFO={} reg={:02X}  {meaning}",
        u8::from(out.confirm()),
        out.error().code(),
        out.device(),
        out.errorinfo().code,
        out.errorinfo().register.bits(),
    )
}

fn main() {
    let devices: DeviceSet = [node(3), node(5), node(12)].into_iter().collect();
    let mut storage = EmcyStorage::with_devices(devices);
    let mut recv_emcy = RecvEmcy::new();

    let names: Vec<String> = devices.iter().map(|d| d.to_string()).collect();
    println!("PLC EMCY scan, devices {} configured", names.join(", "));
    for cycle in 0..CYCLES {
        for &(_, id, data) in BUS.iter().filter(|&&(at, _, _)| at == cycle) {
            let line = receive(&mut storage, id, data);
            println!(
                "cycle {cycle:>2}  rx {id:03X} [{}] {}",
                data.len(),
                hex(data)
            );
            println!("           {line}");
        }
        let out = recv_emcy.call_outputs(&storage);
        println!("cycle {cycle:>2}  RECV_EMCY  {}", outputs(&out));
    }

    println!("\nRECV_EMCY_DEV after cycle {}:", CYCLES - 1);
    for raw in [3, 5, 12, 40] {
        let dev = storage.recv_emcy_dev_outputs(node(raw));
        println!(
            "  DEVICE={raw:>3} CONFIRM={} ERROR={:#06X} ERRORINFO={}",
            u8::from(dev.confirm()),
            dev.error().code(),
            dev.errorinfo().code,
        );
    }
    println!("log analyser, slot of every device holding an error (configured or not):");
    for device in storage.devices_in_error().iter() {
        println!(
            "  node {device:>3}: {}",
            hex(&storage.slot(device).to_bytes())
        );
    }
}
