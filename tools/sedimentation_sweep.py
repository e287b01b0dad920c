#!/usr/bin/env python3
"""Sedimentation sweep: mean settling velocity against solid fraction, fitted to
Richardson & Zaki (paper eq. 21), v_m / V_0 = (1 - phi)^n.

    tools/sedimentation_sweep.py [--phi 0.02 0.05 0.1 0.15 0.2 0.25] [--particles 27]
                                 [--seed 1] [--cells-per-radius 3] [--gap-cells G]
                                 [--reynolds 0.15] [--run-length 0.15] [--study DIR]
                                 [--exact-phi] [--settling-radii R] [--scheme EulerRKC]
                                 [--step-fraction F] [--windows K] [--workers W]
                                 [--threads T] [--fsim PATH] [--csv out.csv]
    tools/sedimentation_sweep.py --combine a.csv b.csv

The runs are one study of tools/study (docs/user-guide/studies.md) over the sedimentation
tutorial, its zipped axes written to DIR/sweep.toml (default studies/sedimentation-sweep): one
point per phi, particle count N and seed, so that finished points are reused, points run in
parallel through Dask and a failed one is recorded. Each point is the tutorial's fully
periodic box made a cube of n cells holding N of its spheres (d = 1.5 mm, rho_p = 2500) at phi,
placed by fsim's randomPacking with the point's seed. r/h is `--cells-per-radius`, raised by
`--gap-cells G` so that the mean gap between neighbours holds G cells (dense suspensions need
finer grids: the paper's section 3.2); the viscosity gives the particle Reynolds number
Re = V_0 d / nu of `--reynolds` (below 0.2); the run is `--run-length` L^2/nu (0.15: about six
e-foldings of the slowest box mode) or `--settling-radii R` a/V_Stokes; the step sits just
under Euler's viscous bound h^2/(6 nu) (`--scheme EulerRKC`: `--step-fraction` of the
spheres' response time); the contact stiffness gives an overlap of 0.5 % of d at V_Stokes.

The mixture's weight is carried by the imposed mean pressure gradient, so the settling
velocity is measured in the frame of zero volume flux: v_m = <v_p> - <u>_box along gravity
(the point's `postProcessing/sedimentation` monitor), averaged over the second half of the
run. The fit is the least-squares line log(v_m/V_Stokes) = log(V_0/V_Stokes) + n log(1 - phi),
weighted by the standard error of each time average (block means); n is reported with its
standard error, and also with V_0 held at Stokes. Runs on different grids are never averaged
together; at a phi run on several, the fit takes the N -> infinity row first, then the finest
grid. Results go to CSV (one row per point) and to stdout. Each run is compared with the
exact sedimentation coefficient of random hard-sphere suspensions at its phi
(tools/hindered_settling.py: Abade et al. 2012) and with the Rotne-Prager-Yamakawa mobility of
the same spheres in the same periodic box (tools/periodic_rpy.py): `rpy_ratio` of the starting
packing, `rpy_fixed_ratio` its fixed array's 1/F; with `--windows K`, `rpy_y_k` along gravity
where window k ends, and the "developed" mean over the second half's ends.

A periodic box of N spheres settles slower than an unbounded suspension (Hasimoto's lattice
hindrance, about 1.76 (phi/N)^{1/3}). With several counts (`--particles 27 64`) v_m is
extrapolated to N -> infinity linearly in N^{-1/3} (Ladd, Phys. Fluids 9, 491 (1997)); with
several seeds the packings are averaged first, their standard error the error. The box is
whole cells, so phi moves with N by up to 3 %; `--exact-phi` sets h so that it holds phi
exactly (r/h then moves by up to 3 %, and runs within 3 % of one r/h count as one grid).

Not kept from the sweep's own case writer (before the study), since randomPacking cannot
express them: a minimum gap between the spheres (randomPacking only excludes overlap: gaps of
0.1 to 0.2 h occur) and a periodic packing. randomPacking keeps every sphere inside the box,
so no centre starts within d/2 of a face: with few spheres they start as a denser cube
separated from its images by a clear layer one diameter thick, which settles faster (the RPY
mobility along gravity of 27 spheres at phi = 0.1: 0.47 to 0.69 of Stokes over seeds 1-5, 0.36
for the old periodic packing's seed 1), and fsim lands 8 to 10 % below RPY along gravity there
(3 % with the old packing: tools/tests/test_sedimentation_tools.py). So the numbers of
docs/richardson_zaki.md, made with the old packing, are not reproduced. A dense box of few
spheres cannot be packed at all (phi = 0.3 fails with 27 and 64 spheres, packs with 125; the
study's dry run names the point and no point runs), hence the default phi stops at 0.25.
`--keep` and `--no-build` went too (the study folder stays; `--fsim`, else the study's build).
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import direct_cases  # noqa: E402
import hindered_settling  # noqa: E402
import periodic_rpy  # noqa: E402
import study  # noqa: E402
import study_references  # noqa: E402
import vtk_checks  # noqa: E402

TUTORIAL = os.path.join(ROOT, "tutorials", "sedimentation")
# the tutorial's spheres and liquid; the viscosity follows from the Reynolds number asked for
D = study_references.fixed_diameter(TUTORIAL)
RHO_F = study_references.fluid_density(TUTORIAL)
RHO_P = study_references.scalar(TUTORIAL, "constant/kinematicCloudProperties",
                                "constantProperties/rho0")
G = math.hypot(*study_references.vector(TUTORIAL, "constant/g", "value"))
CLOUD = "constant/kinematicCloudProperties:subModels/"
SPHERES = CLOUD + "injectionModels/spheres/"
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


def point(phi, count, cells_per_radius, reynolds, run_length, seed, scheme="Euler",
          step_fraction=0.2, settling_radii=None, windows=1, exact_phi=False):
    """One point of the sweep: its parameters and the tutorial's entries it sets. The spheres
    keep the tutorial's size; the cell size h follows from r/h."""
    n, cells_per_radius = box_cells(phi, count, cells_per_radius, exact_phi)
    h = D / (2 * cells_per_radius)
    L = n * h
    phi_box = count * direct_cases.sphere_volume(D) / L ** 3
    # Re = V_0 d / nu with V_0 = (rho_p/rho_f - 1) g d^2 / (18 nu)
    nu = math.sqrt((RHO_P / RHO_F - 1) * G * D ** 3 / (18 * reynolds))
    v0 = direct_cases.stokes_velocity(D, RHO_P, RHO_F, nu, G)
    end = settling_radii * (D / 2) / v0 if settling_radii else run_length * L ** 2 / nu
    if scheme == "Euler":
        # just under the explicit viscous bound h^2/(6 nu) (paper eq. 3), which rules at h < r
        max_dt = min(end / 400, 0.95 * h * h / (6 * nu))
    else:
        max_dt = min(end / 100, step_fraction * response_time(D, nu))
    # soft enough for few collision sub-steps, stiff enough that a head-on impact at the
    # Stokes velocity overlaps by 0.5 % of d: t_c = pi delta / v, kn = (pi/t_c)^2 m/2
    t_c = math.pi * 0.005 * D / v0
    kn = (math.pi / t_c) ** 2 * RHO_P * direct_cases.sphere_volume(D) / 2
    corners = [(i * L, j * L, k * L) for k in (0, 1) for i, j in ((0, 0), (1, 0), (1, 1), (0, 1))]
    num = study.format_number
    entries = {
        SPHERES + "type": "randomPacking",
        SPHERES + "box": f"(0 0 0) ({num(L)} {num(L)} {num(L)})",
        # exactly `count` spheres: randomPacking places round(phi V / V_sphere)
        SPHERES + "volumeFraction": num(phi_box),
        SPHERES + "seed": str(seed),
        CLOUD + "pairCollisionCoeffs/pairLinearSpringDashpotCoeffs/kn": num(kn),
        CLOUD + "pairCollisionCoeffs/wallLinearSpringDashpotCoeffs/kn": num(kn),
        "system/blockMeshDict:vertices": "( " + " ".join(
            "(" + " ".join(num(x) for x in c) + ")" for c in corners) + " )",
        "system/blockMeshDict:blocks": f"( hex (0 1 2 3 4 5 6 7) ({n} {n} {n}) "
                                       "simpleGrading (1 1 1) )",
        "constant/transportProperties:nu": num(nu),
        "system/fvSolution:fsim/timeScheme": scheme,
        "system/controlDict:endTime": num(end),
        "system/controlDict:writeInterval": num(end / windows),
        "system/controlDict:deltaT": num(max_dt),
        "system/controlDict:maxDeltaT": num(max_dt),
    }
    return dict(phi=phi_box, particles=count, n=n, r_over_h=cells_per_radius, h=h, nu=nu,
                stokes=v0, end_time=end, scheme=scheme, seed=seed, windows=windows,
                entries=entries)


