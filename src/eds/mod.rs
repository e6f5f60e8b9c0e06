//! The CiA 306 electronic data sheet (EDS) and device configuration file
//! (DCF) reader (feature `eds`; docs/canopen.md#eds).
//!
//! An EDS describes a device's object dictionary; a DCF is an EDS with the
//! values of one configured node. [`Eds::parse`] reads either into the
//! objects, their names, data types and values, and [`Eds::pdos`] builds
//! each PDO's communication parameters and mapping, so that a decoder can
//! map a COB-ID to the PDO's signals with their names and types.
//!
//! - Sections `[1000]` (an object), `[1A00sub1]` (a sub-index, hex),
//!   `[3004Name]` / `[3004Value]` (the names and values of an array stored
//!   with `CompactSubObj`) and `[DeviceComissioning]` (CiA 306's spelling;
//!   `DeviceCommissioning` is read too). Other sections are ignored.
//! - Keys `ParameterName`, `ObjectType` (7 when absent), `DataType`,
//!   `AccessType`, `DefaultValue`, `ParameterValue`, `PDOMapping`,
//!   `SubNumber`, `CompactSubObj`; any ASCII case.
//! - A DCF's `ParameterValue` wins over `DefaultValue` (CiA 306;
//!   python-canopen does the same).
//! - Integers in decimal, hex (`0x`) or octal (leading `0`); `$NODEID`
//!   expressions (`$NODEID+0x180`, `0x180+$NODEID`, any case, spaces
//!   allowed) resolve to the node-ID given, else to `[DeviceComissioning]
//!   NodeID`; with neither, such a value is an error.
//! - Names: an object's `ParameterName`; for a sub-entry of an ARRAY or
//!   RECORD, `Record name.Sub-entry name` (docs/canopen.md#signals;
//!   python-canopen's `qualname`).
//!
//! Every error names the file (as the caller calls it), the line, and the
//! section and key where there is one: [`EdsError`].
//!
//! ```
//! use motionwire::canopen::{DataType, NodeId, PdoDirection, Value};
//! use motionwire::eds::Eds;
//!
//! let text = "\
//! [1000]
//! ParameterName=Device type
//! DataType=0x0007
//! AccessType=ro
//! DefaultValue=0x00020192
//!
//! [1800]
//! ParameterName=TPDO 1 communication parameter
//! ObjectType=0x9
//! SubNumber=2
//!
//! [1800sub1]
//! ParameterName=COB-ID
//! DataType=0x0007
//! AccessType=rw
//! DefaultValue=$NODEID+0x180
//!
//! [1A00]
//! ParameterName=TPDO 1 mapping parameter
//! ObjectType=0x9
//! SubNumber=2
//!
//! [1A00sub0]
//! ParameterName=Number of mapped objects
//! DataType=0x0005
//! AccessType=rw
//! DefaultValue=1
//!
//! [1A00sub1]
//! ParameterName=Mapping entry 1
//! DataType=0x0007
//! AccessType=rw
//! DefaultValue=0x60410010
//!
//! [6041]
//! ParameterName=Statusword
//! DataType=0x0006
//! AccessType=ro
//! PDOMapping=1
//! ";
//! let eds = Eds::parse(text, "drive.eds", NodeId::new(5))?;
//! assert_eq!(eds.device_type(), Some(0x0002_0192));
//! assert!(eds.is_cia402());
//! assert_eq!(eds.name(0x1800, 1), Some("TPDO 1 communication parameter.COB-ID"));
//!
//! let pdos = eds.pdos()?;
//! let tpdo1 = &pdos[0];
//! assert_eq!((tpdo1.direction, tpdo1.number), (PdoDirection::Transmit, 1));
//! assert_eq!(tpdo1.communication.cob_id.to_u32(), 0x185);
//! assert_eq!(tpdo1.signals[0].name.as_deref(), Some("Statusword"));
//! assert_eq!(tpdo1.signals[0].data_type, Some(DataType::Unsigned16));
//! let signal = tpdo1.unpack(&[0x37, 0x02]).next().unwrap()?;
//! assert_eq!(signal.value, Value::Unsigned(0x0237));
//!
//! // Errors say where.
//! let error = Eds::parse("[1000]\nDataType=0x0007\n", "bad.eds", None).unwrap_err();
//! assert_eq!(error.to_string(), "bad.eds:1: [1000] ParameterName: the key is missing");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod ini;
mod value;

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

