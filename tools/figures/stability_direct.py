#!/usr/bin/env python3
"""Stability map of the direct model from real runs: the step over its bound against r/h.

    tools/figures/draw stability_direct [--no-run] [--study DIR] [--out PNG]

Runs the studies tools/figures/stability_direct_free.toml (settlingSphere: one free sphere,
rho_p/rho_f = 1.1, 2, 8 with virtualMass 2 and 1.1 with virtualMass 0) and
stability_direct_fixed.toml (porousMedia: a fixed array at phi = 0.1), finished points
reused. The steps beyond the fluid scheme's bound (Euler's h^2/(6 nu), RK3's
2.51 h^2/(12 nu), at 1.1 and 2 times it) cannot be in those studies: fsimFoam's dry run
rejects them, and a study with a rejected point runs none. So this script makes their case
copies with `tools/study run … --check` (into STUDY-unrunnable) and starts each with
fsimFoam itself (study.run_point: its exit code, message, done.json), then `tools/study
table`. The one point the dry run finds diverging (n = 18, rho 1.1, virtualMass 0, EulerRKC
at 4 x 0.25 tau_p) is started the same way.

Every cell is classified (`classify`):

- refused: fsimFoam exited with 2 (it refused the case at start, naming the bound);
- unstable: it failed while running (exit 1: the step check saw the velocity grow past the
  scheme's bound, or the Courant step collapsed), or it ended with no finite result;
- inaccurate: it ran, and |error| exceeds the grid's own error at that r/h by more than
  1 % (ERROR_MARGIN): |e| > |e_grid| + 1 %, e_grid the error of the run with the smallest
  step there (free sphere: Euler at 0.5 of its bound, rho_p/rho_f 2, virtualMass 2; fixed
  array: RK3 at 0.5 of its bound). The free sphere's e is the settling velocity's error
  over the last quarter of the run at its 90th percentile in magnitude (worst_late_error: a
  velocity that oscillates at a fixed step can pass the reference at endTime); the fixed
  array's is K's
  (the study's measured.K, its steady value) against Zick & Homsy;
- stable: it ran, within that.

Prints every cell and draws docs/figures/stability_direct.png: top row the tutorials'
schemes (Euler for the free sphere, RK3 for the fixed array) at multiples of their viscous
bound, bottom row EulerRKC (no viscous bound) at multiples of the response bound
0.25 tau_p, tau_p = rho_p d^2/(18 mu).
"""
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch, Rectangle  # noqa: E402
from figure import (ROOT, arguments, block_cells, run_refused_points,  # noqa: E402
                    run_study, save, study_tool)

FREE_SPEC = ROOT / "tools" / "figures" / "stability_direct_free.toml"
FIXED_SPEC = ROOT / "tools" / "figures" / "stability_direct_fixed.toml"
STUDY = ROOT / "studies" / "settlingSphere-stability"
FIXED_STUDY = ROOT / "studies" / "porousMedia-stability"
OUT = ROOT / "docs" / "figures" / "stability_direct.png"
ERROR_MARGIN = 0.01

SCHEME, RHO, VM = "fsim/timeScheme", "constantProperties/rho0", "virtualMass"
BOX, D, NU, RHO_F = 4.5e-3, 2e-3, 1e-3, 1000.0       # settlingSphere
L_CELL, NU_FIXED, PHI = 2.8e-3, 1e-4, 0.1             # porousMedia
FREE_CELLS = (12, 18, 24, 36)
FIXED_CELLS = (9, 14, 18, 28)
CONFIGS = ((1100, 2), (2000, 2), (8000, 2), (1100, 0))   # (rho0, virtualMass)
BEYOND = (1.1, 2)                                      # refused fractions of the fluid bound

COLOURS = {"stable": "#4daf4a", "inaccurate": "#ffbf00", "unstable": "#e41a1c",
           "refused": "#9e9e9e"}


def classify(status, exit_code, error, threshold):
    """A run's outcome: 'refused' (fsimFoam exited with 2: the case refused at start),
    'unstable' (it failed while running, or ended without a finite error), 'inaccurate'
    (|error| > threshold), 'stable'; None for a point that has not run."""
    if status == "failed":
        return "refused" if exit_code == 2 else "unstable"
    if status != "done":
        return None
    if error is None or not math.isfinite(error):
        return "unstable"
    return "inaccurate" if abs(error) > threshold else "stable"


