#!/usr/bin/env python3
"""Packed bed (drag-law model): the pressure drop across the bed against Ergun's equation.

Ergun: dp/L = 150 mu U phi^2 / (eps^3 d^2) + 1.75 rho phi U^2 / (eps^3 d), U the superficial
velocity, phi = 1 - eps the bed's solid fraction. fsim's monitor (postProcessing/dragLaw)
gives the pressure drop less the fluid's weight; tests/drag_law/case.rs holds its mean over
the run's second half within 3 % of Ergun. Prints it and draws packedBed.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (finish, inlet_velocity, monitor, properties, save,  # noqa: E402
                      time_directories)

rho, nu, _, g = properties(case)
g, mu = abs(g[2]), rho * nu
superficial = inlet_velocity(case)[2]

times = time_directories(case)
beads = pv.read(times[0][1] / "particles.vtu")  # the bed as built
d = beads.point_data["d"].mean()
fluid = pv.read(times[-1][1] / "fluid.vtk")
x0, x1, y0, y1, z0, z1 = fluid.bounds
bed = beads.points[:, 2].max() + d / 2 - (beads.points[:, 2].min() - d / 2)
phi = len(beads.points) * np.pi / 6 * d ** 3 / ((x1 - x0) * (y1 - y0) * bed)
eps = 1 - phi
gradient = (150 * mu * superficial * phi ** 2 / (eps ** 3 * d ** 2)
            + 1.75 * rho * phi * superficial ** 2 / (eps ** 3 * d))
ergun = gradient * bed

drag_law = monitor(case, "dragLaw")
t, drop = drag_law["Time"], drag_law["pressureDrop"]
mean = drop[len(drop) // 2:].mean()
print(f"Packed bed: {len(beads.points)} beads of d = {1e3 * d:g} mm, bed {1e3 * bed:g} mm, "
      f"phi = {phi:.4f}, U = {1e3 * superficial:g} mm/s, Re = U d / nu = "
      f"{superficial * d / nu:g}")
print(f"pressure drop (mean over the second half): {mean:.4f} Pa; Ergun {ergun:.4f} Pa; "
      f"{100 * (mean / ergun - 1):+.2f} % (bound 3 %): "
      f"{'within' if abs(mean / ergun - 1) < 0.03 else 'OUTSIDE'}")

# the pressure along the column, without the fluid's weight, relative to the top layer
nx, ny, nz = (n - 1 for n in fluid.dimensions)
z = z0 + (np.arange(nz) + 0.5) * (z1 - z0) / nz
p = fluid.cell_data["p"].reshape(nz, ny, nx).mean(axis=(1, 2))
alpha = fluid.cell_data["alpha"].reshape(nz, ny, nx).mean(axis=(1, 2))
dynamic = rho * (p + g * z)
dynamic -= dynamic[-1]
bed_top = beads.points[:, 2].max() + d / 2

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.8), constrained_layout=True)
a.plot(1e3 * t, drop, lw=1.5, label="fsim (postProcessing/dragLaw)")
a.plot(1e3 * t[len(t) // 2:], np.full(len(t) - len(t) // 2, mean), color="tab:red", lw=2.5,
       label=f"its mean over the second half, {mean:.3f} Pa")
a.axhline(ergun, color="k", ls="--", label=f"Ergun, {ergun:.3f} Pa")
a.axhspan(0.97 * ergun, 1.03 * ergun, color="0.85", label="$\\pm$3 %")
a.set_ylim(0, 2.2 * ergun)
finish(a, "t (ms)", "pressure drop across the column (Pa)",
       f"pressure drop: {mean:.3f} Pa, {100 * (mean / ergun - 1):+.2f} % from Ergun\n"
       "(it swings as the bed settles onto its contact springs)",
       legend=dict(loc="upper right", fontsize=9))

b.plot(dynamic, 1e3 * z, "o-", ms=4, label=f"fsim, t = {times[-1][0]:g} s")
zz = np.linspace(z0, z1, 200)
b.plot(gradient * np.clip(bed_top - zz, 0, None), 1e3 * zz, "k--", label="Ergun")
finish(b, "pressure less the fluid's weight, from the top layer (Pa)", "z (mm)")
c = b.twiny()
c.plot(alpha, 1e3 * z, color="tab:green", lw=1.5)
c.set_xlabel("fluid fraction $\\epsilon$ (green)", color="tab:green")
c.tick_params(axis="x", colors="tab:green")
c.set_xlim(0, 1.05)
b.legend(loc="upper center")
save(fig, case / "packedBed.png", dpi=110)
