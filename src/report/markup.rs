//! Text as the page writes it, shared by the HTML (`html.rs`) and the SVG
//! (`svg.rs`): escaping, and the names of devices and states
//! (docs/report.md#contract).

use crate::can::BusName;
use crate::canopen::{NmtStateByte, NodeId};
use crate::decoder::Device;

use super::recorder::{cia402_state, SILENT};

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
