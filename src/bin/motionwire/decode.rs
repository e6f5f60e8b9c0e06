//! `motionwire decode`: a log → one record per CAN frame (SPEC §6.1), or
//! the summary (SPEC §6.3). The streaming loop: open, detect the format
//! (SPEC §5.7), read with the library's reader, hand each frame to the
//! [`Sink`], which filters and renders.

use std::fs::File;
use std::io::{self, BufWriter, Cursor, Read, StderrLock, StdoutLock, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use motionwire::can::{LogEvent, LogFrame};
use motionwire::canopen::{CanOpenMessage, MessageKind};
use motionwire::logs::candump::{self, LineState, RelativeTimestamps};
use motionwire::logs::LogFormat;
use motionwire::logs::{detect, Detected, ReadError, ReadLog, DETECT_LEN};

use crate::args::{DecodeArgs, IdRange, TimestampBase};
use crate::context::{Context, PdoView};
use crate::eds::NodeDescription;
use crate::failure::Failure;
use crate::profile::Profiles;
use crate::record::Extra;
use crate::record::{Record, CSV_HEADER};
use crate::sdo::{sdo_direction, sdo_frame};
use crate::summary::Summary;

/// An input as given on the command line.
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

/// The formats `detect` knows, in words, for the unrecognised-format error.
const EXPECTED: &str = "a candump log or screen output, Vector ASC or BLF, PEAK TRC, \
                        pcap or pcapng (gzip-compressed or not)";

/// Read the first bytes of an input, decide its format (SPEC §5.7: from
/// the content; `--format` overrides; gzip is inflated and looked into),
/// and return it with a reader that starts again at the first byte.
fn open_log(
    input: Input,
    forced: Option<LogFormat>,
) -> Result<(LogFormat, Box<dyn Read>, bool), Failure> {
    let Input { name, path, reader } = input;
    let mut reader = reader;
    let mut gzip = false;
    loop {
        let mut head = Vec::with_capacity(4096);
        let detected = loop {
            let complete = fill(&mut reader, &mut head, DETECT_LEN)
                .map_err(|e| read_failure(&name, path.as_deref(), e))?;
            match detect(&head, complete) {
                Detected::NeedMore if !complete => continue,
                // Inflating once is enough: a gzip inside a gzip is no log.
                Detected::Gzip if gzip => break Detected::Unrecognised,
                other => break other,
            }
        };
        let again: Box<dyn Read> = Box::new(Cursor::new(head).chain(reader));
        match (detected, forced) {
            (Detected::Gzip, _) => {
                gzip = true;
                reader = Box::new(flate2::read::MultiGzDecoder::new(again));
            }
            (_, Some(format)) => return Ok((format, again, gzip)),
            (Detected::Format(format), None) => return Ok((format, again, gzip)),
            // Nothing but blank or comment lines: nothing to read.
            (Detected::Empty, None) => return Ok((LogFormat::Candump, again, gzip)),
            (Detected::NeedMore | Detected::Unrecognised, None) => {
                return Err(Failure::Unrecognised {
                    name,
                    expected: EXPECTED,
                })
            }
        }
    }
}

/// Read into `head` until it holds `want` bytes or the input ends; return
/// whether it ended. Stops early when a read returns less than asked, so
/// that a live pipe is decided on its first lines.
fn fill(reader: &mut dyn Read, head: &mut Vec<u8>, want: usize) -> io::Result<bool> {
    let start = head.len();
    head.resize(want, 0);
    loop {
        match reader.read(&mut head[start..]) {
            Ok(n) => {
                head.truncate(start + n);
                return Ok(n == 0);
            }
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => {
                head.truncate(start);
                return Err(e);
            }
        }
    }
}

/// How records are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Output {
    Text,
    Json,
    Csv,
}

