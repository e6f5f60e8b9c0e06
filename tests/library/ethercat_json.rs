//! The datagram record's JSON (`DatagramRecord::append_json`) against the
//! same record written key by key with the standard formatting, over
//! arbitrary datagrams, times, interfaces and file names: the record's
//! block and the keys a packet's records share hold every value at its
//! largest.

use motionwire::can::{EthercatPacket, Iface, Timestamp};
use motionwire::decoder::ethercat::{DatagramRecord, Session};
use motionwire::ethercat::{Addressing, Command, DatagramRepr, Encapsulation, EthercatLink, Mac};
use motionwire::logs::Position;
use proptest::prelude::*;

/// The record as docs/ethercat.md#records lists its keys, written with
/// `format!` and serde_json.
fn plain(
    file: Option<&str>,
    packet: u64,
    number: usize,
    ts: Option<Timestamp>,
    iface: Option<Iface<'_>>,
    repr: &DatagramRepr<'_>,
    returned: bool,
) -> String {
    let mut s = String::from("{");
    if let Some(file) = file {
        s += &format!("\"file\":{},", serde_json::to_string(file).unwrap());
    }
    let ts = ts.map_or_else(|| "null".to_owned(), |ts| ts.seconds().to_string());
    let iface = match iface {
        None => "null".to_owned(),
        Some(Iface::Channel(c)) => c.to_string(),
        Some(Iface::Name(name)) => serde_json::to_string(name).unwrap(),
    };
    s += &format!(
        "\"packet\":{packet},\"datagram\":{number},\"ts\":{ts},\"iface\":{iface},\
         \"kind\":\"ecat_datagram\",\"cmd\":\"{}\",\"index\":{},",
        repr.command.name(),
        repr.index
    );
    if repr.command.addressing() == Addressing::Logical {
        s += &format!("\"logical\":{}", repr.address);
    } else {
        s += &format!(
            "\"adp\":{},\"ado\":{}",
            repr.address & 0xFFFF,
            repr.address >> 16
        );
    }
    let data: String = repr.data.iter().map(|b| format!("{b:02x}")).collect();
    s += &format!(
        ",\"length\":{},\"irq\":{},\"wkc\":{},\"returned\":{returned},\"data\":\"{data}\"}}\n",
        repr.data.len(),
        repr.irq,
        repr.working_counter
    );
    s
}

fn ifaces() -> impl Strategy<Value = Option<(bool, String, u16)>> {
    prop::option::of((
        any::<bool>(),
        prop_oneof![
            "[a-z0-9]{1,16}",
            "[a-z\"\\\\\u{1}\n é]{1,20}",
            Just("\\Device\\NPF_{DCEDC919-0A20-47A2-9788-FC57D0169EDB}".to_owned()),
            "[a-z\\\\]{60,200}",
            // Up to 64 bytes, escaped to six times as many.
            "[\u{1}\u{2}a]{40,64}",
        ],
        any::<u16>(),
    ))
}

proptest! {
    #[test]
    fn datagram_records_as_the_plain_writer(
        command in 0u8..=16,
        index in any::<u8>(),
        address in any::<u32>(),
        irq in any::<u16>(),
        wkc in any::<u16>(),
        data in prop::collection::vec(any::<u8>(), 0..40),
        position in prop_oneof![any::<u64>(), 0u64..1_000_000],
        secs in prop_oneof![any::<u64>(), 1_000_000_000u64..10_000_000_000],
        nanos in prop_oneof![0u32..1_000_000_000, (0u32..1_000_000).prop_map(|u| u * 1000)],
        timed in any::<bool>(),
        iface in ifaces(),
        returned in any::<bool>(),
        file in prop::option::of("[a-z\"/.]{0,12}"),
        later in 1_000_000_000u64..10_000_000_000,
    ) {
        let repr = DatagramRepr {
            command: Command::from_byte(command),
            index,
            address,
            circulating: false,
            more_follows: false,
            irq,
            data: &data,
            working_counter: wkc,
        };
        let mut payload = (((12 + data.len()) as u16) | 0x1000).to_le_bytes().to_vec();
        let mut bytes = vec![0; 12 + data.len()];
        repr.emit(&mut bytes).unwrap();
        payload.extend(bytes);
        let ts = Timestamp::from_nanos(secs, nanos).filter(|_| timed);
        let iface = iface.as_ref().map(|(named, name, channel)| {
            if *named { Iface::Name(name) } else { Iface::Channel(*channel) }
        });
        let source = if returned { [0x12, 1, 2, 3, 4, 5] } else { [0x10, 1, 2, 3, 4, 5] };
        let event = EthercatPacket {
            timestamp: ts,
            iface,
            link: EthercatLink {
                destination: None,
                source: Mac(source),
                encapsulation: Encapsulation::Ethernet,
                payload: &payload,
            },
        };
        let mut session = Session::new();
        let packet = session.read(Position::Record(position), &event).unwrap();
        let datagram = packet.datagrams().next().unwrap().unwrap();
        // The copy as the session judges it: by the source MAC's bit 0x02,
        // except a lone frame with the bit set whose working counter is 0,
        // which order decides is the sent one (docs/ethercat.md#direction).
        if wkc != 0 || !returned {
            prop_assert_eq!(packet.copy.returned(), returned);
        }
        let returned = packet.copy.returned();
        let file = file.as_deref();
        // The packet's first record, then a second that writes the keys
        // the first kept.
        for number in [1, usize::MAX] {
            let record = DatagramRecord { packet: &packet, number, datagram };
            let mut out = Vec::new();
            record.append_json(&mut out, file);
            let expected = plain(file, position, number, ts, iface, &repr, returned);
            prop_assert_eq!(String::from_utf8(out).unwrap(), expected);
        }
        // A packet whose time was changed after its first record.
        let mut moved = packet.clone();
        moved.timestamp = Timestamp::from_nanos(later, nanos);
        let record = DatagramRecord { packet: &moved, number: 2, datagram };
        let mut out = Vec::new();
        record.append_json(&mut out, None);
        let expected = plain(None, position, 2, moved.timestamp, iface, &repr, returned);
        prop_assert_eq!(String::from_utf8(out).unwrap(), expected);
    }
}
