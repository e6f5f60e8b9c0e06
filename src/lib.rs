//! # motionwire
//!
//! Codecs and pure state machines for the diagnostic and cyclic-control
//! language of industrial motion devices: the EtherCAT servo ↔ NC cyclic
//! frames, CANopen emergency messages and error control, the CiA 405
//! `RECV_EMCY` consumer, and device profiles (Kollmorgen AKD, Baumer EAM580).
//!
//! The crate is `no_std`, allocates nothing and contains no `unsafe` code.
//! Every decoder takes outside bytes and returns a typed [`Error`] instead of
//! panicking. The formats and behaviours are those of the project's
//! specification (`SPEC.md`); each item's documentation names its section.
//!
//! ## Layout
//!
//! - [`canopen`]: node-IDs and COB-IDs, the EMCY frame, error register and
//!   error codes (CiA 301 §7.2.7, SPEC §2).
//! - [`candump`]: candump text logs (can-utils), one CAN frame per line,
//!   parsed without allocation and written back (SPEC §5).
#![cfg_attr(not(any(test, feature = "std")), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![deny(trivial_numeric_casts)]
#![deny(unused_qualifications)]
#![deny(rustdoc::broken_intra_doc_links)]

pub mod candump;
pub mod canopen;
mod error;

pub use error::{Error, Result};

#[cfg(test)]
mod test_gens;