def block(n):
    return f"( hex (0 1 2 3 4 5 6 7) ({n} {n} {n}) simpleGrading (1 1 1) )"


def euler_bound(n):
    h = BOX / n
    return h * h / (6 * NU)


def response_bound(rho):
    return 0.25 * rho * D * D / (18 * RHO_F * NU)


def rk3_bound(n):
    h = L_CELL / n
    return 2.51 * h * h / (12 * NU_FIXED)


def fmt(x):
    return f"{x:.6g}"


def unrunnable_sets():
    """The `--set` arguments (zipped) of the points fsimFoam's dry run rejects: free sphere
    and fixed array."""
    free = []
    for rho, vm in CONFIGS:
        end = 0.02 if rho == 8000 else 0.005
        for n in FREE_CELLS:
            for f in BEYOND:
                free.append((block(n), rho, vm, end, "Euler", fmt(f * euler_bound(n))))
    free.append((block(18), 1100, 0, 0.005, "EulerRKC", fmt(4 * response_bound(1100))))
    keys = ("system/blockMeshDict:blocks",
            "constant/kinematicCloudProperties:constantProperties/rho0",
            "constant/couplingProperties:virtualMass", "system/controlDict:endTime",
            "system/fvSolution:fsim/timeScheme", "system/controlDict:deltaT")
    free_args = ["--add", "--set", "system/controlDict:adjustTimeStep=no"]
    for k, key in enumerate(keys):
        free_args += ["--set", f"{key}=" + ",".join(str(p[k]) for p in free)]
    fixed = [(n, fmt(f * rk3_bound(n))) for n in FIXED_CELLS for f in BEYOND]
    fixed_args = ["--set", "system/controlDict:adjustTimeStep=no",
                  "--set", "constant/porousParameters:n=" + ",".join(str(n) for n, _ in fixed),
                  "--set", "system/controlDict:deltaT=" + ",".join(d for _, d in fixed)]
    return [("settlingSphere", free_args), ("porousMedia", fixed_args)]


def rows_of(folder):
    """(folder, row) of every row of the folder's results.csv."""
    path = folder / "results.csv"
    return [(folder, r) for r in study_tool.read_table(path)] if path.exists() else []


def free_cells(folder_rows):
    """settlingSphere rows as cells: config, scheme, n, fraction of the bound, signed error
    (worst_late_error)."""
    cells = []
    for folder, r in folder_rows:
        n = block_cells(r["blocks"])[0]
        rho, vm, scheme = r[RHO], r[VM], r[SCHEME]
        bound = euler_bound(n) if scheme == "Euler" else response_bound(rho)
        ref = r.get("reference.settlingVelocity")
        signed = None
        if r["status"] == "done" and isinstance(ref, float):
            signed = worst_late_error(folder / r["point"], r["endTime"], ref)
        cells.append(dict(row=r, config=(int(rho), int(vm)), scheme=scheme, n=n,
                          r_over_h=D / 2 / (BOX / n), fraction=r["deltaT"] / bound,
                          signed=signed))
    return cells


def worst_late_error(point, end_time, reference):
    """The settling velocity's relative error over the last quarter of the run (t >= 0.75
    endTime; the sedimentation monitor), at its 90th percentile in magnitude, signed: a
    velocity that still oscillates at a fixed step can pass the reference at endTime itself,
    while the few-step blips of a sphere's faces changing as it crosses the grid (up to
    0.9 % at r/h 4) are left out."""
    path = point / "postProcessing" / "sedimentation" / "0" / "sedimentation.dat"
    if not path.exists():
        return None
    columns, late = None, []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            columns = line[1:].split()
            continue
        values = line.split()
        if values and columns is not None and float(values[0]) >= 0.75 * end_time:
            late.append(float(values[columns.index("settlingVelocity")]) / reference - 1)
    if not late:
        return None
    if not all(math.isfinite(e) for e in late):
        return float("nan")
    late.sort(key=abs)
    return late[int(0.9 * (len(late) - 1))]


