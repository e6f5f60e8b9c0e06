//! What a configuration says of a slave's process data: the FMMUs, sync
//! managers, PDO assignment and PDO mappings the capture's start-up wrote
//! or read, or a master's ENI file gives (docs/ethercat.md#process-data).

use crate::canopen::{DataType, MappingEntry};
use crate::ethercat::{Fmmu, SyncManager};

/// One entry of a PDO: the object it maps, and the name and type a
/// configuration file gives it (an ENI's `Entry`); without them the
/// object table's are used.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PdoEntryConfig {
    /// Index, sub-index and bit length (index 0: a gap).
    pub entry: MappingEntry,
    /// The entry's name, where the configuration names it.
    pub name: Option<String>,
    /// The entry's CiA 301 data type, where the configuration gives it.
    pub data_type: Option<DataType>,
}

/// One PDO: its mapping object's index (0x1600–0x17FF receive,
/// 0x1A00–0x1BFF transmit) and its entries in order.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PdoConfig {
    /// The mapping object's index.
    pub index: u16,
    /// The entries, in mapping order.
    pub entries: Vec<PdoEntryConfig>,
}

/// What a configuration says of one slave's process data
/// (docs/ethercat.md#process-data): where it is in the logical image
/// (FMMUs), which sync managers guard it, and which PDOs each sync
/// manager carries. [`Session::configure`](super::Session::configure)
/// takes these from an ENI file (`parse_eni`) or a mapping given by hand.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct SlaveConfig {
    /// The configured station address.
    pub station: Option<u16>,
    /// The position on the ring, from 0.
    pub position: Option<u16>,
    /// The slave's name in the configuration.
    pub name: Option<String>,
    /// The vendor id.
    pub vendor: Option<u32>,
    /// The product code.
    pub product: Option<u32>,
    /// The FMMUs, by number (at most 16).
    pub fmmus: Vec<(u8, Fmmu)>,
    /// The sync managers, by number (at most 16).
    pub sync_managers: Vec<(u8, SyncManager)>,
    /// The PDO assignment: for a sync manager's number, the indices of its
    /// PDOs in order (object 0x1C10 + n).
    pub assignment: Vec<(u8, Vec<u16>)>,
    /// The PDOs.
    pub pdos: Vec<PdoConfig>,
}
