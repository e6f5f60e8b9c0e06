//! SSW, the servo status word the drive sends in every feedback frame
//! (docs/servo.md#ssw; the interface manual, "ServoStatusWord").
//!
//! ```
//! use motionwire_codec::servo::{EncoderKind, ServoStatusWord};
//!
//! let ssw = ServoStatusWord::from_bits_retain(0x1187);
//! assert!(ssw.contains(ServoStatusWord::SERVO_EN | ServoStatusWord::SERVO_RDY));
//! assert_eq!(ssw.encoder(), EncoderKind::Incremental);
//! assert_eq!(ssw.parameter_table().get(), 6);
//! assert_eq!(
//!     ssw.flag_names().collect::<Vec<_>>(),
//!     ["ServoEn", "ServoRDY", "AbsIncr", "PulseEnabled", "ExtPRMTBL"]
//! );
//! ```

use core::fmt;

use bitflags::bitflags;

use super::ParameterTable;

bitflags! {
    /// SSW, the servo status word, servo → NC (docs/servo.md#ssw; the interface
    /// manual).
    ///
    /// The 2-bit PRMTBL field (bits 8–9) is read with
    /// [`ServoStatusWord::parameter_table`], not as flags. All bits are
    /// declared as known to bitflags, so the field and the reserved bits
    /// 13–31 survive decoding with [`ServoStatusWord::from_bits_retain`] and
    /// every flag operation.
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
    pub struct ServoStatusWord: u32 {
        /// Bit 0, ServoEn: the drive is enabled (motor live).
        const SERVO_EN = 1 << 0;
        /// Bit 1, ServoRDY: the drive is ready (truth table of
        /// docs/servo.md#servo-ready,
        /// [`servo_ready`](crate::servo::servo_ready)).
        const SERVO_RDY = 1 << 1;
        /// Bit 2, Abs/Incr: 0 = absolute (EnDat) encoder, 1 = incremental
        /// encoder; see [`ServoStatusWord::encoder`].
        const ABS_INCR = 1 << 2;
        /// Bit 3, ZPulseAck: the zero pulse was found after a request
        /// (handshake of docs/servo.md#handshakes).
        const Z_PULSE_ACK = 1 << 3;
        /// Bit 4, ErrClearAck: the drive's errors were cleared after
        /// ErrorClear (handshake of docs/servo.md#handshakes).
        const ERR_CLEAR_ACK = 1 << 4;
        /// Bit 5, N=0: motor speed below the standstill threshold.
        const N_ZERO = 1 << 5;
        /// Bit 6, N=Ns: motor speed within the tolerance of the reference.
        const N_EQ_NS = 1 << 6;
        /// Bit 7, PulseEnabled: the power stage (IGBT) is switched on.
        const PULSE_ENABLED = 1 << 7;
        /// Bit 10, NoEncoder: the axis has no encoder (e.g. an inverter). (The
        /// interface manual's caption "Errors are deleted yet" for this bit is
        /// a copy error; docs/servo.md#ssw.)
        const NO_ENCODER = 1 << 10;
        /// Bit 11, TempWarning: motor temperature measured in the encoder
        /// above 80 °C.
        const TEMP_WARNING = 1 << 11;
        /// Bit 12, ExtPRMTBL: high bit of the active parameter table; see
        /// [`ServoStatusWord::parameter_table`].
        const EXT_PRMTBL = 1 << 12;

        // PRMTBL and the reserved bits are not flags but must survive every
        // operation (bitflags 2, "externally defined flags").
        const _ = !0;
    }
}

/// Bits 8–9: PRMTBL, the active parameter table's low two bits.
const PRMTBL_SHIFT: u32 = 8;
const PRMTBL_MASK: u32 = 0b11 << PRMTBL_SHIFT;

