#!/usr/bin/env python3
"""Write the benchmark's candump log again as Vector ASC and BLF, with
python-can's own writers (the files a python-can user has).

Usage: python3 bench/convert_python_can.py IN.log OUT.asc OUT.blf
"""
import sys

import can


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    src, asc, blf = argv
    with can.ASCWriter(asc) as a, can.BLFWriter(blf) as b:
        for msg in can.CanutilsLogReader(src):
            # One channel: the ASC/BLF channel numbers start at 1.
            msg.channel = 1
            a.on_message_received(msg)
            b.on_message_received(msg)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
