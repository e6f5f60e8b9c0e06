//! CANopen messages from and to any [`embedded_can::Frame`] (feature
//! `embedded-can`).
//!
//! The methods live on the crate's types:
//! [`CanOpenMessage::from_frame`] and [`CanOpenMessage::to_frame`] for every
//! kind, and `to_frame` on [`Emcy`], [`Heartbeat`], [`GuardAnswer`] and
//! [`NmtNodeControl`] for the messages a node or master sends. Reading
//! classifies the identifier and decodes the data as
//! [`CanOpenMessage::decode`] does; writing builds the frame with
//! [`Frame::new`] or [`Frame::new_remote`] and returns `None` where they do.

use embedded_can::{ExtendedId, Frame, Id, StandardId};

use crate::canopen::{
    CanOpenMessage, CanPayload, Emcy, GuardAnswer, Heartbeat, NmtNodeControl, NodeId,
};
use crate::error::Result;

impl CanOpenMessage {
    /// Read any `embedded_can` frame as CANopen (CiA 301 §7.3.5 Table 72;
    /// SPEC §6.1).
    ///
    /// A standard frame is decoded as [`CanOpenMessage::decode`] does, with
    /// its codec's error for data it refuses. A frame with a 29-bit
    /// identifier is not CANopen: it is returned as
    /// [`CanOpenMessage::Extended`], data kept. A frame type that reports
    /// more than 8 data bytes, or a remote frame's DLC above 8, is an
    /// [`Error::OutOfRange`](crate::Error::OutOfRange); nothing panics.
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
    pub fn from_frame<F: Frame>(frame: &F) -> Result<Self> {
        let payload = if frame.is_remote_frame() {
            CanPayload::remote(frame.dlc())?
        } else {
            CanPayload::data(frame.data())?
        };
        match frame.id() {
            Id::Standard(id) => Self::decode(id.as_raw(), payload),
            Id::Extended(id) => Ok(CanOpenMessage::Extended {
                id: id.as_raw(),
                payload,
            }),
        }
    }

    /// Write the message into a frame of type `F`: its identifier
    /// ([`CanOpenMessage::cob_id`], or the 29-bit id of an
    /// [`Extended`](CanOpenMessage::Extended) frame) and its
    /// [`payload`](CanOpenMessage::payload).
    ///
    /// `None` when the fields make no identifier (a PDO number outside
    /// 1..=4, an identifier out of range) or when `F::new` / `F::new_remote`
    /// refuses, as [`Frame::new`] does.
    ///
    /// ```
    /// # use embedded_can::{Frame, Id, StandardId};
    /// # struct MyFrame { id: Id, remote: bool, dlc: usize, data: [u8; 8] }
    /// # impl Frame for MyFrame {
    /// #     fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
    /// #         let mut bytes = [0; 8];
    /// #         bytes.get_mut(..data.len())?.copy_from_slice(data);
    /// #         Some(MyFrame { id: id.into(), remote: false, dlc: data.len(), data: bytes })
    /// #     }
    /// #     fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
    /// #         (dlc <= 8).then(|| MyFrame { id: id.into(), remote: true, dlc, data: [0; 8] })
    /// #     }
    /// #     fn is_extended(&self) -> bool { matches!(self.id, Id::Extended(_)) }
    /// #     fn is_remote_frame(&self) -> bool { self.remote }
    /// #     fn id(&self) -> Id { self.id }
    /// #     fn dlc(&self) -> usize { self.dlc }
    /// #     fn data(&self) -> &[u8] { if self.remote { &[] } else { &self.data[..self.dlc] } }
    /// # }
    /// use motionwire::canopen::{CanOpenMessage, NodeId};
    ///
    /// // The NMT master's node-guarding request: a remote frame on 0x705.
    /// let request = CanOpenMessage::GuardRequest { node: NodeId::new(5).unwrap() };
    /// let frame: MyFrame = request.to_frame().unwrap();
    /// assert_eq!(frame.id(), Id::Standard(StandardId::new(0x705).unwrap()));
    /// assert!(frame.is_remote_frame());
    /// assert_eq!(frame.dlc(), 1);
    /// assert_eq!(CanOpenMessage::from_frame(&frame), Ok(request));
    /// ```
    pub fn to_frame<F: Frame>(&self) -> Option<F> {
        let id = match *self {
            CanOpenMessage::Extended { id, .. } => Id::Extended(ExtendedId::new(id)?),
            _ => Id::Standard(StandardId::new(self.cob_id()?)?),
        };
        match self.payload() {
            CanPayload::Data(data) => F::new(id, data.as_slice()),
            CanPayload::Remote(dlc) => F::new_remote(id, usize::from(dlc.get())),
        }
    }
}