impl ServoStatusWord {
    /// The names of the single-bit flags as docs/servo.md#cli-feedback writes
    /// them, in bit order.
    pub const NAMES: [(ServoStatusWord, &'static str); 11] = [
        (ServoStatusWord::SERVO_EN, "ServoEn"),
        (ServoStatusWord::SERVO_RDY, "ServoRDY"),
        (ServoStatusWord::ABS_INCR, "AbsIncr"),
        (ServoStatusWord::Z_PULSE_ACK, "ZPulseAck"),
        (ServoStatusWord::ERR_CLEAR_ACK, "ErrClearAck"),
        (ServoStatusWord::N_ZERO, "N0"),
        (ServoStatusWord::N_EQ_NS, "NNs"),
        (ServoStatusWord::PULSE_ENABLED, "PulseEnabled"),
        (ServoStatusWord::NO_ENCODER, "NoEncoder"),
        (ServoStatusWord::TEMP_WARNING, "TempWarning"),
        (ServoStatusWord::EXT_PRMTBL, "ExtPRMTBL"),
    ];

    /// Return the names of the set single-bit flags in bit order, as the
    /// command-line decoder's `status_flags` writes them
    /// (docs/servo.md#cli-feedback).
    pub fn flag_names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |&(flag, _)| self.contains(flag))
            .map(|(_, name)| name)
    }

    /// Return the active parameter table, ExtPRMTBL·4 + PRMTBL + 1, from
    /// PRMTBL (bits 8–9) and ExtPRMTBL (bit 12) (docs/servo.md#ssw).
    #[must_use]
    pub const fn parameter_table(self) -> ParameterTable {
        ParameterTable::from_select(
            self.contains(ServoStatusWord::EXT_PRMTBL),
            ((self.bits() & PRMTBL_MASK) >> PRMTBL_SHIFT) as u8,
        )
    }

    /// Return a copy reporting `table` as active (PRMTBL bits 8–9 and
    /// ExtPRMTBL bit 12); every other bit is kept.
    #[must_use]
    pub const fn with_parameter_table(self, table: ParameterTable) -> Self {
        let bits = (self.bits() & !PRMTBL_MASK) | ((table.prmtbl() as u32) << PRMTBL_SHIFT);
        ServoStatusWord::from_bits_retain(bits)
            .with_flag(ServoStatusWord::EXT_PRMTBL, table.ext_prmtbl())
    }

    /// Return the kind of encoder the Abs/Incr bit (bit 2) reports; it
    /// decides how the feedback's ActPos is read (docs/servo.md#feedback).
    #[must_use]
    pub const fn encoder(self) -> EncoderKind {
        if self.contains(ServoStatusWord::ABS_INCR) {
            EncoderKind::Incremental
        } else {
            EncoderKind::Absolute
        }
    }

    /// Return a copy whose Abs/Incr bit (bit 2) reports `encoder`.
    #[must_use]
    pub const fn with_encoder(self, encoder: EncoderKind) -> Self {
        self.with_flag(
            ServoStatusWord::ABS_INCR,
            matches!(encoder, EncoderKind::Incremental),
        )
    }

    /// Return a copy with the single-bit `flag` set or cleared.
    #[must_use]
    pub const fn with_flag(self, flag: ServoStatusWord, set: bool) -> Self {
        if set {
            self.union(flag)
        } else {
            self.difference(flag)
        }
    }
}

/// The kind of position encoder, from SSW bit 2 Abs/Incr
/// (docs/servo.md#feedback, docs/servo.md#ssw).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum EncoderKind {
    /// Abs/Incr = 0: absolute (EnDat) encoder; ActPos is a 64-bit position.
    Absolute,
    /// Abs/Incr = 1: incremental encoder; ActPos holds a 32-bit position
    /// (POSW0..1) and the position latched at the last zero pulse (POSW2..3).
    Incremental,
}

impl EncoderKind {
    /// Return the name the command-line decoder's `encoder` writes
    /// (docs/servo.md#cli-feedback): `"absolute"` or `"incremental"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            EncoderKind::Absolute => "absolute",
            EncoderKind::Incremental => "incremental",
        }
    }
}

impl fmt::Display for EncoderKind {
    /// Format the kind as its name (docs/servo.md#cli-feedback).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/servo.md#ssw / the interface manual's bit diagram: every single-bit
    /// flag at its bit.
    #[test]
    fn flag_bit_positions() {
        let table = [
            (ServoStatusWord::SERVO_EN, 0),
            (ServoStatusWord::SERVO_RDY, 1),
            (ServoStatusWord::ABS_INCR, 2),
            (ServoStatusWord::Z_PULSE_ACK, 3),
            (ServoStatusWord::ERR_CLEAR_ACK, 4),
            (ServoStatusWord::N_ZERO, 5),
            (ServoStatusWord::N_EQ_NS, 6),
            (ServoStatusWord::PULSE_ENABLED, 7),
            (ServoStatusWord::NO_ENCODER, 10),
            (ServoStatusWord::TEMP_WARNING, 11),
            (ServoStatusWord::EXT_PRMTBL, 12),
        ];
        for (flag, bit) in table {
            assert_eq!(flag.bits(), 1u32 << bit, "{flag:?}");
        }
    }

