#!/usr/bin/env python3
"""Generate a realistic candump log of a simulated CANopen machine bus.

The bus (500 kbit/s, interface ``can0``) carries an NMT master and three
devices, each behaving as its manual says (see docs/canopen.md and
the seeds cited below):

* node 3, a Kollmorgen AKD servo drive (docs/canopen.md#akd,
  docs/canopen.md#emcy-producer, seed 000): heartbeat every 100 ms, TPDO1 0x183
  (statusword, position actual) and RPDO1 0x203 (controlword, target velocity)
  every SYNC, a CiA 402 state machine that goes to "fault" while an error is
  active, EMCYs that follow the EMCY error state machine of
  docs/canopen.md#emcy-producer (error EMCYs with the accumulated error
  register, reset EMCYs with code 0x0000 and the remaining register) with byte
  3 = axis id (bits 0-3) and feedback id (bits 4-7), kept in the reset EMCYs as
  docs/canopen.md#akd says, and an object 1003h history (10 entries) read by
  SDO;
* node 5, a Baumer EAM580 absolute encoder (docs/canopen.md#baumer, seed 003):
  heartbeat every 100 ms, TPDO1 0x185 (position 6004h) every SYNC, EMCYs with
  the alarms 6503h in bytes 3-4 and the warnings 6505h in bytes 5-6 (battery
  warning 0xFF00, CAN bus passive 0x8120, temperature 0x4200, watchdog reset
  reason 0x6100, reset 0x0000); it drops off the bus for about 3.3 s and
  comes back with a boot-up;
* node 10, an inclination sensor monitored with node guarding (seed 004,
  docs/canopen.md#error-control): the master sends the RTR ``70A#R`` every 200
  ms (guard time 100Ch = 200 ms, life time factor 100Dh = 3) and the sensor
  answers one byte, bit 7 a toggle that starts at 0 after the boot-up, bits 0-6
  its NMT state; it sends TPDO2 0x28A (slope X and Y, 0.01 deg) every 100 ms.
  Once its toggle fails to alternate (exactly one answer with a wrong toggle),
  and once it goes bus-off for 0.7 s: four guard requests stay unanswered, its
  life guarding expires, it sends EMCY 0x8130, answers as pre-operational
  and is started again by the master.

The master resets all nodes (``000#8100``), configures them by SDO, starts
them (``000#0100``), sends SYNC ``080#`` every 10 ms and TIME 0x100 every
second, reads 1003h of nodes 3 and 5 by SDO (one read past the end is
aborted with 0x08000024) and restarts node 5 after its boot-up.

Timeline of one run (seconds after the first SYNC; the exact lines of the
default output are listed in samples/machine.truth.json, key "events"):

    0.00  NMT reset all; boot-ups of nodes 5 (0.12), 10 (0.18), 3 (0.45)
    0.60  SDO: node 10 guard time 200 ms, life time factor 3; guarding from 0.70
    0.65  SDO: node 3 configured: 1000h, 1008h (segmented), 1017h, then the
          PDO mappings of TPDO1 and RPDO1; the first mapping write is
          refused (abort 0x06040043: TPDO1 still valid)
    1.00  NMT start all; PDOs flow, the drive enables (CiA 402)
    1.5   node 5 EMCY 0xFF00 battery warning (6505h bit 4)
    2.0   node 3 EMCY 0x7305 feedback FB1; 2.3 reset (drive error-free)
    2.8   node 5 EMCY 0x8120 bus passive; 3.1 reset (battery warning remains)
    3.1   node 10 guarding answer with a wrong toggle (the only one)
    3.5   node 3 EMCY 0x4310, 3.8 0x3210 (register accumulates)
    3.9   node 5 EMCY 0x4200 temperature
    4.2   node 5 silent (watchdog reset); 4.4 node 3 EMCY 0x8130 (its
          heartbeat consumer of node 5)
    5.0   node 3 resets 0x3210, 5.6 0x4310 (errors remain: 0x8130)
    5.95  node 10 bus-off: guard requests 6.1 .. 6.7 unanswered; 6.7 it
          recovers, sends EMCY 0x8130 (life guarding expired), answers as
          pre-operational at 6.9 and the master starts it again
    7.5   node 5 boot-up (heartbeat gap ~3.4 s); node 3 resets 0x8130;
          node 5 EMCY 0x6100 watchdog reset reason; 7.8 NMT start node 5
    7.9   node 10 reset EMCY
    8.3   node 5 EMCY 0xFF00 again
    8.8   node 3 EMCY 0x7305 feedback FB2 (root cause at the end), 9.1 0x4310
    9.4   SDO: node 3 1003h read, sub 7 aborted 0x08000024

One run of this scenario ("episode") lasts 10 s and gives about 3 700
frames; that is the default output. ``--frames N`` repeats the scenario
(episodes after the first skip the power-on reset and start with the drive's
fault reset) until N frames exist and cuts the log at exactly N frames.

Output formats: candump log lines (default, docs/formats.md)::

    (1700000000.000500) can0 080#
    (1700000000.000812) can0 183#3706A0860100

or candump's screen format (``--format screen``)::

      can0  183   [6]  37 06 A0 86 01 00
      can0  70A   [0]  remote request

``--pcap FILE`` writes the same frames to a pcap file with link type
LINKTYPE_CAN_SOCKETCAN (227): per packet a 16-byte SocketCAN frame, the CAN
id and flags (EFF 0x80000000, RTR 0x40000000) as a big-endian u32, the
payload length, three zero bytes, and the payload padded to 8 bytes.

``--truth FILE`` writes the ground truth as JSON, computed from the frames
written (not from the scenario script) with the rules stated in its "rules"
key, and cross-checked against what the scenario injected: per node the
frame counts per kind (docs/output.md#common-keys), the EMCY counts, first
error, the EMCY slot at the end under the root-cause rule of
docs/canopen.md#recv-emcy, boot-up lines, heartbeat gaps over 300 ms and the
node-guarding answers with a wrong toggle. Line numbers are 1-based and equal
pcap packet numbers.

The output depends only on the options: the same ``--seed`` gives the same
bytes. Python 3.11 standard library only.

Examples::

    python3 scripts/gen_canlog.py -o samples/machine.log \\
        --truth samples/machine.truth.json
    python3 scripts/gen_canlog.py --frames 1000000 -o /tmp/1m.log --pcap /tmp/1m.pcap
    python3 scripts/gen_canlog.py --format screen | head
"""

from __future__ import annotations

import argparse
import heapq
import json
import random
import struct
import sys
from operator import itemgetter

