//! The recording of a log: the [`Recorder`] fed every frame and bus event,
//! and what it returns, the [`Recording`]: the [`Summary`] and its
//! [`Timeline`] (docs/report.md#bounded).

use std::collections::BTreeMap;

use crate::can::{BusName, Iface, LogEvent, LogFrame, Timestamp};
use crate::canopen::{Cia402State, NodeId, Value};
use crate::decoder::DecoderConfig;
use crate::logs::Position;
use crate::summary::{
    FileSpan, Finding, FindingKind, Summarizer, Summary, SummaryEvent, SummaryEventKind,
};

use super::series::{
    At, BandItem, Detail, MarkItem, RateBucket, Series, SignalBucket, BUCKETS, EXACT_MARKS,
    SIGNAL_BUCKETS,
};

/// What a mark on the timeline stands for: its `data-kind`
/// (docs/report.md#marks).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MarkKind {
    /// An error EMCY (`emcy` less `resets` in docs/summary.md#emcy).
    Emcy,
    /// A reset EMCY, any code 00xxh (`resets`; docs/canopen.md#emcy-codes).
    EmcyReset,
    /// A boot-up message (`heartbeat.boot_ups`).
    BootUp,
    /// A heartbeat gap longer than the consumer time, drawn as a span
    /// (`heartbeat.timeouts`).
    HeartbeatTimeout,
    /// An SDO abort (`sdo.aborts`).
    SdoAbort,
    /// A broken SDO transfer (`sdo.broken`).
    SdoBroken,
    /// An SDO transfer no response answered (`sdo.timeouts`).
    SdoTimeout,
    /// A node-guarding answer with a wrong toggle (`guarding.toggle_errors`).
    ToggleError,
    /// A drive entering a CiA 402 fault state (`cia402.faults`).
    Cia402Fault,
    /// An error frame (the bus record's `error_frames`).
    ErrorFrame,
    /// An error frame that says bus-off (`bus_off`).
    BusOff,
    /// An error frame that says error-passive (`error_passive`).
    ErrorPassive,
}

impl MarkKind {
    /// Every kind, in the order of docs/report.md#marks.
    pub const ALL: [MarkKind; 12] = [
        MarkKind::Emcy,
        MarkKind::EmcyReset,
        MarkKind::BootUp,
        MarkKind::HeartbeatTimeout,
        MarkKind::SdoAbort,
        MarkKind::SdoBroken,
        MarkKind::SdoTimeout,
        MarkKind::ToggleError,
        MarkKind::Cia402Fault,
        MarkKind::ErrorFrame,
        MarkKind::BusOff,
        MarkKind::ErrorPassive,
    ];

    /// Return the kind's name, its `data-kind` (docs/report.md#marks).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            MarkKind::Emcy => "emcy",
            MarkKind::EmcyReset => "emcy_reset",
            MarkKind::BootUp => "boot_up",
            MarkKind::HeartbeatTimeout => "heartbeat_timeout",
            MarkKind::SdoAbort => "sdo_abort",
            MarkKind::SdoBroken => "sdo_broken",
            MarkKind::SdoTimeout => "sdo_timeout",
            MarkKind::ToggleError => "toggle_error",
            MarkKind::Cia402Fault => "cia402_fault",
            MarkKind::ErrorFrame => "error_frame",
            MarkKind::BusOff => "bus_off",
            MarkKind::ErrorPassive => "error_passive",
        }
    }

    /// Return the kind in words, as the page's legend and titles say it.
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            MarkKind::Emcy => "EMCY",
            MarkKind::EmcyReset => "reset EMCY",
            MarkKind::BootUp => "boot-up",
            MarkKind::HeartbeatTimeout => "heartbeat timeout",
            MarkKind::SdoAbort => "SDO abort",
            MarkKind::SdoBroken => "broken SDO transfer",
            MarkKind::SdoTimeout => "unanswered SDO request",
            MarkKind::ToggleError => "guarding toggle error",
            MarkKind::Cia402Fault => "CiA 402 fault",
            MarkKind::ErrorFrame => "error frame",
            MarkKind::BusOff => "bus-off",
            MarkKind::ErrorPassive => "error-passive",
        }
    }

    const fn index(self) -> usize {
        self as usize
    }
}

