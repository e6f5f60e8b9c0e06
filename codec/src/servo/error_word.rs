//! SEW, the servo error word, and the drive's E-codes (docs/servo.md#sew; seed
//! 002, "ServoErrorWord").
//!
//! [`ServoErrorWord`] holds the 25 defined bits as bitflags. Each defined bit
//! is also a [`ServoFault`] with its name (docs/servo.md#sew), meaning and —
//! for most bits — the [`ECode`] the drive shows on its display. The mapping
//! works both ways:
//! [`ServoFault::e_code`] / [`ECode::fault`], [`ServoErrorWord::from_e_code`].
//!
//! ```
//! use motionwire_codec::servo::{ECode, ServoErrorWord, ServoFault};
//!
//! let sew = ServoErrorWord::from_bits_retain(0x0008_0021);
//! let faults: Vec<_> = sew.faults().map(|f| (f.bit(), f.name(), f.e_code())).collect();
//! assert_eq!(faults, [
//!     (0, "ServoErrors", None),
//!     (5, "BVErr", Some(ECode::E05)),
//!     (19, "FollowerErr", Some(ECode::E09)),
//! ]);
//! assert_eq!("E09".parse::<ECode>()?.fault(), ServoFault::FollowerErr);
//! assert_eq!(ServoErrorWord::from_e_code(ECode::E05), ServoErrorWord::BV_ERR);
//! assert_eq!(ECode::E05.to_string(), "E05");
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;
use core::str::FromStr;

use bitflags::bitflags;

use crate::{Error, Result, TextError, ValueError};

bitflags! {
    /// SEW, the servo error word, servo → NC (docs/servo.md#sew; the interface
    /// manual).
    ///
    /// Bit 0 (ServoErrors) summarises the others. The reserved bits 4 and
    /// 25–31 are declared as known to bitflags, so they survive decoding with
    /// [`ServoErrorWord::from_bits_retain`] and every flag operation; they
    /// are never reported as faults. Each flag's meaning is
    /// [`ServoFault::description`].
    ///
    /// With the `serde` feature the word serializes in bitflags' format (in
    /// text, e.g. JSON, flag names joined by `|` and any other bits as hex);
    /// every bit survives a round trip.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    #[cfg_attr(
        feature = "serde",
        derive(serde::Serialize, serde::Deserialize),
        serde(transparent)
    )]
    pub struct ServoErrorWord: u32 {
        /// Bit 0, ServoErrors: summary, some drive error is present.
        const SERVO_ERRORS = 1 << 0;
        /// Bit 1, EncoderErr (E01): encoder error.
        const ENCODER_ERR = 1 << 1;
        /// Bit 2, I2t_Endat (E19): EnDat encoder over temperature.
        const I2T_ENDAT = 1 << 2;
        /// Bit 3, ECatConfigError (E14): wrong EtherCAT initialisation data.
        const ECAT_CONFIG_ERROR = 1 << 3;
        /// Bit 5, BVErr (E05): bus voltage above U_max.
        const BV_ERR = 1 << 5;
        /// Bit 6, CurrErr (E06): motor current above I_max.
        const CURR_ERR = 1 << 6;
        /// Bit 7, CurrOffsetErr (E07): current measurement offset error.
        const CURR_OFFSET_ERR = 1 << 7;
        /// Bit 8, HallErr (E08): commutation signal level error.
        const HALL_ERR = 1 << 8;
        /// Bit 9, HallSeqErr: commutation signal sequence not Gray code.
        const HALL_SEQ_ERR = 1 << 9;
        /// Bit 10, SRTErr: servo program watchdog timeout.
        const SRT_ERR = 1 << 10;
        /// Bit 11, CAN1RTErr: CAN channel 1 communication timeout.
        const CAN1_RT_ERR = 1 << 11;
        /// Bit 12, CAN2RTErr: CAN channel 2 communication timeout.
        const CAN2_RT_ERR = 1 << 12;
        /// Bit 13, CAN1HErr: CAN channel 1 hardware error.
        const CAN1_H_ERR = 1 << 13;
        /// Bit 14, CAN2HErr: CAN channel 2 hardware error.
        const CAN2_H_ERR = 1 << 14;
        /// Bit 15, ECatRTErr (E15): EtherCAT timeout.
        const ECAT_RT_ERR = 1 << 15;
        /// Bit 16, PDPINTErr (E16): power stage driver circuit error.
        const PDPINT_ERR = 1 << 16;
        /// Bit 17, PTBLCHKSErr (E30): active parameter table checksum error.
        const PTBL_CHKS_ERR = 1 << 17;
        /// Bit 18, PRGCHKSErr: program memory checksum error.
        const PRG_CHKS_ERR = 1 << 18;
        /// Bit 19, FollowerErr (E09): speed following error.
        const FOLLOWER_ERR = 1 << 19;
        /// Bit 20, OverLoadErr (E20): motor overload.
        const OVER_LOAD_ERR = 1 << 20;
        /// Bit 21, SFlashErr (E32): serial flash access error.
        const SFLASH_ERR = 1 << 21;
        /// Bit 22, ECatWatchDog (E31): EtherCAT slave watchdog expired.
        const ECAT_WATCH_DOG = 1 << 22;
        /// Bit 23, OverSpeed (E11): motor speed above the limit.
        const OVER_SPEED = 1 << 23;
        /// Bit 24, CurrDiffErr (E12): phase A/B current symmetry error.
        const CURR_DIFF_ERR = 1 << 24;

        // Reserved bits 4 and 25–31 must survive every operation (bitflags
        // 2, "externally defined flags").
        const _ = !0;
    }
}

