#!/usr/bin/env python3
"""Accuracy against cost, sedimentation: both models on one random suspension.

    tools/figures/draw cost_sedimentation [--no-run] [--study DIR] [--draglaw-study DIR]
                                          [--out PNG]

Runs the study tools/figures/cost_sedimentation.toml (the direct model on one suspension of
Fig. 3, phi = 0.1, seed 1: r/h = 2.1 to 6, EulerRKC at three steps, Euler at its bound;
finished points are reused) and takes the drag-law model's points on the same spheres from
Fig. 3's drag-law study (fig3_sedimentation_draglaw.toml, seed 1 at phi = 0.1: 3, 5 and 7
cells per side), then

- finds the reference: no exact value exists for these 57 spheres in their periodic box, so
  it is the direct model's own grid limit, v = v_inf + C h^p fitted by least squares to the
  EulerRKC points at the common step from r/h = 3 on (the fit's p and v_inf are printed, and
  the change of v_inf when the finest point is left out, its uncertainty);
- prints every point (v_m / U_Stokes over the second half, the error against v_inf, wall
  time, peak memory), the Pareto front and the cheapest run within 1 %, 3 % and 10 %, of all
  and with each model;
- draws docs/figures/cost_sedimentation.png: |error| against wall time, every point, the
  Pareto front marked.
"""
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figure import (ROOT, arguments, block_cells, cheapest, cost_axes,  # noqa: E402
                    print_front_and_cheapest, run_study, save, study_tool)

sys.path.insert(0, str(ROOT / "tools"))
import study_references  # noqa: E402
# Fig. 3's drag-law study holds this chart's drag-law points
from fig3_sedimentation import FRACTION, SEED, SPEC_DRAG, STUDY_DRAG  # noqa: E402

SPEC = ROOT / "tools" / "figures" / "cost_sedimentation.toml"
STUDY = ROOT / "studies" / "sedimentation-cost"
OUT = ROOT / "docs" / "figures" / "cost_sedimentation.png"
BOUNDS = (0.01, 0.03, 0.10)
SCHEME = "fsim/timeScheme"
BOX, RADIUS = 0.01, 0.75e-3         # the study's periodic cube and sphere radius (m)
FIT_STEP = 2.8e-4                    # the step of the grid-convergence points


def point(study, r, model):
    case = study / r["point"]
    n = block_cells(r["blocks"])[0]
    return dict(model=model, n=n, r_over_h=RADIUS * n / BOX, scheme=r.get(SCHEME, "Euler"),
                step=r["maxDeltaT"], wall_time=r["wall_time"], peak=r["peak_memory_mb"],
                steps=r["steps"],
                ratio=float(study_references.sedimentation_measure(case)["settlingRatio"]))


def grid_limit(rows):
    """v_inf, p and C of v = v_inf + C (h/r)^p, least squares over p in [0.5, 4] (linear in
    v_inf and C at each p)."""
    h = np.array([1 / r["r_over_h"] for r in rows])
    v = np.array([r["ratio"] for r in rows])
    best = None
    for p in np.linspace(0.5, 4, 351):
        a = np.stack([np.ones_like(h), h ** p], 1)
        coef, *_ = np.linalg.lstsq(a, v, rcond=None)
        residual = float(((a @ coef - v) ** 2).sum())
        if best is None or residual < best[0]:
            best = (residual, float(coef[0]), float(p), float(coef[1]))
    return best[1:]


def describe(r):
    where = (f"r/h {r['r_over_h']:.2f} (n = {r['n']}), {r['scheme']} {1e6 * r['step']:.0f} µs"
             if r["model"] == "direct" else
             f"drag law, {r['n']}³ cells (h = {BOX / r['n'] / (2 * RADIUS):.2g} d)")
    return (f"{where}: {100 * r['signed']:+.2f} %, {r['wall_time']:.1f} s, "
            f"{r['peak']:.1f} MB")


