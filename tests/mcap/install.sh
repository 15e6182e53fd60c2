#!/usr/bin/env bash
# Installs the reference MCAP reader (npm's @mcap/core, pinned) into DIR/node_modules for
# tests/mcap/read.mjs. Usage: tests/mcap/install.sh DIR   (the build tree: build/<preset>)
# Needs node and npm (Debian: nodejs, npm) and the npm registry. Fails loudly without them:
# the MCAP proof must not pass by skipping.
set -euo pipefail
dir=${1:?usage: install.sh DIR}
version=2.2.2
if [ -f "$dir/node_modules/@mcap/core/package.json" ] &&
   grep -q "\"version\": \"$version\"" "$dir/node_modules/@mcap/core/package.json"; then
  exit 0
fi
command -v node >/dev/null || { echo "install.sh: node not found (Debian: apt-get install nodejs npm)" >&2; exit 1; }
command -v npm >/dev/null || { echo "install.sh: npm not found (Debian: apt-get install npm)" >&2; exit 1; }
mkdir -p "$dir"
if ! npm install --prefix "$dir" --no-audit --no-fund --no-save "@mcap/core@$version" >&2; then
  echo "install.sh: 'npm install @mcap/core@$version' failed (no network or registry?): the MCAP reader test cannot run" >&2
  exit 1
fi
