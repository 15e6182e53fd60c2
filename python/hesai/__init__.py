"""Hesai lidar captures and packets decoded into numpy structured arrays.

A thin layer over libhesai_c (ctypes; numpy is the only other import):

    import hesai
    points = hesai.decode_file("data/pandar64_dual.pcap",
                               calibration="data/calibration/pandar64_unit_a_angles.csv")
    points["x"], points["frame"], ...          # the columns of `hesai decode --format csv`

    for frame in hesai.frames("capture.pcapng"):   # one array per frame, in the order frames close
        ...

    decoder = hesai.Decoder()                   # packets the caller already has (UDP payloads)
    pts = decoder.decode(payload)

decode_file and frames run the hesai program's own pipeline (capture reader, held packets until
each sensor's rotation is known, frame assembly): their rows are the CSV's, in its order. The
work is done in C++, a batch of rows per call; Python only joins the batches.
"""

import ctypes

import numpy as np

from . import _lib

__all__ = ["decode_file", "frames", "Decoder", "HesaiError", "ROW_DTYPE", "POINT_DTYPE", "library_path"]

ROW_DTYPE = _lib.ROW_DTYPE
"""Fields of decode_file's rows, as the CSV's columns: frame, packet, block, channel, return,
azimuth_deg, elevation_deg, distance_m, x, y, z, intensity, time_ns."""

POINT_DTYPE = _lib.POINT_DTYPE
"""Fields of Decoder.decode's points (the C interface's hesai_point): the CSV's columns without
frame and packet, and confidence (the QT128's per-point byte, 0 for other models)."""

library_path = _lib.path
"""The libhesai_c that was loaded."""

_BATCH = 1 << 16  # rows per call into the library
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

    def __init__(self, message, status=None, code=None):
        super().__init__(message)
        self.status = status
        self.code = code


def _path_bytes(p):
    return None if p is None else str(p).encode()


def _options(calibration, firetimes, channel_config, rotation, cut_angle, fov, packets, min_range, max_range,
             reflectivity, firetime_azimuth, session_key, allow_unsigned, returns="all"):
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

    def __init__(self, path, **kw):
        self._options, self._key = _options(**kw)
        self._handle = ctypes.c_void_p()
        msg = ctypes.create_string_buffer(512)
        st = _lib.lib.hesai_capture_open(_path_bytes(path), ctypes.byref(self._options), ctypes.byref(self._handle),
                                         msg, len(msg))
        if st != 0:
            raise HesaiError(msg.value.decode(errors="replace"), status=st)
        self._buffer = np.empty(_BATCH, dtype=_RAW)
        self._count = ctypes.c_size_t()
        self._closed = ctypes.c_uint64()
        self._msg = msg

    def read(self):
        """(rows as _RAW records, closed frame id or 0); no rows and 0 at the end. A copy."""
        st = _lib.lib.hesai_capture_read(self._handle, self._buffer.ctypes.data, len(self._buffer),
                                         ctypes.byref(self._count), ctypes.byref(self._closed), self._msg,
                                         len(self._msg))
        if st != 0:
            raise HesaiError(self._msg.value.decode(errors="replace"), status=st)
        return self._buffer[:self._count.value].copy(), self._closed.value

    def read_into(self, out, start):
        """Rows into out[start:] (an array of _RAW records): (rows written, closed frame id or 0)."""
        st = _lib.lib.hesai_capture_read(self._handle, out.ctypes.data + start * out.itemsize,
                                         min(len(out) - start, _BATCH),
                                         ctypes.byref(self._count), ctypes.byref(self._closed), self._msg,
                                         len(self._msg))
        if st != 0:
            raise HesaiError(self._msg.value.decode(errors="replace"), status=st)
        return self._count.value, self._closed.value

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


def decode_file(path, calibration=None, firetimes=None, channel_config=None, *, rotation="auto", cut_angle=0.0,
                fov=None, packets=None, min_range=0.0, max_range=1e9, reflectivity="raw", firetime_azimuth=True,
                session_key=None, allow_unsigned=False, returns="all"):
    """Every point of a pcap or pcapng capture: a structured array of ROW_DTYPE whose rows are those
    of `hesai decode CAPTURE --format csv`, in the same order."""
    cap = _Capture(path, calibration=calibration, firetimes=firetimes, channel_config=channel_config,
                   rotation=rotation, cut_angle=cut_angle, fov=fov, packets=packets, min_range=min_range,
                   max_range=max_range, reflectivity=reflectivity, firetime_azimuth=firetime_azimuth,
                   session_key=session_key, allow_unsigned=allow_unsigned, returns=returns)
    try:
        # The library writes straight into the result, which grows in place (realloc: the pages
        # are remapped, not copied), so each row is written once.
        out = np.empty(_BATCH, dtype=_RAW)
        n = 0
        while True:
            if n == len(out):
                out.resize(2 * len(out), refcheck=False)
            got, closed = cap.read_into(out, n)
            if got == 0 and closed == 0:
                break
            n += got
        out.resize(n, refcheck=False)
        return out.view(ROW_DTYPE)
    finally:
        cap.close()


