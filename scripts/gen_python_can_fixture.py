#!/usr/bin/env python3
"""Write tests/fixtures/python_can.log with python-can's own candump writer
(CanutilsLogWriter) and tests/fixtures/python_can.json with what python-can's
own reader (CanutilsLogReader) reads back from that file, frame by frame.

The frames cover what the candump reader must take from a real writer: data
frames, remote requests, extended identifiers, CAN FD with BRS/ESI, and
error frames (python-can writes every error frame as 20000080#…).
Run: python3 scripts/gen_python_can_fixture.py  (python-can 4.x)
"""
import json
import os

import can

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures")
LOG = os.path.join(OUT, "python_can.log")
TRUTH = os.path.join(OUT, "python_can.json")

t0 = 1700000000.000500
frames = [
    can.Message(timestamp=t0, channel="can0", arbitration_id=0x081,
                data=bytes([0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0]), is_extended_id=False),
    can.Message(timestamp=t0 + 0.001, channel="can0", arbitration_id=0x705,
                data=b"\x05", is_extended_id=False),
    can.Message(timestamp=t0 + 0.002, channel="can0", arbitration_id=0x705,
                is_remote_frame=True, dlc=1, is_extended_id=False),
    can.Message(timestamp=t0 + 0.003, channel="can1", arbitration_id=0x18FF1234,
                data=b"\x01\x02", is_extended_id=True),
    can.Message(timestamp=t0 + 0.004, channel="can0", arbitration_id=0x185,
                data=bytes(range(12)), is_fd=True, bitrate_switch=True,
                is_extended_id=False),
    can.Message(timestamp=t0 + 0.005, channel="can0", arbitration_id=0x185,
                data=bytes(range(64)), is_fd=True, error_state_indicator=True,
                is_extended_id=False),
    can.Message(timestamp=t0 + 0.006, channel="can0", arbitration_id=0,
                data=bytes([0, 0x04, 0, 0, 0, 0, 0, 0]), is_error_frame=True),
    can.Message(timestamp=t0 + 0.007, channel="can0", arbitration_id=0x123,
                data=b"", is_extended_id=False),
    can.Message(timestamp=t0 + 0.008, channel="vcan0", arbitration_id=0x601,
                data=bytes([0x40, 0x08, 0x10, 0, 0, 0, 0, 0]), is_extended_id=False),
]

os.makedirs(OUT, exist_ok=True)
with can.CanutilsLogWriter(LOG) as writer:
    for frame in frames:
        writer.on_message_received(frame)

truth = []
for msg in can.CanutilsLogReader(LOG):
    truth.append({
        "timestamp": f"{msg.timestamp:.6f}",
        "channel": msg.channel,
        "arbitration_id": msg.arbitration_id,
        "is_extended_id": msg.is_extended_id,
        "is_remote_frame": msg.is_remote_frame,
        "is_error_frame": msg.is_error_frame,
        "is_fd": msg.is_fd,
        "bitrate_switch": msg.bitrate_switch,
        "error_state_indicator": msg.error_state_indicator,
        "dlc": msg.dlc,
        "data": bytes(msg.data).hex(),
    })
with open(TRUTH, "w") as f:
    json.dump({"python_can": can.__version__, "frames": truth}, f, indent=1)
    f.write("\n")
print(f"{len(truth)} frames: {LOG}, {TRUTH}")
