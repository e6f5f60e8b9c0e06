#!/usr/bin/env python3
"""Record real SDO traffic between python-canopen's client and server.

Writes tests/fixtures/sdo/python_canopen.log (candump -L, python-can's
CanutilsLogWriter) and tests/fixtures/sdo/python_canopen.json (each transfer
as python-canopen saw it, with the 1-based log lines of its first and last
frame). See tests/fixtures/sdo/README.md for what each transfer shows.

Three python-can virtual buses on the channel "vcan0": one for the servers
(python-canopen LocalNode objects), one for the client (RemoteNode objects)
and one that only listens and records every frame on the bus, in bus order,
with the virtual bus's send time (time.time()).

Who is who:
- node 5: python-canopen's LocalNode with its own SdoServer, unchanged: the
  client and the server are both python-canopen.
- node 6: a LocalNode whose SdoServer is ScriptedSdoServer below: python-
  canopen's server with the block upload/download services it lacks (it
  answers a block upload request with a plain initiate upload response and
  aborts a block download with 0504 0001) written here after CiA 301, and an
  initiate upload response without size indication for the objects listed
  in `unsized`. Every client frame, on every node, is python-canopen's.
- node 9: no server at all (the client times out and aborts).

Run from the repository root (python-canopen 2.4.1, python-can 4.6.1):

    python3 scripts/gen_sdo_fixtures.py

Timestamps change from run to run; the frames and the JSON do not.
"""

import binascii
import json
import os
import struct
import sys
import threading
import time

import can
import canopen
from canopen import objectdictionary as odm
from canopen.objectdictionary import datatypes as dt
from canopen.sdo import SdoAbortedError, SdoCommunicationError
from canopen.sdo.server import SdoServer
import canopen.sdo.client as sdo_client_mod

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "sdo")
LOG = os.path.join(OUT, "python_canopen.log")
TRUTH = os.path.join(OUT, "python_canopen.json")
IFACE = "vcan0"


# ---------------------------------------------------------------------------
# The servers' object dictionary


def variable(name, index, sub, data_type, access, default):
    var = odm.ODVariable(name, index, sub)
    var.data_type = data_type
    var.access_type = access
    var.default = default
    return var


DEVICE_NAME = "motionwire test drive"  # 21 bytes: three full segments
SOFTWARE_VERSION = "fw 2.4.1-rc3 build 1187"  # 23 bytes: 3 full + 2 bytes
DOMAIN_140 = bytes((i * 37 + 11) & 0xFF for i in range(140))  # 20 full segments
assert len(DEVICE_NAME) == 21 and len(SOFTWARE_VERSION) == 23


