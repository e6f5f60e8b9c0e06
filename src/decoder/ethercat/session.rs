//! The session that reads a capture's EtherCAT packets in order: which
//! copy of a frame each packet is, and which sent frames never came back
//! (docs/ethercat.md#direction).

use std::cell::OnceCell;
use std::collections::VecDeque;

use crate::can::{EthercatPacket, Iface, Timestamp};
use crate::ethercat::{Addressing, Command, Datagram, Datagrams, EthercatFrame, FrameType, Mac};

use super::config::SlaveConfig;
use super::network::{Meaning, Network};
use super::problem::ImageProblem;
use super::process::{ProcessData, ServoSlaves};
use crate::decoder::json::Padded;
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
#[derive(Debug, Clone)]
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
    /// The session's index of the interface.
    port: usize,
    /// A returned copy's: the ADP of each datagram of its sent copy, when
    /// the frame holds a position-addressed datagram (whose returned ADP
    /// the slaves counted on).
    sent_adps: Vec<u16>,
    /// The JSON keys every record of the packet writes after `datagram`
    /// (`ts`, `iface`), made by its first record.
    pub(super) shared_keys: OnceCell<SharedKeys>,
}

impl<'a> Packet<'a> {
    /// Return the frame's datagrams, in order.
    #[must_use]
    pub fn datagrams(&self) -> Datagrams<'a> {
        self.frame.datagrams()
    }

    /// Return the ADP the datagram at `at` (from 0) had when it was sent:
    /// its own for a sent copy, the sent copy's for a paired returned one
    /// (`None` for a returned copy without it, or a frame without
    /// position-addressed datagrams).
    #[must_use]
    pub fn sent_adp(&self, at: usize, datagram: &Datagram<'_>) -> Option<u16> {
        match self.copy {
            FrameCopy::Sent => Some(datagram.adp()),
            FrameCopy::Returned { .. } => self.sent_adps.get(at).copied(),
            FrameCopy::ReturnedUnpaired => None,
        }
    }
}

/// A sent frame waiting for its returned copy.
#[derive(Debug, Clone)]
struct Pending {
    position: Position,
    source: Mac,
    signature: u64,
    /// Every datagram's ADP, when one is position-addressed.
    adps: Vec<u16>,
    /// The frame's bytes, when it holds a cyclic datagram (LRW, LRD,
    /// LWR): its outputs are read from them.
    payload: Option<Vec<u8>>,
}

/// What the session keeps per interface.
#[derive(Debug, Default)]
struct Port {
    /// The interface's name (`None`: unnamed).
    name: Option<String>,
    pending: VecDeque<Pending>,
    /// The slaves the port's traffic shows.
    network: Network,
    /// The sent copy of the last returned frame with cyclic datagrams:
    /// its packet and bytes.
    sent: Option<(Position, Vec<u8>)>,
    /// Buffers of sent frames, reused.
    spare: Vec<Vec<u8>>,
    /// The source MACs seen sending with the bit clear (the first
    /// [`SENDERS_KEPT`]): their returned copies are never sent frames.
    senders: Vec<Mac>,
}

/// The masters' MACs a port keeps.
const SENDERS_KEPT: usize = 16;

/// The counts a session keeps, per capture (docs/ethercat.md#direction).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
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
    /// Packets whose time is earlier than the packet's before them (a
    /// merged capture; docs/ethercat.md#reading): read in the capture's
    /// order all the same.
    pub time_reversals: u64,
    /// The first of them, and how far back it went.
    pub first_reversal: Option<(Position, core::time::Duration)>,
}

/// The longest `ts` and `iface` keys kept per packet ([`SharedKeys`]): an
/// interface name of up to about 20 bytes (`eth0`, `enp2s0`); a longer
/// one is written by each record.
pub(super) const SHARED_LEN: usize = 64;

/// The keys every JSON record of a packet writes after `datagram`, `ts`
/// and `iface` (`,"ts":1700000000.000500,"iface":"eth0"`), as the packet's
/// first record wrote them: a packet of cyclic traffic has a record for
/// each of its datagrams and more for what they tell. Kept with the time
/// and interface they were made of (the name by where it lies and its
/// length), and written again for a packet whose time or interface was
/// changed since.
#[derive(Debug, Clone)]
pub(crate) struct SharedKeys {
    pub(super) timestamp: Option<Timestamp>,
    pub(super) iface: IfaceKey,
    pub(super) text: Padded<SHARED_LEN>,
}

/// An interface as [`SharedKeys`] compare it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum IfaceKey {
    None,
    Channel(u16),
    /// The name's address and length.
    Name(usize, usize),
}

