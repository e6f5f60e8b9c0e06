#!/usr/bin/env bash
# Run every fuzz target of motionwire for a bounded time (libFuzzer through
# cargo-fuzz), failing on any crash or broken invariant.
#
#   fuzz/run.sh [SECONDS]          every target, SECONDS each (default 20)
#   fuzz/run.sh --long [SECONDS]   the long mode: every reader's target
#                                  (LONG_TARGETS below), SECONDS each
#                                  (default 300); same as FUZZ_LONG=1
#
# Prints one line per target and a closing count; exits non-zero when a
# target fails (its log and crashing input are named in its line; the input
# is kept under fuzz/artifacts/<target>/). Installs cargo-fuzz when missing.
#
# Environment:
#   FUZZ_LONG       1: the long mode, as --long.
#   FUZZ_SANITIZER  cargo-fuzz sanitizer, default "none": the library has no
#                   unsafe code, so AddressSanitizer adds little but halves the
#                   speed and needs a nightly toolchain ("address" works with one).
#   FUZZ_TARGETS    space-separated subset of targets, default all (the long
#                   mode: the readers' targets).
#   FUZZ_JOBS       targets fuzzed at once, default the number of cores.
#
# The committed seeds in fuzz/corpus/<target>/ are read only; new inputs go
# to fuzz/target/corpus/<target>/, which a later run on the same machine
# starts from: runs add up. 20 s finds what is shallow; some inputs need
# half a million runs and more (a 150 s run of candump_line found what
# every 20 s run had missed, issue 20), which the long mode gives the
# readers of outside files.
set -euo pipefail

# The targets that read outside files: each log format's reader, detection,
# the reading of any log, and the ENI reader.
LONG_TARGETS="candump_line asc_line trc_line pcap blf mf4 log_detect logs_read eni"

long="${FUZZ_LONG:-0}"
if [ "${1:-}" = "--long" ]; then
    long=1
    shift
fi
if [ "$long" = 1 ]; then
    seconds="${1:-300}"
    FUZZ_TARGETS="${FUZZ_TARGETS:-$LONG_TARGETS}"
else
    seconds="${1:-20}"
fi
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
    echo "usage: fuzz/run.sh [--long] [SECONDS]   (SECONDS per target, a positive integer)" >&2
    exit 2
fi
sanitizer="${FUZZ_SANITIZER:-none}"

cd "$(dirname "$0")"

# cargo-fuzz's sanitizer flags need nightly; with no sanitizer the stable
# toolchain works too, so use nightly only when it is installed.
toolchain=()
if command -v rustup >/dev/null 2>&1 && rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
    toolchain=(+nightly)
elif [ "$sanitizer" != none ]; then
    echo "fuzz: FUZZ_SANITIZER=$sanitizer needs a nightly toolchain, none is installed" >&2
    exit 2
fi

if ! cargo "${toolchain[@]}" fuzz --version >/dev/null 2>&1; then
    echo "fuzz: installing cargo-fuzz from crates.io"
    cargo install cargo-fuzz --locked --quiet
fi

# -a: debug assertions and overflow checks on, so that an arithmetic
# overflow on outside data is a crash as the crate's rules say.
flags=(--sanitizer "$sanitizer" --debug-assertions)

start=$(date +%s)
if ! build_log=$(cargo "${toolchain[@]}" fuzz build "${flags[@]}" 2>&1); then
    echo "$build_log" | tail -n 40
    echo "fuzz: build failed"
    exit 1
fi
echo "fuzz: built every target in $(( $(date +%s) - start )) s ($(cargo "${toolchain[@]}" fuzz --version), sanitizer $sanitizer)"

if [ -n "${FUZZ_TARGETS:-}" ]; then
    read -r -a targets <<< "$FUZZ_TARGETS"
else
    mapfile -t targets < <(cargo "${toolchain[@]}" fuzz list)
fi

# Run one target; its exit status goes to target/logs/<target>.status.
run_target() {
    local target="$1" status=0
    local work="target/corpus/$target" log="target/logs/$target.log"
    mkdir -p "$work" "corpus/$target"
    cargo "${toolchain[@]}" fuzz run "${flags[@]}" "$target" "$work" "corpus/$target" -- \
        -max_total_time="$seconds" -timeout=10 -print_final_stats=1 >"$log" 2>&1 || status=$?
    echo "$status" >"target/logs/$target.status"
}

# Print one target's line; return its status.
report() {
    local target="$1" log="target/logs/$1.log" status runs speed cov artifact
    status=$(cat "target/logs/$target.status" 2>/dev/null || echo 1)
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
    cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -n 1 | grep -oE '[0-9]+' || true)
    if [ "$status" -eq 0 ]; then
        echo "fuzz $target: ok, ${runs:-?} runs in ${seconds} s (${speed:-?} exec/s, coverage ${cov:-?} edges)"
    else
        artifact=$(grep -oE 'artifacts/[^ ]+' "$log" | tail -n 1 || true)
        echo "fuzz $target: FAILED (exit $status) after ${runs:-?} runs; input ${artifact:+fuzz/}${artifact:-none saved}; log fuzz/$log"
        grep -E "panicked at|assertion|left:|right:|ERROR: libFuzzer" "$log" | head -n 8 | sed 's/^/    /'
    fi
    return "$status"
}

# libFuzzer runs on one core: run as many targets at once as there are
# cores (FUZZ_JOBS overrides), each for the full time.
jobs="${FUZZ_JOBS:-$(nproc 2>/dev/null || echo 1)}"
if ! [[ "$jobs" =~ ^[0-9]+$ ]] || [ "$jobs" -lt 1 ]; then
    jobs=1
fi
mkdir -p target/logs
passed=0
failed=0
for ((i = 0; i < ${#targets[@]}; i += jobs)); do
    batch=("${targets[@]:i:jobs}")
    for target in "${batch[@]}"; do
        rm -f "target/logs/$target.status"
        run_target "$target" &
    done
    wait
    for target in "${batch[@]}"; do
        if report "$target"; then
            passed=$((passed + 1))
        else
            failed=$((failed + 1))
        fi
    done
done

echo "fuzz: ${#targets[@]} targets, $(( $(date +%s) - start )) s in all"
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
