#!/usr/bin/env python3
"""Fits `model auto`'s error and cost models to the studies of docs/figures (issue 40).

    .venv/bin/python tools/fit_auto_model.py [--studies DIR]

Reads the finished points of the figure studies (run them first: `tools/figures/draw NAME`)
and prints the constants of src/coupling/auto/model_fit.rs with the fit's scatter:

- the direct model's error on a particle's force or settling velocity,
      e = A (h/r)^p (1 + (G/g)^q),
  g the gap between neighbours in cells at the mean spacing of a simple cubic array of the
  same phi, (d (pi/(6 phi))^(1/3) - d)/h; fitted to the settling sphere (one free sphere,
  against U_Stokes/K(phi)) and the porous K (fixed arrays at phi = 0.01-0.45, against Zick &
  Homsy), the points whose error is above the reference's precision. The sedimentation
  study (57 free spheres) is held out to check the fit;
- the drag-law model's error against phi, a table: fixed arrays from Fig. 2's drag-law study
  (the closure's K against the exact K), free suspensions from Fig. 3's drag-law study on
  3^3 cells (h = 2.2 d) against the unbounded hard-sphere suspension;
- the cost, wall time on one thread = t0 + steps (a cells + b particles): least squares per
  model over the studies run on one thread (the direct model: settlingSphere-cost,
  porousMedia-fig1-convergence, porousMedia-fig2-k-vs-phi; the drag law: packedBed-cost,
  fluidizedBed-cost; sedimentation-cost held out).
"""
import argparse
import math
import sys
from pathlib import Path

import numpy as np

TOOLS = Path(__file__).resolve().parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(TOOLS / "figures"))
import hindered_settling  # noqa: E402
from figure import block_cells  # noqa: E402
import study  # noqa: E402
import study_references as refs  # noqa: E402



def cells(row, case):
    text = row.get("blocks") or (case / "system" / "blockMeshDict").read_text()
    if row.get("n") and "blocks" not in row:
        return int(row["n"]) ** 3
    return math.prod(block_cells(text))


def gap_cells(phi, r_over_h):
    """The gap between neighbours, in cells, at the mean spacing of phi."""
    spacing = (math.pi / (6 * phi)) ** (1 / 3)          # in diameters
    return (spacing - 1) * 2 * r_over_h


def direct_points(root):
    """(r/h, phi, |error|, kind) of the direct model's validation studies."""
    out = []
    for r in study.finished_points(root / "settlingSphere-cost"):
        n = block_cells(r["blocks"])[0]
        e = abs(r["sedimentation.settlingVelocity.final"] / r["reference.settlingVelocity"] - 1)
        out.append((n / 4.5, 0.0456, e, "settling sphere"))
    for name in ("porousMedia-fig1-convergence", "porousMedia-fig2-k-vs-phi"):
        for r in study.finished_points(root / name):
            r_over_h = r["n"] * (3 * r["phi"] / (4 * math.pi)) ** (1 / 3)
            e = abs(r["measured.K"] / r["reference.K"] - 1)
            if e > 2e-4:   # above Zick & Homsy's printed precision
                out.append((r_over_h, r["phi"], e, "porous K"))
    return out


def direct_model(x, a, p, g0, q):
    r_over_h, phi = x
    g = np.array([gap_cells(f, s) for s, f in zip(r_over_h, phi)])
    return a * (1 / r_over_h) ** p * (1 + (g0 / g) ** q)


def fit_direct(points):
    """Least squares on log e over a grid of (G, q), linear in (log A, p) at each."""
    s = np.array([p[0] for p in points])
    f = np.array([p[1] for p in points])
    e = np.array([p[2] for p in points])
    keep = s >= 2.9
    s, f, e = s[keep], f[keep], e[keep]
    g = np.array([gap_cells(a, b) for b, a in zip(s, f)])
    best = None
    for g0 in np.linspace(0.1, 3.0, 59):
        for q in np.linspace(0.5, 6.0, 56):
            y = np.log(e) - np.log1p((g0 / g) ** q)
            x = np.stack([np.ones_like(s), np.log(1 / s)], 1)
            coef, *_ = np.linalg.lstsq(x, y, rcond=None)
            res = float(((x @ coef - y) ** 2).sum())
            if best is None or res < best[0]:
                best = (res, math.exp(coef[0]), coef[1], g0, q)
    return best[1:], len(s)


def drag_tables(root):
    fixed = {r["phi"]: abs(r["dragLaw.K.final"] / r["reference.K"] - 1)
             for r in study.finished_points(root / "porousMedia-fig2-k-vs-phi-draglaw")}
    free = {}
    for r in study.finished_points(root / "sedimentation-fig3-draglaw"):
        if block_cells(r["blocks"])[0] != 3:
            continue
        m = refs.sedimentation_measure(root / "sedimentation-fig3-draglaw" / r["point"])
        free.setdefault(round(m["phi"], 3), []).append(
            abs(m["settlingRatio"] / hindered_settling.hard_spheres(m["phi"]) - 1))
    return fixed, {k: sum(v) / len(v) for k, v in free.items()}


