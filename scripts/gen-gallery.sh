#!/usr/bin/env bash
# Renders every built-in scene uncached and with CCT, with the heat map of
# their difference, into docs/images/gallery/, and writes docs/gallery.md.
#
#   scripts/gen-gallery.sh [BINARY]      (default build/release/apps/raycache/raycache)
#
# Each scene: the last of FRAMES frames along its own camera path (and
# animation), SIZE² pixels; CCT under --cache-policy always, so every mirror
# and glass object answers from its cube, as the documents' technique does.
# The behind-N and grid-N families are shown by their largest member.
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${1:-build/release/apps/raycache/raycache}
size=${GALLERY_SIZE:-192}
frames=${GALLERY_FRAMES:-8}
heatmap_max=0.1
out=docs/images/gallery
page=docs/gallery.md
scenes=(room glass behind-32 grid-32 diffuse-32 reflective-32 parallax shapes bowl
        room-moving orbit cloth light-sweep bunny-glass teapot-mirrors dragon-hall dragon-mirrors)

mkdir -p "$out"
rows=()
for scene in "${scenes[@]}"; do
  for technique in none cct; do
    "$binary" render --scene "$scene" --width "$size" --height "$size" --frames "$frames" \
      --technique "$technique" --cache-policy always --out "$out/$scene-$technique.png" >/dev/null
  done
  psnr=$("$binary" diff "$out/$scene-none.png" "$out/$scene-cct.png" \
           --heatmap "$out/$scene-difference.png" --heatmap-max "$heatmap_max" | awk '/^PSNR/ {print $2, $3}')
  rows+=("| \`$scene\` | ![$scene uncached](images/gallery/$scene-none.png) | ![$scene CCT](images/gallery/$scene-cct.png) | ![$scene difference](images/gallery/$scene-difference.png) | $psnr |")
done

{
  cat <<EOF
# Gallery

Every built-in scene ([builtin-scenes.md](builtin-scenes.md)), uncached and
with CCT, and the difference between the two as a heat map (blue = the same,
red = a difference of $heatmap_max or more per channel, displayed sRGB). Each
image is frame $frames of the scene's own camera path (and animation) at
${size}×${size}, CCT under \`--cache-policy always\`, so every mirror and glass
object answers from its cube; the \`behind-N\` and \`grid-N\` families are
shown by their largest member. PSNR is of the CCT frame against the uncached
one. Written by \`scripts/gen-gallery.sh\`; run it again after a change to
the scenes or the renderer.

| scene | uncached | CCT | difference | PSNR |
| --- | --- | --- | --- | --- |
EOF
  printf '%s\n' "${rows[@]}"
  cat <<'EOF'

## Larger renders

| `room` | `glass` | `behind-32` |
| --- | --- | --- |
| ![room](images/room.png) | ![glass](images/glass.png) | ![behind-32](images/behind-32.png) |

| `bunny-glass` | `teapot-mirrors` | `dragon-hall` | `dragon-mirrors` |
| --- | --- | --- | --- |
| ![bunny-glass](images/bunny-glass.png) | ![teapot-mirrors](images/teapot-mirrors.png) | ![dragon-hall](images/dragon-hall.png) | ![dragon-mirrors](images/dragon-mirrors.png) |

Caching cubes unfolded (`raycache cache-view`): `behind-8`'s main sphere, and
the CDCT cube of `parallax`'s left mirror, colour and depth
([caching.md](caching.md#what-is-cached)):

![behind-8 main sphere cube](images/behind-8-main-cube.png)

| colour | depth |
| --- | --- |
| ![parallax left mirror, colour](images/parallax-left-mirror-color.png) | ![parallax left mirror, depth](images/parallax-left-mirror-depth.png) |

The viewer: ![The viewer on behind-8](images/viewer.png)
EOF
} > "$page"
echo "wrote $page and ${#scenes[@]} scenes' images in $out"
