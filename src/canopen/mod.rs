//! CANopen: identifiers, the EMCY frame and its codes, error control and the
//! monitors built on them (CiA 301, CiA 402, CiA 405; SPEC §2–§3).

mod emcy;
mod emcy_producer;
mod error_code;
mod error_history;
mod error_register;
mod node_id;
mod sdo_abort;

pub use emcy::{Emcy, EmcyFrame, EMCY_LEN};
pub use emcy_producer::{
    ActiveError, EmcyEvent, EmcyOutcome, EmcyProducer, EmcyTransition, ErrorCondition,
    IgnoredEvent, DEFAULT_ACTIVE_ERRORS,
};
pub use error_code::{ErrorClass, ErrorCode};
pub use error_history::{ErrorHistory, ErrorHistoryEntry, DEFAULT_ERROR_HISTORY_LEN};
pub use error_register::ErrorRegister;
pub use node_id::{cob_id, CobFunction, NodeId, PdoDirection};
pub use sdo_abort::SdoAbortCode;
