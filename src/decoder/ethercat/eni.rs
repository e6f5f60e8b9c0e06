//! A master's EtherCAT network information file (ENI, ETG.2100 XML, what
//! TwinCAT's "export configuration" writes) read into each slave's
//! [`SlaveConfig`] (docs/ethercat.md#eni): its identity and addresses, the
//! FMMU and sync-manager registers its start-up writes, its PDO assignment
//! and PDO mappings.
//!
//! ```
//! use motionwire::decoder::ethercat::parse_eni;
//!
//! let eni = r##"<EtherCATConfig><Config><Slave>
//!   <Info><Name>Drive</Name><PhysAddr>#x1002</PhysAddr><AutoIncAddr>65535</AutoIncAddr>
//!     <VendorId>#x6a</VendorId><ProductCode>#x414b44</ProductCode></Info>
//!   <ProcessData>
//!     <RxPdo Sm="2"><Index>#x1600</Index>
//!       <Entry><Index>#x6040</Index><SubIndex>0</SubIndex><BitLen>16</BitLen>
//!         <Name>Controlword</Name><DataType>UINT</DataType></Entry></RxPdo>
//!   </ProcessData>
//!   <InitCmds><InitCmd><Transition>PS</Transition><Cmd>5</Cmd><Adp>4098</Adp>
//!     <Ado>2064</Ado><Data>0011020064000100</Data></InitCmd></InitCmds>
//! </Slave></Config></EtherCATConfig>"##;
//! let slaves = parse_eni(eni).unwrap();
//! let drive = &slaves[0];
//! assert_eq!((drive.station, drive.position), (Some(0x1002), Some(1)));
//! let (number, sm) = drive.sync_managers[0];
//! assert_eq!((number, sm.start, sm.len, sm.control), (2, 0x1100, 2, 0x64));
//! assert_eq!(drive.assignment, vec![(2, vec![0x1600])]);
//! assert_eq!(drive.pdos[0].entries[0].entry.index(), 0x6040);
//! assert_eq!(drive.pdos[0].entries[0].name.as_deref(), Some("Controlword"));
//! ```

use std::collections::BTreeMap;

use roxmltree::{Document, Node};

use super::config::{PdoConfig, PdoEntryConfig, SlaveConfig};
use crate::canopen::{DataType, MappingEntry};
use crate::ethercat::{Command, Fmmu, SyncManager, SyncManagerMode, FMMU_LEN, SYNC_MANAGER_LEN};

/// FMMUs and sync managers an ESC has at most (ESC datasheet, section II:
/// 0x0600–0x06FF and 0x0800–0x087F, the reserved space after each).
const REGISTERS: usize = 16;
/// The first FMMU's registers.
const FMMU_BASE: u32 = 0x0600;
/// The first sync manager's registers.
const SYNC_MANAGER_BASE: u32 = 0x0800;
/// A datagram's header: a cyclic command's `InputOffs`/`OutputOffs` is
/// where its datagram starts in the frame, its data follows 10 bytes on.
const DATAGRAM_HEADER: u64 = 10;
/// The control bytes of the mailbox sync managers a `Mailbox` gives when
/// no register write does: mailbox mode, written by the master (SM0) or
/// read (SM1), with the PDI interrupt, as TwinCAT writes them.
const MAILBOX_OUT_CONTROL: u8 = 0x26;
const MAILBOX_IN_CONTROL: u8 = 0x22;
/// How much of a wrong text an error quotes.
const QUOTED: usize = 40;

/// Why an ENI file cannot be read, and where (docs/ethercat.md#eni).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("line {line}{}: {kind}", in_element(.element))]
pub struct EniError {
    /// The 1-based line of the element, or where the XML breaks.
    pub line: u32,
    /// The element (its local name) that holds what is wrong; `None` when
    /// the text is not XML.
    pub element: Option<String>,
    /// What is wrong.
    pub kind: EniErrorKind,
}

fn in_element(element: &Option<String>) -> String {
    element
        .as_ref()
        .map(|name| format!(", <{name}>"))
        .unwrap_or_default()
}

/// What is wrong in an ENI file ([`EniError`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EniErrorKind {
    /// The text is not well-formed XML (or holds a DTD): the XML reader's
    /// message and the column.
    #[error("not XML: {message} (column {column})")]
    Xml {
        /// The XML reader's message.
        message: String,
        /// The 1-based column.
        column: u32,
    },
    /// The root element is another one than `EtherCATConfig`.
    #[error("the root element is <{0}>, not <EtherCATConfig>: not an ENI file")]
    NotEni(String),
    /// An element the reading needs is missing.
    #[error("<{0}> is missing")]
    Missing(&'static str),
    /// A number is neither decimal nor `#x`/`0x` hex.
    #[error("expected a decimal or #x hex number, found {0:?}")]
    BadNumber(String),
    /// A number does not fit its field.
    #[error("{text:?} does not fit in {bits} bits")]
    OutOfRange {
        /// The number as written.
        text: String,
        /// The field's width.
        bits: u32,
    },
    /// A `Data` element is not hex bytes.
    #[error("expected hex bytes, found {0:?}")]
    BadData(String),
    /// An FMMU or sync manager past the 16 an ESC has (numbers 0–15).
    #[error("{what} {number}: an ESC has 16 (0-15)")]
    TooMany {
        /// `"FMMU"` or `"sync manager"`.
        what: &'static str,
        /// The number given.
        number: u64,
    },
    /// A PDO entry's bit length is 0 or above 255.
    #[error("a PDO entry's bit length is 1-255, found {0}")]
    BitLen(u64),
}

/// Read an ENI file: one [`SlaveConfig`] per `Config/Slave`, in the
/// file's order (docs/ethercat.md#eni).
///
/// # Errors
///
/// [`EniError`] when the text is not XML, not an `EtherCATConfig`, or an
/// element the reading uses holds what it cannot be (a number that does
/// not parse or fit, `Data` that is not hex, a sync manager past 15, a
/// PDO entry's bit length 0 or above 255).
pub fn parse_eni(xml: &str) -> Result<Vec<SlaveConfig>, EniError> {
    let document = Document::parse(xml).map_err(xml_error)?;
    let root = document.root_element();
    if root.tag_name().name() != "EtherCATConfig" {
        let found = quoted(root.tag_name().name());
        return Err(error(root, EniErrorKind::NotEni(found)));
    }
    let config =
        child(root, "Config").ok_or_else(|| error(root, EniErrorKind::Missing("Config")))?;
    let cyclic = cyclic_commands(config)?;
    children(config, "Slave")
        .map(|slave| read_slave(slave, &cyclic))
        .collect()
}

fn xml_error(e: roxmltree::Error) -> EniError {
    let position = e.pos();
    let message = e.to_string();
    let message = message
        .strip_suffix(&format!(" at {position}"))
        .unwrap_or(&message)
        .to_owned();
    EniError {
        line: position.row,
        element: None,
        kind: EniErrorKind::Xml {
            message,
            column: position.col,
        },
    }
}

