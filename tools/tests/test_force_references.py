"""tools/force_crosscheck_references.py (issue 42's hand references): each against a value
that holds independently of the code under test."""
import math

import force_crosscheck_references as ref


def test_terminal_velocity_is_settlingInLiquids_hand_value():
    # tutorials/settlingInLiquid's hand balance, 0.145946 m/s (its crosscheck.toml)
    assert abs(ref.terminal(1e-3, 2500, 1000, 1e-6) - 0.145946) < 2e-6


def test_added_mass_history_starts_at_the_reduced_acceleration_and_ends_at_terminal():
    hist = ref.added_mass_history(1e-3, 1500, 1000, 1e-6, 0.5, 0.3, every=1e-5)
    t, v = hist[1]
    assert abs(v / t - 9.81 * 500 / 2000) < 0.01 * 9.81 * 500 / 2000   # g (rp - rf)/(rp + Cvm rf)
    assert abs(hist[-1][1] - ref.terminal(1e-3, 1500, 1000, 1e-6)) < 1e-6


def test_haider_levenspiel_at_phi_one_is_close_to_a_sphere():
    # Haider & Levenspiel's fit at phi = 1 is their sphere correlation: within a few per cent of
    # Schiller-Naumann over 1 < Re < 800 (3.2 to 8.2 % above it)
    for re in (1.0, 10.0, 100.0, 800.0):
        hl = ref.haider_levenspiel_cdre(re, 1.0)
        sn = ref.schiller_naumann_cdre(re)
        assert 1.0 < hl / sn < 1.09, (re, hl, sn)
    # and a less spherical particle has more drag
    assert ref.haider_levenspiel_cdre(100.0, 0.7) > 1.3 * ref.haider_levenspiel_cdre(100.0, 1.0)


def test_saffman_mei_cl_reduces_to_saffman_at_small_reynolds_numbers():
    # Re -> 0 with beta fixed: f -> 1, Cl = 3/(2 pi sqrt(Rew)) 6.46 (Saffman's 6.46)
    cl = ref.saffman_mei_cl(1e-8, 2e-8)
    assert abs(cl - 3 / (2 * math.pi * math.sqrt(2e-8)) * 6.46) < 1e-3 * cl


def test_fluidization_exponents_and_wen_yu_at_the_terminal_velocity():
    assert abs(ref.richardson_zaki_n(0.1, 0.0) - 4.65) < 1e-12
    assert abs(ref.richardson_zaki_n(1000, 0.1) - 2.39) < 1e-12
    assert abs(ref.garside_al_dibouni_n(1e-6) - 5.1) < 1e-3         # creeping flow
    assert abs(ref.garside_al_dibouni_n(1e9) - 2.7) < 1e-3          # inertial limit
    # a bed fluidized at a bead's terminal velocity is infinitely dilute: porosity 1
    vt = ref.terminal(2e-3, 2500, 1000, 1e-6)
    assert abs(ref.wen_yu_porosity(vt, 2e-3, 2500, 1000, 1e-6) - 1) < 1e-6


def test_shear_lift_drift_is_the_balance_of_lift_and_drag():
    drift, slip, cl = ref.shear_lift(10.0)
    k = ref.drag_rate(math.hypot(drift, slip), 1e-3, 1100, 1000, 1e-6, ref.schiller_naumann_cdre)
    assert abs(k * drift - 1000 / 1100 * cl * 10.0 * slip) < 1e-9
