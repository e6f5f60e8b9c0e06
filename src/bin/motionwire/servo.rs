//! `motionwire servo command|feedback HEX`: one EtherCAT servo ↔ NC frame
//! (docs/servo.md#cli). The text is the library's (`Command::details`,
//! `Feedback::details`); this module reads the hex and writes the JSON.

use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use motionwire::servo::{ActualPosition, Command, Feedback, ServoFault, COMMAND_LEN, FEEDBACK_LEN};

use crate::args::ServoArgs;
use crate::failure::Failure;
use serde::Serialize;

/// Which frame the hex holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frame {
    /// The 10-byte NC → servo command frame (docs/servo.md#command).
    Command,
    /// The 40-byte servo → NC feedback frame (docs/servo.md#feedback).
    Feedback,
}

impl Frame {
    const fn len(self) -> usize {
        match self {
            Frame::Command => COMMAND_LEN,
            Frame::Feedback => FEEDBACK_LEN,
        }
    }

    const fn what(self) -> &'static str {
        match self {
            Frame::Command => "a command frame",
            Frame::Feedback => "a feedback frame",
        }
    }
}

/// Read hex digits, ignoring white space; the result must be exactly
/// `frame.len()` bytes.
pub fn parse_hex(frame: Frame, parts: &[String]) -> Result<Vec<u8>, Failure> {
    let mut nibbles = Vec::with_capacity(2 * frame.len());
    let mut position = 0usize;
    for part in parts {
        for c in part.chars() {
            position += 1;
            if c.is_whitespace() {
                continue;
            }
            let digit = c.to_digit(16).ok_or_else(|| {
                Failure::Usage(format!(
                    "bad hex: {c:?} at character {position} is not a hex digit"
                ))
            })?;
            nibbles.push(digit as u8);
        }
        position += 1; // the space between two arguments
    }
    let expected = 2 * frame.len();
    if nibbles.len() != expected {
        return Err(Failure::Usage(format!(
            "wrong length: {} needs {expected} hex digits ({} bytes), found {}",
            frame.what(),
            frame.len(),
            nibbles.len()
        )));
    }
    Ok(nibbles
        .chunks_exact(2)
        .map(|p| (p[0] << 4) | p[1])
        .collect())
}

/// Run `motionwire servo command|feedback`.
pub fn run(frame: Frame, args: &ServoArgs) -> Result<ExitCode, Failure> {
    let bytes = parse_hex(frame, &args.hex)?;
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    match frame {
        Frame::Command => {
            let command = Command::parse(&bytes).map_err(|e| Failure::Usage(e.to_string()))?;
            if args.json {
                command_json(&mut out, &command)?;
            } else {
                writeln!(out, "{}", command.details())?;
            }
        }
        Frame::Feedback => {
            let feedback = Feedback::parse(&bytes).map_err(|e| Failure::Usage(e.to_string()))?;
            if args.json {
                feedback_json(&mut out, &feedback)?;
            } else {
                writeln!(out, "{}", feedback.details())?;
            }
        }
    }
    out.flush()?;
    Ok(ExitCode::SUCCESS)
}

/// The command frame as its JSON object (docs/servo.md#cli-command), keys in
/// the contract's order.
#[derive(Serialize)]
struct CommandJson {
    speed_setpoint: i32,
    speed_setpoint_word: i16,
    control: u32,
    control_flags: Vec<&'static str>,
    servo_enable: u8,
    regulator_mode: &'static str,
    parameter_table: u8,
    extra_data_code: i16,
}

/// Write the command frame as its JSON object (docs/servo.md#cli-command) and a
/// newline.
pub fn command_json<W: Write>(out: &mut W, c: &Command) -> io::Result<()> {
    let json = CommandJson {
        speed_setpoint: c.speed_setpoint,
        speed_setpoint_word: c.speed_setpoint_word(),
        control: c.control.bits(),
        control_flags: c.control.flag_names().collect(),
        servo_enable: c.control.servo_enable().get(),
        regulator_mode: c.control.regulator_mode().name(),
        parameter_table: c.control.parameter_table().get(),
        extra_data_code: c.extra_data_code,
    };
    serde_json::to_writer(&mut *out, &json)?;
    out.write_all(b"\n")
}

/// One fault of the feedback's error word: `{"bit", "name", "e_code"}`.
#[derive(Serialize)]
struct FaultJson {
    bit: u8,
    name: &'static str,
    e_code: Option<String>,
}

/// The feedback frame as its JSON object (docs/servo.md#cli-feedback), keys in
/// the contract's order; floats as their `f64` value, a non-finite one as null.
#[derive(Serialize)]
struct FeedbackJson {
    position: i64,
    encoder: &'static str,
    incremental_position: Option<i32>,
    zero_pulse_position: Option<i32>,
    status: u32,
    status_flags: Vec<&'static str>,
    parameter_table: u8,
    errors: u32,
    faults: Vec<FaultJson>,
    message_code: i32,
    message: &'static str,
    message_value: f64,
    extra: [f64; 4],
}

/// Write the feedback frame as its JSON object (docs/servo.md#cli-feedback) and
/// a newline.
pub fn feedback_json<W: Write>(out: &mut W, f: &Feedback) -> io::Result<()> {
    let (incremental_position, zero_pulse_position) = match f.actual_position() {
        ActualPosition::Absolute(_) => (None, None),
        ActualPosition::Incremental {
            position,
            zero_pulse_position,
        } => (Some(position), Some(zero_pulse_position)),
    };
    let json = FeedbackJson {
        position: f.position,
        encoder: f.status.encoder().name(),
        incremental_position,
        zero_pulse_position,
        status: f.status.bits(),
        status_flags: f.status.flag_names().collect(),
        parameter_table: f.status.parameter_table().get(),
        errors: f.errors.bits(),
        faults: f
            .errors
            .faults()
            .map(|fault: ServoFault| FaultJson {
                bit: fault.bit(),
                name: fault.name(),
                e_code: fault.e_code().map(|code| code.to_string()),
            })
            .collect(),
        message_code: f.message.code,
        message: f.message.kind().name(),
        message_value: f64::from(f.message.data),
        extra: f.extra_data.map(f64::from),
    };
    serde_json::to_writer(&mut *out, &json)?;
    out.write_all(b"\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &[&str]) -> Vec<String> {
        s.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn hex_with_spaces() {
        let bytes = parse_hex(Frame::Command, &args(&["e8030000 05 06 00 00", "0100"])).unwrap();
        assert_eq!(bytes, [0xE8, 0x03, 0, 0, 5, 6, 0, 0, 1, 0]);
    }

    #[test]
    fn bad_hex_and_length() {
        let e = parse_hex(Frame::Command, &args(&["e8030000050600000g00"])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "bad hex: 'g' at character 18 is not a hex digit"
        );
        let e = parse_hex(Frame::Feedback, &args(&["00"])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "wrong length: a feedback frame needs 80 hex digits (40 bytes), found 2"
        );
    }
}
