//! `motionwire decode`: a log → one record per CAN frame (SPEC §6.1), or
//! the per-node summary (SPEC §6.3). The streaming loop: read, parse with
//! the library, hand each frame to the record writer or the summary.

use std::fs::File;
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use motionwire::can::LogFrame;
use motionwire::candump;
use motionwire::canopen::MessageKind;

use crate::args::DecodeArgs;
use crate::failure::Failure;
use crate::profile::Profiles;
use crate::record::Record;
use crate::summary::Summary;

/// One input: a file or standard input.
struct Input {
    name: String,
    path: Option<PathBuf>,
    reader: Box<dyn Read>,
}

fn open_inputs(files: &[PathBuf]) -> Result<Vec<Input>, Failure> {
    if files.is_empty() {
        return Ok(vec![stdin_input()]);
    }
    files
        .iter()
        .map(|path| {
            if path.as_os_str() == "-" {
                return Ok(stdin_input());
            }
            let file = File::open(path).map_err(|source| Failure::File {
                path: path.clone(),
                source,
            })?;
            Ok(Input {
                name: path.display().to_string(),
                path: Some(path.clone()),
                reader: Box::new(file),
            })
        })
        .collect()
}

fn stdin_input() -> Input {
    Input {
        name: "<stdin>".to_owned(),
        path: None,
        reader: Box::new(io::stdin()),
    }
}

/// Run `motionwire decode`.
pub fn run(args: &DecodeArgs) -> Result<ExitCode, Failure> {
    if args.heartbeat_ms.is_some() && !args.summary {
        return Err(Failure::Usage(
            "--heartbeat-ms needs --summary (heartbeat gaps are reported per node)".to_owned(),
        ));
    }
    let inputs = open_inputs(&args.files)?;
    let profiles = Profiles::new(&args.profile);
    let mut keep = [args.only.is_empty(); MessageKind::ALL.len()];
    for kind in &args.only {
        keep[kind.index()] = true;
    }

    let stdout = io::stdout();
    let mut out = BufWriter::with_capacity(1 << 16, stdout.lock());
    let stderr = io::stderr();
    let mut err = BufWriter::new(stderr.lock());
    let mut summary = args.summary.then(|| Summary::new(args.heartbeat_ms));
    let mut skipped: u64 = 0;

    for input in inputs {
        let name = input.name.clone();
        let path = input.path.clone();
        for_each_line(input.reader, |event| {
            let (line, parsed) = match event {
                // Live use: what was decoded so far is written out now
                // (SPEC §6.4); a file read in full blocks never gets here.
                Event::Drained => {
                    out.flush()?;
                    return err.flush();
                }
                Event::Line(line, parsed) => (line, parsed),
            };
            match parsed {
                Ok(None) => {}
                Ok(Some(frame)) => match summary.as_mut() {
                    Some(summary) => summary.add(line, &frame),
                    None => {
                        let record = Record::new(line, &frame);
                        if !keep[record.kind().index()] {
                            return Ok(());
                        }
                        let profile = profiles.of(record.node());
                        if args.json {
                            record.write_json(&mut out, profile)?;
                        } else {
                            record.write_text(&mut out, profile)?;
                        }
                    }
                },
                Err(e) => {
                    skipped += 1;
                    writeln!(err, "{name}:{line}: {e}")?;
                }
            }
            Ok(())
        })
        .map_err(|e| match e {
            LineError::Read(e) => read_failure(&input.name, path.as_deref(), e),
            LineError::Write(e) => Failure::Io(e),
        })?;
    }
    if let Some(summary) = summary {
        if summary.timeouts_not_checked() {
            writeln!(
                err,
                "motionwire: the log has frames without timestamps: heartbeat timeouts were not \
                 checked (--heartbeat-ms)"
            )?;
        }
        summary.write(&mut out, args.json)?;
    }
    out.flush()?;
    if skipped > 0 {
        let s = if skipped == 1 { "" } else { "s" };
        writeln!(err, "motionwire: {skipped} malformed line{s} skipped")?;
        err.flush()?;
        return Ok(ExitCode::from(1));
    }
    err.flush()?;
    Ok(ExitCode::SUCCESS)
}

/// What [`for_each_line`] hands to its handler.
enum Event<'a> {
    /// A line, with its 1-based number, as the candump parser reads it.
    Line(u64, motionwire::Result<Option<LogFrame<'a>>>),
    /// The input has nothing more buffered: the next read would wait (a
    /// pipe from a live `candump`), so the output should be flushed now.
    Drained,
}

/// Why reading the lines of one input stopped.
enum LineError {
    /// The input could not be read.
    Read(io::Error),
    /// The handler could not write its output.
    Write(io::Error),
}

/// Read `reader` in large blocks and hand every line, with its 1-based
/// number, to `handle` as the crate's candump parser reads it. Whole lines
/// are parsed straight out of the block (no copy per line); a line that
/// runs past the block is carried to the front and completed by the next
/// read. Memory stays at one block, whatever the input's size, unless a
/// single line is longer than a block.
fn for_each_line(
    mut reader: Box<dyn Read>,
    mut handle: impl FnMut(Event<'_>) -> io::Result<()>,
) -> Result<(), LineError> {
    const BLOCK: usize = 1 << 18;
    let mut buf = vec![0u8; BLOCK];
    let mut filled = 0;
    let mut base: u64 = 0;
    // Carries what the last line of a block means for the next block's
    // first (an error frame's explanation lines, candump -e).
    let mut state = candump::LineState::default();
    loop {
        if filled == buf.len() {
            // A line longer than the block: make room for the rest of it.
            buf.resize(buf.len() * 2, 0);
        }
        let room = buf.len() - filled;
        let n = match reader.read(&mut buf[filled..]) {
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(LineError::Read(e)),
        };
        // A read that did not fill the room took everything the input had
        // buffered (a pipe from candump): after these lines, say so.
        let drained = n < room;
        let at_end = n == 0;
        filled += n;
        // Parse up to the last complete line (all of it at the end).
        let complete = if at_end {
            filled
        } else {
            match buf[..filled].iter().rposition(|&b| b == b'\n') {
                Some(i) => i + 1,
                None => continue,
            }
        };
        let mut lines = 0;
        let mut iter = candump::lines_from(&buf[..complete], state);
        for (number, parsed) in iter.by_ref() {
            lines = number;
            handle(Event::Line(base + number as u64, parsed)).map_err(LineError::Write)?;
        }
        state = iter.state();
        base += lines as u64;
        if drained && !at_end {
            handle(Event::Drained).map_err(LineError::Write)?;
        }
        if at_end {
            return Ok(());
        }
        buf.copy_within(complete..filled, 0);
        filled -= complete;
    }
}

fn read_failure(name: &str, path: Option<&Path>, source: io::Error) -> Failure {
    Failure::File {
        path: path.map_or_else(|| PathBuf::from(name), Path::to_path_buf),
        source,
    }
}
