#!/usr/bin/env bash
# CI short mode: builds the bench preset, runs hesai_bench briefly (JSON to
# build/bench/bench.json) and prints bench/report.py's table, then a small end-to-end run of
# bench/e2e (HESAI_E2E_PACKETS packets, default 2400, 3 rounds: a few seconds; JSON to
# build/bench/e2e.json). Fails only if the build, the benchmark binary or a command e2e times
# fails; a missed target is reported, not fatal.
# Extra arguments go to hesai_bench (e.g. --benchmark_filter=QT128).
# HESAI_BENCH_BUILD=DIR: a build tree of the release preset (the bench preset's flags, without its
# tests) that has built the core, the port and the program already, as .ci/run's: the benchmarks
# are added to it (HESAI_BUILD_BENCH=ON) and only they compile; the JSON goes to DIR too.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -n "${HESAI_BENCH_BUILD:-}" ]; then
  BUILD=$HESAI_BENCH_BUILD
  cmake -B "$BUILD" -DHESAI_BUILD_BENCH=ON >/dev/null
  cmake --build "$BUILD" -j"${HESAI_JOBS:-2}" --target hesai_bench hesai hesai_columns_decode
else
  BUILD=build/bench
  cmake --preset bench >/dev/null
  cmake --build --preset bench -j"${HESAI_JOBS:-2}"
fi
OUT=$BUILD/bench.json
"$BUILD/bin/hesai_bench" --benchmark_min_time=0.05 --benchmark_out="$OUT" --benchmark_out_format=json "$@" >/dev/null
python3 bench/report.py "$OUT"
python3 bench/e2e --hesai "$BUILD/bin/hesai" --packets "${HESAI_E2E_PACKETS:-2400}" --runs 3 --json "$BUILD/e2e.json"
