#!/usr/bin/env bash
# The main job on a fresh machine: install dependencies, build (release), then
# render the default built-in scene along its camera path. Extra arguments go
# to `raycache render` (e.g. --scene grid-32 --width 1024 --height 1024).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target raycache
mkdir -p out
exec build/release/apps/raycache/raycache render --scene room --out 'out/room_%04d.png' --stats out/room-stats.json "$@"
