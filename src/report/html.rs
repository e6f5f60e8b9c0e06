//! The page (docs/report.md#page): plain writes of HTML, one pass over
//! the recordings; its SVG is drawn by `svg.rs`. Everything that means something carries its data:
//! rows, bands and marks their `data-*` attributes and a `<title>`
//! (docs/report.md#contract).

use std::fmt::Write as _;
use std::io::{self, Write};

use crate::canopen::ErrorCode;
use crate::profiles::Profile;
use crate::summary::{
    Finding, FindingDetail, FindingKind, Listed, NodeSummary, Severity, SlaveSummary,
    StreamSummary, Timeouts,
};

use super::layout::{seconds, Axis, Budget, AXIS, LEFT, PLOT, UNIX_FROM, WIDTH};
use super::markup::slave_name;
use super::markup::{device, esc, iface_attr};
use super::recorder::{MarkKind, Recording, RowData};
use super::series::At;
use super::svg::{
    axis_ticks, chart, defs, drawn_bands, drawn_marks, legend, mark_text, marks, node_row, rate,
    slave_row, stream_row, Charted, Drawn,
};

/// The most rows of the event table (docs/report.md#tables).
const EVENT_ROWS: usize = 2000;
/// The groups of "What went wrong" shown open: the rest are one click
/// away, so that the verdict and the worst findings fit the first screen
/// whatever the log (docs/report.md#page).
const GROUPS_SHOWN: usize = 6;
/// The most marks a page draws: beyond, neighbours cluster within as many
/// pixels (a power of two) as keep them to this (docs/report.md#clusters).
const MARK_BUDGET: usize = 20_000;
/// The most bands a page draws: beyond, neighbouring bands narrower than
/// as many pixels as keep them to this merge.
const BAND_BUDGET: usize = 10_000;
/// Marks and bands have a `<title>` while a page has at most this many
/// (the script shows the same words from their `data-*`).
const TITLE_BUDGET: usize = 5_000;

const STYLE: &str = include_str!("page.css");
const SCRIPT: &str = include_str!("page.js");

/// A log the page was made from, as its header names it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReportInput {
    /// The file, as it was named (`<stdin>` for standard input).
    pub name: String,
    /// Its format, as docs/formats.md names it (`candump`, `asc`, …).
    pub format: String,
    /// Its last line or record number.
    pub last_line: u64,
}

/// The page of one or more recordings (see the [module](super)
/// documentation): [`Report::write_html`] writes it.
#[derive(Debug, Clone, Default)]
pub struct Report {
    recordings: Vec<Recording>,
    inputs: Vec<ReportInput>,
    notes: Vec<String>,
    command: Option<String>,
}

/// A date and time of the Unix epoch in UTC, `2023-11-14 22:13:20.000526 UTC`
/// (days to civil date: H. Hinnant's algorithm).
pub(super) fn utc(us: u64) -> String {
    let secs = us / 1_000_000;
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02}.{:06} UTC",
        rem / 3600,
        rem / 60 % 60,
        rem % 60,
        us % 1_000_000
    )
}

impl Report {
    /// Start a page.
    #[must_use]
    pub fn new() -> Self {
        Report::default()
    }

    /// Add a recording (each log read apart is one; logs read as one
    /// recording, `--joined`, are one).
    pub fn add_recording(&mut self, recording: Recording) {
        self.recordings.push(recording);
    }

    /// Name a log the page was made from, for its header.
    pub fn add_input(&mut self, input: ReportInput) {
        self.inputs.push(input);
    }

    /// Add a sentence to the header (e.g. how many malformed lines were
    /// skipped).
    pub fn add_note(&mut self, note: impl Into<String>) {
        self.notes.push(note.into());
    }

    /// Say the command that made the page, in its header.
    pub fn set_command(&mut self, command: impl Into<String>) {
        self.command = Some(command.into());
    }

    /// Return the recordings.
    #[must_use]
    pub fn recordings(&self) -> &[Recording] {
        &self.recordings
    }

    /// The axis of `recordings` drawn on one: by time when every one of
    /// them is, else by line; from the first place to the last.
    fn span_axis(recordings: &[Recording]) -> Axis {
        let timed = !recordings.is_empty() && recordings.iter().all(|r| r.timeline.is_timed());
        let mut start = u64::MAX;
        let mut end = 0;
        for r in recordings {
            if let Some((first, last)) = r.timeline.span() {
                start = start.min(first.key(timed));
                end = end.max(last.key(timed));
            }
            // Heartbeat gaps can end past the last frame: never.
        }
        if start > end {
            start = 0;
            end = 1;
        }
        if end == start {
            end = start + if timed { 1_000_000 } else { 1 };
        }
        Axis { timed, start, end }
    }

    /// The page's axis, `<body>`'s: the one recording's, or with several
    /// read apart the first's (each has its own, [`axis_of`](Self::axis_of)).
    fn axis(&self) -> Axis {
        Self::span_axis(&self.recordings[..self.recordings.len().min(1)])
    }

    /// The axis a recording is drawn on: its own (docs/report.md#several).
    fn axis_of(r: &Recording) -> Axis {
        Self::span_axis(std::slice::from_ref(r))
    }

    /// Every row drawn: its recording's axis, end and data.
    fn all_rows(&self) -> Vec<(Axis, At, &RowData)> {
        let mut rows = Vec::new();
        for r in &self.recordings {
            let axis = Self::axis_of(r);
            let end = r.timeline.span().map_or(At::default(), |(_, last)| last);
            for bus in &r.timeline.buses {
                rows.push((axis, end, &bus.row));
                for n in r.summary.nodes.iter().filter(|n| n.bus == bus.name) {
                    if let Some(row) = bus.node_row(n.node) {
                        rows.push((axis, end, row));
                    }
                }
            }
            for (_, row) in ethercat_rows(r) {
                rows.push((axis, end, row));
            }
        }
        rows
    }

