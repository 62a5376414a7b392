#!/usr/bin/env bash
# Calibrates the cache policy's per-operation costs (src/cache/CachePolicy.h,
# CachePolicyCosts; docs/caching.md "Caching that never costs") in units of one
# traced ray, from the tile kernel's stage CPU times on one thread:
#   ray      = CPU of the stages that trace and shade rays past the first hits
#              (surfaces, shadow rays, direct shading, secondary rays, tracing,
#              resolve) / (shadow + reflection + refraction rays), uncached
#   lookup   = reuse-lookup CPU / lookups, CCT
#   store    = (cache frame end + resolve CPU over the uncached resolve) / stores queued, CCT
#   cdctStep = reuse-lookup CPU / texels the searches sampled, improved CDCT
# Only the middle frames of each run count (the first fills caches and pages).
# Run it on a quiet machine; it prints the three figures to put into
# CachePolicyCosts. Usage: scripts/calibrate-cache-policy.sh [raycache binary] [scene] [size]
set -euo pipefail
bin=${1:-build/release/apps/raycache/raycache}
scene=${2:-grid-32}
size=${3:-384}
frames=8
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {  # technique, output name
    "$bin" render --scene "$scene" --width "$size" --height "$size" --frames "$frames" --path orbit --threads 1 --stage-times \
        --technique "$1" --cache-policy always --out "$work/$2-%04d.png" --stats "$work/$2.json" >/dev/null
}
run none none
run cct cct
run cdct cdct
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
def frames(name):
    with open(f"{work}/{name}.json") as f:
        return json.load(f)["frames"][2:]  # past the filling frames
def total(fs, get): return sum(get(f) for f in fs)
none, cct, cdct = frames("none"), frames("cct"), frames("cdct")
traced_stages = ["surfaces_cpu_ms", "shadow_rays_cpu_ms", "direct_shading_cpu_ms", "secondary_rays_cpu_ms",
                 "trace_secondary_cpu_ms", "resolve_cpu_ms"]
ms = total(none, lambda f: sum(f["stages"][k] for k in traced_stages))
rays = total(none, lambda f: f["rays"]["shadow"] + f["rays"]["reflection"] + f["rays"]["refraction"])
ray_ns = ms * 1e6 / rays
lookup_ns = total(cct, lambda f: f["stages"]["reuse_lookups_cpu_ms"]) * 1e6 / max(1, total(cct, lambda f: f["cache"]["lookups"]))
resolve_extra = total(cct, lambda f: f["stages"]["resolve_cpu_ms"] + f["stages"]["cache_frame_end_ms"]) \
    - total(none, lambda f: f["stages"]["resolve_cpu_ms"]) * (total(cct, lambda f: f["stages"]["hits_shaded"]) / max(1, total(none, lambda f: f["stages"]["hits_shaded"])))
queued = total(cct, lambda f: sum(o["policy"]["stores_queued"] for o in f["cache"]["objects"]))
store_ns = max(0.0, resolve_extra) * 1e6 / max(1, queued)
step_ns = total(cdct, lambda f: f["stages"]["reuse_lookups_cpu_ms"]) * 1e6 / max(1, total(cdct, lambda f: f["cache"]["objects"] and sum(o["cdct_steps"] for o in f["cache"]["objects"])))
print(f"one traced ray: {ray_ns:.1f} ns ({rays} rays)")
print(f"lookup:   {lookup_ns:.1f} ns = {lookup_ns / ray_ns:.3f} rays")
print(f"store:    {store_ns:.1f} ns = {store_ns / ray_ns:.3f} rays ({queued} queued)")
print(f"cdctStep: {step_ns:.1f} ns = {step_ns / ray_ns:.4f} rays")
PY
