//! `motionwire decode`: a log → one record per CAN frame (docs/output.md), or
//! the summary (docs/summary.md). The streaming loop: open, read with the
//! library's [`LogReader`] (which detects the format,
//! docs/formats.md#detection), hand each event to the [`Sink`], which filters
//! and renders.

use std::fs::File;
use std::io::{self, BufWriter, IsTerminal, Read, StderrLock, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use motionwire::can::{EthercatPacket, LogEvent, LogFrame};
use motionwire::canopen::MessageKind;
use motionwire::decoder::ethercat::{
    DatagramRecord, MeaningRecord, ProcessRecord, Session, DATAGRAM_KIND, PROCESS_DATA_KIND,
    QUIET_KINDS, SERVO_KIND,
};
use motionwire::decoder::{Decoder, DecoderConfig};
use motionwire::logs::candump::RelativeTimestamps;
use motionwire::logs::{
    EventFilter, LogError, LogErrorKind, LogVisitor, Position, ReadLog, ReadOptions,
};
use motionwire::report::{Recorder, Report, ReportInput};
use motionwire::summary::{FileSpan, SeveralFiles, Summarizer, Summary};

use crate::args::{node_profiles, DecodeArgs, IdRange, Kind, TimestampBase};
use crate::failure::Failure;
use crate::out::Out;
use crate::record::{Record, CSV_HEADER};

/// Which EtherCAT records `decode` writes (docs/ethercat.md#filters).
struct EthercatFilter {
    /// The kinds `--only` names; `None`: every kind but the quiet ones
    /// (`ethercat::QUIET_KINDS`: a record a cycle or a poll).
    kinds: Option<Vec<&'static str>>,
    /// The stations `--slave` names; empty: every slave.
    slaves: Vec<u16>,
    /// A CAN filter (`--node`, `--id`) is set: no EtherCAT record.
    none: bool,
    /// The packet being read is outside `--from`, `--to`, `--iface`: none
    /// of its records.
    outside: bool,
}

impl EthercatFilter {
    /// Whether a record of `kind` about `station` is written.
    fn shows(&self, kind: &str, station: Option<u16>) -> bool {
        !self.none
            && !self.outside
            && self.kinds.as_ref().map_or_else(
                || !QUIET_KINDS.contains(&kind),
                |kinds| kinds.contains(&kind),
            )
            && (self.slaves.is_empty() || station.is_some_and(|s| self.slaves.contains(&s)))
    }
}

/// An input as given on the command line.
struct Input {
    name: String,
    path: Option<PathBuf>,
    reader: Box<dyn Read + Send>,
}

/// Open the inputs; a file named twice (by any path) is opened once, and
/// returned among the names said twice.
fn open_inputs(files: &[PathBuf]) -> Result<(Vec<Input>, Vec<String>), Failure> {
    if says_reading_stdin(files, io::stdin().is_terminal()) {
        // Said once, before anything is read: a program that waits on a
        // terminal for what the user meant as a file looks hung.
        let _ = writeln!(
            io::stderr(),
            "motionwire: reading a log from standard input (end it with Ctrl-D, or name a FILE)"
        );
    }
    if files.is_empty() {
        return Ok((vec![stdin_input()], Vec::new()));
    }
    let mut seen = std::collections::HashSet::new();
    let mut twice = Vec::new();
    let mut inputs = Vec::new();
    for path in files {
        if path.as_os_str() == "-" {
            if seen.insert(PathBuf::from("-")) {
                inputs.push(stdin_input());
            } else {
                twice.push("<stdin>".to_owned());
            }
            continue;
        }
        let file = File::open(path).map_err(|source| Failure::File {
            path: path.clone(),
            source,
        })?;
        let same = std::fs::canonicalize(path).unwrap_or_else(|_| path.clone());
        if !seen.insert(same) {
            twice.push(path.display().to_string());
            continue;
        }
        inputs.push(Input {
            name: path.display().to_string(),
            path: Some(path.clone()),
            reader: Box::new(file),
        });
    }
    Ok((inputs, twice))
}

/// Whether reading standard input is said on standard error: when the
/// inputs `files` name it (none named, or `-`) and it is a terminal, where
/// someone may be waiting; a pipe or a file stays silent
/// (docs/output.md#stdin).
fn says_reading_stdin(files: &[PathBuf], stdin_is_terminal: bool) -> bool {
    stdin_is_terminal && (files.is_empty() || files.iter().any(|f| f.as_os_str() == "-"))
}

fn stdin_input() -> Input {
    Input {
        name: "<stdin>".to_owned(),
        path: None,
        reader: Box::new(io::stdin()),
    }
}

/// How many malformed lines and damaged records of one file are said one by
/// one on standard error without `--verbose`; the rest are counted in one
/// line (docs/output.md#stderr).
pub const COMPLAINTS_PER_FILE: u64 = 100;

/// How records are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Output {
    Text,
    Json,
    Csv,
}