    /// How many marks and bands the page would draw, and how to keep them
    /// within the budgets (docs/report.md#size).
    fn budget(&self) -> Budget {
        let rows = self.all_rows();
        let count_marks = |radius: Option<f64>| -> usize {
            rows.iter()
                .flat_map(|(axis, _, row)| row.marks.iter().map(move |s| (axis, s)))
                .filter(|(_, s)| s.len() > 0)
                .map(|(axis, s)| drawn_marks(axis, s, radius).len())
                .sum()
        };
        let count_bands = |px: Option<f64>| -> usize {
            rows.iter()
                .flat_map(|(axis, end, row)| {
                    [&row.nmt, &row.al, &row.cia402, &row.servo].map(|series| (axis, end, series))
                })
                .map(|(axis, end, s)| drawn_bands(axis, s, *end, px).len())
                .sum()
        };
        let mut radius = None;
        let mut marks = count_marks(None);
        if marks > MARK_BUDGET {
            let mut r = 1.0;
            loop {
                marks = count_marks(Some(r));
                if marks <= MARK_BUDGET || r >= PLOT {
                    break;
                }
                r *= 2.0;
            }
            radius = Some(r);
        }
        let mut band_px = None;
        let mut bands = count_bands(None);
        if bands > BAND_BUDGET {
            let mut px = 2.0;
            loop {
                bands = count_bands(Some(px));
                if bands <= BAND_BUDGET || px >= PLOT {
                    break;
                }
                px *= 2.0;
            }
            band_px = Some(px);
        }
        Budget {
            radius,
            band_px,
            titles: marks + bands <= TITLE_BUDGET,
        }
    }

    /// Write the page (docs/report.md#page) to `out`.
    ///
    /// # Errors
    ///
    /// Writing to `out` failed.
    pub fn write_html(&self, out: &mut impl Write) -> io::Result<()> {
        let axis = self.axis();
        let budget = self.budget();
        let mut page = String::with_capacity(1 << 16);
        self.head(&mut page, &axis);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.findings(&mut page);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.timeline(&mut page, &budget);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.signals(&mut page, &budget);
        self.tables(&mut page);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.events(&mut page, &budget);
        out.write_all(page.as_bytes())?;
        out.write_all(b"<script type=\"application/json\" id=\"motionwire-summary\">")?;
        self.summary_json(out)?;
        out.write_all(b"</script>\n<script>\n")?;
        out.write_all(SCRIPT.as_bytes())?;
        out.write_all(b"</script>\n</body>\n</html>\n")
    }

    fn head(&self, p: &mut String, axis: &Axis) {
        let names: Vec<&str> = self.inputs.iter().map(|i| i.name.as_str()).collect();
        let title = if names.is_empty() {
            "motionwire report".to_owned()
        } else {
            format!("motionwire report: {}", names.join(", "))
        };
        let _ = write!(
            p,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <meta name=\"generator\" content=\"motionwire {}\">\n<title>{}</title>\n<style>\n{STYLE}</style>\n</head>\n",
            env!("CARGO_PKG_VERSION"),
            esc(&title)
        );
        let span = axis.end - axis.start;
        let _ = write!(
            p,
            "<body data-axis=\"{}\" data-start=\"{}\" data-span=\"{}\">\n<header>\n<h1>{}</h1>\n",
            if axis.timed { "time" } else { "line" },
            axis.start,
            span,
            esc(&title)
        );
        p.push_str("<dl class=\"facts\">\n");
        for input in &self.inputs {
            let _ = writeln!(
                p,
                "<dt>log</dt><dd><code>{}</code> ({}, {} lines or records)</dd>",
                esc(&input.name),
                esc(&input.format),
                input.last_line
            );
        }
        let frames: u64 = self
            .recordings
            .iter()
            .flat_map(|r| r.summary.buses.iter())
            .map(|b| b.frames)
            .sum();
        let buses: Vec<String> = self
            .recordings
            .iter()
            .flat_map(|r| r.summary.buses.iter())
            .map(|b| b.bus.to_string())
            .collect();
        let nodes: usize = self.recordings.iter().map(|r| r.summary.nodes.len()).sum();
        let _ = write!(
            p,
            "<dt>frames</dt><dd>{frames}</dd>\n<dt>buses</dt><dd>{} ({})</dd>\n<dt>devices</dt><dd>{nodes}</dd>\n",
            buses.len(),
            esc(&buses.join(", "))
        );
        for r in &self.recordings {
            let ethercat = &r.summary.ethercat;
            for port in &ethercat.ports {
                let slaves = ethercat
                    .slaves
                    .iter()
                    .filter(|s| s.iface == port.iface)
                    .count();
                let streams = ethercat
                    .streams
                    .iter()
                    .filter(|s| s.iface == port.iface)
                    .count();
                let _ = writeln!(
                    p,
                    "<dt>EtherCAT</dt><dd>{}: {slaves} slave{}, {streams} cyclic stream{}</dd>",
                    esc(port.to_string().trim_start_matches("ethercat").trim()),
                    if slaves == 1 { "" } else { "s" },
                    if streams == 1 { "" } else { "s" },
                );
            }
        }
        if self.recordings.len() > 1 {
            // Read apart, each recording has its own axis.
            for r in &self.recordings {
                let _ = writeln!(
                    p,
                    "<dt>time</dt><dd>{}: {}{}</dd>",
                    esc(r.summary.file.as_deref().unwrap_or("")),
                    esc(&axis_words(&Self::axis_of(r))),
                    if r.timeline.is_timed() {
                        ""
                    } else {
                        " (no timestamps: drawn by line)"
                    }
                );
            }
        } else if axis.timed {
            let start = if axis.start >= UNIX_FROM {
                utc(axis.start)
            } else {
                format!("{} s (the log's own clock)", seconds(axis.start))
            };
            let _ = writeln!(
                p,
                "<dt>time</dt><dd>from {start}, for {} s; times on this page are seconds after it</dd>",
                seconds(span)
            );
        } else {
            p.push_str(
                "<dt>time</dt><dd class=\"untimed\"><strong>The log has no timestamps:</strong> \
                 events are ordered by line and the axis counts lines, not time; heartbeat \
                 timeouts cannot be checked.</dd>\n",
            );
        }
        if let Some(command) = &self.command {
            let _ = writeln!(p, "<dt>made by</dt><dd><code>{}</code></dd>", esc(command));
        }
        for r in &self.recordings {
            let untimed = r.timeline.untimed_frames();
            if untimed > 0 {
                let _ = writeln!(
                    p,
                    "<dt>note</dt><dd>{untimed} frames without a timestamp are drawn at the time of the frame before them</dd>"
                );
            }
        }
        for note in &self.notes {
            let _ = writeln!(p, "<dt>note</dt><dd>{}</dd>", esc(note));
        }
        p.push_str("</dl>\n<nav><a href=\"#wrong\">What went wrong</a> · <a href=\"#timeline\">Timeline</a> · <a href=\"#signals\">Signals</a> · <a href=\"#devices\">Devices</a> · <a href=\"#events\">Events</a></nav>\n</header>\n");
    }

