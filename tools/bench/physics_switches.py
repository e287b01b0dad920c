#!/usr/bin/env python3
"""What the physics fsim leaves out when a scene does not need it saves, and what it moves
(issue 40, "no more physics than the scene needs"; docs/benchmarks/switches.md).

    tools/bench/physics_switches.py --before OLD_FSIMFOAM [--repeat 3] [--threads 1]
                                    [--only free|convection] [--fsim NEW_FSIMFOAM]

- Free flight (contact detection and, without torque, rotation skipped in steps where no
  pair or wall can meet): an automatic path, so it is measured between two builds, the one
  without it (`--before`, e.g. built from the commit before it) and this one, on tutorials
  whose particles fly free for part of the run. Both runs' last cloud row is compared.
- Convection off (`fsim { convection off; }`, which `model auto` sets at low Re_p): one
  build, the tutorial with and without it. The results (settling velocity, K) are compared,
  and over a sweep of Re_p the change against Oseen's estimate 3 Re_p/16.

Runs are interleaved (A B A B …) on scratch copies; prints the median wall time of each, the
ratio, the peak memory (VmHWM) and the results. Self-contained (no numpy).
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from foam_dict import set_entry  # noqa: E402
from measured_run import wait_measured  # noqa: E402

# (tutorial, youngsModulus or None): settlingColumn's beads fall free for a quarter of the
# run, then land; at E = 1e8 (glass-like stiffness) each contact takes 25 sub-steps, not 3.
# benchmarkDragLaw and particleSettling have contacts nearly always: the test's overhead.
FREE_FLIGHT = (("settlingColumn", None), ("settlingColumn", "1e8"), ("benchmarkDragLaw", None),
               ("particleSettling", None))
CONVECTION = ("settlingSphere", "porousMedia")
# porousMedia's Ubar scaled (Re_p 0.016 in the tutorial), on model auto's 10^3 grid
RE_SWEEP = (1, 10, 100, 1000)


def default_fsim():
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "release", "fsimFoam")


def scratch(tutorial, root, name):
    case = os.path.join(root, name)
    shutil.copytree(os.path.join(ROOT, "tutorials", tutorial), case)
    return case


def edit(path, entry, value):
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(set_entry(text, entry, value))


def convection(case, on):
    """Writes `convection on|off;` into fvSolution's fsim dictionary (made when absent)."""
    path = os.path.join(case, "system", "fvSolution")
    with open(path) as f:
        text = f.read()
    word = "on" if on else "off"
    if re.search(r"^fsim\s*$|^fsim\s*\{", text, re.M):
        text = re.sub(r"^(fsim\s*\{|fsim\s*\n\{)", rf"\1\n    convection {word};", text, 1,
                      flags=re.M)
    else:
        text += f"\nfsim\n{{\n    convection {word};\n}}\n"
    with open(path, "w") as f:
        f.write(text)


