//! PDO mappings as the decoder applies them: learned from the SDO
//! configuration in the log, from a node's EDS/DCF, or the pre-defined
//! connection set (docs/canopen.md#pdo-mappings), each with its signals' names
//! and types (docs/canopen.md#signals).

use std::borrow::Cow;
use std::cell::Cell;
use std::fmt;

use crate::can::CanId;
use crate::canopen::{
    object_data_type, object_name, DataType, MappingEntry, NodeId, PdoCobId, PdoDirection,
    PdoLayout, PdoMapping, Signal, TypeLookup,
};
use crate::logs::Position;
use crate::CodecError;

/// Where a PDO's parameters come from, as the decoder learns them
/// (docs/canopen.md#pdo-mappings, the three sources in their order).
///
/// [`PdoMap::origin`] says what put a mapping in force as it is (an SDO
/// transfer or the EDS/DCF: only those give a mapping);
/// [`PdoMap::cob_id_origin`] where its COB-ID comes from (any of the three).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PdoOrigin {
    /// 1: a completed SDO transfer in the log, to or from the PDO's
    /// communication or mapping parameter, changed the PDO from that frame on.
    Sdo {
        /// Where the log has the frame that completed the transfer (its line
        /// or record, docs/formats.md#positions: the `line` of the
        /// record that carries the `transfer`, docs/output.md#transfer).
        position: Position,
    },
    /// 2: the node's EDS or DCF (`--eds NODE=FILE`,
    /// [`DecoderConfig::eds`](super::DecoderConfig::eds)), which sets the
    /// node's PDOs at the start of each bus.
    Eds,
    /// 3: the pre-defined connection set, for the COB-ID of PDOs 1–4 when no
    /// COB-ID is known (TPDO1–4 at 0x180/0x280/0x380/0x480 + node, RPDO1–4
    /// at 0x200/0x300/0x400/0x500 + node). It gives only the identifier.
    PredefinedConnectionSet,
}

impl fmt::Display for PdoOrigin {
    /// Write the source as a person reads it: `SDO transfer at line 102`,
    /// `EDS`, `pre-defined connection set`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PdoOrigin::Sdo { position } => {
                write!(f, "SDO transfer at {} {position}", position.unit())
            }
            PdoOrigin::Eds => f.write_str("EDS"),
            PdoOrigin::PredefinedConnectionSet => f.write_str("pre-defined connection set"),
        }
    }
}

/// A PDO's mapping as the decoder applies it to the frames on its COB-ID:
/// the owner, the PDO, its COB-ID, where it comes from, its layout and the
/// name of each signal (docs/canopen.md#pdo-mappings,
/// docs/canopen.md#signals). [`Decoder::mappings`](super::Decoder::mappings)
/// lists those in force.
#[derive(Debug)]
pub struct PdoMap {
    id: u32,
    node: NodeId,
    direction: PdoDirection,
    number: u16,
    cob_id: PdoCobId,
    can_id: CanId,
    origin: PdoOrigin,
    cob_id_origin: PdoOrigin,
    layout: PdoLayout,
    names: Vec<Cow<'static, str>>,
    /// Each name as a JSON object key, escaped once, with the comma before
    /// it: `,"Statusword":`, `,"Position actual value":` (the record's
    /// `signals`, docs/output.md#pdo).
    pub(crate) keys: Vec<super::json::Key>,
    drive: bool,
    /// Where the statusword (6041h, 16 bits) is mapped, if it is.
    statusword: Option<usize>,
}

impl PdoMap {
    /// Return a number that no other mapping of the decoder's session has:
    /// a renderer may keep what it works out once per mapping (e.g. the
    /// signal names escaped for its output) under it.
    #[must_use]
    pub fn id(&self) -> u32 {
        self.id
    }

    /// Return the node that owns the PDO (which may differ from the node
    /// the COB-ID names, when the log moved the PDO).
    #[must_use]
    pub fn node(&self) -> NodeId {
        self.node
    }

    /// Return whether the PDO is a TPDO or an RPDO, seen from its node.
    #[must_use]
    pub fn direction(&self) -> PdoDirection {
        self.direction
    }

    /// Return the PDO number, 1..=512.
    #[must_use]
    pub fn number(&self) -> u16 {
        self.number
    }

    /// Return the COB-ID entry in force (sub 1 of the communication
    /// parameter, docs/canopen.md#pdo-mappings): as configured, with its
    /// flags, or the pre-defined connection set's identifier with no flag
    /// set ([`cob_id_origin`](Self::cob_id_origin) says which). It is valid
    /// and 11-bit: a PDO is in force on no other.
    #[must_use]
    pub fn cob_id(&self) -> PdoCobId {
        self.cob_id
    }

