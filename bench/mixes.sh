#!/usr/bin/env bash
# Issue 21: the figures of the issue's table on every traffic mix of
# bench/gen_mix.py, the peers in the same run (BENCHMARKS.md, "Issue 21").
#
# For each mix, from one 1 000 000-frame log written by bench/gen_mix.py
# (candump text, the same frames as a SocketCAN pcap, and as Vector ASC and
# BLF written by python-can's own writers, bench/convert_python_can.py):
#
#   summary   decode --summary MIX.log   vs  python-can + canopen (bench/peer_python.py)
#   json      decode --json MIX.log      vs  tshark -T fields (CANopen) on MIX.pcap
#   asc       decode --summary MIX.asc   vs  bench/peer_python.py MIX.asc (ASCReader)
#   blf       decode --summary MIX.blf   vs  bench/peer_python.py MIX.blf (BLFReader)
#   pcap      decode --summary MIX.pcap  vs  tshark -T fields (the json step's run)
#   memory    peak resident memory (/usr/bin/time -v) of decode --summary and
#             decode --json at 100 000 and 1 000 000 frames
#   floor     where decode --summary's time goes, in one hyperfine session:
#             `cat MIX.log` (the read from the page cache), the library's
#             reading and parsing alone (examples/read_log.rs), and
#             decode --summary (not a peer figure: printed as a second table)
#
# Ours runs BENCH_RUNS times (after a warm-up), the peers PEER_RUNS times
# (they take seconds to minutes); with MOTIONWIRE_BEFORE set to another build
# (e.g. main's), it runs beside ours in the same hyperfine session. The load
# average is recorded before each step: the figures to compare are the
# ratios within one step, not times across runs.
#
# Usage: bench/mixes.sh [MIX...]        (default: sample storm pdo sdo fd)
#        bench/mixes.sh table           print the table from the results
# Environment: BENCH_DIR (default /tmp/motionwire-bench/mixes), BENCH_FRAMES
# (default 1000000), BENCH_RUNS (default 10), PEER_RUNS (default 1),
# MOTIONWIRE (default target/release/motionwire), MOTIONWIRE_BEFORE
# (optional), READ_LOG (default target/release/examples/read_log: cargo build
# --release --example read_log --features logs), STEPS (default "summary json
# asc blf pcap memory floor").
set -euo pipefail
cd "$(dirname "$0")/.."

BENCH_DIR=${BENCH_DIR:-/tmp/motionwire-bench/mixes}
FRAMES=${BENCH_FRAMES:-1000000}
RUNS=${BENCH_RUNS:-10}
PEER_RUNS=${PEER_RUNS:-1}
MOTIONWIRE=${MOTIONWIRE:-target/release/motionwire}
MOTIONWIRE_BEFORE=${MOTIONWIRE_BEFORE:-}
READ_LOG=${READ_LOG:-target/release/examples/read_log}
STEPS=${STEPS:-summary json asc blf pcap memory floor}
RESULTS=bench/results/mixes
# The fields of bench/run.sh: those that match decode --json's keys.
TSHARK=(tshark -d can.subdissector,canopen -T fields -E separator=, -e frame.number
    -e frame.time_epoch -e can.id -e can.flags.xtd -e can.flags.rtr -e can.len -e data.data
    -e canopen.function_code -e canopen.node_id -e canopen.em.err_code -e canopen.em.err_reg
    -e canopen.nmt_guard.state -e canopen.nmt_guard.toggle)

step() { printf '\n==> %s (load average %s)\n' "$*" "$(cut -d' ' -f1-3 /proc/loadavg)"; }

# The step's load average, kept beside its hyperfine export.
load() { cut -d' ' -f1-3 /proc/loadavg >"$RESULTS/$1.load"; }

inputs() {
    local mix=$1 base=$BENCH_DIR/$1
    mkdir -p "$BENCH_DIR"
    if [[ ! -s $base.log || ! -s $base.pcap ]]; then
        python3 bench/gen_mix.py "$mix" --frames "$FRAMES" -o "$base.log" --pcap "$base.pcap"
    fi
    if [[ ! -s $base-100k.log ]]; then
        python3 bench/gen_mix.py "$mix" --frames 100000 -o "$base-100k.log"
    fi
    if [[ ! -s $base.asc || ! -s $base.blf ]]; then
        python3 bench/convert_python_can.py "$base.log" "$base.asc" "$base.blf"
    fi
}

# ours NAME FILE ARGS: hyperfine over ours (and the build before).
ours() {
    local name=$1 file=$2 args=$3
    local extra=()
    if [[ -n $MOTIONWIRE_BEFORE ]]; then
        extra=(-n "before: motionwire $args" "$MOTIONWIRE_BEFORE $args $file >/dev/null 2>&1")
    fi
    load "$name"
    hyperfine --warmup 2 --runs "$RUNS" --export-json "$RESULTS/$name.json" \
        -n "motionwire $args" "$MOTIONWIRE $args $file >/dev/null 2>&1" "${extra[@]}"
}

# peer NAME LABEL COMMAND
peer() {
    local name=$1 label=$2 command=$3
    load "$name-peer"
    hyperfine --runs "$PEER_RUNS" --export-json "$RESULTS/$name-peer.json" \
        -n "$label" "$command >/dev/null 2>&1"
}

