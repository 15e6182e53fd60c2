"""libhesai_c through ctypes: where it is found, and the C declarations the package calls.

The library is looked for, in order: at the path in the environment variable HESAI_LIBRARY; the
copy `pip install` put beside this file (hesai/libhesai_c.so); where `cmake --install` recorded it
(hesai/_installed.py); in the checkout's build trees (build/release/lib, then any build/*/lib); by
the system's loader (ctypes.util.find_library).

At import the layouts of hesai_capture_row and hesai_point, as the loaded library was compiled
(hesai_capture_layout), are compared with ROW_DTYPE and POINT_DTYPE: a mismatch raises LayoutError.
"""

import ctypes
import ctypes.util
import mmap
import os
import pathlib
import sys

import numpy as np

_NAMES = ("libhesai_c.so", "libhesai_c.so.1", "libhesai_c.dylib")


def _candidates():
    env = os.environ.get("HESAI_LIBRARY")
    if env:
        yield env
        return
    here = pathlib.Path(__file__).resolve().parent
    if (here / "libhesai_c.so").exists():  # pip install copies it here
        yield str(here / "libhesai_c.so")
    try:
        from . import _installed  # written by cmake --install
        yield _installed.LIBRARY
    except ImportError:
        pass
    root = pathlib.Path(__file__).resolve().parents[2]  # python/hesai/_lib.py -> the checkout
    build = root / "build"
    dirs = [build / "release" / "lib"] + sorted(p for p in build.glob("*/lib") if p != build / "release" / "lib")
    for d in dirs:
        for name in _NAMES:
            if (d / name).exists():
                yield str(d / name)
    found = ctypes.util.find_library("hesai_c")
    if found:
        yield found


def _load():
    tried = []
    for path in _candidates():
        try:
            return ctypes.CDLL(path), path
        except OSError as e:
            tried.append(f"{path}: {e}")
    raise ImportError("hesai: libhesai_c not found (build it with `cmake --preset release && cmake --build "
                      "build/release --target hesai_c`, or set HESAI_LIBRARY)" + "".join("\n  " + t for t in tried))


lib, path = _load()


class LayoutError(ImportError):
    """The loaded libhesai_c lays out a record otherwise than the package's dtype: a library of
    another version. Reading its records through the dtype would give wrong values."""


def _require(*names):
    """Raises LayoutError when the library lacks one of these functions (an earlier version)."""
    missing = [n for n in names if not hasattr(lib, n)]
    if missing:
        raise LayoutError(f"hesai: {path} has no {', '.join(missing)}: a library of an earlier version; "
                          "install the library and the package from the same version")


_require("hesai_capture_sensors", "hesai_capture_sensor_name")

# ---- hesai_port/hesai_capture.h -----------------------------------------------------------------


class CaptureOptions(ctypes.Structure):
    _fields_ = [
        ("calibration", ctypes.c_char_p),
        ("firetimes", ctypes.c_char_p),
        ("channel_config", ctypes.c_char_p),
        ("reflectivity", ctypes.c_int),
        ("firetime_azimuth", ctypes.c_int),
        ("rotation", ctypes.c_int),
        ("first_packet", ctypes.c_uint64),
        ("end_packet", ctypes.c_uint64),
        ("cut_angle_deg", ctypes.c_float),
        ("has_fov", ctypes.c_int),
        ("fov_start_deg", ctypes.c_float),
        ("fov_end_deg", ctypes.c_float),
        ("min_range_m", ctypes.c_float),
        ("max_range_m", ctypes.c_float),
        ("session_key", ctypes.c_void_p),
        ("allow_unsigned", ctypes.c_int),
        ("returns", ctypes.c_int),
    ]


# hesai_capture_row: the C struct's layout, fields named and ordered as the CSV's columns (sensor:
# the index of the CSV's sensor text, hesai_capture_sensor_name).
ROW_DTYPE = np.dtype({
    "names": ["frame", "packet", "block", "channel", "return", "azimuth_deg", "elevation_deg", "distance_m",
              "x", "y", "z", "intensity", "time_ns", "sensor"],
    "formats": ["<u8", "<u8", "u1", "u1", "u1", "<f4", "<f4", "<f4", "<f4", "<f4", "<f4", "u1", "<i8", "<u2"],
    "offsets": [0, 8, 48, 49, 50, 24, 28, 32, 36, 40, 44, 51, 16, 52],
    "itemsize": 56,
})

