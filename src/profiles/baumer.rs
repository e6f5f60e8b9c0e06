//! Baumer EAM580 absolute encoder: its EMCY manufacturer field and its
//! diagnostic sources (SPEC §4; Baumer EAM580 CANopen manual §8 "Emergency
//! message" and §9.5 "Encoder diagnostic sources", `seeds/003_*.txt`).
//!
//! The encoder sends the alarms object 6503h in bytes 3–4 and the warnings
//! object 6505h in bytes 5–6 of every EMCY; byte 7 is not used
//! ([`BaumerManufacturer`], [`BaumerEmcy`]). Each condition the encoder
//! reports is a row of SPEC §4's table, kept here as the typed const table
//! [`DIAGNOSTIC_SOURCES`] with look-ups by EMCY code ([`sources_for_code`]),
//! by error injection code ([`source_for_injection`]), by name
//! ([`source_by_name`]) and by a received EMCY ([`matching_sources`], which
//! uses the alarm and warning bits to tell apart rows sharing a code).
//!
//! The manual remarks that whenever any diagnostic source appears, the
//! absolute position may be incorrect (SPEC §4).
//!
//! ```
//! use motionwire::canopen::{ErrorCode, ErrorRegister};
//! use motionwire::profiles::baumer::{self, Alarms, BaumerEmcy, Warnings};
//!
//! // Battery empty, seen at startup: code 0xFF01, error register bit 0,
//! // alarms 6503h bits 0 and 15 (SPEC §4).
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
//! # Ok::<(), motionwire::Error>(())
//! ```

use core::fmt;

use bitflags::bitflags;
use byteorder::{ByteOrder, LittleEndian};

use crate::canopen::{Emcy, ErrorCode, ErrorRegister, EMCY_LEN};
use crate::error::{Error, Result};

bitflags! {
    /// The alarms object 6503h (u16), sent in bytes 3–4 of the encoder's
    /// EMCY; only the bits SPEC §4's table uses are named (SPEC §4; CiA 406;
    /// Baumer EAM580 manual §8, §9.5).
    ///
    /// Decode a word that the encoder sent with [`Alarms::from_bits_retain`]
    /// so that unnamed bits survive a round trip.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
    pub struct Alarms: u16 {
        /// Bit 0: position error (CiA 406); set with every alarm the encoder
        /// raises at startup (SPEC §4).
        const POSITION_ERROR = 1 << 0;
        /// Bit 1: problem with the non-volatile memory, seen at startup
        /// (SPEC §4, non-volatile data manager; CiA 406 calls this bit
        /// "commissioning diagnostic").
        const NON_VOLATILE_MEMORY = 1 << 1;
        /// Bit 12: the encoder's data are not valid; set at startup by the
        /// multiturn communication monitor (SPEC §4; Baumer's object list
        /// calls it "data valid encoder").
        const ENCODER_DATA_INVALID = 1 << 12;
        /// Bit 15: battery empty, seen at startup (SPEC §4: battery
        /// monitoring error, multiturn power-on reset).
        const BATTERY_EMPTY = 1 << 15;
    }
}

impl Alarms {
    /// The object index of the alarms, 6503h (CiA 406; SPEC §4).
    pub const OBJECT_INDEX: u16 = 0x6503;
}

