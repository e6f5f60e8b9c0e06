#!/usr/bin/env bash
# Issue 36: the speed of EtherCAT process data (BENCHMARKS.md, "EtherCAT
# process data (issue 36)").
#
# Mixes, each a capture and the options that read it:
#
#   drives   examples/ecat_drives.rs: 1 000 000 cycles of a servo and two
#            CiA 402 drives (one LRW of 79 bytes and one BRD a frame, both
#            copies: 4 000 000 datagrams, 312 MB), read with
#            --servo 0x1001 and without
#   cyclic   bench/gen_ecat.py cyclic: replay-dc's LRW cycles, two output
#            terminals without PDO mapping (bytes only)
#   fault    bench/gen_ecat.py fault: synthetic_akd_fault repeated, one
#            AKD whose inputs come back short in a quarter of the cycles
#
# For each, one hyperfine session of decode --summary (with --servo for
# drives), the same without --servo (drives), decode --json --only
# process_data,servo, and tshark -T fields with the datagram fields of
# SPEC §12.7 (the peer); the goals of issue 36: tshark ÷ --summary --servo
# ≥ 25× and --summary --servo within 2× of --summary on drives. Then the
# peak resident memory of --summary --servo at 100 000 and 1 000 000
# cycles (constant in the capture's length).
#
# Usage: bench/ecat_process.sh [MIX...]   (default: drives cyclic fault)
#        bench/ecat_process.sh table      print the table from the results
# Environment: BENCH_DIR (default /tmp/motionwire-bench/ecat), BENCH_RUNS
# (default 3), MOTIONWIRE (default target/release/motionwire: cargo build
# --release --features cli).
set -euo pipefail
cd "$(dirname "$0")/.."

BENCH_DIR=${BENCH_DIR:-/tmp/motionwire-bench/ecat}
RUNS=${BENCH_RUNS:-3}
MOTIONWIRE=${MOTIONWIRE:-target/release/motionwire}
RESULTS=bench/results/ecat_process
TSHARK="tshark -T fields -e frame.number -e ecat.cmd -e ecat.idx -e ecat.adp -e ecat.ado -e ecat.lad -e ecat.cnt"

mkdir -p "$RESULTS" "$BENCH_DIR"

capture() {
    case $1 in
        drives)
            for cycles in 100000 1000000; do
                local f=$BENCH_DIR/drives-$cycles.pcapng
                if [[ ! -s $f ]]; then
                    cargo run --release -q --example ecat_drives -- --cycles "$cycles" \
                        --out "$f" --model "$BENCH_DIR/drives-$cycles.jsonl" \
                        --eni "$BENCH_DIR/drives-$cycles.xml" >&2
                fi
            done
            echo "$BENCH_DIR/drives-1000000.pcapng"
            ;;
        cyclic | fault)
            local f=$BENCH_DIR/$1.pcapng
            [[ -s $f ]] || python3 bench/gen_ecat.py "$1" --datagrams 1000000 -o "$f" >&2
            echo "$f"
            ;;
        *) echo "unknown mix: $1" >&2; exit 2 ;;
    esac
}

run_mix() {
    local mix=$1 f
    f=$(capture "$mix")
    local servo=()
    [[ $mix == drives ]] && servo=(--servo 0x1001)
    cut -d' ' -f1-3 /proc/loadavg >"$RESULTS/$mix.load"
    local without=()
    if [[ $mix == drives ]]; then
        without=(-n "decode --summary" "$MOTIONWIRE decode --summary $f >/dev/null 2>&1")
    fi
    hyperfine --warmup 1 --runs "$RUNS" --export-json "$RESULTS/$mix-time.json" \
        -n "decode --summary --servo" "$MOTIONWIRE decode --summary ${servo[*]} $f >/dev/null 2>&1" \
        "${without[@]}" \
        -n "decode --json process data" "$MOTIONWIRE decode --json ${servo[*]} --only process_data,servo $f >/dev/null 2>&1" \
        -n "tshark -T fields" "$TSHARK -r $f >/dev/null 2>&1"
    if [[ $mix == drives ]]; then
        : >"$RESULTS/drives-memory.txt"
        for cycles in 100000 1000000; do
            local kb
            kb=$(/usr/bin/time -f %M "$MOTIONWIRE" decode --summary --servo 0x1001 \
                "$BENCH_DIR/drives-$cycles.pcapng" 2>&1 >/dev/null | tail -n 1)
            printf '%s\t%s\n' "$cycles" "$kb" | tee -a "$RESULTS/drives-memory.txt"
        done
    fi
}

table() {
    python3 - "$RESULTS" <<'EOF'
import json, os, sys
results = sys.argv[1]
print("Times in s (mean ± σ); `--summary --servo` is `--summary` on the mixes without a servo.")
print()
print("| mix | `--summary --servo` | `--summary` | `--json --only process_data,servo` | tshark -T fields "
      "| tshark ÷ `--summary --servo` (≥ 25×) | `--servo` ÷ without (≤ 2×) | load |")
print("|---|---|---|---|---|---|---|---|")
for mix in ("drives", "cyclic", "fault"):
    path = os.path.join(results, mix + "-time.json")
    if not os.path.exists(path):
        continue
    runs = {r["command"]: r for r in json.load(open(path))["results"]}
    load = open(os.path.join(results, mix + ".load")).read().split()[0]
    s = lambda r: f"{r['mean']:.2f} ± {r['stddev']:.2f}"
    servo, tshark = runs["decode --summary --servo"], runs["tshark -T fields"]
    plain = runs.get("decode --summary")
    ratio = tshark["mean"] / servo["mean"]
    goal = f"**{ratio:.1f}×** {'met' if ratio >= 25 else 'missed'}" if mix == "drives" else f"{ratio:.1f}×"
    within = "—"
    if plain:
        r = servo["mean"] / plain["mean"]
        within = f"**{r:.2f}×** {'met' if r <= 2 else 'missed'}"
    print(f"| {mix} | {s(servo)} | {s(plain) if plain else '—'} | {s(runs['decode --json process data'])} "
          f"| {s(tshark)} | {goal} | {within} | {load} |")
mem = os.path.join(results, "drives-memory.txt")
if os.path.exists(mem):
    print()
    print("| cycles | peak RSS of `decode --summary --servo 0x1001`, KB |")
    print("|---|---|")
    for line in open(mem):
        cycles, kb = line.split()
        print(f"| {int(cycles):,} | {kb} |")
EOF
}

if [[ ${1:-} == table ]]; then
    table
    exit 0
fi
for mix in "${@:-drives cyclic fault}"; do
    for m in $mix; do run_mix "$m"; done
done
table
