//! The decoder session: every frame of a log read as CANopen, in the
//! context the log itself builds (docs/output.md#json,
//! docs/canopen.md#sdo, docs/canopen.md#pdo-mappings).
//!
//! A [`Decoder`] keeps what ties frames together, per interface and node:
//! the SDO channels and their transfers (docs/canopen.md#transfers), the PDO
//! mappings — learned from the SDO configuration seen in the log, from a node's
//! EDS/DCF, or the pre-defined connection set (docs/canopen.md#pdo-mappings) —
//! and each drive's CiA 402 state (docs/canopen.md#cia402). [`Decoder::decode`]
//! turns one logged frame into a [`Decoded`]: the [`CanOpenMessage`], the SDO
//! step and the transfer it ends with its data, the PDO's signals and the CiA
//! 402 reading — typed values that borrow the session, with no allocation per
//! frame. The [`summary`](crate::summary) builds the post-mortem from them.
//!
//! ```
//! use motionwire::can::{CanFrame, CanId, LogFrame};
//! use motionwire::canopen::NodeId;
//! use motionwire::decoder::{Decoder, DecoderConfig};
//! use motionwire::logs::Position;
//! use motionwire::profiles::Profile;
//!
//! let drive = NodeId::new(3).unwrap();
//! let mut decoder = Decoder::new(DecoderConfig::new().node_profile(drive, Profile::Akd));
//! let frame = |id: u32, data: &[u8]| {
//!     LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
//! };
//!
//! // An expedited SDO read of the statusword, request and response:
//! let request = frame(0x603, &[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]);
//! let step = decoder.decode(Position::Line(1), &request).sdo.unwrap();
//! assert_eq!(step.to_string(), "request initiate upload 6041h.00 Statusword");
//! let response = frame(0x583, &[0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]);
//! let decoded = decoder.decode(Position::Line(2), &response);
//! assert_eq!(decoded.sdo.unwrap().to_string(), "read 6041h.00 = 0x0237 (expedited, 2 B)");
//! assert_eq!(decoded.cia402.unwrap().to_string(), "operation_enabled");
//!
//! // TPDO1 of node 3 with the pre-defined COB-ID, mapped by SDO writes of
//! // 1A00h seen earlier in the log, would now carry named signals.
//! # Ok::<(), motionwire::Error>(())
//! ```

mod bus;
mod cia402;
mod columns;
pub mod ethercat;
pub(crate) mod json;
mod names;
mod pdo;
pub(crate) mod record;
mod sdo;
mod servo;

use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

pub use bus::Device;

/// The owned form of a frame's interface, which sits beside it in
/// [`can`](crate::can) as [`can::BusName`](crate::can::BusName).
#[deprecated(note = "use `motionwire::can::BusName`, the same type")]
pub type BusName = crate::can::BusName;
pub use cia402::Cia402Reading;
pub use columns::FrameColumns;
pub use names::ObjectNames;
pub use pdo::{PdoMap, PdoOrigin, PdoReading};
pub(crate) use sdo::SdoSeen;
pub use sdo::{EndedTransfer, SdoStep};
pub use servo::{CommandRecord, FaultRecord, FeedbackRecord};

use crate::can::{Iface, LogFrame};
use crate::canopen::sdo::{SdoEvent, SdoOutcome, SdoParty, SdoTransfer, TransferDirection};
use crate::canopen::{
    cob_id, CanOpenMessage, DataType, DecodeError, MessageKind, ModeOfOperation, NodeId, PdoCobId,
    PdoDirection, Signal, Value,
};
use crate::eds::{Eds, EdsError};
use crate::logs::Position;
use crate::profiles::{NodeProfiles, Profile};
use crate::CodecError;

pub(crate) use bus::Buses;

use cia402::DriveState;
use pdo::{Names, PdoParams};
use sdo::SdoChannel;

/// The SDO data a transfer keeps by default: `transfer.data`
/// (docs/output.md#transfer) holds the first 4096 bytes.
pub const SDO_DATA_CAP: usize = 4096;

/// How a [`Decoder`] reads a log: each node's profile, the EDS/DCF files
/// that describe nodes, how much SDO data a transfer keeps, and whether
/// PDO signals are unpacked.
///
/// ```
/// use motionwire::canopen::NodeId;
/// use motionwire::decoder::DecoderConfig;
/// use motionwire::profiles::Profile;
///
/// let config = DecoderConfig::new()
///     .profile(Profile::Generic)
///     .node_profile(NodeId::new(3).unwrap(), Profile::Akd)
///     .node_profile(NodeId::new(5).unwrap(), Profile::Baumer)
///     .sdo_data_cap(256);
/// assert_eq!(config.profiles().of(NodeId::new(5)), Profile::Baumer);
/// ```
#[derive(Debug, Clone)]
pub struct DecoderConfig {
    profiles: NodeProfiles,
    descriptions: Vec<Description>,
    sdo_data_cap: usize,
    signals: bool,
    heartbeat: Option<Duration>,
    ethercat_slaves: Vec<ethercat::SlaveConfig>,
    servos: ethercat::ServoSlaves,
}

