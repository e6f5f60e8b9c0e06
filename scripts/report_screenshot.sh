#!/usr/bin/env bash
# Make docs/report.png again: the top of the sample's report, as the README's
# third command writes it, photographed by headless chromium (Debian's
# `chromium` package, the browser of tests/program/report_browser.rs).
#
#     scripts/report_screenshot.sh            # writes docs/report.png
#     scripts/report_screenshot.sh shot.png   # writes shot.png
#
# The page is written in a scratch folder holding samples/machine.log, with
# the README's very command line, so that the page's "made by" line reads as
# the README does.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${1:-$repo/docs/report.png}")
browser=${CHROMIUM:-chromium}

cargo build --quiet --release --features cli --manifest-path "$repo/Cargo.toml"
bin="${CARGO_TARGET_DIR:-$repo/target}/release/motionwire"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/samples"
cp "$repo/samples/machine.log" "$work/samples/"
(cd "$work" && "$bin" report --profile 3=akd,5=baumer --heartbeat-ms 300 samples/machine.log -o machine.html)

"$browser" --headless --no-sandbox --disable-gpu --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --hide-scrollbars --user-data-dir="$work/profile" \
  --window-size=1240,1080 --screenshot="$out" "file://$work/machine.html" 2>/dev/null
echo "$out"