impl IfaceKey {
    #[inline(always)]
    pub(super) fn of(iface: Option<Iface<'_>>) -> Self {
        match iface {
            None => IfaceKey::None,
            Some(Iface::Channel(channel)) => IfaceKey::Channel(channel),
            Some(Iface::Name(name)) => IfaceKey::Name(name.as_ptr() as usize, name.len()),
        }
    }
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
/// use motionwire::ethercat::{Command};
/// use motionwire::decoder::ethercat::Session;
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
/// assert_eq!(second.copy, motionwire::decoder::ethercat::FrameCopy::Returned { sent: Position::Record(1) });
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
    /// The last packet's time.
    last_time: Option<Timestamp>,
    /// What a configuration file says of the slaves.
    config: Vec<SlaveConfig>,
    /// Which slaves carry the servo frames.
    servos: ServoSlaves,
}

impl Session {
    /// Return a session that has read nothing.
    #[must_use]
    pub fn new() -> Self {
        Session::default()
    }

    /// Return a session with the EtherCAT settings of `config`: the slaves'
    /// configuration ([`DecoderConfig::ethercat_slaves`]) and the servos
    /// ([`DecoderConfig::servos`]).
    ///
    /// [`DecoderConfig::ethercat_slaves`]: crate::decoder::DecoderConfig::ethercat_slaves
    /// [`DecoderConfig::servos`]: crate::decoder::DecoderConfig::servos
    #[must_use]
    pub fn with_config(config: &crate::decoder::DecoderConfig) -> Self {
        let mut session = Session::new();
        session.configure(config.ethercat_slave_configs().to_vec());
        session.set_servos(config.servo_slaves().clone());
        session
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
        if let Some(now) = packet.timestamp {
            if let Some(before) = self.last_time.filter(|before| now < *before) {
                self.counts.time_reversals += 1;
                if self.counts.first_reversal.is_none() {
                    let back = before.as_duration().saturating_sub(now.as_duration());
                    self.counts.first_reversal = Some((position, back));
                }
            }
            self.last_time = Some(now);
        }
        let frame = match EthercatFrame::parse(packet.link.payload) {
            Ok(frame) => frame,
            Err(error) => {
                self.counts.damaged += 1;
                return Err(DamagedPacket { position, error });
            }
        };
        let source = packet.link.source;
        let port = self.port(packet.iface);
        let (copy, sent_adps) = if frame.frame_type() == FrameType::Datagrams {
            self.pair(port, position, source, &frame)
        } else {
            // No slave processes it: told by the bit alone, never waited
            // for.
            self.counts.other_frame_types += 1;
            let copy = if source.returned_bit() {
                FrameCopy::ReturnedUnpaired
            } else {
                FrameCopy::Sent
            };
            (copy, Vec::new())
        };
        Ok(Packet {
            position,
            timestamp: packet.timestamp,
            iface: packet.iface,
            source,
            copy,
            frame,
            port,
            sent_adps,
            shared_keys: OnceCell::new(),
        })
    }

    /// Hand `on_meaning` what the datagram at `at` (from 0) of `packet`
    /// tells of the slaves (docs/ethercat.md#slaves): station addresses,
    /// AL states, SII words, mailbox messages. Call it for every datagram
    /// of every packet, in order: the session learns the slaves from them.
    pub fn meanings<'a>(
        &mut self,
        packet: &Packet<'a>,
        at: usize,
        datagram: &Datagram<'a>,
        on_meaning: impl FnMut(Meaning<'a>),
    ) {
        let sent_adp = packet.sent_adp(at, datagram);
        if let Some(port) = self.ports.get_mut(packet.port) {
            port.network.datagram(
                packet.position,
                packet.timestamp,
                packet.copy.returned(),
                datagram,
                sent_adp,
                on_meaning,
            );
        }
    }

    /// Return the station address of the slave a station-addressed
    /// datagram (FPRD, FPWR, FPRW, FRMW) of `packet` reaches: the slave of
    /// that station address, else the one whose enabled station alias its
    /// ADP is, as the datagrams read so far set it up
    /// (docs/ethercat.md#alias); the ADP itself where the session knows
    /// neither. `None` for a datagram addressed otherwise (by position,
    /// broadcast, logical), which names no one slave. `decode --slave`
    /// keeps a slave's datagrams so, whichever way they were addressed
    /// (docs/ethercat.md#filters).
    #[must_use]
    pub fn station(&self, packet: &Packet<'_>, datagram: &Datagram<'_>) -> Option<u16> {
        if datagram.command().addressing() != Addressing::Station {
            return None;
        }
        let adp = datagram.adp();
        Some(
            self.ports
                .get(packet.port)
                .map_or(adp, |port| port.network.station_reached(adp)),
        )
    }