    #[test]
    fn flag_names_are_the_json_names_in_bit_order() {
        assert_eq!(
            ServoStatusWord::from_bits_retain(u32::MAX)
                .flag_names()
                .collect::<Vec<_>>(),
            [
                "ServoEn",
                "ServoRDY",
                "AbsIncr",
                "ZPulseAck",
                "ErrClearAck",
                "N0",
                "NNs",
                "PulseEnabled",
                "NoEncoder",
                "TempWarning",
                "ExtPRMTBL"
            ]
        );
        // PRMTBL and the reserved bits 13–31 have no names.
        assert_eq!(
            ServoStatusWord::from_bits_retain(0xFFFF_E300)
                .flag_names()
                .count(),
            0
        );
        assert_eq!(
            ServoStatusWord::from_bits_retain(0x0000_0830)
                .flag_names()
                .collect::<Vec<_>>(),
            ["ErrClearAck", "N0", "TempWarning"]
        );
    }

    /// The interface manual, "ExtendedPaRaMeterTaBLe Selected": the eight
    /// combinations of ExtPRMTBL (bit 12) and PRMTBL (bits 9–8).
    #[test]
    fn every_parameter_table_combination() {
        // (wire bits, table)
        let table = [
            (0x0000u32, 1u8),
            (0x0100, 2),
            (0x0200, 3),
            (0x0300, 4),
            (0x1000, 5),
            (0x1100, 6),
            (0x1200, 7),
            (0x1300, 8),
        ];
        for (bits, number) in table {
            let expected = ParameterTable::try_new(number).unwrap();
            assert_eq!(
                ServoStatusWord::from_bits_retain(bits).parameter_table(),
                expected
            );
            assert_eq!(
                ServoStatusWord::empty()
                    .with_parameter_table(expected)
                    .bits(),
                bits
            );
            let full = ServoStatusWord::from_bits_retain(u32::MAX).with_parameter_table(expected);
            assert_eq!(full.bits(), !0x1300 | bits);
        }
    }

    #[test]
    fn encoder_kind_from_abs_incr() {
        let absolute = ServoStatusWord::from_bits_retain(0xFFFF_FFFB);
        assert_eq!(absolute.encoder(), EncoderKind::Absolute);
        let incremental = ServoStatusWord::from_bits_retain(0x0000_0004);
        assert_eq!(incremental.encoder(), EncoderKind::Incremental);
        assert_eq!(
            absolute.with_encoder(EncoderKind::Incremental).bits(),
            u32::MAX
        );
        assert_eq!(incremental.with_encoder(EncoderKind::Absolute).bits(), 0);
        assert_eq!(EncoderKind::Absolute.name(), "absolute");
        assert_eq!(EncoderKind::Incremental.to_string(), "incremental");
    }

    #[test]
    fn reserved_bits_survive() {
        for bits in [0xFFFF_E000u32, 0x8000_0000, 0x0000_2000, u32::MAX] {
            let word = ServoStatusWord::from_bits_retain(bits);
            assert_eq!(word.bits(), bits);
            assert_eq!((!word).bits(), !bits);
        }
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::servo::{parameter_table, status_word};

    proptest! {
        #[test]
        fn with_parameter_table_touches_only_its_bits(word in status_word(), table in parameter_table()) {
            let w = word.with_parameter_table(table);
            prop_assert_eq!(w.parameter_table(), table);
            prop_assert_eq!(w.bits() & !0x1300, word.bits() & !0x1300);
        }

        #[test]
        fn bits_round_trip(bits in any::<u32>()) {
            prop_assert_eq!(ServoStatusWord::from_bits_retain(bits).bits(), bits);
        }
    }
}

impl fmt::Display for ServoStatusWord {
    /// The word in hex with the names of its set single-bit flags, as
    /// docs/servo.md#cli-feedback names them: `0x00000021 [EMGON|Brake]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        crate::names::write_word(f, format_args!("{:#010x}", self.bits()), self.flag_names())
    }
}