/// The bits docs/servo.md#sew defines: 0–3 and 5–24.
const DEFINED_BITS: u32 = 0x01FF_FFEF;
/// The defined bits other than the summary bit 0.
const CAUSE_BITS: u32 = DEFINED_BITS & !1;

impl ServoErrorWord {
    /// Return the word with only the bit of E-code `code` set (the summary
    /// bit 0 is not set; see [`ServoErrorWord::summarized`]).
    #[must_use]
    pub const fn from_e_code(code: ECode) -> Self {
        code.fault().flag()
    }

    /// Return the active faults in bit order, the summary bit 0 included as
    /// [`ServoFault::ServoErrors`]; the reserved bits 4 and 25–31 are not
    /// faults (docs/servo.md#sew; `faults` in docs/servo.md#cli-feedback).
    pub fn faults(self) -> impl Iterator<Item = ServoFault> + Clone {
        ServoFault::ALL
            .into_iter()
            .filter(move |fault| self.contains(fault.flag()))
    }

    /// Return whether any cause bit (a defined bit other than the summary
    /// bit 0) is set.
    #[must_use]
    pub const fn has_cause(self) -> bool {
        self.bits() & CAUSE_BITS != 0
    }

    /// Return a copy whose summary bit 0 (ServoErrors) is set exactly when a
    /// cause bit is set — the word a drive produces (the interface manual,
    /// "ServoErrors. Summarized errors"). Reserved bits are kept and do not
    /// count.
    #[must_use]
    pub const fn summarized(self) -> Self {
        if self.has_cause() {
            self.union(ServoErrorWord::SERVO_ERRORS)
        } else {
            self.difference(ServoErrorWord::SERVO_ERRORS)
        }
    }
}

