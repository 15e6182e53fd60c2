"""Several sensors in one capture through the Python package (issue #34), against the program.

The capture is made here as tests/test_sensors_apart.cpp makes it: the bundled PandarXT16 and
PandarXT32 captures' records interleaved one by one under one capture clock, the XT32's resent
from another address. Expected values come from the inputs (the senders' addresses, read from the
records' bytes) and from `hesai decode --format csv`, `--per-frame` and `hesai stats --json` (the
program, run as a subprocess), never from the package.
"""

import json
import struct
import subprocess

import numpy as np
import pytest

import hesai

from test_package import CLI, DATA, HEADER, assert_rows_equal, cli_csv_body

XT32_FROM = (202, 10000)  # the XT32's new sender: 192.168.1.202:10000


def pcap_records(path):
    """(global header, [frame bytes]) of a classic little-endian pcap."""
    data = path.read_bytes()
    out, off = [], 24
    while off + 16 <= len(data):
        incl = struct.unpack_from("<I", data, off + 8)[0]
        out.append(bytearray(data[off + 16: off + 16 + incl]))
        off += 16 + incl
    return data[:24], out


def sender(frame):
    """"a.b.c.d:port" of an Ethernet, IPv4, UDP frame."""
    ip = 14
    udp = ip + (frame[ip] & 0x0F) * 4
    return "%d.%d.%d.%d:%d" % (*frame[ip + 12: ip + 16], struct.unpack_from(">H", frame, udp)[0])


