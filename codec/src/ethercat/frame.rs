//! The EtherCAT header and the datagrams behind it: [`EthercatFrame`].

use core::fmt;

use super::datagram::Datagram;
use crate::error::check_len;
use crate::{LenError, What};

/// The EtherCAT header: 2 bytes, little-endian (ETG.1000.4 §5.4).
pub const ETHERCAT_HEADER_LEN: usize = 2;

/// What an EtherCAT frame carries: the type field of its header (4 bits;
/// ETG.1000.4 table 13; Wireshark's `ecatf.type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrameType {
    /// 1: EtherCAT datagrams (every master's cyclic and acyclic traffic).
    Datagrams,
    /// 2: ADS (Beckhoff's Automation Device Specification).
    Ads,
    /// 3: raw I/O.
    RawIo,
    /// 4: network variables.
    NetworkVariables,
    /// 5: mailbox gateway.
    MailboxGateway,
    /// Another value, reserved.
    Reserved(u8),
}

impl FrameType {
    /// Read the 4-bit type field.
    #[must_use]
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 0x0F {
            1 => FrameType::Datagrams,
            2 => FrameType::Ads,
            3 => FrameType::RawIo,
            4 => FrameType::NetworkVariables,
            5 => FrameType::MailboxGateway,
            other => FrameType::Reserved(other),
        }
    }

    /// Return the 4-bit type field.
    #[must_use]
    pub const fn bits(self) -> u8 {
        match self {
            FrameType::Datagrams => 1,
            FrameType::Ads => 2,
            FrameType::RawIo => 3,
            FrameType::NetworkVariables => 4,
            FrameType::MailboxGateway => 5,
            FrameType::Reserved(bits) => bits & 0x0F,
        }
    }

    /// Return the type's name as docs/ethercat.md writes it:
    /// `datagrams`, `ads`, `raw_io`, `network_variables`,
    /// `mailbox_gateway`, `reserved`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            FrameType::Datagrams => "datagrams",
            FrameType::Ads => "ads",
            FrameType::RawIo => "raw_io",
            FrameType::NetworkVariables => "network_variables",
            FrameType::MailboxGateway => "mailbox_gateway",
            FrameType::Reserved(_) => "reserved",
        }
    }
}

impl fmt::Display for FrameType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An EtherCAT frame: the header and the bytes it covers, a zero-copy view
/// (ETG.1000.4 §5.4; docs/ethercat.md#reading).
///
/// The header's length (11 bits) counts the bytes after the header that
/// belong to EtherCAT; Ethernet padding after them is not part of the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EthercatFrame<'a> {
    header: u16,
    body: &'a [u8],
}

impl<'a> EthercatFrame<'a> {
    /// Read the EtherCAT header at the start of `payload` (an
    /// [`EthercatLink::payload`](super::EthercatLink::payload)).
    ///
    /// # Errors
    ///
    /// [`LenError`] ([`What::EthercatHeader`]) when `payload` is shorter
    /// than the header, or than the header plus the length it announces
    /// (a damaged or truncated frame).
    pub fn parse(payload: &'a [u8]) -> Result<Self, LenError> {
        check_len(What::EthercatHeader, payload, ETHERCAT_HEADER_LEN)?;
        let header = u16::from_le_bytes([payload[0], payload[1]]);
        let length = usize::from(header & 0x07FF);
        check_len(What::EthercatFrame, payload, ETHERCAT_HEADER_LEN + length)?;
        Ok(EthercatFrame {
            header,
            body: &payload[ETHERCAT_HEADER_LEN..ETHERCAT_HEADER_LEN + length],
        })
    }

    /// Return the header's length field: the bytes of EtherCAT after the
    /// header.
    #[inline]
    #[must_use]
    pub const fn length(&self) -> u16 {
        self.header & 0x07FF
    }

    /// Return what the frame carries.
    #[inline]
    #[must_use]
    pub const fn frame_type(&self) -> FrameType {
        FrameType::from_bits((self.header >> 12) as u8)
    }

    /// Return the bytes the header's length covers.
    #[inline]
    #[must_use]
    pub const fn body(&self) -> &'a [u8] {
        self.body
    }

    /// Return the frame's datagrams, in order: nothing unless the frame
    /// carries [`FrameType::Datagrams`].
    #[must_use]
    pub fn datagrams(&self) -> Datagrams<'a> {
        let rest = if self.frame_type() == FrameType::Datagrams {
            self.body
        } else {
            &[]
        };
        Datagrams { rest, done: false }
    }
}

/// The datagrams of an [`EthercatFrame`], in order.
///
/// The list ends after a datagram whose more-follows flag is clear, or
/// when the frame's length is used up (ETG.1000.4 §5.4.1.2; Wireshark
/// reads on while the flag is set). A datagram whose length runs past the
/// frame is a [`LenError`] ([`What::EthercatDatagram`]), after which the
/// iterator ends: nothing behind it can be found.
#[derive(Debug, Clone)]
pub struct Datagrams<'a> {
    rest: &'a [u8],
    done: bool,
}

impl<'a> Iterator for Datagrams<'a> {
    type Item = Result<Datagram<'a>, LenError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done || self.rest.is_empty() {
            return None;
        }
        match Datagram::parse(self.rest) {
            Ok((datagram, rest)) => {
                self.rest = rest;
                self.done = !datagram.more_follows();
                Some(Ok(datagram))
            }
            Err(error) => {
                self.done = true;
                Some(Err(error))
            }
        }
    }
}

impl core::iter::FusedIterator for Datagrams<'_> {}
