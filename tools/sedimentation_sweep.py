#!/usr/bin/env python3
"""Sedimentation sweep: mean settling velocity against solid fraction, fitted to
Richardson & Zaki (paper eq. 21), v_m / V_0 = (1 - phi)^n.

    tools/sedimentation_sweep.py [--phi 0.02 0.05 0.1 0.15 0.2 0.25 0.3] [--particles 27]
                                 [--cells-per-radius 3] [--reynolds 0.15] [--run-length 0.15]
                                 [--csv out.csv]

`--gap-cells G` raises r/h per phi so that the mean gap between neighbours holds G cells
(dense suspensions need finer grids: the paper's section 3.2).

Each run is a fully periodic box (cubic) holding `--particles` spheres at the solid fraction
phi, packed at random without overlap (seeded), released from rest with the direct model.
The mixture's weight is carried by the imposed mean pressure gradient, so the settling
velocity is measured in the frame of zero volume flux (a container's):
v_m = <v_p> - <u>_box along gravity (fsim's `postProcessing/sedimentation` monitor), averaged
over the second half of the run. The viscosity is set for the particle Reynolds number
Re = V_0 d / nu of `--reynolds` (below 0.2), the run length is `--run-length` L^2/nu (0.15:
about six e-foldings of the slowest box mode, so that the flow has settled), i.e. about
(L/h)^2 steps of the Euler scheme at its viscous bound.

The fit is the least-squares line log(v_m/V_Stokes) = log(V_0/V_Stokes) + n log(1 - phi),
weighted by the run-to-run scatter of each mean (the standard error of the time average,
from block means); n is reported with its standard error, and also with V_0 held at the
Stokes velocity. On the ratio, because the sphere's size in metres, and with it V_Stokes,
changes with r/h. Runs on different grids are never averaged together; at a phi run on
several, the fit takes the N -> infinity row first, then the finest grid.
Results go to CSV (one row per phi and particle count) and to stdout.

Each run is compared with the exact sedimentation coefficient of random hard-sphere
suspensions at its phi (`hard_sphere_ratio`, tools/hindered_settling.py: Abade et al. 2012,
fit of Riest et al. 2015), the reference for what a random packing must give; over the
default phi its own Richardson-Zaki fit is n = 5.56 (V_0 = 0.954 of Stokes), 5.75 with V_0 at
Stokes, not the experiments' 4.65-5.1 (settled suspensions have another microstructure).

Each run is also compared with the Rotne-Prager-Yamakawa mobility of the same spheres in the
same periodic box (tools/periodic_rpy.py, far-field hydrodynamics without lubrication):
`rpy_ratio` is the starting packing's mean settling velocity over the Stokes velocity,
`rpy_fixed_ratio` its fixed array's 1/F; with `--windows`, `rpy_y_k` is the mobility along
gravity of the configuration at the end of window k, and the report's "developed" value the
mean over the second half's ends. The Richardson-Zaki fit is repeated on the RPY values.

A periodic box of N spheres settles slower than an unbounded suspension: the periodic images
add Hasimoto's lattice hindrance, of order 1.76 (phi/N)^{1/3} of the Stokes velocity (0.16 at
phi = 0.02, N = 27). With several counts (`--particles 27 64`) each phi is run at every N and
v_m is extrapolated to N -> infinity linearly in N^{-1/3} (the form of that correction; Ladd,
Phys. Fluids 9, 491 (1997) uses the same extrapolation), its error propagated from the
runs' errors; the fit is then made on the extrapolated values.

With several seeds (`--seed 1 2 3`) each phi and N is run on that many random packings and
the packings' mean goes into the extrapolation, its error the packings' standard error (one
packing's configuration is the largest scatter of a point, +-5 to 10 % at N = 27).
`--combine a.csv b.csv` repeats the analysis on rows written before, without running.
The box is whole cells, so without `--exact-phi` its phi moves with N by up to 3 % (0.292
and 0.306 for 0.3 at r/h = 7 with 27 and 64 spheres), and the extrapolation in N amplifies
that; `--exact-phi` resizes the spheres instead (r/h then moves by up to 3 %, and runs within
3 % of one r/h count as one grid).

`--scheme EulerRKC` is as exact as `Euler` for moving spheres (docs/direct_model.md, "Closed
cells and the incremental pressure") and takes larger steps: on the phi = 0.1 case (27
spheres, 1.2 a/V_Stokes) `Euler` took 911 steps in 5.7 s, `EulerRKC` 577 steps in 4.1 s at
`--step-fraction 0.05` (+0.07 %) and 145 in 1.1 s at 0.2 (+0.8 %).
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import direct_cases  # noqa: E402
import hindered_settling  # noqa: E402
import periodic_rpy  # noqa: E402
import vtk_checks  # noqa: E402

# A liquid; the viscosity follows from the Reynolds number asked for
RHO_F = 1000.0
RHO_P = 2000.0
# the RPY references a row carries: the starting packing's mobility and fixed-array 1/F,
# and the developed configurations' mobility along gravity ([`developed_rpy`])
RPY_KEYS = ["rpy_ratio", "rpy_fixed_ratio", "rpy_developed"]


def read_monitor(case):
    path = os.path.join(case, "postProcessing", "sedimentation", "0", "sedimentation.dat")
    names = open(path).readline().lstrip("#").split()
    data = np.loadtxt(path, comments="#", ndmin=2)
    return {n: data[:, i] for i, n in enumerate(names)}


def block_mean(values, blocks=5):
    """Mean and standard error of a correlated series by block averaging."""
    parts = np.array_split(values, blocks)
    means = np.array([p.mean() for p in parts if len(p)])
    return float(values.mean()), float(means.std(ddof=1) / math.sqrt(len(means)))


def response_time(d, nu):
    """The Stokes response time of a sphere with its added mass, (rho_p + rho_f / 2) d^2 /
    (18 mu): the time scale of an explicitly coupled sphere's velocity, which bounds the step
    once the viscous bound does not (EulerRKC)."""
    return (RHO_P / RHO_F + 0.5) * d * d / (18 * nu)


def box_cells(phi, count, cells_per_radius, exact_phi=False):
    """The cubic box's cells per side for `count` spheres of `cells_per_radius` at `phi`
    (whole cells, at least 2.3 diameters), and the spheres' r/h: as asked, so that phi
    rounds with the box, or with `exact_phi` resized so that the box holds exactly phi."""
    volume = count * direct_cases.sphere_volume(2 * cells_per_radius) / phi
    n = max(int(round(volume ** (1 / 3))), int(math.ceil(4.6 * cells_per_radius)))
    if exact_phi:
        cells_per_radius *= (phi * n ** 3 / (count * direct_cases.sphere_volume(
            2 * cells_per_radius))) ** (1 / 3)
    return n, cells_per_radius


def run_one(binary, scratch, phi, count, cells_per_radius, reynolds, run_length, threads, seed,
            scheme="Euler", step_fraction=0.2, settling_radii=None, windows=1, exact_phi=False):
    h = 1e-4
    n, cells_per_radius = box_cells(phi, count, cells_per_radius, exact_phi)
    d = 2 * cells_per_radius * h
    L = [n * h] * 3
    phi_actual = count * direct_cases.sphere_volume(d) / (n * h) ** 3
    # Re = V_0 d / nu with V_0 = (rho_p/rho_f - 1) g d^2 / (18 nu)
    nu = math.sqrt((RHO_P / RHO_F - 1) * 9.81 * d ** 3 / (18 * reynolds))
    v0 = direct_cases.stokes_velocity(d, RHO_P, RHO_F, nu)
    end = run_length * (n * h) ** 2 / nu
    if settling_radii:
        end = settling_radii * (d / 2) / v0
    max_dt = end / 400
    if scheme != "Euler":
        max_dt = min(end / 100, step_fraction * response_time(d, nu))
    case = os.path.join(scratch, f"phi{phi:g}")
    shutil.rmtree(case, ignore_errors=True)
    # random sequential addition jams near phi = 0.38: keep the gaps small when dense
    centres = direct_cases.periodic_packing(L, d, count, seed=seed,
                                            min_gap=(0.5 if phi < 0.25 else 0.1) * h)
    direct_cases.write_case(case, cells=[n, n, n], h=h, d=d, rho_f=RHO_F, nu=nu, rho_p=RHO_P,
                            end_time=end, write_interval=end / windows, centres=centres,
                            max_co=0.5, max_dt=max_dt, restitution=0.5, scheme=scheme,
                            coupling_extra=direct_cases.LINEAR,
                            title=f"sedimentation sweep, phi = {phi_actual:.4f}")
    log = os.path.join(case, "log.fsimFoam")
    start = time.monotonic()
    with open(log, "w") as f:
        subprocess.run(["nice", binary, "-case", case, "-threads", str(threads)], stdout=f,
                       stderr=subprocess.STDOUT, check=True)
    wall = time.monotonic() - start
    m = read_monitor(case)
    t = m["Time"]
    late = t >= 0.5 * t[-1]
    vm, err = block_mean(m["settlingVelocity"][late])
    rpy = periodic_rpy.settling(centres, d / 2, n * h, phi_actual)
    row = dict(phi=phi_actual, particles=count, cells=n ** 3, r_over_h=cells_per_radius,
               v_m=vm, v_m_error=err, stokes=v0, ratio=vm / v0,
               reynolds=vm * d / nu, end_time=end,
               rpy_ratio=rpy["mobility"], rpy_fixed_ratio=rpy["resistance"],
               hard_sphere_ratio=hindered_settling.hard_spheres(phi_actual),
               scheme=scheme, steps=len(t), wall_seconds=round(wall, 1),
               settling_radii=end * v0 / (d / 2), seed=seed)
    if windows > 1:
        # how the settling velocity and the RPY mobility of the spheres (along gravity, the
        # direction a settled microstructure singles out) move as the suspension settles
        bounds = np.linspace(0, t[-1], windows + 1)
        for w in range(windows):
            inside = (t > bounds[w]) & (t <= bounds[w + 1])
            row[f"ratio_{w + 1}"] = float(m["settlingVelocity"][inside].mean() / v0)
        for w, centres_w in enumerate([centres] + written_centres(case, windows)):
            row[f"rpy_y_{w}"] = periodic_rpy.settling(centres_w, d / 2, n * h, phi_actual,
                                                      axes=[1])["mobility"]
    return row


def written_centres(case, count):
    """The sphere centres of the case's last `count` time directories, in time order."""
    times = vtk_checks.time_directories(case)[-count:]
    return [vtk_checks.read_particles(case, name)["positions"] for name, _ in times]