/// One slave: the registers its InitCmds write, what `ProcessData` and
/// `Mailbox` say where they do not, its PDOs and their assignment.
fn read_slave(slave: Node, cyclic: &[CyclicCommand]) -> Result<SlaveConfig, EniError> {
    let mut config = SlaveConfig::default();
    if let Some(info) = child(slave, "Info") {
        config.name = child(info, "Name").and_then(nonempty_text);
        config.station = child_number(info, "PhysAddr", 16)?.map(|n| n as u16);
        config.position =
            child_number(info, "AutoIncAddr", 16)?.map(|n| 0u16.wrapping_sub(n as u16));
        config.vendor = child_number(info, "VendorId", 32)?.map(|n| n as u32);
        config.product = child_number(info, "ProductCode", 32)?.map(|n| n as u32);
    }

    let mut registers = Registers::default();
    for command in grandchildren(slave, "InitCmds", "InitCmd") {
        registers.apply(command)?;
    }

    let mut elements = Vec::new();
    let mut sync_manager_elements = Vec::new();
    let (mut send, mut recv) = (None, None);
    if let Some(process_data) = child(slave, "ProcessData") {
        for node in process_data.children().filter(Node::is_element) {
            match node.tag_name().name() {
                "RxPdo" | "TxPdo" => elements.push(pdo_element(node)?),
                "Send" => send = Some(image_range(node)?),
                "Recv" => recv = Some(image_range(node)?),
                name => {
                    if let Some(number) = sync_manager_element_number(name) {
                        let number = number.map_err(|kind| error(node, kind))?;
                        sync_manager_elements.push(sync_manager_element(node, number)?);
                    }
                }
            }
        }
    }

    let coe = coe_objects(slave)?;
    config.pdos = pdos(&elements, &coe)?;
    config.assignment = assignment(&elements, &sync_manager_elements, &coe);

    config.sync_managers = sync_managers(
        &registers,
        &sync_manager_elements,
        child(slave, "Mailbox"),
        &config,
    )?;
    config.fmmus = registers.fmmus();
    if config.fmmus.is_empty() {
        let derived = [(send, true), (recv, false)]
            .into_iter()
            .filter_map(|(range, output)| {
                derived_fmmu(range?, output, cyclic, &config.sync_managers)
            });
        config.fmmus = (0u8..).zip(derived).collect();
    }
    Ok(config)
}

/// The FMMU and sync-manager registers as the slave's InitCmds leave them
/// on the way to OP: a byte image of each, and which were written.
#[derive(Default)]
struct Registers {
    fmmus: [[u8; FMMU_LEN]; REGISTERS],
    fmmus_written: u16,
    sync_managers: [[u8; SYNC_MANAGER_LEN]; REGISTERS],
    sync_managers_written: u16,
}

impl Registers {
    /// Apply one InitCmd if it is an APWR or FPWR (the commands that
    /// write one slave's registers; `Cmd` is the datagram's command byte)
    /// on the way to OP.
    fn apply(&mut self, command: Node) -> Result<(), EniError> {
        if !on_the_way_to_op(command) {
            return Ok(());
        }
        let Some(cmd) = command_of(command)? else {
            return Ok(());
        };
        if !matches!(cmd, Command::Apwr | Command::Fpwr) {
            return Ok(());
        }
        let (Some(ado), Some(data)) = (child_number(command, "Ado", 16)?, data(command)?) else {
            return Ok(());
        };
        write_area(
            &mut self.fmmus,
            &mut self.fmmus_written,
            FMMU_BASE,
            ado,
            &data,
            "FMMU",
        )
        .and_then(|()| {
            write_area(
                &mut self.sync_managers,
                &mut self.sync_managers_written,
                SYNC_MANAGER_BASE,
                ado,
                &data,
                "sync manager",
            )
        })
        .map_err(|kind| error(command, kind))
    }

    fn fmmus(&self) -> Vec<(u8, Fmmu)> {
        configured(&self.fmmus, self.fmmus_written)
            .map(|(n, bytes)| (n, Fmmu::from_bytes(bytes)))
            .collect()
    }

    fn sync_manager(&self, number: u8) -> Option<SyncManager> {
        configured(&self.sync_managers, self.sync_managers_written)
            .find(|&(n, _)| n == number)
            .map(|(_, bytes)| SyncManager::from_bytes(bytes))
    }
}

/// Write `data` at `ado` into the registers of one area (16 registers of
/// `N` bytes from `base`): bytes before or past the area's two windows
/// are another register's; non-zero bytes in the reserved window after
/// the 16th register name a 17th.
fn write_area<const N: usize>(
    registers: &mut [[u8; N]; REGISTERS],
    written: &mut u16,
    base: u32,
    ado: u64,
    data: &[u8],
    what: &'static str,
) -> Result<(), EniErrorKind> {
    let base = u64::from(base);
    let window_end = base + 2 * (REGISTERS * N) as u64;
    let end = ado + data.len() as u64;
    for address in ado.max(base)..end.min(window_end) {
        let byte = data[(address - ado) as usize];
        let offset = (address - base) as usize;
        let (number, at) = (offset / N, offset % N);
        if number >= REGISTERS {
            if byte != 0 {
                return Err(EniErrorKind::TooMany {
                    what,
                    number: number as u64,
                });
            }
            continue;
        }
        registers[number][at] = byte;
        *written |= 1 << number;
    }
    Ok(())
}

/// The registers written with something other than zeros: a register
/// cleared on the way to OP configures nothing.
fn configured<const N: usize>(
    registers: &[[u8; N]; REGISTERS],
    written: u16,
) -> impl Iterator<Item = (u8, [u8; N])> + '_ {
    (0u8..)
        .zip(registers.iter())
        .filter(move |&(n, bytes)| written & (1 << n) != 0 && bytes.iter().any(|&b| b != 0))
        .map(|(n, bytes)| (n, *bytes))
}

/// Whether an InitCmd runs on the way from INIT to OP: its transitions
/// hold IP, PS or SO, or it names none.
fn on_the_way_to_op(command: Node) -> bool {
    let mut transitions = children(command, "Transition").peekable();
    transitions.peek().is_none()
        || transitions.any(|t| matches!(text(t).to_ascii_uppercase().as_str(), "IP" | "PS" | "SO"))
}

/// An InitCmd's bytes: its `Data` in hex, or `DataLength` zeros.
fn data(command: Node) -> Result<Option<Vec<u8>>, EniError> {
    if let Some(node) = child(command, "Data") {
        return hex(node).map(Some);
    }
    Ok(child_number(command, "DataLength", 16)?.map(|len| vec![0; len as usize]))
}

fn hex(node: Node) -> Result<Vec<u8>, EniError> {
    let digits = text(node);
    let value = |b: u8| match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'a'..=b'f' => Some(b - b'a' + 10),
        b'A'..=b'F' => Some(b - b'A' + 10),
        _ => None,
    };
    let bytes: Option<Vec<u8>> = if digits.len() % 2 == 0 {
        digits
            .as_bytes()
            .chunks_exact(2)
            .map(|pair| Some(value(pair[0])? << 4 | value(pair[1])?))
            .collect()
    } else {
        None
    };
    bytes.ok_or_else(|| error(node, EniErrorKind::BadData(quoted(digits))))
}

/// A `ProcessData/RxPdo` or `TxPdo`: the PDO and the sync manager it is
/// assigned to (its `Sm` attribute or element), if any.
struct PdoElement {
    pdo: PdoConfig,
    sync_manager: Option<u8>,
}

fn pdo_element(node: Node) -> Result<PdoElement, EniError> {
    let index = required_number(node, "Index", 16)? as u16;
    let sync_manager = match (node.attribute("Sm"), child(node, "Sm")) {
        (Some(attribute), _) => Some(
            parse_number(attribute, 32)
                .and_then(sync_manager_number)
                .map_err(|kind| error(node, kind))?,
        ),
        (None, Some(element)) => Some(
            parse_number(text(element), 32)
                .and_then(sync_manager_number)
                .map_err(|kind| error(element, kind))?,
        ),
        (None, None) => None,
    };
    let entries = children(node, "Entry")
        .map(pdo_entry)
        .collect::<Result<_, _>>()?;
    Ok(PdoElement {
        pdo: PdoConfig { index, entries },
        sync_manager,
    })
}

fn pdo_entry(node: Node) -> Result<PdoEntryConfig, EniError> {
    let index = required_number(node, "Index", 16)? as u16;
    let sub_index = child_number(node, "SubIndex", 8)?.unwrap_or(0) as u8;
    let bit_len =
        child(node, "BitLen").ok_or_else(|| error(node, EniErrorKind::Missing("BitLen")))?;
    let bits = number_of(bit_len, 32)?;
    if bits == 0 || bits > 255 {
        return Err(error(bit_len, EniErrorKind::BitLen(bits)));
    }
    Ok(PdoEntryConfig {
        entry: MappingEntry::new(index, sub_index, bits as u8),
        name: child(node, "Name").and_then(nonempty_text),
        data_type: child(node, "DataType").and_then(|t| data_type(text(t))),
    })
}

