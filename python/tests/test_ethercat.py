"""EtherCAT captures in Python (docs/python.md#ethercat,
docs/ethercat.md#python): one row per datagram with the keys of the
program's `ecat_datagram` record as columns, held to the program's
`decode --json` and to tshark's dissection (tests/data/ethercat/*.tshark.tsv)
on every capture of tests/data/ethercat."""

from __future__ import annotations

import csv
import gzip
import json
import os
import struct
import subprocess
import typing
import warnings
from pathlib import Path

import pyarrow as pa
import pytest

import motionwire
from conftest import FIXTURES, ROOT, golden_stdout

ETHERCAT = ROOT / "tests" / "data" / "ethercat"
CAPTURES = sorted(ETHERCAT.glob("*.pcapng"))
#: Captures of a master whose own MAC has bit 0x02 set: its sent copies
#: carry the bit too, and order tells them apart (docs/ethercat.md#direction).
OWN_BIT_MASTERS = {"synthetic_local_mac"}

DICTIONARY = pa.dictionary(pa.int32(), pa.string())
NAMES = pa.dictionary(pa.int8(), pa.string())
READ_LOG_SCHEMA = [
    ("packet", pa.uint64(), False),
    ("datagram", pa.uint16(), False),
    ("ts", pa.float64(), True),
    ("time", pa.timestamp("ns", tz="UTC"), True),
    ("iface", DICTIONARY, True),
    ("kind", NAMES, False),
    ("cmd", NAMES, False),
    ("index", pa.uint8(), False),
    ("adp", pa.uint16(), True),
    ("ado", pa.uint16(), True),
    ("logical", pa.uint32(), True),
    ("length", pa.uint16(), False),
    ("irq", pa.uint16(), False),
    ("wkc", pa.uint16(), False),
    ("returned", pa.bool_(), False),
    ("data", pa.binary(), False),
]
DECODE_SCHEMA = READ_LOG_SCHEMA + [("record", pa.string(), False)]

#: ETG.1000.4's command names by command byte, as tshark's `ecat.cmd`
#: numbers them.
COMMANDS = [
    "NOP", "APRD", "APWR", "APRW", "FPRD", "FPWR", "FPRW", "BRD", "BWR", "BRW",
    "LRD", "LWR", "LRW", "ARMW", "FRMW",
]


def fields(schema):
    return [(f.name, f.type, f.nullable) for f in schema]


def capture_id(path: Path) -> str:
    return path.stem


def test_every_capture_is_here():
    assert [p.stem for p in CAPTURES] == [
        "drives",
        "replay-dc",
        "replay-ek1100-el2828-el2889",
        "replay-ek1914-el3004-configure",
        "replay-ek1914-segmented-upload",
        "soem-akd-sdo",
        "soem-single-lan9252",
        "synthetic_akd_fault",
        "synthetic_local_mac",
        "synthetic_registers",
        "twincat-akd-startup",
    ]


@pytest.mark.parametrize("path", CAPTURES, ids=capture_id)
def test_schema(path):
    table = motionwire.read_log(path)
    assert fields(table.schema) == READ_LOG_SCHEMA
    assert table.schema.metadata[b"motionwire.format"] == b"pcapng"
    decoded = motionwire.decode(path)
    assert fields(decoded.schema) == DECODE_SCHEMA
    # decode is read_log and the record.
    assert decoded.drop_columns(["record"]).equals(table)
    assert table.column("kind").unique().to_pylist() == ["ecat_datagram"]


def test_sources():
    """A capture as bytes, gzip-compressed, or read as pcapng by name: the
    same table (docs/python.md#sources)."""
    path = ETHERCAT / "soem-single-lan9252.pcapng"
    table = motionwire.read_log(path)
    data = path.read_bytes()
    assert motionwire.read_log(data).equals(table)
    assert motionwire.read_log(gzip.compress(data)).equals(table)
    assert motionwire.read_log(str(path), format="pcapng").equals(table)


