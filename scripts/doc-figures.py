#!/usr/bin/env python3
"""Write the figures the docs quote from a committed bench run, or check them.

    scripts/doc-figures.py            # rewrite the generated blocks
    scripts/doc-figures.py --check    # exit 1 if a doc differs from its source
    scripts/doc-figures.py --bench-runs DIR --docs TREE
        # the benchmarks' runs from DIR/<program>/, README.md and docs/*.md of
        # TREE written or checked (tiny runs tried on a copy of the docs)

Sources and targets:
- docs/where-caching-pays/results.json (`raycache bench where-caching-pays`,
  the run whose report is docs/where-caching-pays/results.md): the block of
  docs/performance.md between `<!-- figures:where-caching-pays -->` and
  `<!-- /figures -->`, and README.md's `--cache-policy auto` row;
- docs/render-cache-run/results.json (`raycache bench render-cache`): the
  block between `<!-- figures:render-cache -->` and `<!-- /figures -->`, the
  Render Cache rows of its "Goals at a glance", and README.md's Render Cache
  row;
- docs/full-run/ (`raycache bench all --full`, copied in with
  `scripts/copy-sample-report.py RESULTS_DIR full`: one results.json per
  experiment and run.json, the command and its wall time): in
  docs/performance.md the blocks `full-run-tables` (Tables 5.1-5.3),
  `full-run-dynamic`, `full-run-grids` and `full-run-harness`, the "Goals at a
  glance" rows of CCT against the documents' tables, the Fig 5.9 protocol,
  CDCT on reflective-32, dynamic and grids whose figures come from that run;
  in docs/dynamic-scenes.md the block `full-run-oracle` (the invalidation
  oracle's table); README.md's rows for CDCT, animated scenes, grids and the
  experiments harness (figure and, where it judges the figure, status).
  docs/full-run/where-caching-pays/ is copied along but not read: the
  where-caching-pays figures come from the run of their own above;
- docs/bench-runs/<program>/*.json (the standalone benchmarks' `--json`
  documents, several runs each, written by scripts/record-bench-runs.sh):
  - core_speed and cct_speed: in docs/performance.md the blocks `bench-core`
    ("Core frame and floor"), `bench-core-avx2` (the runs at
    RAYCACHE_LANES=avx2) and `bench-cct` ("CCT against uncached"), and the
    core and CCT goals rows whose figures come from them; README.md's rows
    for uncached Whitted ray tracing and CCT filled and moving (status and
    figure);
  - hybrid_speed: the block `bench-hybrid` ("Hybrid pipeline") and
    README.md's hybrid row (status and figure);
  - moving_cache: the block `bench-moving-cache` ("CCT along a moving
    camera");
  - scene_update_speed: the block `bench-scene-update` ("Dynamic scenes")
    and docs/dynamic-scenes.md's table, the block `bench-scene-update-table`;
  - grids_speed (torus 100k, and any other model recorded beside it): the
    block `bench-grids` ("Grids") and the goals row of the rays alone;
  - soak and scene_load_speed: the blocks `bench-soak` and
    `bench-scene-load` ("Memory and loading"); with dragon-hall in the runs,
    the goals row of loading the dragon and README.md's figure for meshes;
  - cdct_speed (a --speed-only and a --quality-only run each round): the
    block `bench-cdct` ("CDCT"), improved CDCT against uncached and the
    mean PSNR along the orbits.
  Times are medians of the runs' medians with min–max over the runs; a
  ratio is taken within each run, of its medians, and quoted over the runs
  the same way or as their min–max. The runs of core_speed and cct_speed
  are committed, and a missing folder of theirs is an error; for the other
  programs a folder without runs leaves their blocks, rows and README cells
  as they are, and the script says "not generated: no runs in …" and how to
  record them (their hand-written text names its source).
Each block has one provenance line (machine, threads, lane level, size,
date, commit, from the run's `environment`; for the benchmarks' runs also
their number); a goals row is replaced whole,
keyed by its start; a README row must contain its generated phrase (the
check looks for it in the row) or, for the full run's and the benchmarks'
rows, hold exactly the generated cells. Judgements ("met?", "slower than …", "not met") are
generated from the figure and its goal. Sentences whose figures come from
elsewhere (a log entry, another machine, `cct_speed` runs on other scenes,
moving_cache's multi-resolution runs) stay written by hand and name their
source. A ctest test (`doc_figures`) runs the check mode; it fails with one
line when docs/full-run/ or a folder of core_speed's or cct_speed's runs is
missing or empty; `doc_figures_tests` tries the script on --tiny runs.
"""
import argparse
import glob
import json
import os
import re
import shlex
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCE = os.path.join(ROOT, "docs", "where-caching-pays", "results.json")
RENDER_CACHE_SOURCE = os.path.join(ROOT, "docs", "render-cache-run", "results.json")
PERFORMANCE = os.path.join(ROOT, "docs", "performance.md")
README = os.path.join(ROOT, "README.md")
BEGIN, END = "<!-- figures:where-caching-pays -->", "<!-- /figures -->"
RENDER_CACHE_BEGIN = "<!-- figures:render-cache -->"
FULL_RUN = os.path.join(ROOT, "docs", "full-run")
DYNAMIC_SCENES = os.path.join(ROOT, "docs", "dynamic-scenes.md")
TABLES_BEGIN = "<!-- figures:full-run-tables -->"
DYNAMIC_BEGIN = "<!-- figures:full-run-dynamic -->"
GRIDS_BEGIN = "<!-- figures:full-run-grids -->"
HARNESS_BEGIN = "<!-- figures:full-run-harness -->"
ORACLE_BEGIN = "<!-- figures:full-run-oracle -->"
# The goals the full run's judgements compare with (performance.md's "Goals
# at a glance"); the documents' speed-ups come from the run's JSON.
DYNAMIC_PSNR_DB = 40.0  # every CCT frame against the uncached one
DYNAMIC_UPDATE_SHARE = 10.0  # % of the CCT frame
DYNAMIC_NEEDLESS = 2.0  # needless drops over the texels that really changed
DYNAMIC_CCT = 1.3  # CCT speed-up over uncached along the animations
GRIDS_1M_MS = 115.0  # the document's Buddha, 1.09M triangles on a GTX 280
FILL_TRACED = 5.0  # % of lookups traced after frame 2 (Fig 5.9 protocol)
CDCT_REFLECTIVE = 1.0  # improved CDCT on reflective-32, over uncached
CDCT_GOAL_SCENE = "reflective-32"  # the scene of that goal
BENCH_RUNS = os.path.join(ROOT, "docs", "bench-runs")
CORE_BEGIN = "<!-- figures:bench-core -->"
CORE_AVX2_BEGIN = "<!-- figures:bench-core-avx2 -->"
CCT_BEGIN = "<!-- figures:bench-cct -->"
# The goals the standalone benchmarks' judgements compare with (performance.md's "Goals at a glance").
GOAL_SCENE = "grid-32"  # the scene the core and CCT goals name
CORE_PLAIN = 0.5  # uncached frame over the plain Embree Whitted loop's
CORE_FLOOR = 1.3  # ideal frame over the floor
CCT_FILLED = 2.0  # CCT with filled caches over uncached
CCT_MISS = 1.1  # a miss over the plain trace it replaces
HYBRID_BEGIN = "<!-- figures:bench-hybrid -->"
MOVING_BEGIN = "<!-- figures:bench-moving-cache -->"
UPDATE_BEGIN = "<!-- figures:bench-scene-update -->"
UPDATE_TABLE_BEGIN = "<!-- figures:bench-scene-update-table -->"
GRIDS_SPEED_BEGIN = "<!-- figures:bench-grids -->"
SOAK_BEGIN = "<!-- figures:bench-soak -->"
LOAD_BEGIN = "<!-- figures:bench-scene-load -->"
CDCT_BEGIN = "<!-- figures:bench-cdct -->"
GRIDS_SPEED_MODEL = "torus 100k"  # grids_speed's default model, the one its goal names
GRIDS_RAYS = 1.5  # the grids' rays alone over Embree's through a prebuilt hierarchy
LOAD_SCENE = "dragon-hall"  # the scene of the loading goal
LOAD_SECONDS = 1.5
LANE_LEVEL_NAMES = {"avx512": "AVX-512", "avx2": "AVX2", "baseline": "baseline x86-64"}
DYNAMIC_ANCHOR = ("results-sample-full.md#dynamic-scenes-cct-with-per-block-invalidation-against-uncached-along-the-"
                  "built-in-animations")


def x(v):
    return f"{v:.2f}×"


def interval(m):
    s = f"{x(m['speedup'])} ({m['ci95_low']:.2f}–{m['ci95_high']:.2f})"
    return s + ", no measurable difference" if m["no_measurable_difference"] else s


def span(values):
    lo, hi = min(values), max(values)
    return x(lo) if f"{lo:.2f}" == f"{hi:.2f}" else f"{lo:.2f}–{hi:.2f}×"


