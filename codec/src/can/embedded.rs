//! The crate's [`CanFrame`] as an [`embedded_can::Frame`] (feature
//! `embedded-can`).
//!
//! - [`CanFrame`] implements [`embedded_can::Frame`]: a driver generic over
//!   that trait sends and receives the crate's frames directly.
//! - [`CanFrame::from_embedded`] copies any driver's frame into the crate's
//!   frame; [`CanFrame::to_embedded`] writes one back.
//!
//! The protocols above build on these two: CANopen reads and writes its
//! messages in any driver's frame type through them (in `canopen`, which
//! this layer does not know).

use embedded_can::{ExtendedId, Frame, Id, StandardId};

use super::{CanFrame, CanId, FrameType, CLASSIC_MAX_LEN};
use crate::{RangeError, Result};

impl From<CanId> for Id {
    fn from(id: CanId) -> Self {
        // Both constructors accept what `CanId` holds; the fallbacks are
        // never taken.
        if id.is_extended() {
            Id::Extended(ExtendedId::new(id.raw()).unwrap_or(ExtendedId::ZERO))
        } else {
            Id::Standard(StandardId::new(id.raw() as u16).unwrap_or(StandardId::ZERO))
        }
    }
}

impl From<Id> for CanId {
    fn from(id: Id) -> Self {
        // `StandardId` and `ExtendedId` hold at most 11 and 29 bits.
        match id {
            Id::Standard(id) => CanId::masked(u32::from(id.as_raw()), false),
            Id::Extended(id) => CanId::masked(id.as_raw(), true),
        }
    }
}

impl Frame for CanFrame {
    /// A classic data frame; `None` above 8 bytes.
    fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
        CanFrame::new(id.into().into(), data).ok()
    }

    /// A remote request; `None` for a DLC above 8.
    fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
        CanFrame::new_remote(id.into().into(), u8::try_from(dlc).ok()?).ok()
    }

    fn is_extended(&self) -> bool {
        self.id().is_extended()
    }

    fn is_remote_frame(&self) -> bool {
        self.is_rtr()
    }

    /// The identifier; for an error frame, its error classes as an
    /// extended identifier.
    fn id(&self) -> Id {
        CanFrame::id(self).into()
    }

    fn dlc(&self) -> usize {
        usize::from(CanFrame::dlc(self))
    }

    fn data(&self) -> &[u8] {
        CanFrame::data(self)
    }
}

impl CanFrame {
    /// Copy any driver's frame into the crate's frame: a remote frame stays
    /// one, a data frame of up to 8 bytes is a classic frame; a frame type
    /// that reports more than 8 data bytes (a driver that also carries
    /// CAN FD) is read as a CAN FD frame without flags. A DLC above 8 on a
    /// remote frame is a [`RangeError`]; nothing panics.
    pub fn from_embedded<F: Frame>(frame: &F) -> Result<Self, RangeError> {
        let id = CanId::from(frame.id());
        if frame.is_remote_frame() {
            let dlc = u8::try_from(frame.dlc()).unwrap_or(u8::MAX);
            return CanFrame::new_remote(id, dlc);
        }
        let data = frame.data();
        if data.len() > CLASSIC_MAX_LEN {
            CanFrame::new_fd(id, super::FdFlags::EMPTY, data)
        } else {
            CanFrame::new(id, data)
        }
    }

    /// Write the frame into a driver's frame type with [`Frame::new`] or
    /// [`Frame::new_remote`]; `None` where they refuse, and for an error
    /// frame, which a driver reports but does not send.
    #[must_use]
    pub fn to_embedded<F: Frame>(&self) -> Option<F> {
        let id = Id::from(CanFrame::id(self));
        match self.frame_type() {
            FrameType::Remote { dlc } => F::new_remote(id, usize::from(dlc)),
            FrameType::Error => None,
            FrameType::Data | FrameType::Fd(_) => F::new(id, CanFrame::data(self)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strategies::embedded_can::{BadRemote, LongFrame, TestFrame};

    #[test]
    fn ids_convert_both_ways() {
        let std = CanId::standard(0x7FF).unwrap();
        let ext = CanId::extended(0x1FFF_FFFF).unwrap();
        assert_eq!(Id::from(std), Id::Standard(StandardId::MAX));
        assert_eq!(Id::from(ext), Id::Extended(ExtendedId::MAX));
        assert_eq!(CanId::from(Id::from(std)), std);
        assert_eq!(CanId::from(Id::from(ext)), ext);
    }

    #[test]
    fn the_crate_frame_is_an_embedded_can_frame() {
        let id = StandardId::new(0x123).unwrap();
        let frame = <CanFrame as Frame>::new(id, &[1, 2, 3]).unwrap();
        assert_eq!(
            (Frame::dlc(&frame), Frame::data(&frame)),
            (3, &[1, 2, 3][..])
        );
        assert!(<CanFrame as Frame>::new(id, &[0; 9]).is_none());
        let remote = <CanFrame as Frame>::new_remote(id, 8).unwrap();
        assert!(remote.is_remote_frame() && Frame::data(&remote).is_empty());
        assert!(<CanFrame as Frame>::new_remote(id, 9).is_none());
        let error = CanFrame::new_error(0x40, &[0; 8]).unwrap();
        assert!(error.to_embedded::<TestFrame>().is_none());
    }

    #[test]
    fn long_driver_frames_are_read_as_fd() {
        let frame = CanFrame::from_embedded(&LongFrame([7; 12])).unwrap();
        assert!(frame.is_fd());
        assert_eq!(frame.data(), [7; 12]);
    }

    #[test]
    fn impossible_remote_dlc_is_an_error() {
        let e = CanFrame::from_embedded(&BadRemote).unwrap_err();
        assert!(matches!(e, RangeError { found: 255, .. }));
    }

    mod proptests {
        use proptest::prelude::*;

        use super::*;
        use crate::strategies::can::any_can_frame;

        proptest! {
            #[test]
            fn crate_frames_survive_a_driver_frame(frame in any_can_frame()) {
                match frame.to_embedded::<TestFrame>() {
                    Some(driver) => {
                        let back = CanFrame::from_embedded(&driver).unwrap();
                        prop_assert_eq!(back.id(), frame.id());
                        prop_assert_eq!(back.data(), frame.data());
                        prop_assert_eq!(back.is_rtr(), frame.is_rtr());
                    }
                    None => prop_assert!(frame.is_error() || frame.data().len() > 8),
                }
            }
        }
    }
}