bitflags! {
    /// The warnings object 6505h (u16), sent in bytes 5–6 of the encoder's
    /// EMCY; only the bits SPEC §4's table uses are named (SPEC §4; CiA 406;
    /// Baumer EAM580 manual §8, §9.5).
    ///
    /// Decode a word that the encoder sent with [`Warnings::from_bits_retain`]
    /// so that unnamed bits survive a round trip.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
    pub struct Warnings: u16 {
        /// Bit 0: frequency exceeded, the maximum rotation speed was exceeded
        /// (CiA 406; SPEC §4, speed monitoring).
        const FREQUENCY_EXCEEDED = 1 << 0;
        /// Bit 2: software reset by the CPU watchdog (CiA 406; SPEC §4, reset
        /// reason watchdog).
        const CPU_WATCHDOG = 1 << 2;
        /// Bit 3: problem with the non-volatile memory, seen at runtime
        /// (SPEC §4, non-volatile data manager; CiA 406 and Baumer's object
        /// list call this bit "operating time limit").
        const NON_VOLATILE_MEMORY = 1 << 3;
        /// Bit 4: battery of the multiturn system low (CiA 406 "battery
        /// charge"; SPEC §4, battery monitoring warning).
        const BATTERY_LOW = 1 << 4;
        /// Bit 12: mounting error, the multiturn magnetic field is weak,
        /// disturbed or in the wrong sequence (SPEC §4).
        const MOUNTING_ERROR = 1 << 12;
        /// Bit 13: multiturn system fault at runtime: battery empty, internal
        /// communication error or power-on reset (SPEC §4).
        const MULTITURN_SYSTEM = 1 << 13;
        /// Bit 14: singleturn system fault, sensor amplitude out of range
        /// (SPEC §4, singleturn magnetic field strength).
        const SINGLETURN_SYSTEM = 1 << 14;
        /// Bit 15: multiturn supervision, singleturn and multiturn sensors
        /// out of sync (SPEC §4).
        const MULTITURN_SUPERVISION = 1 << 15;
    }
}

impl Warnings {
    /// The object index of the warnings, 6505h (CiA 406; SPEC §4).
    pub const OBJECT_INDEX: u16 = 0x6505;
}

/// The bits of the error register 1001h that this encoder uses: bit 0
/// generic, bit 3 temperature, bit 4 communication (SPEC §4).
pub const ERROR_REGISTER_BITS: ErrorRegister = ErrorRegister::GENERIC
    .union(ErrorRegister::TEMPERATURE)
    .union(ErrorRegister::COMMUNICATION);

/// The number of entries of the encoder's error history, object 1003h
/// (SPEC §4).
pub const ERROR_HISTORY_LEN: usize = 8;

/// The object an error injection code is written to, 2116h, to simulate a
/// diagnostic source (SPEC §4).
pub const INJECTION_OBJECT_INDEX: u16 = 0x2116;

/// Return whether `code` is one of the encoder's manufacturer-reserved error
/// codes, 0xFF0A..=0xFF16 or 0xFF18..=0xFFFF (SPEC §4).
///
/// ```
/// use motionwire::canopen::ErrorCode;
/// use motionwire::profiles::baumer::is_reserved_code;
///
/// assert!(is_reserved_code(ErrorCode::new(0xFF0A)));
/// assert!(!is_reserved_code(ErrorCode::new(0xFF17))); // multiturn power-on reset
/// ```
pub const fn is_reserved_code(code: ErrorCode) -> bool {
    matches!(code.get(), 0xFF0A..=0xFF16 | 0xFF18..=0xFFFF)
}

mod field {
    use core::ops::Range;

    // Offsets inside the EMCY's manufacturer field, which starts at EMCY
    // byte 3 (SPEC §2.1, §4).

    /// EMCY bytes 3–4: alarms, object 6503h, u16.
    pub const ALARMS: Range<usize> = 0..2;
    /// EMCY bytes 5–6: warnings, object 6505h, u16.
    pub const WARNINGS: Range<usize> = 2..4;
    /// EMCY byte 7: not used.
    pub const UNUSED: usize = 4;
}

/// The length of the encoder's manufacturer field, 5 bytes (EMCY bytes 3–7;
/// SPEC §2.1, §4).
pub const MANUFACTURER_LEN: usize = field::UNUSED + 1;

