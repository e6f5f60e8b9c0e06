"""motionwire: CAN logs and CANopen decoding for Python (docs/python.md).

Every format of docs/formats.md (candump, ASC, TRC, BLF, pcap/pcapng, MF4,
gzip-compressed or not) read into Arrow tables built in Rust, EtherCAT
captures datagram by datagram, their process data (signals, servo frames)
and what they tell of the slaves as tables, the CANopen decoder's columns
and JSON records, the post-mortem summary and what went wrong, and
python-can messages. The work is done by the Rust library with the GIL
released; this module only re-exports it.
"""

import os
from typing import Iterable, Literal, Mapping, Optional, Union

from ._motionwire import (
    LogError,
    Message,
    Reader,
    __version__,
    decode,
    ethercat_records,
    findings,
    process_data,
    read_log,
    read_logs,
    servo,
    signals,
    summary,
)

# The types of the arguments, as __init__.pyi has them (each described
# there), for annotations in users' code: `def load(src: motionwire.Source)`.
Source = Union[str, "os.PathLike[str]", bytes, bytearray, memoryview]
Format = Literal["candump", "asc", "trc", "pcap", "pcapng", "blf", "mf4"]
ProfileName = Literal["generic", "akd", "baumer"]
Profiles = Union[ProfileName, Mapping[Optional[int], ProfileName]]
Servo = Union[str, int, Iterable[Union[str, int]], None]
RecordKind = Literal[
    "ecat_datagram",
    "station",
    "al_state",
    "sii",
    "dl_status",
    "error_counters",
    "mailbox",
    "coe_sdo",
    "coe_emcy",
    "process_data",
    "servo",
    "alias",
    "dc",
    "dc_distribution",
    "mailbox_poll",
    "mailbox_repeat",
]

__all__ = [
    "Format",
    "LogError",
    "Message",
    "ProfileName",
    "Profiles",
    "Reader",
    "RecordKind",
    "Servo",
    "Source",
    "decode",
    "ethercat_records",
    "findings",
    "process_data",
    "read_log",
    "read_logs",
    "servo",
    "signals",
    "summary",
]
