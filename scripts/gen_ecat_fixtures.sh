#!/usr/bin/env bash
# The synthetic EtherCAT fixtures of tests/data/ethercat (README there) and
# tshark's dissection of every capture in that folder:
#
#   synthetic_akd_fault.pcapng     scripts/ecat_pcapng.py
#   drives.pcapng, drives.model.jsonl, drives.eni.xml
#                                  examples/ecat_drives.rs, 1 000 cycles
#   NAME.tshark.tsv, NAME.coe.tsv  scripts/ecat_oracle.py --verify
#
# Deterministic: the same bytes on every run (the oracles for the same
# tshark version, which the README names).
#   bash scripts/gen_ecat_fixtures.sh
set -euo pipefail
cd "$(dirname "$0")/.."
data=tests/data/ethercat
python3 scripts/ecat_pcapng.py --out "$data/synthetic_akd_fault.pcapng"
cargo run --quiet --release --example ecat_drives -- --cycles 1000 \
  --out "$data/drives.pcapng" --model "$data/drives.model.jsonl" \
  --eni "$data/drives.eni.xml"
python3 scripts/ecat_oracle.py --verify
