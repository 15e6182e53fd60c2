"""Hesai lidar captures and packets decoded into numpy structured arrays.

A thin layer over libhesai_c (ctypes; numpy is the only other import):

    import hesai
    points = hesai.decode_file("data/pandar64_dual.pcap",
                               calibration="data/calibration/pandar64_unit_a_angles.csv")
    points["x"], points["frame"], ...          # the columns of `hesai decode --format csv`

    for frame in hesai.frames("capture.pcapng"):   # one array per frame of one sensor, as frames close
        ...

    rows, sensors = hesai.decode_file("two_units.pcap", return_sensors=True)
    rows[rows["sensor"] == 1]                   # the rows of sensors[1] ("192.168.1.202:2368", ...)
    for sensor, frame in hesai.frames("two_units.pcap", with_sensor=True):
        ...                                     # sensor: the name of the frame's sensor

    decoder = hesai.Decoder()                   # packets the caller already has (UDP payloads)
    pts = decoder.decode(payload)

    cols = hesai.decode_columns("capture.pcap")  # {"x": float32 array, ..., "time_ns": int64 array}
    counts = hesai.stats("capture.pcap")         # the dict `hesai stats --json` prints

decode_file and frames run the hesai program's own pipeline (capture reader, held packets until
each sensor's rotation is known, frame assembly): their rows are the CSV's, in its order. The
work is done in C++, a batch of rows per call; Python only joins the batches.

A capture may hold several sensors (each source: an address and port, or an MCAP topic). A row's
"sensor" field is its sensor's index, 0, 1, ... in the order they first sent a point-cloud packet;
the names (the CSV's sensor column: "192.168.1.201:2368", or the topic) come as a list with
return_sensors=True, so `np.array(sensors)[rows["sensor"]]` is the CSV's column. Frame ids count
per sensor: a frame is (sensor, frame).
"""

from __future__ import annotations

import ctypes
import json
import os
from typing import Any, Dict, Iterator, List, Optional, Tuple, Union

import numpy as np

from . import _lib
from ._version import __version__

__all__ = ["decode_file", "decode_columns", "ColumnBuffer", "frames", "stats", "Decoder", "HesaiError", "LayoutError", "ROW_DTYPE",
           "POINT_DTYPE", "COLUMNS", "library_path", "__version__"]

PathArg = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
"""A file name: str, bytes or os.PathLike (pathlib.Path, ...)."""

LayoutError = _lib.LayoutError

ROW_DTYPE = _lib.ROW_DTYPE
"""Fields of decode_file's rows, as the CSV's columns: frame, packet, block, channel, return,
azimuth_deg, elevation_deg, distance_m, x, y, z, intensity, time_ns, sensor (uint16: the index of
the sensor's name in the list return_sensors=True gives, where the CSV has the name)."""

POINT_DTYPE = _lib.POINT_DTYPE
"""Fields of Decoder.decode's points (the C interface's hesai_point): the CSV's columns without
frame and packet, and confidence (the QT128's per-point byte, 0 for other models)."""

library_path: str = _lib.path
"""The libhesai_c that was loaded."""

COLUMNS: Dict[str, np.dtype] = {"packet": np.dtype("<u8"), "channel": np.dtype("u1"), "return": np.dtype("u1"),
                                "x": np.dtype("<f4"), "y": np.dtype("<f4"), "z": np.dtype("<f4"),
                                "intensity": np.dtype("u1"), "time_ns": np.dtype("<i8"),
                                "sensor": np.dtype("<u2")}
"""decode_columns' keys (the CSV's column names, in its order) and each array's dtype (sensor: the
index of the sensor's name, as ROW_DTYPE's)."""

_BATCH = 1 << 16  # rows per call into the library (frames)
# Rows are moved as opaque records of ROW_DTYPE's size: numpy copies a structured dtype with holes
# field by field, ten times slower than these plain copies.
_RAW = np.dtype((np.void, ROW_DTYPE.itemsize))
_ROTATIONS = {"auto": -1, "cw": 0, "ccw": 1}
_REFLECTIVITY = {"raw": 0, "nonlinear": 1}
_RETURNS = {"all": 0, "distinct": 1}