/// One defined bit of the servo error word, with its docs/servo.md#sew name,
/// E-code and meaning (the interface manual, "ServoErrorWord").
///
/// The variant names spell the names of docs/servo.md#sew in Rust's case;
/// [`ServoFault::name`] returns their spelling exactly (e.g. `I2tEndat` →
/// `"I2t_Endat"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum ServoFault {
    /// Bit 0, ServoErrors: summary, some drive error is present.
    ServoErrors = 0,
    /// Bit 1, EncoderErr, E01: encoder error (EnDat, SinCos or TTL).
    EncoderErr = 1,
    /// Bit 2, I2t_Endat, E19: EnDat encoder temperature above Max_Temperature.
    I2tEndat = 2,
    /// Bit 3, ECatConfigError, E14: wrong EtherCAT initialisation data.
    ECatConfigError = 3,
    /// Bit 5, BVErr, E05: bus voltage above U_max.
    BvErr = 5,
    /// Bit 6, CurrErr, E06: motor current above I_max.
    CurrErr = 6,
    /// Bit 7, CurrOffsetErr, E07: current measurement offset error.
    CurrOffsetErr = 7,
    /// Bit 8, HallErr, E08: commutation (Hall) signal level error.
    HallErr = 8,
    /// Bit 9, HallSeqErr: commutation signal sequence is not Gray code.
    HallSeqErr = 9,
    /// Bit 10, SRTErr: servo program watchdog timeout.
    SrtErr = 10,
    /// Bit 11, CAN1RTErr: CAN channel 1 communication timeout.
    Can1RtErr = 11,
    /// Bit 12, CAN2RTErr: CAN channel 2 communication timeout.
    Can2RtErr = 12,
    /// Bit 13, CAN1HErr: CAN channel 1 hardware error.
    Can1HErr = 13,
    /// Bit 14, CAN2HErr: CAN channel 2 hardware error.
    Can2HErr = 14,
    /// Bit 15, ECatRTErr, E15: EtherCAT timeout.
    ECatRtErr = 15,
    /// Bit 16, PDPINTErr, E16: power stage (IGBT) driver circuit error.
    PdpintErr = 16,
    /// Bit 17, PTBLCHKSErr, E30: active parameter table checksum error.
    PtblChksErr = 17,
    /// Bit 18, PRGCHKSErr: program memory checksum error.
    PrgChksErr = 18,
    /// Bit 19, FollowerErr, E09: speed following error.
    FollowerErr = 19,
    /// Bit 20, OverLoadErr, E20: motor overload.
    OverLoadErr = 20,
    /// Bit 21, SFlashErr, E32: serial flash access error.
    SFlashErr = 21,
    /// Bit 22, ECatWatchDog, E31: EtherCAT slave watchdog expired.
    ECatWatchDog = 22,
    /// Bit 23, OverSpeed, E11: motor speed above the limit.
    OverSpeed = 23,
    /// Bit 24, CurrDiffErr, E12: phase A/B current symmetry error.
    CurrDiffErr = 24,
}

/// One row of the error-word table of docs/servo.md#sew: a fault with its name,
/// E-code and meaning. [`ServoFault::TABLE`] holds every row; the names,
/// E-codes, descriptions, `Display`, the JSON of `motionwire servo` and the
/// tests all read it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FaultInfo {
    /// The fault (its discriminant is the bit number).
    pub fault: ServoFault,
    /// The name exactly as the name column of docs/servo.md#sew spells it (and
    /// the command-line decoder's `faults` writes it,
    /// docs/servo.md#cli-feedback).
    pub name: &'static str,
    /// The E-code the drive shows, `None` for the bits docs/servo.md#sew gives
    /// none.
    pub e_code: Option<ECode>,
    /// The meaning in words (the meaning column of docs/servo.md#sew).
    pub description: &'static str,
}

