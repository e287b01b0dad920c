#!/usr/bin/env python3
"""Accuracy against cost, drag-law model: the fluidizedBed tutorial's pressure drop against W / A.

    tools/figures/draw cost_fluidized_bed [--no-run] [--study DIR] [--out PNG]

Runs the study tools/figures/cost_fluidized_bed.toml (`tools/study run --spec …`: 1,080
glass beads, d = 2.5 mm, fluidized by air at 1.875 m/s; the grid h = 4d or 2d, deltaT from
100 to 400 µs, the gas velocity's interpolation `cell` or `cellPoint`, endTime 0.2 or
0.6 s, crossed, and endTime 1.2 s at deltaT 200 µs; 36 points, one at a time on one thread;
finished points are reused), then reads its results.csv and

- prints every point: cells, h/d, deltaT, interpolation, endTime, the pressure drop (the
  dragLaw monitor's mean over the second half of the run, `measured.pressureDrop`), the drag
  on the beads per area (`measured.dragPerArea`), the drop over W / A, the error, steps,
  wall time and peak memory; and the points that failed, with fsimFoam's reason;
- prints the Pareto front and the cheapest run (wall time) within 1 %, 3 % and 10 % of W / A;
- draws docs/figures/cost_fluidized_bed.png: left, |error| against wall time, every point,
  the Pareto front marked; right, the drop over W / A by run length (the chaotic slugging,
  not the grid or the step, moves it).
"""
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import (FixedLocator, FormatStrFormatter,  # noqa: E402
                               NullFormatter)
from figure import (ROOT, arguments, block_cells, cost_axes, describe_bed,  # noqa: E402
                    print_front_and_cheapest, run_study, save, study_tool)

SPEC = ROOT / "tools" / "figures" / "cost_fluidized_bed.toml"
STUDY = ROOT / "studies" / "fluidizedBed-cost"
OUT = ROOT / "docs" / "figures" / "cost_fluidized_bed.png"
BOUNDS = (0.01, 0.03, 0.10)
INTERPOLATION = "solution/interpolationSchemes/U.air"
D = 2.5e-3          # the beads' diameter (m)
WIDTH = 10e-3       # the column's extent in x (m)


def read(study):
    """The finished points, with h/d and the signed and absolute relative errors."""
    rows = study_tool.finished_points(study)
    for r in rows:
        r["cells"] = block_cells(r["blocks"])
        r["h_over_d"] = WIDTH / r["cells"][0] / D
        r["signed"] = r["measured.pressureDrop"] / r["reference.pressureDrop"] - 1
        r["error"] = abs(r["signed"])
    return rows


def failed(study):
    """The points that did not finish: (cells, deltaT, interpolation, endTime, reason), the
    reason shortened from fsimFoam's error (results.csv's `message`)."""
    out = []
    for r in study_tool.read_table(study / "results.csv"):
        if r["status"] == "done":
            continue
        message = str(r.get("message") or r["status"])
        bound = re.search(r"stability bound (\S+) s .*? at t = (\S+) s \(step (\d+)", message)
        packed = re.search(r"at t = (\S+) s: the fluid fraction of cell (\([^)]*\)) is (\S+),",
                           message)
        if bound:
            reason = (f"deltaT exceeds the explicit predictor's bound {float(bound[1]):.3g} s "
                      f"at t = {float(bound[2]):.4g} s (step {bound[3]})")
        elif packed:
            reason = (f"fluid fraction {packed[3]} in cell {packed[2]} at "
                      f"t = {float(packed[1]):.4g} s (cell averaging of the packed bed)")
        else:
            reason = message[-160:]
        out.append((block_cells(r["blocks"]), r["deltaT"], r[INTERPOLATION], r["endTime"],
                    reason))
    return sorted(out, key=lambda f: (f[0], f[1], f[2], f[3]))


def describe(r):
    return describe_bed(r, INTERPOLATION)