def test_first_rows_of_twincat():
    """docs/ethercat.md's example record, as a row: the APWR of station
    address 0x03E9 as it came back, ADP counted on to 1."""
    table = motionwire.read_log(ETHERCAT / "twincat-akd-startup.pcapng")
    assert table.num_rows == 511
    rows = table.to_pylist()
    row = next(r for r in rows if r["packet"] == 305)
    # time: the capture's nanoseconds, exact (docs/python.md#time).
    at = rows.index(row)
    assert table.column("time").cast(pa.int64())[at].as_py() == 1655654779674105000
    del row["time"]
    assert row == {
        "packet": 305,
        "datagram": 1,
        "ts": 1655654779.674105,
        "iface": "\\Device\\NPF_{0D792EC2-0E89-4AB6-BE39-3F41EC42AEA3}",
        "kind": "ecat_datagram",
        "cmd": "APWR",
        "index": 160,
        "adp": 1,
        "ado": 16,
        "logical": None,
        "length": 2,
        "irq": 0,
        "wkc": 1,
        "returned": True,
        "data": b"\xe9\x03",
    }
    # Packets 18, 21, 26 come back from another NIC and were never seen
    # sent: returned all the same (docs/ethercat.md#direction).
    assert [r["returned"] for r in rows if r["packet"] in (18, 21, 26)] == [True] * 3


def record_columns(record: dict) -> dict:
    """A row as the JSON record gives it: the data from hex, the address
    keys the record leaves out null."""
    row = {key: record.get(key) for key, _, _ in READ_LOG_SCHEMA if key != "time"}
    row["data"] = bytes.fromhex(record["data"])
    return row


def assert_rows_are_records(table, records):
    assert table.num_rows == len(records)
    for row, record in zip(table.to_pylist(), records):
        expected = record_columns(record)
        # time: the record's ts to the nanosecond (test_time.py holds
        # every digit to it).
        time = row.pop("time")
        assert time is None or abs(time.timestamp() - record["ts"]) < 1e-6, record
        # ts: a float keeps about a microsecond of a Unix time; the record
        # keeps the capture's digits (docs/python.md#columns).
        assert abs(row.pop("ts") - expected.pop("ts")) < 1e-6, record
        assert row == expected, record
        assert list(record) == [key for key, _, _ in READ_LOG_SCHEMA if key in record]


@pytest.mark.parametrize("path", CAPTURES, ids=capture_id)
def test_columns_are_the_records_keys(path):
    """Every column holds its key of the record decode --json writes for
    the datagram, in the record's order."""
    table = motionwire.decode(path)
    records = [json.loads(r) for r in table.column("record").to_pylist()]
    assert_rows_are_records(table.drop_columns(["record"]), records)


def program() -> str | None:
    """The program built by cargo (CI builds it for the Rust tests before
    the Python ones): MOTIONWIRE_BIN, else the newest of the target
    directory's release and debug builds."""
    if os.environ.get("MOTIONWIRE_BIN"):
        return os.environ["MOTIONWIRE_BIN"]
    targets = [Path(os.environ["CARGO_TARGET_DIR"])] if os.environ.get("CARGO_TARGET_DIR") else []
    targets.append(ROOT / "target")
    built = [t / profile / "motionwire" for t in targets for profile in ("release", "debug")]
    built = [path for path in built if path.is_file()]
    return str(max(built, key=lambda path: path.stat().st_mtime)) if built else None


@pytest.mark.parametrize("path", CAPTURES, ids=capture_id)
def test_rows_are_the_programs_decode_json(path):
    """The rows against the program itself: `motionwire decode --json` of
    every capture, key by key."""
    binary = program()
    if binary is None:
        pytest.skip("the program is not built (cargo build --features cli; or MOTIONWIRE_BIN)")
    out = subprocess.run([binary, "decode", "--json", str(path)], capture_output=True, text=True)
    assert out.returncode in (0, 1), out.stderr
    # The datagrams' records: the records of what they tell of the slaves
    # (docs/ethercat.md#meanings) are not rows of a table of datagrams.
    lines = [line for line in out.stdout.splitlines() if '"kind":"ecat_datagram"' in line]
    table = motionwire.decode(path)
    assert table.column("record").to_pylist() == lines
    assert_rows_are_records(table.drop_columns(["record"]), [json.loads(line) for line in lines])