def run(fsim, case, threads):
    """Runs fsimFoam on `case` (cleaned first); (wall s, peak MB, log text, phases): each
    phase's mean step time from the fluid monitor (fluidWallTime, particleWallTime), the
    steps' median in each tenth of the run averaged over the tenths (a median per tenth
    ignores the steps another process interrupted, and the tenths keep the run's phases
    weighted as they were)."""
    for entry in os.listdir(case):
        if entry == "postProcessing" or (re.fullmatch(r"[0-9.e+-]+", entry) and entry != "0"):
            shutil.rmtree(os.path.join(case, entry))
    log = os.path.join(case, "log.fsimFoam")
    with open(log, "w") as out:
        start = time.perf_counter()
        child = subprocess.Popen([fsim, "-case", case, "-threads", str(threads)],
                                 stdout=out, stderr=subprocess.STDOUT)
        code, _, peak = wait_measured(child)
        wall = time.perf_counter() - start
    with open(log) as f:
        text = f.read()
    if code != 0:
        sys.exit(f"{case}: fsimFoam exited with {code}:\n{text[-2000:]}")
    with open(os.path.join(case, "postProcessing", "fluid", "0", "fluid.dat")) as f:
        rows = [line.split() for line in f if not line.startswith("#")]
    tenths = [rows[k * len(rows) // 10:(k + 1) * len(rows) // 10] for k in range(10)]
    phases = {name: statistics.mean(statistics.median(float(r[col]) for r in part)
                                    for part in tenths if part)
              for name, col in (("fluid", 11), ("particles", 13))}
    phases["per_step"] = [float(r[13]) for r in rows]
    return wall, peak / 2**20, text, phases


def last_row(case, monitor):
    """The last row of postProcessing/<monitor>/0/<monitor>.dat as floats."""
    path = os.path.join(case, "postProcessing", monitor, "0", f"{monitor}.dat")
    with open(path) as f:
        rows = [line.split() for line in f if line.strip() and not line.startswith("#")]
    return [float(v) for v in rows[-1]]


def compare(label_a, label_b, a, b, repeat, threads):
    """Runs a and b (fsim, case) interleaved; their medians, ratio and peak memory."""
    walls = {label_a: [], label_b: []}
    phase = {label_a: [], label_b: []}
    peaks = {label_a: 0.0, label_b: 0.0}
    logs = {}
    for _ in range(repeat):
        for label, (fsim, case) in ((label_a, a), (label_b, b)):
            wall, peak, text, phases = run(fsim, case, threads)
            walls[label].append(wall)
            phase[label].append(phases)
            peaks[label] = max(peaks[label], peak)
            logs[label] = text
    med = {k: statistics.median(v) for k, v in walls.items()}
    print(f"  {label_a}: {med[label_a]:.3f} s, {peaks[label_a]:.1f} MB   "
          f"{label_b}: {med[label_b]:.3f} s, {peaks[label_b]:.1f} MB   "
          f"ratio {med[label_b] / med[label_a]:.3f}  (medians of {repeat})")
    medians = {k: {p: statistics.median(r[p] for r in v) for p in ("fluid", "particles")}
               for k, v in phase.items()}
    for k, v in phase.items():
        medians[k]["per_step"] = [r["per_step"] for r in v]
    return logs, medians


def free_flight(args, root):
    print("Free flight: before (no free flight) and after, one build each")
    for tutorial, stiffness in FREE_FLIGHT:
        name = tutorial + (f"-E{stiffness}" if stiffness else "")
        before = scratch(tutorial, root, f"{name}-before")
        after = scratch(tutorial, root, f"{name}-after")
        if stiffness:
            for case in (before, after):
                cloud = os.path.join(case, "constant", "kinematicCloudProperties")
                with open(cloud) as f:
                    text = f.read()
                with open(cloud, "w") as f:
                    f.write(re.sub(r"youngsModulus\s+[^;]+;", f"youngsModulus {stiffness};", text))
        print(f"{name}:")
        logs, phase = compare("before", "after", (args.before, before), (args.fsim, after),
                              args.repeat, args.threads)
        a, b = phase["before"]["particles"], phase["after"]["particles"]
        print(f"  the particles' phase: {1e3 * a:.3f} ms a step before, {1e3 * b:.3f} ms after, "
              f"ratio {b / a:.3f}")
        # the steps "after" took in free flight: the particles' phase summed over them
        free = [("free flight" in line) for line in logs["after"].splitlines()
                if line.startswith("Cloud:")]
        stretch = {k: statistics.median(sum(t for t, f in zip(run, free) if f)
                                        for run in phase[k]["per_step"])
                   for k in ("before", "after")}
        if any(free):
            print(f"  over the {sum(free)} free-flight steps: {stretch['before']:.4f} s before, "
                  f"{stretch['after']:.4f} s after, ratio "
                  f"{stretch['after'] / stretch['before']:.3f}")
        steps = re.search(r"Free flight: (\d+) of (\d+) steps", logs["after"])
        a, b = last_row(before, "cloud"), last_row(after, "cloud")
        # cloud.dat: time, count, KE lin, KE rot, Ux, Uy, Uz, max overlap, sub-steps
        speed = max(abs(v) for v in a[4:7]) or 1.0
        print(f"  free-flight steps {steps.group(1)} of {steps.group(2)}; at the end the "
              f"mean velocity differs by {max(abs(x - y) for x, y in zip(a[4:7], b[4:7])) / speed:.1e} "
              f"of its largest component, the kinetic energy by "
              f"{abs(a[2] - b[2]) / max(abs(a[2]), 1e-300):.1e}")


def convection_cases(args, root):
    print("Convection: on and off, one build")
    for tutorial in CONVECTION:
        on = scratch(tutorial, root, f"{tutorial}-on")
        off = scratch(tutorial, root, f"{tutorial}-off")
        convection(on, True)
        convection(off, False)
        print(f"{tutorial}:")
        _, phase = compare("on", "off", (args.fsim, on), (args.fsim, off), args.repeat,
                           args.threads)
        a, b = phase["on"]["fluid"], phase["off"]["fluid"]
        print(f"  the fluid's phase: {1e3 * a:.3f} ms a step on, {1e3 * b:.3f} ms off, "
              f"ratio {b / a:.3f}")
        if tutorial == "settlingSphere":
            # sedimentation.dat's settlingVelocity column
            a, b = last_row(on, "sedimentation")[8], last_row(off, "sedimentation")[8]
            print(f"  settling velocity {a:.9e} (on) {b:.9e} (off): {abs(b / a - 1):.1e}")
        else:
            a, b = last_row(on, "direct")[-1], last_row(off, "direct")[-1]
            print(f"  K {a:.9e} (on) {b:.9e} (off): {abs(b / a - 1):.1e}")
    print("porousMedia on model auto's 10x10x10 grid, Ubar scaled: K with convection off "
          "against on, and Oseen's 3 Re_p/16")
    d, nu = 0.0, 1e-4
    for scale in RE_SWEEP:
        ks = []
        for on in (True, False):
            case = scratch("porousMedia", root, f"re{scale}-{'on' if on else 'off'}")
            edit(os.path.join(case, "constant", "porousParameters"), "n", "10")
            edit(os.path.join(case, "system", "fvOptions"), "drive/Ubar",
                 f"({0.001 * scale:g} 0 0)")
            convection(case, on)
            run(args.fsim, case, args.threads)
            ks.append(last_row(case, "direct")[-1])
            d = d or 2 * (0.1 * 3 / (4 * 3.141592653589793)) ** (1 / 3) * 2.8e-3
        re_p = 0.001 * scale * d / nu
        print(f"  Re_p {re_p:8.3g}: K on {ks[0]:.6e}, off {ks[1]:.6e}, change "
              f"{abs(ks[1] / ks[0] - 1):.2e}; 3 Re_p/16 = {3 * re_p / 16:.2e}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--before", help="fsimFoam built without free flight (the free-flight part)")
    ap.add_argument("--fsim", default=default_fsim())
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--only", choices=("free", "convection"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="fsim-switches-") as root:
        if args.only != "convection":
            if not args.before:
                sys.exit("--before OLD_FSIMFOAM is needed for the free-flight comparison "
                         "(or --only convection)")
            free_flight(args, root)
        if args.only != "free":
            convection_cases(args, root)


if __name__ == "__main__":
    main()