class HesaiError(Exception):
    """A failure the hesai program would report: `status` is its exit status (1 a usage error such
    as a bad option value or calibration file, 2 an input error such as an unreadable or damaged
    capture); for Decoder, `code` is the hesai_error name ("crc_body", ...)."""

    def __init__(self, message: str, status: Optional[int] = None, code: Optional[str] = None,
                 stats: Optional[Dict[str, Any]] = None):
        super().__init__(message)
        self.status = status
        self.code = code
        self.stats = stats
        """For stats(): the counts up to the damage of a damaged capture (as the program prints them)."""
        self.columns: Optional[Dict[str, np.ndarray]] = None
        """For decode_columns(): the points before the damage of a damaged capture."""

    def __reduce__(self):  # pickled whole (a dask worker's failure reaches the client with its status)
        return (HesaiError, (str(self), self.status, self.code, self.stats))


def _path_bytes(p: Optional[PathArg]) -> Optional[bytes]:
    """The file name as the C library takes it (os.fsencode: str, bytes or os.PathLike; TypeError
    for anything else, ValueError for a NUL inside)."""
    if p is None:
        return None
    b = os.fsencode(p)
    if b"\0" in b:
        raise ValueError(f"a file name with a NUL byte: {p!r}")
    return b


def _options(calibration=None, firetimes=None, channel_config=None, rotation="auto", cut_angle=0.0, fov=None,
             packets=None, min_range=0.0, max_range=1e9, reflectivity="raw", firetime_azimuth=True, session_key=None,
             allow_unsigned=False, returns="all"):
    o = _lib.CaptureOptions()
    _lib.lib.hesai_capture_default_options(ctypes.byref(o))
    o.calibration = _path_bytes(calibration)
    o.firetimes = _path_bytes(firetimes)
    o.channel_config = _path_bytes(channel_config)
    if rotation not in _ROTATIONS:
        raise ValueError("rotation takes 'auto', 'cw' or 'ccw'")
    o.rotation = _ROTATIONS[rotation]
    if reflectivity not in _REFLECTIVITY:
        raise ValueError("reflectivity takes 'raw' or 'nonlinear'")
    o.reflectivity = _REFLECTIVITY[reflectivity]
    o.firetime_azimuth = 1 if firetime_azimuth else 0
    o.cut_angle_deg = cut_angle
    if fov is not None:
        o.has_fov = 1
        o.fov_start_deg, o.fov_end_deg = fov
    if packets is not None:
        o.first_packet, o.end_packet = packets
    o.min_range_m = min_range
    o.max_range_m = max_range
    keep = None
    if session_key is not None:
        if len(session_key) != 32:
            raise ValueError("session_key takes 32 bytes")
        keep = ctypes.create_string_buffer(bytes(session_key), 32)
        o.session_key = ctypes.cast(keep, ctypes.c_void_p)
    o.allow_unsigned = 1 if allow_unsigned else 0
    if returns not in _RETURNS:
        raise ValueError("returns takes 'all' or 'distinct'")
    o.returns = _RETURNS[returns]
    return o, keep