# ---------------------------------------------------------------------------
# Bus and scenario constants (times in microseconds)

START_US = 1_700_000_000_000_500  # first SYNC, as docs/formats.md#candump-log
CYCLE_US = 10_000  # SYNC period
EPISODE_US = 10_000_000  # one run of the scenario
CYCLES_PER_EPISODE = EPISODE_US // CYCLE_US
HEARTBEAT_US = 100_000  # 1017h of nodes 3 and 5
GUARD_US = 200_000  # 100Ch of node 10
LIFE_TIME_FACTOR = 3  # 100Dh of node 10
TPDO2_INCL_US = 100_000  # event timer of node 10's TPDO2
AKD_HB_CONSUMER_US = 250_000  # AKD 1016h: consumes node 5's heartbeat
BITRATE = 500_000

AKD, ENC, INCL = 3, 5, 10
NODE_NAMES = {
    AKD: "Kollmorgen AKD servo drive",
    ENC: "Baumer EAM580 absolute encoder",
    INCL: "inclination sensor (node guarding)",
}
NODE_PROFILES = {AKD: "akd", ENC: "baumer", INCL: "generic"}

# NMT states on the wire (docs/canopen.md#error-control)
BOOT_UP, STOPPED, OPERATIONAL, PRE_OPERATIONAL = 0x00, 0x04, 0x05, 0x7F
STATE_NAMES = {
    BOOT_UP: "boot_up",
    STOPPED: "stopped",
    OPERATIONAL: "operational",
    PRE_OPERATIONAL: "pre_operational",
}

# NMT command specifiers (CiA 301)
NMT_START, NMT_RESET_NODE = 0x01, 0x81

# CiA 402 drive states as statusword values (AKD, remote bit 9 set)
SW_SWITCH_ON_DISABLED = 0x0250
SW_READY_TO_SWITCH_ON = 0x0231
SW_SWITCHED_ON = 0x0233
SW_OPERATION_ENABLED = 0x0637
SW_FAULT = 0x0218

PACK_TPDO_AKD = struct.Struct("<HI").pack  # statusword 6041h, position actual 6064h
PACK_RPDO_AKD = struct.Struct("<Hi").pack  # controlword 6040h, target velocity 60FFh
PACK_TPDO2_INCL = struct.Struct("<hh").pack  # slope long16 X and Y, 0.01 deg
RPDO_ENABLED = PACK_RPDO_AKD(0x000F, 120_000)