impl Default for DecoderConfig {
    fn default() -> Self {
        DecoderConfig::new()
    }
}

impl DecoderConfig {
    /// Every node generic, no EDS, [`SDO_DATA_CAP`] bytes of SDO data, PDO
    /// signals unpacked.
    #[must_use]
    pub fn new() -> Self {
        DecoderConfig {
            profiles: NodeProfiles::default(),
            descriptions: Vec::new(),
            sdo_data_cap: SDO_DATA_CAP,
            signals: true,
            heartbeat: None,
            ethercat_slaves: Vec::new(),
            servos: ethercat::ServoSlaves::default(),
        }
    }

    /// Return the configuration with `profile` for every node not named
    /// with [`node_profile`](Self::node_profile) (`--profile akd` in
    /// docs/output.md#command).
    #[must_use]
    pub fn profile(mut self, profile: Profile) -> Self {
        self.profiles.set_default(profile);
        self
    }

    /// Return the configuration with `profile` for `node`
    /// (`--profile 3=akd` in docs/output.md#command).
    #[must_use]
    pub fn node_profile(mut self, node: NodeId, profile: Profile) -> Self {
        self.profiles.set(node, profile);
        self
    }

    /// Return the configuration with every node's profile from `profiles`.
    #[must_use]
    pub fn profiles_from(mut self, profiles: NodeProfiles) -> Self {
        self.profiles = profiles;
        self
    }

    /// Return each node's profile.
    #[must_use]
    pub fn profiles(&self) -> &NodeProfiles {
        &self.profiles
    }

    /// Return the configuration with `eds` describing `node`
    /// (docs/canopen.md#pdo-mappings item 2, `--eds NODE=FILE`): its PDOs
    /// decode that node's frames until the log's own SDO configuration changes
    /// them, its names and types name the signals, and a device type of 402
    /// makes the node a drive. Read the file for that node (`$NODEID` resolves
    /// to it).
    ///
    /// # Errors
    ///
    /// The file's PDO parameters cannot be read ([`EdsError`]).
    pub fn eds(mut self, node: NodeId, eds: Eds) -> Result<Self, EdsError> {
        let pdos = eds
            .pdos()?
            .into_iter()
            .map(|pdo| DescribedPdo {
                transmit: pdo.direction == PdoDirection::Transmit,
                number: pdo.number,
                cob_id: pdo.communication.cob_id,
                entries: pdo.mapping.entries().iter().map(|e| e.to_u32()).collect(),
            })
            .collect();
        self.descriptions.retain(|d| d.node != node);
        self.descriptions.push(Description { node, eds, pdos });
        Ok(self)
    }

    /// Return the configuration with the EDS or DCF file at `path`
    /// describing `node` ([`eds`](Self::eds)).
    ///
    /// # Errors
    ///
    /// The file cannot be read, or is not a valid EDS/DCF ([`EdsError`]).
    pub fn eds_file(self, node: NodeId, path: impl AsRef<Path>) -> Result<Self, EdsError> {
        let eds = Eds::read_file(path.as_ref(), Some(node))?;
        self.eds(node, eds)
    }

    /// Return the configuration keeping at most `cap` data bytes of each
    /// SDO transfer ([`EndedTransfer::data`]; [`SDO_DATA_CAP`] by default).
    #[must_use]
    pub fn sdo_data_cap(mut self, cap: usize) -> Self {
        self.sdo_data_cap = cap;
        self
    }

    /// Return the configuration that unpacks every PDO's signals (`true`,
    /// the default), or only reads a drive's statusword for its CiA 402
    /// state (`false`: what the [summary](crate::summary) needs; the
    /// [`PdoReading`]s then have no signals).
    #[must_use]
    pub fn signals(mut self, signals: bool) -> Self {
        self.signals = signals;
        self
    }

    /// Return the configuration whose [summary](crate::summary) monitors
    /// every node's heartbeats with the consumer time `time` (object
    /// 1016h; `--heartbeat-ms`): each gap longer than it is a timeout
    /// (docs/summary.md#heartbeat). Without it, heartbeat gaps are not
    /// asked for.
    #[must_use]
    pub fn heartbeat_timeout(mut self, time: Duration) -> Self {
        self.heartbeat = Some(time);
        self
    }

    /// Return the configuration with what an ENI file
    /// or a mapping given by hand says of
    /// the EtherCAT slaves' process data (`--eni FILE`;
    /// docs/ethercat.md#process-data); the capture's own start-up wins
    /// where it writes the same.
    #[must_use]
    pub fn ethercat_slaves(mut self, slaves: Vec<ethercat::SlaveConfig>) -> Self {
        self.ethercat_slaves = slaves;
        self
    }

    /// Return the configuration that reads the slaves `servos` names as
    /// servos of docs/servo.md (`--servo`; docs/ethercat.md#servo).
    #[must_use]
    pub fn servos(mut self, servos: ethercat::ServoSlaves) -> Self {
        self.servos = servos;
        self
    }

    /// Return the EtherCAT slaves' configuration given
    /// ([`ethercat_slaves`](Self::ethercat_slaves)).
    #[must_use]
    pub fn ethercat_slave_configs(&self) -> &[ethercat::SlaveConfig] {
        &self.ethercat_slaves
    }

