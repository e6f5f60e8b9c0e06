//! `defmt::Format` for the types that cannot derive it (feature `defmt`):
//! the flag words (bitflags types, written as their hex value), the frame
//! types (identifier and data in hex) and the crate's error (its message).

use defmt::{write, Format, Formatter};

use crate::can::{CanFrame, ControllerStatus, ErrorClasses, ErrorFrame, FrameData};
use crate::canopen::{Controlword, ErrorRegister, PdoMapping, Statusword};
use crate::profiles::baumer::{Alarms, Warnings};
use crate::servo::{ServoControlWord, ServoErrorWord, ServoStatusWord};
use crate::Error;

macro_rules! flag_word {
    ($($ty:ty => $fmt:literal),* $(,)?) => {
        $(
            impl Format for $ty {
                fn format(&self, f: Formatter<'_>) {
                    write!(f, $fmt, self.bits());
                }
            }
        )*
    };
}

flag_word! {
    ErrorRegister => "ErrorRegister({=u8:#04x})",
    Statusword => "Statusword({=u16:#06x})",
    Controlword => "Controlword({=u16:#06x})",
    ErrorClasses => "ErrorClasses({=u32:#x})",
    ControllerStatus => "ControllerStatus({=u8:#04x})",
    Alarms => "Alarms({=u16:#06x})",
    Warnings => "Warnings({=u16:#06x})",
    ServoControlWord => "ServoControlWord({=u32:#010x})",
    ServoStatusWord => "ServoStatusWord({=u32:#010x})",
    ServoErrorWord => "ServoErrorWord({=u32:#010x})",
}

impl Format for FrameData {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "{=[u8]:02x}", self.as_slice());
    }
}

impl<D: AsRef<[u8]>> Format for CanFrame<D> {
    /// The identifier, the frame type and the data.
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "CanFrame {{ id: {}, type: {}, data: {=[u8]:02x} }}",
            self.id(),
            self.frame_type(),
            self.data()
        );
    }
}

impl Format for ErrorFrame {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "ErrorFrame {{ classes: {}, data: {=[u8]:02x} }}",
            self.classes,
            self.data()
        );
    }
}

impl Format for Error {
    /// The same message as `Display`.
    fn format(&self, f: Formatter<'_>) {
        write!(f, "{}", defmt::Display2Format(self));
    }
}

impl Format for PdoMapping {
    /// The entries in mapping order.
    fn format(&self, f: Formatter<'_>) {
        write!(f, "PdoMapping {{ entries: {} }}", self.entries());
    }
}