class _Capture:
    """An open capture in the library: batches of rows and the frames that closed."""

    _handle = None

    def __init__(self, path: PathArg, **kw: Any):
        self._options, self._key = _options(**kw)
        self._handle = ctypes.c_void_p()
        msg = ctypes.create_string_buffer(512)
        name = _path_bytes(path)
        st = _lib.lib.hesai_capture_open(name, ctypes.byref(self._options), ctypes.byref(self._handle),
                                         msg, len(msg))
        if st != 0:
            raise HesaiError(msg.value.decode(errors="replace"), status=st)
        self._count = ctypes.c_size_t()
        self._closed = ctypes.c_uint64()
        self._closed_sensor = ctypes.c_uint16()
        self._msg = msg
        self._names: List[str] = []
        self._buffer = None

    def __enter__(self) -> "_Capture":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def _fail(self, st: int) -> HesaiError:
        return HesaiError(self._msg.value.decode(errors="replace"), status=st)

    def bound(self) -> Tuple[int, int]:
        """(UDP datagrams, most rows) of the capture (hesai_capture_bound)."""
        datagrams, points = ctypes.c_uint64(), ctypes.c_uint64()
        st = _lib.lib.hesai_capture_bound(self._handle, ctypes.byref(datagrams), ctypes.byref(points), self._msg,
                                          len(self._msg))
        if st != 0:
            raise self._fail(st)
        return datagrams.value, points.value

    def read(self):
        """(rows as _RAW records, closed frame id or 0, its sensor); no rows and 0 at the end. A copy."""
        if self._buffer is None:
            self._buffer = np.empty(_BATCH, dtype=_RAW)
        st = _lib.lib.hesai_capture_read(self._handle, self._buffer.ctypes.data, len(self._buffer),
                                         ctypes.byref(self._count), ctypes.byref(self._closed),
                                         ctypes.byref(self._closed_sensor), self._msg, len(self._msg))
        if st != 0:
            raise self._fail(st)
        return self._buffer[:self._count.value].copy(), self._closed.value, self._closed_sensor.value

    def read_into(self, out, start, capacity) -> int:
        """Rows into out[start:start + capacity] (an array of _RAW records), without stopping where
        frames close: the rows written, 0 at the end."""
        st = _lib.lib.hesai_capture_read(self._handle, out.ctypes.data + start * out.itemsize, capacity,
                                         ctypes.byref(self._count), None, None, self._msg, len(self._msg))
        if st != 0:
            raise self._fail(st)
        return self._count.value

    def sensors(self) -> List[str]:
        """The names of the sensors known so far, by index (hesai_capture_sensor_name)."""
        for i in range(len(self._names), _lib.lib.hesai_capture_sensors(self._handle)):
            self._names.append(_lib.lib.hesai_capture_sensor_name(self._handle, i).decode(errors="replace"))
        return list(self._names)

    def read_columns(self, cols: Dict[str, np.ndarray], start: int) -> int:
        """Points into each cols[name][start:]: the number written, 0 at the end."""
        c = _lib.CaptureColumns()
        for name in ("x", "y", "z", "time_ns", "intensity", "channel", "packet", "sensor"):
            a = cols[name]
            setattr(c, name, a.ctypes.data + start * a.itemsize)
        c.return_index = cols["return"].ctypes.data + start
        c.capacity = len(cols["x"]) - start
        st = _lib.lib.hesai_capture_read_columns(self._handle, ctypes.byref(c), ctypes.byref(self._count), self._msg,
                                                 len(self._msg))
        if st != 0:
            raise self._fail(st)
        return self._count.value

    def stats_json(self) -> Dict[str, Any]:
        """hesai_capture_stats_json, parsed."""
        size = 1 << 16
        while True:
            buf = ctypes.create_string_buffer(size)
            st = _lib.lib.hesai_capture_stats_json(self._handle, buf, size, ctypes.byref(self._count), self._msg,
                                                   len(self._msg))
            if self._count.value < size:
                break
            size = self._count.value + 1  # cut: again, whole (the counts stay)
        counts = json.loads(buf.value.decode()) if self._count.value else None
        if st != 0:
            e = self._fail(st)
            e.stats = counts
            raise e
        return counts

    def packets(self):
        return _lib.lib.hesai_capture_packets(self._handle)

    def close(self):
        if self._handle:
            _lib.lib.hesai_capture_close(self._handle)
            self._handle = ctypes.c_void_p()

    def __del__(self):
        self.close()


_DOC_OPTIONS = """
    Options, as `hesai decode`'s (docs/CLI.md): calibration, firetimes, channel_config (paths of
    the CSV files); rotation ('auto', 'cw', 'ccw'); cut_angle (degrees); fov ((start, end) degrees);
    packets ((first, end) point-cloud packet indices); min_range, max_range (metres); reflectivity
    ('raw', 'nonlinear'); firetime_azimuth (False: --no-firetime-azimuth); session_key (32 bytes)
    and allow_unsigned; returns ('all', 'distinct': a repeated second return once). Raises HesaiError where the program fails."""


