#!/usr/bin/env python3
"""A small pcapng writer for synthetic EtherCAT captures (stdlib only).

What a capture on an EtherCAT master's port holds (SPEC §12.1): every
frame twice, as the master sent it and as it came back through the slaves,
the returned copy with bit 0x02 of the source MAC's first byte set, read
data filled in, working counters counted up and auto-increment addresses
(APxx, BRx) counted on by every slave it passed.

Building blocks:

  pcapng          Pcapng(path, iface=...).packet(ts_ns, frame) ... .close()
                  (little-endian section, one Ethernet interface, link
                  type 1, nanosecond timestamps)
  datagrams       aprd / apwr / fprd / fpwr / brd / bwr / lrw build a
                  Datagram that knows its sent and its returned form
  frames          ecat_frame(src_mac, datagrams, returned) -> Ethernet bytes
                  (EtherType 0x88A4, EtherCAT header type 1; sent frames
                  unpadded as ethercrab's captures show them, returned
                  ones padded to 60 bytes)
  bus             Bus(...).exchange(t_ns, [datagram, ...]) writes the sent
                  copy at t and the returned copy shortly after
  mailbox / CoE   mailbox(), coe_sdo(), coe_emergency(), sdo_upload_*()
  registers       al_status(state, error, code, length), sii_words(), sm(),
                  fmmu()

Run as a program it writes tests/data/ethercat/synthetic_akd_fault.pcapng
(or the path given with --out): an ethercrab-style master (MAC
10:10:10:10:10:10) and two slaves — 0x1000 an EK1100-like coupler, 0x1001
an AKD (vendor 0x6A, product 0x414B44) — start-up, 200 LRW cycles at 1 ms,
a CoE emergency 0x7305 from the AKD, its AL status SAFEOP + error with code
0x001B, and the LRW working counter falling from 3 to 1 for the last 50
cycles. The README of tests/data/ethercat lists the frames. Deterministic:
fixed start time, no randomness; re-running writes the same bytes.
"""

import argparse
import os
import struct

ETHERTYPE_ECAT = 0x88A4

# Commands (ETG.1000.4; SPEC §12.1)
NOP, APRD, APWR, APRW, FPRD, FPWR, FPRW, BRD, BWR, BRW, LRD, LWR, LRW, \
    ARMW, FRMW = range(15)
LOGICAL = (LRD, LWR, LRW)
AUTO_INCREMENT = (APRD, APWR, APRW, BRD, BWR, BRW, ARMW)

# AL states (register 0x0130)
INIT, PREOP, BOOT, SAFEOP, OP = 1, 2, 3, 4, 8
AL_ERROR = 0x10

# Mailbox types and CoE services (SPEC §12.3)
MBX_COE = 3
COE_EMERGENCY, COE_SDO_REQUEST, COE_SDO_RESPONSE = 1, 2, 3


# --------------------------------------------------------------- pcapng --

def _pad4(b):
    return b + b"\0" * (-len(b) % 4)


def _option(code, value):
    return struct.pack("<HH", code, len(value)) + _pad4(value)


def _block(block_type, body):
    total = 12 + len(body)
    return struct.pack("<II", block_type, total) + body + struct.pack(
        "<I", total)


class Pcapng:
    """Writes one pcapng section with one Ethernet interface."""

    def __init__(self, path, iface="eth0", application="ecat_pcapng.py"):
        self.fh = open(path, "wb")
        shb = struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1)
        shb += _option(4, application.encode()) + _option(0, b"")
        self.fh.write(_block(0x0A0D0D0A, shb))
        idb = struct.pack("<HHI", 1, 0, 0)  # LINKTYPE_ETHERNET, snaplen 0
        idb += _option(2, iface.encode())  # if_name
        idb += _option(9, bytes([9]))  # if_tsresol: nanoseconds
        idb += _option(0, b"")
        self.fh.write(_block(1, idb))
        self.count = 0

    def packet(self, ts_ns, frame):
        body = struct.pack("<IIIII", 0, ts_ns >> 32, ts_ns & 0xFFFFFFFF,
                           len(frame), len(frame)) + _pad4(frame)
        self.fh.write(_block(6, body))
        self.count += 1

    def close(self):
        self.fh.close()


# ------------------------------------------------------------ datagrams --

