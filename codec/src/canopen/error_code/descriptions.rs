//! Emergency error code descriptions, from the most specific text known to
//! the least (docs/canopen.md#emcy-codes).
//!
//! A lookup tries, in this order:
//!
//! 1. the exact code in CiA 301's table (`CIA301_CODES`),
//! 2. the exact code in the CiA 402 drive profile's table (`CIA402_CODES`),
//! 3. the sub-class — the code's high byte — in CiA 301's table
//!    (`CIA301_SUB_CLASSES`, the rows written `21xx`, `81xx`, …),
//! 4. the sub-class as CiA 402 names it: a CiA 402 group code ending in
//!    `00` (e.g. 0x7300 "Sensor") heads its block 0x73xx,
//! 5. the class ([`ErrorClass::description`]).
//!
//! A code whose class is [`ErrorClass::Unknown`] is never looked up in any
//! table, so it can never get a text from another class.
//!
//! The tables hold facts (code numbers and their meanings) from the CiA
//! documents; the texts are written for this crate. They were checked
//! against the tables of Wireshark's CANopen dissector (`em_err_code` in
//! `epan/dissectors/packet-canopen.c`) and python-canopen (`EmcyError.DESCRIPTIONS`
//! in `canopen/emcy.py`): every code and range that those name has an entry
//! here (see the tests at the bottom).

use core::fmt;

use super::code::{ErrorClass, ErrorCode};

/// The document a description comes from (docs/canopen.md#emcy-codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DescriptionSource {
    /// CiA 301, the CANopen application layer: Table 26, "Emergency error
    /// codes" (its exact codes, its `xxxx`-ranges and its classes).
    Cia301,
    /// CiA 402 part 2 (IEC 61800-7-201), the drive and motion control
    /// profile: its table of error codes (the values of object 603Fh
    /// "Error code" that a drive also sends in its EMCY).
    Cia402,
}

impl DescriptionSource {
    /// Return the document and table the entry comes from, in words.
    #[must_use]
    pub const fn document(self) -> &'static str {
        match self {
            DescriptionSource::Cia301 => "CiA 301 Table 26 (emergency error codes)",
            DescriptionSource::Cia402 => {
                "CiA 402-2 / IEC 61800-7-201 error code table (object 603Fh)"
            }
        }
    }
}

impl fmt::Display for DescriptionSource {
    /// Format the source as the document's short name, `CiA 301` or `CiA 402`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            DescriptionSource::Cia301 => "CiA 301",
            DescriptionSource::Cia402 => "CiA 402",
        })
    }
}

/// How specific the description found for a code is
/// (docs/canopen.md#emcy-codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Specificity {
    /// A table names this very code (e.g. 0x8130, 0x7121).
    Exact,
    /// A table names the code's sub-class, its high byte (e.g. 0x2399 in
    /// 0x23xx "current, device output side").
    SubClass,
    /// Only the class is known (e.g. 0x2A00 in 0x2xxx "current").
    Class,
    /// The code lies outside every range of CiA 301's table.
    Unknown,
}

impl Specificity {
    /// Return the specificity in words: `exact`, `sub-class`, `class` or
    /// `unknown`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Specificity::Exact => "exact",
            Specificity::SubClass => "sub-class",
            Specificity::Class => "class",
            Specificity::Unknown => "unknown",
        }
    }
}

impl fmt::Display for Specificity {
    /// Format the specificity as its name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The most specific description known for an error code, and where it
/// comes from (docs/canopen.md#emcy-codes); returned by
/// [`ErrorCode::describe`].
///
/// ```
/// use motionwire_codec::canopen::{DescriptionSource, ErrorCode, Specificity};
///
/// let d = ErrorCode::new(0x8611).describe();
/// assert_eq!(d.text, "Following error");
/// assert_eq!(d.specificity, Specificity::Exact);
/// assert_eq!(d.source, Some(DescriptionSource::Cia402));
///
/// let d = ErrorCode::new(0x2399).describe();
/// assert_eq!(d.text, "Current, device output side");
/// assert_eq!(d.specificity, Specificity::SubClass);
///
/// let d = ErrorCode::new(0xA000).describe();
/// assert_eq!(d.specificity, Specificity::Unknown);
/// assert_eq!(d.source, None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Description {
    /// The description in words.
    pub text: &'static str,
    /// How specific the match was.
    pub specificity: Specificity,
    /// The document the text comes from; `None` only for
    /// [`Specificity::Unknown`], which no table names.
    pub source: Option<DescriptionSource>,
}

impl fmt::Display for Description {
    /// Format the description as its text.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.text)
    }
}

/// One row of a description table: a key (an exact code, or a sub-class's
/// high byte), its text and the document it comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Entry<K> {
    key: K,
    text: &'static str,
    source: DescriptionSource,
}

