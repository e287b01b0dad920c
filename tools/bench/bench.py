#!/usr/bin/env python3
"""fsim benchmark: throughput, wall time and peak memory, side by side with OpenFOAM.

    tools/bench/bench.py [--sizes 64 128] [--threads 1 2] [--steps 20] [--no-openfoam]
    tools/bench/bench.py --suite direct [--direct-end 0.1] [--direct-scaling]

Runs the 2-D Taylor-Green vortex in a periodic n^3 box (nu = 0.05, dt = 0.005) with fsimFoam
at each size and thread count, and OpenFOAM's icoFoam (Debian package `openfoam`, its cavity
tutorial's solver settings) on the same grid, time step and number of steps. Prints cell-steps
per second (time loop only, from fsim's per-step monitor and icoFoam's ExecutionTime), whole
wall time, peak resident memory (bytes per cell), the velocity error against the exact
solution at the final time, and the ratio fsim / icoFoam. The machines are shared and noisy:
only ratios from one run mean anything, and each figure is the median of `--repeat` runs.

`--suite direct` runs tutorials/benchmark (the paper's section 3.3 case with the direct model:
60 x 180 x 60 cells, 500 particles; `--direct-end` shortens its 0.1 s of physical time) and
prints wall time, peak memory (VmHWM), cell-steps per second of the whole coupled step and the
shares of the time loop spent in the fluid, the coupling (no-slip, stress integral,
lubrication) and the particles (DEM), from fsim's per-step monitor. `--direct-scaling` adds
the same box at r/h = 2.5, 3.33 and 5 and with 125, 250 and 500 particles. A short run is
projected to 0.1 s as (time per step) x (steps for 0.1 s): `--direct-steps N` when given (the
tutorial's semi-implicit step follows maxCo, and its steps for 0.1 s come from the flow, not
from a short run), else 0.1 s over the run's last full step.
"""
import argparse
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import cases  # noqa: E402

sys.path.insert(0, os.path.dirname(HERE))
import direct_cases  # noqa: E402
from measured_run import wait_measured  # noqa: E402

NU = 0.05
DT = 0.005
FOAM_ENV = dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam", FOAM_ETC="/usr/share/openfoam/etc")


def run_measured(cmd, cwd, env=None, log=None):
    """Run a command; return (wall seconds, peak RSS bytes: the child's VmHWM, polled,
    tools/measured_run.py). fsimFoam also prints its own peak at the end of its log (read by
    run_fsim)."""
    out = open(log, "w") if log else subprocess.DEVNULL
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
    _, _, peak = wait_measured(p)
    wall = time.perf_counter() - t0
    if log:
        out.close()
    if p.returncode != 0:
        tail = open(log).read()[-2000:] if log else ""
        raise RuntimeError(f"{cmd[0]} failed in {cwd}:\n{tail}")
    return wall, peak


def exact_velocity(centres, t):
    decay = math.exp(-2.0 * NU * t)
    x, y = centres[:, 0], centres[:, 1]
    return np.stack([np.sin(x) * np.cos(y) * decay, -np.cos(x) * np.sin(y) * decay, 0 * x], axis=1)


def relative_l2(u, exact):
    return float(np.sqrt(np.sum((u - exact) ** 2) / np.sum(exact ** 2)))


def fsim_binary():
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "release", "fsimFoam")


def latest_time_dir(case):
    times = [d for d in os.listdir(case) if re.fullmatch(r"[0-9.e+-]+", d) and d != "0"]
    return max(times, key=float)


