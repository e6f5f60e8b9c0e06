//! What went wrong, one [`Finding`] per fact (docs/summary.md#findings):
//! the summary's faults, first errors and warnings, restarts, heartbeat
//! timeouts, SDO aborts, broken and unanswered transfers, toggle errors and
//! bus errors, each with its [`Severity`] (docs/summary.md#severity).
//! `Summary::findings` lists them in time order; the report's "What went
//! wrong" and the Python package's `findings` are that list.

use core::fmt;

use crate::can::{BusName, Timestamp};
use crate::canopen::NodeId;
use crate::decoder::Device;
use crate::profiles::Profile;

use super::listed::ListedLines;
use super::values::{Iface, Ts};
use super::{
    AlChange, BusErrorSeen, Cia402Fault, EmcySeen, HeartbeatGap, Listed, SdoAbort, ServoEvent,
    Severity,
};
use crate::decoder::ethercat::SlaveRef;

/// What a [`Finding`] is about: the summary list it comes from
/// (docs/summary.md#findings).
///
/// `#[non_exhaustive]`: later kinds of trouble add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum FindingKind {
    /// A device's first error EMCY (`first_error`, docs/summary.md#emcy),
    /// or, when that one is a warning, its first EMCY that reports an error
    /// (docs/summary.md#severity).
    FirstError,
    /// A device's first error EMCY when it is a warning (`first_error`,
    /// docs/summary.md#severity): the EMCY reports no error present, or
    /// the device's profile calls it a warning.
    FirstWarning,
    /// A drive entering a CiA 402 fault state (`cia402.faults`).
    Cia402Fault,
    /// A device that booted more than once (`heartbeat.boot_ups`).
    Restarts,
    /// A heartbeat gap longer than the consumer time (`heartbeat.timeouts`).
    HeartbeatTimeout,
    /// An SDO abort (`sdo.aborts`).
    SdoAbort,
    /// A broken SDO transfer (`sdo.broken`).
    SdoBroken,
    /// An SDO request no response answered (`sdo.timeouts`).
    SdoTimeout,
    /// A node-guarding answer with a wrong toggle (`guarding.toggle_errors`).
    ToggleError,
    /// An error frame that says bus-off (the bus record's `bus_off`).
    BusOff,
    /// An error frame that says error-passive (`error_passive`).
    ErrorPassive,
    /// An EtherCAT slave reporting an AL state with its error indicator
    /// (a slave's `al_timeline`, docs/ethercat.md#summary).
    AlError,
    /// A fault of a servo's error word (the slave's `servo.events`,
    /// docs/ethercat.md#servo): the drive drops its enable.
    ServoFault,
}

impl FindingKind {
    /// Every kind, in the order a device's findings are listed before
    /// they are sorted by time (docs/summary.md#findings).
    pub const ALL: [FindingKind; 13] = [
        FindingKind::FirstError,
        FindingKind::FirstWarning,
        FindingKind::Cia402Fault,
        FindingKind::Restarts,
        FindingKind::HeartbeatTimeout,
        FindingKind::SdoAbort,
        FindingKind::SdoBroken,
        FindingKind::SdoTimeout,
        FindingKind::ToggleError,
        FindingKind::BusOff,
        FindingKind::ErrorPassive,
        FindingKind::AlError,
        FindingKind::ServoFault,
    ];

    /// Return the kind's name, as JSON and the Python package write it
    /// (docs/summary.md#findings).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            FindingKind::FirstError => "first_error",
            FindingKind::FirstWarning => "first_warning",
            FindingKind::Cia402Fault => "cia402_fault",
            FindingKind::Restarts => "restarts",
            FindingKind::HeartbeatTimeout => "heartbeat_timeout",
            FindingKind::SdoAbort => "sdo_abort",
            FindingKind::SdoBroken => "sdo_broken",
            FindingKind::SdoTimeout => "sdo_timeout",
            FindingKind::ToggleError => "toggle_error",
            FindingKind::BusOff => "bus_off",
            FindingKind::ErrorPassive => "error_passive",
            FindingKind::AlError => "al_error",
            FindingKind::ServoFault => "servo_fault",
        }
    }

    /// Return the kind in words, as a finding that stands for omitted
    /// ones names it (`… and 5 more (SDO abort)`).
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            FindingKind::FirstError => "first error",
            FindingKind::FirstWarning => "first warning",
            FindingKind::Cia402Fault => "CiA 402 fault",
            FindingKind::Restarts => "restart",
            FindingKind::HeartbeatTimeout => "heartbeat timeout",
            FindingKind::SdoAbort => "SDO abort",
            FindingKind::SdoBroken => "broken SDO transfer",
            FindingKind::SdoTimeout => "unanswered SDO request",
            FindingKind::ToggleError => "guarding toggle error",
            FindingKind::BusOff => "bus-off",
            FindingKind::ErrorPassive => "error-passive",
            FindingKind::AlError => "AL error",
            FindingKind::ServoFault => "servo fault",
        }
    }
}

