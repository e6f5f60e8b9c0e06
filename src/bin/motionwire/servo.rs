//! `motionwire servo command|feedback HEX`: one EtherCAT servo ↔ NC frame
//! (SPEC §6.2). The text is the library's (`Command::details`,
//! `Feedback::details`); this module reads the hex and writes the JSON.

use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use motionwire::servo::{ActualPosition, Command, Feedback, ServoFault, COMMAND_LEN, FEEDBACK_LEN};

use crate::args::ServoArgs;
use crate::failure::Failure;
use crate::json::{self, Object};

/// Which frame the hex holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frame {
    /// The 10-byte NC → servo command frame (SPEC §1.1).
    Command,
    /// The 40-byte servo → NC feedback frame (SPEC §1.2).
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

/// The command frame as SPEC §6.2's JSON object.
pub fn command_json<W: Write>(out: &mut W, c: &Command) -> io::Result<()> {
    let mut obj = Object::begin(out)?;
    obj.int("speed_setpoint", i64::from(c.speed_setpoint))?;
    obj.int("speed_setpoint_word", i64::from(c.speed_setpoint_word()))?;
    obj.uint("control", u64::from(c.control.bits()))?;
    obj.names("control_flags", c.control.flag_names())?;
    obj.uint("servo_enable", u64::from(c.control.servo_enable().get()))?;
    obj.name("regulator_mode", c.control.regulator_mode().name())?;
    obj.uint(
        "parameter_table",
        u64::from(c.control.parameter_table().get()),
    )?;
    obj.int("extra_data_code", i64::from(c.extra_data_code))?;
    obj.end()?;
    out.write_all(b"\n")
}

/// The feedback frame as SPEC §6.2's JSON object.
pub fn feedback_json<W: Write>(out: &mut W, f: &Feedback) -> io::Result<()> {
    let mut obj = Object::begin(out)?;
    obj.int("position", f.position)?;
    obj.name("encoder", f.status.encoder().name())?;
    match f.actual_position() {
        ActualPosition::Absolute(_) => {
            obj.null("incremental_position")?;
            obj.null("zero_pulse_position")?;
        }
        ActualPosition::Incremental {
            position,
            zero_pulse_position,
        } => {
            obj.int("incremental_position", i64::from(position))?;
            obj.int("zero_pulse_position", i64::from(zero_pulse_position))?;
        }
    }
    obj.uint("status", u64::from(f.status.bits()))?;
    obj.names("status_flags", f.status.flag_names())?;
    obj.uint(
        "parameter_table",
        u64::from(f.status.parameter_table().get()),
    )?;
    obj.uint("errors", u64::from(f.errors.bits()))?;
    {
        let out = obj.key("faults")?;
        out.write_all(b"[")?;
        for (i, fault) in f.errors.faults().enumerate() {
            if i > 0 {
                out.write_all(b",")?;
            }
            fault_json(out, fault)?;
        }
        out.write_all(b"]")?;
    }
    obj.int("message_code", i64::from(f.message.code))?;
    obj.name("message", f.message.kind().name())?;
    obj.float("message_value", f64::from(f.message.data))?;
    {
        let out = obj.key("extra")?;
        out.write_all(b"[")?;
        for (i, value) in f.extra_data.iter().enumerate() {
            if i > 0 {
                out.write_all(b",")?;
            }
            json::float(out, f64::from(*value))?;
        }
        out.write_all(b"]")?;
    }
    obj.end()?;
    out.write_all(b"\n")
}

fn fault_json<W: Write>(out: &mut W, fault: ServoFault) -> io::Result<()> {
    let mut obj = Object::begin(out)?;
    obj.uint("bit", u64::from(fault.bit()))?;
    obj.name("name", fault.name())?;
    match fault.e_code() {
        Some(code) => obj.str("e_code", &code.to_string())?,
        None => obj.null("e_code")?,
    }
    obj.end()
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
