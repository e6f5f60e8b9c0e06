//! NMT states and the two one-byte error-control messages: the heartbeat
//! (and boot-up) message and the node-guarding answer (CiA 301 §7.2.8.3;
//! docs/canopen.md#error-control).
//!
//! Both messages travel on COB-ID 0x700 + node-ID
//! ([`NodeId::error_control_cob_id`](super::NodeId::error_control_cob_id))
//! and carry one byte whose bits 0–6 are the node's NMT state. They differ in
//! bit 7: a heartbeat producer never sets it; a node-guarding answer uses it
//! as the toggle bit.
//!
//! | type | view | owned | bit 7 |
//! |---|---|---|---|
//! | heartbeat / boot-up | [`HeartbeatFrame`] | [`Heartbeat`] | reserved, 0 when produced, kept when decoded |
//! | node-guarding answer | [`GuardAnswerFrame`] | [`GuardAnswer`] | toggle |
//!
//! ```
//! use motionwire_codec::canopen::{GuardAnswer, GuardAnswerFrame, Heartbeat, NmtState};
//!
//! // A heartbeat of an operational node…
//! let heartbeat = Heartbeat::new(NmtState::Operational);
//! assert_eq!(heartbeat.to_bytes(), [0x05]);
//! assert_eq!(Heartbeat::parse(&[0x05])?, heartbeat);
//!
//! // …and a node-guarding answer with the toggle bit set.
//! let answer = GuardAnswer::new(true, NmtState::PreOperational);
//! let mut data = [0u8; 1];
//! answer.emit(&mut GuardAnswerFrame::new_unchecked(&mut data[..]));
//! assert_eq!(data, [0xFF]);
//! let frame = GuardAnswerFrame::new_checked(&data[..])?;
//! assert!(frame.toggle());
//! assert_eq!(frame.state()?, NmtState::PreOperational);
//! assert_eq!(GuardAnswer::parse(&data)?, answer);
//!
//! // An empty frame and an undefined state are errors, never panics.
//! assert!(Heartbeat::parse(&[]).is_err());
//! assert!(GuardAnswer::parse(&[0x12]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use crate::error::check_len;
use crate::{FrameError, LenError, Result, ValueError};

mod field {
    /// Byte 0: bit 7 (reserved in a heartbeat, toggle in a guarding answer)
    /// and bits 0–6 (NMT state).
    pub(super) const STATE: usize = 0;
    /// Bits 0–6 of byte 0: the NMT state.
    pub(super) const STATE_MASK: u8 = 0x7F;
    /// Bit 7 of byte 0.
    pub(super) const BIT7: u8 = 0x80;
}

/// The length of a heartbeat (and boot-up) message's data, 1 byte
/// (CiA 301 §7.2.8.3.2.2).
pub const HEARTBEAT_LEN: usize = field::STATE + 1;

/// The length of a node-guarding answer's data, 1 byte (CiA 301 §7.2.8.3.2.1).
pub const GUARD_ANSWER_LEN: usize = field::STATE + 1;

const HEARTBEAT_WHAT: What = What::HeartbeatMessage;
const GUARD_ANSWER_WHAT: What = What::NodeGuardingAnswer;

/// The state of a CANopen node's NMT state machine as it appears on the wire
/// in heartbeat, boot-up and node-guarding messages (CiA 301 §7.2.8.3.2,
/// the state values of the error-control protocols;
/// docs/canopen.md#error-control).
///
/// ```
/// use motionwire_codec::canopen::NmtState;
///
/// assert_eq!(NmtState::from_byte(0x7F)?, NmtState::PreOperational);
/// assert_eq!(NmtState::PreOperational.name(), "pre_operational");
/// assert!(NmtState::from_byte(0x12).is_err());
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum NmtState {
    /// 0x00: boot-up; sent once, when the node enters pre-operational after
    /// initialisation.
    BootUp = 0x00,
    /// 0x04: stopped.
    Stopped = 0x04,
    /// 0x05: operational.
    Operational = 0x05,
    /// 0x7F: pre-operational.
    PreOperational = 0x7F,
}