    /// Each recording's verdict, first (docs/report.md#page): the stop and
    /// its first cause as the text summary says them, with the stop's wall
    /// clock time where the log gives a Unix time.
    fn verdicts(&self, p: &mut String) {
        for r in &self.recordings {
            let Some(v) = r.summary.verdict() else {
                continue;
            };
            let file = r
                .summary
                .file
                .as_deref()
                .map_or_else(String::new, |f| format!("{}: ", esc(f)));
            // Where the summary keeps no time (a heartbeat timeout, a
            // bus-off), the stop's mark on the timeline has it.
            let wall = v
                .stop
                .timestamp
                .map(|ts| u64::try_from(ts.as_micros()).unwrap_or(u64::MAX))
                .or_else(|| {
                    r.timeline
                        .is_timed()
                        .then(|| r.timeline.place(&v.stop).t)
                        .filter(|&t| t > 0)
                })
                .filter(|&us| us >= UNIX_FROM)
                .map_or_else(String::new, |us| format!(" at {}", utc(us)));
            let node = v
                .stop
                .node
                .map_or_else(String::new, |n| format!(" data-node=\"{}\"", n.get()));
            let _ = write!(
                p,
                "<div class=\"verdict\" data-kind=\"verdict\" data-line=\"{}\" data-iface=\"{}\"{node} data-severity=\"{}\">\n<p><b>{file}Stop{wall}:</b> {}</p>\n<p><b>First cause:</b> {}</p>\n</div>\n",
                v.stop.line,
                iface_attr(&v.stop.bus),
                v.stop.severity,
                esc(&v.stop_text()),
                esc(&v.first_cause_text()),
            );
        }
    }

    /// "What went wrong" (docs/report.md#page): the verdicts, then the
    /// findings grouped by device and kind, the worst groups first, each
    /// group's first and last finding shown and the rest in a `details`;
    /// the first [`GROUPS_SHOWN`] groups open, the others one click away.
    fn findings(&self, p: &mut String) {
        /// One finding, with where it sorts, where its mark is and the
        /// axis of its recording.
        struct Line {
            key: (usize, u64, u64),
            axis: Axis,
            line: u64,
            finding: Finding,
            at: At,
        }
        /// The findings of one device (or bus) of one kind.
        struct Group {
            severity: Severity,
            lines: Vec<Line>,
        }
        p.push_str("<main>\n<section id=\"wrong\">\n<h2>What went wrong</h2>\n");
        self.verdicts(p);
        let mut groups: Vec<Group> = Vec::new();
        for (i, r) in self.recordings.iter().enumerate() {
            let axis = Self::axis_of(r);
            let mut of_recording: Vec<Group> = Vec::new();
            for finding in r.findings() {
                let at = r.timeline.place(&finding);
                // A device's finding points at its mark, a bus's at its line.
                let line = if finding.node.is_some() {
                    at.line
                } else {
                    finding.line
                };
                let place = of_recording.iter().position(|g| {
                    let f = &g.lines[0].finding;
                    f.bus == finding.bus
                        && f.node == finding.node
                        && group_kind(f.kind) == group_kind(finding.kind)
                });
                let item = Line {
                    key: (i, axis.key(at), line),
                    axis,
                    line,
                    finding,
                    at,
                };
                match place.map(|i| &mut of_recording[i]) {
                    Some(g) => {
                        g.severity = g.severity.min(item.finding.severity);
                        g.lines.push(item);
                    }
                    None => of_recording.push(Group {
                        severity: item.finding.severity,
                        lines: vec![item],
                    }),
                }
            }
            groups.extend(of_recording);
        }
        for g in &mut groups {
            g.lines.sort_by_key(|l| l.key);
        }
        groups.sort_by_key(|g| (g.severity, g.lines[0].key));
        let findings: u64 = groups
            .iter()
            .flat_map(|g| g.lines.iter())
            .map(|l| events_of(&l.finding))
            .sum();
        if groups.is_empty() {
            p.push_str(&self.nothing_wrong());
            p.push_str("</section>\n");
            return;
        }
        let _ = writeln!(
            p,
            "<p class=\"help\">{findings} finding{} in {} group{}, by device and kind, the worst first; each group shows its first and last, the rest one click away. Click one for its mark on the timeline.</p>",
            if findings == 1 { "" } else { "s" },
            groups.len(),
            if groups.len() == 1 { "" } else { "s" },
        );
        let item = |p: &mut String, l: &Line| {
            let f = &l.finding;
            let node = f
                .node
                .map_or_else(String::new, |n| format!(" data-node=\"{}\"", n.get()));
            let _ = write!(
                p,
                "<li data-line=\"{}\" data-iface=\"{}\"{node}{}><b>{}</b> {}",
                l.line,
                iface_attr(&f.bus),
                f.file
                    .as_deref()
                    .map_or_else(String::new, |file| format!(" data-file=\"{}\"", esc(file))),
                esc(&f.subject()),
                esc(&f.text())
            );
            // Where a list omitted entries, the timeline still has them;
            // a finding of one event says when it was.
            if f.is_omitted() {
                p.push_str(", the timeline shows every one");
            } else if !matches!(
                f.kind,
                FindingKind::Restarts | FindingKind::SdoBroken | FindingKind::SdoTimeout
            ) {
                let _ = write!(p, " ({})", l.axis.when_utc(l.at));
            }
            p.push_str("</li>\n");
        };
        let group = |p: &mut String, g: &Group| {
            let f = &g.lines[0].finding;
            let node = f
                .node
                .map_or_else(String::new, |n| format!(" data-node=\"{}\"", n.get()));
            let count = g.lines.len();
            // How many events: a finding that stands for entries a summary
            // list omitted counts them (docs/summary.md#lists).
            let events: u64 = g.lines.iter().map(|l| events_of(&l.finding)).sum();
            let _ = write!(
                p,
                "<li class=\"group\" data-iface=\"{}\"{node} data-kind=\"{}\" data-severity=\"{}\" data-count=\"{events}\"><span class=\"sev sev-{}\">{}</span> ",
                iface_attr(&f.bus),
                group_kind(f.kind),
                g.severity,
                g.severity,
                g.severity,
            );
            if count == 1 {
                p.push_str("<ul class=\"findings one\">\n");
                item(p, &g.lines[0]);
                p.push_str("</ul></li>\n");
                return;
            }
            let _ = writeln!(
                p,
                "<b>{}</b> {}: {events}, the first and the last",
                esc(&f.subject()),
                group_words(f.kind)
            );
            p.push_str("<ul class=\"findings\">\n");
            item(p, &g.lines[0]);
            if count > 2 {
                let _ = writeln!(
                    p,
                    "<li class=\"rest\"><details><summary>{} more between them</summary><ul class=\"findings\">",
                    events.saturating_sub(2)
                );
                for l in &g.lines[1..count - 1] {
                    item(p, l);
                }
                p.push_str("</ul></details></li>\n");
            }
            item(p, &g.lines[count - 1]);
            p.push_str("</ul></li>\n");
        };
        p.push_str("<ul class=\"groups\">\n");
        for g in groups.iter().take(GROUPS_SHOWN) {
            group(p, g);
        }
        p.push_str("</ul>\n");
        if groups.len() > GROUPS_SHOWN {
            let rest = &groups[GROUPS_SHOWN..];
            let _ = write!(
                p,
                "<details class=\"more-groups\"><summary>{} more groups ({} findings)</summary>\n<ul class=\"groups\">\n",
                rest.len(),
                rest.iter()
                    .flat_map(|g| g.lines.iter())
                    .map(|l| events_of(&l.finding))
                    .sum::<u64>()
            );
            for g in rest {
                group(p, g);
            }
            p.push_str("</ul>\n</details>\n");
        }
        p.push_str("</section>\n");
    }