/// The EAM580's manufacturer-specific EMCY field, bytes 3–7 (SPEC §4;
/// Baumer EAM580 manual §8 "Emergency message").
///
/// ```
/// use motionwire::profiles::baumer::{Alarms, BaumerManufacturer, Warnings};
///
/// let field = BaumerManufacturer::from_bytes(&[0x00, 0x00, 0x00, 0x20, 0x00]);
/// assert_eq!(field.alarms, Alarms::empty());
/// assert_eq!(field.warnings, Warnings::MULTITURN_SYSTEM);
/// assert_eq!(field.to_bytes(), [0x00, 0x00, 0x00, 0x20, 0x00]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    pub fn from_bytes(bytes: &[u8; MANUFACTURER_LEN]) -> Self {
        BaumerManufacturer {
            alarms: Alarms::from_bits_retain(LittleEndian::read_u16(&bytes[field::ALARMS])),
            warnings: Warnings::from_bits_retain(LittleEndian::read_u16(&bytes[field::WARNINGS])),
            unused: bytes[field::UNUSED],
        }
    }

    /// Encode the field into its 5 bytes (EMCY bytes 3–7).
    #[inline]
    pub fn to_bytes(&self) -> [u8; MANUFACTURER_LEN] {
        let mut bytes = [0; MANUFACTURER_LEN];
        LittleEndian::write_u16(&mut bytes[field::ALARMS], self.alarms.bits());
        LittleEndian::write_u16(&mut bytes[field::WARNINGS], self.warnings.bits());
        bytes[field::UNUSED] = self.unused;
        bytes
    }
}

/// An EMCY from the EAM580, its manufacturer field decoded (SPEC §2.1, §4).
///
/// Every 8-byte EMCY decodes, and encoding gives the same bytes back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    pub fn from_emcy(emcy: &Emcy) -> Self {
        BaumerEmcy {
            code: emcy.code,
            register: emcy.register,
            manufacturer: BaumerManufacturer::from_bytes(&emcy.manufacturer),
        }
    }

    /// Encode the manufacturer field back into a plain EMCY.
    #[inline]
    pub fn to_emcy(&self) -> Emcy {
        Emcy::new(self.code, self.register, self.manufacturer.to_bytes())
    }

    /// Decode the 8 bytes of an EMCY.
    #[inline]
    pub fn from_bytes(bytes: &[u8; EMCY_LEN]) -> Self {
        Self::from_emcy(&Emcy::from_bytes(bytes))
    }

    /// Encode the EMCY into its 8 bytes.
    #[inline]
    pub fn to_bytes(&self) -> [u8; EMCY_LEN] {
        self.to_emcy().to_bytes()
    }

    /// Decode an EMCY from a CAN frame's data; fewer than 8 bytes is an
    /// [`Error::Length`] (SPEC §2.1).
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self> {
        Ok(Self::from_emcy(&Emcy::parse(data)?))
    }

    /// Return the diagnostic sources this EMCY reports, by the rule of
    /// [`matching_sources`].
    #[inline]
    pub fn sources(&self) -> impl Iterator<Item = &'static DiagnosticSource> + Clone {
        matching(self.code, self.manufacturer)
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

/// When a diagnostic source is signalled (SPEC §4, column "appearance").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Appearance {
    /// At startup.
    Startup,
    /// At runtime.
    Runtime,
}

impl Appearance {
    /// Return the appearance's name, `"startup"` or `"runtime"`.
    pub const fn name(self) -> &'static str {
        match self {
            Appearance::Startup => "startup",
            Appearance::Runtime => "runtime",
        }
    }
}

/// Which encoder design a diagnostic source exists on (SPEC §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    pub const fn name(self) -> &'static str {
        match self {
            Variant::Both => "both",
            Variant::Redundant => "redundant",
            Variant::NonRedundant => "non_redundant",
        }
    }
}

/// When the signalling of a diagnostic source is reset (SPEC §4, column
/// "reset").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ResetBehaviour {
    /// Reset at runtime, once the cause is gone.
    AtRuntime,
    /// Reset only by a reboot.
    AtReboot,
    /// Reset by a reboot, except on the redundant encoder, where it is never
    /// reset (SPEC §4, rows marked "(1)").
    AtRebootExceptRedundant,
    /// Never reset.
    NoReset,
}

