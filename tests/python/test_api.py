"""The package's installed-user surface: decode_columns and stats against the hesai program (its
CSV and `stats --json`, run as a subprocess), path types, closed files, the layout check at
import, the version.
"""

import ctypes
import json
import os
import pathlib
import re
import struct
import subprocess
import sys

import numpy as np
import pytest

import hesai
from hesai import _lib
from test_package import (CAL, CAPTURES, CLI, DATA, FLOAT_COLUMNS, INT_COLUMNS, ROOT, case_args, cli_csv,
                          cli_csv_body, udp_payloads)

CASES = [(name, False) for name in CAPTURES] + [(name, True) for name in CAPTURES]
IDS = [f"{n}-{'unit' if u else 'design'}" for n, u in CASES]


def assert_columns_equal(got, want):
    """The CSV's columns that decode_columns has: integers exactly, floats within half a unit of
    the CSV's last printed digit."""
    assert list(got) == ["packet", "channel", "return", "x", "y", "z", "intensity", "time_ns", "sensor"]
    n = len(want["packet"])
    for name, a in got.items():
        assert a.dtype == hesai.COLUMNS[name] and a.ndim == 1 and len(a) == n, name
    for c in INT_COLUMNS:
        if c in got:
            np.testing.assert_array_equal(got[c].astype(np.int64), want[c], err_msg=c)
    for c, decimals in FLOAT_COLUMNS:
        if c in got:
            tol = 0.5 * 10.0 ** -decimals * (1 + 1e-6)
            diff = np.abs(got[c].astype(np.float64) - want[c])
            assert n == 0 or diff.max() <= tol, c


@pytest.fixture(scope="module")
def csv():
    cache = {}

    def get(name, args=()):
        key = (name, tuple(args))
        if key not in cache:
            cache[key] = cli_csv(DATA / f"{name}.pcap", list(args))
        return cache[key]
    return get


@pytest.mark.parametrize("name,unit", CASES, ids=IDS)
def test_decode_columns_equals_csv(name, unit, csv):
    args, kw = case_args(name, unit)
    want = csv(name, args)
    assert len(want["packet"]) > 1000
    assert_columns_equal(hesai.decode_columns(DATA / f"{name}.pcap", **kw), want)


def test_decode_columns_into_a_buffer(csv):
    """One ColumnBuffer through captures of more, then fewer, points: each result the CSV's. The
    buffer starts at 65 536 points and doubles, its points copied, while the Pandar64 capture is
    read (716 622 points); no capture after it needs more, so its memory stays."""
    buf = hesai.ColumnBuffer()
    first = None
    for name in ["pandar64_dual", "pandar_xt16", "qt128c2x_dual", "pandar_xt32m2x"]:
        got = hesai.decode_columns(DATA / f"{name}.pcap", buffer=buf)
        assert_columns_equal(got, csv(name))
        if first is None:
            first = buf.columns["x"]
            assert len(first) == 1 << 20  # 65 536 doubled four times
        assert buf.columns["x"] is first
        assert np.shares_memory(got["x"], first)


COLUMN_OPTIONS = [
    ("pandar40p_dual", ["--rotation", "ccw", "--no-firetime-azimuth"], {"rotation": "ccw", "firetime_azimuth": False}),
    ("pandar_xt32", ["--packets", "100:900"], {"packets": (100, 900)}),
    ("qt128c2x_dual", ["--channel-config", str(CAL / "qt128c2x_channel_config.csv")],
     {"channel_config": CAL / "qt128c2x_channel_config.csv"}),
    ("pandar64_dual", ["--reflectivity", "nonlinear"], {"reflectivity": "nonlinear"}),
]


@pytest.mark.parametrize("name,args,kw", COLUMN_OPTIONS, ids=[f"{c[0]}-{' '.join(c[1])}" for c in COLUMN_OPTIONS])
def test_decode_columns_options_equal_csv(name, args, kw, csv):
    want = csv(name, args)
    assert len(want["packet"]) > 0
    assert_columns_equal(hesai.decode_columns(DATA / f"{name}.pcap", **kw), want)