def resolution(phi, cells_per_radius, gap_cells):
    """r/h: at least `cells_per_radius`, and enough for the mean surface gap of a suspension at
    phi, (4 pi / 3 phi)^{1/3} r - 2r (the spacing of its number density), to span `gap_cells`
    cells. A sharp-interface boundary blocks a gap of one or two cells: the porous-media
    errors of docs/direct_model.md grow from -0.3 % (gap of 5.7 cells, phi = 0.216, r/h = 8)
    to +10 % (2.8 cells) and +56 % (1.1 cells, phi = 0.343, r/h = 4)."""
    gap_over_r = (4 * math.pi / (3 * phi)) ** (1 / 3) - 2
    return max(cells_per_radius, gap_cells / gap_over_r)


def extrapolate(runs):
    """v_m at N -> infinity from runs at one phi and several N: least squares of
    v_m = v_inf - A N^{-1/3}, the error of v_inf propagated from the runs' errors (at least
    the misfit when there are more than two counts). phi is the mean of the runs' (they differ
    by the rounding of the box to whole cells)."""
    x = np.array([r["particles"] ** (-1 / 3) for r in runs])
    y = np.array([r["v_m"] for r in runs])
    s = np.array([max(r["v_m_error"], 1e-3 * r["v_m"]) for r in runs])
    A = np.stack([np.ones_like(x), -x], axis=1)
    w = 1 / s ** 2
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    coef = cov @ (A.T @ (w * y))
    out = dict(runs[-1])
    out.update(phi=float(np.mean([r["phi"] for r in runs])), particles=0, v_m=float(coef[0]),
               v_m_error=float(math.sqrt(cov[0, 0])), ratio=float(coef[0] / runs[-1]["stokes"]))
    # the RPY reference of the same configurations, extrapolated alike (unweighted)
    out["hard_sphere_ratio"] = hindered_settling.hard_spheres(out["phi"])
    for key in RPY_KEYS:
        values = np.array([r.get(key, math.nan) for r in runs])  # older CSVs lack RPY
        out[key] = float(np.linalg.lstsq(A, values, rcond=None)[0][0])
    return out


