#!/usr/bin/env python3
"""Decodes a capture to CSV and to MCAP with the hesai program, reads the MCAP back with the
reference reader (read.mjs, npm's @mcap/core) and compares the two point for point.

Usage: compare.py HESAI CAPTURE READ_MJS NODE_MODULES_PARENT WORK_DIR [decode options...]
HESAI_RUN_PREFIX (environment): words put before HESAI (cross builds: the qemu-user emulator).

Per frame (the CSV's frame column): one message, its sequence the frame number, its width the
frame's rows, its points the rows in the same order: channel = CSV channel - 1 (nebula counts
from 0), return_type = return, intensity exactly; x, y, z, distance within the CSV's 4 decimals
(0.00005 m) plus float32 rounding; azimuth and elevation (radians) within the CSV's 3 decimals
of a degree; time_ns (stamp + time_stamp) exactly. stamp = the frame's earliest time_ns.
"""
import csv
import math
import os
import subprocess
import sys


def fail(msg):
    print(f"compare.py: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    if len(sys.argv) < 6:
        fail(__doc__)
    hesai, capture, reader, modules, work = sys.argv[1:6]
    extra = sys.argv[6:]
    os.makedirs(work, exist_ok=True)
    name = os.path.splitext(os.path.basename(capture))[0]
    csv_path = os.path.join(work, name + ".csv")
    mcap_path = os.path.join(work, name + ".mcap")
    prefix = os.environ.get("HESAI_RUN_PREFIX", "").split()
    for fmt, out in (("csv", csv_path), ("mcap", mcap_path)):
        r = subprocess.run(prefix + [hesai, "decode", capture, "--format", fmt, "--out", out, "--quiet"] + extra,
                           capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"hesai decode --format {fmt} failed ({r.returncode}): {r.stderr}")
    r = subprocess.run(["node", reader, mcap_path, modules], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"read.mjs failed ({r.returncode}): {r.stderr}")

    frames = {}  # frame -> rows, in file order
    order = []
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            fr = int(row["frame"])
            if fr not in frames:
                frames[fr] = []
                order.append(fr)
            frames[fr].append(row)

    messages = []
    for line in r.stdout.splitlines():
        parts = line.split(",")
        if parts[0] == "M":
            messages.append({"seq": int(parts[1]), "stamp": int(parts[2]), "frame_id": parts[3],
                             "width": int(parts[4]), "topic": parts[5], "points": []})
        elif parts[0] == "P":
            messages[-1]["points"].append(parts[1:])
    if len(messages) != len(order):
        fail(f"{len(messages)} messages, {len(order)} frames in the CSV")
    messages.sort(key=lambda m: m["seq"])
    if [m["seq"] for m in messages] != sorted(order):
        fail("message sequence numbers are not the CSV's frame numbers")

    m_tol = 0.00005 * 1.001 + 1e-6           # metres: 4 printed decimals, float32 at <= 200 m
    deg_tol = 0.0005 * 1.001 + 1e-4           # degrees: 3 printed decimals, float32 radians
    points = 0
    for m in messages:
        rows = frames[m["seq"]]
        if m["width"] != len(rows) or len(m["points"]) != len(rows):
            fail(f"frame {m['seq']}: {m['width']} points in the message, {len(rows)} rows")
        if m["frame_id"] != "hesai" or m["topic"] != "/hesai/points":
            fail(f"frame {m['seq']}: frame_id {m['frame_id']} topic {m['topic']}")
        if m["stamp"] != min(int(row["time_ns"]) for row in rows):
            fail(f"frame {m['seq']}: stamp {m['stamp']} is not the earliest time_ns")
        for i, (p, row) in enumerate(zip(m["points"], rows)):
            ch, ret, inten = int(p[0]), int(p[1]), int(p[2])
            x, y, z, az, el, dist = (float(v) for v in p[3:9])
            t = int(p[9])
            where = f"frame {m['seq']} point {i}"
            if ch != int(row["channel"]) - 1 or ret != int(row["return"]) or inten != int(row["intensity"]):
                fail(f"{where}: channel/return/intensity {ch},{ret},{inten} vs CSV {row['channel']},{row['return']},{row['intensity']}")
            if t != int(row["time_ns"]):
                fail(f"{where}: time {t} vs CSV {row['time_ns']}")
            for key, v in (("x", x), ("y", y), ("z", z), ("distance_m", dist)):
                if abs(v - float(row[key])) > m_tol:
                    fail(f"{where}: {key} {v} vs CSV {row[key]}")
            for key, v in (("azimuth_deg", az), ("elevation_deg", el)):
                d = math.degrees(v) - float(row[key])
                d = (d + 180.0) % 360.0 - 180.0  # 359.9996 prints as 360.000
                if abs(d) > deg_tol:
                    fail(f"{where}: {key} {math.degrees(v)} vs CSV {row[key]}")
            points += 1
    print(f"{name}: {len(messages)} messages = {len(order)} frames, {points} points match the CSV")


if __name__ == "__main__":
    main()
