"""The Python package as people install it (ctest python_pip_install): `pip install
--no-build-isolation --no-index` of python/ into a fresh virtual environment made with
--system-site-packages (Debian's numpy and setuptools, no network), then, from another directory
and without PYTHONPATH or HESAI_LIBRARY, `import hesai; hesai.decode_columns(...)` against the CSV
of `hesai decode` (the program, run as a subprocess, its output parsed here) and `hesai.stats`
against `hesai stats --json`.

Environment: HESAI_BUILD_DIR (the CMake build tree whose lib/libhesai_c.so setup.py copies into
the package; default build/release), HESAI_CLI (the program; default build/release/bin/hesai),
HESAI_DATA (default data/).
"""

import io
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = os.environ.get("HESAI_BUILD_DIR", str(ROOT / "build" / "release"))
CLI = os.environ.get("HESAI_CLI", str(ROOT / "build" / "release" / "bin" / "hesai"))
DATA = pathlib.Path(os.environ.get("HESAI_DATA", str(ROOT / "data")))
HEADER = "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns,sensor"
# The columns decode_columns has, and the decimals the CSV prints for the float ones.
INTS = ["packet", "channel", "return", "intensity", "time_ns"]
FLOATS = {"x": 4, "y": 4, "z": 4}


@pytest.fixture(scope="module")
def venv(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("pip")
    # A copy of python/, so that the build's files (build/, *.egg-info) stay out of the checkout.
    src = tmp / "src"
    shutil.copytree(ROOT / "python", src, ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info",
                                                                         "libhesai_c.so"))
    env_dir = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(env_dir)], check=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "HESAI_LIBRARY", "PIP_INDEX_URL")}
    env["HESAI_BUILD_DIR"] = BUILD
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    run = subprocess.run([str(env_dir / "bin" / "python"), "-m", "pip", "install", "--no-build-isolation", "--no-index",
                          str(src)], env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    return env_dir


def in_venv(venv, code, *args):
    """Runs `code` with the environment's python, from a directory of its own, without
    PYTHONPATH or HESAI_LIBRARY: only what pip installed is found."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "HESAI_LIBRARY", "HESAI_BUILD_DIR")}
    cwd = venv.parent / "elsewhere"
    cwd.mkdir(exist_ok=True)
    run = subprocess.run([str(venv / "bin" / "python"), "-c", code, *map(str, args)], env=env, cwd=cwd,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_installed_into_the_environment(venv):
    out = in_venv(venv, "import hesai; print(hesai.__file__); print(hesai.library_path); print(hesai.__version__)")
    module, library, version = out.split("\n")[:3]
    site = next((venv / "lib").glob("python3*/site-packages"))
    assert module == str(site / "hesai" / "__init__.py")
    assert library == str(site / "hesai" / "libhesai_c.so")  # its own copy, not the build tree's
    assert (site / "hesai" / "py.typed").is_file()
    meta = (site / f"hesai-{version}.dist-info" / "METADATA").read_text()
    assert "Requires-Dist: numpy" in meta.split("\n")
    assert f"Version: {version}" in meta.split("\n")


@pytest.mark.parametrize("name", ["pandar_xt32", "qt128c2x_dual"])
def test_decode_columns_equals_the_csv(venv, name, tmp_path):
    capture = DATA / f"{name}.pcap"
    npz = tmp_path / "cols.npz"
    in_venv(venv, "import sys, numpy, hesai; numpy.savez(sys.argv[2], **hesai.decode_columns(sys.argv[1]))",
            capture, npz)
    got = dict(np.load(npz))
    csv = subprocess.run([CLI, "decode", str(capture), "--quiet"], check=True, capture_output=True).stdout
    head, body = csv.split(b"\n", 1)
    assert head.decode() == HEADER
    names = HEADER.split(",")
    ints = np.loadtxt(io.BytesIO(body), delimiter=",", dtype=np.int64, usecols=[names.index(c) for c in INTS])
    floats = np.loadtxt(io.BytesIO(body), delimiter=",", usecols=[names.index(c) for c in FLOATS])
    assert len(ints) > 100000
    assert sorted(got) == sorted(INTS + list(FLOATS) + ["sensor"])
    assert not got["sensor"].any()  # one sensor: index 0 in every row
    for i, c in enumerate(INTS):
        np.testing.assert_array_equal(got[c].astype(np.int64), ints[:, i], err_msg=c)
    for i, (c, decimals) in enumerate(FLOATS.items()):
        assert np.abs(got[c].astype(np.float64) - floats[:, i]).max() <= 0.5 * 10.0 ** -decimals * (1 + 1e-6), c


def test_stats_equal_the_program_json(venv):
    capture = DATA / "pandar64_dual.pcap"
    got = json.loads(in_venv(venv, "import sys, json, hesai; print(json.dumps(hesai.stats(sys.argv[1])))", capture))
    want = json.loads(subprocess.run([CLI, "stats", str(capture), "--json"], check=True, capture_output=True).stdout)
    assert got == want and want["packets"] == 2400
