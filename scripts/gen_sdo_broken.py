#!/usr/bin/env python3
"""Write tests/fixtures/sdo/broken.log and broken.json: hand-made SDO frames
that a working stack never sends, one scenario per node, and what
docs/canopen.md#transfers says the transfer tracker must report for each
transfer.

The frames are written here, not recorded: each scenario below lists its
frames (time offset in ms, COB-ID, data hex) and its transfers. The line
numbers in broken.json are computed from the order of the frames, so the
log and the JSON cannot drift apart. tests/fixtures/sdo/README.md explains
every scenario. Run from the repository root:

    python3 scripts/gen_sdo_broken.py
"""

import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "sdo")
IFACE = "can0"
T0 = 1_700_000_000.0

# A transfer: the keys of python_canopen.json, with `first`/`last` (and
# `reported`, the frame whose record carries the transfer, or None when only
# the summary can) given as frame labels, resolved to line numbers below.
SCENARIOS = []


def scenario(name, frames, transfers):
    SCENARIOS.append((name, frames, transfers))


def transfer(node, direction, index, subindex, outcome, first, last, reported,
             reason, data=None, size=None, size_indicated=None, expedited=False,
             block=False, abort_code=None, abort_by=None):
    return {
        "node": node, "iface": IFACE, "direction": direction, "index": index,
        "subindex": subindex, "size": size, "size_indicated": size_indicated,
        "data": data, "outcome": outcome, "abort_code": abort_code,
        "abort_by": abort_by, "block": block, "expedited": expedited,
        "frames": None, "first_line": first, "last_line": last, "reported_line": reported,
        "reason": reason,
    }


# A: segmented download whose second segment repeats toggle 0.
scenario("wrong toggle", [
    ("a1", 0, 0x610, "210021000E000000"),  # initiate download 2100h/00, s=1, size 14
    ("a2", 1, 0x590, "6000210000000000"),  # initiate download response
    ("a3", 2, 0x610, "00" + "41424344454647"),  # segment t=0, 7 bytes, c=0
    ("a4", 3, 0x590, "2000000000000000"),  # segment response t=0
    ("a5", 4, 0x610, "01" + "48494A4B4C4D4E"),  # segment t=0 again (1 expected), c=1
], [
    transfer(0x10, "download", 0x2100, 0, "broken", "a1", "a5", "a5",
             "download segment with toggle 0 where 1 was expected (line {a5})",
             data="41424344454647", size_indicated=14),
])

# B: an initiate upload that is never answered, then a new request.
scenario("timeout", [
    ("b1", 20, 0x611, "4000100000000000"),  # initiate upload 1000h/00
    ("b2", 520, 0x611, "4018100100000000"),  # 0.5 s later: initiate upload 1018h/01
    ("b3", 521, 0x591, "431810016A000000"),  # answer to b2: 4 bytes
], [
    transfer(0x11, "upload", 0x1000, 0, "timeout", "b1", "b1", "b2",
             "no response before the next request (line {b2}), 500 ms later"),
    transfer(0x11, "upload", 0x1018, 1, "ok", "b2", "b3", "b3",
             "expedited upload, 4 bytes", data="6a000000", size=4,
             size_indicated=4, expedited=True),
])

# C: a server frame with no request open on its channel.
scenario("unanswered response", [
    ("c1", 540, 0x592, "4300100092010200"),  # initiate upload response, nobody asked
], [
    transfer(0x12, "upload", 0x1000, 0, "broken", "c1", "c1", "c1",
             "initiate upload response that answers no request",
             size_indicated=4, expedited=True),
])

# D: segmented upload announcing 10 bytes and delivering 12.
scenario("size mismatch", [
    ("d1", 560, 0x613, "4000210000000000"),  # initiate upload 2100h/00
    ("d2", 561, 0x593, "410021000A000000"),  # segmented, s=1, size 10
    ("d3", 562, 0x613, "6000000000000000"),  # upload segment request t=0
    ("d4", 563, 0x593, "00" + "30313233343536"),  # t=0, 7 bytes, c=0
    ("d5", 564, 0x613, "7000000000000000"),  # upload segment request t=1
    ("d6", 565, 0x593, "15" + "37383941420000"),  # t=1, n=2 (5 bytes), c=1: 12 in all
], [
    transfer(0x13, "upload", 0x2100, 0, "broken", "d1", "d6", "d6",
             "size indicated 10, 12 bytes delivered",
             data="303132333435363738394142", size=12, size_indicated=10),
])

# E: a new initiate upload while a segmented upload is still open.
scenario("cut off", [
    ("e1", 580, 0x614, "4008100000000000"),  # initiate upload 1008h/00
    ("e2", 581, 0x594, "4108100015000000"),  # segmented, size 21
    ("e3", 582, 0x614, "6000000000000000"),  # upload segment request t=0
    ("e4", 583, 0x594, "00" + "6D6F74696F6E77"),  # "motionw", c=0
    ("e5", 584, 0x614, "4000100000000000"),  # new initiate upload 1000h/00
    ("e6", 585, 0x594, "4300100092010200"),  # its answer
], [
    transfer(0x14, "upload", 0x1008, 0, "broken", "e1", "e4", "e5",
             "cut off by a new request (line {e5}) after 7 of 21 bytes",
             data="6d6f74696f6e77", size_indicated=21),
    transfer(0x14, "upload", 0x1000, 0, "ok", "e5", "e6", "e6",
             "expedited upload, 4 bytes", data="92010200", size=4,
             size_indicated=4, expedited=True),
])

