//! The keys of a frame's record that a table of frames keeps in columns of
//! their own (the Python package's `decode`: `code`, `register`,
//! `description`, `state`; docs/output.md#json).

use crate::canopen::{CanOpenMessage, ErrorCode, ErrorRegister};

use super::Decoded;

/// What a frame's record says in the keys that a table keeps in columns of
/// their own, each `None` where the record has no such key: the EMCY's
/// `code`, `register` and `description` (docs/output.md#emcy; a truncated
/// EMCY keeps the code and register its bytes still hold, without a
/// description) and a heartbeat's `state` (docs/output.md#heartbeat).
///
/// ```
/// use motionwire::can::{CanFrame, CanId, LogFrame};
/// use motionwire::canopen::ErrorCode;
/// use motionwire::decoder::{Decoder, DecoderConfig};
/// use motionwire::logs::Position;
///
/// let mut decoder = Decoder::new(DecoderConfig::new());
/// let frame = |id: u32, data: &[u8]| {
///     LogFrame::new(CanFrame::new(CanId::standard(id).unwrap(), data).unwrap())
/// };
/// let emcy = frame(0x083, &[0x05, 0x73, 0x01, 0x11, 0, 0, 0, 0]);
/// let columns = decoder.decode(Position::Line(1), &emcy).columns();
/// assert_eq!(columns.code, Some(ErrorCode::new(0x7305)));
/// assert_eq!(columns.register.map(|r| r.bits()), Some(1));
/// assert_eq!(columns.description, Some("Incremental sensor 1 fault"));
/// assert_eq!(columns.state, None);
///
/// let boot_up = frame(0x705, &[0x00]);
/// assert_eq!(decoder.decode(Position::Line(2), &boot_up).columns().state, Some("boot_up"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct FrameColumns {
    /// The EMCY's error code (`code`), also of a truncated EMCY that has
    /// bytes 0–1.
    pub code: Option<ErrorCode>,
    /// The EMCY's error register (`register`), also of a truncated EMCY
    /// that has byte 2.
    pub register: Option<ErrorRegister>,
    /// The EMCY code's description (`description`), of a whole EMCY.
    pub description: Option<&'static str>,
    /// The state a heartbeat, boot-up or node-guarding answer names
    /// (`state`: `boot_up`, `stopped`, `operational`, `pre_operational`,
    /// `invalid`).
    pub state: Option<&'static str>,
}

impl Decoded<'_> {
    /// Return the keys of the frame's record that a table keeps in columns
    /// of their own ([`FrameColumns`]); the same values as
    /// [`write_json`](Self::write_json) writes.
    #[must_use]
    pub fn columns(&self) -> FrameColumns {
        match self.message() {
            Ok(CanOpenMessage::Emcy { emcy, .. }) => FrameColumns {
                code: Some(emcy.code),
                register: Some(emcy.register),
                description: Some(emcy.code.description()),
                state: None,
            },
            Ok(CanOpenMessage::Heartbeat { byte, .. }) => FrameColumns {
                state: Some(byte.state_name()),
                ..FrameColumns::default()
            },
            Ok(_) => FrameColumns::default(),
            Err(e) => match e.partial_emcy {
                Some(partial) => FrameColumns {
                    code: partial.code,
                    register: partial.register,
                    ..FrameColumns::default()
                },
                None => FrameColumns::default(),
            },
        }
    }
}
