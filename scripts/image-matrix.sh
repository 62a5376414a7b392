#!/usr/bin/env bash
# Renders every built-in scene through every pipeline, accelerator, technique
# and lane level into a folder of linear EXR frames, so that a restructuring
# can be checked bit for bit against the renderer it replaces:
#
#   scripts/image-matrix.sh OLD_BINARY before/      # e.g. a build of main
#   scripts/image-matrix.sh NEW_BINARY after/
#   scripts/image-matrix.sh --compare before/ after/
#
# --compare exits non-zero and names each frame that differs in any byte.
# Options: --size N (image side, default 96), --frames N (default 4: the
# later frames read what the first ones cached), --scenes "a b c",
# --pipelines "ray hybrid render-cache", --lanes "default avx2 baseline"
# (RAYCACHE_LANES values; a level this processor lacks is skipped with a
# note), --quick (fewer techniques), --cache-res N (cube faces, default 64:
# CDCT's pre-fill traces every texel of every cube, so the scenes' own 512
# makes the matrix slow without testing more of the kernel). The Render Cache runs on Embree with
# no caching and with CCT; the hybrid pipeline on Embree.
set -euo pipefail

size=96
frames=4
scenes=""
lanes="default avx2 baseline"
quick=0
compare=0
pipelines="ray hybrid render-cache"
cache_res=64
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --lanes) lanes=$2; shift 2 ;;
    --pipelines) pipelines=$2; shift 2 ;;
    --cache-res) cache_res=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --compare) compare=1; shift ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done

if [ "$compare" = 1 ]; then
  [ ${#args[@]} -eq 2 ] || { echo "usage: $0 --compare BEFORE_DIR AFTER_DIR" >&2; exit 2; }
  before=${args[0]}; after=${args[1]}
  differ=0; same=0; missing=0
  while IFS= read -r f; do
    rel=${f#"$before"/}
    if [ ! -f "$after/$rel" ]; then
      echo "missing: $rel"; missing=$((missing + 1))
    elif cmp -s "$f" "$after/$rel"; then
      same=$((same + 1))
    else
      echo "differs: $rel"; differ=$((differ + 1))
    fi
  done < <(find "$before" -type f -name '*.exr' | sort)
  echo "image-matrix: $same same, $differ differ, $missing missing"
  [ "$differ" = 0 ] && [ "$missing" = 0 ]
  exit $?
fi

[ ${#args[@]} -eq 2 ] || { echo "usage: $0 BINARY OUT_DIR [options]" >&2; exit 2; }
binary=$(realpath "${args[0]}")
out=${args[1]}
mkdir -p "$out"

if [ -z "$scenes" ]; then
  scenes=$("$binary" scenes | awk '{print $1}')
fi
all_techniques="none cct cdct cdct-parity"
accels="embree grids"
if [ "$quick" = 1 ]; then
  all_techniques="none cct cdct"
fi

# Embree's instructions stay the processor's widest at every lane level (a
# narrowed RAYCACHE_LANES would narrow them too: src/trace/EmbreeDeviceConfig.h),
# so that a frame differs only where the lane code does, and frames compare
# with builds that never narrowed Embree.
export RAYCACHE_EMBREE_ISA=avx512

count=0
for level in $lanes; do
  env_lanes=()
  [ "$level" != default ] && env_lanes=(RAYCACHE_LANES="$level")
  if [ "$level" != default ] && ! env "${env_lanes[@]}" "$binary" render --scene room --width 8 --height 8 --frames 1 \
      --out "$out/.probe.exr" >/dev/null 2>&1; then
    echo "image-matrix: lane level $level not available here, skipped"
    continue
  fi
  for scene in $scenes; do
    for pipeline in $pipelines; do
      for accel in $accels; do
        [ "$pipeline" != ray ] && [ "$accel" = grids ] && continue
        techniques=$all_techniques
        [ "$pipeline" = render-cache ] && techniques="none cct"
        for technique in $techniques; do
          dir="$out/$level/$scene/$pipeline-$accel-$technique"
          mkdir -p "$dir"
          if ! env "${env_lanes[@]}" "$binary" render --scene "$scene" --width "$size" --height "$size" \
              --frames "$frames" --threads 2 --pipeline "$pipeline" --accel "$accel" --technique "$technique" \
              --gbuffer packets --cache-res "$cache_res" --out "$dir/frame_%02d.exr" >"$dir/log.txt" 2>&1; then
            echo "image-matrix: failed: $level $scene $pipeline $accel $technique (see $dir/log.txt)"
          fi
          count=$((count + 1))
        done
      done
    done
  done
done
rm -f "$out/.probe.exr"
echo "image-matrix: $count renders into $out"