def test_decode_columns_rotation_decided_late(tmp_path, csv):
    """The dual-return QT128C2X's packets show no direction by themselves: the first two are held
    until the third decides it (docs/CLI.md), then decoded; the CSV's rows of a capture mirrored
    counter-clockwise would show a wrong hold. Here: the same rows as the CSV with --rotation auto
    and, as a control, that the ccw decode differs (the held packets matter)."""
    want = csv("qt128c2x_dual", [])
    got = hesai.decode_columns(DATA / "qt128c2x_dual.pcap", packets=(0, 5))
    n = int(np.searchsorted(want["packet"], 5))
    assert_columns_equal(got, {c: v[:n] for c, v in want.items()})
    ccw = hesai.decode_columns(DATA / "qt128c2x_dual.pcap", packets=(0, 5), rotation="ccw")
    assert not np.array_equal(ccw["x"], got["x"])


def test_decode_columns_refuses_what_it_does_not_take():
    with pytest.raises(TypeError):
        hesai.decode_columns(DATA / "pandar_xt16.pcap", cut_angle=90.0)
    with pytest.raises(ValueError):
        hesai.decode_columns(DATA / "pandar_xt16.pcap", rotation="sideways")
    with pytest.raises(hesai.HesaiError) as e:  # a 64-channel file for a 16-channel sensor
        hesai.decode_columns(DATA / "pandar_xt16.pcap", calibration=CAL / "pandar64_unit_a_angles.csv")
    assert e.value.status == 1 and "pandar64_unit_a_angles.csv" in str(e.value)


def truncated(tmp_path, name, keep_records):
    """A copy of the capture cut in the middle of record `keep_records` (the test's own pcap walk)."""
    data = (DATA / f"{name}.pcap").read_bytes()
    off = 24
    for _ in range(keep_records):
        off += 16 + struct.unpack_from("<I", data, off + 8)[0]
    out = tmp_path / f"{name}_cut.pcap"
    out.write_bytes(data[:off + 100])
    return out


def test_damaged_capture_gives_the_points_before_the_damage(tmp_path, csv):
    cut = truncated(tmp_path, "pandar_xt32", 500)
    run = subprocess.run([CLI, "decode", str(cut), "--quiet"], capture_output=True)
    assert run.returncode == 2
    want = cli_csv_body(run.stdout.split(b"\n", 1)[1])
    assert want["packet"].max() == 499  # the 500 whole packets' rows
    with pytest.raises(hesai.HesaiError) as e:
        hesai.decode_columns(cut)
    assert e.value.status == 2 and str(e.value) and str(e.value) in run.stderr.decode()  # the program's message
    assert_columns_equal(e.value.columns, want)


def cli_stats(capture, args=()):
    run = subprocess.run([CLI, "stats", str(capture), "--json", *args], capture_output=True)
    return run.returncode, (json.loads(run.stdout) if run.stdout.strip() else None)


@pytest.mark.parametrize("name,unit", CASES, ids=IDS)
def test_stats_equal_the_program_json(name, unit):
    args, kw = case_args(name, unit)
    rc, want = cli_stats(DATA / f"{name}.pcap", args)
    assert rc == 0 and want["packets"] > 1000
    got = hesai.stats(DATA / f"{name}.pcap", **kw)
    assert list(got) == list(want)  # the same keys in the same order
    assert got == want


def test_stats_with_options_and_of_a_damaged_capture(tmp_path):
    rc, want = cli_stats(DATA / "qt128c2x_dual.pcap", ["--cut-angle", "90", "--returns", "distinct"])
    assert rc == 0
    assert hesai.stats(DATA / "qt128c2x_dual.pcap", cut_angle=90.0, returns="distinct") == want
    cut = truncated(tmp_path, "pandar64_dual", 700)
    rc, want = cli_stats(cut)
    assert rc == 2 and want["packets"] == 700
    with pytest.raises(hesai.HesaiError) as e:
        hesai.stats(cut)
    assert e.value.status == 2 and e.value.stats == want
    with pytest.raises(hesai.HesaiError) as e:
        hesai.stats(tmp_path / "missing.pcap")
    assert e.value.status == 2 and e.value.stats is None