def server_od():
    od = odm.ObjectDictionary()
    od.add_object(variable("Device type", 0x1000, 0, dt.UNSIGNED32, "ro", 0x00020192))
    od.add_object(variable("Error register", 0x1001, 0, dt.UNSIGNED8, "ro", 0x11))
    errors = odm.ODArray("Pre-defined error field", 0x1003)
    errors.add_member(variable("Number of errors", 0x1003, 0, dt.UNSIGNED8, "rw", 2))
    # Newest first: 8120h CAN in error passive mode, then 3210h DC link
    # over-voltage with manufacturer information 0012h in the high word.
    errors.add_member(variable("Standard error field", 0x1003, 1, dt.UNSIGNED32, "ro", 0x00008120))
    errors.add_member(variable("Standard error field 2", 0x1003, 2, dt.UNSIGNED32, "ro", 0x00123210))
    od.add_object(errors)
    od.add_object(variable("Manufacturer device name", 0x1008, 0, dt.VISIBLE_STRING, "const", DEVICE_NAME))
    od.add_object(variable("Manufacturer software version", 0x100A, 0, dt.VISIBLE_STRING, "const", SOFTWARE_VERSION))
    identity = odm.ODRecord("Identity object", 0x1018)
    identity.add_member(variable("Highest sub-index supported", 0x1018, 0, dt.UNSIGNED8, "const", 4))
    identity.add_member(variable("Vendor-ID", 0x1018, 1, dt.UNSIGNED32, "ro", 0x0000006A))
    identity.add_member(variable("Product code", 0x1018, 2, dt.UNSIGNED32, "ro", 0x00001234))
    identity.add_member(variable("Revision number", 0x1018, 3, dt.UNSIGNED32, "ro", 0x00010002))
    identity.add_member(variable("Serial number", 0x1018, 4, dt.UNSIGNED32, "ro", 0x00C0FFEE))
    od.add_object(identity)
    od.add_object(variable("Test u8", 0x2000, 0, dt.UNSIGNED8, "rw", 0))
    od.add_object(variable("Test u16", 0x2001, 0, dt.UNSIGNED16, "rw", 0x1234))
    od.add_object(variable("Test 3 bytes", 0x2002, 0, dt.OCTET_STRING, "rw", b"\xa1\xb2\xc3"))
    od.add_object(variable("Test u32", 0x2003, 0, dt.UNSIGNED32, "rw", 0))
    od.add_object(variable("Test write-only", 0x2004, 0, dt.UNSIGNED32, "wo", 0))
    od.add_object(variable("Test domain", 0x2100, 0, dt.DOMAIN, "rw", DOMAIN_140))
    od.add_object(variable("Test domain 2", 0x2101, 0, dt.DOMAIN, "rw", b""))
    od.add_object(variable("Test domain 3", 0x2102, 0, dt.DOMAIN, "rw", b""))
    od.add_object(variable("Block source 61", 0x2200, 0, dt.DOMAIN, "rw", bytes(range(0x40, 0x40 + 61))))
    od.add_object(variable("Block source 45", 0x2201, 0, dt.DOMAIN, "rw", bytes(range(0x80, 0x80 + 45))))
    od.add_object(variable("Block source 28", 0x2202, 0, dt.DOMAIN, "rw", b"block upload, no CRC at all."))
    od.add_object(variable("Block source 20", 0x2203, 0, dt.DOMAIN, "rw", b"cc=0 but server sc=1"))
    od.add_object(variable("Block sink", 0x2300, 0, dt.DOMAIN, "rw", b""))
    od.add_object(variable("Block sink 2", 0x2301, 0, dt.DOMAIN, "rw", b""))
    od.add_object(variable("Block sink 3", 0x2302, 0, dt.DOMAIN, "rw", b""))
    od.add_object(variable("Unsized u16", 0x2400, 0, dt.UNSIGNED16, "ro", 0xBEEF))
    od.add_object(variable("Unsized string", 0x2401, 0, dt.VISIBLE_STRING, "ro", "size not indicated"))
    return od


# ---------------------------------------------------------------------------
# Node 6's server: python-canopen's SdoServer plus block services (CiA 301)

ABORT_CODE = sdo_client_mod.ABORT_INVALID_COMMAND_SPECIFIER  # 0504 0001


