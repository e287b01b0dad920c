#!/usr/bin/env python3
"""Stokes flow through a simple cubic array of fixed spheres: the drag coefficient K.

K = F / (6 pi mu r U) (paper eq. 19), U the superficial velocity; the reference is Sangani &
Acrivos' fit of Zick & Homsy's exact values (paper eq. 17; within 0.15 % of Zick & Homsy's
table up to phi = 0.125). Prints K at the end (as tests/direct/porous_tutorial.rs reads it,
bound 3 %) and draws porousMedia.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (field_axes, finish, keyword, monitor, sangani_acrivos,  # noqa: E402
                      save, time_directories, vector)

phi = keyword(case, "constant/porousParameters", "phi")
n = int(keyword(case, "constant/porousParameters", "n"))
side = keyword(case, "constant/porousParameters", "L")
radius = side * (3 * phi / (4 * np.pi)) ** (1 / 3)
nu = keyword(case, "constant/transportProperties", "nu")
ubar = vector(case, "system/fvOptions", "Ubar")[0]

direct = monitor(case, "direct")
t, k = direct["Time"], direct["K"]
reference = sangani_acrivos(phi)
late = np.median(k[t >= 0.8 * t[-1]])
print(f"Simple cubic array, phi = {phi:g}, r/h = {radius * n / side:.2f} ({n}^3 cells), "
      f"Re = U d / nu = {ubar * 2 * radius / nu:.3f}")
print(f"K at t = {t[-1]:g} s: {k[-1]:.4f} (median over the last fifth of the run {late:.4f}); "
      f"Sangani & Acrivos (paper eq. 17): {reference:.4f}; "
      f"{100 * (k[-1] / reference - 1):+.2f} % (bound 3 %): "
      f"{'within' if abs(k[-1] / reference - 1) < 0.03 else 'OUTSIDE'}")

times = time_directories(case)
mesh = pv.read(times[-1][1] / "fluid.vtk")
nx, ny, nz = (d - 1 for d in mesh.dimensions)
u = mesh.cell_data["U"].reshape(nz, ny, nx, 3)[nz // 2]  # the plane through the centre
h = side / n
centres = 1e3 * (np.arange(n) + 0.5) * h

fig, (a, b) = plt.subplots(1, 2, figsize=(11.5, 4.8), constrained_layout=True)
a.plot(1e3 * t, 100 * (k / reference - 1), lw=2, label="fsim (postProcessing/direct)")
a.axhline(0, color="k", ls="--", label=f"Sangani & Acrivos, K = {reference:.3f}")
a.axhspan(-3, 3, color="0.85", label="$\\pm$3 %")
a.set_ylim(-5, 20)
finish(a, "t (ms)", "K / K$_{ref}$ - 1 (%),  K = F / (6 $\\pi \\mu$ r U)",
       f"drag coefficient: K = {k[-1]:.4f}, {100 * (k[-1] / reference - 1):+.2f} % "
       "from the reference", legend=True)

speed = np.linalg.norm(u, axis=2)
image = b.pcolormesh(centres, centres, 1e3 * speed, cmap="magma", shading="auto")
xx, yy = np.meshgrid(centres, centres)
solid = np.hypot(xx - 1e3 * side / 2, yy - 1e3 * side / 2) < 1e3 * radius
b.streamplot(centres, centres, np.ma.array(u[:, :, 0], mask=solid),
             np.ma.array(u[:, :, 1], mask=solid), color="w", density=0.9,
             linewidth=0.6)
b.add_patch(plt.Circle((1e3 * side / 2, 1e3 * side / 2), 1e3 * radius, fill=False,
                       color="c", lw=1.5))
field_axes(fig, b, image, "x (mm), the flow's direction", "y (mm)",
           f"speed on the mid-plane z = L/2, t = {times[-1][0]:g} s (sphere outlined)",
           "|U| (mm/s)")
save(fig, case / "porousMedia.png", dpi=110)
