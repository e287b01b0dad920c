#!/usr/bin/env python3
"""The paper's Fig. 3: the mean sedimentation velocity of a suspension against phi, both models.

    tools/figures/draw fig3_sedimentation [--no-run] [--study DIR] [--draglaw-study DIR]
                                          [--out PNG]

Runs the studies tools/figures/fig3_sedimentation.toml (direct model, r/h = 3) and
fig3_sedimentation_draglaw.toml (drag-law model, 3, 5 and 7 cells per side) with tools/study
(finished points are reused): the sedimentation tutorial's spheres packed at random (fsim's
randomPacking) in a periodic 10 mm cube at phi = 0.05 ... 0.3, three packings (seeds) each,
the same packings for both models. For every point it takes v_m / U_Stokes, the mean settling
velocity in the frame of zero volume flux over the run's second half
(study_references.sedimentation_measure), and for the direct model's points the far-field
(Rotne-Prager-Yamakawa) settling of the same spheres in the same periodic box at the write
times of the second half (periodic_rpy.box_settling): the reference for the box, whose
periodic images hinder the spheres more than an unbounded suspension. It prints every point
and, per phi, each model's mean and standard deviation over the packings beside RPY, the
unbounded random hard-sphere suspension (Abade et al. 2012) and Richardson & Zaki (paper eq.
21, n = 4.65), and draws docs/figures/fig3_sedimentation.png.
"""
import math
import statistics
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyvista as pv  # noqa: E402
from figure import ROOT, arguments, block_cells, run_study, save, study_tool  # noqa: E402

sys.path.insert(0, str(ROOT / "tools"))
import hindered_settling  # noqa: E402
import periodic_rpy  # noqa: E402
import study_references  # noqa: E402

SPEC = ROOT / "tools" / "figures" / "fig3_sedimentation.toml"
SPEC_DRAG = ROOT / "tools" / "figures" / "fig3_sedimentation_draglaw.toml"
STUDY = ROOT / "studies" / "sedimentation-fig3-direct"
STUDY_DRAG = ROOT / "studies" / "sedimentation-fig3-draglaw"
OUT = ROOT / "docs" / "figures" / "fig3_sedimentation.png"
FRACTION = "subModels/injectionModels/spheres/volumeFraction"
SEED = "subModels/injectionModels/spheres/seed"


def rpy_second_half(case):
    """The RPY settling of the case's spheres (over U_Stokes, in the frame of zero volume
    flux) at its write times of the run's second half, averaged: periodic_rpy.box_settling
    along gravity in the block's box."""
    box = study_references.block_extent(case)
    g = study_references.vector(case, "constant/g", "value")
    axis = int(np.argmax(np.abs(g)))
    times = sorted((float(p.name), p) for p in case.iterdir()
                   if p.is_dir() and (p / "particles.vtu").is_file())
    values = []
    for t, folder in times:
        if t > 0 and t >= 0.5 * times[-1][0]:
            cloud = pv.read(folder / "particles.vtu")
            a = float(np.mean(cloud.point_data["d"])) / 2
            values.append(periodic_rpy.box_settling(cloud.points, a, box, axis=axis))
    return sum(values) / len(values)


def read(study, model, rpy):
    """The study's finished points with phi, v_m / U_Stokes, the cells per side and (when
    `rpy`) the RPY settling of the same spheres."""
    rows = []
    for r in study_tool.finished_points(study):
        case = study / r["point"]
        measured = study_references.sedimentation_measure(case)
        rows.append(dict(model=model, target=r[FRACTION], seed=int(r[SEED]),
                         phi=float(measured["phi"]), ratio=float(measured["settlingRatio"]),
                         n=block_cells(r["blocks"])[0], wall=r["wall_time"],
                         rpy=rpy_second_half(case) if rpy else math.nan))
    return rows


def spread(values):
    return (statistics.mean(values), statistics.stdev(values) if len(values) > 1 else 0.0)