# F: a segmented download on node 0x15 and a segmented upload on node 0x16,
# frame by frame interleaved: both complete.
scenario("interleaved", [
    ("f1", 600, 0x615, "210121000A000000"),  # 0x15: initiate download 2101h/00, size 10
    ("f2", 601, 0x616, "400A100000000000"),  # 0x16: initiate upload 100Ah/00
    ("f3", 602, 0x595, "6001210000000000"),  # 0x15: response
    ("f4", 603, 0x596, "410A100009000000"),  # 0x16: segmented, size 9
    ("f5", 604, 0x615, "00" + "61626364656667"),  # 0x15: segment t=0 "abcdefg"
    ("f6", 605, 0x616, "6000000000000000"),  # 0x16: upload segment request t=0
    ("f7", 606, 0x596, "00" + "667720322E342E"),  # 0x16: "fw 2.4." t=0
    ("f8", 607, 0x595, "2000000000000000"),  # 0x15: segment response t=0
    ("f9", 608, 0x615, "19" + "68696A00000000"),  # 0x15: t=1, n=4 "hij", c=1
    ("f10", 609, 0x616, "7000000000000000"),  # 0x16: upload segment request t=1
    ("f11", 610, 0x595, "3000000000000000"),  # 0x15: segment response t=1 (done)
    ("f12", 611, 0x596, "1B" + "31350000000000"),  # 0x16: t=1, n=5 "15", c=1 (done)
], [
    transfer(0x15, "download", 0x2101, 0, "ok", "f1", "f11", "f11",
             "segmented download, 10 bytes, interleaved with node 0x16",
             data="6162636465666768696a", size=10, size_indicated=10),
    transfer(0x16, "upload", 0x100A, 0, "ok", "f2", "f12", "f12",
             "segmented upload, 9 bytes, interleaved with node 0x15",
             data="667720322e342e3135", size=9, size_indicated=9),
])

# G: the initiate upload response is cut to 5 bytes.
scenario("truncated frame", [
    ("g1", 640, 0x617, "4000100000000000"),  # initiate upload 1000h/00
    ("g2", 641, 0x597, "4300100092"),  # e=1, s=1, n=0 (4 bytes) but only 1 data byte
], [
    transfer(0x17, "upload", 0x1000, 0, "broken", "g1", "g2", "g2",
             "the response is 5 bytes long: the 4 data bytes it announces are cut to 1",
             size_indicated=4, expedited=True),
])

# H: block download whose sub-block skips sequence number 3.
scenario("missing block sequence number", [
    ("h1", 660, 0x618, "C20023001C000000"),  # block download initiate 2300h/00, s=1, size 28, no CRC
    ("h2", 661, 0x598, "A000230004000000"),  # response, no CRC, blksize 4
    ("h3", 662, 0x618, "01" + "62626262626262"),  # seqno 1
    ("h4", 663, 0x618, "02" + "63636363636363"),  # seqno 2
    ("h5", 664, 0x618, "84" + "65656565656565"),  # seqno 4, c=1: 3 is missing
], [
    transfer(0x18, "download", 0x2300, 0, "broken", "h1", "h5", "h5",
             "block segment with sequence number 4 where 3 was expected",
             data="6262626262626263636363636363", size_indicated=28, block=True),
])

# I: the log ends inside two transfers: one waiting for the client's next
# segment request, one initiate never answered.
scenario("input ends mid-transfer", [
    ("i1", 680, 0x619, "4008100000000000"),  # initiate upload 1008h/00
    ("i2", 681, 0x599, "4108100015000000"),  # segmented, size 21
    ("i3", 682, 0x619, "6000000000000000"),  # upload segment request t=0
    ("i4", 683, 0x599, "00" + "6D6F74696F6E77"),  # "motionw", c=0; then nothing
    ("i5", 700, 0x61A, "4000100000000000"),  # node 0x1A: initiate upload, never answered
], [
    transfer(0x19, "upload", 0x1008, 0, "broken", "i1", "i4", None,
             "the input ends mid-transfer after 7 of 21 bytes (summary only)",
             data="6d6f74696f6e77", size_indicated=21),
    transfer(0x1A, "upload", 0x1000, 0, "timeout", "i5", "i5", None,
             "no response before the end of the input (summary only)"),
])


def main():
    lines, where = [], {}
    for _name, frames, _transfers in SCENARIOS:
        for label, ms, cob, data in frames:
            assert label not in where, label
            bytes.fromhex(data)
            lines.append(f"({T0 + ms / 1000:.6f}) {IFACE} {cob:03X}#{data.upper()}")
            where[label] = len(lines)
    truth = []
    for _name, frames, transfers in SCENARIOS:
        for t in transfers:
            for key in ("first_line", "last_line", "reported_line"):
                if t[key] is not None:
                    t[key] = where[t[key]]
            t["reason"] = t["reason"].format(**where)
            # Every frame of the transfer's channel from its first to its last.
            cobs = (0x600 + t["node"], 0x580 + t["node"])
            t["frames"] = sum(1 for line in lines[t["first_line"] - 1:t["last_line"]]
                              if int(line.split()[2].split("#")[0], 16) in cobs)
            truth.append(t)
    truth.sort(key=lambda t: (t["first_line"], t["node"]))
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "broken.log"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(OUT, "broken.json"), "w") as f:
        json.dump(truth, f, indent=1)
        f.write("\n")
    print(f"{len(lines)} frames, {len(truth)} transfers")


if __name__ == "__main__":
    main()
