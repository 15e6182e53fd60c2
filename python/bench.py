#!/usr/bin/env python3
"""What the Python package costs per packet, beside the C and C++ of the same capture, in one run.

    PYTHONPATH=python python3 python/bench.py [--packets N] [--runs N] [--hesai PATH] [--baseline PATH] [capture...]

For each capture (default: every data/*.pcap), its packets are repeated into a temporary pcap of
about --packets packets (so that start-up is small beside the work). Each measure runs --runs
times; the script prints, in nanoseconds of CPU time per UDP packet, the median and the worst
(largest) run. CPU time, not wall time: on a shared machine a run that loses the CPU for a while
would otherwise count another process's work (in-process measures: time.thread_time; the
programs: their rusage).

  hesai stats        the program's pipeline in C++ (capture reader, decode, frames), no output
  hesai decode csv   the same writing the CSV to /dev/null
  decode_file        the package: the same pipeline, rows into numpy (one array sized once)
  frames             the package, one array per frame
  Decoder            the package's Decoder, one Python call per packet (payloads already in memory),
                     each packet's points dropped at once (they stay in cache)
  Decoder kept       the same, each packet's points kept (a list of arrays): the capture's points in
                     memory at the end, as decode_file leaves them
  columns            decode_columns: the core's columnar decode of the capture into new arrays
  columns buf        decode_columns(buffer=ColumnBuffer()): into the same arrays each run
  C whole            hesai_columns_baseline (bench/columns_baseline.c, built with the release
                     preset): hesai_decoder_decode_columns of each packet, payloads in memory, into
                     columns of the whole capture made once, with the int64 time and packet index
                     written, i.e. the bytes decode_columns returns
  C hot              the same program, each packet into one packet's columns (output in cache: the
                     setting of Google Benchmark's BM_<model>_decode_columns)

and the ratios: columns buf / C whole, columns / C whole, columns buf / C hot (each of medians, and
of worst runs), decode_file / Decoder and decode_file / Decoder kept.
"""

import argparse
import json
import os
import pathlib
import resource
import statistics
import struct
import subprocess
import sys
import tempfile
import time

import hesai

ROOT = pathlib.Path(__file__).resolve().parents[1]
def records(path):
    """(global header, [record bytes]) of a classic pcap."""
    data = pathlib.Path(path).read_bytes()
    out, off = [], 24
    while off + 16 <= len(data):
        incl = struct.unpack_from("<I", data, off + 8)[0]
        out.append(data[off: off + 16 + incl])
        off += 16 + incl
    return data[:24], out


def payloads(recs):
    """UDP payloads of Ethernet/IPv4 records."""
    out = []
    for r in recs:
        f = r[16:]
        if struct.unpack_from(">H", f, 12)[0] != 0x0800 or f[23] != 17:
            continue
        udp = 14 + (f[14] & 0x0F) * 4
        out.append(f[udp + 8: udp + struct.unpack_from(">H", f, udp + 4)[0]])
    return out


def cpu(fn, runs, children=False):
    """(median, worst) CPU seconds of fn over `runs` runs: this thread's, or the finished child
    processes' (children=True)."""
    times = []
    for _ in range(runs):
        if children:
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            fn()
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            times.append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
        else:
            t = time.thread_time()
            fn()
            times.append(time.thread_time() - t)
    return statistics.median(times), max(times)