/// The signals a drive's charts show (docs/report.md#signals): position
/// actual value 6064h and velocity actual value 606Ch, sub-index 0.
pub(super) const CHARTED: [(u16, &str); 2] = [
    (0x6064, "Position actual value (6064h)"),
    (0x606C, "Velocity actual value (606Ch)"),
];

/// What a row of the timeline keeps: marks by kind, the state bands, a
/// drive's signals, a bus's frame rate.
#[derive(Debug, Clone)]
pub(crate) struct RowData {
    pub(crate) marks: [Series<MarkItem>; 12],
    pub(crate) nmt: Series<BandItem>,
    nmt_state: Option<u8>,
    /// Where the last NMT band begins.
    nmt_since: At,
    pub(crate) cia402: Series<BandItem>,
    /// Per entry of [`CHARTED`]: its values, once seen.
    pub(crate) signals: [Option<Series<SignalBucket>>; 2],
    pub(crate) rate: Series<RateBucket>,
    /// Its EMCYs by code: how many, the first and the last
    /// (docs/report.md#events: a cluster never hides a code).
    pub(crate) codes: BTreeMap<u16, CodeRun>,
}

/// A row's EMCYs of one code: how many, the first (with its register and
/// manufacturer bytes) and the last.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CodeRun {
    pub(crate) count: u64,
    pub(crate) first: At,
    pub(crate) last: At,
    pub(crate) detail: Detail,
}

impl RowData {
    fn new(timed: bool) -> Self {
        RowData {
            marks: core::array::from_fn(|_| Series::new(EXACT_MARKS, BUCKETS, timed)),
            nmt: Series::new(BUCKETS, BUCKETS, timed),
            nmt_state: None,
            nmt_since: At::default(),
            cia402: Series::new(BUCKETS, BUCKETS, timed),
            signals: [None, None],
            rate: Series::new(0, SIGNAL_BUCKETS, timed),
            codes: BTreeMap::new(),
        }
    }

    fn mark(&mut self, kind: MarkKind, at: At, end: At, detail: Detail) {
        self.marks[kind.index()].add(MarkItem {
            at,
            end,
            count: 1,
            detail,
        });
    }

    fn band(series: &mut Series<BandItem>, at: At, state: u8) {
        series.add(BandItem {
            at,
            state,
            last_state: state,
            count: 1,
        });
    }
}

/// A bus's rows.
#[derive(Debug, Clone)]
pub(crate) struct BusRows {
    pub(crate) name: BusName,
    pub(crate) row: RowData,
    nodes: Vec<Option<Box<RowData>>>,
}

impl BusRows {
    fn new(name: BusName, timed: bool) -> Self {
        BusRows {
            name,
            row: RowData::new(timed),
            nodes: (0..128).map(|_| None).collect(),
        }
    }

    fn node(&mut self, node: NodeId, timed: bool) -> &mut RowData {
        self.nodes[usize::from(node.get())].get_or_insert_with(|| Box::new(RowData::new(timed)))
    }

    pub(crate) fn node_row(&self, node: NodeId) -> Option<&RowData> {
        self.nodes[usize::from(node.get())].as_deref()
    }
}

/// Microseconds of a time, saturating.
fn micros(ts: Timestamp) -> u64 {
    u64::try_from(ts.as_micros()).unwrap_or(u64::MAX)
}

/// Builds a [`Recording`], frame by frame (see the [module](super)
/// documentation).
#[derive(Debug)]
pub struct Recorder {
    summarizer: Summarizer,
    /// Each bus's rows, in the order of the buses' first frames.
    buses: Vec<BusRows>,
    /// The place in `buses` of each bus of the decoder's table, at the
    /// bus's place there ([`Summarizer::bus_at`]); `None` for a bus that
    /// no frame has been seen on yet (only status events).
    rows_of: Vec<Option<usize>>,
    /// Whether the recording is drawn by time: its first frame has one.
    timed: Option<bool>,
    /// The last time seen, in microseconds: frames without one are drawn there.
    last_t: u64,
    /// Frames without a time in a recording drawn by time.
    untimed: u64,
    first: Option<At>,
    last: At,
}

impl Default for Recorder {
    fn default() -> Self {
        Recorder::new(DecoderConfig::new())
    }
}

