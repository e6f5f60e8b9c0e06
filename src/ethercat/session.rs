//! The session that reads a capture's EtherCAT packets in order: which
//! copy of a frame each packet is, and which sent frames never came back
//! (docs/ethercat.md#direction).

use std::collections::VecDeque;

use crate::can::{EthercatPacket, Iface, Timestamp};
use crate::ethercat::{Datagrams, EthercatFrame, FrameType, Mac};
use crate::logs::Position;
use crate::LenError;

/// How many sent frames of an interface wait for their returned copy: a
/// TwinCAT master's returns lag up to about ten frames
/// (docs/ethercat.md#direction); a frame pushed out of the window unpaired
/// is lost.
pub const PAIRING_WINDOW: usize = 64;

/// Which copy of a frame a packet is (docs/ethercat.md#direction).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrameCopy {
    /// As the master sent it (the source MAC's bit 0x02 clear).
    Sent,
    /// As it came back through the slaves, paired with its sent copy at
    /// that packet.
    Returned {
        /// The packet of the sent copy.
        sent: Position,
    },
    /// Came back through the slaves (the bit set), with no sent copy in
    /// the capture: a capture that starts late, a second master, or a
    /// capture taken behind the last slave.
    ReturnedUnpaired,
}

impl FrameCopy {
    /// Return whether the packet came back through the slaves.
    #[must_use]
    pub const fn returned(self) -> bool {
        !matches!(self, FrameCopy::Sent)
    }
}

/// One EtherCAT packet as the session read it: its position and time,
/// which copy it is, and its frame.
#[derive(Debug, Clone, Copy)]
pub struct Packet<'a> {
    /// The packet's number in the capture.
    pub position: Position,
    /// When it was captured.
    pub timestamp: Option<Timestamp>,
    /// The interface it was captured on.
    pub iface: Option<Iface<'a>>,
    /// The source MAC.
    pub source: Mac,
    /// Which copy it is.
    pub copy: FrameCopy,
    /// The EtherCAT frame.
    pub frame: EthercatFrame<'a>,
}

impl<'a> Packet<'a> {
    /// Return the frame's datagrams, in order.
    #[must_use]
    pub fn datagrams(&self) -> Datagrams<'a> {
        self.frame.datagrams()
    }
}

/// A sent frame waiting for its returned copy.
#[derive(Debug, Clone, Copy)]
struct Pending {
    position: Position,
    source: Mac,
    signature: u64,
}

/// What the session keeps per interface.
#[derive(Debug, Default)]
struct Port {
    /// The interface's name (`None`: unnamed).
    name: Option<String>,
    pending: VecDeque<Pending>,
}

/// The counts a session keeps, per capture (docs/ethercat.md#direction).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// EtherCAT packets read.
    pub packets: u64,
    /// Frames of datagrams as sent.
    pub sent: u64,
    /// Returned frames of datagrams paired with their sent copy.
    pub returned: u64,
    /// Returned frames of datagrams without a sent copy.
    pub returned_unpaired: u64,
    /// Sent frames that never came back.
    pub lost: u64,
    /// Packets whose frame is not datagrams (ADS, raw I/O, network
    /// variables, mailbox gateway, a reserved type): counted, not decoded,
    /// not paired.
    pub other_frame_types: u64,
    /// Packets whose EtherCAT header or a datagram is damaged.
    pub damaged: u64,
}

/// A packet whose EtherCAT header or datagram is damaged: where, and why
/// (docs/ethercat.md#reading). The capture is read on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("packet {position}: {error}")]
pub struct DamagedPacket {
    /// The packet.
    pub position: Position,
    /// What is too short.
    pub error: LenError,
}

/// The EtherCAT session of a capture: feed it every EtherCAT packet in
/// the capture's order ([`Session::read`]); it tells each packet's copy,
/// pairs returned frames with sent ones, and counts the frames lost.
///
/// ```
/// use motionwire::can::{EthercatPacket, LogEvent};
/// use motionwire::ethercat::{Command, Session};
/// use motionwire::logs::Position;
/// use motionwire::ethercat::{DatagramRepr, Encapsulation, EthercatLink, Mac};
///
/// // One BRD of AL status, sent by an ethercrab master and returned
/// // through two slaves.
/// let frame = |wkc: u16| {
///     let mut bytes = vec![0x0e, 0x10];
///     let datagram = DatagramRepr {
///         command: Command::Brd, index: 7, address: 0x0130_0000, circulating: false,
///         more_follows: false, irq: 0, data: &[0, 0], working_counter: wkc,
///     };
///     let mut buffer = [0; 14];
///     datagram.emit(&mut buffer).unwrap();
///     bytes.extend(buffer);
///     bytes
/// };
/// let (sent, returned) = (frame(0), frame(2));
/// let packet = |source: [u8; 6], payload: &'static [u8]| EthercatPacket {
///     timestamp: None,
///     iface: None,
///     link: EthercatLink {
///         destination: None,
///         source: Mac(source),
///         encapsulation: Encapsulation::Ethernet,
///         payload,
///     },
/// };
/// let sent: &'static [u8] = sent.leak();
/// let returned: &'static [u8] = returned.leak();
///
/// let mut session = Session::new();
/// let first = session.read(Position::Record(1), &packet([0x10; 6], sent))?;
/// assert!(!first.copy.returned());
/// let second = session.read(Position::Record(2), &packet([0x12, 0x10, 0x10, 0x10, 0x10, 0x10], returned))?;
/// assert_eq!(second.copy, motionwire::ethercat::FrameCopy::Returned { sent: Position::Record(1) });
/// assert_eq!(second.datagrams().next().unwrap()?.working_counter(), 2);
/// assert_eq!(session.finish().lost, 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Default)]
pub struct Session {
    ports: Vec<Port>,
    /// The port of the last packet, tried first.
    last_port: usize,
    counts: Counts,
}