    /// Take what a configuration file (an ENI, `parse_eni`) or a mapping
    /// given by hand says of the slaves' process data, for every port
    /// (docs/ethercat.md#process-data). Where the capture's start-up
    /// writes the same FMMU or sync manager, or shows a PDO's assignment
    /// or mapping, the capture wins.
    pub fn configure(&mut self, slaves: Vec<SlaveConfig>) {
        for port in &mut self.ports {
            port.network.configure(&slaves);
        }
        self.config = slaves;
    }

    /// Read the slaves `servos` names as servos of docs/servo.md: their
    /// process data gives a [`ServoReading`](super::ServoReading) every
    /// cycle.
    pub fn set_servos(&mut self, servos: ServoSlaves) {
        self.servos = servos;
    }

    /// Hand `on` each slave's process data in the datagram at `at` (from
    /// 0) of `packet`, when it is a returned cyclic datagram (LRW, LRD,
    /// LWR): outputs from its sent copy, inputs from it
    /// (docs/ethercat.md#process-data). Call it after
    /// [`meanings`](Self::meanings) for the same datagram. A sent copy
    /// gives nothing: its inputs are the previous cycle's.
    pub fn process_data(
        &mut self,
        packet: &Packet<'_>,
        at: usize,
        datagram: &Datagram<'_>,
        on: impl FnMut(&ProcessData<'_>),
    ) {
        let command = datagram.command();
        if !packet.copy.returned() || !is_cyclic(command) {
            return;
        }
        let Some(port) = self.ports.get_mut(packet.port) else {
            return;
        };
        let sent = match (packet.copy, &port.sent) {
            (FrameCopy::Returned { sent }, Some((position, bytes))) if *position == sent => {
                sent_datagram(bytes, at)
            }
            _ => None,
        };
        port.network.process_data(
            command,
            datagram.address(),
            sent,
            datagram.data(),
            datagram.working_counter(),
            &self.servos,
            packet.position,
            on,
        );
    }

    /// Take the problems of the slaves' configuration and mailboxes said
    /// since the last call ([`ImageProblem`]: a mapping past its sync
    /// manager, overlapping FMMUs, a mailbox message past its sync
    /// manager, an SDO size past a PDO object), in the order they showed;
    /// and how many more there were than the session keeps between two
    /// calls.
    #[inline]
    pub fn take_problems(&mut self) -> (Vec<ImageProblem>, u64) {
        if !self.ports.iter().any(|port| port.network.has_problems()) {
            return (Vec::new(), 0);
        }
        self.take_kept_problems()
    }

    /// [`take_problems`](Self::take_problems) when a port has some.
    fn take_kept_problems(&mut self) -> (Vec<ImageProblem>, u64) {
        let mut all = Vec::new();
        let mut dropped = 0;
        for port in &mut self.ports {
            if !port.network.has_problems() {
                continue;
            }
            let (problems, more) = port.network.take_problems();
            all.extend(problems);
            dropped += more;
        }
        (all, dropped)
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
            (Some(iface), Some(name)) => named(iface, name),
            _ => false,
        };
        if self.ports.get(self.last_port).is_some_and(is) {
            return self.last_port;
        }
        let at = match self.ports.iter().position(is) {
            Some(at) => at,
            None => {
                let mut network = Network::default();
                network.configure(&self.config);
                self.ports.push(Port {
                    name: iface.map(|i| i.to_string()),
                    pending: VecDeque::new(),
                    network,
                    sent: None,
                    spare: Vec::new(),
                    senders: Vec::new(),
                });
                self.ports.len() - 1
            }
        };
        self.last_port = at;
        at
    }

