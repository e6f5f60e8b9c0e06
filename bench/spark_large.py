#!/usr/bin/env python3
"""Large files through `motionwire.spark` (results in BENCHMARKS.md,
"Fleets on Spark", large files). Not a test: it writes logs of gigabytes.

For each size, a candump log of that many bytes (bench/gen_mix.py's pdo
mix, repeated up to the size and cut at a line's end) is summarised by
`motionwire.spark.summary` on a fresh `local[2]` session (its own JVM, in a
child process, so that the driver's memory can be set and a failure stays
in its run), and the rows are compared with `motionwire.summary` of the
same file in one process: the `record` strings, one for one. Prints one
Markdown row per size: the way Spark handed the file over (its content in
a `binaryFile` row, or its path, above
`spark.sql.sources.binaryFile.maxLength`), the outcome and the times.

Usage: python3 bench/spark_large.py [--sizes 1.2G,2.2G] [--driver-memory 1g]
       [--dir /tmp/motionwire-bench/large] [--timeout 900]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
UNITS = {"K": 1 << 10, "M": 1 << 20, "G": 1 << 30}


def size_of(text: str) -> int:
    text = text.strip().upper()
    if text and text[-1] in UNITS:
        return int(float(text[:-1]) * UNITS[text[-1]])
    return int(text)


def make_log(path: Path, size: int, base: Path) -> None:
    """`base` repeated up to `size` bytes, cut after a whole line."""
    if path.exists() and path.stat().st_size <= size and path.stat().st_size > size - (1 << 12):
        return
    block = base.read_bytes()
    with open(path, "wb") as out:
        left = size
        while left >= len(block):
            out.write(block)
            left -= len(block)
        cut = block.rfind(b"\n", 0, left)
        out.write(block[: cut + 1])


def run_one(path: Path, driver_memory: str) -> dict:
    """In the child: the Spark summary of `path` and the single-process
    one, compared."""
    import motionwire
    from motionwire import spark as mws
    from pyspark.sql import SparkSession

    os.environ["PYSPARK_PYTHON"] = sys.executable
    spark = (
        SparkSession.builder.master("local[2]")
        .appName("motionwire-large")
        .config("spark.ui.enabled", "false")
        .config("spark.driver.memory", driver_memory)
        .getOrCreate()
    )
    spark.sparkContext.setLogLevel("ERROR")
    limit, _ = mws.content_limit(spark)
    result: dict = {
        "bytes": path.stat().st_size,
        "handed": "content" if path.stat().st_size <= limit else "path",
        "driver_memory": driver_memory,
    }
    start = time.perf_counter()
    try:
        rows = mws.summary(spark, str(path)).select("type", "file_error", "record").collect()
        result["spark_s"] = time.perf_counter() - start
    except Exception as error:  # the outcome is the figure
        result["spark_s"] = time.perf_counter() - start
        result["outcome"] = "job failed: " + str(error).splitlines()[0][:200]
        spark.stop()
        return result
    spark.stop()
    errors = [r.file_error for r in rows if r.file_error]
    start = time.perf_counter()
    single = motionwire.summary(str(path))
    result["single_s"] = time.perf_counter() - start
    theirs = [r.record for r in rows if r.record is not None and r.type != "file"]
    ours = [json.dumps(r, separators=(",", ":"), ensure_ascii=False) for r in single]
    if errors:
        result["outcome"] = "error row: " + errors[0][:200]
    elif len(theirs) == len(single) and [json.loads(t) for t in theirs] == single:
        result["outcome"] = f"equal ({len(single)} records)"
    else:
        result["outcome"] = f"differ: {len(theirs)} rows, {len(ours)} records"
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="1.2G,2.2G")
    parser.add_argument("--driver-memory", default="1g")
    parser.add_argument("--dir", default="/tmp/motionwire-bench/large")
    parser.add_argument("--timeout", type=int, default=900, help="seconds a size may take")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        print(json.dumps(run_one(Path(args.child), args.driver_memory)))
        return
    folder = Path(args.dir)
    folder.mkdir(parents=True, exist_ok=True)
    base = folder / "pdo-100k.log"
    if not base.exists():
        subprocess.run(
            [sys.executable, str(ROOT / "bench/gen_mix.py"), "pdo", "--frames", "100000", "-o", str(base)],
            check=True,
        )
    print("| bytes | handed over as | driver memory | outcome | Spark s | one process s |")
    print("|---|---|---|---|---|---|")
    for text in args.sizes.split(","):
        size = size_of(text)
        log = folder / f"pdo-{text}" / "big.log"
        log.parent.mkdir(exist_ok=True)
        make_log(log, size, base)
        try:
            child = subprocess.run(
                [sys.executable, __file__, "--child", str(log), "--driver-memory", args.driver_memory],
                capture_output=True,
                text=True,
                timeout=args.timeout,
            )
        except subprocess.TimeoutExpired as expired:
            # A task that runs out of heap in local mode can leave its job
            # waiting for ever: the JVM's own words say why.
            said = expired.stderr.decode(errors="replace") if isinstance(expired.stderr, bytes) else expired.stderr or ""
            why = [line for line in said.splitlines() if "Error" in line or "Exception" in line]
            tail = (why or ["no error said"])[0].strip()[:200]
            print(f"| {log.stat().st_size} | | {args.driver_memory} | no result in {args.timeout} s: {tail} | | |")
            sys.stdout.flush()
            continue
        lines = [line for line in child.stdout.splitlines() if line.startswith("{")]
        if not lines:
            tail = (child.stderr.strip().splitlines() or ["no output"])[-1][:200]
            print(f"| {log.stat().st_size} | | {args.driver_memory} | run died (rc {child.returncode}): {tail} | | |")
            continue
        r = json.loads(lines[-1])
        single = f"{r['single_s']:.2f}" if "single_s" in r else ""
        print(
            f"| {r['bytes']} | {r['handed']} | {r['driver_memory']} | {r['outcome']} | {r['spark_s']:.1f} | {single} |"
        )
        sys.stdout.flush()


if __name__ == "__main__":
    main()
