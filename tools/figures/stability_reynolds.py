#!/usr/bin/env python3
"""Stability map against the particle Reynolds number: where each time scheme stops being
accurate (issue 40, item 1), both models, from real runs.

    tools/figures/draw stability_reynolds [--no-run] [--study DIR] [--out PNG]

Runs (finished points reused) the studies

- tools/figures/stability_reynolds_direct.toml: the direct model, settlingSphere (one free
  sphere, rho_p/rho_f = 2, periodic box, phi = 0.046) at r/h = 4, nu = 4e-4 ... 2.2e-6
  m^2/s, the three schemes Euler, RK3, EulerRKC at the step a user gets (adjustTimeStep yes,
  maxCo 0.5, maxDeltaT 1 s: every step is the scheme's own bound, the Courant rule or the
  sphere's response bound 0.25 tau_p, whichever is smallest);
- tools/figures/stability_reynolds_direct_reference.toml: its reference per nu, RK3 at a
  fixed step of 1/8 of the smallest step any of the three schemes took at that nu (checked
  here: a reference step above that is reported);
- tools/figures/stability_reynolds_draglaw.toml: the drag-law model, settlingInLiquid (one
  bead, Schiller-Naumann drag, h = 4 d), nu = 3e-4 ... 5e-7, its one scheme at the tutorial's
  fixed step 2e-4 s, at 5 times it (1e-3 s), and at 1/8 of it (2.5e-5 s: the reference).

Every run covers the same window, 0 <= t <= tau_p = rho_p d^2/(18 mu) from rest (the start-up,
where the time scheme's error shows: the steady settling velocity of EulerRKC and of the
projection schemes hardly depends on the step). Its error e is the relative error of the
settling velocity's history against the reference of the same grid and nu in the
time-weighted RMS norm, e = sqrt(sum_i dt_i (v_i - v_ref(t_i))^2 / tau_p) / max_t |v_ref|
over the run's own steps (v_ref interpolated linearly between the reference's steps); v is
the sedimentation monitor's settlingVelocity (direct model) or the bead's velocity along
gravity (cloud monitor, drag-law model). Re_p = |v_ref(tau_p)| d / nu, the reference's at the
window's end. The sup norm max_t |v - v_ref| / max_t |v_ref| is printed beside it, but not
classified: it catches one-step blips of a resolved sphere whose faces change as it crosses
the grid, which are no time-scheme error (the 1/8 reference against one at 1/64,
studies/settlingSphere-stability-reynolds-reference-check: sup 1.28 %, from one step, RMS
0.10 % at nu = 4e-5; sup 1.50 %, RMS 0.20 % at 6e-6).

Every cell is classified (`classify`):

- refused: fsimFoam exited with 2 (it refused the case at start);
- unstable: it failed while running (exit 1), or its history is not finite;
- inaccurate: it ran, and e > 1 % (THRESHOLD);
- stable: it ran, with e <= 1 %.

Prints every cell (with its steps, its smallest and largest step, wall time; for the drag-law
model the largest Courant number CoMax of its fluid monitor: the upwind predictor's bound is
CoMax = 1) and draws docs/figures/stability_reynolds.png: one panel per model, x = Re_p (log),
one row per scheme (or step), each cell coloured by its class with e printed.
"""
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch, Rectangle  # noqa: E402
from figure import ROOT, arguments, run_study, save, study_tool  # noqa: E402
from stability_direct import COLOURS, classify  # noqa: E402

FIGURES = ROOT / "tools" / "figures"
DIRECT_SPEC = FIGURES / "stability_reynolds_direct.toml"
DIRECT_REF_SPEC = FIGURES / "stability_reynolds_direct_reference.toml"
DRAG_SPEC = FIGURES / "stability_reynolds_draglaw.toml"
STUDY = ROOT / "studies" / "settlingSphere-stability-reynolds"
DRAG_STUDY = ROOT / "studies" / "settlingInLiquid-stability-reynolds"
OUT = ROOT / "docs" / "figures" / "stability_reynolds.png"
THRESHOLD = 0.01

D_DIRECT, D_DRAG = 2e-3, 1e-3
SCHEMES = ("Euler", "RK3", "EulerRKC")
DRAG_STEPS = (2e-4, 1e-3)          # the tutorial's step, 5 times it
DRAG_REFERENCE = 2.5e-5            # 1/8 of the tutorial's step


