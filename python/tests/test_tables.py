"""The tables themselves (docs/python.md): the schema, what is skipped and
where it is said, sources as paths or bytes, the errors, many logs at once,
the round trips to pandas, polars and DuckDB, and bad input."""

from __future__ import annotations

import gzip
import json
import os
import random
import warnings
from pathlib import Path

import pyarrow as pa
import pyarrow.compute as pc
import pytest

import motionwire
from conftest import FIXTURES, ROOT, SAMPLE

READ_LOG_SCHEMA = [
    ("line", pa.uint64(), False),
    ("ts", pa.float64(), True),
    ("time", pa.timestamp("ns", tz="UTC"), True),
    ("iface", pa.dictionary(pa.int32(), pa.string()), True),
    ("id", pa.uint32(), False),
    ("extended", pa.bool_(), False),
    ("rtr", pa.bool_(), False),
    ("fd", pa.bool_(), False),
    ("brs", pa.bool_(), False),
    ("esi", pa.bool_(), False),
    ("error", pa.bool_(), False),
    ("dlc", pa.uint8(), False),
    ("data", pa.binary(), False),
]
DECODE_SCHEMA = READ_LOG_SCHEMA + [
    ("kind", pa.dictionary(pa.int8(), pa.string()), False),
    ("node", pa.uint8(), True),
    ("code", pa.uint16(), True),
    ("register", pa.uint8(), True),
    ("description", pa.dictionary(pa.int32(), pa.string()), True),
    ("state", pa.dictionary(pa.int32(), pa.string()), True),
    ("cia402_state", pa.dictionary(pa.int32(), pa.string()), True),
    ("record", pa.string(), False),
]

#: One fixture of every format (docs/formats.md), and how many frames it has.
EVERY_FORMAT = {
    "candump": (SAMPLE, 3765),
    "asc": (FIXTURES / "asc" / "canoe.asc", 15),
    "trc": (FIXTURES / "trc" / "handmade_v2_1.trc", 10),
    "pcap": (FIXTURES / "pcap" / "can.pcap", None),
    "pcapng": (FIXTURES / "pcap" / "multi.pcapng", 10),
    "blf": (FIXTURES / "blf" / "python_can.blf", 39),
    "mf4": (FIXTURES / "mf4" / "canedge_vlsd.mf4", 2010),
}


def fields(schema):
    return [(f.name, f.type, f.nullable) for f in schema]


def test_read_log_schema():
    table = motionwire.read_log(SAMPLE)
    assert fields(table.schema) == READ_LOG_SCHEMA
    assert table.num_rows == 3765
    first = table.slice(0, 1).to_pylist()[0]
    assert table.column("time").cast(pa.int64())[0].as_py() == 1700000000000526000
    del first["time"]
    assert first == {
        "line": 1,
        "ts": 1700000000.000526,
        "iface": "can0",
        "id": 0x080,
        "extended": False,
        "rtr": False,
        "fd": False,
        "brs": False,
        "esi": False,
        "error": False,
        "dlc": 0,
        "data": b"",
    }
    assert table.schema.metadata[b"motionwire.format"] == b"candump"


def test_decode_schema():
    table = motionwire.decode(SAMPLE)
    assert fields(table.schema) == DECODE_SCHEMA
    assert table.num_rows == 3765


@pytest.mark.parametrize("fmt", sorted(EVERY_FORMAT))
def test_every_format(fmt):
    path, frames = EVERY_FORMAT[fmt]
    table = motionwire.read_log(path)
    assert table.schema.metadata[b"motionwire.format"] == fmt.encode()
    if frames is not None:
        assert table.num_rows == frames
    # The same from the bytes, and gzip-compressed (docs/formats.md#gzip).
    data = path.read_bytes()
    assert motionwire.read_log(data).equals(table)
    assert motionwire.read_log(gzip.compress(data)).equals(table)
    assert motionwire.read_log(bytearray(data)).equals(table)
    assert motionwire.read_log(memoryview(data)).equals(table)
    assert motionwire.read_log(str(path)).equals(table)
    assert motionwire.read_log(path, format=fmt).equals(table)


def test_timestamps_and_interfaces_may_be_null():
    # candump screen output without -t: no time (docs/formats.md#timestamps);
    # pcap: no interface name (docs/formats.md#interfaces).
    plain = motionwire.read_log(FIXTURES / "candump_screen" / "plain.txt")
    assert plain.column("ts").null_count == plain.num_rows > 0
    pcap = motionwire.read_log(FIXTURES / "pcap" / "can.pcap")
    assert pcap.column("iface").null_count == pcap.num_rows > 0