impl ResetBehaviour {
    /// Return the behaviour on a given encoder design: on the redundant
    /// encoder [`ResetBehaviour::AtRebootExceptRedundant`] becomes
    /// [`ResetBehaviour::NoReset`], on the non-redundant one
    /// [`ResetBehaviour::AtReboot`]; with [`Variant::Both`] it stays as it is
    /// (SPEC §4, "(1)").
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

/// What an error injection code simulates, told by its high word (SPEC §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    pub const fn high_word(self) -> u16 {
        match self {
            InjectionKind::StartupAlarm => 0x0001,
            InjectionKind::StartupWarning => 0x0004,
            InjectionKind::Runtime => 0x0008,
        }
    }

    /// Return the kind whose high word is `high`, if any.
    pub const fn from_high_word(high: u16) -> Option<Self> {
        match high {
            0x0001 => Some(InjectionKind::StartupAlarm),
            0x0004 => Some(InjectionKind::StartupWarning),
            0x0008 => Some(InjectionKind::Runtime),
            _ => None,
        }
    }

    /// Return when a source simulated with this kind appears.
    pub const fn appearance(self) -> Appearance {
        match self {
            InjectionKind::StartupAlarm | InjectionKind::StartupWarning => Appearance::Startup,
            InjectionKind::Runtime => Appearance::Runtime,
        }
    }
}

/// An error injection code, written to object 2116h to simulate a
/// diagnostic source (SPEC §4; Baumer EAM580 manual §9.5).
///
/// The high word tells the [`InjectionKind`]; the low word numbers the
/// source. 0x0000_0000 ([`InjectionCode::NO_ERROR`]) belongs to "error
/// reset or no error".
///
/// ```
/// use motionwire::profiles::baumer::{InjectionCode, InjectionKind};
///
/// let code = InjectionCode::new(InjectionKind::StartupWarning, 0x001C);
/// assert_eq!(code.get(), 0x0004_001C);
/// assert_eq!(InjectionCode::try_new(0x0004_001C), Ok(code));
/// assert_eq!(code.kind(), Some(InjectionKind::StartupWarning));
/// assert!(InjectionCode::try_new(0x0002_0000).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct InjectionCode(u32);

impl InjectionCode {
    /// 0x0000_0000, the code of "error reset or no error" (SPEC §4).
    pub const NO_ERROR: InjectionCode = InjectionCode(0);

    /// Return the code of kind `kind` with low word `number`.
    #[inline]
    pub const fn new(kind: InjectionKind, number: u16) -> Self {
        InjectionCode(((kind.high_word() as u32) << 16) | number as u32)
    }

    /// Return the code `raw` if it is 0x0000_0000 or its high word is
    /// 0x0001, 0x0004 or 0x0008, else an [`Error::InvalidValue`].
    pub const fn try_new(raw: u32) -> Result<Self> {
        if raw == 0 || InjectionKind::from_high_word((raw >> 16) as u16).is_some() {
            Ok(InjectionCode(raw))
        } else {
            Err(Error::InvalidValue {
                what: "error injection code",
                found: raw,
                expected: "0x00000000 or a high word of 0x0001, 0x0004 or 0x0008",
            })
        }
    }

    /// Return the code as a number.
    #[inline]
    pub const fn get(self) -> u32 {
        self.0
    }

    /// Return the kind told by the high word; `None` for
    /// [`InjectionCode::NO_ERROR`].
    #[inline]
    pub const fn kind(self) -> Option<InjectionKind> {
        InjectionKind::from_high_word((self.0 >> 16) as u16)
    }

    /// Return the low word, the number of the simulated source.
    #[inline]
    pub const fn number(self) -> u16 {
        (self.0 & 0xFFFF) as u16
    }
}

