//! The command line: `motionwire decode …` and `motionwire servo …`
//! (docs/output.md#command), parsed by clap.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use motionwire::canopen::{MessageKind, NodeId};
use motionwire::decoder::ethercat::{ServoItem, ServoItemError};
use motionwire::logs::{EventFilter, LogFormat, TimeBound, TimeBoundError};
use motionwire::profiles::{NodeProfiles, Profile};

/// motionwire: read CAN logs of motion machines as CANopen — EMCYs with
/// their root cause, heartbeats and guarding, SDO transfers, PDO signals,
/// CiA 402 drive states, a post-mortem per device — and decode EtherCAT
/// servo ↔ NC frames.
#[derive(Debug, Parser)]
#[command(
    name = "motionwire",
    version,
    after_help = "The output contract, field by field: docs/README.md in the repository."
)]
pub struct Cli {
    #[command(subcommand)]
    /// What to do.
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Decode CAN logs (candump, Vector ASC and BLF, PEAK TRC, pcap/pcapng,
    /// ASAM MDF 4; detected from the content, gzip too) into one record per
    /// CAN frame, or a summary per device (docs/output.md, docs/summary.md).
    #[command(after_long_help = DECODE_AFTER_HELP)]
    Decode(DecodeArgs),
    /// Write the post-mortem of CAN logs as one self-contained HTML page:
    /// what went wrong first, a timeline of every bus and device, drive
    /// signals, the summary's tables (docs/report.md).
    Report(ReportArgs),
    /// Decode one EtherCAT servo ↔ NC frame given as hex (docs/servo.md).
    #[command(subcommand)]
    Servo(ServoCommand),
}

/// The arguments of `motionwire report`: those of `decode --summary` that
/// shape the summary, and the page's file (docs/report.md#command).
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// The HTML file to write (`-` for standard output).
    #[arg(short = 'o', long = "output", value_name = "FILE.html")]
    pub output: PathBuf,
    #[command(flatten)]
    pub reading: ReadingArgs,
    /// Accepted for the command line of `decode --summary`: the page is
    /// the summary's, always.
    #[arg(long, hide = true)]
    pub summary: bool,
    /// With several files: read them as one recording (docs/output.md#several-files).
    #[arg(long)]
    pub joined: bool,
    /// Report heartbeat gaps longer than this many milliseconds as
    /// timeouts.
    #[arg(long, value_name = "MS", value_parser = clap::value_parser!(u16).range(1..))]
    pub heartbeat_ms: Option<u16>,
    /// Refused: the page reads every kind of frame to draw the states it
    /// shows (docs/report.md#command).
    #[arg(long, hide = true, value_delimiter = ',', value_name = "KIND[,KIND]", value_parser = parse_kind)]
    pub only: Vec<Kind>,
    /// Make the page of the CAN frames that carry these node-IDs
    /// (comma-separated): its summary, timeline and signals are theirs.
    #[arg(long, value_delimiter = ',', value_name = "NODE[,NODE]", value_parser = parse_node)]
    pub node: Vec<NodeId>,
    /// Make the page of the CAN frames with these identifiers: values or
    /// ranges `FROM-TO`, comma-separated, as `decode --id`.
    #[arg(long, value_delimiter = ',', value_name = "ID[-ID][,…]", value_parser = parse_id_range)]
    pub id: Vec<IdRange>,
    /// Log files to read; none, or `-`, reads standard input.
    #[arg(value_name = "FILE")]
    pub files: Vec<PathBuf>,
}

impl ReportArgs {
    /// The same reading as `decode --summary` with these options.
    pub fn as_summary(&self) -> DecodeArgs {
        DecodeArgs {
            json: false,
            csv: false,
            reading: self.reading.clone(),
            summary: true,
            joined: self.joined,
            heartbeat_ms: self.heartbeat_ms,
            only: self.only.clone(),
            slave: Vec::new(),
            node: self.node.clone(),
            id: self.id.clone(),
            files: self.files.clone(),
        }
    }
}

/// What `motionwire decode --help` says after the options: the text
/// columns and the exit statuses (docs/output.md#text, #exit-status).
const DECODE_AFTER_HELP: &str = "\
Text output, one line per frame:
  line  ts                 iface  id        kind           node      detail
   613  1700000002.003641  can0        083  emcy           node   3  0x7305 additional_modules: …
  line    the line of a text log, or the record number of a binary one
  ts      seconds (absolute Unix time, or since the recording started), - without one
  iface   interface name or channel number, - without one
  id      CAN identifier in hex (8 digits for an extended one)
  kind    emcy, heartbeat, guard_request, guard_answer, nmt_command, sync,
          time, pdo, sdo, error_frame, other
  node    the node-ID the identifier names, blank for kinds without one
  detail  what the frame says: an EMCY in words, a heartbeat's state, an SDO
          step or the transfer it ends, a PDO's signals, an error frame's
          classes; [n] and the bytes for the others