# Bit time of a classic base-format frame: 47 bits of overhead + 8 per data
# byte, plus about 10 % stuff bits.
FRAME_US = [((47 + 8 * n) * 11 // 10) * 1_000_000 // BITRATE for n in range(9)]


# ---------------------------------------------------------------------------
# EMCY producers


def class_register_bits(code: int) -> int:
    """Error-register class bits derived from an error code
    (docs/canopen.md#emcy-producer)."""
    high = code >> 12
    if high == 0x2:
        return 0x02
    if high == 0x3:
        return 0x04
    if high == 0x4:
        return 0x08
    if code >> 8 in (0x81, 0x82):
        return 0x10
    return 0x00


class AkdEmcy:
    """The AKD's EMCY error state machine (docs/canopen.md#emcy-producer) with
    its byte 3 (docs/canopen.md#akd).

    Error EMCYs carry the code, the register accumulated over all active
    errors (bit 0 plus the class bits) and byte 3 = axis | feedback << 4.
    Reset EMCYs carry code 0x0000, the register of the remaining errors and
    still the cleared error's byte 3 (docs/canopen.md#akd: this drive keeps it
    where a generic device sends a zero manufacturer area). An active error
    occurring again, or clearing an error that is not active, sends nothing.
    """

    def __init__(self) -> None:
        self.active: dict[int, int] = {}  # code -> byte 3
        self.history: list[int] = []  # 1003h entries, newest first

    def register(self) -> int:
        if not self.active:
            return 0x00
        bits = 0x01
        for code in self.active:
            bits |= class_register_bits(code)
        return bits

    def occur(self, code: int, axis: int, feedback: int = 0) -> bytes | None:
        if code in self.active:
            return None
        byte3 = (axis & 0x0F) | ((feedback & 0x0F) << 4)
        self.active[code] = byte3
        self.history.insert(0, code)
        del self.history[10:]
        return struct.pack("<HBB4x", code, self.register(), byte3)

    def clear(self, code: int) -> bytes | None:
        byte3 = self.active.pop(code, None)
        if byte3 is None:
            return None
        return struct.pack("<HBB4x", 0x0000, self.register(), byte3)

    def clear_all(self, axis: int) -> bytes | None:
        if not self.active:
            return None
        self.active.clear()
        return struct.pack("<HBB4x", 0x0000, 0x00, axis & 0x0F)


# Baumer diagnostic sources used here (docs/canopen.md#baumer): code ->
# (register bits, 6503h alarm bits, 6505h warning bits)
BAUMER_SOURCES = {
    0xFF00: (0x00, 0x0000, 1 << 4),  # battery low, runtime, non-redundant
    0x8120: (0x10, 0x0000, 0x0000),  # CAN controller bus passive
    0x4200: (0x09, 0x0000, 0x0000),  # temperature out of range
    0x6100: (0x00, 0x0000, 1 << 2),  # reset reason watchdog
}


class BaumerEmcy:
    """The EAM580's EMCYs: bytes 3-4 alarms 6503h, bytes 5-6 warnings 6505h.

    Register, alarms and warnings are those of all active diagnostic
    sources; a source that clears sends code 0x0000 with what remains. A
    reboot clears everything without an EMCY.
    """

    def __init__(self) -> None:
        self.active: set[int] = set()
        self.history: list[int] = []  # 1003h, 8 entries, newest first

    def _state(self) -> tuple[int, int, int]:
        reg = alarms = warnings = 0
        for code in self.active:
            r, a, w = BAUMER_SOURCES[code]
            reg |= r
            alarms |= a
            warnings |= w
        return reg, alarms, warnings

    def _frame(self, code: int) -> bytes:
        reg, alarms, warnings = self._state()
        return struct.pack("<HBHHx", code, reg, alarms, warnings)

    def occur(self, code: int) -> bytes | None:
        if code in self.active:
            return None
        self.active.add(code)
        self.history.insert(0, code)
        del self.history[8:]
        return self._frame(code)

    def clear(self, code: int) -> bytes | None:
        if code not in self.active:
            return None
        self.active.discard(code)
        return self._frame(0x0000)

    def reboot(self) -> None:
        self.active.clear()
        self.history.clear()


# ---------------------------------------------------------------------------
# The simulation


class Bus:
    """Simulated bus: devices, master and an event queue.

    Frames are tuples (time_us, can_id, rtr, data, tag); `tag` is None or
    (category, text) for the scenario's special events (used for the truth
    file's cross-check and its event list).
    """

    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)
        self.frames: list[tuple] = []
        self.queue: list[tuple] = []  # (time_us, seq, callback)
        self.seq = 0
        # NMT state per node; None = off the bus (powered down or bus-off)
        self.nmt: dict[int, int | None] = {AKD: None, ENC: None, INCL: None}
        self.hb_next: dict[int, int | None] = {AKD: None, ENC: None}
        self.hb_last: dict[int, int] = {}
        # AKD
        self.akd_emcy = AkdEmcy()
        self.akd_sw = SW_SWITCH_ON_DISABLED
        self.akd_cw = 0x0000
        self.akd_pos = 0x0001_86A0
        self.akd_hb_consumer_error = False
        # encoder
        self.enc_emcy = BaumerEmcy()
        self.enc_pos = 0x0040_1C3A
        # inclination sensor and guarding
        self.incl_toggle = 0
        self.incl_skip_toggle = False
        self.incl_busoff = False
        self.incl_last_rtr: int | None = None
        self.incl_tpdo_next: int | None = None
        self.incl_slope = [125, -40]
        self.guard_next: int | None = None
        self.time_next = START_US + 500_000
        self.next_timer = START_US
        self.master_expect_incl = PRE_OPERATIONAL
        self.master_restart_pending = False
        self.incl_error = False

    # -- helpers ------------------------------------------------------------

    def emit(self, t: int, cid: int, data: bytes = b"", rtr: bool = False, tag=None) -> None:
        self.frames.append((t, cid, rtr, data, tag))

    def at(self, t: int, callback) -> None:
        self.seq += 1
        heapq.heappush(self.queue, (t, self.seq, callback))

    def jitter(self, lo: int, hi: int) -> int:
        return lo + int(self.rng.random() * (hi - lo))

    def emcy(self, t: int, node: int, data: bytes | None, text: str) -> None:
        if data is not None:
            self.emit(t, 0x80 + node, data, tag=("emcy", text))

    def sdo_read(self, t: int, node: int, index: int, sub: int, value: int, size: int) -> None:
        """Expedited SDO upload: request 0x600+node, answer 0x580+node."""
        req = struct.pack("<BHB4x", 0x40, index, sub)
        self.emit(t, 0x600 + node, req, tag=("sdo", f"read {index:04X}h sub {sub} of node {node}"))
        cs = {1: 0x4F, 2: 0x4B, 4: 0x43}[size]
        resp = struct.pack("<BHBI", cs, index, sub, value)
        self.emit(t + self.jitter(900, 2_200), 0x580 + node, resp)

    def sdo_abort(self, t: int, node: int, index: int, sub: int, abort: int) -> None:
        req = struct.pack("<BHB4x", 0x40, index, sub)
        self.emit(t, 0x600 + node, req, tag=("sdo", f"read {index:04X}h sub {sub} of node {node} (past the end)"))
        resp = struct.pack("<BHBI", 0x80, index, sub, abort)
        self.emit(t + self.jitter(900, 2_200), 0x580 + node, resp, tag=("sdo_abort", f"abort 0x{abort:08X}"))

    def sdo_write(self, t: int, node: int, index: int, sub: int, value: int, size: int) -> None:
        cs = {1: 0x2F, 2: 0x2B, 4: 0x23}[size]
        req = struct.pack("<BHBI", cs, index, sub, value)
        self.emit(t, 0x600 + node, req)
        resp = struct.pack("<BHB4x", 0x60, index, sub)
        self.emit(t + self.jitter(900, 2_200), 0x580 + node, resp)

    def sdo_write_refused(self, t: int, node: int, index: int, sub: int, value: int, size: int,
                          abort: int, why: str) -> None:
        """Expedited SDO download that the server aborts."""
        cs = {1: 0x2F, 2: 0x2B, 4: 0x23}[size]
        self.emit(t, 0x600 + node, struct.pack("<BHBI", cs, index, sub, value),
                  tag=("sdo", f"write {index:04X}h sub {sub} of node {node} ({why})"))
        resp = struct.pack("<BHBI", 0x80, index, sub, abort)
        self.emit(t + self.jitter(900, 2_200), 0x580 + node, resp, tag=("sdo_abort", f"abort 0x{abort:08X}"))

    def sdo_read_segmented(self, t: int, node: int, index: int, sub: int, data: bytes) -> int:
        """Segmented SDO upload (CiA 301 7.2.4.3.5-7): initiate with the size,
        then one upload segment request and answer per 7 bytes, toggle 0, 1, ...;
        returns the time of the last frame."""
        self.emit(t, 0x600 + node, struct.pack("<BHB4x", 0x40, index, sub),
                  tag=("sdo", f"read {index:04X}h sub {sub} of node {node} (segmented)"))
        t += self.jitter(900, 2_200)
        self.emit(t, 0x580 + node, struct.pack("<BHBI", 0x41, index, sub, len(data)))
        toggle = 0
        for off in range(0, len(data), 7):
            chunk = data[off:off + 7]
            last = off + 7 >= len(data)
            t += self.jitter(300, 900)
            self.emit(t, 0x600 + node, bytes((0x60 | toggle << 4,)) + bytes(7))
            t += self.jitter(600, 1_500)
            cmd = toggle << 4 | (7 - len(chunk)) << 1 | int(last)
            self.emit(t, 0x580 + node, bytes((cmd,)) + chunk + bytes(7 - len(chunk)))
            toggle ^= 1
        return t

    def nmt_command(self, t: int, command: int, node: int, text: str) -> None:
        self.emit(t, 0x000, bytes((command, node)), tag=("nmt", text))
        targets = [node] if node else [AKD, ENC, INCL]
        for n in targets:
            if command == NMT_START and self.nmt[n] is not None:
                self.nmt[n] = OPERATIONAL
                if n == INCL:
                    self.master_expect_incl = OPERATIONAL
                    self.incl_tpdo_next = t + self.jitter(3_000, 6_000)

    def boot(self, t: int, node: int) -> None:
        """A node finished its reset: boot-up message, then pre-operational."""
        self.nmt[node] = PRE_OPERATIONAL
        self.emit(t, 0x700 + node, b"\x00", tag=("boot_up", f"node {node} boot-up"))
        if node in self.hb_next:
            self.hb_next[node] = t + HEARTBEAT_US
            self.hb_last[node] = t
        if node == INCL:
            self.incl_toggle = 0
            self.master_expect_incl = PRE_OPERATIONAL

    # -- periodic traffic of one 10 ms SYNC cycle -----------------------------

    def cycle(self, t0: int, index: int) -> None:
        """SYNC and the synchronous PDOs of one 10 ms cycle starting at `t0`."""
        emit = self.frames.append
        # one draw gives every jitter of the cycle (bit fields of 40 bits)
        r = self.rng.getrandbits(40)
        ts = t0 + (r & 0x1F) + (r >> 5 & 0x07)
        emit((ts, 0x080, False, b"", None))

        if self.nmt[AKD] == OPERATIONAL:
            # the drive answers the SYNC with TPDO1, the master then sends RPDO1
            sw = self.akd_sw
            t183 = ts + 150 + (r >> 8 & 0x7F)
            t203 = ts + 900 + (r >> 15 & 0x1FF)
            if sw == SW_OPERATION_ENABLED and not self.akd_emcy.active:
                # steady state: moving at the target velocity
                self.akd_pos = pos = (self.akd_pos + 1_200 + (r >> 24 & 0x07)) & 0xFFFFFFFF
                emit((t183, 0x183, False, PACK_TPDO_AKD(sw, pos), None))
                emit((t203, 0x203, False, RPDO_ENABLED, None))
            else:
                emit((t183, 0x183, False, PACK_TPDO_AKD(sw, self.akd_pos), None))
                self.akd_cw = cw = self.master_controlword(index)
                emit((t203, 0x203, False, PACK_RPDO_AKD(cw, 120_000 if cw == 0x000F else 0), None))
                self.drive_apply_controlword()
        if self.nmt[ENC] == OPERATIONAL:
            self.enc_pos = pos = (self.enc_pos + 41 + (r >> 27 & 0x03)) & 0xFFFFFFFF
            emit((ts + 200 + (r >> 29 & 0xFF), 0x185, False, pos.to_bytes(4, "little"), None))

        if t0 + CYCLE_US > self.next_timer:
            self.timers(t0, ts, index)

    def timers(self, t0: int, ts: int, index: int) -> None:
        """Heartbeats, guarding, TPDO2 of node 10 and TIME due in this cycle."""
        emit = self.frames.append
        rnd = self.rng.random
        end = t0 + CYCLE_US
        for node in (AKD, ENC):
            nxt = self.hb_next[node]
            if nxt is not None and nxt < end:
                t = nxt + int(rnd() * 60)
                emit((t, 0x700 + node, False, bytes((self.nmt[node],)), None))
                self.hb_last[node] = t
                self.hb_next[node] = nxt + HEARTBEAT_US
        nxt = self.incl_tpdo_next
        if nxt is not None and nxt < end:
            if self.nmt[INCL] == OPERATIONAL and not self.incl_busoff:
                x = self.incl_slope[0] + int(rnd() * 5) - 2
                y = self.incl_slope[1] + int(rnd() * 5) - 2
                emit((nxt + int(rnd() * 50), 0x28A, False, PACK_TPDO2_INCL(x, y), None))
            self.incl_tpdo_next = nxt + TPDO2_INCL_US
        nxt = self.guard_next
        if nxt is not None and nxt < end:
            self.guard(nxt)
            self.guard_next = nxt + GUARD_US
        if self.time_next < end:
            self.time_stamp(ts + 2_000 + int(rnd() * 300))
            self.time_next += 1_000_000
        self.update_next_timer()

    def update_next_timer(self) -> None:
        """Earliest time at which `timers` has something to do."""
        due = [self.time_next, self.hb_next[AKD], self.hb_next[ENC], self.incl_tpdo_next, self.guard_next]
        self.next_timer = min(t for t in due if t is not None)

    def master_controlword(self, index: int) -> int:
        """The master's CiA 402 controlword for the drive's last statusword."""
        sw = self.akd_sw
        if sw == SW_FAULT:
            # fault reset (edge) once every 100 ms while the drive shows a fault
            return 0x0080 if index % 10 == 0 else 0x0000
        if sw == SW_SWITCH_ON_DISABLED:
            return 0x0006
        if sw == SW_READY_TO_SWITCH_ON:
            return 0x0007
        return 0x000F

    def drive_apply_controlword(self) -> None:
        """The drive's CiA 402 state machine, applied to the received RPDO."""
        if self.akd_emcy.active:
            self.akd_sw = SW_FAULT
            return
        cw, sw = self.akd_cw, self.akd_sw
        if sw == SW_FAULT:
            if cw & 0x0080:
                self.akd_sw = SW_SWITCH_ON_DISABLED
        elif sw == SW_SWITCH_ON_DISABLED and cw == 0x0006:
            self.akd_sw = SW_READY_TO_SWITCH_ON
        elif sw == SW_READY_TO_SWITCH_ON and cw == 0x0007:
            self.akd_sw = SW_SWITCHED_ON
        elif sw == SW_SWITCHED_ON and cw == 0x000F:
            self.akd_sw = SW_OPERATION_ENABLED

    def guard(self, t: int) -> None:
        """Master's guard request to node 10 and the sensor's answer."""
        t += int(self.rng.random() * 60)
        state = self.nmt[INCL]
        if state is None or self.incl_busoff:
            self.emit(t, 0x70A, rtr=True, tag=("guard_unanswered", "guard request to node 10 left unanswered"))
            return
        self.emit(t, 0x70A, rtr=True)
        self.incl_last_rtr = t
        if self.incl_skip_toggle:
            # the sensor fails to alternate once: it repeats its last toggle
            self.incl_skip_toggle = False
            toggle = self.incl_toggle ^ 1
            tag = ("guard_wrong_toggle", "guarding answer of node 10 repeats the previous toggle")
        else:
            toggle = self.incl_toggle
            self.incl_toggle ^= 1
            tag = None
        ta = t + self.jitter(280, 520)
        self.emit(ta, 0x70A, bytes((state | (toggle << 7),)), tag=tag)
        if state != self.master_expect_incl and not self.master_restart_pending:
            # the master sees an unexpected state and starts the node again
            self.master_restart_pending = True
            self.at(ta + self.jitter(1_200, 2_000), self.ev_restart_incl)

    def time_stamp(self, t: int) -> None:
        """TIME (0x100): ms after midnight and days since 1984-01-01 (CiA 301)."""
        seconds = t // 1_000_000
        days = (seconds - 441_763_200) // 86_400
        ms = (t // 1_000) % 86_400_000
        self.emit(t, 0x100, struct.pack("<IH", ms, days))

    # -- scripted events -----------------------------------------------------

    def ev_restart_incl(self, t: int) -> None:
        self.master_restart_pending = False
        self.nmt_command(t, NMT_START, INCL, "master restarts node 10 (unexpected guarding state)")

    def configure_drive(self, t: int) -> None:
        """The master's boot-time configuration of the AKD by SDO: identity,
        heartbeat, and the PDO mappings of TPDO1 (statusword, position actual
        value) and RPDO1 (controlword, target velocity), CiA 301 7.5.2.35-38.
        Its first attempt to change TPDO1's mapping while the PDO is valid is
        refused (abort 0x06040043, CiA 301 7.5.2.36: a mapping changes only
        while its PDO is not valid); it then disables the PDO first."""
        step = lambda: self.jitter(3_000, 4_000)  # noqa: E731
        self.sdo_read(t, AKD, 0x1000, 0, 0x0002_0192, 4)
        t += step()
        t = self.sdo_read_segmented(t, AKD, 0x1008, 0, b"AKD-P00306") + step()
        self.sdo_write(t, AKD, 0x1017, 0, HEARTBEAT_US // 1_000, 2)
        t += step()
        self.sdo_write_refused(t, AKD, 0x1A00, 0, 0, 1, 0x0604_0043, "TPDO1 still valid")
        t += step()
        writes = [
            (0x1800, 1, 0x8000_0183, 4), (0x1A00, 0, 0, 1), (0x1A00, 1, 0x6041_0010, 4),
            (0x1A00, 2, 0x6064_0020, 4), (0x1A00, 0, 2, 1), (0x1800, 2, 1, 1), (0x1800, 1, 0x0000_0183, 4),
            (0x1400, 1, 0x8000_0203, 4), (0x1600, 0, 0, 1), (0x1600, 1, 0x6040_0010, 4),
            (0x1600, 2, 0x60FF_0020, 4), (0x1600, 0, 2, 1), (0x1400, 2, 1, 1), (0x1400, 1, 0x0000_0203, 4),
        ]
        for index, sub, value, size in writes:
            self.sdo_write(t, AKD, index, sub, value, size)
            t += step()

    def schedule_episode(self, base: int, first: bool) -> None:
        """Queue the scripted events of one episode starting at `base`."""
        at = lambda rel, fn: self.at(base + rel, fn)  # noqa: E731
        j = self.jitter

        if first:
            at(2_500 + j(0, 900), lambda t: self.nmt_command(t, NMT_RESET_NODE, 0, "reset all nodes"))
            at(120_000 + j(0, 900), lambda t: self.boot(t, ENC))
            at(180_000 + j(0, 900), lambda t: self.boot(t, INCL))
            at(450_000 + j(0, 900), lambda t: self.boot(t, AKD))

            def configure(t: int) -> None:
                self.sdo_write(t, INCL, 0x100C, 0, GUARD_US // 1_000, 2)
                self.sdo_write(t + 4_000, INCL, 0x100D, 0, LIFE_TIME_FACTOR, 1)
                self.guard_next = t + 100_000

            at(600_000 + j(0, 500), configure)
            at(650_000 + j(0, 500), self.configure_drive)
            at(800_000 + j(0, 500),
               lambda t: self.sdo_read(t, AKD, 0x1003, 0, len(self.akd_emcy.history), 1))
            at(1_000_000 + j(3_000, 4_000), lambda t: self.nmt_command(t, NMT_START, 0, "start all nodes"))
        else:
            at(500_000 + j(3_000, 4_000),
               lambda t: self.emcy(t, AKD, self.akd_emcy.clear_all(1), "AKD fault reset: all errors cleared"))

        def read_history(t: int, node: int, history: list[int], subs: list[int]) -> None:
            self.sdo_read(t, node, 0x1003, 0, len(history), 1)
            for k, sub in enumerate(subs, start=1):
                tk = t + 10_000 * k
                if sub <= len(history):
                    self.sdo_read(tk, node, 0x1003, sub, history[sub - 1], 4)
                else:
                    self.sdo_abort(tk, node, 0x1003, sub, 0x0800_0024)

        # encoder: battery warning, bus passive and its recovery
        at(1_500_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, ENC, self.enc_emcy.occur(0xFF00), "EAM580 battery low warning 0xFF00"))
        at(2_000_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.occur(0x7305, axis=1, feedback=1),
                               "AKD 0x7305 feedback FB1 axis 1 (transition 1)"))
        at(2_300_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.clear(0x7305), "AKD reset, error-free (transition 4)"))
        at(2_500_000 + j(3_000, 8_000), lambda t: read_history(t, AKD, self.akd_emcy.history, [1]))
        at(2_800_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, ENC, self.enc_emcy.occur(0x8120), "EAM580 CAN bus passive 0x8120"))
        at(3_000_000, self.ev_toggle_glitch)
        at(3_100_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, ENC, self.enc_emcy.clear(0x8120), "EAM580 reset, battery warning remains"))
        at(3_500_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.occur(0x4310, axis=1),
                               "AKD 0x4310 drive temperature (transition 1)"))
        at(3_800_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.occur(0x3210, axis=1),
                               "AKD 0x3210 DC-link overvoltage (transition 3)"))
        at(3_900_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, ENC, self.enc_emcy.occur(0x4200), "EAM580 temperature 0x4200"))
        at(4_200_000 + j(3_000, 8_000), self.ev_encoder_off)
        at(5_000_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.clear(0x3210), "AKD reset, errors remain (transition 2)"))
        at(5_600_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.clear(0x4310), "AKD reset, errors remain (transition 2)"))
        at(5_950_000 + j(0, 2_000), self.ev_incl_busoff)
        at(6_700_000 + j(3_000, 8_000), self.ev_incl_recover)
        at(7_500_000 + j(3_000, 8_000), self.ev_encoder_boot)
        at(7_700_000 + j(3_000, 8_000), lambda t: read_history(t, ENC, self.enc_emcy.history, [1]))
        at(7_800_000 + j(3_000, 8_000),
           lambda t: self.nmt_command(t, NMT_START, ENC, "master starts node 5 after its boot-up"))
        at(7_900_000 + j(3_000, 8_000), self.ev_incl_error_cleared)
        at(8_300_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, ENC, self.enc_emcy.occur(0xFF00), "EAM580 battery low warning 0xFF00"))
        at(8_800_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.occur(0x7305, axis=1, feedback=2),
                               "AKD 0x7305 feedback FB2 axis 1 (transition 1)"))
        at(9_100_000 + j(3_000, 8_000),
           lambda t: self.emcy(t, AKD, self.akd_emcy.occur(0x4310, axis=1),
                               "AKD 0x4310 drive temperature (transition 3)"))
        at(9_400_000 + j(3_000, 8_000),
           lambda t: read_history(t, AKD, self.akd_emcy.history, [1, 2, len(self.akd_emcy.history) + 1]))

    def ev_toggle_glitch(self, t: int) -> None:
        self.incl_skip_toggle = True

    def ev_encoder_off(self, t: int) -> None:
        """The encoder drops off the bus (watchdog reset): silence, then boot-up."""
        self.nmt[ENC] = None
        self.hb_next[ENC] = None
        last = self.hb_last.get(ENC, t)
        # the AKD consumes node 5's heartbeat and reports its loss
        self.at(max(t, last + AKD_HB_CONSUMER_US) + self.jitter(0, 900), self.ev_akd_hb_lost)

    def ev_akd_hb_lost(self, t: int) -> None:
        self.akd_hb_consumer_error = True
        self.emcy(t, AKD, self.akd_emcy.occur(0x8130, axis=1),
                  "AKD 0x8130 heartbeat of node 5 lost (transition 3)")

    def ev_encoder_boot(self, t: int) -> None:
        self.enc_emcy.reboot()
        self.boot(t, ENC)
        if self.akd_hb_consumer_error:
            self.akd_hb_consumer_error = False
            self.at(t + self.jitter(600, 1_500), lambda tt: self.emcy(
                tt, AKD, self.akd_emcy.clear(0x8130), "AKD reset: heartbeat of node 5 back"))
        self.at(t + self.jitter(40_000, 60_000), lambda tt: self.emcy(
            tt, ENC, self.enc_emcy.occur(0x6100), "EAM580 reset reason watchdog 0x6100"))

    def ev_incl_busoff(self, t: int) -> None:
        self.incl_busoff = True

    def ev_incl_recover(self, t: int) -> None:
        """Back from bus-off: life guarding expired meanwhile
        (docs/canopen.md#error-control)."""
        self.incl_busoff = False
        life = GUARD_US * LIFE_TIME_FACTOR
        if self.incl_last_rtr is not None and t - self.incl_last_rtr > life:
            self.emcy(t, INCL, struct.pack("<HB5x", 0x8130, 0x11), "sensor 0x8130 life guard error")
            self.incl_error = True
            self.nmt[INCL] = PRE_OPERATIONAL

    def ev_incl_error_cleared(self, t: int) -> None:
        """Seed 004: after rectification, code 0 with the current register."""
        if self.incl_error:
            self.incl_error = False
            self.emcy(t, INCL, struct.pack("<HB5x", 0x0000, 0x00), "sensor reset, error-free")

    # -- driver --------------------------------------------------------------

    def run_episode(self, number: int) -> None:
        base = START_US + number * EPISODE_US
        self.schedule_episode(base, first=number == 0)
        queue = self.queue
        for index in range(CYCLES_PER_EPISODE):
            t0 = base + index * CYCLE_US
            if queue and queue[0][0] <= t0:
                while queue and queue[0][0] <= t0:
                    t, _, callback = heapq.heappop(queue)
                    callback(t)
                self.update_next_timer()
            self.cycle(t0, index)
        end = base + EPISODE_US
        while queue and queue[0][0] <= end:
            t, _, callback = heapq.heappop(queue)
            callback(t)


