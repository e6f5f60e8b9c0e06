"""`findings` (docs/python.md#findings): what went wrong, one row per
finding, the list of the report's "What went wrong" (docs/report.md#page)."""

from __future__ import annotations

import html
import os
import re
import subprocess
from pathlib import Path

import pyarrow as pa
import pytest

import motionwire
from conftest import ROOT, SAMPLE

FINDINGS_SCHEMA = [
    ("line", pa.uint64(), False),
    ("ts", pa.float64(), True),
    ("iface", pa.dictionary(pa.int32(), pa.string()), True),
    ("node", pa.uint8(), True),
    ("slave", pa.uint16(), True),
    ("kind", pa.dictionary(pa.int8(), pa.string()), False),
    ("severity", pa.dictionary(pa.int8(), pa.string()), False),
    ("text", pa.string(), False),
]

SAMPLE_ARGS = dict(heartbeat_ms=300, profiles={3: "akd", 5: "baumer"})

# The sample's findings, the ones `motionwire report --profile
# 3=akd,5=baumer --heartbeat-ms 300 samples/machine.log` lists in "What
# went wrong", kind by kind, each kind in time order: (line, iface, node,
# kind, the item's text without its time).
REPORT = [
    # The Baumer encoder's battery EMCY is a warning (docs/summary.md#severity);
    # its first error is the first EMCY with its error register set.
    (393, "can0", 5, "first_warning", "can0 node 5 first warning: EMCY 0xFF00 Device specific (source: Battery monitoring warning, a warning) at line 393"),
    (613, "can0", 3, "first_error", "can0 node 3 first error: EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 1 at line 613"),
    (620, "can0", 3, "cia402_fault", "can0 node 3 went operation_enabled → fault at line 620, 17.1 ms after EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 1 (line 613)"),
    (972, "can0", 5, "first_error", "can0 node 5 first error: EMCY 0x8120 CAN in error passive mode (source: CAN controller bus passive, an error) at line 972"),
    (1291, "can0", 3, "cia402_fault", "can0 node 3 went operation_enabled → fault at line 1291, 15.0 ms after EMCY 0x4310 Excess drive temperature on axis 1 (line 1284)"),
    (2415, "can0", 10, "first_error", "can0 node 10 first error: EMCY 0x8130 Life guard error or heartbeat error at line 2415"),
    (3239, "can0", 3, "cia402_fault", "can0 node 3 went operation_enabled → fault at line 3239, 16.1 ms after EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 2 (line 3231)"),
    (2681, "can0", 5, "restarts", "can0 node 5 restarted 1 time (boot-ups at lines 15, 2681)"),
    (1559, "can0", 5, "heartbeat_timeout", "can0 node 5 no heartbeat for 3386.93 ms after line 1559"),
    (95, "can0", 3, "sdo_abort", "can0 node 3 line 95: server aborted 1A00h.00 (TPDO mapping parameter): 0x06040043: General parameter incompatibility reason"),
    (3518, "can0", 3, "sdo_abort", "can0 node 3 line 3518: server aborted 1003h.07 (Pre-defined error field): 0x08000024: No data available"),
    (1104, "can0", 10, "toggle_error", "can0 node 10 node-guarding answer with a wrong toggle at line 1104"),
]
SECTIONS = ["first_error first_warning cia402_fault", "restarts", "heartbeat_timeout", "sdo_abort",
            "sdo_broken sdo_timeout", "toggle_error", "bus_off error_passive"]


def section(kind: str) -> int:
    return next(i for i, s in enumerate(SECTIONS) if kind in s.split())


def rows(table: pa.Table) -> list[dict]:
    return table.to_pylist()


def as_report(table: pa.Table) -> list[tuple]:
    """The findings kind by kind (SECTIONS), each kind in time order."""
    listed = [
        (r["line"], r["iface"], r["node"], r["kind"], f"{r['iface']} node {r['node']} {r['text']}")
        for r in rows(table)
    ]
    return sorted(listed, key=lambda r: section(r[3]))


def test_schema():
    table = motionwire.findings(SAMPLE, **SAMPLE_ARGS)
    assert [(f.name, f.type, f.nullable) for f in table.schema] == FINDINGS_SCHEMA


def test_the_samples_findings_are_the_reports():
    table = motionwire.findings(SAMPLE, **SAMPLE_ARGS)
    assert as_report(table) == REPORT
    ts = table.column("ts").to_pylist()
    assert all(t is not None for t in ts)
    assert ts == sorted(ts), "in time order"


