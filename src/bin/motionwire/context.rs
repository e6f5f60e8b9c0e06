//! What the decoder learns from the log as it reads it, per interface: the
//! SDO channels and their transfers (SPEC §7.2), the PDO mappings — from
//! the SDO configuration seen in the log, an EDS/DCF given with `--eds`,
//! or the pre-defined connection set (SPEC §8.1) — and each drive's
//! CiA 402 state (SPEC §8.3). The library decodes; this file keeps the
//! state that ties frames together.

use std::borrow::Cow;
use std::collections::HashMap;

use motionwire::can::{Iface, Timestamp};
use motionwire::canopen::sdo::{SdoOutcome, SdoParty, SdoTransfer, TransferDirection};
use motionwire::canopen::{
    object_data_type, object_name, Cia402Command, Cia402State, DataType, MappingEntry,
    ModeOfOperation, NodeId, PdoCobId, PdoDirection, PdoLayout, PdoMapping, Signal, TypeLookup,
    Value,
};

use crate::args::Profile;
use crate::eds::NodeDescription;
use crate::profile::Profiles;
use crate::sdo::{Channel, SdoView};
use crate::summary::BusName;

/// The CiA 402 reading of one frame (SPEC §8.3 `cia402`): each part where
/// the frame tells it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Cia402View {
    /// The state, from a statusword (6041h).
    pub state: Option<Cia402State>,
    /// The command, from a controlword (6040h), its predecessor and the
    /// state.
    pub command: Option<Cia402Command>,
    /// The mode of operation (6060h) or its display (6061h).
    pub mode: Option<ModeOfOperation>,
}

impl Cia402View {
    fn is_empty(&self) -> bool {
        self.state.is_none() && self.command.is_none() && self.mode.is_none()
    }
}

/// A PDO's mapping as the decoder applies it: entries with the name and
/// data type of each (SPEC §8.2).
#[derive(Debug)]
pub struct ActiveMap {
    /// The node that owns the PDO.
    pub node: NodeId,
    /// TPDO or RPDO, seen from the node.
    pub direction: PdoDirection,
    /// The PDO number, 1..=512.
    pub number: u16,
    /// The mapping with each entry's offset and kind worked out.
    pub layout: PdoLayout,
    /// The name of each entry that is not a dummy, in mapping order
    /// (dummies carry no signal, SPEC §8.2).
    pub names: Vec<Cow<'static, str>>,
    /// Each name as a JSON key, escaped once, with the comma before it for
    /// all but the first: `"Statusword":`, `,"Position actual value":`.
    pub keys: Vec<Box<[u8]>>,
    /// The node is a CiA 402 drive, so the controlword and statusword are
    /// read (SPEC §8.3).
    pub drive: bool,
    /// Where the statusword (6041h, 16 bits) is mapped, if it is: the
    /// summary reads only it.
    statusword: Option<usize>,
}

/// The types of a mapping's signals, looked up in order: the unpacker asks
/// once per entry that is not a dummy, in mapping order.
struct InOrder<'a> {
    types: &'a [Option<DataType>],
    next: std::cell::Cell<usize>,
}

impl TypeLookup for InOrder<'_> {
    fn data_type(&self, _entry: MappingEntry) -> Option<DataType> {
        let i = self.next.get();
        self.next.set(i + 1);
        self.types.get(i).copied().flatten()
    }
}

/// One PDO frame with the mapping it is read with and its signals.
pub struct PdoView<'c> {
    /// The mapping in force for the frame's COB-ID.
    pub map: &'c ActiveMap,
    /// The frame's signals in mapping order (the i-th is named
    /// `map.names[i]`), or why the rest could not be read.
    pub signals: &'c [Result<Signal, motionwire::Error>],
    /// The CiA 402 reading, for a drive's PDO that carries its words.
    pub cia402: Option<Cia402View>,
}

