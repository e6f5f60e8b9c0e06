#!/usr/bin/env python3
"""Record python-canopen configuring PDOs over SDO, then sending them.

Writes, under tests/fixtures/pdo/:

- drive.eds: the object dictionary of the CiA 402 drive (node 3), written
  from the table OBJECTS below (CiA 306 syntax) and then imported by
  python-canopen for both sides, so that the EDS is exactly what they used;
- python_canopen.log: the bus, candump -L (python-can's CanutilsLogWriter,
  interface vcan0);
- python_canopen.json: every SDO transfer of the configuration (which PDO
  object it writes, its lines), the configuration of every PDO before and
  after the remap with the lines where it takes effect, and for every PDO
  frame the signals as the receiving python-canopen node decoded them.

See tests/fixtures/pdo/README.md for the story of the log.

Who is who, on python-can's virtual bus (channel "vcan0"):
- node 3: python-canopen's LocalNode (SDO server) with the drive's object
  dictionary; it sends the TPDOs through its own PdoMap objects
  (`local.tpdo[n]`), whose configuration it reads from its own object
  dictionary after the client has written it (`local.tpdo.read()`).
- the client: python-canopen's RemoteNode for node 3 on a second network. It
  reads the PDO configuration (`node.tpdo.read()`), changes it the way
  python-canopen's documentation shows (`clear()`, `add_variable()`,
  `trans_type`, `cob_id`, `enabled`) and writes it back with
  `node.tpdo.save()` / `node.rpdo.save()` (SDO downloads), then sends the
  RPDOs, the NMT commands and SYNC.
- a third bus that only listens and records every frame, in bus order.

The oracle. Each PDO frame is decoded twice, independently of the crate:
1. by the python-canopen node that receives it, in the frame's own
   callback (`PdoMap.add_callback`): the client's TPDO maps for TPDOs, the
   drive's RPDO maps for RPDOs, i.e. with the mapping in force at that
   moment; each mapped variable's `.raw`;
2. by cantools (a CAN database library, no CANopen in it), from a
   cantools Message built from that same PDO map (bit offset, length,
   signedness, float) - CiA 301's little-endian bit packing.
Where they disagree python-canopen is wrong (it decodes an entry that does
not start on a byte boundary from the bytes of its own type's width only,
and cannot shift a float at all): the JSON's `value` is then cantools' and
`python_canopen_value`/`python_canopen_error` say what python-canopen made
of it. TPDO2 is built with entries that straddle byte boundaries, so its
frames are packed with cantools (python-canopen's PdoVariable.set_data
packs them wrong, see the README).

Run from the repository root (python-canopen 2.4.1, python-can 4.6.1,
cantools 45.1.0; `pip install canopen python-can cantools`):

    python3 scripts/gen_pdo_fixtures.py

Timestamps change from run to run; the frames and the JSON do not.
"""

import json
import math
import os
import struct
import threading
import time

import can
import canopen
import cantools
from cantools.database.can import Message, Signal
from cantools.database.conversion import BaseConversion
from canopen.objectdictionary import datatypes as dt

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "pdo")
EDS = os.path.join(OUT, "drive.eds")
LOG = os.path.join(OUT, "python_canopen.log")
TRUTH = os.path.join(OUT, "python_canopen.json")
IFACE = "vcan0"
NODE = 3

# ---------------------------------------------------------------------------
# The drive's object dictionary (CiA 301 communication objects, CiA 402
# drive objects, manufacturer objects), written as a CiA 306 EDS.

BOOLEAN, INTEGER8, INTEGER16, INTEGER32 = 0x0001, 0x0002, 0x0003, 0x0004
UNSIGNED8, UNSIGNED16, UNSIGNED32, REAL32 = 0x0005, 0x0006, 0x0007, 0x0008


def var(name, data_type, access, default, pdo=False):
    return {"name": name, "type": data_type, "access": access,
            "default": default, "pdo": pdo}


