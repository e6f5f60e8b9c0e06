#!/usr/bin/env python3
"""Write one of the benchmark's traffic mixes (issue 21) as a candump log and,
optionally, as a SocketCAN pcap (LINKTYPE_CAN_SOCKETCAN, 227).

Mixes, each deterministic (a fixed xorshift generator), one interface `can0`:

* `sample`: the repository's simulated machine bus, repeated
  (`scripts/gen_canlog.py --frames N`; written by that script);
* `storm`: an EMCY storm from many nodes: 30 % EMCY from 127 nodes with
  random codes, registers and manufacturer bytes, 20 % heartbeats in every
  state (boot-up, stopped, operational, pre-operational), 5 % SYNC, 45 %
  TPDO1 of random lengths 0-8 (the mix of issue 21);
* `pdo`: a PDO-heavy drive bus: four CiA 402 drives (nodes 1-4) whose TPDO1
  (statusword 6041h, position actual 6064h) and RPDO1 (controlword 6040h,
  target position 607Ah) are mapped by SDO writes at the start, then SYNC,
  TPDO1 and RPDO1 of each drive every millisecond, a heartbeat of each drive
  every 100 ms; the statuswords walk the CiA 402 states;
* `sdo`: SDO-heavy boot traffic of 32 nodes: boot-ups, then expedited reads
  and writes, segmented reads of 20 bytes and reads the server aborts;
* `fd`: a CAN FD bus: eight drives whose 32-byte FD TPDO1 (statusword,
  position, velocity, torque, …) and 16-byte FD RPDO1 are mapped by SDO,
  sent every millisecond after a SYNC with BRS, other nodes' FD TPDO2 of
  random FD lengths (0-64), heartbeats of 64 nodes and a few EMCYs.

Usage: python3 bench/gen_mix.py MIX --frames N -o OUT.log [--pcap OUT.pcap]
"""

from __future__ import annotations

import argparse
import os
import struct
import subprocess
import sys

START_US = 1_700_000_000_000_000
MASK = (1 << 64) - 1
FD_LENGTHS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64)


class Rng:
    """xorshift64 (the same generator as benches/session.rs)."""

    def __init__(self, seed: int) -> None:
        self.s = seed

    def next(self) -> int:
        s = self.s
        s ^= (s << 13) & MASK
        s ^= s >> 7
        s ^= (s << 17) & MASK
        self.s = s
        return s

    def below(self, n: int) -> int:
        return self.next() % n

    def bytes(self, n: int) -> bytes:
        return bytes(self.next() & 0xFF for _ in range(n))


# A frame: (t_us, cid, data, fd_flags or None). fd_flags: 0x1 BRS.


def storm(n: int) -> list:
    rng = Rng(0x9E37_79B9_7F4A_7C15)
    out = []
    append = out.append
    for i in range(n):
        t = START_US + 100 * i
        node = 1 + rng.below(127)
        r = rng.below(100)
        data = rng.next().to_bytes(8, "little")
        if r < 30:
            append((t, 0x080 + node, data, None))
        elif r < 50:
            state = (0x00, 0x04, 0x05, 0x7F)[rng.below(4)]
            append((t, 0x700 + node, bytes([state]), None))
        elif r < 55:
            append((t, 0x080, b"", None))
        else:
            append((t, 0x180 + node, data[: rng.below(9)], None))
    return out


def map_by_sdo(out: list, t: int, node: int, index: int, entries: list[int]) -> int:
    """SDO writes of a mapping object (sub 0 = 0, the entries, sub 0 = n),
    each answered; returns the time after them."""

    def write(sub: int, value: int, cs: int) -> None:
        nonlocal t
        out.append((t, 0x600 + node, struct.pack("<BHBI", cs, index, sub, value), None))
        out.append((t + 100, 0x580 + node, struct.pack("<BHB4x", 0x60, index, sub), None))
        t += 200

    write(0, 0, 0x2F)
    for i, entry in enumerate(entries):
        write(i + 1, entry, 0x23)
    write(0, len(entries), 0x2F)
    return t