impl Emcy {
    /// Write the EMCY of `node` into a frame: COB-ID 0x080 + node-ID, the 8
    /// data bytes (CiA 301 §7.2.7.3; SPEC §2.1). `None` when `F::new`
    /// refuses, as [`Frame::new`] does.
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        F::new(StandardId::new(node.emcy_cob_id())?, &self.to_bytes())
    }
}

impl Heartbeat {
    /// Write the heartbeat (or boot-up message) of `node` into a frame:
    /// COB-ID 0x700 + node-ID, 1 data byte (CiA 301 §7.2.8.3.2.2;
    /// SPEC §2.7). `None` when `F::new` refuses, as [`Frame::new`] does.
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        F::new(
            StandardId::new(node.error_control_cob_id())?,
            &self.to_bytes(),
        )
    }
}

impl GuardAnswer {
    /// Write `node`'s node-guarding answer into a frame: COB-ID 0x700 +
    /// node-ID, 1 data byte with the toggle in bit 7 (CiA 301
    /// §7.2.8.3.2.1; SPEC §2.7). `None` when `F::new` refuses, as
    /// [`Frame::new`] does.
    pub fn to_frame<F: Frame>(&self, node: NodeId) -> Option<F> {
        F::new(
            StandardId::new(node.error_control_cob_id())?,
            &self.to_bytes(),
        )
    }
}

