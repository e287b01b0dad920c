"""The tutorials as a user runs them: fsimFoam on a copy of each, then every file it wrote read
by meshio, pyvista and ParaView (tools/vtk_checks.py), and values compared with the exact
solutions where one exists.

Tolerances come from the discretisation, not from a previous run:
- Taylor-Green (h = 2 pi / 32): the second-order MAC Laplacian makes the vortex decay at
  nu k_h^2 with k_h^2 = k^2 (1 - k^2 h^2 / 12), an amplitude error of 2 nu t k^2 h^2 / 12
  (0.32 % at t = 5); the fourth-order cell/face transfers add 3 (kh)^4 / 128 each (4e-5);
  1 % relative L2 bounds their sum with margin.
- Particle settling: the beads fall about 12 mm on average, reaching sqrt(2 g 0.012) = 0.49
  m/s; at rest means every bead below 1 % of that (4.9 mm/s; a last rattler may still
  wobble) and the rms speed below 0.02 % of it (1e-4 m/s). The linear springs give a static overlap of about
  m g N_layers / k_n = 0.1 % of d for the ~15 layers, so overlaps stay under the issue's 1 %.
- Channel: the steady plane Poiseuille profile is a parabola, which the MAC discretisation
  represents exactly; 0.5 % of the centre-line velocity (the issue's bound).
"""

import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import vtk_checks

ROOT = Path(__file__).resolve().parents[2]
TUTORIALS = ["cavity", "channel", "taylorGreen", "particleSettling"]


def copy_case(name: str, dest: Path) -> Path:
    """A clean copy of a tutorial: its input files only."""
    src = ROOT / "tutorials" / name
    case = dest / name
    for sub in ["system", "constant", "0"]:
        shutil.copytree(src / sub, case / sub, ignore=shutil.ignore_patterns(
            "fluid.vt?", "restart.bin", "particles.vtu"))
    return case


@pytest.fixture(scope="session")
def runs(fsim, tmp_path_factory):
    done = {}
    base = tmp_path_factory.mktemp("tutorials")
    for name in TUTORIALS:
        case = copy_case(name, base)
        run = subprocess.run([str(fsim), "-case", str(case)], capture_output=True, text=True)
        assert run.returncode == 0, f"{name}: exit {run.returncode}\n{run.stderr[-3000:]}"
        assert run.stdout.rstrip().endswith("End"), f"{name}: log does not end with End"
        done[name] = case
    return done


@pytest.mark.parametrize("name", TUTORIALS)
def test_every_file_opens_in_meshio_pyvista_and_paraview(runs, name):
    result = vtk_checks.check_case(runs[name], log=lambda *_: None)
    assert len(result["times"]) >= 2
    assert set(result["fluid"]) == {n for n, _ in vtk_checks.time_directories(runs[name])}


def test_taylor_green_decays_as_the_exact_solution(runs):
    case = runs["taylorGreen"]
    nu = 0.1
    names = vtk_checks.time_directories(case)
    assert [t for _, t in names] == [0, 1, 2, 3, 4, 5]
    for name, t in names[1:]:
        fluid = vtk_checks.read_fluid(case, name)
        x, y = fluid["centres"][:, 0], fluid["centres"][:, 1]
        decay = math.exp(-2.0 * nu * t)
        exact = np.stack([np.sin(x) * np.cos(y), -np.cos(x) * np.sin(y), 0 * x], axis=1) * decay
        error = np.linalg.norm(fluid["U"] - exact) / np.linalg.norm(exact)
        assert error < 0.01, f"t = {t}: relative L2 error {error:.4f}"


def test_channel_reaches_the_poiseuille_profile(runs):
    case = runs["channel"]
    name, _ = vtk_checks.time_directories(case)[-1]
    fluid = vtk_checks.read_fluid(case, name)
    height, ubar = 0.01, 0.001
    y = fluid["centres"][:, 1] / height
    exact = 6.0 * ubar * y * (1.0 - y)
    error = np.abs(fluid["U"][:, 0] - exact).max() / (1.5 * ubar)
    assert error < 0.005, f"max profile error {error:.2e} of the centre-line velocity"
    assert np.abs(fluid["U"][:, 1:]).max() < 1e-9 * ubar


def test_cavity_log_and_monitor_follow_openfoam_conventions(runs):
    case = runs["cavity"]
    columns, rows = vtk_checks.read_monitor(case / "postProcessing" / "fluid" / "0" / "fluid.dat")
    assert columns[:2] == ["Time", "deltaT"]
    assert rows.shape[0] == 4000
    assert rows[-1, 0] == pytest.approx(20.0, abs=1e-9)
    assert np.all(rows[:, columns.index("divergence")] < 1e-10)


def test_particle_settling_ends_at_rest_inside_the_box(runs):
    case = runs["particleSettling"]
    names = vtk_checks.time_directories(case)
    assert [t for _, t in names] == pytest.approx([0, 0.1, 0.2, 0.3, 0.4])
    first = vtk_checks.read_particles(case, names[0][0])
    last = vtk_checks.read_particles(case, names[-1][0])
    n = len(first["positions"])
    assert n > 1500 and len(last["positions"]) == n
    assert sorted(last["id"].tolist()) == list(range(n))
    x, d = last["positions"], last["d"]
    lo, hi = np.zeros(3), np.array([0.024, 0.024, 0.048])
    # every sphere inside the box, walls overlapped by less than 1 % of d
    assert np.all(x - 0.5 * d[:, None] > lo - 0.01 * d[:, None])
    assert np.all(x + 0.5 * d[:, None] < hi + 0.01 * d[:, None])
    speed = np.linalg.norm(last["U"], axis=1)
    assert speed.max() < 4.9e-3, f"max particle speed {speed.max():.3e} m/s: not at rest"
    assert np.sqrt(np.mean(speed**2)) < 1e-4, "rms particle speed: not at rest"
    # the bed has settled: the mean height dropped, the packing is denser than the initial 0.3
    assert x[:, 2].mean() < first["positions"][:, 2].mean() - 0.005
    columns, rows = vtk_checks.read_monitor(case / "postProcessing" / "cloud" / "0" / "cloud.dat")
    assert columns == ["Time", "particles", "kineticEnergy", "rotationalEnergy", "Ux", "Uy", "Uz",
                       "maxOverlapOverD", "subSteps"]
    assert rows.shape[0] == 400 and np.all(rows[:, 1] == n)
    assert rows[-1, columns.index("maxOverlapOverD")] < 0.01
    # pair overlaps from the positions (all pairs: 3 million distances), as the monitor says
    gap = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2) - 0.5 * (d[:, None] + d[None, :])
    np.fill_diagonal(gap, np.inf)
    worst = (-gap / np.minimum(d[:, None], d[None, :])).max()
    assert 0 < worst < 0.01, f"max pair overlap {worst:.3e} d"
    assert worst <= rows[-1, columns.index("maxOverlapOverD")] * (1 + 1e-9)
