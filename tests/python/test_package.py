"""The Python package (python/hesai) against the hesai program's CSV.

Expected values come from `hesai decode --format csv` (the program, run as a subprocess, its
output parsed here), never from the package. Environment: HESAI_CLI (the program; default
build/release/bin/hesai), HESAI_DATA (default data/), HESAI_LIBRARY (libhesai_c, optional).
"""

import io
import os
import pathlib
import struct
import subprocess
import sys

import numpy as np
import pytest

import hesai

ROOT = pathlib.Path(__file__).resolve().parents[2]
CLI = os.environ.get("HESAI_CLI", str(ROOT / "build" / "release" / "bin" / "hesai"))
DATA = pathlib.Path(os.environ.get("HESAI_DATA", str(ROOT / "data")))
CAL = DATA / "calibration"

# Each bundled capture, and the unit's calibration files (as the CLI and golden tests use them).
CAPTURES = {
    "pandar40p_dual": ("pandar40p_unit_a_angles.csv", "pandar40p_firetimes.csv"),
    "pandar64_dual": ("pandar64_unit_a_angles.csv", "pandar64_firetimes.csv"),
    "pandar_qt64": ("pandar_qt64_angles.csv", "pandar_qt64_firetimes.csv"),
    "pandar_xt16": ("pandar_xt16_angles.csv", "pandar_xt16_firetimes.csv"),
    "pandar_xt32": ("pandar_xt32_angles.csv", "pandar_xt32_firetimes.csv"),
    "pandar_xt32m2x": ("pandar_xt32m2x_angles.csv", "pandar_xt32m2x_firetimes.csv"),
    "qt128c2x_dual": ("qt128c2x_unit_a_angles.csv", "qt128c2x_firetimes.csv"),
}

INT_COLUMNS = ["frame", "packet", "block", "channel", "return", "intensity", "time_ns"]
# Column, decimals the CSV prints.
FLOAT_COLUMNS = [("azimuth_deg", 3), ("elevation_deg", 3), ("distance_m", 4), ("x", 4), ("y", 4), ("z", 4)]
HEADER = "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns"
# The CLI's CSV: the row's fields, then the sensor (its address and port, or a bag's topic).
CSV_HEADER = HEADER + ",sensor"


def test_every_bundled_capture_is_covered():
    assert sorted(p.stem for p in DATA.glob("*.pcap")) == sorted(CAPTURES)


def cli_csv(capture, args):
    """The program's CSV of `capture`: {column: array}."""
    out = subprocess.run([CLI, "decode", str(capture), "--quiet", *args], check=True, capture_output=True).stdout
    lines = out.split(b"\n", 1)
    assert lines[0].decode() == CSV_HEADER
    return cli_csv_body(lines[1])


def cli_csv_body(body):
    """The CSV rows after the header: {column: array}."""
    ints = [HEADER.split(",").index(c) for c in INT_COLUMNS]
    floats = [HEADER.split(",").index(c) for c, _ in FLOAT_COLUMNS]
    if not body.strip():
        empty = {c: np.empty(0, np.int64) for c in INT_COLUMNS}
        empty.update({c: np.empty(0) for c, _ in FLOAT_COLUMNS})
        return empty
    # One pass over the text: a record a row, each column its own type (time_ns needs int64 exactly).
    names = {i: c for i, c in zip(ints, INT_COLUMNS)}
    names.update({i: c for i, (c, _) in zip(floats, FLOAT_COLUMNS)})
    usecols = sorted(names)
    dtype = [(names[i], np.int64 if i in ints else np.float64) for i in usecols]
    rows = np.loadtxt(io.BytesIO(body), delimiter=",", dtype=dtype, usecols=usecols, ndmin=1)
    return {c: np.ascontiguousarray(rows[c]) for c in names.values()}