impl ServoFault {
    /// The error-word table of docs/servo.md#sew in bit order (bit 4 is
    /// reserved and has no row): the one place the bit → name → E-code →
    /// meaning facts are written.
    pub const TABLE: [FaultInfo; 24] = [
        FaultInfo {
            fault: ServoFault::ServoErrors,
            name: "ServoErrors",
            e_code: None,
            description: "summary: some drive error is present",
        },
        FaultInfo {
            fault: ServoFault::EncoderErr,
            name: "EncoderErr",
            e_code: Some(ECode::E01),
            description: "encoder error (EnDat, SinCos or TTL)",
        },
        FaultInfo {
            fault: ServoFault::I2tEndat,
            name: "I2t_Endat",
            e_code: Some(ECode::E19),
            description: "EnDat encoder temperature above Max_Temperature (usually 95 °C)",
        },
        FaultInfo {
            fault: ServoFault::ECatConfigError,
            name: "ECatConfigError",
            e_code: Some(ECode::E14),
            description: "wrong EtherCAT initialisation data from the master",
        },
        FaultInfo {
            fault: ServoFault::BvErr,
            name: "BVErr",
            e_code: Some(ECode::E05),
            description: "bus voltage above U_max",
        },
        FaultInfo {
            fault: ServoFault::CurrErr,
            name: "CurrErr",
            e_code: Some(ECode::E06),
            description: "motor current above I_max",
        },
        FaultInfo {
            fault: ServoFault::CurrOffsetErr,
            name: "CurrOffsetErr",
            e_code: Some(ECode::E07),
            description: "current measurement offset error",
        },
        FaultInfo {
            fault: ServoFault::HallErr,
            name: "HallErr",
            e_code: Some(ECode::E08),
            description: "commutation (Hall) signal level error",
        },
        FaultInfo {
            fault: ServoFault::HallSeqErr,
            name: "HallSeqErr",
            e_code: None,
            description: "commutation signal sequence is not Gray code",
        },
        FaultInfo {
            fault: ServoFault::SrtErr,
            name: "SRTErr",
            e_code: None,
            description: "servo program watchdog timeout (drive is broken)",
        },
        FaultInfo {
            fault: ServoFault::Can1RtErr,
            name: "CAN1RTErr",
            e_code: None,
            description: "CAN channel 1 communication timeout",
        },
        FaultInfo {
            fault: ServoFault::Can2RtErr,
            name: "CAN2RTErr",
            e_code: None,
            description: "CAN channel 2 communication timeout",
        },
        FaultInfo {
            fault: ServoFault::Can1HErr,
            name: "CAN1HErr",
            e_code: None,
            description: "CAN channel 1 hardware error",
        },
        FaultInfo {
            fault: ServoFault::Can2HErr,
            name: "CAN2HErr",
            e_code: None,
            description: "CAN channel 2 hardware error",
        },
        FaultInfo {
            fault: ServoFault::ECatRtErr,
            name: "ECatRTErr",
            e_code: Some(ECode::E15),
            description: "EtherCAT timeout (no data for 3 cycles)",
        },
        FaultInfo {
            fault: ServoFault::PdpintErr,
            name: "PDPINTErr",
            e_code: Some(ECode::E16),
            description: "power stage (IGBT) driver circuit error",
        },
        FaultInfo {
            fault: ServoFault::PtblChksErr,
            name: "PTBLCHKSErr",
            e_code: Some(ECode::E30),
            description: "active parameter table checksum error",
        },
        FaultInfo {
            fault: ServoFault::PrgChksErr,
            name: "PRGCHKSErr",
            e_code: None,
            description: "program memory checksum error",
        },
        FaultInfo {
            fault: ServoFault::FollowerErr,
            name: "FollowerErr",
            e_code: Some(ECode::E09),
            description: "speed following error",
        },
        FaultInfo {
            fault: ServoFault::OverLoadErr,
            name: "OverLoadErr",
            e_code: Some(ECode::E20),
            description: "motor overload (current above nominal for too long)",
        },
        FaultInfo {
            fault: ServoFault::SFlashErr,
            name: "SFlashErr",
            e_code: Some(ECode::E32),
            description: "serial flash (parameter store) access error",
        },
        FaultInfo {
            fault: ServoFault::ECatWatchDog,
            name: "ECatWatchDog",
            e_code: Some(ECode::E31),
            description: "EtherCAT slave watchdog expired",
        },
        FaultInfo {
            fault: ServoFault::OverSpeed,
            name: "OverSpeed",
            e_code: Some(ECode::E11),
            description: "motor speed above the limit",
        },
        FaultInfo {
            fault: ServoFault::CurrDiffErr,
            name: "CurrDiffErr",
            e_code: Some(ECode::E12),
            description: "phase A/B current symmetry error",
        },
    ];

    /// Every fault in bit order (bit 4 is reserved and has none).
    pub const ALL: [ServoFault; 24] = {
        let mut all = [ServoFault::ServoErrors; 24];
        let mut i = 0;
        while i < Self::TABLE.len() {
            all[i] = Self::TABLE[i].fault;
            i += 1;
        }
        all
    };

    /// Return the fault of SEW bit `bit`, or `None` for a reserved bit
    /// (4, 25–31) or a number above 31.
    #[must_use]
    pub const fn from_bit(bit: u8) -> Option<Self> {
        let mut i = 0;
        while i < Self::TABLE.len() {
            if Self::TABLE[i].fault as u8 == bit {
                return Some(Self::TABLE[i].fault);
            }
            i += 1;
        }
        None
    }

    /// Return the fault's bit number in the error word, 0..=24.
    #[must_use]
    pub const fn bit(self) -> u8 {
        self as u8
    }

    /// Return the fault's bit in the error word.
    #[must_use]
    pub const fn flag(self) -> ServoErrorWord {
        ServoErrorWord::from_bits_retain(1 << self.bit())
    }