/// Where frames go: filtered and rendered, or added to the summary (which
/// sees every frame, SPEC §6.4).
struct Sink<'a> {
    out: BufWriter<StdoutLock<'static>>,
    err: BufWriter<StderrLock<'static>>,
    summary: Option<Summary>,
    output: Output,
    profiles: Profiles,
    kinds: [bool; MessageKind::ALL.len()],
    nodes: Option<[bool; 128]>,
    ids: &'a [IdRange],
    skipped: u64,
    /// Damaged records of binary logs reported.
    damaged: u64,
    /// A progress line is on the terminal (standard error).
    progress_shown: bool,
    /// What the log teaches as it is read: SDO channels, PDO mappings,
    /// drive states (SPEC §7, §8).
    context: Context,
}

impl<'a> Sink<'a> {
    fn new(args: &'a DecodeArgs) -> Result<Self, Failure> {
        let mut descriptions = Vec::new();
        for (node, path) in &args.eds {
            let description = NodeDescription::read(*node, path).map_err(|why| {
                Failure::Usage(format!("--eds {}={}: {why}", node, path.display()))
            })?;
            descriptions.push((*node, description));
        }
        let profiles = Profiles::new(&args.profile);
        let context = Context::new(profiles.clone(), descriptions);
        let mut kinds = [args.only.is_empty(); MessageKind::ALL.len()];
        for kind in &args.only {
            kinds[kind.index()] = true;
        }
        let nodes = (!args.node.is_empty()).then(|| {
            let mut nodes = [false; 128];
            for node in &args.node {
                nodes[usize::from(node.get())] = true;
            }
            nodes
        });
        Ok(Sink {
            out: BufWriter::with_capacity(1 << 16, io::stdout().lock()),
            err: BufWriter::new(io::stderr().lock()),
            summary: args.summary.then(|| Summary::new(args.heartbeat_ms)),
            output: if args.csv {
                Output::Csv
            } else if args.json {
                Output::Json
            } else {
                Output::Text
            },
            profiles,
            kinds,
            nodes,
            ids: &args.id,
            skipped: 0,
            damaged: 0,
            progress_shown: false,
            context,
        })
    }

    #[inline]
    fn frame(&mut self, line: u64, frame: &LogFrame<'_>) -> io::Result<()> {
        if let Some(summary) = self.summary.as_mut() {
            let (kind, node) = summary.add(line, frame);
            match (kind, node) {
                (MessageKind::Sdo, Some(node)) if !frame.frame.is_rtr() => {
                    let direction = sdo_direction(frame.frame.id().raw());
                    let view = self.context.sdo(
                        frame.iface,
                        node,
                        direction,
                        frame.frame.data(),
                        frame.timestamp,
                        line,
                    );
                    summary.add_sdo(line, frame, node, &view);
                }
                (MessageKind::Pdo, Some(_)) if !frame.frame.is_rtr() => {
                    let id = frame.frame.id().raw() as u16;
                    if let Some(PdoView {
                        map,
                        cia402: Some(cia402),
                        ..
                    }) = self.context.pdo(frame.iface, id, frame.frame.data(), false)
                    {
                        summary.add_cia402(line, frame, map.node, cia402);
                    }
                }
                _ => {}
            }
            return Ok(());
        }
        let record = Record::new(line, frame);
        // Every SDO and PDO frame teaches the context, shown or not.
        let extra = match &record.decoded {
            Ok(message) => match sdo_frame(message) {
                Some((node, direction, data)) => Extra::Sdo(self.context.sdo(
                    frame.iface,
                    node,
                    direction,
                    data,
                    frame.timestamp,
                    line,
                )),
                None => match message {
                    CanOpenMessage::Pdo { data, .. } => {
                        let id = frame.frame.id().raw() as u16;
                        match self.context.pdo(frame.iface, id, data.as_slice(), true) {
                            Some(view) => Extra::Pdo(view),
                            None => Extra::None,
                        }
                    }
                    _ => Extra::None,
                },
            },
            Err(_) => Extra::None,
        };
        if !self.ids.is_empty() {
            let id = frame.frame.id().raw();
            if !self.ids.iter().any(|range| range.contains(id)) {
                return Ok(());
            }
        }
        if !self.kinds[record.kind().index()] {
            return Ok(());
        }
        if let Some(nodes) = &self.nodes {
            match record.node() {
                Some(node) if nodes[usize::from(node.get())] => {}
                _ => return Ok(()),
            }
        }
        let profile = self.profiles.of(record.node());
        match self.output {
            Output::Json => record.write_json(&mut self.out, profile, &extra),
            Output::Text => record.write_text(&mut self.out, profile, &extra),
            Output::Csv => record.write_csv(&mut self.out),
        }
    }

