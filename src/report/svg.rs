//! The page's SVG (docs/report.md#timeline, #signals): marks and their
//! clusters, state bands, the frame rate, device rows, the time axis, the
//! legend and the drive charts, written as plain markup into the page's
//! text.

use std::fmt::Write as _;

use crate::canopen::{Emcy, ErrorCode, ErrorRegister, SdoAbortCode};
use crate::ethercat::register::error_counter_name;
use crate::ethercat::{AlState, AlStatusCode};
use crate::profiles::Profile;
use crate::servo::HandshakePhase;
use crate::summary::{NodeSummary, ProfileReading, ServoChange, SlaveSummary, StreamSummary};

use super::fixed::Fixed;
use super::layout::{Axis, Budget, AXIS, EXACT_BANDS, LEFT, PLOT, WIDTH};
use super::markup::{
    al_error, al_name, cia402_name, device, esc, iface_attr, nmt_name, no_flags, servo_enable_name,
    slave_name,
};
use super::recorder::{enable_phase, MarkKind, RowData, AL_ERROR, CHARTED, SILENT};
use super::series::{At, BandItem, Detail, MarkItem, RateBucket, Series};

/// A mark as drawn: one event, or a cluster of neighbours.
#[derive(Debug, Clone, Copy)]
pub(super) struct Drawn {
    pub(super) at: At,
    pub(super) end: At,
    pub(super) count: u64,
    pub(super) detail: Detail,
}

/// The marks of a series as drawn: one by one up to 500, else neighbours
/// within a pixel of the default width as one cluster
/// (docs/report.md#clusters).
pub(super) fn drawn_marks(
    axis: &Axis,
    series: &Series<MarkItem>,
    radius: Option<f64>,
) -> Vec<Drawn> {
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
pub(super) struct DrawnBand {
    item: BandItem,
    x0: f64,
    x1: f64,
}

/// The bands of a series up to `end`; more than 500 on a row: consecutive
/// bands narrower than a pixel merge into one (docs/report.md#bands).
pub(super) fn drawn_bands(
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

/// What a mark says, in words: its title and its event-table cell; an
/// EMCY's with what the device's `profile` reads in it
/// (docs/summary.md#profiles).
pub(super) fn mark_text(kind: MarkKind, m: &Drawn, axis: &Axis, profile: Profile) -> String {
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
        Detail::Emcy {
            code,
            register,
            manufacturer,
        } => {
            let code = ErrorCode::new(code);
            let emcy = Emcy::new(
                code,
                ErrorRegister::from_bits_retain(register),
                manufacturer,
            );
            let _ = write!(
                text,
                "{} {code} {}{} (register 0x{register:02X})",
                kind.words(),
                code.description(),
                ProfileReading::of(&emcy, profile)
            );
        }
        Detail::Gap(us) => {
            let _ = write!(text, "no heartbeat for {} ms", us as f64 / 1000.0);
        }
        Detail::Al { state, code } => {
            let _ = write!(text, "AL status {} with error", al_name(state));
            match code {
                Some(code) => {
                    let _ = write!(text, " {}", AlStatusCode(code));
                }
                None => text.push_str(", code not read"),
            }
        }
        Detail::Abort {
            index,
            subindex,
            code,
        } => {
            let _ = write!(
                text,
                "{} {index:04X}sub{subindex} {}",
                kind.words(),
                SdoAbortCode::new(code)
            );
        }
        Detail::Counter { register, from, to } => {
            let name = error_counter_name(usize::from(register.wrapping_sub(0x0300)));
            let _ = write!(text, "{} {from} → {to}", name.unwrap_or("error counter"));
        }
        Detail::Wkc { wkc, usual } => {
            let _ = write!(text, "working counter {wkc}, usually {usual}");
        }
        Detail::Servo(change) => match change {
            ServoChange::FaultSet(fault) => {
                let _ = write!(text, "servo {change}: {}", fault.description());
            }
            ServoChange::Ready(false) => text.push_str(kind.words()),
            _ => {
                let _ = write!(text, "{}: {change}", kind.words());
            }
        },
        Detail::Handshake {
            phases,
            len,
            position,
        } => {
            text.push_str(kind.words());
            for (i, phase) in phases.iter().take(usize::from(len)).enumerate() {
                let _ = write!(text, "{}{phase}", if i == 0 { " " } else { " → " });
                if let (HandshakePhase::Acknowledged, Some(at)) = (phase, position) {
                    let _ = write!(text, " (zero pulse at {at})");
                }
            }
        }
        Detail::None => text.push_str(kind.words()),
    }
    let _ = write!(text, " (line {}, {})", m.at.line, axis.when(m.at));
    text
}

/// Where a kind's marks sit in a row's marks lane, and how they look.
pub(super) fn mark_y(kind: MarkKind) -> f64 {
    match kind {
        MarkKind::Emcy | MarkKind::EmcyReset => 7.0,
        MarkKind::BootUp | MarkKind::HeartbeatTimeout | MarkKind::ToggleError => 19.0,
        MarkKind::SdoAbort | MarkKind::SdoBroken | MarkKind::SdoTimeout => 19.0,
        MarkKind::Cia402Fault => 7.0,
        MarkKind::ErrorFrame | MarkKind::BusOff | MarkKind::ErrorPassive => 8.0,
        MarkKind::CoeEmcy => 7.0,
        MarkKind::AlError | MarkKind::DlChange | MarkKind::ErrorCounter => 19.0,
        MarkKind::LostFrame | MarkKind::WkcMismatch => 12.0,
        MarkKind::ServoFault | MarkKind::ServoNotReady => 7.0,
        MarkKind::ServoErrorClear | MarkKind::ServoZeroPulse | MarkKind::ServoEnableUnanswered => {
            19.0
        }
    }
}

/// Draw a row's marks of one kind; `lane` is the y of its marks lane.
pub(super) fn marks(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    row: &RowData,
    kind: MarkKind,
    lane: Option<f64>,
    profile: Profile,
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
                "<rect x=\"{}\" y=\"{y}\" width=\"{}\" height=\"{h}\" data-kind=\"{name}\" data-line=\"{}\" data-count=\"{}\"",
                Fixed::<3>(x0),
                Fixed::<3>(w),
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
                "<use href=\"#s-{name}\" x=\"{}\" y=\"{base}\" data-kind=\"{name}\" data-line=\"{}\" data-count=\"1\"",
                Fixed::<3>(x0),
                m.at.line
            );
            "use"
        };
        if budget.titles {
            let _ = writeln!(
                p,
                "><title>{}</title></{element}>",
                esc(&mark_text(kind, &m, axis, profile))
            );
        } else {
            p.push_str("/>\n");
        }
    }
}

