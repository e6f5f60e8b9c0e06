#!/usr/bin/env bash
# Peer benchmark for `motionwire decode` (docs/output.md#json).
#
# Goals (issue 10): `decode --summary` at least 150x faster than a python
# peer (python-can + python-canopen, bench/peer_python.py), and
# `decode --json` at least 30x faster than tshark dissecting the same frames
# as CANopen, whether tshark writes JSON (-T json) or only the fields that
# match our keys (-T fields). With MOTIONWIRE_BEFORE set to another build of
# the program (e.g. the previous release), it runs in the same hyperfine
# session, so the change is measured in one run. Inputs: a 1 000 000-frame candump log and the same frames as a
# SocketCAN pcap, both made by scripts/gen_canlog.py.
#
# Usage: bench/run.sh [STEP...]
#   all          (default) setup build gen verify-tshark summary json ratios
#   setup        install hyperfine, tshark (apt) and python-can, canopen (pip)
#   build        cargo build --release --features cli
#   gen          write $BENCH_DIR/1m.log and 1m.pcap (skipped when up to date)
#   verify-tshark  check that tshark dissects the sample's EMCYs as CANopen EMCY
#   summary      hyperfine: motionwire decode --summary  vs  python peer
#   json         hyperfine: motionwire decode --json     vs  tshark -T json
#   json-fields  hyperfine: motionwire decode --json     vs  tshark -T fields
#   python-only  hyperfine: the python peer alone (no motionwire needed)
#   tshark-only  hyperfine: tshark alone (no motionwire needed)
#   peers        setup gen verify-tshark python-only tshark-only
#   ratios       print peer/motionwire ratios from bench/results/*.json
#   gen-formats  write $BENCH_DIR/1m.asc and 1m.blf from 1m.log with python-can
#   summary-asc  hyperfine: decode --summary on the ASC file vs python-can's ASCReader peer
#   summary-blf  hyperfine: decode --summary on the BLF file vs python-can's BLFReader peer
#   summary-pcap hyperfine: decode --summary on the pcap vs tshark -T fields
#   gen-mf4      write $BENCH_DIR/1m.mf4 from 1m.log with asammdf (python-can's MF4Writer layout)
#   summary-mf4  hyperfine: decode --summary on the MF4 file vs python-can's MF4Reader peer
#   read-mf4     hyperfine: reading the MF4 file alone: logs::open (examples/read_log)
#                vs python-can's MF4Reader vs asammdf reading every CAN_DataFrame channel
#   gen-report   write the report's other mixes: $BENCH_DIR/storm.log (scripts/gen_storm.py),
#                drives.log (scripts/gen_drives.py), screen.log (gen_canlog.py --format screen)
#   report       hyperfine: motionwire report vs decode --summary, same options, on 1m.log,
#                storm.log, drives.log and screen.log, each pair in one session; the page's
#                size and the goals (issue 23: <= 5 MB, <= 3x decode --summary's time)
#
# Environment: BENCH_DIR (default /tmp/motionwire-bench), BENCH_FRAMES
# (default 1000000), BENCH_RUNS (default 3; the report step: REPORT_RUNS,
# default 20), MOTIONWIRE (default
# target/release/motionwire), MOTIONWIRE_BEFORE (optional, a second build).
set -euo pipefail
cd "$(dirname "$0")/.."

BENCH_DIR=${BENCH_DIR:-/tmp/motionwire-bench}
FRAMES=${BENCH_FRAMES:-1000000}
RUNS=${BENCH_RUNS:-3}
MOTIONWIRE=${MOTIONWIRE:-target/release/motionwire}
MOTIONWIRE_BEFORE=${MOTIONWIRE_BEFORE:-}
# tshark -T fields with the fields that match decode --json's keys
# (docs/output.md#json).
TSHARK_FIELDS=(-T fields -E separator=, -e frame.number -e frame.time_epoch -e can.id
    -e can.flags.xtd -e can.flags.rtr -e can.len -e data.data -e canopen.function_code
    -e canopen.node_id -e canopen.em.err_code -e canopen.em.err_reg -e canopen.nmt_guard.state
    -e canopen.nmt_guard.toggle)
