//! `motionwire servo command|feedback HEX`: one EtherCAT servo ↔ NC frame
//! (docs/servo.md#cli). The text and the JSON records are the library's
//! (`Command::details`, `Feedback::details`, `decoder::CommandRecord`,
//! `decoder::FeedbackRecord`); this module reads the hex and writes them.

use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use motionwire::decoder::{CommandRecord, FeedbackRecord};
use motionwire::servo::{Command, Feedback, COMMAND_LEN, FEEDBACK_LEN};

use crate::args::ServoArgs;
use crate::failure::Failure;

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

/// Write the command frame as its JSON record (docs/servo.md#cli-command,
/// the library's [`CommandRecord`]) and a newline.
pub fn command_json<W: Write>(out: &mut W, c: &Command) -> io::Result<()> {
    serde_json::to_writer(&mut *out, &CommandRecord::from(c))?;
    out.write_all(b"\n")
}

/// Write the feedback frame as its JSON record (docs/servo.md#cli-feedback,
/// the library's [`FeedbackRecord`]) and a newline.
pub fn feedback_json<W: Write>(out: &mut W, f: &Feedback) -> io::Result<()> {
    serde_json::to_writer(&mut *out, &FeedbackRecord::from(f))?;
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