def baseline(program, capture, runs):
    """hesai_columns_baseline's (median, worst) ns per packet, hot and whole; None without it."""
    if not program or not os.path.exists(program):
        return None
    out = json.loads(subprocess.run([program, str(capture), str(runs)], check=True, capture_output=True,
                                    text=True).stdout)
    return {k: (statistics.median(out[k]), max(out[k])) for k in ("hot_ns", "whole_ns")}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("captures", nargs="*")
    ap.add_argument("--packets", type=int, default=50000, help="packets per timed file (default 50000)")
    ap.add_argument("--runs", type=int, default=5, help="runs of each measure (default 5)")
    ap.add_argument("--hesai", default=str(ROOT / "build" / "release" / "bin" / "hesai"))
    ap.add_argument("--baseline", default=str(ROOT / "build" / "release" / "bin" / "hesai_columns_baseline"),
                    help="hesai_columns_baseline (the C columns)")
    a = ap.parse_args()
    captures = a.captures or sorted(str(p) for p in (ROOT / "data").glob("*.pcap"))
    print(f"library {hesai.library_path}\nprogram {a.hesai}\nbaseline {a.baseline}\n"
          f"{a.runs} runs; ns of CPU time per packet, median/worst")
    names = ["hesai stats", "decode csv", "decode_file", "frames", "Decoder", "Decoder kept", "columns", "columns buf",
             "C whole", "C hot"]
    print(f"{'capture':<16}{'packets':>8}{'points':>10}  " + "".join(f"{n:>14}" for n in names))
    ratios = {"columns buf / C whole": [], "columns / C whole": [], "columns buf / C hot": [],
              "decode_file / Decoder": [], "decode_file / Decoder kept": []}
    buf = hesai.ColumnBuffer()
    with tempfile.TemporaryDirectory() as tmp:
        for cap in captures:
            name = pathlib.Path(cap).stem
            head, recs = records(cap)
            repeat = max(1, a.packets // max(1, len(recs)))
            big = pathlib.Path(tmp) / f"{name}.pcap"
            big.write_bytes(head + b"".join(recs) * repeat)
            n = len(recs) * repeat
            run = lambda *args: subprocess.run([a.hesai, *args, str(big)], check=True, stdout=subprocess.DEVNULL,
                                               stderr=subprocess.DEVNULL)
            t = {}
            t["hesai stats"] = cpu(lambda: run("stats", "--quiet"), a.runs, children=True)
            t["decode csv"] = cpu(lambda: run("decode", "--quiet"), a.runs, children=True)
            points = [0]

            def decode_file():
                points[0] = len(hesai.decode_file(big))
            t["decode_file"] = cpu(decode_file, a.runs)
            t["frames"] = cpu(lambda: sum(len(f) for f in hesai.frames(big)), a.runs)
            pl = payloads(recs) * repeat

            def decoder():
                d = hesai.Decoder()
                for p in pl:
                    try:
                        d.decode(p)
                    except hesai.HesaiError:
                        pass
            t["Decoder"] = cpu(decoder, a.runs)

            def decoder_kept():
                d = hesai.Decoder()
                kept = []
                for p in pl:
                    try:
                        kept.append(d.decode(p))
                    except hesai.HesaiError:
                        pass
                return kept
            t["Decoder kept"] = cpu(decoder_kept, a.runs)
            t["columns"] = cpu(lambda: hesai.decode_columns(big), a.runs)
            hesai.decode_columns(big, buffer=buf)  # its memory made (and touched) once, as C whole's
            t["columns buf"] = cpu(lambda: hesai.decode_columns(big, buffer=buf), a.runs)
            c = baseline(a.baseline, big, a.runs)
            cell = lambda k: "-" if k not in t else f"{t[k][0] * 1e9 / n:.0f}/{t[k][1] * 1e9 / n:.0f}"
            if c:
                t["C whole"] = tuple(v * n / 1e9 for v in c["whole_ns"])
                t["C hot"] = tuple(v * n / 1e9 for v in c["hot_ns"])
                ratios["columns buf / C whole"].append((name, t["columns buf"], t["C whole"]))
                ratios["columns / C whole"].append((name, t["columns"], t["C whole"]))
                ratios["columns buf / C hot"].append((name, t["columns buf"], t["C hot"]))
            ratios["decode_file / Decoder"].append((name, t["decode_file"], t["Decoder"]))
            ratios["decode_file / Decoder kept"].append((name, t["decode_file"], t["Decoder kept"]))
            print(f"{name:<16}{n:>8}{points[0]:>10}  " + "".join(f"{cell(k):>14}" for k in names), flush=True)
            del pl
    print("\nratios (median of runs; worst run against worst run), per capture, then their median and largest:")
    for label, rows in ratios.items():
        if not rows:
            continue
        med = [m[0] / b[0] for _, m, b in rows]
        worst = [m[1] / b[1] for _, m, b in rows]
        each = ", ".join(f"{name} {x:.2f}/{y:.2f}" for (name, _, _), x, y in zip(rows, med, worst))
        print(f"  {label:<24} median {statistics.median(med):.2f}, largest {max(med):.2f}; worst runs: median "
              f"{statistics.median(worst):.2f}, largest {max(worst):.2f}\n      {each}")


if __name__ == "__main__":
    sys.exit(main())