@pytest.mark.parametrize("kind", ["str", "bytes", "PathLike"])
def test_every_path_type(kind, csv, tmp_path):
    conv = {"str": str, "bytes": lambda p: os.fsencode(str(p)), "PathLike": pathlib.Path}[kind]
    cap, angles = DATA / "pandar_xt16.pcap", CAL / "pandar_xt16_angles.csv"
    want = csv("pandar_xt16", ["--calibration", str(angles)])
    rows = hesai.decode_file(conv(cap), calibration=conv(angles))
    assert len(rows) == len(want["packet"])
    assert_columns_equal(hesai.decode_columns(conv(cap), calibration=conv(angles)), want)
    assert sum(len(f) for f in hesai.frames(conv(cap), calibration=conv(angles))) == len(want["packet"])
    assert hesai.stats(conv(cap))["packets"] == cli_stats(cap)[1]["packets"]
    decoder = hesai.Decoder(calibration=conv(angles))
    assert len(decoder.decode(udp_payloads(cap)[0])) > 0
    with pytest.raises(TypeError):
        hesai.decode_file(12)
    with pytest.raises(ValueError):
        hesai.stats("a\0b.pcap")


def test_no_resource_warning():
    """Each entry point, and a frames() generator dropped half-way, in a fresh interpreter with
    ResourceWarning an error and development mode (which reports unclosed files at collection):
    nothing on stderr."""
    code = f"""
import gc, hesai
cap, angles = {str(DATA / 'pandar_xt16.pcap')!r}, {str(CAL / 'pandar_xt16_angles.csv')!r}
hesai.decode_file(cap, calibration=angles)
hesai.decode_columns(cap, calibration=angles)
hesai.stats(cap, calibration=angles)
g = hesai.frames(cap, calibration=angles)
next(g)
del g
d = hesai.Decoder(calibration=angles, firetimes={str(CAL / 'pandar_xt16_firetimes.csv')!r})
del d
try:
    hesai.Decoder(calibration="/nonexistent/angles.csv")
except FileNotFoundError:
    pass
gc.collect()
print("done")
"""
    run = subprocess.run([sys.executable, "-X", "dev", "-W", "error", "-c", code], capture_output=True, text=True,
                         env=os.environ)
    assert run.returncode == 0, run.stderr
    assert run.stdout == "done\n"
    assert run.stderr == ""


class FakeLayout:
    """The library's layout with one member moved, as a library of another version would have it."""

    def __init__(self, which, field, offset=None, size=None):
        self.which, self.field, self.offset, self.size = which, field, offset, size

    def hesai_capture_layout(self, which, name):
        if which == self.which and name is None and self.size is not None:
            return self.size
        if which == self.which and name is not None and name.decode() == self.field:
            return self.offset
        return _lib.lib.hesai_capture_layout(which, name)


def test_layout_checked(monkeypatch):
    _lib.check_layout()  # the real library matches
    with pytest.raises(hesai.LayoutError, match=r"hesai_capture_row\.z is at 40, the dtype's at 44"):
        _lib.check_layout(FakeLayout(0, "z", offset=40))
    with pytest.raises(hesai.LayoutError, match=r"hesai_capture_row is 64 bytes, the dtype 56"):
        _lib.check_layout(FakeLayout(0, None, size=64))
    with pytest.raises(hesai.LayoutError, match=r"hesai_point\.confidence is absent"):
        _lib.check_layout(FakeLayout(1, "confidence", offset=ctypes.c_size_t(-1).value))
    # And a dtype changed in the package against the real library.
    monkeypatch.setattr(_lib, "ROW_DTYPE", np.dtype({"names": ["frame", "x"], "formats": ["<u8", "<f4"],
                                                     "offsets": [0, 36], "itemsize": 48}))
    with pytest.raises(hesai.LayoutError, match=r"hesai_capture_row is 56 bytes, the dtype 48"):
        _lib.check_layout()
    assert issubclass(hesai.LayoutError, ImportError)


