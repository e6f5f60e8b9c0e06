//! The mailbox header and the mailbox error message: [`MailboxHeader`],
//! [`MailboxError`].

use core::fmt;

use crate::error::check_len;
use crate::{LenError, What};

/// The mailbox header: length (2), address (2), channel and priority (1),
/// type and counter (1) (ETG.1000.6 §5.6, table 29).
pub const MAILBOX_HEADER_LEN: usize = 6;

/// A mailbox protocol: the header's type (4 bits; ETG.1000.6 table 29).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MailboxType {
    /// 0: a mailbox error reply.
    Error,
    /// 1: ADS over EtherCAT.
    Aoe,
    /// 2: Ethernet over EtherCAT.
    Eoe,
    /// 3: CANopen over EtherCAT.
    Coe,
    /// 4: File access over EtherCAT.
    Foe,
    /// 5: Servo drive profile over EtherCAT.
    Soe,
    /// 15: Vendor specific.
    Voe,
    /// Another value, reserved.
    Reserved(u8),
}

impl MailboxType {
    /// Read the 4-bit type.
    #[must_use]
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 0x0F {
            0 => MailboxType::Error,
            1 => MailboxType::Aoe,
            2 => MailboxType::Eoe,
            3 => MailboxType::Coe,
            4 => MailboxType::Foe,
            5 => MailboxType::Soe,
            15 => MailboxType::Voe,
            other => MailboxType::Reserved(other),
        }
    }

    /// Return the 4-bit type.
    #[must_use]
    pub const fn bits(self) -> u8 {
        match self {
            MailboxType::Error => 0,
            MailboxType::Aoe => 1,
            MailboxType::Eoe => 2,
            MailboxType::Coe => 3,
            MailboxType::Foe => 4,
            MailboxType::Soe => 5,
            MailboxType::Voe => 15,
            MailboxType::Reserved(bits) => bits & 0x0F,
        }
    }

    /// Return the type's name as docs/ethercat.md writes it: `error`,
    /// `aoe`, `eoe`, `coe`, `foe`, `soe`, `voe`, `reserved`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            MailboxType::Error => "error",
            MailboxType::Aoe => "aoe",
            MailboxType::Eoe => "eoe",
            MailboxType::Coe => "coe",
            MailboxType::Foe => "foe",
            MailboxType::Soe => "soe",
            MailboxType::Voe => "voe",
            MailboxType::Reserved(_) => "reserved",
        }
    }
}

impl fmt::Display for MailboxType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A mailbox message's header (ETG.1000.6 §5.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MailboxHeader {
    /// The bytes of the message after the header.
    pub length: u16,
    /// The station address of the source (a slave's reply) or destination;
    /// 0 from and to the master.
    pub address: u16,
    /// The channel (6 bits, reserved: 0).
    pub channel: u8,
    /// The priority (2 bits).
    pub priority: u8,
    /// The protocol.
    pub mailbox_type: MailboxType,
    /// The counter (3 bits): 1–7 counting, 0 where the master does not
    /// count (IgH); a repeated message keeps its counter.
    pub counter: u8,
}

impl MailboxHeader {
    /// Read the header at the start of `bytes`.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::MailboxHeader`]) when `bytes` is shorter than
    /// 6 bytes.
    pub fn parse(bytes: &[u8]) -> Result<Self, LenError> {
        check_len(What::MailboxHeader, bytes, MAILBOX_HEADER_LEN)?;
        Ok(MailboxHeader {
            length: u16::from_le_bytes([bytes[0], bytes[1]]),
            address: u16::from_le_bytes([bytes[2], bytes[3]]),
            channel: bytes[4] & 0x3F,
            priority: bytes[4] >> 6,
            mailbox_type: MailboxType::from_bits(bytes[5]),
            counter: (bytes[5] >> 4) & 0x07,
        })
    }

    /// Write the header into the first 6 bytes of `buffer`.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::MailboxHeader`]) when `buffer` is shorter than
    /// 6 bytes.
    pub fn emit(&self, buffer: &mut [u8]) -> Result<(), LenError> {
        check_len(What::MailboxHeader, buffer, MAILBOX_HEADER_LEN)?;
        buffer[0..2].copy_from_slice(&self.length.to_le_bytes());
        buffer[2..4].copy_from_slice(&self.address.to_le_bytes());
        buffer[4] = (self.channel & 0x3F) | (self.priority << 6);
        buffer[5] = self.mailbox_type.bits() | ((self.counter & 0x07) << 4);
        Ok(())
    }

    /// Return the message's body (after the header) in `bytes`, a message
    /// read from a mailbox area, when the area holds all of it.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::MailboxMessage`]) when the header's length
    /// runs past `bytes`.
    pub fn body<'a>(&self, bytes: &'a [u8]) -> Result<&'a [u8], LenError> {
        let end = MAILBOX_HEADER_LEN + usize::from(self.length);
        check_len(What::MailboxMessage, bytes, end)?;
        Ok(&bytes[MAILBOX_HEADER_LEN..end])
    }
}

/// A mailbox error reply (type 0): the service 0x0001 and a detail code
/// (ETG.1000.6 table 30; SOEM's `ec_mbxerrorlist`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MailboxError {
    /// The service type, 0x0001 for a mailbox command error.
    pub service: u16,
    /// The detail code, 1–8.
    pub detail: u16,
}

impl MailboxError {
    /// Read a mailbox error from the message's body.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::MailboxError`]) when the body is shorter than
    /// 4 bytes.
    pub fn parse(body: &[u8]) -> Result<Self, LenError> {
        check_len(What::MailboxError, body, 4)?;
        Ok(MailboxError {
            service: u16::from_le_bytes([body[0], body[1]]),
            detail: u16::from_le_bytes([body[2], body[3]]),
        })
    }

    /// Return the detail code's text, `None` for a code the table does
    /// not define.
    #[must_use]
    pub const fn text(self) -> Option<&'static str> {
        Some(match self.detail {
            1 => "Syntax of the mailbox header is wrong",
            2 => "The mailbox protocol is not supported",
            3 => "Channel field contains a wrong value",
            4 => "The service is not supported",
            5 => "Invalid mailbox header",
            6 => "Length of received mailbox data is too short",
            7 => "No more memory in slave",
            8 => "The length of data is inconsistent",
            _ => return None,
        })
    }
}

impl fmt::Display for MailboxError {
    /// `mailbox error 0x0006 Length of received mailbox data is too short`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "mailbox error {:#06x} {}",
            self.detail,
            self.text().unwrap_or("unknown")
        )
    }
}