def test_can_fd_columns():
    table = motionwire.read_log(FIXTURES / "trc" / "handmade_v2_0.trc")
    fd = [r for r in table.to_pylist() if r["fd"]]
    # dlc is the code of CAN FD's lengths (12 bytes: 9; 64 bytes: 15).
    assert [(len(r["data"]), r["dlc"], r["brs"], r["esi"]) for r in fd] == [
        (12, 9, False, False),
        (64, 15, True, False),
        (8, 8, False, True),
        (16, 10, True, True),
    ]


def test_skipped_lines_are_in_the_metadata():
    text = b"".join(
        b"(1700000000.%06d) can0 705#05\n" % i if i % 3 else b"(1700000000.%06d) can0 0X1#00\n" % i
        for i in range(3000)
    )
    table = motionwire.read_log(text)
    metadata = table.schema.metadata
    assert table.num_rows == 2000
    assert metadata[b"motionwire.skipped_count"] == b"1000"
    skipped = json.loads(metadata[b"motionwire.skipped"])
    assert len(skipped) == 1000
    assert skipped[0] == {
        "line": 1,
        "reason": "candump line, column 27: expected a CAN identifier of 3 or 8 hex digits "
        "followed by '#' or white space, found 'X'",
    }
    # The first 1 000 only, counted all.
    text = text * 2
    metadata = motionwire.read_log(text).schema.metadata
    assert metadata[b"motionwire.skipped_count"] == b"2000"
    assert len(json.loads(metadata[b"motionwire.skipped"])) == 1000


def test_records_without_a_frame_are_said():
    table = motionwire.read_log(FIXTURES / "pcap" / "multi.pcapng")
    other = json.loads(table.schema.metadata[b"motionwire.other"])
    assert other == ["1 packet of EtherType 0x0806 (ARP) skipped: neither CAN nor EtherCAT"]
    # An MF4 file's group without CAN frames, by its name (asammdf wrote it).
    table = motionwire.read_log(FIXTURES / "mf4" / "asammdf_signals.mf4")
    assert table.num_rows == 40
    other = json.loads(table.schema.metadata[b"motionwire.other"])
    assert other == ["3 MF4 records of group EngineSpeed skipped: not CAN"]


def test_summary_warns_of_skipped_lines():
    text = b"(1.000000) can0 705#05\n(1.100000) can0 0X1#00\n"
    with pytest.warns(UserWarning, match="1 malformed line"):
        records = motionwire.summary(text)
    assert records[0]["type"] == "node"


def test_errors():
    with pytest.raises(motionwire.LogError, match="<bytes>: unrecognised log format") as info:
        motionwire.read_log(b"Hello, world!\n")
    assert isinstance(info.value, ValueError)
    with pytest.raises(FileNotFoundError) as info:
        motionwire.read_log(ROOT / "no-such.log")
    assert info.value.filename == str(ROOT / "no-such.log")
    with pytest.raises(motionwire.LogError):
        motionwire.read_log(b"\x00" * 100)
    with pytest.raises(motionwire.LogError):
        motionwire.Reader(b"Hello, world!\n")
    with pytest.raises(motionwire.LogError):
        motionwire.summary(b"Hello, world!\n")
    with pytest.raises(ValueError, match="is not a log format"):
        motionwire.read_log(SAMPLE, format="csv")
    with pytest.raises(TypeError):
        motionwire.read_log(42)
    with pytest.raises(ValueError, match="not a profile"):
        motionwire.decode(SAMPLE, profiles={3: "nope"})
    with pytest.raises(ValueError, match="node-ID"):
        motionwire.decode(SAMPLE, profiles={128: "akd"})
    with pytest.raises(ValueError, match="eds 3="):
        motionwire.decode(SAMPLE, eds={3: ROOT / "README.md"})
    with pytest.raises(NotImplementedError):
        motionwire.decode(SAMPLE, profiles={("can0", 3): "akd"})
    with pytest.raises(TypeError):
        motionwire.read_logs(SAMPLE)


