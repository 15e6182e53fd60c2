"""decode_columns as a mode of the engine (hesai_capture_read_columns runs the Pipeline in its
columns mode): the packets every sensor still holds at the end of a capture, released at once,
reach the caller over as many calls as they need, in the order of the rows; the engine's counters
count the packets it is fed.

Expected values come from the capture's bytes (its records, counted here) and from decode_file's
rows (the Pipeline's points mode, equal to the program's CSV by test_package.py), never from the
columns path.
"""

import struct

import numpy as np

import hesai
from hesai import _lib
from test_package import DATA
from test_sensors import pcap_records, resend_from

SENDERS = 40  # each sends two QT128C2X packets, too few for its direction to be decided


def many_senders(path):
    """SENDERS senders (192.168.1.10 ... :2368) of the capture's first two packets each, then the
    whole capture from its own sender. A dual-return QT128C2X's direction shows only in its third
    packet: each of the first senders holds both packets to the end."""
    _, recs = pcap_records(DATA / "qt128c2x_dual.pcap")
    frames = []
    for s in range(SENDERS):
        for k in range(2):
            f = bytearray(recs[k])
            resend_from(f, 10 + s, 2368)
            frames.append(f)
    frames += recs
    out = bytearray(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
    for i, f in enumerate(frames):
        out += struct.pack("<IIII", 1700000000, i * 100, len(f), len(f)) + f
    path.write_bytes(bytes(out))
    return path, len(frames)


def read_in_small_calls(path):
    """The columns read in calls of HESAI_CAPTURE_COLUMNS_MIN points: (columns, the calls' counts,
    the packets the engine counted)."""
    parts, counts = {name: [] for name in hesai.COLUMNS}, []
    with hesai._Capture(path) as cap:
        while True:
            cols = {name: np.empty(_lib.COLUMNS_MIN, dtype=dt) for name, dt in hesai.COLUMNS.items()}
            got = cap.read_columns(cols, 0)
            if got == 0:
                break
            counts.append(got)
            for name in parts:
                parts[name].append(cols[name][:got].copy())
        packets = cap.packets()
    return {name: np.concatenate(p) for name, p in parts.items()}, counts, packets


def test_held_packets_at_the_end_span_several_calls(tmp_path):
    capture, records = many_senders(tmp_path / "many.pcap")
    rows = hesai.decode_file(capture)
    held = int(np.count_nonzero(rows["sensor"] < SENDERS))  # the first senders' rows: released at the end
    assert held > 2 * _lib.COLUMNS_MIN  # more than a call holds
    cols, counts, packets = read_in_small_calls(capture)
    assert all(0 < n <= _lib.COLUMNS_MIN for n in counts)
    assert len(cols["x"]) == len(rows)
    for name in hesai.COLUMNS:
        np.testing.assert_array_equal(cols[name], rows[name], err_msg=name)
    # The engine counted every datagram it was fed (each record is one).
    assert packets == records
