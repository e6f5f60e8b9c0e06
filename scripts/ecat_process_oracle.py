#!/usr/bin/env python3
"""Cut each slave's process data out of a capture's cyclic datagrams, from
tshark's dissection alone, and write it as an expected file.

For each capture named (by default the fixtures in tests/data/ethercat that
hold LRW/LRD/LWR datagrams: replay-dc, replay-ek1100-el2828-el2889,
synthetic_akd_fault) this runs `tshark -n -r FILE -T pdml` once and
writes, beside the capture, NAME.process.tsv: one row per slave per
returned cyclic datagram (LRW 0x0c, LRD 0x0a, LWR 0x0b), columns

  packet        frame.number of the returned copy
  dg            the datagram's 1-based place in that frame
  logical       ecat.lad
  station       the slave's station address (0x1001); empty for a
                datagram no FMMU seen maps (then outputs/inputs are the
                datagram's whole data, sent and returned)
  wkc           ecat.cnt of the returned copy
  expected_wkc  the working counter the FMMUs ask for: per slave whose
                FMMUs the datagram overlaps, LRW +1 for a read FMMU and +2
                for a write FMMU, LRD +1 read, LWR +1 write (ETG.1000.4:
                once per slave, not per FMMU); empty with no station
  outputs       the slave's output image (hex), from the SENT copy
  inputs        the slave's input image (hex), from the RETURNED copy;
                empty where the slave has no such image or the datagram
                does not hold all of it (for an LWR, inputs; for an LRD,
                outputs: the command carries none)

What the script reads from tshark (no other parser):
  - per datagram: ecat.cmd, ecat.idx, ecat.adp, ecat.ado, ecat.lad,
    ecat.subframe.length, ecat.cnt, and the data (the datagram subtree's
    bytes after the 10-byte header, as scripts/ecat_oracle.py takes it);
  - the FMMU writes as tshark's `ecat.fmmu` subtrees (ecat.fmmu.lstart,
    .llen, .lstartbit, .lendbit, .pstart, .pstartbit, .type, .activate),
    which tshark 4.0 adds for commands 1-9 at an ado of 0x0600 + 16n with
    a length a multiple of 16: one subtree per FMMU, FMMU n first;
  - the sync-manager writes as `ecat.syncman` subtrees (ecat.syncman.start,
    .len, .ctrlstatus, .smenable) at 0x0800 + 8n, likewise;
  - eth.src, to tell the copies apart.
A write that covers the FMMU or SM area and has no such subtree would be
configuration the script cannot see: it stops with an error.

The slaves' configuration (start-up):
  - taken from the RETURNED copy of a write with ecat.cnt >= 1 (the slave
    took it): FPWR/FPRW name the slave by their ADP (the station address);
    APWR/APRW by position (the negated ADP of the sent copy), mapped to a
    station by the APWR writes of register 0x0010 (2 bytes of data at ado
    0x0010); BWR/BRW write every slave known at that point;
  - an FMMU counts when active (activate bit 0); one that maps whole bytes
    (start bit 0, end bit 7, physical start bit 0) maps logical
    [lstart, lstart + llen) onto physical [pstart, pstart + llen); a bit
    FMMU (a register bit, e.g. SM1's status, or a terminal packed into
    part of a byte) adds to the working counter by its type and is no
    part of the image;
  - a slave's outputs image is its buffered sync managers (control bits
    0-1 = 00) that a whole-byte FMMU maps into and the master writes
    (control bits 2-3 = 01), in sync-manager order, each its full SM
    length; its inputs image the same for the SMs the master reads; an
    FMMU whose physical start lies in no such SM is its own segment, an
    output when its type is write-only. A byte of an image is taken from
    the datagram where an FMMU maps it and the datagram covers that
    logical byte; an image the datagram does not fill is not written.

How the sent copy is found: a returned copy is a frame whose source MAC has
bit 0x02 of its first byte set. Its sent copy is the earliest still
unpaired earlier frame whose source MAC is the returned one with that bit
clear and whose datagrams have the same commands and indices in the same
order (sent frames wait in a window of 64; pairing a frame drops the
unpaired ones sent before it, since a ring returns frames in the order they
were sent). The datagram is then the one at the same place in the sent
frame. In ethercrab's captures the returned copy is the packet right after
its sent one, but nothing here assumes it (TwinCAT's returns lag by many
frames and reuse indices). A returned copy without a sent copy takes its
outputs from itself (a slave does not change bytes an FMMU writes) and is
counted on standard error.

Deterministic: rows in packet order, datagrams in wire order, slaves by
station address; re-running rewrites identical files for the same tshark
version.

Usage: scripts/ecat_process_oracle.py [--check] [CAPTURE.pcapng ...]
  --check   compare with the files on disk instead of writing; exit 1 on
            a difference.
"""

