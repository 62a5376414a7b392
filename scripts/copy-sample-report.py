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
"""
import os
import re
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


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
              f"> on your machine. The other sample: [{other}]({other}).\n\n")
    with open(os.path.join(ROOT, "docs", page), "w", encoding="utf-8") as f:
        f.write(header + body)
    print(f"wrote docs/{page} and its plots in docs/images/{images}/")


if __name__ == "__main__":
    main()
