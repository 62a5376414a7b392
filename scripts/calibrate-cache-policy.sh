#!/usr/bin/env bash
# Calibrates the cache policy's per-operation costs (src/cache/CachePolicy.h,
# CachePolicyCosts; docs/caching.md "Caching that never costs") in units of one
# traced ray, from the tile kernel's stage CPU times on one thread:
#   ray      = CPU of the stages that trace and shade rays past the first hits
#              (surfaces, shadow rays, direct shading, secondary rays, tracing,
#              resolve) / (shadow + reflection + refraction rays), uncached
#   lookup   = (reuse-lookup CPU + secondary-ray CPU over the uncached one) / lookups, CCT
#   store    = (cache frame end + resolve CPU over the uncached resolve) / stores queued, CCT
#   cdctStep = reuse-lookup CPU / texels the searches sampled, improved CDCT
# and, on the animated scene orbit (dependencies tracked), what tracking adds:
#   trackedLookup = the same per lookup on orbit, less `lookup`
#   trackedStore  = (cache frame end + resolve CPU over the uncached resolve) / stores queued, less `store`
#   regionTest    = scene-update cache CPU over the uncached one / region tests (blocks x changed regions)
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
animated=orbit
for t in none cct; do
    "$bin" render --scene "$animated" --width "$size" --height "$size" --frames "$frames" --threads 1 --stage-times \
        --technique "$t" --cache-policy always --cache-res 256 --stats "$work/tracked-$t.json" >/dev/null
done
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
def lookup_cpu(cached, plain):
    # Lookups run in the reuse stage and, asked in lanes where rays spawn,
    # in the secondary-ray stage: that stage's CPU over the uncached one's
    # (scaled by the hits shaded) counts too.
    ratio = total(cached, lambda f: f["stages"]["hits_shaded"]) / max(1, total(plain, lambda f: f["stages"]["hits_shaded"]))
    spawn = total(cached, lambda f: f["stages"]["secondary_rays_cpu_ms"]) - ratio * total(plain, lambda f: f["stages"]["secondary_rays_cpu_ms"])
    return total(cached, lambda f: f["stages"]["reuse_lookups_cpu_ms"]) + max(0.0, spawn)
lookup_ns = lookup_cpu(cct, none) * 1e6 / max(1, total(cct, lambda f: f["cache"]["lookups"]))
resolve_extra = total(cct, lambda f: f["stages"]["resolve_cpu_ms"] + f["stages"]["cache_frame_end_ms"]) \
    - total(none, lambda f: f["stages"]["resolve_cpu_ms"]) * (total(cct, lambda f: f["stages"]["hits_shaded"]) / max(1, total(none, lambda f: f["stages"]["hits_shaded"])))
queued = total(cct, lambda f: sum(o["policy"]["stores_queued"] for o in f["cache"]["objects"]))
store_ns = max(0.0, resolve_extra) * 1e6 / max(1, queued)
step_ns = total(cdct, lambda f: f["stages"]["reuse_lookups_cpu_ms"]) * 1e6 / max(1, total(cdct, lambda f: f["cache"]["objects"] and sum(o["cdct_steps"] for o in f["cache"]["objects"])))
print(f"one traced ray: {ray_ns:.1f} ns ({rays} rays)")
print(f"lookup:   {lookup_ns:.1f} ns = {lookup_ns / ray_ns:.3f} rays")
print(f"store:    {store_ns:.1f} ns = {store_ns / ray_ns:.3f} rays ({queued} queued)")
print(f"cdctStep: {step_ns:.1f} ns = {step_ns / ray_ns:.4f} rays")
tnone, tcct = frames("tracked-none"), frames("tracked-cct")
tlookups = max(1, total(tcct, lambda f: f["cache"]["lookups"]))
tracked_lookup_ns = max(0.0, lookup_cpu(tcct, tnone) * 1e6 / tlookups - lookup_ns)
tresolve_extra = total(tcct, lambda f: f["stages"]["resolve_cpu_ms"] + f["stages"]["cache_frame_end_ms"]) \
    - total(tnone, lambda f: f["stages"]["resolve_cpu_ms"]) * (total(tcct, lambda f: f["stages"]["hits_shaded"]) / max(1, total(tnone, lambda f: f["stages"]["hits_shaded"])))
tqueued = max(1, total(tcct, lambda f: sum(o["policy"]["stores_queued"] for o in f["cache"]["objects"])))
tracked_store_ns = max(0.0, max(0.0, tresolve_extra) * 1e6 / tqueued - store_ns)
tests = max(1, total(tcct, lambda f: sum(o["policy"]["region_tests"] for o in f["cache"]["objects"])))
update_extra = total(tcct, lambda f: f["scene_update"]["cache_ms"]) - total(tnone, lambda f: f["scene_update"]["cache_ms"])
region_ns = max(0.0, update_extra) * 1e6 / tests
print(f"trackedLookup: {tracked_lookup_ns:.1f} ns = {tracked_lookup_ns / ray_ns:.3f} rays ({tlookups} lookups)")
print(f"trackedStore:  {tracked_store_ns:.1f} ns = {tracked_store_ns / ray_ns:.3f} rays ({tqueued} queued)")
print(f"regionTest:    {region_ns:.1f} ns = {region_ns / ray_ns:.3f} rays ({tests} tests)")
PY
