"""motionwire: CAN logs and CANopen decoding for Python (docs/python.md).

Every format of docs/formats.md — candump log and screen output, Vector ASC
and BLF, PEAK TRC, pcap and pcapng, ASAM MDF 4 — gzip-compressed or not,
found from the content; EtherCAT captures (pcap, pcapng) datagram by
datagram (docs/python.md#ethercat), what the datagrams tell of the slaves
record by record (docs/python.md#ethercat-records), and their process data
signal by signal (docs/python.md#process-data). Tables are built column by column in Rust and handed
to pyarrow without a copy; pandas (`table.to_pandas()`), polars
(`polars.from_arrow(table)`) and DuckDB (`duckdb.sql("… from table")`) read
them as they are. The GIL is released while a log is read.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping
from types import TracebackType
from typing import Any, Literal, Optional, Union, final

import pyarrow

__version__: str

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

#: A log: its path, or the bytes of the file (gzip-compressed or not).
Source = Union[str, "os.PathLike[str]", bytes, bytearray, memoryview]

#: A format name of docs/formats.md, to read an input as that format
#: whatever its content says (`motionwire decode --format`).
Format = Literal["candump", "asc", "trc", "pcap", "pcapng", "blf", "mf4"]

#: A device profile of docs/canopen.md#profiles: how an EMCY's
#: manufacturer bytes read, whether a node is a CiA 402 drive.
ProfileName = Literal["generic", "akd", "baumer"]

#: `profiles=`: one profile for every node, or {node: profile} (the key
#: None: every node not named).
Profiles = Union[ProfileName, Mapping[Optional[int], ProfileName]]

class LogError(ValueError):
    """A log that cannot be read: none of the formats of docs/formats.md
    (unrecognised), a binary log whose header is damaged, or an input that
    fails while it is read (a damaged gzip stream). The message names the
    source and the reason:

        <bytes>: unrecognised log format: expected a candump log or screen
        output, Vector ASC or BLF, PEAK TRC, pcap or pcapng, ASAM MDF 4
        (gzip-compressed or not)

    A malformed line inside a recognised log is no LogError: it is skipped
    and listed in the table's schema metadata. A path that cannot be opened
    raises the OSError that Python's open() would (FileNotFoundError, …).
    """

def read_log(source: Source, format: Optional[Format] = None) -> pyarrow.Table:
    """Read a log into a table, one row per CAN frame, in the log's order
    (MF4: time order across its channel groups).

    Columns (docs/python.md#read-log; each as the JSON record's key of the
    same name, docs/output.md#common-keys):

    - ``line`` (uint64): the 1-based line of a text log, or the packet,
      object or record number of a binary one (docs/formats.md#positions).
    - ``ts`` (float64, null where the log has no time): seconds, absolute
      Unix time where the log records the date, else since the start of the
      recording (docs/formats.md#timestamps).
    - ``time`` (null where ``ts`` is): the same instant to the nanosecond,
      from the library's timestamps (never from the float):
      ``timestamp[ns, tz=UTC]`` where every time of the table is a Unix
      time (from 2001-09-09 on), else ``duration[ns]`` since the clock's
      zero, the start of the recording (docs/python.md#time). pandas reads
      them as ``datetime64[ns, UTC]`` and ``timedelta64[ns]``.
    - ``iface`` (dictionary string, null where the log names none): the
      interface name (``can0``) or channel number as the file writes it
      (``1``).
    - ``id`` (uint32): the identifier; of an error frame, its class bits.
    - ``extended``, ``rtr``, ``fd``, ``brs``, ``esi``, ``error`` (bool).
    - ``dlc`` (uint8): the data length code: the number of bytes of a
      classic frame, the requested length of a remote request, the code
      0–15 of a CAN FD frame (12 bytes: 9; 64 bytes: 15).
    - ``data`` (binary): the data bytes; empty for a remote request.

    Schema metadata: ``b"motionwire.format"`` (the format read),
    ``b"motionwire.skipped"`` (a JSON list of ``{"line": …, "reason": …}``,
    the first 1 000 lines or records skipped as malformed or damaged),
    ``b"motionwire.skipped_count"`` (how many), where a binary log
    had records without a CAN frame, ``b"motionwire.other"`` (what was
    passed over, as the program says it), and where the log gave no row,
    ``b"motionwire.empty"`` (a JSON list of the program's words,
    ``["empty.log: 0 frames"]``).

    An EtherCAT capture (docs/python.md#ethercat) gives one row per
    datagram instead, with the keys of ``motionwire decode --json``'s
    ``ecat_datagram`` record as columns, in that order:

    - ``packet`` (uint64): the capture's packet number, from 1.
    - ``datagram`` (uint16): the datagram's place in its frame, from 1.
    - ``ts`` (float64 seconds, null where the capture has no time),
      ``time``, ``iface`` (dictionary string, null where none): as for CAN
      frames.
    - ``kind`` (dictionary string): ``ecat_datagram``.
    - ``cmd`` (dictionary string): ``NOP``, ``APRD``, … ``FRMW``, or
      ``reserved``.
    - ``index`` (uint8).
    - ``adp``, ``ado`` (uint16): slave and register address; null for
      LRD, LWR and LRW.
    - ``logical`` (uint32): the logical address of LRD, LWR and LRW; null
      for the others.
    - ``length``, ``irq``, ``wkc`` (uint16): the data's length, the IRQ
      field, the working counter.
    - ``returned`` (bool): the copy that came back through the slaves
      (paired with its sent copy or not), as the library's session tells.
    - ``data`` (binary).

    Its metadata adds ``b"motionwire.ethercat"``: the session's counts as
    a JSON object (``packets``, ``sent``, ``returned``,
    ``returned_unpaired``, ``lost``, ``other_frame_types``, ``damaged``).
    A table holds CAN frames or EtherCAT datagrams, not both: the CAN
    frames where the input has any, the EtherCAT packets then counted in
    ``b"motionwire.other"``.

    Raises LogError for an input that is no log; OSError for a path that
    cannot be opened.
    """

def read_logs(
    sources: Iterable[Source],
    threads: Optional[int] = None,
    *,
    format: Optional[Format] = None,
) -> pyarrow.Table:
    """Read many logs at once on Rust threads (``threads``: by default one
    per core) into one table: a ``file`` column (dictionary string: the
    path as given, ``<bytes N>`` for the N-th source given as bytes) before
    the columns of read_log, each log's rows in the order of ``sources``.
    Each log is read on its own: nothing carries over from one to the next.
    EtherCAT captures give read_log's datagram columns after ``file`` when
    no log of the table has a CAN frame; else their packets are counted in
    ``b"motionwire.other"``.

    The way to take a fleet's logs to pandas, polars or DuckDB, and on to
    Parquet (``pyarrow.parquet.write_table``). The skipped lines of every log
    are in the metadata, each with its ``file``.

    Raises LogError naming the first source (in the order given) that is no
    log.
    """

def decode(
    source: Source,
    *,
    profiles: Optional[Profiles] = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[Format] = None,
) -> pyarrow.Table:
    """Decode a log as CANopen: the columns of read_log, then what the
    decoder session reads in each frame, with SDO transfers followed, PDO
    mappings learned from the log (or ``eds``) and each drive's CiA 402 state
    (docs/python.md#decode):

    - ``kind`` (dictionary string): ``emcy``, ``heartbeat``,
      ``guard_request``, ``guard_answer``, ``nmt_command``, ``sync``,
      ``time``, ``pdo``,
      ``sdo``, ``error_frame``, ``other`` (docs/canopen.md#identifiers).
    - ``node`` (uint8, null for kinds without one).
    - ``code`` (uint16), ``register`` (uint8), ``description`` (dictionary
      string): an EMCY's error code, error register and the code's
      description (a truncated EMCY: the code and register its bytes hold).
    - ``state`` (dictionary string): the NMT state of a heartbeat, boot-up
      or guarding answer (``boot_up``, ``stopped``, ``operational``,
      ``pre_operational``, ``invalid``).
    - ``cia402_state`` (dictionary string, null where the frame tells
      none): the drive's CiA 402 state a statusword in the frame tells
      (``switch_on_disabled``, ``operation_enabled``, ``fault``, …), the
      record's ``cia402.state``.
    - ``record`` (string): the frame's whole JSON record, exactly the line
      ``motionwire decode --json`` writes (docs/output.md#json): SDO,
      transfer, signals, cia402 and every key of its kind.

    ``profiles``: ``"akd"`` for every node, or ``{3: "akd", 5: "baumer"}``
    (``--profile``; the key None sets the default). ``eds``: ``{node:
    path}``, an EDS or DCF file describing that node (``--eds``).

    An EtherCAT capture gives read_log's datagram columns and ``record``
    (string): the datagram's ``ecat_datagram`` record, the line
    ``motionwire decode --json`` writes (docs/ethercat.md#records).

    For pandas, ``table.to_pandas(types_mapper=pandas.ArrowDtype)`` keeps
    ``node``, ``code`` and ``register`` integers where they hold nulls
    (plain ``to_pandas()`` makes them float64 with NaN).
    """

def signals(
    source: Source,
    *,
    profiles: Optional[Profiles] = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[Format] = None,
) -> pyarrow.Table:
    """The PDO signals of a CAN log as a long table (docs/python.md#signals):
    one row per signal value of each PDO whose mapping the decoder knows
    (learned from the log's SDO transfers, or from ``eds``), in the log's
    order and the mapping's: the record's ``signals`` of decode, as
    process_data's long table has EtherCAT's.

    Columns: ``line`` (uint64), ``ts`` (float64 seconds, nullable),
    ``time`` (as read_log's), ``iface`` (dictionary string, nullable),
    ``node`` (uint8: the node whose PDO it is, the mapping's owner),
    ``cob_id`` (uint32: the frame's identifier), ``name`` (dictionary
    string: the signal's name, the EDS's or the object table's, else
    ``0x6041:00``), ``value`` (float64: the value as a number, a boolean
    0 or 1, null for bytes; integers exact up to 2**53), ``raw`` (int64:
    the value where it is an integer an int64 holds, else null).

    ``profiles``, ``eds`` and ``format`` are decode's. Pivot it wide with
    pandas: ``df.pivot_table(index=["line", "node"], columns="name",
    values="value", observed=True)``. An EtherCAT capture's packets have no
    rows and are said with a UserWarning (process_data has their signals);
    the schema metadata is read_log's.
    """

def summary(
    source: Source,
    *,
    heartbeat_ms: Optional[int] = None,
    profiles: Optional[Profiles] = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[Format] = None,
    servo: Any = None,
) -> list[dict[str, Any]]:
    """The post-mortem of a log: exactly the records of ``motionwire decode
    --summary --json`` (docs/summary.md): the verdict when something
    stopped (``type`` ``verdict``, docs/summary.md#verdict), then one dict
    per node and per bus:
    frame counts, first and active error with the CiA 405 root cause,
    heartbeat boot-ups and gaps over ``heartbeat_ms``, node-guarding toggle
    errors, SDO requests, transfers, aborts and latencies, each drive's CiA
    402 timeline. Each list holds the first 10 and the last 10 events of its
    kind, and the count key after it counts them all (docs/summary.md#lists).

    Lines skipped as malformed are said with a UserWarning (read_log lists
    them). An EtherCAT capture gives one record per interface, slave and
    cyclic stream (docs/ethercat.md#summary). A negative ``heartbeat_ms``
    is a ValueError.
    """

def findings(
    source: Source,
    *,
    heartbeat_ms: Optional[int] = None,
    profiles: Optional[Profiles] = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[Format] = None,
    servo: Any = None,
) -> pyarrow.Table:
    """What went wrong (docs/summary.md#findings): one row per finding, the
    list of the report's "What went wrong" (``motionwire report``), in time
    order: first errors and warnings, CiA 402 faults, restarts, heartbeat
    timeouts over ``heartbeat_ms``, SDO aborts, broken and unanswered SDO
    transfers, node-guarding toggle errors, bus-off and error-passive frames;
    an EtherCAT capture's slaves' AL errors and servo faults
    (docs/ethercat.md#findings, ``servo=`` as process_data's); where the
    summary omitted entries of a list, one row says how many.

    Columns: ``line`` (uint64: the line, or an EtherCAT capture's packet),
    ``ts`` (float64 seconds, null where the log has no time), ``iface``
    (dictionary, null for an unnamed bus), ``node`` (uint8, null for a bus's
    findings and an EtherCAT slave's), ``slave`` (uint16, the EtherCAT
    slave's station address, null for CAN), ``kind`` (dictionary:
    ``first_error``, ``first_warning``, ``cia402_fault``, ``restarts``,
    ``heartbeat_timeout``, ``sdo_abort``, ``sdo_broken``, ``sdo_timeout``,
    ``toggle_error``, ``bus_off``, ``error_passive``, ``al_error``,
    ``servo_fault``), ``severity`` (dictionary: ``fault``, ``error``,
    ``warning``, ``notice``; docs/summary.md#severity), ``text`` (what it
    says, without the device).

    Lines skipped as malformed are said with a UserWarning (read_log lists
    them).
    """

#: `servo=`: the slaves read as the servo frames of docs/servo.md, as the
#: program's ``--servo`` names them: ``"auto"`` (every slave of 10 output
#: and 40 input bytes), a station address (``0x1001``), ``"0x1001:1"``
#: (with its Servo_Ready_Mode, 0 or 1), comma-separated items in one
#: string, or a list of these; None for none.
Servo = Union[str, int, Iterable[Union[str, int]], None]

def process_data(
    source: Source,
    *,
    servo: Servo = None,
    format: Optional[Format] = None,
) -> pyarrow.Table:
    """The process data of an EtherCAT capture as a long table
    (docs/python.md#process-data): one row per signal per slave per
    returned cyclic datagram, the values of the program's ``process_data``
    records' ``signals`` (outputs then inputs, in mapping order), then a
    servo's values (``servo=``) as signals too.

    Columns: ``packet`` (uint64), ``datagram`` (uint16), ``ts`` (float64
    seconds, null without time), ``time`` (as read_log's), ``iface``
    (dictionary string), ``slave``
    (uint16 station address, null where no FMMU is known), ``position``
    (uint16 ring position, nullable), ``direction`` (dictionary:
    ``output``, ``input``), ``name`` (dictionary string: the key of
    ``signals``, or a servo value's name: ``speed_setpoint``, ``control``,
    ``servo_enable``; ``position``, ``zero_pulse_position`` (incremental
    encoders), ``status``, ``errors``, ``message_code``,
    ``message_value``), ``value`` (float64: the value as a number, a
    boolean 0 or 1, null for bytes; integers exact up to 2**53), ``raw``
    (int64: the value where it is an integer an int64 holds, else null),
    ``confirmed`` (bool: the working counter confirms the inputs; true for
    outputs).

    Pivot it wide with pandas: ``df.pivot_table(index=["packet", "slave"],
    columns="name", values="value")``. A log's CAN frames have no rows and
    are said with a UserWarning; the schema metadata is read_log's.
    """

def servo(
    source: Source,
    *,
    servo: Servo = "auto",
    format: Optional[Format] = None,
) -> pyarrow.Table:
    """The servo frames of an EtherCAT capture (docs/python.md#servo): one
    row per servo per cycle, the values of the program's ``servo``
    records.

    Columns: ``packet`` (uint64), ``datagram`` (uint16), ``ts``, ``time``,
    ``iface``, ``slave`` (uint16); the command: ``speed_setpoint`` (int32),
    ``control`` (uint32, SCW), ``servo_enable`` (uint8, SE); the feedback,
    null where the inputs are unconfirmed: ``position`` (int64, ActPos
    raw), ``encoder`` (dictionary: ``absolute``, ``incremental``),
    ``status`` (uint32, SSW), ``errors`` (uint32, SEW), ``faults``
    (list of the set error bits' names), ``e_codes`` (list: each fault's
    E-code, ``"E09"``, or null); the handshakes: ``enable``,
    ``enable_cycles`` (uint32), ``error_clear``, ``zero_pulse``
    (dictionary: the phases' names); ``ready`` (bool, ServoRDY by the
    mode, null without feedback); ``confirmed`` (bool).
    """

#: A kind of record ``motionwire decode --json`` writes for an EtherCAT
#: capture (docs/ethercat.md#records, docs/ethercat.md#meanings): the
#: program's ``--only`` names.
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

def ethercat_records(
    source: Source,
    *,
    kinds: Union[RecordKind, Iterable[RecordKind], None] = None,
    servo: Servo = None,
    format: Optional[Format] = None,
) -> pyarrow.Table:
    """The records an EtherCAT capture's datagrams tell of its slaves, as a
    table (docs/python.md#ethercat-records): one row per record that
    ``motionwire decode --json`` writes, in its order, of the kinds
    ``kinds`` names.

    ``kinds`` (a kind, or a list of them; the program's ``--only``): by
    default ``station``, ``al_state``, ``sii``, ``dl_status``,
    ``error_counters``, ``mailbox``, ``coe_sdo``, ``coe_emcy``, ``alias``,
    ``dc``, ``mailbox_repeat`` (docs/ethercat.md#meanings);
    ``ecat_datagram`` (decode's rows), ``process_data`` and ``servo`` (the
    process data, one record per slave per cycle), ``dc_distribution`` and
    ``mailbox_poll`` (a record a cycle or a poll, which ``decode`` too
    writes only when named) when named. ``servo`` (process_data's ``servo=``): the
    slaves read as servos, whose cycles get ``servo`` records.

    Columns: the keys every record has, then those of the meanings'
    records, each the key of the same name (null where the row's kind has
    no such key or the record says null; on the rows of ``ecat_datagram``,
    ``process_data`` and ``servo`` all are null but ``slave`` and
    ``position``):

    - ``packet`` (uint64), ``datagram`` (uint16), ``ts`` (float64 seconds),
      ``time`` (as read_log's), ``iface`` (dictionary string).
    - ``kind`` (dictionary string).
    - ``slave`` (uint16 station address), ``position`` (uint16 ring
      position).
    - ``al_state``: ``al_register`` (the record's ``register``:
      ``al_control``, ``al_status``, ``al_status_code``), ``state``
      (``init``, ``preop``, ``boot``, ``safeop``, ``op``), ``al_error``
      (bool, the record's ``error``), ``code`` (uint16, AL status code)
      and ``code_text``.
    - ``sii``: ``word`` (uint32), ``value`` (uint32), ``field``.
    - ``mailbox``, ``coe_sdo``, ``coe_emcy``: ``direction`` (``write``,
      ``read``), ``type`` (the mailbox type), ``service`` (a CoE message's).
    - ``coe_sdo``: ``index`` (uint16), ``subindex`` (uint8), null in a
      segment; ``abort_code`` (uint32) and ``abort`` (its text).
    - ``coe_emcy``: ``code`` (uint16, the EMCY error code), ``register``
      (uint8, the error register), ``description``.
    - ``record`` (string): the whole JSON record, exactly the line
      ``motionwire decode --json`` writes (every key of its kind: a
      ``coe_sdo``'s ``transfer``, a ``coe_emcy``'s AKD fields …).

    Query it in DuckDB: ``duckdb.sql("select packet, slave, state from t
    where kind = 'al_state'")``. A log's CAN frames have no rows and are
    said with a UserWarning; the schema metadata is read_log's. An unknown
    kind is a ValueError.
    """

@final
class Message:
    """A CAN frame with python-can's attribute names: what Reader yields
    when python-can is not installed."""

    @property
    def timestamp(self) -> float: ...
    @property
    def arbitration_id(self) -> int: ...
    @property
    def is_extended_id(self) -> bool: ...
    @property
    def is_remote_frame(self) -> bool: ...
    @property
    def is_error_frame(self) -> bool: ...
    @property
    def is_fd(self) -> bool: ...
    @property
    def bitrate_switch(self) -> bool: ...
    @property
    def error_state_indicator(self) -> bool: ...
    @property
    def dlc(self) -> int: ...
    @property
    def data(self) -> bytes: ...
    @property
    def channel(self) -> Union[str, int, None]: ...
    @property
    def is_rx(self) -> bool: ...

@final
class Reader:
    """A log as python-can messages: a drop-in for python-can's
    ``can.LogReader`` (docs/python.md#reader), for every format of
    docs/formats.md.

        with motionwire.Reader("trace.blf") as reader:
            for msg in reader:          # can.Message
                ...

    Each message is python-can's ``can.Message`` when python-can is
    installed (else ``motionwire.Message``, with the same attributes):
    ``timestamp`` (0.0 where the log has no time), ``arbitration_id``,
    ``is_extended_id``, ``is_remote_frame``, ``is_error_frame``, ``is_fd``,
    ``bitrate_switch``, ``error_state_indicator``, ``dlc`` (python-can's:
    the data length of a CAN FD frame), ``data``, ``channel`` (the interface
    name, the channel number as the file writes it — from 1 where python-can
    counts from 0 — or None) and ``is_rx`` (True where the log does not
    say). Frames are read in blocks with the GIL released.

    Lines skipped as malformed are in ``skipped`` and ``skipped_count``.
    """

    def __new__(cls, source: Source, format: Optional[Format] = None) -> Reader: ...
    def __iter__(self) -> Iterator[Any]: ...
    def __next__(self) -> Any: ...
    def __enter__(self) -> Reader: ...
    def __exit__(
        self,
        exc_type: Optional[type[BaseException]],
        exc: Optional[BaseException],
        tb: Optional[TracebackType],
    ) -> None: ...
    def stop(self) -> None:
        """Stop reading and close the log (python-can's ``stop``)."""
    @property
    def skipped(self) -> list[dict[str, Any]]:
        """The lines or records skipped so far (the first 1 000), as
        ``{"line": …, "reason": …}``."""
    @property
    def skipped_count(self) -> int:
        """How many lines or records were skipped so far."""
