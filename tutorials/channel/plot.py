#!/usr/bin/env python3
"""Plane Poiseuille flow: the run against the exact parabola.

With the bulk velocity U held by meanVelocityForce, the steady profile between walls H apart
is u(y) = 6 U (y/H)(1 - y/H), driven by the kinematic pressure gradient 12 nu U / H^2. Prints
the profile's largest error over the centre-line velocity 1.5 U (bound 0.5 %,
tools/tests/test_tutorials.py) and the gradient against the exact one; draws channel.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import finish, keyword, monitor, save, time_directories, vector  # noqa: E402

nu = keyword(case, "constant/transportProperties", "nu")
ubar = vector(case, "system/fvOptions", "Ubar")[0]
times = time_directories(case)

mesh = pv.read(times[-1][1] / "fluid.vtk")
nx, ny, nz = (d - 1 for d in mesh.dimensions)
height = mesh.bounds[3] - mesh.bounds[2]
y = mesh.bounds[2] + (np.arange(ny) + 0.5) * height / ny


def profile(folder):
    """u_x(y), averaged over the periodic x and z."""
    u = pv.read(folder / "fluid.vtk").cell_data["U"].reshape(nz, ny, nx, 3)
    return u[:, :, :, 0].mean(axis=(0, 2))


def exact(yy):
    return 6 * ubar * (yy / height) * (1 - yy / height)


u_last = profile(times[-1][1])
error = np.max(np.abs(u_last - exact(y))) / (1.5 * ubar)

fluid = monitor(case, "fluid")
t, gradient = fluid["Time"], fluid["drivingGradient"]
gradient_exact = 12 * nu * ubar / height ** 2

print(f"Plane Poiseuille flow, H = {height:g} m, U = {ubar:g} m/s, Re = U H / nu = "
      f"{ubar * height / nu:g}, {ny} cells across, t = {times[-1][0]:g} s")
print(f"profile: max |u - 6U y(1-y)| / (1.5 U) = {100 * error:.3f} % (bound 0.5 %): "
      f"{'within' if error < 0.005 else 'OUTSIDE'}")
print(f"driving gradient {gradient[-1]:.5e} m/s^2 against 12 nu U / H^2 = {gradient_exact:.5e}: "
      f"{100 * (gradient[-1] / gradient_exact - 1):+.2f} %")

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.6), constrained_layout=True)
fine = np.linspace(0, height, 200)
a.plot(1e3 * exact(fine), 1e3 * fine, "k--", label="exact 6U (y/H)(1 - y/H)")
for time, folder in times[1:]:
    a.plot(1e3 * profile(folder), 1e3 * y, "o-", ms=3, lw=1, label=f"fsim, t = {time:g} s")
finish(a, "u_x (mm/s)", "y (mm)",
       f"velocity profile: max error {100 * error:.2f} % of the centre line",
       legend=dict(fontsize=9))

b.plot(t, 1e3 * gradient, lw=2, label="fsim (meanVelocityForce)")
b.axhline(1e3 * gradient_exact, color="k", ls="--", label="exact 12 $\\nu$ U / H$^2$")
b.set_ylim(0.9e3 * gradient_exact, 1.25e3 * gradient_exact)
finish(b, "t (s)", "kinematic pressure gradient (mm/s$^2$)",
       f"driving gradient at the end: {100 * (gradient[-1] / gradient_exact - 1):+.2f} % "
       "from exact", legend=True)
save(fig, case / "channel.png", dpi=110)
