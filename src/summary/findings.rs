//! What went wrong, as a list (docs/summary.md#findings): the summary's
//! faults, first errors, restarts, heartbeat timeouts, SDO aborts, broken
//! and unanswered transfers, toggle errors and bus errors, one [`Finding`]
//! each, in time order. The report's "What went wrong" and the Python
//! package's `findings` are this list.

use core::fmt;

use crate::can::{BusName, Timestamp};
use crate::canopen::NodeId;
use crate::decoder::Device;

use super::json::{Iface, Ts};
use super::text::ListedLines;
use super::{Cia402Fault, EmcySeen, HeartbeatGap, Listed, SdoAbort, Severity, Summary, Timeouts};
use crate::profiles::Profile;

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
}

impl FindingKind {
    /// Every kind, in the order a device's findings are listed before
    /// they are sorted by time (docs/summary.md#findings).
    pub const ALL: [FindingKind; 11] = [
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
    /// The entries the summary list omitted after the finding's line, the
    /// last it kept before them: how many (docs/summary.md#lists).
    Omitted(u64),
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
    /// The file the summary is of, when it names one ([`Summary::file`]).
    pub file: Option<String>,
    /// The bus.
    pub bus: BusName,
    /// The device; `None` for a bus's findings (bus-off, error-passive).
    pub node: Option<NodeId>,
    /// The line the finding is at: the EMCY's, the transition's, the
    /// abort's, the second boot-up's for a restart, the heartbeat's before
    /// a gap, a transfer's start; for omitted entries, the last entry the
    /// list kept before them.
    pub line: u64,
    /// The time of that line: the summary's own where it keeps one (an
    /// EMCY's, a CiA 402 transition's), else what the caller of
    /// [`Summary::findings_with`] gives; `None` where neither knows.
    pub timestamp: Option<Timestamp>,
    /// What kind of trouble.
    pub kind: FindingKind,
    /// How bad it is ([`Severity::of_finding`], docs/summary.md#severity).
    pub severity: Severity,
    /// What the summary says of it.
    pub detail: FindingDetail,
}

impl Finding {
    /// Return what the finding says without its device: `first error:
    /// EMCY 0x7305 Incremental sensor 1 fault at line 613`
    /// (docs/summary.md#findings).
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

    /// Return whether the summary itself keeps the finding's time: its
    /// `ts` is the EMCY's or the transition's, not a caller's.
    #[must_use]
    pub fn timed_by_summary(&self) -> bool {
        matches!(
            self.detail,
            FindingDetail::Emcy(_) | FindingDetail::Cia402Fault(_)
        )
    }
}

/// A finding's text without its device.
struct Text<'a>(&'a Finding);

impl fmt::Display for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let finding = self.0;
        let line = finding.line;
        match &finding.detail {
            FindingDetail::Emcy(first) => write!(
                f,
                "{}: EMCY {} {} at line {}",
                finding.kind.words(),
                first.code,
                first.code.description(),
                first.line
            ),
            FindingDetail::Cia402Fault(fault) => write!(f, "{fault}"),
            FindingDetail::BootUps(boots) => {
                let times = boots.count().saturating_sub(1);
                write!(
                    f,
                    "restarted {times} time{} (boot-ups at lines {})",
                    if times == 1 { "" } else { "s" },
                    ListedLines(boots)
                )
            }
            FindingDetail::HeartbeatGap(gap) => write!(
                f,
                "no heartbeat for {} ms after line {}",
                gap.gap_ms(),
                gap.after_line
            ),
            FindingDetail::SdoAbort(abort) => write!(f, "line {}: {abort}", abort.line),
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
        match finding.node {
            Some(node) => write!(f, "{}", Device::new(&finding.bus, node)),
            None => write!(f, "bus {}", finding.bus),
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
    /// `{"file"?, "iface", "node", "line", "ts", "kind", "severity", "text"}`: `file`
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
        map.serialize_entry("line", &self.line)?;
        map.serialize_entry("ts", &self.timestamp.map(Ts))?;
        map.serialize_entry("kind", self.kind.name())?;
        map.serialize_entry("severity", self.severity.name())?;
        map.serialize_entry("text", &self.text())?;
        map.end()
    }
}

