//! EtherCAT on the wire (docs/ethercat.md): the views of
//! `motionwire-codec` — frames, datagrams, registers, mailbox, CoE. The
//! session that reads a capture's packets as the master and its slaves
//! exchanged them, and the records `decode` writes, are the decoder's:
//! `motionwire::decoder::ethercat` (feature `decoder`).

pub use motionwire_codec::ethercat::*;
