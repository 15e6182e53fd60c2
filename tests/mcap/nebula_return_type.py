"""The return_type nebula writes for a point of a Hesai packet, from the packet's own bytes,
independently of the C++ code (used by compare.py).

The values are nebula's ReturnType (tier4/nebula, nebula_core_common/nebula_common.hpp). What each
return-mode byte gives per block of a firing (docs/CLI.md, MCAP, "return mode byte -> return_type"):
  manuals: Pandar40 3.1.2 (Table 3.3 note, "Return Mode Information"); Pandar64 3.1.2.2 Body (the
  return-mode table) and 3.1.2.3 Tail; QT128C2X 3.1.2.2 Body (the table "Return Mode field /
  Block 1 / Block 2 / Note") and 3.1.2 Tail. 0x3D (triple) has no manual here: nebula
  hesai_packet.hpp.
  nebula: hesai_sensor.hpp get_return_type (a unit equal in distance and reflectivity to another
  return of its firing is IDENTICAL; "strongest" = no other return of the firing reflects more);
  pandar_xt16.hpp / pandar_xt32.hpp (0x3B: first and last swapped on those two models).

Packet layouts (the same facts as tests/golden/count_points.py): body offset, blocks, block bytes,
offset of the units in a block, channels, unit bytes, and where the tail's return-mode byte is.
"""
import struct

UNKNOWN, LAST, FIRST, STRONGEST, FIRST_WEAK, LAST_WEAK, IDENTICAL, SECOND, SECONDSTRONGEST, \
    FIRST_STRONGEST, LAST_STRONGEST = range(11)

# model: (body offset, blocks, block bytes, units at, channels, unit bytes)
LAYOUTS = {
    "pandar40p": (0, 10, 124, 4, 40, 3),
    "pandar64": (8, 6, 194, 2, 64, 3),
    "qt128c2x": (12, 2, 514, 2, 128, 4),
    "pandar_qt64": (12, 4, 258, 2, 64, 4),
    "pandar_xt16": (12, 8, 66, 2, 16, 4),
    "pandar_xt32": (12, 8, 130, 2, 32, 4),
    "pandar_xt32m2x": (12, 6, 130, 2, 32, 4),
}


def identify(p):
    """The model of a point-cloud payload, by its length and header."""
    n = len(p)
    if n in (1262, 1266) and p[0] == 0xFF and p[1] == 0xEE:
        return "pandar40p"
    if p[0] != 0xEE or p[1] != 0xFF:
        raise ValueError(f"payload of {n} bytes without EE FF")
    version = (p[2], p[3])
    if n in (1194, 1198) and p[2] == 0x40:  # laser num 64, no version bytes
        return "pandar64"
    if version == (3, 2):
        return "qt128c2x"
    if version == (3, 1):
        return "pandar_qt64"
    if version == (6, 1):
        return {568: "pandar_xt16", 1080: "pandar_xt32", 820: "pandar_xt32m2x"}[n]
    raise ValueError(f"payload of {n} bytes, version {version}: no model")


def return_mode(model, p):
    """The tail's return-mode byte."""
    body, blocks, block_bytes = LAYOUTS[model][:3]
    tail = body + blocks * block_bytes
    if model in ("pandar40p", "pandar64"):
        return p[tail + 14]  # reserved 5, flag, reserved 2, motor 2, timestamp 4
    if model == "qt128c2x":
        if p[11] & 0x40:
            raise ValueError("QT128 channel customisation: units are not channels")
        tail = 12 + 1028 + 4 + (17 if p[11] & 4 else 0)  # body, CRC1, functional safety
        return p[tail + 12]  # reserved 5, mode flag, reserved 6
    if model == "pandar_qt64":
        return p[tail + 16]
    return p[tail + 10]  # protocol 6.1


def returns_of(mode):
    if mode in (0x33, 0x34, 0x37, 0x38):
        return 1
    if mode == 0x3D:
        return 3
    return 2


def expected_packet(model, p):
    """nebula's ReturnType of every unit of payload p, and each unit's block's index within its
    firing (the CSV's return): (type, index) by [block][channel], both 0-based. The mode byte and
    the units are read once a packet (compare.py asks for every unit)."""
    body, blocks, block_bytes, units_at, channels, unit_bytes = LAYOUTS[model]
    mode = return_mode(model, p)
    n = returns_of(mode)
    unit_format = "<HB" + "x" * (unit_bytes - 3)
    units = [list(struct.iter_unpack(unit_format, p[body + b * block_bytes + units_at:
                                                  body + b * block_bytes + units_at + channels * unit_bytes]))
             for b in range(blocks)]
    out = []
    for block in range(blocks):
        first = block // n * n
        others_blocks = [b for b in range(first, first + n) if b != block]
        out.append([_type_of(model, mode, block - first, units[block][channel],
                             [units[b][channel] for b in others_blocks]) for channel in range(channels)])
    return out


# The single-return modes: one type whatever the units.
SINGLE = {0x33: FIRST, 0x34: SECOND, 0x37: STRONGEST, 0x38: LAST}


def _type_of(model, mode, r, me, others):
    """nebula's ReturnType of unit `me` (distance, reflectivity), return r of its firing, beside
    the firing's other returns (their units)."""
    if mode in SINGLE:
        return SINGLE[mode], r
    if any(o == me for o in others):
        return (IDENTICAL if mode in (0x39, 0x3A, 0x3B, 0x3C, 0x3D, 0x3E) else UNKNOWN), r
    strongest = all(me[1] >= o[1] for o in others)
    if mode == 0x39:  # last, strongest
        t = (LAST_STRONGEST if strongest else LAST) if r == 0 else (STRONGEST if strongest else SECONDSTRONGEST)
    elif mode == 0x3C:  # first, strongest
        t = (FIRST_STRONGEST if strongest else FIRST) if r == 0 else (STRONGEST if strongest else SECONDSTRONGEST)
    elif mode == 0x3B:  # first, last; the XT16 and XT32 send last first
        order = (LAST, FIRST) if model in ("pandar_xt16", "pandar_xt32") else (FIRST, LAST)
        t = order[r]
    elif mode == 0x3A:
        t = (FIRST, SECOND)[r]
    elif mode == 0x3E:
        t = (STRONGEST, SECONDSTRONGEST)[r]
    elif mode == 0x3D:
        t = (FIRST, LAST, STRONGEST)[r]
    else:
        t = UNKNOWN
    return t, r
