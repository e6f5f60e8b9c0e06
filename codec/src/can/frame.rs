//! The crate's one CAN frame: what every log reader yields, what the
//! CANopen decoders take and what `embedded-can` converts to and from
//! (ISO 11898-1; Linux `linux/can.h`; docs/formats.md).

use crate::error::What;
use core::fmt;
use core::hash::{Hash, Hasher};

use super::{CanId, FdFlags};
use crate::{FieldError, RangeError, Result, ValueError};

/// The most data bytes of a classic CAN frame, 8 (ISO 11898-1).
pub const CLASSIC_MAX_LEN: usize = 8;
/// The most data bytes of a CAN FD frame, 64 (ISO 11898-1).
pub const FD_MAX_LEN: usize = 64;
/// The data length of each CAN FD data length code 0..=15 (ISO 11898-1:
/// 9 → 12 bytes, …, 15 → 64): the one table the log readers check CAN FD
/// lengths and DLC columns against.
pub const FD_LENGTHS: [u8; 16] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64];

/// What kind of frame a [`CanFrame`] is (ISO 11898-1; Linux `linux/can.h`
/// for error frames; docs/formats.md#error-frames).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrameType {
    /// A classic data frame, 0..=8 data bytes.
    Data,
    /// A classic remote request (RTR): no data; `dlc` is the length asked
    /// for, 0..=8.
    Remote {
        /// The requested data length, 0..=8.
        dlc: u8,
    },
    /// A CAN FD frame, 0..=64 data bytes, with its flags.
    Fd(FdFlags),
    /// An error frame as Linux reports it (`CAN_ERR_FLAG`, candump `-e`;
    /// docs/formats.md#error-frames): the identifier holds the error classes,
    /// the 0..=8 data bytes their details. Read it with
    /// [`ErrorFrame`](super::ErrorFrame).
    Error,
}

impl FrameType {
    /// Return the most data bytes this kind of frame carries: 8, 0 for a
    /// remote request, 64 for CAN FD.
    #[inline]
    #[must_use]
    pub const fn max_len(self) -> usize {
        match self {
            FrameType::Data | FrameType::Error => CLASSIC_MAX_LEN,
            FrameType::Remote { .. } => 0,
            FrameType::Fd(_) => FD_MAX_LEN,
        }
    }
}

/// The data of an owned [`CanFrame`]: up to 64 bytes, no heap.
///
/// Comparing two values compares their data only: the bytes of the array
/// past the length are not data.
#[derive(Clone, Copy)]
pub struct FrameData {
    bytes: [u8; FD_MAX_LEN],
    len: u8,
}

impl FrameData {
    /// No data.
    pub const EMPTY: FrameData = FrameData {
        bytes: [0; FD_MAX_LEN],
        len: 0,
    };

    /// Return a copy of `data`, or a [`RangeError`] when it is longer than
    /// 64 bytes.
    pub fn new(data: &[u8]) -> Result<Self, RangeError> {
        let mut bytes = [0; FD_MAX_LEN];
        match bytes.get_mut(..data.len()) {
            Some(head) => head.copy_from_slice(data),
            None => return Err(too_long(What::CanFrameDataLength, data.len(), FD_MAX_LEN)),
        }
        Ok(FrameData {
            bytes,
            // At most 64: `get_mut` succeeded.
            len: data.len() as u8,
        })
    }

    /// Return the data bytes.
    #[inline]
    #[must_use]
    pub fn as_slice(&self) -> &[u8] {
        self.bytes.get(..usize::from(self.len)).unwrap_or_default()
    }

    /// Return the number of data bytes, 0..=64.
    #[inline]
    #[must_use]
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    /// Return whether there are no data bytes.
    #[inline]
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl Default for FrameData {
    fn default() -> Self {
        FrameData::EMPTY
    }
}

impl AsRef<[u8]> for FrameData {
    #[inline]
    fn as_ref(&self) -> &[u8] {
        self.as_slice()
    }
}

impl PartialEq for FrameData {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl Eq for FrameData {}

impl Hash for FrameData {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.as_slice().hash(state);
    }
}

impl fmt::Debug for FrameData {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_slice(), f)
    }
}

fn too_long(what: What, len: usize, max: usize) -> RangeError {
    RangeError {
        what,
        found: u32::try_from(len).unwrap_or(u32::MAX),
        min: 0,
        max: max as u32,
    }
}