def test_a_library_without_the_sensor_functions_is_refused(monkeypatch):
    """A library of the version before sensors (issue #34) lacks hesai_capture_sensors and its
    row has no sensor member: LayoutError, for each."""
    _lib._require("hesai_capture_sensors", "hesai_capture_sensor_name")  # the real library has them

    class Earlier:
        hesai_capture_open = _lib.lib.hesai_capture_open
    monkeypatch.setattr(_lib, "lib", Earlier())
    with pytest.raises(hesai.LayoutError, match=r"has no hesai_capture_sensors, hesai_capture_sensor_name"):
        _lib._require("hesai_capture_sensors", "hesai_capture_sensor_name")
    monkeypatch.undo()
    with pytest.raises(hesai.LayoutError, match=r"hesai_capture_row\.sensor is absent"):
        _lib.check_layout(FakeLayout(0, "sensor", offset=ctypes.c_size_t(-1).value))


def test_layout_mismatch_fails_the_import():
    """At import: a library whose layout differs (hesai_capture_layout answering 40 for the row's
    z, through a patched ctypes.CDLL) makes `import hesai` raise LayoutError."""
    code = """
import ctypes
real = ctypes.CDLL
class Patched:
    def __init__(self, *a, **k):
        self._lib = real(*a, **k)
        self.hesai_capture_layout = self
        self.argtypes = self.restype = None
    def __getattr__(self, name):
        return getattr(self._lib, name)
    def __call__(self, which, name):
        f = self._lib.hesai_capture_layout
        f.argtypes, f.restype = [ctypes.c_int, ctypes.c_char_p], ctypes.c_size_t
        return 40 if (which, name) == (0, b"z") else f(which, name)
ctypes.CDLL = Patched
try:
    import hesai
except ImportError as e:
    print(type(e).__name__, e)
"""
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("LayoutError hesai: ")
    assert "hesai_capture_row.z is at 40, the dtype's at 44" in run.stdout


def test_version_is_the_projects():
    m = re.search(r"project\(hesai VERSION (\S+)", (ROOT / "CMakeLists.txt").read_text())
    assert hesai.__version__ == m.group(1)
    assert (pathlib.Path(hesai.__file__).parent / "py.typed").is_file()


def test_bound_is_the_packets_times_their_points():
    """decode_file and decode_columns size their arrays once from hesai_capture_bound: every
    datagram, and the points per packet of each one's model (the manuals' blocks x channels,
    written here by hand, told apart by payload length)."""
    # Pandar40P 10 x 40, Pandar64 6 x 64 (1198: with the UDP sequence), PandarQT64 4 x 64,
    # XT16 8 x 16, XT32 8 x 32, XT32M2X 6 x 32, QT128C2X 2 x 128.
    points_by_length = {1262: 400, 1198: 384, 1072: 256, 568: 128, 1080: 256, 820: 192, 1127: 256}
    for name in CAPTURES:
        payloads = udp_payloads(DATA / f"{name}.pcap")
        with hesai._Capture(DATA / f"{name}.pcap") as cap:
            datagrams, most = cap.bound()
        assert datagrams == len(payloads), name
        assert most == sum(points_by_length[len(p)] for p in payloads), name


def test_errors_pickle_whole():
    """A worker process's HesaiError reaches the client (dask pickles it) with its status, code and stats."""
    import pickle
    e = pickle.loads(pickle.dumps(hesai.HesaiError("x.pcap: cut", status=2, code="bad_length", stats={"packets": 3})))
    assert (type(e), str(e), e.status, e.code, e.stats) == (hesai.HesaiError, "x.pcap: cut", 2, "bad_length", {"packets": 3})
