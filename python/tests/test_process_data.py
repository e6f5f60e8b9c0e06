"""The process data of an EtherCAT capture in Python (docs/python.md#process-data,
docs/python.md#servo): `process_data`'s long table of signals and servo
values and `servo`'s table of servo cycles, held to the program's
`decode --json --servo … --only process_data,servo` records and to what
the models of the generated capture did (tests/data/ethercat/drives.model.jsonl)."""

from __future__ import annotations

import gzip
import json
import subprocess
import warnings

import pyarrow as pa
import pyarrow.compute as pc
import pytest

import motionwire
from conftest import SAMPLE
from test_ethercat import ETHERCAT, program

DRIVES = ETHERCAT / "drives.pcapng"
MODEL = [json.loads(line) for line in (ETHERCAT / "drives.model.jsonl").read_text().splitlines()]
SERVO, DRIVE_A, DRIVE_B = 0x1001, 0x1002, 0x1003

DICTIONARY = pa.dictionary(pa.int32(), pa.string())
NAMES = pa.dictionary(pa.int8(), pa.string())
STRINGS = pa.list_(pa.string())
SIGNAL_SCHEMA = [
    ("packet", pa.uint64(), False),
    ("datagram", pa.uint16(), False),
    ("ts", pa.float64(), True),
    ("time", pa.timestamp("ns", tz="UTC"), True),
    ("iface", DICTIONARY, True),
    ("slave", pa.uint16(), True),
    ("position", pa.uint16(), True),
    ("direction", NAMES, False),
    ("name", DICTIONARY, False),
    ("value", pa.float64(), True),
    ("raw", pa.int64(), True),
    ("confirmed", pa.bool_(), False),
]
SERVO_SCHEMA = [
    ("packet", pa.uint64(), False),
    ("datagram", pa.uint16(), False),
    ("ts", pa.float64(), True),
    ("time", pa.timestamp("ns", tz="UTC"), True),
    ("iface", DICTIONARY, True),
    ("slave", pa.uint16(), True),
    ("speed_setpoint", pa.int32(), False),
    ("control", pa.uint32(), False),
    ("servo_enable", pa.uint8(), False),
    ("position", pa.int64(), True),
    ("encoder", NAMES, True),
    ("status", pa.uint32(), True),
    ("errors", pa.uint32(), True),
    ("faults", STRINGS, True),
    ("e_codes", STRINGS, True),
    ("enable", NAMES, False),
    ("enable_cycles", pa.uint32(), False),
    ("error_clear", NAMES, False),
    ("zero_pulse", NAMES, False),
    ("ready", pa.bool_(), True),
    ("confirmed", pa.bool_(), False),
]

#: The drives' PDOs (tests/data/ethercat/README.md, "drives.pcapng"): the
#: RxPDO 0x1600's entries are outputs, the TxPDO 0x1A00's inputs.
DRIVE_OUTPUTS = {"Controlword", "Target position", "Modes of operation"}
DRIVE_INPUTS = {"Statusword", "Position actual value", "Modes of operation display"}


def fields(schema):
    return [(f.name, f.type, f.nullable) for f in schema]


