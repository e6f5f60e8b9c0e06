//! `motionwire decode`: candump text → one record per CAN frame (SPEC §6.1).

use std::fs::File;
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::ValueEnum;
use motionwire::candump::{self, CandumpFrame};
use motionwire::canopen::{CobFunction, Emcy, HeartbeatFrame, NmtState, NodeId};
use motionwire::profiles::akd::AkdManufacturerField;
use motionwire::profiles::baumer::BaumerEmcy;

use crate::json::{self, Object};
use crate::summary::Summary;
use crate::{DecodeArgs, Failure, Profile, Profiles};

/// The kind of a frame, from its identifier (SPEC §6.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, ValueEnum)]
#[value(rename_all = "snake_case")]
pub enum Kind {
    /// 0x081–0x0FF.
    Emcy,
    /// 0x701–0x77F, data frame (heartbeat, boot-up or node-guarding answer).
    Heartbeat,
    /// 0x701–0x77F, remote request.
    GuardRequest,
    /// 0x000.
    NmtCommand,
    /// 0x080.
    Sync,
    /// 0x181–0x57F.
    Pdo,
    /// 0x581–0x67F.
    Sdo,
    /// Everything else, and every extended frame.
    Other,
}

impl Kind {
    /// Every kind, in the order the summary lists them.
    pub const ALL: [Kind; 8] = [
        Kind::Emcy,
        Kind::Heartbeat,
        Kind::GuardRequest,
        Kind::NmtCommand,
        Kind::Sync,
        Kind::Pdo,
        Kind::Sdo,
        Kind::Other,
    ];

    /// The name the JSON output uses.
    pub const fn name(self) -> &'static str {
        match self {
            Kind::Emcy => "emcy",
            Kind::Heartbeat => "heartbeat",
            Kind::GuardRequest => "guard_request",
            Kind::NmtCommand => "nmt_command",
            Kind::Sync => "sync",
            Kind::Pdo => "pdo",
            Kind::Sdo => "sdo",
            Kind::Other => "other",
        }
    }

    /// The position of the kind in [`Kind::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Classify a frame by its identifier and return the node it belongs to
    /// where the kind has one (SPEC §6.1's identifier table).
    pub fn of(frame: &CandumpFrame<'_>) -> (Kind, Option<NodeId>) {
        if frame.is_extended() {
            return (Kind::Other, None);
        }
        // A standard identifier is at most 0x7FF, so it fits a u16.
        let id = u16::try_from(frame.id().raw()).unwrap_or(u16::MAX);
        match CobFunction::classify(id) {
            CobFunction::NmtCommand => (Kind::NmtCommand, None),
            CobFunction::Sync => (Kind::Sync, None),
            CobFunction::Emcy(node) => (Kind::Emcy, Some(node)),
            CobFunction::Pdo { node, .. } => (Kind::Pdo, Some(node)),
            CobFunction::SdoTx(node) | CobFunction::SdoRx(node) => (Kind::Sdo, Some(node)),
            CobFunction::ErrorControl(node) if frame.is_rtr() => (Kind::GuardRequest, Some(node)),
            CobFunction::ErrorControl(node) => (Kind::Heartbeat, Some(node)),
            CobFunction::Time | CobFunction::Other => (Kind::Other, None),
        }
    }
}

/// An error-control byte: heartbeat, boot-up or node-guarding answer
/// (SPEC §2.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateByte {
    /// The byte with bit 7 masked off.
    pub raw: u8,
    /// Bit 7: the node-guarding toggle.
    pub toggle: bool,
    /// The NMT state, or `None` for a value CiA 301 does not define.
    pub state: Option<NmtState>,
}

impl StateByte {
    /// The state's JSON name, `invalid` for an undefined value.
    pub fn state_name(&self) -> &'static str {
        self.state.map_or("invalid", NmtState::name)
    }
}

/// What the payload of a frame says, by kind.
#[derive(Debug, Clone, Copy)]
pub enum Payload {
    /// No decoding beyond the common keys.
    Plain,
    /// An EMCY (SPEC §2.1).
    Emcy(Emcy),
    /// A heartbeat-kind frame (SPEC §2.7).
    State(StateByte),
    /// The frame cannot be decoded as its kind.
    Error(motionwire::Error),
}

/// One decoded frame.
pub struct Record<'f, 'a> {
    /// 1-based line number in its input.
    pub line: u64,
    /// The frame as parsed from the line.
    pub frame: &'f CandumpFrame<'a>,
    /// Its kind.
    pub kind: Kind,
    /// Its node, for the kinds that have one.
    pub node: Option<NodeId>,
    /// The decoded payload.
    pub payload: Payload,
}

