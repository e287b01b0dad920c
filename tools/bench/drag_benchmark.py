#!/usr/bin/env python3
"""The drag-law variant of the paper's section 3.3 benchmark: fsimFoam on
tutorials/benchmarkDragLaw (500 particles, 12 x 36 x 12 cells, 0.1 s of physical time).

    tools/bench/drag_benchmark.py [--threads 2] [--end 0.1] [--nice 0] [--fsim PATH]

Runs a scratch copy of the tutorial and prints wall time, CPU time (user + system of the
child), peak memory (the child's VmHWM, sampled from /proc, and its ru_maxrss), the number of
fluid steps, and the rates particle-steps/s and cell-steps/s (per wall second). The issue's
targets: under 5 s and under 20 MB (the paper: 13 min and 0.5 MB on a SUN Ultra SPARC).
Self-contained (no numpy); fsimFoam defaults to target/release/fsimFoam under the
repository, or $CARGO_TARGET_DIR/release/fsimFoam.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from measured_run import wait_measured  # noqa: E402
TUTORIAL = os.path.join(ROOT, "tutorials", "benchmarkDragLaw")
PARTICLES = 500
CELLS = 12 * 36 * 12


def default_fsim():
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "release", "fsimFoam")


def run_measured(cmd, cwd, log):
    """Runs `cmd`; returns (wall s, cpu s, VmHWM kB, exit status)."""
    with open(log, "w") as out:
        start = time.perf_counter()
        child = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
        code, cpu, peak = wait_measured(child)
        wall = time.perf_counter() - start
    return wall, cpu, peak // 1024, code


def set_entry(path, key, value):
    text = open(path).read()
    text, n = re.subn(rf"^{key}\s+[^;]*;", f"{key} {value};", text, flags=re.M)
    if n != 1:
        sys.exit(f"{path}: no single '{key}' entry")
    open(path, "w").write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--end", type=float, default=0.1, help="endTime, s")
    ap.add_argument("--nice", type=int, default=0)
    ap.add_argument("--fsim", default=default_fsim())
    args = ap.parse_args()
    if not os.path.exists(args.fsim):
        sys.exit(f"no fsimFoam at {args.fsim}: cargo build --release first")
    scratch = tempfile.mkdtemp(prefix="fsim-drag-bench-")
    try:
        case = os.path.join(scratch, "benchmarkDragLaw")
        shutil.copytree(TUTORIAL, case)
        control = os.path.join(case, "system", "controlDict")
        set_entry(control, "endTime", f"{args.end:g}")
        set_entry(control, "writeInterval", f"{args.end:g}")
        cmd = (["nice", "-n", str(args.nice)] if args.nice else []) + [
            args.fsim, "-case", case, "-threads", str(args.threads)]
        log = os.path.join(case, "log.fsimFoam")
        wall, cpu, hwm, code = run_measured(cmd, case, log)
        text = open(log).read()
        if code != 0:
            sys.exit(f"fsimFoam failed ({code}):\n{text[-2000:]}")
        steps = len(re.findall(r"^Time = ", text, flags=re.M))
        peak_mb = hwm / 1024.0  # the solver's VmHWM (tools/measured_run.py)
        print(f"benchmarkDragLaw (paper section 3.3, drag law, h = 2r): {PARTICLES} particles, "
              f"{CELLS} cells, endTime {args.end:g} s, {args.threads} threads")
        print(f"  fluid steps      {steps}")
        print(f"  wall             {wall:.2f} s   (target < 5 s)")
        print(f"  CPU              {cpu:.2f} s")
        print(f"  peak memory      {peak_mb:.1f} MB (VmHWM; target < 20 MB)")
        print(f"  particle-steps/s {PARTICLES * steps / wall:.3e}")
        print(f"  cell-steps/s     {CELLS * steps / wall:.3e}")
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