impl Recorder {
    /// Start a recording read by a decoder of `config`: its profiles,
    /// EDS files and heartbeat consumer time
    /// ([`DecoderConfig::heartbeat_timeout`]; `--heartbeat-ms`). The
    /// drives' charts need the PDO signals unpacked
    /// ([`DecoderConfig::signals`], the default).
    #[must_use]
    pub fn new(config: DecoderConfig) -> Self {
        Recorder {
            summarizer: Summarizer::new(config),
            buses: Vec::new(),
            rows_of: Vec::new(),
            timed: None,
            last_t: 0,
            untimed: 0,
            first: None,
            last: At::default(),
        }
    }

    /// Add one log entry read at `position` (docs/formats.md#positions),
    /// as [`Summarizer::add`] does: the summary, the timeline's marks and
    /// the drives' signals learn from it.
    pub fn add(&mut self, position: Position, event: &LogEvent<'_>) {
        match event {
            LogEvent::Frame(frame) => self.add_frame(position, frame, event),
            LogEvent::Status(_) | LogEvent::Ethercat(_) => self.summarizer.add(position, event),
        }
    }

    /// The place in `buses` of the rows of the bus of `iface`, found by
    /// the bus's place in the decoder's table, made on the bus's first
    /// frame.
    #[inline]
    fn bus(&mut self, iface: Option<Iface<'_>>, timed: bool) -> usize {
        let at = self.summarizer.bus_at(iface);
        if let Some(&Some(rows)) = self.rows_of.get(at) {
            return rows;
        }
        self.new_rows(at, timed)
    }

    /// Rows for the bus at `at` in the decoder's table, on its first frame.
    #[cold]
    #[inline(never)]
    fn new_rows(&mut self, at: usize, timed: bool) -> usize {
        if self.rows_of.len() <= at {
            self.rows_of.resize(at + 1, None);
        }
        let name = self.summarizer.decoder().bus_name(at).clone();
        self.buses.push(BusRows::new(name, timed));
        let rows = self.buses.len() - 1;
        self.rows_of[at] = Some(rows);
        rows
    }

    /// Add the frame `log` of the log entry `event`, read at `position`.
    fn add_frame(&mut self, position: Position, log: &LogFrame<'_>, event: &LogEvent<'_>) {
        let timed = *self.timed.get_or_insert(log.timestamp.is_some());
        match log.timestamp {
            Some(ts) => self.last_t = micros(ts),
            None if timed => self.untimed += 1,
            None => {}
        }
        let at = At {
            t: self.last_t,
            line: position.number(),
        };
        self.first.get_or_insert(at);
        self.last = at;
        let b = self.bus(log.iface, timed);
        let Recorder {
            summarizer, buses, ..
        } = self;
        let rows = &mut buses[b];
        rows.row.rate.add(RateBucket { at, frames: 1 });
        let heartbeat = summarizer.decoder().config().heartbeat();
        let decoded = summarizer.add_with(position, event, |event| {
            record(rows, timed, heartbeat, at, &event);
        });
        if let Some(pdo) = decoded.and_then(|decoded| decoded.pdo) {
            if pdo.signals.is_empty() {
                return;
            }
            let node = pdo.map.node();
            for signal in pdo.signals.iter().flatten() {
                let entry = signal.entry;
                if entry.sub_index() != 0 {
                    continue;
                }
                let Some(i) = CHARTED
                    .iter()
                    .position(|(index, _)| *index == entry.index())
                else {
                    continue;
                };
                let value = match signal.value {
                    Value::Signed(v) => v as f64,
                    Value::Unsigned(v) => v as f64,
                    Value::Real32(v) => f64::from(v),
                    Value::Real64(v) => v,
                    _ => continue,
                };
                if !value.is_finite() {
                    continue;
                }
                let series = rows.node(node, timed).signals[i]
                    .get_or_insert_with(|| Series::new(0, SIGNAL_BUCKETS, timed));
                series.add(SignalBucket {
                    at,
                    min: (at, value),
                    max: (at, value),
                });
            }
        }
    }

