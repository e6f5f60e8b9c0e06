//! A slave's process image as a capture's start-up or a configuration
//! file describes it, and the cutting of a cyclic datagram into each
//! slave's outputs and inputs (docs/ethercat.md#process-data).
//!
//! The FMMUs map logical ranges onto the slave's memory; the sync managers
//! there say which bytes are outputs and which inputs, and carry the PDOs
//! their assignment object (0x1C10 + n) lists; each PDO's mapping object
//! gives its entries. The PDO assignment and mappings are learned from the
//! CoE SDO transfers the capture shows ([`CoeObjects`]).

use std::borrow::Cow;

use crate::canopen::{
    object_data_type, object_name, DataType, MappingEntry, ObjectSet, PdoLayout, PdoMapping, Signal,
};
use crate::ethercat::{Command, Fmmu, SyncManager, SyncManagerMode};
use crate::CodecError;

use super::coe::{CoeTransfer, COE_DATA_KEPT};
use super::config::SlaveConfig;
use super::problem::ImageError;

/// The FMMUs and sync managers a slave has at most (ESC datasheet).
pub(super) const UNITS: usize = 16;
/// The entries a mapping object holds at most (sub-indices 1–255; the
/// decoder keeps the first 64 a PDO mapping can hold).
const MAX_ENTRIES: usize = 64;
/// The dummy entry a gap is read as (index 0001h, which reading skips).
const GAP: u16 = 0x0001;

/// Whether `index` is an object the process image is learned from: the
/// PDO assignment of a sync manager (0x1C10–0x1C2F) or a PDO mapping
/// (0x1600–0x17FF receive, 0x1A00–0x1BFF transmit).
pub(super) const fn is_pdo_object(index: u16) -> bool {
    matches!(index, 0x1C10..=0x1C2F | 0x1600..=0x17FF | 0x1A00..=0x1BFF)
}

/// The PDO objects of one slave as its CoE SDO transfers wrote or read
/// them: sub-index 0 (the count) and the entries.
#[derive(Debug, Clone, Default)]
pub(super) struct CoeObjects {
    /// 0x1C10 + n: count and PDO indices.
    assignment: [Option<(u8, Vec<u16>)>; UNITS * 2],
    /// Mapping objects: index, count and raw entries.
    mappings: Vec<(u16, u8, Vec<u32>)>,
    /// A transfer that announced more than a PDO object holds, not said
    /// yet.
    pub(super) oversized: Option<ImageError>,
}

impl CoeObjects {
    /// Keep what a completed transfer of a PDO object wrote or read
    /// (`data`, as kept by the channel); note one that carried more than
    /// such an object holds. Return whether an object changed.
    pub(super) fn transfer(&mut self, transfer: &CoeTransfer, data: &[u8]) -> bool {
        if !is_pdo_object(transfer.index) {
            return false;
        }
        if transfer.size > COE_DATA_KEPT {
            self.oversized = Some(ImageError::SdoSizePastObject {
                index: transfer.index,
                sub_index: transfer.sub_index,
                size: u32::try_from(transfer.size).unwrap_or(u32::MAX),
            });
        }
        self.store(
            transfer.index,
            transfer.sub_index,
            transfer.complete_access,
            data,
        )
    }