/// A bus's or a stream's frame rate, as an area chart (timed only).
pub(super) fn rate(p: &mut String, axis: &Axis, series: &Series<RateBucket>, h: f64) {
    if !axis.timed {
        return;
    }
    let items = series.items();
    if items.len() < 2 {
        return;
    }
    // Frames per second of each bucket: its frames over its width.
    let width = series.width().max(1);
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
    let mut d = format!("M{},{bottom}", Fixed::<2>(points[0].0));
    for &(x0, x1, fps) in &points {
        let y = Fixed::<1>(bottom - (fps / peak.max(1.0)) * (bottom - top));
        let _ = write!(d, "L{},{y}L{},{y}", Fixed::<2>(x0), Fixed::<2>(x1));
    }
    let _ = write!(d, "L{},{bottom}Z", Fixed::<2>(points[points.len() - 1].1));
    let _ = writeln!(
        p,
        "<path d=\"{d}\" data-kind=\"frame_rate\" data-peak=\"{peak:.0}\"><title>frames per second, at most {peak:.0}</title></path>"
    );
}

/// A device's row; returns its height.
#[allow(clippy::too_many_arguments)]
pub(super) fn node_row(
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
    let second: &[(&Series<BandItem>, &BandStyle)] = match row {
        Some(row) if drive => &[(&row.cia402, &CIA402_BANDS)],
        _ => &[],
    };
    let _ = write!(
        p,
        "<g class=\"row node\" data-row=\"node\" data-iface=\"{}\" data-node=\"{}\"{file} transform=\"translate(0,{y})\">\n<text class=\"label\" x=\"8\" y=\"14\">{}</text><text class=\"sub\" x=\"8\" y=\"28\">NMT{}</text>\n<g class=\"plot\" clip-path=\"url(#clip)\">\n",
        iface_attr(&n.bus),
        n.node.get(),
        esc(&device(&n.bus, n.node)),
        if drive { " · CiA 402" } else { "" }
    );
    if let Some(row) = row {
        device_lanes(
            p,
            axis,
            budget,
            row,
            end,
            (&row.nmt, &NMT_BANDS),
            second,
            &MarkKind::NODE,
            n.profile,
        );
    }
    p.push_str("</g>\n</g>\n");
    h
}

