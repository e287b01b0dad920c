"""tools/crosscheck (issue 38): every cross-check tutorial agrees with DPMFoam's histories in
its reference file, and a deliberately wrong physical setting fails, naming the quantity.

These run DPMFoam's side from `crosscheck_reference.csv` (a real DPMFoam v1912 run, its date in
the file), so they take seconds; `tools/test` runs the same cases against the live DPMFoam
afterwards.
"""
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TUTORIALS = ROOT / "tutorials"
CASES = sorted(p.parent.name for p in TUTORIALS.glob("*/crosscheck.toml"))


def crosscheck(fsim, case, *args, out):
    return subprocess.run(
        [sys.executable, str(ROOT / "tools" / "crosscheck.py"), str(case), "--reference",
         "--fsim", str(fsim), "--out", str(out), *args],
        capture_output=True, text=True, timeout=600)


def test_the_issue_cases_are_there():
    assert {"settlingInLiquid", "settlingColumn", "fluidizedBed", "packedBed"} <= set(CASES)
    assert any(name.startswith("impacts") for name in CASES)


@pytest.mark.parametrize("name", CASES)
def test_case_agrees_with_dpmfoams_reference(fsim, name, tmp_path):
    pending = tomllib.loads((TUTORIALS / name / "crosscheck.toml").read_text()).get("pending")
    if pending:
        pytest.skip(f"{name}: {pending}")
    out = crosscheck(fsim, TUTORIALS / name, out=tmp_path)
    print(out.stdout)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "from crosscheck_reference.csv" in out.stdout and "not run here" in out.stdout
    assert (tmp_path / "crosscheck.csv").is_file()
    assert (tmp_path / "crosscheck.png").read_bytes()[:4] == b"\x89PNG"


def scratch_case(name, tmp_path):
    case = tmp_path / name
    shutil.copytree(TUTORIALS / name, case, ignore=shutil.ignore_patterns("*.png", "log.*"))
    return case


def test_a_wrong_drag_closure_fails_on_the_terminal_velocity(fsim, tmp_path):
    case = scratch_case("settlingInLiquid", tmp_path)
    cloud = case / "constant" / "kinematicCloudProperties"
    text = cloud.read_text()
    assert "sphereDrag;" in text
    cloud.write_text(text.replace("sphereDrag;", "PlessisMasliyahDrag;"))
    out = crosscheck(fsim, case, out=tmp_path / "out")
    assert out.returncode == 1, out.stdout + out.stderr
    assert "FAILED: terminal velocity" in out.stderr, out.stderr


def test_a_wrong_restitution_fails_on_the_pair_impacts_only(fsim, tmp_path):
    # the pair damping 10 % too large: e moves by 1.4 % (impacts/README.md), the walls not
    entry = ("constant/kinematicCloudProperties:subModels/pairCollisionCoeffs/"
             "pairSpringSliderDashpotCoeffs/alpha")
    out = crosscheck(fsim, TUTORIALS / "impacts", f"--set={entry}=0.11", out=tmp_path)
    assert out.returncode == 1, out.stdout + out.stderr
    failed = [line for line in out.stderr.splitlines() if line.startswith("FAILED:")]
    assert "FAILED: pair head-on: restitution" in failed, out.stderr
    assert not [line for line in failed if "wall" in line], out.stderr


def test_a_case_without_its_toml_or_with_a_bad_series_is_refused(fsim, tmp_path):
    case = scratch_case("settlingInLiquid", tmp_path)
    toml = case / "crosscheck.toml"
    toml.write_text(toml.read_text().replace('"particles.U.z.mean"', '"particles.V.z.mean"', 1))
    out = crosscheck(fsim, case, out=tmp_path / "out")
    assert out.returncode == 2 and "series 'particles.V.z.mean'" in out.stderr, out.stderr
    toml.unlink()
    out = crosscheck(fsim, case, out=tmp_path / "out")
    assert out.returncode == 2 and "crosscheck.toml: no such file" in out.stderr, out.stderr
