//! The EtherCAT views on hand-written frames, and on arbitrary bytes.

use proptest::prelude::*;

use super::*;
use crate::canopen::Emcy;
use crate::What;

/// A TwinCAT frame as sent: `00:01:05:…` source, two datagrams (APRD of
/// AL status at position 0 for 6 bytes, then an LRW of 4 bytes at
/// 0x01000000).
fn twincat_sent() -> [u8; 14 + 2 + 18 + 16] {
    let mut packet = [0u8; 14 + 2 + 18 + 16];
    packet[..6].copy_from_slice(&[0xff; 6]);
    packet[6..12].copy_from_slice(&[0x00, 0x01, 0x05, 0x11, 0x22, 0x33]);
    packet[12..14].copy_from_slice(&[0x88, 0xa4]);
    packet[14..16].copy_from_slice(&((18u16 + 16) | 0x1000).to_le_bytes());
    let first = DatagramRepr {
        command: Command::Aprd,
        index: 0x41,
        address: 0x0130_0000,
        circulating: false,
        more_follows: true,
        irq: 0,
        data: &[0; 6],
        working_counter: 0,
    };
    let second = DatagramRepr {
        command: Command::Lrw,
        index: 0x42,
        address: 0x0100_0000,
        circulating: false,
        more_follows: false,
        irq: 0,
        data: &[1, 2, 3, 4],
        working_counter: 0,
    };
    assert_eq!(first.emit(&mut packet[16..]).unwrap(), 18);
    assert_eq!(second.emit(&mut packet[34..]).unwrap(), 16);
    packet
}

#[test]
fn a_frame_reads_field_by_field() {
    let packet = twincat_sent();
    let Link::Ethercat(link) = Link::parse(&packet).unwrap() else {
        panic!("EtherCAT")
    };
    assert_eq!(link.source.to_string(), "00:01:05:11:22:33");
    assert!(!link.returned_bit());
    assert_eq!(link.encapsulation, Encapsulation::Ethernet);
    let frame = EthercatFrame::parse(link.payload).unwrap();
    assert_eq!(frame.length(), 34);
    assert_eq!(frame.frame_type(), FrameType::Datagrams);
    let datagrams: Vec<_> = frame.datagrams().map(Result::unwrap).collect();
    assert_eq!(datagrams.len(), 2);
    let [aprd, lrw] = [datagrams[0], datagrams[1]];
    assert_eq!(aprd.command(), Command::Aprd);
    assert_eq!(aprd.command().addressing(), Addressing::Position);
    assert_eq!((aprd.index(), aprd.adp(), aprd.ado()), (0x41, 0, 0x0130));
    assert_eq!(aprd.length(), 6);
    assert!(aprd.more_follows() && !aprd.circulating());
    assert_eq!(lrw.command().to_string(), "LRW");
    assert_eq!(lrw.address(), 0x0100_0000);
    assert_eq!(lrw.data(), [1, 2, 3, 4]);
    assert_eq!(lrw.working_counter(), 0);
    assert!(!lrw.more_follows());
    assert_eq!(DatagramRepr::parse(&lrw).buffer_len(), 16);
}

#[test]
fn tags_and_udp_carry_ethercat_and_other_types_are_named() {
    let sent = twincat_sent();
    // One 802.1Q tag, VLAN 5.
    let mut tagged = Vec::from(&sent[..12]);
    tagged.extend([0x81, 0x00, 0x00, 0x05, 0x88, 0xa4]);
    tagged.extend(&sent[14..]);
    let Link::Ethercat(link) = Link::parse(&tagged).unwrap() else {
        panic!("EtherCAT")
    };
    assert_eq!(link.encapsulation, Encapsulation::Vlan(5));
    assert_eq!(link.payload, &sent[14..]);
    // UDP to 0x88A4 over IPv4 (a 20-byte header, no options).
    let mut udp = Vec::from(&sent[..12]);
    udp.extend([0x08, 0x00, 0x45, 0, 0, 0, 0, 0, 0, 0, 64, 17, 0, 0]);
    udp.extend([10, 0, 0, 1, 10, 0, 0, 2]);
    udp.extend([0x88, 0xa4, 0x88, 0xa4, 0, 0, 0, 0]);
    udp.extend(&sent[14..]);
    let Link::Ethercat(link) = Link::parse(&udp).unwrap() else {
        panic!("EtherCAT")
    };
    assert_eq!(link.encapsulation, Encapsulation::Udp);
    assert_eq!(link.payload, &sent[14..]);
    // UDP to another port is IPv4, not EtherCAT; so is ARP.
    udp[14 + 20 + 3] = 0x35;
    assert!(matches!(
        Link::parse(&udp).unwrap(),
        Link::Other {
            ether_type: 0x0800,
            ..
        }
    ));
    let mut arp = sent;
    arp[12..14].copy_from_slice(&[0x08, 0x06]);
    assert!(matches!(
        Link::parse(&arp).unwrap(),
        Link::Other {
            ether_type: 0x0806,
            ..
        }
    ));
}

