//! CANopen: identifiers, the EMCY frame and its codes, error control and the
//! monitors built on them (CiA 301, CiA 402, CiA 405; SPEC §2–§3).

mod emcy;
mod error_code;
mod error_control;
mod error_register;
mod guarding;
mod heartbeat;
mod nmt;
mod node_id;

pub use emcy::{Emcy, EmcyFrame, EMCY_LEN};
pub use error_code::{ErrorClass, ErrorCode};
pub use error_control::{millis_to_micros, ErrorControlConfig, ErrorControlMethod, Events, Micros};
pub use error_register::ErrorRegister;
pub use guarding::{
    AcceptedStates, GuardingEvent, GuardingEvents, LifeGuard, LifeGuardExpiry, NodeGuardingMaster,
};
pub use heartbeat::{
    ConsumerEntry, HeartbeatConsumer, HeartbeatEvent, HeartbeatEvents, HeartbeatProducer,
    MonitorState,
};
pub use nmt::{
    GuardAnswer, GuardAnswerFrame, Heartbeat, HeartbeatFrame, NmtState, GUARD_ANSWER_LEN,
    HEARTBEAT_LEN,
};
pub use node_id::{cob_id, CobFunction, NodeId, PdoDirection};
