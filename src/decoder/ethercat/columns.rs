//! The keys of a meaning's record that a table of records keeps in columns
//! of their own (the Python package's `ethercat_records`;
//! docs/ethercat.md#meanings).

use crate::canopen::{Emcy, ErrorCode, ErrorRegister, SdoAbortCode};
use crate::ethercat::{AlState, AlStatusCode, CoeSdo, CoeService, MailboxType};

use super::record::coe;
use super::{AlRegister, Meaning, MeaningRecord, SiiField};

/// What a meaning's record says in the keys a table keeps in columns of
/// their own ([`MeaningRecord::columns`]), each `None` where the record's
/// kind has no such key or its value is `null`; the same values as
/// [`MeaningRecord::append_json`] writes.
///
/// ```
/// use motionwire::can::LogEvent;
/// use motionwire::decoder::ethercat::{MeaningRecord, Session};
/// use motionwire::logs::{self, ReadLog};
///
/// // The synthetic AKD's fault: its CoE emergency, read at packet 456.
/// let mut log = logs::open("tests/data/ethercat/synthetic_akd_fault.pcapng").unwrap();
/// let mut session = Session::new();
/// let mut emergencies = Vec::new();
/// while let Some(record) = log.next_event() {
///     let record = record.unwrap();
///     let LogEvent::Ethercat(packet) = record.event else { continue };
///     let packet = session.read(record.position, &packet).unwrap();
///     for (at, datagram) in packet.datagrams().enumerate() {
///         let datagram = datagram.unwrap();
///         session.meanings(&packet, at, &datagram, |meaning| {
///             let record = MeaningRecord { packet: &packet, number: at + 1, meaning };
///             if record.kind() == "coe_emcy" {
///                 emergencies.push((packet.position.number(), record.columns()));
///             }
///         });
///     }
/// }
/// let (packet, columns) = emergencies[0];
/// assert_eq!(packet, 456);
/// assert_eq!(columns.emcy_code.map(|code| code.get()), Some(0x7305));
/// assert_eq!(columns.description, Some("Incremental sensor 1 fault"));
/// assert_eq!(columns.emcy_register.map(|r| r.bits()), Some(0x81));
/// assert_eq!(columns.written, Some(false));
/// assert_eq!(columns.state, None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeaningColumns {
    /// `al_state`: the register read or written (`register`).
    pub al_register: Option<AlRegister>,
    /// `al_state`: the state the bits name (`state`).
    pub state: Option<AlState>,
    /// `al_state`: AL status's error indicator, AL control's acknowledge
    /// (`error`).
    pub al_error: Option<bool>,
    /// `al_state`: the AL status code (`code`; `code_text` is its
    /// [`text`](AlStatusCode::text)).
    pub al_code: Option<AlStatusCode>,
    /// `sii`: the word address (`word`).
    pub sii_word: Option<u32>,
    /// `sii`: the double word read (`value`).
    pub sii_value: Option<u32>,
    /// `sii`: the identity field the word is (`field`).
    pub sii_field: Option<SiiField>,
    /// `mailbox`, `coe_sdo`, `coe_emcy`: written by the master (`direction`
    /// `write`) or read from the slave (`read`).
    pub written: Option<bool>,
    /// The mailbox message's type (`type`).
    pub mailbox_type: Option<MailboxType>,
    /// A CoE message's service (`service`).
    pub service: Option<CoeService>,
    /// `coe_sdo`: the object (`index`), not of a segment.
    pub index: Option<u16>,
    /// `coe_sdo`: the sub-index (`subindex`), not of a segment.
    pub subindex: Option<u8>,
    /// `coe_sdo`: an abort's code (`abort_code`; `abort` is its
    /// `Display`).
    pub abort_code: Option<SdoAbortCode>,
    /// `coe_emcy`: the emergency's error code (`code`).
    pub emcy_code: Option<ErrorCode>,
    /// `coe_emcy`: the error register (`register`).
    pub emcy_register: Option<ErrorRegister>,
    /// `coe_emcy`: the code's description (`description`).
    pub description: Option<&'static str>,
}

impl MeaningRecord<'_, '_> {
    /// Return the keys of the record that a table keeps in columns of
    /// their own ([`MeaningColumns`]).
    #[must_use]
    pub fn columns(&self) -> MeaningColumns {
        let mut c = MeaningColumns::default();
        match self.meaning {
            Meaning::StationAddress { .. }
            | Meaning::DlStatus { .. }
            | Meaning::ErrorCounters { .. }
            | Meaning::MailboxPoll { .. }
            | Meaning::MailboxRepeat { .. }
            | Meaning::StationAlias { .. }
            | Meaning::Dc { .. }
            | Meaning::DcDistribution { .. } => {}
            Meaning::AlState {
                register,
                status,
                code,
                ..
            } => {
                c.al_register = Some(register);
                c.state = status.and_then(|s| s.state());
                c.al_error = status.map(|s| s.error());
                c.al_code = code;
            }
            Meaning::BroadcastAlStatus { status, .. } => {
                c.al_register = Some(AlRegister::Status);
                c.state = status.state();
                c.al_error = Some(status.error());
            }
            Meaning::Sii { word, value, .. } => {
                c.sii_word = Some(word);
                c.sii_value = Some(value);
                c.sii_field = SiiField::at(word);
            }
            Meaning::Mailbox {
                written,
                header,
                body,
                ..
            } => {
                c.written = Some(written);
                c.mailbox_type = Some(header.mailbox_type);
                mailbox_columns(&mut c, header.mailbox_type, body);
            }
        }
        c
    }
}

/// The columns of what a mailbox message holds: a CoE service, an SDO's
/// object and abort, an emergency's code.
fn mailbox_columns(c: &mut MeaningColumns, mailbox_type: MailboxType, body: &[u8]) {
    let Some((service, rest)) = coe(mailbox_type, body) else {
        return;
    };
    c.service = Some(service);
    match service {
        CoeService::Emergency => {
            if let Ok(emcy) = Emcy::parse(rest) {
                c.emcy_code = Some(emcy.code);
                c.emcy_register = Some(emcy.register);
                c.description = Some(emcy.code.description());
            }
        }
        CoeService::SdoRequest | CoeService::SdoResponse => {
            if let Ok(sdo) = CoeSdo::parse(rest) {
                // A segment (command specifier 0) has no index.
                if let Some((index, sub)) = sdo.multiplexer().filter(|_| sdo.specifier() != 0) {
                    c.index = Some(index);
                    c.subindex = Some(sub);
                }
                c.abort_code = sdo.abort_code();
            }
        }
        _ => {}
    }
}
