#!/usr/bin/env python3
"""Write the pcap/pcapng fixtures of tests/library/pcap.rs and their truth
files.

The frames are a candump-style list (identifier word with the Linux flags,
FD flags, data). From them:

- can.pcap        pcap, little-endian, microseconds, link type 227, written
                  here with struct as libpcap lays it out (classic frames as
                  the 16-byte struct can_frame, CAN FD as the 72-byte struct
                  canfd_frame with CANFD_FDF set, as libpcap >= 1.10.2 does);
- can.pcapng      `editcap -F pcapng can.pcap` (Wireshark's pcapng writer);
- can_ns.pcap     `editcap -F nsecpcap can.pcap` (nanosecond pcap);
- can_be.pcap     pcap, big-endian, microseconds, written here;
- can_ns_comments.pcapng
                  `editcap -F pcapng -a 2:... -a 7:... can_ns.pcap`: an
                  interface with if_tsresol 9 (nanoseconds), and two enhanced
                  packet blocks with a comment option (a classic and a CAN
                  FD frame), which the reader's fast paths leave to its
                  general path;
- multi.pcapng    pcapng written here: interface 0 "can0" (link type 227,
                  microseconds), interface 1 "eth0" (link type 1, Ethernet),
                  interface 2 "vcan1" (link type 227, if_tsresol 9 =
                  nanoseconds); an Ethernet packet and a name resolution
                  block between CAN packets, then a second section with its
                  own interface "can9".

Each FILE gets FILE.json: what tshark (`-T fields`) reads from it, one
object per packet. Run from the repository root:

    python3 scripts/gen_pcap_fixtures.py
"""

import json
import os
import struct
import subprocess

OUT = "tests/fixtures/pcap"

EFF, RTR, ERR = 0x80000000, 0x40000000, 0x20000000
BRS, ESI, FDF = 0x01, 0x02, 0x04

T0 = 1_700_000_000

# (seconds offset, microseconds, word, fd flags or None for classic, data)
FRAMES = [
    (0, 500, 0x081, None, bytes.fromhex("1081110000000000")),
    (0, 1_500, 0x705, None, bytes.fromhex("05")),
    (0, 2_000, 0x000, None, bytes.fromhex("8205")),
    (1, 0, RTR | 0x705, None, b"\x01"),  # remote request, DLC 1 (len byte)
    (1, 250, EFF | 0x18FF50E5, None, bytes.fromhex("0102030405060708")),
    (1, 999_999, 0x123, FDF | BRS, bytes(range(12))),
    (2, 1, 0x7FF, FDF | BRS | ESI, bytes(range(64))),
    (2, 10, EFF | 0x1ABCDEF, FDF, bytes.fromhex("aabbcc")),
    (3, 0, ERR | 0x004, None, bytes.fromhex("0004000000000000")),
    (3, 7, 0x181, None, b""),
]


def socketcan(word, fd, data):
    """The packet bytes: header (word big-endian) and data, padded to the MTU."""
    if word & RTR and fd is None:
        length, payload = data[0], b""
    else:
        length, payload = len(data), data
    head = struct.pack(">IBBBB", word, length, fd or 0, 0, 0)
    mtu = 72 if fd is not None else 16
    return (head + payload).ljust(mtu, b"\x00")


def pcap(path, frames, endian="<", nanos=False):
    magic = 0xA1B23C4D if nanos else 0xA1B2C3D4
    with open(path, "wb") as f:
        f.write(struct.pack(endian + "IHHiIII", magic, 2, 4, 0, 0, 262_144, 227))
        for secs, micros, word, fd, data in frames:
            pkt = socketcan(word, fd, data)
            frac = micros * 1000 if nanos else micros
            f.write(struct.pack(endian + "IIII", T0 + secs, frac, len(pkt), len(pkt)))
            f.write(pkt)


def block(kind, body):
    body = body + b"\x00" * (-len(body) % 4)
    n = len(body) + 12
    return struct.pack("<II", kind, n) + body + struct.pack("<I", n)


def option(code, value):
    return struct.pack("<HH", code, len(value)) + value + b"\x00" * (-len(value) % 4)


def shb():
    return block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1) + option(0, b""))


def idb(link, name, tsresol=None):
    opts = option(2, name.encode())
    if tsresol is not None:
        opts += option(9, bytes([tsresol]))
    return block(1, struct.pack("<HHI", link, 0, 262_144) + opts + option(0, b""))


def epb(iface, ticks, pkt):
    head = struct.pack("<IIIII", iface, ticks >> 32, ticks & 0xFFFFFFFF, len(pkt), len(pkt))
    return block(6, head + pkt + b"\x00" * (-len(pkt) % 4))


def multi(path):
    eth = bytes.fromhex("ffffffffffff020000000001" "0806") + bytes(28)
    out = [shb(), idb(227, "can0"), idb(1, "eth0"), idb(227, "vcan1", tsresol=9)]
    for i, (secs, micros, word, fd, data) in enumerate(FRAMES[:6]):
        if i % 2 == 0:
            out.append(epb(0, (T0 + secs) * 1_000_000 + micros, socketcan(word, fd, data)))
        else:
            ns = (T0 + secs) * 1_000_000_000 + micros * 1000 + 123
            out.append(epb(2, ns, socketcan(word, fd, data)))
        if i == 2:
            out.append(epb(1, (T0 + 2) * 1_000_000, eth))
            # name resolution block: skipped, takes no number
            out.append(block(4, struct.pack("<HH", 0, 0)))
    out += [shb(), idb(227, "can9")]
    for secs, micros, word, fd, data in FRAMES[6:]:
        out.append(epb(0, (T0 + 10 + secs) * 1_000_000 + micros, socketcan(word, fd, data)))
    with open(path, "wb") as f:
        f.write(b"".join(out))


FIELDS = [
    "frame.number", "frame.time_epoch", "frame.interface_name", "frame.protocols",
    "can.id", "can.flags.xtd", "can.flags.rtr", "can.flags.err", "can.len",
    "canfd.flags.brs", "canfd.flags.esi", "data.data", "can.err.ctrl",
    "can.err.ctrl.rx_warning",
]


def truth(path):
    # The AUTOSAR NM heuristic would take some payloads from data.data.
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
    pcap(p("can.pcap"), FRAMES)
    subprocess.run(["editcap", "-F", "pcapng", p("can.pcap"), p("can.pcapng")], check=True)
    subprocess.run(["editcap", "-F", "nsecpcap", p("can.pcap"), p("can_ns.pcap")], check=True)
    pcap(p("can_be.pcap"), FRAMES, endian=">")
    subprocess.run(["editcap", "-F", "pcapng", "-a", "2:a classic frame", "-a", "7:a CAN FD frame",
                    p("can_ns.pcap"), p("can_ns_comments.pcapng")], check=True)
    multi(p("multi.pcapng"))
    for name in ["can.pcap", "can.pcapng", "can_ns.pcap", "can_be.pcap", "can_ns_comments.pcapng",
                 "multi.pcapng"]:
        truth(p(name))


if __name__ == "__main__":
    main()