/// Where frames go: read by the library's decoder, then filtered and
/// rendered, or added to the summary (which sees every frame,
/// docs/output.md#filters).
struct Sink<'a> {
    /// Standard output: records are built into its block, which its own
    /// thread writes.
    out: Out,
    err: BufWriter<StderrLock<'static>>,
    summary: Option<Summarizer>,
    /// With `motionwire report`: the recording's timeline and summary, and
    /// the page they go to (docs/report.md).
    recorder: Option<Recorder>,
    report: Option<Report>,
    output: Output,
    kinds: [bool; MessageKind::ALL.len()],
    /// Which EtherCAT records are written (docs/ethercat.md#filters).
    ethercat_shown: EthercatFilter,
    nodes: Option<[bool; 128]>,
    ids: &'a [IdRange],
    /// `--from`, `--to`, `--iface`: what is read at all, the summary and
    /// the page included (docs/output.md#window). Without them every event
    /// is kept, and the filter is not asked.
    filter: EventFilter,
    /// Frames of the file being read that the filter leaves out.
    file_dropped: u64,
    skipped: u64,
    /// Damaged records of binary logs reported.
    damaged: u64,
    /// The malformed lines and damaged records of the file being read.
    file_skipped: u64,
    file_damaged: u64,
    /// Say every complaint, not only the first [`COMPLAINTS_PER_FILE`] of
    /// each file.
    verbose: bool,
    /// Bus events read (log entries that are not frames), from every
    /// input.
    bus_events: u64,
    /// A progress line is on the terminal (standard error).
    progress_shown: bool,
    /// Frames read so far, from every input.
    frames: u64,
    /// The decoder session: what the log teaches as it is read (SDO
    /// channels, PDO mappings, drive states; docs/canopen.md#transfers,
    /// docs/canopen.md#pdo-mappings, docs/canopen.md#cia402).
    decoder: Decoder,
    /// How the decoder was configured (the summary's heartbeat consumer
    /// time too): a new recording starts with it.
    config: DecoderConfig,
    /// The input's name, when several are read: every record names it.
    file: Option<String>,
    /// The files, joined or apart: where a file's lines lie in its
    /// recording (docs/output.md#several-files).
    files: SeveralFiles,
    /// A summary was written.
    summary_written: bool,
    /// The EtherCAT session: which copy each packet is, the frames lost
    /// (docs/ethercat.md#direction).
    ethercat: Session,
    /// The name of the input being read, for the messages about it.
    input: String,
}

/// Read an ENI file: UTF-8 (a byte-order mark skipped), else Latin-1, as
/// XML declares it.
fn read_eni(
    path: &std::path::Path,
) -> Result<Vec<motionwire::decoder::ethercat::SlaveConfig>, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
    let text = match std::str::from_utf8(bytes) {
        Ok(text) => std::borrow::Cow::Borrowed(text),
        Err(_) => std::borrow::Cow::Owned(bytes.iter().map(|&b| char::from(b)).collect()),
    };
    motionwire::decoder::ethercat::parse_eni(&text).map_err(|e| e.to_string())
}