def assert_rows_equal(got, want, skip=()):
    """Integer columns exactly; float columns within half a unit of the CSV's last printed digit."""
    n = len(want["frame"])
    assert len(got) == n
    for c in INT_COLUMNS:
        if c not in skip:
            np.testing.assert_array_equal(got[c].astype(np.int64), want[c], err_msg=c)
    for c, decimals in FLOAT_COLUMNS:
        tol = 0.5 * 10.0 ** -decimals * (1 + 1e-6)
        diff = np.abs(got[c].astype(np.float64) - want[c])
        worst = int(np.argmax(diff)) if n else 0
        assert n == 0 or diff[worst] <= tol, f"{c} row {worst}: {got[c][worst]} vs CSV {want[c][worst]}"


CASES = [(name, False) for name in CAPTURES] + [(name, True) for name in CAPTURES]


def case_args(name, unit):
    """(CLI arguments, decode_file keyword arguments) for a capture with or without its unit's files."""
    if not unit:
        return [], {}
    angles, firetimes = CAPTURES[name]
    return (["--calibration", str(CAL / angles), "--firetimes", str(CAL / firetimes)],
            {"calibration": CAL / angles, "firetimes": CAL / firetimes})


@pytest.fixture(scope="module")
def expected():
    cache = {}

    def get(name, unit, extra=()):
        key = (name, unit, tuple(extra))
        if key not in cache:
            cache[key] = cli_csv(DATA / f"{name}.pcap", case_args(name, unit)[0] + list(extra))
        return cache[key]
    return get


@pytest.mark.parametrize("name,unit", CASES, ids=[f"{n}-{'unit' if u else 'design'}" for n, u in CASES])
def test_decode_file_equals_csv(name, unit, expected):
    want = expected(name, unit)
    got = hesai.decode_file(DATA / f"{name}.pcap", **case_args(name, unit)[1])
    assert got.dtype.names == tuple(CSV_HEADER.split(","))  # the sensor: an index (decode_file names them)
    assert len(got) > 1000
    assert_rows_equal(got, want)


# The frame and selection options the CLI has, on captures where they change the rows.
OPTION_CASES = [
    ("pandar64_dual", ["--cut-angle", "90"], {"cut_angle": 90.0}),
    ("qt128c2x_dual", ["--cut-angle", "270.5", "--fov", "300:60"], {"cut_angle": 270.5, "fov": (300.0, 60.0)}),
    ("pandar_xt32", ["--packets", "100:900", "--min-range", "2", "--max-range", "40"],
     {"packets": (100, 900), "min_range": 2.0, "max_range": 40.0}),
    ("pandar40p_dual", ["--rotation", "ccw", "--no-firetime-azimuth"], {"rotation": "ccw", "firetime_azimuth": False}),
    ("qt128c2x_dual", ["--channel-config", str(CAL / "qt128c2x_channel_config.csv")],
     {"channel_config": CAL / "qt128c2x_channel_config.csv"}),
    ("pandar64_dual", ["--returns", "distinct"], {"returns": "distinct"}),
    ("qt128c2x_dual", ["--returns", "distinct"], {"returns": "distinct"}),
]


@pytest.mark.parametrize("name,args,kw", OPTION_CASES, ids=[f"{c[0]}-{' '.join(c[1])}" for c in OPTION_CASES])
def test_options_equal_csv(name, args, kw, expected):
    want = expected(name, False, args)
    # Each option keeps some of the capture's points: an empty CSV would equal an empty decode.
    assert len(want["frame"]) > 0
    got = hesai.decode_file(DATA / f"{name}.pcap", **kw)
    assert_rows_equal(got, want)


