#!/usr/bin/env bash
# Builds the fuzz preset (clang, libFuzzer + ASan + UBSan) and runs every harness for SECONDS
# (default 30) over a temporary copy of its committed corpus, with fuzz/hesai.dict.
# Fails on the first crash, leak, timeout or invariant violation (the reproducer is saved in
# build/fuzz/artifacts/). The committed corpus is never modified.
# Usage: bash fuzz/run.sh [SECONDS] [HARNESS...]
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-30}
shift || true
HARNESSES=("$@")
if [ ${#HARNESSES[@]} -eq 0 ]; then
  # Every harness there is: fuzz/fuzz_<name>.cpp (a list here lost fuzz_qt64 in a merge).
  for f in fuzz/fuzz_*.cpp; do
    h=${f#fuzz/fuzz_}
    HARNESSES+=("${h%.cpp}")
  done
fi
JOBS=${HESAI_JOBS:-2}
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j"$JOBS"

BIN=build/fuzz/bin
ARTIFACTS=build/fuzz/artifacts
mkdir -p "$ARTIFACTS"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
status=0
for h in "${HARNESSES[@]}"; do
  mkdir -p "$WORK/$h"
  cp -r fuzz/corpus/"$h"/. "$WORK/$h/"
  log="$WORK/$h.log"
  if "$BIN/fuzz_$h" "$WORK/$h" -dict=fuzz/hesai.dict -max_total_time="$SECONDS_EACH" \
       -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$ARTIFACTS/${h}-" >"$log" 2>&1; then
    runs=$(grep -m1 '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    speed=$(grep -m1 '^stat::average_exec_per_sec' "$log" | awk '{print $2}')
    printf '%-20s ok   %12s runs %9s exec/s\n' "$h" "${runs:-?}" "${speed:-?}"
  else
    printf '%-20s FAIL (log below, reproducer in %s)\n' "$h" "$ARTIFACTS"
    tail -40 "$log"
    status=1
  fi
done
exit $status
