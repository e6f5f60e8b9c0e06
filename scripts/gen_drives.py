#!/usr/bin/env python3
"""Generate a candump log of many CiA 402 drives, the PDO-heavy traffic for
the report (BENCHMARKS.md "Issue 23"): every drive's charts are drawn and
its CiA 402 state changes often.

16 drives (nodes 1 to 16) on can0, a SYNC every millisecond. The master
configures each drive by SDO first (CiA 301 expedited transfers: it reads
device type 1000h, 0x00020192, a drive; then the writes of
scripts/gen_canlog.py's drive: TPDO1 0x180+n = statusword 6041h
and position actual value 6064h, TPDO2 0x280+n = velocity actual value
606Ch, both on every SYNC), so the decoder learns the mappings from the log
(docs/canopen.md#pdo-mappings); then it starts them (NMT 01h). After that,
every SYNC each drive sends TPDO1 and TPDO2: of every 33 frames, 1 SYNC and
32 PDOs; a heartbeat every 100 ms. Each drive runs the CiA 402 state
machine (docs/canopen.md#cia402): switch on disabled, ready to switch on,
switched on, operation enabled; about every 0.5 s (at random) an error EMCY
and fault reaction active, fault, then after 40 ms a reset EMCY and the way
back up, one state per 2 ms. Deterministic for a seed.

    python3 scripts/gen_drives.py --frames 1000000 -o /tmp/drives.log
"""

import argparse
import math
import random
import struct
import sys

DRIVES = range(1, 17)
SYNC_US = 1_000
HEARTBEAT_US = 100_000

# Statusword values (CiA 402 table of the state bits).
SWITCH_ON_DISABLED = 0x0040
READY_TO_SWITCH_ON = 0x0021
SWITCHED_ON = 0x0023
OPERATION_ENABLED = 0x0027
FAULT_REACTION_ACTIVE = 0x000F
FAULT = 0x0008
UP = [SWITCH_ON_DISABLED, READY_TO_SWITCH_ON, SWITCHED_ON, OPERATION_ENABLED]

EMCY_CODES = [0x7305, 0x4310, 0x2310, 0x3210, 0x5530]


class Drive:
    def __init__(self, node: int, rng: random.Random):
        self.node = node
        self.rng = rng
        self.position = rng.randint(-1_000_000, 1_000_000)
        self.phase = rng.random() * math.tau
        self.climb = 0  # index into UP while coming up
        self.next_step = 0  # time of the next step up
        self.fault_at = 0
        self.reset_at = None
        self.statusword = SWITCH_ON_DISABLED
        self.pending = []  # frames to send before the next PDOs

    def schedule_fault(self, t: int) -> None:
        self.fault_at = t + self.rng.randint(250_000, 750_000)

    def step(self, t: int) -> None:
        n = self.node
        if self.reset_at is not None:
            if self.statusword == FAULT_REACTION_ACTIVE:
                self.statusword = FAULT
            elif t >= self.reset_at:
                self.pending.append((0x80 + n, bytes(8)))  # reset EMCY
                self.reset_at = None
                self.climb = 0
                self.statusword = UP[0]
                self.next_step = t + 2_000
        elif self.statusword != OPERATION_ENABLED:
            if t >= self.next_step:
                self.climb += 1
                self.statusword = UP[self.climb]
                self.next_step = t + 2_000
                if self.statusword == OPERATION_ENABLED:
                    self.schedule_fault(t)
        elif t >= self.fault_at:
            code = self.rng.choice(EMCY_CODES)
            data = struct.pack("<HB5s", code, 0x01 | (0x08 if code >> 12 == 4 else 0), bytes(5))
            self.pending.append((0x80 + n, data))
            self.statusword = FAULT_REACTION_ACTIVE
            self.reset_at = t + 40_000

    def velocity(self, t: int) -> int:
        if self.statusword != OPERATION_ENABLED:
            return 0
        return int(50_000 * math.sin(self.phase + t / 700_000))


def sdo_download(node: int, index: int, sub: int, value: int, size: int):
    cs = {1: 0x2F, 2: 0x2B, 4: 0x23}[size]
    yield 0x600 + node, struct.pack("<BHBI", cs, index, sub, value)
    yield 0x580 + node, struct.pack("<BHB4x", 0x60, index, sub)


def configure(node: int):
    # An upload of device type 1000h: 0x00020192, a drive (CiA 402).
    yield 0x600 + node, struct.pack("<BHB4x", 0x40, 0x1000, 0)
    yield 0x580 + node, struct.pack("<BHBI", 0x43, 0x1000, 0, 0x0002_0192)
    writes = [
        (0x1800, 1, 0x8000_0180 + node, 4), (0x1A00, 0, 0, 1), (0x1A00, 1, 0x6041_0010, 4),
        (0x1A00, 2, 0x6064_0020, 4), (0x1A00, 0, 2, 1), (0x1800, 2, 1, 1), (0x1800, 1, 0x180 + node, 4),
        (0x1801, 1, 0x8000_0280 + node, 4), (0x1A01, 0, 0, 1), (0x1A01, 1, 0x606C_0020, 4),
        (0x1A01, 0, 1, 1), (0x1801, 2, 1, 1), (0x1801, 1, 0x280 + node, 4),
        (0x1017, 0, HEARTBEAT_US // 1_000, 2),
    ]
    for index, sub, value, size in writes:
        yield from sdo_download(node, index, sub, value, size)


def frames(rng: random.Random):
    """(time in µs, identifier, data) for ever."""
    t = 1_700_000_000_000_000
    for n in DRIVES:
        yield t, 0x700 + n, b"\x00"
        t += rng.randint(200, 400)
    for n in DRIVES:
        for cid, data in configure(n):
            yield t, cid, data
            t += rng.randint(400, 900)
    yield t, 0x000, b"\x01\x00"
    drives = [Drive(n, rng) for n in DRIVES]
    for d in drives:
        d.next_step = t + 2_000
    cycle = 0
    while True:
        t += SYNC_US
        cycle += 1
        at = t
        yield at, 0x080, b""
        for d in drives:
            d.step(t)
            for cid, data in d.pending:
                at += rng.randint(10, 30)
                yield at, cid, data
            d.pending.clear()
            v = d.velocity(t)
            d.position = (d.position + v // 1_000 + 2**31) % 2**32 - 2**31
            at += rng.randint(10, 30)
            yield at, 0x180 + d.node, struct.pack("<Hi", d.statusword, d.position)
            at += rng.randint(10, 30)
            yield at, 0x280 + d.node, struct.pack("<i", v)
        if cycle % (HEARTBEAT_US // SYNC_US) == 0:
            for d in drives:
                at += rng.randint(10, 30)
                yield at, 0x700 + d.node, b"\x05"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=1_000_000)
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("-o", "--output", default="-")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    out = sys.stdout if args.output == "-" else open(args.output, "w", encoding="ascii", newline="\n")
    lines = []
    for i, (t, cid, data) in enumerate(frames(rng)):
        if i == args.frames:
            break
        lines.append(f"({t // 1_000_000}.{t % 1_000_000:06d}) can0 {cid:03X}#{data.hex().upper()}\n")
        if len(lines) == 65_536:
            out.write("".join(lines))
            lines.clear()
    out.write("".join(lines))
    out.flush()


if __name__ == "__main__":
    main()