/// One PDO's parameters as far as the decoder knows them (CiA 301
/// §7.5.2.35–§7.5.2.38).
#[derive(Debug, Clone, Copy)]
struct PdoParams {
    /// Sub 1 of the communication parameter, when known.
    cob_id: Option<PdoCobId>,
    /// Sub 0 of the mapping parameter, when known.
    count: Option<u8>,
    /// Subs 1..=64 of the mapping parameter.
    entries: [Option<u32>; 64],
    /// The COB-ID this PDO is active on, if any.
    active: Option<u16>,
}

impl Default for PdoParams {
    fn default() -> Self {
        PdoParams {
            cob_id: None,
            count: None,
            entries: [None; 64],
            active: None,
        }
    }
}

/// What the decoder knows of one node.
#[derive(Debug, Default)]
struct NodeState {
    sdo: Channel,
    pdos: HashMap<(bool, u16), PdoParams>,
    drive: bool,
    state: Option<Cia402State>,
    controlword: Option<u16>,
}

/// One interface.
struct BusState {
    name: BusName,
    nodes: Vec<Option<NodeState>>,
    /// COB-ID → index + 1 into `maps` (0: no mapping).
    by_cob: Box<[u16; 2048]>,
    maps: Vec<ActiveMap>,
    /// Node descriptions have been applied (on first sight of the bus).
    described: bool,
}

impl BusState {
    fn new(name: BusName) -> Self {
        BusState {
            name,
            nodes: (0..128).map(|_| None).collect(),
            by_cob: Box::new([0; 2048]),
            maps: Vec::new(),
            described: false,
        }
    }
}

/// The decoder's per-interface state.
pub struct Context {
    buses: Vec<BusState>,
    last: usize,
    /// Where the last frame's interface name lay in the input buffer
    /// (address, length): the same slice is the same bus without comparing
    /// names. Valid until [`Context::new_block`].
    last_name: (usize, usize),
    profiles: Profiles,
    descriptions: Vec<(NodeId, NodeDescription)>,
    /// The signals of the last PDO (reused: no allocation per frame).
    signals: Vec<Result<Signal, motionwire::Error>>,
}

impl Context {
    /// Start with the nodes' profiles and their `--eds` descriptions.
    pub fn new(profiles: Profiles, descriptions: Vec<(NodeId, NodeDescription)>) -> Self {
        Context {
            buses: Vec::new(),
            last: 0,
            last_name: (0, 0),
            profiles,
            descriptions,
            signals: Vec::with_capacity(64),
        }
    }

    /// The input buffer changes: interface names are no longer where they
    /// were.
    pub fn new_block(&mut self) {
        self.last_name = (0, 0);
    }

    #[inline]
    fn bus(&mut self, iface: Option<Iface<'_>>) -> usize {
        if let Some(Iface::Name(name)) = iface {
            let key = (name.as_ptr() as usize, name.len());
            if key == self.last_name {
                return self.last;
            }
            self.last_name = key;
        }
        let at = match self.buses.get(self.last) {
            Some(bus) if bus.name.is(iface) => self.last,
            _ => match self.buses.iter().position(|bus| bus.name.is(iface)) {
                Some(at) => at,
                None => {
                    self.buses.push(BusState::new(BusName::of(iface)));
                    self.buses.len() - 1
                }
            },
        };
        self.last = at;
        if !self.buses[at].described {
            self.buses[at].described = true;
            self.describe(at);
        }
        at
    }

    /// A new bus: every node given an EDS/DCF starts with its PDOs, and
    /// every node of the `akd` profile is a drive (SPEC §8.1, §8.3).
    fn describe(&mut self, at: usize) {
        let descriptions = std::mem::take(&mut self.descriptions);
        for (node, description) in &descriptions {
            let state = self.node(at, *node);
            state.drive |= description.is_drive();
            for pdo in description.pdos() {
                let params = state.pdos.entry((pdo.transmit, pdo.number)).or_default();
                params.cob_id = pdo.cob_id;
                params.count = Some(pdo.entries.len() as u8);
                for (slot, entry) in params.entries.iter_mut().zip(&pdo.entries) {
                    *slot = Some(*entry);
                }
            }
            let keys: Vec<_> = state.pdos.keys().copied().collect();
            for key in keys {
                self.activate(at, *node, key);
            }
        }
        self.descriptions = descriptions;
    }