memory() {
    local mix=$1 base=$BENCH_DIR/$1 out=$RESULTS/$1-memory.txt
    : >"$out"
    for file in "$base-100k.log" "$base.log"; do
        for args in "decode --summary" "decode --json"; do
            local kb
            kb=$(/usr/bin/time -f %M "$MOTIONWIRE" $args "$file" 2>&1 >/dev/null | tail -n 1)
            printf '%s\t%s\t%s\n' "$(basename "$file")" "$args" "$kb" | tee -a "$out"
        done
    done
}

run_mix() {
    local mix=$1 base=$BENCH_DIR/$1
    inputs "$mix"
    for s in $STEPS; do
        step "$mix: $s"
        case $s in
            summary)
                ours "$mix-summary" "$base.log" "decode --summary"
                peer "$mix-summary" "python-can + canopen" "python3 bench/peer_python.py $base.log" ;;
            json)
                ours "$mix-json" "$base.log" "decode --json"
                peer "$mix-json" "tshark -T fields" "${TSHARK[*]} -r $base.pcap" ;;
            asc)
                ours "$mix-asc" "$base.asc" "decode --summary"
                peer "$mix-asc" "python-can ASCReader + canopen" "python3 bench/peer_python.py $base.asc" ;;
            blf)
                ours "$mix-blf" "$base.blf" "decode --summary"
                peer "$mix-blf" "python-can BLFReader + canopen" "python3 bench/peer_python.py $base.blf" ;;
            pcap)
                # The peer is the json step's tshark run.
                ours "$mix-pcap" "$base.pcap" "decode --summary" ;;
            memory) memory "$mix" ;;
            floor)
                load "$mix-floor"
                hyperfine --warmup 2 --runs "$RUNS" --export-json "$RESULTS/$mix-floor.json" \
                    -n "cat" "cat $base.log" \
                    -n "read and parse (examples/read_log)" "$READ_LOG $base.log" \
                    -n "decode --summary" "$MOTIONWIRE decode --summary $base.log" >/dev/null ;;
            *) echo "unknown step: $s" >&2; exit 2 ;;
        esac
    done
}

table() {
    python3 - "$RESULTS" <<'EOF'
import json, os, sys
results = sys.argv[1]
figures = [  # (step, peer step, what, goal)
    ("summary", "summary", "`decode --summary` vs python-can + canopen", 150),
    ("json", "json", "`decode --json` vs `tshark -T fields`", 30),
    ("asc", "asc", "ASC `--summary` vs python-can `ASCReader` + canopen", 50),
    ("blf", "blf", "BLF `--summary` vs python-can `BLFReader` + canopen", 20),
    ("pcap", "json", "pcap `--summary` vs `tshark -T fields`", 100),
]
def read(name):
    path = os.path.join(results, name + ".json")
    if not os.path.exists(path):
        return None
    runs = json.load(open(path))["results"]
    load = open(os.path.join(results, name + ".load")).read().split()[0]
    return runs, load
mixes = [m for m in ("sample", "storm", "pdo", "sdo", "fd")
         if os.path.exists(os.path.join(results, m + "-summary.json"))]
print("| mix | figure | goal | motionwire (mean ± σ, min) | peer | ratio (means) | before → now | load |")
print("|---|---|---|---|---|---|---|---|")
for mix in mixes:
    for step, peer_step, what, goal in figures:
        ours = read(f"{mix}-{step}")
        peer = read(f"{mix}-{peer_step}-peer")
        if ours is None:
            continue
        runs, load = ours
        now = runs[0]
        cell = f"{now['mean']*1e3:.1f} ms ± {now['stddev']*1e3:.1f}, {now['min']*1e3:.1f}"
        before = ""
        for r in runs[1:]:
            before = f"{r['mean']*1e3:.1f} → {now['mean']*1e3:.1f} ms ({r['mean']/now['mean']:.2f}×)"
        if peer:
            p = peer[0][0]
            ratio = p["mean"] / now["mean"]
            verdict = "met" if ratio >= goal else "missed"
            pcell = f"{p['mean']:.2f} s ({len(p['times'])} run{'s' if len(p['times']) > 1 else ''})"
            rcell = f"**{ratio:.0f}×** {verdict}"
            load = f"{load} / {peer[1]}"
        else:
            pcell, rcell = "—", "—"
        print(f"| {mix} | {what} | ≥ {goal}× | {cell} | {pcell} | {rcell} | {before} | {load} |")
floors = [m for m in mixes if os.path.exists(os.path.join(results, m + "-floor.json"))]
if floors:
    print()
    print("| mix | `cat` | reading and parsing | `decode --summary` | the summary beyond the parse | load |")
    print("|---|---|---|---|---|---|")
for mix in floors:
    runs, load = read(f"{mix}-floor")
    cat, parse, summary = (r["mean"] * 1e3 for r in runs)
    print(f"| {mix} | {cat:.1f} ms | {parse:.1f} ms | {summary:.1f} ms "
          f"| {summary - parse:.1f} ms ({(summary - parse) / parse:.1f}× the parse) | {load} |")
EOF
}

mkdir -p "$RESULTS"
if [[ ${1:-} == table ]]; then
    table
    exit
fi
[[ -x $MOTIONWIRE ]] || { echo "error: $MOTIONWIRE not built (cargo build --release --features cli)" >&2; exit 1; }
if [[ " $STEPS " == *" floor "* && ! -x $READ_LOG ]]; then
    echo "error: $READ_LOG not built (cargo build --release --example read_log --features logs)" >&2
    exit 1
fi
if [[ $# -eq 0 ]]; then
    set -- sample storm pdo sdo fd
fi
for mix in "$@"; do
    run_mix "$mix"
done
table
