//! SDO frames: the 8 data bytes of a request (client → server, COB-ID
//! 0x600 + node) or a response (server → client, 0x580 + node)
//! (CiA 301 §7.2.4.3; docs/canopen.md#sdo).
//!
//! [`SdoFrame`] is the zero-copy view over the bytes, with the fields every
//! service shares; [`SdoRequest`], [`SdoResponse`] and [`SdoBlockSegment`]
//! are the owned values, each with `parse` and `to_bytes`. A segment inside
//! a block transfer cannot be told from a request or response by its bytes
//! alone: [`SdoTracker`](super::SdoTracker) knows when one is due.
//!
//! The module's files: `view.rs` ([`SdoFrame`] and [`SdoFields`]),
//! `data.rs` (what initiate and segment frames carry), `request.rs`,
//! `response.rs`, and `block.rs` (block sub-commands, segments and the
//! CRC); here, the byte offsets they all share (`mod field`), a frame's
//! sender and service, and the command-byte helpers. The multiplexer of
//! a frame is an [`ObjectAddress`].
//!
//! ```
//! use motionwire_codec::canopen::sdo::{SdoInitiateData, SdoRequest, SdoResponse};
//! use motionwire_codec::canopen::ObjectAddress;
//!
//! // A client reads 1008h sub 0 (manufacturer device name)…
//! let request = SdoRequest::InitiateUpload { multiplexer: ObjectAddress::new(0x1008, 0) };
//! assert_eq!(request.to_bytes(), [0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]);
//! assert_eq!(SdoRequest::parse(&request.to_bytes())?, request);
//!
//! // …and the server answers "segmented, 10 bytes follow".
//! let response = SdoResponse::parse(&[0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0])?;
//! assert_eq!(response, SdoResponse::InitiateUpload {
//!     multiplexer: ObjectAddress::new(0x1008, 0),
//!     data: SdoInitiateData::Segmented { size: Some(10) },
//! });
//!
//! // A short frame is an error that says how short, never a panic.
//! assert!(SdoResponse::parse(&[0x41, 0x08, 0x10]).is_err());
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

#[cfg(doc)]
use crate::canopen::ObjectAddress;

mod block;
mod common;
mod data;
mod layout;
mod party;
mod request;
mod response;
mod view;

pub use block::{BlockCrc, SdoBlockSegment};
pub use data::{SdoInitiateData, SdoSegmentData};
pub(super) use layout::{field, segment_unused, CRC_SUPPORTED, LAST, TOGGLE};
pub use layout::{BLKSIZE_MAX, SDO_LEN, SEGMENT_MAX};
pub use party::{BlockSubcommand, SdoParty, SdoService};
pub use request::SdoRequest;
pub use response::SdoResponse;
pub use view::{SdoFields, SdoFrame};
