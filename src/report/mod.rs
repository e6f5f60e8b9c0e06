//! The post-mortem as a page a person looks at: `motionwire report`
//! (docs/report.md). One self-contained HTML file — inline CSS, SVG written
//! here, a small script for zoom, pan and details only, nothing fetched —
//! drawn from the library's own [decoder](crate::decoder) and
//! [summary](crate::summary): the faults first, a timeline with one row per
//! bus and per device (NMT and CiA 402 state bands, a mark for every fact
//! the summary records) and, for an EtherCAT capture, per slave (AL state
//! bands and marks) and per cyclic stream (lost frames, working-counter
//! mismatches; docs/report.md#ethercat), drive signals, and the summary as tables and as the
//! embedded `decode --summary --json` records (docs/report.md#contract).
//!
//! A [`Recorder`] is fed every frame and bus event of a recording, as a
//! [`Summarizer`] is (it holds one, which holds the decoder); [`Recorder::finish`] returns the
//! [`Recording`]: the [`Summary`] and its [`Timeline`], kept in bounded
//! memory whatever the log's size (an EMCY storm becomes clusters, signals
//! are reduced to minima and maxima per bucket; docs/report.md#bounded). A
//! [`Report`] gathers the recordings of the logs and writes the page.
//!
//! [`Summarizer`]: crate::summary::Summarizer
//! [`Summary`]: crate::summary::Summary
//!
//! ```
//! use motionwire::can::LogEvent;
//! use motionwire::decoder::DecoderConfig;
//! use motionwire::logs::Position;
//! use motionwire::report::{MarkKind, Recorder, Report};
//!
//! let log = b"(1700000000.000000) can0 703#00\n\
//!             (1700000000.100000) can0 083#1081110000000000\n\
//!             (1700000000.200000) can0 703#05\n";
//! let mut recorder = Recorder::new(DecoderConfig::new());
//! for (line, text) in log.split(|&b| b == b'\n').enumerate() {
//!     if let Ok(Some(frame)) = motionwire::logs::candump::parse_line(text) {
//!         recorder.add(Position::Line(line as u64 + 1), &LogEvent::Frame(frame));
//!     }
//! }
//! let recording = recorder.finish();
//! let node = recording.summary.nodes[0].node;
//! let bus = &recording.summary.nodes[0].bus;
//! assert_eq!(recording.timeline.mark_count(bus, Some(node), MarkKind::Emcy), 1);
//! assert_eq!(recording.timeline.mark_count(bus, Some(node), MarkKind::BootUp), 1);
//!
//! let mut report = Report::new();
//! report.add_recording(recording);
//! let mut page = Vec::new();
//! report.write_html(&mut page)?;
//! let page = String::from_utf8(page).unwrap();
//! assert!(page.contains(r#"data-kind="emcy""#));
//! assert!(page.contains(r#"<script type="application/json" id="motionwire-summary">"#));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod fixed;
mod html;
mod layout;
mod markup;
mod recorder;
mod series;
mod svg;

pub use html::{Report, ReportInput};
pub use recorder::{MarkKind, Recorder, Recording, Timeline};
