//! The page's geometry, shared by the HTML (`html.rs`) and the SVG
//! (`svg.rs`): the plot's size, the axis that places a time or a line on
//! it, and the budget that keeps a page's marks and bands few enough
//! (docs/report.md#size).

use super::series::At;

/// The SVG's width: labels, then the plot.
pub(super) const WIDTH: f64 = 1200.0;
/// Where the plot begins.
pub(super) const LEFT: f64 = 170.0;
/// The plot's default width in pixels: "within a pixel" for clusters
/// (docs/report.md#clusters) is a pixel of it.
pub(super) const PLOT: f64 = 1000.0;
/// The axis's height.
pub(super) const AXIS: f64 = 26.0;
/// More bands than this on a row: neighbours narrower than a pixel merge.
pub(super) const EXACT_BANDS: usize = 500;

/// How a page draws its marks and bands, to stay small whatever the log
/// (docs/report.md#size).
#[derive(Debug, Clone, Copy)]
pub(super) struct Budget {
    /// `None`: each series as docs/report.md#clusters says; else every
    /// series clustered within this many pixels.
    pub(super) radius: Option<f64>,
    /// Bands narrower than this many pixels merge with their neighbours
    /// (`None`: only on rows of more than 500).
    pub(super) band_px: Option<f64>,
    pub(super) titles: bool,
}

/// The shared axis: time in microseconds, or lines.
#[derive(Debug, Clone, Copy)]
pub(super) struct Axis {
    pub(super) timed: bool,
    pub(super) start: u64,
    pub(super) end: u64,
}

impl Axis {
    pub(super) fn key(&self, at: At) -> u64 {
        at.key(self.timed)
    }

    /// The x of a place, in the default view.
    pub(super) fn x(&self, at: At) -> f64 {
        self.x_of(self.key(at))
    }

    pub(super) fn x_of(&self, key: u64) -> f64 {
        let span = (self.end - self.start).max(1) as f64;
        LEFT + (key.saturating_sub(self.start) as f64 / span) * PLOT
    }

    /// A pixel of the default view, in the axis's unit.
    pub(super) fn pixel(&self) -> f64 {
        (self.end - self.start).max(1) as f64 / PLOT
    }

    /// Whether the axis counts Unix time (microseconds since 1970, from
    /// 2001 on): then a place has a wall-clock time.
    pub(super) fn is_unix(&self) -> bool {
        self.timed && self.start >= UNIX_FROM
    }

    /// A place with its wall-clock time where the log gives one:
    /// `+2.003641 s, 2023-11-14 22:13:22.003641 UTC` (docs/report.md#page).
    pub(super) fn when_utc(&self, at: At) -> String {
        if self.is_unix() {
            format!("{}, {}", self.when(at), super::html::utc(at.t))
        } else {
            self.when(at)
        }
    }

    /// Its `data-axis`, `data-start` and `data-span` attributes, with a
    /// space before (docs/report.md#contract).
    pub(super) fn attrs(&self) -> String {
        format!(
            " data-axis=\"{}\" data-start=\"{}\" data-span=\"{}\"",
            if self.timed { "time" } else { "line" },
            self.start,
            self.end - self.start
        )
    }

    /// A place as the page writes it: `+2.003641 s` or `line 613`.
    pub(super) fn when(&self, at: At) -> String {
        if self.timed {
            format!("+{} s", seconds(at.t.saturating_sub(self.start)))
        } else {
            format!("line {}", at.line)
        }
    }
}

/// The first microsecond the page reads as a Unix time: the library's
/// [`Timestamp::UNIX_FROM`](crate::can::Timestamp::UNIX_FROM).
pub(super) const UNIX_FROM: u64 = crate::can::Timestamp::UNIX_FROM.as_micros() as u64;

/// Microseconds as seconds with six decimals.
pub(super) fn seconds(us: u64) -> String {
    format!("{}.{:06}", us / 1_000_000, us % 1_000_000)
}
