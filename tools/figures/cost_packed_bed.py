#!/usr/bin/env python3
"""Accuracy against cost, drag-law model: the packedBed tutorial's pressure drop against Ergun.

    tools/figures/draw cost_packed_bed [--no-run] [--study DIR] [--out PNG]

Runs the study tools/figures/cost_packed_bed.toml (`tools/study run --spec …`: 160 beads on
a simple cubic lattice, water up through them at Re = 1; the grid h = 2d or d, deltaT from
25 to 400 µs, the fluid velocity's interpolation `cell` or `cellPoint`, endTime 20 or 50 ms;
40 points; finished points are reused), then reads its results.csv and

- prints every point: cells, h/d, deltaT, interpolation, endTime, the pressure drop (the
  dragLaw monitor's mean over the second half of the run, `measured.pressureDrop`), Ergun's,
  the error, wall time and peak memory;
- prints the Pareto front and the cheapest run (wall time) within 1 %, 3 % and 10 % of Ergun;
- draws docs/figures/cost_packed_bed.png: |error| against wall time, every point, the
  Pareto front marked.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from figure import (ROOT, arguments, block_cells, cost_axes, describe_bed,  # noqa: E402
                    print_front_and_cheapest, run_study, save, study_tool)

SPEC = ROOT / "tools" / "figures" / "cost_packed_bed.toml"
STUDY = ROOT / "studies" / "packedBed-cost"
OUT = ROOT / "docs" / "figures" / "cost_packed_bed.png"
BOUNDS = (0.01, 0.03, 0.10)
INTERPOLATION = "solution/interpolationSchemes/U.water"
D = 1e-3            # the beads' diameter (m)
LENGTH = 4e-3       # the column's side (m)


def read(study):
    """The finished points, with h/d and the signed and absolute relative errors."""
    rows = study_tool.finished_points(study)
    for r in rows:
        r["cells"] = block_cells(r["blocks"])
        r["h_over_d"] = LENGTH / r["cells"][0] / D
        r["signed"] = r["measured.pressureDrop"] / r["reference.pressureDrop"] - 1
        r["error"] = abs(r["signed"])
    return rows


def describe(r):
    return describe_bed(r, INTERPOLATION)


def main(argv=None):
    args = arguments(__doc__, STUDY, OUT).parse_args(argv)
    if not args.no_run:
        run_study(SPEC, args.study)

    rows = sorted(read(args.study), key=lambda r: (-r["h_over_d"], r["endTime"],
                                                    r[INTERPOLATION], r["deltaT"]))
    print("cells     h/d  deltaT   interp.    endTime  dp(fsim)  dp(Ergun)  error %  "
          "steps  wall s  peak MB")
    for r in rows:
        nx, ny, nz = r["cells"]
        print(f"{nx}x{ny}x{nz:<4} {r['h_over_d']:3g}  {r['deltaT']:<8g} {r[INTERPOLATION]:<10} "
              f"{r['endTime']:<7g} {r['measured.pressureDrop']:8.4f} "
              f"{r['reference.pressureDrop']:9.4f} {100 * r['signed']:+8.3f} {r['steps']:6.0f} "
              f"{r['wall_time']:7.2f} {r['peak_memory_mb']:8.1f}")

    front = print_front_and_cheapest(rows, BOUNDS, describe, "Ergun")

    fig, ax = plt.subplots(figsize=(8.5, 5.6), constrained_layout=True)
    colours = {2.0: "tab:orange", 1.0: "tab:blue"}
    markers = {0.02: "o", 0.05: "s"}
    for h in sorted({r["h_over_d"] for r in rows}, reverse=True):
        for end in sorted({r["endTime"] for r in rows}):
            for interp, fill in (("cell", True), ("cellPoint", False)):
                mine = [r for r in rows if r["h_over_d"] == h and r["endTime"] == end
                        and r[INTERPOLATION] == interp]
                if not mine:
                    continue
                ax.loglog([r["wall_time"] for r in mine], [100 * r["error"] for r in mine],
                          markers.get(end, "^"), color=colours.get(h, "tab:green"),
                          mfc=colours.get(h, "tab:green") if fill else "w", ms=7,
                          label=f"h = {h:g} d, endTime {1e3 * end:g} ms, {interp}")
                for r in mine:
                    ax.annotate(f"{1e6 * r['deltaT']:g}", (r["wall_time"], 100 * r["error"]),
                                xytext=(4, 2), textcoords="offset points", fontsize=6,
                                color="0.35")
    cost_axes(ax, BOUNDS, front)
    ax.set_ylabel("|Δp − Δp$_{Ergun}$| / Δp$_{Ergun}$ (%)")
    ax.set_title("packedBed (drag-law model): pressure drop against Ergun, accuracy against "
                 "cost\n(labels: deltaT in µs; grey: 1 %, 3 %, 10 %)", fontsize=10)
    ax.legend(fontsize=7, loc="upper right")
    save(fig, args.out)


if __name__ == "__main__":
    main()
