//! Driver frame types for the `embedded-can` tests of `can` and
//! `canopen`: what a CAN driver's HAL would hand over as an
//! `embedded_can::Frame`.

use embedded_can::{Frame, Id, StandardId};

/// A classic CAN frame as a driver would give it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TestFrame {
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
#[derive(Debug, Clone, Copy)]
pub struct LongFrame(pub [u8; 12]);

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
#[derive(Debug, Clone, Copy)]
pub struct BadRemote;

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