impl<'a> Sink<'a> {
    fn new(args: &'a DecodeArgs, page: bool, files: SeveralFiles) -> Result<Self, Failure> {
        // The page charts drives' signals (docs/report.md#signals).
        let mut config = DecoderConfig::new()
            .profiles_from(node_profiles(&args.reading.profile))
            .signals(page || !args.summary);
        for (node, path) in &args.reading.eds {
            config = config.eds_file(*node, path).map_err(|why| {
                Failure::Usage(format!("--eds {}={}: {why}", node, path.display()))
            })?;
        }
        let mut kinds = [args.only.is_empty(); MessageKind::ALL.len()];
        let mut ethercat_kinds = Vec::new();
        for kind in &args.only {
            match kind {
                Kind::Can(kind) => kinds[kind.index()] = true,
                Kind::Ethercat(kind) => ethercat_kinds.push(*kind),
            }
        }
        // docs/ethercat.md#filters: `--only` of CAN kinds alone, `--node`
        // and `--id` select CAN frames, which no EtherCAT record is;
        // `--slave` selects EtherCAT records, which no CAN frame is.
        let can_filtered = !args.node.is_empty() || !args.id.is_empty();
        let ethercat_shown = EthercatFilter {
            kinds: (!args.only.is_empty()).then_some(ethercat_kinds),
            slaves: args.slave.clone(),
            none: can_filtered,
            outside: false,
        };
        if !args.slave.is_empty() {
            kinds = [false; MessageKind::ALL.len()];
        }
        let nodes = (!args.node.is_empty()).then(|| {
            let mut nodes = [false; 128];
            for node in &args.node {
                nodes[usize::from(node.get())] = true;
            }
            nodes
        });
        if let Some(ms) = args.heartbeat_ms {
            config = config.heartbeat_timeout(Duration::from_millis(u64::from(ms)));
        }
        config = config.servos(args.reading.servo.iter().copied().collect());
        if let Some(path) = &args.reading.eni {
            let slaves = read_eni(path)
                .map_err(|why| Failure::Usage(format!("--eni {}: {why}", path.display())))?;
            config = config.ethercat_slaves(slaves);
        }
        let summary = (args.summary && !page).then(|| Summarizer::new(config.clone()));
        let recorder = page.then(|| Recorder::new(config.clone()));
        Ok(Sink {
            out: Out::new(),
            err: BufWriter::new(io::stderr().lock()),
            summary,
            recorder,
            report: page.then(Report::new),
            output: if args.csv {
                Output::Csv
            } else if args.json {
                Output::Json
            } else {
                Output::Text
            },
            kinds,
            ethercat_shown,
            nodes,
            ids: &args.id,
            filter: args.reading.event_filter(),
            file_dropped: 0,
            skipped: 0,
            damaged: 0,
            file_skipped: 0,
            file_damaged: 0,
            verbose: args.reading.verbose,
            bus_events: 0,
            progress_shown: false,
            frames: 0,
            decoder: Decoder::new(config.clone()),
            ethercat: Session::with_config(&config),
            config,
            file: None,
            files,
            summary_written: false,
            input: String::new(),
        })
    }

    #[inline]
    fn frame(&mut self, position: Position, frame: &LogFrame<'_>, kept: bool) -> io::Result<()> {
        // Every frame teaches the decoder, shown or not.
        let decoded = self.decoder.decode(position, frame);
        if !kept {
            return Ok(());
        }
        if !self.ids.is_empty() {
            let id = frame.frame.id().raw();
            if !self.ids.iter().any(|range| range.contains(id)) {
                return Ok(());
            }
        }
        if !self.kinds[decoded.kind.index()] {
            return Ok(());
        }
        if let Some(nodes) = &self.nodes {
            match decoded.node {
                Some(node) if nodes[usize::from(node.get())] => {}
                _ => return Ok(()),
            }
        }
        if self.output == Output::Json {
            decoded.append_json(self.out.block(), self.file.as_deref());
            return self.out.wrote();
        }
        let record = Record {
            line: position.number(),
            log: frame,
            decoded: &decoded,
            message: decoded.message(),
            file: self.file.as_deref(),
        };
        match self.output {
            Output::Text => record.write_text(&mut self.out),
            _ => record.write_csv(&mut self.out),
        }
    }