RESULTS=bench/results
LOG=$BENCH_DIR/1m.log
PCAP=$BENCH_DIR/1m.pcap
ASC=$BENCH_DIR/1m.asc
BLF=$BENCH_DIR/1m.blf
MF4=$BENCH_DIR/1m.mf4
STORM=$BENCH_DIR/storm.log
DRIVES=$BENCH_DIR/drives.log
SCREEN=$BENCH_DIR/screen.log
REPORT_RUNS=${REPORT_RUNS:-20}
# Wireshark's SocketCAN dissector hands the payload to the dissector chosen in
# its "can.subdissector" Decode-As table; without this it guesses (heuristics,
# e.g. AUTOSAR NM) or shows raw CAN data.
TSHARK_CANOPEN=(-d can.subdissector,canopen)

step() { printf '\n==> %s\n' "$*"; }

setup() {
    step "setup: hyperfine, tshark, python-can, canopen"
    if ! command -v hyperfine >/dev/null || ! command -v tshark >/dev/null; then
        apt-get update
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q hyperfine tshark
    fi
    if ! python3 -c 'import can, canopen' 2>/dev/null; then
        python3 -m pip install -q python-can canopen
    fi
    hyperfine --version
    tshark --version 2>/dev/null | head -n 1
    python3 -c 'import can, canopen; print("python-can", can.__version__, "canopen", canopen.__version__)'
}

build() {
    step "cargo build --release --features cli"
    cargo build --release --features cli
}

gen() {
    step "generate $FRAMES frames: $LOG, $PCAP"
    mkdir -p "$BENCH_DIR"
    if [[ -s $LOG && -s $PCAP && $LOG -nt scripts/gen_canlog.py && $PCAP -nt scripts/gen_canlog.py
          && $(wc -l <"$LOG") -eq $FRAMES ]]; then
        echo "up to date"
        return
    fi
    local start end
    start=$(date +%s.%N)
    python3 scripts/gen_canlog.py --frames "$FRAMES" -o "$LOG" --pcap "$PCAP"
    end=$(date +%s.%N)
    python3 -c "import sys; s=float(sys.argv[2])-float(sys.argv[1]); print(f'{int(sys.argv[3])} frames (log + pcap) in {s:.2f} s, {int(sys.argv[3])/s:,.0f} frames/s')" "$start" "$end" "$FRAMES"
    ls -l "$LOG" "$PCAP"
}

gen_formats() {
    gen
    step "the same frames as Vector ASC and BLF, written by python-can: $ASC, $BLF"
    if [[ -s $ASC && -s $BLF && $ASC -nt $LOG && $BLF -nt $LOG ]]; then
        echo "up to date"
        return
    fi
    python3 bench/convert_python_can.py "$LOG" "$ASC" "$BLF"
    ls -l "$ASC" "$BLF"
}

gen_mf4() {
    gen
    step "the same frames as ASAM MDF 4, written by asammdf: $MF4"
    if [[ -s $MF4 && $MF4 -nt $LOG && $MF4 -nt bench/convert_mf4.py ]]; then
        echo "up to date"
        return
    fi
    python3 -c 'import asammdf' 2>/dev/null || python3 -m pip install -q asammdf
    python3 bench/convert_mf4.py "$LOG" "$MF4"
    ls -l "$MF4"
}

read_mf4() {
    gen_mf4
    step "cargo build --release --example read_log --features logs"
    cargo build --release --example read_log --features logs
    step "hyperfine: reading $MF4 alone ($FRAMES frames)"
    mkdir -p "$RESULTS"
    hyperfine --warmup 1 --runs "$RUNS" \
        --export-markdown "$RESULTS/read-mf4.md" --export-json "$RESULTS/read-mf4.json" \
        -n "motionwire logs::open (examples/read_log)" "target/release/examples/read_log $MF4 >/dev/null" \
        -n "python-can MF4Reader" "python3 -c 'import can,sys; n=sum(1 for _ in can.MF4Reader(sys.argv[1])); print(n)' $MF4 >/dev/null" \
        -n "asammdf MDF.get (every CAN_DataFrame channel)" "python3 -c 'import asammdf,sys; m=asammdf.MDF(sys.argv[1]); [m.get(c.name, 0) for c in m.groups[0].channels]' $MF4 >/dev/null 2>&1"
}

