#!/usr/bin/env bash
# The Render Cache displayed at its own rate in the viewer: scripted runs of
# `raycache view --pipeline render-cache --render-cache-display async` under
# Xvfb (Mesa llvmpipe), along each scene's camera path (the camera moves every
# frame), variants interleaved round by round: the display reshading every
# mirror/glass sample every frame (--render-cache-reshade-ms 0), within the
# default budget, and the synchronous display; full frames beside them.
# Prints, per scene and variant, medians (min-max) over every frame after the
# warm-up of all rounds: display fps (1000 / interval between shown frames),
# and where the time goes (render thread: render, encode; UI thread: upload,
# ui, present), which `bench render-cache`'s headless async rows leave out.
# Usage: benchmarks/render_cache_async_speed.sh [build dir] [rounds] [size] [scenes...]
set -euo pipefail
build=${1:-build/release}
rounds=${2:-3}
size=${3:-1024}
shift $(($# < 3 ? $# : 3))
scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(room dragon-hall)
bin="$build/apps/raycache/raycache"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
frames=40
warmup=10
xvfb() { xvfb-run -a -s "-screen 0 $((size + 256))x$((size + 256))x24" "$@"; }

variants=(async-budget async-every-frame sync full)
run() {  # scene variant
  local common=("$1" --width "$size" --height "$size" --threads 2 --frames $frames --warmup $warmup --hide-ui)
  case $2 in
    async-budget)      xvfb "$bin" view "${common[@]}" --pipeline render-cache --render-cache-display async ;;
    async-every-frame) xvfb "$bin" view "${common[@]}" --pipeline render-cache --render-cache-display async \
                         --render-cache-reshade-ms 0 ;;
    sync)              xvfb "$bin" view "${common[@]}" --pipeline render-cache --render-cache-display sync ;;
    full)              xvfb "$bin" view "${common[@]}" --pipeline ray ;;
  esac
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for ((r = 1; r <= rounds; r++)); do
  for s in "${scenes[@]}"; do
    for v in "${variants[@]}"; do run "$s" "$v" > "$out/$s-$v-$r.txt"; done
  done
done
echo "load average after:  $(cut -d' ' -f1-3 /proc/loadavg)"

# Column values of frames after the warm-up, one per line.
column() {  # scene-variant field
  cat "$out/$1"-[0-9]*.txt | awk -v warm=$warmup -v field="$2" '
    /^frame [0-9]+\/[0-9]+ / {
      split($2, f, "/"); if (f[1] + 0 <= warm) next
      if (field == "render") { print $3; next }
      for (i = 1; i < NF; i++) if ($i == field) print $(i + 1)
    }' | grep -v '^$' || true
}
summary() {  # median (min-max) of stdin
  sort -g | awk '{ v[NR] = $1 } END {
    if (NR == 0) { print "-"; exit }
    m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    printf "%.1f (%.1f-%.1f)", m, v[1], v[NR] }'
}
printf '%-12s %-18s %-20s %-20s %-18s %-18s %-18s %-18s\n' scene variant fps render_ms encode_ms upload_ms ui_ms present_ms
for s in "${scenes[@]}"; do
  for v in "${variants[@]}"; do
    fps=$(column "$s-$v" interval | awk '$1 > 0 { print 1000 / $1 }' | summary)
    printf '%-12s %-18s %-20s %-20s %-18s %-18s %-18s %-18s\n' "$s" "$v" "$fps" "$(column "$s-$v" render | summary)" \
      "$(column "$s-$v" encode | summary)" "$(column "$s-$v" upload | summary)" "$(column "$s-$v" ui | summary)" \
      "$(column "$s-$v" present | summary)"
  done
done