def program() -> Path | None:
    """The program, where a cargo build left it: MOTIONWIRE_BIN, else the
    newest of the target directory's release and debug builds (an older
    release build beside a fresh debug one is stale)."""
    if os.environ.get("MOTIONWIRE_BIN"):
        return Path(os.environ["MOTIONWIRE_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    built = [target / profile / "motionwire" for profile in ("release", "debug")]
    built = [exe for exe in built if exe.is_file()]
    return max(built, key=lambda exe: exe.stat().st_mtime) if built else None


def test_the_page_lists_the_same(tmp_path):
    exe = program()
    if exe is None:
        pytest.skip("no motionwire program built (cargo build --features cli)")
    out = tmp_path / "sample.html"
    subprocess.run(
        [exe, "report", "--profile", "3=akd,5=baumer", "--heartbeat-ms", "300", SAMPLE, "-o", out],
        check=True,
        capture_output=True,
    )
    page = out.read_text()
    wrong = page[page.index('<section id="wrong">'):]
    wrong = wrong[: wrong.index("</section>")]
    items = [
        (int(m[1]), m[2], int(m[3]) if m[3] else None,
         re.sub(r" \(\+[0-9.]+ s(, [0-9-]+ [0-9:.]+ UTC)?\)$", "", html.unescape(re.sub("<[^>]+>", "", m[4]))))
        for m in re.finditer(
            r'<li data-line="(\d+)" data-iface="([^"]*)"(?: data-node="(\d+)")?>(.*?)</li>', wrong
        )
    ]
    table = motionwire.findings(SAMPLE, **SAMPLE_ARGS)
    # The page groups them by device and kind (docs/report.md#page): the
    # same findings, in its own order.
    assert sorted(items) == sorted(
        (line, iface, node, text) for line, iface, node, _, text in as_report(table)
    )


def test_bytes_and_a_log_without_findings():
    log = b"(1700000000.000000) can0 703#05\n(1700000000.100000) can0 703#05\n"
    table = motionwire.findings(log)
    assert table.num_rows == 0
    assert [f.name for f in table.schema] == [name for name, _, _ in FINDINGS_SCHEMA]


def test_without_timestamps_ts_is_null_and_lines_order():
    log = b"  can0  703   [1]  00\n  can0  083   [8]  10 81 11 00 00 00 00 00\n  can0  703   [1]  00\n"
    found = rows(motionwire.findings(log))
    assert [(r["line"], r["kind"]) for r in found] == [(2, "first_error"), (3, "restarts")]
    assert [r["ts"] for r in found] == [None, None]
    assert found[1]["text"] == "restarted 1 time (boot-ups at lines 1, 3)"


def test_omitted_entries_are_one_row():
    lines = []
    t = 0
    for _ in range(25):
        t += 1000
        lines.append(f"(1700000000.{t:06}) can0 605#4000100000000000")
        t += 1000
        lines.append(f"(1700000000.{t:06}) can0 585#8000100000000206")
    found = rows(motionwire.findings(("\n".join(lines) + "\n").encode()))
    assert [r["kind"] for r in found] == ["sdo_abort"] * 21
    omitted = [r for r in found if r["text"].startswith("…")]
    assert len(omitted) == 1
    assert omitted[0]["line"] == 20
    assert omitted[0]["text"].startswith("… and 5 more (SDO abort) after line 20")


def test_bad_arguments():
    with pytest.raises(ValueError):
        motionwire.findings(SAMPLE, profiles={3: "nope"})
    with pytest.raises(TypeError):
        motionwire.findings(SAMPLE, 300)


def test_severities():
    """docs/summary.md#severity: the Baumer encoder's battery EMCY is a
    warning, the drive's faults are faults."""
    table = motionwire.findings(SAMPLE, **SAMPLE_ARGS)
    found = {(r["line"], r["kind"]): r["severity"] for r in rows(table)}
    assert found[(393, "first_warning")] == "warning"
    assert found[(972, "first_error")] == "error"
    assert found[(3239, "cia402_fault")] == "fault"
    assert found[(1559, "heartbeat_timeout")] == "error"
    assert found[(95, "sdo_abort")] == "notice"
    assert found[(1104, "toggle_error")] == "warning"


def test_the_docs_example():
    """docs/python.md#findings, as written there."""
    t = motionwire.findings(SAMPLE, **SAMPLE_ARGS)
    assert t.column("kind").to_pylist()[:3] == ["sdo_abort", "first_warning", "first_error"]
    assert t.column("text")[2].as_py() == "first error: EMCY 0x7305 Incremental sensor 1 fault on axis 1, feedback 1 at line 613"
