//! What the metadata blocks say (ASAM MDF 4.1 §5; docs/formats.md#mf4): the
//! header (HD), the data groups (DG) and their channel groups (CG), and for
//! each CAN bus-logging group where its members are (CN) and how they convert
//! (CC).

use std::io::{Read, Seek};

use crate::logs::bytes::padded;
use crate::logs::mf4::block::{damaged, Block, Chain, Source};
use crate::logs::mf4::channel::{Channel, Conversion, Location};
use crate::logs::{BinaryError, LogError};

/// The most metadata blocks (DG, CG, CN, CC, TX) the reader reads: a
/// CANedge file has about 2 000; a hostile file that links the same
/// chains over and over ends with [`BinaryError::TooLarge`].
pub(super) const MAX_METADATA_BLOCKS: u64 = 1 << 20;

/// The most bytes of a name the reader reads.
const MAX_NAME: usize = 256;

/// The most values of a conversion the reader reads (a CANedge DLC table
/// has 32).
const MAX_CONVERSION_VALUES: usize = 4096;

/// CG flag bit 0: a VLSD channel group (records are a u32 length and
/// bytes).
const CG_VLSD: u16 = 0x1;

/// The kind of frame a CAN group holds (docs/formats.md#mf4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum FrameKind {
    /// `CAN_DataFrame`.
    Data,
    /// `CAN_RemoteFrame`.
    Remote,
    /// `CAN_ErrorFrame`.
    Error,
}

impl FrameKind {
    const ALL: [(FrameKind, &'static str); 3] = [
        (FrameKind::Data, "CAN_DataFrame"),
        (FrameKind::Remote, "CAN_RemoteFrame"),
        (FrameKind::Error, "CAN_ErrorFrame"),
    ];
}

/// Where a CAN group's `DataBytes` are.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum DataBytes {
    /// In the record: byte offset and length.
    Fixed { byte: u32, len: u32 },
    /// VLSD (cn_type 1): the record holds an offset into the signal data
    /// that `link` leads to (SD, DZ, DL, HL).
    Signal { offset: Channel, link: u64 },
    /// VLSD: the record holds an offset into the records of the VLSD
    /// channel group `record_id` of the same data group.
    Group { offset: Channel, record_id: u64 },
}

/// The members of a CAN group (docs/formats.md#mf4), each where the group has
/// it.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct Members {
    pub(super) bus_channel: Option<Channel>,
    pub(super) id: Option<Channel>,
    pub(super) ide: Option<Channel>,
    pub(super) dlc: Option<Channel>,
    pub(super) data_length: Option<Channel>,
    pub(super) dir: Option<Channel>,
    pub(super) edl: Option<Channel>,
    pub(super) brs: Option<Channel>,
    pub(super) esi: Option<Channel>,
    pub(super) error_type: Option<Channel>,
}

/// A CAN bus-logging channel group.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CanGroup {
    pub(super) kind: FrameKind,
    /// The master channel (time, seconds), where the group has one.
    pub(super) master: Option<Channel>,
    pub(super) members: Members,
    pub(super) data_bytes: Option<DataBytes>,
}

/// What a channel group is to the reader.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Kind {
    Can(Box<CanGroup>),
    /// A VLSD channel group: its records are a u32 length and bytes.
    Vlsd,
    /// Any other group (LIN, `CAN_OverloadFrame`, signals): counted by name.
    Other(String),
}

/// A channel group.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Group {
    /// The CG block's offset.
    pub(super) at: u64,
    pub(super) record_id: u64,
    /// The bytes of a record after the record id (data and invalidation
    /// bytes); `None` for a VLSD group.
    pub(super) record_len: Option<u64>,
    /// The records the group holds, as its cycle count says (read only in
    /// a finalized file).
    pub(super) cycles: u64,
    pub(super) kind: Kind,
}

/// A data group.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct DataGroup {
    /// The DG block's offset.
    pub(super) at: u64,
    /// The link to its data (DT, DZ, DL, HL; 0 for none).
    pub(super) data: u64,
    /// The bytes of the record id before each record: 0, 1, 2, 4 or 8.
    pub(super) record_id_len: u8,
    pub(super) groups: Vec<Group>,
    /// In a finalized file, the records of its data: the sum of its
    /// channel groups' cycle counts; `None` in an unfinalized file, whose
    /// records run until the data end.
    pub(super) records: Option<u64>,
    /// Whether a data block whose length is its header runs to the end of
    /// the file (an unfinalized file: the length was never written).
    pub(super) open_ended: bool,
}

