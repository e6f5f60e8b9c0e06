//! SDO: service data objects, how a client reads and writes a device's
//! object dictionary (CiA 301 §7.2.4; docs/canopen.md#sdo).
//!
//! - [`frame`]: the request and response frames, every field of CiA 301
//!   (docs/canopen.md#sdo);
//! - [`tracker`]: the pure transfer tracker of one channel
//!   (docs/canopen.md#transfers);
//! - [`server`]: answering requests for the objects the crate owns, the
//!   error register 1001h and the pre-defined error field 1003h
//!   (docs/canopen.md#serving-1001h-and-1003h).

pub mod frame;
pub mod server;
pub mod tracker;

pub use frame::{
    BlockCrc, BlockSubcommand, SdoBlockSegment, SdoFields, SdoFrame, SdoInitiateData, SdoParty,
    SdoRequest, SdoResponse, SdoSegmentData, SdoService, BLKSIZE_MAX, SDO_LEN, SEGMENT_MAX,
};
pub use server::serve_error_objects;
pub use tracker::{
    BrokenReason, SdoEvent, SdoMessage, SdoOutcome, SdoTracker, SdoTransfer, TransferDirection,
    TransferMode,
};

#[cfg(test)]
mod tests;
