#!/usr/bin/env python3
"""One light bead (rho_p = 1500) from rest in water with pressureGradient and virtualMass
(Cvm 0.5), a DPMFoam cross-check case of issue 42.

With the water at rest, (rho_p + Cvm rho_f) dv/dt = (rho_p - rho_f) g - 18 mu/d^2 f(Re) v
(Schiller-Naumann). Integrates it (RK4) with and without the added mass, and draws
settlingAddedMass.png: fsim's velocity, DPMFoam's (crosscheck_reference.csv) and both hand
histories over the first 50 ms and the whole run.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (dpmfoam_reference, finish, keyword, particle_history,  # noqa: E402
                      properties, save)

rho_f, nu, rho_p, g = properties(case)
g, mu = abs(g[2]), rho_f * nu
d = keyword(case, "constant/kinematicCloudProperties", "value")
cvm = keyword(case, "constant/kinematicCloudProperties", "Cvm")


def integrate(c, t_end, step=1e-5):
    def accel(v):
        re = v * d / nu
        return ((rho_p - rho_f) * g - 18 * mu / d ** 2 * (1 + 0.15 * re ** 0.687) * v) / (
            rho_p + c * rho_f)
    ts = np.arange(0, t_end + step / 2, step)
    vs = np.zeros_like(ts)
    for k in range(1, len(ts)):
        u = vs[k - 1]
        k1 = accel(u)
        k2 = accel(u + step / 2 * k1)
        k3 = accel(u + step / 2 * k2)
        vs[k] = u + step / 6 * (k1 + 2 * k2 + 2 * k3 + accel(u + step * k3))
    return ts, vs


t, v = particle_history(case, "U", "z")
t_end = t[-1] if len(t) else 0.3
hand = integrate(cvm, t_end)
plain = integrate(0.0, t_end)
dpm = dpmfoam_reference(case, "particles.U.z.mean")
if len(t):
    ref = np.interp(t, *hand)
    print(f"fsim at {1e3 * t[1]:.0f} ms: {-v[1]:.5f} m/s, hand {ref[1]:.5f} m/s; "
          f"terminal (last) {-v[-1]:.5f} m/s, hand {hand[1][-1]:.5f} m/s")
fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
for ax, limit in zip(axes, (0.05, t_end)):
    ax.plot(hand[0], hand[1], "k--", lw=1.2, label=f"hand, Cvm = {cvm:g}")
    ax.plot(plain[0], plain[1], color="0.6", ls=":", lw=1.2, label="hand, no added mass")
    if dpm is not None:
        ax.plot(dpm[0], -dpm[1], "o", ms=3, color="tab:blue", label="DPMFoam v1912")
    if len(t):
        ax.plot(t, -v, "s", ms=2.5, color="tab:orange", label="fsim")
    ax.set_xlim(0, limit)
    finish(ax, "t (s)", "settling velocity $-U_z$ (m/s)",
           "the first 50 ms" if limit < t_end else "the whole run",
           legend=dict(loc="lower right", fontsize=9))
save(fig, case / "settlingAddedMass.png", 100)