def pdo_objects():
    """1400h-1403h, 1600h-1603h, 1800h-1803h, 1A00h-1A03h. Defaults: TPDO1
    (statusword) and RPDO1 (controlword) valid, the others not valid and
    empty; TPDO COB-IDs with bit 30 set (no RTR), as CiA 301 recommends."""
    objs = {}
    for n in range(4):
        valid = 0 if n == 0 else 0x80000000
        objs[0x1400 + n] = (f"RPDO{n + 1} communication parameter", {
            0: var("Highest sub-index supported", UNSIGNED8, "const", "2"),
            1: var("COB-ID used by RPDO", UNSIGNED32, "rw", f"$NODEID+0x{valid + 0x200 + n * 0x100:X}"),
            2: var("Transmission type", UNSIGNED8, "rw", "0xFF"),
        })
        objs[0x1800 + n] = (f"TPDO{n + 1} communication parameter", {
            0: var("Highest sub-index supported", UNSIGNED8, "const", "6"),
            1: var("COB-ID used by TPDO", UNSIGNED32, "rw",
                   f"$NODEID+0x{valid + 0x40000000 + 0x180 + n * 0x100:X}"),
            2: var("Transmission type", UNSIGNED8, "rw", "0xFF"),
            3: var("Inhibit time", UNSIGNED16, "rw", "0"),
            5: var("Event timer", UNSIGNED16, "rw", "0"),
            6: var("SYNC start value", UNSIGNED8, "rw", "0"),
        })
        for base, kind, first in ((0x1600, "RPDO", "0x60400010"), (0x1A00, "TPDO", "0x60410010")):
            subs = {0: var("Number of mapped application objects in PDO", UNSIGNED8, "rw",
                           "1" if n == 0 else "0")}
            for k in range(1, 9):
                subs[k] = var(f"Application object {k}", UNSIGNED32, "rw",
                              first if (n == 0 and k == 1) else "0x00000000")
            objs[base + n] = (f"{kind}{n + 1} mapping parameter", subs)
    return objs


OBJECTS = {
    0x1000: ("Device type", var("Device type", UNSIGNED32, "ro", "0x00020192")),
    0x1001: ("Error register", var("Error register", UNSIGNED8, "ro", "0", pdo=True)),
    0x1018: ("Identity object", {
        0: var("Highest sub-index supported", UNSIGNED8, "const", "4"),
        1: var("Vendor-ID", UNSIGNED32, "ro", "0x0000006A"),
        2: var("Product code", UNSIGNED32, "ro", "0x00004020"),
        3: var("Revision number", UNSIGNED32, "ro", "0x00010000"),
        4: var("Serial number", UNSIGNED32, "ro", "0x00000003"),
    }),
    **pdo_objects(),
    0x2000: ("Brake released", var("Brake released", BOOLEAN, "ro", "0", pdo=True)),
    0x2001: ("Motor temperature", var("Motor temperature", REAL32, "ro", "25.0", pdo=True)),
    0x2010: ("Digital inputs", {
        0: var("Highest sub-index supported", UNSIGNED8, "const", "3"),
        1: var("Positive limit switch", BOOLEAN, "ro", "0", pdo=True),
        2: var("Negative limit switch", BOOLEAN, "ro", "0", pdo=True),
        3: var("Home switch", BOOLEAN, "ro", "0", pdo=True),
    }),
    0x6040: ("Controlword", var("Controlword", UNSIGNED16, "rw", "0", pdo=True)),
    0x6041: ("Statusword", var("Statusword", UNSIGNED16, "ro", "0", pdo=True)),
    0x6060: ("Modes of operation", var("Modes of operation", INTEGER8, "rw", "0", pdo=True)),
    0x6061: ("Modes of operation display", var("Modes of operation display", INTEGER8, "ro", "0", pdo=True)),
    0x6064: ("Position actual value", var("Position actual value", INTEGER32, "ro", "0", pdo=True)),
    0x606C: ("Velocity actual value", var("Velocity actual value", INTEGER32, "ro", "0", pdo=True)),
    0x6077: ("Torque actual value", var("Torque actual value", INTEGER16, "ro", "0", pdo=True)),
    0x607A: ("Target position", var("Target position", INTEGER32, "rw", "0", pdo=True)),
    0x60FF: ("Target velocity", var("Target velocity", INTEGER32, "rw", "0", pdo=True)),
}


