//! EtherCAT captures (docs/ethercat.md): the wire views of
//! `motionwire-codec` (frames, datagrams, registers, mailbox, CoE), and the
//! session that reads a capture's packets as the master and its slaves
//! exchanged them.

pub use motionwire_codec::ethercat::*;

#[cfg(feature = "std")]
mod network;
#[cfg(feature = "std")]
mod session;
#[cfg(feature = "std")]
pub use network::{AlRegister, Meaning, SiiField, SlaveRef, ERROR_COUNTERS_LEN};
#[cfg(feature = "std")]
pub use session::{Counts, DamagedPacket, FrameCopy, Packet, Session, PAIRING_WINDOW};
#[cfg(feature = "decoder")]
mod record;
#[cfg(feature = "decoder")]
pub use record::{DatagramRecord, Fields, MeaningRecord, DATAGRAM_KIND, RECORD_KINDS};
