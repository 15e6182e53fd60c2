#!/usr/bin/env bash
# Builds the fuzz preset (clang, libFuzzer + ASan + UBSan) and runs every harness for SECONDS
# (default 30) over a temporary copy of its committed corpus, with fuzz/hesai.dict, HESAI_JOBS
# (default 2) harnesses at a time.
# Fails on any crash, leak, timeout or invariant violation (the reproducer is saved in
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
# run_one HARNESS: one harness for SECONDS_EACH over its corpus copy; its report line (and on a
# failure the log's tail) to $WORK/HARNESS.out; exit status 1 on a failure.
run_one() {
  local h=$1 log="$WORK/$1.log" out="$WORK/$1.out"
  mkdir -p "$WORK/$h"
  cp -r fuzz/corpus/"$h"/. "$WORK/$h/"
  if "$BIN/fuzz_$h" "$WORK/$h" -dict=fuzz/hesai.dict -max_total_time="$SECONDS_EACH" \
       -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$ARTIFACTS/${h}-" >"$log" 2>&1; then
    local runs speed
    runs=$(grep -m1 '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    speed=$(grep -m1 '^stat::average_exec_per_sec' "$log" | awk '{print $2}')
    printf '%-20s ok   %12s runs %9s exec/s\n' "$h" "${runs:-?}" "${speed:-?}" >"$out"
    return 0
  fi
  { printf '%-20s FAIL (log below, reproducer in %s)\n' "$h" "$ARTIFACTS"; tail -40 "$log"; } >"$out"
  return 1
}

# A harness runs on one core: JOBS of them at a time (each still gets SECONDS_EACH of its own),
# their reports printed in the harnesses' order.
status=0
for ((i = 0; i < ${#HARNESSES[@]}; i += JOBS)); do
  batch=("${HARNESSES[@]:i:JOBS}")
  pids=()
  for h in "${batch[@]}"; do
    run_one "$h" &
    pids+=($!)
  done
  for j in "${!batch[@]}"; do
    wait "${pids[$j]}" || status=1
    cat "$WORK/${batch[$j]}.out" 2>/dev/null || printf '%-20s FAIL (no report: its corpus or binary is missing)\n' "${batch[$j]}"
  done
done
exit $status
