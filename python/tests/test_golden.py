"""summary and decode against the program (docs/python.md#summary,
docs/python.md#decode): every `decode --summary --json` and `decode --json`
case of tests/golden/cases.txt — the sample and every fixture, with their
--heartbeat-ms, --profile and --eds — as the program writes it
(tests/golden/*.gz, the snapshots tests/program/golden.rs holds the program
to)."""

from __future__ import annotations

import json
import warnings

import pytest

import motionwire
from conftest import ROOT, decode_options, golden_cases, golden_stdout

SUMMARY_CASES = []
JSON_CASES = []
for name, args in golden_cases():
    if "--json" not in args:
        continue
    options = decode_options(args)
    if options is None:
        continue
    (SUMMARY_CASES if "--summary" in args else JSON_CASES).append((name, options))


def case_id(case):
    name, _options = case
    return name.removesuffix(".gz")


@pytest.mark.parametrize("case", SUMMARY_CASES, ids=case_id)
def test_summary_is_decode_summary_json(case):
    name, (kwargs, path) = case
    expected = [json.loads(line) for line in golden_stdout(name).splitlines()]
    with warnings.catch_warnings():
        # Logs with malformed lines: summary warns, as the program does on
        # standard error.
        warnings.simplefilter("ignore")
        found = motionwire.summary(path, **kwargs)
    assert found == expected


@pytest.mark.parametrize("case", JSON_CASES, ids=case_id)
def test_decode_record_is_decode_json(case):
    name, (kwargs, path) = case
    kwargs.pop("heartbeat_ms", None)
    expected = golden_stdout(name).splitlines()
    if "ethercat" in name:
        # A table of datagrams: the records of what they tell of the slaves
        # (docs/ethercat.md#meanings) are not its rows.
        expected = [line for line in expected if '"kind":"ecat_datagram"' in line]
    table = motionwire.decode(path, **kwargs)
    assert table.column("record").to_pylist() == expected


def test_every_kind_of_case_is_compared():
    assert len(SUMMARY_CASES) >= 40
    assert len(JSON_CASES) >= 40
    assert any("profiles" in kwargs for _, (kwargs, _) in SUMMARY_CASES)
    assert any("eds" in kwargs for _, (kwargs, _) in JSON_CASES)
    files = {path for _, (_, path) in SUMMARY_CASES}
    for suffix in (".log", ".asc", ".trc", ".blf", ".pcap", ".pcapng", ".txt"):
        assert any(f.endswith(suffix) for f in files), suffix


def test_decode_columns_are_the_records_keys():
    """kind, node, code, register, description and state hold what each
    record's keys hold (docs/output.md#json)."""
    table = motionwire.decode(ROOT / "samples" / "machine.log", profiles={3: "akd", 5: "baumer"})
    columns = ("kind", "node", "code", "register", "description", "state")
    rows = table.select(list(columns) + ["record", "line", "ts", "iface", "id", "data"]).to_pylist()
    kinds = set()
    for row in rows:
        record = json.loads(row["record"])
        for key in columns:
            assert row[key] == record.get(key), (key, row["line"])
        assert row["line"] == record["line"] and row["id"] == record["id"]
        assert row["iface"] == record["iface"] and abs(row["ts"] - record["ts"]) < 1e-6
        assert bytes(row["data"]).hex() == record["data"]
        kinds.add(row["kind"])
    assert {"emcy", "heartbeat", "pdo", "sdo", "nmt_command", "sync"} <= kinds