class Datagram:
    """One datagram in its sent and its returned form.

    adp/ado (or lad for LRD/LWR/LRW) are the sent copy's; the returned copy
    has adp counted on by every slave for auto-increment commands (the bus
    does it), data = ret_data and working counter = wkc.
    """

    def __init__(self, cmd, adp=0, ado=0, lad=None, data=b"",
                 ret_data=None, wkc=0, irq=0):
        self.cmd, self.adp, self.ado, self.lad = cmd, adp, ado, lad
        self.data = bytes(data)
        self.ret_data = self.data if ret_data is None else bytes(ret_data)
        if len(self.ret_data) != len(self.data):
            raise ValueError("returned data must keep the datagram's length")
        self.wkc, self.irq = wkc, irq

    def encode(self, idx, more, returned, n_slaves):
        if self.cmd in LOGICAL:
            address = struct.pack("<I", self.lad)
        else:
            adp = self.adp
            if returned and self.cmd in AUTO_INCREMENT:
                adp = (adp + n_slaves) & 0xFFFF
            address = struct.pack("<HH", adp, self.ado)
        data = self.ret_data if returned else self.data
        length = len(data) | (0x8000 if more else 0)
        wkc = self.wkc if returned else 0
        return (struct.pack("<BB", self.cmd, idx) + address
                + struct.pack("<HH", length, self.irq) + data
                + struct.pack("<H", wkc))


def _position_adp(position):
    return (-position) & 0xFFFF


def aprd(position, ado, length, ret_data=None, wkc=1):
    return Datagram(APRD, _position_adp(position), ado, data=bytes(length),
                    ret_data=ret_data, wkc=wkc)


def apwr(position, ado, data, wkc=1):
    return Datagram(APWR, _position_adp(position), ado, data=data, wkc=wkc)


def fprd(station, ado, length, ret_data=None, wkc=1):
    return Datagram(FPRD, station, ado, data=bytes(length),
                    ret_data=ret_data, wkc=wkc)


def fpwr(station, ado, data, wkc=1):
    return Datagram(FPWR, station, ado, data=data, wkc=wkc)


def brd(ado, length, ret_data=None, wkc=0):
    return Datagram(BRD, 0, ado, data=bytes(length), ret_data=ret_data,
                    wkc=wkc)


def bwr(ado, data, wkc=0):
    return Datagram(BWR, 0, ado, data=data, wkc=wkc)


def lrw(lad, data, ret_data, wkc):
    return Datagram(LRW, lad=lad, data=data, ret_data=ret_data, wkc=wkc)


# --------------------------------------------------------------- frames --

def mac_bytes(mac):
    return bytes(int(x, 16) for x in mac.split(":"))


def ecat_frame(src_mac, datagrams, first_idx, returned, n_slaves,
               dst_mac="ff:ff:ff:ff:ff:ff"):
    """Ethernet + EtherCAT header (type 1) + datagrams; returns bytes."""
    src = bytearray(mac_bytes(src_mac))
    if returned:
        src[0] |= 0x02
    body = b""
    for i, dg in enumerate(datagrams):
        body += dg.encode((first_idx + i) & 0xFF, i + 1 < len(datagrams),
                          returned, n_slaves)
    if len(body) > 0x7FF:
        raise ValueError("EtherCAT frame longer than 2047 bytes")
    frame = (mac_bytes(dst_mac) + bytes(src)
             + struct.pack(">H", ETHERTYPE_ECAT)
             + struct.pack("<H", len(body) | (1 << 12)) + body)
    if returned and len(frame) < 60:
        frame += bytes(60 - len(frame))
    return frame


class Bus:
    """A master's port: each exchange writes the sent and returned copy."""

    def __init__(self, pcap, master_mac, n_slaves, return_ns=18_000):
        self.pcap, self.mac, self.n = pcap, master_mac, n_slaves
        self.idx = 0
        self.return_ns = return_ns
        self.exchanges = []  # (sent packet number, datagrams, note)

    def exchange(self, t_ns, datagrams, note="", lost=False):
        first = self.idx
        self.idx = (self.idx + len(datagrams)) & 0xFF
        self.pcap.packet(t_ns, ecat_frame(self.mac, datagrams, first, False,
                                          self.n))
        self.exchanges.append((self.pcap.count, datagrams, note))
        if not lost:
            self.pcap.packet(t_ns + self.return_ns,
                             ecat_frame(self.mac, datagrams, first, True,
                                        self.n))


# ------------------------------------------------------- mailbox / CoE --

