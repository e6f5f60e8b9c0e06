//! The verdict of a post-mortem (docs/summary.md#verdict): how bad each
//! finding is ([`Severity`]), the causal link the log supports between a
//! drive's EMCY and its CiA 402 fault ([`CAUSE_WINDOW`]), and on top of the
//! list the stop and its first cause ([`Verdict`]).

use core::fmt;
use core::time::Duration;

use crate::can::Timestamp;
use crate::canopen::Emcy;
use crate::profiles::akd::AkdManufacturerField;
use crate::profiles::baumer::BaumerEmcy;
use crate::profiles::Profile;

use super::json::Iface;
use super::{Cia402Fault, EmcySeen, Finding, FindingDetail, FindingKind, NodeSummary, Summary};

/// How bad a finding is (docs/summary.md#severity), the worst first:
/// `Fault < Error < Warning < Notice`.
///
/// ```
/// use motionwire::canopen::{Emcy, ErrorCode, ErrorRegister};
/// use motionwire::profiles::Profile;
/// use motionwire::summary::Severity;
///
/// let battery = Emcy::new(ErrorCode::new(0xFF00), ErrorRegister::empty(), [0, 0, 0x10, 0, 0]);
/// assert_eq!(Severity::of_emcy(&battery, Profile::Baumer), Severity::Warning);
/// let sensor = Emcy::new(ErrorCode::new(0x7305), ErrorRegister::GENERIC, [0x21, 0, 0, 0, 0]);
/// assert_eq!(Severity::of_emcy(&sensor, Profile::Akd), Severity::Error);
/// assert!(Severity::Fault < Severity::Error);
/// assert_eq!(Severity::Warning.to_string(), "warning");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// A device stopped doing its job: a CiA 402 drive entered a fault
    /// state (CiA 402), a controller went bus-off (ISO 11898-1).
    Fault,
    /// A device reports an error (an EMCY whose error register is set,
    /// CiA 301), or was lost (a heartbeat timeout, CiA 301's heartbeat
    /// event).
    Error,
    /// Something went wrong and did not stop anything: an EMCY that reports
    /// no error present, or that the device's profile calls a warning; a
    /// restart; a guarding toggle error; a broken or unanswered SDO
    /// transfer; error-passive.
    Warning,
    /// Worth knowing: an SDO abort (a server refusing a request is part of
    /// the protocol).
    Notice,
}

impl Severity {
    /// Return the name JSON writes: `fault`, `error`, `warning`, `notice`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Severity::Fault => "fault",
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Notice => "notice",
        }
    }

    /// Return whether it is a fault or an error: what a first cause can be.
    #[must_use]
    pub const fn is_fault_or_error(self) -> bool {
        matches!(self, Severity::Fault | Severity::Error)
    }

    /// Return the severity of an EMCY of a node read with `profile`
    /// (docs/summary.md#severity): a reset is a notice; an EMCY the
    /// profile's own table calls a warning (a Baumer diagnostic source
    /// signalled in 6505h only, [`BaumerEmcy::is_warning`]) or that
    /// reports no error present (error register 0,
    /// [`Emcy::reports_no_error`]) is a warning; any other is an error.
    #[must_use]
    pub fn of_emcy(emcy: &Emcy, profile: Profile) -> Severity {
        if emcy.is_reset() {
            return Severity::Notice;
        }
        if profile == Profile::Baumer && BaumerEmcy::from_emcy(emcy).is_warning() {
            return Severity::Warning;
        }
        if emcy.reports_no_error() {
            return Severity::Warning;
        }
        Severity::Error
    }

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
            (FindingKind::Cia402Fault | FindingKind::BusOff, _) => Severity::Fault,
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

impl fmt::Display for Severity {
    /// The [`name`](Self::name).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl NodeSummary {
    /// Return the node's first EMCY when it is a warning
    /// ([`Severity::of_emcy`] with the node's profile;
    /// docs/summary.md#severity): its [`first_error`](Self::first_error),
    /// or `None` when that one is an error.
    #[must_use]
    pub fn first_warning(&self) -> Option<EmcySeen> {
        self.first_error
            .filter(|e| Severity::of_emcy(&e.emcy(), self.profile) == Severity::Warning)
    }

    /// Return the node's first EMCY that reports an error: its
    /// [`first_error`](Self::first_error), or, when that one is a warning,
    /// its first EMCY with the error register set
    /// ([`first_error_with_register`](Self::first_error_with_register))
    /// unless the profile calls that one a warning too
    /// (docs/summary.md#severity).
    #[must_use]
    pub fn first_error_reported(&self) -> Option<EmcySeen> {
        if self.first_warning().is_none() {
            return self.first_error;
        }
        self.first_error_with_register
            .filter(|e| Severity::of_emcy(&e.emcy(), self.profile) != Severity::Warning)
    }
}