/// The CiA 301 type of an ENI `DataType` (IEC 61131-3 and ETG.1020 names,
/// and the CiA 301 names themselves); `None` for a type CiA 301 has no
/// basic type for (BIT2…BIT8, arrays, structures). BYTE, WORD, DWORD and
/// LWORD, bit strings, read as the unsigned integers of their width.
fn data_type(name: &str) -> Option<DataType> {
    let name = name.trim().to_ascii_uppercase();
    let base = name.split('(').next().unwrap_or_default().trim_end();
    Some(match base {
        "BOOL" | "BIT" | "BIT1" => DataType::Boolean,
        "SINT" | "INT8" => DataType::Integer8,
        "INT" | "INT16" => DataType::Integer16,
        "INT24" => DataType::Integer24,
        "DINT" | "INT32" => DataType::Integer32,
        "INT40" => DataType::Integer40,
        "INT48" => DataType::Integer48,
        "INT56" => DataType::Integer56,
        "LINT" | "INT64" => DataType::Integer64,
        "USINT" | "UINT8" | "BYTE" => DataType::Unsigned8,
        "UINT" | "UINT16" | "WORD" => DataType::Unsigned16,
        "UINT24" => DataType::Unsigned24,
        "UDINT" | "UINT32" | "DWORD" => DataType::Unsigned32,
        "UINT40" => DataType::Unsigned40,
        "UINT48" => DataType::Unsigned48,
        "UINT56" => DataType::Unsigned56,
        "ULINT" | "UINT64" | "LWORD" => DataType::Unsigned64,
        "REAL" => DataType::Real32,
        "LREAL" => DataType::Real64,
        "STRING" => DataType::VisibleString,
        "WSTRING" => DataType::UnicodeString,
        other => return DataType::ALL.into_iter().find(|t| t.name() == other),
    })
}

/// The number of a `ProcessData` element named `Sm<n>`, `None` for an
/// element of another name.
fn sync_manager_element_number(name: &str) -> Option<Result<u8, EniErrorKind>> {
    let digits = name.strip_prefix("Sm")?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(sync_manager_number(digits.parse().unwrap_or(u64::MAX)))
}

fn sync_manager_number(number: u64) -> Result<u8, EniErrorKind> {
    if number < REGISTERS as u64 {
        Ok(number as u8)
    } else {
        Err(EniErrorKind::TooMany {
            what: "sync manager",
            number,
        })
    }
}

/// A `ProcessData/Sm<n>`: where the sync manager is and how it is set,
/// and the PDOs assigned to it.
struct SyncManagerElement {
    number: u8,
    start: Option<u16>,
    control: Option<u8>,
    enable: u8,
    default_size: Option<u16>,
    pdos: Vec<u16>,
}

fn sync_manager_element(node: Node, number: u8) -> Result<SyncManagerElement, EniError> {
    let enable = match child(node, "Enable") {
        None => 0,
        Some(enable) => match text(enable).to_ascii_lowercase().as_str() {
            "true" => 1,
            "false" => 0,
            _ => number_of(enable, 8)? as u8,
        },
    };
    Ok(SyncManagerElement {
        number,
        start: child_number(node, "StartAddress", 16)?.map(|n| n as u16),
        control: child_number(node, "ControlByte", 8)?.map(|n| n as u8),
        enable,
        default_size: child_number(node, "DefaultSize", 16)?.map(|n| n as u16),
        pdos: children(node, "Pdo")
            .map(|pdo| number_of(pdo, 16).map(|n| n as u16))
            .collect::<Result<_, _>>()?,
    })
}

/// The sync managers: the registers written on the way to OP; where none
/// is written, a `ProcessData/Sm<n>` with a start address (its length
/// from its assigned PDOs, else `DefaultSize`), else for SM0 and SM1 the
/// `Mailbox`'s `Send` and `Recv`.
fn sync_managers(
    registers: &Registers,
    elements: &[SyncManagerElement],
    mailbox: Option<Node>,
    config: &SlaveConfig,
) -> Result<Vec<(u8, SyncManager)>, EniError> {
    let mailbox_sm = |number: u8| -> Result<Option<SyncManager>, EniError> {
        let Some(mailbox) = mailbox else {
            return Ok(None);
        };
        let (names, control): (&[&str], u8) = if number == 0 {
            (&["Send"], MAILBOX_OUT_CONTROL)
        } else {
            (&["Recv", "Receive"], MAILBOX_IN_CONTROL)
        };
        let Some(node) = names.iter().find_map(|name| child(mailbox, name)) else {
            return Ok(None);
        };
        let (start, len) = (
            child_number(node, "Start", 16)?,
            child_number(node, "Length", 16)?,
        );
        Ok(start.zip(len).map(|(start, len)| SyncManager {
            start: start as u16,
            len: len as u16,
            control,
            status: 0,
            activate: 1,
        }))
    };
    let mut sync_managers = Vec::new();
    for number in 0..REGISTERS as u8 {
        let element = elements
            .iter()
            .find(|e| e.number == number && e.start.is_some());
        let sync_manager = match (registers.sync_manager(number), element) {
            (Some(written), _) => Some(written),
            (None, Some(element)) => Some(SyncManager {
                start: element.start.unwrap_or_default(),
                len: assigned_bytes(config, number)
                    .or(element.default_size)
                    .unwrap_or_default(),
                control: element.control.unwrap_or_default(),
                status: 0,
                activate: element.enable,
            }),
            (None, None) if number < 2 => mailbox_sm(number)?,
            (None, None) => None,
        };
        if let Some(sync_manager) = sync_manager {
            sync_managers.push((number, sync_manager));
        }
    }
    Ok(sync_managers)
}

/// The bytes of the PDOs assigned to a sync manager, when every one of
/// them is known.
fn assigned_bytes(config: &SlaveConfig, number: u8) -> Option<u16> {
    let (_, indices) = config.assignment.iter().find(|(n, _)| *n == number)?;
    let mut pdo_bits = BTreeMap::new();
    for pdo in &config.pdos {
        pdo_bits.entry(pdo.index).or_insert_with(|| {
            pdo.entries
                .iter()
                .map(|e| u64::from(e.entry.bits()))
                .sum::<u64>()
        });
    }
    let bits = indices
        .iter()
        .map(|index| pdo_bits.get(index))
        .sum::<Option<u64>>()?;
    u16::try_from(bits.div_ceil(8)).ok()
}

/// One CoE object an InitCmd downloads on the way to OP (0x1C10–0x1C1F,
/// 0x1600–0x17FF, 0x1A00–0x1BFF): sub-index 0 and the values of the
/// others, each with the line that wrote it.
#[derive(Default)]
struct CoeObject {
    count: Option<u8>,
    values: BTreeMap<u8, (u32, u32)>,
}

impl CoeObject {
    /// The values of sub-indices 1 to the count written (every one
    /// written when no count is).
    fn values(&self) -> Vec<(u32, u32)> {
        match self.count {
            Some(count) => (1..=count)
                .filter_map(|sub| self.values.get(&sub).copied())
                .collect(),
            None => self.values.values().copied().collect(),
        }
    }
}

/// The width of one value of a PDO assignment (2 bytes) or a PDO mapping
/// (4 bytes) object; `None` for another object.
fn coe_width(index: u16) -> Option<usize> {
    match index {
        0x1C10..=0x1C1F => Some(2),
        0x1600..=0x17FF | 0x1A00..=0x1BFF => Some(4),
        _ => None,
    }
}