    /// Return the slaves read as servos ([`servos`](Self::servos)).
    #[must_use]
    pub fn servo_slaves(&self) -> &ethercat::ServoSlaves {
        &self.servos
    }

    /// Return the heartbeat consumer time the summary checks gaps against,
    /// if one was given ([`heartbeat_timeout`](Self::heartbeat_timeout)).
    #[must_use]
    pub fn heartbeat(&self) -> Option<Duration> {
        self.heartbeat
    }
}

/// One PDO as a node's EDS/DCF gives it.
#[derive(Debug, Clone)]
struct DescribedPdo {
    transmit: bool,
    number: u16,
    cob_id: PdoCobId,
    entries: Vec<u32>,
}

/// A node's EDS/DCF and the PDOs it configures.
#[derive(Debug, Clone)]
struct Description {
    node: NodeId,
    eds: Eds,
    pdos: Vec<DescribedPdo>,
}

impl Names for Description {
    fn name(&self, index: u16, sub: u8) -> Option<&str> {
        self.eds.name(index, sub)
    }

    fn data_type(&self, index: u16, sub: u8) -> Option<DataType> {
        self.eds.data_type(index, sub)
    }
}

/// One frame as the decoder read it: its kind and node, the CANopen
/// message, and what the session adds to it (docs/output.md#json,
/// docs/output.md#sdo, docs/output.md#pdo, docs/output.md#cia402). Borrows the
/// decoder and the frame until the next frame.
#[derive(Debug, Clone, Copy)]
pub struct Decoded<'d> {
    /// Where the log has the frame: its line or record (`line` in
    /// docs/formats.md#positions).
    pub position: Position,
    /// The frame as the log recorded it.
    pub log: &'d LogFrame<'d>,
    /// The frame's kind, from its identifier (`kind` in
    /// docs/output.md#common-keys).
    pub kind: MessageKind,
    /// The node the identifier names, for the kinds that have one
    /// (`node` in docs/output.md#common-keys).
    pub node: Option<NodeId>,
    /// The profile of the frame's node (the default profile for frames
    /// without a node): how its EMCY's manufacturer bytes read.
    pub profile: Profile,
    /// An SDO frame as its channel's tracker read it, with the transfer it
    /// ends (docs/output.md#transfer).
    pub sdo: Option<SdoStep<'d>>,
    /// A PDO read with the mapping in force for its COB-ID
    /// (docs/canopen.md#signals); `None` when no mapping is known.
    pub pdo: Option<PdoReading<'d>>,
    /// What the frame tells of a drive's CiA 402 state machine: a drive's
    /// PDO that maps its statusword, controlword or mode (the drive is the
    /// owner of [`pdo`](Self::pdo)'s mapping), or a completed expedited SDO
    /// transfer of one of them (the drive is [`node`](Self::node))
    /// (docs/output.md#cia402). [`Decoded::drive`] names the drive.
    pub cia402: Option<Cia402Reading>,
}

impl Decoded<'_> {
    /// Return the drive [`cia402`](Self::cia402) is about: the owner of
    /// the PDO's mapping, else the frame's node.
    #[must_use]
    pub fn drive(&self) -> Option<NodeId> {
        match &self.pdo {
            Some(pdo) => Some(pdo.map.node()),
            None => self.node,
        }
    }

    /// Return the frame read as CANopen, or why its data could not be
    /// ([`CanOpenMessage::decode`]; worked out on each call, so that a
    /// caller that needs only the kind pays nothing for it).
    ///
    /// # Errors
    ///
    /// The frame's data is not what its kind needs ([`DecodeError`], which
    /// still has the kind and node).
    pub fn message(&self) -> Result<CanOpenMessage, DecodeError> {
        CanOpenMessage::decode(&self.log.frame)
    }
}

/// A transfer that the input ended in the middle of (docs/canopen.md#transfers:
/// reported in the summary only).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OpenTransfer {
    /// The bus.
    pub bus: crate::can::BusName,
    /// The node whose SDO server the transfer reached.
    pub node: NodeId,
    /// The transfer, with outcome [`SdoOutcome::Broken`] or
    /// [`SdoOutcome::TimedOut`].
    pub transfer: SdoTransfer,
    /// The name of the transfer's object, where known (`object` in
    /// docs/canopen.md#object-names, as [`EndedTransfer::object`]).
    pub object: Option<String>,
}

/// What the decoder knows of one node.
#[derive(Debug, Default)]
struct NodeState {
    sdo: SdoChannel,
    pdos: HashMap<(bool, u16), PdoParams>,
    drive: bool,
    cia402: DriveState,
}

/// What the decoder knows of one interface.
#[derive(Debug)]
struct BusState {
    nodes: Vec<Option<NodeState>>,
    /// COB-ID → index + 1 into `maps` (0: no mapping).
    by_cob: Box<[u16; 2048]>,
    maps: Vec<PdoMap>,
    /// By node-ID: a guard request (RTR on 0x700 + node) was seen and not
    /// yet answered, so the next data frame on that identifier is its
    /// answer (docs/output.md#heartbeat).
    guard_requests: [bool; 128],
}