    #[inline]
    fn event(&mut self, line: u64, event: &LogEvent<'_>) -> io::Result<()> {
        match event {
            LogEvent::Frame(frame) => self.frame(line, frame),
            LogEvent::Status(_) => {
                if let Some(summary) = self.summary.as_mut() {
                    summary.add_event(event);
                }
                Ok(())
            }
        }
    }

    /// A line or record that could not be read: said on standard error
    /// with its position, counted (SPEC §5.7).
    #[cold]
    fn malformed(&mut self, name: &str, line: u64, why: &dyn std::fmt::Display) -> io::Result<()> {
        self.skipped += 1;
        self.clear_progress()?;
        writeln!(self.err, "{name}:{line}: {why}")
    }

    /// Erase the progress line, so that the next message starts on a
    /// clean line.
    fn clear_progress(&mut self) -> io::Result<()> {
        if self.progress_shown {
            self.progress_shown = false;
            self.err.write_all(b"\r\x1b[K")?;
        }
        Ok(())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()?;
        self.err.flush()
    }
}

pub fn run(args: &DecodeArgs) -> Result<ExitCode, Failure> {
    if args.heartbeat_ms.is_some() && !args.summary {
        return Err(Failure::Usage(
            "--heartbeat-ms needs --summary (heartbeat gaps are reported per node)".to_owned(),
        ));
    }
    let inputs = open_inputs(&args.files)?;
    let mut sink = Sink::new(args)?;
    if sink.output == Output::Csv {
        write!(sink.out, "{CSV_HEADER}\r\n")?;
    }
    for input in inputs {
        let name = input.name.clone();
        let path = input.path.clone();
        // Progress: the file's size, when the bytes read are the file's.
        let size = path
            .as_deref()
            .and_then(|p| std::fs::metadata(p).ok())
            .map(|m| m.len());
        let (format, reader, gzip) = open_log(input, args.format)?;
        let mut progress = Progress::new(&name, size.filter(|_| !gzip));
        match format {
            LogFormat::Candump => {
                read_candump(
                    &mut sink,
                    &mut progress,
                    reader,
                    &name,
                    path.as_deref(),
                    args.timestamps,
                )?;
                sink.clear_progress()?;
            }
            LogFormat::Asc => {
                let mut parser = motionwire::logs::asc::AscParser::new();
                read_text(
                    &mut sink,
                    &mut progress,
                    reader,
                    &name,
                    path.as_deref(),
                    &mut parser,
                )?;
                sink.clear_progress()?;
            }
            LogFormat::Trc => {
                let mut parser = motionwire::logs::trc::TrcParser::new();
                read_text(
                    &mut sink,
                    &mut progress,
                    reader,
                    &name,
                    path.as_deref(),
                    &mut parser,
                )?;
                sink.clear_progress()?;
            }
            LogFormat::Blf => {
                let mut log = motionwire::logs::blf::BlfReader::new(reader)
                    .map_err(|e| binary_failure(&name, path.as_deref(), e))?;
                read_binary(&mut sink, &mut log, &name, path.as_deref())?;
            }
            LogFormat::Pcap | LogFormat::Pcapng => {
                let mut log = motionwire::logs::pcap::PcapReader::new(reader)
                    .map_err(|e| binary_failure(&name, path.as_deref(), e))?;
                read_binary(&mut sink, &mut log, &name, path.as_deref())?;
            }
            other => {
                return Err(Failure::Unreadable {
                    name,
                    format: other,
                    why: "its reader is not built yet",
                })
            }
        }
    }

    let Sink {
        mut out,
        mut err,
        summary,
        skipped,
        damaged,
        profiles,
        mut context,
        ..
    } = sink;
    if let Some(mut summary) = summary {
        for (bus, node, transfer) in context.finish() {
            summary.sdo_left_open(&bus, node, &transfer);
        }
        summary.drives(|bus, node| context.is_drive(bus, node));
        if summary.timeouts_not_checked() {
            writeln!(
                err,
                "motionwire: the log has frames without timestamps: heartbeat timeouts were not \
                 checked (--heartbeat-ms)"
            )?;
        }
        summary.write(&mut out, args.json, &profiles)?;
    }
    out.flush()?;
    if skipped > 0 || damaged > 0 {
        let plural = |n: u64| if n == 1 { "" } else { "s" };
        match (skipped, damaged) {
            (lines, 0) => writeln!(
                err,
                "motionwire: {lines} malformed line{} skipped",
                plural(lines)
            )?,
            (0, records) => writeln!(
                err,
                "motionwire: {records} damaged record{} reported",
                plural(records)
            )?,
            (lines, records) => writeln!(
                err,
                "motionwire: {lines} malformed line{} skipped, {records} damaged record{} reported",
                plural(lines),
                plural(records)
            )?,
        }
        err.flush()?;
        return Ok(ExitCode::from(1));
    }
    err.flush()?;
    Ok(ExitCode::SUCCESS)
}