    /// Return the identifier of the frames the mapping reads: the
    /// [`cob_id`](Self::cob_id)'s, 11-bit.
    #[must_use]
    pub fn can_id(&self) -> CanId {
        self.can_id
    }

    /// Return what put the mapping in force as it is: the completed SDO
    /// transfer that changed one of the PDO's parameters last, or the node's
    /// EDS/DCF at the start of the bus (docs/canopen.md#pdo-mappings; never
    /// [`PdoOrigin::PredefinedConnectionSet`], which gives no mapping).
    #[must_use]
    pub fn origin(&self) -> PdoOrigin {
        self.origin
    }

    /// Return where the COB-ID comes from: the SDO transfer that set it, the
    /// EDS/DCF, or the pre-defined connection set when neither gave one
    /// (docs/canopen.md#pdo-mappings).
    #[must_use]
    pub fn cob_id_origin(&self) -> PdoOrigin {
        self.cob_id_origin
    }

    /// Return the mapping with each entry's offset and kind worked out.
    #[must_use]
    pub fn layout(&self) -> &PdoLayout {
        &self.layout
    }

    /// Return the name of each signal, in mapping order, dummies left out
    /// (docs/canopen.md#signals: the EDS's `ParameterName`, else the profile's
    /// name, else `6041sub0`).
    #[must_use]
    pub fn names(&self) -> &[Cow<'static, str>] {
        &self.names
    }

    /// Return whether the node is a CiA 402 drive, whose controlword and
    /// statusword are read (docs/canopen.md#cia402).
    #[must_use]
    pub fn is_drive(&self) -> bool {
        self.drive
    }

    /// Return where the statusword is mapped, if it is.
    pub(crate) fn statusword(&self) -> Option<usize> {
        self.statusword
    }
}

/// A PDO frame read with the mapping in force for its COB-ID (`signals`
/// in docs/output.md#pdo).
///
/// `Display` writes the PDO and its signals as a person reads them:
/// `TPDO1 Statusword=567 Position actual value=100000`, with `  error: …`
/// where the payload ends before the mapping does.
#[derive(Debug, Clone, Copy)]
pub struct PdoReading<'d> {
    /// The mapping in force.
    pub map: &'d PdoMap,
    /// The frame's signals in mapping order (the i-th is named
    /// `map.names()[i]`), and why the rest could not be read
    /// (docs/canopen.md#signals: a PDO shorter than its mapping). Empty when
    /// the decoder does not unpack signals
    /// ([`DecoderConfig::signals`](super::DecoderConfig::signals)).
    pub signals: &'d [Result<Signal, CodecError>],
}

impl<'d> PdoReading<'d> {
    /// Return the signals that could be read, each with its name.
    pub fn named(&self) -> impl Iterator<Item = (&'d str, &'d Signal)> + '_ {
        let names = self.map.names();
        self.signals
            .iter()
            .enumerate()
            .filter_map(move |(i, s)| Some((names.get(i)?.as_ref(), s.as_ref().ok()?)))
    }

    /// Return why the signals end before the mapping does, if they do.
    #[must_use]
    pub fn error(&self) -> Option<&'d CodecError> {
        self.signals.iter().find_map(|s| s.as_ref().err())
    }
}

impl fmt::Display for PdoReading<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let map = self.map;
        write!(f, "{}{}", map.direction, map.number)?;
        for (i, signal) in self.signals.iter().enumerate() {
            match signal {
                Ok(signal) => {
                    let name = map.names.get(i).map_or("", |n| n.as_ref());
                    write!(f, " {name}={}", signal.value)?;
                }
                Err(e) => write!(f, "  error: {e}")?,
            }
        }
        Ok(())
    }
}

/// One PDO's parameters as far as the decoder knows them (CiA 301
/// §7.5.2.35–§7.5.2.38).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PdoParams {
    /// Sub 1 of the communication parameter and where it comes from, when
    /// known.
    pub(crate) cob_id: Option<(PdoCobId, PdoOrigin)>,
    /// Sub 0 of the mapping parameter, when known.
    pub(crate) count: Option<u8>,
    /// Subs 1..=64 of the mapping parameter.
    pub(crate) entries: [Option<u32>; 64],
    /// The COB-ID this PDO is active on, if any.
    pub(crate) active: Option<u16>,
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

/// Which PDO parameter an object index holds, if it holds one: the PDO
/// (`true` for a TPDO, its number) and whether it is the communication
/// (else the mapping) parameter (CiA 301 §7.5.2.35–§7.5.2.38).
pub(crate) fn pdo_parameter(index: u16) -> Option<((bool, u16), bool)> {
    match index {
        0x1400..=0x15FF => Some(((false, index - 0x1400 + 1), true)),
        0x1600..=0x17FF => Some(((false, index - 0x1600 + 1), false)),
        0x1800..=0x19FF => Some(((true, index - 0x1800 + 1), true)),
        0x1A00..=0x1BFF => Some(((true, index - 0x1A00 + 1), false)),
        _ => None,
    }
}