    /// Return the fault's row of [`ServoFault::TABLE`].
    #[must_use]
    pub const fn info(self) -> &'static FaultInfo {
        // Rows are in bit order without the reserved bit 4.
        let bit = self.bit() as usize;
        &Self::TABLE[if bit < 4 { bit } else { bit - 1 }]
    }

    /// Return the fault's name exactly as the name column of docs/servo.md#sew
    /// spells it (and the command-line decoder's `faults` writes it,
    /// docs/servo.md#cli-feedback).
    #[must_use]
    pub const fn name(self) -> &'static str {
        self.info().name
    }

    /// Return the E-code the drive shows for this fault, or `None` for the
    /// bits docs/servo.md#sew gives none (0, 9–14, 18).
    #[must_use]
    pub const fn e_code(self) -> Option<ECode> {
        self.info().e_code
    }

    /// Return the fault's meaning in words (the meaning column of
    /// docs/servo.md#sew).
    #[must_use]
    pub const fn description(self) -> &'static str {
        self.info().description
    }
}

impl fmt::Display for ServoFault {
    /// Format the fault as its docs/servo.md#sew name.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An error code the drive shows on its display, `E01`…`E32`, for the
/// error-word bits that have one (docs/servo.md#sew; the interface manual,
/// "Error Code" columns).
///
/// Only the sixteen codes of docs/servo.md#sew exist; each maps to exactly one
/// [`ServoFault`]. Parse one from its number ([`ECode::from_number`]) or from
/// its text (`"E05".parse()`); [`Display`](fmt::Display) prints `E05`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum ECode {
    /// E01: encoder error (bit 1, EncoderErr).
    E01 = 1,
    /// E05: bus voltage above U_max (bit 5, BVErr).
    E05 = 5,
    /// E06: motor current above I_max (bit 6, CurrErr).
    E06 = 6,
    /// E07: current measurement offset error (bit 7, CurrOffsetErr).
    E07 = 7,
    /// E08: commutation signal level error (bit 8, HallErr).
    E08 = 8,
    /// E09: speed following error (bit 19, FollowerErr).
    E09 = 9,
    /// E11: motor speed above the limit (bit 23, OverSpeed).
    E11 = 11,
    /// E12: phase A/B current symmetry error (bit 24, CurrDiffErr).
    E12 = 12,
    /// E14: wrong EtherCAT initialisation data (bit 3, ECatConfigError).
    E14 = 14,
    /// E15: EtherCAT timeout (bit 15, ECatRTErr).
    E15 = 15,
    /// E16: power stage driver circuit error (bit 16, PDPINTErr).
    E16 = 16,
    /// E19: EnDat encoder over temperature (bit 2, I2t_Endat).
    E19 = 19,
    /// E20: motor overload (bit 20, OverLoadErr).
    E20 = 20,
    /// E30: active parameter table checksum error (bit 17, PTBLCHKSErr).
    E30 = 30,
    /// E31: EtherCAT slave watchdog expired (bit 22, ECatWatchDog).
    E31 = 31,
    /// E32: serial flash access error (bit 21, SFlashErr).
    E32 = 32,
}

/// The E-codes in words, for error messages.
const E_CODES_IN_WORDS: &str =
    "E01, E05, E06, E07, E08, E09, E11, E12, E14, E15, E16, E19, E20, E30, E31, E32";

impl ECode {
    /// Every E-code in ascending order.
    pub const ALL: [ECode; 16] = [
        ECode::E01,
        ECode::E05,
        ECode::E06,
        ECode::E07,
        ECode::E08,
        ECode::E09,
        ECode::E11,
        ECode::E12,
        ECode::E14,
        ECode::E15,
        ECode::E16,
        ECode::E19,
        ECode::E20,
        ECode::E30,
        ECode::E31,
        ECode::E32,
    ];

    /// Return the E-code numbered `number` (5 → E05), or `None` when
    /// docs/servo.md#sew defines no such code.
    #[must_use]
    pub const fn from_number(number: u8) -> Option<Self> {
        let mut i = 0;
        while i < Self::ALL.len() {
            if Self::ALL[i] as u8 == number {
                return Some(Self::ALL[i]);
            }
            i += 1;
        }
        None
    }

    /// Return the E-code numbered `number`, or a [`ValueError`] listing
    /// the defined codes.
    pub const fn try_from_number(number: u8) -> Result<Self, ValueError> {
        match Self::from_number(number) {
            Some(code) => Ok(code),
            None => Err(ValueError {
                what: What::ServoECode,
                found: number as u32,
                expected: E_CODES_IN_WORDS,
            }),
        }
    }

    /// Return the code's number (E05 → 5).
    #[must_use]
    pub const fn number(self) -> u8 {
        self as u8
    }