/// What the metadata of a file says.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    /// The version number, e.g. 411 for 4.11.
    pub(super) version: u16,
    /// The start time, ns since the Unix epoch (HD at 72).
    pub(super) start_ns: u64,
    pub(super) data_groups: Vec<DataGroup>,
}

/// Reads the metadata, counting blocks against [`MAX_METADATA_BLOCKS`].
struct Reader<'a, R> {
    source: &'a mut Source<R>,
    blocks: u64,
}

impl<R: Read + Seek> Reader<'_, R> {
    fn block(&mut self, at: u64, ids: &'static str, data: usize) -> Result<Block, LogError> {
        self.count(at)?;
        self.source.block(at, ids, data)
    }

    fn text(&mut self, at: u64) -> Result<Option<String>, LogError> {
        if at != 0 {
            self.count(at)?;
        }
        self.source.text(at, MAX_NAME)
    }

    fn count(&mut self, at: u64) -> Result<(), LogError> {
        self.blocks += 1;
        if self.blocks > MAX_METADATA_BLOCKS {
            return Err(damaged(
                at,
                BinaryError::TooLarge {
                    length: self.blocks,
                    limit: MAX_METADATA_BLOCKS,
                },
            ));
        }
        Ok(())
    }
}

/// Read the identification block and the metadata after it.
pub(super) fn read<R: Read + Seek>(source: &mut Source<R>) -> Result<Layout, LogError> {
    let mut id = [0u8; 64];
    let got = source.read_at(0, &mut id)?;
    let magic = id.get(..8).unwrap_or_default();
    if got >= 8 && magic != b"MDF     " && magic != b"UnFinMF " {
        return Err(damaged(
            0,
            BinaryError::BadMagic {
                found: u32::from_le_bytes(padded(&id, 0)),
            },
        ));
    }
    if got < 64 {
        return Err(damaged(
            0,
            BinaryError::Truncated {
                needed: 64,
                found: got as u64,
            },
        ));
    }
    let version = u16::from_le_bytes(padded(&id, 28));
    if !(400..500).contains(&version) {
        return Err(damaged(
            28,
            BinaryError::UnsupportedVersion {
                major: version / 100,
                minor: version % 100,
            },
        ));
    }
    // Finalized: `MDF     ` and, from version 4.10, no unfinalized flag
    // (`id_unfin_flags` at 60), as asammdf decides it.
    let finalized =
        magic == b"MDF     " && (version < 410 || u16::from_le_bytes(padded(&id, 60)) == 0);
    let mut reader = Reader { source, blocks: 0 };
    let hd = reader.block(64, "##HD", 32)?;
    let start_ns = hd.u64(0);
    let mut data_groups = Vec::new();
    let mut chain = Chain::default();
    let mut next = hd.link(0);
    while next != 0 {
        chain.visit(next, reader.source.len)?;
        let dg = reader.block(next, "##DG", 8)?;
        data_groups.push(data_group(&mut reader, &dg, finalized)?);
        next = dg.link(0);
    }
    Ok(Layout {
        version,
        start_ns,
        data_groups,
    })
}

fn data_group<R: Read + Seek>(
    reader: &mut Reader<'_, R>,
    dg: &Block,
    finalized: bool,
) -> Result<DataGroup, LogError> {
    let record_id_len = dg.u8(0);
    if !matches!(record_id_len, 0 | 1 | 2 | 4 | 8) {
        return Err(damaged(
            dg.data_at(),
            BinaryError::BadLength {
                length: u64::from(record_id_len),
            },
        ));
    }
    let mut groups = Vec::new();
    let mut chain = Chain::default();
    let mut next = dg.link(1);
    while next != 0 {
        chain.visit(next, reader.source.len)?;
        let cg = reader.block(next, "##CG", 32)?;
        groups.push(channel_group(reader, &cg)?);
        next = cg.link(0);
    }
    // A sorted group holds one channel group's records (the reader reads
    // no other).
    let counted = if record_id_len == 0 { 1 } else { groups.len() };
    let records = finalized.then(|| {
        groups
            .iter()
            .take(counted)
            .fold(0u64, |sum, group| sum.saturating_add(group.cycles))
    });
    Ok(DataGroup {
        at: dg.at,
        data: dg.link(2),
        record_id_len,
        groups,
        records,
        open_ended: !finalized,
    })
}

