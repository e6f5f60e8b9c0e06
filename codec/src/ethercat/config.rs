//! The configuration registers that say where a slave's process data is:
//! an FMMU (16 bytes at 0x0600 + 16·n) maps a range of the logical
//! address space onto the slave's memory, a sync manager (8 bytes at
//! 0x0800 + 8·n) guards an area of that memory (Beckhoff's ESC datasheet,
//! section II, 0x0600–0x06FF and 0x0800–0x087F; ETG.1000.4 §6.6, §6.7).
//!
//! ```
//! use motionwire_codec::ethercat::{Fmmu, SyncManager, SyncManagerMode};
//!
//! // TwinCAT's FMMU 0 of a drive: 7 output bytes at logical 0x0001000A
//! // onto SM2 at 0x1100, written by the master, active.
//! let fmmu = Fmmu::from_bytes([
//!     0x0a, 0x00, 0x01, 0x00, 0x07, 0x00, 0x00, 0x07,
//!     0x00, 0x11, 0x00, 0x02, 0x01, 0x00, 0x00, 0x00,
//! ]);
//! assert_eq!((fmmu.logical, fmmu.len, fmmu.physical), (0x0001_000A, 7, 0x1100));
//! assert!(fmmu.writes() && !fmmu.reads() && fmmu.active);
//! assert_eq!(Fmmu::from_bytes(fmmu.to_bytes()), fmmu);
//!
//! // SM2: 7 bytes at 0x1100, buffered, written by the master.
//! let sm = SyncManager::from_bytes([0x00, 0x11, 0x07, 0x00, 0x64, 0x00, 0x01, 0x00]);
//! assert_eq!(sm.mode(), SyncManagerMode::Buffered);
//! assert!(sm.written_by_master() && sm.enabled());
//! ```

/// An FMMU's configuration registers are 16 bytes.
pub const FMMU_LEN: usize = 16;
/// A sync manager's configuration registers are 8 bytes.
pub const SYNC_MANAGER_LEN: usize = 8;

/// One FMMU's configuration (ESC datasheet, 0x0600 + 16·n): the logical
/// range it maps, the physical memory it maps it onto, and whether a read
/// or a write of the range reaches the slave.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Fmmu {
    /// Logical start address (bytes 0–3).
    pub logical: u32,
    /// Length in bytes, counted from the first byte to the last byte
    /// mapped (bytes 4–5).
    pub len: u16,
    /// The first bit mapped of the first logical byte (byte 6, bits 0–2).
    pub logical_start_bit: u8,
    /// The last bit mapped of the last logical byte (byte 7, bits 0–2).
    pub logical_end_bit: u8,
    /// Physical start address in the slave's memory (bytes 8–9).
    pub physical: u16,
    /// The first bit mapped of the first physical byte (byte 10, bits 0–2).
    pub physical_start_bit: u8,
    /// Type (byte 11): bit 0 read, bit 1 write.
    pub kind: u8,
    /// Activate (byte 12, bit 0).
    pub active: bool,
}

impl Fmmu {
    /// Read the 16 configuration bytes.
    #[must_use]
    pub const fn from_bytes(b: [u8; FMMU_LEN]) -> Self {
        Fmmu {
            logical: u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            len: u16::from_le_bytes([b[4], b[5]]),
            logical_start_bit: b[6] & 0x07,
            logical_end_bit: b[7] & 0x07,
            physical: u16::from_le_bytes([b[8], b[9]]),
            physical_start_bit: b[10] & 0x07,
            kind: b[11],
            active: b[12] & 0x01 != 0,
        }
    }

    /// Return the 16 configuration bytes (reserved bytes 0).
    #[must_use]
    pub const fn to_bytes(self) -> [u8; FMMU_LEN] {
        let l = self.logical.to_le_bytes();
        let n = self.len.to_le_bytes();
        let p = self.physical.to_le_bytes();
        [
            l[0],
            l[1],
            l[2],
            l[3],
            n[0],
            n[1],
            self.logical_start_bit & 0x07,
            self.logical_end_bit & 0x07,
            p[0],
            p[1],
            self.physical_start_bit & 0x07,
            self.kind,
            self.active as u8,
            0,
            0,
            0,
        ]
    }

    /// Return whether a read of the range reaches the slave (type bit 0:
    /// the slave's inputs).
    #[must_use]
    pub const fn reads(self) -> bool {
        self.kind & 0x01 != 0
    }

    /// Return whether a write of the range reaches the slave (type bit 1:
    /// the slave's outputs).
    #[must_use]
    pub const fn writes(self) -> bool {
        self.kind & 0x02 != 0
    }

    /// Return whether the FMMU maps whole bytes (start bit 0, end bit 7,
    /// physical start bit 0), as FMMUs of sync-manager areas do; a bit
    /// range maps a register's bits (a sync manager's status, 0x080D).
    #[must_use]
    pub const fn whole_bytes(self) -> bool {
        self.logical_start_bit == 0 && self.logical_end_bit == 7 && self.physical_start_bit == 0
    }