def monitor(point, name, column):
    """(times, values) of one column of postProcessing/<name>/0/<name>.dat; None when the
    file is missing."""
    path = point / "postProcessing" / name / "0" / f"{name}.dat"
    if not path.exists():
        return None
    columns, times, values = None, [], []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            columns = line[1:].split()
            continue
        fields = line.split()
        if fields and columns is not None:
            times.append(float(fields[0]))
            values.append(float(fields[columns.index(column)]))
    return times, values


def interpolate(times, values, t):
    """values at t, linear between the neighbouring times (0 at t = 0: the start from rest)."""
    if t <= times[0]:
        return values[0] * t / times[0]
    lo, hi = 0, len(times) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if times[mid] <= t:
            lo = mid
        else:
            hi = mid
    if t >= times[hi]:
        return values[hi]
    w = (t - times[lo]) / (times[hi] - times[lo])
    return (1 - w) * values[lo] + w * values[hi]


def history_error(run, reference):
    """The history's relative error in the time-weighted RMS (L2) norm:
    sqrt(sum_i dt_i (v_i - v_ref(t_i))^2 / t_end) / max_t |v_ref|, over the run's own steps
    (dt_i: the step ending at t_i); nan when v is not finite."""
    times, values = run
    if not all(math.isfinite(v) for v in values):
        return float("nan")
    scale = max(abs(v) for v in reference[1])
    total, previous = 0.0, 0.0
    for t, v in zip(times, values):
        total += (t - previous) * (v - interpolate(*reference, t)) ** 2
        previous = t
    return math.sqrt(total / times[-1]) / scale


def sup_error(run, reference):
    """max_t |v - v_ref| / max_t |v_ref| over the run's steps (printed beside the L2 error:
    it also catches one-step blips, see the module's docstring); nan when v is not finite."""
    times, values = run
    if not all(math.isfinite(v) for v in values):
        return float("nan")
    scale = max(abs(v) for v in reference[1])
    return max(abs(v - interpolate(*reference, t)) for t, v in zip(times, values)) / scale


def steps_of(point):
    """(smallest, largest) step of the fluid monitor, the last step (landing on endTime) left
    out, and the largest CoMax."""
    dts = monitor(point, "fluid", "deltaT")
    co = monitor(point, "fluid", "CoMax")
    if dts is None or not dts[1]:
        return None, None, None
    body = dts[1][:-1] or dts[1]
    return min(body), max(body), max(co[1]) if co else None


def rows_of(folder):
    path = folder / "results.csv"
    return study_tool.read_table(path) if path.exists() else []


def direct_cells(study, reference_study):
    refs = {}
    for r in rows_of(reference_study):
        if r["status"] == "done":
            refs[r["nu"]] = (r, monitor(reference_study / r["point"], "sedimentation",
                                        "settlingVelocity"))
    cells = []
    for r in rows_of(study):
        point = study / r["point"]
        ref_row, ref = refs.get(r["nu"], (None, None))
        run = monitor(point, "sedimentation", "settlingVelocity") \
            if r["status"] == "done" else None
        error = history_error(run, ref) if run and ref else None
        sup = sup_error(run, ref) if run and ref else None
        smallest, largest, co = steps_of(point)
        cells.append(dict(row=r, nu=r["nu"], scheme=r["fsim/timeScheme"], error=error, sup=sup,
                          re=abs(ref[1][-1]) * D_DIRECT / r["nu"] if ref else None,
                          smallest=smallest, largest=largest, co=co, ref_row=ref_row))
    # the reference's step against 1/8 of the smallest step taken at its nu
    for nu, (ref_row, _) in sorted(refs.items()):
        taken = [c["smallest"] for c in cells if c["nu"] == nu and c["smallest"]]
        if taken and ref_row["deltaT"] > min(taken) / 8 * 1.0001:
            print(f"note: the reference at nu = {nu:g} steps {ref_row['deltaT']:g} s, above 1/8 "
                  f"of the smallest step taken ({min(taken):g} s): rewrite "
                  f"{DIRECT_REF_SPEC.name}")
    return cells