/// One CAN frame: identifier, kind (data, remote request, CAN FD with its
/// flags, error frame) and data (ISO 11898-1; docs/formats.md).
///
/// This is the crate's one frame type. Every log reader yields it (inside a
/// [`LogFrame`](super::LogFrame) with the time and interface), the CANopen
/// decoders take it (`canopen::CanOpenMessage::decode`), and with the
/// `embedded-can` feature it is an `embedded_can::Frame`.
///
/// It comes in two forms, as smoltcp's and etherparse's headers do: the
/// owned `CanFrame` (the default, `CanFrame<FrameData>`: `Copy`, the data
/// kept inline, no heap) and the borrowed [`CanFrameRef`]
/// (`CanFrame<&[u8]>`), whose data stays where a binary log or a driver
/// buffer holds it. Both have the same accessors and compare equal when
/// they hold the same frame.
///
/// Every value keeps the invariants of ISO 11898-1: a classic data frame or
/// an error frame has at most 8 data bytes, a CAN FD frame at most 64, a
/// remote request no data and a requested length 0..=8; an error frame's
/// identifier is an extended one (the 29 bits of Linux `can_id` under
/// `CAN_ERR_FLAG`).
///
/// `Display` writes the frame in candump's log notation
/// (docs/formats.md#candump-log): `081#1081110000000000`, `701#R`,
/// `123##1AABB`, and an error frame with `CAN_ERR_FLAG` set,
/// `20000004#0004000000000000`.
///
/// ```
/// use motionwire_codec::can::{CanFrame, CanFrameRef, CanId, FdFlags, FrameType};
///
/// let id = CanId::standard(0x081).unwrap();
/// let frame = CanFrame::new(id, &[0x10, 0x81, 0x11, 0, 0, 0, 0, 0])?;
/// assert_eq!(frame.data(), [0x10, 0x81, 0x11, 0, 0, 0, 0, 0]);
/// assert_eq!(frame.to_string(), "081#1081110000000000");
///
/// // Borrowed: the bytes stay where they are; the frames compare equal.
/// let bytes = [0x10, 0x81, 0x11, 0, 0, 0, 0, 0];
/// let view = CanFrameRef::new_ref(id, FrameType::Data, &bytes)?;
/// assert_eq!(view, frame);
/// assert_eq!(view.to_owned_frame(), frame);
///
/// // A remote request, a CAN FD frame; too much data is an error.
/// let request = CanFrame::new_remote(CanId::standard(0x705).unwrap(), 1)?;
/// assert_eq!((request.is_rtr(), request.dlc(), request.data().len()), (true, 1, 0));
/// let fd = CanFrame::new_fd(id, FdFlags::BRS, &[0xAB; 12])?;
/// assert_eq!((fd.is_fd(), fd.dlc()), (true, 9));
/// assert_eq!(
///     CanFrame::new(id, &[0; 9]).unwrap_err().to_string(),
///     "CAN frame data length: 9 is outside 0..=8"
/// );
/// # Ok::<(), motionwire_codec::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct CanFrame<D = FrameData> {
    id: CanId,
    frame_type: FrameType,
    data: D,
}

/// A [`CanFrame`] whose data is borrowed: the zero-copy form, for readers of
/// binary logs and for driver buffers.
pub type CanFrameRef<'a> = CanFrame<&'a [u8]>;

/// Check `len` data bytes against the kind `frame_type` and the identifier.
fn check(id: CanId, frame_type: FrameType, len: usize) -> Result<(), FieldError> {
    if frame_type == FrameType::Error && !id.is_extended() {
        return Err(FieldError::InvalidValue(ValueError {
            what: What::CanErrorFrameIdentifier,
            found: id.raw(),
            expected: "an extended (29-bit) identifier holding the error classes",
        }));
    }
    Ok(check_len(frame_type, len)?)
}

/// Check `len` data bytes (and a remote request's DLC) against the kind
/// `frame_type`.
fn check_len(frame_type: FrameType, len: usize) -> Result<(), RangeError> {
    match frame_type {
        FrameType::Remote { dlc } if usize::from(dlc) > CLASSIC_MAX_LEN => Err(too_long(
            What::CanRemoteRequestLength,
            usize::from(dlc),
            CLASSIC_MAX_LEN,
        )),
        _ if len > frame_type.max_len() => Err(too_long(
            match frame_type {
                FrameType::Remote { .. } => What::CanRemoteRequestDataLength,
                _ => What::CanFrameDataLength,
            },
            len,
            frame_type.max_len(),
        )),
        _ => Ok(()),
    }
}

