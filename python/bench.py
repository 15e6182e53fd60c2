#!/usr/bin/env python3
"""What the Python package costs per packet, beside the C++ of the same capture, in one run.

    PYTHONPATH=python python3 python/bench.py [--repeat N] [--hesai PATH] [--bench PATH] [capture...]

For each capture (default: every data/*.pcap), its packets are repeated into a temporary pcap of
about --packets packets (so that process start-up is small beside the work), and the script times,
best of --runs, in nanoseconds per UDP packet:

  hesai stats        the program's pipeline in C++ (capture reader, decode, frames), no output
  hesai decode csv   the same writing the CSV to /dev/null
  decode_file        the package: the same pipeline, rows into numpy
  frames             the package, one array per frame
  Decoder            the package's Decoder, one Python call per packet (payloads already in memory)
  C++ columns        Google Benchmark BM_<model>_decode_columns (hesai_bench, bench preset): the
                     core's columnar decode of one packet, hot in cache; "-" when not built
"""

import argparse
import json
import os
import pathlib
import struct
import subprocess
import sys
import tempfile
import time

import hesai

ROOT = pathlib.Path(__file__).resolve().parents[1]
MODELS = {"pandar40p_dual": "Pandar40P", "pandar64_dual": "Pandar64", "pandar_qt64": "PandarQT64",
          "pandar_xt16": "PandarXT16", "pandar_xt32": "PandarXT32", "pandar_xt32m2x": "PandarXT32M2X",
          "qt128c2x_dual": "QT128C2X"}


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


def best(fn, runs):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def google_benchmark(bench, model):
    if not bench:
        return None
    r = subprocess.run([bench, f"--benchmark_filter=^BM_{model}_decode_columns$", "--benchmark_format=json",
                        "--benchmark_min_time=0.2"], capture_output=True, text=True)
    if r.returncode != 0:
        return None
    for b in json.loads(r.stdout)["benchmarks"]:
        if b["name"] == f"BM_{model}_decode_columns":
            scale = {"ns": 1, "us": 1e3, "ms": 1e6}[b["time_unit"]]
            return b["real_time"] * scale
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("captures", nargs="*")
    ap.add_argument("--packets", type=int, default=50000, help="packets per timed file (default 50000)")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--hesai", default=str(ROOT / "build" / "release" / "bin" / "hesai"))
    default_bench = ROOT / "build" / "bench" / "bin" / "hesai_bench"
    ap.add_argument("--bench", default=os.environ.get("HESAI_BENCH", str(default_bench) if default_bench.exists() else ""),
                    help="hesai_bench (Google Benchmark) for the C++ columns column")
    a = ap.parse_args()
    captures = a.captures or sorted(str(p) for p in (ROOT / "data").glob("*.pcap"))
    print(f"library {hesai.library_path}\nprogram {a.hesai}\nbenchmark {a.bench or '(not built: cmake --workflow --preset bench)'}")
    print(f"{'capture':<16}{'packets':>8}{'points':>10}  ns per packet: {'hesai stats':>11}{'decode csv':>11}"
          f"{'decode_file':>12}{'frames':>9}{'Decoder':>9}{'C++ columns':>12}")
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
            t_stats = best(lambda: run("stats", "--quiet"), a.runs)
            t_csv = best(lambda: run("decode", "--quiet"), a.runs)
            points = [0]

            def decode_file():
                points[0] = len(hesai.decode_file(big))
            t_file = best(decode_file, a.runs)
            t_frames = best(lambda: sum(len(f) for f in hesai.frames(big)), a.runs)
            pl = payloads(recs) * repeat

            def decoder():
                d = hesai.Decoder()
                for p in pl:
                    try:
                        d.decode(p)
                    except hesai.HesaiError:
                        pass
            t_dec = best(decoder, a.runs)
            gb = google_benchmark(a.bench, MODELS.get(name, ""))
            ns = lambda t: f"{t * 1e9 / n:.0f}"
            print(f"{name:<16}{n:>8}{points[0]:>10}  {'':>15}{ns(t_stats):>11}{ns(t_csv):>11}{ns(t_file):>12}"
                  f"{ns(t_frames):>9}{ns(t_dec):>9}{('-' if gb is None else f'{gb:.0f}'):>12}")


if __name__ == "__main__":
    sys.exit(main())