def mailbox(mbx_type, counter, payload, address=0, channel=0, priority=0):
    """6-byte mailbox header + payload (SPEC §12.3)."""
    return struct.pack("<HHBB", len(payload), address,
                       (channel & 0x3F) | (priority & 3) << 6,
                       (mbx_type & 0x0F) | (counter & 7) << 4) + payload


def coe_header(service, number=0):
    return struct.pack("<H", (number & 0x1FF) | (service & 0x0F) << 12)


def coe_sdo(counter, service, command, index, sub, data=b"\0\0\0\0"):
    """A CoE SDO message of 10 bytes (CiA 301 command, index, sub, 4 data)."""
    payload = (coe_header(service) + struct.pack("<BHB", command, index, sub)
               + bytes(data).ljust(4, b"\0"))
    return mailbox(MBX_COE, counter, payload)


def sdo_upload_request(counter, index, sub):
    return coe_sdo(counter, COE_SDO_REQUEST, 0x40, index, sub)


def sdo_upload_response(counter, index, sub, value, size):
    """Expedited upload response: 0x4F/0x4B/0x47/0x43 for 1/2/3/4 bytes."""
    command = 0x43 | (4 - size) << 2
    return coe_sdo(counter, COE_SDO_RESPONSE, command, index, sub,
                   value.to_bytes(4, "little"))


def coe_emergency(counter, code, register, manufacturer=b""):
    """CoE emergency: CoE header (service 1) + the 8-byte EMCY of SPEC §2."""
    emcy = struct.pack("<HB", code, register) + bytes(manufacturer).ljust(
        5, b"\0")[:5]
    return mailbox(MBX_COE, counter, coe_header(COE_EMERGENCY) + emcy)


def akd_manufacturer(axis, feedback):
    """SPEC §2.4: byte 3 = axis id (bits 0-3) | feedback id (bits 4-7)."""
    return bytes([(axis & 0x0F) | (feedback & 0x0F) << 4, 0, 0, 0, 0])


# ------------------------------------------------------------ registers --

def al_status(state, error=False, code=0, length=2):
    """Register 0x0130 read with `length` bytes: 2 = status only, 6 =
    status, reserved, AL status code (TwinCAT and SOEM); al_status_code()
    is 0x0134 alone (ethercrab)."""
    status = state | (AL_ERROR if error else 0)
    raw = struct.pack("<HHH", status, 0, code)
    return raw[:length]


def al_status_code(code):
    return struct.pack("<H", code)


def al_control(state, ack=False):
    return struct.pack("<H", state | (AL_ERROR if ack else 0))


def sm(start, length, control, activate=1):
    """One sync manager (8 bytes at 0x0800 + 8 n)."""
    return struct.pack("<HHBBBB", start, length, control, 0, activate, 0)


def fmmu(logical, length, physical, kind, start_bit=0, stop_bit=7):
    """One FMMU (16 bytes at 0x0600 + 16 n); kind 1 read, 2 write."""
    return struct.pack("<IHBBHBBB3x", logical, length, start_bit, stop_bit,
                       physical, 0, kind, 1)


def sii_words(eeprom, word):
    """Two SII words from a dict word -> u16, as a 4-byte 0x0508 read."""
    return struct.pack("<HH", eeprom.get(word, 0), eeprom.get(word + 1, 0))


def eeprom_image(vendor, product, revision, serial, mbx=None):
    words = {}
    for w, v in ((0x08, vendor), (0x0A, product), (0x0C, revision),
                 (0x0E, serial)):
        words[w], words[w + 1] = v & 0xFFFF, v >> 16
    if mbx:
        (words[0x18], words[0x19], words[0x1A], words[0x1B]) = mbx
    return words


# ------------------------------------------------------ the AKD scenario --

MASTER = "10:10:10:10:10:10"
COUPLER, AKD = 0x1000, 0x1001
T0_NS = 1_767_225_600 * 1_000_000_000  # 2026-01-01T00:00:00Z
MBX_OUT, MBX_IN, MBX_SIZE = 0x1800, 0x1C00, 0x400
SM2_OUT, SM3_IN = 0x1100, 0x1180
CYCLES, BAD_CYCLES = 200, 50