    fn node(&mut self, at: usize, node: NodeId) -> &mut NodeState {
        let drive = self.profiles.of(Some(node)) == Profile::Akd;
        self.buses[at].nodes[usize::from(node.get())].get_or_insert_with(|| NodeState {
            drive,
            ..NodeState::default()
        })
    }

    /// Feed one SDO frame to its channel (SPEC §7.2); a completed transfer
    /// to or from a PDO parameter changes the mapping from here on
    /// (SPEC §8.1), an upload of 1000h can make the node a drive, and an
    /// expedited transfer of 6040h/6041h/6060h/6061h is read as CiA 402.
    pub fn sdo(
        &mut self,
        iface: Option<Iface<'_>>,
        node: NodeId,
        direction: SdoParty,
        data: &[u8],
        ts: Option<Timestamp>,
        line: u64,
    ) -> SdoView<'_> {
        let at = self.bus(iface);
        let learned = {
            let state = self.node(at, node);
            let view = state.sdo.feed(direction, data, ts, line);
            match view.ended {
                Some((transfer, data)) if transfer.outcome == SdoOutcome::Completed => {
                    Some((transfer, value_of(data)))
                }
                _ => None,
            }
        };
        let mut cia402 = None;
        if let Some((transfer, Some(value))) = learned {
            cia402 = self.learn(at, node, &transfer, value);
        }
        let state = self.buses[at].nodes[usize::from(node.get())]
            .as_mut()
            .expect("made above");
        let mut view = state.sdo.view();
        view.cia402 = cia402;
        view
    }

    /// What a completed transfer teaches (SPEC §8.1, §8.3).
    fn learn(
        &mut self,
        at: usize,
        node: NodeId,
        transfer: &SdoTransfer,
        value: u32,
    ) -> Option<Cia402View> {
        let m = transfer.multiplexer;
        let key = match m.index {
            0x1400..=0x15FF => Some(((false, m.index - 0x1400 + 1), true)),
            0x1600..=0x17FF => Some(((false, m.index - 0x1600 + 1), false)),
            0x1800..=0x19FF => Some(((true, m.index - 0x1800 + 1), true)),
            0x1A00..=0x1BFF => Some(((true, m.index - 0x1A00 + 1), false)),
            _ => None,
        };
        if let Some((key, communication)) = key {
            let params = self.node(at, node).pdos.entry(key).or_default();
            match (communication, m.sub_index) {
                (true, 1) => params.cob_id = Some(PdoCobId::from_u32(value)),
                (true, _) => return None,
                (false, 0) => params.count = Some(value as u8),
                (false, sub @ 1..=64) => params.entries[usize::from(sub) - 1] = Some(value),
                (false, _) => return None,
            }
            self.activate(at, node, key);
            return None;
        }
        let state = self.node(at, node);
        if m.index == 0x1000 && transfer.direction == TransferDirection::Upload {
            if motionwire::canopen::cia402::is_drive_device_type(value) {
                state.drive = true;
            }
            return None;
        }
        if !state.drive || m.sub_index != 0 {
            return None;
        }
        let mut view = Cia402View::default();
        match m.index {
            0x6041 => view.state = state.observe_statusword(value as u16),
            0x6040 => view.command = state.observe_controlword(value as u16),
            0x6060 | 0x6061 => view.mode = Some(ModeOfOperation::from_i8(value as u8 as i8)),
            _ => return None,
        }
        Some(view)
    }

    /// Put a PDO's mapping in force on its COB-ID, or take it out of force,
    /// after its parameters changed.
    fn activate(&mut self, at: usize, node: NodeId, key: (bool, u16)) {
        let profile = self.profiles.of(Some(node));
        let description = self
            .descriptions
            .iter()
            .find(|(n, _)| *n == node)
            .map(|(_, d)| d);
        let bus = &mut self.buses[at];
        let state = bus.nodes[usize::from(node.get())].as_mut().expect("made");
        let drive = state.drive;
        let params = state.pdos.get_mut(&key).expect("made");
        let (transmit, number) = key;
        let direction = if transmit {
            PdoDirection::Transmit
        } else {
            PdoDirection::Receive
        };
        // The COB-ID: as configured, else the pre-defined connection set
        // for PDOs 1–4 (CiA 301 §7.3.5).
        let cob_id = match params.cob_id {
            Some(cob) if !cob.is_valid() || cob.is_extended() => None,
            Some(cob) => cob.can_id().and_then(|id| id.standard_raw()),
            None => node.pdo_cob_id(direction, number),
        };
        let mapping = params.count.filter(|&n| n > 0).and_then(|n| {
            let raw: Option<Vec<u32>> = params.entries[..usize::from(n).min(64)]
                .iter()
                .copied()
                .collect();
            PdoMapping::from_u32s(&raw?).ok()
        });
        let old = params.active.take();
        if let Some(old) = old {
            bus.by_cob[usize::from(old)] = 0;
        }
        let (Some(cob_id), Some(mapping)) = (cob_id, mapping) else {
            return;
        };
        // A node whose device type says CiA 402 reads with the drive
        // profile's names and types, whatever `--profile` says (SPEC §8.2).
        let set = profile
            .object_set()
            .or(drive.then_some(motionwire::canopen::ObjectSet::Drive));
        let names: Vec<Cow<'static, str>> = mapping
            .entries()
            .iter()
            .filter(|e| !e.is_dummy())
            .map(|e| {
                if let Some(name) = description.and_then(|d| d.name(e.index(), e.sub_index())) {
                    return Cow::Owned(name.to_owned());
                }
                match object_name(e.index(), set) {
                    Some(name) if e.sub_index() == 0 => Cow::Borrowed(name),
                    Some(name) => Cow::Owned(format!("{name}.sub{}", e.sub_index())),
                    None => Cow::Owned(e.object().sub_notation().to_string()),
                }
            })
            .collect();
        let keys = names
            .iter()
            .enumerate()
            .map(|(i, name)| json_key(name, i > 0))
            .collect();
        let types: Vec<Option<DataType>> = mapping
            .entries()
            .iter()
            .filter(|e| !e.is_dummy())
            .map(|e| {
                description
                    .and_then(|d| d.data_type(e.index(), e.sub_index()))
                    .or_else(|| object_data_type(e.index(), e.sub_index(), set))
            })
            .collect();
        let layout = PdoLayout::new(
            &mapping,
            InOrder {
                types: &types,
                next: std::cell::Cell::new(0),
            },
        );
        let map = ActiveMap {
            node,
            direction,
            number,
            statusword: layout
                .position(0x6041, 0)
                .filter(|&i| layout_bits(&mapping, i) == 16),
            layout,
            names,
            keys,
            drive,
        };
        let slot = &mut bus.by_cob[usize::from(cob_id)];
        if *slot != 0 {
            bus.maps[usize::from(*slot) - 1] = map;
        } else {
            bus.maps.push(map);
            *slot = bus.maps.len() as u16;
        }
        params.active = Some(cob_id);
    }

    /// The mapping in force for a PDO frame on `cob_id`, its signals
    /// (when `signals` is asked for, or the node is a drive), and its
    /// CiA 402 reading for a drive (SPEC §8.2, §8.3).
    pub fn pdo(
        &mut self,
        iface: Option<Iface<'_>>,
        cob_id: u16,
        data: &[u8],
        signals: bool,
    ) -> Option<PdoView<'_>> {
        let at = self.bus(iface);
        let BusState {
            by_cob,
            maps,
            nodes,
            ..
        } = &mut self.buses[at];
        let slot = *by_cob.get(usize::from(cob_id))?;
        if slot == 0 {
            return None;
        }
        let map = &maps[usize::from(slot) - 1];
        let node = map.node;
        let state = nodes[usize::from(node.get())].get_or_insert_with(NodeState::default);
        let drive = map.drive || state.drive;
        self.signals.clear();
        if !signals {
            // The summary: only the statusword of a drive (SPEC §8.3's
            // timeline is observed from statuswords).
            let mut cia402 = None;
            if drive {
                let sw = map
                    .statusword
                    .and_then(|i| map.layout.read(i, data))
                    .and_then(|s| match s.ok()?.value {
                        Value::Unsigned(v) => Some(v as u16),
                        _ => None,
                    });
                if let Some(sw) = sw {
                    cia402 = Some(Cia402View {
                        state: state.observe_statusword(sw),
                        ..Cia402View::default()
                    });
                }
            }
            return Some(PdoView {
                map,
                signals: &self.signals,
                cia402,
            });
        }
        self.signals.extend(map.layout.unpack(data));
        let mut cia402 = None;
        if drive {
            let mut view = Cia402View::default();
            let (mut sw, mut cw) = (None, None);
            for signal in self.signals.iter().flatten() {
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
                        view.mode = Some(ModeOfOperation::from_i8(raw as i8));
                    }
                    _ => {}
                }
            }
            if let Some(sw) = sw {
                view.state = state.observe_statusword(sw);
            }
            if let Some(cw) = cw {
                view.command = state.observe_controlword(cw);
            }
            cia402 = (!view.is_empty()).then_some(view);
        }
        Some(PdoView {
            map,
            signals: &self.signals,
            cia402,
        })
    }

    /// Whether `node` on `iface` is a drive (SPEC §8.3).
    pub fn is_drive(&self, bus: &BusName, node: NodeId) -> bool {
        self.buses
            .iter()
            .find(|b| &b.name == bus)
            .and_then(|b| b.nodes[usize::from(node.get())].as_ref())
            .is_some_and(|n| n.drive)
            || self.profiles.of(Some(node)) == Profile::Akd
    }

    /// End of the input: every transfer left open (SPEC §7.2: reported in
    /// the summary only).
    pub fn finish(&mut self) -> Vec<(BusName, NodeId, SdoTransfer)> {
        let mut open = Vec::new();
        for bus in &mut self.buses {
            for (i, state) in bus.nodes.iter_mut().enumerate() {
                let Some(state) = state else { continue };
                if let Some(transfer) = state.sdo.finish() {
                    let node = NodeId::new(i as u8).expect("1..=127");
                    open.push((bus.name.clone(), node, transfer));
                }
            }
        }
        open
    }
}

