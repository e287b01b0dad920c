#!/usr/bin/env python3
"""Taylor-Green vortex: the run against the exact solution.

u = sin x cos y e^(-2 nu t), v = -cos x sin y e^(-2 nu t): the kinetic energy decays as
e^(-4 nu t). Prints the fitted decay rate and the relative L2 velocity error at each written
time (bound 1 %, tools/tests/test_tutorials.py); draws taylorGreen.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import finish, keyword, monitor, save, time_directories  # noqa: E402

nu = keyword(case, "constant/transportProperties", "nu")

# kinetic-energy history from the per-step monitor
fluid = monitor(case, "fluid")
t = np.concatenate([[0.0], fluid["Time"]])
energy = fluid["kineticEnergy"]

times = time_directories(case)
print(f"Taylor-Green vortex, nu = {nu:g} m^2/s; exact energy decay rate 4 nu = {4 * nu:.4f} 1/s")
errors = []
for time, folder in times:
    mesh = pv.read(folder / "fluid.vtk")
    x, y = mesh.cell_centers().points[:, 0], mesh.cell_centers().points[:, 1]
    decay = np.exp(-2 * nu * time)
    exact = np.stack([np.sin(x) * np.cos(y), -np.cos(x) * np.sin(y), 0 * x], axis=1) * decay
    error = np.linalg.norm(mesh.cell_data["U"] - exact) / np.linalg.norm(exact)
    errors.append((time, error))
    if time == 0:
        energy0 = 0.5 * np.mean(np.sum(mesh.cell_data["U"] ** 2, axis=1))
    print(f"  t = {time:g}: relative L2 velocity error {100 * error:.3f} %")
energy = np.concatenate([[energy0], energy])
rate = -np.polyfit(t, np.log(energy / energy0), 1)[0]
print(f"fitted energy decay rate {rate:.4f} 1/s against {4 * nu:.4f}: "
      f"{100 * (rate / (4 * nu) - 1):+.2f} %")
worst = max(e for _, e in errors)
print(f"largest L2 error {100 * worst:.3f} % (bound 1 %): {'within' if worst < 0.01 else 'OUTSIDE'}")

# the picture: vorticity at the last time, and the energy against the exact decay
last_time, last = times[-1]
mesh = pv.read(last / "fluid.vtk")
nx, ny, nz = (d - 1 for d in mesh.dimensions)
u = mesh.cell_data["U"].reshape(nz, ny, nx, 3)[0]
h = mesh.spacing[0]
xc = (np.arange(nx) + 0.5) * h
yc = (np.arange(ny) + 0.5) * mesh.spacing[1]
omega = np.gradient(u[:, :, 1], h, axis=1) - np.gradient(u[:, :, 0], mesh.spacing[1], axis=0)

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.6), constrained_layout=True)
image = a.pcolormesh(xc, yc, omega, cmap="RdBu_r", shading="auto")
a.quiver(xc[::2], yc[::2], u[::2, ::2, 0], u[::2, ::2, 1], color="k", scale=12)
a.set_aspect("equal")
a.set_xlabel("x (m)")
a.set_ylabel("y (m)")
a.set_title(f"vorticity and velocity at t = {last_time:g} s")
fig.colorbar(image, ax=a, label="vorticity $\\omega_z$ (1/s)")

b.plot(t, energy / energy0, lw=2, label="fsim (monitor)")
b.plot(t, np.exp(-4 * nu * t), "k--", label="exact $e^{-4\\nu t}$")
finish(b, "t (s)", "kinetic energy / initial",
       f"decay rate {rate:.4f} 1/s vs exact {4 * nu:.4f} 1/s; L2 error {100 * worst:.2f} %")
c = b.twinx()
c.plot(t, 100 * (energy / energy0 / np.exp(-4 * nu * t) - 1), color="tab:red", lw=1)
c.plot([e[0] for e in errors], [100 * e[1] for e in errors], "o", color="tab:red")
c.set_ylabel("energy / exact - 1 (line), L2 velocity error (dots)  (%)", color="tab:red")
c.tick_params(axis="y", colors="tab:red")
lines = b.get_legend_handles_labels()
b.legend(lines[0] + c.get_lines()[:1] + c.get_lines()[1:],
         lines[1] + ["energy / exact - 1", "L2 velocity error"], loc="upper center")
save(fig, case / "taylorGreen.png", dpi=110)
