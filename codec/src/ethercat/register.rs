//! The ESC registers motionwire decodes where a capture reads or writes
//! them (Beckhoff's ESC datasheet, section II; docs/ethercat.md#registers).
//!
//! A register is decoded when a datagram covers it:
//! [`covered`] gives its bytes in a datagram's data.

/// Configured station address (2 bytes).
pub const STATION_ADDRESS: u16 = 0x0010;
/// Configured station alias (2 bytes).
pub const STATION_ALIAS: u16 = 0x0012;
/// DL control (4 bytes; bit 24 of the word, byte 0x0103 bit 0, enables
/// the alias).
pub const DL_CONTROL: u16 = 0x0100;
/// DL status (2 bytes: link and loop per port).
pub const DL_STATUS: u16 = 0x0110;
/// AL control (2 bytes).
pub const AL_CONTROL: u16 = 0x0120;
/// AL status (2 bytes).
pub const AL_STATUS: u16 = 0x0130;
/// AL status code (2 bytes).
pub const AL_STATUS_CODE: u16 = 0x0134;
/// RX error counters, 2 bytes per port from here (invalid frames, RX errors).
pub const RX_ERROR_COUNTERS: u16 = 0x0300;
/// Forwarded RX error counters, 1 byte per port.
pub const FORWARDED_ERROR_COUNTERS: u16 = 0x0308;
/// ECAT processing unit error counter.
pub const PROCESSING_UNIT_ERRORS: u16 = 0x030C;
/// PDI error counter.
pub const PDI_ERRORS: u16 = 0x030D;
/// Lost link counters, 1 byte per port.
pub const LOST_LINK_COUNTERS: u16 = 0x0310;
/// SII/EEPROM control and status (2 bytes).
pub const SII_CONTROL: u16 = 0x0502;
/// SII/EEPROM word address (4 bytes).
pub const SII_ADDRESS: u16 = 0x0504;
/// SII/EEPROM data (4 or 8 bytes).
pub const SII_DATA: u16 = 0x0508;
/// The first FMMU (16 bytes each).
pub const FMMU_BASE: u16 = 0x0600;
/// The first sync manager (8 bytes each).
pub const SYNC_MANAGER_BASE: u16 = 0x0800;
/// DC system time (8 bytes).
pub const SYSTEM_TIME: u16 = 0x0910;

/// Return the bytes of the register at `register`, `len` bytes long, in
/// the data of a datagram that starts at register `ado`, when the datagram
/// covers all of it.
///
/// ```
/// use motionwire_codec::ethercat::register::{covered, AL_STATUS, AL_STATUS_CODE};
///
/// // TwinCAT and SOEM read AL status and its code in one: 0x0130, 6 bytes.
/// let data = [0x14, 0x00, 0x00, 0x00, 0x1b, 0x00];
/// assert_eq!(covered(0x0130, &data, AL_STATUS, 2), Some(&[0x14, 0x00][..]));
/// assert_eq!(covered(0x0130, &data, AL_STATUS_CODE, 2), Some(&[0x1b, 0x00][..]));
/// assert_eq!(covered(0x0134, &data[..2], AL_STATUS, 2), None);
/// ```
#[must_use]
pub fn covered(ado: u16, data: &[u8], register: u16, len: usize) -> Option<&[u8]> {
    let start = usize::from(register.checked_sub(ado)?);
    data.get(start..start.checked_add(len)?)
}

/// The name of the error counter at `offset` from 0x0300 (Beckhoff's ESC
/// datasheet, section II, 0x0300–0x0313), `None` for a reserved byte.
#[must_use]
pub const fn error_counter_name(offset: usize) -> Option<&'static str> {
    Some(match offset {
        0x00 => "invalid frames port 0",
        0x01 => "RX errors port 0",
        0x02 => "invalid frames port 1",
        0x03 => "RX errors port 1",
        0x04 => "invalid frames port 2",
        0x05 => "RX errors port 2",
        0x06 => "invalid frames port 3",
        0x07 => "RX errors port 3",
        0x08 => "forwarded errors port 0",
        0x09 => "forwarded errors port 1",
        0x0A => "forwarded errors port 2",
        0x0B => "forwarded errors port 3",
        0x0C => "processing unit errors",
        0x0D => "PDI errors",
        0x0E => "PDI error code",
        0x10 => "lost links port 0",
        0x11 => "lost links port 1",
        0x12 => "lost links port 2",
        0x13 => "lost links port 3",
        _ => return None,
    })
}
