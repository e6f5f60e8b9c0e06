//! Emergency error codes and their classes (CiA 301 Table 26;
//! docs/canopen.md#emcy-codes).

mod code;
mod descriptions;

pub use code::{ErrorClass, ErrorCode};
pub use descriptions::{Description, DescriptionSource, Specificity};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::ErrorRegister;

    /// The range table of docs/canopen.md#emcy-codes, written out: (first,
    /// last, class).
    const RANGES: &[(u16, u16, ErrorClass)] = &[
        (0x0000, 0x00FF, ErrorClass::Reset),
        (0x1000, 0x10FF, ErrorClass::Generic),
        (0x2000, 0x2FFF, ErrorClass::Current),
        (0x3000, 0x3FFF, ErrorClass::Voltage),
        (0x4000, 0x4FFF, ErrorClass::Temperature),
        (0x5000, 0x5FFF, ErrorClass::DeviceHardware),
        (0x6000, 0x6FFF, ErrorClass::DeviceSoftware),
        (0x7000, 0x7FFF, ErrorClass::AdditionalModules),
        (0x8000, 0x8FFF, ErrorClass::Monitoring),
        (0x9000, 0x9FFF, ErrorClass::External),
        (0xF000, 0xF0FF, ErrorClass::AdditionalFunctions),
        (0xFF00, 0xFFFF, ErrorClass::DeviceSpecific),
    ];

    #[test]
    fn all_65536_codes_against_the_range_table() {
        for raw in 0..=u16::MAX {
            let expected = RANGES
                .iter()
                .find(|&&(lo, hi, _)| (lo..=hi).contains(&raw))
                .map_or(ErrorClass::Unknown, |&(_, _, class)| class);
            assert_eq!(ErrorCode::new(raw).class(), expected, "{raw:#06x}");
            assert_eq!(ErrorCode::new(raw).is_reset(), raw <= 0x00FF);
        }
    }

    #[test]
    fn unknown_ranges_named_by_the_spec() {
        for raw in [
            0x0100, 0x0FFF, 0x1100, 0x1FFF, 0xA000, 0xEFFF, 0xF100, 0xFEFF,
        ] {
            assert_eq!(
                ErrorCode::new(raw).class(),
                ErrorClass::Unknown,
                "{raw:#06x}"
            );
        }
    }

    #[test]
    fn register_class_bits() {
        let table = [
            (0x1000, ErrorRegister::empty()),
            (0x2310, ErrorRegister::CURRENT),
            (0x3210, ErrorRegister::VOLTAGE),
            (0x4310, ErrorRegister::TEMPERATURE),
            (0x5100, ErrorRegister::empty()),
            (0x8000, ErrorRegister::empty()),
            (0x8110, ErrorRegister::COMMUNICATION),
            (0x8250, ErrorRegister::COMMUNICATION),
            (0x8311, ErrorRegister::empty()),
            (0xFF00, ErrorRegister::empty()),
        ];
        for (raw, bits) in table {
            assert_eq!(
                ErrorCode::new(raw).register_class_bits(),
                bits,
                "{raw:#06x}"
            );
        }
    }

    #[test]
    fn class_names() {
        assert_eq!(ErrorClass::DeviceHardware.name(), "device_hardware");
        assert_eq!(
            ErrorClass::AdditionalFunctions.to_string(),
            "additional_functions"
        );
        assert_eq!(ErrorCode::new(0x2310).to_string(), "0x2310");
    }
}