class ScriptedSdoServer(SdoServer):
    """python-canopen's SdoServer; block upload and block download (CiA 301
    7.2.4.3.x: initiate, sub-blocks of `blksize` segments each confirmed
    with ackseq, end with CRC-16/XMODEM) are written here, and the objects
    in `unsized` are answered with an initiate upload response that does not
    indicate the size (s = 0)."""

    def __init__(self, rx_cobid, tx_cobid, node, blksize=4):
        super().__init__(rx_cobid, tx_cobid, node)
        self.blksize = blksize  # segments per sub-block we ask for (download)
        self.crc_capable = True  # what we answer in the sc bit
        self.unsized = set()
        self.blk = None  # state of the open block transfer

    # -- dispatch: inside a block transfer the frames are ours -------------
    def on_request(self, can_id, data, timestamp):
        if self.blk is not None:
            try:
                self.block_frame(bytes(data))
            except SdoAbortedError as exc:
                self.blk = None
                self.abort(exc.code)
            return
        super().on_request(can_id, data, timestamp)

    def init_upload(self, request):
        _, index, subindex = struct.unpack_from("<BHB", request)
        if (index, subindex) not in self.unsized:
            return super().init_upload(request)
        self._index, self._subindex = index, subindex
        data = self._node.get_data(index, subindex, check_readable=True)
        response = bytearray(8)
        if len(data) <= 4:
            # e = 1, s = 0: four data bytes, the size not indicated.
            struct.pack_into("<BHB", response, 0, 0x42, index, subindex)
            response[4:4 + len(data)] = data
        else:
            # e = 0, s = 0: segmented, the size not indicated.
            struct.pack_into("<BHB", response, 0, 0x40, index, subindex)
            self._buffer = bytearray(data)
            self._toggle = 0
        self.send_response(response)

    def send(self, frame):
        self.network.send_message(self.tx_cobid, bytes(frame))

    # -- block download ---------------------------------------------------
    def block_download(self, data):
        cmd, index, subindex = struct.unpack_from("<BHB", data)
        self._index, self._subindex = index, subindex
        if cmd & 0x01:  # cs must be 0 (initiate) outside a transfer
            raise SdoAbortedError(ABORT_CODE)
        obj = self._node._find_object(index, subindex)
        if not obj.writable:
            raise SdoAbortedError(0x06010002)
        size = struct.unpack_from("<L", data, 4)[0] if cmd & 0x02 else None
        self.blk = {
            "kind": "download", "state": "segments", "size": size,
            "crc": bool(cmd & 0x04) and self.crc_capable,
            "data": bytearray(), "seqno": 0, "received": 0,
        }
        response = bytearray(8)
        struct.pack_into("<BHBB", response, 0, 0xA0 | (0x04 if self.crc_capable else 0),
                         index, subindex, self.blksize)
        self.send(response)

    def block_frame(self, data):
        blk = self.blk
        if data[0] == 0x80:  # abort from the client (seqno 0 is no segment)
            self.request_aborted(data)
            self.blk = None
            return
        if blk["kind"] == "download":
            self.block_download_frame(blk, data)
        else:
            self.block_upload_frame(blk, data)

    def block_download_frame(self, blk, data):
        if blk["state"] == "segments":
            seqno, last = data[0] & 0x7F, bool(data[0] & 0x80)
            blk["received"] += 1
            if seqno == blk["seqno"] + 1:
                blk["seqno"] = seqno
                blk["data"] += data[1:8]
                blk["last"] = last
            if blk["received"] >= self.blksize or last:
                # Confirm the sub-block: ackseq = last segment received in order.
                self.send(bytes([0xA2, blk["seqno"], self.blksize, 0, 0, 0, 0, 0]))
                if blk.get("last"):
                    blk["state"] = "end"
                blk["seqno"] = blk["received"] = 0
            return
        # state "end": the client's end request (ccs 6, cs 1)
        if data[0] & 0xE3 != 0xC1:
            raise SdoAbortedError(ABORT_CODE)
        unused = (data[0] >> 2) & 0x7
        if unused:
            del blk["data"][-unused:]
        if blk["size"] is not None and blk["size"] != len(blk["data"]):
            raise SdoAbortedError(0x06070010)
        if blk["crc"]:
            crc = struct.unpack_from("<H", data, 1)[0]
            if crc != binascii.crc_hqx(bytes(blk["data"]), 0):
                raise SdoAbortedError(0x05040004)
        self._node.set_data(self._index, self._subindex, bytes(blk["data"]), check_writable=True)
        self.blk = None
        self.send(bytes([0xA1, 0, 0, 0, 0, 0, 0, 0]))

    # -- block upload -----------------------------------------------------
    def block_upload(self, data):
        cmd, index, subindex, blksize, _pst = struct.unpack_from("<BHBBB", data)
        self._index, self._subindex = index, subindex
        if cmd & 0x03:  # cs must be 0 (initiate) outside a transfer
            raise SdoAbortedError(ABORT_CODE)
        if not 1 <= blksize <= 127:
            raise SdoAbortedError(0x05040002)
        payload = self._node.get_data(index, subindex, check_readable=True)
        self.blk = {
            "kind": "upload", "state": "start", "data": bytes(payload),
            "pos": 0, "sent": 0, "blksize": blksize,
            "crc": bool(cmd & 0x04) and self.crc_capable,
        }
        response = bytearray(8)
        struct.pack_into("<BHBL", response, 0, 0xC2 | (0x04 if self.crc_capable else 0),
                         index, subindex, len(payload))
        self.send(response)

    def send_sub_block(self, blk):
        pos, seqno = blk["pos"], 0
        while seqno < blk["blksize"] and pos < len(blk["data"]):
            seqno += 1
            chunk = blk["data"][pos:pos + 7]
            pos += len(chunk)
            last = 0x80 if pos >= len(blk["data"]) else 0
            self.send(bytes([last | seqno]) + chunk.ljust(7, b"\x00"))
        blk["sent"] = seqno
        blk["state"] = "ack"

    def block_upload_frame(self, blk, data):
        cmd = data[0]
        if blk["state"] == "start":
            if cmd != 0xA3:
                raise SdoAbortedError(ABORT_CODE)
            self.send_sub_block(blk)
        elif blk["state"] == "ack":
            if cmd & 0xE3 != 0xA2:
                raise SdoAbortedError(ABORT_CODE)
            ackseq, blksize = data[1], data[2]
            if not 1 <= blksize <= 127:
                raise SdoAbortedError(0x05040002)
            blk["pos"] = min(blk["pos"] + 7 * ackseq, len(blk["data"]))
            blk["blksize"] = blksize
            if blk["pos"] < len(blk["data"]):
                self.send_sub_block(blk)
                return
            unused = (7 - len(blk["data"]) % 7) % 7
            crc = binascii.crc_hqx(blk["data"], 0) if blk["crc"] else 0
            self.send(struct.pack("<BH5x", 0xC1 | (unused << 2), crc))
            blk["state"] = "end"
        else:  # "end": the client's end response (ccs 5, cs 1) closes it
            if cmd & 0xE3 != 0xA1:
                raise SdoAbortedError(ABORT_CODE)
            self.blk = None


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


