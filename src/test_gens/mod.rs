//! Proptest strategies for the log readers' types; those of the frames and
//! protocols are `motionwire_codec::strategies`, re-exported here so that a
//! test names one module.

pub(crate) use motionwire_codec::strategies::*;

pub(crate) mod candump;
