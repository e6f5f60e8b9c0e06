//! Baumer EAM580 absolute encoder: its EMCY manufacturer field and its
//! diagnostic sources (docs/canopen.md#baumer; Baumer EAM580 CANopen manual §8
//! "Emergency message" and §9.5 "Encoder diagnostic sources").
//!
//! The encoder sends the alarms object 6503h in bytes 3–4 and the warnings
//! object 6505h in bytes 5–6 of every EMCY; byte 7 is not used
//! ([`BaumerManufacturer`], [`BaumerEmcy`]). Each condition the encoder
//! reports is a row of the diagnostic-source table (Baumer EAM580 manual §9.5;
//! docs/canopen.md#baumer), kept here as the typed const table
//! [`DIAGNOSTIC_SOURCES`] with look-ups by EMCY code ([`sources_for_code`]),
//! by error injection code ([`source_for_injection`]), by name
//! ([`source_by_name`]) and by a received EMCY ([`matching_sources`], which
//! uses the alarm and warning bits to tell apart rows sharing a code).
//!
//! The manual remarks that whenever any diagnostic source appears, the
//! absolute position may be incorrect (docs/canopen.md#baumer).
//!
//! ```
//! use motionwire_codec::canopen::{ErrorCode, ErrorRegister};
//! use motionwire_codec::profiles::baumer::{self, Alarms, BaumerEmcy, Warnings};
//!
//! // Battery empty, seen at startup: code 0xFF01, error register bit 0,
//! // alarms 6503h bits 0 and 15 (docs/canopen.md#baumer).
//! let data = [0x01, 0xFF, 0x01, 0x01, 0x80, 0x00, 0x00, 0x00];
//! let emcy = BaumerEmcy::parse(&data)?;
//! assert_eq!(emcy.code, ErrorCode::new(0xFF01));
//! assert_eq!(emcy.register, ErrorRegister::GENERIC);
//! assert_eq!(emcy.manufacturer.alarms, Alarms::POSITION_ERROR | Alarms::BATTERY_EMPTY);
//! assert_eq!(emcy.manufacturer.warnings, Warnings::empty());
//!
//! // The alarm bits tell the startup row from the runtime row of 0xFF01.
//! let names: Vec<_> = emcy.sources().map(|s| s.name()).collect();
//! assert_eq!(names, ["battery_monitoring_error_startup"]);
//! assert_eq!(baumer::sources_for_code(emcy.code).count(), 2);
//!
//! // Encoding gives the same bytes back.
//! assert_eq!(emcy.to_bytes(), data);
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use bitflags::bitflags;
use byteorder::{ByteOrder, LittleEndian};

use crate::canopen::{Emcy, ErrorCode, ErrorRegister, EMCY_LEN};
use crate::{LenError, Result, ValueError};

bitflags! {
    /// The alarms object 6503h (u16), sent in bytes 3–4 of the encoder's
    /// EMCY; only the bits the diagnostic-source table uses are named
    /// (docs/canopen.md#baumer; CiA 406; Baumer EAM580 manual §8, §9.5).
    ///
    /// Decode a word that the encoder sent with [`Alarms::from_bits_retain`]
    /// so that unnamed bits survive a round trip.
    ///
    /// With the `serde` feature the word serializes in bitflags' format (in
    /// text, e.g. JSON, flag names joined by `|` and any other bits as hex);
    /// every bit survives a round trip.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
    #[cfg_attr(
        feature = "serde",
        derive(serde::Serialize, serde::Deserialize),
        serde(transparent)
    )]
    pub struct Alarms: u16 {
        /// Bit 0: position error (CiA 406); set with every alarm the encoder
        /// raises at startup (docs/canopen.md#baumer).
        const POSITION_ERROR = 1 << 0;
        /// Bit 1: problem with the non-volatile memory, seen at startup
        /// (docs/canopen.md#baumer, non-volatile data manager; CiA 406 calls
        /// this bit "commissioning diagnostic").
        const NON_VOLATILE_MEMORY = 1 << 1;
        /// Bit 12: the encoder's data are not valid; set at startup by the
        /// multiturn communication monitor (docs/canopen.md#baumer; Baumer's
        /// object list calls it "data valid encoder").
        const ENCODER_DATA_INVALID = 1 << 12;
        /// Bit 15: battery empty, seen at startup (docs/canopen.md#baumer:
        /// battery monitoring error, multiturn power-on reset).
        const BATTERY_EMPTY = 1 << 15;
    }
}

impl Alarms {
    /// The object index of the alarms, 6503h (CiA 406; docs/canopen.md#baumer);
    /// its name is the encoder row of [`crate::canopen::OBJECT_NAMES`].
    pub const OBJECT_INDEX: u16 = 0x6503;
}

bitflags! {
    /// The warnings object 6505h (u16), sent in bytes 5–6 of the encoder's
    /// EMCY; only the bits the diagnostic-source table uses are named
    /// (docs/canopen.md#baumer; CiA 406; Baumer EAM580 manual §8, §9.5).
    ///
    /// Decode a word that the encoder sent with [`Warnings::from_bits_retain`]
    /// so that unnamed bits survive a round trip.
    ///
    /// With the `serde` feature the word serializes in bitflags' format (in
    /// text, e.g. JSON, flag names joined by `|` and any other bits as hex);
    /// every bit survives a round trip.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
    #[cfg_attr(
        feature = "serde",
        derive(serde::Serialize, serde::Deserialize),
        serde(transparent)
    )]
    pub struct Warnings: u16 {
        /// Bit 0: frequency exceeded, the maximum rotation speed was exceeded
        /// (CiA 406; docs/canopen.md#baumer, speed monitoring).
        const FREQUENCY_EXCEEDED = 1 << 0;
        /// Bit 2: software reset by the CPU watchdog (CiA 406;
        /// docs/canopen.md#baumer, reset reason watchdog).
        const CPU_WATCHDOG = 1 << 2;
        /// Bit 3: problem with the non-volatile memory, seen at runtime
        /// (docs/canopen.md#baumer, non-volatile data manager; CiA 406 and
        /// Baumer's object list call this bit "operating time limit").
        const NON_VOLATILE_MEMORY = 1 << 3;
        /// Bit 4: battery of the multiturn system low (CiA 406 "battery
        /// charge"; docs/canopen.md#baumer, battery monitoring warning).
        const BATTERY_LOW = 1 << 4;
        /// Bit 12: mounting error, the multiturn magnetic field is weak,
        /// disturbed or in the wrong sequence (docs/canopen.md#baumer).
        const MOUNTING_ERROR = 1 << 12;
        /// Bit 13: multiturn system fault at runtime: battery empty, internal
        /// communication error or power-on reset (docs/canopen.md#baumer).
        const MULTITURN_SYSTEM = 1 << 13;
        /// Bit 14: singleturn system fault, sensor amplitude out of range
        /// (docs/canopen.md#baumer, singleturn magnetic field strength).
        const SINGLETURN_SYSTEM = 1 << 14;
        /// Bit 15: multiturn supervision, singleturn and multiturn sensors
        /// out of sync (docs/canopen.md#baumer).
        const MULTITURN_SUPERVISION = 1 << 15;
    }
}

impl Warnings {
    /// The object index of the warnings, 6505h (CiA 406;
    /// docs/canopen.md#baumer); its name is the encoder row of
    /// [`crate::canopen::OBJECT_NAMES`].
    pub const OBJECT_INDEX: u16 = 0x6505;
}

/// The bits of the error register 1001h that this encoder uses: bit 0
/// generic, bit 3 temperature, bit 4 communication (docs/canopen.md#baumer).
pub const ERROR_REGISTER_BITS: ErrorRegister = ErrorRegister::GENERIC
    .union(ErrorRegister::TEMPERATURE)
    .union(ErrorRegister::COMMUNICATION);

/// The number of entries of the encoder's error history, object 1003h
/// (docs/canopen.md#baumer).
pub const ERROR_HISTORY_LEN: usize = 8;

/// The object an error injection code is written to, 2116h, to simulate a
/// diagnostic source (docs/canopen.md#baumer); named in
/// [`crate::canopen::OBJECT_NAMES`].
pub const INJECTION_OBJECT_INDEX: u16 = 0x2116;

/// Return whether `code` is one of the encoder's manufacturer-reserved error
/// codes, 0xFF0A..=0xFF16 or 0xFF18..=0xFFFF (docs/canopen.md#baumer).
///
/// ```
/// use motionwire_codec::canopen::ErrorCode;
/// use motionwire_codec::profiles::baumer::is_reserved_code;
///
/// assert!(is_reserved_code(ErrorCode::new(0xFF0A)));
/// assert!(!is_reserved_code(ErrorCode::new(0xFF17))); // multiturn power-on reset
/// ```
#[must_use]
pub const fn is_reserved_code(code: ErrorCode) -> bool {
    matches!(code.get(), 0xFF0A..=0xFF16 | 0xFF18..=0xFFFF)
}

mod field {
    use core::ops::Range;

    // Offsets inside the EMCY's manufacturer field, which starts at EMCY
    // byte 3 (docs/canopen.md#emcy, docs/canopen.md#baumer).

    /// EMCY bytes 3–4: alarms, object 6503h, u16.
    pub(super) const ALARMS: Range<usize> = 0..2;
    /// EMCY bytes 5–6: warnings, object 6505h, u16.
    pub(super) const WARNINGS: Range<usize> = 2..4;
    /// EMCY byte 7: not used.
    pub(super) const UNUSED: usize = 4;
}

/// The length of the encoder's manufacturer field, 5 bytes (EMCY bytes 3–7;
/// docs/canopen.md#emcy, docs/canopen.md#baumer).
pub const MANUFACTURER_LEN: usize = field::UNUSED + 1;