/// A frame without its data: the identifier, the kind and the number of
/// data bytes, held to the invariants of [`CanFrame`] (ISO 11898-1: at most
/// 8 bytes in a classic data or error frame, 64 in a CAN FD frame, none in
/// a remote request, whose requested length is 0..=8; an error frame's
/// identifier an extended one). With a data array it is a frame
/// ([`CanFrame::from_header`]); a parser makes it where it has read the
/// parts, with the constructor of the kind it read.
///
/// Its constructors cannot fail: what lies beyond the kind's limits is cut
/// to them. A parser that knows the kind where it reads it makes the header
/// with that kind's constructor: no match on the kind is left to make,
/// only that kind's cut.
///
/// ```
/// use motionwire_codec::can::{CanId, FdFlags, FrameHeader, FrameType};
///
/// let id = CanId::standard(0x705).unwrap();
/// assert_eq!(FrameHeader::data(id, 3).len(), 3);
/// assert_eq!(FrameHeader::data(id, 12).len(), 8);
/// assert_eq!(FrameHeader::remote(id, 9).frame_type(), FrameType::Remote { dlc: 8 });
/// assert_eq!(FrameHeader::fd(id, FdFlags::BRS, 12).len(), 12);
/// assert!(FrameHeader::error(id, 8).id().is_extended());
/// assert_eq!(FrameHeader::new(id, FrameType::Data, 3), FrameHeader::data(id, 3));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FrameHeader {
    id: CanId,
    frame_type: FrameType,
    len: u8,
}

impl FrameHeader {
    /// Return the header of a frame of kind `frame_type` with `len` data
    /// bytes, cut as the kind's own constructor cuts it
    /// ([`data`](Self::data), [`remote`](Self::remote), [`fd`](Self::fd),
    /// [`error`](Self::error)).
    #[inline]
    #[must_use]
    pub const fn new(id: CanId, frame_type: FrameType, len: u8) -> Self {
        match frame_type {
            FrameType::Data => Self::data(id, len),
            FrameType::Remote { dlc } => Self::remote(id, dlc),
            FrameType::Fd(flags) => Self::fd(id, flags, len),
            FrameType::Error => Self::error(id, len),
        }
    }

    /// Return the header of a classic data frame with `len` data bytes,
    /// cut to 8.
    #[inline]
    #[must_use]
    pub const fn data(id: CanId, len: u8) -> Self {
        FrameHeader {
            id,
            frame_type: FrameType::Data,
            len: cut(len, CLASSIC_MAX_LEN),
        }
    }

    /// Return the header of a remote request asking for `dlc` bytes, cut
    /// to 8; it has no data.
    #[inline]
    #[must_use]
    pub const fn remote(id: CanId, dlc: u8) -> Self {
        FrameHeader {
            id,
            frame_type: FrameType::Remote {
                dlc: cut(dlc, CLASSIC_MAX_LEN),
            },
            len: 0,
        }
    }

    /// Return the header of a CAN FD frame with `flags` and `len` data
    /// bytes, cut to 64.
    #[inline]
    #[must_use]
    pub const fn fd(id: CanId, flags: FdFlags, len: u8) -> Self {
        FrameHeader {
            id,
            frame_type: FrameType::Fd(flags),
            len: cut(len, FD_MAX_LEN),
        }
    }

    /// Return the header of an error frame whose identifier holds the error
    /// classes (read as an extended identifier: its low 29 bits) and with
    /// `len` data bytes, cut to 8.
    #[inline]
    #[must_use]
    pub const fn error(classes: CanId, len: u8) -> Self {
        FrameHeader {
            id: CanId::masked(classes.raw(), true),
            frame_type: FrameType::Error,
            len: cut(len, CLASSIC_MAX_LEN),
        }
    }

    /// Return the identifier.
    #[inline]
    #[must_use]
    pub const fn id(&self) -> CanId {
        self.id
    }

    /// Return the kind of frame.
    #[inline]
    #[must_use]
    pub const fn frame_type(&self) -> FrameType {
        self.frame_type
    }

    /// Return the number of data bytes.
    #[inline]
    #[must_use]
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    /// Return whether the frame has no data bytes.
    #[inline]
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// `value`, or `max` when it is larger.
#[inline]
const fn cut(value: u8, max: usize) -> u8 {
    if value as usize > max {
        max as u8
    } else {
        value
    }
}

impl CanFrame {
    /// Return a classic data frame; more than 8 bytes is a [`RangeError`].
    pub fn new(id: CanId, data: &[u8]) -> Result<Self, RangeError> {
        Self::with_len_checked(id, FrameType::Data, data)
    }

