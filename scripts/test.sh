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
# Fuzzing, the test suite's fixed run: a fixed seed and input count per target
# from the committed corpus, so it is the same run on every machine.
FUZZ_FIXED=1 scripts/fuzz.sh