    /// Close the recording ([`Summarizer::finish`]): its summary and its
    /// timeline.
    #[must_use]
    pub fn finish(self) -> Recording {
        let Recorder {
            summarizer,
            mut buses,
            timed,
            untimed,
            first,
            last,
            last_t,
            ..
        } = self;
        let timed = timed.unwrap_or(false);
        let end = At {
            t: last_t,
            line: last.line,
        };
        let heartbeat = summarizer.decoder().config().heartbeat();
        let summary = summarizer.finish_with(|event| {
            let at = match buses.iter().position(|b| &b.name == event.bus) {
                Some(at) => at,
                None => {
                    buses.push(BusRows::new(event.bus.clone(), timed));
                    buses.len() - 1
                }
            };
            record(&mut buses[at], timed, heartbeat, end, &event);
        });
        if summary.timeouts_not_checked() {
            // The summary says null: nothing is drawn as if checked.
            for bus in &mut buses {
                for row in bus.nodes.iter_mut().flatten() {
                    row.marks[MarkKind::HeartbeatTimeout.index()] =
                        Series::new(EXACT_MARKS, BUCKETS, timed);
                    // Nor is a silence drawn as if it were checked.
                    row.nmt.retain(|band| band.state != SILENT);
                }
            }
        }
        Recording {
            summary,
            timeline: Timeline {
                timed,
                untimed,
                first,
                last: first.map(|_| last),
                buses,
            },
            files: Vec::new(),
        }
    }
}

/// The NMT band of a device silent past its heartbeat consumer time
/// (`data-state="unknown"`, docs/report.md#bands): not a state byte's value,
/// whose bit 7 a band never keeps.
pub(crate) const SILENT: u8 = 0x80;

/// Record one fact of the summary on its row; `heartbeat` is the consumer
/// time the summary's heartbeat timeouts are checked against.
fn record(
    rows: &mut BusRows,
    timed: bool,
    heartbeat: Option<core::time::Duration>,
    now: At,
    event: &SummaryEvent<'_>,
) {
    let at = At {
        t: event.timestamp.map_or(now.t, micros),
        line: event.line,
    };
    let row = match event.node {
        Some(node) => rows.node(node, timed),
        None => &mut rows.row,
    };
    match event.kind {
        SummaryEventKind::Emcy {
            code,
            register,
            manufacturer,
        } => {
            // A reset is any 00xxh code, as the summary counts `resets`
            // (docs/canopen.md#emcy-codes).
            let kind = if code.is_reset() {
                MarkKind::EmcyReset
            } else {
                MarkKind::Emcy
            };
            let detail = Detail::Emcy {
                code: code.get(),
                register: register.bits(),
                manufacturer,
            };
            row.mark(kind, at, at, detail);
            let run = row.codes.entry(code.get()).or_insert(CodeRun {
                count: 0,
                first: at,
                last: at,
                detail,
            });
            run.count += 1;
            if at.key(timed) < run.first.key(timed) {
                run.first = at;
                run.detail = detail;
            }
            if at.key(timed) >= run.last.key(timed) {
                run.last = at;
            }
        }
        SummaryEventKind::Nmt { state, .. } => {
            let state = state.state_raw();
            if row.nmt_state != Some(state) {
                row.nmt_state = Some(state);
                row.nmt_since = at;
                RowData::band(&mut row.nmt, at, state);
            }
        }
        SummaryEventKind::BootUp => row.mark(MarkKind::BootUp, at, at, Detail::None),
        SummaryEventKind::HeartbeatTimeout(gap) => {
            let us = u64::try_from(gap.gap.as_micros()).unwrap_or(u64::MAX);
            let end = At {
                t: at.t.saturating_add(us),
                line: at.line,
            };
            row.mark(MarkKind::HeartbeatTimeout, at, end, Detail::Gap(us));
            // Past the consumer time nothing tells the node's state: the
            // band says so up to the heartbeat that ends the gap (handed
            // over after this event) or to the end.
            let time = heartbeat.map_or(0, |time| {
                u64::try_from(time.as_micros()).unwrap_or(u64::MAX)
            });
            let silent = At {
                t: at.t.saturating_add(time.min(us)),
                line: at.line,
            };
            if timed && silent.t >= row.nmt_since.t && row.nmt_state != Some(SILENT) {
                row.nmt_state = Some(SILENT);
                row.nmt_since = silent;
                RowData::band(&mut row.nmt, silent, SILENT);
            }
        }
        SummaryEventKind::ToggleError => row.mark(MarkKind::ToggleError, at, at, Detail::None),
        SummaryEventKind::SdoAbort(_) => row.mark(MarkKind::SdoAbort, at, at, Detail::None),
        SummaryEventKind::SdoBroken(_) => row.mark(MarkKind::SdoBroken, at, at, Detail::None),
        SummaryEventKind::SdoTimeout(_) => row.mark(MarkKind::SdoTimeout, at, at, Detail::None),
        SummaryEventKind::Cia402 { transition, fault } => {
            RowData::band(&mut row.cia402, at, transition.to as u8);
            if fault.is_some() {
                row.mark(MarkKind::Cia402Fault, at, at, Detail::None);
            }
        }
        SummaryEventKind::ErrorFrame {
            bus_off,
            error_passive,
        } => {
            row.mark(MarkKind::ErrorFrame, at, at, Detail::None);
            if bus_off {
                row.mark(MarkKind::BusOff, at, at, Detail::None);
            }
            if error_passive {
                row.mark(MarkKind::ErrorPassive, at, at, Detail::None);
            }
        }
        SummaryEventKind::Ethercat(_) => {}
    }
}