def settle(recorder, quiet=0.08):
    """The number of recorded frames once the bus has been quiet for `quiet` s."""
    last, since = recorder.count(), time.monotonic()
    while time.monotonic() - since < quiet:
        time.sleep(0.005)
        now = recorder.count()
        if now != last:
            last, since = now, time.monotonic()
    return last


def main():
    os.makedirs(OUT, exist_ok=True)
    recorder = Recorder()
    rec_bus = can.Bus(interface="virtual", channel=IFACE)
    rec_notifier = can.Notifier(rec_bus, [recorder])

    servers = canopen.Network()
    servers.connect(interface="virtual", channel=IFACE)
    node5 = canopen.LocalNode(5, server_od())
    servers.add_node(node5)
    node6 = canopen.LocalNode(6, server_od())
    node6.sdo = ScriptedSdoServer(0x606, 0x586, node6)
    servers.add_node(node6)
    node6.sdo.unsized = {(0x2400, 0), (0x2401, 0)}

    clients = canopen.Network()
    clients.connect(interface="virtual", channel=IFACE)
    # The client knows no object dictionary (as a generic tool): upload()
    # then returns the bytes the server sent, never truncated to a type.
    c5 = clients.add_node(canopen.RemoteNode(5, odm.ObjectDictionary()))
    c6 = clients.add_node(canopen.RemoteNode(6, odm.ObjectDictionary()))
    c9 = clients.add_node(canopen.RemoteNode(9, odm.ObjectDictionary()))

    transfers = []

    def run(client, direction, index, sub, action, block=False, note=""):
        first = settle(recorder) + 1
        outcome, code, data, error = "ok", None, None, None
        try:
            data = action()
        except SdoAbortedError as exc:
            outcome, code, error = "abort", exc.code, repr(exc)
        except SdoCommunicationError as exc:
            outcome, error = "abort", repr(exc)
        last = settle(recorder)
        transfers.append({
            "node": client.id, "iface": IFACE, "direction": direction,
            "index": index, "subindex": sub, "block": block,
            "outcome": outcome, "abort_code": code, "data_bytes": data,
            "python_canopen_error": error, "note": note,
            "first_line": first, "last_line": last,
        })
        return data

    def upload(client, index, sub, note=""):
        return run(client, "upload", index, sub, lambda: client.sdo.upload(index, sub), note=note)

    def download(client, index, sub, data, note="", indicate_size=True):
        def act():
            if indicate_size:
                client.sdo.download(index, sub, data)
            else:  # open() without a size: s = 0
                with client.sdo.open(index, sub, "wb") as f:
                    f.write(data)
            return data  # what the client wrote
        return run(client, "download", index, sub, act, note=note)

    def block_upload(client, index, sub, crc=True, note=""):
        def act():
            with client.sdo.open(index, sub, "rb", block_transfer=True,
                                 request_crc_support=crc) as f:
                return f.read()
        return run(client, "upload", index, sub, act, block=True, note=note)

    def block_download(client, index, sub, data, crc=True, note=""):
        def act():
            with client.sdo.open(index, sub, "wb", size=len(data), block_transfer=True,
                                 request_crc_support=crc) as f:
                f.write(data)
            return data
        return run(client, "download", index, sub, act, block=True, note=note)

    # --- node 5: python-canopen on both sides -----------------------------
    upload(c5, 0x1000, 0, "expedited upload, 4 bytes")
    upload(c5, 0x1001, 0, "expedited upload, 1 byte")
    upload(c5, 0x1003, 0, "1003h sub 0: number of errors")
    upload(c5, 0x1003, 1, "1003h sub 1: newest error")
    upload(c5, 0x1003, 2, "1003h sub 2")
    upload(c5, 0x2001, 0, "expedited upload, 2 bytes")
    upload(c5, 0x2002, 0, "expedited upload, 3 bytes")
    upload(c5, 0x1018, 1, "expedited upload of a record's sub-index")
    download(c5, 0x2000, 0, b"\x7f", "expedited download, 1 byte")
    download(c5, 0x2001, 0, b"\x34\x12", "expedited download, 2 bytes")
    download(c5, 0x2002, 0, b"\x01\x02\x03", "expedited download, 3 bytes")
    download(c5, 0x2003, 0, b"\x78\x56\x34\x12", "expedited download, 4 bytes")
    upload(c5, 0x1008, 0, "segmented upload, 21 bytes: the last segment is full")
    upload(c5, 0x100A, 0, "segmented upload, 23 bytes")
    download(c5, 0x2101, 0, b"segmented download 27", "segmented download, 21 bytes (last segment full)")
    download(c5, 0x2100, 0, bytes(reversed(DOMAIN_140)), "segmented download, 140-byte DOMAIN")
    upload(c5, 0x2100, 0, "segmented upload, 140-byte DOMAIN (reads back the download)")
    download(c5, 0x2102, 0, b"0123456789", indicate_size=False,
             note="segmented download, size not indicated: python-canopen ends it with an empty last segment")
    download(c5, 0x2101, 0, b"twenty bytes of data", "segmented download, 20 bytes")
    upload(c5, 0x6000, 0, "abort by the server: object does not exist")
    upload(c5, 0x1018, 7, "abort by the server: sub-index does not exist")
    download(c5, 0x1000, 0, b"\x00\x00\x00\x00", "abort by the server: expedited download to a read-only object")
    download(c5, 0x2003, 0, b"\x01\x00", "abort by the server: length does not match the type")
    upload(c5, 0x2004, 0, "abort by the server: read of a write-only object")
    download(c5, 0x1008, 0, b"renamed drive 0123456",
             "abort by the server: segmented download to a const object, aborted only at the last segment")
    block_download(c5, 0x2300, 0, b"no block download here",
                   note="python-canopen's server has no block download: it aborts 0504 0001")
    block_upload(c5, 0x1008, 0,
                 note="python-canopen's server answers a block upload with an initiate upload response; the client aborts")
    upload(c9, 0x1000, 0, "no server on node 9: the client times out (0.3 s) and aborts 0504 0000")

    # --- node 6: python-canopen client, scripted block server ---------------
    block_upload(c6, 0x2200, 0, note="block upload, 61 bytes, CRC, one sub-block (client blksize 127)")
    sdo_client_mod.BlockUploadStream.blksize = 4
    block_upload(c6, 0x2201, 0, note="block upload, 45 bytes, CRC, client blksize 4: two sub-blocks")
    sdo_client_mod.BlockUploadStream.blksize = 127
    node6.sdo.crc_capable = False
    block_upload(c6, 0x2202, 0, crc=False, note="block upload, 28 bytes, no CRC (cc = 0, sc = 0)")
    node6.sdo.crc_capable = True
    block_upload(c6, 0x2203, 0, crc=False,
                 note="block upload, cc = 0 and sc = 1: CiA 301 says no CRC (crc = 0); python-canopen checks one")
    block_download(c6, 0x2300, 0, bytes(range(0xC0, 0xC0 + 45)),
                   note="block download, 45 bytes, CRC, server blksize 4: two sub-blocks")
    block_download(c6, 0x2301, 0, b"block download, without CRC.",
                   crc=False, note="block download, 28 bytes, cc = 0, sc = 1")
    node6.sdo.crc_capable = False
    block_download(c6, 0x2302, 0, b"ten bytes!", note="block download, 10 bytes, cc = 1, sc = 0")
    node6.sdo.crc_capable = True
    upload(c6, 0x2400, 0, "expedited upload, size not indicated (scripted server)")
    upload(c6, 0x2401, 0, "segmented upload, size not indicated (scripted server)")
    upload(c6, 0x1003, 1, "1003h sub 1 on the second node")

    settle(recorder, 0.2)
    clients.disconnect()
    servers.disconnect()
    rec_notifier.stop()
    rec_bus.shutdown()

    frames = recorder.frames
    with can.CanutilsLogWriter(LOG, channel=IFACE) as writer:
        for msg in frames:
            writer.on_message_received(msg)

    check_and_describe(frames, transfers)
    with open(TRUTH, "w") as f:
        json.dump(transfers, f, indent=1)
        f.write("\n")
    print(f"{len(frames)} frames, {len(transfers)} transfers")
    print("python-canopen", canopen.__version__, "python-can", can.__version__)


