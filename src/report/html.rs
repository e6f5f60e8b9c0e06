//! The page (docs/report.md#page): plain writes of HTML and SVG, one pass
//! over the recordings. Everything that means something carries its data:
//! rows, bands and marks their `data-*` attributes and a `<title>`
//! (docs/report.md#contract).

use std::fmt::Write as _;
use std::io::{self, Write};

use crate::canopen::{ErrorCode, NmtStateByte, NodeId};
use crate::decoder::BusName;
use crate::summary::{NodeSummary, Timeouts};

use super::series::{At, BandItem, Detail, MarkItem, Series};
use super::{cia402_state, BusRows, MarkKind, Recording, RowData, CHARTED};

/// The SVG's width: labels, then the plot.
const WIDTH: f64 = 1200.0;
/// Where the plot begins.
const LEFT: f64 = 170.0;
/// The plot's default width in pixels: "within a pixel" for clusters
/// (docs/report.md#clusters) is a pixel of it.
const PLOT: f64 = 1000.0;
/// The axis's height.
const AXIS: f64 = 26.0;
/// The most rows of the event table (docs/report.md#tables).
const EVENT_ROWS: usize = 2000;
/// The most items of one list of "What went wrong".
const LIST_ITEMS: usize = 50;
/// More bands than this on a row: neighbours narrower than a pixel merge.
const EXACT_BANDS: usize = 500;
/// The most marks a page draws: beyond, neighbours cluster within as many
/// pixels (a power of two) as keep them to this (docs/report.md#clusters).
const MARK_BUDGET: usize = 20_000;
/// The most bands a page draws: beyond, neighbouring bands narrower than
/// as many pixels as keep them to this merge.
const BAND_BUDGET: usize = 10_000;
/// Marks and bands have a `<title>` while a page has at most this many
/// (the script shows the same words from their `data-*`).
const TITLE_BUDGET: usize = 5_000;

/// How a page draws its marks and bands, to stay small whatever the log
/// (docs/report.md#size).
#[derive(Debug, Clone, Copy)]
struct Budget {
    /// `None`: each series as docs/report.md#clusters says; else every
    /// series clustered within this many pixels.
    radius: Option<f64>,
    /// Bands narrower than this many pixels merge with their neighbours
    /// (`None`: only on rows of more than 500).
    band_px: Option<f64>,
    titles: bool,
}

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

/// The shared axis: time in microseconds, or lines.
#[derive(Debug, Clone, Copy)]
struct Axis {
    timed: bool,
    start: u64,
    end: u64,
}

impl Axis {
    fn key(&self, at: At) -> u64 {
        at.key(self.timed)
    }

    /// The x of a place, in the default view.
    fn x(&self, at: At) -> f64 {
        self.x_of(self.key(at))
    }

    fn x_of(&self, key: u64) -> f64 {
        let span = (self.end - self.start).max(1) as f64;
        LEFT + (key.saturating_sub(self.start) as f64 / span) * PLOT
    }

    /// A pixel of the default view, in the axis's unit.
    fn pixel(&self) -> f64 {
        (self.end - self.start).max(1) as f64 / PLOT
    }

    /// A place as the page writes it: `+2.003641 s` or `line 613`.
    fn when(&self, at: At) -> String {
        if self.timed {
            format!("+{} s", seconds(at.t.saturating_sub(self.start)))
        } else {
            format!("line {}", at.line)
        }
    }
}

/// Microseconds as seconds with six decimals.
fn seconds(us: u64) -> String {
    format!("{}.{:06}", us / 1_000_000, us % 1_000_000)
}

/// Escape text for HTML text and quoted attributes.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A date and time of the Unix epoch in UTC, `2023-11-14 22:13:20.000526 UTC`
/// (days to civil date: H. Hinnant's algorithm).
fn utc(us: u64) -> String {
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

/// A device as the page names it: `can0 node 3`.
fn device(bus: &BusName, node: NodeId) -> String {
    match bus {
        BusName::Unnamed => format!("node {}", node.get()),
        _ => format!("{bus} node {}", node.get()),
    }
}

fn iface_attr(bus: &BusName) -> String {
    match bus {
        BusName::Unnamed => String::new(),
        bus => esc(&bus.to_string()),
    }
}

fn nmt_name(state: u8) -> &'static str {
    NmtStateByte::new(state).state_name()
}

fn cia402_name(state: u8) -> &'static str {
    cia402_state(state).map_or("unknown", |s| s.name())
}

/// A mark as drawn: one event, or a cluster of neighbours.
#[derive(Debug, Clone, Copy)]
struct Drawn {
    at: At,
    end: At,
    count: u64,
    detail: Detail,
}