    /// An EtherCAT packet: one record per datagram
    /// (docs/ethercat.md#records); a damaged header or datagram said on
    /// standard error with the packet's number, and counted.
    fn ethercat(
        &mut self,
        position: Position,
        packet: &EthercatPacket<'_>,
        kept: bool,
    ) -> io::Result<()> {
        // Outside the window or interfaces: the session still reads the
        // packet (which copy it is, frames lost), no record of it is written.
        self.ethercat_shown.outside = !kept;
        let packet = match self.ethercat.read(position, packet) {
            Ok(packet) => packet,
            Err(damaged) => {
                self.damaged += 1;
                self.clear_progress()?;
                return writeln!(self.err, "{}:{}: {}", self.input, position, damaged.error);
            }
        };
        for (at, datagram) in packet.datagrams().enumerate() {
            let datagram = match datagram {
                Ok(datagram) => datagram,
                Err(error) => {
                    self.ethercat.count_damaged();
                    self.damaged += 1;
                    self.clear_progress()?;
                    return writeln!(
                        self.err,
                        "{}:{}: datagram {}: {error}",
                        self.input,
                        position,
                        at + 1
                    );
                }
            };
            let record = DatagramRecord {
                packet: &packet,
                number: at + 1,
                datagram,
            };
            // The slave it reaches, by station address or alias: asked
            // only when `--slave` selects.
            let station = if self.ethercat_shown.slaves.is_empty() {
                None
            } else {
                self.ethercat.station(&packet, &datagram)
            };
            if self.ethercat_shown.shows(DATAGRAM_KIND, station) {
                match self.output {
                    Output::Json => {
                        record.append_json(self.out.block(), self.file.as_deref());
                    }
                    Output::Text => record.write_text(&mut self.out, self.file.as_deref())?,
                    Output::Csv => crate::record::write_datagram_csv(
                        &mut self.out,
                        &record,
                        self.file.as_deref(),
                    )?,
                }
            }
            // What the datagram tells, after its record: written as the
            // session hands it over.
            let (output, file) = (self.output, self.file.as_deref());
            let out = &mut self.out;
            let shown = &self.ethercat_shown;
            let mut written = Ok(());
            self.ethercat.meanings(&packet, at, &datagram, |meaning| {
                let record = MeaningRecord {
                    packet: &packet,
                    number: at + 1,
                    meaning,
                };
                if !shown.shows(record.kind(), record.slave().station) {
                    return;
                }
                match output {
                    Output::Json => record.append_json(out.block(), file),
                    Output::Text if written.is_ok() => {
                        written = record.write_text(out, datagram.command().name(), file);
                    }
                    // One table of frames (docs/ethercat.md#records): the
                    // datagram's row holds the bytes.
                    Output::Text | Output::Csv => {}
                }
            });
            written?;
            // Each slave's process data of a returned cyclic datagram.
            let out = &mut self.out;
            let mut written = Ok(());
            self.ethercat.process_data(&packet, at, &datagram, |data| {
                let record = ProcessRecord {
                    packet: &packet,
                    number: at + 1,
                    data,
                };
                let station = data.slave.and_then(|s| s.station);
                let process = shown.shows(PROCESS_DATA_KIND, station);
                let servo = data.servo.is_some() && shown.shows(SERVO_KIND, station);
                match output {
                    Output::Json => {
                        if process {
                            record.append_json(out.block(), file);
                        }
                        if servo {
                            record.append_servo_json(out.block(), file);
                        }
                    }
                    Output::Text if written.is_ok() && (process || servo) => {
                        written = record.write_text(out, file, process, servo);
                    }
                    Output::Text | Output::Csv => {}
                }
            });
            written?;
            self.out.wrote()?;
        }
        // What the configuration or a mailbox shows wrong
        // (docs/ethercat.md#process-data): said with its packet.
        let (problems, more) = self.ethercat.take_problems();
        if !problems.is_empty() || more > 0 {
            self.clear_progress()?;
        }
        for problem in problems {
            writeln!(
                self.err,
                "{}:{}: {}: {}",
                self.input, problem.position, problem.slave, problem.error
            )?;
        }
        if more > 0 {
            writeln!(
                self.err,
                "{}:{}: {more} more configuration problems",
                self.input, position
            )?;
        }
        Ok(())
    }

    #[inline]
    fn event(&mut self, position: Position, event: &LogEvent<'_>) -> io::Result<()> {
        if let LogEvent::Status(_) = event {
            return self.bus_event(position, event);
        }
        self.frames += 1;
        if !self.filter.is_empty() && !self.filter.keeps(event) {
            return self.left_out(position, event);
        }
        // The summary and the page are those of the events kept.
        if let Some(summary) = self.summary.as_mut() {
            summary.add(position, event);
            return Ok(());
        }
        if self.recorder.is_some() {
            if self.page_keeps(event) {
                if let Some(recorder) = self.recorder.as_mut() {
                    recorder.add(position, event);
                }
            }
            return Ok(());
        }
        match event {
            LogEvent::Frame(frame) => self.frame(position, frame, true),
            LogEvent::Status(_) => Ok(()),
            LogEvent::Ethercat(packet) => self.ethercat(position, packet, true),
        }
    }

