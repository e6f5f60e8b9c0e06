//! CANopen: identifiers, the EMCY frame and its codes, error control and the
//! monitors built on them (CiA 301, CiA 402, CiA 405; SPEC §2–§3).

mod emcy;
mod error_code;
mod error_register;
mod node_id;
mod recv_emcy;

pub use emcy::{Emcy, EmcyFrame, EMCY_LEN};
pub use error_code::{Description, DescriptionSource, ErrorClass, ErrorCode, Specificity};
pub use error_register::ErrorRegister;
pub use node_id::{cob_id, CobFunction, NodeId, PdoDirection};
pub use recv_emcy::{
    DeviceSet, EmcyStorage, KernelError, RecvEmcy, RecvEmcyDevOutputs, RecvEmcyOutputs,
    RecvEmcyResult, SlotUpdate,
};