def tshark_rows(path: Path) -> list[dict]:
    with open(path.with_suffix(".tshark.tsv"), newline="") as f:
        return list(csv.DictReader(f, delimiter="\t"))


def hex_or_none(cell: str) -> int | None:
    return int(cell, 16) if cell else None


@pytest.mark.parametrize("path", CAPTURES, ids=capture_id)
def test_rows_are_tsharks_dissection(path):
    """tshark's ecat dissector as the oracle (scripts/ecat_oracle.py):
    frame, datagram, command, index, ADP/ADO or logical address, length,
    working counter, IRQ and data of every datagram; returned is the
    source MAC's bit 0x02 (docs/ethercat.md#direction: every frame with
    the bit set is a returned copy, paired or not)."""
    expected = tshark_rows(path)
    table = motionwire.read_log(path)
    assert table.num_rows == len(expected)
    for row, tshark in zip(table.to_pylist(), expected):
        where = (tshark["frame"], tshark["dg"])
        assert row["packet"] == int(tshark["frame"]), where
        assert row["datagram"] == int(tshark["dg"]), where
        assert row["cmd"] == COMMANDS[int(tshark["cmd"], 16)], where
        assert row["index"] == int(tshark["idx"], 16), where
        assert row["adp"] == hex_or_none(tshark["adp"]), where
        assert row["ado"] == hex_or_none(tshark["ado"]), where
        assert row["logical"] == hex_or_none(tshark["lad"]), where
        assert row["length"] == int(tshark["len"]), where
        assert row["wkc"] == int(tshark["wkc"]), where
        assert row["irq"] == int(tshark["irq"], 16), where
        assert row["data"].hex() == tshark["data"], where
        if path.stem not in OWN_BIT_MASTERS:
            assert row["returned"] == bool(int(tshark["eth_src"][:2], 16) & 0x02), where


def test_lost_and_unpaired_frames_are_counted():
    """The session's counts (docs/python.md#ethercat): SOEM's BRD of packet
    809 never came back; TwinCAT's three frames from the host's other NIC
    have no sent copy."""
    soem = motionwire.read_log(ETHERCAT / "soem-akd-sdo.pcapng").schema.metadata
    assert json.loads(soem[b"motionwire.ethercat"]) == {
        "packets": 829,
        "sent": 415,
        "returned": 414,
        "returned_unpaired": 0,
        "lost": 1,
        "other_frame_types": 0,
        "damaged": 0,
        "time_reversals": 0,
    }
    assert json.loads(soem[b"motionwire.other"]) == [
        "1 packet of EtherType 0x0806 (ARP) skipped: neither CAN nor EtherCAT"
    ]
    twincat = motionwire.read_log(ETHERCAT / "twincat-akd-startup.pcapng").schema.metadata
    assert json.loads(twincat[b"motionwire.ethercat"]) == {
        "packets": 478,
        "sent": 237,
        "returned": 237,
        "returned_unpaired": 3,
        "lost": 0,
        # A frame of reserved type 7 (tests/data/ethercat/README.md).
        "other_frame_types": 1,
        "damaged": 0,
        "time_reversals": 0,
    }


def test_pandas_dtypes():
    """to_pandas of a capture with logical and addressed datagrams: the
    integers keep their width, the names are categories; adp/ado/logical
    hold nulls and come as float64 with NaN, as pandas makes every
    nullable integer column, or as nullable integers with
    types_mapper=pd.ArrowDtype."""
    pd = pytest.importorskip("pandas")
    table = motionwire.read_log(ETHERCAT / "replay-dc.pcapng")
    frame = table.to_pandas()
    assert {name: str(dtype) for name, dtype in frame.dtypes.items()} == {
        "packet": "uint64",
        "datagram": "uint16",
        "ts": "float64",
        "time": "datetime64[ns, UTC]",
        "iface": "category",
        "kind": "category",
        "cmd": "category",
        "index": "uint8",
        "adp": "float64",
        "ado": "float64",
        "logical": "float64",
        "length": "uint16",
        "irq": "uint16",
        "wkc": "uint16",
        "returned": "bool",
        "data": "object",
    }
    lrw = frame[frame["cmd"] == "LRW"]
    assert len(lrw) == 514 and lrw["adp"].isna().all() and lrw["logical"].notna().all()
    assert frame["logical"].isna().sum() == len(frame) - 514
    assert isinstance(frame["data"].iloc[0], bytes)
    arrow = table.to_pandas(types_mapper=pd.ArrowDtype)
    assert str(arrow["adp"].dtype) == "uint16[pyarrow]"
    assert arrow["logical"].dropna().astype(int).tolist() == frame["logical"].dropna().astype(int).tolist()