/// A channel as the group's list holds it: its name and block.
struct Named {
    name: String,
    block: Block,
}

fn channel_group<R: Read + Seek>(
    reader: &mut Reader<'_, R>,
    cg: &Block,
) -> Result<Group, LogError> {
    let record_id = cg.u64(0);
    let cycles = cg.u64(8);
    let flags = cg.u16(16);
    if flags & CG_VLSD != 0 {
        return Ok(Group {
            at: cg.at,
            record_id,
            record_len: None,
            cycles,
            kind: Kind::Vlsd,
        });
    }
    let record_len = u64::from(cg.u32(24)) + u64::from(cg.u32(28));
    // The channels, and the members of composed ones (one level down).
    let mut channels: Vec<Named> = Vec::new();
    let mut chain = Chain::default();
    let mut next = cg.link(1);
    while next != 0 {
        chain.visit(next, reader.source.len)?;
        let cn = reader.block(next, "##CN", 24)?;
        next = cn.link(0);
        let name = reader.text(cn.link(2))?.unwrap_or_default();
        let composition = cn.link(1);
        channels.push(Named { name, block: cn });
        if composition != 0 {
            // A composition is a CN list or an array (CA): only lists hold
            // bus-logging members.
            let mut members = Chain::default();
            let mut member = composition;
            while member != 0 {
                members.visit(member, reader.source.len)?;
                let Ok(cn) = reader.block(member, "##CN", 24) else {
                    break;
                };
                member = cn.link(0);
                let name = reader.text(cn.link(2))?.unwrap_or_default();
                channels.push(Named { name, block: cn });
            }
        }
    }
    let kind = FrameKind::ALL.into_iter().find(|(_, top)| {
        channels
            .iter()
            .any(|c| c.name == *top || member_of(&c.name, top).is_some())
    });
    let Some((kind, top)) = kind else {
        // Named by its composed top channel (`LIN_Frame`), else by the
        // group's acquisition name, else by its first channel.
        let name = channels
            .iter()
            .find(|c| c.block.link(1) != 0)
            .map(|c| c.name.clone())
            .or(reader.text(cg.link(2))?)
            .or_else(|| {
                channels
                    .iter()
                    .find(|c| !is_master(&c.block))
                    .map(|c| c.name.clone())
            })
            .unwrap_or_default();
        return Ok(Group {
            at: cg.at,
            record_id,
            record_len: Some(record_len),
            cycles,
            kind: Kind::Other(name),
        });
    };
    let mut group = CanGroup {
        kind,
        master: None,
        members: Members::default(),
        data_bytes: None,
    };
    for channel in &channels {
        if group.master.is_none() && is_master(&channel.block) {
            group.master = Some(self::channel(reader, &channel.block, false)?);
            continue;
        }
        let Some(member) = member_of(&channel.name, top) else {
            continue;
        };
        let cn = &channel.block;
        let slot = match member {
            "BusChannel" => &mut group.members.bus_channel,
            "ID" => &mut group.members.id,
            "IDE" => &mut group.members.ide,
            "DLC" => &mut group.members.dlc,
            "DataLength" => &mut group.members.data_length,
            "Dir" => &mut group.members.dir,
            "EDL" => &mut group.members.edl,
            "BRS" => &mut group.members.brs,
            "ESI" => &mut group.members.esi,
            "ErrorType" => &mut group.members.error_type,
            "DataBytes" => {
                group.data_bytes = data_bytes(reader, cn)?;
                continue;
            }
            _ => continue,
        };
        if slot.is_none() {
            *slot = Some(self::channel(reader, cn, member == "Dir")?);
        }
    }
    Ok(Group {
        at: cg.at,
        record_id,
        record_len: Some(record_len),
        cycles,
        kind: Kind::Can(Box::new(group)),
    })
}

/// `CAN_DataFrame.ID` → `ID` when `top` is `CAN_DataFrame`.
fn member_of<'a>(name: &'a str, top: &str) -> Option<&'a str> {
    name.strip_prefix(top)?.strip_prefix('.')
}