/// The CiA 402 state of a band's index.
pub(crate) fn cia402_state(index: u8) -> Option<Cia402State> {
    Cia402State::ALL.get(usize::from(index)).copied()
}

/// The marks that hold a finding whose time the summary does not keep.
fn mark_kind(finding: &Finding) -> Option<MarkKind> {
    if finding.timed_by_summary() {
        return None;
    }
    Some(match finding.kind {
        FindingKind::FirstError | FindingKind::FirstWarning => return None,
        FindingKind::Cia402Fault => MarkKind::Cia402Fault,
        FindingKind::Restarts => MarkKind::BootUp,
        FindingKind::HeartbeatTimeout => MarkKind::HeartbeatTimeout,
        FindingKind::SdoAbort => MarkKind::SdoAbort,
        FindingKind::SdoBroken => MarkKind::SdoBroken,
        FindingKind::SdoTimeout => MarkKind::SdoTimeout,
        FindingKind::ToggleError => MarkKind::ToggleError,
        FindingKind::BusOff => MarkKind::BusOff,
        FindingKind::ErrorPassive => MarkKind::ErrorPassive,
    })
}

/// A recording's timeline: per bus and device, the marks, state bands,
/// signals and frame rate the page draws (docs/report.md#timeline), in
/// bounded memory.
#[derive(Debug, Clone)]
pub struct Timeline {
    timed: bool,
    untimed: u64,
    first: Option<At>,
    last: Option<At>,
    pub(crate) buses: Vec<BusRows>,
}

impl Timeline {
    /// Return whether the recording is drawn by time: its first frame had
    /// a timestamp (else by line, docs/report.md#no-timestamps).
    #[must_use]
    pub fn is_timed(&self) -> bool {
        self.timed
    }

    /// Return how many frames had no timestamp in a recording drawn by
    /// time (each drawn at the time of the frame before it).
    #[must_use]
    pub fn untimed_frames(&self) -> u64 {
        self.untimed
    }

    pub(crate) fn span(&self) -> Option<(At, At)> {
        Some((self.first?, self.last?))
    }

    pub(crate) fn rows(&self, bus: &BusName) -> Option<&BusRows> {
        self.buses.iter().find(|b| &b.name == bus)
    }

    fn row(&self, bus: &BusName, node: Option<NodeId>) -> Option<&RowData> {
        let rows = self.rows(bus)?;
        match node {
            Some(node) => rows.node_row(node),
            None => Some(&rows.row),
        }
    }

    /// Where a mark of `kind` holds the summary's line `line` on the row
    /// of `node` on `bus`: the mark at that line, else the cluster of
    /// marks it lies in (docs/report.md#clusters).
    fn mark_at(
        &self,
        bus: &BusName,
        node: Option<NodeId>,
        kind: MarkKind,
        line: u64,
    ) -> Option<At> {
        let items = self.row(bus, node)?.marks[kind.index()].items();
        items
            .iter()
            .find(|m| m.at.line == line)
            .or_else(|| items.iter().rev().find(|m| m.at.line <= line))
            .map(|m| m.at)
    }

