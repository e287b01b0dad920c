#!/usr/bin/env python3
"""Bubbling fluidized bed (drag-law model): the bed's motion and its pressure drop.

A fluidized bed hangs on the gas: its pressure drop carries the beads' buoyant weight per
cross-section, W / A = N (rho_p - rho_f) g V_p / A, apart from what the walls and the floor
take while the bed slugs. Prints the mean pressure drop and drag after the start-up (the
first 0.1 s) against W / A and W, and draws fluidizedBed.png: the beads at about nine write
times and the pressure-drop history.
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

rho_f, _, rho_p, g = properties(case)
g, inlet = abs(g[2]), inlet_velocity(case)[2]

times = time_directories(case)
fluid = pv.read(times[-1][1] / "fluid.vtk")
x0, x1, y0, y1, z0, z1 = fluid.bounds
shown = times[::max(1, round((len(times) - 1) / 8))]  # about nine snapshots
clouds = [(time, pv.read(folder / "particles.vtu")) for time, folder in shown]
d = clouds[0][1].point_data["d"]
weight = np.sum((rho_p - rho_f) * g * np.pi / 6 * d ** 3)
area = (x1 - x0) * (y1 - y0)

drag_law = monitor(case, "dragLaw")
t, drop, drag = drag_law["Time"], drag_law["pressureDrop"], drag_law["FdParticlesZ"]
settled = t > min(0.1, t[-1] / 2)
mean_drop, mean_drag = drop[settled].mean(), drag[settled].mean()
print(f"Fluidized bed: {len(d)} beads of d = {1e3 * d.mean():g} mm, rho_p = {rho_p:g} kg/m^3, "
      f"air at {inlet:g} m/s; buoyant weight W = {1e3 * weight:.2f} mN, W / A = "
      f"{weight / area:.1f} Pa")
print(f"mean over {t[settled][0]:.2g}-{t[-1]:g} s: pressure drop {mean_drop:.1f} Pa = "
      f"{mean_drop / (weight / area):.3f} W / A; drag on the beads {1e3 * mean_drag:.2f} mN = "
      f"{mean_drag / weight:.3f} W (the rest on the walls and the floor)")

fig = plt.figure(figsize=(14, 6), constrained_layout=True)
grid = fig.add_gridspec(1, len(clouds) + 3, width_ratios=[1] * len(clouds) + [0.12, 0.3, 4.2])
limit = 0.5
for k, (time, cloud) in enumerate(clouds):
    a = fig.add_subplot(grid[k])
    order = np.argsort(cloud.points[:, 0])  # the front layer drawn last
    dots = a.scatter(1e3 * cloud.points[order, 1], 1e3 * cloud.points[order, 2], s=5,
                     c=cloud.point_data["U"][order, 2], cmap="coolwarm", vmin=-limit,
                     vmax=limit)
    a.set_xlim(1e3 * y0, 1e3 * y1)
    a.set_ylim(1e3 * z0, 1e3 * z1)
    a.set_aspect("equal")
    a.set_title(f"t = {time:g} s", fontsize=9)
    a.set_xticks([1e3 * y0, 1e3 * y1])
    if k:
        a.set_yticklabels([])
    else:
        a.set_ylabel("z (mm)")
    a.set_xlabel("y (mm)", fontsize=8)
bar = fig.colorbar(dots, cax=fig.add_subplot(grid[len(clouds)]), label="bead velocity $U_z$ (m/s)")
b = fig.add_subplot(grid[-1])
b.plot(t, drop, lw=1, label="fsim (postProcessing/dragLaw)")
b.plot(t[settled], np.full(settled.sum(), mean_drop), color="tab:red", lw=2.5,
       label=f"its mean after the start-up, {mean_drop:.0f} Pa")
b.axhline(weight / area, color="k", ls="--",
          label=f"buoyant weight / area, {weight / area:.0f} Pa")
b.set_ylim(0, 2.5 * weight / area)
finish(b, "t (s)", "pressure drop across the column (Pa)",
       f"mean pressure drop: {mean_drop / (weight / area):.2f} W / A",
       legend=dict(loc="upper right", fontsize=9))
save(fig, case / "fluidizedBed.png", dpi=100)