--json writes one JSON object per frame, --csv one row; --summary one record per
device and per bus. Every key: docs/output.md and docs/summary.md in the
repository.

Exit status:
  0  every line or record was read
  1  some lines were malformed or some records damaged: each said on standard
     error with its position, then a count; the rest was decoded
  2  the command could not do its job: bad arguments, a file that cannot be
     read, an input in no known log format, a damaged binary header, an input
     of which nothing could be read (every line malformed: is --format right?)

Complaints are bounded: the first 100 malformed lines or damaged records of
each file are said one by one, the rest counted in one line (--verbose says
every one).";

/// The arguments of `motionwire decode`.
#[derive(Debug, Args)]
pub struct DecodeArgs {
    /// Write one JSON object per line instead of aligned text.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Write one CSV row per frame, under a header row (docs/output.md#csv).
    #[arg(long, conflicts_with = "summary")]
    pub csv: bool,
    #[command(flatten)]
    pub reading: ReadingArgs,
    /// After the input, write one record per node seen instead of one per
    /// frame: frame counts, EMCYs with the root cause, heartbeats, guarding.
    #[arg(long)]
    pub summary: bool,
    /// With several files: read them as one recording (rotated logs of one
    /// bus, in order): one decoder and one summary across them, lines
    /// numbered on from one file to the next. Without it each file is a
    /// recording of its own, decoded and summarized apart
    /// (docs/output.md#several-files).
    #[arg(long)]
    pub joined: bool,
    /// With --summary: report heartbeat gaps longer than this many
    /// milliseconds as timeouts.
    #[arg(long, value_name = "MS", value_parser = clap::value_parser!(u16).range(1..))]
    pub heartbeat_ms: Option<u16>,
    /// Keep only frames of these kinds (comma-separated) in the per-frame
    /// output; the summary always counts every frame.
    #[arg(long, value_delimiter = ',', value_name = "KIND[,KIND]", value_parser = parse_kind, help = kind_help())]
    pub only: Vec<Kind>,
    /// Keep only the EtherCAT records of these slaves, by station address
    /// (comma-separated, decimal or `0x` hex; docs/ethercat.md#filters);
    /// the summary counts every packet.
    #[arg(long, value_delimiter = ',', value_name = "STATION[,STATION]", value_parser = parse_station)]
    pub slave: Vec<u16>,
    /// Keep only frames that carry one of these node-IDs (comma-separated;
    /// an NMT command's target is not one); the summary counts every frame.
    #[arg(long, value_delimiter = ',', value_name = "NODE[,NODE]", value_parser = parse_node)]
    pub node: Vec<NodeId>,
    /// Keep only frames with these CAN identifiers: values or ranges
    /// `FROM-TO`, comma-separated, decimal or `0x` hex (e.g.
    /// `--id 0x081-0x0FF,0x705`); the summary counts every frame.
    #[arg(long, value_delimiter = ',', value_name = "ID[-ID][,…]", value_parser = parse_id_range)]
    pub id: Vec<IdRange>,
    /// Log files to read; none, or `-`, reads standard input.
    #[arg(value_name = "FILE")]
    pub files: Vec<PathBuf>,
}

