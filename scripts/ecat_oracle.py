#!/usr/bin/env python3
"""Write tshark's dissection of the EtherCAT fixtures as expected files.

For every tests/data/ethercat/*.pcapng (or the captures named on the command
line) this runs `tshark -T pdml` once and writes, beside the capture:

  NAME.tshark.tsv  one row per EtherCAT datagram tshark shows
  NAME.coe.tsv     one row per mailbox message tshark dissects (CoE SDO,
                   SDO information, EoE ...; the mailbox header for all of
                   them, the CoE columns where the type is CoE)

Why PDML and not `-T fields`: a frame holds several datagrams, and tshark
leaves a field out of a datagram that lacks it (no ecat.data in a datagram
whose data it dissects as a mailbox, no ecat.adp/ado in an LRW), so
`-E occurrence=a` lists cannot be lined up with one another. In PDML each
datagram is its own subtree ("EtherCAT datagram: ...") whose `value` is the
datagram's bytes, so every row is read from one datagram only.

Values are tshark's own `show` strings: cmd, idx, adp, ado, lad, irq,
mailbox address, SDO index/sub-index and abort code in tshark's hex
(`0x0c`, `0x03e9`, `0x00010000`); len, wkc, mailbox length/type/counter,
CoE number/type in decimal. An absent field is an empty cell. `data` is
the datagram's data in lower-case hex (taken from the datagram subtree's
bytes, so it is there for mailbox datagrams too).

Deterministic: rows in frame order, datagrams in wire order, no
timestamps; re-running rewrites identical files for the same tshark
version (the README of the fixtures names the version used).

Usage: scripts/ecat_oracle.py [--check] [--verify] [CAPTURE.pcapng ...]
  --check   compare with the files on disk instead of writing; exit 1 on
            a difference.
  --verify  also parse each capture without tshark (pcapng blocks,
            Ethernet, EtherCAT header, datagrams) and compare every cell
            of the datagram rows with tshark's; exit 1 on a difference.
"""

import os
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(os.path.dirname(HERE), "tests", "data", "ethercat")

DG_COLS = ["frame", "dg", "eth_src", "cmd", "idx", "adp", "ado", "lad",
           "len", "wkc", "irq", "data"]
DG_FIELDS = {"ecat.cmd": "cmd", "ecat.idx": "idx", "ecat.adp": "adp",
             "ecat.ado": "ado", "ecat.lad": "lad",
             "ecat.subframe.length": "len", "ecat.cnt": "wkc",
             "ecat.int": "irq"}

MB_COLS = ["frame", "dg", "eth_src", "dg_cmd", "dg_ado", "dg_wkc",
           "mbx_len", "mbx_addr", "mbx_prio", "mbx_type", "mbx_cnt",
           "coe_number", "coe_type", "sdo_dir", "sdo_ccs", "sdo_cmd",
           "sdo_complete", "sdo_idx", "sdo_sub", "sdo_length", "sdo_data",
           "abort_code", "info_opcode"]
MB_FIELDS = {
    "ecat_mailbox.length": "mbx_len",
    "ecat_mailbox.address": "mbx_addr",
    "ecat_mailbox.priority": "mbx_prio",
    "ecat_mailbox.type": "mbx_type",
    "ecat_mailbox.counter": "mbx_cnt",
    "ecat_mailbox.coe.number": "coe_number",
    "ecat_mailbox.coe.type": "coe_type",
    "ecat_mailbox.coe.sdoidx": "sdo_idx",
    "ecat_mailbox.coe.sdosub": "sdo_sub",
    "ecat_mailbox.coe.sdolength": "sdo_length",
    "ecat_mailbox.coe.sdodata": "sdo_data",
    "ecat_mailbox.coe.abortcode": "abort_code",
    "ecat_mailbox.coe.sdoinfoopcode": "info_opcode",
}
# The command byte of an SDO message: tshark puts it in one of these,
# named after the service it read from the command specifier.
SDO_CMD_FIELDS = {
    "ecat_mailbox.coe.sdoccsid": "initiate_download",
    "ecat_mailbox.coe.sdoccsds": "download_segment",
    "ecat_mailbox.coe.sdoccsiu": "initiate_upload",
    "ecat_mailbox.coe.sdoccsus": "upload_segment",
    "ecat_mailbox.coe.sdoscsiu": "initiate_upload_response",
    "ecat_mailbox.coe.sdoscsds": "download_segment_response",
    "ecat_mailbox.coe.sdoscsus": "upload_segment_response",
}
COMPLETE_FIELDS = ("ecat_mailbox.coe.sdoccsid.complete",
                   "ecat_mailbox.coe.sdoscsiu_complete")


