"""The sedimentation reference of tools/study_references.py (Fig. 3 and its accuracy-against-
cost chart): the suspension's phi from the case, and v_m / U_Stokes measured from either
model's output."""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import foam_dict
import hindered_settling
import study_references as refs

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "tutorials" / "sedimentation"
CLOUD = "constant/kinematicCloudProperties"


def test_phi_of_the_positions_file_and_of_a_random_packing(tmp_path):
    # the tutorial: 48 spheres of 1.5 mm in 8 x 16 x 8 mm
    by_hand = 48 * math.pi / 6 * 1.5e-3 ** 3 / (8e-3 * 16e-3 * 8e-3)
    assert refs.suspension_fraction(TUTORIAL) == pytest.approx(by_hand, rel=1e-12)
    values = refs.REFERENCES["sedimentation"].values(TUTORIAL)
    assert values["hardSpheres"] == pytest.approx(hindered_settling.hard_spheres(by_hand))
    assert values["richardsonZaki"] == pytest.approx((1 - by_hand) ** 4.65)
    # randomPacking at 0.1 of the same box: round(0.1 V / V_p) = 58 spheres
    case = tmp_path / "case"
    shutil.copytree(TUTORIAL, case)
    file = case / CLOUD
    text = file.read_text()
    for key, value in (("type", "randomPacking"), ("volumeFraction", "0.1")):
        text = foam_dict.set_entry(text, f"subModels/injectionModels/spheres/{key}", value)
    file.write_text(text)
    particle = math.pi / 6 * 1.5e-3 ** 3
    volume = 8e-3 * 16e-3 * 8e-3
    assert round(0.1 * volume / particle) == 58
    assert refs.suspension_fraction(case) == pytest.approx(58 * particle / volume, rel=1e-12)


def test_settling_ratio_of_the_direct_monitor_is_its_second_half_mean(tmp_path):
    case = tmp_path / "case"
    shutil.copytree(TUTORIAL, case)
    out = case / "postProcessing" / "sedimentation" / "0"
    out.mkdir(parents=True)
    velocities = [0.0, 0.05, 0.01, 0.011, 0.012, 0.013]  # m/s, the first half left out
    out.joinpath("sedimentation.dat").write_text(
        "# Time phi settlingVelocity\n"
        + "".join(f"{0.01 * (i + 1)} 0.0828 {v}\n" for i, v in enumerate(velocities)))
    stokes = (2500 - 1000) * 9.81 * 1.5e-3 ** 2 / (18 * 1000 * 6e-5)
    assert refs.stokes_velocity(case) == pytest.approx(stokes, rel=1e-12)
    got = refs.sedimentation_measure(case)
    assert got["phi"] == 0.0828
    assert got["settlingRatio"] == pytest.approx(0.0115 / stokes, rel=1e-12)


def test_settling_ratio_of_the_drag_law_fields_is_relative_to_the_volume_flux(tmp_path):
    # v_m = (1 - phi) v_p - <eps u> along gravity (-y), whatever the frame: the same fields
    # seen from a frame moving at w along y give the same v_m
    pv = pytest.importorskip("pyvista")
    case = tmp_path / "case"
    shutil.copytree(TUTORIAL, case)
    rng = np.random.default_rng(2)
    eps = 0.9 + 0.05 * rng.random(8)
    u = rng.normal(size=(8, 3)) * 1e-3
    v = rng.normal(size=(5, 3)) * 1e-3 - [0, 0.01, 0]
    stokes = refs.stokes_velocity(case)

    def write(shift):
        for t in ("0", "0.1", "0.2"):
            folder = case / t
            folder.mkdir(exist_ok=True)
            fluid = pv.ImageData(dimensions=(3, 3, 3), spacing=(4e-3, 8e-3, 4e-3))
            fluid.cell_data["alpha"] = eps
            fluid.cell_data["U"] = u + [0, shift, 0]
            fluid.save(folder / "fluid.vti")
            cloud = pv.PolyData(rng.random((5, 3)) * 8e-3)
            cloud.point_data["U"] = v + [0, shift, 0]
            cloud.cast_to_unstructured_grid().save(folder / "particles.vtu")
        return refs.sedimentation_measure(case)

    phi = 1 - eps.mean()
    by_hand = ((1 - phi) * -v[:, 1].mean() + (eps * u[:, 1]).mean()) / stokes
    got = write(0.0)
    assert got["phi"] == pytest.approx(phi, rel=1e-12)
    assert got["settlingRatio"] == pytest.approx(by_hand, rel=1e-10)
    assert write(0.004)["settlingRatio"] == pytest.approx(by_hand, rel=1e-3)