    /// What "What went wrong" says when there is nothing to list: that the
    /// log is empty, that it has no CANopen device, or that nothing went
    /// wrong.
    fn nothing_wrong(&self) -> String {
        let frames: u64 = self
            .recordings
            .iter()
            .flat_map(|r| r.summary.buses.iter())
            .map(|b| b.frames)
            .sum();
        let devices: usize = self.recordings.iter().map(|r| r.summary.nodes.len()).sum();
        let ethercat: u64 = self
            .recordings
            .iter()
            .flat_map(|r| r.summary.ethercat.ports.iter())
            .map(|p| p.counts.packets)
            .sum();
        if devices == 0 && ethercat > 0 {
            format!("<p class=\"empty\" data-kind=\"ethercat\"><strong>No slave in trouble:</strong> {ethercat} EtherCAT packet{} read, and no slave reported an error emergency, an AL state with its error indicator, a CiA 402 fault or a servo fault; the timeline draws each cyclic stream's lost frames and working-counter mismatches.</p>\n", if ethercat == 1 { "" } else { "s" })
        } else if frames == 0 {
            "<p class=\"empty\" data-kind=\"empty\"><strong>The log is empty:</strong> no frame was read, so nothing can be said of the machine.</p>\n".to_owned()
        } else if devices == 0 {
            format!("<p class=\"empty\" data-kind=\"no_device\"><strong>No CANopen device in this log:</strong> {frames} frame{} read, none of them from or to a CANopen node (no EMCY, heartbeat, node guarding, PDO or SDO of a node-ID).</p>\n", if frames == 1 { "" } else { "s" })
        } else {
            "<p>No fault, error EMCY, restart, heartbeat timeout, SDO abort or bus error in this log.</p>\n".to_owned()
        }
    }

    fn timeline(&self, p: &mut String, budget: &Budget) {
        let several = self.recordings.len() > 1;
        p.push_str("<section id=\"timeline\">\n<h2>Timeline</h2>\n");
        if several {
            p.push_str("<p class=\"help\">One timeline per recording, each on its own axis: the logs were read apart. <span class=\"js\">Drag to pan, Ctrl + wheel or the buttons to zoom (every timeline at once), click a mark for its details.</span> Hover a mark or band for what it is.</p>\n");
        } else {
            p.push_str("<p class=\"help\">One axis for every row. <span class=\"js\">Drag to pan, Ctrl + wheel or the buttons to zoom, click a mark for its details.</span> Hover a mark or band for what it is.</p>\n");
        }
        p.push_str("<div class=\"tools js\"><button type=\"button\" data-zoom=\"in\">zoom in</button> <button type=\"button\" data-zoom=\"out\">zoom out</button> <button type=\"button\" data-zoom=\"reset\">whole log</button> <output id=\"details\"></output></div>\n");
        let groups: Vec<&[Recording]> = if several {
            self.recordings.chunks(1).collect()
        } else {
            vec![&self.recordings[..]]
        };
        for (i, recordings) in groups.into_iter().enumerate() {
            let axis = Self::span_axis(recordings);
            let file = recordings
                .first()
                .and_then(|r| r.summary.file.as_deref())
                .map_or_else(String::new, |f| format!(" data-file=\"{}\"", esc(f)));
            if several {
                let name = recordings[0].summary.file.as_deref().unwrap_or("");
                let _ = writeln!(
                    p,
                    "<h3 class=\"recording\"{file}>{}: {}</h3>",
                    esc(name),
                    axis_words(&axis)
                );
            }
            self.timeline_svg(p, recordings, &axis, budget, i == 0, &file);
        }
        legend(p);
        p.push_str("</section>\n");
    }