/// How long before a drive's CiA 402 fault its EMCY may come to be its
/// cause (docs/summary.md#causes): one second. A drive sends the EMCY when
/// it detects the error and shows the fault in its statusword at the next
/// PDO, a few cycles later (15–17 ms on `samples/machine.log`); a second
/// leaves room for event-driven TPDOs with long inhibit times, and no more.
pub const CAUSE_WINDOW: Duration = Duration::from_secs(1);

impl Cia402Fault {
    /// Return the EMCY the log supports as the fault's cause
    /// (docs/summary.md#causes): the drive's last error EMCY at or before
    /// the fault, when both have a time and it came at most
    /// [`CAUSE_WINDOW`] before; `None` otherwise (a log without times
    /// cannot tell).
    #[must_use]
    pub fn cause(&self) -> Option<EmcySeen> {
        let emcy = self.emcy_before?;
        let gap = self.transition.timestamp?.duration_since(emcy.timestamp?)?;
        (gap <= CAUSE_WINDOW).then_some(emcy)
    }
}

/// What stopped the machine, and where the trouble began
/// (docs/summary.md#verdict): the verdict on top of the findings.
///
/// - The **stop** is the last finding that stops a device: a drive's
///   transition into a CiA 402 fault state, a heartbeat timeout (the loss
///   of a device) or a bus-off, with what led to it (the EMCY that caused a
///   fault, [`Cia402Fault::cause`]).
/// - The **first cause** is the earliest fault or error finding the stop
///   traces back to: of the stop's device (of its bus, for a bus-off), at
///   or before the stop — the stop itself when nothing came before it.
///
/// `Display` writes it as the text summary's first lines; with `serde`,
/// the `{"type": "verdict", …}` record.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct Verdict {
    /// The stop.
    pub stop: Finding,
    /// What led to the stop: for a drive's fault, the EMCY that caused it.
    pub cause: Option<EmcySeen>,
    /// The stop device's profile: how [`cause`](Self::cause)'s
    /// manufacturer bytes read.
    pub profile: Profile,
    /// The first cause.
    pub first_cause: Finding,
    /// The recording's first time, from which the verdict counts its
    /// times (`+8.820 s`).
    pub start: Option<Timestamp>,
}

impl Verdict {
    /// Return the verdict on `summary`'s findings ([`Summary::findings`]),
    /// or `None` when nothing stopped: no fault, no heartbeat timeout, no
    /// bus-off.
    #[must_use]
    pub fn of(summary: &Summary) -> Option<Verdict> {
        let findings = summary.findings();
        let at = findings.iter().rposition(|f| {
            !f.is_omitted()
                && matches!(
                    f.kind,
                    FindingKind::Cia402Fault | FindingKind::HeartbeatTimeout | FindingKind::BusOff
                )
        })?;
        let stop = &findings[at];
        let first_cause = findings[..=at]
            .iter()
            .find(|f| {
                !f.is_omitted()
                    && f.severity.is_fault_or_error()
                    && f.bus == stop.bus
                    && (stop.node.is_none() || f.node == stop.node)
            })
            .unwrap_or(stop);
        let cause = match &stop.detail {
            FindingDetail::Cia402Fault(fault) => fault.cause(),
            _ => None,
        };
        let profile = stop
            .node
            .and_then(|node| summary.node(&stop.bus, node))
            .map_or(Profile::Generic, |n: &NodeSummary| n.profile);
        let start = summary.buses.iter().filter_map(|b| b.first_timestamp).min();
        Some(Verdict {
            stop: stop.clone(),
            cause,
            profile,
            first_cause: first_cause.clone(),
            start,
        })
    }

    /// Return the stop in one sentence, its device first: `can0 node 3
    /// went operation_enabled → fault at line 3239 (+8.820 s), 16.1 ms
    /// after EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2
    /// (line 3231)`.
    #[must_use]
    pub fn stop_text(&self) -> String {
        StopText(self).to_string()
    }

    /// Return the first cause in one sentence, its device first: `can0
    /// node 3 first error: EMCY 0x7305 Incremental sensor 1 fault at line
    /// 613 (+2.003 s)`; `the stop itself: no fault or error before it on
    /// its device` when it is the stop.
    #[must_use]
    pub fn first_cause_text(&self) -> String {
        if self.first_cause == self.stop {
            return "the stop itself: no fault or error before it on its device".to_owned();
        }
        format!(
            "{}{}",
            self.first_cause,
            Since(self.first_cause.timestamp, self.start)
        )
    }
}

/// ` (+8.820 s)`: a time counted from the recording's first; nothing
/// without both.
struct Since(Option<Timestamp>, Option<Timestamp>);

