//! The distributed-clock registers a datagram covers
//! (docs/ethercat.md#dc): port receive times, system time, the system-time
//! offset and delay, the system-time difference, SYNC activation and the
//! SYNC0/SYNC1 cycle times (Beckhoff's ESC datasheet, section II,
//! 0x0900–0x09A7).

use crate::ethercat::register::{self, covered};

/// What a datagram read or wrote of one slave's distributed-clock
/// registers, each where the datagram covers it.
///
/// ```
/// use motionwire::decoder::ethercat::DcRegisters;
///
/// // A read of 0x092C: the local copy 12 ns behind the received time.
/// let read = DcRegisters::covered(0x092C, &[0x0c, 0, 0, 0x80], true).unwrap();
/// assert_eq!(read.time_difference_ns, Some(-12));
/// // A write of SYNC activation 0x0981: cyclic operation and SYNC0.
/// let written = DcRegisters::covered(0x0981, &[0x03], false).unwrap();
/// assert_eq!((written.sync0(), written.sync1()), (Some(true), Some(false)));
/// // A write of 0x0910 is the drift compensation's, no register here.
/// assert_eq!(DcRegisters::covered(0x0910, &[0; 8], false), None);
/// // ethercrab's write of the offset and, in the next datagram, the delay.
/// let offset = (-1_000_000_000i64).to_le_bytes();
/// let written = DcRegisters::covered(0x0920, &offset, false).unwrap();
/// assert_eq!(written.system_time_offset_ns, Some(-1_000_000_000));
/// let written = DcRegisters::covered(0x0928, &[0x2c, 0x01, 0, 0], false).unwrap();
/// assert_eq!(written.system_time_delay_ns, Some(300));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DcRegisters {
    /// The receive times of ports 0–3 (0x0900 + 4·p, 32-bit local time in
    /// ns), read.
    pub receive_times: [Option<u32>; 4],
    /// The system time (0x0910, ns since 2000-01-01), read: 64 bits, or
    /// the low 32 where the read covers 4 bytes.
    pub system_time: Option<u64>,
    /// The system-time offset (0x0920), read or written: what the slave
    /// adds to its local time to give the system time, in ns, as a
    /// two's-complement number — 64 bits, or 32 where the datagram covers
    /// 4 bytes (a slave with a 32-bit clock). The specification types it
    /// unsigned, but the addition wraps either way and masters write
    /// negative offsets (ethercrab: the master's time minus the slave's
    /// receive time).
    pub system_time_offset_ns: Option<i64>,
    /// The system-time delay (0x0928), read or written: the propagation
    /// delay from the reference clock to the slave, in ns.
    pub system_time_delay_ns: Option<u32>,
    /// The system-time difference (0x092C), read: the local copy minus
    /// the received time, in ns (bits 0–30 the magnitude, bit 31 the sign).
    pub time_difference_ns: Option<i64>,
    /// Cyclic unit control (0x0980).
    pub cyclic_unit_control: Option<u8>,
    /// SYNC activation (0x0981): bit 0 cyclic operation, bit 1 SYNC0,
    /// bit 2 SYNC1.
    pub activation: Option<u8>,
    /// SYNC0 cycle time (0x09A0), ns.
    pub sync0_cycle_ns: Option<u32>,
    /// SYNC1 cycle time (0x09A4), ns.
    pub sync1_cycle_ns: Option<u32>,
}

