"""The tutorials explain themselves, as OpenFOAM's and Lethe's do (issue 37): each has a README
with the same sections, an executable Allrun that sources ../RunFunctions and runs the case and
its post-processing, and an Allclean that removes what the run wrote. One cheap tutorial
(taylorGreen, under a second) runs its Allrun and Allclean end to end on a copy.

The solver is the release fsimFoam the suite builds (the `fsim` fixture of conftest.py), or
the one $FSIM names.
"""
import hashlib
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TUTORIALS_DIR = ROOT / "tutorials"
TUTORIALS = sorted(p.name for p in TUTORIALS_DIR.iterdir()
                   if (p / "system" / "controlDict").is_file())
SECTIONS = ["What it shows", "Knobs", "Expected result", "Run"]
CHEAP = "taylorGreen"


def test_the_tutorials_are_the_documented_ones():
    assert TUTORIALS == sorted([
        "benchmark", "benchmarkDragLaw", "cavity", "channel", "fluidizedBed", "impacts",
        "impactsDamped", "packedBed", "particleSettling", "porousMedia", "sedimentation",
        "settlingColumn", "settlingInLiquid", "settlingSphere", "taylorGreen",
        # issue 42's DPMFoam cross-checks (pending in their crosscheck.toml)
        "settlingAddedMass", "liquidFluidizedBed", "shearLift", "shearLiftTomiyama",
        "nonSphereSettling"])


@pytest.mark.parametrize("name", TUTORIALS)
def test_readme_has_the_sections_in_order_and_stays_short(name):
    text = (TUTORIALS_DIR / name / "README.md").read_text()
    headings = re.findall(r"^## (.+?)\s*$", text, re.M)
    assert headings == SECTIONS, f"{name}/README.md sections {headings}"
    assert text.startswith(f"# {name}"), f"{name}/README.md: title should start with '# {name}'"
    lines = len(text.splitlines())
    assert 40 <= lines <= 90, f"{name}/README.md has {lines} lines (40-90)"
    run = text.split("## Run", 1)[1]
    for word in ["./Allrun", "./Allclean", "about"]:
        assert word in run, f"{name}/README.md, Run: no '{word}'"
    assert re.search(r"\|\s*file\s*\|\s*entry\s*\|", text), f"{name}/README.md: no knob table"


@pytest.mark.parametrize("name", TUTORIALS)
@pytest.mark.parametrize("script", ["Allrun", "Allclean"])
def test_scripts_are_executable_bash_that_source_run_functions(name, script):
    path = TUTORIALS_DIR / name / script
    assert path.is_file(), f"{name}/{script} missing"
    assert os.access(path, os.X_OK), f"{name}/{script} is not executable"
    text = path.read_text()
    assert text.startswith("#!/bin/bash\n"), f"{name}/{script}: not a bash script"
    assert re.search(r"^\s*(\.|source)\s+\.\./RunFunctions\b", text, re.M), \
        f"{name}/{script} does not source ../RunFunctions"
    assert re.search(r'^cd "\$\(dirname "\$0"\)"', text, re.M), \
        f"{name}/{script} does not run from its own folder"
    assert ("runFsim" if script == "Allrun" else "cleanFsimCase") in text
    subprocess.run(["bash", "-n", str(path)], check=True)


@pytest.mark.parametrize("name", TUTORIALS)
def test_allrun_draws_a_picture_with_a_script_of_the_folder(name):
    allrun = (TUTORIALS_DIR / name / "Allrun").read_text()
    scripts = re.findall(r"^\s*runPython\s+(\S+)", allrun, re.M)
    assert scripts, f"{name}/Allrun has no post-processing"
    for script in scripts:
        assert (TUTORIALS_DIR / name / script).is_file(), f"{name}/{script} missing"
    readme = (TUTORIALS_DIR / name / "README.md").read_text()
    assert f"{name}.png" in readme, f"{name}/README.md does not name {name}.png"


def test_run_functions_parse_and_the_index_links_every_tutorial():
    subprocess.run(["bash", "-n", str(TUTORIALS_DIR / "RunFunctions")], check=True)
    index = (TUTORIALS_DIR / "README.md").read_text()
    for name in TUTORIALS:
        assert f"({name}/README.md)" in index, f"tutorials/README.md does not link {name}"


@pytest.mark.parametrize("readme", ["README.md"] + [f"{n}/README.md" for n in TUTORIALS])
def test_relative_links_resolve(readme):
    path = TUTORIALS_DIR / readme
    for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", path.read_text()):
        if re.match(r"[a-z]+:", target):
            continue
        assert (path.parent / target).exists(), f"tutorials/{readme}: broken link {target}"


@pytest.fixture(scope="module")
def solver(request):
    """$FSIM when set (a given binary), else the release build of the suite."""
    given = os.environ.get("FSIM")
    return Path(given) if given else request.getfixturevalue("fsim")