lib.hesai_capture_default_options.argtypes = [ctypes.POINTER(CaptureOptions)]
lib.hesai_capture_default_options.restype = None
lib.hesai_capture_open.argtypes = [ctypes.c_char_p, ctypes.POINTER(CaptureOptions), ctypes.POINTER(ctypes.c_void_p),
                                   ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_capture_open.restype = ctypes.c_int
lib.hesai_capture_read.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t),
                                   ctypes.POINTER(ctypes.c_uint64), ctypes.POINTER(ctypes.c_uint16), ctypes.c_char_p,
                                   ctypes.c_size_t]
lib.hesai_capture_read.restype = ctypes.c_int
lib.hesai_capture_sensors.argtypes = [ctypes.c_void_p]
lib.hesai_capture_sensors.restype = ctypes.c_size_t
lib.hesai_capture_sensor_name.argtypes = [ctypes.c_void_p, ctypes.c_size_t]
lib.hesai_capture_sensor_name.restype = ctypes.c_char_p
lib.hesai_capture_packets.argtypes = [ctypes.c_void_p]
lib.hesai_capture_packets.restype = ctypes.c_uint64
lib.hesai_capture_close.argtypes = [ctypes.c_void_p]
lib.hesai_capture_close.restype = None
lib.hesai_capture_bound.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint64), ctypes.POINTER(ctypes.c_uint64),
                                    ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_capture_bound.restype = ctypes.c_int


class CaptureColumns(ctypes.Structure):
    _fields_ = [
        ("x", ctypes.c_void_p),
        ("y", ctypes.c_void_p),
        ("z", ctypes.c_void_p),
        ("time_ns", ctypes.c_void_p),
        ("intensity", ctypes.c_void_p),
        ("channel", ctypes.c_void_p),
        ("return_index", ctypes.c_void_p),
        ("packet", ctypes.c_void_p),
        ("sensor", ctypes.c_void_p),
        ("capacity", ctypes.c_size_t),
    ]


COLUMNS_MIN = 4000  # HESAI_CAPTURE_COLUMNS_MIN
lib.hesai_capture_read_columns.argtypes = [ctypes.c_void_p, ctypes.POINTER(CaptureColumns),
                                           ctypes.POINTER(ctypes.c_size_t), ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_capture_read_columns.restype = ctypes.c_int
lib.hesai_capture_stats_json.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t,
                                         ctypes.POINTER(ctypes.c_size_t), ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_capture_stats_json.restype = ctypes.c_int
lib.hesai_capture_layout.argtypes = [ctypes.c_int, ctypes.c_char_p]
lib.hesai_capture_layout.restype = ctypes.c_size_t

# ---- hesai/hesai.h ------------------------------------------------------------------------------

DECODER_SIZE = 8192                 # HESAI_DECODER_SIZE
CALIBRATION_SCRATCH_SIZE = 2312     # HESAI_CALIBRATION_SCRATCH_SIZE
MAX_POINTS_PER_PACKET = 400         # HESAI_MAX_POINTS_PER_PACKET

# hesai_point (hesai::Point's layout), its members named as the CSV's columns (return_index is
# "return"); confidence is the QT128's per-point byte, 0 for other models.
POINT_DTYPE = np.dtype({
    "names": ["x", "y", "z", "distance_m", "azimuth_deg", "elevation_deg", "time_ns", "intensity", "channel",
              "return", "confidence", "block"],
    "formats": ["<f4"] * 6 + ["<i8"] + ["u1"] * 5,
    "offsets": [0, 4, 8, 12, 16, 20, 24, 32, 33, 34, 35, 36],
    "itemsize": 40,
})

_u8p = ctypes.c_void_p
lib.hesai_error_name.argtypes = [ctypes.c_int]
lib.hesai_error_name.restype = ctypes.c_char_p
lib.hesai_model_name.argtypes = [ctypes.c_int]
lib.hesai_model_name.restype = ctypes.c_char_p
lib.hesai_model_channels.argtypes = [ctypes.c_int]
lib.hesai_model_channels.restype = ctypes.c_size_t
lib.hesai_identify.argtypes = [_u8p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_uint8), ctypes.POINTER(ctypes.c_uint8)]
lib.hesai_identify.restype = ctypes.c_int
lib.hesai_decoder_init.argtypes = [_u8p, ctypes.c_int]
lib.hesai_decoder_init.restype = ctypes.c_int
for _name in ("hesai_decoder_set_angles_csv", "hesai_decoder_set_firetimes_csv", "hesai_decoder_set_channel_config_csv"):
    getattr(lib, _name).argtypes = [_u8p, ctypes.c_char_p, ctypes.c_size_t, _u8p, ctypes.POINTER(ctypes.c_uint32)]
    getattr(lib, _name).restype = ctypes.c_int
