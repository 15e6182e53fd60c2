#!/usr/bin/env bash
# CI short mode: builds the bench preset, runs hesai_bench briefly (JSON to
# build/bench/bench.json) and prints bench/report.py's table. Fails only if the build or the
# benchmark binary fails; a missed target is reported, not fatal.
# Extra arguments go to hesai_bench (e.g. --benchmark_filter=QT128).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset bench >/dev/null
cmake --build --preset bench -j"${HESAI_JOBS:-2}"
OUT=build/bench/bench.json
build/bench/bin/hesai_bench --benchmark_min_time=0.05 --benchmark_out="$OUT" --benchmark_out_format=json "$@" >/dev/null
python3 bench/report.py "$OUT"