impl BusState {
    /// The mapping in force for a PDO on `cob_id`, and the state of the
    /// node that owns it (made on first sight); `None` without a mapping.
    #[inline(always)]
    fn mapping(&mut self, cob_id: u16) -> Option<(&PdoMap, &mut NodeState)> {
        let slot = *self.by_cob.get(usize::from(cob_id))?;
        let map = self.maps.get(usize::from(slot).checked_sub(1)?)?;
        let state = self
            .nodes
            .get_mut(usize::from(map.node().get()))?
            .get_or_insert_with(NodeState::default);
        Some((map, state))
    }

    fn new() -> Self {
        BusState {
            nodes: (0..128).map(|_| None).collect(),
            by_cob: Box::new([0; 2048]),
            maps: Vec::new(),
            guard_requests: [false; 128],
        }
    }

    #[inline]
    fn node(&mut self, node: NodeId, profiles: &NodeProfiles) -> &mut NodeState {
        self.nodes[usize::from(node.get())].get_or_insert_with(|| NodeState {
            drive: profiles.of(Some(node)).is_drive(),
            ..NodeState::default()
        })
    }
}

/// The decoder session: reads each frame of a log in the context of the
/// frames before it (see the [module](self) documentation).
#[derive(Debug)]
pub struct Decoder {
    buses: Buses<BusState>,
    config: DecoderConfig,
    /// Index 1..=127: where each node's objects get their names, worked
    /// out once from the configuration (which does not change after
    /// [`Decoder::new`]), not for every SDO frame.
    names: Box<[NodeNames; 128]>,
    /// The signals of the last PDO (reused: no allocation per frame).
    signals: Vec<Result<Signal, CodecError>>,
    next_map: u32,
    /// The guard requests not yet answered, on every bus: with none, a
    /// heartbeat is one without a look at its bus's requests.
    guard_requests: u32,
}

impl Decoder {
    /// Start a session.
    #[must_use]
    pub fn new(config: DecoderConfig) -> Self {
        let mut names = Box::new([NodeNames::default(); 128]);
        for (raw, slot) in names.iter_mut().enumerate() {
            if let Some(node) = NodeId::new(raw as u8) {
                *slot = NodeNames::of(&config, node);
            }
        }
        Decoder {
            buses: Buses::default(),
            config,
            names,
            signals: Vec::with_capacity(64),
            next_map: 0,
            guard_requests: 0,
        }
    }

    /// Return the session's configuration.
    #[must_use]
    pub fn config(&self) -> &DecoderConfig {
        &self.config
    }

