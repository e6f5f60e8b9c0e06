//! The post-mortem of a log: one record per device and per bus
//! (docs/summary.md), built with the crate's own state machines — the CiA 405
//! EMCY storage for the root cause (docs/canopen.md#recv-emcy), the heartbeat
//! consumer for timeouts and the node-guarding observer for toggle errors
//! (docs/canopen.md#error-control) — from what the [decoder](crate::decoder)
//! makes of each frame: SDO statistics (docs/summary.md#sdo) and each drive's
//! CiA 402 timeline (docs/summary.md#cia402).
//!
//! A [`Summarizer`] is fed every log entry, frames and bus events, in log
//! order; it reads the frames with its own [`Decoder`], so that the settings
//! of the session are one [`DecoderConfig`]. [`Summarizer::finish`] returns
//! the typed [`Summary`]. `Display` writes the text summary; with `serde`,
//! `Serialize` writes exactly the records of `motionwire decode --summary
//! --json` (one JSON value per record, [`Summary::records`]).
//! [`Summary::findings`] is what went wrong, one [`Finding`] per fault,
//! first error, restart, timeout, abort or bus error, in time order
//! (docs/summary.md#findings); [`SeveralFiles`] reads several logs as
//! recordings of their own or joined (docs/output.md#several-files).
//!
//! ```
//! use motionwire::can::LogEvent;
//! use motionwire::decoder::DecoderConfig;
//! use motionwire::logs::Position;
//! use motionwire::summary::Summarizer;
//!
//! let log = b"(1700000000.000000) can0 703#00\n\
//!             (1700000000.100000) can0 083#1081110000000000\n\
//!             (1700000000.200000) can0 703#05\n";
//! let mut summarizer = Summarizer::new(DecoderConfig::new().signals(false));
//! for (line, text) in log.split(|&b| b == b'\n').enumerate() {
//!     if let Ok(Some(frame)) = motionwire::logs::candump::parse_line(text) {
//!         summarizer.add(Position::Line(line as u64 + 1), &LogEvent::Frame(frame));
//!     }
//! }
//! let summary = summarizer.finish();
//! let node = &summary.nodes[0];
//! assert_eq!(node.node.get(), 3);
//! assert_eq!(node.heartbeat.boot_ups.head(), [1]);
//! assert_eq!(node.active_error.unwrap().code.get(), 0x8110);
//! assert!(summary.to_string().contains("active error: 0x8110 CAN overrun (objects lost) (line 2)"));
//! ```

mod causes;
mod cia402;
mod emcy;
mod ethercat;
mod ethercat_regs;
mod event;
mod file;
mod findings;
mod heartbeat;
mod json;
mod listed;
mod record;
mod sdo;
mod servo;
mod severity;
mod summarizer;
mod text;
mod values;
mod verdict;
mod wrong;

pub use causes::LOST_HEARTBEAT;
pub use cia402::{Cia402Fault, Cia402Timeline, Cia402Transition};
pub use emcy::{EmcySeen, ProfileReading};
pub use ethercat::{
    device_name, AlChange, CoeEmergency, CoeSdoAbort, CounterRise, DcSummary, DlChange,
    EthercatFact, EthercatSummary, PortSummary, SlaveRegisters, SlaveSummary, StreamSummary,
    MAX_AL_CHANGES, MAX_EMERGENCIES, MAX_STREAMS, STATUS_STREAM_MIN,
};
pub use event::{SummaryEvent, SummaryEventKind};
pub use file::{FileSpan, SeveralFiles};
pub use findings::{Finding, FindingCause, FindingDetail, FindingKind};
pub use heartbeat::{BusErrorSeen, GuardingSummary, HeartbeatGap, HeartbeatSummary, Timeouts};
pub use listed::{Listed, ListedIter};
pub use record::{BusSummary, FrameCounts, NodeSummary, Summary, SummaryItem, SummaryRecord};
pub use sdo::{LatencyStats, SdoAbort, SdoSummary};
pub use servo::{ServoChange, ServoEvent, ServoTimeline};
pub use severity::Severity;
pub use summarizer::Summarizer;
pub use verdict::{Verdict, CAUSE_WINDOW};

#[cfg(doc)]
use crate::decoder::{Decoder, DecoderConfig};

#[cfg(test)]
mod tests;