    /// One timeline: the rows of `recordings` on `axis`; the first writes
    /// the shapes the others use.
    fn timeline_svg(
        &self,
        p: &mut String,
        recordings: &[Recording],
        axis: &Axis,
        budget: &Budget,
        first: bool,
        file_attr: &str,
    ) {
        // Rows: per recording, per bus, the bus row then its devices.
        let mut body = String::new();
        let mut y = AXIS + 4.0;
        for r in recordings {
            let file = r
                .summary
                .file
                .as_deref()
                .map_or_else(String::new, |f| format!(" data-file=\"{}\"", esc(f)));
            let end = r.timeline.span().map_or(At::default(), |(_, last)| last);
            for b in &r.summary.buses {
                let data = r.timeline.rows(&b.bus);
                let h = 40.0;
                let _ = write!(
                    body,
                    "<g class=\"row bus\" data-row=\"bus\" data-iface=\"{}\"{file} transform=\"translate(0,{y})\">\n<text class=\"label\" x=\"8\" y=\"16\">bus {}</text><text class=\"sub\" x=\"8\" y=\"30\">{} frames</text>\n<g class=\"plot\" clip-path=\"url(#clip)\">\n",
                    iface_attr(&b.bus),
                    esc(&b.bus.to_string()),
                    b.frames
                );
                if let Some(data) = data {
                    rate(&mut body, axis, &data.row.rate, h);
                    for kind in MarkKind::BUS {
                        marks(
                            &mut body,
                            axis,
                            budget,
                            &data.row,
                            kind,
                            None,
                            Profile::Generic,
                        );
                    }
                }
                body.push_str("</g>\n</g>\n");
                y += h + 4.0;
                for n in r.summary.nodes.iter().filter(|n| n.bus == b.bus) {
                    let row = data.and_then(|d| d.node_row(n.node));
                    let h = node_row(&mut body, axis, budget, n, row, &file, y, end);
                    y += h + 4.0;
                }
            }
            // Each EtherCAT interface: its slaves, then its streams.
            let ethercat = &r.summary.ethercat;
            for port in &ethercat.ports {
                let rows = r.timeline.port(&port.iface);
                let slaves = ethercat.slaves.iter().filter(|s| s.iface == port.iface);
                for (place, s) in slaves.enumerate() {
                    let row = rows.and_then(|rows| rows.slave_row(place));
                    let h = slave_row(&mut body, axis, budget, s, row, &file, y, end);
                    y += h + 4.0;
                }
                for s in ethercat.streams.iter().filter(|s| s.iface == port.iface) {
                    let row = rows.and_then(|rows| rows.stream_row(s.command, s.address));
                    let h = stream_row(&mut body, axis, budget, s, row, &file, y);
                    y += h + 4.0;
                }
            }
        }
        let height = y + 4.0;
        let _ = writeln!(
            p,
            "<svg class=\"tl\"{} viewBox=\"0 0 {WIDTH} {height}\" width=\"{WIDTH}\" height=\"{height}\" role=\"img\" aria-label=\"timeline\" data-left=\"{LEFT}\" data-plot=\"{PLOT}\"{}{file_attr}>",
            if first { " id=\"timeline-svg\"" } else { "" },
            axis.attrs()
        );
        if first {
            defs(p);
        }
        axis_ticks(p, axis, height);
        p.push_str(&body);
        p.push_str("</svg>\n");
    }

    fn signals(&self, p: &mut String, budget: &Budget) {
        p.push_str("<section id=\"signals\">\n<h2>Drive signals</h2>\n");
        let mut any = false;
        for r in &self.recordings {
            let end = r.timeline.span().map_or(At::default(), |(_, last)| last);
            let axis = if self.recordings.len() > 1 {
                Self::axis_of(r)
            } else {
                self.axis()
            };
            let mut charted = Vec::new();
            for n in &r.summary.nodes {
                if let Some(row) = r.timeline.rows(&n.bus).and_then(|b| b.node_row(n.node)) {
                    charted.push(Charted::node(n, row));
                }
            }
            // Each EtherCAT interface's slaves, as the timeline has them.
            let ethercat = &r.summary.ethercat;
            for port in &ethercat.ports {
                let Some(rows) = r.timeline.port(&port.iface) else {
                    continue;
                };
                let slaves = ethercat.slaves.iter().filter(|s| s.iface == port.iface);
                for (place, s) in slaves.enumerate() {
                    if let Some(row) = rows.slave_row(place) {
                        charted.push(Charted::slave(s, row));
                    }
                }
            }
            for who in charted.iter().filter(|who| who.any()) {
                any = true;
                chart(p, &axis, budget, who, end);
            }
        }
        if !any {
            p.push_str(
                "<p>No drive in this log: no CiA 402 state, position or velocity, no servo's ActPos or speed set point to chart.</p>\n",
            );
        }
        p.push_str("</section>\n");
    }