pub use ini::{IniEntry, IniError, IniErrorKind, IniFile, IniSection};
pub use value::EdsValue;
use value::ValueError;

use crate::canopen::{
    DataType, EventTimer, InhibitTime, MappingEntry, NodeId, ObjectAddress, PdoCobId,
    PdoCommunication, PdoDirection, PdoMapping, Signals, TransmissionType, TypeLookup,
};

/// The object type of an object-dictionary entry (CiA 301 object codes;
/// CiA 306 `ObjectType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ObjectType {
    /// 0x0 NULL.
    Null,
    /// 0x2 DOMAIN.
    Domain,
    /// 0x5 DEFTYPE.
    DefType,
    /// 0x6 DEFSTRUCT.
    DefStruct,
    /// 0x7 VAR.
    Var,
    /// 0x8 ARRAY.
    Array,
    /// 0x9 RECORD.
    Record,
}

impl ObjectType {
    /// Return the object type of code `code`, or `None` for another code.
    #[must_use]
    pub const fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            0x0 => ObjectType::Null,
            0x2 => ObjectType::Domain,
            0x5 => ObjectType::DefType,
            0x6 => ObjectType::DefStruct,
            0x7 => ObjectType::Var,
            0x8 => ObjectType::Array,
            0x9 => ObjectType::Record,
            _ => return None,
        })
    }

    /// Return whether objects of this type have sub-indices of their own
    /// (ARRAY, RECORD, DEFSTRUCT).
    #[must_use]
    pub const fn is_compound(self) -> bool {
        matches!(
            self,
            ObjectType::Array | ObjectType::Record | ObjectType::DefStruct
        )
    }
}

/// The access type of an entry (CiA 306 `AccessType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AccessType {
    /// `ro`: read only.
    ReadOnly,
    /// `wo`: write only.
    WriteOnly,
    /// `rw`: read and write.
    ReadWrite,
    /// `rwr`: read and write, mapped in TPDOs.
    ReadWriteRead,
    /// `rww`: read and write, mapped in RPDOs.
    ReadWriteWrite,
    /// `const`: constant.
    Const,
}

impl AccessType {
    /// Return the access type written `text` (any case), or `None`.
    #[must_use]
    pub fn from_text(text: &str) -> Option<Self> {
        Some(match text.to_ascii_lowercase().as_str() {
            "ro" => AccessType::ReadOnly,
            "wo" => AccessType::WriteOnly,
            "rw" => AccessType::ReadWrite,
            "rwr" => AccessType::ReadWriteRead,
            "rww" => AccessType::ReadWriteWrite,
            "const" => AccessType::Const,
            _ => return None,
        })
    }

    /// Return the access type as CiA 306 writes it, e.g. `"rw"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            AccessType::ReadOnly => "ro",
            AccessType::WriteOnly => "wo",
            AccessType::ReadWrite => "rw",
            AccessType::ReadWriteRead => "rwr",
            AccessType::ReadWriteWrite => "rww",
            AccessType::Const => "const",
        }
    }
}

/// One object of the dictionary: `[1A00]` and its sub-entries.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// The index.
    pub index: u16,
    /// Its `ParameterName`.
    pub name: String,
    /// Its `ObjectType`.
    pub object_type: ObjectType,
    /// Its `SubNumber`, where written.
    pub sub_number: Option<u8>,
    /// The line of its section header.
    pub line: usize,
    entries: BTreeMap<u8, Entry>,
}

impl Object {
    /// Return the entry at `sub_index` (sub-index 0 of a VAR is the VAR).
    #[must_use]
    pub fn entry(&self, sub_index: u8) -> Option<&Entry> {
        self.entries.get(&sub_index)
    }

    /// Return the entries in sub-index order.
    pub fn entries(&self) -> impl Iterator<Item = &Entry> {
        self.entries.values()
    }
}