/// A row taken from CiA 301.
const fn cia301<K>(key: K, text: &'static str) -> Entry<K> {
    Entry {
        key,
        text,
        source: DescriptionSource::Cia301,
    }
}

/// A row taken from CiA 402.
const fn cia402<K>(key: K, text: &'static str) -> Entry<K> {
    Entry {
        key,
        text,
        source: DescriptionSource::Cia402,
    }
}

/// The exact codes of CiA 301 Table 26: the rows of the 81xx
/// (communication) and 82xx (protocol error) sub-classes. Sorted by code.
const CIA301_CODES: &[Entry<u16>] = &[
    cia301(0x8110, "CAN overrun (objects lost)"),
    cia301(0x8120, "CAN in error passive mode"),
    cia301(0x8130, "Life guard error or heartbeat error"),
    cia301(0x8140, "Recovered from bus off"),
    cia301(0x8150, "CAN-ID collision"),
    cia301(0x8210, "PDO not processed due to length error"),
    cia301(0x8220, "PDO length exceeded"),
    cia301(
        0x8230,
        "DAM MPDO not processed, destination object not available",
    ),
    cia301(0x8240, "Unexpected SYNC data length"),
    cia301(0x8250, "RPDO timeout"),
];

/// The rows of CiA 301 Table 26 that name a range `hhxx`, keyed by the high
/// byte `hh`. Sorted by high byte.
const CIA301_SUB_CLASSES: &[Entry<u8>] = &[
    cia301(0x00, "Error reset or no error"),
    cia301(0x10, "Generic error"),
    cia301(0x20, "Current, generic error"),
    cia301(0x21, "Current, device input side"),
    cia301(0x22, "Current inside the device"),
    cia301(0x23, "Current, device output side"),
    cia301(0x30, "Voltage, generic error"),
    cia301(0x31, "Mains voltage"),
    cia301(0x32, "Voltage inside the device"),
    cia301(0x33, "Output voltage"),
    cia301(0x40, "Temperature, generic error"),
    cia301(0x41, "Ambient temperature"),
    cia301(0x42, "Device temperature"),
    cia301(0x50, "Device hardware, generic error"),
    cia301(0x60, "Device software, generic error"),
    cia301(0x61, "Internal software"),
    cia301(0x62, "User software"),
    cia301(0x63, "Data set"),
    cia301(0x70, "Additional modules, generic error"),
    cia301(0x80, "Monitoring, generic error"),
    cia301(0x81, "Communication"),
    cia301(0x82, "Protocol error"),
    cia301(0x90, "External error"),
    cia301(0xF0, "Additional functions"),
    cia301(0xFF, "Device specific"),
];

