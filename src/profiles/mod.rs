//! Device-specific layouts: how particular devices fill the
//! manufacturer-specific field of the EMCY and which diagnostic sources they
//! report (SPEC §2.4, §4).

pub mod baumer;