    /// Return the logical range `[start, end)` it maps, `None` for a
    /// length of 0 or a range past the 4 GiB address space.
    #[must_use]
    pub const fn logical_range(self) -> Option<(u32, u32)> {
        if self.len == 0 {
            return None;
        }
        match self.logical.checked_add(self.len as u32) {
            Some(end) => Some((self.logical, end)),
            None => None,
        }
    }
}

/// How a sync manager hands its area over (control byte bits 0–1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SyncManagerMode {
    /// 0b00: buffered (three buffers), the process data's mode.
    Buffered,
    /// 0b10: mailbox (one buffer, a handshake).
    Mailbox,
    /// 0b01 or 0b11: reserved.
    Reserved(u8),
}

/// One sync manager's configuration (ESC datasheet, 0x0800 + 8·n).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SyncManager {
    /// Physical start address (bytes 0–1).
    pub start: u16,
    /// Length in bytes (bytes 2–3).
    pub len: u16,
    /// Control (byte 4): mode in bits 0–1, direction in bits 2–3,
    /// interrupts and watchdog above.
    pub control: u8,
    /// Status (byte 5), as written (the slave owns it).
    pub status: u8,
    /// Activate (byte 6): bit 0 enables the sync manager.
    pub activate: u8,
}

impl SyncManager {
    /// Read the 8 configuration bytes (byte 7, the PDI's, is not kept).
    #[must_use]
    pub const fn from_bytes(b: [u8; SYNC_MANAGER_LEN]) -> Self {
        SyncManager {
            start: u16::from_le_bytes([b[0], b[1]]),
            len: u16::from_le_bytes([b[2], b[3]]),
            control: b[4],
            status: b[5],
            activate: b[6],
        }
    }

    /// Return the 8 configuration bytes (byte 7 zero).
    #[must_use]
    pub const fn to_bytes(self) -> [u8; SYNC_MANAGER_LEN] {
        let s = self.start.to_le_bytes();
        let n = self.len.to_le_bytes();
        [
            s[0],
            s[1],
            n[0],
            n[1],
            self.control,
            self.status,
            self.activate,
            0,
        ]
    }

    /// Return the mode.
    #[must_use]
    pub const fn mode(self) -> SyncManagerMode {
        match self.control & 0x03 {
            0b00 => SyncManagerMode::Buffered,
            0b10 => SyncManagerMode::Mailbox,
            other => SyncManagerMode::Reserved(other),
        }
    }

    /// Return whether the master writes the area (direction 0b01: the
    /// slave's outputs, or the master's mailbox); else the master reads
    /// it (0b00).
    #[must_use]
    pub const fn written_by_master(self) -> bool {
        (self.control >> 2) & 0x03 == 0x01
    }

    /// Return whether the sync manager is enabled (activate bit 0).
    #[must_use]
    pub const fn enabled(self) -> bool {
        self.activate & 0x01 != 0
    }

    /// Return whether `address` lies in its area.
    #[must_use]
    pub const fn holds(self, address: u16) -> bool {
        address >= self.start && (address as u32) < self.start as u32 + self.len as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fmmu_round_trip_and_bits() {
        // SOEM's FMMU of SM1's status bit 3 (0x080D) at logical bit 4.
        let bytes = [
            0x20, 0x00, 0x00, 0x00, 0x01, 0x00, 0x04, 0x04, 0x0d, 0x08, 0x03, 0x01, 0x01, 0, 0, 0,
        ];
        let fmmu = Fmmu::from_bytes(bytes);
        assert_eq!(fmmu.to_bytes(), bytes);
        assert!(fmmu.reads() && !fmmu.writes() && !fmmu.whole_bytes());
        assert_eq!(fmmu.logical_range(), Some((0x20, 0x21)));
        let empty = Fmmu::default();
        assert_eq!(empty.logical_range(), None);
        let wraps = Fmmu {
            logical: u32::MAX,
            len: 2,
            ..Fmmu::default()
        };
        assert_eq!(wraps.logical_range(), None);
    }

    #[test]
    fn sync_manager_modes() {
        let mailbox_out = SyncManager::from_bytes([0, 0x10, 0x80, 0, 0x26, 0, 1, 0]);
        assert_eq!(mailbox_out.mode(), SyncManagerMode::Mailbox);
        assert!(mailbox_out.written_by_master() && mailbox_out.enabled());
        let inputs = SyncManager::from_bytes([0x80, 0x11, 7, 0, 0x20, 0, 1, 0]);
        assert_eq!(inputs.mode(), SyncManagerMode::Buffered);
        assert!(!inputs.written_by_master());
        assert!(inputs.holds(0x1186) && !inputs.holds(0x1187) && !inputs.holds(0x117F));
        assert_eq!(SyncManager::from_bytes(inputs.to_bytes()), inputs);
        assert_eq!(
            SyncManager::from_bytes([0, 0, 0, 0, 0x01, 0, 0, 0]).mode(),
            SyncManagerMode::Reserved(1)
        );
    }
}
