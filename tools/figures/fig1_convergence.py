#!/usr/bin/env python3
"""The paper's Fig. 1 from fsim runs: the error of the direct model's K against the cell size h.

    tools/figures/draw fig1_convergence [--no-run] [--study DIR] [--out PNG]

Runs the study tools/figures/fig1_convergence.toml (`tools/study run --spec …`: the
porousMedia tutorial, a simple cubic array of fixed spheres, at phi = 0.064, 0.125, 0.216 and
r/h from about 2.2 to 16; points finished before are reused), then reads its results.csv and

- prints every point: r/h, K (the median over the last fifth of the run, `measured.K`), the
  exact K (Zick & Homsy's table), the error, wall time and peak memory;
- fits the order p of |error| = C (h/r)^p per phi over r/h >= 4, and over every point,
  leaving out errors below the reference's own precision (half a unit of the last printed
  digit of Zick & Homsy's K: 0.018, 0.012, 0.007 % at phi = 0.064, 0.125, 0.216);
- prints the cheapest run (wall time) within 1 %, 3 % and 10 % of the exact K per phi, and
  the cheapest from which every finer run stays within (the error is not monotone on coarse
  grids);
- runs tools/figures/fig1_convergence_draglaw.toml (the same arrays with the drag-law model
  on 1 to 4 cells per unit cell) and prints its K and errors;
- draws docs/figures/fig1_convergence.png: |error| against h/r with the fitted lines and the
  paper's O(h^1.5), and |error| against wall time with each phi's Pareto front and the
  drag-law points.
"""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from figure import (ROOT, arguments, cheapest, cost_axes, pareto,  # noqa: E402
                    porous_points, run_study, study_tool)

SPEC = ROOT / "tools" / "figures" / "fig1_convergence.toml"
STUDY = ROOT / "studies" / "porousMedia-fig1-convergence"
SPEC_DRAG_LAW = ROOT / "tools" / "figures" / "fig1_convergence_draglaw.toml"
STUDY_DRAG_LAW = ROOT / "studies" / "porousMedia-fig1-draglaw"
OUT = ROOT / "docs" / "figures" / "fig1_convergence.png"
FIT_FROM = 4.0      # r/h from which the order is fitted (the asymptotic range)
BOUNDS = (0.01, 0.03, 0.10)


def read(study):
    """The finished points, with r/h and the signed and absolute relative errors of K."""
    rows = porous_points(study)
    for row in rows:
        row["error"] = abs(row["signed"])
    return rows


def precision(row):
    """Half a unit of the last printed digit of the reference K, relative (Zick & Homsy print
    4 significant figures below phi = 0.3, 3 above)."""
    return (0.0005 if row["phi"] < 0.3 else 0.05) / row["reference.K"]


def fit_order(rows):
    """Least-squares slope of ln|error| against ln(h/r) and its prefactor; NaN below 2
    points."""
    pts = [(math.log(1 / r["r_over_h"]), math.log(r["error"])) for r in rows if r["error"] > 0]
    if len(pts) < 2:
        return math.nan, math.nan
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    slope = (sum((x - mx) * (y - my) for x, y in pts)
             / sum((x - mx) ** 2 for x, _ in pts))
    return slope, math.exp(my - slope * mx)