    fn tables(&self, p: &mut String) {
        p.push_str("<section id=\"devices\">\n<h2>Devices</h2>\n<p class=\"help\">The facts of <code>motionwire decode --summary</code>, one row per device and per bus.</p>\n<table class=\"summary\">\n<thead><tr><th>device</th><th>frames</th><th>EMCY</th><th>first error</th><th>active error</th><th>heartbeat</th><th>guarding</th><th>SDO</th><th>CiA 402</th></tr></thead>\n<tbody>\n");
        for r in &self.recordings {
            let prefix = r
                .summary
                .file
                .as_deref()
                .map_or_else(String::new, |f| format!("{f}: "));
            for n in &r.summary.nodes {
                node_table_row(p, &prefix, n);
            }
        }
        p.push_str("</tbody>\n</table>\n<table class=\"summary\">\n<thead><tr><th>bus</th><th>frames</th><th>error frames</th><th>bus-off</th><th>error-passive</th><th>status events</th><th>from</th><th>to</th><th>nodes</th></tr></thead>\n<tbody>\n");
        for r in &self.recordings {
            for b in &r.summary.buses {
                let ts = |t: Option<crate::can::Timestamp>| {
                    t.map_or_else(|| "–".to_owned(), |t| format!("{}", t.seconds()))
                };
                let nodes: Vec<u8> = b.nodes.iter().map(|n| n.get()).collect();
                let _ = writeln!(
                    p,
                    "<tr data-iface=\"{}\"><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                    iface_attr(&b.bus),
                    esc(r.summary.file.as_deref().map_or("", |f| f)),
                    esc(&b.bus.to_string()),
                    b.frames,
                    b.error_frames,
                    listed_lines_or_none(&b.bus_off),
                    listed_lines_or_none(&b.error_passive),
                    b.status_events,
                    ts(b.first_timestamp),
                    ts(b.last_timestamp),
                    lines(&nodes)
                );
            }
        }
        p.push_str("</tbody>\n</table>\n</section>\n");
    }

    fn events(&self, p: &mut String, budget: &Budget) {
        struct Row {
            /// The recording, the place, the line and the row's number:
            /// rows at one place stay in the order they were made.
            key: (usize, u64, u64, usize),
            axis: Axis,
            /// Its device's (or bus's, slave's, stream's) place in `names`.
            who: usize,
            kind: MarkKind,
            mark: Drawn,
            profile: Profile,
            /// Set on a row that stands for every EMCY of one code of its
            /// device.
            code: Option<u16>,
        }
        let mut all: Vec<Row> = Vec::new();
        let mut total = 0usize;
        // Only the first rows are written: whenever many are kept, the
        // first of them are, so that a storm of distinct codes stays small.
        let keep_first = |all: &mut Vec<Row>| {
            if all.len() >= 4 * EVENT_ROWS {
                all.select_nth_unstable_by_key(EVENT_ROWS, |r| r.key);
                all.truncate(EVENT_ROWS);
            }
        };
        // The devices' and buses' names and attributes, once each: a storm
        // of distinct codes is many rows of few devices.
        let mut names: Vec<(String, String)> = Vec::new();
        let (mut timed, mut unix) = (false, false);
        for (i, r) in self.recordings.iter().enumerate() {
            let axis = if self.recordings.len() > 1 {
                Self::axis_of(r)
            } else {
                self.axis()
            };
            let axis = &axis;
            timed |= axis.timed;
            unix |= axis.is_unix();
            let prefix = r
                .summary
                .file
                .as_deref()
                .map_or_else(String::new, |f| format!("{f}: "));
            // Every row: its name, its attributes, its profile, its data.
            let mut rows: Vec<(String, String, Profile, &RowData)> = Vec::new();
            for bus in &r.timeline.buses {
                let iface = format!(" data-iface=\"{}\"", iface_attr(&bus.name));
                rows.push((
                    format!("{prefix}bus {}", bus.name),
                    iface.clone(),
                    Profile::Generic,
                    &bus.row,
                ));
                for n in &r.summary.nodes {
                    if n.bus == bus.name {
                        if let Some(row) = bus.node_row(n.node) {
                            rows.push((
                                format!("{prefix}{}", device(&bus.name, n.node)),
                                format!("{iface} data-node=\"{}\"", n.node.get()),
                                n.profile,
                                row,
                            ));
                        }
                    }
                }
            }
            for (owner, row) in ethercat_rows(r) {
                let (name, attrs, profile) = match owner {
                    Ethercat::Slave(s) => (
                        slave_name(s),
                        format!(
                            " data-iface=\"{}\" data-slave=\"{}\"",
                            iface_attr(&s.iface),
                            s.station.map_or_else(String::new, |st| st.to_string())
                        ),
                        s.emergencies
                            .first()
                            .map_or(Profile::Generic, |e| e.profile),
                    ),
                    Ethercat::Stream(s) => (
                        format!("{} stream {}", s.iface, s.key()),
                        format!(
                            " data-iface=\"{}\" data-stream=\"{}\"",
                            iface_attr(&s.iface),
                            esc(&s.key())
                        ),
                        Profile::Generic,
                    ),
                };
                rows.push((format!("{prefix}{name}"), attrs, profile, row));
            }
            for (name, attrs, profile, row) in rows {
                names.push((name, attrs));
                let who = names.len() - 1;
                for kind in MarkKind::ALL {
                    let marks = drawn_marks(axis, &row.marks[kind as usize], budget.radius);
                    let emcy = matches!(
                        kind,
                        MarkKind::Emcy | MarkKind::EmcyReset | MarkKind::CoeEmcy
                    );
                    if emcy && marks.iter().any(|m| m.count > 1) {
                        // A cluster would hide the codes in it: the
                        // row's EMCYs of this kind one row per code
                        // (a CAN device's resets apart).
                        let reset = kind == MarkKind::EmcyReset;
                        for (&code, run) in &row.codes {
                            if kind != MarkKind::CoeEmcy && ErrorCode::new(code).is_reset() != reset
                            {
                                continue;
                            }
                            let mark = Drawn {
                                at: run.first,
                                end: run.last,
                                count: run.count,
                                detail: run.detail,
                            };
                            total += 1;
                            keep_first(&mut all);
                            all.push(Row {
                                key: (i, axis.key(mark.at), mark.at.line, total),
                                axis: *axis,
                                who,
                                kind,
                                mark,
                                profile,
                                code: Some(code),
                            });
                        }
                        continue;
                    }
                    for mark in marks {
                        total += 1;
                        keep_first(&mut all);
                        all.push(Row {
                            key: (i, axis.key(mark.at), mark.at.line, total),
                            axis: *axis,
                            who,
                            kind,
                            mark,
                            profile,
                            code: None,
                        });
                    }
                }
            }
        }
        if all.len() > EVENT_ROWS {
            all.select_nth_unstable_by_key(EVENT_ROWS, |r| r.key);
            all.truncate(EVENT_ROWS);
        }
        all.sort_by_key(|r| r.key);
        let _ = write!(
            p,
            "<section id=\"events\">\n<h2>Events</h2>\n<p class=\"help\">Every mark of the timeline in {} order, with its line{}.</p>\n<table class=\"events\">\n<thead><tr><th>line</th><th>{}</th><th>device</th><th>event</th><th>count</th><th>what</th></tr></thead>\n<tbody>\n",
            if timed { "time" } else { "line" },
            if total > EVENT_ROWS {
                format!("; the first {EVENT_ROWS} of {total}")
            } else {
                String::new()
            },
            if unix {
                "time</th><th>UTC"
            } else if timed {
                "time"
            } else {
                ""
            },
        );
        for row in all.iter().take(EVENT_ROWS) {
            let m = row.mark;
            let lines = if m.count > 1 {
                format!("{}–{}", m.at.line, m.end.line)
            } else {
                m.at.line.to_string()
            };
            let axis = &row.axis;
            let mut what = mark_text(row.kind, &m, axis, row.profile);
            let mut code = String::new();
            if let (Some(c), true) = (row.code, m.count > 1) {
                let words = format!("{} {}s, ", m.count, row.kind.words());
                what = what.replacen(
                    &words,
                    &format!(
                        "{} {}s of code {}, ",
                        m.count,
                        row.kind.words(),
                        ErrorCode::new(c)
                    ),
                    1,
                );
            }
            if let Some(c) = row.code {
                let _ = write!(code, " data-code=\"{c}\"");
            }
            let when = match (unix, axis.is_unix(), timed) {
                (true, true, _) => format!("{}</td><td>{}", axis.when(m.at), utc(m.at.t)),
                (true, false, _) => format!("{}</td><td>", axis.when(m.at)),
                (false, _, true) => axis.when(m.at),
                (false, _, false) => String::new(),
            };
            let _ = writeln!(
                p,
                "<tr data-line=\"{}\"{}{code}><td>{lines}</td><td>{when}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                m.at.line,
                names[row.who].1,
                esc(&names[row.who].0),
                row.kind.words(),
                m.count,
                esc(&what)
            );
        }
        p.push_str("</tbody>\n</table>\n</section>\n</main>\n");
    }

