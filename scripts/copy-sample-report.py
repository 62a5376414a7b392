#!/usr/bin/env python3
"""Copy a `raycache bench` report into docs/ as a sample report.

    scripts/copy-sample-report.py RESULTS_DIR quick|full

Reads RESULTS_DIR/report.md (what `raycache bench all` writes), copies every
plot it shows into docs/images/bench/ (quick) or docs/images/bench-full/
(full) and writes docs/results-sample.md or docs/results-sample-full.md with
- the plots as images under docs/images/…, so they display;
- every other link to a file of the run (results.json, per-experiment pages,
  renders) shown as its path under `results/`, since those files are not
  committed.

A full run is also the source of the figures the docs quote from it
(scripts/doc-figures.py): docs/full-run/ is emptied and receives every
RESULTS_DIR/<experiment>/results.json as docs/full-run/<experiment>/results.json
(but render-cache's: see SKIPPED), and docs/full-run/run.json with what only the
report's header holds: the command and its wall time.
"""
import json
import os
import re
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FULL_RUN = os.path.join(ROOT, "docs", "full-run")
# Experiments whose results.json stays out of docs/full-run/, and why.
SKIPPED = {
    "render-cache": "its per-frame samples make about 2 MB at --full; the docs quote the Render Cache from "
                    "docs/render-cache-run/, a run of its own",
}


def elapsed_seconds(text):
    """Seconds of a wall time as the report writes it (ProgressBar::formatDuration):
    1h02m, 12m11s or 46s."""
    m = re.fullmatch(r"(?:(\d+)h(\d+)m|(\d+)m(\d+)s|(\d+)s)", text)
    if not m:
        sys.exit(f"copy-sample-report: cannot read the wall time {text!r} of report.md")
    h, hm, m_, s, only = m.groups()
    if h is not None:
        return int(h) * 3600 + int(hm) * 60
    if m_ is not None:
        return int(m_) * 60 + int(s)
    return int(only)


def copy_full_run(results, report):
    """docs/full-run/: every experiment's results.json and run.json."""
    produced = re.search(r"^Produced by `([^`]+)` in (\S+?)\. ", report, re.M)
    if not produced:
        sys.exit("copy-sample-report: report.md has no line \"Produced by `…` in …\"")
    finished = re.search(r"^\| finished \|.*other processes used (.+?) of the CPU time", report, re.M)
    if os.path.isdir(FULL_RUN):
        shutil.rmtree(FULL_RUN)
    copied = []
    for name in sorted(os.listdir(results)):
        source = os.path.join(results, name, "results.json")
        if name in SKIPPED or not os.path.isfile(source):
            continue
        os.makedirs(os.path.join(FULL_RUN, name))
        shutil.copyfile(source, os.path.join(FULL_RUN, name, "results.json"))
        copied.append(name)
    run = {
        "command": produced.group(1),
        "elapsed": produced.group(2),
        "elapsed_seconds": elapsed_seconds(produced.group(2)),
        "others_cpu_share": finished.group(1) if finished else None,
        "experiments": copied,
        "not_copied": {name: why for name, why in SKIPPED.items()
                       if os.path.isfile(os.path.join(results, name, "results.json"))},
    }
    with open(os.path.join(FULL_RUN, "run.json"), "w", encoding="utf-8") as f:
        json.dump(run, f, indent=2, ensure_ascii=False)
        f.write("\n")
    print(f"wrote docs/full-run/run.json and the results.json of {', '.join(copied)}")


def main():
    if len(sys.argv) != 3 or sys.argv[2] not in ("quick", "full"):
        sys.exit(__doc__)
    results, size = sys.argv[1], sys.argv[2]
    images = "bench" if size == "quick" else "bench-full"
    page = "results-sample.md" if size == "quick" else "results-sample-full.md"
    other = "results-sample-full.md" if size == "quick" else "results-sample.md"
    with open(os.path.join(results, "report.md"), encoding="utf-8") as f:
        report = f.read()
    os.makedirs(os.path.join(ROOT, "docs", "images", images), exist_ok=True)

    def image(m):
        alt, target = m.group(1), m.group(2)
        if target.startswith(("http:", "https:", "/")) or not target.endswith(".svg"):
            return f"{alt} (`results/{target}`)"
        # Every experiment names its plots alike (speedup.svg): prefix the experiment.
        name = target.replace("/", "-")
        shutil.copyfile(os.path.join(results, target), os.path.join(ROOT, "docs", "images", images, name))
        return f"![{alt}](images/{images}/{name})"

    def link(m):
        text, target = m.group(1), m.group(2)
        if target.startswith(("http:", "https:", "#", "/")):
            return m.group(0)
        return f"`results/{target}`" if text == target else f"{text} (`results/{target}`)"

    body = re.sub(r"!\[([^\]]*)\]\(([^)\s]+)\)", image, report)
    body = re.sub(r"(?<!!)\[([^\]]*)\]\(([^)\s]+)\)", link, body)
    header = (f"> A report written by `raycache bench all --{size}` (`results/report.md`), copied here by\n"
              f"> `scripts/copy-sample-report.py` with its plots (under `docs/images/{images}/`); its machine and\n"
              f"> build are in the table below. Links to files a run writes (results.json, per-experiment pages,\n"
              f"> renders, heat maps) are shown as paths under `results/`; run `scripts/run.sh"
              f"{' --full' if size == 'full' else ''}` to produce them\n"
              f"> on your machine. The other sample: [{other}]({other}).\n"
              + (f"> Its results.json files (but {', '.join(SKIPPED)}'s) are in `docs/full-run/`, the source of\n"
                 "> the figures the other docs quote from this run (`scripts/doc-figures.py`).\n"
                 if size == "full" else "")
              + "\n")
    with open(os.path.join(ROOT, "docs", page), "w", encoding="utf-8") as f:
        f.write(header + body)
    print(f"wrote docs/{page} and its plots in docs/images/{images}/")
    if size == "full":
        copy_full_run(results, report)


if __name__ == "__main__":
    main()