    /// Read one frame, logged at `position` (the line or record a
    /// transfer's `start_line` names, docs/formats.md#positions), in the
    /// context of the frames before it; the session learns from it (SDO
    /// transfers, PDO mappings, drive states).
    pub fn decode<'d>(&'d mut self, position: Position, frame: &'d LogFrame<'d>) -> Decoded<'d> {
        let can = &frame.frame;
        let (kind, node) = MessageKind::classify(can);
        let profile = self.config.profiles.of(node);
        let mut decoded = Decoded {
            position,
            log: frame,
            kind,
            node,
            profile,
            sdo: None,
            pdo: None,
            cia402: None,
        };
        match (kind, node) {
            (MessageKind::Sdo, Some(node)) if !can.is_rtr() => {
                let (step, cia402) = self.sdo_owned(position, frame, node);
                decoded.sdo = Some(step);
                decoded.cia402 = cia402;
            }
            (MessageKind::Pdo, Some(_)) if !can.is_rtr() => {
                if let Some((reading, cia402)) = self.pdo_frame(frame) {
                    decoded.pdo = Some(reading);
                    decoded.cia402 = cia402;
                }
            }
            (MessageKind::Heartbeat | MessageKind::GuardRequest, Some(node)) => {
                decoded.kind = self.error_control_frame(frame, kind, node).1;
            }
            _ => {}
        }
        decoded
    }

    /// [`decode`](Self::decode) for a frame that [`MessageKind::classify`]
    /// makes a heartbeat or a guard request of `node` (`kind`): the place
    /// of its bus ([`bus`](Self::bus)) and its kind in the context of the
    /// log — a data frame is a [`MessageKind::GuardAnswer`] when it is the
    /// first one after a guard request to the node, else a heartbeat
    /// (docs/output.md#heartbeat). What the [summary](crate::summary) reads
    /// (`Summarizer::add`).
    #[inline]
    pub(crate) fn error_control_frame(
        &mut self,
        frame: &LogFrame<'_>,
        kind: MessageKind,
        node: NodeId,
    ) -> (usize, MessageKind) {
        let at = self.bus(&frame.iface);
        if kind == MessageKind::Heartbeat && self.guard_requests == 0 {
            return (at, kind);
        }
        let pending = &mut self.buses.get_mut(at).guard_requests[usize::from(node.get())];
        let kind = match kind {
            MessageKind::GuardRequest => {
                if !*pending {
                    *pending = true;
                    self.guard_requests += 1;
                }
                kind
            }
            MessageKind::Heartbeat if *pending => {
                *pending = false;
                self.guard_requests -= 1;
                MessageKind::GuardAnswer
            }
            _ => kind,
        };
        (at, kind)
    }

    /// [`decode`](Self::decode) for a data frame that
    /// [`MessageKind::classify`] makes an SDO frame of `node`: the SDO step
    /// and the CiA 402 reading, without the rest of a [`Decoded`] (what the
    /// [summary](crate::summary) reads, `Summarizer::add`).
    /// The place of the frame's bus ([`bus`](Self::bus)), the step and the
    /// reading go to `then`.
    #[inline(always)]
    pub(crate) fn sdo_frame<'d, R>(
        &'d mut self,
        position: Position,
        frame: &'d LogFrame<'d>,
        node: NodeId,
        then: impl FnOnce(usize, &SdoSeen<'_, 'd>, Option<Cia402Reading>) -> R,
    ) -> R {
        let sender = if frame.frame.id().raw() < u32::from(cob_id::SDO_RX_BASE) {
            SdoParty::Server
        } else {
            SdoParty::Client
        };
        self.sdo(frame, node, sender, position, then)
    }

    /// [`sdo_frame`](Self::sdo_frame) for [`decode`](Self::decode), out of
    /// line, so that the SDO path the summary inlines does not enlarge
    /// `decode`'s other paths (PDOs, every other kind).
    #[inline(never)]
    fn sdo_owned<'d>(
        &'d mut self,
        position: Position,
        frame: &'d LogFrame<'d>,
        node: NodeId,
    ) -> (SdoStep<'d>, Option<Cia402Reading>) {
        self.sdo_frame(position, frame, node, |_, seen, cia402| {
            (seen.step(), cia402)
        })
    }

    /// The CiA 402 reading of a data frame that [`MessageKind::classify`]
    /// makes a PDO, as [`pdo_frame`](Self::pdo_frame) gives it, without
    /// the PDO's reading where the session does not unpack signals: what
    /// the [summary](crate::summary) reads (`Summarizer::add`).
    /// With the reading, the place of the frame's bus ([`bus`](Self::bus)).
    #[inline]
    pub(crate) fn pdo_cia402(
        &mut self,
        frame: &LogFrame<'_>,
    ) -> (usize, Option<(NodeId, Cia402Reading)>) {
        let can = &frame.frame;
        let at = self.bus(&frame.iface);
        let cob_id = can.id().raw() as u16;
        if self.config.signals {
            return (
                at,
                self.pdo_at(at, cob_id, can.data())
                    .and_then(|(pdo, cia402)| Some((pdo.map.node(), cia402?))),
            );
        }
        let reading = self
            .buses
            .get_mut(at)
            .mapping(cob_id)
            .and_then(|(map, state)| {
                Some((map.node(), statusword_reading(map, state, can.data())?))
            });
        (at, reading)
    }

    /// [`decode`](Self::decode) for a data frame that
    /// [`MessageKind::classify`] makes a PDO: its reading and CiA 402
    /// reading, when a mapping is in force for its COB-ID.
    #[inline]
    pub(crate) fn pdo_frame<'d>(
        &'d mut self,
        frame: &LogFrame<'_>,
    ) -> Option<(PdoReading<'d>, Option<Cia402Reading>)> {
        let can = &frame.frame;
        self.pdo(frame.iface, can.id().raw() as u16, can.data())
    }

    /// The place of the bus of `iface` in the session's one table of
    /// buses, which never changes (buses are only added, in the order the
    /// log shows them): the summary keeps what it learns of a bus at the
    /// same place. A new bus starts with the nodes' descriptions.
    #[inline(always)]
    pub(crate) fn bus(&mut self, iface: &Option<Iface<'_>>) -> usize {
        let (at, made) = self.buses.find_or_insert(iface, |_| BusState::new());
        if made {
            self.describe(at);
        }
        at
    }

    /// A new bus: every node given an EDS/DCF starts with its PDOs, and
    /// every node of a drive profile is a drive (docs/canopen.md#pdo-mappings,
    /// docs/canopen.md#cia402).
    fn describe(&mut self, at: usize) {
        for d in 0..self.config.descriptions.len() {
            let description = &self.config.descriptions[d];
            let node = description.node;
            let is_drive = description.eds.is_cia402();
            let state = self.buses.get_mut(at).node(node, &self.config.profiles);
            state.drive |= is_drive;
            for pdo in &description.pdos {
                let params = state.pdos.entry((pdo.transmit, pdo.number)).or_default();
                params.cob_id = Some((pdo.cob_id, PdoOrigin::Eds));
                params.count = Some(pdo.entries.len() as u8);
                for (slot, entry) in params.entries.iter_mut().zip(&pdo.entries) {
                    *slot = Some(*entry);
                }
            }
            let mut keys: Vec<_> = state.pdos.keys().copied().collect();
            keys.sort_unstable();
            for key in keys {
                self.activate(at, node, key, PdoOrigin::Eds);
            }
        }
    }

    /// Feed one SDO frame to its channel (docs/canopen.md#transfers); a
    /// completed transfer to or from a PDO parameter changes the mapping from
    /// here on (docs/canopen.md#pdo-mappings), an upload of 1000h can make the
    /// node a drive, and an expedited transfer of 6040h/6041h/6060h/6061h is
    /// read as CiA 402.
    ///
    /// The step and the reading go to `then`, which the caller inlines:
    /// the summary reads the step where it was made, without a copy.
    #[inline(always)]
    fn sdo<'d, R>(
        &'d mut self,
        frame: &'d LogFrame<'d>,
        node: NodeId,
        sender: SdoParty,
        position: Position,
        then: impl FnOnce(usize, &SdoSeen<'_, 'd>, Option<Cia402Reading>) -> R,
    ) -> R {
        let at = self.bus(&frame.iface);
        let bytes = frame.frame.data();
        let cap = self.config.sdo_data_cap;
        let state = self.buses.get_mut(at).node(node, &self.config.profiles);
        let mut event = SdoEvent::new(sender, bytes);
        state
            .sdo
            .feed(&mut event, frame.timestamp, position.number(), cap);
        let value = match &event.ended {
            Some(transfer)
                if transfer.outcome == SdoOutcome::Completed
                    && teaches(transfer.multiplexer.index) =>
            {
                value_of(state.sdo.finished())
            }
            _ => None,
        };
        let cia402 = match (&event.ended, value) {
            (Some(transfer), Some(value)) => self.learn(at, node, position, transfer, value),
            _ => None,
        };
        let names = self.names[usize::from(node.get())].get(&self.config);
        let step = SdoSeen {
            node,
            event: &event,
            data: bytes,
            names,
            buses: &self.buses,
            at,
        };
        then(at, &step, cia402)
    }

    /// What a completed transfer teaches (docs/canopen.md#pdo-mappings,
    /// docs/canopen.md#cia402); `position` is the frame that completed it.
    fn learn(
        &mut self,
        at: usize,
        node: NodeId,
        position: Position,
        transfer: &SdoTransfer,
        value: u32,
    ) -> Option<Cia402Reading> {
        let m = transfer.multiplexer;
        let profiles = &self.config.profiles;
        if let Some((key, communication)) = pdo::pdo_parameter(m.index) {
            let origin = PdoOrigin::Sdo { position };
            let params = self
                .buses
                .get_mut(at)
                .node(node, profiles)
                .pdos
                .entry(key)
                .or_default();
            match (communication, m.sub_index) {
                (true, 1) => params.cob_id = Some((PdoCobId::from_u32(value), origin)),
                (true, _) => return None,
                (false, 0) => params.count = Some(value as u8),
                (false, sub @ 1..=64) => params.entries[usize::from(sub) - 1] = Some(value),
                (false, _) => return None,
            }
            self.activate(at, node, key, origin);
            return None;
        }
        let state = self.buses.get_mut(at).node(node, profiles);
        if m.index == 0x1000 && transfer.direction == TransferDirection::Upload {
            if crate::canopen::cia402::is_drive_device_type(value) {
                state.drive = true;
            }
            return None;
        }
        if !state.drive || m.sub_index != 0 {
            return None;
        }
        let mut reading = Cia402Reading::empty();
        match m.index {
            0x6041 => reading.state = state.cia402.observe_statusword(value as u16),
            0x6040 => reading.command = state.cia402.observe_controlword(value as u16),
            0x6060 | 0x6061 => reading.mode = Some(ModeOfOperation::from_i8(value as u8 as i8)),
            _ => return None,
        }
        Some(reading)
    }

    /// Put a PDO's mapping in force on its COB-ID, or take it out of force,
    /// after its parameters changed (the change came from `origin`).
    fn activate(&mut self, at: usize, node: NodeId, key: (bool, u16), origin: PdoOrigin) {
        let profile = self.config.profiles.of(Some(node));
        let description = self.config.descriptions.iter().find(|d| d.node == node);
        let bus = self.buses.get_mut(at);
        let state = bus.nodes[usize::from(node.get())]
            .as_mut()
            .expect("made by the caller");
        let drive = state.drive;
        let params = state.pdos.get_mut(&key).expect("made by the caller");
        let (transmit, number) = key;
        let direction = if transmit {
            PdoDirection::Transmit
        } else {
            PdoDirection::Receive
        };
        if let Some(old) = params.active.take() {
            bus.by_cob[usize::from(old)] = 0;
        }
        let Some(force) = pdo::in_force(params, node, direction, number) else {
            return;
        };
        let cob_id = force.raw();
        // A node whose device type says CiA 402 reads with the drive
        // profile's names and types, whatever its profile
        // (docs/canopen.md#signals).
        let set = profile
            .object_set()
            .or(drive.then_some(crate::canopen::ObjectSet::Drive));
        let names: Option<&dyn Names> = match description {
            Some(d) => Some(d),
            None => None,
        };
        let id = self.next_map;
        self.next_map = self.next_map.wrapping_add(1);
        let map = pdo::build_map(
            id, node, direction, number, &force, origin, names, set, drive,
        );
        let slot = &mut bus.by_cob[usize::from(cob_id)];
        if *slot != 0 {
            bus.maps[usize::from(*slot) - 1] = map;
        } else {
            bus.maps.push(map);
            *slot = bus.maps.len() as u16;
        }
        params.active = Some(cob_id);
    }

    /// The mapping in force for a PDO frame on `cob_id`, its signals (when
    /// the session unpacks them), and its CiA 402 reading for a drive
    /// (docs/canopen.md#signals, docs/canopen.md#cia402).
    fn pdo(
        &mut self,
        iface: Option<Iface<'_>>,
        cob_id: u16,
        data: &[u8],
    ) -> Option<(PdoReading<'_>, Option<Cia402Reading>)> {
        let at = self.bus(&iface);
        self.pdo_at(at, cob_id, data)
    }

    /// [`pdo`](Self::pdo) on the bus at `at`.
    #[inline(always)]
    fn pdo_at(
        &mut self,
        at: usize,
        cob_id: u16,
        data: &[u8],
    ) -> Option<(PdoReading<'_>, Option<Cia402Reading>)> {
        let (map, state) = self.buses.get_mut(at).mapping(cob_id)?;
        let drive = map.is_drive() || state.drive;
        self.signals.clear();
        if !self.config.signals {
            let cia402 = statusword_reading(map, state, data);
            let reading = PdoReading {
                map,
                signals: &self.signals,
            };
            return Some((reading, cia402));
        }
        self.signals.extend(
            map.layout()
                .unpack(data)
                .map(|s| s.map_err(CodecError::from)),
        );
        let cia402 = if drive {
            state.cia402.read(self.signals.iter().flatten())
        } else {
            None
        };
        let reading = PdoReading {
            map,
            signals: &self.signals,
        };
        Some((reading, cia402))
    }

    /// Return how `node`'s objects are named (`object` in
    /// docs/canopen.md#object-names): its EDS or DCF's `ParameterName` first,
    /// then the CiA 301 communication objects and the objects of its profile
    /// (CiA 402's for a node whose EDS makes it a drive): what
    /// [`SdoStep::object`] names.
    #[must_use]
    pub fn object_names(&self, node: NodeId) -> ObjectNames<'_> {
        self.names[usize::from(node.get())].get(&self.config)
    }

    /// Return whether `node` on `bus` is a CiA 402 drive: its profile, its
    /// EDS's device type or an SDO upload of 1000h in the log says so
    /// (docs/canopen.md#cia402).
    #[must_use]
    pub fn is_drive(&self, bus: &crate::can::BusName, node: NodeId) -> bool {
        self.buses
            .find(bus)
            .and_then(|b| b.nodes[usize::from(node.get())].as_ref())
            .is_some_and(|n| n.drive)
            || self.config.profiles.of(Some(node)).is_drive()
    }

    /// Return the PDO mappings in force for `node` on `bus`, as the log
    /// has set them so far (docs/canopen.md#pdo-mappings): its TPDOs, then
    /// its RPDOs, each by number. A bus on which no SDO or PDO frame has
    /// been decoded yet has none (an EDS/DCF sets a node's PDOs when the
    /// bus's first such frame comes).
    ///
    /// ```
    /// use motionwire::can::{CanFrame, CanId, LogFrame};
    /// use motionwire::canopen::{NodeId, PdoDirection};
    /// use motionwire::can::BusName;
    /// use motionwire::decoder::{Decoder, DecoderConfig, PdoOrigin};
    /// use motionwire::logs::Position;
    /// use motionwire::profiles::Profile;
    ///
    /// let node = NodeId::new(3).unwrap();
    /// let mut decoder = Decoder::new(DecoderConfig::new().node_profile(node, Profile::Akd));
    /// // Map the statusword (6041h, 16 bits) into TPDO1 of node 3: entry 1,
    /// // then the count, each an expedited SDO write and its answer.
    /// let writes: [(u32, [u8; 8]); 4] = [
    ///     (0x603, [0x23, 0x00, 0x1A, 0x01, 0x10, 0x00, 0x41, 0x60]),
    ///     (0x583, [0x60, 0x00, 0x1A, 0x01, 0, 0, 0, 0]),
    ///     (0x603, [0x2F, 0x00, 0x1A, 0x00, 0x01, 0, 0, 0]),
    ///     (0x583, [0x60, 0x00, 0x1A, 0x00, 0, 0, 0, 0]),
    /// ];
    /// for (line, (id, data)) in (1..).zip(writes) {
    ///     let frame = LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), &data).unwrap());
    ///     decoder.decode(Position::Line(line), &frame);
    /// }
    /// let bus = BusName::of(None);
    /// let maps: Vec<_> = decoder.mappings(&bus, node).collect();
    /// assert_eq!(maps.len(), 1);
    /// let tpdo1 = maps[0];
    /// assert_eq!((tpdo1.direction(), tpdo1.number()), (PdoDirection::Transmit, 1));
    /// assert_eq!(tpdo1.can_id().raw(), 0x183);
    /// assert_eq!(tpdo1.names(), ["Statusword"]);
    /// // In force from the answer to the count's write, on the pre-defined
    /// // COB-ID.
    /// assert_eq!(tpdo1.origin(), PdoOrigin::Sdo { position: Position::Line(4) });
    /// assert_eq!(tpdo1.cob_id_origin(), PdoOrigin::PredefinedConnectionSet);
    /// ```
    pub fn mappings(
        &self,
        bus: &crate::can::BusName,
        node: NodeId,
    ) -> impl Iterator<Item = &PdoMap> + '_ {
        let mut maps: Vec<&PdoMap> = self.buses.find(bus).map_or_else(Vec::new, |b| {
            // In force: the map its COB-ID's slot points to (a map taken
            // out of force, or moved, keeps its place in `maps`).
            b.maps
                .iter()
                .enumerate()
                .filter(|&(i, map)| {
                    map.node() == node
                        && usize::from(b.by_cob[map.can_id().raw() as usize]) == i + 1
                })
                .map(|(_, map)| map)
                .collect()
        });
        maps.sort_unstable_by_key(|m| (m.direction() == PdoDirection::Receive, m.number()));
        maps.into_iter()
    }

    /// Return the name of the bus at `at` ([`bus`](Self::bus)).
    pub(crate) fn bus_name(&self, at: usize) -> &crate::can::BusName {
        self.buses.name(at)
    }

    /// End of the input: take every transfer left open, which ends here
    /// (docs/canopen.md#transfers: reported in the summary only). The session
    /// can go on with a new input afterwards.
    pub fn finish(&mut self) -> Vec<OpenTransfer> {
        let mut open = Vec::new();
        for (bus, state) in self.buses.iter_mut() {
            for (i, node) in state.nodes.iter_mut().enumerate() {
                let Some(node) = node else { continue };
                if let Some(transfer) = node.sdo.finish() {
                    let object = self.names[i]
                        .get(&self.config)
                        .name(transfer.multiplexer.index)
                        .map(str::to_owned);
                    open.push(OpenTransfer {
                        bus: bus.clone(),
                        node: NodeId::new(i as u8).expect("1..=127"),
                        transfer,
                        object,
                    });
                }
            }
        }
        open
    }
}

