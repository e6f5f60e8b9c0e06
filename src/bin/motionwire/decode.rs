//! `motionwire decode`: a log → one record per CAN frame (SPEC §6.1), or
//! the per-node summary (SPEC §6.3). The streaming loop: read, parse with
//! the library, hand each frame to the record writer or the summary.

use std::fs::File;
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
        let mut blocks = Blocks::new(input.reader);
        loop {
            let block = blocks
                .next_block()
                .map_err(|e| read_failure(&name, path.as_deref(), e))?;
            let Some(block) = block else { break };
            let drained = block.drained;
            let mut lines = candump::lines_from(block.text, block.state);
            let mut last = 0;
            for (number, parsed) in lines.by_ref() {
                last = number;
                let line = block.base + number as u64;
                match parsed {
                    Ok(None) => {}
                    Ok(Some(frame)) => match summary.as_mut() {
                        Some(summary) => summary.add(line, &frame),
                        None => {
                            let record = Record::new(line, &frame);
                            if keep[record.kind().index()] {
                                let profile = profiles.of(record.node());
                                if args.json {
                                    record.write_json(&mut out, profile)?;
                                } else {
                                    record.write_text(&mut out, profile)?;
                                }
                            }
                        }
                    },
                    Err(e) => {
                        skipped += 1;
                        writeln!(err, "{name}:{line}: {e}")?;
                    }
                }
            }
            let state = lines.state();
            blocks.done(last, state);
            if drained {
                // Live use: what was decoded so far is written out now
                // (SPEC §6.4); a file read in full blocks never gets here.
                out.flush()?;
                err.flush()?;
            }
        }
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

/// An input read in large blocks of whole lines, parsed in place (no copy
/// per line). A line that runs past a block is carried to the front and
/// completed by the next read. Memory stays at one block, whatever the
/// input's size, unless a single line is longer than a block.
struct Blocks {
    reader: Box<dyn Read>,
    buf: Vec<u8>,
    /// Bytes of `buf` read.
    filled: usize,
    /// Bytes at the front of `buf` handed out in the last block.
    handed: usize,
    /// Lines before the next block.
    base: u64,
    /// What the last block's last line means for the next block's first
    /// (an error frame's explanation lines, candump -e).
    state: candump::LineState,
    at_end: bool,
}

/// Whole lines of an input, with what the lines before them leave.
struct Block<'b> {
    /// The lines, each ending in `\n` but maybe the input's last.
    text: &'b [u8],
    /// How many lines came before.
    base: u64,
    /// What the lines before mean for the first.
    state: candump::LineState,
    /// Whether the input has nothing more buffered after these lines (the
    /// next read would wait, as on a live pipe).
    drained: bool,
}

impl Blocks {
    const BLOCK: usize = 1 << 18;

    fn new(reader: Box<dyn Read>) -> Self {
        Blocks {
            reader,
            buf: vec![0; Self::BLOCK],
            filled: 0,
            handed: 0,
            base: 0,
            state: candump::LineState::default(),
            at_end: false,
        }
    }

    /// Read until there is at least one whole line (or the end), and return
    /// the whole lines; `None` after the end.
    fn next_block(&mut self) -> io::Result<Option<Block<'_>>> {
        // Drop what the last block handed out.
        self.buf.copy_within(self.handed..self.filled, 0);
        self.filled -= self.handed;
        self.handed = 0;
        if self.at_end {
            return Ok(None);
        }
        loop {
            if self.filled == self.buf.len() {
                // A line longer than the block: make room for the rest of it.
                self.buf.resize(self.buf.len() * 2, 0);
            }
            let room = self.buf.len() - self.filled;
            let n = match self.reader.read(&mut self.buf[self.filled..]) {
                Ok(n) => n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            self.filled += n;
            self.at_end = n == 0;
            // Up to the last complete line (all of it at the end).
            let complete = if self.at_end {
                self.filled
            } else {
                match self.buf[..self.filled].iter().rposition(|&b| b == b'\n') {
                    Some(i) => i + 1,
                    None => continue,
                }
            };
            self.handed = complete;
            return Ok(Some(Block {
                text: &self.buf[..complete],
                base: self.base,
                state: self.state,
                // A read that did not fill the room took everything the
                // input had buffered.
                drained: n < room && !self.at_end,
            }));
        }
    }

    /// Record that the last block held `lines` lines and left `state`.
    fn done(&mut self, lines: usize, state: candump::LineState) {
        self.base += lines as u64;
        self.state = state;
    }
}

fn read_failure(name: &str, path: Option<&Path>, source: io::Error) -> Failure {
    Failure::File {
        path: path.map_or_else(|| PathBuf::from(name), Path::to_path_buf),
        source,
    }
}