/// Read a candump log (SPEC §5.1, §5.2) block by block.
fn read_candump(
    sink: &mut Sink<'_>,
    progress: &mut Progress,
    reader: Box<dyn Read>,
    name: &str,
    path: Option<&Path>,
    base: Option<TimestampBase>,
) -> Result<(), Failure> {
    let mut blocks = Blocks::new(reader);
    let mut state = base.map(|base| {
        LineState::new(match base {
            TimestampBase::Delta => RelativeTimestamps::Delta,
            TimestampBase::Zero => RelativeTimestamps::Zero,
        })
    });
    let mut line_base: u64 = 0;
    loop {
        let block = blocks
            .next_block()
            .map_err(|e| read_failure(name, path, e))?;
        let Some(block) = block else { break };
        if block.overlong {
            line_base += 1;
            sink.malformed(name, line_base, &OverlongLine)?;
        }
        let line_state = match state {
            Some(state) => state,
            // Relative timestamps: -t d or -t z? Up to 64 frames decide
            // (SPEC §5.2); a live stream waits for them.
            None => match candump::detect_relative_timestamps(block.text, block.at_end) {
                Some(relative) => *state.insert(LineState::new(relative)),
                None => {
                    blocks.hold();
                    continue;
                }
            },
        };
        let drained = block.drained;
        let block_len = block.text.len() as u64;
        if let Some(summary) = sink.summary.as_mut() {
            summary.new_block();
        }
        sink.context.new_block();
        let mut lines = candump::lines_from(block.text, line_state);
        let mut last = 0;
        for (number, parsed) in lines.by_ref() {
            last = number;
            let line = line_base + number as u64;
            match parsed {
                Ok(None) => {}
                Ok(Some(frame)) => sink.frame(line, &frame)?,
                Err(e) => sink.malformed(name, line, &e)?,
            }
        }
        state = Some(lines.state());
        line_base += last as u64;
        progress.advance(sink, block_len, line_base)?;
        if drained {
            // Live use: what was decoded so far is written out now
            // (SPEC §6.4); a file read in full blocks never gets here.
            sink.flush()?;
        }
    }
    Ok(())
}

/// A text log read line by line by a stateful parser (PEAK TRC, Vector
/// ASC): the state its header sets is carried from line to line.
trait LineReader {
    fn read_line<'l>(&mut self, line: &'l [u8]) -> motionwire::Result<Option<LogEvent<'l>>>;
}

impl LineReader for motionwire::logs::trc::TrcParser {
    #[inline]
    fn read_line<'l>(&mut self, line: &'l [u8]) -> motionwire::Result<Option<LogEvent<'l>>> {
        self.parse_line(line)
    }
}

impl LineReader for motionwire::logs::asc::AscParser {
    #[inline]
    fn read_line<'l>(&mut self, line: &'l [u8]) -> motionwire::Result<Option<LogEvent<'l>>> {
        self.parse_line(line)
    }
}