    /// Keep what a completed transfer wrote or read.
    fn store(&mut self, index: u16, sub_index: u8, complete_access: bool, data: &[u8]) -> bool {
        let assignment = matches!(index, 0x1C10..=0x1C2F);
        let width = if assignment { 2 } else { 4 };
        let word = |bytes: &[u8]| -> u32 {
            let mut b = [0u8; 4];
            b[..bytes.len().min(4)].copy_from_slice(&bytes[..bytes.len().min(4)]);
            u32::from_le_bytes(b)
        };
        // The values by sub-index: (sub-index, value).
        let mut count = None;
        let mut entries: Vec<(usize, u32)> = Vec::new();
        if complete_access {
            // Sub-index 0 takes 16 bits (a byte and a padding byte), the
            // entries follow (ETG.1000.6 §5.6.2.1.1: complete access).
            let mut rest = data;
            let mut sub = usize::from(sub_index);
            if sub == 0 {
                let Some(&n) = rest.first() else {
                    return false;
                };
                count = Some(n);
                rest = rest.get(2..).unwrap_or(&[]);
                sub = 1;
            }
            for chunk in rest.chunks_exact(width) {
                if sub > MAX_ENTRIES {
                    break;
                }
                entries.push((sub, word(chunk)));
                sub += 1;
            }
        } else if sub_index == 0 {
            let Some(&n) = data.first() else {
                return false;
            };
            count = Some(n);
        } else if usize::from(sub_index) <= MAX_ENTRIES && data.len() >= width {
            entries.push((usize::from(sub_index), word(&data[..width])));
        } else {
            return false;
        }
        if assignment {
            let slot = &mut self.assignment[usize::from(index - 0x1C10)];
            let (n, pdos) = slot.get_or_insert_with(|| (0, Vec::new()));
            for (sub, value) in entries {
                if pdos.len() < sub {
                    pdos.resize(sub, 0);
                }
                pdos[sub - 1] = value as u16;
            }
            if let Some(c) = count {
                *n = c;
            }
        } else {
            let at = match self.mappings.iter().position(|m| m.0 == index) {
                Some(at) => at,
                None => {
                    self.mappings.push((index, 0, Vec::new()));
                    self.mappings.len() - 1
                }
            };
            let (_, n, raw) = &mut self.mappings[at];
            for (sub, value) in entries {
                if raw.len() < sub {
                    raw.resize(sub, 0);
                }
                raw[sub - 1] = value;
            }
            if let Some(c) = count {
                *n = c;
            }
        }
        true
    }

    /// The PDOs assigned to sync manager `sm`, `None` when the capture
    /// did not show its assignment.
    fn assigned(&self, sm: usize) -> Option<&[u16]> {
        let (n, pdos) = self.assignment.get(sm)?.as_ref()?;
        Some(&pdos[..usize::from(*n).min(pdos.len())])
    }

    /// The entries of mapping object `index`, `None` when not shown.
    fn mapping(&self, index: u16) -> Option<&[u32]> {
        let (_, n, raw) = self.mappings.iter().find(|m| m.0 == index)?;
        Some(&raw[..usize::from(*n).min(raw.len())])
    }
}

/// One byte area of the image: a sync manager's (or, where none is known
/// there, an FMMU's own range).
#[derive(Debug, Clone)]
struct Segment {
    output: bool,
    /// The sync manager, where one holds it.
    sm: Option<usize>,
    physical: u16,
    len: u16,
    /// Where it starts in the outputs or the inputs image.
    offset: usize,
}

/// A logical range an FMMU maps onto a segment.
#[derive(Debug, Clone, Copy)]
struct Area {
    logical: u32,
    len: u32,
    segment: usize,
    /// Where the range starts in its segment.
    within: usize,
}

/// The CiA 402 objects a drive's state is read from (CiA 402-2): the
/// controlword, the statusword, the mode of operation and its display.
pub(super) const CIA402_OBJECTS: [u16; 4] = [0x6040, 0x6041, 0x6060, 0x6061];

/// A PDO placed in the image.
#[derive(Debug, Clone)]
struct Piece {
    /// Its first bit in the image.
    bit: usize,
    layout: PdoLayout,
    names: Vec<Cow<'static, str>>,
}

/// How one slave's image is cut from cyclic datagrams, worked out once
/// per configuration.
#[derive(Debug, Clone, Default)]
pub(super) struct Plan {
    segments: Vec<Segment>,
    areas: Vec<Area>,
    /// FMMUs of bits (a sync manager's status, a terminal packed into
    /// part of a byte) read and written: counted in the working counter,
    /// not part of the image.
    bit_reads: Vec<(u32, u32)>,
    bit_writes: Vec<(u32, u32)>,
    outputs_len: usize,
    inputs_len: usize,
    outputs: Vec<Piece>,
    inputs: Vec<Piece>,
    /// Some PDO maps one of [`CIA402_OBJECTS`].
    cia402: bool,
    /// PDOs that do not fit in their sync manager.
    pub(super) too_long: Vec<ImageError>,
}

