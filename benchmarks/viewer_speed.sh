#!/usr/bin/env bash
# The viewer's speed: grid-32 at 640x360 on 2 threads, scripted runs of
# `raycache view` under Xvfb (Mesa llvmpipe), variants interleaved round by
# round. Prints, per variant, medians (min-max) over every frame after the
# warm-up frames of all rounds: fps (1000 / interval between shown frames)
# and where the time goes (render thread: render, encode; UI thread: upload,
# ui, present). `render` rows are the offline command on the same frames.
# Usage: benchmarks/viewer_speed.sh [build dir] [rounds]
set -euo pipefail
build=${1:-build/release}
rounds=${2:-3}
bin="$build/apps/raycache/raycache"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
common=(grid-32 --width 640 --height 360 --threads 2 --frames 60)
warmup=20
xvfb() { xvfb-run -a -s '-screen 0 1280x1024x24' "$@"; }

variants=(view-static-cct view-static-cct-hidden-ui view-static-none render-static-cct view-orbit-cct view-orbit-none render-orbit-cct)
run() {
  case $1 in
    view-static-cct)           xvfb "$bin" view "${common[@]}" --path static --technique cct --warmup $warmup ;;
    view-static-cct-hidden-ui) xvfb "$bin" view "${common[@]}" --path static --technique cct --warmup $warmup --hide-ui ;;
    view-static-none)          xvfb "$bin" view "${common[@]}" --path static --technique none --warmup $warmup ;;
    render-static-cct)         "$bin" render --scene "${common[@]}" --path static --technique cct ;;
    view-orbit-cct)            xvfb "$bin" view "${common[@]}" --technique cct --warmup $warmup ;;
    view-orbit-none)           xvfb "$bin" view "${common[@]}" --technique none --warmup $warmup ;;
    render-orbit-cct)          "$bin" render --scene "${common[@]}" --technique cct ;;
  esac
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for ((r = 1; r <= rounds; r++)); do
  for v in "${variants[@]}"; do run "$v" > "$out/$v-$r.txt"; done
done
echo "load average after:  $(cut -d' ' -f1-3 /proc/loadavg)"

# Column values of frames after the warm-up, one per line.
column() {  # variant field
  cat "$out/$1"-[0-9]*.txt | awk -v warm=$warmup -v field="$2" '
    /^frame [0-9]+\/[0-9]+ / {
      split($2, f, "/"); if (f[1] + 0 <= warm) next
      if (field == "render") { print $3; next }
      for (i = 1; i < NF; i++) if ($i == field) {
        v = $(i + 1); if (field == "fps") print (v > 0 ? 1000 / v : ""); else print v
      }
    }' | grep -v '^$' || true
}
summary() {  # median (min-max) of stdin
  sort -g | awk '{ v[NR] = $1 } END {
    if (NR == 0) { print "-"; exit }
    m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    printf "%.1f (%.1f-%.1f)", m, v[1], v[NR] }'
}
printf '%-26s %-20s %-20s %-18s %-18s %-18s %-18s\n' variant fps render_ms encode_ms upload_ms ui_ms present_ms
for v in "${variants[@]}"; do
  fps=$(column "$v" interval | awk '$1 > 0 { print 1000 / $1 }' | summary)
  [[ $v == render-* ]] && fps="$(column "$v" render | awk '{ print 1000 / $1 }' | summary) *"
  printf '%-26s %-20s %-20s %-18s %-18s %-18s %-18s\n' "$v" "$fps" "$(column "$v" render | summary)" \
    "$(column "$v" encode | summary)" "$(column "$v" upload | summary)" "$(column "$v" ui | summary)" \
    "$(column "$v" present | summary)"
done
echo "* render rows: 1000 / render ms (no window, nothing else per frame)"
