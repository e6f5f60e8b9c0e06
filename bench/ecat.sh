#!/usr/bin/env bash
# Issue 35: SPEC §12.7's speed goals for EtherCAT captures on every traffic
# mix of bench/gen_ecat.py (BENCHMARKS.md, "EtherCAT captures (issue 35)").
#
# For each mix, from one capture of 1 000 000 datagrams written by
# bench/gen_ecat.py (and one of 100 000 for the memory step):
#
#   time     one hyperfine session of
#              decode --summary F          (today: counts EtherCAT packets)
#              decode --json F >/dev/null
#              decode F >/dev/null         (the text records)
#              cat F >/dev/null            (the read from the page cache)
#              cat F | cat >/dev/null      (the capture's bytes through a pipe)
#              decode --json F | cat >/dev/null
#              cat J | cat >/dev/null      (J: decode --json's output, kept
#                                           in a file: the same bytes piped)
#              decode --json F >FILE, cat J >FILE  (into a file in BENCH_DIR)
#              tshark -T fields            (the peer: the fields below)
#            the goals: tshark / --summary ≥ 50×, tshark / --json ≥ 10×,
#            --json within 1.5× of cat piping the same bytes: read both
#            ways, --json / cat F and --json | cat / cat J | cat
#   memory   peak resident memory (/usr/bin/time -f %M) of decode --summary,
#            --json and text at 100 000 and 1 000 000 datagrams, and of
#            --json into a pipe (where a thread of its own writes it)
#
# Every command runs BENCH_RUNS times after one warm-up, tshark included
# (a second each). The load average is recorded before each step: compare
# the ratios within a session, not times across runs. With
# MOTIONWIRE_BEFORE set to another build (e.g. main's), its --summary,
# --json, text and --json | cat run in the same session.
#
# Usage: bench/ecat.sh [MIX...]        (default: cyclic fault sdo)
#        bench/ecat.sh table           print the table from the results
# Environment: BENCH_DIR (default /tmp/motionwire-bench/ecat),
# BENCH_DATAGRAMS (default 1000000), BENCH_RUNS (default 5), MOTIONWIRE
# (default target/release/motionwire: cargo build --release --features
# cli), MOTIONWIRE_BEFORE (optional), STEPS (default "time memory").
set -euo pipefail
cd "$(dirname "$0")/.."

BENCH_DIR=${BENCH_DIR:-/tmp/motionwire-bench/ecat}
DATAGRAMS=${BENCH_DATAGRAMS:-1000000}
RUNS=${BENCH_RUNS:-5}
MOTIONWIRE=${MOTIONWIRE:-target/release/motionwire}
MOTIONWIRE_BEFORE=${MOTIONWIRE_BEFORE:-}
STEPS=${STEPS:-time memory}
RESULTS=bench/results/ecat
# SPEC §12.7's command: one row per datagram.
TSHARK=(tshark -T fields -e frame.number -e ecat.cmd -e ecat.idx -e ecat.adp -e ecat.ado
    -e ecat.lad -e ecat.cnt)

step() { printf '\n==> %s (load average %s)\n' "$*" "$(cut -d' ' -f1-3 /proc/loadavg)"; }

# The step's load average, kept beside its hyperfine export.
load() { cut -d' ' -f1-3 /proc/loadavg >"$RESULTS/$1.load"; }

inputs() {
    local mix=$1 base=$BENCH_DIR/$1
    mkdir -p "$BENCH_DIR"
    if [[ ! -s $base.pcapng ]]; then
        python3 bench/gen_ecat.py "$mix" --datagrams "$DATAGRAMS" -o "$base.pcapng"
    fi
    if [[ ! -s $base.json ]]; then
        "$MOTIONWIRE" decode --json "$base.pcapng" >"$base.json" 2>/dev/null
    fi
    if [[ ! -s $base-100k.pcapng ]]; then
        python3 bench/gen_ecat.py "$mix" --datagrams 100000 -o "$base-100k.pcapng"
    fi
}