    /// Return the error-word fault this code is shown for (from
    /// [`ServoFault::TABLE`]).
    #[must_use]
    pub const fn fault(self) -> ServoFault {
        let mut i = 0;
        while i < ServoFault::TABLE.len() {
            if let Some(code) = ServoFault::TABLE[i].e_code {
                if code as u8 == self as u8 {
                    return ServoFault::TABLE[i].fault;
                }
            }
            i += 1;
        }
        // Every E-code has a row (checked by `every_e_code_has_one_fault`);
        // the summary fault is never reached.
        ServoFault::ServoErrors
    }

    /// Return the bit number of this code's fault in the error word.
    #[must_use]
    pub const fn bit(self) -> u8 {
        self.fault().bit()
    }

    /// Return the meaning of this code's fault in words.
    #[must_use]
    pub const fn description(self) -> &'static str {
        self.fault().description()
    }
}

impl TryFrom<u8> for ECode {
    type Error = ValueError;

    fn try_from(number: u8) -> Result<Self, ValueError> {
        Self::try_from_number(number)
    }
}

impl fmt::Display for ECode {
    /// Format the code as the drive's display shows it, e.g. `E05`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "E{:02}", self.number())
    }
}

impl FromStr for ECode {
    type Err = ParseECodeError;

    /// Parse `E` (or `e`) followed by one or two decimal digits, e.g. `E05`
    /// or `E5`. Other text is a [`ParseECodeError::Malformed`]; a number
    /// docs/servo.md#sew does not define is a
    /// [`ParseECodeError::InvalidValue`].
    fn from_str(text: &str) -> Result<Self, ParseECodeError> {
        let malformed = TextError {
            what: What::ServoECode,
            expected: "E followed by one or two decimal digits, e.g. E05",
        };
        let digits = match text.as_bytes() {
            [b'E' | b'e', digits @ ..] if (1..=2).contains(&digits.len()) => digits,
            _ => return Err(malformed.into()),
        };
        let mut number = 0u8;
        for &digit in digits {
            if !digit.is_ascii_digit() {
                return Err(malformed.into());
            }
            // At most two digits: at most 99, no overflow.
            number = number * 10 + (digit - b'0');
        }
        Ok(Self::try_from_number(number)?)
    }
}