/// A device's lanes, shared by a CAN device's row and an EtherCAT slave's:
/// its first band (`first`: NMT or AL states) from y 2, the bands of
/// `more` below it (a drive's CiA 402 states, a servo's enable phases),
/// and its marks of `kinds` under the bands; a CiA 402 fault is drawn
/// over the CiA 402 band.
#[allow(clippy::too_many_arguments)]
fn device_lanes(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    row: &RowData,
    end: At,
    first: (&Series<BandItem>, &BandStyle),
    more: &[(&Series<BandItem>, &BandStyle)],
    kinds: &[MarkKind],
    profile: Profile,
) {
    bands(p, axis, budget, first.0, end, 2.0, first.1);
    let mut lane = 16.0;
    let mut cia402 = lane;
    for (series, style) in more {
        if style.kind == CIA402_BANDS.kind {
            cia402 = lane;
        }
        bands(p, axis, budget, series, end, lane, style);
        lane += BAND_LANE;
    }
    for &kind in kinds {
        let at = if kind == MarkKind::Cia402Fault {
            cia402
        } else {
            lane
        };
        marks(p, axis, budget, row, kind, Some(at), profile);
    }
}

/// The height a band lane takes in a row.
const BAND_LANE: f64 = 14.0;

/// An EtherCAT slave's row (docs/report.md#ethercat): its AL states as a
/// band, a drive's CiA 402 states below, and its marks; `place` is its
/// place among its interface's slave records. Returns its height.
#[allow(clippy::too_many_arguments)]
pub(super) fn slave_row(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    s: &SlaveSummary,
    row: Option<&RowData>,
    file: &str,
    y: f64,
    end: At,
) -> f64 {
    let drive = row.is_some_and(|row| row.cia402.len() > 0);
    let servo = row.is_some_and(|row| row.servo.len() > 0);
    let mut more: Vec<(&Series<BandItem>, &BandStyle)> = Vec::new();
    if let Some(row) = row {
        if drive {
            more.push((&row.cia402, &CIA402_BANDS));
        }
        if servo {
            more.push((&row.servo, &SERVO_BANDS));
        }
    }
    let h = 44.0 + BAND_LANE * more.len() as f64;
    let position = s
        .position
        .map_or_else(String::new, |at| format!(" data-position=\"{at}\""));
    let what = s
        .vendor
        .zip(s.product)
        .and_then(|(v, p)| crate::summary::device_name(v, p))
        .unwrap_or("slave");
    let _ = write!(
        p,
        "<g class=\"row slave\" data-row=\"slave\" data-iface=\"{}\" data-slave=\"{}\"{position}{file} transform=\"translate(0,{y})\">\n<text class=\"label\" x=\"8\" y=\"14\"><title>{}</title>{}</text><text class=\"sub\" x=\"8\" y=\"28\">{} · AL{}{}</text>\n<g class=\"plot\" clip-path=\"url(#clip)\">\n",
        iface_attr(&s.iface),
        s.station.map_or_else(String::new, |st| st.to_string()),
        esc(&slave_name(s)),
        esc(&slave_name(s).replacen(&format!("{} ", s.iface), "", 1)),
        esc(what),
        if drive { " · CiA 402" } else { "" },
        if servo { " · servo" } else { "" }
    );
    if let Some(row) = row {
        let profile = s
            .emergencies
            .first()
            .map_or(Profile::Generic, |e| e.profile);
        device_lanes(
            p,
            axis,
            budget,
            row,
            end,
            (&row.al, &AL_BANDS),
            &more,
            &MarkKind::SLAVE,
            profile,
        );
    }
    p.push_str("</g>\n</g>\n");
    h
}

