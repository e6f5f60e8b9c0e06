#!/usr/bin/env python3
"""Write the EDS-names fixture of tests/library/eds_names.rs and its truth file.

docs/canopen.md#signals and docs/canopen.md#object-names: a PDO signal mapped
from a sub-entry of an ARRAY (object type 0x8) or a RECORD (0x9) is named
`Object name.Sub-entry name`; with `--eds`, an SDO record names its object by
the file's ParameterName.

- array_drive.eds   a CiA 402 drive (device type 0x00020192) whose file
                    names its objects in its own words ("Control word",
                    "Status word", "Modes of operation display" …), with an
                    ARRAY 20C2h "Driver temperature" (sub 1 "Actual
                    temperature", sub 2 "Warning temperature"), a RECORD
                    2010h "Digital inputs", and TPDO1 on $NODEID+0x180
                    mapping 6041h, 20C2h sub 1 and 2010h sub 1;
- array_drive.log   candump -L lines for node 3 written here: SDO reads and
                    writes of those objects (expedited, one abort) and
                    TPDO1 frames;
- array_drive.json  what python-canopen reads from the EDS: every object's
                    name (`od[index].name`), every sub-entry's qualified
                    name (`od[index][sub].qualname`), and TPDO1's signals
                    as python-canopen maps them from the file
                    (`node.tpdo.read(from_od=True)`, each variable's
                    qualname), with the value it decodes from each TPDO1
                    frame of the log.

Run from the repository root (python-canopen 2.x):

    python3 scripts/gen_eds_names_fixtures.py
"""

import json
import os
import struct

import canopen

OUT = "tests/fixtures/eds"
NODE = 3

EDS = """[FileInfo]
FileName=array_drive.eds
FileVersion=1
FileRevision=0
EDSVersion=4.0
Description=A CiA 402 drive whose file names its objects in its own words

[DeviceInfo]
VendorName=motionwire tests
ProductName=array_drive
NrOfRXPDO=0
NrOfTXPDO=1

[MandatoryObjects]
SupportedObjects=2
1=0x1000
2=0x1018

[OptionalObjects]
SupportedObjects=4
1=0x1800
2=0x1A00
3=0x6040
4=0x6041

[ManufacturerObjects]
SupportedObjects=2
1=0x2010
2=0x20C2

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0x00020192
PDOMapping=0

[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2

[1018sub0]
ParameterName=Number of entries
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=1
PDOMapping=0

[1018sub1]
ParameterName=Vendor ID
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0x12345678
PDOMapping=0

[1800]
ParameterName=Transmit PDO 1 parameter
ObjectType=0x9
SubNumber=3

[1800sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=2
PDOMapping=0

[1800sub1]
ParameterName=COB-ID used by TPDO 1
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x180
PDOMapping=0

[1800sub2]
ParameterName=Transmission type TPDO 1
ObjectType=0x7
DataType=0x0005
AccessType=rw
DefaultValue=255
PDOMapping=0

[1A00]
ParameterName=Transmit PDO 1 mapping
ObjectType=0x9
SubNumber=4

[1A00sub0]
ParameterName=Number of mapped objects
ObjectType=0x7
DataType=0x0005
AccessType=rw
DefaultValue=3
PDOMapping=0

[1A00sub1]
ParameterName=Mapping entry 1
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x60410010
PDOMapping=0

[1A00sub2]
ParameterName=Mapping entry 2
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x20C20110
PDOMapping=0

[1A00sub3]
ParameterName=Mapping entry 3
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x20100101
PDOMapping=0

[2010]
ParameterName=Digital inputs
ObjectType=0x9
SubNumber=2

[2010sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=const
DefaultValue=1
PDOMapping=0

[2010sub1]
ParameterName=Enable input
ObjectType=0x7
DataType=0x0001
AccessType=ro
DefaultValue=0
PDOMapping=1

[20C2]
ParameterName=Driver temperature
ObjectType=0x8
SubNumber=3

[20C2sub0]
ParameterName=Number of entries
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=2
PDOMapping=0

[20C2sub1]
ParameterName=Actual temperature
ObjectType=0x7
DataType=0x0003
AccessType=ro
DefaultValue=0
PDOMapping=1

[20C2sub2]
ParameterName=Warning temperature
ObjectType=0x7
DataType=0x0003
AccessType=rw
DefaultValue=80
PDOMapping=1

[6040]
ParameterName=Control word
ObjectType=0x7
DataType=0x0006
AccessType=rw
DefaultValue=0
PDOMapping=1

[6041]
ParameterName=Status word
ObjectType=0x7
DataType=0x0006
AccessType=ro
DefaultValue=0
PDOMapping=1
"""