def fixed_cells(folder_rows):
    """porousMedia rows as cells; the error is the table's steady K against Zick & Homsy."""
    cells = []
    for _, r in folder_rows:
        n = int(r["n"])
        k, ref = r.get("measured.K"), r.get("reference.K")
        signed = None
        if r["status"] == "done" and isinstance(k, float) and isinstance(ref, float):
            signed = k / ref - 1
        cells.append(dict(row=r, config="fixed", scheme="RK3", n=n,
                          r_over_h=n * (3 * PHI / (4 * math.pi)) ** (1 / 3),
                          fraction=r["deltaT"] / rk3_bound(n), signed=signed))
    return cells


def grid_errors(cells, config, scheme):
    """|e_grid| per n: the error of the smallest step of `config` and `scheme` that ran."""
    out = {}
    for c in cells:
        if c["config"] == config and c["scheme"] == scheme and c["row"]["status"] == "done" \
                and c["signed"] is not None:
            best = out.get(c["n"])
            if best is None or c["fraction"] < best[0]:
                out[c["n"]] = (c["fraction"], abs(c["signed"]))
    return {n: e for n, (_, e) in out.items()}


def message_class(row):
    msg = (row.get("message") or "").replace("fsimFoam: error: ", "")
    if "exceeds the stability bound" in msg:
        scheme = msg.split(" of the ")[1].split(" (")[0] if " of the " in msg else "scheme"
        if "it held until now" in msg:
            return f"step {msg.split('(step ')[1].split(';')[0]}: past {scheme} bound, diverging"
        return f"at start: past {scheme} bound"
    return msg.splitlines()[0][:90] if msg else ""


def main(argv=None):
    parser = arguments(__doc__, STUDY, OUT)
    parser.add_argument("--fixed-study", type=Path, default=FIXED_STUDY)
    args = parser.parse_args(argv)
    free_extra = args.study.with_name(args.study.name + "-unrunnable")
    fixed_extra = args.fixed_study.with_name(args.fixed_study.name + "-unrunnable")
    if not args.no_run:
        run_study(FIXED_SPEC, args.fixed_study)
        run_study(FREE_SPEC, args.study)
        for (tutorial, extra_args), folder in zip(unrunnable_sets(), (free_extra, fixed_extra)):
            run_refused_points(tutorial, ["--zip", *extra_args], folder, tutorial)

    free = free_cells(rows_of(args.study) + rows_of(free_extra))
    fixed = fixed_cells(rows_of(args.fixed_study) + rows_of(fixed_extra))
    grid_free = grid_errors(free, (2000, 2), "Euler")
    grid_fixed = grid_errors(fixed, "fixed", "RK3")
    for c in free + fixed:
        grid = (grid_fixed if c["config"] == "fixed" else grid_free).get(c["n"])
        c["threshold"] = grid + ERROR_MARGIN if grid is not None else ERROR_MARGIN
        r = c["row"]
        c["outcome"] = classify(r["status"], r.get("exit_code"), c["signed"], c["threshold"])

    print("case                   scheme    r/h   step/bound  outcome     error %  "
          "threshold %  steps  wall s  message")
    for c in sorted(free + fixed, key=lambda c: (str(c["config"]), c["scheme"], c["n"],
                                                  c["fraction"])):
        r = c["row"]
        err = f"{100 * c['signed']:+8.2f}" if c["signed"] is not None else "       -"
        steps = r.get("steps")
        wall = r.get("wall_time")
        print(f"{label(c['config']):<22} {c['scheme']:<9} {c['r_over_h']:4.2f}  "
              f"{c['fraction']:9.3g}  {c['outcome'] or '-':<10} {err}  "
              f"{100 * c['threshold']:10.2f}  "
              f"{steps if isinstance(steps, (int, float)) and steps == steps else '-':>5}  "
              f"{wall if isinstance(wall, float) else float('nan'):6.1f}  {message_class(r)}")
    total = sum(c["row"].get("wall_time") or 0 for c in free + fixed
                if isinstance(c["row"].get("wall_time"), float))
    print(f"\nwall time of all runs: {total:.0f} s (1 thread each)")
    draw(free, fixed, args.out)


def label(config):
    if config == "fixed":
        return "fixed array phi 0.1"
    rho, vm = config
    return f"rho_p/rho_f {rho / RHO_F:g}, C_v {vm}"


