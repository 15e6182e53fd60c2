#!/usr/bin/env python3
"""Writes what hesai.decode_columns gives for every bundled capture into OUT_DIR, one .npy file a
column, so that two builds of libhesai_c can be compared byte for byte (as outputs.sh does for the
program): a change of the columns path must leave them identical.

    python3 tests/identity/columns.py build/release/lib/libhesai_c.so /tmp/columns-before
    ... change, rebuild ...
    python3 tests/identity/columns.py build/release/lib/libhesai_c.so /tmp/columns-after
    diff -r /tmp/columns-before /tmp/columns-after && echo identical

For each capture of data/ and of the folders given with --captures: the design tables; the unit's
calibration, firing times (and the QT128C2X's channel configuration); each rotation; a packet
range; the default read again in calls of HESAI_CAPTURE_COLUMNS_MIN points (the library's smallest, so that
the held packets released at the end do not fit one call). Then captures made here: many senders
whose direction is never decided (each holds its packets to the end), two sensors interleaved,
and a capture cut part-way (the columns before the damage, the status and the message).
"""

import os
import pathlib
import struct
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def records(path):
    data = path.read_bytes()
    out, off = [], 24
    while off + 16 <= len(data):
        incl = struct.unpack_from("<I", data, off + 8)[0]
        out.append(bytearray(data[off + 16: off + 16 + incl]))
        off += 16 + incl
    return out


def resend_from(frame, last_octet, port):
    """The IPv4 source 192.168.1.<last_octet>:<port> (the header checksum left as it was: the
    reader does not check it)."""
    ip = 14
    frame[ip + 12: ip + 16] = bytes([192, 168, 1, last_octet])
    struct.pack_into(">H", frame, ip + (frame[ip] & 0x0F) * 4, port)
    return frame


def write_pcap(path, frames):
    out = bytearray(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
    for i, f in enumerate(frames):
        us = i * 100
        out += struct.pack("<IIII", 1700000000 + us // 1000000, us % 1000000, len(f), len(f)) + f
    path.write_bytes(bytes(out))
    return path


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    os.environ["HESAI_LIBRARY"] = str(pathlib.Path(sys.argv[1]).resolve())
    out = pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    extra = [pathlib.Path(p) for p in sys.argv[3:]]
    sys.path.insert(0, str(ROOT / "python"))
    import numpy as np
    import hesai
    from hesai import _lib

    def dump(name, cols, sensors=None, error=None):
        for col, a in cols.items():
            np.save(out / f"{name}.{col}.npy", a)
        with open(out / f"{name}.txt", "w") as f:
            f.write(f"points {len(cols['x'])}\nsensors {sensors}\nerror {error}\n")

    def chunked(path, **kw):
        """decode_columns' arrays, read in calls of COLUMNS_MIN points."""
        parts = {name: [] for name in hesai.COLUMNS}
        with hesai._Capture(path, **kw) as cap:
            while True:
                cols = {name: np.empty(_lib.COLUMNS_MIN, dtype=dt) for name, dt in hesai.COLUMNS.items()}
                got = cap.read_columns(cols, 0)
                if got == 0:
                    break
                for name in parts:
                    parts[name].append(cols[name][:got].copy())
            sensors = cap.sensors()
        return {name: np.concatenate(p) if p else np.empty(0, hesai.COLUMNS[name]) for name, p in parts.items()}, sensors

    def run(name, path, chunks=False, **kw):
        try:
            cols, sensors = hesai.decode_columns(path, return_sensors=True, **kw)
            dump(name, cols, sensors)
        except hesai.HesaiError as e:
            dump(name, e.columns if e.columns is not None else {}, None, f"{e.status} {e}".replace(str(out), "OUT"))
        if not chunks:
            return
        try:
            cols, sensors = chunked(path, **kw)
            dump(name + ".chunked", cols, sensors)
        except hesai.HesaiError as e:
            with open(out / f"{name}.chunked.txt", "w") as f:
                f.write(f"error {e.status} {e}\n".replace(str(out), "OUT"))

    cal = ROOT / "data" / "calibration"
    captures = sorted((ROOT / "data").glob("*.pcap"))
    for d in extra:
        captures += sorted(d.glob("*.pcap"))
    for cap in captures:
        tag = f"{cap.parent.name}.{cap.stem}"
        run(tag, cap, chunks=True)
        base = cap.stem
        files = {}
        if (cal / f"{base}_firetimes.csv").exists():
            angles = cal / f"{base}_unit_a_angles.csv"
            files = {"calibration": angles if angles.exists() else cal / f"{base}_angles.csv",
                     "firetimes": cal / f"{base}_firetimes.csv"}
        elif base.endswith("_dual") and (cal / f"{base[:-5]}_firetimes.csv").exists():
            files = {"calibration": cal / f"{base[:-5]}_unit_a_angles.csv", "firetimes": cal / f"{base[:-5]}_firetimes.csv"}
            if base.startswith("qt128"):
                files["channel_config"] = cal / "qt128c2x_channel_config.csv"
        if files:
            run(tag + ".unit", cap, **files)
        run(tag + ".cw", cap, rotation="cw")
        run(tag + ".ccw", cap, rotation="ccw")
        run(tag + ".packets", cap, packets=(3, 700))

    made = out / "made"
    made.mkdir(exist_ok=True)
    qt = records(ROOT / "data" / "qt128c2x_dual.pcap")
    # 40 senders of two QT128C2X packets each (the direction undecided: held to the end), then one
    # whole capture: the end releases 80 held packets at once.
    many = [resend_from(bytearray(qt[k]), 10 + s, 2368) for s in range(40) for k in range(2)] + [bytearray(f) for f in qt]
    run("made.many_senders", write_pcap(made / "many.pcap", many), chunks=True)
    xt16, xt32 = records(ROOT / "data" / "pandar_xt16.pcap"), records(ROOT / "data" / "pandar_xt32.pcap")
    two = []
    for k in range(max(len(xt16), len(xt32))):
        if k < len(xt16):
            two.append(xt16[k])
        if k < len(xt32):
            two.append(resend_from(bytearray(xt32[k]), 202, 10000))
    run("made.two_sensors", write_pcap(made / "two.pcap", two), chunks=True)
    data = (ROOT / "data" / "pandar64_dual.pcap").read_bytes()
    cut = made / "cut.pcap"
    cut.write_bytes(data[: 24 + 500 * (16 + len(records(ROOT / "data" / "pandar64_dual.pcap")[0])) + 30])
    run("made.cut", cut, chunks=True)
    for p in (made / "many.pcap", made / "two.pcap", cut):
        p.unlink()
    made.rmdir()
    print(f"{len(list(out.glob('*.txt')))} runs written to {out}")


if __name__ == "__main__":
    main()
