//! A small BLF writer for the tests: the layouts the reader reads, written
//! as python-can's `BLFWriter` writes them (v1 object headers, nanosecond
//! times, `size % 4` padding), with stored or zlib containers.

use std::io::Write;

/// One object's body after its v1 header.
pub(crate) struct Object {
    pub(crate) kind: u32,
    pub(crate) nanos: u64,
    pub(crate) body: Vec<u8>,
}

/// The 144-byte file header with a start time (SYSTEMTIME, UTC).
pub(crate) fn file_header(
    year: u16,
    month: u16,
    day: u16,
    h: u16,
    m: u16,
    s: u16,
    ms: u16,
) -> Vec<u8> {
    let mut out = vec![0u8; 144];
    out[..4].copy_from_slice(b"LOGG");
    out[4..8].copy_from_slice(&144u32.to_le_bytes());
    for (i, v) in [year, month, 0, day, h, m, s, ms].into_iter().enumerate() {
        out[40 + 2 * i..42 + 2 * i].copy_from_slice(&v.to_le_bytes());
    }
    out
}

/// An object with its `LOBJ` and v1 headers, padded as python-can pads.
pub(crate) fn object(o: &Object) -> Vec<u8> {
    let size = 32 + o.body.len();
    let mut out = Vec::with_capacity(size + 4);
    out.extend_from_slice(b"LOBJ");
    out.extend_from_slice(&32u16.to_le_bytes());
    out.extend_from_slice(&1u16.to_le_bytes());
    out.extend_from_slice(&(size as u32).to_le_bytes());
    out.extend_from_slice(&o.kind.to_le_bytes());
    out.extend_from_slice(&2u32.to_le_bytes()); // nanoseconds
    out.extend_from_slice(&0u16.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out.extend_from_slice(&o.nanos.to_le_bytes());
    out.extend_from_slice(&o.body);
    out.extend(std::iter::repeat(0).take(o.body.len() % 4));
    out
}

/// A container holding `data`, zlib-compressed or stored.
pub(crate) fn container(data: &[u8], compress: bool) -> Vec<u8> {
    let (method, payload) = if compress {
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(data).unwrap();
        (2u16, z.finish().unwrap())
    } else {
        (0u16, data.to_vec())
    };
    let size = 32 + payload.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"LOBJ");
    out.extend_from_slice(&16u16.to_le_bytes());
    out.extend_from_slice(&1u16.to_le_bytes());
    out.extend_from_slice(&(size as u32).to_le_bytes());
    out.extend_from_slice(&10u32.to_le_bytes());
    out.extend_from_slice(&method.to_le_bytes());
    out.extend_from_slice(&[0; 6]);
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(&[0; 4]);
    out.extend_from_slice(&payload);
    out.extend(std::iter::repeat(0).take(size % 4));
    out
}

/// A `CAN_MESSAGE` body: channel, flags (0x80 remote, 0x01 Tx), DLC, id
/// (bit 31 extended), 8 data bytes.
pub(crate) fn can_message(channel: u16, flags: u8, dlc: u8, id: u32, data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(&channel.to_le_bytes());
    out.push(flags);
    out.push(dlc);
    out.extend_from_slice(&id.to_le_bytes());
    let mut bytes = [0u8; 8];
    bytes[..data.len().min(8)].copy_from_slice(&data[..data.len().min(8)]);
    out.extend_from_slice(&bytes);
    out
}

/// A `CAN_FD_MESSAGE` body.
pub(crate) fn can_fd_message(
    channel: u16,
    flags: u8,
    dlc: u8,
    id: u32,
    fd_flags: u8,
    data: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(&channel.to_le_bytes());
    out.push(flags);
    out.push(dlc);
    out.extend_from_slice(&id.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out.push(0);
    out.push(fd_flags);
    out.push(data.len() as u8);
    out.extend_from_slice(&[0; 5]);
    let mut bytes = [0u8; 64];
    bytes[..data.len()].copy_from_slice(data);
    out.extend_from_slice(&bytes);
    out
}