impl DcRegisters {
    /// Return the registers a datagram at `ado` with `data` covers: every
    /// one for a read (`read`), the configuration (system-time offset and
    /// delay, cyclic unit control, activation, cycle times) for a write —
    /// a write of the receive times latches them and one of the system
    /// time is the drift compensation's, neither a value of the slave.
    /// `None` when it covers none.
    #[must_use]
    pub fn covered(ado: u16, data: &[u8], read: bool) -> Option<Self> {
        let u32_at = |reg: u16| {
            covered(ado, data, reg, 4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        };
        let byte_at = |reg: u16| covered(ado, data, reg, 1).map(|b| b[0]);
        let offset = match covered(ado, data, register::SYSTEM_TIME_OFFSET, 8) {
            Some(b) => Some(i64::from_le_bytes([
                b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7],
            ])),
            None => covered(ado, data, register::SYSTEM_TIME_OFFSET, 4)
                .map(|b| i64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]]))),
        };
        let mut dc = DcRegisters {
            system_time_offset_ns: offset,
            system_time_delay_ns: u32_at(register::SYSTEM_TIME_DELAY),
            cyclic_unit_control: byte_at(register::CYCLIC_UNIT_CONTROL),
            activation: byte_at(register::SYNC_ACTIVATION),
            sync0_cycle_ns: u32_at(register::SYNC0_CYCLE_TIME),
            sync1_cycle_ns: u32_at(register::SYNC1_CYCLE_TIME),
            ..DcRegisters::default()
        };
        if read {
            for (p, time) in dc.receive_times.iter_mut().enumerate() {
                *time = u32_at(register::RECEIVE_TIMES + 4 * p as u16);
            }
            dc.system_time = match covered(ado, data, register::SYSTEM_TIME, 8) {
                Some(b) => Some(u64::from_le_bytes([
                    b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7],
                ])),
                None => u32_at(register::SYSTEM_TIME).map(u64::from),
            };
            dc.time_difference_ns = u32_at(register::SYSTEM_TIME_DIFFERENCE).map(time_difference);
        }
        (dc != DcRegisters::default()).then_some(dc)
    }

    /// Return whether cyclic operation is activated (0x0981 bit 0).
    #[must_use]
    pub fn cyclic_operation(&self) -> Option<bool> {
        self.activation.map(|a| a & 0x01 != 0)
    }

    /// Return whether SYNC0 is activated (0x0981 bit 1).
    #[must_use]
    pub fn sync0(&self) -> Option<bool> {
        self.activation.map(|a| a & 0x02 != 0)
    }

    /// Return whether SYNC1 is activated (0x0981 bit 2).
    #[must_use]
    pub fn sync1(&self) -> Option<bool> {
        self.activation.map(|a| a & 0x04 != 0)
    }
}