def decode_file(path: PathArg, calibration: Optional[PathArg] = None, firetimes: Optional[PathArg] = None,
                channel_config: Optional[PathArg] = None, *, rotation: str = "auto", cut_angle: float = 0.0,
                fov: Optional[Tuple[float, float]] = None, packets: Optional[Tuple[int, int]] = None,
                min_range: float = 0.0, max_range: float = 1e9, reflectivity: str = "raw",
                firetime_azimuth: bool = True, session_key: Optional[bytes] = None, allow_unsigned: bool = False,
                returns: str = "all",
                return_sensors: bool = False) -> Union[np.ndarray, Tuple[np.ndarray, List[str]]]:
    """Every point of a pcap, pcapng or MCAP capture: a structured array of ROW_DTYPE whose rows
    are those of `hesai decode CAPTURE --format csv`, in the same order. With return_sensors,
    (rows, sensors): sensors[i] is the name (the CSV's sensor column) of the rows whose "sensor" is
    i, so rows[rows["sensor"] == i] are that sensor's rows, in order."""
    with _Capture(path, calibration=calibration, firetimes=firetimes, channel_config=channel_config,
                  rotation=rotation, cut_angle=cut_angle, fov=fov, packets=packets, min_range=min_range,
                  max_range=max_range, reflectivity=reflectivity, firetime_azimuth=firetime_azimuth,
                  session_key=session_key, allow_unsigned=allow_unsigned, returns=returns) as cap:
        # Sized once, for the most rows the capture can give (each point-cloud packet's model's
        # points per packet), then trimmed: the library writes straight into the result. Pages
        # past the last row are never touched; the trim gives them back.
        out = _lib.empty(max(cap.bound()[1], 1), _RAW)
        n = 0
        while True:
            if n == len(out):  # the file grew since its bound: not expected
                out.resize(2 * len(out), refcheck=False)
                _lib.small_pages(out[n:])
            got = cap.read_into(out, n, len(out) - n)
            if got == 0:
                break
            n += got
        out.resize(n, refcheck=False)
        rows = out.view(ROW_DTYPE)
        return (rows, cap.sensors()) if return_sensors else rows


_BUFFER_MIN = 1 << 16  # points a ColumnBuffer holds at least


class ColumnBuffer:
    """Memory decode_columns fills again and again (its `buffer` argument): the arrays are made
    (or made twice as large, the points so far copied) only when a capture needs more room than
    they have, so a loop over many captures touches new memory a few times at most. The dict decode_columns returns is then views of it, valid
    until the buffer's next use."""

    def __init__(self) -> None:
        self.columns: Dict[str, np.ndarray] = {name: np.empty(0, dtype=dt) for name, dt in COLUMNS.items()}

    def room(self, size: int) -> Dict[str, np.ndarray]:
        if len(self.columns["x"]) < size:  # numpy's pages (huge ones, where it asks): touched once, reused
            self.columns = {name: np.empty(size, dtype=dt) for name, dt in COLUMNS.items()}
        return self.columns