    /// A bus event (a TRC status row): counted, and added to the summary
    /// or the page when the filter keeps it; it has no record.
    #[cold]
    fn bus_event(&mut self, position: Position, event: &LogEvent<'_>) -> io::Result<()> {
        self.bus_events += 1;
        if !self.filter.is_empty() && !self.filter.keeps(event) {
            return Ok(());
        }
        if let Some(summary) = self.summary.as_mut() {
            // `add_with` rather than `add`: with a second call, `add` would
            // no longer be compiled into the frames' path (`event`).
            summary.add_with(position, event, |_| {});
        } else if self.recorder.is_some() && self.page_keeps(event) {
            if let Some(recorder) = self.recorder.as_mut() {
                recorder.add(position, event);
            }
        }
        Ok(())
    }

    /// A frame or packet that `--from`, `--to` or `--iface` leave out:
    /// counted and, outside the summary and the page, still read by the
    /// decoder or the EtherCAT session; no record is written.
    #[cold]
    fn left_out(&mut self, position: Position, event: &LogEvent<'_>) -> io::Result<()> {
        self.file_dropped += 1;
        if self.summary.is_some() || self.recorder.is_some() {
            return Ok(());
        }
        match event {
            LogEvent::Frame(frame) => self.frame(position, frame, false),
            LogEvent::Status(_) => Ok(()),
            LogEvent::Ethercat(packet) => self.ethercat(position, packet, false),
        }
    }

    /// With `motionwire report`: whether `--node` and `--id` keep the event
    /// for the page (docs/report.md#command): a CAN frame that carries one of
    /// the node-IDs in its identifier and has one of the identifiers; with
    /// either option, no bus event or EtherCAT packet.
    fn page_keeps(&self, event: &LogEvent<'_>) -> bool {
        if self.nodes.is_none() && self.ids.is_empty() {
            return true;
        }
        let LogEvent::Frame(frame) = event else {
            return false;
        };
        let id = frame.frame.id().raw();
        if !self.ids.is_empty() && !self.ids.iter().any(|range| range.contains(id)) {
            return false;
        }
        match (&self.nodes, MessageKind::classify(&frame.frame).1) {
            (None, _) => true,
            (Some(nodes), Some(node)) => nodes[usize::from(node.get())],
            (Some(_), None) => false,
        }
    }

    /// A line or record that could not be read: said on standard error
    /// with its position, counted (docs/formats.md#reported).
    #[cold]
    fn malformed(&mut self, name: &str, line: u64, why: &dyn std::fmt::Display) -> io::Result<()> {
        self.skipped += 1;
        self.file_skipped += 1;
        if !self.says_complaint() {
            return Ok(());
        }
        self.clear_progress()?;
        writeln!(self.err, "{name}:{line}: {why}")
    }

    /// Whether the file's complaint just counted is said one by one: the
    /// first [`COMPLAINTS_PER_FILE`] of a file, or all with `--verbose`.
    fn says_complaint(&self) -> bool {
        self.verbose || self.file_skipped + self.file_damaged <= COMPLAINTS_PER_FILE
    }

    /// The file's complaints not said one by one.
    fn unsaid(&self) -> u64 {
        if self.verbose {
            return 0;
        }
        (self.file_skipped + self.file_damaged).saturating_sub(COMPLAINTS_PER_FILE)
    }

