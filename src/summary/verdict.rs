//! The verdict of a post-mortem (docs/summary.md#verdict): the causal link
//! the log supports between a drive's EMCY and its CiA 402 fault
//! ([`CAUSE_WINDOW`]), and on top of the findings the stop and its first
//! cause ([`Verdict`], made by [`Verdict::of`]).

use core::fmt;
use core::time::Duration;

use crate::can::Timestamp;
use crate::profiles::Profile;

use super::values::{Iface, Ts};
use super::{Cia402Fault, EmcySeen, Finding, FindingDetail};

/// How long before a drive's CiA 402 fault its EMCY may come to be its
/// cause (docs/summary.md#causes): one second. A drive sends the EMCY when
/// it detects the error and shows the fault in its statusword at the next
/// PDO, a few cycles later; a second
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
                // A capture numbers packets, a log lines.
                let unit = if stop.slave.is_some() {
                    "packet"
                } else {
                    "line"
                };
                write!(
                    f,
                    "{} went {} → {} at {unit} {}{since}",
                    stop.subject(),
                    t.from.map_or("-", |s| s.name()),
                    t.to.name(),
                    t.line
                )?;
                let what = format!(
                    "EMCY {} {}{}",
                    cause.code,
                    cause.code.description(),
                    cause.reading(v.profile)
                );
                match t.timestamp.zip(cause.timestamp) {
                    // A CoE emergency read after the fault: it waited in
                    // the slave's mailbox (docs/ethercat.md#findings).
                    Some((at, then)) if cause.line > t.line => {
                        let gap = then.duration_since(at).unwrap_or_default();
                        write!(
                            f,
                            ", with {what} read {:.1} ms later ({unit} {})",
                            gap.as_secs_f64() * 1000.0,
                            cause.line
                        )
                    }
                    Some((at, then)) => {
                        let gap = at.duration_since(then).unwrap_or_default();
                        write!(
                            f,
                            ", {:.1} ms after {what} ({unit} {})",
                            gap.as_secs_f64() * 1000.0,
                            cause.line
                        )
                    }
                    None => write!(f, ", after {what} ({unit} {})", cause.line),
                }
            }
            (FindingDetail::Cia402Fault(fault), None) => {
                let t = fault.transition;
                let unit = if stop.slave.is_some() {
                    "packet"
                } else {
                    "line"
                };
                write!(
                    f,
                    "{} went {} → {} at {unit} {}{since}",
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
        map.serialize_entry("slave", &finding.slave.and_then(|s| s.station))?;
        map.serialize_entry("line", &finding.line)?;
        map.serialize_entry("ts", &finding.timestamp.map(Ts))?;
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
