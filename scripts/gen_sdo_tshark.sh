#!/usr/bin/env bash
# Regenerate the tshark oracle of the SDO fixtures (tests/fixtures/sdo/).
#
# For each of python_canopen.log and broken.log (candump -L):
#   1. write NAME.pcap: pcap, little-endian, microseconds, link type 227
#      (LINKTYPE_CAN_SOCKETCAN), one packet per log line in order, each the
#      16-byte struct can_frame (CAN ID big-endian, length, data padded to 8)
#      as scripts/gen_pcap_fixtures.py lays it out; the times are the log's;
#   2. run tshark's CANopen dissector on it ("Decode As" CAN -> CANopen:
#      -d can.subdissector,canopen, as bench/run.sh does) and write the
#      per-frame SDO fields, one row per packet (frame.number = log line),
#      header row = tshark field names, to NAME's TSV:
#        python_canopen.log -> tshark_fields.tsv
#        broken.log         -> broken_tshark_fields.tsv
#
# Needs tshark (apt-get install tshark; `bash bench/run.sh setup` installs
# it) and python3. Made with TShark (Wireshark) 4.0.17 (Debian 12).
# Run from anywhere: bash scripts/gen_sdo_tshark.sh
set -euo pipefail
cd "$(dirname "$0")/../tests/fixtures/sdo"

FIELDS=(
    frame.number can.id can.len _ws.col.Info
    canopen.sdo.cmd canopen.sdo.ccs canopen.sdo.scs canopen.sdo.cs canopen.sdo.ss
    canopen.sdo.crc_support canopen.sdo.s canopen.sdo.e canopen.sdo.n
    canopen.sdo.toggle canopen.sdo.c
    canopen.sdo.main_idx canopen.sdo.sub_idx canopen.sdo.data.bytes
    canopen.sdo.abort_code canopen.sdo.blksize canopen.sdo.ackseq canopen.sdo.pst
    canopen.reserved _ws.expert.message
)

to_pcap() {
    python3 - "$1" "$2" <<'EOF'
import re
import struct
import sys

src, dst = sys.argv[1], sys.argv[2]
line_re = re.compile(r"\((\d+)\.(\d{6})\) \S+ ([0-9A-Fa-f]{3}|[0-9A-Fa-f]{8})#([0-9A-Fa-f]*)")
with open(dst, "wb") as out:
    out.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 262_144, 227))
    for n, line in enumerate(open(src), 1):
        m = line_re.match(line)
        assert m, f"{src}:{n}: not a classic candump -L frame: {line!r}"
        secs, micros, ident, data = m.groups()
        data = bytes.fromhex(data)
        word = int(ident, 16) | (0x80000000 if len(ident) == 8 else 0)
        pkt = struct.pack(">IBBBB", word, len(data), 0, 0, 0) + data.ljust(8, b"\x00")
        out.write(struct.pack("<IIII", int(secs), int(micros), len(pkt), len(pkt)))
        out.write(pkt)
EOF
}

args=()
for f in "${FIELDS[@]}"; do args+=(-e "$f"); done

for pair in python_canopen.log:tshark_fields.tsv broken.log:broken_tshark_fields.tsv; do
    log=${pair%%:*}
    tsv=${pair#*:}
    pcap=${log%.log}.pcap
    to_pcap "$log" "$pcap"
    tshark -r "$pcap" -d can.subdissector,canopen -T fields \
        -E header=y -E separator=/t -E occurrence=a -E aggregator=, "${args[@]}" \
        2>/dev/null >"$tsv"
    rows=$(($(wc -l <"$tsv") - 1))
    lines=$(wc -l <"$log")
    [[ $rows -eq $lines ]] || { echo "$tsv: $rows rows for $lines log lines" >&2; exit 1; }
    echo "$tsv: $rows rows ($pcap)"
done
tshark --version 2>/dev/null | head -n 1