def resend_from(frame, last_octet, port):
    """The frame's IPv4 source set to 192.168.1.<last_octet>, its UDP source port to `port` (the
    RFC 791 header checksum recomputed; the UDP checksum 0, "none", RFC 768)."""
    ip = 14
    ihl = (frame[ip] & 0x0F) * 4
    udp = ip + ihl
    frame[ip + 12: ip + 16] = bytes([192, 168, 1, last_octet])
    frame[ip + 10: ip + 12] = b"\0\0"
    total = sum(struct.unpack_from(">%dH" % (ihl // 2), frame, ip))
    while total >> 16:
        total = (total & 0xFFFF) + (total >> 16)
    struct.pack_into(">H", frame, ip + 10, ~total & 0xFFFF)
    struct.pack_into(">H", frame, udp, port)
    frame[udp + 6: udp + 8] = b"\0\0"


def two_sensor_capture(path):
    """The XT16's records and the XT32's (from XT32_FROM), alternating, record i at
    1 700 000 000 s + 100 us x i. Returns (path, XT16's sender, XT32's sender)."""
    _, a = pcap_records(DATA / "pandar_xt16.pcap")
    _, b = pcap_records(DATA / "pandar_xt32.pcap")
    for f in b:
        resend_from(f, *XT32_FROM)
    out = bytearray(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))  # microseconds, Ethernet
    i = 0
    for k in range(max(len(a), len(b))):
        for frames in (a, b):
            if k < len(frames):
                us = i * 100
                out += struct.pack("<IIII", 1700000000 + us // 1000000, us % 1000000, len(frames[k]), len(frames[k]))
                out += frames[k]
                i += 1
    path.write_bytes(bytes(out))
    return path, sender(a[0]), sender(b[0])


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    return two_sensor_capture(tmp_path_factory.mktemp("sensors") / "two.pcap")


def csv_with_sensor(capture, args=()):
    """The program's CSV of `capture`: ({column: array} as test_package parses it, [sensor text per row])."""
    out = subprocess.run([CLI, "decode", str(capture), "--quiet", *args], check=True, capture_output=True).stdout
    header, body = out.split(b"\n", 1)
    assert header.decode() == HEADER + ",sensor"
    names = [line.rsplit(b",", 1)[1].decode() for line in body.split(b"\n") if line]
    return cli_csv_body(body), names


def test_each_row_names_its_sensor_as_the_csv(two):
    capture, xt16, xt32 = two
    want, want_names = csv_with_sensor(capture)
    rows, sensors = hesai.decode_file(capture, return_sensors=True)
    assert rows.dtype.names == tuple(HEADER.split(",")) + ("sensor",)
    assert_rows_equal(rows, want)
    # The names, in the order the sensors first sent: the inputs' senders, the XT16's record first.
    assert sensors == [xt16, xt32]
    assert xt32 == "192.168.1.%d:%d" % XT32_FROM
    # Row for row, the index names the CSV's sensor; both sensors have rows.
    assert np.array(sensors)[rows["sensor"]].tolist() == want_names
    assert set(want_names) == {xt16, xt32}
    # The columns name the same sensors.
    cols, col_sensors = hesai.decode_columns(capture, return_sensors=True)
    assert col_sensors == sensors
    assert cols["sensor"].dtype == np.dtype("<u2")
    assert np.array(col_sensors)[cols["sensor"]].tolist() == want_names


def test_frames_are_cut_per_sensor(two, tmp_path):
    capture, xt16, xt32 = two
    want, want_names = csv_with_sensor(capture)
    names = np.array(want_names)
    parts = list(hesai.frames(capture, with_sensor=True))
    # As many frames as the program counts (its frames are cut per sensor), each of one sensor.
    counts = json.loads(subprocess.run([CLI, "stats", str(capture), "--json"], check=True, capture_output=True).stdout)
    assert len(parts) == counts["frames"]
    _, sensors = hesai.decode_file(capture, return_sensors=True)
    ids = {xt16: [], xt32: []}
    for sensor, frame in parts:
        assert sensor in ids
        if len(frame):
            assert set(frame["sensor"].tolist()) == {sensors.index(sensor)}
            assert len(set(frame["frame"].tolist())) == 1
            ids[sensor].append(int(frame["frame"][0]))
    # Each sensor's frames, in id order, hold that sensor's CSV rows in their order (within a
    # sensor the CSV interleaves two frames' rows where a packet straddles the cut: a stable sort
    # by frame).
    for sensor in (xt16, xt32):
        assert len(ids[sensor]) >= 2 and ids[sensor] == sorted(set(ids[sensor]))
        mine = np.flatnonzero(names == sensor)
        order = mine[np.argsort(want["frame"][mine], kind="stable")]
        joined = np.concatenate([f for s, f in parts if s == sensor])
        assert_rows_equal(joined, {c: v[order] for c, v in want.items()})
    # Without with_sensor: the same frames, the arrays alone.
    plain = list(hesai.frames(capture))
    assert len(plain) == len(parts)
    for (_, a), b in zip(parts, plain):
        np.testing.assert_array_equal(a, b)
    # And each is one of the files `--per-frame` writes (one per sensor and frame).
    out = tmp_path / "frames"
    subprocess.run([CLI, "decode", str(capture), "--quiet", "--per-frame", "--out", str(out)], check=True,
                   capture_output=True)
    files = sorted(out.glob("frame_*.csv"))
    assert len(files) == len(parts)
    by_key = {}
    for f in files:
        header, body = f.read_bytes().split(b"\n", 1)
        lines = [line for line in body.split(b"\n") if line]
        if lines:
            key = (lines[0].rsplit(b",", 1)[1].decode(), int(lines[0].split(b",", 1)[0]))
            by_key[key] = cli_csv_body(body)
    matched = 0
    for sensor, frame in parts:
        if len(frame):
            assert_rows_equal(frame, by_key[(sensor, int(frame["frame"][0]))])
            matched += 1
    assert matched == len(by_key)


def test_one_sensor_is_sensor_zero():
    capture = DATA / "pandar_xt16.pcap"
    _, want_names = csv_with_sensor(capture)
    _, recs = pcap_records(capture)
    rows, sensors = hesai.decode_file(capture, return_sensors=True)
    assert sensors == [sender(recs[0])]
    assert set(want_names) == {sensors[0]}
    assert len(rows) == len(want_names) and not rows["sensor"].any()
    assert len(hesai.decode_file(capture)) == len(rows)  # without return_sensors: the rows alone
    parts = list(hesai.frames(capture, with_sensor=True))
    assert len(parts) >= 2 and all(s == sensors[0] and not f["sensor"].any() for s, f in parts)
    cols = hesai.decode_columns(capture)
    assert len(cols["sensor"]) == len(rows) and not cols["sensor"].any()
