//! CANopen over EtherCAT: the CoE header ([`CoeHeader`]) and SDO messages
//! ([`CoeSdo`]). A CoE emergency is the CiA 301 EMCY of
//! [`crate::canopen::Emcy`] after the header.

use core::fmt;

use crate::canopen::SdoAbortCode;
use crate::error::check_len;
use crate::{LenError, What};

/// The CoE header: number (9 bits), reserved (3), service (4)
/// (ETG.1000.6 §5.6.2, table 31).
pub const COE_HEADER_LEN: usize = 2;

/// A CoE service (ETG.1000.6 table 31).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CoeService {
    /// 1: emergency.
    Emergency,
    /// 2: SDO request.
    SdoRequest,
    /// 3: SDO response.
    SdoResponse,
    /// 4: TxPDO.
    TxPdo,
    /// 5: RxPDO.
    RxPdo,
    /// 6: TxPDO remote request.
    TxPdoRemoteRequest,
    /// 7: RxPDO remote request.
    RxPdoRemoteRequest,
    /// 8: SDO information.
    SdoInformation,
    /// Another value, reserved.
    Reserved(u8),
}

impl CoeService {
    /// Read the 4-bit service.
    #[must_use]
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 0x0F {
            1 => CoeService::Emergency,
            2 => CoeService::SdoRequest,
            3 => CoeService::SdoResponse,
            4 => CoeService::TxPdo,
            5 => CoeService::RxPdo,
            6 => CoeService::TxPdoRemoteRequest,
            7 => CoeService::RxPdoRemoteRequest,
            8 => CoeService::SdoInformation,
            other => CoeService::Reserved(other),
        }
    }

    /// Return the 4-bit service.
    #[must_use]
    pub const fn bits(self) -> u8 {
        match self {
            CoeService::Emergency => 1,
            CoeService::SdoRequest => 2,
            CoeService::SdoResponse => 3,
            CoeService::TxPdo => 4,
            CoeService::RxPdo => 5,
            CoeService::TxPdoRemoteRequest => 6,
            CoeService::RxPdoRemoteRequest => 7,
            CoeService::SdoInformation => 8,
            CoeService::Reserved(bits) => bits & 0x0F,
        }
    }

    /// Return the service's name as docs/ethercat.md writes it:
    /// `emergency`, `sdo_request`, `sdo_response`, `txpdo`, `rxpdo`,
    /// `txpdo_rtr`, `rxpdo_rtr`, `sdo_information`, `reserved`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            CoeService::Emergency => "emergency",
            CoeService::SdoRequest => "sdo_request",
            CoeService::SdoResponse => "sdo_response",
            CoeService::TxPdo => "txpdo",
            CoeService::RxPdo => "rxpdo",
            CoeService::TxPdoRemoteRequest => "txpdo_rtr",
            CoeService::RxPdoRemoteRequest => "rxpdo_rtr",
            CoeService::SdoInformation => "sdo_information",
            CoeService::Reserved(_) => "reserved",
        }
    }
}

impl fmt::Display for CoeService {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The CoE header of a mailbox message of type CoE.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CoeHeader {
    /// The number (9 bits): the PDO number of a PDO service, else 0.
    pub number: u16,
    /// The service.
    pub service: CoeService,
}

impl CoeHeader {
    /// Read the header at the start of a CoE message's body.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::CoeHeader`]) when `bytes` is shorter than 2
    /// bytes.
    pub fn parse(bytes: &[u8]) -> Result<Self, LenError> {
        check_len(What::CoeHeader, bytes, COE_HEADER_LEN)?;
        let word = u16::from_le_bytes([bytes[0], bytes[1]]);
        Ok(CoeHeader {
            number: word & 0x01FF,
            service: CoeService::from_bits((word >> 12) as u8),
        })
    }

    /// Write the header into the first 2 bytes of `buffer`.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::CoeHeader`]) when `buffer` is shorter than 2
    /// bytes.
    pub fn emit(&self, buffer: &mut [u8]) -> Result<(), LenError> {
        check_len(What::CoeHeader, buffer, COE_HEADER_LEN)?;
        let word = (self.number & 0x01FF) | (u16::from(self.service.bits()) << 12);
        buffer[..2].copy_from_slice(&word.to_le_bytes());
        Ok(())
    }
}

/// A CoE SDO message (service 2 or 3) after its CoE header, a zero-copy
/// view: the CiA 301 command byte, then — except in a segment — index and
/// sub-index, then data (ETG.1000.6 §5.6.2.1–5.6.2.6).
///
/// Which fields a message has depends on its command specifier and its
/// direction (a segment has no index): the view gives each field where
/// the bytes hold it and leaves the reading to the session, as
/// docs/ethercat.md#coe-sdo describes. A response of only command, index
/// and sub-index (older slaves answer a download so) still gives them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CoeSdo<'a> {
    bytes: &'a [u8],
}

impl<'a> CoeSdo<'a> {
    /// The command byte's complete-access flag (bit 4 of an initiate
    /// command).
    pub const COMPLETE_ACCESS: u8 = 0x10;

    /// View the bytes after a CoE header as an SDO message.
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::CoeSdo`]) when `bytes` is empty.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, LenError> {
        check_len(What::CoeSdo, bytes, 1)?;
        Ok(CoeSdo { bytes })
    }

    /// Return the command byte.
    #[inline]
    #[must_use]
    pub const fn command(&self) -> u8 {
        self.bytes[0]
    }

    /// Return the command specifier (the command byte's top 3 bits).
    #[inline]
    #[must_use]
    pub const fn specifier(&self) -> u8 {
        self.bytes[0] >> 5
    }

    /// Return whether the complete-access flag is set.
    #[inline]
    #[must_use]
    pub const fn complete_access(&self) -> bool {
        self.bytes[0] & Self::COMPLETE_ACCESS != 0
    }

    /// Return index and sub-index, when the message is long enough to hold
    /// them (every message but a segment does).
    #[must_use]
    pub const fn multiplexer(&self) -> Option<(u16, u8)> {
        if self.bytes.len() < 4 {
            return None;
        }
        Some((
            u16::from_le_bytes([self.bytes[1], self.bytes[2]]),
            self.bytes[3],
        ))
    }

    /// Return the bytes after command, index and sub-index: the expedited
    /// data or the complete size of an initiate message, and any data after
    /// it.
    #[must_use]
    pub fn initiate_data(&self) -> &'a [u8] {
        self.bytes.get(4..).unwrap_or(&[])
    }

    /// Return the bytes after the command byte: a segment's data.
    #[must_use]
    pub fn segment_data(&self) -> &'a [u8] {
        &self.bytes[1..]
    }

    /// Return the abort code of an abort message (command specifier 4,
    /// from either side), when the message holds it.
    #[must_use]
    pub fn abort_code(&self) -> Option<SdoAbortCode> {
        if self.specifier() != 4 {
            return None;
        }
        let code = self.bytes.get(4..8)?;
        Some(SdoAbortCode::new(u32::from_le_bytes([
            code[0], code[1], code[2], code[3],
        ])))
    }

    /// Return the message's bytes, from the command byte on.
    #[inline]
    #[must_use]
    pub const fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }
}