def write_eds(path):
    def group(cond):
        return [i for i in sorted(OBJECTS) if cond(i)]

    mandatory = [0x1000, 0x1001, 0x1018]
    manufacturer = group(lambda i: 0x2000 <= i < 0x6000)
    optional = group(lambda i: i not in mandatory and i not in manufacturer)
    lines = [
        "; The CiA 402 drive of tests/fixtures/pdo/python_canopen.log (node 3).",
        "; Written by scripts/gen_pdo_fixtures.py; python-canopen imports it for",
        "; both sides of the log. The log itself is meant to be decoded without it.",
        "[FileInfo]", "FileName=drive.eds", "FileVersion=1", "FileRevision=0",
        "EDSVersion=4.0", "Description=motionwire test drive (CiA 402)",
        "CreatedBy=motionwire scripts/gen_pdo_fixtures.py", "",
        "[DeviceInfo]", "VendorName=motionwire tests", "VendorNumber=0x6A",
        "ProductName=motionwire test drive", "ProductNumber=0x4020",
        "RevisionNumber=0x00010000", "OrderCode=none",
        *[f"BaudRate_{r}={1 if r == 500 else 0}" for r in (10, 20, 50, 125, 250, 500, 800, 1000)],
        "SimpleBootUpMaster=0", "SimpleBootUpSlave=1", "Granularity=8",
        "DynamicChannelsSupported=0", "GroupMessaging=0",
        "NrOfRXPDO=4", "NrOfTXPDO=4", "LSS_Supported=0", "",
        # CiA 301 dummy mapping: 0005h (UNSIGNED8) may be mapped as a gap.
        "[DummyUsage]", *[f"Dummy{i:04X}={1 if i == 5 else 0}" for i in range(1, 8)], "",
    ]
    for title, indices in (("MandatoryObjects", mandatory), ("OptionalObjects", optional),
                           ("ManufacturerObjects", manufacturer)):
        lines += [f"[{title}]", f"SupportedObjects={len(indices)}"]
        lines += [f"{k}=0x{i:04X}" for k, i in enumerate(indices, 1)]
        lines.append("")

    def entry(section, v):
        return [f"[{section}]", f"ParameterName={v['name']}", "ObjectType=0x7",
                f"DataType=0x{v['type']:04X}", f"AccessType={v['access']}",
                f"DefaultValue={v['default']}", f"PDOMapping={1 if v['pdo'] else 0}", ""]

    for index in sorted(OBJECTS):
        name, body = OBJECTS[index]
        if "type" not in body:  # a record: sub-index -> entry
            lines += [f"[{index:04X}]", f"ParameterName={name}", "ObjectType=0x9",
                      f"SubNumber={len(body)}", ""]
            for sub in sorted(body):
                lines += entry(f"{index:04X}sub{sub:X}", body[sub])
        else:
            lines += entry(f"{index:04X}", body)
    with open(path, "w", newline="\r\n") as f:
        f.write("\n".join(lines))


# ---------------------------------------------------------------------------
# Recording


class Recorder(can.Listener):
    def __init__(self):
        self.frames = []
        self.lock = threading.Lock()

    def on_message_received(self, msg):
        with self.lock:
            self.frames.append(msg)

    def count(self):
        with self.lock:
            return len(self.frames)


def settle(recorder, quiet=0.03):
    """The number of recorded frames once the bus has been quiet for `quiet` s."""
    last, since = recorder.count(), time.monotonic()
    while time.monotonic() - since < quiet:
        time.sleep(0.002)
        now = recorder.count()
        if now != last:
            last, since = now, time.monotonic()
    return last


SIGNED = {INTEGER8, INTEGER16, INTEGER32}


def pdo_label(index):
    """The PDO a communication or mapping object belongs to, and which kind."""
    for base, kind, part in ((0x1400, "RPDO", "communication"), (0x1600, "RPDO", "mapping"),
                             (0x1800, "TPDO", "communication"), (0x1A00, "TPDO", "mapping")):
        if base <= index < base + 0x200:
            return f"{kind}{index - base + 1}", part
    return None, None


COM_ROLES = {1: "COB-ID", 2: "transmission type", 3: "inhibit time", 5: "event timer",
             6: "SYNC start value"}