def drag_cells(study):
    refs = {}
    for r in rows_of(study):
        if r["status"] == "done" and abs(r["deltaT"] - DRAG_REFERENCE) < 1e-12:
            refs[r["nu"]] = monitor(study / r["point"], "cloud", "Uz")
    cells = []
    for r in rows_of(study):
        if abs(r["deltaT"] - DRAG_REFERENCE) < 1e-12:
            continue
        point = study / r["point"]
        ref = refs.get(r["nu"])
        run = monitor(point, "cloud", "Uz") if r["status"] == "done" else None
        error = history_error(run, ref) if run and ref else None
        sup = sup_error(run, ref) if run and ref else None
        smallest, largest, co = steps_of(point)
        cells.append(dict(row=r, nu=r["nu"], scheme=r["deltaT"], error=error, sup=sup,
                          re=abs(ref[1][-1]) * D_DRAG / r["nu"] if ref else None,
                          smallest=smallest, largest=largest, co=co))
    return cells


def label_of(scheme):
    if isinstance(scheme, str):
        return scheme
    return f"Δt {scheme:g} s" + (" (tutorial)" if scheme == DRAG_STEPS[0] else "")


def print_cells(title, cells):
    print(f"\n{title}")
    print("nu         Re_p      scheme / step         outcome     error %  sup %   steps  "
          "smallest step  largest step  CoMax  wall s  message")
    for c in cells:
        r = c["row"]
        err = f"{100 * c['error']:8.3f}" if c["error"] is not None else "       -"
        err += f"  {100 * c['sup']:6.2f}" if c["sup"] is not None else "       -"
        wall = r.get("wall_time")
        print(f"{c['nu']:<9.3g}  {c['re'] if c['re'] is not None else float('nan'):8.3g}  "
              f"{label_of(c['scheme']):<20}  {c['outcome'] or '-':<10} {err}  "
              f"{r.get('steps') if r.get('steps') == r.get('steps') else '-':>5}  "
              f"{c['smallest'] or float('nan'):13.3g}  {c['largest'] or float('nan'):12.3g}  "
              f"{c['co'] if c['co'] is not None else float('nan'):5.3f}  "
              f"{wall if isinstance(wall, float) else float('nan'):6.2f}  "
              f"{(r.get('message') or '').splitlines()[0][:80] if r.get('message') else ''}")


def first_inaccurate(cells, scheme):
    """The smallest and largest Re_p at which `scheme` is not stable, and the stable
    ones, for the headline."""
    mine = sorted((c for c in cells if c["scheme"] == scheme and c["re"] is not None),
                  key=lambda c: c["re"])
    return [(c["re"], c["outcome"]) for c in mine]


def panel(ax, cells, rows, title):
    res = sorted({c["re"] for c in cells if c["re"] is not None})
    logs = [math.log10(x) for x in res]
    edges = {}
    for k, x in enumerate(logs):
        left = (x + logs[k - 1]) / 2 if k else x - (logs[1] - logs[0]) / 2
        right = (x + logs[k + 1]) / 2 if k + 1 < len(logs) else x + (logs[-1] - logs[-2]) / 2
        edges[res[k]] = (left, right)
    for j, scheme in enumerate(rows):
        for c in cells:
            if c["scheme"] != scheme or c["re"] is None or c["outcome"] is None:
                continue
            left, right = edges[c["re"]]
            ax.add_patch(Rectangle((left, j - 0.45), right - left, 0.9,
                                   color=COLOURS[c["outcome"]], ec="white", lw=1.5))
            if c["outcome"] in ("refused", "unstable"):
                text = f"exit {c['row'].get('exit_code')}"
            else:
                text = f"{100 * c['error']:.2f} %" if c["error"] < 0.1 \
                    else f"{100 * c['error']:.1f} %"
            ax.text((left + right) / 2, j, text, ha="center", va="center", fontsize=8)
    ax.set_xlim(min(e[0] for e in edges.values()), max(e[1] for e in edges.values()))
    ax.set_ylim(-0.5, len(rows) - 0.5)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([label_of(s) for s in rows])
    lo, hi = math.floor(ax.get_xlim()[0]), math.ceil(ax.get_xlim()[1])
    ticks = [t for t in range(lo, hi + 1) if ax.get_xlim()[0] <= t <= ax.get_xlim()[1]]
    ax.set_xticks(ticks)
    ax.set_xticklabels([f"10$^{{{t}}}$" for t in ticks])
    ax.set_xlabel("particle Reynolds number Re$_p$ = v d / ν  (v: the reference's at t = τ$_p$)")
    ax.set_title(title, fontsize=9)
    for x in res:
        ax.axvline(math.log10(x), color="0.3", lw=0.4, ls=":", zorder=0)


