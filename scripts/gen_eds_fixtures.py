#!/usr/bin/env python3
"""Write the expected results of tests/library/eds.rs with python-canopen as
the oracle.

For each EDS/DCF under tests/fixtures/eds/ (see the README there), imports the
file with ``canopen.import_od`` for a node-ID, builds every PDO the way
python-canopen does (``node.tpdo.read(from_od=True)`` /
``node.rpdo.read(from_od=True)``: ParameterValue when the file has one, else
DefaultValue), and decodes sample payloads with its ``PdoMap``: for each
payload the name (``Variable.name``: "Record.Sub-entry" for sub-entries),
index, sub-index, bit offset, length and decoded value of every mapped
variable. Writes ``<file>.json`` beside the file.

Usage:  python3 scripts/gen_eds_fixtures.py      (pip install canopen)

The payloads are fixed byte patterns (not random), so the JSON is stable:
all zeros, all ones, an ascending count, and a pattern with the top bit of
every byte set, each 64 bytes long and cut to the PDO's length.
"""

import json
import math
import os
import sys

import canopen

FIXTURES = os.path.join(os.path.dirname(__file__), "..", "tests", "fixtures", "eds")

# (file, node-ID): the node the file is read for.
FILES = [
    ("sample.eds", 0x10),
    ("prbt_0_1.dcf", 3),
    ("cia402_slave.eds", 2),
    ("bitfields.eds", 0x21),
]

PATTERNS = {
    "zeros": bytes(64),
    "ones": bytes([0xFF] * 64),
    "count": bytes(range(1, 65)),
    "high": bytes((0x80 | (i * 37)) & 0xFF for i in range(64)),
}


def json_value(value):
    """The decoded value as JSON: bools, ints, finite floats as themselves;
    other floats as strings; bytes as lowercase hex; strings as strings."""
    if isinstance(value, bool) or isinstance(value, int):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else repr(value)
    if isinstance(value, (bytes, bytearray)):
        return {"hex": bytes(value).hex()}
    return value


def pdo_record(direction, number, pdo_map):
    entries = []
    for var in pdo_map.map:
        entries.append(
            {
                "name": var.name,
                "index": var.index,
                "subindex": var.subindex,
                "offset": var.offset,
                "length": var.length,
                "data_type": var.od.data_type,
            }
        )
    samples = []
    byte_len = (pdo_map.length + 7) // 8
    for label, pattern in PATTERNS.items():
        data = pattern[:byte_len]
        pdo_map.data = bytearray(data)
        signals = []
        for var in pdo_map.map:
            try:
                value = json_value(var.raw)
                signals.append({"name": var.name, "value": value})
            except Exception as error:  # python-canopen's own failure, kept as evidence
                signals.append({"name": var.name, "error": f"{type(error).__name__}: {error}"})
        samples.append({"pattern": label, "data": data.hex(), "signals": signals})
    return {
        "direction": direction,
        "number": number,
        "cob_id": pdo_map.cob_id,
        "enabled": pdo_map.enabled,
        "rtr_allowed": pdo_map.rtr_allowed,
        "transmission_type": pdo_map.trans_type,
        "inhibit_time": pdo_map.inhibit_time,
        "event_timer": pdo_map.event_timer,
        "bit_length": pdo_map.length,
        "entries": entries,
        "samples": samples,
    }


def objects_record(od):
    """Name, data type and value of every entry, for the look-up checks."""
    out = []
    for obj in od.values():
        if isinstance(obj, canopen.objectdictionary.ODVariable):
            variables = [obj]
        else:
            variables = [obj[sub] for sub in obj.subindices]
        for var in variables:
            value = var.value if var.value is not None else var.default
            out.append(
                {
                    "index": var.index,
                    "subindex": var.subindex,
                    "name": var.qualname,
                    "data_type": var.data_type,
                    "value": json_value(value) if value is not None else None,
                }
            )
    return out


def main():
    network = canopen.Network()  # never connected: only PdoMap's bookkeeping
    for name, node_id in FILES:
        path = os.path.join(FIXTURES, name)
        od = canopen.import_od(path, node_id)
        node = canopen.RemoteNode(node_id, od)
        network.add_node(node)
        pdos = []
        for direction, maps in (("receive", node.rpdo), ("transmit", node.tpdo)):
            for number, pdo_map in sorted(maps.map.items()):
                try:
                    pdo_map.read(from_od=True)
                except KeyError as error:
                    pdos.append({"direction": direction, "number": number, "error": str(error)})
                    continue
                pdos.append(pdo_record(direction, number, pdo_map))
        device_type = od[0x1000].default if 0x1000 in od else None
        result = {
            "file": name,
            "node": node_id,
            "generator": f"python-canopen {canopen.__version__}",
            "device_type": device_type,
            "objects": objects_record(od),
            "pdos": pdos,
        }
        with open(path + ".json", "w") as f:
            json.dump(result, f, indent=1, sort_keys=True)
            f.write("\n")
        print(f"{name}: {len(pdos)} PDOs, {len(result['objects'])} entries", file=sys.stderr)


if __name__ == "__main__":
    main()