    /// Return a remote request (RTR) asking for `dlc` bytes; above 8 is a
    /// [`RangeError`].
    pub fn new_remote(id: CanId, dlc: u8) -> Result<Self, RangeError> {
        Self::with_len_checked(id, FrameType::Remote { dlc }, &[])
    }

    /// Return a CAN FD frame with `flags`; more than 64 bytes is a
    /// [`RangeError`]. Any length 0..=64 is kept as given, as Linux and
    /// candump keep it.
    pub fn new_fd(id: CanId, flags: FdFlags, data: &[u8]) -> Result<Self, RangeError> {
        Self::with_len_checked(id, FrameType::Fd(flags), data)
    }

    /// Return an error frame whose identifier holds the error classes
    /// `classes` (the low 29 bits of Linux `can_id`, without
    /// `CAN_ERR_FLAG`) and whose data holds their details
    /// (docs/formats.md#error-frames). Above `0x1FFFFFFF`, or more than 8
    /// bytes, is a [`RangeError`].
    pub fn new_error(classes: u32, data: &[u8]) -> Result<Self, RangeError> {
        let id = CanId::extended(classes).ok_or(RangeError {
            what: What::CanErrorFrameClasses,
            found: classes,
            min: 0,
            max: CanId::EXTENDED_MAX,
        })?;
        // `CanId::extended` made an extended identifier: only the length
        // is left to check.
        Self::with_len_checked(id, FrameType::Error, data)
    }

    /// Return a frame of kind `frame_type`, with the errors of the
    /// constructors above: a [`FieldError::OutOfRange`] for a length the
    /// kind does not allow, a [`FieldError::InvalidValue`] for an error
    /// frame whose identifier is a standard one.
    pub fn with_type(id: CanId, frame_type: FrameType, data: &[u8]) -> Result<Self, FieldError> {
        check(id, frame_type, data.len())?;
        Ok(Self::with_len_checked(id, frame_type, data)?)
    }

    /// Return a frame of kind `frame_type` after checking its length only:
    /// the constructors whose kind or identifier needs no other check.
    fn with_len_checked(id: CanId, frame_type: FrameType, data: &[u8]) -> Result<Self, RangeError> {
        check_len(frame_type, data.len())?;
        Ok(CanFrame {
            id,
            frame_type,
            data: FrameData::new(data)?,
        })
    }

    /// Return a frame of kind `frame_type` whose data is the first `len`
    /// bytes of `bytes`: the constructor of a reader whose parser has read
    /// and checked the parts already, and the data into an array, which is
    /// moved, not copied again.
    ///
    /// It cannot fail and cannot make an invalid frame: the parts are cut
    /// as [`FrameHeader::new`] cuts them — `len` to the kind's
    /// [`max_len`](FrameType::max_len), a remote request's `dlc` to 8, an
    /// error frame's identifier read as an extended one. A parser that
    /// rejects such parts first (every reader of motionwire does) never
    /// sees a cut. The bytes past `len` are not data: comparisons and
    /// [`data`](Self::data) ignore them. A parser that knows the kind where
    /// it reads it makes the header there with the kind's own constructor
    /// and calls [`from_header`](Self::from_header).
    ///
    /// ```
    /// use motionwire_codec::can::{CanFrame, CanId, FrameType};
    ///
    /// let mut bytes = [0; 64];
    /// bytes[..2].copy_from_slice(&[0x05, 0x7F]);
    /// let frame = CanFrame::from_array(CanId::standard(0x705).unwrap(), FrameType::Data, bytes, 1);
    /// assert_eq!(frame.data(), [0x05]);
    /// assert_eq!(frame, CanFrame::new(CanId::standard(0x705).unwrap(), &[0x05])?);
    /// // Nine bytes are more than a classic frame holds: cut to eight.
    /// assert_eq!(CanFrame::from_array(frame.id(), FrameType::Data, bytes, 9).data().len(), 8);
    /// # Ok::<(), motionwire_codec::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub const fn from_array(
        id: CanId,
        frame_type: FrameType,
        bytes: [u8; FD_MAX_LEN],
        len: u8,
    ) -> Self {
        Self::from_header(FrameHeader::new(id, frame_type, len), bytes)
    }