import os
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(os.path.dirname(HERE), "tests", "data", "ethercat")
# The real captures with LRW cycles, and the synthetic one whose sent
# copies carry the previous cycle's inputs (so that inputs taken from the
# wrong copy show).
DEFAULT = ["replay-dc.pcapng", "replay-ek1100-el2828-el2889.pcapng",
           "synthetic_akd_fault.pcapng"]

COLS = ["packet", "dg", "logical", "station", "wkc", "expected_wkc",
        "outputs", "inputs"]
LRD, LWR, LRW = 0x0A, 0x0B, 0x0C
CYCLIC = (LRD, LWR, LRW)
# Writes, by how they address the slave.
BY_STATION = (0x05, 0x06)   # FPWR, FPRW
BY_POSITION = (0x02, 0x03)  # APWR, APRW
BROADCAST = (0x08, 0x09)    # BWR, BRW
WINDOW = 64

FMMU_FIELDS = {"ecat.fmmu.lstart": "lstart", "ecat.fmmu.llen": "llen",
               "ecat.fmmu.lstartbit": "lstartbit",
               "ecat.fmmu.lendbit": "lendbit", "ecat.fmmu.pstart": "pstart",
               "ecat.fmmu.pstartbit": "pstartbit", "ecat.fmmu.type": "type",
               "ecat.fmmu.activate": "activate"}
SM_FIELDS = {"ecat.syncman.start": "start", "ecat.syncman.len": "len",
             "ecat.syncman.ctrlstatus": "ctrlstatus",
             "ecat.syncman.smenable": "smenable"}


def walk(el):
    for child in el:
        yield child
        yield from walk(child)


def num(text):
    return int(text, 0)