/// One value-holding entry: a VAR, or one sub-index of an ARRAY or RECORD.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The object's index.
    pub index: u16,
    /// The sub-index.
    pub sub_index: u8,
    /// The name a signal gets (docs/canopen.md#signals): `ParameterName`, or
    /// for a sub-entry of an ARRAY or RECORD `Record name.Sub-entry name`.
    pub name: String,
    /// The entry's own `ParameterName`.
    pub parameter_name: String,
    /// The data type, when it is a CiA 301 basic type.
    pub data_type: Option<DataType>,
    /// The `DataType` as written (also for complex and manufacturer types).
    pub data_type_index: Option<u16>,
    /// The `AccessType`.
    pub access_type: Option<AccessType>,
    /// The `PDOMapping` flag.
    pub pdo_mapping: bool,
    /// The `DefaultValue`.
    pub default_value: Option<EdsValue>,
    /// The `ParameterValue` (DCF).
    pub parameter_value: Option<EdsValue>,
    /// The line of its section header.
    pub line: usize,
}

impl Entry {
    /// Return the value: the DCF's `ParameterValue` when written, else the
    /// `DefaultValue` (CiA 306; docs/canopen.md#eds).
    #[must_use]
    pub fn value(&self) -> Option<&EdsValue> {
        self.parameter_value
            .as_ref()
            .or(self.default_value.as_ref())
    }
}

/// A signal of a PDO as the file describes it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SignalInfo {
    /// The mapping entry.
    pub entry: MappingEntry,
    /// The mapped object's name ([`Entry::name`]), when the file has it.
    pub name: Option<String>,
    /// The mapped object's data type, when the file gives a basic type.
    pub data_type: Option<DataType>,
}

/// One PDO of the file: its communication parameters, mapping and the
/// names and types of its signals (docs/canopen.md#eds,
/// docs/canopen.md#signals).
#[derive(Debug, Clone, PartialEq)]
pub struct EdsPdo {
    /// TPDO (1800h–19FFh) or RPDO (1400h–15FFh).
    pub direction: PdoDirection,
    /// The PDO number, 1..=512 (1800h is TPDO 1).
    pub number: u16,
    /// The communication parameter.
    pub communication: PdoCommunication,
    /// The mapping parameter (empty when the file has no mapping object).
    pub mapping: PdoMapping,
    /// One per mapping entry that is not a dummy, in mapping order.
    pub signals: Vec<SignalInfo>,
}

impl EdsPdo {
    /// Return the signal of `entry`, if it is mapped.
    #[must_use]
    pub fn signal(&self, entry: MappingEntry) -> Option<&SignalInfo> {
        self.signals.iter().find(|s| s.entry == entry)
    }

    /// Read `payload` with this PDO's mapping and the file's data types.
    #[must_use]
    pub fn unpack<'a>(&'a self, payload: &'a [u8]) -> Signals<'a, &'a EdsPdo> {
        self.mapping.unpack_with(payload, self)
    }
}

impl TypeLookup for &EdsPdo {
    fn data_type(&self, entry: MappingEntry) -> Option<DataType> {
        self.signal(entry).and_then(|s| s.data_type)
    }
}

/// What is wrong in an EDS or DCF file.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum EdsErrorKind {
    /// The file cannot be read.
    Io(String),
    /// A line of INI text is malformed.
    Ini(IniErrorKind),
    /// A key the reader needs is missing.
    MissingKey,
    /// A number is not decimal, `0x` hex, octal or a `$NODEID` expression.
    BadNumber(String),
    /// A number outside the range of its field or data type.
    OutOfRange(String),
    /// `$NODEID` with no node-ID given nor in `[DeviceComissioning]`.
    NodeIdUnknown,
    /// An `ObjectType` that is no CiA 301 object code.
    BadObjectType(String),
    /// An `AccessType` other than ro, wo, rw, rwr, rww, const.
    BadAccessType(String),
    /// A `[xxxxsubN]` section whose object section `[xxxx]` is missing.
    MissingObject,
    /// A PDO mapping entry that the mapping refuses, or a mapping or
    /// communication sub-index that a PDO needs and the file lacks.
    Pdo(String),
}

