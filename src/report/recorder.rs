//! The recording of a log: the [`Recorder`] fed every frame and bus event,
//! and what it returns, the [`Recording`]: the [`Summary`] and its
//! [`Timeline`] (docs/report.md#bounded).

use std::collections::BTreeMap;

use crate::can::{BusName, Iface, LogEvent, LogFrame, Timestamp};
use crate::canopen::{Cia402State, NodeId, Value};
use crate::decoder::ethercat::ProcessData;
use crate::decoder::DecoderConfig;
use crate::ethercat::Command;
use crate::logs::Position;
use crate::servo::{ActualPosition, EnablePhase, HandshakePhase};
use crate::summary::{
    EthercatFact, FileSpan, Finding, FindingKind, ServoChange, Summarizer, Summary, SummaryEvent,
    SummaryEventKind,
};

use super::series::{
    At, BandItem, Detail, MarkItem, RateBucket, Series, SignalBucket, BUCKETS, EXACT_MARKS,
    HANDSHAKE_PHASES, SIGNAL_BUCKETS,
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
    /// A CoE emergency of an EtherCAT slave (`emcy_count` of its record,
    /// docs/ethercat.md#summary).
    CoeEmcy,
    /// An AL status read with its error indicator set: a slave that
    /// refused or left a state (the `al_timeline` entries with `error`).
    AlError,
    /// A change of an EtherCAT slave's DL status (`dl_status_changes`).
    DlChange,
    /// A rise of an EtherCAT slave's error counter (`error_counter_rises`).
    ErrorCounter,
    /// A frame of a cyclic stream sent and never returned (the stream
    /// record's `lost`).
    LostFrame,
    /// A returned copy of a cyclic stream with another working counter
    /// than its usual one (`wkc_mismatches`).
    WkcMismatch,
    /// A fault of a servo's error word set (`servo.fault_set_count`,
    /// docs/ethercat.md#servo).
    ServoFault,
    /// A servo's error-clear handshake requested (`servo.error_clear_count`).
    ServoErrorClear,
    /// A servo's zero-pulse handshake requested (`servo.zero_pulse_count`).
    ServoZeroPulse,
    /// ServoRDY seen low (`servo.not_ready_count`).
    ServoNotReady,
    /// An enable edge the servo did not answer (`servo.enable_unanswered`).
    ServoEnableUnanswered,
}

impl MarkKind {
    /// Every kind, in the order of docs/report.md#marks.
    pub const ALL: [MarkKind; 23] = [
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
        MarkKind::CoeEmcy,
        MarkKind::AlError,
        MarkKind::DlChange,
        MarkKind::ErrorCounter,
        MarkKind::LostFrame,
        MarkKind::WkcMismatch,
        MarkKind::ServoFault,
        MarkKind::ServoErrorClear,
        MarkKind::ServoZeroPulse,
        MarkKind::ServoNotReady,
        MarkKind::ServoEnableUnanswered,
    ];

    /// The kinds a CAN device's row draws.
    pub const NODE: [MarkKind; 9] = [
        MarkKind::Emcy,
        MarkKind::EmcyReset,
        MarkKind::BootUp,
        MarkKind::HeartbeatTimeout,
        MarkKind::SdoAbort,
        MarkKind::SdoBroken,
        MarkKind::SdoTimeout,
        MarkKind::ToggleError,
        MarkKind::Cia402Fault,
    ];

    /// The kinds a CAN bus's row draws.
    pub const BUS: [MarkKind; 3] = [
        MarkKind::ErrorFrame,
        MarkKind::BusOff,
        MarkKind::ErrorPassive,
    ];

    /// The kinds an EtherCAT slave's row draws.
    pub const SLAVE: [MarkKind; 11] = [
        MarkKind::CoeEmcy,
        MarkKind::AlError,
        MarkKind::SdoAbort,
        MarkKind::DlChange,
        MarkKind::ErrorCounter,
        MarkKind::Cia402Fault,
        MarkKind::ServoFault,
        MarkKind::ServoErrorClear,
        MarkKind::ServoZeroPulse,
        MarkKind::ServoNotReady,
        MarkKind::ServoEnableUnanswered,
    ];