def role_of(index, sub, value):
    _, part = pdo_label(index)
    if part == "communication":
        role = COM_ROLES.get(sub, f"sub {sub}")
        if sub == 1 and value is not None:
            role += " (not valid, bit 31 set)" if value & 0x80000000 else " (valid)"
        return role
    if sub == 0:
        return "number of mapped objects"
    return f"mapping entry {sub}"


def snapshot(pdo_map):
    """The mapping of a python-canopen PdoMap, as plain data."""
    return [{"index": v.index, "subindex": v.subindex, "name": v.name, "bits": v.length,
             "offset": v.offset, "data_type": v.od.data_type} for v in pdo_map.map]


def cantools_message(cob_id, entries):
    signals = []
    for k, e in enumerate(entries):
        is_float = e["data_type"] in (REAL32,)
        signals.append(Signal(
            f"e{k}", e["offset"], e["bits"], byte_order="little_endian",
            is_signed=e["data_type"] in SIGNED and e["bits"] > 1,
            conversion=BaseConversion.factory(scale=1, offset=0, choices=None, is_float=is_float)))
    length = math.ceil(sum(e["bits"] for e in entries) / 8)
    return Message(cob_id, f"PDO_{cob_id:X}", length, signals)


def cantools_raw_message(cob_id, entries):
    """The same layout, every entry unsigned: the bits as they are."""
    plain = [dict(e, data_type=UNSIGNED32) for e in entries]
    return cantools_message(cob_id, plain)


def json_number(data_type, bits, value):
    if data_type == BOOLEAN or (bits == 1 and isinstance(value, (bool, int))):
        return bool(value)
    if data_type == REAL32:
        return float(value)
    return int(value)