    /// The file's malformed lines and damaged records, in words.
    fn file_complaints(&self) -> String {
        let plural = |n: u64| if n == 1 { "" } else { "s" };
        let lines = (self.file_skipped > 0).then(|| {
            format!(
                "{} malformed line{}",
                self.file_skipped,
                plural(self.file_skipped)
            )
        });
        let records = (self.file_damaged > 0).then(|| {
            format!(
                "{} damaged record{}",
                self.file_damaged,
                plural(self.file_damaged)
            )
        });
        lines
            .into_iter()
            .chain(records)
            .collect::<Vec<_>>()
            .join(", ")
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
    run_with(args, false).map(|(code, _)| code)
}

/// Read the logs as `decode --summary` does, into the page of `motionwire
/// report` (docs/report.md): the same inputs, options, messages on standard
/// error and exit statuses; the page is returned, not written.
pub fn run_page(args: &DecodeArgs) -> Result<(ExitCode, Report), Failure> {
    let (code, report) = run_with(args, true)?;
    Ok((code, report.unwrap_or_default()))
}

fn run_with(args: &DecodeArgs, page: bool) -> Result<(ExitCode, Option<Report>), Failure> {
    if args.heartbeat_ms.is_some() && !args.summary {
        return Err(Failure::Usage(
            "--heartbeat-ms needs --summary (heartbeat gaps are reported per node)".to_owned(),
        ));
    }
    let (inputs, twice) = open_inputs(&args.files)?;
    let several = inputs.len() > 1;
    let mut sink = Sink::new(args, page, SeveralFiles::new(inputs.len(), args.joined))?;
    for name in twice {
        writeln!(
            sink.err,
            "motionwire: {name} is given more than once: read once"
        )?;
    }
    if sink.output == Output::Csv {
        if several {
            sink.out.write_all(b"file,")?;
        }
        write!(sink.out, "{CSV_HEADER}\r\n")?;
    }
    let mut options = ReadOptions::new();
    if let Some(format) = args.reading.format {
        options = options.format(format);
    }
    if let Some(base) = args.reading.timestamps {
        options = options.relative_timestamps(match base {
            TimestampBase::Delta => RelativeTimestamps::Delta,
            TimestampBase::Zero => RelativeTimestamps::Zero,
        });
    }
    for input in inputs {
        let Input { name, path, reader } = input;
        if sink.files.begin() {
            // A recording of its own: nothing learned from the file
            // before carries over (docs/output.md#several-files).
            sink.decoder = Decoder::new(sink.config.clone());
            sink.ethercat = Session::with_config(sink.decoder.config());
            sink.filter.restart();
            if args.summary && !page {
                sink.summary = Some(Summarizer::new(sink.config.clone()));
            }
            if page {
                sink.recorder = Some(Recorder::new(sink.config.clone()));
            }
        }
        if several {
            sink.file = Some(name.clone());
        }
        // Progress: the file's size, when the bytes read are the file's.
        let size = path
            .as_deref()
            .and_then(|p| std::fs::metadata(p).ok())
            .map(|m| m.len());
        // A file by its path: a format read in place (MF4 seeks through
        // its blocks) needs the file, not a stream of it.
        let opened = match path.as_deref() {
            Some(path) => {
                drop(reader);
                options.open(path)
            }
            None => options.read(reader),
        };
        let mut log = opened.map_err(|e| open_failure(&name, path.as_deref(), e))?;
        let format = log.format();
        let mut progress = Progress::new(&name, size.filter(|_| !log.is_gzip()));
        let before = sink.frames;
        sink.input.clone_from(&name);
        let bus_events_before = sink.bus_events;
        sink.file_skipped = 0;
        sink.file_damaged = 0;
        sink.file_dropped = 0;
        let reversals_before = sink.ethercat.counts().time_reversals;
        let last = log.visit(ReadAll {
            sink: &mut sink,
            progress: &mut progress,
            name: &name,
            path: path.as_deref(),
        })?;
        sink.clear_progress()?;
        let counts = sink.ethercat.counts();
        if let (true, Some((at, back))) = (
            counts.time_reversals > reversals_before,
            counts.first_reversal,
        ) {
            // docs/ethercat.md#reading: said once, read in the capture's
            // order all the same.
            writeln!(
                sink.err,
                "{name}: {} EtherCAT packet{} earlier than the packet before (the first, packet {at}, by {:.6} s): read in the capture's order",
                counts.time_reversals - reversals_before,
                if counts.time_reversals - reversals_before == 1 { " is" } else { "s are" },
                back.as_secs_f64()
            )?;
        }
        if sink.file_skipped + sink.file_damaged > 0
            && sink.frames == before
            && sink.bus_events == bus_events_before
        {
            // Nothing read but complaints: the input is not what it was
            // read as (`--format trc` on a candump log), said in one line.
            sink.flush()?;
            return Err(Failure::NothingRead {
                name,
                format: format.name(),
                complaints: sink.file_complaints(),
                partly: sink.unsaid() > 0,
            });
        }
        if sink.unsaid() > 0 {
            writeln!(
                sink.err,
                "{name}: {} in all; the first {COMPLAINTS_PER_FILE} are said above (--verbose says each)",
                sink.file_complaints()
            )?;
        }
        if sink.frames == before {
            // Nothing to write is not nothing to say (docs/output.md#stderr).
            writeln!(sink.err, "{name}: 0 frames")?;
        } else if sink.file_dropped == sink.frames - before && !sink.filter.is_empty() {
            // A UTC window on a log of relative times, a channel number
            // for a named interface: said, not left to an empty output.
            let read = sink.file_dropped;
            writeln!(
                sink.err,
                "{name}: none of its {read} frame{} passes {}",
                if read == 1 { "" } else { "s" },
                filter_words(&args.reading)
            )?;
        }
        if let Some(report) = sink.report.as_mut() {
            report.add_input(ReportInput {
                name: name.clone(),
                format: format.name().to_owned(),
                last_line: last,
            });
        }
        if sink.files.end(&name, last) {
            write_summary(&mut sink, args.json, Some(name.clone()))?;
            take_recording(&mut sink, Some(name), Vec::new())?;
        }
    }
    if !several || sink.files.joined() {
        let spans = sink.files.take_spans();
        write_summary(&mut sink, args.json, None)?;
        if sink.summary_written {
            write_spans(&mut sink, args.json, &spans)?;
        }
        take_recording(&mut sink, None, spans)?;
    }

    let Sink {
        out,
        mut err,
        skipped,
        damaged,
        mut report,
        ..
    } = sink;
    if let Some(report) = report.as_mut() {
        // The page says what standard error said (docs/report.md#page).
        if skipped > 0 {
            report.add_note(format!(
                "{skipped} malformed line{} skipped (said on standard error)",
                if skipped == 1 { "" } else { "s" }
            ));
        }
        if damaged > 0 {
            report.add_note(format!(
                "{damaged} damaged record{} reported (said on standard error)",
                if damaged == 1 { "" } else { "s" }
            ));
        }
    }
    out.finish()?;
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
        return Ok((ExitCode::from(1), report));
    }
    err.flush()?;
    Ok((ExitCode::SUCCESS, report))
}

