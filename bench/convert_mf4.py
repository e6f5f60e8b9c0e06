#!/usr/bin/env python3
"""Write the benchmark's candump log again as an ASAM MDF 4 file, with
asammdf in python-can's MF4Writer layout (one CAN_DataFrame group, the
frames in time order, transposed + deflated DZ blocks in a data list): the
file a python-can or asammdf user has. MF4Writer itself appends one record
per call, which for a million frames takes most of an hour; the records
here are the ones it would write, put in one numpy array.

Usage: python3 bench/convert_mf4.py IN.log OUT.mf4
"""
import sys
from datetime import datetime, timezone

import can
# First: can.io.mf4 imports asammdf's blocks in an order of its own.
from can.io.mf4 import RTR_DTYPE, STD_DTYPE
import numpy as np
from asammdf import MDF, Signal
from asammdf.blocks.v4_blocks import SourceInformation
from asammdf.blocks.v4_constants import BUS_TYPE_CAN, SOURCE_BUS


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    src, out = argv
    messages = list(can.CanutilsLogReader(src))
    start = messages[0].timestamp if messages else 0.0
    frames = [m for m in messages if not m.is_remote_frame]
    remote = [m for m in messages if m.is_remote_frame]
    source = SourceInformation(source_type=SOURCE_BUS, bus_type=BUS_TYPE_CAN)
    mdf = MDF(version="4.10")
    mdf.header.start_time = datetime.fromtimestamp(start, timezone.utc)
    for name, dtype, group in (("CAN_DataFrame", STD_DTYPE, frames),
                               ("CAN_RemoteFrame", RTR_DTYPE, remote)):
        samples = np.zeros(len(group), dtype=dtype)
        samples[f"{name}.BusChannel"] = 1
        samples[f"{name}.ID"] = [m.arbitration_id for m in group]
        samples[f"{name}.IDE"] = [m.is_extended_id for m in group]
        samples[f"{name}.DLC"] = [m.dlc for m in group]
        samples[f"{name}.Dir"] = [0 if m.is_rx else 1 for m in group]
        if name == "CAN_DataFrame":
            samples[f"{name}.DataLength"] = [len(m.data) for m in group]
            data = np.zeros((len(group), 64), dtype=np.uint8)
            for i, m in enumerate(group):
                data[i, : len(m.data)] = np.frombuffer(bytes(m.data), dtype=np.uint8)
            samples[f"{name}.DataBytes"] = data
        times = np.array([m.timestamp - start for m in group], dtype="<f8")
        mdf.append(Signal(name=name, samples=samples, timestamps=times, source=source))
    mdf.save(out, overwrite=True, compression=2)
    mdf.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
