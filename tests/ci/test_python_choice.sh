#!/usr/bin/env bash
# ctest ci_python_choice: the Python package's interpreter (cmake/HesaiPython.cmake) with a
# python3 lacking numpy and pytest first on PATH. The fake is the build's own interpreter run with
# -I -S (no site directories: the standard library only), so find_package(Python3) takes it as
# Python3_EXECUTABLE. Each case configures tests/ci/python_choice (a project with no compiler):
# 1. the fallback has both: it is chosen, not the fake, and imports numpy and pytest;
# 2. no candidate has both: configuring stops, naming each interpreter tried and the fix;
# 3. -DHESAI_PYTHON naming the fake: configuring stops too (an explicit choice is not replaced);
# 4. -DHESAI_PYTHON naming one with both: chosen.
# Usage: test_python_choice.sh SOURCE_DIR WORK_DIR PYTHON_WITH_NUMPY_PYTEST
set -euo pipefail
src=${1:?usage: test_python_choice.sh SOURCE_DIR WORK_DIR PYTHON}
work=${2:?}
good=${3:?}
project=$src/tests/ci/python_choice
rm -rf "$work"
mkdir -p "$work/fake" "$work/fallback"
# python3 first on PATH: the good interpreter without its site directories.
printf '#!/bin/sh\nexec %s -I -S "$@"\n' "$good" >"$work/fake/python3"
# Another interpreter lacking both, for the fallback.
cp "$work/fake/python3" "$work/fallback/python3"
chmod 755 "$work/fake/python3" "$work/fallback/python3"
fake=$work/fake/python3
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# The setup itself: the good one imports both, the fake neither.
"$good" -c 'import numpy, pytest' || { echo "FAIL: $good does not import numpy and pytest"; exit 1; }
if "$fake" -c 'import numpy' 2>/dev/null || "$fake" -c 'import pytest' 2>/dev/null; then
  echo "FAIL: the fake python3 imports numpy or pytest: the test proves nothing"
  exit 1
fi

# configure NAME ARGS...: configures the project in $work/NAME with the fake first on PATH; sets
# status and out (stdout and stderr).
configure() {
  local name=$1
  shift
  status=0
  out=$(PATH="$work/fake:$PATH" cmake -S "$project" -B "$work/$name" "$@" 2>&1) || status=$?
}

# 1. The fake is Python3_EXECUTABLE; the fallback (the good one) is chosen.
configure fallback_has_both "-DHESAI_PYTHON_FALLBACK=$good"
if [ "$status" -ne 0 ]; then
  fail "1: configure failed (exit $status)"
  echo "$out" | sed 's/^/    /'
else
  { read -r found; read -r chosen; } <"$work/fallback_has_both/chosen.txt"
  [ "$found" = "$fake" ] || fail "1: find_package(Python3) found $found, not the fake first on PATH"
  [ "$chosen" = "$good" ] || fail "1: chose $chosen, expected $good"
  "$chosen" -c 'import numpy, pytest' || fail "1: the chosen $chosen does not import numpy and pytest"
  echo "ok 1: with $found first on PATH, $chosen was chosen"
fi

# 2. Neither candidate has both: configure stops with both named and the fix.
configure none_has_both "-DHESAI_PYTHON_FALLBACK=$work/fallback/python3"
if [ "$status" -eq 0 ]; then
  fail "2: configure succeeded without numpy and pytest"
else
  missing=""
  for m in "none of the interpreters tried imports both" "$fake: ModuleNotFoundError: No module named 'numpy'" \
    "$work/fallback/python3: ModuleNotFoundError: No module named 'numpy'" \
    "apt-get install python3-numpy python3-pytest" "-DHESAI_PYTHON="; do
    [[ $out == *"$m"* ]] || missing+=$'\n'"    $m"
  done
  if [ -n "$missing" ]; then
    fail "2: the message lacks:$missing"
    echo "$out" | sed 's/^/    /'
  else
    echo "ok 2: configure stopped (exit $status), naming both interpreters and the fix"
  fi
fi

# 3. HESAI_PYTHON naming the fake: stops, naming it.
configure explicit_fake "-DHESAI_PYTHON=$fake" "-DHESAI_PYTHON_FALLBACK=$good"
if [ "$status" -ne 0 ] && [[ $out == *"$fake: ModuleNotFoundError"* ]] && [[ $out != *"$good:"* ]]; then
  echo "ok 3: -DHESAI_PYTHON=$fake: configure stopped, naming it alone"
else
  fail "3: -DHESAI_PYTHON=$fake: exit $status"
  echo "$out" | sed 's/^/    /'
fi

# 4. HESAI_PYTHON naming the good one: chosen.
configure explicit_good "-DHESAI_PYTHON=$good" "-DHESAI_PYTHON_FALLBACK=$work/fallback/python3"
if [ "$status" -eq 0 ] && [ "$(sed -n 2p "$work/explicit_good/chosen.txt")" = "$good" ]; then
  echo "ok 4: -DHESAI_PYTHON=$good: chosen"
else
  fail "4: -DHESAI_PYTHON=$good: exit $status"
  echo "$out" | sed 's/^/    /'
fi

[ "$failures" -eq 0 ] && echo "ci_python_choice: all passed"
exit $((failures > 0))
