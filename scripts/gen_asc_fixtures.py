#!/usr/bin/env python3
"""Write the Vector ASC fixtures of tests/codecs/asc.rs with real writers, and
beside each a JSON file with what a real reader reads back, frame by frame.

- python_can.asc: python-can's ASCWriter (base hex, absolute times; classic,
  remote, extended, CAN FD with BRS/ESI at 12 and 64 bytes, an error frame,
  two channels, Tx and Rx); truth: python-can's ASCReader.
- log2asc.asc and log2asc_fd.asc: can-utils' log2asc from log2asc_in.log
  (a candump log), the second with -f (every frame in the CANFD form);
  truth: can-utils' asc2log reading them back into candump lines.
- canoe.asc: hand-written in the shapes CANoe writes (as python-can's own
  test data, test/data/logfile.asc and test_CanFdMessage64.asc, has them;
  our identifiers and data): statistics after classic data and right
  after a remote request's `r` (`Tx r Length = 1704000 BitCount = 145 ID =
  88888888x`), `r 8` with statistics, error frames with CANoe's details,
  CANFD lines with EDL (0x1000) and, at 12 and 64 bytes, without it (flags
  `0`), a CANFD remote request (flags 0x200050, length 0); truth:
  python-can's ASCReader.
- handmade_dec_relative.asc: hand-written (python-can cannot write it):
  base dec, timestamps relative, a symbolic name in a CANFD line, TxRq,
  Statistic and chip status lines; truth: python-can's ASCReader (which, in
  4.6, returns relative times as written) with, beside each frame, the time
  since the start: the deltas of every event line added up.
- canoe15.asc: hand-written in the shapes of CANoe 15's logs and of CSS
  Electronics' ASC conversions: `TriggerEvent: TriggerBlock[Logging]
  Start/Stop DirectLogging` lines, and classic-syntax lines with DLC 9
  followed by 12 data bytes (the recording's 12-byte CAN FD frames), by 8
  (a classic frame of DLC 9), and with CANoe's statistics after the data;
  truth: python-can's ASCReader.

Run: python3 scripts/gen_asc_fixtures.py   (python-can 4.x; can-utils'
log2asc and asc2log on the PATH, e.g. Debian's can-utils package)
     python3 scripts/gen_asc_fixtures.py canoe   (canoe.asc alone: python-can only)
     python3 scripts/gen_asc_fixtures.py canoe15   (canoe15.asc alone)
"""
import json
import os
import subprocess

import can

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "asc")


def message_json(msg, channel_from_one):
    return {
        "timestamp": f"{msg.timestamp:.6f}",
        "channel": None if msg.channel is None else msg.channel + (1 if channel_from_one else 0),
        "id": msg.arbitration_id,
        "extended": msg.is_extended_id,
        "rtr": msg.is_remote_frame,
        "fd": msg.is_fd,
        "brs": msg.bitrate_switch,
        "esi": msg.error_state_indicator,
        "error": msg.is_error_frame,
        "dlc": msg.dlc,
        "data": bytes(msg.data).hex(),
        "rx": msg.is_rx,
    }