impl fmt::Display for EdsErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EdsErrorKind::Io(e) => write!(f, "cannot be read: {e}"),
            EdsErrorKind::Ini(kind) => write!(f, "{kind}"),
            EdsErrorKind::MissingKey => f.write_str("the key is missing"),
            EdsErrorKind::BadNumber(text) => write!(
                f,
                "expected a decimal, 0x hex or octal number or a $NODEID expression, found {text:?}"
            ),
            EdsErrorKind::OutOfRange(text) => {
                write!(f, "{text:?} is out of range for its data type")
            }
            EdsErrorKind::NodeIdUnknown => {
                f.write_str("$NODEID with no node-ID given and none in [DeviceComissioning] NodeID")
            }
            EdsErrorKind::BadObjectType(text) => write!(
                f,
                "expected an object type 0x0, 0x2, 0x5, 0x6, 0x7, 0x8 or 0x9, found {text:?}"
            ),
            EdsErrorKind::BadAccessType(text) => write!(
                f,
                "expected an access type ro, wo, rw, rwr, rww or const, found {text:?}"
            ),
            EdsErrorKind::MissingObject => {
                f.write_str("a sub-index section without its object's section")
            }
            EdsErrorKind::Pdo(reason) => f.write_str(reason),
        }
    }
}

/// An error in an EDS or DCF file: the file as the caller named it, the
/// 1-based line (0 when the file could not be read), the section and key
/// where there is one, and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EdsError {
    /// The file's name as the caller gave it.
    pub file: String,
    /// The 1-based line.
    pub line: usize,
    /// The section.
    pub section: Option<String>,
    /// The key.
    pub key: Option<String>,
    /// What is wrong.
    pub kind: EdsErrorKind,
}

impl fmt::Display for EdsError {
    /// `file:line: [section] key: reason`, `file:line: reason` for a line
    /// outside any section, `file: reason` for what belongs to no line
    /// (the file cannot be read).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.file)?;
        if self.line > 0 {
            write!(f, ":{}", self.line)?;
        }
        if self.section.is_some() || self.key.is_some() {
            f.write_str(":")?;
        }
        if let Some(section) = &self.section {
            write!(f, " [{section}]")?;
        }
        if let Some(key) = &self.key {
            write!(f, " {key}")?;
        }
        write!(f, ": {}", self.kind)
    }
}

impl std::error::Error for EdsError {}

impl From<IniError> for EdsErrorKind {
    fn from(e: IniError) -> Self {
        EdsErrorKind::Ini(e.kind)
    }
}

/// A parsed EDS or DCF (CiA 306; docs/canopen.md#eds).
#[derive(Debug, Clone, PartialEq)]
pub struct Eds {
    file: String,
    node: Option<NodeId>,
    objects: BTreeMap<u16, Object>,
}

/// What a section name says it holds.
enum SectionKind {
    Object(u16),
    Sub(u16, u8),
    CompactNames(u16),
    CompactValues(u16),
    Other,
}

fn section_kind(name: &str) -> SectionKind {
    let hex4 = |s: &str| {
        (s.len() == 4 && s.bytes().all(|b| b.is_ascii_hexdigit()))
            .then(|| u16::from_str_radix(s, 16).ok())
            .flatten()
    };
    if let Some(index) = hex4(name) {
        return SectionKind::Object(index);
    }
    if name.len() <= 4 || !name.is_char_boundary(4) {
        return SectionKind::Other;
    }
    let Some(index) = hex4(&name[..4]) else {
        return SectionKind::Other;
    };
    let rest = &name[4..];
    if rest.len() > 3 && rest.as_bytes()[..3].eq_ignore_ascii_case(b"sub") {
        let digits = &rest[3..];
        if digits.bytes().all(|b| b.is_ascii_hexdigit()) {
            if let Ok(sub) = u8::from_str_radix(digits, 16) {
                return SectionKind::Sub(index, sub);
            }
        }
        return SectionKind::Other;
    }
    if rest.eq_ignore_ascii_case("name") {
        SectionKind::CompactNames(index)
    } else if rest.eq_ignore_ascii_case("value") {
        SectionKind::CompactValues(index)
    } else {
        SectionKind::Other
    }
}

/// Reads one file, with the context its errors need.
struct Reader<'f> {
    file: &'f str,
    node: Option<NodeId>,
}

