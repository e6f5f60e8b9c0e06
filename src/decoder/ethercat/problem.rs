//! What is wrong with a slave's configuration or its mailbox, as a
//! capture shows it ([`ImageError`], [`ImageProblem`];
//! docs/ethercat.md#process-data).

use super::slave::SlaveRef;

/// What is wrong with a slave's configuration or its mailbox, as the
/// capture shows it (docs/ethercat.md#process-data): said with the packet
/// where it shows, and the capture read on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ImageError {
    /// A PDO of a sync manager ends past the sync manager: its signals and
    /// those after it are not read, the bytes are shown.
    #[error(
        "PDO {pdo:#06x} of sync manager {sm} ends at bit {end_bit}, past the sync manager's {len} bytes: its signals are not read"
    )]
    MappingPastSyncManager {
        /// The sync manager.
        sm: u8,
        /// The PDO's mapping object.
        pdo: u16,
        /// Where the PDO would end, in bits from the sync manager's start.
        end_bit: u32,
        /// The sync manager's length.
        len: u16,
    },
    /// Two slaves' FMMUs write the same logical bytes: each is cut as its
    /// own FMMUs say, but one slave's outputs are the other's.
    #[error("its outputs at logical {start:#010x}..{end:#010x} overlap the outputs of {other}")]
    OverlappingFmmus {
        /// The other slave.
        other: SlaveRef,
        /// The first logical address both map.
        start: u32,
        /// The end of the overlap (exclusive).
        end: u32,
    },
    /// A mailbox message's header announces more bytes than its sync
    /// manager holds.
    #[error("a mailbox message of {length} bytes is longer than its sync manager's {room} bytes")]
    MailboxPastSyncManager {
        /// The header's length.
        length: u16,
        /// The bytes the sync manager holds after the header.
        room: u16,
    },
    /// A CoE SDO transfer of a PDO object announces more data than such an
    /// object holds (sub-index 0 and 64 entries): the rest is not kept.
    #[error("an SDO transfer of {index:#06x}:{sub_index:02x} announces {size} bytes, more than a PDO object holds")]
    SdoSizePastObject {
        /// The object.
        index: u16,
        /// The sub-index.
        sub_index: u8,
        /// The size announced.
        size: u32,
    },
}

/// A problem of a slave's configuration or mailbox, where it shows
/// ([`Session::problems`](super::Session::take_problems)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("packet {position}: {slave}: {error}")]
pub struct ImageProblem {
    /// The packet.
    pub position: crate::logs::Position,
    /// The slave.
    pub slave: SlaveRef,
    /// What is wrong.
    pub error: ImageError,
}