def average_packings(runs):
    """The mean of runs at one phi and N on different packings: v_m and the RPY values
    averaged, the error the standard error over the packings (at least the mean of the
    runs' own errors over sqrt(k)), phi the mean (the boxes round alike)."""
    k = len(runs)
    if k == 1:
        return dict(runs[0], packings=1)
    v = np.array([r["v_m"] for r in runs])
    own = np.mean([r["v_m_error"] for r in runs]) / math.sqrt(k)
    out = dict(runs[0])
    out.update(phi=float(np.mean([r["phi"] for r in runs])), v_m=float(v.mean()),
               v_m_error=float(max(v.std(ddof=1) / math.sqrt(k), own)),
               seed=" ".join(str(r["seed"]) for r in runs), packings=k)
    out["ratio"] = out["v_m"] / out["stokes"]
    for key in RPY_KEYS:
        out[key] = float(np.mean([r.get(key, math.nan) for r in runs]))
    return out


def developed_rpy(row):
    """The RPY mobility along gravity of the configurations a run reached at the ends of its
    second-half windows (`rpy_y_k`, k > windows / 2), averaged: the reference for the
    developed suspension, where `rpy_ratio` is that of the starting packing. NaN without
    windows."""
    ends = sorted(int(k[6:]) for k in row if k.startswith("rpy_y_"))
    late = [row[f"rpy_y_{k}"] for k in ends if k > ends[-1] / 2]
    return float(np.mean(late)) if late else math.nan