def simulate(seed: int, frames: int | None) -> list[tuple]:
    """Run the scenario; return the frames sorted by their wanted send time.

    The times are not yet bus times: `apply_bus_timing` (or `write_log`,
    which does the same on the fly) delays a frame while the bus is busy.
    """
    bus = Bus(seed)
    episode = 0
    bus.run_episode(episode)
    if frames is not None:
        while len(bus.frames) < frames:
            episode += 1
            bus.run_episode(episode)
    out = bus.frames
    out.sort(key=itemgetter(0))
    if frames is not None:
        del out[frames:]
    return out


def apply_bus_timing(frames: list[tuple]) -> None:
    """One frame at a time on the bus: delay a frame until the previous ended."""
    busy_until = 0
    for i, f in enumerate(frames):
        t = f[0]
        if t < busy_until:
            t = busy_until
            frames[i] = (t,) + f[1:]
        busy_until = t + FRAME_US[len(f[3])]


# ---------------------------------------------------------------------------
# Writers

CHUNK = 65_536


def write_log(frames: list[tuple], out, iface: str) -> None:
    """candump -l log lines: (sec.usec) iface ID#DATA, ID#R for RTR.

    Applies the bus timing of `apply_bus_timing` on the fly (a no-op on
    frames that already went through it): the hot path of a 1 M-frame log.
    """
    heads = [f") {iface} {cid:03X}#" for cid in range(0x800)]
    frame_us = FRAME_US
    busy_until = 0
    second_base, second_end, prefix = 0, -1, ""
    for start in range(0, len(frames), CHUNK):
        lines = []
        append = lines.append
        for t, cid, rtr, data, _ in frames[start:start + CHUNK]:
            if t < busy_until:
                t = busy_until
            busy_until = t + frame_us[len(data)]
            if t >= second_end:
                second = t // 1_000_000
                second_base = second * 1_000_000
                second_end = second_base + 1_000_000
                prefix = f"({second}."
            if rtr:
                append(f"{prefix}{t - second_base:06d}{heads[cid]}R{len(data) or ''}\n")
            else:
                append(f"{prefix}{t - second_base:06d}{heads[cid]}{data.hex().upper()}\n")
        out.write("".join(lines))


