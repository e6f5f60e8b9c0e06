#!/usr/bin/env python3
"""Write the Linux "cooked" capture fixtures of tests/library/pcap.rs
(docs/formats.md#pcap) with scapy, and beside each what tshark reads from it.

`tcpdump -i any`, and dumpcap/Wireshark on a CAN interface in some setups,
write link type 113 (LINUX_SLL, 16-byte header) or 276 (LINUX_SLL2, 20-byte
header with the interface index), protocol 0x000C (CAN) or 0x000D (CAN
FD), followed by the SocketCAN frame in the capturing machine's byte order
(little-endian on every common Linux machine). No vcan interface can be made
where these were written (no vcan kernel module), so scapy writes them: its
`CookedLinux` / `CookedLinuxV2` layers over its `CAN` / `CANFD` layers with
`conf.contribs['CAN']['swap-bytes'] = True` (the identifier word in host
order, as the kernel hands it to a cooked capture).

- sll.pcap       link type 113: classic, extended, remote, error and CAN FD
                 frames (protocol 0x000C, CAN FD 0x000D), packet types
                 "sent by us" and "broadcast", and one IPv4 packet (protocol
                 0x0800) that is not CAN;
- sll2.pcap      link type 276, the same frames with interface indices;
- sll2.pcapng    `editcap -F pcapng sll2.pcap` (Wireshark's pcapng writer);
- sll_mixed.pcapng  `mergecap` of sll2.pcap and an Ethernet capture
                 (link type 1) written here: two interfaces, the Ethernet
                 packets between the CAN ones by time;
- sll2_two_buses.pcap  sll2.pcap's packets with the CAN ones alternating
                 between interface indices 3 and 4, as `tcpdump -i any`
                 captures two CAN buses.

Each FILE gets FILE.json: what tshark (`-T fields`, the fields of
gen_pcap_fixtures.py) reads from it, one object per packet.

Run from the repository root (scapy 2.5+, tshark, editcap, mergecap):

    python3 scripts/gen_sll_fixtures.py
"""

import json
import os
import subprocess

from scapy.config import conf
from scapy.layers.can import CAN, CANFD
from scapy.layers.inet import IP, UDP
from scapy.layers.l2 import CookedLinux, CookedLinuxV2, Ether
from scapy.packet import Raw
from scapy.utils import wrpcap

# After the import: scapy.layers.can sets its defaults when loaded.
conf.contribs["CAN"] = {"swap-bytes": True, "remove-padding": False}

OUT = "tests/fixtures/pcap"
T0 = 1_700_000_000
ARPHRD_CAN = 280
ETH_P_CAN, ETH_P_CANFD, ETH_P_IP = 0x000C, 0x000D, 0x0800
# Linux packet types: 0 to us, 1 broadcast, 4 sent by us (outgoing).
HOST, BROADCAST, OUTGOING = 0, 1, 4

# (seconds offset, microseconds, protocol, scapy frame) — scapy pads a
# classic frame to 8 data bytes (struct can_frame, CAN_MTU 16) as the
# kernel does, and a CAN FD frame to 64 (CANFD_MTU 72).
def classic(flags, identifier, data, length=None):
    frame = CAN(flags=flags, identifier=identifier,
                length=len(data) if length is None else length, data=data)
    return bytes(frame).ljust(16, b"\0")


def fd(identifier, data, fd_flags, flags=0):
    frame = CANFD(flags=flags, identifier=identifier, length=len(data),
                  fd_flags=fd_flags, data=data)
    return bytes(frame).ljust(72, b"\0")


FRAMES = [
    (0, 500, ETH_P_CAN, HOST, classic(0, 0x081, bytes.fromhex("1081110000000000"))),
    (0, 1_500, ETH_P_CAN, HOST, classic(0, 0x705, bytes.fromhex("05"))),
    (0, 1_800, ETH_P_IP, HOST, None),  # an IPv4 packet: not CAN
    (0, 2_000, ETH_P_CAN, OUTGOING, classic(0, 0x000, bytes.fromhex("8205"))),
    (1, 0, ETH_P_CAN, HOST, classic("remote_transmission_request", 0x705, b"", length=1)),
    (1, 250, ETH_P_CAN, BROADCAST, classic("extended", 0x18FF50E5, bytes.fromhex("0102030405060708"))),
    (1, 999_999, ETH_P_CANFD, HOST, fd(0x123, bytes(range(12)), 0x05)),  # FDF | BRS
    (2, 1, ETH_P_CANFD, OUTGOING, fd(0x7FF, bytes(range(64)), 0x07)),  # FDF | BRS | ESI
    (2, 10, ETH_P_CANFD, HOST, fd(0x1ABCDEF, bytes.fromhex("aabbcc"), 0x04, flags="extended")),
    (3, 0, ETH_P_CAN, HOST, classic("error", 0x004, bytes.fromhex("0004000000000000"))),
    (3, 7, ETH_P_CAN, HOST, classic(0, 0x181, b"")),
]


