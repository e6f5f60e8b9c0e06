//! What a slave record says of the station alias, the mailbox protocol
//! (polls and repeats) and the distributed clock (docs/ethercat.md#summary).

use core::fmt;

use serde::ser::SerializeMap;

use crate::decoder::ethercat::{DcRegisters, Meaning};

/// A slave's station alias, its mailbox polls and repeats, and its
/// distributed clock, as the capture showed them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SlaveRegisters {
    /// The station alias as last read (0x0012).
    pub alias: Option<u16>,
    /// Whether FPxx reach it by its alias (DL control 0x0103 bit 0, as
    /// last written to it or to every slave).
    pub alias_enabled: Option<bool>,
    /// Reads of its mailbox-in sync manager's status (SM1's 0x080D).
    pub mailbox_polls: u64,
    /// Of them, reads that found the mailbox full.
    pub mailbox_polls_full: u64,
    /// The master's repeat requests (0x080E bit 1 toggled).
    pub mailbox_repeat_requests: u64,
    /// Messages read again after a repeat request: counted once, not in
    /// `mailbox_read`.
    pub mailbox_repeated: u64,
    /// Its distributed clock, where the capture touches it.
    pub dc: Option<DcSummary>,
}

/// A slave's distributed clock: its configuration as last written or
/// read, the reference clock's distribution, and the system-time
/// difference reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DcSummary {
    /// Returned ARMW/FRMW datagrams of 0x0910 addressed to it: it is the
    /// reference clock.
    pub distributions: u64,
    /// Cyclic unit control (0x0980).
    pub cyclic_unit_control: Option<u8>,
    /// SYNC activation (0x0981).
    pub activation: Option<u8>,
    /// SYNC0 cycle time, ns (0x09A0).
    pub sync0_cycle_ns: Option<u32>,
    /// SYNC1 cycle time, ns (0x09A4).
    pub sync1_cycle_ns: Option<u32>,
    /// The port receive times as last read (0x0900–0x090F).
    pub receive_times: [Option<u32>; 4],
    /// The system time as last read (0x0910).
    pub system_time: Option<u64>,
    /// The system-time offset as last written or read, ns (0x0920).
    pub system_time_offset_ns: Option<i64>,
    /// The system-time delay as last written or read, ns (0x0928).
    pub system_time_delay_ns: Option<u32>,
    /// Reads of the system-time difference (0x092C).
    pub time_difference_reads: u64,
    /// The last, ns (local copy minus received time).
    pub time_difference_last_ns: Option<i64>,
    /// The smallest.
    pub time_difference_min_ns: Option<i64>,
    /// The largest.
    pub time_difference_max_ns: Option<i64>,
}

impl SlaveRegisters {
    /// Add a meaning of the alias, the mailbox protocol or the clock;
    /// return whether it was one.
    pub(super) fn observe(&mut self, meaning: &Meaning<'_>) -> bool {
        match *meaning {
            Meaning::StationAlias { alias, enabled, .. } => {
                self.alias = alias.or(self.alias);
                self.alias_enabled = enabled.or(self.alias_enabled);
            }
            Meaning::MailboxPoll { full, .. } => {
                self.mailbox_polls += 1;
                self.mailbox_polls_full += u64::from(full);
            }
            Meaning::MailboxRepeat { acknowledged, .. } => {
                self.mailbox_repeat_requests += u64::from(!acknowledged);
            }
            Meaning::Dc { registers, .. } => self.dc_registers(&registers),
            Meaning::DcDistribution { .. } => {
                self.dc.get_or_insert_with(DcSummary::default).distributions += 1;
            }
            _ => return false,
        }
        true
    }

    fn dc_registers(&mut self, r: &DcRegisters) {
        let dc = self.dc.get_or_insert_with(DcSummary::default);
        dc.cyclic_unit_control = r.cyclic_unit_control.or(dc.cyclic_unit_control);
        dc.activation = r.activation.or(dc.activation);
        dc.sync0_cycle_ns = r.sync0_cycle_ns.or(dc.sync0_cycle_ns);
        dc.sync1_cycle_ns = r.sync1_cycle_ns.or(dc.sync1_cycle_ns);
        if r.receive_times.iter().any(Option::is_some) {
            dc.receive_times = r.receive_times;
        }
        dc.system_time = r.system_time.or(dc.system_time);
        dc.system_time_offset_ns = r.system_time_offset_ns.or(dc.system_time_offset_ns);
        dc.system_time_delay_ns = r.system_time_delay_ns.or(dc.system_time_delay_ns);
        if let Some(ns) = r.time_difference_ns {
            dc.time_difference_reads += 1;
            dc.time_difference_last_ns = Some(ns);
            dc.time_difference_min_ns = Some(dc.time_difference_min_ns.map_or(ns, |m| m.min(ns)));
            dc.time_difference_max_ns = Some(dc.time_difference_max_ns.map_or(ns, |m| m.max(ns)));
        }
    }