@pytest.mark.parametrize("name,unit", CASES, ids=[f"{n}-{'unit' if u else 'design'}" for n, u in CASES])
def test_frames_concatenated_equal_decode_file(name, unit):
    kw = case_args(name, unit)[1]
    whole = hesai.decode_file(DATA / f"{name}.pcap", **kw)
    parts = list(hesai.frames(DATA / f"{name}.pcap", **kw))
    ids = [int(p["frame"][0]) for p in parts if len(p)]
    assert ids == sorted(ids) and len(set(ids)) == len(ids)
    for p in parts:
        assert len(set(p["frame"].tolist())) <= 1
    joined = np.concatenate(parts)
    # Frames close in id order; within a frame the rows keep the CSV's order. The CSV interleaves
    # two frames' rows where a packet straddles the cut, so it equals the frames joined after a
    # stable sort by frame.
    order = np.argsort(whole["frame"], kind="stable")
    np.testing.assert_array_equal(joined, whole[order])
    # And frames() may not buffer the whole capture: it yields more than one frame.
    assert len(ids) >= 2


@pytest.mark.parametrize("cut", [0.0, 123.4])
def test_frames_with_a_cut_equal_the_csv_frames(cut, expected):
    want = expected("qt128c2x_dual", False, ["--cut-angle", str(cut)])
    assert len(want["frame"]) > 0
    parts = list(hesai.frames(DATA / "qt128c2x_dual.pcap", cut_angle=cut))
    joined = np.concatenate(parts)
    order = np.argsort(want["frame"], kind="stable")
    assert_rows_equal(joined, {c: v[order] for c, v in want.items()})


PER_FRAME_CASES = [
    ("pandar64_dual", [], {}),
    ("pandar_xt32m2x", ["--cut-angle", "123.4"], {"cut_angle": 123.4}),
    ("qt128c2x_dual", ["--cut-angle", "123.4", "--fov", "300:60"], {"cut_angle": 123.4, "fov": (300.0, 60.0)}),
]


@pytest.mark.parametrize("name,args,kw", PER_FRAME_CASES, ids=[f"{c[0]}-{' '.join(c[1])}" for c in PER_FRAME_CASES])
def test_frames_equal_the_per_frame_csv_files(name, args, kw, tmp_path):
    """frames() gives the frames `hesai decode --per-frame` writes a file for, in order, each
    with that file's rows."""
    out = tmp_path / "frames"
    subprocess.run([CLI, "decode", str(DATA / f"{name}.pcap"), "--quiet", "--per-frame", "--out", str(out), *args],
                   check=True, capture_output=True)
    files = sorted(out.glob("frame_*.csv"))
    parts = list(hesai.frames(DATA / f"{name}.pcap", **kw))
    assert len(files) >= 2
    assert len(parts) == len(files)
    rows = 0
    for part, f in zip(parts, files):
        text = f.read_bytes()
        body = text.split(b"\n", 1)[1] if b"\n" in text else b""
        want = cli_csv_body(body)
        assert_rows_equal(part, want)
        rows += len(want["frame"])
        if len(part):
            assert int(f.stem.rsplit("_", 1)[1]) == int(part["frame"][0])  # frame_<sensor>_<n>
    assert rows > 0


def udp_payloads(path):
    """The UDP payloads of a classic pcap (Ethernet, IPv4), in file order: the test's own reader."""
    data = pathlib.Path(path).read_bytes()
    magic = struct.unpack_from("<I", data, 0)[0]
    assert magic in (0xA1B2C3D4, 0xA1B23C4D), "the bundled captures are little-endian classic pcap"
    link = struct.unpack_from("<I", data, 20)[0]
    assert link == 1
    off = 24
    out = []
    while off + 16 <= len(data):
        incl = struct.unpack_from("<I", data, off + 8)[0]
        frame = data[off + 16: off + 16 + incl]
        off += 16 + incl
        eth = 14
        ethertype = struct.unpack_from(">H", frame, 12)[0]
        while ethertype in (0x8100, 0x88A8):
            ethertype = struct.unpack_from(">H", frame, eth + 2)[0]
            eth += 4
        if ethertype != 0x0800:
            continue
        ihl = (frame[eth] & 0x0F) * 4
        if frame[eth + 9] != 17:
            continue
        udp = eth + ihl
        length = struct.unpack_from(">H", frame, udp + 4)[0]
        out.append(frame[udp + 8: udp + length])
    return out


