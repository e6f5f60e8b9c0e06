#!/usr/bin/env python3
"""Benchmark of `motionwire.spark` (issue 37; results in BENCHMARKS.md,
"Fleets on Spark"). Not a test: prints Markdown tables, writes
bench/results/spark.json.

- Spark's own cost per file: N tiny logs (40 frames each, so that
  decoding is nothing) summarised on a warm session, the time per file,
  with the files in one directory and with one file per directory
  (partition discovery lists more than 32 directories in a Spark job of
  its own);
- the fleet summary (examples/fleet, 602 logs) on local[2] against
  local[1] (goal: at least 1.6x);
- frames per second per executor core: `frames` and `summary` on
  local[1] beside `read_logs(threads=1)` and a loop of the summary in one
  process, on the same files;
- where the time goes on local[1]: the JVM's scan of the files alone,
  then the bytes handed to the Python worker and dropped, then each file
  read by the package with nothing handed back, then the whole job;
- the output batch size of `frames` (rows per Arrow batch back to Spark);
- each job again with the files packed into fewer partitions
  (`spark.sql.files.openCostInBytes` 1 MB instead of 4 MB): a Python task
  has a fixed cost.

Every Spark figure is the shortest of --runs runs on a session warmed by
one run of the same job (the machine is shared); the jobs write to Spark's `noop` sink, so that
every row is made and nothing written.

Usage: python3 bench/spark.py [--fleet DIR] [--runs 2] [--small 400] [--results spark.json]
       python3 bench/spark.py --speedup-only [--rounds 3] [--pinned]   (the 1.6x goal alone)
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import motionwire
from motionwire import _motionwire
from motionwire import spark as mws

ROOT = Path(__file__).resolve().parents[1]
OPTIONS = dict(heartbeat_ms=300, profiles={3: "akd", 5: "baumer"})
#: `spark.sql.files.openCostInBytes` of the packed runs (Spark's is 4 MB).
OPEN_COST = 1 << 20
#: Rows per Arrow batch handed back to Spark by `frames`, tried in turn.
BATCHES = (1 << 12, 1 << 16, 1 << 20)


def session(master: str):
    from pyspark.sql import SparkSession

    os.environ["PYSPARK_PYTHON"] = sys.executable
    spark = (
        SparkSession.builder.master(master)
        .appName("motionwire-bench")
        .config("spark.ui.enabled", "false")
        .config("spark.ui.showConsoleProgress", "false")
        .config("spark.sql.shuffle.partitions", "4")
        .getOrCreate()
    )
    spark.sparkContext.setLogLevel("ERROR")
    return spark


def timed(job, runs: int) -> float:
    """The shortest wall time of `job()` in `runs` runs, after one run to
    warm up: the machine is shared, and the shortest run is the one the
    other tenants disturbed least."""
    job()
    times = []
    for _ in range(runs):
        gc.collect()
        t = time.perf_counter()
        job()
        times.append(time.perf_counter() - t)
    return min(times)


def noop(df) -> None:
    df.write.format("noop").mode("overwrite").save()


def tiny_fleet(root: Path, n: int, per_dir: bool) -> Path:
    """`n` candump logs of 40 frames (the sample's lines, shifted)."""
    lines = (ROOT / "samples" / "machine.log").read_text().splitlines(keepends=True)
    for i in range(n):
        d = root / f"machine={i:04d}" if per_dir else root
        d.mkdir(parents=True, exist_ok=True)
        (d / f"{i:04d}.log").write_text("".join(lines[(i * 40) % 3700 : (i * 40) % 3700 + 40]))
    return root


# The stages of "where the time goes": each a mapInArrow function.


def _drop(batches):
    """The bytes handed to Python, dropped."""
    for batch in batches:
        batch.column(1)
    return iter(())


def _read_only(batches):
    """Each file read by the package, nothing handed back."""
    for batch in batches:
        contents = batch.column(1)
        for i in range(batch.num_rows):
            try:
                motionwire.read_log(contents[i].as_py())
            except motionwire.LogError:
                pass
    return iter(())


def _summary_only(batches):
    for batch in batches:
        contents = batch.column(1)
        for i in range(batch.num_rows):
            try:
                _motionwire.post_mortem(contents[i].as_py(), **OPTIONS)
            except motionwire.LogError:
                pass
    return iter(())


def speedup_one(master: str, logs: Path, runs: int) -> tuple[float, float]:
    """The fleet summary's shortest time on `master`, with Spark's
    partitions and packed."""
    spark = session(master)
    plain = timed(lambda: noop(mws.summary(spark, str(logs), **OPTIONS)), runs)
    spark.conf.set("spark.sql.files.openCostInBytes", str(OPEN_COST))
    packed = timed(lambda: noop(mws.summary(spark, str(logs), **OPTIONS)), runs)
    spark.stop()
    return plain, packed


def speedup_rounds(logs: Path, args) -> dict:
    """local[2] against local[1] on the fleet's summary, the sessions
    alternated so that both see the same tenants. With `--pinned`, each
    session runs in a child process (its JVM and Python workers) that
    `taskset` limits to as many CPUs as the session has task slots: on a
    2-core machine an unpinned local[1] also uses the second core (the
    JVM's reading and Arrow threads beside the Python worker), so that
    the pinned ratio is the one of one core against two."""
    speedup: dict = {"local[1]": [], "local[2]": [], "local[1] packed": [], "local[2] packed": []}
    for _ in range(args.rounds):
        for master, cpus in (("local[1]", "0"), ("local[2]", "0,1")):
            if args.pinned:
                command = ["taskset", "-c", cpus, sys.executable, __file__, "--child", master, "--fleet", str(args.fleet)]
                out = subprocess.run(command + ["--runs", str(args.runs)], capture_output=True, text=True, check=True)
                plain, packed = json.loads(out.stdout.strip().splitlines()[-1])
            else:
                plain, packed = speedup_one(master, logs, args.runs)
            speedup[master].append(plain)
            speedup[master + " packed"].append(packed)
    print(f"speed-up rounds: {speedup}")
    return speedup


def speedup_table(sp: dict) -> None:
    print(f"\nsummary, {len(sp['local[1]'])} alternations of the sessions, the shortest of each:\n")
    print("| partitions | local[1] | local[2] | speed-up |\n|---|---|---|---|")
    for label, key in (("Spark's (4 MB open cost)", ""), ("packed (1 MB open cost)", " packed")):
        a, b = min(sp["local[1]" + key]), min(sp["local[2]" + key])
        print(f"| {label} | {a:.2f} s | {b:.2f} s | {a / b:.2f}x |")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fleet", type=Path, default=Path("/tmp/fleet"))
    parser.add_argument("--runs", type=int, default=2)
    parser.add_argument("--small", type=int, default=400)
    parser.add_argument("--results", default="spark.json", help="the file in bench/results")
    parser.add_argument("--rounds", type=int, default=3, help="alternations of local[1] and local[2]")
    parser.add_argument("--speedup-only", action="store_true", help="only the local[2] against local[1] rounds")
    parser.add_argument("--pinned", action="store_true", help="each session on as many CPUs as task slots (taskset)")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        print(json.dumps(speedup_one(args.child, args.fleet / "logs", args.runs)))
        return 0
    if not (args.fleet / "logs").exists():
        subprocess.run([sys.executable, str(ROOT / "examples" / "fleet" / "generate.py"), str(args.fleet)], check=True)
    logs = args.fleet / "logs"
    if args.speedup_only:
        before = os.getloadavg()
        sp = speedup_rounds(logs, args)
        print(f"\nload average {before[0]:.1f} before, {os.getloadavg()[0]:.1f} after")
        speedup_table(sp)
        return 0
    files = sorted(str(p) for p in logs.rglob("*") if p.is_file())
    results: dict = {"load_before": os.getloadavg()}
    from pyspark.sql import functions as F

    # -- one process -------------------------------------------------------
    readable = []
    for p in files:
        try:
            motionwire.read_log(p)
            readable.append(p)
        except motionwire.LogError:
            pass
    table = motionwire.read_logs(readable, threads=1)
    can_frames = table.num_rows
    del table

    def one_process_read(threads):
        return lambda: motionwire.read_logs(readable, threads=threads)

    def one_process_summary():
        for p in files:
            try:
                _motionwire.post_mortem(Path(p).read_bytes(), **OPTIONS)
            except motionwire.LogError:
                pass

    r = results["one_process"] = {
        "files": len(files),
        "frames": can_frames,
        "bytes": sum(os.path.getsize(p) for p in files),
        "read_logs_1": timed(one_process_read(1), args.runs),
        "read_logs_2": timed(one_process_read(2), args.runs),
        "summary_loop_1": timed(one_process_summary, args.runs),
    }
    print(f"one process: {r}")

    # -- local[1] and local[2] ---------------------------------------------
    for master in ("local[1]", "local[2]"):
        spark = session(master)
        out = results[master] = {}
        path = str(logs)
        files_df = spark.read.format("binaryFile").option("recursiveFileLookup", "true").load(path)
        out["partitions"] = files_df.rdd.getNumPartitions()
        out["summary"] = timed(lambda: noop(mws.summary(spark, path, **OPTIONS)), args.runs)
        out["findings"] = timed(lambda: noop(mws.findings(spark, path, **OPTIONS)), args.runs)
        out["frames"] = timed(lambda: noop(mws.frames(spark, path)), args.runs)
        # Fewer, larger file partitions: each small log counted as 1 MB
        # instead of Spark's 4 MB open cost.
        spark.conf.set("spark.sql.files.openCostInBytes", str(OPEN_COST))
        out["packed_partitions"] = spark.read.format("binaryFile").option("recursiveFileLookup", "true").load(path).rdd.getNumPartitions()
        out["packed_summary"] = timed(lambda: noop(mws.summary(spark, path, **OPTIONS)), args.runs)
        out["packed_findings"] = timed(lambda: noop(mws.findings(spark, path, **OPTIONS)), args.runs)
        out["packed_frames"] = timed(lambda: noop(mws.frames(spark, path)), args.runs)
        spark.conf.unset("spark.sql.files.openCostInBytes")
        if master == "local[1]":
            held = files_df.select("path", "content")
            out["scan_only"] = timed(lambda: noop(files_df.select(F.length("content"))), args.runs)
            out["to_python"] = timed(lambda: noop(held.mapInArrow(_drop, "x int")), args.runs)
            out["read_in_python"] = timed(lambda: noop(held.mapInArrow(_read_only, "x int")), args.runs)
            out["summary_in_python"] = timed(lambda: noop(held.mapInArrow(_summary_only, "x int")), args.runs)
            for rows in BATCHES:
                mws.BATCH_ROWS = rows
                out[f"frames_batch_{rows}"] = timed(lambda: noop(mws.frames(spark, path)), 1)
            mws.BATCH_ROWS = 1 << 16
            # Spark's cost per file: tiny logs, warm session.
            with tempfile.TemporaryDirectory() as tmp:
                for n in (args.small // 2, args.small):
                    for per_dir in (False, True):
                        root = tiny_fleet(Path(tmp) / f"{n}-{per_dir}", n, per_dir)
                        key = f"tiny_{n}_{'per_dir' if per_dir else 'one_dir'}"
                        out[key] = timed(lambda: noop(mws.summary(spark, str(root), **OPTIONS)), args.runs)
                        out[key + "_frames"] = timed(lambda: noop(mws.frames(spark, str(root))), args.runs)
                        t = time.perf_counter()
                        spark.read.format("binaryFile").option("recursiveFileLookup", "true").load(str(root))
                        out[key + "_listing"] = time.perf_counter() - t
                        shutil.rmtree(root)
        print(f"{master}: {out}")
        spark.stop()
    results["speedup"] = speedup_rounds(logs, args)
    results["load_after"] = os.getloadavg()
    (ROOT / "bench" / "results").mkdir(exist_ok=True)
    (ROOT / "bench" / "results" / args.results).write_text(json.dumps(results, indent=1) + "\n")
    report(results, args.small)
    return 0


def report(results: dict, small: int) -> None:
    one, l1, l2 = results["one_process"], results["local[1]"], results["local[2]"]
    frames = one["frames"]
    print(f"\nFleet: {one['files']} files, {frames} CAN frames, {one['bytes'] / 1e6:.1f} MB; "
          f"load average {results['load_before'][0]:.1f} before, {results['load_after'][0]:.1f} after\n")
    print("| job | partitions | local[1] | local[2] | speed-up |\n|---|---|---|---|---|")
    for job in ("summary", "findings", "frames", "packed_summary", "packed_findings", "packed_frames"):
        parts = l1["packed_partitions" if job.startswith("packed") else "partitions"]
        print(f"| {job} | {parts} | {l1[job]:.2f} s | {l2[job]:.2f} s | {l1[job] / l2[job]:.2f}x |")
    speedup_table(results["speedup"])
    print("\n| per core | frames/s |\n|---|---|")
    print(f"| read_logs(threads=1), one process | {frames / one['read_logs_1']:,.0f} |")
    print(f"| read_logs(threads=2), one process (per core) | {frames / one['read_logs_2'] / 2:,.0f} |")
    print(f"| frames on local[1] | {frames / l1['frames']:,.0f} |")
    print(f"| frames on local[1], packed | {frames / l1['packed_frames']:,.0f} |")
    print(f"| summary loop, one process | {frames / one['summary_loop_1']:,.0f} |")
    print(f"| summary on local[1] | {frames / l1['summary']:,.0f} |")
    print(f"| summary on local[1], packed | {frames / l1['packed_summary']:,.0f} |")
    print("\n| local[1], the fleet | time |\n|---|---|")
    for key in ("scan_only", "to_python", "read_in_python", "frames", "summary_in_python", "summary"):
        print(f"| {key} | {l1[key]:.2f} s |")
    print("\n| frames, rows per batch | time |\n|---|---|")
    for rows in BATCHES:
        print(f"| {rows} | {l1[f'frames_batch_{rows}']:.2f} s |")
    print("\n| tiny logs, local[1] | files | summary | per file | frames | per file | listing |\n|---|---|---|---|---|---|---|")
    for n in (small // 2, small):
        for layout in ("one_dir", "per_dir"):
            k = f"tiny_{n}_{layout}"
            print(f"| {layout} | {n} | {l1[k]:.2f} s | {l1[k] / n * 1e3:.1f} ms | {l1[k + '_frames']:.2f} s | "
                  f"{l1[k + '_frames'] / n * 1e3:.1f} ms | {l1[k + '_listing']:.2f} s |")
    for layout in ("one_dir", "per_dir"):
        a, b = l1[f"tiny_{small // 2}_{layout}"], l1[f"tiny_{small}_{layout}"]
        print(f"marginal cost per file ({layout}, summary): {(b - a) / (small - small // 2) * 1e3:.1f} ms")


if __name__ == "__main__":
    sys.exit(main())