def decode_columns(path: PathArg, calibration: Optional[PathArg] = None, firetimes: Optional[PathArg] = None,
                   channel_config: Optional[PathArg] = None, *, rotation: str = "auto",
                   packets: Optional[Tuple[int, int]] = None, reflectivity: str = "raw", firetime_azimuth: bool = True,
                   session_key: Optional[bytes] = None, allow_unsigned: bool = False,
                   buffer: Optional[ColumnBuffer] = None,
                   return_sensors: bool = False) -> Union[Dict[str, np.ndarray],
                                                          Tuple[Dict[str, np.ndarray], List[str]]]:
    """Every point of a capture as columns: {"packet", "channel", "return", "x", "y", "z",
    "intensity", "time_ns", "sensor"} (the CSV's column names; COLUMNS gives each dtype), element i
    of each the CSV's row i with the same options ("sensor": the index of the row's sensor; with
    return_sensors, (columns, sensors), sensors[i] the name of index i, as decode_file's). Filled in place by the core's columnar decode
    (hesai_capture_read_columns: the vector code the CPU has), without the program's frames or
    counters: no frame, block, angle or distance columns, and no cut_angle, fov, range or returns
    options (decode_file has them). Options as decode_file's; raises HesaiError where the program
    fails; for a capture damaged part-way its `columns` holds the points before the damage (the
    rows the program writes before it exits 2).

    Without `buffer` the arrays are new, sized once for the most points the capture can hold and
    trimmed. With a ColumnBuffer they are views of its arrays (overwritten by its next use), grown
    when a capture needs more: no pass to size them, no new memory to touch once the buffer is as
    large as the largest capture, the cheaper way through many captures."""
    with _Capture(path, calibration=calibration, firetimes=firetimes, channel_config=channel_config,
                  rotation=rotation, packets=packets, reflectivity=reflectivity, firetime_azimuth=firetime_azimuth,
                  session_key=session_key, allow_unsigned=allow_unsigned) as cap:
        # Room for the most points the capture can give, and the library's margin (it stops
        # COLUMNS_MIN points short of the end, where the next packets might not fit).
        if buffer is not None:
            # The buffer's room as it is (no pass over the capture to size it), grown below when
            # the capture needs more: a loop over many captures grows it a few times at most.
            cols = buffer.room(_BUFFER_MIN)
            size = len(cols["x"])
        else:
            size = cap.bound()[1] + _lib.COLUMNS_MIN
            cols = {name: _lib.empty(size, dt) for name, dt in COLUMNS.items()}
        n = 0

        def trimmed() -> Dict[str, np.ndarray]:
            if buffer is not None:
                return {name: a[:n] for name, a in cols.items()}
            for a in cols.values():
                a.resize(n, refcheck=False)
            return cols

        while True:
            if size - n < _lib.COLUMNS_MIN:  # a buffer too small, or a file grown since its bound
                size *= 2
                if buffer is not None:
                    old = cols
                    cols = buffer.room(size)
                    for name in cols:
                        cols[name][:n] = old[name][:n]
                else:
                    for name in cols:
                        cols[name].resize(size, refcheck=False)
                        _lib.small_pages(cols[name][n:])
            try:
                got = cap.read_columns(cols, n)
            except HesaiError as e:  # the points before the damage go with the error
                e.columns = trimmed()
                raise
            if got == 0:
                break
            n += got
        cols = trimmed()
        return (cols, cap.sensors()) if return_sensors else cols


def stats(path: PathArg, calibration: Optional[PathArg] = None, firetimes: Optional[PathArg] = None,
          channel_config: Optional[PathArg] = None, *, rotation: str = "auto", cut_angle: float = 0.0,
          fov: Optional[Tuple[float, float]] = None, packets: Optional[Tuple[int, int]] = None,
          min_range: float = 0.0, max_range: float = 1e9, reflectivity: str = "raw", firetime_azimuth: bool = True,
          session_key: Optional[bytes] = None, allow_unsigned: bool = False,
          returns: str = "all") -> Dict[str, Any]:
    """The counters of a capture: the dict `hesai stats CAPTURE --json` prints with the same
    options (the same keys and values: the program's own code, hesai_capture_stats_json). A
    capture damaged part-way raises HesaiError (status 2) whose `stats` holds the counts up to the
    damage."""
    with _Capture(path, calibration=calibration, firetimes=firetimes, channel_config=channel_config,
                  rotation=rotation, cut_angle=cut_angle, fov=fov, packets=packets, min_range=min_range,
                  max_range=max_range, reflectivity=reflectivity, firetime_azimuth=firetime_azimuth,
                  session_key=session_key, allow_unsigned=allow_unsigned, returns=returns) as cap:
        return cap.stats_json()