/// The PDO assignment and mapping objects the `Mailbox/CoE/InitCmds`
/// download on the way to OP (`Ccs` 1 or none: a download), in order; a
/// complete access from sub-index 0 carries the count in 16 bits, then
/// the values.
fn coe_objects(slave: Node) -> Result<BTreeMap<u16, CoeObject>, EniError> {
    let mut objects: BTreeMap<u16, CoeObject> = BTreeMap::new();
    let commands = child(slave, "Mailbox")
        .and_then(|mailbox| child(mailbox, "CoE"))
        .into_iter()
        .flat_map(|coe| grandchildren(coe, "InitCmds", "InitCmd"));
    for command in commands {
        if !on_the_way_to_op(command) || child_number(command, "Ccs", 8)?.is_some_and(|c| c != 1) {
            continue;
        }
        let Some(index) = child_number(command, "Index", 16)? else {
            continue;
        };
        let index = index as u16;
        let Some(width) = coe_width(index) else {
            continue;
        };
        let sub_index = child_number(command, "SubIndex", 8)?.unwrap_or(0) as u8;
        let complete = command
            .attribute("CompleteAccess")
            .or_else(|| child(command, "CompleteAccess").map(text))
            .is_some_and(|t| matches!(t.trim().to_ascii_lowercase().as_str(), "1" | "true"));
        let Some(bytes) = data(command)? else {
            continue;
        };
        let line = line(command);
        let object = objects.entry(index).or_default();
        let (mut next, values) = match (sub_index, complete) {
            (0, complete) => {
                let Some(&count) = bytes.first() else {
                    continue;
                };
                object.count = Some(count);
                if !complete {
                    continue;
                }
                (1u8, bytes.get(2..).unwrap_or_default())
            }
            (sub, false) => {
                let value = little_endian(&bytes[..bytes.len().min(width)]);
                object.values.insert(sub, (value, line));
                continue;
            }
            (sub, true) => (sub, &bytes[..]),
        };
        for chunk in values.chunks_exact(width) {
            object.values.insert(next, (little_endian(chunk), line));
            let Some(after) = next.checked_add(1) else {
                break;
            };
            next = after;
        }
    }
    Ok(objects)
}

fn little_endian(bytes: &[u8]) -> u32 {
    bytes
        .iter()
        .rev()
        .fold(0, |value, &b| value << 8 | u32::from(b))
}

/// The entries of a PDO mapping object as the CoE InitCmds write it.
fn coe_entries(object: &CoeObject) -> Result<Vec<PdoEntryConfig>, EniError> {
    object
        .values()
        .into_iter()
        .map(|(raw, line)| {
            let entry = MappingEntry::from_u32(raw);
            if entry.bits() == 0 {
                return Err(EniError {
                    line,
                    element: Some("InitCmd".to_owned()),
                    kind: EniErrorKind::BitLen(0),
                });
            }
            Ok(PdoEntryConfig {
                entry,
                name: None,
                data_type: None,
            })
        })
        .collect()
}

/// The PDOs: every `RxPdo` and `TxPdo` in the file's order, assigned or
/// not (one without entries takes those the CoE InitCmds map), then the
/// mapping objects only the CoE InitCmds write.
fn pdos(
    elements: &[PdoElement],
    coe: &BTreeMap<u16, CoeObject>,
) -> Result<Vec<PdoConfig>, EniError> {
    let mut pdos = Vec::with_capacity(elements.len());
    for element in elements {
        let mut pdo = element.pdo.clone();
        if pdo.entries.is_empty() {
            if let Some(object) = coe.get(&pdo.index) {
                pdo.entries = coe_entries(object)?;
            }
        }
        pdos.push(pdo);
    }
    for (&index, object) in coe {
        if coe_width(index) == Some(4) && !elements.iter().any(|e| e.pdo.index == index) {
            pdos.push(PdoConfig {
                index,
                entries: coe_entries(object)?,
            });
        }
    }
    Ok(pdos)
}

/// The PDO assignment per sync manager: the `Pdo`s of its
/// `ProcessData/Sm<n>`, else the PDOs whose `Sm` names it, else object
/// 0x1C10 + n as the CoE InitCmds write it.
fn assignment(
    elements: &[PdoElement],
    sync_managers: &[SyncManagerElement],
    coe: &BTreeMap<u16, CoeObject>,
) -> Vec<(u8, Vec<u16>)> {
    (0..REGISTERS as u8)
        .filter_map(|number| {
            let listed = sync_managers
                .iter()
                .find(|e| e.number == number && !e.pdos.is_empty())
                .map(|e| e.pdos.clone());
            let attributed: Vec<u16> = elements
                .iter()
                .filter(|e| e.sync_manager == Some(number))
                .map(|e| e.pdo.index)
                .collect();
            let written = coe.get(&(0x1C10 + u16::from(number))).map(|object| {
                object
                    .values()
                    .into_iter()
                    .map(|(value, _)| value as u16)
                    .collect()
            });
            let indices = listed
                .or_else(|| (!attributed.is_empty()).then_some(attributed))
                .or(written)?;
            Some((number, indices))
        })
        .collect()
}

/// A `ProcessData/Send` or `Recv`: the slave's bits in the master's
/// process image.
#[derive(Clone, Copy)]
struct ImageRange {
    bit_start: u64,
    bit_length: u64,
}

fn image_range(node: Node) -> Result<ImageRange, EniError> {
    Ok(ImageRange {
        bit_start: child_number(node, "BitStart", 32)?.unwrap_or(0),
        bit_length: child_number(node, "BitLength", 32)?.unwrap_or(0),
    })
}

/// A logical command of a `Cyclic/Frame`: its logical address and length,
/// and where its datagram sits in the master's process image.
struct CyclicCommand {
    reads: bool,
    writes: bool,
    logical: u64,
    len: u64,
    input_offset: Option<u64>,
    output_offset: Option<u64>,
}

fn cyclic_commands(config: Node) -> Result<Vec<CyclicCommand>, EniError> {
    let mut commands = Vec::new();
    for frame in grandchildren(config, "Cyclic", "Frame") {
        for command in children(frame, "Cmd") {
            let (reads, writes) = match command_of(command)? {
                Some(Command::Lrd) => (true, false),
                Some(Command::Lwr) => (false, true),
                Some(Command::Lrw) => (true, true),
                _ => continue,
            };
            let Some(logical) = child_number(command, "Addr", 32)? else {
                continue;
            };
            commands.push(CyclicCommand {
                reads,
                writes,
                logical,
                len: child_number(command, "DataLength", 16)?.unwrap_or(0),
                input_offset: child_number(command, "InputOffs", 32)?,
                output_offset: child_number(command, "OutputOffs", 32)?,
            });
        }
    }
    Ok(commands)
}

/// The FMMU of a slave's outputs (`Send`) or inputs (`Recv`) where no
/// InitCmd writes one: its logical address from the cyclic command that
/// carries those bytes of the process image, its physical address the
/// first buffered sync manager of that direction. `None` when either is
/// not known.
fn derived_fmmu(
    range: ImageRange,
    output: bool,
    cyclic: &[CyclicCommand],
    sync_managers: &[(u8, SyncManager)],
) -> Option<Fmmu> {
    if range.bit_length == 0 {
        return None;
    }
    let byte = range.bit_start / 8;
    let logical = cyclic.iter().find_map(|command| {
        let offset = if output {
            command.output_offset.filter(|_| command.writes)
        } else {
            command.input_offset.filter(|_| command.reads)
        }?;
        let data = offset + DATAGRAM_HEADER;
        (data..data + command.len)
            .contains(&byte)
            .then(|| command.logical + (byte - data))
    })?;
    let (_, sync_manager) = sync_managers.iter().find(|(_, sm)| {
        sm.mode() == SyncManagerMode::Buffered && sm.written_by_master() == output
    })?;
    let first_bit = range.bit_start % 8;
    let last_bit = (range.bit_start + range.bit_length - 1) % 8;
    Some(Fmmu {
        logical: u32::try_from(logical).ok()?,
        len: u16::try_from((first_bit + range.bit_length).div_ceil(8)).ok()?,
        logical_start_bit: first_bit as u8,
        logical_end_bit: last_bit as u8,
        physical: sync_manager.start,
        physical_start_bit: 0,
        kind: if output { 0x02 } else { 0x01 },
        active: true,
    })
}

