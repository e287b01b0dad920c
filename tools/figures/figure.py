"""What the figure scripts of this folder share: the command line, running the figure's study
(tools/study; finished points are reused) and reading the porousMedia studies' points with r/h
and the relative error of K."""
import argparse
import math
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