def same_phi(rows, phi, tolerance=0.08):
    """The index of the first of `rows` whose phi is within `tolerance` (relative) of `phi`,
    or None. The box rounds to whole cells, so the runs of one requested phi differ by a
    few percent (0.1025 and 0.0977 for 0.1 with 27 and 64 spheres)."""
    return next((i for i, r in enumerate(rows) if abs(phi / r["phi"] - 1) <= tolerance), None)


def same_grid(grids, r_over_h, tolerance=0.03):
    """The index of the first of `grids` (r/h values) within `tolerance` (relative) of
    `r_over_h`, or None. With `--exact-phi` the sphere's r/h moves by up to a few percent
    with N around the one asked for."""
    return next((i for i, g in enumerate(grids) if abs(r_over_h / g - 1) <= tolerance), None)


def group_runs(runs):
    """Runs grouped by phi ([`same_phi`]), r/h ([`same_grid`]) and N, each group averaged
    over its packings; then by phi and r/h, the counts in ascending order. Runs on different
    grids are never averaged together: the sweep's sphere size, viscosity and Stokes
    velocity change with r/h."""
    phis = []
    grids = {}
    groups = {}
    for r in runs:
        key = same_phi(phis, float(r["phi"]))
        if key is None:
            key = len(phis)
            phis.append(r)
        known = grids.setdefault(key, [])
        r_over_h = float(r.get("r_over_h", 0.0)) or 1.0
        grid = same_grid(known, r_over_h)
        if grid is None:
            grid = len(known)
            known.append(r_over_h)
        groups.setdefault((key, grid, int(r["particles"])), []).append(r)
    by_phi = {}
    for (key, grid, count), members in groups.items():
        by_phi.setdefault((key, grid), []).append(average_packings(members))
    return [sorted(rows, key=lambda r: r["particles"]) for rows in by_phi.values()]


def finest_grid_per_phi(rows):
    """Of rows at one phi ([`same_phi`]) on several grids, the one to fit: extrapolated
    to N -> infinity before a single count (the box size moves v_m by 10-20 %, the grids
    here by less), then the largest r/h. The others are returned apart (reported, not
    fitted)."""
    def rank(r):
        return (r["particles"] == 0, r.get("r_over_h", 0.0))
    best, coarser = [], []
    for r in rows:
        same = same_phi(best, r["phi"])
        if same is None:
            best.append(r)
        elif rank(r) > rank(best[same]):
            coarser.append(best[same])
            best[same] = r
        else:
            coarser.append(r)
    return best, coarser


def read_rows(paths):
    """Rows of sweep CSVs, numbers as floats (seed and scheme kept as written)."""
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                rows.append({k: (v if k in ("scheme", "seed") else float(v))
                             for k, v in row.items() if v != ""})
    return rows


