#!/usr/bin/env python3
"""Decodes a capture to CSV and to MCAP with the hesai program, reads the MCAP back with the
reference reader (read.mjs, npm's @mcap/core) and compares the two point for point.

Usage: compare.py HESAI CAPTURE READ_MJS NODE_MODULES_PARENT WORK_DIR [decode options...]
HESAI_RUN_PREFIX (environment): words put before HESAI (cross builds: the qemu-user emulator).

Per frame (the CSV's frame column): one message, its sequence the frame number, its width the
frame's rows, its points the rows in the same order: channel = CSV channel - 1 (nebula counts
from 0), intensity exactly; return_type = nebula's ReturnType, derived here from the capture's own
bytes (nebula_return_type.py: the packet's return-mode byte and the other returns of the point's
firing, by the CSV's packet, block and channel), and the CSV's return = the block's index in its
firing, as before; x, y, z, distance within the CSV's 4 decimals
(0.00005 m) plus float32 rounding; azimuth and elevation (radians) within the CSV's 3 decimals
of a degree; time_ns (stamp + time_stamp) exactly. stamp = the frame's earliest time_ns.
Topic and frame_id: /hesai/<token>/points and hesai_<token>, the token made here from the CSV's
sensor column by the documented rule ("ip_" and the address with '_' for '.'). log_time: the pcap
time of a datagram at or after the frame's last packet (the frame closed when it came), never
before the previous message's.
"""
import csv
import math
import os
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_pandarscan  # noqa: E402  (its pcap reader: the capture's datagram times)
import nebula_return_type  # noqa: E402  (the expected return_type, from the packet bytes)


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
    # Pass 1 over the CSV: the frames, and the row at which each is complete (near a cut the rows
    # of two frames interleave). Pass 2 keeps only the rows of frames not yet compared.
    with open(csv_path, newline="") as f:
        reader_csv = csv.reader(f)
        header = next(reader_csv)
        last_row = {}
        for i, row in enumerate(reader_csv):
            last_row[int(row[0])] = i
    col = {k: header.index(k) for k in ("frame", "packet", "block", "channel", "return", "intensity", "x", "y", "z",
                                         "azimuth_deg", "elevation_deg", "distance_m", "time_ns", "sensor")}
    # The capture's datagram times, by point-cloud packet index (every bundled capture's datagrams
    # are point-cloud packets).
    datagrams = make_pandarscan.pcap_payloads(capture)
    times = [t for t, _ in datagrams]
    payloads = [p for _, p in datagrams]
    models = {}  # packet index -> model
    type_counts = {}
    last_log = -1
    frames = sorted(last_row)

    node = subprocess.Popen(["node", reader, mcap_path, modules], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    lines = iter(node.stdout)
    m_tol = 0.00005 * 1.001 + 1e-6           # metres: 4 printed decimals, float32 at <= 200 m
    deg_tol = 0.0005 * 1.001 + 1e-4           # degrees: 3 printed decimals, float32 radians
    points = 0
    pending = {}
    def fail_read(msg):
        # read.mjs's own message first when it stopped early.
        node.stdout.close()
        err, status = node.stderr.read(), node.wait()
        fail(f"read.mjs failed ({status}): {err}" if status != 0 else msg)

    consumed = -1  # the last CSV data row read
    with open(csv_path, newline="") as f:
        rows_iter = csv.reader(f)
        next(rows_iter)
        for frame in frames:
            while consumed < last_row[frame]:
                row = next(rows_iter)
                consumed += 1
                pending.setdefault(int(row[col["frame"]]), []).append(row)
            rows = pending.pop(frame)
            line = next(lines, None)
            if line is None:
                fail_read(f"no message for frame {frame}")
            mparts = line.rstrip("\n").split(",")
            if mparts[0] != "M" or int(mparts[1]) != frame:
                fail_read(f"expected the message of frame {frame}, read '{line.strip()}'")
            stamp, frame_id, width, topic = int(mparts[2]), mparts[3], int(mparts[4]), mparts[5]
            log_time = int(mparts[6])
            if width != len(rows):
                fail(f"frame {frame}: {width} points in the message, {len(rows)} rows")
            sensors = {row[col["sensor"]] for row in rows}
            if len(sensors) != 1:
                fail(f"frame {frame}: rows of several sensors {sensors}")
            token = "ip_" + sensors.pop().rsplit(":", 1)[0].replace(".", "_")
            if frame_id != "hesai_" + token or topic != "/hesai/" + token + "/points":
                fail(f"frame {frame}: frame_id {frame_id} topic {topic}, sensor token {token}")
            last_packet = max(int(row[col["packet"]]) for row in rows)
            if not (times[last_packet] <= log_time <= times[-1]) or log_time < last_log:
                fail(f"frame {frame}: log_time {log_time}, its last packet's time {times[last_packet]}, "
                     f"the previous message's {last_log}, the capture's last {times[-1]}")
            last_log = log_time
            if stamp != min(int(row[col["time_ns"]]) for row in rows):
                fail(f"frame {frame}: stamp {stamp} is not the earliest time_ns")
            for i, row in enumerate(rows):
                p = next(lines, "").rstrip("\n").split(",")
                where = f"frame {frame} point {i}"
                if p[0] != "P":
                    fail_read(f"{where}: no point line")
                ch, ret, inten = int(p[1]), int(p[2]), int(p[3])
                x, y, z, az, el, dist = (float(v) for v in p[4:10])
                if ch != int(row[col["channel"]]) - 1 or inten != int(row[col["intensity"]]):
                    fail(f"{where}: channel/intensity {ch},{inten} vs CSV "
                         f"{row[col['channel']]},{row[col['intensity']]}")
                packet = int(row[col["packet"]])
                payload = payloads[packet]
                model = models.get(packet) or models.setdefault(packet, nebula_return_type.identify(payload))
                want, index_in_firing = nebula_return_type.expected(model, payload, int(row[col["block"]]), ch)
                if ret != want:
                    fail(f"{where} (packet {packet} block {row[col['block']]} channel {ch}): return_type {ret}, "
                         f"nebula's ReturnType from the packet's bytes is {want}")
                if int(row[col["return"]]) != index_in_firing:
                    fail(f"{where}: the CSV's return {row[col['return']]}, the block's index in its firing "
                         f"{index_in_firing}")
                type_counts[ret] = type_counts.get(ret, 0) + 1
                if int(p[10]) != int(row[col["time_ns"]]):
                    fail(f"{where}: time {p[10]} vs CSV {row[col['time_ns']]}")
                for key, v in (("x", x), ("y", y), ("z", z), ("distance_m", dist)):
                    if abs(v - float(row[col[key]])) > m_tol:
                        fail(f"{where}: {key} {v} vs CSV {row[col[key]]}")
                for key, v in (("azimuth_deg", az), ("elevation_deg", el)):
                    d = math.degrees(v) - float(row[col[key]])
                    d = (d + 180.0) % 360.0 - 180.0  # 359.9996 prints as 360.000
                    if abs(d) > deg_tol:
                        fail(f"{where}: {key} {math.degrees(v)} vs CSV {row[col[key]]}")
                points += 1
    extra = next(lines, None)
    err = node.stderr.read()
    status = node.wait()
    if status != 0:
        fail(f"read.mjs failed ({status}): {err}")
    if extra is not None:
        fail(f"more messages than the CSV's {len(frames)} frames: '{extra.strip()}'")
    if points != sum(1 for _ in open(csv_path)) - 1:
        fail(f"{points} points compared, the CSV has more rows (a frame without a message)")
    # Every bundled capture has points: a decode that wrote none would compare nothing and pass.
    if points == 0 or not frames:
        fail(f"nothing compared: {len(frames)} frames, {points} points (the CSV has no rows)")
    # Every point has a ReturnType nebula defines, never UNKNOWN (0) on these captures.
    if type_counts.get(0):
        fail(f"{type_counts[0]} points with return_type 0 (UNKNOWN)")
    counts = ", ".join(f"{t}: {n}" for t, n in sorted(type_counts.items()))
    print(f"{name}: {len(frames)} messages = {len(frames)} frames, {points} points match the CSV; "
          f"return_type {{{counts}}} as the packets' bytes give")

if __name__ == "__main__":
    main()
