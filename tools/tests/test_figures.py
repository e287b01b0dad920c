"""The paper's figures (tools/figures/, docs/figures/README.md): the exact porous reference
the study compares with, the steady K it measures, the fitted order and the Pareto front."""
import importlib.util
import math
import sys
from pathlib import Path

import pytest

import study_references as refs

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "figures"))  # the scripts' shared module, figure.py


def load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "tools" / "figures" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_exact_k_is_zick_and_homsy_at_their_phi_and_sangani_acrivos_between():
    # Zick & Homsy (1982) Table 2, as printed
    assert refs.exact_simple_cubic(0.064) == 2.810
    assert refs.exact_simple_cubic(0.216) == 7.442
    assert refs.exact_simple_cubic(0.45) == 28.1
    # eq. 17 below 0.125 (0.8 % low at 0.216, where the table is used instead)
    assert refs.exact_simple_cubic(0.1) == refs.sangani_acrivos(0.1)
    assert refs.sangani_acrivos(0.216) == pytest.approx(7.3827, abs=1e-4)
    # between 0.216 and 0.343: linear in ln K
    mid = refs.exact_simple_cubic(0.5 * (0.216 + 0.343))
    assert mid == pytest.approx(math.sqrt(7.442 * 15.4), rel=1e-12)
    assert math.isnan(refs.exact_simple_cubic(0.6))
    # eq. 18 as docs/numerics.md reads it: 1.6408 and 7.2886 at phi = 0.1 and 0.3
    assert refs.ergun_eq18(0.1) == pytest.approx(0.9 ** -4.7)
    assert refs.ergun_eq18(0.1) == pytest.approx(1.6408, abs=1e-4)
    assert refs.ergun_eq18(0.3) == pytest.approx(7.2886, abs=1e-4)


def test_the_porous_reference_of_a_point_and_its_steady_k(tmp_path):
    case = tmp_path / "case"
    (case / "constant").mkdir(parents=True)
    (case / "constant" / "porousParameters").write_text("phi 0.064;\nn 16;\nL 0.0028;\n")
    values = refs.REFERENCES["porousMedia"].values(case)
    assert values == {"K": 2.810, "K_SA": refs.sangani_acrivos(0.064)}
    # K settles, then the last steps, shortened onto endTime, move it: the median of the last
    # fifth is the steady value, not the final one
    out = case / "postProcessing" / "direct" / "0"
    out.mkdir(parents=True)
    times = [0.001 * i for i in range(1, 101)]
    ks = [3.0 + math.exp(-t / 0.005) for t in times[:-2]] + [3.2, 3.3]
    out.joinpath("direct.dat").write_text(
        "# Time Fx K\n" + "".join(f"{t} 0 {k}\n" for t, k in zip(times, ks)))
    steady = refs.REFERENCES["porousMedia"].measure(case)["K"]
    assert steady == pytest.approx(3.0, abs=1e-6)
    assert refs.REFERENCES["porousMedia"].compare["measured.K"] == "K"


def test_the_fitted_order_and_the_pareto_front():
    fig1 = load("fig1_convergence")
    rows = [{"r_over_h": rh, "error": 0.3 * rh ** -2.5, "wall_time": rh ** 5}
            for rh in (2, 4, 8, 16)]
    order, prefactor = fig1.fit_order(rows)
    assert order == pytest.approx(2.5, abs=1e-12)
    assert prefactor == pytest.approx(0.3, rel=1e-12)
    # a slower run that is no better is off the front
    rows.append({"r_over_h": 5, "error": 0.3 * 4 ** -2.5, "wall_time": 1e5})
    front = fig1.pareto(rows)
    assert [r["r_over_h"] for r in front] == [2, 4, 8, 16]


def test_the_packed_bed_reference_is_ergun_and_its_measure_the_second_half(tmp_path):
    # the tutorial's own dictionaries: 160 beads, d = 1 mm, a 4 x 4 x 10 mm bed, U = 1 mm/s;
    # Ergun by hand, 3.888 Pa as tutorials/packedBed/README.md prints it
    values = refs.REFERENCES["packedBed"].values(ROOT / "tutorials" / "packedBed")
    phi = math.pi / 6
    eps = 1 - phi
    by_hand = 0.01 * (150 * 1e-3 * 1e-3 * phi ** 2 / (eps ** 3 * 1e-6)
                      + 1.75 * 1000 * phi * 1e-6 / (eps ** 3 * 1e-3))
    assert values["phi"] == pytest.approx(phi, rel=1e-12)
    assert values["pressureDrop"] == pytest.approx(by_hand, rel=1e-12)
    assert values["pressureDrop"] == pytest.approx(3.888, abs=5e-4)
    # the monitor's mean over the second half of the rows, the swings of the start left out
    out = tmp_path / "postProcessing" / "dragLaw" / "0"
    out.mkdir(parents=True)
    drops = [100.0, 50.0, 10.0, 3.0, 4.0, 3.5, 3.5, 4.0]
    out.joinpath("dragLaw.dat").write_text(
        "# Time alphaMin pressureDrop\n"
        + "".join(f"{0.001 * (i + 1)} 0.47 {p}\n" for i, p in enumerate(drops)))
    assert refs.REFERENCES["packedBed"].measure(tmp_path)["pressureDrop"] == 3.75
    assert refs.REFERENCES["packedBed"].compare == {"measured.pressureDrop": "pressureDrop"}


