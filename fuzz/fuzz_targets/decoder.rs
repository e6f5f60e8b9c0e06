//! The decoder session and the post-mortem (docs/output.md, docs/summary.md)
//! fed arbitrary frames: a stream of CANopen traffic on two buses, with SDO
//! transfers that teach PDO mappings, drives' statuswords and EMCY storms.
//!
//! Input: records of `[header, id, bytes…]`: header bits 0–3 the data
//! length (0..=15, cut to 8 and to what is left), bit 4 the bus (`can0` or
//! `can1`), bit 5 a remote frame, bits 6–7 the time step (0, 1, 10 or
//! 1000 ms); `id` picks the function (the high 3 bits: NMT, SYNC/EMCY,
//! TPDO1/RPDO1, TPDO2…, SDO response, SDO request, heartbeat, any 11-bit
//! identifier) and the node (the low 5 bits, nodes 1–31, 0 kept as 0).
//!
//! Invariants:
//! - nothing panics: not the decoder, not the summary, not their renderings;
//! - every JSON record the decoder writes is one valid JSON object whose
//!   `line`, `id` and `kind` are the frame's;
//! - every SDO transfer that starts ends exactly once: at a frame, or left
//!   open at the end of the input (`Decoder::finish`); a transfer's data
//!   never exceeds the cap;
//! - a PDO's signals never lie beyond its payload;
//! - the summary counts every frame once, and its JSON is what the
//!   records say.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::can::{CanFrame, CanId, Iface, LogFrame, Timestamp};
use motionwire::canopen::NodeId;
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::profiles::Profile;
use motionwire::summary::Summarizer;

const CAP: usize = 64;

fuzz_target!(|input: &[u8]| {
    let drive = NodeId::new(3).unwrap();
    let config = DecoderConfig::new()
        .node_profile(drive, Profile::Akd)
        .node_profile(NodeId::new(5).unwrap(), Profile::Baumer)
        .sdo_data_cap(CAP);
    let mut decoder = Decoder::new(config.clone());
    let mut lean = Decoder::new(config.signals(false));
    let mut summarizer = Summarizer::new().heartbeat_timeout(core::time::Duration::from_millis(50));
    let mut rest = input;
    let mut ms: u64 = 0;
    let mut line = 0u64;
    let (mut started, mut ended) = (0u64, 0u64);
    let mut frames = 0u64;
    while let Some((&[header, id], tail)) = rest.split_first_chunk::<2>() {
        let len = usize::from(header & 0x0F).min(8).min(tail.len());
        let (data, tail) = tail.split_at(len);
        rest = tail;
        line += 1;
        ms += [0, 1, 10, 1000][usize::from(header >> 6)];
        let node = u32::from(id & 0x1F);
        let raw = match id >> 5 {
            0 => 0x000,
            1 => 0x080 + node,
            2 => 0x180 + node,
            3 => 0x200 + node + 0x80 * (node % 4),
            4 => 0x580 + node,
            5 => 0x600 + node,
            6 => 0x700 + node,
            _ => (u32::from(id) << 3) | u32::from(header & 7),
        };
        let frame = if header & 0x20 != 0 {
            CanFrame::new_remote(CanId::standard(raw).unwrap(), len as u8)
        } else {
            CanFrame::new(CanId::standard(raw).unwrap(), data)
        };
        let Ok(frame) = frame else { continue };
        let iface = if header & 0x10 != 0 { "can1" } else { "can0" };
        let log = LogFrame::new(frame)
            .with_timestamp(Timestamp::from_duration(core::time::Duration::from_millis(
                ms,
            )))
            .with_iface(Iface::Name(iface));
        frames += 1;

        let decoded = decoder.decode(line, &log);
        let json = decoded.to_json();
        let value: serde_json::Value = serde_json::from_str(&json).expect("a valid JSON record");
        assert_eq!(value["line"], line);
        assert_eq!(value["id"], raw);
        assert_eq!(value["kind"], decoded.kind.name());
        let _ = decoded.message();
        if let Some(step) = &decoded.sdo {
            let _ = step.to_string();
            if step.started {
                started += 1;
            }
            if let Some(end) = &step.ended {
                ended += 1;
                assert!(end.data.len() <= CAP);
                assert!(end.data.len() <= end.transfer.bytes as usize);
            }
        }
        if let Some(pdo) = &decoded.pdo {
            let _ = pdo.to_string();
            for signal in pdo.signals.iter().flatten() {
                let end = usize::from(signal.offset) + usize::from(signal.entry.bits());
                assert!(
                    end <= 8 * log.frame.data().len(),
                    "a signal beyond the payload"
                );
            }
        }
        if let Some(reading) = &decoded.cia402 {
            let _ = reading.to_string();
        }

        let decoded = lean.decode(line, &log);
        summarizer.add_frame(line, &log, &decoded);
    }
    let open = decoder.finish();
    assert_eq!(
        started,
        ended + open.len() as u64,
        "every transfer ends once"
    );

    let summary = summarizer.finish(&mut lean);
    let counted: u64 = summary.buses.iter().map(|b| b.frames).sum();
    assert_eq!(counted, frames);
    let _ = summary.to_string();
    let records: serde_json::Value =
        serde_json::to_value(&summary).expect("the summary serializes");
    assert_eq!(
        records.as_array().map(Vec::len),
        Some(summary.nodes.len() + summary.buses.len())
    );
});
