#!/usr/bin/env python3
"""Generate a candump log of an EMCY storm, the worst traffic for the report
(docs/report.md#bounded, BENCHMARKS.md "Issue 23"): of every frame, 30 % an
EMCY from one of 127 nodes (one in ten a reset), 20 % a heartbeat (one in a
thousand a boot-up, one in fifty pre-operational), 5 % SYNC and 45 % a TPDO1
of a random length. Deterministic for a seed.

    python3 scripts/gen_storm.py --frames 1000000 -o /tmp/storm.log
"""

import argparse
import random
import sys


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=1_000_000)
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("-o", "--output", default="-")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    out = sys.stdout if args.output == "-" else open(args.output, "w")
    codes = [0x1000, 0x2310, 0x3210, 0x4210, 0x5530, 0x7305, 0x8110, 0x8130, 0xFF00]
    t = 1_700_000_000_000_000
    lines = []
    for _ in range(args.frames):
        t += rng.randint(50, 150)
        ts = f"({t // 1_000_000}.{t % 1_000_000:06d}) can0 "
        r = rng.random()
        node = rng.randint(1, 127)
        if r < 0.30:
            code = 0 if rng.random() < 0.1 else rng.choice(codes)
            reg = 0 if code == 0 else rng.choice([1, 3, 5, 9, 0x11, 0x81])
            data = bytes([code & 0xFF, code >> 8, reg]) + bytes(rng.getrandbits(8) for _ in range(5))
            lines.append(f"{ts}{0x80 + node:03X}#{data.hex().upper()}\n")
        elif r < 0.50:
            s = rng.random()
            state = 0x00 if s < 0.001 else 0x7F if s < 0.021 else 0x05
            lines.append(f"{ts}{0x700 + node:03X}#{state:02X}\n")
        elif r < 0.55:
            lines.append(f"{ts}080#\n")
        else:
            n = rng.randint(0, 8)
            data = bytes(rng.getrandbits(8) for _ in range(n))
            lines.append(f"{ts}{0x180 + node:03X}#{data.hex().upper()}\n")
        if len(lines) >= 65536:
            out.write("".join(lines))
            lines.clear()
    out.write("".join(lines))


if __name__ == "__main__":
    main()