def frames(path: PathArg, calibration: Optional[PathArg] = None, firetimes: Optional[PathArg] = None,
           channel_config: Optional[PathArg] = None, *, rotation: str = "auto", cut_angle: float = 0.0,
           fov: Optional[Tuple[float, float]] = None, packets: Optional[Tuple[int, int]] = None,
           min_range: float = 0.0, max_range: float = 1e9, reflectivity: str = "raw", firetime_azimuth: bool = True,
           session_key: Optional[bytes] = None, allow_unsigned: bool = False,
           returns: str = "all",
           with_sensor: bool = False) -> Iterator[Union[np.ndarray, Tuple[str, np.ndarray]]]:
    """Yields one structured array of ROW_DTYPE per frame of one sensor, as each frame closes (each
    sensor's in id order), with its rows in the CSV's order; a frame that kept no point gives an
    empty array. Frames are cut per sensor, as `hesai stats` counts them: every row of a frame has
    the frame's "sensor" and "frame". With with_sensor, (sensor, frame) pairs: sensor is the name
    of the frame's sensor (the CSV's sensor column), given for an empty frame too. The frames'
    rows together are decode_file's rows, each frame's in their order (near a cut, or with several
    sensors, the CSV interleaves frames' rows). The capture is closed when the generator ends or is
    closed."""
    with _Capture(path, calibration=calibration, firetimes=firetimes, channel_config=channel_config,
                  rotation=rotation, cut_angle=cut_angle, fov=fov, packets=packets, min_range=min_range,
                  max_range=max_range, reflectivity=reflectivity, firetime_azimuth=firetime_azimuth,
                  session_key=session_key, allow_unsigned=allow_unsigned, returns=returns) as cap:
        names: List[str] = []

        def named(sensor: int, frame: np.ndarray) -> Union[np.ndarray, Tuple[str, np.ndarray]]:
            if not with_sensor:
                return frame
            if sensor >= len(names):
                names[:] = cap.sensors()
            return names[sensor], frame

        pending = []  # rows given whose frame has not closed yet
        while True:
            rows, closed, sensor = cap.read()
            if len(rows):
                pending.append(rows)
            if closed == 0:
                if len(rows) == 0:
                    break
                continue
            held = np.concatenate(pending) if len(pending) > 1 else (pending[0] if pending else
                                                                    np.empty(0, dtype=_RAW))
            view = held.view(ROW_DTYPE)
            mine = (view["frame"] == closed) & (view["sensor"] == sensor)
            yield named(sensor, held[mine].view(ROW_DTYPE))
            rest = held[~mine]
            pending = [rest] if len(rest) else []
        if pending:  # rows of frames that never closed (not expected: finish() closes them)
            held = np.concatenate(pending)
            view = held.view(ROW_DTYPE)
            keys = np.unique(view[["sensor", "frame"]])
            for key in keys:
                mine = (view["sensor"] == key["sensor"]) & (view["frame"] == key["frame"])
                yield named(int(key["sensor"]), held[mine].view(ROW_DTYPE))


decode_file.__doc__ += _DOC_OPTIONS
frames.__doc__ += _DOC_OPTIONS
stats.__doc__ += _DOC_OPTIONS


def _read_file(p: PathArg) -> bytes:
    """The bytes of a calibration file, the file closed before returning."""
    with open(os.fsdecode(p) if isinstance(p, bytes) else p, "rb") as f:
        return f.read()