def main():
    os.makedirs(OUT, exist_ok=True)
    write_eds(EDS)

    recorder = Recorder()
    rec_bus = can.Bus(interface="virtual", channel=IFACE)
    rec_notifier = can.Notifier(rec_bus, [recorder])

    drive_net = canopen.Network()
    drive_net.connect(interface="virtual", channel=IFACE)
    drive = canopen.LocalNode(NODE, canopen.import_od(EDS, NODE))
    drive_net.add_node(drive)

    master = canopen.Network()
    master.connect(interface="virtual", channel=IFACE)
    node = master.add_node(canopen.RemoteNode(NODE, canopen.import_od(EDS, NODE)))

    # --- every SDO transfer the client makes, with its lines ---------------
    sdo_log = []
    state = {"phase": None}
    real_upload, real_download = node.sdo.upload, node.sdo.download

    def traced(direction, real):
        def call(index, subindex, *args, **kwargs):
            first = settle(recorder) + 1
            result = real(index, subindex, *args, **kwargs)
            last = settle(recorder)
            data = bytes(args[0]) if direction == "download" else bytes(result)
            value = int.from_bytes(data, "little")
            pdo, part = pdo_label(index)
            sdo_log.append({
                "first_line": first, "last_line": last, "phase": state["phase"],
                "direction": direction, "index": index, "subindex": subindex,
                "data": data.hex(), "value": value, "pdo": pdo, "object": part,
                "role": role_of(index, subindex, value),
            })
            return result
        return call

    node.sdo.upload = traced("upload", real_upload)
    node.sdo.download = traced("download", real_download)

    # --- the receivers' decoding, frame by frame ---------------------------
    decoded = []
    decoded_lock = threading.Lock()

    def on_pdo(receiver, kind):
        def callback(pdo_map):
            signals = []
            for v in pdo_map.map:
                try:
                    raw, error = v.raw, None
                except Exception as exc:  # python-canopen cannot decode it
                    raw, error = None, f"{type(exc).__name__}: {exc}"
                signals.append((raw, error))
            number = next(n for n, m in receiver.map.items() if m is pdo_map)
            with decoded_lock:
                decoded.append({
                    "cob_id": pdo_map.cob_id, "data": bytes(pdo_map.data),
                    "timestamp": pdo_map.timestamp, "pdo": f"{kind}{number}",
                    "entries": snapshot(pdo_map), "python_canopen": signals,
                    "python_canopen_name": pdo_map.name,
                })
        return callback

    # ---------------------------------------------------------------------
    # The story

    state["phase"] = "boot"
    node.nmt.state = "PRE-OPERATIONAL"
    settle(recorder)

    # 1. The client reads the configuration the drive comes up with.
    state["phase"] = "read"
    node.tpdo.read()
    node.rpdo.read()

    # 2. It maps the PDOs it wants and writes them back.
    state["phase"] = "configure"
    tpdo1 = node.tpdo[1]
    tpdo1.clear()
    tpdo1.add_variable(0x6041)  # Statusword
    tpdo1.add_variable(0x6064)  # Position actual value
    tpdo1.trans_type = 255
    tpdo1.enabled = True

    tpdo2 = node.tpdo[2]  # entries that straddle byte boundaries
    tpdo2.clear()
    tpdo2.add_variable(0x2000, 0, 1)  # Brake released, BOOLEAN, 1 bit: bit 0
    tpdo2.add_variable(0x6077)  # Torque actual value, INTEGER16: bits 1-16
    tpdo2.add_variable(0x6061)  # Modes of operation display, INTEGER8: bits 17-24
    tpdo2.add_variable(0x2001)  # Motor temperature, REAL32: bits 25-56
    tpdo2.trans_type = 254
    tpdo2.event_timer = 100
    tpdo2.enabled = True

    tpdo3 = node.tpdo[3]  # a COB-ID outside the pre-defined connection set
    tpdo3.clear()
    tpdo3.add_variable(0x6061)  # Modes of operation display: bits 0-7
    tpdo3.add_variable(0x0005)  # dummy UNSIGNED8: bits 8-15, a gap
    tpdo3.add_variable(0x2001)  # Motor temperature, REAL32: bits 16-47
    tpdo3.add_variable(0x2010, 1, 1)  # Digital inputs.Positive limit switch: bit 48
    tpdo3.add_variable(0x2010, 3, 1)  # Digital inputs.Home switch: bit 49
    tpdo3.cob_id = 0x2C0
    tpdo3.trans_type = 1  # synchronous, every SYNC
    tpdo3.enabled = True
    node.tpdo.save()

    rpdo1 = node.rpdo[1]
    rpdo1.clear()
    rpdo1.add_variable(0x6040)  # Controlword
    rpdo1.add_variable(0x60FF)  # Target velocity
    rpdo1.trans_type = 255
    rpdo1.enabled = True

    rpdo2 = node.rpdo[2]
    rpdo2.clear()
    rpdo2.add_variable(0x6060)  # Modes of operation
    rpdo2.add_variable(0x607A)  # Target position
    rpdo2.trans_type = 255
    rpdo2.enabled = True
    node.rpdo.save()
    settle(recorder)

    # The drive takes its PDO configuration from its own object dictionary,
    # i.e. from what the client wrote (no bus traffic: the server reads its
    # own data store).
    drive.tpdo.read()
    drive.rpdo.read()
    for n, m in node.tpdo.map.items():
        m.add_callback(on_pdo(node.tpdo, "TPDO"))
    for n, m in drive.rpdo.map.items():
        m.add_callback(on_pdo(drive.rpdo, "RPDO"))

    state["phase"] = "run"
    node.nmt.state = "OPERATIONAL"
    settle(recorder)

    built_by_cantools = []  # (cob_id, data) of the frames packed with cantools

    def send_tpdo1(statusword, position):
        m = drive.tpdo[1]
        m[0x6041].raw = statusword
        m[0x6064].raw = position
        m.transmit()
        settle(recorder)

    def send_tpdo1_remapped(statusword, mode, velocity):
        m = drive.tpdo[1]
        m[0x6041].raw = statusword
        m[0x6061].raw = mode
        m[0x606C].raw = velocity
        m.transmit()
        settle(recorder)

    def send_tpdo2(brake, torque, mode, temperature):
        # python-canopen packs entries that straddle bytes wrong (see the
        # README); cantools packs them after CiA 301.
        m = drive.tpdo[2]
        msg = cantools_message(m.cob_id, snapshot(m))
        data = msg.encode({"e0": int(brake), "e1": torque, "e2": mode, "e3": temperature},
                          scaling=False)
        m.data = bytearray(data)
        built_by_cantools.append((m.cob_id, bytes(data)))
        m.transmit()
        settle(recorder)

    def sync_tpdo3(mode, temperature, limit, home):
        master.sync.transmit()
        settle(recorder)
        m = drive.tpdo[3]
        m[0x6061].raw = mode
        m[0x2001].raw = temperature
        m.map[3].raw = limit
        m.map[4].raw = home
        m.transmit()
        settle(recorder)

    def send_rpdo1(controlword, velocity):
        m = node.rpdo[1]
        m[0x6040].raw = controlword
        m[0x60FF].raw = velocity
        m.transmit()
        settle(recorder)

    def send_rpdo2(mode, target):
        m = node.rpdo[2]
        m[0x6060].raw = mode
        m[0x607A].raw = target
        m.transmit()
        settle(recorder)

    # 3. A CiA 402 walk: switch on disabled -> ready -> switched on ->
    #    operation enabled, motion, a fault, the fault reset.
    send_tpdo1(0x0250, 0)  # switch on disabled
    send_rpdo2(3, 0)  # profile velocity mode
    sync_tpdo3(3, 31.5, False, True)
    send_rpdo1(0x0006, 0)  # shutdown
    send_tpdo1(0x0231, 0)  # ready to switch on
    send_rpdo1(0x0007, 0)  # switch on
    send_tpdo1(0x0233, 0)  # switched on
    send_tpdo1(0x0233, 0)
    send_rpdo1(0x000F, 0)  # enable operation
    send_tpdo1(0x0237, 0)  # operation enabled
    send_tpdo2(True, 0, 3, 31.75)
    send_rpdo1(0x000F, 1000)
    send_tpdo1(0x0237, 125)
    send_tpdo2(True, -850, 3, 32.5)
    sync_tpdo3(3, 32.625, False, False)
    send_tpdo1(0x0637, 1250)  # bit 10 target reached
    send_rpdo1(0x000F, -2000)
    send_tpdo2(True, 0x7FFF, 3, 33.0)  # bit 16 of the frame set, bit 0 of byte 2
    send_tpdo1(0x0237, -40000)
    send_tpdo2(True, -32768, -1, 34.25)  # a negative (manufacturer) mode display
    send_tpdo1(0x0218, -40100)  # fault
    send_tpdo2(False, 0, -1, -0.5)
    sync_tpdo3(-1, 34.5, True, False)
    send_rpdo1(0x0000, 0)
    send_rpdo1(0x0080, 0)  # fault reset: bit 7 0 -> 1
    send_tpdo1(0x0250, -40100)  # switch on disabled
    send_rpdo1(0x0006, 0)  # shutdown
    send_tpdo1(0x0231, -40100)  # ready to switch on

    # 4. The remap: python-canopen's save() disables TPDO1 (COB-ID bit 31),
    #    writes the new mapping and re-enables it.
    state["phase"] = "remap"
    tpdo1.clear()
    tpdo1.add_variable(0x6041)  # Statusword: bits 0-15
    tpdo1.add_variable(0x6061)  # Modes of operation display: bits 16-23
    tpdo1.add_variable(0x606C)  # Velocity actual value: bits 24-55
    tpdo1.save()
    settle(recorder)
    drive.tpdo[1].read()

    # 5. The same walk on, with the new TPDO1.
    state["phase"] = "run after remap"
    send_tpdo1_remapped(0x0231, 3, 0)
    send_rpdo1(0x0007, 0)  # switch on
    send_tpdo1_remapped(0x0233, 3, 0)
    send_rpdo1(0x000F, 1500)  # enable operation
    send_tpdo1_remapped(0x0237, 3, 0)
    send_tpdo1_remapped(0x0237, 3, 1498)
    send_tpdo2(True, 420, 3, 35.125)
    sync_tpdo3(3, 35.25, False, False)
    send_rpdo1(0x0007, 0)  # disable operation
    send_tpdo1_remapped(0x0233, 3, -3)

    settle(recorder, 0.2)
    master.disconnect()
    drive_net.disconnect()
    rec_notifier.stop()
    rec_bus.shutdown()

    frames = recorder.frames
    with can.CanutilsLogWriter(LOG, channel=IFACE) as writer:
        for msg in frames:
            writer.on_message_received(msg)

    truth = describe(frames, sdo_log, decoded, built_by_cantools)
    with open(TRUTH, "w") as f:
        json.dump(truth, f, indent=1)
        f.write("\n")
    print(f"{len(frames)} frames, {len(truth['frames'])} PDO frames, {len(sdo_log)} SDO transfers")
    print("python-canopen", canopen.__version__, "python-can", can.__version__,
          "cantools", cantools.__version__)


