"""libhesai_c through ctypes: where it is found, and the C declarations the package calls.

The library is looked for, in order: at the path in the environment variable HESAI_LIBRARY; where
`cmake --install` recorded it (hesai/_installed.py); in the checkout's build trees
(build/release/lib, then any build/*/lib); by the system's loader (ctypes.util.find_library).
"""

import ctypes
import ctypes.util
import os
import pathlib

import numpy as np

_NAMES = ("libhesai_c.so", "libhesai_c.so.0", "libhesai_c.dylib")


def _candidates():
    env = os.environ.get("HESAI_LIBRARY")
    if env:
        yield env
        return
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


# hesai_capture_row: the C struct's layout, fields named and ordered as the CSV's columns.
ROW_DTYPE = np.dtype({
    "names": ["frame", "packet", "block", "channel", "return", "azimuth_deg", "elevation_deg", "distance_m",
              "x", "y", "z", "intensity", "time_ns"],
    "formats": ["<u8", "<u8", "u1", "u1", "u1", "<f4", "<f4", "<f4", "<f4", "<f4", "<f4", "u1", "<i8"],
    "offsets": [0, 8, 48, 49, 50, 24, 28, 32, 36, 40, 44, 51, 16],
    "itemsize": 56,
})

lib.hesai_capture_default_options.argtypes = [ctypes.POINTER(CaptureOptions)]
lib.hesai_capture_default_options.restype = None
lib.hesai_capture_open.argtypes = [ctypes.c_char_p, ctypes.POINTER(CaptureOptions), ctypes.POINTER(ctypes.c_void_p),
                                   ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_capture_open.restype = ctypes.c_int
lib.hesai_capture_read.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t),
                                   ctypes.POINTER(ctypes.c_uint64), ctypes.c_char_p, ctypes.c_size_t]
lib.hesai_capture_read.restype = ctypes.c_int
lib.hesai_capture_packets.argtypes = [ctypes.c_void_p]
lib.hesai_capture_packets.restype = ctypes.c_uint64
lib.hesai_capture_close.argtypes = [ctypes.c_void_p]
lib.hesai_capture_close.restype = None

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


def error_name(code):
    return lib.hesai_error_name(code).decode()