impl NmtState {
    /// Every state, in the order of their codes.
    pub const ALL: [NmtState; 4] = [
        NmtState::BootUp,
        NmtState::Stopped,
        NmtState::Operational,
        NmtState::PreOperational,
    ];

    /// Return the state coded by `byte`, or a [`ValueError`] for
    /// any byte other than 0x00, 0x04, 0x05 and 0x7F
    /// (docs/canopen.md#error-control: any other value is invalid, reported,
    /// never a panic).
    ///
    /// The whole byte is checked: strip a toggle bit first (as
    /// [`GuardAnswerFrame::state`] does).
    #[inline]
    pub const fn from_byte(byte: u8) -> Result<Self, ValueError> {
        match byte {
            0x00 => Ok(NmtState::BootUp),
            0x04 => Ok(NmtState::Stopped),
            0x05 => Ok(NmtState::Operational),
            0x7F => Ok(NmtState::PreOperational),
            found => Err(ValueError {
                what: What::NmtState,
                found: found as u32,
                expected: "0x00, 0x04, 0x05, 0x7f",
            }),
        }
    }

    /// Return the state's code on the wire (0x00, 0x04, 0x05 or 0x7F).
    #[inline]
    #[must_use]
    pub const fn to_byte(self) -> u8 {
        self as u8
    }

    /// Return the state's name as the command-line decoder writes it
    /// (docs/output.md#heartbeat, key `state`): `boot_up`, `stopped`,
    /// `operational` or `pre_operational`.
    #[inline]
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            NmtState::BootUp => "boot_up",
            NmtState::Stopped => "stopped",
            NmtState::Operational => "operational",
            NmtState::PreOperational => "pre_operational",
        }
    }
}

impl TryFrom<u8> for NmtState {
    type Error = ValueError;

    fn try_from(byte: u8) -> Result<Self, ValueError> {
        Self::from_byte(byte)
    }
}

impl From<NmtState> for u8 {
    fn from(state: NmtState) -> u8 {
        state.to_byte()
    }
}

