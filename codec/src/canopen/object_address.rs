//! The address of an object-dictionary entry: a 16-bit index and an 8-bit
//! sub-index (CiA 301 §7.4.1). An SDO transfer carries it as its
//! "multiplexer" (CiA 301 §7.2.4.3, bytes 1–3), a PDO mapping entry as its
//! top 24 bits (CiA 301 §7.5.2.36), an EDS as its section names
//! (CiA 306): one type for all of them.
//!
//! It is written two ways, both in the program's output: CiA's hex notation
//! `1008h.00` ([`Display`](core::fmt::Display)) and CiA 306's sub-object
//! notation `1008sub0` ([`ObjectAddress::sub_notation`]).
//!
//! ```
//! use motionwire_codec::canopen::ObjectAddress;
//!
//! let address = ObjectAddress::new(0x1A00, 0x1A);
//! assert_eq!(address.to_string(), "1A00h.1A");
//! assert_eq!(address.sub_notation().to_string(), "1A00sub1A");
//! assert_eq!(ObjectAddress::default().to_string(), "0000h.00");
//! ```

use core::fmt;

/// An object-dictionary entry's address: index and sub-index (CiA 301
/// §7.4.1; the SDO "multiplexer" of CiA 301 §7.2.4.3).
///
/// Displays in CiA's notation, index and sub-index in hex: `1008h.00`.
/// [`ObjectAddress::sub_notation`] gives `1008sub0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ObjectAddress {
    /// The object index, e.g. `0x1003`.
    pub index: u16,
    /// The sub-index.
    pub sub_index: u8,
}

impl ObjectAddress {
    /// Return the address of `index`, sub-index `sub_index`.
    #[must_use]
    pub const fn new(index: u16, sub_index: u8) -> Self {
        ObjectAddress { index, sub_index }
    }

    /// Return the address written as CiA 306 names a sub-object's section
    /// and docs/canopen.md#signals a signal that neither an EDS nor a profile
    /// names: the index in four hex digits, `sub`, the sub-index in hex without
    /// padding (`6041sub0`, `1A00sub1A`).
    #[must_use]
    pub const fn sub_notation(self) -> SubNotation {
        SubNotation(self)
    }
}

impl fmt::Display for ObjectAddress {
    /// `1008h.00`: CiA's notation, index and sub-index in hex.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04X}h.{:02X}", self.index, self.sub_index)
    }
}

/// An [`ObjectAddress`] displayed in CiA 306's sub-object notation,
/// `6041sub0`: what [`ObjectAddress::sub_notation`] returns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SubNotation(ObjectAddress);

impl fmt::Display for SubNotation {
    /// `6041sub0`, `1A00sub1A`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04X}sub{:X}", self.0.index, self.0.sub_index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_notations() {
        let cases = [
            (0x1008, 0x00, "1008h.00", "1008sub0"),
            (0x6041, 0x00, "6041h.00", "6041sub0"),
            (0x1A00, 0x1A, "1A00h.1A", "1A00sub1A"),
            (0x0001, 0xFF, "0001h.FF", "0001subFF"),
        ];
        for (index, sub_index, hex, sub) in cases {
            let address = ObjectAddress::new(index, sub_index);
            assert_eq!(address.to_string(), hex);
            assert_eq!(address.sub_notation().to_string(), sub);
        }
    }
}
