//! `motionwire`: decode CANopen candump logs and EtherCAT servo frames.
//!
//! Built with the feature `cli`. The JSON output is a stable contract
//! (SPEC §6): names and meanings change only with a CHANGELOG entry.
//!
//! ```text
//! motionwire decode [--json] [--profile generic|akd|baumer|NODE=PROFILE,…] [--summary]
//!                   [--heartbeat-ms N] [--only KIND[,KIND]] [FILE…]
//! motionwire servo command  [--json] HEX
//! motionwire servo feedback [--json] HEX
//! ```

mod decode;
mod json;
mod servo;
mod summary;

use std::io::{self, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// Decode the diagnostic and cyclic-control messages of industrial motion
/// devices: CANopen candump logs and EtherCAT servo ↔ NC frames.
#[derive(Debug, Parser)]
#[command(name = "motionwire", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Decode candump text logs (can-utils, python-can) into one record per
    /// CAN frame (SPEC §6.1).
    Decode(DecodeArgs),
    /// Decode one EtherCAT servo ↔ NC frame given as hex (SPEC §6.2).
    #[command(subcommand)]
    Servo(ServoCommand),
}

/// The arguments of `motionwire decode`.
#[derive(Debug, Args)]
pub struct DecodeArgs {
    /// Write one JSON object per line instead of aligned text.
    #[arg(long)]
    pub json: bool,
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
    /// After the input, write one record per node seen instead of one per
    /// frame: frame counts, EMCYs with the root cause, heartbeats, guarding.
    #[arg(long)]
    pub summary: bool,
    /// With --summary: report heartbeat gaps longer than this many
    /// milliseconds as timeouts.
    #[arg(long, value_name = "MS", value_parser = clap::value_parser!(u16).range(1..))]
    pub heartbeat_ms: Option<u16>,
    /// Keep only frames of these kinds (comma-separated) in the per-frame
    /// output; the summary always counts every frame.
    #[arg(long, value_enum, value_delimiter = ',', value_name = "KIND[,KIND]")]
    pub only: Vec<decode::Kind>,
    /// candump files to read; none, or `-`, reads standard input.
    #[arg(value_name = "FILE")]
    pub files: Vec<PathBuf>,
}

/// How the manufacturer-specific EMCY bytes are read (SPEC §6.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Profile {
    /// CiA 301 only: the manufacturer field as raw hex.
    Generic,
    /// Kollmorgen AKD: axis and feedback ids (SPEC §2.4).
    Akd,
    /// Baumer EAM580: alarms, warnings and diagnostic sources (SPEC §4).
    Baumer,
}

/// One `--profile` item: for every node, or for one node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileChoice {
    /// The profile of every node not named otherwise.
    Default(Profile),
    /// The profile of one node.
    Node(motionwire::canopen::NodeId, Profile),
}

fn parse_profile_choice(text: &str) -> Result<ProfileChoice, String> {
    let profile = |name: &str| Profile::from_str(name, false);
    match text.split_once('=') {
        None => profile(text).map(ProfileChoice::Default),
        Some((node, name)) => {
            let raw: u8 = node
                .parse()
                .map_err(|_| format!("{node:?} is not a node-ID (1..=127)"))?;
            let node = motionwire::canopen::NodeId::try_new(raw).map_err(|e| e.to_string())?;
            Ok(ProfileChoice::Node(node, profile(name)?))
        }
    }
}

/// The profile of each node, from the `--profile` items.
#[derive(Debug, Clone)]
pub struct Profiles([Profile; 128]);

impl Profiles {
    /// Build the table; later items win over earlier ones.
    pub fn new(choices: &[ProfileChoice]) -> Self {
        let default = choices
            .iter()
            .rev()
            .find_map(|c| match c {
                ProfileChoice::Default(p) => Some(*p),
                ProfileChoice::Node(..) => None,
            })
            .unwrap_or(Profile::Generic);
        let mut table = [default; 128];
        for choice in choices {
            if let ProfileChoice::Node(node, profile) = choice {
                table[usize::from(node.get())] = *profile;
            }
        }
        Profiles(table)
    }

    /// The profile of `node` (the default for frames without a node).
    pub fn of(&self, node: Option<motionwire::canopen::NodeId>) -> Profile {
        self.0[node.map_or(0, |n| usize::from(n.get()))]
    }
}

#[derive(Debug, Subcommand)]
enum ServoCommand {
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Decode(args) => decode::run(&args),
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

/// Why a command could not do its job (exit status 2).
#[derive(Debug)]
pub enum Failure {
    /// Bad input given on the command line (e.g. bad hex).
    Usage(String),
    /// A file that cannot be read.
    File(PathBuf, io::Error),
    /// Writing the output failed.
    Io(io::Error),
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Usage(msg) => f.write_str(msg),
            Failure::File(path, e) => write!(f, "{}: {e}", path.display()),
            Failure::Io(e) => write!(f, "writing the output: {e}"),
        }
    }
}

impl From<io::Error> for Failure {
    fn from(e: io::Error) -> Self {
        Failure::Io(e)
    }
}
