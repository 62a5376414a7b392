#!/usr/bin/env bash
# MPI cluster mode end to end (docs/cluster.md), on localhost:
#   mpi_render_test.sh <raycache> <mpiexec> identical <processes> <technique|cct-levels|cct-view|cct-fill> [<tile-balance> [<threads>]]
#       the image of `mpiexec -np N raycache render` equals the single-process
#       one bit for bit (orbit path, 3 frames, so later frames read the caches
#       the earlier ones filled on every process)
#   mpi_render_test.sh <raycache> <mpiexec> animated <processes>
#       the same for animated scenes with CCT: texels dropped by each change
#       (their ray-tree records travel with the stores) alike on every process
#   mpi_render_test.sh <raycache> <mpiexec> whole-frames <processes>
#       caches off, several frames: every frame's image equals the single-process one
#   mpi_render_test.sh <raycache> <mpiexec> bench <processes>
#       `raycache bench all --tiny` over N processes writes the same files
#       as one process, and its report names the processes
#   mpi_render_test.sh <raycache> <mpiexec> load-failure
#       one process cannot load its scene: one error line naming it, exit 2, no image
#   mpi_render_test.sh <raycache> <mpiexec> dead-process
#       a process killed mid-job ends the job (non-zero exit, no hang, no image)
set -uo pipefail
raycache=$1
mpiexec=$2
case_name=$3
shift 3
scratch=$(mktemp -d)
# Open MPI 4's launchers race to create one shared session directory
# (/tmp/ompi.<host>.<uid>) when ctest starts two at once ("mkdir ... File
# exists", orte_init failed): each test gets its own.
sessions=$(mktemp -d)
trap 'rm -rf "$scratch" "$sessions"' EXIT
export OMPI_MCA_orte_tmpdir_base=$sessions
mpi=("$mpiexec" --oversubscribe)
fail() { echo "FAIL: $*"; exit 1; }
# Small and quick; 2 threads per process would only oversubscribe the machine more.
size=(--width 80 --height 48)
common=("${size[@]}" --cache-res 32)

case "$case_name" in
identical)
  processes=$1
  technique=$2
  balance=${3:-dynamic}
  threads=${4:-1}
  # cct-levels: CCT with multi-resolution cubes, whose coarse answers depend on
  # the exchanged stores' seen points too.
  technique_args=(--technique "$technique")
  [ "$technique" = cct-levels ] && technique_args=(--technique cct --cache-levels 4 --cache-level-error 1)
  # cct-view: CCT cubes resized after every frame from the lookups of all
  # processes (from 128², finer than these images need).
  [ "$technique" = cct-view ] && technique_args=(--technique cct --cache-res-from-view)
  # cct-fill: CCT cubes also filled from the surfaces each tile sees.
  [ "$technique" = cct-fill ] && technique_args=(--technique cct --cache-fill exact)
  resolution=(--cache-res 32)
  [ "$technique" = cct-view ] && resolution=(--cache-res 128)
  for scene in room glass; do
    args=(render --scene "$scene" "${size[@]}" "${resolution[@]}" --frames 3 --path orbit "${technique_args[@]}")
    "$raycache" "${args[@]}" --threads 2 --out "$scratch/one-$scene.exr" >"$scratch/one.log" 2>&1 ||
      { cat "$scratch/one.log"; fail "single-process render of $scene"; }
    "${mpi[@]}" -np "$processes" "$raycache" "${args[@]}" --threads "$threads" --tile-balance "$balance" \
      --out "$scratch/many-$scene.exr" --stats "$scratch/many-$scene.json" >"$scratch/many.log" 2>&1 ||
      { cat "$scratch/many.log"; fail "$processes-process render of $scene"; }
    cat "$scratch/many.log"
    cmp "$scratch/one-$scene.exr" "$scratch/many-$scene.exr" ||
      fail "$scene, $technique: $processes processes give another image than one"
    grep -q "\"processes\": $processes" "$scratch/many-$scene.json" || fail "statistics do not name $processes processes"
    [ "$(grep -c '^frame ' "$scratch/many.log")" = 3 ] || fail "expected 3 frame lines from process 0 only"
    if [ "$technique" != none ]; then
      grep -q '"store_bytes": [1-9]' "$scratch/many-$scene.json" || fail "no cache stores exchanged"
    fi
    if [ "$technique" = cct-view ]; then
      grep -q '"resized_to": [1-9]' "$scratch/many-$scene.json" || fail "no cube was resized"
    fi
  done
  ;;
animated)
  processes=$1
  for scene in orbit room-moving; do
    args=(render --scene "$scene" "${common[@]}" --frames 4 --technique cct)
    "$raycache" "${args[@]}" --threads 2 --out "$scratch/one-${scene}_%04d.exr" >"$scratch/one.log" 2>&1 ||
      { cat "$scratch/one.log"; fail "single-process render of $scene"; }
    "${mpi[@]}" -np "$processes" "$raycache" "${args[@]}" --threads 1 --out "$scratch/many-${scene}_%04d.exr" \
      >"$scratch/many.log" 2>&1 || { cat "$scratch/many.log"; fail "$processes-process render of $scene"; }
    cat "$scratch/many.log"
    grep -q "texels invalidated" "$scratch/many.log" || fail "$scene: no scene update reported"
    for f in 0001 0002 0003 0004; do
      cmp "$scratch/one-${scene}_$f.exr" "$scratch/many-${scene}_$f.exr" ||
        fail "$scene frame $f: $processes processes give another image than one"
    done
  done
  ;;