impl Session {
    /// Return a session that has read nothing.
    #[must_use]
    pub fn new() -> Self {
        Session::default()
    }

    /// Read the packet at `position`.
    ///
    /// # Errors
    ///
    /// [`DamagedPacket`] when the EtherCAT header is cut off or announces
    /// more bytes than the packet holds. A damaged datagram inside a whole
    /// frame is the datagram iterator's error, which the caller reports
    /// with the packet's position; count it with
    /// [`Session::count_damaged`].
    pub fn read<'a>(
        &mut self,
        position: Position,
        packet: &EthercatPacket<'a>,
    ) -> Result<Packet<'a>, DamagedPacket> {
        self.counts.packets += 1;
        let frame = match EthercatFrame::parse(packet.link.payload) {
            Ok(frame) => frame,
            Err(error) => {
                self.counts.damaged += 1;
                return Err(DamagedPacket { position, error });
            }
        };
        let source = packet.link.source;
        let copy = if frame.frame_type() == FrameType::Datagrams {
            let port = self.port(packet.iface);
            self.pair(port, position, source, signature(&frame))
        } else {
            // No slave processes it: told by the bit alone, never waited
            // for.
            self.counts.other_frame_types += 1;
            if source.returned_bit() {
                FrameCopy::ReturnedUnpaired
            } else {
                FrameCopy::Sent
            }
        };
        Ok(Packet {
            position,
            timestamp: packet.timestamp,
            iface: packet.iface,
            source: packet.link.source,
            copy,
            frame,
        })
    }

    /// Count a packet whose datagrams the caller found damaged.
    pub fn count_damaged(&mut self) {
        self.counts.damaged += 1;
    }

    /// Return the counts so far; sent frames still waiting are not lost
    /// yet.
    #[must_use]
    pub const fn counts(&self) -> Counts {
        self.counts
    }

    /// End the capture: the sent frames still waiting are lost. Return the
    /// counts.
    pub fn finish(&mut self) -> Counts {
        for port in &mut self.ports {
            self.counts.lost += port.pending.len() as u64;
            port.pending.clear();
        }
        self.counts
    }

    /// Return the index of the port of `iface`, adding it when new.
    fn port(&mut self, iface: Option<Iface<'_>>) -> usize {
        let is = |port: &Port| match (iface, &port.name) {
            (None, None) => true,
            (Some(iface), Some(name)) => iface.to_string() == *name,
            _ => false,
        };
        if self.ports.get(self.last_port).is_some_and(is) {
            return self.last_port;
        }
        let at = match self.ports.iter().position(is) {
            Some(at) => at,
            None => {
                self.ports.push(Port {
                    name: iface.map(|i| i.to_string()),
                    pending: VecDeque::new(),
                });
                self.ports.len() - 1
            }
        };
        self.last_port = at;
        at
    }

    /// Tell which copy a packet is, pairing a returned copy with the
    /// waiting sent frame of the same master and the same datagrams.
    fn pair(&mut self, port: usize, position: Position, source: Mac, signature: u64) -> FrameCopy {
        let pending = &mut self.ports[port].pending;
        if source.returned_bit() {
            let master = source.without_returned_bit();
            let found = pending
                .iter()
                .position(|p| p.signature == signature && p.source == master);
            let Some(at) = found else {
                self.counts.returned_unpaired += 1;
                return FrameCopy::ReturnedUnpaired;
            };
            let sent = pending[at].position;
            // The frames sent before it are not coming back: a ring
            // returns frames in the order they were sent.
            for _ in 0..at {
                pending.pop_front();
                self.counts.lost += 1;
            }
            pending.pop_front();
            self.counts.returned += 1;
            return FrameCopy::Returned { sent };
        }
        if pending.len() == PAIRING_WINDOW {
            pending.pop_front();
            self.counts.lost += 1;
        }
        pending.push_back(Pending {
            position,
            source,
            signature,
        });
        self.counts.sent += 1;
        FrameCopy::Sent
    }
}

/// A frame's datagrams' commands and indices in order, hashed (FNV-1a):
/// what a returned copy keeps of its sent one.
fn signature(frame: &EthercatFrame<'_>) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut mix = |byte: u8| {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    };
    mix(frame.frame_type().bits());
    for datagram in frame.datagrams() {
        match datagram {
            Ok(datagram) => {
                mix(datagram.command().byte());
                mix(datagram.index());
            }
            Err(_) => mix(0xff),
        }
    }
    hash
}
