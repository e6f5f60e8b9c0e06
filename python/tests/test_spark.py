"""`motionwire.spark` (docs/spark.md): a fleet's logs as Spark DataFrames,
on a real Spark (`local[2]`, one session for the module).

The fleet is built in a temporary directory, partitioned by machine and
date as a fleet's object storage is: every log of the repository's
fixtures and EtherCAT captures (candump log and screen output, ASC, TRC,
BLF, pcap, pcapng, MF4), gzip-compressed copies, damaged copies, files
that are no log (the fixtures' JSON, TSV, EDS and README files, random
bytes) and an empty file. Each DataFrame must equal, file by file, what
the single-process functions of docs/python.md give for that file.

Spark is part of the test suite (the `test` extra installs pyspark;
Java 17 runs it): without pyspark or Java the module fails at once and
says which is missing, as `.ci/run` would.
"""

from __future__ import annotations

import gzip
import functools
import hashlib
import json
import os
import random
import re
import shutil
import subprocess
import sys
import warnings
from collections import defaultdict
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq
import pytest

import motionwire
from motionwire import spark as mws
from conftest import FIXTURES, ROOT, SAMPLE

def _missing() -> str | None:
    try:
        import pyspark  # noqa: F401
    except ImportError:
        return "pyspark is not installed (pip install ./python[spark])"
    java = os.path.join(os.environ["JAVA_HOME"], "bin", "java") if "JAVA_HOME" in os.environ else shutil.which("java")
    if not java or not os.path.exists(java):
        return "no Java for Spark (java on PATH or JAVA_HOME)"
    return None


MISSING = _missing()
if MISSING:
    raise RuntimeError(f"the Spark tests need Spark: {MISSING}")

#: The options of every call: the sample's devices (docs/python.md#summary).
OPTIONS = dict(heartbeat_ms=300, profiles={3: "akd", 5: "baumer"})


# ---------------------------------------------------------------------------
# The fleet


