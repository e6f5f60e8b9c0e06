//! `motionwire`: decode CANopen logs and EtherCAT servo frames.
//!
//! Built with the feature `cli`. The JSON output is a stable contract
//! (docs/output.md, docs/summary.md, docs/servo.md#cli): names and meanings
//! change only with a CHANGELOG entry. The program only parses arguments and
//! renders what the library decodes: whatever a library user could use
//! belongs in the library.
//!
//! ```text
//! motionwire decode [--json] [--profile generic|akd|baumer|NODE=PROFILE,…] [--summary]
//!                   [--heartbeat-ms N] [--only KIND[,KIND]] [--node …] [--id …]
//!                   [--from T] [--to T] [--iface NAME[,NAME]] [FILE…]
//! motionwire report [--heartbeat-ms N] [--profile …] [--eds …] [--format …]
//!                   [--node …] [--id …] [--from T] [--to T] [--iface …]
//!                   [--joined] LOG… -o FILE.html
//! motionwire servo command  [--json] HEX
//! motionwire servo feedback [--json] HEX
//! ```

mod args;
mod decode;
mod failure;
mod out;
mod record;
mod report;
mod servo;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser;

use crate::args::{Cli, Command, ServoCommand};
use crate::failure::Failure;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Decode(args) => decode::run(&args),
        Command::Report(args) => report::run(&args),
        Command::Servo(ServoCommand::Command(args)) => servo::run(servo::Frame::Command, &args),
        Command::Servo(ServoCommand::Feedback(args)) => servo::run(servo::Frame::Feedback, &args),
    };
    match result {
        Ok(code) => code,
        // `motionwire decode … | head`: the reader went away; end quietly.
        Err(Failure::Io(e)) if e.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(failure) => {
            let _ = writeln!(io::stderr(), "motionwire: {failure}");
            ExitCode::from(2)
        }
    }
}