def run_fsim(binary, n, threads, steps, scratch, scheme):
    import meshio

    case = os.path.join(scratch, f"fsim_{n}_{threads}")
    shutil.rmtree(case, ignore_errors=True)
    end = cases.taylor_green(case, n, steps, DT, nu=NU, scheme=scheme)
    log = os.path.join(case, "log.fsimFoam")
    wall, rss = run_measured([binary, "-case", case, "-threads", str(threads)], scratch, log=log)
    reported = re.findall(r"Peak memory = ([0-9.]+) MB", open(log).read())
    if reported:
        rss = max(rss, float(reported[-1]) * 1e6)
    monitor = os.path.join(case, "postProcessing", "fluid", "0", "fluid.dat")
    data = np.loadtxt(monitor, comments="#")
    names = open(monitor).readline().lstrip("#").split()
    step_wall = data[:, names.index("stepWallTime")]
    loop = float(np.sum(step_wall[1:])) * len(step_wall) / max(len(step_wall) - 1, 1)
    last = latest_time_dir(case)
    mesh = meshio.read(os.path.join(case, last, "fluid.vtk"))
    u = np.asarray(mesh.cell_data["U"][0])
    pts = mesh.points
    cells = mesh.cells[0].data
    centres = pts[cells].mean(axis=1)
    err = relative_l2(u, exact_velocity(centres, end))
    return dict(solver=f"fsim {scheme}", n=n, threads=threads, steps=len(step_wall), loop=loop, wall=wall,
                rss=rss, cells=n ** 3, error=err)