def tshark_version():
    out = subprocess.run(["tshark", "--version"], capture_output=True,
                         text=True, check=True).stdout
    return out.splitlines()[0]


def walk(el):
    """Every descendant of el in document order (el itself excluded)."""
    for child in el:
        yield child
        yield from walk(child)


def first_mailbox_data_walk(el):
    """Descendants of el, not descending into an ecat_mailbox proto."""
    for child in el:
        yield child
        if not (child.tag == "proto" and child.get("name") == "ecat_mailbox"):
            yield from first_mailbox_data_walk(child)


def datagram_nodes(ecat_proto):
    for child in ecat_proto:
        if child.get("name") == "" and (child.get("show") or "").startswith(
                "EtherCAT datagram"):
            yield child


def mailbox_row(mbx):
    row = {}
    for f in walk(mbx):
        name = f.get("name")
        if name in MB_FIELDS and MB_FIELDS[name] not in row:
            row[MB_FIELDS[name]] = f.get("show")
        elif name == "ecat_mailbox.coe.sdoreq":
            row["sdo_dir"] = "req"
            row["sdo_ccs"] = f.get("show")
        elif name == "ecat_mailbox.coe.sdores":
            row["sdo_dir"] = "res"
            row["sdo_ccs"] = f.get("show")
        elif name in SDO_CMD_FIELDS and "sdo_cmd" not in row:
            row["sdo_cmd"] = "%s:%s" % (SDO_CMD_FIELDS[name], f.get("show"))
        elif name in COMPLETE_FIELDS:
            row["sdo_complete"] = f.get("show")
    return row


