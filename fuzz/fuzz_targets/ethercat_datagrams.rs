//! The EtherCAT wire views (docs/ethercat.md#reading):
//! `motionwire::ethercat::{Link, EthercatFrame, Datagram, MailboxHeader,
//! CoeHeader, CoeSdo, MailboxError}`.
//!
//! Arbitrary bytes → an Ethernet frame, and the same bytes as an EtherCAT
//! payload. Invariants:
//! - nothing panics; every view reads or returns a `LenError` whose
//!   `found` is less than its `expected` and whose message prints;
//! - a frame's datagrams lie within the bytes its header's length covers,
//!   one after another; after an error there is none;
//! - every datagram written back by `DatagramRepr::emit` is the same bytes
//!   but for the reserved bits of its length word, and reads back the same;
//! - the mailbox and CoE views of any bytes read or fail with a length
//!   error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motionwire::ethercat::{CoeHeader, CoeSdo, Datagram, DatagramRepr, EthercatFrame, Link, MailboxError, MailboxHeader};
use motionwire::LenError;

fn check(error: &LenError) {
    assert!(error.found < error.expected, "{error:?}");
    let _ = error.to_string();
}

fn frame(payload: &[u8]) {
    let frame = match EthercatFrame::parse(payload) {
        Ok(frame) => frame,
        Err(error) => return check(&error),
    };
    assert_eq!(frame.body().len(), usize::from(frame.length()));
    let mut used = 0;
    let mut failed = false;
    for datagram in frame.datagrams() {
        assert!(!failed, "a datagram after an error");
        match datagram {
            Ok(datagram) => {
                let bytes = datagram.as_bytes();
                assert_eq!(frame.body()[used..used + bytes.len()], *bytes);
                used += bytes.len();
                assert_eq!(datagram.data().len(), usize::from(datagram.length()));
                let repr = DatagramRepr::parse(&datagram);
                let mut buffer = vec![0; repr.buffer_len()];
                assert_eq!(repr.emit(&mut buffer).unwrap(), bytes.len());
                // The same bytes but for the length word's reserved bits.
                let mut expected = bytes.to_vec();
                expected[7] &= 0xC7;
                assert_eq!(buffer, expected);
                let (again, rest) = Datagram::parse(&buffer).unwrap();
                assert!(rest.is_empty());
                assert_eq!(DatagramRepr::parse(&again), repr);
                let _ = (datagram.command().to_string(), datagram.command().addressing());
                mailbox(datagram.data());
            }
            Err(error) => {
                check(&error);
                failed = true;
            }
        }
    }
    assert!(used <= frame.body().len());
}

fn mailbox(bytes: &[u8]) {
    let header = match MailboxHeader::parse(bytes) {
        Ok(header) => header,
        Err(error) => return check(&error),
    };
    let mut written = [0; 6];
    header.emit(&mut written).unwrap();
    assert_eq!(MailboxHeader::parse(&written).unwrap(), header);
    let body = match header.body(bytes) {
        Ok(body) => body,
        Err(error) => return check(&error),
    };
    if let Err(error) = MailboxError::parse(body).map(|e| e.to_string()) {
        check(&error);
    }
    match CoeHeader::parse(body) {
        Ok(coe) => {
            let _ = coe.service.name();
            if let Ok(sdo) = CoeSdo::parse(&body[2..]) {
                let _ = (sdo.multiplexer(), sdo.initiate_data(), sdo.segment_data(), sdo.abort_code());
            }
        }
        Err(error) => check(&error),
    }
}

fuzz_target!(|data: &[u8]| {
    match Link::parse(data) {
        Ok(Link::Ethercat(link)) => {
            assert!(link.payload.len() <= data.len());
            frame(link.payload);
        }
        Ok(Link::Other { .. }) => {}
        Err(error) => check(&error),
    }
    frame(data);
});