def datagrams(path):
    """Yield (frame, eth_src, [datagram dict]) for every EtherCAT frame."""
    proc = subprocess.Popen(["tshark", "-n", "-r", path, "-T", "pdml"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    for _event, pkt in ET.iterparse(proc.stdout, events=("end",)):
        if pkt.tag != "packet":
            continue
        frame = src = ecat = None
        for proto in pkt:
            name = proto.get("name")
            if name == "frame":
                for f in proto:
                    if f.get("name") == "frame.number":
                        frame = int(f.get("show"))
            elif name == "eth" and src is None:
                for f in proto:
                    if f.get("name") == "eth.src":
                        src = f.get("show")
            elif name == "ecat":
                ecat = proto
        if ecat is not None:
            dgs = []
            for node in ecat:
                if node.get("name") != "" or not (node.get("show") or "") \
                        .startswith("EtherCAT datagram"):
                    continue
                dg = {"fmmus": [], "sms": []}
                for f in walk(node):
                    n = f.get("name")
                    if n in ("ecat.cmd", "ecat.idx", "ecat.adp", "ecat.ado",
                             "ecat.lad", "ecat.cnt") and n[5:] not in dg:
                        dg[n[5:]] = num(f.get("show"))
                    elif n == "ecat.subframe.length" and "len" not in dg:
                        dg["len"] = int(f.get("show"))
                    elif n == "ecat.fmmu":
                        dg["fmmus"].append(
                            {FMMU_FIELDS[c.get("name")]: num(c.get("show"))
                             for c in f if c.get("name") in FMMU_FIELDS})
                    elif n == "ecat.syncman":
                        dg["sms"].append(
                            {SM_FIELDS[c.get("name")]: num(c.get("show"))
                             for c in f if c.get("name") in SM_FIELDS})
                raw = node.get("value") or ""
                dg["data"] = bytes.fromhex(raw[20:20 + 2 * dg["len"]])
                dgs.append(dg)
            yield frame, src, dgs
        pkt.clear()
    proc.wait()
    if proc.returncode != 0:
        raise SystemExit("tshark failed on %s" % path)


def returned_bit(mac):
    return int(mac[:2], 16) & 0x02 != 0


def without_bit(mac):
    return "%02x%s" % (int(mac[:2], 16) & ~0x02, mac[2:])


class Slave:
    def __init__(self):
        self.fmmus = {}  # n -> fields
        self.sms = {}    # n -> fields


class Oracle:
    def __init__(self, name):
        self.name = name
        self.slaves = {}      # station -> Slave
        self.positions = {}   # position -> station
        self.pending = []     # [(frame, src, signature, dgs)]
        self.unpaired = 0
        self.max_lag = 0
        self.rows = []

    def fail(self, frame, why):
        raise SystemExit("%s frame %d: %s" % (self.name, frame, why))

    def slave(self, station):
        return self.slaves.setdefault(station, Slave())

    # -- configuration ----------------------------------------------------

    def configure(self, frame, dg, sent):
        cmd, data = dg["cmd"], dg["data"]
        if cmd not in BY_STATION + BY_POSITION + BROADCAST or dg["cnt"] < 1:
            return
        ado, end = dg["ado"], dg["ado"] + dg["len"]
        if cmd in BY_POSITION and ado <= 0x0010 and end >= 0x0012:
            at = 0x0010 - ado
            position = -sent["adp"] & 0xFFFF
            self.positions[position] = data[at] | data[at + 1] << 8
        fmmu_area = ado < 0x0700 and end > 0x0600
        sm_area = ado < 0x0880 and end > 0x0800
        if not fmmu_area and not sm_area:
            return
        if fmmu_area and not (ado % 16 == 0 and 0x0600 <= ado
                              and len(dg["fmmus"]) == min(16, dg["len"] // 16)
                              and dg["len"] % 16 == 0):
            self.fail(frame, "FMMU write tshark does not dissect")
        if sm_area and not (ado % 8 == 0 and 0x0800 <= ado
                            and dg["len"] % 8 == 0 and dg["sms"]):
            self.fail(frame, "SM write tshark does not dissect")
        if cmd in BY_STATION:
            targets = [self.slave(dg["adp"])]
        elif cmd in BY_POSITION:
            station = self.positions.get(-sent["adp"] & 0xFFFF)
            if station is None:
                self.fail(frame, "position write to a slave of no station")
            targets = [self.slave(station)]
        else:
            targets = list(self.slaves.values())
        for slave in targets:
            for k, fields in enumerate(dg["fmmus"]):
                slave.fmmus[(ado - 0x0600) // 16 + k] = fields
            for k, fields in enumerate(dg["sms"]):
                slave.sms[(ado - 0x0800) // 8 + k] = fields

    # -- the image ----------------------------------------------------------

    @staticmethod
    def layout(slave):
        """The slave's FMMUs as (logical, length, physical, output) byte
        areas and its images as [(output, physical, length)] segments in
        order; and its bit FMMUs as (logical, length, type)."""
        areas, bits, segments = [], [], []
        for n in sorted(slave.fmmus):
            f = slave.fmmus[n]
            if not f["activate"] & 1 or f["llen"] == 0:
                continue
            whole = (f["lstartbit"] == 0 and f["lendbit"] == 7
                     and f["pstartbit"] == 0)
            if not whole:
                bits.append((f["lstart"], f["llen"], f["type"]))
                continue
            sm = None
            for m in sorted(slave.sms):
                s = slave.sms[m]
                if s["ctrlstatus"] & 0x03 == 0 and s["len"] > 0 and \
                        s["start"] <= f["pstart"] < s["start"] + s["len"]:
                    sm = m
                    break
            if sm is not None:
                s = slave.sms[sm]
                seg = (sm, s["start"], s["len"],
                       (s["ctrlstatus"] >> 2) & 0x03 == 1)
            else:
                seg = (len(slave.sms) + 16, f["pstart"], f["llen"],
                       f["type"] & 3 == 2)
            if seg not in segments:
                segments.append(seg)
            areas.append((f["lstart"], f["llen"], f["pstart"], seg[3]))
        segments.sort()
        return areas, bits, [(o, p, ln) for _, p, ln, o in segments]

    @staticmethod
    def image(segments, areas, output, logical, data):
        """The image of one direction filled from `data` at `logical`, or
        None when the slave has none or the datagram leaves a byte out."""
        image = {}
        for o, p, ln in segments:
            if o == output:
                for b in range(p, p + ln):
                    image[b] = None
        if not image:
            return None
        for lstart, llen, pstart, out in areas:
            if out != output:
                continue
            for k in range(llen):
                at = lstart + k - logical
                if pstart + k in image and 0 <= at < len(data):
                    image[pstart + k] = data[at]
        order = [b for o, p, ln in segments if o == output
                 for b in range(p, p + ln)]
        if any(image[b] is None for b in order):
            return None
        return bytes(image[b] for b in order)

    def cut(self, frame, place, dg, sent):
        logical, end = dg["lad"], dg["lad"] + dg["len"]
        out_data = sent["data"] if sent is not None else dg["data"]
        rows = []
        for station in sorted(self.slaves):
            areas, bits, segments = self.layout(self.slaves[station])
            over = [a for a in areas if a[0] < end and logical < a[0] + a[1]]
            over_bits = [t for s, ln, t in bits if s < end and logical < s + ln]
            if not over and not over_bits:
                continue
            writes = any(a[3] for a in over) or any(t & 2 for t in over_bits)
            reads = any(not a[3] for a in over) or any(t & 1 for t in over_bits)
            share = {LRW: reads + 2 * writes, LRD: reads,
                     LWR: writes}[dg["cmd"]]
            outputs = inputs = None
            if dg["cmd"] in (LRW, LWR):
                outputs = self.image(segments, areas, True, logical, out_data)
            if dg["cmd"] in (LRW, LRD):
                inputs = self.image(segments, areas, False, logical,
                                    dg["data"])
            rows.append([station, share, outputs, inputs])
        expected = sum(r[1] for r in rows)
        if not rows:
            rows = [[None, None,
                     out_data if dg["cmd"] in (LRW, LWR) else None,
                     dg["data"] if dg["cmd"] in (LRW, LRD) else None]]
        for station, _share, outputs, inputs in rows:
            self.rows.append({
                "packet": str(frame), "dg": str(place),
                "logical": "0x%08x" % logical,
                "station": "" if station is None else "0x%04x" % station,
                "wkc": str(dg["cnt"]),
                "expected_wkc": "" if station is None else str(expected),
                "outputs": "" if outputs is None else outputs.hex(),
                "inputs": "" if inputs is None else inputs.hex()})

    # -- frames -------------------------------------------------------------

    def frame(self, frame, src, dgs):
        signature = tuple((d["cmd"], d["idx"]) for d in dgs)
        if not returned_bit(src):
            self.pending.append((frame, src, signature, dgs))
            if len(self.pending) > WINDOW:
                self.pending.pop(0)
            return
        sent = None
        master = without_bit(src)
        for k, (f, s, sig, sdgs) in enumerate(self.pending):
            if s == master and sig == signature:
                sent = sdgs
                self.max_lag = max(self.max_lag, frame - f)
                del self.pending[:k + 1]
                break
        if sent is None:
            self.unpaired += 1
        for place, dg in enumerate(dgs, 1):
            sdg = sent[place - 1] if sent is not None else None
            if sdg is not None and (sdg["cmd"], sdg["idx"], sdg["len"]) != \
                    (dg["cmd"], dg["idx"], dg["len"]):
                self.fail(frame, "datagram %d differs from its sent copy"
                          % place)
            if sdg is not None and dg["cmd"] in CYCLIC and \
                    sdg["lad"] != dg["lad"]:
                self.fail(frame, "logical address differs from the sent copy")
            self.configure(frame, dg, sdg if sdg is not None else dg)
            if dg["cmd"] in CYCLIC:
                self.cut(frame, place, dg, sdg)


def table(rows):
    lines = ["\t".join(COLS)]
    lines += ["\t".join(r[c] for c in COLS) for r in rows]
    return "\n".join(lines) + "\n"


def main(argv):
    check = "--check" in argv
    files = [a for a in argv if a != "--check"] or \
        [os.path.join(DATA, f) for f in DEFAULT]
    out = subprocess.run(["tshark", "--version"], capture_output=True,
                         text=True, check=True).stdout
    sys.stderr.write("%s\n" % out.splitlines()[0])
    bad = 0
    for path in files:
        name = os.path.basename(path)
        oracle = Oracle(name)
        for frame, src, dgs in datagrams(path):
            oracle.frame(frame, src, dgs)
        text = table(oracle.rows)
        base = path[:-len(".pcapng")] if path.endswith(".pcapng") else path
        target = base + ".process.tsv"
        if check:
            try:
                with open(target) as fh:
                    same = fh.read() == text
            except FileNotFoundError:
                same = False
            if not same:
                bad += 1
                sys.stderr.write("differs: %s\n" % target)
        else:
            with open(target, "w") as fh:
                fh.write(text)
        full = sum(1 for r in oracle.rows if r["expected_wkc"] == r["wkc"])
        sys.stderr.write(
            "%s: %d rows, %d at the full working counter, slaves with "
            "FMMUs %s, %d returned without a sent copy, largest lag %d "
            "packets\n" % (name, len(oracle.rows), full,
                           ", ".join("0x%04x" % s for s in sorted(
                               oracle.slaves) if oracle.slaves[s].fmmus),
                           oracle.unpaired, oracle.max_lag))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
