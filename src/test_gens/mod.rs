//! Shared proptest strategies, one file per area, used by every module's
//! tests (after etherparse's `test_gens`).

pub(crate) mod candump;
pub(crate) mod canopen;
