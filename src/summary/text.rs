//! The text summary: the records of docs/summary.md#text in sentences a service
//! engineer can act on.

use core::fmt;

use crate::can::Timestamp;
use crate::canopen::Cia402State;
use crate::profiles::Profile;

use super::listed::{each, ListedLines};
use super::{
    BusSummary, Cia402Fault, Cia402Timeline, EmcySeen, NodeSummary, SdoAbort, SdoSummary, Summary,
    SummaryItem, SummaryRecord, Timeouts,
};

impl fmt::Display for Summary {
    /// Every node's sentences, then one line per bus.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for record in self.records() {
            write!(f, "{record}")?;
        }
        Ok(())
    }
}

impl fmt::Display for SummaryRecord<'_> {
    /// The record's sentences, after `FILE: ` when the summary names its
    /// file.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(file) = self.file {
            write!(f, "{file}: ")?;
        }
        match self.item {
            SummaryItem::Verdict(verdict) => fmt::Display::fmt(verdict, f),
            SummaryItem::Node(node) => fmt::Display::fmt(node, f),
            SummaryItem::Bus(bus) => fmt::Display::fmt(bus, f),
            SummaryItem::EthercatPort(port) => fmt::Display::fmt(port, f),
            SummaryItem::Slave(slave) => fmt::Display::fmt(slave, f),
            SummaryItem::Stream(stream) => fmt::Display::fmt(stream, f),
        }
    }
}

/// A count and its noun, plural unless the count is one: `1 request`,
/// `2 transfers`.
struct Counted(u64, &'static str);

impl fmt::Display for Counted {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = if self.0 == 1 { "" } else { "s" };
        write!(f, "{} {}{s}", self.0, self.1)
    }
}

/// Lines as a comma-separated list: `12, 40, 41`.
struct Lines<'a, T>(&'a [T]);

impl<T: fmt::Display> fmt::Display for Lines<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, line) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{line}")?;
        }
        Ok(())
    }
}

/// A time as seconds with six decimals and no padding (`0.052000`,
/// `1700000000.000520`): relative times read as they are.
struct Seconds(Timestamp);

impl fmt::Display for Seconds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{:06}", self.0.secs(), self.0.micros())
    }
}

fn seen(f: &mut fmt::Formatter<'_>, what: &str, seen: Option<EmcySeen>) -> fmt::Result {
    match seen {
        None => write!(f, ", {what}: none"),
        Some(seen) => write!(
            f,
            ", {what}: {} {} (line {})",
            seen.code,
            seen.code.description(),
            seen.line
        ),
    }
}

