#!/usr/bin/env bash
# CI short mode: builds the bench preset, runs hesai_bench briefly (JSON to
# build/bench/bench.json) and prints bench/report.py's table, then a small end-to-end run of
# bench/e2e (HESAI_E2E_PACKETS packets, default 2400, 3 rounds: a few seconds; JSON to
# build/bench/e2e.json). Fails only if the build, the benchmark binary or a command e2e times
# fails; a missed target is reported, not fatal.
# Extra arguments go to hesai_bench (e.g. --benchmark_filter=QT128).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset bench >/dev/null
cmake --build --preset bench -j"${HESAI_JOBS:-2}"
OUT=build/bench/bench.json
build/bench/bin/hesai_bench --benchmark_min_time=0.05 --benchmark_out="$OUT" --benchmark_out_format=json "$@" >/dev/null
python3 bench/report.py "$OUT"
python3 bench/e2e --hesai build/bench/bin/hesai --packets "${HESAI_E2E_PACKETS:-2400}" --runs 3 --json build/bench/e2e.json