impl Plan {
    /// Work out the plan of a slave from its configuration: what the
    /// capture's start-up wrote (`fmmus`, `sync_managers`, `coe`), then
    /// the configurations `given`, the first that has an object wins (an
    /// ENI's, then the SII's).
    pub(super) fn new(
        fmmus: &[Option<Fmmu>; UNITS],
        sync_managers: &[Option<SyncManager>; UNITS],
        coe: &CoeObjects,
        given: &[&SlaveConfig],
    ) -> Self {
        let mut plan = Plan::default();
        for fmmu in fmmus.iter().flatten().filter(|f| f.active) {
            let Some((start, end)) = fmmu.logical_range() else {
                continue;
            };
            if !fmmu.whole_bytes() {
                if fmmu.reads() {
                    plan.bit_reads.push((start, end));
                }
                if fmmu.writes() {
                    plan.bit_writes.push((start, end));
                }
                continue;
            }
            let sm = sync_managers.iter().enumerate().find_map(|(n, sm)| {
                let sm = (*sm)?;
                (sm.mode() == SyncManagerMode::Buffered && sm.len > 0 && sm.holds(fmmu.physical))
                    .then_some((n, sm))
            });
            let (segment, within) = match sm {
                Some((n, sm)) => {
                    let at = match plan.segments.iter().position(|s| s.sm == Some(n)) {
                        Some(at) => at,
                        None => {
                            plan.segments.push(Segment {
                                output: sm.written_by_master(),
                                sm: Some(n),
                                physical: sm.start,
                                len: sm.len,
                                offset: 0,
                            });
                            plan.segments.len() - 1
                        }
                    };
                    (at, usize::from(fmmu.physical - sm.start))
                }
                None => {
                    plan.segments.push(Segment {
                        output: fmmu.writes() && !fmmu.reads(),
                        sm: None,
                        physical: fmmu.physical,
                        len: fmmu.len,
                        offset: 0,
                    });
                    (plan.segments.len() - 1, 0)
                }
            };
            let room = usize::from(plan.segments[segment].len).saturating_sub(within);
            plan.areas.push(Area {
                logical: start,
                len: (end - start).min(room as u32),
                segment,
                within,
            });
        }
        // A slave whose PDOs map the statusword is a CiA 402 drive: its
        // objects are named and typed by the drive profile.
        let set = maps_statusword(coe, given).then_some(ObjectSet::Drive);
        // Segments in sync-manager order, outputs and inputs apart.
        let mut order: Vec<usize> = (0..plan.segments.len()).collect();
        order.sort_by_key(|&i| {
            (
                plan.segments[i].sm.unwrap_or(UNITS),
                plan.segments[i].physical,
            )
        });
        for i in order {
            let segment = &mut plan.segments[i];
            let len = usize::from(segment.len);
            let image = if segment.output {
                &mut plan.outputs_len
            } else {
                &mut plan.inputs_len
            };
            segment.offset = *image;
            *image += len;
            let Some(sm) = segment.sm else { continue };
            let pdos = pdos_of(sm, coe, given);
            let pieces = if segment.output {
                &mut plan.outputs
            } else {
                &mut plan.inputs
            };
            let mut bit = segment.offset * 8;
            let end = (segment.offset + len) * 8;
            for (index, entries) in pdos {
                let mut mapping = PdoMapping::new();
                let mut names = Vec::new();
                let mut types = Vec::new();
                for (entry, name, data_type) in entries {
                    // A gap (index 0, EtherCAT's padding) is a dummy entry
                    // of its length: skipped when read.
                    let entry = if entry.index() == 0 {
                        MappingEntry::new(GAP, 0, entry.bits())
                    } else {
                        entry
                    };
                    if mapping.push(entry).is_err() {
                        break;
                    }
                    if !entry.is_dummy() {
                        names.push(name.unwrap_or_else(|| entry_name(entry, set)));
                    }
                    plan.cia402 |= CIA402_OBJECTS.contains(&entry.index());
                    types.push((entry, data_type));
                }
                let bits = usize::from(mapping.bit_len());
                if bit + bits > end {
                    // A mapping longer than the sync manager: not read
                    // (docs/ethercat.md#process-data).
                    plan.too_long.push(ImageError::MappingPastSyncManager {
                        sm: sm as u8,
                        pdo: index,
                        end_bit: (bit + bits - segment.offset * 8) as u32,
                        len: segment.len,
                    });
                    break;
                }
                let lookup = |e: MappingEntry| {
                    types
                        .iter()
                        .find(|(t, _)| *t == e)
                        .and_then(|(_, d)| *d)
                        .or_else(|| object_data_type(e.index(), e.sub_index(), set))
                };
                pieces.push(Piece {
                    bit,
                    layout: PdoLayout::new(&mapping, lookup),
                    names,
                });
                bit += bits;
            }
        }
        plan
    }

