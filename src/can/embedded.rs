//! The crate's [`CanFrame`] as an [`embedded_can::Frame`], and CANopen
//! messages from and to any driver's frame type (feature `embedded-can`).
//!
//! - [`CanFrame`] implements [`embedded_can::Frame`]: a driver generic over
//!   that trait sends and receives the crate's frames directly.
//! - [`CanFrame::from_embedded`] copies any driver's frame into the crate's
//!   frame; [`CanFrame::to_embedded`] writes one back.
//! - [`CanOpenMessage::from_frame`] and [`CanOpenMessage::to_frame`] go
//!   through them, as do the `to_frame` methods of [`Emcy`], [`Heartbeat`],
//!   [`GuardAnswer`] and [`NmtNodeControl`].

use embedded_can::{ExtendedId, Frame, Id, StandardId};

use super::{CanFrame, CanId, FrameType, CLASSIC_MAX_LEN};
use crate::canopen::{
    CanOpenMessage, DecodeError, Emcy, GuardAnswer, Heartbeat, MessageKind, NmtNodeControl, NodeId,
};
use crate::error::Result;

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
            Id::Standard(id) => CanId::new_unchecked(u32::from(id.as_raw()), false),
            Id::Extended(id) => CanId::new_unchecked(id.as_raw(), true),
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
    /// remote frame is an [`Error::OutOfRange`](crate::Error::OutOfRange); nothing panics.
    pub fn from_embedded<F: Frame>(frame: &F) -> Result<Self> {
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

impl CanOpenMessage {
    /// Read any `embedded_can` frame as CANopen (CiA 301 §7.3.5 Table 72;
    /// SPEC §6.1): [`CanFrame::from_embedded`], then
    /// [`CanOpenMessage::decode`].
    ///
    /// ```
    /// use embedded_can::{Frame, Id, StandardId};
    /// use motionwire::canopen::{CanOpenMessage, ErrorCode, NodeId};
    ///
    /// /// A driver's frame type; any type implementing `Frame` will do.
    /// struct MyFrame { id: Id, remote: bool, dlc: usize, data: [u8; 8] }
    ///
    /// impl Frame for MyFrame {
    ///     fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
    ///         let mut bytes = [0; 8];
    ///         bytes.get_mut(..data.len())?.copy_from_slice(data);
    ///         Some(MyFrame { id: id.into(), remote: false, dlc: data.len(), data: bytes })
    ///     }
    ///     fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
    ///         (dlc <= 8).then(|| MyFrame { id: id.into(), remote: true, dlc, data: [0; 8] })
    ///     }
    ///     fn is_extended(&self) -> bool { matches!(self.id, Id::Extended(_)) }
    ///     fn is_remote_frame(&self) -> bool { self.remote }
    ///     fn id(&self) -> Id { self.id }
    ///     fn dlc(&self) -> usize { self.dlc }
    ///     fn data(&self) -> &[u8] { if self.remote { &[] } else { &self.data[..self.dlc] } }
    /// }
    ///
    /// // An EMCY of node 1, as a driver received it.
    /// let id = StandardId::new(0x081).unwrap();
    /// let frame = MyFrame::new(id, &[0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0]).unwrap();
    /// let message = CanOpenMessage::from_frame(&frame)?;
    /// let CanOpenMessage::Emcy { node, emcy } = message else { unreachable!() };
    /// assert_eq!(node, NodeId::new(1).unwrap());
    /// assert_eq!(emcy.code, ErrorCode::new(0x8130));
    ///
    /// // The same message written back into a frame.
    /// let again: MyFrame = emcy.to_frame(node).unwrap();
    /// assert_eq!((again.id(), again.data()), (frame.id(), frame.data()));
    ///
    /// // Too short for an EMCY: an error, not a guess.
    /// let short = MyFrame::new(id, &[0x30, 0x81]).unwrap();
    /// assert!(CanOpenMessage::from_frame(&short).is_err());
    /// # Ok::<(), motionwire::Error>(())
    /// ```
    pub fn from_frame<F: Frame>(frame: &F) -> Result<Self, DecodeError> {
        let frame = CanFrame::from_embedded(frame).map_err(|error| DecodeError {
            kind: MessageKind::Other,
            node: None,
            error,
            partial_emcy: None,
        })?;
        CanOpenMessage::decode(&frame)
    }

    /// Write the message into a frame of type `F`:
    /// [`CanOpenMessage::encode`], then [`CanFrame::to_embedded`]. `None`
    /// where either gives none.
    ///
    /// ```
    /// # use embedded_can::{Frame, Id, StandardId};
    /// use motionwire::can::CanFrame;
    /// use motionwire::canopen::{CanOpenMessage, NodeId};
    ///
    /// // The NMT master's node-guarding request: a remote frame on 0x705.
    /// let request = CanOpenMessage::GuardRequest { node: NodeId::new(5).unwrap() };
    /// let frame: CanFrame = request.to_frame().unwrap();
    /// assert_eq!(Frame::id(&frame), Id::Standard(StandardId::new(0x705).unwrap()));
    /// assert!(frame.is_remote_frame());
    /// assert_eq!(Frame::dlc(&frame), 1);
    /// assert_eq!(CanOpenMessage::from_frame(&frame), Ok(request));
    /// ```
    #[must_use]
    pub fn to_frame<F: Frame>(&self) -> Option<F> {
        self.encode()?.to_embedded()
    }
}

/// Build a classic frame of `F` on the standard identifier `cob_id`.
fn classic<F: Frame>(cob_id: u16, data: &[u8]) -> Option<F> {
    F::new(StandardId::new(cob_id)?, data)
}

impl Emcy {
    /// Write the EMCY of `node` into a frame: COB-ID 0x080 + node-ID, the 8
    /// data bytes (CiA 301 §7.2.7.3; SPEC §2.1). `None` when `F::new`
    /// refuses, as [`Frame::new`] does.
    #[must_use]
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        classic(node.emcy_cob_id(), &self.to_bytes())
    }
}

