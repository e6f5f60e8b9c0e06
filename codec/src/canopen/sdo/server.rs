//! Answering SDO requests for the objects the crate owns: the error
//! register 1001h and the pre-defined error field 1003h
//! (docs/canopen.md#serving-1001h-and-1003h, docs/canopen.md#error-history; CiA
//! 301 §7.5.2.2, §7.5.2.3).
//!
//! A device firmware that keeps its error state with the crate's
//! [`ErrorHistory`] and [`ErrorRegister`] passes each request frame to
//! [`serve_error_objects`] and sends the response it returns.
//!
//! ```
//! use motionwire_codec::canopen::sdo::{serve_error_objects, SdoRequest, SdoResponse, SdoInitiateData};
//! use motionwire_codec::canopen::ObjectAddress;
//! use motionwire_codec::canopen::{Emcy, ErrorCode, ErrorHistory, ErrorRegister, SdoAbortCode};
//!
//! let register = ErrorRegister::GENERIC | ErrorRegister::COMMUNICATION;
//! let mut history: ErrorHistory = ErrorHistory::new();
//! history.record(&Emcy::new(ErrorCode::new(0x8130), register, [0; 5]));
//!
//! // Read 1003h.00: one entry.
//! let read = SdoRequest::InitiateUpload { multiplexer: ObjectAddress::new(0x1003, 0) };
//! let answer = serve_error_objects(&read.to_bytes(), &mut history, register);
//! assert_eq!(answer.map(|b| b[..5].to_vec()), Some(vec![0x4F, 0x03, 0x10, 0x00, 1]));
//!
//! // Clear it by writing 0 to sub-index 0.
//! let clear = SdoRequest::InitiateDownload {
//!     multiplexer: ObjectAddress::new(0x1003, 0),
//!     data: SdoInitiateData::expedited(&[0]).unwrap(),
//! };
//! let answer = serve_error_objects(&clear.to_bytes(), &mut history, register).unwrap();
//! assert_eq!(SdoResponse::parse(&answer)?, SdoResponse::InitiateDownload {
//!     multiplexer: ObjectAddress::new(0x1003, 0),
//! });
//! assert_eq!(history.read(0), Ok(0));
//!
//! // Any other object: "object does not exist".
//! let other = SdoRequest::InitiateUpload { multiplexer: ObjectAddress::new(0x6041, 0) };
//! let answer = serve_error_objects(&other.to_bytes(), &mut history, register).unwrap();
//! assert!(matches!(SdoResponse::parse(&answer)?,
//!     SdoResponse::Abort { code: SdoAbortCode::OBJECT_DOES_NOT_EXIST, .. }));
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use super::frame::{SdoInitiateData, SdoRequest, SdoResponse, SDO_LEN};
use crate::canopen::{ErrorHistory, ErrorRegister, ObjectAddress, SdoAbortCode};

/// The error register (CiA 301 §7.5.2.2).
pub const ERROR_REGISTER_INDEX: u16 = 0x1001;
/// The pre-defined error field (CiA 301 §7.5.2.3).
pub const ERROR_HISTORY_INDEX: u16 = 0x1003;

