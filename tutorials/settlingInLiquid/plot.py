#!/usr/bin/env python3
"""One glass bead settling from rest in water (drag-law model, a DPMFoam cross-check case).

With drag and gravity only (the forces this case gives both programs), the bead obeys
    dv/dt = (1 - rho_f/rho_p) g - v / tau(v),   tau = rho_p d^2 / (18 mu (1 + 0.15 Re^0.687)),
Schiller-Naumann's law, Re = v d / nu, in still water. Integrates it (RK4) from rest, prints
fsim's terminal velocity (its mean over the run's second half) against the balance's, and
draws settlingInLiquid.png: fsim's velocity and its departure from the hand-integrated
history. `tools/crosscheck tutorials/settlingInLiquid` compares the same run with DPMFoam's.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (finish, monitor, properties, save, schiller_naumann,  # noqa: E402
                      time_directories)

rho_f, nu, rho_p, g = properties(case)
g, mu = abs(g[2]), rho_f * nu
times = time_directories(case)
d = float(pv.read(times[0][1] / "particles.vtu").point_data["d"].mean())
drive = (rho_p - rho_f) * g * d ** 2 / (18 * mu)  # Stokes' settling velocity
terminal = schiller_naumann(drive, rho_f, d, mu, drive)
reynolds = terminal * d / nu


def accel(v):
    re = v * d / nu
    return (1 - rho_f / rho_p) * g - v * 18 * mu * (1 + 0.15 * re ** 0.687) / (rho_p * d ** 2)


cloud = monitor(case, "cloud")
t, v = cloud["Time"], -cloud["Uz"]
step = 1e-5
exact_t = np.arange(0, t[-1] + step / 2, step)
exact = np.zeros_like(exact_t)
for k in range(1, len(exact_t)):
    u = exact[k - 1]
    k1 = accel(u)
    k2 = accel(u + step / 2 * k1)
    k3 = accel(u + step / 2 * k2)
    k4 = accel(u + step * k3)
    exact[k] = u + step / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
reference = np.interp(t, exact_t, exact)

late = t >= t[-1] / 2
mean = v[late].mean()
error = (mean - terminal) / terminal
tau = rho_p * d ** 2 / (18 * mu * (1 + 0.15 * reynolds ** 0.687))
print(f"Settling in a liquid: d = {1e3 * d:g} mm, rho_p = {rho_p:g}, rho_f = {rho_f:g} kg/m^3, "
      f"nu = {nu:g} m^2/s; drag and gravity only")
print(f"Schiller-Naumann terminal velocity {terminal:.5f} m/s (Re = {reynolds:.0f}, relaxation "
      f"time {1e3 * tau:.1f} ms)")
print(f"fsim, mean over {t[late][0]:.3g}-{t[-1]:g} s: {mean:.5f} m/s, {100 * error:+.2f} % "
      f"(bound 1 %): {'within' if abs(error) < 0.01 else 'OUTSIDE'}")
print(f"largest departure from the integrated history: "
      f"{100 * np.max(np.abs(v - reference)) / terminal:.2f} % of the terminal velocity")

fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
a.plot(exact_t, exact, color="k", ls="--", lw=1.2, label="Schiller-Naumann, integrated by hand")
a.plot(t, v, color="tab:blue", lw=1.5, label="fsim (postProcessing/cloud)")
a.axhline(terminal, color="tab:red", ls=":", label=f"terminal velocity, {terminal:.4f} m/s")
a.set_ylim(0, 1.15 * terminal)
finish(a, "t (s)", "settling velocity $-U_z$ (m/s)",
       f"one bead of {1e3 * d:g} mm in water: fsim {100 * error:+.2f} % at terminal velocity",
       legend=dict(loc="lower right", fontsize=9))
b.plot(t, 100 * (v - reference) / terminal, color="tab:blue", lw=1)
b.axhline(0, color="k", lw=0.8)
finish(b, "t (s)", "fsim - hand-integrated (% of the terminal velocity)",
       "departure: the water the bead drags along in its cell, and its cell crossings")
save(fig, case / "settlingInLiquid.png", 100)