def panel(ax, cells, title, xlabel):
    fractions = sorted({round(c["fraction"], 3) for c in cells})
    ratios = sorted({round(c["r_over_h"], 2) for c in cells})
    for c in cells:
        if c["outcome"] is None:
            continue
        i = fractions.index(round(c["fraction"], 3))
        j = ratios.index(round(c["r_over_h"], 2))
        ax.add_patch(Rectangle((i - 0.46, j - 0.44), 0.92, 0.88,
                               color=COLOURS[c["outcome"]], lw=0))
        r = c["row"]
        if c["outcome"] in ("stable", "inaccurate"):
            text = f"{100 * c['signed']:+.1f} %"
        elif c["outcome"] == "refused":
            text = "exit 2\nat start"
        else:
            code = r.get("exit_code")
            text = f"exit {int(code) if isinstance(code, (int, float)) else '?'}"
            if "it held until now" in (r.get("message") or ""):
                text += f"\nstep {r['message'].split('(step ')[1].split(';')[0]}"
            elif c["outcome"] == "unstable" and r["status"] == "done":
                text = "no finite\nresult"
        ax.text(i, j, text, ha="center", va="center", fontsize=7)
    ax.set_xlim(-0.5, len(fractions) - 0.5)
    ax.set_ylim(-0.5, len(ratios) - 0.5)
    ax.set_xticks(range(len(fractions)), [f"{f:g}" for f in fractions])
    ax.set_yticks(range(len(ratios)), [f"{r:g}" for r in ratios])
    ax.set_xlabel(xlabel, fontsize=8)
    ax.set_ylabel("r/h", fontsize=8)
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=8)
    for side in ax.spines.values():
        side.set_visible(False)


def draw(free, fixed, out):
    fig, axes = plt.subplots(2, 5, figsize=(17, 7.4), constrained_layout=True)
    for k, config in enumerate(CONFIGS):
        rho, vm = config
        tau = rho * D * D / (18 * RHO_F * NU)
        name = (f"free sphere, ρ$_p$/ρ$_f$ = {rho / RHO_F:g}, virtualMass {vm}")
        panel(axes[0, k], [c for c in free if c["config"] == config and c["scheme"] == "Euler"],
              f"{name}\nEuler (the tutorial's scheme)", "Δt / (h²/6ν)  (paper eq. 3)")
        panel(axes[1, k], [c for c in free if c["config"] == config
                           and c["scheme"] == "EulerRKC"],
              f"{name}\nEulerRKC (no viscous bound)",
              f"Δt / (0.25 τ$_p$),  τ$_p$ = ρ$_p$d²/18μ = {1e3 * tau:.3g} ms")
    panel(axes[0, 4], fixed, "fixed array (porousMedia, φ = 0.1)\nRK3 (the tutorial's scheme)",
          "Δt / (2.51 h²/12ν)")
    axes[1, 4].axis("off")
    handles = [Patch(color=COLOURS[k], label=t) for k, t in (
        ("stable", "stable: |e| ≤ |e$_{grid}$| + 1 %"),
        ("inaccurate", "inaccurate: |e| > |e$_{grid}$| + 1 %"),
        ("unstable", "unstable: failed while running (exit 1)"),
        ("refused", "refused at start (exit 2, bound named)"))]
    axes[1, 4].legend(handles=handles, loc="upper left", fontsize=8, frameon=False)
    axes[1, 4].text(0, 0.45,
                    "e: the settling velocity's error against U$_{Stokes}$/K(φ)\n"
                    "(Sangani & Acrivos) over the last quarter of the run,\n"
                    "its 90th percentile in magnitude; or the steady K\n"
                    "against Zick & Homsy;\n"
                    "e$_{grid}$: the error of the smallest step at that r/h\n"
                    "(Euler, ρ 2, or RK3), at 0.5 of the bound.\n"
                    "endTime 5 ms at ρ 1.1 and 2, 20 ms at ρ 8\n"
                    "(≥ 11 τ$_p$); cell text: signed error or exit code,\n"
                    "'step k': the step at which the run stopped.",
                    fontsize=8, va="top", transform=axes[1, 4].transAxes)
    fig.suptitle("Direct model: stability map from real runs (settlingSphere, porousMedia; "
                 "fixed deltaT, adjustTimeStep no)", fontsize=11)
    save(fig, out)


if __name__ == "__main__":
    main()