/// Answer one SDO request frame for the objects 1001h and 1003h
/// (docs/canopen.md#serving-1001h-and-1003h): the response frame to send, or
/// `None` when no answer is due (an abort from the client, or a frame too short
/// to be a request).
///
/// - An upload of 1001h.00 answers the register (UNSIGNED8); of 1003h any
///   sub-index: sub-index 0 the count (UNSIGNED8), 1..=N the entries
///   (UNSIGNED32), expedited with the size indicated.
/// - A download of 0 to 1003h.00 clears the history.
/// - Everything [`ErrorHistory::read`] and [`ErrorHistory::write`] refuse is
///   aborted with their codes (docs/canopen.md#error-history); writing 1001h
///   is [`SdoAbortCode::WRITE_OF_READ_ONLY`], a sub-index other than 0 of
///   1001h [`SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST`]; any other object
///   [`SdoAbortCode::OBJECT_DOES_NOT_EXIST`] (0x0602_0000).
///
/// **Decisions**: both objects fit in 4 bytes, so the server answers only
/// expedited: a segmented download initiate or a block initiate to them is
/// aborted with [`SdoAbortCode::UNSUPPORTED_ACCESS`]; a download with more
/// data than the entry (more than 1 byte for sub-index 0) with
/// [`SdoAbortCode::LENGTH_TOO_HIGH`]; an expedited download without a size
/// is read as the four bytes it carries. A segment, block segment or other
/// frame outside a transfer is aborted with
/// [`SdoAbortCode::INVALID_COMMAND_SPECIFIER`] (there is no transfer for it
/// to belong to), with multiplexer 0000h.00.
#[must_use]
pub fn serve_error_objects<const N: usize>(
    request: &[u8],
    history: &mut ErrorHistory<N>,
    register: ErrorRegister,
) -> Option<[u8; SDO_LEN]> {
    let request = SdoRequest::parse(request).ok()?;
    let abort = |multiplexer, code| Some(SdoResponse::Abort { multiplexer, code }.to_bytes());
    let (multiplexer, download) = match request {
        SdoRequest::Abort { .. } => return None,
        SdoRequest::InitiateUpload { multiplexer } => (multiplexer, None),
        SdoRequest::InitiateDownload { multiplexer, data } => (multiplexer, Some(data)),
        SdoRequest::BlockUploadInitiate { multiplexer, .. }
        | SdoRequest::BlockDownloadInitiate { multiplexer, .. } => {
            return abort(
                multiplexer,
                owned_or(multiplexer, SdoAbortCode::UNSUPPORTED_ACCESS),
            );
        }
        _ => {
            return abort(
                ObjectAddress::default(),
                SdoAbortCode::INVALID_COMMAND_SPECIFIER,
            )
        }
    };
    let ObjectAddress {
        index,
        sub_index: subindex,
    } = multiplexer;
    if index != ERROR_REGISTER_INDEX && index != ERROR_HISTORY_INDEX {
        return abort(multiplexer, SdoAbortCode::OBJECT_DOES_NOT_EXIST);
    }
    match download {
        None => {
            let read = if index == ERROR_REGISTER_INDEX {
                if subindex == 0 {
                    Ok((u32::from(register.bits()), 1))
                } else {
                    Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST)
                }
            } else {
                history
                    .read(subindex)
                    .map(|value| (value, if subindex == 0 { 1 } else { 4 }))
            };
            match read {
                Ok((value, len)) => {
                    let data = SdoInitiateData::expedited(&value.to_le_bytes()[..len])?;
                    Some(SdoResponse::InitiateUpload { multiplexer, data }.to_bytes())
                }
                Err(code) => abort(multiplexer, code),
            }
        }
        Some(data) => {
            if index == ERROR_REGISTER_INDEX {
                let code = if subindex == 0 {
                    SdoAbortCode::WRITE_OF_READ_ONLY
                } else {
                    SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST
                };
                return abort(multiplexer, code);
            }
            let SdoInitiateData::Expedited { .. } = data else {
                return abort(multiplexer, SdoAbortCode::UNSUPPORTED_ACCESS);
            };
            let bytes = data.data();
            if subindex == 0 && data.size().is_some_and(|len| len > 1) {
                return abort(multiplexer, SdoAbortCode::LENGTH_TOO_HIGH);
            }
            let mut value = [0u8; 4];
            value[..bytes.len()].copy_from_slice(bytes);
            match history.write(subindex, u32::from_le_bytes(value)) {
                Ok(()) => Some(SdoResponse::InitiateDownload { multiplexer }.to_bytes()),
                Err(code) => abort(multiplexer, code),
            }
        }
    }
}

/// The abort for a block transfer: the object's own refusal first (it does
/// not exist), else `code`.
fn owned_or(multiplexer: ObjectAddress, code: SdoAbortCode) -> SdoAbortCode {
    if multiplexer.index == ERROR_REGISTER_INDEX || multiplexer.index == ERROR_HISTORY_INDEX {
        code
    } else {
        SdoAbortCode::OBJECT_DOES_NOT_EXIST
    }
}
