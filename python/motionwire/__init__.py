"""motionwire: CAN logs and CANopen decoding for Python (docs/python.md).

Every format of docs/formats.md (candump, ASC, TRC, BLF, pcap/pcapng, MF4,
gzip-compressed or not) read into Arrow tables built in Rust, EtherCAT
captures datagram by datagram and their process data (signals, servo
frames) as tables, the CANopen decoder's columns and JSON
records, the post-mortem summary and what went wrong, and python-can
messages. The work is done by the Rust library with the GIL
released; this module only re-exports it.
"""

from ._motionwire import (
    LogError,
    Message,
    Reader,
    __version__,
    decode,
    findings,
    process_data,
    read_log,
    read_logs,
    servo,
    signals,
    summary,
)

__all__ = [
    "LogError",
    "Message",
    "Reader",
    "decode",
    "findings",
    "process_data",
    "read_log",
    "read_logs",
    "servo",
    "signals",
    "summary",
]
