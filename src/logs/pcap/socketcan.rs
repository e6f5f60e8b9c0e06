//! The payload of a `LINKTYPE_CAN_SOCKETCAN` (227) packet: Linux's
//! `struct can_frame` / `struct canfd_frame` with the identifier word in
//! network byte order (docs/formats.md#pcap; the tcpdump.org link-type page;
//! `linux/can.h`).
//!
//! ```text
//! 0..4  CAN ID and flags, big-endian: EFF 0x80000000, RTR 0x40000000,
//!       ERR 0x20000000, identifier in the low 29 (EFF) or 11 bits
//! 4     payload length (CAN XL: a flags byte with CANXL_XLF 0x80)
//! 5     CAN FD flags: BRS 0x01, ESI 0x02, FDF 0x04
//! 6     reserved
//! 7     len8_dlc (classic frames) / reserved
//! 8..   data
//! ```
//!
//! **Classic or CAN FD.** Wireshark's `packet-socketcan.c` (tshark 4.0)
//! reads a packet as CAN FD when the FDF flag is set, no unknown bit is set
//! in the flags byte and the two bytes after it are zero (older captures
//! left junk there). A capture from a libpcap that predates the FDF flag
//! holds CAN FD frames without it, but always as the whole 72-byte
//! `struct canfd_frame` (`CANFD_MTU`), where a classic frame is 16 bytes
//! (`CAN_MTU`): such a packet is CAN FD too (tshark 4.0 shows a 72-byte
//! packet without FDF as classic CAN).
//!
//! **CAN XL** (`CANXL_XLF` in byte 4, which a classic or FD length, at most
//! 64, never sets) cannot be held by [`CanFrame`]: the packet is counted
//! with the records of other link types, never misread as CAN or CAN FD.

use crate::can::{CanFrame, CanId, FdFlags, FrameType, CLASSIC_MAX_LEN, FD_MAX_LEN};
use crate::logs::BinaryError;

/// The frame header: identifier word, length, flags, two reserved bytes.
pub(super) const HEADER_LEN: usize = 8;
/// The captured length of a classic frame, `sizeof(struct can_frame)`.
pub(super) const CAN_MTU: usize = 16;
/// The captured length of a CAN FD frame, `sizeof(struct canfd_frame)`.
pub(super) const CANFD_MTU: usize = 72;

/// Extended frame format (`CAN_EFF_FLAG`).
pub(super) const EFF_FLAG: u32 = 0x8000_0000;
/// Remote transmission request (`CAN_RTR_FLAG`).
pub(super) const RTR_FLAG: u32 = 0x4000_0000;
/// Error frame (`CAN_ERR_FLAG`).
pub(super) const ERR_FLAG: u32 = 0x2000_0000;
/// The identifier bits of an extended frame (`CAN_EFF_MASK`), also the
/// error classes of an error frame.
const EFF_MASK: u32 = 0x1FFF_FFFF;
/// The identifier bits of a standard frame (`CAN_SFF_MASK`).
const SFF_MASK: u32 = 0x7FF;
/// CAN FD frame marker in the flags byte (`CANFD_FDF`).
const FDF: u8 = 0x04;
/// The flags byte's known bits: BRS, ESI, FDF.
const FD_KNOWN: u8 = 0x07;
/// CAN XL frame marker in byte 4 (`CANXL_XLF`).
const XLF: u8 = 0x80;

/// How a packet lays out its frame: the identifier word's byte order and
/// how CAN FD is told from classic CAN.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum FrameLayout {
    /// `LINKTYPE_CAN_SOCKETCAN` (227): the identifier word big-endian, CAN
    /// FD by Wireshark's rule (FDF, or the whole `canfd_frame`).
    LinkType227,
    /// After a Linux cooked header (link types 113, 276): the identifier
    /// word in the capturing machine's byte order, read little-endian as
    /// tshark does (the decision in docs/formats.md#pcap); CAN FD when the
    /// protocol says so (`ETH_P_CANFD`), classic when it says `ETH_P_CAN`.
    Cooked {
        /// The protocol is `ETH_P_CANFD`.
        fd: bool,
    },
}

/// What a SocketCAN packet holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Payload {
    /// A classic, remote, CAN FD or error frame.
    Frame(CanFrame),
    /// A packet the crate's frame cannot hold: a CAN XL frame (and, in the
    /// reader, a packet of another link type). Counted, not an error.
    NotCan,
}