/// The error codes of the CiA 402 drive profile (CiA 402-2 / IEC
/// 61800-7-201, error code table; the same numbers are listed by
/// CANopenNode's `CO_402_ErrorCodes.h`). Group codes ending in `00` also
/// name their block (module docs, step 4). Sorted by code.
const CIA402_CODES: &[Entry<u16>] = &[
    // 21xx: current, device input side.
    cia402(0x2110, "Short circuit or earth leakage (input side)"),
    cia402(0x2120, "Earth leakage (input side)"),
    cia402(0x2121, "Earth leakage, phase L1"),
    cia402(0x2122, "Earth leakage, phase L2"),
    cia402(0x2123, "Earth leakage, phase L3"),
    cia402(0x2130, "Short circuit (input side)"),
    cia402(0x2131, "Short circuit, phases L1-L2"),
    cia402(0x2132, "Short circuit, phases L2-L3"),
    cia402(0x2133, "Short circuit, phases L3-L1"),
    // 22xx: current inside the device.
    cia402(0x2211, "Internal current no. 1"),
    cia402(0x2212, "Internal current no. 2"),
    cia402(0x2213, "Over-current in ramp function"),
    cia402(0x2214, "Over-current in the sequence"),
    cia402(0x2220, "Continuous over-current (inside the device)"),
    cia402(0x2221, "Continuous over-current no. 1 (inside the device)"),
    cia402(0x2222, "Continuous over-current no. 2 (inside the device)"),
    cia402(0x2230, "Short circuit or earth leakage (inside the device)"),
    cia402(0x2240, "Earth leakage (inside the device)"),
    cia402(0x2250, "Short circuit (inside the device)"),
    // 23xx: current, device output (motor) side.
    cia402(0x2310, "Continuous over-current (output side)"),
    cia402(0x2311, "Continuous over-current no. 1 (output side)"),
    cia402(0x2312, "Continuous over-current no. 2 (output side)"),
    cia402(0x2320, "Short circuit or earth leakage (output side)"),
    cia402(0x2330, "Earth leakage (output side)"),
    cia402(0x2331, "Earth leakage, phase U"),
    cia402(0x2332, "Earth leakage, phase V"),
    cia402(0x2333, "Earth leakage, phase W"),
    cia402(0x2340, "Short circuit (output side)"),
    cia402(0x2341, "Short circuit, phases U-V"),
    cia402(0x2342, "Short circuit, phases V-W"),
    cia402(0x2343, "Short circuit, phases W-U"),
    cia402(0x2350, "Load level fault (I2t, thermal state)"),
    cia402(0x2351, "Load level warning (I2t, thermal state)"),
    // 31xx: mains voltage.
    cia402(0x3110, "Mains over-voltage"),
    cia402(0x3111, "Mains over-voltage, phase L1"),
    cia402(0x3112, "Mains over-voltage, phase L2"),
    cia402(0x3113, "Mains over-voltage, phase L3"),
    cia402(0x3120, "Mains under-voltage"),
    cia402(0x3121, "Mains under-voltage, phase L1"),
    cia402(0x3122, "Mains under-voltage, phase L2"),
    cia402(0x3123, "Mains under-voltage, phase L3"),
    cia402(0x3130, "Phase failure"),
    cia402(0x3131, "Phase failure, L1"),
    cia402(0x3132, "Phase failure, L2"),
    cia402(0x3133, "Phase failure, L3"),
    cia402(0x3134, "Phase sequence"),
    cia402(0x3140, "Mains frequency"),
    cia402(0x3141, "Mains frequency too high"),
    cia402(0x3142, "Mains frequency too low"),
    // 32xx: voltage inside the device.
    cia402(0x3210, "DC link over-voltage"),
    cia402(0x3211, "DC link over-voltage no. 1"),
    cia402(0x3212, "DC link over-voltage no. 2"),
    cia402(0x3220, "DC link under-voltage"),
    cia402(0x3221, "DC link under-voltage no. 1"),
    cia402(0x3222, "DC link under-voltage no. 2"),
    cia402(0x3230, "Load error"),
    // 33xx: output voltage.
    cia402(0x3310, "Output over-voltage"),
    cia402(0x3311, "Output over-voltage, phase U"),
    cia402(0x3312, "Output over-voltage, phase V"),
    cia402(0x3313, "Output over-voltage, phase W"),
    cia402(0x3320, "Armature circuit"),
    cia402(0x3321, "Armature circuit interrupted"),
    cia402(0x3330, "Field circuit"),
    cia402(0x3331, "Field circuit interrupted"),
    // 41xx: ambient temperature; 42xx: device temperature.
    cia402(0x4110, "Excess ambient temperature"),
    cia402(0x4120, "Too low ambient temperature"),
    cia402(0x4130, "Supply air temperature"),
    cia402(0x4140, "Air outlet temperature"),
    cia402(0x4210, "Excess device temperature"),
    cia402(0x4220, "Too low device temperature"),
    // 43xx: drive temperature; 44xx: supply temperature.
    cia402(0x4300, "Drive temperature"),
    cia402(0x4310, "Excess drive temperature"),
    cia402(0x4320, "Too low drive temperature"),
    cia402(0x4400, "Supply temperature"),
    cia402(0x4410, "Excess supply temperature"),
    cia402(0x4420, "Too low supply temperature"),
    // 5xxx: device hardware.
    cia402(0x5100, "Supply"),
    cia402(0x5110, "Supply low voltage"),
    cia402(0x5111, "Supply U1 (+/-15 V)"),
    cia402(0x5112, "Supply U2 (+24 V)"),
    cia402(0x5113, "Supply U3 (+5 V)"),
    cia402(0x5114, "Supply U4 (manufacturer specific)"),
    cia402(0x5115, "Supply U5 (manufacturer specific)"),
    cia402(0x5116, "Supply U6 (manufacturer specific)"),
    cia402(0x5117, "Supply U7 (manufacturer specific)"),
    cia402(0x5118, "Supply U8 (manufacturer specific)"),
    cia402(0x5119, "Supply U9 (manufacturer specific)"),
    cia402(0x5120, "Supply intermediate circuit"),
    cia402(0x5200, "Control hardware"),
    cia402(0x5210, "Measurement circuit"),
    cia402(0x5220, "Computing circuit"),
    cia402(0x5300, "Operating unit"),
    cia402(0x5400, "Power section"),
    cia402(0x5410, "Output stages"),
    cia402(0x5420, "Chopper"),
    cia402(0x5430, "Input stages"),
    cia402(0x5440, "Contacts"),
    cia402(0x5441, "Contact 1 (manufacturer specific)"),
    cia402(0x5442, "Contact 2 (manufacturer specific)"),
    cia402(0x5443, "Contact 3 (manufacturer specific)"),
    cia402(0x5444, "Contact 4 (manufacturer specific)"),
    cia402(0x5445, "Contact 5 (manufacturer specific)"),
    cia402(0x5450, "Fuses"),
    cia402(0x5451, "Fuse S1 (L1)"),
    cia402(0x5452, "Fuse S2 (L2)"),
    cia402(0x5453, "Fuse S3 (L3)"),
    cia402(0x5454, "Fuse S4 (manufacturer specific)"),
    cia402(0x5455, "Fuse S5 (manufacturer specific)"),
    cia402(0x5456, "Fuse S6 (manufacturer specific)"),
    cia402(0x5457, "Fuse S7 (manufacturer specific)"),
    cia402(0x5458, "Fuse S8 (manufacturer specific)"),
    cia402(0x5459, "Fuse S9 (manufacturer specific)"),
    cia402(0x5500, "Hardware data storage"),
    cia402(0x5510, "RAM"),
    cia402(0x5520, "ROM/EPROM"),
    cia402(0x5530, "EEPROM"),
    // 6xxx: device software.
    cia402(0x6010, "Software reset (watchdog)"),
    cia402(0x6301, "Data record no. 1"),
    cia402(0x6302, "Data record no. 2"),
    cia402(0x6303, "Data record no. 3"),
    cia402(0x6304, "Data record no. 4"),
    cia402(0x6305, "Data record no. 5"),
    cia402(0x6306, "Data record no. 6"),
    cia402(0x6307, "Data record no. 7"),
    cia402(0x6308, "Data record no. 8"),
    cia402(0x6309, "Data record no. 9"),
    cia402(0x630A, "Data record no. 10"),
    cia402(0x630B, "Data record no. 11"),
    cia402(0x630C, "Data record no. 12"),
    cia402(0x630D, "Data record no. 13"),
    cia402(0x630E, "Data record no. 14"),
    cia402(0x630F, "Data record no. 15"),
    cia402(0x6310, "Loss of parameters"),
    cia402(0x6320, "Parameter error"),
    // 7xxx: additional modules.
    cia402(0x7100, "Power module"),
    cia402(0x7110, "Brake chopper"),
    cia402(0x7111, "Brake chopper failure"),
    cia402(0x7112, "Brake chopper over-current"),
    cia402(0x7113, "Brake chopper protective circuit"),
    cia402(0x7120, "Motor"),
    cia402(0x7121, "Motor blocked"),
    cia402(0x7122, "Motor error or commutation malfunction"),
    cia402(0x7123, "Motor tilted"),
    cia402(0x7200, "Measurement circuit module"),
    cia402(0x7300, "Sensor"),
    cia402(0x7301, "Tacho fault"),
    cia402(0x7302, "Tacho wrong polarity"),
    cia402(0x7303, "Resolver 1 fault"),
    cia402(0x7304, "Resolver 2 fault"),
    cia402(0x7305, "Incremental sensor 1 fault"),
    cia402(0x7306, "Incremental sensor 2 fault"),
    cia402(0x7307, "Incremental sensor 3 fault"),
    cia402(0x7310, "Speed sensor"),
    cia402(0x7320, "Position sensor"),
    cia402(0x7400, "Computation circuit"),
    cia402(0x7500, "Communication module"),
    cia402(0x7510, "Serial interface no. 1"),
    cia402(0x7520, "Serial interface no. 2"),
    cia402(0x7600, "Data storage (external)"),
    // 83xx–8Axx: monitoring of the drive's control loops.
    cia402(0x8300, "Torque control"),
    cia402(0x8311, "Excess torque"),
    cia402(0x8312, "Difficult start-up"),
    cia402(0x8313, "Standstill torque"),
    cia402(0x8321, "Insufficient torque"),
    cia402(0x8331, "Torque fault"),
    cia402(0x8400, "Velocity (speed) controller"),
    cia402(0x8500, "Position controller"),
    cia402(0x8600, "Positioning controller"),
    cia402(0x8611, "Following error"),
    cia402(0x8612, "Reference limit"),
    cia402(0x8613, "Homing error"),
    cia402(0x8700, "Sync controller"),
    cia402(0x8800, "Winding controller"),
    cia402(0x8900, "Process data monitoring"),
    cia402(0x8A00, "Control monitoring"),
    // F0xx: additional functions.
    cia402(0xF001, "Deceleration"),
    cia402(0xF002, "Sub-synchronous run"),
    cia402(0xF003, "Stroke operation"),
    cia402(0xF004, "Control function"),
];