def figures(run):
    rows = run["rows"]
    env, version, settings = run["environment"], run["environment"]["version"], run["settings"]
    auto = [r["cct_auto"]["path"] for r in rows]
    not_slower = sum(1 for a in auto if a["ci95_high"] >= 1.0)
    still = [r["cct"]["still"] for r in rows]
    paying = [s["measured"]["speedup"] for s in still if s["parts"]["cacheable_share"] >= 0.2]
    small = [s["measured"]["speedup"] for s in still if s["parts"]["cacheable_share"] < 0.2]
    path = [r["cct"]["path"]["measured"]["speedup"] for r in rows]
    cct_error = max(abs(r["cct"][k]["error"]) for r in rows for k in ("still", "path"))
    cdct_error = max(abs(r["cdct"][k]["error"]) for r in rows for k in ("still", "path"))
    cdct_still = [r["cdct"]["still"]["measured"]["speedup"] for r in rows]
    dragon = next(r for r in rows if r["scene"] == "dragon-mirrors")
    median = statistics.median(a["speedup"] for a in auto)
    readme_phrase = f"{len(rows)} scenes' camera paths: median {median:.2f}× uncached, lowest {min(a['speedup'] for a in auto):.2f}×"
    lines = [
        BEGIN,
        "",
        f"The committed run ([report](where-caching-pays/results.md)): {env['cpu_model']}, "
        f"{env['worker_threads']} threads, {lanes_text(version)}, {settings['width']}×{settings['height']}, "
        f"{settings['cache_resolution']}² faces, {env['started_at'][:10]}, commit {commit_text(version)}. "
        "Generated by `scripts/doc-figures.py` from its results.json.",
        "",
        "| figure | value |",
        "| --- | --- |",
        f"| `auto` along the {len(rows)} paths, speed-up over uncached | median {median:.2f}×, "
        f"{span([a['speedup'] for a in auto])}; not slower on {not_slower} of {len(rows)} |",
        f"| CCT filled where the cacheable share ≥ 20 % | {span(paying)} on {len(paying)} scenes |",
        f"| CCT filled where the cacheable share < 20 % | {span(small)} on {len(small)} scenes |",
        f"| CCT `always` along the paths from empty caches | {span(path)} |",
        f"| CDCT filled | {span(cdct_still)} |",
        f"| dragon-mirrors filled ({dragon['mirror_glass_coverage'] * 100:.0f} % of the image mirrors and glass) | "
        f"CCT {interval(dragon['cct']['still']['measured'])}; free cache "
        f"{x(dragon['cct']['still']['parts']['free_cache_speedup'])} |",
        f"| the model's largest error | CCT {cct_error * 100:.0f} %, CDCT {cdct_error * 100:.0f} % |",
        "",
        END,
    ]
    return "\n".join(lines), readme_phrase


