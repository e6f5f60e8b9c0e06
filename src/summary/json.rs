//! `Serialize` for the summary: exactly the records of `motionwire decode
//! --summary --json` (docs/summary.md), key for key and in order.
//!
//! Times are written as JSON numbers with the log's resolution, six or
//! nine decimals (`1700000000.000500`), never rounded through a float
//! (docs/formats.md#timestamps): with `serde_json` they are raw numbers; other
//! serializers see serde_json's raw-value token.

use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};

use crate::can::Timestamp;

use super::text::ms;
use super::values::{Iface, Ts};
use super::{
    BusSummary, Cia402Timeline, EmcySeen, FrameCounts, GuardingSummary, HeartbeatGap,
    HeartbeatSummary, Listed, NodeSummary, SdoAbort, SdoSummary, Summary, SummaryItem,
    SummaryRecord, Timeouts,
};

impl Summary {
    /// Write the summary as `motionwire decode --summary --json` writes it
    /// (docs/summary.md): each of its [`records`](Self::records) as one
    /// JSON object on a line of its own, the keys in the documented order,
    /// every time with the log's own digits (docs/formats.md#timestamps).
    ///
    /// This is the exact JSON. Going through `serde_json::Value`
    /// (`serde_json::to_value`) is not: without serde_json's
    /// `preserve_order` feature a `Value` sorts the keys, and it reads a
    /// time as an `f64`, which rounds `1700000000.000000001`.
    ///
    /// ```
    /// use motionwire::can::LogEvent;
    /// use motionwire::decoder::DecoderConfig;
    /// use motionwire::logs::Position;
    /// use motionwire::summary::Summarizer;
    ///
    /// let mut summarizer = Summarizer::new(DecoderConfig::new());
    /// for (line, text) in ["(1700000000.000000001) can0 705#05"].iter().enumerate() {
    ///     let frame = motionwire::logs::candump::parse_line(text.as_bytes())?.unwrap();
    ///     summarizer.add(Position::Line(line as u64 + 1), &LogEvent::Frame(frame));
    /// }
    /// let mut out = Vec::new();
    /// summarizer.finish().write_json(&mut out)?;
    /// let text = String::from_utf8(out)?;
    /// let lines: Vec<&str> = text.lines().collect();
    /// assert_eq!(lines.len(), 2); // node 5, then the bus
    /// assert!(lines[0].starts_with(r#"{"type":"node","iface":"can0","node":5,"#));
    /// assert!(lines[1].contains(r#""first_ts":1700000000.000000001"#));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn write_json(&self, mut out: impl std::io::Write) -> std::io::Result<()> {
        for record in self.records() {
            record.write_json(&mut out)?;
            out.write_all(b"\n")?;
        }
        Ok(())
    }
}

impl SummaryRecord<'_> {
    /// Write the record as one JSON object, exactly as
    /// [`Summary::write_json`] writes it (without the line break).
    pub fn write_json(&self, out: impl std::io::Write) -> std::io::Result<()> {
        serde_json::to_writer(out, self).map_err(std::io::Error::from)
    }

    /// Return the record as one JSON object, exactly as
    /// [`Summary::write_json`] writes it (without the line break).
    #[must_use]
    pub fn to_json(&self) -> String {
        let mut out = Vec::new();
        // Writing into a `Vec` cannot fail, and the records serialize:
        // every key is a string, every value a number, string or list.
        let _ = self.write_json(&mut out);
        String::from_utf8(out).unwrap_or_default()
    }
}

fn ts<M: SerializeMap>(map: &mut M, key: &str, ts: Option<Timestamp>) -> Result<(), M::Error> {
    map.serialize_entry(key, &ts.map(Ts))
}

impl Serialize for Summary {
    /// The records in output order, as a sequence.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_seq(Some(self.records().count()))?;
        for record in self.records() {
            seq.serialize_element(&record)?;
        }
        seq.end()
    }
}