/// Read a text log (TRC, ASC) block by block, line by line.
fn read_text(
    sink: &mut Sink<'_>,
    progress: &mut Progress,
    reader: Box<dyn Read>,
    name: &str,
    path: Option<&Path>,
    parser: &mut dyn LineReader,
) -> Result<(), Failure> {
    let mut blocks = Blocks::new(reader);
    let mut line: u64 = 0;
    while let Some(block) = blocks
        .next_block()
        .map_err(|e| read_failure(name, path, e))?
    {
        if block.overlong {
            line += 1;
            sink.malformed(name, line, &OverlongLine)?;
        }
        let drained = block.drained;
        let block_len = block.text.len() as u64;
        if let Some(summary) = sink.summary.as_mut() {
            summary.new_block();
        }
        sink.context.new_block();
        for text in motionwire::logs::split_lines(block.text) {
            line += 1;
            match parser.read_line(text) {
                Ok(None) => {}
                Ok(Some(event)) => sink.event(line, &event)?,
                Err(e) => sink.malformed(name, line, &e)?,
            }
        }
        progress.advance(sink, block_len, line)?;
        if drained {
            sink.flush()?;
        }
    }
    Ok(())
}

/// Read a binary log (pcap, pcapng, BLF) record by record; `line` is the
/// record's number (SPEC §5.7).
fn read_binary(
    sink: &mut Sink<'_>,
    log: &mut dyn ReadLog,
    name: &str,
    path: Option<&Path>,
) -> Result<(), Failure> {
    while let Some(record) = log.next_record() {
        match record {
            Ok(record) => {
                // Names borrowed from the reader may move between records.
                if let Some(summary) = sink.summary.as_mut() {
                    summary.new_block();
                }
                sink.context.new_block();
                sink.event(record.number, &record.event)?;
            }
            Err(ReadError::Io(e)) => return Err(read_failure(name, path, e)),
            // The file is damaged here; what came before was read, and the
            // reader ends.
            Err(ReadError::Log(e)) => {
                sink.damaged += 1;
                sink.clear_progress()?;
                writeln!(sink.err, "{name}: {e}")?;
            }
        }
    }
    let others = log.other_records();
    if others > 0 {
        // SPEC §5.5, §5.6: counted and said once, not per record.
        let s = if others == 1 { "" } else { "s" };
        writeln!(
            sink.err,
            "{name}: {others} {} record{s} without a CAN frame skipped",
            log.format()
        )?;
    }
    Ok(())
}

/// A binary log whose header cannot be read: the input's failure.
fn binary_failure(name: &str, path: Option<&Path>, e: ReadError) -> Failure {
    match e {
        ReadError::Io(e) => read_failure(name, path, e),
        ReadError::Log(e) => Failure::Damaged {
            name: name.to_owned(),
            error: e,
        },
    }
}

/// Progress of a long run on standard error, only when it is a terminal
/// (SPEC §6.4): `name: 42 % (310 MiB), 9 200 000 lines`, redrawn at most
/// four times a second after the first second, erased at the end.
struct Progress {
    name: String,
    size: Option<u64>,
    read: u64,
    start: std::time::Instant,
    last: std::time::Instant,
    enabled: bool,
}

impl Progress {
    const FIRST: std::time::Duration = std::time::Duration::from_secs(1);
    const EVERY: std::time::Duration = std::time::Duration::from_millis(250);

    fn new(name: &str, size: Option<u64>) -> Self {
        use std::io::IsTerminal;
        let now = std::time::Instant::now();
        Progress {
            name: name.to_owned(),
            size,
            read: 0,
            start: now,
            last: now,
            enabled: io::stderr().is_terminal(),
        }
    }

    fn advance(&mut self, sink: &mut Sink<'_>, bytes: u64, lines: u64) -> io::Result<()> {
        self.read += bytes;
        if !self.enabled {
            return Ok(());
        }
        let now = std::time::Instant::now();
        if now.duration_since(self.start) < Self::FIRST
            || now.duration_since(self.last) < Self::EVERY
        {
            return Ok(());
        }
        self.last = now;
        sink.progress_shown = true;
        let err = &mut sink.err;
        let mib = self.read >> 20;
        match self.size {
            Some(size) if size > 0 => write!(
                err,
                "\r{}: {} % ({mib} MiB), {lines} lines\x1b[K",
                self.name,
                self.read.saturating_mul(100) / size
            )?,
            _ => write!(err, "\r{}: {mib} MiB, {lines} lines\x1b[K", self.name)?,
        }
        err.flush()
    }
}