    /// Return the frame `header` whose data is the first
    /// [`header.len()`](FrameHeader::len) bytes of `bytes`: nothing is left
    /// to check, the header holds a valid frame's parts. The bytes past the
    /// length are not data, as for [`from_array`](Self::from_array).
    ///
    /// ```
    /// use motionwire_codec::can::{CanFrame, CanId, FrameHeader};
    ///
    /// let id = CanId::standard(0x181).unwrap();
    /// let mut bytes = [0; 64];
    /// bytes[..2].copy_from_slice(&[0x37, 0x06]);
    /// let frame = CanFrame::from_header(FrameHeader::data(id, 2), bytes);
    /// assert_eq!(frame, CanFrame::new(id, &[0x37, 0x06])?);
    /// assert_eq!(frame.header(), FrameHeader::data(id, 2));
    /// # Ok::<(), motionwire_codec::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub const fn from_header(header: FrameHeader, bytes: [u8; FD_MAX_LEN]) -> Self {
        CanFrame {
            id: header.id,
            frame_type: header.frame_type,
            data: FrameData {
                bytes,
                len: header.len,
            },
        }
    }

    /// Return the data's array of 64 bytes and the number of data bytes
    /// in it, so that a writer may read the data in whole blocks and cut
    /// what it writes (motionwire's JSON records). Past that number the
    /// array holds no data; a frame made by [`from_array`](Self::from_array)
    /// keeps there what it was given.
    #[inline]
    #[must_use]
    pub const fn data_array(&self) -> (&[u8; FD_MAX_LEN], usize) {
        (&self.data.bytes, self.data.len as usize)
    }

    /// Return the frame in its borrowed form.
    #[inline]
    #[must_use]
    pub fn as_frame_ref(&self) -> CanFrameRef<'_> {
        CanFrame {
            id: self.id,
            frame_type: self.frame_type,
            data: self.data.as_slice(),
        }
    }
}

impl<'a> CanFrame<&'a [u8]> {
    /// Return a borrowed frame of kind `frame_type` over `data`, with the
    /// errors of [`CanFrame::with_type`].
    pub fn new_ref(id: CanId, frame_type: FrameType, data: &'a [u8]) -> Result<Self, FieldError> {
        check(id, frame_type, data.len())?;
        Ok(CanFrame {
            id,
            frame_type,
            data,
        })
    }
}

impl<D: AsRef<[u8]>> CanFrame<D> {
    /// Return the identifier (for an error frame: the error classes).
    #[inline]
    #[must_use]
    pub fn id(&self) -> CanId {
        self.id
    }

    /// Return the kind of frame.
    #[inline]
    #[must_use]
    pub fn frame_type(&self) -> FrameType {
        self.frame_type
    }

    /// Return whether the identifier is extended (29-bit).
    #[inline]
    #[must_use]
    pub fn is_extended(&self) -> bool {
        self.id.is_extended()
    }

    /// Return whether this is a remote request (RTR).
    #[inline]
    #[must_use]
    pub fn is_rtr(&self) -> bool {
        matches!(self.frame_type, FrameType::Remote { .. })
    }

    /// Return whether this is a CAN FD frame.
    #[inline]
    #[must_use]
    pub fn is_fd(&self) -> bool {
        matches!(self.frame_type, FrameType::Fd(_))
    }

    /// Return whether this is an error frame (docs/formats.md#error-frames).
    #[inline]
    #[must_use]
    pub fn is_error(&self) -> bool {
        matches!(self.frame_type, FrameType::Error)
    }

    /// Return the CAN FD flags; empty for any other kind.
    #[inline]
    #[must_use]
    pub fn fd_flags(&self) -> FdFlags {
        match self.frame_type {
            FrameType::Fd(flags) => flags,
            _ => FdFlags::EMPTY,
        }
    }

    /// Return the data bytes; empty for a remote request.
    #[inline]
    #[must_use]
    pub fn data(&self) -> &[u8] {
        self.data.as_ref()
    }

    /// Return the data length code: the number of data bytes of a classic
    /// or error frame, the requested length of a remote request, and for
    /// CAN FD the code 0..=15 of the smallest CAN FD length that holds the
    /// data (ISO 11898-1: 12 bytes → 9, 64 bytes → 15).
    #[must_use]
    pub fn dlc(&self) -> u8 {
        let len = self.data().len();
        match self.frame_type {
            FrameType::Remote { dlc } => dlc,
            FrameType::Fd(_) => match len {
                0..=8 => len as u8,
                9..=12 => 9,
                13..=16 => 10,
                17..=20 => 11,
                21..=24 => 12,
                25..=32 => 13,
                33..=48 => 14,
                _ => 15,
            },
            // At most 8.
            FrameType::Data | FrameType::Error => len as u8,
        }
    }