    /// The kinds an EtherCAT stream's row draws.
    pub const STREAM: [MarkKind; 2] = [MarkKind::LostFrame, MarkKind::WkcMismatch];

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
            MarkKind::CoeEmcy => "coe_emcy",
            MarkKind::AlError => "al_error",
            MarkKind::DlChange => "dl_change",
            MarkKind::ErrorCounter => "error_counter",
            MarkKind::LostFrame => "lost_frame",
            MarkKind::WkcMismatch => "wkc_mismatch",
            MarkKind::ServoFault => "servo_fault",
            MarkKind::ServoErrorClear => "servo_error_clear",
            MarkKind::ServoZeroPulse => "servo_zero_pulse",
            MarkKind::ServoNotReady => "servo_not_ready",
            MarkKind::ServoEnableUnanswered => "servo_enable_unanswered",
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
            MarkKind::CoeEmcy => "CoE EMCY",
            MarkKind::AlError => "AL error",
            MarkKind::DlChange => "DL status change",
            MarkKind::ErrorCounter => "error counter rise",
            MarkKind::LostFrame => "lost frame",
            MarkKind::WkcMismatch => "working counter mismatch",
            MarkKind::ServoFault => "servo fault",
            MarkKind::ServoErrorClear => "servo error clear",
            MarkKind::ServoZeroPulse => "servo zero pulse",
            MarkKind::ServoNotReady => "ServoRDY low",
            MarkKind::ServoEnableUnanswered => "unanswered enable edge",
        }
    }

    const fn index(self) -> usize {
        self as usize
    }
}

/// The signals a drive's charts show (docs/report.md#signals), in the
/// charts' order: each its `data-signal` and its title. A CAN drive's
/// position and velocity actual values 6064h and 606Ch ([`CAN_CHARTED`]),
/// an EtherCAT CiA 402 drive's also the target position 607Ah and
/// target velocity 60FFh ([`SLAVE_CHARTED`]), a servo's ActPos and speed
/// set point ([`ACT_POS`], [`SPEED_SETPOINT`]).
pub(super) const CHARTED: [(&str, &str); 6] = [
    ("6064", "Position actual value (6064h)"),
    ("607a", "Target position (607Ah)"),
    ("606c", "Velocity actual value (606Ch)"),
    ("60ff", "Target velocity (60FFh)"),
    ("act_pos", "ActPos (actual position)"),
    ("speed_setpoint", "Speed set point (SSP)"),
];

/// The objects a CAN drive's PDOs are charted of, sub-index 0, with
/// their places in [`CHARTED`].
const CAN_CHARTED: [(u16, usize); 2] = [(0x6064, 0), (0x606C, 2)];

/// The objects an EtherCAT slave's process data is charted of, sub-index
/// 0, with their places in [`CHARTED`].
const SLAVE_CHARTED: [(u16, usize); 4] = [(0x6064, 0), (0x607A, 1), (0x606C, 2), (0x60FF, 3)];

/// A servo's ActPos in [`CHARTED`].
const ACT_POS: usize = 4;
/// A servo's speed set point in [`CHARTED`].
const SPEED_SETPOINT: usize = 5;

/// A signal's value as a chart plots it: a number, finite.
fn plotted(value: &Value) -> Option<f64> {
    let value = match *value {
        Value::Signed(v) => v as f64,
        Value::Unsigned(v) => v as f64,
        Value::Real32(v) => f64::from(v),
        Value::Real64(v) => v,
        _ => return None,
    };
    value.is_finite().then_some(value)
}

/// What a row of the timeline keeps: marks by kind, the state bands, a
/// drive's signals, a bus's or a stream's frame rate. A CAN device's row
/// has NMT bands, an EtherCAT slave's AL bands; both have CiA 402 bands
/// for a drive.
#[derive(Debug, Clone)]
pub(crate) struct RowData {
    pub(crate) marks: [Series<MarkItem>; MarkKind::ALL.len()],
    pub(crate) nmt: Series<BandItem>,
    /// An EtherCAT slave's AL states as it reported them; a band's state
    /// is the AL status's low byte (state bits 0–3, error indicator bit 4).
    pub(crate) al: Series<BandItem>,
    nmt_state: Option<u8>,
    /// Where the last NMT band begins.
    nmt_since: At,
    pub(crate) cia402: Series<BandItem>,
    /// A servo's enable handshake phases (an `EnablePhase` as its index,
    /// [`enable_phase`]).
    pub(crate) servo: Series<BandItem>,
    /// Per entry of [`CHARTED`]: its values, once seen.
    pub(crate) signals: [Option<Series<SignalBucket>>; CHARTED.len()],
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
            al: Series::new(BUCKETS, BUCKETS, timed),
            cia402: Series::new(BUCKETS, BUCKETS, timed),
            servo: Series::new(BUCKETS, BUCKETS, timed),
            signals: Default::default(),
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