def fit(rows):
    """Weighted least squares of log(v_m / V_Stokes) on log(1 - phi): returns
    (n, sigma_n, V0 / V_Stokes). On v_m / V_Stokes, not v_m: the sweep's Stokes velocity
    changes with r/h (the sphere's size in metres does), so rows on different grids share
    only the ratio."""
    x = np.array([math.log(1 - r["phi"]) for r in rows])
    y = np.array([math.log(r["v_m"] / r["stokes"]) for r in rows])
    s = np.array([max(r["v_m_error"] / r["v_m"], 1e-3) for r in rows])
    w = 1 / s ** 2
    A = np.stack([np.ones_like(x), x], axis=1)
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    coef = cov @ (A.T @ (w * y))
    resid = y - A @ coef
    dof = max(len(rows) - 2, 1)
    scale = max(float(np.sum(w * resid ** 2) / dof), 1.0)  # inflate by the misfit
    return float(coef[1]), float(math.sqrt(cov[1, 1] * scale)), float(math.exp(coef[0]))


def fit_fixed_v0(rows):
    x = np.array([math.log(1 - r["phi"]) for r in rows])
    y = np.array([math.log(r["v_m"] / r["stokes"]) for r in rows])
    n = float(np.sum(x * y) / np.sum(x * x))
    resid = y - n * x
    sigma = float(math.sqrt(np.sum(resid ** 2) / max(len(rows) - 1, 1) / np.sum(x * x)))
    return n, sigma


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--phi", type=float, nargs="+", default=[0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3])
    ap.add_argument("--particles", type=int, nargs="+", default=[27],
                    help="spheres per periodic box; two or more: extrapolate to N -> infinity")
    ap.add_argument("--cells-per-radius", type=float, default=3.0)
    ap.add_argument("--gap-cells", type=float, default=0.0,
                    help="raise r/h so that the mean gap between neighbours spans this many cells")
    ap.add_argument("--exact-phi", action="store_true",
                    help="size the spheres so that every box holds exactly phi (its r/h then "
                         "differs from --cells-per-radius by up to a few percent); without it "
                         "the box rounds to whole cells and phi moves with N")
    ap.add_argument("--reynolds", type=float, default=0.15, help="V_0 d / nu of an isolated sphere")
    ap.add_argument("--run-length", type=float, default=0.15, help="in units of L^2 / nu")
    ap.add_argument("--settling-radii", type=float,
                    help="run length in radii settled at the Stokes velocity, a / V_Stokes "
                         "(in place of --run-length)")
    ap.add_argument("--scheme", default="Euler", choices=["Euler", "EulerRKC"])
    ap.add_argument("--step-fraction", type=float, default=0.2,
                    help="EulerRKC: the step's bound as a fraction of the spheres' response time")
    ap.add_argument("--windows", type=int, default=1,
                    help="split the run into this many windows: the settling velocity of each, "
                         "and the RPY mobility of the spheres where each ends")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, nargs="+", default=[1],
                    help="random packings: each phi and N is run on each, and averaged")
    ap.add_argument("--combine", nargs="+",
                    help="analyse the rows of these sweep CSVs instead of running")
    ap.add_argument("--csv", default="sedimentation_sweep.csv")
    ap.add_argument("--keep", help="keep the cases in this directory")
    ap.add_argument("--no-build", action="store_true")
    a = ap.parse_args()

    if a.combine:
        report(read_rows(a.combine))
        return
    if not a.no_build:
        subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    binary = os.path.join(target, "release", "fsimFoam")
    scratch = a.keep or tempfile.mkdtemp(prefix="fsim-sedimentation-")
    os.makedirs(scratch, exist_ok=True)
    runs = []
    try:
        for phi, count, seed in [(p, c, s) for p in a.phi for c in a.particles
                                 for s in a.seed]:
            r = run_one(binary, os.path.join(scratch, f"N{count}"), phi, count,
                        resolution(phi, a.cells_per_radius, a.gap_cells), a.reynolds,
                        a.run_length, a.threads, seed, scheme=a.scheme,
                        step_fraction=a.step_fraction, settling_radii=a.settling_radii,
                        windows=a.windows, exact_phi=a.exact_phi)
            runs.append(r)
            print(f"phi {r['phi']:.4f}, N {count}, seed {seed}: v_m = {r['v_m']:.4e} +- "
                  f"{r['v_m_error']:.1e} m/s, v_m/V_Stokes = {r['ratio']:.4f} "
                  f"(RPY, starting packing: {r['rpy_ratio']:.4f}), "
                  f"Re = {r['reynolds']:.3f}, {r['cells']} cells, {r['steps']} steps, "
                  f"{r['wall_seconds']} s", flush=True)
            if a.windows > 1:
                print("  by window: v_m/V_Stokes " + " ".join(
                    f"{r[f'ratio_{w + 1}']:.4f}" for w in range(a.windows))
                    + "; RPY along gravity " + " ".join(
                    f"{r[f'rpy_y_{w}']:.4f}" for w in range(a.windows + 1)), flush=True)
    finally:
        if not a.keep:
            shutil.rmtree(scratch, ignore_errors=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(runs[0].keys()))
        w.writeheader()
        w.writerows(runs)
    report(runs)
    print(f"wrote {a.csv}")


