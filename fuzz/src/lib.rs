//! Helpers shared by the fuzz targets.
//!
//! The state-machine targets read their input as a sequence of small
//! operations: one opcode byte followed by that operation's fixed-size
//! payload, little-endian. [`Reader`] takes the bytes off the front; a target
//! stops at the first operation whose payload is cut short. The format is
//! simple on purpose, so that the seed inputs in `corpus/` can be written by
//! hand (see `fuzz/README.md`).

/// Takes bytes off the front of a fuzz input.
#[derive(Debug, Clone)]
pub struct Reader<'a> {
    rest: &'a [u8],
}

impl<'a> Reader<'a> {
    /// Return a reader over `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Reader { rest: data }
    }

    /// Return whether every byte was taken.
    pub fn is_empty(&self) -> bool {
        self.rest.is_empty()
    }

    /// Take `N` bytes, or `None` when fewer are left.
    pub fn array<const N: usize>(&mut self) -> Option<[u8; N]> {
        let (head, rest) = self.rest.split_first_chunk::<N>()?;
        self.rest = rest;
        Some(*head)
    }

    /// Take one byte.
    pub fn u8(&mut self) -> Option<u8> {
        self.array::<1>().map(|[b]| b)
    }

    /// Take a little-endian `u16`.
    pub fn u16(&mut self) -> Option<u16> {
        self.array().map(u16::from_le_bytes)
    }

    /// Take a little-endian `u32`.
    pub fn u32(&mut self) -> Option<u32> {
        self.array().map(u32::from_le_bytes)
    }

    /// Take every byte that is left.
    pub fn rest(&mut self) -> &'a [u8] {
        core::mem::take(&mut self.rest)
    }

    /// Take a little-endian `u64`.
    pub fn u64(&mut self) -> Option<u64> {
        self.array().map(u64::from_le_bytes)
    }
}

/// One frame of the CANopen traffic the `decoder` and `report` targets
/// read from their input ([`traffic`]).
#[derive(Debug, Clone)]
pub struct TrafficFrame {
    /// The record's number, from 1 (records that make no frame count too).
    pub line: u64,
    /// Milliseconds since the start.
    pub ms: u64,
    /// The 11-bit identifier.
    pub raw: u32,
    /// The frame.
    pub frame: motionwire::can::CanFrame,
    /// `can0` or `can1`.
    pub iface: &'static str,
}

/// The frames of `input` read as records of `[header, id, bytes…]`: header
/// bits 0–3 the data length (0..=15, cut to 8 and to what is left), bit 4
/// the bus (`can0` or `can1`), bit 5 a remote frame, bits 6–7 the time
/// step (0, 1, 10 or 1000 ms); `id` picks the function (the high 3 bits:
/// NMT, SYNC/EMCY, TPDO1, RPDO1…RPDO4, SDO response, SDO request,
/// heartbeat, any 11-bit identifier) and the node (the low 5 bits, nodes
/// 1–31, 0 kept as 0). A record cut short ends the input.
pub fn traffic(input: &[u8]) -> impl Iterator<Item = TrafficFrame> + '_ {
    use motionwire::can::{CanFrame, CanId};

    let mut rest = input;
    let (mut ms, mut line) = (0u64, 0u64);
    core::iter::from_fn(move || loop {
        let (&[header, id], tail) = rest.split_first_chunk::<2>()?;
        let len = usize::from(header & 0x0F).min(8).min(tail.len());
        let (data, tail) = tail.split_at(len);
        rest = tail;
        line += 1;
        ms += [0, 1, 10, 1000][usize::from(header >> 6)];
        let node = u32::from(id & 0x1F);
        let raw = match id >> 5 {
            0 => 0x000,
            1 => 0x080 + node,
            2 => 0x180 + node,
            3 => 0x200 + node + 0x80 * (node % 4),
            4 => 0x580 + node,
            5 => 0x600 + node,
            6 => 0x700 + node,
            _ => (u32::from(id) << 3) | u32::from(header & 7),
        };
        let can_id = CanId::standard(raw).expect("at most 11 bits");
        let frame = if header & 0x20 != 0 {
            CanFrame::new_remote(can_id, len as u8)
        } else {
            CanFrame::new(can_id, data)
        };
        let Ok(frame) = frame else { continue };
        let iface = if header & 0x10 != 0 { "can1" } else { "can0" };
        return Some(TrafficFrame {
            line,
            ms,
            raw,
            frame,
            iface,
        });
    })
}