def cost_rows(root, names, direct):
    """(features, wall time, study) per one-thread run: [1, steps, steps cells, steps
    particles (r/h)^2] for the direct model (a sphere's stress integral and forcing grow with
    its surface in cells), [1, steps, steps cells, steps particles] for the drag law."""
    rows = []
    for name in names:
        for r in study.finished_points(root / name):
            if r.get("threads") != 1:
                continue
            case = root / name / r["point"]
            parts = r.get("cloud.particles.final") or 0
            n = cells(r, case)
            weight = 1.0
            if direct and parts and "phi" in r and "n" in r:      # porousMedia
                weight = (r["n"] * (3 * r["phi"] / (4 * math.pi)) ** (1 / 3)) ** 2
            elif direct and parts:
                lx, ly, lz = refs.block_extent(case)
                h = (lx * ly * lz / n) ** (1 / 3)
                weight = (0.5 * refs.fixed_diameter(case) / h) ** 2
            st = r["steps"]
            rows.append(([1.0, st, st * n, st * parts * weight], r["wall_time"], name))
    return rows


def fit_cost(rows):
    """Least squares on the relative error, coefficients kept non-negative (a negative one is
    dropped and the rest refitted)."""
    x = np.array([f for f, _, _ in rows])
    t = np.array([w for _, w, _ in rows])
    active = list(range(x.shape[1]))
    while True:
        coef, *_ = np.linalg.lstsq(x[:, active] / t[:, None], np.ones_like(t), rcond=None)
        if (coef >= 0).all():
            break
        active.pop(int(np.argmin(coef)))
    full = np.zeros(x.shape[1])
    full[active] = coef
    return full, (x @ full) / t


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--studies", type=Path, default=TOOLS.parent / "studies")
    args = ap.parse_args(argv)
    root = args.studies

    points = direct_points(root)
    (a, p, g0, q), used = fit_direct(points)
    print(f"direct error: e = {a:.4g} (h/r)^{p:.3f} (1 + ({g0:.3g}/g)^{q:.3g})  "
          f"({used} points, r/h >= 2.9)")
    s = np.array([x[0] for x in points])
    f = np.array([x[1] for x in points])
    e = np.array([x[2] for x in points])
    ratio = direct_model((s, f), a, p, g0, q) / e
    fit = s >= 2.9
    print(f"  predicted / measured over the fitted points: median {np.median(ratio[fit]):.2f}, "
          f"within 2x: {np.mean((ratio[fit] > 0.5) & (ratio[fit] < 2)):.0%}, "
          f"range {ratio[fit].min():.2f}-{ratio[fit].max():.2f}")
    held = [r for r in study.finished_points(root / "sedimentation-cost")
            if r.get("fsim/timeScheme") == "EulerRKC" and r["maxDeltaT"] == 2.8e-4]
    v_inf = 0.4550   # the direct model's grid limit (docs/figures/README.md)
    for r in held:
        n = block_cells(r["blocks"])[0]
        r_over_h = 0.75e-3 * n / 0.01
        m = refs.sedimentation_measure(root / "sedimentation-cost" / r["point"])
        measured = abs(m["settlingRatio"] / v_inf - 1)
        predicted = direct_model((np.array([r_over_h]), np.array([m["phi"]])), a, p, g0, q)[0]
        print(f"  held out, sedimentation r/h {r_over_h:.2f}: predicted {100 * predicted:.2f} %, "
              f"measured {100 * measured:.2f} %, ratio {predicted / measured:.2f}")

    fixed, free = drag_tables(root)
    print("drag-law error, fixed arrays (phi: |K/K_exact - 1|):",
          ", ".join(f"({k:g}, {v:.3f})" for k, v in sorted(fixed.items())))
    print("drag-law error, free suspensions (phi: |v/v_hard spheres - 1|, 3^3 cells):",
          ", ".join(f"({k:g}, {v:.3f})" for k, v in sorted(free.items())))

    for model, names in (("direct", ("settlingSphere-cost", "porousMedia-fig1-convergence",
                                     "porousMedia-fig2-k-vs-phi",
                                     "sedimentation-fig3-direct")),
                         ("dragLaw", ("packedBed-cost", "fluidizedBed-cost"))):
        rows = cost_rows(root, names, model == "direct")
        coef, ratio = fit_cost(rows)
        print(f"cost, {model}: t = {coef[0]:.3g} s + steps ({1e6 * coef[1]:.4g} us + "
              f"{1e9 * coef[2]:.4g} ns cells + {1e9 * coef[3]:.4g} ns particles"
              + (" (r/h)^2" if model == "direct" else "") + f")  ({len(rows)} runs; predicted"
              f" / measured median {np.median(ratio):.2f}, within 2x "
              f"{np.mean((ratio > 0.5) & (ratio < 2)):.0%}, range {ratio.min():.2f}-"
              f"{ratio.max():.2f})")
        if model == "direct":
            direct_cost = coef
    held = cost_rows(root, ("sedimentation-cost",), True)
    ratios = [np.dot(direct_cost, f) / w for f, w, _ in held]
    print(f"  held out, sedimentation-cost: predicted / measured {min(ratios):.2f}-"
          f"{max(ratios):.2f}")


if __name__ == "__main__":
    main()
