#!/usr/bin/env python3
"""Write the ASAM MDF 4 (MF4) fixtures of tests/library/mf4.rs with the real
writers, and beside each a JSON file with what python-can's MF4Reader
(asammdf underneath) reads back.

Written here:
- python_can.mf4: python-can's MF4Writer, compression_level=2 (DZ blocks,
  transposed + deflate): classic, remote, extended, CAN FD with BRS/ESI at
  12 and 64 bytes, an error frame, channels 0 and 1, Tx and Rx; three data
  groups (CAN_DataFrame, CAN_ErrorFrame, CAN_RemoteFrame), merged by time.
- python_can_deflate.mf4: the same frames, compression_level=1 (DZ, deflate).
- python_can_plain.mf4: the same frames, compression_level=0 (DT blocks),
  with MF4Writer's own start time (the time it was written): the frames'
  offsets from it are negative.
- asammdf_many.mf4: asammdf's MDF.append + save(compression=2) of 2 000
  frames (classic and CAN FD, two channels) in python-can's layout, in
  blocks of 16 KiB: a data list (DL) of several transposed DZ blocks.

The truths of the last four are short rows (message_json's values in its
key order), gzip-compressed.
- asammdf_signals.mf4: python_can.mf4 with a data group of signals
  (`EngineSpeed`, three records, no CAN frame) appended and saved by
  asammdf (compression=2): its records are counted by the group's name.
  `python3 scripts/gen_mf4_fixtures.py signals` writes only this one.
- asammdf_sd.mf4: canedge_vlsd.mf4 sorted and saved by asammdf
  (compression=2): DataBytes a VLSD channel whose data is an SD block in a
  DZ block.
- finalized_empty_groups.mf4: a finalized file (`MDF     `, unfinalized
  flags 0) whose empty groups have header-only DT blocks, as CSS
  Electronics' tools finalize a CANedge recording: python-can's MF4Writer
  (compression_level=0) with data frames only, an empty LIN_Frame group
  appended by asammdf and saved as 4.11; then each empty data group (cycle
  count 0) given a DT block of length 24, and the CAN_DataFrame DT moved
  after them, so that a DT read to the end of the file would run over it.
  `python3 scripts/gen_mf4_fixtures.py empty` writes only this one.
- canedge_vlsd.mf4 and canedge_01_07.mf4 are not written here: they are two
  real CANedge log files (CSS Electronics' public api-examples repository,
  MIT licence: examples/data-processing/LOG/17BD1DB7/00000006/00000170.MF4
  and examples/other/concatenate-mf4-by-period/LOG/2F6913DB/00001089/
  00000002-63BEFDF9.MF4), copied as they are; their truth is made here.
  The first is an unfinalized file of an older firmware: one unsorted data
  group, DataBytes in a VLSD channel group, a DT block whose length was
  never written. The second (firmware 01.07+) has 73 channel groups in one
  unsorted data group, BusChannel/IDE/Dir/EDL virtual, Rx and Tx.

`bench` writes the 1 000 000-frame file of BENCHMARKS.md instead:
    python3 scripts/gen_mf4_fixtures.py bench /tmp/motionwire-bench/1m.mf4

Run: python3 scripts/gen_mf4_fixtures.py   (python-can 4.x, asammdf 8.x; TZ
does not matter: the start time is set in UTC)
"""
import gzip
import json
import os
import struct
import sys
from datetime import datetime, timezone

import can
# First: can.io.mf4 imports asammdf's blocks in an order of its own, and
# finds none of them when asammdf's submodules were imported before it.
from can.io.mf4 import STD_DTYPE, MF4Reader, MF4Writer
import asammdf
import numpy as np
from asammdf import MDF, Signal
from asammdf.blocks.v4_blocks import SourceInformation
from asammdf.blocks.v4_constants import BUS_TYPE_CAN, SOURCE_BUS

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "mf4")

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
        can.Message(timestamp=T0 + 0.009, channel=1, arbitration_id=0x1234, is_remote_frame=True,
                    dlc=8, is_extended_id=True, is_rx=False),
    ]
    for i in range(30):
        out.append(can.Message(timestamp=T0 + 0.01 + i * 0.0015, channel=i % 2,
                               arbitration_id=0x181 + (i % 5), data=bytes([i, i * 3 % 256]),
                               is_extended_id=False, is_rx=i % 3 != 0))
    return out