/// A master channel of time: cn_type 2 (master) or 3 (virtual master),
/// sync type 1 (time).
fn is_master(cn: &Block) -> bool {
    matches!(cn.u8(0), 2 | 3) && cn.u8(1) == 1
}

/// The channel of a CN block: its bits (or the record index for a virtual
/// one) and its conversion (a value-to-text one only for `Dir`, whose texts
/// are `Rx` and `Tx`: any other member reads its raw value).
fn channel<R: Read + Seek>(
    reader: &mut Reader<'_, R>,
    cn: &Block,
    dir: bool,
) -> Result<Channel, LogError> {
    let location = match cn.u8(0) {
        3 | 6 => Location::Index,
        _ => Location::Bits {
            byte: cn.u32(4),
            bit: cn.u8(3),
            bits: cn.u32(8),
            data_type: cn.u8(2),
        },
    };
    let conversion = match conversion(reader, cn.link(4))? {
        Conversion::Text { .. } if !dir => Conversion::Identity,
        conversion => conversion,
    };
    Ok(Channel {
        location,
        conversion,
    })
}

/// Where `DataBytes` are: in the record (cn_type 0), or VLSD (cn_type 1)
/// through its data link.
fn data_bytes<R: Read + Seek>(
    reader: &mut Reader<'_, R>,
    cn: &Block,
) -> Result<Option<DataBytes>, LogError> {
    match cn.u8(0) {
        1 => {
            let link = cn.link(5);
            if link == 0 {
                return Ok(None);
            }
            let offset = Channel {
                location: Location::Bits {
                    byte: cn.u32(4),
                    bit: cn.u8(3),
                    bits: cn.u32(8).min(64),
                    data_type: 0,
                },
                conversion: Conversion::Identity,
            };
            let (id, _, _) = reader.source.header(link, "##SD|##DZ|##DL|##HL|##CG")?;
            if &id == b"##CG" {
                let cg = reader.block(link, "##CG", 8)?;
                Ok(Some(DataBytes::Group {
                    offset,
                    record_id: cg.u64(0),
                }))
            } else {
                Ok(Some(DataBytes::Signal { offset, link }))
            }
        }
        0 => Ok(Some(DataBytes::Fixed {
            byte: cn.u32(4),
            len: cn.u32(8) / 8,
        })),
        _ => Ok(None),
    }
}

/// The conversion of a CC block (none: identity). Types the reader does not
/// apply read as identity.
fn conversion<R: Read + Seek>(reader: &mut Reader<'_, R>, at: u64) -> Result<Conversion, LogError> {
    if at == 0 {
        return Ok(Conversion::Identity);
    }
    let head = reader.block(at, "##CC", 8)?;
    let kind = head.u8(0);
    let values = usize::from(head.u16(6)).min(MAX_CONVERSION_VALUES);
    let cc = reader.block(at, "##CC", 24 + 8 * values)?;
    let value = |i: usize| cc.f64(24 + 8 * i);
    Ok(match kind {
        1 if values >= 2 => Conversion::Linear {
            b: value(0),
            a: value(1),
        },
        2 if values >= 6 => {
            Conversion::Rational([value(0), value(1), value(2), value(3), value(4), value(5)])
        }
        4 | 5 => Conversion::Table {
            pairs: (0..values / 2)
                .map(|i| (value(2 * i), value(2 * i + 1)))
                .collect(),
            interpolate: kind == 4,
        },
        6 => Conversion::Ranges {
            ranges: (0..values / 3)
                .map(|i| (value(3 * i), value(3 * i + 1), value(3 * i + 2)))
                .collect(),
            default: if values % 3 == 1 {
                value(values - 1)
            } else {
                0.0
            },
        },
        7 => {
            // Keys, then one text per key and the default: 1 for `Tx`.
            let mut tx = |link: u64| -> Result<f64, LogError> {
                let text = reader.text(link)?.unwrap_or_default();
                Ok(if text.trim().eq_ignore_ascii_case("tx") {
                    1.0
                } else {
                    0.0
                })
            };
            let mut keys = Vec::with_capacity(values);
            for i in 0..values {
                keys.push((value(i), tx(cc.link(4 + i))?));
            }
            let default = tx(cc.link(4 + values))?;
            Conversion::Text { keys, default }
        }
        _ => Conversion::Identity,
    })
}