def snapshot(folder: Path) -> dict:
    """Every file under `folder` with its content's hash, and every directory."""
    state = {}
    for path in sorted(folder.rglob("*")):
        key = str(path.relative_to(folder))
        state[key] = hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else "dir"
    return state


def copy_tutorial(name: str, dest: Path) -> Path:
    """The tutorial folder as the repository holds it, beside copies of RunFunctions and of
    plotting.py (what every plot.py imports)."""
    tutorials = dest / "tutorials"
    tutorials.mkdir()
    for shared in ["RunFunctions", "plotting.py"]:
        shutil.copy2(TUTORIALS_DIR / shared, tutorials / shared)
    keep = {"Allrun", "Allclean", "README.md", "plot.py", "system", "constant", "0"}
    shutil.copytree(TUTORIALS_DIR / name, tutorials / name,
                    ignore=lambda folder, names: [] if Path(folder) != TUTORIALS_DIR / name
                    else [n for n in names if n not in keep])
    case = tutorials / name
    # leftovers of a run in the repository's 0/ are not case files
    for leftover in ["fluid.vtk", "fluid.vti", "restart.bin", "particles.vtu"]:
        (case / "0" / leftover).unlink(missing_ok=True)
    return case


def run(script: Path, env: dict) -> subprocess.CompletedProcess:
    return subprocess.run([str(script)], capture_output=True, text=True, timeout=120,
                          env={**os.environ, **env}, cwd="/")


def test_allrun_then_allclean_on_the_cheap_tutorial(solver, tmp_path):
    case = copy_tutorial(CHEAP, tmp_path)
    before = snapshot(case)
    env = {"FSIM": str(solver), "FSIM_PYTHON": sys.executable}
    out = run(case / "Allrun", env)
    assert out.returncode == 0, out.stdout + out.stderr
    log = (case / "log.fsimFoam").read_text()
    assert log.rstrip().endswith("End"), log[-2000:]
    png = case / f"{CHEAP}.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", "no PNG drawn"
    assert png.stat().st_size > 20_000, "the PNG is nearly empty"
    plot_log = (case / "log.plot").read_text()
    assert "(bound 1 %): within" in plot_log, plot_log
    assert (case / "5" / "fluid.vtk").is_file() and (case / f"{CHEAP}.pvd").is_file()
    # a second Allrun does not run the case again (OpenFOAM's runApplication rule)
    again = run(case / "Allrun", env)
    assert again.returncode == 0 and "already run" in again.stdout, again.stdout
    out = run(case / "Allclean", env)
    assert out.returncode == 0, out.stdout + out.stderr
    assert snapshot(case) == before, "Allclean left or removed files"


def test_allrun_without_python_skips_the_picture_with_a_note(solver, tmp_path):
    case = copy_tutorial(CHEAP, tmp_path)
    out = run(case / "Allrun", {"FSIM": str(solver), "FSIM_PYTHON": str(tmp_path / "none")})
    assert out.returncode == 0, out.stdout + out.stderr
    assert "skipped" in out.stdout, out.stdout
    assert (case / "log.fsimFoam").is_file() and not (case / f"{CHEAP}.png").exists()


def test_without_fsim_allrun_builds_the_solver_with_cargo(solver, tmp_path):
    """A fresh clone with only cargo: no $FSIM, no fsimFoam on PATH. A stand-in cargo, run at
    the repository's root (here the copy's), puts the suite's binary where a release build
    leaves it."""
    case = copy_tutorial(CHEAP, tmp_path)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    cargo = bin_dir / "cargo"
    cargo.write_text("#!/bin/bash\n"
                     f'[ "$*" = "build --release --quiet --bin fsimFoam" ] || exit 3\n'
                     "mkdir -p target/release\n"
                     f'ln -sf "{solver}" target/release/fsimFoam\n')
    cargo.chmod(0o755)
    env = {k: v for k, v in os.environ.items() if k not in ("FSIM", "CARGO_TARGET_DIR")}
    env.update(PATH=f"{bin_dir}:/usr/bin:/bin", FSIM_PYTHON=str(tmp_path / "none"))
    out = subprocess.run([str(case / "Allrun")], capture_output=True, text=True, timeout=120,
                         env=env, cwd="/")
    assert out.returncode == 0, out.stdout + out.stderr
    assert "Building fsimFoam" in out.stderr, out.stderr
    assert (tmp_path / "target/release/fsimFoam").exists()
    assert (case / "log.fsimFoam").read_text().rstrip().endswith("End")


def test_a_failing_run_fails_allrun_and_shows_the_log(tmp_path):
    case = copy_tutorial(CHEAP, tmp_path)
    fake = tmp_path / "fsimFoam"
    fake.write_text("#!/bin/bash\necho 'fsimFoam: error: a bad case' >&2\nexit 2\n")
    fake.chmod(0o755)
    out = run(case / "Allrun", {"FSIM": str(fake), "FSIM_PYTHON": sys.executable})
    assert out.returncode != 0
    assert "a bad case" in out.stderr and "exit 2" in out.stderr, out.stderr
    assert not (case / f"{CHEAP}.png").exists()