# ---------------------------------------------------------------------------
# Captures built here: damaged packets, CAN and EtherCAT together

def datagram(cmd: int, index: int, address: int, data: bytes, wkc: int, more: bool,
             length: int | None = None) -> bytes:
    length_word = (len(data) if length is None else length) | (0x8000 if more else 0)
    return struct.pack("<BBIHH", cmd, index, address, length_word, 0) + data + struct.pack("<H", wkc)


def ethernet(source: bytes, payload: bytes) -> bytes:
    header = struct.pack("<H", len(payload) | 0x1000)
    return b"\xff" * 6 + source + b"\x88\xa4" + header + payload


def pcap(packets: list[bytes]) -> bytes:
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1)
    for n, packet in enumerate(packets):
        out += struct.pack("<IIII", 1_700_000_000, n * 1000, len(packet), len(packet)) + packet
    return out


def test_damaged_packets_are_skipped_rows():
    """A datagram whose length runs past the frame: the datagrams before it
    are rows, the packet is listed as skipped with the program's reason
    (docs/ethercat.md#damaged-packets); so is an EtherCAT header that
    announces more than the packet holds."""
    master = b"\x01\x01\x01\x01\x01\x01"
    whole = datagram(7, 1, 0x0130_0000, b"\x00\x00", 0, more=True)
    cut = datagram(4, 2, 0x0130_1001, b"\x00\x00", 0, more=False, length=40)
    header_past = b"\xff" * 6 + master + b"\x88\xa4" + struct.pack("<H", 0x07FF | 0x1000) + whole
    table = motionwire.read_log(pcap([ethernet(master, whole + cut), header_past]))
    assert fields(table.schema) == READ_LOG_SCHEMA
    assert [(r["packet"], r["datagram"], r["cmd"]) for r in table.to_pylist()] == [(1, 1, "BRD")]
    metadata = table.schema.metadata
    assert metadata[b"motionwire.skipped_count"] == b"2"
    skipped = json.loads(metadata[b"motionwire.skipped"])
    assert [s["line"] for s in skipped] == [1, 2]
    assert skipped[0]["reason"].startswith("datagram 2: EtherCAT datagram: buffer of ")
    assert "EtherCAT" in skipped[1]["reason"]
    assert json.loads(metadata[b"motionwire.ethercat"])["damaged"] == 2


def test_can_and_ethercat_in_one_capture():
    """A capture of CAN and EtherCAT interfaces (here two pcapng sections):
    the table holds the CAN frames and counts the EtherCAT packets
    (docs/ethercat.md#python), whichever comes first."""
    can = (FIXTURES / "pcap" / "can.pcapng").read_bytes()
    ecat = (ETHERCAT / "soem-akd-sdo.pcapng").read_bytes()
    alone = motionwire.read_log(can)
    # The CAN packets are the first 1 or come after the capture's 830.
    for data, before in ((can + ecat, 0), (ecat + can, 830)):
        table = motionwire.read_log(data)
        assert table.schema.names[:4] == ["line", "ts", "time", "iface"]
        assert table.drop_columns(["line"]).equals(alone.drop_columns(["line"]))
        lines = alone.column("line").to_pylist()
        assert table.column("line").to_pylist() == [line + before for line in lines]
        other = json.loads(table.schema.metadata[b"motionwire.other"])
        assert other[0] == (
            "829 EtherCAT packets skipped: the capture holds CAN frames too, and a table "
            "holds CAN frames or EtherCAT datagrams, not both"
        )
        assert json.loads(table.schema.metadata[b"motionwire.ethercat"])["packets"] == 829
        assert motionwire.decode(data).num_rows == alone.num_rows


