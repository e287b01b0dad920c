#!/usr/bin/env python3
"""`model auto`'s predictions against runs of three variants that were not used to fit them.

    .venv/bin/python tools/check_auto_model.py [--out DIR] [--fsim PATH]

Each variant is a tutorial with `model auto` (docs/user-guide/choosing-a-model.md): fsimFoam
chooses the model and grid and prints its predicted error and wall time (one thread); the
run is then made on one thread and its error measured against the variant's reference:

- settlingSphere with rho_p / rho_f = 4 (the fit saw 2 only), to 10 ms, tolerance 2 %:
  the settling velocity against U_Stokes / K(phi) (Sangani & Acrivos);
- porousMedia at phi = 0.1 (the fit saw 0.01-0.45 without 0.1), tolerance 2 %: K against
  the exact K (Sangani & Acrivos' eq. 17, within 0.15 % of Zick & Homsy there);
- sedimentation: Fig. 3's suspension of 57 spheres at phi = 0.1, seed 1 (the fit saw no free
  suspension of several spheres), tolerance 3 %: v_m against the direct model's grid limit
  for these spheres, 0.4550 U_Stokes (docs/figures/README.md, cost_sedimentation).

Prints each variant's choice, predicted and measured error and time, and their ratios; the
acceptance (issue 40) is both ratios within a factor 2.
"""
import argparse
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
ROOT = TOOLS.parent
sys.path.insert(0, str(TOOLS))
import foam_dict  # noqa: E402
import measured_run  # noqa: E402
import study  # noqa: E402
import study_references as refs  # noqa: E402

GRID_LIMIT = 0.4550      # v_inf / U_Stokes of the sedimentation variant's spheres


def edit(case, file, entries):
    path = case / file
    text = path.read_text()
    for key, value in entries.items():
        text = foam_dict.set_entry(text, key, value)
    path.write_text(text)


def auto(case, tolerance):
    """`model auto; tolerance …;` in the case's couplingProperties, its other settings kept
    (porousMedia's fixedParticles)."""
    path = case / "constant" / "couplingProperties"
    text = foam_dict.set_entry(path.read_text(), "model", "auto")
    path.write_text(foam_dict.set_entry(text, "tolerance", str(tolerance)))


def settling_sphere(case):
    edit(case, "constant/kinematicCloudProperties", {"constantProperties/rho0": "4000"})
    edit(case, "system/controlDict", {"endTime": "0.01", "writeInterval": "0.01"})
    auto(case, 0.02)
    reference = refs.settling_sphere(case)["settlingVelocity"]
    return lambda: refs.monitor(case, "sedimentation")["settlingVelocity"][-1] / reference - 1


def porous_media(case):
    auto(case, 0.02)
    reference = refs.porous_media(case)["K"]
    return lambda: refs.porous_media_measure(case)["K"] / reference - 1


def sedimentation(case):
    spheres = "subModels/injectionModels/spheres/"
    edit(case, "constant/kinematicCloudProperties", {
        spheres + "type": "randomPacking", spheres + "box": "(0 0 0) (0.01 0.01 0.01)",
        spheres + "volumeFraction": "0.1", spheres + "seed": "1"})
    edit(case, "system/blockMeshDict", {
        "vertices": "( (0 0 0) (0.01 0 0) (0.01 0.01 0) (0 0.01 0) (0 0 0.01) (0.01 0 0.01) "
                    "(0.01 0.01 0.01) (0 0.01 0.01) )",
        "blocks": "( hex (0 1 2 3 4 5 6 7) (40 40 40) simpleGrading (1 1 1) )"})
    edit(case, "constant/transportProperties", {"nu": "1.5e-4"})
    edit(case, "system/fvSolution", {"fsim/timeScheme": "EulerRKC"})
    edit(case, "system/controlDict", {"deltaT": "2.8e-4", "maxDeltaT": "2.8e-4",
                                      "endTime": "0.15", "writeInterval": "0.025"})
    auto(case, 0.03)
    return lambda: refs.sedimentation_measure(case)["settlingRatio"] / GRID_LIMIT - 1


VARIANTS = {"settlingSphere": settling_sphere, "porousMedia": porous_media,
            "sedimentation": sedimentation}
CHOSEN = re.compile(r"chosen: (.*?) on (\S+) cells: .*?\((\S+) % predicted, about (\S+) (s|min|h)")


def seconds(value, unit):
    return float(value) * {"s": 1, "min": 60, "h": 3600}[unit]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=ROOT / "studies" / "auto-check")
    ap.add_argument("--fsim", default=None)
    args = ap.parse_args(argv)
    fsim = study.fsim_binary(args.fsim)
    rows = []
    for name, prepare in VARIANTS.items():
        case = args.out / name
        shutil.rmtree(case, ignore_errors=True)
        shutil.copytree(ROOT / "tutorials" / name, case,
                        ignore=shutil.ignore_patterns("*.png", "log.*"))
        measure = prepare(case)
        plan = subprocess.run([fsim, "-case", str(case), "-dry-run", "-threads", "1"],
                              capture_output=True, text=True)
        found = CHOSEN.search(plan.stdout)
        if plan.returncode != 0 or not found:
            print(f"{name}: the dry run failed ({plan.returncode}):\n{plan.stderr}{plan.stdout}")
            return 1
        label, grid, error, planned, unit = found.groups()
        predicted_error, predicted_time = float(error) / 100, seconds(planned, unit)
        with open(case / "log.fsimFoam", "w") as log:
            start = time.monotonic()
            proc = subprocess.Popen([fsim, "-case", str(case), "-threads", "1"], stdout=log,
                                    stderr=subprocess.STDOUT)
            code, _, peak = measured_run.wait_measured(proc)
            wall, peak = time.monotonic() - start, peak / 1e6
        if code != 0:
            print(f"{name}: the run failed ({code}); see {case / 'log.fsimFoam'}")
            return 1
        measured_error = abs(measure())
        rows.append((name, label, grid, predicted_error, measured_error, predicted_time, wall,
                     peak))
        print(f"{name}: {label} on {grid}: error predicted {100 * predicted_error:.2f} %, "
              f"measured {100 * measured_error:.2f} % (ratio {predicted_error / measured_error:.2f}); "
              f"time predicted {predicted_time:.1f} s, measured {wall:.1f} s (ratio "
              f"{predicted_time / wall:.2f}), {peak:.0f} MB", flush=True)
    ok = all(0.5 <= pe / me <= 2 and 0.5 <= pt / mt <= 2 for _, _, _, pe, me, pt, mt, _ in rows)
    print("within a factor 2 on every variant" if ok else "NOT within a factor 2 everywhere")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
