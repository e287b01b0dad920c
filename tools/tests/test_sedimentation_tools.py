"""The case writer's periodic packing and the Richardson-Zaki fit of the sedimentation sweep."""
import math

import numpy as np

import direct_cases
import sedimentation_sweep


def test_periodic_packing_has_no_overlap_across_periodic_faces():
    length = [1.0, 2.0, 1.0]
    d, gap = 0.1, 0.02
    centres = np.array(direct_cases.periodic_packing(length, d, 300, seed=5, min_gap=gap))
    assert centres.shape == (300, 3)
    assert np.all(centres >= 0) and np.all(centres < np.array(length))
    diff = centres[:, None, :] - centres[None, :, :]
    diff -= np.array(length) * np.round(diff / np.array(length))
    dist = np.sqrt((diff ** 2).sum(-1)) + np.eye(len(centres)) * 10
    assert dist.min() >= d + gap - 1e-12


def test_sangani_acrivos_matches_hasimoto_when_dilute():
    # Hasimoto (1959): 1/K = 1 - 1.7601 phi^(1/3) + O(phi)
    phi = 1e-6
    assert abs(direct_cases.sangani_acrivos_inverse_k(phi) - (1 - 1.7601 * phi ** (1 / 3))) < 2e-6


def test_richardson_zaki_fit_recovers_exponent_and_uncertainty():
    rng = np.random.default_rng(3)
    v0, n = 2e-3, 4.8
    rows = []
    for phi in [0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3]:
        vm = v0 * (1 - phi) ** n * (1 + 0.01 * rng.standard_normal())
        rows.append(dict(phi=phi, v_m=vm, v_m_error=0.01 * vm, stokes=v0))
    fit_n, sigma, fit_v0 = sedimentation_sweep.fit(rows)
    assert abs(fit_n - n) < 3 * sigma and 0.05 < sigma < 0.5
    assert abs(fit_v0 / v0 - 1) < 0.03
    n1, s1 = sedimentation_sweep.fit_fixed_v0(rows)
    assert abs(n1 - n) < 3 * s1 + 0.05
    assert math.isfinite(s1)
