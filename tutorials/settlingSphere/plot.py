#!/usr/bin/env python3
"""One sphere settling in a periodic box: its terminal velocity against the periodic array's.

A sphere in a periodic cube of side L settles as the simple cubic array of fixed spheres at
the same phi resists: v = U_Stokes / K(phi), K from Sangani & Acrivos (paper eq. 17), with
U_Stokes = (rho_p - rho_f) g d^2 / (18 mu). Prints v / (U_Stokes / K) at the end
(tests/direct/motion.rs holds it within 3 %) and draws settlingSphere.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (NUMBER, entry, field_axes, finish, monitor, properties,  # noqa: E402
                      sangani_acrivos, save, time_directories)

rho_f, nu, rho_p, (_, g, _) = properties(case)
d = entry(case, "constant/kinematicCloudProperties",
          rf"fixedValueDistribution\s*\{{\s*value\s+({NUMBER})")
stokes = (rho_p - rho_f) * abs(g) * d ** 2 / (18 * rho_f * nu)

m = monitor(case, "sedimentation")
t, v, phi = m["Time"], m["settlingVelocity"] / stokes, m["phi"][0]
expected = 1 / sangani_acrivos(phi)
ratio = v[-1] / expected
print(f"One sphere, d = {1e3 * d:g} mm, rho_p / rho_f = {rho_p / rho_f:g}, phi = {phi:.5f}, "
      f"Re = v d / nu = {v[-1] * stokes * d / nu:.4f}; U_Stokes = {1e3 * stokes:.4f} mm/s")
print(f"v / U_Stokes at t = {t[-1]:g} s: {v[-1]:.5f}; periodic array 1/K (Sangani & Acrivos): "
      f"{expected:.5f}; ratio {ratio:.4f} (bound 3 %): "
      f"{'within' if abs(ratio - 1) < 0.03 else 'OUTSIDE'}")

times = time_directories(case)
mesh = pv.read(times[-1][1] / "fluid.vtk")
cloud = pv.read(times[-1][1] / "particles.vtu")
nx, ny, nz = (n - 1 for n in mesh.dimensions)
h = mesh.spacing[0]
centre = cloud.points[0]
plane = min(nz - 1, int(centre[2] / h))
u = mesh.cell_data["U"].reshape(nz, ny, nx, 3)[plane]
xs = 1e3 * (np.arange(nx) + 0.5) * h
ys = 1e3 * (np.arange(ny) + 0.5) * h

fig, (a, b) = plt.subplots(1, 2, figsize=(11.5, 4.8), constrained_layout=True)
a.plot(1e3 * t, v, lw=2, label="fsim, frame of zero volume flux")
a.axhline(expected, color="k", ls="--", label=f"U_Stokes / K(phi) = {expected:.4f}")
a.axhspan(0.97 * expected, 1.03 * expected, color="0.85", label="$\\pm$3 %")
finish(a, "t (ms)", "settling velocity / U_Stokes",
       f"terminal velocity: {ratio:.4f} of the periodic array's", legend=dict(loc="lower right"))

image = b.pcolormesh(xs, ys, 1e3 * u[:, :, 1], cmap="RdBu_r", shading="auto",
                     vmin=-1e3 * abs(u[:, :, 1]).max(), vmax=1e3 * abs(u[:, :, 1]).max())
b.add_patch(plt.Circle((1e3 * centre[0], 1e3 * centre[1]), 0.5e3 * d, fill=False, color="k"))
field_axes(fig, b, image, "x (mm)", "y (mm), gravity along -y",
           f"vertical fluid velocity through the sphere's centre, t = {times[-1][0]:g} s",
           "$u_y$ (mm/s)")
save(fig, case / "settlingSphere.png", dpi=110)
