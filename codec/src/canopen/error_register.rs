//! The error register, object 1001h (CiA 301 §7.5.2.2;
//! docs/canopen.md#error-register).

use bitflags::bitflags;

bitflags! {
    /// The error register, object 1001h, sent in byte 2 of every EMCY
    /// (CiA 301 §7.5.2.2; docs/canopen.md#error-register).
    ///
    /// Decode a byte that a device sent with [`ErrorRegister::from_bits_retain`]
    /// so that the reserved bit 6 survives a round trip.
    ///
    /// ```
    /// use motionwire_codec::canopen::ErrorRegister;
    ///
    /// let reg = ErrorRegister::from_bits_retain(0x11);
    /// assert!(reg.contains(ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION));
    /// assert_eq!(reg.names().collect::<Vec<_>>(), ["generic", "communication"]);
    /// ```
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
    pub struct ErrorRegister: u8 {
        /// Bit 0: generic error; set whenever any error is present.
        const GENERIC = 1 << 0;
        /// Bit 1: current.
        const CURRENT = 1 << 1;
        /// Bit 2: voltage.
        const VOLTAGE = 1 << 2;
        /// Bit 3: temperature.
        const TEMPERATURE = 1 << 3;
        /// Bit 4: communication error (overrun, error state).
        const COMMUNICATION = 1 << 4;
        /// Bit 5: device profile specific.
        const DEVICE_PROFILE = 1 << 5;
        /// Bit 6: reserved; always 0 when produced, preserved when decoded.
        const RESERVED = 1 << 6;
        /// Bit 7: manufacturer specific.
        const MANUFACTURER = 1 << 7;
    }
}

impl ErrorRegister {
    /// The eight bits in bit order with the names the JSON output of the
    /// command-line decoder writes (docs/output.md#emcy, `register_flags`): the
    /// one table that the names, `Display` and the tests read.
    pub const NAMES: [(ErrorRegister, &'static str); 8] = [
        (ErrorRegister::GENERIC, "generic"),
        (ErrorRegister::CURRENT, "current"),
        (ErrorRegister::VOLTAGE, "voltage"),
        (ErrorRegister::TEMPERATURE, "temperature"),
        (ErrorRegister::COMMUNICATION, "communication"),
        (ErrorRegister::DEVICE_PROFILE, "device_profile"),
        (ErrorRegister::RESERVED, "reserved"),
        (ErrorRegister::MANUFACTURER, "manufacturer"),
    ];

    /// Return the names of the set bits in bit order (`register_flags` in
    /// docs/output.md#emcy).
    pub fn names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |(flag, _)| self.contains(*flag))
            .map(|(_, name)| name)
    }
}

impl core::fmt::Display for ErrorRegister {
    /// `0x11 [generic|communication]`, `0x00 []`.
    ///
    /// ```
    /// use motionwire_codec::canopen::ErrorRegister;
    ///
    /// let register = ErrorRegister::from_bits_retain(0x11);
    /// assert_eq!(register.to_string(), "0x11 [generic|communication]");
    /// ```
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        crate::names::write_word(f, format_args!("{:#04x}", self.bits()), self.names())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_byte_round_trips() {
        for byte in 0..=255u8 {
            assert_eq!(ErrorRegister::from_bits_retain(byte).bits(), byte);
        }
    }

    #[test]
    fn bit_positions() {
        let table = [
            (ErrorRegister::GENERIC, 0x01),
            (ErrorRegister::CURRENT, 0x02),
            (ErrorRegister::VOLTAGE, 0x04),
            (ErrorRegister::TEMPERATURE, 0x08),
            (ErrorRegister::COMMUNICATION, 0x10),
            (ErrorRegister::DEVICE_PROFILE, 0x20),
            (ErrorRegister::RESERVED, 0x40),
            (ErrorRegister::MANUFACTURER, 0x80),
        ];
        for (flag, bits) in table {
            assert_eq!(flag.bits(), bits);
        }
    }

    #[test]
    fn names_in_bit_order() {
        assert_eq!(
            ErrorRegister::all().names().collect::<Vec<_>>(),
            [
                "generic",
                "current",
                "voltage",
                "temperature",
                "communication",
                "device_profile",
                "reserved",
                "manufacturer"
            ]
        );
        for (bit, (flag, _)) in ErrorRegister::NAMES.into_iter().enumerate() {
            assert_eq!(flag.bits(), 1 << bit);
        }
        assert_eq!(ErrorRegister::empty().to_string(), "0x00 []");
        assert_eq!(ErrorRegister::empty().names().count(), 0);
        assert_eq!(
            ErrorRegister::from_bits_retain(0x89)
                .names()
                .collect::<Vec<_>>(),
            ["generic", "temperature", "manufacturer"]
        );
    }
}
