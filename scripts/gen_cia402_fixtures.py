#!/usr/bin/env python3
"""Write tests/fixtures/cia402/python_canopen.json: what python-canopen's CiA 402
profile (canopen/profiles/p402.py) makes of statuswords and which controlwords
it writes to move a drive between states. tests/codecs/cia402.rs checks the
crate's state machine (codec/src/canopen/cia402.rs, docs/canopen.md#cia402)
against it.

Everything is read from python-canopen itself, not retyped:

- "statusword": the state python-canopen's own `BaseNode402.state` property
  reports for each of the 65 536 statuswords. The generator runs the property
  on every word and checks that the answer depends on the low byte only (the
  masks of `State402.SW_MASK` are all within 0x00FF), then writes the 256
  low bytes grouped by state; "UNKNOWN" is python-canopen's answer for a
  pattern that names no state.
- "sw_mask", "transition_table", "operation_modes": State402.SW_MASK,
  State402.TRANSITIONTABLE and OperationMode.CODE2NAME as python-canopen has
  them (controlwords as numbers).
- "walks": for every start state and every state python-canopen's `state`
  setter can be asked for, the controlwords it writes, in order, and the
  state it waits for after each. The drive on the other side is simulated by
  python-canopen's own table: on a controlword it enters the state that
  State402.TRANSITIONTABLE names for (current state, controlword). The node
  talks to the simulated drive through its own controlword setter (an RPDO
  pointer) and statusword property (the TPDO value cache), so python-canopen's
  code runs unchanged.
- "reset_from_fault": the controlwords `BaseNode402.reset_from_fault` writes
  for a drive in FAULT, with the same simulated drive.

Run: pip install canopen; python3 scripts/gen_cia402_fixtures.py
"""
import json
import os

import canopen
from canopen.objectdictionary import ObjectDictionary
from canopen.profiles.p402 import BaseNode402, OperationMode, State402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT_DIR = os.path.join(HERE, "..", "tests", "fixtures", "cia402")
OUT = os.path.join(OUT_DIR, "python_canopen.json")

# The states python-canopen's state setter refuses as targets
# (BaseNode402._next_state raises ValueError for them).
UNREACHABLE_TARGETS = ("NOT READY TO SWITCH ON", "FAULT REACTION ACTIVE", "FAULT")


def statusword_of(state):
    """The statusword python-canopen's SW_MASK gives for a state (its value bits)."""
    _mask, value = State402.SW_MASK[state]
    return value


class SimulatedDrive:
    """A drive that follows python-canopen's TRANSITIONTABLE: on a controlword
    it enters the state the table names for (current state, controlword)."""

    def __init__(self, node, state):
        self.node = node
        self.state = state
        self.written = []
        self.node.tpdo_values[0x6041] = statusword_of(state)

    def write(self, controlword):
        before = self.state
        targets = [to for (frm, to), cw in State402.TRANSITIONTABLE.items()
                   if frm == before and cw == controlword]
        assert len(targets) <= 1, (before, controlword, targets)
        if targets:
            self.state = targets[0]
            self.node.tpdo_values[0x6041] = statusword_of(self.state)
        self.written.append({"from": before, "controlword": controlword, "to": self.state})


class PdoParent:
    """What the controlword setter asks of the RPDO: periodic, so it does not
    transmit (the simulated drive reads the value at once)."""
    is_periodic = True


class ControlwordPointer:
    """Stands in for the RPDO variable the node writes 6040h into."""

    def __init__(self, drive):
        self.drive = drive
        self.pdo_parent = PdoParent()

    @property
    def raw(self):
        raise AssertionError("python-canopen never reads the controlword back")

    @raw.setter
    def raw(self, value):
        self.drive.write(value)


def node_with_drive(state):
    node = BaseNode402(1, ObjectDictionary())
    node.tpdo_values = {}
    drive = SimulatedDrive(node, state)
    node.rpdo_pointers[0x6040] = ControlwordPointer(drive)
    return node, drive


def statusword_table():
    node, _ = node_with_drive("SWITCH ON DISABLED")
    by_low_byte = {}
    for word in range(0x10000):
        node.tpdo_values[0x6041] = word
        state = node.state
        low = word & 0xFF
        if low in by_low_byte:
            assert by_low_byte[low] == state, (hex(word), state, by_low_byte[low])
        else:
            by_low_byte[low] = state
    groups = {}
    for low in range(0x100):
        groups.setdefault(by_low_byte[low], []).append(low)
    return groups


def walks():
    out = []
    for start in State402.SW_MASK:
        for target in State402.SW_MASK:
            if target in UNREACHABLE_TARGETS or target == start:
                continue
            node, drive = node_with_drive(start)
            try:
                node.state = target
                outcome = "reached"
            except (RuntimeError, ValueError) as error:
                outcome = f"{type(error).__name__}: {error}"
            out.append({
                "start": start,
                "target": target,
                "outcome": outcome,
                "steps": drive.written,
            })
    return out


def reset_from_fault():
    node, drive = node_with_drive("FAULT")
    node.TIMEOUT_RESET_FAULT = 0.01  # the loop waits for a reset it has not sent yet
    node.reset_from_fault()
    return {"steps": drive.written, "final": drive.state}


def main():
    fixture = {
        "source": f"python-canopen {canopen.__version__}, canopen/profiles/p402.py",
        "generator": "scripts/gen_cia402_fixtures.py",
        "sw_mask": {state: list(pair) for state, pair in State402.SW_MASK.items()},
        "transition_table": [
            {"from": frm, "to": to, "controlword": cw}
            for (frm, to), cw in State402.TRANSITIONTABLE.items()
        ],
        "statusword": {
            "note": "state of python-canopen's BaseNode402.state for every statusword; "
                    "checked over all 65536 words to depend on the low byte only, "
                    "so listed as low bytes",
            "low_bytes_by_state": statusword_table(),
        },
        "walks": walks(),
        "reset_from_fault": reset_from_fault(),
        "operation_modes": {str(code): name for code, name in OperationMode.CODE2NAME.items()},
        "operation_mode_constants": {
            name: value for name, value in vars(OperationMode).items()
            if name.isupper() and isinstance(value, int)
        },
    }
    os.makedirs(OUT_DIR, exist_ok=True)
    with open(OUT, "w") as f:
        json.dump(fixture, f, indent=1)
        f.write("\n")
    print(f"wrote {OUT} ({os.path.getsize(OUT)} bytes)")


if __name__ == "__main__":
    main()