/// Read a number as the ENI writes it: decimal, `#x` hex (ETG's
/// HexDecValue), or `0x` hex; a negative decimal (xs:int) as its two's
/// complement in `bits` bits.
fn parse_number(text: &str, bits: u32) -> Result<u64, EniErrorKind> {
    let text = text.trim();
    let bad = || EniErrorKind::BadNumber(quoted(text));
    let out_of_range = || EniErrorKind::OutOfRange {
        text: quoted(text),
        bits,
    };
    let max = u64::MAX >> (64 - bits);
    let hex = ["#x", "#X", "0x", "0X"]
        .iter()
        .find_map(|prefix| text.strip_prefix(prefix));
    if let Some(digits) = hex {
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(bad());
        }
        let value = u64::from_str_radix(digits, 16).map_err(|_| out_of_range())?;
        return if value <= max {
            Ok(value)
        } else {
            Err(out_of_range())
        };
    }
    let (negative, digits) = match text.strip_prefix('-') {
        Some(digits) => (true, digits),
        None => (false, text),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    let value: u64 = digits.parse().map_err(|_| out_of_range())?;
    match negative {
        false if value <= max => Ok(value),
        true if value <= max / 2 + 1 => Ok(value.wrapping_neg() & max),
        _ => Err(out_of_range()),
    }
}

/// The datagram command an element's `Cmd` child names (ETG.1000.4 table
/// 14).
fn command_of(node: Node) -> Result<Option<Command>, EniError> {
    Ok(child_number(node, "Cmd", 8)?.map(|byte| Command::from_byte(byte as u8)))
}

fn number_of(node: Node, bits: u32) -> Result<u64, EniError> {
    parse_number(text(node), bits).map_err(|kind| error(node, kind))
}

fn child_number(node: Node, name: &str, bits: u32) -> Result<Option<u64>, EniError> {
    child(node, name).map(|c| number_of(c, bits)).transpose()
}

fn required_number(node: Node, name: &'static str, bits: u32) -> Result<u64, EniError> {
    let element = child(node, name).ok_or_else(|| error(node, EniErrorKind::Missing(name)))?;
    number_of(element, bits)
}

fn child<'a, 'input>(node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

fn children<'a, 'input: 'a>(
    node: Node<'a, 'input>,
    name: &'static str,
) -> impl Iterator<Item = Node<'a, 'input>> {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

fn grandchildren<'a, 'input: 'a>(
    node: Node<'a, 'input>,
    name: &'static str,
    inner: &'static str,
) -> impl Iterator<Item = Node<'a, 'input>> {
    children(node, name).flat_map(move |c| children(c, inner))
}

/// The element's text, trimmed (`""` when it has none).
fn text<'a>(node: Node<'a, '_>) -> &'a str {
    node.text().unwrap_or_default().trim()
}

fn nonempty_text(node: Node) -> Option<String> {
    Some(text(node))
        .filter(|t| !t.is_empty())
        .map(str::to_owned)
}

fn line(node: Node) -> u32 {
    node.document().text_pos_at(node.range().start).row
}

fn error(node: Node, kind: EniErrorKind) -> EniError {
    EniError {
        line: line(node),
        element: Some(node.tag_name().name().to_owned()),
        kind,
    }
}