impl fmt::Display for NmtState {
    /// Format the state as its [`NmtState::name`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A zero-copy view over a heartbeat (or boot-up) message's data
/// (CiA 301 §7.2.8.3.2.2; docs/canopen.md#error-control).
///
/// After [`HeartbeatFrame::new_checked`] (or [`HeartbeatFrame::check_len`])
/// succeeds, no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HeartbeatFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> HeartbeatFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// empty.
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        HeartbeatFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least [`HEARTBEAT_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`HEARTBEAT_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(HEARTBEAT_WHAT, self.buffer.as_ref(), HEARTBEAT_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the NMT state field (bits 0–6 of byte 0) as a number, whether
    /// or not it codes a defined state (docs/output.md#heartbeat, key
    /// `state_raw`).
    #[inline]
    pub fn state_raw(&self) -> u8 {
        self.buffer.as_ref()[field::STATE] & field::STATE_MASK
    }

    /// Return the NMT state field (bits 0–6 of byte 0), or a
    /// [`ValueError`] when it codes no defined state.
    #[inline]
    pub fn state(&self) -> Result<NmtState, ValueError> {
        NmtState::from_byte(self.state_raw())
    }

    /// Return the reserved bit 7 of byte 0; a conforming producer always
    /// sends 0 (CiA 301 §7.2.8.3.2.2). It is set in node-guarding answers,
    /// which share the COB-ID.
    #[inline]
    pub fn reserved_bit(&self) -> bool {
        self.buffer.as_ref()[field::STATE] & field::BIT7 != 0
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> HeartbeatFrame<T> {
    /// Set the NMT state field (bits 0–6 of byte 0) and clear the reserved
    /// bit 7, as a heartbeat producer does.
    #[inline]
    pub fn set_state(&mut self, state: NmtState) {
        self.buffer.as_mut()[field::STATE] = state.to_byte() & field::STATE_MASK;
    }

    /// Write a whole decoded byte back: state and reserved bit (used to
    /// re-emit a received message unchanged).
    #[inline]
    fn set_byte(&mut self, state: NmtState, reserved_bit: bool) {
        let bit7 = if reserved_bit { field::BIT7 } else { 0 };
        self.buffer.as_mut()[field::STATE] = (state.to_byte() & field::STATE_MASK) | bit7;
    }
}

/// A heartbeat or boot-up message, owned (CiA 301 §7.2.8.3.2.2;
/// docs/canopen.md#error-control).
///
/// [`Heartbeat::new`] never sets the reserved bit 7 ("a producer never sets
/// it"); decoding keeps it, so that a received byte with bit 7 set
/// round-trips and can be reported ([`Heartbeat::reserved_bit`]).
///
/// ```
/// use motionwire_codec::canopen::{Heartbeat, NmtState};
///
/// let received = Heartbeat::parse(&[0x85])?;
/// assert_eq!(received.state(), NmtState::Operational);
/// assert!(received.reserved_bit());
/// assert_eq!(received.to_bytes(), [0x85]);
/// assert!(!Heartbeat::new(NmtState::Operational).reserved_bit());
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Heartbeat {
    state: NmtState,
    reserved_bit: bool,
}

impl Heartbeat {
    /// Return the heartbeat a producer sends in `state`; bit 7 is 0.
    #[inline]
    #[must_use]
    pub const fn new(state: NmtState) -> Self {
        Heartbeat {
            state,
            reserved_bit: false,
        }
    }

    /// Return the boot-up message (state 0x00), sent once when a node enters
    /// pre-operational after initialisation (CiA 301 §7.2.8.3.3).
    #[inline]
    #[must_use]
    pub const fn boot_up() -> Self {
        Self::new(NmtState::BootUp)
    }

    /// Return the NMT state the message reports.
    #[inline]
    #[must_use]
    pub const fn state(&self) -> NmtState {
        self.state
    }

    /// Return whether this is a boot-up message (state 0x00).
    #[inline]
    #[must_use]
    pub const fn is_boot_up(&self) -> bool {
        matches!(self.state, NmtState::BootUp)
    }

    /// Return whether the reserved bit 7 was set in the received byte; always
    /// `false` for a heartbeat built with [`Heartbeat::new`].
    #[inline]
    #[must_use]
    pub const fn reserved_bit(&self) -> bool {
        self.reserved_bit
    }

    /// Decode the byte of a heartbeat message; a byte whose bits 0–6 code no
    /// NMT state is a [`ValueError`].
    #[inline]
    pub fn from_bytes(bytes: &[u8; HEARTBEAT_LEN]) -> Result<Self, ValueError> {
        Self::parse_frame(&HeartbeatFrame::new_unchecked(bytes))
    }

    /// Encode the heartbeat into its byte.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; HEARTBEAT_LEN] {
        let mut bytes = [0; HEARTBEAT_LEN];
        self.emit(&mut HeartbeatFrame::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode a heartbeat from a CAN frame's data: an empty slice is an
    /// [`FrameError::Length`], an undefined state a [`FrameError::Content`].
    /// Bytes after the first are not read (as for every frame of the crate).
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, FrameError> {
        Ok(Self::parse_frame(&HeartbeatFrame::new_checked(data)?)?)
    }

    /// Read the owned value out of a view whose length has been checked.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &HeartbeatFrame<T>) -> Result<Self, ValueError> {
        Ok(Heartbeat {
            state: frame.state()?,
            reserved_bit: frame.reserved_bit(),
        })
    }

    /// Write the state (and a received reserved bit) into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut HeartbeatFrame<T>) {
        frame.set_byte(self.state, self.reserved_bit);
    }
}

/// A zero-copy view over a node-guarding answer's data
/// (CiA 301 §7.2.8.3.2.1; docs/canopen.md#error-control).
///
/// After [`GuardAnswerFrame::new_checked`] (or [`GuardAnswerFrame::check_len`])
/// succeeds, no accessor panics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GuardAnswerFrame<T: AsRef<[u8]>> {
    buffer: T,
}

impl<T: AsRef<[u8]>> GuardAnswerFrame<T> {
    /// Wrap a buffer without checking its length; accessors panic when it is
    /// empty.
    #[inline]
    pub const fn new_unchecked(buffer: T) -> Self {
        GuardAnswerFrame { buffer }
    }

    /// Wrap a buffer, checking that it holds at least [`GUARD_ANSWER_LEN`] bytes.
    #[inline]
    pub fn new_checked(buffer: T) -> Result<Self, LenError> {
        let frame = Self::new_unchecked(buffer);
        frame.check_len()?;
        Ok(frame)
    }

    /// Check that the buffer holds at least [`GUARD_ANSWER_LEN`] bytes.
    #[inline]
    pub fn check_len(&self) -> Result<(), LenError> {
        check_len(GUARD_ANSWER_WHAT, self.buffer.as_ref(), GUARD_ANSWER_LEN)
    }

    /// Return the wrapped buffer.
    #[inline]
    pub fn into_inner(self) -> T {
        self.buffer
    }

    /// Return the toggle field (bit 7 of byte 0): 0 in the first answer after
    /// initialisation, alternating afterwards.
    #[inline]
    pub fn toggle(&self) -> bool {
        self.buffer.as_ref()[field::STATE] & field::BIT7 != 0
    }

    /// Return the NMT state field (bits 0–6 of byte 0) as a number, whether
    /// or not it codes a defined state.
    #[inline]
    pub fn state_raw(&self) -> u8 {
        self.buffer.as_ref()[field::STATE] & field::STATE_MASK
    }

    /// Return the NMT state field (bits 0–6 of byte 0), or a
    /// [`ValueError`] when it codes no defined state.
    #[inline]
    pub fn state(&self) -> Result<NmtState, ValueError> {
        NmtState::from_byte(self.state_raw())
    }
}

impl<T: AsRef<[u8]> + AsMut<[u8]>> GuardAnswerFrame<T> {
    /// Set the toggle field (bit 7 of byte 0).
    #[inline]
    pub fn set_toggle(&mut self, toggle: bool) {
        let byte = &mut self.buffer.as_mut()[field::STATE];
        if toggle {
            *byte |= field::BIT7;
        } else {
            *byte &= !field::BIT7;
        }
    }

    /// Set the NMT state field (bits 0–6 of byte 0), keeping the toggle.
    #[inline]
    pub fn set_state(&mut self, state: NmtState) {
        let byte = &mut self.buffer.as_mut()[field::STATE];
        *byte = (*byte & field::BIT7) | (state.to_byte() & field::STATE_MASK);
    }
}

/// A node-guarding answer, owned: the node's reply to the master's remote
/// frame (CiA 301 §7.2.8.3.2.1; docs/canopen.md#error-control).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GuardAnswer {
    /// Toggle bit (bit 7): 0 in the first answer after initialisation or a
    /// communication reset, alternating with every answer afterwards.
    pub toggle: bool,
    /// The node's NMT state (bits 0–6).
    pub state: NmtState,
}

impl GuardAnswer {
    /// Return the answer with the given toggle bit and state.
    #[inline]
    #[must_use]
    pub const fn new(toggle: bool, state: NmtState) -> Self {
        GuardAnswer { toggle, state }
    }