#[test]
fn short_and_overlong_lengths_are_length_errors() {
    let packet = twincat_sent();
    assert_eq!(
        Link::parse(&packet[..13]).unwrap_err().what,
        What::EthernetFrame
    );
    let payload = &packet[14..];
    // The header announces more than the frame holds.
    let error = EthercatFrame::parse(&payload[..30]).unwrap_err();
    assert_eq!(
        error.to_string(),
        "EtherCAT frame: buffer of 30 bytes where 36 are needed"
    );
    // A datagram whose length runs past the frame: the error, then nothing.
    let mut damaged = Vec::from(payload);
    damaged[2 + 6] = 0x20; // the APRD's length: 32 bytes
    let frame = EthercatFrame::parse(&damaged).unwrap();
    let mut datagrams = frame.datagrams();
    let error = datagrams.next().unwrap().unwrap_err();
    assert_eq!(error.what, What::EthercatDatagram);
    assert_eq!((error.expected, error.found), (44, 34));
    assert!(datagrams.next().is_none());
    // A frame of another type has no datagrams.
    let mut ads = Vec::from(payload);
    ads[1] = (ads[1] & 0x0F) | 0x20;
    assert_eq!(
        EthercatFrame::parse(&ads).unwrap().frame_type(),
        FrameType::Ads
    );
    assert_eq!(EthercatFrame::parse(&ads).unwrap().datagrams().count(), 0);
}

#[test]
fn returned_bit_is_the_source_macs_bit_1() {
    assert!(Mac([0x12, 0x10, 0x10, 0x10, 0x10, 0x10]).returned_bit());
    assert_eq!(
        Mac([0x03, 1, 1, 1, 1, 1]).without_returned_bit(),
        Mac([0x01, 1, 1, 1, 1, 1])
    );
}

#[test]
fn al_status_and_codes() {
    let status = AlStatus(0x0014);
    assert_eq!(status.state(), Some(AlState::SafeOp));
    assert!(status.error());
    assert_eq!(AlStatus(0x000A).state(), None, "the OR of PREOP and OP");
    assert_eq!(
        AlStatusCode(0x001B).to_string(),
        "0x001b Sync manager watchdog"
    );
    assert_eq!(
        AlStatusCode(0x0070).text(),
        Some("Detected module ident list does not match")
    );
    assert_eq!(AlStatusCode(0x8123).text(), Some("vendor specific"));
    assert_eq!(AlStatusCode(0x0099).to_string(), "0x0099 unknown");
    for state in [
        AlState::Init,
        AlState::PreOp,
        AlState::Boot,
        AlState::SafeOp,
        AlState::Op,
    ] {
        assert_eq!(AlState::from_bits(state.bits()), Some(state));
    }
}