def test_read_logs_of_captures():
    """read_logs: EtherCAT captures alone give a table of datagrams with
    its file column; with a CAN log among them, the CAN frames, the
    captures' packets counted."""
    paths = [ETHERCAT / "soem-akd-sdo.pcapng", ETHERCAT / "twincat-akd-startup.pcapng"]
    table = motionwire.read_logs(paths)
    assert fields(table.schema) == [("file", DICTIONARY, False)] + READ_LOG_SCHEMA
    assert table.num_rows == 829 + 511
    assert table.slice(0, 829).drop_columns(["file"]).to_pylist() == motionwire.read_log(paths[0]).to_pylist()
    assert json.loads(table.schema.metadata[b"motionwire.ethercat"])["packets"] == 829 + 478
    mixed = motionwire.read_logs([FIXTURES / "pcap" / "can.pcapng", paths[0]])
    assert mixed.schema.names[:3] == ["file", "line", "ts"]
    assert mixed.num_rows == motionwire.read_log(FIXTURES / "pcap" / "can.pcapng").num_rows
    assert json.loads(mixed.schema.metadata[b"motionwire.other"])[0].startswith(
        "829 EtherCAT packets skipped: other logs of the table hold CAN frames"
    )


def test_summary_is_the_programs_and_findings_name_the_slaves():
    """summary gives the capture's verdict, interface, slave and stream
    records (docs/ethercat.md#summary), as `decode --summary --json`;
    findings are the slaves' (docs/ethercat.md#findings)."""
    path = ETHERCAT / "soem-akd-sdo.pcapng"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        records = motionwire.summary(path)
        found = motionwire.findings(path)
    assert [r["type"] for r in records][:3] == ["verdict", "ethercat", "slave"]
    akd = records[2]
    assert (akd["slave"], akd["name"], akd["al_code"]) == (0x1001, "Kollmorgen AKD", 0x001D)
    assert records[0]["stop"]["slave"] == 0x1001
    assert records[0]["stop"]["kind"] == "al_error"
    assert found.column("kind").to_pylist() == ["al_error"]
    assert found.column("slave").to_pylist() == [0x1001]
    assert found.column("node").to_pylist() == [None]
    assert found.column("line").to_pylist() == [records[0]["stop"]["line"]]
    # The drives capture's servo is read with servo=, its faults found.
    drives = ETHERCAT / "drives.pcapng"
    kinds = motionwire.findings(drives, servo=0x1001).column("kind").to_pylist()
    assert kinds.count("servo_fault") == 2
    assert "servo_fault" not in motionwire.findings(drives).column("kind").to_pylist()
    assert motionwire.summary(drives, servo="0x1001")[0]["type"] == "verdict"
    # A CAN log: no such warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        motionwire.summary(FIXTURES / "pcap" / "can.pcapng")


# ---------------------------------------------------------------------------
# ethercat_records: the records of what the datagrams tell
# (docs/python.md#ethercat-records)

