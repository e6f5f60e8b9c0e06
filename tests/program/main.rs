//! The integration tests of the `motionwire` program (feature `cli`): its
//! options and outputs, its output on every fixture against the snapshots
//! of `tests/golden`, and the report page, read as a script reads it and
//! loaded in a real browser. One test binary, so that the crate is linked
//! once; each former test file is a module.

#[path = "../common/mod.rs"]
mod common;
#[path = "../report_common/mod.rs"]
mod report_common;

mod cli;
mod findings;
mod golden;
mod report;
mod report_browser;