impl Serialize for SummaryRecord<'_> {
    /// The verdict, node or bus record, with `"file"` first when the
    /// summary names its file.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        if let Some(file) = self.file {
            map.serialize_entry("file", file)?;
        }
        match self.item {
            SummaryItem::Verdict(verdict) => super::verdict::verdict_entries(verdict, &mut map)?,
            SummaryItem::Node(node) => node_entries(node, &mut map)?,
            SummaryItem::Bus(bus) => bus_entries(bus, &mut map)?,
            SummaryItem::EthercatPort(port) => super::ethercat::port_entries(port, &mut map)?,
            SummaryItem::Slave(slave) => super::ethercat::slave_entries(slave, &mut map)?,
            SummaryItem::Stream(stream) => super::ethercat::stream_entries(stream, &mut map)?,
        }
        map.end()
    }
}

impl Serialize for EmcySeen {
    /// `{"line", "ts", "code", "description"}`.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(4))?;
        map.serialize_entry("line", &self.line)?;
        ts(&mut map, "ts", self.timestamp)?;
        map.serialize_entry("code", &self.code.get())?;
        map.serialize_entry("description", self.code.description())?;
        map.end()
    }
}

impl Serialize for FrameCounts {
    /// `{kind: count}` for every kind, in the order of
    /// docs/summary.md#frames.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        for (key, n) in self.iter() {
            map.serialize_entry(key, &n)?;
        }
        map.end()
    }
}

impl Serialize for HeartbeatGap {
    /// `{"after_line", "gap_ms"}`.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(2))?;
        map.serialize_entry("after_line", &self.after_line)?;
        map.serialize_entry("gap_ms", &self.gap_ms())?;
        map.end()
    }
}

impl Serialize for HeartbeatSummary {
    /// `{"count", "last_state", "boot_ups", "boot_up_count"}` and, when
    /// asked for, `"timeouts"` and `"timeout_count"` (a list and its
    /// count, or both null when not checked).
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("count", &self.count)?;
        map.serialize_entry("last_state", &self.last_state.map(|s| s.state_name()))?;
        map.serialize_entry("boot_ups", &self.boot_ups)?;
        map.serialize_entry("boot_up_count", &self.boot_ups.count())?;
        match &self.timeouts {
            Timeouts::NotAsked => {}
            Timeouts::NotChecked => {
                map.serialize_entry("timeouts", &None::<()>)?;
                map.serialize_entry("timeout_count", &None::<()>)?;
            }
            Timeouts::Checked(gaps) => {
                map.serialize_entry("timeouts", gaps)?;
                map.serialize_entry("timeout_count", &gaps.count())?;
            }
        }
        map.end()
    }
}

impl Serialize for GuardingSummary {
    /// `{"answers", "toggle_errors", "toggle_error_count"}`.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(3))?;
        map.serialize_entry("answers", &self.answers)?;
        map.serialize_entry("toggle_errors", &self.toggle_errors)?;
        map.serialize_entry("toggle_error_count", &self.toggle_errors.count())?;
        map.end()
    }
}

impl Serialize for SdoAbort {
    /// `{"line", "index", "subindex", "object", "code", "description",
    /// "by"}`.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(7))?;
        map.serialize_entry("line", &self.line)?;
        map.serialize_entry("index", &self.multiplexer.index)?;
        map.serialize_entry("subindex", &self.multiplexer.sub_index)?;
        map.serialize_entry("object", &self.object)?;
        map.serialize_entry("code", &self.code.get())?;
        map.serialize_entry("description", self.code.description())?;
        map.serialize_entry("by", self.by.name())?;
        map.end()
    }
}

impl Serialize for SdoSummary {
    /// docs/summary.md#sdo: `{"requests", "transfers", "aborts",
    /// "abort_count", "broken", "broken_count", "timeouts", "timeout_count",
    /// "latency_ms"}`.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        struct Latency<'a>(&'a super::LatencyStats);
        impl Serialize for Latency<'_> {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let mut map = serializer.serialize_map(Some(4))?;
                map.serialize_entry("count", &self.0.count)?;
                map.serialize_entry("median", &ms(self.0.median))?;
                map.serialize_entry("p99", &ms(self.0.p99))?;
                map.serialize_entry("max", &ms(self.0.max))?;
                map.end()
            }
        }
        let mut map = serializer.serialize_map(Some(9))?;
        map.serialize_entry("requests", &self.requests)?;
        map.serialize_entry("transfers", &self.transfers)?;
        map.serialize_entry("aborts", &self.aborts)?;
        map.serialize_entry("abort_count", &self.aborts.count())?;
        map.serialize_entry("broken", &self.broken)?;
        map.serialize_entry("broken_count", &self.broken.count())?;
        map.serialize_entry("timeouts", &self.timeouts)?;
        map.serialize_entry("timeout_count", &self.timeouts.count())?;
        map.serialize_entry("latency_ms", &self.latency.as_ref().map(Latency))?;
        map.end()
    }
}

