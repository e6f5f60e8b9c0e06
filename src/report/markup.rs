//! Text as the page writes it, shared by the HTML (`html.rs`) and the SVG
//! (`svg.rs`): escaping, and the names of devices and states
//! (docs/report.md#contract).

use crate::can::BusName;
use crate::canopen::{NmtStateByte, NodeId};
use crate::decoder::ethercat::SlaveRef;
use crate::decoder::Device;
use crate::ethercat::AlState;
use crate::summary::SlaveSummary;

use super::recorder::{cia402_state, enable_phase, AL_ERROR, SILENT};

/// Escape text for HTML text and quoted attributes.
pub(super) fn esc(text: &str) -> String {
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

/// A device as the page names it: `can0 node 3` ([`Device`]).
pub(super) fn device(bus: &BusName, node: NodeId) -> String {
    Device::new(bus, node).to_string()
}

pub(super) fn iface_attr(bus: &BusName) -> String {
    match bus {
        BusName::Unnamed => String::new(),
        bus => esc(&bus.to_string()),
    }
}

pub(super) fn nmt_name(state: u8) -> &'static str {
    if state == SILENT {
        return "unknown";
    }
    NmtStateByte::new(state).state_name()
}

pub(super) fn cia402_name(state: u8) -> &'static str {
    cia402_state(state).map_or("unknown", |s| s.name())
}

/// A servo band's enable phase as the summary writes it (`disabled`, …,
/// `dropped`; docs/ethercat.md#servo).
pub(super) fn servo_enable_name(state: u8) -> &'static str {
    enable_phase(state).map_or("unknown", |phase| phase.name())
}

/// An AL band's state as the summary writes it (`init`, `preop`, `boot`,
/// `safeop`, `op`; docs/ethercat.md#summary), `unknown` where the state
/// bits name no one state.
pub(super) fn al_name(state: u8) -> &'static str {
    AlState::from_bits(state).map_or("unknown", AlState::name)
}

/// An AL band's error indicator, as an attribute.
pub(super) fn al_error(state: u8) -> &'static str {
    if state & AL_ERROR != 0 {
        " data-error=\"true\""
    } else {
        ""
    }
}

/// No attribute: a band whose state says it all.
pub(super) fn no_flags(_: u8) -> &'static str {
    ""
}

/// An EtherCAT slave as the page names it, as the text summary does:
/// `enp2s0 slave 0x1001 (4097) at 1`.
pub(super) fn slave_name(s: &SlaveSummary) -> String {
    let slave = SlaveRef {
        station: s.station,
        position: s.position,
    };
    format!("{} {slave}", s.iface)
}