/// Decode one packet laid out as `layout` says; the error says what is
/// wrong with it.
#[inline]
pub(super) fn decode(packet: &[u8], layout: FrameLayout) -> Result<Payload, BinaryError> {
    let Some(header) = packet.first_chunk::<HEADER_LEN>() else {
        return Err(too_short(HEADER_LEN, packet.len()));
    };
    let [i0, i1, i2, i3, len, flags, res0, res1] = *header;
    if len & XLF != 0 {
        return Ok(Payload::NotCan);
    }
    let (word, fd) = match layout {
        FrameLayout::LinkType227 => {
            let marked_fd = flags & FDF != 0 && flags & !FD_KNOWN == 0 && res0 == 0 && res1 == 0;
            (
                u32::from_be_bytes([i0, i1, i2, i3]),
                marked_fd || packet.len() == CANFD_MTU,
            )
        }
        FrameLayout::Cooked { fd } => (u32::from_le_bytes([i0, i1, i2, i3]), fd),
    };
    let max = if fd { FD_MAX_LEN } else { CLASSIC_MAX_LEN };
    if usize::from(len) > max {
        return Err(BinaryError::CanDataTooLong {
            len,
            max: max as u8,
        });
    }
    let id = if word & EFF_FLAG != 0 {
        CanId::masked(word & EFF_MASK, true)
    } else {
        CanId::masked(word & SFF_MASK, false)
    };
    let (id, frame_type, data_len) = if fd {
        let flags = FdFlags::new(flags & 0x0F).unwrap_or_default();
        (id, FrameType::Fd(flags), len)
    } else if word & ERR_FLAG != 0 {
        (CanId::masked(word & EFF_MASK, true), FrameType::Error, len)
    } else if word & RTR_FLAG != 0 {
        (id, FrameType::Remote { dlc: len }, 0)
    } else {
        (id, FrameType::Data, len)
    };
    let end = HEADER_LEN + usize::from(data_len);
    let Some(data) = packet.get(HEADER_LEN..end) else {
        return Err(too_short(end, packet.len()));
    };
    let mut bytes = [0; FD_MAX_LEN];
    if let Some(head) = bytes.get_mut(..data.len()) {
        head.copy_from_slice(data);
    }
    // Checked above: the identifier is masked to its kind, an error frame's
    // is extended, the length is at most the kind's (a remote request's
    // DLC at most 8, with no data).
    Ok(Payload::Frame(CanFrame::from_array(
        id, frame_type, bytes, data_len,
    )))
}

/// [`decode`] of a `LINKTYPE_CAN_SOCKETCAN` packet of exactly [`CAN_MTU`]
/// bytes, a capture's usual packet, when it holds a classic data frame:
/// the frame [`decode`] makes of it, read without the general path's
/// slicing and variable-length copy. `None` for any other packet (CAN FD,
/// CAN XL, remote or error frame, a length above 8), which [`decode`]
/// reads.
#[inline]
pub(super) fn classic_data(packet: &[u8; CAN_MTU]) -> Option<CanFrame> {
    let (header, data) = packet.split_at(HEADER_LEN);
    let [i0, i1, i2, i3, len, flags, res0, res1] = *header.first_chunk::<HEADER_LEN>()?;
    let marked_fd = flags & FDF != 0 && flags & !FD_KNOWN == 0 && res0 == 0 && res1 == 0;
    // A length above 8 also covers CANXL_XLF.
    if usize::from(len) > CLASSIC_MAX_LEN || marked_fd {
        return None;
    }
    let word = u32::from_be_bytes([i0, i1, i2, i3]);
    if word & (ERR_FLAG | RTR_FLAG) != 0 {
        return None;
    }
    let id = if word & EFF_FLAG != 0 {
        CanId::masked(word & EFF_MASK, true)
    } else {
        CanId::masked(word & SFF_MASK, false)
    };
    // The 8 bytes after the header with those past the length cleared:
    // `len` is 0..=8, so the shift is 0..=64 (64: no byte kept).
    let raw = u64::from_le_bytes(*data.first_chunk::<CLASSIC_MAX_LEN>()?);
    let keep = u64::MAX.checked_shr(64 - 8 * u32::from(len)).unwrap_or(0);
    let mut bytes = [0; FD_MAX_LEN];
    if let Some(head) = bytes.first_chunk_mut::<CLASSIC_MAX_LEN>() {
        *head = (raw & keep).to_le_bytes();
    }
    // As in `decode`: the identifier masked to its kind, the length at
    // most 8, the bytes past it zero.
    Some(CanFrame::from_array(id, FrameType::Data, bytes, len))
}