def check_and_describe(frames, transfers):
    """Check that the transfers cover the log line by line, each with its own
    node's frames only, and fill in the keys read from the frames."""
    expect = 1
    for t in transfers:
        assert t["first_line"] == expect, (t, expect)
        assert t["last_line"] >= t["first_line"], t
        expect = t["last_line"] + 1
        own = frames[t["first_line"] - 1:t["last_line"]]
        node = t["node"]
        for msg in own:
            assert msg.arbitration_id in (0x600 + node, 0x580 + node), (t, msg)
            assert len(msg.data) == 8, msg
        req = bytes(own[0].data)
        assert own[0].arbitration_id == 0x600 + node, t
        ccs = req[0] >> 5
        # What the initiate frames say.
        expedited, size_indicated = False, None
        if not t["block"] and ccs == 1:  # initiate download request
            expedited = bool(req[0] & 0x02)
            if req[0] & 0x01:
                size_indicated = 4 - ((req[0] >> 2) & 3) if expedited else struct.unpack_from("<L", req, 4)[0]
        elif not t["block"] and ccs == 2 and len(own) > 1 and own[1].data[0] >> 5 == 2:
            res = bytes(own[1].data)
            expedited = bool(res[0] & 0x02)
            if res[0] & 0x01:
                size_indicated = 4 - ((res[0] >> 2) & 3) if expedited else struct.unpack_from("<L", res, 4)[0]
        elif t["block"] and ccs == 6 and req[0] & 0x02:
            size_indicated = struct.unpack_from("<L", req, 4)[0]
        elif t["block"] and len(own) > 1 and own[1].data[0] >> 5 == 6 and own[1].data[0] & 0x02:
            size_indicated = struct.unpack_from("<L", bytes(own[1].data), 4)[0]
        t["frames"] = len(own)
        t["expedited"] = expedited
        t["size_indicated"] = size_indicated
        # Aborts: who sent the abort frame and its code (the last frame).
        end = own[-1]
        if t["outcome"] == "abort":
            assert end.data[0] == 0x80, (t, end)
            code = struct.unpack_from("<L", bytes(end.data), 4)[0]
            by = "server" if end.arbitration_id == 0x580 + node else "client"
            if t["abort_code"] is not None:
                assert t["abort_code"] == code, (t, code)
            t["abort_code"] = code
            t["abort_by"] = by
            t["size"], t["data"] = None, None
        else:
            assert not any(m.data[0] == 0x80 and m.arbitration_id in (0x580 + node,) for m in own), t
            t["abort_by"] = None
            t["size"] = len(t["data_bytes"])
            t["data"] = bytes(t["data_bytes"]).hex()
        del t["data_bytes"]
    assert expect == len(frames) + 1, (expect, len(frames))
    order = ["node", "iface", "direction", "index", "subindex", "size", "size_indicated",
             "data", "outcome", "abort_code", "abort_by", "block", "expedited",
             "frames", "first_line", "last_line", "note", "python_canopen_error"]
    for i, t in enumerate(transfers):
        transfers[i] = {k: t[k] for k in order}


if __name__ == "__main__":
    sys.exit(main())
