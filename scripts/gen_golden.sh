#!/usr/bin/env bash
# The program's output on every fixture log and the sample, as a snapshot
# that `tests/program/golden.rs` compares byte for byte: the program's output
# changes only on purpose. Each line of tests/golden/cases.txt is one
# command line (arguments after `motionwire`); its stdout, stderr and exit
# status are kept gzip-compressed in tests/golden/NAME.gz, NAME the case's
# arguments joined by `_`, `tests/fixtures/` left out and every other `/`
# and every `:` written `-`, a name every file system holds (`golden_name`
# in tests/common/mod.rs, the same rule): adding a case adds one file and
# renames none.
#
# Made with the build of commit c5dd14a (before the move); run it again only
# when the output is meant to change, and say so in the CHANGELOG.
#   bash scripts/gen_golden.sh [path/to/motionwire]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/motionwire}
[ -x "$bin" ] || cargo build --release --features cli
out=tests/golden
rm -f "$out"/*.gz
logs=(
  samples/machine.log
  tests/fixtures/python_can.log
  tests/fixtures/sdo/python_canopen.log
  tests/fixtures/sdo/broken.log
  tests/fixtures/sdo/python_canopen.pcap
  tests/fixtures/sdo/broken.pcap
  tests/fixtures/pdo/python_canopen.log
  tests/fixtures/pcap/can.pcap
  tests/fixtures/pcap/can.pcapng
  tests/fixtures/pcap/can_be.pcap
  tests/fixtures/pcap/can_ns.pcap
  tests/fixtures/pcap/multi.pcapng
  tests/fixtures/blf/python_can.blf
  tests/fixtures/blf/python_can_many.blf
  tests/fixtures/blf/python_can_stored.blf
)
for f in tests/fixtures/asc/*.asc tests/fixtures/asc/*.log tests/fixtures/trc/*.trc \
         tests/fixtures/candump_screen/*.txt tests/fixtures/candump_screen/*.log; do
  logs+=("$f")
done
{
  for log in "${logs[@]}"; do
    echo "decode $log"
    echo "decode --json $log"
    echo "decode --csv $log"
    echo "decode --summary $log"
    echo "decode --summary --json --heartbeat-ms 300 $log"
  done
  echo "decode --summary --heartbeat-ms 300 samples/machine.log"
  echo "decode --json --profile 3=akd,5=baumer samples/machine.log"
  echo "decode --profile 3=akd,5=baumer samples/machine.log"
  echo "decode --summary --json --heartbeat-ms 300 --profile 3=akd,5=baumer samples/machine.log"
  echo "decode --summary --heartbeat-ms 300 --profile akd samples/machine.log"
  echo "decode --json --only sdo,pdo --node 3 samples/machine.log"
  echo "decode --id 0x000-0x080,0x705 samples/machine.log"
  echo "decode --json --eds 3=tests/fixtures/pdo/drive.eds tests/fixtures/pdo/python_canopen.log"
  echo "decode --eds 3=tests/fixtures/pdo/drive.eds tests/fixtures/pdo/python_canopen.log"
  echo "decode --summary --json --eds 3=tests/fixtures/pdo/drive.eds tests/fixtures/pdo/python_canopen.log"
  echo "decode --summary --eds 3=tests/fixtures/pdo/drive.eds tests/fixtures/pdo/python_canopen.log"
  echo "decode --json --profile akd tests/fixtures/pdo/python_canopen.log"
  echo "decode --json samples/machine.log tests/fixtures/sdo/python_canopen.log"
  echo "decode --summary --json samples/machine.log tests/fixtures/pcap/multi.pcapng"
  echo "decode --json --eds 3=tests/fixtures/eds/array_drive.eds tests/fixtures/eds/array_drive.log"
  echo "decode --summary --eds 3=tests/fixtures/eds/array_drive.eds tests/fixtures/eds/array_drive.log"
  echo "decode tests/fixtures/pcap/sll_mixed.pcapng"
  echo "decode --json tests/fixtures/pcap/sll.pcap"
  echo "decode --summary --json tests/fixtures/pcap/sll2.pcapng"
  # The time window and interfaces (docs/output.md#window).
  echo "decode --from 2 --to 2.05 samples/machine.log"
  echo "decode --summary --json --from 2023-11-14T22:13:22Z --to 2023-11-14T22:13:25Z samples/machine.log"
  echo "decode --summary --iface vcan1 tests/fixtures/pcap/multi.pcapng"
  # EtherCAT captures (docs/ethercat.md): the three outputs and the summary.
  echo "decode tests/data/ethercat/twincat-akd-startup.pcapng"
  echo "decode --json tests/data/ethercat/replay-ek1914-segmented-upload.pcapng"
  echo "decode --csv tests/data/ethercat/soem-single-lan9252.pcapng"
  echo "decode --summary tests/data/ethercat/soem-akd-sdo.pcapng"
  echo "decode --summary tests/data/ethercat/synthetic_akd_fault.pcapng"
  echo "decode --summary --json tests/data/ethercat/synthetic_akd_fault.pcapng"
  # The alias, the clock, the mailbox's polls and repeat; a master whose
  # MAC has bit 0x02 set (docs/ethercat.md#alias, #dc, #mailbox-repeat).
  echo "decode --json tests/data/ethercat/synthetic_registers.pcapng"
  echo "decode --summary --json tests/data/ethercat/synthetic_registers.pcapng"
  echo "decode --only mailbox_poll,dc_distribution tests/data/ethercat/synthetic_registers.pcapng"
  echo "decode --summary tests/data/ethercat/synthetic_local_mac.pcapng"
  # A real start-up's CoE SDO transfers and their objects' names
  # (docs/ethercat.md#coe-sdo): 0x1C00, 0x1C12, 0x1C13 among them.
  echo "decode --json --only coe_sdo tests/data/ethercat/soem-single-lan9252.pcapng"
} > "$out/cases.txt"
n=0
while read -r line; do
  n=$((n + 1))
  name=${line//tests\/fixtures\//}
  name=${name// /_}
  name=${name//\//-}
  name=${name//:/-}
  # shellcheck disable=SC2086
  { set +e; "$bin" $line >"$out/stdout" 2>"$out/stderr"; status=$?; set -e; }
  {
    echo "status $status"
    echo "stderr $(wc -c <"$out/stderr")"
    cat "$out/stderr"
    cat "$out/stdout"
  } | gzip -n -9 >"$out/$name.gz"
done < "$out/cases.txt"
rm -f "$out/stdout" "$out/stderr"
echo "$n cases in $out"
