#!/usr/bin/env bash
# Renders each Blender-made glTF scene in tests/data/blender/ with raycache
# and scores it against Cycles' reference of the same scene:
#
#   scripts/compare-with-cycles.sh [--spp N] [--scenes "a b"] [--scale-lights F]
#                                  [--keep DIR] [--data DIR] [RAYCACHE_BINARY]
#
# Prints one row per scene: PSNR and SSIM (raycache diff: displayed 8-bit
# sRGB images) against X.png, Cycles' render with its default 1.5 px
# Blackman-Harris filter, and against X-point.png, the same render point
# sampled (one ray per pixel centre), which separates aliasing's share.
# --spp N passes --spp N to raycache (a raycache without the option fails).
# --scale-lights F multiplies every KHR_lights_punctual intensity in a copy
# of the .glb by F first (e.g. 0.00146413 = 1/683 to check the units by hand).
# --keep DIR keeps raycache's renders there; --data DIR reads the scenes and
# references from DIR instead (make-scenes.py's output). RAYCACHE_BINARY defaults to
# build/release/apps/raycache/raycache. Exits non-zero when a scene's .glb
# or reference is missing, or a render or comparison fails.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data="$root/tests/data/blender"

spp=""
scenes="lambert-point lambert-sun lambert-spot studio metals glass"
scale=""
keep=""
binary="$root/build/release/apps/raycache/raycache"
while [ $# -gt 0 ]; do
  case "$1" in
    --spp) spp=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --scale-lights) scale=$2; shift 2 ;;
    --keep) keep=$2; shift 2 ;;
    --data) data=$2; shift 2 ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "compare-with-cycles: unknown option $1" >&2; exit 2 ;;
    *) binary=$1; shift ;;
  esac
done
[ -x "$binary" ] || { echo "compare-with-cycles: no raycache binary at $binary" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${keep:-$work}
mkdir -p "$out"

# Width and height of a PNG, from its IHDR chunk.
png_size() {
  python3 -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); print(*struct.unpack(">II", d[16:24]))' "$1"
}

# A copy of a .glb with every light's intensity multiplied by a factor.
scale_lights() {
  python3 - "$1" "$2" "$3" <<'EOF'
import json, struct, sys
src, dst, factor = sys.argv[1], sys.argv[2], float(sys.argv[3])
data = open(src, "rb").read()
length = struct.unpack("<I", data[12:16])[0]
doc = json.loads(data[20:20 + length])
for light in doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []):
    light["intensity"] = light.get("intensity", 1.0) * factor
text = json.dumps(doc, separators=(",", ":")).encode()
text += b" " * (-len(text) % 4)
rest = data[20 + length:]
body = struct.pack("<II", len(text), 0x4E4F534A) + text + rest
open(dst, "wb").write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)
EOF
}

# "PSNR SSIM" of raycache diff's report.
score() {
  "$binary" diff "$1" "$2" | awk '/^PSNR/ {p=$2} /^SSIM/ {s=$2} END {if (p == "" || s == "") exit 1; print p, s}'
}

missing=0
for scene in $scenes; do
  for f in "$scene.glb" "$scene.png" "$scene-point.png"; do
    if [ ! -f "$data/$f" ]; then
      echo "compare-with-cycles: missing $data/$f" >&2
      missing=1
    fi
  done
done
[ "$missing" = 0 ] || exit 1

printf '%-14s %9s %7s   %9s %7s\n' scene "PSNR dB" SSIM "PSNR(pt)" "SSIM(pt)"
for scene in $scenes; do
  glb="$data/$scene.glb"
  if [ -n "$scale" ]; then
    scale_lights "$glb" "$work/$scene.glb" "$scale"
    glb="$work/$scene.glb"
  fi
  read -r width height <<< "$(png_size "$data/$scene.png")"
  args=(render --scene "$glb" --width "$width" --height "$height" --frames 1 --out "$out/$scene.png")
  [ -z "$spp" ] || args+=(--spp "$spp")
  "$binary" "${args[@]}" > "$work/$scene.log" 2>&1 || {
    echo "compare-with-cycles: raycache failed on $scene:" >&2
    cat "$work/$scene.log" >&2
    exit 1
  }
  filtered=$(score "$out/$scene.png" "$data/$scene.png") &&
    point=$(score "$out/$scene.png" "$data/$scene-point.png") || {
    echo "compare-with-cycles: raycache diff failed on $scene" >&2
    exit 1
  }
  read -r psnr ssim <<< "$filtered"
  read -r psnr_point ssim_point <<< "$point"
  printf '%-14s %9s %7s   %9s %7s\n' "$scene" "$psnr" "$ssim" "$psnr_point" "$ssim_point"
done