def python_can():
    t0 = 1700000000.0005
    frames = [
        can.Message(timestamp=t0, channel=0, arbitration_id=0x081,
                    data=bytes([0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0]), is_extended_id=False),
        can.Message(timestamp=t0 + 0.001, channel=0, arbitration_id=0x705, data=b"\x05",
                    is_extended_id=False),
        can.Message(timestamp=t0 + 0.002, channel=1, arbitration_id=0x705, is_remote_frame=True,
                    dlc=1, is_extended_id=False),
        can.Message(timestamp=t0 + 0.003, channel=1, arbitration_id=0x18FF1234, data=b"\x01\x02",
                    is_extended_id=True, is_rx=False),
        can.Message(timestamp=t0 + 0.004, channel=0, arbitration_id=0x185, data=bytes(range(12)),
                    is_fd=True, bitrate_switch=True, is_extended_id=False),
        can.Message(timestamp=t0 + 0.005, channel=0, arbitration_id=0x1FFFFFFF,
                    data=bytes(range(64)), is_fd=True, error_state_indicator=True,
                    is_extended_id=True),
        can.Message(timestamp=t0 + 0.006, channel=0, is_error_frame=True),
        can.Message(timestamp=t0 + 0.007, channel=0, arbitration_id=0x123, data=b"",
                    is_extended_id=False),
        can.Message(timestamp=t0 + 0.0081234, channel=1, arbitration_id=0x7FF,
                    data=bytes([0xFF] * 8), is_extended_id=False),
    ]
    # Thirty more: heartbeats and PDOs on both channels.
    for i in range(30):
        frames.append(can.Message(timestamp=t0 + 0.01 + i * 0.0015, channel=i % 2,
                                  arbitration_id=0x181 + (i % 5), data=bytes([i, i * 3 % 256]),
                                  is_extended_id=False, is_rx=i % 3 != 0))
    path = os.path.join(OUT, "python_can.asc")
    with can.ASCWriter(path) as writer:
        for msg in frames:
            writer.on_message_received(msg)
    with can.ASCReader(path) as reader:
        read = [message_json(m, True) for m in reader]
    with open(os.path.join(OUT, "python_can.json"), "w") as f:
        json.dump({"python_can": can.__version__, "read_from": "python_can.asc",
                   "note": "channel is python-can's plus 1 (python-can counts from 0)",
                   "frames": read}, f, indent=1)
        f.write("\n")


CANDUMP = """\
(1700000000.000500) can0 081#1081110000000000
(1700000000.001000) can0 705#05
(1700000000.002000) can1 705#R
(1700000000.003000) can0 18FF1234#0102
(1700000000.004000) can0 185##1000102030405060708090A0B
(1700000000.005000) can1 186##30001020304050607
(1700000000.006000) can0 20000080#0000000000000000
(1700000000.007000) can0 123#
(1700000000.008000) can0 701#R1
(1700000000.009999) can1 1FFFFFFF#DEADBEEF
(1700000000.010000) can0 7FF#FFFFFFFFFFFFFFFF
"""


def parse_candump(line):
    """A candump log line as asc2log writes it: (ts) iface id#data [dir]."""
    ts, iface, frame, *rest = line.split()
    ident, _, data = frame.partition("#")
    fd = data.startswith("#")
    flags = 0
    if fd:
        flags = int(data[1], 16)
        data = data[2:]
    rtr = data.startswith("R")
    dlc = int(data[1:] or "0") if rtr else len(data) // 2
    raw = int(ident, 16)
    error = len(ident) == 8 and raw & 0x20000000 != 0
    return {
        "ts": ts.strip("()"),
        "channel": int(iface[3:]) + 1,
        "id": raw & 0x1FFFFFFF,
        "extended": len(ident) == 8,
        "rtr": rtr,
        "fd": fd,
        "brs": bool(flags & 1),
        "esi": bool(flags & 2),
        "error": error,
        "dlc": dlc,
        "data": "" if rtr else data.lower(),
        "direction": rest[0] if rest else None,
    }


def can_utils():
    src = os.path.join(OUT, "log2asc_in.log")
    with open(src, "w") as f:
        f.write(CANDUMP)
    for name, options in (("log2asc.asc", []), ("log2asc_fd.asc", ["-f"])):
        path = os.path.join(OUT, name)
        with open(path, "w") as f:
            subprocess.run(["log2asc", "-I", src, *options, "can0", "can1"], stdout=f, check=True,
                           env={**os.environ, "TZ": "UTC"})
        back = subprocess.run(["asc2log", "-I", path], capture_output=True, text=True,
                              check=True, env={**os.environ, "TZ": "UTC"}).stdout
        frames = [parse_candump(line) for line in back.splitlines() if line.strip()]
        # asc2log adds the date line's time: keep the time since the first
        # frame, which is what the file holds.
        first = float(frames[0]["ts"]) if frames else 0.0
        for fr in frames:
            # asc2log's absolute time depends on when it ran: not kept.
            fr["since_first"] = f"{float(fr.pop('ts')) - first:.6f}"
        with open(path.replace(".asc", ".json"), "w") as f:
            json.dump({"tool": "can-utils log2asc " + " ".join(options) + " / asc2log",
                       "read_from": name, "frames": frames}, f, indent=1)
            f.write("\n")