impl Reader<'_> {
    fn error(&self, line: usize, section: &str, key: Option<&str>, kind: EdsErrorKind) -> EdsError {
        EdsError {
            file: self.file.to_owned(),
            line,
            section: Some(section.to_owned()),
            key: key.map(str::to_owned),
            kind,
        }
    }

    fn required<'a>(&self, section: &IniSection<'a>, key: &str) -> Result<&'a str, EdsError> {
        section.get(key).ok_or_else(|| {
            self.error(
                section.line,
                section.name,
                Some(key),
                EdsErrorKind::MissingKey,
            )
        })
    }

    /// Read the unsigned number of `key`, if written, within `max`.
    fn number(
        &self,
        section: &IniSection<'_>,
        key: &str,
        max: u64,
    ) -> Result<Option<u64>, EdsError> {
        let Some(entry) = section.entry(key) else {
            return Ok(None);
        };
        if entry.value.is_empty() {
            return Ok(None);
        }
        let value = value::parse_integer(entry.value, self.node)
            .map_err(|e| self.value_error(section, entry, e))?;
        u64::try_from(value)
            .ok()
            .filter(|&v| v <= max)
            .map(Some)
            .ok_or_else(|| {
                self.error(
                    entry.line,
                    section.name,
                    Some(entry.key),
                    EdsErrorKind::OutOfRange(entry.value.to_owned()),
                )
            })
    }

    fn value_error(
        &self,
        section: &IniSection<'_>,
        entry: &IniEntry<'_>,
        e: ValueError,
    ) -> EdsError {
        let kind = match e {
            ValueError::Syntax => EdsErrorKind::BadNumber(entry.value.to_owned()),
            ValueError::NodeIdUnknown => EdsErrorKind::NodeIdUnknown,
            ValueError::OutOfRange => EdsErrorKind::OutOfRange(entry.value.to_owned()),
        };
        self.error(entry.line, section.name, Some(entry.key), kind)
    }

    fn value(
        &self,
        section: &IniSection<'_>,
        key: &str,
        data_type: Option<DataType>,
    ) -> Result<Option<EdsValue>, EdsError> {
        let Some(entry) = section.entry(key) else {
            return Ok(None);
        };
        value::parse_value(entry.value, data_type, self.node)
            .map_err(|e| self.value_error(section, entry, e))
    }

    fn object_type(&self, section: &IniSection<'_>) -> Result<ObjectType, EdsError> {
        let Some(entry) = section.entry("ObjectType") else {
            // CiA 306 §4.6.3.2: no ObjectType means VAR.
            return Ok(ObjectType::Var);
        };
        let bad = || {
            self.error(
                entry.line,
                section.name,
                Some(entry.key),
                EdsErrorKind::BadObjectType(entry.value.to_owned()),
            )
        };
        let code = value::parse_integer(entry.value, None).map_err(|_| bad())?;
        u8::try_from(code)
            .ok()
            .and_then(ObjectType::from_code)
            .ok_or_else(bad)
    }

    /// Read a section describing one value-holding entry.
    fn entry(
        &self,
        section: &IniSection<'_>,
        index: u16,
        sub_index: u8,
        name: String,
    ) -> Result<Entry, EdsError> {
        let parameter_name = self.required(section, "ParameterName")?.to_owned();
        let data_type_index = self
            .number(section, "DataType", u64::from(u16::MAX))?
            .map(|v| v as u16);
        let data_type = data_type_index.and_then(DataType::from_index);
        let access_type = match section.entry("AccessType") {
            None => None,
            Some(entry) => Some(AccessType::from_text(entry.value).ok_or_else(|| {
                self.error(
                    entry.line,
                    section.name,
                    Some(entry.key),
                    EdsErrorKind::BadAccessType(entry.value.to_owned()),
                )
            })?),
        };
        let pdo_mapping = self.number(section, "PDOMapping", 1)? == Some(1);
        Ok(Entry {
            index,
            sub_index,
            name,
            parameter_name,
            data_type,
            data_type_index,
            access_type,
            pdo_mapping,
            default_value: self.value(section, "DefaultValue", data_type)?,
            parameter_value: self.value(section, "ParameterValue", data_type)?,
            line: section.line,
        })
    }
}