def describe(frames, sdo_log, decoded, built_by_cantools):
    # Every SDO transfer the client made is two frames, request and response,
    # and they cover every 603h/583h frame of the log.
    sdo_lines = set()
    for t in sdo_log:
        assert t["last_line"] == t["first_line"] + 1, t
        req, resp = frames[t["first_line"] - 1], frames[t["last_line"] - 1]
        assert req.arbitration_id == 0x600 + NODE and resp.arbitration_id == 0x580 + NODE, t
        assert resp.data[0] != 0x80, ("abort", t)
        sdo_lines.update((t["first_line"], t["last_line"]))

    # Match each receiver's decoding to its frame (same id, bytes, time).
    by_key = {}
    for d in decoded:
        key = (d["cob_id"], d["data"], d["timestamp"])
        assert key not in by_key, key
        by_key[key] = d
    out_frames, other = [], []
    for line, msg in enumerate(frames, 1):
        key = (msg.arbitration_id, bytes(msg.data), msg.timestamp)
        d = by_key.pop(key, None)
        if d is None:
            other.append(line)
            continue
        out_frames.append(frame_record(line, msg, d))
    assert not by_key, by_key
    for line in other:
        msg = frames[line - 1]
        kind = msg.arbitration_id
        assert line in sdo_lines or kind in (0x000, 0x080), (line, msg)

    # The frames packed with cantools were packed from the intended values;
    # cantools' decoding of them is checked against those in frame_record.
    assert all(any(f["cob_id"] == c and f["data"] == d.hex() for f in out_frames)
               for c, d in built_by_cantools)

    configurations = configuration_history(sdo_log)
    as_read = initial_configuration(sdo_log)
    remap = remap_lines(sdo_log, out_frames)
    return {
        "iface": IFACE,
        "node": NODE,
        "versions": {"python-canopen": canopen.__version__, "python-can": can.__version__,
                     "cantools": cantools.__version__},
        "nmt_lines": [line for line in other if frames[line - 1].arbitration_id == 0x000],
        "sync_lines": [line for line in other if frames[line - 1].arbitration_id == 0x080],
        "sdo": sdo_log,
        "as_read": as_read,
        "configurations": configurations,
        "remap": remap,
        "frames": out_frames,
    }


