//! The integration tests of the library's `std` features: every log reader
//! (`logs`, `pcap`, `blf`, `mf4`), the EDS reader (`eds`), the ENI reader
//! (`eni`), and the decoder and the summary (`decoder`) read and written as
//! the program would. One test binary (it needs `std`), so that the crate
//! is linked once; each former test file is a module, built when the
//! features it tests are on, so `cargo test --no-default-features
//! --features pcap` still runs the pcap tests alone.

#[cfg(all(feature = "decoder", feature = "logs"))]
#[path = "../common/mod.rs"]
mod common;
/// The generated capture of tests/data/ethercat/drives.pcapng, shared by
/// `drives_capture` and `drives_model`.
#[cfg(feature = "logs")]
#[path = "../common/ecat_drives.rs"]
mod ecat_drives;

#[cfg(feature = "blf")]
mod blf;
#[cfg(feature = "logs")]
mod drives_capture;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod drives_model;
#[cfg(feature = "eds")]
mod eds;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod eds_names;
#[cfg(feature = "eni")]
mod eni;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod ethercat;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod ethercat_json;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod ethercat_process;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod ethercat_registers;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod ethercat_startup;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod library;
#[cfg(feature = "logs")]
mod logs;
#[cfg(feature = "logs")]
mod mf4;
#[cfg(feature = "pcap")]
mod pcap;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod pdo;
#[cfg(all(feature = "decoder", feature = "logs"))]
mod sdo;
