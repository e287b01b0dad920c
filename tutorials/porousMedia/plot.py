#!/usr/bin/env python3
"""Stokes flow through a simple cubic array of fixed spheres: the drag coefficient K.

K = F / (6 pi mu r U) (paper eq. 19), U the superficial velocity; the reference is Sangani &
Acrivos' fit of Zick & Homsy's exact values (paper eq. 17; within 0.15 % of Zick & Homsy's
table up to phi = 0.125). Prints K at the end (as tests/direct/porous_tutorial.rs reads it,
bound 3 %) and draws porousMedia.png.
"""
import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
parameters = (case / "constant/porousParameters").read_text()
phi = float(re.search(r"^\s*phi\s+([0-9.eE+-]+)\s*;", parameters, re.M).group(1))
n = int(re.search(r"^\s*n\s+([0-9]+)\s*;", parameters, re.M).group(1))
side = float(re.search(r"^\s*L\s+([0-9.eE+-]+)\s*;", parameters, re.M).group(1))
radius = side * (3 * phi / (4 * np.pi)) ** (1 / 3)
nu = float(re.search(r"^\s*nu\s+([0-9.eE+-]+)\s*;",
                     (case / "constant/transportProperties").read_text(), re.M).group(1))
ubar = float(re.search(r"Ubar\s*\(\s*([0-9.eE+-]+)",
                       (case / "system/fvOptions").read_text()).group(1))


def sangani_acrivos(phi):
    """Paper eq. 17 (Sangani & Acrivos 1982, simple cubic array)."""
    c = phi ** (1 / 3)
    return 1 / (1 - 1.7601 * c + phi - 1.5593 * phi ** 2 + 3.9799 * phi ** (8 / 3)
                - 3.0734 * phi ** (10 / 3))


monitor = case / "postProcessing/direct/0/direct.dat"
columns = monitor.read_text().splitlines()[0].lstrip("#").split()
data = np.loadtxt(monitor, comments="#", ndmin=2)
t, k = data[:, columns.index("Time")], data[:, columns.index("K")]
reference = sangani_acrivos(phi)
late = np.median(k[t >= 0.8 * t[-1]])
print(f"Simple cubic array, phi = {phi:g}, r/h = {radius * n / side:.2f} ({n}^3 cells), "
      f"Re = U d / nu = {ubar * 2 * radius / nu:.3f}")
print(f"K at t = {t[-1]:g} s: {k[-1]:.4f} (median over the last fifth of the run {late:.4f}); "
      f"Sangani & Acrivos (paper eq. 17): {reference:.4f}; "
      f"{100 * (k[-1] / reference - 1):+.2f} % (bound 3 %): "
      f"{'within' if abs(k[-1] / reference - 1) < 0.03 else 'OUTSIDE'}")

times = sorted((float(p.name), p) for p in case.iterdir()
               if p.is_dir() and re.fullmatch(r"[0-9.eE+-]+", p.name))
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
a.set_xlabel("t (ms)")
a.set_ylabel("K / K$_{ref}$ - 1 (%),  K = F / (6 $\\pi \\mu$ r U)")
a.set_title(f"drag coefficient: K = {k[-1]:.4f}, {100 * (k[-1] / reference - 1):+.2f} % "
            "from the reference", fontsize=10)
a.grid(alpha=0.3)
a.legend()

speed = np.linalg.norm(u, axis=2)
image = b.pcolormesh(centres, centres, 1e3 * speed, cmap="magma", shading="auto")
xx, yy = np.meshgrid(centres, centres)
solid = np.hypot(xx - 1e3 * side / 2, yy - 1e3 * side / 2) < 1e3 * radius
b.streamplot(centres, centres, np.ma.array(u[:, :, 0], mask=solid),
             np.ma.array(u[:, :, 1], mask=solid), color="w", density=0.9,
             linewidth=0.6)
b.add_patch(plt.Circle((1e3 * side / 2, 1e3 * side / 2), 1e3 * radius, fill=False,
                       color="c", lw=1.5))
b.set_aspect("equal")
b.set_xlabel("x (mm), the flow's direction")
b.set_ylabel("y (mm)")
b.set_title(f"speed on the mid-plane z = L/2, t = {times[-1][0]:g} s (sphere outlined)",
            fontsize=10)
fig.colorbar(image, ax=b, label="|U| (mm/s)")
fig.savefig(case / "porousMedia.png", dpi=110)
print("wrote porousMedia.png")
