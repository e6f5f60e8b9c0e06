//! The EtherCAT side of the decoder session (docs/ethercat.md): which copy
//! of a frame each packet of a capture is ([`Session`]), what each datagram
//! tells of the slaves ([`Meaning`]), and the records `decode` writes of
//! them ([`DatagramRecord`], [`MeaningRecord`]). Built on the wire views of
//! [`crate::ethercat`].

mod coe;
mod columns;
mod config;
mod dc;
#[cfg(feature = "eni")]
mod eni;
mod image;
mod missing;
mod network;
mod problem;
mod process;
mod record;
mod record_regs;
mod session;
mod sii;
mod slave;

pub use coe::{CoeSdoStep, CoeTransfer, COE_DATA_KEPT};
pub use columns::MeaningColumns;
pub use config::{PdoConfig, PdoEntryConfig, SlaveConfig};
pub use dc::{time_difference, DcRegisters};
#[cfg(feature = "eni")]
pub use eni::{parse_eni, EniError, EniErrorKind};
pub use missing::{Evidence, Missed};
pub use network::{AlRegister, Meaning, SiiField, ERROR_COUNTERS_LEN};
pub use problem::{ImageError, ImageProblem};
pub use process::{ProcessData, ServoItem, ServoItemError, ServoReading, ServoSlaves};
pub use record::{
    DatagramRecord, Fields, MeaningRecord, ProcessRecord, DATAGRAM_KIND, PROCESS_DATA_KIND,
    RECORD_KINDS, SERVO_KIND,
};
pub use record_regs::QUIET_KINDS;
pub use session::{Counts, DamagedPacket, FrameCopy, Packet, Session, PAIRING_WINDOW};
pub use slave::SlaveRef;