impl Heartbeat {
    /// Write the heartbeat (or boot-up message) of `node` into a frame:
    /// COB-ID 0x700 + node-ID, 1 data byte (CiA 301 §7.2.8.3.2.2;
    /// SPEC §2.7). `None` when `F::new` refuses, as [`Frame::new`] does.
    #[must_use]
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        classic(node.error_control_cob_id(), &self.to_bytes())
    }
}

impl GuardAnswer {
    /// Write `node`'s node-guarding answer into a frame: COB-ID 0x700 +
    /// node-ID, 1 data byte with the toggle in bit 7 (CiA 301
    /// §7.2.8.3.2.1; SPEC §2.7). `None` when `F::new` refuses, as
    /// [`Frame::new`] does.
    #[must_use]
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        classic(node.error_control_cob_id(), &self.to_bytes())
    }
}

impl NmtNodeControl {
    /// Write the NMT node-control message into a frame: COB-ID 0x000, 2
    /// data bytes (CiA 301 §7.2.8.3.1). `None` when `F::new` refuses, as
    /// [`Frame::new`] does.
    #[must_use]
    pub fn to_frame<F: Frame>(&self) -> Option<F> {
        classic(0x000, &self.to_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::{ErrorCode, ErrorRegister, NmtCommand, NmtState};
    use crate::Error;

    /// A classic CAN frame as a driver would give it.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    struct TestFrame {
        id: Id,
        remote: bool,
        dlc: usize,
        data: [u8; 8],
    }

    impl Frame for TestFrame {
        fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
            let mut bytes = [0; 8];
            bytes.get_mut(..data.len())?.copy_from_slice(data);
            Some(TestFrame {
                id: id.into(),
                remote: false,
                dlc: data.len(),
                data: bytes,
            })
        }

        fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
            (dlc <= 8).then(|| TestFrame {
                id: id.into(),
                remote: true,
                dlc,
                data: [0; 8],
            })
        }

        fn is_extended(&self) -> bool {
            matches!(self.id, Id::Extended(_))
        }

        fn is_remote_frame(&self) -> bool {
            self.remote
        }