class Decoder:
    """Decodes UDP payloads the caller already has, one packet per call, with the core's C
    interface (hesai_decoder_decode). The model is taken from the first point-cloud packet unless
    given ("Pandar64", ... as hesai_model_name says, or the hesai_model number). Calibration as
    decode_file's (paths); rotation 'cw' or 'ccw' (a Decoder has no rotation detector: set it from
    the unit's configuration). Pandar40 GPS packets set the time base and give no point."""

    def __init__(self, model: Union[str, int, None] = None, calibration: Optional[PathArg] = None,
                 firetimes: Optional[PathArg] = None, channel_config: Optional[PathArg] = None, *,
                 rotation: str = "cw", reflectivity: str = "raw", firetime_azimuth: bool = True,
                 session_key: Optional[bytes] = None, allow_unsigned: bool = False):
        if rotation not in ("cw", "ccw"):
            raise ValueError("a Decoder's rotation is 'cw' or 'ccw'")
        if reflectivity not in _REFLECTIVITY:
            raise ValueError("reflectivity takes 'raw' or 'nonlinear'")
        self._storage = np.zeros(_lib.DECODER_SIZE // 8, dtype=np.uint64)     # aligned for the decoder
        self._scratch = np.zeros(_lib.CALIBRATION_SCRATCH_SIZE // 8 + 1, dtype=np.uint64)
        self._points = np.empty(_lib.MAX_POINTS_PER_PACKET, dtype=POINT_DTYPE)
        self._raw = self._points.view(np.dtype((np.void, POINT_DTYPE.itemsize)))
        self._count = ctypes.c_size_t()
        self._files = [(name, None if p is None else _read_file(p))
                       for name, p in (("hesai_decoder_set_angles_csv", calibration),
                                       ("hesai_decoder_set_firetimes_csv", firetimes),
                                       ("hesai_decoder_set_channel_config_csv", channel_config))]
        self._settings = (_ROTATIONS[rotation], _REFLECTIVITY[reflectivity], 1 if firetime_azimuth else 0,
                          None if session_key is None else bytes(session_key), 1 if allow_unsigned else 0)
        self.model = None
        self._gps = None
        if model is not None:
            self._init(model)

    model: Optional[str]
    """The model's name ("QT128C2X", ...), once known."""

    def _check(self, code: int, what: str) -> None:
        if code != 0:
            name = _lib.error_name(code)
            raise HesaiError(f"{what}: {name}", code=name)

    def _init(self, model: Union[str, int]) -> None:
        if isinstance(model, str):
            names = {_lib.lib.hesai_model_name(m).decode(): m for m in range(1, 9)}
            if model not in names:
                raise ValueError(f"unknown model {model!r}; one of {', '.join(names)}")
            model = names[model]
        d = self._storage.ctypes.data
        self._check(_lib.lib.hesai_decoder_init(d, int(model)), "model")
        scratch = self._scratch.ctypes.data
        for name, text in self._files:
            if text is not None:
                line = ctypes.c_uint32()
                code = getattr(_lib.lib, name)(d, text, len(text), scratch, ctypes.byref(line))
                self._check(code, f"{name[len('hesai_decoder_set_'):]} line {line.value}")
        rotation, reflectivity, firetime, key, allow = self._settings
        self._check(_lib.lib.hesai_decoder_set_rotation(d, rotation), "rotation")
        if reflectivity:
            self._check(_lib.lib.hesai_decoder_set_reflectivity(d, reflectivity), "reflectivity")
        self._check(_lib.lib.hesai_decoder_set_firetime_correction(d, firetime), "firetime correction")
        if key is not None:
            self._check(_lib.lib.hesai_decoder_set_session_key(d, key), "session key")
        self._check(_lib.lib.hesai_decoder_set_allow_unsigned(d, allow), "allow unsigned")
        if self._gps is not None:
            self._check(_lib.lib.hesai_decoder_update_gps(d, self._gps, len(self._gps)), "gps")
        self.model = _lib.lib.hesai_model_name(int(model)).decode()

    def decode(self, payload: Union[bytes, bytearray, memoryview]) -> np.ndarray:
        """The points of one UDP payload (bytes-like): a structured array of POINT_DTYPE, in the
        order the CSV gives them. A GPS packet gives none. Raises HesaiError (code: the error's
        name) for a packet the decoder rejects."""
        payload = bytes(payload)
        model = ctypes.c_uint8()
        gps = ctypes.c_uint8()
        self._check(_lib.lib.hesai_identify(payload, len(payload), ctypes.byref(model), ctypes.byref(gps)), "packet")
        if gps.value:
            self._gps = payload  # the time base of the packets that follow
            if self.model is not None:
                self._check(_lib.lib.hesai_decoder_update_gps(self._storage.ctypes.data, payload, len(payload)), "gps")
            return np.empty(0, dtype=POINT_DTYPE)
        if self.model is None:
            self._init(model.value)
        code = _lib.lib.hesai_decoder_decode(self._storage.ctypes.data, payload, len(payload), None,
                                             self._points.ctypes.data, len(self._points), ctypes.byref(self._count))
        self._check(code, "packet")
        return self._raw[:self._count.value].copy().view(POINT_DTYPE)
