//! The records of the alias, distributed-clock and mailbox-protocol
//! meanings (docs/ethercat.md#meanings): their kinds, JSON keys and words.

use core::fmt;

use crate::decoder::ethercat::{DcRegisters, Meaning, SlaveRef};
use crate::decoder::json::{self, Object};

/// The kinds a `decode` writes only when `--only` names them: one a cycle
/// or a poll, which the summary counts (docs/ethercat.md#filters).
pub const QUIET_KINDS: [&str; 2] = ["dc_distribution", "mailbox_poll"];

/// The record kind of a meaning of this module, `None` for the others.
pub(super) const fn kind(meaning: &Meaning<'_>) -> Option<&'static str> {
    Some(match meaning {
        Meaning::StationAlias { .. } => "alias",
        Meaning::Dc { .. } => "dc",
        Meaning::DcDistribution { .. } => "dc_distribution",
        Meaning::MailboxPoll { .. } => "mailbox_poll",
        Meaning::MailboxRepeat { .. } => "mailbox_repeat",
        _ => return None,
    })
}

/// The slave of a meaning of this module, `None` for the others.
pub(super) const fn slave(meaning: &Meaning<'_>) -> Option<SlaveRef> {
    match *meaning {
        Meaning::StationAlias { slave, .. }
        | Meaning::Dc { slave, .. }
        | Meaning::DcDistribution { slave, .. }
        | Meaning::MailboxPoll { slave, .. }
        | Meaning::MailboxRepeat { slave, .. } => Some(slave),
        _ => None,
    }
}

/// The keys after `slave` and `position` of a meaning of this module.
pub(super) fn append_json(obj: &mut Object<'_>, meaning: &Meaning<'_>) {
    match *meaning {
        Meaning::StationAlias {
            slave,
            alias,
            enabled,
        } => {
            obj.bool(
                "broadcast",
                slave.station.is_none() && slave.position.is_none(),
            );
            opt_uint(obj, "alias", alias.map(u64::from));
            match enabled {
                Some(enabled) => obj.bool("enabled", enabled),
                None => obj.null("enabled"),
            }
        }
        Meaning::Dc {
            written, registers, ..
        } => {
            obj.name("direction", if written { "write" } else { "read" });
            dc_json(obj, &registers);
        }
        Meaning::DcDistribution {
            system_time, wkc, ..
        } => {
            opt_uint(obj, "system_time", system_time);
            obj.uint("wkc", u64::from(wkc));
        }
        Meaning::MailboxPoll { full, .. } => obj.bool("full", full),
        Meaning::MailboxRepeat { acknowledged, .. } => obj.bool("acknowledged", acknowledged),
        _ => {}
    }
}

/// The registers, null where the datagram does not cover them.
fn dc_json(obj: &mut Object<'_>, dc: &DcRegisters) {
    let out = obj.key("receive_times");
    out.push(b'[');
    for (p, time) in dc.receive_times.iter().enumerate() {
        if p > 0 {
            out.push(b',');
        }
        match time {
            Some(time) => json::uint(out, u64::from(*time)),
            None => out.extend_from_slice(b"null"),
        }
    }
    out.push(b']');
    opt_uint(obj, "system_time", dc.system_time);
    match dc.system_time_offset_ns {
        Some(ns) => json::int(obj.key("system_time_offset_ns"), ns),
        None => obj.null("system_time_offset_ns"),
    }
    opt_uint(
        obj,
        "system_time_delay_ns",
        dc.system_time_delay_ns.map(u64::from),
    );
    match dc.time_difference_ns {
        Some(ns) => json::int(obj.key("time_difference_ns"), ns),
        None => obj.null("time_difference_ns"),
    }
    opt_uint(
        obj,
        "cyclic_unit_control",
        dc.cyclic_unit_control.map(u64::from),
    );
    opt_uint(obj, "activation", dc.activation.map(u64::from));
    for (key, bit) in [
        ("cyclic_operation", dc.cyclic_operation()),
        ("sync0", dc.sync0()),
        ("sync1", dc.sync1()),
    ] {
        match bit {
            Some(bit) => obj.bool(key, bit),
            None => obj.null(key),
        }
    }
    opt_uint(obj, "sync0_cycle_ns", dc.sync0_cycle_ns.map(u64::from));
    opt_uint(obj, "sync1_cycle_ns", dc.sync1_cycle_ns.map(u64::from));
}

fn opt_uint(obj: &mut Object<'_>, key: &'static str, value: Option<u64>) {
    match value {
        Some(value) => obj.uint(key, value),
        None => obj.null(key),
    }
}

/// A meaning of this module in words, after its slave.
pub(super) fn words(f: &mut fmt::Formatter<'_>, meaning: &Meaning<'_>) -> fmt::Result {
    match *meaning {
        Meaning::StationAlias { alias, enabled, .. } => {
            if let Some(alias) = alias {
                write!(f, " alias {alias:#06x} ({alias})")?;
            }
            match enabled {
                Some(true) => f.write_str(" alias enabled"),
                Some(false) => f.write_str(" alias disabled"),
                None => Ok(()),
            }
        }
        Meaning::Dc {
            written, registers, ..
        } => {
            f.write_str(if written { " DC write" } else { " DC read" })?;
            dc_words(f, &registers)
        }
        Meaning::DcDistribution { system_time, .. } => {
            f.write_str(" reference clock")?;
            match system_time {
                Some(time) => write!(f, " system time {time} ns"),
                None => Ok(()),
            }
        }
        Meaning::MailboxPoll { full, .. } => f.write_str(if full {
            " mailbox full"
        } else {
            " mailbox empty"
        }),
        Meaning::MailboxRepeat { acknowledged, .. } => f.write_str(if acknowledged {
            " mailbox repeat acknowledged"
        } else {
            " mailbox repeat requested"
        }),
        _ => Ok(()),
    }
}

fn dc_words(f: &mut fmt::Formatter<'_>, dc: &DcRegisters) -> fmt::Result {
    for (p, time) in dc.receive_times.iter().enumerate() {
        if let Some(time) = time {
            write!(f, " port {p} received {time} ns")?;
        }
    }
    if let Some(time) = dc.system_time {
        write!(f, " system time {time} ns")?;
    }
    if let Some(ns) = dc.system_time_offset_ns {
        write!(f, " system time offset {ns} ns")?;
    }
    if let Some(ns) = dc.system_time_delay_ns {
        write!(f, " system time delay {ns} ns")?;
    }
    if let Some(ns) = dc.time_difference_ns {
        write!(f, " system time difference {ns} ns")?;
    }
    if let Some(control) = dc.cyclic_unit_control {
        write!(f, " cyclic unit control {control:#04x}")?;
    }
    if let Some(activation) = dc.activation {
        write!(f, " activation {activation:#04x}")?;
        for (name, on) in [
            ("cyclic", dc.cyclic_operation()),
            ("SYNC0", dc.sync0()),
            ("SYNC1", dc.sync1()),
        ] {
            if on == Some(true) {
                write!(f, " {name}")?;
            }
        }
    }
    if let Some(ns) = dc.sync0_cycle_ns {
        write!(f, " SYNC0 cycle {ns} ns")?;
    }
    if let Some(ns) = dc.sync1_cycle_ns {
        write!(f, " SYNC1 cycle {ns} ns")?;
    }
    Ok(())
}