/// How the logs are read and their nodes described: the options that
/// `decode` and `report` share (docs/output.md#command, docs/report.md#command).
#[derive(Debug, Clone, Args)]
pub struct ReadingArgs {
    /// Read the input as this format instead of detecting it from the
    /// content (docs/formats.md#detection).
    #[arg(long, value_name = "FORMAT", value_parser = parse_format, help = format_help())]
    pub format: Option<LogFormat>,
    /// What candump's relative timestamps `(000.000123)` count: `delta`
    /// (`candump -t d`) or `zero` (`-t z`); detected from the first 64
    /// frames when not given (docs/formats.md#candump-relative-times).
    #[arg(long, value_name = "delta|zero")]
    pub timestamps: Option<TimestampBase>,
    /// How to read the manufacturer-specific bytes of EMCY frames:
    /// `generic`, `akd` or `baumer` for every node, or per node as
    /// `NODE=PROFILE` (e.g. `--profile 3=akd,5=baumer`); a bare profile sets
    /// the default for the nodes not named.
    #[arg(
        long,
        value_name = "PROFILE|NODE=PROFILE",
        value_delimiter = ',',
        value_parser = parse_profile_choice,
    )]
    pub profile: Vec<ProfileChoice>,
    /// The EDS or DCF file that describes a node, as `NODE=FILE` (repeat
    /// for several nodes): its PDO mappings, object names and data types
    /// decode that node's PDOs until the log's own SDO configuration
    /// changes them (docs/canopen.md#pdo-mappings).
    #[arg(long, value_name = "NODE=FILE", value_parser = parse_eds_choice)]
    pub eds: Vec<(NodeId, PathBuf)>,
    /// EtherCAT: read these slaves' process data as the servo frames of
    /// docs/servo.md — `auto` (every slave with 10 output and 40 input
    /// bytes) or a station address (decimal or `0x` hex) with `:MODE`, its
    /// Servo_Ready_Mode 0 or 1; comma-separated (docs/ethercat.md#servo).
    #[arg(long, value_delimiter = ',', value_name = "auto|STATION[:MODE]", value_parser = parse_servo)]
    pub servo: Vec<ServoItem>,
    /// EtherCAT: the master's network information file (ENI, ETG.2100
    /// XML; TwinCAT exports it): the slaves' FMMUs, sync managers and PDOs
    /// for a capture that starts after the start-up; what the capture's
    /// start-up writes wins (docs/ethercat.md#eni).
    #[arg(long, value_name = "FILE")]
    pub eni: Option<PathBuf>,
    /// Keep only what was logged at this time or later: seconds from the
    /// recording's first time (`12.5`) or a UTC time
    /// (`2023-11-14T22:13:20Z`); the summary and the page are those of the
    /// frames kept (docs/output.md#window).
    #[arg(long, value_name = "SECONDS|UTC", value_parser = parse_time_bound)]
    pub from: Option<TimeBound>,
    /// Keep only what was logged before this time: seconds from the
    /// recording's first time or a UTC time, as --from.
    #[arg(long, value_name = "SECONDS|UTC", value_parser = parse_time_bound)]
    pub to: Option<TimeBound>,
    /// Keep only what was logged on these interfaces: names (`can0`) or
    /// channel numbers (`1`), comma-separated or repeated; the summary and
    /// the page are those of the frames kept (docs/output.md#window).
    #[arg(long, value_delimiter = ',', value_name = "NAME[,NAME]")]
    pub iface: Vec<String>,
    /// Say every malformed line and damaged record on standard error; without
    /// it, the first 100 of each file are said one by one and the rest
    /// counted in one line (docs/output.md#stderr).
    #[arg(long)]
    pub verbose: bool,
}

impl ReadingArgs {
    /// The library's filter of `--from`, `--to` and `--iface`.
    pub fn event_filter(&self) -> EventFilter {
        let mut filter = EventFilter::new();
        if let Some(from) = self.from {
            filter = filter.from(from);
        }
        if let Some(to) = self.to {
            filter = filter.to(to);
        }
        for name in &self.iface {
            filter = filter.iface(name.as_str());
        }
        filter
    }
}

fn parse_time_bound(text: &str) -> Result<TimeBound, String> {
    text.parse().map_err(|e: TimeBoundError| e.to_string())
}

/// Parse one `--servo` item: `auto`, `STATION` or `STATION:MODE` (the
/// library's [`ServoItem`]).
fn parse_servo(text: &str) -> Result<ServoItem, String> {
    text.parse().map_err(|e: ServoItemError| e.to_string())
}

/// One `--profile` item: for every node, or for one node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileChoice {
    /// The profile of every node not named otherwise.
    Default(Profile),
    /// The profile of one node.
    Node(NodeId, Profile),
}

fn parse_profile_choice(text: &str) -> Result<ProfileChoice, String> {
    let profile = |name: &str| {
        Profile::from_name(name).ok_or_else(|| {
            let names: Vec<_> = Profile::ALL.iter().map(|p| p.name()).collect();
            format!("{name:?} is not a profile; one of {}", names.join(", "))
        })
    };
    match text.split_once('=') {
        None => profile(text).map(ProfileChoice::Default),
        Some((node, name)) => {
            let raw: u8 = node
                .parse()
                .map_err(|_| format!("{node:?} is not a node-ID (1..=127)"))?;
            let node = NodeId::try_new(raw).map_err(|e| e.to_string())?;
            Ok(ProfileChoice::Node(node, profile(name)?))
        }
    }
}

/// Each node's profile from the `--profile` items: a bare profile is the
/// default for the nodes not named (the last one wins), `NODE=PROFILE`
/// names one node (later items win).
pub fn node_profiles(choices: &[ProfileChoice]) -> NodeProfiles {
    let default = choices
        .iter()
        .rev()
        .find_map(|c| match c {
            ProfileChoice::Default(p) => Some(*p),
            ProfileChoice::Node(..) => None,
        })
        .unwrap_or_default();
    let mut profiles = NodeProfiles::new(default);
    for choice in choices {
        if let ProfileChoice::Node(node, profile) = choice {
            profiles.set(*node, *profile);
        }
    }
    profiles
}

