#!/usr/bin/env bash
# Writes tests/fixtures/candump_screen/*.txt, candump's screen output with the
# option sets of docs/formats.md#candump-screen (-t a|A|d|z, -N, -x, -e, -a, -8,
# -c, -S, -i), and beside each a .json with what every printed line holds.
#
# The lines are made by can-utils' own formatting code (lib.c) and candump.c's
# line assembly, reproduced in scripts/candump_screen/driver.c: candump itself
# needs a CAN socket (vcan), which a container usually lacks.
#
#   scripts/gen_candump_screen_fixtures.sh CAN_UTILS_SOURCE_DIR
#
# CAN_UTILS_SOURCE_DIR: a checkout of https://github.com/linux-can/can-utils
# (the fixtures were made from its master of 2026-11, lib.c as of that commit).
set -euo pipefail
src=${1:?usage: $0 CAN_UTILS_SOURCE_DIR}
here=$(cd "$(dirname "$0")" && pwd)
out="$here/../tests/fixtures/candump_screen"
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cc -O1 -std=gnu11 -I"$src/include" -I"$src" -o "$tmp/driver" \
    "$here/candump_screen/driver.c" "$src/lib.c"
# -t A prints local time; the reader reads it as UTC
# (docs/formats.md#candump-screen), so the fixture is made in UTC.
for mode in plain ta_x_e tA_a_8 td tz_N c3_ta c1_tA_N_a S i; do
    TZ=UTC "$tmp/driver" "$mode" "$out/$mode.txt" "$out/$mode.json"
done
# can-utils' log2long (the installed one: Debian's can-utils) turns a
# candump log into the screen form with the ASCII column; the test reads
# both and compares them frame by frame.
if command -v log2long >/dev/null; then
    log2long < "$out/log2long_in.log" > "$out/log2long.txt"
fi