/// A cyclic datagram stream's row (docs/report.md#ethercat): its returned
/// frames per second, its lost frames and working-counter mismatches.
/// Returns its height.
pub(super) fn stream_row(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    s: &StreamSummary,
    row: Option<&RowData>,
    file: &str,
    y: f64,
) -> f64 {
    let h = 36.0;
    let key = s.key();
    let address = if matches!(
        s.command,
        crate::ethercat::Command::Lrd
            | crate::ethercat::Command::Lrw
            | crate::ethercat::Command::Lwr
    ) {
        format!(" data-logical=\"{}\"", s.address)
    } else {
        format!(
            " data-adp=\"{}\" data-ado=\"{}\"",
            s.address & 0xFFFF,
            s.address >> 16
        )
    };
    let _ = write!(
        p,
        "<g class=\"row stream\" data-row=\"stream\" data-iface=\"{}\" data-stream=\"{}\" data-cmd=\"{}\"{address}{file} transform=\"translate(0,{y})\">\n<text class=\"label\" x=\"8\" y=\"14\"><title>{} {}</title>stream {}</text><text class=\"sub\" x=\"8\" y=\"28\">{} frames</text>\n<g class=\"plot\" clip-path=\"url(#clip)\">\n",
        iface_attr(&s.iface),
        esc(&key),
        s.command.name(),
        esc(&s.iface.to_string()),
        esc(&key),
        esc(&key),
        s.sent
    );
    if let Some(row) = row {
        rate(p, axis, &row.rate, h);
        for kind in MarkKind::STREAM {
            marks(p, axis, budget, row, kind, None, Profile::Generic);
        }
    }
    p.push_str("</g>\n</g>\n");
    h
}

/// How a kind of state band is written: its `data-kind`, the name of a
/// band's state, and the attributes it adds (a space before each).
#[derive(Debug)]
pub(super) struct BandStyle {
    pub(super) kind: &'static str,
    pub(super) name: fn(u8) -> &'static str,
    pub(super) flags: fn(u8) -> &'static str,
}

/// A CAN device's NMT state.
pub(super) const NMT_BANDS: BandStyle = BandStyle {
    kind: "nmt_state",
    name: nmt_name,
    flags: no_flags,
};

/// A drive's CiA 402 state, on a CAN device's row and an EtherCAT slave's.
pub(super) const CIA402_BANDS: BandStyle = BandStyle {
    kind: "cia402_state",
    name: cia402_name,
    flags: no_flags,
};

/// An EtherCAT slave's AL state, with `data-error="true"` where the
/// slave's AL status had its error indicator set.
pub(super) const AL_BANDS: BandStyle = BandStyle {
    kind: "al_state",
    name: al_name,
    flags: al_error,
};

/// A servo's enable handshake phase (docs/ethercat.md#servo).
pub(super) const SERVO_BANDS: BandStyle = BandStyle {
    kind: "servo_enable",
    name: servo_enable_name,
    flags: no_flags,
};

/// A row's state bands, from `y`, 12 pixels high.
#[allow(clippy::too_many_arguments)]
pub(super) fn bands(
    p: &mut String,
    axis: &Axis,
    budget: &Budget,
    series: &Series<BandItem>,
    end: At,
    y: f64,
    style: &BandStyle,
) {
    let (kind, name) = (style.kind, style.name);
    for band in drawn_bands(axis, series, end, budget.band_px) {
        let b = band.item;
        let state = name(b.state);
        let w = (band.x1 - band.x0).max(0.5);
        let _ = write!(
            p,
            "<rect x=\"{}\" y=\"{y}\" width=\"{}\" height=\"12\" data-kind=\"{kind}\" data-state=\"{state}\"{} data-line=\"{}\" data-count=\"{}\"",
            Fixed::<3>(band.x0),
            Fixed::<3>(w),
            (style.flags)(b.state),
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
            } else if kind == "nmt_state" && b.state == SILENT {
                format!(
                    "state unknown: no heartbeat within the consumer time after line {} ({})",
                    b.at.line,
                    axis.when(b.at)
                )
            } else {
                let error = if style.kind == AL_BANDS.kind && b.state & AL_ERROR != 0 {
                    " with error"
                } else {
                    ""
                };
                format!(
                    "{state}{error} from line {} ({})",
                    b.at.line,
                    axis.when(b.at)
                )
            };
            let _ = write!(p, "><title>{}</title></rect>", esc(&title));
        } else {
            p.push_str("/>");
        }
        if w >= 70.0 && b.count == 1 {
            let _ = write!(
                p,
                "<text class=\"bl\" x=\"{}\" y=\"{}\">{state}</text>",
                Fixed::<3>(band.x0 + 3.0),
                y + 9.5
            );
        }
        p.push('\n');
    }
}

