//! Shared proptest strategies, one file per area, used by every module's
//! tests (after etherparse's `test_gens`).

pub(crate) mod akd;
pub(crate) mod baumer;
pub(crate) mod can;
pub(crate) mod candump;
pub(crate) mod canopen;
pub(crate) mod cia402;
#[cfg(feature = "embedded-can")]
pub(crate) mod embedded_can;
pub(crate) mod emcy_producer;
pub(crate) mod error_control;
#[cfg(feature = "serde")]
pub(crate) mod owned;
pub(crate) mod pdo;
pub(crate) mod recv_emcy;
pub(crate) mod sdo;
pub(crate) mod servo;
