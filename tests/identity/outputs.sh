#!/usr/bin/env bash
# Writes every output the program makes of every bundled capture into OUT_DIR, so that two builds
# can be compared byte for byte (`diff -r`): a refactoring or a speed-up must leave them identical.
#   bash tests/identity/outputs.sh build/release/bin/hesai /tmp/outputs-before
#   ... change, rebuild ...
#   bash tests/identity/outputs.sh build/release/bin/hesai /tmp/outputs-after
#   diff -r /tmp/outputs-before /tmp/outputs-after && echo identical
# For each capture (with its unit's calibration and firing times): CSV, PCD, PLY, MCAP, per-frame
# PCD, the stats JSON and text, and two more cut angles, a range and a field of view.
set -euo pipefail
hesai=$(realpath "$1")
mkdir -p "$2"
out=.  # the outputs by names relative to OUT_DIR, so that messages naming them compare equal
root=$(realpath "$(dirname "$0")/../..")
cd "$2"
cal=$root/data/calibration
run() {  # name, then the program's arguments: stdout and stderr to files, the exit status noted
  local name=$1
  shift
  set +e
  "$hesai" "$@" >"$out/$name.stdout" 2>"$out/$name.stderr"
  echo $? >"$out/$name.rc"
  set -e
}
for capture in "$root"/data/*.pcap; do
  base=$(basename "$capture" .pcap)
  case $base in
    pandar40p_dual) files=(--calibration $cal/pandar40p_unit_a_angles.csv --firetimes $cal/pandar40p_firetimes.csv) ;;
    pandar64_dual) files=(--calibration $cal/pandar64_unit_a_angles.csv --firetimes $cal/pandar64_firetimes.csv) ;;
    qt128c2x_dual) files=(--calibration $cal/qt128c2x_unit_a_angles.csv --firetimes $cal/qt128c2x_firetimes.csv
      --channel-config $cal/qt128c2x_channel_config.csv) ;;
    *) files=(--calibration "$cal/${base}_angles.csv" --firetimes "$cal/${base}_firetimes.csv") ;;
  esac
  for format in csv pcd ply mcap; do
    run "$base.decode.$format" decode "$capture" "${files[@]}" --format "$format" --out "$out/$base.$format"
  done
  mkdir -p "$out/$base.frames"
  run "$base.frames" decode "$capture" "${files[@]}" --format pcd --per-frame --out "$out/$base.frames"
  run "$base.stats.json" stats "$capture" "${files[@]}" --json
  run "$base.stats.text" stats "$capture" "${files[@]}"
  run "$base.cut" decode "$capture" "${files[@]}" --cut-angle 180.5 --min-range 1 --max-range 50 --out "$out/$base.cut.csv"
  run "$base.fov" stats "$capture" "${files[@]}" --cut-angle 90 --fov 300:30 --json
  run "$base.distinct" decode "$capture" "${files[@]}" --returns distinct --packets 10:200 --out "$out/$base.distinct.csv"
done
# Failures: their messages and exit statuses.
head -c 300000 "$root/data/pandar64_dual.pcap" >truncated.pcap
run error.truncated.stats stats truncated.pcap --json
run error.truncated.decode decode truncated.pcap --out truncated.csv
run error.missing_calibration decode "$root/data/pandar64_dual.pcap" --calibration missing.csv --out missing.csv
run error.bad_channel_config stats "$root/data/qt128c2x_dual.pcap" --channel-config "$cal/pandar64_unit_a_angles.csv"
run error.wrong_calibration stats "$root/data/qt128c2x_dual.pcap" --calibration "$cal/pandar64_unit_a_angles.csv"
run error.pcd_to_stdout decode "$root/data/pandar64_dual.pcap" --format pcd
run error.unwritable decode "$root/data/pandar64_dual.pcap" --out /proc/no/such.csv
run error.per_frame_mcap decode "$root/data/pandar64_dual.pcap" --format mcap --per-frame --out x