    /// Tell which copy a packet is, pairing a returned copy with the
    /// waiting sent frame of the same master and the same datagrams.
    fn pair(
        &mut self,
        port: usize,
        position: Position,
        source: Mac,
        frame: &EthercatFrame<'_>,
    ) -> (FrameCopy, Vec<u16>) {
        let shape = Shape::of(frame);
        let signature = shape.signature;
        let master = source.without_returned_bit();
        // A master whose own MAC has the bit: its sent frames wait under
        // that MAC, and order decides (docs/ethercat.md#direction).
        let found = self.ports[port]
            .pending
            .iter()
            .position(|p| p.signature == signature && (p.source == master || p.source == source));
        if let (true, Some(at)) = (source.returned_bit(), found) {
            // The frames sent before it are not coming back: a ring
            // returns frames in the order they were sent.
            let port = &mut self.ports[port];
            for _ in 0..at {
                if let Some(lost) = port.pending.pop_front() {
                    port.spare.extend(lost.payload);
                }
                self.counts.lost += 1;
            }
            let mut sent = port.pending.pop_front().expect("found at the front");
            if let Some(payload) = sent.payload.take() {
                if let Some((_, old)) = port.sent.replace((sent.position, payload)) {
                    port.spare.push(old);
                }
            }
            self.counts.returned += 1;
            return (
                FrameCopy::Returned {
                    sent: sent.position,
                },
                sent.adps,
            );
        }
        if source.returned_bit() {
            // Sent by a master whose MAC has the bit set, if no master is
            // known by the MAC without it and no slave has counted yet.
            if shape.counted || self.ports[port].senders.contains(&master) {
                self.counts.returned_unpaired += 1;
                return (FrameCopy::ReturnedUnpaired, Vec::new());
            }
        } else {
            let senders = &mut self.ports[port].senders;
            if senders.len() < SENDERS_KEPT && !senders.contains(&source) {
                senders.push(source);
            }
        }
        let pending = &mut self.ports[port].pending;
        if pending.len() == PAIRING_WINDOW {
            if let Some(lost) = pending.pop_front() {
                self.ports[port].spare.extend(lost.payload);
            }
            self.counts.lost += 1;
        }
        // A returned position-addressed datagram has another ADP: keep the
        // sent ones (start-up frames only; a cyclic frame keeps none).
        let adps = if shape.positioned {
            frame.datagrams().flatten().map(|d| d.adp()).collect()
        } else {
            Vec::new()
        };
        let port = &mut self.ports[port];
        let payload = shape.cyclic.then(|| {
            let mut buffer = port.spare.pop().unwrap_or_default();
            buffer.clear();
            let header = frame.length() | u16::from(frame.frame_type().bits()) << 12;
            buffer.extend_from_slice(&header.to_le_bytes());
            buffer.extend_from_slice(frame.body());
            buffer
        });
        port.pending.push_back(Pending {
            position,
            source,
            signature,
            adps,
            payload,
        });
        self.counts.sent += 1;
        (FrameCopy::Sent, Vec::new())
    }
}

/// Return whether `name` is `iface` written out (its `Display`), without
/// allocating: the port is looked up for every packet.
fn named(iface: Iface<'_>, name: &str) -> bool {
    match iface {
        Iface::Name(_) => iface.is_name(name.as_bytes()),
        Iface::Channel(channel) => {
            let mut digits = [0u8; 5];
            let mut at = digits.len();
            let mut rest = channel;
            loop {
                at -= 1;
                digits[at] = b'0' + (rest % 10) as u8;
                rest /= 10;
                if rest == 0 {
                    break;
                }
            }
            digits.get(at..) == Some(name.as_bytes())
        }
    }
}

/// Whether a command carries process data: LRW, LRD, LWR.
const fn is_cyclic(command: Command) -> bool {
    matches!(command, Command::Lrw | Command::Lrd | Command::Lwr)
}

/// The data of the datagram at `at` (from 0) of a frame's bytes.
fn sent_datagram(bytes: &[u8], at: usize) -> Option<&[u8]> {
    let frame = EthercatFrame::parse(bytes).ok()?;
    let datagram = frame.datagrams().nth(at)?.ok()?;
    Some(datagram.data())
}

/// What pairing needs of a frame's datagrams, read in one pass.
struct Shape {
    /// The datagrams' commands and indices in order, hashed (FNV-1a):
    /// what a returned copy keeps of its sent one.
    signature: u64,
    /// Whether a datagram's working counter is not 0, or a datagram is
    /// damaged.
    counted: bool,
    /// Whether a whole datagram is position-addressed.
    positioned: bool,
    /// Whether a whole datagram carries process data.
    cyclic: bool,
}

impl Shape {
    fn of(frame: &EthercatFrame<'_>) -> Self {
        let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
        let mut mix = |byte: u8| {
            hash ^= u64::from(byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        };
        mix(frame.frame_type().bits());
        let (mut counted, mut positioned, mut cyclic) = (false, false, false);
        for datagram in frame.datagrams() {
            match datagram {
                Ok(datagram) => {
                    let command = datagram.command();
                    mix(command.byte());
                    mix(datagram.index());
                    counted |= datagram.working_counter() != 0;
                    positioned |= command.addressing() == Addressing::Position;
                    cyclic |= is_cyclic(command);
                }
                Err(_) => {
                    mix(0xff);
                    counted = true;
                }
            }
        }
        Shape {
            signature: hash,
            counted,
            positioned,
            cyclic,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `named` as the interface's text compared.
    #[test]
    fn named_as_the_display() {
        let names = [
            "", "0", "1", "01", "9", "10", "65535", "65536", "eth0", "enp2s0", "x",
        ];
        let ifaces = [0, 1, 9, 10, 99, 100, 12345, 65535]
            .map(Iface::Channel)
            .into_iter()
            .chain(names.map(Iface::Name));
        for iface in ifaces {
            for name in names.iter().copied().chain([iface.to_string().as_str()]) {
                assert_eq!(
                    named(iface, name),
                    iface.to_string() == name,
                    "{iface:?} {name:?}"
                );
            }
        }
    }
}