def write_spec(folder, points):
    """The study of `points` as a TOML file in `folder` (zipped axes, one value per point)."""
    lines = ["# the sedimentation sweep's study, written by tools/sedimentation_sweep.py",
             'tutorial = "sedimentation"', 'name = "sweep"', "zip = true", "add = true",
             '# the sweep compares with its own references (the hard-sphere and RPY values)',
             'reference = "none"',
             "", "[set]"]
    for key in points[0]["entries"]:
        values = ", ".join(json.dumps(p["entries"][key]) for p in points)
        lines.append(f"{json.dumps(key)} = [{values}]")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "sweep.toml")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def run_points(folder, points, fsim=None, workers=None, threads=None):
    """Runs (or resumes) the study of `points` in `folder`; returns (rows of the finished
    points, [(point, message)] of the failed ones). Exits on a bad sweep or a stop."""
    argv = ["run", "--spec", write_spec(folder, points), "--out", str(folder)]
    argv += ["--fsim", str(fsim)] if fsim else []
    argv += ["--workers", str(workers)] if workers else []
    argv += ["--threads-per-point", str(threads)] if threads else []
    code = study.main(argv)
    if code not in (0, 1):
        sys.exit(code)
    table = study.read_table(os.path.join(folder, "results.csv"))
    assert len(table) == len(points), f"{folder}/results.csv: {len(table)} rows"
    rows, failed = [], []
    for p, t in zip(points, table):
        assert int(t[SPHERES.split(":")[1] + "seed"]) == p["seed"], (t["point"], p["seed"])
        if t["status"] == "done":
            rows.append(measure(os.path.join(folder, t["point"]), p, t))
        else:
            failed.append((p, t.get("message")))
    return rows, failed