    /// Decode the byte of a node-guarding answer; bits 0–6 that code no NMT
    /// state are a [`ValueError`].
    #[inline]
    pub fn from_bytes(bytes: &[u8; GUARD_ANSWER_LEN]) -> Result<Self, ValueError> {
        Self::parse_frame(&GuardAnswerFrame::new_unchecked(bytes))
    }

    /// Encode the answer into its byte.
    #[inline]
    #[must_use]
    pub fn to_bytes(&self) -> [u8; GUARD_ANSWER_LEN] {
        let mut bytes = [0; GUARD_ANSWER_LEN];
        self.emit(&mut GuardAnswerFrame::new_unchecked(&mut bytes));
        bytes
    }

    /// Decode an answer from a CAN frame's data: an empty slice is an
    /// [`FrameError::Length`], an undefined state a [`FrameError::Content`].
    /// Bytes after the first are not read.
    #[inline]
    pub fn parse(data: &[u8]) -> Result<Self, FrameError> {
        Ok(Self::parse_frame(&GuardAnswerFrame::new_checked(data)?)?)
    }

    /// Read the owned value out of a view whose length has been checked.
    #[inline]
    pub fn parse_frame<T: AsRef<[u8]>>(frame: &GuardAnswerFrame<T>) -> Result<Self, ValueError> {
        Ok(GuardAnswer {
            toggle: frame.toggle(),
            state: frame.state()?,
        })
    }

