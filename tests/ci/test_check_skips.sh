#!/usr/bin/env bash
# ctest ci_check_skips: .ci/check-skips on hand-made JUnit files (tests/ci/junit/, as ctest
# --output-junit writes them, and tests/ci/junit/gtest-xml/, as GoogleTest's --gtest_output=xml
# does) against hand-made allowlists (tests/ci/junit/allowlist*): the exit code and the names and
# GoogleTest messages it prints.
# Usage: test_check_skips.sh SOURCE_DIR [PYTHON]   (default python3)
set -euo pipefail
src=${1:?usage: test_check_skips.sh SOURCE_DIR [PYTHON]}
python=${2:-python3}
dir=$src/tests/ci/junit
failures=0

# expect STATUS JUNIT ALLOWLIST TEXT...: check-skips exits STATUS and its output holds every TEXT.
# Runs with HESAI_EXPECT_SHA256 as the caller's environment gives it.
expect() {
  local want=$1 junit=$2 allowlist=$3
  shift 3
  local out status=0 missing=""
  out=$("$python" "$src/.ci/check-skips" "$dir/$junit" demo "$dir/$allowlist" 2>&1) || status=$?
  for m in "$@"; do
    [[ $out == *"$m"* ]] || missing+=" '$m'"
  done
  if [ "$status" -eq "$want" ] && [ -z "$missing" ]; then
    echo "ok: $junit with $allowlist${HESAI_EXPECT_SHA256:+ (HESAI_EXPECT_SHA256=$HESAI_EXPECT_SHA256)}: exit $status"
  else
    echo "FAIL: $junit with $allowlist: exit $status (expected $want)${missing:+, lacks$missing}"
    echo "$out" | sed 's/^/    /'
    failures=$((failures + 1))
  fi
}

unset HESAI_EXPECT_SHA256
# One skip, allowed: 0, shown with GoogleTest's message and the allowlist's reason.
expect 0 allowed_skip.xml allowlist "check-skips demo: 3 tests, 1 skipped, 1 allowed" \
  "skipped, allowed: Udp.MulticastGroupOnLoopback: no network namespace of our own" \
  "allowlist:2: made up: this pretend preset has no multicast"
# An allowed skip and one the list does not name: 1, naming it and its message.
expect 1 unlisted_skip.xml allowlist "3 tests, 2 skipped, 1 allowed" \
  "1 skipped test(s) that" "  Tshark.SyntheticPcapngAgrees: tshark is not on PATH"
# A skip allowed only where the CPU has no SHA instructions (HESAI_EXPECT_SHA256=portable):
# (The name as gtest_discover_tests gives it, "...  # GetParam() = 1-byte object <01>", matched
# and printed without the comment.)
expect 1 sha_hardware_skip.xml allowlist "  Paths/Sha256Kat.Whole/hardware: no SHA instructions on this CPU"
HESAI_EXPECT_SHA256=sha-ni expect 1 sha_hardware_skip.xml allowlist "0 allowed"
HESAI_EXPECT_SHA256=portable expect 0 sha_hardware_skip.xml allowlist "1 skipped, 1 allowed"
# No skip, an allowlist of comments only: 0.
expect 0 no_skip.xml allowlist_empty "check-skips demo: 2 tests, 0 skipped, 0 allowed"
# A skip with an allowlist of comments only: 1.
expect 1 allowed_skip.xml allowlist_empty "  Udp.MulticastGroupOnLoopback: no network namespace of our own"
# An allowlist entry without its reason, a file that is not XML: 2.
expect 2 allowed_skip.xml allowlist_no_reason "allowlist_no_reason:2: no '# why'"
expect 2 allowlist allowlist "check-skips: $dir/allowlist:"
# Suites run as one ctest each ("Suite.*", under qemu-user: cmake/HesaiGtestSuites.cmake): their
# cases and skips come from GoogleTest's reports in gtest-xml/ beside the JUnit file (a skip, a
# parameterised case, a DISABLED_ case, a prefixed suite); each counts as a test.
unset HESAI_EXPECT_SHA256
expect 0 suites.xml allowlist_suites "check-skips demo: 7 tests, 3 skipped, 3 allowed" \
  "skipped, allowed: Udp.MulticastGroupOnLoopback: no network namespace of our own" \
  "skipped, allowed: Paths/Sha256Kat.Whole/hardware: no SHA instructions on this CPU" \
  "skipped, allowed: Paths/Sha256Kat.DISABLED_Slow/portable: disabled (not run)"
# The same skips against the allowlist without the suite's entries: 1, naming the cases.
expect 1 suites.xml allowlist "7 tests, 3 skipped, 1 allowed" "2 skipped test(s) that" \
  "  Paths/Sha256Kat.Whole/hardware: no SHA instructions on this CPU"
# A suite whose report is missing could hide a skip: 1, naming it.
expect 1 suites_missing_report.xml allowlist_suites "1 suite(s) without the report that would show their skips" \
  "  zero_allocation.Stats.*: no GoogleTest report of the suite"

[ "$failures" -eq 0 ] && echo "ci_check_skips: all passed"
exit $((failures > 0))
