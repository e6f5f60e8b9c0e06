#!/usr/bin/env python3
"""Python peer for `motionwire decode --summary`: what a user would write instead.

Reads a log file with python-can's reader for its format (`can.LogReader`
picks it by the file's suffix: `.log` candump, `.asc` Vector ASC, `.blf`
Vector BLF, `.trc` PEAK TRC; docs/formats.md), classifies every frame by its CAN
identifier as docs/canopen.md#identifiers does, feeds every EMCY to
python-canopen's `canopen.emcy.EmcyConsumer` (one per node, as
`canopen.RemoteNode` does) and describes the codes with
`canopen.emcy.EmcyError.get_desc()`. Prints one JSON summary: per node the frame
counts per kind, EMCY count, resets, first error (line, code, description), the
errors still active at the end (python-canopen's view: a reset clears all),
boot-ups and the described codes.

This is the benchmark's peer (bench/run.sh), not part of motionwire. Needs
`pip install python-can canopen`.

Usage: python3 bench/peer_python.py FILE.log|.asc|.blf|.trc [FILE ...]
"""

from __future__ import annotations

import json
import sys

import can
from canopen.emcy import EmcyConsumer

KINDS = ("emcy", "heartbeat", "guard_request", "pdo", "sdo")


def kind_of(can_id: int, extended: bool, remote: bool) -> str:
    """The `kind` of a frame, by identifier (docs/canopen.md#identifiers)."""
    if extended:
        return "other"
    if can_id == 0x000:
        return "nmt_command"
    if can_id == 0x080:
        return "sync"
    if 0x081 <= can_id <= 0x0FF:
        return "emcy"
    if 0x181 <= can_id <= 0x57F:
        return "pdo"
    if 0x581 <= can_id <= 0x67F:
        return "sdo"
    if 0x701 <= can_id <= 0x77F:
        return "guard_request" if remote else "heartbeat"
    return "other"


def summarize(path: str) -> dict:
    totals: dict[str, int] = {}
    nodes: dict[int, dict] = {}
    consumers: dict[int, EmcyConsumer] = {}
    line = 0
    with can.LogReader(path) as reader:
        for msg in reader:
            line += 1
            kind = kind_of(msg.arbitration_id, msg.is_extended_id, msg.is_remote_frame)
            totals[kind] = totals.get(kind, 0) + 1
            if kind not in KINDS:
                continue
            node_id = msg.arbitration_id & 0x7F
            node = nodes.get(node_id)
            if node is None:
                node = nodes[node_id] = {
                    "frames": dict.fromkeys(KINDS, 0),
                    "emcy": 0,
                    "resets": 0,
                    "first_error": None,
                    "boot_ups": 0,
                    "codes": {},
                }
                consumers[node_id] = EmcyConsumer()
            node["frames"][kind] += 1
            if kind == "emcy":
                if len(msg.data) < 8:
                    node.setdefault("short_emcy_lines", []).append(line)
                    continue
                consumer = consumers[node_id]
                consumer.on_emcy(msg.arbitration_id, bytes(msg.data), msg.timestamp)
                error = consumer.log[-1]
                node["emcy"] += 1
                key = f"0x{error.code:04X}"
                entry = node["codes"].get(key)
                if entry is None:
                    entry = node["codes"][key] = {"description": error.get_desc(), "count": 0}
                entry["count"] += 1
                if error.code & 0xFF00 == 0:
                    node["resets"] += 1
                elif node["first_error"] is None:
                    node["first_error"] = {
                        "line": line,
                        "code": key,
                        "register": error.register,
                        "description": error.get_desc(),
                    }
            elif kind == "heartbeat" and msg.data and msg.data[0] == 0x00:
                node["boot_ups"] += 1
    for node_id, node in nodes.items():
        node["active_at_end"] = [f"0x{e.code:04X}" for e in consumers[node_id].active]
    return {
        "file": path,
        "frames": line,
        "totals": totals,
        "nodes": {str(n): nodes[n] for n in sorted(nodes)},
    }


def main(argv: list[str]) -> int:
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    for path in argv:
        json.dump(summarize(path), sys.stdout, indent=1)
        sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