    /// An EMCY of `kind` (with its code's run, docs/report.md#events).
    fn emcy(&mut self, kind: MarkKind, at: At, detail: Detail, code: u16, timed: bool) {
        self.mark(kind, at, at, detail);
        let run = self.codes.entry(code).or_insert(CodeRun {
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

    /// A value of the signal at `chart` in [`CHARTED`].
    fn plot(&mut self, chart: usize, at: At, value: f64, timed: bool) {
        self.signals[chart]
            .get_or_insert_with(|| Series::new(0, SIGNAL_BUCKETS, timed))
            .add(SignalBucket {
                at,
                min: (at, value),
                max: (at, value),
            });
    }

    /// A phase of a servo's handshake of `kind`: a request is a new mark,
    /// the phases after it complete the last one's detail.
    fn handshake(&mut self, kind: MarkKind, at: At, phase: HandshakePhase, position: Option<i32>) {
        if phase == HandshakePhase::Requested {
            let detail = Detail::Handshake {
                phases: [phase; HANDSHAKE_PHASES],
                len: 1,
                position,
            };
            self.mark(kind, at, at, detail);
            return;
        }
        let Some(last) = self.marks[kind.index()].last_mut() else {
            return;
        };
        if let (
            1,
            Detail::Handshake {
                phases,
                len,
                position: at_ack,
            },
        ) = (last.count, &mut last.detail)
        {
            let n = usize::from(*len);
            if phases[n - 1] == HandshakePhase::Done {
                return;
            }
            phases[n.min(HANDSHAKE_PHASES - 1)] = phase;
            *len = (n + 1).min(HANDSHAKE_PHASES) as u8;
            if position.is_some() {
                *at_ack = position;
            }
        }
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

/// An EtherCAT interface's rows: one per slave, at the slave's place
/// among the interface's slave records, and one per stream.
#[derive(Debug, Clone)]
pub(crate) struct PortRows {
    pub(crate) name: BusName,
    slaves: Vec<RowData>,
    pub(crate) streams: Vec<StreamRows>,
}

/// A datagram stream's row, and its returned copies by working counter
/// until the summary says which is the usual one.
#[derive(Debug, Clone)]
pub(crate) struct StreamRows {
    pub(crate) command: Command,
    pub(crate) address: u32,
    pub(crate) row: RowData,
    /// The returned copies of each working counter the stream counts (at
    /// most 64, as the summary counts them).
    wkcs: Vec<(u16, Series<MarkItem>)>,
}

impl PortRows {
    fn new(name: BusName) -> Self {
        PortRows {
            name,
            slaves: Vec::new(),
            streams: Vec::new(),
        }
    }

    fn slave(&mut self, place: usize, timed: bool) -> &mut RowData {
        while self.slaves.len() <= place {
            self.slaves.push(RowData::new(timed));
        }
        &mut self.slaves[place]
    }

    /// The row of the slave at `place` among the interface's slave records.
    pub(crate) fn slave_row(&self, place: usize) -> Option<&RowData> {
        self.slaves.get(place)
    }

    fn stream(&mut self, command: Command, address: u32, timed: bool) -> &mut StreamRows {
        let at = match self
            .streams
            .iter()
            .position(|s| s.command == command && s.address == address)
        {
            Some(at) => at,
            None => {
                self.streams.push(StreamRows {
                    command,
                    address,
                    row: RowData::new(timed),
                    wkcs: Vec::new(),
                });
                self.streams.len() - 1
            }
        };
        &mut self.streams[at]
    }

    /// The row of the stream of `command` at `address`.
    pub(crate) fn stream_row(&self, command: Command, address: u32) -> Option<&RowData> {
        self.streams
            .iter()
            .find(|s| s.command == command && s.address == address)
            .map(|s| &s.row)
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
    /// Each EtherCAT interface's rows, in the order of their first facts.
    ports: Vec<PortRows>,
    /// Each EtherCAT interface's slaves' signals, by the slave's place
    /// among its records; they join the slaves' rows at the end.
    plots: Vec<(BusName, Vec<RowData>)>,
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
            ports: Vec::new(),
            plots: Vec::new(),
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
            LogEvent::Status(_) => self.summarizer.add(position, event),
            LogEvent::Ethercat(packet) => {
                let at = self.place(position, packet.timestamp);
                let timed = self.timed == Some(true);
                let Recorder {
                    summarizer,
                    ports,
                    plots,
                    ..
                } = self;
                summarizer.add_ethercat_with(
                    position,
                    packet,
                    |event| record_ethercat(ports, timed, at, &event),
                    |iface, place, data| plot_process_data(plots, timed, at, iface, place, data),
                );
            }
        }
    }

    /// Where an entry read at `position` with `timestamp` lies: the first
    /// entry says whether the recording is drawn by time; an entry
    /// without a time in a recording drawn by time lies at the time of the
    /// one before it.
    fn place(&mut self, position: Position, timestamp: Option<Timestamp>) -> At {
        let timed = *self.timed.get_or_insert(timestamp.is_some());
        match timestamp {
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
        at
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
        let at = self.place(position, log.timestamp);
        let timed = self.timed == Some(true);
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
                let Some(&(_, chart)) = CAN_CHARTED
                    .iter()
                    .find(|(index, _)| *index == entry.index())
                else {
                    continue;
                };
                if let Some(value) = plotted(&signal.value) {
                    rows.node(node, timed).plot(chart, at, value, timed);
                }
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
            mut ports,
            plots,
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
            if let SummaryEventKind::Ethercat(_) = event.kind {
                record_ethercat(&mut ports, timed, end, &event);
                return;
            }
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
        for (iface, slaves) in plots {
            let at = match ports.iter().position(|p| p.name == iface) {
                Some(at) => at,
                None => {
                    ports.push(PortRows::new(iface));
                    ports.len() - 1
                }
            };
            for (place, plotted) in slaves.into_iter().enumerate() {
                if plotted.signals.iter().any(Option::is_some) {
                    ports[at].slave(place, timed).signals = plotted.signals;
                }
            }
        }
        for port in &mut ports {
            for stream in &mut port.streams {
                let usual = summary
                    .ethercat
                    .streams
                    .iter()
                    .find(|s| {
                        s.iface == port.name
                            && s.command == stream.command
                            && s.address == stream.address
                    })
                    .and_then(|s| s.wkc_usual);
                stream.mismatches(usual);
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
                ports,
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
            row.emcy(kind, at, detail, code.get(), timed);
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
        // On an EtherCAT interface's rows (`record_ethercat`).
        SummaryEventKind::Ethercat(_) => {}
    }
}

impl StreamRows {
    /// The returned copies whose working counter is not `usual` (the
    /// summary's `wkc_usual`) as the row's mismatch marks.
    fn mismatches(&mut self, usual: Option<u16>) {
        let Some(usual) = usual else {
            self.wkcs.clear();
            return;
        };
        let series = &mut self.row.marks[MarkKind::WkcMismatch.index()];
        for (wkc, copies) in self.wkcs.drain(..) {
            if wkc == usual {
                continue;
            }
            for item in copies.items() {
                series.add(MarkItem {
                    detail: Detail::Wkc { wkc, usual },
                    ..*item
                });
            }
        }
    }
}

/// Plot one cycle of a slave's process data, the slave at `place` among
/// the slave records of `iface` (docs/report.md#signals): a servo's
/// ActPos (from confirmed feedback) and speed set point, and the position
/// and velocity objects its PDOs map (inputs where confirmed).
fn plot_process_data(
    plots: &mut Vec<(BusName, Vec<RowData>)>,
    timed: bool,
    at: At,
    iface: &BusName,
    place: usize,
    data: &ProcessData<'_>,
) {
    let port = match plots.iter().position(|(name, _)| name == iface) {
        Some(port) => port,
        None => {
            plots.push((iface.clone(), Vec::new()));
            plots.len() - 1
        }
    };
    let slaves = &mut plots[port].1;
    let row = |slaves: &mut Vec<RowData>| {
        while slaves.len() <= place {
            slaves.push(RowData::new(timed));
        }
    };
    if let Some(servo) = &data.servo {
        row(slaves);
        let row = &mut slaves[place];
        if let Some(feedback) = &servo.feedback {
            let position = match feedback.actual_position() {
                ActualPosition::Absolute(position) => position as f64,
                ActualPosition::Incremental { position, .. } => f64::from(position),
            };
            row.plot(ACT_POS, at, position, timed);
        }
        let speed = f64::from(servo.command.speed_setpoint);
        row.plot(SPEED_SETPOINT, at, speed, timed);
    }
    if !data.has_signals() {
        return;
    }
    // Inputs the working counter leaves unconfirmed are not charted, as
    // no state is read from them (docs/ethercat.md#process-data).
    let confirmed = data.confirmed;
    data.for_each_signal(|output, _, signal| {
        let Ok(signal) = signal else { return };
        if !output && !confirmed {
            return;
        }
        let entry = signal.entry;
        if entry.sub_index() != 0 {
            return;
        }
        let Some(&(_, chart)) = SLAVE_CHARTED
            .iter()
            .find(|(index, _)| *index == entry.index())
        else {
            return;
        };
        if let Some(value) = plotted(&signal.value) {
            row(slaves);
            slaves[place].plot(chart, at, value, timed);
        }
    });
}

/// Record one fact of an EtherCAT capture's slave or stream records on its
/// row (docs/report.md#ethercat).
fn record_ethercat(ports: &mut Vec<PortRows>, timed: bool, now: At, event: &SummaryEvent<'_>) {
    let SummaryEventKind::Ethercat(fact) = event.kind else {
        return;
    };
    let at = At {
        t: event.timestamp.map_or(now.t, micros),
        line: event.line,
    };
    let port = match ports.iter().position(|p| &p.name == event.bus) {
        Some(port) => port,
        None => {
            ports.push(PortRows::new(event.bus.clone()));
            ports.len() - 1
        }
    };
    let port = &mut ports[port];
    match fact {
        EthercatFact::AlState { slave, change } => {
            if change.requested {
                return;
            }
            let row = port.slave(slave, timed);
            let status = change.status;
            let state = status.state_bits() | if status.error() { AL_ERROR } else { 0 };
            RowData::band(&mut row.al, at, state);
            if status.error() {
                let detail = Detail::Al {
                    state,
                    code: change.code.map(|c| c.0),
                };
                row.mark(MarkKind::AlError, at, at, detail);
            }
        }
        EthercatFact::AlCode { slave, of, code } => {
            let row = port.slave(slave, timed);
            if let Some(last) = row.marks[MarkKind::AlError.index()].last_mut() {
                if let (true, Detail::Al { state, code: None }) = (last.at.line == of, last.detail)
                {
                    last.detail = Detail::Al {
                        state,
                        code: Some(code.0),
                    };
                }
            }
        }
        EthercatFact::Emergency { slave, emergency } => {
            let emcy = emergency.emcy;
            let detail = Detail::Emcy {
                code: emcy.code.get(),
                register: emcy.register.bits(),
                manufacturer: emcy.manufacturer,
            };
            port.slave(slave, timed)
                .emcy(MarkKind::CoeEmcy, at, detail, emcy.code.get(), timed);
        }
        EthercatFact::Cia402 {
            slave,
            transition,
            fault,
        } => {
            let row = port.slave(slave, timed);
            RowData::band(&mut row.cia402, at, transition.to as u8);
            if fault.is_some() {
                row.mark(MarkKind::Cia402Fault, at, at, Detail::None);
            }
        }
        EthercatFact::Servo { slave, event } => {
            let row = port.slave(slave, timed);
            let change = event.change;
            match change {
                ServoChange::Enable { to, .. } => {
                    RowData::band(&mut row.servo, at, to as u8);
                    if change.is_unanswered_enable() {
                        let kind = MarkKind::ServoEnableUnanswered;
                        row.mark(kind, at, at, Detail::Servo(change));
                    }
                }
                ServoChange::FaultSet(_) => {
                    row.mark(MarkKind::ServoFault, at, at, Detail::Servo(change));
                }
                ServoChange::Ready(false) => {
                    row.mark(MarkKind::ServoNotReady, at, at, Detail::Servo(change));
                }
                ServoChange::ErrorClear(phase) => {
                    row.handshake(MarkKind::ServoErrorClear, at, phase, None);
                }
                ServoChange::ZeroPulse { phase, position } => {
                    row.handshake(MarkKind::ServoZeroPulse, at, phase, position);
                }
                // What the error word and ServoRDY say after: the marks
                // are where they went wrong.
                ServoChange::FaultCleared(_) | ServoChange::Ready(true) => {}
            }
        }
        EthercatFact::SdoAbort { slave, abort } => {
            let detail = Detail::Abort {
                index: abort.index,
                subindex: abort.subindex,
                code: abort.code.get(),
            };
            port.slave(slave, timed)
                .mark(MarkKind::SdoAbort, at, at, detail);
        }
        EthercatFact::DlChange { slave, .. } => {
            port.slave(slave, timed)
                .mark(MarkKind::DlChange, at, at, Detail::None);
        }
        EthercatFact::CounterRise { slave, rise } => {
            let detail = Detail::Counter {
                register: rise.register,
                from: rise.from,
                to: rise.to,
            };
            port.slave(slave, timed)
                .mark(MarkKind::ErrorCounter, at, at, detail);
        }
        EthercatFact::StreamReturned {
            command,
            address,
            wkc,
        } => {
            let stream = port.stream(command, address, timed);
            stream.row.rate.add(RateBucket { at, frames: 1 });
            let copies = match stream.wkcs.iter().position(|(w, _)| *w == wkc) {
                Some(i) => &mut stream.wkcs[i].1,
                None => {
                    stream
                        .wkcs
                        .push((wkc, Series::new(EXACT_MARKS, BUCKETS, timed)));
                    &mut stream.wkcs.last_mut().expect("just pushed").1
                }
            };
            copies.add(MarkItem {
                at,
                end: at,
                count: 1,
                detail: Detail::None,
            });
        }
        EthercatFact::StreamLost { command, address } => {
            port.stream(command, address, timed).row.mark(
                MarkKind::LostFrame,
                at,
                at,
                Detail::None,
            );
        }
    }
}

/// The AL error indicator in an AL band's state (bit 4 of AL status).
pub(crate) const AL_ERROR: u8 = 0x10;

/// The enable handshake's phases, a servo band's state as its index.
const ENABLE_PHASES: [EnablePhase; 6] = [
    EnablePhase::Disabled,
    EnablePhase::Disabling,
    EnablePhase::Arming,
    EnablePhase::Enabling,
    EnablePhase::Enabled,
    EnablePhase::Dropped,
];

/// The enable phase of a servo band's state.
pub(crate) fn enable_phase(index: u8) -> Option<EnablePhase> {
    ENABLE_PHASES
        .iter()
        .copied()
        .find(|phase| *phase as u8 == index)
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
        // Timed by the summary: placed at their own time.
        FindingKind::AlError | FindingKind::ServoFault => return None,
    })
}

/// A recording's timeline: per bus and device, and per EtherCAT slave and
/// stream, the marks, state bands, signals and frame rate the page draws
/// (docs/report.md#timeline), in bounded memory.
#[derive(Debug, Clone)]
pub struct Timeline {
    timed: bool,
    untimed: u64,
    first: Option<At>,
    last: Option<At>,
    pub(crate) buses: Vec<BusRows>,
    pub(crate) ports: Vec<PortRows>,
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

    /// The rows of the EtherCAT interface `iface`.
    pub(crate) fn port(&self, iface: &BusName) -> Option<&PortRows> {
        self.ports.iter().find(|p| &p.name == iface)
    }

    /// Return how many events of `kind` the row of the EtherCAT slave at
    /// `place` among the slave records of `iface` holds
    /// ([`EthercatFact`]): what its marks' `data-count`s add up to
    /// (docs/report.md#ethercat).
    #[must_use]
    pub fn slave_mark_count(&self, iface: &BusName, place: usize, kind: MarkKind) -> u64 {
        self.port(iface)
            .and_then(|p| p.slave_row(place))
            .map_or(0, |row| count(row, kind))
    }

    /// Return how many events of `kind` the row of the stream of
    /// `command` at `address` (as its `StreamSummary` has them) on
    /// `iface` holds (docs/report.md#ethercat).
    #[must_use]
    pub fn stream_mark_count(
        &self,
        iface: &BusName,
        command: Command,
        address: u32,
        kind: MarkKind,
    ) -> u64 {
        self.port(iface)
            .and_then(|p| p.stream_row(command, address))
            .map_or(0, |row| count(row, kind))
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
        self.row(bus, node).map_or(0, |row| count(row, kind))
    }
}

/// How many events of `kind` a row holds.
fn count(row: &RowData, kind: MarkKind) -> u64 {
    row.marks[kind.index()]
        .items()
        .iter()
        .map(|m| m.count)
        .sum()
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
