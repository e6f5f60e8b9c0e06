//! CANopen messages from and to any driver's frame type (feature
//! `embedded-can`): a driver's `embedded_can::Frame` is copied into the
//! crate's [`CanFrame`] and decoded ([`CanOpenMessage::from_frame`]), and a
//! message is encoded into one ([`CanOpenMessage::to_frame`], and the
//! `to_frame` methods of [`Emcy`], [`Heartbeat`], [`GuardAnswer`] and
//! [`NmtNodeControl`]). The link layer's half — [`CanFrame`] as an
//! [`embedded_can::Frame`], [`CanFrame::from_embedded`] and
//! [`CanFrame::to_embedded`] — lives in [`crate::can`], which knows nothing
//! of CANopen: layers point one way.

use embedded_can::{Frame, StandardId};

use super::{
    CanOpenMessage, DecodeError, Emcy, GuardAnswer, Heartbeat, MessageKind, NmtNodeControl, NodeId,
};
use crate::can::CanFrame;

impl CanOpenMessage {
    /// Read any `embedded_can` frame as CANopen (CiA 301 §7.3.5 Table 72;
    /// docs/canopen.md#identifiers): [`CanFrame::from_embedded`], then
    /// [`CanOpenMessage::decode`].
    ///
    /// ```
    /// use embedded_can::{Frame, Id, StandardId};
    /// use motionwire_codec::canopen::{CanOpenMessage, ErrorCode, NodeId};
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
    /// # Ok::<(), motionwire_codec::Error>(())
    /// ```
    pub fn from_frame<F: Frame>(frame: &F) -> Result<Self, DecodeError> {
        let frame = CanFrame::from_embedded(frame).map_err(|error| DecodeError {
            kind: MessageKind::Other,
            node: None,
            error: error.into(),
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
    /// use motionwire_codec::can::CanFrame;
    /// use motionwire_codec::canopen::{CanOpenMessage, NodeId};
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
    /// data bytes (CiA 301 §7.2.7.3; docs/canopen.md#emcy). `None` when
    /// `F::new` refuses, as [`Frame::new`] does.
    #[must_use]
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        classic(node.emcy_cob_id(), &self.to_bytes())
    }
}

impl Heartbeat {
    /// Write the heartbeat (or boot-up message) of `node` into a frame:
    /// COB-ID 0x700 + node-ID, 1 data byte (CiA 301 §7.2.8.3.2.2;
    /// docs/canopen.md#error-control). `None` when `F::new` refuses, as
    /// [`Frame::new`] does.
    #[must_use]
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        classic(node.error_control_cob_id(), &self.to_bytes())
    }
}

impl GuardAnswer {
    /// Write `node`'s node-guarding answer into a frame: COB-ID 0x700 +
    /// node-ID, 1 data byte with the toggle in bit 7 (CiA 301 §7.2.8.3.2.1;
    /// docs/canopen.md#error-control). `None` when `F::new` refuses, as
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
    use embedded_can::Id;

    use super::*;
    use crate::canopen::{ErrorCode, ErrorRegister, NmtCommand, NmtState};
    use crate::strategies::embedded_can::{BadRemote, LongFrame, TestFrame};
    use crate::{Error, RangeError};

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
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
        assert!(matches!(
            CanOpenMessage::from_frame(&long),
            Ok(CanOpenMessage::Pdo { data, .. }) if data.as_slice() == [7; 12]
        ));
    }

    #[test]
    fn impossible_remote_dlc_is_an_error() {
        let e = CanOpenMessage::from_frame(&BadRemote).unwrap_err();
        assert!(matches!(
            e.error,
            Error::OutOfRange(RangeError { found: 255, .. })
        ));
    }

    mod proptests {
        use proptest::prelude::*;

        use super::*;
        use crate::strategies::can::canopen_message;

        proptest! {
            #[test]
            fn message_frame_message(message in canopen_message()) {
                let frame: TestFrame = message.to_frame().expect("generated messages have a frame");
                prop_assert_eq!(CanOpenMessage::from_frame(&frame), Ok(message));
            }
        }
    }
}