def write_akd_fault(path):
    pcap = Pcapng(path, iface="enp2s0")
    bus = Bus(pcap, MASTER, n_slaves=2)
    t = T0_NS
    step = 200_000  # start-up: one exchange every 200 µs

    def ex(datagrams, note=""):
        nonlocal t
        bus.exchange(t, datagrams, note)
        t += step

    slaves = {
        COUPLER: eeprom_image(0x2, 0x044C2C52, 0x00120000, 0),
        AKD: eeprom_image(0x6A, 0x414B44, 0x2, 0x00012345,
                          mbx=(MBX_OUT, MBX_SIZE, MBX_IN, MBX_SIZE)),
    }

    # Bus reset and discovery
    ex([brd(0x0000, 1, b"\x11", wkc=2)], "count slaves")
    ex([bwr(0x0010, b"\0\0", wkc=2)], "clear station addresses")
    ex([bwr(0x0120, al_control(INIT, ack=True), wkc=2)], "AL control INIT")
    for position, station in enumerate((COUPLER, AKD)):
        ex([apwr(position, 0x0010, struct.pack("<H", station))],
           "station address")
        ex([aprd(position, 0x0010, 2, struct.pack("<H", station))],
           "station address read back")

    # SII identity, per slave: address write, status poll, 4-byte read
    for station, eeprom in slaves.items():
        words = (0x08, 0x0A, 0x0C, 0x0E) + ((0x18, 0x1A) if station == AKD
                                             else ())
        for word in words:
            ex([fpwr(station, 0x0502, struct.pack("<HHH", 0x0100, word, 0))],
               "SII read word 0x%02X" % word)
            ex([fprd(station, 0x0502, 2, b"\x40\x00")], "SII status")
            ex([fprd(station, 0x0508, 4, sii_words(eeprom, word))],
               "SII data")

    # Mailbox sync managers of the AKD, then PREOP
    ex([fpwr(AKD, 0x0800, sm(MBX_OUT, MBX_SIZE, 0x26)
             + sm(MBX_IN, MBX_SIZE, 0x22))], "SM0/SM1 mailbox")
    for state in (PREOP,):
        for station in slaves:
            ex([fpwr(station, 0x0120, al_control(state))], "AL control")
        for station in slaves:
            ex([fprd(station, 0x0130, 2, al_status(state))], "AL status")

    # PDO assignment and mapping, uploaded over CoE (mailbox counter 1..7)
    uploads = [
        (0x1C12, 1, 0x1600, 2), (0x1600, 0, 2, 1),
        (0x1600, 1, 0x60400010, 4), (0x1600, 2, 0x607A0020, 4),
        (0x1C13, 1, 0x1A00, 2), (0x1A00, 0, 2, 1),
        (0x1A00, 1, 0x60410010, 4), (0x1A00, 2, 0x60640020, 4),
    ]
    counter = 0
    for index, sub, value, size in uploads:
        counter = counter % 7 + 1
        req = sdo_upload_request(counter, index, sub).ljust(MBX_SIZE, b"\0")
        res = sdo_upload_response(counter, index, sub, value, size).ljust(
            MBX_SIZE, b"\0")
        ex([fpwr(AKD, MBX_OUT, req)], "SDO upload request")
        ex([fprd(AKD, 0x080D, 1, b"\x08")], "SM1 status: mailbox full")
        ex([fprd(AKD, MBX_IN, MBX_SIZE, res)], "SDO upload response")

    # Process data: SM2 outputs (6 B), SM3 inputs (6 B), FMMU0/1, SAFEOP, OP
    ex([fpwr(AKD, 0x0810, sm(SM2_OUT, 6, 0x64) + sm(SM3_IN, 6, 0x20))],
       "SM2/SM3 process data")
    ex([fpwr(AKD, 0x0600, fmmu(0x0, 6, SM2_OUT, 2) + fmmu(0x6, 6, SM3_IN, 1))],
       "FMMU0 outputs, FMMU1 inputs")
    for state in (SAFEOP, OP):
        for station in slaves:
            ex([fpwr(station, 0x0120, al_control(state))], "AL control")
        for station in slaves:
            ex([fprd(station, 0x0130, 2, al_status(state))], "AL status")
    ex([brd(0x0130, 2, al_status(OP), wkc=2)], "BRD AL status")

    # Cyclic process data: LRW of 12 bytes at 1 ms; the AKD's outputs
    # (controlword 0x6040, target 0x607A) and inputs (statusword 0x6041,
    # position actual 0x6064). The sent copy carries the previous cycle's
    # inputs. Every 10th frame also polls the AKD's SM1 status.
    t = (t // 1_000_000 + 1) * 1_000_000
    inputs_prev = bytes(6)
    good = CYCLES - BAD_CYCLES
    for cycle in range(CYCLES):
        faulted = cycle >= good
        target = 1000 * cycle
        outputs = struct.pack("<Hi", 0x000F, target)
        status = 0x0218 if faulted else 0x1237
        inputs = struct.pack("<Hi", status, target - 40)
        datagrams = [lrw(0, outputs + inputs_prev, outputs + inputs,
                         1 if faulted else 3)]
        if cycle % 10 == 9:
            full = cycle == good - 1
            datagrams.append(fprd(AKD, 0x080D, 1,
                                  b"\x08" if full else b"\x00"))
        bus.exchange(t, datagrams, "cycle %d" % (cycle + 1))
        inputs_prev = inputs
        if cycle == good - 1:
            # The AKD faults: an emergency in its mailbox-in SM, then it
            # drops to SAFEOP with the error bit and code 0x001B (sync
            # manager watchdog).
            emcy = coe_emergency(2, 0x7305, 0x81, akd_manufacturer(1, 2))
            bus.exchange(t + 250_000, [fprd(AKD, MBX_IN, MBX_SIZE,
                                            emcy.ljust(MBX_SIZE, b"\0"))],
                         "CoE emergency 0x7305")
            bus.exchange(t + 500_000, [
                fprd(AKD, 0x0130, 2, al_status(SAFEOP, error=True)),
                fprd(AKD, 0x0134, 2, al_status_code(0x001B)),
            ], "AL status SAFEOP+error, code 0x001B")
        t += 1_000_000
    pcap.close()
    return bus


# ------------------------------------------- registers: alias, repeat, DC --

def frmw(station, ado, length, ret_data, wkc):
    return Datagram(FRMW, station, ado, data=bytes(length),
                    ret_data=ret_data, wkc=wkc)


REG_MBX_OUT, REG_MBX_IN, REG_MBX_SIZE = 0x1000, 0x1080, 0x80
ALIAS = 0x0077


def write_registers(path):
    """The registers SPEC §12.2 and §12.3 name that the real fixtures do
    not show (tests/data/ethercat/README.md): the station alias enabled and
    used, SM1 status polls, a mailbox message repeated after a repeat
    request, and the distributed clock configured, read and distributed."""
    pcap = Pcapng(path, iface="enp2s0")
    bus = Bus(pcap, MASTER, n_slaves=2)
    t = T0_NS
    step = 200_000

    def ex(datagrams, note=""):
        nonlocal t
        bus.exchange(t, datagrams, note)
        t += step

    ex([bwr(0x0010, b"\0\0", wkc=2)], "clear station addresses")
    ex([bwr(0x0103, b"\0", wkc=2)], "DL control: alias off on every slave")
    for position, station in enumerate((COUPLER, AKD)):
        ex([apwr(position, 0x0010, struct.pack("<H", station))],
           "station address")
    ex([fprd(AKD, 0x0012, 2, struct.pack("<H", ALIAS))], "alias read")
    ex([fpwr(AKD, 0x0103, b"\x01")], "DL control: alias on")
    ex([fprd(ALIAS, 0x0130, 2, al_status(INIT))], "AL status by alias")

    # Mailbox SM0/SM1, an SDO upload whose response is read twice: the
    # master asks for it again (0x080E bit 1), the slave acknowledges
    # (0x080F bit 1) and puts the same message (counter 1) back.
    ex([fpwr(AKD, 0x0800, sm(REG_MBX_OUT, REG_MBX_SIZE, 0x26)
             + sm(REG_MBX_IN, REG_MBX_SIZE, 0x22))], "SM0/SM1 mailbox")
    req = sdo_upload_request(1, 0x1018, 1).ljust(REG_MBX_SIZE, b"\0")
    res = sdo_upload_response(1, 0x1018, 1, 0x6A, 4).ljust(REG_MBX_SIZE,
                                                           b"\0")
    ex([fpwr(AKD, REG_MBX_OUT, req)], "SDO upload request")
    ex([fprd(AKD, 0x080D, 1, b"\x00")], "SM1 status: empty")
    ex([fprd(AKD, 0x080D, 1, b"\x08")], "SM1 status: full")
    ex([fprd(AKD, REG_MBX_IN, REG_MBX_SIZE, res)], "SDO upload response")
    ex([fprd(AKD, 0x080D, 2, b"\x00\x01")], "SM1 status and activate")
    ex([fpwr(AKD, 0x080D, b"\x00\x03")], "repeat request (0x080E bit 1)")
    ex([fprd(AKD, 0x080F, 1, b"\x02")], "repeat acknowledge (0x080F bit 1)")
    ex([fprd(AKD, 0x080D, 1, b"\x08")], "SM1 status: full again")
    ex([fprd(AKD, REG_MBX_IN, REG_MBX_SIZE, res)], "the response repeated")
    req = sdo_upload_request(2, 0x1018, 2).ljust(REG_MBX_SIZE, b"\0")
    res = sdo_upload_response(2, 0x1018, 2, 0x414B44, 4).ljust(
        REG_MBX_SIZE, b"\0")
    ex([fpwr(AKD, REG_MBX_OUT, req)], "SDO upload request")
    ex([fprd(AKD, REG_MBX_IN, REG_MBX_SIZE, res)], "SDO upload response")

    # Distributed clock: latch, receive times, SYNC0 at 1 ms, difference
    # reads, then the reference clock's time distributed every cycle.
    ex([bwr(0x0900, b"\0\0\0\0", wkc=2)], "latch receive times")
    ex([aprd(1, 0x0900, 16, struct.pack("<IIII", 1000, 1400, 0, 0))],
       "receive times")
    ex([fprd(AKD, 0x0910, 8, struct.pack("<Q", 820_454_400_000_000_000))],
       "system time")
    ex([fpwr(AKD, 0x09A0, struct.pack("<II", 1_000_000, 0))],
       "SYNC0/SYNC1 cycle times")
    ex([fpwr(AKD, 0x0981, b"\x03")], "SYNC activation: cyclic, SYNC0")
    for raw in (0x0000_0014, 0x8000_0009, 0x0000_0003):
        ex([fprd(AKD, 0x092C, 4, struct.pack("<I", raw))],
           "system time difference")
    t = (t // 1_000_000 + 1) * 1_000_000
    for cycle in range(10):
        now = 820_454_400_000_000_000 + 1_000_000 * (cycle + 1)
        bus.exchange(t, [frmw(COUPLER, 0x0910, 8, struct.pack("<Q", now),
                              2)], "DC distribution %d" % (cycle + 1))
        t += 1_000_000
    pcap.close()
    return bus


LOCAL_MASTER = "02:00:00:00:00:01"


def write_local_mac(path):
    """A master whose own MAC has bit 0x02 set (a locally administered
    address): its sent and returned copies carry the same MAC, and order
    decides (SPEC §12.1). Six exchanges, the fourth lost."""
    pcap = Pcapng(path, iface="eth0")
    bus = Bus(pcap, LOCAL_MASTER, n_slaves=1)
    t = T0_NS
    bus.exchange(t, [brd(0x0000, 1, b"\x11", wkc=1)], "count slaves")
    t += 200_000
    bus.exchange(t, [apwr(0, 0x0010, struct.pack("<H", COUPLER))],
                 "station address")
    t += 200_000
    bus.exchange(t, [fprd(COUPLER, 0x0130, 2, al_status(INIT))], "AL status")
    t += 200_000
    bus.exchange(t, [fprd(COUPLER, 0x0130, 2, al_status(INIT))], "AL status",
                 lost=True)
    t += 200_000
    bus.exchange(t, [fprd(COUPLER, 0x0130, 2, al_status(INIT))], "AL status")
    t += 200_000
    bus.exchange(t, [brd(0x0130, 2, al_status(INIT), wkc=1)], "BRD AL status")
    pcap.close()
    return bus


FIXTURES = {
    "akd_fault": ("synthetic_akd_fault.pcapng", write_akd_fault),
    "registers": ("synthetic_registers.pcapng", write_registers),
    "local_mac": ("synthetic_local_mac.pcapng", write_local_mac),
}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(os.path.dirname(here), "tests", "data",
                           "ethercat", "synthetic_akd_fault.pcapng")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fixture", choices=sorted(FIXTURES),
                    default="akd_fault",
                    help="which capture: the AKD fault (default), the "
                         "registers of SPEC 12.2/12.3, a master whose MAC "
                         "has bit 0x02 set")
    ap.add_argument("--out", default=None)
    ap.add_argument("--list", action="store_true",
                    help="print the sent packet number and note of each "
                         "exchange")
    args = ap.parse_args()
    name, write = FIXTURES[args.fixture]
    if args.out is None:
        args.out = os.path.join(os.path.dirname(default), name)
    bus = write(args.out)
    if args.list:
        for number, datagrams, note in bus.exchanges:
            print("%d\t%d\t%s" % (number, len(datagrams), note))
    print("%s: %d packets" % (args.out, bus.pcap.count))


if __name__ == "__main__":
    main()
