#!/usr/bin/env python3
"""A fleet's recordings decoded on a dask.distributed cluster: one task per capture.

    PYTHONPATH=python python3 python/examples/fleet.py DIR [--scheduler ADDRESS] [--workers N] [--json]

Each task runs in a worker: hesai.stats(capture) (the dict `hesai stats --json` prints) and
hesai.decode_columns(capture) (the points, reduced here to a count and the height range: a real
job would write them out or run its own analysis next to the data). Only those small results
travel back; the client merges the counters (merge_stats) and prints them.

Without --scheduler the cluster is a LocalCluster of --workers workers in this process (threads:
the library releases the GIL while it decodes). With --scheduler tcp://HOST:8786 the same tasks go
to a running cluster (`dask scheduler` on one machine, `dask worker tcp://HOST:8786` on each of
the others, every worker with the hesai package installed and the captures at the same path, on a
shared file system): docs/LIBRARY.md, "Many captures, many machines".
"""

import argparse
import json
import pathlib
import sys
from typing import Any, Dict, Iterable, List

import hesai

# Counters of `stats --json` that are not counts, and so are not summed: the first and last packet
# times (min and max instead), the last fault seen, the azimuth FOV, the loss method (merged).
NOT_SUMMED = {"first_time_ns", "last_time_ns", "fs_last_fault_code", "fs_last_fault_id", "fs_last_fault_total",
              "fov_gap_deg", "lost_by", "sensors"}


def capture_task(path: str, **options: Any) -> Dict[str, Any]:
    """One capture, in a worker: its stats and a summary of its points."""
    counts = hesai.stats(path, **options)
    cols = hesai.decode_columns(path, **{k: v for k, v in options.items()
                                         if k not in ("cut_angle", "fov", "min_range", "max_range", "returns")})
    z = cols["z"]
    try:
        from distributed import get_worker
        worker = get_worker().address
    except (ImportError, ValueError):  # called outside a worker
        worker = None
    return {"path": path, "worker": worker, "stats": counts, "points": int(len(z)),
            "z_range_m": [float(z.min()), float(z.max())] if len(z) else None}


def merge_stats(all_counts: Iterable[Dict[str, Any]]) -> Dict[str, Any]:
    """The counters of several captures as one: counts summed (per model, per lidar state, per
    channel too), first_time_ns the earliest (of those with a time), last_time_ns the latest,
    lost_by "mixed" where the captures differ; the per-capture values that are no counts
    (NOT_SUMMED) are left out."""
    merged: Dict[str, Any] = {}
    lost_by = set()
    for counts in all_counts:
        for key, value in counts.items():
            if key == "lost_by":
                if value != "none":
                    lost_by.add(value)
            elif key == "first_time_ns":
                if value:
                    merged[key] = min(merged.get(key, value), value)
            elif key == "last_time_ns":
                merged[key] = max(merged.get(key, value), value)
            elif key in NOT_SUMMED:
                continue
            elif isinstance(value, dict):
                into = merged.setdefault(key, {})
                for k, v in value.items():
                    into[k] = into.get(k, 0) + v
            elif isinstance(value, list):
                into = merged.setdefault(key, [])
                into.extend([0] * (len(value) - len(into)))
                for i, v in enumerate(value):
                    into[i] += v
            else:
                merged[key] = merged.get(key, 0) + value
    merged["lost_by"] = "none" if not lost_by else lost_by.pop() if len(lost_by) == 1 else "mixed"
    return merged


def run(client, captures: List[str], timeout: float = None, **options: Any) -> Dict[str, Any]:
    """One task per capture on the client's cluster; the results in the captures' order. A task's
    exception (hesai.HesaiError for a damaged capture, ...) is raised here; `timeout` seconds
    without all results: distributed's TimeoutError."""
    from distributed import wait

    futures = client.map(capture_task, captures, pure=False, **options)
    wait(futures, timeout=timeout)
    results = client.gather(futures)
    return {"captures": results, "stats": merge_stats(r["stats"] for r in results)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("directory", help="a directory of captures (*.pcap, *.pcapng, *.mcap)")
    ap.add_argument("--scheduler", help="address of a running dask scheduler (default: a LocalCluster here)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    ap.add_argument("--json", action="store_true", help="print the result as one JSON object")
    a = ap.parse_args(argv)
    from dask.distributed import Client, LocalCluster  # Debian: python3-distributed

    captures = sorted(str(p) for p in pathlib.Path(a.directory).iterdir()
                      if p.suffix in (".pcap", ".pcapng", ".mcap"))
    if not captures:
        print(f"fleet: no captures in {a.directory}", file=sys.stderr)
        return 2
    if a.scheduler:
        with Client(a.scheduler) as client:
            client.upload_file(__file__)  # the workers import capture_task from this file
            result = run(client, captures)
    else:
        with LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            result = run(client, captures)
    if a.json:
        print(json.dumps(result))
    else:
        for r in result["captures"]:
            print(f"{r['path']}: {r['stats']['packets']} packets, {r['points']} points")
        s = result["stats"]
        print(f"all {len(captures)}: {s['packets']} packets, {s['points']} points, {s['frames']} frames, "
              f"{s['lost']} lost, {s['crc_errors']} CRC errors")
    return 0


if __name__ == "__main__":
    sys.exit(main())