impl NodeState {
    /// A statusword seen: the state it codes (CiA 402; SPEC §8.3).
    fn observe_statusword(&mut self, sw: u16) -> Option<Cia402State> {
        let state = Cia402State::from_statusword(sw);
        if state.is_some() {
            self.state = state;
        }
        state
    }

    /// A controlword seen: the command it gives in the current state, with
    /// the previous controlword for the fault-reset edge (SPEC §8.3).
    fn observe_controlword(&mut self, cw: u16) -> Option<Cia402Command> {
        let command = Cia402Command::from_controlword(cw, self.controlword, self.state);
        self.controlword = Some(cw);
        command
    }
}

/// The value of a completed expedited transfer's data, little-endian, for
/// the objects the decoder learns from (all of them 4 bytes or fewer).
fn value_of(data: &[u8]) -> Option<u32> {
    if data.is_empty() || data.len() > 4 {
        return None;
    }
    let mut bytes = [0; 4];
    bytes[..data.len()].copy_from_slice(data);
    Some(u32::from_le_bytes(bytes))
}

/// A signal's name as a JSON object key, escaped once (`"Statusword":`),
/// with the comma before it for every signal but the first.
fn json_key(name: &str, comma: bool) -> Box<[u8]> {
    let mut key = Vec::with_capacity(name.len() + 4);
    if comma {
        key.push(b',');
    }
    crate::json::string(&mut key, name).expect("writing to a Vec");
    key.push(b':');
    key.into_boxed_slice()
}

/// The bit length of the entry at `position` of a mapping.
fn layout_bits(mapping: &PdoMapping, position: usize) -> u8 {
    mapping.entries().get(position).map_or(0, |e| e.bits())
}
