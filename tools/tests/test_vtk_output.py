"""fsim's output read by meshio, pyvista and ParaView, against analytic values.

The sample run (examples/write_sample_output.rs) writes fields known in closed form; these
tests build and run it into a temporary case, then read every file back. Tolerance for values
recomputed here: 1e-12 absolute (the Rust writer and numpy evaluate the same formulas in f64;
cell centres differ by a few ulps between `origin + (i + ½) h` and the mean of 8 corners).
Values compared between readers are compared exactly.

test_tutorials.py runs the same checks on the tutorials as fsimFoam writes them.
"""

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import vtk_checks

REPO = Path(__file__).resolve().parents[2]
TIMES = [0.0, 1e-5, 0.1, 0.25, 1.0]
NAMES = ["0", "1e-05", "0.1", "0.25", "1"]
N = np.array([16, 12, 8])
H = np.array([0.0625, 0.05, 0.1])
ORIGIN = np.array([-0.5, 0.2, 1.0])
TOLERANCE = 1e-12


@pytest.fixture(scope="module")
def sample_case(tmp_path_factory):
    case = tmp_path_factory.mktemp("runs") / "sampleCase"
    subprocess.run(
        ["cargo", "run", "--quiet", "--release", "--example", "write_sample_output", "--", str(case)],
        cwd=REPO, check=True, stdout=subprocess.DEVNULL,
    )
    return case


def analytic_fluid(centres, t):
    """The sample's fields (see examples/write_sample_output.rs)."""
    x, y, z = centres.T
    length = N * H
    u = np.stack([
        np.sin(2 * np.pi * (x - ORIGIN[0]) / length[0]) * (1 + t),
        np.cos(2 * np.pi * (y - ORIGIN[1]) / length[1]),
        z * t,
    ], axis=1)
    return u, x * y + t


def expected_centres():
    k, j, i = np.meshgrid(*(np.arange(n) for n in N[::-1]), indexing="ij")
    index = np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1)  # x fastest
    return ORIGIN + (index + 0.5) * H


def test_collection_lists_every_time_in_order(sample_case):
    assert vtk_checks.check_collection(sample_case) == TIMES
    entries = vtk_checks.read_collection(sample_case)
    assert [e["file"] for e in entries] == [
        f"{name}/{file}" for name in NAMES for file in ("fluid.vti", "particles.vtu")
    ]
    assert [e["part"] for e in entries] == [0, 1] * len(NAMES)
    assert not [p for p in sample_case.iterdir() if p.name.startswith(".")], "hidden leftovers"


def test_fluid_values_match_the_analytic_fields(sample_case):
    fluid = vtk_checks.check_fluid(sample_case)
    assert list(fluid) == NAMES
    for name, t in zip(NAMES, TIMES):
        f = fluid[name]
        assert np.abs(f["centres"] - expected_centres()).max() < TOLERANCE
        u, p = analytic_fluid(f["centres"], t)
        assert f["U"].shape == (N.prod(), 3) and f["p"].shape == (N.prod(),)
        assert np.abs(f["U"] - u).max() < TOLERANCE, name
        assert np.abs(f["p"] - p).max() < TOLERANCE, name


def test_pyvista_time_series_reads_the_right_time(sample_case):
    import pyvista

    reader = pyvista.get_reader(str(vtk_checks.collection_path(sample_case)))
    reader.set_active_time_value(0.25)
    blocks = reader.read()
    fluid = next(b for b in blocks if isinstance(b, pyvista.ImageData))
    _, p = analytic_fluid(np.asarray(fluid.cell_centers().points), 0.25)
    assert np.abs(np.asarray(fluid.cell_data["p"]) - p).max() < TOLERANCE


def test_particles_match_the_analytic_values(sample_case):
    particles = vtk_checks.check_particles(sample_case)
    assert list(particles) == NAMES
    for name, t in zip(NAMES, TIMES):
        p = particles[name]
        count = 0 if name == "1e-05" else 5
        i = np.arange(count, dtype=float)
        assert set(p) == {"positions", "id", "d", "U", "omega", "F_hydro", "F_contact"}
        assert p["id"].dtype.kind == "i"
        expected = {
            "positions": np.stack([-0.4 + 0.15 * i, 0.5 + 0 * i, 1.25 + t + 0 * i], axis=1),
            "id": 100 + i,
            "d": 1e-3 * (1 + i),
            "U": np.stack([i, t + 0 * i, -1 + 0 * i], axis=1),
            "omega": np.stack([0 * i, 0 * i, i * t], axis=1),
            "F_hydro": np.stack([1e-6 * i, 0 * i, 0 * i], axis=1),
            "F_contact": np.stack([0 * i, -1e-7 + 0 * i, t + 0 * i], axis=1),
        }
        for key, values in expected.items():
            got = p[key].reshape(values.shape)
            assert got.shape == values.shape, (name, key)
            assert np.abs(got - values).max(initial=0) < TOLERANCE, (name, key)


def test_restart_state_holds_the_exact_pressure(sample_case):
    restart = vtk_checks.check_restart(sample_case)
    fluid = vtk_checks.check_fluid(sample_case)
    for step, (name, t) in enumerate(zip(NAMES, TIMES)):
        header, arrays = restart[name]
        assert header["time"] == t and header["step"] == step and header["delta_t"] == 1e-5
        assert np.array_equal(arrays["p"], fluid[name]["p"])


def test_monitor_has_header_and_one_row_per_write(sample_case):
    columns, rows = vtk_checks.read_monitor(sample_case / "postProcessing/sample/0/sample.dat")
    assert columns == ["Time", "meanP"]
    assert rows[:, 0].tolist() == TIMES
    centres = expected_centres()
    mean_xy = np.mean(centres[:, 0] * centres[:, 1])
    # Written with 12 significant digits.
    assert np.allclose(rows[:, 1], mean_xy + np.array(TIMES), rtol=1e-11, atol=1e-12)


@pytest.mark.skipif(vtk_checks.pvpython() is None, reason="ParaView (pvpython) not installed")
def test_paraview_opens_the_collection(sample_case):
    fluid = vtk_checks.check_fluid(sample_case)
    seen = vtk_checks.check_paraview(sample_case, fluid)
    assert seen["times"] == TIMES
    first = seen["steps"][0]["blocks"]
    assert [b["class"] for b in first] == ["vtkImageData", "vtkUnstructuredGrid"]
    assert first[1]["points"] == 5 and seen["steps"][1]["blocks"][1]["points"] == 0


def test_checks_fail_on_damaged_output(sample_case, tmp_path):
    """The checks can fail: a changed value, a missing time and a flipped restart byte."""
    case = tmp_path / "damaged"
    shutil.copytree(sample_case, case)
    (case / f"{sample_case.name}.pvd").rename(case / "damaged.pvd")

    vti = case / "0.1" / "fluid.vti"
    raw = bytearray(vti.read_bytes())
    raw[-100] ^= 0x01
    vti.write_bytes(bytes(raw))
    with pytest.raises(AssertionError, match="differs between pyvista and meshio"):
        vtk_checks.read_fluid(case, "0.1")

    pvd = case / "damaged.pvd"
    text = pvd.read_text()
    pvd.write_text("\n".join(l for l in text.splitlines() if "0.25/fluid.vti" not in l))
    with pytest.raises(AssertionError, match="time directories hold"):
        vtk_checks.check_collection(case)

    restart = case / "1" / "restart.bin"
    raw = bytearray(restart.read_bytes())
    raw[40] ^= 0x01
    restart.write_bytes(bytes(raw))
    with pytest.raises(AssertionError, match="checksum"):
        vtk_checks.read_restart(restart)
