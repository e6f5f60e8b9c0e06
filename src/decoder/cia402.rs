//! The CiA 402 reading of one frame, and what the decoder remembers of a
//! drive to make it: its last state and controlword (docs/canopen.md#cia402).

use core::fmt;

use crate::canopen::{Cia402Command, Cia402State, ModeOfOperation, Signal, Value};

/// What one frame tells of a drive's CiA 402 state machine (`cia402`
/// in docs/output.md#cia402): each part where the frame carries it. The
/// drive is the record's: the node that owns the PDO or whose SDO server
/// the transfer reached on CAN, the slave on EtherCAT.
///
/// `Display` writes the parts that are there, joined by commas:
/// `operation_enabled, enable_operation, profile position`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Cia402Reading {
    /// The state, from a statusword (6041h).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub state: Option<Cia402State>,
    /// The command, from a controlword (6040h), the drive's previous
    /// controlword and its state (the decision in docs/canopen.md#cia402).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub command: Option<Cia402Command>,
    /// The mode of operation (6060h) or its display (6061h).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub mode: Option<ModeOfOperation>,
}

impl Cia402Reading {
    pub(crate) const fn empty() -> Self {
        Cia402Reading {
            state: None,
            command: None,
            mode: None,
        }
    }

    /// Return whether the frame told nothing of the state machine.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.state.is_none() && self.command.is_none() && self.mode.is_none()
    }
}

impl fmt::Display for Cia402Reading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut sep = "";
        if let Some(state) = self.state {
            write!(f, "{state}")?;
            sep = ", ";
        }
        if let Some(command) = self.command {
            write!(f, "{sep}{command}")?;
            sep = ", ";
        }
        if let Some(mode) = self.mode {
            write!(f, "{sep}{mode}")?;
        }
        Ok(())
    }
}

/// What the decoder remembers of a drive between frames.
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct DriveState {
    state: Option<Cia402State>,
    controlword: Option<u16>,
}

impl DriveState {
    /// A statusword seen: the state it codes (CiA 402; docs/canopen.md#cia402).
    pub(crate) fn observe_statusword(&mut self, sw: u16) -> Option<Cia402State> {
        let state = Cia402State::from_statusword(sw);
        if state.is_some() {
            self.state = state;
        }
        state
    }

    /// A controlword seen: the command it gives in the current state, with
    /// the previous controlword for the fault-reset edge
    /// (docs/canopen.md#cia402).
    pub(crate) fn observe_controlword(&mut self, cw: u16) -> Option<Cia402Command> {
        let command = Cia402Command::from_controlword(cw, self.controlword, self.state);
        self.controlword = Some(cw);
        command
    }

    /// The reading of a PDO's signals (CAN) or a slave's process data
    /// (EtherCAT): statusword 6041h, controlword 6040h and mode
    /// 6060h/6061h where they are mapped with their own lengths; `None`
    /// when none is.
    pub(crate) fn read<'s>(
        &mut self,
        signals: impl IntoIterator<Item = &'s Signal>,
    ) -> Option<Cia402Reading> {
        let mut reading = Cia402Reading::empty();
        let (mut sw, mut cw) = (None, None);
        for signal in signals {
            let raw = match signal.value {
                Value::Unsigned(v) => v as i64,
                Value::Signed(v) => v,
                _ => continue,
            };
            match (
                signal.entry.index(),
                signal.entry.sub_index(),
                signal.entry.bits(),
            ) {
                (0x6041, 0, 16) => sw = Some(raw as u16),
                (0x6040, 0, 16) => cw = Some(raw as u16),
                (0x6060 | 0x6061, 0, 8) => {
                    reading.mode = Some(ModeOfOperation::from_i8(raw as i8));
                }
                _ => {}
            }
        }
        if let Some(sw) = sw {
            reading.state = self.observe_statusword(sw);
        }
        if let Some(cw) = cw {
            reading.command = self.observe_controlword(cw);
        }
        (!reading.is_empty()).then_some(reading)
    }
}