/// The shapes of the marks, the clip of the plot, the hatch of merged bands.
pub(super) fn defs(p: &mut String) {
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
<path id=\"s-coe_emcy\" d=\"M0,5L-5,-5H5Z\"/>\n\
<path id=\"s-al_error\" d=\"M-1.5,-6H1.5V2H-1.5ZM-1.5,3.5H1.5V6.5H-1.5Z\"/>\n\
<path id=\"s-dl_change\" d=\"M-6,2L-2,-4L2,4L6,-2\"/>\n\
<path id=\"s-error_counter\" d=\"M0,6V-6M-4,-2L0,-6L4,-2\"/>\n\
<path id=\"s-lost_frame\" d=\"M-4,-4L4,4M4,-4L-4,4M0,-6V6\"/>\n\
<path id=\"s-wkc_mismatch\" d=\"M0,-6V6M-4,2L0,6L4,2\"/>\n\
<path id=\"s-servo_fault\" d=\"M0,-6L5,0L0,6L-5,0Z\"/>\n\
<path id=\"s-servo_error_clear\" d=\"M-5,0L-1,4L5,-5\"/>\n\
<path id=\"s-servo_zero_pulse\" d=\"M-5,0H5M0,-5V5M-3,-3H3V3H-3Z\"/>\n\
<path id=\"s-servo_not_ready\" d=\"M-5,-3L0,3L5,-3\"/>\n\
<path id=\"s-servo_enable_unanswered\" d=\"M0,-6L6,5H-6Z\"/>\n\
</defs>\n"
    );
}