def measure(case, p, table_row):
    """A finished point's row: v_m over the second half of the run, against Stokes, the
    hard-sphere reference and the RPY mobility of the same spheres."""
    m = read_monitor(case)
    t = m["Time"]
    late = t >= 0.5 * t[-1]
    vm, err = block_mean(m["settlingVelocity"][late])
    v0, L = p["stokes"], p["n"] * p["h"]
    centres = written_centres(case)
    rpy = periodic_rpy.settling(centres[0], D / 2, L, p["phi"])
    row = dict(point=table_row["point"], phi=p["phi"], particles=p["particles"],
               cells=p["n"] ** 3, r_over_h=p["r_over_h"], v_m=vm, v_m_error=err, stokes=v0,
               ratio=vm / v0, reynolds=vm * D / p["nu"], end_time=p["end_time"],
               rpy_ratio=rpy["mobility"], rpy_fixed_ratio=rpy["resistance"],
               hard_sphere_ratio=hindered_settling.hard_spheres(p["phi"]),
               scheme=p["scheme"], steps=int(table_row["steps"]),
               wall_seconds=round(float(table_row["wall_time"]), 1),
               settling_radii=p["end_time"] * v0 / (D / 2), seed=p["seed"])
    windows = p["windows"]
    if windows > 1:
        # how the settling velocity and the RPY mobility of the spheres (along gravity, the
        # direction a settled microstructure singles out) move as the suspension settles
        bounds = np.linspace(0, t[-1], windows + 1)
        for w in range(windows):
            inside = (t > bounds[w]) & (t <= bounds[w + 1])
            row[f"ratio_{w + 1}"] = float(m["settlingVelocity"][inside].mean() / v0)
        for w, centres_w in enumerate(centres[-(windows + 1):]):
            row[f"rpy_y_{w}"] = periodic_rpy.settling(centres_w, D / 2, L, p["phi"],
                                                      axes=[1])["mobility"]
    return row