    /// Return the frame without its data: identifier, kind and data
    /// length.
    #[inline]
    #[must_use]
    pub fn header(&self) -> FrameHeader {
        FrameHeader {
            id: self.id,
            frame_type: self.frame_type,
            // At most 64: every constructor checks or cuts the length.
            len: self.data().len() as u8,
        }
    }

    /// Return the frame in its owned form (a copy of the data).
    #[must_use]
    pub fn to_owned_frame(&self) -> CanFrame {
        let mut bytes = [0; FD_MAX_LEN];
        let data = self.data();
        for (to, from) in bytes.iter_mut().zip(data) {
            *to = *from;
        }
        // The length was checked when the frame was made.
        CanFrame::from_array(self.id, self.frame_type, bytes, data.len() as u8)
    }
}

impl<D: AsRef<[u8]>, E: AsRef<[u8]>> PartialEq<CanFrame<E>> for CanFrame<D> {
    fn eq(&self, other: &CanFrame<E>) -> bool {
        self.id == other.id && self.frame_type == other.frame_type && self.data() == other.data()
    }
}

impl<D: AsRef<[u8]>> Eq for CanFrame<D> {}

impl<D: AsRef<[u8]>> Hash for CanFrame<D> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.id.hash(state);
        self.frame_type.hash(state);
        self.data().hash(state);
    }
}

impl<D: AsRef<[u8]>> fmt::Debug for CanFrame<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CanFrame")
            .field("id", &self.id)
            .field("frame_type", &self.frame_type)
            .field("data", &self.data())
            .finish()
    }
}

impl<'a> From<&'a CanFrame> for CanFrameRef<'a> {
    fn from(frame: &'a CanFrame) -> Self {
        frame.as_frame_ref()
    }
}

/// Linux `CAN_ERR_FLAG`: the identifier bit that marks an error frame in
/// candump's log notation (docs/formats.md#error-frames).
pub const CAN_ERR_FLAG: u32 = 0x2000_0000;

const HEX_UPPER: [u8; 16] = *b"0123456789ABCDEF";

