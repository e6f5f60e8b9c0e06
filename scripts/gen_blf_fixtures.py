#!/usr/bin/env python3
"""Write the Vector BLF fixtures of tests/library/blf.rs with python-can's
BLFWriter, and beside each a JSON file with what python-can's BLFReader reads
back.

- python_can.blf: compressed (zlib) containers; classic, remote, extended,
  CAN FD with BRS/ESI at 12 and 64 bytes, an error frame, two channels,
  Tx and Rx.
- python_can_stored.blf: the same frames, compression_level=0 (stored
  containers).
- python_can_many.blf: 600 frames in containers of 1 KiB, so objects
  continue from one container into the next (truth as short rows: time,
  channel, id, data).
- error_ext.blf: CAN_ERROR_EXT objects written through BLFWriter's own
  object writer (its containers and headers; python-can's error frames
  carry flags 0): CANoe 10's form (flags 0xFFFE, bit 0 clear and bit 1
  set: the error byte 0x81 is a Vector CAN-Core code, form error,
  received; extended flags 0x2060 say the same), an SJA1000 error code
  capture (flags 1, byte 0xA3: stuff error, received, segment 3), a
  CAN-Core CRC error while sending (0xC4) and python-can's own (flags 0),
  between two data frames. `python3 scripts/gen_blf_fixtures.py
  error_ext` writes only this one.

Run: python3 scripts/gen_blf_fixtures.py   (python-can 4.x)
"""
import json
import os
import sys

import can
from can.io.blf import CAN_ERROR_EXT, CAN_ERROR_EXT_STRUCT

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "blf")

T0 = 1700000000.5


def frames():
    out = [
        can.Message(timestamp=T0, channel=0, arbitration_id=0x081,
                    data=bytes([0x30, 0x81, 0x11, 0x01, 0, 0, 0, 0]), is_extended_id=False),
        can.Message(timestamp=T0 + 0.001, channel=0, arbitration_id=0x705, data=b"\x05",
                    is_extended_id=False),
        can.Message(timestamp=T0 + 0.002, channel=1, arbitration_id=0x705, is_remote_frame=True,
                    dlc=1, is_extended_id=False),
        can.Message(timestamp=T0 + 0.003, channel=1, arbitration_id=0x18FF1234, data=b"\x01\x02",
                    is_extended_id=True, is_rx=False),
        can.Message(timestamp=T0 + 0.004, channel=0, arbitration_id=0x185, data=bytes(range(12)),
                    is_fd=True, bitrate_switch=True, is_extended_id=False),
        can.Message(timestamp=T0 + 0.005, channel=0, arbitration_id=0x1FFFFFFF,
                    data=bytes(range(64)), is_fd=True, error_state_indicator=True,
                    is_extended_id=True, is_rx=False),
        can.Message(timestamp=T0 + 0.006, channel=0, is_error_frame=True, arbitration_id=0,
                    data=bytes(8), dlc=8),
        can.Message(timestamp=T0 + 0.007, channel=0, arbitration_id=0x123, data=b"",
                    is_extended_id=False),
        can.Message(timestamp=T0 + 0.0081234567, channel=1, arbitration_id=0x7FF,
                    data=bytes([0xFF] * 8), is_extended_id=False),
    ]
    for i in range(30):
        out.append(can.Message(timestamp=T0 + 0.01 + i * 0.0015, channel=i % 2,
                               arbitration_id=0x181 + (i % 5), data=bytes([i, i * 3 % 256]),
                               is_extended_id=False, is_rx=i % 3 != 0))
    return out


def message_json(msg):
    return {
        "timestamp": f"{msg.timestamp:.9f}",
        "channel": msg.channel + 1,
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


def compact(msg):
    """One frame as a short row: time, channel, id, data."""
    return [f"{msg.timestamp:.9f}", msg.channel + 1, msg.arbitration_id, bytes(msg.data).hex()]


def write(name, messages, short=False, **options):
    path = os.path.join(OUT, name)
    with can.BLFWriter(path, **options) as writer:
        for msg in messages:
            writer.on_message_received(msg)
    with can.BLFReader(path) as reader:
        start = reader.start_timestamp
        read = [compact(m) if short else message_json(m) for m in reader]
    with open(path.replace(".blf", ".json"), "w") as f:
        json.dump({"python_can": can.__version__, "read_from": name,
                   "start_timestamp": f"{start:.3f}",
                   "note": "channel is python-can's plus 1 (python-can counts from 0); "
                           "timestamps are python-can's floats",
                   "frames": read}, f, indent=1)
        f.write("\n")


def error_ext():
    """error_ext.blf (see the module's documentation)."""
    name = "error_ext.blf"
    path = os.path.join(OUT, name)
    data_frame = can.Message(timestamp=T0, channel=0, arbitration_id=0x181, data=b"\x01\x02",
                             is_extended_id=False)
    # (channel as the file writes it, flags, error byte, extended flags).
    objects = [(1, 0xFFFE, 0x81, 0x2060), (2, 0x1, 0xA3, 0x0), (1, 0xFFFE, 0xC4, 0x3000),
               (1, 0x0, 0x0, 0x0)]
    with can.BLFWriter(path) as writer:
        writer.on_message_received(data_frame)
        for i, (channel, flags, ecc, flags_ext) in enumerate(objects):
            body = CAN_ERROR_EXT_STRUCT.pack(channel, 0, flags, ecc, 0, 0, 0, 0, flags_ext,
                                             bytes(8))
            writer._add_object(CAN_ERROR_EXT, body, T0 + 0.001 * (i + 1))  # noqa: SLF001
        data_frame.timestamp = T0 + 0.01
        writer.on_message_received(data_frame)
    with can.BLFReader(path) as reader:
        start = reader.start_timestamp
        read = [message_json(m) for m in reader]
    with open(path.replace(".blf", ".json"), "w") as f:
        json.dump({"python_can": can.__version__, "read_from": name,
                   "start_timestamp": f"{start:.3f}",
                   "note": "channel is python-can's plus 1 (python-can counts from 0); "
                           "timestamps are python-can's floats; python-can reads a "
                           "CAN_ERROR_EXT as the object's identifier and data",
                   "written": [{"channel": c, "flags": f, "ecc": e, "flags_ext": x}
                               for c, f, e, x in objects],
                   "frames": read}, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    if sys.argv[1:2] == ["error_ext"]:
        error_ext()
        sys.exit(0)
    write("python_can.blf", frames())
    write("python_can_stored.blf", frames(), compression_level=0)
    many = []
    for i in range(600):
        many.append(can.Message(timestamp=T0 + i * 0.0001, channel=i % 3,
                                arbitration_id=0x100 + i % 0x600,
                                data=bytes([(i + k) % 256 for k in range(i % 9)]),
                                is_extended_id=False))
    write("python_can_many.blf", many, short=True, max_container_size=1024)
    error_ext()
