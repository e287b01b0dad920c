"""The periodic Rotne-Prager-Yamakawa reference of tools/periodic_rpy.py."""
import math

import numpy as np

import direct_cases
import periodic_rpy


def test_single_sphere_follows_hasimoto():
    # Hasimoto (1959) / Sangani & Acrivos (1982): 1/K = 1 - 1.7601 phi^(1/3) + phi - 1.5593 phi^2
    # for a simple cubic array; RPY carries the first three terms exactly.
    for phi in [1e-3, 1e-2]:
        length = (4 / 3 * math.pi / phi) ** (1 / 3)
        m = periodic_rpy.mobility_matrix([[0.1, 0.2, 0.3]], 1.0, length)
        expected = 1 - 1.7601 * phi ** (1 / 3) + phi
        assert np.allclose(np.diag(m), expected, atol=2e-4 + 2 * phi ** 2)
        assert np.abs(m - np.diag(np.diag(m))).max() < 1e-12


def test_free_suspension_settles_at_least_as_fast_as_the_fixed_array():
    # <M> <M^-1> >= 1 for a symmetric positive definite M (Cauchy-Schwarz): equal forces move
    # the spheres faster on average than one velocity with its mean force.
    phi, count = 0.1, 27
    length = (count * 4 / 3 * math.pi / phi) ** (1 / 3)
    centres = direct_cases.periodic_packing([length] * 3, 2.0, count, seed=2, min_gap=0.1)
    s = periodic_rpy.settling(centres, 1.0, length, phi)
    assert s["resistance"] < s["mobility"] < 1 - phi


def test_settling_along_one_axis_averages_to_the_isotropic_mean():
    # `axes` picks the directions of gravity: the three single-axis mobilities of a random
    # packing average to the default (all three), and differ from each other (anisotropy of
    # one packing), so the per-axis value is not the isotropic one by construction.
    length, d = 12.0, 2.0
    centres = direct_cases.periodic_packing([length] * 3, d, 8, seed=3)
    phi = 8 * direct_cases.sphere_volume(d) / length ** 3
    single = [periodic_rpy.settling(centres, d / 2, length, phi, ka_max=10.0, axes=[a])
              for a in range(3)]
    both = periodic_rpy.settling(centres, d / 2, length, phi, ka_max=10.0)
    mean = sum(s["mobility"] for s in single) / 3
    assert abs(mean - both["mobility"]) < 1e-12 * both["mobility"]
    spread = max(s["mobility"] for s in single) - min(s["mobility"] for s in single)
    assert spread > 1e-6 * both["mobility"]


def test_box_settling_equals_the_mobility_matrix_mean_in_a_cube_and_scales_with_the_box():
    # box_settling's structure-factor sum is the mean of the full mobility matrix's
    # mobility along one axis (settling(..., axes=(1,))) for the same spheres
    rng = np.random.default_rng(4)
    length, a = 1.0, 0.08
    centres = free_packing(rng, 12, length, 2.2 * a)
    phi = len(centres) * 4 / 3 * np.pi * a ** 3 / length ** 3
    full = periodic_rpy.settling(centres, a, length, phi, axes=(1,))["mobility"]
    box = periodic_rpy.box_settling(centres, a, [length] * 3, axis=1)
    assert abs(box - full) < 2e-3 * full
    # the same spheres scaled with their box settle at the same ratio (units drop out)
    scaled = periodic_rpy.box_settling(3 * np.asarray(centres), 3 * a, [3 * length] * 3)
    assert abs(scaled - box) < 1e-9


def free_packing(rng, count, length, min_distance):
    """`count` centres in a periodic cube, no two closer than `min_distance`."""
    centres = []
    while len(centres) < count:
        x = rng.random(3) * length
        d = np.array(centres) - x if centres else np.zeros((0, 3))
        d -= length * np.round(d / length)
        if not len(d) or np.sqrt((d ** 2).sum(1)).min() >= min_distance:
            centres.append(x)
    return np.array(centres)
