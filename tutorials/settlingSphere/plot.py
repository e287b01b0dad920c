#!/usr/bin/env python3
"""One sphere settling in a periodic box: its terminal velocity against the periodic array's.

A sphere in a periodic cube of side L settles as the simple cubic array of fixed spheres at
the same phi resists: v = U_Stokes / K(phi), K from Sangani & Acrivos (paper eq. 17), with
U_Stokes = (rho_p - rho_f) g d^2 / (18 mu). Prints v / (U_Stokes / K) at the end
(tests/direct/motion.rs holds it within 3 %) and draws settlingSphere.png.
"""
import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent


def entry(file, key):
    return float(re.search(rf"^\s*{re.escape(key)}\s+([0-9.eE+-]+)\s*;",
                           (case / file).read_text(), re.M).group(1))


rho_f = float(re.search(r"^\s*rho\.\w+\s+([0-9.eE+-]+)\s*;",
                        (case / "constant/transportProperties").read_text(), re.M).group(1))
nu = entry("constant/transportProperties", "nu")
rho_p = entry("constant/kinematicCloudProperties", "rho0")
d = float(re.search(r"fixedValueDistribution\s*\{\s*value\s+([0-9.eE+-]+)",
                    (case / "constant/kinematicCloudProperties").read_text()).group(1))
g = float(re.search(r"value\s*\(\s*[0-9.eE+-]+\s+(-?[0-9.eE+-]+)",
                    (case / "constant/g").read_text()).group(1))
stokes = (rho_p - rho_f) * abs(g) * d ** 2 / (18 * rho_f * nu)


def sangani_acrivos(phi):
    """Paper eq. 17 (Sangani & Acrivos 1982, simple cubic array)."""
    c = phi ** (1 / 3)
    return 1 / (1 - 1.7601 * c + phi - 1.5593 * phi ** 2 + 3.9799 * phi ** (8 / 3)
                - 3.0734 * phi ** (10 / 3))


monitor = case / "postProcessing/sedimentation/0/sedimentation.dat"
columns = monitor.read_text().splitlines()[0].lstrip("#").split()
data = np.loadtxt(monitor, comments="#", ndmin=2)
t = data[:, columns.index("Time")]
v = data[:, columns.index("settlingVelocity")] / stokes
phi = data[0, columns.index("phi")]
expected = 1 / sangani_acrivos(phi)
ratio = v[-1] / expected
print(f"One sphere, d = {1e3 * d:g} mm, rho_p / rho_f = {rho_p / rho_f:g}, phi = {phi:.5f}, "
      f"Re = v d / nu = {v[-1] * stokes * d / nu:.4f}; U_Stokes = {1e3 * stokes:.4f} mm/s")
print(f"v / U_Stokes at t = {t[-1]:g} s: {v[-1]:.5f}; periodic array 1/K (Sangani & Acrivos): "
      f"{expected:.5f}; ratio {ratio:.4f} (bound 3 %): "
      f"{'within' if abs(ratio - 1) < 0.03 else 'OUTSIDE'}")

times = sorted((float(p.name), p) for p in case.iterdir()
               if p.is_dir() and re.fullmatch(r"[0-9.eE+-]+", p.name))
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
a.set_xlabel("t (ms)")
a.set_ylabel("settling velocity / U_Stokes")
a.set_title(f"terminal velocity: {ratio:.4f} of the periodic array's", fontsize=10)
a.grid(alpha=0.3)
a.legend(loc="lower right")

image = b.pcolormesh(xs, ys, 1e3 * u[:, :, 1], cmap="RdBu_r", shading="auto",
                     vmin=-1e3 * abs(u[:, :, 1]).max(), vmax=1e3 * abs(u[:, :, 1]).max())
b.add_patch(plt.Circle((1e3 * centre[0], 1e3 * centre[1]), 0.5e3 * d, fill=False, color="k"))
b.set_aspect("equal")
b.set_xlabel("x (mm)")
b.set_ylabel("y (mm), gravity along -y")
b.set_title(f"vertical fluid velocity through the sphere's centre, t = {times[-1][0]:g} s",
            fontsize=10)
fig.colorbar(image, ax=b, label="$u_y$ (mm/s)")
fig.savefig(case / "settlingSphere.png", dpi=110)
print("wrote settlingSphere.png")