RECORD_KINDS = list(typing.get_args(motionwire.RecordKind))
MEANING_KINDS = [
    "station", "al_state", "sii", "dl_status", "error_counters", "mailbox", "coe_sdo", "coe_emcy",
    "alias", "dc", "mailbox_repeat",
]
#: The kinds `decode` writes only when `--only` names them.
QUIET_KINDS = ["dc_distribution", "mailbox_poll"]
RECORDS_SCHEMA = [
    ("packet", pa.uint64(), False),
    ("datagram", pa.uint16(), False),
    ("ts", pa.float64(), True),
    ("time", pa.timestamp("ns", tz="UTC"), True),
    ("iface", DICTIONARY, True),
    ("kind", NAMES, False),
    ("slave", pa.uint16(), True),
    ("position", pa.uint16(), True),
    ("al_register", NAMES, True),
    ("state", NAMES, True),
    ("al_error", pa.bool_(), True),
    ("code", pa.uint16(), True),
    ("code_text", DICTIONARY, True),
    ("word", pa.uint32(), True),
    ("value", pa.uint32(), True),
    ("field", NAMES, True),
    ("direction", NAMES, True),
    ("type", NAMES, True),
    ("service", NAMES, True),
    ("index", pa.uint16(), True),
    ("subindex", pa.uint8(), True),
    ("abort_code", pa.uint32(), True),
    ("abort", DICTIONARY, True),
    ("register", pa.uint8(), True),
    ("description", DICTIONARY, True),
    ("record", pa.string(), False),
]
#: The typed columns and the kinds whose records have each, by the key of
#: the record it holds.
TYPED = {
    "al_register": ({"al_state"}, "register"),
    "state": ({"al_state"}, "state"),
    "al_error": ({"al_state"}, "error"),
    "code": ({"al_state", "coe_emcy"}, "code"),
    "code_text": ({"al_state"}, "code_text"),
    "word": ({"sii"}, "word"),
    "value": ({"sii"}, "value"),
    "field": ({"sii"}, "field"),
    "direction": ({"mailbox", "coe_sdo", "coe_emcy"}, "direction"),
    "type": ({"mailbox", "coe_sdo", "coe_emcy"}, "type"),
    "service": ({"mailbox", "coe_sdo", "coe_emcy"}, "service"),
    "index": ({"coe_sdo"}, "index"),
    "subindex": ({"coe_sdo"}, "subindex"),
    "abort_code": ({"coe_sdo"}, "abort_code"),
    "abort": ({"coe_sdo"}, "abort"),
    "register": ({"coe_emcy"}, "register"),
    "description": ({"coe_emcy"}, "description"),
}


def programs_records(path: Path, *args: str) -> list[str]:
    binary = program()
    if binary is None:
        pytest.skip("the program is not built (cargo build --features cli; or MOTIONWIRE_BIN)")
    out = subprocess.run([binary, "decode", "--json", *args, str(path)], capture_output=True, text=True)
    assert out.returncode in (0, 1), out.stderr
    return out.stdout.splitlines()


@pytest.mark.parametrize("path", CAPTURES, ids=capture_id)
def test_records_are_the_programs_decode_json(path):
    """Every record `motionwire decode --json` writes for the capture, one
    row each in its order: by default the meanings, with every kind named
    all of them (the quiet kinds as `--only` names them)."""
    lines = programs_records(path)
    loud = [kind for kind in RECORD_KINDS if kind not in QUIET_KINDS]
    everything = motionwire.ethercat_records(path, kinds=loud)
    assert everything.column("record").to_pylist() == lines
    quiet = motionwire.ethercat_records(path, kinds=QUIET_KINDS)
    assert quiet.column("record").to_pylist() == programs_records(path, "--only", ",".join(QUIET_KINDS))
    meanings = [line for line in lines if json.loads(line)["kind"] in MEANING_KINDS]
    table = motionwire.ethercat_records(path)
    assert fields(table.schema) == RECORDS_SCHEMA
    assert table.column("record").to_pylist() == meanings
    assert table.schema.metadata[b"motionwire.format"] == b"pcapng"
    assert b"motionwire.ethercat" in table.schema.metadata
    # The datagrams' rows are decode's.
    datagrams = motionwire.ethercat_records(path, kinds="ecat_datagram")
    assert datagrams.column("record").equals(motionwire.decode(path).column("record"))


def test_servo_records_are_the_programs():
    """With servo=, the servo records of `decode --json --servo`; the
    process data's records when named."""
    path = ETHERCAT / "drives.pcapng"
    lines = programs_records(path, "--servo", "0x1001", "--only", "process_data,servo")
    table = motionwire.ethercat_records(path, kinds=["process_data", "servo"], servo=0x1001)
    assert table.column("record").to_pylist() == lines
    kinds = table.column("kind").to_pylist()
    assert kinds.count("servo") > 100
    servo = [json.loads(r) for k, r in zip(kinds, table.column("record").to_pylist()) if k == "servo"]
    assert {r["slave"] for r in servo} == {0x1001}


