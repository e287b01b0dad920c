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
TUTORIAL = os.path.join(ROOT, "tutorials", "benchmarkDragLaw")
PARTICLES = 500
CELLS = 12 * 36 * 12


def default_fsim():
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "release", "fsimFoam")


def vm_hwm_kb(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def run_measured(cmd, cwd, log):
    """Runs `cmd`; returns (wall s, cpu s, VmHWM kB, ru_maxrss kB, exit status)."""
    with open(log, "w") as out:
        start = time.perf_counter()
        child = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
        hwm = 0
        while True:
            pid, status, usage = os.wait4(child.pid, os.WNOHANG)
            if pid:
                break
            hwm = max(hwm, vm_hwm_kb(child.pid))
            time.sleep(0.005)
        wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    return wall, usage.ru_utime + usage.ru_stime, hwm, usage.ru_maxrss, child.returncode


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
        wall, cpu, hwm, maxrss, code = run_measured(cmd, case, log)
        text = open(log).read()
        if code != 0:
            sys.exit(f"fsimFoam failed ({code}):\n{text[-2000:]}")
        steps = len(re.findall(r"^Time = ", text, flags=re.M))
        # ru_maxrss also counts the forked Python image before exec: VmHWM is the solver's.
        peak_mb = (hwm or maxrss) / 1024.0
        print(f"benchmarkDragLaw (paper section 3.3, drag law, h = 2r): {PARTICLES} particles, "
              f"{CELLS} cells, endTime {args.end:g} s, {args.threads} threads")
        print(f"  fluid steps      {steps}")
        print(f"  wall             {wall:.2f} s   (target < 5 s)")
        print(f"  CPU              {cpu:.2f} s")
        print(f"  peak memory      {peak_mb:.1f} MB (VmHWM {hwm / 1024:.1f} MB, "
              f"ru_maxrss incl. the fork {maxrss / 1024:.1f} MB; target < 20 MB)")
        print(f"  particle-steps/s {PARTICLES * steps / wall:.3e}")
        print(f"  cell-steps/s     {CELLS * steps / wall:.3e}")
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