impl fmt::Display for NodeSummary {
    /// The node's sentences: frames by kind; EMCYs with the first and the
    /// active error; heartbeats, boot-ups and timeouts; guarding; SDO;
    /// the CiA 402 timeline of a drive.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} node {:>3}  frames", self.bus, self.node.get())?;
        for (key, n) in self.frames.iter() {
            if n > 0 {
                write!(f, " {key}={n}")?;
            }
        }
        writeln!(f)?;
        write!(f, "          emcy {} (resets {})", self.emcy, self.resets)?;
        // A first EMCY that is a warning is said as one, and the first
        // error after it (docs/summary.md#severity).
        if let Some(warning) = self.first_warning() {
            seen(f, "first warning", Some(warning))?;
            seen(f, "first error", self.first_error_reported())?;
        } else {
            seen(f, "first error", self.first_error)?;
        }
        seen(f, "active error", self.active_error)?;
        if let Some(register) = self.last_register.filter(|r| r.bits() != 0) {
            if self.active_error.is_none() {
                // A reset EMCY with a non-zero register: other errors are
                // still active (docs/summary.md#emcy).
                write!(
                    f,
                    ", error register {:#04x} still set by the last EMCY",
                    register.bits()
                )?;
            }
        }
        writeln!(f)?;
        let hb = &self.heartbeat;
        write!(
            f,
            "          heartbeats {}, last state {}",
            hb.count,
            hb.last_state.map_or("-", |st| st.state_name())
        )?;
        if !hb.boot_ups.is_empty() {
            write!(f, ", boot-ups at lines {}", ListedLines(&hb.boot_ups))?;
        }
        match &hb.timeouts {
            Timeouts::NotAsked => {}
            Timeouts::NotChecked => f.write_str(", timeouts not checked (no timestamps)")?,
            Timeouts::Checked(gaps) => {
                if gaps.is_empty() {
                    f.write_str(", no timeouts")?;
                }
                each(
                    gaps,
                    f,
                    |gap, f, _| {
                        write!(
                            f,
                            ", timeout: {} ms after line {}",
                            gap.gap_ms(),
                            gap.after_line
                        )
                    },
                    |omitted, f| write!(f, ", … {} …", Counted(omitted, "more timeout")),
                )?;
            }
        }
        writeln!(f)?;
        let g = &self.guarding;
        if g.answers > 0 || !g.toggle_errors.is_empty() {
            write!(f, "          guarding answers {}", g.answers)?;
            if !g.toggle_errors.is_empty() {
                write!(
                    f,
                    ", wrong toggle at lines {}",
                    ListedLines(&g.toggle_errors)
                )?;
            }
            writeln!(f)?;
        }
        fmt::Display::fmt(&self.sdo, f)?;
        if let Some(cia402) = &self.cia402 {
            fmt::Display::fmt(cia402, f)?;
        }
        Ok(())
    }
}

impl fmt::Display for BusSummary {
    /// One line: frames, error frames, bus-off and error-passive lines,
    /// status events, the time span and the nodes.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "bus {}  frames {}, error frames {}",
            self.bus, self.frames, self.error_frames
        )?;
        if !self.bus_off.is_empty() {
            write!(f, ", bus-off at lines {}", ListedLines(&self.bus_off))?;
        }
        if !self.error_passive.is_empty() {
            write!(
                f,
                ", error-passive at lines {}",
                ListedLines(&self.error_passive)
            )?;
        }
        if self.status_events > 0 {
            write!(f, ", status events {}", self.status_events)?;
        }
        if let (Some(first), Some(last)) = (self.first_timestamp, self.last_timestamp) {
            write!(f, ", from {} to {}", Seconds(first), Seconds(last))?;
        }
        if !self.nodes.is_empty() {
            let nodes: Vec<u8> = self.nodes.iter().map(|n| n.get()).collect();
            write!(f, ", nodes {}", Lines(&nodes))?;
        }
        writeln!(f)
    }
}

impl fmt::Display for SdoSummary {
    /// The node's SDO sentences (nothing when it had no SDO frame).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return Ok(());
        }
        write!(
            f,
            "          SDO: {}, {}",
            Counted(self.requests, "request"),
            Counted(self.transfers, "transfer")
        )?;
        if let Some(l) = self.latency {
            write!(
                f,
                "; latency median {:.3} ms, p99 {:.3} ms, max {:.3} ms over {}",
                ms(l.median),
                ms(l.p99),
                ms(l.max),
                l.count
            )?;
        }
        writeln!(f)?;
        each(
            &self.aborts,
            f,
            |abort, f, _| writeln!(f, "          line {}: {abort}", abort.line),
            |omitted, f| writeln!(f, "          … {} …", Counted(omitted, "more abort")),
        )?;
        if !self.broken.is_empty() {
            writeln!(
                f,
                "          broken transfers starting at lines {}",
                ListedLines(&self.broken)
            )?;
        }
        if !self.timeouts.is_empty() {
            writeln!(
                f,
                "          unanswered requests at lines {}",
                ListedLines(&self.timeouts)
            )?;
        }
        Ok(())
    }
}

pub(super) fn ms(d: core::time::Duration) -> f64 {
    d.as_nanos() as f64 / 1e6
}