    /// The summary records, exactly those of `decode --summary --json`, as
    /// one JSON array; `<` written as `\u003c` so that no text in them can
    /// end the script element (docs/report.md#contract).
    fn summary_json(&self, out: &mut impl Write) -> io::Result<()> {
        let mut json: Vec<u8> = Vec::with_capacity(1 << 14);
        json.push(b'[');
        let mut first = true;
        for r in &self.recordings {
            for record in r.summary.records() {
                if !first {
                    json.push(b',');
                }
                first = false;
                record.write_json(&mut json)?;
            }
            for span in &r.files {
                if !first {
                    json.push(b',');
                }
                first = false;
                serde_json::to_writer(&mut json, span).map_err(io::Error::from)?;
            }
        }
        json.push(b']');
        let mut start = 0;
        for (i, &b) in json.iter().enumerate() {
            if b == b'<' {
                out.write_all(&json[start..i])?;
                out.write_all(b"\\u003c")?;
                start = i + 1;
            }
        }
        out.write_all(&json[start..])
    }
}

/// An EtherCAT row of the timeline: a slave's or a stream's.
enum Ethercat<'r> {
    Slave(&'r SlaveSummary),
    Stream(&'r StreamSummary),
}

/// The EtherCAT rows a recording's timeline draws, in its order: per
/// interface, its slaves, then its streams (docs/report.md#ethercat).
fn ethercat_rows(r: &Recording) -> Vec<(Ethercat<'_>, &RowData)> {
    let ethercat = &r.summary.ethercat;
    let mut rows = Vec::new();
    for port in &ethercat.ports {
        let Some(data) = r.timeline.port(&port.iface) else {
            continue;
        };
        let slaves = ethercat.slaves.iter().filter(|s| s.iface == port.iface);
        for (place, s) in slaves.enumerate() {
            if let Some(row) = data.slave_row(place) {
                rows.push((Ethercat::Slave(s), row));
            }
        }
        for s in ethercat.streams.iter().filter(|s| s.iface == port.iface) {
            if let Some(row) = data.stream_row(s.command, s.address) {
                rows.push((Ethercat::Stream(s), row));
            }
        }
    }
    rows
}

/// Lines as `12, 40, 41`, the first 20 of a longer list and how many more.
fn lines<T: std::fmt::Display>(list: &[T]) -> String {
    let mut out = String::new();
    for (i, l) in list.iter().enumerate().take(20) {
        if i > 0 {
            out.push_str(", ");
        }
        let _ = write!(out, "{l}");
    }
    if list.len() > 20 {
        let _ = write!(out, " … ({} more)", list.len() - 20);
    }
    out
}

/// The lines of a summary list, with how many it omitted between its
/// first and its last (docs/summary.md#lists), as the text summary writes
/// them.
fn listed_lines<T: std::fmt::Display>(list: &Listed<T>) -> String {
    let mut out = String::new();
    for item in items(list) {
        let _ = match item {
            Item::Kept(l) if out.is_empty() => write!(out, "{l}"),
            Item::Kept(l) => write!(out, ", {l}"),
            Item::Omitted(more) => write!(out, ", … {more} more …"),
        };
    }
    out
}

fn listed_lines_or_none(list: &Listed<u64>) -> String {
    if list.is_empty() {
        "none".to_owned()
    } else {
        listed_lines(list)
    }
}

/// An entry a summary list keeps, or the entries it omitted: how many,
/// and the last entry kept before them (docs/summary.md#lists).
enum Item<'a, T> {
    Kept(&'a T),
    Omitted(u64),
}

/// The entries a summary list keeps, in order, with its omitted ones in
/// their place.
fn items<T>(list: &Listed<T>) -> impl Iterator<Item = Item<'_, T>> {
    let omitted = match list.omitted() {
        0 => None,
        n => Some(Item::Omitted(n)),
    };
    list.head()
        .iter()
        .map(Item::Kept)
        .chain(omitted)
        .chain(list.tail().map(Item::Kept))
}