impl fmt::Display for FindingKind {
    /// The kind's [`name`](Self::name).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What the summary says of a [`Finding`]: the value of its list it
/// stands for, or how many of the list it omitted there.
///
/// `#[non_exhaustive]`: later findings add variants.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum FindingDetail {
    /// The first error EMCY ([`FindingKind::FirstError`],
    /// [`FindingKind::FirstWarning`]).
    Emcy(EmcySeen),
    /// The fault ([`FindingKind::Cia402Fault`]).
    Cia402Fault(Cia402Fault),
    /// The device's boot-ups ([`FindingKind::Restarts`]): it restarted
    /// one time fewer than it booted.
    BootUps(Listed<u64>),
    /// The gap ([`FindingKind::HeartbeatTimeout`]).
    HeartbeatGap(HeartbeatGap),
    /// The abort ([`FindingKind::SdoAbort`]).
    SdoAbort(SdoAbort),
    /// The event at the finding's line, which the summary lists by its
    /// line alone (a broken or unanswered transfer, a toggle error, a
    /// bus-off or error-passive frame).
    Line,
    /// The AL status with its error indicator ([`FindingKind::AlError`]).
    AlError(AlChange),
    /// The fault set in the servo's error word
    /// ([`FindingKind::ServoFault`]).
    ServoFault(ServoEvent),
    /// The entries the summary list omitted after the finding's line, the
    /// last it kept before them: how many (docs/summary.md#lists).
    Omitted(u64),
}

/// What the log supports as the cause of a [`Finding`]
/// (docs/summary.md#causes).
///
/// `#[non_exhaustive]`: later links add variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum FindingCause {
    /// The drive's EMCY that caused its CiA 402 fault
    /// ([`Cia402Fault::cause`]).
    Emcy(EmcySeen),
    /// The bus-off or error-passive frame before a heartbeat timeout on
    /// the same bus ([`HeartbeatGap::cause`]).
    BusError(BusErrorSeen),
    /// Another node's heartbeat timeout before an EMCY 0x8130 "Life guard
    /// error or heartbeat error" ([`Summary::lost_before`](super::Summary::lost_before)).
    HeartbeatTimeout {
        /// The node that was lost.
        node: NodeId,
        /// Its gap.
        gap: HeartbeatGap,
    },
}

/// One thing that went wrong (docs/summary.md#findings): where, when, what
/// kind, and what the summary says of it.
///
/// `Display` writes the sentence a person reads, the device or bus first:
/// `can0 node 3 first error: EMCY 0x7305 Incremental sensor 1 fault at
/// line 613`. With `serde`, `Serialize` writes `{"file"?, "iface", "node",
/// "line", "ts", "kind", "severity", "text"}` ([`text`](Self::text) for
/// `text`).
///
/// `#[non_exhaustive]`: later fields are added.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct Finding {
    /// The file the summary is of, when it names one ([`Summary::file`](super::Summary::file)).
    pub file: Option<String>,
    /// The bus.
    pub bus: BusName,
    /// The device; `None` for a bus's findings (bus-off, error-passive)
    /// and an EtherCAT slave's.
    pub node: Option<NodeId>,
    /// The EtherCAT slave, for a slave's findings (docs/ethercat.md#findings).
    pub slave: Option<SlaveRef>,
    /// The line the finding is at: the EMCY's, the transition's, the
    /// abort's, the second boot-up's for a restart, the heartbeat's before
    /// a gap, a transfer's start; for omitted entries, the last entry the
    /// list kept before them.
    pub line: u64,
    /// The time of that line: the summary's own where it keeps one (an
    /// EMCY's, a CiA 402 transition's), else what the caller of
    /// [`Summary::findings_with`](super::Summary::findings_with) gives; `None` where neither knows.
    pub timestamp: Option<Timestamp>,
    /// What kind of trouble.
    pub kind: FindingKind,
    /// How bad it is ([`Severity::of_finding`], docs/summary.md#severity).
    pub severity: Severity,
    /// What the summary says of it.
    pub detail: FindingDetail,
    /// The device's profile (`--profile`): what its EMCYs' manufacturer
    /// bytes say in the text ([`ProfileReading`](super::ProfileReading),
    /// docs/summary.md#profiles); [`Profile::Generic`] for a bus.
    pub profile: Profile,
    /// What the log supports as its cause (docs/summary.md#causes).
    pub cause: Option<FindingCause>,
}

