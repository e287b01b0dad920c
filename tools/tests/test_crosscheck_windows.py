"""tools/crosscheck's window statistics: a DPMFoam history moved by dpmfoam_shift_steps covers
the same window as fsim's (its value at the window's end interpolated, not its last interval
dropped)."""
import numpy as np

import crosscheck


def ramp(shift):
    # written every 5 ms from 5 ms to 0.2 s, times moved by `shift`; the value is the time
    t = np.arange(1, 41) * 0.005
    return t + shift, t + shift


def test_a_shifted_history_keeps_the_windows_last_interval():
    q = {"statistic": "mean", "window": [0.005, 0.1]}
    fsim = crosscheck.statistic(q, ramp(0.0))
    dpm = crosscheck.statistic(q, ramp(2e-4))
    # the exact mean of t over [0.005, 0.1] is 0.0525; DPMFoam's starts at its first sample,
    # 5.2 ms (before: 0.0502, its samples 5.2-95.2 ms only)
    assert abs(fsim - 0.0525) < 1e-12
    assert abs(dpm - (0.0052 + 0.1) / 2) < 1e-12


def test_window_ends_on_samples_add_nothing():
    t, v = crosscheck.windowed(ramp(0.0), [0.005, 0.1])
    assert len(t) == 20 and t[0] == 0.005 and abs(t[-1] - 0.1) < 1e-15
    t, v = crosscheck.windowed(ramp(2e-4), [0.005, 0.1])
    assert len(t) == 20 and abs(t[0] - 0.0052) < 1e-15 and t[-1] == 0.1
    assert np.allclose(v, t)


def test_final_and_min_see_the_value_at_the_windows_end():
    q = {"statistic": "final", "window": [0.005, 0.1]}
    assert abs(crosscheck.statistic(q, ramp(2e-4)) - 0.1) < 1e-12
    q = {"statistic": "min", "window": [0.05, 0.1]}
    assert abs(crosscheck.statistic(q, ramp(2e-4)) - 0.05) < 1e-12


def test_no_window_and_nan_samples():
    t = np.array([0.0, 1.0, 2.0, 3.0])
    v = np.array([1.0, np.nan, 3.0, 4.0])
    tw, vw = crosscheck.windowed((t, v), None)
    assert list(tw) == [0.0, 2.0, 3.0] and list(vw) == [1.0, 3.0, 4.0]
    tw, vw = crosscheck.windowed((t, v), [0.5, 2.5])
    assert list(tw) == [0.5, 2.0, 2.5] and np.allclose(vw, [1.5, 3.0, 3.5])