def dissect(path):
    """Yield ('dg', row) and ('mbx', row) in capture order."""
    proc = subprocess.Popen(
        ["tshark", "-n", "-r", path, "-T", "pdml"],
        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    for _event, pkt in ET.iterparse(proc.stdout, events=("end",)):
        if pkt.tag != "packet":
            continue
        frame = eth_src = None
        ecat = None
        for proto in pkt:
            name = proto.get("name")
            if name == "frame":
                for f in proto:
                    if f.get("name") == "frame.number":
                        frame = f.get("show")
            elif name == "eth" and eth_src is None:
                for f in proto:
                    if f.get("name") == "eth.src":
                        eth_src = f.get("show")
            elif name == "ecat":
                ecat = proto
        if ecat is not None:
            for pos, dg in enumerate(datagram_nodes(ecat), 1):
                row = {"frame": frame, "dg": str(pos), "eth_src": eth_src}
                for f in first_mailbox_data_walk(dg):
                    n = f.get("name")
                    if n in DG_FIELDS and DG_FIELDS[n] not in row:
                        row[DG_FIELDS[n]] = f.get("show")
                raw = dg.get("value") or ""
                length = int(row.get("len") or 0)
                row["data"] = raw[20:20 + 2 * length]
                yield "dg", row
                for mbx in walk(dg):
                    if mbx.tag == "proto" and mbx.get("name") == "ecat_mailbox":
                        m = mailbox_row(mbx)
                        m.update({"frame": frame, "dg": str(pos),
                                  "eth_src": eth_src, "dg_cmd": row.get("cmd"),
                                  "dg_ado": row.get("ado"),
                                  "dg_wkc": row.get("wkc")})
                        yield "mbx", m
        pkt.clear()
    proc.wait()
    if proc.returncode != 0:
        raise SystemExit("tshark failed on %s" % path)


def raw_datagrams(path):
    """The datagram rows, parsed from the pcapng bytes without tshark."""
    buf = open(path, "rb").read()
    pos, number, order = 0, 0, "<"
    while pos + 12 <= len(buf):
        btype = struct.unpack_from("<I", buf, pos)[0]
        if btype == 0x0A0D0D0A:
            bom = struct.unpack_from("<I", buf, pos + 8)[0]
            order = "<" if bom == 0x1A2B3C4D else ">"
        btype, blen = struct.unpack_from(order + "II", buf, pos)
        pkt = None
        if btype == 6:  # enhanced packet block
            caplen = struct.unpack_from(order + "I", buf, pos + 20)[0]
            pkt = buf[pos + 28:pos + 28 + caplen]
        elif btype == 3:  # simple packet block
            pkt = buf[pos + 12:pos + blen - 4]
        pos += blen
        if pkt is None:
            continue
        number += 1
        off, ethertype = 14, struct.unpack_from(">H", pkt, 12)[0]
        if ethertype == 0x8100:
            off, ethertype = 18, struct.unpack_from(">H", pkt, 16)[0]
        if ethertype != 0x88A4:
            continue
        off += 2  # EtherCAT header
        src = ":".join("%02x" % b for b in pkt[6:12])
        dg = 0
        while off + 12 <= len(pkt):
            cmd, idx, a1, a2, ln, irq = struct.unpack_from("<BBHHHH", pkt, off)
            length = ln & 0x7FF
            data = pkt[off + 10:off + 10 + length]
            wkc = struct.unpack_from("<H", pkt, off + 10 + length)[0]
            dg += 1
            row = {"frame": str(number), "dg": str(dg), "eth_src": src,
                   "cmd": "0x%02x" % cmd, "idx": "0x%02x" % idx,
                   "len": str(length), "wkc": str(wkc), "irq": "0x%04x" % irq,
                   "data": data.hex()}
            if cmd in (10, 11, 12):
                row["lad"] = "0x%08x" % (a1 | a2 << 16)
            else:
                row["adp"], row["ado"] = "0x%04x" % a1, "0x%04x" % a2
            yield row
            off += 12 + length
            if not ln & 0x8000:
                break


def verify(path, dgs):
    """Count the cells where tshark's rows and the raw parse differ."""
    raw = list(raw_datagrams(path))
    bad = abs(len(raw) - len(dgs))
    for a, b in zip(dgs, raw):
        for c in DG_COLS:
            if (a.get(c) or "") != (b.get(c) or ""):
                bad += 1
                if bad <= 5:
                    sys.stderr.write("verify %s frame %s dg %s %s: tshark %r"
                                     " raw %r\n" % (os.path.basename(path),
                                                    a["frame"], a["dg"], c,
                                                    a.get(c), b.get(c)))
    return bad


def table(cols, rows):
    lines = ["\t".join(cols)]
    for r in rows:
        lines.append("\t".join(r.get(c) or "" for c in cols))
    return "\n".join(lines) + "\n"


def main(argv):
    check = "--check" in argv
    do_verify = "--verify" in argv
    files = [a for a in argv if a not in ("--check", "--verify")]
    if not files:
        files = sorted(os.path.join(DATA, f) for f in os.listdir(DATA)
                       if f.endswith(".pcapng"))
    sys.stderr.write("%s\n" % tshark_version())
    bad = 0
    for path in files:
        dgs, mbxs = [], []
        for kind, row in dissect(path):
            (dgs if kind == "dg" else mbxs).append(row)
        if do_verify:
            diffs = verify(path, dgs)
            bad += 1 if diffs else 0
            sys.stderr.write("%s: raw parse %s\n" % (
                os.path.basename(path),
                "agrees" if not diffs else "differs in %d cells" % diffs))
        base = path[:-len(".pcapng")] if path.endswith(".pcapng") else path
        outs = {base + ".tshark.tsv": table(DG_COLS, dgs),
                base + ".coe.tsv": table(MB_COLS, mbxs)}
        for out, text in outs.items():
            if check:
                try:
                    with open(out) as fh:
                        same = fh.read() == text
                except FileNotFoundError:
                    same = False
                if not same:
                    bad += 1
                    sys.stderr.write("differs: %s\n" % out)
            else:
                with open(out, "w") as fh:
                    fh.write(text)
        sys.stderr.write("%s: %d datagrams, %d mailbox messages\n"
                         % (os.path.basename(path), len(dgs), len(mbxs)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