/// The EAM580's manufacturer-specific EMCY field, bytes 3–7
/// (docs/canopen.md#baumer; Baumer EAM580 manual §8 "Emergency message").
///
/// ```
/// use motionwire_codec::profiles::baumer::{Alarms, BaumerManufacturer, Warnings};
///
/// let field = BaumerManufacturer::from_bytes(&[0x00, 0x00, 0x00, 0x20, 0x00]);
/// assert_eq!(field.alarms, Alarms::empty());
/// assert_eq!(field.warnings, Warnings::MULTITURN_SYSTEM);
/// assert_eq!(field.to_bytes(), [0x00, 0x00, 0x00, 0x20, 0x00]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BaumerManufacturer {
    /// Alarms, object 6503h (EMCY bytes 3–4, little-endian).
    pub alarms: Alarms,
    /// Warnings, object 6505h (EMCY bytes 5–6, little-endian).
    pub warnings: Warnings,
    /// EMCY byte 7: not used by the encoder; kept as received so that
    /// encoding gives the same bytes back.
    pub unused: u8,
}

impl BaumerManufacturer {
    /// Return the field with the given alarms and warnings and a zero unused
    /// byte.
    #[inline]
    #[must_use]
    pub const fn new(alarms: Alarms, warnings: Warnings) -> Self {
        BaumerManufacturer {
            alarms,
            warnings,
            unused: 0,
        }
    }

    /// Decode the 5 bytes of the manufacturer field (EMCY bytes 3–7);
    /// unnamed alarm and warning bits are retained.
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; MANUFACTURER_LEN]) -> Self {
        BaumerManufacturer {
            alarms: Alarms::from_bits_retain(LittleEndian::read_u16(&bytes[field::ALARMS])),
            warnings: Warnings::from_bits_retain(LittleEndian::read_u16(&bytes[field::WARNINGS])),
            unused: bytes[field::UNUSED],
        }
    }

    /// Encode the field into its 5 bytes (EMCY bytes 3–7).
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; MANUFACTURER_LEN] {
        let mut bytes = [0; MANUFACTURER_LEN];
        LittleEndian::write_u16(&mut bytes[field::ALARMS], self.alarms.bits());
        LittleEndian::write_u16(&mut bytes[field::WARNINGS], self.warnings.bits());
        bytes[field::UNUSED] = self.unused;
        bytes
    }
}

/// An EMCY from the EAM580, its manufacturer field decoded
/// (docs/canopen.md#emcy, docs/canopen.md#baumer).
///
/// Every 8-byte EMCY decodes, and encoding gives the same bytes back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BaumerEmcy {
    /// Emergency error code (bytes 0–1).
    pub code: ErrorCode,
    /// Error register, object 1001h (byte 2); this encoder uses the bits of
    /// [`ERROR_REGISTER_BITS`].
    pub register: ErrorRegister,
    /// Alarms, warnings and the unused byte (bytes 3–7).
    pub manufacturer: BaumerManufacturer,
}

impl BaumerEmcy {
    /// Return an EMCY with the given fields.
    #[inline]
    #[must_use]
    pub const fn new(
        code: ErrorCode,
        register: ErrorRegister,
        manufacturer: BaumerManufacturer,
    ) -> Self {
        BaumerEmcy {
            code,
            register,
            manufacturer,
        }
    }

    /// Decode the manufacturer field of an EMCY.
    #[inline]
    #[must_use]
    pub fn from_emcy(emcy: &Emcy) -> Self {
        BaumerEmcy {
            code: emcy.code,
            register: emcy.register,
            manufacturer: BaumerManufacturer::from_bytes(&emcy.manufacturer),
        }
    }

    /// Encode the manufacturer field back into a plain EMCY.
    #[inline]
    #[must_use]
    pub fn to_emcy(&self) -> Emcy {
        Emcy::new(self.code, self.register, self.manufacturer.to_bytes())
    }

    /// Decode the 8 bytes of an EMCY.
    #[inline]
    #[must_use]
    pub fn from_bytes(bytes: &[u8; EMCY_LEN]) -> Self {
        Self::from_emcy(&Emcy::from_bytes(bytes))
    }

    /// Encode the EMCY into its 8 bytes.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; EMCY_LEN] {
        self.to_emcy().to_bytes()
    }

    /// Decode an EMCY from a CAN frame's data; fewer than 8 bytes is a
    /// [`LenError`] (docs/canopen.md#emcy).
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, LenError> {
        Ok(Self::from_emcy(&Emcy::parse(data)?))
    }

    /// Return the diagnostic sources this EMCY reports, by the rule of
    /// [`matching_sources`].
    #[inline]
    pub fn sources(&self) -> impl Iterator<Item = &'static DiagnosticSource> + Clone {
        matching(self.code, self.manufacturer)
    }

    /// Return whether the encoder's own table makes this EMCY a warning:
    /// it matches at least one diagnostic source, and every source it
    /// matches is a warning ([`DiagnosticSource::is_warning`]; Baumer
    /// EAM580 manual §9.5).
    ///
    /// ```
    /// use motionwire_codec::profiles::baumer::BaumerEmcy;
    ///
    /// // 0xFF00 with 6505h bit 4: the battery monitoring warning.
    /// let battery = BaumerEmcy::from_bytes(&[0x00, 0xFF, 0x00, 0x00, 0x00, 0x10, 0x00, 0x00]);
    /// assert!(battery.is_warning());
    /// // 0x4200 with 1001h bits 0 and 3: temperature out of range, an error.
    /// let hot = BaumerEmcy::from_bytes(&[0x00, 0x42, 0x09, 0x00, 0x00, 0x00, 0x00, 0x00]);
    /// assert!(!hot.is_warning());
    /// ```
    #[must_use]
    pub fn is_warning(&self) -> bool {
        let mut sources = self.sources().peekable();
        sources.peek().is_some() && sources.all(DiagnosticSource::is_warning)
    }
}

impl From<Emcy> for BaumerEmcy {
    fn from(emcy: Emcy) -> Self {
        BaumerEmcy::from_emcy(&emcy)
    }
}

impl From<BaumerEmcy> for Emcy {
    fn from(emcy: BaumerEmcy) -> Self {
        emcy.to_emcy()
    }
}

/// When a diagnostic source is signalled (docs/canopen.md#baumer: when it
/// appears).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Appearance {
    /// At startup.
    Startup,
    /// At runtime.
    Runtime,
}

impl Appearance {
    /// Return the appearance's name, `"startup"` or `"runtime"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Appearance::Startup => "startup",
            Appearance::Runtime => "runtime",
        }
    }
}

/// Which encoder design a diagnostic source exists on (docs/canopen.md#baumer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Variant {
    /// Both the redundant and the non-redundant encoder.
    Both,
    /// Only the redundant encoder.
    Redundant,
    /// Only the non-redundant encoder.
    NonRedundant,
}

impl Variant {
    /// Return the variant's name, `"both"`, `"redundant"` or
    /// `"non_redundant"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Variant::Both => "both",
            Variant::Redundant => "redundant",
            Variant::NonRedundant => "non_redundant",
        }
    }
}

/// When the signalling of a diagnostic source is reset (docs/canopen.md#baumer:
/// how it is reset).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ResetBehaviour {
    /// Reset at runtime, once the cause is gone.
    AtRuntime,
    /// Reset only by a reboot.
    AtReboot,
    /// Reset by a reboot, except on the redundant encoder, where it is never
    /// reset (the rows marked "(1)" in Baumer EAM580 manual §9.5).
    AtRebootExceptRedundant,
    /// Never reset.
    NoReset,
}

impl ResetBehaviour {
    /// Return the behaviour on a given encoder design: on the redundant
    /// encoder [`ResetBehaviour::AtRebootExceptRedundant`] becomes
    /// [`ResetBehaviour::NoReset`], on the non-redundant one
    /// [`ResetBehaviour::AtReboot`]; with [`Variant::Both`] it stays as it is
    /// (Baumer EAM580 manual §9.5, "(1)").
    #[must_use]
    pub const fn on(self, variant: Variant) -> ResetBehaviour {
        match (self, variant) {
            (ResetBehaviour::AtRebootExceptRedundant, Variant::Redundant) => {
                ResetBehaviour::NoReset
            }
            (ResetBehaviour::AtRebootExceptRedundant, Variant::NonRedundant) => {
                ResetBehaviour::AtReboot
            }
            (behaviour, _) => behaviour,
        }
    }
}

/// What an error injection code simulates, told by its high word
/// (docs/canopen.md#baumer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum InjectionKind {
    /// High word 0x0001: an alarm at startup.
    StartupAlarm,
    /// High word 0x0004: a warning at startup.
    StartupWarning,
    /// High word 0x0008: a source at runtime.
    Runtime,
}

impl InjectionKind {
    /// Return the high word of codes of this kind.
    #[must_use]
    pub const fn high_word(self) -> u16 {
        match self {
            InjectionKind::StartupAlarm => 0x0001,
            InjectionKind::StartupWarning => 0x0004,
            InjectionKind::Runtime => 0x0008,
        }
    }

    /// Return the kind whose high word is `high`, if any.
    #[must_use]
    pub const fn from_high_word(high: u16) -> Option<Self> {
        match high {
            0x0001 => Some(InjectionKind::StartupAlarm),
            0x0004 => Some(InjectionKind::StartupWarning),
            0x0008 => Some(InjectionKind::Runtime),
            _ => None,
        }
    }

    /// Return when a source simulated with this kind appears.
    #[must_use]
    pub const fn appearance(self) -> Appearance {
        match self {
            InjectionKind::StartupAlarm | InjectionKind::StartupWarning => Appearance::Startup,
            InjectionKind::Runtime => Appearance::Runtime,
        }
    }
}

/// An error injection code, written to object 2116h to simulate a
/// diagnostic source (docs/canopen.md#baumer; Baumer EAM580 manual §9.5).
///
/// The high word tells the [`InjectionKind`]; the low word numbers the
/// source. 0x0000_0000 ([`InjectionCode::NO_ERROR`]) belongs to "error
/// reset or no error".
///
/// ```
/// use motionwire_codec::profiles::baumer::{InjectionCode, InjectionKind};
///
/// let code = InjectionCode::new(InjectionKind::StartupWarning, 0x001C);
/// assert_eq!(code.get(), 0x0004_001C);
/// assert_eq!(InjectionCode::try_new(0x0004_001C), Ok(code));
/// assert_eq!(code.kind(), Some(InjectionKind::StartupWarning));
/// assert!(InjectionCode::try_new(0x0002_0000).is_err());
/// ```
///
/// With the `serde` feature a code serializes as its number;
/// deserializing refuses what [`InjectionCode::try_new`] refuses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "u32", into = "u32")
)]
pub struct InjectionCode(u32);