/// Where one node's objects get their names (`object` in
/// docs/canopen.md#object-names): its description's place in the
/// configuration, if it has one, and the objects of its profile (CiA 402's
/// for a node whose EDS makes it a drive).
#[derive(Debug, Clone, Copy, Default)]
struct NodeNames {
    description: Option<u8>,
    set: Option<crate::canopen::ObjectSet>,
}

impl NodeNames {
    /// How `node` names its objects under `config`.
    fn of(config: &DecoderConfig, node: NodeId) -> Self {
        let description = config.descriptions.iter().position(|d| d.node == node);
        let eds = description.map(|at| &config.descriptions[at].eds);
        let set = config.profiles.of(Some(node)).object_set().or(eds
            .is_some_and(Eds::is_cia402)
            .then_some(crate::canopen::ObjectSet::Drive));
        NodeNames {
            // One description per node (`DecoderConfig::eds` replaces a
            // node's): fewer than 128 of them.
            description: description.and_then(|at| u8::try_from(at).ok()),
            set,
        }
    }

    /// The names, with the EDS from `config` (the configuration they were
    /// worked out from).
    #[inline]
    fn get(self, config: &DecoderConfig) -> ObjectNames<'_> {
        let eds = self
            .description
            .and_then(|at| config.descriptions.get(usize::from(at)))
            .map(|d| &d.eds);
        ObjectNames::new(eds, self.set)
    }
}

