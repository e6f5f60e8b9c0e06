"""motionwire on Apache Spark: a fleet's logs as Spark DataFrames
(docs/spark.md).

    from motionwire import spark as mws

    frames = mws.frames(spark, "s3a://bucket/logs/")      # a row per frame
    decoded = mws.decode(spark, paths, profiles={3: "akd"})
    summary = mws.summary(spark, paths, heartbeat_ms=300)  # a row per record
    wrong = mws.findings(spark, paths, heartbeat_ms=300)   # what went wrong

Files are listed and read by Spark's ``binaryFile`` source, so anything it
reads is a path here (local, HDFS, S3, ABFS, GCS; globs; directories read
recursively), or give a DataFrame of that source to choose its options.
Each executor reads its files with the compiled package inside
``mapInArrow``: Arrow batches in and out, no Python object per frame, the
GIL released while Rust reads. Every file has its rows: one that is not a
log or cannot be read gives a row whose ``file_error`` says why, and the
job goes on. The schemas are fixed (docs/spark.md#schemas): unsigned
integers become the next wider signed Spark type.

pyspark is needed here only (``pip install ./python[spark]``);
``import motionwire`` never imports it.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import tempfile
import urllib.parse
from collections.abc import Iterable, Iterator, Mapping
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import pyarrow as pa

from . import _motionwire  # type: ignore[attr-defined]

if TYPE_CHECKING:
    from pyspark.sql import DataFrame, SparkSession

__all__ = [
    "frames",
    "decode",
    "summary",
    "findings",
    "content_limit",
    "jvm_bytes",
    "FRAMES",
    "DECODE",
    "SUMMARY",
    "FINDINGS",
    "HEAP_SHARE",
    "MAX_LENGTH_KEY",
]

# ---------------------------------------------------------------------------
# The schemas (docs/spark.md#schemas), as the Arrow batches the executors
# give Spark. Every column is nullable but `file`: a file's error row has
# nothing but its name and its error.

_HEAD = [
    pa.field("file", pa.string(), nullable=False),
    pa.field("file_error", pa.string()),
]

#: `frames`: the columns of `motionwire.read_log` of a CAN log, then those
#: of an EtherCAT capture's datagrams (docs/python.md#ethercat; `line` is
#: the capture's packet number there, as `packet` in `read_log`).
FRAMES = pa.schema(
    _HEAD
    + [
        pa.field("line", pa.int64()),
        pa.field("ts", pa.float64()),
        pa.field("iface", pa.string()),
        pa.field("id", pa.int64()),
        pa.field("extended", pa.bool_()),
        pa.field("rtr", pa.bool_()),
        pa.field("fd", pa.bool_()),
        pa.field("brs", pa.bool_()),
        pa.field("esi", pa.bool_()),
        pa.field("error", pa.bool_()),
        pa.field("dlc", pa.int16()),
        pa.field("data", pa.binary()),
        pa.field("datagram", pa.int32()),
        pa.field("cmd", pa.string()),
        pa.field("index", pa.int16()),
        pa.field("adp", pa.int32()),
        pa.field("ado", pa.int32()),
        pa.field("logical", pa.int64()),
        pa.field("length", pa.int32()),
        pa.field("irq", pa.int32()),
        pa.field("wkc", pa.int32()),
        pa.field("returned", pa.bool_()),
    ]
)

#: `decode`: the columns of `frames`, then those `motionwire.decode` adds.
DECODE = pa.schema(
    list(FRAMES)
    + [
        pa.field("kind", pa.string()),
        pa.field("node", pa.int16()),
        pa.field("code", pa.int32()),
        pa.field("register", pa.int16()),
        pa.field("description", pa.string()),
        pa.field("state", pa.string()),
        pa.field("cia402_state", pa.string()),
        pa.field("record", pa.string()),
    ]
)

#: `summary`: a row per record of `decode --summary --json` and one
#: `type = "file"` row per file; typed columns taken from the record, and
#: the whole record.
SUMMARY = pa.schema(
    _HEAD
    + [
        pa.field("type", pa.string()),
        pa.field("iface", pa.string()),
        pa.field("node", pa.int16()),
        pa.field("frames_total", pa.int64()),
        pa.field("emcy", pa.int64()),
        pa.field("first_error_code", pa.int32()),
        pa.field("first_error_line", pa.int64()),
        pa.field("first_error_ts", pa.float64()),
        pa.field("boot_ups", pa.int64()),
        pa.field("heartbeat_timeouts", pa.int64()),
        pa.field("sdo_aborts", pa.int64()),
        pa.field("cia402_faults", pa.int64()),
        pa.field("format", pa.string()),
        pa.field("skipped", pa.int64()),
        pa.field("record", pa.string()),
    ]
)

#: `findings`: a row per finding of `motionwire.findings`, and the
#: verdict's stop and first cause.
FINDINGS = pa.schema(
    _HEAD
    + [
        pa.field("ts", pa.float64()),
        pa.field("iface", pa.string()),
        pa.field("node", pa.int16()),
        pa.field("slave", pa.int32()),
        pa.field("kind", pa.string()),
        pa.field("line", pa.int64()),
        pa.field("code", pa.int64()),
        pa.field("severity", pa.string()),
        pa.field("text", pa.string()),
    ]
)

_SPARK_TYPES = {
    pa.string(): "string",
    pa.binary(): "binary",
    pa.bool_(): "boolean",
    pa.int16(): "short",
    pa.int32(): "int",
    pa.int64(): "long",
    pa.float64(): "double",
}


def ddl(schema: pa.Schema) -> str:
    """The Spark DDL of one of the schemas (``file string NOT NULL, …``)."""
    return ", ".join(
        f"`{f.name}` {_SPARK_TYPES[f.type]}{'' if f.nullable else ' NOT NULL'}" for f in schema
    )


# ---------------------------------------------------------------------------
# The API


Paths = Union[str, "os.PathLike[str]", Iterable[Union[str, "os.PathLike[str]"]], "DataFrame"]


def frames(spark: SparkSession, paths: Paths, *, format: Optional[str] = None) -> DataFrame:
    """A row per frame of every log (`motionwire.read_log`'s columns, an
    EtherCAT capture's datagram columns beside them), with `file` and
    `file_error`; schema `FRAMES` (docs/spark.md#frames)."""
    _check(format=format)
    work = functools.partial(_frames_of, format=format, decoded=False, options={}, rows=BATCH_ROWS)
    return _run(spark, paths, work, FRAMES, per_batch=False)


def decode(
    spark: SparkSession,
    paths: Paths,
    *,
    profiles: Any = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[str] = None,
) -> DataFrame:
    """`frames` plus `motionwire.decode`'s columns (`kind`, `node`, `code`,
    `register`, `description`, `state`, `record`); schema `DECODE`
    (docs/spark.md#decode). `eds` files are read here, on the driver, and
    handed to the executors."""
    eds_files = _check(format=format, profiles=profiles, eds=eds)
    work = functools.partial(
        _frames_of,
        format=format,
        decoded=True,
        options={"profiles": profiles, "eds": eds_files},
        rows=BATCH_ROWS,
    )
    return _run(spark, paths, work, DECODE, per_batch=False)


def summary(
    spark: SparkSession,
    paths: Paths,
    *,
    heartbeat_ms: Optional[int] = None,
    profiles: Any = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[str] = None,
) -> DataFrame:
    """A row per record of each file's `motionwire.summary` (the verdict,
    nodes, buses, EtherCAT interfaces, slaves and streams) and one
    `type = "file"` row per file; schema `SUMMARY`
    (docs/spark.md#summary)."""
    eds_files = _check(format=format, profiles=profiles, eds=eds, heartbeat_ms=heartbeat_ms)
    options = {"heartbeat_ms": heartbeat_ms, "profiles": profiles, "eds": eds_files, "format": format}
    work = functools.partial(_summary_of, options=options)
    return _run(spark, paths, work, SUMMARY, per_batch=True, empty_files=True)


def findings(
    spark: SparkSession,
    paths: Paths,
    *,
    heartbeat_ms: Optional[int] = None,
    profiles: Any = None,
    eds: Optional[Mapping[int, Union[str, "os.PathLike[str]"]]] = None,
    format: Optional[str] = None,
) -> DataFrame:
    """What went wrong in each file: a row per finding of
    `motionwire.findings` with the code it is about, and the verdict's
    stop (`kind = "stop"`) and first cause (`kind = "first_cause"`) when
    something stopped; schema `FINDINGS` (docs/spark.md#findings)."""
    eds_files = _check(format=format, profiles=profiles, eds=eds, heartbeat_ms=heartbeat_ms)
    options = {"heartbeat_ms": heartbeat_ms, "profiles": profiles, "eds": eds_files, "format": format}
    work = functools.partial(_findings_of, options=options)
    return _run(spark, paths, work, FINDINGS, per_batch=True)


# ---------------------------------------------------------------------------
# The driver's part

#: Spark's own limit on a `binaryFile` row (an internal SQL setting, a
#: Java byte array's length): files longer than it are read by path.
MAX_LENGTH_KEY = "spark.sql.sources.binaryFile.maxLength"
_MAX_LENGTH_DEFAULT = 2**31 - 1
#: A file's content comes in a `binaryFile` row only up to this share of
#: the heap of the JVM that reads it (`spark.executor.memory`; in local
#: mode `spark.driver.memory`; Spark's default 1g): the bytes are copied
#: several times on their way to the Python worker (the file's growing
#: array, the row, the Arrow batch), and a task that runs out of heap
#: fails the job — in local mode its job never returns. On Spark 3.5's
#: default 1 GB heap a 100 MB log went through and a 150 MB one did not
#: (bench/spark_large.py). Longer files are read by path.
HEAP_SHARE = 16
_MEMORY_DEFAULT = "1g"
_UNITS = {"k": 1 << 10, "m": 1 << 20, "g": 1 << 30, "t": 1 << 40, "p": 1 << 50}


def jvm_bytes(text: str) -> int:
    """The bytes of a JVM memory setting as Spark reads it (``"1g"``,
    ``"512m"``, ``"4096k"``, ``"2gb"``; a bare number is MiB, as for
    `spark.executor.memory`)."""
    value = text.strip().lower().removesuffix("b")
    if value and value[-1] in _UNITS:
        return int(value[:-1]) * _UNITS[value[-1]]
    return int(value) << 20


def content_limit(spark: SparkSession) -> tuple[int, str]:
    """The longest file whose content Spark hands over in a row, and what
    sets it: Spark's `binaryFile` limit, or 1/`HEAP_SHARE` of the heap
    that reads it (`spark.driver.memory` in local mode, else
    `spark.executor.memory`)."""

    def conf(key: str, default: str) -> str:
        try:
            return spark.conf.get(key, default) or default
        except Exception:  # a Connect server may refuse a key it hides
            return default

    max_length = int(conf(MAX_LENGTH_KEY, str(_MAX_LENGTH_DEFAULT)))
    local = conf("spark.master", "").startswith("local")
    key = "spark.driver.memory" if local else "spark.executor.memory"
    memory = conf(key, _MEMORY_DEFAULT)
    try:
        heap = jvm_bytes(memory) // HEAP_SHARE
    except ValueError:
        heap = max_length
    if heap < max_length:
        return heap, f"1/{HEAP_SHARE} of the heap that reads it ({key} = {memory})"
    return max_length, f"a Spark binaryFile row holds ({MAX_LENGTH_KEY} = {max_length})"


def _check(*, format=None, profiles=None, eds=None, heartbeat_ms=None) -> Optional[dict]:
    """Raise on the driver what every executor would raise for the
    arguments (an unknown format or profile, a node-ID out of range, an
    EDS file that cannot be read), before any file is read; return the EDS
    files' bytes by node."""
    eds_files = None
    if eds is not None:
        eds_files = {}
        for node, path in dict(eds).items():
            with open(path, "rb") as f:
                eds_files[node] = (os.path.basename(os.fspath(path)), f.read())
    try:
        _motionwire.post_mortem(
            b"",
            heartbeat_ms=heartbeat_ms,
            profiles=profiles,
            eds=None if eds is None else {n: os.fspath(p) for n, p in dict(eds).items()},
            format=format,
        )
    except _motionwire.LogError:
        # An empty input is no log of a binary format: the arguments are
        # fine.
        pass
    return eds_files


def _files(spark: SparkSession, paths: Paths) -> DataFrame:
    """The `binaryFile` DataFrame of `paths` (directories read
    recursively), or `paths` when it is one already."""
    if hasattr(paths, "schema") and hasattr(paths, "mapInArrow"):
        return paths  # type: ignore[return-value]
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    names = [os.fspath(p) for p in paths]
    reader = spark.read.format("binaryFile").option("recursiveFileLookup", "true")
    return reader.load(names)


def _run(
    spark: SparkSession,
    paths: Paths,
    work: Callable[[str, Any], Any],
    schema: pa.Schema,
    *,
    per_batch: bool,
    empty_files: bool = False,
) -> DataFrame:
    """The DataFrame of `work` over every file, in one Python stage.

    Files up to Spark's `binaryFile` limit and 1/`HEAP_SHARE` of the
    reading JVM's heap (`content_limit`) come with their content, one task per
    file partition. The others come as `(path, null, length)` rows,
    gathered into one more task: those longer than the limit (the
    `length` filter is pushed into the source, which then never loads
    them), read by path on the executor; and with `empty_files` the files
    of 0 bytes, which Spark's file scans leave out (`summary` gives each
    its row). Finding them is the JVM's work alone (a scan of the files'
    lengths, the listing's `inputFiles()`, a broadcast anti-join): a Python
    task costs a worker's round trip even when it has no row, so there is
    one Python task per partition of content and one for the rest."""
    from pyspark.sql import functions as F

    files = _files(spark, paths)
    limit, why = content_limit(spark)
    held = files.filter(F.col("length") <= limit).select("path", "content", "length")
    rest = files.filter(F.col("length") > limit).select("path", "length")
    if empty_files:
        # The files the listing found (inputFiles(), as URIs) that the scan
        # does not give (Hadoop paths, as the `path` column names them).
        listed = spark.createDataFrame([(hadoop_path(uri),) for uri in files.inputFiles()], "path string")
        empty = listed.join(F.broadcast(files.select("path")), "path", "left_anti")
        rest = rest.unionByName(empty.select("path", F.lit(0).cast("long").alias("length")))
    rest = rest.repartition(1).select("path", F.lit(None).cast("binary").alias("content"), "length")
    mapper = functools.partial(_map_files, work=work, schema=schema, per_batch=per_batch, limit=limit, why=why)
    return held.unionByName(rest).mapInArrow(mapper, ddl(schema))


def hadoop_path(uri: str) -> str:
    """A path as Spark's `binaryFile` source names it (Hadoop's
    `Path.toString`: ``file:/data/a b.log``) from its URI as
    `DataFrame.inputFiles()` gives it (``file:///data/a%20b.log``)."""
    parts = urllib.parse.urlsplit(uri)
    authority = "//" + urllib.parse.unquote(parts.netloc) if parts.netloc else ""
    fragment = "#" + urllib.parse.unquote(parts.fragment) if parts.fragment else ""
    scheme = parts.scheme + ":" if parts.scheme else ""
    return scheme + authority + urllib.parse.unquote(parts.path) + fragment


# ---------------------------------------------------------------------------
# The executors' part: pure Python and pyarrow, no pyspark.


def _map_files(
    batches: Iterator[pa.RecordBatch],
    *,
    work,
    schema: pa.Schema,
    per_batch: bool,
    limit: int,
    why: Optional[str] = None,
) -> Iterator[pa.RecordBatch]:
    """`mapInArrow` over `(path, content, length)` batches: a file's
    content read from memory; without content, an empty file (length 0)
    or one longer than a `binaryFile` row, read by path where the
    executor sees it (a `file:` path), else given an error row."""
    for batch in batches:
        paths = batch.column(0).to_pylist()
        contents, lengths = batch.column(1), batch.column(2)
        reason = why or f"a Spark binaryFile row holds ({MAX_LENGTH_KEY} = {limit})"
        yield from _emit(_sources(paths, contents, lengths, reason), work, schema, per_batch)


def _sources(paths, contents, lengths, why: str):
    for i, path in enumerate(paths):
        content = contents[i]
        if content.is_valid:
            yield path, content.as_py()
            continue
        length = lengths[i].as_py()
        if length == 0:
            yield path, b""
            continue
        local = local_path(path)
        if local is None:
            yield path, _TooLarge(
                f"{length} bytes, more than {why}, and not on a file system the executors share "
                "(a file: path): not read"
            )
        else:
            yield path, local


class _TooLarge:
    """A file that is not read: its error row says why."""

    def __init__(self, reason: str):
        self.reason = reason


def local_path(path: str) -> Optional[str]:
    """The local path of a `file:` path as Spark names it
    (``file:/data/a.log``, ``file:///data/a.log``); None for any other
    scheme."""
    if path.startswith("file://"):
        rest = path[len("file://") :]
        # file:///data: an empty authority; file://host/data is not local.
        return rest if rest.startswith("/") else None
    if path.startswith("file:"):
        return path[len("file:") :]
    return None


def _emit(sources, work, schema: pa.Schema, per_batch: bool) -> Iterator[pa.RecordBatch]:
    """Run `work` on each `(path, source)`; `per_batch`: its rows (dicts)
    gathered into one batch, else its record batches as they come."""
    if per_batch:
        rows: list = []
        for path, source in sources:
            rows.extend(work(path, source))
        if rows:
            yield pa.RecordBatch.from_pylist(rows, schema=schema)
    else:
        for path, source in sources:
            yield from work(path, source)


def _reason(error: BaseException, source) -> str:
    """What a `file_error` says: a `LogError`'s message without the
    source's name (the `file` column has it), else the exception's type
    and message."""
    if isinstance(error, _motionwire.LogError):
        text = str(error)
        name = "<bytes>" if isinstance(source, (bytes, bytearray, memoryview)) else str(source)
        return text[len(name) + 2 :] if text.startswith(name + ": ") else text
    return f"{type(error).__name__}: {error}"


def _guard(call, source):
    """Run `call()`, giving `(value, None)` or, when it raises, `(None,
    reason)`: one file never ends the job. A panic of the native module
    (`pyo3_runtime.PanicException`, a BaseException) is an error row too."""
    try:
        return call(), None
    except (KeyboardInterrupt, SystemExit, GeneratorExit):
        raise
    except BaseException as error:  # noqa: BLE001 — the file's row says it
        return None, _reason(error, source)


class _Eds:
    """EDS files given to the driver, written once per Python worker into a
    directory of its own (executors need not see the driver's files)."""

    _written: dict = {}

    @classmethod
    def paths(cls, files: Optional[dict]) -> Optional[dict]:
        if files is None:
            return None
        out = {}
        for node, (name, content) in files.items():
            key = hashlib.sha256(content).hexdigest()
            path = cls._written.get(key)
            if path is None or not os.path.exists(path):
                directory = tempfile.mkdtemp(prefix="motionwire-eds-")
                path = os.path.join(directory, name)
                with open(path, "wb") as f:
                    f.write(content)
                cls._written[key] = path
            out[node] = path
        return out


def _error_batch(schema: pa.Schema, path: str, reason: str) -> pa.RecordBatch:
    return pa.RecordBatch.from_pylist([{"file": path, "file_error": reason}], schema=schema)


#: Rows per record batch handed to Spark from a log's frames.
BATCH_ROWS = 1 << 16


def _frames_of(
    path: str, source, *, format, decoded: bool, options: dict, rows: int = BATCH_ROWS
) -> Iterator[pa.RecordBatch]:
    """The batches of `frames` (or `decode`) of one file, of at most `rows`
    rows (the driver's `BATCH_ROWS` when the DataFrame was made)."""
    schema = DECODE if decoded else FRAMES
    if isinstance(source, _TooLarge):
        yield _error_batch(schema, path, source.reason)
        return
    if decoded:
        eds = _Eds.paths(options["eds"])
        table, reason = _guard(
            lambda: _motionwire.decode(source, profiles=options["profiles"], eds=eds, format=format),
            source,
        )
    else:
        table, reason = _guard(lambda: _motionwire.read_log(source, format=format), source)
    if reason is not None:
        yield _error_batch(schema, path, reason)
        return
    for batch in table.to_batches(max_chunksize=rows):
        yield conform(batch, path, schema)


def conform(batch: pa.RecordBatch, path: str, schema: pa.Schema) -> pa.RecordBatch:
    """A batch of `read_log` or `decode` in `schema`: `file` and
    `file_error` first, dictionaries decoded to strings, unsigned integers
    widened to the next signed type, columns the batch lacks null; an
    EtherCAT capture's `packet` is `line`."""
    n = batch.num_rows
    names = batch.schema.names
    columns = []
    for field in schema:
        name = field.name
        if name == "file":
            columns.append(pa.nulls(n, pa.string()).fill_null(path))
            continue
        if name == "line" and "line" not in names:
            name = "packet"
        if name in names:
            columns.append(batch.column(name).cast(field.type))
        else:
            columns.append(pa.nulls(n, field.type))
    return pa.RecordBatch.from_arrays(columns, schema=schema)


def _post_mortem(source, options: dict, findings: bool):
    eds = _Eds.paths(options["eds"])
    return _motionwire.post_mortem(
        source,
        heartbeat_ms=options["heartbeat_ms"],
        profiles=options["profiles"],
        eds=eds,
        format=options["format"],
        findings=findings,
    )


def _summary_of(path: str, source, *, options: dict) -> list:
    """The rows of `summary` of one file."""
    if isinstance(source, _TooLarge):
        return [{"file": path, "file_error": source.reason}]
    result, reason = _guard(lambda: _post_mortem(source, options, findings=False), source)
    if reason is not None:
        return [{"file": path, "file_error": reason}]
    file_record, records, _ = result
    return [file_row(path, file_record)] + [record_row(path, r) for r in records]


def file_row(path: str, record: str) -> dict:
    """A file's `type = "file"` row: frames read (CAN frames, or an
    EtherCAT capture's packets), lines skipped, the format."""
    r = json.loads(record)
    return {
        "file": path,
        "type": "file",
        "frames_total": r["frames"] + r["ethercat_packets"],
        "format": r["format"],
        "skipped": r["skipped_count"],
        "record": record,
    }


def record_row(path: str, record: str) -> dict:
    """A summary record's row: its typed columns (docs/spark.md#summary)
    and the record itself."""
    r = json.loads(record)
    kind = r.get("type")
    row = {"file": path, "type": kind, "iface": r.get("iface"), "record": record}
    if kind == "node":
        first = r.get("first_error") or {}
        heartbeat = r.get("heartbeat") or {}
        cia402 = r.get("cia402") or {}
        row.update(
            node=r.get("node"),
            frames_total=sum((r.get("frames") or {}).values()),
            emcy=r.get("emcy"),
            first_error_code=first.get("code"),
            first_error_line=first.get("line"),
            first_error_ts=first.get("ts"),
            boot_ups=heartbeat.get("boot_up_count"),
            heartbeat_timeouts=heartbeat.get("timeout_count"),
            sdo_aborts=(r.get("sdo") or {}).get("abort_count"),
            cia402_faults=cia402.get("fault_count", 0),
        )
    elif kind == "bus":
        row["frames_total"] = r.get("frames")
    elif kind == "verdict":
        stop = r.get("stop") or {}
        row.update(iface=stop.get("iface"), node=stop.get("node"))
    elif kind == "ethercat":
        row["frames_total"] = r.get("packets")
    return row


def _findings_of(path: str, source, *, options: dict) -> list:
    """The rows of `findings` of one file."""
    if isinstance(source, _TooLarge):
        return [{"file": path, "file_error": source.reason}]
    result, reason = _guard(lambda: _post_mortem(source, options, findings=True), source)
    if reason is not None:
        return [{"file": path, "file_error": reason}]
    _, records, found = result
    rows = [
        {
            "file": path,
            "line": line,
            "ts": ts,
            "iface": iface,
            "node": node,
            "slave": slave,
            "kind": kind,
            "severity": severity,
            "code": code,
            "text": text,
        }
        for line, ts, iface, node, slave, kind, severity, code, text in found
    ]
    for record in records:
        if record.startswith('{"type":"verdict"'):
            rows.extend(verdict_rows(path, json.loads(record), rows))
    return rows


def verdict_rows(path: str, verdict: dict, found: list) -> list:
    """The verdict's stop and first cause as findings rows (`kind`
    `stop`, `first_cause`), each with the text the verdict gives it. The
    time is the verdict's, else that of the finding it is (`found`, the
    file's findings rows: the report timeline's time of a heartbeat
    timeout); the code is that of the EMCY that caused the stop, else the
    finding's."""
    by_key = {(r["iface"], r["node"], r["slave"], r["line"], r["kind"]): r for r in found}
    rows = []
    for kind in ("stop", "first_cause"):
        finding = verdict[kind]
        cause = finding.get("cause") or {}
        same = by_key.get(
            (finding.get("iface"), finding.get("node"), finding.get("slave"), finding["line"], finding["kind"]),
            {},
        )
        ts = finding.get("ts")
        rows.append(
            {
                "file": path,
                "line": finding["line"],
                "ts": ts if ts is not None else same.get("ts"),
                "iface": finding.get("iface"),
                "node": finding.get("node"),
                "slave": finding.get("slave"),
                "kind": kind,
                "severity": finding["severity"],
                "code": cause.get("code", same.get("code")),
                "text": finding["text"],
            }
        )
    return rows