def render_cache_figures(run):
    """The Render Cache block and README phrase: per scene, the whole frame
    against the full render on the same path, reconstruction, quality, and
    the asynchronous display beside the full render's frame rate."""
    env, version, settings = run["environment"], run["environment"]["version"], run["settings"]
    side = max(settings["sides"])
    rows = [r for r in run["runs"] if r["width"] == side]
    lines = [
        RENDER_CACHE_BEGIN,
        "",
        f"The committed run (`raycache bench render-cache --{run['size']}`, its "
        f"[results.json](render-cache-run/results.json)): {env['cpu_model']}, {env['worker_threads']} threads, "
        f"{lanes_text(version)}, {side}², frames 2–{settings['frames']} of each scene's path, "
        f"{settings['render_cache']['budget'] * 100:.0f} % of the pixels traced a frame, "
        f"{env['started_at'][:10]}, commit {commit_text(version)}. × is the full render's mean frame time "
        "over the Render Cache's (above 1× the Render Cache is faster; 95 % CI). "
        "Generated by `scripts/doc-figures.py`.",
        "",
        "| scene | full render ms | × with reflections reshaded (the default) | × with reflections reprojected | "
        "reconstruction ms | reshading ms | mean PSNR dB (SSIM), reshaded | async display fps: every sample "
        "reshaded / within the budget | full render fps |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]

    def speedup(variant):
        sp = variant["speedup_vs_full"]
        ci = f" ({sp['ci95_low']:.2f}–{sp['ci95_high']:.2f})" if sp["ci95_low"] is not None else ""
        return sp["speedup"], f"{sp['speedup']:.2f}×{ci}"

    reshaded, reprojected = [], []
    for r in rows:
        v = r["variants"]["reshade"]
        s = v["summary"]
        full_ms = r["full"]["summary"]["ms"]["median"]
        (shaded, shaded_cell), (projected, projected_cell) = speedup(v), speedup(r["variants"]["reproject"])
        reshaded.append(shaded)
        reprojected.append(projected)
        a = r["async"]
        lines.append(
            f"| {r['scene']} | {full_ms:.1f} | {shaded_cell} | {projected_cell} | "
            f"{s['reconstruction_ms']['median']:.1f} | {s['reshade_ms']['median']:.1f} | "
            f"{s['psnr_db']['mean']:.1f} ({s['ssim']['mean']:.3f}) | "
            f"{a['async_every_frame']['display_fps']:.1f} / {a['async_budget']['display_fps']:.1f} | "
            f"{1000.0 / full_ms:.1f} |")
    lines += ["", END]
    phrase = (f"{min(reshaded):.2f}–{max(reshaded):.2f}× the full render at {side}² with reflections reshaded "
              f"(the default), {min(reprojected):.2f}–{max(reprojected):.2f}× with them reprojected")
    return "\n".join(lines), phrase


def render_cache_goal_rows(run):
    """The Render Cache rows of performance.md's "Goals at a glance", whole,
    each keyed by its first two cells: every figure from the same run as the
    block."""
    env, targets = run["environment"], run["goal_targets"]
    sides = sorted(run["settings"]["sides"])
    side = sides[-1]
    at = {w: [r for r in run["runs"] if r["width"] == w] for w in sides}
    level = lanes_text(run["environment"]["version"])

    def per_scene(rows, value, fmt):
        return ", ".join(f"{r['scene']} {fmt(value(r))}" for r in rows)

    def reconstruction(r):
        return r["variants"]["reshade"]["summary"]["reconstruction_ms"]["median"]

    big = at[side]
    limit = targets["reconstruction_ms_1024"] if side == 1024 else None
    recon = per_scene(big, reconstruction, lambda v: f"{v:.1f} ms")
    if len(sides) > 1:
        recon += f"; {sides[0]}²: " + per_scene(at[sides[0]], reconstruction, lambda v: f"{v:.1f}")
    recon_met = "–" if limit is None else ("yes" if all(reconstruction(r) <= limit for r in big) else "no")

    def psnr(r):
        return r["variants"]["reshade"]["summary"]["psnr_db"]["mean"]

    psnr_met = sum(1 for r in big if psnr(r) >= targets["mean_psnr_db"])

    def fps(r):
        return 1000.0 / r["variants"]["reshade"]["summary"]["ms"]["median"]

    fps_met = sum(1 for r in big if fps(r) >= targets["end_to_end_fps"] and psnr(r) >= targets["mean_psnr_db"])

    def faster(r):
        return r["variants"]["reshade"]["speedup_vs_full"]["speedup"]

    faster_met = sum(1 for r in big if (r["variants"]["reshade"]["speedup_vs_full"]["ci95_low"] or 0) > 1.0)
    room = next((r for r in big if r["scene"] == "room"), big[0])
    a = room["async"]
    display = a["async_budget"]["display_fps"]
    gains = [g for g in run["goals"] if g["goal"].startswith("re-evaluated reflections") and g["where"].endswith(f"{side}²")]
    gain_values = [float(g["measured"].split(" dB")[0]) for g in gains]
    gain_met = sum(1 for g in gains if g["met"])
    where = f"{side}², {level}"
    return {
        "| Render Cache | a frame faster than the full render": (
            f"| Render Cache | a frame faster than the full render, reflections reshaded ({where}) | "
            f"{per_scene(big, faster, lambda v: f'{v:.2f}×')} | {faster_met} of {len(big)} |"),
        "| Render Cache | reconstruction": (
            f"| Render Cache | reconstruction ≤ {targets['reconstruction_ms_1024']:g} ms at 1024² "
            f"(≤ {targets['reconstruction_ms_512']:g} ms at 512²) | {recon} | {recon_met} |"),
        "| Render Cache | mean PSNR": (
            f"| Render Cache | mean PSNR of frames 2–{run['settings']['frames']} ≥ {targets['mean_psnr_db']:g} dB "
            f"at 5 % of the pixels a frame | {per_scene(big, psnr, lambda v: f'{v:.1f} dB')} | "
            f"{psnr_met} of {len(big)} |"),
        "| Render Cache | a whole frame": (
            f"| Render Cache | a whole frame ≤ {1000.0 / targets['end_to_end_fps']:.1f} ms "
            f"({targets['end_to_end_fps']:g} fps) with mean PSNR ≥ {targets['mean_psnr_db']:g} dB | "
            f"{per_scene(big, fps, lambda v: f'{v:.1f} fps')} | {fps_met} of {len(big)} |"),
        "| Render Cache | the async display": (
            f"| Render Cache | the async display on `room` ≥ {targets['end_to_end_fps']:g} fps while the tracer "
            f"feeds samples (bench, no window) | {display:.1f} fps (every sample reshaded: "
            f"{a['async_every_frame']['display_fps']:.1f}; full frames {1000.0 / room['full']['summary']['ms']['median']:.1f}) | "
            f"{'yes' if display >= targets['end_to_end_fps'] else 'no'} |"),
        "| Render Cache | re-evaluated reflections": (
            f"| Render Cache | re-evaluated reflections ≥ {targets['mirror_gain_db']:g} dB better on mirror pixels | "
            + (f"+{min(gain_values):.1f} to +{max(gain_values):.1f} dB" if gain_values else "not measured")
            + f" | {gain_met} of {len(gains)} |"),
    }


def load_full_run():
    """docs/full-run/'s experiments this script reads, and run.json."""
    if not os.path.isdir(FULL_RUN):
        sys.exit("doc-figures: docs/full-run/ is missing: copy a `raycache bench all --full` run in with "
                 "scripts/copy-sample-report.py RESULTS_DIR full")
    run = {}
    for name in ("table-5.1", "table-5.2", "table-5.3", "fill-rate", "dynamic", "grids", "run"):
        path = os.path.join(FULL_RUN, "run.json" if name == "run" else os.path.join(name, "results.json"))
        if not os.path.isfile(path):
            sys.exit(f"doc-figures: {os.path.relpath(path, ROOT)} is missing: copy the whole run in with "
                     "scripts/copy-sample-report.py RESULTS_DIR full")
        with open(path, encoding="utf-8") as f:
            run[name] = json.load(f)
    return run


def commit_text(version):
    """A build's commit, short, and whether it had uncommitted changes."""
    commit = version["git_commit"]
    return commit[:7] + (" with uncommitted changes" if commit.endswith("-dirty") else "")


def lanes_text(version):
    """The lane level a run used, and Embree's bound when it had one (runs
    recorded before raycache reported it say nothing of Embree)."""
    embree = version.get("embree_instructions", "the processor's widest")
    return version["lanes"] + ("" if embree == "the processor's widest" else f"; Embree {embree}")


def provenance(experiment, size=None):
    """Machine, threads, lane level, image size, date and commit of one experiment."""
    env, version = experiment["environment"], experiment["environment"]["version"]
    return (f"{env['cpu_model']}, {env['worker_threads']} threads, {lanes_text(version)}, "
            + (f"{size}, " if size else "") + f"{env['started_at'][:10]}, commit {commit_text(version)}")


def plural(n, word):
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def side(width, height):
    return f"{width}²" if width == height else f"{width}×{height}"


def wrap(text, width=118):
    """`text` as lines of at most `width` characters, never starting a line
    with what Markdown would read as a list item, quote or heading."""
    lines, line = [], ""
    for word in text.split(" "):
        starts_block = re.fullmatch(r"[-+*>#=]|\d+[.)]", word) is not None
        if line and len(line) + 1 + len(word) > width and not starts_block:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return "\n".join(lines + [line])


def speedup_cell(m):
    """A speed-up with its 95 % interval when the run has one."""
    s = x(m["speedup"])
    if m.get("ci95_low") is None:
        return s
    tail = ", no measurable difference" if m["no_measurable_difference"] else ""
    return f"{s} (95 % CI {m['ci95_low']:.2f}–{m['ci95_high']:.2f}{tail})"


def still(row, key):
    """The still-camera speed-up of variant `key` of a table row; None when
    the build could not run it."""
    v = row["variants"].get(key)
    return v["still"]["speedup_vs_standard"] if v and v.get("available") and v.get("still") else None


def documents_speedups(table):
    return {r["label"]: r["speedup"] for r in table["documents"]["rows"]}


def table_row(table, scene):
    return next((r for r in table["rows"] if r["scene"] == scene), None)


def tables_figures(run):
    """The block after "CCT against uncached" (Tables 5.1-5.3), the goals rows
    of CCT against the documents' figures and of CDCT on reflective-32, and
    README.md's CDCT row (status, figure)."""
    t51, t52, t53 = run["table-5.1"], run["table-5.2"], run["table-5.3"]

    def ranges(table):
        rows = [r for r in table["rows"] if still(r, "cct")]
        if not rows:
            sys.exit(f"doc-figures: docs/full-run/{table['experiment']} has no CCT speed-up (not run in that build?)")
        docs = documents_speedups(table)
        measured = span([still(r, "cct")["speedup"] for r in rows])
        documents = span([docs[r["label"]] for r in rows if r["label"] in docs])
        return f"{rows[0]['scene']}…{rows[-1]['label']}", measured, documents

    hybrid, hybrid_x, hybrid_docs = ranges(t51)
    plain, plain_x, plain_docs = ranges(t52)
    diffuse = next(r for r in t53["rows"] if r["label"] == "Diffuse")
    reflective = next(r for r in t53["rows"] if r["label"] == "Reflective")

    def documents_53(row, key):
        fps = row["variants"][key]["documents_fps"]
        return fps / row["variants"]["standard"]["documents_fps"] if fps else None

    parity = [k for k in reflective["variants"] if k.startswith("cdct-") and k != "cdct-improved"]
    parity_x = span([still(reflective, k)["speedup"] for k in parity if still(reflective, k)])
    parity_docs = span([documents_53(reflective, k) for k in parity if documents_53(reflective, k)])
    improved = still(reflective, "cdct-improved")
    s51, s53 = t51["settings"], t53["settings"]
    text = (f"The documents' tables at their sizes (`{run['run']['command']}`, "
            f"[findings](results-sample-full.md#findings-at-a-glance); "
            f"{provenance(t51, side(s51['width'], s51['height']))}; generated by `scripts/doc-figures.py` from "
            f"`docs/full-run/`), CCT filled against uncached: {hybrid_x} over {hybrid} in the hybrid pipeline "
            f"(Table 5.1, documents {hybrid_docs}), {plain_x} over {plain} (Table 5.2, documents {plain_docs}), "
            f"{x(still(reflective, 'cct')['speedup'])} on Reflective at {side(s53['width'], s53['height'])} "
            f"(Table 5.3, documents {x(documents_53(reflective, 'cct'))}); there improved CDCT "
            f"{x(still(diffuse, 'cdct-improved')['speedup'])} on Diffuse and {x(improved['speedup'])} on Reflective, "
            f"CDCT parity {parity_x} on Reflective (documents {parity_docs}).")
    block = "\n".join([TABLES_BEGIN, wrap(text), END])

    def goal(table, scene, start, where):
        docs = documents_speedups(table)[scene.split("-")[-1]]
        row = table_row(table, scene)
        m = still(row, "cct") if row else None
        figure = f"{speedup_cell(m)} in `bench {table['experiment']}`{where}" if m else "not in this run"
        met = "–" if m is None else ("yes" if m["speedup"] >= docs else "no")
        return f"{start} {x(docs)} | {figure} | {met} |"

    rows = {
        "| CCT | filled grid-32 ≥ the documents'": goal(
            t52, "grid-32", "| CCT | filled grid-32 ≥ the documents'", "; `cct_speed`: the row above"),
        "| CCT | behind-32 in the hybrid pipeline ≥ the documents'": goal(
            t51, "behind-32", "| CCT | behind-32 in the hybrid pipeline ≥ the documents'", ""),
        "| CDCT | improved CDCT ≥": (
            f"| CDCT | improved CDCT ≥ {CDCT_REFLECTIVE:.1f}× uncached on {reflective['scene']} | "
            f"{speedup_cell(improved)} | "
            f"{'yes' if improved['speedup'] >= CDCT_REFLECTIVE else 'no; not reachable here'} |"),
    }
    slower = [r["scene"] for r in (diffuse, reflective) if still(r, "cdct-improved")["speedup"] < 1.0]
    status = ("works" if not slower else "works, slower than uncached" if len(slower) == 2
              else f"works, slower than uncached on {slower[0]}")
    readme = {1: status,
              2: f"{reflective['scene']} at {side(s53['width'], s53['height'])}: {x(improved['speedup'])} uncached"}
    return block, rows, readme


def fill_rate_figures(run):
    """The Fig 5.9 figures: the harness block's sentence, the goals row of
    the protocol and README.md's harness figure."""
    fill = run["fill-rate"]
    series = sorted(fill["series"], key=lambda s: s["resolution"])
    docs = {r["label"]: r["invalid-after-frame-1"] for r in fill["documents"]["rows"]}
    invalid = [s["invalid_percent_before_frame"][1] for s in series]  # before frame 2 = after frame 1
    resolutions = ", ".join(f"{s['resolution']}²" for s in series)
    documents = ", ".join(f"{docs[str(s['resolution'])]:.0f}" for s in series)
    sentence = (f"Fill rate (Fig 5.9), invalid after frame 1 at {resolutions}: "
                f"{', '.join(f'{v:.1f}' for v in invalid)} % (documents {documents} %).")
    faces = fill["visible_fill"]["faces"]
    one_level = next(s for s in series if s["resolution"] == faces)
    traced = 100.0 - one_level["hit_percent"][2]
    filled = fill["visible_fill"]["traced_percent"][2]
    met = ("yes" if traced <= FILL_TRACED else "with the visible-surface fill" if filled <= FILL_TRACED else "no")
    row = (f"| CCT, moving | Fig 5.9 protocol: ≤ {FILL_TRACED:g} % traced after frame 2 | frame 3: {traced:.1f} % "
           f"({filled:.1f} % with the visible-surface fill) | {met} |")
    last = series[-1]
    readme = (f"fill rate at {last['resolution']}²: {invalid[-1]:.1f} % invalid after frame 1 "
              f"(the documents: {docs[str(last['resolution'])]:.0f} %)")
    return sentence, {"| CCT, moving | Fig 5.9 protocol": row}, {2: readme}


def harness_figures(run):
    """The block of "Experiments harness": the run's wall time and Fig 5.9."""
    info = run["run"]
    seconds = info["elapsed_seconds"]
    if seconds >= 3600:
        took = f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"
    elif seconds >= 60:
        took = f"{seconds // 60} min {seconds % 60} s"
    else:
        took = f"{seconds} s"
    others = f", other processes taking {info['others_cpu_share']} of the CPU time" if info["others_cpu_share"] else ""
    fill = run["fill-rate"]
    sentence, rows, readme = fill_rate_figures(run)
    text = (f"`{info['command']}` took {took}{others} ([full report](results-sample-full.md); "
            f"{provenance(fill)}; generated by `scripts/doc-figures.py` from "
            f"`docs/full-run/`). {sentence}")
    return "\n".join([HARNESS_BEGIN, wrap(text), END]), rows, readme


def per_scene_dynamic(run):
    """Per scene: the CCT speed-up (ratio of the medians), the update's share
    of the CCT frame (median), the lowest PSNR, over frames 1 on, as the
    bench's table has them; and the oracle's counts."""
    def tail(v):
        return v[1:] if len(v) > 1 else v

    out = []
    for s in run["dynamic"]["series"]:
        share = [100.0 * u / c for u, c in zip(s["update_ms"], s["cct_ms"])]
        out.append({
            "scene": s["scene"],
            "speedup": statistics.median(tail(s["uncached_ms"])) / statistics.median(tail(s["cct_ms"])),
            "share": statistics.median(tail(share)),
            "psnr": min(tail(s["psnr_db"])),
            "oracle": s["oracle"],
        })
    return out


def needless(o):
    """Needless drops over the texels that really changed; None when nothing changed."""
    return o["needless"] / o["changed"] if o["changed"] else None


def needless_range(scenes, protocol):
    ratios = [needless(s["oracle"][protocol]) for s in scenes if s["oracle"][protocol]["changed"]]
    return f"{min(ratios):.1f}–{max(ratios):.1f}×" if ratios else "no change"


def needless_met(s, protocol):
    return s["oracle"][protocol]["needless"] <= DYNAMIC_NEEDLESS * s["oracle"][protocol]["changed"]


def dynamic_figures(run):
    """The block of performance.md's "Dynamic scenes", its goals rows and
    README.md's animated scenes row."""
    dyn = run["dynamic"]
    settings, scenes = dyn["settings"], per_scene_dynamic(run)
    lowest = min(scenes, key=lambda s: s["psnr"])
    others = [s["psnr"] for s in scenes if s is not lowest]
    stale = {s["scene"]: s["oracle"]["as_timed"]["stale"] + s["oracle"]["coarse"]["stale"] for s in scenes}
    timed_range = needless_range(scenes, "as_timed")
    worst = max(((needless(s["oracle"]["coarse"]), s["scene"]) for s in scenes if s["oracle"]["coarse"]["changed"]),
                default=(0.0, "none"))
    stale_text = ("0 stale texels on every scene" if not any(stale.values()) else
                  "stale texels: " + ", ".join(f"{n} on {scene}" for scene, n in stale.items() if n))
    sides = side(settings["width"], settings["height"])
    frames = plural(settings["frames"], "frame")
    shares = f"{min(s['share'] for s in scenes):.1f}–{max(s['share'] for s in scenes):.1f} %"
    speedups = ", ".join(f"{x(s['speedup'])}{' uncached' if i == 0 else ''} on {s['scene']}"
                         for i, s in enumerate(scenes))
    coarse = f"{settings['oracle_coarse_resolution']}² faces: up to {worst[0]:.1f}× on {worst[1]}"
    text = (f"`raycache bench dynamic --{dyn['size']} --threads {dyn['environment']['worker_threads']}` "
            f"(in the committed `bench all` run, [its tables]({DYNAMIC_ANCHOR}); {provenance(dyn, sides)}; generated "
            f"by `scripts/doc-figures.py` from `docs/full-run/`): {frames} from t = 0, still camera, uncached and CCT "
            f"rendering each frame in turn; medians over frames 1–{settings['frames'] - 1}: CCT {speedups}; the "
            f"update {shares} of the CCT frame; PSNR against uncached at least {lowest['psnr']:.1f} dB "
            f"({lowest['scene']}), {min(others):.1f}–{max(others):.1f} dB elsewhere. The invalidation oracle (same "
            f"run; deterministic counts) finds {stale_text}, and needless drops at {timed_range} the texels really "
            f"changed as timed (coarse, {coarse}; "
            "[dynamic-scenes.md](dynamic-scenes.md#invalidation-measured-raycache-bench-dynamic)).")
    block = "\n".join([DYNAMIC_BEGIN, wrap(text), END])

    def count(met, n, unit):
        return "yes" if met == n else "no" if met == 0 else f"on {met} of {n} {unit}"

    timed_met = sum(1 for s in scenes if needless_met(s, "as_timed"))
    coarse_met = sum(1 for s in scenes if needless_met(s, "coarse"))
    over = [f"{s['scene']} {needless(s['oracle']['coarse']):.1f}×" for s in scenes if not needless_met(s, "coarse")]
    coarse_cell = ", ".join(over) if over else f"up to {worst[0]:.1f}×"
    needless_judgement = ("yes" if timed_met == coarse_met == len(scenes)
                          else "yes, as timed" if timed_met == len(scenes)
                          else f"no; {timed_met} of {len(scenes)} as timed")
    cct_met = count(sum(1 for s in scenes if s["speedup"] >= DYNAMIC_CCT), len(scenes), "scenes")
    rows = {
        "| dynamic | every frame": (
            f"| dynamic | every frame ≥ {DYNAMIC_PSNR_DB:g} dB against uncached | lowest {lowest['psnr']:.1f} dB "
            f"({lowest['scene']}) | {'yes' if lowest['psnr'] >= DYNAMIC_PSNR_DB else 'no'} |"),
        "| dynamic | scene update": (
            f"| dynamic | scene update ≤ {DYNAMIC_UPDATE_SHARE:g} % of the frame | "
            f"{shares} (medians) | "
            f"{count(sum(1 for s in scenes if s['share'] <= DYNAMIC_UPDATE_SHARE), len(scenes), 'scenes')} |"),
        "| dynamic | needless drops": (
            f"| dynamic | needless drops ≤ {DYNAMIC_NEEDLESS:g}× the texels that really changed | {timed_range} as "
            f"timed (coarse: {coarse_cell}) | {needless_judgement} |"),
        "| dynamic | CCT ≥": (
            f"| dynamic | CCT ≥ {DYNAMIC_CCT:g}× uncached along the animation | "
            f"{span([s['speedup'] for s in scenes])} | "
            f"{'no; out of reach on these scenes ([below](#dynamic-scenes))' if cct_met == 'no' else cct_met} |"),
    }
    all_slower = all(s["speedup"] < 1.0 for s in scenes)
    none_slower = all(s["speedup"] >= 1.0 for s in scenes)
    readme = {1: ("works, slower than uncached with CCT" if all_slower else "works" if none_slower
                  else "works, CCT slower than uncached on some scenes"),
              2: f"CCT {span([s['speedup'] for s in scenes])} uncached, {sum(stale.values())} stale texels"}
    return block, rows, readme


def oracle_block(run):
    """docs/dynamic-scenes.md's table of the invalidation oracle, with its
    provenance and the judgement of the needless-drops goal."""
    dyn = run["dynamic"]
    settings, scenes = dyn["settings"], per_scene_dynamic(run)
    lines = [
        ORACLE_BEGIN,
        "",
        f"`raycache bench dynamic --{dyn['size']} --threads {dyn['environment']['worker_threads']}` in the committed "
        f"`bench all` run ([its other tables]({DYNAMIC_ANCHOR}), its results.json in `docs/full-run/dynamic/`): "
        f"{provenance(dyn, side(settings['width'], settings['height']))}; "
        f"{plural(settings['oracle_changes'], 'change')}, "
        f"as timed at {settings['oracle_as_timed_side']}², coarse at {settings['oracle_coarse_side']}² with "
        f"{settings['oracle_coarse_resolution']}² faces; the counts are deterministic. "
        "Generated by `scripts/doc-figures.py`.",
        "",
        "| scene | protocol | texels checked | kept | stale | dropped | needless | changed | needless / changed | "
        "texels of moving caching objects | of them kept | of them within 1/255 if all kept |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for protocol, name in (("as_timed", "as timed"), ("coarse", "coarse")):
        for s in scenes:
            o = s["oracle"][protocol]
            ratio = needless(o)
            ratio = "–" if ratio is None else f"**{ratio:.1f}**" if protocol == "as_timed" else f"{ratio:.1f}"
            within = f"{100.0 * o['moved_cube_within_tolerance'] / o['moved_cube']:.1f} %" if o["moved_cube"] else "–"
            lines.append(f"| {s['scene']} | {name} | {o['checked']} | {o['kept']} | {o['stale']} | {o['dropped']} | "
                         f"{o['needless']} | {o['changed']} | {ratio} | {o['moved_cube']} | {o['moved_cube_kept']} | "
                         f"{within} |")

    def over(protocol):
        return [s for s in scenes if not needless_met(s, protocol)]

    timed_range = needless_range(scenes, "as_timed")
    missed = over("as_timed")
    goal = (f"met as timed on every scene ({timed_range})" if not missed else
            f"not met as timed on {', '.join(s['scene'] for s in missed)} ({timed_range})")
    coarse = over("coarse")
    goal += ("; on the coarse protocol too" if not coarse else "; on the coarse protocol " + ", ".join(
        f"{s['scene']} is at {needless(s['oracle']['coarse']):.1f}×" for s in coarse))
    stale = sum(s["oracle"][p]["stale"] for s in scenes for p in ("as_timed", "coarse"))
    lines += [
        "",
        f"- **Goal \"needless ≤ {DYNAMIC_NEEDLESS:g}×\"**: {goal}.",
        f"- {stale} stale texels in both protocols." if stale == 0 else
        f"- **{stale} stale texels**: " + ", ".join(
            f"{s['scene']} {s['oracle']['as_timed']['stale']} as timed, {s['oracle']['coarse']['stale']} coarse"
            for s in scenes) + ".",
        "",
        END,
    ]
    return "\n".join(lines)


def grids_figures(run):
    """The block of performance.md's "Grids", its goals rows of the full run
    and README.md's grids row."""
    grids = run["grids"]
    settings, models = grids["settings"], grids["series"]

    def best(m):
        return min(m["embree_low"]["total_ms"], m["embree_medium"]["total_ms"])

    def ratio(m):  # the grids' time over Embree's best rebuild
        return m["grids"]["total_ms"] / best(m)

    def size(m):
        k = int(re.fullmatch(r"torus (\d+)k", m["model"]).group(1))
        return f"{k // 1000}M" if k >= 1000 and k % 1000 == 0 else f"{k}k"

    tori = sorted((m for m in models if not m["animated"]), key=lambda m: m["triangles"])
    animated = [m for m in models if m["animated"]]
    largest = tori[-1]
    torus_text = ", ".join([f"{ratio(tori[0]):.2f}× Embree's time on torus {size(tori[0])}"]
                           + [f"{ratio(m):.2f}× on {size(m)}" for m in tori[1:]])
    torus_text += f" ({largest['grids']['total_ms']:.1f} against {best(largest):.1f} ms)"
    animated_text = ", ".join(f"{ratio(m):.2f}× on `{m['model']}`" for m in animated)
    agreements = [m["agreement"] for m in models]
    ties = sum(g["ties"] for g in agreements)
    grazes = sum(g["primary_edge_grazes"] + g["shadow_edge_grazes"] for g in agreements)
    mismatches = sum(g["primary_mismatches"] + g["shadow_mismatches"] for g in agreements)
    agreement = ("0 ties, 0 edge grazes and 0 mismatches on every model" if ties == grazes == mismatches == 0 else
                 f"{ties} ties, {grazes} edge grazes and {mismatches} mismatches over the {len(models)} models")
    faster = [m for m in models if ratio(m) < 1.0]
    faster_text = (f"none of the {len(models)} models (no crossover up to {size(largest)} triangles)" if not faster
                   else f"all {len(models)} models" if len(faster) == len(models)
                   else f"{len(faster)} of the {len(models)} models ({', '.join(m['model'] for m in faster)})")
    one_m = next((m for m in tori if m["triangles"] >= 1_000_000), None)
    one_m_text = ("1M triangles are not in this run" if one_m is None else
                  f"1M triangles in {one_m['grids']['total_ms']:.1f} ms against a goal of ≤ {GRIDS_1M_MS:g} ms, "
                  + ("met" if one_m["grids"]["total_ms"] <= GRIDS_1M_MS else "not met"))
    text = (f"`{run['run']['command']}` (the [sample report](results-sample-full.md); "
            f"{provenance(grids, side(settings['side'], settings['side']))}; generated by `scripts/doc-figures.py` "
            f"from `docs/full-run/`), means of {plural(settings['frames'], 'frame')}, grids against the better of "
            f"Embree's LOW and MEDIUM rebuilds every frame: grids take {torus_text}; {animated_text}; "
            f"{agreement}. Goals of this run: faster than Embree rebuilt every frame on {faster_text}; {one_m_text}.")
    block = "\n".join([GRIDS_BEGIN, wrap(text), END])
    ratios = [ratio(m) for m in models]
    met = "yes" if len(faster) == len(models) else "no" if not faster else f"on {len(faster)} of {len(models)} models"
    rows = {
        "| grids | faster than Embree rebuilt every frame": (
            f"| grids | faster than Embree rebuilt every frame | {span(ratios)} Embree's time | {met} |"),
        f"| grids | 1M triangles ≤ {GRIDS_1M_MS:g} ms": (
            f"| grids | 1M triangles ≤ {GRIDS_1M_MS:g} ms | not in this run | – |" if one_m is None else
            f"| grids | 1M triangles ≤ {GRIDS_1M_MS:g} ms | {one_m['grids']['total_ms']:.1f} ms (Embree rebuilt: "
            f"{best(one_m):.1f}) | {'yes' if one_m['grids']['total_ms'] <= GRIDS_1M_MS else 'no'} |"),
    }
    speeds = [1.0 / r for r in ratios]  # README's ×: Embree's time over the grids'
    status = ("works, slower than Embree" if not faster else "works" if len(faster) == len(models)
              else "works, slower than Embree on some models")
    readme = {1: status, 2: f"{span(speeds)} Embree rebuilt every frame, {mismatches} mismatches"}
    return block, rows, readme


def shown(path):
    """`path` as the messages name it: from the checkout's root when inside it."""
    relative = os.path.relpath(path, ROOT)
    return path if relative.startswith("..") else relative


def load_bench_runs(bench_runs, program, required=True):
    """Every run of one standalone benchmark, <bench_runs>/<program>/*.json
    (scripts/record-bench-runs.sh), in file order. None of them: an exit with
    one line when `required`, else an empty list."""
    folder = os.path.join(bench_runs, program)
    files = sorted(glob.glob(os.path.join(folder, "*.json")))
    if not files:
        if not required:
            return []
        sys.exit(f"doc-figures: {shown(folder)}/ is missing or holds no runs: record them with "
                 f"scripts/record-bench-runs.sh --programs {program}")
    runs = []
    for path in files:
        with open(path, encoding="utf-8") as f:
            run = json.load(f)
        if run.get("benchmark") != program:
            sys.exit(f"doc-figures: {os.path.relpath(path, ROOT)} is not a {program} run")
        run["file"] = shown(path)
        runs.append(run)
    return runs


def bench_command(run):
    """The run's command line as the docs quote it: the program under
    build/release/benchmarks/, RAYCACHE_LANES when it was set, no --json."""
    args, kept = shlex.split(run["command"])[1:], []
    while args:
        a = args.pop(0)
        if a == "--json":
            args = args[1:]
        elif not a.startswith("--json="):
            kept.append(a)
    lanes = f"RAYCACHE_LANES={run['lanes_requested']} " if run["lanes_requested"] else ""
    return f"{lanes}build/release/benchmarks/{run['benchmark']} {shlex.join(kept)}"


def same_runs(runs, what):
    """`runs` (of one lane level) after checking that they ran the same
    command on the same machine, the figures of one measurement run."""
    first = runs[0]
    for r in runs[1:]:
        for key, value in (("command", bench_command), ("machine", lambda r: r["environment"]["cpu_model"]),
                           ("threads", lambda r: r["environment"]["worker_threads"])):
            if value(r) != value(first):
                sys.exit(f"doc-figures: {r['file']} differs from {first['file']} in its {key}; {what} must come from "
                         "one recording (scripts/record-bench-runs.sh)")
    return runs


def by_lanes(runs, program, one_command=True):
    """The runs at the processor's default lane level and those at
    RAYCACHE_LANES=avx2; any other level is not quoted. `one_command`: each
    group must be of one command (same_runs)."""
    default = [r for r in runs if not r["lanes_requested"]]
    avx2 = [r for r in runs if r["lanes_requested"] == "avx2"]
    if not default:
        sys.exit(f"doc-figures: docs/bench-runs/{program}/ has no run at the default lane level")
    if not one_command:
        return default, avx2
    return same_runs(default, program), same_runs(avx2, program) if avx2 else []


def runs_provenance(runs):
    """Machine, threads, lane level, size, dates, commits and number of runs."""
    env = runs[0]["environment"]
    dates = sorted({r["environment"]["started_at"][:10] for r in runs})
    commits = sorted({r["git_commit"][:7] + (" with uncommitted changes" if r["dirty"] else "") for r in runs})
    size = f"{runs[0]['settings']['size']}², " if "size" in runs[0]["settings"] else ""
    return (f"{env['cpu_model']}, {plural(env['worker_threads'], 'thread')}, {lanes_text(env['version'])}, {size}"
            f"{dates[0] if len(dates) == 1 else dates[0] + ' to ' + dates[-1]}, commit {', '.join(commits)}, "
            f"{plural(len(runs), 'run')}")


def and_list(items):
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def scene_label(scene):
    """A built-in scene's name, or a scene file's name without its folder and .json."""
    return os.path.splitext(os.path.basename(scene))[0]


def per_scene(runs, scene, value, table="scenes"):
    """`value` of `scene` in the list `table` of every run (the first run's
    scenes are the ones quoted)."""
    out = []
    for r in runs:
        s = next((s for s in r[table] if s["scene"] == scene), None)
        if s is None:
            sys.exit(f"doc-figures: {r['file']} has no scene {scene} (the other runs have it)")
        out.append(value(s))
    return out


def goal_scene(runs, program):
    scenes = runs[0]["settings"]["scenes"]
    if GOAL_SCENE not in scenes:
        sys.exit(f"doc-figures: {runs[0]['file']} has no {GOAL_SCENE}, the scene of {program}'s goals")
    return GOAL_SCENE


def ms_cell(values):
    """Median of the runs' medians (min–max over the runs)."""
    return f"{statistics.median(values):.1f} ({min(values):.1f}–{max(values):.1f})"


def ratio_cell(values):
    return f"{statistics.median(values):.2f}× ({min(values):.2f}–{max(values):.2f})"


def ms_span(values):
    lo, hi = min(values), max(values)
    return f"{lo:.1f}" if f"{lo:.1f}" == f"{hi:.1f}" else f"{lo:.1f}–{hi:.1f}"


def level_name(run):
    return LANE_LEVEL_NAMES.get(run["lane_level"], run["lane_level"])


def at_most_over_runs(values, goal):
    """"yes" when every run's value is at most the goal, "at the median" when
    the median is, else "no"."""
    return ("yes" if all(v <= goal for v in values) else "at the median" if statistics.median(values) <= goal
            else "no")


def core_figures(runs):
    """performance.md's "Core frame and floor" table with its provenance,
    the AVX2 paragraph, the core goals rows and README.md's uncached row."""
    default, avx2 = by_lanes(runs, "core_speed")
    first = default[0]
    scenes = first["settings"]["scenes"]

    def median_ms(variant):
        return lambda s: s["variants"][variant]["median_ms"]

    lines = [
        CORE_BEGIN,
        wrap(f"`{bench_command(first)}` (depth {first['settings']['max_depth']}; {runs_provenance(default)}; "
             "generated by `scripts/doc-figures.py` from `docs/bench-runs/core_speed/`): ms per frame as the median "
             "of the runs' medians (min–max over the runs), the ratios of each run's medians likewise:"),
        "",
        "| scene | plain Embree loop | raycache, uncached | ideal frame | floor | uncached / plain loop | "
        "ideal / floor |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for scene in scenes:
        cells = [ms_cell(per_scene(default, scene, median_ms(v))) for v in ("plain_loop", "raycache", "ideal", "floor")]
        cells += [ratio_cell(per_scene(default, scene, lambda s: s[k]))
                  for k in ("uncached_over_plain_loop", "ideal_over_floor")]
        lines.append(f"| {scene_label(scene)} | " + " | ".join(cells) + " |")
    lines += ["", END]
    table = "\n".join(lines)

    def floor_ratios(group, scene):
        return per_scene(group, scene, lambda s: s["ideal_over_floor"])

    level = level_name(first)
    # On a processor without AVX-512 the runs above are at AVX2 already: the
    # RAYCACHE_LANES=avx2 runs are a second sample of the same level.
    avx2_name = "`RAYCACHE_LANES=avx2`" if level == "AVX2" else "AVX2"
    if avx2:
        avx2_scenes = avx2[0]["settings"]["scenes"]
        text = (f"`{bench_command(avx2[0])}` ({runs_provenance(avx2)}; generated by `scripts/doc-figures.py` from "
                f"`docs/bench-runs/core_speed/`), taking turns with the runs above: ideal/floor is "
                + ", ".join(f"{span(floor_ratios(avx2, s))} on {scene_label(s)}" for s in avx2_scenes)
                + f" at `RAYCACHE_LANES=avx2` and "
                + ", ".join(span(floor_ratios(default, s)) for s in avx2_scenes)
                + (" in the runs above, which this processor (no AVX-512) ran at AVX2 as well." if level == "AVX2"
                   else f" at {level} in those runs."))
    else:
        text = "No run at `RAYCACHE_LANES=avx2` is committed in `docs/bench-runs/core_speed/`."
    avx2_block = "\n".join([CORE_AVX2_BEGIN, wrap(text), END])

    scene = goal_scene(default, "core_speed")
    plain = per_scene(default, scene, median_ms("plain_loop"))
    uncached = per_scene(default, scene, median_ms("raycache"))
    over_plain = per_scene(default, scene, lambda s: s["uncached_over_plain_loop"])
    medians = {s: statistics.median(floor_ratios(default, s)) for s in scenes}
    highest = max(max(floor_ratios(default, s)) for s in scenes)

    def floor_judgement(group, name):
        over = [scene_label(s) for s in group[0]["settings"]["scenes"]
                if statistics.median(floor_ratios(group, s)) > CORE_FLOOR]
        if over:
            return f"not at {name} on {and_list(over)}"
        every = all(v <= CORE_FLOOR for s in group[0]["settings"]["scenes"] for v in floor_ratios(group, s))
        return f"at {name}" if every else f"at {name}, at the median"

    judgement = floor_judgement(default, level)
    avx2_text = ""
    if avx2:
        judgement += "; " + floor_judgement(avx2, avx2_name)
        avx2_text = f"; at {avx2_name} " + ", ".join(
            f"{scene_label(s)} {x(statistics.median(floor_ratios(avx2, s)))}" for s in avx2[0]["settings"]["scenes"])
    if judgement == f"at {level}" + (f"; at {avx2_name}" if avx2 else ""):
        judgement = "yes"
    rows = {
        f"| core | uncached {GOAL_SCENE} ≤": (
            f"| core | uncached {scene} ≤ {CORE_PLAIN:g}× the time of a plain Embree Whitted loop | "
            f"{statistics.median(over_plain):.2f}× ({statistics.median(uncached):.1f} ms a frame) | "
            f"{at_most_over_runs(over_plain, CORE_PLAIN)} |"),
        "| core | ideal frame ≤": (
            f"| core | ideal frame ≤ {CORE_FLOOR:g}× the floor | "
            + ", ".join(f"{scene_label(s)} {x(m)}" for s, m in medians.items())
            + f" (medians; single runs up to {x(highest)}){avx2_text} ([below](#core-frame-and-floor)) | "
            f"{judgement} |"),
    }
    speedup = statistics.median(plain) / statistics.median(uncached)
    readme = {1: "works" if speedup >= 1.0 else "works, slower than a plain Embree Whitted loop",
              2: f"{scene}: {speedup:.1f}× a plain Embree Whitted loop ({statistics.median(uncached):.1f} against "
                 f"{statistics.median(plain):.1f} ms)"}
    return table, avx2_block, rows, readme


def cct_figures(runs):
    """performance.md's paragraph of "CCT against uncached" (cct_speed), its
    goals rows and README.md's two CCT rows."""
    default, _ = by_lanes(runs, "cct_speed")
    first = default[0]
    settings = first["settings"]
    scenes = settings["scenes"]

    def still(scene, key):
        return per_scene(default, scene, lambda s: s["still"][key])

    def path(scene, key):
        return per_scene(default, scene, lambda s: s["path"][key])

    def still_ms(scene, variant):
        return per_scene(default, scene, lambda s: s["still"][variant]["median_ms"])

    def bold(scene, text):
        return f"**{text}**" if scene == GOAL_SCENE else text

    def miss(scene):
        costs = [c for c in path(scene, "miss_over_plain_trace") if c is not None]
        return span(costs) if costs else "–"

    still_text = ", ".join(
        f"{scene_label(s)} {bold(s, span(still(s, 'speedup')))} (uncached {ms_span(still_ms(s, 'uncached'))} ms, "
        f"CCT {ms_span(still_ms(s, 'cct'))}; the ideal cache bounds it at {span(still(s, 'ideal_speedup'))})"
        for s in scenes)
    path_text = ", ".join(f"{scene_label(s)} {span(path(s, 'speedup'))}" for s in scenes)
    miss_text = ", ".join(f"{miss(s)}{' the traced tree it replaces' if i == 0 else ''} on {scene_label(s)}"
                          for i, s in enumerate(scenes))
    text = (f"`{bench_command(first)}` (depth {settings['max_depth']}; {runs_provenance(default)}; generated by "
            "`scripts/doc-figures.py` from `docs/bench-runs/cct_speed/`), speed-ups over uncached from each run's "
            f"medians, min–max over the runs. Still camera, caches filled: {still_text}. Along the orbit (1° a "
            f"frame, {plural(settings['path_frames'], 'frame')} from empty caches, `always`): {path_text}; a miss "
            f"costs {miss_text}, and the default `--cache-policy auto` stands such cubes aside.")
    block = "\n".join([CCT_BEGIN, wrap(text), END])

    scene = goal_scene(default, "cct_speed")
    speedups, bounds = still(scene, "speedup"), still(scene, "ideal_speedup")
    reached = sum(1 for v in speedups if v >= CCT_FILLED)
    filled_met = ("yes" if reached == len(speedups) else f"in {reached} of {len(speedups)} runs" if reached
                  else "no; within the bound" if statistics.median(bounds) >= CCT_FILLED
                  else "no; above what an ideal cache reaches")
    miss_costs = {s: [c for c in path(s, "miss_over_plain_trace") if c is not None] for s in scenes}
    cheap = [scene_label(s) for s, c in miss_costs.items() if c and statistics.median(c) <= CCT_MISS]
    miss_met = ("yes" if len(cheap) == len(scenes) and all(v <= CCT_MISS for c in miss_costs.values() for v in c)
                else "no" if not cheap else f"on {', '.join(cheap)}")
    rows = {
        f"| CCT | filled {GOAL_SCENE} ≥ {CCT_FILLED:.1f}×": (
            f"| CCT | filled {scene} ≥ {CCT_FILLED:.1f}× uncached | {span(speedups)} (`cct_speed`); an ideal cache "
            f"bounds it at {span(bounds)} | {filled_met} |"),
        "| CCT | a miss ≤": (
            f"| CCT | a miss ≤ {CCT_MISS:g}× the trace it replaces | "
            + ", ".join(f"{miss(s)} on {scene_label(s)}" for s in scenes) + f" | {miss_met} |"),
    }
    documents = per_scene(default, scene, lambda s: s["still"]["documents_speedup"])[0]
    orbit = path(scene, "speedup")

    def status(values):
        return ("works, slower than uncached" if all(v < 1.0 for v in values) else "works"
                if all(v >= 1.0 for v in values) else "works, slower than uncached in some runs")

    readme_filled = {1: status(speedups), 2: f"{scene}: {span(speedups)} uncached"
                     + (f" (the documents: {x(documents)})" if documents else "")}
    readme_moving = {1: status(orbit), 2: f"{scene}'s orbit: {span(orbit)} uncached"}
    return block, rows, readme_filled, readme_moving


def value_cell(values, form):
    """One value when the runs agree at the precision `form` shows, else the
    median with min–max over the runs."""
    lo, mid, hi = (form.format(v) for v in (min(values), statistics.median(values), max(values)))
    return mid if lo == hi else f"{mid} ({lo}–{hi})"


def generated_from(program):
    return f"generated by `scripts/doc-figures.py` from `docs/bench-runs/{program}/`"


def hybrid_figures(runs):
    """The paragraph of performance.md's "Hybrid pipeline" (hybrid_speed's
    whole frames, part b) and README.md's hybrid row."""
    default, _ = by_lanes(runs, "hybrid_speed")
    first = default[0]
    if not first["whole_frames"]:
        sys.exit(f"doc-figures: {first['file']} has no whole frames: record hybrid_speed with --parts b")

    def frames(scene, value):
        return per_scene(default, scene, value, "whole_frames")

    def ms(variant):
        return lambda f: f[variant]["median_ms"]

    def scene_text(scene):
        raster = frames(scene, lambda f: f["hybrid_opengl_phases"]["raster"]["median_ms"])
        return (f"on {scene} the hybrid frame with the OpenGL G-buffer on llvmpipe takes "
                f"{ms_cell(frames(scene, ms('hybrid_opengl')))} ms against {ms_cell(frames(scene, ms('ray')))} for the "
                f"ray frame, {ratio_cell(frames(scene, lambda f: f['ray_over_hybrid_opengl']))} its speed; the "
                f"llvmpipe raster alone takes {ms_cell(raster)} ms")

    scenes = [f["scene"] for f in first["whole_frames"]]
    parts = [scene_text(scene) for scene in scenes]
    text = (f"`{bench_command(first)}` (no caches; {runs_provenance(default)}; {generated_from('hybrid_speed')}), "
            "medians of the runs' medians (min–max over the runs): " + "; ".join(parts) + ".")
    scene = scenes[0]
    ratios = frames(scene, lambda f: f["ray_over_hybrid_opengl"])
    status = ("works, slower than the ray pipeline" if all(v < 1.0 for v in ratios) else "works"
              if all(v >= 1.0 for v in ratios) else "works, slower than the ray pipeline in some runs")
    readme = {1: status, 2: f"{scene}: {span(ratios)} the ray pipeline"}
    return "\n".join([HYBRID_BEGIN, wrap(text), END]), readme


def moving_cache_figures(runs):
    """The paragraph of performance.md's "CCT along a moving camera"
    (moving_cache): on grid-32 (or the first scene run), each cached
    variant's hits at the path's last frame, mean PSNR, cube memory and
    speed-up over uncached."""
    default, _ = by_lanes(runs, "moving_cache")
    first = default[0]
    frames = first["settings"]["frames"]

    def values(scene, key, value):
        return per_scene(default, scene, lambda s: value(s["variants"][key]))

    def variant(scene, key, label):
        if key not in first["scenes"][0]["variants"]:
            return None
        hits = value_cell(values(scene, key, lambda v: v["frames"][-1]["hit_percent"]), "{:.1f}")
        psnr = values(scene, key, lambda v: v["mean_psnr_db"])
        psnr_text = "identical images" if None in psnr else f"{value_cell(psnr, '{:.2f}')} dB"
        mib = value_cell(values(scene, key, lambda v: v["frames"][-1]["cache_mib"]), "{:.0f}")
        speedup = span(values(scene, key, lambda v: v["speedup"]))
        if key == "cct" and scene == GOAL_SCENE:
            speedup = f"**{speedup}**"
        return f"{label} {hits} %, {psnr_text}, {speedup} in {mib} MiB"

    def scene_text(scene):
        parts = [p for p in (variant(scene, "cct", "CCT"),
                             variant(scene, "cct_multi_res", "multi-resolution cubes"),
                             variant(scene, "cct_from_view", "cubes sized from the view")) if p]
        fills = [values(scene, key, lambda v: v["speedup"]) for key in ("cct_fill", "cct_from_view_fill")
                 if key in first["scenes"][0]["variants"]]
        if fills:
            parts.append(f"with the visible-surface fill {span([v for f in fills for v in f])}")
        return ", ".join(parts)

    scenes = first["settings"]["scenes"]
    scene = GOAL_SCENE if GOAL_SCENE in scenes else scenes[0]
    text = (f"`{bench_command(first)}` ({runs_provenance(default)}; {generated_from('moving_cache')}), {scene}'s "
            f"orbit from empty caches; per variant its hits at frame {frames}, mean PSNR against uncached over frames "
            f"2–{frames}, speed-up over uncached (each run's medians) and cubes' memory, min–max over the runs: "
            f"{scene_text(scene)}.")
    return "\n".join([MOVING_BEGIN, wrap(text), END])


def scene_update_figures(runs):
    """The sentence of performance.md's "Dynamic scenes" and the table of
    docs/dynamic-scenes.md (scene_update_speed)."""
    default, _ = by_lanes(runs, "scene_update_speed")
    first = default[0]
    settings = first["settings"]
    rows = [(v["scene"], v["variant"]) for v in first["variants"]]

    def values(row, value):
        out = []
        for r in default:
            v = next((v for v in r["variants"] if (v["scene"], v["variant"]) == row), None)
            if v is None:
                sys.exit(f"doc-figures: {r['file']} has no {row[0]} {row[1]} (the other runs have it)")
            out.append(value(v))
        return out

    def cell(row, part, unit="ms"):
        return value_cell(values(row, lambda v: v[part][f"median_{unit}"]), "{:.2f}")

    refit, rebuild = ("cloth", "refit, uncached"), ("cloth", "rebuild, uncached")
    for row in (refit, rebuild):
        if row not in rows:
            sys.exit(f"doc-figures: {first['file']} has no {row[0]} {row[1]}")
    shares = {row: statistics.median(values(row, lambda v: v["update_share"]["median_percent"]))
              for row in rows if row != rebuild}
    largest = max(shares, key=shares.get)
    command = f"`{bench_command(first)}` ({runs_provenance(default)}; {generated_from('scene_update_speed')}"
    text = (f"{command}; the table: [dynamic-scenes.md](dynamic-scenes.md#measured-benchmarksscene_update_speed)): "
            f"every update but the cloth's rebuild at most {shares[largest]:.1f} % of the frame ({largest[0]}, "
            f"{largest[1]}: the median over a run's frames, median of the runs); the cloth's refit "
            f"{cell(refit, 'update')} ms against {cell(rebuild, 'update')} ms for a rebuild.")
    block = "\n".join([UPDATE_BEGIN, wrap(text), END])
    summarized = (settings["frames"] - 1) * settings["rounds"]
    lines = [
        UPDATE_TABLE_BEGIN,
        wrap(f"{command}). Variants interleave frame by frame; per run the median over its "
             f"{plural(summarized, 'frame')} (frame 0 of each round left out), here the median of the runs' "
             "medians (min–max over the runs):"),
        "",
        "| scene | variant | update ms | render ms | frame ms | update share of the frame |",
        "|---|---|---|---|---|---|",
    ]
    lines += [f"| {row[0]} | {row[1]} | {cell(row, 'update')} | {cell(row, 'render')} | {cell(row, 'frame')} | "
              f"{cell(row, 'update_share', 'percent')} % |" for row in rows]
    lines += [
        "",
        wrap(f"**Refit**: {cell(refit, 'update')} ms against {cell(rebuild, 'update')} ms for a rebuild at MEDIUM; "
             f"the refitted tree renders in {cell(refit, 'render')} against {cell(rebuild, 'render')} ms."),
        END,
    ]
    return block, "\n".join(lines)


def grids_speed_figures(runs):
    """The paragraph of performance.md's "Grids" (grids_speed, its default
    model and any other recorded) and the goals row of the rays alone."""
    default, _ = by_lanes(runs, "grids_speed", one_command=False)
    models = {}
    for r in default:
        models.setdefault(r["settings"]["model"], []).append(r)
    if GRIDS_SPEED_MODEL not in models:
        sys.exit(f"doc-figures: docs/bench-runs/grids_speed/ has no run on {GRIDS_SPEED_MODEL}, its goal's model")
    main = same_runs(models.pop(GRIDS_SPEED_MODEL), "grids_speed")

    def ms(group, tracer, part="total"):
        return [r[tracer][part]["median_ms"] for r in group]

    rays = [r["rays_over_embree"] for r in main]
    text = (f"`{bench_command(main[0])}` ({runs_provenance(main)}; {generated_from('grids_speed')}), medians of the "
            f"runs' medians (min–max over the runs): {GRIDS_SPEED_MODEL} {ms_cell(ms(main, 'grids'))} against "
            f"{ms_cell(ms(main, 'embree'))} ms for Embree's LOW rebuild and its rays, "
            f"{ratio_cell([r['total_over_embree'] for r in main])} Embree's time; the rays alone take "
            f"{ratio_cell(rays)} the time of Embree's through the hierarchy it has just built, against a goal of "
            f"{GRIDS_RAYS:g}×.")
    for model, group in sorted(models.items()):
        group = same_runs(group, "grids_speed")
        builds = [b for r in group for b in r["embree"]["build"]["samples_ms"]]
        decided = ", so the ratio there is decided by Embree's build time of the moment" if max(builds) >= 2 * min(
            builds) else ""
        text += (f" `{bench_command(group[0])}` ({plural(len(group), 'run')}, taking turns with those above): "
                 f"{model} {ms_cell(ms(group, 'grids'))} against {ms_cell(ms(group, 'embree'))} ms; Embree's "
                 f"rebuild alone took {ms_span(builds)} ms from round to round{decided}.")
    row = (f"| grids | rays alone within {GRIDS_RAYS:g}× of a prebuilt BVH ({GRIDS_SPEED_MODEL}) | "
           f"{ratio_cell(rays)} (`grids_speed`) | {at_most_over_runs(rays, GRIDS_RAYS)} |")
    return "\n".join([GRIDS_SPEED_BEGIN, wrap(text), END]), {"| grids | rays alone within": row}


def soak_figures(runs):
    """The sentence of performance.md's "Memory and loading" on soak."""
    runs, _ = by_lanes(runs, "soak")
    first = runs[0]
    settings = first["settings"]

    def sample(run, frame):
        return next(s for s in run["samples"] if s["frame"] == frame)

    every, frames = settings["every"], settings["frames"]
    at_every = value_cell([sample(r, every)["resident_kib"] for r in runs], "{:.0f}")
    at_end = value_cell([sample(r, frames)["resident_kib"] for r in runs], "{:.0f}")
    resident = [r["second_half"]["resident_growth_kib"] for r in runs]
    heap = [r["second_half"]["heap_growth_kib"] for r in runs]
    half = first["second_half"]
    flat = "flat" if all(round(v) == 0 for v in resident) else "growing"
    text = (f"`{bench_command(first)}` ({settings['scene']}'s orbit, {settings['technique'].upper()} with "
            f"{settings['cache_res']}² faces; {runs_provenance(runs)}; {generated_from('soak')}): resident memory "
            f"{flat} over the second half, {value_cell(resident, '{:+.0f}')} KiB from frame {half['from_frame']} to "
            f"{half['to_frame']} (the live heap {value_cell(heap, '{:+.0f}')} KiB); {at_every} KiB at frame {every}, "
            f"{at_end} KiB at frame {frames}.")
    return "\n".join([SOAK_BEGIN, wrap(text), END])


def scene_load_figures(runs):
    """The sentence of performance.md's "Memory and loading" on loading
    scenes, the goals row of the loading goal and README.md's meshes row."""
    default, _ = by_lanes(runs, "scene_load_speed")
    first = default[0]

    def seconds(scene):
        return [ms / 1000.0 for ms in per_scene(default, scene, lambda s: s["load"]["median_ms"])]

    def triangles(scene):
        return f"{per_scene(default, scene, lambda s: s['triangles'])[0] / 1000:.0f}k"

    scenes = first["settings"]["scenes"]
    loads = ", ".join(f"{scene} ({triangles(scene)} triangles) in {value_cell(seconds(scene), '{:.2f}')} s"
                      for scene in scenes)
    text = (f"`{bench_command(first)}` (loading alone, without the ray tracing structures; {runs_provenance(default)}; "
            f"{generated_from('scene_load_speed')}), medians of the runs' medians (min–max over the runs): {loads}.")
    rows, readme = {}, {}
    if LOAD_SCENE in scenes:
        load = seconds(LOAD_SCENE)
        rows["| scenes | the"] = (
            f"| scenes | the {triangles(LOAD_SCENE)}-triangle dragon loads in ≤ {LOAD_SECONDS:g} s | "
            f"{value_cell(load, '{:.2f}')} s | {at_most_over_runs(load, LOAD_SECONDS)} |")
        readme = {2: f"the {triangles(LOAD_SCENE)}-triangle Stanford dragon loads in {statistics.median(load):.2f} s"}
    return "\n".join([LOAD_BEGIN, wrap(text), END]), rows, readme


def cdct_figures(runs):
    """The speed and quality sentences of performance.md's "CDCT"
    (cdct_speed): improved CDCT's speed-up over uncached on Table 5.3's
    scenes, its and uncached's frame times on the goal's scene, and the mean
    PSNR of improved CDCT and CCT along each orbit."""
    default, _ = by_lanes(runs, "cdct_speed", one_command=False)
    speed = [r for r in default if r["speed"]]
    quality = [r for r in default if r["quality"]]
    if not speed or not quality:
        sys.exit("doc-figures: docs/bench-runs/cdct_speed/ needs runs of both --speed-only and --quality-only "
                 "(scripts/record-bench-runs.sh --programs cdct_speed)")
    speed, quality = same_runs(speed, "cdct_speed --speed-only"), same_runs(quality, "cdct_speed --quality-only")

    def row(table, technique):
        return next(v for v in table["variants"] if v["technique"] == technique)

    def improved(table):
        """The improved CDCT with every change on: the last of the changes switched on one by one."""
        return table["improvements_one_by_one"][-1]

    def speed_values(scene, technique, key):
        return per_scene(speed, scene, lambda t: row(t, technique)[key], "speed")

    def psnr(scene, technique):
        def value(table):
            return (improved(table) if technique == "cdct" else row(table, technique))["mean_psnr_db"]
        values = per_scene(quality, scene, value, "quality")
        return "identical" if None in values else value_cell(values, "{:.2f}")

    s, q = speed[0]["speed"][0], quality[0]["quality"][0]
    speed_scenes = [t["scene"] for t in speed[0]["speed"]]
    quality_scenes = [t["scene"] for t in quality[0]["quality"]]
    # The frame times of the scene of the CDCT goal, else of the last scene.
    timed = CDCT_GOAL_SCENE if CDCT_GOAL_SCENE in speed_scenes else speed_scenes[-1]

    def speedup(scene):
        text = f"**{ratio_cell(speed_values(scene, 'cdct', 'speedup_vs_uncached'))}** on {scene}"
        if scene != timed:
            return text
        return (f"{text} ({ms_cell(speed_values(scene, 'cdct', 'median_ms'))} against "
                f"{ms_cell(speed_values(scene, 'none', 'median_ms'))} ms)")

    # The quality run's options alone: the same program as the speed run's.
    options = shlex.join(shlex.split(bench_command(quality[0]))[1:])
    runs_text = runs_provenance(speed).replace(plural(len(speed), "run"), f"{plural(len(speed), 'run')} of each")
    text = (f"`{bench_command(speed[0])}` and `{options}` ({runs_text}; {generated_from('cdct_speed')}), medians of "
            f"the runs' medians (min–max over the runs): {side(s['width'], s['height'])}, {s['face_resolution']}² "
            f"faces, caches filled, improved CDCT against uncached "
            + ", ".join(speedup(scene) for scene in speed_scenes)
            + f"; mean PSNR along the orbits from empty caches ({q['size']}², {q['face_resolution']}² faces, frames "
            f"2–{q['frames']}): " + ", ".join(f"{scene} {psnr(scene, 'cdct')}" for scene in quality_scenes)
            + " dB, CCT " + ", ".join(psnr(scene, "cct") for scene in quality_scenes) + ".")
    return "\n".join([CDCT_BEGIN, wrap(text), END])


def replace_rows(text, rows, path):
    """`text` with the one line starting with each key of `rows` replaced by
    that key's row."""
    lines = text.split("\n")
    for start, row in rows.items():
        found = [i for i, l in enumerate(lines) if l.startswith(start)]
        if len(found) != 1:
            sys.exit(f"doc-figures: {path} needs exactly one row starting with {start} (has {len(found)})")
        lines[found[0]] = row
    return "\n".join(lines)


def replace_block(text, block, path, begin=BEGIN):
    i = text.find(begin)
    j = text.find(END, i)
    if i < 0 or j < 0:
        sys.exit(f"doc-figures: {path} has no {begin} … {END} block")
    return text[:i] + block + text[j + len(END):]


def row_cells(text, row_start, cells, path):
    """`text` with the table row starting with `row_start` holding `cells`
    ({index: text}; index 0 is the row's first cell)."""
    rows = [l for l in text.split("\n") if l.startswith(row_start)]
    if len(rows) != 1:
        sys.exit(f"doc-figures: {path} needs exactly one row starting with {row_start} (has {len(rows)})")
    parts = rows[0].split(" | ")
    for i, cell in cells.items():
        parts[i] = cell
    return text.replace(rows[0], " | ".join(parts))


def row_phrase(text, row_start, phrase, cell, path):
    """`text` unchanged when the row starting with `row_start` contains
    `phrase`, else with its cell `cell` rewritten to it."""
    row = next((l for l in text.split("\n") if l.startswith(row_start)), None)
    if row is None:
        sys.exit(f"doc-figures: {path} has no row starting with {row_start}")
    return text if phrase in row else row_cells(text, row_start, {cell: phrase}, path)


def regenerate(path, edits, check, failures):
    """Apply `edits` ((what, function of the text) pairs) to the doc at
    `path` and write it; when checking, note instead each part that would
    change."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    new = text
    for what, edit in edits:
        before, new = new, edit(new)
        if check and new != before:
            failures.append(f"{shown(path)}: {what} differs from its source")
    if new != text and not check:
        with open(path, "w", encoding="utf-8") as f:
            f.write(new)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 on a difference")
    parser.add_argument("--bench-runs", default=BENCH_RUNS, metavar="DIR",
                        help="the standalone benchmarks' runs, DIR/<program>/*.json (default docs/bench-runs)")
    parser.add_argument("--docs", default=ROOT, metavar="DIR",
                        help="the tree whose README.md and docs/*.md are written or checked (default this checkout)")
    args = parser.parse_args()
    performance = os.path.join(args.docs, "docs", "performance.md")
    dynamic_scenes = os.path.join(args.docs, "docs", "dynamic-scenes.md")
    readme = os.path.join(args.docs, "README.md")
    full = load_full_run()
    with open(SOURCE, encoding="utf-8") as f:
        block, readme_phrase = figures(json.load(f))
    with open(RENDER_CACHE_SOURCE, encoding="utf-8") as f:
        render_cache_run = json.load(f)
    rc_block, rc_phrase = render_cache_figures(render_cache_run)
    tables_block, tables_rows, cdct_readme = tables_figures(full)
    harness_block, fill_rows, harness_readme = harness_figures(full)
    dynamic_block, dynamic_rows, dynamic_readme = dynamic_figures(full)
    grids_block, grids_rows, grids_readme = grids_figures(full)
    core_table, core_avx2, core_rows, core_readme = core_figures(load_bench_runs(args.bench_runs, "core_speed"))
    cct_block, cct_rows, cct_readme_filled, cct_readme_moving = cct_figures(
        load_bench_runs(args.bench_runs, "cct_speed"))

    # The benchmarks whose runs are recorded later: without runs their
    # blocks, rows and README cells stay as they are.
    not_generated = []
    performance_blocks = [(BEGIN, block), (RENDER_CACHE_BEGIN, rc_block), (TABLES_BEGIN, tables_block),
                          (DYNAMIC_BEGIN, dynamic_block), (GRIDS_BEGIN, grids_block), (HARNESS_BEGIN, harness_block),
                          (CORE_BEGIN, core_table), (CORE_AVX2_BEGIN, core_avx2), (CCT_BEGIN, cct_block)]
    goal_rows = [render_cache_goal_rows(render_cache_run), tables_rows, fill_rows, dynamic_rows, grids_rows,
                 core_rows, cct_rows]
    dynamic_scenes_blocks = [(ORACLE_BEGIN, oracle_block(full))]
    readme_cells = {"| Whitted ray tracing": core_readme, "| CCT, caches filled": cct_readme_filled,
                    "| CCT, camera moving": cct_readme_moving, "| CDCT, parallax-correct": cdct_readme,
                    "| Animated scenes": dynamic_readme, "| Grids for primary": grids_readme,
                    "| Experiments harness": harness_readme}

    def recorded(program):
        runs = load_bench_runs(args.bench_runs, program, required=False)
        if not runs:
            folder = shown(os.path.join(args.bench_runs, program))
            not_generated.append(f"doc-figures: not generated: no runs in {folder} (record them: "
                                 f"scripts/record-bench-runs.sh --programs {program})")
        return runs

    if runs := recorded("hybrid_speed"):
        hybrid_block, readme_cells["| Hybrid pipeline"] = hybrid_figures(runs)
        performance_blocks.append((HYBRID_BEGIN, hybrid_block))
    if runs := recorded("moving_cache"):
        performance_blocks.append((MOVING_BEGIN, moving_cache_figures(runs)))
    if runs := recorded("scene_update_speed"):
        update_block, update_table = scene_update_figures(runs)
        performance_blocks.append((UPDATE_BEGIN, update_block))
        dynamic_scenes_blocks.append((UPDATE_TABLE_BEGIN, update_table))
    if runs := recorded("grids_speed"):
        grids_speed_block, grids_speed_rows = grids_speed_figures(runs)
        performance_blocks.append((GRIDS_SPEED_BEGIN, grids_speed_block))
        goal_rows.append(grids_speed_rows)
    if runs := recorded("soak"):
        performance_blocks.append((SOAK_BEGIN, soak_figures(runs)))
    if runs := recorded("scene_load_speed"):
        load_block, load_rows, load_readme = scene_load_figures(runs)
        performance_blocks.append((LOAD_BEGIN, load_block))
        goal_rows.append(load_rows)
        if load_readme:
            readme_cells["| Meshes and glTF"] = load_readme
    if runs := recorded("cdct_speed"):
        performance_blocks.append((CDCT_BEGIN, cdct_figures(runs)))

    def blocks(path, pairs):
        return [(f"the block {begin}", lambda t, b=b, begin=begin: replace_block(t, b, path, begin))
                for begin, b in pairs]

    def rows(table):
        return [(f"the row \"{start}…\"", lambda t, start=start, row=row: replace_rows(t, {start: row}, performance))
                for start, row in table.items()]

    failures = []
    regenerate(performance, blocks(performance, performance_blocks) + [e for t in goal_rows for e in rows(t)],
               args.check, failures)
    regenerate(dynamic_scenes, blocks(dynamic_scenes, dynamic_scenes_blocks), args.check, failures)
    readme_edits = [(f"the row \"{start}…\"", lambda t, start=start, cells=cells: row_cells(t, start, cells, readme))
                    for start, cells in readme_cells.items()]
    readme_edits += [
        ("the row \"| `--cache-policy auto`…\"",
         lambda t: row_phrase(t, "| `--cache-policy auto`", readme_phrase, 2, readme)),
        ("the row \"| Render Cache…\"", lambda t: row_phrase(t, "| Render Cache", rc_phrase, 2, readme)),
    ]
    regenerate(readme, readme_edits, args.check, failures)
    for line in not_generated:
        print(line)
    for failure in failures:
        print(failure, file=sys.stderr)
    if failures:
        print("run scripts/doc-figures.py to write them again", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