/// The marks of a series as drawn: one by one up to 500, else neighbours
/// within a pixel of the default width as one cluster
/// (docs/report.md#clusters).
fn drawn_marks(axis: &Axis, series: &Series<MarkItem>, radius: Option<f64>) -> Vec<Drawn> {
    let mut items: Vec<MarkItem> = series.items().to_vec();
    let key = |m: &MarkItem| (axis.key(m.at), m.at.line);
    if !items.windows(2).all(|w| key(&w[0]) <= key(&w[1])) {
        items.sort_by_key(key);
    }
    if series.is_exact() && radius.is_none() {
        return items
            .into_iter()
            .map(|m| Drawn {
                at: m.at,
                end: m.end,
                count: m.count,
                detail: m.detail,
            })
            .collect();
    }
    let pixel = axis.pixel() * radius.unwrap_or(1.0);
    let mut out: Vec<Drawn> = Vec::new();
    for m in items {
        if let Some(last) = out.last_mut() {
            let gap = axis.key(m.at).saturating_sub(axis.key(last.end)) as f64;
            if gap <= pixel {
                last.count += m.count;
                if axis.key(m.end) > axis.key(last.end) {
                    last.end = m.end;
                }
                if m.end.line > last.end.line {
                    last.end.line = m.end.line;
                }
                continue;
            }
        }
        out.push(Drawn {
            at: m.at,
            end: m.end,
            count: m.count,
            detail: m.detail,
        });
    }
    out
}

/// A band as drawn, up to where the next begins.
#[derive(Debug, Clone, Copy)]
struct DrawnBand {
    item: BandItem,
    x0: f64,
    x1: f64,
}

/// The bands of a series up to `end`; more than 500 on a row: consecutive
/// bands narrower than a pixel merge into one (docs/report.md#bands).
fn drawn_bands(
    axis: &Axis,
    series: &Series<BandItem>,
    end: At,
    band_px: Option<f64>,
) -> Vec<DrawnBand> {
    let items = series.items();
    let mut out: Vec<DrawnBand> = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        let next = items.get(i + 1).map_or(end, |n| n.at);
        let x0 = axis.x(item.at);
        let x1 = axis.x(next).max(x0);
        out.push(DrawnBand {
            item: *item,
            x0,
            x1,
        });
    }
    if out.len() <= EXACT_BANDS && band_px.is_none() {
        return out;
    }
    let px = band_px.unwrap_or(1.0);
    let mut merged: Vec<DrawnBand> = Vec::new();
    for band in out {
        if let Some(last) = merged.last_mut() {
            if last.x1 - last.x0 < px && band.x1 - band.x0 < px {
                last.item.count += band.item.count;
                last.item.last_state = band.item.last_state;
                last.x1 = band.x1;
                continue;
            }
        }
        merged.push(band);
    }
    merged
}

/// One line of "What went wrong", with where it sorts.
struct Finding {
    key: (u64, u64),
    line: u64,
    iface: String,
    node: Option<u8>,
    text: String,
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

