#!/usr/bin/env bash
# Builds the libFuzzer targets (the `fuzz` preset: clang, ASan + UBSan) and runs
# each for a bounded time from its committed seed corpus (tests/fuzz/corpus/).
# The fixed run (FUZZ_FIXED=1, below) uses the targets the `asan` preset
# builds beside the tests instead, so the test suite compiles the library
# once for both (docs/testing.md).
# Fails on any crash, sanitizer report, leak, timeout or out-of-memory;
# the input that caused it is left in build/<preset>/artifacts/<target>/ and
# its command to reproduce is printed. New interesting inputs go to
# build/<preset>/corpus/<target>/, never into the repository.
#
#   scripts/fuzz.sh                 every target, 60 s each
#   FUZZ_SECONDS=20 scripts/fuzz.sh scene_file   one target, 20 s
#   FUZZ_JOBS=1 scripts/fuzz.sh     one target at a time (default: one per core)
#   FUZZ_FIXED=1 scripts/fuzz.sh    the test suite's run (scripts/test.sh): a
#                                   fixed seed and a fixed number of inputs per
#                                   target (about a minute each here), from the
#                                   committed corpus only, without address
#                                   randomisation and without libFuzzer's
#                                   comparison hints, so the run is the same
#                                   on every run and every clone and cannot
#                                   turn red by chance
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${FUZZ_SECONDS:-60}"
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  # The longest fixed runs first, so that the two cores finish together.
  targets=(render_command image_loader scene_file mesh_loader gltf_scene)
fi

# The fuzz preset instruments the library for libFuzzer's comparison hints
# too, which the time-bounded runs use; the asan preset's coverage counters
# are all the fixed run needs, which does without the hints.
preset=fuzz
if [ -n "${FUZZ_FIXED:-}" ]; then preset=asan; fi
build="build/${preset}"
scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" --target "${targets[@]/#/fuzz_}"

# Debian's Assimp leaks inside itself on some malformed files (a PLY with a
# garbled element line): not our code, and not fixable from our wrapper.
# Every other leak still fails. intercept_tls_get_addr=0: the sanitizer
# runtime of clang 14 (and GCC 12) mistakes a heap block that happens to sit
# at a certain page offset for an old glibc's thread-local block header, and
# its leak checker's tracer then crashes at exit with "Tracer caught signal
# 11" after every test passed (docs/testing.md, "Sanitizer options").
sanitizerOptions=(
  ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:intercept_tls_get_addr=0"
  UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  LSAN_OPTIONS="suppressions=../../../../tests/fuzz/lsan-suppressions.txt"
)
# Inputs per target in the fixed run: 10-100 s each on the quiet 2-core machine
# (scene files: 2 200 inputs/s on a quiet machine, 270/s seen on a busy one;
# glTF scenes: 900/s seen on a busy one, so about 33 s there).
declare -A fixedRuns=([scene_file]=50000 [mesh_loader]=6000 [image_loader]=100000 [render_command]=20000
  [gltf_scene]=30000)
# One libFuzzer process is single-threaded: targets run side by side, one per
# core, each writing only its own log and directories.
runTarget() {
  local target="$1" work binary corpus artifacts log
  local -a budget launch
  # Each target runs inside its own working directory, build/<preset>/work/<target>,
  # where it keeps its scratch files (tests/fuzz/FuzzScratchDir.h); every path
  # below is relative to it.
  work="${build}/work/${target}"
  binary="../../tests/fuzz/fuzz_${target}"
  corpus="../../corpus/${target}"
  budget=(-max_total_time="$seconds" -timeout=10)
  launch=(env "${sanitizerOptions[@]}")
  if [ -n "${FUZZ_FIXED:-}" ]; then
    corpus="../../fixed-corpus/${target}"
    rm -rf "${build:?}/fixed-corpus/${target}"
    # A generous per-input timeout: the machine may be busy with other builds.
    # libFuzzer learns from the values the code compares (-use_cmp,
    # -use_memmem), pointers among them, whose values follow the environment,
    # the command line and the clone's path: the fixed run does without.
    # With that, the same environment, a relative command line and no address
    # randomisation, the same seed gives the same inputs on every run and in
    # every clone for scene_file, mesh_loader and gltf_scene (checked: two
    # copies at different paths, identical logs line for line).
    # render_command renders on up to two worker threads and image_loader
    # drifts too: their coverage, and so the inputs libFuzzer keeps, differ
    # by a few inputs from run to run; the count of inputs stays fixed.
    budget=(-runs="${fixedRuns[$target]}" -seed=1 -timeout=30 -use_cmp=0 -use_memmem=0)
    launch=(env -i PATH=/usr/bin:/bin "${sanitizerOptions[@]}" setarch "$(uname -m)" -R)
  fi
  # A target's dictionary of the names its format uses, if it has one.
  if [ -f "tests/fuzz/${target}.dict" ]; then budget+=(-dict="../../../../tests/fuzz/${target}.dict"); fi
  artifacts="../../artifacts/${target}/"
  log="${build}/logs/${target}.log"
  mkdir -p "$work" "${work}/${corpus}" "${work}/${artifacts}" "$(dirname "$log")"
  echo "fuzz: ${target}: ${budget[*]} (log ${log})"
  # -timeout: one input taking longer than 10 s is a finding (the CLI target
  # renders at most 12x12 pixels for 3 frames); -rss_limit_mb: so is 2 GiB.
  if ! (cd "$work" && "${launch[@]}" "$binary" "$corpus" "../../../../tests/fuzz/corpus/${target}" \
      "${budget[@]}" -rss_limit_mb=2048 -max_len=16384 \
      -artifact_prefix="$artifacts" -print_final_stats=1) >"$log" 2>&1; then
    tail -n 60 "$log"
    echo "fuzz: ${target} FAILED; the input is in ${build}/artifacts/${target}/;" \
      "reproduce with: ${build}/tests/fuzz/fuzz_${target} <that file>" >&2
    return 1
  fi
  # The last status line says how many inputs ran and how fast.
  grep -E '^#[0-9]+.*(DONE|pulse)' "$log" | tail -n 1 | sed "s/^/fuzz: ${target}: /"
}

# A target that fails leaves a mark, read once every target has ended.
sideBySide="${FUZZ_JOBS:-$(nproc)}"
mkdir -p "${build}/logs"
rm -f "${build}"/logs/*.failed
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$sideBySide" ]; do wait -n || true; done
  (runTarget "$target" || touch "${build}/logs/${target}.failed") &
done
wait
if compgen -G "${build}/logs/*.failed" >/dev/null; then
  echo "fuzz: failed: $(basename -s .failed "${build}"/logs/*.failed | tr '\n' ' ')" >&2
  exit 1
fi