impl Serialize for Cia402Timeline {
    /// docs/summary.md#cia402: `{"transitions": [{"line", "ts", "from", "to"}],
    /// "transition_count", "last_state", "faults": [lines], "fault_count"}`;
    /// `"faults"` and `"fault_count"` null when no statusword was seen (the
    /// decision in docs/summary.md#cia402).
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        /// The lines of the faults kept.
        struct FaultLines<'a>(&'a Listed<super::Cia402Fault>);
        impl Serialize for FaultLines<'_> {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                serializer.collect_seq(self.0.iter().map(|f| f.transition.line))
            }
        }
        let mut map = serializer.serialize_map(Some(5))?;
        map.serialize_entry("transitions", &self.transitions)?;
        map.serialize_entry("transition_count", &self.transitions.count())?;
        map.serialize_entry("last_state", &self.last_state().map(|s| s.name()))?;
        map.serialize_entry("faults", &self.faults.as_ref().map(FaultLines))?;
        map.serialize_entry("fault_count", &self.faults.as_ref().map(Listed::count))?;
        map.end()
    }
}

impl Serialize for super::Cia402Transition {
    /// `{"line", "ts", "from", "to"}`.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(4))?;
        map.serialize_entry("line", &self.line)?;
        ts(&mut map, "ts", self.timestamp)?;
        map.serialize_entry("from", &self.from.map(|s| s.name()))?;
        map.serialize_entry("to", self.to.name())?;
        map.end()
    }
}

impl Serialize for NodeSummary {
    /// The node record of docs/summary.md#node.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        node_entries(self, &mut map)?;
        map.end()
    }
}

fn node_entries<M: SerializeMap>(n: &NodeSummary, map: &mut M) -> Result<(), M::Error> {
    map.serialize_entry("type", "node")?;
    map.serialize_entry("iface", &Iface(&n.bus))?;
    map.serialize_entry("node", &n.node.get())?;
    map.serialize_entry("frames", &n.frames)?;
    map.serialize_entry("emcy", &n.emcy)?;
    map.serialize_entry("first_error", &n.first_error)?;
    map.serialize_entry("active_error", &n.active_error)?;
    map.serialize_entry("resets", &n.resets)?;
    map.serialize_entry("last_register", &n.last_register.map(|r| r.bits()))?;
    map.serialize_entry("heartbeat", &n.heartbeat)?;
    map.serialize_entry("guarding", &n.guarding)?;
    map.serialize_entry("sdo", &n.sdo)?;
    map.serialize_entry("cia402", &n.cia402)
}

impl Serialize for BusSummary {
    /// The bus record of docs/summary.md#bus.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        bus_entries(self, &mut map)?;
        map.end()
    }
}

fn bus_entries<M: SerializeMap>(b: &BusSummary, map: &mut M) -> Result<(), M::Error> {
    map.serialize_entry("type", "bus")?;
    map.serialize_entry("iface", &Iface(&b.bus))?;
    map.serialize_entry("frames", &b.frames)?;
    map.serialize_entry("error_frames", &b.error_frames)?;
    map.serialize_entry("bus_off", &b.bus_off)?;
    map.serialize_entry("bus_off_count", &b.bus_off.count())?;
    map.serialize_entry("error_passive", &b.error_passive)?;
    map.serialize_entry("error_passive_count", &b.error_passive.count())?;
    map.serialize_entry("status_events", &b.status_events)?;
    ts(map, "first_ts", b.first_timestamp)?;
    ts(map, "last_ts", b.last_timestamp)?;
    let nodes: Vec<u8> = b.nodes.iter().map(|n| n.get()).collect();
    map.serialize_entry("nodes", &nodes)
}