fn parse_eds_choice(text: &str) -> Result<(NodeId, PathBuf), String> {
    let (node, path) = text
        .split_once('=')
        .ok_or_else(|| format!("{text:?} is not NODE=FILE"))?;
    let raw: u8 = node
        .parse()
        .map_err(|_| format!("{node:?} is not a node-ID (1..=127)"))?;
    let node = NodeId::try_new(raw).map_err(|e| e.to_string())?;
    Ok((node, PathBuf::from(path)))
}

/// The frames `motionwire servo` decodes.
#[derive(Debug, Subcommand)]
pub enum ServoCommand {
    /// Decode a 10-byte NC → servo command frame (20 hex digits).
    Command(ServoArgs),
    /// Decode a 40-byte servo → NC feedback frame (80 hex digits).
    Feedback(ServoArgs),
}

/// The arguments of `motionwire servo command|feedback`.
#[derive(Debug, Args)]
pub struct ServoArgs {
    /// Write one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// The frame as hex digits; spaces are allowed (quote them, or pass the
    /// groups as several arguments).
    #[arg(value_name = "HEX", required = true, num_args = 1..)]
    pub hex: Vec<String>,
}

/// What `(000.000123)` timestamps count (docs/formats.md#candump-relative-times).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TimestampBase {
    /// `candump -t d`: the time since the previous frame.
    Delta,
    /// `candump -t z`: the time since the first frame.
    Zero,
}

/// An inclusive range of CAN identifiers (`--id`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IdRange {
    pub from: u32,
    pub to: u32,
}

impl IdRange {
    pub fn contains(&self, id: u32) -> bool {
        (self.from..=self.to).contains(&id)
    }
}

fn parse_number(text: &str) -> Result<u32, String> {
    let text = text.trim();
    let parsed = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => u32::from_str_radix(hex, 16),
        None => text.parse(),
    };
    match parsed {
        Ok(id) if id <= 0x1FFF_FFFF => Ok(id),
        Ok(id) => Err(format!(
            "{id:#X} is above the largest CAN identifier 0x1FFFFFFF"
        )),
        Err(_) => Err(format!(
            "{text:?} is not a CAN identifier (decimal, or hex with 0x)"
        )),
    }
}

fn parse_id_range(text: &str) -> Result<IdRange, String> {
    let (from, to) = match text.split_once('-') {
        Some((from, to)) => (parse_number(from)?, parse_number(to)?),
        None => {
            let id = parse_number(text)?;
            (id, id)
        }
    };
    if from > to {
        return Err(format!("{text:?}: the range ends before it starts"));
    }
    Ok(IdRange { from, to })
}

fn parse_node(text: &str) -> Result<NodeId, String> {
    let raw: u8 = text
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a node-ID (1..=127)"))?;
    NodeId::try_new(raw).map_err(|e| e.to_string())
}

/// `--format`'s help, with the format names.
fn format_help() -> String {
    let names: Vec<_> = LogFormat::ALL.iter().map(|f| f.name()).collect();
    format!(
        "Read the input as this format instead of detecting it from the content: {}",
        names.join(", ")
    )
}

/// `--only`'s help, with the kind names.
fn kind_help() -> String {
    format!(
        "Keep only frames and records of these kinds (comma-separated) in the per-frame output: \
         {}; the summary always counts every frame",
        kind_names().join(", ")
    )
}

fn parse_format(text: &str) -> Result<LogFormat, String> {
    LogFormat::from_name(text).ok_or_else(|| {
        let names: Vec<_> = LogFormat::ALL.iter().map(|f| f.name()).collect();
        format!("{text:?} is not a log format; one of {}", names.join(", "))
    })
}

/// A kind of record `--only` keeps: a CAN frame's, or an EtherCAT record's
/// (docs/ethercat.md#filters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A CAN frame's kind.
    Can(MessageKind),
    /// An EtherCAT record's kind, one of `ethercat::RECORD_KINDS`.
    Ethercat(&'static str),
}

/// Every kind's name, CAN's then EtherCAT's.
fn kind_names() -> Vec<&'static str> {
    MessageKind::ALL
        .iter()
        .map(|k| k.name())
        .chain(motionwire::decoder::ethercat::RECORD_KINDS)
        .collect()
}

fn parse_kind(text: &str) -> Result<Kind, String> {
    if let Some(kind) = MessageKind::from_name(text) {
        return Ok(Kind::Can(kind));
    }
    motionwire::decoder::ethercat::RECORD_KINDS
        .iter()
        .find(|k| **k == text)
        .map(|k| Kind::Ethercat(k))
        .ok_or_else(|| format!("{text:?} is not a kind; one of {}", kind_names().join(", ")))
}

fn parse_station(text: &str) -> Result<u16, String> {
    let parsed = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => u16::from_str_radix(hex, 16),
        None => text.parse(),
    };
    parsed.map_err(|_| format!("{text:?} is not a station address (0 to 65535, decimal or 0x hex)"))
}