impl NmtNodeControl {
    /// Write the NMT node-control message into a frame: COB-ID 0x000, 2
    /// data bytes (CiA 301 §7.2.8.3.1). `None` when `F::new` refuses, as
    /// [`Frame::new`] does.
    pub fn to_frame<F: Frame>(&self) -> Option<F> {
        F::new(StandardId::ZERO, &self.to_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::{
        CanData, ErrorCode, ErrorRegister, NmtCommand, NmtState, PdoDirection, MAX_EXTENDED_ID,
    };
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

    /// A frame type of a driver that breaks the trait's promise of at most 8
    /// bytes (e.g. one that also carries CAN FD frames).
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

    /// A frame type that carries no data at all: every `new` fails.
    struct RemoteOnlyFrame;

    impl Frame for RemoteOnlyFrame {
        fn new(_: impl Into<Id>, _: &[u8]) -> Option<Self> {
            None
        }

        fn new_remote(_: impl Into<Id>, _: usize) -> Option<Self> {
            Some(RemoteOnlyFrame)
        }

        fn is_extended(&self) -> bool {
            false
        }

        fn is_remote_frame(&self) -> bool {
            true
        }

        fn id(&self) -> Id {
            Id::Standard(StandardId::ZERO)
        }

        fn dlc(&self) -> usize {
            0
        }

        fn data(&self) -> &[u8] {
            &[]
        }
    }

    fn n(raw: u8) -> NodeId {
        NodeId::new(raw).unwrap()
    }

    fn standard(raw: u16) -> Id {
        Id::Standard(StandardId::new(raw).unwrap())
    }

    fn data_frame(id: u16, data: &[u8]) -> TestFrame {
        TestFrame::new(standard(id), data).unwrap()
    }

    fn remote_frame(id: u16, dlc: usize) -> TestFrame {
        TestFrame::new_remote(standard(id), dlc).unwrap()
    }

    /// The AKD EMCY of seed 000 (SPEC §2.1): code 0x8130, register 0x11, axis 1.
    static EMCY_BYTES: [u8; 8] = [0x30, 0x81, 0x11, 0x01, 0x00, 0x00, 0x00, 0x00];

    #[test]
    fn reads_every_kind() {
        let emcy = Emcy::from_bytes(&EMCY_BYTES);
        let cases = [
            (
                data_frame(0x081, &EMCY_BYTES),
                CanOpenMessage::Emcy { node: n(1), emcy },
            ),
            (
                data_frame(0x705, &[0x05]),
                CanOpenMessage::Heartbeat {
                    node: n(5),
                    heartbeat: Heartbeat::new(NmtState::Operational),
                },
            ),
            (
                data_frame(0x77F, &[0x00]),
                CanOpenMessage::Heartbeat {
                    node: n(127),
                    heartbeat: Heartbeat::boot_up(),
                },
            ),
            (
                remote_frame(0x705, 1),
                CanOpenMessage::GuardRequest { node: n(5) },
            ),
            (
                data_frame(0x080, &[]),
                CanOpenMessage::Sync { counter: None },
            ),
            (
                data_frame(0x000, &[0x01, 0x00]),
                CanOpenMessage::NmtNodeControl(NmtNodeControl::new(
                    NmtCommand::StartRemoteNode,
                    None,
                )),
            ),
            (
                data_frame(0x201, &[1, 2, 3]),
                CanOpenMessage::Pdo {
                    node: n(1),
                    number: 1,
                    direction: PdoDirection::Receive,
                    data: CanData::new(&[1, 2, 3]).unwrap(),
                },
            ),
            (
                data_frame(0x581, &[0x60, 0, 0x10, 0, 0, 0, 0, 0]),
                CanOpenMessage::SdoResponse {
                    node: n(1),
                    data: CanData::new(&[0x60, 0, 0x10, 0, 0, 0, 0, 0]).unwrap(),
                },
            ),
            (
                data_frame(0x7E5, &[0x04]),
                CanOpenMessage::Other {
                    cob_id: 0x7E5,
                    payload: CanPayload::data(&[0x04]).unwrap(),
                },
            ),
        ];
        for (frame, expected) in cases {
            assert_eq!(
                CanOpenMessage::from_frame(&frame),
                Ok(expected),
                "{frame:?}"
            );
            assert_eq!(
                expected.to_frame::<TestFrame>(),
                Some(frame),
                "{expected:?}"
            );
        }
    }

    #[test]
    fn an_extended_frame_is_not_canopen() {
        let id = ExtendedId::new(0x18FF_0081).unwrap();
        let frame = TestFrame::new(id, &EMCY_BYTES).unwrap();
        let expected = CanOpenMessage::Extended {
            id: 0x18FF_0081,
            payload: CanPayload::data(&EMCY_BYTES).unwrap(),
        };
        assert_eq!(CanOpenMessage::from_frame(&frame), Ok(expected));
        assert_eq!(expected.name(), "other");
        assert_eq!(expected.to_frame::<TestFrame>(), Some(frame));

        // Even with a CANopen-looking low 11 bits and RTR.
        let request = TestFrame::new_remote(ExtendedId::new(0x705).unwrap(), 1).unwrap();
        assert_eq!(
            CanOpenMessage::from_frame(&request),
            Ok(CanOpenMessage::Extended {
                id: 0x705,
                payload: CanPayload::remote(1).unwrap(),
            })
        );
    }

    #[test]
    fn short_and_invalid_data_are_the_codecs_errors() {
        assert_eq!(
            CanOpenMessage::from_frame(&data_frame(0x081, &EMCY_BYTES[..4])),
            Err(Error::Length {
                what: "EMCY frame",
                expected: 8,
                found: 4,
            })
        );
        assert_eq!(
            CanOpenMessage::from_frame(&data_frame(0x705, &[])),
            Err(Error::Length {
                what: "heartbeat message",
                expected: 1,
                found: 0,
            })
        );
        assert_eq!(
            CanOpenMessage::from_frame(&data_frame(0x705, &[0x12])),
            Err(Error::InvalidValue {
                what: "NMT state",
                found: 0x12,
                expected: "0x00, 0x04, 0x05, 0x7f",
            })
        );
    }

    #[test]
    fn a_frame_type_breaking_the_8_byte_promise_is_refused() {
        assert_eq!(
            CanOpenMessage::from_frame(&LongFrame([0; 12])),
            Err(Error::OutOfRange {
                what: "CAN data length",
                found: 12,
                min: 0,
                max: 8,
            })
        );
        let long_remote = TestFrame {
            id: standard(0x705),
            remote: true,
            dlc: 15,
            data: [0; 8],
        };
        assert_eq!(
            CanOpenMessage::from_frame(&long_remote),
            Err(Error::OutOfRange {
                what: "CAN remote frame DLC",
                found: 15,
                min: 0,
                max: 8,
            })
        );
    }

    #[test]
    fn values_write_their_frames() {
        let node = n(0x22);
        let emcy = Emcy::new(ErrorCode::new(0x4310), ErrorRegister::TEMPERATURE, [0; 5]);
        assert_eq!(
            emcy.to_frame::<TestFrame>(node),
            Some(data_frame(0x0A2, &emcy.to_bytes()))
        );
        assert_eq!(
            Heartbeat::new(NmtState::PreOperational).to_frame::<TestFrame>(node),
            Some(data_frame(0x722, &[0x7F]))
        );
        assert_eq!(
            GuardAnswer::new(true, NmtState::Operational).to_frame::<TestFrame>(node),
            Some(data_frame(0x722, &[0x85]))
        );
        assert_eq!(
            NmtNodeControl::new(NmtCommand::ResetCommunication, Some(node)).to_frame::<TestFrame>(),
            Some(data_frame(0x000, &[0x82, 0x22]))
        );
    }

    #[test]
    fn a_frame_type_that_refuses_gives_none() {
        let node = n(1);
        assert!(Emcy::reset(ErrorRegister::empty())
            .to_frame::<RemoteOnlyFrame>(node)
            .is_none());
        assert!(Heartbeat::boot_up()
            .to_frame::<RemoteOnlyFrame>(node)
            .is_none());
        assert!(CanOpenMessage::Sync { counter: None }
            .to_frame::<RemoteOnlyFrame>()
            .is_none());
        assert!(CanOpenMessage::GuardRequest { node }
            .to_frame::<RemoteOnlyFrame>()
            .is_some());
    }

    #[test]
    fn fields_without_an_identifier_give_none() {
        let no_pdo = CanOpenMessage::Pdo {
            node: n(1),
            number: 0,
            direction: PdoDirection::Transmit,
            data: CanData::EMPTY,
        };
        assert_eq!(no_pdo.to_frame::<TestFrame>(), None);
        let too_wide = CanOpenMessage::Extended {
            id: MAX_EXTENDED_ID + 1,
            payload: CanPayload::data(&[]).unwrap(),
        };
        assert_eq!(too_wide.to_frame::<TestFrame>(), None);
        let not_standard = CanOpenMessage::Other {
            cob_id: 0x800,
            payload: CanPayload::data(&[]).unwrap(),
        };
        assert_eq!(not_standard.to_frame::<TestFrame>(), None);
    }

    mod proptests {
        use proptest::prelude::*;

        use super::*;
        use crate::test_gens::can::{can_payload, canopen_message};

        proptest! {
            #[test]
            fn message_frame_message(message in canopen_message()) {
                let frame: TestFrame = message.to_frame().expect("generated messages have a frame");
                prop_assert_eq!(CanOpenMessage::from_frame(&frame), Ok(message));
            }

            #[test]
            fn any_frame_never_panics(
                raw_id in any::<u32>(),
                extended in any::<bool>(),
                payload in can_payload(),
            ) {
                let id = if extended {
                    Id::Extended(ExtendedId::new(raw_id & MAX_EXTENDED_ID).unwrap())
                } else {
                    standard((raw_id & 0x7FF) as u16)
                };
                let frame = match payload {
                    CanPayload::Data(data) => TestFrame::new(id, data.as_slice()),
                    CanPayload::Remote(dlc) => TestFrame::new_remote(id, usize::from(dlc.get())),
                }
                .unwrap();
                match CanOpenMessage::from_frame(&frame) {
                    Ok(CanOpenMessage::Extended { payload: read, .. }) => {
                        prop_assert!(extended);
                        prop_assert_eq!(read, payload);
                    }
                    Ok(message) => {
                        prop_assert!(!extended);
                        prop_assert_eq!(message.cob_id(), Some((raw_id & 0x7FF) as u16));
                    }
                    Err(_) => prop_assert!(!extended && !payload.is_remote()),
                }
            }
        }
    }
}