def test_the_cost_charts_cheapest_run_and_block_cells():
    import figure
    rows = [{"wall_time": 1.0, "error": 0.005}, {"wall_time": 0.5, "error": 0.02},
            {"wall_time": 0.7, "error": 0.04}, {"wall_time": 0.2, "error": 0.09}]
    assert figure.cheapest(rows, 0.01) is rows[0]
    assert figure.cheapest(rows, 0.03) is rows[1]
    assert figure.cheapest(rows, 0.10) is rows[3]
    assert figure.cheapest(rows, 0.001) is None
    assert figure.pareto(rows) == [rows[3], rows[1], rows[0]]
    assert figure.block_cells("( hex (0 1 2 3 4 5 6 7) (4 4 20) simpleGrading (1 1 1) )") \
        == (4, 4, 20)


def test_the_fluidized_bed_reference_is_the_buoyant_weight_per_area(tmp_path):
    # the tutorial's own dictionaries: 1,080 beads, d = 2.5 mm, rho_p = 2526 kg/m^3, air of
    # 1.2 kg/m^3, g = 9.81 m/s^2, a 10 x 50 mm cross-section; by hand 437.7 Pa as
    # tutorials/fluidizedBed/README.md prints it
    values = refs.REFERENCES["fluidizedBed"].values(ROOT / "tutorials" / "fluidizedBed")
    weight = 1080 * (2526 - 1.2) * 9.81 * math.pi / 6 * 2.5e-3 ** 3
    assert values["beads"] == 1080
    assert values["buoyantWeight"] == pytest.approx(weight, rel=1e-12)
    assert values["pressureDrop"] == pytest.approx(weight / (10e-3 * 50e-3), rel=1e-12)
    assert values["pressureDrop"] == pytest.approx(437.7, abs=0.05)
    # the monitor's mean over the second half of the run in time (t > endTime / 2), the
    # drag on the beads against gravity per cross-section beside it
    out = tmp_path / "postProcessing" / "dragLaw" / "0"
    out.mkdir(parents=True)
    for name in ("constant", "system"):
        (tmp_path / name).mkdir()
    for file in ("constant/g", "system/blockMeshDict"):
        (tmp_path / file).write_text(
            (ROOT / "tutorials" / "fluidizedBed" / file).read_text())
    drops = [900.0, 100.0, 600.0, 300.0, 400.0, 500.0, 350.0, 450.0]
    out.joinpath("dragLaw.dat").write_text(
        "# Time alphaMin pressureDrop FdParticlesX FdParticlesY FdParticlesZ\n"
        + "".join(f"{0.025 * (i + 1)} 0.47 {p} 0 0 {p * 5e-4 * 1.01}\n"
                  for i, p in enumerate(drops)))
    measured = refs.REFERENCES["fluidizedBed"].measure(tmp_path)
    assert measured["pressureDrop"] == 425.0
    assert measured["dragPerArea"] == pytest.approx(1.01 * 425.0, rel=1e-12)
    assert refs.REFERENCES["fluidizedBed"].compare == {"measured.pressureDrop": "pressureDrop"}


def test_the_sedimentation_grid_limit_recovers_a_known_limit_and_order():
    # v = v_inf + C (h/r)^p on the cost chart's grids: the fit returns v_inf, p and C
    cost = load("cost_sedimentation")
    rows = [dict(r_over_h=x, ratio=0.455 - 0.3 * (1 / x) ** 3.5) for x in (3, 3.6, 4.2, 4.8, 6)]
    v_inf, p, c = cost.grid_limit(rows)
    assert v_inf == pytest.approx(0.455, abs=1e-6)
    assert p == pytest.approx(3.5, abs=0.011)
    assert c == pytest.approx(-0.3, rel=0.02)


def test_the_stability_maps_classification_of_a_run():
    # refused: exit 2, the case turned down at start (a deltaT past the scheme's bound);
    # unstable: failed while running (exit 1, a signal) or ended with no finite error;
    # inaccurate / stable: |error| against the threshold (grid error + 1 %)
    classify = load("stability_direct").classify
    assert classify("failed", 2, None, 0.03) == "refused"
    assert classify("failed", 1, None, 0.03) == "unstable"
    assert classify("failed", -9, None, 0.03) == "unstable"
    assert classify("done", 0, float("nan"), 0.03) == "unstable"
    assert classify("done", 0, None, 0.03) == "unstable"
    assert classify("done", 0, -0.031, 0.03) == "inaccurate"
    assert classify("done", 0, 0.05, 0.03) == "inaccurate"
    assert classify("done", 0, -0.029, 0.03) == "stable"
    assert classify("done", 0, 0.0, 0.03) == "stable"
    assert classify("", None, None, 0.03) is None


def test_the_drag_law_stability_maps_table_values_and_worst_error():
    # results.csv holds sedimentation_measure's values as numpy's repr ('np.float64(x)'),
    # which the table reader leaves as text; the map reads them as numbers
    module = load("stability_draglaw")
    assert module.number("np.float64(0.7817411488455231)") == 0.7817411488455231
    assert module.number(0.5) == 0.5
    assert math.isnan(module.number("np.float64(nan)"))
    assert module.number("") is None and module.number(None) is None
    assert module.relative_error("np.float64(0.75)", 0.5) == pytest.approx(0.5)
    assert module.relative_error(float("nan"), 0.5) is None
    # the worst of the restitutions' errors, signed; NaN when any is not finite
    assert module.worst([0.01, -0.03, 0.02]) == -0.03
    assert math.isnan(module.worst([0.01, float("inf")]))