/// Read a log event by event, each with its line or record
/// (docs/formats.md#positions): frames and bus events to the sink, malformed
/// lines and damaged records said on standard error, and the output flushed
/// whenever the input has nothing more buffered (live use,
/// docs/output.md#live). A [`LogVisitor`], so that the loop is compiled for
/// each format's reader.
struct ReadAll<'r, 's, 'a> {
    sink: &'r mut Sink<'a>,
    progress: &'r mut Progress,
    name: &'s str,
    path: Option<&'s Path>,
}

impl LogVisitor for ReadAll<'_, '_, '_> {
    /// The last line or record number of the input.
    type Output = Result<u64, Failure>;

    fn visit<L: ReadLog + ?Sized>(self, log: &mut L) -> Result<u64, Failure> {
        /// How many lines or records pass between looks at the progress.
        const PROGRESS_EVERY: u64 = 1 << 12;
        let ReadAll {
            sink,
            progress,
            name,
            path,
        } = self;
        let mut number = 0;
        loop {
            match log.next_event() {
                None => break,
                // Read where it lies: the record is not moved.
                Some(Ok(ref record)) => {
                    number = record.position.number();
                    sink.event(sink.files.line(record.position), &record.event)?;
                }
                Some(Err(error)) => {
                    number = error.position().map_or(number, Position::number);
                    report(sink, error, name, path)?;
                }
            }
            if number % PROGRESS_EVERY == 0 {
                progress.advance(sink, log.bytes_read(), number)?;
            }
            if log.drained() {
                // Live use: what was decoded so far is written out now
                // (docs/output.md#live); a file read in full blocks never gets
                // here.
                sink.flush()?;
            }
        }
        // docs/formats.md#pcap, docs/formats.md#blf, docs/formats.md#mf4:
        // counted and said once per kind, not per record, naming the link
        // type or the group ("12 packets of link type 1 (Ethernet) skipped:
        // not CAN"); the kinds count every record skipped (`ReadLog::other_kinds`).
        for kind in log.other_kinds() {
            writeln!(sink.err, "{name}: {kind}")?;
        }
        Ok(number)
    }
}

/// The `--from`, `--to` and `--iface` given, as the message about a file
/// they keep nothing of says them.
fn filter_words(reading: &crate::args::ReadingArgs) -> String {
    let mut words = Vec::new();
    if let Some(from) = reading.from {
        words.push(format!("--from {from}"));
    }
    if let Some(to) = reading.to {
        words.push(format!("--to {to}"));
    }
    if !reading.iface.is_empty() {
        words.push(format!("--iface {}", reading.iface.join(",")));
    }
    words.join(" ")
}

/// Write the summary of the recording read so far (with `--summary`),
/// naming its file when several are read apart.
fn write_summary(sink: &mut Sink<'_>, json: bool, file: Option<String>) -> Result<(), Failure> {
    let Some(summarizer) = sink.summary.take() else {
        return Ok(());
    };
    let mut summary = summarizer.finish();
    summary.file = file;
    say_unchecked_timeouts(&mut sink.err, &summary)?;
    if json {
        summary.write_json(&mut sink.out)?;
    } else {
        write!(sink.out, "{summary}")?;
    }
    sink.summary_written = true;
    Ok(())
}