def written_centres(case):
    """The sphere centres of the case's time directories (the start's first), in time order."""
    return [vtk_checks.read_particles(case, name)["positions"]
            for name, _ in vtk_checks.time_directories(case)]


def sweep(folder, phis, counts, seeds, cells_per_radius=3.0, gap_cells=0.0, reynolds=0.15,
          run_length=0.15, settling_radii=None, scheme="Euler", step_fraction=0.2, windows=1,
          exact_phi=False, fsim=None, workers=None, threads=None):
    """Every phi at every count and seed, as one study in `folder`: (rows, failed)."""
    points = [point(phi, count, resolution(phi, cells_per_radius, gap_cells), reynolds,
                    run_length, seed, scheme=scheme, step_fraction=step_fraction,
                    settling_radii=settling_radii, windows=windows, exact_phi=exact_phi)
              for phi in phis for count in counts for seed in seeds]
    return run_points(folder, points, fsim, workers, threads)


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
                rows.append({k: (v if k in ("scheme", "seed", "point") else float(v))
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
    ap.add_argument("--phi", type=float, nargs="+", default=[0.02, 0.05, 0.1, 0.15, 0.2, 0.25])
    ap.add_argument("--particles", type=int, nargs="+", default=[27],
                    help="spheres per periodic box; two or more: extrapolate to N -> infinity")
    ap.add_argument("--cells-per-radius", type=float, default=3.0)
    ap.add_argument("--gap-cells", type=float, default=0.0,
                    help="raise r/h so that the mean gap between neighbours spans this many cells")
    ap.add_argument("--exact-phi", action="store_true",
                    help="size the cells so that every box holds exactly phi (its r/h then "
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
    ap.add_argument("--seed", type=int, nargs="+", default=[1],
                    help="random packings: each phi and N is run on each, and averaged")
    ap.add_argument("--study", default=os.path.join(ROOT, "studies", "sedimentation-sweep"),
                    help="the study folder (finished points in it are reused)")
    ap.add_argument("--workers", type=int, help="points at once (default: tools/study's)")
    ap.add_argument("--threads", type=int, help="fsimFoam -threads of each point")
    ap.add_argument("--fsim", help="the fsimFoam to run (default: tools/study's)")
    ap.add_argument("--combine", nargs="+",
                    help="analyse the rows of these sweep CSVs instead of running")
    ap.add_argument("--csv", default="sedimentation_sweep.csv")
    a = ap.parse_args()

    if a.combine:
        report(read_rows(a.combine))
        return
    runs, failed = sweep(a.study, a.phi, a.particles, a.seed, a.cells_per_radius, a.gap_cells,
                         a.reynolds, a.run_length, a.settling_radii, a.scheme, a.step_fraction,
                         a.windows, a.exact_phi, a.fsim, a.workers, a.threads)
    for p, message in failed:
        print(f"phi {p['phi']:.4f}, N {p['particles']}, seed {p['seed']}: not finished "
              f"({message})", flush=True)
    for r in runs:
        print(f"{r['point']}: phi {r['phi']:.4f}, N {r['particles']}, seed {r['seed']}: "
              f"v_m = {r['v_m']:.4e} +- {r['v_m_error']:.1e} m/s, v_m/V_Stokes = "
              f"{r['ratio']:.4f} (RPY, starting packing: {r['rpy_ratio']:.4f}), "
              f"Re = {r['reynolds']:.3f}, {r['cells']} cells, {r['steps']} steps, "
              f"{r['wall_seconds']} s", flush=True)
        if a.windows > 1:
            print("  by window: v_m/V_Stokes " + " ".join(
                f"{r[f'ratio_{w + 1}']:.4f}" for w in range(a.windows))
                + "; RPY along gravity " + " ".join(
                f"{r[f'rpy_y_{w}']:.4f}" for w in range(a.windows + 1)), flush=True)
    if not runs:
        sys.exit("no point finished")
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
