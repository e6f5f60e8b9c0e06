//! `motionwire::logs`: one way to read any log (SPEC §5.7, §6.4).