def sdo(cob, data):
    return (cob, bytes(data))


def expedited_read(index, sub, value, size):
    """An initiate upload request and its expedited answer."""
    n = 4 - size
    return [
        sdo(0x600 + NODE, [0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0]),
        sdo(0x580 + NODE, [0x43 | (n << 2), index & 0xFF, index >> 8, sub]
            + list(value.to_bytes(size, "little")) + [0] * n),
    ]


def expedited_write(index, sub, value, size):
    n = 4 - size
    return [
        sdo(0x600 + NODE, [0x23 | (n << 2), index & 0xFF, index >> 8, sub]
            + list(value.to_bytes(size, "little")) + [0] * n),
        sdo(0x580 + NODE, [0x60, index & 0xFF, index >> 8, sub, 0, 0, 0, 0]),
    ]


def tpdo1(status, temperature, enable):
    return (0x180 + NODE, struct.pack("<Hh", status, temperature) + bytes([enable]))


FRAMES = (
    expedited_read(0x1000, 0, 0x00020192, 4)
    + expedited_read(0x1018, 1, 0x12345678, 4)
    + expedited_write(0x6040, 0, 0x0006, 2)
    + expedited_read(0x6041, 0, 0x0221, 2)
    + [tpdo1(0x0221, 41, 0)]
    + expedited_write(0x6040, 0, 0x000F, 2)
    + expedited_read(0x20C2, 1, 43, 2)
    + expedited_write(0x20C2, 2, 85, 2)
    # A write to the read-only status word: the drive aborts (06010002h).
    + [sdo(0x600 + NODE, [0x2B, 0x41, 0x60, 0, 0x0F, 0, 0, 0]),
       sdo(0x580 + NODE, [0x80, 0x41, 0x60, 0, 0x02, 0x00, 0x01, 0x06])]
    + [tpdo1(0x0237, 44, 1), tpdo1(0x0237, -3, 1)]
    # The manufacturer array's own sub 0, by its index.
    + expedited_read(0x20C2, 0, 2, 1)
    + expedited_read(0x2010, 1, 1, 1)
)


def main():
    os.makedirs(OUT, exist_ok=True)
    eds_path = os.path.join(OUT, "array_drive.eds")
    with open(eds_path, "w") as f:
        f.write(EDS)
    lines = []
    for i, (cob, data) in enumerate(FRAMES):
        lines.append(f"({1700000000 + i // 100}.{(i % 100) * 10000:06d}) can0 {cob:03X}#{data.hex().upper()}")
    with open(os.path.join(OUT, "array_drive.log"), "w") as f:
        f.write("\n".join(lines) + "\n")

    od = canopen.import_od(eds_path, node_id=NODE)
    objects = {}
    entries = {}
    for obj in od.values():
        objects[f"{obj.index:04X}"] = obj.name
        if isinstance(obj, (canopen.objectdictionary.ODRecord, canopen.objectdictionary.ODArray)):
            for sub in obj.values():
                entries[f"{obj.index:04X}sub{sub.subindex:X}"] = sub.qualname
        else:
            entries[f"{obj.index:04X}sub0"] = obj.qualname

    node = canopen.RemoteNode(NODE, od)
    # Not connected: the network only takes the PDO's subscription.
    canopen.Network().add_node(node)
    node.tpdo.read(from_od=True)
    pdo = node.tpdo[1]
    signals = [v.name for v in pdo]
    frames = []
    for line_no, (cob, data) in enumerate(FRAMES, start=1):
        if cob != pdo.cob_id:
            continue
        pdo.data = bytearray(data)
        frames.append({"line": line_no,
                       "signals": {v.name: v.raw for v in pdo}})
    truth = {
        "python_canopen": canopen.__version__,
        "read_from": "array_drive.eds",
        "note": "objects: od[index].name; entries: od[index][sub].qualname; "
                "tpdo1: node.tpdo.read(from_od=True), each PdoVariable.name "
                "(Object.Sub for a sub-entry) and its .raw in each TPDO1 frame of array_drive.log",
        "objects": objects,
        "entries": entries,
        "tpdo1": {"cob_id": pdo.cob_id, "signals": signals, "frames": frames},
    }
    with open(os.path.join(OUT, "array_drive.json"), "w") as f:
        json.dump(truth, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