@pytest.mark.parametrize("path", CAPTURES, ids=capture_id)
def test_record_columns_are_the_records_keys(path):
    """Each column holds its key of the row's record, null where the kind
    has none."""
    table = motionwire.ethercat_records(path, kinds=RECORD_KINDS)
    for row in table.to_pylist():
        record = json.loads(row["record"])
        assert row["packet"] == record["packet"]
        assert row["datagram"] == record["datagram"]
        assert row["kind"] == record["kind"]
        assert row["iface"] == record["iface"]
        assert row["slave"] == record.get("slave"), record
        assert row["position"] == record.get("position"), record
        assert (row["ts"] is None) == (record["ts"] is None)
        for column, (kinds, key) in TYPED.items():
            expected = record.get(key) if record["kind"] in kinds else None
            assert row[column] == expected, (column, record)


def test_what_the_akd_fault_capture_tells():
    """The synthetic AKD's fault: its emergency (docs/ethercat.md's
    example) and AL states; the EK1914's name in an SDO transfer."""
    table = motionwire.ethercat_records(ETHERCAT / "synthetic_akd_fault.pcapng")
    rows = table.to_pylist()
    emcy = next(r for r in rows if r["kind"] == "coe_emcy")
    assert (emcy["packet"], emcy["slave"], emcy["position"]) == (456, 4097, 1)
    assert (emcy["code"], emcy["register"], emcy["description"]) == (
        0x7305, 0x81, "Incremental sensor 1 fault",
    )
    assert (emcy["direction"], emcy["type"], emcy["service"]) == ("read", "coe", "emergency")
    assert json.loads(emcy["record"])["axis"] == 1
    states = {r["state"] for r in rows if r["kind"] == "al_state"}
    assert {"preop", "safeop", "op"} <= states
    # The EK1914's name, read by an upload of 0x1008
    # (docs/ethercat.md#coe-sdo): the transfer's data in the record.
    sdo = motionwire.ethercat_records(ETHERCAT / "replay-ek1914-segmented-upload.pcapng", kinds="coe_sdo")
    name = next(r for r in sdo.to_pylist() if r["packet"] == 964)
    assert (name["slave"], name["index"], name["subindex"], name["service"]) == (
        0x1000, 0x1008, 0, "sdo_response",
    )
    transfer = json.loads(name["record"])["transfer"]
    assert bytes.fromhex(transfer["data"]) == b"EK1914"
    assert transfer["object"] == "Manufacturer device name"
    # DuckDB reads the table as it is.
    duckdb = pytest.importorskip("duckdb")
    records = table  # noqa: F841 (read by DuckDB by its name)
    found = duckdb.sql(
        "select count(*) from records where kind = 'coe_emcy' and description is not null"
    ).fetchall()
    assert found == [(sum(r["kind"] == "coe_emcy" and r["description"] is not None for r in rows),)]


def test_record_kinds_and_can_logs():
    path = ETHERCAT / "soem-akd-sdo.pcapng"
    one = motionwire.ethercat_records(path, kinds="coe_sdo")
    assert set(one.column("kind").to_pylist()) == {"coe_sdo"}
    assert motionwire.ethercat_records(path, kinds=("coe_sdo",)).equals(one)
    with pytest.raises(ValueError, match='"sdo" is not a kind of EtherCAT record; one of ecat_datagram'):
        motionwire.ethercat_records(path, kinds=["sdo"])
    with pytest.raises(TypeError):
        motionwire.ethercat_records(path, kinds=3)
    # A CAN log: no rows, said with a UserWarning; the schema all the same.
    with pytest.warns(UserWarning, match="CAN frames? read: the records of EtherCAT captures"):
        table = motionwire.ethercat_records(FIXTURES / "pcap" / "can.pcapng")
    assert table.num_rows == 0
    assert [f.name for f in table.schema] == [name for name, _, _ in RECORDS_SCHEMA]


def test_record_kind_is_the_librarys_list_of_kinds():
    """`motionwire.RecordKind` is written out for type checkers; it must
    name the library's kinds (`decoder::ethercat::RECORD_KINDS`) in its
    order, as an unknown kind's ValueError lists them."""
    with pytest.raises(ValueError) as error:
        motionwire.ethercat_records(ETHERCAT / "drives.pcapng", kinds="nope")
    listed = str(error.value).split("; one of ", 1)[1].split(", ")
    assert list(typing.get_args(motionwire.RecordKind)) == listed