impl Summary {
    /// Return what went wrong (docs/summary.md#findings), with the times
    /// the summary keeps: an EMCY's and a CiA 402 transition's; every other
    /// finding's `ts` is `None` ([`findings_with`](Self::findings_with)
    /// gives them), so the list is in line order.
    ///
    /// ```
    /// use motionwire::can::LogEvent;
    /// use motionwire::decoder::DecoderConfig;
    /// use motionwire::logs::Position;
    /// use motionwire::summary::{FindingKind, Summarizer};
    ///
    /// let log = b"(1700000000.000000) can0 703#00\n\
    ///             (1700000000.100000) can0 083#1081110000000000\n\
    ///             (1700000000.200000) can0 703#00\n";
    /// let mut summarizer = Summarizer::new(DecoderConfig::new().signals(false));
    /// for (line, text) in log.split(|&b| b == b'\n').enumerate() {
    ///     if let Ok(Some(frame)) = motionwire::logs::candump::parse_line(text) {
    ///         summarizer.add(Position::Line(line as u64 + 1), &LogEvent::Frame(frame));
    ///     }
    /// }
    /// let summary = summarizer.finish();
    /// let findings = summary.findings();
    /// let kinds: Vec<_> = findings.iter().map(|f| f.kind).collect();
    /// assert_eq!(kinds, [FindingKind::FirstError, FindingKind::Restarts]);
    /// assert_eq!(
    ///     findings[0].to_string(),
    ///     "can0 node 3 first error: EMCY 0x8110 CAN overrun (objects lost) at line 2"
    /// );
    /// assert_eq!(findings[1].text(), "restarted 1 time (boot-ups at lines 1, 3)");
    /// assert_eq!(findings[1].line, 3);
    /// let json = serde_json::to_string(&findings[0])?;
    /// assert_eq!(
    ///     json,
    ///     r#"{"iface":"can0","node":3,"line":2,"ts":1700000000.100000,"kind":"first_error","severity":"error","text":"first error: EMCY 0x8110 CAN overrun (objects lost) at line 2"}"#
    /// );
    /// # Ok::<(), serde_json::Error>(())
    /// ```
    #[must_use]
    pub fn findings(&self) -> Vec<Finding> {
        self.findings_with(|_| None)
    }