def _fleet(root: Path) -> list[Path]:
    """Write the fleet under `root`; return its files."""
    sources = sorted(
        p
        for d in (FIXTURES, ROOT / "tests" / "data" / "ethercat")
        for p in d.rglob("*")
        if p.is_file()
    ) + [SAMPLE]
    files: list[Path] = []

    def put(i: int, name: str, content: bytes) -> None:
        machine, day = i % 12, i % 3
        path = root / f"machine={machine:03d}" / f"date=2024-05-0{day + 1}" / f"{i:03d}-{name}"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)
        files.append(path)

    for i, source in enumerate(sources):
        put(i, source.name, source.read_bytes())
    n = len(sources)
    rng = random.Random(37)
    logs = {
        "machine.log": SAMPLE,
        "python_can.blf": FIXTURES / "blf" / "python_can.blf",
        "canedge_01_07.mf4": FIXTURES / "mf4" / "canedge_01_07.mf4",
        "twincat-akd-startup.pcapng": ROOT / "tests" / "data" / "ethercat" / "twincat-akd-startup.pcapng",
        "sll2.pcap": FIXTURES / "pcap" / "sll2.pcap",
        "canoe.asc": FIXTURES / "asc" / "canoe.asc",
        "python_can_v2_1.trc": FIXTURES / "trc" / "python_can_v2_1.trc",
    }
    extra: list[tuple[str, bytes]] = []
    for name, path in logs.items():
        content = path.read_bytes()
        # gzip-compressed, as loggers upload them.
        extra.append((name + ".gz", gzip.compress(content, mtime=0)))
        # Cut in the middle: a damaged tail (skipped records) or a
        # damaged file (an error row), as the single-process reading says.
        extra.append(("cut-" + name, content[: len(content) // 2]))
        # Bytes overwritten early: a damaged header or damaged records.
        spoiled = bytearray(content)
        for at in rng.sample(range(min(len(content), 512)), 16):
            spoiled[at] = rng.randrange(256)
        extra.append(("spoiled-" + name, bytes(spoiled)))
    # A gzip stream cut short: the input fails while it is read.
    extra.append(("cut-machine.log.gz", gzip.compress(SAMPLE.read_bytes(), mtime=0)[:3000]))
    # A candump log with malformed lines among the good ones.
    lines = SAMPLE.read_text().splitlines(keepends=True)
    for at in (5, 50, 500, 1500):
        lines.insert(at, "(1700000000.5) can0 XYZ#not-a-frame\n")
    extra.append(("garbled-machine.log", "".join(lines).encode()))
    extra.append(("empty.log", b""))
    extra.append(("empty log #2 100%.log", b""))
    extra.append(("machine log #7 100%.log", SAMPLE.read_bytes()))
    extra.append(("random.bin", bytes(rng.randrange(256) for _ in range(4096))))
    extra.append(("notes.txt", b"Machine 7 was serviced on Tuesday; no log this time.\n"))
    for j, (name, content) in enumerate(extra):
        put(n + j, name, content)
    return files


@pytest.fixture(scope="module")
def fleet(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("fleet")
    _fleet(root)
    return root


def _files(root: Path) -> list[Path]:
    return sorted(p for p in root.rglob("*") if p.is_file())


@pytest.fixture(scope="module")
def spark():
    if MISSING:
        pytest.skip(MISSING)
    from pyspark.sql import SparkSession

    # The executors' Python is this one, which has the package.
    os.environ["PYSPARK_PYTHON"] = sys.executable
    # MOTIONWIRE_SPARK_REMOTE runs the module through Spark Connect
    # instead (pyspark 4: "local[2]" starts a local Connect server).
    remote = os.environ.get("MOTIONWIRE_SPARK_REMOTE")
    if remote:
        builder = SparkSession.builder.remote(remote)
    else:
        builder = SparkSession.builder.master("local[2]").config("spark.ui.enabled", "false")
    session = builder.appName("motionwire-tests").config("spark.sql.shuffle.partitions", "2").getOrCreate()
    if not remote:
        session.sparkContext.setLogLevel("ERROR")
    yield session
    session.stop()


def _local(file: str) -> str:
    """The real path of a `file` of the DataFrames."""
    local = mws.local_path(file)
    assert local is not None, file
    return os.path.realpath(local)


def _single(call, path: Path, **kwargs):
    """`call(path, …)` in one process: its result, or the error row's
    reason (the message without the path it starts with)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return call(str(path), **kwargs), None
    except motionwire.LogError as error:
        text = str(error)
        assert text.startswith(f"{path}: "), text
        return None, text[len(f"{path}: ") :]


def _digest(rows: list) -> str:
    return hashlib.sha256(repr(rows).encode()).hexdigest()


def _by_file(rows: list[dict]) -> dict[str, list[dict]]:
    out: dict[str, list[dict]] = defaultdict(list)
    for row in rows:
        out[_local(row["file"])].append(row)
    return out


# ---------------------------------------------------------------------------
# Without Spark


def test_import_motionwire_does_not_import_pyspark():
    code = (
        "import sys, motionwire, motionwire.spark\n"
        "assert 'pyspark' not in sys.modules, sorted(m for m in sys.modules if 'spark' in m)\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


def test_hadoop_paths_of_uris():
    """inputFiles() gives URIs; the binaryFile source Hadoop paths."""
    assert mws.hadoop_path("file:///data/a%20b/c%23d%25.log") == "file:/data/a b/c#d%.log"
    assert mws.hadoop_path("s3a://fleet/machine%3D7/x.mf4") == "s3a://fleet/machine=7/x.mf4"
    assert mws.hadoop_path("hdfs://nn:8020/logs/a.log") == "hdfs://nn:8020/logs/a.log"


def test_local_paths_are_file_uris_only():
    assert mws.local_path("file:/data/a.log") == "/data/a.log"
    assert mws.local_path("file:///data/a b.log") == "/data/a b.log"
    assert mws.local_path("file://otherhost/data/a.log") is None
    assert mws.local_path("s3a://bucket/logs/a.mf4") is None
    assert mws.local_path("hdfs://nn:8020/logs/a.mf4") is None
    assert mws.local_path("/data/a.log") is None


class _Conf:
    def __init__(self, values: dict):
        self.values = values

    def get(self, key, default=None):
        return self.values.get(key, default)


class _Session:
    def __init__(self, **values):
        self.conf = _Conf({key.replace("_", "."): value for key, value in values.items()})


def test_jvm_memory_settings_are_read_as_spark_reads_them():
    assert mws.jvm_bytes("1g") == 1 << 30
    assert mws.jvm_bytes("512m") == 512 << 20
    assert mws.jvm_bytes("4096K") == 4 << 20
    assert mws.jvm_bytes("2gb") == 2 << 30
    assert mws.jvm_bytes("1024") == 1 << 30
    with pytest.raises(ValueError):
        mws.jvm_bytes("lots")


def test_the_content_limit_is_a_share_of_the_heap_that_reads_it():
    """A file's content in a row is copied several times over: above
    1/16 of the reading JVM's heap (local mode: the driver's) a file goes
    by path; Spark's own binaryFile limit caps it."""
    # Spark's defaults: 1g of heap, so 64 MiB.
    assert mws.content_limit(_Session(spark_master="local[2]")) == (
        64 << 20,
        "1/16 of the heap that reads it (spark.driver.memory = 1g)",
    )
    assert mws.content_limit(_Session(spark_master="yarn", spark_executor_memory="4g")) == (
        256 << 20,
        "1/16 of the heap that reads it (spark.executor.memory = 4g)",
    )
    # 64g: a sixteenth is more than a row holds.
    assert mws.content_limit(_Session(spark_master="yarn", spark_executor_memory="64g")) == (
        2**31 - 1,
        "a Spark binaryFile row holds (spark.sql.sources.binaryFile.maxLength = 2147483647)",
    )
    lowered = _Session(spark_master="local[*]", spark_driver_memory="64g")
    lowered.conf.values[mws.MAX_LENGTH_KEY] = "4096"
    assert mws.content_limit(lowered) == (
        4096,
        "a Spark binaryFile row holds (spark.sql.sources.binaryFile.maxLength = 4096)",
    )


def test_a_file_too_large_for_spark_and_not_local_is_an_error_row(tmp_path):
    """What an executor does with a file longer than a binaryFile row:
    one it cannot open by path (object storage) gives an error row saying
    so; one it can is read in place, as read_log reads it."""
    batch = pa.RecordBatch.from_pydict(
        {
            "path": ["s3a://fleet/machine=7/big.mf4", "file:" + str(SAMPLE), "file:" + str(tmp_path / "gone.log")],
            "content": pa.nulls(3, pa.binary()),
            "length": [3_000_000_000, SAMPLE.stat().st_size, 3_000_000_000],
        }
    )
    work = functools.partial(mws._frames_of, format=None, decoded=False, options={})
    out = pa.Table.from_batches(
        list(mws._map_files(iter([batch]), work=work, schema=mws.FRAMES, per_batch=False, limit=2**31 - 1))
    )
    assert out.schema == mws.FRAMES
    by_file = defaultdict(list)
    for row in out.to_pylist():
        by_file[row["file"]].append(row)
    (s3,) = by_file["s3a://fleet/machine=7/big.mf4"]
    assert s3["file_error"] == (
        "3000000000 bytes, more than a Spark binaryFile row holds "
        "(spark.sql.sources.binaryFile.maxLength = 2147483647), and not on a file "
        "system the executors share (a file: path): not read"
    )
    assert [r["line"] for r in by_file["file:" + str(SAMPLE)]] == motionwire.read_log(SAMPLE).column("line").to_pylist()
    (gone,) = by_file["file:" + str(tmp_path / "gone.log")]
    assert gone["file_error"].startswith("FileNotFoundError: "), gone


def test_the_schemas_are_the_documented_ones():
    """docs/spark.md#schemas lists these columns and Spark types."""
    doc = (ROOT / "docs" / "spark.md").read_text()
    for name, schema in (("frames", mws.FRAMES), ("decode", mws.DECODE), ("summary", mws.SUMMARY), ("findings", mws.FINDINGS)):
        m = re.search(rf'<a id="{name}-schema"></a>\n\n```\n(.*?)\n```', doc, re.S)
        assert m, f"docs/spark.md has no {name} schema"
        documented = [line.split()[:2] for line in m.group(1).splitlines()]
        assert documented == [[f.name, mws._SPARK_TYPES[f.type]] for f in schema], name


#: The Spark type each Arrow type of the single-process tables becomes
#: (docs/spark.md#schemas): unsigned integers the next wider signed type,
#: dictionaries plain strings.
WIDER = {pa.uint8(): pa.int16(), pa.uint16(): pa.int32(), pa.uint32(): pa.int64(), pa.uint64(): pa.int64()}


def _spark_type(arrow_type: pa.DataType) -> pa.DataType:
    if pa.types.is_dictionary(arrow_type):
        return arrow_type.value_type
    return WIDER.get(arrow_type, arrow_type)


def test_the_schemas_hold_the_native_tables_columns():
    """The Spark schemas are written out (docs/spark.md lists them); every
    column of the single-process tables they carry is there with its
    widened type, so that a native column's type cannot change under
    them unseen."""
    capture = ROOT / "tests" / "data" / "ethercat" / "synthetic_akd_fault.pcapng"
    for schema, tables in (
        (mws.FRAMES, [motionwire.read_log(SAMPLE), motionwire.read_log(capture)]),
        (mws.DECODE, [motionwire.decode(SAMPLE), motionwire.decode(capture)]),
        (mws.FINDINGS, [motionwire.findings(SAMPLE, **OPTIONS), motionwire.findings(capture)]),
    ):
        spark_types = {f.name: f.type for f in schema}
        for table in tables:
            for field in table.schema:
                # `time` is not kept, a datagram's `packet` is `line`, and
                # `frames` leaves out the datagrams' constant `kind`.
                if field.name == "time" or (schema is mws.FRAMES and field.name == "kind"):
                    continue
                name = "line" if field.name == "packet" else field.name
                assert spark_types.get(name) == _spark_type(field.type), (field, schema.names)


# ---------------------------------------------------------------------------
# On Spark


def test_the_dataframes_have_the_fixed_schemas(spark, fleet):
    for call, schema in ((mws.frames, mws.FRAMES), (mws.decode, mws.DECODE), (mws.summary, mws.SUMMARY), (mws.findings, mws.FINDINGS)):
        df = call(spark, str(fleet))
        assert [(f.name, f.dataType.simpleString(), f.nullable) for f in df.schema] == [
            (f.name, mws._SPARK_TYPES[f.type].replace("short", "smallint").replace("long", "bigint"), f.nullable)
            for f in schema
        ]


def _expected_frames(path: Path, decoded: bool) -> tuple[list, str | None]:
    """The rows of `frames` (or `decode`) for one file, from read_log (or
    decode) in one process, in the DataFrame's columns."""
    schema = mws.DECODE if decoded else mws.FRAMES
    call = motionwire.decode if decoded else motionwire.read_log
    kwargs = {"profiles": OPTIONS["profiles"]} if decoded else {}
    table, reason = _single(call, path, **kwargs)
    if table is None:
        return [], reason
    names = [f.name for f in schema][2:]
    ethercat = "packet" in table.schema.names
    rows = []
    for row in table.to_pylist():
        # The DataFrames keep `ts`: `time` is a timestamp or a duration
        # by the file, which one fixed schema cannot hold
        # (docs/spark.md#schemas).
        row.pop("time", None)
        if ethercat:
            row["line"] = row.pop("packet")
            if not decoded:
                del row["kind"]
        assert set(row) <= set(names), set(row) - set(names)
        rows.append(tuple(row.get(name) for name in names))
    return rows, None


def _check_frames(spark, fleet, tmp_path, decoded: bool):
    call = mws.decode if decoded else mws.frames
    kwargs = {"profiles": OPTIONS["profiles"]} if decoded else {}
    out = tmp_path / "parquet"
    # Written to Parquet as they are (docs/spark.md#parquet), read back by
    # pyarrow: the rows of each file in the log's order.
    call(spark, str(fleet), **kwargs).write.parquet(str(out))
    got = _by_file(pq.read_table(out).to_pylist())
    schema = mws.DECODE if decoded else mws.FRAMES
    names = [f.name for f in schema][2:]
    expected, found = {}, {}
    errors = 0
    for path in _files(fleet):
        rows, reason = _expected_frames(path, decoded)
        key = os.path.realpath(path)
        spark_rows = got.get(key, [])
        if reason is not None:
            errors += 1
            expected[key] = ("error", reason)
            assert len(spark_rows) == 1, (path, len(spark_rows))
            assert all(spark_rows[0][n] is None for n in names)
            found[key] = ("error", spark_rows[0]["file_error"])
        else:
            expected[key] = (len(rows), _digest(rows))
            assert all(r["file_error"] is None for r in spark_rows)
            spark_rows = [tuple(r[n] for n in names) for r in spark_rows]
            found[key] = (len(spark_rows), _digest(spark_rows))
    assert found == expected
    assert set(got) <= set(expected)
    assert errors >= 80 and len(expected) - errors >= 70, (errors, len(expected))


def test_frames_equal_read_log_file_by_file(spark, fleet, tmp_path):
    _check_frames(spark, fleet, tmp_path, decoded=False)


def test_decode_equals_decode_file_by_file(spark, fleet, tmp_path):
    _check_frames(spark, fleet, tmp_path, decoded=True)


def _typed(record: dict) -> dict:
    """The typed columns docs/spark.md#summary takes from a summary record."""
    kind = record["type"]
    if kind == "node":
        return {
            "type": "node",
            "iface": record["iface"],
            "node": record["node"],
            "frames_total": sum(record["frames"].values()),
            "emcy": record["emcy"],
            "first_error_code": (record["first_error"] or {}).get("code"),
            "first_error_line": (record["first_error"] or {}).get("line"),
            "first_error_ts": (record["first_error"] or {}).get("ts"),
            "boot_ups": record["heartbeat"]["boot_up_count"],
            "heartbeat_timeouts": record["heartbeat"]["timeout_count"],
            "sdo_aborts": record["sdo"]["abort_count"],
            "cia402_faults": record["cia402"]["fault_count"] if record["cia402"] else 0,
        }
    if kind == "bus":
        return {"type": "bus", "iface": record["iface"], "frames_total": record["frames"]}
    if kind == "verdict":
        return {"type": "verdict", "iface": record["stop"]["iface"], "node": record["stop"]["node"]}
    if kind == "ethercat":
        return {"type": "ethercat", "iface": record["iface"], "frames_total": record["packets"]}
    return {"type": kind, "iface": record.get("iface")}


TYPED = [f.name for f in mws.SUMMARY][2:-3]


def test_summary_equals_summary_file_by_file(spark, fleet):
    got = _by_file([r.asDict() for r in mws.summary(spark, str(fleet), **OPTIONS).collect()])
    files = _files(fleet)
    assert set(got) == {os.path.realpath(p) for p in files}, "every file has a row"
    kinds = defaultdict(int)
    for path in files:
        rows = got[os.path.realpath(path)]
        records, reason = _single(motionwire.summary, path, **OPTIONS)
        if reason is not None:
            assert [(r["file_error"], r["type"], r["record"]) for r in rows] == [(reason, None, None)], path
            kinds["error"] += 1
            continue
        assert all(r["file_error"] is None for r in rows)
        file_row, rest = rows[0], rows[1:]
        # The record strings: exactly the summary's records, in its order.
        assert [json.loads(r["record"]) for r in rest] == records, path
        for row, record in zip(rest, records):
            typed = {name: row[name] for name in TYPED}
            assert typed == {name: _typed(record).get(name) for name in TYPED}, (path, record["type"])
            kinds[record["type"]] += 1
        # The file's row: frames read, lines skipped, the format.
        table, _ = _single(motionwire.read_log, path)
        meta = table.schema.metadata
        ethercat = json.loads(meta.get(b"motionwire.ethercat", b'{"packets": 0, "damaged": 0}'))
        can_frames = table.num_rows if "id" in table.schema.names else 0
        record = json.loads(file_row["record"])
        assert file_row["type"] == "file" and record["type"] == "file"
        assert file_row["frames_total"] == can_frames + ethercat["packets"], path
        assert (record["frames"], record["ethercat_packets"]) == (can_frames, ethercat["packets"])
        assert file_row["format"] == record["format"] == meta[b"motionwire.format"].decode()
        # read_log also lists an EtherCAT capture's damaged datagrams,
        # which the summary's `ethercat` record counts.
        assert file_row["skipped"] + ethercat["damaged"] == int(meta[b"motionwire.skipped_count"]), path
        assert file_row["skipped"] == record["skipped_count"]
        assert record["skipped"] == json.loads(meta[b"motionwire.skipped"])[:10]
        kinds["file"] += 1
        if path.name.split("-", 1)[1].startswith(("empty.log", "empty log")):
            assert file_row["frames_total"] == 0 and rest == []
            kinds["empty"] += 1
        if path.name.endswith("garbled-machine.log"):
            assert file_row["skipped"] == 4
            assert [s["line"] for s in record["skipped"]] == [6, 51, 501, 1501]
            kinds["garbled"] += 1
    assert kinds["empty"] == 2 and kinds["garbled"] == 1
    for kind in ("node", "bus", "verdict", "ethercat", "slave", "stream", "file", "error"):
        assert kinds[kind] > 0, kind


def test_findings_equal_findings_file_by_file(spark, fleet):
    got = _by_file([r.asDict() for r in mws.findings(spark, str(fleet), **OPTIONS).collect()])
    with_findings = 0
    for path in _files(fleet):
        rows = got.get(os.path.realpath(path), [])
        table, reason = _single(motionwire.findings, path, **OPTIONS)
        if reason is not None:
            assert [r["file_error"] for r in rows] == [reason], path
            continue
        expected = table.to_pylist()
        findings = [r for r in rows if r["kind"] not in ("stop", "first_cause")]
        verdict = [r for r in rows if r["kind"] in ("stop", "first_cause")]
        assert [{k: r[k] for k in expected[0]} for r in findings] == expected if expected else findings == [], path
        for r in findings:
            # The code is the EMCY's or the SDO abort's the text names.
            if r["kind"] in ("first_error", "first_warning"):
                assert f"EMCY 0x{r['code']:04X}" in r["text"], r
            elif r["kind"] == "sdo_abort":
                assert f"0x{r['code']:08x}" in r["text"].lower(), r
            elif r["kind"] == "cia402_fault" and "after EMCY" in r["text"]:
                assert f"after EMCY 0x{r['code']:04X}" in r["text"], r
            elif r["kind"] != "cia402_fault":
                assert r["code"] is None, r
        records, _ = _single(motionwire.summary, path, **OPTIONS)
        stops = [rec for rec in records if rec["type"] == "verdict"]
        if stops:
            (v,) = stops
            assert [(r["kind"], r["line"], r["iface"], r["node"], r["severity"], r["text"]) for r in verdict] == [
                (kind, v[kind]["line"], v[kind]["iface"], v[kind]["node"], v[kind]["severity"], v[kind]["text"])
                for kind in ("stop", "first_cause")
            ], path
            assert verdict[0]["ts"] is not None or v["stop"].get("ts") is None
        else:
            assert verdict == []
        # Every file whose summary has a fault has its findings.
        faulty = any(
            rec["type"] == "node"
            and (
                rec["first_error"]
                or (rec["cia402"] or {}).get("fault_count")
                or rec["heartbeat"]["timeout_count"]
                or rec["heartbeat"]["boot_up_count"] > 1
                or rec["guarding"]["toggle_error_count"]
                or rec["sdo"]["abort_count"]
                or rec["sdo"]["broken_count"]
                or rec["sdo"]["timeout_count"]
            )
            or rec["type"] == "bus" and (rec["bus_off_count"] or rec["error_passive_count"])
            # An EtherCAT slave's error emergency, AL error, CiA 402 or
            # servo fault (docs/ethercat.md#findings).
            or rec["type"] == "slave"
            and (
                any(e["code"] != 0 for e in rec["emcy"])
                or any(c["error"] and not c["requested"] for c in rec["al_timeline"])
                or (rec["cia402"] or {}).get("fault_count")
                or (rec["servo"] or {}).get("fault_set_count")
            )
            for rec in records
        )
        assert faulty == bool(findings), path
        with_findings += bool(findings)
    assert with_findings >= 10


def test_files_longer_than_a_binaryfile_row_are_read_by_path(spark, fleet):
    """Above Spark's binaryFile limit a file is read by path on the
    executor (the file: paths of local[2]); the rows are the same. The
    limit is lowered to 4 kB so that most of the fleet goes that way."""
    expected = sorted(map(tuple, mws.summary(spark, str(fleet), **OPTIONS).collect()), key=repr)
    spark.conf.set(mws.MAX_LENGTH_KEY, "4096")
    try:
        files = spark.read.format("binaryFile").option("recursiveFileLookup", "true").load(str(fleet))
        assert files.filter("length > 4096").count() >= 40
        got = sorted(map(tuple, mws.summary(spark, str(fleet), **OPTIONS).collect()), key=repr)
    finally:
        spark.conf.unset(mws.MAX_LENGTH_KEY)
    assert got == expected


def test_paths_globs_and_a_binaryfile_dataframe(spark, fleet):
    """A list of paths, a glob, and a binaryFile DataFrame of the caller's
    options select the same files' rows."""
    machine = fleet / "machine=003"
    by_dir = mws.summary(spark, [str(machine)], **OPTIONS).filter("type = 'file' or file_error is not null")
    by_glob = mws.summary(spark, str(fleet / "machine=00[3]" / "*" / "*"), **OPTIONS).filter(
        "type = 'file' or file_error is not null"
    )
    files = spark.read.format("binaryFile").option("pathGlobFilter", "*.mf4").option("recursiveFileLookup", "true")
    mf4 = mws.summary(spark, files.load(str(fleet)), **OPTIONS).filter("type = 'file' or file_error is not null")
    names = lambda df: sorted(os.path.basename(r["file"]) for r in df.collect())  # noqa: E731
    expected = sorted(p.name for p in machine.rglob("*") if p.is_file())
    assert names(by_dir) == names(by_glob) == expected
    assert names(mf4) == sorted(p.name for p in fleet.rglob("*.mf4"))
    assert len(names(mf4)) >= 10


def test_wrong_arguments_raise_on_the_driver(spark, fleet):
    with pytest.raises(ValueError, match="is not a profile"):
        mws.summary(spark, str(fleet), profiles={3: "no-such-drive"})
    with pytest.raises(ValueError, match="is not a node-ID"):
        mws.decode(spark, str(fleet), profiles={300: "akd"})
    with pytest.raises(ValueError, match="is not a log format"):
        mws.frames(spark, str(fleet), format="csv")
    with pytest.raises(FileNotFoundError):
        mws.decode(spark, str(fleet), eds={2: str(fleet / "no-such.eds")})


def test_eds_files_go_to_the_executors(spark, tmp_path):
    """decode's `eds` files are read on the driver and written for the
    executors: the records of a drive's log whose PDOs only its EDS maps
    equal decode's in one process, signals and all."""
    log = FIXTURES / "eds" / "array_drive.log"
    eds = {3: str(FIXTURES / "eds" / "array_drive.eds")}
    (tmp_path / "logs").mkdir()
    shutil.copy(log, tmp_path / "logs" / log.name)
    rows = mws.decode(spark, str(tmp_path / "logs"), eds=eds).select("record").collect()
    expected = motionwire.decode(str(log), eds=eds).column("record").to_pylist()
    assert [r["record"] for r in rows] == expected
    assert any('"signals"' in r for r in expected)
    assert expected != motionwire.decode(str(log)).column("record").to_pylist()


def test_the_readme_block(spark, monkeypatch):
    """README.md, "From Python": the block of motionwire.spark, run with
    this module's session as `spark`."""
    from test_readme import blocks

    (block,) = blocks(spark=True)
    monkeypatch.chdir(ROOT)
    exec(compile(block, "README.md, From Python, the Spark block", "exec"), {"spark": spark})
