#!/usr/bin/env bash
# The main job on a fresh machine: install dependencies, build (release), then
# reproduce the documents' experiments at quick size (a few minutes on 2 cores):
# tables, plots, difference images and results/report.md.
# Extra arguments go to `raycache bench`: `scripts/run.sh --full` (the documents'
# sizes), `scripts/run.sh table-5.2 fill-rate` (some experiments only).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target raycache
if [ $# -eq 0 ] || [[ "$1" == -* ]]; then
  set -- all "$@"   # no experiment named: all of them, with the report
fi
exec build/release/apps/raycache/raycache bench "$@"