def main(argv=None):
    parser = arguments(__doc__, STUDY, OUT)
    parser.add_argument("--drag-study", type=Path, default=DRAG_STUDY)
    args = parser.parse_args(argv)
    reference_study = args.study.with_name(args.study.name + "-reference")
    if not args.no_run:
        run_study(DIRECT_SPEC, args.study)
        run_study(DIRECT_REF_SPEC, reference_study)
        run_study(DRAG_SPEC, args.drag_study)

    direct = direct_cells(args.study, reference_study)
    drag = drag_cells(args.drag_study)
    for c in direct + drag:
        c["outcome"] = classify(c["row"]["status"], c["row"].get("exit_code"), c["error"],
                                THRESHOLD)
    direct.sort(key=lambda c: (SCHEMES.index(c["scheme"]), -c["nu"]))
    drag.sort(key=lambda c: (c["scheme"], -c["nu"]))
    print_cells("direct model (settlingSphere, r/h = 4, adjustTimeStep yes, maxCo 0.5)",
                direct)
    print_cells("drag-law model (settlingInLiquid, h = 4 d, fixed step)", drag)
    print(f"\nclasses (inaccurate: e > {100 * THRESHOLD:g} %) against Re_p:")
    for cells, rows in ((direct, SCHEMES), (drag, DRAG_STEPS)):
        for scheme in rows:
            print(f"  {label_of(scheme):<20} " + ", ".join(
                f"{re:.3g}: {o}" for re, o in first_inaccurate(cells, scheme)))
    runs = [c["row"] for c in direct + drag] + rows_of(reference_study) + [
        r for r in rows_of(args.drag_study) if abs(r["deltaT"] - DRAG_REFERENCE) < 1e-12]
    walls = [r["wall_time"] for r in runs if isinstance(r.get("wall_time"), float)]
    print(f"\n{len(runs)} runs, {sum(walls):.1f} s of wall time (1 thread each)")

    fig, axes = plt.subplots(1, 2, figsize=(15, 4.6), gridspec_kw=dict(width_ratios=[1, 1]))
    panel(axes[0], direct, SCHEMES,
          "direct model: settlingSphere (ρ$_p$/ρ$_f$ = 2, φ = 0.046), r/h = 4,\n"
          "the step a user gets: adjustTimeStep yes, maxCo 0.5, each scheme's own bound;\n"
          "reference: RK3 at 1/8 of the smallest step taken")
    panel(axes[1], drag, DRAG_STEPS,
          "drag-law model: settlingInLiquid (ρ$_p$/ρ$_f$ = 2.5, h = 4 d), its one scheme\n"
          "(implicit Euler predictor, upwind) at a fixed step; reference: Δt 2.5·10$^{-5}$ s\n"
          f"(1/8 of the tutorial's); largest Courant number of any run "
          f"{max(c['co'] for c in drag if c['co'] is not None):.2g} (its bound: 1)")
    handles = [Patch(color=COLOURS[k], label=t) for k, t in (
        ("stable", f"stable: e ≤ {100 * THRESHOLD:g} %"),
        ("inaccurate", f"inaccurate: e > {100 * THRESHOLD:g} %"),
        ("unstable", "unstable: failed while running (exit 1)"),
        ("refused", "refused at start (exit 2)"))]
    fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=9, frameon=False)
    fig.text(0.5, 0.075,
             "e: the settling velocity's history from rest over 0 ≤ t ≤ τ$_p$ = ρ$_p$d²/18μ "
             "against the reference of the same grid and ν: RMS over time of v − v$_{ref}$, "
             "over max |v$_{ref}$|",
             ha="center", fontsize=9)
    fig.suptitle("Where each time scheme stops being accurate: the particle Reynolds number "
                 "(real runs; ν varied)", fontsize=11)
    fig.tight_layout(rect=(0, 0.11, 1, 0.95))
    save(fig, args.out)


if __name__ == "__main__":
    main()