/// Why a text is not a servo E-code ([`ECode`]'s `FromStr`): not of the
/// form `E` and one or two digits, or a number docs/servo.md#sew does not
/// define. The message is the inner error's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
pub enum ParseECodeError {
    /// The text is not `E` (or `e`) followed by one or two decimal digits.
    #[error(transparent)]
    Malformed(#[from] TextError),
    /// The number is not one of the defined E-codes.
    #[error(transparent)]
    InvalidValue(#[from] ValueError),
}

impl From<ParseECodeError> for Error {
    fn from(error: ParseECodeError) -> Self {
        match error {
            ParseECodeError::Malformed(e) => Error::Malformed(e),
            ParseECodeError::InvalidValue(e) => Error::InvalidValue(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table is in bit order, each row's fault is its own bit in the
    /// word, and every E-code belongs to exactly one row.
    #[test]
    fn every_e_code_has_one_fault() {
        let bits: Vec<u8> = ServoFault::TABLE
            .iter()
            .map(|row| row.fault.bit())
            .collect();
        let mut sorted = bits.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(bits, sorted);
        assert!(!bits.contains(&4));
        for row in ServoFault::TABLE {
            assert_eq!(row.fault.info(), &row);
            assert_eq!(ServoFault::from_bit(row.fault.bit()), Some(row.fault));
        }
        for code in ECode::ALL {
            let rows: Vec<_> = ServoFault::TABLE
                .iter()
                .filter(|row| row.e_code == Some(code))
                .collect();
            assert_eq!(rows.len(), 1, "{code}");
            assert_eq!(code.fault(), rows[0].fault);
        }
    }
    use ECode as E;
    use ServoErrorWord as W;
    use ServoFault as F;

    /// docs/servo.md#sew written out: (bit, flag, fault, name, E-code).
    #[rustfmt::skip]
    const TABLE: [(u8, W, F, &str, Option<E>); 24] = [
        (0,  W::SERVO_ERRORS,      F::ServoErrors,     "ServoErrors",     None),
        (1,  W::ENCODER_ERR,       F::EncoderErr,      "EncoderErr",      Some(E::E01)),
        (2,  W::I2T_ENDAT,         F::I2tEndat,        "I2t_Endat",       Some(E::E19)),
        (3,  W::ECAT_CONFIG_ERROR, F::ECatConfigError, "ECatConfigError", Some(E::E14)),
        (5,  W::BV_ERR,            F::BvErr,           "BVErr",           Some(E::E05)),
        (6,  W::CURR_ERR,          F::CurrErr,         "CurrErr",         Some(E::E06)),
        (7,  W::CURR_OFFSET_ERR,   F::CurrOffsetErr,   "CurrOffsetErr",   Some(E::E07)),
        (8,  W::HALL_ERR,          F::HallErr,         "HallErr",         Some(E::E08)),
        (9,  W::HALL_SEQ_ERR,      F::HallSeqErr,      "HallSeqErr",      None),
        (10, W::SRT_ERR,           F::SrtErr,          "SRTErr",          None),
        (11, W::CAN1_RT_ERR,       F::Can1RtErr,       "CAN1RTErr",       None),
        (12, W::CAN2_RT_ERR,       F::Can2RtErr,       "CAN2RTErr",       None),
        (13, W::CAN1_H_ERR,        F::Can1HErr,        "CAN1HErr",        None),
        (14, W::CAN2_H_ERR,        F::Can2HErr,        "CAN2HErr",        None),
        (15, W::ECAT_RT_ERR,       F::ECatRtErr,       "ECatRTErr",       Some(E::E15)),
        (16, W::PDPINT_ERR,        F::PdpintErr,       "PDPINTErr",       Some(E::E16)),
        (17, W::PTBL_CHKS_ERR,     F::PtblChksErr,     "PTBLCHKSErr",     Some(E::E30)),
        (18, W::PRG_CHKS_ERR,      F::PrgChksErr,      "PRGCHKSErr",      None),
        (19, W::FOLLOWER_ERR,      F::FollowerErr,     "FollowerErr",     Some(E::E09)),
        (20, W::OVER_LOAD_ERR,     F::OverLoadErr,     "OverLoadErr",     Some(E::E20)),
        (21, W::SFLASH_ERR,        F::SFlashErr,       "SFlashErr",       Some(E::E32)),
        (22, W::ECAT_WATCH_DOG,    F::ECatWatchDog,    "ECatWatchDog",    Some(E::E31)),
        (23, W::OVER_SPEED,        F::OverSpeed,       "OverSpeed",       Some(E::E11)),
        (24, W::CURR_DIFF_ERR,     F::CurrDiffErr,     "CurrDiffErr",     Some(E::E12)),
    ];

    #[test]
    fn every_bit_name_and_e_code() {
        for (bit, flag, fault, name, e_code) in TABLE {
            assert_eq!(flag.bits(), 1u32 << bit, "{name}");
            assert_eq!(fault.bit(), bit);
            assert_eq!(fault.flag(), flag);
            assert_eq!(fault.name(), name);
            assert_eq!(fault.to_string(), name);
            assert_eq!(fault.e_code(), e_code, "{name}");
            assert_eq!(ServoFault::from_bit(bit), Some(fault));
            assert!(!fault.description().is_empty());
            // A word with only this bit lists exactly this fault.
            assert_eq!(flag.faults().collect::<Vec<_>>(), [fault]);
        }
        assert_eq!(
            TABLE.map(|(_, _, fault, _, _)| fault),
            ServoFault::ALL,
            "ALL is in bit order"
        );
    }

    #[test]
    fn every_e_code_both_ways() {
        let mut seen = 0;
        for (bit, flag, fault, _, e_code) in TABLE {
            let Some(code) = e_code else { continue };
            seen += 1;
            assert_eq!(code.fault(), fault);
            assert_eq!(code.bit(), bit);
            assert_eq!(ServoErrorWord::from_e_code(code), flag);
            assert_eq!(code.description(), fault.description());
            // Number and text.
            assert_eq!(ECode::from_number(code.number()), Some(code));
            let text = code.to_string();
            assert_eq!(text, format!("E{:02}", code.number()));
            assert_eq!(text.parse::<ECode>(), Ok(code));
            assert_eq!(text.to_lowercase().parse::<ECode>(), Ok(code));
        }
        assert_eq!(seen, 16);
        assert_eq!(ECode::ALL.len(), 16);
        assert!(ECode::ALL.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn e_code_numbers_and_text() {
        for number in 0..=255u8 {
            let defined =
                [1, 5, 6, 7, 8, 9, 11, 12, 14, 15, 16, 19, 20, 30, 31, 32].contains(&number);
            assert_eq!(ECode::from_number(number).is_some(), defined, "{number}");
            if !defined {
                assert_eq!(
                    ECode::try_from(number),
                    Err(ValueError {
                        what: What::ServoECode,
                        found: u32::from(number),
                        expected: E_CODES_IN_WORDS
                    })
                );
            }
        }
        assert_eq!("E5".parse::<ECode>(), Ok(ECode::E05));
        assert_eq!(ECode::E32.to_string(), "E32");
        let malformed = Err(ParseECodeError::Malformed(TextError {
            what: What::ServoECode,
            expected: "E followed by one or two decimal digits, e.g. E05",
        }));
        for text in [
            "", "E", "05", "X05", "E005", "E0x", "E-5", " E05", "E05 ", "Е05",
        ] {
            assert_eq!(text.parse::<ECode>(), malformed, "{text:?}");
        }
        assert_eq!(
            "E02".parse::<ECode>(),
            Err(ParseECodeError::InvalidValue(ValueError {
                what: What::ServoECode,
                found: 2,
                expected: E_CODES_IN_WORDS
            }))
        );
    }

    #[test]
    fn reserved_bits_are_not_faults_and_survive() {
        let reserved = ServoErrorWord::from_bits_retain(0xFE00_0010);
        assert_eq!(reserved.faults().count(), 0);
        assert!(!reserved.has_cause());
        assert_eq!(reserved.bits(), 0xFE00_0010);
        assert_eq!((!reserved).bits(), 0x01FF_FFEF);
        for bit in [4u8, 25, 26, 27, 28, 29, 30, 31, 32, 255] {
            assert_eq!(ServoFault::from_bit(bit), None);
        }
    }

    #[test]
    fn faults_in_bit_order() {
        let all = ServoErrorWord::from_bits_retain(u32::MAX);
        assert_eq!(all.faults().collect::<Vec<_>>(), ServoFault::ALL);
        assert_eq!(ServoErrorWord::empty().faults().count(), 0);
    }

    #[test]
    fn summary_bit() {
        // (word, has_cause, summarized)
        let table = [
            (0x0000_0000u32, false, 0x0000_0000u32),
            (0x0000_0001, false, 0x0000_0000),
            (0x0000_0002, true, 0x0000_0003),
            (0x0100_0001, true, 0x0100_0001),
            (0xFE00_0010, false, 0xFE00_0010),
            (0xFE00_0011, false, 0xFE00_0010),
        ];
        for (bits, cause, summarized) in table {
            let word = ServoErrorWord::from_bits_retain(bits);
            assert_eq!(word.has_cause(), cause, "{bits:#x}");
            assert_eq!(word.summarized().bits(), summarized, "{bits:#x}");
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::error_word;

    proptest! {
        /// `faults` lists exactly the defined bits that are set, in order.
        #[test]
        fn faults_are_the_defined_set_bits(word in error_word()) {
            let bits: Vec<u8> = word.faults().map(ServoFault::bit).collect();
            let expected: Vec<u8> = (0..32u8)
                .filter(|&bit| word.bits() & (1 << bit) != 0 && DEFINED_BITS & (1 << bit) != 0)
                .collect();
            prop_assert_eq!(bits, expected);
            prop_assert_eq!(ServoErrorWord::from_bits_retain(word.bits()).bits(), word.bits());
        }

        #[test]
        fn parse_never_panics(text in "\\PC{0,6}") {
            if let Ok(code) = text.parse::<ECode>() {
                prop_assert_eq!(code.number(), text[1..].parse::<u8>().unwrap());
            }
        }
    }
}

impl fmt::Display for ServoErrorWord {
    /// The word in hex with its faults and their E-codes (docs/servo.md#sew):
    /// `0x00000101 [ServoErrors, FollowerErr E09]`.
    ///
    /// ```
    /// use motionwire_codec::servo::{ECode, ServoErrorWord};
    ///
    /// let word = ServoErrorWord::from_e_code(ECode::E09).summarized();
    /// assert_eq!(word.to_string(), format!("{:#010x} [ServoErrors, FollowerErr E09]", word.bits()));
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#010x} [", self.bits())?;
        for (i, fault) in self.faults().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            f.write_str(fault.name())?;
            if let Some(code) = fault.e_code() {
                write!(f, " {code}")?;
            }
        }
        f.write_str("]")
    }
}