# One hyperfine run: decode --summary of FILE against PEER (a command).
summary_of() {
    local name=$1 file=$2 peer_name=$3 peer=$4
    need_motionwire
    step "hyperfine: decode --summary on $file vs $peer_name ($FRAMES frames)"
    mkdir -p "$RESULTS"
    hyperfine --warmup 1 --runs "$RUNS" \
        --export-markdown "$RESULTS/$name.md" --export-json "$RESULTS/$name.json" \
        -n "motionwire decode --summary" "$MOTIONWIRE decode --summary $file >/dev/null" \
        -n "$peer_name" "$peer >/dev/null 2>&1"
}

gen_report() {
    gen
    step "the report's other mixes, $FRAMES frames each: $STORM, $DRIVES, $SCREEN"
    if [[ ! ( -s $STORM && $STORM -nt scripts/gen_storm.py ) ]]; then
        python3 scripts/gen_storm.py --frames "$FRAMES" -o "$STORM"
    fi
    if [[ ! ( -s $DRIVES && $DRIVES -nt scripts/gen_drives.py ) ]]; then
        python3 scripts/gen_drives.py --frames "$FRAMES" -o "$DRIVES"
    fi
    if [[ ! ( -s $SCREEN && $SCREEN -nt scripts/gen_canlog.py ) ]]; then
        python3 scripts/gen_canlog.py --frames "$FRAMES" --format screen -o "$SCREEN"
    fi
    ls -l "$LOG" "$STORM" "$DRIVES" "$SCREEN"
}

# One hyperfine session: decode --summary and report with the same OPTIONS
# on FILE, then the page's size.
report_of() {
    local mix=$1 file=$2 opts=$3
    local page=$BENCH_DIR/report-$mix.html
    step "hyperfine: report vs decode --summary on $file ($mix; load: $(cut -d' ' -f1-3 /proc/loadavg))"
    mkdir -p "$RESULTS"
    hyperfine -N --warmup 2 --runs "$REPORT_RUNS" \
        --export-markdown "$RESULTS/report-$mix.md" --export-json "$RESULTS/report-$mix.json" \
        -n "decode --summary" "$MOTIONWIRE decode --summary $opts $file" \
        -n "report" "$MOTIONWIRE report $opts $file -o $page"
    echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
    stat -c '%s' "$page" >"$RESULTS/report-$mix.size"
}

report() {
    need_motionwire
    report_of sample "$LOG" "--profile 3=akd,5=baumer --heartbeat-ms 300"
    report_of storm "$STORM" "--heartbeat-ms 300"
    report_of drives "$DRIVES" "--heartbeat-ms 300"
    report_of screen "$SCREEN" "--profile 3=akd,5=baumer --heartbeat-ms 300"
    step "the report's goals: a page <= 5 MB, written in <= 3x decode --summary's time"
    python3 - "$RESULTS" <<'EOF'
import json, os, sys
results = sys.argv[1]
failed = False
for mix in ("sample", "storm", "drives", "screen"):
    runs = {r["command"]: r for r in json.load(open(os.path.join(results, f"report-{mix}.json")))["results"]}
    summary, report = runs["decode --summary"], runs["report"]
    size = int(open(os.path.join(results, f"report-{mix}.size")).read())
    ratio = report["median"] / summary["median"]
    ok = ratio <= 3.0 and size <= 5_000_000
    failed |= not ok
    print(f"{mix}: decode --summary {summary['median'] * 1e3:.1f} ms, report {report['median'] * 1e3:.1f} ms "
          f"(medians), {ratio:.2f}x; page {size:,} bytes: {'OK' if ok else 'GOAL MISSED'}")
sys.exit(1 if failed else 0)
EOF
}