impl fmt::Display for Cia402Timeline {
    /// The states in order (up to 12 in full; a longer timeline shows its
    /// first 4 and last 8), and each fault with the EMCY before it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.transitions.is_empty() {
            return writeln!(f, "          CiA 402: no statusword seen");
        }
        let n = self.transitions.count();
        write!(f, "          CiA 402, {n} states in turn:")?;
        // Every state kept when there are up to 12, else the first 4 and
        // the last 8 (the list keeps at least those).
        let kept = self.transitions.kept();
        for (i, t) in self.transitions.iter().enumerate() {
            if n > 12 && (4..kept - 8).contains(&i) {
                if i == 4 {
                    write!(f, " → … {} more …", n - 12)?;
                }
                continue;
            }
            if i > 0 {
                f.write_str(" →")?;
            }
            write!(f, " {} (line {})", t.to.name(), t.line)?;
        }
        writeln!(f)?;
        if let Some(faults) = &self.faults {
            each(
                faults,
                f,
                |fault, f, _| writeln!(f, "          {fault}"),
                |omitted, f| writeln!(f, "          … {} …", Counted(omitted, "more fault")),
            )?;
        }
        Ok(())
    }
}

impl fmt::Display for Cia402Fault {
    /// `went operation_enabled → fault at line L, T ms after EMCY CODE
    /// DESCRIPTION (line M)` (docs/summary.md#text).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.sentence(Profile::Generic))
    }
}

impl Cia402Fault {
    /// Return the fault's sentence with what the drive's `profile` reads
    /// in the EMCY before it ([`ProfileReading`](super::ProfileReading),
    /// docs/summary.md#profiles): `went operation_enabled → fault at line
    /// L, T ms after EMCY CODE DESCRIPTION on axis A, feedback F (line
    /// M)` for an AKD; `Display` is the sentence of a generic node.
    #[must_use]
    pub fn sentence(&self, profile: Profile) -> impl fmt::Display + '_ {
        FaultSentence(self, profile, "line")
    }

    /// The sentence with positions counted in `unit` (`packet` for a
    /// capture's slave).
    pub(crate) fn sentence_in(
        &self,
        profile: Profile,
        unit: &'static str,
    ) -> impl fmt::Display + '_ {
        FaultSentence(self, profile, unit)
    }
}

/// [`Cia402Fault::sentence`].
struct FaultSentence<'a>(&'a Cia402Fault, Profile, &'static str);

impl fmt::Display for FaultSentence<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let FaultSentence(fault, profile, unit) = *self;
        let t = fault.transition;
        write!(
            f,
            "went {} → {} at {unit} {}",
            t.from.map_or("-", Cia402State::name),
            t.to.name(),
            t.line
        )?;
        if let Some(emcy) = fault.emcy_before {
            let code = emcy.code;
            let reading = emcy.reading(profile);
            match (t.timestamp, emcy.timestamp) {
                (Some(at), Some(then)) => {
                    let gap = at.duration_since(then).unwrap_or_default();
                    write!(
                        f,
                        ", {:.1} ms after EMCY {code} {}{reading} ({unit} {})",
                        gap.as_secs_f64() * 1000.0,
                        code.description(),
                        emcy.line
                    )?;
                }
                _ => write!(
                    f,
                    ", after EMCY {code} {}{reading} ({unit} {})",
                    code.description(),
                    emcy.line
                )?,
            }
        }
        Ok(())
    }
}

impl fmt::Display for SdoAbort {
    /// `server aborted 1A00h.00 (TPDO mapping parameter): 0x06040043:
    /// General parameter incompatibility reason` (docs/summary.md#text).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} aborted {}", self.by.name(), self.multiplexer)?;
        if let Some(name) = &self.object {
            write!(f, " ({name})")?;
        }
        write!(f, ": {}", self.code)
    }
}