/// The longest line a text reader holds (1 MiB); a longer one is reported
/// and skipped, so memory stays bounded whatever the input (issue 11).
const MAX_LINE: usize = 1 << 20;

/// The error for a line longer than [`MAX_LINE`].
struct OverlongLine;

impl std::fmt::Display for OverlongLine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "line longer than {} MiB: not a log line, skipped",
            MAX_LINE >> 20
        )
    }
}

/// Whole lines of an input, a block at a time (256 KiB, more for a long
/// line, at most [`MAX_LINE`] for one line).
struct Blocks {
    reader: Box<dyn Read>,
    buf: Vec<u8>,
    filled: usize,
    handed: usize,
    at_end: bool,
    /// Dropping the rest of an overlong line.
    skipping: bool,
}

struct Block<'b> {
    /// Whole lines (the last one may lack its line end at the end of the
    /// input).
    text: &'b [u8],
    /// The read that filled the block took everything the input had
    /// buffered: flush the output (live use).
    drained: bool,
    /// The block holds the end of the input.
    at_end: bool,
    /// An overlong line was skipped right before the block's text.
    overlong: bool,
}

impl Blocks {
    const BLOCK: usize = 1 << 18;

    fn new(reader: Box<dyn Read>) -> Self {
        Blocks {
            reader,
            buf: vec![0; Self::BLOCK],
            filled: 0,
            handed: 0,
            at_end: false,
            skipping: false,
        }
    }

    /// Hand out the last block's text again, with more after it, at the
    /// next call (the caller needs more lines to decide something).
    fn hold(&mut self) {
        self.handed = 0;
    }

    fn next_block(&mut self) -> io::Result<Option<Block<'_>>> {
        // Drop what the last block handed out.
        self.buf.copy_within(self.handed..self.filled, 0);
        self.filled -= self.handed;
        self.handed = 0;
        if self.at_end && self.filled == 0 {
            return Ok(None);
        }
        let mut overlong = false;
        let mut drained = false;
        while !self.at_end {
            if self.filled == self.buf.len() {
                if self.buf.len() >= MAX_LINE {
                    // One line fills the largest buffer: drop it up to its
                    // end.
                    self.skipping = true;
                    self.filled = 0;
                } else {
                    let len = (self.buf.len() * 2).min(MAX_LINE);
                    self.buf.resize(len, 0);
                }
            }
            let room = self.buf.len() - self.filled;
            let n = match self.reader.read(&mut self.buf[self.filled..]) {
                Ok(n) => n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            let start = self.filled;
            self.filled += n;
            self.at_end = n == 0;
            drained = n < room && !self.at_end;
            if self.skipping {
                match self.buf[start..self.filled]
                    .iter()
                    .position(|&b| b == b'\n')
                {
                    Some(i) => {
                        self.buf.copy_within(start + i + 1..self.filled, 0);
                        self.filled -= start + i + 1;
                        self.skipping = false;
                        overlong = true;
                    }
                    None => {
                        self.filled = 0;
                        if self.at_end {
                            self.skipping = false;
                            overlong = true;
                        }
                        continue;
                    }
                }
            }
            if self.buf[start..self.filled].contains(&b'\n') || self.at_end {
                break;
            }
            if overlong && self.filled == 0 {
                // Report the skipped line before waiting for more.
                break;
            }
        }
        // Up to the last complete line (all of it at the end).
        let complete = if self.at_end {
            self.filled
        } else {
            self.buf[..self.filled]
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |i| i + 1)
        };
        self.handed = complete;
        Ok(Some(Block {
            text: &self.buf[..complete],
            drained,
            at_end: self.at_end,
            overlong,
        }))
    }
}

fn read_failure(name: &str, path: Option<&Path>, source: io::Error) -> Failure {
    Failure::File {
        path: path.map_or_else(|| PathBuf::from(name), Path::to_path_buf),
        source,
    }
}