def read_foam_vectors(path):
    text = open(path).read()
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s*(\d+)\s*\(", text)
    count = int(m.group(1))
    body = text[m.end():]
    nums = re.findall(r"\(([^()]*)\)", body[: body.find("\n)")])
    arr = np.array([[float(v) for v in s.split()] for s in nums[:count]])
    return arr


def run_icofoam(n, steps, scratch):
    if shutil.which("icoFoam") is None:
        return None
    case = os.path.join(scratch, f"ico_{n}")
    shutil.rmtree(case, ignore_errors=True)
    end = cases.taylor_green(case, n, steps, DT, nu=NU)
    run_measured(["blockMesh"], case, env=FOAM_ENV, log=os.path.join(case, "log.blockMesh"))
    wall, rss = run_measured(["icoFoam"], case, env=FOAM_ENV, log=os.path.join(case, "log.icoFoam"))
    exec_times = [float(x) for x in re.findall(r"ExecutionTime = ([0-9.e+-]+) s",
                                               open(os.path.join(case, "log.icoFoam")).read())]
    per_step = (exec_times[-1] - exec_times[0]) / max(len(exec_times) - 1, 1)
    loop = per_step * steps
    h = 2 * math.pi / n
    idx = np.arange(n)
    cx, cy, cz = np.meshgrid((idx + 0.5) * h, (idx + 0.5) * h, (idx + 0.5) * h, indexing="ij")
    centres = np.stack([cx.ravel(order="F"), cy.ravel(order="F"), cz.ravel(order="F")], axis=1)
    u = read_foam_vectors(os.path.join(case, latest_time_dir(case), "U"))
    err = relative_l2(u, exact_velocity(centres, end))
    return dict(solver="icoFoam", n=n, threads=1, steps=steps, loop=loop, wall=wall, rss=rss,
                cells=n ** 3, error=err)


def run_direct(binary, scratch, threads, end, cells_per_radius=2.5, particles=500):
    """tutorials/benchmark (or a variant at another r/h or particle count) for `end` s."""
    case = os.path.join(scratch, f"direct_{cells_per_radius:g}_{particles}_{threads}_{end:g}")
    shutil.rmtree(case, ignore_errors=True)
    if cells_per_radius == 2.5 and particles == 500:
        src = os.path.join(ROOT, "tutorials", "benchmark")
        for sub in ("system", "constant", "0"):
            shutil.copytree(os.path.join(src, sub), os.path.join(case, sub))
        text = open(os.path.join(case, "system", "controlDict")).read()
        text = re.sub(r"\nendTime\s+[^;]+;", f"\nendTime         {end:g};", text)
        text = re.sub(r"\nwriteInterval\s+[^;]+;", f"\nwriteInterval   {end:g};", text)
        open(os.path.join(case, "system", "controlDict"), "w").write(text)
    else:
        direct_cases.benchmark(case, end_time=end, cells_per_radius=cells_per_radius,
                               particles=particles)
    plan = dry_run_plan(binary, case, threads)
    log = os.path.join(case, "log.fsimFoam")
    wall, rss = run_measured([binary, "-case", case, "-threads", str(threads)], scratch, log=log)
    reported = re.findall(r"Peak memory = ([0-9.]+) MB", open(log).read())
    if reported:
        rss = max(rss, float(reported[-1]) * 1e6)
    monitor = os.path.join(case, "postProcessing", "fluid", "0", "fluid.dat")
    data = np.loadtxt(monitor, comments="#", ndmin=2)
    names = open(monitor).readline().lstrip("#").split()
    col = lambda n: data[:, names.index(n)] if n in names else np.zeros(len(data))  # noqa: E731
    loop = float(np.sum(col("stepWallTime")))
    # the last two steps may be shortened to land on endTime
    full_step = float(np.max(col("deltaT")[-3:]))
    phases = {k: float(np.sum(col(k + "WallTime"))) for k in ("fluid", "coupling", "particle")}
    cells = int(np.prod([round(c * cells_per_radius) for c in (24, 72, 24)]))
    return dict(solver=f"direct r/h={cells_per_radius:g} n_p={particles}", threads=threads,
                steps=len(data), loop=loop, wall=wall, rss=rss, cells=cells, end=end,
                full_step=full_step, plan=plan, **phases)


def dry_run_plan(binary, case, threads):
    """What `fsimFoam -dry-run` plans for the case (it times a few steps in memory): steps,
    seconds of run time and the peak memory after its timed steps, to print beside what the
    run then measures."""
    out = subprocess.run([binary, "-case", case, "-threads", str(threads), "-dry-run"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        print(f"-dry-run of {case} failed ({out.returncode}): {out.stderr.strip()}",
              file=sys.stderr)
    number = lambda pattern: (  # noqa: E731
        float(m.group(1)) if (m := re.search(pattern, out.stdout)) else float("nan"))
    return dict(steps=number(r"Steps\s*: about ([0-9.e+]+)"),
                seconds=number(r"Run time: about ([0-9.e+]+) s"),
                peak_mb=number(r"peak after the timed steps ([0-9.]+) MB"))


def direct_suite(binary, scratch, a):
    rows = [run_direct(binary, scratch, t, a.direct_end) for t in a.threads]
    if a.direct_scaling:
        t = max(a.threads)
        for cpr in (3.333333, 5.0):
            rows.append(run_direct(binary, scratch, t, a.direct_scaling_end, cells_per_radius=cpr))
        rows.append(run_direct(binary, scratch, t, a.direct_scaling_end))
        for n_p in (125, 250):
            rows.append(run_direct(binary, scratch, t, a.direct_scaling_end, particles=n_p))
    print("\ntutorials/benchmark (paper section 3.3), direct model; noisy shared machine")
    print(f"{'case':28} {'thr':>3} {'end s':>8} {'steps':>6} {'cells':>9} {'Mcell-steps/s':>13} "
          f"{'loop s':>8} {'wall s':>8} {'peak MB':>8} {'fluid':>6} {'coupl':>6} {'part':>6}")
    for r in rows:
        rate = r["cells"] * r["steps"] / max(r["loop"], 1e-9)
        share = {k: 100 * r[k] / max(r["loop"], 1e-9) for k in ("fluid", "coupling", "particle")}
        print(f"{r['solver']:28} {r['threads']:>3} {r['end']:>8.1e} {r['steps']:>6} {r['cells']:>9} "
              f"{rate / 1e6:>13.2f} {r['loop']:>8.2f} {r['wall']:>8.2f} {r['rss'] / 1e6:>8.1f} "
              f"{share['fluid']:>5.1f}% {share['coupling']:>5.1f}% {share['particle']:>5.1f}%")
        p = r["plan"]
        print(f"{'':28} -dry-run planned {p['steps']:.0f} steps, about {p['seconds']:.0f} s "
              f"({p['seconds'] / max(r['loop'], 1e-9):.2f} of the time loop), "
              f"{p['peak_mb']:.1f} MB after its timed steps")
        if r["end"] == a.direct_end and a.direct_end < 0.1 and "r/h=2.5 n_p=500" in r["solver"]:
            per_step = r["loop"] / r["steps"]
            steps = a.direct_steps or 0.1 / r["full_step"]
            source = "--direct-steps" if a.direct_steps else f"0.1 s / last step {r['full_step']:.3g} s"
            print(f"{'':28} {per_step:.3f} s per step; projected to 0.1 s: {steps:.0f} steps "
                  f"({source}), about {per_step * steps:.0f} s of time loop")


def median_run(fn, repeat):
    runs = [fn() for _ in range(repeat)]
    runs = [r for r in runs if r]
    if not runs:
        return None
    best = dict(runs[0])
    for key in ("loop", "wall", "rss"):
        best[key] = statistics.median(r[key] for r in runs)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[64, 128])
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--openfoam-sizes", type=int, nargs="*", default=[64])
    ap.add_argument("--no-openfoam", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--schemes", nargs="+", default=["Euler", "RK3"],
                    help="fsim time schemes to run (Euler: one projection per step)")
    ap.add_argument("--suite", nargs="+", default=["taylorGreen"], choices=["taylorGreen", "direct"])
    ap.add_argument("--direct-end", type=float, default=0.1,
                    help="physical time of tutorials/benchmark (0.1 s in the paper)")
    ap.add_argument("--direct-steps", type=float, default=None,
                    help="steps for 0.1 s of the benchmark, for the projection (default: 0.1 s "
                         "over the short run's last full step)")
    ap.add_argument("--direct-scaling", action="store_true",
                    help="also r/h = 2.5, 3.33, 5 and 125, 250, 500 particles")
    ap.add_argument("--direct-scaling-end", type=float, default=3e-5,
                    help="physical time of each scaling run (r/h = 5: about 30 steps)")
    a = ap.parse_args()

    binary = fsim_binary()
    if "direct" in a.suite:
        scratch = tempfile.mkdtemp(prefix="fsim-bench-")
        try:
            direct_suite(binary, scratch, a)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        if "taylorGreen" not in a.suite:
            return
    scratch = tempfile.mkdtemp(prefix="fsim-bench-")
    rows = []
    try:
        for n in a.sizes:
            for scheme in a.schemes:
                for t in a.threads:
                    rows.append(median_run(
                        lambda: run_fsim(binary, n, t, a.steps, scratch, scheme), a.repeat))
            if not a.no_openfoam and n in a.openfoam_sizes:
                r = median_run(lambda: run_icofoam(n, a.steps, scratch), 1)
                if r:
                    rows.append(r)
                else:
                    print("note: icoFoam not found (apt-get install openfoam); no comparison")
    finally:
        shutil.rmtree(scratch, ignore_errors=True)

    print(f"\nTaylor-Green vortex, nu = {NU}, dt = {DT}, {a.steps} steps "
          f"(medians of {a.repeat} runs for fsim)")
    print(f"{'solver':10} {'cells':>9} {'thr':>3} {'Mcell-steps/s':>13} {'loop s':>8} {'wall s':>8} "
          f"{'peak MB':>8} {'B/cell':>7} {'L2 error':>10}")
    for r in rows:
        r["rate"] = r["cells"] * r["steps"] / r["loop"]
        print(f"{r['solver']:10} {r['cells']:>9} {r['threads']:>3} {r['rate'] / 1e6:>13.2f} "
              f"{r['loop']:>8.2f} {r['wall']:>8.2f} {r['rss'] / 1e6:>8.1f} "
              f"{r['rss'] / r['cells']:>7.0f} {r['error']:>10.3e}")
    for r in rows:
        if r["solver"] != "icoFoam":
            continue
        for f in rows:
            if f["solver"].startswith("fsim") and f["n"] == r["n"]:
                print(f"ratio {f['solver']} ({f['threads']} thr) / icoFoam at {r['n']}^3: "
                      f"throughput x{f['rate'] / r['rate']:.1f}, "
                      f"error {f['error'] / r['error']:.2f} of icoFoam's")


if __name__ == "__main__":
    main()