def ip_packet():
    return bytes(IP(src="192.0.2.1", dst="192.0.2.2") / UDP(sport=5000, dport=5001) / Raw(b"not CAN"))


def sll(version, ifindex=lambda i: 3):
    packets = []
    for i, (secs, micros, proto, pkttype, frame) in enumerate(FRAMES):
        payload = ip_packet() if frame is None else frame
        hatype = 1 if frame is None else ARPHRD_CAN
        addr_len = 6 if frame is None else 0
        if version == 1:
            head = CookedLinux(pkttype=pkttype, lladdrtype=hatype, lladdrlen=addr_len,
                               src=b"\x02\0\0\0\0\x01\0\0" if addr_len else b"\0" * 8, proto=proto)
        else:
            head = CookedLinuxV2(proto=proto, ifindex=ifindex(i) if frame is not None else 2,
                                 lladdrtype=hatype, pkttype=pkttype, lladdrlen=addr_len,
                                 src=b"\x02\0\0\0\0\x01\0\0" if addr_len else b"\0" * 8)
        pkt = head / Raw(payload)
        pkt.time = T0 + secs + micros / 1e6
        packets.append(pkt)
    return packets


FIELDS = [
    "frame.number", "frame.time_epoch", "frame.interface_name", "frame.protocols",
    "can.id", "can.flags.xtd", "can.flags.rtr", "can.flags.err", "can.len",
    "canfd.flags.brs", "canfd.flags.esi", "data.data", "can.err.ctrl",
    "can.err.ctrl.rx_warning", "sll.pkttype", "sll.ltype", "sll.ifindex",
]


def truth(path):
    cmd = ["tshark", "-r", path, "--disable-protocol", "autosar-nm", "-T", "fields",
           "-E", "separator=\t", "-E", "occurrence=f"]
    for field in FIELDS:
        cmd += ["-e", field]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    packets = []
    for line in out.splitlines():
        values = line.split("\t")
        packets.append({k: (v if v != "" else None) for k, v in zip(FIELDS, values)})
    version = subprocess.run(["tshark", "--version"], capture_output=True, text=True).stdout
    with open(path + ".json", "w") as f:
        json.dump({"tool": version.splitlines()[0], "fields": FIELDS, "packets": packets}, f, indent=1)
        f.write("\n")


def main():
    os.makedirs(OUT, exist_ok=True)
    p = lambda name: os.path.join(OUT, name)
    wrpcap(p("sll.pcap"), sll(1), linktype=113)
    wrpcap(p("sll2.pcap"), sll(2), linktype=276)
    subprocess.run(["editcap", "-F", "pcapng", p("sll2.pcap"), p("sll2.pcapng")], check=True)
    ether = []
    for i, (secs, micros) in enumerate([(0, 1_000), (2, 5)]):
        pkt = Ether(src="02:00:00:00:00:01", dst="02:00:00:00:00:02") / Raw(ip_packet())
        pkt.time = T0 + secs + micros / 1e6
        ether.append(pkt)
    eth_path = p("eth.tmp.pcap")
    wrpcap(eth_path, ether, linktype=1)
    subprocess.run(["mergecap", "-F", "pcapng", "-w", p("sll_mixed.pcapng"), p("sll2.pcap"), eth_path],
                   check=True)
    os.remove(eth_path)
    # `tcpdump -i any` on two buses: the CAN packets alternate between
    # interfaces 3 and 4.
    wrpcap(p("sll2_two_buses.pcap"), sll(2, lambda i: 3 + i % 2), linktype=276)
    for name in ["sll.pcap", "sll2.pcap", "sll2.pcapng", "sll_mixed.pcapng", "sll2_two_buses.pcap"]:
        truth(p(name))


if __name__ == "__main__":
    main()
