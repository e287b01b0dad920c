"""What the figure scripts of this folder share: the command line, running the figure's study
(tools/study; finished points are reused), reading the porousMedia studies' points with r/h
and the relative error of K, and for the accuracy-against-cost charts the Pareto front, the
cheapest point within an error bound and a block's cell counts."""
import argparse
import math
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import study as study_tool  # noqa: E402


def arguments(doc, study, out):
    """The parser of a figure script: --no-run, --study DIR, --out PNG."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("--no-run", action="store_true",
                        help="draw from the study's results.csv as it is")
    parser.add_argument("--study", type=Path, default=study)
    parser.add_argument("--out", type=Path, default=out)
    return parser


def run_study(spec, study):
    """Runs (or resumes) the study of `spec` into `study`; exits unless it finished, or
    finished with failed points (exit 1: the others are drawn)."""
    done = subprocess.run([str(ROOT / "tools" / "study"), "run", "--spec", str(spec),
                           "--out", str(study)])
    if done.returncode not in (0, 1):
        sys.exit(done.returncode)


def porous_points(study):
    """The study's finished porousMedia points, with r/h and K's signed relative error."""
    rows = study_tool.finished_points(study)
    for row in rows:
        row["r_over_h"] = row["n"] * (3 * row["phi"] / (4 * math.pi)) ** (1 / 3)
        row["signed"] = row["measured.K"] / row["reference.K"] - 1
    return rows


def pareto(rows, cost="wall_time", error="error"):
    """The points no other point beats in both `cost` and `error`, by cost."""
    front, best = [], math.inf
    for r in sorted(rows, key=lambda r: (r[cost], r[error])):
        if r[error] < best:
            front.append(r)
            best = r[error]
    return front


def cheapest(rows, bound, cost="wall_time", error="error"):
    """The row of least `cost` whose `error` is within `bound`; None when there is none."""
    ok = [r for r in rows if r[error] <= bound]
    return min(ok, key=lambda r: r[cost]) if ok else None


def block_cells(blocks):
    """The cell counts (nx, ny, nz) of a blockMeshDict `blocks` value of one hex."""
    found = re.search(r"hex\s*\([^()]*\)\s*\(\s*(\d+)\s+(\d+)\s+(\d+)\s*\)", str(blocks))
    return tuple(int(v) for v in found.groups())


def print_front_and_cheapest(rows, bounds, describe, closer_to):
    """Prints the Pareto front of `rows` and the cheapest run within each bound; the front."""
    front = pareto(rows)
    print(f"\nPareto front (no run is both cheaper and closer to {closer_to}):")
    for r in front:
        print(f"  {describe(r)}")
    print("\ncheapest run (wall time) within each error bound")
    for bound in bounds:
        best = cheapest(rows, bound)
        print(f"  {100 * bound:2g} %: {describe(best) if best else 'none'}")
    return front


def cost_axes(ax, bounds, front=None):
    """An error-against-wall-time panel's common parts: the Pareto front (when given), a
    grey line per error bound, the time axis and the grid."""
    if front is not None:
        ax.loglog([r["wall_time"] for r in front], [100 * r["error"] for r in front], "k-",
                  lw=1.5, label="Pareto front")
    for bound in bounds:
        ax.axhline(100 * bound, color="0.6", lw=0.8)
    ax.set_xlabel("wall time of the run (s, 1 thread)")
    ax.grid(True, which="both", alpha=0.3)


def save(fig, out):
    """Writes the figure to `out` (its folder made) and says so."""
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    print(f"\nwrote {out.relative_to(ROOT) if out.is_relative_to(ROOT) else out}")


def describe_bed(r, interpolation):
    """One run of a bed's cost chart: its grid (r["cells"], h/d), step, the interpolation
    (the column `interpolation`), endTime, signed error, wall time and peak memory."""
    nx, ny, nz = r["cells"]
    return (f"{nx}x{ny}x{nz} (h = {r['h_over_d']:g} d), deltaT {r['deltaT']:g} s, "
            f"{r[interpolation]}, endTime {r['endTime']:g} s: {100 * r['signed']:+.2f} %, "
            f"{r['wall_time']:.2f} s, {r['peak_memory_mb']:.1f} MB")


def run_refused_points(tutorial, args, folder, reference):
    """Points fsimFoam's dry run rejects, which a study will not run (a study with a rejected
    point runs none): their case copies by `tools/study run … --check` (which stops at the
    rejection), then each started by fsimFoam itself, then the table rebuilt."""
    tool = str(ROOT / "tools" / "study")
    subprocess.run([tool, "run", tutorial, *args, "--reference", reference, "--check",
                    "--workers", "1", "--out", str(folder)],
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    fsim = study_tool.fsim_binary(None)
    for point in sorted(folder.glob("point-*")):
        if not (point / "done.json").exists():
            record = study_tool.run_point(point, fsim, 1)
            print(f"  {folder.name}/{point.name}: exit {record.get('exit_code')}")
    done = subprocess.run([tool, "table", str(folder)], stdout=subprocess.DEVNULL)
    if done.returncode != 0:
        sys.exit(done.returncode)