def main(argv=None):
    args = arguments(__doc__, STUDY, OUT).parse_args(argv)
    if not args.no_run:
        run_study(SPEC, args.study)

    rows = sorted(read(args.study), key=lambda r: (-r["h_over_d"], r["endTime"],
                                                    r[INTERPOLATION], r["deltaT"]))
    weight = rows[0]["reference.pressureDrop"] if rows else float("nan")
    print(f"W / A = {weight:.2f} Pa (the beads' buoyant weight per cross-section)\n")
    print("cells     h/d  deltaT   interp.    endTime  dp(fsim)  drag/A  dp/(W/A)  error %  "
          "steps  wall s  peak MB")
    for r in rows:
        nx, ny, nz = r["cells"]
        print(f"{nx}x{ny}x{nz:<4} {r['h_over_d']:3g}  {r['deltaT']:<8g} {r[INTERPOLATION]:<10} "
              f"{r['endTime']:<7g} {r['measured.pressureDrop']:8.1f} "
              f"{r['measured.dragPerArea']:7.1f} {1 + r['signed']:8.3f} "
              f"{100 * r['signed']:+8.2f} {r['steps']:6.0f} "
              f"{r['wall_time']:7.2f} {r['peak_memory_mb']:8.1f}")
    broken = failed(args.study)
    if broken:
        print("\nfailed (not drawn):")
        for (nx, ny, nz), dt, interp, end, reason in broken:
            print(f"  {nx}x{ny}x{nz}, deltaT {dt:g} s, {interp}, endTime {end:g} s: {reason}")

    front = print_front_and_cheapest(rows, BOUNDS, describe, "W / A")

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 6.4), width_ratios=[1.6, 1],
                                 constrained_layout=True)
    colours = {4.0: "tab:orange", 2.0: "tab:blue"}
    markers = {0.2: "o", 0.6: "s", 1.2: "^"}
    ends = sorted({r["endTime"] for r in rows})
    for h in sorted({r["h_over_d"] for r in rows}, reverse=True):
        for end in ends:
            for interp, fill in (("cell", True), ("cellPoint", False)):
                mine = [r for r in rows if r["h_over_d"] == h and r["endTime"] == end
                        and r[INTERPOLATION] == interp]
                if not mine:
                    continue
                style = dict(marker=markers.get(end, "D"), ls="none", ms=7,
                             color=colours.get(h, "tab:green"),
                             mfc=colours.get(h, "tab:green") if fill else "w")
                ax.loglog([r["wall_time"] for r in mine], [100 * r["error"] for r in mine],
                          label=f"h = {h:g} d, endTime {end:g} s (mean over "
                                f"{end / 2:g}–{end:g} s), {interp}", **style)
                # right: the signed ratio by run length, the grids and interpolations apart
                shift = (0.06 if h == 2.0 else -0.06) + (0.025 if fill else -0.025)
                bx.plot([ends.index(end) + shift] * len(mine),
                        [1 + r["signed"] for r in mine], **style)
                for r in mine:
                    ax.annotate(f"{1e6 * r['deltaT']:g}", (r["wall_time"], 100 * r["error"]),
                                xytext=(4, 2), textcoords="offset points", fontsize=6,
                                color="0.35")
    cost_axes(ax, BOUNDS, front)
    for axis, ticks in ((ax.xaxis, [4, 6, 10, 20, 40]), (ax.yaxis, [0.5, 1, 2, 3, 5, 10])):
        axis.set_major_locator(FixedLocator(ticks))
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(NullFormatter())
    ax.set_ylabel("|Δp − W/A| / (W/A) (%)")
    ax.set_title("accuracy against cost (labels: deltaT in µs; grey: 1 %, 3 %, 10 %)",
                 fontsize=10)
    bx.axhline(1, color="k", lw=0.8)
    for bound in BOUNDS:
        for sign in (-1, 1):
            bx.axhline(1 + sign * bound, color="0.6", lw=0.8)
    bx.set_xticks(range(len(ends)),
                  [f"{end:g} s\n(mean over\n{end / 2:g}–{end:g} s)" for end in ends])
    bx.set_xlim(-0.5, len(ends) - 0.5)
    bx.set_xlabel("endTime")
    bx.set_ylabel("Δp / (W/A)")
    bx.set_title("the mean drop by run length, every deltaT (grey: ±1, 3, 10 %)", fontsize=10)
    bx.grid(True, axis="y", alpha=0.3)
    fig.suptitle("fluidizedBed (drag-law model): the mean pressure drop against the beads' "
                 f"buoyant weight per area W/A = {weight:.1f} Pa", fontsize=11)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3,
               fontsize=7.5)
    save(fig, args.out)


if __name__ == "__main__":
    main()
