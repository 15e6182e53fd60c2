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
    # (The frame is the first column, and no field holds a comma or a quote: a split will do.)
    with open(csv_path, newline="") as f:
        header = next(csv.reader([f.readline()]))
        if header[0] != "frame":
            fail(f"the CSV's first column is {header[0]!r}, not frame")
        last_row = {}
        for i, line in enumerate(f):
            last_row[int(line.split(",", 1)[0])] = i
    col = {k: header.index(k) for k in ("frame", "packet", "block", "channel", "return", "intensity", "x", "y", "z",
                                         "azimuth_deg", "elevation_deg", "distance_m", "time_ns", "sensor")}
    i_channel, i_intensity, i_packet, i_block, i_return, i_time = (
        col[k] for k in ("channel", "intensity", "packet", "block", "return", "time_ns"))
    i_x, i_y, i_z, i_az, i_el, i_dist = (
        col[k] for k in ("x", "y", "z", "azimuth_deg", "elevation_deg", "distance_m"))
    # The capture's datagram times, by point-cloud packet index (every bundled capture's datagrams
    # are point-cloud packets).
    datagrams = make_pandarscan.pcap_payloads(capture)
    times = [t for t, _ in datagrams]
    payloads = [p for _, p in datagrams]
    packet_types = {}  # packet index -> nebula_return_type.expected_packet of it
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
                if p[0] != "P":
                    fail_read(f"frame {frame} point {i}: no point line")
                ch = int(p[1])
                if ch != int(row[i_channel]) - 1 or p[3] != row[i_intensity]:
                    fail(f"frame {frame} point {i}: channel/intensity {ch},{p[3]} vs CSV "
                         f"{row[i_channel]},{row[i_intensity]}")
                packet = int(row[i_packet])
                types = packet_types.get(packet)
                if types is None:
                    payload = payloads[packet]
                    types = packet_types[packet] = nebula_return_type.expected_packet(
                        nebula_return_type.identify(payload), payload)
                want, index_in_firing = types[int(row[i_block])][ch]
                ret = int(p[2])
                if ret != want:
                    fail(f"frame {frame} point {i} (packet {packet} block {row[i_block]} channel {ch}): "
                         f"return_type {ret}, nebula's ReturnType from the packet's bytes is {want}")
                if int(row[i_return]) != index_in_firing:
                    fail(f"frame {frame} point {i}: the CSV's return {row[i_return]}, the block's index in "
                         f"its firing {index_in_firing}")
                type_counts[ret] = type_counts.get(ret, 0) + 1
                if p[10] != row[i_time]:
                    fail(f"frame {frame} point {i}: time {p[10]} vs CSV {row[i_time]}")
                x, y, z, az, el, dist = map(float, p[4:10])
                if (abs(x - float(row[i_x])) > m_tol or abs(y - float(row[i_y])) > m_tol or
                        abs(z - float(row[i_z])) > m_tol or abs(dist - float(row[i_dist])) > m_tol):
                    fail(f"frame {frame} point {i}: x, y, z, distance {x}, {y}, {z}, {dist} vs CSV "
                         f"{row[i_x]}, {row[i_y]}, {row[i_z]}, {row[i_dist]}")
                d_az = (math.degrees(az) - float(row[i_az]) + 180.0) % 360.0 - 180.0  # 359.9996 prints as 360.000
                d_el = (math.degrees(el) - float(row[i_el]) + 180.0) % 360.0 - 180.0
                if abs(d_az) > deg_tol or abs(d_el) > deg_tol:
                    fail(f"frame {frame} point {i}: azimuth, elevation {math.degrees(az)}, {math.degrees(el)} vs CSV "
                         f"{row[i_az]}, {row[i_el]}")
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