    /// The shared axis: by time when every recording is, else by line.
    fn axis(&self) -> Axis {
        let timed =
            !self.recordings.is_empty() && self.recordings.iter().all(|r| r.timeline.is_timed());
        let mut start = u64::MAX;
        let mut end = 0;
        for r in &self.recordings {
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

    /// Every row drawn: its recording's end and data.
    fn all_rows(&self) -> Vec<(At, &RowData)> {
        let mut rows = Vec::new();
        for r in &self.recordings {
            let end = r.timeline.span().map_or(At::default(), |(_, last)| last);
            for bus in &r.timeline.buses {
                rows.push((end, &bus.row));
                for n in r.summary.nodes.iter().filter(|n| n.bus == bus.name) {
                    if let Some(row) = bus.node_row(n.node) {
                        rows.push((end, row));
                    }
                }
            }
        }
        rows
    }

    /// How many marks and bands the page would draw, and how to keep them
    /// within the budgets (docs/report.md#size).
    fn budget(&self, axis: &Axis) -> Budget {
        let rows = self.all_rows();
        let count_marks = |radius: Option<f64>| -> usize {
            rows.iter()
                .flat_map(|(_, row)| row.marks.iter())
                .filter(|s| s.len() > 0)
                .map(|s| drawn_marks(axis, s, radius).len())
                .sum()
        };
        let count_bands = |px: Option<f64>| -> usize {
            rows.iter()
                .flat_map(|(end, row)| [(end, &row.nmt), (end, &row.cia402)])
                .map(|(end, s)| drawn_bands(axis, s, *end, px).len())
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
        let budget = self.budget(&axis);
        let mut page = String::with_capacity(1 << 16);
        self.head(&mut page, &axis);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.findings(&mut page, &axis);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.timeline(&mut page, &axis, &budget);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.signals(&mut page, &axis, &budget);
        self.tables(&mut page);
        out.write_all(page.as_bytes())?;
        page.clear();
        self.events(&mut page, &axis, &budget);
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
        if axis.timed {
            let start = if axis.start >= 1_000_000_000_000_000 {
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

    /// The time of a summary line on a row, where a mark of `kind` holds it.
    fn at_of(rows: Option<&RowData>, kind: MarkKind, line: u64) -> At {
        let found = rows.and_then(|row| {
            let items = row.marks[kind as usize].items();
            items
                .iter()
                .find(|m| m.at.line == line)
                .or_else(|| items.iter().rev().find(|m| m.at.line <= line))
                .map(|m| m.at)
        });
        found.unwrap_or(At { t: 0, line })
    }

    fn findings(&self, p: &mut String, axis: &Axis) {
        p.push_str("<main>\n<section id=\"wrong\">\n<h2>What went wrong</h2>\n");
        let mut faults: Vec<Finding> = Vec::new();
        let mut restarts: Vec<Finding> = Vec::new();
        let mut timeouts: Vec<Finding> = Vec::new();
        let mut aborts: Vec<Finding> = Vec::new();
        let mut transfers: Vec<Finding> = Vec::new();
        let mut toggles: Vec<Finding> = Vec::new();
        let mut bus_errors: Vec<Finding> = Vec::new();
        for r in &self.recordings {
            let prefix = r
                .summary
                .file
                .as_deref()
                .map_or_else(String::new, |f| format!("{f}: "));
            for n in &r.summary.nodes {
                let rows = r.timeline.rows(&n.bus).and_then(|b| b.node_row(n.node));
                let who = format!("{prefix}{}", device(&n.bus, n.node));
                let push = |list: &mut Vec<Finding>, at: At, text: String| {
                    list.push(Finding {
                        key: (axis.key(at), at.line),
                        line: at.line,
                        iface: iface_attr(&n.bus),
                        node: Some(n.node.get()),
                        text: format!("<b>{}</b> {}", esc(&who), text),
                    });
                };
                if let Some(first) = n.first_error {
                    let at = At {
                        t: first.ts.map_or(0, super::micros),
                        line: first.line,
                    };
                    push(
                        &mut faults,
                        at,
                        format!(
                            "first error: EMCY {} {} at line {} ({})",
                            first.code,
                            esc(first.code.description()),
                            first.line,
                            axis.when(at)
                        ),
                    );
                }
                for fault in n.cia402.iter().flat_map(|c| c.faults.iter().flatten()) {
                    let t = fault.transition;
                    let at = At {
                        t: t.ts.map_or(0, super::micros),
                        line: t.line,
                    };
                    push(
                        &mut faults,
                        at,
                        format!("{} ({})", esc(&fault.to_string()), axis.when(at)),
                    );
                }
                let boots = &n.heartbeat.boot_ups;
                if boots.len() > 1 {
                    let at = Self::at_of(rows, MarkKind::BootUp, boots[1]);
                    let times = boots.len() - 1;
                    push(
                        &mut restarts,
                        at,
                        format!(
                            "restarted {times} time{} (boot-ups at lines {})",
                            if times == 1 { "" } else { "s" },
                            lines(boots)
                        ),
                    );
                }
                if let Timeouts::Checked(gaps) = &n.heartbeat.timeouts {
                    for gap in gaps {
                        let at = Self::at_of(rows, MarkKind::HeartbeatTimeout, gap.after_line);
                        push(
                            &mut timeouts,
                            at,
                            format!(
                                "no heartbeat for {} ms after line {} ({})",
                                gap.gap_ms(),
                                gap.after_line,
                                axis.when(at)
                            ),
                        );
                    }
                }
                for abort in &n.sdo.aborts {
                    let at = Self::at_of(rows, MarkKind::SdoAbort, abort.line);
                    push(
                        &mut aborts,
                        at,
                        format!(
                            "line {}: {} ({})",
                            abort.line,
                            esc(&abort.to_string()),
                            axis.when(at)
                        ),
                    );
                }
                for &line in &n.sdo.broken {
                    let at = Self::at_of(rows, MarkKind::SdoBroken, line);
                    push(
                        &mut transfers,
                        at,
                        format!("broken SDO transfer starting at line {line}"),
                    );
                }
                for &line in &n.sdo.timeouts {
                    let at = Self::at_of(rows, MarkKind::SdoTimeout, line);
                    push(
                        &mut transfers,
                        at,
                        format!("unanswered SDO request at line {line}"),
                    );
                }
                for &line in &n.guarding.toggle_errors {
                    let at = Self::at_of(rows, MarkKind::ToggleError, line);
                    push(
                        &mut toggles,
                        at,
                        format!(
                            "node-guarding answer with a wrong toggle at line {line} ({})",
                            axis.when(at)
                        ),
                    );
                }
            }
            for b in &r.summary.buses {
                let rows = r.timeline.rows(&b.bus).map(|rows| &rows.row);
                for (kind, list) in [
                    (MarkKind::BusOff, &b.bus_off),
                    (MarkKind::ErrorPassive, &b.error_passive),
                ] {
                    for &line in list {
                        let at = Self::at_of(rows, kind, line);
                        bus_errors.push(Finding {
                            key: (axis.key(at), line),
                            line,
                            iface: iface_attr(&b.bus),
                            node: None,
                            text: format!(
                                "<b>{}bus {}</b> {} at line {line} ({})",
                                esc(&prefix),
                                esc(&b.bus.to_string()),
                                kind.words(),
                                axis.when(at)
                            ),
                        });
                    }
                }
            }
        }
        let sections: [(&str, &str, &mut Vec<Finding>); 7] = [
            (
                "faults",
                "Faults and first errors, in time order",
                &mut faults,
            ),
            ("restarts", "Restarts", &mut restarts),
            ("heartbeat-timeouts", "Heartbeat timeouts", &mut timeouts),
            ("sdo-aborts", "SDO aborts", &mut aborts),
            (
                "sdo-transfers",
                "Broken and unanswered SDO transfers",
                &mut transfers,
            ),
            ("toggle-errors", "Node-guarding toggle errors", &mut toggles),
            ("bus-errors", "Bus-off and error-passive", &mut bus_errors),
        ];
        let mut any = false;
        for (id, heading, list) in sections {
            if list.is_empty() {
                continue;
            }
            any = true;
            list.sort_by_key(|f| f.key);
            let _ = write!(
                p,
                "<h3 id=\"{id}\">{heading}</h3>\n<ul class=\"findings\">\n"
            );
            for f in list.iter().take(LIST_ITEMS) {
                let node = f
                    .node
                    .map_or_else(String::new, |n| format!(" data-node=\"{n}\""));
                let _ = writeln!(
                    p,
                    "<li data-line=\"{}\" data-iface=\"{}\"{node}>{}</li>",
                    f.line, f.iface, f.text
                );
            }
            if list.len() > LIST_ITEMS {
                let _ = writeln!(
                    p,
                    "<li class=\"more\">… and {} more (the timeline and the event table show every one)</li>",
                    list.len() - LIST_ITEMS
                );
            }
            p.push_str("</ul>\n");
        }
        if !any {
            p.push_str("<p>No fault, error EMCY, restart, heartbeat timeout, SDO abort or bus error in this log.</p>\n");
        }
        p.push_str("</section>\n");
    }

    fn timeline(&self, p: &mut String, axis: &Axis, budget: &Budget) {
        p.push_str("<section id=\"timeline\">\n<h2>Timeline</h2>\n");
        p.push_str("<p class=\"help\">One axis for every row. <span class=\"js\">Drag to pan, Ctrl + wheel or the buttons to zoom, click a mark for its details.</span> Hover a mark or band for what it is.</p>\n");
        p.push_str("<div class=\"tools js\"><button type=\"button\" data-zoom=\"in\">zoom in</button> <button type=\"button\" data-zoom=\"out\">zoom out</button> <button type=\"button\" data-zoom=\"reset\">whole log</button> <output id=\"details\"></output></div>\n");
        // Rows: per recording, per bus, the bus row then its devices.
        let mut rows: Vec<(String, f64)> = Vec::new();
        let mut body = String::new();
        let mut y = AXIS + 4.0;
        for r in &self.recordings {
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
                    rate(&mut body, axis, data, h);
                    for kind in [
                        MarkKind::ErrorFrame,
                        MarkKind::BusOff,
                        MarkKind::ErrorPassive,
                    ] {
                        marks(&mut body, axis, budget, &data.row, kind, None);
                    }
                }
                body.push_str("</g>\n</g>\n");
                rows.push((String::new(), y));
                y += h + 4.0;
                for n in r.summary.nodes.iter().filter(|n| n.bus == b.bus) {
                    let row = data.and_then(|d| d.node_row(n.node));
                    let h = node_row(&mut body, axis, budget, n, row, &file, y, end);
                    y += h + 4.0;
                }
            }
        }
        let height = y + 4.0;
        let _ = writeln!(
            p,
            "<svg class=\"tl\" id=\"timeline-svg\" viewBox=\"0 0 {WIDTH} {height}\" width=\"{WIDTH}\" height=\"{height}\" role=\"img\" aria-label=\"timeline\" data-left=\"{LEFT}\" data-plot=\"{PLOT}\">"
        );
        defs(p);
        axis_ticks(p, axis, height);
        p.push_str(&body);
        p.push_str("</svg>\n");
        legend(p);
        p.push_str("</section>\n");
    }

    fn signals(&self, p: &mut String, axis: &Axis, budget: &Budget) {
        p.push_str("<section id=\"signals\">\n<h2>Drive signals</h2>\n");
        let mut any = false;
        for r in &self.recordings {
            for n in &r.summary.nodes {
                let Some(row) = r.timeline.rows(&n.bus).and_then(|b| b.node_row(n.node)) else {
                    continue;
                };
                let has_signals = row.signals.iter().any(Option::is_some);
                if n.cia402.is_none() && !has_signals {
                    continue;
                }
                any = true;
                let end = r.timeline.span().map_or(At::default(), |(_, last)| last);
                chart(p, axis, budget, n, row, end);
            }
        }
        if !any {
            p.push_str(
                "<p>No drive in this log: no CiA 402 state, position or velocity to chart.</p>\n",
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
                    lines_or_none(&b.bus_off),
                    lines_or_none(&b.error_passive),
                    b.status_events,
                    ts(b.first_ts),
                    ts(b.last_ts),
                    lines(&nodes)
                );
            }
        }
        p.push_str("</tbody>\n</table>\n</section>\n");
    }

    fn events(&self, p: &mut String, axis: &Axis, budget: &Budget) {
        struct Row<'a> {
            key: (u64, u64),
            who: String,
            kind: MarkKind,
            mark: Drawn,
            bus: &'a BusName,
            node: Option<NodeId>,
        }
        let mut all: Vec<Row<'_>> = Vec::new();
        for r in &self.recordings {
            let prefix = r
                .summary
                .file
                .as_deref()
                .map_or_else(String::new, |f| format!("{f}: "));
            for bus in &r.timeline.buses {
                let mut rows: Vec<(Option<NodeId>, &RowData)> = vec![(None, &bus.row)];
                for n in &r.summary.nodes {
                    if n.bus == bus.name {
                        if let Some(row) = bus.node_row(n.node) {
                            rows.push((Some(n.node), row));
                        }
                    }
                }
                for (node, row) in rows {
                    let who = match node {
                        Some(node) => format!("{prefix}{}", device(&bus.name, node)),
                        None => format!("{prefix}bus {}", bus.name),
                    };
                    for kind in MarkKind::ALL {
                        for mark in drawn_marks(axis, &row.marks[kind as usize], budget.radius) {
                            all.push(Row {
                                key: (axis.key(mark.at), mark.at.line),
                                who: who.clone(),
                                kind,
                                mark,
                                bus: &bus.name,
                                node,
                            });
                        }
                    }
                }
            }
        }
        all.sort_by_key(|r| r.key);
        let _ = write!(
            p,
            "<section id=\"events\">\n<h2>Events</h2>\n<p class=\"help\">Every mark of the timeline in {} order, with its line{}.</p>\n<table class=\"events\">\n<thead><tr><th>line</th><th>{}</th><th>device</th><th>event</th><th>count</th><th>what</th></tr></thead>\n<tbody>\n",
            if axis.timed { "time" } else { "line" },
            if all.len() > EVENT_ROWS {
                format!("; the first {EVENT_ROWS} of {}", all.len())
            } else {
                String::new()
            },
            if axis.timed { "time" } else { "" },
        );
        for row in all.iter().take(EVENT_ROWS) {
            let m = row.mark;
            let lines = if m.count > 1 {
                format!("{}–{}", m.at.line, m.end.line)
            } else {
                m.at.line.to_string()
            };
            let node = row
                .node
                .map_or_else(String::new, |n| format!(" data-node=\"{}\"", n.get()));
            let _ = writeln!(
                p,
                "<tr data-line=\"{}\" data-iface=\"{}\"{node}><td>{lines}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                m.at.line,
                iface_attr(row.bus),
                if axis.timed { axis.when(m.at) } else { String::new() },
                esc(&row.who),
                row.kind.words(),
                m.count,
                esc(&mark_text(row.kind, &m, axis))
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
                serde_json::to_writer(&mut json, &record).map_err(io::Error::from)?;
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

fn lines_or_none(list: &[u64]) -> String {
    if list.is_empty() {
        "none".to_owned()
    } else {
        lines(list)
    }
}

/// What a mark says, in words: its title and its event-table cell.
fn mark_text(kind: MarkKind, m: &Drawn, axis: &Axis) -> String {
    let mut text = String::new();
    if m.count > 1 {
        let _ = write!(
            text,
            "{} {}s, lines {} to {} ({} to {}); the first: ",
            m.count,
            kind.words(),
            m.at.line,
            m.end.line,
            axis.when(m.at),
            axis.when(m.end)
        );
    }
    match m.detail {
        Detail::Emcy { code, register } => {
            let code = ErrorCode::new(code);
            let _ = write!(
                text,
                "{} {code} {} (register 0x{register:02X})",
                kind.words(),
                code.description()
            );
        }
        Detail::Gap(us) => {
            let _ = write!(text, "no heartbeat for {} ms", us as f64 / 1000.0);
        }
        Detail::None => text.push_str(kind.words()),
    }
    let _ = write!(text, " (line {}, {})", m.at.line, axis.when(m.at));
    text
}

/// Where a kind's marks sit in a row's marks lane, and how they look.
fn mark_y(kind: MarkKind) -> f64 {
    match kind {
        MarkKind::Emcy | MarkKind::EmcyReset => 7.0,
        MarkKind::BootUp | MarkKind::HeartbeatTimeout | MarkKind::ToggleError => 19.0,
        MarkKind::SdoAbort | MarkKind::SdoBroken | MarkKind::SdoTimeout => 19.0,
        MarkKind::Cia402Fault => 7.0,
        MarkKind::ErrorFrame | MarkKind::BusOff | MarkKind::ErrorPassive => 8.0,
    }
}

/// Draw a row's marks of one kind; `lane` is the y of its marks lane.
fn marks(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    row: &RowData,
    kind: MarkKind,
    lane: Option<f64>,
) {
    let series = &row.marks[kind as usize];
    if series.len() == 0 {
        return;
    }
    let base = lane.unwrap_or(0.0) + mark_y(kind);
    let name = kind.name();
    for m in drawn_marks(axis, series, budget.radius) {
        let x0 = axis.x(m.at);
        let x1 = axis.x(m.end);
        let element = if m.count > 1 || kind == MarkKind::HeartbeatTimeout {
            // A span (a heartbeat gap) or a cluster: a bar as wide as it
            // lasts, at least 2 pixels.
            let w = (x1 - x0).max(2.0);
            let (y, h) = if kind == MarkKind::HeartbeatTimeout {
                (base - 5.0, 10.0)
            } else {
                (base - 6.0, 12.0)
            };
            let _ = write!(
                p,
                "<rect x=\"{x0:.3}\" y=\"{y}\" width=\"{w:.3}\" height=\"{h}\" data-kind=\"{name}\" data-line=\"{}\" data-count=\"{}\"",
                m.at.line,
                m.count
            );
            if m.count > 1 {
                let _ = write!(p, " data-last-line=\"{}\"", m.end.line);
            }
            "rect"
        } else {
            let _ = write!(
                p,
                "<use href=\"#s-{name}\" x=\"{x0:.3}\" y=\"{base}\" data-kind=\"{name}\" data-line=\"{}\" data-count=\"1\"",
                m.at.line
            );
            "use"
        };
        if budget.titles {
            let _ = writeln!(
                p,
                "><title>{}</title></{element}>",
                esc(&mark_text(kind, &m, axis))
            );
        } else {
            p.push_str("/>\n");
        }
    }
}

/// A bus row's frame rate, as an area chart (timed only).
fn rate(p: &mut String, axis: &Axis, rows: &BusRows, h: f64) {
    if !axis.timed {
        return;
    }
    let items = rows.row.rate.items();
    if items.len() < 2 {
        return;
    }
    // Frames per second of each bucket: its frames over its width.
    let width = rows.row.rate.width().max(1);
    let mut peak: f64 = 0.0;
    let mut points: Vec<(f64, f64, f64)> = Vec::with_capacity(items.len());
    for b in items {
        let from = b.at.t / width * width;
        let fps = b.frames as f64 / (width as f64 / 1e6);
        peak = peak.max(fps);
        points.push((axis.x_of(from), axis.x_of(from + width), fps));
    }
    let top = 16.0;
    let bottom = h - 2.0;
    let mut d = format!("M{:.2},{bottom}", points[0].0);
    for (x0, x1, fps) in &points {
        let y = bottom - (fps / peak.max(1.0)) * (bottom - top);
        let _ = write!(d, "L{x0:.2},{y:.1}L{x1:.2},{y:.1}");
    }
    let _ = write!(d, "L{:.2},{bottom}Z", points[points.len() - 1].1);
    let _ = writeln!(
        p,
        "<path d=\"{d}\" data-kind=\"frame_rate\" data-peak=\"{peak:.0}\"><title>frames per second, at most {peak:.0}</title></path>"
    );
}

/// A device's row; returns its height.
#[allow(clippy::too_many_arguments)]
fn node_row(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    n: &NodeSummary,
    row: Option<&RowData>,
    file: &str,
    y: f64,
    end: At,
) -> f64 {
    let drive = n.cia402.is_some();
    let h = if drive { 58.0 } else { 44.0 };
    let _ = write!(
        p,
        "<g class=\"row node\" data-row=\"node\" data-iface=\"{}\" data-node=\"{}\"{file} transform=\"translate(0,{y})\">\n<text class=\"label\" x=\"8\" y=\"14\">{}</text><text class=\"sub\" x=\"8\" y=\"28\">NMT{}</text>\n<g class=\"plot\" clip-path=\"url(#clip)\">\n",
        iface_attr(&n.bus),
        n.node.get(),
        esc(&device(&n.bus, n.node)),
        if drive { " · CiA 402" } else { "" }
    );
    if let Some(row) = row {
        bands(p, axis, budget, &row.nmt, end, 2.0, "nmt_state", nmt_name);
        let mut lane = 16.0;
        if drive {
            bands(
                p,
                axis,
                budget,
                &row.cia402,
                end,
                16.0,
                "cia402_state",
                cia402_name,
            );
            lane = 30.0;
        }
        for kind in MarkKind::ALL {
            if matches!(
                kind,
                MarkKind::ErrorFrame | MarkKind::BusOff | MarkKind::ErrorPassive
            ) {
                continue;
            }
            let at = if kind == MarkKind::Cia402Fault {
                16.0
            } else {
                lane
            };
            marks(p, axis, budget, row, kind, Some(at));
        }
    }
    p.push_str("</g>\n</g>\n");
    h
}

/// A row's state bands, from `y`, 12 pixels high.
#[allow(clippy::too_many_arguments)]
fn bands(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    series: &Series<BandItem>,
    end: At,
    y: f64,
    kind: &str,
    name: fn(u8) -> &'static str,
) {
    for band in drawn_bands(axis, series, end, budget.band_px) {
        let b = band.item;
        let state = name(b.state);
        let w = (band.x1 - band.x0).max(0.5);
        let _ = write!(
            p,
            "<rect x=\"{:.3}\" y=\"{y}\" width=\"{w:.3}\" height=\"12\" data-kind=\"{kind}\" data-state=\"{state}\" data-line=\"{}\" data-count=\"{}\"",
            band.x0,
            b.at.line,
            b.count,
        );
        if b.count > 1 {
            p.push_str(" class=\"mixed\"");
        }
        if budget.titles {
            let title = if b.count > 1 {
                format!(
                    "{} state changes from line {} ({}), from {state} to {}",
                    b.count,
                    b.at.line,
                    axis.when(b.at),
                    name(b.last_state)
                )
            } else {
                format!("{state} from line {} ({})", b.at.line, axis.when(b.at))
            };
            let _ = write!(p, "><title>{}</title></rect>", esc(&title));
        } else {
            p.push_str("/>");
        }
        if w >= 70.0 && b.count == 1 {
            let _ = write!(
                p,
                "<text class=\"bl\" x=\"{:.3}\" y=\"{}\">{state}</text>",
                band.x0 + 3.0,
                y + 9.5
            );
        }
        p.push('\n');
    }
}

/// The shapes of the marks, the clip of the plot, the hatch of merged bands.
fn defs(p: &mut String) {
    let _ = write!(
        p,
        "<defs>\n<clipPath id=\"clip\"><rect x=\"{LEFT}\" y=\"-20\" width=\"{PLOT}\" height=\"200\"/></clipPath>\n\
<pattern id=\"hatch\" width=\"4\" height=\"4\" patternUnits=\"userSpaceOnUse\" patternTransform=\"rotate(45)\"><rect width=\"2\" height=\"4\" fill=\"#555\"/></pattern>\n\
<path id=\"s-emcy\" d=\"M0,5L-5,-5H5Z\"/>\n\
<circle id=\"s-emcy_reset\" r=\"4\"/>\n\
<path id=\"s-boot_up\" d=\"M0,-6L5,4H-5Z\"/>\n\
<path id=\"s-heartbeat_timeout\" d=\"M-3,-5H3V5H-3Z\"/>\n\
<path id=\"s-sdo_abort\" d=\"M-4,-4L4,4M4,-4L-4,4\"/>\n\
<path id=\"s-sdo_broken\" d=\"M-4,-4H4V4H-4Z\"/>\n\
<path id=\"s-sdo_timeout\" d=\"M0,-5L5,0L0,5L-5,0Z\"/>\n\
<path id=\"s-toggle_error\" d=\"M-5,-4H5M0,-4V5\"/>\n\
<path id=\"s-cia402_fault\" d=\"M0,-7V7M-4,-7H4\"/>\n\
<path id=\"s-error_frame\" d=\"M0,-6V6\"/>\n\
<path id=\"s-bus_off\" d=\"M-5,-5H5V5H-5Z\"/>\n\
<path id=\"s-error_passive\" d=\"M-4,-4H4V4H-4Z\"/>\n\
</defs>\n"
    );
}

/// Round ticks for a span of `span` units: the step and its unit's label.
fn tick_step(span: f64) -> f64 {
    let raw = span / 8.0;
    let pow = 10f64.powf(raw.log10().floor());
    let unit = raw / pow;
    let nice = if unit < 1.5 {
        1.0
    } else if unit < 3.5 {
        2.0
    } else if unit < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * pow
}

/// The axis at the top, with grid lines down through every row (the script
/// redraws them when the view changes).
fn axis_ticks(p: &mut String, axis: &Axis, height: f64) {
    let _ = write!(
        p,
        "<g class=\"axis\" data-unit=\"{}\">\n<text class=\"unit\" x=\"8\" y=\"16\">{}</text>\n",
        if axis.timed { "s" } else { "line" },
        if axis.timed { "seconds" } else { "line" }
    );
    let span_units = if axis.timed {
        (axis.end - axis.start) as f64 / 1e6
    } else {
        (axis.end - axis.start) as f64
    };
    let step = tick_step(span_units.max(1e-6));
    let mut v = 0.0;
    while v <= span_units + step * 1e-9 {
        let x = LEFT + v / span_units.max(1e-12) * PLOT;
        let label = if axis.timed {
            format_tick(v, step)
        } else {
            format!("{}", (axis.start as f64 + v).round())
        };
        let _ = writeln!(
            p,
            "<line class=\"grid\" x1=\"{x:.2}\" x2=\"{x:.2}\" y1=\"{}\" y2=\"{height}\"/><text class=\"tick\" x=\"{x:.2}\" y=\"16\">{label}</text>",
            AXIS - 4.0
        );
        v += step;
    }
    p.push_str("</g>\n");
}

fn format_tick(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 {
        0
    } else {
        (-step.log10().floor()) as usize
    };
    format!("{v:.decimals$}")
}

/// The legend: every kind of mark and band, in words.
fn legend(p: &mut String) {
    p.push_str("<div class=\"legend\"><svg width=\"0\" height=\"0\" aria-hidden=\"true\"></svg>\n<h3>Marks</h3>\n<ul class=\"legend\">\n");
    for kind in MarkKind::ALL {
        let _ = writeln!(
            p,
            "<li><svg width=\"16\" height=\"16\" viewBox=\"-8 -8 16 16\" aria-hidden=\"true\"><use class=\"lm-{0}\" href=\"#s-{0}\"/></svg> {1} <code>{0}</code></li>",
            kind.name(),
            kind.words()
        );
    }
    p.push_str("<li><svg width=\"16\" height=\"16\" aria-hidden=\"true\"><rect class=\"lm-emcy lm-cluster\" x=\"2\" y=\"2\" width=\"12\" height=\"12\"/></svg> a cluster of neighbours within a pixel, when a row has more than 500 marks of a kind (its title says how many)</li>\n</ul>\n<h3>Bands</h3>\n<ul class=\"legend\">\n");
    for state in ["boot_up", "pre_operational", "operational", "stopped"] {
        let _ = writeln!(
            p,
            "<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-{state}\" width=\"16\" height=\"12\"/></svg> NMT {state}</li>"
        );
    }
    for state in crate::canopen::Cia402State::ALL {
        let _ = writeln!(
            p,
            "<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-{0}\" width=\"16\" height=\"12\"/></svg> CiA 402 {0}</li>",
            state.name()
        );
    }
    p.push_str("<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-mixed\" width=\"16\" height=\"12\"/></svg> several states within a pixel</li>\n</ul></div>\n");
}

/// A drive's charts: its CiA 402 state, position and velocity on the
/// shared axis (docs/report.md#signals).
fn chart(p: &mut String, axis: &Axis, budget: &Budget, n: &NodeSummary, row: &RowData, end: At) {
    const H: f64 = 70.0;
    let mut body = String::new();
    let mut y = AXIS + 4.0;
    // The CiA 402 state, as a step line over the 8 states.
    if n.cia402.is_some() {
        let levels = crate::canopen::Cia402State::ALL.len() as f64;
        let bands = drawn_bands(axis, &row.cia402, end, budget.band_px);
        let mut d = String::new();
        for (i, band) in bands.iter().enumerate() {
            let level = f64::from(band.item.state);
            let yy = y + 4.0 + (level / (levels - 1.0)) * (H - 8.0);
            let _ = write!(
                d,
                "{}{:.2},{yy:.1}H{:.2}",
                if i == 0 { "M" } else { "L" },
                band.x0,
                band.x1
            );
        }
        let _ = write!(
            body,
            "<g class=\"chart\" transform=\"translate(0,0)\"><text class=\"label\" x=\"8\" y=\"{}\">CiA 402 state</text><text class=\"sub\" x=\"8\" y=\"{}\">top: not ready</text><text class=\"sub\" x=\"8\" y=\"{}\">bottom: fault</text>\n<g class=\"plot\" clip-path=\"url(#clip-c)\"><path class=\"sig state\" d=\"{d}\" data-kind=\"signal\" data-signal=\"cia402_state\" data-points=\"{}\"><title>CiA 402 state of {}</title></path></g></g>\n",
            y + 14.0,
            y + 28.0,
            y + 42.0,
            bands.len(),
            esc(&device(&n.bus, n.node))
        );
        y += H + 8.0;
    }
    for (i, (index, title)) in CHARTED.iter().enumerate() {
        let Some(series) = &row.signals[i] else {
            continue;
        };
        let items = series.items();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for b in items {
            lo = lo.min(b.min.1);
            hi = hi.max(b.max.1);
        }
        if hi <= lo {
            hi = lo + 1.0;
        }
        let yv = |v: f64| y + 4.0 + (hi - v) / (hi - lo) * (H - 8.0);
        let mut d = String::new();
        let mut points = 0;
        for b in items {
            let pair = if axis.key(b.min.0) <= axis.key(b.max.0) {
                [b.min, b.max]
            } else {
                [b.max, b.min]
            };
            for (k, (at, v)) in pair.iter().enumerate() {
                if k == 1 && pair[0].0 == pair[1].0 {
                    continue;
                }
                let _ = write!(
                    d,
                    "{}{:.2},{:.1}",
                    if points == 0 { "M" } else { "L" },
                    axis.x(*at),
                    yv(*v)
                );
                points += 1;
            }
        }
        let _ = write!(
            body,
            "<g class=\"chart\"><text class=\"label\" x=\"8\" y=\"{}\">{}</text><text class=\"sub\" x=\"8\" y=\"{}\">max {hi}</text><text class=\"sub\" x=\"8\" y=\"{}\">min {lo}</text>\n<g class=\"plot\" clip-path=\"url(#clip-c)\"><path class=\"sig\" d=\"{d}\" data-kind=\"signal\" data-signal=\"{index:04x}\" data-points=\"{points}\"><title>{} of {}: from {lo} to {hi}, {points} points (minimum and maximum per bucket)</title></path></g></g>\n",
            y + 14.0,
            esc(title.split(" (").next().unwrap_or(title)),
            y + 28.0,
            y + H - 4.0,
            esc(title),
            esc(&device(&n.bus, n.node))
        );
        y += H + 8.0;
    }
    let height = y;
    let _ = write!(
        p,
        "<h3>{}</h3>\n<svg class=\"tl chart\" viewBox=\"0 0 {WIDTH} {height}\" width=\"{WIDTH}\" height=\"{height}\" role=\"img\" aria-label=\"signals of {}\" data-node=\"{}\" data-iface=\"{}\" data-left=\"{LEFT}\" data-plot=\"{PLOT}\">\n<defs><clipPath id=\"clip-c\"><rect x=\"{LEFT}\" y=\"0\" width=\"{PLOT}\" height=\"100000\"/></clipPath></defs>\n",
        esc(&device(&n.bus, n.node)),
        esc(&device(&n.bus, n.node)),
        n.node.get(),
        iface_attr(&n.bus)
    );
    axis_ticks(p, axis, height);
    p.push_str(&body);
    p.push_str("</svg>\n");
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
            |s| format!("{} {} (line {})", s.code, esc(s.code.description()), s.line),
        )
    };
    let hb = &n.heartbeat;
    let mut heartbeat = format!(
        "{} heartbeats, last {}",
        hb.count,
        hb.last_state.map_or("–", |s| s.state_name())
    );
    if !hb.boot_ups.is_empty() {
        let _ = write!(heartbeat, "; boot-ups at lines {}", lines(&hb.boot_ups));
    }
    match &hb.timeouts {
        Timeouts::NotAsked => {}
        Timeouts::NotChecked => heartbeat.push_str("; timeouts not checked (no timestamps)"),
        Timeouts::Checked(gaps) if gaps.is_empty() => heartbeat.push_str("; no timeouts"),
        Timeouts::Checked(gaps) => {
            let _ = write!(heartbeat, "; {} timeouts", gaps.len());
        }
    }
    let g = &n.guarding;
    let guarding = if g.answers == 0 && g.toggle_errors.is_empty() {
        "–".to_owned()
    } else {
        format!(
            "{} answers, wrong toggle at lines {}",
            g.answers,
            lines_or_none(&g.toggle_errors)
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
            s.aborts.len()
        );
        if !s.broken.is_empty() {
            let _ = write!(t, ", broken at lines {}", lines(&s.broken));
        }
        if !s.timeouts.is_empty() {
            let _ = write!(t, ", unanswered at lines {}", lines(&s.timeouts));
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
            c.transitions.len(),
            c.last_state().map_or("–", |s| s.name()),
            c.faults.as_ref().map_or(0, Vec::len)
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