def message_json(msg):
    return {
        "timestamp": f"{msg.timestamp:.9f}",
        "channel": msg.channel,
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
    """One frame as a short row: the keys of message_json in their order."""
    return list(message_json(msg).values())


def truth(name, short=False):
    """What python-can's MF4Reader reads from the fixture, as JSON beside it."""
    path = os.path.join(OUT, name)
    reader = MF4Reader(path)
    start = reader._start_timestamp  # noqa: SLF001 (the HD start time)
    read = [compact(m) if short else message_json(m) for m in reader]
    reader.stop()
    # Large truths as short rows, gzip-compressed (tests read them so).
    opener = gzip.open if short else open
    suffix = ".json.gz" if short else ".json"
    with opener(path[: path.rindex(".")] + suffix, "wt") as f:
        json.dump({"python_can": can.__version__, "asammdf": asammdf.__version__,
                   "read_from": name, "start_timestamp": f"{start:.9f}",
                   "note": "python-can's MF4Reader: channel as python-can gives it "
                           "(BusChannel), timestamps are floats (start + master)",
                   "frames": read}, f, indent=None if short else 1)
        f.write("\n")


def write_python_can(name, messages, fixed_start=True, **options):
    path = os.path.join(OUT, name)
    writer = MF4Writer(path, **options)
    if fixed_start:
        # A start time that does not change from one run to the next.
        writer._mdf.header.start_time = datetime.fromtimestamp(T0, timezone.utc)  # noqa: SLF001
        writer._start_time = writer.last_timestamp = T0  # noqa: SLF001
    for msg in messages:
        writer.on_message_received(msg)
    writer.stop()
    truth(name)


def asammdf_frames(count, seed=7):
    """`count` frames in python-can's CAN_DataFrame layout (numpy, fast)."""
    rng = np.random.default_rng(seed)
    samples = np.zeros(count, dtype=STD_DTYPE)
    index = np.arange(count)
    fd = (index % 7) == 3
    lengths = np.where(fd, rng.choice([12, 16, 24, 32, 64], count), rng.integers(0, 9, count))
    dlc = np.where(fd, np.searchsorted([0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64],
                                       lengths), lengths)
    extended = (index % 11) == 5
    ids = np.where(extended, rng.integers(0, 0x20000000, count), rng.integers(0, 0x800, count))
    samples["CAN_DataFrame.BusChannel"] = index % 2
    samples["CAN_DataFrame.ID"] = ids
    samples["CAN_DataFrame.IDE"] = extended
    samples["CAN_DataFrame.DLC"] = dlc
    samples["CAN_DataFrame.DataLength"] = lengths
    data = rng.integers(0, 256, (count, 64), dtype=np.uint8)
    data[np.arange(64)[None, :] >= lengths[:, None]] = 0
    samples["CAN_DataFrame.DataBytes"] = data
    samples["CAN_DataFrame.Dir"] = (index % 5) == 0
    samples["CAN_DataFrame.EDL"] = fd
    samples["CAN_DataFrame.BRS"] = fd & ((index % 2) == 0)
    samples["CAN_DataFrame.ESI"] = 0
    timestamps = np.cumsum(rng.integers(50, 400, count)) * 1e-6
    return samples, timestamps


def write_asammdf(path, count, compression=2, fragment=None):
    samples, timestamps = asammdf_frames(count)
    mdf = MDF(version="4.10")
    if fragment:
        # Smaller data blocks than asammdf's default, so that a small file
        # has a data list (DL) of several DZ blocks.
        mdf.configure(write_fragment_size=fragment)
    mdf.header.start_time = datetime.fromtimestamp(T0, timezone.utc)
    mdf.append(Signal(name="CAN_DataFrame", samples=samples, timestamps=timestamps,
                      source=SourceInformation(source_type=SOURCE_BUS, bus_type=BUS_TYPE_CAN)))
    mdf.save(path, overwrite=True, compression=compression)
    mdf.close()


def write_signals():
    """python_can.mf4 with a data group of signals appended by asammdf."""
    source = MDF(os.path.join(OUT, "python_can.mf4"))
    times = np.array([0.05, 0.15, 0.25])
    speed = Signal(np.array([100, 200, 300], dtype=np.uint16), times, name="EngineSpeed")
    source.append([speed], comment="signals")
    source.save(os.path.join(OUT, "asammdf_signals.mf4"), overwrite=True, compression=2)
    source.close()
    truth("asammdf_signals.mf4", short=True)


def write_empty_groups():
    """finalized_empty_groups.mf4 (see the module's documentation)."""
    name = "finalized_empty_groups.mf4"
    path = os.path.join(OUT, name)
    plain = os.path.join(OUT, "empty_groups_plain.tmp.mf4")
    data_frames = [m for m in frames() if not (m.is_error_frame or m.is_remote_frame)]
    writer = MF4Writer(plain, compression_level=0)
    writer._mdf.header.start_time = datetime.fromtimestamp(T0, timezone.utc)  # noqa: SLF001
    writer._start_time = writer.last_timestamp = T0  # noqa: SLF001
    for msg in data_frames:
        writer.on_message_received(msg)
    writer.stop()
    source = MDF(plain)
    empty = np.array([], dtype=np.uint8)
    source.append([Signal(empty, np.array([], dtype=np.float64), name="LIN_Frame.ID")],
                  acq_name="LIN_Frame")
    source = source.convert("4.11")
    source.save(path, overwrite=True, compression=0)
    source.close()
    os.remove(plain)

    data = bytearray(open(path, "rb").read())
    assert data[:8] == b"MDF     " and struct.unpack_from("<H", data, 60)[0] == 0

    def block(at):
        return bytes(data[at:at + 4]), *struct.unpack_from("<QQ", data, at + 8)

    def align():
        data.extend(bytes(-len(data) % 8))

    dg = struct.unpack_from("<Q", data, 64 + 24)[0]
    filled = None
    empties = []
    while dg:
        _, _, links = block(dg)
        next_dg, cg, link = struct.unpack_from("<QQQ", data, dg + 24)
        _, _, cg_links = block(cg)
        cycles = struct.unpack_from("<Q", data, cg + 24 + 8 * cg_links + 8)[0]
        if cycles == 0:
            assert link == 0, "an empty group with data"
            empties.append(dg)
        else:
            filled = (dg, link)
        dg = next_dg
    assert filled and len(empties) == 3, (filled, empties)
    for dg in empties:
        align()
        struct.pack_into("<Q", data, dg + 24 + 16, len(data))
        data.extend(b"##DT" + bytes(4) + struct.pack("<QQ", 24, 0))
    dg, link = filled
    kind, length, _ = block(link)
    assert kind == b"##DT"
    align()
    struct.pack_into("<Q", data, dg + 24 + 16, len(data))
    data.extend(data[link:link + length])
    # The DT left behind is no block any more: zeros.
    data[link:link + length] = bytes(length)
    with open(path, "wb") as f:
        f.write(data)
    truth(name)


if __name__ == "__main__":
    if sys.argv[1:2] == ["empty"]:
        write_empty_groups()
        sys.exit(0)
    if sys.argv[1:2] == ["bench"]:
        write_asammdf(sys.argv[2], 1_000_000)
        sys.exit(0)
    if sys.argv[1:2] == ["signals"]:
        write_signals()
        sys.exit(0)
    os.makedirs(OUT, exist_ok=True)
    write_python_can("python_can.mf4", frames(), compression_level=2)
    write_python_can("python_can_deflate.mf4", frames(), compression_level=1)
    write_python_can("python_can_plain.mf4", frames(), fixed_start=False, compression_level=0)
    write_asammdf(os.path.join(OUT, "asammdf_many.mf4"), 2_000, fragment=16_384)
    truth("asammdf_many.mf4", short=True)
    write_signals()
    source = MDF(os.path.join(OUT, "canedge_vlsd.mf4"))
    source.save(os.path.join(OUT, "asammdf_sd.mf4"), overwrite=True, compression=2)
    source.close()
    truth("asammdf_sd.mf4", short=True)
    truth("canedge_vlsd.mf4", short=True)
    truth("canedge_01_07.mf4", short=True)
    write_empty_groups()
