#!/usr/bin/env python3
"""One chart and one Markdown table of every cross-check case, from the crosscheck.csv files
that tools/crosscheck wrote (docs/crosscheck.md):

    tools/crosscheck_summary.py OUT.png DIR [DIR ...]     # each DIR holds a crosscheck.csv

The chart draws each quantity's fsim–DPMFoam difference as a fraction of its tolerance (a bar
past 1 fails); the table (printed) gives per case the quantities passed, the largest fraction
and both wall times with their ratio.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(folder):
    meta, rows = {}, []
    lines = (Path(folder) / "crosscheck.csv").read_text().splitlines()
    for line in lines:
        if line.startswith("# "):
            key, _, value = line[2:].partition(": ")
            meta[key] = value
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    return meta, rows


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, folders = Path(argv[1]), argv[2:]
    cases = [read(f) for f in folders]
    labels, fractions, colours = [], [], []
    print("| case | quantities within tolerance | largest difference / tolerance | "
          "DPMFoam (serial) | fsimFoam (1 thread) | ratio |")
    print("|---|---|---|---|---|---|")
    for k, (meta, rows) in enumerate(cases):
        worst = 0.0
        for r in rows:
            f = float(r["difference"]) / float(r["tolerance"])
            worst = max(worst, f)
            labels.append(f"{meta['case']}: {r['quantity']}")
            fractions.append(f)
            colours.append(f"C{k}")
        passed = sum(r["pass"] == "True" for r in rows)
        dpm, fsim = float(meta["DPMFoam wall (s)"]), float(meta["fsim wall (s)"])
        print(f"| {meta['case']} | {passed} of {len(rows)} | {worst:.2g} | {dpm:.1f} s | "
              f"{fsim:.2f} s | {dpm / fsim:.0f}× |")
    floor = 1e-4  # smaller differences are drawn at the floor
    fig, ax = plt.subplots(figsize=(9, 0.22 * len(labels) + 1.3), constrained_layout=True)
    y = range(len(labels))[::-1]
    ax.barh(list(y), [max(f, floor) for f in fractions], color=colours)
    ax.axvline(1, color="black", lw=1)
    ax.set_yticks(list(y), labels, fontsize=7)
    ax.set_xscale("log")
    ax.set_xlim(floor / 3, max(2, max(fractions) * 1.3))
    ax.set_xlabel("|fsim − DPMFoam| / tolerance (past 1: fails; below 1e-4: drawn at 1e-4)")
    ax.set_title("fsimFoam against DPMFoam v1912, cross-check tutorials", fontsize=10)
    ax.grid(axis="x", alpha=0.3)
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv)
