"""What a Python user meets in the first hour (docs/python.md): the
`time` column beside `ts`, to the nanosecond; the errors a directory, a
wrong argument and an empty file give."""

from __future__ import annotations

import json
import re
from decimal import Decimal
from pathlib import Path

import pyarrow as pa
import pytest

import motionwire
from conftest import FIXTURES, ROOT, SAMPLE

ETHERCAT = ROOT / "tests" / "data" / "ethercat"
UTC = pa.timestamp("ns", tz="UTC")
RELATIVE = FIXTURES / "asc" / "handmade_dec_relative.asc"
#: A capture with nanoseconds (nine digits in the records' ts).
NANOSECONDS = ETHERCAT / "replay-dc.pcapng"


def record_nanos(record: str) -> int | None:
    """The record's ts (every digit the log has) in nanoseconds."""
    found = re.search(r'"ts":([0-9.]+)', record)
    return None if found is None else int(Decimal(found.group(1)) * 10**9)


def nanos(table: pa.Table) -> list:
    return table.column("time").cast(pa.int64()).to_pylist()


# ---------------------------------------------------------------------------
# time (docs/python.md#time)

@pytest.mark.parametrize("path", [SAMPLE, NANOSECONDS, RELATIVE, FIXTURES / "mf4" / "canedge_vlsd.mf4"],
                         ids=lambda p: p.name)
def test_time_is_the_records_ts_to_the_nanosecond(path):
    table = motionwire.decode(path)
    assert table.schema.names.index("time") == table.schema.names.index("ts") + 1
    expected = [record_nanos(r) for r in table.column("record").to_pylist()]
    assert nanos(table) == expected
    assert any(n is not None and n % 1000 for n in expected) == (path == NANOSECONDS)


def test_time_is_utc_where_the_log_has_a_date():
    table = motionwire.read_log(SAMPLE)
    assert table.schema.field("time").type == UTC
    first = table.column("time")[0].as_py()
    assert (first.year, first.month, first.day, first.hour, first.minute, first.second) == (
        2023, 11, 14, 22, 13, 20)
    # ts stays, the float of the same instant.
    assert nanos(table)[0] == 1700000000000526000
    assert table.column("ts")[0].as_py() == 1700000000.000526


def test_time_is_a_duration_where_the_log_has_only_relative_times():
    table = motionwire.read_log(RELATIVE)
    assert table.schema.field("time").type == pa.duration("ns")
    assert nanos(table)[:3] == [1_000_000, 1_500_000, 2_000_000]
    assert table.column("ts").to_pylist()[:3] == [0.001, 0.0015, 0.002]


def test_time_is_null_where_ts_is():
    plain = motionwire.read_log(FIXTURES / "candump_screen" / "plain.txt")
    assert plain.column("time").null_count == plain.column("ts").null_count == plain.num_rows > 0
    assert plain.schema.field("time").type == pa.duration("ns")


def test_read_logs_time_of_dated_and_relative_logs():
    dated = motionwire.read_logs([SAMPLE, FIXTURES / "blf" / "python_can.blf"])
    assert dated.schema.field("time").type == UTC
    # A table with a log of relative times: durations since each clock's
    # zero, every log's exact.
    mixed = motionwire.read_logs([SAMPLE, RELATIVE])
    assert mixed.schema.field("time").type == pa.duration("ns")
    assert nanos(mixed)[0] == 1700000000000526000
    assert nanos(mixed)[3765] == 1_000_000
    assert nanos(mixed) == nanos(motionwire.read_log(SAMPLE)) + nanos(motionwire.read_log(RELATIVE))


def test_ethercat_tables_have_time():
    table = motionwire.read_log(NANOSECONDS)
    assert table.schema.field("time").type == UTC
    assert table.schema.names[:5] == ["packet", "datagram", "ts", "time", "iface"]
    drives = ETHERCAT / "drives.pcapng"
    for t in (motionwire.process_data(drives, servo=0x1001), motionwire.servo(drives)):
        assert t.schema.names[:5] == ["packet", "datagram", "ts", "time", "iface"]
        assert t.schema.field("time").type == UTC
        # The packet's time, as read_log's datagrams have it.
        datagrams = motionwire.read_log(drives)
        by_packet = dict(zip(datagrams.column("packet").to_pylist(), nanos(datagrams)))
        assert all(by_packet[p] == n for p, n in zip(t.column("packet").to_pylist(), nanos(t)))