/// The system-time difference register's value in ns, signed, the local
/// copy of the system time minus the received system time: bits 0–30 the
/// mean difference, bit 31 set when the local copy is smaller than the
/// received time — a sign and a magnitude, not two's complement.
///
/// This is the register description of Beckhoff's ESC datasheet (section
/// II, 0x092C:0x092F: bit 31 "0: local copy of System Time greater than or
/// equal received System Time, 1: local copy of System Time smaller than
/// received System Time"), which Infineon's XMC4800 reference manual
/// repeats for its ESC (`ECAT0.DC_SYS_TIME_DIFF`, field `CPY`). Masters
/// read it so: ethercrab's `examples/dc.rs` and SOEM's
/// `test/linux/red_test/red_test.c` negate the magnitude when bit 31 is
/// set.
#[must_use]
pub const fn time_difference(raw: u32) -> i64 {
    let magnitude = (raw & 0x7FFF_FFFF) as i64;
    if raw & 0x8000_0000 != 0 {
        -magnitude
    } else {
        magnitude
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        /// Any datagram: no panic; a write decodes the configuration alone,
        /// and the same registers as the read of the same bytes.
        #[test]
        fn any_datagram_decodes_or_is_none(ado: u16, data in proptest::collection::vec(any::<u8>(), 0..64)) {
            let read = DcRegisters::covered(ado, &data, true);
            let written = DcRegisters::covered(ado, &data, false);
            if let Some(written) = written {
                prop_assert_eq!(written.receive_times, [None; 4]);
                prop_assert_eq!(written.system_time, None);
                prop_assert_eq!(written.time_difference_ns, None);
                let read = read.unwrap();
                prop_assert_eq!(read.activation, written.activation);
                prop_assert_eq!(read.system_time_offset_ns, written.system_time_offset_ns);
                prop_assert_eq!(read.system_time_delay_ns, written.system_time_delay_ns);
                prop_assert_eq!(read.sync0_cycle_ns, written.sync0_cycle_ns);
                prop_assert_eq!(read.sync1_cycle_ns, written.sync1_cycle_ns);
            }
            if let Some(ns) = read.and_then(|r| r.time_difference_ns) {
                prop_assert!(ns.abs() <= 0x7FFF_FFFF);
            }
        }
    }

    /// TwinCAT's APRD of 0x0900 with 32 bytes: the four receive times and
    /// the 64-bit system time; 0x0918 is not one of them.
    #[test]
    fn a_wide_read_gives_times_and_system_time() {
        let mut data = [0u8; 32];
        for p in 0..4u32 {
            data[4 * p as usize..4 * p as usize + 4].copy_from_slice(&(100 + p).to_le_bytes());
        }
        data[16..24].copy_from_slice(&0x0102_0304_0506_0708u64.to_le_bytes());
        let dc = DcRegisters::covered(0x0900, &data, true).unwrap();
        assert_eq!(
            dc.receive_times,
            [Some(100), Some(101), Some(102), Some(103)]
        );
        assert_eq!(dc.system_time, Some(0x0102_0304_0506_0708));
        assert_eq!(dc.time_difference_ns, None);
        // Written, the same bytes latch the times: nothing to decode.
        assert_eq!(DcRegisters::covered(0x0900, &data, false), None);
    }

    /// TwinCAT's APWR of 0x0920 with 12 bytes: the offset and the delay;
    /// a 4-byte offset is a 32-bit clock's, signed as well.
    #[test]
    fn the_offset_and_the_delay_are_read_or_written() {
        let mut data = [0u8; 12];
        data[..8].copy_from_slice(&0x0000_02AB_CDEF_0123u64.to_le_bytes());
        data[8..].copy_from_slice(&450u32.to_le_bytes());
        for read in [true, false] {
            let dc = DcRegisters::covered(0x0920, &data, read).unwrap();
            assert_eq!(dc.system_time_offset_ns, Some(0x0000_02AB_CDEF_0123));
            assert_eq!(dc.system_time_delay_ns, Some(450));
            assert_eq!(dc.time_difference_ns, None);
        }
        let narrow = DcRegisters::covered(0x0920, &[0xff, 0xff, 0xff, 0xff], false).unwrap();
        assert_eq!(narrow.system_time_offset_ns, Some(-1));
        assert_eq!(narrow.system_time_delay_ns, None);
        // A read from 0x0910 with 32 bytes covers every one of them.
        let mut wide = [0u8; 32];
        wide[16..24].copy_from_slice(&(-5i64).to_le_bytes());
        wide[28..].copy_from_slice(&0x8000_0007u32.to_le_bytes());
        let dc = DcRegisters::covered(0x0910, &wide, true).unwrap();
        assert_eq!(
            (
                dc.system_time,
                dc.system_time_offset_ns,
                dc.system_time_delay_ns,
                dc.time_difference_ns
            ),
            (Some(0), Some(-5), Some(0), Some(-7))
        );
    }

    #[test]
    fn a_narrow_read_gives_the_low_word_and_the_sign() {
        let dc = DcRegisters::covered(0x0910, &[1, 0, 0, 0], true).unwrap();
        assert_eq!(dc.system_time, Some(1));
        assert_eq!(time_difference(0x0000_0005), 5);
        assert_eq!(time_difference(0x8000_0005), -5);
        assert_eq!(time_difference(0xFFFF_FFFF), -0x7FFF_FFFF);
        let cycles = DcRegisters::covered(0x09A0, &[0x40, 0x42, 0x0f, 0, 0, 0, 0, 0], false);
        assert_eq!(cycles.unwrap().sync0_cycle_ns, Some(1_000_000));
        assert_eq!(cycles.unwrap().sync1_cycle_ns, Some(0));
        assert_eq!(DcRegisters::covered(0x0981, &[], true), None);
    }
}