STATUSWORDS = (0x0250, 0x0231, 0x0233, 0x0237, 0x0237, 0x0237, 0x0208, 0x0237)
CONTROLWORDS = (0x0006, 0x0006, 0x0007, 0x000F, 0x000F, 0x000F, 0x0080, 0x000F)


def pdo(n: int) -> list:
    out: list = []
    t = START_US
    for node in range(1, 5):
        out.append((t, 0x700 + node, b"\x00", None))
        t += 100
    for node in range(1, 5):
        t = map_by_sdo(out, t, node, 0x1A00, [0x6041_0010, 0x6064_0020])
        t = map_by_sdo(out, t, node, 0x1600, [0x6040_0010, 0x607A_0020])
    out.append((t, 0x000, b"\x01\x00", None))
    rng = Rng(42)
    cycle = 0
    positions = [0, 0, 0, 0]
    base = t + 1000
    while len(out) < n:
        t0 = base + 1000 * cycle
        out.append((t0, 0x080, b"", None))
        phase = (cycle // 250) % len(STATUSWORDS)
        for node in range(1, 5):
            positions[node - 1] = (positions[node - 1] + 100 + rng.below(50)) & 0xFFFF_FFFF
            p = positions[node - 1]
            t = t0 + 20 + 240 * (node - 1)
            out.append((t, 0x180 + node, struct.pack("<HI", STATUSWORDS[phase], p), None))
            out.append((t + 120, 0x200 + node, struct.pack("<HI", CONTROLWORDS[phase], p + 500 & 0xFFFF_FFFF), None))
        if cycle % 100 == 0:
            for node in range(1, 5):
                out.append((t0 + 980 - 4 + node, 0x700 + node, b"\x05", None))
        cycle += 1
    del out[n:]
    return out


def sdo(n: int) -> list:
    out: list = []
    rng = Rng(7)
    t = START_US
    for node in range(1, 33):
        out.append((t, 0x700 + node, b"\x00", None))
        t += 150
    while len(out) < n:
        node = 1 + rng.below(32)
        t += 300
        kind = rng.below(4)
        req, resp = 0x600 + node, 0x580 + node
        if kind == 0:
            out.append((t, req, bytes([0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]), None))
            out.append((t + 100 + rng.below(400), resp, bytes([0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00]), None))
        elif kind == 1:
            out.append((t, req, bytes([0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0, 0]), None))
            out.append((t + 100 + rng.below(400), resp, bytes([0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0]), None))
        elif kind == 2:
            out.append((t, req, bytes([0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]), None))
            out.append((t + 100, resp, bytes([0x41, 0x08, 0x10, 0x00, 20, 0, 0, 0]), None))
            for i, last in ((0, False), (1, False), (0, True)):
                toggle = i << 4
                t += 200
                out.append((t, req, bytes([0x60 | toggle, 0, 0, 0, 0, 0, 0, 0]), None))
                cmd = toggle | 0x03 if last else toggle
                # 20 bytes: 7 + 7 + 6 (the last segment says 1 byte unused).
                out.append((t + 100, resp, bytes([cmd]) + b"motionw", None))
        else:
            out.append((t, req, bytes([0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]), None))
            out.append((t + 100, resp, bytes([0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06]), None))
    del out[n:]
    return out


def fd(n: int) -> list:
    out: list = []
    rng = Rng(0xFD)
    t = START_US
    drives = range(1, 9)
    for node in range(1, 65):
        out.append((t, 0x700 + node, b"\x00", None))
        t += 50
    for node in drives:
        t = map_by_sdo(out, t, node, 0x1A00, [0x6041_0010, 0x6064_0020, 0x606C_0020, 0x6077_0010,
                                               0x6061_0008, 0x60F4_0020, 0x6078_0010, 0x2000_0020,
                                               0x2001_0020])
        t = map_by_sdo(out, t, node, 0x1600, [0x6040_0010, 0x607A_0020, 0x60FF_0020, 0x6071_0010,
                                               0x6060_0008])
    out.append((t, 0x000, b"\x01\x00", None))
    cycle = 0
    base = t + 1000
    positions = [0] * 8
    while len(out) < n:
        t0 = base + 1000 * cycle
        out.append((t0, 0x080, b"", None))
        phase = (cycle // 250) % len(STATUSWORDS)
        for node in drives:
            i = node - 1
            positions[i] = (positions[i] + 1000 + rng.below(200)) & 0xFFFF_FFFF
            p = positions[i]
            t = t0 + 10 + 80 * i
            tpdo = struct.pack("<HIiHbiHii", STATUSWORDS[phase], p, 1000, 200, 8, 5, 300,
                               rng.below(1 << 31), rng.below(1 << 31))
            out.append((t, 0x180 + node, tpdo.ljust(32, b"\x00"), 0x1))
            rpdo = struct.pack("<HIihb", CONTROLWORDS[phase], p + 500 & 0xFFFF_FFFF, 1000, 100, 8)
            out.append((t + 40, 0x200 + node, rpdo.ljust(16, b"\x00"), 0x1))
        # Other nodes' FD TPDO2, random lengths.
        for _ in range(4):
            node = 9 + rng.below(56)
            length = FD_LENGTHS[rng.below(len(FD_LENGTHS))]
            out.append((t0 + 700 + rng.below(200), 0x280 + node, rng.bytes(length), 0x1))
        if cycle % 100 == 0:
            for node in range(1, 65):
                out.append((t0 + 900 + node, 0x700 + node, b"\x05", None))
        if cycle % 500 == 250:
            node = 9 + rng.below(56)
            out.append((t0 + 990, 0x080 + node, struct.pack("<HB5s", 0x8110, 0x11, rng.bytes(5)), None))
        cycle += 1
    out.sort(key=lambda f: f[0])
    del out[n:]
    return out


MIXES = {"storm": storm, "pdo": pdo, "sdo": sdo, "fd": fd}

HEX = [f"{b:02X}" for b in range(256)]


def write_log(frames: list, path: str, iface: str = "can0") -> None:
    heads = [f") {iface} {cid:03X}#" for cid in range(0x800)]
    with open(path, "w") as f:
        lines = []
        append = lines.append
        for t, cid, data, flags in frames:
            s, us = divmod(t, 1_000_000)
            hexed = data.hex().upper()
            if flags is None:
                append(f"({s}.{us:06d}{heads[cid]}{hexed}\n")
            else:
                append(f"({s}.{us:06d}{heads[cid]}#{flags:X}{hexed}\n")
            if len(lines) >= 65536:
                f.write("".join(lines))
                lines.clear()
        f.write("".join(lines))


PCAP_GLOBAL = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65_535, 227)
PCAP_RECORD = struct.Struct("<IIII")
CLASSIC = struct.Struct(">IB3x8s")
CANFD = struct.Struct(">IBBxx64s")
CANFD_FDF = 0x04


def write_pcap(frames: list, path: str) -> None:
    with open(path, "wb") as f:
        f.write(PCAP_GLOBAL)
        parts = []
        append = parts.append
        for t, cid, data, flags in frames:
            s, us = divmod(t, 1_000_000)
            if flags is None:
                append(PCAP_RECORD.pack(s, us, 16, 16))
                append(CLASSIC.pack(cid, len(data), data))
            else:
                append(PCAP_RECORD.pack(s, us, 72, 72))
                append(CANFD.pack(cid, len(data), CANFD_FDF | flags, data))
            if len(parts) >= 131072:
                f.write(b"".join(parts))
                parts.clear()
        f.write(b"".join(parts))


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("mix", choices=["sample", *MIXES])
    p.add_argument("--frames", type=int, default=1_000_000)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--pcap")
    a = p.parse_args(argv)
    if a.mix == "sample":
        gen = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "gen_canlog.py")
        cmd = [sys.executable, gen, "--frames", str(a.frames), "-o", a.output]
        if a.pcap:
            cmd += ["--pcap", a.pcap]
        return subprocess.call(cmd)
    frames = MIXES[a.mix](a.frames)
    write_log(frames, a.output)
    if a.pcap:
        write_pcap(frames, a.pcap)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