/// The CiA 402 reading of a PDO mapped by `map` on a drive (`state` its
/// node's) whose statusword it carries, read from `data` alone: what a
/// session that does not unpack signals reads (the summary's timeline is
/// observed from statuswords, docs/summary.md#cia402).
#[inline]
fn statusword_reading(map: &PdoMap, state: &mut NodeState, data: &[u8]) -> Option<Cia402Reading> {
    if !(map.is_drive() || state.drive) {
        return None;
    }
    let sw = map
        .statusword()
        .and_then(|i| map.layout().read(i, data))
        .and_then(|s| match s.ok()?.value {
            Value::Unsigned(v) => Some(v as u16),
            _ => None,
        })?;
    Some(Cia402Reading {
        state: state.cia402.observe_statusword(sw),
        ..Cia402Reading::empty()
    })
}

/// Whether a completed transfer of object `index` can teach the session
/// anything ([`Decoder::learn`]): a PDO parameter (`pdo::pdo_parameter`),
/// the device type, a drive's controlword, statusword or mode (the objects
/// `learn` reads after the PDO parameters). Every other object is only
/// reported: its transfer is not handed to `learn`.
#[inline]
fn teaches(index: u16) -> bool {
    pdo::pdo_parameter(index).is_some()
        || matches!(index, 0x1000 | 0x6040 | 0x6041 | 0x6060 | 0x6061)
}

/// The value of a completed expedited transfer's data, little-endian, for
/// the objects the decoder learns from (all of them 4 bytes or fewer).
fn value_of(data: &[u8]) -> Option<u32> {
    if data.is_empty() || data.len() > 4 {
        return None;
    }
    // Byte by byte (at most four), not by a call to `memcpy` of a
    // length known only here.
    Some(
        data.iter()
            .rev()
            .fold(0, |value, &byte| value << 8 | u32::from(byte)),
    )
}

#[cfg(test)]
mod tests;