HANDMADE = """\
date Mon Nov 23 07:35:00.000 2026
base dec  timestamps relative
// hand-written (python-can cannot write base dec or relative times):
// decimal identifiers and data, relative times, a CANFD line with a
// symbolic name, a transmit request, statistics and a chip status line
internal events logged
Begin Triggerblock Mon Nov 23 07:35:00.000 2026
   0.000000 Start of measurement
   0.001000 1  129             Rx   d 8 48 129 17 0 0 0 0 0
   0.000500 2  1797            Tx   d 1 5
   0.000250 1  1797            TxRq d 1 5
   0.000250 1  1797            Rx   r 1
   0.001000 1  419369524x      Rx   d 2 1 2
   0.000125 CANFD   2 Rx        389  PdoName                          1 0 9 12 0 1 2 3 4 5 6 7 8 9 10 11   130000  130     3000 0 0 0 0 0
   0.002000 1  Statistic: D 0 R 0 XD 0 XR 0 E 0 O 0 B 0.00%
   0.000001 CAN 1 Status:chip status error active
   0.000999 2  ErrorFrame
   0.010000 1  1793            Rx   d 1 127
End TriggerBlock
"""


def handmade():
    path = os.path.join(OUT, "handmade_dec_relative.asc")
    with open(path, "w") as f:
        f.write(HANDMADE)
    with can.ASCReader(path, relative_timestamp=False) as reader:
        start = None
        read = []
        for m in reader:
            read.append(message_json(m, True))
        start = reader.start_time
    # python-can 4.6 returns relative times as written (the deltas). The
    # time since the start adds up the deltas of every event line; the
    # k-th line python-can's own pattern takes for a frame is its k-th
    # frame.
    import re
    pattern = re.compile(r"\d+\.\d+\s+(\d+\s+(\w+\s+(Tx|Rx)|ErrorFrame)|CANFD)",
                         re.ASCII | re.IGNORECASE)
    since_start = []
    total = 0.0
    for line in HANDMADE.splitlines():
        text = line.strip()
        if re.match(r"\d+\.\d+\s", text):
            total += float(text.split()[0])
            if pattern.match(text):
                since_start.append(f"{total:.6f}")
    assert len(since_start) == len(read), (since_start, read)
    for fr, t in zip(read, since_start):
        fr["delta_as_written"] = fr["timestamp"]
        fr["since_start"] = t
    with open(path.replace(".asc", ".json"), "w") as f:
        json.dump({"python_can": can.__version__, "read_from": "handmade_dec_relative.asc",
                   "note": "ASCReader(relative_timestamp=False); since_start adds up the "
                           "deltas of every event line; channel is python-can's plus 1",
                   "frames": read}, f, indent=1)
        f.write("\n")


