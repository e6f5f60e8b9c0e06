//! A small pcap/pcapng writer for the tests: frames in, file bytes out,
//! laid out as libpcap and Wireshark write them (docs/formats.md#pcap).

use crate::can::{CanFrame, FrameType, Timestamp};

use super::socketcan::{CANFD_MTU, CAN_MTU, EFF_FLAG, ERR_FLAG, RTR_FLAG};

/// The SocketCAN packet of `frame`: classic frames as the 16-byte
/// `struct can_frame`, CAN FD as the 72-byte `struct canfd_frame` with the
/// frame's own flags (the length makes it CAN FD, FDF or not).
pub(super) fn socketcan(frame: &CanFrame) -> Vec<u8> {
    let id = frame.id();
    let mut word = id.raw() | if id.is_extended() { EFF_FLAG } else { 0 };
    let (len, flags, mtu) = match frame.frame_type() {
        FrameType::Data => (frame.data().len(), 0, CAN_MTU),
        FrameType::Remote { dlc } => {
            word |= RTR_FLAG;
            (usize::from(dlc), 0, CAN_MTU)
        }
        FrameType::Fd(flags) => (frame.data().len(), flags.bits(), CANFD_MTU),
        FrameType::Error => {
            word = id.raw() | ERR_FLAG;
            (frame.data().len(), 0, CAN_MTU)
        }
    };
    let mut p = word.to_be_bytes().to_vec();
    p.extend([len as u8, flags, 0, 0]);
    p.extend(frame.data());
    p.resize(mtu, 0);
    p
}

fn u16b(v: u16, be: bool) -> [u8; 2] {
    if be {
        v.to_be_bytes()
    } else {
        v.to_le_bytes()
    }
}

fn u32b(v: u32, be: bool) -> [u8; 4] {
    if be {
        v.to_be_bytes()
    } else {
        v.to_le_bytes()
    }
}

/// A pcap file of link type `link` holding `packets` (time, bytes).
pub(super) fn pcap(packets: &[(Timestamp, Vec<u8>)], link: u32, be: bool, nanos: bool) -> Vec<u8> {
    let magic: u32 = if nanos { 0xA1B2_3C4D } else { 0xA1B2_C3D4 };
    let mut f = Vec::new();
    f.extend(u32b(magic, be));
    f.extend(u16b(2, be));
    f.extend(u16b(4, be));
    f.extend([0; 8]);
    f.extend(u32b(262_144, be));
    f.extend(u32b(link, be));
    for (ts, data) in packets {
        let frac = if nanos {
            ts.subsec_nanos()
        } else {
            ts.micros()
        };
        f.extend(u32b(ts.secs() as u32, be));
        f.extend(u32b(frac, be));
        f.extend(u32b(data.len() as u32, be));
        f.extend(u32b(data.len() as u32, be));
        f.extend(data);
    }
    f
}

/// A pcapng interface: link type, name, `if_tsresol`, `if_tsoffset`.
#[derive(Debug, Clone)]
pub(super) struct Interface {
    pub(super) link: u16,
    pub(super) name: Option<String>,
    pub(super) tsresol: Option<u8>,
    pub(super) tsoffset: Option<i64>,
}

/// A pcapng writer of one byte order.
#[derive(Debug, Default)]
pub(super) struct Pcapng {
    pub(super) bytes: Vec<u8>,
    pub(super) be: bool,
}

impl Pcapng {
    pub(super) fn block(&mut self, kind: u32, body: &[u8]) -> &mut Self {
        let padded = body.len().div_ceil(4) * 4;
        let len = (padded + 12) as u32;
        self.bytes.extend(u32b(kind, self.be));
        self.bytes.extend(u32b(len, self.be));
        self.bytes.extend(body);
        self.bytes.resize(self.bytes.len() + padded - body.len(), 0);
        self.bytes.extend(u32b(len, self.be));
        self
    }

    fn option(&self, out: &mut Vec<u8>, code: u16, value: &[u8]) {
        out.extend(u16b(code, self.be));
        out.extend(u16b(value.len() as u16, self.be));
        out.extend(value);
        out.resize(out.len() + value.len().div_ceil(4) * 4 - value.len(), 0);
    }

    pub(super) fn section(&mut self, be: bool) -> &mut Self {
        self.be = be;
        let mut body = u32b(0x1A2B_3C4D, be).to_vec();
        body.extend(u16b(1, be));
        body.extend(u16b(0, be));
        body.extend([0xFF; 8]);
        self.block(0x0A0D_0D0A, &body)
    }

    pub(super) fn interface(&mut self, i: &Interface) -> &mut Self {
        let mut body = u16b(i.link, self.be).to_vec();
        body.extend([0, 0]);
        body.extend(u32b(0, self.be));
        if let Some(name) = &i.name {
            self.option(&mut body, 2, name.as_bytes());
        }
        if let Some(r) = i.tsresol {
            self.option(&mut body, 9, &[r]);
        }
        if let Some(o) = i.tsoffset {
            let v = if self.be {
                o.to_be_bytes()
            } else {
                o.to_le_bytes()
            };
            self.option(&mut body, 14, &v);
        }
        if body.len() > 8 {
            self.option(&mut body, 0, &[]);
        }
        self.block(1, &body)
    }

    pub(super) fn packet(&mut self, iface: u32, ticks: u64, data: &[u8]) -> &mut Self {
        let mut body = u32b(iface, self.be).to_vec();
        body.extend(u32b((ticks >> 32) as u32, self.be));
        body.extend(u32b(ticks as u32, self.be));
        body.extend(u32b(data.len() as u32, self.be));
        body.extend(u32b(data.len() as u32, self.be));
        body.extend(data);
        self.block(6, &body)
    }

    pub(super) fn simple_packet(&mut self, data: &[u8]) -> &mut Self {
        let mut body = u32b(data.len() as u32, self.be).to_vec();
        body.extend(data);
        self.block(3, &body)
    }
}