    /// Write every field into a view.
    #[inline]
    pub fn emit<T: AsRef<[u8]> + AsMut<[u8]>>(&self, frame: &mut GuardAnswerFrame<T>) {
        frame.set_state(self.state);
        frame.set_toggle(self.toggle);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The wire codes of CiA 301 §7.2.8.3.2 (docs/canopen.md#error-control)
    /// with their JSON names (docs/output.md#heartbeat).
    const STATE_TABLE: [(u8, NmtState, &str); 4] = [
        (0x00, NmtState::BootUp, "boot_up"),
        (0x04, NmtState::Stopped, "stopped"),
        (0x05, NmtState::Operational, "operational"),
        (0x7F, NmtState::PreOperational, "pre_operational"),
    ];

    /// A guarding answer: toggle 1, pre-operational.
    static GUARD_ANSWER_BYTES: [u8; 1] = [0xFF];
    /// A heartbeat: operational.
    static HEARTBEAT_BYTES: [u8; 1] = [0x05];

    #[test]
    fn nmt_state_table() {
        for (byte, state, name) in STATE_TABLE {
            assert_eq!(NmtState::from_byte(byte), Ok(state));
            assert_eq!(NmtState::try_from(byte), Ok(state));
            assert_eq!(state.to_byte(), byte);
            assert_eq!(u8::from(state), byte);
            assert_eq!(state.name(), name);
            assert_eq!(state.to_string(), name);
        }
        assert_eq!(
            NmtState::ALL.map(NmtState::to_byte),
            [0x00, 0x04, 0x05, 0x7F]
        );
    }

    #[test]
    fn every_other_byte_is_an_invalid_state() {
        for byte in 0..=255u8 {
            if STATE_TABLE.iter().any(|&(b, _, _)| b == byte) {
                continue;
            }
            assert_eq!(
                NmtState::from_byte(byte),
                Err(ValueError {
                    what: What::NmtState,
                    found: u32::from(byte),
                    expected: "0x00, 0x04, 0x05, 0x7f",
                })
            );
        }
    }

    #[test]
    fn heartbeat_deconstruct() {
        let frame = HeartbeatFrame::new_checked(&HEARTBEAT_BYTES[..]).unwrap();
        assert_eq!(frame.state_raw(), 0x05);
        assert_eq!(frame.state(), Ok(NmtState::Operational));
        assert!(!frame.reserved_bit());
        assert_eq!(frame.into_inner(), &HEARTBEAT_BYTES[..]);
    }

    #[test]
    fn heartbeat_construct_clears_bit7() {
        let mut bytes = [0xFFu8; 1];
        HeartbeatFrame::new_unchecked(&mut bytes[..]).set_state(NmtState::Operational);
        assert_eq!(bytes, HEARTBEAT_BYTES);
    }

    #[test]
    fn heartbeat_parse_and_emit() {
        let heartbeat = Heartbeat::parse(&HEARTBEAT_BYTES).unwrap();
        assert_eq!(heartbeat, Heartbeat::new(NmtState::Operational));
        assert_eq!(heartbeat.to_bytes(), HEARTBEAT_BYTES);
        assert_eq!(Heartbeat::from_bytes(&HEARTBEAT_BYTES), Ok(heartbeat));
    }

    #[test]
    fn heartbeat_a_producer_never_sets_bit7() {
        for state in NmtState::ALL {
            let heartbeat = Heartbeat::new(state);
            assert_eq!(heartbeat.to_bytes(), [state.to_byte()]);
            assert_eq!(heartbeat.to_bytes()[0] & 0x80, 0);
        }
        assert_eq!(Heartbeat::boot_up().to_bytes(), [0x00]);
        assert!(Heartbeat::boot_up().is_boot_up());
    }

    #[test]
    fn heartbeat_decoding_keeps_bit7() {
        let received = Heartbeat::parse(&[0xFF]).unwrap();
        assert_eq!(received.state(), NmtState::PreOperational);
        assert!(received.reserved_bit());
        assert_eq!(received.to_bytes(), [0xFF]);
        let frame = HeartbeatFrame::new_checked(&[0x84u8][..]).unwrap();
        assert!(frame.reserved_bit());
        assert_eq!(frame.state_raw(), 0x04);
    }

    #[test]
    fn heartbeat_invalid_state_reports_bits_0_to_6() {
        let expected = ValueError {
            what: What::NmtState,
            found: 0x12,
            expected: "0x00, 0x04, 0x05, 0x7f",
        };
        assert_eq!(
            Heartbeat::parse(&[0x12]),
            Err(FrameError::Content(expected))
        );
        assert_eq!(
            Heartbeat::parse(&[0x92]),
            Err(FrameError::Content(expected))
        );
        // The view still reads the raw fields (docs/output.md#heartbeat: state
        // "invalid").
        let frame = HeartbeatFrame::new_checked(&[0x92u8][..]).unwrap();
        assert_eq!(frame.state_raw(), 0x12);
        assert!(frame.reserved_bit());
    }

    #[test]
    fn guard_answer_deconstruct() {
        let frame = GuardAnswerFrame::new_checked(&GUARD_ANSWER_BYTES[..]).unwrap();
        assert!(frame.toggle());
        assert_eq!(frame.state_raw(), 0x7F);
        assert_eq!(frame.state(), Ok(NmtState::PreOperational));
    }

    #[test]
    fn guard_answer_construct() {
        let mut bytes = [0x00u8; 1];
        let mut frame = GuardAnswerFrame::new_unchecked(&mut bytes[..]);
        frame.set_toggle(true);
        frame.set_state(NmtState::PreOperational);
        assert_eq!(bytes, GUARD_ANSWER_BYTES);
        let mut frame = GuardAnswerFrame::new_unchecked(&mut bytes[..]);
        frame.set_toggle(false);
        assert_eq!(bytes, [0x7F]);
        let mut frame = GuardAnswerFrame::new_unchecked(&mut bytes[..]);
        frame.set_state(NmtState::Stopped);
        frame.set_toggle(true);
        assert_eq!(bytes, [0x84]);
    }

    #[test]
    fn guard_answer_parse_and_emit() {
        let answer = GuardAnswer::parse(&GUARD_ANSWER_BYTES).unwrap();
        assert_eq!(answer, GuardAnswer::new(true, NmtState::PreOperational));
        assert_eq!(answer.to_bytes(), GUARD_ANSWER_BYTES);
        assert_eq!(GuardAnswer::from_bytes(&GUARD_ANSWER_BYTES), Ok(answer));
    }

    /// Every answer a guarded node can give, as bytes (CiA 301 §7.2.8.3.2.1).
    #[test]
    fn guard_answer_table() {
        let table: [(u8, bool, NmtState); 6] = [
            (0x04, false, NmtState::Stopped),
            (0x84, true, NmtState::Stopped),
            (0x05, false, NmtState::Operational),
            (0x85, true, NmtState::Operational),
            (0x7F, false, NmtState::PreOperational),
            (0xFF, true, NmtState::PreOperational),
        ];
        for (byte, toggle, state) in table {
            let answer = GuardAnswer::new(toggle, state);
            assert_eq!(GuardAnswer::parse(&[byte]), Ok(answer), "{byte:#04x}");
            assert_eq!(answer.to_bytes(), [byte]);
        }
    }

    #[test]
    fn every_short_length_is_an_exact_error() {
        let heartbeat = LenError {
            what: What::HeartbeatMessage,
            expected: 1,
            found: 0,
        };
        assert_eq!(Heartbeat::parse(&[]), Err(FrameError::Length(heartbeat)));
        assert_eq!(HeartbeatFrame::new_checked(&[][..]), Err(heartbeat));
        let answer = LenError {
            what: What::NodeGuardingAnswer,
            expected: 1,
            found: 0,
        };
        assert_eq!(GuardAnswer::parse(&[]), Err(FrameError::Length(answer)));
        assert_eq!(GuardAnswerFrame::new_checked(&[][..]), Err(answer));
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::strategies::error_control::{guard_answer, heartbeat, nmt_state};

    proptest! {
        #[test]
        fn nmt_state_any_byte_never_panics(byte in any::<u8>()) {
            match NmtState::from_byte(byte) {
                Ok(state) => prop_assert_eq!(state.to_byte(), byte),
                Err(e) => prop_assert!(matches!(e, ValueError { what: What::NmtState, .. }), "{}", e),
            }
        }

        #[test]
        fn nmt_state_round_trip(state in nmt_state()) {
            prop_assert_eq!(NmtState::from_byte(state.to_byte()), Ok(state));
        }

        #[test]
        fn heartbeat_bytes_owned_bytes(byte in any::<u8>()) {
            match Heartbeat::from_bytes(&[byte]) {
                Ok(value) => {
                    prop_assert_eq!(value.to_bytes(), [byte]);
                    prop_assert_eq!(value.reserved_bit(), byte & 0x80 != 0);
                }
                Err(e) => prop_assert_eq!(e, NmtState::from_byte(byte & 0x7F).unwrap_err()),
            }
        }

        #[test]
        fn heartbeat_owned_bytes_owned(value in heartbeat()) {
            prop_assert_eq!(Heartbeat::from_bytes(&value.to_bytes()), Ok(value));
            prop_assert_eq!(Heartbeat::new(value.state()).to_bytes()[0] & 0x80, 0);
        }

        #[test]
        fn guard_answer_bytes_owned_bytes(byte in any::<u8>()) {
            match GuardAnswer::from_bytes(&[byte]) {
                Ok(value) => prop_assert_eq!(value.to_bytes(), [byte]),
                Err(e) => prop_assert_eq!(e, NmtState::from_byte(byte & 0x7F).unwrap_err()),
            }
        }

        #[test]
        fn guard_answer_owned_bytes_owned(value in guard_answer()) {
            prop_assert_eq!(GuardAnswer::from_bytes(&value.to_bytes()), Ok(value));
        }

        #[test]
        fn arbitrary_slices_never_panic(data in proptest::collection::vec(any::<u8>(), 0..4)) {
            for result in [
                Heartbeat::parse(&data).map(|h| h.to_bytes()),
                GuardAnswer::parse(&data).map(|a| a.to_bytes()),
            ] {
                match result {
                    Ok(bytes) => prop_assert_eq!(&bytes[..], &data[..1]),
                    Err(FrameError::Length(LenError { expected, found, .. })) => {
                        prop_assert_eq!((expected, found), (1, 0));
                        prop_assert!(data.is_empty());
                    }
                    Err(FrameError::Content(e)) => prop_assert!(matches!(e, ValueError { what: What::NmtState, .. }), "{}", e),
                }
            }
        }
    }
}

impl fmt::Display for Heartbeat {
    /// `heartbeat operational`, `boot-up`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_boot_up() {
            f.write_str("boot-up")
        } else {
            write!(f, "heartbeat {}", self.state.name())
        }
    }
}

impl fmt::Display for GuardAnswer {
    /// `guard answer operational, toggle 1`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "guard answer {}, toggle {}",
            self.state.name(),
            u8::from(self.toggle)
        )
    }
}
