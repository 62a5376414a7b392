#!/usr/bin/env bash
# The whole test suite on a fresh machine: install dependencies, then build and
# run every test twice, optimized (release) and under AddressSanitizer +
# UndefinedBehaviorSanitizer (asan); then the cache's concurrency test under
# ThreadSanitizer (tsan).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --workflow --preset release
cmake --workflow --preset asan
cmake --workflow --preset tsan