    /// Where the page draws a finding: its own time where the summary
    /// keeps one (time 0 without), else at the mark that holds its line
    /// (time 0 and its line where no mark does).
    pub(crate) fn place(&self, finding: &Finding) -> At {
        let line = finding.line;
        match mark_kind(finding) {
            None => At {
                t: finding.timestamp.map_or(0, micros),
                line,
            },
            Some(kind) => self
                .mark_at(&finding.bus, finding.node, kind, line)
                .unwrap_or(At { t: 0, line }),
        }
    }

    /// The time of the mark that holds a finding whose time the summary
    /// does not keep, to the microsecond, in a recording drawn by time.
    fn time_of(&self, finding: &Finding) -> Option<Timestamp> {
        if !self.timed {
            return None;
        }
        let at = self.mark_at(
            &finding.bus,
            finding.node,
            mark_kind(finding)?,
            finding.line,
        )?;
        Some(Timestamp::from_duration(core::time::Duration::from_micros(
            at.t,
        )))
    }

    /// Return how many events of `kind` the row of `node` on `bus` (the
    /// bus's own row for `None`) holds: what its marks' `data-count`s add
    /// up to (docs/report.md#marks).
    #[must_use]
    pub fn mark_count(&self, bus: &BusName, node: Option<NodeId>, kind: MarkKind) -> u64 {
        self.row(bus, node).map_or(0, |row| {
            row.marks[kind.index()]
                .items()
                .iter()
                .map(|m| m.count)
                .sum()
        })
    }
}

impl Recording {
    /// Return what went wrong ([`Summary::findings_with`],
    /// docs/summary.md#findings), each finding at the time of its mark on
    /// the timeline, to the microsecond: the list the page's "What went
    /// wrong" shows (docs/report.md#page).
    #[must_use]
    pub fn findings(&self) -> Vec<Finding> {
        self.summary
            .findings_with(|finding| self.timeline.time_of(finding))
    }
}

/// One recording: its summary and its timeline, and with several files
/// read as one (`--joined`), where each file's lines lie.
#[derive(Debug, Clone)]
pub struct Recording {
    /// The post-mortem, as `decode --summary` writes it.
    pub summary: Summary,
    /// What the page draws of it.
    pub timeline: Timeline,
    /// The files of a recording read from several (docs/output.md#several-files):
    /// their records follow the summary's in the embedded JSON.
    pub files: Vec<FileSpan>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::can::{BusStatus, CanFrame, CanId};

    /// The rows are found by the bus's place in the decoder's table, but
    /// kept in the order of the buses' first frames: a bus that a status
    /// event named first (so that the decoder's table holds it first) comes
    /// after the bus of the first frame, and a bus named by status events
    /// only has no rows.
    #[test]
    fn rows_follow_the_first_frames_not_the_decoders_table() {
        let emcy = |iface| {
            let frame = CanFrame::new(
                CanId::standard(0x083).unwrap(),
                &[0, 0x10, 1, 0, 0, 0, 0, 0],
            )
            .unwrap();
            LogEvent::Frame(LogFrame::new(frame).with_iface(iface))
        };
        let status = |iface| {
            LogEvent::Status(BusStatus {
                timestamp: None,
                iface: Some(iface),
            })
        };
        let (can0, can1, can2) = (
            Iface::Name("can0"),
            Iface::Name("can1"),
            Iface::Name("can2"),
        );
        let mut recorder = Recorder::new(DecoderConfig::new());
        let events = [
            status(can1),
            status(can2),
            emcy(can0),
            emcy(can1),
            emcy(can0),
            status(can1),
        ];
        for (i, event) in events.iter().enumerate() {
            recorder.add(Position::Line(i as u64 + 1), event);
        }
        let timeline = recorder.finish().timeline;
        let names: Vec<_> = timeline.buses.iter().map(|b| b.name.to_string()).collect();
        assert_eq!(names, ["can0", "can1"]);
        let node = NodeId::new(3);
        let emcys = |bus| timeline.mark_count(&BusName::of(Some(bus)), node, MarkKind::Emcy);
        assert_eq!((emcys(can0), emcys(can1), emcys(can2)), (2, 1, 0));
    }
}