/// Where names and data types come from for a node: its EDS/DCF first,
/// then the profile's objects (docs/canopen.md#signals).
pub(crate) trait Names {
    fn name(&self, index: u16, sub: u8) -> Option<&str>;
    fn data_type(&self, index: u16, sub: u8) -> Option<DataType>;
}

/// The COB-ID a PDO is active on, as configured or pre-defined, and its
/// mapping, or `None` when it is not in force (CiA 301 §7.3.5, §7.5.2.35).
pub(crate) struct InForce {
    /// The COB-ID entry.
    pub(crate) cob_id: PdoCobId,
    /// Its identifier, 11-bit.
    pub(crate) can_id: CanId,
    /// Where the COB-ID comes from.
    pub(crate) cob_id_origin: PdoOrigin,
    /// The mapping.
    pub(crate) mapping: PdoMapping,
}

impl InForce {
    /// The identifier as an index into the decoder's table of COB-IDs.
    pub(crate) fn raw(&self) -> u16 {
        self.can_id.raw() as u16
    }
}

/// The COB-ID a PDO is active on and its mapping, or `None` when it is
/// not in force (CiA 301 §7.3.5, §7.5.2.35).
pub(crate) fn in_force(
    params: &PdoParams,
    node: NodeId,
    direction: PdoDirection,
    number: u16,
) -> Option<InForce> {
    // The COB-ID: as configured, else the pre-defined connection set for
    // PDOs 1–4 (CiA 301 §7.3.5).
    let cob_id = match params.cob_id {
        Some((cob, _)) if !cob.is_valid() || cob.is_extended() => None,
        Some((cob, origin)) => cob
            .can_id()
            .filter(|id| id.standard_raw().is_some())
            .map(|id| (cob, id, origin)),
        None => node.pdo_cob_id(direction, number).and_then(|raw| {
            let id = CanId::standard(u32::from(raw))?;
            Some((
                PdoCobId::from_u32(u32::from(raw)),
                id,
                PdoOrigin::PredefinedConnectionSet,
            ))
        }),
    };
    let mapping = params.count.filter(|&n| n > 0).and_then(|n| {
        let raw: Option<Vec<u32>> = params.entries[..usize::from(n).min(64)]
            .iter()
            .copied()
            .collect();
        PdoMapping::from_u32s(&raw?).ok()
    });
    let (cob_id, can_id, cob_id_origin) = cob_id?;
    Some(InForce {
        cob_id,
        can_id,
        cob_id_origin,
        mapping: mapping?,
    })
}

/// Build the map of a mapping in force: names and types from the node's
/// description, else the object set's (docs/canopen.md#signals).
#[allow(clippy::too_many_arguments)]
pub(crate) fn build_map(
    id: u32,
    node: NodeId,
    direction: PdoDirection,
    number: u16,
    force: &InForce,
    origin: PdoOrigin,
    description: Option<&dyn Names>,
    set: Option<crate::canopen::ObjectSet>,
    drive: bool,
) -> PdoMap {
    let mapping = &force.mapping;
    let signals = || mapping.entries().iter().filter(|e| !e.is_dummy());
    let names: Vec<Cow<'static, str>> = signals()
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
    let types: Vec<Option<DataType>> = signals()
        .map(|e| {
            description
                .and_then(|d| d.data_type(e.index(), e.sub_index()))
                .or_else(|| object_data_type(e.index(), e.sub_index(), set))
        })
        .collect();
    let layout = PdoLayout::new(
        mapping,
        InOrder {
            types: &types,
            next: Cell::new(0),
        },
    );
    let statusword = layout
        .position(0x6041, 0)
        .filter(|&i| mapping.entries().get(i).map_or(0, |e| e.bits()) == 16);
    let keys = names
        .iter()
        .map(|name| super::json::Key::new(name))
        .collect();
    PdoMap {
        id,
        node,
        direction,
        number,
        cob_id: force.cob_id,
        can_id: force.can_id,
        origin,
        cob_id_origin: force.cob_id_origin,
        layout,
        names,
        keys,
        drive,
        statusword,
    }
}

/// The types of a mapping's signals, looked up in order: the layout asks
/// once per entry that is not a dummy, in mapping order.
struct InOrder<'a> {
    types: &'a [Option<DataType>],
    next: Cell<usize>,
}

impl TypeLookup for InOrder<'_> {
    fn data_type(&self, _entry: MappingEntry) -> Option<DataType> {
        let i = self.next.get();
        self.next.set(i + 1);
        self.types.get(i).copied().flatten()
    }
}