    /// Return the first logical range both plans write, if any.
    pub(super) fn output_overlap(&self, other: &Plan) -> Option<(u32, u32)> {
        let outputs = |plan: &'_ Plan| -> Vec<(u32, u32)> {
            plan.areas
                .iter()
                .filter(|a| plan.segments[a.segment].output)
                .map(|a| (a.logical, a.logical + a.len))
                .collect()
        };
        let theirs = outputs(other);
        outputs(self).into_iter().find_map(|(s, e)| {
            theirs.iter().find_map(|&(os, oe)| {
                let (start, end) = (s.max(os), e.min(oe));
                (start < end).then_some((start, end))
            })
        })
    }

    /// Return whether the slave has any FMMU in the range.
    pub(super) fn touches(&self, start: u32, end: u32) -> bool {
        self.areas
            .iter()
            .any(|a| a.logical < end && start < a.logical + a.len)
            || self
                .bit_reads
                .iter()
                .chain(&self.bit_writes)
                .any(|&(s, e)| s < end && start < e)
    }

    /// The slave's share of a datagram's working counter over `[start,
    /// end)` (ETG.1000.4 §5.4.1.2): a read FMMU there adds 1, a write
    /// FMMU 1 (LWR) or 2 (LRW), once per slave.
    pub(super) fn share(&self, command: Command, start: u32, end: u32) -> u16 {
        let over = |a: &Area| a.logical < end && start < a.logical + a.len;
        let mut reads = self.bit_reads.iter().any(|&(s, e)| s < end && start < e);
        let mut writes = self.bit_writes.iter().any(|&(s, e)| s < end && start < e);
        for area in self.areas.iter().filter(|a| over(a)) {
            if self.segments[area.segment].output {
                writes = true;
            } else {
                reads = true;
            }
        }
        match command {
            Command::Lrw => u16::from(reads) + 2 * u16::from(writes),
            Command::Lrd => u16::from(reads),
            Command::Lwr => u16::from(writes),
            _ => 0,
        }
    }

    /// Copy the slave's bytes of a datagram at `logical` into its images:
    /// outputs from `sent`, inputs from `returned`. Return how many bytes
    /// of each image the datagram held.
    pub(super) fn cut(
        &self,
        logical: u32,
        sent: &[u8],
        returned: &[u8],
        outputs: &mut Vec<u8>,
        inputs: &mut Vec<u8>,
    ) -> (usize, usize) {
        outputs.resize(self.outputs_len, 0);
        inputs.resize(self.inputs_len, 0);
        let end = logical.saturating_add(returned.len() as u32);
        let mut held = (0, 0);
        for area in &self.areas {
            let from = area.logical.max(logical);
            let to = (area.logical + area.len).min(end);
            if from >= to {
                continue;
            }
            let segment = &self.segments[area.segment];
            let at = segment.offset + area.within + (from - area.logical) as usize;
            let n = (to - from) as usize;
            let source = (from - logical) as usize;
            let (image, bytes, count) = if segment.output {
                (&mut *outputs, sent, &mut held.0)
            } else {
                (&mut *inputs, returned, &mut held.1)
            };
            if let (Some(dst), Some(src)) =
                (image.get_mut(at..at + n), bytes.get(source..source + n))
            {
                dst.copy_from_slice(src);
                *count += n;
            }
        }
        held
    }

    /// The images' lengths: outputs, inputs.
    pub(super) const fn lens(&self) -> (usize, usize) {
        (self.outputs_len, self.inputs_len)
    }

    /// Return whether any PDO is known.
    pub(super) fn has_signals(&self) -> bool {
        !self.outputs.is_empty() || !self.inputs.is_empty()
    }

    /// Return whether some PDO maps one of [`CIA402_OBJECTS`]: the
    /// slave's drive state can be read from its process data.
    pub(super) const fn maps_cia402(&self) -> bool {
        self.cia402
    }

    /// Call `f` with each signal of an image (`output` picks which) and
    /// its name, in mapping order.
    pub(super) fn for_each_signal(
        &self,
        output: bool,
        image: &[u8],
        mut f: impl FnMut(&str, Result<Signal, CodecError>),
    ) {
        let pieces = if output { &self.outputs } else { &self.inputs };
        for piece in pieces {
            for (name, signal) in piece
                .names
                .iter()
                .zip(piece.layout.unpack_at(image, piece.bit))
            {
                f(name, signal.map_err(CodecError::from));
            }
        }
    }
}

