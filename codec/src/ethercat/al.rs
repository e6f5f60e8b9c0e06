//! The application layer's state, status and status code: [`AlState`],
//! [`AlStatus`], [`AlStatusCode`].

use core::fmt;

/// An EtherCAT state machine state (ETG.1000.6 §6.4.1; the low 4 bits of
/// AL control 0x0120 and AL status 0x0130).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum AlState {
    /// 1: INIT.
    Init,
    /// 2: PRE-OPERATIONAL (mailbox running).
    PreOp,
    /// 3: BOOTSTRAP (firmware update).
    Boot,
    /// 4: SAFE-OPERATIONAL (inputs running, outputs safe).
    SafeOp,
    /// 8: OPERATIONAL.
    Op,
}

impl AlState {
    /// Read the 4 state bits; `None` for a value that is no one state
    /// (0, or the OR of several slaves' states read by a broadcast).
    #[must_use]
    pub const fn from_bits(bits: u8) -> Option<Self> {
        match bits & 0x0F {
            1 => Some(AlState::Init),
            2 => Some(AlState::PreOp),
            3 => Some(AlState::Boot),
            4 => Some(AlState::SafeOp),
            8 => Some(AlState::Op),
            _ => None,
        }
    }

    /// Return the 4 state bits.
    #[must_use]
    pub const fn bits(self) -> u8 {
        match self {
            AlState::Init => 1,
            AlState::PreOp => 2,
            AlState::Boot => 3,
            AlState::SafeOp => 4,
            AlState::Op => 8,
        }
    }

    /// Return the state's name as docs/ethercat.md writes it: `init`,
    /// `preop`, `boot`, `safeop`, `op`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            AlState::Init => "init",
            AlState::PreOp => "preop",
            AlState::Boot => "boot",
            AlState::SafeOp => "safeop",
            AlState::Op => "op",
        }
    }
}

impl fmt::Display for AlState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The AL status register 0x0130 (or the AL control register 0x0120, which
/// has the same layout: the requested state, and the error acknowledge in
/// bit 4), as read: state bits 0–3, error indicator bit 4, device
/// identification bit 5 (Beckhoff's ESC datasheet, section II, 0x0130).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct AlStatus(pub u16);

impl AlStatus {
    /// Return the 4 state bits as read (a broadcast read gives the OR of
    /// every slave's).
    #[inline]
    #[must_use]
    pub const fn state_bits(self) -> u8 {
        (self.0 & 0x0F) as u8
    }

    /// Return the state, when the bits name one.
    #[inline]
    #[must_use]
    pub const fn state(self) -> Option<AlState> {
        AlState::from_bits(self.state_bits())
    }

    /// Return bit 4: in AL status the error indicator (the slave refused
    /// or left a state; AL status code 0x0134 says why), in AL control the
    /// error acknowledge.
    #[inline]
    #[must_use]
    pub const fn error(self) -> bool {
        self.0 & 0x10 != 0
    }
}

/// An AL status code, register 0x0134: why a slave refused or left a state
/// (ETG.1000.6 table 11, as ethercrab lists it, with the codes SOEM's
/// `ec_ALstatuscodelist` adds; docs/ethercat.md#al-status-codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct AlStatusCode(pub u16);

impl AlStatusCode {
    /// Return the code's text: the table's, `vendor specific` for
    /// 0x8000–0xFFFF, `None` for a code the table does not define.
    #[must_use]
    pub const fn text(self) -> Option<&'static str> {
        Some(match self.0 {
            0x0000 => "No error",
            0x0001 => "Unspecified error",
            0x0002 => "No memory",
            0x0004 => "Invalid revision",
            0x0006 => "SII/EEPROM information does not match firmware",
            0x0007 => "Firmware update not successful, old firmware still running",
            0x000E => "License error",
            0x0011 => "Invalid requested state change",
            0x0012 => "Unknown requested state",
            0x0013 => "Bootstrap not supported",
            0x0014 => "No valid firmware",
            0x0015 | 0x0016 => "Invalid mailbox configuration",
            0x0017 => "Invalid sync manager configuration",
            0x0018 => "No valid inputs available",
            0x0019 => "No valid outputs",
            0x001A => "Synchronization error",
            0x001B => "Sync manager watchdog",
            0x001C => "Invalid sync manager types",
            0x001D => "Invalid output configuration",
            0x001E => "Invalid input configuration",
            0x001F => "Invalid watchdog configuration",
            0x0020 => "Slave needs cold start",
            0x0021 => "Slave needs INIT",
            0x0022 => "Slave needs PREOP",
            0x0023 => "Slave needs SAFEOP",
            0x0024 => "Invalid input mapping",
            0x0025 => "Invalid output mapping",
            0x0026 => "Inconsistent settings",
            0x0027 => "Freerun not supported",
            0x0028 => "Synchronization not supported",
            0x0029 => "Freerun needs 3-buffer mode",
            0x002A => "Background watchdog",
            0x002B => "No valid inputs and outputs",
            0x002C => "Fatal sync error",
            0x002D => "No sync error",
            0x002E => "Invalid input FMMU configuration",
            0x0030 => "Invalid DC SYNC configuration",
            0x0031 => "Invalid DC latch configuration",
            0x0032 => "PLL error",
            0x0033 => "DC sync IO error",
            0x0034 => "DC sync timeout error",
            0x0035 => "DC invalid sync cycle time",
            0x0036 => "DC invalid sync0 cycle time",
            0x0037 => "DC invalid sync1 cycle time",
            0x0041 => "MBX_AOE",
            0x0042 => "MBX_EOE",
            0x0043 => "MBX_COE",
            0x0044 => "MBX_FOE",
            0x0045 => "MBX_SOE",
            0x004F => "MBX_VOE",
            0x0050 => "EEPROM no access",
            0x0051 => "EEPROM error",
            0x0052 => "External hardware not ready",
            0x0060 => "Slave restarted locally",
            0x0061 => "Device identification value updated",
            0x0070 => "Detected module ident list does not match",
            0x0080 => "Supply voltage too low",
            0x0081 => "Supply voltage too high",
            0x0082 => "Temperature too low",
            0x0083 => "Temperature too high",
            0x00F0 => "Application controller available",
            0x8000..=0xFFFF => "vendor specific",
            _ => return None,
        })
    }
}

impl fmt::Display for AlStatusCode {
    /// `0x001b Sync manager watchdog`; `0x0099 unknown` for a code the
    /// table does not define.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#06x} {}", self.0, self.text().unwrap_or("unknown"))
    }
}