def main(argv=None):
    parser = arguments(__doc__, STUDY, OUT)
    parser.add_argument("--draglaw-study", type=Path, default=STUDY_DRAG)
    args = parser.parse_args(argv)
    if not args.no_run:
        run_study(SPEC, args.study)
        run_study(SPEC_DRAG, args.draglaw_study)
    rows = [point(args.study, r, "direct") for r in study_tool.finished_points(args.study)]
    rows += [point(args.draglaw_study, r, "dragLaw")
             for r in study_tool.finished_points(args.draglaw_study)
             if r[FRACTION] == 0.1 and r[SEED] == 1]

    fit = sorted((r for r in rows if r["model"] == "direct" and r["scheme"] == "EulerRKC"
                  and r["step"] == FIT_STEP and r["r_over_h"] >= 2.99),
                 key=lambda r: r["r_over_h"])
    v_inf, p, c = grid_limit(fit)
    v_less, p_less, _ = grid_limit(fit[:-1])
    print(f"grid limit from {len(fit)} EulerRKC points (r/h {fit[0]['r_over_h']:.2f}-"
          f"{fit[-1]['r_over_h']:.2f}): v_inf = {v_inf:.5f} U_Stokes, p = {p:.2f}; without the "
          f"finest: {v_less:.5f} (p = {p_less:.2f}), {100 * (v_less / v_inf - 1):+.2f} %")
    for r in rows:
        r["signed"] = r["ratio"] / v_inf - 1
        r["error"] = abs(r["signed"])

    print("\nmodel    n    r/h   scheme    step µs  v_m/U_St  error %   steps  wall s  peak MB")
    for r in sorted(rows, key=lambda r: (r["model"], r["n"], r["scheme"], r["step"])):
        r_over_h = f"{r['r_over_h']:5.2f}" if r["model"] == "direct" else "    -"
        print(f"{r['model']:<8} {r['n']:3d} {r_over_h}  {r['scheme']:<9} "
              f"{1e6 * r['step']:6.0f}  {r['ratio']:8.5f}  {100 * r['signed']:+7.2f}  "
              f"{r['steps']:6.0f}  {r['wall_time']:6.1f}  {r['peak']:7.1f}")
    front = print_front_and_cheapest(rows, BOUNDS, describe, "the grid limit")
    print("\nthe same with each model")
    for model in ("direct", "dragLaw"):
        mine = [r for r in rows if r["model"] == model]
        for bound in BOUNDS:
            best = cheapest(mine, bound)
            print(f"  {model:<8} {100 * bound:2g} %: {describe(best) if best else 'none'}")

    fig, ax = plt.subplots(figsize=(8.5, 5.6), constrained_layout=True)
    grids = sorted({r["n"] for r in rows if r["model"] == "direct"})
    colours = dict(zip(grids, plt.cm.viridis(np.linspace(0, 0.9, len(grids)))))
    markers = {("direct", "EulerRKC"): "^", ("direct", "Euler"): "o"}
    for n in grids:
        for (model, scheme), marker in markers.items():
            mine = [r for r in rows if r["model"] == model and r["n"] == n
                    and r["scheme"] == scheme]
            if not mine:
                continue
            ax.loglog([r["wall_time"] for r in mine], [100 * max(r["error"], 1e-4) for r in mine],
                      marker, color=colours[n], ms=7, ls="none",
                      mfc=colours[n] if scheme == "EulerRKC" else "w",
                      label=f"direct, r/h = {mine[0]['r_over_h']:.2f}, {scheme}")
            for r in mine:
                ax.annotate(f"{1e6 * r['step']:.0f}", (r["wall_time"], 100 * max(r["error"], 1e-4)),
                            xytext=(4, 2), textcoords="offset points", fontsize=6, color="0.35")
    drag = sorted((r for r in rows if r["model"] == "dragLaw"), key=lambda r: r["n"])
    ax.loglog([r["wall_time"] for r in drag], [100 * r["error"] for r in drag], "s",
              color="tab:red", ms=7, ls="none", label="drag law (3³, 5³, 7³ cells)")
    for r in drag:
        ax.annotate(f"{r['n']}³", (r["wall_time"], 100 * r["error"]), xytext=(4, 2),
                    textcoords="offset points", fontsize=7, color="tab:red")
    cost_axes(ax, BOUNDS, front)
    ax.set_ylabel("|v$_m$ − v$_\\infty$| / v$_\\infty$ (%)")
    ax.set_title("sedimentation, 57 spheres at φ = 0.1 (both models): accuracy against cost\n"
                 f"(reference: the direct model's grid limit v∞ = {v_inf:.4f} U$_{{Stokes}}$; "
                 "labels: step in µs; grey: 1 %, 3 %, 10 %)", fontsize=10)
    ax.legend(fontsize=7, loc="lower left", ncol=2)
    save(fig, args.out)
    return math.isfinite(v_inf)


if __name__ == "__main__":
    main()
