#!/usr/bin/env bash
# The whole test suite on a fresh machine: install dependencies, then build and
# run every test twice, optimized (release) and under AddressSanitizer +
# UndefinedBehaviorSanitizer (asan); then the cache's concurrency test under
# ThreadSanitizer (tsan); then the fuzzers' fixed run. Each step prints its
# wall time (docs/testing.md: where the time goes).
set -euo pipefail
cd "$(dirname "$0")/.."

# ctest runs test processes side by side, one per core; tests that must run
# alone (MPI jobs) say so with RUN_SERIAL, and the Xvfb ones take turns.
export CTEST_PARALLEL_LEVEL="${CTEST_PARALLEL_LEVEL:-$(nproc)}"

timed() {
  local start=$SECONDS
  "$@"
  echo "test.sh: '$*' took $(((SECONDS - start) / 60))m$(((SECONDS - start) % 60))s"
}

timed scripts/install-deps.sh
timed cmake --workflow --preset release
timed cmake --workflow --preset asan
timed cmake --workflow --preset tsan
# Fuzzing, the test suite's fixed run: a fixed seed and input count per target
# from the committed corpus, so it is the same run on every machine.
FUZZ_FIXED=1 timed scripts/fuzz.sh
echo "test.sh: all passed in $((SECONDS / 60))m$((SECONDS % 60))s"