def frames(path, calibration=None, firetimes=None, channel_config=None, *, rotation="auto", cut_angle=0.0,
           fov=None, packets=None, min_range=0.0, max_range=1e9, reflectivity="raw", firetime_azimuth=True,
           session_key=None, allow_unsigned=False, returns="all"):
    """Yields one structured array of ROW_DTYPE per frame, as each frame closes (in id order), with
    its rows in the CSV's order; a frame that kept no point gives an empty array. The frames'
    rows together are decode_file's rows, each frame's in their order (near a cut the CSV
    interleaves two frames' rows)."""
    cap = _Capture(path, calibration=calibration, firetimes=firetimes, channel_config=channel_config,
                   rotation=rotation, cut_angle=cut_angle, fov=fov, packets=packets, min_range=min_range,
                   max_range=max_range, reflectivity=reflectivity, firetime_azimuth=firetime_azimuth,
                   session_key=session_key, allow_unsigned=allow_unsigned, returns=returns)
    try:
        pending = []  # rows given whose frame has not closed yet
        while True:
            rows, closed = cap.read()
            if len(rows):
                pending.append(rows)
            if closed == 0:
                if len(rows) == 0:
                    break
                continue
            held = np.concatenate(pending) if len(pending) > 1 else (pending[0] if pending else
                                                                    np.empty(0, dtype=_RAW))
            mine = held.view(ROW_DTYPE)["frame"] == closed
            yield held[mine].view(ROW_DTYPE)
            rest = held[~mine]
            pending = [rest] if len(rest) else []
        if pending:  # rows of frames that never closed (not expected: finish() closes them)
            held = np.concatenate(pending)
            ids = held.view(ROW_DTYPE)["frame"]
            for fid in np.unique(ids):
                yield held[ids == fid].view(ROW_DTYPE)
    finally:
        cap.close()


decode_file.__doc__ += _DOC_OPTIONS
frames.__doc__ += _DOC_OPTIONS


class Decoder:
    """Decodes UDP payloads the caller already has, one packet per call, with the core's C
    interface (hesai_decoder_decode). The model is taken from the first point-cloud packet unless
    given ("Pandar64", ... as hesai_model_name says, or the hesai_model number). Calibration as
    decode_file's (paths); rotation 'cw' or 'ccw' (a Decoder has no rotation detector: set it from
    the unit's configuration). Pandar40 GPS packets set the time base and give no point."""

    def __init__(self, model=None, calibration=None, firetimes=None, channel_config=None, *, rotation="cw",
                 reflectivity="raw", firetime_azimuth=True, session_key=None, allow_unsigned=False):
        if rotation not in ("cw", "ccw"):
            raise ValueError("a Decoder's rotation is 'cw' or 'ccw'")
        if reflectivity not in _REFLECTIVITY:
            raise ValueError("reflectivity takes 'raw' or 'nonlinear'")
        self._storage = np.zeros(_lib.DECODER_SIZE // 8, dtype=np.uint64)     # aligned for the decoder
        self._scratch = np.zeros(_lib.CALIBRATION_SCRATCH_SIZE // 8 + 1, dtype=np.uint64)
        self._points = np.empty(_lib.MAX_POINTS_PER_PACKET, dtype=POINT_DTYPE)
        self._raw = self._points.view(np.dtype((np.void, POINT_DTYPE.itemsize)))
        self._count = ctypes.c_size_t()
        self._files = [(name, None if p is None else open(p, "rb").read())
                       for name, p in (("hesai_decoder_set_angles_csv", calibration),
                                       ("hesai_decoder_set_firetimes_csv", firetimes),
                                       ("hesai_decoder_set_channel_config_csv", channel_config))]
        self._settings = (_ROTATIONS[rotation], _REFLECTIVITY[reflectivity], 1 if firetime_azimuth else 0,
                          None if session_key is None else bytes(session_key), 1 if allow_unsigned else 0)
        self.model = None
        self._gps = None
        if model is not None:
            self._init(model)

    def _check(self, code, what):
        if code != 0:
            name = _lib.error_name(code)
            raise HesaiError(f"{what}: {name}", code=name)

    def _init(self, model):
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

    def decode(self, payload):
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