impl InjectionCode {
    /// 0x0000_0000, the code of "error reset or no error"
    /// (docs/canopen.md#baumer).
    pub const NO_ERROR: InjectionCode = InjectionCode(0);

    /// Return the code of kind `kind` with low word `number`.
    #[inline]
    #[must_use]
    pub const fn new(kind: InjectionKind, number: u16) -> Self {
        InjectionCode(((kind.high_word() as u32) << 16) | number as u32)
    }

    /// Return the code `raw` if it is 0x0000_0000 or its high word is
    /// 0x0001, 0x0004 or 0x0008, else a [`ValueError`].
    pub const fn try_new(raw: u32) -> Result<Self, ValueError> {
        if raw == 0 || InjectionKind::from_high_word((raw >> 16) as u16).is_some() {
            Ok(InjectionCode(raw))
        } else {
            Err(ValueError {
                what: What::ErrorInjectionCode,
                found: raw,
                expected: "0x00000000 or a high word of 0x0001, 0x0004 or 0x0008",
            })
        }
    }

    /// Return the code as a number.
    #[inline]
    #[must_use]
    pub const fn get(self) -> u32 {
        self.0
    }

    /// Return the kind told by the high word; `None` for
    /// [`InjectionCode::NO_ERROR`].
    #[inline]
    #[must_use]
    pub const fn kind(self) -> Option<InjectionKind> {
        InjectionKind::from_high_word((self.0 >> 16) as u16)
    }

    /// Return the low word, the number of the simulated source.
    #[inline]
    #[must_use]
    pub const fn number(self) -> u16 {
        (self.0 & 0xFFFF) as u16
    }
}

impl TryFrom<u32> for InjectionCode {
    type Error = ValueError;

    /// [`InjectionCode::try_new`].
    fn try_from(raw: u32) -> Result<Self, ValueError> {
        Self::try_new(raw)
    }
}

impl From<InjectionCode> for u32 {
    fn from(code: InjectionCode) -> u32 {
        code.0
    }
}

impl fmt::Display for InjectionCode {
    /// Format the code as the manual writes it, e.g. `0x0008_0020`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:04X}_{:04X}", self.0 >> 16, self.number())
    }
}

/// Where a diagnostic source becomes visible: error register 1001h bits,
/// alarms 6503h bits and warnings 6505h bits (docs/canopen.md#baumer: how it
/// is signalled).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Signalling {
    /// Bits of the error register, object 1001h.
    pub register: ErrorRegister,
    /// Bits of the alarms, object 6503h.
    pub alarms: Alarms,
    /// Bits of the warnings, object 6505h.
    pub warnings: Warnings,
}

impl Signalling {
    /// No signalling ("—").
    pub const NONE: Signalling =
        Signalling::new(ErrorRegister::empty(), Alarms::empty(), Warnings::empty());

    /// Return the signalling with the given bits.
    #[inline]
    #[must_use]
    pub const fn new(register: ErrorRegister, alarms: Alarms, warnings: Warnings) -> Self {
        Signalling {
            register,
            alarms,
            warnings,
        }
    }

    /// Return whether any alarm (6503h) or warning (6505h) bit is signalled.
    #[inline]
    #[must_use]
    pub const fn has_alarm_or_warning_bits(&self) -> bool {
        !self.alarms.is_empty() || !self.warnings.is_empty()
    }
}

/// One row of the encoder's diagnostic-source table (docs/canopen.md#baumer;
/// Baumer EAM580 manual §9.5).
///
/// The rows are the entries of [`DIAGNOSTIC_SOURCES`]; a source that
/// appears both at startup and at runtime, or on both encoder designs with
/// different signalling, has one row each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DiagnosticSource {
    name: &'static str,
    source: &'static str,
    description: &'static str,
    code: Option<ErrorCode>,
    appearance: Appearance,
    signalling: Signalling,
    reset: Option<ResetBehaviour>,
    injection: Option<InjectionCode>,
    variant: Variant,
}

impl DiagnosticSource {
    /// Return the row's stable, unique snake_case name, e.g.
    /// `"non_volatile_data_manager_startup"`: the string the command-line
    /// decoder writes in `sources` (docs/output.md#json).
    #[inline]
    #[must_use]
    pub const fn name(&self) -> &'static str {
        self.name
    }

    /// Return the diagnostic source as the manual names it, e.g.
    /// `"Non-volatile data manager"`.
    #[inline]
    #[must_use]
    pub const fn source(&self) -> &'static str {
        self.source
    }

    /// Return what the source reports, e.g. `"Problem with the non-volatile
    /// memory"`.
    #[inline]
    #[must_use]
    pub const fn description(&self) -> &'static str {
        self.description
    }

    /// Return the EMCY error code; `None` when no EMCY is sent (CAN
    /// controller bus off).
    #[inline]
    #[must_use]
    pub const fn code(&self) -> Option<ErrorCode> {
        self.code
    }

    /// Return when the source is signalled.
    #[inline]
    #[must_use]
    pub const fn appearance(&self) -> Appearance {
        self.appearance
    }

    /// Return where the source becomes visible.
    #[inline]
    #[must_use]
    pub const fn signalling(&self) -> Signalling {
        self.signalling
    }

    /// Return whether the source is a warning: the manual's table signals
    /// it in the warnings (6505h) only, not in the error register (1001h)
    /// nor in the alarms (6503h) (Baumer EAM580 manual §9.5: the battery
    /// monitoring warning 0xFF00, the watchdog reset reason 0x6100, …).
    #[inline]
    #[must_use]
    pub const fn is_warning(&self) -> bool {
        let s = self.signalling;
        s.register.is_empty() && s.alarms.is_empty() && !s.warnings.is_empty()
    }

    /// Return when the signalling is reset; `None` where the table gives
    /// none ("error reset or no error").
    #[inline]
    #[must_use]
    pub const fn reset(&self) -> Option<ResetBehaviour> {
        self.reset
    }

    /// Return the error injection code that simulates the source; `None`
    /// for the CAN controller and error-control sources, which have none.
    #[inline]
    #[must_use]
    pub const fn injection(&self) -> Option<InjectionCode> {
        self.injection
    }

    /// Return the encoder design the row applies to.
    #[inline]
    #[must_use]
    pub const fn variant(&self) -> Variant {
        self.variant
    }

    /// Return whether the row signals alarm or warning bits and all of them
    /// are set in `field`.
    #[inline]
    #[must_use]
    pub fn is_signalled_in(&self, field: &BaumerManufacturer) -> bool {
        self.signalling.has_alarm_or_warning_bits()
            && field.alarms.contains(self.signalling.alarms)
            && field.warnings.contains(self.signalling.warnings)
    }

    /// Return the EMCY the encoder sends when this is its only active
    /// source: the row's code, its error register bits and its alarm and
    /// warning bits (docs/canopen.md#baumer); `None` when no EMCY is sent (bus
    /// off).
    #[must_use]
    pub const fn emcy(&self) -> Option<BaumerEmcy> {
        match self.code {
            Some(code) => Some(BaumerEmcy::new(
                code,
                self.signalling.register,
                BaumerManufacturer::new(self.signalling.alarms, self.signalling.warnings),
            )),
            None => None,
        }
    }
}

impl fmt::Display for DiagnosticSource {
    /// Format the row as `source: description`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.source, self.description)
    }
}

/// Return the rows whose EMCY error code is `code`, in table order; empty
/// for a code the encoder does not send (docs/canopen.md#baumer).
///
/// ```
/// use motionwire_codec::canopen::ErrorCode;
/// use motionwire_codec::profiles::baumer::sources_for_code;
///
/// let names: Vec<_> = sources_for_code(ErrorCode::new(0x5100)).map(|s| s.name()).collect();
/// assert_eq!(names, ["non_volatile_data_manager_startup", "non_volatile_data_manager_runtime"]);
/// ```
pub fn sources_for_code(
    code: ErrorCode,
) -> impl Iterator<Item = &'static DiagnosticSource> + Clone {
    DIAGNOSTIC_SOURCES
        .iter()
        .filter(move |source| source.code == Some(code))
}

/// Return the row simulated by injection code `code`; at most one row has
/// each code (docs/canopen.md#baumer).
#[must_use]
pub fn source_for_injection(code: InjectionCode) -> Option<&'static DiagnosticSource> {
    DIAGNOSTIC_SOURCES
        .iter()
        .find(|source| source.injection == Some(code))
}

/// Return the row named `name` (see [`DiagnosticSource::name`]).
#[must_use]
pub fn source_by_name(name: &str) -> Option<&'static DiagnosticSource> {
    DIAGNOSTIC_SOURCES.iter().find(|source| source.name == name)
}

/// Return the rows a received EMCY reports, using its alarm and warning bits
/// to tell apart rows that share a code (docs/canopen.md#baumer; `sources` in
/// docs/output.md#emcy).
///
/// The rule:
/// 1. Take the rows whose code is the EMCY's code; any 0x00xx code counts as
///    0x0000, "error reset or no error" (the **Decision** in
///    docs/canopen.md#emcy-codes).
/// 2. Of these, keep the rows that signal at least one 6503h/6505h bit and
///    whose signalled alarm bits are all set in bytes 3–4 and warning bits
///    all set in bytes 5–6 (other bits may be set too: the objects hold
///    every active alarm and warning).
/// 3. When no row is kept — none of the rows' bits are present, or the rows
///    signal no 6503h/6505h bits at all — return all rows of step 1.
///
/// So 0x5100 with alarms bits 0 and 1 is the startup row and with warning
/// bit 3 the runtime row; 0xFF00 cannot be told apart this way (both rows
/// signal warning bit 4 and differ only in the encoder design); a code the
/// encoder does not send gives no rows.
///
/// ```
/// use motionwire_codec::canopen::{Emcy, ErrorCode, ErrorRegister};
/// use motionwire_codec::profiles::baumer::matching_sources;
///
/// // 0x5100 at runtime: warnings 6505h bit 3 in bytes 5–6.
/// let emcy = Emcy::new(ErrorCode::new(0x5100), ErrorRegister::empty(), [0, 0, 0x08, 0, 0]);
/// let names: Vec<_> = matching_sources(&emcy).map(|s| s.name()).collect();
/// assert_eq!(names, ["non_volatile_data_manager_runtime"]);
/// ```
pub fn matching_sources(emcy: &Emcy) -> impl Iterator<Item = &'static DiagnosticSource> + Clone {
    matching(
        emcy.code,
        BaumerManufacturer::from_bytes(&emcy.manufacturer),
    )
}