/// Round ticks for a span of `span` units: the step and its unit's label.
pub(super) fn tick_step(span: f64) -> f64 {
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
pub(super) fn axis_ticks(p: &mut String, axis: &Axis, height: f64) {
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

pub(super) fn format_tick(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 {
        0
    } else {
        (-step.log10().floor()) as usize
    };
    format!("{v:.decimals$}")
}

/// The legend: every kind of mark and band, in words.
pub(super) fn legend(p: &mut String) {
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
    p.push_str("<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-unknown\" width=\"16\" height=\"12\"/></svg> NMT unknown: silent past the heartbeat consumer time</li>\n");
    for state in [
        AlState::Init,
        AlState::PreOp,
        AlState::Boot,
        AlState::SafeOp,
        AlState::Op,
    ] {
        let _ = writeln!(
            p,
            "<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-al-{0}\" width=\"16\" height=\"12\"/></svg> AL {0}</li>",
            state.name()
        );
    }
    p.push_str("<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-al-error\" width=\"16\" height=\"12\"/></svg> AL state with the error indicator</li>\n");
    for state in crate::canopen::Cia402State::ALL {
        let _ = writeln!(
            p,
            "<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-{0}\" width=\"16\" height=\"12\"/></svg> CiA 402 {0}</li>",
            state.name()
        );
    }
    for phase in 0..=u8::MAX {
        let Some(phase) = enable_phase(phase) else {
            break;
        };
        let _ = writeln!(
            p,
            "<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-servo-{0}\" width=\"16\" height=\"12\"/></svg> servo enable {0}</li>",
            phase.name()
        );
    }
    p.push_str("<li><svg width=\"16\" height=\"12\" aria-hidden=\"true\"><rect class=\"lb-mixed\" width=\"16\" height=\"12\"/></svg> several states within a pixel</li>\n</ul></div>\n");
}

/// Whose charts: a CAN device's or an EtherCAT slave's.
pub(super) struct Charted<'a> {
    /// Its name, as the page says it.
    pub(super) name: String,
    /// Its attributes on the chart's `svg`, a space before each.
    pub(super) attrs: String,
    /// Whether it is a drive, whose CiA 402 state is charted.
    pub(super) drive: bool,
    pub(super) row: &'a RowData,
}

impl<'a> Charted<'a> {
    /// A CAN device's.
    pub(super) fn node(n: &NodeSummary, row: &'a RowData) -> Self {
        Charted {
            name: device(&n.bus, n.node),
            attrs: format!(
                " data-node=\"{}\" data-iface=\"{}\"",
                n.node.get(),
                iface_attr(&n.bus)
            ),
            drive: n.cia402.is_some(),
            row,
        }
    }

    /// An EtherCAT slave's.
    pub(super) fn slave(s: &SlaveSummary, row: &'a RowData) -> Self {
        Charted {
            name: slave_name(s),
            attrs: format!(
                " data-slave=\"{}\" data-iface=\"{}\"",
                s.station.map_or_else(String::new, |st| st.to_string()),
                iface_attr(&s.iface)
            ),
            drive: s.cia402.is_some(),
            row,
        }
    }

    /// Whether it has anything to chart.
    pub(super) fn any(&self) -> bool {
        self.drive || self.row.signals.iter().any(Option::is_some)
    }
}

/// A drive's charts: its CiA 402 state, position and velocity, a servo's
/// ActPos and speed set point, on the shared axis (docs/report.md#signals).
pub(super) fn chart(p: &mut String, axis: &Axis, budget: &Budget, who: &Charted<'_>, end: At) {
    const H: f64 = 70.0;
    let row = who.row;
    let name = esc(&who.name);
    let mut body = String::new();
    let mut y = AXIS + 4.0;
    // The CiA 402 state, as a step line over the 8 states.
    if who.drive {
        let levels = crate::canopen::Cia402State::ALL.len() as f64;
        let bands = drawn_bands(axis, &row.cia402, end, budget.band_px);
        let mut d = String::new();
        for (i, band) in bands.iter().enumerate() {
            let level = f64::from(band.item.state);
            let yy = y + 4.0 + (level / (levels - 1.0)) * (H - 8.0);
            let _ = write!(
                d,
                "{}{},{}H{}",
                if i == 0 { "M" } else { "L" },
                Fixed::<2>(band.x0),
                Fixed::<1>(yy),
                Fixed::<2>(band.x1)
            );
        }
        let _ = write!(
            body,
            "<g class=\"chart\" transform=\"translate(0,0)\"><text class=\"label\" x=\"8\" y=\"{}\">CiA 402 state</text><text class=\"sub\" x=\"8\" y=\"{}\">top: not ready</text><text class=\"sub\" x=\"8\" y=\"{}\">bottom: fault</text>\n<g class=\"plot\" clip-path=\"url(#clip-c)\"><path class=\"sig state\" d=\"{d}\" data-kind=\"signal\" data-signal=\"cia402_state\" data-points=\"{}\"><title>CiA 402 state of {name}</title></path></g></g>\n",
            y + 14.0,
            y + 28.0,
            y + 42.0,
            bands.len(),
        );
        y += H + 8.0;
    }
    for (i, (key, title)) in CHARTED.iter().enumerate() {
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
                    "{}{},{}",
                    if points == 0 { "M" } else { "L" },
                    Fixed::<2>(axis.x(*at)),
                    Fixed::<1>(yv(*v))
                );
                points += 1;
            }
        }
        let _ = write!(
            body,
            "<g class=\"chart\"><text class=\"label\" x=\"8\" y=\"{}\">{}</text><text class=\"sub\" x=\"8\" y=\"{}\">max {hi}</text><text class=\"sub\" x=\"8\" y=\"{}\">min {lo}</text>\n<g class=\"plot\" clip-path=\"url(#clip-c)\"><path class=\"sig\" d=\"{d}\" data-kind=\"signal\" data-signal=\"{key}\" data-points=\"{points}\" data-min=\"{lo}\" data-max=\"{hi}\"><title>{} of {name}: from {lo} to {hi}, {points} points (minimum and maximum per bucket)</title></path></g></g>\n",
            y + 14.0,
            esc(title.split(" (").next().unwrap_or(title)),
            y + 28.0,
            y + H - 4.0,
            esc(title),
        );
        y += H + 8.0;
    }
    let height = y;
    let _ = write!(
        p,
        "<h3>{name}</h3>\n<svg class=\"tl chart\" viewBox=\"0 0 {WIDTH} {height}\" width=\"{WIDTH}\" height=\"{height}\" role=\"img\" aria-label=\"signals of {name}\"{} data-left=\"{LEFT}\" data-plot=\"{PLOT}\"{}>\n<defs><clipPath id=\"clip-c\"><rect x=\"{LEFT}\" y=\"0\" width=\"{PLOT}\" height=\"100000\"/></clipPath></defs>\n",
        who.attrs,
        axis.attrs()
    );
    axis_ticks(p, axis, height);
    p.push_str(&body);
    p.push_str("</svg>\n");
}