        fn id(&self) -> Id {
            self.id
        }

        fn dlc(&self) -> usize {
            self.dlc
        }

        fn data(&self) -> &[u8] {
            if self.remote {
                &[]
            } else {
                &self.data[..self.dlc]
            }
        }
    }

    /// A frame type of a driver that also carries CAN FD: more than the
    /// trait's 8 bytes.
    struct LongFrame([u8; 12]);

    impl Frame for LongFrame {
        fn new(_: impl Into<Id>, data: &[u8]) -> Option<Self> {
            let mut bytes = [0; 12];
            bytes.get_mut(..data.len())?.copy_from_slice(data);
            Some(LongFrame(bytes))
        }

        fn new_remote(_: impl Into<Id>, _: usize) -> Option<Self> {
            None
        }

        fn is_extended(&self) -> bool {
            false
        }

        fn is_remote_frame(&self) -> bool {
            false
        }

        fn id(&self) -> Id {
            Id::Standard(StandardId::new(0x181).unwrap())
        }

        fn dlc(&self) -> usize {
            12
        }

        fn data(&self) -> &[u8] {
            &self.0
        }
    }

    /// A remote frame type that reports a DLC the standard does not allow.
    struct BadRemote;

    impl Frame for BadRemote {
        fn new(_: impl Into<Id>, _: &[u8]) -> Option<Self> {
            None
        }

        fn new_remote(_: impl Into<Id>, _: usize) -> Option<Self> {
            Some(BadRemote)
        }

        fn is_extended(&self) -> bool {
            false
        }

        fn is_remote_frame(&self) -> bool {
            true
        }

        fn id(&self) -> Id {
            Id::Standard(StandardId::new(0x705).unwrap())
        }

        fn dlc(&self) -> usize {
            300
        }

        fn data(&self) -> &[u8] {
            &[]
        }
    }

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

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
    fn driver_frames_round_trip() {
        let emcy = Emcy::new(
            ErrorCode::new(0x8130),
            ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION,
            [1, 0, 0, 0, 0],
        );
        let sent: TestFrame = emcy.to_frame(n(1)).unwrap();
        assert_eq!(
            CanOpenMessage::from_frame(&sent),
            Ok(CanOpenMessage::Emcy { node: n(1), emcy })
        );
        let heartbeat: TestFrame = Heartbeat::new(NmtState::Operational)
            .to_frame(n(5))
            .unwrap();
        assert_eq!(heartbeat.data(), [0x05]);
        let answer: TestFrame = GuardAnswer::new(true, NmtState::Stopped)
            .to_frame(n(5))
            .unwrap();
        assert_eq!(answer.data(), [0x84]);
        let nmt: TestFrame = NmtNodeControl::new(NmtCommand::ResetNode, Some(n(9)))
            .to_frame()
            .unwrap();
        assert_eq!(
            (nmt.id(), nmt.data()),
            (Id::Standard(StandardId::ZERO), &[0x81, 9][..])
        );
    }

    #[test]
    fn long_driver_frames_are_read_as_fd() {
        let long = LongFrame([7; 12]);
        let frame = CanFrame::from_embedded(&long).unwrap();
        assert!(frame.is_fd());
        assert!(matches!(
            CanOpenMessage::from_frame(&long),
            Ok(CanOpenMessage::Pdo { data, .. }) if data.as_slice() == [7; 12]
        ));
    }

    #[test]
    fn impossible_remote_dlc_is_an_error() {
        let e = CanOpenMessage::from_frame(&BadRemote).unwrap_err();
        assert!(matches!(e.error, Error::OutOfRange { found: 255, .. }));
    }

    mod proptests {
        use proptest::prelude::*;

        use super::*;
        use crate::test_gens::can::{any_can_frame, canopen_message};

        proptest! {
            #[test]
            fn message_frame_message(message in canopen_message()) {
                let frame: TestFrame = message.to_frame().expect("generated messages have a frame");
                prop_assert_eq!(CanOpenMessage::from_frame(&frame), Ok(message));
            }

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