def test_time_in_pandas_and_polars():
    pd = pytest.importorskip("pandas")
    frame = motionwire.read_log(SAMPLE).to_pandas()
    assert str(frame["time"].dtype) == "datetime64[ns, UTC]"
    assert frame["time"].iloc[0] == pd.Timestamp("2023-11-14 22:13:20.000526", tz="UTC")
    relative = motionwire.read_log(RELATIVE).to_pandas()
    assert relative["time"].iloc[1] == pd.Timedelta(microseconds=1500)
    pl = pytest.importorskip("polars")
    assert str(pl.from_arrow(motionwire.read_log(SAMPLE))["time"].dtype) == "Datetime(time_unit='ns', time_zone='UTC')"


# ---------------------------------------------------------------------------
# Errors (docs/python.md#errors)

def test_a_directory_is_an_is_a_directory_error(tmp_path: Path):
    calls = [
        motionwire.read_log,
        motionwire.decode,
        motionwire.summary,
        motionwire.findings,
        motionwire.process_data,
        motionwire.Reader,
        lambda p: motionwire.read_logs([p]),
    ]
    for call in calls:
        with pytest.raises(IsADirectoryError) as info:
            call(tmp_path)
        assert info.value.filename == str(tmp_path)
        assert not isinstance(info.value, motionwire.LogError)


@pytest.mark.parametrize("call", [motionwire.summary, motionwire.findings], ids=lambda c: c.__name__)
def test_a_negative_heartbeat_is_a_value_error_naming_it(call):
    with pytest.raises(ValueError, match=r"heartbeat_ms must be a number of milliseconds, 0 or more; not -5"):
        call(SAMPLE, heartbeat_ms=-5)
    # 0 and more are timeouts.
    assert call(SAMPLE, heartbeat_ms=0) is not None


def test_an_empty_file_says_so_in_the_metadata(tmp_path: Path):
    empty = tmp_path / "empty.log"
    empty.write_bytes(b"")
    for call in (motionwire.read_log, motionwire.decode):
        table = call(empty)
        assert table.num_rows == 0
        # As the program says it: `FILE: 0 frames` (docs/output.md#stderr).
        assert json.loads(table.schema.metadata[b"motionwire.empty"]) == [f"{empty}: 0 frames"]
        assert table.schema.metadata[b"motionwire.skipped_count"] == b"0"
    assert json.loads(motionwire.read_log(b"# a comment\n").schema.metadata[b"motionwire.empty"]) == [
        "<bytes>: 0 frames"]
    fleet = motionwire.read_logs([SAMPLE, b""])
    assert json.loads(fleet.schema.metadata[b"motionwire.empty"]) == ["<bytes 1>: 0 frames"]
    assert b"motionwire.empty" not in motionwire.read_log(SAMPLE).schema.metadata


# ---------------------------------------------------------------------------
# PDO signals and the CiA 402 state outside the record (docs/python.md#signals)

PDO_LOG = FIXTURES / "pdo" / "python_canopen.log"
PDO_EDS = {3: FIXTURES / "pdo" / "drive.eds"}