def write_screen(frames: list[tuple], out, iface: str) -> None:
    """candump screen lines: '  can0  183   [6]  37 06 ...', RTR 'remote request'."""
    head = f"  {iface}  "
    for start in range(0, len(frames), CHUNK):
        lines = []
        append = lines.append
        for _, cid, rtr, data, _ in frames[start:start + CHUNK]:
            if rtr:
                append(f"{head}{cid:03X}   [{len(data)}]  remote request\n")
            else:
                hexed = " " + data.hex(" ").upper() if data else ""
                append(f"{head}{cid:03X}   [{len(data)}] {hexed}\n")
        out.write("".join(lines))


PCAP_GLOBAL = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65_535, 227)
PCAP_RECORD = struct.Struct("<IIII")
SOCKETCAN = struct.Struct(">IB3x8s")
CAN_RTR_FLAG = 0x4000_0000
CAN_EFF_FLAG = 0x8000_0000


def write_pcap(frames: list[tuple], path: str) -> None:
    """pcap, LINKTYPE_CAN_SOCKETCAN (227), 16-byte SocketCAN frames."""
    with open(path, "wb") as f:
        f.write(PCAP_GLOBAL)
        rec, can = PCAP_RECORD.pack, SOCKETCAN.pack
        for start in range(0, len(frames), CHUNK):
            parts = []
            append = parts.append
            for t, cid, rtr, data, _ in frames[start:start + CHUNK]:
                can_id = cid | CAN_EFF_FLAG if cid > 0x7FF else cid
                if rtr:
                    can_id |= CAN_RTR_FLAG
                append(rec(t // 1_000_000, t % 1_000_000, 16, 16))
                append(can(can_id, len(data), data))
            f.write(b"".join(parts))


# ---------------------------------------------------------------------------
# Ground truth


def kind_of(cid: int, rtr: bool) -> str:
    """The `kind` (docs/output.md#common-keys) of a base-format frame."""
    if cid == 0x000:
        return "nmt_command"
    if cid == 0x080:
        return "sync"
    if 0x081 <= cid <= 0x0FF:
        return "emcy"
    if 0x181 <= cid <= 0x57F:
        return "pdo"
    if 0x581 <= cid <= 0x67F:
        return "sdo"
    if 0x701 <= cid <= 0x77F:
        return "guard_request" if rtr else "heartbeat"
    return "other"


NODE_KINDS = ("emcy", "heartbeat", "guard_request", "pdo", "sdo")
# The summary's frame counts: the kinds, with node-guarding answers counted
# apart from heartbeats.
NODE_COUNTS = ("emcy", "heartbeat", "guard_request", "guard_answer", "pdo", "sdo")
GAP_MS = 300

RULES = {
    "line": "1-based line number in the log (= pcap packet number)",
    "frames": "frames per kind (docs/output.md#common-keys); node = CAN id & 0x7F for emcy, heartbeat, guard_request, pdo, sdo; a guarding answer (see guarding) counts as guard_answer, not heartbeat",
    "emcy": "error = code outside 0x0000-0x00FF, reset = code 0x0000-0x00FF (docs/canopen.md#emcy-codes)",
    "slot_at_end": "RECV_EMCY_DEV (docs/canopen.md#recv-emcy): an error EMCY is stored only while the slot holds no error; a reset always overwrites; an EMCY with an error code and error register 0 reports no error (a warning) and is not stored; a boot-up empties the slot (EMCY state machine transition 0; state no_error with the boot-up's line and boot_up true); null = no EMCY ever received",
    "last_state": "the NMT state of the last data frame on 0x700+node (heartbeat, boot-up or guarding answer), bit 7 masked off; null = none",
    "boot_up_lines": "data frames on 0x700+node whose byte is 0x00",
    "heartbeat_gaps": f"consecutive data frames on 0x700+node (heartbeats, boot-ups, guarding answers) more than {GAP_MS} ms apart; gap_ms = difference of the log timestamps",
    "sdo": "requests = data frames on 0x600+node; transfers = requests whose command specifier (byte 0 bits 7-5) is 1 or 2 (initiate download, initiate upload; the log has no block transfers); aborts = SDO frames whose byte 0 is 0x80, with the multiplexer of bytes 1-3 and the code of bytes 4-7",
    "guarding": "an answer is the first data frame on 0x700+node after a guard request (RTR) and before the next one; the expected toggle is 0 after a boot-up and flips after each accepted answer; an answer whose toggle differs is wrong and not accepted (the expected toggle stays); a request with no answer before the next request is unanswered",
}


def emcy_record(line: int, data: bytes) -> dict:
    code = int.from_bytes(data[0:2], "little")
    return {"line": line, "code": code, "code_hex": f"0x{code:04X}", "register": data[2], "data": data.hex()}


def compute_truth(frames: list[tuple], seed: int, fmt: str, iface: str) -> dict:
    """The ground truth, from the frames only (see RULES)."""
    totals = {k: 0 for k in ("nmt_command", "sync", "emcy", "pdo", "sdo", "heartbeat", "guard_request", "other")}
    nodes: dict[int, dict] = {}

    def node_entry(n: int) -> dict:
        e = nodes.get(n)
        if e is None:
            e = nodes[n] = {
                "frames": {k: 0 for k in NODE_COUNTS},
                "emcy": {"count": 0, "errors": 0, "resets": 0, "first_error": None, "slot_at_end": None,
                         "last": None},
                "boot_up_lines": [],
                "last_state": None,
                "heartbeat_gaps": [],
                "_last_hb": None,
                "guarding": None,
                "_g": None,
                "sdo": {"requests": 0, "transfers": 0, "aborts": []},
            }
        return e

    for i, (t, cid, rtr, data, _) in enumerate(frames):
        line = i + 1
        kind = kind_of(cid, rtr)
        totals[kind] += 1
        if kind not in NODE_KINDS:
            continue
        e = node_entry(cid & 0x7F)
        e["frames"][kind] += 1
        if kind == "emcy":
            em = e["emcy"]
            rec = emcy_record(line, data)
            em["count"] += 1
            em["last"] = rec
            if rec["code"] <= 0x00FF:
                em["resets"] += 1
                em["slot_at_end"] = {"state": "no_error", **rec}
            else:
                em["errors"] += 1
                if em["first_error"] is None:
                    em["first_error"] = rec
                slot = em["slot_at_end"]
                if rec["register"] == 0:
                    pass
                elif slot is None or slot["state"] == "no_error":
                    em["slot_at_end"] = {"state": "error", **rec}
        elif kind == "sdo":
            sdo = e["sdo"]
            if cid >= 0x600:
                sdo["requests"] += 1
                if data[0] >> 5 in (1, 2):
                    sdo["transfers"] += 1
            if data[0] == 0x80:
                sdo["aborts"].append({"line": line, "index": int.from_bytes(data[1:3], "little"),
                                      "subindex": data[3], "code": int.from_bytes(data[4:8], "little"),
                                      "by": "client" if cid >= 0x600 else "server"})
        elif kind == "guard_request":
            g = e["_g"]
            if g is None:
                g = e["_g"] = {"expected": 0, "pending": None}
                e["guarding"] = {"requests": 0, "answers": 0, "wrong_toggle_lines": [],
                                 "unanswered_request_lines": [], "answer_states": {}}
            if g["pending"] is not None:
                e["guarding"]["unanswered_request_lines"].append(g["pending"])
            g["pending"] = line
            e["guarding"]["requests"] += 1
        elif kind == "heartbeat":
            byte = data[0] if data else 0
            e["last_state"] = STATE_NAMES.get(byte & 0x7F, "invalid")
            if byte == 0x00:
                e["boot_up_lines"].append(line)
                if e["emcy"]["slot_at_end"] is not None:
                    e["emcy"]["slot_at_end"] = {"state": "no_error", "line": line, "boot_up": True}
                if e["_g"] is not None:
                    e["_g"]["expected"] = 0
            elif e["_g"] is not None and e["_g"]["pending"] is not None:
                g, gd = e["_g"], e["guarding"]
                g["pending"] = None
                gd["answers"] += 1
                e["frames"]["heartbeat"] -= 1
                e["frames"]["guard_answer"] += 1
                state = STATE_NAMES.get(byte & 0x7F, "invalid")
                gd["answer_states"][state] = gd["answer_states"].get(state, 0) + 1
                toggle = byte >> 7
                if toggle != g["expected"]:
                    gd["wrong_toggle_lines"].append(line)
                else:
                    g["expected"] ^= 1
            last = e["_last_hb"]
            if last is not None and t - last[0] > GAP_MS * 1_000:
                e["heartbeat_gaps"].append({"line_before": last[1], "line_after": line,
                                            "gap_ms": round((t - last[0]) / 1_000, 3)})
            e["_last_hb"] = (t, line)

    out_nodes = {}
    for n in sorted(nodes):
        e = nodes[n]
        g = e.pop("_g")
        e.pop("_last_hb")
        if g is not None and g["pending"] is not None:
            e["guarding"]["unanswered_request_lines"].append(g["pending"])
        out_nodes[str(n)] = {"name": NODE_NAMES.get(n, "unknown"), "profile": NODE_PROFILES.get(n, "generic"), **e}

    first_ts = frames[0][0] if frames else START_US
    last_ts = frames[-1][0] if frames else START_US
    return {
        "generator": "scripts/gen_canlog.py",
        "seed": seed,
        "format": fmt,
        "iface": iface,
        "frames": len(frames),
        "first_ts": f"{first_ts // 1_000_000}.{first_ts % 1_000_000:06d}",
        "last_ts": f"{last_ts // 1_000_000}.{last_ts % 1_000_000:06d}",
        "rules": RULES,
        "totals": totals,
        "nodes": out_nodes,
    }


def cross_check(truth: dict, frames: list[tuple]) -> list[dict]:
    """Compare the computed truth with the events the scenario injected.

    Returns the list of tagged events (line, node, category, text). Raises
    AssertionError when the independent computation disagrees with the
    scenario (a bug in the generator).
    """
    events = []
    injected: dict[tuple[str, int], list[int]] = {}
    for i, f in enumerate(frames):
        tag = f[4]
        if tag is None:
            continue
        cid = f[1]
        node = cid & 0x7F if cid else (f[3][1] if len(f[3]) > 1 else 0)
        events.append({"line": i + 1, "node": node, "what": tag[0], "text": tag[1]})
        injected.setdefault((tag[0], cid & 0x7F), []).append(i + 1)
    for key, n in truth["nodes"].items():
        node = int(key)
        assert n["boot_up_lines"] == injected.get(("boot_up", node), []), f"boot-ups of node {node}"
        g = n["guarding"]
        if g is not None:
            assert g["wrong_toggle_lines"] == injected.get(("guard_wrong_toggle", node), []), "wrong toggles"
            assert g["unanswered_request_lines"] == injected.get(("guard_unanswered", node), []), "unanswered"
        assert n["emcy"]["count"] == len(injected.get(("emcy", node), [])), f"EMCYs of node {node}"
        assert [a["line"] for a in n["sdo"]["aborts"]] == injected.get(("sdo_abort", node), []), "SDO aborts"
    return events


# ---------------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    doc = __doc__ or ""
    parser = argparse.ArgumentParser(
        prog="gen_canlog.py",
        description=doc.split("\n\n")[0],
        epilog="Scenario, formats and truth file: see the module docstring (python3 -m pydoc scripts/gen_canlog.py).",
    )
    parser.add_argument("--seed", type=int, default=1, help="random seed for timing jitter and payload noise (default 1)")
    parser.add_argument("--frames", type=int, metavar="N",
                        help="repeat the 10 s scenario and cut at exactly N frames (default: one run, about 3700 frames)")
    parser.add_argument("--format", choices=("log", "screen"), default="log",
                        help="text format: candump -l log lines (default) or candump screen lines")
    parser.add_argument("-o", "--output", metavar="FILE", help="text output file (default standard output)")
    parser.add_argument("--no-text", action="store_true", help="write no text output (with --pcap or --truth)")
    parser.add_argument("--pcap", metavar="FILE", help="also write the frames as pcap (LINKTYPE_CAN_SOCKETCAN, 227)")
    parser.add_argument("--truth", metavar="FILE", help="also write the ground truth as JSON")
    parser.add_argument("--iface", default="can0", help="interface name (default can0)")
    args = parser.parse_args(argv)
    if args.frames is not None and args.frames < 1:
        parser.error("--frames must be at least 1")

    frames = simulate(args.seed, args.frames)
    if args.pcap or args.truth:
        apply_bus_timing(frames)

    if not args.no_text:
        writer = write_log if args.format == "log" else write_screen
        if args.output:
            with open(args.output, "w", encoding="ascii", newline="\n", buffering=1 << 20) as out:
                writer(frames, out, args.iface)
        else:
            writer(frames, sys.stdout, args.iface)
            sys.stdout.flush()
    if args.pcap:
        write_pcap(frames, args.pcap)
    if args.truth:
        truth = compute_truth(frames, args.seed, args.format, args.iface)
        events = cross_check(truth, frames)
        if len(frames) <= 20_000:
            truth["events"] = events
        else:
            truth["events"] = [e for e in events if e["line"] <= 5_000]
            truth["events_note"] = "log longer than 20000 frames: only the events in the first 5000 lines are listed"
        with open(args.truth, "w", encoding="utf-8") as f:
            json.dump(truth, f, indent=1)
            f.write("\n")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:
        # e.g. `gen_canlog.py | head`: stop quietly
        sys.stderr.close()
        sys.exit(0)