whole-frames)
  processes=$1
  args=(render --scene room "${common[@]}" --frames 4 --path orbit --technique none)
  "$raycache" "${args[@]}" --out "$scratch/one_%04d.exr" >"$scratch/one.log" 2>&1 || { cat "$scratch/one.log"; fail "single"; }
  "${mpi[@]}" -np "$processes" "$raycache" "${args[@]}" --out "$scratch/many_%04d.exr" >"$scratch/many.log" 2>&1 ||
    { cat "$scratch/many.log"; fail "$processes-process render"; }
  cat "$scratch/many.log"
  grep -q "whole frames per process" "$scratch/many.log" || fail "caches off and 4 frames should spread whole frames"
  for f in 0001 0002 0003 0004; do
    cmp "$scratch/one_$f.exr" "$scratch/many_$f.exr" || fail "frame $f differs"
  done
  ;;
bench)
  processes=$1
  args=(bench all --tiny)
  # Only the files' names are compared: the single process may use both cores.
  "$raycache" "${args[@]}" --threads 2 --out "$scratch/one" >"$scratch/one.log" 2>&1 || { cat "$scratch/one.log"; fail "single"; }
  "${mpi[@]}" -np "$processes" "$raycache" "${args[@]}" --threads 1 --out "$scratch/many" >"$scratch/many.log" 2>&1 ||
    { cat "$scratch/many.log"; fail "$processes-process bench"; }
  cat "$scratch/many.log"
  (cd "$scratch/one" && find . -type f | sort) >"$scratch/one.files"
  (cd "$scratch/many" && find . -type f | sort) >"$scratch/many.files"
  diff "$scratch/one.files" "$scratch/many.files" || fail "$processes processes wrote other files than one"
  grep -q "$processes MPI processes, each experiment run whole on one" "$scratch/many/report.md" ||
    fail "the report does not say which process ran what"
  grep -q "(process 1)" "$scratch/many.log" || fail "process 1 ran no experiment"
  [ "$(grep -c '^raycache bench:' "$scratch/many.log")" = 1 ] || fail "expected one header line, from process 0 only"
  ;;
load-failure)
  # MPMD: process 0 gets a good scene, processes 1 and 2 one that does not exist.
  "${mpi[@]}" -np 1 "$raycache" render --scene room "${common[@]}" --frames 2 --out "$scratch/out.png" : \
    -np 2 "$raycache" render --scene "$scratch/missing.json" "${common[@]}" --frames 2 --out "$scratch/out.png" \
    >"$scratch/out.log" 2>"$scratch/err.log"
  code=$?
  cat "$scratch/err.log"
  [ "$code" = 2 ] || fail "exit code $code, expected 2"
  [ "$(grep -c '^error: ' "$scratch/err.log")" = 1 ] || fail "expected exactly one error line"
  grep -q "^error: process 1 of 3: .*missing.json: scene file not found" "$scratch/err.log" || fail "error line"
  [ ! -s "$scratch/out.log" ] || fail "nothing should be printed to stdout"
  [ -z "$(ls "$scratch" | grep -v '\.log$')" ] || fail "files left behind: $(ls "$scratch")"
  ;;
dead-process)
  "${mpi[@]}" -np 3 "$raycache" render --scene room "${common[@]}" --frames 1000000 --technique cct \
    --out "$scratch/out.png" >"$scratch/out.log" 2>&1 &
  launcher=$!
  for _ in $(seq 1 300); do grep -q '^frame ' "$scratch/out.log" && break; sleep 0.1; done
  grep -q '^frame ' "$scratch/out.log" || { kill "$launcher"; fail "the job did not start rendering"; }
  victim=
  # The launcher's children (from /proc: no procps needed) are the ranks; find rank 1.
  for dir in /proc/[0-9]*; do
    [ "$(awk '{print $4}' "$dir/stat" 2>/dev/null)" = "$launcher" ] || continue
    if tr '\0' '\n' <"$dir/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then victim=${dir#/proc/}; fi
  done
  [ -n "$victim" ] || { kill "$launcher"; fail "process 1 not found among the launcher's children"; }
  kill -KILL "$victim"
  # The launcher must end the job by itself, well within a minute; if it
  # hangs, it is stopped here (it takes its processes with it) and the test fails.
  for _ in $(seq 1 600); do kill -0 "$launcher" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$launcher" 2>/dev/null; then
    kill -TERM "$launcher"
    wait "$launcher"
    fail "the job still ran 60 s after process 1 was killed"
  fi
  wait "$launcher"
  code=$?
  tail -5 "$scratch/out.log"
  [ "$code" != 0 ] || fail "the job exited 0 after losing a process"
  [ -z "$(ls "$scratch" | grep -v '\.log$')" ] || fail "files left behind: $(ls "$scratch")"
  ;;
*)
  fail "unknown case $case_name"
  ;;
esac
echo PASS
