//! Device-specific layouts: how one vendor's device fills the fields that
//! CANopen leaves to the manufacturer (STYLE.md, "device-specific profiles
//! apart"; SPEC §2.4, §4).
//!
//! The generic codecs in [`crate::canopen`] decode every device's frames;
//! a profile gives the manufacturer-specific bytes their meaning for one
//! device family.

pub mod akd;
pub mod baumer;
