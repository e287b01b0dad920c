#!/usr/bin/env python3
"""Plane Poiseuille flow: the run against the exact parabola.

With the bulk velocity U held by meanVelocityForce, the steady profile between walls H apart
is u(y) = 6 U (y/H)(1 - y/H), driven by the kinematic pressure gradient 12 nu U / H^2. Prints
the profile's largest error over the centre-line velocity 1.5 U (bound 0.5 %,
tools/tests/test_tutorials.py) and the gradient against the exact one; draws channel.png.
"""
import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
nu = float(re.search(r"^\s*nu\s+([0-9.eE+-]+)\s*;",
                     (case / "constant/transportProperties").read_text(), re.M).group(1))
ubar = float(re.search(r"Ubar\s*\(\s*([0-9.eE+-]+)",
                       (case / "system/fvOptions").read_text()).group(1))
times = sorted((float(p.name), p) for p in case.iterdir()
               if p.is_dir() and re.fullmatch(r"[0-9.eE+-]+", p.name))

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

monitor = case / "postProcessing/fluid/0/fluid.dat"
columns = monitor.read_text().splitlines()[0].lstrip("#").split()
data = np.loadtxt(monitor, comments="#", ndmin=2)
t = data[:, columns.index("Time")]
gradient = data[:, columns.index("drivingGradient")]
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
a.set_xlabel("u_x (mm/s)")
a.set_ylabel("y (mm)")
a.set_title(f"velocity profile: max error {100 * error:.2f} % of the centre line", fontsize=10)
a.grid(alpha=0.3)
a.legend(fontsize=9)

b.plot(t, 1e3 * gradient, lw=2, label="fsim (meanVelocityForce)")
b.axhline(1e3 * gradient_exact, color="k", ls="--", label="exact 12 $\\nu$ U / H$^2$")
b.set_xlabel("t (s)")
b.set_ylabel("kinematic pressure gradient (mm/s$^2$)")
b.set_ylim(0.9e3 * gradient_exact, 1.25e3 * gradient_exact)
b.set_title(f"driving gradient at the end: {100 * (gradient[-1] / gradient_exact - 1):+.2f} % "
            "from exact", fontsize=10)
b.grid(alpha=0.3)
b.legend()
fig.savefig(case / "channel.png", dpi=110)
print("wrote channel.png")
