//! `--eds NODE=FILE`: the EDS or DCF that describes a node (SPEC §8.1 item
//! 2). The library reads the file; this keeps what the decoder asks of it.

use std::path::Path;

use motionwire::canopen::{DataType, NodeId, PdoCobId, PdoDirection};
use motionwire::eds::Eds;

/// One PDO as a node description gives it.
pub struct DescribedPdo {
    /// A TPDO (else an RPDO).
    pub transmit: bool,
    /// The PDO number, 1..=512.
    pub number: u16,
    /// The COB-ID entry (communication parameter sub 1).
    pub cob_id: Option<PdoCobId>,
    /// The mapping entries as u32 (mapping parameter subs 1..=n).
    pub entries: Vec<u32>,
}

/// A node's EDS or DCF, read for that node-ID (`$NODEID` resolves to it).
pub struct NodeDescription {
    eds: Eds,
    pdos: Vec<DescribedPdo>,
}

impl NodeDescription {
    /// Read `path` for `node`.
    pub fn read(node: NodeId, path: &Path) -> Result<Self, String> {
        let eds = Eds::read_file(path, Some(node)).map_err(|e| e.to_string())?;
        let pdos = eds
            .pdos()
            .map_err(|e| e.to_string())?
            .into_iter()
            .map(|pdo| DescribedPdo {
                transmit: pdo.direction == PdoDirection::Transmit,
                number: pdo.number,
                cob_id: Some(pdo.communication.cob_id),
                entries: pdo.mapping.entries().iter().map(|e| e.to_u32()).collect(),
            })
            .collect();
        Ok(NodeDescription { eds, pdos })
    }

    /// Whether the device type (1000h) says CiA 402 (SPEC §8.3).
    pub fn is_drive(&self) -> bool {
        self.eds.is_cia402()
    }

    /// The PDOs the file configures.
    pub fn pdos(&self) -> &[DescribedPdo] {
        &self.pdos
    }

    /// The name of an entry (`Record name.Sub-entry name` for a record's
    /// sub-entry, SPEC §8.2).
    pub fn name(&self, index: u16, sub: u8) -> Option<&str> {
        self.eds.name(index, sub)
    }

    /// The data type of an entry.
    pub fn data_type(&self, index: u16, sub: u8) -> Option<DataType> {
        self.eds.data_type(index, sub)
    }
}
