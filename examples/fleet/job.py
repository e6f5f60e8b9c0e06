#!/usr/bin/env python3
"""The fleet's post-mortem on Spark: every log of a fleet written by
generate.py summarised by `motionwire.spark` into Parquet tables, and
the fleet's questions answered from them in Spark SQL and in DuckDB
(docs/spark.md#questions).

    python3 examples/fleet/generate.py /tmp/fleet
    python3 examples/fleet/job.py /tmp/fleet            # local[*]
    python3 examples/fleet/job.py /tmp/fleet --remote sc://host:15002   # Spark Connect

Writes FLEET/tables/summary and FLEET/tables/findings (Parquet), prints
the answers as Markdown tables, and checks them against the generator's
manifest (FLEET/manifest.json): every machine-day the generator gave a
drive fault, a bus-off or a reboot is found, and no healthy one.

Needs the package with its Spark extra (``pip install ./python[spark]``)
and Java 17; DuckDB for the last answers (``pip install duckdb``).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

from motionwire import spark as mws

OPTIONS = dict(heartbeat_ms=300, profiles={3: "akd", 5: "baumer"})

QUESTIONS = {
    "Which machines had a drive fault, on how many days, with which first EMCY": """
        SELECT regexp_extract(s.file, 'machine=([^/]+)', 1) AS machine,
               count(DISTINCT regexp_extract(s.file, 'date=([^/]+)', 1)) AS days,
               sum(s.cia402_faults) AS faults,
               concat_ws(' ', sort_array(collect_set(printf('0x%04X', s.first_error_code)))) AS first_emcy
        FROM summary s
        WHERE s.type = 'node' AND s.node = 3 AND s.cia402_faults > 0
        GROUP BY machine ORDER BY days DESC, faults DESC, machine LIMIT 12""",
    "What stopped the machines, and the first cause": """
        SELECT get_json_object(v.record, '$.stop.kind') AS stop,
               get_json_object(v.record, '$.first_cause.kind') AS first_cause,
               CASE WHEN c.code IS NULL THEN '' ELSE printf('0x%04X', c.code) END AS code,
               count(*) AS logs
        FROM summary v LEFT JOIN findings c ON v.file = c.file AND c.kind = 'first_cause'
        WHERE v.type = 'verdict'
        GROUP BY 1, 2, 3 ORDER BY logs DESC""",
    "Which EMCY code comes first most often (the verdict's first cause)": """
        SELECT printf('0x%04X', code) AS emcy, count(*) AS stops,
               count(DISTINCT regexp_extract(file, 'machine=([^/]+)', 1)) AS machines
        FROM findings WHERE kind = 'first_cause' AND code IS NOT NULL
        GROUP BY code ORDER BY stops DESC""",
    "Where the drive's SDO latencies grow (median per day, ms)": """
        SELECT machine,
               round(max(IF(date = '2024-05-01', median, NULL)), 2) AS `05-01`,
               round(max(IF(date = '2024-05-02', median, NULL)), 2) AS `05-02`,
               round(max(IF(date = '2024-05-03', median, NULL)), 2) AS `05-03`
        FROM (SELECT regexp_extract(file, 'machine=([^/]+)', 1) AS machine,
                     regexp_extract(file, 'date=([^/]+)', 1) AS date,
                     CAST(get_json_object(record, '$.sdo.latency_ms.median') AS DOUBLE) AS median
              FROM summary WHERE type = 'node' AND node = 3)
        GROUP BY machine
        HAVING max(median) - min(median) > 2
        ORDER BY machine""",
    "Which buses went error-passive or bus-off before a heartbeat was lost": """
        SELECT regexp_extract(e.file, 'machine=([^/]+)', 1) AS machine,
               regexp_extract(e.file, 'date=([^/]+)', 1) AS date,
               e.iface, e.kind AS bus_error, h.node AS lost_node,
               round(h.ts - e.ts, 3) AS seconds_later
        FROM findings e JOIN findings h ON e.file = h.file AND e.iface <=> h.iface
        WHERE e.kind IN ('error_passive', 'bus_off') AND h.kind = 'heartbeat_timeout'
          AND e.ts <= h.ts
          AND NOT EXISTS (SELECT 1 FROM findings x WHERE x.file = e.file AND x.kind = e.kind AND x.ts < e.ts)
        ORDER BY machine, date, bus_error DESC""",
    "Files that are no log, damaged, empty, or had lines skipped": """
        SELECT regexp_extract(file, 'logs/(.*)', 1) AS file, file_error AS why
        FROM summary WHERE file_error IS NOT NULL
        UNION ALL
        SELECT regexp_extract(file, 'logs/(.*)', 1),
               IF(skipped = 0, 'empty: no frame',
                  concat(frames_total, ' frames read, ', skipped, ' lines or records skipped'))
        FROM summary WHERE type = 'file' AND (skipped > 0 OR frames_total = 0)
        ORDER BY file""",
}


def markdown(columns: list[str], rows: list) -> str:
    cell = lambda v: "" if v is None else str(v).replace("|", "\\|")  # noqa: E731
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in rows]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fleet", type=Path)
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--master", default="local[*]", help="a classic session's master")
    where.add_argument(
        "--remote",
        help="a Spark Connect server (sc://host:port, or local[2] for pyspark 4's own)",
    )
    args = parser.parse_args(argv)
    logs, tables = args.fleet / "logs", args.fleet / "tables"

    from pyspark.sql import SparkSession

    os.environ.setdefault("PYSPARK_PYTHON", sys.executable)
    started = time.perf_counter()
    builder = SparkSession.builder.appName("motionwire-fleet")
    if args.remote:
        builder = builder.remote(args.remote)
    else:
        builder = builder.master(args.master).config("spark.ui.enabled", "false")
    spark = (
        builder.config("spark.ui.showConsoleProgress", "false")
        .config("spark.sql.shuffle.partitions", "8")
        .getOrCreate()
    )
    if not args.remote:
        # A Connect session has no SparkContext; its server logs apart.
        spark.sparkContext.setLogLevel("ERROR")
    on = args.remote or args.master
    print(f"Spark {spark.version} on {on}: session in {time.perf_counter() - started:.1f} s")

    for name, make in (("summary", mws.summary), ("findings", mws.findings)):
        t = time.perf_counter()
        make(spark, str(logs), **OPTIONS).write.mode("overwrite").parquet(str(tables / name))
        print(f"{name}: {tables / name} in {time.perf_counter() - t:.1f} s")
        spark.read.parquet(str(tables / name)).createOrReplaceTempView(name)

    files = spark.sql("SELECT count(DISTINCT file) FROM summary").first()[0]
    frames = spark.sql("SELECT sum(frames_total) FROM summary WHERE type = 'file'").first()[0]
    print(f"\n{files} files, {frames} frames read\n")

    answers = {}
    for question, sql in QUESTIONS.items():
        df = spark.sql(sql)
        rows = [tuple(r) for r in df.collect()]
        answers[question] = rows
        print(f"### {question}\n\n{markdown(df.columns, rows)}\n")

    try:
        import duckdb
    except ImportError:
        print("(DuckDB not installed: its answers are left out)")
    else:
        summary_parquet = str(tables / "summary" / "*.parquet")
        sql = f"""
            SELECT regexp_extract(file, 'machine=([^/]+)', 1) AS machine,
                   count(DISTINCT regexp_extract(file, 'date=([^/]+)', 1)) AS days,
                   sum(cia402_faults) AS faults
            FROM '{summary_parquet}'
            WHERE type = 'node' AND node = 3 AND cia402_faults > 0
            GROUP BY machine ORDER BY days DESC, faults DESC, machine LIMIT 5"""
        rel = duckdb.sql(sql)
        print(f"### DuckDB over the Parquet: the drive faults again\n\n{markdown(rel.columns, rel.fetchall())}\n")
        sql = f"""
            SELECT round(CAST(json_extract(record, '$.sdo.latency_ms.median') AS DOUBLE), 1) AS median_ms,
                   count(*) AS drives
            FROM '{summary_parquet}' WHERE type = 'node' AND node = 3
            GROUP BY ALL ORDER BY median_ms"""
        rel = duckdb.sql(sql)
        print(f"### DuckDB: the drives' SDO median latency, all days\n\n{markdown(rel.columns, rel.fetchall())}\n")

    check(spark, args.fleet)
    spark.stop()
    return 0


def check(spark, fleet: Path) -> None:
    """The answers against what the generator wrote (manifest.json)."""
    manifest = json.loads((fleet / "manifest.json").read_text())
    faulted = {
        (r["machine"], r["date"])
        for r in spark.sql(
            """SELECT regexp_extract(file, 'machine=([^/]+)', 1) AS machine,
                      regexp_extract(file, 'date=([^/]+)', 1) AS date
               FROM summary WHERE type = 'node' AND node = 3 AND cia402_faults > 0"""
        ).collect()
    }
    bus_off = {
        (r["machine"], r["date"])
        for r in spark.sql(
            """SELECT regexp_extract(file, 'machine=([^/]+)', 1) AS machine,
                      regexp_extract(file, 'date=([^/]+)', 1) AS date
               FROM findings WHERE kind = 'bus_off'"""
        ).collect()
    }
    whole = [e for e in manifest if not e.get("damage")]
    # The encoder's loss is the drive's heartbeat-consumer error: a
    # reboot and bus errors fault the drive too.
    expected = {(e["machine"], e["date"]) for e in whole if e["scenario"] in ("drive_fault", "reboot", "bus_errors")}
    healthy = {(e["machine"], e["date"]) for e in whole if e["scenario"] == "healthy"}
    assert expected <= faulted, sorted(expected - faulted)[:5]
    assert not (faulted & healthy), sorted(faulted & healthy)[:5]
    assert {(e["machine"], e["date"]) for e in whole if e["scenario"] == "bus_errors"} <= bus_off
    slow = {e["machine"] for e in manifest if e.get("firmware") == "M01.20" and e["format"] not in ("ethercat", None)}
    growing = {
        r[0]
        for r in spark.sql(QUESTIONS["Where the drive's SDO latencies grow (median per day, ms)"]).collect()
    }
    assert growing <= slow, sorted(growing - slow)
    print(
        f"Checked against manifest.json: {len(expected)} machine-days with a drive fault, a reboot or bus "
        f"errors all found, none of the {len(healthy)} healthy ones; the growing SDO latencies are "
        f"{len(growing)} of the {len(slow)} machines with drive firmware M01.20."
    )


if __name__ == "__main__":
    sys.exit(main())
