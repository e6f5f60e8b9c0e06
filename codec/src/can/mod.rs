//! CAN: the one frame vocabulary every part of the crate speaks
//! (ISO 11898-1; Linux `linux/can.h` and `linux/can/error.h`; docs/formats.md).
//!
//! - [`CanId`]: a standard (11-bit) or extended (29-bit) identifier.
//! - [`CanFrame`]: one frame — identifier, [`FrameType`] (data, remote
//!   request, CAN FD with its [`FdFlags`], error frame) and up to 64 data
//!   bytes — owned and `Copy`, or borrowed as [`CanFrameRef`].
//! - [`ErrorFrame`]: the classes and details of an error frame
//!   (docs/formats.md#error-frames).
//! - [`LogFrame`]: a frame as a log records it, with its [`Timestamp`],
//!   [`Iface`] and [`Direction`]: what every log reader yields.
//!
//! Every reader yields these types and the protocol layers above (CANopen)
//! decode them; this layer knows nothing of those protocols, so that layers
//! point one way. With the `embedded-can` feature a [`CanFrame`] is an
//! `embedded_can::Frame`. Because every layer above reads these types, a
//! new log source plugs in without touching the protocols above it.
//!
//! ```
//! use motionwire_codec::can::{CanFrame, CanId};
//!
//! // 705#05: one data byte on a standard identifier.
//! let frame = CanFrame::new(CanId::standard(0x705).unwrap(), &[0x05])?;
//! assert_eq!((frame.id().raw(), frame.data(), frame.dlc()), (0x705, &[0x05][..], 1));
//! assert!(!frame.is_extended() && !frame.is_rtr());
//!
//! // Nine bytes do not fit a classic frame: an error, not a panic.
//! assert!(CanFrame::new(CanId::standard(0x705).unwrap(), &[0; 9]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

#[cfg(feature = "alloc")]
mod bus_name;
#[cfg(feature = "embedded-can")]
mod embedded;
mod error_frame;
mod flags;
mod frame;
mod id;
mod log;
#[cfg(feature = "serde")]
mod serde_impls;
mod timestamp;

#[cfg(feature = "alloc")]
pub use bus_name::BusName;
pub use error_frame::{ControllerStatus, ErrorClasses, ErrorFrame};
pub use flags::{Direction, FdFlags};
pub use frame::{
    CanFrame, CanFrameRef, FrameData, FrameHeader, FrameType, CAN_ERR_FLAG, CLASSIC_MAX_LEN,
    FD_LENGTHS, FD_MAX_LEN,
};
pub use id::CanId;
pub use log::{BusStatus, EthercatPacket, Iface, LogEvent, LogFrame};
pub use timestamp::{Seconds, Timestamp, SECONDS_LEN};