/// One device's row of the summary table.
fn node_table_row(p: &mut String, prefix: &str, n: &NodeSummary) {
    let frames: Vec<String> = n
        .frames
        .iter()
        .filter(|(_, c)| *c > 0)
        .map(|(k, c)| format!("{k} {c}"))
        .collect();
    let seen = |s: Option<crate::summary::EmcySeen>| {
        s.map_or_else(
            || "none".to_owned(),
            |s| {
                format!(
                    "{} {}{} (line {})",
                    s.code,
                    esc(s.code.description()),
                    esc(&s.reading(n.profile).to_string()),
                    s.line
                )
            },
        )
    };
    let hb = &n.heartbeat;
    let mut heartbeat = format!(
        "{} heartbeats, last {}",
        hb.count,
        hb.last_state.map_or("–", |s| s.state_name())
    );
    if !hb.boot_ups.is_empty() {
        let _ = write!(
            heartbeat,
            "; boot-ups at lines {}",
            listed_lines(&hb.boot_ups)
        );
    }
    match &hb.timeouts {
        Timeouts::NotAsked => {}
        Timeouts::NotChecked => heartbeat.push_str("; timeouts not checked (no timestamps)"),
        Timeouts::Checked(gaps) if gaps.is_empty() => heartbeat.push_str("; no timeouts"),
        Timeouts::Checked(gaps) => {
            let _ = write!(heartbeat, "; {} timeouts", gaps.count());
        }
    }
    let g = &n.guarding;
    let guarding = if g.answers == 0 && g.toggle_errors.is_empty() {
        "–".to_owned()
    } else {
        format!(
            "{} answers, wrong toggle at lines {}",
            g.answers,
            listed_lines_or_none(&g.toggle_errors)
        )
    };
    let s = &n.sdo;
    let sdo = if s.is_empty() {
        "–".to_owned()
    } else {
        let mut t = format!(
            "{} requests, {} transfers, {} aborts",
            s.requests,
            s.transfers,
            s.aborts.count()
        );
        if !s.broken.is_empty() {
            let _ = write!(t, ", broken at lines {}", listed_lines(&s.broken));
        }
        if !s.timeouts.is_empty() {
            let _ = write!(t, ", unanswered at lines {}", listed_lines(&s.timeouts));
        }
        if let Some(l) = s.latency {
            let _ = write!(
                t,
                "; latency median {:.3} ms, max {:.3} ms",
                l.median.as_secs_f64() * 1000.0,
                l.max.as_secs_f64() * 1000.0
            );
        }
        t
    };
    let cia402 = match &n.cia402 {
        None => "–".to_owned(),
        Some(c) if !c.observed() => "no statusword seen".to_owned(),
        Some(c) => format!(
            "{} states, last {}, {} faults",
            c.transitions.count(),
            c.last_state().map_or("–", |s| s.name()),
            c.faults.as_ref().map_or(0, Listed::count)
        ),
    };
    let _ = writeln!(
        p,
        "<tr data-iface=\"{}\" data-node=\"{}\"><td>{}{}</td><td>{}</td><td>{} (resets {})</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
        iface_attr(&n.bus),
        n.node.get(),
        esc(prefix),
        esc(&device(&n.bus, n.node)),
        esc(&frames.join(", ")),
        n.emcy,
        n.resets,
        seen(n.first_error),
        seen(n.active_error),
        esc(&heartbeat),
        esc(&guarding),
        esc(&sdo),
        esc(&cia402)
    );
}

/// The group a finding of `kind` is in: a device's first error and first
/// warning are one group, its first EMCYs.
fn group_kind(kind: FindingKind) -> &'static str {
    match kind {
        FindingKind::FirstWarning => FindingKind::FirstError.name(),
        kind => kind.name(),
    }
}

/// A group's kind in words, plural.
fn group_words(kind: FindingKind) -> &'static str {
    match kind {
        FindingKind::FirstError | FindingKind::FirstWarning => "first warning and first error",
        FindingKind::Cia402Fault => "CiA 402 faults",
        FindingKind::Restarts => "restarts",
        FindingKind::HeartbeatTimeout => "heartbeat timeouts",
        FindingKind::SdoAbort => "SDO aborts",
        FindingKind::SdoBroken => "broken SDO transfers",
        FindingKind::SdoTimeout => "unanswered SDO requests",
        FindingKind::ToggleError => "guarding toggle errors",
        FindingKind::BusOff => "bus-offs",
        FindingKind::ErrorPassive => "error-passives",
        FindingKind::AlError => "AL errors",
        FindingKind::ServoFault => "servo faults",
    }
}

/// What an axis spans, in words: `from 2023-11-14 22:13:20.000526 UTC, for
/// 9.991137 s`, `lines 1 to 40`.
fn axis_words(axis: &Axis) -> String {
    if !axis.timed {
        return format!("lines {} to {}", axis.start, axis.end);
    }
    let start = if axis.is_unix() {
        utc(axis.start)
    } else {
        format!("{} s (the log's own clock)", seconds(axis.start))
    };
    format!("from {start}, for {} s", seconds(axis.end - axis.start))
}

/// How many events a finding stands for: one, or the entries a summary
/// list omitted where it stands for them.
fn events_of(finding: &Finding) -> u64 {
    match finding.detail {
        FindingDetail::Omitted(n) => n,
        _ => 1,
    }
}