impl fmt::Display for InjectionCode {
    /// Format the code as the manual writes it, e.g. `0x0008_0020`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:04X}_{:04X}", self.0 >> 16, self.number())
    }
}

/// Where a diagnostic source becomes visible: error register 1001h bits,
/// alarms 6503h bits and warnings 6505h bits (SPEC §4, column "signalling").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    pub const fn new(register: ErrorRegister, alarms: Alarms, warnings: Warnings) -> Self {
        Signalling {
            register,
            alarms,
            warnings,
        }
    }

    /// Return whether any alarm (6503h) or warning (6505h) bit is signalled.
    #[inline]
    pub const fn has_alarm_or_warning_bits(&self) -> bool {
        !self.alarms.is_empty() || !self.warnings.is_empty()
    }
}

/// One row of the encoder's diagnostic-source table (SPEC §4; Baumer EAM580
/// manual §9.5).
///
/// The rows are the entries of [`DIAGNOSTIC_SOURCES`]; a source that
/// appears both at startup and at runtime, or on both encoder designs with
/// different signalling, has one row each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
    /// decoder writes in `sources` (SPEC §6.1).
    #[inline]
    pub const fn name(&self) -> &'static str {
        self.name
    }

    /// Return the diagnostic source as the manual names it, e.g.
    /// `"Non-volatile data manager"`.
    #[inline]
    pub const fn source(&self) -> &'static str {
        self.source
    }

    /// Return what the source reports, e.g. `"Problem with the non-volatile
    /// memory"`.
    #[inline]
    pub const fn description(&self) -> &'static str {
        self.description
    }

    /// Return the EMCY error code; `None` when no EMCY is sent (CAN
    /// controller bus off).
    #[inline]
    pub const fn code(&self) -> Option<ErrorCode> {
        self.code
    }

    /// Return when the source is signalled.
    #[inline]
    pub const fn appearance(&self) -> Appearance {
        self.appearance
    }

    /// Return where the source becomes visible.
    #[inline]
    pub const fn signalling(&self) -> Signalling {
        self.signalling
    }

    /// Return when the signalling is reset; `None` where the table gives
    /// none ("error reset or no error").
    #[inline]
    pub const fn reset(&self) -> Option<ResetBehaviour> {
        self.reset
    }

    /// Return the error injection code that simulates the source; `None`
    /// for the CAN controller and error-control sources, which have none.
    #[inline]
    pub const fn injection(&self) -> Option<InjectionCode> {
        self.injection
    }

    /// Return the encoder design the row applies to.
    #[inline]
    pub const fn variant(&self) -> Variant {
        self.variant
    }

    /// Return whether the row signals alarm or warning bits and all of them
    /// are set in `field`.
    #[inline]
    pub fn is_signalled_in(&self, field: &BaumerManufacturer) -> bool {
        self.signalling.has_alarm_or_warning_bits()
            && field.alarms.contains(self.signalling.alarms)
            && field.warnings.contains(self.signalling.warnings)
    }

    /// Return the EMCY the encoder sends when this is its only active
    /// source: the row's code, its error register bits and its alarm and
    /// warning bits (SPEC §4); `None` when no EMCY is sent (bus off).
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
/// for a code the encoder does not send (SPEC §4).
///
/// ```
/// use motionwire::canopen::ErrorCode;
/// use motionwire::profiles::baumer::sources_for_code;
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
/// each code (SPEC §4).
pub fn source_for_injection(code: InjectionCode) -> Option<&'static DiagnosticSource> {
    DIAGNOSTIC_SOURCES
        .iter()
        .find(|source| source.injection == Some(code))
}

/// Return the row named `name` (see [`DiagnosticSource::name`]).
pub fn source_by_name(name: &str) -> Option<&'static DiagnosticSource> {
    DIAGNOSTIC_SOURCES.iter().find(|source| source.name == name)
}