impl Eds {
    /// Read the EDS or DCF `text`, called `file` in errors, for node `node`
    /// (`None`: the `NodeID` of `[DeviceComissioning]`, if any).
    pub fn parse(text: &str, file: &str, node: Option<NodeId>) -> Result<Eds, EdsError> {
        let ini = IniFile::parse(text).map_err(|e| EdsError {
            file: file.to_owned(),
            line: e.line,
            section: e.section,
            key: e.key,
            kind: EdsErrorKind::Ini(e.kind),
        })?;
        let mut reader = Reader { file, node };
        if reader.node.is_none() {
            let commissioning = ini
                .section("DeviceComissioning")
                .or_else(|| ini.section("DeviceCommissioning"));
            if let Some(section) = commissioning {
                if let Some(id) = reader.number(section, "NodeID", 127)? {
                    reader.node = NodeId::new(id as u8);
                }
            }
        }
        let mut objects: BTreeMap<u16, Object> = BTreeMap::new();
        let mut compact_names = BTreeMap::new();
        let mut compact_values = BTreeMap::new();
        // Objects first, so that a sub-index section may come before its
        // object's section.
        for section in ini.sections() {
            match section_kind(section.name) {
                SectionKind::Object(index) => {
                    let object = reader.object(section, index)?;
                    objects.insert(index, object);
                }
                SectionKind::CompactNames(index) => {
                    compact_names.insert(index, section);
                }
                SectionKind::CompactValues(index) => {
                    compact_values.insert(index, section);
                }
                SectionKind::Sub(..) | SectionKind::Other => {}
            }
        }
        for section in ini.sections() {
            let SectionKind::Sub(index, sub_index) = section_kind(section.name) else {
                continue;
            };
            let Some(object) = objects.get_mut(&index) else {
                return Err(reader.error(
                    section.line,
                    section.name,
                    None,
                    EdsErrorKind::MissingObject,
                ));
            };
            if !object.object_type.is_compound() {
                // A sub-index of a VAR: python-canopen ignores it too.
                continue;
            }
            let parameter_name = reader.required(section, "ParameterName")?;
            let name = format!("{}.{}", object.name, parameter_name);
            let entry = reader.entry(section, index, sub_index, name)?;
            object.entries.insert(sub_index, entry);
        }
        for (index, object) in &mut objects {
            let Some(section) = ini
                .sections()
                .iter()
                .find(|s| matches!(section_kind(s.name), SectionKind::Object(i) if i == *index))
            else {
                continue;
            };
            reader.compact(
                section,
                object,
                compact_names.get(index).copied(),
                compact_values.get(index).copied(),
            )?;
        }
        Ok(Eds {
            file: file.to_owned(),
            node: reader.node,
            objects,
        })
    }

    /// Read the bytes of an EDS or DCF: UTF-8, or else Latin-1 (ISO 8859-1,
    /// which many vendors' files are written in; every byte is a character).
    pub fn from_bytes(bytes: &[u8], file: &str, node: Option<NodeId>) -> Result<Eds, EdsError> {
        match std::str::from_utf8(bytes) {
            Ok(text) => Eds::parse(text, file, node),
            Err(_) => {
                let text: String = bytes.iter().map(|&b| char::from(b)).collect();
                Eds::parse(&text, file, node)
            }
        }
    }