def frame_record(line, msg, d):
    entries = d["entries"]
    msg_ct = cantools_message(d["cob_id"], entries)
    raw_ct = cantools_raw_message(d["cob_id"], entries)
    data = bytes(msg.data)
    assert len(data) == msg_ct.length, (line, data.hex(), msg_ct.length)
    ct_values = msg_ct.decode(data, decode_choices=False, scaling=False)
    ct_raw = raw_ct.decode(data, decode_choices=False, scaling=False)
    signals = []
    for k, (e, (pc_value, pc_error)) in enumerate(zip(entries, d["python_canopen"])):
        value = json_number(e["data_type"], e["bits"], ct_values[f"e{k}"])
        sig = {"index": e["index"], "subindex": e["subindex"], "name": e["name"],
               "bits": e["bits"], "offset": e["offset"], "data_type": e["data_type"],
               "value": value, "raw": int(ct_raw[f"e{k}"])}
        if e["index"] < 0x0008:
            sig["dummy"] = True
        agrees = pc_error is None and json_number(e["data_type"], e["bits"], pc_value) == value
        if not agrees:
            sig["python_canopen_value"] = (None if pc_value is None
                                           else json_number(e["data_type"], e["bits"], pc_value))
            if pc_error is not None:
                sig["python_canopen_error"] = pc_error
        signals.append(sig)
    return {"line": line, "cob_id": msg.arbitration_id, "node": NODE, "pdo": d["pdo"],
            "data": data.hex(), "python_canopen_map_name": d["python_canopen_name"],
            "signals": signals}