verify_tshark() {
    step "verify: tshark ${TSHARK_CANOPEN[*]} dissects EMCYs as CANopen EMCY"
    mkdir -p "$BENCH_DIR"
    python3 scripts/gen_canlog.py --no-text --pcap "$BENCH_DIR/machine.pcap"
    local out
    out=$(tshark -r "$BENCH_DIR/machine.pcap" "${TSHARK_CANOPEN[@]}" -V -Y 'canopen.em.err_code' 2>/dev/null)
    grep -m1 -F 'Error code: Communication - CAN in error passive mode (0x8120)' <<<"$out"
    grep -m1 -F 'Error code: Error reset or no error (0x0000)' <<<"$out"
    local n
    n=$(grep -c -F 'Type: EMCY' <<<"$out" || true)
    echo "EMCY frames dissected as CANopen EMCY: $n"
    [[ $n -gt 0 ]]
}

need_motionwire() {
    if [[ ! -x $MOTIONWIRE ]]; then
        echo "error: $MOTIONWIRE not built (run: bench/run.sh build); the CLI (docs/output.md) must exist" >&2
        exit 1
    fi
}

# The previous build as a third command, when MOTIONWIRE_BEFORE is set.
before() {
    local args=$1
    if [[ -n $MOTIONWIRE_BEFORE ]]; then
        printf '%s\n' -n "before: motionwire $args" "$MOTIONWIRE_BEFORE $args $LOG >/dev/null"
    fi
}

summary() {
    need_motionwire
    step "hyperfine: decode --summary vs python peer ($FRAMES frames)"
    mkdir -p "$RESULTS"
    local extra=()
    mapfile -t extra < <(before "decode --summary")
    hyperfine --warmup 1 --runs "$RUNS" \
        --export-markdown "$RESULTS/summary.md" --export-json "$RESULTS/summary.json" \
        -n "motionwire decode --summary" "$MOTIONWIRE decode --summary $LOG >/dev/null" \
        "${extra[@]}" \
        -n "python-can + canopen peer" "python3 bench/peer_python.py $LOG >/dev/null"
}

json() {
    need_motionwire
    step "hyperfine: decode --json vs tshark -T json ($FRAMES frames)"
    mkdir -p "$RESULTS"
    local extra=()
    mapfile -t extra < <(before "decode --json")
    hyperfine --runs "$RUNS" \
        --export-markdown "$RESULTS/json.md" --export-json "$RESULTS/json.json" \
        -n "motionwire decode --json" "$MOTIONWIRE decode --json $LOG >/dev/null" \
        "${extra[@]}" \
        -n "tshark -T json (CANopen)" "tshark -r $PCAP ${TSHARK_CANOPEN[*]} -T json >/dev/null 2>&1"
}

json_fields() {
    need_motionwire
    step "hyperfine: decode --json vs tshark -T fields ($FRAMES frames)"
    mkdir -p "$RESULTS"
    hyperfine --runs "$RUNS" \
        --export-markdown "$RESULTS/json-fields.md" --export-json "$RESULTS/json-fields.json" \
        -n "motionwire decode --json" "$MOTIONWIRE decode --json $LOG >/dev/null" \
        -n "tshark -T fields (CANopen)" "tshark -r $PCAP ${TSHARK_CANOPEN[*]} ${TSHARK_FIELDS[*]} >/dev/null 2>&1"
}

python_only() {
    step "hyperfine: python peer alone ($FRAMES frames)"
    mkdir -p "$RESULTS"
    hyperfine --warmup 1 --runs "$RUNS" \
        --export-markdown "$RESULTS/python-only.md" --export-json "$RESULTS/python-only.json" \
        -n "python-can + canopen peer" "python3 bench/peer_python.py $LOG >/dev/null"
}