@pytest.mark.parametrize("name,unit", CASES, ids=[f"{n}-{'unit' if u else 'design'}" for n, u in CASES])
def test_decoder_single_packets_equal_rows(name, unit, expected):
    want = expected(name, unit)
    kw = case_args(name, unit)[1]
    decoder = hesai.Decoder(**kw)
    starts = np.searchsorted(want["packet"], np.arange(want["packet"][-1] + 2))  # rows are in packet order
    assert np.all(np.diff(want["packet"]) >= 0)
    index = 0
    checked = 0
    for payload in udp_payloads(DATA / f"{name}.pcap"):
        try:
            points = decoder.decode(payload)
        except hesai.HesaiError:
            continue  # rejected: no packet index, as in the program
        if len(points) == 0 and len(payload) == 512:
            continue  # a GPS packet
        lo, hi = starts[index], starts[index + 1]
        assert_rows_equal(points, {c: v[lo:hi] for c, v in want.items()}, skip=("frame", "packet"))
        index += 1
        checked += hi - lo
    assert index == want["packet"][-1] + 1
    assert checked == len(want["packet"])


def test_decoder_errors_name_the_code():
    payload = bytearray(udp_payloads(DATA / "qt128c2x_dual.pcap")[0])
    decoder = hesai.Decoder()
    assert len(decoder.decode(bytes(payload))) > 0
    assert decoder.model == "QT128C2X"
    payload[100] ^= 0xFF
    with pytest.raises(hesai.HesaiError) as e:
        decoder.decode(bytes(payload))
    assert e.value.code == "crc_body"


def test_unreadable_capture_and_bad_calibration_raise(tmp_path):
    with pytest.raises(hesai.HesaiError) as e:
        hesai.decode_file(tmp_path / "missing.pcap")
    assert e.value.status == 2
    not_pcap = tmp_path / "x.pcap"
    not_pcap.write_bytes(b"\0" * 64)
    with pytest.raises(hesai.HesaiError) as e:
        hesai.decode_file(not_pcap)
    assert e.value.status == 2 and "capture" in str(e.value)
    with pytest.raises(hesai.HesaiError) as e:  # a 64-channel file for a 40-channel sensor
        hesai.decode_file(DATA / "pandar40p_dual.pcap", calibration=CAL / "pandar64_unit_a_angles.csv")
    assert e.value.status == 1
    with pytest.raises(hesai.HesaiError):
        hesai.decode_file(DATA / "pandar40p_dual.pcap", cut_angle=360.0)


def test_installed_package_finds_its_library(tmp_path):
    """cmake --install puts the package and libhesai_c under a prefix; the package imported from
    there (no HESAI_LIBRARY, run from elsewhere) loads that library and decodes."""
    build = os.environ.get("HESAI_BUILD_DIR", str(ROOT / "build" / "release"))
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True, capture_output=True)
    site = prefix / "lib" / "python3" / "dist-packages"
    env = {k: v for k, v in os.environ.items() if k not in ("HESAI_LIBRARY", "PYTHONPATH")}
    env["PYTHONPATH"] = str(site)
    code = ("import sys, hesai; print(hesai.__file__); print(hesai.library_path); "
            "print(len(hesai.decode_file(sys.argv[1])))")
    out = subprocess.run([sys.executable, "-c", code, str(DATA / "pandar_xt16.pcap")], check=True,
                         capture_output=True, text=True, cwd=tmp_path, env=env).stdout.split("\n")
    assert out[0].startswith(str(site))
    assert out[1].startswith(str(prefix / "lib"))
    assert int(out[2]) == len(cli_csv(DATA / "pandar_xt16.pcap", [])["frame"])