/// The rule of [`matching_sources`] on a decoded manufacturer field.
fn matching(
    code: ErrorCode,
    field: BaumerManufacturer,
) -> impl Iterator<Item = &'static DiagnosticSource> + Clone {
    let code = if code.is_reset() {
        ErrorCode::NO_ERROR
    } else {
        code
    };
    let rows = sources_for_code(code);
    let told_apart = rows.clone().any(|source| source.is_signalled_in(&field));
    rows.filter(move |source| !told_apart || source.is_signalled_in(&field))
}

const fn code(raw: u16) -> Option<ErrorCode> {
    Some(ErrorCode::new(raw))
}

const fn inject(kind: InjectionKind, number: u16) -> Option<InjectionCode> {
    Some(InjectionCode::new(kind, number))
}

/// The number of rows of the diagnostic-source table.
pub const DIAGNOSTIC_SOURCE_COUNT: usize = 27;

/// Every diagnostic source of the EAM580, one entry per row of the
/// diagnostic-source table, in its order (Baumer EAM580 manual §9.5).
pub static DIAGNOSTIC_SOURCES: [DiagnosticSource; DIAGNOSTIC_SOURCE_COUNT] = [
    // Row 1; manual §9.5 "Error reset or no error".
    DiagnosticSource {
        name: "error_reset_or_no_error",
        source: "Error reset or no error",
        description: "No error is present any more",
        code: code(0x0000),
        appearance: Appearance::Runtime,
        signalling: Signalling::NONE,
        reset: None,
        injection: Some(InjectionCode::NO_ERROR),
        variant: Variant::Both,
    },
    // Row 2; manual §9.5 "Temperature Monitoring".
    DiagnosticSource {
        name: "temperature_monitoring",
        source: "Temperature monitoring",
        description: "Temperature out of range",
        code: code(0x4200),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::GENERIC.union(ErrorRegister::TEMPERATURE),
            Alarms::empty(),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtRuntime),
        injection: inject(InjectionKind::Runtime, 0x0020),
        variant: Variant::Both,
    },
    // Row 3; manual §9.5 "Non-Volatile Data Manager", at
    // startup.
    DiagnosticSource {
        name: "non_volatile_data_manager_startup",
        source: "Non-volatile data manager",
        description: "Problem with the non-volatile memory",
        code: code(0x5100),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::GENERIC,
            Alarms::POSITION_ERROR.union(Alarms::NON_VOLATILE_MEMORY),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::StartupAlarm, 0x0024),
        variant: Variant::Both,
    },
    // Row 4; manual §9.5 "Non-Volatile Data Manager", at
    // runtime.
    DiagnosticSource {
        name: "non_volatile_data_manager_runtime",
        source: "Non-volatile data manager",
        description: "Problem with the non-volatile memory",
        code: code(0x5100),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::NON_VOLATILE_MEMORY,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0024),
        variant: Variant::Both,
    },
    // Row 5; manual §9.5 "Reset Reason Watchdog".
    DiagnosticSource {
        name: "reset_reason_watchdog",
        source: "Reset reason watchdog",
        description: "Software reset due to a watchdog timer issue",
        code: code(0x6100),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::CPU_WATCHDOG,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0025),
        variant: Variant::Both,
    },
    // Row 6; manual §9.5 "CAN-Controller Bus Warning".
    DiagnosticSource {
        name: "can_controller_bus_warning",
        source: "CAN controller bus warning",
        description: "Communication error (bus warning)",
        code: code(0x8100),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::COMMUNICATION,
            Alarms::empty(),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtRuntime),
        injection: None,
        variant: Variant::Both,
    },
    // Row 7; manual §9.5 "CAN-Controller RX Buffer Overflow".
    DiagnosticSource {
        name: "can_controller_rx_buffer_overflow",
        source: "CAN controller RX buffer overflow",
        description: "CAN receive buffer overflow",
        code: code(0x8110),
        appearance: Appearance::Runtime,
        signalling: Signalling::NONE,
        reset: Some(ResetBehaviour::AtRuntime),
        injection: None,
        variant: Variant::Both,
    },
    // Row 8; manual §9.5 "CAN-Controller Bus Passive".
    DiagnosticSource {
        name: "can_controller_bus_passive",
        source: "CAN controller bus passive",
        description: "CAN in error passive mode",
        code: code(0x8120),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::COMMUNICATION,
            Alarms::empty(),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtRuntime),
        injection: None,
        variant: Variant::Both,
    },
    // Row 9; manual §9.5 "CAN-Controller Bus Off": no EMCY is sent.
    DiagnosticSource {
        name: "can_controller_bus_off",
        source: "CAN controller bus off",
        description: "CAN in bus-off mode; no EMCY can be sent",
        code: None,
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::COMMUNICATION,
            Alarms::empty(),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtRuntime),
        injection: None,
        variant: Variant::Both,
    },
    // Row 10; manual §9.5 "Lifeguard or Heartbeat".
    DiagnosticSource {
        name: "lifeguard_or_heartbeat",
        source: "Lifeguard or heartbeat",
        description: "Life guard error or heartbeat error",
        code: code(0x8130),
        appearance: Appearance::Runtime,
        signalling: Signalling::NONE,
        reset: Some(ResetBehaviour::AtRuntime),
        injection: None,
        variant: Variant::Both,
    },
    // Row 11; manual §9.5 "Battery Monitoring Warning
    // (non-redundant encoder)".
    DiagnosticSource {
        name: "battery_monitoring_warning_non_redundant",
        source: "Battery monitoring warning",
        description: "Battery of the multiturn system low; replace the encoder",
        code: code(0xFF00),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::BATTERY_LOW,
        ),
        reset: Some(ResetBehaviour::AtRuntime),
        injection: inject(InjectionKind::Runtime, 0x0005),
        variant: Variant::NonRedundant,
    },
    // Row 12; manual §9.5 "Battery Monitoring Warning
    // (redundant encoder)".
    DiagnosticSource {
        name: "battery_monitoring_warning_redundant",
        source: "Battery monitoring warning",
        description: "Battery of the multiturn system low; replace the encoder",
        code: code(0xFF00),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::BATTERY_LOW,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::StartupWarning, 0x001C),
        variant: Variant::Redundant,
    },
    // Row 13; manual §9.5 "Battery Monitoring Error (Battery Empty)", at
    // startup; reset "(1)".
    DiagnosticSource {
        name: "battery_monitoring_error_startup",
        source: "Battery monitoring error (battery empty)",
        description:
            "Battery of the multiturn system empty; absolute position may be wrong after restart",
        code: code(0xFF01),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::GENERIC,
            Alarms::POSITION_ERROR.union(Alarms::BATTERY_EMPTY),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtRebootExceptRedundant),
        injection: inject(InjectionKind::StartupAlarm, 0x0004),
        variant: Variant::Both,
    },
    // Row 14; manual §9.5 "Battery Monitoring Error (Battery Empty)", at
    // runtime; reset "(1)".
    DiagnosticSource {
        name: "battery_monitoring_error_runtime",
        source: "Battery monitoring error (battery empty)",
        description:
            "Battery of the multiturn system empty; absolute position may be wrong after restart",
        code: code(0xFF01),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MULTITURN_SYSTEM,
        ),
        reset: Some(ResetBehaviour::AtRebootExceptRedundant),
        injection: inject(InjectionKind::Runtime, 0x0004),
        variant: Variant::Both,
    },
    // Row 15; manual §9.5 "Multiturn Magnetic Field sequence (non-redundant
    // encoder)", at startup.
    DiagnosticSource {
        name: "multiturn_magnetic_field_sequence_non_redundant_startup",
        source: "Multiturn magnetic field sequence",
        description: "Wrong magnetic field sequence (weak or disturbed field)",
        code: code(0xFF02),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MOUNTING_ERROR,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::StartupWarning, 0x0003),
        variant: Variant::NonRedundant,
    },
    // Row 16; manual §9.5 "Multiturn Magnetic Field sequence (non-redundant
    // encoder)", at runtime.
    DiagnosticSource {
        name: "multiturn_magnetic_field_sequence_non_redundant_runtime",
        source: "Multiturn magnetic field sequence",
        description: "Wrong magnetic field sequence (weak or disturbed field)",
        code: code(0xFF02),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MOUNTING_ERROR,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0003),
        variant: Variant::NonRedundant,
    },
    // Row 17; manual §9.5 "Multiturn Magnetic Field sequence (redundant
    // encoder)", at startup.
    DiagnosticSource {
        name: "multiturn_magnetic_field_sequence_redundant_startup",
        source: "Multiturn magnetic field sequence",
        description: "Wrong magnetic field sequence (weak or disturbed field)",
        code: code(0xFF02),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::GENERIC,
            Alarms::POSITION_ERROR,
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::NoReset),
        injection: inject(InjectionKind::StartupAlarm, 0x001A),
        variant: Variant::Redundant,
    },
    // Row 18; manual §9.5 "Multiturn Magnetic Field sequence (redundant
    // encoder)", at runtime.
    DiagnosticSource {
        name: "multiturn_magnetic_field_sequence_redundant_runtime",
        source: "Multiturn magnetic field sequence",
        description: "Wrong magnetic field sequence (weak or disturbed field)",
        code: code(0xFF02),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MOUNTING_ERROR,
        ),
        reset: Some(ResetBehaviour::NoReset),
        injection: inject(InjectionKind::Runtime, 0x001A),
        variant: Variant::Redundant,
    },
    // Row 19; manual §9.5 "Multiturn Magnetic Field strength (redundant
    // encoder)", at startup.
    DiagnosticSource {
        name: "multiturn_magnetic_field_strength_redundant_startup",
        source: "Multiturn magnetic field strength",
        description: "Magnetic field too low",
        code: code(0xFF03),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::GENERIC,
            Alarms::POSITION_ERROR,
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::NoReset),
        injection: inject(InjectionKind::StartupAlarm, 0x001B),
        variant: Variant::Redundant,
    },
    // Row 20; manual §9.5 "Multiturn Magnetic Field strength (redundant
    // encoder)", at runtime.
    DiagnosticSource {
        name: "multiturn_magnetic_field_strength_redundant_runtime",
        source: "Multiturn magnetic field strength",
        description: "Magnetic field too low",
        code: code(0xFF03),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MOUNTING_ERROR,
        ),
        reset: Some(ResetBehaviour::NoReset),
        injection: inject(InjectionKind::Runtime, 0x001B),
        variant: Variant::Redundant,
    },
    // Row 21; manual §9.5 "Multiturn Communication Monitor", at startup.
    DiagnosticSource {
        name: "multiturn_communication_monitor_startup",
        source: "Multiturn communication monitor",
        description: "Internal communication error",
        code: code(0xFF04),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::GENERIC,
            Alarms::POSITION_ERROR.union(Alarms::ENCODER_DATA_INVALID),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::StartupAlarm, 0x0009),
        variant: Variant::Both,
    },
    // Row 22; manual §9.5 "Multiturn Communication Monitor", at runtime.
    DiagnosticSource {
        name: "multiturn_communication_monitor_runtime",
        source: "Multiturn communication monitor",
        description: "Internal communication error",
        code: code(0xFF04),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MULTITURN_SYSTEM,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0009),
        variant: Variant::Both,
    },
    // Row 23; manual §9.5 "Speed Monitoring".
    DiagnosticSource {
        name: "speed_monitoring",
        source: "Speed monitoring",
        description: "Maximum rotation speed exceeded",
        code: code(0xFF05),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::FREQUENCY_EXCEEDED,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0021),
        variant: Variant::Both,
    },
    // Row 24; manual §9.5 "Singleturn Magnetic Field
    // strength".
    DiagnosticSource {
        name: "singleturn_magnetic_field_strength",
        source: "Singleturn magnetic field strength",
        description: "Singleturn sensor amplitude out of range (weak or disturbed field)",
        code: code(0xFF06),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::SINGLETURN_SYSTEM,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0022),
        variant: Variant::Both,
    },
    // Row 25; manual §9.5 "Singleturn/Multiturn Supervision".
    DiagnosticSource {
        name: "singleturn_multiturn_supervision",
        source: "Singleturn/multiturn supervision",
        description: "Singleturn and multiturn sensors out of sync",
        code: code(0xFF07),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MULTITURN_SUPERVISION,
        ),
        reset: Some(ResetBehaviour::AtReboot),
        injection: inject(InjectionKind::Runtime, 0x0023),
        variant: Variant::Both,
    },
    // Row 26; manual §9.5 "Multiturn Power On Reset
    // (redundant encoder)", at startup.
    DiagnosticSource {
        name: "multiturn_power_on_reset_redundant_startup",
        source: "Multiturn power-on reset",
        description: "Power-on reset of the multiturn system; absolute position may be wrong",
        code: code(0xFF17),
        appearance: Appearance::Startup,
        signalling: Signalling::new(
            ErrorRegister::GENERIC,
            Alarms::POSITION_ERROR.union(Alarms::BATTERY_EMPTY),
            Warnings::empty(),
        ),
        reset: Some(ResetBehaviour::NoReset),
        injection: inject(InjectionKind::StartupAlarm, 0x0014),
        variant: Variant::Redundant,
    },
    // Row 27; manual §9.5 "Multiturn Power On Reset
    // (redundant encoder)", at runtime.
    DiagnosticSource {
        name: "multiturn_power_on_reset_redundant_runtime",
        source: "Multiturn power-on reset",
        description: "Power-on reset of the multiturn system; absolute position may be wrong",
        code: code(0xFF17),
        appearance: Appearance::Runtime,
        signalling: Signalling::new(
            ErrorRegister::empty(),
            Alarms::empty(),
            Warnings::MULTITURN_SYSTEM,
        ),
        reset: Some(ResetBehaviour::NoReset),
        injection: inject(InjectionKind::Runtime, 0x0014),
        variant: Variant::Redundant,
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    const STARTUP: Appearance = Appearance::Startup;
    const RUNTIME: Appearance = Appearance::Runtime;
    const BOTH: Variant = Variant::Both;
    const REDUNDANT: Variant = Variant::Redundant;
    const NON_REDUNDANT: Variant = Variant::NonRedundant;
    const AT_RUNTIME: Option<ResetBehaviour> = Some(ResetBehaviour::AtRuntime);
    const AT_REBOOT: Option<ResetBehaviour> = Some(ResetBehaviour::AtReboot);
    const AT_REBOOT_1: Option<ResetBehaviour> = Some(ResetBehaviour::AtRebootExceptRedundant);
    const NO_RESET: Option<ResetBehaviour> = Some(ResetBehaviour::NoReset);

    /// One row of the diagnostic-source table (Baumer EAM580 manual §9.5),
    /// written out by hand: signalling as lists of bit numbers.
    struct ManualRow {
        name: &'static str,
        source: &'static str,
        /// A phrase that the row's description contains.
        says: &'static str,
        code: Option<u16>,
        appearance: Appearance,
        register_bits: &'static [u8],
        alarm_bits: &'static [u8],
        warning_bits: &'static [u8],
        reset: Option<ResetBehaviour>,
        injection: Option<u32>,
        variant: Variant,
    }

    #[rustfmt::skip]
    const MANUAL_TABLE: [ManualRow; 27] = [
        ManualRow { name: "error_reset_or_no_error", source: "error reset or no error", says: "no error", code: Some(0x0000), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[], reset: None, injection: Some(0x0000_0000), variant: BOTH },
        ManualRow { name: "temperature_monitoring", source: "temperature monitoring", says: "temperature out of range", code: Some(0x4200), appearance: RUNTIME, register_bits: &[0, 3], alarm_bits: &[], warning_bits: &[], reset: AT_RUNTIME, injection: Some(0x0008_0020), variant: BOTH },
        ManualRow { name: "non_volatile_data_manager_startup", source: "non-volatile data manager", says: "problem with the non-volatile memory", code: Some(0x5100), appearance: STARTUP, register_bits: &[0], alarm_bits: &[0, 1], warning_bits: &[], reset: AT_REBOOT, injection: Some(0x0001_0024), variant: BOTH },
        ManualRow { name: "non_volatile_data_manager_runtime", source: "non-volatile data manager", says: "problem with the non-volatile memory", code: Some(0x5100), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[3], reset: AT_REBOOT, injection: Some(0x0008_0024), variant: BOTH },
        ManualRow { name: "reset_reason_watchdog", source: "reset reason watchdog", says: "watchdog timer issue", code: Some(0x6100), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[2], reset: AT_REBOOT, injection: Some(0x0008_0025), variant: BOTH },
        ManualRow { name: "can_controller_bus_warning", source: "can controller bus warning", says: "bus warning", code: Some(0x8100), appearance: RUNTIME, register_bits: &[4], alarm_bits: &[], warning_bits: &[], reset: AT_RUNTIME, injection: None, variant: BOTH },
        ManualRow { name: "can_controller_rx_buffer_overflow", source: "can controller rx buffer overflow", says: "receive buffer overflow", code: Some(0x8110), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[], reset: AT_RUNTIME, injection: None, variant: BOTH },
        ManualRow { name: "can_controller_bus_passive", source: "can controller bus passive", says: "error passive mode", code: Some(0x8120), appearance: RUNTIME, register_bits: &[4], alarm_bits: &[], warning_bits: &[], reset: AT_RUNTIME, injection: None, variant: BOTH },
        ManualRow { name: "can_controller_bus_off", source: "can controller bus off", says: "bus-off mode", code: None, appearance: RUNTIME, register_bits: &[4], alarm_bits: &[], warning_bits: &[], reset: AT_RUNTIME, injection: None, variant: BOTH },
        ManualRow { name: "lifeguard_or_heartbeat", source: "lifeguard or heartbeat", says: "life guard error or heartbeat error", code: Some(0x8130), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[], reset: AT_RUNTIME, injection: None, variant: BOTH },
        ManualRow { name: "battery_monitoring_warning_non_redundant", source: "battery monitoring warning", says: "replace the encoder", code: Some(0xFF00), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[4], reset: AT_RUNTIME, injection: Some(0x0008_0005), variant: NON_REDUNDANT },
        ManualRow { name: "battery_monitoring_warning_redundant", source: "battery monitoring warning", says: "replace the encoder", code: Some(0xFF00), appearance: STARTUP, register_bits: &[], alarm_bits: &[], warning_bits: &[4], reset: AT_REBOOT, injection: Some(0x0004_001C), variant: REDUNDANT },
        ManualRow { name: "battery_monitoring_error_startup", source: "battery monitoring error (battery empty)", says: "absolute position may be wrong after restart", code: Some(0xFF01), appearance: STARTUP, register_bits: &[0], alarm_bits: &[0, 15], warning_bits: &[], reset: AT_REBOOT_1, injection: Some(0x0001_0004), variant: BOTH },
        ManualRow { name: "battery_monitoring_error_runtime", source: "battery monitoring error (battery empty)", says: "absolute position may be wrong after restart", code: Some(0xFF01), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[13], reset: AT_REBOOT_1, injection: Some(0x0008_0004), variant: BOTH },
        ManualRow { name: "multiturn_magnetic_field_sequence_non_redundant_startup", source: "multiturn magnetic field sequence", says: "weak or disturbed field", code: Some(0xFF02), appearance: STARTUP, register_bits: &[], alarm_bits: &[], warning_bits: &[12], reset: AT_REBOOT, injection: Some(0x0004_0003), variant: NON_REDUNDANT },
        ManualRow { name: "multiturn_magnetic_field_sequence_non_redundant_runtime", source: "multiturn magnetic field sequence", says: "weak or disturbed field", code: Some(0xFF02), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[12], reset: AT_REBOOT, injection: Some(0x0008_0003), variant: NON_REDUNDANT },
        ManualRow { name: "multiturn_magnetic_field_sequence_redundant_startup", source: "multiturn magnetic field sequence", says: "weak or disturbed field", code: Some(0xFF02), appearance: STARTUP, register_bits: &[0], alarm_bits: &[0], warning_bits: &[], reset: NO_RESET, injection: Some(0x0001_001A), variant: REDUNDANT },
        ManualRow { name: "multiturn_magnetic_field_sequence_redundant_runtime", source: "multiturn magnetic field sequence", says: "weak or disturbed field", code: Some(0xFF02), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[12], reset: NO_RESET, injection: Some(0x0008_001A), variant: REDUNDANT },
        ManualRow { name: "multiturn_magnetic_field_strength_redundant_startup", source: "multiturn magnetic field strength", says: "field too low", code: Some(0xFF03), appearance: STARTUP, register_bits: &[0], alarm_bits: &[0], warning_bits: &[], reset: NO_RESET, injection: Some(0x0001_001B), variant: REDUNDANT },
        ManualRow { name: "multiturn_magnetic_field_strength_redundant_runtime", source: "multiturn magnetic field strength", says: "field too low", code: Some(0xFF03), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[12], reset: NO_RESET, injection: Some(0x0008_001B), variant: REDUNDANT },
        ManualRow { name: "multiturn_communication_monitor_startup", source: "multiturn communication monitor", says: "internal communication error", code: Some(0xFF04), appearance: STARTUP, register_bits: &[0], alarm_bits: &[0, 12], warning_bits: &[], reset: AT_REBOOT, injection: Some(0x0001_0009), variant: BOTH },
        ManualRow { name: "multiturn_communication_monitor_runtime", source: "multiturn communication monitor", says: "internal communication error", code: Some(0xFF04), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[13], reset: AT_REBOOT, injection: Some(0x0008_0009), variant: BOTH },
        ManualRow { name: "speed_monitoring", source: "speed monitoring", says: "maximum rotation speed exceeded", code: Some(0xFF05), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[0], reset: AT_REBOOT, injection: Some(0x0008_0021), variant: BOTH },
        ManualRow { name: "singleturn_magnetic_field_strength", source: "singleturn magnetic field strength", says: "amplitude out of range", code: Some(0xFF06), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[14], reset: AT_REBOOT, injection: Some(0x0008_0022), variant: BOTH },
        ManualRow { name: "singleturn_multiturn_supervision", source: "singleturn/multiturn supervision", says: "out of sync", code: Some(0xFF07), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[15], reset: AT_REBOOT, injection: Some(0x0008_0023), variant: BOTH },
        ManualRow { name: "multiturn_power_on_reset_redundant_startup", source: "multiturn power-on reset", says: "absolute position may be wrong", code: Some(0xFF17), appearance: STARTUP, register_bits: &[0], alarm_bits: &[0, 15], warning_bits: &[], reset: NO_RESET, injection: Some(0x0001_0014), variant: REDUNDANT },
        ManualRow { name: "multiturn_power_on_reset_redundant_runtime", source: "multiturn power-on reset", says: "absolute position may be wrong", code: Some(0xFF17), appearance: RUNTIME, register_bits: &[], alarm_bits: &[], warning_bits: &[13], reset: NO_RESET, injection: Some(0x0008_0014), variant: REDUNDANT },
    ];

    /// The word with the listed bits set.
    fn bits(list: &[u8]) -> u16 {
        list.iter().fold(0, |word, &bit| word | 1 << bit)
    }

    fn names<'a>(rows: impl Iterator<Item = &'a DiagnosticSource>) -> Vec<&'static str> {
        rows.map(|row| row.name()).collect()
    }

    #[test]
    fn every_row_matches_manual_table_field_by_field() {
        assert_eq!(DIAGNOSTIC_SOURCES.len(), MANUAL_TABLE.len());
        for (row, spec) in DIAGNOSTIC_SOURCES.iter().zip(&MANUAL_TABLE) {
            let name = spec.name;
            assert_eq!(row.name(), name);
            assert_eq!(row.source().to_lowercase(), spec.source, "{name}: source");
            assert!(
                row.description().to_lowercase().contains(spec.says),
                "{name}: description {:?} should say {:?}",
                row.description(),
                spec.says
            );
            assert_eq!(row.code(), spec.code.map(ErrorCode::new), "{name}: code");
            assert_eq!(row.appearance(), spec.appearance, "{name}: appearance");
            let signalling = row.signalling();
            assert_eq!(
                u16::from(signalling.register.bits()),
                bits(spec.register_bits),
                "{name}: 1001h bits"
            );
            assert_eq!(
                signalling.alarms.bits(),
                bits(spec.alarm_bits),
                "{name}: 6503h bits"
            );
            assert_eq!(
                signalling.warnings.bits(),
                bits(spec.warning_bits),
                "{name}: 6505h bits"
            );
            assert_eq!(row.reset(), spec.reset, "{name}: reset");
            assert_eq!(
                row.injection().map(InjectionCode::get),
                spec.injection,
                "{name}: injection"
            );
            assert_eq!(row.variant(), spec.variant, "{name}: variant");
        }
    }

    #[test]
    fn row_count_is_manual_table_row_count() {
        assert_eq!(DIAGNOSTIC_SOURCE_COUNT, 27);
        // The reset row and the bus-off row (no EMCY) are both present.
        assert_eq!(DIAGNOSTIC_SOURCES[0].code(), Some(ErrorCode::NO_ERROR));
        let no_emcy: Vec<_> = names(DIAGNOSTIC_SOURCES.iter().filter(|s| s.code().is_none()));
        assert_eq!(no_emcy, ["can_controller_bus_off"]);
    }

    #[test]
    fn names_are_unique_snake_case() {
        for (i, row) in DIAGNOSTIC_SOURCES.iter().enumerate() {
            let name = row.name();
            assert!(
                !name.is_empty()
                    && !name.starts_with('_')
                    && !name.ends_with('_')
                    && !name.contains("__")
                    && name.bytes().all(|b| b.is_ascii_lowercase() || b == b'_'),
                "{name:?} is not snake_case"
            );
            for other in &DIAGNOSTIC_SOURCES[i + 1..] {
                assert_ne!(name, other.name());
            }
            assert_eq!(source_by_name(name), Some(row));
        }
        assert_eq!(source_by_name("battery_monitoring_error"), None);
        assert_eq!(source_by_name(""), None);
    }

    #[test]
    fn injection_codes_are_unique() {
        let codes: Vec<_> = DIAGNOSTIC_SOURCES
            .iter()
            .filter_map(|s| s.injection())
            .collect();
        // Every row but the four CAN controller rows and lifeguard/heartbeat.
        assert_eq!(codes.len(), DIAGNOSTIC_SOURCE_COUNT - 5);
        for (i, code) in codes.iter().enumerate() {
            assert!(!codes[i + 1..].contains(code), "{code} twice");
        }
    }

    #[test]
    fn injection_high_word_matches_appearance() {
        for row in DIAGNOSTIC_SOURCES.iter() {
            let Some(injection) = row.injection() else {
                continue;
            };
            let name = row.name();
            match injection.kind() {
                None => {
                    assert_eq!(injection, InjectionCode::NO_ERROR, "{name}");
                    assert_eq!(row.code(), Some(ErrorCode::NO_ERROR), "{name}");
                }
                Some(kind) => {
                    assert_eq!(kind.appearance(), row.appearance(), "{name}");
                    let high = injection.get() >> 16;
                    let expected = match row.appearance() {
                        Appearance::Startup => [0x0001, 0x0004].contains(&high),
                        Appearance::Runtime => high == 0x0008,
                    };
                    assert!(expected, "{name}: {injection}");
                    // A startup alarm signals 6503h bits, a startup warning
                    // only 6505h bits.
                    match kind {
                        InjectionKind::StartupAlarm => {
                            assert!(!row.signalling().alarms.is_empty(), "{name}")
                        }
                        InjectionKind::StartupWarning => {
                            assert!(row.signalling().alarms.is_empty(), "{name}");
                            assert!(!row.signalling().warnings.is_empty(), "{name}");
                        }
                        InjectionKind::Runtime => {}
                    }
                }
            }
        }
    }

    #[test]
    fn look_up_by_injection_code_finds_at_most_one_row() {
        for row in DIAGNOSTIC_SOURCES.iter() {
            if let Some(injection) = row.injection() {
                assert_eq!(source_for_injection(injection), Some(row), "{injection}");
            }
        }
        let unknown = [
            InjectionCode::new(InjectionKind::Runtime, 0x0001),
            InjectionCode::new(InjectionKind::StartupWarning, 0x0024),
            InjectionCode::new(InjectionKind::StartupAlarm, 0x0005),
        ];
        for injection in unknown {
            assert_eq!(source_for_injection(injection), None, "{injection}");
        }
    }

    /// docs/canopen.md#baumer: every EMCY code of the table and the rows it
    /// has, in order.
    #[rustfmt::skip]
    const ROWS_BY_CODE: &[(u16, &[&str])] = &[
        (0x0000, &["error_reset_or_no_error"]),
        (0x4200, &["temperature_monitoring"]),
        (0x5100, &["non_volatile_data_manager_startup", "non_volatile_data_manager_runtime"]),
        (0x6100, &["reset_reason_watchdog"]),
        (0x8100, &["can_controller_bus_warning"]),
        (0x8110, &["can_controller_rx_buffer_overflow"]),
        (0x8120, &["can_controller_bus_passive"]),
        (0x8130, &["lifeguard_or_heartbeat"]),
        (0xFF00, &["battery_monitoring_warning_non_redundant", "battery_monitoring_warning_redundant"]),
        (0xFF01, &["battery_monitoring_error_startup", "battery_monitoring_error_runtime"]),
        (0xFF02, &[
            "multiturn_magnetic_field_sequence_non_redundant_startup",
            "multiturn_magnetic_field_sequence_non_redundant_runtime",
            "multiturn_magnetic_field_sequence_redundant_startup",
            "multiturn_magnetic_field_sequence_redundant_runtime",
        ]),
        (0xFF03, &["multiturn_magnetic_field_strength_redundant_startup", "multiturn_magnetic_field_strength_redundant_runtime"]),
        (0xFF04, &["multiturn_communication_monitor_startup", "multiturn_communication_monitor_runtime"]),
        (0xFF05, &["speed_monitoring"]),
        (0xFF06, &["singleturn_magnetic_field_strength"]),
        (0xFF07, &["singleturn_multiturn_supervision"]),
        (0xFF17, &["multiturn_power_on_reset_redundant_startup", "multiturn_power_on_reset_redundant_runtime"]),
    ];

    #[test]
    fn look_up_by_code_returns_exactly_the_expected_rows() {
        for raw in 0..=u16::MAX {
            let expected: &[&str] = ROWS_BY_CODE
                .iter()
                .find(|&&(code, _)| code == raw)
                .map_or(&[], |&(_, rows)| rows);
            assert_eq!(
                names(sources_for_code(ErrorCode::new(raw))),
                expected,
                "{raw:#06x}"
            );
        }
        // Together the codes cover every row but bus off.
        let total: usize = ROWS_BY_CODE.iter().map(|(_, rows)| rows.len()).sum();
        assert_eq!(total, DIAGNOSTIC_SOURCE_COUNT - 1);
    }

    /// An EMCY with `code`, alarms and warnings as the encoder sends it.
    fn emcy(code: u16, alarms: u16, warnings: u16) -> Emcy {
        BaumerEmcy::new(
            ErrorCode::new(code),
            ErrorRegister::empty(),
            BaumerManufacturer::new(
                Alarms::from_bits_retain(alarms),
                Warnings::from_bits_retain(warnings),
            ),
        )
        .to_emcy()
    }

    #[test]
    fn startup_and_runtime_rows_told_apart_by_alarm_and_warning_bits() {
        #[rustfmt::skip]
        let table: &[(u16, u16, u16, &[&str])] = &[
            // code, 6503h, 6505h, rows
            (0x5100, 0x0003, 0x0000, &["non_volatile_data_manager_startup"]),
            (0x5100, 0x0000, 0x0008, &["non_volatile_data_manager_runtime"]),
            (0xFF01, 0x8001, 0x0000, &["battery_monitoring_error_startup"]),
            (0xFF01, 0x0000, 0x2000, &["battery_monitoring_error_runtime"]),
            (0xFF02, 0x0001, 0x0000, &["multiturn_magnetic_field_sequence_redundant_startup"]),
            (0xFF02, 0x0000, 0x1000, &[
                "multiturn_magnetic_field_sequence_non_redundant_startup",
                "multiturn_magnetic_field_sequence_non_redundant_runtime",
                "multiturn_magnetic_field_sequence_redundant_runtime",
            ]),
            (0xFF03, 0x0001, 0x0000, &["multiturn_magnetic_field_strength_redundant_startup"]),
            (0xFF03, 0x0000, 0x1000, &["multiturn_magnetic_field_strength_redundant_runtime"]),
            (0xFF04, 0x1001, 0x0000, &["multiturn_communication_monitor_startup"]),
            (0xFF04, 0x0000, 0x2000, &["multiturn_communication_monitor_runtime"]),
            (0xFF17, 0x8001, 0x0000, &["multiturn_power_on_reset_redundant_startup"]),
            (0xFF17, 0x0000, 0x2000, &["multiturn_power_on_reset_redundant_runtime"]),
            // Other active alarms and warnings do not hide a row's bits.
            (0x5100, 0x8103, 0x0004, &["non_volatile_data_manager_startup"]),
            (0xFF01, 0x0001, 0x2010, &["battery_monitoring_error_runtime"]),
        ];
        for &(code, alarms, warnings, expected) in table {
            assert_eq!(
                names(matching_sources(&emcy(code, alarms, warnings))),
                expected,
                "{code:#06x} alarms {alarms:#06x} warnings {warnings:#06x}"
            );
        }
    }

    #[test]
    fn without_telling_bits_every_row_of_the_code() {
        #[rustfmt::skip]
        let table: &[(u16, u16, u16)] = &[
            (0x5100, 0x0000, 0x0000), // no bits at all
            (0x5100, 0x0001, 0x0000), // bit 1 of the startup row missing
            (0xFF04, 0x0001, 0x0000), // bit 12 of the startup row missing
            (0xFF01, 0x8001, 0x2000), // both rows' bits present
            (0xFF00, 0x0000, 0x0010), // both rows signal warning bit 4
            (0xFF02, 0x0001, 0x1000), // every row's bits present
        ];
        for &(code, alarms, warnings) in table {
            let all = names(sources_for_code(ErrorCode::new(code)));
            assert!(all.len() > 1);
            assert_eq!(
                names(matching_sources(&emcy(code, alarms, warnings))),
                all,
                "{code:#06x} alarms {alarms:#06x} warnings {warnings:#06x}"
            );
        }
    }

    #[test]
    fn rows_without_alarm_or_warning_bits_match_on_the_code_alone() {
        for (code, rows) in [
            (0x4200, ["temperature_monitoring"]),
            (0x8100, ["can_controller_bus_warning"]),
            (0x8130, ["lifeguard_or_heartbeat"]),
        ] {
            for (alarms, warnings) in [(0, 0), (0xFFFF, 0xFFFF), (0x0001, 0x1000)] {
                assert_eq!(names(matching_sources(&emcy(code, alarms, warnings))), rows);
            }
        }
    }

    #[test]
    fn codes_outside_the_table_match_no_row() {
        for code in [0x1000, 0x5000, 0x8110 + 1, 0xFF08, 0xFF09, 0xFF0A, 0xFF18] {
            assert_eq!(matching_sources(&emcy(code, 0xFFFF, 0xFFFF)).count(), 0);
        }
    }

    #[test]
    fn any_reset_code_is_the_reset_row() {
        // The Decision in docs/canopen.md#emcy-codes: any 0x00xx is "error
        // reset or no error".
        for code in [0x0000, 0x0001, 0x00FF] {
            assert_eq!(
                names(matching_sources(&emcy(code, 0, 0))),
                ["error_reset_or_no_error"],
                "{code:#06x}"
            );
        }
        assert_eq!(sources_for_code(ErrorCode::new(0x0001)).count(), 0);
    }

    #[test]
    fn each_rows_own_emcy_finds_the_row() {
        for row in DIAGNOSTIC_SOURCES.iter() {
            let Some(sent) = row.emcy() else {
                assert_eq!(row.name(), "can_controller_bus_off");
                continue;
            };
            assert_eq!(Some(sent.code), row.code());
            assert_eq!(sent.register, row.signalling().register);
            assert!(sent.sources().any(|found| found == row), "{}", row.name());
            // The row's own bits never select a row of another appearance
            // unless that row signals the same bits.
            for found in sent.sources() {
                assert!(
                    found.appearance() == row.appearance()
                        || found.signalling().alarms == row.signalling().alarms
                            && found.signalling().warnings == row.signalling().warnings,
                    "{} found {}",
                    row.name(),
                    found.name()
                );
            }
        }
    }

    #[test]
    fn signalled_register_bits_are_the_ones_the_encoder_uses() {
        let used = DIAGNOSTIC_SOURCES
            .iter()
            .fold(ErrorRegister::empty(), |acc, s| {
                acc | s.signalling().register
            });
        assert_eq!(used, ERROR_REGISTER_BITS);
        assert_eq!(ERROR_REGISTER_BITS.bits(), 0b0001_1001);
    }

    #[test]
    fn named_bits_are_the_ones_the_table_uses() {
        let (alarms, warnings) = DIAGNOSTIC_SOURCES
            .iter()
            .fold((Alarms::empty(), Warnings::empty()), |(a, w), s| {
                (a | s.signalling().alarms, w | s.signalling().warnings)
            });
        assert_eq!(alarms, Alarms::all());
        assert_eq!(warnings, Warnings::all());
    }

    #[test]
    fn alarm_and_warning_bit_positions() {
        let alarms = [
            (Alarms::POSITION_ERROR, 0),
            (Alarms::NON_VOLATILE_MEMORY, 1),
            (Alarms::ENCODER_DATA_INVALID, 12),
            (Alarms::BATTERY_EMPTY, 15),
        ];
        for (flag, bit) in alarms {
            assert_eq!(flag.bits(), 1 << bit, "{flag:?}");
        }
        let warnings = [
            (Warnings::FREQUENCY_EXCEEDED, 0),
            (Warnings::CPU_WATCHDOG, 2),
            (Warnings::NON_VOLATILE_MEMORY, 3),
            (Warnings::BATTERY_LOW, 4),
            (Warnings::MOUNTING_ERROR, 12),
            (Warnings::MULTITURN_SYSTEM, 13),
            (Warnings::SINGLETURN_SYSTEM, 14),
            (Warnings::MULTITURN_SUPERVISION, 15),
        ];
        for (flag, bit) in warnings {
            assert_eq!(flag.bits(), 1 << bit, "{flag:?}");
        }
        assert_eq!(Alarms::OBJECT_INDEX, 0x6503);
        assert_eq!(Warnings::OBJECT_INDEX, 0x6505);
    }

    #[test]
    fn encoder_facts() {
        assert_eq!(ERROR_HISTORY_LEN, 8);
        assert_eq!(INJECTION_OBJECT_INDEX, 0x2116);
        assert_eq!(MANUFACTURER_LEN, 5);
    }

    #[test]
    fn reserved_codes() {
        for raw in 0..=u16::MAX {
            let reserved = (0xFF0A..=0xFF16).contains(&raw) || (0xFF18..=0xFFFF).contains(&raw);
            let code = ErrorCode::new(raw);
            assert_eq!(is_reserved_code(code), reserved, "{raw:#06x}");
            if reserved {
                assert_eq!(sources_for_code(code).count(), 0, "{raw:#06x}");
            }
        }
        for (raw, reserved) in [
            (0xFF07, false),
            (0xFF09, false),
            (0xFF0A, true),
            (0xFF16, true),
            (0xFF17, false),
            (0xFF18, true),
            (0xFFFF, true),
        ] {
            assert_eq!(
                is_reserved_code(ErrorCode::new(raw)),
                reserved,
                "{raw:#06x}"
            );
        }
    }

    #[test]
    fn reset_behaviour_on_each_variant() {
        use ResetBehaviour::*;
        let table = [
            (AtRebootExceptRedundant, Variant::Redundant, NoReset),
            (AtRebootExceptRedundant, Variant::NonRedundant, AtReboot),
            (
                AtRebootExceptRedundant,
                Variant::Both,
                AtRebootExceptRedundant,
            ),
            (AtReboot, Variant::Redundant, AtReboot),
            (AtRuntime, Variant::NonRedundant, AtRuntime),
            (NoReset, Variant::Both, NoReset),
        ];
        for (behaviour, variant, expected) in table {
            assert_eq!(behaviour.on(variant), expected, "{behaviour:?} {variant:?}");
        }
    }

    #[test]
    fn injection_code_construction() {
        let table = [
            (0x0000_0000, Ok(None)),
            (0x0001_0024, Ok(Some(InjectionKind::StartupAlarm))),
            (0x0004_001C, Ok(Some(InjectionKind::StartupWarning))),
            (0x0008_FFFF, Ok(Some(InjectionKind::Runtime))),
            (0x0000_0001, Err(())),
            (0x0002_0000, Err(())),
            (0x0010_0020, Err(())),
            (0xFFFF_FFFF, Err(())),
        ];
        for (raw, expected) in table {
            let code = InjectionCode::try_new(raw);
            match expected {
                Ok(kind) => {
                    let code = code.unwrap();
                    assert_eq!(code.get(), raw);
                    assert_eq!(code.kind(), kind);
                    assert_eq!(code.number(), (raw & 0xFFFF) as u16);
                }
                Err(()) => assert_eq!(
                    code,
                    Err(ValueError {
                        what: What::ErrorInjectionCode,
                        found: raw,
                        expected: "0x00000000 or a high word of 0x0001, 0x0004 or 0x0008",
                    }),
                    "{raw:#010x}"
                ),
            }
        }
        assert_eq!(
            InjectionCode::new(InjectionKind::Runtime, 0x0020).get(),
            0x0008_0020
        );
        assert_eq!(
            InjectionCode::new(InjectionKind::StartupWarning, 0x001C).to_string(),
            "0x0004_001C"
        );
        for kind in [
            InjectionKind::StartupAlarm,
            InjectionKind::StartupWarning,
            InjectionKind::Runtime,
        ] {
            assert_eq!(InjectionKind::from_high_word(kind.high_word()), Some(kind));
        }
    }

    /// Multiturn communication monitor at startup (docs/canopen.md#baumer):
    /// code 0xFF04, register bit 0, alarms bits 0 and 12, unused byte 0xA5.
    static FRAME_BYTES: [u8; 8] = [0x04, 0xFF, 0x01, 0x01, 0x10, 0x00, 0x00, 0xA5];

    #[test]
    fn deconstruct() {
        let emcy = BaumerEmcy::from_bytes(&FRAME_BYTES);
        assert_eq!(emcy.code, ErrorCode::new(0xFF04));
        assert_eq!(emcy.register, ErrorRegister::GENERIC);
        assert_eq!(
            emcy.manufacturer.alarms,
            Alarms::POSITION_ERROR | Alarms::ENCODER_DATA_INVALID
        );
        assert_eq!(emcy.manufacturer.warnings, Warnings::empty());
        assert_eq!(emcy.manufacturer.unused, 0xA5);
        assert_eq!(
            names(emcy.sources()),
            ["multiturn_communication_monitor_startup"]
        );
    }

    #[test]
    fn construct() {
        let mut manufacturer = BaumerManufacturer::new(
            Alarms::POSITION_ERROR | Alarms::ENCODER_DATA_INVALID,
            Warnings::empty(),
        );
        manufacturer.unused = 0xA5;
        let emcy = BaumerEmcy::new(ErrorCode::new(0xFF04), ErrorRegister::GENERIC, manufacturer);
        assert_eq!(emcy.to_bytes(), FRAME_BYTES);
        assert_eq!(Emcy::from(emcy).to_bytes(), FRAME_BYTES);
    }

    #[test]
    fn manufacturer_field_is_little_endian() {
        // Alarms 0x8001 in bytes 3–4, warnings 0x2010 in bytes 5–6.
        let field = BaumerManufacturer::from_bytes(&[0x01, 0x80, 0x10, 0x20, 0x00]);
        assert_eq!(field.alarms, Alarms::POSITION_ERROR | Alarms::BATTERY_EMPTY);
        assert_eq!(
            field.warnings,
            Warnings::BATTERY_LOW | Warnings::MULTITURN_SYSTEM
        );
        assert_eq!(field.to_bytes(), [0x01, 0x80, 0x10, 0x20, 0x00]);
    }

    #[test]
    fn unnamed_bits_survive() {
        let bytes = [0x00, 0x00, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF];
        let emcy = BaumerEmcy::from_bytes(&bytes);
        assert_eq!(emcy.manufacturer.alarms.bits(), 0xFFFF);
        assert_eq!(emcy.manufacturer.warnings.bits(), 0xFFFF);
        assert_eq!(emcy.to_bytes(), bytes);
    }

    #[test]
    fn parse_and_emit() {
        let emcy = BaumerEmcy::parse(&FRAME_BYTES).unwrap();
        assert_eq!(emcy, BaumerEmcy::from_bytes(&FRAME_BYTES));
        assert_eq!(emcy.to_emcy(), Emcy::from_bytes(&FRAME_BYTES));
        assert_eq!(BaumerEmcy::from(Emcy::from_bytes(&FRAME_BYTES)), emcy);
        // Bytes after the eighth are not part of the EMCY.
        let mut longer = [0u8; 12];
        longer[..8].copy_from_slice(&FRAME_BYTES);
        assert_eq!(BaumerEmcy::parse(&longer), Ok(emcy));
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        for len in 0..EMCY_LEN {
            assert_eq!(
                BaumerEmcy::parse(&FRAME_BYTES[..len]),
                Err(LenError {
                    what: What::EmcyFrame,
                    expected: 8,
                    found: len,
                })
            );
        }
    }

    #[test]
    fn display() {
        let row = source_by_name("speed_monitoring").unwrap();
        assert_eq!(
            row.to_string(),
            "Speed monitoring: Maximum rotation speed exceeded"
        );
        assert_eq!(Appearance::Startup.name(), "startup");
        assert_eq!(Appearance::Runtime.name(), "runtime");
        assert_eq!(Variant::NonRedundant.name(), "non_redundant");
        assert_eq!(Variant::Redundant.name(), "redundant");
        assert_eq!(Variant::Both.name(), "both");
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::baumer::{baumer_emcy, injection_code, manufacturer, table_emcy};

    proptest! {
        #[test]
        fn bytes_decoded_encoded_are_the_same_bytes(bytes in any::<[u8; 8]>()) {
            let emcy = BaumerEmcy::from_bytes(&bytes);
            prop_assert_eq!(emcy.to_bytes(), bytes);
            prop_assert_eq!(emcy.to_emcy(), Emcy::from_bytes(&bytes));
            prop_assert_eq!(BaumerEmcy::from_emcy(&Emcy::from_bytes(&bytes)).to_emcy().to_bytes(), bytes);
        }

        #[test]
        fn owned_encoded_decoded_is_the_same_value(value in baumer_emcy()) {
            prop_assert_eq!(BaumerEmcy::from_bytes(&value.to_bytes()), value);
            prop_assert_eq!(BaumerEmcy::from_emcy(&value.to_emcy()), value);
        }

        #[test]
        fn manufacturer_round_trip(value in manufacturer()) {
            prop_assert_eq!(BaumerManufacturer::from_bytes(&value.to_bytes()), value);
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..16)) {
            match BaumerEmcy::parse(&data) {
                Ok(value) => prop_assert_eq!(&value.to_bytes()[..], &data[..8]),
                Err(e) => prop_assert_eq!(e, LenError { what: What::EmcyFrame, expected: 8, found: data.len() }),
            }
        }

        #[test]
        fn matching_rows_are_rows_of_the_code(bytes in any::<[u8; 8]>()) {
            let emcy = Emcy::from_bytes(&bytes);
            let code = if emcy.code.is_reset() { ErrorCode::NO_ERROR } else { emcy.code };
            let all: Vec<_> = sources_for_code(code).collect();
            let found: Vec<_> = matching_sources(&emcy).collect();
            prop_assert_eq!(found.is_empty(), all.is_empty());
            for row in &found {
                prop_assert!(all.contains(row));
            }
        }

        #[test]
        fn a_table_code_always_matches_some_row(emcy in table_emcy()) {
            let field = BaumerManufacturer::from_bytes(&emcy.manufacturer);
            let found: Vec<_> = matching_sources(&emcy).collect();
            prop_assert!(!found.is_empty());
            // Either every found row's bits are present, or none of the
            // code's rows has its bits present and all of them are returned.
            let told_apart = sources_for_code(emcy.code).any(|row| row.is_signalled_in(&field));
            if told_apart {
                prop_assert!(found.iter().all(|row| row.is_signalled_in(&field)));
            } else {
                prop_assert_eq!(found.len(), sources_for_code(emcy.code).count());
            }
        }

        #[test]
        fn injection_code_accepts_exactly_the_known_high_words(raw in any::<u32>()) {
            let valid = raw == 0 || [0x0001, 0x0004, 0x0008].contains(&(raw >> 16));
            let code = InjectionCode::try_new(raw);
            prop_assert_eq!(code.is_ok(), valid);
            if let Ok(code) = code {
                prop_assert_eq!(code.get(), raw);
                prop_assert!(source_for_injection(code).map_or(true, |row| row.injection() == Some(code)));
            }
        }

        #[test]
        fn injection_code_from_parts_round_trips(code in injection_code()) {
            prop_assert_eq!(InjectionCode::try_new(code.get()), Ok(code));
        }
    }
}