time_mix() {
    local mix=$1 f=$BENCH_DIR/$1.pcapng j=$BENCH_DIR/$1.json
    local before=()
    if [[ -n $MOTIONWIRE_BEFORE ]]; then
        before=(-n "before: decode --summary" "$MOTIONWIRE_BEFORE decode --summary $f >/dev/null 2>&1"
            -n "before: decode --json" "$MOTIONWIRE_BEFORE decode --json $f >/dev/null 2>&1"
            -n "before: decode" "$MOTIONWIRE_BEFORE decode $f >/dev/null 2>&1"
            -n "before: decode --json | cat" "$MOTIONWIRE_BEFORE decode --json $f 2>/dev/null | cat >/dev/null")
    fi
    load "$mix-time"
    hyperfine --warmup 1 --runs "$RUNS" --export-json "$RESULTS/$mix-time.json" \
        -n "decode --summary" "$MOTIONWIRE decode --summary $f >/dev/null 2>&1" \
        -n "decode --json" "$MOTIONWIRE decode --json $f >/dev/null 2>&1" \
        -n "decode" "$MOTIONWIRE decode $f >/dev/null 2>&1" \
        -n "cat F >/dev/null" "cat $f >/dev/null" \
        -n "cat F | cat >/dev/null" "cat $f | cat >/dev/null" \
        -n "decode --json | cat" "$MOTIONWIRE decode --json $f 2>/dev/null | cat >/dev/null" \
        -n "cat J | cat >/dev/null" "cat $j | cat >/dev/null" \
        -n "decode --json >FILE" "$MOTIONWIRE decode --json $f >$BENCH_DIR/out.json 2>/dev/null" \
        -n "cat J >FILE" "cat $j >$BENCH_DIR/out.json" \
        -n "tshark -T fields" "${TSHARK[*]} -r $f >/dev/null 2>&1" \
        "${before[@]}"
    rm -f "$BENCH_DIR/out.json"
}

memory() {
    local mix=$1 base=$BENCH_DIR/$1 out=$RESULTS/$1-memory.txt
    : >"$out"
    for file in "$base-100k.pcapng" "$base.pcapng"; do
        for args in "decode --summary" "decode --json" "decode"; do
            local kb
            kb=$(/usr/bin/time -f %M "$MOTIONWIRE" $args "$file" 2>&1 >/dev/null | tail -n 1)
            printf '%s\t%s\t%s\n' "$(basename "$file")" "$args" "$kb" | tee -a "$out"
        done
        local kb
        /usr/bin/time -f %M -o "$out.kb" "$MOTIONWIRE" decode --json "$file" 2>/dev/null | cat >/dev/null
        kb=$(tail -n 1 "$out.kb")
        rm -f "$out.kb"
        printf '%s\t%s\t%s\n' "$(basename "$file")" "decode --json | cat" "$kb" | tee -a "$out"
    done
}

run_mix() {
    local mix=$1
    inputs "$mix"
    for s in $STEPS; do
        step "$mix: $s"
        case $s in
            time) time_mix "$mix" ;;
            memory) memory "$mix" ;;
            *) echo "unknown step: $s" >&2; exit 2 ;;
        esac
    done
}