ZEROS_60 = " ".join(["00"] * 60)
FD64 = "11 22 33 44 " + ZEROS_60
CANOE = f"""date Mon Nov 23 07:35:00.000 am 2026
base hex  timestamps absolute
internal events logged
// version 13.0.0
Begin Triggerblock Mon Nov 23 07:35:00.000 am 2026
   0.000000 Start of measurement
   0.001000 CAN 1 Status:chip status error active
   0.001000 CAN 2 Status:chip status error active
   0.501000 1 ErrorFrame
   0.501010 1 ErrorFrame ECC: 10100010
   0.501020 2 ErrorFrame Flags = 0xe CodeExt = 0x20a2 Code = 0x82 ID = 0 DLC = 0 Position = 5 Length = 11300
   0.510001 1  705             Tx   r
   0.520002 1  603             Tx   r Length = 1704000 BitCount = 145 ID = 1539
   0.584921 2  18FF50E5x       Tx   r 8 Length = 1704000 BitCount = 145 ID = 419385573x
   1.015991 1  Statistic: D 0 R 0 XD 0 XR 0 E 0 O 0 B 0.00%
   1.098426 1  183             Rx   d 6 37 02 A0 86 01 00  Length = 240015 BitCount = 124 ID = 387
   1.148421 2  18FF50E5x       Rx   d 8 01 02 03 04 05 06 07 08    Length = 273910 BitCount = 141 ID = 419385573x
   2.005071 CANFD   1 Rx        283  Drive_TPDO3                      1 0 8  8 37 02 00 00 A0 86 01 00   102203  133   303000 e0006659 46500250 4b140250 20011736 2001040d
   2.005141 CANFD   2 Tx        1C4D80A7x                                   0 1 9 12 01 02 03 04 05 06 07 08 09 0A 0B 0C   130000  150   105000 1a2b3c 46500250 4b140250 20011736 2001040d
   2.300981 CANFD   1 Tx     50005x                                0 0 5 0 140000 73 200050 7a60 46500250 460a0250 20011736 20010205
   2.506898 CANFD   1 Rx        4EE                                   1 0 f 64 {FD64} 1331984 11 0 46500250 460a0250 20011736 20010205
   2.606898 CANFD   2 Rx        1C4D80A8x    AlphaNumericName_2                             0 1 f 64 {FD64} 1331984 11 0 46500250 460a0250 20011736 20010205
   2.706898 CANFD   1 Rx        2A1                                   1 1 9 12 01 02 03 04 05 06 07 08 09 0A 0B 0C 130000 150 0 0 46500250 460a0250 20011736 20010205
   2.806898 CANFD   2 Tx ErrorFrame Not Acknowledge error, dominant error flag fffe c7 31ca Arb. 556 44 0 0 f 64 {" ".join(["00"] * 64)} 1331984 11 0 46500250 460a0250 20011736 20010205
 113.016026 1  Statistic: D 0 R 0 XD 0 XR 0 E 0 O 0 B 0.00%
End TriggerBlock
"""


def canoe():
    path = os.path.join(OUT, "canoe.asc")
    with open(path, "w") as f:
        f.write(CANOE)
    with can.ASCReader(path, relative_timestamp=False) as reader:
        read = [message_json(m, True) for m in reader]
        start = reader.start_time
    for fr in read:
        fr["as_written"] = f"{float(fr['timestamp']) - start:.6f}"
    with open(path.replace(".asc", ".json"), "w") as f:
        json.dump({"python_can": can.__version__, "read_from": "canoe.asc",
                   "note": "ASCReader(relative_timestamp=False); as_written is the time "
                           "less the reader's start_time (the date line); channel is "
                           "python-can's plus 1",
                   "frames": read}, f, indent=1)
        f.write("\n")


CANOE15 = """date Tue Oct 1 10:00:00.000 am 2024
base hex  timestamps absolute
internal events logged
// version 15.0.0
Begin TriggerBlock Tue Oct 1 10:00:00.000 am 2024
   0.000000 Start of measurement
   0.000000 TriggerEvent: TriggerBlock[Logging] Start DirectLogging
   0.001000 1  181             Rx   d 8 01 02 03 04 05 06 07 08
   0.002000 1  2A1             Rx   d 9 01 02 03 04 05 06 07 08 09 0A 0B 0C
   0.003000 1  2A2             Rx   d 9 11 12 13 14 15 16 17 18
   0.004000 1  181             Rx   d 2 01 02  Length = 228000 BitCount = 117 ID = 385
   0.005000 2  18FF1234x       Tx   d 9 00 01 02 03 04 05 06 07 08 09 0A 0B  Length = 300000 BitCount = 150 ID = 419369524x
   0.006000 TriggerEvent: TriggerBlock[Logging] Stop DirectLogging
End TriggerBlock
"""


def canoe15():
    path = os.path.join(OUT, "canoe15.asc")
    with open(path, "w") as f:
        f.write(CANOE15)
    with can.ASCReader(path, relative_timestamp=True) as reader:
        read = [message_json(m, True) for m in reader]
    with open(path.replace(".asc", ".json"), "w") as f:
        json.dump({"python_can": can.__version__, "read_from": "canoe15.asc",
                   "note": "ASCReader(relative_timestamp=True): times as written; channel "
                           "is python-can's plus 1",
                   "frames": read}, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    import sys
    os.makedirs(OUT, exist_ok=True)
    if sys.argv[1:] == ["canoe"]:
        canoe()
        sys.exit(0)
    if sys.argv[1:] == ["canoe15"]:
        canoe15()
        sys.exit(0)
    python_can()
    can_utils()
    handmade()
    canoe()
    canoe15()
