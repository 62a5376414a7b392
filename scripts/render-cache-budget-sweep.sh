#!/usr/bin/env bash
# Render Cache quality and time against its ray budget: for each scene and
# budget, renders the scene's own camera path with the Render Cache (the
# default re-evaluated reflections) and with the ray pipeline, and prints the
# mean PSNR of frames 2..N against the ray pipeline's frames (displayed sRGB,
# `raycache diff`) beside the median frame, reconstruction, tracing and
# reshading times (ms, from --stats).
#
# Usage: scripts/render-cache-budget-sweep.sh [--size S] [--frames N]
#          [--scenes "room behind-32"] [--budgets "0.05 0.1 0.2 0.3 0.5"]
# Needs a release build (scripts/run.sh builds one). Time it on a quiet machine.
set -euo pipefail
cd "$(dirname "$0")/.."
size=1024 frames=30 scenes="room behind-32" budgets="0.05 0.1 0.2 0.3 0.5"
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --budgets) budgets=$2; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "render-cache-budget-sweep: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
raycache=build/release/apps/raycache/raycache
[ -x "$raycache" ] || { echo "render-cache-budget-sweep: $raycache not built (run scripts/run.sh first)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
render() {  # name, extra options...
  local name=$1; shift
  "$raycache" render --width "$size" --height "$size" --frames "$frames" --threads 2 \
    --out "$work/$name-%04d.exr" --stats "$work/$name.json" "$@" >/dev/null
}
for scene in $scenes; do
  render "$scene-full" --scene "$scene" --pipeline ray
  for budget in $budgets; do
    render "$scene-$budget" --scene "$scene" --pipeline render-cache --rc-budget "$budget"
    for ((i = 2; i <= frames; ++i)); do
      frame=$(printf %04d "$i")
      "$raycache" diff "$work/$scene-full-$frame.exr" "$work/$scene-$budget-$frame.exr" |
        awk -v s="$scene" -v b="$budget" '$1 == "PSNR" { print s, b, $2 }'
    done >"$work/$scene-$budget.psnr"
  done
done
python3 - "$work" "$scenes" "$budgets" <<'PY'
import json, statistics, sys
work, scenes, budgets = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
def frames(name):
    return json.load(open(f"{work}/{name}.json"))["frames"][1:]  # frame 1 traces every pixel
print("| scene | budget | mean PSNR dB (min) | ms per frame | reconstruction ms | trace ms | reshade ms |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for s in scenes:
    full = statistics.median(f["ms"] for f in frames(f"{s}-full"))
    print(f"| {s} | full render | – | {full:.1f} | – | – | – |")
    for b in budgets:
        fr = frames(f"{s}-{b}")
        med = lambda key: statistics.median(f["render_cache"][key] for f in fr)
        psnr = [float(l.split()[2]) for l in open(f"{work}/{s}-{b}.psnr") if l.split()[2] != "inf"]
        recon = med("reproject_ms") + med("maps_ms") + med("filter_ms")
        print(f"| {s} | {float(b):.0%} | {statistics.mean(psnr):.2f} ({min(psnr):.2f}) | "
              f"{statistics.median(f['ms'] for f in fr):.1f} | {recon:.1f} | {med('trace_ms'):.1f} | {med('reshade_ms'):.1f} |")
PY
