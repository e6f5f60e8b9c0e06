#!/usr/bin/env python3
"""Write a fleet's logs: machines × days, one log per machine and day, in
the formats their loggers write, partitioned as a fleet's object storage
is (``OUT/logs/machine=M017/date=2024-05-02/0800.log``), with a manifest
of what each machine went through (``OUT/manifest.json``).

Every machine is scripts/gen_canlog.py's simulated CANopen bus (an AKD
servo drive at node 3, a Baumer encoder at node 5, a guarded sensor at
node 10: SYNC every 10 ms, PDOs, heartbeats, node guarding, SDO reads of
the drive), 10 s of it, about 3 700 frames a log; the scripted faults of
that script are left out and each machine-day gets one scenario instead,
drawn from a seeded generator:

- ``healthy``: nothing goes wrong;
- ``drive_fault``: the drive sends an error EMCY (0x7305 feedback,
  0x4310 temperature, 0x2310 overcurrent or 0x3210 DC-link overvoltage)
  and goes to its CiA 402 fault state until the end: the machine stops;
- ``bus_errors`` (loggers that record error frames: candump and pcap):
  the bus goes error-passive, the encoder's heartbeat is lost, the bus
  goes bus-off, and the encoder boots again 2 s later;
- ``reboot``: the encoder resets (watchdog): its heartbeat stops and it
  boots again.

The master polls the drive's error register by SDO every 250 ms; the
answers take 0.9–2.2 ms, but on machines whose drive runs firmware
``M01.20`` they grow from day to day (1, 4 and 7 ms more).
Some files are damaged as loggers damage them (cut short, an SD card's
garbage), and a few are no logs (a note, an empty file). The formats:
candump log (some gzip-compressed), candump screen output, Vector ASC and
BLF (python-can's writers), PEAK TRC (python-can), pcap and pcapng, ASAM
MDF 4 (asammdf, python-can's MF4Writer layout), and EtherCAT captures
(the repository's tests/data/ethercat) for the machines with EtherCAT
drives.

Needs python-can, asammdf and numpy (``pip install python-can asammdf``).
Deterministic: the same options write the same bytes.

Usage: python3 examples/fleet/generate.py OUT [--machines 200] [--days 3]
       [--episodes 1] [--jobs N]
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import random
import shutil
import struct
import sys
from concurrent.futures import ProcessPoolExecutor
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import gen_canlog as gen  # noqa: E402

#: The loggers of the fleet, by machine number: (first machine, format).
LOGGERS = [
    (0, "candump"),      # SocketCAN loggers, candump -l
    (40, "candump.gz"),  # the same, compressed on upload
    (60, "screen"),      # candump's screen output, piped to a file
    (66, "asc"),         # CANoe / CANalyzer
    (86, "blf"),
    (106, "trc"),        # PCAN-View
    (126, "pcap"),       # tcpdump / dumpcap
    (146, "pcapng"),
    (162, "mf4"),        # CANedge
    (195, "ethercat"),   # EtherCAT drives: a capture of the master's port
]
EXTENSIONS = {"candump": "log", "candump.gz": "log.gz", "screen": "txt", "asc": "asc", "blf": "blf",
              "trc": "trc", "pcap": "pcap", "pcapng": "pcapng", "mf4": "mf4", "ethercat": "pcapng"}
ERROR_FRAMES = {"candump", "candump.gz", "pcap", "pcapng"}
SLOW_FIRMWARE = "M01.20"
DRIVE_FAULTS = [0x7305, 0x4310, 0x2310, 0x3210]
ETHERCAT = ["drives.pcapng", "synthetic_akd_fault.pcapng", "twincat-akd-startup.pcapng", "soem-akd-sdo.pcapng"]

# Linux error frames (linux/can/error.h): the class in the identifier with
# CAN_ERR_FLAG, the details in 8 data bytes.
CAN_ERR_FLAG = 0x2000_0000
CAN_ERR_CRTL, CAN_ERR_BUSOFF = 0x0004, 0x0040
CAN_ERR_CRTL_RX_PASSIVE, CAN_ERR_CRTL_TX_PASSIVE = 0x10, 0x20


def logger_of(machine: int) -> str:
    return [fmt for first, fmt in LOGGERS if machine >= first][-1]


class Machine(gen.Bus):
    """gen_canlog's bus with one scenario instead of its scripted episode."""

    def __init__(self, seed: int, scenario: str, sdo_extra_us: int, fault_code: int):
        super().__init__(seed)
        self.scenario = scenario
        self.sdo_extra_us = sdo_extra_us
        self.fault_code = fault_code

    def poll_error_register(self, t: int) -> None:
        """The master reads the drive's error register (1001h) by SDO; the
        drive answers after its firmware's latency."""
        self.emit(t, 0x600 + gen.AKD, struct.pack("<BHB4x", 0x40, 0x1001, 0))
        answer = struct.pack("<BHBI", 0x4F, 0x1001, 0, self.akd_emcy.register())
        self.emit(t + self.jitter(900, 2_200) + self.sdo_extra_us, 0x580 + gen.AKD, answer)

    def error_frame(self, t: int, classes: int, controller: int) -> None:
        self.emit(t, CAN_ERR_FLAG | classes, bytes((0, controller, 0, 0, 0, 0, 0x80, 0x80)))

    def schedule_episode(self, base: int, first: bool) -> None:
        at = lambda rel, fn: self.at(base + rel, fn)  # noqa: E731
        j = self.jitter
        if first:
            # gen_canlog's start-up: reset, boot-ups, configuration, start.
            at(2_500 + j(0, 900), lambda t: self.nmt_command(t, gen.NMT_RESET_NODE, 0, "reset all nodes"))
            at(120_000 + j(0, 900), lambda t: self.boot(t, gen.ENC))
            at(180_000 + j(0, 900), lambda t: self.boot(t, gen.INCL))
            at(450_000 + j(0, 900), lambda t: self.boot(t, gen.AKD))

            def configure(t: int) -> None:
                self.sdo_write(t, gen.INCL, 0x100C, 0, gen.GUARD_US // 1_000, 2)
                self.sdo_write(t + 4_000, gen.INCL, 0x100D, 0, gen.LIFE_TIME_FACTOR, 1)
                self.guard_next = t + 100_000

            at(600_000 + j(0, 500), configure)
            at(650_000 + j(0, 500), self.configure_drive)
            at(1_000_000 + j(3_000, 4_000), lambda t: self.nmt_command(t, gen.NMT_START, 0, "start all nodes"))
        # The master reads the drive's error register every 250 ms.
        for k in range(6, 40):
            at(k * 250_000 + j(1_000, 9_000), self.poll_error_register)
        when = 3_000_000 + j(0, 5_000_000)
        if self.scenario == "drive_fault":
            at(when, lambda t: self.emcy(t, gen.AKD, self.akd_emcy.occur(self.fault_code, axis=1, feedback=1), "fault"))
        elif self.scenario == "bus_errors":
            at(when, lambda t: self.error_frame(t, CAN_ERR_CRTL, CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE))
            at(when + 150_000, self.ev_encoder_off)
            at(when + 600_000 + j(0, 100_000), lambda t: self.error_frame(t, CAN_ERR_BUSOFF, 0))
            at(when + 2_000_000, self.ev_encoder_boot)
            at(when + 2_300_000, lambda t: self.nmt_command(t, gen.NMT_START, gen.ENC, "start node 5"))
        elif self.scenario == "reboot":
            at(when, self.ev_encoder_off)
            at(when + 1_500_000 + j(0, 500_000), self.ev_encoder_boot)
            at(when + 1_800_000 + j(0, 500_000), lambda t: self.nmt_command(t, gen.NMT_START, gen.ENC, "start node 5"))


def simulate(machine: Machine, episodes: int, start_us: int) -> list[tuple]:
    """The machine's frames `(t_us, id, rtr, data)` in bus time, from
    `start_us`."""
    for number in range(episodes):
        machine.run_episode(number)
    frames = sorted(machine.frames, key=lambda f: f[0])
    gen.apply_bus_timing(frames)
    shift = start_us - gen.START_US
    return [(t + shift, cid, rtr, data) for t, cid, rtr, data, _ in frames]


# ---------------------------------------------------------------------------
# Writers: each takes the frames and a path.


def write_candump(frames, path, iface="can0"):
    lines = []
    for t, cid, rtr, data in frames:
        head = f"({t // 1_000_000}.{t % 1_000_000:06d}) {iface} "
        ident = f"{cid:08X}" if cid > 0x7FF else f"{cid:03X}"
        lines.append(f"{head}{ident}#R\n" if rtr else f"{head}{ident}#{data.hex().upper()}\n")
    text = "".join(lines).encode()
    opener = gzip.open if str(path).endswith(".gz") else open
    with opener(path, "wb") as f:
        f.write(text)


def write_screen(frames, path, iface="can0"):
    with open(path, "w") as f:
        gen.write_screen([(t, cid, rtr, data, None) for t, cid, rtr, data in frames], f, iface)


def _socketcan(cid: int, rtr: bool, data: bytes) -> bytes:
    # Error frames keep their flag; others are base-format identifiers.
    can_id = cid | (gen.CAN_RTR_FLAG if rtr else 0)
    return struct.pack(">IB3x8s", can_id, len(data), data)


def write_pcap(frames, path):
    parts = [gen.PCAP_GLOBAL]
    for t, cid, rtr, data in frames:
        parts.append(gen.PCAP_RECORD.pack(t // 1_000_000, t % 1_000_000, 16, 16))
        parts.append(_socketcan(cid, rtr, data))
    Path(path).write_bytes(b"".join(parts))


def _block(kind: int, body: bytes) -> bytes:
    length = 12 + len(body)
    return struct.pack("<II", kind, length) + body + struct.pack("<I", length)


def write_pcapng(frames, path, iface="can0"):
    """pcapng: a section, one SocketCAN interface named `iface`
    (microseconds), an enhanced packet block per frame."""
    name = iface.encode()
    option = struct.pack("<HH", 2, len(name)) + name + b"\0" * (-len(name) % 4) + struct.pack("<HH", 0, 0)
    parts = [
        _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1)),
        _block(0x00000001, struct.pack("<HHI", 227, 0, 65_535) + option),
    ]
    for t, cid, rtr, data in frames:
        packet = _socketcan(cid, rtr, data)
        parts.append(_block(0x00000006, struct.pack("<IIIII", 0, t >> 32, t & 0xFFFF_FFFF, 16, 16) + packet))
    Path(path).write_bytes(b"".join(parts))


def _messages(frames, channel, remote=True):
    import can

    for t, cid, rtr, data in frames:
        if cid & CAN_ERR_FLAG:
            continue  # these loggers never get the scenario with error frames
        if rtr and not remote:
            continue
        yield can.Message(timestamp=t / 1e6, arbitration_id=cid, is_extended_id=False,
                          is_remote_frame=rtr, dlc=len(data), data=None if rtr else data, channel=channel)


def write_python_can(frames, path):
    import can

    writer = {".asc": can.ASCWriter, ".blf": can.BLFWriter, ".trc": can.TRCWriter}[Path(path).suffix]
    # python-can's TRCWriter writes no remote frames (4.6: "not
    # implemented"): the guard requests are left out of TRC logs.
    with writer(str(path)) as w:
        for msg in _messages(frames, channel=1, remote=Path(path).suffix != ".trc"):
            w.on_message_received(msg)


def write_mf4(frames, path):
    """python-can's MF4Writer layout (CAN_DataFrame and CAN_RemoteFrame
    groups, transposed and deflated), written with asammdf in one go as
    bench/convert_mf4.py does."""
    import can  # noqa: F401  (first: can.io.mf4 imports asammdf in its order)
    import numpy as np
    from asammdf import MDF, Signal
    from asammdf.blocks.v4_blocks import SourceInformation
    from asammdf.blocks.v4_constants import BUS_TYPE_CAN, SOURCE_BUS
    from can.io.mf4 import RTR_DTYPE, STD_DTYPE

    start = frames[0][0]
    data_frames = [f for f in frames if not f[2]]
    remote = [f for f in frames if f[2]]
    mdf = MDF(version="4.10")
    mdf.header.start_time = datetime.fromtimestamp(start / 1e6, timezone.utc)
    source = SourceInformation(source_type=SOURCE_BUS, bus_type=BUS_TYPE_CAN)
    for name, dtype, group in (("CAN_DataFrame", STD_DTYPE, data_frames), ("CAN_RemoteFrame", RTR_DTYPE, remote)):
        samples = np.zeros(len(group), dtype=dtype)
        samples[f"{name}.BusChannel"] = 1
        samples[f"{name}.ID"] = [f[1] for f in group]
        samples[f"{name}.DLC"] = [len(f[3]) for f in group]
        if name == "CAN_DataFrame":
            samples[f"{name}.DataLength"] = [len(f[3]) for f in group]
            data = np.zeros((len(group), 64), dtype=np.uint8)
            for i, f in enumerate(group):
                data[i, : len(f[3])] = np.frombuffer(f[3], dtype=np.uint8)
            samples[f"{name}.DataBytes"] = data
        times = np.array([(f[0] - start) / 1e6 for f in group], dtype="<f8")
        mdf.append(Signal(name=name, samples=samples, timestamps=times, source=source))
    mdf.save(str(path), overwrite=True, compression=2)
    mdf.close()


WRITERS = {"candump": write_candump, "candump.gz": write_candump, "screen": write_screen,
           "asc": write_python_can, "blf": write_python_can, "trc": write_python_can,
           "pcap": write_pcap, "pcapng": write_pcapng, "mf4": write_mf4}


# ---------------------------------------------------------------------------
# The fleet


def plan(machines: int, days: int, seed: int = 37) -> list[dict]:
    """What every machine-day is: its file, format, scenario, and how its
    file is damaged, drawn from one seeded generator."""
    rng = random.Random(seed)
    firmware = {m: (SLOW_FIRMWARE if rng.random() < 0.2 else "M01.18") for m in range(machines)}
    fault_code = {m: rng.choice(DRIVE_FAULTS) for m in range(machines)}
    out = []
    for m in range(machines):
        fmt = logger_of(m)
        for d in range(days):
            date = f"2024-05-{d + 1:02d}"
            hour = 6 + rng.randrange(12)
            r = rng.random()
            if fmt == "ethercat":
                scenario = "ethercat"
            elif r < 0.10:
                scenario = "drive_fault"
            elif r < 0.16 and fmt in ERROR_FRAMES:
                scenario = "bus_errors"
            elif r < 0.24:
                scenario = "reboot"
            else:
                scenario = "healthy"
            r = rng.random()
            damage = "cut" if r < 0.012 else "garbage" if r < 0.02 else None
            out.append({
                "file": f"machine=M{m:03d}/date={date}/{hour:02d}00.{EXTENSIONS[fmt]}",
                "machine": f"M{m:03d}", "date": date, "format": fmt, "scenario": scenario,
                "firmware": firmware[m], "fault_code": fault_code[m] if scenario == "drive_fault" else None,
                "damage": damage, "seed": rng.randrange(1 << 30),
                "start_us": int(datetime(2024, 5, d + 1, hour, tzinfo=timezone.utc).timestamp()) * 1_000_000,
                "sdo_extra_us": (1_000 + 3_000 * d) if firmware[m] == SLOW_FIRMWARE else 0,
            })
    # Files that are no log: a technician's note, a logger that crashed at
    # power-on (an empty file).
    for m, name, content in ((3, "note.txt", b"Encoder cable replaced, machine M003, 2024-05-02.\n"),
                             (77, "0000.log", b"")):
        out.append({"file": f"machine=M{m:03d}/date=2024-05-02/{name}", "machine": f"M{m:03d}",
                    "date": "2024-05-02", "format": None, "scenario": "no_log", "content": content.hex()})
    return out


def write(entry: dict, out: Path, episodes: int) -> int:
    """Write one file of the plan; its size."""
    path = out / "logs" / entry["file"]
    path.parent.mkdir(parents=True, exist_ok=True)
    if entry["scenario"] == "no_log":
        path.write_bytes(bytes.fromhex(entry["content"]))
        return path.stat().st_size
    if entry["format"] == "ethercat":
        capture = ETHERCAT[int(entry["machine"][1:]) % len(ETHERCAT)]
        shutil.copyfile(ROOT / "tests" / "data" / "ethercat" / capture, path)
        return path.stat().st_size
    machine = Machine(entry["seed"], entry["scenario"], entry["sdo_extra_us"], entry["fault_code"] or 0)
    frames = simulate(machine, episodes, entry["start_us"])
    WRITERS[entry["format"]](frames, path)
    if entry["damage"] == "cut":
        content = path.read_bytes()
        path.write_bytes(content[: len(content) * 3 // 5])
    elif entry["damage"] == "garbage":
        content = bytearray(path.read_bytes())
        rng = random.Random(entry["seed"])
        at = rng.randrange(len(content) // 4, len(content) // 2)
        content[at : at + 4096] = bytes(rng.randrange(256) for _ in range(4096))
        path.write_bytes(bytes(content))
    return path.stat().st_size


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--machines", type=int, default=200)
    parser.add_argument("--days", type=int, default=3)
    parser.add_argument("--episodes", type=int, default=1, help="10-s episodes per log (default 1: about 3 700 frames)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    args = parser.parse_args(argv)
    entries = plan(args.machines, args.days)
    args.out.mkdir(parents=True, exist_ok=True)
    with ProcessPoolExecutor(args.jobs) as pool:
        sizes = list(pool.map(write, entries, [args.out] * len(entries), [args.episodes] * len(entries), chunksize=8))
    manifest = [{k: v for k, v in e.items() if k not in ("seed", "start_us", "content")} for e in entries]
    (args.out / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
    print(f"{len(entries)} files, {sum(sizes) / 1e6:.1f} MB in {args.out / 'logs'}, {args.out / 'manifest.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