/// An entry's name: the object table's (the drive profile's for a
/// drive), else `0x6041:00`.
fn entry_name(entry: MappingEntry, set: Option<ObjectSet>) -> Cow<'static, str> {
    match object_name(entry.index(), set) {
        Some(name) if entry.sub_index() == 0 => Cow::Borrowed(name),
        Some(name) => Cow::Owned(format!("{name}.{:02X}", entry.sub_index())),
        None => Cow::Owned(format!("0x{:04X}:{:02X}", entry.index(), entry.sub_index())),
    }
}

/// Whether any PDO the slave's transfers or configurations show maps the
/// statusword 6041h.
fn maps_statusword(coe: &CoeObjects, given: &[&SlaveConfig]) -> bool {
    coe.mappings
        .iter()
        .any(|(_, _, raw)| raw.iter().any(|&r| r >> 16 == 0x6041))
        || given.iter().any(|g| {
            g.pdos
                .iter()
                .any(|p| p.entries.iter().any(|e| e.entry.index() == 0x6041))
        })
}

/// An entry with the name and type a configuration gives it.
type Entry = (MappingEntry, Option<Cow<'static, str>>, Option<DataType>);

/// The PDOs of sync manager `sm`, in order, each with its entries: from
/// the capture's CoE transfers first, then the configurations in their
/// order (a file's, then the SII's), object by object. An entry takes its
/// name and type from the first configuration that has it in the same
/// PDO with a name or a type.
fn pdos_of(sm: usize, coe: &CoeObjects, given: &[&SlaveConfig]) -> Vec<(u16, Vec<Entry>)> {
    let pdo =
        |config: &&SlaveConfig, index: u16| config.pdos.iter().find(|p| p.index == index).cloned();
    // An entry's name or type where its own source gives none: the first
    // configuration that has the same entry in the same PDO with one.
    let describe = |index: u16, (entry, name, data_type): Entry| -> Entry {
        let same = |config: &&SlaveConfig| {
            let pdo = config.pdos.iter().find(|p| p.index == index)?;
            pdo.entries.iter().find(|e| e.entry == entry).cloned()
        };
        let name = name.or_else(|| {
            given
                .iter()
                .find_map(|g| same(g).and_then(|e| e.name))
                .map(Cow::Owned)
        });
        let data_type =
            data_type.or_else(|| given.iter().find_map(|g| same(g).and_then(|e| e.data_type)));
        (entry, name, data_type)
    };
    let assigned: Vec<u16> = match coe.assigned(sm) {
        Some(pdos) => pdos.to_vec(),
        None => match given.iter().find_map(|g| {
            g.assignment
                .iter()
                .find(|(n, _)| usize::from(*n) == sm)
                .map(|(_, pdos)| pdos.clone())
        }) {
            Some(pdos) => pdos,
            None => return Vec::new(),
        },
    };
    assigned
        .into_iter()
        .filter_map(|index| {
            let entries: Vec<Entry> = match coe.mapping(index) {
                Some(raw) => raw
                    .iter()
                    .map(|&r| (MappingEntry::from_u32(r), None, None))
                    .collect(),
                None => given
                    .iter()
                    .find_map(|g| pdo(g, index))?
                    .entries
                    .into_iter()
                    .map(|e| (e.entry, e.name.map(Cow::Owned), e.data_type))
                    .collect(),
            };
            Some((
                index,
                entries.into_iter().map(|e| describe(index, e)).collect(),
            ))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decoder::ethercat::coe::CoeChannel;
    use crate::ethercat::CoeSdo;

    /// A slave's channel and its PDO objects.
    #[derive(Default)]
    struct Coe {
        channel: CoeChannel,
        objects: CoeObjects,
    }

    impl core::ops::Deref for Coe {
        type Target = CoeObjects;
        fn deref(&self) -> &CoeObjects {
            &self.objects
        }
    }

    /// Feed one SDO message (command byte onwards); return whether a PDO
    /// object changed.
    fn feed(coe: &mut Coe, request: bool, bytes: &[u8]) -> bool {
        let step = coe
            .channel
            .message(request, &CoeSdo::parse(bytes).unwrap(), None);
        match step.ended {
            Some(transfer) => coe.objects.transfer(&transfer, &transfer.data),
            None => false,
        }
    }

    /// An expedited download of `value` (`len` bytes) to index.sub, and
    /// its response.
    fn expedited(coe: &mut Coe, index: u16, sub: u8, value: u32, len: usize) {
        let n = (4 - len) as u8;
        let i = index.to_le_bytes();
        let v = value.to_le_bytes();
        let request = [0x23 | n << 2, i[0], i[1], sub, v[0], v[1], v[2], v[3]];
        assert!(!feed(coe, true, &request));
        assert!(feed(coe, false, &[0x60, i[0], i[1], sub, 0, 0, 0, 0]));
    }

    #[test]
    fn expedited_downloads_build_assignment_and_mapping() {
        let mut coe = Coe::default();
        expedited(&mut coe, 0x1C12, 0, 0, 1);
        expedited(&mut coe, 0x1600, 0, 0, 1);
        expedited(&mut coe, 0x1600, 1, 0x6040_0010, 4);
        expedited(&mut coe, 0x1600, 2, 0x607A_0020, 4);
        expedited(&mut coe, 0x1600, 0, 2, 1);
        expedited(&mut coe, 0x1C12, 1, 0x1600, 2);
        expedited(&mut coe, 0x1C12, 0, 1, 1);
        assert_eq!(coe.assigned(2), Some(&[0x1600][..]));
        assert_eq!(coe.mapping(0x1600), Some(&[0x6040_0010, 0x607A_0020][..]));
        // Another object changes nothing; an abort closes the transfer.
        let request = [0x2F, 0x60, 0x60, 0, 8, 0, 0, 0];
        assert!(!feed(&mut coe, true, &request));
        assert!(!feed(&mut coe, false, &[0x60, 0x60, 0x60, 0, 0, 0, 0, 0]));
        assert!(!feed(&mut coe, true, &[0x23, 0x00, 0x16, 1, 0, 0, 0, 0]));
        assert!(!feed(
            &mut coe,
            false,
            &[0x80, 0x00, 0x16, 1, 0, 0, 0x02, 0x06]
        ));
        assert_eq!(coe.mapping(0x1600), Some(&[0x6040_0010, 0x607A_0020][..]));
    }

    #[test]
    fn complete_access_download_and_upload() {
        let mut coe = Coe::default();
        // TwinCAT: 0x1A00 complete access from sub-index 0: count, pad,
        // three entries; normal transfer with its size.
        let mut request = vec![0x31, 0x00, 0x1A, 0x00, 14, 0, 0, 0, 3, 0];
        for entry in [0x6041_0010u32, 0x6064_0020, 0x6061_0008] {
            request.extend(entry.to_le_bytes());
        }
        assert!(!feed(&mut coe, true, &request));
        assert!(feed(&mut coe, false, &[0x60, 0x00, 0x1A, 0, 0, 0, 0, 0]));
        assert_eq!(
            coe.mapping(0x1A00),
            Some(&[0x6041_0010, 0x6064_0020, 0x6061_0008][..])
        );
        // SOEM: 0x1C13 read back by a complete-access upload.
        assert!(!feed(&mut coe, true, &[0x50, 0x13, 0x1C, 0, 0, 0, 0, 0]));
        let response = [0x41, 0x13, 0x1C, 0, 4, 0, 0, 0, 1, 0, 0x00, 0x1A];
        assert!(feed(&mut coe, false, &response));
        assert_eq!(coe.assigned(3), Some(&[0x1A00][..]));
    }

    #[test]
    fn segmented_upload() {
        let mut coe = Coe::default();
        assert!(!feed(&mut coe, true, &[0x40, 0x00, 0x1A, 1, 0, 0, 0, 0]));
        // Normal response, size 4, no data in it; one segment with 4 bytes.
        assert!(!feed(&mut coe, false, &[0x41, 0x00, 0x1A, 1, 4, 0, 0, 0]));
        assert!(!feed(&mut coe, true, &[0x60, 0, 0, 0, 0, 0, 0, 0]));
        let segment = [0x07, 0x10, 0x00, 0x41, 0x60, 0, 0, 0];
        assert!(feed(&mut coe, false, &segment));
        // Sub-index 1 is kept; the count (sub-index 0) is not known yet.
        assert_eq!(coe.mapping(0x1A00), Some(&[][..]));
        expedited(&mut coe, 0x1A00, 0, 1, 1);
        assert_eq!(coe.mapping(0x1A00), Some(&[0x6041_0010][..]));
    }

    /// A plan of one drive: 7 output bytes at logical 10, 7 input bytes
    /// at logical 64, PDOs 0x1600/0x1A00, and SM1's status bit mapped.
    fn drive_plan() -> Plan {
        let mut fmmus = [None; UNITS];
        let mut sms = [None; UNITS];
        let fmmu = |logical, len, physical, kind| Fmmu {
            logical,
            len,
            logical_start_bit: 0,
            logical_end_bit: 7,
            physical,
            physical_start_bit: 0,
            kind,
            active: true,
        };
        fmmus[0] = Some(fmmu(10, 7, 0x1100, 2));
        fmmus[1] = Some(fmmu(64, 7, 0x1180, 1));
        fmmus[2] = Some(Fmmu {
            logical_start_bit: 0,
            logical_end_bit: 0,
            physical_start_bit: 3,
            ..fmmu(78, 1, 0x080D, 1)
        });
        let sm = |start, len, control| SyncManager {
            start,
            len,
            control,
            status: 0,
            activate: 1,
        };
        sms[0] = Some(sm(0x1000, 128, 0x26));
        sms[1] = Some(sm(0x1080, 128, 0x22));
        sms[2] = Some(sm(0x1100, 7, 0x64));
        sms[3] = Some(sm(0x1180, 7, 0x20));
        let mut coe = Coe::default();
        for (index, entries) in [
            (0x1600, [0x6040_0010u32, 0x607A_0020, 0x6060_0008]),
            (0x1A00, [0x6041_0010, 0x6064_0020, 0x6061_0008]),
        ] {
            for (sub, entry) in entries.into_iter().enumerate() {
                expedited(&mut coe, index, sub as u8 + 1, entry, 4);
            }
            expedited(&mut coe, index, 0, 3, 1);
        }
        expedited(&mut coe, 0x1C12, 1, 0x1600, 2);
        expedited(&mut coe, 0x1C12, 0, 1, 1);
        expedited(&mut coe, 0x1C13, 1, 0x1A00, 2);
        expedited(&mut coe, 0x1C13, 0, 1, 1);
        Plan::new(&fmmus, &sms, &coe.objects, &[])
    }

    #[test]
    fn cut_and_share() {
        let plan = drive_plan();
        assert_eq!(plan.lens(), (7, 7));
        assert!(plan.touches(0, 79) && !plan.touches(17, 64));
        // Reads (inputs and the status bit) and writes: 3 in an LRW.
        assert_eq!(plan.share(Command::Lrw, 0, 79), 3);
        assert_eq!(plan.share(Command::Lrd, 0, 79), 1);
        assert_eq!(plan.share(Command::Lwr, 0, 79), 1);
        assert_eq!(plan.share(Command::Lrw, 64, 79), 1);
        let mut sent = [0u8; 79];
        let mut returned = [0u8; 79];
        sent[10..17].copy_from_slice(&[0x0F, 0, 0x10, 0x27, 0, 0, 8]);
        // The sent copy carries last cycle's inputs; the returned one
        // today's.
        sent[64..71].copy_from_slice(&[0x33, 0x02, 0, 0, 0, 0, 8]);
        returned[..].copy_from_slice(&sent);
        returned[64..71].copy_from_slice(&[0x37, 0x02, 0x10, 0x27, 0, 0, 8]);
        let (mut outputs, mut inputs) = (Vec::new(), Vec::new());
        assert_eq!(
            plan.cut(0, &sent, &returned, &mut outputs, &mut inputs),
            (7, 7)
        );
        assert_eq!(outputs, [0x0F, 0, 0x10, 0x27, 0, 0, 8]);
        assert_eq!(inputs, [0x37, 0x02, 0x10, 0x27, 0, 0, 8]);
        let mut named = Vec::new();
        plan.for_each_signal(false, &inputs, |name, signal| {
            named.push((name.to_string(), signal.unwrap().value));
        });
        assert_eq!(named.len(), 3);
        assert_eq!(named[0].0, "Statusword");
        assert_eq!(named[0].1, crate::canopen::Value::Unsigned(0x0237));
        assert_eq!(named[1].1, crate::canopen::Value::Signed(10_000));
        // A datagram that holds only part of the inputs.
        assert_eq!(
            plan.cut(0, &sent[..66], &returned[..66], &mut outputs, &mut inputs),
            (7, 2)
        );
    }

    #[test]
    fn a_mapping_longer_than_its_sync_manager_is_not_read() {
        let mut fmmus = [None; UNITS];
        let mut sms = [None; UNITS];
        fmmus[0] = Some(Fmmu {
            logical: 0,
            len: 2,
            logical_start_bit: 0,
            logical_end_bit: 7,
            physical: 0x1100,
            physical_start_bit: 0,
            kind: 2,
            active: true,
        });
        sms[2] = Some(SyncManager {
            start: 0x1100,
            len: 2,
            control: 0x64,
            status: 0,
            activate: 1,
        });
        let mut coe = Coe::default();
        expedited(&mut coe, 0x1600, 1, 0x607A_0020, 4);
        expedited(&mut coe, 0x1600, 0, 1, 1);
        expedited(&mut coe, 0x1C12, 1, 0x1600, 2);
        expedited(&mut coe, 0x1C12, 0, 1, 1);
        let plan = Plan::new(&fmmus, &sms, &coe.objects, &[]);
        assert_eq!(
            plan.too_long,
            [ImageError::MappingPastSyncManager {
                sm: 2,
                pdo: 0x1600,
                end_bit: 32,
                len: 2
            }]
        );
        assert!(!plan.has_signals());
        assert_eq!(plan.lens(), (2, 0));
    }

    /// An FMMU of `bits` bits at logical 0, bit `first`, onto 0x0F00.
    fn bit_fmmu(first: u8, bits: u8, kind: u8) -> Fmmu {
        Fmmu {
            logical: 0,
            len: 1,
            logical_start_bit: first,
            logical_end_bit: first + bits - 1,
            physical: 0x0F00,
            physical_start_bit: 0,
            kind,
            active: true,
        }
    }

    fn plan(fmmu: Fmmu) -> Plan {
        let mut fmmus = [None; UNITS];
        fmmus[0] = Some(fmmu);
        Plan::new(&fmmus, &[None; UNITS], &CoeObjects::default(), &[])
    }

    /// A terminal of fewer than 8 bits packed into part of a byte (as
    /// SOEM maps bit-oriented slaves) counts in the working counter like
    /// any FMMU: +2 written and +1 read in an LRW (ETG.1000.4 §5.4.1.2).
    #[test]
    fn bit_fmmus_count_in_the_working_counter() {
        let outputs = plan(bit_fmmu(4, 4, 2));
        assert!(outputs.touches(0, 1));
        assert_eq!(outputs.share(Command::Lrw, 0, 1), 2);
        assert_eq!(outputs.share(Command::Lwr, 0, 1), 1);
        assert_eq!(outputs.share(Command::Lrd, 0, 1), 0);
        let inputs = plan(bit_fmmu(0, 4, 1));
        assert!(inputs.touches(0, 1));
        assert_eq!(inputs.share(Command::Lrw, 0, 1), 1);
        assert_eq!(inputs.share(Command::Lrd, 0, 1), 1);
        assert_eq!(inputs.share(Command::Lwr, 0, 1), 0);
        assert!(!inputs.touches(1, 2));
    }
}