/// Find `key` in a table sorted by key.
fn find<K: Ord + Copy>(table: &[Entry<K>], key: K) -> Option<Entry<K>> {
    table
        .binary_search_by_key(&key, |entry| entry.key)
        .ok()
        .and_then(|index| table.get(index).copied())
}

impl<K> Entry<K> {
    fn describe(self, specificity: Specificity) -> Description {
        Description {
            text: self.text,
            specificity,
            source: Some(self.source),
        }
    }
}

impl ErrorCode {
    /// Return the most specific description known for this code: the exact
    /// code (CiA 301, then CiA 402), else its sub-class, else its class;
    /// `"Unknown error code"` outside every range (docs/canopen.md#emcy-codes).
    ///
    /// ```
    /// use motionwire_codec::canopen::ErrorCode;
    ///
    /// assert_eq!(ErrorCode::new(0x8130).description(), "Life guard error or heartbeat error");
    /// assert_eq!(ErrorCode::new(0x7121).description(), "Motor blocked");
    /// assert_eq!(ErrorCode::new(0x8199).description(), "Communication");
    /// assert_eq!(ErrorCode::new(0x2A00).description(), "Current");
    /// assert_eq!(ErrorCode::new(0xA000).description(), "Unknown error code");
    /// ```
    #[inline]
    #[must_use]
    pub fn description(self) -> &'static str {
        self.describe().text
    }

    /// Return the most specific description known for this code, with how
    /// specific it is and the document it comes from
    /// (docs/canopen.md#emcy-codes).
    #[must_use]
    pub fn describe(self) -> Description {
        let class = self.class();
        if class == ErrorClass::Unknown {
            return Description {
                text: class.description(),
                specificity: Specificity::Unknown,
                source: None,
            };
        }
        let raw = self.get();
        let [high, _] = raw.to_be_bytes();
        if let Some(entry) = find(CIA301_CODES, raw).or_else(|| find(CIA402_CODES, raw)) {
            return entry.describe(Specificity::Exact);
        }
        if let Some(entry) = find(CIA301_SUB_CLASSES, high) {
            return entry.describe(Specificity::SubClass);
        }
        if let Some(entry) = find(CIA402_CODES, raw & 0xFF00) {
            return entry.describe(Specificity::SubClass);
        }
        Description {
            text: class.description(),
            specificity: Specificity::Class,
            source: Some(DescriptionSource::Cia301),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys<K: Copy>(table: &[Entry<K>]) -> Vec<K> {
        table.iter().map(|entry| entry.key).collect()
    }

    fn assert_strictly_sorted<K: Ord + Copy + fmt::Debug>(name: &str, table: &[Entry<K>]) {
        for pair in keys(table).windows(2) {
            assert!(
                pair[0] < pair[1],
                "{name}: {:?} then {:?} is unsorted or duplicated",
                pair[0],
                pair[1]
            );
        }
    }

    #[test]
    fn tables_are_sorted_and_free_of_duplicates() {
        assert_strictly_sorted("CIA301_CODES", CIA301_CODES);
        assert_strictly_sorted("CIA301_SUB_CLASSES", CIA301_SUB_CLASSES);
        assert_strictly_sorted("CIA402_CODES", CIA402_CODES);
        for entry in CIA301_CODES {
            assert!(
                !keys(CIA402_CODES).contains(&entry.key),
                "{:#06x} is in both exact tables",
                entry.key
            );
        }
    }

    #[test]
    fn every_entry_has_its_source_and_a_text() {
        for entry in CIA301_CODES {
            assert_eq!(entry.source, DescriptionSource::Cia301);
            assert!(!entry.text.is_empty());
        }
        for entry in CIA301_SUB_CLASSES {
            assert_eq!(entry.source, DescriptionSource::Cia301);
            assert!(!entry.text.is_empty());
        }
        for entry in CIA402_CODES {
            assert_eq!(entry.source, DescriptionSource::Cia402);
            assert!(!entry.text.is_empty());
        }
    }

    #[test]
    fn every_entry_lies_inside_a_known_class() {
        for entry in CIA301_CODES.iter().chain(CIA402_CODES) {
            assert_ne!(
                ErrorCode::new(entry.key).class(),
                ErrorClass::Unknown,
                "{:#06x}",
                entry.key
            );
        }
        for entry in CIA301_SUB_CLASSES {
            let first = u16::from(entry.key) << 8;
            assert_ne!(
                ErrorCode::new(first).class(),
                ErrorClass::Unknown,
                "{first:#06x}"
            );
            // A sub-class never straddles two classes.
            assert_eq!(
                ErrorCode::new(first).class(),
                ErrorCode::new(first | 0xFF).class()
            );
        }
    }

    #[test]
    fn every_exact_entry_returns_its_own_text_and_source() {
        for entry in CIA301_CODES.iter().chain(CIA402_CODES) {
            let code = ErrorCode::new(entry.key);
            assert_eq!(
                code.describe(),
                Description {
                    text: entry.text,
                    specificity: Specificity::Exact,
                    source: Some(entry.source),
                },
                "{code}"
            );
            assert_eq!(code.description(), entry.text);
        }
    }

    #[test]
    fn cia301_codes_named_by_the_spec() {
        let table = [
            (0x8110, "CAN overrun (objects lost)"),
            (0x8120, "CAN in error passive mode"),
            (0x8130, "Life guard error or heartbeat error"),
            (0x8140, "Recovered from bus off"),
            (0x8150, "CAN-ID collision"),
            (0x8210, "PDO not processed due to length error"),
            (0x8220, "PDO length exceeded"),
            (
                0x8230,
                "DAM MPDO not processed, destination object not available",
            ),
            (0x8240, "Unexpected SYNC data length"),
            (0x8250, "RPDO timeout"),
        ];
        for (raw, text) in table {
            let d = ErrorCode::new(raw).describe();
            assert_eq!(d.text, text, "{raw:#06x}");
            assert_eq!(d.specificity, Specificity::Exact);
            assert_eq!(d.source, Some(DescriptionSource::Cia301));
        }
    }

    #[test]
    fn cia402_drive_codes_named_by_the_spec() {
        let table = [
            (0x2310, "Continuous over-current (output side)"),
            (0x3210, "DC link over-voltage"),
            (0x4310, "Excess drive temperature"),
            (0x7121, "Motor blocked"),
            (0x7305, "Incremental sensor 1 fault"),
            (0x8611, "Following error"),
        ];
        for (raw, text) in table {
            let d = ErrorCode::new(raw).describe();
            assert_eq!(d.text, text, "{raw:#06x}");
            assert_eq!(d.specificity, Specificity::Exact);
            assert_eq!(d.source, Some(DescriptionSource::Cia402));
        }
    }

    #[test]
    fn sub_class_fallback() {
        // (code, text, source): codes that no table names exactly.
        let table = [
            (0x0001, "Error reset or no error", DescriptionSource::Cia301),
            (0x10FF, "Generic error", DescriptionSource::Cia301),
            (0x2001, "Current, generic error", DescriptionSource::Cia301),
            (
                0x2199,
                "Current, device input side",
                DescriptionSource::Cia301,
            ),
            (
                0x2299,
                "Current inside the device",
                DescriptionSource::Cia301,
            ),
            (
                0x2399,
                "Current, device output side",
                DescriptionSource::Cia301,
            ),
            (0x3199, "Mains voltage", DescriptionSource::Cia301),
            (
                0x3299,
                "Voltage inside the device",
                DescriptionSource::Cia301,
            ),
            (0x3399, "Output voltage", DescriptionSource::Cia301),
            (0x4199, "Ambient temperature", DescriptionSource::Cia301),
            (0x4299, "Device temperature", DescriptionSource::Cia301),
            (0x6199, "Internal software", DescriptionSource::Cia301),
            (0x6299, "User software", DescriptionSource::Cia301),
            (0x6399, "Data set", DescriptionSource::Cia301),
            (0x8100, "Communication", DescriptionSource::Cia301),
            (0x8111, "Communication", DescriptionSource::Cia301),
            (0x81FF, "Communication", DescriptionSource::Cia301),
            (0x8251, "Protocol error", DescriptionSource::Cia301),
            (0x9001, "External error", DescriptionSource::Cia301),
            (0xF0FF, "Additional functions", DescriptionSource::Cia301),
            (0xFF42, "Device specific", DescriptionSource::Cia301),
            // CiA 402 group codes head their block.
            (0x4399, "Drive temperature", DescriptionSource::Cia402),
            (0x5199, "Supply", DescriptionSource::Cia402),
            (0x7150, "Power module", DescriptionSource::Cia402),
            (0x7399, "Sensor", DescriptionSource::Cia402),
            (0x8614, "Positioning controller", DescriptionSource::Cia402),
            (0x8A01, "Control monitoring", DescriptionSource::Cia402),
        ];
        for (raw, text, source) in table {
            let d = ErrorCode::new(raw).describe();
            assert_eq!(
                d,
                Description {
                    text,
                    specificity: Specificity::SubClass,
                    source: Some(source),
                },
                "{raw:#06x}"
            );
        }
    }

    #[test]
    fn class_fallback() {
        let table = [
            (0x2A00, ErrorClass::Current, "Current"),
            (0x3FFF, ErrorClass::Voltage, "Voltage"),
            (0x4500, ErrorClass::Temperature, "Temperature"),
            (0x5600, ErrorClass::DeviceHardware, "Device hardware"),
            (0x6F00, ErrorClass::DeviceSoftware, "Device software"),
            (0x7700, ErrorClass::AdditionalModules, "Additional modules"),
            (0x8B00, ErrorClass::Monitoring, "Monitoring"),
            (0x9100, ErrorClass::External, "External error"),
        ];
        for (raw, class, text) in table {
            let code = ErrorCode::new(raw);
            assert_eq!(code.class(), class);
            assert_eq!(
                code.describe(),
                Description {
                    text,
                    specificity: Specificity::Class,
                    source: Some(DescriptionSource::Cia301),
                },
                "{raw:#06x}"
            );
            assert_eq!(text, class.description());
        }
    }

    #[test]
    fn unknown_codes() {
        for raw in [
            0x0100, 0x0FFF, 0x1100, 0x1FFF, 0xA000, 0xEFFF, 0xF100, 0xFEFF,
        ] {
            assert_eq!(
                ErrorCode::new(raw).describe(),
                Description {
                    text: "Unknown error code",
                    specificity: Specificity::Unknown,
                    source: None,
                },
                "{raw:#06x}"
            );
        }
    }

    /// The lookup, written out the slow way: a linear search through the
    /// tables in the order of docs/canopen.md#emcy-codes.
    fn reference(raw: u16) -> Description {
        let class = ErrorCode::new(raw).class();
        if class == ErrorClass::Unknown {
            return Description {
                text: "Unknown error code",
                specificity: Specificity::Unknown,
                source: None,
            };
        }
        let linear = |table: &[Entry<u16>], key: u16| table.iter().find(|e| e.key == key).copied();
        if let Some(e) = linear(CIA301_CODES, raw).or_else(|| linear(CIA402_CODES, raw)) {
            return e.describe(Specificity::Exact);
        }
        if let Some(e) = CIA301_SUB_CLASSES
            .iter()
            .find(|e| u16::from(e.key) == raw >> 8)
        {
            return e.describe(Specificity::SubClass);
        }
        if let Some(e) = linear(CIA402_CODES, raw & 0xFF00) {
            return e.describe(Specificity::SubClass);
        }
        Description {
            text: class.description(),
            specificity: Specificity::Class,
            source: Some(DescriptionSource::Cia301),
        }
    }

    #[test]
    fn all_65536_codes_are_consistent_with_their_class() {
        for raw in 0..=u16::MAX {
            let code = ErrorCode::new(raw);
            let d = code.describe();
            assert_eq!(d, reference(raw), "{raw:#06x}");
            assert_eq!(code.description(), d.text);
            match code.class() {
                ErrorClass::Unknown => {
                    assert_eq!(d.specificity, Specificity::Unknown, "{raw:#06x}");
                    assert_eq!(d.source, None);
                }
                class => {
                    assert_ne!(d.specificity, Specificity::Unknown, "{raw:#06x}");
                    assert!(d.source.is_some());
                    if d.specificity == Specificity::Class {
                        assert_eq!(d.text, class.description(), "{raw:#06x}");
                    }
                }
            }
            // A text never comes from another class: the entry that gave it
            // lies in the same 256-code block (exact or sub-class match),
            // or the text is the class's own.
            match d.specificity {
                Specificity::Exact => assert!(keys(CIA301_CODES)
                    .into_iter()
                    .chain(keys(CIA402_CODES))
                    .any(|k| k == raw)),
                Specificity::SubClass => {
                    let block = raw & 0xFF00;
                    assert_eq!(ErrorCode::new(block).class(), code.class());
                }
                Specificity::Class | Specificity::Unknown => {
                    assert_eq!(d.text, code.class().description())
                }
            }
        }
    }

    /// Every code and range of Wireshark's CANopen dissector (`em_err_code`
    /// in `epan/dissectors/packet-canopen.c`), probed at its first and last
    /// code, with the text this crate gives.
    #[test]
    fn wireshark_em_err_code_ranges() {
        use Specificity::{Exact, SubClass};
        let table = [
            (0x0000, 0x00FF, "Error reset or no error", SubClass),
            (0x1000, 0x10FF, "Generic error", SubClass),
            (0x2000, 0x20FF, "Current, generic error", SubClass),
            (0x2100, 0x21FF, "Current, device input side", SubClass),
            (0x2200, 0x22FF, "Current inside the device", SubClass),
            (0x2300, 0x23FF, "Current, device output side", SubClass),
            (0x3000, 0x30FF, "Voltage, generic error", SubClass),
            (0x3100, 0x31FF, "Mains voltage", SubClass),
            (0x3200, 0x32FF, "Voltage inside the device", SubClass),
            (0x3300, 0x33FF, "Output voltage", SubClass),
            (0x4000, 0x40FF, "Temperature, generic error", SubClass),
            (0x4100, 0x41FF, "Ambient temperature", SubClass),
            (0x4200, 0x42FF, "Device temperature", SubClass),
            (0x5000, 0x50FF, "Device hardware, generic error", SubClass),
            (0x6000, 0x60FF, "Device software, generic error", SubClass),
            (0x6100, 0x61FF, "Internal software", SubClass),
            (0x6200, 0x62FF, "User software", SubClass),
            (0x6300, 0x63FF, "Data set", SubClass),
            (
                0x7000,
                0x70FF,
                "Additional modules, generic error",
                SubClass,
            ),
            (0x8000, 0x80FF, "Monitoring, generic error", SubClass),
            (0x8100, 0x810F, "Communication", SubClass),
            (0x8110, 0x8110, "CAN overrun (objects lost)", Exact),
            (0x8111, 0x811F, "Communication", SubClass),
            (0x8120, 0x8120, "CAN in error passive mode", Exact),
            (0x8121, 0x812F, "Communication", SubClass),
            (0x8130, 0x8130, "Life guard error or heartbeat error", Exact),
            (0x8131, 0x813F, "Communication", SubClass),
            (0x8140, 0x8140, "Recovered from bus off", Exact),
            (0x8141, 0x814F, "Communication", SubClass),
            (0x8150, 0x8150, "CAN-ID collision", Exact),
            (0x8151, 0x81FF, "Communication", SubClass),
            (0x8200, 0x820F, "Protocol error", SubClass),
            (
                0x8210,
                0x8210,
                "PDO not processed due to length error",
                Exact,
            ),
            (0x8211, 0x821F, "Protocol error", SubClass),
            (0x8220, 0x8220, "PDO length exceeded", Exact),
            (0x8221, 0x822F, "Protocol error", SubClass),
            (
                0x8230,
                0x8230,
                "DAM MPDO not processed, destination object not available",
                Exact,
            ),
            (0x8231, 0x823F, "Protocol error", SubClass),
            (0x8240, 0x8240, "Unexpected SYNC data length", Exact),
            (0x8241, 0x824F, "Protocol error", SubClass),
            (0x8250, 0x8250, "RPDO timeout", Exact),
            (0x8251, 0x82FF, "Protocol error", SubClass),
            (0x9000, 0x90FF, "External error", SubClass),
            (0xF000, 0xF000, "Additional functions", SubClass),
            (0xF005, 0xF0FF, "Additional functions", SubClass),
            (0xFF00, 0xFFFF, "Device specific", SubClass),
        ];
        for (first, last, text, specificity) in table {
            for raw in [first, last] {
                let d = ErrorCode::new(raw).describe();
                assert_eq!((d.text, d.specificity), (text, specificity), "{raw:#06x}");
            }
        }
    }

    /// Every row of python-canopen's `EmcyError.DESCRIPTIONS` (code and mask,
    /// in `canopen/emcy.py`), probed at a code that no narrower entry names,
    /// with the class this crate sorts it into and the text it gives.
    #[test]
    fn python_canopen_descriptions() {
        let table = [
            // (code, python-canopen's row, class, our text)
            (
                0x0000,
                "Error Reset / No Error",
                ErrorClass::Reset,
                "Error reset or no error",
            ),
            (
                0x1000,
                "Generic Error",
                ErrorClass::Generic,
                "Generic error",
            ),
            (0x2A00, "Current", ErrorClass::Current, "Current"),
            (0x3A00, "Voltage", ErrorClass::Voltage, "Voltage"),
            (
                0x4A00,
                "Temperature",
                ErrorClass::Temperature,
                "Temperature",
            ),
            (
                0x5000,
                "Device Hardware",
                ErrorClass::DeviceHardware,
                "Device hardware, generic error",
            ),
            (
                0x6A00,
                "Device Software",
                ErrorClass::DeviceSoftware,
                "Device software",
            ),
            (
                0x7000,
                "Additional Modules",
                ErrorClass::AdditionalModules,
                "Additional modules, generic error",
            ),
            (
                0x8A50,
                "Monitoring",
                ErrorClass::Monitoring,
                "Control monitoring",
            ),
            (0x8F00, "Monitoring", ErrorClass::Monitoring, "Monitoring"),
            (
                0x9000,
                "External Error",
                ErrorClass::External,
                "External error",
            ),
            (
                0xF000,
                "Additional Functions",
                ErrorClass::AdditionalFunctions,
                "Additional functions",
            ),
            (
                0xFF00,
                "Device Specific",
                ErrorClass::DeviceSpecific,
                "Device specific",
            ),
        ];
        for (raw, python_name, class, text) in table {
            let code = ErrorCode::new(raw);
            assert_eq!(code.class(), class, "{raw:#06x} ({python_name})");
            assert_eq!(code.description(), text, "{raw:#06x} ({python_name})");
        }
    }

    #[test]
    fn display_and_sources() {
        assert_eq!(
            ErrorCode::new(0x8130).describe().to_string(),
            "Life guard error or heartbeat error"
        );
        assert_eq!(DescriptionSource::Cia301.to_string(), "CiA 301");
        assert_eq!(DescriptionSource::Cia402.to_string(), "CiA 402");
        assert!(DescriptionSource::Cia301.document().contains("Table 26"));
        assert!(DescriptionSource::Cia402.document().contains("603Fh"));
        assert!(Specificity::Exact < Specificity::Unknown);
        let names = [
            Specificity::Exact,
            Specificity::SubClass,
            Specificity::Class,
            Specificity::Unknown,
        ]
        .map(|s| s.to_string());
        assert_eq!(names, ["exact", "sub-class", "class", "unknown"]);
    }
}
