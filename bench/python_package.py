#!/usr/bin/env python3
"""Benchmark of the Python package `motionwire` against its Python peers, in
one run (issue 24; results in BENCHMARKS.md, "The Python package").

Goals on the 1 000 000-frame candump log of bench/run.sh
(`scripts/gen_canlog.py`, the simulated machine bus of samples/machine.log):

- `motionwire.read_log` at least 50x faster than python-can's `can.LogReader`
  building its list of `can.Message`s;
- `motionwire.summary` at least 100x faster than the python-can +
  python-canopen peer (`bench/peer_python.py`, in this process);
- `motionwire.read_logs` on 8 logs using both cores (CPU time over wall time,
  and the speed-up over `threads=1`);
- the table's memory per frame at most 48 bytes plus the data bytes.

Also measured, not goals: `decode` (every frame's columns and JSON record),
`Reader` against `can.LogReader` message by message, and python-can's
memory per message.

Needs the package installed (`pip install ./python`) and python-can,
canopen. Not a test: prints a Markdown table, writes
bench/results/python.json, and exits 1 when a goal is missed.

Usage: python3 bench/python_package.py [--frames N] [--runs N]
       python3 bench/python_package.py --mixes DIR [--runs N]

With --mixes, the two speed goals that depend on the traffic (read_log and
summary against their peers) on every traffic mix of bench/gen_mix.py, in
one run: DIR/MIX.log for each mix, written with `bench/gen_mix.py` when
missing; results in bench/results/python-mixes.json.
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import statistics
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path

import can
import pyarrow.compute as pc

import motionwire

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
import peer_python  # noqa: E402  (bench/peer_python.py, the summary's peer)


def log_file(frames: int) -> Path:
    """The benchmark's log (bench/run.sh's `gen` makes the same file)."""
    directory = Path(os.environ.get("BENCH_DIR", "/tmp/motionwire-bench"))
    path = directory / ("1m.log" if frames == 1_000_000 else f"{frames}.log")
    if not path.exists() or sum(1 for _ in path.open("rb")) != frames:
        directory.mkdir(parents=True, exist_ok=True)
        subprocess.run(
            [sys.executable, str(ROOT / "scripts" / "gen_canlog.py"), "--frames", str(frames), "-o", str(path)],
            check=True,
        )
    return path


def timed(fn, runs: int):
    """The best and median wall time of `runs` calls, the CPU time of the
    best, and the last result."""
    walls, cpus = [], []
    result = None
    for _ in range(runs):
        result = None
        gc.collect()
        cpu0, wall0 = time.process_time(), time.perf_counter()
        result = fn()
        wall = time.perf_counter() - wall0
        cpus.append(time.process_time() - cpu0)
        walls.append(wall)
    best = min(range(runs), key=walls.__getitem__)
    return {"best": walls[best], "median": statistics.median(walls), "cpu": cpus[best], "runs": runs}, result


def python_can_list(path: Path):
    with can.LogReader(str(path)) as reader:
        return list(reader)


def motionwire_reader_list(path: Path):
    with motionwire.Reader(path) as reader:
        return list(reader)


MIXES = ["sample", "storm", "pdo", "sdo", "fd"]


def mixes(directory: Path, frames: int, runs: int, peer_runs: int) -> int:
    """read_log and summary against their peers on every mix, one run."""
    directory.mkdir(parents=True, exist_ok=True)
    rows = []
    failed = False
    for mix in MIXES:
        path = directory / f"{mix}.log"
        if not path.exists():
            subprocess.run([sys.executable, str(ROOT / "bench" / "gen_mix.py"), mix,
                            "--frames", str(frames), "-o", str(path)], check=True)
        load = os.getloadavg()[0]
        read, table = timed(lambda: motionwire.read_log(path), runs)
        n = table.num_rows
        del table
        peer_read, messages = timed(lambda: python_can_list(path), peer_runs)
        assert len(messages) == n, (mix, len(messages), n)
        del messages
        summary, _ = timed(lambda: motionwire.summary(path), runs)
        peer_summary, _ = timed(lambda: peer_python.summarize(str(path)), peer_runs)
        row = {
            "mix": mix, "frames": n, "load": load,
            "read_log": read, "python_can_list": peer_read,
            "summary": summary, "peer_summary": peer_summary,
            "read_ratio": peer_read["best"] / read["best"],
            "summary_ratio": peer_summary["best"] / summary["best"],
        }
        failed |= row["read_ratio"] < 50 or row["summary_ratio"] < 100
        rows.append(row)
    print(f"\n{frames:,} frames a mix; python-can {can.__version__}; {os.cpu_count()} cores\n")
    print("| mix | load | read_log | python-can list | ratio (≥ 50×) | summary | peer | ratio (≥ 100×) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['mix']} | {r['load']:.2f} | {r['read_log']['best']*1000:,.1f} ms "
              f"| {r['python_can_list']['best']*1000:,.0f} ms | {r['read_ratio']:.1f}× "
              f"| {r['summary']['best']*1000:,.1f} ms | {r['peer_summary']['best']*1000:,.0f} ms "
              f"| {r['summary_ratio']:.1f}× |")
    out = ROOT / "bench" / "results" / "python-mixes.json"
    out.write_text(json.dumps({"python_can": can.__version__, "cores": os.cpu_count(),
                               "rows": rows}, indent=1) + "\n")
    return 1 if failed else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=1_000_000)
    parser.add_argument("--runs", type=int, default=5, help="runs of each motionwire call")
    parser.add_argument("--peer-runs", type=int, default=2, help="runs of each Python peer")
    parser.add_argument("--mixes", type=Path, help="a directory of the traffic mixes' logs")
    args = parser.parse_args()
    if args.mixes:
        return mixes(args.mixes, args.frames, args.runs, args.peer_runs)
    path = log_file(args.frames)
    frames = args.frames
    results: dict = {"frames": frames, "file": str(path), "cores": os.cpu_count(),
                     "load_before": os.getloadavg()[0],
                     "python_can": can.__version__, "motionwire": motionwire.__version__}

    read, table = timed(lambda: motionwire.read_log(path), args.runs)
    assert table.num_rows == frames, table.num_rows
    peer_read, messages = timed(lambda: python_can_list(path), args.peer_runs)
    assert len(messages) == frames
    results["read_log"] = read
    results["python_can_list"] = peer_read

    data_bytes = pc.sum(pc.binary_length(table.column("data"))).as_py()
    results["memory"] = {
        "table_bytes": table.nbytes,
        "data_bytes": data_bytes,
        "per_frame_without_data": (table.nbytes - data_bytes) / frames,
    }
    del table
    del messages
    # python-can's list, for comparison: what 100 000 can.Messages hold.
    sample = log_file(100_000)
    gc.collect()
    tracemalloc.start()
    kept = python_can_list(sample)
    current, _ = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    results["memory"]["python_can_per_message"] = current / len(kept)
    del kept

    summary, records = timed(lambda: motionwire.summary(path), args.runs)
    peer_summary, peer = timed(lambda: peer_python.summarize(str(path)), args.peer_runs)
    assert peer["frames"] == frames
    results["summary"] = summary
    results["peer_summary"] = peer_summary
    results["summary_records"] = len(records)

    decode, decoded = timed(lambda: motionwire.decode(path), max(2, args.runs // 2))
    results["decode"] = decode
    results["decode_bytes"] = decoded.nbytes
    del decoded

    reader, msgs = timed(lambda: motionwire_reader_list(path), max(1, args.peer_runs))
    assert len(msgs) == frames
    results["reader_list"] = reader
    del msgs

    paths = [path] * 8
    one, table = timed(lambda: motionwire.read_logs(paths, threads=1), max(2, args.runs // 2))
    both, table = timed(lambda: motionwire.read_logs(paths), max(2, args.runs // 2))
    assert table.num_rows == 8 * frames
    results["read_logs_1_thread"] = one
    results["read_logs"] = both
    del table

    ratio = lambda peer, ours: results[peer]["best"] / results[ours]["best"]  # noqa: E731
    goals = [
        ("read_log vs python-can LogReader list", ratio("python_can_list", "read_log"), 50, "x"),
        ("summary vs python-can + canopen peer", ratio("peer_summary", "summary"), 100, "x"),
        ("read_logs, 8 logs: CPU time / wall time", both["cpu"] / both["best"], 1.6, "cores"),
        ("read_logs, 8 logs: speed-up over threads=1", ratio("read_logs_1_thread", "read_logs"), 1.6, "x"),
        ("table bytes per frame without the data", results["memory"]["per_frame_without_data"], 48, "B (at most)"),
    ]
    results["goals"] = []
    failed = False
    results["load_after"] = os.getloadavg()[0]
    print(
        f"\n{frames:,} frames, {path}; python-can {can.__version__}; {os.cpu_count()} cores; "
        f"load average {results['load_before']:.2f} before, {results['load_after']:.2f} after\n"
    )
    print("| call | best | median | frames/s |")
    print("|---|---:|---:|---:|")
    for name, key in (
        ("motionwire.read_log", "read_log"),
        ("python-can: list(can.LogReader)", "python_can_list"),
        ("motionwire.summary", "summary"),
        ("python-can + canopen peer (bench/peer_python.py)", "peer_summary"),
        ("motionwire.decode", "decode"),
        ("list(motionwire.Reader) (can.Message)", "reader_list"),
        ("motionwire.read_logs, 8 logs, threads=1", "read_logs_1_thread"),
        ("motionwire.read_logs, 8 logs", "read_logs"),
    ):
        r = results[key]
        n = 8 * frames if key.startswith("read_logs") else frames
        print(f"| {name} | {r['best']*1000:,.1f} ms | {r['median']*1000:,.1f} ms | {n / r['best']:,.0f} |")
    print()
    print("| goal | measured | wanted | |")
    print("|---|---:|---:|---|")
    for name, value, wanted, unit in goals:
        at_most = unit.endswith("(at most)")
        ok = value <= wanted if at_most else value >= wanted
        failed |= not ok
        results["goals"].append({"goal": name, "measured": value, "wanted": wanted, "ok": ok})
        print(f"| {name} | {value:,.1f} | {wanted} {unit} | {'ok' if ok else 'MISSED'} |")
    m = results["memory"]
    print(
        f"\ntable: {m['table_bytes']:,} bytes, of which data {m['data_bytes']:,}; "
        f"python-can: {m['python_can_per_message']:,.0f} bytes per can.Message"
    )
    out = ROOT / "bench" / "results" / "python.json"
    out.write_text(json.dumps(results, indent=1) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