    /// Return what went wrong, in time order, as
    /// [`findings`](Self::findings) does, with `time_of` giving the time
    /// of each finding whose time the summary does not keep (a boot-up's,
    /// an abort's, …): the report's timeline places them where its marks
    /// are (`report::Recording::findings`).
    ///
    /// The order: by time, then by line, when every finding has a time;
    /// else by line (a log without timestamps, a caller without times).
    /// Findings at the same place stay in the order of
    /// [`FindingKind::ALL`], devices before buses.
    #[must_use]
    pub fn findings_with(
        &self,
        mut time_of: impl FnMut(&Finding) -> Option<Timestamp>,
    ) -> Vec<Finding> {
        let mut list = Vec::new();
        for n in &self.nodes {
            let mut push = |kind, line, detail, ts| {
                list.push(Finding {
                    file: self.file.clone(),
                    bus: n.bus.clone(),
                    node: Some(n.node),
                    line,
                    timestamp: ts,
                    kind,
                    severity: Severity::of_finding(kind, &detail, n.profile),
                    detail,
                });
            };
            if let Some(warning) = n.first_warning() {
                push(
                    FindingKind::FirstWarning,
                    warning.line,
                    FindingDetail::Emcy(warning),
                    warning.timestamp,
                );
            }
            if let Some(error) = n.first_error_reported() {
                push(
                    FindingKind::FirstError,
                    error.line,
                    FindingDetail::Emcy(error),
                    error.timestamp,
                );
            }
            if let Some(faults) = n.cia402.as_ref().and_then(|c| c.faults.as_ref()) {
                each(
                    faults,
                    |fault| fault.transition.line,
                    |line, fault| {
                        let (detail, ts) = match fault {
                            Ok(fault) => (
                                FindingDetail::Cia402Fault(*fault),
                                fault.transition.timestamp,
                            ),
                            Err(n) => (FindingDetail::Omitted(n), None),
                        };
                        push(FindingKind::Cia402Fault, line, detail, ts);
                    },
                );
            }
            let boots = &n.heartbeat.boot_ups;
            if boots.count() > 1 {
                let line = *boots.get(1).unwrap_or(&0);
                push(
                    FindingKind::Restarts,
                    line,
                    FindingDetail::BootUps(boots.clone()),
                    None,
                );
            }
            if let Timeouts::Checked(gaps) = &n.heartbeat.timeouts {
                each(
                    gaps,
                    |gap| gap.after_line,
                    |line, gap| {
                        let detail = gap.map_or_else(FindingDetail::Omitted, |gap| {
                            FindingDetail::HeartbeatGap(*gap)
                        });
                        push(FindingKind::HeartbeatTimeout, line, detail, None);
                    },
                );
            }
            each(
                &n.sdo.aborts,
                |abort| abort.line,
                |line, abort| {
                    let detail = abort.map_or_else(FindingDetail::Omitted, |abort| {
                        FindingDetail::SdoAbort(abort.clone())
                    });
                    push(FindingKind::SdoAbort, line, detail, None);
                },
            );
            for (kind, lines) in [
                (FindingKind::SdoBroken, &n.sdo.broken),
                (FindingKind::SdoTimeout, &n.sdo.timeouts),
                (FindingKind::ToggleError, &n.guarding.toggle_errors),
            ] {
                each_line(lines, |line, detail| push(kind, line, detail, None));
            }
        }
        for b in &self.buses {
            for (kind, lines) in [
                (FindingKind::BusOff, &b.bus_off),
                (FindingKind::ErrorPassive, &b.error_passive),
            ] {
                each_line(lines, |line, detail| {
                    list.push(Finding {
                        file: self.file.clone(),
                        bus: b.bus.clone(),
                        node: None,
                        line,
                        timestamp: None,
                        kind,
                        severity: Severity::of_finding(kind, &detail, Profile::Generic),
                        detail,
                    });
                });
            }
        }
        for finding in &mut list {
            if !finding.timed_by_summary() {
                finding.timestamp = time_of(finding);
            }
        }
        if list.iter().all(|f| f.timestamp.is_some()) {
            list.sort_by_key(|f| (f.timestamp, f.line));
        } else {
            list.sort_by_key(|f| f.line);
        }
        list
    }
}

/// Hand `found` each entry a summary list keeps, in order, as `Ok` at its
/// line, and in their place the entries it omitted as `Err(count)` at the
/// line of the last entry kept before them (docs/summary.md#lists).
fn each<T>(
    list: &Listed<T>,
    line: impl Fn(&T) -> u64,
    mut found: impl FnMut(u64, Result<&T, u64>),
) {
    for entry in list.head() {
        found(line(entry), Ok(entry));
    }
    if let (n @ 1.., Some(last)) = (list.omitted(), list.head().last()) {
        found(line(last), Err(n));
    }
    for entry in list.tail() {
        found(line(entry), Ok(entry));
    }
}

/// [`each`] for a list of lines.
fn each_line(list: &Listed<u64>, mut found: impl FnMut(u64, FindingDetail)) {
    each(
        list,
        |&line| line,
        |line, entry| {
            found(
                line,
                entry.map_or_else(FindingDetail::Omitted, |_| FindingDetail::Line),
            );
        },
    );
}