def test_a_forced_format_reads_the_input_as_that_format():
    with pytest.raises(motionwire.LogError):
        motionwire.read_log(FIXTURES / "blf" / "python_can.blf", format="pcap")
    table = motionwire.read_log(SAMPLE, format="asc")
    assert table.num_rows == 0
    assert int(table.schema.metadata[b"motionwire.skipped_count"]) > 3000


def test_profiles_and_eds():
    akd = motionwire.decode(SAMPLE, profiles={3: "akd"})
    generic = motionwire.decode(SAMPLE)
    every = motionwire.decode(SAMPLE, profiles="akd")
    assert akd.column("record") != generic.column("record")
    assert motionwire.decode(SAMPLE, profiles={None: "akd"}).equals(every)
    eds = motionwire.decode(
        FIXTURES / "pdo" / "python_canopen.log", eds={3: FIXTURES / "pdo" / "drive.eds"}
    )
    assert any('"signals"' in r for r in eds.column("record").to_pylist())


def test_read_logs():
    paths = [SAMPLE, FIXTURES / "blf" / "python_can.blf", FIXTURES / "mf4" / "canedge_vlsd.mf4"]
    table = motionwire.read_logs(paths)
    assert fields(table.schema) == [("file", pa.dictionary(pa.int32(), pa.string()), False)] + READ_LOG_SCHEMA
    assert table.num_rows == 3765 + 39 + 2010
    assert table.column("file").to_pylist() == [str(p) for p in paths for _ in range(
        {0: 3765, 1: 39, 2: 2010}[paths.index(p)])]
    # Each log's rows are read_log's, in the order given; one dictionary of
    # interfaces for the table.
    for path in paths:
        mine = table.filter(pc.equal(table.column("file").cast(pa.string()), str(path)))
        assert mine.drop_columns(["file"]).to_pylist() == motionwire.read_log(path).to_pylist()
    assert sorted(set(table.column("iface").to_pylist()) - {None}) == ["1", "2", "can0"]
    dictionaries = {tuple(chunk.dictionary.to_pylist()) for chunk in table.column("iface").chunks}
    assert len(dictionaries) == 1
    # Any number of threads reads the same table; bytes are named by place.
    assert motionwire.read_logs(paths, threads=1).equals(table)
    assert motionwire.read_logs(paths, 7).equals(table)
    named = motionwire.read_logs([SAMPLE.read_bytes(), os.fspath(SAMPLE)])
    assert set(named.column("file").to_pylist()) == {"<bytes 0>", str(SAMPLE)}
    with pytest.raises(motionwire.LogError, match="<bytes 1>: unrecognised"):
        motionwire.read_logs([SAMPLE, b"nothing to see\n"])
    assert motionwire.read_logs([]).num_rows == 0
    with pytest.raises(ValueError):
        motionwire.read_logs(paths, threads=0)


def test_read_logs_lists_each_files_skipped_lines():
    bad = b"(1.000000) can0 705#05\n(1.100000) can0 0X1#00\n"
    table = motionwire.read_logs([bad, bad])
    metadata = table.schema.metadata
    assert metadata[b"motionwire.skipped_count"] == b"2"
    assert [s["file"] for s in json.loads(metadata[b"motionwire.skipped"])] == ["<bytes 0>", "<bytes 1>"]


def test_pandas_round_trip():
    pd = pytest.importorskip("pandas")
    table = motionwire.decode(SAMPLE)
    frame = table.to_pandas()
    assert len(frame) == 3765
    assert isinstance(frame["kind"].dtype, pd.CategoricalDtype)
    assert frame["node"].isna().sum() == table.column("node").null_count
    assert frame.loc[frame["kind"] == "emcy", "code"].iloc[1] == 0x7305
    back = pa.Table.from_pandas(frame, preserve_index=False)
    assert back.column("record").to_pylist() == table.column("record").to_pylist()
    assert back.column("data").to_pylist() == table.column("data").to_pylist()
    assert back.column("line").to_pylist() == table.column("line").to_pylist()


def test_duckdb_round_trip():
    duckdb = pytest.importorskip("duckdb")
    t = motionwire.decode(SAMPLE)
    counts = duckdb.sql(
        "select node, count(*) as frames from t where node is not null group by node order by node"
    ).fetchall()
    summary = motionwire.summary(SAMPLE)
    expected = sorted((r["node"], sum(r["frames"].values())) for r in summary if r["type"] == "node")
    assert counts == expected
    emcys = duckdb.sql("select line, code, description from t where kind = 'emcy' order by line").fetchall()
    assert emcys[1] == (613, 0x7305, "Incremental sensor 1 fault")
    back = duckdb.sql("select * from t").arrow()
    if hasattr(back, "read_all"):
        back = back.read_all()
    assert back.num_rows == t.num_rows
    assert back.column("record").to_pylist() == t.column("record").to_pylist()