def decode_json(*args: str) -> list[dict]:
    """The program's records of `decode --json ARGS`."""
    binary = program()
    if binary is None:
        pytest.skip("the program is not built (cargo build --features cli; or MOTIONWIRE_BIN)")
    out = subprocess.run([binary, "decode", "--json", *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return [json.loads(line) for line in out.stdout.splitlines()]


def expected_rows(records: list[dict]) -> list[dict]:
    """process_data's rows as the program's records give them: each
    process_data record's signals, outputs then inputs, then the servo
    record's values (docs/python.md#process-data)."""
    rows = []
    confirmed = {}
    for r in records:
        common = {key: r[key] for key in ("packet", "datagram", "ts", "iface", "slave", "position")}
        key = (r["packet"], r["datagram"], r["slave"])
        if r["kind"] == "process_data":
            confirmed[key] = r["confirmed"]
            for name, value in r["signals"].items():
                output = name in DRIVE_OUTPUTS
                assert output or name in DRIVE_INPUTS, name
                rows.append({**common, "direction": "output" if output else "input",
                             "name": name, "value": value, "confirmed": output or r["confirmed"]})
            continue
        assert r["kind"] == "servo"
        values = [("output", name, r["command"][name])
                  for name in ("speed_setpoint", "control", "servo_enable")]
        feedback = r["feedback"]
        if feedback is not None:
            if feedback["encoder"] == "incremental":
                values += [("input", "position", feedback["incremental_position"]),
                           ("input", "zero_pulse_position", feedback["zero_pulse_position"])]
            else:
                values.append(("input", "position", feedback["position"]))
            values += [("input", name, feedback[name])
                       for name in ("status", "errors", "message_code", "message_value")]
        for direction, name, value in values:
            rows.append({**common, "direction": direction, "name": name, "value": value,
                         "confirmed": direction == "output" or confirmed[key]})
    return rows


def test_schemas():
    table = motionwire.process_data(DRIVES, servo=SERVO)
    assert fields(table.schema) == SIGNAL_SCHEMA
    servo = motionwire.servo(DRIVES)
    assert fields(servo.schema) == SERVO_SCHEMA
    for t in (table, servo):
        metadata = t.schema.metadata
        assert metadata[b"motionwire.format"] == b"pcapng"
        assert metadata[b"motionwire.skipped_count"] == b"0"
        counts = json.loads(metadata[b"motionwire.ethercat"])
        assert counts["packets"] == 2215 and counts["lost"] == 1


def test_rows_are_the_programs_records():
    """One row per signal and servo value of the program's process_data
    and servo records, in their order, with their values."""
    records = decode_json("--servo", "0x1001", "--only", "process_data,servo", str(DRIVES))
    expected = expected_rows(records)
    rows = motionwire.process_data(DRIVES, servo=SERVO).to_pylist()
    assert len(rows) == len(expected)
    assert len(rows) > 20000
    for row, want in zip(rows, expected):
        # ts: a float keeps about a microsecond of a Unix time; time is
        # the same instant to the nanosecond (docs/python.md#time).
        ts = want.pop("ts")
        assert abs(row.pop("ts") - ts) < 1e-6, want
        assert abs(row.pop("time").timestamp() - ts) < 1e-6, want
        raw = row.pop("raw")
        assert row == want, want
        value = want["value"]
        if isinstance(value, int):
            assert raw == value, want
        else:
            # message_value: a float, no raw.
            assert raw is None and want["name"] == "message_value", want


def test_servo_rows_are_the_programs_servo_records():
    records = decode_json("--servo", "0x1001", "--only", "process_data,servo", str(DRIVES))
    confirmed = {(r["packet"], r["slave"]): r["confirmed"]
                 for r in records if r["kind"] == "process_data"}
    servos = [r for r in records if r["kind"] == "servo"]
    rows = motionwire.servo(DRIVES, servo=SERVO).to_pylist()
    assert len(rows) == len(servos) == 999
    for row, r in zip(rows, servos):
        feedback = r["feedback"] or {}
        faults = feedback.get("faults")
        want = {
            "packet": r["packet"], "datagram": r["datagram"], "iface": r["iface"],
            "slave": r["slave"],
            "speed_setpoint": r["command"]["speed_setpoint"],
            "control": r["command"]["control"],
            "servo_enable": r["command"]["servo_enable"],
            "position": feedback.get("position"),
            "encoder": feedback.get("encoder"),
            "status": feedback.get("status"),
            "errors": feedback.get("errors"),
            "faults": None if faults is None else [f["name"] for f in faults],
            "e_codes": None if faults is None else [f["e_code"] for f in faults],
            "enable": r["enable"], "enable_cycles": r["enable_cycles"],
            "error_clear": r["error_clear"], "zero_pulse": r["zero_pulse"],
            "ready": r["ready"],
            "confirmed": confirmed[(r["packet"], r["slave"])],
        }
        assert abs(row.pop("ts") - r["ts"]) < 1e-6
        assert abs(row.pop("time").timestamp() - r["ts"]) < 1e-6
        assert row == want, r


def test_auto_and_modes_are_the_programs():
    """servo="auto" finds the servo by its 10 and 40 bytes, as --servo
    auto; "0x1001:1" reads ServoRDY with Servo_Ready_Mode 1, as the
    program does."""
    named = motionwire.servo(DRIVES, servo=SERVO)
    assert motionwire.servo(DRIVES).equals(named)
    assert motionwire.servo(DRIVES, servo="auto").equals(named)
    assert motionwire.servo(DRIVES, servo=["0x1001"]).equals(named)
    assert motionwire.servo(DRIVES, servo="4097").equals(named)
    mode1 = motionwire.servo(DRIVES, servo="0x1001:1")
    records = decode_json("--servo", "0x1001:1", "--only", "servo", str(DRIVES))
    assert mode1.column("ready").to_pylist() == [r["ready"] for r in records]
    assert mode1.column("ready").to_pylist() != named.column("ready").to_pylist()
    # Without servo=, the servo's values have no rows; the drives' do.
    plain = motionwire.process_data(DRIVES)
    assert set(plain.column("slave").to_pylist()) == {DRIVE_A, DRIVE_B}
    with_servo = motionwire.process_data(DRIVES, servo="auto")
    # The same rows; the name dictionary holds the servo's names too.
    assert with_servo.filter(pc.field("slave") != SERVO).to_pylist() == plain.to_pylist()
    assert motionwire.servo(DRIVES, servo=None).num_rows == 0


def test_statuswords_are_the_models_cia402_states():
    """Each drive's Statusword rows change exactly at the packets where the
    model's CiA 402 state changed, to the model's statusword, confirmed."""
    table = motionwire.process_data(DRIVES)
    for slave in (DRIVE_A, DRIVE_B):
        words = table.filter((pc.field("slave") == slave) & (pc.field("name") == "Statusword"))
        assert set(words.column("direction").to_pylist()) == {"input"}
        changes = []
        last = None
        for row in words.to_pylist():
            if row["raw"] != last:
                changes.append((row["packet"], row["raw"], row["confirmed"]))
                last = row["raw"]
        model = [(m["packet"], m["statusword"], True) for m in MODEL
                 if m["kind"] == "cia402_state" and m["slave"] == slave]
        assert changes == model
        assert len(model) == (10 if slave == DRIVE_A else 4)


def test_servo_phases_and_faults_are_the_models():
    """The servo table's enable, error-clear and zero-pulse phases change
    at the model's packets to the model's phases; the faults it set and
    cleared, with their E-codes, and ServoRDY, too."""
    rows = motionwire.servo(DRIVES).to_pylist()

    def changes(column):
        found, last = [], "idle" if column != "enable" else None
        for row in rows:
            if row[column] != last:
                found.append((row["packet"], row[column]))
                last = row[column]
        return found

    for column, kind in (("enable", "servo_enable"), ("error_clear", "error_clear"),
                         ("zero_pulse", "zero_pulse")):
        model = [(m["packet"], m["to"]) for m in MODEL if m["kind"] == kind]
        assert changes(column) == model, column
        assert len(model) >= 3
    set_, cleared, ready = [], [], []
    before, was_ready = {}, None
    for row in rows:
        if row["faults"] is None:
            continue
        now = dict(zip(row["faults"], row["e_codes"]))
        now.pop("ServoErrors", None)  # the summary bit: the model names the faults
        set_ += [(row["packet"], f, now[f]) for f in now if f not in before]
        cleared += [(row["packet"], f, before[f]) for f in before if f not in now]
        before = now
        if row["ready"] != was_ready:
            ready.append((row["packet"], row["ready"]))
            was_ready = row["ready"]
    assert set_ == [(m["packet"], m["fault"], m["e_code"]) for m in MODEL if m["kind"] == "sew_set"]
    assert cleared == [(m["packet"], m["fault"], m["e_code"])
                       for m in MODEL if m["kind"] == "sew_cleared"]
    assert ready == [(m["packet"], m["value"]) for m in MODEL if m["kind"] == "servo_rdy"]
    # The cycle whose working counter is short: no feedback, unconfirmed.
    short = next(m for m in MODEL if m["kind"] == "short_wkc")
    row = next(r for r in rows if r["packet"] == short["packet"])
    assert row["confirmed"] is False
    assert row["position"] is row["faults"] is row["ready"] is None
    # ActPos at the last cycle, incremental: the position's low 32 bits.
    last = next(m for m in MODEL if m["kind"] == "act_pos")
    row = next(r for r in rows if r["packet"] == last["packet"])
    assert row["encoder"] == "incremental"
    assert row["position"] & 0xFFFF_FFFF == last["value"]


def test_unconfirmed_inputs_say_so():
    """The cycle with a short working counter: the drives' inputs are
    rows, unconfirmed; their outputs confirmed; the servo's feedback has
    no rows (the library reads none from unconfirmed inputs)."""
    short = next(m for m in MODEL if m["kind"] == "short_wkc")
    table = motionwire.process_data(DRIVES, servo=SERVO)
    rows = table.filter(pc.field("packet") == short["packet"]).to_pylist()
    drives = [r for r in rows if r["slave"] != SERVO]
    assert {r["name"] for r in drives} == DRIVE_OUTPUTS | DRIVE_INPUTS
    assert all(r["confirmed"] == (r["direction"] == "output") for r in drives)
    servo = [r["name"] for r in rows if r["slave"] == SERVO]
    assert servo == ["speed_setpoint", "control", "servo_enable"]


def test_pandas_pivot():
    """The wide table of docs/python.md#wide: one row per packet and
    slave, a column per signal name."""
    table = motionwire.process_data(DRIVES, servo=SERVO)
    df = table.to_pandas()
    wide = df.pivot_table(index=["packet", "slave"], columns="name", values="value",
                          observed=True)
    assert len(wide) == len(df[["packet", "slave"]].drop_duplicates()) == 3 * 999
    assert wide.loc[(214, DRIVE_A), "Statusword"] == 576
    assert wide.loc[(216, DRIVE_B), "Statusword"] == 545
    assert wide.loc[(214, SERVO), "control"] == 1029
    assert wide.loc[(214, SERVO), "status"] == 102
    # A slave has the columns of its own signals; the others' are NaN.
    assert wide.loc[(214, SERVO)].isna()["Statusword"]
    assert set(wide.columns) == set(table.column("name").unique().to_pylist())


def test_terminals_without_coe_are_read_by_their_sii():
    """replay-dc.pcapng: output-only terminals without CoE (EL2828,
    EL2889) whose PDOs the capture's SII reads give
    (docs/ethercat.md#sii-pdos): one BOOLEAN output per bit, 257 cycles of
    8 + 16 outputs; the same values as the program's records; no servo."""
    path = ETHERCAT / "replay-dc.pcapng"
    table = motionwire.process_data(path)
    assert fields(table.schema) == SIGNAL_SCHEMA
    assert json.loads(table.schema.metadata[b"motionwire.ethercat"])["packets"] == 3604
    assert table.num_rows == 257 * (8 + 16)
    assert set(table.column("direction").to_pylist()) == {"output"}
    el2889 = table.filter(pc.equal(table["slave"], 0x1002))
    assert el2889.column("name").unique().to_pylist() == [
        f"0x{0x7000 + 0x10 * k:04X}:01" for k in range(16)
    ]
    servo = motionwire.servo(path)
    assert servo.num_rows == 0
    assert fields(servo.schema) == SERVO_SCHEMA
    signals: dict = {}
    for row in table.select(["packet", "slave", "name", "value"]).to_pylist():
        signals.setdefault((row["packet"], row["slave"]), {})[row["name"]] = row["value"]
    records = decode_json("--only", "process_data", str(path))
    assert len(records) == 257 * 2
    for r in records:
        want = {name: float(value) for name, value in r["signals"].items()}
        assert signals[(r["packet"], r["slave"])] == want


def test_a_can_log_is_an_empty_table_and_a_warning():
    with pytest.warns(UserWarning, match="3765 CAN frames read: the process data of EtherCAT"):
        table = motionwire.process_data(SAMPLE)
    assert table.num_rows == 0
    # No EtherCAT packet: no time read as Unix time (docs/python.md#time).
    duration = ("time", pa.duration("ns"), True)
    assert fields(table.schema) == [duration if f[0] == "time" else f for f in SIGNAL_SCHEMA]
    assert b"motionwire.ethercat" not in table.schema.metadata
    with pytest.warns(UserWarning, match="CAN frames read"):
        servo = motionwire.servo(SAMPLE)
    assert servo.num_rows == 0
    assert fields(servo.schema) == [duration if f[0] == "time" else f for f in SERVO_SCHEMA]


def test_sources_and_no_warning_for_a_capture():
    data = DRIVES.read_bytes()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        table = motionwire.process_data(DRIVES, servo=SERVO)
        assert motionwire.process_data(data, servo=SERVO).equals(table)
        assert motionwire.process_data(gzip.compress(data), servo=SERVO).equals(table)
        assert motionwire.process_data(str(DRIVES), servo=SERVO, format="pcapng").equals(table)


def test_errors():
    with pytest.raises(FileNotFoundError):
        motionwire.process_data(ETHERCAT / "no-such.pcapng")
    with pytest.raises(FileNotFoundError):
        motionwire.servo(ETHERCAT / "no-such.pcapng")
    with pytest.raises(motionwire.LogError, match="unrecognised log format"):
        motionwire.process_data(b"\x00\x01 not a log")
    with pytest.raises(motionwire.LogError, match="unrecognised log format"):
        motionwire.servo(b"\x00\x01 not a log")
    with pytest.raises(ValueError, match="is not a log format"):
        motionwire.process_data(DRIVES, format="pcapx")
    with pytest.raises(ValueError, match=r'"2" is not a Servo_Ready_Mode \(0 or 1\)'):
        motionwire.servo(DRIVES, servo="0x1001:2")
    with pytest.raises(ValueError, match=r'"70000" is not a station address'):
        motionwire.process_data(DRIVES, servo=70000)
    with pytest.raises(ValueError, match=r'"drive" is not a station address'):
        motionwire.servo(DRIVES, servo=["auto", "drive"])
    for wrong in (1.5, True, {0x1001: 1}):
        with pytest.raises(TypeError, match="servo must be"):
            motionwire.servo(DRIVES, servo=wrong)


@pytest.mark.parametrize("cut", [24, 1000, 50000, 200000])
def test_truncated_captures_never_end_the_interpreter(cut):
    """A capture cut short anywhere: the rows before the cut, or a
    LogError; both functions, never a crash."""
    data = DRIVES.read_bytes()[:cut]
    for function in (motionwire.process_data, motionwire.servo):
        try:
            table = function(data, servo=SERVO)
        except motionwire.LogError:
            continue
        full = function(DRIVES, servo=SERVO)
        assert table.num_rows <= full.num_rows
        # The rows up to the cut (the dictionaries hold the values seen).
        assert table.to_pylist() == full.slice(0, table.num_rows).to_pylist()


def test_the_docs_examples():
    """docs/python.md#process-data, #wide and #servo, as written there."""
    t = motionwire.process_data(DRIVES, servo=0x1001)
    assert t.filter(pc.field("packet") == 214).select(
        ["slave", "direction", "name", "value"]).to_pylist()[:4] == [
        {"slave": 4097, "direction": "output", "name": "speed_setpoint", "value": 0.0},
        {"slave": 4097, "direction": "output", "name": "control", "value": 1029.0},
        {"slave": 4097, "direction": "output", "name": "servo_enable", "value": 1.0},
        {"slave": 4097, "direction": "input", "name": "position", "value": 0.0},
    ]
    df = t.to_pandas()
    wide = df.pivot_table(index=["packet", "slave"], columns="name", values="value", observed=True)
    assert wide.loc[(214, 4098), ["Controlword", "Statusword"]].to_dict() == {
        "Controlword": 0.0, "Statusword": 576.0}
    s = motionwire.servo(DRIVES)
    assert s.filter(pc.field("packet") == 514).select(
        ["enable", "error_clear", "faults", "e_codes"]).to_pylist() == [
        {"enable": "dropped", "error_clear": "requested",
         "faults": ["ServoErrors", "FollowerErr"], "e_codes": [None, "E09"]}]
    polars = pytest.importorskip("polars")
    w = polars.from_arrow(t).pivot(on="name", index=["packet", "slave"], values="value")
    assert w.shape == (len(wide), 2 + len(wide.columns))
    row = w.filter((polars.col("packet") == 214) & (polars.col("slave") == 4098))
    assert row.select(["Controlword", "Statusword"]).to_dicts() == [
        {"Controlword": 0.0, "Statusword": 576.0}]