def configuration_history(sdo_log):
    """Replay the client's SDO downloads (and the uploads it read first) into
    the configuration of each PDO, and note where each version takes effect:
    the line of the response to the download that makes the PDO valid
    (COB-ID with bit 31 clear) with its mapping complete."""
    state = {}
    history = []
    for t in sdo_log:
        if t["pdo"] is None:
            continue
        cfg = state.setdefault(t["pdo"], {"cob_id_raw": None, "trans_type": None, "inhibit_time": None,
                                          "event_timer": None, "sync_start": None, "count": 0,
                                          "entries": {}})
        idx, sub, value = t["index"], t["subindex"], t["value"]
        if t["object"] == "communication":
            key = {1: "cob_id_raw", 2: "trans_type", 3: "inhibit_time", 5: "event_timer",
                   6: "sync_start"}[sub]
            cfg[key] = value
        elif sub == 0:
            cfg["count"] = value
        else:
            cfg["entries"][sub] = value
        if t["direction"] == "download" and t["object"] == "communication" and sub == 1 \
                and not value & 0x80000000:
            mapped = [cfg["entries"].get(k, 0) for k in range(1, cfg["count"] + 1)]
            history.append({
                "pdo": t["pdo"], "phase": t["phase"], "valid_from_line": t["last_line"],
                "cob_id": value & 0x1FFFFFFF, "cob_id_raw": value,
                "trans_type": cfg["trans_type"], "inhibit_time": cfg["inhibit_time"],
                "event_timer": cfg["event_timer"], "sync_start_value": cfg["sync_start"],
                "entries": [{"index": m >> 16, "subindex": (m >> 8) & 0xFF, "bits": m & 0xFF,
                             "raw": f"0x{m:08X}"} for m in mapped],
                "sdo_lines": [[x["first_line"], x["last_line"]] for x in sdo_log
                              if x["pdo"] == t["pdo"] and x["phase"] == t["phase"]],
            })
    return history


def initial_configuration(sdo_log):
    """What the client's read() uploaded before it changed anything: the
    drive's configuration at power-on (the EDS defaults)."""
    out = {}
    for t in sdo_log:
        if t["phase"] != "read":
            continue
        cfg = out.setdefault(t["pdo"], {"pdo": t["pdo"], "lines": [t["first_line"], t["last_line"]],
                                        "cob_id": None, "valid": None, "cob_id_raw": None,
                                        "trans_type": None, "entries": []})
        cfg["lines"][1] = t["last_line"]
        sub, value = t["subindex"], t["value"]
        if t["object"] == "communication":
            if sub == 1:
                cfg.update(cob_id=value & 0x1FFFFFFF, valid=not value & 0x80000000, cob_id_raw=value)
            elif sub == 2:
                cfg["trans_type"] = value
        elif sub > 0:
            cfg["entries"].append({"index": value >> 16, "subindex": (value >> 8) & 0xFF,
                                   "bits": value & 0xFF, "raw": f"0x{value:08X}"})
    return list(out.values())


def remap_lines(sdo_log, out_frames):
    remap = [t for t in sdo_log if t["phase"] == "remap"]
    disable = next(t for t in remap if t["role"].startswith("COB-ID (not valid"))
    enable = next(t for t in remap if t["role"] == "COB-ID (valid)")
    count = [t for t in remap if t["role"] == "number of mapped objects"]
    first_new = next(f["line"] for f in out_frames
                     if f["pdo"] == "TPDO1" and f["line"] > enable["last_line"])
    last_old = max(f["line"] for f in out_frames
                   if f["pdo"] == "TPDO1" and f["line"] < disable["first_line"])
    return {"pdo": "TPDO1", "sdo_lines": [remap[0]["first_line"], remap[-1]["last_line"]],
            "disabled_at_line": disable["last_line"],
            "mapping_cleared_at_line": count[0]["last_line"],
            "mapping_set_at_line": count[-1]["last_line"],
            "enabled_at_line": enable["last_line"],
            "last_frame_old_mapping": last_old, "first_frame_new_mapping": first_new}


if __name__ == "__main__":
    main()