for _name in ("hesai_decoder_set_firetime_correction", "hesai_decoder_set_rotation", "hesai_decoder_set_reflectivity",
              "hesai_decoder_set_allow_unsigned"):
    getattr(lib, _name).argtypes = [_u8p, ctypes.c_int]
    getattr(lib, _name).restype = ctypes.c_int
lib.hesai_decoder_set_session_key.argtypes = [_u8p, ctypes.c_char_p]
lib.hesai_decoder_set_session_key.restype = ctypes.c_int
lib.hesai_decoder_update_gps.argtypes = [_u8p, ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_decoder_update_gps.restype = ctypes.c_int
lib.hesai_decoder_decode.argtypes = [_u8p, ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p,
                                     ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t)]
lib.hesai_decoder_decode.restype = ctypes.c_int


# ---- memory for results ------------------------------------------------------------------------

# numpy asks Linux for transparent huge pages under every array of 4 MiB or more
# (madvise(MADV_HUGEPAGE)). The first write to such a page makes the kernel clear 2 MiB at once; in
# a virtual machine whose free memory goes back to the host (Firecracker, balloon free page
# reporting) each of those pages is new to the host as well, and a capture's rows written into
# fresh huge pages cost 2 to 5 times the CPU time of the same rows in ordinary 4 KiB pages
# (docs/PERFORMANCE.md). The arrays the package fills (written once, front to back) ask for
# ordinary pages instead.
_HUGE = 1 << 22  # numpy's threshold
_MADV_NOHUGEPAGE = 15
_madvise = None
if sys.platform.startswith("linux"):
    try:
        _madvise = ctypes.CDLL(None, use_errno=True).madvise
        _madvise.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int]
        _madvise.restype = ctypes.c_int
    except (OSError, AttributeError):
        _madvise = None


def small_pages(a: np.ndarray) -> np.ndarray:
    """`a` (new, not yet written) on ordinary pages where the platform has the choice; returns it.
    A refusal changes nothing but the speed."""
    if _madvise is not None and a.nbytes >= _HUGE:
        start = (a.ctypes.data + mmap.PAGESIZE - 1) & ~(mmap.PAGESIZE - 1)
        end = (a.ctypes.data + a.nbytes) & ~(mmap.PAGESIZE - 1)
        if end > start:
            _madvise(start, end - start, _MADV_NOHUGEPAGE)
    return a


def empty(size: int, dtype) -> np.ndarray:
    """np.empty(size, dtype) on ordinary pages (small_pages)."""
    return small_pages(np.empty(size, dtype=dtype))


def error_name(code: int) -> str:
    return lib.hesai_error_name(code).decode()


def check_layout(library=None) -> None:
    """Compares ROW_DTYPE and POINT_DTYPE with the layouts the library was compiled with
    (hesai_capture_layout): the record size and each field's offset. Raises LayoutError naming
    every difference."""
    layout = (library or lib).hesai_capture_layout
    wrong = []
    for which, name, dtype in ((0, "hesai_capture_row", ROW_DTYPE), (1, "hesai_point", POINT_DTYPE)):
        size = layout(which, None)
        if size != dtype.itemsize:
            wrong.append(f"{name} is {size} bytes, the dtype {dtype.itemsize}")
        for field in dtype.names:
            offset = layout(which, field.encode())
            if offset != dtype.fields[field][1]:
                where = "absent" if offset == ctypes.c_size_t(-1).value else f"at {offset}"
                wrong.append(f"{name}.{field} is {where}, the dtype's at {dtype.fields[field][1]}")
    if wrong:
        raise LayoutError(f"hesai: {path} does not match this package ({'; '.join(wrong)}): "
                          "install the library and the package from the same version")


check_layout()
