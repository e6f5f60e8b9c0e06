//! Proptest strategies for the codec's types, one file per area: every
//! property test of this crate draws its values from here, and so can the
//! tests of a crate built on it (feature `proptest`), as motionwire's log
//! readers and decoder do.

pub mod akd;
pub mod baumer;
pub mod can;
pub mod canopen;
pub mod cia402;
#[cfg(feature = "embedded-can")]
pub mod embedded_can;
pub mod emcy_producer;
pub mod error_control;
#[cfg(feature = "serde")]
pub mod owned;
pub mod pdo;
pub mod recv_emcy;
pub mod sdo;
pub mod servo;