def main(argv=None):
    parser = arguments(__doc__, STUDY, OUT)
    parser.add_argument("--draglaw-study", type=Path, default=STUDY_DRAG)
    args = parser.parse_args(argv)
    if not args.no_run:
        run_study(SPEC, args.study)
        run_study(SPEC_DRAG, args.draglaw_study)
    direct = read(args.study, "direct", rpy=True)
    drag = read(args.draglaw_study, "dragLaw", rpy=False)

    print("model    cells  phi target  seed  phi      v_m/U_St  RPY (box)  fsim/RPY  wall s")
    for r in sorted(direct + drag, key=lambda r: (r["model"], r["n"], r["target"], r["seed"])):
        print(f"{r['model']:<8} {r['n']:4d}  {r['target']:<10g} {r['seed']:4d}  "
              f"{r['phi']:.4f}  {r['ratio']:8.4f}  {r['rpy']:9.4f}  "
              f"{r['ratio'] / r['rpy']:8.3f}  {r['wall']:6.1f}")

    targets = sorted({r["target"] for r in direct + drag})
    grids = sorted({r["n"] for r in drag})
    print("\nper phi, mean ± standard deviation over the packings (v_m / U_Stokes)")
    header = ("phi     direct (r/h 3)    RPY, same box     fsim/RPY        "
              + "".join(f"drag law {n}^3        " for n in grids)
              + "hard spheres  R-Z 4.65")
    print(header)
    table = []
    for target in targets:
        mine = [r for r in direct if r["target"] == target]
        phi = statistics.mean(r["phi"] for r in mine) if mine else target
        row = dict(phi=phi, direct=spread([r["ratio"] for r in mine]),
                   rpy=spread([r["rpy"] for r in mine]),
                   ratio=spread([r["ratio"] / r["rpy"] for r in mine]),
                   drag={n: spread([r["ratio"] for r in drag
                                    if r["target"] == target and r["n"] == n])
                         for n in grids})
        table.append(row)
        cells = "".join(f"{m:.3f} ± {s:.3f}     " for m, s in
                        (row["direct"], row["rpy"], row["ratio"]))
        cells += "".join(f"{m:.3f} ± {s:.3f}       " for m, s in row["drag"].values())
        print(f"{phi:.4f}  {cells}{hindered_settling.hard_spheres(phi):.3f}         "
              f"{(1 - phi) ** 4.65:.3f}")

    fig, ax = plt.subplots(figsize=(8.5, 5.8), constrained_layout=True)
    curve = np.linspace(0, 0.32, 200)
    ax.plot(curve, hindered_settling.hard_spheres(curve), "k-", lw=1.8,
            label="random hard spheres, unbounded (Abade et al. 2012)")
    ax.plot(curve, (1 - curve) ** 4.65, "k--", lw=1.2, label="Richardson–Zaki, n = 4.65 (eq. 21)")
    phis = [row["phi"] for row in table]
    ax.errorbar(phis, [row["direct"][0] for row in table], [row["direct"][1] for row in table],
                fmt="o", color="tab:blue", ms=7, capsize=3,
                label="fsim, direct model (r/h = 3), 10 mm periodic box")
    ax.errorbar([p - 0.003 for p in phis], [row["rpy"][0] for row in table],
                [row["rpy"][1] for row in table],
                fmt="s", color="tab:blue", mfc="w", ms=7, capsize=3,
                label="RPY mobility of the same spheres in the same box (far field)")
    colours = dict(zip(grids, ("tab:red", "tab:orange", "tab:brown")))
    for n in grids:
        h_over_d = 10.0 / n / 1.5
        ax.errorbar([p + 0.002 * (n - 5) for p in phis], [row["drag"][n][0] for row in table],
                    [row["drag"][n][1] for row in table], fmt="^", color=colours[n], ms=6,
                    capsize=3, label=f"fsim, drag-law model, {n}³ cells (h = {h_over_d:.2g} d)")
    ax.set_xlim(0, 0.32)
    ax.set_ylim(0, 1.1)
    ax.set_xlabel("solid fraction φ")
    ax.set_ylabel("mean sedimentation velocity $v_m$ / $U_{Stokes}$")
    ax.set_title("Mean sedimentation velocity against φ (paper Fig. 3): three random packings "
                 "per point\n(bars: their standard deviation; frame of zero volume flux; "
                 "Re ≈ 0.1)", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    save(fig, args.out)


if __name__ == "__main__":
    main()