def main(argv=None):
    args = arguments(__doc__, STUDY, OUT).parse_args(argv)
    if not args.no_run:
        run_study(SPEC, args.study)
        run_study(SPEC_DRAG_LAW, STUDY_DRAG_LAW)
    drag = study_tool.finished_points(STUDY_DRAG_LAW) if STUDY_DRAG_LAW.exists() else []
    for r in drag:
        r["signed"] = r["dragLaw.K.final"] / r["reference.K"] - 1
        r["error"] = abs(r["signed"])

    rows = read(args.study)
    phis = sorted({r["phi"] for r in rows})
    print("phi     n   r/h    K(fsim)   K(exact)  error %   wall s   peak MB")
    for r in sorted(rows, key=lambda r: (r["phi"], r["n"])):
        print(f"{r['phi']:<6g} {r['n']:3.0f} {r['r_over_h']:5.2f} {r['measured.K']:9.4f} "
              f"{r['reference.K']:9.4f} {100 * r['signed']:+8.3f} {r['wall_time']:8.2f} "
              f"{r['peak_memory_mb']:8.1f}")

    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8), constrained_layout=True)
    colours = dict(zip(phis, ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")))
    print(f"\nfitted order p of |error| = C (h/r)^p (paper: 1.5)")
    for phi in phis:
        mine = sorted((r for r in rows if r["phi"] == phi), key=lambda r: r["r_over_h"])
        above = [r for r in mine if r["error"] > precision(r)]
        fine = [r for r in above if r["r_over_h"] >= FIT_FROM]
        p_fine, c_fine = fit_order(fine)
        p_all, _ = fit_order(above)
        left = len(mine) - len(above)
        print(f"  phi = {phi:g}: p = {p_fine:.2f} over r/h >= {FIT_FROM:g} "
              f"({len(fine)} points), {p_all:.2f} over all {len(above)}"
              + (f" ({left} below the reference's precision left out)" if left else ""))
        col = colours[phi]
        x = [1 / r["r_over_h"] for r in mine]
        a.loglog(x, [100 * r["error"] for r in mine], "o-", color=col, lw=1,
                 label=f"φ = {phi:g} (K = {mine[0]['reference.K']:g}), fitted p = {p_fine:.2f}")
        # hollow markers: fsim's K below the exact one
        below = [(1 / r["r_over_h"], 100 * r["error"]) for r in mine if r["signed"] < 0]
        if below:
            a.loglog(*zip(*below), "o", mfc="w", color=col)
        if fine and math.isfinite(p_fine):
            xs = [1 / fine[-1]["r_over_h"], 1 / fine[0]["r_over_h"]]
            a.loglog(xs, [100 * c_fine * v ** p_fine for v in xs], "--", color=col, lw=2,
                     alpha=0.6)
        # the reference's printed digits: half a unit of its last digit
        a.axhline(100 * precision(mine[0]), color=col, ls=":", lw=0.8)
        front = pareto(mine)
        b.loglog([r["wall_time"] for r in mine], [100 * r["error"] for r in mine], "o",
                 color=col, alpha=0.5)
        b.loglog([r["wall_time"] for r in front], [100 * r["error"] for r in front], "-",
                 color=col, lw=1.5, label=f"φ = {phi:g}: Pareto front")
        mine_drag = [r for r in drag if r["phi"] == phi]
        if mine_drag:
            b.loglog([r["wall_time"] for r in mine_drag], [100 * r["error"] for r in mine_drag],
                     "s", color=col, mfc="w", ms=7,
                     label=f"φ = {phi:g}: drag law, {len(mine_drag)} grids")
    # the paper's O(h^1.5) through the middle of the data
    mid = sorted(rows, key=lambda r: r["r_over_h"])[len(rows) // 2]
    xs = [1 / 16.5, 1 / 2.1]
    x0, e0 = 1 / mid["r_over_h"], 100 * mid["error"]
    a.loglog(xs, [e0 * (v / x0) ** 1.5 for v in xs], "k-", lw=1.5, label="paper: O(h$^{1.5}$)")
    a.set_xlabel("h / r (cell size over sphere radius)")
    a.set_ylabel("|K − K$_{exact}$| / K$_{exact}$ (%)")
    a.set_title("direct model, simple cubic array: error of K against h\n"
                "(hollow: K below the exact value; dotted: the reference's printed digits)",
                fontsize=10)
    a.grid(True, which="both", alpha=0.3)
    a.legend(fontsize=8)
    cost_axes(b, BOUNDS)
    b.set_ylabel("|K − K$_{exact}$| / K$_{exact}$ (%)")
    b.set_title("accuracy against cost, direct (dots) and drag-law model (squares)\n"
                "(grey: 1 %, 3 %, 10 %)", fontsize=10)
    b.legend(fontsize=8)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)

    def describe(r):
        return (f"n = {r['n']:.0f} (r/h = {r['r_over_h']:.2f}), error "
                f"{100 * r['signed']:+.3f} %, {r['wall_time']:.2f} s, "
                f"{r['peak_memory_mb']:.1f} MB")

    print("\ncheapest run (wall time) within each error bound; and the cheapest from which "
          "every finer run stays within")
    for phi in phis:
        mine = sorted((r for r in rows if r["phi"] == phi), key=lambda r: r["r_over_h"])
        for bound in BOUNDS:
            best = cheapest(mine, bound)
            if best is None:
                print(f"  phi = {phi:g}, {100 * bound:2g} %: none")
                continue
            print(f"  phi = {phi:g}, {100 * bound:2g} %: {describe(best)}")
            steady = [r for k, r in enumerate(mine)
                      if all(q["error"] <= bound for q in mine[k:])]
            if steady:
                print(f"  {'':>17}  from {describe(steady[0])} on")
    print("\ndrag-law model on the same arrays (n cells per unit cell; K against the exact K)")
    for r in sorted(drag, key=lambda r: (r["phi"], r["n"])):
        print(f"  phi = {r['phi']:g}, n = {r['n']:.0f}: K = {r['dragLaw.K.final']:.4f}, "
              f"{100 * r['signed']:+.1f} %, {r['wall_time']:.2f} s, {r['peak_memory_mb']:.1f} MB")
    for bound in BOUNDS:
        best = cheapest(drag, bound)
        print(f"  drag law within {100 * bound:2g} %: "
              + (f"phi = {best['phi']:g}, n = {best['n']:.0f}" if best else "none"))
    print(f"\nwrote {args.out.relative_to(ROOT) if args.out.is_relative_to(ROOT) else args.out}")


if __name__ == "__main__":
    main()