    /// Read the file at `path` ([`Eds::from_bytes`]); errors name it as
    /// `path` displays.
    pub fn read_file(path: &Path, node: Option<NodeId>) -> Result<Eds, EdsError> {
        let file = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| EdsError {
            file: file.clone(),
            line: 0,
            section: None,
            key: None,
            kind: EdsErrorKind::Io(e.to_string()),
        })?;
        Eds::from_bytes(&bytes, &file, node)
    }

    /// Return the file's name as the caller gave it.
    #[must_use]
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Return the node-ID `$NODEID` resolved to, if any.
    #[must_use]
    pub fn node(&self) -> Option<NodeId> {
        self.node
    }

    /// Return the object at `index`.
    #[must_use]
    pub fn object(&self, index: u16) -> Option<&Object> {
        self.objects.get(&index)
    }

    /// Return every object, by index.
    pub fn objects(&self) -> impl Iterator<Item = &Object> {
        self.objects.values()
    }

    /// Return the entry at `index`, `sub_index` (a VAR at sub-index 0).
    #[must_use]
    pub fn entry(&self, index: u16, sub_index: u8) -> Option<&Entry> {
        self.objects.get(&index)?.entry(sub_index)
    }

    /// Return the name the entry's signal gets (docs/canopen.md#signals; see
    /// [`Entry::name`]).
    #[must_use]
    pub fn name(&self, index: u16, sub_index: u8) -> Option<&str> {
        self.entry(index, sub_index).map(|e| e.name.as_str())
    }

    /// Return the entry's basic data type.
    #[must_use]
    pub fn data_type(&self, index: u16, sub_index: u8) -> Option<DataType> {
        self.entry(index, sub_index)?.data_type
    }

    /// Return the entry's value ([`Entry::value`]).
    #[must_use]
    pub fn value(&self, index: u16, sub_index: u8) -> Option<&EdsValue> {
        self.entry(index, sub_index)?.value()
    }

    /// Return the device type, object 1000h (CiA 301 §7.5.2.1): the device
    /// profile number in the low 16 bits.
    #[must_use]
    pub fn device_type(&self) -> Option<u32> {
        self.value(0x1000, 0)?
            .as_u64()
            .and_then(|v| u32::try_from(v).ok())
    }

    /// Return whether the device type names CiA 402 (0x0192 in the low
    /// word of 1000h; docs/canopen.md#cia402).
    #[must_use]
    pub fn is_cia402(&self) -> bool {
        self.device_type()
            .is_some_and(crate::canopen::cia402::is_drive_device_type)
    }

    /// Return every PDO whose communication parameter object the file has
    /// (RPDOs 1400h–15FFh, then TPDOs 1800h–19FFh), with its mapping from
    /// 1600h–17FFh / 1A00h–1BFFh and its signals' names and types.
    ///
    /// Sub-index 1 (COB-ID) of a communication parameter is needed;
    /// sub-indices 2, 3, 5 and 6 are read where present. A mapping reads
    /// sub-index 0's number of entries, then each entry; an entry of value
    /// 0 is skipped (as python-canopen and lely's dcf-tools do).
    pub fn pdos(&self) -> Result<Vec<EdsPdo>, EdsError> {
        let mut pdos = Vec::new();
        for (base, direction) in [
            (0x1400u16, PdoDirection::Receive),
            (0x1800u16, PdoDirection::Transmit),
        ] {
            for n in 0..0x200u16 {
                let Some(comm) = self.object(base + n) else {
                    continue;
                };
                let communication = self.communication(comm)?;
                let (mapping, signals) = match self.object(base + 0x200 + n) {
                    Some(map) => self.mapping(map)?,
                    None => (PdoMapping::new(), Vec::new()),
                };
                pdos.push(EdsPdo {
                    direction,
                    number: n + 1,
                    communication,
                    mapping,
                    signals,
                });
            }
        }
        Ok(pdos)
    }

    fn pdo_error(&self, object: &Object, sub: Option<&Entry>, reason: String) -> EdsError {
        EdsError {
            file: self.file.clone(),
            line: sub.map_or(object.line, |e| e.line),
            section: Some(match sub {
                Some(e) => ObjectAddress::new(e.index, e.sub_index)
                    .sub_notation()
                    .to_string(),
                None => format!("{:04X}", object.index),
            }),
            key: None,
            kind: EdsErrorKind::Pdo(reason),
        }
    }

    /// Return the unsigned value of `object`'s sub-index `sub`, at most `max`.
    fn sub_value(&self, object: &Object, sub: u8, max: u64) -> Result<Option<u64>, EdsError> {
        let Some(entry) = object.entry(sub) else {
            return Ok(None);
        };
        match entry.value() {
            None => Ok(None),
            Some(value) => match value.as_u64().filter(|&v| v <= max) {
                Some(v) => Ok(Some(v)),
                None => Err(self.pdo_error(
                    object,
                    Some(entry),
                    format!("expected an unsigned value at most {max:#x}, found {value}"),
                )),
            },
        }
    }

    fn communication(&self, object: &Object) -> Result<PdoCommunication, EdsError> {
        let cob_id = self
            .sub_value(object, 1, u64::from(u32::MAX))?
            .ok_or_else(|| {
                self.pdo_error(
                    object,
                    None,
                    "expected sub-index 1 (COB-ID) with a value, found none".to_owned(),
                )
            })?;
        let mut communication = PdoCommunication::new(PdoCobId::from_u32(cob_id as u32));
        communication.transmission_type = self
            .sub_value(object, 2, 0xFF)?
            .map(|v| TransmissionType::from_byte(v as u8));
        communication.inhibit_time = self
            .sub_value(object, 3, 0xFFFF)?
            .map(|v| InhibitTime::from_raw(v as u16));
        communication.event_timer = self
            .sub_value(object, 5, 0xFFFF)?
            .map(|v| EventTimer::from_raw(v as u16));
        communication.sync_start = self.sub_value(object, 6, 0xFF)?.map(|v| v as u8);
        Ok(communication)
    }

    fn mapping(&self, object: &Object) -> Result<(PdoMapping, Vec<SignalInfo>), EdsError> {
        let count = self.sub_value(object, 0, 0xFF)?.unwrap_or(0) as u8;
        let mut mapping = PdoMapping::new();
        let mut signals = Vec::new();
        for sub in 1..=count {
            let Some(raw) = self.sub_value(object, sub, u64::from(u32::MAX))? else {
                return Err(self.pdo_error(
                    object,
                    object.entry(0),
                    format!("expected {count} mapping entries, sub-index {sub} has no value"),
                ));
            };
            if raw == 0 {
                continue;
            }
            let entry = MappingEntry::from_u32(raw as u32);
            mapping
                .push(entry)
                .map_err(|e| self.pdo_error(object, object.entry(sub), e.to_string()))?;
            if entry.is_dummy() {
                continue;
            }
            let target = self.entry(entry.index(), entry.sub_index());
            signals.push(SignalInfo {
                entry,
                name: target.map(|e| e.name.clone()),
                data_type: target.and_then(|e| e.data_type),
            });
        }
        Ok((mapping, signals))
    }
}

