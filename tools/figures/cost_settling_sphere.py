#!/usr/bin/env python3
"""Accuracy against cost, direct model: the settlingSphere tutorial's terminal velocity.

    tools/figures/draw cost_settling_sphere [--no-run] [--study DIR] [--out PNG]

Runs the study tools/figures/cost_settling_sphere.toml (`tools/study run --spec …`: one
sphere, d = 2 mm, settling in a 4.5 mm periodic box; r/h = 2.7 to 14.2, the time scheme
Euler, RK3 or EulerRKC, and the step as a multiple of Euler's viscous bound h^2/(6 nu);
26 points; finished points are reused), then reads its results.csv and

- prints every point: n, r/h, scheme, step, the settling velocity at 5 ms (the
  sedimentation monitor), the reference U_Stokes / K(phi) (Sangani & Acrivos), the error,
  steps, wall time and peak memory;
- prints the Pareto front and the cheapest run (wall time) within 1 %, 3 % and 10 %, of
  all and with each time scheme;
- draws docs/figures/cost_settling_sphere.png: |error| against wall time, every point, the
  Pareto front marked.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from figure import (ROOT, arguments, block_cells, cheapest, cost_axes,  # noqa: E402
                    print_front_and_cheapest, run_study, save, study_tool)

SPEC = ROOT / "tools" / "figures" / "cost_settling_sphere.toml"
STUDY = ROOT / "studies" / "settlingSphere-cost"
OUT = ROOT / "docs" / "figures" / "cost_settling_sphere.png"
BOUNDS = (0.01, 0.03, 0.10)
SCHEME = "fsim/timeScheme"
BOX, RADIUS, NU = 4.5e-3, 1e-3, 1e-3    # the tutorial's box side, sphere radius (m), nu


def read(study):
    """The finished points, with n, r/h, the step over Euler's viscous bound and the errors."""
    rows = study_tool.finished_points(study)
    for r in rows:
        r["n"] = block_cells(r["blocks"])[0]
        h = BOX / r["n"]
        r["r_over_h"] = RADIUS / h
        r["step_over_bound"] = r["maxDeltaT"] / (h * h / (6 * NU))
        r["signed"] = (r["sedimentation.settlingVelocity.final"]
                       / r["reference.settlingVelocity"] - 1)
        r["error"] = abs(r["signed"])
    return rows


def describe(r):
    return (f"n = {r['n']} (r/h = {r['r_over_h']:.2f}), {r[SCHEME]}, step "
            f"{r['maxDeltaT']:.3g} s ({r['step_over_bound']:.3g} x h²/6ν): "
            f"{100 * r['signed']:+.2f} %, {r['wall_time']:.1f} s, "
            f"{r['peak_memory_mb']:.1f} MB")


def main(argv=None):
    args = arguments(__doc__, STUDY, OUT).parse_args(argv)
    if not args.no_run:
        run_study(SPEC, args.study)

    rows = sorted(read(args.study), key=lambda r: (r["n"], r[SCHEME], r["maxDeltaT"]))
    print("  n    r/h  scheme     step s      x bound  v (mm/s)  v_ref (mm/s)  error %  "
          "steps  wall s  peak MB")
    for r in rows:
        print(f"{r['n']:3d} {r['r_over_h']:6.2f}  {r[SCHEME]:<9} {r['maxDeltaT']:<11.4g} "
              f"{r['step_over_bound']:6.3g} {1e3 * r['sedimentation.settlingVelocity.final']:9.5f} "
              f"{1e3 * r['reference.settlingVelocity']:12.5f} {100 * r['signed']:+8.3f} "
              f"{r['steps']:6.0f} {r['wall_time']:7.1f} {r['peak_memory_mb']:8.1f}")

    front = print_front_and_cheapest(rows, BOUNDS, describe, "the reference")
    print("\nthe same with each time scheme")
    for scheme in ("Euler", "RK3", "EulerRKC"):
        mine = [r for r in rows if r[SCHEME] == scheme]
        for bound in BOUNDS:
            best = cheapest(mine, bound)
            print(f"  {scheme:<8} {100 * bound:2g} %: {describe(best) if best else 'none'}")

    fig, ax = plt.subplots(figsize=(8.5, 5.6), constrained_layout=True)
    grids = sorted({r["n"] for r in rows})
    colours = dict(zip(grids, ("tab:red", "tab:orange", "tab:green", "tab:blue",
                               "tab:purple", "tab:brown")))
    markers = {"Euler": "o", "RK3": "s", "EulerRKC": "^"}
    for n in grids:
        for scheme, marker in markers.items():
            mine = [r for r in rows if r["n"] == n and r[SCHEME] == scheme]
            if not mine:
                continue
            ax.loglog([r["wall_time"] for r in mine], [100 * r["error"] for r in mine],
                      marker, color=colours[n], ms=7, ls="none",
                      mfc=colours[n] if scheme != "EulerRKC" else "w",
                      label=f"r/h = {mine[0]['r_over_h']:.2f} (n = {n}), {scheme}")
            for r in mine:
                ax.annotate(f"{r['step_over_bound']:.3g}", (r["wall_time"], 100 * r["error"]),
                            xytext=(4, 2), textcoords="offset points", fontsize=6,
                            color="0.35")
    cost_axes(ax, BOUNDS, front)
    ax.set_ylabel("|v − U$_{Stokes}$/K(φ)| / (U$_{Stokes}$/K(φ)) (%)")
    ax.set_title("settlingSphere (direct model): terminal velocity, accuracy against cost\n"
                 "(labels: the step over Euler's viscous bound h²/6ν; grey: 1 %, 3 %, 10 %)",
                 fontsize=10)
    ax.legend(fontsize=7, loc="upper right", ncol=2)
    save(fig, args.out)


if __name__ == "__main__":
    main()