impl<'f, 'a> Record<'f, 'a> {
    /// Classify and decode a frame.
    pub fn new(line: u64, frame: &'f CandumpFrame<'a>) -> Self {
        let (kind, node) = Kind::of(frame);
        let payload = match kind {
            Kind::Emcy => match Emcy::parse(frame.data()) {
                Ok(emcy) => Payload::Emcy(emcy),
                Err(e) => Payload::Error(e),
            },
            Kind::Heartbeat => match HeartbeatFrame::new_checked(frame.data()) {
                Ok(view) => {
                    let raw = view.state_raw() & 0x7F;
                    Payload::State(StateByte {
                        raw,
                        toggle: view.reserved_bit(),
                        state: NmtState::from_byte(raw).ok(),
                    })
                }
                Err(e) => Payload::Error(e),
            },
            _ => Payload::Plain,
        };
        Record {
            line,
            frame,
            kind,
            node,
            payload,
        }
    }

    /// Write the record as one JSON object and a newline (SPEC §6.1).
    pub fn write_json<W: Write>(&self, out: &mut W, profile: Profile) -> io::Result<()> {
        let frame = self.frame;
        let mut obj = Object::begin(out)?;
        obj.uint("line", self.line)?;
        match frame.timestamp() {
            Some(ts) => write!(obj.key("ts")?, "{}.{:06}", ts.secs(), ts.micros())?,
            None => obj.null("ts")?,
        }
        obj.str("iface", frame.iface_str())?;
        obj.uint("id", u64::from(frame.id().raw()))?;
        obj.bool("extended", frame.is_extended())?;
        obj.bool("rtr", frame.is_rtr())?;
        obj.bool("fd", frame.is_fd())?;
        json::hex_string(obj.key("data")?, frame.data())?;
        obj.str("kind", self.kind.name())?;
        if let Some(node) = self.node {
            obj.uint("node", u64::from(node.get()))?;
        }
        match self.payload {
            Payload::Plain => {}
            Payload::Error(e) => obj.str("error", &e.to_string())?,
            Payload::State(s) => {
                obj.str("state", s.state_name())?;
                obj.uint("state_raw", u64::from(s.raw))?;
                obj.bool("toggle", s.toggle)?;
            }
            Payload::Emcy(emcy) => {
                obj.uint("code", u64::from(emcy.code.get()))?;
                obj.str("class", emcy.code.class().name())?;
                obj.str("description", emcy.code.description())?;
                obj.uint("register", u64::from(emcy.register.bits()))?;
                obj.strs("register_flags", emcy.register.names())?;
                json::hex_string(obj.key("manufacturer")?, &emcy.manufacturer)?;
                match profile {
                    Profile::Generic => {}
                    Profile::Akd => {
                        let field = AkdManufacturerField::new_unchecked(&emcy.manufacturer[..]);
                        obj.uint("axis", u64::from(field.axis_id().get()))?;
                        match field.feedback_id() {
                            Ok(fb) => match fb.number() {
                                Some(n) => obj.uint("feedback", u64::from(n))?,
                                None => obj.null("feedback")?,
                            },
                            Err(e) => {
                                obj.null("feedback")?;
                                obj.str("error", &e.to_string())?;
                            }
                        }
                    }
                    Profile::Baumer => {
                        let baumer = BaumerEmcy::from_emcy(&emcy);
                        obj.uint("alarms", u64::from(baumer.manufacturer.alarms.bits()))?;
                        obj.uint("warnings", u64::from(baumer.manufacturer.warnings.bits()))?;
                        obj.strs("sources", baumer.sources().map(|s| s.name()))?;
                    }
                }
            }
        }
        obj.end()?;
        out_newline(out)
    }