/// Say on standard error that `summary`'s heartbeat timeouts could not be
/// checked: its log has frames without timestamps (docs/output.md#stderr).
fn say_unchecked_timeouts(err: &mut impl Write, summary: &Summary) -> io::Result<()> {
    if !summary.timeouts_not_checked() {
        return Ok(());
    }
    let about = summary
        .file
        .as_deref()
        .map_or_else(String::new, |file| format!("{file}: "));
    writeln!(
        err,
        "motionwire: {about}the log has frames without timestamps: heartbeat timeouts were \
         not checked (--heartbeat-ms)"
    )
}

/// With `motionwire report`: the recording read so far, with its summary,
/// onto the page, naming its file when several are read apart.
fn take_recording(
    sink: &mut Sink<'_>,
    file: Option<String>,
    files: Vec<FileSpan>,
) -> Result<(), Failure> {
    let Some(recorder) = sink.recorder.take() else {
        return Ok(());
    };
    let mut recording = recorder.finish();
    recording.summary.file = file;
    recording.files = files;
    say_unchecked_timeouts(&mut sink.err, &recording.summary)?;
    if let Some(report) = sink.report.as_mut() {
        report.add_recording(recording);
    }
    Ok(())
}

/// With `--joined`: where each file's lines lie in the one recording
/// (docs/output.md#several-files).
fn write_spans(sink: &mut Sink<'_>, json: bool, spans: &[FileSpan]) -> io::Result<()> {
    for span in spans {
        if json {
            serde_json::to_writer(&mut sink.out, span).map_err(io::Error::from)?;
            writeln!(sink.out)?;
        } else {
            writeln!(sink.out, "{span}")?;
        }
    }
    Ok(())
}

/// Say an error of the reader: a malformed or over-long line is counted
/// with its line; a damaged record of a binary log is said with its byte
/// offset; an input that cannot be read ends the run.
#[cold]
fn report(
    sink: &mut Sink<'_>,
    error: LogError,
    name: &str,
    path: Option<&Path>,
) -> Result<(), Failure> {
    let skipped = error.is_skipped();
    match (error.position(), error.into_kind()) {
        (Some(Position::Line(line)), kind) if skipped => sink.malformed(name, line, &kind)?,
        (_, LogErrorKind::Io(e)) => return Err(read_failure(name, path, e)),
        (_, kind) => {
            sink.damaged += 1;
            sink.file_damaged += 1;
            if sink.says_complaint() {
                sink.clear_progress()?;
                writeln!(sink.err, "{name}: {kind}")?;
            }
        }
    }
    Ok(())
}

/// A log that cannot be opened: unreadable, unrecognised, or a binary log
/// whose header is damaged.
fn open_failure(name: &str, path: Option<&Path>, error: LogError) -> Failure {
    match error.into_kind() {
        LogErrorKind::Io(e) => read_failure(name, path, e),
        LogErrorKind::Damaged(error) | LogErrorKind::Malformed(error) => Failure::Damaged {
            name: name.to_owned(),
            error: error.into(),
        },
        kind => Failure::Log {
            name: name.to_owned(),
            kind,
        },
    }
}

/// Progress of a long run on standard error, only when it is a terminal
/// (docs/output.md#progress): `name: 42 % (310 MiB), 9 200 000 lines`, redrawn
/// at most four times a second after the first second, erased at the end.
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

    fn advance(&mut self, sink: &mut Sink<'_>, read: u64, lines: u64) -> io::Result<()> {
        self.read = read;
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

fn read_failure(name: &str, path: Option<&Path>, source: io::Error) -> Failure {
    Failure::File {
        path: path.map_or_else(|| PathBuf::from(name), Path::to_path_buf),
        source,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_input_is_said_only_on_a_terminal() {
        let files = |names: &[&str]| names.iter().map(PathBuf::from).collect::<Vec<_>>();
        assert!(says_reading_stdin(&files(&[]), true));
        assert!(says_reading_stdin(&files(&["a.log", "-"]), true));
        assert!(!says_reading_stdin(&files(&["a.log"]), true));
        assert!(!says_reading_stdin(&files(&[]), false));
        assert!(!says_reading_stdin(&files(&["-"]), false));
    }
}
