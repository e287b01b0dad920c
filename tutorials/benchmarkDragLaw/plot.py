#!/usr/bin/env python3
"""The paper's section 3.3 benchmark with the drag-law model: the suspension's settling speed.

In the fully periodic box the gas streams up through the particles. The settling speed in the
frame of zero volume flux is v_s = (1 - phi)(u_f - v_p), u_f the gas's mean (interstitial)
velocity, v_p the particles'. References: an isolated particle's terminal velocity
(Schiller-Naumann), which a suspension must settle below (tests/drag_law/benchmark.rs), and
the uniform suspension of the paper's closure (eq. 11, Wen & Yu: v_s (1 + 0.15 Re^0.687) =
U_Stokes eps^4.7). Prints them and draws benchmarkDragLaw.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (field_axes, monitor, properties, save, schiller_naumann,  # noqa: E402
                      settling_references, time_directories)

rho_f, nu, rho_p, g = properties(case)
mu, g = rho_f * nu, abs(g[1])

times = time_directories(case)
fields = []
for time, folder in times:
    fluid, cloud = pv.read(folder / "fluid.vtk"), pv.read(folder / "particles.vtu")
    eps = fluid.cell_data["alpha"]
    u_f = np.mean(eps * fluid.cell_data["U"][:, 1]) / eps.mean()
    v_p = cloud.point_data["U"][:, 1].mean()
    fields.append((time, eps.mean() * (u_f - v_p)))  # (1 - phi)(u_f - v_p)
d = cloud.point_data["d"].mean()
phi = 1 - eps.mean()
stokes = (rho_p - rho_f) * g * d ** 2 / (18 * mu)
isolated = schiller_naumann(stokes, rho_f, d, mu, stokes)
uniform = schiller_naumann(stokes * (1 - phi) ** 4.7, rho_f, d, mu, stokes)

# the history from the monitors: box-mean gas velocity (unweighted) and mean particle velocity
f, c = monitor(case, "fluid"), monitor(case, "cloud")
t, u_box, v_box = f["Time"], f["Uy"], np.interp(f["Time"], c["Time"], c["Uy"])
history = (1 - phi) * (u_box - v_box)
late = history[t >= t[-1] / 2].mean()

print(f"{len(cloud.points)} particles, d = {1e6 * d:g} um, rho_p = {rho_p:g} kg/m^3, in gas of "
      f"rho = {rho_f:g} kg/m^3; phi = {phi:.4f}; U_Stokes = {stokes:.4f} m/s")
for time, value in fields[1:]:
    print(f"settling speed (1 - phi)(u_f - v_p) at t = {time:g} s: {value:.4f} m/s")
print(f"mean over {t[-1] / 2:g}-{t[-1]:g} s (box-mean gas velocity): {late:.4f} m/s")
print(f"isolated particle (Schiller-Naumann): {isolated:.4f} m/s; "
      f"{'below it: hindered' if fields[-1][1] < isolated else 'NOT below it'}")
print(f"uniform suspension with the paper's closure (eps^4.7 hindrance): {uniform:.4f} m/s; "
      f"fsim {fields[-1][1] / uniform:.2f} times it")

fluid = pv.read(times[-1][1] / "fluid.vtk")
nx, ny, nz = (n - 1 for n in fluid.dimensions)
x0, x1, y0, y1, *_ = fluid.bounds
eps_xy = fluid.cell_data["alpha"].reshape(nz, ny, nx).mean(axis=0)
fig = plt.figure(figsize=(11, 6.5), constrained_layout=True)
grid = fig.add_gridspec(1, 2, width_ratios=[1, 2.2])
a = fig.add_subplot(grid[0])
image = a.pcolormesh(np.linspace(1e3 * x0, 1e3 * x1, nx + 1),
                     np.linspace(1e3 * y0, 1e3 * y1, ny + 1), 1 - eps_xy, cmap="Greys",
                     vmin=0, vmax=0.15)
a.scatter(1e3 * cloud.points[:, 0], 1e3 * cloud.points[:, 1], s=4, c="tab:orange")
field_axes(fig, a, image, "x (mm)", "y (mm), gravity along -y",
           f"t = {times[-1][0]:g} s: particles,\nsolid fraction averaged over z",
           "solid fraction 1 - $\\epsilon$", shrink=0.6)
b = fig.add_subplot(grid[1])
b.plot(t, history, lw=1, label="fsim: (1 - $\\phi$)(box-mean gas velocity - $v_p$)")
b.plot(*zip(*fields[1:]), "ks", label="fsim: (1 - $\\phi$)($u_f$ - $v_p$) from the fields")
settling_references(b, isolated, "particle", uniform,
                    f"uniform suspension, paper's closure, {uniform:.3f} m/s", top=1.2,
                    ylabel="settling speed in the frame of zero volume flux (m/s)",
                    title=f"drag-law model: settling speed {fields[-1][1]:.3f} m/s at "
                    f"t = {times[-1][0]:g} s")
save(fig, case / "benchmarkDragLaw.png", dpi=100)