impl Reader<'_> {
    fn object(&self, section: &IniSection<'_>, index: u16) -> Result<Object, EdsError> {
        let name = self.required(section, "ParameterName")?.to_owned();
        let object_type = self.object_type(section)?;
        let sub_number = self.number(section, "SubNumber", 0xFF)?.map(|v| v as u8);
        let mut entries = BTreeMap::new();
        if matches!(object_type, ObjectType::Var | ObjectType::Domain) {
            let entry = self.entry(section, index, 0, name.clone())?;
            entries.insert(0, entry);
        }
        Ok(Object {
            index,
            name,
            object_type,
            sub_number,
            line: section.line,
            entries,
        })
    }

    /// Expand an ARRAY written with `CompactSubObj=N` (CiA 306, compact storage of sub-objects):
    /// sub-index 0 "Number of entries" (UNSIGNED8, N; python-canopen's
    /// name), sub-indices 1..=N named by `[xxxxName]` or else the object's
    /// name followed by the sub-index in decimal (lely's dcf-tools), valued
    /// by `[xxxxValue]` or else the object's own value.
    fn compact(
        &self,
        section: &IniSection<'_>,
        object: &mut Object,
        names: Option<&IniSection<'_>>,
        values: Option<&IniSection<'_>>,
    ) -> Result<(), EdsError> {
        let Some(count) = self.number(section, "CompactSubObj", 0xFE)? else {
            return Ok(());
        };
        if object.object_type != ObjectType::Array || count == 0 || !object.entries.is_empty() {
            return Ok(());
        }
        let template = self.entry(section, object.index, 1, String::new())?;
        object.entries.insert(
            0,
            Entry {
                index: object.index,
                sub_index: 0,
                name: format!("{}.Number of entries", object.name),
                parameter_name: "Number of entries".to_owned(),
                data_type: Some(DataType::Unsigned8),
                data_type_index: Some(DataType::Unsigned8.index()),
                access_type: Some(AccessType::ReadOnly),
                pdo_mapping: false,
                default_value: Some(EdsValue::Unsigned(count)),
                parameter_value: None,
                line: section.line,
            },
        );
        for sub in 1..=count as u8 {
            let key = sub.to_string();
            let parameter_name = names
                .and_then(|s| s.get(&key))
                .map_or_else(|| format!("{}{sub}", object.name), str::to_owned);
            let mut entry = template.clone();
            entry.sub_index = sub;
            entry.name = format!("{}.{}", object.name, parameter_name);
            entry.parameter_name = parameter_name;
            if let Some(values) = values {
                if values.entry(&key).is_some() {
                    entry.parameter_value = self.value(values, &key, entry.data_type)?;
                }
            }
            object.entries.insert(sub, entry);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
