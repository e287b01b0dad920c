"""The Goldschmidt benchmark's own parts (tools/bench/goldschmidt.py), without the long runs:
DPMFoam's log parser, fsim's monitor reader, the window averages and their comparison, and the
case preparation. When DPMFoam is installed, a 3-step run checks the parser on a real log:
v1912's first step applies gravity twice, so the mean vertical velocity after it is
-2 g dt (1 - rho_f/rho_p) (gravity with buoyancy, rho_f 1.2, rho_p 2526); the only other force,
the drag of the inflow that cellPoint interpolation lets the bottom layer see through the
inlet's point values, changes it by under 1e-4 (measured 7e-5), so the bound is 2e-4.
"""
import os
import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
import goldschmidt  # noqa: E402

LOG = """\
Time = 2e-05

Cloud: kinematicCloud
    Current number of parcels       = 2
    Current mass in system          = 0.5
    Linear momentum                 = (1e-05 0 -0.0002)
   |Linear momentum|                = 0.0002
ExecutionTime = 1.5 s  ClockTime = 2 s

Time = 4e-05

Cloud: kinematicCloud
    Current mass in system          = 0.5
    Linear momentum                 = (0 0 -0.0004)
   |Linear momentum|                = 0.0004
ExecutionTime = 1.75 s  ClockTime = 2 s
"""


def test_dpmfoam_log_gives_momentum_over_mass_per_step():
    times, w, execution = goldschmidt.parse_dpmfoam_log(LOG)
    assert times == [2e-05, 4e-05]
    assert w == pytest.approx([-0.0004, -0.0008], rel=1e-15)
    assert execution == 1.75


def test_fsim_monitor_columns_by_name(tmp_path):
    path = tmp_path / "cloud.dat"
    path.write_text("# Time particles Uz\n1e-05 3 -0.5\n2e-05 3 -0.25\n\n")
    assert goldschmidt.read_monitor(path, "Uz") == ([1e-05, 2e-05], [-0.5, -0.25])


def test_window_averages_of_a_linear_history_are_the_window_midpoints():
    dt = 0.001
    times = [dt * (i + 1) for i in range(100)]
    values = [2.0 * t for t in times]
    means = goldschmidt.window_averages(times, values, 0.0, 0.1, 4)
    # samples t = 0.001..0.025 in the first window: mean 2 * 0.013
    assert means == pytest.approx([0.026, 0.076, 0.126, 0.176], rel=1e-12)
    rows = goldschmidt.compare((times, values), (times, [1.05 * v for v in values]), 0.0,
                               0.1, 4)
    assert [r[4] for r in rows] == pytest.approx([0.05] * 4, rel=1e-12)
    assert rows[1][:2] == pytest.approx((0.025, 0.05))
    later = goldschmidt.shifted((times, values), dt, 1)
    assert later[0][0] == pytest.approx(0.002) and later[1] == values


def test_prepared_case_runs_the_requested_steps_and_writes_once(tmp_path):
    if not os.path.isdir(goldschmidt.GOLDSCHMIDT):
        pytest.skip("openfoam-examples not installed")
    dt = goldschmidt.prepare_case(str(tmp_path / "case"), 1000)
    assert dt == 2e-05
    text = (tmp_path / "case" / "system" / "controlDict").read_text()
    assert "endTime 0.02;" in text and "writeInterval 0.02;" in text
    assert "deltaT          2e-5;" in text
    assert (tmp_path / "case" / "constant" / "kinematicCloudPositions.gz").exists()
    with pytest.raises(ValueError):
        goldschmidt.set_entry("a 1;", "endTime", "2")


def test_three_dpmfoam_steps_give_the_doubled_first_gravity_step(tmp_path):
    if not os.path.isdir(goldschmidt.GOLDSCHMIDT) or shutil.which("DPMFoam") is None:
        pytest.skip("DPMFoam or its tutorials not installed")
    r = goldschmidt.run_dpmfoam(3, str(tmp_path), nice=0)
    assert r["version"] == "v1912"
    assert r["times"] == pytest.approx([2e-05, 4e-05, 6e-05])
    assert r["w"][0] == pytest.approx(-2 * 9.81 * 2e-05 * (1 - 1.2 / 2526), rel=2e-4)
    assert r["w"][0] != pytest.approx(-9.81 * 2e-05 * (1 - 1.2 / 2526), rel=0.1)
    assert all(w < 0 for w in r["w"])
    assert r["peak"] > 0 and r["cpu"] > 0


def test_history_difference_is_relative_to_the_largest_reference_mean():
    # A history offset by 0.001 m/s everywhere: 50 % in a first window near rest, 1 % of the
    # history's scale of 0.1 m/s.
    rows = [(0.0, 1.0, -0.002, -0.003, 0.5), (1.0, 2.0, -0.1, -0.101, 0.01)]
    assert abs(goldschmidt.history_difference(rows) - 0.01) < 1e-12