#[test]
fn mailbox_coe_sdo_and_emergency() {
    // An SDO upload response of an AKD: 0x1018:01 = 0x6A (expedited).
    let message = [
        0x0a, 0x00, 0x00, 0x00, 0x00, 0x23, // header: 10 bytes, CoE, counter 2
        0x00, 0x30, // CoE: SDO response
        0x4f, 0x18, 0x10, 0x01, 0x6a, 0x00, 0x00, 0x00,
    ];
    let header = MailboxHeader::parse(&message).unwrap();
    assert_eq!(header.mailbox_type, MailboxType::Coe);
    assert_eq!((header.length, header.counter), (10, 2));
    let mut written = [0; 6];
    header.emit(&mut written).unwrap();
    assert_eq!(written, message[..6]);
    let body = header.body(&message).unwrap();
    let coe = CoeHeader::parse(body).unwrap();
    assert_eq!(coe.service, CoeService::SdoResponse);
    let sdo = CoeSdo::parse(&body[2..]).unwrap();
    assert_eq!(sdo.specifier(), 2);
    assert_eq!(sdo.multiplexer(), Some((0x1018, 1)));
    assert_eq!(sdo.initiate_data(), [0x6a, 0, 0, 0]);
    assert!(!sdo.complete_access());
    assert_eq!(sdo.abort_code(), None);
    // A body longer than the area holds.
    assert_eq!(
        header.body(&message[..12]).unwrap_err().what,
        What::MailboxMessage
    );
    // An abort from the slave in a request (service 2, specifier 4).
    let abort = [0x80, 0x00, 0x60, 0x00, 0x11, 0x00, 0x09, 0x06];
    let sdo = CoeSdo::parse(&abort).unwrap();
    assert_eq!(sdo.abort_code().unwrap().get(), 0x0609_0011);
    // A CoE emergency: the EMCY of CiA 301 after the CoE header.
    let emergency = [0x00, 0x10, 0x05, 0x73, 0x81, 0x02, 0x00, 0x00, 0x00, 0x00];
    assert_eq!(
        CoeHeader::parse(&emergency).unwrap().service,
        CoeService::Emergency
    );
    assert_eq!(Emcy::parse(&emergency[2..]).unwrap().code.get(), 0x7305);
    // A mailbox error: size too short.
    let error = MailboxError::parse(&[0x01, 0x00, 0x06, 0x00]).unwrap();
    assert_eq!(
        error.to_string(),
        "mailbox error 0x0006 Length of received mailbox data is too short"
    );
}

#[test]
fn emit_refuses_data_the_length_field_cannot_say() {
    let data = [0; 2048];
    let repr = DatagramRepr {
        command: Command::Lrd,
        index: 0,
        address: 0,
        circulating: false,
        more_follows: false,
        irq: 0,
        data: &data,
        working_counter: 0,
    };
    let mut buffer = [0; 2100];
    assert_eq!(repr.emit(&mut buffer).unwrap_err().found, 2048);
    assert_eq!(repr.emit(&mut buffer[..10]).unwrap_err().expected, 2047);
}

proptest! {
    /// Any bytes: every view reads or returns an error, and nothing panics.
    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        if let Ok(Link::Ethercat(link)) = Link::parse(&bytes) {
            if let Ok(frame) = EthercatFrame::parse(link.payload) {
                for datagram in frame.datagrams().flatten() {
                    let _ = (datagram.data(), datagram.working_counter(), datagram.command().name());
                }
            }
        }
        if let Ok(frame) = EthercatFrame::parse(&bytes) {
            let total: usize = frame.datagrams().flatten().map(|d| d.as_bytes().len()).sum();
            prop_assert!(total <= frame.body().len());
        }
        if let Ok(header) = MailboxHeader::parse(&bytes) {
            let _ = header.body(&bytes);
        }
        let _ = MailboxError::parse(&bytes).map(MailboxError::text);
        if let Ok(sdo) = CoeSdo::parse(&bytes) {
            let _ = (sdo.multiplexer(), sdo.initiate_data(), sdo.segment_data(), sdo.abort_code());
        }
    }

    /// A datagram written by `emit` reads back as what was written.
    #[test]
    fn emit_then_parse_is_identity(
        command in any::<u8>(),
        index in any::<u8>(),
        address in any::<u32>(),
        circulating in any::<bool>(),
        more_follows in any::<bool>(),
        irq in any::<u16>(),
        data in proptest::collection::vec(any::<u8>(), 0..64),
        working_counter in any::<u16>(),
    ) {
        let repr = DatagramRepr {
            command: Command::from_byte(command),
            index,
            address,
            circulating,
            more_follows,
            irq,
            data: &data,
            working_counter,
        };
        let mut buffer = vec![0; repr.buffer_len() + 3];
        let written = repr.emit(&mut buffer).unwrap();
        let (datagram, rest) = Datagram::parse(&buffer).unwrap();
        prop_assert_eq!(rest.len(), 3);
        prop_assert_eq!(written, repr.buffer_len());
        prop_assert_eq!(DatagramRepr::parse(&datagram), repr);
        prop_assert_eq!(Command::from_byte(command).byte(), command);
    }
}
