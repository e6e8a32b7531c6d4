#!/usr/bin/env bash
# scripts/npm-ci.sh DIR: the npm packages DIR/package-lock.json pins, installed into
# DIR/node_modules with `npm ci` (no install scripts), skipped while node_modules holds what
# that lock file names. The page's packages (web/) and the tests' reference readers use it.
set -euo pipefail
dir=$1
if ! cmp -s "$dir/package-lock.json" "$dir/node_modules/.telear-installed-lock"; then
  npm ci --prefix "$dir" --ignore-scripts --no-audit --no-fund
  cp "$dir/package-lock.json" "$dir/node_modules/.telear-installed-lock"
fi