/// At most the first 40 characters of a wrong text, for an error.
fn quoted(text: &str) -> String {
    text.chars().take(QUOTED).collect()
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// An ENI of one slave whose `Slave` element holds `body`.
    fn one(body: &str) -> Result<SlaveConfig, EniError> {
        let xml =
            format!("<EtherCATConfig><Config><Slave>{body}</Slave></Config></EtherCATConfig>");
        parse_eni(&xml).map(|mut slaves| slaves.remove(0))
    }

    fn init_cmd(transitions: &[&str], cmd: u8, ado: u16, data: &str) -> String {
        let transitions: String = transitions
            .iter()
            .map(|t| format!("<Transition>{t}</Transition>"))
            .collect();
        format!("<InitCmd>{transitions}<Cmd>{cmd}</Cmd><Adp>1001</Adp><Ado>{ado}</Ado><Data>{data}</Data></InitCmd>")
    }

    fn coe_cmd(index: &str, sub: u8, data: &str, complete: bool) -> String {
        let attribute = if complete {
            r#" CompleteAccess="1""#
        } else {
            ""
        };
        format!("<InitCmd{attribute}><Transition>PS</Transition><Ccs>1</Ccs><Index>{index}</Index><SubIndex>{sub}</SubIndex><Data>{data}</Data></InitCmd>")
    }

    fn entry(index: u16, sub_index: u8, bits: u8) -> PdoEntryConfig {
        PdoEntryConfig {
            entry: MappingEntry::new(index, sub_index, bits),
            name: None,
            data_type: None,
        }
    }

    #[test]
    fn info_gives_identity_and_addresses() {
        let slave = one(
            "<Info><Name><![CDATA[Term 2 (EL2008)]]></Name><PhysAddr>1002</PhysAddr>\
             <AutoIncAddr>65535</AutoIncAddr><VendorId>2</VendorId>\
             <ProductCode>#x07d83052</ProductCode><RevisionNo>#x00100000</RevisionNo></Info>",
        )
        .unwrap();
        assert_eq!(slave.name.as_deref(), Some("Term 2 (EL2008)"));
        assert_eq!((slave.station, slave.position), (Some(1002), Some(1)));
        assert_eq!((slave.vendor, slave.product), (Some(2), Some(0x07d8_3052)));
        assert!(slave.fmmus.is_empty() && slave.sync_managers.is_empty());
        assert!(slave.pdos.is_empty() && slave.assignment.is_empty());

        let bare = one("").unwrap();
        assert_eq!(bare, SlaveConfig::default());
    }

    #[test]
    fn auto_increment_address_is_the_negated_position() {
        for (written, position) in [
            ("0", 0),
            ("65535", 1),
            ("#xFFFE", 2),
            ("-3", 3),
            ("0xfff0", 16),
        ] {
            let slave = one(&format!(
                "<Info><AutoIncAddr>{written}</AutoIncAddr></Info>"
            ))
            .unwrap();
            assert_eq!(slave.position, Some(position), "{written}");
        }
    }

    #[test]
    fn numbers_in_every_notation() {
        let cases: [(&str, u32, Result<u64, EniErrorKind>); 14] = [
            ("4096", 16, Ok(4096)),
            (" #x1600 ", 16, Ok(0x1600)),
            ("#X1a00", 16, Ok(0x1A00)),
            ("0x1C12", 16, Ok(0x1C12)),
            ("0XFF", 8, Ok(0xFF)),
            ("-1", 16, Ok(0xFFFF)),
            ("-1", 32, Ok(0xFFFF_FFFF)),
            ("-32768", 16, Ok(0x8000)),
            (
                "65536",
                16,
                Err(EniErrorKind::OutOfRange {
                    text: "65536".into(),
                    bits: 16,
                }),
            ),
            (
                "-32769",
                16,
                Err(EniErrorKind::OutOfRange {
                    text: "-32769".into(),
                    bits: 16,
                }),
            ),
            (
                "#x100",
                8,
                Err(EniErrorKind::OutOfRange {
                    text: "#x100".into(),
                    bits: 8,
                }),
            ),
            ("#x", 16, Err(EniErrorKind::BadNumber("#x".into()))),
            ("0x+5", 16, Err(EniErrorKind::BadNumber("0x+5".into()))),
            ("12a", 16, Err(EniErrorKind::BadNumber("12a".into()))),
        ];
        for (text, bits, expected) in cases {
            assert_eq!(parse_number(text, bits), expected, "{text}");
        }
        assert_eq!(
            parse_number("99999999999999999999999", 32),
            Err(EniErrorKind::OutOfRange {
                text: "99999999999999999999999".into(),
                bits: 32
            })
        );
        assert_eq!(
            parse_number("", 8),
            Err(EniErrorKind::BadNumber(String::new()))
        );
    }

    #[test]
    fn init_cmds_on_the_way_to_op_write_the_registers() {
        let commands = [
            // The master clears SM0–SM1 in one 16-byte write, then sets them.
            init_cmd(&["IP", "PI", "SI", "OI"], 5, 0x0800, &"00".repeat(16)),
            init_cmd(&["IP"], 5, 0x0800, "0018f60026000100"),
            init_cmd(&["IP"], 2, 0x0808, "0018f60022000100"),
            // Bootstrap only: not on the way to OP.
            init_cmd(&["IB"], 5, 0x0808, "001c000422000100"),
            init_cmd(&["PS"], 5, 0x0810, "0011070064000100"),
            init_cmd(&["PS"], 5, 0x0818, "8011070020000100"),
            // The activate byte of SM3 alone, no transition named.
            "<InitCmd><Cmd>5</Cmd><Ado>#x81e</Ado><Data>00</Data></InitCmd>".to_owned(),
            init_cmd(&["PS"], 5, 0x0600, "0a000100070000070011000201000000"),
            init_cmd(&["PS"], 5, 0x0610, "40000100070000078011000101000000"),
            // Cleared on the way back, and a BWR: neither counts.
            init_cmd(&["SP", "SI", "OP", "OI"], 5, 0x0600, &"00".repeat(32)),
            init_cmd(&["PS"], 8, 0x0620, "01000000010000000d08000101000000"),
            // A cleared register configures nothing.
            "<InitCmd><Transition>IP</Transition><Cmd>5</Cmd><Ado>2096</Ado><DataLength>8</DataLength></InitCmd>".to_owned(),
        ];
        let slave = one(&format!("<InitCmds>{}</InitCmds>", commands.concat())).unwrap();
        let sm = |start, len, control, activate| SyncManager {
            start,
            len,
            control,
            status: 0,
            activate,
        };
        assert_eq!(
            slave.sync_managers,
            vec![
                (0, sm(0x1800, 0xf6, 0x26, 1)),
                (1, sm(0x1800, 0xf6, 0x22, 1)),
                (2, sm(0x1100, 7, 0x64, 1)),
                (3, sm(0x1180, 7, 0x20, 0)),
            ]
        );
        let fmmu = |logical, physical, kind| Fmmu {
            logical,
            len: 7,
            logical_start_bit: 0,
            logical_end_bit: 7,
            physical,
            physical_start_bit: 0,
            kind,
            active: true,
        };
        assert_eq!(
            slave.fmmus,
            vec![
                (0, fmmu(0x0001_000A, 0x1100, 2)),
                (1, fmmu(0x0001_0040, 0x1180, 1))
            ]
        );
    }

    #[test]
    fn a_write_across_areas_reaches_each_register() {
        // From SM15's last bytes into the reserved window: zeros there are
        // a clear, not a 17th sync manager.
        let slave = one(&format!(
            "<InitCmds>{}</InitCmds>",
            init_cmd(&["PS"], 5, 0x0878, "00100100640001000000000000000000")
        ))
        .unwrap();
        assert_eq!(slave.sync_managers.len(), 1);
        assert_eq!(slave.sync_managers[0].0, 15);
        assert_eq!(slave.sync_managers[0].1.start, 0x1000);
    }

    #[test]
    fn process_data_and_mailbox_give_what_no_register_write_does() {
        let slave = one(&(
            "<ProcessData>\
               <Sm2><Type>Outputs</Type><DefaultSize>32</DefaultSize><StartAddress>#x1100</StartAddress>\
                 <ControlByte>100</ControlByte><Enable>1</Enable><Pdo>#x1601</Pdo></Sm2>\
               <Sm3><Type>Inputs</Type><DefaultSize>32</DefaultSize><StartAddress>4480</StartAddress>\
                 <ControlByte>#x20</ControlByte><Enable>true</Enable></Sm3>\
               <Sm4><Type>Outputs</Type></Sm4>\
               <RxPdo Fixed=\"true\"><Index>#x1601</Index><Name>Outputs</Name>\
                 <Entry><Index>#x60ff</Index><SubIndex>0</SubIndex><BitLen>32</BitLen></Entry>\
                 <Entry><Index>#x6040</Index><SubIndex>0</SubIndex><BitLen>16</BitLen></Entry></RxPdo>\
             </ProcessData>\
             <Mailbox><Send><Start>6144</Start><Length>140</Length></Send>\
               <Receive><Start>6400</Start><Length>140</Length></Receive></Mailbox>\
             <InitCmds>".to_owned()
                + &init_cmd(&["IP"], 5, 0x0800, "0010800026000100")
                + "</InitCmds>"),
        )
        .unwrap();
        let sm = |start, len, control, activate| SyncManager {
            start,
            len,
            control,
            status: 0,
            activate,
        };
        assert_eq!(
            slave.sync_managers,
            vec![
                // Written: the mailbox's Send does not replace it.
                (0, sm(0x1000, 0x80, 0x26, 1)),
                // SOEM's <Receive> for <Recv>.
                (1, sm(6400, 140, 0x22, 1)),
                // The length of the assigned PDO, not DefaultSize.
                (2, sm(0x1100, 6, 0x64, 1)),
                // Nothing assigned: DefaultSize.
                (3, sm(4480, 32, 0x20, 1)),
            ]
        );
        assert_eq!(slave.assignment, vec![(2, vec![0x1601])]);
    }

    #[test]
    fn pdo_elements_give_mapping_names_types_and_assignment() {
        let slave = one(
            "<ProcessData>\
               <RxPdo Sm=\"2\" Fixed=\"1\"><Index>#x1600</Index><Name>Outputs</Name>\
                 <Entry><Index>#x6040</Index><SubIndex>0</SubIndex><BitLen>16</BitLen>\
                   <Name>Controlword</Name><DataType>UINT</DataType></Entry>\
                 <Entry><Index>#x0</Index><BitLen>8</BitLen></Entry>\
                 <Entry><Index>#x607A</Index><SubIndex>#x00</SubIndex><BitLen>32</BitLen>\
                   <Name>Target position</Name><DataType>DINT</DataType></Entry></RxPdo>\
               <RxPdo><Index>#x1601</Index><Exclude>#x1600</Exclude>\
                 <Entry><Index>#x60FF</Index><SubIndex>0</SubIndex><BitLen>32</BitLen></Entry></RxPdo>\
               <TxPdo><Sm>3</Sm><Index>6656</Index>\
                 <Entry><Index>#x6000</Index><SubIndex>1</SubIndex><BitLen>1</BitLen>\
                   <Name></Name><DataType>BOOL</DataType></Entry></TxPdo>\
               <TxPdo Sm=\"3\"><Index>#x1a01</Index></TxPdo>\
             </ProcessData>",
        )
        .unwrap();
        let named = |index, sub, bits, name: &str, data_type| PdoEntryConfig {
            entry: MappingEntry::new(index, sub, bits),
            name: Some(name.to_owned()),
            data_type: Some(data_type),
        };
        assert_eq!(
            slave.pdos,
            vec![
                PdoConfig {
                    index: 0x1600,
                    entries: vec![
                        named(0x6040, 0, 16, "Controlword", DataType::Unsigned16),
                        // A gap stays in the list.
                        entry(0, 0, 8),
                        named(0x607A, 0, 32, "Target position", DataType::Integer32),
                    ],
                },
                // Listed though not assigned.
                PdoConfig {
                    index: 0x1601,
                    entries: vec![entry(0x60FF, 0, 32)]
                },
                PdoConfig {
                    index: 0x1A00,
                    entries: vec![PdoEntryConfig {
                        data_type: Some(DataType::Boolean),
                        ..entry(0x6000, 1, 1)
                    }],
                },
                PdoConfig {
                    index: 0x1A01,
                    entries: vec![]
                },
            ]
        );
        assert_eq!(
            slave.assignment,
            vec![(2, vec![0x1600]), (3, vec![0x1A00, 0x1A01])]
        );
    }

    #[test]
    fn sync_manager_elements_list_the_assignment_before_pdo_attributes() {
        let slave = one(
            "<ProcessData>\
               <Sm2><StartAddress>4352</StartAddress><ControlByte>100</ControlByte><Enable>1</Enable>\
                 <Pdo>5633</Pdo></Sm2>\
               <RxPdo Sm=\"2\"><Index>#x1600</Index></RxPdo>\
               <RxPdo><Index>#x1601</Index></RxPdo>\
             </ProcessData>",
        )
        .unwrap();
        assert_eq!(slave.assignment, vec![(2, vec![0x1601])]);
    }

    #[test]
    fn coe_init_cmds_give_what_the_pdo_elements_do_not() {
        let coe = [
            // TwinCAT: count cleared, each sub-index, then the count.
            coe_cmd("7186", 0, "00", false),
            coe_cmd("#x1600", 0, "00", false),
            coe_cmd("#x1600", 1, "10004060", false),
            coe_cmd("#x1600", 2, "20007a60", false),
            coe_cmd("#x1600", 0, "02", false),
            coe_cmd("7186", 1, "0016", false),
            coe_cmd("7186", 0, "01", false),
            // SOEM: complete access, sub-index 0 in 16 bits, then the values.
            coe_cmd("0x1c13", 0, "0200001a011a", true),
            coe_cmd("#x1a00", 0, "0200100041602000646000000000", true),
            // Complete access from sub-index 1 keeps the count.
            coe_cmd("#x1a01", 0, "01", false),
            coe_cmd("#x1a01", 1, "08006160", true),
            // An upload, a back transition, another object: not read.
            "<InitCmd><Transition>PS</Transition><Ccs>2</Ccs><Index>#x1c12</Index><SubIndex>1</SubIndex><Data>0216</Data></InitCmd>".to_owned(),
            "<InitCmd><Transition>SP</Transition><Ccs>1</Ccs><Index>#x1c12</Index><SubIndex>0</SubIndex><Data>00</Data></InitCmd>".to_owned(),
            coe_cmd("#x6060", 0, "08", false),
        ];
        let slave = one(&format!(
            "<ProcessData><RxPdo Fixed=\"true\"><Index>#x1600</Index><Name>Outputs</Name></RxPdo></ProcessData>\
             <Mailbox><CoE><InitCmds>{}</InitCmds></CoE></Mailbox>",
            coe.concat()
        ))
        .unwrap();
        assert_eq!(
            slave.assignment,
            vec![(2, vec![0x1600]), (3, vec![0x1A00, 0x1A01])]
        );
        assert_eq!(
            slave.pdos,
            vec![
                // The element without entries takes the downloaded ones.
                PdoConfig {
                    index: 0x1600,
                    entries: vec![entry(0x6040, 0, 16), entry(0x607A, 0, 32)]
                },
                PdoConfig {
                    index: 0x1A00,
                    entries: vec![entry(0x6041, 0, 16), entry(0x6064, 0, 32)]
                },
                PdoConfig {
                    index: 0x1A01,
                    entries: vec![entry(0x6061, 0, 8)]
                },
            ]
        );
    }

    #[test]
    fn pdo_elements_win_over_coe_init_cmds() {
        let slave = one(&format!(
            "<ProcessData><RxPdo Sm=\"2\"><Index>#x1600</Index>\
               <Entry><Index>#x6040</Index><SubIndex>0</SubIndex><BitLen>16</BitLen></Entry></RxPdo></ProcessData>\
             <Mailbox><CoE><InitCmds>{}{}</InitCmds></CoE></Mailbox>",
            coe_cmd("#x1c12", 0, "0200011602160000", true),
            coe_cmd("#x1600", 0, "01000800606000", true),
        ))
        .unwrap();
        assert_eq!(slave.assignment, vec![(2, vec![0x1600])]);
        assert_eq!(
            slave.pdos,
            vec![PdoConfig {
                index: 0x1600,
                entries: vec![entry(0x6040, 0, 16)]
            }]
        );
    }

    #[test]
    fn send_and_recv_give_the_fmmus_where_no_init_cmd_writes_them() {
        // One LRW of 78 bytes at 0x00010000 whose datagram starts at byte
        // 16 of the image: its data at byte 26 (bit 208).
        let cyclic = "<Cyclic><Frame>\
            <Cmd><Cmd>7</Cmd><Adp>0</Adp><Ado>304</Ado><DataLength>2</DataLength><InputOffs>0</InputOffs></Cmd>\
            <Cmd><Cmd>12</Cmd><Addr>65536</Addr><DataLength>78</DataLength><InputOffs>16</InputOffs><OutputOffs>16</OutputOffs></Cmd>\
            </Frame></Cyclic>";
        let slave = |extra: &str| {
            let xml = format!(
                "<EtherCATConfig><Config><Slave><ProcessData>\
                   <Send><BitStart>288</BitStart><BitLength>56</BitLength></Send>\
                   <Recv><BitStart>723</BitStart><BitLength>4</BitLength></Recv>\
                 </ProcessData><InitCmds>{}{}{extra}</InitCmds></Slave>{cyclic}</Config></EtherCATConfig>",
                init_cmd(&["PS"], 5, 0x0810, "0011070064000100"),
                init_cmd(&["PS"], 5, 0x0818, "8011070020000100"),
            );
            parse_eni(&xml).unwrap().remove(0)
        };
        let derived = slave("");
        let output = Fmmu {
            logical: 0x0001_000A,
            len: 7,
            logical_start_bit: 0,
            logical_end_bit: 7,
            physical: 0x1100,
            physical_start_bit: 0,
            kind: 2,
            active: true,
        };
        // Bits 3–6 of image byte 90: logical 0x00010040.
        let input = Fmmu {
            logical: 0x0001_0040,
            len: 1,
            logical_start_bit: 3,
            logical_end_bit: 6,
            physical: 0x1180,
            kind: 1,
            ..output
        };
        assert_eq!(derived.fmmus, vec![(0, output), (1, input)]);
        // One written FMMU: the registers are the truth, nothing derived.
        let written = slave(&init_cmd(
            &["PS"],
            5,
            0x0600,
            "00000200010000070011000201000000",
        ));
        assert_eq!(written.fmmus.len(), 1);
        assert_eq!(written.fmmus[0].1.logical, 0x0002_0000);
    }

    #[test]
    fn data_types_by_iec_etg_and_cia_names() {
        let cases = [
            ("BOOL", Some(DataType::Boolean)),
            ("BIT", Some(DataType::Boolean)),
            ("BIT2", None),
            ("BIT8", None),
            ("SINT", Some(DataType::Integer8)),
            ("INT", Some(DataType::Integer16)),
            ("DINT", Some(DataType::Integer32)),
            ("LINT", Some(DataType::Integer64)),
            ("USINT", Some(DataType::Unsigned8)),
            ("UINT", Some(DataType::Unsigned16)),
            ("UDINT", Some(DataType::Unsigned32)),
            ("ULINT", Some(DataType::Unsigned64)),
            ("REAL", Some(DataType::Real32)),
            ("LREAL", Some(DataType::Real64)),
            ("BYTE", Some(DataType::Unsigned8)),
            ("WORD", Some(DataType::Unsigned16)),
            ("DWORD", Some(DataType::Unsigned32)),
            ("STRING(10)", Some(DataType::VisibleString)),
            ("uint16", Some(DataType::Unsigned16)),
            ("INT24", Some(DataType::Integer24)),
            ("UNSIGNED40", Some(DataType::Unsigned40)),
            ("TIME_OF_DAY", Some(DataType::TimeOfDay)),
            ("ARRAY [0..3] OF BYTE", None),
            ("", None),
        ];
        for (name, expected) in cases {
            assert_eq!(data_type(name), expected, "{name}");
        }
    }

    #[test]
    fn errors_say_line_element_and_what() {
        let error = parse_eni("<EtherCATConfig>\n<Config>\n</Slave>").unwrap_err();
        assert_eq!((error.line, error.element.as_deref()), (3, None));
        assert!(
            matches!(error.kind, EniErrorKind::Xml { column: 1, .. }),
            "{error}"
        );
        assert!(
            error.to_string().starts_with("line 3: not XML: "),
            "{error}"
        );

        let dtd = "<!DOCTYPE x [<!ENTITY a \"b\">]><EtherCATConfig/>";
        assert!(matches!(
            parse_eni(dtd).unwrap_err().kind,
            EniErrorKind::Xml { .. }
        ));

        let error = parse_eni("<?xml version=\"1.0\"?>\n<EtherCATInfo/>").unwrap_err();
        assert_eq!(error.kind, EniErrorKind::NotEni("EtherCATInfo".into()));
        assert_eq!(
            error.to_string(),
            "line 2, <EtherCATInfo>: the root element is <EtherCATInfo>, not <EtherCATConfig>: not an ENI file"
        );
        assert_eq!(
            parse_eni("<EtherCATConfig/>").unwrap_err().kind,
            EniErrorKind::Missing("Config")
        );
        assert_eq!(
            parse_eni("<EtherCATConfig><Config/></EtherCATConfig>"),
            Ok(vec![])
        );

        let error = one("\n<Info>\n<PhysAddr>10O1</PhysAddr></Info>").unwrap_err();
        assert_eq!(
            error,
            EniError {
                line: 3,
                element: Some("PhysAddr".into()),
                kind: EniErrorKind::BadNumber("10O1".into())
            }
        );
        assert_eq!(
            error.to_string(),
            "line 3, <PhysAddr>: expected a decimal or #x hex number, found \"10O1\""
        );
        let error = one("<Info><VendorId>#x100000000</VendorId></Info>").unwrap_err();
        assert_eq!(
            error.kind,
            EniErrorKind::OutOfRange {
                text: "#x100000000".into(),
                bits: 32
            }
        );

        let error = one(&format!(
            "<InitCmds>{}</InitCmds>",
            init_cmd(&["PS"], 5, 0x0800, "00112")
        ))
        .unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("Data"), EniErrorKind::BadData("00112".into()))
        );
        let error = one(&format!(
            "<InitCmds>{}</InitCmds>",
            init_cmd(&["PS"], 5, 0x0800, "zz")
        ))
        .unwrap_err();
        assert_eq!(error.kind, EniErrorKind::BadData("zz".into()));
        let long = "x".repeat(100);
        let error = one(&format!(
            "<InitCmds>{}</InitCmds>",
            init_cmd(&["PS"], 5, 0x0800, &long)
        ))
        .unwrap_err();
        assert_eq!(error.kind, EniErrorKind::BadData("x".repeat(40)));
    }

    #[test]
    fn more_than_sixteen_fmmus_or_sync_managers_is_an_error() {
        let too_many = |what, number| EniErrorKind::TooMany { what, number };
        let error = one(&format!(
            "<InitCmds>{}</InitCmds>",
            init_cmd(&["PS"], 5, 0x0700, "01")
        ))
        .unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("InitCmd"), too_many("FMMU", 16))
        );
        let error = one(&format!(
            "<InitCmds>{}</InitCmds>",
            init_cmd(&["IP"], 5, 0x0888, "0010")
        ))
        .unwrap_err();
        assert_eq!(error.kind, too_many("sync manager", 17));
        assert_eq!(
            error.to_string(),
            "line 1, <InitCmd>: sync manager 17: an ESC has 16 (0-15)"
        );
        let error =
            one("<ProcessData><Sm16><StartAddress>4096</StartAddress></Sm16></ProcessData>")
                .unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("Sm16"), too_many("sync manager", 16))
        );
        let error = one("<ProcessData><Sm99999999999999999999/></ProcessData>").unwrap_err();
        assert_eq!(error.kind, too_many("sync manager", u64::MAX));
        let error =
            one("<ProcessData><RxPdo Sm=\"16\"><Index>#x1600</Index></RxPdo></ProcessData>")
                .unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("RxPdo"), too_many("sync manager", 16))
        );
        let error =
            one("<ProcessData><TxPdo><Index>#x1a00</Index><Sm>#x20</Sm></TxPdo></ProcessData>")
                .unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("Sm"), too_many("sync manager", 32))
        );
        // An element that only starts with "Sm" is no sync manager.
        assert!(one("<ProcessData><SmFoo/><Sm/></ProcessData>").is_ok());
    }

    #[test]
    fn a_pdo_entry_needs_an_index_and_a_bit_length_of_1_to_255() {
        let pdo = |entry: &str| {
            one(&format!("<ProcessData><RxPdo><Index>#x1600</Index><Entry>{entry}</Entry></RxPdo></ProcessData>"))
        };
        let error = pdo("<Index>#x6040</Index><BitLen>0</BitLen>").unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("BitLen"), EniErrorKind::BitLen(0))
        );
        assert_eq!(
            pdo("<Index>#x6040</Index><BitLen>256</BitLen>")
                .unwrap_err()
                .kind,
            EniErrorKind::BitLen(256)
        );
        assert!(pdo("<Index>#x6040</Index><BitLen>255</BitLen>").is_ok());
        let error = pdo("<Index>#x6040</Index>").unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("Entry"), EniErrorKind::Missing("BitLen"))
        );
        assert_eq!(
            pdo("<BitLen>8</BitLen>").unwrap_err().kind,
            EniErrorKind::Missing("Index")
        );
        let error = one("<ProcessData><TxPdo><Name>x</Name></TxPdo></ProcessData>").unwrap_err();
        assert_eq!(
            (error.element.as_deref(), error.kind),
            (Some("TxPdo"), EniErrorKind::Missing("Index"))
        );
        // A mapping entry downloaded with length 0: the InitCmd's line.
        let error = one(&format!(
            "<Mailbox><CoE><InitCmds>\n{}</InitCmds></CoE></Mailbox>",
            coe_cmd("#x1600", 1, "00004060", false)
        ))
        .unwrap_err();
        assert_eq!(
            error,
            EniError {
                line: 2,
                element: Some("InitCmd".into()),
                kind: EniErrorKind::BitLen(0)
            }
        );
    }

    /// Text shaped like an ENI: its elements, numbers in every notation,
    /// hex data, and noise.
    fn eni_like_text() -> impl Strategy<Value = String> {
        let element = prop_oneof![
            Just("<Slave>".to_owned()),
            Just("</Slave>".to_owned()),
            "<(Info|ProcessData|Mailbox|CoE|InitCmds|InitCmd|Entry|Send|Recv|Sm[0-9]{1,2}|Cyclic|Frame|Cmd)>",
            "</(Info|ProcessData|Mailbox|CoE|InitCmds|InitCmd|Entry|Send|Recv|Sm[0-9]{1,2}|Cyclic|Frame|Cmd)>",
            "<(Rx|Tx)Pdo( Sm=\"[0-9]{1,2}\")?>",
            "</(Rx|Tx)Pdo>",
            "<(PhysAddr|AutoIncAddr|Cmd|Ado|Index|SubIndex|BitLen|Ccs|Pdo|StartAddress|BitStart|BitLength|Addr|DataLength|InputOffs|OutputOffs)>(#x|0x|-)?[0-9a-fA-F]{0,9}</[A-Za-z]{2,12}>",
            "<Transition>(IP|PS|SO|SP|IB)</Transition>",
            "<Data>[0-9a-f]{0,40}</Data>",
            "<DataType>[A-Z]{2,6}</DataType>",
            "[ -~]{0,12}",
        ];
        proptest::collection::vec(element, 0..60).prop_map(|parts| {
            format!(
                "<EtherCATConfig><Config>{}</Config></EtherCATConfig>",
                parts.concat()
            )
        })
    }

    fn check(text: &str) {
        match parse_eni(text) {
            Ok(slaves) => {
                for slave in slaves {
                    assert!(
                        slave.fmmus.len() <= REGISTERS && slave.sync_managers.len() <= REGISTERS
                    );
                    assert!(slave.fmmus.iter().all(|&(n, _)| usize::from(n) < REGISTERS));
                    assert!(slave
                        .sync_managers
                        .iter()
                        .all(|&(n, _)| usize::from(n) < REGISTERS));
                    assert!(slave
                        .assignment
                        .iter()
                        .all(|(n, _)| usize::from(*n) < REGISTERS));
                    for pdo in &slave.pdos {
                        assert!(pdo.entries.iter().all(|e| e.entry.bits() > 0));
                    }
                }
            }
            Err(error) => {
                let lines = u32::try_from(text.split('\n').count()).unwrap_or(u32::MAX);
                assert!(error.line >= 1 && error.line <= lines, "{error}");
                let _ = error.to_string();
            }
        }
    }

    proptest! {
        #[test]
        fn any_eni_like_text_reads_without_panic(text in eni_like_text()) {
            check(&text);
        }

        #[test]
        fn any_text_reads_without_panic(text in ".{0,300}") {
            check(&text);
        }

        #[test]
        fn any_bytes_read_without_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
            check(&String::from_utf8_lossy(&bytes));
        }
    }
}