impl<D: AsRef<[u8]>> fmt::Display for CanFrame<D> {
    /// Write the frame in candump's log notation (docs/formats.md#candump-log),
    /// as can-utils' `snprintf_canframe` does: upper-case hex, `R` and the DLC
    /// when it is not 0 for a remote request, `##` and the flags nibble for CAN
    /// FD.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.frame_type {
            FrameType::Error => write!(f, "{:08X}#", self.id.raw() | CAN_ERR_FLAG)?,
            _ => write!(f, "{}#", self.id)?,
        }
        match self.frame_type {
            FrameType::Remote { dlc: 0 } => return f.write_str("R"),
            FrameType::Remote { dlc } => return write!(f, "R{dlc}"),
            FrameType::Fd(flags) => write!(f, "#{:X}", flags.bits())?,
            FrameType::Data | FrameType::Error => {}
        }
        let mut buf = [0u8; 2 * FD_MAX_LEN];
        let mut n = 0;
        for (pair, &byte) in buf.chunks_exact_mut(2).zip(self.data()) {
            pair[0] = HEX_UPPER[usize::from(byte >> 4)];
            pair[1] = HEX_UPPER[usize::from(byte & 0xF)];
            n += 2;
        }
        f.write_str(core::str::from_utf8(buf.get(..n).unwrap_or_default()).unwrap_or_default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn std_id(raw: u32) -> CanId {
        CanId::standard(raw).unwrap()
    }

    #[test]
    fn classic_limits() {
        for len in 0..=8 {
            let frame = CanFrame::new(std_id(1), &[0xAA; 8][..len]).unwrap();
            assert_eq!(frame.data().len(), len);
            assert_eq!(usize::from(frame.dlc()), len);
        }
        assert_eq!(
            CanFrame::new(std_id(1), &[0; 9]),
            Err(RangeError {
                what: What::CanFrameDataLength,
                found: 9,
                min: 0,
                max: 8
            })
        );
    }

    #[test]
    fn remote_limits() {
        for dlc in 0..=8 {
            let frame = CanFrame::new_remote(std_id(0x705), dlc).unwrap();
            assert!(frame.is_rtr());
            assert_eq!((frame.dlc(), frame.data()), (dlc, &[][..]));
        }
        assert_eq!(
            CanFrame::new_remote(std_id(0x705), 9),
            Err(RangeError {
                what: What::CanRemoteRequestLength,
                found: 9,
                min: 0,
                max: 8
            })
        );
        assert_eq!(
            CanFrameRef::new_ref(std_id(0x705), FrameType::Remote { dlc: 1 }, &[1]),
            Err(FieldError::OutOfRange(RangeError {
                what: What::CanRemoteRequestDataLength,
                found: 1,
                min: 0,
                max: 0
            }))
        );
    }

    #[test]
    fn fd_length_table_and_dlc_agree() {
        for (dlc, &len) in FD_LENGTHS.iter().enumerate() {
            let data = [0u8; FD_MAX_LEN];
            let frame = CanFrame::new_fd(
                CanId::standard(1).unwrap(),
                FdFlags::EMPTY,
                &data[..usize::from(len)],
            )
            .unwrap();
            assert_eq!(usize::from(frame.dlc()), dlc);
        }
    }

    #[test]
    fn fd_lengths_and_dlc() {
        let table = [
            (0, 0),
            (8, 8),
            (9, 9),
            (12, 9),
            (13, 10),
            (16, 10),
            (20, 11),
            (24, 12),
            (32, 13),
            (48, 14),
            (49, 15),
            (64, 15),
        ];
        for (len, dlc) in table {
            let frame = CanFrame::new_fd(std_id(1), FdFlags::EMPTY, &[0; 64][..len]).unwrap();
            assert_eq!((frame.data().len(), frame.dlc()), (len, dlc), "{len}");
        }
        assert!(CanFrame::new_fd(std_id(1), FdFlags::EMPTY, &[0; 65]).is_err());
    }

    #[test]
    fn error_frames_need_an_extended_identifier() {
        let frame = CanFrame::new_error(0x004, &[0, 4, 0, 0, 0, 0, 0, 0]).unwrap();
        assert!(frame.is_error() && frame.is_extended());
        assert_eq!(frame.to_string(), "20000004#0004000000000000");
        assert!(CanFrame::new_error(0x2000_0000, &[]).is_err());
        assert!(CanFrame::with_type(std_id(4), FrameType::Error, &[]).is_err());
        assert!(CanFrame::new_error(0x004, &[0; 9]).is_err());
    }

    /// Each kind's header cuts what lies beyond the kind's limits, and
    /// nothing within them.
    #[test]
    fn headers_cut_to_the_kinds_limits() {
        let id = std_id(0x705);
        let ext = CanId::extended(0x0000_0705).unwrap();
        let cases = [
            // (header, identifier, kind, data length)
            (FrameHeader::data(id, 8), id, FrameType::Data, 8),
            (FrameHeader::data(id, 9), id, FrameType::Data, 8),
            (FrameHeader::data(id, 255), id, FrameType::Data, 8),
            (
                FrameHeader::remote(id, 8),
                id,
                FrameType::Remote { dlc: 8 },
                0,
            ),
            (
                FrameHeader::remote(id, 15),
                id,
                FrameType::Remote { dlc: 8 },
                0,
            ),
            (
                FrameHeader::fd(id, FdFlags::BRS, 64),
                id,
                FrameType::Fd(FdFlags::BRS),
                64,
            ),
            (
                FrameHeader::fd(id, FdFlags::BRS, 65),
                id,
                FrameType::Fd(FdFlags::BRS),
                64,
            ),
            (FrameHeader::error(ext, 8), ext, FrameType::Error, 8),
            (FrameHeader::error(ext, 9), ext, FrameType::Error, 8),
            // A standard identifier's bits read as an extended one.
            (FrameHeader::error(id, 0), ext, FrameType::Error, 0),
        ];
        for (header, id, frame_type, len) in cases {
            assert_eq!(
                (header.id(), header.frame_type(), header.len()),
                (id, frame_type, len)
            );
            assert_eq!(FrameHeader::new(id, frame_type, len as u8), header);
        }
    }

    #[test]
    fn display_as_candump_log() {
        let fd = CanFrame::new_fd(
            CanId::extended(0x18FF_1234).unwrap(),
            FdFlags::BRS,
            &[0xAB; 12],
        )
        .unwrap();
        assert_eq!(fd.to_string(), "18FF1234##1ABABABABABABABABABABABAB");
        assert_eq!(
            CanFrame::new(std_id(0x123), &[]).unwrap().to_string(),
            "123#"
        );
        assert_eq!(
            CanFrame::new_remote(std_id(0x705), 0).unwrap().to_string(),
            "705#R"
        );
        assert_eq!(
            CanFrame::new_remote(std_id(0x705), 1).unwrap().to_string(),
            "705#R1"
        );
    }

    #[test]
    fn owned_and_borrowed_agree() {
        let bytes = [1, 2, 3];
        let owned = CanFrame::new(std_id(0x181), &bytes).unwrap();
        let view = CanFrameRef::new_ref(std_id(0x181), FrameType::Data, &bytes).unwrap();
        assert_eq!(owned, view);
        assert_eq!(view, owned);
        assert_eq!(owned.as_frame_ref(), view);
        assert_eq!(view.to_owned_frame(), owned);
        assert_ne!(owned, CanFrame::new(std_id(0x181), &bytes[..2]).unwrap());
        assert_ne!(
            owned,
            CanFrame::new_fd(std_id(0x181), FdFlags::EMPTY, &bytes).unwrap()
        );
        assert_eq!(format!("{view:?}"), format!("{owned:?}"));
    }
}

