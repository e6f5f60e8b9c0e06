//! What went wrong, from a summary: its findings in time order
//! (docs/summary.md#findings), each device's first warning and first error
//! (docs/summary.md#severity), and the verdict on them
//! (docs/summary.md#verdict).

use crate::can::Timestamp;
use crate::decoder::ethercat::SlaveRef;
use crate::profiles::Profile;

use super::{
    EmcySeen, Finding, FindingCause, FindingDetail, FindingKind, Listed, NodeSummary, Severity,
    Summary, Timeouts, Verdict, CAUSE_WINDOW,
};

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
    ///     r#"{"iface":"can0","node":3,"slave":null,"line":2,"ts":1700000000.100000,"kind":"first_error","severity":"error","text":"first error: EMCY 0x8110 CAN overrun (objects lost) at line 2"}"#
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
            let mut push = |kind, line, detail: FindingDetail, ts| {
                let cause = match &detail {
                    FindingDetail::Emcy(seen) => self
                        .lost_before(&n.bus, n.node, seen)
                        .map(|(node, gap)| FindingCause::HeartbeatTimeout { node, gap }),
                    FindingDetail::Cia402Fault(fault) => fault.cause().map(FindingCause::Emcy),
                    FindingDetail::HeartbeatGap(gap) => gap.cause.map(FindingCause::BusError),
                    _ => None,
                };
                list.push(Finding {
                    file: self.file.clone(),
                    bus: n.bus.clone(),
                    node: Some(n.node),
                    slave: None,
                    line,
                    timestamp: ts,
                    kind,
                    severity: Severity::of_finding(kind, &detail, n.profile),
                    detail,
                    profile: n.profile,
                    cause,
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
                        slave: None,
                        line,
                        timestamp: None,
                        kind,
                        severity: Severity::of_finding(kind, &detail, Profile::Generic),
                        detail,
                        profile: Profile::Generic,
                        cause: None,
                    });
                });
            }
        }
        self.slave_findings(&mut list);
        for finding in &mut list {
            if !finding.timed_by_summary() {
                finding.timestamp = time_of(finding);
            }
        }
        // A finding is large: the keys are sorted, then the findings moved
        // once each.
        if list.iter().all(|f| f.timestamp.is_some()) {
            list.sort_by_cached_key(|f| (f.timestamp, f.line));
        } else {
            list.sort_by_cached_key(|f| f.line);
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

impl Summary {
    /// The findings of the EtherCAT slaves (docs/ethercat.md#findings):
    /// each slave's first error emergency, its CiA 402 faults (caused by
    /// an emergency read up to [`CAUSE_WINDOW`] before the fault, or after
    /// it: a CoE emergency waits in the slave's mailbox until the master
    /// reads it), its AL states with the error indicator, and its servo
    /// faults.
    fn slave_findings(&self, list: &mut Vec<Finding>) {
        for s in &self.ethercat.slaves {
            let slave = Some(SlaveRef {
                station: s.station,
                position: s.position,
            });
            let profile = s
                .emergencies
                .first()
                .map_or(Profile::Generic, |e| e.profile);
            let mut push = |kind, line, detail: FindingDetail, ts, cause| {
                list.push(Finding {
                    file: self.file.clone(),
                    bus: s.iface.clone(),
                    node: None,
                    slave,
                    line,
                    timestamp: ts,
                    kind,
                    severity: Severity::of_finding(kind, &detail, profile),
                    detail,
                    profile,
                    cause,
                });
            };
            let seen = |e: &super::CoeEmergency| EmcySeen {
                line: e.packet,
                timestamp: e.timestamp,
                code: e.emcy.code,
                register: e.emcy.register,
                manufacturer: e.emcy.manufacturer,
            };
            let errors: Vec<EmcySeen> = s
                .emergencies
                .iter()
                .filter(|e| e.emcy.code.get() != 0)
                .map(seen)
                .collect();
            if let Some(first) = errors.first() {
                push(
                    FindingKind::FirstError,
                    first.line,
                    FindingDetail::Emcy(*first),
                    first.timestamp,
                    None,
                );
            }
            if let Some(faults) = s.cia402.as_ref().and_then(|c| c.faults.as_ref()) {
                for fault in faults.iter() {
                    let after = || {
                        let at = fault.transition.timestamp?;
                        errors.iter().copied().find(|e| {
                            e.line > fault.transition.line
                                && e.timestamp
                                    .and_then(|t| t.duration_since(at))
                                    .is_some_and(|gap| gap <= CAUSE_WINDOW)
                        })
                    };
                    let cause = fault.cause().or_else(after).map(FindingCause::Emcy);
                    push(
                        FindingKind::Cia402Fault,
                        fault.transition.line,
                        FindingDetail::Cia402Fault(*fault),
                        fault.transition.timestamp,
                        cause,
                    );
                }
            }
            for change in s
                .al_changes
                .iter()
                .filter(|c| !c.requested && c.status.error())
            {
                push(
                    FindingKind::AlError,
                    change.packet,
                    FindingDetail::AlError(*change),
                    change.timestamp,
                    None,
                );
            }
            if let Some(servo) = &s.servo {
                each(
                    &servo.faults,
                    |event| event.packet,
                    |line, event| {
                        let (detail, ts) = match event {
                            Ok(event) => (FindingDetail::ServoFault(*event), event.timestamp),
                            Err(n) => (FindingDetail::Omitted(n), None),
                        };
                        push(FindingKind::ServoFault, line, detail, ts, None);
                    },
                );
            }
        }
    }
}

impl Verdict {
    /// Return the verdict on `summary`'s findings ([`Summary::findings`]),
    /// or `None` when nothing stopped: no fault, no heartbeat timeout, no
    /// bus-off.
    #[must_use]
    pub fn of(summary: &Summary) -> Option<Verdict> {
        if !summary.may_stop() {
            return None;
        }
        let findings = summary.findings();
        let at = findings.iter().rposition(Finding::stops)?;
        // A bus-off that caused heartbeat timeouts is not the end: the
        // loss of the devices it silenced is, the last of them.
        let at = if findings[at].kind == FindingKind::BusOff {
            (0..findings.len())
                .filter(|&j| {
                    findings[j].kind == FindingKind::HeartbeatTimeout
                        && linked(summary, &findings, j) == Some(at)
                })
                .max_by_key(|&j| match &findings[j].detail {
                    FindingDetail::HeartbeatGap(gap) => (gap.due, j),
                    _ => (gap_none(), j),
                })
                .unwrap_or(at)
        } else {
            at
        };
        let stop = &findings[at];
        let first_cause = &findings[first_cause(summary, &findings, at)];
        let cause = match (&stop.detail, stop.cause) {
            (FindingDetail::Cia402Fault(_), Some(FindingCause::Emcy(emcy))) => Some(emcy),
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
}

impl Summary {
    /// Whether the summary may hold a finding that stops the recording: a
    /// CiA 402 fault, a heartbeat timeout or a bus-off listed, or an
    /// EtherCAT slave (whose AL errors and servo faults stop it too).
    /// Without one, [`Verdict::of`] has nothing to find and builds no
    /// findings.
    fn may_stop(&self) -> bool {
        let node_stops = |n: &NodeSummary| {
            n.cia402
                .as_ref()
                .and_then(|c| c.faults.as_ref())
                .is_some_and(|faults| !faults.is_empty())
                || matches!(&n.heartbeat.timeouts, Timeouts::Checked(gaps) if !gaps.is_empty())
        };
        self.nodes.iter().any(node_stops)
            || self.buses.iter().any(|b| !b.bus_off.is_empty())
            || !self.ethercat.slaves.is_empty()
    }
}

/// The finding that finding `i`'s cause is (docs/summary.md#causes): for a
/// fault, the heartbeat timeout that caused its EMCY 0x8130; for an EMCY
/// 0x8130, the heartbeat timeout before it; for a heartbeat timeout, the
/// bus-off before it. An error-passive is a warning: never a first cause.
fn linked(summary: &Summary, findings: &[Finding], i: usize) -> Option<usize> {
    let f = &findings[i];
    let lost = |node, gap: super::HeartbeatGap| {
        findings.iter().position(|g| {
            g.kind == FindingKind::HeartbeatTimeout
                && g.bus == f.bus
                && g.node == Some(node)
                && g.line == gap.after_line
                && !g.is_omitted()
        })
    };
    match f.cause? {
        FindingCause::Emcy(emcy) => {
            let (node, gap) = summary.lost_before(&f.bus, f.node?, &emcy)?;
            lost(node, gap)
        }
        FindingCause::HeartbeatTimeout { node, gap } => lost(node, gap),
        FindingCause::BusError(error) if error.bus_off => findings.iter().position(|g| {
            g.kind == FindingKind::BusOff
                && g.bus == f.bus
                && g.node.is_none()
                && g.line == error.line
                && !g.is_omitted()
        }),
        _ => None,
    }
}

/// The first cause of the stop at `at` (docs/summary.md#verdict): follow
/// the links back from the stop as far as the log supports them, to the
/// root; its first cause is the earliest fault or error finding of the
/// root's device (of any device of its bus, for a bus-off) at or before
/// it, leaving out the links followed and what the root caused; and from
/// there on, its own links.
fn first_cause(summary: &Summary, findings: &[Finding], at: usize) -> usize {
    let mut root = at;
    let mut chain = vec![at];
    // A link always leads to another kind of finding: fault, EMCY 0x8130,
    // heartbeat timeout, bus-off; a few steps reach the end.
    for _ in 0..6 {
        if let Some(i) = linked(summary, findings, root).filter(|i| !chain.contains(i)) {
            chain.push(i);
            root = i;
            continue;
        }
        let r = &findings[root];
        let first = findings[..=root]
            .iter()
            .enumerate()
            .find(|&(i, f)| {
                !f.is_omitted()
                    && f.severity.is_fault_or_error()
                    && f.bus == r.bus
                    && ((r.node.is_none() && r.slave.is_none())
                        || (f.node == r.node && f.slave == r.slave))
                    && (i == root
                        || (!chain.contains(&i) && linked(summary, findings, i) != Some(root)))
            })
            .map_or(root, |(i, _)| i);
        match linked(summary, findings, first).filter(|i| !chain.contains(i)) {
            Some(i) => {
                chain.push(first);
                chain.push(i);
                root = i;
            }
            None => return first,
        }
    }
    root
}

/// The earliest time, for a gap without one.
fn gap_none() -> Timestamp {
    Timestamp::from_duration(core::time::Duration::ZERO)
}