/// [`decode`] of a `LINKTYPE_CAN_SOCKETCAN` packet of exactly
/// [`CANFD_MTU`] bytes (always CAN FD) whose length is at most 64: the
/// frame [`decode`] makes of it, read without the general path's slicing.
/// `None` for a longer length or CAN XL, which [`decode`] reads.
#[inline]
pub(super) fn fd_data(packet: &[u8; CANFD_MTU]) -> Option<CanFrame> {
    let (header, data) = packet.split_at(HEADER_LEN);
    let [i0, i1, i2, i3, len, flags, _, _] = *header.first_chunk::<HEADER_LEN>()?;
    // A length above 64 also covers CANXL_XLF.
    let n = usize::from(len);
    if n > FD_MAX_LEN {
        return None;
    }
    let word = u32::from_be_bytes([i0, i1, i2, i3]);
    let id = if word & EFF_FLAG != 0 {
        CanId::masked(word & EFF_MASK, true)
    } else {
        CanId::masked(word & SFF_MASK, false)
    };
    let flags = FdFlags::new(flags & 0x0F).unwrap_or_default();
    let mut bytes = [0; FD_MAX_LEN];
    if let (Some(head), Some(data)) = (bytes.get_mut(..n), data.get(..n)) {
        head.copy_from_slice(data);
    }
    Some(CanFrame::from_array(id, FrameType::Fd(flags), bytes, len))
}

fn too_short(needed: usize, found: usize) -> BinaryError {
    BinaryError::SocketCanTooShort {
        needed: needed as u64,
        found: found as u64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn packet(word: u32, len: u8, flags: u8, data: &[u8], total: usize) -> Vec<u8> {
        let mut p = word.to_be_bytes().to_vec();
        p.extend([len, flags, 0, 0]);
        p.extend(data);
        p.resize(total.max(p.len()), 0);
        p
    }

    fn frame(p: &[u8]) -> CanFrame {
        match decode(p, FrameLayout::LinkType227) {
            Ok(Payload::Frame(f)) => f,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn classic_extended_remote_error() {
        let f = frame(&packet(0x081, 3, 0, &[1, 2, 3], CAN_MTU));
        assert_eq!(
            f,
            CanFrame::new(CanId::standard(0x81).unwrap(), &[1, 2, 3]).unwrap()
        );
        let f = frame(&packet(EFF_FLAG | 0x1234_5678, 1, 0, &[9], CAN_MTU));
        assert_eq!(f.id(), CanId::extended(0x1234_5678).unwrap());
        let f = frame(&packet(RTR_FLAG | 0x705, 1, 0, &[], CAN_MTU));
        assert_eq!(f.frame_type(), FrameType::Remote { dlc: 1 });
        assert!(f.data().is_empty());
        let f = frame(&packet(
            ERR_FLAG | 0x4,
            8,
            0,
            &[0, 4, 0, 0, 0, 0, 0, 0],
            CAN_MTU,
        ));
        assert!(f.is_error());
        assert_eq!(f.id().raw(), 0x4);
        assert_eq!(f.data(), [0, 4, 0, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn fd_by_flag_or_by_length() {
        let f = frame(&packet(0x123, 12, FDF | 0x1, &[0xAA; 12], 0));
        assert_eq!(f.frame_type(), FrameType::Fd(FdFlags::new(0x5).unwrap()));
        assert_eq!(f.data().len(), 12);
        // No FDF, but the whole canfd_frame: an old libpcap's CAN FD frame.
        let f = frame(&packet(0x123, 2, 0x2, &[1, 2], CANFD_MTU));
        assert_eq!(f.frame_type(), FrameType::Fd(FdFlags::ESI));
        // FDF with junk beside it (an old classic capture): classic.
        let mut p = packet(0x123, 2, FDF | 0x40, &[1, 2], CAN_MTU);
        assert_eq!(frame(&p).frame_type(), FrameType::Data);
        p[5] = FDF;
        p[7] = 9; // len8_dlc of a classic frame
        assert_eq!(frame(&p).frame_type(), FrameType::Data);
    }

    #[test]
    fn can_xl_is_not_misread() {
        // prio, flags (XLF|SEC), sdt, len (little-endian), af, data
        let p = [0, 0, 0x01, 0x23, 0x81, 0x03, 4, 0, 0, 0, 0, 0, 1, 2, 3, 4];
        assert_eq!(decode(&p, FrameLayout::LinkType227), Ok(Payload::NotCan));
    }

    #[test]
    fn damaged_packets() {
        assert_eq!(
            decode(&[0; 7], FrameLayout::LinkType227),
            Err(too_short(8, 7))
        );
        assert_eq!(
            decode(&packet(0x1, 8, 0, &[1, 2], 0), FrameLayout::LinkType227),
            Err(too_short(16, 10))
        );
        assert_eq!(
            decode(&packet(0x1, 9, 0, &[0; 9], 0), FrameLayout::LinkType227),
            Err(BinaryError::CanDataTooLong { len: 9, max: 8 })
        );
        assert_eq!(
            decode(&packet(0x1, 65, FDF, &[0; 65], 0), FrameLayout::LinkType227),
            Err(BinaryError::CanDataTooLong { len: 65, max: 64 })
        );
        assert_eq!(
            decode(
                &packet(RTR_FLAG | 0x1, 9, 0, &[], CAN_MTU),
                FrameLayout::LinkType227
            ),
            Err(BinaryError::CanDataTooLong { len: 9, max: 8 })
        );
    }
}
