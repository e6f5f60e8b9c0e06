//! Write a deterministic EtherCAT capture of a servo (docs/servo.md) and two
//! CiA 402 drives, driven by the crate's own models, with its ENI file and
//! the record of what the models did (tests/common/ecat_drives.rs;
//! tests/data/ethercat/README.md, "drives.pcapng").
//!
//! ```text
//! cargo run --release --example ecat_drives -- --cycles 1000 \
//!     --out drives.pcapng --model drives.model.jsonl --eni drives.eni.xml
//! ```
//!
//! Every cycle is one frame sent and returned (two packets); the faults
//! fall at the same fractions of any cycle count of at least 500.

#[path = "../tests/common/ecat_drives.rs"]
mod ecat_drives;

use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str =
    "usage: ecat_drives --cycles N --out CAPTURE.pcapng --model MODEL.jsonl --eni ENI.xml";

fn main() -> ExitCode {
    let mut cycles = None;
    let (mut out, mut model, mut eni) = (None, None, None);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let value = args.next();
        match (arg.as_str(), value) {
            ("--cycles", Some(v)) => match v.parse::<u32>() {
                Ok(n) => cycles = Some(n),
                Err(e) => {
                    eprintln!("--cycles {v}: {e}\n{USAGE}");
                    return ExitCode::FAILURE;
                }
            },
            ("--out", Some(v)) => out = Some(PathBuf::from(v)),
            ("--model", Some(v)) => model = Some(PathBuf::from(v)),
            ("--eni", Some(v)) => eni = Some(PathBuf::from(v)),
            _ => {
                eprintln!("{USAGE}");
                return ExitCode::FAILURE;
            }
        }
    }
    let (Some(cycles), Some(out), Some(model), Some(eni)) = (cycles, out, model, eni) else {
        eprintln!("{USAGE}");
        return ExitCode::FAILURE;
    };
    match ecat_drives::write_files(cycles, &out, &model, &eni) {
        Ok(written) => {
            let s = written.schedule;
            println!(
                "{}: {} packets; {}: {} records; {}",
                out.display(),
                written.packets,
                model.display(),
                written.records,
                eni.display()
            );
            println!(
                "SEW error {}, zero pulse {}, encoder lost {} (back {}, enable timeout {} cycles), \
                 lost frame {}, servo absent {}, drive A fault {}",
                s.sew_error,
                s.home,
                s.encoder_lost,
                s.encoder_back,
                s.timeout,
                s.lost_frame,
                s.servo_absent,
                s.drive_fault
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
