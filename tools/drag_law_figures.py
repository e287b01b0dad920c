#!/usr/bin/env python3
"""Draws the drag-law model's curves of the paper's Fig. 2 and Fig. 3 as PNG charts.

    tools/drag_law_figures.py [OUTDIR] [closure]

Runs `cargo run --release --example drag_law_figures -- OUTDIR closure` when the CSV files are
not in OUTDIR yet (default OUTDIR: postProcessing/dragLawFigures), then writes
OUTDIR/drag_law_porous_media.png (K against phi with Sangani & Acrivos, eq. 17, and Ergun /
Wen & Yu, eq. 18) and OUTDIR/drag_law_sedimentation.png (v/V0 against phi with Richardson &
Zaki, eq. 21, n = 4.65).
"""
import csv
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = list(csv.DictReader(lines))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                          os.path.join(ROOT, "postProcessing", "dragLawFigures"))
    closure = sys.argv[2] if len(sys.argv) > 2 else "paper"
    porous = os.path.join(out, "drag_law_porous_media.csv")
    settling = os.path.join(out, "drag_law_sedimentation.csv")
    if not (os.path.exists(porous) and os.path.exists(settling)):
        subprocess.run(["cargo", "run", "--release", "--example", "drag_law_figures", "--",
                        out, closure], cwd=ROOT, check=True)

    k = read(porous)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.semilogy(k["phi"], k["K_Sangani"], "k-", label="Sangani & Acrivos (eq. 17)")
    ax.semilogy(k["phi"], k["K_Ergun"], "k--", label="Ergun / Wen & Yu (eq. 18)")
    ax.semilogy(k["phi"], k["K_dragLaw"], "o", color="tab:red",
                label=f"drag-law model, h = 2r ({closure})")
    ax.set_xlabel("solid volume fraction φ")
    ax.set_ylabel("K = f_h / (6 π μ r U)")
    ax.set_title("Stokes flow through a simple cubic array (paper Fig. 2)")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "drag_law_porous_media.png"), dpi=120)

    s = read(settling)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(s["phi"], s["RichardsonZaki"], "k-", label="Richardson & Zaki, n = 4.65 (eq. 21)")
    ax.plot(s["phi"], s["v_over_V0"], "o", color="tab:blue",
            label=f"drag-law model, h = 2r ({closure})")
    ax.set_xlabel("solid volume fraction φ")
    ax.set_ylabel("v_m / V_0")
    ax.set_title("Mean sedimentation velocity (paper Fig. 3)")
    ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "drag_law_sedimentation.png"), dpi=120)
    print("wrote", os.path.join(out, "drag_law_porous_media.png"), "and",
          os.path.join(out, "drag_law_sedimentation.png"))


if __name__ == "__main__":
    main()