impl fmt::Display for Since {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.0, self.1) {
            (Some(at), Some(start)) => match at.duration_since(start) {
                Some(d) => write!(f, " (+{:.3} s)", d.as_secs_f64()),
                None => Ok(()),
            },
            _ => Ok(()),
        }
    }
}

/// What a node's profile adds to an EMCY in a sentence: ` on axis 1,
/// feedback 2` (AKD, docs/canopen.md#akd), ` (battery monitoring warning)`
/// (Baumer's diagnostic sources, docs/canopen.md#baumer); nothing for a
/// generic node.
struct ProfileWords<'a>(&'a EmcySeen, Profile);

impl fmt::Display for ProfileWords<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ProfileWords(seen, profile) = *self;
        match profile {
            Profile::Generic => Ok(()),
            Profile::Akd => {
                let field = AkdManufacturerField::new_unchecked(&seen.manufacturer[..]);
                let axis = field.axis_id();
                let feedback = field.feedback_id().ok().and_then(|fb| fb.number());
                match (axis.is_given(), feedback) {
                    (true, Some(fb)) => write!(f, " on axis {}, feedback {fb}", axis.get()),
                    (false, Some(fb)) => write!(f, " on feedback {fb}"),
                    (true, None) => write!(f, " on axis {}", axis.get()),
                    (false, None) => Ok(()),
                }
            }
            Profile::Baumer => {
                let emcy = BaumerEmcy::from_emcy(&seen.emcy());
                let mut names: Vec<&str> = emcy.sources().map(|s| s.source()).collect();
                names.dedup();
                if names.is_empty() {
                    return Ok(());
                }
                write!(f, " ({})", names.join(", "))
            }
        }
    }
}

/// The stop's sentence ([`Verdict::stop_text`]).
struct StopText<'a>(&'a Verdict);

impl fmt::Display for StopText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let stop = &v.stop;
        let since = Since(stop.timestamp, v.start);
        match (&stop.detail, v.cause) {
            (FindingDetail::Cia402Fault(fault), Some(cause)) => {
                let t = fault.transition;
                write!(
                    f,
                    "{} went {} → {} at line {}{since}",
                    stop.subject(),
                    t.from.map_or("-", |s| s.name()),
                    t.to.name(),
                    t.line
                )?;
                let gap = t
                    .timestamp
                    .zip(cause.timestamp)
                    .and_then(|(at, then)| at.duration_since(then))
                    .unwrap_or_default();
                write!(
                    f,
                    ", {:.1} ms after EMCY {} {}{} (line {})",
                    gap.as_secs_f64() * 1000.0,
                    cause.code,
                    cause.code.description(),
                    ProfileWords(&cause, v.profile),
                    cause.line
                )
            }
            (FindingDetail::Cia402Fault(fault), None) => {
                let t = fault.transition;
                write!(
                    f,
                    "{} went {} → {} at line {}{since}",
                    stop.subject(),
                    t.from.map_or("-", |s| s.name()),
                    t.to.name(),
                    t.line
                )
            }
            _ => write!(f, "{stop}{since}"),
        }
    }
}

impl fmt::Display for Verdict {
    /// Two lines: `verdict   stop: …` and `          first cause: …`
    /// (docs/summary.md#text).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "verdict   stop: {}", StopText(self))?;
        writeln!(f, "          first cause: {}", self.first_cause_text())
    }
}

/// A finding inside the verdict record: the finding's JSON without its
/// `file` (the record has it), with its severity.
struct FindingJson<'a>(&'a Finding, Option<Option<EmcySeen>>);

impl serde::Serialize for FindingJson<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let FindingJson(finding, cause) = self;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("iface", &Iface(&finding.bus))?;
        map.serialize_entry("node", &finding.node.map(|n| n.get()))?;
        map.serialize_entry("line", &finding.line)?;
        map.serialize_entry("ts", &finding.timestamp.map(super::json::Ts))?;
        map.serialize_entry("kind", finding.kind.name())?;
        map.serialize_entry("severity", finding.severity.name())?;
        map.serialize_entry("text", &finding.text())?;
        if let Some(cause) = cause {
            map.serialize_entry("cause", cause)?;
        }
        map.end()
    }
}

/// The entries of the verdict record (after its `file`): `type`, `stop`
/// with its `cause`, `first_cause`, `text`.
pub(super) fn verdict_entries<M: serde::ser::SerializeMap>(
    v: &Verdict,
    map: &mut M,
) -> Result<(), M::Error> {
    map.serialize_entry("type", "verdict")?;
    map.serialize_entry("stop", &FindingJson(&v.stop, Some(v.cause)))?;
    map.serialize_entry("first_cause", &FindingJson(&v.first_cause, None))?;
    map.serialize_entry(
        "text",
        &format!(
            "stop: {}; first cause: {}",
            v.stop_text(),
            v.first_cause_text()
        ),
    )
}