/// Return the rows a received EMCY reports, using its alarm and warning bits
/// to tell apart rows that share a code (SPEC §4, §6.1 `sources`).
///
/// The rule:
/// 1. Take the rows whose code is the EMCY's code; any 0x00xx code counts as
///    0x0000, "error reset or no error" (SPEC §2.3, **Decision**).
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
/// use motionwire::canopen::{Emcy, ErrorCode, ErrorRegister};
/// use motionwire::profiles::baumer::matching_sources;
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

/// The number of rows of SPEC §4's table.
pub const DIAGNOSTIC_SOURCE_COUNT: usize = 27;

/// Every diagnostic source of the EAM580, one entry per row of SPEC §4's
/// table, in its order (Baumer EAM580 manual §9.5).
pub static DIAGNOSTIC_SOURCES: [DiagnosticSource; DIAGNOSTIC_SOURCE_COUNT] = [
    // SPEC §4 row 1; manual §9.5 "Error reset or no error".
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
    // SPEC §4 row 2; manual §9.5 "Temperature Monitoring".
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
    // SPEC §4 row 3; manual §9.5 "Non-Volatile Data Manager", at startup.
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
    // SPEC §4 row 4; manual §9.5 "Non-Volatile Data Manager", at runtime.
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
    // SPEC §4 row 5; manual §9.5 "Reset Reason Watchdog".
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
    // SPEC §4 row 6; manual §9.5 "CAN-Controller Bus Warning".
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
    // SPEC §4 row 7; manual §9.5 "CAN-Controller RX Buffer Overflow".
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
    // SPEC §4 row 8; manual §9.5 "CAN-Controller Bus Passive".
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
    // SPEC §4 row 9; manual §9.5 "CAN-Controller Bus Off": no EMCY is sent.
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
    // SPEC §4 row 10; manual §9.5 "Lifeguard or Heartbeat".
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
    // SPEC §4 row 11; manual §9.5 "Battery Monitoring Warning
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
    // SPEC §4 row 12; manual §9.5 "Battery Monitoring Warning (redundant
    // encoder)".
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
    // SPEC §4 row 13; manual §9.5 "Battery Monitoring Error (Battery
    // Empty)", at startup; reset "(1)".
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
    // SPEC §4 row 14; manual §9.5 "Battery Monitoring Error (Battery
    // Empty)", at runtime; reset "(1)".
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
    // SPEC §4 row 15; manual §9.5 "Multiturn Magnetic Field sequence
    // (non-redundant encoder)", at startup.
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
    // SPEC §4 row 16; manual §9.5 "Multiturn Magnetic Field sequence
    // (non-redundant encoder)", at runtime.
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
    // SPEC §4 row 17; manual §9.5 "Multiturn Magnetic Field sequence
    // (redundant encoder)", at startup.
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
    // SPEC §4 row 18; manual §9.5 "Multiturn Magnetic Field sequence
    // (redundant encoder)", at runtime.
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
    // SPEC §4 row 19; manual §9.5 "Multiturn Magnetic Field strength
    // (redundant encoder)", at startup.
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
    // SPEC §4 row 20; manual §9.5 "Multiturn Magnetic Field strength
    // (redundant encoder)", at runtime.
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
    // SPEC §4 row 21; manual §9.5 "Multiturn Communication Monitor", at
    // startup.
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
    // SPEC §4 row 22; manual §9.5 "Multiturn Communication Monitor", at
    // runtime.
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
    // SPEC §4 row 23; manual §9.5 "Speed Monitoring".
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
    // SPEC §4 row 24; manual §9.5 "Singleturn Magnetic Field strength".
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
    // SPEC §4 row 25; manual §9.5 "Singleturn/Multiturn Supervision".
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
    // SPEC §4 row 26; manual §9.5 "Multiturn Power On Reset (redundant
    // encoder)", at startup.
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
    // SPEC §4 row 27; manual §9.5 "Multiturn Power On Reset (redundant
    // encoder)", at runtime.
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