tshark_only() {
    step "hyperfine: tshark alone ($FRAMES frames)"
    mkdir -p "$RESULTS"
    hyperfine --runs "$RUNS" \
        --export-markdown "$RESULTS/tshark-only.md" --export-json "$RESULTS/tshark-only.json" \
        -n "tshark -T json (CANopen)" "tshark -r $PCAP ${TSHARK_CANOPEN[*]} -T json >/dev/null 2>&1"
}

ratios() {
    step "ratios (peer mean / motionwire mean)"
    python3 - "$RESULTS" <<'EOF'
import json, os, sys
results = sys.argv[1]
goals = {"summary": 150.0, "json": 30.0, "json-fields": 30.0,
         "summary-asc": 50.0, "summary-blf": 20.0, "summary-pcap": 100.0,
         "summary-mf4": 20.0, "read-mf4": 1.0}
failed = False
for name, goal in goals.items():
    path = os.path.join(results, f"{name}.json")
    if not os.path.exists(path):
        print(f"{name}: no results ({path} missing)")
        continue
    runs = json.load(open(path))["results"]
    ours = next(r for r in runs if r["command"].startswith("motionwire"))
    peer = next(r for r in runs if not r["command"].startswith(("motionwire", "before")))
    for old in (r for r in runs if r["command"].startswith("before")):
        print(f"{name}: {old['command']} {old['mean']:.3f} s -> {ours['mean']:.4f} s "
              f"({old['mean'] / ours['mean']:.1f}x faster)")
    ratio = peer["mean"] / ours["mean"]
    verdict = "OK" if ratio >= goal else "BELOW GOAL"
    failed |= ratio < goal
    print(f"{name}: {peer['command']} {peer['mean']:.3f} s / "
          f"{ours['command']} {ours['mean']:.4f} s = {ratio:.1f}x (goal >= {goal:.0f}x) {verdict}")
for name in ("python-only", "tshark-only"):
    path = os.path.join(results, f"{name}.json")
    if os.path.exists(path):
        r = json.load(open(path))["results"][0]
        print(f"{name}: {r['command']} mean {r['mean']:.2f} s (min {r['min']:.2f}, max {r['max']:.2f}, {len(r['times'])} runs)")
sys.exit(1 if failed else 0)
EOF
}

run_step() {
    case $1 in
        all) setup; build; gen; verify_tshark; summary; json; json_fields; ratios ;;
        peers) setup; gen; verify_tshark; python_only; tshark_only; ratios ;;
        setup) setup ;;
        build) build ;;
        gen) gen ;;
        verify-tshark) verify_tshark ;;
        summary) gen; summary ;;
        json) gen; json ;;
        json-fields) gen; json_fields ;;
        python-only) gen; python_only ;;
        tshark-only) gen; tshark_only ;;
        ratios) ratios ;;
        gen-formats) gen_formats ;;
        summary-asc) gen_formats; summary_of summary-asc "$ASC" "python-can ASCReader + canopen peer" "python3 bench/peer_python.py $ASC" ;;
        summary-blf) gen_formats; summary_of summary-blf "$BLF" "python-can BLFReader + canopen peer" "python3 bench/peer_python.py $BLF" ;;
        gen-mf4) gen_mf4 ;;
        summary-mf4) gen_mf4; summary_of summary-mf4 "$MF4" "python-can MF4Reader + canopen peer" "python3 bench/peer_python.py $MF4" ;;
        read-mf4) read_mf4 ;;
        gen-report) gen_report ;;
        report) gen_report; report ;;
        summary-pcap) gen; summary_of summary-pcap "$PCAP" "tshark -T fields (CANopen)" "tshark -r $PCAP ${TSHARK_CANOPEN[*]} ${TSHARK_FIELDS[*]}" ;;
        *) echo "unknown step: $1 (see the header of $0)" >&2; exit 2 ;;
    esac
}

if [[ $# -eq 0 ]]; then
    set -- all
fi
for s in "$@"; do
    run_step "$s"
done