#[cfg(test)]
mod proptests {
    use super::*;
    use crate::strategies::can::{any_can_frame, any_frame_type, can_id};
    use proptest::prelude::*;

    proptest! {
        /// The constructors accept exactly what ISO 11898-1 and Linux allow,
        /// and the owned and borrowed forms agree on everything they accept.
        #[test]
        fn constructors_check_exactly_the_invariants(
            id in can_id(),
            frame_type in any_frame_type(),
            data in proptest::collection::vec(any::<u8>(), 0..=80),
        ) {
            let valid = match frame_type {
                FrameType::Data => data.len() <= 8,
                FrameType::Remote { dlc } => dlc <= 8 && data.is_empty(),
                FrameType::Fd(_) => data.len() <= 64,
                FrameType::Error => id.is_extended() && data.len() <= 8,
            };
            let owned = CanFrame::with_type(id, frame_type, &data);
            let borrowed = CanFrameRef::new_ref(id, frame_type, &data);
            prop_assert_eq!(owned.is_ok(), valid);
            prop_assert_eq!(borrowed.is_ok(), valid);
            if let (Ok(owned), Ok(borrowed)) = (owned, borrowed) {
                prop_assert_eq!(owned, borrowed);
                prop_assert_eq!(borrowed.to_owned_frame(), owned);
                prop_assert_eq!((owned.id(), owned.frame_type(), owned.data()), (id, frame_type, &data[..]));
            }
        }

        /// A header made of any parts is a valid frame's: the frame made
        /// from it is one the checked constructor accepts, it gives its
        /// header back, and valid parts are kept as given.
        #[test]
        fn headers_make_only_valid_frames(
            id in can_id(),
            frame_type in any_frame_type(),
            len in any::<u8>(),
        ) {
            let bytes = [0xA5; FD_MAX_LEN];
            let header = FrameHeader::new(id, frame_type, len);
            let frame = CanFrame::from_header(header, bytes);
            let checked = CanFrame::with_type(frame.id(), frame.frame_type(), frame.data());
            prop_assert_eq!(checked.ok(), Some(frame));
            prop_assert_eq!(frame.header(), header);
            prop_assert_eq!(CanFrame::from_array(id, frame_type, bytes, len), frame);
            let given = vec![0xA5; usize::from(len)];
            if let Ok(valid) = CanFrame::with_type(id, frame_type, &given) {
                prop_assert_eq!(valid, frame);
            }
        }

        /// Every frame's candump notation names its identifier, type and data.
        #[test]
        fn display_is_candump_notation(frame in any_can_frame()) {
            let text = frame.to_string();
            let (id, rest) = text.split_once('#').expect("a separator");
            let raw = u32::from_str_radix(id, 16).expect("hex identifier");
            prop_assert_eq!(raw & !CAN_ERR_FLAG, frame.id().raw());
            prop_assert_eq!(raw & CAN_ERR_FLAG != 0, frame.is_error());
            prop_assert_eq!(id.len(), if frame.is_extended() { 8 } else { 3 });
            let hex = match frame.frame_type() {
                FrameType::Remote { .. } => { prop_assert!(rest.starts_with('R')); "" }
                FrameType::Fd(flags) => {
                    prop_assert_eq!(u8::from_str_radix(&rest[1..2], 16).unwrap(), flags.bits());
                    &rest[2..]
                }
                _ => rest,
            };
            let bytes: Vec<u8> = (0..hex.len()).step_by(2)
                .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).unwrap()).collect();
            prop_assert_eq!(&bytes[..], frame.data());
        }
    }
}