table() {
    python3 - "$RESULTS" "$BENCH_DIR" <<'EOF'
import json, os, sys
results, inputs = sys.argv[1:]
mixes = [m for m in ("cyclic", "fault", "sdo")
         if os.path.exists(os.path.join(results, m + "-time.json"))]
def ms(r):
    return f"{r['mean']*1e3:.1f} ± {r['stddev']*1e3:.1f}"
print("Times in ms (mean ± σ), tshark in s; F the capture, J its JSON.")
print()
print("| mix | F, J | `--summary` | `--json` | text | `cat F` | `cat F \\| cat` | `--json \\| cat` | `cat J \\| cat` "
      "| tshark | tshark ÷ `--summary` (≥ 50×) | tshark ÷ `--json` (≥ 10×) | `--json` ÷ `cat F \\| cat` (≤ 1.5×) "
      "| `--json \\| cat` ÷ `cat J \\| cat` (≤ 1.5×) | load |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
befores = []
for mix in mixes:
    runs = {r["command"]: r for r in json.load(open(os.path.join(results, mix + "-time.json")))["results"]}
    load = open(os.path.join(results, mix + "-time.load")).read().split()[0]
    def size(ext):
        path = os.path.join(inputs, mix + ext)
        return f"{os.path.getsize(path)/1e6:.0f}" if os.path.exists(path) else "?"
    s, j, t = runs["decode --summary"], runs["decode --json"], runs["decode"]
    c, cc, ts = runs["cat F >/dev/null"], runs["cat F | cat >/dev/null"], runs["tshark -T fields"]
    jc, cj = runs["decode --json | cat"], runs["cat J | cat >/dev/null"]
    def goal(ratio, target, above):
        met = ratio >= target if above else ratio <= target
        return f"**{ratio:.1f}×** {'met' if met else 'missed'}"
    print(f"| {mix} | {size('.pcapng')}, {size('.json')} MB | {ms(s)} | {ms(j)} | {ms(t)} | {ms(c)} | {ms(cc)} "
          f"| {ms(jc)} | {ms(cj)} | {ts['mean']:.2f} ± {ts['stddev']:.2f} "
          f"| {goal(ts['mean']/s['mean'], 50, True)} | {goal(ts['mean']/j['mean'], 10, True)} "
          f"| {goal(j['mean']/cc['mean'], 1.5, False)} | {goal(jc['mean']/cj['mean'], 1.5, False)} | {load} |")
    for name in ("before: decode --summary", "before: decode --json", "before: decode",
                 "before: decode --json | cat"):
        if name in runs:
            now = runs[name.removeprefix("before: ")]
            shown = name.removeprefix("before: ").replace("|", "\\|")
            befores.append(f"| {mix} | `{shown}` | {ms(runs[name])} ms | {ms(now)} ms "
                           f"| {runs[name]['mean']/now['mean']:.2f}× | {load} |")
files = [(mix, runs) for mix in mixes
         for runs in [{r["command"]: r for r in json.load(open(os.path.join(results, mix + "-time.json")))["results"]}]
         if "cat J >FILE" in runs]
if files:
    print()
    print("| mix | `--json >FILE` | `cat J >FILE` | ratio |")
    print("|---|---|---|---|")
    for mix, runs in files:
        jf, cf = runs["decode --json >FILE"], runs["cat J >FILE"]
        print(f"| {mix} | {ms(jf)} | {ms(cf)} | {jf['mean']/cf['mean']:.2f}× |")
if befores:
    print()
    print("| mix | command | before | now | faster | load |")
    print("|---|---|---|---|---|---|")
    print("\n".join(befores))
mem = [m for m in mixes if os.path.exists(os.path.join(results, m + "-memory.txt"))]
if mem:
    print()
    print("| mix | command | peak RSS, 100 000 datagrams | 1 000 000 |")
    print("|---|---|---|---|")
for mix in mem:
    rows = [l.split("\t") for l in open(os.path.join(results, mix + "-memory.txt")).read().splitlines()]
    by = {}
    for f, args, kb in rows:
        by.setdefault(args, []).append(int(kb))
    for args, kbs in by.items():
        shown = args.replace("|", "\\|")
        print(f"| {mix} | `{shown}` | " + " | ".join(f"{kb/1024:.1f} MiB" for kb in kbs) + " |")
EOF
}

mkdir -p "$RESULTS"
if [[ ${1:-} == table ]]; then
    table
    exit
fi
[[ -x $MOTIONWIRE ]] || { echo "error: $MOTIONWIRE not built (cargo build --release --features cli)" >&2; exit 1; }
if [[ $# -eq 0 ]]; then
    set -- cyclic fault sdo
fi
for mix in "$@"; do
    run_mix "$mix"
done
table
