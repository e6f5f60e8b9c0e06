"""read_log and Reader against python-can, the oracle of the log readers
(docs/python.md#read-log, docs/python.md#reader): every fixture of a format
python-can reads (candump log, ASC, BLF, TRC, MF4 through asammdf), frame for
frame, where docs/formats.md#where-tools-disagree agrees with python-can; the
rules of conftest.Oracle are that table's rows. pcap/pcapng and candump's
screen output are formats python-can does not read (the Rust tests compare
them with tshark and can-utils)."""

from __future__ import annotations

import warnings

import pytest

import motionwire
from conftest import FIXTURES, Oracle, compare, frame_of_message, frame_of_row, python_can_files

can = pytest.importorskip("can")

FILES = python_can_files()

#: TRC 1.2: python-can reads the bus column as the identifier and fails
#: (docs/formats.md#where-tools-disagree: "version 1.2 … read as 1.0").
PYTHON_CAN_FAILS = {FIXTURES / "trc" / "handmade_v1_2.trc"}


def python_can(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with can.LogReader(str(path)) as reader:
            return [frame_of_message(m) for m in reader]


def ids(path):
    return str(path.relative_to(FIXTURES.parent.parent))


@pytest.mark.parametrize("path", FILES, ids=ids)
def test_read_log_reads_what_python_can_reads(path):
    if path in PYTHON_CAN_FAILS:
        with pytest.raises(Exception):
            python_can(path)
        assert motionwire.read_log(path).num_rows > 0
        return
    if path.suffix == ".mf4":
        pytest.importorskip("asammdf")
    theirs = python_can(path)
    table = motionwire.read_log(path)
    assert table.schema.metadata[b"motionwire.skipped_count"] == b"0"
    ours = [frame_of_row(row) for row in table.to_pylist()]
    problems = compare(path, ours, theirs)
    assert not problems, "\n".join(problems)
    assert len(theirs) > 0


@pytest.mark.parametrize("path", FILES, ids=ids)
def test_reader_yields_what_can_logreader_yields(path):
    if path in PYTHON_CAN_FAILS:
        pytest.skip("python-can cannot read TRC 1.2")
    if path.suffix == ".mf4":
        pytest.importorskip("asammdf")
    theirs = python_can(path)
    with motionwire.Reader(path) as reader:
        messages = list(reader)
    assert all(isinstance(m, can.Message) for m in messages)
    ours = [frame_of_message(m) for m in messages]
    # The rows of read_log and the messages of Reader are the same frames
    # (a frame without a time: python-can's default 0.0).
    rows = [frame_of_row(row) for row in motionwire.read_log(path).to_pylist()]
    assert [{**r, "ts": r["ts"] or 0.0} for r in rows] == [{**m, "rx": None} for m in ours]
    problems = compare(path, ours, theirs)
    assert not problems, "\n".join(problems)


def test_reader_messages_equal_python_cans_on_the_sample():
    """On a candump log the messages are python-can's, attribute for attribute
    (can.Message.equals, which compares channel and direction too)."""
    path = FIXTURES.parent.parent / "samples" / "machine.log"
    with can.LogReader(str(path)) as theirs, motionwire.Reader(str(path)) as ours:
        pairs = list(zip(theirs, ours))
    assert len(pairs) == motionwire.read_log(path).num_rows
    for theirs_msg, ours_msg in pairs:
        assert ours_msg.equals(theirs_msg, timestamp_delta=1e-6), (theirs_msg, ours_msg)


def test_reader_is_a_drop_in_for_can_logreader():
    """What a python-can script does with can.LogReader works unchanged."""
    path = FIXTURES / "blf" / "python_can.blf"
    reader = motionwire.Reader(path)
    assert iter(reader) is reader
    first = next(reader)
    assert first.arbitration_id == 0x081 and first.channel == 1
    rest = [msg for msg in reader]
    assert len(rest) == 38
    reader.stop()
    assert list(reader) == []
    with motionwire.Reader(path) as again:
        assert sum(1 for _ in again) == 39


def test_oracle_rules_are_the_documented_ones():
    """Each rule of the oracle is a row of docs/formats.md#where-tools-disagree."""
    doc = (FIXTURES.parent.parent / "docs" / "formats.md").read_text()
    for row in (
        "python-can's error frame `20000080#0004…`",
        "a `CANFD` line without EDL, of at most 8 bytes",
        "`TxRq` lines",
        "`timestamps relative`",
        "| ASC, BLF | channels | python-can: from 0",
        "| TRC | `ER` rows, status rows | python-can: skipped",
        "| TRC | no bus column | python-can: channel 1",
        "| TRC | `FE`, `BI` |",
        "| TRC | version 1.2 |",
        "| MF4 | `CAN_ErrorFrame` |",
        "| BLF | `CAN_ERROR_EXT` |",
    ):
        assert row in doc, row
    assert Oracle(FIXTURES / "asc" / "handmade_dec_relative.asc").python_can_only() == 1
