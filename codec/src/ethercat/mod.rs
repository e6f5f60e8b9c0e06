//! EtherCAT as it appears on the wire: the Ethernet frames a master sends
//! and gets back, the EtherCAT header, the datagrams, the registers a
//! capture shows being read and written, the mailbox and CoE
//! (docs/ethercat.md).
//!
//! Each layer is a zero-copy view over the bytes that checks its length
//! before it reads a field, as smoltcp's `wire` module does, and a
//! [`DatagramRepr`] that writes a datagram back:
//!
//! - [`Link`]: an Ethernet frame unwrapped to its EtherCAT payload —
//!   EtherType 0x88A4, also behind one 802.1Q tag, or in UDP to port
//!   0x88A4 over IPv4 (ETG.1000.4 §5.3; Wireshark's `packet-ethercat-frame.c`);
//! - [`EthercatFrame`]: the 2-byte EtherCAT header (length, type) and the
//!   [`Datagrams`] behind it (ETG.1000.4 §5.4);
//! - [`Datagram`]: command, index, address, length with its circulating
//!   and more-follows flags, IRQ, data and working counter (ETG.1000.4
//!   §5.4.1.2; Beckhoff's ESC datasheet, section I, table 7);
//! - [`register`]: the ESC registers motionwire decodes, the AL state and
//!   AL status code with the texts of ETG.1000.6 table 11 ([`AlStatusCode`]);
//! - [`Fmmu`] and [`SyncManager`]: the configuration that says where a
//!   slave's process data and mailbox are (ETG.1000.4 §6.6, §6.7);
//! - [`MailboxHeader`] and [`MailboxError`] (ETG.1000.6 §5.6), the CoE
//!   header ([`CoeHeader`]), CoE SDO messages ([`CoeSdo`]) and emergencies
//!   (the CiA 301 EMCY of [`crate::canopen::Emcy`] after the CoE header).
//!
//! Nothing here pairs a sent frame with its returned copy or knows which
//! slave is which: that is the session's (motionwire's `ethercat` module),
//! built on these views.
//!
//! ```
//! use motionwire_codec::ethercat::{Command, EthercatFrame, Link};
//!
//! // An ethercrab master's BRD of AL status (0x0130), as it came back
//! // through two slaves: the source MAC's bit 0x02 set, working counter 2.
//! let packet = [
//!     0xff, 0xff, 0xff, 0xff, 0xff, 0xff, // destination
//!     0x12, 0x10, 0x10, 0x10, 0x10, 0x10, // source (sent as 10:10:…)
//!     0x88, 0xa4, // EtherType
//!     0x0e, 0x10, // EtherCAT header: 14 bytes of datagrams, type 1
//!     0x07, 0x00, 0x02, 0x00, 0x30, 0x01, 0x02, 0x00, 0x00, 0x00, // BRD 0x0130, 2 bytes
//!     0x08, 0x00, // AL status: OP
//!     0x02, 0x00, // working counter
//! ];
//! let Link::Ethercat(link) = Link::parse(&packet)? else { panic!() };
//! assert!(link.returned_bit());
//! let frame = EthercatFrame::parse(link.payload)?;
//! let datagram = frame.datagrams().next().unwrap()?;
//! assert_eq!(datagram.command(), Command::Brd);
//! assert_eq!(datagram.ado(), 0x0130);
//! assert_eq!(datagram.data(), [0x08, 0x00]);
//! assert_eq!(datagram.working_counter(), 2);
//! # Ok::<(), motionwire_codec::LenError>(())
//! ```

mod al;
mod coe;
mod config;
mod datagram;
mod frame;
mod link;
mod mailbox;
pub mod register;
#[cfg(test)]
mod tests;

pub use al::{AlState, AlStatus, AlStatusCode};
pub use coe::{CoeHeader, CoeSdo, CoeService, COE_HEADER_LEN};
pub use config::{Fmmu, SyncManager, SyncManagerMode, FMMU_LEN, SYNC_MANAGER_LEN};
pub use datagram::{Addressing, Command, Datagram, DatagramRepr, DATAGRAM_OVERHEAD};
pub use frame::{Datagrams, EthercatFrame, FrameType, ETHERCAT_HEADER_LEN};
pub use link::{Encapsulation, EthercatLink, Link, Mac, ETHERTYPE_ETHERCAT, UDP_PORT_ETHERCAT};
pub use mailbox::{MailboxError, MailboxHeader, MailboxType, MAILBOX_HEADER_LEN};
