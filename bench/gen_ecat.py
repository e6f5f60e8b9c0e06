#!/usr/bin/env python3
"""Write one of the EtherCAT benchmark's traffic mixes (issue 35) as a
pcapng of at least N datagrams, built from a real capture of
tests/data/ethercat by repeating its traffic.

Mixes, each deterministic (the fixture's bytes, only the times moved):

* `cyclic`: `replay-dc.pcapng` (ethercrab, EK1100 + EL2828 + EL2889, DC):
  its start-up once (every packet before the first LRW frame), then its
  cyclic frames — FRMW 0x0910 (DC system time) + LRW + 3 × FPRD 0x0130 in
  one frame, the sent and the returned copy — repeated, each repetition
  after the last by the capture's span of those frames and one cycle;
  5 datagrams a frame, 93-byte packets;
* `fault`: `synthetic_akd_fault.pcapng` (scripts/ecat_pcapng.py: an AKD's
  start-up, SII, mailbox set-up, CoE SDOs, LRW cycles and a fault), the
  whole capture repeated: start-up and mailbox traffic of two slaves;
* `sdo`: `soem-akd-sdo.pcapng` (SOEM, one AKD), the whole capture
  repeated: one datagram a frame, 35 CoE SDO uploads through 1024-byte
  mailbox datagrams, SII reads, AL status polling, a lost frame and an ARP
  packet of the host per repetition.

Repetitions of a whole capture follow each other by a millisecond.
Every packet keeps its bytes; a repetition's times are the original's
plus the repetition's offset. The section and interface blocks are the
fixture's; its statistics block is left out. The output stops after the
packet whose datagrams make the count reach N (a frame is never cut);
the count written goes to standard error.

Usage: python3 bench/gen_ecat.py MIX --datagrams N -o OUT.pcapng
"""

from __future__ import annotations

import argparse
import os
import struct
import sys

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "ethercat")
SHB, IDB, EPB = 0x0A0D0D0A, 1, 6
ETHERTYPE_ECAT = 0x88A4
LRW = 0x0C


def blocks(path: str):
    """The (type, bytes) of each block of a little-endian pcapng."""
    data = open(path, "rb").read()
    off = 0
    while off < len(data):
        kind, length = struct.unpack_from("<II", data, off)
        yield kind, data[off : off + length]
        off += length


def datagrams(packet: bytes) -> list[int]:
    """The commands of an Ethernet packet's EtherCAT datagrams (none for
    another EtherType or frame type)."""
    if len(packet) < 16:
        return []
    off = 12
    ethertype = struct.unpack_from(">H", packet, off)[0]
    if ethertype == 0x8100:
        off += 4
        ethertype = struct.unpack_from(">H", packet, off)[0]
    if ethertype != ETHERTYPE_ECAT:
        return []
    header = struct.unpack_from("<H", packet, off + 2)[0]
    if header >> 12 != 1:
        return []
    off += 4
    commands = []
    while off + 10 <= len(packet):
        command = packet[off]
        length = struct.unpack_from("<H", packet, off + 6)[0]
        commands.append(command)
        off += 10 + (length & 0x07FF) + 2
        if not length & 0x8000:
            break
    return commands


class Packet:
    """An EPB: its time in the interface's ticks, the rest of the block as
    it is, and the commands of its datagrams."""

    __slots__ = ("ticks", "head", "tail", "commands")

    def __init__(self, block: bytes) -> None:
        high, low = struct.unpack_from("<II", block, 12)
        self.ticks = high << 32 | low
        self.head = block[8:12]
        self.tail = block[20:]
        caplen = struct.unpack_from("<I", block, 20)[0]
        self.commands = datagrams(block[28 : 28 + caplen])

    def block(self, shift: int) -> bytes:
        ticks = self.ticks + shift
        length = 20 + len(self.tail)
        return b"".join(
            (
                struct.pack("<II", EPB, length),
                self.head,
                struct.pack("<II", ticks >> 32, ticks & 0xFFFF_FFFF),
                self.tail,
            )
        )


def ticks_per_second(idb: bytes) -> int:
    """The interface's `if_tsresol` as ticks a second (10^6 without it)."""
    off = 16
    while off + 4 <= len(idb) - 4:
        code, length = struct.unpack_from("<HH", idb, off)
        if code == 0:
            break
        if code == 9:
            r = idb[off + 4]
            return 2 ** (r & 0x7F) if r & 0x80 else 10**r
        off += 4 + (length + 3) // 4 * 4
    return 10**6


def read(name: str) -> tuple[bytes, list[Packet], int]:
    """The fixture's section and interface blocks, its packets and its
    (one) interface's ticks a second."""
    head = []
    packets = []
    resolution = 10**6
    for kind, block in blocks(os.path.join(DATA, name)):
        if kind == SHB:
            head.append(block)
        elif kind == IDB:
            head.append(block)
            resolution = ticks_per_second(block)
        elif kind == EPB:
            packets.append(Packet(block))
    return b"".join(head), packets, resolution


def cycle(packets: list[Packet]) -> int:
    """The median time between consecutive sent LRW frames."""
    sent = [p.ticks for p in packets if LRW in p.commands and not p.tail[8 + 6] & 0x02]
    gaps = sorted(b - a for a, b in zip(sent, sent[1:]))
    return gaps[len(gaps) // 2]


MIXES = {
    "cyclic": "replay-dc.pcapng",
    "fault": "synthetic_akd_fault.pcapng",
    "sdo": "soem-akd-sdo.pcapng",
}


def write(mix: str, n: int, path: str) -> int:
    head, packets, resolution = read(MIXES[mix])
    if mix == "cyclic":
        first = next(i for i, p in enumerate(packets) if LRW in p.commands)
        once = packets[:first]
        repeated = [p for p in packets[first:] if LRW in p.commands]
        gap = cycle(packets)
    else:
        once = []
        repeated = packets
        # The next start-up a millisecond after the last packet.
        gap = resolution // 1000
    span = repeated[-1].ticks - repeated[0].ticks + gap
    shift0 = (once[-1].ticks + gap - repeated[0].ticks) if once else 0
    count = 0
    with open(path, "wb") as f:
        f.write(head)
        parts = [p.block(0) for p in once]
        count = sum(len(p.commands) for p in once)
        k = 0
        while count < n:
            shift = shift0 + k * span
            for p in repeated:
                parts.append(p.block(shift))
                count += len(p.commands)
                if count >= n:
                    break
            if len(parts) >= 65536:
                f.write(b"".join(parts))
                parts.clear()
            k += 1
        f.write(b"".join(parts))
    return count


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("mix", choices=list(MIXES))
    p.add_argument("--datagrams", type=int, default=1_000_000)
    p.add_argument("-o", "--output", required=True)
    a = p.parse_args(argv)
    count = write(a.mix, a.datagrams, a.output)
    print(f"{a.output}: {count} datagrams", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