impl Finding {
    /// Return what the finding says without its device: `first error:
    /// EMCY 0x7305 Incremental sensor 1 fault at line 613`, with what the
    /// device's profile reads in an EMCY (`… fault on axis 1, feedback 1
    /// at line 613`; docs/summary.md#findings).
    #[must_use]
    pub fn text(&self) -> String {
        Text(self).to_string()
    }

    /// Return what the finding is about, as [`Display`](fmt::Display)
    /// starts: `FILE: ` where the summary names one, then the device
    /// (`can0 node 3`, `node 3` on an unnamed bus) or the bus (`bus can0`).
    #[must_use]
    pub fn subject(&self) -> String {
        Subject(self).to_string()
    }

    /// Return whether the finding stands for entries a summary list
    /// omitted ([`FindingDetail::Omitted`]).
    #[must_use]
    pub fn is_omitted(&self) -> bool {
        matches!(self.detail, FindingDetail::Omitted(_))
    }

    /// Return whether the finding is one that stops the recording, which
    /// the [verdict](super::Verdict) looks for (docs/summary.md#verdict):
    /// a CiA 402 fault, a heartbeat timeout, a bus-off, an EtherCAT AL
    /// error or a servo fault, not one standing for omitted entries.
    #[must_use]
    pub fn stops(&self) -> bool {
        !self.is_omitted()
            && matches!(
                self.kind,
                FindingKind::Cia402Fault
                    | FindingKind::HeartbeatTimeout
                    | FindingKind::BusOff
                    | FindingKind::AlError
                    | FindingKind::ServoFault
            )
    }

    /// Return whether the summary itself keeps the finding's time: its
    /// `ts` is the EMCY's or the transition's, not a caller's.
    #[must_use]
    pub fn timed_by_summary(&self) -> bool {
        matches!(
            self.detail,
            FindingDetail::Emcy(_)
                | FindingDetail::Cia402Fault(_)
                | FindingDetail::AlError(_)
                | FindingDetail::ServoFault(_)
        )
    }
}

/// A finding's text without its device.
struct Text<'a>(&'a Finding);

