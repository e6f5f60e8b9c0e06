//! CANopen: identifiers, the EMCY frame and its codes, error control and the
//! monitors built on them, the CiA 402 drive state machine, PDO mappings and
//! the names of object-dictionary entries (CiA 301, CiA 402, CiA 405,
//! CiA 406; docs/canopen.md).
//!
//! Each submodule holds one frame, register or state machine and documents
//! its decisions; the types are re-exported here.

pub mod cia402;
pub mod data_type;
#[cfg(feature = "embedded-can")]
mod embedded;
pub mod emcy;
pub mod emcy_producer;
pub mod error_code;
pub mod error_control;
pub mod error_history;
pub mod error_register;
pub mod guarding;
pub mod heartbeat;
pub mod message;
pub mod nmt;
pub mod nmt_command;
pub mod node_id;
pub mod object_address;
pub mod objects;
pub mod pdo;
pub mod recv_emcy;
pub mod sdo;
pub mod sdo_abort;
pub mod time_of_day;

pub use cia402::{
    Cia402Command, Cia402DriveEvent, Cia402State, Cia402Transition, Controlword, ModeOfOperation,
    Statusword,
};
pub use data_type::{DataType, Octets, Value, ValueKind, MAX_OCTETS};
pub use emcy::{Emcy, EmcyFrame, EMCY_LEN};
pub use emcy_producer::{
    ActiveError, EmcyEvent, EmcyOutcome, EmcyProducer, EmcyTransition, ErrorCondition,
    IgnoredEvent, DEFAULT_ACTIVE_ERRORS,
};
pub use error_code::{Description, DescriptionSource, ErrorClass, ErrorCode, Specificity};
pub use error_control::{ErrorControlConfig, ErrorControlMethod, Events};
pub use error_history::{ErrorHistory, ErrorHistoryEntry, DEFAULT_ERROR_HISTORY_LEN};
pub use error_register::ErrorRegister;
pub use guarding::{
    AcceptedStates, GuardingEvent, GuardingEvents, LifeGuard, LifeGuardExpiry, NodeGuardingMaster,
};
pub use heartbeat::{
    ConsumerEntry, HeartbeatConsumer, HeartbeatEvent, HeartbeatEvents, HeartbeatProducer,
    MonitorState, DEFAULT_CONSUMER_ENTRIES,
};
pub use message::{CanOpenMessage, DecodeError, MessageKind, NmtStateByte, PartialEmcy};
pub use nmt::{
    GuardAnswer, GuardAnswerFrame, Heartbeat, HeartbeatFrame, NmtState, GUARD_ANSWER_LEN,
    HEARTBEAT_LEN,
};
pub use nmt_command::{NmtCommand, NmtNodeControl, NmtNodeControlFrame, NMT_NODE_CONTROL_LEN};
pub use node_id::{cob_id, CobFunction, NodeId, PdoDirection};
pub use object_address::{ObjectAddress, SubNotation};
pub use objects::{
    find_object, object_data_type, object_instance, object_name, ObjectDataType, ObjectName,
    ObjectSet, OBJECT_DATA_TYPES, OBJECT_NAMES,
};
pub use pdo::{
    ByLength, EventTimer, InhibitTime, LayoutSignals, MappingEntry, PdoCobId, PdoCommunication,
    PdoEntryError, PdoEntryReason, PdoLayout, PdoMapping, PdoPackError, Signal, Signals,
    TransmissionKind, TransmissionType, TypeLookup, CLASSIC_PDO_BITS, MAX_MAPPING_ENTRIES,
    MAX_PDO_BITS,
};
pub use recv_emcy::{
    DeviceSet, EmcyStorage, KernelError, RecvEmcy, RecvEmcyDevOutputs, RecvEmcyOutputs,
    RecvEmcyResult, SlotUpdate,
};
pub use sdo_abort::SdoAbortCode;
pub use time_of_day::{TimeOfDay, TIME_OF_DAY_LEN};
