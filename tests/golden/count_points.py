#!/usr/bin/env python3
"""Counts the packets and points of the bundled captures, independently of the C++ code.

Plain Python over the pcap bytes: the pcap record headers, then each frame's Ethernet, IPv4 and UDP
headers (the IPv4 header length read from the packet), then the point-cloud layouts of the manuals:
  Pandar40P (Pandar40 manual, Section 3.1.2, Tables 3.2 and 3.3; the Pandar40P packet document,
    "LiDAR UDP Payload Structure"): 10 blocks of 124 bytes from offset 0, each 0xFFEE, azimuth
    u16, 40 x {distance u16, reflectivity u8}; payload 1262 (1266 with sequence).
  Pandar64 (Pandar64 manual, Sections 3.1.2.1 Header and 3.1.2.2 Body): 8-byte header, 6 blocks
    of 194 bytes, each azimuth u16, 64 x {distance u16, reflectivity u8}; payload 1194 (1198 with
    sequence).
  QT128C2X (QT128C2X manual, Section 3.1.2 UDP Data): 12-byte header, 2 blocks of 514 bytes, each
    azimuth u16, 128 x {distance u16, reflectivity u8, reserved u8}; the payload length follows
    the header's flags (bit 0 UDP sequence +4, bit 2 functional safety +17, bit 3 signature +32).
  PandarQT64 (point cloud protocol 3.1; no manual here: the vendor SDK's udp_protocol_v3_1.h):
    12-byte header, 4 blocks of 258 bytes, each azimuth u16, 64 x {distance u16, reflectivity u8,
    confidence u8}; payload 1072 (1068 without the UDP sequence).
  PandarXT16 / XT32 / XT32M2X (point cloud protocol 6.1; no manual here: the vendor SDK's
    udp_protocol_v6_1.h): 12-byte header, 8 / 8 / 6 blocks of 2 + 16 / 32 / 32 x 4 bytes, each
    azimuth u16, then {distance u16, reflectivity u8, confidence u8}; payload 568 / 1080 / 820.
A point is a distance that is not 0 (no return); for the QT128 not 1 either (the Chinese QT128C2X
manual, Section 3.1.2, notes on the Distance field: 1 is a reserved marker, not a measurement).

Prints the counts. With --check FILE, also compares them with the totals in the Layout
initializers of tests/test_golden.cpp ({"capture.pcap", packets, points, ...}) and exits 1 on
any difference. Run by ctest as `golden_counts`.
"""
import argparse
import os
import re
import struct
import sys


def udp_payloads(path):
    with open(path, "rb") as f:
        data = f.read()
    magic = struct.unpack_from("<I", data, 0)[0]
    if magic not in (0xA1B2C3D4, 0xA1B23C4D):
        raise ValueError(f"{path}: not a little-endian classic pcap")
    if struct.unpack_from("<I", data, 20)[0] != 1:
        raise ValueError(f"{path}: link type is not Ethernet")
    off = 24
    while off + 16 <= len(data):
        incl = struct.unpack_from("<I", data, off + 8)[0]
        frame = data[off + 16:off + 16 + incl]
        off += 16 + incl
        if len(frame) < incl:
            raise ValueError(f"{path}: truncated record")
        if struct.unpack_from(">H", frame, 12)[0] != 0x0800:
            raise ValueError(f"{path}: a frame that is not IPv4")
        ip = frame[14:]
        ihl = (ip[0] & 0x0F) * 4
        if ip[0] >> 4 != 4 or ip[9] != 17:
            raise ValueError(f"{path}: a packet that is not IPv4 UDP")
        udp_length = struct.unpack_from(">H", ip, ihl + 4)[0]
        yield ip[ihl + 8:ihl + udp_length]


def qt128_length(flags):
    return 12 + 1028 + 4 + (17 if flags & 4 else 0) + 26 + (4 if flags & 1 else 0) + 4 + (32 if flags & 8 else 0)


# name: (lengths allowed, or None for the QT128's flag-dependent length; body offset, blocks,
#        block bytes, offset of the points in a block, channels, point bytes, smallest distance)
MODELS = {
    "pandar40p": ((1262, 1266), 0, 10, 124, 4, 40, 3, 1),
    "pandar64": ((1194, 1198), 8, 6, 194, 2, 64, 3, 1),
    "qt128c2x": (None, 12, 2, 514, 2, 128, 4, 2),
    "pandar_qt64": ((1068, 1072), 12, 4, 258, 2, 64, 4, 1),
    "pandar_xt16": ((568,), 12, 8, 66, 2, 16, 4, 1),
    "pandar_xt32": ((1080,), 12, 8, 130, 2, 32, 4, 1),
    "pandar_xt32m2x": ((820,), 12, 6, 130, 2, 32, 4, 1),
}
# The bundled capture of each model.
CAPTURES = {"pandar40p": "pandar40p_dual.pcap", "pandar64": "pandar64_dual.pcap", "qt128c2x": "qt128c2x_dual.pcap",
            "pandar_qt64": "pandar_qt64.pcap", "pandar_xt16": "pandar_xt16.pcap", "pandar_xt32": "pandar_xt32.pcap",
            "pandar_xt32m2x": "pandar_xt32m2x.pcap"}


def count(path, model):
    lengths, body, blocks, block_bytes, points_at, channels, point_bytes, smallest = MODELS[model]
    packets = points = markers = 0
    for p in udp_payloads(path):
        allowed = lengths if lengths else (qt128_length(p[11]),)
        if len(p) not in allowed:
            raise ValueError(f"{path}: payload of {len(p)} bytes, expected {allowed}")
        packets += 1
        for b in range(blocks):
            for c in range(channels):
                d = struct.unpack_from("<H", p, body + b * block_bytes + points_at + c * point_bytes)[0]
                points += d >= smallest
                markers += d == 1 and smallest == 2
    return packets, points, markers


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "data"), help="folder of the captures")
    ap.add_argument("--check", metavar="FILE", action="append",
                    help="a test file whose totals must match (test_golden.cpp, test_qt64.cpp, test_xt.cpp); repeatable")
    args = ap.parse_args()

    counted = {}
    for model in MODELS:
        name = CAPTURES[model]
        counted[name] = count(os.path.join(args.data, name), model)
        packets, points, markers = counted[name]
        print(f"{name}: {packets} packets, {points} points ({markers} distance-1 markers)")
    if not args.check:
        return 0

    claimed = {}
    for path in args.check:
        with open(path, encoding="utf-8") as f:
            claimed.update({m[0]: (int(m[1]), int(m[2]))
                            for m in re.findall(r'\{"(\w+\.pcap)",\s*(\d+),\s*(\d+)[,}]', f.read())})
    ok = True
    for name, (packets, points, _) in counted.items():
        if claimed.get(name) != (packets, points):
            print(f"MISMATCH {name}: {', '.join(args.check)} say {claimed.get(name)}, counted ({packets}, {points})")
            ok = False
    if ok:
        print(f"all totals in {', '.join(os.path.basename(c) for c in args.check)} match")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
