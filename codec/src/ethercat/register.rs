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
/// The byte of DL control whose bit 0 enables the station alias.
pub const DL_CONTROL_ALIAS: u16 = 0x0103;
/// Sync manager n's status byte is this far into its 8 bytes (SM1's,
/// 0x080D, bit 3: the mailbox is full).
pub const SYNC_MANAGER_STATUS: u16 = 5;
/// Sync manager n's activate byte (bit 1: the master's repeat request).
pub const SYNC_MANAGER_ACTIVATE: u16 = 6;
/// Sync manager n's PDI control byte (bit 1: the slave's repeat
/// acknowledge).
pub const SYNC_MANAGER_PDI_CONTROL: u16 = 7;
/// DC receive times of ports 0–3 (4 bytes each).
pub const RECEIVE_TIMES: u16 = 0x0900;
/// DC system time (8 bytes).
pub const SYSTEM_TIME: u16 = 0x0910;
/// DC system time offset (8 bytes, or 4 on a slave with a 32-bit clock:
/// added to the local time to give the system time).
pub const SYSTEM_TIME_OFFSET: u16 = 0x0920;
/// DC system time delay (4 bytes, ns: the propagation delay from the
/// reference clock).
pub const SYSTEM_TIME_DELAY: u16 = 0x0928;
/// DC system time difference (4 bytes: the mean difference in bits 0–30,
/// bit 31 set when the local copy is the smaller).
pub const SYSTEM_TIME_DIFFERENCE: u16 = 0x092C;
/// DC cyclic unit control (1 byte).
pub const CYCLIC_UNIT_CONTROL: u16 = 0x0980;
/// DC activation (1 byte: bit 0 cyclic operation, bit 1 SYNC0, bit 2
/// SYNC1).
pub const SYNC_ACTIVATION: u16 = 0x0981;
/// DC SYNC0 cycle time (4 bytes, ns).
pub const SYNC0_CYCLE_TIME: u16 = 0x09A0;
/// DC SYNC1 cycle time (4 bytes, ns).
pub const SYNC1_CYCLE_TIME: u16 = 0x09A4;

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