def report(runs):
    """Packings averaged, N extrapolated where there are several counts, and the fits."""
    runs = [dict(r, rpy_developed=developed_rpy(r)) for r in runs]
    groups = group_runs(runs)
    for group in groups:
        for r in group:
            if r["packings"] > 1:
                print(f"phi {r['phi']:.4f}, N {int(r['particles'])}, packings {r['seed']}: "
                      f"v_m/V_Stokes = {r['ratio']:.4f} +- {r['v_m_error'] / r['stokes']:.4f} "
                      f"(RPY: {r['rpy_ratio']:.4f} start, {r['rpy_developed']:.4f} developed)")
    # N -> infinity where a phi and grid has several counts; else its one count
    rows = [extrapolate(g) if len(g) > 1 else g[0] for g in groups]
    rows, coarser = finest_grid_per_phi(rows)
    listed = [(r, True) for r in rows] + [(r, False) for r in coarser]
    for r, fitted in sorted(listed, key=lambda pair: pair[0]["phi"]):
        count = int(r["particles"]) if r["particles"] else "-> infinity"
        print(f"phi {r['phi']:.4f}, N {count}, r/h {r.get('r_over_h', 0):.3g}: "
              f"v_m/V_Stokes = {r['ratio']:.4f} +- {r['v_m_error'] / r['stokes']:.4f} "
              f"(RPY: {r.get('rpy_ratio', math.nan):.4f} start, "
              f"{r.get('rpy_developed', math.nan):.4f} developed)"
              + ("" if fitted else "; not fitted (another row at this phi is)"))
    if len(rows) >= 2:
        n, sn, v0 = fit(rows)
        n1, sn1 = fit_fixed_v0(rows)
        print(f"Richardson-Zaki fit: n = {n:.2f} +- {sn:.2f} (V_0 = {v0:.3f} of Stokes); "
              f"with V_0 = Stokes: n = {n1:.2f} +- {sn1:.2f}")
        for key, what in [("rpy_ratio", "starting packings"),
                          ("rpy_developed", "developed configurations, along gravity")]:
            rpy_rows = [dict(r, v_m=r.get(key, math.nan) * r["stokes"], v_m_error=0.0)
                        for r in rows]
            if all(math.isfinite(r["v_m"]) for r in rpy_rows):
                n_rpy, sn_rpy, _ = fit(rpy_rows)
                print(f"the same fit to the RPY mobility of the {what}: n = {n_rpy:.2f} +- "
                      f"{sn_rpy:.2f} (V_0 free)")
        phis = [r["phi"] for r in rows]
        n_hs, v0_hs, n1_hs = hindered_settling.exponent(
            phis, [hindered_settling.hard_spheres(p) for p in phis])
        print(f"the same fit to the exact random hard-sphere reference (Abade et al. 2012, "
              f"tools/hindered_settling.py) at these phi: n = {n_hs:.2f} (V_0 = {v0_hs:.3f} "
              f"of Stokes), with V_0 = Stokes {n1_hs:.2f}")
        for r in rows:
            print(f"  phi {r['phi']:.4f}: fsim / hard-sphere reference = "
                  f"{r['ratio'] / hindered_settling.hard_spheres(r['phi']):.3f}")


if __name__ == "__main__":
    main()
