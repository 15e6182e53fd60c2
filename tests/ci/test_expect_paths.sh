#!/usr/bin/env bash
# ctest ci_expect_paths: .ci/expect-paths over made-up cpuinfo files (tests/ci/cpuinfo/), each
# against the three lines written here by hand from the CPU's flags and the rules of .ci/run
# (AVX-512 needs F, BW, DQ and VL; VPCLMULQDQ counts only with AVX-512; PCLMULQDQ and SHA-NI need
# SSSE3 and SSE4.1; AArch64 is NEON, its PMULL and SHA-2 chosen at compile time: not checked).
# Runs under set -euo pipefail, as .ci/run does: a CPU without SHA-NI (the last test of the old
# function) must not end it.
# Usage: test_expect_paths.sh SOURCE_DIR
set -euo pipefail
src=${1:?usage: test_expect_paths.sh SOURCE_DIR}
script=$src/.ci/expect-paths
cpuinfo=$src/tests/ci/cpuinfo
failures=0

# expect FILE SIMD CRC32 SHA256: the script exits 0 and prints exactly these three lines.
expect() {
  local file=$1 want got status=0
  want=$(printf 'HESAI_EXPECT_SIMD=%s\nHESAI_EXPECT_CRC32=%s\nHESAI_EXPECT_SHA256=%s' "$2" "$3" "$4")
  got=$("$script" "$cpuinfo/$file") || status=$?
  if [ "$status" -eq 0 ] && [ "$got" = "$want" ]; then
    echo "ok: $file: $2 / ${3:-(not checked)} / ${4:-(not checked)}"
  else
    echo "FAIL: $file (exit $status)"
    echo "  expected:"; echo "$want" | sed 's/^/    /'
    echo "  got:"; echo "$got" | sed 's/^/    /'
    failures=$((failures + 1))
  fi
}

expect icelake_server.txt avx512 vpclmulqdq sha-ni      # everything
expect cascadelake.txt avx512 pclmulqdq portable        # AVX-512 without VPCLMULQDQ or SHA-NI
expect skylake_client.txt avx2 pclmulqdq portable       # AVX2, no AVX-512, no SHA-NI
expect zen3.txt avx2 pclmulqdq sha-ni                   # VPCLMULQDQ without AVX-512: 128-bit folding
expect no_pclmul.txt none slicing portable              # SSE4.1 only
expect aarch64_crypto.txt neon "" ""                    # pmull sha2 listed: compile-time, not checked
expect aarch64_plain.txt neon "" ""

# A file that cannot be read: exit 2 and a message naming it.
status=0
out=$("$script" "$cpuinfo/no-such-file.txt" 2>&1) || status=$?
if [ "$status" -eq 2 ] && [[ $out == *"cannot read $cpuinfo/no-such-file.txt"* ]]; then
  echo "ok: an unreadable file: exit 2, named"
else
  echo "FAIL: an unreadable file: exit $status, '$out'"
  failures=$((failures + 1))
fi

# A readable file with neither flags nor Features: the machine's arch (uname -m), three lines, exit 0.
empty=$(mktemp)
trap 'rm -f "$empty"' EXIT
status=0
out=$("$script" "$empty") || status=$?
if [ "$status" -eq 0 ] && [ "$(grep -c '^HESAI_EXPECT_\(SIMD\|CRC32\|SHA256\)=' <<<"$out")" -eq 3 ] &&
  [ "$(wc -l <<<"$out")" -eq 3 ]; then
  echo "ok: no flags line: three lines for $(uname -m)"
else
  echo "FAIL: no flags line: exit $status, '$out'"
  failures=$((failures + 1))
fi

[ "$failures" -eq 0 ] && echo "ci_expect_paths: all passed"
exit $((failures > 0))
