//! The integration tests that need no feature: the servo interface and the
//! drive model through frame bytes, CiA 402 against python-canopen, and the
//! text-log readers (candump, ASC, TRC) against the tools that wrote their
//! fixtures. One test binary for all of them, so that the crate is linked
//! once; each former test file is a module.

mod asc;
mod candump_screen;
mod cia402;
mod python_can;
mod servo;
mod servo_drive;
mod trc;