    /// Write the record as one aligned line of text.
    pub fn write_text<W: Write>(&self, out: &mut W, profile: Profile) -> io::Result<()> {
        let frame = self.frame;
        write!(out, "{:>7}  ", self.line)?;
        match frame.timestamp() {
            Some(ts) => write!(out, "{:>10}.{:06}  ", ts.secs(), ts.micros())?,
            None => write!(out, "{:>17}  ", "-")?,
        }
        let id = frame.id().raw();
        if frame.is_extended() {
            write!(out, "{:<6} {id:08X}  ", frame.iface_str())?;
        } else {
            write!(out, "{:<6}      {id:03X}  ", frame.iface_str())?;
        }
        write!(out, "{:<13}  ", self.kind.name())?;
        match self.node {
            Some(node) => write!(out, "node {:>3}  ", node.get())?,
            None => write!(out, "{:10}", "")?,
        }
        match self.payload {
            Payload::Error(e) => {
                write_data(out, frame)?;
                write!(out, "  error: {e}")?;
            }
            Payload::Plain if self.kind == Kind::GuardRequest => {
                out.write_all(b"remote request")?
            }
            Payload::Plain => write_data(out, frame)?,
            Payload::State(s) => {
                write!(out, "{}", s.state_name())?;
                if s.state.is_none() {
                    write!(out, " (0x{:02X})", s.raw)?;
                }
                if s.toggle {
                    out.write_all(b", toggle 1")?;
                }
            }
            Payload::Emcy(emcy) => {
                write!(
                    out,
                    "{} {}: {}  register 0x{:02X}",
                    emcy.code,
                    emcy.code.class(),
                    emcy.code.description(),
                    emcy.register.bits(),
                )?;
                let mut names = emcy.register.names().peekable();
                if names.peek().is_some() {
                    out.write_all(b" [")?;
                    for (i, name) in names.enumerate() {
                        if i > 0 {
                            out.write_all(b", ")?;
                        }
                        out.write_all(name.as_bytes())?;
                    }
                    out.write_all(b"]")?;
                }
                match profile {
                    Profile::Generic => {
                        out.write_all(b"  manufacturer ")?;
                        write_hex(out, &emcy.manufacturer)?;
                    }
                    Profile::Akd => {
                        let field = AkdManufacturerField::new_unchecked(&emcy.manufacturer[..]);
                        write!(out, "  axis {}", field.axis_id().get())?;
                        match field.feedback_id() {
                            Ok(fb) => match fb.number() {
                                Some(n) => write!(out, ", feedback FB{n}")?,
                                None => out.write_all(b", no feedback fault")?,
                            },
                            Err(e) => write!(out, "  error: {e}")?,
                        }
                    }
                    Profile::Baumer => {
                        let baumer = BaumerEmcy::from_emcy(&emcy);
                        write!(
                            out,
                            "  alarms 0x{:04X} warnings 0x{:04X}",
                            baumer.manufacturer.alarms.bits(),
                            baumer.manufacturer.warnings.bits()
                        )?;
                        for (i, source) in baumer.sources().enumerate() {
                            out.write_all(if i == 0 { b"  sources " } else { b", " })?;
                            out.write_all(source.name().as_bytes())?;
                        }
                    }
                }
            }
        }
        out_newline(out)
    }
}

fn out_newline<W: Write>(out: &mut W) -> io::Result<()> {
    out.write_all(b"\n")
}

fn write_data<W: Write>(out: &mut W, frame: &CandumpFrame<'_>) -> io::Result<()> {
    if frame.is_rtr() {
        return write!(out, "[{}] remote request", frame.dlc());
    }
    write!(out, "[{}]", frame.data().len())?;
    for b in frame.data() {
        write!(out, " {b:02X}")?;
    }
    Ok(())
}

fn write_hex<W: Write>(out: &mut W, bytes: &[u8]) -> io::Result<()> {
    for b in bytes {
        write!(out, "{b:02x}")?;
    }
    Ok(())
}

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
            let file = File::open(path).map_err(|e| Failure::File(path.clone(), e))?;
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
    let mut keep = [args.only.is_empty(); Kind::ALL.len()];
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
        for_each_line(input.reader, |line, parsed| {
            match parsed {
                Ok(None) => {}
                Ok(Some(frame)) => {
                    let record = Record::new(line, &frame);
                    match summary.as_mut() {
                        Some(summary) => summary.add(&record),
                        None if keep[record.kind.index()] => {
                            if args.json {
                                record.write_json(&mut out, profiles.of(record.node))?;
                            } else {
                                record.write_text(&mut out, profiles.of(record.node))?;
                            }
                        }
                        None => {}
                    }
                }
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
    mut handle: impl FnMut(u64, motionwire::Result<Option<CandumpFrame<'_>>>) -> io::Result<()>,
) -> Result<(), LineError> {
    const BLOCK: usize = 1 << 18;
    let mut buf = vec![0u8; BLOCK];
    let mut filled = 0;
    let mut base: u64 = 0;
    loop {
        if filled == buf.len() {
            // A line longer than the block: make room for the rest of it.
            buf.resize(buf.len() * 2, 0);
        }
        let n = match reader.read(&mut buf[filled..]) {
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(LineError::Read(e)),
        };
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
        for (number, parsed) in candump::lines(&buf[..complete]) {
            lines = number;
            handle(base + number as u64, parsed).map_err(LineError::Write)?;
        }
        base += lines as u64;
        if at_end {
            return Ok(());
        }
        buf.copy_within(complete..filled, 0);
        filled -= complete;
    }
}

fn read_failure(name: &str, path: Option<&Path>, e: io::Error) -> Failure {
    Failure::File(
        path.map_or_else(|| PathBuf::from(name), Path::to_path_buf),
        e,
    )
}