@pytest.mark.parametrize("path, eds", [(SAMPLE, None), (PDO_LOG, PDO_EDS)], ids=["sample", "eds"])
def test_signals_are_the_records_signals(path, eds):
    table = motionwire.signals(path, eds=eds)
    assert [(f.name, f.type, f.nullable) for f in table.schema] == [
        ("line", pa.uint64(), False),
        ("ts", pa.float64(), True),
        ("time", UTC, True),
        ("iface", pa.dictionary(pa.int32(), pa.string()), True),
        ("node", pa.uint8(), False),
        ("cob_id", pa.uint32(), False),
        ("name", pa.dictionary(pa.int32(), pa.string()), False),
        ("value", pa.float64(), True),
        ("raw", pa.int64(), True),
    ]
    decoded = motionwire.decode(path, eds=eds)
    expected = []
    for row in decoded.to_pylist():
        record = json.loads(row["record"])
        for name, value in record.get("signals", {}).items():
            expected.append({
                "line": row["line"], "ts": row["ts"], "time": row["time"], "iface": row["iface"],
                "node": record["node"], "cob_id": row["id"], "name": name,
                # A REAL's raw is null; an integer's the integer.
                "value": float(value), "raw": value if isinstance(value, int) else None,
            })
    assert len(expected) > 100
    rows = table.to_pylist()
    # node: the PDO's owner, whose mapping read it; the record's node is
    # the identifier's, the same but for a COB-ID the owner chose (the
    # drive's RPDO on 0x2C0 below: the record says node 64).
    owners = [row.pop("node") for row in rows]
    nodes = [row.pop("node") for row in expected]
    if eds is None:
        assert owners == nodes
    else:
        assert set(owners) == {3} and 64 in nodes
    assert rows == expected


def test_signals_pivot_wide_in_pandas():
    pytest.importorskip("pandas")
    frame = motionwire.signals(SAMPLE).to_pandas()
    wide = frame.pivot_table(index=["line", "node"], columns="name", values="raw", observed=True)
    assert wide.loc[(173, 3), "Statusword"] == 592
    assert wide.loc[(173, 3), "Position actual value"] == 100000


def test_signals_warn_of_ethercat_packets_and_profiles_are_decodes():
    with pytest.warns(UserWarning, match="EtherCAT packets read: the signals of CAN PDOs"):
        table = motionwire.signals(ETHERCAT / "soem-akd-sdo.pcapng")
    assert table.num_rows == 0
    assert motionwire.signals(SAMPLE, profiles={3: "akd"}).equals(motionwire.signals(SAMPLE))
    with pytest.raises(ValueError, match="not a profile"):
        motionwire.signals(SAMPLE, profiles="nope")


def test_cia402_state_is_the_records():
    table = motionwire.decode(SAMPLE)
    assert table.schema.field("cia402_state").type == pa.dictionary(pa.int32(), pa.string())
    states = table.column("cia402_state").to_pylist()
    expected = [json.loads(r).get("cia402", {}).get("state") for r in table.column("record").to_pylist()]
    assert states == expected
    assert {"switch_on_disabled", "operation_enabled", "fault"} <= set(states)
    assert states.count(None) > 0


# ---------------------------------------------------------------------------
# help(): the docstrings are on the objects, the stubs' own


def test_help_shows_the_stubs_docstrings():
    import ast
    import inspect

    stub = ast.parse((ROOT / "python" / "motionwire" / "__init__.pyi").read_text())
    documented = {
        node.name: ast.get_docstring(node, clean=True)
        for node in stub.body
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and ast.get_docstring(node)
    }
    assert set(documented) == {
        "LogError", "read_log", "read_logs", "decode", "signals", "summary", "findings",
        "process_data", "servo", "ethercat_records", "Message", "Reader",
    }
    for name, doc in documented.items():
        assert inspect.getdoc(getattr(motionwire, name)) == doc, name
    assert motionwire.decode.__text_signature__ == "(source, *, profiles=None, eds=None, format=None)"


def test_the_stubs_types_are_there_at_run_time():
    import typing

    assert typing.get_args(motionwire.Format) == ("candump", "asc", "trc", "pcap", "pcapng", "blf", "mf4")
    assert typing.get_args(motionwire.ProfileName) == ("generic", "akd", "baumer")
    # Every kind of the program's EtherCAT records (--only), in its order.
    assert typing.get_args(motionwire.RecordKind)[0] == "ecat_datagram"
    assert len(typing.get_args(motionwire.RecordKind)) == 16
    assert bytes in typing.get_args(motionwire.Source)
    # Submodules a test imported (motionwire.spark) are attributes too, and
    # not in __all__ (import motionwire never imports them).
    import types

    assert sorted(motionwire.__all__) == sorted(
        name
        for name in dir(motionwire)
        if not name.startswith("_")
        and name not in ("os", "Iterable", "Literal", "Mapping", "Optional", "Union")
        and not isinstance(getattr(motionwire, name), types.ModuleType)
    )