    /// The slave record's keys: `alias`, `alias_enabled`,
    /// `mailbox_polls`, `mailbox_polls_full`, `mailbox_repeat_requests`,
    /// `mailbox_repeated`, `dc`.
    pub(super) fn entries<M: SerializeMap>(&self, map: &mut M) -> Result<(), M::Error> {
        map.serialize_entry("alias", &self.alias)?;
        map.serialize_entry("alias_enabled", &self.alias_enabled)?;
        map.serialize_entry("mailbox_polls", &self.mailbox_polls)?;
        map.serialize_entry("mailbox_polls_full", &self.mailbox_polls_full)?;
        map.serialize_entry("mailbox_repeat_requests", &self.mailbox_repeat_requests)?;
        map.serialize_entry("mailbox_repeated", &self.mailbox_repeated)?;
        map.serialize_entry("dc", &self.dc.as_ref().map(DcJson))
    }
}

/// A slave's clock as JSON, keys in the order docs/ethercat.md#summary
/// lists them.
struct DcJson<'a>(&'a DcSummary);

impl serde::Serialize for DcJson<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let dc = self.0;
        let bit = |n: u8| dc.activation.map(|a| a & (1 << n) != 0);
        let mut map = serializer.serialize_map(Some(17))?;
        map.serialize_entry("reference_clock", &(dc.distributions > 0))?;
        map.serialize_entry("distributions", &dc.distributions)?;
        map.serialize_entry("cyclic_unit_control", &dc.cyclic_unit_control)?;
        map.serialize_entry("activation", &dc.activation)?;
        map.serialize_entry("cyclic_operation", &bit(0))?;
        map.serialize_entry("sync0", &bit(1))?;
        map.serialize_entry("sync1", &bit(2))?;
        map.serialize_entry("sync0_cycle_ns", &dc.sync0_cycle_ns)?;
        map.serialize_entry("sync1_cycle_ns", &dc.sync1_cycle_ns)?;
        map.serialize_entry("receive_times", &dc.receive_times)?;
        map.serialize_entry("system_time", &dc.system_time)?;
        map.serialize_entry("system_time_offset_ns", &dc.system_time_offset_ns)?;
        map.serialize_entry("system_time_delay_ns", &dc.system_time_delay_ns)?;
        map.serialize_entry("time_difference_reads", &dc.time_difference_reads)?;
        map.serialize_entry("time_difference_last_ns", &dc.time_difference_last_ns)?;
        map.serialize_entry("time_difference_min_ns", &dc.time_difference_min_ns)?;
        map.serialize_entry("time_difference_max_ns", &dc.time_difference_max_ns)?;
        map.end()
    }
}

impl fmt::Display for SlaveRegisters {
    /// What the slave's text line adds, each part after `; `: an alias in
    /// use, the clock, the repeats (polls are counted in JSON alone).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.alias, self.alias_enabled) {
            (Some(alias), Some(true)) => write!(f, "; alias {alias:#06x} ({alias}) enabled")?,
            (Some(alias), _) if alias != 0 => write!(f, "; alias {alias:#06x} ({alias})")?,
            (None, Some(true)) => f.write_str("; alias enabled")?,
            _ => {}
        }
        if let Some(dc) = &self.dc {
            if dc.distributions > 0 {
                write!(
                    f,
                    "; DC reference clock ({} distributions)",
                    dc.distributions
                )?;
            }
            if let Some(activation) = dc.activation {
                let on: Vec<&str> = [(0, "cyclic"), (1, "SYNC0"), (2, "SYNC1")]
                    .into_iter()
                    .filter(|(n, _)| activation & (1 << n) != 0)
                    .map(|(_, name)| name)
                    .collect();
                if on.is_empty() {
                    f.write_str("; SYNC off")?;
                } else {
                    write!(f, "; {}", on.join(" "))?;
                }
            }
            if let Some(ns) = dc.sync0_cycle_ns {
                write!(f, "; SYNC0 cycle {ns} ns")?;
            }
            if let Some(ns) = dc.sync1_cycle_ns.filter(|&ns| ns != 0) {
                write!(f, "; SYNC1 cycle {ns} ns")?;
            }
            if let Some(ns) = dc.system_time_offset_ns {
                write!(f, "; system time offset {ns} ns")?;
            }
            if let Some(ns) = dc.system_time_delay_ns {
                write!(f, "; system time delay {ns} ns")?;
            }
            if let (Some(last), Some(min), Some(max)) = (
                dc.time_difference_last_ns,
                dc.time_difference_min_ns,
                dc.time_difference_max_ns,
            ) {
                let reads = dc.time_difference_reads;
                write!(f, "; system time difference {last} ns")?;
                if reads > 1 {
                    write!(f, " ({min} to {max} ns over {reads} reads)")?;
                }
            }
        }
        if self.mailbox_repeat_requests > 0 || self.mailbox_repeated > 0 {
            let plural = |n: u64| if n == 1 { "" } else { "s" };
            write!(
                f,
                "; {} mailbox repeat request{}, {} message{} read again",
                self.mailbox_repeat_requests,
                plural(self.mailbox_repeat_requests),
                self.mailbox_repeated,
                plural(self.mailbox_repeated)
            )?;
        }
        Ok(())
    }
}