def test_polars():
    pl = pytest.importorskip("polars")
    frame = pl.from_arrow(motionwire.read_logs([SAMPLE, FIXTURES / "blf" / "python_can.blf"]))
    per_file = frame.group_by("file").len().sort("file")
    assert per_file.rows() == [(str(SAMPLE), 3765), (str(FIXTURES / "blf" / "python_can.blf"), 39)]


def test_parquet(tmp_path: Path):
    pq = pytest.importorskip("pyarrow.parquet")
    table = motionwire.read_logs([SAMPLE, FIXTURES / "asc" / "canoe.asc"])
    pq.write_table(table, tmp_path / "fleet.parquet")
    back = pq.read_table(tmp_path / "fleet.parquet")
    assert back.num_rows == table.num_rows
    assert back.column("data").to_pylist() == table.column("data").to_pylist()


def fixtures_of_every_kind():
    """Every fixture of every format, and the EtherCAT captures."""
    return sorted(
        p
        for p in FIXTURES.rglob("*")
        if p.is_file() and p.suffix in (".log", ".txt", ".asc", ".trc", ".blf", ".pcap", ".pcapng", ".mf4")
    ) + sorted((ROOT / "tests" / "data" / "ethercat").glob("*.pcapng"))


@pytest.mark.parametrize("path", fixtures_of_every_kind(), ids=lambda p: str(p.relative_to(ROOT)))
def test_bad_input_never_crashes(path):
    """Truncated and damaged copies of every fixture and EtherCAT capture:
    a table, or LogError; never a crash, a panic or another exception."""
    data = path.read_bytes()
    rng = random.Random(path.name)
    inputs = [data[:n] for n in sorted({0, 1, 7, 64, 100, len(data) // 3, len(data) // 2, len(data) - 1})]
    for _ in range(6):
        damaged = bytearray(data)
        for _ in range(1 + len(data) // 200):
            damaged[rng.randrange(len(damaged))] = rng.randrange(256)
        inputs.append(bytes(damaged))
    inputs.append(gzip.compress(data)[: len(data) // 2])
    for source in inputs:
        for call in (
            motionwire.read_log,
            motionwire.decode,
            motionwire.summary,
            lambda s: list(motionwire.Reader(s)),
        ):
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    call(source)
            except motionwire.LogError:
                pass


def test_random_bytes_never_crash():
    rng = random.Random(24)
    for n in range(200):
        source = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 2000)))
        if n % 4 == 0:
            # Headers of the binary formats, then noise.
            source = rng.choice([b"LOGG", b"\xd4\xc3\xb2\xa1", b"\x0a\x0d\x0d\x0a", b"MDF     4.10"]) + source
        for call in (motionwire.read_log, motionwire.decode):
            try:
                call(source)
            except motionwire.LogError:
                pass


def test_the_gil_is_released_while_reading():
    """Two threads read at once: each call runs without the GIL."""
    import threading
    import time

    data = SAMPLE.read_bytes() * 40
    started = time.perf_counter()
    motionwire.read_log(data)
    alone = time.perf_counter() - started
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1

    counter = threading.Thread(target=count)
    counter.start()
    started = time.perf_counter()
    motionwire.read_log(data)
    done.set()
    counter.join()
    # While Rust read, Python ran: the counting thread was not starved.
    assert ticks > 1000, (ticks, alone)


def test_reader_without_python_can(tmp_path):
    """Without python-can, Reader yields motionwire.Message with the same
    attributes."""
    import subprocess
    import sys

    script = (
        "import sys; sys.modules['can'] = None\n"
        "import motionwire\n"
        f"msgs = list(motionwire.Reader({str(SAMPLE)!r}))\n"
        "m = msgs[612]\n"
        "assert type(m).__name__ == 'Message' and type(m).__module__ == 'motionwire'\n"
        "assert (m.arbitration_id, m.channel, m.dlc, m.data, m.is_rx) == (0x083, 'can0', 8, bytes.fromhex('0573011100000000'), True)\n"
        "print(len(msgs), repr(m))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("3765 motionwire.Message(")