impl fmt::Display for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let finding = self.0;
        let line = finding.line;
        // A capture's findings are at packets, a log's at lines.
        let unit = if finding.slave.is_some() {
            "packet"
        } else {
            "line"
        };
        match &finding.detail {
            FindingDetail::Emcy(first) => {
                write!(
                    f,
                    "{}: EMCY {} {}{} at {unit} {}",
                    finding.kind.words(),
                    first.code,
                    first.code.description(),
                    first.reading(finding.profile),
                    first.line
                )?;
                if let Some(FindingCause::HeartbeatTimeout { node, gap }) = finding.cause {
                    write!(
                        f,
                        ", caused by node {}'s heartbeat timeout after line {}",
                        node.get(),
                        gap.after_line
                    )?;
                }
                Ok(())
            }
            FindingDetail::Cia402Fault(fault) => {
                write!(f, "{}", fault.sentence_in(finding.profile, unit))
            }
            FindingDetail::BootUps(boots) => {
                let times = boots.count().saturating_sub(1);
                write!(
                    f,
                    "restarted {times} time{} (boot-ups at lines {})",
                    if times == 1 { "" } else { "s" },
                    ListedLines(boots)
                )
            }
            FindingDetail::HeartbeatGap(gap) => {
                write!(
                    f,
                    "no heartbeat for {} ms after line {}",
                    gap.gap_ms(),
                    gap.after_line
                )?;
                if let Some(cause) = gap.cause {
                    write!(f, ", caused by {cause}")?;
                }
                Ok(())
            }
            FindingDetail::SdoAbort(abort) => write!(f, "line {}: {abort}", abort.line),
            FindingDetail::AlError(change) => {
                match change.status.state() {
                    Some(state) => write!(f, "{state} with error")?,
                    None => write!(f, "AL states {:#04x} with error", change.status.state_bits())?,
                }
                match change.code {
                    Some(code) => write!(f, " {code}")?,
                    None => f.write_str(", code not read")?,
                }
                write!(f, " at packet {line}")
            }
            FindingDetail::ServoFault(event) => write!(f, "{} at packet {line}", event.change),
            FindingDetail::Line => match finding.kind {
                FindingKind::SdoBroken => {
                    write!(f, "broken SDO transfer starting at line {line}")
                }
                FindingKind::SdoTimeout => write!(f, "unanswered SDO request at line {line}"),
                FindingKind::ToggleError => {
                    write!(f, "node-guarding answer with a wrong toggle at line {line}")
                }
                kind => write!(f, "{} at line {line}", kind.words()),
            },
            FindingDetail::Omitted(n) => write!(
                f,
                "… and {n} more ({}) after line {line}: the summary lists the first {} and the last {} of each kind",
                finding.kind.words(),
                Listed::<u64>::FIRST,
                Listed::<u64>::LAST
            ),
        }
    }
}

/// A finding's device or bus, with its file.
struct Subject<'a>(&'a Finding);

impl fmt::Display for Subject<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let finding = self.0;
        if let Some(file) = &finding.file {
            write!(f, "{file}: ")?;
        }
        match (finding.node, finding.slave) {
            (Some(node), _) => write!(f, "{}", Device::new(&finding.bus, node)),
            (None, Some(slave)) => write!(f, "{} {slave}", finding.bus),
            (None, None) => write!(f, "bus {}", finding.bus),
        }
    }
}

impl fmt::Display for Finding {
    /// The [`subject`](Self::subject), then the [`text`](Self::text).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", Subject(self), Text(self))
    }
}

impl serde::Serialize for Finding {
    /// `{"file"?, "iface", "node", "slave", "line", "ts", "kind", "severity", "text"}`: `file`
    /// only when the summary names one, `iface` as in every record
    /// (docs/output.md#common-keys), `ts` with the log's resolution.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        if let Some(file) = &self.file {
            map.serialize_entry("file", file)?;
        }
        map.serialize_entry("iface", &Iface(&self.bus))?;
        map.serialize_entry("node", &self.node.map(NodeId::get))?;
        map.serialize_entry("slave", &self.slave.and_then(|s| s.station))?;
        map.serialize_entry("line", &self.line)?;
        map.serialize_entry("ts", &self.timestamp.map(Ts))?;
        map.serialize_entry("kind", self.kind.name())?;
        map.serialize_entry("severity", self.severity.name())?;
        map.serialize_entry("text", &self.text())?;
        map.end()
    }
}

impl Severity {
    /// Return the severity of a finding of `kind` saying `detail`, of a
    /// node read with `profile` (docs/summary.md#severity).
    #[must_use]
    pub fn of_finding(kind: FindingKind, detail: &FindingDetail, profile: Profile) -> Severity {
        match (kind, detail) {
            (FindingKind::FirstError, FindingDetail::Emcy(seen)) => {
                Severity::of_emcy(&seen.emcy(), profile)
            }
            (FindingKind::FirstError, _) => Severity::Error,
            (FindingKind::FirstWarning, _) => Severity::Warning,
            (FindingKind::Cia402Fault | FindingKind::BusOff | FindingKind::ServoFault, _) => {
                Severity::Fault
            }
            (FindingKind::AlError, _) => Severity::Error,
            (FindingKind::HeartbeatTimeout, _) => Severity::Error,
            (FindingKind::SdoAbort, _) => Severity::Notice,
            (
                FindingKind::Restarts
                | FindingKind::SdoBroken
                | FindingKind::SdoTimeout
                | FindingKind::ToggleError
                | FindingKind::ErrorPassive,
                _,
            ) => Severity::Warning,
        }
    }
}
